/* Distance transform of a binary 8-bit image: for each object pixel
 * (non-zero) the distance to the nearest zero pixel, by the two-pass 3x3
 * chamfer algorithm (a forward raster pass over the upper-left neighbours,
 * then a backward pass over the lower-right ones), into a caller-owned
 * 16-bit image. Zero pixels get 0. Integer only, no scratch memory.
 *
 * Metrics (the weights of a horizontal or vertical step and of a diagonal
 * step):
 *   RTE_DIST_L1        1, 2   city block; bit-exact with
 *                             cv::distanceTransform(src, dst, DIST_L1, 3)
 *   RTE_DIST_C         1, 1   chessboard; bit-exact with
 *                             cv::distanceTransform(src, dst, DIST_C, 3)
 *   RTE_DIST_CHAMFER34 3, 4   in thirds of a pixel; an approximation of the
 *                             Euclidean distance (cv::DIST_L2 with
 *                             DIST_MASK_PRECISE): value / 3 lies within
 *                             [0.9428, 1.0541] times the Euclidean distance
 *                             (-5.7% at 45 degrees, +5.4% at atan(1/3)),
 *                             measured by the oracle suite on every fixture,
 *                             real photo and random image.
 * OpenCV returns float32 holding these integers; the u16 here holds the
 * same numbers.
 *
 * The image border: with RTE_DIST_BORDER_FAR, as OpenCV 4.6 treats it,
 * pixels outside the image are not zero pixels (an object touching the
 * border is measured from its other edges only); with RTE_DIST_BORDER_ZERO
 * they are (the result of OpenCV on the image framed by one row and column
 * of zeros, cropped back), which suits rte_split_u8: the distance of an
 * object cut by the border still peaks inside it. Values are capped: L1 and
 * C at RTE_DIST_CAP (8192, OpenCV's (INT_MAX >> 2) in its 16.16 fixed
 * point), so with BORDER_FAR an image without a zero pixel is 8192
 * everywhere; CHAMFER34 saturates at 65535 (21845 px), reached only in
 * images with sides over about 20000 pixels with BORDER_FAR or over 43000
 * with BORDER_ZERO (so never within RTE_MAX_SIDE); L1 and C values
 * saturate at the cap, never overflow. */
#ifndef RTEDGE_DISTANCE_H
#define RTEDGE_DISTANCE_H

#include <stdint.h>

#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* L1 and C take OpenCV's cv::DistanceTypes numbers; CHAMFER34 has no
 * OpenCV counterpart (34 for its weights). */
typedef enum rte_dist_metric {
    RTE_DIST_L1 = 1,
    RTE_DIST_C = 3,
    RTE_DIST_CHAMFER34 = 34,
} rte_dist_metric;

/* How pixels outside the image count. */
typedef enum rte_dist_border {
    RTE_DIST_BORDER_FAR = 0,  /* not zero pixels: OpenCV's cv::distanceTransform */
    RTE_DIST_BORDER_ZERO = 1, /* zero pixels: the image as if framed by zeros */
} rte_dist_border;

/* The largest L1 or C value (OpenCV's); CHAMFER34's is UINT16_MAX. */
#define RTE_DIST_CAP 8192

/* Distance units per pixel: 1 for L1 and C, 3 for CHAMFER34; 0 for an
 * unknown metric. */
RTE_API int32_t rte_distance_unit(rte_dist_metric metric);

/* dst = the distance transform of src (same size; strides may differ).
 * RTE_ERR_ARGUMENT for a NULL image or an unknown metric or border,
 * RTE_ERR_SIZE for an invalid view or different sizes. */
RTE_API rte_status rte_distance_transform_u8(const rte_image_u8 *src, rte_image_u16 *dst,
                                             rte_dist_metric metric, rte_dist_border border);

#ifdef __cplusplus
}
#endif
#endif
