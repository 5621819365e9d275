/* The derivative subcommands (sobel, scharr, laplacian, log): int16
 * results, written as .npy or as their saturated absolute value. */
#include <math.h>

#include "cli_derivative.h"
#include "cli_filter.h"
#include "commands.h"
#include "rtedge/blur.h"
#include "rtedge/gradient.h"

/* round(sqrt(gx^2 + gy^2)) of the ksize Sobel derivatives, saturated to
 * int16: cv2.magnitude of the two as float32 (whose squares are exact
 * below 2^24, so the rounding, hence the 8-bit image, is the same). */
static rte_status sobel_magnitude(const rte_image_u8 *gray, rte_image_s16 *d, int ksize,
                                  rte_arena *arena)
{
    const int32_t w = gray->width, h = gray->height;
    void *mem = rte_arena_alloc(arena, (size_t)w * (size_t)h * 2);
    if (!mem)
        return RTE_ERR_NO_MEMORY;
    rte_image_s16 gy = rte_image_s16_view(mem, w, h, 0);
    rte_status st = rte_sobel_s16(gray, &gy, 0, 1, ksize, arena);
    if (st == RTE_OK)
        st = rte_sobel_s16(gray, d, 1, 0, ksize, arena);
    for (int32_t y = 0; st == RTE_OK && y < h; y++) {
        int16_t *gx = rte_s16_row(d, y);
        const int16_t *gyr = rte_s16_row(&gy, y);
        for (int32_t x = 0; x < w; x++) {
            const double m = sqrt((double)gx[x] * gx[x] + (double)gyr[x] * gyr[x]);
            gx[x] = (int16_t)(m > INT16_MAX ? INT16_MAX : lrint(m));
        }
    }
    return st;
}

int cli_derivative_prepare(const char *name, void *ctx)
{
    derivative_options *o = ctx;
    const char *problem = NULL;
    if (o->kind == DERIV_SOBEL && (o->ksize % 2 == 0 || o->dx + o->dy == 0))
        problem = "--ksize must be odd and dx + dy at least 1";
    else if (o->magnitude && (o->ksize == 1 || o->dx != 1 || o->dy != 0))
        problem = "--magnitude takes no --dx/--dy, and --ksize 3, 5 or 7";
    else if (o->kind == DERIV_SCHARR && o->dx + o->dy != 1)
        problem = "exactly one of --dx 1 and --dy 1";
    else if (o->kind == DERIV_LAPLACIAN && o->ksize == 2)
        problem = "--ksize must be 1 or 3";
    if (problem) {
        cli_error(name, "%s", problem);
        return CLI_EXIT_USAGE;
    }
    return o->blur_first ? cli_blur_prepare(name, &o->blur) : CLI_EXIT_OK;
}

size_t cli_derivative_scratch(void *ctx, int32_t w, int32_t h)
{
    derivative_options *o = ctx;
    switch (o->kind) {
    case DERIV_SOBEL: /* with the magnitude, the y derivative first */
        return rte_sobel_scratch_size(w, h, o->ksize) +
               (o->magnitude ? rte_arena_piece_size((size_t)w * (size_t)h * 2) : 0);
    case DERIV_SCHARR: return rte_scharr_scratch_size(w, h);
    case DERIV_LAPLACIAN: break;
    }
    size_t scratch = rte_laplacian_scratch_size(w, h, o->ksize);
    if (o->blur_first) /* the blurred image lives in `out` */
        scratch = cli_max_size(scratch, cli_blur_scratch(&o->blur, w, h));
    return scratch;
}

rte_status cli_derivative_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                                rte_image_s16 *d, rte_arena *arena)
{
    derivative_options *o = ctx;
    switch (o->kind) {
    case DERIV_SOBEL:
        return o->magnitude ? sobel_magnitude(gray, d, o->ksize, arena)
                            : rte_sobel_s16(gray, d, o->dx, o->dy, o->ksize, arena);
    case DERIV_SCHARR: return rte_scharr_s16(gray, d, o->dx, o->dy, arena);
    case DERIV_LAPLACIAN: break;
    }
    if (o->blur_first) {
        rte_status st = rte_gaussian_blur_u8(gray, out, &o->blur.kernel, arena);
        if (st != RTE_OK)
            return st;
        gray = out;
    }
    return rte_laplacian_s16(gray, d, o->ksize, arena);
}

static int derivative_main(const cli_entry *self, int argc, char **argv, derivative_options *o,
                           cli_option *options, const char *details)
{
    filter_spec spec = {
        details, options, o, cli_derivative_prepare, cli_derivative_scratch, cli_derivative_apply,
        true,    NULL};
    return cli_filter_main(self, argc, argv, &spec);
}

int cmd_sobel(const cli_entry *self, int argc, char **argv)
{
    derivative_options o = {.kind = DERIV_SOBEL, .dx = 1, .dy = 0, .ksize = 3};
    cli_option options[] = {
        {"dx", CLI_INT, &o.dx, 0, 2, NULL, "order of the x derivative", NULL},
        {"dy", CLI_INT, &o.dy, 0, 2, NULL, "order of the y derivative", NULL},
        {"ksize", CLI_INT, &o.ksize, 1, 7, NULL, "aperture: 1, 3, 5 or 7", NULL},
        {"magnitude", CLI_FLAG, &o.magnitude, 0, 0, NULL,
         "gradient magnitude of the first derivatives instead", NULL},
        {0}};
    return derivative_main(self, argc, argv, &o, options,
                           "= cv2.Sobel(img, cv2.CV_16S, dx, dy, ksize=ksize)\n"
                           "--magnitude: round(cv2.magnitude(gx, gy)) of the float32 derivatives\n"
                           "(dx = 1, dy = 1), saturated to int16.");
}

int cmd_scharr(const cli_entry *self, int argc, char **argv)
{
    derivative_options o = {.kind = DERIV_SCHARR, .dx = 1, .dy = 0};
    cli_option options[] = {{"dx", CLI_INT, &o.dx, 0, 1, NULL, "x derivative (dx + dy = 1)", NULL},
                            {"dy", CLI_INT, &o.dy, 0, 1, NULL, "y derivative", NULL},
                            {0}};
    return derivative_main(self, argc, argv, &o, options, "= cv2.Scharr(img, cv2.CV_16S, dx, dy)");
}

int cmd_laplacian(const cli_entry *self, int argc, char **argv)
{
    derivative_options o = {.kind = DERIV_LAPLACIAN, .ksize = 1};
    cli_option options[] = {{"ksize", CLI_INT, &o.ksize, 1, 3, NULL, "aperture: 1 or 3", NULL},
                            {0}};
    return derivative_main(self, argc, argv, &o, options,
                           "= cv2.Laplacian(img, cv2.CV_16S, ksize=ksize)");
}

int cmd_log(const cli_entry *self, int argc, char **argv)
{
    derivative_options o = {.kind = DERIV_LAPLACIAN,
                            .ksize = 1,
                            .blur_first = true,
                            .blur = {.ksize = 3, .ksize_y = -1}};
    cli_option options[] = {
        {"blur", CLI_INT, &o.blur.ksize, 0, RTE_GAUSSIAN_MAX_KSIZE, NULL,
         "Gaussian kernel size, 0 = from --sigma", NULL},
        {"sigma", CLI_DOUBLE, &o.blur.sigma, 0, 100, NULL, "Gaussian sigma, 0 = from the size",
         NULL},
        {"ksize", CLI_INT, &o.ksize, 1, 3, NULL, "Laplacian aperture: 1 or 3", NULL},
        {0}};
    return derivative_main(
        self, argc, argv, &o, options,
        "= cv2.Laplacian(cv2.GaussianBlur(img, (blur, blur), sigma), cv2.CV_16S, ksize=ksize)");
}
