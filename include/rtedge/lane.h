/* Lane detection for a forward-looking road camera, with tracking.
 *
 * Per frame: grey (and, when the frame has colour, a white/yellow cue) ->
 * crop to the region of interest's bounding box -> Gaussian blur -> Canny
 * (fixed or automatic thresholds) -> edges outside the ROI polygon cleared ->
 * Hough segments -> slope filter (left lane negative dy/dx, right positive,
 * near-horizontal rejected) -> gate around the tracked lanes -> per-side
 * robust line fit weighted by segment length -> each lane as a line from the
 * bottom row to the ROI top with a confidence -> a fixed-point tracker that
 * damps jumps and holds a lost lane as predicted for a few frames -> lane
 * centre offset and heading. Why each step is there: docs/lanes.md.
 *
 * Memory: rte_lane_create() allocates everything once for the maximum frame
 * size; rte_lane_process*() allocates nothing. Everything per frame is
 * integer arithmetic (the file builds with -mgeneral-regs-only); floating
 * point is used only in rte_lane_create() (Gaussian taps, Hough tables).
 * A context is not thread-safe; use one per camera. */
#ifndef RTEDGE_LANE_H
#define RTEDGE_LANE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/color.h"
#include "rtedge/hough.h"
#include "rtedge/image.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RTE_LANE_MAX_ROI_VERTICES 8
/* Limits of rte_lane_config (they keep the fits' 64-bit sums exact). */
#define RTE_LANE_MAX_SIDE 8192
#define RTE_LANE_MAX_SEGMENTS 65536
/* Fixed-point scale of lane coordinates and slopes: 1/256 pixel. */
#define RTE_LANE_Q 8
#define RTE_LANE_ONE (1 << RTE_LANE_Q)

typedef enum rte_lane_fit {
    RTE_LANE_FIT_LEAST_SQUARES = 0, /* weighted least squares, outliers rejected, refitted */
    RTE_LANE_FIT_THEIL_SEN = 1,     /* weighted medians of slope and intercept */
} rte_lane_fit;

typedef enum rte_lane_canny_mode {
    RTE_LANE_CANNY_FIXED = 0,  /* canny_low, canny_high */
    RTE_LANE_CANNY_MEDIAN = 1, /* median rule on the ROI's histogram (auto_sigma_permille) */
    RTE_LANE_CANNY_OTSU = 2,   /* Otsu rule on the ROI's histogram */
} rte_lane_canny_mode;

/* Everything that may change while running: rte_lane_set_params() copies it
 * into a live context without allocating (the ROI mask is rebuilt on the
 * next frame). Slopes are |dy/dx| in 1/256; pixel lengths are in pixels of
 * the processed frame. */
typedef struct rte_lane_params {
    /* ROI polygon in fractions of width and height (Q16, 65536 = the full
     * side; see rte_polygon_from_fractions), 3..RTE_LANE_MAX_ROI_VERTICES
     * vertices. Default: the tutorial trapezoid (0,1) (0.45,0.6) (0.55,0.6)
     * (1,1). Its top row is where lanes end. */
    rte_vertex roi[RTE_LANE_MAX_ROI_VERTICES];
    int32_t roi_count;
    /* Edges */
    rte_lane_canny_mode canny_mode; /* default: RTE_LANE_CANNY_MEDIAN */
    int32_t canny_low, canny_high;  /* fixed thresholds on |dx|+|dy| (3x3 Sobel) */
    int32_t auto_sigma_permille;    /* median rule's sigma */
    /* Colour cue, used when the frame has colour: marking-coloured pixels
     * become 255 and all others are scaled by dim_q8/256 before the blur,
     * so white and yellow paint keeps a strong edge while shadows and road
     * patches lose contrast. */
    bool use_color;
    int32_t white_min;       /* white: B, G and R all >= white_min */
    int32_t yellow_rg_min;   /* yellow: R and G >= yellow_rg_min ... */
    int32_t yellow_b_margin; /* ... and B <= min(R, G) - yellow_b_margin */
    int32_t dim_q8;          /* 256 = leave non-marking pixels as they are */
    /* Curves: follow the markings up the image in windows and report a
     * bow when they bend (false: straight lanes only). */
    bool curves;
    /* Segments (cv::HoughLinesP parameters) */
    int32_t hough_threshold, min_length, max_gap;
    uint32_t hough_seed; /* the search's point order; 0: RTE_HOUGH_SEGMENTS_SEED */
    /* Slope filter per side: min_slope_q8 <= |dy/dx| * 256 <= max_slope_q8 */
    int32_t left_min_slope_q8, left_max_slope_q8;
    int32_t right_min_slope_q8, right_max_slope_q8;
    /* Fit */
    rte_lane_fit fit;
    int32_t outlier_px;     /* least squares: residual beyond which a segment is dropped */
    int32_t min_support_px; /* a lane needs this much segment length to count as seen */
    /* Tracking */
    int32_t gate_px;     /* segments farther than this from a tracked lane are ignored */
    int32_t hold_frames; /* a lost lane is predicted this many frames, then dropped */
    int32_t alpha_q8;    /* share of a measurement taken into the state (256 = all) */
    int32_t beta_q8;     /* share of the innovation taken into the velocity */
    int32_t max_step_px; /* innovations are clamped to +- this per frame (damping) */
} rte_lane_params;

/* Fixed at creation. */
typedef struct rte_lane_config {
    int32_t max_width, max_height; /* largest frame to be processed */
    int32_t max_segments;          /* Hough segments kept per frame (extra ones: truncated) */
    int32_t blur_ksize;            /* Gaussian kernel size (odd, sigma from the size) */
    rte_lane_params params;        /* initial runtime parameters */
} rte_lane_config;

/* Defaults for frames of about width x height (lengths scale with the
 * height; 540 rows give the tutorial's numbers). */
RTE_API void rte_lane_config_default(rte_lane_config *cfg, int32_t width, int32_t height);

typedef struct rte_lane_context rte_lane_context;

/* Everything the lane path needs, allocated once (as rte_grasp_create).
 * RTE_ERR_ARGUMENT for a configuration field out of range (sizes, counts,
 * blur size, parameters), RTE_ERR_NO_MEMORY when allocation fails; *ctx is
 * NULL then. */
RTE_API rte_status rte_lane_create(const rte_lane_config *cfg, rte_lane_context **ctx);
RTE_API void rte_lane_destroy(rte_lane_context *ctx);
/* Checks and copies new runtime parameters (RTE_ERR_ARGUMENT leaves the
 * old ones). Safe between any two frames; allocates nothing. */
RTE_API rte_status rte_lane_set_params(rte_lane_context *ctx, const rte_lane_params *params);
/* Forgets the tracked lanes (e.g. after a seek in a recording). */
RTE_API void rte_lane_reset(rte_lane_context *ctx);

enum {
    RTE_LANE_LEFT = 0,
    RTE_LANE_RIGHT = 1,
};

/* How a segment was used. */
typedef enum rte_lane_segment_use {
    RTE_LANE_SEG_REJECTED_SLOPE = 0, /* near-horizontal, wrong sign or out of the slope bounds */
    RTE_LANE_SEG_REJECTED_GATE = 1,  /* too far from the tracked lane */
    RTE_LANE_SEG_OUTLIER = 2,        /* dropped by the robust fit */
    RTE_LANE_SEG_LEFT = 3,           /* supports the left lane */
    RTE_LANE_SEG_RIGHT = 4,          /* supports the right lane */
} rte_lane_segment_use;

typedef struct rte_lane_segment {
    int32_t x0, y0, x1, y1; /* frame pixels */
    rte_lane_segment_use use;
} rte_lane_segment;

/* Points of a lane's far trace (rte_lane.far_count). */
#define RTE_LANE_FAR_POINTS 12

typedef struct rte_lane {
    bool found;          /* a lane is reported (measured now or predicted) */
    bool predicted;      /* not seen in this frame: held from the tracker's prediction */
    int32_t lost_frames; /* frames since it was last seen */
    /* The lane from (x_bottom, y_bottom) on the bottom row to (x_top, y_top)
     * on the ROI's top row; x in 1/256 pixel. This is the chord; a curved
     * lane lies bow_q8 beside it at mid-height (positive: right of it, the
     * road bending left; 0: straight). Its shape is a flat road's bend in
     * perspective, x = a d + b + c / d with d the rows below y_horizon
     * (where the two lanes' straight fits meet, or an eighth of the lane
     * above y_top): rte_lane_x_q8 gives x at any row. */
    int32_t x_bottom_q8, x_top_q8;
    int32_t y_bottom, y_top;
    int32_t bow_q8;
    int32_t y_horizon; /* the curve's horizon row (above y_top) */
    /* The highest row the marking was seen on this frame (y_bottom when
     * the lane is predicted or nothing above the bottom window was seen). */
    int32_t y_supported;
    /* The marking followed beyond where the curve leaves it (a road that
     * turns sharply past a crest, its markings running nearly along the
     * rows): far_count points from far_y[0], a row where the curve lies on
     * the marking, upwards (far_y falling), x in 1/256 pixel; rows above
     * far_y[0] take x from them (rte_lane_x_q8). 0 when the curve holds up
     * to where the marking ends. */
    int32_t far_count;
    int32_t far_x_q8[RTE_LANE_FAR_POINTS], far_y[RTE_LANE_FAR_POINTS];
    /* share of the lane's rows with paint along it, 1000 from two fifths of
     * them, less four times the share of the ROI washed out by glare
     * (docs/lanes.md, "Lane line and confidence") */
    int32_t confidence_permille;
    int32_t support_px; /* supporting segment length this frame */
} rte_lane;

typedef enum rte_lane_stage {
    RTE_LANE_STAGE_GRAY = 0, /* grey conversion and colour cue */
    RTE_LANE_STAGE_BLUR, /* 0 with fixed thresholds: blur and Canny run fused (rte_canny_blurred_u8) */
    RTE_LANE_STAGE_CANNY, /* thresholds, edges, ROI mask */
    RTE_LANE_STAGE_HOUGH,
    RTE_LANE_STAGE_FIT, /* slope filter, gate, fits, tracking */
    RTE_LANE_STAGES,
} rte_lane_stage;

RTE_API const char *rte_lane_stage_name(rte_lane_stage stage);

typedef struct rte_lane_result {
    rte_lane lane[2];  /* RTE_LANE_LEFT, RTE_LANE_RIGHT */
    bool centre_valid; /* both lanes found */
    /* Lane centre on the bottom row minus the image centre (positive: the
     * lane centre is to the right, i.e. the camera sits left of it). */
    int32_t offset_q8;
    int32_t offset_permille; /* the same as a fraction of the lane width */
    /* Heading of the lane centre line against the image's vertical at the
     * bottom row (the centre curve's tangent there), positive when it
     * leans right going up: tangent in 1/65536 and milliradians. */
    int32_t heading_tan_q16;
    int32_t heading_mrad;
    int32_t canny_low, canny_high; /* thresholds used this frame */
    /* The Hough segments of this frame, a view of the context's memory
     * valid until the next call; truncated when more were found than
     * max_segments. */
    const rte_lane_segment *segments;
    int32_t segment_count;
    bool truncated;
    /* The Canny edges inside the ROI polygon (what the Hough search saw):
     * the ROI's bounding box, a view of the context's memory valid until
     * the next call, its top-left pixel at (edges_x0, edges_y0) of the
     * frame. */
    rte_image_u8 edges;
    int32_t edges_x0, edges_y0;
    int64_t t_ns;
    int64_t stage_ns[RTE_LANE_STAGES]; /* CLOCK_MONOTONIC time spent per stage */
} rte_lane_result;

/* x of a found lane at row y, in 1/256 pixel: its curve, and above the far
 * trace's first row the trace's pieces (the last one extended beyond its
 * end). */
RTE_API int32_t rte_lane_x_q8(const rte_lane *lane, int32_t y);

/* Rows between the points of rte_lane_polyline (more when max_points are
 * too few for the lane). */
#define RTE_LANE_POINT_STEP 10
/* Points enough for rte_lane_polyline at its own step on any frame. */
#define RTE_LANE_POLYLINE_POINTS (RTE_LANE_MAX_SIDE / RTE_LANE_POINT_STEP + 2)
/* A found lane as points from its bottom row up to the highest row its
 * markings were seen on (the ROI's top row for a straight or predicted
 * lane), every RTE_LANE_POINT_STEP rows and at that row (which replaces
 * a point less than half a step below it, so that the last piece is not a
 * row or two long), or, with a far
 * trace, up to the trace's first row and then the trace's points: at most
 * max_points (>= 2) into x_q8[] (1/256 px) and y[], rows falling; returns
 * how many (0 for a lane not found). */
RTE_API int32_t rte_lane_polyline(const rte_lane *lane, int32_t max_points, int32_t *x_q8,
                                  int32_t *y);
/* Curvature of a found lane's image curve at its bottom row, in 1/px:
 * positive when it bends right going up the image, 0 when straight.
 * (Floating point: for reports, not part of the per-frame core.) */
RTE_API double rte_lane_curvature(const rte_lane *lane);

/* One frame. `frame` may be any rte_frame format up to the configured
 * size; BGR24 and RGB24 frames give the colour cue from their colours,
 * NV12, YUYV and UYVY from their chroma (full-range BT.601), GREY frames
 * none. Only the ROI's bounding box is read. t_ns is the frame's time
 * (kept in the result). */
RTE_API rte_status rte_lane_process(rte_lane_context *ctx, const rte_frame *frame, int64_t t_ns,
                                    rte_lane_result *out);
/* The same from a grey image and, optionally, the BGR image it came from
 * (same size; NULL for grey-only sources). */
RTE_API rte_status rte_lane_process_gray(rte_lane_context *ctx, const rte_image_u8 *gray,
                                         const rte_image_u8c3 *bgr, int64_t t_ns,
                                         rte_lane_result *out);

#ifdef __cplusplus
}
#endif
#endif
