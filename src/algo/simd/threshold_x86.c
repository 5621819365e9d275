/* The fixed-level threshold row for AVX2 and AVX-512: the C reference's
 * loops (src/algo/threshold_rows.h) as byte compares and blends on 32 or 64
 * pixels; compiler-vectorised (rows.h). */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/threshold_rows.h"

void RTE_SIMD_NAME(rte_threshold_row)(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                                      uint8_t maxval)
{
    threshold_row(s, d, n, type, t, maxval);
}

#endif
