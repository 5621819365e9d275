/* Lane detection, per frame (integer only: built with -mgeneral-regs-only):
 * the parameters, the ROI and the stages in order, with their timings;
 * the stages' own work is in lane_cue.c, lane_fit.c, lane_refine.c,
 * lane_windows.c, lane_curve.c, lane_double.c, lane_track.c and
 * lane_trace.c. The stages and the reasons for them are in
 * include/rtedge/lane.h and docs/lanes.md. */
#include <string.h>
#include <time.h>

#include "algo/geom_fixed.h"
#include "lane_fixed.h"
#include "rtedge/color.h"
#include "rtedge/polygon_mask.h"
#include "core/clock.h"

const char *rte_lane_stage_name(rte_lane_stage stage)
{
    static const char *const names[RTE_LANE_STAGES] = {"gray", "blur", "canny", "hough", "fit"};
    return (unsigned)stage < RTE_LANE_STAGES ? names[stage] : "unknown";
}

static bool in_range(int32_t v, int32_t lo, int32_t hi) { return v >= lo && v <= hi; }

rte_status rte_lane_set_params(rte_lane_context *ctx, const rte_lane_params *p)
{
    if (!ctx || !p || !in_range(p->roi_count, 3, RTE_LANE_MAX_ROI_VERTICES) ||
        !in_range((int32_t)p->canny_mode, 0, 2) || !in_range(p->canny_low, 0, 2040) ||
        !in_range(p->canny_high, 0, 2040) || p->canny_low > p->canny_high ||
        !in_range(p->auto_sigma_permille, 0, 10000) || !in_range(p->white_min, 0, 256) ||
        !in_range(p->yellow_rg_min, 0, 256) || !in_range(p->yellow_b_margin, 0, 255) ||
        !in_range(p->dim_q8, 0, 256) || !in_range(p->hough_threshold, 1, 1 << 20) ||
        !in_range(p->min_length, 0, 1 << 20) || !in_range(p->max_gap, 0, 1 << 20) ||
        !in_range(p->left_min_slope_q8, 1, 1 << 20) ||
        p->left_max_slope_q8 < p->left_min_slope_q8 ||
        !in_range(p->right_min_slope_q8, 1, 1 << 20) ||
        p->right_max_slope_q8 < p->right_min_slope_q8 || p->left_max_slope_q8 > (1 << 20) ||
        p->right_max_slope_q8 > (1 << 20) || !in_range((int32_t)p->fit, 0, 1) ||
        !in_range(p->outlier_px, 0, 1 << 14) || !in_range(p->min_support_px, 0, 1 << 20) ||
        !in_range(p->gate_px, 0, 1 << 14) || !in_range(p->hold_frames, 0, 1 << 20) ||
        !in_range(p->alpha_q8, 1, 256) || !in_range(p->beta_q8, 0, 256) ||
        !in_range(p->max_step_px, 1, 1 << 14))
        return RTE_ERR_ARGUMENT;
    for (int32_t i = 0; i < p->roi_count; i++)
        if (!in_range(p->roi[i].x, -RTE_POLYGON_MAX_FRACTION, RTE_POLYGON_MAX_FRACTION) ||
            !in_range(p->roi[i].y, -RTE_POLYGON_MAX_FRACTION, RTE_POLYGON_MAX_FRACTION))
            return RTE_ERR_ARGUMENT;
    ctx->params = *p;
    ctx->roi_dirty = true;
    return RTE_OK;
}

void rte_lane_reset(rte_lane_context *ctx)
{
    if (ctx) {
        memset(ctx->track, 0, sizeof ctx->track);
        ctx->width_valid = false;
    }
}

/* A view of rows y0..y1-1, columns x0..x1-1 of img. */
static rte_image_u8 lane_view(const rte_image_u8 *img, int32_t x0, int32_t y0, int32_t x1,
                              int32_t y1)
{
    rte_image_u8 v = {x1 - x0, y1 - y0, img->stride,
                      img->buf + (size_t)y0 * (size_t)img->stride + (size_t)x0};
    return v;
}

/* The ROI in pixels for this frame size, its bounding box and its mask
 * (in crop coordinates). */
static rte_status lane_roi(rte_lane_context *ctx, int32_t w, int32_t h)
{
    if (!ctx->roi_dirty && ctx->roi_width == w && ctx->roi_height == h)
        return RTE_OK;
    const rte_lane_params *p = &ctx->params;
    rte_status st = rte_polygon_from_fractions(p->roi, p->roi_count, w, h, ctx->roi_px);
    if (st != RTE_OK)
        return st;
    int32_t x0 = INT32_MAX, y0 = INT32_MAX, x1 = INT32_MIN, y1 = INT32_MIN;
    for (int32_t i = 0; i < p->roi_count; i++) {
        x0 = ctx->roi_px[i].x < x0 ? ctx->roi_px[i].x : x0;
        y0 = ctx->roi_px[i].y < y0 ? ctx->roi_px[i].y : y0;
        x1 = ctx->roi_px[i].x > x1 ? ctx->roi_px[i].x : x1;
        y1 = ctx->roi_px[i].y > y1 ? ctx->roi_px[i].y : y1;
    }
    /* Clip (fillPoly draws the closing pixel too, hence + 1). */
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 + 1 > w ? w : x1 + 1;
    y1 = y1 + 1 > h ? h : y1 + 1;
    if (x1 - x0 < 2 || y1 - y0 < 2)
        return RTE_ERR_ARGUMENT; /* the ROI misses the frame */
    ctx->crop_x0 = x0;
    ctx->crop_y0 = y0;
    ctx->crop_x1 = x1;
    ctx->crop_y1 = y1;
    rte_vertex local[RTE_LANE_MAX_ROI_VERTICES];
    for (int32_t i = 0; i < p->roi_count; i++) {
        local[i].x = ctx->roi_px[i].x - x0;
        local[i].y = ctx->roi_px[i].y - y0;
    }
    rte_image_u8 mask = lane_view(&ctx->mask, 0, 0, x1 - x0, y1 - y0);
    rte_polygon poly = {local, p->roi_count};
    st = rte_polygon_mask_build(&mask, &poly, 1, &ctx->arena);
    if (st != RTE_OK)
        return st;
    rte_lane_roi_spans(ctx, &mask);
    ctx->roi_width = w;
    ctx->roi_height = h;
    ctx->roi_dirty = false;
    return RTE_OK;
}

/* Ends a stage: its time since *t0 goes into stage_ns[stage], and the next
 * stage starts now. */
static void lane_stage_end(rte_lane_result *out, rte_lane_stage stage, int64_t *t0)
{
    const int64_t t1 = rte_clock_now_ns();
    out->stage_ns[stage] = t1 - *t0;
    *t0 = t1;
}

/* The grey stage's part here: the crop of `gray` to the ROI's bounding
 * box, or the colour cue of it when there is colour. */
static rte_image_u8 lane_stage_gray(rte_lane_context *ctx, const rte_image_u8 *gray,
                                    const lane_colour *colour)
{
    const rte_lane_params *p = &ctx->params;
    const int32_t cx0 = ctx->crop_x0, cy0 = ctx->crop_y0, cx1 = ctx->crop_x1, cy1 = ctx->crop_y1;
    rte_image_u8 src = lane_view(gray, cx0, cy0, cx1, cy1);
    if (!colour || !p->use_color)
        return src;
    rte_image_u8 cue = lane_view(&ctx->cue, 0, 0, cx1 - cx0, cy1 - cy0);
    if (colour->chroma)
        rte_lane_chroma_cue(p, &src, colour, &cue);
    else
        rte_lane_color_cue(p, &src,
                           colour->bgr + (size_t)cy0 * (size_t)colour->bgr_stride + (size_t)cx0 * 3,
                           colour->bgr_stride, colour->rgb, &cue);
    return cue;
}

/* The blur and Canny stages: the edge map of the crop `src` in *edges and
 * its part inside the ROI polygon in *inside. The blur's time is its own
 * stage's only with automatic thresholds; the fused front end counts it in
 * the Canny stage. */
static rte_status lane_stage_edges(rte_lane_context *ctx, const rte_image_u8 *src, int64_t *t0,
                                   rte_lane_result *out, rte_image_u8 *edges, rte_image_u8 *inside)
{
    const rte_lane_params *p = &ctx->params;
    const int32_t cw = ctx->crop_x1 - ctx->crop_x0, ch = ctx->crop_y1 - ctx->crop_y0;
    rte_image_u8 mask = lane_view(&ctx->mask, 0, 0, cw, ch);
    *edges = lane_view(&ctx->edges, 0, 0, cw, ch);
    int32_t low = p->canny_low, high = p->canny_high;
    rte_status st;
    if (p->canny_mode == RTE_LANE_CANNY_FIXED) {
        /* Fused front end: blur, Sobel and suppression over a band of rows,
         * no blurred image (its time counts in the Canny stage). */
        ctx->canny.low = low;
        ctx->canny.high = high;
        if ((st = rte_canny_blurred_u8(src, edges, &ctx->blur, &ctx->canny, &ctx->arena)) != RTE_OK)
            return st;
    } else {
        /* The thresholds come from the blurred pixels' histogram, so the
         * blurred image is needed before any suppression. */
        rte_image_u8 blurred = lane_view(&ctx->blurred, 0, 0, cw, ch);
        if ((st = rte_gaussian_blur_u8(src, &blurred, &ctx->blur, &ctx->arena)) != RTE_OK)
            return st;
        lane_stage_end(out, RTE_LANE_STAGE_BLUR, t0);
        rte_lane_thresholds(ctx, &blurred, &mask, &low, &high);
        /* Integer thresholds on the L1 magnitude of a 3x3 Sobel are what
         * rte_canny_params_init gives for whole numbers: set them directly. */
        ctx->canny.low = low;
        ctx->canny.high = high;
        if ((st = rte_canny_u8(&blurred, edges, &ctx->canny, &ctx->arena)) != RTE_OK)
            return st;
    }
    out->canny_low = low;
    out->canny_high = high;
    *inside = lane_view(&ctx->edges_roi, 0, 0, cw, ch);
    return rte_lane_keep_roi(ctx, edges, &mask, inside);
}

/* The Hough stage: the segments of the edge map, in frame coordinates. */
static rte_status lane_stage_hough(rte_lane_context *ctx, const rte_image_u8 *edges, int32_t *count,
                                   bool *truncated)
{
    const rte_lane_params *p = &ctx->params;
    const rte_hough_segments_params hp = {p->hough_threshold, p->min_length, p->max_gap,
                                          p->hough_seed};
    rte_status st = rte_hough_segments(ctx->hough, edges, &hp, &ctx->arena, ctx->raw,
                                       ctx->cfg.max_segments, count, truncated);
    if (st != RTE_OK)
        return st;
    for (int32_t i = 0; i < *count; i++) {
        rte_lane_segment *s = &ctx->segments[i];
        s->x0 = ctx->raw[i].x0 + ctx->crop_x0;
        s->y0 = ctx->raw[i].y0 + ctx->crop_y0;
        s->x1 = ctx->raw[i].x1 + ctx->crop_x0;
        s->y1 = ctx->raw[i].y1 + ctx->crop_y0;
    }
    return RTE_OK;
}

/* The mark of the segments that support a side's lane. */
static rte_lane_segment_use lane_side_use(int side)
{
    return side == RTE_LANE_LEFT ? RTE_LANE_SEG_LEFT : RTE_LANE_SEG_RIGHT;
}

/* A line fitted to segments, refined on the edge pixels: the rows on which
 * paint lies along it (segments are edges; a lane needs paint along them
 * too). */
static int32_t lane_refined_paint_rows(const lane_maps *maps, const lane_fit_hint *hint,
                                       const rte_lane *lane, lane_line *line)
{
    rte_lane_refine_on_edges(maps->edges, maps->cx0, maps->cy0, hint, maps->tol, line);
    const rte_lane fitted = lane_of_line(line, 0, 0, lane->y_top, lane->y_bottom);
    int64_t offset_q8;
    return rte_lane_find_marking(maps, hint, &fitted, 2, &offset_q8);
}

/* One side of the fit stage: its segments members[0..n) fitted and the
 * line refined on the edge pixels. A tracked side whose segments are too
 * few (the gap between two dashes, a dash the Hough search left out) is
 * searched for along its predicted curve instead and counts as seen when
 * a marking shows on a sixteenth of the lane's rows: its line is then the
 * predicted chord moved onto the marking, with the predicted bow in
 * *bow_q8. Returns the supporting length (segments, else those rows), 0
 * when not seen. */
static int64_t lane_fit_tracked(rte_lane_context *ctx, const lane_maps *maps, int side,
                                int32_t *members, int32_t n, const rte_lane *lane, lane_line *line,
                                int64_t *bow_q8, int32_t *rows)
{
    *rows = 0;
    const rte_lane_params *p = &ctx->params;
    const lane_track *t = &ctx->track[side];
    *line = (lane_line){0, 0, (lane->y_bottom + lane->y_top) / 2};
    *bow_q8 = 0;
    const lane_fit_hint hint = rte_lane_track_hint(t, lane->y_top, lane->y_bottom);
    int32_t inliers;
    const int64_t support = rte_lane_fit_side(ctx, members, n, &hint, line, &inliers);
    rte_lane_mark_side(ctx, members, n, inliers, lane_side_use(side));
    if (p->fit != RTE_LANE_FIT_LEAST_SQUARES)
        return support >= p->min_support_px ? support : 0;
    if (support > 0 && support >= p->min_support_px) {
        *rows = lane_refined_paint_rows(maps, &hint, lane, line);
        return *rows >= lane_min_rows(lane) ? support : 0;
    }
    if (!t->valid)
        return 0;
    const rte_lane pred = rte_lane_track_predict(t, lane->y_top, lane->y_bottom);
    int64_t offset_q8;
    /* twice the refit's band: the prediction is a frame old */
    *rows = rte_lane_find_marking(maps, &hint, &pred, 2, &offset_q8);
    if (*rows < lane_min_rows(lane))
        return 0;
    *line = lane_line_of_chord((int64_t)pred.x_bottom_q8 + offset_q8,
                               (int64_t)pred.x_top_q8 + offset_q8, lane->y_top, lane->y_bottom);
    *bow_q8 = pred.bow_q8;
    return *rows;
}

/* A side: lane_fit_tracked, and when that does not see it on a tracked
 * side, the segments the gate rejected fitted alone (no tracked slope):
 * when they hold paint, the tracked lane has lost the marking (it took
 * an outlier, or the marking moved faster than the gate allows) and is
 * restarted from them (*fresh) rather than held where it is not. When it
 * sees the side with paint on fewer than an eighth of the lane's rows (a
 * lane half on the marking), all the side's segments, inside the gate and
 * outside, are fitted alone the same way, and restart the lane when they
 * hold paint on an eighth of the rows and twice as many as it. */
static int64_t lane_fit_one_side(rte_lane_context *ctx, const lane_maps *maps, int side,
                                 int32_t count, int32_t *members, int32_t n, const rte_lane *lane,
                                 lane_line *line, int64_t *bow_q8, bool *fresh)
{
    *fresh = false;
    int32_t rows = 0;
    const int64_t support =
        lane_fit_tracked(ctx, maps, side, members, n, lane, line, bow_q8, &rows);
    const int32_t weak = (lane->y_bottom - lane->y_top) / 8;
    if ((support > 0 && rows >= weak) || !ctx->track[side].valid ||
        ctx->params.fit != RTE_LANE_FIT_LEAST_SQUARES)
        return support;
    /* members[] holds count: the gated-out ones go after the n in the gate */
    const int32_t gated = rte_lane_gated_out(ctx, side, count, members + n);
    int32_t *refit = support > 0 ? members : members + n;
    const int32_t listed = support > 0 ? n + gated : gated;
    const lane_fit_hint hint = {lane->y_top, lane->y_bottom, 0, 0, 0, false};
    lane_line found = {0, 0, (lane->y_bottom + lane->y_top) / 2};
    int32_t inliers;
    const int64_t again = rte_lane_fit_side(ctx, refit, listed, &hint, &found, &inliers);
    if (again <= 0 || again < ctx->params.min_support_px)
        return support;
    const int32_t again_rows = lane_refined_paint_rows(maps, &hint, lane, &found);
    if (again_rows < lane_min_rows(lane) ||
        (support > 0 && (again_rows < weak || again_rows < 2 * rows)))
        return support;
    if (refit != members) /* the gate's segments: the lane does not use them */
        rte_lane_mark_side(ctx, members, n, 0, RTE_LANE_SEG_OUTLIER);
    rte_lane_mark_side(ctx, refit, listed, inliers, lane_side_use(side));
    *line = found;
    *bow_q8 = 0;
    *fresh = true;
    return again;
}

/* x of the lane's curve at row y (its far trace aside). */
static int32_t curve_x_q8(const rte_lane *lane, int32_t y)
{
    const int64_t span = lane->y_bottom - lane->y_top, v = lane->y_bottom - y;
    if (span <= 0)
        return lane->x_bottom_q8;
    const int64_t chord = lane_chord_x_q8(lane, y);
    if (lane->bow_q8 == 0)
        return lane_clamp32(chord, INT32_MIN, INT32_MAX);
    /* q = d_top / d, d the rows below the horizon (lane_horizon_row) */
    const lane_fit_hint h = {lane->y_top, lane->y_bottom, 0, 0, lane->y_horizon, true};
    const int64_t y_h = lane_horizon_row(&h), d_top = lane->y_top - y_h;
    const int64_t d = y - y_h > 1 ? y - y_h : 1, dm = lane->y_bottom - span / 2 - y_h;
    const int64_t qb = (d_top * 65536) / (lane->y_bottom - y_h);
    const int64_t sag = (d_top * 65536) / d - (qb + (65536 - qb) * v / span);
    const int64_t sag_mid = (d_top * 65536) / dm - (qb + 65536) / 2;
    if (sag_mid >= 0)
        return lane_clamp32(chord, INT32_MIN, INT32_MAX);
    return lane_clamp32(chord + lane->bow_q8 * sag / sag_mid, INT32_MIN, INT32_MAX);
}

int32_t rte_lane_x_q8(const rte_lane *lane, int32_t y)
{
    const int32_t n = lane->far_count;
    if (n < 2 || n > RTE_LANE_FAR_POINTS || y > lane->far_y[0])
        return curve_x_q8(lane, y);
    /* along the far trace's pieces, the last one extended beyond its end */
    int32_t i = 0;
    while (i < n - 2 && y < lane->far_y[i + 1])
        i++;
    const int64_t xa = lane->far_x_q8[i], ya = lane->far_y[i];
    const int64_t xb = lane->far_x_q8[i + 1], yb = lane->far_y[i + 1];
    if (ya == yb)
        return (int32_t)xa;
    /* 128 bits: any int32 fields, whatever a caller filled in */
    const rte_i128 x = xa + (rte_i128)(xb - xa) * (y - ya) / (yb - ya);
    return x < INT32_MIN ? INT32_MIN : x > INT32_MAX ? INT32_MAX : (int32_t)x;
}

/* atan(t) in milliradians for t in 1/65536 (error below 2 mrad). */
static int32_t lane_atan_mrad(int64_t t)
{
    const bool neg = t < 0;
    int64_t a = neg ? -t : t;
    bool inv = a > 65536;
    if (inv)
        a = ((int64_t)65536 * 65536) / a;
    /* atan(x) ~ pi/4 x + x (1 - x)(0.2447 + 0.0663 x) on [0, 1], in micro-radians */
    const int64_t k = 785398 + ((65536 - a) * (244700 + ((66300 * a) >> 16)) >> 16);
    int64_t mrad = (a * k / 65536 + 500) / 1000;
    if (inv)
        mrad = 1571 - mrad;
    return (int32_t)(neg ? -mrad : mrad);
}

/* The centre between the two lanes, when both are found and in order:
 * the offset of the image's centre column from it and its heading at the
 * bottom row: the tangent of the centre curve there (taken over a
 * sixteenth of the lane's rows), which on a bend is what the vehicle
 * steers along, where the chord would lean into the bend. */
static void lane_centre(rte_lane_result *out, int32_t w, int32_t y_bottom, int32_t y_top)
{
    const rte_lane *l = &out->lane[RTE_LANE_LEFT], *r = &out->lane[RTE_LANE_RIGHT];
    if (l->found && r->found && r->x_bottom_q8 > l->x_bottom_q8) {
        out->centre_valid = true;
        const int64_t cb = ((int64_t)l->x_bottom_q8 + r->x_bottom_q8) / 2;
        out->offset_q8 = (int32_t)(cb - (int64_t)(w - 1) * 128);
        out->offset_permille =
            (int32_t)((int64_t)out->offset_q8 * 1000 / (r->x_bottom_q8 - l->x_bottom_q8));
        const int32_t dy = (y_bottom - y_top) / 16 + 1;
        const int64_t ct =
            ((int64_t)rte_lane_x_q8(l, y_bottom - dy) + rte_lane_x_q8(r, y_bottom - dy)) / 2;
        out->heading_tan_q16 = lane_clamp32((ct - cb) * 256 / dy, -INT32_MAX, INT32_MAX);
        out->heading_mrad = lane_atan_mrad(out->heading_tan_q16);
    }
}

/* A lane's confidence: the share of its rows on which paint lies along it
 * (rte_lane_find_marking in the refit's band), full from two fifths of the
 * rows (a dashed line's share of paint), less four times the share of the
 * ROI washed out by glare (glare_permille; none is left when a quarter of
 * it is): in glare, sunlit road and kerbs look like paint, and a side is
 * right less often than its paint says. See docs/lanes.md, "Lane line and
 * confidence". */
#define LANE_CONFIDENT_ROWS_Q8 102 /* 0.4 */
static void lane_confidence(const lane_maps *maps, int32_t glare_permille, rte_lane *lane)
{
    const int32_t span = lane->y_bottom - lane->y_top;
    lane->confidence_permille = 0;
    if (!lane->found || span <= 0)
        return;
    const lane_fit_hint hint = {lane->y_top, lane->y_bottom, 0, 0, 0, false};
    int64_t offset_q8;
    const int64_t rows = rte_lane_find_marking(maps, &hint, lane, 1, &offset_q8);
    const int64_t paint =
        lane_clamp32(rows * 1000 * 256 / ((int64_t)span * LANE_CONFIDENT_ROWS_Q8), 0, 1000);
    const int64_t clear = 1000 - 4 * (int64_t)glare_permille;
    lane->confidence_permille = clear > 0 ? (int32_t)(paint * clear / 1000) : 0;
}

/* Whether the tracked lane has left the marking this frame's measurement
 * lies on: paint along the measurement on a quarter of the lane's rows at
 * least and on three times as many as along the prediction (in the
 * refit's band). The tracker smooths a marking it follows; where the lane
 * it holds lies on bare road it has lost it (a bend or a lane change
 * faster than its steps), and the measurement is taken whole. */
static bool lane_track_lost(const rte_lane_context *ctx, const lane_maps *maps,
                            const lane_fit_hint *rows, int side, const lane_line *line,
                            const lane_curve *curve)
{
    const lane_track *t = &ctx->track[side];
    if (!t->valid || t->lost > 0)
        return false;
    const rte_lane pred = rte_lane_track_predict(t, rows->y_top, rows->y_bottom);
    const rte_lane meas =
        lane_of_line(line, curve->bow_q8, curve->y_horizon, rows->y_top, rows->y_bottom);
    int64_t offset_q8;
    const int32_t on_meas = rte_lane_find_marking(maps, rows, &meas, 1, &offset_q8);
    if (on_meas < (rows->y_bottom - rows->y_top) / 4)
        return false;
    return on_meas >= 3 * rte_lane_find_marking(maps, rows, &pred, 1, &offset_q8);
}

/* The fit stage: the segments (ctx->segments[0..count)) sorted into sides,
 * both lanes fitted and tracked, then their centre. */
static void lane_stage_fit(rte_lane_context *ctx, const rte_image_u8 *src, const rte_image_u8 *gray,
                           const rte_image_u8 *edges, int32_t w, int32_t h, int32_t count,
                           rte_lane_result *out)
{
    const rte_lane_params *p = &ctx->params;
    /* The ROI's top row, clipped, is where the lanes end. */
    int32_t y_top = INT32_MAX;
    for (int32_t i = 0; i < p->roi_count; i++)
        y_top = ctx->roi_px[i].y < y_top ? ctx->roi_px[i].y : y_top;
    y_top = y_top < 0 ? 0 : y_top > h - 1 ? h - 1 : y_top;
    const int32_t y_bottom = h - 1;
    /* Side lists: at most `count` members each; the third part of `order`
     * is the medians' work list. */
    int32_t *members[2] = {ctx->order, ctx->order + ctx->cfg.max_segments};
    int32_t n[2] = {0, 0};
    const rte_image_u8 gray_crop =
        lane_view(gray, ctx->crop_x0, ctx->crop_y0, ctx->crop_x1, ctx->crop_y1);
    const lane_maps maps = {edges,        src,          &gray_crop,
                            ctx->crop_x0, ctx->crop_y0, (int64_t)p->outlier_px};
    const lane_fit_hint rows = {y_top, y_bottom, 0, 0, 0, false};
    const rte_image_u8 mask =
        lane_view(&ctx->mask, 0, 0, ctx->crop_x1 - ctx->crop_x0, ctx->crop_y1 - ctx->crop_y0);
    const int32_t glare_permille = rte_lane_glare_permille(ctx, &gray_crop, &mask);
    rte_lane_paint_weights(ctx, &maps, &rows, count);
    rte_lane_classify(ctx, count, w, y_bottom, y_top, members, n);
    lane_line line[2];
    int64_t support[2], seeded_bow[2];
    bool seen[2], fresh[2];
    for (int side = 0; side < 2; side++) {
        rte_lane *lane = &out->lane[side];
        lane->y_bottom = y_bottom;
        lane->y_top = y_top;
        support[side] = lane_fit_one_side(ctx, &maps, side, count, members[side], n[side], lane,
                                          &line[side], &seeded_bow[side], &fresh[side]);
        seen[side] = support[side] > 0;
    }
    /* seen on its own: a side found from the other takes its bend (its
     * few dashes would bend both) */
    const bool own[2] = {seen[0], seen[1]};
    lane_curve curve[2] = {{0, y_bottom, 0, y_bottom}, {0, y_bottom, 0, y_bottom}};
    if (p->curves && p->fit == RTE_LANE_FIT_LEAST_SQUARES)
        rte_lane_curves_fit(&maps, &rows, own, line, curve);
    /* A side found along its predicted curve keeps that bend unless the
     * curve fit gave it one. */
    for (int side = 0; side < 2; side++)
        if (seen[side] && seeded_bow[side] != 0 && curve[side].bow_q8 == 0) {
            curve[side].bow_q8 = seeded_bow[side];
            curve[side].y_horizon = ctx->track[side].y_horizon;
        }
    rte_lane_fit_partner(ctx, &maps, &rows, glare_permille, w, seen, line, curve, support, fresh);
    if (p->fit == RTE_LANE_FIT_LEAST_SQUARES)
        rte_lane_double_centre(&maps, &rows, own, line, curve);
    rte_lane_width_hold(ctx, seen, line, curve, y_top, y_bottom);
    for (int side = 0; side < 2; side++)
        if (seen[side] && !fresh[side])
            fresh[side] = lane_track_lost(ctx, &maps, &rows, side, &line[side], &curve[side]);
    for (int side = 0; side < 2; side++)
        rte_lane_track_update(ctx, side, seen[side], fresh[side], &line[side], &curve[side],
                              support[side], &out->lane[side]);
    for (int side = 0; side < 2; side++) {
        rte_lane_trace_far(&maps, &rows, &out->lane[side]);
        lane_confidence(&maps, glare_permille, &out->lane[side]);
    }
    lane_centre(out, w, y_bottom, y_top);
}

/* gray_ns: time already spent making `gray` (counted in the grey stage). */
static rte_status lane_run(rte_lane_context *ctx, const rte_image_u8 *gray,
                           const lane_colour *colour, int64_t t_ns, int64_t gray_ns,
                           rte_lane_result *out)
{
    int64_t t0 = rte_clock_now_ns() - gray_ns;
    const int32_t w = gray->width, h = gray->height;
    memset(out, 0, sizeof *out);
    out->t_ns = t_ns;
    rte_status st = lane_roi(ctx, w, h);
    if (st != RTE_OK)
        return st;
    const rte_image_u8 src = lane_stage_gray(ctx, gray, colour);
    lane_stage_end(out, RTE_LANE_STAGE_GRAY, &t0);

    rte_image_u8 edges, edges_inside;
    if ((st = lane_stage_edges(ctx, &src, &t0, out, &edges, &edges_inside)) != RTE_OK)
        return st;
    lane_stage_end(out, RTE_LANE_STAGE_CANNY, &t0);

    int32_t count = 0;
    bool truncated = false;
    if ((st = lane_stage_hough(ctx, &edges_inside, &count, &truncated)) != RTE_OK)
        return st;
    lane_stage_end(out, RTE_LANE_STAGE_HOUGH, &t0);

    lane_stage_fit(ctx, &src, gray, &edges, w, h, count, out);
    out->segments = ctx->segments;
    out->segment_count = count;
    out->truncated = truncated;
    out->edges = edges_inside;
    out->edges_x0 = ctx->crop_x0;
    out->edges_y0 = ctx->crop_y0;
    out->stage_ns[RTE_LANE_STAGE_FIT] = rte_clock_now_ns() - t0;
    return RTE_OK;
}

static rte_status lane_check_size(const rte_lane_context *ctx, int32_t w, int32_t h)
{
    return w <= ctx->cfg.max_width && h <= ctx->cfg.max_height ? RTE_OK : RTE_ERR_SIZE;
}

rte_status rte_lane_process_gray(rte_lane_context *ctx, const rte_image_u8 *gray,
                                 const rte_image_u8c3 *bgr, int64_t t_ns, rte_lane_result *out)
{
    if (!ctx || !out)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check(gray);
    if (st != RTE_OK || (st = lane_check_size(ctx, gray->width, gray->height)) != RTE_OK)
        return st;
    if (bgr && (!bgr->buf || bgr->width != gray->width || bgr->height != gray->height ||
                bgr->stride < 3 * bgr->width))
        return RTE_ERR_SIZE;
    const lane_colour colour = {.bgr = bgr ? bgr->buf : NULL, .bgr_stride = bgr ? bgr->stride : 0};
    return lane_run(ctx, gray, bgr ? &colour : NULL, t_ns, 0, out);
}

rte_status rte_lane_process(rte_lane_context *ctx, const rte_frame *frame, int64_t t_ns,
                            rte_lane_result *out)
{
    if (!ctx || !out)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_frame_check(frame);
    if (st != RTE_OK || (st = lane_check_size(ctx, frame->width, frame->height)) != RTE_OK)
        return st;
    const int64_t t0 = rte_clock_now_ns();
    /* The ROI first: only its bounding box becomes grey or gives colour. */
    if ((st = lane_roi(ctx, frame->width, frame->height)) != RTE_OK)
        return st;
    const rte_pixel_format f = frame->format;
    lane_colour colour = {0}, *with = NULL;
    if (ctx->params.use_color &&
        (f == RTE_PIXEL_NV12 || f == RTE_PIXEL_YUYV || f == RTE_PIXEL_UYVY)) {
        if ((st = rte_lane_frame_chroma(ctx, frame, &colour)) != RTE_OK)
            return st;
        with = &colour;
    }
    rte_image_u8 gray;
    if (rte_frame_gray_view(frame, &gray) != RTE_OK) {
        /* the crop widened to even x0 (a YUYV pair), as a view of the frame */
        const int32_t x0 = ctx->crop_x0 & ~1, y0 = ctx->crop_y0;
        const rte_frame part = lane_frame_part(frame, x0, y0, ctx->crop_x1, ctx->crop_y1);
        gray = lane_view(&ctx->gray, x0, y0, ctx->crop_x1, ctx->crop_y1);
        if ((st = rte_frame_to_gray(&part, &gray)) != RTE_OK)
            return st;
        gray = lane_view(&ctx->gray, 0, 0, frame->width, frame->height);
        if (f == RTE_PIXEL_BGR24 || f == RTE_PIXEL_RGB24) {
            colour = (lane_colour){.bgr = frame->plane[0],
                                   .bgr_stride = frame->stride[0],
                                   .rgb = f == RTE_PIXEL_RGB24};
            with = &colour;
        }
    }
    return lane_run(ctx, &gray, with, t_ns, rte_clock_now_ns() - t0, out);
}
