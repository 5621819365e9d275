/* Debug overlays: the lane and grasp paths' results drawn on a BGR canvas
 * that shows a frame at a scale (the daemon's debug stream: a reduced
 * frame; the rtedge tool: the image itself). Integer only, no allocation,
 * everything clipped to the canvas (drawn with draw.h). */
#ifndef RTEDGE_OVERLAY_H
#define RTEDGE_OVERLAY_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/draw.h"
#include "rtedge/grasp.h"
#include "rtedge/lane.h"

/* What an overlay shows, as bits. */
typedef enum rte_overlay_layer {
    RTE_OVERLAY_ROI = 1 << 0,      /* the lane ROI polygon */
    RTE_OVERLAY_EDGES = 1 << 1,    /* the Canny edges the Hough search saw */
    RTE_OVERLAY_SEGMENTS = 1 << 2, /* Hough segments: used green, others grey */
    RTE_OVERLAY_LANES = 1 << 3,    /* the lanes' polylines: left blue, right red */
    RTE_OVERLAY_CONTOURS = 1 << 4, /* the objects' outlines */
    RTE_OVERLAY_GRASP = 1 << 5,    /* grasp point, closing line, opened jaws */
    RTE_OVERLAY_LABELS = 1 << 6,   /* object numbers, shapes, scores (%); lane offset */
} rte_overlay_layer;
#define RTE_OVERLAY_ALL 0x7f

/* The layer bit of a name of len bytes: roi, edges, segments, lanes,
 * contours, grasp, labels, or all (every bit); -1 for another name. */
RTE_API int32_t rte_overlay_layer_named(const char *name, size_t len);

/* A canvas showing a frame: canvas pixel (x, y) is frame pixel
 * (x, y) * 65536 / scale_q16. */
typedef struct rte_overlay {
    rte_image_u8c3 canvas;
    int32_t scale_q16; /* 65536: the frame's own size */
} rte_overlay;

/* The canvas size for a frame at a scale (at least 1 x 1). */
RTE_API void rte_overlay_size(int32_t frame_width, int32_t frame_height, int32_t scale_q16,
                              int32_t *width, int32_t *height);
/* Fills the canvas with the grey frame, reduced by nearest neighbour. */
RTE_API void rte_overlay_fill_gray(rte_overlay *o, const rte_image_u8 *gray);

RTE_API void rte_overlay_roi(rte_overlay *o, const rte_point *roi, int32_t n);
/* The lane result's layers (edges, segments, lanes, labels). */
RTE_API void rte_overlay_lanes(rte_overlay *o, const rte_lane_result *r, uint32_t layers);
/* The grasp result's layers (contours, grasp, labels), in reverse order:
 * object 0, the best grasp, last, on top. */
RTE_API void rte_overlay_grasp(rte_overlay *o, const rte_grasp_result *r, uint32_t layers);

/* Text on a black band, moved inside the canvas where it would leave it. */
RTE_API void rte_overlay_label(rte_image_u8c3 *canvas, int32_t x, int32_t y, const char *text,
                               rte_draw_color c);
/* Object i's colour (a palette of 8). */
RTE_API rte_draw_color rte_overlay_color(int32_t i);

#endif
