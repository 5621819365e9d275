/* The gradient family's row loops (private to src/algo): included by
 * gradient.c, which builds them for the baseline target as the C
 * reference, and by simd/gradient_x86.c, which builds the same loops for
 * AVX2 (16 int16 lanes instead of 8). Integer arithmetic only, so every
 * build gives the same bytes; tests/unit/test_simd.c checks it. */
#ifndef RTEDGE_ALGO_GRADIENT_LOOPS_H
#define RTEDGE_ALGO_GRADIENT_LOOPS_H

#include <stdint.h>

#include "gradient_rows.h"

/* out[x] = sum_k ky[k] * row[k][x] for 0 <= x < w. */
static inline void grad_column_loop(const uint8_t *const *row, int32_t w, const int16_t *ky,
                                    int32_t ny, int16_t *v)
{
    int16_t *restrict out = v;
    /* One loop per tap count so each vectorises with the taps in registers. */
    switch (ny) {
    case 1: {
        const uint8_t *restrict a = row[0];
        const int16_t c0 = ky[0];
        for (int32_t x = 0; x < w; x++)
            out[x] = (int16_t)(c0 * a[x]);
        break;
    }
    case 3: {
        const uint8_t *restrict a = row[0], *restrict b = row[1], *restrict c = row[2];
        const int16_t c0 = ky[0], c1 = ky[1], c2 = ky[2];
        /* The two 3x3 Sobel taps (and Canny's) without multiplies. */
        if (c0 == 1 && c1 == 2 && c2 == 1)
            for (int32_t x = 0; x < w; x++)
                out[x] = (int16_t)(a[x] + 2 * b[x] + c[x]);
        else if (c0 == -1 && c1 == 0 && c2 == 1)
            for (int32_t x = 0; x < w; x++)
                out[x] = (int16_t)(c[x] - a[x]);
        else
            for (int32_t x = 0; x < w; x++)
                out[x] = (int16_t)(c0 * a[x] + c1 * b[x] + c2 * c[x]);
        break;
    }
    case 5: {
        const uint8_t *restrict a = row[0], *restrict b = row[1], *restrict c = row[2];
        const uint8_t *restrict d = row[3], *restrict e = row[4];
        const int16_t c0 = ky[0], c1 = ky[1], c2 = ky[2], c3 = ky[3], c4 = ky[4];
        for (int32_t x = 0; x < w; x++)
            out[x] = (int16_t)(c0 * a[x] + c1 * b[x] + c2 * c[x] + c3 * d[x] + c4 * e[x]);
        break;
    }
    default: {
        const uint8_t *restrict a = row[0], *restrict b = row[1], *restrict c = row[2];
        const uint8_t *restrict d = row[3], *restrict e = row[4], *restrict f = row[5];
        const uint8_t *restrict g = row[6];
        const int16_t c0 = ky[0], c1 = ky[1], c2 = ky[2], c3 = ky[3], c4 = ky[4], c5 = ky[5],
                      c6 = ky[6];
        for (int32_t x = 0; x < w; x++)
            out[x] = (int16_t)(c0 * a[x] + c1 * b[x] + c2 * c[x] + c3 * d[x] + c4 * e[x] +
                               c5 * f[x] + c6 * g[x]);
        break;
    }
    }
}

static inline int16_t sat_s16(int32_t v)
{
    return (int16_t)(v < INT16_MIN ? INT16_MIN : v > INT16_MAX ? INT16_MAX : v);
}

/* The sums in int32, then truncated (when the caller knows they fit: the
 * compiler then runs the loop in 16-bit lanes), saturated, or divided by 16
 * rounding half to even. The bias keeps the shift on non-negative values;
 * it is a multiple of 16 above any 7-tap sum of int16 column values. */
static inline int16_t finish(int32_t v, rte_row_mode mode)
{
    if (mode == RTE_ROW_FITS)
        return (int16_t)v;
    if (mode == RTE_ROW_SATURATE)
        return sat_s16(v);
    const int32_t bias = 1 << 25;
    const int32_t b = v + bias, q = b >> 4, r = b & 15;
    return (int16_t)(q - (bias >> 4) + ((r > 8) | ((r == 8) & (q & 1))));
}

static inline void grad_row_loop(const int16_t *restrict s, const int16_t *kx, int32_t nx,
                                 int16_t *restrict o, int32_t width, rte_row_mode mode)
{
    const int16_t c0 = kx[0];
    switch (nx) {
    case 1:
        for (int32_t x = 0; x < width; x++)
            o[x] = finish(c0 * s[x], mode);
        break;
    case 3: {
        const int16_t c1 = kx[1], c2 = kx[2];
        if (c0 == 1 && c1 == 2 && c2 == 1)
            for (int32_t x = 0; x < width; x++)
                o[x] = finish(s[x] + 2 * s[x + 1] + s[x + 2], mode);
        else if (c0 == -1 && c1 == 0 && c2 == 1)
            for (int32_t x = 0; x < width; x++)
                o[x] = finish(s[x + 2] - s[x], mode);
        else
            for (int32_t x = 0; x < width; x++)
                o[x] = finish(c0 * s[x] + c1 * s[x + 1] + c2 * s[x + 2], mode);
        break;
    }
    case 5: {
        const int16_t c1 = kx[1], c2 = kx[2], c3 = kx[3], c4 = kx[4];
        for (int32_t x = 0; x < width; x++)
            o[x] = finish(c0 * s[x] + c1 * s[x + 1] + c2 * s[x + 2] + c3 * s[x + 3] + c4 * s[x + 4],
                          mode);
        break;
    }
    default: {
        const int16_t c1 = kx[1], c2 = kx[2], c3 = kx[3], c4 = kx[4], c5 = kx[5], c6 = kx[6];
        for (int32_t x = 0; x < width; x++)
            o[x] = finish(c0 * s[x] + c1 * s[x + 1] + c2 * s[x + 2] + c3 * s[x + 3] +
                              c4 * s[x + 4] + c5 * s[x + 5] + c6 * s[x + 6],
                          mode);
        break;
    }
    }
}

/* out[x] = sum_k kx[k] * v[x + k - nx/2], finished as `mode` says. */
static inline void grad_row_pass_loop(const int16_t *v, const int16_t *kx, int32_t nx, int16_t *out,
                                      int32_t width, int mode)
{
    /* One instance per mode, each with a constant `finish`. */
    switch (mode) {
    case RTE_ROW_FITS: grad_row_loop(v - nx / 2, kx, nx, out, width, RTE_ROW_FITS); break;
    case RTE_ROW_SATURATE: grad_row_loop(v - nx / 2, kx, nx, out, width, RTE_ROW_SATURATE); break;
    default: grad_row_loop(v - nx / 2, kx, nx, out, width, RTE_ROW_ROUND_DIV16); break;
    }
}

/* Defines rte_grad_column_<isa> and rte_grad_row_<isa> (declared in
 * simd/rows.h) as the loops above, built for the including file's target. */
#define RTE_GRAD_ROWS_DEFINE(isa)                                                            \
    void rte_grad_column_##isa(const uint8_t *const *rows, int32_t width, const int16_t *ky, \
                               int32_t ny, int16_t *out)                                     \
    {                                                                                        \
        grad_column_loop(rows, width, ky, ny, out);                                          \
    }                                                                                        \
    void rte_grad_row_##isa(const int16_t *v, const int16_t *kx, int32_t nx, int16_t *out,   \
                            int32_t width, int mode)                                         \
    {                                                                                        \
        grad_row_pass_loop(v, kx, nx, out, width, mode);                                     \
    }

#endif
