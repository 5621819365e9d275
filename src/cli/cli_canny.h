/* The Canny step of the rtedge subcommands (optional Gaussian blur first),
 * shared by `rtedge canny` and the commands that start from edges
 * (lines, segments, circles): one option table, one implementation. */
#ifndef RTEDGE_CLI_CANNY_H
#define RTEDGE_CLI_CANNY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cli.h"
#include "rtedge/arena.h"
#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

/* Gaussian blur options, shared by blur, log and canny. */
typedef struct blur_options {
    int ksize;
    double sigma;
    int ksize_y;
    double sigma_y;
    rte_gaussian_kernel kernel;
} blur_options;

/* Builds o->kernel (configuration time); an exit code, after a message. */
int cli_blur_prepare(const char *name, void *blur_options_ptr);
size_t cli_blur_scratch(void *blur_options_ptr, int32_t w, int32_t h);

typedef struct canny_options {
    double low, high, auto_sigma;
    int aperture, auto_rule; /* auto_rule: 0 none, 1 median, 2 otsu */
    bool l2, blur_first;
    blur_options blur;
} canny_options;

/* Defaults of `rtedge canny` (50, 150, aperture 3, no blur). */
canny_options cli_canny_defaults(void);
/* The option rows of the Canny step (CLI_CANNY_OPTIONS of them, no
 * terminator) into rows[]; returns how many. */
#define CLI_CANNY_OPTIONS 8
int cli_canny_option_rows(cli_option *rows, canny_options *o);
/* Checks the options and builds the blur kernel; an exit code. */
int cli_canny_prepare(const char *name, void *ctx);
size_t cli_canny_scratch(void *ctx, int32_t w, int32_t h);
/* The thresholds for `gray` (the auto rules read its histogram; blur it
 * first when asked) into *params. */
rte_status cli_canny_params(canny_options *o, const rte_image_u8 *gray, rte_canny_params *params);
/* Blur (when asked) and Canny of `gray` into `out`. */
rte_status cli_canny_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out, rte_image_s16 *d,
                           rte_arena *arena);

#endif
