/* Fixed-level threshold of one row (private to src/algo): included by
 * threshold.c, which builds it for the baseline target as the C reference,
 * and by simd/threshold_x86.c, which builds the same loops for AVX2 (the
 * compiler turns each into byte compares and selects, 32 pixels at a
 * time). simd/threshold_neon.c writes them with NEON intrinsics. */
#ifndef RTEDGE_ALGO_THRESHOLD_ROWS_H
#define RTEDGE_ALGO_THRESHOLD_ROWS_H

#include <stdint.h>

#include "rtedge/threshold.h"

/* Plain loops over bytes without branches. No restrict: s == d (in
 * place) is allowed. */
static inline void threshold_row(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                                 uint8_t maxval)
{
    switch (type) {
    case RTE_THRESH_BINARY:
        for (int32_t x = 0; x < n; x++)
            d[x] = s[x] > t ? maxval : 0;
        break;
    case RTE_THRESH_BINARY_INV:
        for (int32_t x = 0; x < n; x++)
            d[x] = s[x] > t ? 0 : maxval;
        break;
    case RTE_THRESH_TRUNC:
        for (int32_t x = 0; x < n; x++)
            d[x] = s[x] > t ? t : s[x];
        break;
    case RTE_THRESH_TOZERO:
        for (int32_t x = 0; x < n; x++)
            d[x] = s[x] > t ? s[x] : 0;
        break;
    default: /* RTE_THRESH_TOZERO_INV */
        for (int32_t x = 0; x < n; x++)
            d[x] = s[x] > t ? 0 : s[x];
        break;
    }
}

#endif
