/* The lane context, shared by lane_config.c (creation, floating point) and
 * lane.c (per frame, integer only). */
#ifndef RTEDGE_LANE_INTERNAL_H
#define RTEDGE_LANE_INTERNAL_H

#include "rtedge/arena.h"
#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/hough.h"
#include "rtedge/lane.h"

/* Tracker state of one lane: positions at the bottom row and the ROI top in
 * 1/256 pixel, their velocities in 1/256 pixel per frame. */
typedef struct lane_track {
    bool valid;
    int32_t lost;
    int32_t x_bottom_q8, x_top_q8;
    int32_t v_bottom_q8, v_top_q8;
} lane_track;

/* One fitted line x = x_mid + slope * (y - y_mid), slope in 1/65536. */
typedef struct lane_line {
    int64_t x_mid_q8;
    int64_t slope_q16;
    int32_t y_mid;
} lane_line;

struct rte_lane_context {
    rte_lane_config cfg;
    rte_lane_params params;
    bool roi_dirty;           /* rebuild the mask on the next frame */
    int32_t roi_width, roi_height; /* the frame size the mask was built for */
    rte_vertex roi_px[RTE_LANE_MAX_ROI_VERTICES];
    int32_t crop_x0, crop_y0, crop_x1, crop_y1; /* the ROI's bounding box, clipped */
    rte_gaussian_kernel blur;
    rte_hough_config *hough;
    rte_canny_params canny;
    /* Images of max_width x max_height */
    rte_image_u8 gray;        /* grey when the frame is not grey itself */
    rte_image_u8 cue;         /* grey with the colour cue */
    rte_image_u8 blurred;
    rte_image_u8 edges;
    rte_image_u8 mask;        /* ROI polygon, crop coordinates */
    /* Segments */
    rte_hough_segment *raw;
    rte_lane_segment *segments;
    int32_t *order;           /* per-side index lists and weighted-median work */
    int64_t *keys;
    rte_arena arena;
    lane_track track[2];
    void *memory;
};

#endif
