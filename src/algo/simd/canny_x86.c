/* Canny's row kernels (aperture 3, L1) built for AVX2: the same C loops as
 * the reference (src/algo/canny_rows.h), vectorised by the compiler in
 * 16-bit lanes of 256-bit registers (the sector test's multiply becomes
 * vpmulhuw). Same integer operations, same bytes. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "../canny_rows.h"

void rte_canny_sobel_row_avx2(const uint8_t *up, const uint8_t *mid, const uint8_t *down,
                              int16_t *dx, int16_t *dy, int16_t *mag, int32_t width)
{
    canny_sobel_row(up, mid, down, dx, dy, mag, width);
}

void rte_canny_nms_row_avx2(const int16_t *up, const int16_t *cur, const int16_t *down,
                            const int16_t *dx, const int16_t *dy, uint8_t *map, int32_t width,
                            int16_t low, int16_t high)
{
    canny_nms_row(up, cur, down, dx, dy, map, width, low, high);
}

#endif
