/* The lane path's image cues, per frame (integer only): the colour cue
 * that makes white and yellow paint stand out, and the automatic Canny
 * thresholds (see include/rtedge/lane.h and docs/lanes.md). */
#include "lane_cue_rows.h"
#include "lane_fixed.h"
#include "lane_internal.h"
#include "rtedge/cpu.h"
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

/* The colour cue: white or yellow paint -> 255, everything else grey scaled
 * by dim_q8 / 256. `bgr` rows hold B,G,R (R,G,B when rgb is set). */
void rte_lane_color_cue(const rte_lane_params *p, const rte_image_u8 *gray, const uint8_t *bgr,
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
void rte_lane_thresholds(rte_lane_context *ctx, const rte_image_u8 *img, const rte_image_u8 *mask,
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

/* The share of the ROI washed out by glare, in permille: grey pixels at
 * LANE_SATURATED or more inside the mask, on a grid of every fourth row
 * and column (a frame-wide figure, which needs no more: 23 000 samples at
 * 1280x720). */
int32_t rte_lane_glare_permille(const rte_image_u8 *gray_crop, const rte_image_u8 *mask)
{
    int64_t all = 0, glare = 0;
    for (int32_t y = 0; y < mask->height; y += 4) {
        const uint8_t *g = rte_u8_row(gray_crop, y), *m = rte_u8_row(mask, y);
        for (int32_t x = 0; x < mask->width; x += 4) {
            all += m[x] != 0;
            glare += m[x] != 0 && g[x] >= LANE_SATURATED;
        }
    }
    return all > 0 ? (int32_t)(glare * 1000 / all) : 0;
}
