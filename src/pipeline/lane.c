/* Lane detection, per frame (integer only: built with -mgeneral-regs-only).
 * The stages and the reasons for them are in include/rtedge/lane.h and
 * docs/lanes.md. */
#include <string.h>
#include <time.h>

#include "algo/geom_fixed.h"
#include "lane_cue_rows.h"
#include "lane_internal.h"
#include "rtedge/cpu.h"
#include "rtedge/color.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/threshold.h"
#include "core/clock.h"

const char *rte_lane_stage_name(rte_lane_stage stage)
{
    static const char *const names[RTE_LANE_STAGES] = {"gray", "blur", "canny", "hough", "fit"};
    return (unsigned)stage < RTE_LANE_STAGES ? names[stage] : "unknown";
}

static bool in_range(int32_t v, int32_t lo, int32_t hi)
{
    return v >= lo && v <= hi;
}

rte_status rte_lane_set_params(rte_lane_context *ctx, const rte_lane_params *p)
{
    if (!ctx || !p || !in_range(p->roi_count, 3, RTE_LANE_MAX_ROI_VERTICES) ||
        !in_range((int32_t)p->canny_mode, 0, 2) || !in_range(p->canny_low, 0, 2040) ||
        !in_range(p->canny_high, 0, 2040) || p->canny_low > p->canny_high ||
        !in_range(p->auto_sigma_permille, 0, 10000) || !in_range(p->white_min, 0, 256) ||
        !in_range(p->yellow_rg_min, 0, 256) || !in_range(p->yellow_b_margin, 0, 255) ||
        !in_range(p->dim_q8, 0, 256) || !in_range(p->hough_threshold, 1, 1 << 20) ||
        !in_range(p->min_length, 0, 1 << 20) || !in_range(p->max_gap, 0, 1 << 20) ||
        !in_range(p->left_min_slope_q8, 1, 1 << 20) || p->left_max_slope_q8 < p->left_min_slope_q8 ||
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
    if (ctx)
        memset(ctx->track, 0, sizeof ctx->track);
}

/* A view of rows y0..y1-1, columns x0..x1-1 of img. */
static rte_image_u8 lane_view(const rte_image_u8 *img, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    rte_image_u8 v = {x1 - x0, y1 - y0, img->stride, img->buf + (size_t)y0 * (size_t)img->stride + (size_t)x0};
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
    ctx->roi_width = w;
    ctx->roi_height = h;
    ctx->roi_dirty = false;
    return RTE_OK;
}

/* The colour cue's row kernel, once per instruction set (see simd/rows.h). */
void rte_lane_cue_row_c(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst, int32_t width,
                        const rte_lane_cue *cue, bool rgb)
{
    lane_cue_row(gray, bgr, dst, width, cue, rgb);
}

rte_lane_cue_row_fn rte_lane_cue_row_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, rte_lane_cue_row_c, rte_lane_cue_row_avx2, rte_lane_cue_row_c);
}

/* The colour cue: white or yellow paint -> 255, everything else grey scaled
 * by dim_q8 / 256. `bgr` rows hold B,G,R (R,G,B when rgb is set). */
static void lane_color_cue(const rte_lane_params *p, const rte_image_u8 *gray, const uint8_t *bgr,
                           int32_t bgr_stride, bool rgb, rte_image_u8 *dst)
{
    /* 8-bit comparisons (16 or 32 pixels per vector): a threshold of 256
     * can never be reached, so it disables its test. */
    const rte_lane_cue cue = {
        .white_min = (uint8_t)(p->white_min > 255 ? 255 : p->white_min),
        .white_on = p->white_min <= 255 ? 0xFF : 0,
        .yellow_min = (uint8_t)(p->yellow_rg_min > 255 ? 255 : p->yellow_rg_min),
        .yellow_on = p->yellow_rg_min <= 255 ? 0xFF : 0,
        .yellow_b_margin = (uint8_t)p->yellow_b_margin,
        .dim_q8 = (uint16_t)p->dim_q8,
    };
    const rte_lane_cue_row_fn row = rte_lane_cue_row_select(rte_cpu_features());
    for (int32_t y = 0; y < dst->height; y++)
        row(rte_u8_row(gray, y), bgr + (size_t)y * (size_t)bgr_stride, rte_u8_row(dst, y),
            dst->width, &cue, rgb);
}

/* Automatic Canny thresholds for this frame from the histogram of the
 * blurred pixels inside the ROI (unchanged when it is empty). */
static void lane_thresholds(rte_lane_context *ctx, const rte_image_u8 *img, const rte_image_u8 *mask,
                            int32_t *low, int32_t *high)
{
    const rte_lane_params *p = &ctx->params;
    uint32_t hist[256];
    if (rte_histogram_masked_u8(img, mask, hist) != RTE_OK)
        return;
    int32_t lo, hi;
    rte_status st = p->canny_mode == RTE_LANE_CANNY_MEDIAN
                        ? rte_threshold_auto_canny_median(hist, p->auto_sigma_permille, &lo, &hi)
                        : rte_threshold_auto_canny_otsu(hist, &lo, &hi);
    if (st == RTE_OK) {
        *low = lo;
        *high = hi;
    }
}

static int64_t lane_abs64(int64_t v)
{
    return v < 0 ? -v : v;
}

static int32_t seg_length(const rte_lane_segment *s)
{
    const int64_t dx = s->x1 - s->x0, dy = s->y1 - s->y0;
    return (int32_t)rte_isqrt64((uint64_t)(dx * dx + dy * dy));
}

/* num * 65536 / den (den > 0), without overflow for any 62-bit inputs. */
static int64_t lane_div_q16(int64_t num, int64_t den)
{
    while (lane_abs64(num) >= ((int64_t)1 << 46) || den >= ((int64_t)1 << 46)) {
        num /= 2;
        den /= 2;
    }
    return den > 0 ? num * 65536 / den : 0;
}

/* x of a line at row y, in 1/256 pixel. */
static int64_t line_x_q8(const lane_line *l, int64_t y)
{
    return l->x_mid_q8 + ((l->slope_q16 * (y - l->y_mid)) >> 8);
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

/* Weighted median of key over the segments sides[0..n) (weights: lengths). */
static int64_t weighted_median(int32_t *work, const int32_t *members, int32_t n, const int64_t *key,
                               const rte_lane_segment *segs)
{
    int64_t total = 0;
    for (int32_t i = 0; i < n; i++) {
        work[i] = members[i];
        total += seg_length(&segs[members[i]]);
    }
    lane_sort(work, key, n);
    int64_t acc = 0;
    for (int32_t i = 0; i < n; i++) {
        acc += seg_length(&segs[work[i]]);
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
    line->slope_q16 = weighted_median(work, members, n, key, segs);
    for (int32_t i = 0; i < n; i++) {
        const rte_lane_segment *s = &segs[members[i]];
        /* midpoint x (Q8) moved along the slope to y_mid */
        const int64_t xm = (int64_t)(s->x0 + s->x1) * 128, ym2 = (int64_t)(s->y0 + s->y1);
        key[members[i]] = xm - ((line->slope_q16 * (ym2 - 2 * line->y_mid)) >> 9);
    }
    line->x_mid_q8 = weighted_median(work, members, n, key, segs);
}

/* Largest horizontal distance of a segment's end points from the line, 1/256 px. */
static int64_t seg_residual_q8(const lane_line *l, const rte_lane_segment *s)
{
    const int64_t r0 = lane_abs64((int64_t)s->x0 * 256 - line_x_q8(l, s->y0));
    const int64_t r1 = lane_abs64((int64_t)s->x1 * 256 - line_x_q8(l, s->y1));
    return r0 > r1 ? r0 : r1;
}

/* What the least-squares fit knows besides the segments: the rows the lane
 * spans, and a slope to lean on (the tracked lane's, as predicted for this
 * frame) with the weight of R^3 in the units of the fit's row moment, i.e.
 * as much as a marking along R rows would give: one short dash far up the
 * image then moves the lane sideways but hardly turns it, while paint along
 * the whole lane outweighs the prior. weight 0: no prior. */
typedef struct lane_fit_hint {
    int32_t y_top, y_bottom;
    int64_t slope_q16;
    int64_t weight;
} lane_fit_hint;

/* Rows from the ROI's top row down to y, within the lane's span. */
static int64_t rows_below_top(const lane_fit_hint *h, int64_t y)
{
    const int64_t span = h->y_bottom - h->y_top, d = y - h->y_top;
    return d < 0 || span <= 0 ? 0 : d > span ? span : d;
}

/* A segment's weight by its row, /256: the inverse variance of a pixel's
 * lateral position on the road, which grows as (distance from the horizon)^2
 * in perspective (the horizon taken an eighth of the lane above the ROI
 * top). The lane near the camera is measured best and matters most: on a
 * bend, far dashes must not turn the lane away from the near ones. */
static int64_t row_weight_q8(const lane_fit_hint *h, int64_t y)
{
    const int64_t span = h->y_bottom - h->y_top, q = span / 8 + 1, d = rows_below_top(h, y);
    if (span <= 0)
        return 256;
    return 256 * (d + q) * (d + q) / ((span + q) * (span + q)) + 1;
}

/* A segment's own direction counts this many times the spread of its
 * pixels: it is fitted to all of them (the Hough refit), and on a bend the
 * markings' local direction describes the lane near them better than the
 * chord between dashes far apart. */
#define LANE_DIRECTION_WEIGHT 4

/* Weighted least squares of x on y over the inlier segments, each taken as
 * a uniform line of points (its second moment includes the segment's own
 * extent: d^2/12), weighted by length and row_weight_q8. Returns false
 * when the rows do not spread enough to give a slope and there is no prior. */
static bool fit_least_squares(const rte_lane_segment *segs, const int32_t *members, int32_t n,
                              const lane_fit_hint *hint, lane_line *line)
{
    int64_t w = 0, sx = 0, sy = 0;
    for (int32_t i = 0; i < n; i++) {
        const rte_lane_segment *s = &segs[members[i]];
        const int64_t len = seg_length(s) * row_weight_q8(hint, (s->y0 + s->y1) / 2);
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
        const int64_t len = seg_length(s) * row_weight_q8(hint, (s->y0 + s->y1) / 2);
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
    if (lane_abs64(line->slope_q16) > 64 * 65536)
        return false;
    /* x at y_mid from the weighted means (Q8) */
    line->x_mid_q8 = sx * 128 / w + ((line->slope_q16 * ((int64_t)line->y_mid * 256 - sy * 128 / w)) >> 16);
    return true;
}

/* The robust fit of one side over members[0..n): medians first; for least
 * squares, segments beyond outlier_px are marked and the rest refitted
 * (twice, so an outlier that pulled the start is caught on the second
 * pass). Returns the supporting length. */
static int64_t fit_side(rte_lane_context *ctx, int32_t *members, int32_t n, const lane_fit_hint *hint,
                        lane_line *line, rte_lane_segment_use use)
{
    rte_lane_segment *segs = ctx->segments;
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
            rte_lane_segment *s = &segs[members[i]];
            if (seg_residual_q8(line, s) <= pass_tol) {
                s->use = use;
                members[kept++] = members[i];
            } else {
                s->use = RTE_LANE_SEG_OUTLIER;
            }
        }
        n = kept;
        if (ctx->params.fit == RTE_LANE_FIT_THEIL_SEN || n == 0)
            break;
        lane_line ls = *line;
        if (fit_least_squares(segs, members, n, hint, &ls))
            *line = ls;
    }
    int64_t support = 0;
    for (int32_t i = 0; i < kept; i++)
        support += seg_length(&segs[members[i]]);
    return support;
}

/* Half-width of the band of edge pixels around a fitted lane at row y:
 * `tol` on the bottom row, shrinking in perspective towards the horizon to
 * about a quarter of it on the ROI's top row (near the top the two lanes
 * are only tens of pixels apart), at least 5 px so both edges of a narrow
 * far marking stay in, and at most LANE_BAND_MAX. */
#define LANE_BAND_MAX 64
static int64_t band_px(const lane_fit_hint *h, int64_t tol, int32_t y)
{
    const int64_t span = h->y_bottom - h->y_top, q = 3 * (span / 8 + 1);
    const int64_t b = span > 0 ? tol * (rows_below_top(h, y) + q) / (span + q) : tol;
    return b < 5 ? 5 : b > LANE_BAND_MAX ? LANE_BAND_MAX : b;
}

/* The edge pixels of columns xa..xb of one row that run along a line. */
typedef struct band_pixels {
    int64_t n, sum_x;    /* how many, and the sum of their x */
    int64_t first, last; /* the outermost */
} band_pixels;

/* Eight bytes, the first in the lowest bits whatever the byte order. */
static inline uint64_t load_le64(const uint8_t *p)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return v;
}

static inline void band_add(band_pixels *px, int64_t x)
{
    px->n++;
    px->sum_x += x;
    px->first = x < px->first ? x : px->first;
    px->last = x > px->last ? x : px->last;
}

/* The edge pixels in columns xa..xb (inside the map) of row y of `edges`
 * that run along a line of slope_q16 (x per row): each needs an edge pixel
 * in the row above or below at one of the two columns the slope reaches
 * there, so edges crossing the line (shadows, patch borders, car bumpers)
 * do not count. Eight pixels at a time away from the map's borders. */
static band_pixels band_row(const rte_image_u8 *edges, int32_t y, int64_t xa, int64_t xb, int64_t slope_q16)
{
    band_pixels px = {0, 0, INT64_MAX, INT64_MIN};
    const uint8_t *row = rte_u8_row(edges, y);
    const uint8_t *up = y > 0 ? row - edges->stride : NULL;
    const uint8_t *down = y < edges->height - 1 ? row + edges->stride : NULL;
    /* below: x + slope lies in [x + step, x + step + 1]; above: x - slope
     * in [x - back, x - back + 1] */
    const int64_t step = slope_q16 >> 16, back = step + ((slope_q16 & 0xFFFF) != 0);
    const int64_t words_end = xa + ((xb - xa) / 8 + 1) * 8; /* the word loop reads up to here + 1 */
    if (up && down && xa - back >= 0 && xa + step >= 0 && words_end + 1 - back <= edges->width &&
        words_end + 1 + step <= edges->width && words_end <= edges->width) {
        const uint64_t low7 = 0x7F7F7F7F7F7F7F7Fu;
        for (int64_t x = xa; x <= xb; x += 8) {
            uint64_t h = load_le64(row + x);
            if (xb - x < 7)
                h &= ((uint64_t)1 << (8 * (xb - x + 1))) - 1; /* bytes past xb */
            if (!h)
                continue;
            const uint64_t m = h & (load_le64(up + x - back) | load_le64(up + x - back + 1) |
                                    load_le64(down + x + step) | load_le64(down + x + step + 1));
            /* the top bit of each nonzero byte of m */
            for (uint64_t nz = (((m & low7) + low7) | m) & ~low7; nz; nz &= nz - 1)
                band_add(&px, x + (__builtin_ctzll(nz) >> 3));
        }
        return px;
    }
    for (int64_t x = xa; x <= xb; x++) {
        if (!row[x])
            continue;
        bool along = false;
        for (int64_t k = 0; k <= 1 && !along; k++) {
            const int64_t xu = x - back + k, xd = x + step + k;
            along = (up && xu >= 0 && xu < edges->width && up[xu]) ||
                    (down && xd >= 0 && xd < edges->width && down[xd]);
        }
        if (along)
            band_add(&px, x);
    }
    return px;
}

/* The segment fit refined on the edge pixels themselves: the edge pixels
 * within band_px of the line that run along it (band_row; `edges` and the
 * ROI mask `roi` are the crop at (cx0, cy0)) enter a weighted
 * least-squares fit of their horizontal residuals to the line (row weights
 * as for segments, the tracked slope as a prior). Up to three passes, each
 * in the band around the line of the one before, until the line's ends
 * move less than a quarter of a pixel (with two, 2 of the 136 photo runs
 * of tests/unit/test_lane.c over eight point orders of the Hough search
 * fail; with three or four, none). Short dashes and paint that the Hough
 * search left without a segment (or split differently) then count by
 * their pixels, so the lane does not depend on which segments the search
 * happened to find, and a marking's two edges put the line on its centre. */
static void refine_on_edges(const rte_image_u8 *edges, const rte_image_u8 *roi, int32_t cx0, int32_t cy0,
                            const lane_fit_hint *hint, int64_t tol, lane_line *line)
{
    const int32_t y0 = hint->y_top > cy0 ? hint->y_top : cy0;
    const int32_t y1 = hint->y_bottom < cy0 + edges->height - 1 ? hint->y_bottom : cy0 + edges->height - 1;
    const int64_t half_span = (hint->y_bottom - hint->y_top) / 2 + 1;
    for (int pass = 0; pass < 3; pass++) {
        /* Sums over the pixels of rw, rw Y, rw r, rw Y^2 and rw Y r, with
         * rw the row weight (<= 257, /256), Y = y - y_mid (|Y| <= 4096 px)
         * and r the residual to the line (|r| <= 65 px, in 1/256 px): at
         * most 8192 rows of 129 pixels keep every sum, and the products
         * with the mean below, under 2^63. */
        int64_t sw = 0, sy = 0, sr = 0, syy = 0, syr = 0;
        for (int32_t y = y0; y <= y1; y++) {
            const int64_t band = band_px(hint, tol, y);
            const int64_t lx = line_x_q8(line, y), xa = ((lx + 128) >> 8) - band - cx0, xb = xa + 2 * band;
            /* Only rows where the whole band is inside the ROI: where the
             * ROI's border cuts a marking, its edge on the inside alone
             * would pull the line off the marking's centre. */
            if (xa < 0 || xb > edges->width - 1)
                continue;
            const uint8_t *inside = rte_u8_row(roi, y - cy0);
            if (!inside[xa] || !inside[xb])
                continue;
            const band_pixels px = band_row(edges, y - cy0, xa, xb, line->slope_q16);
            /* Both edges of the marking, one either side of the line: a row
             * where one of them is missing (worn paint, a shadow's border on
             * it, the end of a dash) would pull the line to the other. */
            if (px.n == 0 || (px.first + cx0) * 256 >= lx || (px.last + cx0) * 256 <= lx)
                continue;
            const int64_t rw = row_weight_q8(hint, y), Y = y - line->y_mid;
            const int64_t r = (px.sum_x + px.n * cx0) * 256 - px.n * lx; /* sum of the residuals */
            sw += rw * px.n;
            sy += rw * px.n * Y;
            sr += rw * r;
            syy += rw * px.n * Y * Y;
            syr += rw * Y * r;
        }
        if (sw < 256 * 8)
            return; /* hardly any paint near the line: keep it */
        const int64_t my_q8 = sy * 256 / sw; /* mean Y */
        const int64_t cyy = syy - ((my_q8 * sy) >> 8), cyr = syr - ((my_q8 * sr) >> 8);
        /* The tracked slope as a prior with the weight of a marking along a
         * fifth of the lane (both its edges: R^3 rw / 6 in these units). */
        const int64_t prior = hint->weight / 6;
        int64_t dslope_q16 = 0;
        if (prior > 0)
            dslope_q16 = lane_div_q16(cyr + (prior * (hint->slope_q16 - line->slope_q16) >> 8), (cyy + prior) * 256);
        else if (cyy >= sw * 64) /* rows spread over ~8 px at least */
            dslope_q16 = lane_div_q16(cyr, cyy * 256);
        const int64_t slope = line->slope_q16 + dslope_q16;
        if (lane_abs64(slope) > 64 * 65536)
            return;
        const int64_t dx_mid = sr / sw - ((dslope_q16 * my_q8) >> 16);
        line->x_mid_q8 += dx_mid;
        line->slope_q16 = slope;
        /* settled: both ends moved less than a quarter of a pixel */
        if (lane_abs64(dx_mid) + ((lane_abs64(dslope_q16) * half_span) >> 8) < 64)
            return;
    }
}

/* Tracked lane x at row y (1/256 px), from its bottom and top points. */
static int64_t track_x_q8(const lane_track *t, int32_t y_bottom, int32_t y_top, int32_t y)
{
    const int32_t span = y_bottom - y_top;
    if (span <= 0)
        return t->x_bottom_q8;
    return t->x_bottom_q8 +
           (int64_t)(t->x_top_q8 - t->x_bottom_q8) * (y_bottom - y) / span;
}

static int32_t clamp32(int64_t v, int64_t lo, int64_t hi)
{
    return (int32_t)(v < lo ? lo : v > hi ? hi : v);
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

static void lane_track_update(rte_lane_context *ctx, int side, bool seen, const lane_line *line,
                              int64_t support, rte_lane *out)
{
    const rte_lane_params *p = &ctx->params;
    lane_track *t = &ctx->track[side];
    const int64_t mb = seen ? line_x_q8(line, out->y_bottom) : 0;
    const int64_t mt = seen ? line_x_q8(line, out->y_top) : 0;
    const int64_t lim = 1 << 28; /* keeps far-off extrapolations in range */
    if (seen && !t->valid) {
        t->valid = true;
        t->x_bottom_q8 = clamp32(mb, -lim, lim);
        t->x_top_q8 = clamp32(mt, -lim, lim);
        t->v_bottom_q8 = t->v_top_q8 = 0;
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
            const int64_t share = clamp32(support * 256 / len, 32, 256); /* /256 */
            const int64_t alpha = (int64_t)p->alpha_q8 * share >> 8;
            const int64_t step = (int64_t)p->max_step_px * 256;
            const int64_t rb = clamp32(mb - pb, -step, step), rt = clamp32(mt - pt, -step, step);
            t->x_bottom_q8 = clamp32(pb + ((rb * alpha) >> 8), -lim, lim);
            t->x_top_q8 = clamp32(pt + ((rt * alpha) >> 8), -lim, lim);
            t->v_bottom_q8 = clamp32(t->v_bottom_q8 + ((rb * p->beta_q8) >> 8), -step, step);
            t->v_top_q8 = clamp32(t->v_top_q8 + ((rt * p->beta_q8) >> 8), -step, step);
            t->lost = 0;
        } else if (++t->lost > p->hold_frames) {
            t->valid = false;
        } else {
            /* Held as predicted; the velocity fades (by 1/8 a frame) so a
             * lane held for long settles instead of drifting away. */
            t->x_bottom_q8 = clamp32(pb, -lim, lim);
            t->x_top_q8 = clamp32(pt, -lim, lim);
            t->v_bottom_q8 -= t->v_bottom_q8 / 8;
            t->v_top_q8 -= t->v_top_q8 / 8;
        }
    }
    out->found = t->valid;
    out->predicted = t->valid && t->lost > 0;
    out->lost_frames = t->valid ? t->lost : 0;
    out->support_px = (int32_t)(support > INT32_MAX ? INT32_MAX : support);
    if (t->valid) {
        out->x_bottom_q8 = t->x_bottom_q8;
        out->x_top_q8 = t->x_top_q8;
        const int64_t dx = ((int64_t)t->x_top_q8 - t->x_bottom_q8) / 256;
        const int64_t dy = out->y_bottom - out->y_top;
        const int64_t len = rte_isqrt64((uint64_t)(dx * dx + dy * dy));
        out->confidence_permille = len > 0 ? clamp32(support * 1000 / len, 0, 1000) : 0;
    }
}

/* Sorts the Hough segments into sides by slope, position and the gate;
 * fills side lists and marks rejected ones. */
static void lane_classify(rte_lane_context *ctx, int32_t count, int32_t width, int32_t y_bottom,
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
        const int64_t adx = lane_abs64(dx);
        /* dy/dx < 0 in image coordinates (y down): the left lane */
        const int side = dx < 0 ? RTE_LANE_LEFT : RTE_LANE_RIGHT;
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
            const int64_t d = lane_abs64(mid2 * 128 - track_x_q8(t, y_bottom, y_top, (int32_t)ym));
            if (d > (int64_t)p->gate_px * 256) {
                s->use = RTE_LANE_SEG_REJECTED_GATE;
                continue;
            }
        }
        members[side][n[side]++] = i;
    }
}

/* gray_ns: time already spent making `gray` (counted in the grey stage). */
static rte_status lane_run(rte_lane_context *ctx, const rte_image_u8 *gray, const uint8_t *color,
                           int32_t color_stride, bool rgb, int64_t t_ns, int64_t gray_ns,
                           rte_lane_result *out)
{
    int64_t t0 = rte_clock_now_ns() - gray_ns, t1;
    const int32_t w = gray->width, h = gray->height;
    memset(out, 0, sizeof *out);
    out->t_ns = t_ns;
    rte_status st = lane_roi(ctx, w, h);
    if (st != RTE_OK)
        return st;
    const rte_lane_params *p = &ctx->params;
    const int32_t cx0 = ctx->crop_x0, cy0 = ctx->crop_y0, cx1 = ctx->crop_x1, cy1 = ctx->crop_y1;
    const int32_t cw = cx1 - cx0, ch = cy1 - cy0;
    rte_image_u8 src = lane_view(gray, cx0, cy0, cx1, cy1);
    if (color && p->use_color) {
        rte_image_u8 cue = lane_view(&ctx->cue, 0, 0, cw, ch);
        lane_color_cue(p, &src, color + (size_t)cy0 * (size_t)color_stride + (size_t)cx0 * 3,
                       color_stride, rgb, &cue);
        src = cue;
    }
    t1 = rte_clock_now_ns();
    out->stage_ns[RTE_LANE_STAGE_GRAY] = t1 - t0;
    t0 = t1;

    rte_image_u8 mask = lane_view(&ctx->mask, 0, 0, cw, ch);
    rte_image_u8 edges = lane_view(&ctx->edges, 0, 0, cw, ch);
    int32_t low = p->canny_low, high = p->canny_high;
    if (p->canny_mode == RTE_LANE_CANNY_FIXED) {
        /* Fused front end: blur, Sobel and suppression over a band of rows,
         * no blurred image (its time counts in the Canny stage). */
        ctx->canny.low = low;
        ctx->canny.high = high;
        if ((st = rte_canny_blurred_u8(&src, &edges, &ctx->blur, &ctx->canny, &ctx->arena)) != RTE_OK)
            return st;
    } else {
        /* The thresholds come from the blurred pixels' histogram, so the
         * blurred image is needed before any suppression. */
        rte_image_u8 blurred = lane_view(&ctx->blurred, 0, 0, cw, ch);
        if ((st = rte_gaussian_blur_u8(&src, &blurred, &ctx->blur, &ctx->arena)) != RTE_OK)
            return st;
        t1 = rte_clock_now_ns();
        out->stage_ns[RTE_LANE_STAGE_BLUR] = t1 - t0;
        t0 = t1;
        lane_thresholds(ctx, &blurred, &mask, &low, &high);
        /* Integer thresholds on the L1 magnitude of a 3x3 Sobel are what
         * rte_canny_params_init gives for whole numbers: set them directly. */
        ctx->canny.low = low;
        ctx->canny.high = high;
        if ((st = rte_canny_u8(&blurred, &edges, &ctx->canny, &ctx->arena)) != RTE_OK)
            return st;
    }
    out->canny_low = low;
    out->canny_high = high;
    if ((st = rte_polygon_mask_apply(&edges, &mask, &edges)) != RTE_OK)
        return st;
    t1 = rte_clock_now_ns();
    out->stage_ns[RTE_LANE_STAGE_CANNY] = t1 - t0;
    t0 = t1;

    const rte_hough_segments_params hp = {p->hough_threshold, p->min_length, p->max_gap, p->hough_seed};
    int32_t count = 0;
    bool truncated = false;
    if ((st = rte_hough_segments(ctx->hough, &edges, &hp, &ctx->arena, ctx->raw,
                                 ctx->cfg.max_segments, &count, &truncated)) != RTE_OK)
        return st;
    for (int32_t i = 0; i < count; i++) {
        rte_lane_segment *s = &ctx->segments[i];
        s->x0 = ctx->raw[i].x0 + cx0;
        s->y0 = ctx->raw[i].y0 + cy0;
        s->x1 = ctx->raw[i].x1 + cx0;
        s->y1 = ctx->raw[i].y1 + cy0;
    }
    t1 = rte_clock_now_ns();
    out->stage_ns[RTE_LANE_STAGE_HOUGH] = t1 - t0;
    t0 = t1;

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
    lane_classify(ctx, count, w, y_bottom, y_top, members, n);
    for (int side = 0; side < 2; side++) {
        rte_lane *lane = &out->lane[side];
        lane->y_bottom = y_bottom;
        lane->y_top = y_top;
        lane_line line = {0, 0, (y_bottom + y_top) / 2};
        const lane_track *t = &ctx->track[side];
        lane_fit_hint hint = {y_top, y_bottom, 0, 0};
        if (t->valid && y_bottom > y_top) {
            const int64_t dx = ((int64_t)t->x_top_q8 + t->v_top_q8) - ((int64_t)t->x_bottom_q8 + t->v_bottom_q8);
            const int64_t rows = (y_bottom - y_top) / 5 + 1; /* a fifth of the lane */
            hint.slope_q16 = clamp32(dx * 256 / (y_top - y_bottom), -64 * 65536, 64 * 65536);
            hint.weight = rows * rows * rows * 128; /* 128: the mean row weight */
        }
        const int64_t support = fit_side(ctx, members[side], n[side], &hint, &line,
                                         side == RTE_LANE_LEFT ? RTE_LANE_SEG_LEFT : RTE_LANE_SEG_RIGHT);
        if (support > 0 && p->fit == RTE_LANE_FIT_LEAST_SQUARES)
            refine_on_edges(&edges, &mask, cx0, cy0, &hint, (int64_t)p->outlier_px, &line);
        const bool seen = support > 0 && support >= p->min_support_px;
        lane_track_update(ctx, side, seen, &line, support, lane);
    }
    const rte_lane *l = &out->lane[RTE_LANE_LEFT], *r = &out->lane[RTE_LANE_RIGHT];
    if (l->found && r->found && r->x_bottom_q8 > l->x_bottom_q8) {
        out->centre_valid = true;
        const int64_t cb = ((int64_t)l->x_bottom_q8 + r->x_bottom_q8) / 2;
        const int64_t ct = ((int64_t)l->x_top_q8 + r->x_top_q8) / 2;
        out->offset_q8 = (int32_t)(cb - (int64_t)(w - 1) * 128);
        out->offset_permille = (int32_t)((int64_t)out->offset_q8 * 1000 / (r->x_bottom_q8 - l->x_bottom_q8));
        const int64_t dy = y_bottom - y_top;
        out->heading_tan_q16 = dy > 0 ? clamp32((ct - cb) * 256 / dy, -INT32_MAX, INT32_MAX) : 0;
        out->heading_mrad = lane_atan_mrad(out->heading_tan_q16);
    }
    out->segments = ctx->segments;
    out->segment_count = count;
    out->truncated = truncated;
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
    return lane_run(ctx, gray, bgr ? bgr->buf : NULL, bgr ? bgr->stride : 0, false, t_ns, 0, out);
}

rte_status rte_lane_process(rte_lane_context *ctx, const rte_frame *frame, int64_t t_ns,
                            rte_lane_result *out)
{
    if (!ctx || !out)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_frame_check(frame);
    if (st != RTE_OK || (st = lane_check_size(ctx, frame->width, frame->height)) != RTE_OK)
        return st;
    rte_image_u8 gray;
    if (rte_frame_gray_view(frame, &gray) == RTE_OK)
        return lane_run(ctx, &gray, NULL, 0, false, t_ns, 0, out);
    const int64_t t0 = rte_clock_now_ns();
    const bool colour = frame->format == RTE_PIXEL_BGR24 || frame->format == RTE_PIXEL_RGB24;
    /* Only the ROI's bounding box is read: with 3-byte pixels (where any
     * crop is a plain view of the frame) only that part becomes grey. */
    rte_frame part = *frame;
    int32_t x0 = 0, y0 = 0;
    if (colour && lane_roi(ctx, frame->width, frame->height) == RTE_OK) {
        x0 = ctx->crop_x0;
        y0 = ctx->crop_y0;
        part.width = ctx->crop_x1 - x0;
        part.height = ctx->crop_y1 - y0;
        part.plane[0] += (size_t)y0 * (size_t)frame->stride[0] + 3 * (size_t)x0;
    }
    gray = lane_view(&ctx->gray, x0, y0, x0 + part.width, y0 + part.height);
    if ((st = rte_frame_to_gray(&part, &gray)) != RTE_OK)
        return st;
    gray = lane_view(&ctx->gray, 0, 0, frame->width, frame->height);
    return lane_run(ctx, &gray, colour ? frame->plane[0] : NULL, frame->stride[0],
                    frame->format == RTE_PIXEL_RGB24, t_ns, rte_clock_now_ns() - t0, out);
}
