/* The rho bins of a point for AVX2: the C reference's loop
 * (src/algo/hough_rows.h) with 32-bit multiplies on 8 angles.
 * Compiler-vectorised, no intrinsics: built with -mavx2 -O3 whatever the
 * build type (src/meson.build: rtedge_simd_autovec). Safe because the loops
 * are integer only, so vectorising them only reorders exact operations and
 * the bytes stay the C reference's. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/hough_rows.h"

void rte_hough_bins_avx2(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n, int32_t x,
                         int32_t y, int32_t bias, int32_t shift, const int32_t *row_base,
                         int32_t *idx)
{
    hough_bins_row(rho_cos, rho_sin, n, x, y, bias, shift, row_base, idx);
}

#endif
