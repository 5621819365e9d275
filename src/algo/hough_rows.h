/* The rho bins of one point at every angle (private to src/algo): included
 * by hough_segments.c, which builds it for the baseline target as the C
 * reference, and by simd/hough_x86.c, which builds the same loop for AVX2
 * (the compiler turns it into 32-bit multiplies on 8 angles at a time). On
 * aarch64 the baseline build already vectorises it with NEON. */
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

#endif
