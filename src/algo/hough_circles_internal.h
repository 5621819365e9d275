/* Hough circles (internal): what the votes (hough_circles.c) and the
 * radius and refinement step (hough_circles_radius.c) share. */
#ifndef RTEDGE_HOUGH_CIRCLES_INTERNAL_H
#define RTEDGE_HOUGH_CIRCLES_INTERNAL_H

#include <stdint.h>

#include "rtedge/hough.h"

typedef struct circle_geom {
    int32_t acols, arows, min_r, max_r, nbins, window;
} circle_geom;

/* Edge pixels are listed in raster order (packed y << 16 | x) with, for
 * each row, where every BLOCK-pixel block of columns starts, so the scans
 * around a centre go straight to the pixels near it. */
#define BLOCK 16
static inline int32_t blocks_of(int32_t w) { return (w + BLOCK - 1) / BLOCK + 1; }

/* Radius bins without a square root per pixel: floor(sqrt(d2)) - min_r * 16
 * for d2 in [rmin2, rmax2] is the last bin k with sq[k] <= d2. A coarse table
 * gives the bin at the start of each 2^shift-wide range of d2 (at most
 * RADIUS_COARSE entries), and a few steps up find it (the integer Newton
 * square root, with its divisions, took a third of the transform). */
#define RADIUS_COARSE 4096
typedef struct radius_table {
    int64_t *sq;     /* sq[k] = (min_r * 16 + k)^2 for k <= nbins (sq[nbins] stops the steps) */
    int32_t *coarse; /* the bin of rmin2 + (i << shift) */
    /* reach[k + max_r + 1], for the row k pixels below the centre's pixel
     * row: how far (1/16 pixel) from the centre's x a pixel of that row
     * may lie within max_r of any centre in that pixel (-1: none) */
    int32_t *reach;
    int64_t rmin2;
    int32_t shift;
} radius_table;

/* Entries of rte_circle_radius's pairs. */
static inline size_t radius_pairs(const circle_geom *g) { return 2 * (size_t)g->nbins + 2; }

/* Entries of radius_table.reach. */
static inline size_t radius_reach_rows(const circle_geom *g) { return 2 * (size_t)g->max_r + 3; }

/* The tables of g's radii (t->sq, t->coarse and t->reach allocated by the
 * caller: nbins + 1, RADIUS_COARSE and radius_reach_rows entries). */
void rte_circle_radius_table_init(radius_table *t, const circle_geom *g);

/* Step 3's bins for the pixels around centres at one position within
 * their pixel (fx, fy in 1/16 pixel; with an integer dp, every centre's):
 * bin2[(ry + max_r + 1) * cols + rx + half_w] is twice the radius bin of
 * the pixel rx columns right and ry rows below the centre's pixel, or
 * 2 nbins (out of range). It covers the rows within max_r + 1 and the
 * columns of the blocks a row's scan visits (ring_window's: up to
 * max_r + BLOCK columns away). One lookup a pixel instead
 * of a distance and a search of the bins: half of step 3's time. */
typedef struct radius_offsets {
    int16_t *bin2;
    int32_t cols, half_w, fx, fy;
} radius_offsets;

/* The table's entries for g (0: too many, or bins beyond int16; the
 * centres are scanned without it), at most RADIUS_OFFSETS_MAX. */
#define RADIUS_OFFSETS_MAX (1 << 16)
size_t rte_circle_radius_offsets_size(const circle_geom *g);

/* Fills o (o->bin2 of rte_circle_radius_offsets_size entries allocated by
 * the caller) for centres at (fx, fy) within their pixel. */
void rte_circle_radius_offsets_init(radius_offsets *o, const circle_geom *g, const radius_table *rt,
                                    int32_t fx, int32_t fy);

/* Step 3 for one centre (cx, cy in 1/16 pixel) over the edge pixels pts
 * with their row blocks blk (nblk a row): the support, and the radius in
 * *radius_q4. pairs has radius_pairs(g) entries, all zero, and is left so.
 * With o not NULL (made for the centre's position in its pixel), the bins
 * come from it; else from the distances. */
int32_t rte_circle_radius(const uint32_t *pts, const int32_t *blk, int32_t nblk, int32_t h,
                          const circle_geom *g, const radius_table *rt, const radius_offsets *o,
                          int32_t cx, int32_t cy, int32_t *pairs, int32_t *radius_q4);

/* Step 3b's largest move of a centre along each axis, 1/16 pixel: 2 dp. */
static inline int32_t circle_refine_limit(int32_t dp_q8) { return (dp_q8 + 4) / 8; }

/* What step 3b reads: the edge pixels with their row blocks (as for
 * rte_circle_radius), the image height, the gradient and dp. */
typedef struct circle_pixels {
    const uint32_t *pts;
    const int32_t *blk;
    int32_t nblk, h, dp_q8;
    const rte_image_s16 *dx, *dy;
} circle_pixels;

/* Step 3b: the centre (*cx, *cy) and radius *r_q4 refined to where the
 * gradient lines of the circle's edge pixels meet (moving the centre at
 * most circle_refine_limit along each axis). */
void rte_circle_refine(const circle_pixels *cp, int32_t *cx, int32_t *cy, int32_t *r_q4);

#endif
