#include "cli_image.h"

#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "rtedge/color.h"
#include "rtedge/imageio.h"

int cli_load(const char *command, const char *path, cli_image *image)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_info info;
    *image = (cli_image){0};
    rte_status st = rte_image_probe(path, &info, msg, sizeof msg);
    if (st != RTE_OK) {
        cli_error(command, "%s", msg);
        return CLI_EXIT_INPUT;
    }
    size_t pixels = (size_t)info.width * (size_t)info.height;
    image->memory = malloc(pixels * 4);
    rte_image_reader *reader = rte_image_reader_create(info.width, info.height);
    if (!image->memory || !reader) {
        cli_error(command, "%s: not enough memory for %dx%d", path, info.width, info.height);
        rte_image_reader_destroy(reader);
        cli_image_free(image);
        return CLI_EXIT_INPUT;
    }
    uint8_t *base = (uint8_t *)image->memory;
    image->gray = rte_image_u8_view(base, info.width, info.height, 0);
    if (info.channels == 1) {
        st = rte_image_read_gray(reader, path, &image->gray, msg, sizeof msg);
    } else {
        image->bgr = (rte_image_u8c3){info.width, info.height, info.width * 3, base + pixels};
        st = rte_image_read_bgr(reader, path, &image->bgr, msg, sizeof msg);
        if (st == RTE_OK)
            st = rte_color_bgr_to_gray(&image->bgr, &image->gray);
    }
    rte_image_reader_destroy(reader);
    if (st != RTE_OK) {
        cli_error(command, "%s", msg[0] ? msg : rte_status_message(st));
        cli_image_free(image);
        return CLI_EXIT_INPUT;
    }
    return CLI_EXIT_OK;
}

void cli_image_free(cli_image *image)
{
    free(image->memory);
    *image = (cli_image){0};
}

void *cli_new_u8(const char *command, int32_t width, int32_t height, rte_image_u8 *img)
{
    void *mem = calloc((size_t)width * (size_t)height, 1);
    if (!mem)
        cli_error(command, "not enough memory for a %dx%d image", width, height);
    *img = rte_image_u8_view(mem, width, height, 0);
    return mem;
}

void *cli_new_s16(const char *command, int32_t width, int32_t height, rte_image_s16 *img)
{
    void *mem = calloc((size_t)width * (size_t)height, sizeof(int16_t));
    if (!mem)
        cli_error(command, "not enough memory for a %dx%d image", width, height);
    *img = rte_image_s16_view(mem, width, height, 0);
    return mem;
}

void *cli_new_arena(const char *command, size_t bytes, rte_arena *arena)
{
    void *mem = malloc(bytes ? bytes : 1);
    if (!mem)
        cli_error(command, "not enough memory for %zu bytes of scratch", bytes);
    rte_arena_init(arena, mem, bytes);
    return mem;
}

/* The end of every writer: the message on failure. */
static int saved(const char *command, rte_status st, const char *msg)
{
    if (st != RTE_OK) {
        cli_error(command, "%s", msg);
        return CLI_EXIT_FAILURE;
    }
    return CLI_EXIT_OK;
}

int cli_save_gray(const char *command, const char *path, const rte_image_u8 *img)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    return saved(command, rte_image_write_gray(path, img, msg, sizeof msg), msg);
}

int cli_save_s16(const char *command, const char *path, const rte_image_s16 *img)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    return saved(command, rte_image_write_s16(path, img, msg, sizeof msg), msg);
}

int cli_save_bgr(const char *command, const char *path, const rte_image_u8c3 *img)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    return saved(command, rte_image_write_bgr(path, img, msg, sizeof msg), msg);
}
