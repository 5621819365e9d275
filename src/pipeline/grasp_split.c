/* The grasp path's split of touching objects (see rtedge/grasp.h, .split),
 * per frame, integer only: which contours may hold touching objects, the
 * split of each on its own pixels, and whether its parts are objects. */
#include <stdint.h>
#include <string.h>

#include "algo/geom_fixed.h"
#include "core/int_math.h"
#include "grasp_ctx.h"
#include "rtedge/distance.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/split.h"

/* Solidity (area / hull area, per mille) under which a contour may be
 * touching objects and the split is tried on it: two touching discs have
 * 880, a single disc or box on a noisy binary image 970 or more. A gate
 * for speed, not a decision: the split cuts only at necks. */
#define SPLIT_SOLIDITY_PERMILLE 950

/* Whether contour pts may hold touching objects the gripper could take
 * apart: its solidity is below SPLIT_SOLIDITY_PERMILLE, its narrowest
 * width (the hull's calipers) at most twice the gripper's widest opening
 * (two objects side by side; a road, a sky or a wall is wider) and its
 * bounding box at most a quarter of the frame. */
static rte_status needs_split(rte_grasp_ctx *ctx, const rte_point *pts, int32_t n, int64_t area2,
                              int32_t w, int32_t h, bool *split)
{
    *split = false;
    const rte_rect box = rte_shape_bounding_rect(pts, n);
    if (n < 4 || (int64_t)box.width * box.height * 4 > (int64_t)w * h)
        return RTE_OK;
    const size_t mark = rte_arena_mark(&ctx->arena);
    int32_t *idx = rte_arena_alloc(&ctx->arena, (size_t)n * sizeof *idx);
    rte_point *hull = rte_arena_alloc(&ctx->arena, ((size_t)n + 1) * sizeof *hull);
    rte_caliper *cal = rte_arena_alloc(&ctx->arena, ((size_t)n + 1) * sizeof *cal);
    int32_t nh = 0, nc = 0;
    rte_status st = idx && hull && cal ? rte_shape_convex_hull(pts, n, idx, hull, &nh, &ctx->arena)
                                       : RTE_ERR_NO_MEMORY;
    int64_t hull2 = 0;
    if (st == RTE_OK) {
        hull2 = rte_abs64(rte_shape_area2(hull, nh));
    }
    if (st == RTE_OK && area2 * 1000 < hull2 * SPLIT_SOLIDITY_PERMILLE)
        st = rte_shape_caliper_widths(hull, nh, cal, &nc);
    if (st == RTE_OK && nc > 0) {
        int32_t narrowest = cal[0].width_q8;
        for (int32_t i = 1; i < nc; i++)
            narrowest = cal[i].width_q8 < narrowest ? cal[i].width_q8 : narrowest;
        *split = narrowest <= 2 * 256 * ctx->params.gripper_max_px;
    }
    rte_arena_reset(&ctx->arena, mark);
    return st;
}

/* The split's parts must be alike in size: the smallest of those of at
 * least min_area px at least this share (per mille) of the largest. Two to
 * four touching sweets or boxes are; a pen's metal tip or a lighter's head,
 * cut off at a narrowing, is not (and stays on its object). */
#define SPLIT_PART_SHARE_PERMILLE 200

static int32_t run_root(int32_t *parent, int32_t a)
{
    while (parent[a] != a)
        a = parent[a] = parent[parent[a]];
    return a;
}

/* The areas of the 8-connected parts of a w x h binary crop (nonzero), by
 * runs united across rows: areas[] gets at most max (the rest are added to
 * the last). Returns the parts. runs[] holds 4 (w + 1) h / 2 + 4 ints: x0,
 * x1, parent and area of each run, at most (w + 1) / 2 a row. */
static int32_t part_areas(const uint8_t *px, int32_t w, int32_t h, int32_t *areas, int32_t max,
                          int32_t *runs)
{
    const int32_t cap = (w + 1) / 2 * h + 1;
    int32_t *x0 = runs, *x1 = runs + cap, *parent = runs + 2 * cap, *area = runs + 3 * cap;
    int32_t n = 0, prev = 0, prev_end = 0;
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *row = px + (size_t)y * w;
        const int32_t first = n;
        for (int32_t x = 0; x < w;) {
            if (!row[x]) {
                x++;
                continue;
            }
            x0[n] = x;
            while (x < w && row[x])
                x++;
            x1[n] = x - 1;
            parent[n] = n;
            area[n] = x - x0[n];
            /* 8-connected to the runs of the row above that overlap or touch
             * at a corner */
            while (prev < prev_end && x1[prev] < x0[n] - 1)
                prev++;
            for (int32_t q = prev; q < prev_end && x0[q] <= x1[n] + 1; q++) {
                const int32_t ra = run_root(parent, q), rb = run_root(parent, n);
                if (ra != rb)
                    parent[ra > rb ? ra : rb] = ra < rb ? ra : rb;
            }
            n++;
        }
        prev = first;
        prev_end = n;
    }
    int32_t parts = 0;
    for (int32_t r = 0; r < n; r++) {
        const int32_t root = run_root(parent, r);
        if (root != r) {
            area[root] += area[r];
            continue;
        }
        parent[r] = r;
    }
    for (int32_t r = 0; r < n; r++)
        if (parent[r] == r) {
            if (parts < max)
                areas[parts++] = area[r];
            else
                areas[max - 1] += area[r];
        }
    return parts;
}

/* Whether the split parts of a crop are objects of their own: two or more
 * of at least min_area px, alike in size (SPLIT_PART_SHARE_PERMILLE). */
static bool parts_alike(const uint8_t *px, int32_t w, int32_t h, int64_t min_area, int32_t *runs,
                        int32_t *objects)
{
    int32_t areas[RTE_GRASP_MAX_SPLIT_PARTS];
    const int32_t n = part_areas(px, w, h, areas, RTE_GRASP_MAX_SPLIT_PARTS, runs);
    int64_t lo = INT64_MAX, hi = 0;
    *objects = 0;
    for (int32_t i = 0; i < n; i++)
        if (areas[i] >= min_area) {
            (*objects)++;
            lo = areas[i] < lo ? areas[i] : lo;
            hi = areas[i] > hi ? areas[i] : hi;
        }
    return *objects >= 2 && lo * 1000 >= hi * SPLIT_PART_SHARE_PERMILLE;
}

/* The highest distance in dist. A cut needs two basins each rising
 * min_dynamic above the level where they meet, at least one pixel (3 in
 * CHAMFER34's thirds): a thin shape (a lane marking, a crack, a drawn
 * line) has none, and the split's flood is not run on it. */
static int32_t highest_distance(const rte_image_u16 *dist)
{
    uint16_t most = 0;
    for (int32_t y = 0; y < dist->height; y++) {
        const uint16_t *row = dist->buf + (size_t)y * dist->stride;
        for (int32_t x = 0; x < dist->width; x++)
            most = row[x] > most ? row[x] : most;
    }
    return most;
}

/* Splits touching objects within one contour (rtedge/split.h): on the
 * contour's bounding box (and a pixel around it), the pixels of bin inside
 * the contour (filled as cv::fillPoly fills it, so that other objects
 * reaching into the box are left alone), their chamfer distance, the split;
 * the cut pixels are cleared in bin. Adds the parts beyond the first to
 * *parts. */
static rte_status split_contour(rte_grasp_ctx *ctx, const rte_image_u8 *grey, rte_image_u8 *bin,
                                const rte_point *pts, int32_t n, int32_t *parts)
{
    const rte_rect r = rte_shape_bounding_rect(pts, n);
    const int32_t x0 = r.x > 0 ? r.x - 1 : 0, y0 = r.y > 0 ? r.y - 1 : 0;
    const int32_t x1 = r.x + r.width < bin->width ? r.x + r.width + 1 : bin->width;
    const int32_t y1 = r.y + r.height < bin->height ? r.y + r.height + 1 : bin->height;
    const int32_t cw = x1 - x0, ch = y1 - y0;
    const size_t mark = rte_arena_mark(&ctx->arena);
    rte_vertex *v = rte_arena_alloc(&ctx->arena, (size_t)n * sizeof *v);
    uint8_t *inside = rte_arena_alloc(&ctx->arena, (size_t)cw * ch);
    uint8_t *own = rte_arena_alloc(&ctx->arena, (size_t)cw * ch);
    int32_t *runs = rte_arena_alloc(&ctx->arena, rte_grasp_split_runs_bytes(cw, ch));
    if (!v || !inside || !own || !runs) {
        rte_arena_reset(&ctx->arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    for (int32_t i = 0; i < n; i++)
        v[i] = (rte_vertex){pts[i].x - x0, pts[i].y - y0};
    rte_image_u8 mask = {cw, ch, cw, inside}, part = {cw, ch, cw, own};
    const rte_polygon poly = {v, n};
    rte_status st = rte_polygon_mask_build(&mask, &poly, 1, &ctx->arena);
    rte_image_u8 box = {cw, ch, bin->stride, rte_u8_row(bin, y0) + x0};
    if (st == RTE_OK)
        st = rte_polygon_mask_apply(&box, &mask, &part);
    rte_image_u16 dist = {cw, ch, cw, ctx->distance};
    if (st == RTE_OK)
        st = rte_distance_transform_u8(&part, &dist, RTE_DIST_CHAMFER34, RTE_DIST_BORDER_ZERO);
    rte_split_params sp;
    rte_split_params_default(&sp, RTE_DIST_CHAMFER34);
    /* necks narrower than 75% of the smaller part's inscribed radius: the
     * background binarisation keeps the shadow between two sweets, which
     * widens their neck (250 lies in the range that splits the smarties and
     * cuts none of the synthetic single shapes, docs/distance.md) */
    sp.min_ratio_permille = 250;
    rte_split_result sr = {0};
    if (st == RTE_OK && highest_distance(&dist) >= sp.min_dynamic + 3)
        st = rte_split_u8(&part, &dist, &part, &sp, &ctx->arena, &sr);
    /* the parts are told by the distance, their cut then placed by the
     * grey (the parts may change size: told again) */
    const rte_image_u8 grey_box = {cw, ch, grey->stride, (uint8_t *)rte_u8_row(grey, y0) + x0};
    int32_t objects = 0;
    bool keep = st == RTE_OK && sr.cut_pixels > 0 &&
                parts_alike(own, cw, ch, ctx->params.min_area, runs, &objects);
    if (keep) {
        st = rte_grasp_refine_cut(ctx, &grey_box, &box, inside, own, ctx->distance, cw, ch);
        keep = st == RTE_OK && parts_alike(own, cw, ch, ctx->params.min_area, runs, &objects);
    }
    if (keep) {
        /* inside the contour, bin becomes the split part */
        for (int32_t y = 0; y < ch; y++) {
            uint8_t *b = rte_u8_row(&box, y);
            const uint8_t *in = inside + (size_t)y * cw, *o = own + (size_t)y * cw;
            for (int32_t x = 0; x < cw; x++)
                b[x] = in[x] ? o[x] : b[x];
        }
        *parts += objects - 1;
    }
    rte_arena_reset(&ctx->arena, mark);
    return st;
}

rte_status rte_grasp_split_touching(rte_grasp_ctx *ctx, const rte_image_u8 *grey, rte_image_u8 *bin,
                                    int32_t *parts)
{
    const rte_contours *cs = &ctx->contours;
    const int64_t min2 = 2 * (int64_t)ctx->params.min_area;
    const int32_t before = *parts;
    rte_status st = RTE_OK;
    for (int32_t i = 0; i < cs->n_contours && st == RTE_OK; i++) {
        const rte_contour *c = &cs->contours[i];
        const rte_point *pts = cs->points + c->offset;
        const int64_t a2 = rte_abs64(rte_shape_area2(pts, c->count));
        bool split = false;
        if (a2 >= 2 * min2 && a2 > 0)
            st = needs_split(ctx, pts, c->count, a2, bin->width, bin->height, &split);
        if (st == RTE_OK && split)
            st = split_contour(ctx, grey, bin, pts, c->count, parts);
    }
    if (st == RTE_OK && *parts > before)
        st = rte_contours_find(bin, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_SIMPLE,
                               &ctx->contours, &ctx->arena);
    return st;
}
