/* Integer helpers shared by the contour feature files (internal). */
#ifndef RTEDGE_ALGO_GEOM_FIXED_H
#define RTEDGE_ALGO_GEOM_FIXED_H

#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/contours.h"
#include "rtedge/shape.h"
#include "rtedge/status.h"

__extension__ typedef __int128 rte_i128;
__extension__ typedef unsigned __int128 rte_u128;

/* floor(sqrt(v)) for any 64-bit v: Newton's iteration from above. */
static inline uint64_t rte_isqrt64(uint64_t v)
{
    if (v < 2)
        return v;
    int bits = 64 - __builtin_clzll(v);
    uint64_t r = (uint64_t)1 << ((bits + 1) / 2); /* >= sqrt(v) */
    for (;;) {
        uint64_t y = (r + v / r) / 2;
        if (y >= r)
            return r;
        r = y;
    }
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

/* 2^shift * w / sqrt(l), rounded to nearest (w^2 * 2^(2 shift + 2) below
 * 2^127): a length in 1/2^shift px when w is a cross or dot product with
 * a vector of squared length l. */
static inline int32_t rte_scaled_len(int64_t w, int64_t l, int shift)
{
    rte_u128 v = ((rte_u128)((rte_u128)w * (rte_u128)w) << (2 * shift + 2)) / (rte_u128)l;
    return (int32_t)((rte_isqrt128(v) + 1) / 2);
}

/* The angle of (x, y) in degrees Q16 for x > 0 (|angle| < 90) or x == 0
 * (+-90), |x|, |y| below 2^26: an integer CORDIC, error below 0.001 degree. */
static inline int32_t rte_atan2_deg_q16(int64_t x, int64_t y)
{
    /* atan(2^-i) in degrees, Q16 */
    static const int32_t atan_q16[24] = {
        2949120, 1740967, 919879, 466945, 234379, 117304, 58666, 29335, 14668, 7334, 3667, 1833,
        917,     458,     229,    115,    57,     29,     14,    7,     4,     2,    1,    0,
    };
    if (x == 0)
        return y >= 0 ? 90 * 65536 : -90 * 65536;
    /* scale up for precision */
    x *= (int64_t)1 << 20;
    y *= (int64_t)1 << 20;
    int64_t z = 0;
    for (int i = 0; i < 24; i++) {
        int64_t xs = x >> i, ys = y >> i;
        if (y > 0) {
            x += ys;
            y -= xs;
            z += atan_q16[i];
        } else {
            x -= ys;
            y += xs;
            z -= atan_q16[i];
        }
    }
    return (int32_t)z;
}

/* The convex hull of pts as points, in a piece of `scratch` that stays
 * taken (the caller resets the arena to its own mark). */
rte_status rte_shape_hull_in_arena(const rte_point *pts, int32_t n, rte_arena *scratch,
                                   rte_point **hull, int32_t *n_hull);

/* rte_shape_min_area_rect and rte_shape_enclosing_circle of a hull
 * already at hand (rte_shape_convex_hull's output, m >= 1 vertices): the
 * same results, without computing it again. The circle shuffles h. */
void rte_shape_min_area_rect_of_hull(const rte_point *hull, int32_t m, rte_rotated_rect *r);
void rte_shape_enclosing_circle_of_hull(rte_point *h, int32_t m, rte_circle *out);

/* rte_shape_calipers with the widths only: each caliper's direction
 * (angle_q16, ux_q16, uy_q16) is left 0 where rte_shape_calipers would
 * compute it, and rte_caliper_direction fills it in for the few a caller
 * needs (most of the time went to directions no one read). The one caliper
 * of a point, a segment or collinear vertices comes complete. */
rte_status rte_shape_caliper_widths(const rte_point *hull, int32_t n, rte_caliper *out,
                                    int32_t *n_out);
/* Fills in the direction of caliper c of hull (n vertices) from
 * rte_shape_caliper_widths; exactly what rte_shape_calipers gives. */
void rte_caliper_direction(const rte_point *hull, int32_t n, rte_caliper *c);

static inline int64_t rte_cross(rte_point o, rte_point a, rte_point b)
{
    return (int64_t)(a.x - o.x) * (b.y - o.y) - (int64_t)(a.y - o.y) * (b.x - o.x);
}

#endif
