/* The rho bins of a point at many angles (segments, 32-bit multiplies on 8
 * or 16 angles) and the sum of the lines' vote copies (8 or 16 cells at a
 * time) for AVX2 and AVX-512: the C references' loops
 * (src/algo/hough_rows.h); compiler-vectorised (rows.h). */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/hough_rows.h"

void RTE_SIMD_NAME(rte_hough_bins)(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n,
                                   int32_t x, int32_t y, int32_t bias, int32_t shift,
                                   const int32_t *row_base, int32_t *idx)
{
    hough_bins_row(rho_cos, rho_sin, n, x, y, bias, shift, row_base, idx);
}

void RTE_SIMD_NAME(rte_hough_sum_copies)(int32_t *cells, uint16_t *copies, int32_t cstep, int32_t n)
{
    hough_sum_copies_row(cells, copies, cstep, n);
}

#endif
