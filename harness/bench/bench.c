/*
 * bench.c — see bench.h.
 *
 * The driver of the bench: the stage names, their order, the provenance
 * header, the summary and the --markdown file. Each stage is a file of its
 * own (bench_stages.h); the rows, timing and writers they share are
 * bench_row.c, below them.
 *
 * Studies run last, after this file's GL context and BVHs are freed: sl_run
 * makes its own (one OSMesa context at a time).
 */
#define _GNU_SOURCE   /* open_memstream, fopencookie */
#include "bench_stages.h"
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <omp.h>
#include "gbuffer.h"
#include "glctx.h"
#include "provenance.h"
#include "scenefile.h"
#include "truth.h"
#include "util.h"

#define TARGET_RSS_MIB       2048.0
#define TARGET_CONTEXT_MS    2000.0   /* the first context, driver loading included */

static const char *const stage_names[SL_BENCH_NSTAGES] = {
#define SL_BENCH_NAME(id, name) name,
    SL_BENCH_STAGES(SL_BENCH_NAME)
#undef SL_BENCH_NAME
};

enum sl_err sl_bench_parse_stages(const char *list, unsigned *out, struct sl_diag *d)
{
    *out = 0;
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (int i = 0; i < SL_BENCH_NSTAGES; i++)
            if (strlen(stage_names[i]) == n && strncmp(p, stage_names[i], n) == 0) {
                *out |= 1u << i;
                found = 1;
            }
        if (!found) {
            /* the names as SL_BENCH_STAGES lists them, so the message cannot drift */
            char known[256] = "";
            for (int i = 0, k = 0; i < SL_BENCH_NSTAGES && k < (int)sizeof known; i++)
                k += snprintf(known + k, sizeof known - (size_t)k, "%s%s", i ? ", " : "", stage_names[i]);
            return sl_fail(d, SL_E_USAGE, NULL, 0, "--only", "unknown stage '%.*s' (known: %s)", (int)n, p, known);
        }
        p += n;
        if (*p == ',')
            p++;
    }
    if (!*out)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--only", "no stage named");
    return SL_OK;
}

/* ---- --markdown FILE: the same text, into memory as well ------------------ */

/* The bench's Markdown goes to its stream as the stages finish (a run of
 * every stage takes minutes) and, with --markdown, also into memory: a
 * stream that writes each block to both. The real stream is flushed with
 * every block, so nothing of it sits in a buffer when a study is forked. */
struct tee { FILE *a, *b; };

static ssize_t tee_write(void *c, const char *buf, size_t n)
{
    struct tee *t = c;
    if (fwrite(buf, 1, n, t->a) != n || fwrite(buf, 1, n, t->b) != n)
        return -1;
    fflush(t->a);
    return (ssize_t)n;
}

static int tee_close(void *c)
{
    (void)c;
    return 0;
}


/* ---- the driver -------------------------------------------------------------- */

static enum sl_err setup(const struct sl_bench_opts *o, struct sl_bench_ctx *x, struct sl_diag *d)
{
    struct sl_config c;
    int have_cfg = o->config != NULL;
    enum sl_err e;
    if (have_cfg && (e = sl_config_load(o->config, &c, d)))
        return e;
    if (have_cfg)
        sl_config_free(&c);   /* its values only (scenes, viewpoints, sizes): no package runs here */
    const char *ref = o->scene ? o->scene : have_cfg ? c.scenes[0].path : "bench";
    if ((e = sl_scene_build(ref, &x->s, d)))
        return e;
    x->nvp = 0;
    if (have_cfg && !o->scene) {
        for (int i = 0; i < c.scenes[0].nviewpoints; i++) {
            int vp = sl_scene_find_viewpoint(&x->s, c.scenes[0].viewpoints[i]);
            if (vp >= 0)
                x->vp[x->nvp++] = vp;
        }
    } else {
        for (int i = 0; i < x->s.nvp; i++)
            x->vp[x->nvp++] = i;
    }
    if (x->nvp == 0)
        return sl_fail(d, SL_E_SCENE, x->s.path, 0, NULL, "scene %s has no viewpoint", x->s.name);
    x->W = o->width > 0 ? o->width : have_cfg ? c.viewport_w[0] : 1024;
    x->H = o->height > 0 ? o->height : have_cfg ? c.viewport_h[0] : 1024;
    x->S = o->map > 0 ? o->map : 2048;
    x->threads = have_cfg ? c.threads : omp_get_num_procs();
    x->reps = o->reps > 0 ? o->reps : 7;
    return SL_OK;
}

enum sl_err sl_bench(const struct sl_bench_opts *o, struct sl_bench_result *res_out, struct sl_diag *d)
{
    /* bigmap only when named: 16384^2 layers take GBs and minutes; timing too: it runs
     * the Moderno study six times */
    unsigned stages = o->stages ? o->stages : SL_BENCH_ALL & ~SL_BENCH_STAGE(BIGMAP) & ~SL_BENCH_STAGE(TIMING);
    FILE *out = o->out ? o->out : stdout;
    struct sl_bench_result *res = sl_calloc(1, sizeof *res);
    if (!res)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench rows");
    /* --markdown: everything written to out is also kept for the file */
    char *md_body = NULL;
    size_t md_len = 0;
    FILE *md_mem = NULL, *md_tee = NULL;
    struct tee md_t = {out, NULL};
    if (o->markdown) {
        md_mem = open_memstream(&md_body, &md_len);
        md_t.b = md_mem;
        md_tee = md_mem ? fopencookie(&md_t, "w", (cookie_io_functions_t){.write = tee_write, .close = tee_close})
                        : NULL;
        if (!md_tee) {
            if (md_mem)
                fclose(md_mem);
            free(md_body);
            free(res);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench Markdown");
        }
        out = md_tee;
    }
    char load0[64] = "unknown", stage_list[256] = "";
    int have_prov = 0;
    struct sl_bench_ctx x;
    memset(&x, 0, sizeof x);
    x.out = out;
    enum sl_err e = SL_OK;
    int need_scene = (stages & (SL_BENCH_STAGE(TRUTH) | SL_BENCH_STAGE(LAYERS) | SL_BENCH_STAGE(BACKENDS) |
                                SL_BENCH_STAGE(CHURN) | SL_BENCH_STAGE(TECHNIQUES) |
                                SL_BENCH_STAGE(SCORING) | SL_BENCH_STAGE(LIGHTFIT) |
                                SL_BENCH_STAGE(BIGMAP))) != 0;

    /* the studies' table (below): declared before any jump to done, which frees it */
    char *studies_md = NULL;
    size_t studies_len = 0;
    struct sl_bench_result study_rows;
    memset(&study_rows, 0, sizeof study_rows);

    /* start-up first, while this process has loaded nothing heavy (its own
     * RSS is the floor of its children's; bench_startup.c); its table is
     * printed in its turn, after the header */
    char *startup_md = NULL;
    size_t startup_len = 0;
    /* a bad SHADOWLAB_EMBREE_CONFIG stops the bench before any stage (after
     * the declarations that done frees) */
    if ((e = sl_rt_check_env(d)))
        goto done;
    if (stages & SL_BENCH_STAGE(STARTUP)) {
        FILE *mem = open_memstream(&startup_md, &startup_len);
        if (!mem)
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench start-up table");
        e = sl_bench_startup(o->config ? o->config : "configs/default.yaml", o->reps > 0 ? o->reps : 7, mem, res, d);
        fclose(mem);
        if (e)
            goto done;
    }

    /* the studies next, each in a child forked while this process is still
     * a single thread with nothing made (bench_study.c) */
    if (stages & (SL_BENCH_STAGE(MODERNO) | SL_BENCH_STAGE(MORAIS) | SL_BENCH_STAGE(TIMING))) {
        FILE *mem = open_memstream(&studies_md, &studies_len);
        if (!mem) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench studies' table");
            goto done;
        }
        fflush(out);
        if (stages & (SL_BENCH_STAGE(MODERNO) | SL_BENCH_STAGE(MORAIS)))
            e = sl_bench_studies(o, stages, mem, &study_rows, d);
        /* the timing stage: 3 pairs unless --reps says (each pair is two whole studies) */
        if (!e && (stages & SL_BENCH_STAGE(TIMING)))
            e = sl_bench_timing(o->moderno ? o->moderno : "configs/moderno-2011.yaml", o->gl, o->reps > 0 ? o->reps : 3,
                                mem, &study_rows, d);
        fclose(mem);
        if (e)
            goto done;
    }

    /* provenance first: a short-lived context for the renderer's name; the
     * process's first context, so its time includes loading the driver */
    struct sl_provenance prov;
    memset(&prov, 0, sizeof prov);
    const struct sl_gl_desc gdesc = {.backend = o->gl};
    double ctx_t0 = sl_now(), ctx_c0 = sl_bench_cpu_s();
    if ((e = sl_gl_open(&x.gl, &gdesc, d)))
        goto done;
    double ctx_ms = 1e3 * (sl_now() - ctx_t0), ctx_cpu_ms = 1e3 * (sl_bench_cpu_s() - ctx_c0);
    snprintf(prov.gl_renderer, sizeof prov.gl_renderer, "%s", x.gl.renderer);
    snprintf(prov.gl_version, sizeof prov.gl_version, "%s", x.gl.version);
    sl_gl_describe(&x.gl, prov.gl_backend, sizeof prov.gl_backend);
    enum sl_gl_backend used = x.gl.backend;
    sl_gl_free(&x.gl);
    snprintf(prov.embree, sizeof prov.embree, "%d.%d.%d", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    prov.threads = omp_get_num_procs();
    sl_provenance_fill(&prov);
    fprintf(out, "# shadowlab bench\n\n```\n");
    sl_provenance_write(&prov, out, "");
    fprintf(out, "stages:");
    for (int i = 0; i < SL_BENCH_NSTAGES; i++)
        if (stages & (1u << i)) {
            fprintf(out, " %s", stage_names[i]);
            size_t sl = strlen(stage_list);
            snprintf(stage_list + sl, sizeof stage_list - sl, "%s%s", sl ? ", " : "", stage_names[i]);
        }
    have_prov = 1;
    char la[64];
    sl_bench_loadavg(la, sizeof la);
    snprintf(load0, sizeof load0, "%s", la);
    fprintf(out, "\nload average at start: %s\n```\n\n", la);
    fflush(out);

    if (need_scene) {
        if ((e = setup(o, &x, d)) || (e = sl_gl_open(&x.gl, &gdesc, d)) || (e = sl_gl_mesh_upload(&x.mesh, &x.s, d)) ||
            (e = sl_gbuffer_init(&x.gp, &x.s, d)))
            goto done;
        if (stages & SL_BENCH_STAGE(TRUTH))
            e = sl_bench_truth(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(LAYERS)))
            e = sl_bench_layers(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(CHURN)))
            e = sl_bench_churn(&x.s, &x.mesh, &x.gp, x.vp[0], x.W, x.H, x.S, x.reps, out, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(TECHNIQUES)))
            e = sl_bench_techniques(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(SCORING)))
            e = sl_bench_score(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(LIGHTFIT)))
            e = sl_bench_lightfit(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(BIGMAP)))
            e = sl_bench_bigmap(&x, o->map > 0 ? o->map : 16384, res, d);
        fflush(out);
        sl_gbuffer_free(&x.gp);
        sl_gl_mesh_free(&x.mesh);
        sl_gl_free(&x.gl);
        /* with no context of this file's open: it opens its own, both kinds */
        if (!e && (stages & SL_BENCH_STAGE(BACKENDS)))
            e = sl_bench_backends(&x, res, d);
        fflush(out);
        if (e)
            goto done;
    }
    /* the studies' sections, measured first (above), in their turn */
    if (studies_md) {
        fputs(studies_md, out);
        fflush(out);
    }
    for (int i = 0; i < study_rows.nrows; i++) {
        struct sl_bench_row *row = sl_bench_add_row(res, "study", "", 0, 0, 0, SL_BENCH_AT_MOST);
        if (row)
            *row = study_rows.rows[i];
    }
    if (stages & SL_BENCH_STAGE(JOBS)) {
        e = sl_bench_jobs(o->config ? o->config : o->morais ? o->morais : "configs/morais-2015.yaml", o->gl, out, res, d);
        fflush(out);
        if (e)
            goto done;
    }
    if (startup_md) {
        fputs(startup_md, out);
        fflush(out);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    struct sl_bench_row *row = sl_bench_add_row(res, "memory", "MiB", ru.ru_maxrss / 1024.0, 0, TARGET_RSS_MIB,
                                       SL_BENCH_AT_MOST);
    if (row)
        snprintf(row->name, sizeof row->name, "peak RSS after all stages");
    /* last, so the stages' rows keep their places */
    struct sl_bench_row *crow = sl_bench_add_row(res, "context", "ms", ctx_ms, 0, TARGET_CONTEXT_MS, SL_BENCH_AT_MOST);
    if (crow)
        snprintf(crow->name, sizeof crow->name, "first GL context (%s), cpu %.1f ms",
                 sl_gl_backend_name(used), ctx_cpu_ms);
    sl_bench_write_summary(res, out);
    sl_bench_loadavg(la, sizeof la);
    fprintf(out, "load average at the end: %s\n\n", la);
    if (o->csv)
        e = sl_bench_write_csv(res, o->csv, d);
    if (!e && md_tee) {
        fclose(md_tee);
        md_tee = NULL;
        fclose(md_mem);
        md_mem = NULL;
        if (have_prov)
            e = sl_bench_write_markdown(o->markdown, &prov, stage_list, load0, la, md_body, md_len, d);
    }
done:
    if (md_tee)
        fclose(md_tee);
    if (md_mem)
        fclose(md_mem);
    free(md_body);
    if (x.gl.backend) {
        sl_gbuffer_free(&x.gp);
        sl_gl_mesh_free(&x.mesh);
        sl_gl_free(&x.gl);
    }
    if (need_scene)
        sl_scene_free(&x.s);
    if (res_out && !e)
        *res_out = *res;
    free(res);
    free(startup_md);
    free(studies_md);
    return e;
}

