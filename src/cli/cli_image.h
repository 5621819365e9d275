/* Loading and saving images for the rtedge subcommands. */
#ifndef RTEDGE_CLI_IMAGE_H
#define RTEDGE_CLI_IMAGE_H

#include <stddef.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"

/* An input image as grey (always) and BGR (when the file is colour; for a
 * grey file bgr.buf is NULL). */
typedef struct cli_image {
    rte_image_u8 gray;
    rte_image_u8c3 bgr;
    void *memory;
} cli_image;

/* Reads `path` as cv::cvtColor(cv::imread(path), COLOR_BGR2GRAY) does.
 * Returns CLI_EXIT_OK, or CLI_EXIT_INPUT after printing what is wrong. */
int cli_load(const char *command, const char *path, cli_image *image);
void cli_image_free(cli_image *image);

/* A grey output image of the given size (packed), or NULL after a message. */
void *cli_new_u8(const char *command, int32_t width, int32_t height, rte_image_u8 *img);
void *cli_new_s16(const char *command, int32_t width, int32_t height, rte_image_s16 *img);

/* An arena of `bytes` bytes; free the returned memory when done. NULL after a
 * message when memory runs out. */
void *cli_new_arena(const char *command, size_t bytes, rte_arena *arena);

/* Writes by extension (.pgm, .png, .npy for grey; .npy for int16).
 * Returns CLI_EXIT_OK or CLI_EXIT_FAILURE after printing the problem. */
int cli_save_gray(const char *command, const char *path, const rte_image_u8 *img);
int cli_save_s16(const char *command, const char *path, const rte_image_s16 *img);

#endif
