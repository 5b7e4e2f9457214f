/*
 * selfshadow.h — the self-shadow policies of the depth comparison (nsm and
 * the methods that reuse its lookup: zpart, lispsm, coherence) and the
 * declarations of that comparison's parameters, shared by those methods'
 * parameter lists; the comparison's configure and offset, defined in nsm.c
 * and called by nsm and coherence alike.
 *
 * Owns: nothing. Does not: check a value against its declaration
 * (base/params.c does; sl_self_shadow_configure checks one against another).
 */
#ifndef SL_SELFSHADOW_H
#define SL_SELFSHADOW_H
#include "params.h"
#include "sl_error.h"

struct sl_method_params;
struct sl_method_args;
struct sl_light_frame;

/* Self-shadow policies of the depth comparison (nsm), in the order of the
 * choice `self_shadow` (its value is the index). */
#define SL_SELF_SHADOW(X)                                        \
    X(SL_SELF_NONE,        "none")                               \
    X(SL_SELF_CONSTANT,    "constant")     /* depth bias */      \
    X(SL_SELF_SLOPE,       "slope")        /* slope-scaled */    \
    X(SL_SELF_FRONT_FACES, "front_faces")  /* Moderno 2011 */    \
    X(SL_SELF_TRIANGLE_ID, "triangle_id")  /* Hertel 2009 */
enum sl_self_shadow {
#define SL_SELF_ENUM(id, text) id,
    SL_SELF_SHADOW(SL_SELF_ENUM)
#undef SL_SELF_ENUM
    SL_SELF_COUNT
};
const char *sl_self_shadow_name(enum sl_self_shadow s);

#define SL_SELF_WORD_(id, text) text,
/* The depth comparison's parameters, as nsm declares them; zpart and lispsm
 * list them first in their own declarations (lispsm: the policy alone). */
#define SL_SELF_SHADOW_DECL                                                                              \
    SL_PARAM_CHOICE_DECL("self_shadow", SL_SELF_FRONT_FACES,                                           \
                         "the self-shadow policy: front_faces (Moderno 2011), none, constant, slope, "  \
                         "triangle_id (Hertel 2009)",                                                   \
                         SL_SELF_SHADOW(SL_SELF_WORD_))
#define SL_DEPTH_BIAS_DECLS                                                                              \
    SL_PARAM_FLOAT_DECL("bias", 1, 0, 1000, "texels",                                                  \
                        "self_shadow constant or slope: the depth bias (default 1 under constant, 0 "   \
                        "under slope)"),                                                                \
    SL_PARAM_FLOAT_DECL("slope", 1, 0, 1000, "texels",                                                 \
                        "self_shadow slope: texels of depth per unit of tan(angle)")


/* nsm's checks of the comparison's parameters (bias under constant or
 * slope only, slope under slope only) and their derived defaults (bias 1
 * texel under constant, 0 under slope): every method that declares them
 * configures them so. */
enum sl_err sl_self_shadow_configure(struct sl_method_params *p, struct sl_diag *d);

/* One run's depth comparison: the policy and its offsets, in window depth
 * units for a directional frame (persp: recomputed per pixel). */
struct sl_self_test {
    int policy;
    int persp;
    float bias_texels, slope_texels;   /* as configured */
    float bias, slope;                 /* directional: in window depth units */
    float toward[3];                   /* toward the light (directional) */
};
void sl_self_test_of(const struct sl_method_args *a, struct sl_self_test *t);

/* The offset subtracted from a pixel's window depth z before it is
 * compared with a stored depth: 0 under front_faces, none and triangle_id;
 * the bias, plus the slope term scaled by tan of the normal's angle to the
 * light (clamped at 10), under constant and slope. */
float sl_self_offset(const struct sl_self_test *t, const struct sl_light_frame *f, const float pos[3],
                     const float nrm[3], float z);

#endif
