/* Split of touching objects in a binary image by the dynamics of its
 * distance transform: two or three sweets, or boxes touching across a
 * narrower neck, become separate 8-connected components, each cut from its
 * neighbours by a line of pixels set to zero; a single convex, elongated
 * (a plateau ridge) or ring-shaped object, or one with a noisy outline, is
 * left whole.
 *
 * Method: the object pixels are flooded in decreasing order of their
 * distance d (a counting sort: distances are small integers), with a
 * union-find over pixels. A pixel with no flooded 8-neighbour starts a
 * basin whose peak is its distance (a regional maximum, or one pixel of a
 * plateau, which the next pixels of the plateau join); a pixel next to one
 * basin joins it. At a pixel where several basins meet, a basin is
 * significant when its dynamic, peak - d, is at least `min_dynamic` and at
 * least `min_ratio_permille` / 1000 of its peak. When two or more of the
 * meeting basins are significant the pixel is a cut pixel (it joins none,
 * and the basins stay apart: their dynamics only grow as d falls);
 * otherwise they all merge into the one of highest peak. A final pass
 * gives back every cut pixel whose flooded neighbours all lie in one basin,
 * so the cut lines are as thin as the 8-connectivity allows: no pixel of
 * one part is an 8-neighbour of a pixel of another, so cv::findContours
 * (RETR_EXTERNAL) sees each part as its own contour.
 *
 * The peak of a basin is the largest inscribed-circle radius of its part,
 * its dynamic how far that radius falls at the neck towards a larger
 * part: two discs of radius r meeting in a neck of half-width h give the
 * smaller disc a dynamic of r - h. The ratio makes the rule scale-free
 * (CHAMFER34's default 30% splits discs whose neck is narrower than 70% of
 * the smaller radius); the absolute minimum keeps the ripples of a noisy outline from
 * making parts in small objects. The ratio must also stay above the
 * metric's own ripple: L1 and C are not round (a ring's ridge rises 41%
 * at 45 degrees in L1, falls 29% in C), CHAMFER34 is within 6% of round,
 * which makes it the metric of choice here (docs/distance.md has the
 * measured margins). Compute the distance with RTE_DIST_BORDER_ZERO, so
 * that an object cut by the image border peaks inside it rather than on
 * the border. Two boxes side by side that touch along the whole side of
 * the smaller one have no neck and stay one object.
 *
 * Against cv::watershed: this is a watershed on the inverted distance with
 * its markers chosen by their dynamics, as a by-product of the flood, where
 * cv::watershed takes markers from the caller (commonly thresholded
 * distance peaks, which cut elongated objects whose ridge crosses the
 * threshold in several places) and floods an image's grey levels (8-bit,
 * colour) from them with 4-connected watershed lines of -1 that may leave
 * parts 8-connected across a diagonal. Here the cut lines are 8-safe, the
 * flood is on the distance itself, and only the object pixels are labelled.
 *
 * Memory: scratch from an arena sized with rte_split_scratch_size() (8
 * bytes per pixel, plus a one-pixel frame and 8 bytes per row, plus a 256
 * KiB histogram), given back before returning. Cost: a pass over the rows
 * of src (runs of 8 and 32 bytes of background at a time) and work in
 * proportion to the object pixels only. Integer only. */
#ifndef RTEDGE_SPLIT_H
#define RTEDGE_SPLIT_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/distance.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rte_split_params {
    int32_t min_dynamic;        /* >= 1, in the distance's units (thirds for CHAMFER34) */
    int32_t min_ratio_permille; /* 0..1000: the dynamic's least share of the basin's peak */
} rte_split_params;

typedef struct rte_split_result {
    int32_t parts;      /* basins left: the 8-connected components of dst */
    int32_t cut_pixels; /* object pixels set to 0 */
} rte_split_result;

/* The defaults for a distance of this metric: min_dynamic 2 px (2, or 6
 * thirds) and a ratio of 300 per mille for CHAMFER34, 350 for L1, 250 for
 * C, measured in docs/distance.md. RTE_ERR_ARGUMENT for an unknown
 * metric. */
RTE_API rte_status rte_split_params_default(rte_split_params *params, rte_dist_metric metric);

/* Arena bytes that rte_split_u8 needs for images up to max_width x
 * max_height; 0 for sizes outside 1..RTE_MAX_SIDE. */
RTE_API size_t rte_split_scratch_size(int32_t max_width, int32_t max_height);

/* dst = src with the cut pixels set to 0 (other pixels copied). `dist` is
 * the distance transform of src (rte_distance_transform_u8, any metric,
 * best with RTE_DIST_BORDER_ZERO; any u16 image of object heights works). dst may be src itself.
 * `result` may be NULL. RTE_ERR_ARGUMENT for NULL arguments or parameters
 * out of range, RTE_ERR_SIZE for invalid views or different sizes,
 * RTE_ERR_NO_MEMORY when the arena is too small (dst is then untouched). */
RTE_API rte_status rte_split_u8(const rte_image_u8 *src, const rte_image_u16 *dist,
                                rte_image_u8 *dst, const rte_split_params *params, rte_arena *arena,
                                rte_split_result *result);

#ifdef __cplusplus
}
#endif
#endif
