/*
 * glload.h — the backends' own entry points (OSMesa*, egl*), taken from
 * libOSMesa and libEGL with dlopen when the first context of that backend
 * opens, and called under their usual names through the macros below.
 *
 * Why not linked: libOSMesa carries llvmpipe and LLVM (~55 MB mapped and
 * 60 ms of relocation at every start here), and a verb that renders nothing
 * (version, validate, table, check) should not pay for it. glfn.h already
 * fetches every gl* function through the backend, so these few are all that
 * tied the binary to the GL libraries.
 *
 * Include after <GL/osmesa.h> / <EGL/egl.h>: the prototypes there give the
 * pointers their types (__typeof__), and the macros then rename the calls.
 */
#ifndef SL_GLLOAD_H
#define SL_GLLOAD_H
#include <stddef.h>

#ifdef SL_HAVE_OSMESA
#define SL_OSMESA_FUNCS(X) \
    X(OSMesaCreateContextAttribs) X(OSMesaDestroyContext) X(OSMesaGetProcAddress) X(OSMesaMakeCurrent)
#ifdef OSMESA_MAJOR_VERSION
struct sl_osmesa_fns {
#define SL_GLLOAD_FIELD(f) __typeof__(f) *f;
    SL_OSMESA_FUNCS(SL_GLLOAD_FIELD)
#undef SL_GLLOAD_FIELD
};
extern struct sl_osmesa_fns sl_osmesa;
#define OSMesaCreateContextAttribs sl_osmesa.OSMesaCreateContextAttribs
#define OSMesaDestroyContext sl_osmesa.OSMesaDestroyContext
#define OSMesaGetProcAddress sl_osmesa.OSMesaGetProcAddress
#define OSMesaMakeCurrent sl_osmesa.OSMesaMakeCurrent
#endif
/* 0 when libOSMesa is loaded (now or before); else the reason in why. */
int sl_osmesa_load(char *why, size_t n);
#endif

#ifdef SL_HAVE_EGL
#define SL_EGL_FUNCS(X)                                                                                 \
    X(eglBindAPI) X(eglChooseConfig) X(eglCreateContext) X(eglDestroyContext) X(eglGetProcAddress)     \
    X(eglInitialize) X(eglMakeCurrent) X(eglQueryString) X(eglReleaseThread) X(eglTerminate)
#ifdef EGL_VERSION_1_0
struct sl_egl_fns {
#define SL_GLLOAD_FIELD(f) __typeof__(f) *f;
    SL_EGL_FUNCS(SL_GLLOAD_FIELD)
#undef SL_GLLOAD_FIELD
};
extern struct sl_egl_fns sl_egl;
#define eglBindAPI sl_egl.eglBindAPI
#define eglChooseConfig sl_egl.eglChooseConfig
#define eglCreateContext sl_egl.eglCreateContext
#define eglDestroyContext sl_egl.eglDestroyContext
#define eglGetProcAddress sl_egl.eglGetProcAddress
#define eglInitialize sl_egl.eglInitialize
#define eglMakeCurrent sl_egl.eglMakeCurrent
#define eglQueryString sl_egl.eglQueryString
#define eglReleaseThread sl_egl.eglReleaseThread
#define eglTerminate sl_egl.eglTerminate
#endif
/* 0 when libEGL is loaded (now or before); else the reason in why. */
int sl_egl_load(char *why, size_t n);
#endif

#endif
