/*
 * run.c — see run.h.
 *
 * Invariants: cells are visited in sweep order, so the cells sharing a scene,
 * a view and a map size are contiguous and each shared stage is computed once
 * for them (the run context holds the current scene, view and frame); the
 * layers rendered for a (view, map size) are the union of what the methods of
 * the selected cells in that group declare (plan.c); methods see the view
 * without its truth.
 */
#define _XOPEN_SOURCE 700
#include "run.h"
#include <math.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "adjacency.h"
#include "softmap.h"
#include "softtruth.h"
#include "cache.h"
#include "cell.h"
#include "contour.h"
#include "cuberun.h"
#include "package.h"
#include "session.h"
#include "gbuffer.h"
#include "glctx.h"
#include "lightfit.h"
#include "lightframe.h"
#include "motion.h"
#include "motion_run.h"
#include "cellsink.h"
#include "outputs.h"
#include "overlay.h"
#include "shadowmap.h"
#include "scenefile.h"
#include "temporal.h"
#include "truth.h"
#include "util.h"

/* ---- the run ---- */

/* A timed stage's runs (reps.h) and, for a cell's method, each run's
 * stages apart (enum mstage), in the same order: one allocation for the
 * run, as a stage's runs may number SL_MAX_REPS. */
enum mstage { MS_MAP, MS_POST, MS_READBACK, MS_RAYS, MS_STEP, MS_GPU_MAP, MS_GPU_POST, MS_GPU_LOOKUP, MS_COUNT };
struct run_timing {
    struct sl_rep rep;
    double stage[MS_COUNT][SL_MAX_REPS];
};

struct run_ctx {
    struct sl_session *session;   /* the config's scenes (each taken once) and packages (their GL
                                   * objects are released with the context) */
    unsigned looks[2];   /* layers the rest of the view's group reads through lookups (plan.h) */
    struct sl_gl gl;
    struct sl_rt rt;
    /* current scene */
    int scene_i;
    struct sl_scene scene;
    unsigned long long scene_key;      /* truth cache key of the scene */
    struct sl_adjacency adj;
    int have_adj;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gpass;
    struct sl_shadowmap_pass spass;
    /* current view */
    int view_scene, view_vp, view_viewport;
    struct sl_view view;
    struct sl_light_box box;
    struct sl_stage_ms vms;
    int truth_cached;
    uint64_t truth_rays;
    /* current frame */
    int frame_map;
    struct sl_light_frame frame;        /* a point light's: the cube's sums, no arrays (cuberun.h) */
    struct sl_cube cube;                 /* a point light's six frames, per (view, map size) */
    double layer_ms[SL_LAYER_COUNT][3];   /* render time of each layer: median, min, max */
    double layer_gpu[SL_LAYER_COUNT][3];  /* its GPU time (GL_TIME_ELAPSED), the same */
    int layer_runs[SL_LAYER_COUNT];       /* its timed runs (reps.h) */
    struct sl_reps *reps;                 /* how often each timed stage runs; the run's account (res->reps) */
    struct run_timing *tm;                /* the stage under way's runs */
    uint64_t view_bad, layer_bad[SL_LAYER_COUNT];   /* values that are not finite or out of range */
    /* per-pixel scratch */
    int W, H;
    uint8_t *state, *band, *rgb;
    struct sl_verdicts vd;
    struct sl_alias_cache alias;         /* m of the view under the cells' frame (aliasing.h) */
    struct sl_overlay_shade shade;       /* the overlay's lit colours of the view (overlay.h) */
    /* contour_from nsm: NSM's verdicts (front faces culled) and the contour
     * bands drawn from them, once per (view, map size), shared by its cells */
    struct sl_verdicts nvd;
    uint8_t *nsm_band;
    int nsm_map;                         /* map index the bands are for, -1 none */
    double nsm_band_ms;
    int nsm_label;                       /* the config's label the verdicts are the run of, -1 none */
    struct sl_cost nsm_cost;             /* that run's cost */
    /* an area light's scene: its truth is the visible fraction (softtruth.h) */
    int area;
    float *soft_truth, *soft_se;
    /* its layers for soft_mc (softmap.h) and their N-buffer, per (view, map size) */
    struct sl_softmap_pass softpass;
    struct sl_softmap softmap;
    struct sl_softmap_nbuf nbuf;
    int soft_map;                        /* map index the layers are for, -1 none */
    uint8_t *receivers;                  /* per scene range: a pure receiver */
    struct sl_temporal temporal;         /* a path's previous frame, for flicker (temporal.h) */
    struct sl_alt_frames alt;            /* labels' own stabilised light frames (lightframe.h) */
    /* where notes, violations and progress go (the library never prints) */
    void (*on_event)(const struct sl_run_event *ev, void *user);
    void *user;
    const struct sl_cell_sink *sink;     /* where finished cells go; their sheets (cellsink.h) */
    const volatile int *stop;            /* o->stop, for the methods' passes that may run long */
};

static void emit(const struct run_ctx *x, const struct sl_run_event *ev)
{
    if (x->on_event)
        x->on_event(ev, x->user);
}

static void drop_frame(struct run_ctx *x)
{
    sl_frame_free(&x->frame);
    sl_cube_drop(&x->cube);
    x->frame_map = -1;
    x->nsm_map = -1;
}

static void drop_view(struct run_ctx *x)
{
    drop_frame(x);
    sl_light_box_free(&x->box);
    sl_softmap_free(&x->softmap);
    memset(&x->softmap, 0, sizeof x->softmap);
    x->soft_map = -1;
    sl_gbuffer_give_back(&x->gpass, &x->view);   /* its arrays serve the next view */
    sl_alias_cache_free(&x->alias);
    sl_overlay_shade_free(&x->shade);
    x->view_scene = x->view_vp = x->view_viewport = -1;
}

static void drop_scene(struct run_ctx *x)
{
    drop_view(x);
    sl_alt_frames_free(&x->alt);   /* a label's own frame may outlive a view (lightframe.h), not its scene */
    sl_rt_free(&x->rt);
    if (x->have_adj)
        sl_adjacency_free(&x->adj);
    x->have_adj = 0;
    if (x->gl.backend)
        sl_gl_mesh_free(&x->mesh);   /* the G-buffer pass is kept for the next scene */
    sl_scene_free(&x->scene);
    x->scene_i = -1;
#ifdef __GLIBC__
    /* what a scene freed (its BVH, meshes, views) leaves holes in the heaps
     * of the threads that held it: their pages go back before the next
     * scene (issue 20: the Morais study's peak RSS; per view it changed
     * nothing and cost faults) */
    malloc_trim(0);
#endif
}

static void free_nsm(struct run_ctx *x);

static void ctx_free(struct run_ctx *x)
{
    free_nsm(x);
    drop_scene(x);
    free(x->state); free(x->band); free(x->rgb); free(x->vd.v); free(x->vd.how); free(x->vd.base);
    free(x->vd.detail); free(x->vd.tests); free(x->vd.vis); free(x->soft_truth); free(x->soft_se);
    sl_verdicts_drop_frames(&x->vd);
    free(x->receivers);
    free(x->tm);
    sl_temporal_free(&x->temporal);
    sl_softmap_nbuf_free(&x->nbuf);
    if (x->gl.backend) {
        sl_softmap_pass_free(&x->softpass);
        if (x->session)
            sl_packages_release_gl(&x->session->packages);   /* their GL objects, while the context is current */
        sl_shadowmap_free(&x->spass);
        sl_gbuffer_free(&x->gpass);
        sl_gl_free(&x->gl);
    }
}

static enum sl_err ensure_scene(struct run_ctx *x, const struct sl_config *c, int si,
                                struct sl_run_result *res, struct sl_diag *d)
{
    if (x->scene_i == si)
        return SL_OK;
    drop_scene(x);
    double ms_load = 0;
    enum sl_err e = sl_session_take_scene(x->session, c->scenes[si].path, &x->scene, &ms_load, d);
    if (e)
        return e;
    res->ms_scene += ms_load;   /* read by the config's load (session.h), timed there */
    if ((e = sl_gl_mesh_upload(&x->mesh, &x->scene, d)) || (e = sl_gbuffer_init(&x->gpass, &x->scene, d)) ||
        (e = sl_rt_build(&x->rt, &x->scene, c->threads, 1, d)))
        return e;
    res->ms_bvh += x->rt.ms_build;
    res->prov.embree_packets = 1 << x->rt.shift;
    res->passes.scenes++;
    x->area = x->scene.light.type == SL_LIGHT_AREA;
    free(x->receivers);
    x->receivers = sl_calloc((size_t)(x->scene.nranges ? x->scene.nranges : 1), 1);
    if (!x->receivers)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "receiver flags");
    for (int r = 0; r < x->scene.nranges; r++)
        x->receivers[r] = (uint8_t)x->scene.ranges[r].receiver;
    x->scene_key = sl_cache_scene_key(&x->scene, sl_gl_backend_name(x->gl.backend), x->gl.renderer, x->gl.version, &x->rt);
    unsigned needs = 0;
    for (int m = 0; m < c->nmethods; m++)
        if (c->scenes[si].method_mask & (1u << m))
            needs |= c->methods[m].method->needs(&c->methods[m].params);
    if (needs & SL_NEED_ADJACENCY) {
        if ((e = sl_adjacency_build(&x->scene, &x->adj, d)))
            return e;
        x->have_adj = 1;
        if ((e = sl_gl_mesh_upload_adjacency(&x->mesh, &x->scene, &x->adj, d)))
            return e;
        res->passes.adjacency++;
    }
    x->scene_i = si;
    return SL_OK;
}

static void free_nsm(struct run_ctx *x)
{
    free(x->nvd.v); free(x->nvd.how); free(x->nvd.base); free(x->nvd.detail); free(x->nvd.tests);
    free(x->nvd.vis); free(x->nsm_band);
    sl_verdicts_drop_frames(&x->nvd);   /* a point light's faces (cuberun.c, sl_cube_mark) */
    memset(&x->nvd, 0, sizeof x->nvd);
    x->nsm_band = NULL;
    x->nsm_map = -1;
}

static enum sl_err ensure_buffers(struct run_ctx *x, int W, int H, struct sl_diag *d)
{
    if (x->W == W && x->H == H)
        return SL_OK;
    size_t npx = (size_t)W * (size_t)H;
    free(x->state); free(x->band); free(x->rgb); free(x->vd.v); free(x->vd.how); free(x->vd.base);
    free(x->vd.detail); free(x->vd.tests); free(x->vd.vis); free(x->soft_truth); free(x->soft_se);
    sl_verdicts_drop_frames(&x->vd);
    x->vd.vis = sl_calloc(npx, sizeof(float));
    x->soft_truth = sl_calloc(npx, sizeof(float));
    x->soft_se = sl_calloc(npx, sizeof(float));
    x->vd.tests = sl_calloc(npx, 1);
    x->vd.base = sl_calloc(npx, 1);
    x->vd.detail = sl_calloc(npx, 1);
    x->state = sl_calloc(npx, 1);
    x->band = sl_calloc(npx, 1);
    x->rgb = sl_calloc(npx, 3);
    x->vd.v = sl_calloc(npx, 1);
    x->vd.how = sl_calloc(npx, 1);
    x->W = x->vd.w = W;
    x->H = x->vd.h = H;
    free_nsm(x);
    x->nvd.v = sl_calloc(npx, 1);
    x->nvd.how = sl_calloc(npx, 1);
    x->nvd.base = sl_calloc(npx, 1);
    x->nvd.detail = sl_calloc(npx, 1);
    x->nvd.tests = sl_calloc(npx, 1);
    x->nvd.vis = sl_calloc(npx, sizeof(float));
    x->nsm_band = sl_calloc(npx, 1);
    x->nvd.w = W;
    x->nvd.h = H;
    x->nsm_map = -1;
    if (!x->state || !x->band || !x->rgb || !x->vd.v || !x->vd.how || !x->vd.base || !x->vd.detail || !x->vd.tests ||
        !x->vd.vis || !x->soft_truth || !x->soft_se || !x->nvd.v || !x->nvd.how || !x->nvd.base || !x->nvd.detail ||
        !x->nvd.tests || !x->nvd.vis || !x->nsm_band) {
        x->W = x->H = 0;
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "per-pixel buffers %dx%d", W, H);
    }
    return SL_OK;
}

/* The view's truth is in place: its light frustum (lightfit.h), timed (a
 * point light's says what it could not map), its count of bad G-buffer
 * values, and the key it is kept under. */
static enum sl_err view_ready(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                              struct sl_diag *d)
{
    double t0 = sl_now();
    sl_light_fit_mt(&x->scene, &x->view, &x->box, c->threads);
    x->vms.fit = 1e3 * (sl_now() - t0);
    if (x->box.n_outside || x->box.n_unmapped) {
        struct sl_run_event ev = {.kind = SL_EVENT_FRUSTUM_NOTE, .config = c, .scene = x->scene.name,
                                  .viewpoint = c->scenes[k->scene].viewpoints[k->vp], .box = &x->box};
        emit(x, &ev);
    }
    x->view_bad = sl_view_bad(&x->view);
    x->view_scene = k->scene;
    x->view_vp = k->vp;
    x->view_viewport = k->viewport;
    return sl_temporal_view(&x->temporal, k->scene, k->viewport, &x->scene.vp[x->view.vp], &x->view, d);
}

/* The truths of a view under an area light: the visible fraction of the
 * light per pixel from the config's samples and seed, and the hard truth of
 * the point at its centre (one ray per PFL pixel, truth.h), which the
 * hard-shadow methods' figures and exactness are measured against; then the
 * point's perspective frustum (lightfit.h). The soft layers fit their own.
 * Both truths are timed together as the view's truth; the point's adds one
 * ray per pixel to the area's area_samples^2. Both come from the cache
 * (area_key) when it holds them, timed as the read, as a hard truth is. */
static enum sl_err area_view(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                             unsigned long long view_key, const char *cache_dir, struct sl_run_result *res,
                             struct sl_diag *d)
{
    struct sl_rep *rs = &x->tm->rep;
    const int cache = cache_dir && cache_dir[0];
    const unsigned long long key = sl_cache_area_key(view_key, sl_soft_truth_side(c->area_samples), c->seed);
    double t0 = sl_now();
    uint64_t soft_rays = 0;
    enum sl_cache_read got =
        cache ? sl_cache_area_read(cache_dir, key, &x->view, x->soft_truth, x->soft_se, &soft_rays) : SL_CACHE_MISS;
    x->truth_cached = got == SL_CACHE_HIT;
    /* the counts of the computation, not of the cache: the area samples the
     * entry's trace made, and one ray per lit or shadowed pixel of the centre */
    x->truth_rays = soft_rays + x->view.n_lit + x->view.n_shadow;
    res->passes.cache_rejected += got == SL_CACHE_REJECTED;
    if (x->truth_cached) {
        res->passes.truths_cached++;
        res->passes.soft_truths_cached++;
        x->vms.truth[SL_MED] = x->vms.truth[SL_MIN] = x->vms.truth[SL_MAX] = 1e3 * (sl_now() - t0);
    } else {
        struct sl_soft_truth_stats st;
        struct sl_truth_stats ts;
        enum sl_err e = sl_soft_truth(&x->rt, &x->scene, &x->view, c->area_samples, c->seed, x->soft_truth,
                                      x->soft_se, &st, d);
        if (!e)
            e = sl_truth_trace(&x->rt, &x->scene, &x->view, &ts, d);
        if (e)
            return e;
        sl_rep_begin(rs, x->reps, SL_REP_TRUTH, st.ms_trace + ts.ms_trace, NAN);
        while (!e && sl_rep_more(rs)) {
            /* repetitions trace the same rays into the same answer */
            e = sl_soft_truth(&x->rt, &x->scene, &x->view, c->area_samples, c->seed, x->soft_truth, x->soft_se,
                              &st, d);
            if (!e)
                e = sl_truth_trace(&x->rt, &x->scene, &x->view, &ts, d);
            sl_rep_add(rs, st.ms_trace + ts.ms_trace, NAN);
        }
        if (e)
            return e;
        sl_rep_end(rs, x->vms.truth, NULL);
        res->passes.truths_traced++;
        res->passes.soft_truths++;
        x->truth_rays = st.rays + ts.rays;
        if (cache)
            sl_cache_area_write(cache_dir, key, &x->view, x->soft_truth, x->soft_se, st.rays);
    }
    return view_ready(x, c, k, d);
}

static enum sl_err ensure_view(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                               const char *cache_dir, struct sl_run_result *res, struct sl_diag *d)
{
    if (x->view_scene == k->scene && x->view_vp == k->vp && x->view_viewport == k->viewport)
        return SL_OK;
    drop_view(x);
    int W = c->viewport_w[k->viewport], H = c->viewport_h[k->viewport];
    int vp = sl_scene_find_viewpoint(&x->scene, c->scenes[k->scene].viewpoints[k->vp]);
    if (vp < 0)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "viewpoint vanished from the scene");
    sl_scene_use_view_light(&x->scene, vp);   /* a light path's frame moves the light */
    memset(&x->vms, 0, sizeof x->vms);
    struct sl_rep *rs = &x->tm->rep;
    double ms0, gpu0;
    enum sl_err e = sl_gbuffer_render(&x->gpass, &x->mesh, &x->scene, vp, W, H, &x->view, &ms0,
                                      &x->vms.gbuffer_readback, &gpu0, d);
    if (e)
        return e;
    res->passes.gbuffers++;
    sl_rep_begin(rs, x->reps, SL_REP_GBUFFER, ms0, gpu0);
    while (!e && sl_rep_more(rs)) {
        /* the same pass again, timed only: no view made */
        e = sl_gbuffer_render(&x->gpass, &x->mesh, &x->scene, vp, W, H, NULL, &ms0, NULL, &gpu0, d);
        sl_rep_add(rs, ms0, gpu0);
    }
    if (e)
        return e;
    sl_rep_end(rs, x->vms.gbuffer_render, x->vms.gpu_gbuffer);
    unsigned long long key = sl_cache_view_key(x->scene_key, &x->scene.vp[vp], W, H);
    if (x->area)
        return area_view(x, c, k, key, cache_dir, res, d);
    double t0 = sl_now();
    enum sl_cache_read got =
        cache_dir && cache_dir[0] ? sl_cache_truth_read(cache_dir, key, &x->view) : SL_CACHE_MISS;
    x->truth_cached = got == SL_CACHE_HIT;
    /* one ray per lit or shadowed pixel, as the trace counts them */
    x->truth_rays = x->view.n_lit + x->view.n_shadow;
    res->passes.cache_rejected += got == SL_CACHE_REJECTED;
    if (x->truth_cached) {
        res->passes.truths_cached++;
        x->vms.truth[SL_MED] = x->vms.truth[SL_MIN] = x->vms.truth[SL_MAX] = 1e3 * (sl_now() - t0);
    } else {
        struct sl_truth_stats ts;
        if ((e = sl_truth_trace(&x->rt, &x->scene, &x->view, &ts, d)))
            return e;
        sl_rep_begin(rs, x->reps, SL_REP_TRUTH, ts.ms_trace, NAN);
        while (!e && sl_rep_more(rs)) {
            /* repetitions trace the same rays into the same answer */
            e = sl_truth_trace(&x->rt, &x->scene, &x->view, &ts, d);
            sl_rep_add(rs, ts.ms_trace, NAN);
        }
        if (e)
            return e;
        sl_rep_end(rs, x->vms.truth, NULL);
        res->passes.truths_traced++;
        x->truth_rays = ts.rays;
        if (cache_dir && cache_dir[0])
            sl_cache_truth_write(cache_dir, key, &x->view);
    }
    return view_ready(x, c, k, d);
}

static enum sl_err ensure_frame(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                                unsigned needs, unsigned gath, struct sl_run_result *res, struct sl_diag *d)
{
    needs &= (1u << SL_LAYER_COUNT) - 1u;   /* the frame's layers; adjacency is per scene */
    /* lazily: the layers this cell reads (BGSM2 reads BGSM) and the contour's, after giving back
     * those no remaining cell of the group reads: a view holds what its methods read at once */
    unsigned now = c->methods[k->method].method->needs(&c->methods[k->method].params);
    now = needs & (now | SL_NEED(SL_LAYER_DEPTH_ID_BACK) | (now & SL_NEED(SL_LAYER_BGSM2) ? SL_NEED(SL_LAYER_BGSM) : 0));
    for (int l = 0; l < SL_LAYER_COUNT && x->frame_map == k->map; l++)
        if (x->frame.have & ~needs & SL_NEED(l))
            sl_frame_drop_layer(&x->frame, l);
    if (x->frame_map == k->map && (x->frame.have & now) == now)
        return SL_OK;
    if (x->frame_map != k->map) {
        drop_frame(x);
        memset(&x->frame, 0, sizeof x->frame);
        x->frame.pool = &x->spass.pool;   /* arrays reused across layers, frames, views */
        x->frame.pix_pool = &x->spass.pix_pool;
        x->frame.size = c->maps[k->map];
        memcpy(x->frame.dir, x->scene.light_dir, sizeof x->frame.dir);
        x->frame.box = x->box;
        x->frame.texel_world = fmaxf(x->box.hi[0] - x->box.lo[0], x->box.hi[1] - x->box.lo[1]) /
                               (float)x->frame.size;
        x->frame.depth_range = x->box.hi[2] - x->box.lo[2];
        x->frame_map = k->map;
    }
    if (x->scene.light.type == SL_LIGHT_POINT)
        return sl_cube_ensure(&x->cube, &x->spass, &x->mesh, &x->scene, &x->view, k->map, c->maps[k->map], now, needs,
                              &(struct sl_layer_timing){x->reps, x->layer_ms, x->layer_gpu, x->layer_bad,
                                                       res->passes.layers, x->layer_runs, c->threads}, &x->frame, d);
    /* layers every remaining reader reads per pixel (sl_plan_group_at_pixel)
     * are gathered per pixel once drawn, and drawn with the first cell that
     * reads any of them, before the dense ones: their map-sized arrays are
     * then free again for the dense layers, and a view holds the dense
     * layers of one method, not of every method of the group. BGSM stays
     * dense: BGSM2 reads its ids, and BGSM2's readback is the peak anyway. */
    const unsigned gather = gath & ~SL_NEED(SL_LAYER_BGSM) & ~x->frame.have;
    const struct sl_layer_timing t = {x->reps, x->layer_ms, x->layer_gpu, x->layer_bad,
                                     res->passes.layers, x->layer_runs, c->threads};
    enum sl_err e = SL_OK;
    if (now & gather)
        e = sl_frame_render_timed(&x->spass, &x->mesh, &x->frame, gather & ~SL_NEED(SL_LAYER_BGSM2), gather,
                                  &x->view, &t, d);
    if (!e)
        e = sl_frame_render_timed(&x->spass, &x->mesh, &x->frame, now, gather, &x->view, &t, d);
    return e;
}

/* The area light's near and far layers at the cell's map size, and their
 * N-buffer, once per (view, map size) and only when a soft method of the
 * group reads them. */
static enum sl_err ensure_soft(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                               unsigned needs, struct sl_run_result *res, struct sl_diag *d)
{
    if (!(needs & SL_NEED_SOFT) || x->soft_map == k->map)
        return SL_OK;
    if (!x->softpass.prog) {
        enum sl_err e = sl_softmap_init(&x->softpass, d);
        if (e)
            return e;
    }
    sl_softmap_free(&x->softmap);
    memset(&x->softmap, 0, sizeof x->softmap);
    x->soft_map = -1;
    struct sl_softmap_desc sd = {.size = c->maps[k->map], .receiver = x->receivers};
    enum sl_err e = sl_softmap_render(&x->softpass, &x->mesh, &x->scene, &x->view, &sd, &x->softmap, d);
    if (!e)
        e = sl_softmap_nbuf_build(&x->softmap, c->threads, &x->nbuf, d);
    if (e)
        return e;
    res->passes.soft_layers++;
    x->soft_map = k->map;
    return SL_OK;
}

/* sl_method_make_looks for method m on fr, the view's frame or a label's own */
static enum sl_err make_looks(struct run_ctx *x, const struct sl_config *c, const struct sl_method *m,
                              unsigned needs, struct sl_light_frame *fr, unsigned shared, struct sl_diag *d)
{
    /* a point light's methods read the cube's faces, which make none */
    return x->scene.light.type == SL_LIGHT_POINT ? SL_OK
           : sl_method_make_looks(fr, fr == &x->frame, &x->view, m, needs, shared, c->threads, d);
}

/* contour_from nsm: the contours of the current view at the cell's map
 * size, drawn from NSM's image (front faces culled, as Moderno 2011 drew
 * them) whatever the config's methods are, once per (view, map size). The
 * frame must hold the back-face layer. A config with its own such NSM label
 * has this run taken as that label's (run_cell reuses the verdicts: NSM is
 * computed once per (view, map)); otherwise the run is counted apart
 * (passes.contour_runs), not among the sweep's method runs. */
static enum sl_err ensure_contour(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                                  struct sl_run_result *res, struct sl_diag *d)
{
    if (x->nsm_map == k->map)
        return SL_OK;
    const struct sl_method *m = sl_method_find("nsm");
    if (!m)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "contour_from nsm: no nsm method");
    struct sl_method_params p;
    const int label = sl_config_contour_label(c);
    enum sl_err e = SL_OK;
    if (label >= 0) {
        p = c->methods[label].params;
    } else {
        sl_method_params_init(m, &p);   /* its defaults: front_faces */
        if ((e = sl_method_configure(m, &p, d)))
            return e;
    }
    size_t npx = (size_t)x->W * (size_t)x->H;
    /* this run reads the lookups too, besides the group's cells, unless it is the NSM label's */
    if ((e = make_looks(x, c, m, m->needs(&p), &x->frame, x->looks[1] | (label < 0 ? x->looks[0] : 0u), d)))
        return e;
    struct sl_view mview = x->view;
    mview.truth = NULL;
    struct sl_method_args a = {
        .scene = &x->scene, .view = &mview, .frame = &x->frame, .params = &p,
        .rt = &x->rt, .adj = NULL, .threads = c->threads, .seed = c->seed,
    };
    struct sl_cost cost = {0};
    x->nvd.has_base = 0;
    x->nvd.has_detail = 0;
    x->nvd.has_vis = 0;
    memset(x->nvd.tests, 0, npx);
    double t0 = sl_now();
    if ((e = sl_cube_method_run(&x->cube, m, &a, &x->nvd, &cost, d)))
        return e;
    res->passes.contour_runs++;          /* taken back if a cell of `label` reuses it */
    x->nsm_label = label;
    x->nsm_cost = cost;
    for (size_t i = 0; i < npx; i++)
        x->state[i] = x->nvd.v[i];   /* 0 background, else the verdict: as a method's own contour */
    int maxt = c->regions[c->nregions - 2];
    sl_contour_bands_mt(x->W, x->H, x->state, maxt / 2 - 1, x->nsm_band, c->threads);
    x->nsm_band_ms = 1e3 * (sl_now() - t0);
    x->nsm_map = k->map;
    return SL_OK;
}

/* The cell's cost by stages (cell.h, one definition for every method):
 * from its method's runs (rs, each run's stages in st) and the layers it
 * read (already in cell->ms: map_render, gpu_map, map_readback). Each
 * stage is the median of its timed runs; the total's min and max sum the
 * stages' (the method's runs as wholes). ms.method and cost.ms_method
 * become the per-pixel step (lookup and rays) for every method, a
 * package's too. */
static void cell_stages(struct sl_rep *rs, double (*st)[SL_MAX_REPS], struct sl_cell *cell)
{
    struct sl_stage_ms *s = &cell->ms;
    int first, n = sl_rep_timed(rs, &first);
    double whole[3], v[MS_COUNT][3], lookup[SL_MAX_REPS], lk[3];
    for (int k = 0; k < MS_COUNT; k++)
        sl_rep_stats(st[k], first, n, v[k]);
    for (int i = first; i < first + n; i++)
        lookup[i] = st[MS_STEP][i] - st[MS_RAYS][i];
    sl_rep_stats(lookup, first, n, lk);
    s->runs_method = sl_rep_end(rs, whole, NULL);
    memcpy(s->method, v[MS_STEP], sizeof s->method);
    cell->cost.ms_method = v[MS_STEP][SL_MED];
    cell->cost.ms_trace = v[MS_RAYS][SL_MED];
    s->st_map = s->map_render[SL_MED] + v[MS_MAP][SL_MED];
    s->st_post = v[MS_POST][SL_MED];
    s->st_lookup = lk[SL_MED];
    s->st_readback = s->map_readback + v[MS_READBACK][SL_MED];
    s->st_rays = v[MS_RAYS][SL_MED];
    for (int j = 0; j < 3; j++) {
        s->total[j] = s->map_render[j] + s->map_readback + whole[j];
        s->gpu_map[j] += v[MS_GPU_MAP][j];
    }
    s->gpu_post = v[MS_GPU_POST][SL_MED];
    s->gpu_lookup = v[MS_GPU_LOOKUP][SL_MED];
}

static enum sl_err run_cell(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                            struct sl_cell *cell, const char *ovdir, const char *exrdir, const char *visdir,
                            struct sl_run_result *res, struct sl_diag *d)
{
    const struct sl_config_method *cm = &c->methods[k->method];
    int W = c->viewport_w[k->viewport], H = c->viewport_h[k->viewport];
    size_t npx = (size_t)W * (size_t)H;
    cell->key = *k;
    snprintf(cell->scene, sizeof cell->scene, "%s", x->scene.name);
    snprintf(cell->viewpoint, sizeof cell->viewpoint, "%s", c->scenes[k->scene].viewpoints[k->vp]);
    cell->ms = x->vms;
    cell->truth_cached = x->truth_cached;
    cell->truth_rays = x->truth_rays;
    cell->nonfinite = x->view_bad;
    cell->n_pfl = x->view.n_pfl;
    cell->n_pnfl = x->view.n_pnfl;
    cell->n_background = x->view.n_background;
    cell->n_truth_lit = x->view.n_lit;
    cell->n_truth_shadow = x->view.n_shadow;
    cell->n_outside_cone = x->view.n_outside_cone;
    sl_light_heading(&x->scene.light, cell->light, sizeof cell->light);
    unsigned mneeds = cm->method->needs(&cm->params);
    struct sl_light_frame *fr = &x->frame;   /* a label's own stabilised frame, if it asks (lightfit.h) */
    enum sl_err e = cm->frame_fit.fit == SL_FIT_TIGHT ? SL_OK
                    : sl_alt_frame(&x->alt, &x->spass, &x->mesh, &x->scene, &x->view, k->map, c->maps[k->map],
                                   &cm->frame_fit, mneeds, &fr, res->passes.layers, d);
    if (e)
        return e;
    cell->ms.runs_map = 0;   /* the fewest timed runs of a layer it reads (0: none read) */
    for (int l = 0; l < SL_LAYER_COUNT; l++)
        if (mneeds & SL_NEED(l)) {
            if (fr == &x->frame && (!cell->ms.runs_map || x->layer_runs[l] < cell->ms.runs_map))
                cell->ms.runs_map = x->layer_runs[l];
            for (int j = 0; j < 3; j++) {
                cell->ms.map_render[j] += x->layer_ms[l][j];
                cell->ms.gpu_map[j] += x->layer_gpu[l][j];
            }
            cell->nonfinite += x->layer_bad[l];
            cell->ms.map_readback += fr->layer[l].ms_readback;
            cell->gs_prims += fr->layer[l].gs_prims;
            cell->fragments += fr->layer[l].fragments;
        }
    if ((mneeds & SL_NEED_SOFT) && x->soft_map >= 0)
        for (int j = 0; j < 3; j++) {   /* rendered once (ensure_soft): no spread */
            cell->ms.map_render[j] += x->softmap.ms_near + x->softmap.ms_far;
            cell->ms.gpu_map[j] += x->softmap.ms_gpu_near + x->softmap.ms_gpu_far;
        }
    if ((e = make_looks(x, c, cm->method, mneeds, fr, x->looks[1], d)))
        return e;
    /* methods get the view without its truth */
    struct sl_view mview = x->view;
    mview.truth = NULL;
    struct sl_method_args a = {
        .scene = &x->scene, .view = &mview, .frame = fr, .params = &cm->params,
        .rt = &x->rt, .adj = x->have_adj ? &x->adj : NULL, .threads = c->threads,
        .softmap = x->soft_map >= 0 ? &x->softmap : NULL,
        .seed = c->seed, .spass = &x->spass, .mesh = &x->mesh,
        .stop = x->stop, .pass_seconds = c->pass_seconds,
    };
    struct sl_rep *rs = &x->tm->rep;
    double (*st)[SL_MAX_REPS] = x->tm->stage;
    /* contour_from nsm with this label's run already made for the contour:
     * its verdicts are this cell's first run (further repetitions only time) */
    const int reuse = c->contour_from == SL_CONTOUR_NSM && x->nsm_map == k->map && x->nsm_label == (int)k->method &&
                      fr == &x->frame;
    int r = 0;
    do {   /* the real run, then its repetitions (reps.h), timed only */
        struct sl_cost cost = {0};
        res->passes.method_runs++;
        if (reuse && r == 0) {
            memcpy(x->vd.v, x->nvd.v, npx);
            memcpy(x->vd.how, x->nvd.how, npx);
            memcpy(x->vd.base, x->nvd.base, npx);
            memcpy(x->vd.detail, x->nvd.detail, npx);
            memcpy(x->vd.tests, x->nvd.tests, npx);
            x->vd.has_base = x->nvd.has_base;
            x->vd.has_detail = x->nvd.has_detail, x->vd.nframes = 0;   /* NSM's: the cell's frame */
            x->vd.has_vis = 0;
            x->vd.nonfinite = 0;
            res->passes.contour_runs--;
            cost = x->nsm_cost;
            e = sl_cube_mark(&x->cube, &x->vd, d);   /* a point light's faces (cuberun.h) */
        } else {
            x->vd.has_base = x->vd.nframes = 0;   /* nframes: the cell's frame unless the method says */
            x->vd.has_detail = 0;
            x->vd.has_vis = 0;
            x->vd.nonfinite = 0;
            memset(x->vd.tests, 0, npx);
            e = sl_cube_method_run(&x->cube, cm->method, &a, &x->vd, &cost, d);
        }
        if (e)
            break;
        if (r == 0) {
            cell->cost = cost;   /* counters are the same every run */
            sl_rep_begin(rs, x->reps, SL_REP_METHOD, cost.ms_method, NAN);
        } else {
            sl_rep_add(rs, cost.ms_method, NAN);
        }
        /* this run's stages (method.h): its own GL passes, its rays, the rest its lookup */
        st[MS_MAP][r] = cost.ms_map;
        st[MS_POST][r] = cost.ms_post;
        st[MS_READBACK][r] = cost.ms_readback;
        st[MS_RAYS][r] = cost.ms_trace;
        st[MS_STEP][r] = cost.ms_method - cost.ms_map - cost.ms_post - cost.ms_readback;
        st[MS_GPU_MAP][r] = cost.gpu_map;
        st[MS_GPU_POST][r] = cost.gl_passes && cost.ms_post > 0.0 ? cost.gpu_post : NAN;   /* NAN: no post pass */
        st[MS_GPU_LOOKUP][r] = cost.gl_passes ? cost.gpu_lookup : NAN;
        r++;
    } while (sl_rep_more(rs));
    if (e)
        return e;
    cell_stages(rs, st, cell);
    sl_cube_cell_costs(&x->cube, &cell->faces, &cell->ms_face_max);   /* a point light's (cuberun.h) */
    int measured;   /* flicker against the path's previous frame, if any */
    if ((e = sl_temporal_cell(&x->temporal, k->map, k->method, x->vd.v, &measured, &cell->flicker,
                              &cell->flicker_compared, &cell->ms.flicker, d)))
        return e;

    char ovpath[1600] = "", exrpath[1400] = "", vispath[1400] = "";
    if (ovdir) {
        char name[400];
        sl_out_overlay_name(c, cell, name, sizeof name);
        snprintf(ovpath, sizeof ovpath, "%s/%s", ovdir, name);
    }
    if (exrdir) {
        char name[400];
        sl_out_exr_name(c, cell, name, sizeof name);
        snprintf(exrpath, sizeof exrpath, "%s/%s", exrdir, name);
    }
    if (visdir) {
        char name[400];
        sl_out_visibility_name(c, cell, name, sizeof name);
        snprintf(vispath, sizeof vispath, "%s/%s", visdir, name);
    }
    struct sl_cell_inputs in = {
        .method = cm->method, .view = &x->view, .frame = fr, .light_dir = x->scene.light_dir, .threads = c->threads,
        .light_pos = x->scene.light.type != SL_LIGHT_DIRECTIONAL ? x->scene.light.pos : NULL,
        .sheets = sl_sink_sheets(x->sink),   /* the sheet drawn into its slot, written off the cell's path */
        .regions = c->regions, .nregions = c->nregions, .overlay_contour = c->overlay_contour,
        .soft_truth = x->area ? x->soft_truth : NULL, .soft_se = x->area ? x->soft_se : NULL,
        .state = x->state, .band = x->band, .rgb = x->rgb, .params = &cm->params,
        .shared_band = c->contour_from == SL_CONTOUR_NSM ? x->nsm_band : NULL, .shared_band_ms = x->nsm_band_ms,
        .overlay_path = ovdir ? ovpath : NULL, .exr_path = exrdir ? exrpath : NULL, .label = cm->label,
        .scene = &x->scene,
        .visibility_path = visdir ? vispath : NULL,
        .alias_cache = &x->alias, .aliasing = c->aliasing,
        .overlay_shade = &x->shade,
    };
    return sl_cell_score(&in, &x->vd, cell, d);
}

/* skip[idx] for the cells of [first, last) a resumed run skips: a cell st
 * (or also) holds whose files the config asks for are where that store's
 * results folder keeps them. This run's: its results folder and dead runs'
 * staging folders (what sl_out_stage_finish carries). also's (the main
 * store of run --jobs): <its folder>/<name>, where the merge gathers them. */
static enum sl_err resume_skips(const struct sl_config *c, const struct sl_run_opts *o, const struct sl_out_dirs *dirs,
                                struct sl_store *st, struct sl_store *also, int first, int last, uint8_t *skip,
                                struct sl_diag *d)
{
    const int files = o->write_files && (c->overlays || c->exr || c->visibility);
    struct sl_out_kept own = {0}, gath = {0};
    enum sl_err e = SL_OK;
    if (files && !(e = sl_out_kept_find(c, dirs->root, dirs->final, dirs->stage, &own, d)) && also) {
        char gathered[1300];
        const char *slash = strrchr(o->stored_in, '/');
        if (slash)
            snprintf(gathered, sizeof gathered, "%.*s/%s", (int)(slash - o->stored_in), o->stored_in, c->name);
        else
            snprintf(gathered, sizeof gathered, "%s", c->name);
        e = sl_out_kept_find(c, NULL, gathered, NULL, &gath, d);
    }
    for (int idx = first; idx < last && !e; idx++) {
        struct sl_cell_key k;
        sl_plan_cell(c, idx, &k);
        skip[idx] = (uint8_t)((sl_out_stored(c, &k, st) && (!files || sl_out_kept_whole(c, &k, &own, st))) ||
                              (also && sl_out_stored(c, &k, also) && (!files || sl_out_kept_whole(c, &k, &gath, also))));
    }
    sl_out_kept_free(&own);
    sl_out_kept_free(&gath);
    return e;
}

/* The sweep index of the cell of idx's key on the frame before idx's in its
 * path, -1 when idx is no frame of a path or its path's first. */
static int prev_frame_cell(const struct sl_config *c, int idx)
{
    struct sl_cell_key k;
    sl_plan_cell(c, idx, &k);
    const struct sl_config_scene *cs = &c->scenes[k.scene];
    char path[64], other[64];
    int f = sl_motion_frame_of(cs->viewpoints[k.vp], path, sizeof path);
    if (f <= 0)
        return -1;
    for (int v = cs->nnamed; v < cs->nviewpoints; v++)
        if (sl_motion_frame_of(cs->viewpoints[v], other, sizeof other) == f - 1 && strcmp(other, path) == 0) {
            k.vp = v;
            return sl_plan_index(c, &k);
        }
    return -1;
}

/* Flicker of a path's frame is counted against the frame before it
 * (temporal.h): its verdicts must be in this process when the frame is
 * scored, whoever computed and stored that frame (a --cells slice or a
 * --jobs worker starting mid-path, a resume after a kill). So a computed
 * frame whose previous frame this run does not compute gets that frame
 * computed first as a warm-up cell: scored for its verdicts only, neither
 * stored nor written nor counted. Recomputing it gives the verdicts the run
 * that stored it had (a cell's verdicts depend on its key and config only),
 * so the stored flicker counts are the same however the sweep is split or
 * resumed. The cost: one frame's cells per slice start or resume point, of
 * the labels and map sizes computed after it.
 * warm[i] for such cells (indexed by cell); off[i] for every cell of
 * [*lo, last) this run does not score (skipped or outside the slice, not a
 * warm-up), which the group planner reads; *lo: the first cell scored. */
static void warm_up_cells(const struct sl_config *c, int first, int last, const uint8_t *skip, uint8_t *warm,
                          uint8_t *off, int *lo)
{
    *lo = first;
    for (int i = first; i < last; i++) {
        if (skip && skip[i])
            continue;
        int p = prev_frame_cell(c, i);
        if (p >= 0 && (p < first || (skip && skip[p]))) {
            warm[p] = 1;
            if (p < *lo)
                *lo = p;
        }
    }
    for (int i = *lo; i < last; i++)
        off[i] = (uint8_t)(!warm[i] && (i < first || (skip && skip[i])));
}

enum sl_err sl_run(const struct sl_config *c, const struct sl_run_opts *o, struct sl_run_result *res,
                   struct sl_diag *d)
{
    memset(res, 0, sizeof *res);
    double t_start = sl_now();
    const char *root = o->out_root ? o->out_root : "results";
    int total = sl_plan_count(c);
    int first = o->first > 0 ? o->first : 0;
    int last = o->last > 0 ? o->last : total;
    if (first >= total || last > total || first >= last)
        return sl_fail(d, SL_E_USAGE, c->path, 0, "--cells", "cells %d:%d outside the sweep of %d cells",
                       first, last, total);
    struct sl_cell_sink sink;
    memset(&sink, 0, sizeof sink);
    sink.config = c;
    sink.write_files = o->write_files;
    struct sl_out_dirs *const dirs = &sink.dirs;
    char *const store_path = sink.store_path;
    char cache[1100] = "";
    if (o->store)
        snprintf(store_path, sizeof sink.store_path, "%s", o->store);
    else if (c->store[0])
        snprintf(store_path, sizeof sink.store_path, "%s/%s", root, c->store);   /* under --out (config.c) */
    else if (o->write_files)
        snprintf(store_path, sizeof sink.store_path, "%s/shadowlab.db", root);
    if (o->cache_dir)
        snprintf(cache, sizeof cache, "%s", o->cache_dir);
    else if (o->write_files)
        snprintf(cache, sizeof cache, "%s/cache", root);
    if (o->resume && !store_path[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--resume", "--resume needs a results store");

    /* a bad SHADOWLAB_EMBREE_CONFIG is refused before anything is written */
    enum sl_err e = sl_rt_check_env(d);
    if (e)
        return e;
    /* what the run names itself under --out is never a symbolic link (what
     * --db and --cache name is the caller's choice) */
    if (!o->store && store_path[0] && (e = sl_out_no_store_link(store_path, d)))
        return e;
    if (!o->cache_dir && cache[0] && (e = sl_out_no_link(cache, d)))
        return e;
    if (o->write_files) {
        /* fail on an unwritable output before any GL or Embree work */
        if ((e = sl_mkdirs(root, d)))
            return e;
        if (!o->store && strchr(c->store, '/')) {   /* store: sub/x.db: its folder under --out */
            char dir[1100];
            sl_path_dir(store_path, dir, sizeof dir);
            if ((e = sl_mkdirs(dir, d)))
                return e;
        }
        if ((e = sl_out_stage_begin(c, root, dirs, d)))
            return e;
        snprintf(res->out_dir, sizeof res->out_dir, "%s", dirs->final);
    }
    if (cache[0] && sl_mkdirs(cache, NULL) != SL_OK)
        cache[0] = '\0';   /* no cache is only slower */

    struct run_ctx x;
    memset(&x, 0, sizeof x);
    x.session = c->session;
    x.stop = o->stop;
    x.scene_i = x.view_scene = x.view_vp = x.view_viewport = x.frame_map = x.soft_map = x.nsm_map = x.nsm_label = -1;
    x.on_event = o->on_event;
    x.user = o->user;
    x.sink = &sink;
    sl_reps_init(&res->reps, c->rep_mode, c->warmup, c->runs, c->rep_spread, c->rep_budget_ms, c->rep_share);
    res->reps.t0 = t_start;
    x.reps = &res->reps;
    struct sl_store *also = NULL;
    uint8_t *skip = NULL, *warm = NULL, *off = NULL;
    struct sl_cell *wcell = NULL;   /* a warm-up cell's (warm_up_cells) */
    if (!(x.tm = malloc(sizeof *x.tm))) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "stage timings");
        goto out;
    }
    if (o->write_files && c->overlays && !o->overlay_inline && (e = sl_sink_open_overlays(&sink, d)))
        goto out;
    if ((e = sl_gl_open(&x.gl, &(struct sl_gl_desc){.backend = c->gl}, d)) || (e = sl_shadowmap_init(&x.spass, d)))
        goto out;
    /* technique packages' shaders compiled before the first cell: a GLSL
     * error stops the run with nothing written (package.h) */
    for (int m = 0; m < c->nmethods && !e; m++)
        e = sl_package_prepare(c->methods[m].method, d);
    /* and their maps within this GL's texture size at every map size a
     * scene runs them at, before any truth is traced (validate checked
     * the harness's own limit) */
    for (int s = 0; s < c->nscenes && !e; s++)
        for (int k = 0; k < c->nmaps && !e; k++)
            for (int m = 0; m < c->nmethods && !e; m++)
                if ((c->scenes[s].map_mask & (1u << k)) && (c->scenes[s].method_mask & (1u << m)))
                    e = sl_package_fits(c->methods[m].method, &c->methods[m].params, c->maps[k], d);
    if (e)
        goto out;
    snprintf(res->prov.gl_renderer, sizeof res->prov.gl_renderer, "%s", x.gl.renderer);
    snprintf(res->prov.gl_version, sizeof res->prov.gl_version, "%s", x.gl.version);
    sl_gl_describe(&x.gl, res->prov.gl_backend, sizeof res->prov.gl_backend);
    snprintf(res->prov.embree, sizeof res->prov.embree, "%d.%d.%d", RTC_VERSION_MAJOR, RTC_VERSION_MINOR,
             RTC_VERSION_PATCH);
    res->prov.threads = c->threads;
    sl_provenance_fill(&res->prov);
    if (store_path[0]) {
        if ((e = sl_sink_open_store(&sink, &res->prov, d)))
            goto out;
        snprintf(res->store_path, sizeof res->store_path, "%s", store_path);
    }

    res->cells = sl_calloc((size_t)(last - first), sizeof *res->cells);
    if (!res->cells) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cell table");
        goto out;
    }
    /* the cells a resumed run skips, decided once: held by its store, or by
     * the store it was pointed at besides (a --jobs worker: the main one),
     * with their files (overlay, EXR) where the store's results folder keeps
     * them; a held cell whose files are lost is computed again (its row is
     * replaced, its files written again) */
    if (o->resume) {
        if (!(skip = sl_calloc((size_t)total, 1))) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cells to skip");
            goto out;
        }
        if (o->stored_in && o->stored_in[0] && (e = sl_store_open_existing(o->stored_in, &also, d)))
            goto out;
        if ((e = resume_skips(c, o, dirs, sink.st, also, first, last, skip, d)))
            goto out;
        sl_store_close(also);
        also = NULL;
    }
    if (!(warm = sl_calloc((size_t)total, 1)) || !(off = sl_calloc((size_t)total, 1)) ||
        !(wcell = sl_calloc(1, sizeof *wcell))) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "warm-up cells");
        goto out;
    }
    int lo = first;
    if (sl_motion_config_has_paths(c))
        warm_up_cells(c, first, last, skip, warm, off, &lo);
    else if (skip)
        memcpy(off + first, skip + first, (size_t)(last - first));
    for (int idx = lo; idx < last && !e; idx++) {
        if (o->stop && *o->stop) {
            res->interrupted = 1;
            break;
        }
        struct sl_cell_key k;
        sl_plan_cell(c, idx, &k);
        if (off[idx]) {
            res->skipped += idx >= first;
            continue;
        }
        if ((e = ensure_scene(&x, c, k.scene, res, d)) ||
            (e = ensure_buffers(&x, c->viewport_w[k.viewport], c->viewport_h[k.viewport], d)) ||
            (e = ensure_view(&x, c, &k, cache, res, d)))
            break;
        /* contour_from nsm: a hard method's contours come from NSM's image,
         * which reads the back-face layer */
        const int nsm_contour = c->contour_from == SL_CONTOUR_NSM &&
                                !(c->methods[k.method].method->lights & SL_LIGHTS_AREA);
        const unsigned needs = sl_plan_group_needs(c, idx, last, off) |
                               (nsm_contour && x.nsm_map != k.map ? SL_NEED(SL_LAYER_DEPTH_ID_BACK) : 0u);
        const unsigned at_pixel = sl_plan_group_at_pixel(c, idx, last, off);
        sl_plan_group_looks(c, idx, last, off, x.looks);
        if ((e = ensure_frame(&x, c, &k, needs, at_pixel, res, d)) || (x.area && (e = ensure_soft(&x, c, &k, needs, res, d))) ||
            (nsm_contour && (e = ensure_contour(&x, c, &k, res, d))))
            break;
        if (warm[idx]) {   /* its verdicts for the next frame's flicker, nothing else */
            memset(wcell, 0, sizeof *wcell);
            wcell->index = idx;
            e = run_cell(&x, c, &k, wcell, NULL, NULL, NULL, res, d);
            res->warmed += !e;
            res->skipped += idx >= first;   /* in the slice: a stored cell (--resume) */
            continue;
        }
        struct sl_cell *cell = &res->cells[res->ncells];
        cell->index = idx;
        if ((e = run_cell(&x, c, &k, cell, o->write_files && c->overlays ? dirs->overlays : NULL,
                          o->write_files && c->exr ? dirs->exr : NULL,
                          o->write_files && c->visibility ? dirs->visibility : NULL, res, d)))
            break;
        if (cell->violations) {
            struct sl_run_event ev = {.kind = SL_EVENT_VIOLATIONS, .config = c, .cell = cell};
            emit(&x, &ev);
        }
        if (cell->nonfinite) {
            struct sl_run_event ev = {.kind = SL_EVENT_NONFINITE, .config = c, .cell = cell};
            emit(&x, &ev);
        }
        /* a stored cell is a whole one (--resume skips it): its sheet is on
         * disk before its row, or a kill between the two loses the sheet */
        if ((e = sl_sink_put(&sink, cell, d)))
            break;
        res->ncells++;
        struct sl_run_event ev = {.kind = SL_EVENT_PROGRESS, .config = c, .cell = cell,
                                  .done = res->ncells + res->skipped, .total = last - first,
                                  .elapsed_s = sl_now() - t_start};
        emit(&x, &ev);
    }
    if (e == SL_E_STOPPED) {   /* a signal during a method's long pass: that cell is dropped whole */
        e = SL_OK;
        res->interrupted = 1;
    }
    if (!e)   /* every sheet in the staging folder before it is renamed (a write error fails the run) */
        e = sl_sink_drain(&sink, d);
    res->ms_total = 1e3 * (sl_now() - t_start);
    if (!e)
        e = sl_sink_finish(&sink, res, o->resume, o->table_out, d);
out:
    sl_store_close(also);
    sl_sink_close(&sink, res, e != SL_OK);
    free(skip);
    free(warm);
    free(off);
    free(wcell);
    ctx_free(&x);
    return e;
}
