/*
 * contour.h — contours of a method's own result image (never of the truth),
 * after Moderno 2011: the pixels on both sides of a change of state (a 2-px
 * thick line), dilated once (4 px) and twice (6 px).
 *
 * Neighbourhood: 4-connected (left, right, up, down) both for finding a change
 * and for each dilation, so a straight axis-aligned boundary gives exactly
 * 2, 4 and 6 pixels across, and the even width keeps the contour unbiased
 * ("roughly 50/50 shadow/light pixels", Moderno 3.1.2).
 * States: 0 = background, which never enters a contour and never makes one
 * (an object's silhouette against the sky is not a shadow boundary); any
 * other value is a state, and PnFL pixels carry the shadow state, as they
 * are dark in the method's image (the terminator of a lit surface is a
 * lit/shadow change like any other).
 */
#ifndef SL_CONTOUR_H
#define SL_CONTOUR_H
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* band[i] = 0 outside every contour; k >= 1: in the contour of thickness 2k
 * and every thicker one (k = 1 the change itself, k = 2 after one dilation,
 * ...). dilations >= 0. */
void sl_contour_bands(int w, int h, const uint8_t *state, int dilations, uint8_t *band);

/* The same on `threads` threads (<= 0: omp_get_max_threads()); the bands
 * do not depend on the thread count. sl_contour_bands is this with 0. */
void sl_contour_bands_mt(int w, int h, const uint8_t *state, int dilations, uint8_t *band, int threads);

/* The bands of rows [y0, y1) only, exactly as the whole image's, into
 * the same rows of band; scratch: sl_contour_scratch(w, y1 - y0, dilations)
 * bytes. Blocks of rows drawn by different threads touch nothing in common
 * but the states they read. */
void   sl_contour_bands_rows(int w, int h, const uint8_t *state, int dilations, int y0, int y1, uint8_t *band,
                             uint8_t *scratch);
size_t sl_contour_scratch(int w, int rows, int dilations);

/* The reference: one thread, pixel by pixel, as the bands were drawn
 * before (tests and the bench compare the two). */
void sl_contour_bands_plain(int w, int h, const uint8_t *state, int dilations, uint8_t *band);

/* Is pixel band b inside the contour of `thickness` pixels (0 = whole image)? */
static inline int sl_in_contour(uint8_t b, int thickness)
{
    return thickness == 0 || (b != 0 && 2 * (int)b <= thickness);
}

/* How far the 64 bytes p[0..64) stray from c, as one word: 0 when every
 * byte is c. Four 16-byte vectors (GCC's vector extension: SSE2 on x86-64,
 * NEON on arm64) XORed with c's broadcast and ORed: a table-free test the
 * contour segments and the scoring pass's uniform runs share. */
typedef uint64_t sl_bytes64_v2 __attribute__((vector_size(16)));

static inline uint64_t sl_bytes64_dev(const uint8_t *p, uint8_t c)
{
    const uint64_t cw = (uint64_t)c * 0x0101010101010101ull;
    const sl_bytes64_v2 b = {cw, cw};
    sl_bytes64_v2 w[4], d = {0, 0};
    memcpy(w, p, sizeof w);
    for (int k = 0; k < 4; k++)
        d |= w[k] ^ b;
    return d[0] | d[1];
}

#endif
