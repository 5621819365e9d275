/* Reporting a lane (see include/rtedge/lane.h): its polyline and the
 * curvature of its image curve. Not per-frame code: the curvature needs
 * floating point, which the per-frame lane files do not use. */
#include <math.h>

#include "lane_fixed.h"

/* The highest row the points reach without a far trace: where the
 * markings were seen, the ROI's top for a predicted lane or one seen only
 * by its segments. */
static int32_t lane_end_row(const rte_lane *l)
{
    return l->predicted || l->y_supported >= l->y_bottom - RTE_LANE_POINT_STEP ? l->y_top
                                                                               : l->y_supported;
}

int32_t rte_lane_polyline(const rte_lane *l, int32_t max_points, int32_t *x_q8, int32_t *y)
{
    if (!l || !l->found || max_points < 2 || !x_q8 || !y)
        return 0;
    /* the far trace's points (the last of them when too many), with the
     * curve's points below its first row: one at least */
    int32_t far = l->far_count >= 2 && l->far_count <= RTE_LANE_FAR_POINTS ? l->far_count : 0;
    far = far < max_points - 1 ? far : max_points - 1;
    const int32_t curve_points = max_points - far;
    const int32_t end = far > 0 ? l->far_y[0] : lane_end_row(l), length = l->y_bottom - end;
    /* every RTE_LANE_POINT_STEP rows, or more when the points are too few */
    int32_t step = curve_points > 1 ? (length + curve_points - 2) / (curve_points - 1) : length;
    step = step < RTE_LANE_POINT_STEP ? RTE_LANE_POINT_STEP : step;
    int32_t n = 0;
    if (far == 0) {
        for (int32_t row = l->y_bottom; n < curve_points; row -= step) {
            /* the end replaces a point less than half a step from it: a last
             * piece of a row or two would hand a reader who extends the lane
             * beyond its end the direction of a pixel's rounding */
            row = row < end || (n > 0 && row - end < step / 2) ? end : row;
            x_q8[n] = rte_lane_x_q8(l, row);
            y[n++] = row;
            if (row == end)
                break;
        }
        return n;
    }
    for (int32_t row = l->y_bottom; n < curve_points && row > end; row -= step) {
        x_q8[n] = rte_lane_x_q8(l, row);
        y[n++] = row;
    }
    for (int32_t i = l->far_count - far; i < l->far_count; i++) {
        x_q8[n] = l->far_x_q8[i];
        y[n++] = l->far_y[i];
    }
    return n;
}

double rte_lane_curvature(const rte_lane *l)
{
    const double span = l->y_bottom - l->y_top;
    if (!l->found || span <= 0 || l->bow_q8 == 0)
        return 0;
    /* x(y) = chord(y) + k sag(y), sag = q - its chord, q = d_top / d with d
     * the rows below the horizon (as rte_lane_x_q8) */
    const lane_fit_hint h = {l->y_top, l->y_bottom, 0, 0, l->y_horizon, true};
    const double y_h = (double)lane_horizon_row(&h), d_top = l->y_top - y_h;
    const double d_b = l->y_bottom - y_h, d_m = l->y_bottom - (int32_t)(span / 2) - y_h;
    const double q_b = d_top / d_b, sag_mid = d_top / d_m - (q_b + 1) / 2;
    if (sag_mid >= 0)
        return 0;
    const double k = l->bow_q8 / 256.0 / sag_mid;
    const double dx_dy = -(l->x_top_q8 - l->x_bottom_q8) / 256.0 / span +
                         k * (-d_top / (d_b * d_b) + (1 - q_b) / span);
    const double d2x_dy2 = k * 2 * d_top / (d_b * d_b * d_b);
    /* going up the image: dx/dv = -dx/dy, d2x/dv2 = d2x/dy2 */
    return d2x_dy2 / pow(1 + dx_dy * dx_dy, 1.5);
}
