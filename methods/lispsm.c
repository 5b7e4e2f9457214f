/*
 * lispsm.c — Light Space Perspective Shadow Maps (Wimmer, Scherzer,
 * Purgathofer 2004): one map whose light frame is a perspective warp in
 * light space, its near distance n_opt = (z_n + sqrt(z_n z_f)) / sin gamma
 * (lightfit.h, sl_light_fit_lispsm), so texels are spent more densely near
 * the viewer; the uniform map where gamma -> 0 (light along the view), as
 * the paper falls back. NSM's lookup and self-shadow policy (front_faces,
 * none or triangle_id: a bias in texels assumes a uniform map). It is
 * zpart's run with one slice and the warp (zpart.c), so the two share
 * every line of the lookup; its frame is rendered by the method, and
 * ms_method includes the fit and the render.
 */
#include "method.h"
#include "zpart.h"

extern const struct sl_method sl_method_nsm;

static unsigned lispsm_needs(const struct sl_method_params *p)
{
    (void)p;
    return 0;   /* renders its own frame */
}

static const struct sl_param lispsm_params[] = {SL_SELF_SHADOW_DECL};

static enum sl_err lispsm_configure(struct sl_method_params *p, struct sl_diag *d)
{
    enum sl_err e = sl_method_nsm.configure(p, d);
    if (e)
        return e;
    int policy = (int)sl_method_param(p, "self_shadow");
    if (policy == SL_SELF_CONSTANT || policy == SL_SELF_SLOPE)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "self_shadow",
                       "lispsm takes self_shadow front_faces, none or triangle_id: a depth bias in texels "
                       "assumes a uniform map");
    return SL_OK;
}

static enum sl_err lispsm_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                              struct sl_diag *d)
{
    return sl_zpart_run_k(a, 1, 1.0, 1, out, c, d);
}

const struct sl_method sl_method_lispsm = {
    .cite = "wimmer2004",
    .name = "lispsm", .display = "LiSPSM", .family = "seed-004",
    .summary = "light space perspective shadow maps (Wimmer et al. 2004), NSM's lookup",
    .lights = SL_LIGHTS_DIRECTIONAL,
    .figures = SL_FIGS_ALIASING,
    SL_METHOD_PARAMS(lispsm_params),
    .needs = lispsm_needs,
    .configure = lispsm_configure,
    .run = lispsm_run,
};
