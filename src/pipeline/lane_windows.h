/* What the lane curve's two files share (integer only): lane_windows.c
 * measures each marking up the image in windows, lane_curve.c fits the
 * curve model to them (see lane_curve.c for the model). */
#ifndef RTEDGE_PIPELINE_LANE_WINDOWS_H
#define RTEDGE_PIPELINE_LANE_WINDOWS_H

#include "lane_fixed.h"

#define CURVE_WINDOWS 12
/* Rows traced above the last window (trace_up), every CURVE_TRACE_STEP. */
#define CURVE_TRACE_MAX 16
#define CURVE_TRACE_STEP 4

typedef struct curve_window {
    int64_t r_q8;   /* mean residual to the line, 1/256 px */
    int64_t y;      /* mean row */
    int64_t x_q8;   /* the line's x there plus r: where the paint is */
    int64_t weight; /* edge pixels */
} curve_window;

/* The model's basis at a row: u = (y_bottom - y) / span, q = d_top / d
 * (1 on the top row) and delta = d / d_bottom (1 on the bottom row), all
 * in 1/65536. */
typedef struct curve_basis {
    int64_t u_q16, q_q16, delta_q16;
} curve_basis;

/* The windows of one side, up from the bottom row. */
typedef struct curve_side {
    curve_window win[CURVE_WINDOWS + CURVE_TRACE_MAX];
    curve_basis bs[CURVE_WINDOWS + CURVE_TRACE_MAX];
    int32_t n;
    int32_t y_supported;
} curve_side;

/* The model's bases at row y: delta (d / d_bottom) alone, and all three. */
static inline int64_t delta_at(const lane_fit_hint *h, int64_t y)
{
    const int64_t y_h = lane_horizon_row(h), d = y - y_h > 1 ? y - y_h : 1;
    return d * 65536 / (h->y_bottom - y_h);
}

static inline curve_basis basis_at(const lane_fit_hint *h, int64_t y)
{
    const int64_t span = h->y_bottom - h->y_top, y_h = lane_horizon_row(h);
    const int64_t d = y - y_h > 1 ? y - y_h : 1;
    return (curve_basis){(h->y_bottom - y) * 65536 / span, (h->y_top - y_h) * 65536 / d,
                         delta_at(h, y)};
}

/* The windows of one side up the image from the bottom row, around its
 * straight fit `line`, then the marking traced above the last one. */
void rte_lane_walk_side(const lane_maps *maps, const lane_fit_hint *hint, const lane_line *line,
                        curve_side *cs);

#endif
