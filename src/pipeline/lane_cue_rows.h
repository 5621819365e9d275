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
#include <string.h>

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

/* The same rules on Y rows with half-resolution chroma (NV12, YUYV and
 * UYVY frames): each 2x2 (4:2:0) or 2x1 block's Cb, Cr give B, G, R =
 * Y + (db, dg, dr), full-range BT.601 (as JPEG) in Q7, not clipped. Y
 * cancels from "B <= min(R, G) - margin", so a block is paint where Y
 * reaches one threshold of its own: white where Y plus the least of db,
 * dg, dr reaches white_min, yellow where Y + min(dr, dg) reaches
 * yellow_min and the margin. All in 16 bits (|Q7 products| < 2^15), so
 * the compiler keeps 16-bit lanes. */
#define LANE_CUE_CHUNK 128 /* chroma blocks a step (stack rows) */

/* t[i] = block i's threshold - 1 (paint: Y > t[i]; 255: never). Block i's
 * Cb, Cr are cb[i], cr[i] (step 1), or the bytes of the 16-bit word at
 * cb + 2 i (step 2, NV12's U, V: one load gives both in 16-bit lanes). */
static inline void lane_cue_thresholds(const uint8_t *restrict cb, const uint8_t *restrict cr,
                                       int32_t step, uint8_t *restrict t, int32_t n,
                                       const rte_lane_cue *k)
{
    /* a rule that is off, or a block that is not yellowish, gets a
     * threshold past 256 (|db|, |dg|, |dr| < 230): selects, no branches */
    const int16_t yb = k->yellow_b_margin;
    const int16_t white = (int16_t)(k->white_min + (k->white_on ? 0 : 512));
    const int16_t yellow =
        (int16_t)((k->yellow_min > yb ? k->yellow_min : yb) + (k->yellow_on ? 0 : 512));
    for (int32_t i = 0; i < n; i++) {
        int16_t u, v;
        if (step == 2) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
            uint16_t w;
            memcpy(&w, cb + 2 * i, sizeof w);
            u = (int16_t)((w & 0xFF) - 128);
            v = (int16_t)((w >> 8) - 128);
#else
            u = (int16_t)(cb[2 * i] - 128);
            v = (int16_t)(cb[2 * i + 1] - 128);
#endif
        } else {
            u = (int16_t)(cb[i] - 128);
            v = (int16_t)(cr[i] - 128);
        }
        const int16_t pr = (int16_t)(179 * v + 64), pb = (int16_t)(227 * u + 64);
        const int16_t pg = (int16_t)(-44 * u - 91 * v + 64);
        const int16_t dr = (int16_t)(pr >> 7), db = (int16_t)(pb >> 7), dg = (int16_t)(pg >> 7);
        const int16_t m = dr < dg ? dr : dg, least = m < db ? m : db;
        const int16_t tw = (int16_t)(white - least);
        const int16_t ty = (int16_t)(yellow - m + (db <= (int16_t)(m - yb) ? 0 : 512));
        int16_t th = tw < ty ? tw : ty;
        th = th < 1 ? 1 : th;
        th = th > 256 ? 256 : th;
        t[i] = (uint8_t)(th - 1);
    }
}

/* One pixel on threshold t. */
static inline uint8_t lane_cue_one(uint8_t g, uint8_t t, uint16_t dim)
{
    return g > t ? 255 : (uint8_t)((g * dim) >> 8);
}

/* n pixels on thresholds t[x]. */
static inline void lane_cue_apply(const uint8_t *restrict g, const uint8_t *restrict t,
                                  uint8_t *restrict d, int32_t n, uint16_t dim)
{
    for (int32_t x = 0; x < n; x++)
        d[x] = lane_cue_one(g[x], t[x], dim);
}

/* The rows of `width` pixels that share a row of chroma blocks: g[0] and
 * g[1] (g[1] and d[1] NULL for one row) into d[0] and d[1]. Chroma block i
 * is cb[step i], cr[step i] (as lane_cue_thresholds reads them); block 0
 * starts one pixel left of the rows when `odd` is set. Each block's
 * threshold is computed once for both rows, then set on its two pixels. */
static inline void lane_cue_chroma_rows_step(const uint8_t *const g[2], const uint8_t *cb,
                                             const uint8_t *cr, int32_t step, uint8_t *const d[2],
                                             int32_t width, bool odd, const rte_lane_cue *k)
{
    uint8_t t[LANE_CUE_CHUNK], t2[2 * LANE_CUE_CHUNK];
    const uint16_t dim = k->dim_q8;
    const int rows = g[1] ? 2 : 1;
    int32_t x = 0;
    if (odd && width > 0) { /* the first pixel alone: the pairs start on a block */
        lane_cue_thresholds(cb, cr, step, t, 1, k);
        for (int r = 0; r < rows; r++)
            d[r][0] = lane_cue_one(g[r][0], t[0], dim);
        cb += step, cr += step, x = 1;
    }
    while (x < width) {
        const int32_t blocks = (width - x + 1) / 2;
        const int32_t n = blocks < LANE_CUE_CHUNK ? blocks : LANE_CUE_CHUNK;
        lane_cue_thresholds(cb, cr, step, t, n, k);
        for (int32_t i = 0; i < n; i++)
            t2[2 * i] = t2[2 * i + 1] = t[i];
        const int32_t pixels = width - x < 2 * n ? width - x : 2 * n;
        for (int r = 0; r < rows; r++)
            lane_cue_apply(g[r] + x, t2, d[r] + x, pixels, dim);
        cb += step * n, cr += step * n, x += 2 * n;
    }
}

static inline void lane_cue_chroma_rows(const uint8_t *const g[2], const uint8_t *cb,
                                        const uint8_t *cr, bool interleaved, uint8_t *const d[2],
                                        int32_t width, bool odd, const rte_lane_cue *k)
{
    if (interleaved)
        lane_cue_chroma_rows_step(g, cb, cr, 2, d, width, odd, k);
    else
        lane_cue_chroma_rows_step(g, cb, cr, 1, d, width, odd, k);
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
