/* Hough transforms on a binary edge map (non-zero = edge): standard lines
 * (cv::HoughLines), line segments (cv::HoughLinesP) and circles
 * (cv::HoughCircles, HOUGH_GRADIENT).
 *
 * Everything per frame is integer arithmetic, so results are identical on
 * every platform and build. Angles and the rho resolution are turned into
 * fixed-point trig tables once, by rte_hough_config_init() (the only place
 * that uses floating point). Working memory comes from the caller's arena,
 * sized at start-up with the *_scratch_size() functions; outputs go into
 * caller arrays of a fixed capacity, with a flag when more would have been
 * found. Deviations from OpenCV are listed in docs/hough.md. */
#ifndef RTEDGE_HOUGH_H
#define RTEDGE_HOUGH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most angle bins a configuration holds: theta resolution down to pi/2048. */
#define RTE_HOUGH_MAX_ANGLES 2048

/* The (rho, theta) quantisation shared by lines and segments. Fill it with
 * rte_hough_config_init(); the fields are read-only afterwards. */
typedef struct rte_hough_config {
    int32_t max_width, max_height; /* largest edge map the scratch is sized for */
    int32_t num_angles;            /* theta bins: min_theta + n * theta, n < num_angles */
    int32_t trig_shift;            /* fraction bits of rho_cos / rho_sin */
    int32_t inv_rho_q16;           /* 65536 / rho, for the number of rho bins */
    int32_t rho_q16;               /* rho resolution in 1/65536 pixel */
    int32_t theta0_q16;            /* min_theta in 1/65536 radian */
    int32_t theta_q16;             /* theta resolution in 1/65536 radian */
    /* cos, sin of each angle divided by rho, times 2^trig_shift: a point's
     * rho bin is (x * rho_cos + y * rho_sin) >> trig_shift, rounded. */
    int32_t rho_cos[RTE_HOUGH_MAX_ANGLES];
    int32_t rho_sin[RTE_HOUGH_MAX_ANGLES];
    /* cos, sin of each angle times 2^16 (unit vectors, for walking lines) */
    int32_t unit_cos[RTE_HOUGH_MAX_ANGLES];
    int32_t unit_sin[RTE_HOUGH_MAX_ANGLES];
    /* The float parameters, for the conversion helpers. */
    double rho, theta, min_theta;
} rte_hough_config;

/* Configures cv::HoughLines(rho, theta, min_theta, max_theta) quantisation
 * for edge maps up to max_width x max_height. The number of angles is
 * round((max_theta - min_theta) / theta) as in OpenCV (at least 1, at most
 * RTE_HOUGH_MAX_ANGLES). For segments use min_theta = 0, max_theta = pi.
 * RTE_ERR_ARGUMENT when rho <= 0, theta <= 0, max_theta < min_theta or the
 * sizes are out of range. */
RTE_API rte_status rte_hough_config_init(rte_hough_config *cfg, int32_t max_width,
                                         int32_t max_height, double rho, double theta,
                                         double min_theta, double max_theta);

/* ---- standard lines ---- */

/* One line x*cos(theta) + y*sin(theta) = rho. rho = rho_bin * rho resolution
 * (negative rho_bin for lines whose normal points up-left), theta = min_theta
 * + theta_bin * theta resolution. */
typedef struct rte_hough_line {
    int32_t rho_bin;
    int32_t theta_bin;
    int32_t votes;
} rte_hough_line;

/* Conversion helpers (configuration-time file; floating point). */
RTE_API double rte_hough_line_rho(const rte_hough_config *cfg, const rte_hough_line *line);
RTE_API double rte_hough_line_theta(const rte_hough_config *cfg, const rte_hough_line *line);
/* Integer forms: rho in 1/65536 pixel, theta in 1/65536 radian. */
RTE_API int64_t rte_hough_line_rho_q16(const rte_hough_config *cfg, const rte_hough_line *line);
RTE_API int64_t rte_hough_line_theta_q16(const rte_hough_config *cfg, const rte_hough_line *line);

RTE_API size_t rte_hough_lines_scratch_size(const rte_hough_config *cfg, int32_t max_lines);

/* cv::HoughLines: every edge pixel votes for the lines through it; an
 * accumulator cell is a line when its votes exceed `threshold` and it is a
 * local maximum (OpenCV's rule: > the lower neighbours, >= the upper ones in
 * both rho and theta). Lines are sorted by votes (most first), then theta
 * bin, then rho bin. At most `max_lines` are written to `lines`; *count gets
 * how many, *truncated is set when more lines qualified (cleared otherwise).
 * The edge map may be smaller than the configured maximum. */
RTE_API rte_status rte_hough_lines(const rte_hough_config *cfg, const rte_image_u8 *edges,
                                   int32_t threshold, rte_arena *arena, rte_hough_line *lines,
                                   int32_t max_lines, int32_t *count, bool *truncated);

/* ---- segments ---- */

typedef struct rte_hough_segment {
    int32_t x0, y0, x1, y1;
} rte_hough_segment;

typedef struct rte_hough_segments_params {
    int32_t threshold;  /* accumulator votes a line needs (cv::HoughLinesP threshold) */
    int32_t min_length; /* shortest segment kept, Euclidean length in pixels */
    int32_t max_gap;    /* longest run of missing pixels bridged along a segment */
    uint32_t seed;      /* point-order seed; 0: RTE_HOUGH_SEGMENTS_SEED */
} rte_hough_segments_params;

/* The default seed of the point-order shuffle (xorshift32). The order, and
 * so the segments, depend only on the seed: every run on every platform
 * with the same seed gives the same segments. */
#define RTE_HOUGH_SEGMENTS_SEED 0x2545F491u

/* 0 for a configuration segments refuse: accumulator cells are at most 16
 * bits and hold their count plus 32769 - threshold, so
 * max(max_width, max_height) * (rho * sqrt 2 + 2), the most pixels one
 * cell can count, must stay below 32768 unless the whole map has fewer
 * pixels (rho 1: sides up to 10922). rte_hough_segments returns
 * RTE_ERR_ARGUMENT for such a configuration, and no segments (RTE_OK) for
 * a threshold above that bound, which no cell can reach. */
RTE_API size_t rte_hough_segments_scratch_size(const rte_hough_config *cfg);

/* cv::HoughLinesP (progressive probabilistic Hough) with the fixes listed in
 * docs/hough.md: points are visited in a fixed pseudo-random order; once a
 * cell reaches the threshold the line is followed both ways, refitted to the
 * pixels found and followed again along the refitted line, and the run of
 * edge pixels across it (up to two pixels either side) is consumed, so one
 * straight edge gives one segment. At most `max_segments`
 * are written; *truncated is set when the search stopped because the output
 * was full. */
RTE_API rte_status rte_hough_segments(const rte_hough_config *cfg, const rte_image_u8 *edges,
                                      const rte_hough_segments_params *params, rte_arena *arena,
                                      rte_hough_segment *segments, int32_t max_segments,
                                      int32_t *count, bool *truncated);

/* ---- circles ---- */

typedef struct rte_hough_circle {
    int32_t x_q4, y_q4; /* centre in 1/16 pixel */
    int32_t r_q4;       /* radius in 1/16 pixel */
    int32_t votes;      /* edge pixels on the circle (OpenCV's accumulator value) */
} rte_hough_circle;

typedef struct rte_hough_circles_params {
    int32_t dp_q8;         /* inverse accumulator resolution dp, times 256 (>= 256) */
    int32_t min_dist;      /* smallest distance between centres, pixels (>= 1) */
    int32_t acc_threshold; /* param2: votes a centre needs (>= 1) */
    int32_t min_radius;    /* pixels; < 0 is taken as 0 */
    int32_t max_radius;    /* pixels; <= 0: max(width, height); <= min_radius: min_radius + 2 */
    int32_t max_centres;   /* budget: most candidate centres given a radius (the strongest);
                              0: RTE_HOUGH_CIRCLES_MAX_CENTRES */
    int32_t max_votes;     /* budget: most accumulator votes, 2 (max_r - min_r + 1) per voting
                              edge pixel, in raster order; 0: RTE_HOUGH_CIRCLES_VOTES_PER_PIXEL
                              per image pixel */
} rte_hough_circles_params;

/* The default budget of candidate centres (max_centres 0). */
#define RTE_HOUGH_CIRCLES_MAX_CENTRES 512
/* The default vote budget (max_votes 0), per pixel of the image. */
#define RTE_HOUGH_CIRCLES_VOTES_PER_PIXEL 8

RTE_API size_t rte_hough_circles_scratch_size(int32_t max_width, int32_t max_height,
                                              const rte_hough_circles_params *params);

/* cv::HoughCircles(HOUGH_GRADIENT). The caller supplies what OpenCV computes
 * inside: `edges` = Canny(max(1, param1 / 2), param1) of the grey image and
 * `dx`, `dy` = its 3x3 Sobel derivatives with BORDER_REPLICATE, all of one
 * size. Each edge pixel votes along its gradient for centres between the
 * radii; centres above acc_threshold that are local maxima get a radius from
 * a histogram of edge distances, then the centre is refined to where the
 * gradient lines of the circle's edge pixels meet (least squares, within 2 dp
 * of the accumulator cell) and the radius to their mean distance; circles
 * are sorted by support and any centre closer than min_dist to a stronger
 * one is dropped. With more candidate centres than the budget
 * (params->max_centres), only the strongest (most votes, then raster order)
 * get a radius, and *truncated is set, as when more than max_circles
 * qualify. Only the edge pixels within the vote budget (params->max_votes,
 * the first in raster order) vote; all count in the radius and its support;
 * *truncated is set when an edge pixel did not vote. */
RTE_API rte_status rte_hough_circles(const rte_image_u8 *edges, const rte_image_s16 *dx,
                                     const rte_image_s16 *dy,
                                     const rte_hough_circles_params *params, rte_arena *arena,
                                     rte_hough_circle *circles, int32_t max_circles, int32_t *count,
                                     bool *truncated);

#ifdef __cplusplus
}
#endif
#endif
