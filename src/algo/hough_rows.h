/* The rho bins of one point at every angle (segments) and of many points at
 * one angle (lines), and the sum of the lines' vote copies, private to
 * src/algo: included by hough_segments.c and hough_lines.c, which build
 * them for the baseline target as the C references, and by simd/hough_x86.c,
 * which builds the same loops for AVX2 (the compiler turns them into 32-bit
 * multiplies on 8 lanes at a time); simd/hough_lines_x86.c has the lines'
 * bins in AVX2 intrinsics. On aarch64 the baseline build already vectorises
 * them with NEON. */
#ifndef RTEDGE_ALGO_HOUGH_ROWS_H
#define RTEDGE_ALGO_HOUGH_ROWS_H

#include <stdint.h>

/* idx[a] = row_base[a] + ((x * rho_cos[a] + y * rho_sin[a] + bias) >> shift)
 * for a < n. The caller guarantees the sum is in [0, 2^31) (the
 * configuration's trig_shift keeps it there), so the shift of a signed
 * value is the same everywhere. */
static inline void hough_bins_row(const int32_t *restrict rho_cos, const int32_t *restrict rho_sin,
                                  int32_t n, int32_t x, int32_t y, int32_t bias, int32_t shift,
                                  const int32_t *restrict row_base, int32_t *restrict idx)
{
    for (int32_t a = 0; a < n; a++)
        idx[a] = row_base[a] + ((x * rho_cos[a] + y * rho_sin[a] + bias) >> shift);
}

/* idx[i] = (x * rho_cos + y * rho_sin + bias) >> shift for the n packed
 * points pts[i] = y << 16 | x, the sum in [0, 2^31) as above. */
static inline void hough_point_bins_row(const uint32_t *restrict pts, int32_t n, int32_t rho_cos,
                                        int32_t rho_sin, int32_t bias, int32_t shift,
                                        int32_t *restrict idx)
{
    for (int32_t i = 0; i < n; i++) {
        const int32_t x = (int32_t)(pts[i] & 0xFFFFu), y = (int32_t)(pts[i] >> 16);
        idx[i] = (x * rho_cos + y * rho_sin + bias) >> shift;
    }
}

/* cells[r] += copies[r] + copies[cstep + r] + ... (4 copies) for r < n,
 * and the copies' cells cleared. */
static inline void hough_sum_copies_row(int32_t *restrict cells, uint16_t *restrict copies,
                                        int32_t cstep, int32_t n)
{
    uint16_t *restrict c0 = copies, *restrict c1 = c0 + cstep, *restrict c2 = c1 + cstep,
                       *restrict c3 = c2 + cstep;
    for (int32_t r = 0; r < n; r++) {
        cells[r] += (int32_t)c0[r] + c1[r] + c2[r] + c3[r];
        c0[r] = c1[r] = c2[r] = c3[r] = 0;
    }
}

#endif
