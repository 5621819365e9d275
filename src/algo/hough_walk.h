/* The line walk of the segment search (hough_segments.c): stepping along
 * a line over the edge mask, collecting the runs of edge pixels it meets,
 * and the integer principal-axis refit of what it found. Internal. */
#ifndef RTEDGE_ALGO_HOUGH_WALK_H
#define RTEDGE_ALGO_HOUGH_WALK_H

#include <stdbool.h>
#include <stdint.h>

/* Mask states of a pixel. */
enum { PX_NONE = 0, PX_EDGE = 1, PX_VOTED = 2, PX_USED = 3 };
/* PX_USED: consumed by a reported segment. A later walk crosses such pixels
 * without counting a gap (OpenCV counts them as missing, which cuts lines
 * where they cross), but they neither extend nor fit the new segment. */
static inline bool live(uint8_t m) { return m == PX_EDGE || m == PX_VOTED; }

/* How far across the line a continuing run of edge pixels is consumed
 * (one pixel either side always). */
#define CONSUME_REACH 2

/* Fitted or quantised line: a point on it (Q16) and a unit direction (Q16). */
typedef struct line_q16 {
    int64_t px, py;
    int32_t ux, uy;
} line_q16;

typedef struct walk_ctx {
    uint8_t *mask;
    int32_t w, h, max_gap;
    uint32_t *hits; /* packed (2y << 16) | 2x: run centres in half pixels */
    int32_t nhits;
    int32_t end2[4]; /* the hits at the extreme steps (half pixels) */
    bool strict;     /* only the pixel on the line hits (walks of refitted lines) */
} walk_ctx;

/* Steps of one pixel along the major axis of the line; the minor coordinate
 * advances by a Q16 fraction. */
typedef struct stepper {
    int32_t major_x;  /* 1: x is the major axis */
    int32_t dmaj;     /* +-1 */
    int64_t dmin_q16; /* minor advance per major step */
    int32_t maj0;     /* start, major coordinate */
    int64_t min0_q16; /* start, minor coordinate (Q16) */
} stepper;

/* floor(v / 65536) for |v| < 2^47, also for negative values: shifted as a
 * non-negative number (no branch, no implementation-defined shift) */
static inline int32_t floor_q16(int64_t v)
{
    return (int32_t)((int64_t)((uint64_t)(v + ((int64_t)1 << 47)) >> 16) - ((int64_t)1 << 31));
}

/* The pixel of step k: the minor coordinate in Q16 plus a half, floored. */
static inline void stepper_at(const stepper *s, int32_t k, int32_t *x, int32_t *y)
{
    int32_t maj = s->maj0 + k * s->dmaj;
    int32_t mn = floor_q16(s->min0_q16 + (int64_t)k * s->dmin_q16 + 32768);
    *x = s->major_x ? maj : mn;
    *y = s->major_x ? mn : maj;
}

/* The stepper of line l from the pixel (start_x, start_y). */
stepper rte_hough_walk_stepper(const line_q16 *l, int32_t start_x, int32_t start_y);

/* Follows the line both ways from step 0 until more than max_gap steps in
 * a row miss; collects the hits in c (nhits, end2) and returns the extreme
 * steps walked. */
void rte_hough_walk_follow(walk_ctx *c, const stepper *s, int32_t *kmin, int32_t *kmax);

/* The hit (half pixels) projected onto the line, rounded to a pixel. */
void rte_hough_walk_project(const line_q16 *l, int32_t hx2, int32_t hy2, int32_t *x, int32_t *y);

/* Refits l to the hits' principal axis; false (l unchanged) when they
 * are too few or show no direction. */
bool rte_hough_walk_fit(const walk_ctx *c, line_q16 *l);

#endif
