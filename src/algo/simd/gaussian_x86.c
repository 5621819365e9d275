/* The Gaussian blur's row kernels for AVX2 and AVX-512: the C reference's
 * loops (src/algo/gaussian_rows.h) in 16-bit lanes of 256-bit or 512-bit
 * registers; compiler-vectorised (rows.h). */
#include <stdint.h>
#include <string.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/gaussian_rows.h"

void RTE_SIMD_NAME(rte_gaussian_column_pass)(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,
                                             int32_t width, const uint16_t *taps, int32_t ksize,
                                             int split)
{
    gaussian_column_pass(rows, hi, lo, width, taps, ksize, split);
}

void RTE_SIMD_NAME(rte_gaussian_row_pass)(const uint16_t *hi, const uint16_t *lo, uint8_t *dst,
                                          int32_t width, const uint16_t *taps, int32_t ksize,
                                          int split)
{
    gaussian_row_pass(hi, lo, dst, width, taps, ksize, split);
}

#endif
