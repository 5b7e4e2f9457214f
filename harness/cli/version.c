/*
 * version.c — `shadowlab --version` (also `-V`, `version`): what a paper's
 * methods section and a bug report need to name this binary.
 *
 * The first line is "shadowlab X.Y.Z (git SHA)" (scripts read it), then
 * the build type and the Embree the binary was compiled against. These come
 * from the binary alone: `--version` loads no library (cli::startup holds it
 * to that, as scripts and the shell's completion call it often).
 *
 * `--version --verbose` also opens what a run opens, each as a run would
 * (SHADOWLAB_GL, SHADOWLAB_EGL_DEVICE and SHADOWLAB_EMBREE_CONFIG obeyed):
 * the GL context, to print its renderer and version, and an Embree device,
 * to print the library's own version and the packet width it runs natively
 * (which names the ISA of its kernels: 4 wide SSE, 8 AVX/AVX2, 16 AVX-512).
 * The choice of a flag, and not always, is so that the light form stays
 * light (about 100 ms and Mesa's and Embree's libraries for the heavy
 * one); `run` writes the same fields beside every result. Either part that
 * cannot be opened says why on its line and the exit status stays 0: the
 * version was printed, and a machine without GL is worth describing too.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <string.h>
#include <embree3/rtcore.h>
#include "cli.h"
#include "glctx.h"
#include "provenance.h"
#include "rtload.h"
#include "truth.h"

#ifndef SL_VERSION
#define SL_VERSION "unknown"
#endif
#ifndef SL_BUILD_TYPE
#define SL_BUILD_TYPE "unknown"
#endif

static void print_gl(void)
{
    struct sl_gl g;
    struct sl_diag d;
    memset(&g, 0, sizeof g);
    memset(&d, 0, sizeof d);
    if (sl_gl_init(&g, &d) != SL_OK) {
        printf("gl: unavailable (%s)\n", d.msg);
        return;
    }
    char backend[192];
    sl_gl_describe(&g, backend, sizeof backend);
    printf("gl renderer: %s\n", g.renderer);
    printf("gl version: %s\n", g.version);
    printf("gl backend: %s\n", backend);
    sl_gl_free(&g);
}

static void print_embree(void)
{
    char why[256];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (sl_rt_check_env(&d) != SL_OK) {
        printf("embree: unavailable (%s: %s)\n", d.key, d.msg);
        return;
    }
    if (sl_rtc_load(why, sizeof why)) {
        printf("embree: unavailable (%s)\n", why);
        return;
    }
    const char *cfg = sl_rt_env_config();
    RTCDevice dev = rtcNewDevice(cfg);
    if (!dev) {
        printf("embree: unavailable (rtcNewDevice failed, error %d)\n", (int)rtcGetDeviceError(NULL));
        return;
    }
    int w = rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) ? 16
          : rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)  ? 8
          : rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)  ? 4
                                                                                  : 1;
    printf("embree: %d.%d.%d\n", (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
           (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_MINOR),
           (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_PATCH));
    printf("embree packets: %d wide (%s kernels)\n", w,
           w == 16 ? "AVX-512" : w == 8 ? "AVX or AVX2" : w == 4 ? "SSE" : "no packet");
    printf("embree config: %s\n", cfg ? cfg : "(unset: the CPU's best ISA)");
    rtcReleaseDevice(dev);
}

int cli_version(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"verbose", no_argument, NULL, 'v'}, {0, 0, 0, 0}};
    const struct cli_parser parser = {"version", "v", cli_usage_version, lo};
    int verbose = 0;
    for (int c; (c = cli_opt_next(&parser, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case 'v': verbose = 1; break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind < argc)
        return cli_usage_error("version: takes no argument", cli_usage_version);
    printf("shadowlab %s (git %s)\n", SL_VERSION, sl_git_sha());
    printf("build: %s\n", SL_BUILD_TYPE);
    printf("embree headers: %d.%d.%d\n", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    if (verbose) {
        struct sl_provenance p;
        memset(&p, 0, sizeof p);
        sl_provenance_fill(&p);
        printf("cpu: %s (%s)\n", p.cpu, p.isa);
        print_gl();
        print_embree();
    }
    return 0;
}
