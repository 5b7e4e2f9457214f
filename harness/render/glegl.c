/*
 * glegl.c — the EGL backend of glctx.h: a 4.5 core context with no surface.
 *
 * Which display, in order (each tried until one gives a 4.5 core context):
 *   1. SHADOWLAB_EGL_DEVICE=N: EGL device N exactly (software allowed); a
 *      value that is not a device number is SL_E_USAGE, never a fallback.
 *   2. CUDA_VISIBLE_DEVICES set: the EGL device whose EGL_CUDA_DEVICE_NV is
 *      its first entry (EGL's device order does not follow CUDA's; only with
 *      EGL_NV_device_cuda; UUID entries are not matched).
 *   3. every device not advertising EGL_MESA_device_software, in order;
 *   4. EGL_PLATFORM_SURFACELESS_MESA;
 *   5. the software devices (llvmpipe), last resort.
 * What failed is kept in one line for the SL_E_GL message; what worked goes
 * into g->device for provenance. Library code: nothing printed.
 */
#ifdef SL_HAVE_EGL
#include "glegl.h"
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include "glload.h"
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEV 32

struct egl_fns {
    PFNEGLQUERYDEVICESEXTPROC query_devices;
    PFNEGLQUERYDEVICESTRINGEXTPROC device_string;
    PFNEGLQUERYDEVICEATTRIBEXTPROC device_attrib;
    PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display;
};

static sl_glproc egl_proc(const char *name)
{
    return (sl_glproc)eglGetProcAddress(name);
}

static int has_ext(const char *list, const char *ext)
{
    size_t n = strlen(ext);
    for (const char *p = list; p && (p = strstr(p, ext)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
    return 0;
}

static void note(char *tried, size_t n, const char *what, const char *why)
{
    size_t len = strlen(tried);
    snprintf(tried + len, n - len, "%s%s (%s)", len ? "; " : "", what, why);
}

/* libglvnd unloads the vendor library (Mesa's libEGL_mesa and its DRI
 * driver) at exit, before LeakSanitizer looks: what Mesa keeps for the life
 * of the process then shows under whatever library was mapped there later,
 * and no suppression can name it. Marking the loaded ones RTLD_NODELETE
 * keeps them mapped (they would stay until exit anyway: the display is
 * kept, below), so their allocations keep their names (tests/lsan.supp).
 * A library not loaded is left alone (RTLD_NOLOAD). */
static void keep_vendor_libraries(void)
{
    static const char *const libs[] = {"libEGL_mesa.so.0", "libEGL_nvidia.so.0", "libgallium_dri.so",
                                       "swrast_dri.so", "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so"};
    for (size_t i = 0; i < sizeof libs / sizeof libs[0]; i++) {
        void *h = dlopen(libs[i], RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
        if (h)
            dlclose(h);   /* drops the count dlopen added; NODELETE stays */
    }
}

/* Display -> current 4.5 core context with entry points, or a reason. */
static const char *try_display(struct sl_gl *g, EGLDisplay dpy)
{
    if (dpy == EGL_NO_DISPLAY)
        return "no display";
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor))
        return "eglInitialize failed";
    keep_vendor_libraries();
    const char *why = NULL;
    const char *exts = eglQueryString(dpy, EGL_EXTENSIONS);
    EGLConfig cfg = (EGLConfig)0;
    if (!eglBindAPI(EGL_OPENGL_API))
        why = "no desktop OpenGL API";
    else if (!has_ext(exts, "EGL_KHR_surfaceless_context"))
        why = "no EGL_KHR_surfaceless_context";
    else if (!has_ext(exts, "EGL_KHR_no_config_context")) {
        const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, want, &cfg, 1, &n) || n < 1)
            why = "no OpenGL config";
    }
    if (!why) {
        const EGLint attrs[] = {
            EGL_CONTEXT_MAJOR_VERSION, 4,
            EGL_CONTEXT_MINOR_VERSION, 5,
            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
            EGL_NONE,
        };
        EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, attrs);
        if (ctx == EGL_NO_CONTEXT)
            why = "no 4.5 core context";
        else if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            eglDestroyContext(dpy, ctx);
            why = "eglMakeCurrent failed";
        } else {
            const char *missing = sl_glfn_load(egl_proc);
            if (missing) {
                eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
                eglDestroyContext(dpy, ctx);
                static char buf[96];
                snprintf(buf, sizeof buf, "lacks %s", missing);
                why = buf;
            } else {
                g->egl_display = dpy;
                g->egl_ctx = ctx;
                return NULL;
            }
        }
    }
    eglTerminate(dpy);
    return why;
}

static void describe_device(const struct egl_fns *f, EGLDeviceEXT dev, int i, char *buf, size_t n)
{
    const char *exts = f->device_string ? f->device_string(dev, EGL_EXTENSIONS) : NULL;
    const char *drm = has_ext(exts, "EGL_EXT_device_drm") ? f->device_string(dev, EGL_DRM_DEVICE_FILE_EXT) : NULL;
    EGLAttrib cuda = -1;
    if (has_ext(exts, "EGL_NV_device_cuda") && !f->device_attrib(dev, EGL_CUDA_DEVICE_NV, &cuda))
        cuda = -1;
    char extra[64] = "";
    if (drm)
        snprintf(extra, sizeof extra, " %s", drm);
    else if (cuda >= 0)
        snprintf(extra, sizeof extra, " cuda %ld", (long)cuda);
    snprintf(buf, n, "device %d%s%s", i, has_ext(exts, "EGL_MESA_device_software") ? " software" : "", extra);
}

static int open_device(struct sl_gl *g, const struct egl_fns *f, EGLDeviceEXT *devs, int i, char *tried,
                       size_t tn)
{
    char what[96];
    describe_device(f, devs[i], i, what, sizeof what);
    const char *why = try_display(g, f->platform_display(EGL_PLATFORM_DEVICE_EXT, devs[i], NULL));
    if (why) {
        note(tried, tn, what, why);
        return 0;
    }
    snprintf(g->device, sizeof g->device, "%s, vendor %s", what,
             eglQueryString(g->egl_display, EGL_VENDOR));
    return 1;
}

static int is_software(const struct egl_fns *f, EGLDeviceEXT dev)
{
    return has_ext(f->device_string(dev, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

enum sl_err sl_egl_open(struct sl_gl *g, struct sl_diag *d)
{
    char why[300];
    if (sl_egl_load(why, sizeof why))
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "%s", why);
    struct egl_fns f;
    memset(&f, 0, sizeof f);
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    int devices = has_ext(client, "EGL_EXT_device_enumeration") || has_ext(client, "EGL_EXT_device_base");
    if (devices) {
        f.query_devices = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
        f.device_string = (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
        f.device_attrib = (PFNEGLQUERYDEVICEATTRIBEXTPROC)eglGetProcAddress("eglQueryDeviceAttribEXT");
    }
    f.platform_display = (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDeviceEXT devs[MAX_DEV];
    EGLint ndev = 0;
    if (!f.query_devices || !f.device_string || !f.device_attrib || !f.platform_display ||
        !f.query_devices(MAX_DEV, devs, &ndev))
        ndev = 0;
    char tried[400] = "";

    const char *want = getenv("SHADOWLAB_EGL_DEVICE");
    if (want && *want) {
        char *end;
        long n = strtol(want, &end, 10);
        if (end == want || *end || n < 0)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EGL_DEVICE",
                           "'%s' is not an EGL device number (0..%d)", want, ndev - 1);
        if (n >= ndev)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EGL_DEVICE",
                           "no EGL device %ld: this machine has %d (0..%d)", n, ndev, ndev - 1);
        if (open_device(g, &f, devs, (int)n, tried, sizeof tried))
            return SL_OK;
        return sl_fail(d, SL_E_GL, NULL, 0, "SHADOWLAB_EGL_DEVICE", "EGL: %s", tried);
    }

    const char *cuda = getenv("CUDA_VISIBLE_DEVICES");
    if (cuda && *cuda && ndev > 0) {
        char *end;
        long c = strtol(cuda, &end, 10);
        if (end != cuda && (*end == ',' || *end == '\0') && c >= 0)
            for (int i = 0; i < ndev; i++) {
                EGLAttrib v = -1;
                if (has_ext(f.device_string(devs[i], EGL_EXTENSIONS), "EGL_NV_device_cuda") &&
                    f.device_attrib(devs[i], EGL_CUDA_DEVICE_NV, &v) && v == c) {
                    if (open_device(g, &f, devs, i, tried, sizeof tried))
                        return SL_OK;
                    break;
                }
            }
    }
    for (int i = 0; i < ndev; i++)
        if (!is_software(&f, devs[i]) && open_device(g, &f, devs, i, tried, sizeof tried))
            return SL_OK;
    if (f.platform_display && has_ext(client, "EGL_MESA_platform_surfaceless")) {
        const char *why =
            try_display(g, f.platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL));
        if (!why) {
            snprintf(g->device, sizeof g->device, "surfaceless, vendor %s",
                     eglQueryString(g->egl_display, EGL_VENDOR));
            return SL_OK;
        }
        note(tried, sizeof tried, "surfaceless", why);
    } else
        note(tried, sizeof tried, "surfaceless", "no EGL_MESA_platform_surfaceless");
    for (int i = 0; i < ndev; i++)
        if (is_software(&f, devs[i]) && open_device(g, &f, devs, i, tried, sizeof tried))
            return SL_OK;
    if (ndev == 0)
        note(tried, sizeof tried, "devices", devices ? "none enumerated" : "no EGL_EXT_device_enumeration");
    return sl_fail(d, SL_E_GL, NULL, 0, NULL, "no EGL display gave a 4.5 core context: tried %s", tried);
}

/* The display of the last context stays initialized until exit. eglTerminate
 * makes Mesa unload its DRI driver (dlclose), and the next eglInitialize
 * loads, relocates and configures it again (dlopen of swrast_dri.so, the
 * driconf XML through expat): perf showed that as nearly all of a context's
 * creation, 60 ms per context on llvmpipe against OSMesa's 1.4 ms (bench
 * --only backends). eglInitialize of an initialized display does nothing, so
 * the next context on it costs what OSMesa's does. */
static EGLDisplay kept = EGL_NO_DISPLAY;

static void terminate_kept(void)
{
    if (kept != EGL_NO_DISPLAY)
        eglTerminate(kept);
    kept = EGL_NO_DISPLAY;
    eglReleaseThread();
}

void sl_egl_close(struct sl_gl *g)
{
    if (g->egl_display) {
        eglMakeCurrent(g->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (g->egl_ctx)
            eglDestroyContext(g->egl_display, g->egl_ctx);
        if (kept != g->egl_display) {
            static int registered;
            if (kept != EGL_NO_DISPLAY)
                eglTerminate(kept);
            kept = g->egl_display;
            if (!registered)
                registered = atexit(terminate_kept) == 0;
        }
    }
    g->egl_display = g->egl_ctx = NULL;
}
#else
typedef int sl_glegl_unused; /* an empty translation unit is not ISO C */
#endif
