/*
 * knobs.h — the parameters a labelled method entry of a config may give
 * (SL_KNOBS, the only place a knob is declared) and the self-shadow
 * policies, apart from the plugin face (method.h), so a config holds a
 * label's parameters without the methods' types.
 *
 * Owns: nothing. Does not: check a value (each method's configure does).
 */
#ifndef SL_KNOBS_H
#define SL_KNOBS_H
#include "technique.h"

/* Self-shadow policies of the depth comparison (nsm). */
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
int         sl_self_shadow_parse(const char *name);   /* -1 if unknown */

/*
 * Method knobs: the keys a labelled method entry of a config may give, one
 * line each; the only place a knob is declared. From this list come the
 * SL_PARAM_* bits and the fields of struct sl_method_params here, and in
 * config.c a method entry's cyaml schema, the copy into the params, the
 * names in messages and the text of the filled-in config.
 *   X(ID, bit, name, type, kind, a, b, doc)
 * ID = 1 << bit, the knob's bit in `set` and params_ok; name: the config
 * key and the field; type: the field's C type; kind: what a config may
 * write (libcyaml's check, then config.c's) and how the filled-in config
 * writes it back:
 *   UINT    a non-negative integer                       "%d"
 *   FLOAT   a number                                     "%g"
 *   BOOL    true or false                                true, false
 *   WORDS   the word a (field 0) or the word b (1)       a, b
 *   POLICY  a self-shadow policy (SL_SELF_SHADOW above)  its name
 * a and b: a WORDS knob's words, 0 for the other kinds. A value's range
 * is its method's to check (configure; doc says what the methods accept):
 * the kind is the same for every method.
 */
#define SL_KNOBS(X)                                                                                       \
    X(SL_PARAM_SELF_SHADOW, 0, self_shadow, int,   POLICY, 0, 0,                                          \
      "nsm: the self-shadow policy: front_faces (default; Moderno 2011), none, constant, slope, triangle_id (Hertel 2009)")                             \
    X(SL_PARAM_BIAS,        1, bias,        float, FLOAT,  0, 0,                                          \
      "nsm with self_shadow constant or slope: depth bias in texels, 0..1000")                           \
    X(SL_PARAM_SLOPE,       2, slope,       float, FLOAT,  0, 0,                                          \
      "nsm with self_shadow slope: texels of depth per unit of tan(angle), 0..1000")                     \
    X(SL_PARAM_TEXELS,      3, texels,      int,   UINT,   0, 0,                                          \
      "coherence, neighbours: texels tested, 4 or 9")                                                    \
    X(SL_PARAM_LEVEL,       4, level,       int,   UINT,   0, 0,                                          \
      "adjacency: 1 (edge) or 2 (vertex)")                                                               \
    X(SL_PARAM_FINISH,      5, finish,      int,   WORDS,  "trace", "lit",                                \
      "chain: trace (default: the pixels left are traced) or lit (they are left lit)")                                                \
    X(SL_PARAM_GRID,        6, grid,        int,   UINT,   0, 0,                                          \
      "soft_mc: rays per pixel = grid x grid (jittered points on the light), 1..16")                     \
    X(SL_PARAM_SEARCH,      7, search,      int,   WORDS,  "linear", "hierarchical",                      \
      "soft_mc: linear (+ binary refinement) or hierarchical (N-buffer)")                                \
    X(SL_PARAM_LAYERS,      8, layers,      int,   UINT,   0, 0,                                          \
      "soft_mc: 1 (near only), 2 (near and far) or 3 (and the camera's depth)")                          \
    X(SL_PARAM_BLUR,        9, blur,        int,   BOOL,   0, 0,                                          \
      "soft_mc: true: the depth-sensitive screen-space blur; false: none")                                        \
    X(SL_PARAM_PARTITIONS, 10, partitions,  int,   UINT,   0, 0,                                          \
      "zpart: shadow maps over the view's depth slices, 1..8")                                           \
    X(SL_PARAM_LAMBDA,     11, lambda,      float, FLOAT,  0, 0,                                          \
      "zpart: split planes, 0 uniform .. 1 logarithmic (seed 004 eq. 62)")                             \
    X(SL_PARAM_WARP,       12, warp,        int,   WORDS,  "uniform", "lispsm",                           \
      "zpart: each slice's map uniform (orthographic) or lispsm (Wimmer et al. 2004)")

enum sl_param {
#define SL_KNOB_BIT(id, bit, ...) id = 1 << (bit),
    SL_KNOBS(SL_KNOB_BIT)
#undef SL_KNOB_BIT
};
/* the bits are 0 .. n-1, each once: `set` and params_ok stay small masks */
#define SL_KNOB_OR(id, ...) | id
#define SL_KNOB_ONE(...) + 1
_Static_assert((0 SL_KNOBS(SL_KNOB_OR)) == (1 << (0 SL_KNOBS(SL_KNOB_ONE))) - 1,
               "SL_KNOBS: bits 0 .. n-1, each once");
#undef SL_KNOB_OR
#undef SL_KNOB_ONE

/*
 * Parameters of one labelled method entry. Zero means "the method's default"
 * (its configure fills them in); `set` has a bit per key the config gave,
 * so a method can reject keys it does not read.
 */
struct sl_method_params {
    unsigned set;   /* SL_PARAM_* */
#define SL_KNOB_FIELD(id, bit, name, type, ...) type name;
    SL_KNOBS(SL_KNOB_FIELD)
#undef SL_KNOB_FIELD
    /* A technique package's method (methods/package.h): the package and
     * its parameters' values (every one set: the config fills in the
     * defaults); NULL and empty for a C method. */
    const struct sl_technique *tech;
    struct sl_tech_values      pkg;
};

#endif
