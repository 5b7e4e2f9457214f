/*
 * contour.c — see contour.h. Invariant: bands only grow outward one 4-step per
 * dilation and never onto background.
 */
#include "contour.h"
#include <string.h>

void sl_contour_bands(int w, int h, const uint8_t *state, int dilations, uint8_t *band)
{
    memset(band, 0, (size_t)w * (size_t)h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            uint8_t s = state[i];
            if (!s)
                continue;
            int edge = (x > 0 && state[i - 1] && state[i - 1] != s) ||
                       (x + 1 < w && state[i + 1] && state[i + 1] != s) ||
                       (y > 0 && state[i - (size_t)w] && state[i - (size_t)w] != s) ||
                       (y + 1 < h && state[i + (size_t)w] && state[i + (size_t)w] != s);
            if (edge)
                band[i] = 1;
        }
    for (int k = 1; k <= dilations; k++) {
        uint8_t nb = (uint8_t)(k + 1);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                if (band[i] || !state[i])
                    continue;
                int touch = (x > 0 && band[i - 1] == k) || (x + 1 < w && band[i + 1] == k) ||
                            (y > 0 && band[i - (size_t)w] == k) ||
                            (y + 1 < h && band[i + (size_t)w] == k);
                if (touch)
                    band[i] = nb;
            }
    }
}
