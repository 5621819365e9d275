/* The lane path's image cues, per frame (integer only): the colour cue
 * that makes white and yellow paint stand out, the ROI's spans, and the
 * automatic Canny thresholds (see include/rtedge/lane.h and
 * docs/lanes.md). */
#include <string.h>

#include "lane_cue_rows.h"
#include "lane_fixed.h"
#include "lane_internal.h"
#include "rtedge/color.h"
#include "rtedge/cpu.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/threshold.h"

/* The colour cue's row kernel, once per instruction set (see simd/rows.h). */
void rte_lane_cue_row_c(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst, int32_t width,
                        const rte_lane_cue *cue, bool rgb)
{
    lane_cue_row(gray, bgr, dst, width, cue, rgb);
}

rte_lane_cue_row_fn rte_lane_cue_row_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, rte_lane_cue_row_c, rte_lane_cue_row_avx2,
                         rte_lane_cue_row_avx512, rte_lane_cue_row_c);
}

void rte_lane_cue_chroma_row_c(const uint8_t *const g[2], const uint8_t *cb, const uint8_t *cr,
                               bool interleaved, uint8_t *const d[2], int32_t width, bool odd,
                               const rte_lane_cue *cue)
{
    lane_cue_chroma_rows(g, cb, cr, interleaved, d, width, odd, cue);
}

rte_lane_cue_chroma_row_fn rte_lane_cue_chroma_row_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, rte_lane_cue_chroma_row_c, rte_lane_cue_chroma_row_avx2,
                         rte_lane_cue_chroma_row_avx512, rte_lane_cue_chroma_row_c);
}

/* The rules in the row kernels' 8-bit form: a threshold of 256 can never
 * be reached, so it disables its test. */
static rte_lane_cue lane_cue_rules(const rte_lane_params *p)
{
    return (rte_lane_cue){
        .white_min = (uint8_t)(p->white_min > 255 ? 255 : p->white_min),
        .white_on = p->white_min <= 255 ? 0xFF : 0,
        .yellow_min = (uint8_t)(p->yellow_rg_min > 255 ? 255 : p->yellow_rg_min),
        .yellow_on = p->yellow_rg_min <= 255 ? 0xFF : 0,
        .yellow_b_margin = (uint8_t)p->yellow_b_margin,
        .dim_q8 = (uint16_t)p->dim_q8,
    };
}

/* The colour cue: white or yellow paint -> 255, everything else grey scaled
 * by dim_q8 / 256. `bgr` rows hold B,G,R (R,G,B when rgb is set). */
void rte_lane_color_cue(const rte_lane_params *p, const rte_image_u8 *gray, const uint8_t *bgr,
                        int32_t bgr_stride, bool rgb, rte_image_u8 *dst)
{
    const rte_lane_cue cue = lane_cue_rules(p);
    const rte_lane_cue_row_fn row = rte_lane_cue_row_select(rte_cpu_features());
    for (int32_t y = 0; y < dst->height; y++)
        row(rte_u8_row(gray, y), bgr + (size_t)y * (size_t)bgr_stride, rte_u8_row(dst, y),
            dst->width, &cue, rgb);
}

void rte_lane_chroma_cue(const rte_lane_params *p, const rte_image_u8 *gray,
                         const lane_colour *colour, rte_image_u8 *dst)
{
    const rte_lane_cue cue = lane_cue_rules(p);
    const rte_lane_cue_chroma_row_fn row = rte_lane_cue_chroma_row_select(rte_cpu_features());
    const int32_t h = dst->height, odd_y = colour->odd_y;
    for (int32_t y = 0; y < h;) {
        /* the rows on chroma row c: one when the crop starts on a block's
         * second row or ends on its first, else two */
        const int32_t c = (y + odd_y) >> 1;
        const bool two = y + 1 < h && ((y + 1 + odd_y) >> 1) == c;
        const uint8_t *g[2] = {rte_u8_row(gray, y), two ? rte_u8_row(gray, y + 1) : NULL};
        uint8_t *d[2] = {rte_u8_row(dst, y), two ? rte_u8_row(dst, y + 1) : NULL};
        const size_t at = (size_t)c * (size_t)colour->chroma_stride;
        row(g, colour->cb + at, colour->cr + at, colour->interleaved, d, dst->width, colour->odd_x,
            &cue);
        y += two ? 2 : 1;
    }
}

rte_status rte_lane_frame_chroma(rte_lane_context *ctx, const rte_frame *frame, lane_colour *colour)
{
    /* the crop widened to whole chroma blocks on its left and top */
    const int32_t x0 = ctx->crop_x0 & ~1, y0 = ctx->crop_y0 & ~1;
    *colour = (lane_colour){
        .chroma = true, .odd_x = (ctx->crop_x0 & 1) != 0, .odd_y = (ctx->crop_y0 & 1) != 0};
    if (frame->format == RTE_PIXEL_NV12) {
        colour->interleaved = true;
        colour->cb = frame->plane[1] + (size_t)(y0 / 2) * (size_t)frame->stride[1] + (size_t)x0;
        colour->cr = colour->cb + 1;
        colour->chroma_stride = frame->stride[1];
        return RTE_OK;
    }
    if (frame->format != RTE_PIXEL_YUYV && frame->format != RTE_PIXEL_UYVY)
        return RTE_ERR_UNSUPPORTED;
    const rte_frame part = lane_frame_part(frame, x0, y0, ctx->crop_x1, ctx->crop_y1);
    const int32_t cw = (part.width + 1) / 2, ch = (part.height + 1) / 2;
    rte_image_u8 cb = rte_image_u8_view(ctx->cb.buf, cw, ch, ctx->cb.stride);
    rte_image_u8 cr = rte_image_u8_view(ctx->cr.buf, cw, ch, ctx->cr.stride);
    rte_status st = rte_frame_chroma_half(&part, &cb, &cr);
    colour->cb = cb.buf;
    colour->cr = cr.buf;
    colour->chroma_stride = cb.stride;
    return st;
}

void rte_lane_roi_spans(rte_lane_context *ctx, const rte_image_u8 *mask)
{
    ctx->roi_spans = true;
    for (int32_t y = 0; y < mask->height; y++) {
        const uint8_t *m = rte_u8_row(mask, y);
        int32_t a = 0, b = mask->width;
        while (a < b && m[a] == 0)
            a++;
        while (b > a && m[b - 1] == 0)
            b--;
        for (int32_t x = a; x < b; x++)
            ctx->roi_spans = ctx->roi_spans && m[x] != 0;
        ctx->roi_x0[y] = a;
        ctx->roi_x1[y] = b;
    }
}

rte_status rte_lane_keep_roi(const rte_lane_context *ctx, const rte_image_u8 *edges,
                             const rte_image_u8 *mask, rte_image_u8 *inside)
{
    if (!ctx->roi_spans)
        return rte_polygon_mask_apply(edges, mask, inside);
    for (int32_t y = 0; y < edges->height; y++) {
        const uint8_t *e = rte_u8_row(edges, y);
        uint8_t *in = rte_u8_row(inside, y);
        const int32_t a = ctx->roi_x0[y], b = ctx->roi_x1[y];
        memset(in, 0, (size_t)a);
        memcpy(in + a, e + a, (size_t)(b - a));
        memset(in + b, 0, (size_t)(edges->width - b));
    }
    return RTE_OK;
}

/* Automatic Canny thresholds for this frame from the histogram of the
 * blurred pixels inside the ROI (unchanged when it is empty). */
void rte_lane_thresholds(rte_lane_context *ctx, const rte_image_u8 *img, const rte_image_u8 *mask,
                         int32_t *low, int32_t *high)
{
    const rte_lane_params *p = &ctx->params;
    uint32_t hist[256];
    const rte_status counted = ctx->roi_spans
                                   ? rte_histogram_spans_u8(img, ctx->roi_x0, ctx->roi_x1, hist)
                                   : rte_histogram_masked_u8(img, mask, hist);
    if (counted != RTE_OK)
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

/* The share of the ROI washed out by glare, in permille: grey pixels at
 * LANE_SATURATED or more inside the mask, on a grid of every fourth row
 * and column (a frame-wide figure, which needs no more: 23 000 samples at
 * 1280x720). */
int32_t rte_lane_glare_permille(const rte_lane_context *ctx, const rte_image_u8 *gray_crop,
                                const rte_image_u8 *mask)
{
    int64_t all = 0, glare = 0;
    for (int32_t y = 0; y < mask->height; y += 4) {
        const uint8_t *g = rte_u8_row(gray_crop, y), *m = rte_u8_row(mask, y);
        if (ctx->roi_spans) { /* the grid's columns within the row's span */
            for (int32_t x = (ctx->roi_x0[y] + 3) & ~3; x < ctx->roi_x1[y]; x += 4) {
                all++;
                glare += g[x] >= LANE_SATURATED;
            }
            continue;
        }
        for (int32_t x = 0; x < mask->width; x += 4) {
            all += m[x] != 0;
            glare += m[x] != 0 && g[x] >= LANE_SATURATED;
        }
    }
    return all > 0 ? (int32_t)(glare * 1000 / all) : 0;
}
