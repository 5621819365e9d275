/* Subcommands that run one librtedge kernel on an image file: read IN (grey,
 * or colour converted to grey as OpenCV does), run the kernel, write OUT.
 * Each is a filter_spec run by cli_filter_main (cli_filter.h). */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_canny.h"
#include "cli_filter.h"
#include "cli_image.h"
#include "commands.h"
#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/gradient.h"
#include "rtedge/morphology.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/threshold.h"

/* --- gray --- */

static rte_status gray_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                             rte_image_s16 *d, rte_arena *arena)
{
    for (int32_t y = 0; y < gray->height; y++)
        memcpy(rte_u8_row(out, y), rte_u8_row(gray, y), (size_t)gray->width);
    return RTE_OK;
}

int cmd_gray(const cli_entry *self, int argc, char **argv)
{
    cli_option options[] = {{0}};
    filter_spec spec = {.details = "", .options = options, .apply = gray_apply};
    return cli_filter_main(self, argc, argv, &spec);
}

/* --- blur, median --- */

int cli_blur_prepare(const char *name, void *ctx)
{
    blur_options *o = ctx;
    rte_status st = rte_gaussian_kernel_init(
        &o->kernel, o->ksize, o->ksize_y < 0 ? o->ksize : o->ksize_y, o->sigma, o->sigma_y);
    if (st != RTE_OK) {
        cli_error(name, "Gaussian kernel size %d, sigma %g: %s", o->ksize, o->sigma,
                  rte_status_message(st));
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

size_t cli_blur_scratch(void *ctx, int32_t w, int32_t h)
{
    return rte_gaussian_blur_u8_scratch_size(w, h, &((blur_options *)ctx)->kernel);
}

static rte_status blur_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                             rte_image_s16 *d, rte_arena *arena)
{
    return rte_gaussian_blur_u8(gray, out, &((blur_options *)ctx)->kernel, arena);
}

int cmd_blur(const cli_entry *self, int argc, char **argv)
{
    blur_options b = {.ksize = 5, .ksize_y = -1};
    cli_option options[] = {
        {"ksize", CLI_INT, &b.ksize, 0, RTE_GAUSSIAN_MAX_KSIZE, NULL,
         "odd kernel size, 0 = from --sigma", NULL},
        {"sigma", CLI_DOUBLE, &b.sigma, 0, 100, NULL, "sigma, 0 = from the kernel size", NULL},
        {"ksize-y", CLI_INT, &b.ksize_y, -1, RTE_GAUSSIAN_MAX_KSIZE, NULL,
         "vertical size, -1 = --ksize", NULL},
        {"sigma-y", CLI_DOUBLE, &b.sigma_y, 0, 100, NULL, "vertical sigma, 0 = --sigma", NULL},
        {0}};
    filter_spec spec = {"= cv2.GaussianBlur(img, (ksize, ksize-y), sigma, sigmaY=sigma-y)",
                        options,
                        &b,
                        cli_blur_prepare,
                        cli_blur_scratch,
                        blur_apply,
                        false,
                        NULL};
    return cli_filter_main(self, argc, argv, &spec);
}

static int median_prepare(const char *name, void *ctx)
{
    if (*(int *)ctx % 2 == 0) {
        cli_error(name, "--ksize must be 1, 3 or 5");
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

static size_t median_scratch(void *ctx, int32_t w, int32_t h)
{
    return rte_median_blur_u8_scratch_size(w, h, *(int *)ctx);
}

static rte_status median_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                               rte_image_s16 *d, rte_arena *arena)
{
    return rte_median_blur_u8(gray, out, *(int *)ctx, arena);
}

int cmd_median(const cli_entry *self, int argc, char **argv)
{
    int ksize = 3;
    cli_option options[] = {{"ksize", CLI_INT, &ksize, 1, 5, NULL, "aperture: 1, 3 or 5", NULL},
                            {0}};
    filter_spec spec = {"= cv2.medianBlur(img, ksize)",
                        options,
                        &ksize,
                        median_prepare,
                        median_scratch,
                        median_apply,
                        false,
                        NULL};
    return cli_filter_main(self, argc, argv, &spec);
}

/* --- canny --- */

int cli_canny_prepare(const char *name, void *ctx)
{
    canny_options *o = ctx;
    if (o->aperture != 3 && o->aperture != 5) {
        cli_error(name, "--aperture must be 3 or 5");
        return CLI_EXIT_USAGE;
    }
    o->blur_first = o->blur.ksize > 0 || o->blur.sigma > 0;
    return o->blur_first ? cli_blur_prepare(name, &o->blur) : CLI_EXIT_OK;
}

size_t cli_canny_scratch(void *ctx, int32_t w, int32_t h)
{
    canny_options *o = ctx;
    size_t scratch = rte_canny_scratch_size(w, h, o->aperture);
    if (o->blur_first) /* the blurred image, then the larger of the two kernels' needs */
        scratch = rte_arena_piece_size((size_t)w * (size_t)h) +
                  cli_max_size(scratch, cli_blur_scratch(&o->blur, w, h));
    return scratch;
}

rte_status cli_canny_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out, rte_image_s16 *d,
                           rte_arena *arena)
{
    canny_options *o = ctx;
    rte_status st = RTE_OK;
    rte_image_u8 blurred;
    if (o->blur_first) {
        void *mem = rte_arena_alloc(arena, (size_t)gray->width * (size_t)gray->height);
        if (!mem)
            return RTE_ERR_NO_MEMORY;
        blurred = rte_image_u8_view(mem, gray->width, gray->height, 0);
        if ((st = rte_gaussian_blur_u8(gray, &blurred, &o->blur.kernel, arena)) != RTE_OK)
            return st;
        gray = &blurred;
    }
    rte_canny_params params;
    st = cli_canny_params(o, gray, &params);
    return st == RTE_OK ? rte_canny_u8(gray, out, &params, arena) : st;
}

rte_status cli_canny_params(canny_options *o, const rte_image_u8 *gray, rte_canny_params *params)
{
    rte_status st = RTE_OK;
    if (o->auto_rule) {
        uint32_t hist[256];
        int32_t low = 0, high = 0;
        st = rte_histogram_u8(gray, hist);
        if (st == RTE_OK && o->auto_rule == 1)
            st = rte_threshold_auto_canny_median(hist, (int32_t)(o->auto_sigma * 1000 + 0.5), &low,
                                                 &high);
        else if (st == RTE_OK)
            st = rte_threshold_auto_canny_otsu(hist, &low, &high);
        o->low = low;
        o->high = high;
    }
    return st == RTE_OK ? rte_canny_params_init(params, o->low, o->high, o->aperture, o->l2) : st;
}

static void canny_report(void *ctx)
{
    canny_options *o = ctx;
    printf("{\"low\":%g,\"high\":%g}\n", o->low, o->high);
}

canny_options cli_canny_defaults(void)
{
    return (canny_options){
        .low = 50, .high = 150, .auto_sigma = 0.33, .aperture = 3, .blur = {.ksize_y = -1}};
}

int cli_canny_option_rows(cli_option *rows, canny_options *o)
{
    static const char *const auto_rules[] = {"none", "median", "otsu", NULL};
    const cli_option r[CLI_CANNY_OPTIONS] = {
        {"low", CLI_DOUBLE, &o->low, -1e6, 1e6, NULL, "lower hysteresis threshold", NULL},
        {"high", CLI_DOUBLE, &o->high, -1e6, 1e6, NULL, "upper hysteresis threshold", NULL},
        {"aperture", CLI_INT, &o->aperture, 3, 5, NULL, "Sobel aperture: 3 or 5", NULL},
        {"l2", CLI_FLAG, &o->l2, 0, 0, NULL,
         "L2 gradient magnitude (squared, as OpenCV compares it)", NULL},
        {"blur", CLI_INT, &o->blur.ksize, 0, RTE_GAUSSIAN_MAX_KSIZE, NULL,
         "Gaussian blur first with this odd size; 0 = none unless --sigma", NULL},
        {"sigma", CLI_DOUBLE, &o->blur.sigma, 0, 100, NULL, "Gaussian sigma of that blur", NULL},
        {"auto", CLI_CHOICE, &o->auto_rule, 0, 0, auto_rules,
         "thresholds from the image: median rule or Otsu rule", NULL},
        {"auto-sigma", CLI_DOUBLE, &o->auto_sigma, 0, 1, NULL, "s of the median rule", NULL}};
    for (int i = 0; i < CLI_CANNY_OPTIONS; i++)
        rows[i] = r[i];
    return CLI_CANNY_OPTIONS;
}

int cmd_canny(const cli_entry *self, int argc, char **argv)
{
    canny_options o = cli_canny_defaults();
    cli_option options[CLI_CANNY_OPTIONS + 1];
    options[cli_canny_option_rows(options, &o)] = (cli_option){0};
    filter_spec spec = {
        "= cv2.Canny(cv2.GaussianBlur(img, (blur, blur), sigma), low, high,\n"
        "            apertureSize=aperture, L2gradient=l2)\n"
        "--auto median: low = max(0, (1-s) * median), high = min(255, (1+s) * median),\n"
        "truncated to integers; --auto otsu: high = Otsu's threshold, low = high / 2.\n"
        "Prints the thresholds used as JSON: {\"low\":L,\"high\":H}.",
        options,
        &o,
        cli_canny_prepare,
        cli_canny_scratch,
        cli_canny_apply,
        false,
        canny_report};
    return cli_filter_main(self, argc, argv, &spec);
}

/* --- threshold --- */

typedef struct threshold_options {
    double value, maxval;
    int type;
    bool otsu;
    rte_threshold_params params;
    int32_t used;
} threshold_options;

static int threshold_prepare(const char *name, void *ctx)
{
    threshold_options *o = ctx;
    rte_status st = rte_threshold_params_init(&o->params, (rte_threshold_type)o->type, o->value,
                                              o->maxval, o->otsu);
    if (st != RTE_OK) {
        cli_error(name, "%s", rte_status_message(st));
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

static rte_status threshold_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                                  rte_image_s16 *d, rte_arena *arena)
{
    threshold_options *o = ctx;
    return rte_threshold_u8(gray, out, &o->params, &o->used);
}

static void threshold_report(void *ctx)
{
    printf("{\"threshold\":%d}\n", ((threshold_options *)ctx)->used);
}

int cmd_threshold(const cli_entry *self, int argc, char **argv)
{
    static const char *const types[] = {"binary", "binary_inv", "trunc",
                                        "tozero", "tozero_inv", NULL};
    threshold_options o = {.value = 127, .maxval = 255};
    cli_option options[] = {
        {"value", CLI_DOUBLE, &o.value, -1e6, 1e6, NULL, "threshold (ignored with --otsu)", NULL},
        {"maxval", CLI_DOUBLE, &o.maxval, -1e6, 1e6, NULL, "value for binary and binary_inv", NULL},
        {"type", CLI_CHOICE, &o.type, 0, 0, types, "threshold type", NULL},
        {"otsu", CLI_FLAG, &o.otsu, 0, 0, NULL, "Otsu's threshold from the image's histogram",
         NULL},
        {0}};
    filter_spec spec = {"= cv2.threshold(img, value, maxval, type [+ cv2.THRESH_OTSU]);\n"
                        "prints the threshold used as JSON: {\"threshold\":T}.",
                        options,
                        &o,
                        threshold_prepare,
                        NULL,
                        threshold_apply,
                        false,
                        threshold_report};
    return cli_filter_main(self, argc, argv, &spec);
}

/* --- erode, dilate, open, close: the subcommand's name is the operation --- */

typedef struct morphology_options {
    const char *name;
    int shape, ksize, ksize_y, iterations;
    rte_morph_op op;
    rte_morph_element element;
} morphology_options;

static int morphology_prepare(const char *name, void *ctx)
{
    static const char *const ops[] = {"erode", "dilate", "open", "close"};
    morphology_options *o = ctx;
    for (int i = 0; i < 4; i++)
        if (strcmp(ops[i], name) == 0)
            o->op = (rte_morph_op)i;
    int h = o->ksize_y ? o->ksize_y : o->ksize;
    rte_status st =
        rte_morphology_element_init(&o->element, (rte_morph_shape)o->shape, o->ksize, h);
    if (st != RTE_OK) {
        cli_error(name, "element %dx%d: %s", o->ksize, h, rte_status_message(st));
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

static size_t morphology_scratch(void *ctx, int32_t w, int32_t h)
{
    morphology_options *o = ctx;
    return rte_morphology_scratch_size(w, h, &o->element, o->iterations);
}

static rte_status morphology_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                                   rte_image_s16 *d, rte_arena *arena)
{
    morphology_options *o = ctx;
    return rte_morphology_u8(gray, out, o->op, &o->element, o->iterations, arena);
}

int cmd_morphology(const cli_entry *self, int argc, char **argv)
{
    static const char *const shapes[] = {"rect", "cross", "ellipse", NULL};
    morphology_options o = {.shape = RTE_MORPH_RECT, .ksize = 3, .iterations = 1};
    cli_option options[] = {
        {"shape", CLI_CHOICE, &o.shape, 0, 0, shapes, "structuring element", NULL},
        {"ksize", CLI_INT, &o.ksize, 1, RTE_MORPH_MAX_KSIZE, NULL, "element width", NULL},
        {"ksize-y", CLI_INT, &o.ksize_y, 0, RTE_MORPH_MAX_KSIZE, NULL,
         "element height, 0 = --ksize", NULL},
        {"iterations", CLI_INT, &o.iterations, 1, 100, NULL, "times applied", NULL},
        {0}};
    filter_spec spec = {
        "= cv2.erode / cv2.dilate / cv2.morphologyEx(MORPH_OPEN / MORPH_CLOSE) with\n"
        "cv2.getStructuringElement(shape, (ksize, ksize-y)) and iterations.",
        options,
        &o,
        morphology_prepare,
        morphology_scratch,
        morphology_apply,
        false,
        NULL};
    return cli_filter_main(self, argc, argv, &spec);
}

/* --- mask --- */

enum { MASK_MAX_VERTICES = 256 };

typedef struct mask_options {
    const char *polygon;
    bool mask_only;
    rte_vertex vertex[MASK_MAX_VERTICES];
    int32_t count;
} mask_options;

/* Parses "x,y;x,y;..." into at most `max` vertices; returns the count, or -1. */
static int parse_polygon(const char *text, rte_vertex *v, int max)
{
    int n = 0;
    const char *p = text;
    while (*p) {
        char *end;
        long x = strtol(p, &end, 10);
        if (end == p || *end != ',')
            return -1;
        p = end + 1;
        long y = strtol(p, &end, 10);
        if (end == p || (*end && *end != ';') || n >= max || x < -RTE_POLYGON_MAX_COORD ||
            x > RTE_POLYGON_MAX_COORD || y < -RTE_POLYGON_MAX_COORD || y > RTE_POLYGON_MAX_COORD)
            return -1;
        v[n].x = (int32_t)x;
        v[n].y = (int32_t)y;
        n++;
        p = *end ? end + 1 : end;
    }
    return n;
}

static int mask_prepare(const char *name, void *ctx)
{
    mask_options *o = ctx;
    o->count = o->polygon ? parse_polygon(o->polygon, o->vertex, MASK_MAX_VERTICES) : -1;
    if (o->count < 1) {
        cli_error(name, "--polygon needs \"x,y;x,y;...\": 1 to %d integer vertices within +-%d",
                  MASK_MAX_VERTICES, RTE_POLYGON_MAX_COORD);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

static size_t mask_scratch(void *ctx, int32_t w, int32_t h)
{
    return rte_polygon_mask_scratch_size(((mask_options *)ctx)->count);
}

static rte_status mask_apply(void *ctx, const rte_image_u8 *gray, rte_image_u8 *out,
                             rte_image_s16 *d, rte_arena *arena)
{
    mask_options *o = ctx;
    rte_polygon poly = {o->vertex, o->count};
    return o->mask_only ? rte_polygon_mask_build(out, &poly, 1, arena)
                        : rte_polygon_keep_u8(gray, &poly, 1, out, arena);
}

int cmd_mask(const cli_entry *self, int argc, char **argv)
{
    mask_options o = {0};
    cli_option options[] = {{"polygon", CLI_STRING, &o.polygon, 0, 0, NULL,
                             "vertices in pixels: \"x,y;x,y;...\" (required)", NULL},
                            {"mask-only", CLI_FLAG, &o.mask_only, 0, 0, NULL,
                             "write the 0/255 mask instead of the masked image", NULL},
                            {0}};
    filter_spec spec = {
        "= mask = zeros; cv2.fillPoly(mask, [pts], 255); cv2.bitwise_and(img, mask)\n"
        "Example (the lane tutorial's trapezoid on 960x540):\n"
        "  rtedge mask road.jpg roi.png --polygon \"0,540;460,310;500,310;960,540\"",
        options,
        &o,
        mask_prepare,
        mask_scratch,
        mask_apply,
        false,
        NULL};
    return cli_filter_main(self, argc, argv, &spec);
}
