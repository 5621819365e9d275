/* The grasp context, shared by its configuration-time (grasp_config.c) and
 * per-frame (grasp.c) halves. */
#ifndef RTEDGE_PIPELINE_GRASP_CTX_H
#define RTEDGE_PIPELINE_GRASP_CTX_H

#include "rtedge/blur.h"
#include "rtedge/grasp.h"
#include "rtedge/morphology.h"

/* A contour that passed the filters: its index, twice its area, its
 * score and grasp (the rte_grasp_object fields of the same names). */
typedef struct grasp_candidate {
    int64_t area2;
    int32_t contour;
    int32_t score_q16;
    int32_t x_q8, y_q8, angle_q16, width_q8, opening_q8, clearance_q8;
    int32_t jaws_q8[2][2];
} grasp_candidate;

struct rte_grasp_ctx {
    rte_grasp_config config; /* as created; config.params is not updated */
    rte_grasp_params params; /* in force */
    rte_gaussian_kernel blur;
    rte_morph_element close;
    rte_morph_element shade_open;        /* 3 x 3 square: opens the half-size shade mask */
    rte_image_u8 blurred, edges, binary; /* edges: also the table estimate (background mode) */
    uint16_t *distance;                  /* the split's chamfer distances, max_width x max_height */
    rte_image_u8 tinted;                 /* the grey with colour differences as contrast (chroma) */
    rte_image_u8 cb_table, cr_table;     /* the table's chroma estimates, half size */
    rte_image_u8 workspace;           /* the ROI's mask (255 inside), built for workspace_w x _h */
    int32_t workspace_w, workspace_h; /* 0: to build (new parameters) */
    rte_contours contours;
    grasp_candidate *best; /* config.max_objects, best score first */
    rte_grasp_object *objects;
    rte_arena arena;
    void *memory; /* the block to free (rte_grasp_create), NULL after rte_grasp_init */
};

/* Bytes of the run table that tells the parts of a w x h split crop apart
 * (grasp_split.c): x0, x1, parent and area of at most (w + 1) / 2 runs a
 * row. */
static inline size_t rte_grasp_split_runs_bytes(int32_t w, int32_t h)
{
    return 4 * ((size_t)(w + 1) / 2 * (size_t)h + 1) * sizeof(int32_t);
}

/* Bytes of arena that rte_grasp_refine_cut takes for a w x h crop. */
static inline size_t rte_grasp_refine_cut_bytes(int32_t w, int32_t h)
{
    const size_t n = (size_t)w * (size_t)h;
    return rte_arena_piece_size(n) + rte_arena_piece_size(n * sizeof(int32_t));
}

/* Moves the cut between the parts of own (the split of the object pixels
 * of box inside the contour, `inside`; `dist` their chamfer distance; all
 * cw x ch crops) to the grey edge between them (grasp_cut.c); grey: the
 * crop of the blurred frame. RTE_ERR_NO_MEMORY when the arena is short. */
rte_status rte_grasp_refine_cut(rte_grasp_ctx *ctx, const rte_image_u8 *grey,
                                const rte_image_u8 *box, const uint8_t *inside, uint8_t *own,
                                const uint16_t *dist, int32_t cw, int32_t ch);

/* What the edge test of an outline reads: the binary image, the image it
 * was thresholded from, the table's estimate and the threshold of
 * |img - table|. */
typedef struct grasp_outline_images {
    rte_image_u8 bin, img, table;
    int32_t threshold;
} grasp_outline_images;

/* The share (per mille) of an outline's pixels (pts[0..n), a contour of
 * bin, CHAIN_APPROX_SIMPLE) beside the table that differ by `step` or more
 * in img from the table `reach` pixels away along one of the 4 axis
 * directions (grasp_outline.c); 1000 when none is beside the table. */
int32_t rte_grasp_outline_on_edges(const grasp_outline_images *im, const rte_point *pts, int32_t n,
                                   int32_t step, int32_t reach);

/* Splits the contours of ctx->contours that may hold touching objects
 * (grasp_split.c), clearing their cut pixels in bin, then finds the
 * contours again when any was cut; adds the parts gained to *parts. */
rte_status rte_grasp_split_touching(rte_grasp_ctx *ctx, const rte_image_u8 *grey, rte_image_u8 *bin,
                                    int32_t *parts);

/* Integer checks of run-time parameters against a configuration. */
rte_status rte_grasp_check_params(const rte_grasp_config *config, const rte_grasp_params *params);

#endif
