/* Minimum-area rotated rectangle: rotating calipers over the convex hull.
 * Each hull edge e defines a rectangle with one side along e; its area is
 * (dot_max - dot_min) * cross_max / |e|^2, compared exactly in 128 bits.
 * The angle comes from an integer CORDIC (geom_fixed.h). */
#include "rtedge/shape.h"

#include "geom_fixed.h"

size_t rte_shape_min_area_rect_scratch_size(int32_t max_points)
{
    if (max_points < 0)
        return 0;
    return rte_shape_hull_scratch_size(max_points) +
           rte_arena_piece_size(((size_t)max_points + 1) * sizeof(rte_point));
}

static int64_t dot(rte_point e, rte_point a, rte_point b)
{
    return (int64_t)e.x * (b.x - a.x) + (int64_t)e.y * (b.y - a.y);
}

static int64_t crs(rte_point e, rte_point a, rte_point b)
{
    return (int64_t)e.x * (b.y - a.y) - (int64_t)e.y * (b.x - a.x);
}

/* 256 * v / l rounded, for the corner offsets. */
static int32_t q8_div(rte_i128 v, rte_i128 l) { return (int32_t)rte_div_round128(v * 256, l); }

static void fill_rect(rte_rotated_rect *r, rte_point p, rte_point e, int64_t dmin, int64_t dmax,
                      int64_t h, int64_t l)
{
    const rte_point nrm = {-e.y, e.x};
    const int64_t w = dmax - dmin;
    const int along_e = w >= h;
    /* u: the long side's direction, turned into x > 0 (or straight down) */
    rte_point u = along_e ? e : nrm;
    int flip = u.x < 0 || (u.x == 0 && u.y < 0);
    if (flip)
        u = (rte_point){-u.x, -u.y};
    r->angle_q16 = rte_atan2_deg_q16(u.x, u.y);
    r->length_q8 = rte_scaled_len(along_e ? w : h, l, 8);
    r->width_q8 = rte_scaled_len(along_e ? h : w, l, 8);
    r->cx_q8 =
        p.x * 256 + q8_div((rte_i128)e.x * (dmin + dmax) + (rte_i128)nrm.x * h, 2 * (rte_i128)l);
    r->cy_q8 =
        p.y * 256 + q8_div((rte_i128)e.y * (dmin + dmax) + (rte_i128)nrm.y * h, 2 * (rte_i128)l);
    for (int amax = 0; amax < 2; amax++) {
        for (int bh = 0; bh < 2; bh++) {
            int64_t a = amax ? dmax : dmin, b = bh ? h : 0;
            int su, sv;
            if (along_e) {
                su = flip ? !amax : amax;
                sv = flip ? !bh : bh;
            } else {
                su = flip ? !bh : bh;
                sv = flip ? amax : !amax;
            }
            /* boxPoints order: (-u,+v) (-u,-v) (+u,-v) (+u,+v) */
            int slot = su ? (sv ? 3 : 2) : (sv ? 0 : 1);
            r->corners_q8[slot][0] = p.x * 256 + q8_div((rte_i128)e.x * a + (rte_i128)nrm.x * b, l);
            r->corners_q8[slot][1] = p.y * 256 + q8_div((rte_i128)e.y * a + (rte_i128)nrm.y * b, l);
        }
    }
}

void rte_shape_min_area_rect_of_hull(const rte_point *hull, int32_t m, rte_rotated_rect *r)
{
    *r = (rte_rotated_rect){0};
    if (m == 1) {
        for (int k = 0; k < 4; k++) {
            r->corners_q8[k][0] = hull[0].x * 256;
            r->corners_q8[k][1] = hull[0].y * 256;
        }
        r->cx_q8 = hull[0].x * 256;
        r->cy_q8 = hull[0].y * 256;
    } else if (m == 2) {
        rte_point e = {hull[1].x - hull[0].x, hull[1].y - hull[0].y};
        int64_t l = (int64_t)e.x * e.x + (int64_t)e.y * e.y;
        fill_rect(r, hull[0], e, 0, l, 0, l);
    } else {
        /* r <= k <= l as hull positions: max along e, max across e, min
         * along e; each only moves forward as the edge turns. */
        int64_t ir = 1, ik = 1, il = 1;
        int have = 0;
        rte_i128 best_wh = 0, best_l = 1;
        rte_point best_p = hull[0], best_e = hull[0];
        int64_t best_dmin = 0, best_dmax = 0, best_h = 0;
        for (int32_t i = 0; i < m; i++) {
            const rte_point p = hull[i], q = hull[(i + 1) % m];
            const rte_point e = {q.x - p.x, q.y - p.y};
            const int64_t l = (int64_t)e.x * e.x + (int64_t)e.y * e.y;
            if (ir < i + 1)
                ir = i + 1;
            while (dot(e, p, hull[(ir + 1) % m]) > dot(e, p, hull[ir % m]))
                ir++;
            if (ik < ir)
                ik = ir;
            while (crs(e, p, hull[(ik + 1) % m]) > crs(e, p, hull[ik % m]))
                ik++;
            if (il < ik)
                il = ik;
            while (dot(e, p, hull[(il + 1) % m]) < dot(e, p, hull[il % m]))
                il++;
            const int64_t dmax = dot(e, p, hull[ir % m]), dmin = dot(e, p, hull[il % m]);
            const int64_t h = crs(e, p, hull[ik % m]);
            const rte_i128 wh = (rte_i128)(dmax - dmin) * h;
            if (!have || wh * best_l < best_wh * l) {
                have = 1;
                best_wh = wh;
                best_l = l;
                best_p = p;
                best_e = e;
                best_dmin = dmin;
                best_dmax = dmax;
                best_h = h;
            }
        }
        fill_rect(r, best_p, best_e, best_dmin, best_dmax, best_h, (int64_t)best_l);
    }
}

rte_status rte_shape_min_area_rect(const rte_point *pts, int32_t n, rte_rotated_rect *r,
                                   rte_arena *scratch)
{
    if (!r || n < 1 || !pts || !scratch)
        return RTE_ERR_ARGUMENT;
    *r = (rte_rotated_rect){0};
    const size_t mark = rte_arena_mark(scratch);
    rte_point *hull = NULL;
    int32_t m = 0;
    rte_status st = rte_shape_hull_in_arena(pts, n, scratch, &hull, &m);
    if (st != RTE_OK)
        return st;
    rte_shape_min_area_rect_of_hull(hull, m, r);
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}
