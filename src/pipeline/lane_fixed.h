/* Fixed-point helpers the per-frame lane files share (integer only):
 * clamps, a safe Q16 division, points of fitted lines and the row weights
 * of the segment fit (lane_fit.c) and the refit on the edge pixels
 * (lane_refine.c). */
#ifndef RTEDGE_PIPELINE_LANE_FIXED_H
#define RTEDGE_PIPELINE_LANE_FIXED_H

#include <stdint.h>

#include "core/int_math.h"
#include "lane_internal.h"

static inline int32_t lane_clamp32(int64_t v, int64_t lo, int64_t hi)
{
    return (int32_t)(v < lo ? lo : v > hi ? hi : v);
}

/* num * 65536 / den (den > 0), without overflow for any 62-bit inputs. */
static inline int64_t lane_div_q16(int64_t num, int64_t den)
{
    while (rte_abs64(num) >= ((int64_t)1 << 46) || den >= ((int64_t)1 << 46)) {
        num /= 2;
        den /= 2;
    }
    return den > 0 ? num * 65536 / den : 0;
}

/* x of a line at row y, in 1/256 pixel. */
static inline int64_t lane_line_x_q8(const lane_line *l, int64_t y)
{
    return l->x_mid_q8 + ((l->slope_q16 * (y - l->y_mid)) >> 8);
}

/* A fitted line with a bow (lane_curve) as a lane over rows y_top..y_bottom
 * (x clamped so far-off extrapolations stay in range), for rte_lane_x_q8. */
static inline rte_lane lane_of_line(const lane_line *l, int64_t bow_q8, int32_t y_horizon,
                                    int32_t y_top, int32_t y_bottom)
{
    const int64_t lim = 1 << 28;
    return (rte_lane){.x_bottom_q8 = lane_clamp32(lane_line_x_q8(l, y_bottom), -lim, lim),
                      .x_top_q8 = lane_clamp32(lane_line_x_q8(l, y_top), -lim, lim),
                      .y_bottom = y_bottom,
                      .y_top = y_top,
                      .bow_q8 = lane_clamp32(bow_q8, -lim, lim),
                      .y_horizon = y_horizon};
}

/* x of a lane's chord (its bottom end to its top end) at row y, 1/256 px. */
static inline int64_t lane_chord_x_q8(const rte_lane *l, int64_t y)
{
    const int64_t span = l->y_bottom - l->y_top;
    if (span <= 0)
        return l->x_bottom_q8;
    return l->x_bottom_q8 + ((int64_t)l->x_top_q8 - l->x_bottom_q8) * (l->y_bottom - y) / span;
}

/* The line through (x_bottom, y_bottom) and (x_top, y_top): lane_of_line's
 * inverse for a lane without bow. */
static inline lane_line lane_line_of_chord(int64_t x_bottom_q8, int64_t x_top_q8, int32_t y_top,
                                           int32_t y_bottom)
{
    const int64_t span = y_bottom - y_top;
    return (lane_line){x_bottom_q8, span > 0 ? (x_top_q8 - x_bottom_q8) * 256 / -span : 0,
                       y_bottom};
}

/* The rows a side needs paint on to count as seen: a sixteenth of the
 * lane's. */
static inline int32_t lane_min_rows(const rte_lane *lane)
{
    return (lane->y_bottom - lane->y_top) / 16 + 1;
}

/* Rows from the ROI's top row down to y, within the lane's span. */
static inline int64_t lane_rows_below_top(const lane_fit_hint *h, int64_t y)
{
    const int64_t span = h->y_bottom - h->y_top, d = y - h->y_top;
    return d < 0 || span <= 0 ? 0 : d > span ? span : d;
}

/* The horizon row of the curve model: the hint's when it has one, else an
 * eighth of the lane above the ROI's top row (where the default
 * trapezoid's sides meet). */
static inline int64_t lane_horizon_row(const lane_fit_hint *h)
{
    if (h->has_horizon && h->y_horizon < h->y_top)
        return h->y_horizon;
    return h->y_top - ((h->y_bottom - h->y_top) / 8 + 1);
}

/* How much brighter paint is than the road beside it, in grey levels
 * (rte_lane_is_ridge, the double line's gap, the segments' paint weights). */
#define LANE_RIDGE_MIN 12
/* A grey level this bright is glare (or may be): it tells nothing of paint. */
#define LANE_SATURATED 250

/* A segment's weight by its row, /256: the inverse variance of a pixel's
 * lateral position on the road, which grows as (distance from the horizon)^2
 * in perspective (the horizon taken an eighth of the lane above the ROI
 * top). The lane near the camera is measured best and matters most: on a
 * bend, far dashes must not turn the lane away from the near ones. */
static inline int64_t lane_row_weight_q8(const lane_fit_hint *h, int64_t y)
{
    const int64_t span = h->y_bottom - h->y_top, q = span / 8 + 1, d = lane_rows_below_top(h, y);
    if (span <= 0)
        return 256;
    return 256 * (d + q) * (d + q) / ((span + q) * (span + q)) + 1;
}

#endif
