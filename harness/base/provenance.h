/*
 * provenance.h — where a number came from: git SHA (built in), host, CPU
 * model and instruction set (llvmpipe and Embree pick code paths by ISA; the
 * results are meant to be the same on each, and CI checks that they are),
 * GL backend and renderer, Embree version and device config, threads,
 * UTC time. Written beside every result.
 */
#ifndef SL_PROVENANCE_H
#define SL_PROVENANCE_H
#include <stdio.h>
#ifdef __cplusplus
extern "C" {
#endif

struct sl_provenance {
    char git_sha[48];
    char time_utc[32];
    char host[64];
    char cpu[128];
    char isa[64];
    char gl_renderer[128];
    char gl_version[128];
    char gl_backend[192];    /* "osmesa", or "egl " + the EGL device and vendor used */
    char embree[200];        /* the version, then SHADOWLAB_EMBREE_CONFIG when set ("3.13.5 isa=avx2"): the
                              * store's runs.embree, so `check` counts a forced ISA as another machine */
    char embree_config[160]; /* SHADOWLAB_EMBREE_CONFIG as set, or "" */
    int  embree_packets;     /* rays per packet the truth used (the device's native width), 0 = not traced */
    int  threads;
    char lp_threads[16];     /* LP_NUM_THREADS as set, or "" */
    char omp_wait[40];       /* OMP_WAIT_POLICY as set (main.c sets passive for run and bench), else
                              * "GOMP_SPINCOUNT=N" if that is set, else "" (libgomp's default: spinning) */
};

/* The git SHA of the source this binary was built from (generated at build
 * time; "-dirty" when tracked files had uncommitted changes). */
const char *sl_git_sha(void);

void sl_provenance_fill(struct sl_provenance *p);

/* What a time measured on GL renderer `renderer` is, one sentence for the
 * caption or note of every cost table: the renderer named, and, on a
 * renderer that runs GL on the CPU (llvmpipe, softpipe, swrast), that its
 * GL times are CPU-emulated GL times, not a GPU's. "" or NULL: renderer
 * unknown (a store written before it was kept), said so. */
void sl_gl_times_note(const char *renderer, char *out, size_t n);
/* "key: value" lines, each prefixed by `prefix` (e.g. "# "). */
void sl_provenance_write(const struct sl_provenance *p, FILE *f, const char *prefix);

#ifdef __cplusplus
}
#endif
#endif
