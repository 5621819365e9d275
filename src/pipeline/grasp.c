/* The grasp path, per frame (see rtedge/grasp.h). Integer only. */
#include <string.h>
#include <time.h>

#include "algo/geom_fixed.h"
#include "grasp_ctx.h"
#include "rtedge/background.h"
#include "rtedge/canny.h"
#include "rtedge/threshold.h"
#include "core/clock.h"
#include "core/int_math.h"

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
        (p->split == 0 || p->split == 1) && (p->chroma == 0 || p->chroma == 1) &&
        p->edge_support_permille >= 0 && p->edge_support_permille <= 1000 && p->max_objects >= 1 &&
        p->max_objects <= c->max_objects &&
        (p->roi_count == 0 || (p->roi_count >= 3 && p->roi_count <= RTE_GRASP_MAX_ROI_VERTICES)) &&
        p->gripper_min_px >= 0 && p->gripper_min_px <= p->gripper_max_px &&
        p->gripper_max_px <= RTE_GRASP_MAX_OPENING_PX && p->margin_px >= 0 &&
        p->margin_px <= RTE_GRASP_MAX_CLEARANCE_PX && p->finger_px >= 0 &&
        p->finger_px <= RTE_GRASP_MAX_CLEARANCE_PX;
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

/* Colour as contrast (params.chroma): the table's cb and cr estimated as
 * its grey is, then the colour differences from them put in place of the
 * grey ones where larger (rte_background_tint_u8), so that the threshold
 * sees the colour an object differs by; and the pixels a shadow may have
 * dimmed (rte_background_shade_u8, at half size) into shade, opened by a
 * 3 x 3 square there (a cast shadow is several pixels across; the rim of
 * a dark object's blurred edge, dimmed as a shadow is, and a thin light
 * part such as a pencil's sharpened tip are not). */
static rte_status read_colour(rte_grasp_ctx *ctx, const rte_image_u8 *src,
                              const rte_image_u8 *table, const rte_background_params *bp,
                              const rte_image_u8 *cb, const rte_image_u8 *cr, bool bright,
                              bool dark, rte_image_u8 *dst, rte_image_u8 *shade)
{
    const int32_t hw = cb->width, hh = cb->height;
    rte_image_u8 cbt = sub(&ctx->cb_table, hw, hh), crt = sub(&ctx->cr_table, hw, hh);
    /* the grey's parameters (cell side) on the half-size planes: cells twice
     * as wide in the frame and a fourth as many (the table's colour changes
     * slowly) */
    rte_status st = rte_background_estimate_u8(cb, &cbt, bp, &ctx->arena);
    if (st == RTE_OK)
        st = rte_background_estimate_u8(cr, &crt, bp, &ctx->arena);
    if (st != RTE_OK)
        return st;
    /* colour differences below half the contrast are the sensor's noise */
    const rte_background_tint_params tp = {
        .least = (ctx->params.contrast + 1) / 2, .bright = bright, .dark = dark};
    st = rte_background_tint_u8(src, table, cb, &cbt, cr, &crt, dst, &tp);
    /* a shadow keeps 40-90% of the table's light (darker is an object's
     * own shade, lighter the table's texture) and its colour within the
     * tint's noise floor and half again: half-size chroma (and JPEG's blur
     * of it) put the object's colour on the shadow's first pixels */
    const rte_background_shade_params sp = {
        .darkest_permille = 400, .lightest_permille = 900, .chroma = tp.least * 3 / 2};
    if (st == RTE_OK)
        st = rte_background_shade_u8(src, table, cb, &cbt, cr, &crt, shade, &sp);
    if (st == RTE_OK)
        st = rte_morphology_u8(shade, shade, RTE_MORPH_OPEN, &ctx->shade_open, 1, &ctx->arena);
    return st;
}

static rte_status binarize(rte_grasp_ctx *ctx, const rte_image_u8 *src, const rte_image_u8 *cb,
                           const rte_image_u8 *cr, rte_image_u8 *bin, rte_grasp_result *out)
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
        rte_image_u8 tinted = sub(&ctx->tinted, src->width, src->height);
        /* the half-size shade mask in the split's distance buffer, free
         * until then */
        const int32_t hw = (src->width + 1) / 2, hh = (src->height + 1) / 2;
        rte_image_u8 shade = {hw, hh, hw, (uint8_t *)ctx->distance};
        const rte_image_u8 *shade_in = NULL;
        if (st == RTE_OK && cb && p->chroma) {
            st = read_colour(ctx, src, &table, &bp, cb, cr, tp.bright, tp.dark, &tinted, &shade);
            src = &tinted;
            shade_in = &shade;
        }
        rte_background_threshold_result tr = {0};
        if (st == RTE_OK)
            st = rte_background_threshold_shaded_u8(src, &table, shade_in, bin, &tp, &ctx->arena,
                                                    &tr);
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

/* What the edge test reads (background mode): the image that was
 * thresholded (the grey with colour as contrast, or the grey), the table's
 * estimate, the threshold. */
static grasp_outline_images outline_images(rte_grasp_ctx *ctx, const rte_image_u8 *bin,
                                           const rte_image_u8 *grey, bool colour, int32_t threshold)
{
    const int32_t w = bin->width, h = bin->height;
    return (grasp_outline_images){
        .bin = *bin,
        .img = colour && ctx->params.chroma ? sub(&ctx->tinted, w, h) : *grey,
        .table = sub(&ctx->edges, w, h),
        .threshold = threshold,
    };
}

/* Whether contour pts is an object: its area within min_area..max_area
 * (*area2: twice it), clear of the border (skip_border) and, where objects
 * are told from the table (background mode), its outline on an edge in
 * the thresholded image: a step of a fifth of the least contrast (a just
 * visible object's step, blurred, is about a third of it) over a pixel
 * for each 640 of the frame's width (its edges spread with its size). */
static bool is_object(const rte_grasp_ctx *ctx, const rte_image_u8 *bin,
                      const grasp_outline_images *edges, const rte_point *pts, int32_t n,
                      int64_t *area2)
{
    const rte_grasp_params *p = &ctx->params;
    *area2 = rte_abs64(rte_shape_area2(pts, n));
    if (*area2 < 2 * (int64_t)p->min_area || (p->max_area > 0 && *area2 > 2 * (int64_t)p->max_area))
        return false;
    if (p->skip_border && touches_border(ctx, pts, n, bin->width, bin->height))
        return false;
    const int32_t step = p->contrast / 5 > 1 ? p->contrast / 5 : 1;
    const int32_t reach = (bin->width + 320) / 640 > 1 ? (bin->width + 320) / 640 : 1;
    return p->binarize != RTE_GRASP_BACKGROUND || p->edge_support_permille == 0 ||
           rte_grasp_outline_on_edges(edges, pts, n, step, reach) >= p->edge_support_permille;
}

/* Whether candidate a goes before b: a better score, or an equal score
 * and a larger area (equal both: contour order, the earlier first). */
static bool before(const grasp_candidate *a, const grasp_candidate *b)
{
    return a->score_q16 > b->score_q16 || (a->score_q16 == b->score_q16 && a->area2 > b->area2);
}

/* Keeps the `cap` best candidates in best[] (best first). Returns the new
 * count; *dropped counts the rest. */
static int32_t keep_best(grasp_candidate *best, int32_t n, int32_t cap, const grasp_candidate *c,
                         int32_t *dropped)
{
    if (n == cap && !before(c, &best[n - 1])) {
        (*dropped)++;
        return n;
    }
    if (n == cap) {
        (*dropped)++;
        n--;
    }
    int32_t i = n;
    while (i > 0 && before(c, &best[i - 1])) {
        best[i] = best[i - 1];
        i--;
    }
    best[i] = *c;
    return n + 1;
}

/* a * b in Q16, rounded. */
static int32_t mul_q16(int32_t a, int32_t b) { return (int32_t)(((int64_t)a * b + 32768) >> 16); }

/* The point t (Q8 px) along the unit vector u (Q16) from c (Q16), in Q8. */
static int32_t along_q8(int64_t c_q16, int32_t u_q16, int64_t t_q8)
{
    return (int32_t)((c_q16 + (int64_t)u_q16 * t_q8 / 256 + 128) >> 8);
}

/* Free pixels beyond t0 (Q8, the hull's extreme) in the direction `sign`
 * along the line through c along u, up to `need`: the walk stops at the
 * first pixel of the binary image that is set (another object: this one
 * has nothing beyond its hull) or outside the frame or the workspace. */
static int32_t free_run(const rte_grasp_ctx *ctx, const rte_image_u8 *bin, int64_t cx, int64_t cy,
                        int32_t ux, int32_t uy, int64_t t0, int sign, int32_t need)
{
    const rte_image_u8 mask = sub(&ctx->workspace, bin->width, bin->height);
    for (int32_t k = 1; k <= need; k++) {
        const int64_t t = t0 + (int64_t)sign * k * 256;
        const int32_t x = (along_q8(cx, ux, t) + 128) >> 8, y = (along_q8(cy, uy, t) + 128) >> 8;
        if (x < 0 || y < 0 || x >= bin->width || y >= bin->height || rte_u8_row(bin, y)[x] ||
            (ctx->params.roi_count && !rte_u8_row(&mask, y)[x]))
            return k - 1;
    }
    return need;
}

/* The width factor of the score (see rte_grasp_object), Q16. */
static int32_t width_factor(const rte_grasp_params *p, int32_t width_q8)
{
    const int64_t lo = (int64_t)p->gripper_min_px * 256, hi = (int64_t)p->gripper_max_px * 256;
    const int64_t m2 = (int64_t)p->margin_px * 512;
    if (width_q8 < lo || width_q8 > hi)
        return 0;
    if (width_q8 + m2 <= hi)
        return 65536;
    return (int32_t)((hi - width_q8) * 65536 / m2); /* m2 > 0 here */
}

/* The grasp and score of contour pts (twice its area a2) into c: the
 * hull's centroid, then over the hull's calipers within 1/16 + 1 px of the
 * narrowest, the best score (see rte_grasp_object). */
static rte_status grasp_of(rte_grasp_ctx *ctx, const rte_image_u8 *bin, const rte_point *pts,
                           int32_t n, grasp_candidate *c)
{
    const rte_grasp_params *p = &ctx->params;
    const size_t mark = rte_arena_mark(&ctx->arena);
    rte_point *hull = rte_arena_alloc(&ctx->arena, ((size_t)n + 1) * sizeof *hull);
    rte_caliper *cal = rte_arena_alloc(&ctx->arena, ((size_t)n + 1) * sizeof *cal);
    int32_t nh = 0, nc = 0;
    rte_status st = hull && cal ? RTE_OK : RTE_ERR_NO_MEMORY;
    if (st == RTE_OK)
        st = rte_shape_convex_hull(pts, n, NULL, hull, &nh, &ctx->arena);
    if (st == RTE_OK)
        st = rte_shape_caliper_widths(hull, nh, cal, &nc);
    if (st != RTE_OK) {
        rte_arena_reset(&ctx->arena, mark);
        return st;
    }
    const int64_t hull2 = rte_abs64(rte_shape_area2(hull, nh));
    /* the point: the hull's centroid (see rte_grasp_object) */
    int64_t cx, cy;
    rte_moments hm;
    if (c->area2 > 0 && hull2 > 0 && rte_shape_moments(hull, nh, &hm) == RTE_OK) {
        cx = hm.cx_q16;
        cy = hm.cy_q16;
    } else { /* a line or a dot: no area to take moments of */
        const rte_rect r = rte_shape_bounding_rect(pts, n);
        cx = (2 * (int64_t)r.x + r.width - 1) << 15;
        cy = (2 * (int64_t)r.y + r.height - 1) << 15;
    }
    c->x_q8 = (int32_t)((cx + 128) >> 8);
    c->y_q8 = (int32_t)((cy + 128) >> 8);
    const int32_t solidity = hull2 ? (int32_t)((c->area2 * 65536 + hull2 / 2) / hull2) : 0;
    const int32_t need = p->margin_px + p->finger_px;

    int32_t narrowest = cal[0].width_q8;
    for (int32_t i = 1; i < nc; i++)
        narrowest = cal[i].width_q8 < narrowest ? cal[i].width_q8 : narrowest;
    const int64_t near = narrowest + narrowest / 16 + 256;
    int have = 0;
    for (int32_t i = 0; i < nc; i++) {
        const rte_caliper *k = &cal[i];
        if (k->width_q8 > near)
            continue;
        rte_caliper_direction(hull, nh, &cal[i]);
        /* the hull's extremes along u, from the centroid (Q8) */
        int64_t t[2];
        const rte_point v[2] = {hull[k->edge], hull[k->far]};
        for (int j = 0; j < 2; j++) {
            const int64_t d = (((int64_t)v[j].x << 16) - cx) * k->ux_q16 +
                              (((int64_t)v[j].y << 16) - cy) * k->uy_q16;
            t[j] = d >= 0 ? (d + (1 << 23)) >> 24 : -((-d + (1 << 23)) >> 24);
        }
        const int64_t lo = t[0] < t[1] ? t[0] : t[1], hi = t[0] < t[1] ? t[1] : t[0];
        int32_t clear = need;
        if (need) {
            const int32_t a = free_run(ctx, bin, cx, cy, k->ux_q16, k->uy_q16, lo, -1, need);
            const int32_t b = free_run(ctx, bin, cx, cy, k->ux_q16, k->uy_q16, hi, 1, need);
            clear = a < b ? a : b;
        }
        const int32_t fc = need ? (int32_t)((int64_t)clear * 65536 / need) : 65536;
        const int32_t score = mul_q16(mul_q16(solidity, width_factor(p, k->width_q8)), fc);
        if (have && (score < c->score_q16 || (score == c->score_q16 && k->width_q8 >= c->width_q8)))
            continue;
        have = 1;
        c->score_q16 = score;
        c->angle_q16 = k->angle_q16;
        c->width_q8 = k->width_q8;
        c->opening_q8 = k->width_q8 + 2 * 256 * p->margin_px;
        c->clearance_q8 = clear * 256;
        const int64_t m = 256 * (int64_t)p->margin_px;
        c->jaws_q8[0][0] = along_q8(cx, k->ux_q16, lo - m);
        c->jaws_q8[0][1] = along_q8(cy, k->uy_q16, lo - m);
        c->jaws_q8[1][0] = along_q8(cx, k->ux_q16, hi + m);
        c->jaws_q8[1][1] = along_q8(cy, k->uy_q16, hi + m);
    }
    rte_arena_reset(&ctx->arena, mark);
    return RTE_OK;
}

rte_status rte_grasp_process(rte_grasp_ctx *ctx, const rte_image_u8 *gray, rte_grasp_result *out)
{
    return rte_grasp_process_chroma(ctx, gray, NULL, NULL, out);
}

rte_status rte_grasp_process_chroma(rte_grasp_ctx *ctx, const rte_image_u8 *gray,
                                    const rte_image_u8 *cb, const rte_image_u8 *cr,
                                    rte_grasp_result *out)
{
    if (!ctx || !out || !cb != !cr)
        return RTE_ERR_ARGUMENT;
    *out = (rte_grasp_result){.objects = ctx->objects, .contours = &ctx->contours, .threshold = -1};
    rte_status st = rte_image_u8_check(gray);
    if (st == RTE_OK && cb)
        st = rte_image_u8_check_pair(cb, cr);
    if (st != RTE_OK)
        return st;
    const int32_t w = gray->width, h = gray->height;
    if (w > ctx->config.max_width || h > ctx->config.max_height ||
        (cb && (cb->width != (w + 1) / 2 || cb->height != (h + 1) / 2)))
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
        st = binarize(ctx, src, cb, cr, &bin, out);
    if (st == RTE_OK && p->roi_count)
        st = keep_workspace(ctx, &bin);
    const int64_t t2 = rte_clock_now_ns();

    if (st == RTE_OK)
        st = rte_contours_find(&bin, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_SIMPLE,
                               &ctx->contours, &ctx->arena);
    const int64_t t3 = rte_clock_now_ns();
    if (st == RTE_OK && p->split)
        st = rte_grasp_split_touching(ctx, src, &bin, &out->split_parts);
    const int64_t t3s = rte_clock_now_ns();
    if (st != RTE_OK) {
        ctx->contours.n_contours = 0;
        return st;
    }

    /* filters, a grasp and a score each, then the best max_objects */
    const rte_contours *cs = &ctx->contours;
    const grasp_outline_images edges = outline_images(ctx, &bin, src, cb != NULL, out->threshold);
    int32_t n_best = 0, dropped = 0;
    for (int32_t i = 0; i < cs->n_contours && st == RTE_OK; i++) {
        const rte_contour *c = &cs->contours[i];
        const rte_point *pts = cs->points + c->offset;
        int64_t a2 = 0;
        if (!is_object(ctx, &bin, &edges, pts, c->count, &a2))
            continue;
        grasp_candidate g = {.area2 = a2, .contour = i};
        st = grasp_of(ctx, &bin, pts, c->count, &g);
        if (st == RTE_OK)
            n_best = keep_best(ctx->best, n_best, p->max_objects, &g, &dropped);
    }

    int32_t n = 0;
    for (int32_t k = 0; k < n_best && st == RTE_OK; k++) {
        const grasp_candidate *g = &ctx->best[k];
        const rte_contour *c = &cs->contours[g->contour];
        rte_grasp_object *o = &ctx->objects[n];
        st = rte_shape_classify(cs->points + c->offset, c->count, &o->info, &ctx->arena);
        if (st != RTE_OK)
            break;
        o->contour = g->contour;
        /* with skip_border the filter above has already ruled it out */
        o->touches_border =
            !p->skip_border && touches_border(ctx, cs->points + c->offset, c->count, w, h);
        o->x_q8 = g->x_q8;
        o->y_q8 = g->y_q8;
        o->angle_q16 = g->angle_q16;
        o->width_q8 = g->width_q8;
        o->opening_q8 = g->opening_q8;
        memcpy(o->jaws_q8, g->jaws_q8, sizeof o->jaws_q8);
        o->clearance_q8 = g->clearance_q8;
        o->score_q16 = g->score_q16;
        n++;
    }
    const int64_t t4 = rte_clock_now_ns();
    out->n_objects = n;
    out->dropped_objects = dropped;
    out->dropped_contours = cs->dropped_contours;
    out->truncated = dropped > 0 || cs->truncated;
    out->timing = (rte_grasp_timing){t1 - t0, t2 - t1, t3 - t2, t3s - t3, t4 - t3s, t4 - t0};
    return st;
}
