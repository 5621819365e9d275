/* Objects on a table under uneven light: the table's brightness estimated
 * per pixel, and a two-sided threshold of the difference, so that objects
 * both lighter and darker than the table are found where a single global
 * threshold takes a vignetted corner for an object.
 *
 * rte_background_estimate_u8: the frame is cut into cells of cell x cell
 * px and each cell's median taken. The cells form regions, joined through
 * neighbours whose medians differ by at most `step`: light falling off
 * across a table is many small steps between cells, an object's edge one
 * large step (a cell's median flips from table to object where the object
 * covers half of it). The table is the region with the most cells on the
 * frame's edge, then the most cells: it surrounds the objects and runs out
 * of the view, while a sheet or a tray on it lies inside. So the table is
 * followed into a vignetted corner while objects of any size stay out.
 * Each cell's estimate is the least-squares plane through the table cells
 * within `radius` cells of it, evaluated at the cell and kept within
 * `tolerance` of those cells' range (where there are fewer than 6 of them,
 * inside a large object: the mean of the table cells within 2, 4, ...
 * times the radius), in 1/16 grey levels, interpolated bilinearly between
 * cell centres to every pixel. An object whose brightness meets the
 * table's somewhere along a gradient (a shaded or gradient-filled object)
 * is joined to the table there; edges (Canny) find those.
 *
 * rte_background_threshold_u8: d = src - background per pixel; the high
 * threshold is params.high, or Otsu's threshold of the histogram of |d|,
 * at least params.min_contrast; the low threshold is two thirds of it. Pixels
 * with |d| > low form 8-connected regions of one sign, kept when one of
 * their pixels has |d| > high (hysteresis, as in Canny). A dark region that
 * comes within shadow_gap px of a bright one both larger and of higher mean contrast is the
 * shadow that object casts, and is dropped (params.drop_shadows); other
 * touching regions stay one object (a dark pen with a bright metal tip).
 *
 * Both are integer only and take their scratch from the arena (sized by
 * the *_scratch_size functions for the largest frame); they allocate
 * nothing. */
#ifndef RTEDGE_BACKGROUND_H
#define RTEDGE_BACKGROUND_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RTE_BACKGROUND_MIN_CELL 2
#define RTE_BACKGROUND_MAX_CELL 255
#define RTE_BACKGROUND_MAX_RADIUS 8

typedef struct rte_background_params {
    int32_t cell;      /* cell side in px, RTE_BACKGROUND_MIN_CELL..MAX_CELL */
    int32_t radius;    /* window half-size in cells, 1..RTE_BACKGROUND_MAX_RADIUS */
    int32_t tolerance; /* grey levels a cell's plane may reach beyond the range of the table
                        * cells it was fitted to, 0..255 */
    int32_t step;      /* grey levels between neighbouring table cells, 0..255 */
} rte_background_params;

/* Defaults for frames `width` px wide: cells of width / 40 px (at least 4),
 * radius 4 (a 9 x 9 cell window), tolerance 12, step 8. */
RTE_API void rte_background_params_default(rte_background_params *params, int32_t width);

/* Arena bytes rte_background_estimate_u8 needs for frames up to max_width x
 * max_height with cells of at least min_cell px (0 for invalid sizes). */
RTE_API size_t rte_background_scratch_size(int32_t max_width, int32_t max_height, int32_t min_cell);

/* The table's brightness at every pixel of src, into background (same
 * size; may not alias src). */
RTE_API rte_status rte_background_estimate_u8(const rte_image_u8 *src, rte_image_u8 *background,
                                              const rte_background_params *params,
                                              rte_arena *arena);

typedef struct rte_background_threshold_params {
    int32_t high;         /* 0: Otsu's threshold of |src - background|; else 1..255 */
    int32_t min_contrast; /* the high threshold is at least this, 1..255 */
    bool bright;          /* objects lighter than the table are found */
    bool dark;            /* objects darker than the table are found */
    bool drop_shadows;    /* dark regions that are a brighter object's shadow are dropped */
    /* A kept region's pixels with |d| at most this share of its mean |d| are
     * left out (0..1000): a sweet's own soft shadow, weak beside its colour,
     * is not the sweet. */
    int32_t region_share_permille;
    /* px: smaller dark regions are not looked at as shadows (left to an
     * area filter). */
    int32_t shadow_min_area;
    /* px between a shadow and its object (d crosses zero between them, over
     * about the blur's width), 0..RTE_BACKGROUND_MAX_SHADOW_GAP. */
    int32_t shadow_gap;
} rte_background_threshold_params;

#define RTE_BACKGROUND_MAX_SHADOW_GAP 32

/* For frames `width` px wide: high 0 (Otsu), min_contrast 20, both sides,
 * shadows of 64 px or more dropped within width / 200 px (at least 3), a
 * region's pixels below 40% of its mean |d| left out. */
RTE_API void rte_background_threshold_params_default(rte_background_threshold_params *params,
                                                     int32_t width);

/* Arena bytes rte_background_threshold_u8 needs for frames up to max_width x
 * max_height (0 for invalid sizes). */
RTE_API size_t rte_background_threshold_scratch_size(int32_t max_width, int32_t max_height);

typedef struct rte_background_threshold_result {
    int32_t high, low;      /* the thresholds applied */
    int32_t regions;        /* regions of one side beyond low (strong or not) */
    int32_t shadows;        /* strong dark regions dropped as shadows */
    int64_t dropped_pixels; /* pixels beyond low left out: the run table was full (a frame
                             * flipping side every few pixels); 0 on real frames */
} rte_background_threshold_result;

/* dst = 255 on object pixels, 0 elsewhere (same size as src and
 * background; dst may alias neither). result may be NULL. */
RTE_API rte_status rte_background_threshold_u8(const rte_image_u8 *src,
                                               const rte_image_u8 *background, rte_image_u8 *dst,
                                               const rte_background_threshold_params *params,
                                               rte_arena *arena,
                                               rte_background_threshold_result *result);

/* As rte_background_threshold_u8, with shade: where shade (a half-size
 * mask, ((width + 1) / 2) x ((height + 1) / 2), each sample for its 2x2
 * block; NULL for none) is non-zero, a dark pixel may be a shadow on the
 * table (rte_background_shade_u8). Those pixels form regions of their
 * own within their object (its dark pixels, shade or not, connected). In
 * an object whose other dark pixels form one region of shadow_min_area px
 * or more (its core), a shade region of shadow_min_area px or more, at
 * least a twentieth of the core and lighter than it (mean |d|) is the
 * core's cast shadow and is dropped (counted in result->shadows); the rest
 * of every object is one region, as without the mask. Every region of the
 * mask may be taken for a shadow: take out its thin parts first (the rim
 * of a dark object's blurred edge is dimmed as a shadow is); the grasp
 * path opens it with a 3 x 3 square. */
RTE_API rte_status rte_background_threshold_shaded_u8(const rte_image_u8 *src,
                                                      const rte_image_u8 *background,
                                                      const rte_image_u8 *shade, rte_image_u8 *dst,
                                                      const rte_background_threshold_params *params,
                                                      rte_arena *arena,
                                                      rte_background_threshold_result *result);

/* A shadow dims the table's light and leaves its colour: shade = 255 where
 * src is between darkest and lightest (per mille) of the table's
 * brightness and its chroma is the table's dimmed as much, within
 * `chroma` (|cb - 128 - k (cb_background - 128)| + |cr - 128 - k
 * (cr_background - 128)| with k = src / background; chroma planes as for
 * rte_background_tint_u8), else 0. shade has the chroma planes' size: one
 * decision per 2x2 block, on its top-left pixel. */
typedef struct rte_background_shade_params {
    int32_t darkest_permille;  /* 0..1000 */
    int32_t lightest_permille; /* darkest..1000 */
    int32_t chroma;            /* 0..255 */
} rte_background_shade_params;

RTE_API rte_status rte_background_shade_u8(const rte_image_u8 *src, const rte_image_u8 *background,
                                           const rte_image_u8 *cb,
                                           const rte_image_u8 *cb_background,
                                           const rte_image_u8 *cr,
                                           const rte_image_u8 *cr_background, rte_image_u8 *shade,
                                           const rte_background_shade_params *params);

/* Colour as contrast, for rte_background_threshold_u8: the frame's colour
 * difference from the table's, c = |cb - cb_background| + |cr -
 * cr_background| (chroma planes at half size, ((width + 1) / 2) x ((height
 * + 1) / 2), each sample for its 2x2 block; at most 255), replaces its grey
 * difference where it is larger and at least `least` (smaller ones are the
 * sensor's noise): dst = background + c or background - c (clamped), on
 * the side of src - background (where src equals background, the side
 * with room: up below 128), or on the one side looked for; elsewhere dst =
 * src. So an object as grey as the table but of another colour stands out.
 * dst has src's size and may alias neither src nor background. */
typedef struct rte_background_tint_params {
    int32_t least; /* 1..255 */
    bool bright;   /* objects lighter than the table are looked for */
    bool dark;     /* objects darker than the table are looked for */
} rte_background_tint_params;

RTE_API rte_status rte_background_tint_u8(const rte_image_u8 *src, const rte_image_u8 *background,
                                          const rte_image_u8 *cb, const rte_image_u8 *cb_background,
                                          const rte_image_u8 *cr, const rte_image_u8 *cr_background,
                                          rte_image_u8 *dst,
                                          const rte_background_tint_params *params);

#ifdef __cplusplus
}
#endif
#endif
