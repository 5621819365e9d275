/* Features of a contour for the grasp path, in integer arithmetic.
 *
 * A contour is an array of rte_point (as rte_contours_find writes them),
 * read as a closed polygon. Fixed-point formats are named by their suffix:
 * _q8 = 1/256, _q16 = 1/65536, _q32 = 1/2^32 of the unit. Where OpenCV 4.6
 * computes exactly on integer points (areas, spatial moments, convex hull,
 * approxPolyDP's decisions, hull defect positions) the result is identical;
 * elsewhere the precision is stated next to each function. */
#ifndef RTEDGE_SHAPE_H
#define RTEDGE_SHAPE_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/contours.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Coordinates the feature functions accept: |x|, |y| <= this. Keeps every
 * exact product inside 64 bits (moments) or 128 bits (everything else). */
#define RTE_SHAPE_MAX_COORD 2047

typedef struct rte_rect {
    int32_t x, y, width, height;
} rte_rect;

/* ---- moments.c ---- */

/* Twice the oriented area (shoelace), exact: OpenCV's
 * contourArea(oriented=true) * 2. Negative for outer borders from
 * rte_contours_find, positive for holes. 0 when n < 3. */
RTE_API int64_t rte_shape_area2(const rte_point *pts, int32_t n);

/* Perimeter (closed != 0) or polyline length, in 1/65536 px: the sum of
 * per-segment lengths each rounded to Q16 (error <= n/131072 px). */
RTE_API int64_t rte_shape_perimeter_q16(const rte_point *pts, int32_t n, int closed);

/* cv::boundingRect of a point set; {0,0,0,0} when n == 0. */
RTE_API rte_rect rte_shape_bounding_rect(const rte_point *pts, int32_t n);

/* Moments of the polygon, as cv::moments(contour). The spatial moments are
 * exact: mPQ = sPQ / dPQ with the divisors in the comments (OpenCV divides
 * in double). The sign is normalised so that s00 >= 0; all are 0 when the
 * area is 0. Central moments are rounded to Q8, the centroid to Q16, the
 * normalised moments nu and the seven Hu invariants to Q32 (absolute error
 * below 1e-7 for shapes of 20 px and more). */
typedef struct rte_moments {
    int64_t s00;                /* m00 = s00 / 2 */
    int64_t s10, s01;           /* m10 = s10 / 6 */
    int64_t s20, s11, s02;      /* m20 = s20 / 12, m11 = s11 / 24 */
    int64_t s30, s21, s12, s03; /* m30 = s30 / 20, m21 = s21 / 60 */
    int64_t cx_q16, cy_q16;     /* centroid m10/m00, m01/m00 */
    int64_t mu20_q8, mu11_q8, mu02_q8, mu30_q8, mu21_q8, mu12_q8, mu03_q8;
    int64_t nu20_q32, nu11_q32, nu02_q32, nu30_q32, nu21_q32, nu12_q32, nu03_q32;
    int64_t hu_q32[7];
} rte_moments;

/* RTE_ERR_ARGUMENT for n < 0 or NULL; RTE_ERR_TOO_LARGE for coordinates
 * beyond RTE_SHAPE_MAX_COORD. */
RTE_API rte_status rte_shape_moments(const rte_point *pts, int32_t n, rte_moments *m);

/* ---- convex_hull.c ---- */

RTE_API size_t rte_shape_hull_scratch_size(int32_t max_points);

/* cv::convexHull(points, clockwise=false): the same hull vertices in the
 * same order (clockwise on screen), as indices into pts (`indices`, may be
 * NULL) and/or as points (`hull`, may be NULL); both need room for n
 * entries. *n_hull gets the vertex count (0 when n == 0). */
RTE_API rte_status rte_shape_convex_hull(const rte_point *pts, int32_t n, int32_t *indices,
                                         rte_point *hull, int32_t *n_hull, rte_arena *scratch);

/* cv::convexityDefects: one entry per hull edge that has contour points
 * strictly off it: the edge's start and end indices, the farthest point's
 * index and its distance in 1/256 px (round(depth * 256), as OpenCV).
 * `hull` are indices from rte_shape_convex_hull. Needs room for n_hull
 * defects; *n_defects = 0 when n <= 3 or n_hull < 3. RTE_ERR_ARGUMENT when
 * the hull indices are not monotonic (self-intersecting contours). */
typedef struct rte_defect {
    int32_t start, end, farthest, depth_q8;
} rte_defect;

RTE_API rte_status rte_shape_convexity_defects(const rte_point *pts, int32_t n, const int32_t *hull,
                                               int32_t n_hull, rte_defect *defects,
                                               int32_t *n_defects);

/* ---- approx_poly.c ---- */

RTE_API size_t rte_shape_approx_scratch_size(int32_t max_points);

/* cv::approxPolyDP(curve, epsilon, closed=true) with epsilon =
 * epsilon_q16 / 65536 (< 1024 px): the same vertices in the same order.
 * Every comparison OpenCV makes in double is reproduced exactly, rounding
 * included, so the result equals OpenCV's for that (exactly representable)
 * epsilon. `out` needs room for n points. */
RTE_API rte_status rte_shape_approx_poly(const rte_point *pts, int32_t n, uint32_t epsilon_q16,
                                         rte_point *out, int32_t *n_out, rte_arena *scratch);

/* ---- min_area_rect.c ---- */

/* The minimum-area rotated rectangle (rotating calipers over the convex
 * hull, exact integer area comparisons).
 * Convention: `length` is the long side and `angle_q16` its direction in
 * degrees within (-90, 90], measured in image coordinates (x right, y
 * down: a positive angle turns clockwise on screen). `width` is the short
 * side. Corners are ordered as cv::boxPoints orders a RotatedRect of
 * size (length, width) at that angle: bottom-left, top-left, top-right,
 * bottom-right for angle 0. Coordinates are Q8 (error <= 1/256 px), the
 * angle error is below 0.001 degree. */
typedef struct rte_rotated_rect {
    int32_t cx_q8, cy_q8;
    int32_t length_q8, width_q8;
    int32_t angle_q16;
    int32_t corners_q8[4][2];
} rte_rotated_rect;

RTE_API size_t rte_shape_min_area_rect_scratch_size(int32_t max_points);
RTE_API rte_status rte_shape_min_area_rect(const rte_point *pts, int32_t n, rte_rotated_rect *r,
                                           rte_arena *scratch);

/* ---- calipers.c ---- */

/* The widths of a convex polygon by rotating calipers, one per edge: the
 * polygon's extent across that edge (the distance from the edge's line to
 * the farthest vertex). The narrowest width of a shape is the smallest of
 * its hull's: the minimum over all directions of its extent along one is
 * reached across a hull edge. `hull`: distinct vertices in order, either
 * orientation (rte_shape_convex_hull's output); `out` needs room for n
 * entries. *n_out = n, or 1 for a point, a segment or collinear vertices
 * (width 0, across the segment). RTE_ERR_ARGUMENT for a repeated vertex,
 * RTE_ERR_TOO_LARGE beyond RTE_SHAPE_MAX_COORD. Width rounded to Q8, unit
 * vector to Q16, angle within 0.001 degree. */
typedef struct rte_caliper {
    int32_t edge;           /* hull[edge] -> hull[(edge + 1) % n] */
    int32_t far;            /* the vertex farthest from the edge's line (the first of equals) */
    int32_t width_q8;       /* its distance from that line */
    int32_t angle_q16;      /* that direction, normal to the edge: degrees within (-90, 90] */
    int32_t ux_q16, uy_q16; /* its unit vector, pointing the way angle_q16 does */
} rte_caliper;

RTE_API rte_status rte_shape_calipers(const rte_point *hull, int32_t n, rte_caliper *out,
                                      int32_t *n_out);

/* ---- enclosing_circle.c ---- */

/* The smallest circle holding every point (Welzl's incremental algorithm
 * over the convex hull in a fixed pseudo-random order; exact rational
 * centres and in-circle tests). Q8 centre and radius, rounded (OpenCV adds
 * 1e-4 to its float radius; this does not). */
typedef struct rte_circle {
    int32_t cx_q8, cy_q8, r_q8;
} rte_circle;

RTE_API size_t rte_shape_enclosing_circle_scratch_size(int32_t max_points);
RTE_API rte_status rte_shape_enclosing_circle(const rte_point *pts, int32_t n, rte_circle *c,
                                              rte_arena *scratch);

/* ---- shape.c ---- */

typedef enum rte_shape_class {
    RTE_SHAPE_OTHER = 0,
    RTE_SHAPE_TRIANGLE,
    RTE_SHAPE_SQUARE,
    RTE_SHAPE_RECTANGLE,
    RTE_SHAPE_PENTAGON,
    RTE_SHAPE_HEXAGON,
    RTE_SHAPE_CIRCLE,
} rte_shape_class;

/* What a pick-and-place robot needs of one contour. Ratios are Q16. */
typedef struct rte_shape_info {
    rte_shape_class shape;
    int32_t vertices;        /* after approxPolyDP with 0.02 x perimeter */
    int32_t vertices_coarse; /* the same with 0.04 x perimeter */
    int64_t area2;           /* |twice the area| */
    int64_t perimeter_q16;
    rte_rect bounds;
    int32_t aspect_q16;           /* long / short side of the rotated rectangle (>= 1) */
    int32_t extent_q16;           /* area / bounding-box area */
    int32_t solidity_q16;         /* area / hull area */
    int32_t circularity_q16;      /* 4 pi area / perimeter^2 (1.0 for a disc) */
    int32_t hull_circularity_q16; /* the same with the hull's perimeter */
    rte_rotated_rect box;
    rte_circle circle;
    int64_t cx_q16, cy_q16; /* centroid */
} rte_shape_info;

/* Classification: the OpenCV tutorial's vertex rule, made robust to edge
 * noise. v = vertices after approxPolyDP(0.02 x perimeter); c = hull
 * circularity, 4 pi area / hull perimeter^2 (regular triangle 0.60, square
 * 0.785, pentagon 0.865, hexagon 0.907, disc 1; unlike the contour's own
 * circularity it ignores the pixel staircase and the dents of a noisy
 * edge); f = area / area of the enclosing circle; a = aspect ratio;
 * roundness = 0.86 c + 0.14 f.
 *  - area below 16 px or solidity below 0.80: other
 *  - v == 3: triangle
 *  - v == 4, or c < 0.813 (a quadrilateral or triangle whose noisy edge
 *    kept an extra vertex): triangle when c < 0.70 and a < 1.3, or when the
 *    shape fills less than 0.70 of its minimum-area rectangle (a triangle
 *    with a rounded corner: about 0.5; squares and rectangles, even
 *    hand-drawn: 0.9 and more); else square when a <= 1.15 (the square
 *    tolerance), else rectangle
 *  - v > 6 and roundness >= 0.904 (circularity confirming): circle
 *  - v <= 8: hexagon when roundness >= 0.858, else pentagon, where the
 *    vertex count with 0.04 x perimeter (which drops most vertices that
 *    noise adds) moves the threshold to 0.868 when it is 5 or less and to
 *    0.848 when it is 6; more than 8 vertices: other.
 * Measured on synthetic shapes with noisy edges (6% of edge pixels
 * flipped): 1 of 12000 shapes of 20-150 px misclassified, and 11 of
 * 12000 (0.09%) of 20-26 px, nearly all pentagon/hexagon confusions. */
#define RTE_SHAPE_SQUARE_ASPECT_Q16 75366 /* 1.15 */
#define RTE_SHAPE_CIRCLE_MIN_Q16 59245    /* 0.904 */

RTE_API size_t rte_shape_classify_scratch_size(int32_t max_points);
RTE_API rte_status rte_shape_classify(const rte_point *pts, int32_t n, rte_shape_info *info,
                                      rte_arena *scratch);

#ifdef __cplusplus
}
#endif
#endif
