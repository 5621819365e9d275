/* Row loops of the table estimate and the threshold against it (private
 * to src/algo): included by background.c and background_threshold.c,
 * which build them for the baseline target as the C references, and by
 * simd/background_x86.c, which builds the same loops for AVX2 (32 bytes or
 * 8 values at a time). Integer only: vectorising reorders exact operations,
 * so the bytes stay the C reference's. */
#ifndef RTEDGE_ALGO_BACKGROUND_ROWS_H
#define RTEDGE_ALGO_BACKGROUND_ROWS_H

#include <stdint.h>
#include <string.h>

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

/* out[h] = 255 where chroma sample h's 2x2 block may be the table in
 * shadow, judged on its top-left pixel 2h, else 0: with k = s / t, s in
 * [lo, hi] t / 1000 and the chroma, (cb, cr) - 128, within tol of the
 * table's times k (|(cb - 128) t - s (cbt - 128)| + |(cr - 128) t - s (crt
 * - 128)| <= tol t). Reads s and t up to pixel 2 hw - 1 (pairs, loaded as
 * 16-bit words: they vectorise better than every other byte); 32-bit
 * lanes: every product is below 2^17. */
static inline void background_shade_row(const uint8_t *restrict s, const uint8_t *restrict t,
                                        const uint8_t *restrict cb, const uint8_t *restrict cbt,
                                        const uint8_t *restrict cr, const uint8_t *restrict crt,
                                        uint8_t *restrict out, int32_t hw, int32_t lo, int32_t hi,
                                        int32_t tol)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    const int first = 8; /* the pair's first byte in its 16-bit word */
#else
    const int first = 0;
#endif
    for (int32_t h = 0; h < hw; h++) {
        uint16_t sp, tp;
        memcpy(&sp, s + 2 * h, sizeof sp);
        memcpy(&tp, t + 2 * h, sizeof tp);
        const int32_t sv = (sp >> first) & 0xFF, tv = (tp >> first) & 0xFF;
        const int32_t b = cb[h] - 128, bt = cbt[h] - 128, r = cr[h] - 128, rt = crt[h] - 128;
        const int32_t eb = b * tv - sv * bt, er = r * tv - sv * rt;
        const int32_t e = (eb < 0 ? -eb : eb) + (er < 0 ? -er : er);
        out[h] =
            (uint8_t)(((tv > 0) & (sv * 1000 >= lo * tv) & (sv * 1000 <= hi * tv) & (e <= tol * tv))
                          ? 255
                          : 0);
    }
}

/* c[x] (a class of background_classify_row) becomes side 3 where it is
 * dark (side 2) and the half-size shade mask m is set at x / 2. */
static inline void background_shade_class_row(uint8_t *restrict c, const uint8_t *restrict m,
                                              int32_t w)
{
    for (int32_t h = 0; h < w / 2; h++) {
        const uint8_t set = m[h] != 0;
        c[2 * h] |= (uint8_t)(((c[2 * h] & 3) == 2) & set);
        c[2 * h + 1] |= (uint8_t)(((c[2 * h + 1] & 3) == 2) & set);
    }
    if (w & 1)
        c[w - 1] |= (uint8_t)(((c[w - 1] & 3) == 2) & (m[w / 2] != 0));
}

/* a[x] = 255 where a[x] > fl[x], else 0. */
static inline void background_above_floor_row(uint8_t *restrict a, const uint8_t *restrict fl,
                                              int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        a[x] = a[x] > fl[x] ? 255 : 0;
}

#endif
