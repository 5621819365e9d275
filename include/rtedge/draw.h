/* Drawing on BGR images for overlays and debug renders: lines, polylines,
 * circles, filled dots and text in a built-in 5x7 bitmap font. Integer
 * only, no allocation; everything is clipped to the image (any coordinate
 * is accepted, nothing is written outside width x height). Used by the
 * rtedge tool (shapes, grasp, lanes) and the daemon's debug renders. */
#ifndef RTEDGE_DRAW_H
#define RTEDGE_DRAW_H

#include <stdint.h>

#include "rtedge/contours.h" /* rte_point */
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rte_draw_color {
    uint8_t b, g, r;
} rte_draw_color;

/* The font: glyphs are 5x7 pixels in a 6x9 cell (one column and two rows
 * of spacing), scaled by an integer factor. Lower case is drawn as upper
 * case; characters without a glyph are drawn as blanks. */
#define RTE_DRAW_GLYPH_W 5
#define RTE_DRAW_GLYPH_H 7
#define RTE_DRAW_CELL_W 6
#define RTE_DRAW_CELL_H 9

/* thickness >= 1: a square brush of that many pixels, centred on the line
 * (thickness 1 is a 1-pixel Bresenham line). RTE_ERR_ARGUMENT on a bad image
 * or thickness outside 1..64. */
RTE_API rte_status rte_draw_line(rte_image_u8c3 *img, int32_t x0, int32_t y0, int32_t x1,
                                 int32_t y1, rte_draw_color color, int32_t thickness);

/* n vertices; closed != 0 joins the last to the first. */
RTE_API rte_status rte_draw_polyline(rte_image_u8c3 *img, const rte_point *pts, int32_t n,
                                     int closed, rte_draw_color color, int32_t thickness);

/* Circle outline of radius r >= 0 (midpoint algorithm). */
RTE_API rte_status rte_draw_circle(rte_image_u8c3 *img, int32_t cx, int32_t cy, int32_t r,
                                   rte_draw_color color, int32_t thickness);

/* Filled disc of radius r >= 0: every pixel with dx^2 + dy^2 <= r^2 + r. */
RTE_API rte_status rte_draw_dot(rte_image_u8c3 *img, int32_t cx, int32_t cy, int32_t r,
                                rte_draw_color color);

/* Text with its top-left corner at (x, y); scale 1..16. Returns RTE_OK. */
RTE_API rte_status rte_draw_text(rte_image_u8c3 *img, int32_t x, int32_t y, const char *text,
                                 rte_draw_color color, int32_t scale);

/* Width and height in pixels of `text` at `scale`. */
RTE_API void rte_draw_text_size(const char *text, int32_t scale, int32_t *width, int32_t *height);

#ifdef __cplusplus
}
#endif
#endif
