/*
 * run.c — see run.h.
 *
 * Order of work, each arrow computed once and shared downstream:
 * scene -> GL mesh + Embree BVH; per viewport x viewpoint: G-buffer -> truth
 * -> light fit; per map size: the union of the methods' layers; per method:
 * verdicts -> contours of its own image -> figures -> overlay.
 */
#define _XOPEN_SOURCE 700
#include "run.h"
#include <ftw.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "contour.h"
#include "gbuffer.h"
#include "glctx.h"
#include "image.h"
#include "lightfit.h"
#include "overlay.h"
#include "shadowmap.h"
#include "truth.h"
#include "util.h"

void sl_run_result_free(struct sl_run_result *r)
{
    if (!r)
        return;
    free(r->cells);
    memset(r, 0, sizeof *r);
}

static int rm_cb(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb; (void)flag; (void)ftw;
    return remove(p);
}

static void rm_tree(const char *path)
{
    nftw(path, rm_cb, 16, FTW_DEPTH | FTW_PHYS);
}

static const char *region_name(int t, char *buf, size_t n)
{
    if (t == 0)
        snprintf(buf, n, "image");
    else
        snprintf(buf, n, "%dpx", t);
    return buf;
}

/* ---- writers ---- */

static void write_csv_header(FILE *f)
{
    fprintf(f, "scene,viewpoint,viewport,map_size,method,label,region,figure,count,percent,percent_of,"
               "git_sha,config_hash,machine\n");
}

static void write_csv_cell(FILE *f, const struct sl_config *c, const struct sl_run_result *res,
                           const struct sl_cell *cell)
{
    const struct sl_config_method *m = &c->methods[cell->method];
    for (int r = 0; r < cell->fig.nregions; r++) {
        const struct sl_region_figures *g = &cell->fig.r[r];
        char rn[16];
        region_name(g->thickness, rn, sizeof rn);
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            fprintf(f, "%s,%s,%dx%d,%d,%s,%s,%s,%s,%llu,", c->scene, cell->viewpoint,
                    c->viewport_w[cell->viewport], c->viewport_h[cell->viewport], c->maps[cell->map],
                    m->method->name, m->label, rn, sl_figure_name((enum sl_figure)k),
                    (unsigned long long)g->n[k]);
            if (isnan(g->pct[k]))
                fprintf(f, ",");
            else
                fprintf(f, "%.4f,", g->pct[k]);
            fprintf(f, "%s,%s,%016llx,\"%s/%s/%s\"\n", sl_figure_of((enum sl_figure)k), res->prov.git_sha,
                    c->hash, res->prov.host, res->prov.cpu, res->prov.isa);
        }
    }
    fprintf(f, "%s,%s,%dx%d,%d,%s,%s,image,background,%llu,,,%s,%016llx,\"%s/%s/%s\"\n", c->scene,
            cell->viewpoint, c->viewport_w[cell->viewport], c->viewport_h[cell->viewport],
            c->maps[cell->map], m->method->name, m->label, (unsigned long long)cell->fig.background,
            res->prov.git_sha, c->hash, res->prov.host, res->prov.cpu, res->prov.isa);
}

static void write_costs_header(FILE *f)
{
    fprintf(f, "scene,viewpoint,viewport,map_size,label,ms_gbuffer_render,ms_gbuffer_readback,"
               "ms_truth,truth_rays,ms_fit,ms_map_render,ms_map_readback,ms_method,lookups,rays,"
               "tri_tests,ms_contours,ms_figures,ms_overlay,git_sha,config_hash,machine\n");
}

static void write_costs_cell(FILE *f, const struct sl_config *c, const struct sl_run_result *res,
                             const struct sl_cell *cell)
{
    const struct sl_stage_ms *s = &cell->ms;
    fprintf(f, "%s,%s,%dx%d,%d,%s,%.3f,%.3f,%.3f,%llu,%.3f,%.3f,%.3f,%.3f,%llu,%llu,%llu,%.3f,%.3f,%.3f,"
               "%s,%016llx,\"%s/%s/%s\"\n",
            c->scene, cell->viewpoint, c->viewport_w[cell->viewport], c->viewport_h[cell->viewport],
            c->maps[cell->map], c->methods[cell->method].label, s->gbuffer_render, s->gbuffer_readback,
            s->truth, (unsigned long long)cell->truth_rays, s->fit, s->map_render, s->map_readback,
            s->method, (unsigned long long)cell->cost.lookups, (unsigned long long)cell->cost.rays,
            (unsigned long long)cell->cost.tri_tests, s->contours, s->figures, s->overlay,
            res->prov.git_sha, c->hash, res->prov.host, res->prov.cpu, res->prov.isa);
}

static void md_cell(FILE *f, const struct sl_region_figures *g, int k)
{
    if (isnan(g->pct[k]))
        fprintf(f, " %llu |", (unsigned long long)g->n[k]);
    else
        fprintf(f, " %llu (%.2f%%) |", (unsigned long long)g->n[k], g->pct[k]);
}

/* One table per (viewport, viewpoint, method): rows are figures, columns are
 * map size x region (Moderno 2011 Tables 17/18 and Morais 2015 Table 7 in one). */
static void write_markdown(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "# shadowlab: %s\n\n", c->name);
    fprintf(f, "scene `%s`, config `%s` (hash %016llx), git %s, %s (%s, %s), %s, Embree %s, %d threads, %s\n\n",
            c->scene, c->path, c->hash, res->prov.git_sha, res->prov.host, res->prov.cpu, res->prov.isa,
            res->prov.gl_renderer, res->prov.embree, res->prov.threads, res->prov.time_utc);
    fprintf(f, "Percentages: PFL, PnFL, light, shadow, wrong of the region's pixels; correct/incorrect "
               "of the method's light or shadow pixels; wrong caught of all wrong pixels of the image. "
               "Background pixels enter no region; PnFL pixels count as shadow.\n\n");
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *first = &res->cells[i];
        if (first->map != 0)
            continue;
        const struct sl_config_method *m = &c->methods[first->method];
        fprintf(f, "## %s / %s / %dx%d / %s\n\n", c->scene, first->viewpoint,
                c->viewport_w[first->viewport], c->viewport_h[first->viewport], m->label);
        fprintf(f, "PFL %llu, PnFL %llu, background %llu; truth: %llu PFL lit, %llu PFL shadowed.\n\n",
                (unsigned long long)first->n_pfl, (unsigned long long)first->n_pnfl,
                (unsigned long long)first->n_background, (unsigned long long)first->n_truth_lit,
                (unsigned long long)first->n_truth_shadow);
        fprintf(f, "| figure |");
        for (int mp = 0; mp < c->nmaps; mp++)
            for (int r = 0; r < c->nregions; r++) {
                char rn[16];
                fprintf(f, " %d² %s |", c->maps[mp], region_name(c->regions[r], rn, sizeof rn));
            }
        fprintf(f, "\n|---|");
        for (int k = 0; k < c->nmaps * c->nregions; k++)
            fprintf(f, "---:|");
        fprintf(f, "\n");
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            fprintf(f, "| %s |", sl_figure_name((enum sl_figure)k));
            for (int mp = 0; mp < c->nmaps; mp++) {
                /* cells of this view and method are laid out map-major */
                const struct sl_cell *cell = first + mp * c->nmethods;
                for (int r = 0; r < cell->fig.nregions; r++)
                    md_cell(f, &cell->fig.r[r], k);
            }
            fprintf(f, "\n");
        }
        fprintf(f, "\n");
    }
    fprintf(f, "## Cost per cell (ms; G-buffer and truth are shared by the cells of a view)\n\n");
    fprintf(f, "| viewpoint | map | label | G-buffer | truth | rays | fit | map render | readback | method | lookups | contours | figures | overlay |\n");
    fprintf(f, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        const struct sl_stage_ms *s = &cl->ms;
        fprintf(f, "| %s | %d | %s | %.1f | %.1f | %llu | %.1f | %.1f | %.1f | %.1f | %llu | %.1f | %.1f | %.1f |\n",
                cl->viewpoint, c->maps[cl->map], c->methods[cl->method].label,
                s->gbuffer_render + s->gbuffer_readback, s->truth, (unsigned long long)cl->truth_rays,
                s->fit, s->map_render, s->map_readback, s->method, (unsigned long long)cl->cost.lookups,
                s->contours, s->figures, s->overlay);
    }
    fprintf(f, "\nTotal %.0f ms (scene %.1f ms, BVH %.1f ms).\n", res->ms_total, res->ms_scene, res->ms_bvh);
}

static void write_figures_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    write_csv_header(f);
    for (int i = 0; i < res->ncells; i++)
        write_csv_cell(f, c, res, &res->cells[i]);
}

static void write_costs_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    write_costs_header(f);
    for (int i = 0; i < res->ncells; i++)
        write_costs_cell(f, c, res, &res->cells[i]);
}

static void write_config_yaml(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "# from %s (hash %016llx), git %s\n", c->path, c->hash, res->prov.git_sha);
    sl_config_write(c, f);
}

static void write_run_yaml(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "config: %s\nconfig_hash: %016llx\n", c->path, c->hash);
    sl_provenance_write(&res->prov, f, "");
    fprintf(f, "ms_total: %.1f\n", res->ms_total);
}

/* ---- the run ---- */

struct run_ctx {
    struct sl_gl gl;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gpass;
    struct sl_shadowmap_pass spass;
    struct sl_rt rt;
    struct sl_scene scene;
    uint8_t *state, *band, *rgb;
    struct sl_verdicts vd;
};

static void ctx_free(struct run_ctx *x)
{
    free(x->state);
    free(x->band);
    free(x->rgb);
    free(x->vd.v);
    free(x->vd.how);
    sl_rt_free(&x->rt);
    if (x->gl.ctx) {
        sl_shadowmap_free(&x->spass);
        sl_gbuffer_free(&x->gpass);
        sl_gl_mesh_free(&x->mesh);
        sl_gl_free(&x->gl);
    }
    sl_scene_free(&x->scene);
}

enum sl_err sl_run(const struct sl_config *c, const struct sl_run_opts *o, struct sl_run_result *res,
                   struct sl_diag *d)
{
    memset(res, 0, sizeof *res);
    double t_start = sl_now();
    const char *root = o->out_root ? o->out_root : "results";
    char stage[1100] = "", final[1100] = "", ovdir[1200] = "";
    enum sl_err e = SL_OK;
    if (o->write_files) {
        /* fail on an unwritable output before any GL or Embree work */
        if ((e = sl_mkdirs(root, d)))
            return e;
        snprintf(final, sizeof final, "%s/%s", root, c->name);
        snprintf(stage, sizeof stage, "%s/.%s.partial-%ld", root, c->name, (long)getpid());
        rm_tree(stage);
        if ((e = sl_mkdirs(stage, d)))
            return e;
        snprintf(ovdir, sizeof ovdir, "%s/overlays", stage);
        if (c->overlays && (e = sl_mkdirs(ovdir, d))) {
            rm_tree(stage);
            return e;
        }
        snprintf(res->out_dir, sizeof res->out_dir, "%s", final);
    }

    struct run_ctx x;
    memset(&x, 0, sizeof x);
    double t0 = sl_now();
    if ((e = sl_scene_build(c->scene, &x.scene, d)))
        goto out;
    res->ms_scene = 1e3 * (sl_now() - t0);
    if ((e = sl_gl_init(&x.gl, d)) || (e = sl_gl_mesh_upload(&x.mesh, &x.scene, d)) ||
        (e = sl_gbuffer_init(&x.gpass, &x.scene, d)) || (e = sl_shadowmap_init(&x.spass, d)))
        goto out;
    if ((e = sl_rt_build(&x.rt, &x.scene, c->threads, 1, d)))
        goto out;
    res->ms_bvh = x.rt.ms_build;
    snprintf(res->prov.gl_renderer, sizeof res->prov.gl_renderer, "%s", x.gl.renderer);
    snprintf(res->prov.gl_version, sizeof res->prov.gl_version, "%s", x.gl.version);
    snprintf(res->prov.embree, sizeof res->prov.embree, "%s", x.rt.version);
    res->prov.threads = c->threads;
    sl_provenance_fill(&res->prov);

    int nvp = c->nviewpoints ? c->nviewpoints : x.scene.nvp;
    int vp_index[SL_MAX_VIEWPOINTS];
    for (int i = 0; i < nvp; i++)
        vp_index[i] = c->nviewpoints ? sl_scene_find_viewpoint(&x.scene, c->viewpoints[i]) : i;
    res->ncells = c->nviewports * nvp * c->nmaps * c->nmethods;
    res->cells = sl_calloc((size_t)res->ncells, sizeof *res->cells);
    if (!res->cells) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cell table");
        goto out;
    }
    unsigned needs = 0;
    for (int m = 0; m < c->nmethods; m++)
        needs |= c->methods[m].method->needs(&c->methods[m].params);

    int cell_i = 0;
    for (int vw = 0; vw < c->nviewports && !e; vw++) {
        int W = c->viewport_w[vw], H = c->viewport_h[vw];
        size_t npx = (size_t)W * (size_t)H;
        free(x.state); free(x.band); free(x.rgb); free(x.vd.v); free(x.vd.how);
        x.state = sl_calloc(npx, 1);
        x.band = sl_calloc(npx, 1);
        x.rgb = sl_calloc(npx, 3);
        x.vd.v = sl_calloc(npx, 1);
        x.vd.how = sl_calloc(npx, 1);
        x.vd.w = W;
        x.vd.h = H;
        if (!x.state || !x.band || !x.rgb || !x.vd.v || !x.vd.how) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "per-pixel buffers %dx%d", W, H);
            break;
        }
        for (int vi = 0; vi < nvp && !e; vi++) {
            struct sl_view view;
            struct sl_stage_ms vms = {0};
            if ((e = sl_gbuffer_render(&x.gpass, &x.mesh, &x.scene, vp_index[vi], W, H, &view,
                                       &vms.gbuffer_render, &vms.gbuffer_readback, d)))
                break;
            struct sl_truth_stats ts;
            if ((e = sl_truth_trace(&x.rt, &x.scene, &view, &ts, d))) {
                sl_view_free(&view);
                break;
            }
            vms.truth = ts.ms_trace;
            t0 = sl_now();
            struct sl_light_box box;
            sl_light_fit(&x.scene, &view, &box);
            vms.fit = 1e3 * (sl_now() - t0);
            /* methods get the view without its truth */
            struct sl_view mview = view;
            mview.truth = NULL;
            for (int mp = 0; mp < c->nmaps && !e; mp++) {
                struct sl_light_frame frame;
                memset(&frame, 0, sizeof frame);
                frame.size = c->maps[mp];
                memcpy(frame.dir, x.scene.light_dir, sizeof frame.dir);
                frame.box = box;
                frame.texel_world = fmaxf(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1]) / (float)frame.size;
                frame.depth_range = box.hi[2] - box.lo[2];
                if ((e = sl_shadowmap_render(&x.spass, &x.mesh, &frame, needs, d))) {
                    sl_frame_free(&frame);
                    break;
                }
                for (int m = 0; m < c->nmethods && !e; m++) {
                    const struct sl_config_method *cm = &c->methods[m];
                    struct sl_cell *cell = &res->cells[cell_i++];
                    cell->vp = vp_index[vi];
                    cell->viewport = vw;
                    cell->map = mp;
                    cell->method = m;
                    snprintf(cell->viewpoint, sizeof cell->viewpoint, "%s", x.scene.vp[vp_index[vi]].name);
                    cell->ms = vms;
                    cell->truth_rays = ts.rays;
                    cell->n_pfl = view.n_pfl;
                    cell->n_pnfl = view.n_pnfl;
                    cell->n_background = view.n_background;
                    cell->n_truth_lit = view.n_lit;
                    cell->n_truth_shadow = view.n_shadow;
                    unsigned mneeds = cm->method->needs(&cm->params);
                    for (int l = 0; l < SL_LAYER_COUNT; l++)
                        if (mneeds & SL_NEED(l)) {
                            cell->ms.map_render += frame.layer[l].ms_render;
                            cell->ms.map_readback += frame.layer[l].ms_readback;
                        }
                    struct sl_method_args a = {
                        .scene = &x.scene, .view = &mview, .frame = &frame, .params = &cm->params,
                        .rt = &x.rt, .threads = c->threads,
                    };
                    if ((e = cm->method->run(&a, &x.vd, &cell->cost, d)))
                        break;
                    cell->ms.method = cell->cost.ms_method;
                    t0 = sl_now();
                    for (size_t i = 0; i < npx; i++)
                        x.state[i] = x.vd.v[i];   /* 0 background, else the verdict */
                    /* regions are the increasing contours, then 0 (whole image) */
                    int maxt = c->regions[c->nregions - 2];
                    sl_contour_bands(W, H, x.state, maxt / 2 - 1, x.band);
                    cell->ms.contours = 1e3 * (sl_now() - t0);
                    t0 = sl_now();
                    sl_figures_compute(&view, &x.vd, x.band, c->regions, c->nregions, &cell->fig);
                    cell->ms.figures = 1e3 * (sl_now() - t0);
                    if (o->write_files && c->overlays) {
                        t0 = sl_now();
                        char path[1400];
                        snprintf(path, sizeof path, "%s/%s-%s-%dx%d-%d-%s.png", ovdir, c->scene,
                                 cell->viewpoint, W, H, c->maps[mp], cm->label);
                        sl_overlay_build(&view, x.scene.light_dir, &x.vd, x.band, c->overlay_contour, x.rgb);
                        e = sl_image_write_rgb8(path, W, H, x.rgb, d);
                        cell->ms.overlay = 1e3 * (sl_now() - t0);
                    }
                }
                sl_frame_free(&frame);
            }
            sl_view_free(&view);
        }
    }
    res->ms_total = 1e3 * (sl_now() - t_start);
    if (e || !o->write_files)
        goto out;

    {
        static const struct {
            const char *name;
            void (*write)(FILE *, const struct sl_config *, const struct sl_run_result *);
        } files[] = {
            {"figures.csv", write_figures_csv},
            {"costs.csv", write_costs_csv},
            {"table.md", write_markdown},
            {"config.yaml", write_config_yaml},
            {"run.yaml", write_run_yaml},
        };
        for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
            struct sl_outfile f;
            char path[1300];
            snprintf(path, sizeof path, "%s/%s", stage, files[k].name);
            if ((e = sl_out_open(&f, path, d)))
                goto out;
            files[k].write(f.f, c, res);
            if ((e = sl_out_commit(&f, d)))
                goto out;
        }
    }
    /* swap the finished folder into place */
    {
        char old[1200];
        snprintf(old, sizeof old, "%s/.%s.old-%ld", root, c->name, (long)getpid());
        struct stat st;
        int had = stat(final, &st) == 0;
        if (had && rename(final, old) != 0) {
            e = sl_fail(d, SL_E_OUTPUT, final, 0, NULL, "cannot replace the previous results");
            goto out;
        }
        if (rename(stage, final) != 0) {
            if (had)
                rename(old, final);
            e = sl_fail(d, SL_E_OUTPUT, final, 0, NULL, "cannot move results into place");
            goto out;
        }
        if (had)
            rm_tree(old);
    }
    if (o->table_out) {
        write_markdown(o->table_out, c, res);
        fprintf(o->table_out, "\nwritten to %s/\n", final);
    }
out:
    if (e && stage[0])
        rm_tree(stage);
    ctx_free(&x);
    return e;
}
