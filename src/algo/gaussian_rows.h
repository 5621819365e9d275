/* The Gaussian blur's row kernels (private to src/algo): included by
 * gaussian.c, which builds them for the baseline target as the C
 * reference, and by simd/gaussian_x86.c, which builds the very same loops
 * for AVX2 (the compiler vectorises them in 16-bit lanes, 16 at a time
 * instead of 8). Integer arithmetic only, so every build gives the same
 * bytes; tests/unit/test_simd.c checks it. See gaussian.c for the maths. */
#ifndef RTEDGE_ALGO_GAUSSIAN_ROWS_H
#define RTEDGE_ALGO_GAUSSIAN_ROWS_H

#include <stdint.h>

/* v = sum_j taps[j] * rows[j][x] (taps symmetric). Split: stored as
 * hi = v >> 8 and lo = v & 255; otherwise v goes to hi as it is. The radius
 * r and `split` are constants in each caller so the tap loop unrolls and the
 * x loop vectorises in u16 lanes. */
static inline void column_taps(const uint8_t *const *rows, uint16_t *restrict hi,
                               uint16_t *restrict lo, int32_t width, const uint16_t *restrict taps,
                               int32_t r, int split)
{
    const uint8_t *restrict mid = rows[r];
    for (int32_t x = 0; x < width; x++) {
        uint16_t s = (uint16_t)(taps[r] * mid[x]);
        for (int32_t j = 0; j < r; j++)
            s = (uint16_t)(s + taps[j] * (uint16_t)(rows[j][x] + rows[2 * r - j][x]));
        if (split) {
            hi[x] = (uint16_t)(s >> 8);
            lo[x] = (uint16_t)(s & 255);
        } else {
            hi[x] = s;
        }
    }
}

/* dst[x] = (sum_i taps[i] * v(x + i) + 2^15) >> 16 over the padded planes,
 * v = 256 * hi + lo. With H = sum taps * hi and L = sum taps * lo (each at
 * most 255 * 256, so u16):
 *   sum = 256 * H + L  and  (sum + 2^15) >> 16 = (H + (L >> 8) + 128) >> 8,
 * where H + (L >> 8) <= 255 * 256 (as sum <= 255 * 2^16): no overflow. */
static inline void row_taps(const uint16_t *restrict hi, const uint16_t *restrict lo,
                            uint8_t *restrict dst, int32_t width, const uint16_t *restrict taps,
                            int32_t r)
{
    for (int32_t x = 0; x < width; x++) {
        uint16_t hs = (uint16_t)(taps[r] * hi[x + r]);
        uint16_t ls = (uint16_t)(taps[r] * lo[x + r]);
        for (int32_t i = 0; i < r; i++) {
            hs = (uint16_t)(hs + taps[i] * (uint16_t)(hi[x + i] + hi[x + 2 * r - i]));
            ls = (uint16_t)(ls + taps[i] * (uint16_t)(lo[x + i] + lo[x + 2 * r - i]));
        }
        dst[x] = (uint8_t)((uint16_t)(hs + (ls >> 8) + 128) >> 8);
    }
}

/* Narrow path: dst[x] = (sum_i taps[i] * v(x + i) + 128) >> 8 where the
 * scaled-down taps keep the sum within 255 * 256. */
static inline void row_taps_narrow(const uint16_t *restrict v, uint8_t *restrict dst, int32_t width,
                                   const uint16_t *restrict taps, int32_t r)
{
    for (int32_t x = 0; x < width; x++) {
        uint16_t s = (uint16_t)(taps[r] * v[x + r]);
        for (int32_t i = 0; i < r; i++)
            s = (uint16_t)(s + taps[i] * (uint16_t)(v[x + i] + v[x + 2 * r - i]));
        dst[x] = (uint8_t)((uint16_t)(s + 128) >> 8);
    }
}

/* Calls STEP(r) with the radius as a constant, so each pass is compiled once
 * per kernel size with its tap loop unrolled. */
#define DISPATCH_RADIUS(radius, STEP) \
    switch (radius) {                 \
    case 0: STEP(0); break;           \
    case 1: STEP(1); break;           \
    case 2: STEP(2); break;           \
    case 3: STEP(3); break;           \
    case 4: STEP(4); break;           \
    case 5: STEP(5); break;           \
    case 6: STEP(6); break;           \
    default: STEP(7); break;          \
    }

/* The same for the split (two-plane) or narrow (one-plane) variant. */
#define DISPATCH(split, radius, SPLIT_STEP, NARROW_STEP) \
    do {                                                 \
        if (split) {                                     \
            DISPATCH_RADIUS(radius, SPLIT_STEP)          \
        } else {                                         \
            DISPATCH_RADIUS(radius, NARROW_STEP)         \
        }                                                \
    } while (0)

static inline void gaussian_column_pass(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,
                                        int32_t width, const uint16_t *taps, int32_t ksize,
                                        int split)
{
#define COLUMN_SPLIT(r) column_taps(rows, hi, lo, width, taps, r, 1)
#define COLUMN_NARROW(r) column_taps(rows, hi, lo, width, taps, r, 0)
    DISPATCH(split, ksize / 2, COLUMN_SPLIT, COLUMN_NARROW);
}

static inline void gaussian_row_pass(const uint16_t *hi, const uint16_t *lo, uint8_t *dst,
                                     int32_t width, const uint16_t *taps, int32_t ksize, int split)
{
#define ROW_SPLIT(r) row_taps(hi, lo, dst, width, taps, r)
#define ROW_NARROW(r) row_taps_narrow(hi, dst, width, taps, r)
    DISPATCH(split, ksize / 2, ROW_SPLIT, ROW_NARROW);
}

#endif
