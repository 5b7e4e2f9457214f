/*
 * glload.c — dlopen of libOSMesa and libEGL on the first context (glload.h).
 * The handles are never closed (dlib.h): a context's driver state lives as
 * long as the process, as it did when the libraries were linked.
 */
#ifdef SL_HAVE_OSMESA
#include <GL/osmesa.h>
#endif
#ifdef SL_HAVE_EGL
#include <EGL/egl.h>
#endif
#include "glload.h"
#include "dlib.h"

#define SL_GLLOAD_NAME(f) #f,

#ifdef SL_HAVE_OSMESA
struct sl_osmesa_fns sl_osmesa;

int sl_osmesa_load(char *why, size_t n)
{
    static const char *const names[] = {"libOSMesa.so.8", "libOSMesa.so", NULL};
    static const char *const syms[] = {SL_OSMESA_FUNCS(SL_GLLOAD_NAME)};
    static int loaded;
    _Static_assert(sizeof sl_osmesa == sizeof syms / sizeof syms[0] * sizeof(void *), "one field per name");
    return sl_dl_table(&loaded, names, syms, (int)(sizeof syms / sizeof syms[0]), &sl_osmesa, why, n);
}
#endif

#ifdef SL_HAVE_EGL
struct sl_egl_fns sl_egl;

int sl_egl_load(char *why, size_t n)
{
    static const char *const names[] = {"libEGL.so.1", "libEGL.so", NULL};
    static const char *const syms[] = {SL_EGL_FUNCS(SL_GLLOAD_NAME)};
    static int loaded;
    _Static_assert(sizeof sl_egl == sizeof syms / sizeof syms[0] * sizeof(void *), "one field per name");
    return sl_dl_table(&loaded, names, syms, (int)(sizeof syms / sizeof syms[0]), &sl_egl, why, n);
}
#endif
