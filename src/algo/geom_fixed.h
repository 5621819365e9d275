/* Integer helpers shared by the contour feature files (internal). */
#ifndef RTEDGE_ALGO_GEOM_FIXED_H
#define RTEDGE_ALGO_GEOM_FIXED_H

#include <stdint.h>

#include "rtedge/contours.h"

__extension__ typedef __int128 rte_i128;
__extension__ typedef unsigned __int128 rte_u128;

/* floor(sqrt(v)) for any 64-bit v (digit-by-digit, no floating point). */
static inline uint64_t rte_isqrt64(uint64_t v)
{
    uint64_t r = 0, bit = (uint64_t)1 << 62;
    while (bit > v)
        bit >>= 2;
    while (bit) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r;
}

/* floor(sqrt(v)) for a 128-bit v. */
static inline rte_u128 rte_isqrt128(rte_u128 v)
{
    rte_u128 r = 0, bit = (rte_u128)1 << 126;
    while (bit > v)
        bit >>= 2;
    while (bit) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r;
}

/* sqrt(v) rounded to nearest (v < 2^62). */
static inline uint64_t rte_isqrt64_round(uint64_t v)
{
    uint64_t r = rte_isqrt64(v);
    /* round up when v >= (r + 0.5)^2 = r^2 + r + 0.25 */
    return v > r * r + r ? r + 1 : r;
}

/* n / d rounded to nearest, ties away from zero; d > 0. */
static inline rte_i128 rte_div_round128(rte_i128 n, rte_i128 d)
{
    return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

static inline int64_t rte_cross(rte_point o, rte_point a, rte_point b)
{
    return (int64_t)(a.x - o.x) * (b.y - o.y) - (int64_t)(a.y - o.y) * (b.x - o.x);
}

#endif
