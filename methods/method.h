/*
 * method.h — the plugin face of a shadow method.
 *
 * A method reads the view (G-buffer: positions, normals, triangle ids, and
 * which pixels are PnFL/background — never the truth) and the light frame
 * layers it asked for in `needs`, and writes one verdict per pixel with how it
 * was decided, plus its cost counters. It never renders what the frame
 * builder renders, never talks to the store, returns an error id, never exits.
 *
 * Methods are const values in the plain table of registry.c; adding one is
 * its own file in methods/ (CMake picks it up) and one line there
 * (doc/adding-a-method.md walks through a 3x3 PCF method).
 *
 * The face. struct sl_method has a core every method fills (name, summary,
 * exact, lights, params, needs, run; configure may be NULL) and an
 * optional fast path (struct sl_method_fast, zero: none) that only lets the
 * driver hand the same layers more cheaply. A method that leaves the fast
 * path zero gets every layer dense and computes every lookup itself, and
 * its verdicts are the same; the driver reads the fast path through
 * sl_method_at_pixel/_looks/_look_parts below and nowhere else.
 *
 * Rules a method author needs, all in this header and frame.h:
 * - Layers arrive dense (f->layer[l].depth/id indexed by texel, S x S) unless
 *   the method lists the layer in fast.at_pixel and every method of the
 *   cell's group that needs it does too: then the driver may gather it
 *   (sl_frame_gather), indexed by pixel, f->layer[l].per_pixel set. A method
 *   that lists a layer in at_pixel reads it only at each decided pixel's
 *   own texel and always through sl_layer_at(L, k, i) (frame.h), which
 *   serves both forms; one that reads a neighbour's texel leaves at_pixel 0.
 * - A lookup may reach SL_LOOK_REACH (frame.h: 1) texels beyond the
 *   receiver's own texel, a 3x3 neighbourhood, and no further: under a
 *   point light each cube face is rendered with a guard band of
 *   SL_GUARD_TEXELS (frame.h) around its receivers, sized for that reach,
 *   so such a lookup never reads a border, a clamp or another face's map
 *   (cube.h). A wider footprint needs SL_LOOK_REACH raised first.
 * - Parameters are declared, one line each, in the method's `params`
 *   (base/params.h: name, type, default, range or choices, doc, unit). A
 *   config's values arrive checked against them, the rest at their
 *   defaults; the method reads each by name (sl_method_param). configure
 *   (optional) checks what one parameter says of another, derives a default
 *   that depends on another (sl_params_derive) and marks the ones that do
 *   not apply to the values given (sl_params_off: nsm's bias under
 *   front_faces), which a config may then not give.
 * - Costs (struct sl_cost) are machine-independent counts beside the time:
 *   `lookups` one per shadow-map texel read (a 3x3 PCF is 9 a pixel),
 *   `rays` one per ray given to Embree (sl_method_trace_left counts its
 *   own), `tri_tests` one per ray-triangle test outside Embree; ms_method
 *   all its run took, its ray step (ms_trace) and any GL pass of its own
 *   (ms_map, ms_post, ms_readback) included. Add to them:
 *   the driver zeroes them and sums a cube's faces.
 */
#ifndef SL_METHOD_H
#define SL_METHOD_H
#include <stdint.h>
#include "frame.h"
#include "methodparams.h"
#include "selfshadow.h"
#include "scene.h"
#include "sl_error.h"
#include "view.h"

struct sl_rt;
struct sl_adjacency;
struct sl_softmap;
struct sl_shadowmap_pass;
struct sl_gl_mesh;

/* Beyond the frame layers (SL_NEED(layer) bits of frame.h), a method may need
 * the scene's edge and vertex adjacency, built once per scene on demand. */
#define SL_NEED_ADJACENCY (1u << 16)
/* The near and far depth layers of an area light and their N-buffer
 * (softmap.h; Curtis 2009). */
#define SL_NEED_SOFT      (1u << 17)
/* Maps of its own, rendered over the cell's light frame (a technique
 * package: render/techpass.h): no layer of the driver's, yet a point
 * light's cube runs it per face (cuberun.h) as it runs a method reading
 * layers. */
#define SL_NEED_OWN_MAPS  (1u << 18)

enum sl_verdict {
    SL_V_NONE      = 0,   /* background */
    SL_V_LIT       = 1,
    SL_V_SHADOW    = 2,
    SL_V_UNCERTAIN = 3,   /* left for a ray tracer */
};

#define SL_HOWS(X)                                     \
    X(SL_HOW_NONE,     "none")      /* background */   \
    X(SL_HOW_PNFL,     "pnfl")      /* faces away */   \
    X(SL_HOW_MAP,      "map")                          \
    X(SL_HOW_HINT,     "hint")                         \
    X(SL_HOW_CONFIRM,  "confirm")                      \
    X(SL_HOW_CONFIRM_ADJ, "confirm_adj") /* the chain's adjacency step */ \
    X(SL_HOW_CORRECT,  "correct")                      \
    X(SL_HOW_TRACED,   "traced")                       \
    X(SL_HOW_FALLBACK, "fallback")
enum sl_how {
#define SL_HOW_ENUM(id, text) id,
    SL_HOWS(SL_HOW_ENUM)
#undef SL_HOW_ENUM
    SL_HOW_COUNT
};

struct sl_verdicts {
    int      w, h;
    uint8_t *v;      /* enum sl_verdict */
    uint8_t *how;    /* enum sl_how */
    uint8_t *base;   /* the verdict of the method this one refines (NSM), when has_base */
    int      has_base;
    uint8_t *detail; /* coherence: how many of the texels tested say shadow, when has_detail */
    int      has_detail;
    uint8_t *tests;  /* ray-triangle tests spent on each pixel (saturating at 255), zeroed before a run */
    float   *vis;    /* soft methods (area lights): the visible fraction of the light per pixel, 0..1 */
    int      has_vis; /* a hard method wrote a fractional visibility into vis (a technique package):
                       * scored as it is, not from its verdicts; zeroed before a run.
                       * A pixel whose visibility is not finite holds NaN there and
                       * the verdict SL_V_UNCERTAIN: counted, never scored as a shadow */
    uint64_t nonfinite; /* values the method read that are not finite, beyond the driver's
                         * layers (a package's map texels); zeroed before a run */
    /* A method that looks up light frames of its own (zpart, lispsm: fitted
     * and rendered by the method through a->spass) hands them to scoring
     * here: pixel i was served by frames[slice[i]] (slice NULL: frames[0];
     * 255: by none). nframes = 0, as the driver sets it before every run:
     * the cell's frame served every pixel. The frames (nown allocated) and
     * slice are the verdicts' own: sl_verdicts_drop_frames frees them; a
     * frame's layers may be gone (have = 0): scoring reads its box and size. */
    struct sl_light_frame *frames;
    int      nframes, nown;
    uint8_t *slice;
};
void sl_verdicts_drop_frames(struct sl_verdicts *vd);

/* Machine-independent counts beside wall time. */
struct sl_cost {
    double   ms_method;     /* all the method's run took (its own GL passes and its ray step included) */
    double   ms_trace;      /* of which: the ray step */
    /* of which: the GL passes of a method rendering maps of its own (a
     * technique package, render/techpass.h; 0 for a method reading the
     * driver's layers): the map pass, the post passes (blur, mipmaps), the
     * readback of its visibility, and gl_passes set; their GPU times
     * (GL_TIME_ELAPSED) beside, with its lookup pass's. The cell's stages
     * (cellcols.h) are made from these: lookup = ms_method - ms_map - ms_post
     * - ms_readback - ms_trace. */
    double   ms_map, ms_post, ms_readback;
    double   gpu_map, gpu_post, gpu_lookup;
    int      gl_passes;
    double   ms_step[4];    /* a chain's steps (coherence, neighbours, adjacency, the rest) */
    uint64_t lookups;       /* shadow-map texel reads */
    uint64_t rays;          /* shadow rays handed to Embree */
    uint64_t tri_tests;     /* ray-triangle tests outside Embree */
};

struct sl_method_args {
    const struct sl_scene         *scene;
    const struct sl_view          *view;     /* truth field must not be read */
    const struct sl_light_frame   *frame;
    const struct sl_method_params *params;
    const struct sl_rt            *rt;       /* for methods that trace */
    const struct sl_adjacency     *adj;      /* when needs has SL_NEED_ADJACENCY, else NULL */
    const struct sl_softmap       *softmap;  /* when needs has SL_NEED_SOFT: the area light's layers,
                                              * their N-buffer built (softmap->nbuf) */
    uint32_t                       seed;     /* the config's seed, for methods that sample */
    /* the shadow-map pass and the scene's GL mesh, for a method that
     * renders frames of its own (zpart, lispsm); NULL where none can */
    struct sl_shadowmap_pass *spass;   /* not const: the pass keeps its targets (shadowmap.h) */
    const struct sl_gl_mesh        *mesh;
    int                            threads;
    /* what ends a method's GL pass that may run long (a package's, drawn in
     * tiles: techpass.h): the run's stop flag (set by a signal: SL_E_STOPPED)
     * and limits.pass_seconds (0: none); NULL and 0 where nothing may */
    const volatile int            *stop;
    double                         pass_seconds;
};

/* What a method guarantees by construction; the driver checks it on every
 * cell and reports each violation (a violation is a bug). */
#define SL_EXACT_LIT    (1u << 0)   /* a PFL pixel it calls lit is lit in truth */
#define SL_EXACT_SHADOW (1u << 1)   /* a PFL pixel it calls shadowed is shadowed in truth */
#define SL_EXACT_PROVED (1u << 2)   /* a pixel it confirms, corrects or traces agrees with the truth */

/* Whether a PFL pixel's verdict v (decided `how`) breaks one of the
 * promises in `exact` against its truth t (enum sl_truth): the one rule
 * the cell's check, the fused scoring pass and the bench share. */
static inline int sl_exact_violated(unsigned exact, uint8_t v, uint8_t how, uint8_t t)
{
    int proved = how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ || how == SL_HOW_CORRECT || how == SL_HOW_TRACED;
    int right = (v == SL_V_LIT) == (t == SL_T_LIT);
    return ((exact & SL_EXACT_LIT) && v == SL_V_LIT && t != SL_T_LIT) ||
           ((exact & SL_EXACT_SHADOW) && v == SL_V_SHADOW && t != SL_T_SHADOW) ||
           ((exact & SL_EXACT_PROVED) && proved && !right);
}

/* The lights a method handles. A hard-shadow method (lights = 0) runs under
 * a directional light, a spot light, a point light (per face of its cube
 * of six frames, methods/cuberun.h: a technique package's maps as a C
 * method's layers), and under an area light taken as a point at its
 * centre: its frame is then the point's perspective frustum (frame.h), its
 * rays go to the point (sl_frame_toward), its figures and exactness answer
 * to the point's truth, and its verdicts, as a visible fraction 0 or 1,
 * are also scored against the area truth (the error of the hard-shadow
 * approximation). A soft method (SL_LIGHTS_AREA) needs an area light and
 * writes the visible fraction itself. */
#define SL_LIGHTS_AREA (1u << 1)
/* A hard-shadow method that needs a directional light (zpart, lispsm: their
 * fits are orthographic in light space); a scene with an area light does
 * not run it unless its list names it, which is then an error. */
#define SL_LIGHTS_DIRECTIONAL (1u << 2)

/* Optional figure families (struct sl_method.figures). The aliasing error m
 * of every PFL pixel (seed 004, score/aliasing.h): a tenth of the Morais
 * study's CPU, read by the aliasing study's methods (zpart, lispsm). */
#define SL_FIGS_ALIASING (1u << 0)

/* The optional fast path: how a method lets the driver hand its layers
 * more cheaply. Zero (the default) is no fast path: every layer dense, every
 * lookup the method's own. An embedded value rather than a pointer: a
 * method gives `.fast = {...}` beside its core, no second object, and the
 * zero of a designated initialiser is already "none". */
struct sl_method_fast {
    /* Layers (SL_NEED bits) it reads only at each decided pixel's own
     * texel, through sl_layer_at (frame.h): the driver may hand them
     * gathered per pixel (sl_frame_gather). 0: every layer dense. */
    unsigned at_pixel;
    /* Layers (SL_NEED bits, dense) it reads through sl_frame_look_of
     * (frame.h) when the driver made each pixel's lookup in them for the
     * view (sl_frame_look): made once, read by every such method of the
     * view. The method computes them itself where they are not there (a
     * point light's faces, a caller other than the driver). */
    unsigned looks;
    unsigned look_parts;   /* SL_LOOK_* parts of them it reads (frame.h) */
};

struct sl_method {
    const char *name;          /* config key */
    const char *summary;
    /* Where the method comes from, as data the run stores beside each cell
     * (cells.family, cells.beside) and the report reads — the report keeps
     * no list of methods. family: the work it is from ("moderno-2011",
     * "morais-2015", "curtis-2009", "hertel-2009", "seed-004"; a technique
     * package's `family:`, else "package"); NULL: none (a baseline). beside:
     * the space-separated theses whose tables list it beside their own
     * methods without making a study theirs (nsm: "moderno-2011
     * morais-2015"); NULL: none. A study gets a thesis's sections when a
     * method of that family ran. */
    const char *family;
    const char *beside;
    /* The method's name for people (LaTeX tables: "Texel coherence"); NULL:
     * its name. A config's `display:` overrides it per label. */
    const char *display;
    /* What to cite for it: space-separated keys of shadowlab's bibliography
     * (harness/cli/cite.c, doc/references.md), printed as BibTeX by
     * `shadowlab cite`; NULL: none (a baseline, or a source with no author
     * to name: cite says so). */
    const char *cite;
    unsigned    exact;         /* SL_EXACT_* */
    unsigned    lights;        /* 0: hard shadows, any light; SL_LIGHTS_AREA: soft shadows, area lights only;
                                * SL_LIGHTS_DIRECTIONAL: hard shadows, directional lights only */
    const struct sl_param *params;   /* its parameters, declared (base/params.h); NULL: none */
    int         nparams;
    unsigned    figures;       /* optional figure families its study reads (SL_FIGS_*): computed for
                                * a config's cells only where one of its methods asks, or the config
                                * does (outputs.aliasing); 0: the figures every method gets */
    /* Layers the method reads, given its parameters. */
    unsigned (*needs)(const struct sl_method_params *p);
    /* Check the values against each other, derive dependent defaults, mark
     * the parameters that do not apply (see the rules above). NULL: the
     * declarations say all. */
    enum sl_err (*configure)(struct sl_method_params *p, struct sl_diag *d);
    enum sl_err (*run)(const struct sl_method_args *a, struct sl_verdicts *out,
                       struct sl_cost *c, struct sl_diag *d);
    struct sl_method_fast fast;   /* optional; zero: none */
};

/* family and beside as text, "" for none (what the store holds). */
static inline const char *sl_method_family(const struct sl_method *m) { return m && m->family ? m->family : ""; }
static inline const char *sl_method_beside(const struct sl_method *m) { return m && m->beside ? m->beside : ""; }

/* A C method's declarations in its struct: `SL_METHOD_PARAMS(arr)` gives
 * .params and .nparams of a const array. */
#define SL_METHOD_PARAMS(arr) .params = (arr), .nparams = (int)(sizeof(arr) / sizeof((arr)[0]))

/* The parameters of m at their defaults, nothing given (a package's
 * method: its package's and its cascades', methods/package.h). */
void sl_method_params_init(const struct sl_method *m, struct sl_method_params *p);
/* Give one by name (checked against its declaration: base/params.h). */
static inline enum sl_err sl_method_param_put(struct sl_method_params *p, const char *name, double x,
                                              struct sl_diag *d)
{
    return sl_params_put(&p->values, name, x, d);
}
/* A parameter's value by name (NaN for a name m does not declare). */
static inline double sl_method_param(const struct sl_method_params *p, const char *name)
{
    return sl_params_get(&p->values, name);
}

/* The driver's reads of the face: configure with NULL meaning the
 * declarations say all, and the fast path, zero where a method gives none. */
enum sl_err sl_method_configure(const struct sl_method *m, struct sl_method_params *p, struct sl_diag *d);
static inline unsigned sl_method_at_pixel(const struct sl_method *m) { return m->fast.at_pixel; }
static inline unsigned sl_method_looks(const struct sl_method *m) { return m->fast.looks; }
static inline unsigned sl_method_look_parts(const struct sl_method *m) { return m->fast.look_parts; }

/* Helpers the methods share (method.c). */

/* Background and PnFL pixels get their fixed verdicts (none; shadow by
 * definition); returns 1 for them, 0 for a PFL pixel the method decides. */
static inline int sl_verdict_fixed(const struct sl_view *v, size_t i, struct sl_verdicts *out)
{
    if (v->cls[i] == SL_C_BACKGROUND) {
        out->v[i] = SL_V_NONE;
        out->how[i] = SL_HOW_NONE;
        return 1;
    }
    if (v->cls[i] == SL_C_PNFL) {
        out->v[i] = SL_V_SHADOW;
        out->how[i] = SL_HOW_PNFL;
        return 1;
    }
    return 0;
}

/* Trace the pixels `left` marks with the truth's own rays (up to tfar[i]
 * world units when tfar is not NULL) and give them the answer, how =
 * SL_HOW_TRACED; rays and time go to the cost (ms_trace, and ms_method). */
enum sl_err sl_method_trace_left(const struct sl_method_args *a, const uint8_t *left, const float *tfar,
                                 struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d);

/* Whether the shadow ray of pixel p (own: its triangle + 1) surely misses
 * every triangle the frame's conservative layers leave out (a point light's
 * unmapped triangles, frame.h): a method may claim light from those layers
 * only then. Always 1 for a directional light; tests are counted in *tests. */
int sl_method_unmapped_missed(const struct sl_method_args *a, const float p[3], uint32_t own, uint64_t *tests);

/* The built-in methods (registry.c): by name (NULL if none: a technique
 * package's method is found in the config's session, plan/session.h), how
 * many, the i-th. */
const struct sl_method *sl_method_find(const char *name);
int                     sl_method_count(void);
const struct sl_method *sl_method_at(int i);

/* Each pixel's lookup in the dense layers method m reads (needs) and
 * declares (looks), once per (frame, view) for every such method of the
 * view (frame.h: sl_frame_look). Made only where two readers or more
 * share them (`shared`: layers so read by the rest of the group, plan.h),
 * on the view's own frame (own_frame): one reader alone would pay a pass
 * and its arrays for nothing. Lookups made already get the parts m asks
 * for. */
enum sl_err sl_method_make_looks(struct sl_light_frame *f, int own_frame, const struct sl_view *v,
                                 const struct sl_method *m, unsigned needs, unsigned shared, int threads,
                                 struct sl_diag *d);


#endif
