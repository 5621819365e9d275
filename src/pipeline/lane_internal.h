/* The lane context and what the lane files share: lane_config.c
 * (creation, floating point) and the per-frame files (integer only):
 * lane.c (parameters, the ROI, the stages in order, the centre),
 * lane_cue.c (colour cue, automatic Canny thresholds), lane_fit.c (the
 * robust fit of the segments), lane_refine.c (the refit on the edge
 * pixels), lane_windows.c and lane_curve.c (the curve model),
 * lane_partner.c (a side searched for from the other), lane_double.c
 * (double markings), lane_track.c (sides, gate, the trackers) and
 * lane_trace.c (the far trace). */
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
    int32_t bow_q8;    /* the curve's bow (lane_curve), smoothed */
    int32_t y_horizon; /* and its horizon row */
} lane_track;

/* One fitted line x = x_mid + slope * (y - y_mid), slope in 1/65536. */
typedef struct lane_line {
    int64_t x_mid_q8;
    int64_t slope_q16;
    int32_t y_mid;
} lane_line;

/* What lane_curve.c found beyond the line: the bow (the lane's middle
 * beside its chord, 1/256 px, positive to the right; 0 when straight),
 * the highest row the windows saw paint on, the horizon row the bow's
 * shape is drawn from and the lowest row the windows saw paint on (the
 * bottom row when there were none). */
typedef struct lane_curve {
    int64_t bow_q8;
    int32_t y_supported;
    int32_t y_horizon;
    int32_t y_lowest;
} lane_curve;

/* What the least-squares fit knows besides the segments: the rows the lane
 * spans, and a slope to lean on (the tracked lane's, as predicted for this
 * frame) with the weight of R^3 in the units of the fit's row moment, i.e.
 * as much as a marking along R rows would give: one short dash far up the
 * image then moves the lane sideways but hardly turns it, while paint along
 * the whole lane outweighs the prior. weight 0: no prior. */
typedef struct lane_fit_hint {
    int32_t y_top, y_bottom;
    int64_t slope_q16;
    int64_t weight;
    int32_t y_horizon; /* the curve model's horizon row when has_horizon */
    bool has_horizon;
} lane_fit_hint;

struct rte_lane_context {
    rte_lane_config cfg;
    rte_lane_params params;
    bool roi_dirty;                /* rebuild the mask on the next frame */
    int32_t roi_width, roi_height; /* the frame size the mask was built for */
    rte_vertex roi_px[RTE_LANE_MAX_ROI_VERTICES];
    int32_t crop_x0, crop_y0, crop_x1, crop_y1; /* the ROI's bounding box, clipped */
    rte_gaussian_kernel blur;
    rte_hough_config *hough;
    rte_canny_params canny;
    /* Images of max_width x max_height */
    rte_image_u8 gray; /* grey when the frame is not grey itself */
    rte_image_u8 cue;  /* grey with the colour cue */
    /* The crop's Cb and Cr at half resolution, for the cue of a frame whose
     * colour is chroma (NV12, YUYV, UYVY): (max_width + 1) / 2 + 1 wide,
     * (max_height + 1) / 2 + 1 high (a crop widened to even x0, y0) */
    rte_image_u8 cb, cr;
    rte_image_u8 blurred;
    rte_image_u8 edges;     /* Canny over the ROI's bounding box: the lanes are followed here */
    rte_image_u8 edges_roi; /* the same inside the ROI polygon: what the Hough search sees */
    rte_image_u8 mask;      /* ROI polygon, crop coordinates */
    /* Each mask row's span [roi_x0[y], roi_x1[y]) (max_height entries);
     * roi_spans when every row is that one run (a convex ROI) */
    int32_t *roi_x0, *roi_x1;
    bool roi_spans;
    /* Segments */
    rte_hough_segment *raw;
    rte_lane_segment *segments;
    int32_t *order;  /* per-side index lists and weighted-median work */
    int32_t *weight; /* per segment: the fits' weight (rte_lane_paint_weights) */
    int64_t *keys;
    rte_arena arena;
    lane_track track[2];
    /* The lane's width on the bottom row (1/256 px) while both sides show
     * paint near it (rte_lane_width_hold). */
    bool width_valid;
    int32_t width_q8;
    void *memory;
};

/* A frame's colour for the cue: its B,G,R rows (R,G,B when rgb is set;
 * bgr at the frame's first pixel), or, when chroma is set, the Cb and Cr
 * of the crop's chroma blocks: row 0 at cb and cr, rows chroma_stride
 * apart, Cb and Cr of block i at cb[i], cr[i], or cb[2 i], cr[2 i] when
 * interleaved (NV12, cr = cb + 1). The blocks start on the row and column
 * before the crop when odd_y, odd_x are set. */
typedef struct lane_colour {
    const uint8_t *bgr;
    int32_t bgr_stride;
    bool rgb;
    bool chroma, interleaved, odd_x, odd_y;
    const uint8_t *cb, *cr;
    int32_t chroma_stride;
} lane_colour;

/* Pixels x0..x1-1 of rows y0..y1-1 of a one-plane frame (BGR24, RGB24,
 * YUYV, UYVY; x0 even for the last two) as a frame of their own: a view. */
static inline rte_frame lane_frame_part(const rte_frame *frame, int32_t x0, int32_t y0, int32_t x1,
                                        int32_t y1)
{
    const rte_pixel_format f = frame->format;
    const size_t bytes = f == RTE_PIXEL_BGR24 || f == RTE_PIXEL_RGB24 ? 3 : 2;
    rte_frame part = *frame;
    part.width = x1 - x0;
    part.height = y1 - y0;
    part.plane[0] += (size_t)y0 * (size_t)frame->stride[0] + bytes * (size_t)x0;
    return part;
}

/* lane_cue.c: the colour cue of the crop `gray` (white or yellow paint ->
 * 255, everything else grey scaled by dim_q8 / 256; `bgr` rows hold B,G,R,
 * R,G,B when rgb is set), and the automatic Canny thresholds of a blurred
 * crop inside the ROI mask, counted by its row spans when every row is one
 * run (*low, *high unchanged when it is empty). */
void rte_lane_color_cue(const rte_lane_params *p, const rte_image_u8 *gray, const uint8_t *bgr,
                        int32_t bgr_stride, bool rgb, rte_image_u8 *dst);
/* The same from the chroma of colour->chroma (lane_cue_rows.h). */
void rte_lane_chroma_cue(const rte_lane_params *p, const rte_image_u8 *gray,
                         const lane_colour *colour, rte_image_u8 *dst);
/* *colour set to the chroma of the crop (ctx->crop_*, set by the ROI) of
 * an NV12 frame (its own UV plane), or of a YUYV or UYVY frame (averaged
 * over each block's two rows into ctx->cb and ctx->cr). */
rte_status rte_lane_frame_chroma(rte_lane_context *ctx, const rte_frame *frame,
                                 lane_colour *colour);
/* The ROI mask's span on each row into ctx->roi_x0, roi_x1, and
 * ctx->roi_spans set when each row is that one run (a convex ROI): its rows
 * are then counted and kept without reading the mask on every frame. */
void rte_lane_roi_spans(rte_lane_context *ctx, const rte_image_u8 *mask);
/* inside = edges within the ROI (the mask, or its spans), 0 elsewhere. */
rte_status rte_lane_keep_roi(const rte_lane_context *ctx, const rte_image_u8 *edges,
                             const rte_image_u8 *mask, rte_image_u8 *inside);
void rte_lane_thresholds(rte_lane_context *ctx, const rte_image_u8 *img, const rte_image_u8 *mask,
                         int32_t *low, int32_t *high);
/* The share of the ROI (the grey crop's pixels inside `mask`, same size)
 * washed out by glare (LANE_SATURATED or brighter), in permille. */
int32_t rte_lane_glare_permille(const rte_lane_context *ctx, const rte_image_u8 *gray_crop,
                                const rte_image_u8 *mask);

/* lane_track.c: sorts the Hough segments (ctx->segments[0..count)) into
 * sides by slope, position and the gate around the tracked lanes, filling
 * members[side][0..n[side]) and marking the rejected ones. */
void rte_lane_classify(rte_lane_context *ctx, int32_t count, int32_t width, int32_t y_bottom,
                       int32_t y_top, int32_t *members[2], int32_t n[2]);
/* The segments of `side` that the gate alone rejected, into members[];
 * returns how many. */
int32_t rte_lane_gated_out(const rte_lane_context *ctx, int side, int32_t count, int32_t *members);
/* The fit's hint for a side: its rows, and the tracked lane's slope as
 * predicted for this frame as the prior (none when not tracked). */
lane_fit_hint rte_lane_track_hint(const lane_track *t, int32_t y_top, int32_t y_bottom);
/* The tracked lane as predicted for this frame (t->valid), its rows set. */
rte_lane rte_lane_track_predict(const lane_track *t, int32_t y_top, int32_t y_bottom);
/* Moves the side's tracker by this frame's line (seen) or holds it, and
 * fills the lane of the result from it (out->y_bottom and y_top set). A
 * fresh line (found outside the gate) restarts the tracker from it. */
void rte_lane_track_update(rte_lane_context *ctx, int side, bool seen, bool fresh,
                           const lane_line *line, const lane_curve *curve, int64_t support,
                           rte_lane *out);

/* lane_track.c: the lane's width on the bottom row, tracked while both
 * sides show paint in the lane's lowest quarter; a side seen only farther
 * up (a dashed line between two dashes) then has its bottom end put that
 * width from the other side's, its top end kept. */
void rte_lane_width_hold(rte_lane_context *ctx, const bool seen[2], lane_line line[2],
                         const lane_curve curve[2], int32_t y_top, int32_t y_bottom);
/* lane_fit.c: the robust fit of one side over the segments members[0..n),
 * reordered with its *inliers inliers first. Returns their supporting
 * length. The segments' `use` is left as it is: rte_lane_mark_side marks
 * the inliers `use` and the rest outliers once the fit is taken. */
int64_t rte_lane_fit_side(rte_lane_context *ctx, int32_t *members, int32_t n,
                          const lane_fit_hint *hint, lane_line *line, int32_t *inliers);
void rte_lane_mark_side(rte_lane_context *ctx, const int32_t *members, int32_t n, int32_t inliers,
                        rte_lane_segment_use use);

/* The edge pixels of columns xa..xb of one row that run along a line. */
typedef struct band_pixels {
    int64_t n, sum_x;    /* how many, and the sum of their x */
    int64_t first, last; /* the outermost */
} band_pixels;

/* The images the pixel searches read: the edge map, the image the edges
 * came from (grey or the colour cue) and grey, all the crop of the ROI's
 * bounding box at (cx0, cy0); tol is the search band's half-width on the
 * bottom row. The edge map is not masked by the ROI polygon: the polygon
 * is where segments are searched, and a lane found from them is followed
 * anywhere in the crop (on a bend the markings leave the trapezoid). */
typedef struct lane_maps {
    const rte_image_u8 *edges, *src, *gray;
    int32_t cx0, cy0;
    int64_t tol;
} lane_maps;

/* lane_fit.c: each segment's weight in the fits (ctx->weight[0..count)):
 * its length, scaled by how much of it borders paint (a bright stripe of
 * a marking's width, twice the search band at its row, beside it) from a
 * ninth (none) to one (all). */
void rte_lane_paint_weights(rte_lane_context *ctx, const lane_maps *maps, const lane_fit_hint *rows,
                            int32_t count);

/* lane_refine.c: the half-width of the band searched around a lane at row
 * y (tol on the bottom row, narrowing in perspective), and the edge pixels
 * of columns xa..xb of row y of `edges` that run along slope_q16 (x per
 * row; edges crossing it do not count). */
int64_t rte_lane_band_px(const lane_fit_hint *h, int64_t tol, int32_t y);
band_pixels rte_lane_band_row(const rte_image_u8 *edges, int32_t y, int64_t xa, int64_t xb,
                              int64_t slope_q16);

/* lane_refine.c: the segment fit refined on the edge pixels along it
 * (`edges` is the crop at (cx0, cy0); `tol` the band's half-width on the
 * bottom row). */
void rte_lane_refine_on_edges(const rte_image_u8 *edges, int32_t cx0, int32_t cy0,
                              const lane_fit_hint *hint, int64_t tol, lane_line *line);

/* lane_refine.c: whether row y of the maps holds paint between the edge
 * pixels at columns first and last (crop coordinates), and the marking
 * found along a lane (its mean offset from it, within band_scale times the
 * refit's band; returns the rows that show it). */
bool rte_lane_is_ridge(const lane_maps *maps, int32_t y, int64_t first, int64_t last);
/* lane_refine.c: the edge pixels of columns xa..xb (crop coordinates) of
 * frame row y that run along slope_q16, when they mark paint: the columns
 * inside the map, two edges at least with paint between them
 * (rte_lane_is_ridge), or the two inner edges of a double line. */
bool rte_lane_paint_row(const lane_maps *maps, int32_t y, int64_t xa, int64_t xb, int64_t slope_q16,
                        band_pixels *px);
/* lane_refine.c: the marking nearest column x of frame row y, within
 * `reach` of it (see lane_refine.c); false when there is none. Its edge
 * pixels run along slope_q16, or have any direction for LANE_SLOPE_ANY. */
#define LANE_SLOPE_ANY INT64_MIN
bool rte_lane_paint_near(const lane_maps *maps, int32_t y, int64_t x, int64_t reach,
                         int64_t slope_q16, band_pixels *px);
/* lane_refine.c: whether row y shows paint along `lane` (within
 * band_scale times the refit's band around it, its edges along the lane's
 * direction there), into *px; *lane_x_q8 gets the lane's x on that row. */
bool rte_lane_paint_along(const lane_maps *maps, const lane_fit_hint *hint, const rte_lane *lane,
                          int32_t band_scale, int32_t y, int64_t *lane_x_q8, band_pixels *px);
int32_t rte_lane_find_marking(const lane_maps *maps, const lane_fit_hint *hint,
                              const rte_lane *pred, int32_t band_scale, int64_t *offset_q8);

/* lane_curve.c: the curves of both lanes, whose straight fits are line[]
 * (seen[side]: the side was fitted this frame), with one bend shared by
 * the two (see lane_curve.c); a curved side's line becomes its chord. */
void rte_lane_curves_fit(const lane_maps *maps, const lane_fit_hint *hint, const bool seen[2],
                         lane_line line[2], lane_curve curve[2]);

/* lane_trace.c: a found lane's marking followed beyond where its curve
 * leaves it, into lane->far_count and its points (see rte_lane). */
void rte_lane_trace_far(const lane_maps *maps, const lane_fit_hint *rows, rte_lane *lane);

/* lane_partner.c: with only seen_side's lane found (`seen`, its curve
 * included), the other side's marking on the lanes of the same road that
 * meet it on the horizon, the one with paint on most rows into *found
 * (its bend the seen lane's); returns those rows (0: none). width: the
 * frame's. */
int32_t rte_lane_partner(const lane_maps *maps, const lane_fit_hint *rows, int seen_side,
                         const rte_lane *seen, int32_t width, rte_lane *found);
/* lane_partner.c: the fit stage's search for a side from the other (see
 * lane_partner.c): seen[], line[], curve[], support[] and fresh[] of the
 * side found are set. */
void rte_lane_fit_partner(rte_lane_context *ctx, const lane_maps *maps, const lane_fit_hint *rows,
                          int32_t glare_permille, int32_t w, bool seen[2], lane_line line[2],
                          lane_curve curve[2], int64_t support[2], bool fresh[2]);
/* lane_double.c: a side whose marking has a twin beside it (a double
 * centre line) moved onto the centre between the two (both sides seen). */
void rte_lane_double_centre(const lane_maps *maps, const lane_fit_hint *hint, const bool seen[2],
                            lane_line line[2], const lane_curve curve[2]);

#endif
