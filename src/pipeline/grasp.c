/* The grasp path, per frame (see rtedge/grasp.h). Integer only. */
#include <time.h>

#include "grasp_ctx.h"
#include "rtedge/background.h"
#include "rtedge/canny.h"
#include "rtedge/threshold.h"
#include "core/clock.h"

#define DEG90_Q16 (90 * 65536)

/* Largest L1 magnitude of the 3x3 Sobel pair on 8-bit images. */
#define CANNY_MAX 2040

rte_status rte_grasp_check_params(const rte_grasp_config *c, const rte_grasp_params *p)
{
    if (!c || !p)
        return RTE_ERR_ARGUMENT;
    const int ok =
        (p->binarize == RTE_GRASP_OTSU || p->binarize == RTE_GRASP_FIXED ||
         p->binarize == RTE_GRASP_CANNY_CLOSE || p->binarize == RTE_GRASP_BACKGROUND) &&
        p->threshold >= 0 && p->threshold <= 255 &&
        (p->polarity == RTE_GRASP_AUTO || p->polarity == RTE_GRASP_DARK ||
         p->polarity == RTE_GRASP_BRIGHT) &&
        p->canny_low >= 0 && p->canny_low <= CANNY_MAX && p->canny_high >= 0 &&
        p->canny_high <= CANNY_MAX && p->contrast >= 1 && p->contrast <= 255 &&
        (p->background_cell == 0 || (p->background_cell >= RTE_BACKGROUND_MIN_CELL &&
                                     p->background_cell <= RTE_BACKGROUND_MAX_CELL)) &&
        p->min_area >= 0 && p->max_area >= 0 && (p->skip_border == 0 || p->skip_border == 1) &&
        p->max_objects >= 1 && p->max_objects <= c->max_objects &&
        (p->roi_count == 0 || (p->roi_count >= 3 && p->roi_count <= RTE_GRASP_MAX_ROI_VERTICES));
    if (!ok)
        return RTE_ERR_ARGUMENT;
    for (int32_t i = 0; i < p->roi_count; i++)
        if (p->roi[i].x < -RTE_POLYGON_MAX_FRACTION || p->roi[i].x > RTE_POLYGON_MAX_FRACTION ||
            p->roi[i].y < -RTE_POLYGON_MAX_FRACTION || p->roi[i].y > RTE_POLYGON_MAX_FRACTION)
            return RTE_ERR_ARGUMENT;
    return RTE_OK;
}

rte_status rte_grasp_set_params(rte_grasp_ctx *ctx, const rte_grasp_params *params)
{
    if (!ctx)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_grasp_check_params(&ctx->config, params);
    if (st == RTE_OK) {
        ctx->params = *params;
        ctx->workspace_w = ctx->workspace_h = 0; /* the mask is rebuilt on the next frame */
    }
    return st;
}

rte_status rte_grasp_get_params(const rte_grasp_ctx *ctx, rte_grasp_params *params)
{
    if (!ctx || !params)
        return RTE_ERR_ARGUMENT;
    *params = ctx->params;
    return RTE_OK;
}

const char *rte_grasp_shape_name(rte_shape_class shape)
{
    static const char *const names[] = {"other",    "triangle", "square", "rectangle",
                                        "pentagon", "hexagon",  "circle"};
    return (unsigned)shape < sizeof names / sizeof names[0] ? names[shape] : "other";
}

/* A view of the first w x h pixels of a context buffer. */
static rte_image_u8 sub(const rte_image_u8 *buf, int32_t w, int32_t h)
{
    return (rte_image_u8){w, h, w, buf->buf};
}

/* Mean of the outermost rows and columns: the table, when objects lie
 * inside the view. Decides which side of the threshold is object. */
static int32_t border_mean(const rte_image_u8 *img)
{
    const int32_t w = img->width, h = img->height;
    uint64_t sum = 0, n = 0;
    const uint8_t *top = rte_u8_row(img, 0), *bottom = rte_u8_row(img, h - 1);
    for (int32_t x = 0; x < w; x++)
        sum += (uint32_t)top[x] + bottom[x];
    n += 2 * (uint64_t)w;
    for (int32_t y = 1; y + 1 < h; y++) {
        const uint8_t *row = rte_u8_row(img, y);
        sum += (uint32_t)row[0] + row[w - 1];
        n += 2;
    }
    return (int32_t)((sum + n / 2) / n);
}

static rte_status binarize(rte_grasp_ctx *ctx, const rte_image_u8 *src, rte_image_u8 *bin,
                           rte_grasp_result *out)
{
    const rte_grasp_params *p = &ctx->params;
    if (p->binarize == RTE_GRASP_CANNY_CLOSE) {
        rte_image_u8 edges = sub(&ctx->edges, src->width, src->height);
        const int32_t lo = p->canny_low < p->canny_high ? p->canny_low : p->canny_high;
        const int32_t hi = p->canny_low < p->canny_high ? p->canny_high : p->canny_low;
        /* integer thresholds are their own comparison values (L1, aperture 3) */
        const rte_canny_params cp = {.aperture = 3, .l2_gradient = false, .low = lo, .high = hi};
        rte_status st = rte_canny_u8(src, &edges, &cp, &ctx->arena);
        if (st == RTE_OK)
            st = rte_morphology_u8(&edges, bin, RTE_MORPH_CLOSE, &ctx->close,
                                   ctx->config.close_iterations, &ctx->arena);
        out->threshold = -1;
        out->polarity = RTE_GRASP_BRIGHT;
        return st;
    }
    if (p->binarize == RTE_GRASP_BACKGROUND) {
        /* the table's estimate goes where canny-close keeps its edges */
        rte_image_u8 table = sub(&ctx->edges, src->width, src->height);
        rte_background_params bp;
        rte_background_params_default(&bp, src->width);
        if (p->background_cell)
            bp.cell = p->background_cell;
        rte_background_threshold_params tp;
        rte_background_threshold_params_default(&tp, src->width);
        tp.min_contrast = p->contrast;
        tp.bright = p->polarity != RTE_GRASP_DARK;
        tp.dark = p->polarity != RTE_GRASP_BRIGHT;
        rte_status st = rte_background_estimate_u8(src, &table, &bp, &ctx->arena);
        rte_background_threshold_result tr = {0};
        if (st == RTE_OK)
            st = rte_background_threshold_u8(src, &table, bin, &tp, &ctx->arena, &tr);
        out->threshold = tr.high;
        out->polarity = p->polarity;
        return st;
    }
    int32_t t = p->threshold;
    if (p->binarize == RTE_GRASP_OTSU) {
        rte_status st = rte_threshold_otsu_u8(src, &t);
        if (st != RTE_OK)
            return st;
    }
    rte_grasp_polarity pol = p->polarity;
    if (pol == RTE_GRASP_AUTO)
        pol = border_mean(src) > t ? RTE_GRASP_DARK : RTE_GRASP_BRIGHT;
    const rte_threshold_params tp = {
        .type = pol == RTE_GRASP_DARK ? RTE_THRESH_BINARY_INV : RTE_THRESH_BINARY,
        .thresh = t,
        .maxval = 255,
        .otsu = false,
    };
    out->threshold = t;
    out->polarity = pol;
    return rte_threshold_u8(src, bin, &tp, NULL);
}

/* The workspace's mask for a w x h frame, built when the parameters or the
 * size changed, then applied: nothing outside the workspace is an object. */
static rte_status keep_workspace(rte_grasp_ctx *ctx, rte_image_u8 *bin)
{
    const rte_grasp_params *p = &ctx->params;
    rte_image_u8 mask = sub(&ctx->workspace, bin->width, bin->height);
    if (ctx->workspace_w != bin->width || ctx->workspace_h != bin->height) {
        rte_vertex px[RTE_GRASP_MAX_ROI_VERTICES];
        rte_status st =
            rte_polygon_from_fractions(p->roi, p->roi_count, bin->width, bin->height, px);
        rte_polygon poly = {px, p->roi_count};
        size_t mark = rte_arena_mark(&ctx->arena);
        if (st == RTE_OK)
            st = rte_polygon_mask_build(&mask, &poly, 1, &ctx->arena);
        rte_arena_reset(&ctx->arena, mark);
        if (st != RTE_OK)
            return st;
        ctx->workspace_w = bin->width;
        ctx->workspace_h = bin->height;
    }
    return rte_polygon_mask_apply(bin, &mask, bin);
}

/* Whether an object reaches the edge of the frame or, with a workspace, a
 * pixel outside it (a 4-neighbour of a contour point off the mask): it may
 * go on beyond what is seen. */
static bool touches_border(const rte_grasp_ctx *ctx, const rte_point *pts, int32_t n, int32_t w,
                           int32_t h)
{
    const rte_rect r = rte_shape_bounding_rect(pts, n);
    if (r.x == 0 || r.y == 0 || r.x + r.width == w || r.y + r.height == h)
        return true;
    if (!ctx->params.roi_count)
        return false;
    const rte_image_u8 mask = sub(&ctx->workspace, w, h);
    for (int32_t i = 0; i < n; i++) {
        const uint8_t *row = rte_u8_row(&mask, pts[i].y);
        if (!row[pts[i].x - 1] || !row[pts[i].x + 1] ||
            !rte_u8_row(&mask, pts[i].y - 1)[pts[i].x] ||
            !rte_u8_row(&mask, pts[i].y + 1)[pts[i].x])
            return true;
    }
    return false;
}

/* Keeps the `cap` largest candidates in best[] (largest first; equal areas
 * in contour order). Returns the new count; *dropped counts the rest. */
static int32_t keep_largest(grasp_candidate *best, int32_t n, int32_t cap, grasp_candidate c,
                            int32_t *dropped)
{
    if (n == cap && best[n - 1].area2 >= c.area2) {
        (*dropped)++;
        return n;
    }
    if (n == cap) {
        (*dropped)++;
        n--;
    }
    int32_t i = n;
    while (i > 0 && best[i - 1].area2 < c.area2) {
        best[i] = best[i - 1];
        i--;
    }
    best[i] = c;
    return n + 1;
}

static void grasp_of(rte_grasp_object *o)
{
    const rte_shape_info *s = &o->info;
    if (s->area2 > 0) {
        o->x_q8 = (int32_t)((s->cx_q16 + 128) >> 8);
        o->y_q8 = (int32_t)((s->cy_q16 + 128) >> 8);
    } else { /* a line or a dot: no area to take moments of */
        o->x_q8 = s->box.cx_q8;
        o->y_q8 = s->box.cy_q8;
    }
    /* the box angle is its long side: close across it */
    int32_t a = s->box.angle_q16 + DEG90_Q16;
    if (a > DEG90_Q16)
        a -= 2 * DEG90_Q16;
    o->angle_q16 = a;
    o->width_q8 = s->box.width_q8;
}

rte_status rte_grasp_process(rte_grasp_ctx *ctx, const rte_image_u8 *gray, rte_grasp_result *out)
{
    if (!ctx || !out)
        return RTE_ERR_ARGUMENT;
    *out = (rte_grasp_result){.objects = ctx->objects, .contours = &ctx->contours, .threshold = -1};
    rte_status st = rte_image_u8_check(gray);
    if (st != RTE_OK)
        return st;
    const int32_t w = gray->width, h = gray->height;
    if (w > ctx->config.max_width || h > ctx->config.max_height)
        return RTE_ERR_SIZE;
    const rte_grasp_params *p = &ctx->params;
    const int64_t t0 = rte_clock_now_ns();

    const rte_image_u8 *src = gray;
    rte_image_u8 blurred = sub(&ctx->blurred, w, h);
    if (ctx->config.blur_ksize > 1) {
        st = rte_gaussian_blur_u8(gray, &blurred, &ctx->blur, &ctx->arena);
        src = &blurred;
    }
    const int64_t t1 = rte_clock_now_ns();

    rte_image_u8 bin = sub(&ctx->binary, w, h);
    ctx->binary.width = w; /* what out->binary shows */
    ctx->binary.height = h;
    ctx->binary.stride = w;
    out->binary = &ctx->binary;
    if (st == RTE_OK)
        st = binarize(ctx, src, &bin, out);
    if (st == RTE_OK && p->roi_count)
        st = keep_workspace(ctx, &bin);
    const int64_t t2 = rte_clock_now_ns();

    if (st == RTE_OK)
        st = rte_contours_find(&bin, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_SIMPLE,
                               &ctx->contours, &ctx->arena);
    const int64_t t3 = rte_clock_now_ns();
    if (st != RTE_OK) {
        ctx->contours.n_contours = 0;
        return st;
    }

    /* filters, then the largest max_objects by area */
    const rte_contours *cs = &ctx->contours;
    const int64_t min2 = 2 * (int64_t)p->min_area, max2 = 2 * (int64_t)p->max_area;
    int32_t n_best = 0, dropped = 0;
    for (int32_t i = 0; i < cs->n_contours; i++) {
        const rte_contour *c = &cs->contours[i];
        const rte_point *pts = cs->points + c->offset;
        int64_t a2 = rte_shape_area2(pts, c->count);
        a2 = a2 < 0 ? -a2 : a2;
        if (a2 < min2 || (max2 > 0 && a2 > max2))
            continue;
        if (p->skip_border && touches_border(ctx, pts, c->count, w, h))
            continue;
        n_best =
            keep_largest(ctx->best, n_best, p->max_objects, (grasp_candidate){a2, i}, &dropped);
    }

    int32_t n = 0;
    for (int32_t k = 0; k < n_best && st == RTE_OK; k++) {
        const rte_contour *c = &cs->contours[ctx->best[k].contour];
        rte_grasp_object *o = &ctx->objects[n];
        st = rte_shape_classify(cs->points + c->offset, c->count, &o->info, &ctx->arena);
        if (st != RTE_OK)
            break;
        o->contour = ctx->best[k].contour;
        /* with skip_border the filter above has already ruled it out */
        o->touches_border =
            !p->skip_border && touches_border(ctx, cs->points + c->offset, c->count, w, h);
        grasp_of(o);
        n++;
    }
    const int64_t t4 = rte_clock_now_ns();
    out->n_objects = n;
    out->dropped_objects = dropped;
    out->dropped_contours = cs->dropped_contours;
    out->truncated = dropped > 0 || cs->truncated;
    out->timing = (rte_grasp_timing){t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0};
    return st;
}
