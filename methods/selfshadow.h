/*
 * selfshadow.h — the self-shadow policies of the depth comparison (nsm and
 * the methods that reuse its lookup: zpart, lispsm) and the declarations of
 * that comparison's parameters, shared by those methods' parameter lists.
 *
 * Owns: nothing. Does not: check a value (base/params.c checks each against
 * its declaration; nsm's configure checks one against another).
 */
#ifndef SL_SELFSHADOW_H
#define SL_SELFSHADOW_H
#include "params.h"

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

#endif
