/*
 * techtest.h — `shadowlab test technique NAME`: a technique package tried
 * on one view of a scene before a study runs it, the checks a run cannot
 * make because it looks at each result once.
 *
 * What it does, in order: finds the package on the search path (as `show
 * technique`: no config, a C method's name refused), compiles its shaders
 * with glslang (techcheck.h) and then on the GL (techpass.h); renders the
 * scene's first viewpoint (or the one named) and fits the light frame as a
 * run does (lightfit.h); then draws the package at its defaults:
 *
 *   - determinism: the ordinary maps and lookup twice; any PFL pixel whose
 *     visibility differs (bit for bit; NaN equal to NaN) between the two is
 *     a finding;
 *   - reach: the maps grown by SL_TECHTEST_EXTRA texels a side beyond the
 *     guard band the package declares, those texels filled once with a
 *     surface at the near plane (sl_map(0)) and once with none (sl_map(1))
 *     (techpass.h, extra and fill), the lookup run on each: a lookup that
 *     reads only within its declared reach cannot tell them apart, so any
 *     pixel whose visibility or verdict differs reads beyond it (along the
 *     frame's border: points farther in read other texels of the scene,
 *     the same in both);
 *   - non-finite: the lookups that returned NaN or +-inf, and the maps'
 *     texels that are not finite;
 *   - taps: the texel reads each pixel's lookup made, counted in the shader
 *     (techsrc.h, SL_TECHSRC_LOOKUP_TAPS), against the declared `taps`;
 *   - time: the map, post and lookup passes' ms, and the lookup's per pixel.
 *
 * Under a point light each face of its cube that holds receivers is a
 * frame of its own, fitted as lightframe.c fits it, over the face's pixels;
 * the counts are the faces' sums, the times too.
 *
 * Does not: print (the verb does), trace any truth (it compares the
 * package with itself, not with the scene's shadows), write files.
 */
#ifndef SL_TECHTEST_H
#define SL_TECHTEST_H
#include <stdint.h>
#include "glctx.h"
#include "sl_error.h"

/* Texels of guard band the reach test adds beyond the declared one. */
#define SL_TECHTEST_EXTRA 16

struct sl_techtest_opts {
    const char *name;        /* the package */
    const char *scene;       /* a scene file or a built-in scene's name; NULL: primitives */
    const char *viewpoint;   /* NULL: the scene's first */
    int w, h;                /* the view; 0: 256 x 256 */
    int map_size;            /* the light frame's S; 0: 512 */
    enum sl_gl_backend gl;
};

struct sl_techtest_result {
    char file[1100];         /* the package's technique.yaml */
    char scene[64], viewpoint[64];
    char renderer[128];
    int w, h, map_size, guard, reach;
    int frames;              /* light frames drawn: 1, or a point light's cube faces with receivers */
    uint64_t pixels;         /* PFL pixels looked up */
    /* determinism: pixels whose visibility differs between two runs */
    uint64_t unstable;
    /* reach: pixels whose visibility differs with the fill, of them those
     * whose verdict differs; the first such pixel (x, y; rows from the bottom), -1 when none */
    uint64_t reach_changed, reach_verdicts;
    int reach_x, reach_y;
    uint64_t nonfinite, map_nonfinite;
    /* taps: declared at the defaults; counted per pixel: mean, least, most */
    double taps_declared, taps_mean;
    uint32_t taps_min, taps_max;
    int taps_given;          /* the package declares `taps` (else the default, 1) */
    int taps_off;            /* declared, and outside taps_min .. taps_max: a finding */
    /* time, ms, the second ordinary run's (the first's holds the driver's first use of the
     * programs), summed over the frames */
    double ms_map, ms_post, ms_lookup;
    int findings;            /* the checks above that failed */
};

/* A finding is no error: SL_OK with r->findings counting them. Errors: an
 * unknown package, scene or viewpoint (SL_E_USAGE), a
 * package that fails to load or compile (SL_E_PACKAGE naming its file and
 * line), the GL's. */
enum sl_err sl_techtest(const struct sl_techtest_opts *o, struct sl_techtest_result *r, struct sl_diag *d);

#endif
