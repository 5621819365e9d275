/* The grasp context: configuration-time half (defaults, sizes, the one
 * allocation, the Gaussian and ellipse tables). May use floating point. */
#include <stdlib.h>
#include <string.h>

#include "grasp_ctx.h"
#include "rtedge/background.h"
#include "rtedge/canny.h"
#include "rtedge/split.h"
#include "rtedge/contours.h"
#include "rtedge/shape.h"

void rte_grasp_config_default(rte_grasp_config *config)
{
    if (!config)
        return;
    *config = (rte_grasp_config){
        .max_width = 1280,
        .max_height = 720,
        .max_contours = 4096,
        .max_points = 1 << 18,
        .max_objects = 64,
        .blur_ksize = 5,
        .close_ksize = 5,
        .close_iterations = 2,
        .params =
            {
                .binarize = RTE_GRASP_BACKGROUND,
                .threshold = 127,
                .polarity = RTE_GRASP_AUTO,
                .canny_low = 50,
                .canny_high = 150,
                .contrast = 20,
                .background_cell = 0,
                .chroma = 1,
                .edge_support_permille = 750,
                .min_area = 100,
                .max_area = 0,
                .skip_border = 1,
                .split = 1,
                .max_objects = 64,
                .gripper_min_px = 4,
                .gripper_max_px = 160,
                .margin_px = 8,
                .finger_px = 8,
            },
    };
}

static int config_ok(const rte_grasp_config *c)
{
    return c && c->max_width >= 1 && c->max_width <= RTE_SHAPE_MAX_COORD + 1 &&
           c->max_height >= 1 && c->max_height <= RTE_SHAPE_MAX_COORD + 1 && c->max_contours >= 1 &&
           c->max_contours <= RTE_GRASP_MAX_CONTOURS && c->max_points >= 1 &&
           c->max_points <= RTE_GRASP_MAX_POINTS && c->max_objects >= 1 && c->max_objects <= 4096 &&
           c->blur_ksize >= 1 && c->blur_ksize <= RTE_GAUSSIAN_MAX_KSIZE && (c->blur_ksize & 1) &&
           c->close_ksize >= 1 && c->close_ksize <= RTE_MORPH_MAX_KSIZE && (c->close_ksize & 1) &&
           c->close_iterations >= 1 && c->close_iterations <= 8 &&
           rte_grasp_check_params(c, &c->params) == RTE_OK;
}

static size_t max_size(size_t a, size_t b) { return a > b ? a : b; }

/* The element that opens the half-size shade mask (grasp.c, read_colour). */
static rte_morph_element shade_square(void)
{
    rte_morph_element e;
    rte_morphology_element_init(&e, RTE_MORPH_RECT, 3, 3); /* a valid size: cannot fail */
    return e;
}

/* The arena: the largest need of any one stage (each resets it). */
static size_t arena_size(const rte_grasp_config *c, const rte_gaussian_kernel *k,
                         const rte_morph_element *e)
{
    const int32_t w = c->max_width, h = c->max_height;
    size_t s = rte_gaussian_blur_u8_scratch_size(w, h, k);
    s = max_size(s, rte_canny_scratch_size(w, h, 3));
    s = max_size(s, rte_morphology_scratch_size(w, h, e, c->close_iterations));
    const rte_morph_element square = shade_square();
    s = max_size(s, rte_morphology_scratch_size((w + 1) / 2, (h + 1) / 2, &square, 1));
    s = max_size(s, rte_contours_scratch_size(w, h, c->max_contours));
    s = max_size(s, rte_polygon_mask_scratch_size(RTE_GRASP_MAX_ROI_VERTICES));
    s = max_size(s, rte_background_scratch_size(w, h, RTE_BACKGROUND_MIN_CELL));
    s = max_size(s, rte_background_threshold_scratch_size(w, h));
    /* the split of one contour: the vertices, the crop's two masks, then
     * the polygon fill's, the split's or the cut's scratch; the gate's hull before */
    const size_t pts = (size_t)c->max_points, image = (size_t)w * (size_t)h;
    s = max_size(
        s, rte_arena_piece_size(pts * sizeof(rte_vertex)) + 2 * rte_arena_piece_size(image) +
               rte_arena_piece_size(rte_grasp_split_runs_bytes(w, h)) +
               max_size(rte_polygon_mask_scratch_size(c->max_points),
                        max_size(rte_split_scratch_size(w, h), rte_grasp_refine_cut_bytes(w, h))));
    s = max_size(s, rte_arena_piece_size(pts * sizeof(int32_t)) +
                        rte_arena_piece_size((pts + 1) * sizeof(rte_point)) +
                        rte_arena_piece_size((pts + 1) * sizeof(rte_caliper)) +
                        rte_shape_hull_scratch_size(c->max_points));
    s = max_size(s, rte_shape_classify_scratch_size(c->max_points));
    /* the grasp of one contour: its hull, calipers and the hull's scratch */
    const size_t n = (size_t)c->max_points + 1;
    return max_size(s, rte_arena_piece_size(n * sizeof(rte_point)) +
                           rte_arena_piece_size(n * sizeof(rte_caliper)) +
                           rte_shape_hull_scratch_size(c->max_points));
}

/* The pieces of the block, in order; with base NULL only counts bytes. */
static size_t layout(rte_grasp_ctx *ctx, uint8_t *base, const rte_grasp_config *c,
                     size_t arena_bytes)
{
    const size_t image = (size_t)c->max_width * (size_t)c->max_height;
    const size_t half = (size_t)((c->max_width + 1) / 2) * (size_t)((c->max_height + 1) / 2);
    const size_t sizes[] = {
        image,
        image,
        image,
        image,
        image * sizeof(uint16_t),
        image,
        half,
        half,
        (size_t)c->max_points * sizeof(rte_point),
        (size_t)c->max_contours * sizeof(rte_contour),
        (size_t)c->max_objects * sizeof(grasp_candidate),
        (size_t)c->max_objects * sizeof(rte_grasp_object),
        arena_bytes,
    };
    size_t off = 0;
    uint8_t *at[sizeof sizes / sizeof sizes[0]];
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        at[i] = base ? base + off : NULL;
        off += rte_arena_piece_size(sizes[i]);
    }
    if (ctx) {
        ctx->blurred = (rte_image_u8){c->max_width, c->max_height, c->max_width, at[0]};
        ctx->edges = (rte_image_u8){c->max_width, c->max_height, c->max_width, at[1]};
        ctx->binary = (rte_image_u8){c->max_width, c->max_height, c->max_width, at[2]};
        ctx->workspace = (rte_image_u8){c->max_width, c->max_height, c->max_width, at[3]};
        ctx->distance = (uint16_t *)(void *)at[4];
        ctx->tinted = (rte_image_u8){c->max_width, c->max_height, c->max_width, at[5]};
        const int32_t hw = (c->max_width + 1) / 2, hh = (c->max_height + 1) / 2;
        ctx->cb_table = (rte_image_u8){hw, hh, hw, at[6]};
        ctx->cr_table = (rte_image_u8){hw, hh, hw, at[7]};
        ctx->contours.points = (rte_point *)(void *)at[8];
        ctx->contours.contours = (rte_contour *)(void *)at[9];
        ctx->contours.max_points = c->max_points;
        ctx->contours.max_contours = c->max_contours;
        ctx->best = (grasp_candidate *)(void *)at[10];
        ctx->objects = (rte_grasp_object *)(void *)at[11];
        rte_arena_init(&ctx->arena, at[12], arena_bytes);
    }
    return off + RTE_ARENA_ALIGN; /* room to align the block's start */
}

static rte_status tables(const rte_grasp_config *c, rte_gaussian_kernel *k, rte_morph_element *e)
{
    rte_status st = rte_gaussian_kernel_init(k, c->blur_ksize, c->blur_ksize, 0.0, 0.0);
    if (st == RTE_OK)
        st = rte_morphology_element_init(e, RTE_MORPH_ELLIPSE, c->close_ksize, c->close_ksize);
    return st;
}

/* The block: the context, then its buffers, each 64-byte aligned. */
static size_t block_size(const rte_grasp_config *c, size_t arena_bytes)
{
    return rte_arena_piece_size(sizeof(rte_grasp_ctx)) + layout(NULL, NULL, c, arena_bytes);
}

size_t rte_grasp_memory_size(const rte_grasp_config *config)
{
    rte_gaussian_kernel k;
    rte_morph_element e;
    if (!config_ok(config) || tables(config, &k, &e) != RTE_OK)
        return 0;
    return block_size(config, arena_size(config, &k, &e));
}

rte_status rte_grasp_init(const rte_grasp_config *config, void *memory, size_t bytes,
                          rte_grasp_ctx **out)
{
    if (!out)
        return RTE_ERR_ARGUMENT;
    *out = NULL;
    rte_gaussian_kernel k;
    rte_morph_element e;
    if (!memory || !config_ok(config) || tables(config, &k, &e) != RTE_OK)
        return RTE_ERR_ARGUMENT;
    const size_t arena_bytes = arena_size(config, &k, &e);
    if (bytes < block_size(config, arena_bytes))
        return RTE_ERR_NO_MEMORY;
    const uintptr_t base =
        ((uintptr_t)memory + RTE_ARENA_ALIGN - 1) & ~(uintptr_t)(RTE_ARENA_ALIGN - 1);
    rte_grasp_ctx *ctx = (rte_grasp_ctx *)base;
    memset(ctx, 0, sizeof *ctx);
    ctx->blur = k;
    ctx->close = e;
    ctx->shade_open = shade_square();
    layout(ctx, (uint8_t *)base + rte_arena_piece_size(sizeof *ctx), config, arena_bytes);
    ctx->config = *config;
    ctx->params = config->params;
    *out = ctx;
    return RTE_OK;
}

rte_status rte_grasp_create(const rte_grasp_config *config, rte_grasp_ctx **out)
{
    if (!out)
        return RTE_ERR_ARGUMENT;
    *out = NULL;
    const size_t bytes = rte_grasp_memory_size(config);
    if (bytes == 0)
        return RTE_ERR_ARGUMENT;
    void *memory = malloc(bytes);
    if (!memory)
        return RTE_ERR_NO_MEMORY;
    rte_status st = rte_grasp_init(config, memory, bytes, out);
    if (st != RTE_OK) {
        free(memory);
        return st;
    }
    (*out)->memory = memory;
    return RTE_OK;
}

void rte_grasp_destroy(rte_grasp_ctx *ctx)
{
    if (ctx)
        free(ctx->memory); /* the context lives in that block; NULL after rte_grasp_init */
}
