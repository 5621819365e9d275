/* Border following (Suzuki & Abe 1985), bit-exact with OpenCV 4.6's
 * cv::findContours (the legacy implementation): the same contours, the same
 * point order, the same hierarchy and the same output order, for the modes
 * EXTERNAL, LIST, CCOMP and TREE and the methods NONE and SIMPLE.
 *
 * Memory is bounded: the caller owns the output arrays (rte_contours) and a
 * scratch arena sized with rte_contours_scratch_size(). When a bound is hit
 * the result keeps a prefix of the contours in discovery (raster) order,
 * which is closed under "parent of", so the hierarchy stays consistent; the
 * rest is counted in dropped_contours / dropped_points and nothing is
 * written past the bounds. */
#ifndef RTEDGE_CONTOURS_H
#define RTEDGE_CONTOURS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Same numeric values as OpenCV's RETR_* and CHAIN_APPROX_*. */
typedef enum rte_contour_mode {
    RTE_CONTOURS_EXTERNAL = 0, /* outer borders only, nothing inside them */
    RTE_CONTOURS_LIST = 1,     /* every border, no hierarchy */
    RTE_CONTOURS_CCOMP = 2,    /* two levels: outer borders and their holes */
    RTE_CONTOURS_TREE = 3,     /* the full nesting */
} rte_contour_mode;

typedef enum rte_contour_method {
    RTE_CONTOURS_APPROX_NONE = 1,   /* every border pixel */
    RTE_CONTOURS_APPROX_SIMPLE = 2, /* only where the chain direction changes */
} rte_contour_method;

typedef struct rte_point {
    int32_t x, y;
} rte_point;

/* One contour of a result: its points are points[offset .. offset+count). */
typedef struct rte_contour {
    int32_t offset, count;
    /* OpenCV's layout: next sibling, previous sibling, first child, parent;
     * -1 when absent. Indices into rte_contours.contours. */
    int32_t hierarchy[4];
    bool is_hole; /* a hole border (its oriented area is positive) */
} rte_contour;

/* The caller fills the four storage fields; rte_contours_find() fills the
 * rest. Contours come out in OpenCV's order (a depth-first pre-order of the
 * tree, newest sibling first). */
typedef struct rte_contours {
    rte_point *points;     /* max_points entries */
    rte_contour *contours; /* max_contours entries */
    int32_t max_points, max_contours;

    int32_t n_points, n_contours;
    bool truncated;           /* a bound was hit */
    int32_t dropped_contours; /* contours found but not stored */
    int64_t dropped_points;   /* their points */
} rte_contours;

/* Scratch for images up to max_width x max_height and results of up to
 * max_contours contours. */
RTE_API size_t rte_contours_scratch_size(int32_t max_width, int32_t max_height,
                                         int32_t max_contours);

/* Finds the borders of the non-zero regions of `src` (not modified). Objects
 * touching the image border are traced (OpenCV pads by one zero pixel).
 * Returns RTE_OK also when truncated; RTE_ERR_NO_MEMORY when the arena is
 * too small (out->n_contours is 0 then). */
RTE_API rte_status rte_contours_find(const rte_image_u8 *src, rte_contour_mode mode,
                                     rte_contour_method method, rte_contours *out,
                                     rte_arena *scratch);

#ifdef __cplusplus
}
#endif
#endif
