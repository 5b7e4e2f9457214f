/*
 * external.h — method `external`: a visibility image rendered by another
 * program (an engine's shadow term), graded as if it were a method's
 * output (`shadowlab grade`, harness/run/grade.h).
 *
 * Its run does two things, in order:
 * 1. registration: before a single pixel is scored, the image must show
 *    the view shadowlab rendered. With a depth image, each pixel's linear
 *    depth is compared with the G-buffer's (view.h: the eye-space distance
 *    along the view axis of the pixel's position); without one, the
 *    image's background (alpha 0 or NaN) with the view's. A mismatch over
 *    the tolerance, or one that a flipped or one-pixel-shifted image would
 *    explain (sl_external_register), refuses the grade: SL_E_USAGE naming
 *    the share of misregistered pixels and the likely cause. An image with
 *    no background and no depth cannot be checked: the run goes on and
 *    says so (report->unchecked).
 * 2. verdicts: background and PnFL pixels as every method has them; a PFL
 *    pixel is lit iff its visibility >= threshold (a visibility not finite:
 *    uncertain, counted as nonfinite); the visibility itself goes to
 *    scoring (vd->vis, has_vis) for the fractional figures, as a technique
 *    package's does.
 *
 * A config cannot run it: nothing but `shadowlab grade` hands it an image
 * (the run refuses a label of method external without one).
 *
 * Owns: nothing (the image belongs to the grade). Does not: read files.
 */
#ifndef SL_EXTERNAL_H
#define SL_EXTERNAL_H
#include <stdint.h>
#include "sl_error.h"
#include "view.h"

/* What registration found, written by the run for the grade to show. */
struct sl_external_report {
    int      checked;        /* 0: no background and no depth: nothing to compare */
    int      by_depth;       /* compared depths, else background masks */
    uint64_t misregistered;  /* pixels that disagree as the image stands */
    uint64_t pixels;
    double   share;          /* misregistered / pixels */
    char     cause[256];     /* the likely cause when refused, else "" */
};

struct sl_external {
    int          w, h;
    const float *vis;        /* w * h, rows bottom-up; NaN: background */
    const uint8_t *bg;       /* w * h: 1 where the image is background (alpha 0 or NaN) */
    int          has_bg;     /* the image marks any background (an alpha channel, or a NaN) */
    const float *depth;      /* w * h linear depth (converted from the engine's convention), rows
                              * bottom-up, NaN or inf where the engine drew nothing; NULL: none */
    double       threshold;  /* a PFL pixel is lit iff vis >= threshold */
    double       tolerance;  /* share of pixels allowed to disagree (registration) */
    double       depth_tolerance;   /* relative: |z - z_view| / z_view above it disagrees */
    const char  *image, *depth_file;   /* the files, for messages */
    struct sl_external_report *report; /* written by the run; may be NULL */
};

/* Registration of e against the view v (same size): fills r; SL_OK when
 * registered (or unchecked), SL_E_USAGE with the share and the likely cause
 * in d when not. Exposed for tests. */
enum sl_err sl_external_register(const struct sl_external *e, const struct sl_view *v,
                                 struct sl_external_report *r, struct sl_diag *d);

/* The view's linear depth of pixel i (eye-space distance along the view
 * axis), NaN on background: what a depth image is compared with. */
float sl_external_view_depth(const struct sl_view *v, size_t i);

#endif
