/* cli_filter_main: see cli_filter.h. */
#include "cli_filter.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_image.h"
#include "rtedge/gradient.h"

#define FILTER_DETAILS                                                            \
    "IN: PGM/PPM (P2, P3, P5, P6), PNG or JPEG; colour is converted to grey as\n" \
    "cv2.cvtColor(cv2.imread(IN), cv2.COLOR_BGR2GRAY) does. OUT: .pgm, .png or .npy.\n"
#define INT16_DETAILS                                                           \
    "OUT .npy holds the int16 result; .pgm/.png its saturated absolute value\n" \
    "(cv2.convertScaleAbs).\n"

static bool has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    if (n < e)
        return false;
    for (size_t i = 0; i < e; i++)
        if ((path[n - e + i] | 0x20) != (ext[i] | 0x20))
            return false;
    return true;
}

rte_status cli_filter_apply(const char *name, const filter_spec *spec, const rte_image_u8 *gray,
                            rte_image_u8 *out, rte_image_s16 *d, bool abs_to_out)
{
    rte_arena arena;
    void *arena_memory = cli_new_arena(
        name, spec->scratch ? spec->scratch(spec->ctx, gray->width, gray->height) : 0, &arena);
    rte_status st = RTE_ERR_NO_MEMORY;
    if (arena_memory)
        st = spec->apply(spec->ctx, gray, out, d, &arena);
    if (st == RTE_OK && spec->int16 && abs_to_out)
        st = rte_abs_s16_u8(d, out);
    free(arena_memory);
    return st;
}

int cli_filter_main(const cli_entry *self, int argc, char **argv, const filter_spec *spec)
{
    char details[1024];
    snprintf(details, sizeof details, "%s%s%s", FILTER_DETAILS, spec->int16 ? INT16_DETAILS : "",
             spec->details);
    cli_command cmd = {self->name, "IN OUT", self->summary, details, spec->options, 2};
    const char *paths[2];
    int rc = cli_parse(&cmd, argc, argv, paths);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (spec->prepare && (rc = spec->prepare(self->name, spec->ctx)) != CLI_EXIT_OK)
        return rc;

    cli_image in;
    if ((rc = cli_load(self->name, paths[0], &in)) != CLI_EXIT_OK)
        return rc;
    int32_t w = in.gray.width, h = in.gray.height;
    rte_image_u8 out;
    rte_image_s16 d = {0};
    void *out_memory = cli_new_u8(self->name, w, h, &out);
    void *d_memory = spec->int16 ? cli_new_s16(self->name, w, h, &d) : NULL;
    bool npy = spec->int16 && has_extension(paths[1], ".npy");
    rte_status st = RTE_ERR_NO_MEMORY;
    if (out_memory && (d_memory || !spec->int16))
        st = cli_filter_apply(self->name, spec, &in.gray, &out, &d, !npy);
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        rc = CLI_EXIT_FAILURE;
    } else {
        rc = npy ? cli_save_s16(self->name, paths[1], &d)
                 : cli_save_gray(self->name, paths[1], &out);
        if (rc == CLI_EXIT_OK && spec->report)
            spec->report(spec->ctx);
    }
    cli_image_free(&in);
    free(out_memory);
    free(d_memory);
    return rc;
}
