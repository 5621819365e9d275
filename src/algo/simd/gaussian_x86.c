/* The Gaussian blur's row kernels built for AVX2: the same C loops as the
 * reference (src/algo/gaussian_rows.h), vectorised by the compiler in
 * 16-bit lanes of 256-bit registers. Same integer operations, same bytes. */
#include <stdint.h>
#include <string.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "algo/gaussian_rows.h"

void rte_gaussian_column_pass_avx2(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,
                                   int32_t width, const uint16_t *taps, int32_t ksize, int split)
{
    gaussian_column_pass(rows, hi, lo, width, taps, ksize, split);
}

void rte_gaussian_row_pass_avx2(const uint16_t *hi, const uint16_t *lo, uint8_t *dst,
                                int32_t width, const uint16_t *taps, int32_t ksize, int split)
{
    gaussian_row_pass(hi, lo, dst, width, taps, ksize, split);
}

#endif
