/* The frame of the rtedge subcommands that run one kernel on an image
 * (cmd_filters.c): a filter_spec gives the options, a check of them that
 * runs before the input is read (so usage errors come first), the scratch
 * size and the kernel call; cli_filter_main does the rest the same way for
 * all. */
#ifndef RTEDGE_CLI_FILTER_H
#define RTEDGE_CLI_FILTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cli.h"
#include "commands.h"
#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

typedef struct filter_spec {
    const char *details; /* after the common input/output text */
    cli_option *options;
    void *ctx; /* the subcommand's option values and tables */
    /* Checks the options and builds tables (configuration time); returns an
     * exit code (CLI_EXIT_USAGE after a message). NULL: nothing to check. */
    int (*prepare)(const char *name, void *ctx);
    size_t (*scratch)(void *ctx, int32_t width, int32_t height);
    /* The kernel: `gray` in, `out` (u8) or, for int16 results, `d` out. */
    rte_status (*apply)(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out, rte_image_s16 *d,
                        rte_arena *arena);
    bool int16;                /* the result is int16 (written to .npy, or |d| to an image) */
    void (*report)(void *ctx); /* prints what the run found, after OUT is written; may be NULL */
} filter_spec;

/* Runs spec's kernel (prepared) on gray: into *out, or for int16 results
 * into *d and, with abs_to_out, its saturated absolute value into *out
 * (cv2.convertScaleAbs). */
rte_status cli_filter_apply(const char *name, const filter_spec *spec, const rte_image_u8 *gray,
                            rte_image_u8 *out, rte_image_s16 *d, bool abs_to_out);
/* Parses the options, prepares, reads IN, runs the kernel and writes OUT
 * (.npy for int16 results, else the image); an exit code. */
int cli_filter_main(const cli_entry *self, int argc, char **argv, const filter_spec *spec);

#endif
