/* Shape features and classes of one contour (see shape.h for the rule). */
#include "rtedge/shape.h"

#include <string.h>

#include "geom_fixed.h"

/* pi and 2 pi in Q16 */
#define PI_Q16 205887
#define TWO_PI_Q16 411775

/* Q16 thresholds of the rule in shape.h */
#define Q16(num, den) ((int32_t)(((int64_t)(num)*65536 + (den) / 2) / (den)))

size_t rte_shape_classify_scratch_size(int32_t max_points)
{
    if (max_points < 0)
        return 0;
    size_t pts = rte_arena_piece_size(((size_t)max_points + 1) * sizeof(rte_point));
    size_t a = rte_shape_hull_scratch_size(max_points);
    size_t b = rte_shape_approx_scratch_size(max_points);
    size_t c = rte_shape_min_area_rect_scratch_size(max_points);
    size_t d = rte_shape_enclosing_circle_scratch_size(max_points);
    size_t m = a > b ? a : b;
    m = m > c ? m : c;
    m = m > d ? m : d;
    return 2 * pts + m;
}

static int32_t ratio_q16(int64_t num, int64_t den)
{
    if (den <= 0)
        return 0;
    rte_i128 q = ((rte_i128)num * 65536 + den / 2) / den;
    return q > INT32_MAX ? INT32_MAX : (int32_t)q;
}

/* 4 pi area / perimeter^2 in Q16, from twice the area and a Q16 length. */
static int32_t circularity(int64_t area2, int64_t per_q16)
{
    if (per_q16 <= 0)
        return 0;
    rte_i128 num = (rte_i128)TWO_PI_Q16 * area2 * ((rte_i128)1 << 32);
    rte_i128 q = (num + ((rte_i128)per_q16 * per_q16) / 2) / ((rte_i128)per_q16 * per_q16);
    return q > INT32_MAX ? INT32_MAX : (int32_t)q;
}

/* area / (pi r^2) of the enclosing circle, Q16 */
static int32_t circle_fill(int64_t area2, int32_t r_q8)
{
    if (r_q8 <= 0)
        return 0;
    rte_i128 den = (rte_i128)PI_Q16 * r_q8 * r_q8;
    rte_i128 q = (((rte_i128)area2 << 47) + den / 2) / den;
    return q > INT32_MAX ? INT32_MAX : (int32_t)q;
}

/* area / area of the minimum-area rectangle, Q16 */
static int32_t box_fill(const rte_shape_info *s)
{
    return ratio_q16(s->area2 * 32768, (int64_t)s->box.length_q8 * s->box.width_q8);
}

static rte_shape_class classify(const rte_shape_info *s)
{
    const int32_t v = s->vertices, c = s->hull_circularity_q16, a = s->aspect_q16;
    if (s->area2 < 32 || s->solidity_q16 < Q16(80, 100))
        return RTE_SHAPE_OTHER;
    if (v == 3)
        return RTE_SHAPE_TRIANGLE;
    if (v == 4 || c < Q16(813, 1000)) {
        if (c < Q16(70, 100) && a < Q16(130, 100))
            return RTE_SHAPE_TRIANGLE;
        /* A triangle with a rounded or blunt corner keeps a fourth vertex;
         * it still fills only about half of its minimum-area box, where a
         * square or rectangle, however hand-drawn, fills most of it. */
        if (box_fill(s) < Q16(70, 100))
            return RTE_SHAPE_TRIANGLE;
        return a <= RTE_SHAPE_SQUARE_ASPECT_Q16 ? RTE_SHAPE_SQUARE : RTE_SHAPE_RECTANGLE;
    }
    /* roundness: mostly hull circularity, a little enclosing-circle fill */
    const int32_t r =
        (int32_t)(((int64_t)c * 86 + (int64_t)circle_fill(s->area2, s->circle.r_q8) * 14 + 50) /
                  100);
    if (v > 6 && r >= RTE_SHAPE_CIRCLE_MIN_Q16)
        return RTE_SHAPE_CIRCLE;
    if (v > 8)
        return RTE_SHAPE_OTHER;
    /* the coarser approximation drops most vertices that noise added */
    const int32_t v2 = s->vertices_coarse;
    const int32_t hex_from = v2 <= 5 ? Q16(868, 1000) : v2 == 6 ? Q16(848, 1000) : Q16(858, 1000);
    return r >= hex_from ? RTE_SHAPE_HEXAGON : RTE_SHAPE_PENTAGON;
}

rte_status rte_shape_classify(const rte_point *pts, int32_t n, rte_shape_info *info,
                              rte_arena *scratch)
{
    if (!info || !pts || n < 1 || !scratch)
        return RTE_ERR_ARGUMENT;
    *info = (rte_shape_info){0};
    const size_t mark = rte_arena_mark(scratch);
    rte_point *hull = rte_arena_alloc(scratch, ((size_t)n + 1) * sizeof *hull);
    rte_point *poly = rte_arena_alloc(scratch, ((size_t)n + 1) * sizeof *poly);
    if (!hull || !poly) {
        rte_arena_reset(scratch, mark);
        return RTE_ERR_NO_MEMORY;
    }
    rte_moments m;
    int32_t nh = 0, nv = 0;
    rte_status st = rte_shape_moments(pts, n, &m);
    if (st == RTE_OK)
        st = rte_shape_convex_hull(pts, n, NULL, hull, &nh, scratch);
    const int64_t per = rte_shape_perimeter_q16(pts, n, 1);
    /* epsilon = 0.02 x perimeter, in Q16 like the perimeter */
    const int64_t eps = (per * 2 + 50) / 100;
    if (st == RTE_OK)
        st = rte_shape_approx_poly(pts, n, (uint32_t)(eps < (1 << 26) ? eps : (1 << 26) - 1), poly,
                                   &nv, scratch);
    if (st == RTE_OK)
        st =
            rte_shape_approx_poly(pts, n, (uint32_t)(2 * eps < (1 << 26) ? 2 * eps : (1 << 26) - 1),
                                  poly, &info->vertices_coarse, scratch);
    if (st != RTE_OK) {
        rte_arena_reset(scratch, mark);
        return st;
    }
    rte_shape_min_area_rect_of_hull(hull, nh, &info->box);
    /* poly is free now: a copy of the hull for the circle to shuffle */
    memcpy(poly, hull, (size_t)nh * sizeof *poly);
    rte_shape_enclosing_circle_of_hull(poly, nh, &info->circle);
    int64_t area2 = rte_shape_area2(pts, n);
    area2 = area2 < 0 ? -area2 : area2;
    int64_t hull_area2 = rte_shape_area2(hull, nh);
    hull_area2 = hull_area2 < 0 ? -hull_area2 : hull_area2;

    info->vertices = nv;
    info->area2 = area2;
    info->perimeter_q16 = per;
    info->bounds = rte_shape_bounding_rect(pts, n);
    info->aspect_q16 =
        info->box.width_q8 > 0 ? ratio_q16(info->box.length_q8, info->box.width_q8) : INT32_MAX;
    info->extent_q16 = ratio_q16(area2, 2 * (int64_t)info->bounds.width * info->bounds.height);
    info->solidity_q16 = ratio_q16(area2, hull_area2);
    info->circularity_q16 = circularity(area2, per);
    info->hull_circularity_q16 = circularity(area2, rte_shape_perimeter_q16(hull, nh, 1));
    info->cx_q16 = m.cx_q16;
    info->cy_q16 = m.cy_q16;
    info->shape = classify(info);
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}
