/* Polygon regions of interest: filled polygons and masking.
 *
 * rte_polygon_fill_u8 is bit-exact with OpenCV 4.6's
 *   cv::fillPoly(img, {poly1, poly2, ...}, value, LINE_8, shift 0)
 * for integer vertices: each polygon's edges are drawn with the 8-connected
 * line algorithm (clipped to the image) and the even-odd rule fills the
 * scanlines of all polygons together (two overlapping polygons cancel where
 * they overlap, apart from their drawn edges). Concave, self-intersecting
 * and degenerate polygons (repeated or collinear points, 1 or 2 points) and
 * vertices far outside the image behave as in OpenCV.
 *
 * All integer; scratch comes from the caller's arena, sized by
 * rte_polygon_mask_scratch_size(). */
#ifndef RTEDGE_POLYGON_MASK_H
#define RTEDGE_POLYGON_MASK_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A vertex in pixels (x right, y down). */
typedef struct rte_vertex {
    int32_t x, y;
} rte_vertex;

/* One closed polygon: count vertices, the last joined to the first. */
typedef struct rte_polygon {
    const rte_vertex *vertex;
    int32_t count;
} rte_polygon;

/* Vertex coordinates must lie within +-RTE_POLYGON_MAX_COORD: this keeps
 * the Q16 edge and clipping arithmetic inside int64 (checked against
 * OpenCV at the limit). */
#define RTE_POLYGON_MAX_COORD (1 << 24)

/* Scratch bytes for a call whose polygons have at most max_vertices
 * vertices in total. */
RTE_API size_t rte_polygon_mask_scratch_size(int32_t max_vertices);

/* cv::fillPoly(img, polygons, value): sets the pixels inside or on the
 * polygons to `value`, leaves the others. Polygons with count 0 are skipped.
 * RTE_ERR_NO_MEMORY when the arena cannot hold the edges; on any error the
 * image is left unchanged. */
RTE_API rte_status rte_polygon_fill_u8(rte_image_u8 *img, const rte_polygon *polygons,
                                       int32_t polygon_count, uint8_t value, rte_arena *arena);

/* A region-of-interest mask: mask = 0, then the polygons filled with 255
 * (left unchanged on any error). */
RTE_API rte_status rte_polygon_mask_build(rte_image_u8 *mask, const rte_polygon *polygons,
                                          int32_t polygon_count, rte_arena *arena);

/* dst = src where mask != 0, else 0: cv::bitwise_and(src, src, dst, mask),
 * which for a 0/255 mask equals cv::bitwise_and(src, mask). dst may be src. */
RTE_API rte_status rte_polygon_mask_apply(const rte_image_u8 *src, const rte_image_u8 *mask,
                                          rte_image_u8 *dst);

/* dst = src inside or on the polygons, 0 elsewhere: rte_polygon_mask_build
 * and rte_polygon_mask_apply in one pass without a mask image (the lane
 * tutorial's fillPoly of a zero mask with 255, then bitwise_and), for a
 * region that changes from frame to frame. dst must not overlap src
 * (RTE_ERR_ARGUMENT). Scratch: rte_polygon_mask_scratch_size. On any error
 * dst is left unchanged. */
RTE_API rte_status rte_polygon_keep_u8(const rte_image_u8 *src, const rte_polygon *polygons,
                                       int32_t polygon_count, rte_image_u8 *dst, rte_arena *arena);

/* Fractions of the image size are Q16: 65536 = the full width or height. */
#define RTE_POLYGON_FRACTION_ONE 65536

/* Pixel vertices from fractional ones: x = floor(fx * width / 65536 + 1/2),
 * y = floor(fy * height / 65536 + 1/2), i.e. the nearest pixel coordinate
 * with halves rounded up (towards +infinity). 0 maps to column/row 0 and
 * RTE_POLYGON_FRACTION_ONE to `width`/`height`, just past the last pixel
 * (like the lane tutorials' (0, height) corners). Fractions may lie outside
 * [0, 1] (within +-RTE_POLYGON_MAX_FRACTION) and give vertices outside the
 * image. `out` may be `frac`. */
#define RTE_POLYGON_MAX_FRACTION (64 * RTE_POLYGON_FRACTION_ONE)
RTE_API rte_status rte_polygon_from_fractions(const rte_vertex *frac, int32_t count, int32_t width,
                                              int32_t height, rte_vertex *out);

#ifdef __cplusplus
}
#endif
#endif
