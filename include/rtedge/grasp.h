/* The grasp path: graspable objects on a table seen from above.
 *
 *   grey -> Gaussian blur -> binary image (the difference from the table's
 *   estimated brightness thresholded both ways, Otsu, a fixed threshold,
 *   or Canny + morphological close for objects whose boundary is the only
 *   reliable cue) -> external contours -> area filter -> features
 *   (centroid from moments, minimum-area box, shape class, solidity)
 *   -> grasp (below, rte_grasp_object): the point at the centroid, the
 *   gripper closing across the object's narrowest width, opened to that
 *   width plus a margin on each side, and a graspability score; the
 *   objects are reported best score first.
 *
 * A context is set up once for a maximum frame size and maximum counts: it
 * holds every buffer and the scratch arena, in one block of caller memory
 * (rte_grasp_init) or one malloc at start-up (rte_grasp_create).
 * rte_grasp_process() allocates nothing and is integer only. The parameters of rte_grasp_params can be changed between frames
 * with rte_grasp_set_params() (no allocation); the fields of
 * rte_grasp_config outside .params fix buffer sizes and tables and cannot.
 * A context is not thread-safe: one per thread. */
#ifndef RTEDGE_GRASP_H
#define RTEDGE_GRASP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/contours.h"
#include "rtedge/image.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/shape.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rte_grasp_binarize {
    RTE_GRASP_OTSU = 0,        /* Otsu's threshold of each frame */
    RTE_GRASP_FIXED = 1,       /* params.threshold */
    RTE_GRASP_CANNY_CLOSE = 2, /* Canny edges closed by an ellipse: the object's outline */
    RTE_GRASP_BACKGROUND = 3,  /* |frame - table| beyond a contrast (rtedge/background.h):
                                * uneven light, objects lighter and darker than the table */
} rte_grasp_binarize;

/* Which side of the threshold the objects are (background, Otsu and fixed
 * modes). */
typedef enum rte_grasp_polarity {
    RTE_GRASP_AUTO = 0,   /* background mode: both sides; Otsu and fixed: the side the
                           * image border is not on (the border is table) */
    RTE_GRASP_DARK = 1,   /* objects darker than the table: pixel <= threshold */
    RTE_GRASP_BRIGHT = 2, /* objects brighter: pixel > threshold */
} rte_grasp_polarity;

/* Parts of one contour the split tells apart by size (more are counted as
 * the last). */
#define RTE_GRASP_MAX_SPLIT_PARTS 64

/* Bounds of rte_grasp_config's contour store. */
#define RTE_GRASP_MAX_CONTOURS (1 << 20)
#define RTE_GRASP_MAX_POINTS (1 << 26)

/* Safe to change at run time (rte_grasp_set_params). */
#define RTE_GRASP_MAX_ROI_VERTICES 8
#define RTE_GRASP_MAX_OPENING_PX 65535  /* gripper_max_px */
#define RTE_GRASP_MAX_CLEARANCE_PX 4096 /* margin_px, finger_px */

typedef struct rte_grasp_params {
    rte_grasp_binarize binarize;
    int32_t threshold; /* RTE_GRASP_FIXED: 0..255 */
    rte_grasp_polarity polarity;
    int32_t canny_low, canny_high; /* RTE_GRASP_CANNY_CLOSE: L1 magnitude thresholds, 0..2040 */
    int32_t contrast;        /* RTE_GRASP_BACKGROUND: least |frame - table| of an object, 1..255
                              * (the threshold is Otsu's of |frame - table|, at least this) */
    int32_t background_cell; /* RTE_GRASP_BACKGROUND: the table estimate's cell side in px,
                              * 2..255, or 0: a 40th of the frame's width (at least 4) */
    int32_t chroma;          /* RTE_GRASP_BACKGROUND, 1: with rte_grasp_process_chroma, a
                              * pixel whose colour differs from the table's (|cb - table's
                              * cb| + |cr - table's cr|) more than its grey does counts
                              * by that difference: an object as grey as the table but
                              * of another colour is found; and a dark object's cast
                              * shadow (the table dimmed, its colour kept) is told from
                              * it and dropped */
    int32_t min_area;        /* pixels; smaller objects are dropped (>= 0) */
    int32_t max_area;        /* pixels; larger ones are dropped; 0 = no limit */
    int32_t skip_border;     /* 1: drop objects touching the image or workspace border */
    int32_t split;           /* 1: split touching objects at their necks (rtedge/split.h):
                              * contours of solidity below 0.95, at least twice min_area,
                              * at most twice gripper_max_px across and a quarter of the
                              * frame, by the chamfer distance of their own pixels */
    int32_t max_objects;     /* 1..config.max_objects: objects reported (best scores) */
    /* RTE_GRASP_BACKGROUND: 0..1000, 0 = off. An object's outline lies on an
     * edge: one whose pixels beside the table step by a fifth of `contrast`
     * or more (in the thresholded image, to the table pixel one per 640 px
     * of the frame's width away) on less than this share (per mille) is a
     * threshold across a smooth ramp (a shaded box crossing the table's
     * grey, a soft shadow's rim) and is dropped. */
    int32_t edge_support_permille;
    /* The workspace: a polygon in fractions of width and height (Q16, as
     * rte_polygon_from_fractions takes them), 3..RTE_GRASP_MAX_ROI_VERTICES
     * vertices; objects are looked for inside it only, and one that reaches
     * its edge touches the border. roi_count 0: the whole frame. */
    rte_vertex roi[RTE_GRASP_MAX_ROI_VERTICES];
    int32_t roi_count;
    /* The gripper, in image pixels: the jaws open from gripper_min_px to
     * gripper_max_px (0 <= min <= max <= RTE_GRASP_MAX_OPENING_PX); they
     * open margin_px wider than the object on each side, and each finger
     * needs finger_px of free room beyond its jaw face (both
     * 0..RTE_GRASP_MAX_CLEARANCE_PX). */
    int32_t gripper_min_px, gripper_max_px;
    int32_t margin_px;
    int32_t finger_px;
} rte_grasp_params;

typedef struct rte_grasp_config {
    int32_t max_width, max_height; /* 1..RTE_SHAPE_MAX_COORD + 1 */
    int32_t max_contours;          /* per frame, 1..RTE_GRASP_MAX_CONTOURS (then truncated) */
    int32_t max_points;            /* contour points per frame, 1..RTE_GRASP_MAX_POINTS */
    int32_t max_objects;           /* capacity of the object list */
    int32_t blur_ksize;            /* odd 1..15; 1 = no blur (sigma from the size) */
    int32_t close_ksize;           /* ellipse of the canny-close mode, odd 1..31 */
    int32_t close_iterations;      /* 1..8 */
    rte_grasp_params params;       /* the initial parameters */
} rte_grasp_config;

/* Defaults: 1280x720, 4096 contours, 262144 points, 64 objects, blur 5,
 * background mode (contrast 20, automatic cells) with automatic polarity,
 * Canny 50/150 closed by a 5x5 ellipse twice, min area 100 px, no max
 * area, objects touching the border dropped. */
RTE_API void rte_grasp_config_default(rte_grasp_config *config);

/* The grasp of one object, for a parallel-jaw gripper seen from above.
 *
 * Point: the centroid of the contour's convex hull, the shape the jaws
 * close on (a convex object's own centroid; where part of an outline is
 * lost against a table of the same shade, as a lighter's metal head, the
 * hull bridges the notches that would pull the centroid away); for an
 * object of no area, a line or a dot, the centre of its bounding
 * rectangle. Direction: the gripper closes across the object's
 * narrowest width, measured on the convex hull of its contour by rotating
 * calipers (rte_shape_calipers): the smallest extent of the object along
 * any direction. A parallel-jaw gripper closing along a direction d must
 * clear the object's whole extent along d, which is its hull's: so the
 * width is the jaw opening the object needs wherever along the jaws it
 * lies. For a convex object the jaws then touch it on both sides of the
 * centroid. For a non-convex one (an L, a C) they close on its hull: the
 * contacts are the hull's extreme points along d (an L's outer corner and
 * the tips of both arms), which may be away from the centroid, and the
 * centroid itself may lie outside the object; solidity (area / hull area)
 * lowers such objects' score. Among the hull directions whose width is
 * within 1/16 (+ 1 px) of the narrowest, the one with the best score is
 * taken (a disc's or a square's neighbours choose the side to grasp from),
 * ties to the narrowest.
 *
 * Jaws: on the line through the centroid along d, at the hull's two
 * extreme positions along d moved margin_px outwards: the gripper opens
 * to opening_q8 = width + 2 margin and its centre is the jaws' midpoint.
 *
 * Clearance: along that line beyond each extreme position, the free room
 * (pixels of the binary image that are not object, inside the frame and
 * the workspace) up to margin_px + finger_px; the smaller side's, Q8.
 *
 * Score (Q16, 0..65536 = 0..1): the product of
 *   - solidity (area / hull area);
 *   - width: 1 when gripper_min_px <= width and opening <= gripper_max_px;
 *     falling linearly to 0 as the margin is used up (width from
 *     gripper_max_px - 2 margin to gripper_max_px); 0 when the width is
 *     below gripper_min_px or above gripper_max_px;
 *   - clearance / (margin_px + finger_px) (1 when that sum is 0).
 * A score of 0: the gripper cannot take it (too wide or narrow, no room for
 * a finger, no area). */
typedef struct rte_grasp_object {
    /* The point (Q8 px), the closing direction (degrees Q16 within
     * (-90, 90], image coordinates, y down: positive turns clockwise on
     * screen), the narrowest width and the jaw opening (Q8 px). */
    int32_t x_q8, y_q8;
    int32_t angle_q16;
    int32_t width_q8;
    int32_t opening_q8;
    /* the opened jaws' faces on the closing line: [0] behind, [1] ahead along angle_q16 */
    int32_t jaws_q8[2][2];
    int32_t clearance_q8; /* free room beyond the tighter jaw, up to margin + finger */
    int32_t score_q16;    /* graspability, 0..65536 */
    int32_t contour;      /* index into rte_grasp_result.contours */
    int32_t touches_border;
    rte_shape_info info; /* area, box, class, solidity, ... */
} rte_grasp_object;

/* Nanoseconds spent per stage of the last frame (CLOCK_MONOTONIC). */
typedef struct rte_grasp_timing {
    int64_t blur_ns, binarize_ns, contours_ns, split_ns, features_ns, total_ns;
} rte_grasp_timing;

/* Filled by rte_grasp_process; the pointers refer to the context's storage
 * and stay valid until the next call or rte_grasp_destroy. */
typedef struct rte_grasp_result {
    const rte_grasp_object *objects; /* best score first; equal scores largest first */
    int32_t n_objects;
    bool truncated;               /* objects, contours or points were dropped for room */
    int32_t split_parts;          /* objects the split added (parts beyond the first) */
    int32_t dropped_objects;      /* objects that passed the filters but exceeded max_objects */
    int32_t dropped_contours;     /* contours beyond max_contours / max_points */
    int32_t threshold;            /* the threshold used (background mode: on |frame - table|;
                                   * -1 in canny-close mode) */
    rte_grasp_polarity polarity;  /* DARK or BRIGHT as applied (AUTO resolved; BRIGHT for
                                  * canny-close, where the closed edges are the objects;
                                  * AUTO in background mode: both) */
    const rte_contours *contours; /* the external contours of the frame */
    const rte_image_u8 *binary;   /* the binary image the contours came from */
    rte_grasp_timing timing;
} rte_grasp_result;

typedef struct rte_grasp_ctx rte_grasp_ctx;

/* Bytes the context needs for a configuration, everything included
 * (0 when the configuration is invalid). */
RTE_API size_t rte_grasp_memory_size(const rte_grasp_config *config);

/* Places the context in caller memory of at least rte_grasp_memory_size()
 * bytes (any alignment): nothing is allocated. The memory must outlive the
 * context; rte_grasp_destroy() is not needed (and does nothing) for it.
 * RTE_ERR_ARGUMENT for a field out of range, RTE_ERR_NO_MEMORY when
 * `bytes` is too small. */
RTE_API rte_status rte_grasp_init(const rte_grasp_config *config, void *memory, size_t bytes,
                                  rte_grasp_ctx **ctx);

/* The same in one block from malloc (the only allocation of the grasp
 * path, at start-up); rte_grasp_destroy() frees it. */
RTE_API rte_status rte_grasp_create(const rte_grasp_config *config, rte_grasp_ctx **ctx);
RTE_API void rte_grasp_destroy(rte_grasp_ctx *ctx);

/* Checks and applies new parameters (RTE_ERR_ARGUMENT leaves the old ones). */
RTE_API rte_status rte_grasp_set_params(rte_grasp_ctx *ctx, const rte_grasp_params *params);
RTE_API rte_status rte_grasp_get_params(const rte_grasp_ctx *ctx, rte_grasp_params *params);

/* One frame, at most max_width x max_height (RTE_ERR_SIZE otherwise). */
RTE_API rte_status rte_grasp_process(rte_grasp_ctx *ctx, const rte_image_u8 *gray,
                                     rte_grasp_result *out);

/* The same with the frame's colour: cb and cr are its chroma planes at
 * half size, ((width + 1) / 2) x ((height + 1) / 2) (rte_frame_chroma_half
 * makes them from any colour frame). With params.chroma in background mode
 * the table's colour is estimated as its grey is, colour differences
 * count as contrast and cast shadows are dropped (params.chroma);
 * otherwise they are not read. cb and cr NULL: as
 * rte_grasp_process. */
RTE_API rte_status rte_grasp_process_chroma(rte_grasp_ctx *ctx, const rte_image_u8 *gray,
                                            const rte_image_u8 *cb, const rte_image_u8 *cr,
                                            rte_grasp_result *out);

/* Lower-case name of a shape class ("circle", "rectangle", ...). */
RTE_API const char *rte_grasp_shape_name(rte_shape_class shape);

#ifdef __cplusplus
}
#endif
#endif
