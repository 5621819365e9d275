/* Lane context creation: sizes, the Gaussian taps and the Hough tables
 * (floating point is allowed here, not in the per-frame lane files). */
#include <stdlib.h>
#include <string.h>

#include "lane_internal.h"
#include "rtedge/threshold.h"

void rte_lane_config_default(rte_lane_config *cfg, int32_t width, int32_t height)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->max_width = width;
    cfg->max_height = height;
    cfg->max_segments = 512;
    cfg->blur_ksize = 5;
    rte_lane_params *p = &cfg->params;
    const int32_t one = RTE_POLYGON_FRACTION_ONE;
    /* The tutorial trapezoid: bottom corners, apex band at 60% of the height. */
    const rte_vertex roi[4] = {
        {0, one}, {one * 45 / 100, one * 60 / 100}, {one * 55 / 100, one * 60 / 100}, {one, one}};
    memcpy(p->roi, roi, sizeof roi);
    p->roi_count = 4;
    p->canny_mode = RTE_LANE_CANNY_MEDIAN; /* robust to exposure: see docs/lanes.md */
    p->canny_low = 50;
    p->canny_high = 150;
    p->auto_sigma_permille = RTE_AUTO_CANNY_SIGMA_PERMILLE;
    p->use_color = true;
    p->curves = true;
    p->white_min = 200;
    p->yellow_rg_min = 120;
    p->yellow_b_margin = 50;
    p->dim_q8 = 160;
    /* Lengths scale with the frame height (540 rows: the tutorial's values). */
    int32_t s = height > 0 ? height : 540;
    p->hough_threshold = 15 * s / 540 > 8 ? 15 * s / 540 : 8;
    p->min_length = 20 * s / 540 > 8 ? 20 * s / 540 : 8;
    p->max_gap = 20 * s / 540 > 4 ? 20 * s / 540 : 4;
    p->hough_seed = 0;
    p->left_min_slope_q8 = 128;  /* |dy/dx| >= 0.5: steeper than 27 degrees */
    p->left_max_slope_q8 = 2560; /* <= 10: not vertical (image borders, poles) */
    p->right_min_slope_q8 = 128;
    p->right_max_slope_q8 = 2560;
    p->fit = RTE_LANE_FIT_LEAST_SQUARES;
    p->outlier_px = 20 * s / 540 > 4 ? 20 * s / 540 : 4;
    p->min_support_px = 30 * s / 540 > 8 ? 30 * s / 540 : 8;
    p->gate_px = 40 * s / 540 > 8 ? 40 * s / 540 : 8;
    p->hold_frames = 5;
    p->alpha_q8 = 160;
    p->beta_q8 = 32;
    p->max_step_px = 30 * s / 540 > 4 ? 30 * s / 540 : 4;
}

/* One image of the context's block. */
static void lane_image(rte_image_u8 *img, uint8_t **cursor, int32_t width, int32_t height)
{
    img->width = width;
    img->height = height;
    img->stride = (width + 63) & ~63;
    img->buf = *cursor;
    *cursor += (size_t)img->stride * (size_t)height;
}

rte_status rte_lane_create(const rte_lane_config *cfg, rte_lane_context **out)
{
    if (!out)
        return RTE_ERR_ARGUMENT;
    *out = NULL;
    if (!cfg || cfg->max_width < 1 || cfg->max_height < 1 || cfg->max_width > RTE_LANE_MAX_SIDE ||
        cfg->max_height > RTE_LANE_MAX_SIDE || cfg->max_segments < 1 ||
        cfg->max_segments > RTE_LANE_MAX_SEGMENTS)
        return RTE_ERR_ARGUMENT;
    rte_lane_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return RTE_ERR_NO_MEMORY;
    ctx->cfg = *cfg;
    ctx->hough = calloc(1, sizeof *ctx->hough);
    if (!ctx->hough) {
        rte_lane_destroy(ctx);
        return RTE_ERR_NO_MEMORY;
    }
    if (rte_gaussian_kernel_init(&ctx->blur, cfg->blur_ksize, cfg->blur_ksize, 0, 0) != RTE_OK ||
        rte_hough_config_init(ctx->hough, cfg->max_width, cfg->max_height, 1.0,
                              3.14159265358979323846 / 180.0, 0.0,
                              3.14159265358979323846) != RTE_OK ||
        rte_canny_params_init(&ctx->canny, 50, 150, 3, false) != RTE_OK ||
        rte_lane_set_params(ctx, &cfg->params) != RTE_OK) {
        rte_lane_destroy(ctx);
        return RTE_ERR_ARGUMENT;
    }
    const int32_t w = cfg->max_width, h = cfg->max_height, n = cfg->max_segments;
    const size_t plane = (size_t)((w + 63) & ~63) * (size_t)h;
    size_t scratch = rte_gaussian_blur_u8_scratch_size(w, h, &ctx->blur);
    size_t s = rte_canny_blurred_scratch_size(w, h, &ctx->blur, 3);
    scratch = s > scratch ? s : scratch;
    s = rte_hough_segments_scratch_size(ctx->hough);
    scratch = s > scratch ? s : scratch;
    s = rte_polygon_mask_scratch_size(RTE_LANE_MAX_ROI_VERTICES);
    scratch = s > scratch ? s : scratch;
    const size_t lists = (size_t)n * (sizeof(rte_hough_segment) + sizeof(rte_lane_segment) +
                                      4 * sizeof(int32_t) + 2 * sizeof(int64_t));
    const int32_t half_w = (w + 1) / 2 + 1, half_h = (h + 1) / 2 + 1;
    const size_t half_plane = (size_t)((half_w + 63) & ~63) * (size_t)half_h;
    const size_t span_row = ((size_t)h * sizeof(int32_t) + 63) & ~(size_t)63;
    size_t total = 6 * plane + 2 * half_plane + lists + 2 * span_row + 64 * 8 + scratch;
    uint8_t *mem = aligned_alloc(64, (total + 63) & ~(size_t)63);
    if (!mem) {
        rte_lane_destroy(ctx);
        return RTE_ERR_NO_MEMORY;
    }
    ctx->memory = mem;
    uint8_t *cur = mem;
    lane_image(&ctx->gray, &cur, w, h);
    lane_image(&ctx->cue, &cur, w, h);
    lane_image(&ctx->blurred, &cur, w, h);
    lane_image(&ctx->edges, &cur, w, h);
    lane_image(&ctx->edges_roi, &cur, w, h);
    lane_image(&ctx->mask, &cur, w, h);
    lane_image(&ctx->cb, &cur, half_w, half_h);
    lane_image(&ctx->cr, &cur, half_w, half_h);
    ctx->raw = (rte_hough_segment *)cur;
    cur += ((size_t)n * sizeof(rte_hough_segment) + 63) & ~(size_t)63;
    ctx->segments = (rte_lane_segment *)cur;
    cur += ((size_t)n * sizeof(rte_lane_segment) + 63) & ~(size_t)63;
    ctx->order = (int32_t *)cur;
    cur += ((size_t)n * 3 * sizeof(int32_t) + 63) & ~(size_t)63;
    ctx->weight = (int32_t *)cur;
    cur += ((size_t)n * sizeof(int32_t) + 63) & ~(size_t)63;
    ctx->keys = (int64_t *)cur;
    cur += ((size_t)n * 2 * sizeof(int64_t) + 63) & ~(size_t)63;
    ctx->roi_x0 = (int32_t *)cur;
    cur += span_row;
    ctx->roi_x1 = (int32_t *)cur;
    cur += span_row;
    rte_arena_init(&ctx->arena, cur, total - (size_t)(cur - mem));
    *out = ctx;
    return RTE_OK;
}

void rte_lane_destroy(rte_lane_context *ctx)
{
    if (!ctx)
        return;
    free(ctx->memory);
    free(ctx->hough);
    free(ctx);
}
