/* The grasp path on an image file: `rtedge grasp` (grasp points as JSON)
 * and `rtedge shapes` (the shape table), both with an optional overlay. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "cli_image.h"
#include "cli_pipeline.h"
#include "commands.h"
#include "rtedge/grasp.h"

#define PIPELINE_DETAILS                                                                          \
    "IN: PGM/PPM, PNG or JPEG (colour becomes grey as cv2.cvtColor(cv2.imread(IN), BGR2GRAY)).\n" \
    "grey -> Gaussian blur -> Otsu, a fixed threshold or Canny + close -> external contours\n"    \
    "-> area filter -> features (moments, minimum-area box, hull, shape class)."

typedef struct grasp_run {
    const char *name;
    const char *paths[1];
    const char *overlay;
    cli_pipeline_options opts;
    cli_image in;
    rte_grasp_ctx *ctx;
    rte_grasp_result result;
} grasp_run;

/* Parses, loads and runs the pipeline. Returns CLI_EXIT_OK to go on, -1
 * after --help, or an exit code (everything freed then). */
static int grasp_start(grasp_run *run, const cli_entry *self, int argc, char **argv,
                       const char *details, int default_min_area)
{
    *run = (grasp_run){.name = self->name};
    cli_pipeline_defaults(&run->opts, 5, default_min_area);
    cli_option options[CLI_PIPELINE_OPTIONS + 2];
    int n = cli_pipeline_option_table(options, &run->opts, true);
    options[n] = (cli_option){"overlay",
                              CLI_STRING,
                              &run->overlay,
                              0,
                              0,
                              NULL,
                              "draw the objects on the input and write it here (.png, .ppm)",
                              NULL};
    options[n + 1] = (cli_option){0};
    cli_command cmd = {self->name, "IN", self->summary, details, options, 1};
    int rc = cli_parse(&cmd, argc, argv, run->paths);
    if (rc != CLI_EXIT_OK)
        return rc;
    rte_grasp_config config;
    if ((rc = cli_pipeline_config(self->name, &run->opts, 1, 1, &config)) != CLI_EXIT_OK)
        return rc;
    if ((rc = cli_load(self->name, run->paths[0], &run->in)) != CLI_EXIT_OK)
        return rc;
    const int32_t w = run->in.gray.width, h = run->in.gray.height;
    if (w > RTE_SHAPE_MAX_COORD + 1 || h > RTE_SHAPE_MAX_COORD + 1) {
        cli_error(self->name, "%s: %dx%d is larger than %d px a side", run->paths[0], w, h,
                  RTE_SHAPE_MAX_COORD + 1);
        cli_image_free(&run->in);
        return CLI_EXIT_INPUT;
    }
    cli_pipeline_config(self->name, &run->opts, w, h, &config);
    rte_status st = rte_grasp_create(&config, &run->ctx);
    if (st == RTE_OK)
        st = rte_grasp_process(run->ctx, &run->in.gray, &run->result);
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        rte_grasp_destroy(run->ctx);
        cli_image_free(&run->in);
        return CLI_EXIT_FAILURE;
    }
    return CLI_EXIT_OK;
}

static void grasp_end(grasp_run *run)
{
    rte_grasp_destroy(run->ctx);
    cli_image_free(&run->in);
}

/* The object's outline in its colour. */
static void draw_contour(rte_image_u8c3 *canvas, const rte_grasp_result *r,
                         const rte_grasp_object *o, rte_draw_color c)
{
    const rte_contour *ct = &r->contours->contours[o->contour];
    rte_draw_polyline(canvas, r->contours->points + ct->offset, ct->count, 1, c, 1);
}

static int32_t q8_px(int32_t v) { return (v + 128) >> 8; }

/* Draws with draw_object for every object and writes the overlay. */
static int overlay(grasp_run *run,
                   void (*draw_object)(rte_image_u8c3 *, const grasp_run *, int32_t))
{
    if (!run->overlay)
        return CLI_EXIT_OK;
    rte_image_u8c3 canvas;
    void *mem = cli_overlay_canvas(run->name, &run->in, &canvas);
    if (!mem)
        return CLI_EXIT_FAILURE;
    /* largest last, so small objects inside big ones stay visible */
    for (int32_t i = run->result.n_objects - 1; i >= 0; i--)
        draw_object(&canvas, run, i);
    int rc = cli_save_bgr(run->name, run->overlay, &canvas);
    free(mem);
    return rc;
}

static void draw_grasp(rte_image_u8c3 *canvas, const grasp_run *run, int32_t i)
{
    const rte_grasp_object *o = &run->result.objects[i];
    const rte_draw_color c = cli_overlay_color(i);
    draw_contour(canvas, &run->result, o, c);
    cli_overlay_box(canvas, o->info.box.corners_q8, (rte_draw_color){255, 255, 255});
    /* the jaws' closing line: across the short side, as long as the opening */
    const double a = o->angle_q16 / 65536.0 * 3.14159265358979323846 / 180.0;
    const double half = o->width_q8 / 512.0, x = o->x_q8 / 256.0, y = o->y_q8 / 256.0;
    const double dx = half * cos(a), dy = half * sin(a);
    rte_draw_line(canvas, (int32_t)(x - dx + 0.5), (int32_t)(y - dy + 0.5), (int32_t)(x + dx + 0.5),
                  (int32_t)(y + dy + 0.5), (rte_draw_color){0, 255, 255}, 2);
    rte_draw_dot(canvas, q8_px(o->x_q8), q8_px(o->y_q8), 3, (rte_draw_color){0, 0, 255});
    char label[48];
    snprintf(label, sizeof label, "%d %s", (int)i, rte_grasp_shape_name(o->info.shape));
    cli_overlay_label(canvas, o->info.bounds.x, o->info.bounds.y - 10, label, c);
}

static void print_q8_pair(int32_t x, int32_t y)
{
    printf("[");
    cli_print_q8(x);
    printf(",");
    cli_print_q8(y);
    printf("]");
}

int cmd_grasp(const cli_entry *self, int argc, char **argv)
{
    grasp_run run;
    int rc = grasp_start(
        &run, self, argc, argv,
        PIPELINE_DETAILS
        "\nGrasp: the centroid, the gripper closing across the short side of the\n"
        "minimum-area box (angle in degrees, image axes, y down), opened to that side.\n"
        "Prints {\"objects\":[{\"center\",\"angle\",\"width\",\"area\",\"shape\",\"box\"}],...}\n"
        "largest first.",
        100);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    const rte_grasp_result *r = &run.result;
    printf("{\"objects\":[");
    for (int32_t i = 0; i < r->n_objects; i++) {
        const rte_grasp_object *o = &r->objects[i];
        printf("%s{\"center\":", i ? "," : "");
        print_q8_pair(o->x_q8, o->y_q8);
        printf(",\"angle\":");
        cli_print_q16(o->angle_q16);
        printf(",\"width\":");
        cli_print_q8(o->width_q8);
        printf(",\"area\":");
        cli_print_q8(o->info.area2 * 128);
        printf(",\"shape\":\"%s\",\"box\":[", rte_grasp_shape_name(o->info.shape));
        for (int k = 0; k < 4; k++) {
            printf(k ? "," : "");
            print_q8_pair(o->info.box.corners_q8[k][0], o->info.box.corners_q8[k][1]);
        }
        printf("]}");
    }
    const rte_grasp_timing *t = &r->timing;
    printf("],\"threshold\":%d,\"truncated\":%s,\"dropped_objects\":%d,"
           "\"timing_ns\":{\"blur\":%lld,\"binarize\":%lld,\"contours\":%lld,\"features\":%lld,"
           "\"total\":%lld}}\n",
           (int)r->threshold, r->truncated ? "true" : "false", (int)r->dropped_objects,
           (long long)t->blur_ns, (long long)t->binarize_ns, (long long)t->contours_ns,
           (long long)t->features_ns, (long long)t->total_ns);
    rc = overlay(&run, draw_grasp);
    grasp_end(&run);
    return rc;
}

static void draw_shape(rte_image_u8c3 *canvas, const grasp_run *run, int32_t i)
{
    const rte_grasp_object *o = &run->result.objects[i];
    const rte_draw_color c = cli_overlay_color(i);
    draw_contour(canvas, &run->result, o, c);
    rte_draw_dot(canvas, q8_px(o->x_q8), q8_px(o->y_q8), 2, c);
    cli_overlay_label(canvas, q8_px(o->x_q8) - 20, q8_px(o->y_q8) + 5,
                      rte_grasp_shape_name(o->info.shape), c);
}

int cmd_shapes(const cli_entry *self, int argc, char **argv)
{
    grasp_run run;
    int rc = grasp_start(&run, self, argc, argv,
                         PIPELINE_DETAILS "\nPrints one line per object, largest first:\n"
                                          "  index shape area perimeter solidity aspect cx cy",
                         100);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    const rte_grasp_result *r = &run.result;
    printf("%-3s %-10s %10s %10s %8s %7s %8s %8s\n", "#", "shape", "area", "perimeter", "solidity",
           "aspect", "cx", "cy");
    for (int32_t i = 0; i < r->n_objects; i++) {
        const rte_shape_info *s = &r->objects[i].info;
        printf("%-3d %-10s %10.1f %10.2f %8.3f %7.3f %8.2f %8.2f\n", (int)i,
               rte_grasp_shape_name(s->shape), s->area2 / 2.0, s->perimeter_q16 / 65536.0,
               s->solidity_q16 / 65536.0, s->aspect_q16 / 65536.0, r->objects[i].x_q8 / 256.0,
               r->objects[i].y_q8 / 256.0);
    }
    if (r->truncated)
        printf("(truncated: %d more objects)\n", (int)r->dropped_objects);
    rc = overlay(&run, draw_shape);
    grasp_end(&run);
    return rc;
}
