/* The grasp path on an image file: `rtedge grasp` (grasp points as JSON)
 * and `rtedge shapes` (the shape table), both with an optional overlay. */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "cli_image.h"
#include "cli_pipeline.h"
#include "commands.h"
#include "rtedge/overlay.h"
#include "rtedge/grasp.h"

#define PIPELINE_DETAILS                                                                         \
    "IN: PGM/PPM, PNG or JPEG (colour becomes grey as cv2.cvtColor(cv2.imread(IN), BGR2GRAY);\n" \
    "background mode: its colour differences from the table count as contrast too).\n"           \
    "grey -> Gaussian blur -> |grey - table| both ways (background), Otsu, a fixed threshold\n"  \
    "or Canny + close -> external contours -> area and border filters -> features (moments,\n"   \
    "minimum-area box, hull, shape class). grasp: background, border objects dropped;\n"         \
    "shapes: Otsu, border objects kept (the OpenCV tutorial's shape analysis)."

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
                       const char *details, int default_min_area, bool tutorial)
{
    *run = (grasp_run){.name = self->name};
    cli_pipeline_defaults(&run->opts, 5, default_min_area, tutorial);
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
        st = cli_grasp_process(run->ctx, &run->in, &run->result);
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

static int32_t q8_px(int32_t v) { return (v + 128) >> 8; }

/* Draws the objects with draw and writes the overlay. */
static int overlay(grasp_run *run, void (*draw)(rte_overlay *, const grasp_run *))
{
    if (!run->overlay)
        return CLI_EXIT_OK;
    rte_overlay o = {.scale_q16 = 65536};
    void *mem = cli_overlay_canvas(run->name, &run->in, &o.canvas);
    if (!mem)
        return CLI_EXIT_FAILURE;
    draw(&o, run);
    int rc = cli_save_bgr(run->name, run->overlay, &o.canvas);
    free(mem);
    return rc;
}

static void draw_grasp(rte_overlay *o, const grasp_run *run)
{
    rte_overlay_grasp(o, &run->result,
                      RTE_OVERLAY_CONTOURS | RTE_OVERLAY_GRASP | RTE_OVERLAY_LABELS);
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
        "\nGrasp: the centroid, the gripper closing across the narrowest width of the\n"
        "object's convex hull (angle in degrees, image axes, y down), opened to that\n"
        "width plus --margin on each side (the jaws' faces: jaws); score 0..1: solidity x\n"
        "width within --gripper-min..--gripper-max x room for the fingers (clearance,\n"
        "of --margin + --finger) on both sides. Prints {\"objects\":[{\"center\",\"angle\",\n"
        "\"width\",\"opening\",\"jaws\",\"clearance\",\"score\",\"area\",\"shape\",\"box\"}],...}\n"
        "best score first (equal scores: largest first).",
        100, false);
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
        printf(",\"opening\":");
        cli_print_q8(o->opening_q8);
        printf(",\"jaws\":[");
        print_q8_pair(o->jaws_q8[0][0], o->jaws_q8[0][1]);
        printf(",");
        print_q8_pair(o->jaws_q8[1][0], o->jaws_q8[1][1]);
        printf("],\"clearance\":");
        cli_print_q8(o->clearance_q8);
        printf(",\"score\":");
        cli_print_q16(o->score_q16);
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
    printf("],\"threshold\":%d,\"truncated\":%s,\"dropped_objects\":%d,\"split_parts\":%d,"
           "\"timing_ns\":{\"blur\":%lld,\"binarize\":%lld,\"contours\":%lld,\"split\":%lld,"
           "\"features\":%lld,\"total\":%lld}}\n",
           (int)r->threshold, r->truncated ? "true" : "false", (int)r->dropped_objects,
           (int)r->split_parts, (long long)t->blur_ns, (long long)t->binarize_ns,
           (long long)t->contours_ns, (long long)t->split_ns, (long long)t->features_ns,
           (long long)t->total_ns);
    rc = overlay(&run, draw_grasp);
    grasp_end(&run);
    return rc;
}

static void draw_shapes(rte_overlay *o, const grasp_run *run)
{
    /* the first (best) last, on top */
    rte_overlay_grasp(o, &run->result, RTE_OVERLAY_CONTOURS);
    for (int32_t i = run->result.n_objects - 1; i >= 0; i--) {
        const rte_grasp_object *g = &run->result.objects[i];
        const rte_draw_color c = rte_overlay_color(i);
        rte_draw_dot(&o->canvas, q8_px(g->x_q8), q8_px(g->y_q8), 2, c);
        rte_overlay_label(&o->canvas, q8_px(g->x_q8) - 20, q8_px(g->y_q8) + 5,
                          rte_grasp_shape_name(g->info.shape), c);
    }
}

int cmd_shapes(const cli_entry *self, int argc, char **argv)
{
    grasp_run run;
    int rc = grasp_start(&run, self, argc, argv,
                         PIPELINE_DETAILS "\nPrints one line per object, best grasp score first:\n"
                                          "  index shape area perimeter solidity aspect cx cy",
                         100, true);
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
    rc = overlay(&run, draw_shapes);
    grasp_end(&run);
    return rc;
}
