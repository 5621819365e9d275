/* Which side each Hough segment supports, the gate around the tracked
 * lanes and the trackers themselves, per frame (integer only; see
 * include/rtedge/lane.h and docs/lanes.md). */
#include "algo/geom_fixed.h"
#include "lane_fixed.h"

/* Tracked lane x at row y (1/256 px): its curve (chord and bow). */
static int64_t track_x_q8(const lane_track *t, int32_t y_bottom, int32_t y_top, int32_t y)
{
    rte_lane l = {.x_bottom_q8 = t->x_bottom_q8,
                  .x_top_q8 = t->x_top_q8,
                  .y_bottom = y_bottom,
                  .y_top = y_top,
                  .bow_q8 = t->bow_q8,
                  .y_horizon = t->y_horizon};
    return rte_lane_x_q8(&l, y);
}

/* The side a segment ((x0, y0) its upper end) would belong to: one whose
 * upper end lies right of its lower end (dy/dx < 0 in image coordinates,
 * y down) is the left lane's. */
static int segment_side(const rte_lane_segment *s)
{
    return s->x1 < s->x0 ? RTE_LANE_LEFT : RTE_LANE_RIGHT;
}

/* Sorts the Hough segments into sides by slope, position and the gate;
 * fills side lists and marks rejected ones. */
void rte_lane_classify(rte_lane_context *ctx, int32_t count, int32_t width, int32_t y_bottom,
                       int32_t y_top, int32_t *members[2], int32_t n[2])
{
    const rte_lane_params *p = &ctx->params;
    for (int32_t i = 0; i < count; i++) {
        rte_lane_segment *s = &ctx->segments[i];
        if (s->y1 < s->y0) { /* (x0, y0) the upper end */
            int32_t tx = s->x0, ty = s->y0;
            s->x0 = s->x1, s->y0 = s->y1, s->x1 = tx, s->y1 = ty;
        }
        const int64_t dx = s->x1 - s->x0, dy = s->y1 - s->y0; /* dy >= 0 */
        const int64_t adx = rte_abs64(dx);
        const int side = segment_side(s);
        const int64_t lo = side == RTE_LANE_LEFT ? p->left_min_slope_q8 : p->right_min_slope_q8;
        const int64_t hi = side == RTE_LANE_LEFT ? p->left_max_slope_q8 : p->right_max_slope_q8;
        const bool slope_ok = dx != 0 && dy * 256 >= lo * adx && dy * 256 <= hi * adx;
        /* ... and on its own half of the image */
        const int64_t mid2 = s->x0 + s->x1;
        const bool half_ok = side == RTE_LANE_LEFT ? mid2 < width : mid2 >= width;
        s->use = RTE_LANE_SEG_REJECTED_SLOPE;
        if (!slope_ok || !half_ok)
            continue;
        const lane_track *t = &ctx->track[side];
        if (t->valid) {
            const int64_t ym = (s->y0 + s->y1) / 2;
            const int64_t d = rte_abs64(mid2 * 128 - track_x_q8(t, y_bottom, y_top, (int32_t)ym));
            if (d > (int64_t)p->gate_px * 256) {
                s->use = RTE_LANE_SEG_REJECTED_GATE;
                continue;
            }
        }
        members[side][n[side]++] = i;
    }
}

int32_t rte_lane_gated_out(const rte_lane_context *ctx, int side, int32_t count, int32_t *members)
{
    int32_t n = 0;
    for (int32_t i = 0; i < count; i++) {
        const rte_lane_segment *s = &ctx->segments[i]; /* classified: (x0, y0) the upper end */
        if (s->use == RTE_LANE_SEG_REJECTED_GATE && segment_side(s) == side)
            members[n++] = i;
    }
    return n;
}

lane_fit_hint rte_lane_track_hint(const lane_track *t, int32_t y_top, int32_t y_bottom)
{
    lane_fit_hint hint = {y_top, y_bottom, 0, 0, 0, false};
    if (t->valid && y_bottom > y_top) {
        const int64_t dx =
            ((int64_t)t->x_top_q8 + t->v_top_q8) - ((int64_t)t->x_bottom_q8 + t->v_bottom_q8);
        const int64_t rows = (y_bottom - y_top) / 5 + 1; /* a fifth of the lane */
        hint.slope_q16 = lane_clamp32(dx * 256 / (y_top - y_bottom), -64 * 65536, 64 * 65536);
        hint.weight = rows * rows * rows * 128; /* 128: the mean row weight */
    }
    return hint;
}

rte_lane rte_lane_track_predict(const lane_track *t, int32_t y_top, int32_t y_bottom)
{
    const int64_t lim = 1 << 28;
    return (rte_lane){.x_bottom_q8 =
                          lane_clamp32((int64_t)t->x_bottom_q8 + t->v_bottom_q8, -lim, lim),
                      .x_top_q8 = lane_clamp32((int64_t)t->x_top_q8 + t->v_top_q8, -lim, lim),
                      .y_bottom = y_bottom,
                      .y_top = y_top,
                      .bow_q8 = t->bow_q8,
                      .y_horizon = t->y_horizon};
}

#define LANE_FAR_STEPS 8
void rte_lane_track_update(rte_lane_context *ctx, int side, bool seen, bool fresh,
                           const lane_line *line, const lane_curve *curve, int64_t support,
                           rte_lane *out)
{
    const rte_lane_params *p = &ctx->params;
    lane_track *t = &ctx->track[side];
    const int64_t mb = seen ? lane_line_x_q8(line, out->y_bottom) : 0;
    const int64_t mt = seen ? lane_line_x_q8(line, out->y_top) : 0;
    const int64_t lim = 1 << 28; /* keeps far-off extrapolations in range */
    /* Seen again after being held: the prediction has drifted for
     * t->lost frames, so the measurement is taken whole; so is one found
     * outside the gate, where the tracked lane has lost the marking. */
    if (seen && (!t->valid || t->lost > 0 || fresh)) {
        t->valid = true;
        t->x_bottom_q8 = lane_clamp32(mb, -lim, lim);
        t->x_top_q8 = lane_clamp32(mt, -lim, lim);
        t->v_bottom_q8 = t->v_top_q8 = 0;
        t->bow_q8 = lane_clamp32(curve->bow_q8, -lim, lim);
        t->y_horizon = curve->y_horizon;
        t->lost = 0;
    } else if (t->valid) {
        const int64_t pb = (int64_t)t->x_bottom_q8 + t->v_bottom_q8;
        const int64_t pt = (int64_t)t->x_top_q8 + t->v_top_q8;
        if (seen) {
            /* A measurement resting on little paint (one short dash) moves
             * the state less: full weight from half the lane's length of
             * support, a quarter at least. */
            const int64_t dxl = (mt - mb) / 256, dyl = out->y_bottom - out->y_top;
            const int64_t len = (int64_t)rte_isqrt64((uint64_t)(dxl * dxl + dyl * dyl)) + 1;
            const int64_t share = lane_clamp32(support * 256 / len, 192, 256); /* /256 */
            const int64_t alpha = (int64_t)p->alpha_q8 * share >> 8;
            /* The clamp holds the bottom row, where the vehicle is; the
             * far end and the bow, which a bend moves fast (on a winding
             * road at 6 fps the far end moved 100 px a frame), may move
             * LANE_FAR_STEPS times as far when the marking was seen in the
             * lane's upper quarter (not extrapolated past a glare patch
             * or the last dash). */
            const bool seen_far = (curve->y_supported - out->y_top) * 4 <= dyl;
            const int64_t step = (int64_t)p->max_step_px * 256;
            const int64_t far = seen_far ? LANE_FAR_STEPS * step : step;
            const int64_t rb = lane_clamp32(mb - pb, -step, step),
                          rt = lane_clamp32(mt - pt, -far, far);
            t->x_bottom_q8 = lane_clamp32(pb + ((rb * alpha) >> 8), -lim, lim);
            t->x_top_q8 = lane_clamp32(pt + ((rt * alpha) >> 8), -lim, lim);
            t->v_bottom_q8 = lane_clamp32(t->v_bottom_q8 + ((rb * p->beta_q8) >> 8), -step, step);
            t->v_top_q8 = lane_clamp32(t->v_top_q8 + ((rt * p->beta_q8) >> 8), -step, step);
            const int64_t rbow = lane_clamp32(curve->bow_q8 - t->bow_q8, -far, far);
            t->bow_q8 = lane_clamp32(t->bow_q8 + ((rbow * alpha) >> 8), -lim, lim);
            t->y_horizon = curve->y_horizon;
            t->lost = 0;
        } else if (++t->lost > p->hold_frames) {
            t->valid = false;
        } else {
            /* Held as predicted; the velocity fades (by 1/8 a frame) so a
             * lane held for long settles instead of drifting away. */
            t->x_bottom_q8 = lane_clamp32(pb, -lim, lim);
            t->x_top_q8 = lane_clamp32(pt, -lim, lim);
            t->v_bottom_q8 -= t->v_bottom_q8 / 8;
            t->v_top_q8 -= t->v_top_q8 / 8;
            t->bow_q8 -= t->bow_q8 / 8;
        }
    }
    out->found = t->valid;
    out->predicted = t->valid && t->lost > 0;
    out->lost_frames = t->valid ? t->lost : 0;
    out->support_px = (int32_t)(support > INT32_MAX ? INT32_MAX : support);
    out->bow_q8 = t->valid ? t->bow_q8 : 0;
    out->y_horizon = t->valid ? t->y_horizon : curve->y_horizon;
    out->y_supported = seen ? curve->y_supported : out->y_bottom;
    if (t->valid) {
        out->x_bottom_q8 = t->x_bottom_q8;
        out->x_top_q8 = t->x_top_q8;
    }
}

void rte_lane_width_hold(rte_lane_context *ctx, const bool seen[2], lane_line line[2],
                         const lane_curve curve[2], int32_t y_top, int32_t y_bottom)
{
    const int32_t span = y_bottom - y_top;
    if (!seen[0] || !seen[1] || span <= 0)
        return;
    bool near[2];
    for (int side = 0; side < 2; side++)
        near[side] = (y_bottom - curve[side].y_lowest) * 4 <= span;
    const int64_t xl = lane_line_x_q8(&line[0], y_bottom), xr = lane_line_x_q8(&line[1], y_bottom);
    if (near[0] && near[1]) {
        const int64_t w = xr - xl;
        if (w <= 0)
            return;
        const int64_t lim = 1 << 28;
        ctx->width_q8 = lane_clamp32(
            ctx->width_valid ? ctx->width_q8 + (((w - ctx->width_q8) * ctx->params.alpha_q8) >> 8)
                             : w,
            0, lim);
        ctx->width_valid = true;
        return;
    }
    if (!ctx->width_valid || near[0] == near[1])
        return;
    const int far = near[0] ? 1 : 0;
    const int64_t xb = far == 1 ? xl + ctx->width_q8 : xr - ctx->width_q8;
    const int64_t xt = lane_line_x_q8(&line[far], y_top);
    line[far] = (lane_line){xb, (xt - xb) * 256 / -span, y_bottom};
}
