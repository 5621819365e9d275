/* Pieces shared by the contours, shapes and grasp subcommands: the
 * binarisation options, fixed-point printing and overlays (draw.h). */
#ifndef RTEDGE_CLI_PIPELINE_H
#define RTEDGE_CLI_PIPELINE_H

#include <stdint.h>

#include "cli.h"
#include "cli_image.h"
#include "rtedge/draw.h"
#include "rtedge/grasp.h"

/* The grasp options of shapes and grasp (and the binarisation of contours). */
typedef struct cli_pipeline_options {
    const char *binarize; /* "background", "otsu", "canny" or a threshold 0..255 */
    int polarity;         /* index in cli_polarities: auto, dark, bright */
    int blur, min_area, max_area, max_objects, canny_low, canny_high, close, close_iterations;
    int contrast;
    bool no_chroma;
    double edge_support;
    bool skip_border, keep_border, split, no_split;
    const char *roi; /* the workspace, "x,y;..." fractions; NULL: the whole image */
    int gripper_min, gripper_max, margin, finger; /* px: rte_grasp_params */
    /* which of the sizes in pixels the command line gave */
    bool given_min_area, given_gripper_min, given_gripper_max, given_margin, given_finger;
} cli_pipeline_options;

/* The sizes in pixels the command line did not give, for a w x h photo:
 * the defaults are for a camera's 640 px side, and grow with a larger
 * photo's longest side (areas with its square). */
void cli_pipeline_scale_sizes(cli_pipeline_options *o, int32_t w, int32_t h);

extern const char *const cli_polarities[];

/* Defaults (blur: the default Gaussian size of the command). `tutorial`:
 * Otsu, objects on the border kept, no split, as the OpenCV tutorial's
 * shape analysis; otherwise the grasp path's defaults (background, border
 * objects dropped, touching objects split). */
void cli_pipeline_defaults(cli_pipeline_options *o, int blur, int min_area, bool tutorial);

/* Fills options[] (room for CLI_PIPELINE_OPTIONS entries) with the table
 * entries of `o`; `grasp` adds the object options (areas, border, count,
 * gripper). */
#define CLI_PIPELINE_OPTIONS 22
int cli_pipeline_option_table(cli_option *options, cli_pipeline_options *o, bool grasp);

/* The grasp configuration for an image of w x h. CLI_EXIT_USAGE after a
 * message when --binarize is not background, otsu, canny or 0..255, --roi
 * is not a polygon or --gripper-min exceeds --gripper-max. */
int cli_pipeline_config(const char *command, const cli_pipeline_options *o, int32_t w, int32_t h,
                        rte_grasp_config *config);

/* Q8 / Q16 fixed point as decimals in JSON (2 or 4 places, trailing zeros cut). */
void cli_print_q8(int64_t v);
void cli_print_q16(int64_t v);

/* A BGR copy of the input to draw on (grey replicated); NULL after a message. */
void *cli_overlay_canvas(const char *command, const cli_image *in, rte_image_u8c3 *canvas);

/* The grasp path on a loaded image: with its colour (half-size chroma,
 * for the background mode) when it has any. */
rte_status cli_grasp_process(rte_grasp_ctx *ctx, const cli_image *in, rte_grasp_result *out);

#endif
