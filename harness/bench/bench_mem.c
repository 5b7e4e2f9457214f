/*
 * bench_mem.c — the `bigmap` stage of `shadowlab bench` (bench.h): the peak
 * memory of one view's conservative layers at a big map size (16384^2 by
 * default; `--map N` for another), rendered the way a run's group renders
 * them for csm and csm_adj (run.c, ensure_frame): SGSM and SGSM with
 * adjacency first, each gathered per pixel of the view once drawn
 * (frame.h: both methods read them at a pixel's own texel only), then BGSM
 * and BGSM2, BGSM2 gathered too; at most three map-sized arrays at once
 * (five before: BGSM, BGSM2 and SGSM held dense). At 16384^2 a layer array is 1 GiB and so is each
 * texture of the render target: issue 20 measured 13.9 GB (five 2 GiB
 * layers held at once, the GL target, BGSM2's id copy, a repetition's
 * scratch layer). Target: at most 6 GB (6e9 bytes: the stricter reading).
 *
 * Peak RSS is the kernel's high-water mark (VmHWM), reset to the current
 * RSS when the stage starts (/proc/self/clear_refs, "5"), so earlier stages
 * do not count; what the process held before (scene, GL driver) does, and
 * is printed apart. Where the reset is refused the row says so and quotes
 * the process's peak so far.
 *
 * Then the check: each layer rendered again the plain way — a pass of its
 * own, calloc'd arrays, one layer at a time, BGSM2 uploading BGSM's ids
 * from the frame (plain_hashes) — its 64-bit hash against the measured
 * layer's. The check's own memory comes after the peak is read.
 */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include "adjacency.h"
#include "bench_stages.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "util.h"

#define TARGET_BYTES 6e9

/* "VmHWM:" or "VmRSS:" of /proc/self/status in bytes, -1 unknown. */
static double proc_status_bytes(const char *key)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f)
        return -1;
    char line[256];
    double v = -1;
    size_t n = strlen(key);
    while (fgets(line, sizeof line, f))
        if (strncmp(line, key, n) == 0) {
            v = 1024.0 * strtod(line + n, NULL);
            break;
        }
    fclose(f);
    return v;
}

/* The high-water mark back to the current RSS; 0 when the kernel refused. */
static int reset_hwm(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f)
        return 0;
    int ok = fputs("5", f) >= 0;
    return fclose(f) == 0 && ok;
}

/* A layer's arrays hashed (FNV-1a over 32-bit words; the id array may be
 * NULL): equal hashes stand for equal layers. */
static uint64_t layer_hash(const struct sl_depth_layer *L, size_t n)
{
    uint64_t h = 1469598103934665603ull;
    const uint32_t *w = (const uint32_t *)L->depth;
    for (size_t i = 0; i < n; i++)
        h = (h ^ w[i]) * 1099511628211ull;
    h = (h ^ (L->id != NULL)) * 1099511628211ull;
    for (size_t i = 0; L->id && i < n; i++)
        h = (h ^ L->id[i]) * 1099511628211ull;
    return h;
}

static void frame_init(struct sl_light_frame *f, const struct sl_scene *s, const struct sl_view *v, int S,
                       struct sl_layer_pool *pool)
{
    memset(f, 0, sizeof *f);
    f->pool = pool;
    f->size = S;
    memcpy(f->dir, s->light_dir, sizeof f->dir);
    sl_light_fit(s, v, &f->box);
    f->texel_world = fmaxf(f->box.hi[0] - f->box.lo[0], f->box.hi[1] - f->box.lo[1]) / (float)S;
    f->depth_range = f->box.hi[2] - f->box.lo[2];
}

/* Layers held at the map's size (not gathered per pixel). */
static int dense(const struct sl_light_frame *f)
{
    int k = 0;
    for (int l = 0; l < SL_LAYER_COUNT; l++)
        k += (f->have & SL_NEED(l)) && !f->layer[l].per_pixel;
    return k;
}

/* The plain way (see the top): every layer of `want` once, hashed into h[]. */
static enum sl_err plain_hashes(const struct sl_bench_ctx *x, const struct sl_view *v, int S, uint64_t h[],
                                struct sl_diag *d)
{
    struct sl_shadowmap_pass p;
    enum sl_err e = sl_shadowmap_init(&p, d);
    if (e)
        return e;
    struct sl_light_frame f;
    frame_init(&f, &x->s, v, S, NULL);
    const size_t n = (size_t)S * (size_t)S;
    /* SGSM between BGSM and BGSM2: BGSM2 then finds SGSM's ids in the
     * target and uploads BGSM's from the frame, where the measured render
     * reads them where BGSM left them — the two ways checked against each
     * other */
    const int order[4] = {SL_LAYER_BGSM, SL_LAYER_SGSM, SL_LAYER_BGSM2, SL_LAYER_SGSM_ADJ};
    for (int i = 0; i < 4 && !e; i++) {
        int l = order[i];
        if ((e = sl_shadowmap_render(&p, &x->mesh, &f, SL_NEED(l), d)))
            break;
        h[l] = layer_hash(&f.layer[l], n);
        if (l == SL_LAYER_BGSM2)
            sl_frame_drop_layer(&f, SL_LAYER_BGSM);
        if (l != SL_LAYER_BGSM)
            sl_frame_drop_layer(&f, l);
    }
    if (!e && p.ids_uploads != 1)
        e = sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "bigmap: the plain BGSM2 did not upload BGSM's ids");
    sl_light_box_free(&f.box);
    sl_frame_free(&f);
    sl_shadowmap_free(&p);
    return e;
}

enum sl_err sl_bench_bigmap(struct sl_bench_ctx *x, int S, struct sl_bench_result *res, struct sl_diag *d)
{
    FILE *out = x->out;
    struct sl_view v;
    memset(&v, 0, sizeof v);
    struct sl_shadowmap_pass p;
    memset(&p, 0, sizeof p);
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    enum sl_err e = SL_OK;
    if (!x->mesh.vao_adj) {
        struct sl_adjacency adj = {0};
        e = sl_adjacency_build(&x->s, &adj, d);
        if (!e)
            e = sl_gl_mesh_upload_adjacency(&x->mesh, &x->s, &adj, d);
        sl_adjacency_free(&adj);
        if (e)
            return e;
    }
    if ((e = sl_gbuffer_render(&x->gp, &x->mesh, &x->s, x->vp[0], x->W, x->H, &v, NULL, NULL, NULL, d)) ||
        (e = sl_shadowmap_init(&p, d)))
        goto out;
    /* the programs are compiled and the view rendered: what is held now is
     * the floor the layers add to */
    char la0[64], la1[64];
    sl_bench_loadavg(la0, sizeof la0);
    glFinish();
    const int reset = reset_hwm();
    const double rss0 = proc_status_bytes("VmRSS:");
    struct rusage ru0, ru1;
    getrusage(RUSAGE_SELF, &ru0);
    const double t0 = sl_now(), c0 = sl_bench_cpu_s();
    const size_t n = (size_t)S * (size_t)S;
    uint64_t h[SL_LAYER_COUNT] = {0}, hp[SL_LAYER_COUNT] = {0};
    frame_init(&f, &x->s, &v, S, &p.pool);
    f.pix_pool = &p.pix_pool;
    /* as run.c's ensure_frame for a group of csm and csm_adj: the layers
     * both read only at each pixel's own texel (SGSM, SGSM with adjacency,
     * BGSM2) are gathered per pixel once drawn, SGSM's two first, each
     * hashed first; then BGSM and BGSM2, the dense layers csm holds */
    const int order[4] = {SL_LAYER_SGSM, SL_LAYER_SGSM_ADJ, SL_LAYER_BGSM, SL_LAYER_BGSM2};
    int most = 0;
    for (int i = 0; i < 4 && !e; i++) {
        const int l = order[i];
        if ((e = sl_shadowmap_render(&p, &x->mesh, &f, SL_NEED(l), d)))
            break;
        most = dense(&f) > most ? dense(&f) : most;
        h[l] = layer_hash(&f.layer[l], n);
        if (l != SL_LAYER_BGSM)
            e = sl_frame_gather(&f, l, &v, 0, d);
    }
    if (e)
        goto out;
    const double t1 = sl_now(), c1 = sl_bench_cpu_s();
    getrusage(RUSAGE_SELF, &ru1);
    const double hwm = proc_status_bytes("VmHWM:");
    const double peak = reset ? hwm : 1024.0 * (double)ru1.ru_maxrss;
    sl_bench_loadavg(la1, sizeof la1);
    double ms[SL_LAYER_COUNT];
    for (int l = 0; l < SL_LAYER_COUNT; l++)
        ms[l] = f.layer[l].ms_render + f.layer[l].ms_readback;
    const uint64_t made = p.targets_made, uploads = p.ids_uploads;
    const double pool_bytes = (double)p.pool.bytes, pix_bytes = (double)p.pix_pool.bytes;
    sl_light_box_free(&f.box);
    sl_frame_free(&f);
    sl_shadowmap_free(&p);   /* the pool and any target: the check's memory is its own */
    if ((e = plain_hashes(x, &v, S, hp, d)))
        goto out;
    int same = 0;
    for (int l = SL_LAYER_BGSM; l < SL_LAYER_COUNT; l++)
        same += h[l] == hp[l];
    const double GiB = 1024.0 * 1024.0 * 1024.0;
    fprintf(out, "## Big map: one view's conservative layers at %d² (%s, %u triangles, view %dx%d)\n\n", S,
            x->s.name, x->s.nt, x->W, x->H);
    fprintf(out, "As a run's group renders them for csm and csm_adj: SGSM, then SGSM with adjacency, each gathered "
                 "per pixel of the view once drawn (the map-sized arrays given back), then BGSM and BGSM2 (BGSM2 "
                 "gathered too). Peak RSS: the kernel's high-water mark (VmHWM) "
                 "%s. A layer array at this size: %.3f GiB.\n\n",
            reset ? "reset when the stage started" : "NOT reset (clear_refs refused): the process's peak so far",
            (double)n * 4.0 / GiB);
    fprintf(out, "| | |\n|---|---|\n");
    fprintf(out, "| peak RSS | %.0f MiB (%.2f GB; target ≤ %.0f GB: **%s**) |\n", peak / 1048576.0, peak / 1e9,
            TARGET_BYTES / 1e9, peak <= TARGET_BYTES ? "PASS" : "MISS");
    fprintf(out, "| RSS at the start (scene, view, GL driver) | %.0f MiB |\n", rss0 / 1048576.0);
    fprintf(out, "| map-sized layers held at once, at most | %d |\n", most);
    fprintf(out, "| pool arrays at the end: map-sized / per pixel | %.0f / %.1f MiB |\n", pool_bytes / 1048576.0,
            pix_bytes / 1048576.0);
    fprintf(out, "| render targets made / BGSM2 id uploads | %llu / %llu |\n", (unsigned long long)made,
            (unsigned long long)uploads);
    fprintf(out, "| wall / CPU (user + sys) | %.2f s / %.2f s |\n", t1 - t0, c1 - c0);
    fprintf(out, "| minor / major page faults | %ld / %ld |\n", ru1.ru_minflt - ru0.ru_minflt,
            ru1.ru_majflt - ru0.ru_majflt);
    fprintf(out, "| load average before / after | %s / %s |\n", la0, la1);
    for (int l = SL_LAYER_BGSM; l < SL_LAYER_COUNT; l++)
        fprintf(out, "| %s | %.0f ms render + readback; %s the plain render (hash %016llx) |\n", sl_layer_titles[l], ms[l],
                h[l] == hp[l] ? "bit-identical to" : "**DIFFERS from**", (unsigned long long)h[l]);
    fprintf(out, "\nlayers identical: %d of 4\n\n", same);
    struct sl_bench_row *row = sl_bench_add_row(res, "bigmap", "MiB", peak / 1048576.0, 0,
                                                TARGET_BYTES / 1048576.0, SL_BENCH_AT_MOST);
    if (row) {
        snprintf(row->name, sizeof row->name, "peak RSS, conservative layers %d²", S);
        snprintf(row->note, sizeof row->note, "%d layers at once; wall %.1f s, CPU %.1f s; %d of 4 identical",
                 most, t1 - t0, c1 - c0, same);
    }
    if (same != 4)
        e = sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "bigmap: %d of 4 layers differ from the plain render",
                    4 - same);
out:
    sl_light_box_free(&f.box);
    sl_frame_free(&f);
    if (p.prog_depth_id)
        sl_shadowmap_free(&p);
    sl_view_free(&v);
    return e;
}
