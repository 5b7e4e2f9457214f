/*
 * figures.h — the numbers of one (view, map size, method): per region (the
 * 2, 4 and 6 px contours and the whole image) the pixel counts of Morais 2015
 * Table 7 and Moderno 2011 Tables 5, 17 and 18.
 *
 * Counting rules: background pixels are counted once, apart, and enter no
 * region. PnFL pixels are in every count of pixels and of shadow (the method
 * shadows them by definition and is always right there), so that
 * light + shadow + uncertain = pixels in the region, as in the seeds' tables.
 * "correct"/"incorrect" compare the verdict with the truth.
 *
 * PnFL in the hints, confirmations and NSM's light/shadow split: the two
 * theses count them differently, and both counts exist. Morais 2015 keeps
 * PnFL apart (his PFL/PnFL tables): nsm_light, nsm_shadow, hinted*,
 * confirmed, corrected and the vs-NSM classes count PFL pixels only.
 * Moderno 2011 counts PnFL as shadow, hinted and confirmed ("all approaches
 * use normals", §4.4; Table 18's shadow pixels include them): the *_moderno
 * figures, defined for a method that reports NSM's verdicts (has_base).
 * PnFL are never wrong, so the wrong counts are the same under both; only
 * their bases differ.
 * Does not: format or write (run.c does).
 */
#ifndef SL_FIGURES_H
#define SL_FIGURES_H
#include <stdint.h>
#include "figrec.h"
#include "method.h"
#include "view.h"

/* thickness[] lists the regions (0 = whole image), at most SL_MAX_REGIONS.
 * Counts through sl_figures_fused on every core (exact 0, threads 0). */
void sl_figures_compute(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                        const int *thickness, int nregions, struct sl_figures *out);

/* The same figures, and the exactness check's count, in one multithreaded
 * pass over the pixels (a histogram of each pixel's classes; figures.c).
 * Returns how many PFL pixels (v->cls) break a guarantee in `exact`
 * (SL_EXACT_*: a lit pixel not lit in truth, a shadowed one not shadowed, a
 * confirmed/corrected/traced one wrong; 0 when exact is 0), or UINT64_MAX
 * when it had no memory for its tables and counted the figures pixel by
 * pixel without checking. threads <= 0: omp_get_max_threads(). */
uint64_t sl_figures_fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                          const int *thickness, int nregions, unsigned exact, int threads,
                          struct sl_figures *out);

/* The contour bands and the same in one pass: block by block, each block's
 * bands drawn from the states (sl_contour_bands_rows: `dilations` as
 * sl_contour_bands takes it) into band (w * h, every row written, as
 * sl_contour_bands writes it) and counted while in cache. Returns as
 * sl_figures_fused. */
uint64_t sl_score_fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *state, int dilations,
                        uint8_t *band, const int *thickness, int nregions, unsigned exact, int threads,
                        struct sl_figures *out);

/* The reference: the same counting rules, pixel by pixel on one thread, as
 * the figures were counted before the fused pass (tests and the bench
 * compare the two). */
void sl_figures_compute_pixelwise(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                                  const int *thickness, int nregions, struct sl_figures *out);

#endif
