/*
 * grade.h — grading a visibility image rendered by another program: the
 * image (EXR, or a 16-bit PNG: one channel, 1 lit, 0 shadowed, fractions
 * allowed; background alpha 0 or NaN) and, optionally, the engine's depth
 * buffer become a run of one cell of method `external` (methods/external.h)
 * on the scene, viewpoint and viewport given, scored exactly as a method's
 * cell is (PFL/PnFL, contour bands, fractional figures, overlay) and put in
 * the store with the user's label, so `table`, `report`, `check` and
 * `pivot` read it as any cell.
 *
 * The grade is written as a config beside its results (<out>/grade-<label>.yaml,
 * the files graded named in its comments) and run by sl_run: the same code
 * path as `shadowlab run`, nothing scored twice. Registration (external.h)
 * happens in the cell's run, before anything of the cell is stored: a
 * misregistered image leaves no cell.
 *
 * Owns: the images while it runs. Does not: print or exit.
 */
#ifndef SL_GRADE_H
#define SL_GRADE_H
#include "external.h"
#include "glbackend.h"
#include "sl_error.h"

/* How the engine's depth buffer holds depth (doc/grade.md). A window
 * depth is the same number under every API's perspective projection: an
 * OpenGL one's NDC z (-1..1) mapped to 0..1 by the default depth range
 * equals a Vulkan / D3D / Metal one's NDC z (0..1), f (z - n) / ((f - n) z)
 * for eye depth z (tests/test_grade.c checks it on cglm's matrices). */
enum sl_depth_kind {
    SL_DEPTH_LINEAR = 0,   /* eye-space distance along the view axis, world units */
    SL_DEPTH_WINDOW,       /* the depth buffer's value: 0 at the near plane, 1 at the far one */
};

/* A depth buffer's value z as linear depth (eye-space distance along the
 * view axis) under the convention given; NaN where nothing was drawn (not
 * finite, at or beyond the far plane, a linear depth <= 0). */
double sl_grade_linear_depth(enum sl_depth_kind kind, int reversed, double near_z, double far_z, double z);

/* Zero means default where it says. */
struct sl_grade_desc {
    const char *scene;       /* a scene file or a built-in scene's name */
    const char *viewpoint;
    int         w, h;
    const char *image;
    const char *depth;       /* NULL: register by background */
    enum sl_depth_kind depth_kind;
    int         reversed_z;
    double      near_z, far_z;   /* window depths: the engine's near and far planes */
    const char *label;
    const char *out_root;    /* NULL: "results" */
    const char *store;       /* NULL: <out_root>/shadowlab.db */
    int         map_size;    /* the map NSM's contours are drawn at; 0: 1024 */
    int         contour_own; /* 1: contours from the image's own verdicts */
    double      threshold;   /* 0: 0.5 */
    double      tolerance;   /* share of pixels; 0: 0.01 */
    double      depth_tolerance;   /* relative; 0: 0.01 */
    enum sl_gl_backend gl;   /* 0: the config default */
    int         threads;     /* 0: every core */
};

struct sl_grade_result {
    struct sl_external_report reg;
    char     config[1100];   /* the config written and run */
    char     out_dir[1100], store_path[1100];
    int      has_cell;
    uint64_t nonfinite;      /* the cell's (a NaN visibility on a surface pixel counts) */
};

/* Grade: SL_E_USAGE for a bad image (unreadable, 8-bit, several differing
 * colour channels, values outside 0..1, the wrong size) or a misregistered
 * one (the share and the likely cause in d), SL_E_SCENE / SL_E_CONFIG for
 * a scene, viewpoint or label the config refuses. table_out: the cell's
 * Markdown tables, NULL none. */
enum sl_err sl_grade(const struct sl_grade_desc *g, FILE *table_out, struct sl_grade_result *r,
                     struct sl_diag *d);

#endif
