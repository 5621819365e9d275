/* The rho bins of a point built for AVX2: the same C loop as the reference
 * (src/algo/hough_rows.h), vectorised by the compiler with 32-bit multiplies
 * on 8 angles. Same values. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "algo/hough_rows.h"

void rte_hough_bins_avx2(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n, int32_t x, int32_t y,
                         int32_t bias, int32_t shift, const int32_t *row_base, int32_t *idx)
{
    hough_bins_row(rho_cos, rho_sin, n, x, y, bias, shift, row_base, idx);
}

#endif
