/* Double markings, per frame (integer only; see docs/lanes.md, "Double
 * lines"): a double centre line (two yellow lines, or a solid beside a
 * dashed one) is one marking, and the lane is reported on its centre.
 *
 * With both sides fitted, the lane's width W(y) is known on every row. A
 * twin of a side's marking is paint (two edges with paint between them,
 * rte_lane_is_ridge) at a distance of LANE_TWIN_MIN..LANE_TWIN_MAX of W
 * beside it, on many rows and on one side of it only. The twin's mean
 * distance, as a share of W, then moves the lane half of it over: in
 * perspective a distance in the road plane is a fixed share of W on every
 * row, so the lane moves by the same share at its bottom and its top. */
#include "lane_fixed.h"

/* The twin lies 5% to 22% of the lane's width beside the marking: two
 * lines 0.3 to 0.5 m apart (centre to centre) in a 2.5 to 4 m lane. */
#define LANE_TWIN_MIN_Q16 3277  /* 0.05 */
#define LANE_TWIN_MAX_Q16 14418 /* 0.22 */

typedef struct twin_count {
    int32_t rows;
    int64_t share_q16; /* sum of the twin's distance / W over those rows */
} twin_count;

/* Paint at distances LANE_TWIN_MIN..MAX of the width w (px) from x (1/256
 * px) on row y, towards dir (-1 left, +1 right): adds the row to *t. */
static void look_beside(const lane_maps *maps, int32_t y, int64_t x_q8, int64_t w, int dir,
                        int64_t slope_q16, twin_count *t)
{
    const int64_t near = (w * LANE_TWIN_MIN_Q16) >> 16, far = (w * LANE_TWIN_MAX_Q16) >> 16;
    const int64_t x = (x_q8 + 128) >> 8;
    const int64_t xa = dir > 0 ? x + near : x - far, xb = dir > 0 ? x + far : x - near;
    band_pixels px;
    if (far - near < 2 ||
        !rte_lane_paint_row(maps, y, xa - maps->cx0, xb - maps->cx0, slope_q16, &px))
        return;
    const int64_t twin_q8 = ((px.first + px.last + 2 * (int64_t)maps->cx0) * 128) - x_q8;
    t->rows++;
    t->share_q16 += rte_abs64(twin_q8) * 256 / w;
}

void rte_lane_double_centre(const lane_maps *maps, const lane_fit_hint *hint, const bool seen[2],
                            lane_line line[2], const lane_curve curve[2])
{
    if (!seen[RTE_LANE_LEFT] || !seen[RTE_LANE_RIGHT])
        return;
    const int32_t y_top = hint->y_top, y_bottom = hint->y_bottom;
    const int32_t y0 = y_top > maps->cy0 ? y_top : maps->cy0;
    const int32_t y1 = y_bottom < maps->cy0 + maps->edges->height - 1
                           ? y_bottom
                           : maps->cy0 + maps->edges->height - 1;
    const rte_lane lanes[2] = {
        lane_of_line(&line[0], curve[0].bow_q8, curve[0].y_horizon, y_top, y_bottom),
        lane_of_line(&line[1], curve[1].bow_q8, curve[1].y_horizon, y_top, y_bottom)};
    int64_t move[2][2] = {{0, 0}, {0, 0}}; /* per side: at the bottom and the top row */
    for (int side = 0; side < 2; side++) {
        twin_count beside[2] = {{0, 0}, {0, 0}}; /* [0] to the left, [1] to the right */
        int32_t rows = 0;
        for (int32_t y = y1; y > y0; y--) {
            const int64_t xl = rte_lane_x_q8(&lanes[0], y);
            const int64_t xr = rte_lane_x_q8(&lanes[1], y);
            const int64_t w = (xr - xl) >> 8;
            if (w < 16)
                continue;
            const int64_t x = side == RTE_LANE_LEFT ? xl : xr;
            const int64_t slope = (rte_lane_x_q8(&lanes[side], y + 1) - x) * 256;
            look_beside(maps, y, x, w, -1, slope, &beside[0]);
            look_beside(maps, y, x, w, +1, slope, &beside[1]);
            rows++;
        }
        /* The twin on one side only, on a third of the rows at least, and
         * on four times as many rows as anything on the other side. */
        const int dir = beside[1].rows > beside[0].rows ? 1 : 0;
        const twin_count *t = &beside[dir], *other = &beside[1 - dir];
        if (rows == 0 || 3 * t->rows < rows || t->rows < 4 * other->rows)
            continue;
        const int64_t share_q16 = t->share_q16 / t->rows; /* the twin's distance / W */
        /* Half of it over, as a share of W at both ends of the line. */
        const int64_t half = (dir ? share_q16 : -share_q16) / 2;
        const int64_t wb = lane_line_x_q8(&line[1], y_bottom) - lane_line_x_q8(&line[0], y_bottom);
        const int64_t wt = lane_line_x_q8(&line[1], y_top) - lane_line_x_q8(&line[0], y_top);
        move[side][0] = (wb * half) >> 16;
        move[side][1] = (wt * half) >> 16;
    }
    for (int side = 0; side < 2; side++) {
        if (move[side][0] == 0 && move[side][1] == 0)
            continue;
        const int64_t xb = lane_line_x_q8(&line[side], y_bottom) + move[side][0];
        const int64_t xt = lane_line_x_q8(&line[side], y_top) + move[side][1];
        line[side].y_mid = y_bottom;
        line[side].x_mid_q8 = xb;
        line[side].slope_q16 = y_bottom > y_top ? (xt - xb) * 256 / (y_top - y_bottom) : 0;
    }
}
