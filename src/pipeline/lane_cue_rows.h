/* The lane path's colour cue, one row at a time (private to librtedge):
 * included by lane_cue.c, which builds it for the baseline target as the C
 * reference, and by src/algo/simd/lane_cue_x86.c, which builds the same
 * loop for AVX2 (where the compiler deinterleaves the 3-byte pixels with
 * byte shuffles, about five times faster than baseline SSE2 can). On
 * aarch64 the baseline build already deinterleaves with ld3. */
#ifndef RTEDGE_PIPELINE_LANE_CUE_ROWS_H
#define RTEDGE_PIPELINE_LANE_CUE_ROWS_H

#include <stdbool.h>
#include <stdint.h>

#include "algo/simd/rows.h"

/* White or yellow paint -> 255, every other pixel grey * dim / 256, in
 * 8-bit comparisons (a threshold of 256 can never be reached, so its
 * *_on mask is 0 instead). The pixel offsets of B and R are constants in
 * each caller so the loads vectorise. */
static inline void lane_cue_pixels(const uint8_t *restrict g, const uint8_t *restrict c,
                                   uint8_t *restrict d, int32_t width, const rte_lane_cue *k,
                                   int bi, int ri)
{
    const uint8_t wm = k->white_min, white_on = k->white_on, ym = k->yellow_min;
    const uint8_t yellow_on = k->yellow_on, yb = k->yellow_b_margin;
    const uint16_t dim = k->dim_q8;
    for (int32_t x = 0; x < width; x++) {
        const uint8_t b = c[3 * x + bi], gg = c[3 * x + 1], r = c[3 * x + ri];
        const uint8_t mn = r < gg ? r : gg;
        const uint8_t mb = mn > yb ? (uint8_t)(mn - yb) : 0; /* B may be at most this */
        const uint8_t white = (uint8_t)(-(uint8_t)((b >= wm) & (gg >= wm) & (r >= wm)) & white_on);
        const uint8_t yellow =
            (uint8_t)(-(uint8_t)((mn >= ym) & (mn >= yb) & (b <= mb)) & yellow_on);
        const uint8_t paint = white | yellow; /* 0xFF or 0 */
        d[x] = (uint8_t)(paint | (~paint & (uint8_t)((g[x] * dim) >> 8)));
    }
}

static inline void lane_cue_row(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst,
                                int32_t width, const rte_lane_cue *cue, bool rgb)
{
    if (rgb)
        lane_cue_pixels(gray, bgr, dst, width, cue, 2, 0);
    else
        lane_cue_pixels(gray, bgr, dst, width, cue, 0, 2);
}

#endif
