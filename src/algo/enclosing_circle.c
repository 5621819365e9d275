/* Minimum enclosing circle: Welzl's incremental algorithm (expected linear
 * time) over the convex hull vertices, in a fixed pseudo-random order so
 * results repeat. Centres are exact rationals (nx / d, ny / d) and the
 * in-circle test is exact in 128 bits. */
#include "rtedge/shape.h"

#include "geom_fixed.h"

typedef struct circ {
    rte_i128 nx, ny, r2; /* centre (nx/d, ny/d), radius^2 = r2 / d^2 */
    int64_t d;
} circ;

static circ circ1(rte_point a) { return (circ){a.x, a.y, 0, 1}; }

static circ circ2(rte_point a, rte_point b)
{
    int64_t dx = (int64_t)a.x - b.x, dy = (int64_t)a.y - b.y;
    return (circ){(rte_i128)a.x + b.x, (rte_i128)a.y + b.y, (rte_i128)(dx * dx + dy * dy), 2};
}

static int64_t dist2(rte_point a, rte_point b)
{
    int64_t dx = (int64_t)a.x - b.x, dy = (int64_t)a.y - b.y;
    return dx * dx + dy * dy;
}

static circ circ3(rte_point a, rte_point b, rte_point c)
{
    const int64_t bx = (int64_t)b.x - a.x, by = (int64_t)b.y - a.y;
    const int64_t cx = (int64_t)c.x - a.x, cy = (int64_t)c.y - a.y;
    int64_t d = 2 * (bx * cy - by * cx);
    if (d == 0) { /* collinear: the farthest pair spans the circle */
        int64_t ab = dist2(a, b), ac = dist2(a, c), bc = dist2(b, c);
        return ab >= ac && ab >= bc ? circ2(a, b) : ac >= bc ? circ2(a, c) : circ2(b, c);
    }
    const int64_t b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    rte_i128 ux = (rte_i128)cy * b2 - (rte_i128)by * c2;
    rte_i128 uy = (rte_i128)bx * c2 - (rte_i128)cx * b2;
    if (d < 0) {
        d = -d;
        ux = -ux;
        uy = -uy;
    }
    return (circ){(rte_i128)a.x * d + ux, (rte_i128)a.y * d + uy, ux * ux + uy * uy, d};
}

static int inside(const circ *c, rte_point p)
{
    rte_i128 dx = (rte_i128)p.x * c->d - c->nx, dy = (rte_i128)p.y * c->d - c->ny;
    return dx * dx + dy * dy <= c->r2;
}

size_t rte_shape_enclosing_circle_scratch_size(int32_t max_points)
{
    return rte_shape_min_area_rect_scratch_size(max_points);
}

void rte_shape_enclosing_circle_of_hull(rte_point *h, int32_t m, rte_circle *out)
{
    /* Fisher-Yates with a fixed xorshift seed: expected linear time,
     * repeatable results. */
    uint32_t seed = 0x9E3779B9u;
    for (int32_t i = m - 1; i > 0; i--) {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        int32_t j = (int32_t)(seed % (uint32_t)(i + 1));
        rte_point t = h[i];
        h[i] = h[j];
        h[j] = t;
    }
    circ c = circ1(h[0]);
    for (int32_t i = 1; i < m; i++) {
        if (inside(&c, h[i]))
            continue;
        c = circ1(h[i]);
        for (int32_t j = 0; j < i; j++) {
            if (inside(&c, h[j]))
                continue;
            c = circ2(h[i], h[j]);
            for (int32_t k = 0; k < j; k++)
                if (!inside(&c, h[k]))
                    c = circ3(h[i], h[j], h[k]);
        }
    }
    out->cx_q8 = (int32_t)rte_div_round128(c.nx * 256, c.d);
    out->cy_q8 = (int32_t)rte_div_round128(c.ny * 256, c.d);
    /* r = sqrt(r2) / d; 2 * 256 r by integer sqrt, then halved with rounding */
    rte_u128 v = ((rte_u128)c.r2 << 18) / ((rte_u128)c.d * (rte_u128)c.d);
    out->r_q8 = (int32_t)((rte_isqrt128(v) + 1) / 2);
}

rte_status rte_shape_enclosing_circle(const rte_point *pts, int32_t n, rte_circle *out,
                                      rte_arena *scratch)
{
    if (!out || n < 1 || !pts || !scratch)
        return RTE_ERR_ARGUMENT;
    *out = (rte_circle){0, 0, 0};
    const size_t mark = rte_arena_mark(scratch);
    rte_point *h = NULL;
    int32_t m = 0;
    rte_status st = rte_shape_hull_in_arena(pts, n, scratch, &h, &m);
    if (st != RTE_OK)
        return st;
    rte_shape_enclosing_circle_of_hull(h, m, out);
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}
