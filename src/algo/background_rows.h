/* Row loops of the table estimate and the threshold against it (private
 * to src/algo): included by background.c and background_threshold.c,
 * which build them for the baseline target as the C references, and by
 * simd/background_x86.c, which builds the same loops for AVX2 (32 bytes or
 * 8 values at a time). Integer only: vectorising reorders exact operations,
 * so the bytes stay the C reference's. */
#ifndef RTEDGE_ALGO_BACKGROUND_ROWS_H
#define RTEDGE_ALGO_BACKGROUND_ROWS_H

#include <stdint.h>

/* Interpolated values carry 4 + 2 x 8 fractional bits (background.c). */
#define RTE_BACKGROUND_VALUE_SHIFT 20

/* v[x] += add[x]: the next row's values. */
static inline void background_add_row(int32_t *restrict v, const int32_t *restrict add, int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        v[x] += add[x];
}

/* out[x] = the row's values rounded down to grey levels. */
static inline void background_store_row(const int32_t *restrict v, uint8_t *restrict out, int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        out[x] = (uint8_t)(v[x] >> RTE_BACKGROUND_VALUE_SHIFT);
}

/* a[x] = |s[x] - b[x]| (max - min). */
static inline void background_absdiff_row(const uint8_t *restrict s, const uint8_t *restrict b,
                                          uint8_t *restrict a, int32_t w)
{
    for (int32_t x = 0; x < w; x++) {
        const uint8_t hi = s[x] > b[x] ? s[x] : b[x], lo = s[x] > b[x] ? b[x] : s[x];
        a[x] = (uint8_t)(hi - lo);
    }
}

/* c[x]: the side's class (bright_class where s > b, else dark_class; 0 for
 * a side not looked for) where a[x] > low, shifted up by 2 more where
 * a[x] > high. */
static inline void background_classify_row(const uint8_t *restrict a, const uint8_t *restrict s,
                                           const uint8_t *restrict b, uint8_t *restrict c,
                                           int32_t w, uint8_t low, uint8_t high,
                                           uint8_t bright_class, uint8_t dark_class)
{
    for (int32_t x = 0; x < w; x++) {
        const uint8_t side = s[x] > b[x] ? bright_class : dark_class;
        c[x] = (uint8_t)((a[x] > low ? side : 0) | (a[x] > high ? side << 2 : 0));
    }
}

/* a[x] = 255 where a[x] > fl[x], else 0. */
static inline void background_above_floor_row(uint8_t *restrict a, const uint8_t *restrict fl,
                                              int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        a[x] = a[x] > fl[x] ? 255 : 0;
}

#endif
