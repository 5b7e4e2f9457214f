/*
 * bench_techniques.c — the `techniques` stage of `shadowlab bench`
 * (bench.h): each technique package of the source tree's techniques/
 * folder (issue 36) on the GL, its passes against plain passes of the same
 * size.
 *
 * Every package is measured at its defaults, or, when `sweeps` below names
 * it, at each of the values listed (pcf: kernel 3 and 5, the rest of its
 * parameters at their defaults). For each setting a plain package is built
 * in memory from it: the same maps (formats, filters), the same culling and
 * the same guard band (so the same N = S + 2g texels a side), no post pass;
 * its map shader writes the fragment's depth into every channel of every
 * map; its lookup reads `taps` texels of the first map (sl_tech_taps at
 * those values, rounded) in a plain loop over a square around the home
 * texel. Both run through techpass.c (the code a study runs), so the plain
 * passes carry the same harness work — the empty-texel pass, the G-buffer
 * upload, the projection — and the ratios are the packages' own shaders'.
 * A third plain lookup reading no texel gives that harness work alone (the
 * floor): on a GPU it is most of a lookup (the G-buffer upload), so the
 * lookup row also says what each costs above it.
 *
 * Each repetition renders and looks up with both, the package first on odd
 * repetitions, so drift of a shared VM hits both. Times are techpass.c's
 * costs (wall: the pass + glFinish; GPU: GL_TIME_ELAPSED, NaN = not
 * measured); CPU is the process's user + sys over the whole call (the post
 * passes included in the render call's). The lookup runs over the view's
 * PFL pixels, as a study looks up.
 */
#include "bench_stages.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "gbuffer.h"
#include "lightfit.h"
#include "techpass.h"
#include "technique.h"
#include "util.h"

/* issue 36: a package's map pass within 1.3x a plain raster writing the
 * same bytes per texel; its lookup within 1.5x a plain pass reading as many
 * texels */
#define TARGET_MAP_RATIO    1.3
#define TARGET_LOOKUP_RATIO 1.5

/* Settings measured beside the defaults: a package, an int parameter and
 * its values (the defaults are measured when no entry names the package). */
static const struct { const char *pkg, *param; int n; double v[4]; } sweeps[] = {
    {"pcf", "kernel", 2, {3, 5}},
    {NULL, NULL, 0, {0}},
};

/* what is timed; FLOOR: the plain lookup reading nothing, what every lookup pays before its reads */
enum { M_MAP, M_POST, M_LOOKUP, M_PMAP, M_PLOOKUP, M_FLOOR, M_N };
enum { K_WALL, K_GPU, K_CPU, K_N };

struct times {
    double *v;          /* [M_N][K_N][reps] */
    int reps;
};

#define TV(t, m, k, r) (t)->v[((size_t)(m) * K_N + (size_t)(k)) * (size_t)(t)->reps + (size_t)(r)]

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* min and median of the finite values of n (NaN when none), sorted in place */
static void min_med(double *v, int n, double *mn, double *md)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i]))
            v[k++] = v[i];
    if (!k) {
        *mn = *md = NAN;
        return;
    }
    qsort(v, (size_t)k, sizeof *v, cmp_d);
    *mn = v[0];
    *md = k % 2 ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
}

/* ---- the plain package -------------------------------------------------- */

/* The plain counterpart of t at guard band g and `taps` reads: the maps of
 * t without post passes, its map and lookup shaders (owned: free both
 * sources, never sl_tech_free). */
static enum sl_err plain_package(const struct sl_technique *t, int g, int taps, struct sl_technique *p,
                                 struct sl_diag *d)
{
    *p = *t;
    p->map_src = p->lookup_src = NULL;
    snprintf(p->name, sizeof p->name, "plain");
    snprintf(p->file, sizeof p->file, "%s (its plain counterpart, bench_techniques.c)", t->file);
    snprintf(p->map_shader, sizeof p->map_shader, "(plain map)");
    snprintf(p->lookup_shader, sizeof p->lookup_shader, "(plain lookup)");
    for (int i = 0; i < p->nmaps; i++) {
        p->map[i].post = SL_TECH_POST_NONE;
        p->map[i].blur = -1;
    }
    /* the same guard band, hence the same map size, as a fixed reach */
    p->reach = (struct sl_tech_scaled){.texels = g, .scale = 0, .power = 1, .param = -1};
    p->taps = (struct sl_tech_scaled){.texels = taps, .scale = 0, .power = 1, .param = -1};
    size_t nm = 256 + (size_t)p->nmaps * (SL_TECH_NAME_MAX + 32), nl = 1024;
    p->map_src = malloc(nm);
    p->lookup_src = malloc(nl);
    if (!p->map_src || !p->lookup_src) {
        free(p->map_src);
        free(p->lookup_src);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "plain package shaders");
    }
    size_t k = (size_t)snprintf(p->map_src, nm, "void sl_map(float z)\n{\n");
    for (int i = 0; i < p->nmaps; i++)
        k += (size_t)snprintf(p->map_src + k, nm - k, "    out_%s = vec4(z);\n", p->map[i].name);
    snprintf(p->map_src + k, nm - k, "}\n");
    /* a square of side w around the home texel, read row by row */
    int w = (int)ceil(sqrt((double)taps));
    snprintf(p->lookup_src, nl,
             "float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)\n"
             "{\n"
             "    ivec2 hi = textureSize(%s, 0) - 1;\n"
             "    float s = 0.0;\n"
             "    for (int i = 0; i < %d; i++)\n"
             "        s += dot(texelFetch(%s, clamp(sl_home_texel + ivec2(i %% %d, i / %d) - %d, ivec2(0), hi), 0),"
             " vec4(1.0));\n"
             "    return s >= z * %d.0 ? 1.0 : 0.0;\n"
             "}\n",
             p->map[0].name, taps, p->map[0].name, w > 0 ? w : 1, w > 0 ? w : 1, w / 2, taps);
    return SL_OK;
}

/* ---- one package at one setting ------------------------------------------ */

struct setting {
    const struct sl_technique *t;
    struct sl_params v;
    char label[96];
};

struct scene_in {
    const struct sl_bench_ctx *x;
    const struct sl_light_frame *f;
    const struct sl_view *view;
    const uint8_t *mask;
    float *vis;
};

/* What the post passes of t do at v, in words. */
static void post_text(const struct sl_technique *t, const struct sl_params *v, char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < t->nmaps && k < n; i++) {
        const struct sl_tech_map *m = &t->map[i];
        if (m->post == SL_TECH_POST_NONE)
            continue;
        int r = m->blur >= 0 && m->blur < v->n ? (int)v->v[m->blur] : 0;
        char what[96] = "";
        if ((m->post == SL_TECH_POST_BLUR || m->post == SL_TECH_POST_BLUR_MIPMAPS) && r > 0)
            snprintf(what, sizeof what, "box blur r=%d (2 passes of %d taps)", r, 2 * r + 1);
        if (m->post == SL_TECH_POST_MIPMAPS || m->post == SL_TECH_POST_BLUR_MIPMAPS) {
            size_t w = strlen(what);
            snprintf(what + w, sizeof what - w, "%smipmaps", w ? " + " : "");
        }
        k += (size_t)snprintf(buf + k, n - k, "%s%s %s: %s", k ? "; " : "", m->name, sl_tech_format_names[m->format],
                              what[0] ? what : "nothing at this setting");
    }
}

static void print_pair(FILE *out, const char *label, const char *pass, const char *what, struct times *tm, int m,
                       int pm, double target, double ratio)
{
    double mn[K_N], md[K_N], pmn[K_N], pmd[K_N];
    for (int k = 0; k < K_N; k++) {
        min_med(&TV(tm, m, k, 0), tm->reps, &mn[k], &md[k]);
        if (pm >= 0)
            min_med(&TV(tm, pm, k, 0), tm->reps, &pmn[k], &pmd[k]);
        else
            pmn[k] = pmd[k] = NAN;
    }
    char r[32] = "", tg[16] = "";
    if (pm >= 0) {
        snprintf(r, sizeof r, "**%.2f**", ratio);
        snprintf(tg, sizeof tg, "≤ %.1f", target);
    }
    fprintf(out, "| %s | %s | %s | %.2f | %.2f |", label, pass, what, mn[K_WALL], md[K_WALL]);
    if (pm >= 0)
        fprintf(out, " %.2f | %.2f |", pmn[K_WALL], pmd[K_WALL]);
    else
        fprintf(out, " — | — |");
    fprintf(out, " %s | %s |", r, tg);
    fputc(' ', out);
    double col[4] = {md[K_GPU], pmd[K_GPU], md[K_CPU], pmd[K_CPU]};
    for (int i = 0; i < 4; i++) {
        if (isfinite(col[i]))
            fprintf(out, "%.2f |", col[i]);
        else
            fprintf(out, "— |");
        fputc(i < 3 ? ' ' : '\n', out);
    }
}

static enum sl_err one_setting(const struct scene_in *in, const struct setting *st, struct times *tm,
                               struct sl_bench_result *res, struct sl_diag *d)
{
    const struct sl_bench_ctx *x = in->x;
    const struct sl_technique *t = st->t;
    const struct sl_params *v = &st->v;
    struct sl_techpass pk, pp, pf;
    memset(&pk, 0, sizeof pk);
    memset(&pp, 0, sizeof pp);
    memset(&pf, 0, sizeof pf);
    struct sl_technique plain, floor_pkg;
    memset(&plain, 0, sizeof plain);
    memset(&floor_pkg, 0, sizeof floor_pkg);
    int g = 0, N = 0;
    const int taps = (int)llround(sl_tech_taps(t, v));
    enum sl_err e = sl_techpass_init(&pk, t, d);
    if (!e)
        e = sl_techpass_size(&pk, in->f, v, &g, &N, d);
    if (!e)
        e = plain_package(t, g, taps, &plain, d);
    if (!e)
        e = sl_techpass_init(&pp, &plain, d);
    if (!e)
        e = plain_package(t, g, 0, &floor_pkg, d);
    if (!e)
        e = sl_techpass_init(&pf, &floor_pkg, d);
    /* the floor's maps once: its lookup reads none of them */
    if (!e)
        e = sl_techpass_render(&pf, &x->mesh, in->f, v, d);
    for (int r = -1; r < x->reps && !e; r++) {   /* r = -1: a warm-up, not kept (maps and targets made there) */
        for (int o = 0; o < 2 && !e; o++) {
            const int is_pkg = (o == 0) == (r % 2 != 0);   /* the package first on odd repetitions */
            struct sl_techpass *p = is_pkg ? &pk : &pp;
            double c0 = sl_bench_cpu_s();
            if ((e = sl_techpass_render(p, &x->mesh, in->f, v, d)))
                break;
            double c1 = sl_bench_cpu_s();
            if ((e = sl_techpass_lookup(p, in->f, v, in->view->pos, in->view->nrm, in->mask, in->view->w,
                                        in->view->h, in->vis, d)))
                break;
            double c2 = sl_bench_cpu_s();
            if (r < 0)
                continue;
            const struct sl_techpass_costs *c = &p->costs;
            const int mm = is_pkg ? M_MAP : M_PMAP, ml = is_pkg ? M_LOOKUP : M_PLOOKUP;
            TV(tm, mm, K_WALL, r) = c->ms_map;
            TV(tm, mm, K_GPU, r) = c->gpu_map;
            TV(tm, mm, K_CPU, r) = 1e3 * (c1 - c0);
            TV(tm, ml, K_WALL, r) = c->ms_lookup;
            TV(tm, ml, K_GPU, r) = c->gpu_lookup;
            TV(tm, ml, K_CPU, r) = 1e3 * (c2 - c1);
            if (is_pkg) {
                TV(tm, M_POST, K_WALL, r) = c->ms_post;
                TV(tm, M_POST, K_GPU, r) = c->gpu_post;
                TV(tm, M_POST, K_CPU, r) = NAN;   /* inside the render call's */
            }
        }
        double c3 = sl_bench_cpu_s();
        if (e || (e = sl_techpass_lookup(&pf, in->f, v, in->view->pos, in->view->nrm, in->mask, in->view->w,
                                         in->view->h, in->vis, d)))
            break;
        if (r >= 0) {
            TV(tm, M_FLOOR, K_WALL, r) = pf.costs.ms_lookup;
            TV(tm, M_FLOOR, K_GPU, r) = pf.costs.gpu_lookup;
            TV(tm, M_FLOOR, K_CPU, r) = 1e3 * (sl_bench_cpu_s() - c3);
        }
    }
    if (!e) {
        if (pk.costs.map_size != N || pp.costs.map_size != N)
            e = sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "%s: maps of %d and %d texels, not %d", st->label,
                        pk.costs.map_size, pp.costs.map_size, N);
        else if (pk.costs.lookups != pp.costs.lookups)
            e = sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "%s: %llu lookups, plain %llu", st->label,
                        (unsigned long long)pk.costs.lookups, (unsigned long long)pp.costs.lookups);
    }
    if (!e) {
        FILE *out = x->out;
        const uint64_t pixels = pk.costs.pixels;
        /* the wall medians from copies: print_pair sorts the columns in place */
        double mn, wall[M_N];
        for (int m = 0; m < M_N; m++) {
            double *col = &TV(tm, m, K_WALL, 0);
            double *copy = malloc((size_t)x->reps * sizeof *copy);
            if (!copy) {
                e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench medians");
                break;
            }
            memcpy(copy, col, (size_t)x->reps * sizeof *copy);
            min_med(copy, x->reps, &mn, &wall[m]);
            free(copy);
        }
        if (e)
            goto out;
        char what[320], fmts[96] = "";
        for (int i = 0, k = 0; i < t->nmaps; i++)
            k += snprintf(fmts + k, sizeof fmts - (size_t)k, "%s%s", i ? "+" : "", sl_tech_format_names[t->map[i].format]);
        /* map */
        snprintf(what, sizeof what, "%d map%s %s, %d² (S %d + 2 × guard %d), cull %s", t->nmaps,
                 t->nmaps > 1 ? "s" : "", fmts, N, in->f->size, g, sl_tech_cull_names[t->cull]);
        double rmap = wall[M_MAP] / wall[M_PMAP];
        print_pair(out, st->label, "map", what, tm, M_MAP, M_PMAP, TARGET_MAP_RATIO, rmap);
        struct sl_bench_row *row = sl_bench_add_row(res, "technique", "ms", wall[M_MAP], wall[M_PMAP],
                                                    TARGET_MAP_RATIO, SL_BENCH_AT_MOST);
        if (row) {
            snprintf(row->name, sizeof row->name, "%s map %d²", st->label, N);
            snprintf(row->note, sizeof row->note, "%s; plain: depth into every channel", fmts);
        }
        /* post passes: their own row, no target */
        char post[160];
        post_text(t, v, post, sizeof post);
        if (post[0])
            print_pair(out, st->label, "post", post, tm, M_POST, -1, 0, 0);
        /* lookup */
        const double above = wall[M_LOOKUP] - wall[M_FLOOR], p_above = wall[M_PLOOKUP] - wall[M_FLOOR];
        char rest[32] = "";
        if (above > 0 && p_above > 0)   /* else within the noise of the floor */
            snprintf(rest, sizeof rest, " = %.2fx", above / p_above);
        snprintf(what, sizeof what, "%d tap%s × %llu PFL px of %dx%d (%.3g M texel reads); floor (no reads) %.2f ms, "
                 "above it %.2f vs %.2f ms%s", taps, taps == 1 ? "" : "s", (unsigned long long)pixels, in->view->w,
                 in->view->h, 1e-6 * (double)pk.costs.lookups, wall[M_FLOOR], above, p_above, rest);
        double rl = wall[M_LOOKUP] / wall[M_PLOOKUP];
        print_pair(out, st->label, "lookup", what, tm, M_LOOKUP, M_PLOOKUP, TARGET_LOOKUP_RATIO, rl);
        row = sl_bench_add_row(res, "technique", "ms", wall[M_LOOKUP], wall[M_PLOOKUP], TARGET_LOOKUP_RATIO,
                               SL_BENCH_AT_MOST);
        if (row) {
            snprintf(row->name, sizeof row->name, "%s lookup %d tap%s", st->label, taps, taps == 1 ? "" : "s");
            snprintf(row->note, sizeof row->note, "%llu px; floor (G-buffer upload, projection, no reads) %.2f ms in both",
                     (unsigned long long)pixels, wall[M_FLOOR]);
        }
    }
out:
    if (pf.prog_map)
        sl_techpass_free(&pf);
    if (pp.prog_map)
        sl_techpass_free(&pp);
    if (pk.prog_map)
        sl_techpass_free(&pk);
    free(plain.map_src);
    free(plain.lookup_src);
    free(floor_pkg.map_src);
    free(floor_pkg.lookup_src);
    return e;
}

/* ---- the stage ----------------------------------------------------------- */

/* The packages of the source tree's techniques/ folder alone. */
static enum sl_err source_packages(struct sl_tech_set *set, char *where, size_t n, struct sl_diag *d)
{
    char (*dirs)[1024] = malloc(SL_TECH_MAX_DIRS * sizeof *dirs);
    const char *origin[SL_TECH_MAX_DIRS];
    memset(set, 0, sizeof *set);
    if (!dirs)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "technique search path");
    int nd = sl_tech_dirs(NULL, 0, NULL, dirs, origin, SL_TECH_MAX_DIRS), i = 0;
    while (i < nd && strcmp(origin[i], "source tree"))
        i++;
    enum sl_err e = SL_OK;
    if (i == nd)
        e = sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "no source tree on the technique search path");
    else {
        snprintf(where, n, "%s", dirs[i]);
        e = sl_tech_set_scan(set, &dirs[i], &origin[i], 1, NULL, d);
    }
    free(dirs);
    return e;
}

/* The settings measured: each package at its defaults, or at each value of
 * its sweep. Returns how many (at most max). */
static int settings_of(const struct sl_tech_set *set, struct setting *st, int max)
{
    int n = 0;
    for (int i = 0; i < set->n; i++) {
        const struct sl_technique *t = &set->t[i];
        int swept = 0;
        for (int s = 0; sweeps[s].pkg; s++) {
            int pi = sl_tech_param_index(t, sweeps[s].param);
            if (strcmp(sweeps[s].pkg, t->name) || pi < 0)
                continue;
            for (int k = 0; k < sweeps[s].n && n < max; k++, n++) {
                st[n].t = t;
                sl_tech_defaults(t, &st[n].v);
                st[n].v.v[pi] = sweeps[s].v[k];
                snprintf(st[n].label, sizeof st[n].label, "%s %s=%g", t->name, sweeps[s].param, sweeps[s].v[k]);
            }
            swept = 1;
        }
        if (!swept && n < max) {
            st[n].t = t;
            sl_tech_defaults(t, &st[n].v);
            snprintf(st[n].label, sizeof st[n].label, "%s", t->name);
            n++;
        }
    }
    return n;
}

enum sl_err sl_bench_techniques(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
{
    FILE *out = x->out;
    const int vp = x->vp[0];
    char la0[64], la1[64], where[1024] = "";
    sl_bench_loadavg(la0, sizeof la0);
    const double w0 = sl_now(), c0 = sl_bench_cpu_s();
    struct sl_view v;
    memset(&v, 0, sizeof v);
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    struct sl_tech_set set;
    uint8_t *mask = NULL;
    float *vis = NULL;
    struct setting *st = NULL;
    struct times tm = {NULL, x->reps};
    enum sl_err e = source_packages(&set, where, sizeof where, d);
    if (e)
        return e;
    if ((e = sl_gbuffer_render(&x->gp, &x->mesh, &x->s, vp, x->W, x->H, &v, NULL, NULL, NULL, d)))
        goto out;
    const size_t npx = (size_t)v.w * (size_t)v.h;
    mask = malloc(npx);
    vis = malloc(npx * sizeof *vis);
    st = calloc(SL_TECH_MAX_SET, sizeof *st);
    tm.v = calloc((size_t)M_N * K_N * (size_t)x->reps, sizeof *tm.v);
    if (!mask || !vis || !st || !tm.v) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "techniques stage buffers");
        goto out;
    }
    for (size_t i = 0; i < npx; i++)
        mask[i] = v.cls[i] == SL_C_PFL;   /* what a study looks up (methods/package.c) */
    /* the light frame of that view, as the layers stage fits it */
    f.size = x->S;
    memcpy(f.dir, x->s.light_dir, sizeof f.dir);
    sl_light_fit(&x->s, &v, &f.box);
    f.texel_world = fmaxf(f.box.hi[0] - f.box.lo[0], f.box.hi[1] - f.box.lo[1]) / (float)x->S;
    f.depth_range = f.box.hi[2] - f.box.lo[2];
    const int nst = settings_of(&set, st, SL_TECH_MAX_SET);

    fprintf(out, "## Technique packages vs plain passes of the same size (%s, %u triangles, viewpoint %s, "
                 "map %d², viewport %dx%d; min and median of %d after a warm-up)\n\n",
            x->s.name, x->s.nt, x->s.vp[vp].name, x->S, x->W, x->H, x->reps);
    fprintf(out, "Packages: %s (%d, %d settings). Plain map: the package's maps (formats, culling, guard band), "
                 "a map shader writing the fragment's depth into every channel, no post pass. Plain lookup: "
                 "as many texelFetch reads of the first map per pixel as the package counts (taps, rounded), "
                 "a plain loop over a square around the home texel. Both through techpass.c: the empty-texel "
                 "pass, the G-buffer upload and the projection are in both; the floor, that lookup reading no "
                 "texel, is what they cost alone (on a GPU most of a lookup). Wall: the pass + glFinish; "
                 "GPU: GL_TIME_ELAPSED (— = not measured); CPU: user + sys of the process over the whole "
                 "call (a render call's includes its post passes). Medians unless named.\n\n",
            where, set.n, nst);
    fprintf(out, "| package | pass | what | wall min ms | wall median ms | plain min ms | plain median ms | ratio "
                 "| target | GPU ms | plain GPU ms | CPU ms | plain CPU ms |\n");
    fprintf(out, "|---|---|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n");
    for (int i = 0; i < nst && !e; i++) {
        struct scene_in in = {x, &f, &v, mask, vis};
        e = one_setting(&in, &st[i], &tm, res, d);
        fflush(out);
    }
    if (!e) {
        sl_bench_loadavg(la1, sizeof la1);
        fprintf(out, "\nWhole stage: wall %.1f s, CPU (user + sys) %.1f s; load average before %s, after %s.\n\n",
                sl_now() - w0, sl_bench_cpu_s() - c0, la0, la1);
    }
out:
    sl_light_box_free(&f.box);
    sl_frame_free(&f);
    sl_view_free(&v);
    sl_tech_set_free(&set);
    free(mask);
    free(vis);
    free(st);
    free(tm.v);
    return e;
}
