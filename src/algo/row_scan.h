/* Row scans eight bytes at a time, for per-frame kernels that spend most
 * of their time crossing runs of one value (contour following, region
 * labelling). Internal to src/algo. */
#ifndef RTE_ALGO_ROW_SCAN_H
#define RTE_ALGO_ROW_SCAN_H

#include <stdint.h>
#include <string.h>

/* The first x1 in [x, end) with row[x1] != value, or end. */
static inline int32_t rte_row_skip_run(const uint8_t *row, int32_t x, int32_t end, uint8_t value)
{
    const uint64_t pattern = value * UINT64_C(0x0101010101010101);
    for (; x + 8 <= end; x += 8) {
        uint64_t v;
        memcpy(&v, row + x, sizeof v);
        v ^= pattern;
        if (v) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
            return x + (__builtin_ctzll(v) >> 3);
#else
            break;
#endif
        }
    }
    while (x < end && row[x] == value)
        x++;
    return x;
}

#endif
