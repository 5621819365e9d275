/* The derivative step of the rtedge subcommands (sobel, scharr, laplacian,
 * log; int16 results), shared with `rtedge compare`, whose cells are what
 * these commands write. */
#ifndef RTEDGE_CLI_DERIVATIVE_H
#define RTEDGE_CLI_DERIVATIVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cli_canny.h"
#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

typedef enum derivative_kind { DERIV_SOBEL, DERIV_SCHARR, DERIV_LAPLACIAN } derivative_kind;

typedef struct derivative_options {
    derivative_kind kind;
    int dx, dy, ksize;
    bool magnitude;  /* sobel: round(sqrt(dx^2 + dy^2)) of the first derivatives */
    bool blur_first; /* log: Gaussian blur, then the Laplacian */
    blur_options blur;
} derivative_options;

/* A filter_spec's prepare, scratch and apply for derivative_options. */
int cli_derivative_prepare(const char *name, void *ctx);
size_t cli_derivative_scratch(void *ctx, int32_t w, int32_t h);
rte_status cli_derivative_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                                rte_image_s16 *d, rte_arena *arena);

#endif
