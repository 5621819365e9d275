/* The widths of a convex polygon: rotating calipers. For each edge e the
 * vertex farthest from its line is found by a pointer that only moves
 * forward as the edge turns (the distance along a convex polygon rises,
 * may stay level at its top, then falls), so all n widths take O(n).
 * Distances are exact cross products; only the final lengths, the unit
 * vectors and the angles are rounded. */
#include "rtedge/shape.h"

#include "geom_fixed.h"

/* |cross(e, v - p)| for the polygon's orientation sign s. */
static int64_t dist2x(int s, rte_point p, rte_point q, rte_point v)
{
    return s * rte_cross(p, q, v);
}

/* One caliper's direction: across the edge vector e, l = |e|^2 > 0. */
static void set_direction(rte_caliper *c, rte_point e, int64_t l)
{
    rte_point nrm = {-e.y, e.x};
    /* the line has two directions: the one within (-90, 90] */
    if (nrm.x < 0 || (nrm.x == 0 && nrm.y < 0))
        nrm = (rte_point){-nrm.x, -nrm.y};
    c->angle_q16 = rte_atan2_deg_q16(nrm.x, nrm.y);
    c->ux_q16 = rte_scaled_len(nrm.x, l, 16);
    c->uy_q16 = (nrm.y < 0 ? -1 : 1) * rte_scaled_len(nrm.y, l, 16);
}

/* One caliper: across the edge vector e, `h` = |e| x the distance to
 * the far vertex; the direction only when asked (it takes most of the
 * time). */
static rte_caliper make(int32_t edge, int32_t far, rte_point e, int64_t h, bool direction)
{
    const int64_t l = (int64_t)e.x * e.x + (int64_t)e.y * e.y;
    rte_caliper c = {.edge = edge, .far = far};
    if (l == 0) { /* a single point */
        c.ux_q16 = 65536;
        return c;
    }
    c.width_q8 = rte_scaled_len(h, l, 8);
    if (direction)
        set_direction(&c, e, l);
    return c;
}

static rte_status calipers(const rte_point *hull, int32_t n, rte_caliper *out, int32_t *n_out,
                           bool directions)
{
    if (!hull || !out || !n_out || n < 1)
        return RTE_ERR_ARGUMENT;
    for (int32_t i = 0; i < n; i++)
        if (hull[i].x < -RTE_SHAPE_MAX_COORD || hull[i].x > RTE_SHAPE_MAX_COORD ||
            hull[i].y < -RTE_SHAPE_MAX_COORD || hull[i].y > RTE_SHAPE_MAX_COORD)
            return RTE_ERR_TOO_LARGE;
    *n_out = 0;
    if (n <= 2) {
        /* a point or a segment: no width, across its direction */
        const rte_point e = {hull[n - 1].x - hull[0].x, hull[n - 1].y - hull[0].y};
        out[0] = make(0, 0, e, 0, true);
        *n_out = 1;
        return RTE_OK;
    }
    for (int32_t i = 0; i < n; i++)
        if (hull[i].x == hull[(i + 1) % n].x && hull[i].y == hull[(i + 1) % n].y)
            return RTE_ERR_ARGUMENT; /* a repeated vertex */
    /* the orientation: the sign of the first turn that is not straight */
    int s = 0;
    for (int32_t i = 0; i < n && !s; i++) {
        const int64_t c = rte_cross(hull[i], hull[(i + 1) % n], hull[(i + 2) % n]);
        s = c > 0 ? 1 : c < 0 ? -1 : 0;
    }
    if (!s) { /* every vertex on one line: the segment between its extremes */
        int32_t a = 0, b = 0;
        for (int32_t i = 1; i < n; i++) {
            if (hull[i].x < hull[a].x || (hull[i].x == hull[a].x && hull[i].y < hull[a].y))
                a = i;
            if (hull[i].x > hull[b].x || (hull[i].x == hull[b].x && hull[i].y > hull[b].y))
                b = i;
        }
        const rte_point e = {hull[b].x - hull[a].x, hull[b].y - hull[a].y};
        out[0] = make(a, a, e, 0, true);
        *n_out = 1;
        return RTE_OK;
    }
    int32_t k = 1; /* the far vertex of the current edge, as a count of steps from 0 */
    for (int32_t i = 0; i < n; i++) {
        const rte_point p = hull[i], q = hull[(i + 1) % n];
        if (k < i + 1)
            k = i + 1;
        /* at most one turn round the polygon */
        while (k < i + n && dist2x(s, p, q, hull[(k + 1) % n]) > dist2x(s, p, q, hull[k % n]))
            k++;
        const rte_point v = hull[k % n];
        const rte_point e = {q.x - p.x, q.y - p.y};
        out[i] = make(i, k % n, e, dist2x(s, p, q, v), directions);
    }
    *n_out = n;
    return RTE_OK;
}

rte_status rte_shape_calipers(const rte_point *hull, int32_t n, rte_caliper *out, int32_t *n_out)
{
    return calipers(hull, n, out, n_out, true);
}

rte_status rte_shape_caliper_widths(const rte_point *hull, int32_t n, rte_caliper *out,
                                    int32_t *n_out)
{
    return calipers(hull, n, out, n_out, false);
}

void rte_caliper_direction(const rte_point *hull, int32_t n, rte_caliper *c)
{
    if (c->ux_q16 != 0 || c->uy_q16 != 0)
        return;
    const rte_point p = hull[c->edge], q = hull[(c->edge + 1) % n];
    const rte_point e = {q.x - p.x, q.y - p.y};
    set_direction(c, e, (int64_t)e.x * e.x + (int64_t)e.y * e.y);
}
