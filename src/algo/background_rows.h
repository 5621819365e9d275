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

/* c2[2h] = c2[2h + 1] = |cb[h] - cbt[h]| + |cr[h] - crt[h]| (at most 255):
 * the colour differences of a row of half-size chroma samples, each twice. */
static inline void background_chroma_diff_row(const uint8_t *restrict cb,
                                              const uint8_t *restrict cbt,
                                              const uint8_t *restrict cr,
                                              const uint8_t *restrict crt, uint8_t *restrict c2,
                                              int32_t hw)
{
    for (int32_t h = 0; h < hw; h++) {
        const uint8_t db = cb[h] > cbt[h] ? cb[h] - cbt[h] : cbt[h] - cb[h];
        const uint8_t dr = cr[h] > crt[h] ? cr[h] - crt[h] : crt[h] - cr[h];
        const uint8_t sum = (uint8_t)(db + dr), c = sum < db ? 255 : sum; /* saturated */
        c2[2 * h] = c;
        c2[2 * h + 1] = c;
    }
}

/* cd[x] (the colour difference on entry) becomes the tinted pixel: s[x],
 * or where cd[x] >= least and cd[x] > |s[x] - b[x]|, b[x] + cd[x] (up) or
 * b[x] - cd[x], clamped; up where up_only, or with `either` where s > b,
 * or s == b and b < 128 (the side with room). */
static inline void background_tint_row(const uint8_t *restrict s, const uint8_t *restrict b,
                                       uint8_t *restrict cd, int32_t w, uint8_t least,
                                       uint8_t up_only, uint8_t either)
{
    /* all in bytes (no wider lanes): the sums saturate by their wrap */
    for (int32_t x = 0; x < w; x++) {
        const uint8_t c = cd[x], sv = s[x], bv = b[x];
        const uint8_t ad = (uint8_t)((sv > bv ? sv : bv) - (sv > bv ? bv : sv));
        const uint8_t sum = (uint8_t)(bv + c);
        const uint8_t upv = sum < bv ? 255 : sum;
        const uint8_t downv = bv > c ? (uint8_t)(bv - c) : 0;
        const uint8_t up = up_only | (either & ((sv > bv) | ((sv == bv) & (bv < 128))));
        cd[x] = ((c >= least) & (c > ad)) ? (up ? upv : downv) : sv;
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
