/* Erosion, dilation, opening and closing of 8-bit single-channel images,
 * bit-identical with OpenCV 4.6 cv::erode, cv::dilate and
 * cv::morphologyEx(MORPH_OPEN / MORPH_CLOSE) with the default border
 * (pixels outside the image never win) and a structuring element from
 * cv::getStructuringElement (MORPH_RECT, MORPH_CROSS, MORPH_ELLIPSE) or any
 * 0/1 mask.
 *
 * The element is built once, at configuration time, into a struct the
 * caller owns; the per-frame functions are integer only and take their
 * scratch from an arena sized with rte_morphology_scratch_size().
 *
 * Like OpenCV, erosion is the minimum and dilation the maximum of
 * src(x + i - anchor_x, y + j - anchor_y) over the element's set cells
 * (i, j); the element is not mirrored for dilation. iterations > 1 repeats
 * the operation (for a rectangle OpenCV instead uses one larger rectangle,
 * which gives the same pixels); opening is `iterations` erosions followed
 * by `iterations` dilations, closing the reverse. */
#ifndef RTEDGE_MORPHOLOGY_H
#define RTEDGE_MORPHOLOGY_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Same numbering as OpenCV's cv::MorphShapes. */
typedef enum rte_morph_shape {
    RTE_MORPH_RECT = 0,
    RTE_MORPH_CROSS = 1,
    RTE_MORPH_ELLIPSE = 2,
} rte_morph_shape;

/* Same numbering as OpenCV's cv::MorphTypes (the supported subset). */
typedef enum rte_morph_op {
    RTE_MORPH_ERODE = 0,
    RTE_MORPH_DILATE = 1,
    RTE_MORPH_OPEN = 2,
    RTE_MORPH_CLOSE = 3,
} rte_morph_op;

/* Largest element side. */
#define RTE_MORPH_MAX_KSIZE 31

/* One horizontal run of set cells: row `dy` of the element, columns
 * dx .. dx + len - 1 (both relative to the element's top-left corner). */
typedef struct rte_morph_run {
    int16_t dy, dx, len;
} rte_morph_run;

/* A structuring element as runs of set cells, plus the mask it came from.
 * Fill it with rte_morphology_element_init() or _from_mask(). */
typedef struct rte_morph_element {
    int32_t width, height;      /* 1..RTE_MORPH_MAX_KSIZE */
    int32_t anchor_x, anchor_y; /* 0 <= anchor < size */
    int32_t full;               /* every cell set: the separable rectangle path */
    int32_t run_count;          /* >= 1 */
    int32_t max_run;            /* longest run */
    rte_morph_run runs[RTE_MORPH_MAX_KSIZE * ((RTE_MORPH_MAX_KSIZE + 1) / 2)];
    uint8_t mask[RTE_MORPH_MAX_KSIZE * RTE_MORPH_MAX_KSIZE]; /* row-major, width per row, 0/1 */
} rte_morph_element;

/* cv::getStructuringElement(shape, Size(width, height)) with the default
 * anchor (width / 2, height / 2). Configuration time (the ellipse is
 * computed in floating point as OpenCV does). RTE_ERR_ARGUMENT for an
 * unknown shape or a side outside 1..RTE_MORPH_MAX_KSIZE. */
RTE_API rte_status rte_morphology_element_init(rte_morph_element *element, rte_morph_shape shape,
                                               int32_t width, int32_t height);

/* An element from a width x height mask (row-major, non-zero = set) with
 * the given anchor; anchor_x/anchor_y of -1 mean the centre (size / 2).
 * RTE_ERR_ARGUMENT for a mask with no set cell (OpenCV has no meaningful
 * result for it). */
RTE_API rte_status rte_morphology_element_from_mask(rte_morph_element *element, const uint8_t *mask,
                                                    int32_t width, int32_t height, int32_t anchor_x,
                                                    int32_t anchor_y);

/* Arena bytes that any rte_morphology_* call needs for images up to
 * max_width x max_height with this element and iteration count. */
RTE_API size_t rte_morphology_scratch_size(int32_t max_width, int32_t max_height,
                                           const rte_morph_element *element, int32_t iterations);

/* dst = op(src). `dst` has the size of `src` and may be `src` itself.
 * iterations >= 1 (RTE_ERR_ARGUMENT otherwise). RTE_ERR_NO_MEMORY when the arena is too small; the arena is returned to
 * its entry mark. */
RTE_API rte_status rte_morphology_u8(const rte_image_u8 *src, rte_image_u8 *dst, rte_morph_op op,
                                     const rte_morph_element *element, int32_t iterations,
                                     rte_arena *arena);

/* cv::erode / cv::dilate: rte_morphology_u8 with RTE_MORPH_ERODE / _DILATE. */
RTE_API rte_status rte_morphology_erode_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                           const rte_morph_element *element, int32_t iterations,
                                           rte_arena *arena);
RTE_API rte_status rte_morphology_dilate_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                            const rte_morph_element *element, int32_t iterations,
                                            rte_arena *arena);

#ifdef __cplusplus
}
#endif
#endif
