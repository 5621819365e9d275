/* The robust fit of the lane segments of one side, per frame (integer
 * only): weighted medians (Theil-Sen style), then weighted least squares
 * with the outliers dropped (see include/rtedge/lane.h and docs/lanes.md). */
#include "algo/geom_fixed.h"
#include "lane_fixed.h"

static int32_t seg_length(const rte_lane_segment *s)
{
    const int64_t dx = s->x1 - s->x0, dy = s->y1 - s->y0;
    return (int32_t)rte_isqrt64((uint64_t)(dx * dx + dy * dy));
}

/* Whether the edge at column x of row y (crop coordinates) bounds paint:
 * the brighter side (two pixels out) brighter than the other by
 * LANE_RIDGE_MIN and darker again within `width` pixels, i.e. a stripe of
 * a marking's width, not the border of a wide bright area (a road's edge,
 * a shadow's end, a kerb). */
static bool borders_paint(const rte_image_u8 *img, int32_t x, int32_t y, int32_t width)
{
    if (y < 0 || y >= img->height || x - width - 2 < 0 || x + width + 2 > img->width - 1)
        return false;
    const uint8_t *row = rte_u8_row(img, y);
    const int32_t dir = row[x + 2] > row[x - 2] ? 1 : -1, paint = row[x + 2 * dir];
    if (paint < row[x - 2 * dir] + LANE_RIDGE_MIN)
        return false;
    for (int32_t k = 3; k <= width; k++)
        if (row[x + k * dir] + LANE_RIDGE_MIN <= paint)
            return true;
    return false;
}

/* Points of a segment tested for paint (rte_lane_paint_weights). */
#define LANE_PAINT_SAMPLES 8

void rte_lane_paint_weights(rte_lane_context *ctx, const lane_maps *maps, const lane_fit_hint *rows,
                            int32_t count)
{
    for (int32_t i = 0; i < count; i++) {
        const rte_lane_segment *s = &ctx->segments[i];
        int32_t paint = 0;
        for (int32_t k = 0; k < LANE_PAINT_SAMPLES; k++) {
            /* points at (k + 1/2) / SAMPLES along the segment */
            const int32_t x = s->x0 + (int32_t)(((int64_t)(s->x1 - s->x0) * (2 * k + 1)) /
                                                (2 * LANE_PAINT_SAMPLES));
            const int32_t y = s->y0 + (int32_t)(((int64_t)(s->y1 - s->y0) * (2 * k + 1)) /
                                                (2 * LANE_PAINT_SAMPLES));
            const int32_t width = (int32_t)(2 * rte_lane_band_px(rows, maps->tol, y));
            paint += borders_paint(maps->src, x - maps->cx0, y - maps->cy0, width);
        }
        const int64_t len = seg_length(s);
        ctx->weight[i] =
            (int32_t)((len * (paint + 1) + LANE_PAINT_SAMPLES) / (LANE_PAINT_SAMPLES + 1));
    }
}

/* Sorts idx[0..n) by key[idx] (shell sort: no recursion, no allocation). */
static void lane_sort(int32_t *idx, const int64_t *key, int32_t n)
{
    static const int32_t gaps[] = {701, 301, 132, 57, 23, 10, 4, 1};
    for (size_t g = 0; g < sizeof gaps / sizeof gaps[0]; g++) {
        const int32_t gap = gaps[g];
        for (int32_t i = gap; i < n; i++) {
            const int32_t v = idx[i];
            int32_t j = i;
            while (j >= gap && key[idx[j - gap]] > key[v]) {
                idx[j] = idx[j - gap];
                j -= gap;
            }
            idx[j] = v;
        }
    }
}

/* Weighted median of key over the segments members[0..n) (weights: the
 * segments' fit weights). */
static int64_t weighted_median(int32_t *work, const int32_t *members, int32_t n, const int64_t *key,
                               const int32_t *weight)
{
    int64_t total = 0;
    for (int32_t i = 0; i < n; i++) {
        work[i] = members[i];
        total += weight[members[i]];
    }
    lane_sort(work, key, n);
    int64_t acc = 0;
    for (int32_t i = 0; i < n; i++) {
        acc += weight[work[i]];
        if (2 * acc >= total)
            return key[work[i]];
    }
    return key[work[n - 1]];
}

/* Theil-Sen style start: slope = weighted median of the segments' own
 * slopes dx/dy, then x at y_mid = weighted median of the segments'
 * intercepts under that slope. */
static void fit_medians(rte_lane_context *ctx, const int32_t *members, int32_t n, lane_line *line)
{
    const rte_lane_segment *segs = ctx->segments;
    int64_t *key = ctx->keys;
    int32_t *work = ctx->order + 2 * ctx->cfg.max_segments;
    for (int32_t i = 0; i < n; i++) {
        const rte_lane_segment *s = &segs[members[i]];
        key[members[i]] = (int64_t)(s->x1 - s->x0) * 65536 / (s->y1 - s->y0);
    }
    line->slope_q16 = weighted_median(work, members, n, key, ctx->weight);
    for (int32_t i = 0; i < n; i++) {
        const rte_lane_segment *s = &segs[members[i]];
        /* midpoint x (Q8) moved along the slope to y_mid */
        const int64_t xm = (int64_t)(s->x0 + s->x1) * 128, ym2 = (int64_t)(s->y0 + s->y1);
        key[members[i]] = xm - ((line->slope_q16 * (ym2 - 2 * line->y_mid)) >> 9);
    }
    line->x_mid_q8 = weighted_median(work, members, n, key, ctx->weight);
}

/* Largest horizontal distance of a segment's end points from the line, 1/256 px. */
static int64_t seg_residual_q8(const lane_line *l, const rte_lane_segment *s)
{
    const int64_t r0 = rte_abs64((int64_t)s->x0 * 256 - lane_line_x_q8(l, s->y0));
    const int64_t r1 = rte_abs64((int64_t)s->x1 * 256 - lane_line_x_q8(l, s->y1));
    return r0 > r1 ? r0 : r1;
}

/* A segment's own direction counts this many times the spread of its
 * pixels: it is fitted to all of them (the Hough refit), and on a bend the
 * markings' local direction describes the lane near them better than the
 * chord between dashes far apart. */
#define LANE_DIRECTION_WEIGHT 4

/* Weighted least squares of x on y over the inlier segments, each taken as
 * a uniform line of points (its second moment includes the segment's own
 * extent: d^2/12), weighted by their fit weights (length and paint) and
 * lane_row_weight_q8. Returns false
 * when the rows do not spread enough to give a slope and there is no prior. */
static bool fit_least_squares(const rte_lane_segment *segs, const int32_t *weight,
                              const int32_t *members, int32_t n, const lane_fit_hint *hint,
                              lane_line *line)
{
    int64_t w = 0, sx = 0, sy = 0;
    for (int32_t i = 0; i < n; i++) {
        const rte_lane_segment *s = &segs[members[i]];
        const int64_t len = weight[members[i]] * lane_row_weight_q8(hint, (s->y0 + s->y1) / 2);
        w += len;
        sx += len * (s->x0 + s->x1); /* Q1 */
        sy += len * (s->y0 + s->y1);
    }
    if (w <= 0)
        return false;
    const int64_t mx = sx / w, my = sy / w; /* Q1 means (the rounding cancels: centred below) */
    int64_t cyy = 0, cxy = 0;
    for (int32_t i = 0; i < n; i++) {
        const rte_lane_segment *s = &segs[members[i]];
        const int64_t len = weight[members[i]] * lane_row_weight_q8(hint, (s->y0 + s->y1) / 2);
        const int64_t X = s->x0 + s->x1 - mx, Y = s->y0 + s->y1 - my;
        const int64_t dx = s->x1 - s->x0, dy = s->y1 - s->y0;
        /* Q2 moments times 3: 3*X*Y + (2dx)(2dy)*3/12 = 3XY + dx*dy */
        cyy += len * (3 * Y * Y + LANE_DIRECTION_WEIGHT * dy * dy);
        cxy += len * (3 * X * Y + LANE_DIRECTION_WEIGHT * dx * dy);
    }
    if (hint->weight > 0) /* (cxy + weight slope) / (cyy + weight), in Q8 */
        line->slope_q16 = lane_div_q16(cxy * 256 + ((hint->weight * hint->slope_q16) >> 8),
                                       (cyy + hint->weight) * 256);
    else if (cyy < w * 3 * 64 * 4) /* need a spread of rows: at least ~8 px */
        return false;
    else
        line->slope_q16 = lane_div_q16(cxy, cyy);
    if (rte_abs64(line->slope_q16) > 64 * 65536)
        return false;
    /* x at y_mid from the weighted means (Q8) */
    line->x_mid_q8 =
        sx * 128 / w + ((line->slope_q16 * ((int64_t)line->y_mid * 256 - sy * 128 / w)) >> 16);
    return true;
}

/* The robust fit of one side over members[0..n): medians first; for least
 * squares, segments beyond outlier_px are set aside and the rest refitted
 * (twice, so an outlier that pulled the start is caught on the second
 * pass). members[] is partitioned in place, the inliers first. */
int64_t rte_lane_fit_side(rte_lane_context *ctx, int32_t *members, int32_t n,
                          const lane_fit_hint *hint, lane_line *line, int32_t *inliers)
{
    rte_lane_segment *segs = ctx->segments;
    *inliers = 0;
    if (n == 0)
        return 0;
    fit_medians(ctx, members, n, line);
    const int64_t tol = (int64_t)ctx->params.outlier_px * 256;
    int32_t kept = n;
    int passes = ctx->params.fit == RTE_LANE_FIT_LEAST_SQUARES ? 2 : 1;
    for (int pass = 0; pass < passes; pass++) {
        /* The median start sits on one edge of a marking: the first pass
         * is twice as tolerant so the marking's other edge stays in and the
         * least-squares line moves to the marking's centre. */
        const int64_t pass_tol = pass == 0 && passes > 1 ? 2 * tol : tol;
        kept = 0;
        for (int32_t i = 0; i < n; i++) {
            if (seg_residual_q8(line, &segs[members[i]]) <= pass_tol) {
                const int32_t m = members[i]; /* swapped: the outliers stay listed */
                members[i] = members[kept];
                members[kept++] = m;
            }
        }
        n = kept;
        if (ctx->params.fit == RTE_LANE_FIT_THEIL_SEN || n == 0)
            break;
        lane_line ls = *line;
        if (fit_least_squares(segs, ctx->weight, members, n, hint, &ls))
            *line = ls;
    }
    int64_t support = 0;
    for (int32_t i = 0; i < kept; i++)
        support += seg_length(&segs[members[i]]);
    *inliers = kept;
    return support;
}

void rte_lane_mark_side(rte_lane_context *ctx, const int32_t *members, int32_t n, int32_t inliers,
                        rte_lane_segment_use use)
{
    for (int32_t i = 0; i < n; i++)
        ctx->segments[members[i]].use = i < inliers ? use : RTE_LANE_SEG_OUTLIER;
}
