/* The fixed-level threshold row built for AVX2: the same C loops as the
 * reference (src/algo/threshold_rows.h), vectorised by the compiler as
 * byte compares and blends on 32 pixels. Same bytes. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "algo/threshold_rows.h"

void rte_threshold_row_avx2(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                            uint8_t maxval)
{
    threshold_row(s, d, n, type, t, maxval);
}

#endif
