/*
 * provenance.c — see provenance.h. Reads /proc/cpuinfo once; never fails
 * (unknown fields stay "unknown").
 */
#define _POSIX_C_SOURCE 200809L
#include "provenance.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

void sl_provenance_fill(struct sl_provenance *p)
{
    char gl_r[128], gl_v[128], gl_b[192], emb[sizeof p->embree];
    int threads = p->threads, packets = p->embree_packets;
    memcpy(gl_r, p->gl_renderer, sizeof gl_r);
    memcpy(gl_v, p->gl_version, sizeof gl_v);
    memcpy(gl_b, p->gl_backend, sizeof gl_b);
    memcpy(emb, p->embree, sizeof emb);
    memset(p, 0, sizeof *p);
    memcpy(p->gl_renderer, gl_r, sizeof gl_r);
    memcpy(p->gl_version, gl_v, sizeof gl_v);
    memcpy(p->gl_backend, gl_b, sizeof gl_b);
    memcpy(p->embree, emb, sizeof emb);
    p->threads = threads;
    p->embree_packets = packets;
    /* how Embree was told to trace (truth.h, sl_rt_env_config) */
    const char *ec = getenv("SHADOWLAB_EMBREE_CONFIG");
    if (ec && *ec) {
        snprintf(p->embree_config, sizeof p->embree_config, "%s", ec);
        if (p->embree[0]) {
            size_t len = strlen(p->embree);
            snprintf(p->embree + len, sizeof p->embree - len, " %s", p->embree_config);
        }
    }
    snprintf(p->git_sha, sizeof p->git_sha, "%s", sl_git_sha());
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(p->time_utc, sizeof p->time_utc, "%Y-%m-%dT%H:%M:%SZ", &tm);
    if (gethostname(p->host, sizeof p->host) != 0)
        snprintf(p->host, sizeof p->host, "unknown");
    snprintf(p->cpu, sizeof p->cpu, "unknown");
    snprintf(p->isa, sizeof p->isa, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[4096];
        int got_model = 0, got_flags = 0;
        while (fgets(line, sizeof line, f) && !(got_model && got_flags)) {
            char *colon = strchr(line, ':');
            if (!colon)
                continue;
            char *val = colon + 1;
            while (*val == ' ')
                val++;
            val[strcspn(val, "\n")] = '\0';
            if (!got_model && strncmp(line, "model name", 10) == 0) {
                snprintf(p->cpu, sizeof p->cpu, "%s", val);
                got_model = 1;
            } else if (!got_flags && strncmp(line, "flags", 5) == 0) {
                /* the widest vector ISA, which is what llvmpipe and Embree key on */
                const char *isa = strstr(val, " avx512f") ? "avx512"
                                : strstr(val, " avx2")    ? "avx2"
                                : strstr(val, " avx ")    ? "avx"
                                : strstr(val, " sse4_2")  ? "sse4.2"
                                                          : "sse2";
                snprintf(p->isa, sizeof p->isa, "x86_64-%s%s", isa, strstr(val, " fma") ? "+fma" : "");
                got_flags = 1;
            }
        }
        fclose(f);
    }
    const char *lp = getenv("LP_NUM_THREADS");
    snprintf(p->lp_threads, sizeof p->lp_threads, "%s", lp ? lp : "");
    const char *wp = getenv("OMP_WAIT_POLICY"), *sc = getenv("GOMP_SPINCOUNT");
    if (wp)
        snprintf(p->omp_wait, sizeof p->omp_wait, "%.32s", wp);
    else if (sc)
        snprintf(p->omp_wait, sizeof p->omp_wait, "GOMP_SPINCOUNT=%.20s", sc);
    else
        p->omp_wait[0] = 0;
}

void sl_provenance_write(const struct sl_provenance *p, FILE *f, const char *prefix)
{
    fprintf(f, "%sgit_sha: %s\n", prefix, p->git_sha);
    fprintf(f, "%stime_utc: %s\n", prefix, p->time_utc);
    fprintf(f, "%shost: %s\n", prefix, p->host);
    fprintf(f, "%scpu: %s\n", prefix, p->cpu);
    fprintf(f, "%sisa: %s\n", prefix, p->isa);
    fprintf(f, "%sgl_renderer: %s\n", prefix, p->gl_renderer);
    fprintf(f, "%sgl_version: %s\n", prefix, p->gl_version);
    fprintf(f, "%sgl_backend: %s\n", prefix, p->gl_backend[0] ? p->gl_backend : "(unknown)");
    fprintf(f, "%sembree: %s\n", prefix, p->embree);
    fprintf(f, "%sembree_config: %s\n", prefix, p->embree_config[0] ? p->embree_config : "(unset)");
    if (p->embree_packets)
        fprintf(f, "%sembree_packets: %d\n", prefix, p->embree_packets);
    fprintf(f, "%sthreads: %d\n", prefix, p->threads);
    fprintf(f, "%slp_num_threads: %s\n", prefix, p->lp_threads[0] ? p->lp_threads : "(unset)");
    fprintf(f, "%somp_wait_policy: %s\n", prefix, p->omp_wait[0] ? p->omp_wait : "(unset)");
}

void sl_gl_times_note(const char *renderer, char *out, size_t n)
{
    if (!renderer || !renderer[0]) {
        snprintf(out, n, "Times in ms on a GL renderer not recorded.");
        return;
    }
    /* Mesa's software rasterisers: GL executed by CPU threads */
    const int cpu = strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") || strstr(renderer, "swrast");
    snprintf(out, n, "Times in ms on %s%s", renderer,
             cpu ? ", which runs GL on the CPU: its GL times (wall and GL_TIME_ELAPSED) are CPU-emulated GL times, "
                   "not a GPU's."
                 : " (GL stages: wall time, GPU time from GL_TIME_ELAPSED beside).");
}
