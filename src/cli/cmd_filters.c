/* Subcommands that run one librtedge kernel on an image file: read IN (grey,
 * or colour converted to grey as OpenCV does), run the kernel, write OUT. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_image.h"
#include "commands.h"
#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/gradient.h"
#include "rtedge/morphology.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/threshold.h"

/* One run of a filter subcommand: the input, the u8 output, scratch. */
typedef struct filter_run {
    const char *name;
    const char *paths[2]; /* IN, OUT */
    cli_image in;
    rte_image_u8 out;
    void *out_memory;
    rte_arena arena;
    void *arena_memory;
} filter_run;

/* Parses the command line. Returns CLI_EXIT_OK to go on, -1 after --help
 * (exit 0), or an exit code. */
static int filter_parse(filter_run *run, const cli_command *cmd, int argc, char **argv)
{
    memset(run, 0, sizeof *run);
    run->name = cmd->name;
    return cli_parse(cmd, argc, argv, run->paths);
}

/* Reads IN (after the options were checked, so usage errors come first). */
static int filter_load(filter_run *run)
{
    return cli_load(run->name, run->paths[0], &run->in);
}

/* Allocates the u8 output (same size as the input) and `scratch` bytes of arena. */
static int filter_buffers(filter_run *run, size_t scratch)
{
    run->out_memory = cli_new_u8(run->name, run->in.gray.width, run->in.gray.height, &run->out);
    run->arena_memory = cli_new_arena(run->name, scratch, &run->arena);
    return run->out_memory && run->arena_memory ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
}

/* Reports a kernel's status, writes OUT on success (the int16 image `s16`
 * when given, else the u8 output), frees everything. */
static int filter_end_s16(filter_run *run, rte_status st, const rte_image_s16 *s16)
{
    int rc = CLI_EXIT_OK;
    if (st != RTE_OK) {
        cli_error(run->name, "%s", rte_status_message(st));
        rc = CLI_EXIT_FAILURE;
    } else if (s16) {
        rc = cli_save_s16(run->name, run->paths[1], s16);
    } else {
        rc = cli_save_gray(run->name, run->paths[1], &run->out);
    }
    cli_image_free(&run->in);
    free(run->out_memory);
    free(run->arena_memory);
    return rc;
}

static int filter_end(filter_run *run, rte_status st)
{
    return filter_end_s16(run, st, NULL);
}

#define FILTER_USAGE "IN OUT"
#define FILTER_DETAILS \
    "IN: PGM/PPM (P2, P3, P5, P6), PNG or JPEG; colour is converted to grey as\n" \
    "cv2.cvtColor(cv2.imread(IN), cv2.COLOR_BGR2GRAY) does. OUT: .pgm, .png or .npy."

int cmd_gray(const cli_entry *self, int argc, char **argv)
{
    cli_option options[] = {{0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary, FILTER_DETAILS, options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rc = cli_save_gray(run.name, run.paths[1], &run.in.gray);
    cli_image_free(&run.in);
    return rc;
}

/* Gaussian blur options shared by blur, log and canny. */
typedef struct blur_options {
    int ksize;
    double sigma;
    int ksize_y;
    double sigma_y;
} blur_options;

/* Builds the Gaussian kernel; CLI_EXIT_USAGE after a message when the
 * options do not make one. */
static int blur_kernel(const char *name, const blur_options *o, rte_gaussian_kernel *k)
{
    rte_status st = rte_gaussian_kernel_init(k, o->ksize, o->ksize_y < 0 ? o->ksize : o->ksize_y,
                                             o->sigma, o->sigma_y);
    if (st != RTE_OK) {
        cli_error(name, "Gaussian kernel size %d, sigma %g: %s", o->ksize, o->sigma,
                  rte_status_message(st));
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

int cmd_blur(const cli_entry *self, int argc, char **argv)
{
    blur_options b = {5, 0.0, -1, 0.0};
    cli_option options[] = {
        {"ksize", CLI_INT, &b.ksize, 0, RTE_GAUSSIAN_MAX_KSIZE, NULL, "odd kernel size, 0 = from --sigma", NULL},
        {"sigma", CLI_DOUBLE, &b.sigma, 0, 100, NULL, "sigma, 0 = from the kernel size", NULL},
        {"ksize-y", CLI_INT, &b.ksize_y, -1, RTE_GAUSSIAN_MAX_KSIZE, NULL, "vertical size, -1 = --ksize", NULL},
        {"sigma-y", CLI_DOUBLE, &b.sigma_y, 0, 100, NULL, "vertical sigma, 0 = --sigma", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       FILTER_DETAILS "\n= cv2.GaussianBlur(img, (ksize, ksize-y), sigma, sigmaY=sigma-y)",
                       options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    rte_gaussian_kernel k;
    if ((rc = blur_kernel(self->name, &b, &k)) != CLI_EXIT_OK || (rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rte_status st;
    size_t scratch = rte_gaussian_blur_u8_scratch_size(run.in.gray.width, run.in.gray.height, &k);
    if ((rc = filter_buffers(&run, scratch)) == CLI_EXIT_OK)
        st = rte_gaussian_blur_u8(&run.in.gray, &run.out, &k, &run.arena);
    return filter_end(&run, rc == CLI_EXIT_OK ? st : RTE_ERR_NO_MEMORY);
}

int cmd_median(const cli_entry *self, int argc, char **argv)
{
    int ksize = 3;
    cli_option options[] = {{"ksize", CLI_INT, &ksize, 1, 5, NULL, "aperture: 1, 3 or 5", NULL}, {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       FILTER_DETAILS "\n= cv2.medianBlur(img, ksize)", options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (ksize % 2 == 0) {
        cli_error(self->name, "--ksize must be 1, 3 or 5");
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rte_status st = RTE_ERR_NO_MEMORY;
    size_t scratch = rte_median_blur_u8_scratch_size(run.in.gray.width, run.in.gray.height, ksize);
    if (filter_buffers(&run, scratch) == CLI_EXIT_OK)
        st = rte_median_blur_u8(&run.in.gray, &run.out, ksize, &run.arena);
    return filter_end(&run, st);
}

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

/* An int16 result goes to OUT as is when OUT is .npy, otherwise as its
 * saturated absolute value (cv2.convertScaleAbs) in an 8-bit image. */
static int derivative_end(filter_run *run, rte_status st, rte_image_s16 *d, void *d_memory)
{
    bool npy = has_extension(run->paths[1], ".npy");
    if (st == RTE_OK && !npy)
        st = rte_abs_s16_u8(d, &run->out);
    int rc = filter_end_s16(run, st, npy ? d : NULL);
    free(d_memory);
    return rc;
}

/* Buffers of a derivative run: u8 output, s16 result, scratch. */
static void *derivative_buffers(filter_run *run, size_t scratch, rte_image_s16 *d)
{
    void *d_memory = cli_new_s16(run->name, run->in.gray.width, run->in.gray.height, d);
    if (filter_buffers(run, scratch) != CLI_EXIT_OK) {
        free(d_memory);
        return NULL;
    }
    return d_memory;
}

#define DERIVATIVE_DETAILS \
    FILTER_DETAILS "\nOUT .npy holds the int16 result; .pgm/.png its saturated absolute value\n" \
    "(cv2.convertScaleAbs)."

int cmd_sobel(const cli_entry *self, int argc, char **argv)
{
    int dx = 1, dy = 0, ksize = 3;
    cli_option options[] = {
        {"dx", CLI_INT, &dx, 0, 2, NULL, "order of the x derivative", NULL},
        {"dy", CLI_INT, &dy, 0, 2, NULL, "order of the y derivative", NULL},
        {"ksize", CLI_INT, &ksize, 1, 7, NULL, "aperture: 1, 3, 5 or 7", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       DERIVATIVE_DETAILS "\n= cv2.Sobel(img, cv2.CV_16S, dx, dy, ksize=ksize)", options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (ksize % 2 == 0 || dx + dy == 0 || (ksize == 1 && (dx > 2 || dy > 2))) {
        cli_error(self->name, "--ksize must be odd and dx + dy at least 1");
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rte_image_s16 d;
    void *d_memory = derivative_buffers(&run, rte_sobel_scratch_size(run.in.gray.width, run.in.gray.height, ksize), &d);
    rte_status st = d_memory ? rte_sobel_s16(&run.in.gray, &d, dx, dy, ksize, &run.arena) : RTE_ERR_NO_MEMORY;
    return derivative_end(&run, st, &d, d_memory);
}

int cmd_scharr(const cli_entry *self, int argc, char **argv)
{
    int dx = 1, dy = 0;
    cli_option options[] = {
        {"dx", CLI_INT, &dx, 0, 1, NULL, "x derivative (dx + dy = 1)", NULL},
        {"dy", CLI_INT, &dy, 0, 1, NULL, "y derivative", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       DERIVATIVE_DETAILS "\n= cv2.Scharr(img, cv2.CV_16S, dx, dy)", options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (dx + dy != 1) {
        cli_error(self->name, "exactly one of --dx 1 and --dy 1");
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rte_image_s16 d;
    void *d_memory = derivative_buffers(&run, rte_scharr_scratch_size(run.in.gray.width, run.in.gray.height), &d);
    rte_status st = d_memory ? rte_scharr_s16(&run.in.gray, &d, dx, dy, &run.arena) : RTE_ERR_NO_MEMORY;
    return derivative_end(&run, st, &d, d_memory);
}

int cmd_laplacian(const cli_entry *self, int argc, char **argv)
{
    int ksize = 1;
    cli_option options[] = {{"ksize", CLI_INT, &ksize, 1, 3, NULL, "aperture: 1 or 3", NULL}, {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       DERIVATIVE_DETAILS "\n= cv2.Laplacian(img, cv2.CV_16S, ksize=ksize)", options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (ksize == 2) {
        cli_error(self->name, "--ksize must be 1 or 3");
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rte_image_s16 d;
    void *d_memory = derivative_buffers(&run, rte_laplacian_scratch_size(run.in.gray.width, run.in.gray.height, ksize), &d);
    rte_status st = d_memory ? rte_laplacian_s16(&run.in.gray, &d, ksize, &run.arena) : RTE_ERR_NO_MEMORY;
    return derivative_end(&run, st, &d, d_memory);
}

static size_t max_size(size_t a, size_t b) { return a > b ? a : b; }

int cmd_log(const cli_entry *self, int argc, char **argv)
{
    blur_options b = {3, 0.0, -1, 0.0};
    int ksize = 1;
    cli_option options[] = {
        {"blur", CLI_INT, &b.ksize, 0, RTE_GAUSSIAN_MAX_KSIZE, NULL, "Gaussian kernel size, 0 = from --sigma", NULL},
        {"sigma", CLI_DOUBLE, &b.sigma, 0, 100, NULL, "Gaussian sigma, 0 = from the size", NULL},
        {"ksize", CLI_INT, &ksize, 1, 3, NULL, "Laplacian aperture: 1 or 3", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       DERIVATIVE_DETAILS "\n= cv2.Laplacian(cv2.GaussianBlur(img, (blur, blur), sigma), cv2.CV_16S, ksize=ksize)",
                       options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    rte_gaussian_kernel k;
    if (ksize == 2) {
        cli_error(self->name, "--ksize must be 1 or 3");
        return CLI_EXIT_USAGE;
    }
    if ((rc = blur_kernel(self->name, &b, &k)) != CLI_EXIT_OK || (rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    int32_t w = run.in.gray.width, h = run.in.gray.height;
    rte_image_s16 d;
    void *d_memory = derivative_buffers(&run, max_size(rte_gaussian_blur_u8_scratch_size(w, h, &k),
                                                       rte_laplacian_scratch_size(w, h, ksize)), &d);
    rte_status st = RTE_ERR_NO_MEMORY;
    if (d_memory) {
        /* The blurred image lives in run.out until the Laplacian has read it. */
        st = rte_gaussian_blur_u8(&run.in.gray, &run.out, &k, &run.arena);
        if (st == RTE_OK)
            st = rte_laplacian_s16(&run.out, &d, ksize, &run.arena);
    }
    return derivative_end(&run, st, &d, d_memory);
}

int cmd_canny(const cli_entry *self, int argc, char **argv)
{
    static const char *const auto_rules[] = {"none", "median", "otsu", NULL};
    double low = 50, high = 150, auto_sigma = 0.33;
    int aperture = 3, auto_rule = 0;
    bool l2 = false;
    blur_options b = {0, 0.0, -1, 0.0};
    cli_option options[] = {
        {"low", CLI_DOUBLE, &low, -1e6, 1e6, NULL, "lower hysteresis threshold", NULL},
        {"high", CLI_DOUBLE, &high, -1e6, 1e6, NULL, "upper hysteresis threshold", NULL},
        {"aperture", CLI_INT, &aperture, 3, 5, NULL, "Sobel aperture: 3 or 5", NULL},
        {"l2", CLI_FLAG, &l2, 0, 0, NULL, "L2 gradient magnitude (squared, as OpenCV compares it)", NULL},
        {"blur", CLI_INT, &b.ksize, 0, RTE_GAUSSIAN_MAX_KSIZE, NULL, "Gaussian blur first with this odd size; 0 = none unless --sigma", NULL},
        {"sigma", CLI_DOUBLE, &b.sigma, 0, 100, NULL, "Gaussian sigma of that blur", NULL},
        {"auto", CLI_CHOICE, &auto_rule, 0, 0, auto_rules, "thresholds from the image: median rule or Otsu rule", NULL},
        {"auto-sigma", CLI_DOUBLE, &auto_sigma, 0, 1, NULL, "s of the median rule", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       FILTER_DETAILS "\n= cv2.Canny(cv2.GaussianBlur(img, (blur, blur), sigma), low, high,\n"
                       "            apertureSize=aperture, L2gradient=l2)\n"
                       "--auto median: low = max(0, (1-s) * median), high = min(255, (1+s) * median),\n"
                       "truncated to integers; --auto otsu: high = Otsu's threshold, low = high / 2.\n"
                       "Prints the thresholds used as JSON.",
                       options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (aperture != 3 && aperture != 5) {
        cli_error(self->name, "--aperture must be 3 or 5");
        return CLI_EXIT_USAGE;
    }
    bool blur = b.ksize > 0 || b.sigma > 0;
    rte_gaussian_kernel k;
    if (blur && (rc = blur_kernel(self->name, &b, &k)) != CLI_EXIT_OK)
        return rc;
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    int32_t w = run.in.gray.width, h = run.in.gray.height;
    rte_image_u8 blurred = {0};
    void *blurred_memory = blur ? cli_new_u8(self->name, w, h, &blurred) : NULL;
    size_t scratch = rte_canny_scratch_size(w, h, aperture);
    if (blur)
        scratch = max_size(scratch, rte_gaussian_blur_u8_scratch_size(w, h, &k));
    rte_status st = RTE_ERR_NO_MEMORY;
    if ((!blur || blurred_memory) && filter_buffers(&run, scratch) == CLI_EXIT_OK) {
        const rte_image_u8 *src = &run.in.gray;
        st = RTE_OK;
        if (blur) {
            st = rte_gaussian_blur_u8(src, &blurred, &k, &run.arena);
            src = &blurred;
        }
        if (st == RTE_OK && auto_rule) {
            uint32_t hist[256];
            int32_t lo = 0, hi = 0;
            st = rte_histogram_u8(src, hist);
            if (st == RTE_OK && auto_rule == 1)
                st = rte_threshold_auto_canny_median(hist, (int32_t)(auto_sigma * 1000 + 0.5), &lo, &hi);
            else if (st == RTE_OK)
                st = rte_threshold_auto_canny_otsu(hist, &lo, &hi);
            low = lo;
            high = hi;
        }
        rte_canny_params params;
        if (st == RTE_OK)
            st = rte_canny_params_init(&params, low, high, aperture, l2);
        if (st == RTE_OK)
            st = rte_canny_u8(src, &run.out, &params, &run.arena);
        if (st == RTE_OK)
            printf("{\"low\":%g,\"high\":%g}\n", low, high);
    }
    free(blurred_memory);
    return filter_end(&run, st);
}

int cmd_threshold(const cli_entry *self, int argc, char **argv)
{
    static const char *const types[] = {"binary", "binary_inv", "trunc", "tozero", "tozero_inv", NULL};
    double value = 127, maxval = 255;
    int type = 0;
    bool otsu = false;
    cli_option options[] = {
        {"value", CLI_DOUBLE, &value, -1e6, 1e6, NULL, "threshold (ignored with --otsu)", NULL},
        {"maxval", CLI_DOUBLE, &maxval, -1e6, 1e6, NULL, "value for binary and binary_inv", NULL},
        {"type", CLI_CHOICE, &type, 0, 0, types, "threshold type", NULL},
        {"otsu", CLI_FLAG, &otsu, 0, 0, NULL, "Otsu's threshold from the image's histogram", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       FILTER_DETAILS "\n= cv2.threshold(img, value, maxval, type [+ cv2.THRESH_OTSU]);\n"
                       "prints the threshold used as JSON: {\"threshold\":T}.",
                       options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    rte_threshold_params params;
    rte_status st = rte_threshold_params_init(&params, (rte_threshold_type)type, value, maxval, otsu);
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    int32_t used = 0;
    st = RTE_ERR_NO_MEMORY;
    if (filter_buffers(&run, 0) == CLI_EXIT_OK)
        st = rte_threshold_u8(&run.in.gray, &run.out, &params, &used);
    if (st == RTE_OK)
        printf("{\"threshold\":%d}\n", used);
    return filter_end(&run, st);
}

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

int cmd_mask(const cli_entry *self, int argc, char **argv)
{
    enum { MAX_VERTICES = 256 };
    const char *polygon = NULL;
    bool mask_only = false;
    cli_option options[] = {
        {"polygon", CLI_STRING, &polygon, 0, 0, NULL, "vertices in pixels: \"x,y;x,y;...\" (required)", NULL},
        {"mask-only", CLI_FLAG, &mask_only, 0, 0, NULL, "write the 0/255 mask instead of the masked image", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       FILTER_DETAILS "\n= mask = zeros; cv2.fillPoly(mask, [pts], 255); cv2.bitwise_and(img, mask)\n"
                       "Example (the lane tutorial's trapezoid on 960x540):\n"
                       "  rtedge mask road.jpg roi.png --polygon \"0,540;460,310;500,310;960,540\"",
                       options, 2};
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    rte_vertex vertices[MAX_VERTICES];
    int count = polygon ? parse_polygon(polygon, vertices, MAX_VERTICES) : -1;
    if (count < 1) {
        cli_error(self->name, "--polygon needs \"x,y;x,y;...\": 1 to %d integer vertices within +-%d",
                  MAX_VERTICES, RTE_POLYGON_MAX_COORD);
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    rte_polygon poly = {vertices, count};
    rte_status st = RTE_ERR_NO_MEMORY;
    if (filter_buffers(&run, rte_polygon_mask_scratch_size(count)) == CLI_EXIT_OK) {
        st = rte_polygon_mask_build(&run.out, &poly, 1, &run.arena);
        if (st == RTE_OK && !mask_only)
            st = rte_polygon_mask_apply(&run.in.gray, &run.out, &run.out);
    }
    return filter_end(&run, st);
}

/* erode, dilate, open and close: the subcommand's name is the operation. */
int cmd_morphology(const cli_entry *self, int argc, char **argv)
{
    static const char *const shapes[] = {"rect", "cross", "ellipse", NULL};
    static const char *const ops[] = {"erode", "dilate", "open", "close", NULL};
    int shape = RTE_MORPH_RECT, ksize = 3, ksize_y = 0, iterations = 1;
    cli_option options[] = {
        {"shape", CLI_CHOICE, &shape, 0, 0, shapes, "structuring element", NULL},
        {"ksize", CLI_INT, &ksize, 1, RTE_MORPH_MAX_KSIZE, NULL, "element width", NULL},
        {"ksize-y", CLI_INT, &ksize_y, 0, RTE_MORPH_MAX_KSIZE, NULL, "element height, 0 = --ksize", NULL},
        {"iterations", CLI_INT, &iterations, 1, 100, NULL, "times applied", NULL},
        {0}};
    cli_command cmd = {self->name, FILTER_USAGE, self->summary,
                       FILTER_DETAILS "\n= cv2.erode / cv2.dilate / cv2.morphologyEx(MORPH_OPEN / MORPH_CLOSE) with\n"
                       "cv2.getStructuringElement(shape, (ksize, ksize-y)) and iterations.",
                       options, 2};
    int op = 0;
    while (ops[op] && strcmp(ops[op], self->name) != 0)
        op++;
    filter_run run;
    int rc = filter_parse(&run, &cmd, argc, argv);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    rte_morph_element element;
    rte_status st = rte_morphology_element_init(&element, (rte_morph_shape)shape, ksize,
                                                ksize_y ? ksize_y : ksize);
    if (st != RTE_OK) {
        cli_error(self->name, "element %s %dx%d: %s", shapes[shape], ksize, ksize_y ? ksize_y : ksize,
                  rte_status_message(st));
        return CLI_EXIT_USAGE;
    }
    if ((rc = filter_load(&run)) != CLI_EXIT_OK)
        return rc;
    size_t scratch = rte_morphology_scratch_size(run.in.gray.width, run.in.gray.height, &element, iterations);
    st = RTE_ERR_NO_MEMORY;
    if (filter_buffers(&run, scratch) == CLI_EXIT_OK)
        st = rte_morphology_u8(&run.in.gray, &run.out, (rte_morph_op)op, &element, iterations, &run.arena);
    return filter_end(&run, st);
}
