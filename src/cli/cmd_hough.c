/* `rtedge lines`, `rtedge segments`, `rtedge circles`: the Hough transforms
 * on the edges of an image (optional blur, then Canny with the options of
 * `rtedge canny`) or on an edge map given as the input (--edges). JSON on
 * stdout; --overlay draws the result on the input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "cli_canny.h"
#include "cli_image.h"
#include "cli_pipeline.h"
#include "commands.h"
#include "rtedge/draw.h"
#include "rtedge/gradient.h"
#include "rtedge/hough.h"

#define PI 3.14159265358979323846

typedef enum hough_kind { HOUGH_LINES, HOUGH_SEGMENTS, HOUGH_CIRCLES } hough_kind;

typedef struct hough_run {
    hough_kind kind;
    canny_options canny;
    bool edges_given;
    const char *overlay;
    int max_out;
    double rho, theta, min_theta, max_theta;
    int threshold, min_length, max_gap, seed;
    double dp;
    int min_dist, votes, min_radius, max_radius, max_centres, max_votes;
} hough_run;

/* Everything per run: the edge map (and for circles the gradients), then
 * the transform and the JSON. */
typedef struct hough_buffers {
    rte_image_u8 blurred, edges;
    rte_image_s16 dx, dy;
    void *blurred_mem, *edges_mem, *dx_mem, *dy_mem, *arena_mem, *out_mem;
    rte_arena arena;
} hough_buffers;

static void free_buffers(hough_buffers *b)
{
    free(b->blurred_mem);
    free(b->edges_mem);
    free(b->dx_mem);
    free(b->dy_mem);
    free(b->arena_mem);
    free(b->out_mem);
}

static size_t transform_scratch(const hough_run *o, const rte_hough_config *cfg,
                                const rte_hough_circles_params *cp, int32_t w, int32_t h)
{
    switch (o->kind) {
    case HOUGH_LINES: return rte_hough_lines_scratch_size(cfg, o->max_out);
    case HOUGH_SEGMENTS: return rte_hough_segments_scratch_size(cfg);
    default:
        return cli_max_size(rte_hough_circles_scratch_size(w, h, cp),
                            rte_sobel_scratch_size(w, h, 3));
    }
}

/* The edge map: IN itself with --edges, else blur (when asked) and Canny;
 * for circles also the 3x3 Sobel derivatives of the (blurred) image: with
 * Canny's aperture 3 its own (BORDER_REPLICATE, as cv::HoughCircles), in
 * the same pass. */
static rte_status make_edges(hough_run *o, const rte_image_u8 *gray, hough_buffers *b)
{
    rte_status st = RTE_OK;
    const rte_image_u8 *src = gray;
    if (!o->edges_given && o->canny.blur_first) {
        if ((st = rte_gaussian_blur_u8(gray, &b->blurred, &o->canny.blur.kernel, &b->arena)) !=
            RTE_OK)
            return st;
        src = &b->blurred;
    }
    if (o->kind == HOUGH_CIRCLES && !o->edges_given && o->canny.aperture == 3) {
        rte_canny_params params;
        st = cli_canny_params(&o->canny, src, &params);
        return st == RTE_OK
                   ? rte_canny_gradient_u8(src, &b->edges, &b->dx, &b->dy, &params, &b->arena)
                   : st;
    }
    if (o->kind == HOUGH_CIRCLES) {
        if ((st = rte_sobel_s16(src, &b->dx, 1, 0, 3, &b->arena)) == RTE_OK)
            st = rte_sobel_s16(src, &b->dy, 0, 1, 3, &b->arena);
        if (st != RTE_OK)
            return st;
    }
    if (o->edges_given) {
        b->edges = *gray;
        return RTE_OK;
    }
    canny_options c = o->canny;
    c.blur_first = false; /* blurred above */
    return cli_canny_apply(&c, src, &b->edges, NULL, &b->arena);
}

static void draw_full_line(rte_image_u8c3 *img, double rho, double theta, rte_draw_color c)
{
    double cs = cos(theta), sn = sin(theta), far = 2.0 * (img->width + img->height);
    double x0 = rho * cs, y0 = rho * sn;
    rte_draw_line(img, (int32_t)lround(x0 - far * sn), (int32_t)lround(y0 + far * cs),
                  (int32_t)lround(x0 + far * sn), (int32_t)lround(y0 - far * cs), c, 1);
}

/* Scratch, the edge map (unless IN is one), the gradients (circles) and
 * the output array; false when one cannot be had (said on stderr). */
static bool alloc_buffers(const char *name, hough_run *o, const rte_hough_config *cfg,
                          const rte_hough_circles_params *cp, int32_t w, int32_t h,
                          hough_buffers *b)
{
    size_t scratch = transform_scratch(o, cfg, cp, w, h);
    if (!o->edges_given)
        scratch = cli_max_size(scratch, cli_canny_scratch(&o->canny, w, h));
    if (!(b->arena_mem = cli_new_arena(name, scratch, &b->arena)))
        return false;
    if (!o->edges_given && !(b->edges_mem = cli_new_u8(name, w, h, &b->edges)))
        return false;
    if (o->canny.blur_first && !o->edges_given &&
        !(b->blurred_mem = cli_new_u8(name, w, h, &b->blurred)))
        return false;
    if (o->kind == HOUGH_CIRCLES && (!(b->dx_mem = cli_new_s16(name, w, h, &b->dx)) ||
                                     !(b->dy_mem = cli_new_s16(name, w, h, &b->dy))))
        return false;
    size_t item = o->kind == HOUGH_LINES      ? sizeof(rte_hough_line)
                  : o->kind == HOUGH_SEGMENTS ? sizeof(rte_hough_segment)
                                              : sizeof(rte_hough_circle);
    b->out_mem = malloc((size_t)o->max_out * item + 1);
    return b->out_mem != NULL;
}

static rte_status transform(hough_run *o, const rte_hough_config *cfg,
                            const rte_hough_circles_params *cp, hough_buffers *b, int32_t *count,
                            bool *truncated)
{
    switch (o->kind) {
    case HOUGH_LINES:
        return rte_hough_lines(cfg, &b->edges, o->threshold, &b->arena, b->out_mem, o->max_out,
                               count, truncated);
    case HOUGH_SEGMENTS: {
        rte_hough_segments_params p = {o->threshold, o->min_length, o->max_gap, (uint32_t)o->seed};
        return rte_hough_segments(cfg, &b->edges, &p, &b->arena, b->out_mem, o->max_out, count,
                                  truncated);
    }
    default:
        return rte_hough_circles(&b->edges, &b->dx, &b->dy, cp, &b->arena, b->out_mem, o->max_out,
                                 count, truncated);
    }
}

/* The JSON (without its closing "truncated") and, onto canvas when given,
 * the overlay. */
static void print_results(const hough_run *o, const rte_hough_config *cfg, const void *out,
                          int32_t count, rte_image_u8c3 *canvas)
{
    const rte_draw_color red = {0, 0, 255}, green = {0, 255, 0};
    if (o->kind == HOUGH_LINES) {
        const rte_hough_line *l = out;
        printf("{\"lines\":[");
        for (int32_t i = 0; i < count; i++) {
            double rho = rte_hough_line_rho(cfg, &l[i]), theta = rte_hough_line_theta(cfg, &l[i]);
            printf("%s{\"rho\":%.9g,\"theta\":%.9g,\"votes\":%d}", i ? "," : "", rho, theta,
                   (int)l[i].votes);
            if (canvas)
                draw_full_line(canvas, rho, theta, red);
        }
    } else if (o->kind == HOUGH_SEGMENTS) {
        const rte_hough_segment *s = out;
        printf("{\"segments\":[");
        for (int32_t i = 0; i < count; i++) {
            printf("%s{\"x1\":%d,\"y1\":%d,\"x2\":%d,\"y2\":%d}", i ? "," : "", (int)s[i].x0,
                   (int)s[i].y0, (int)s[i].x1, (int)s[i].y1);
            if (canvas)
                rte_draw_line(canvas, s[i].x0, s[i].y0, s[i].x1, s[i].y1, red, 2);
        }
    } else {
        const rte_hough_circle *c = out;
        printf("{\"circles\":[");
        for (int32_t i = 0; i < count; i++) {
            printf("%s{\"x\":%.4g,\"y\":%.4g,\"r\":%.4g,\"votes\":%d}", i ? "," : "",
                   c[i].x_q4 / 16.0, c[i].y_q4 / 16.0, c[i].r_q4 / 16.0, (int)c[i].votes);
            if (canvas) {
                int32_t x = (c[i].x_q4 + 8) >> 4, y = (c[i].y_q4 + 8) >> 4;
                rte_draw_circle(canvas, x, y, (c[i].r_q4 + 8) >> 4, green, 2);
                rte_draw_dot(canvas, x, y, 2, red);
            }
        }
    }
}

static int hough_main(const cli_entry *self, int argc, char **argv, hough_run *o, cli_option *extra,
                      int n_extra, const char *details)
{
    cli_option options[CLI_CANNY_OPTIONS + 16];
    int n = cli_canny_option_rows(options, &o->canny);
    options[n++] = (cli_option){"edges",
                                CLI_FLAG,
                                &o->edges_given,
                                0,
                                0,
                                NULL,
                                "IN is an edge map (non-zero = edge): no blur, no Canny",
                                NULL};
    options[n++] = (cli_option){"overlay",
                                CLI_STRING,
                                &o->overlay,
                                0,
                                0,
                                NULL,
                                "draw the result on the input into this .png/.ppm",
                                NULL};
    for (int i = 0; i < n_extra; i++)
        options[n++] = extra[i];
    options[n] = (cli_option){0};
    cli_command cmd = {self->name, "IN", self->summary, details, options, 1};
    const char *path[1];
    int rc = cli_parse(&cmd, argc, argv, path);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if ((rc = cli_canny_prepare(self->name, &o->canny)) != CLI_EXIT_OK)
        return rc;
    rte_hough_circles_params cp = {(int32_t)lround(o->dp * 256),
                                   o->min_dist,
                                   o->votes,
                                   o->min_radius,
                                   o->max_radius,
                                   o->max_centres,
                                   o->max_votes};

    cli_image in;
    if ((rc = cli_load(self->name, path[0], &in)) != CLI_EXIT_OK)
        return rc;
    const int32_t w = in.gray.width, h = in.gray.height;
    rte_hough_config cfg;
    rte_status st = RTE_OK;
    if (o->kind != HOUGH_CIRCLES)
        st = rte_hough_config_init(&cfg, w, h, o->rho, o->theta, o->min_theta, o->max_theta);
    if (st != RTE_OK) {
        cli_error(self->name, "--rho %g --theta %g --min-theta %g --max-theta %g: %s", o->rho,
                  o->theta, o->min_theta, o->max_theta, rte_status_message(st));
        cli_image_free(&in);
        return CLI_EXIT_USAGE;
    }
    hough_buffers b = {0};
    if (!alloc_buffers(self->name, o, &cfg, &cp, w, h, &b)) {
        free_buffers(&b);
        cli_image_free(&in);
        return CLI_EXIT_FAILURE;
    }

    int32_t count = 0;
    bool truncated = false;
    st = make_edges(o, &in.gray, &b);
    if (st == RTE_OK)
        st = transform(o, &cfg, &cp, &b, &count, &truncated);
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        free_buffers(&b);
        cli_image_free(&in);
        return CLI_EXIT_FAILURE;
    }

    rte_image_u8c3 canvas;
    void *canvas_mem = o->overlay ? cli_overlay_canvas(self->name, &in, &canvas) : NULL;
    print_results(o, &cfg, b.out_mem, count, canvas_mem ? &canvas : NULL);
    printf("],\"truncated\":%s}\n", truncated ? "true" : "false");
    rc = CLI_EXIT_OK;
    if (o->overlay)
        rc = canvas_mem ? cli_save_bgr(self->name, o->overlay, &canvas) : CLI_EXIT_FAILURE;
    free(canvas_mem);
    free_buffers(&b);
    cli_image_free(&in);
    return rc;
}

#define EDGES_DETAILS                                                                              \
    "IN: PGM/PPM, PNG or JPEG (grey as cv2.cvtColor(cv2.imread(IN), COLOR_BGR2GRAY)). Edges are\n" \
    "cv2.Canny(cv2.GaussianBlur(img, (blur, blur), sigma), low, high) as `rtedge canny` makes "    \
    "them\n"                                                                                       \
    "(same options), or IN itself with --edges. theta in radians, coordinates in pixels.\n"

/* The accumulator resolution options of lines and segments. */
#define RESOLUTION_ROWS(o)                                                                     \
    {"rho", CLI_DOUBLE, &(o).rho, 0.015625, 65536, NULL, "distance resolution, pixels", NULL}, \
    {                                                                                          \
        "theta", CLI_DOUBLE, &(o).theta, 1e-4, 3.2, NULL, "angle resolution, radians", NULL    \
    }

int cmd_lines(const cli_entry *self, int argc, char **argv)
{
    hough_run o = {.kind = HOUGH_LINES,
                   .canny = cli_canny_defaults(),
                   .max_out = 256,
                   .rho = 1,
                   .theta = PI / 180,
                   .max_theta = PI,
                   .threshold = 100};
    cli_option extra[] = {
        RESOLUTION_ROWS(o),
        {"min-theta", CLI_DOUBLE, &o.min_theta, -64, 64, NULL, "smallest angle, radians", NULL},
        {"max-theta", CLI_DOUBLE, &o.max_theta, -64, 64, NULL, "largest angle, radians", NULL},
        {"threshold", CLI_INT, &o.threshold, 0, 1e9, NULL, "a line needs more votes than this",
         NULL},
        {"max", CLI_INT, &o.max_out, 0, 1 << 20, NULL, "most lines reported (then truncated: true)",
         NULL}};
    return hough_main(self, argc, argv, &o, extra, (int)(sizeof extra / sizeof extra[0]),
                      EDGES_DETAILS
                      "= cv2.HoughLines(edges, rho, theta, threshold, min_theta=, max_theta=)\n"
                      "(integer accumulator; sorted by votes, then theta, then rho).\n"
                      "Prints {\"lines\":[{\"rho\",\"theta\",\"votes\"}],\"truncated\":false}.");
}

int cmd_segments(const cli_entry *self, int argc, char **argv)
{
    hough_run o = {.kind = HOUGH_SEGMENTS,
                   .canny = cli_canny_defaults(),
                   .max_out = 4096,
                   .rho = 1,
                   .theta = PI / 180,
                   .max_theta = PI,
                   .threshold = 50,
                   .min_length = 30,
                   .max_gap = 10};
    cli_option extra[] = {
        RESOLUTION_ROWS(o),
        {"threshold", CLI_INT, &o.threshold, 1, 1e9, NULL, "accumulator votes a line needs", NULL},
        {"min-length", CLI_INT, &o.min_length, 0, 65535, NULL,
         "shortest segment (Euclidean), pixels", NULL},
        {"max-gap", CLI_INT, &o.max_gap, 0, 1e6, NULL, "longest gap bridged, pixels", NULL},
        {"seed", CLI_INT, &o.seed, 0, INT32_MAX, NULL,
         "point order of the search, 0 = RTE_HOUGH_SEGMENTS_SEED", NULL},
        {"max", CLI_INT, &o.max_out, 0, 1 << 20, NULL,
         "most segments reported (then truncated: true)", NULL}};
    return hough_main(self, argc, argv, &o, extra, (int)(sizeof extra / sizeof extra[0]),
                      EDGES_DETAILS
                      "~ cv2.HoughLinesP(edges, rho, theta, threshold, minLineLength=min-length,\n"
                      "maxLineGap=max-gap), deterministic; deviations in docs/hough.md.\n"
                      "Prints {\"segments\":[{\"x1\",\"y1\",\"x2\",\"y2\"}],\"truncated\":false}.");
}

int cmd_circles(const cli_entry *self, int argc, char **argv)
{
    hough_run o = {.kind = HOUGH_CIRCLES,
                   .canny = cli_canny_defaults(),
                   .max_out = 256,
                   .dp = 1,
                   .min_dist = 20,
                   .votes = 30};
    o.canny.low = 50;
    o.canny.high = 100;
    cli_option extra[] = {
        {"dp", CLI_DOUBLE, &o.dp, 1, 64, NULL, "inverse accumulator resolution", NULL},
        {"min-dist", CLI_INT, &o.min_dist, 1, 1e6, NULL,
         "smallest distance between centres, pixels", NULL},
        {"votes", CLI_INT, &o.votes, 1, 1e9, NULL, "param2: accumulator votes a centre needs",
         NULL},
        {"min-radius", CLI_INT, &o.min_radius, 0, 65535, NULL, "smallest radius, pixels", NULL},
        {"max-radius", CLI_INT, &o.max_radius, 0, 65535, NULL,
         "largest radius, pixels; 0 = image size", NULL},
        {"max-centres", CLI_INT, &o.max_centres, 0, 1 << 30, NULL,
         "budget: most candidate centres given a radius, the strongest (then truncated: true); "
         "0 = RTE_HOUGH_CIRCLES_MAX_CENTRES",
         NULL},
        {"max-votes", CLI_INT, &o.max_votes, 0, 2147483647, NULL,
         "budget: most accumulator votes, the first edge pixels' in raster order (then "
         "truncated: true); 0 = RTE_HOUGH_CIRCLES_VOTES_PER_PIXEL per image pixel",
         NULL},
        {"max", CLI_INT, &o.max_out, 0, 1 << 20, NULL,
         "most circles reported (then truncated: true)", NULL}};
    return hough_main(
        self, argc, argv, &o, extra, (int)(sizeof extra / sizeof extra[0]),
        EDGES_DETAILS
        "Gradients: 3x3 Sobel of the (blurred) image or of IN with --edges.\n"
        "= cv2.HoughCircles(blurred, HOUGH_GRADIENT, dp, min-dist, param1=high,\n"
        "param2=votes, minRadius=, maxRadius=) with --low = high / 2 (the defaults).\n"
        "Prints {\"circles\":[{\"x\",\"y\",\"r\",\"votes\"}],\"truncated\":false}.");
}
