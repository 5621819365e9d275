/* The grasp path on an image file: `rtedge grasp` (grasp points as JSON)
 * and `rtedge shapes` (the shape table), both with an optional overlay. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "cli_image.h"
#include "cli_pipeline.h"
#include "commands.h"
#include "core/int_math.h"
#include "rtedge/overlay.h"
#include "rtedge/grasp.h"

#define PIPELINE_DETAILS                                                                         \
    "IN: PGM/PPM, PNG or JPEG (colour becomes grey as cv2.cvtColor(cv2.imread(IN), BGR2GRAY);\n" \
    "background mode: its colour differences from the table count as contrast too).\n"           \
    "grey -> Gaussian blur -> |grey - table| both ways (background), Otsu, a fixed threshold\n"  \
    "or Canny + close -> external contours -> area and border filters -> features (moments,\n"   \
    "minimum-area box, hull, shape class). grasp: background, border objects dropped;\n"         \
    "shapes: Otsu, border objects kept (the OpenCV tutorial's shape analysis). A photo over\n"   \
    "2048 px a side is reduced by the smallest whole factor that fits (block means;\n"           \
    "\"reduced\"); options and results are in the photo's pixels."

typedef struct grasp_run {
    const char *name;
    const char *paths[1];
    const char *overlay;
    cli_pipeline_options opts;
    cli_image in;      /* as read */
    cli_image reduced; /* in reduced by `reduce` (memory NULL when reduce is 1) */
    int32_t reduce;
    rte_grasp_ctx *ctx;
    rte_grasp_result result;
} grasp_run;

/* The largest side the grasp path takes (its fixed-point moments). */
#define GRASP_MAX_SIDE (RTE_SHAPE_MAX_COORD + 1)

/* The mean of each k x k block of src into dst (src's size / k, the last
 * partial blocks dropped), for `channels` interleaved channels. */
static void reduce_plane(const uint8_t *src, size_t src_stride, int32_t w, int32_t h, int32_t k,
                         int32_t channels, uint8_t *dst, size_t dst_stride)
{
    const uint32_t n = (uint32_t)k * (uint32_t)k;
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++)
            for (int32_t c = 0; c < channels; c++) {
                uint32_t sum = 0;
                for (int32_t j = 0; j < k; j++) {
                    const uint8_t *row = src + (size_t)(y * k + j) * src_stride;
                    for (int32_t i = 0; i < k; i++)
                        sum += row[(size_t)(x * k + i) * channels + c];
                }
                dst[(size_t)y * dst_stride + (size_t)x * channels + c] =
                    (uint8_t)((sum + n / 2) / n);
            }
}

/* A photo larger than the grasp path takes is reduced by the smallest
 * whole factor that fits (block means, grey and colour alike); the
 * results are reported in the photo's pixels. */
static int reduce_input(grasp_run *run)
{
    const int32_t w = run->in.gray.width, h = run->in.gray.height;
    const int32_t side = w > h ? w : h;
    run->reduce = (side + GRASP_MAX_SIDE - 1) / GRASP_MAX_SIDE;
    run->reduced = run->in;
    run->reduced.memory = NULL;
    if (run->reduce == 1)
        return CLI_EXIT_OK;
    const int32_t k = run->reduce, rw = w / k, rh = h / k;
    if (rw < 1 || rh < 1) {
        cli_error(run->name,
                  "%s: %dx%d is larger than %d px a side and too thin to reduce %d times",
                  run->paths[0], w, h, GRASP_MAX_SIDE, k);
        return CLI_EXIT_INPUT;
    }
    const size_t grey = (size_t)rw * rh, colour = run->in.bgr.buf ? 3 * grey : 0;
    uint8_t *mem = malloc(grey + colour);
    if (!mem) {
        cli_error(run->name, "out of memory reducing %dx%d", w, h);
        return CLI_EXIT_FAILURE;
    }
    run->reduced.memory = mem;
    run->reduced.gray = (rte_image_u8){rw, rh, rw, mem};
    reduce_plane(run->in.gray.buf, run->in.gray.stride, rw, rh, k, 1, mem, rw);
    if (colour) {
        run->reduced.bgr = (rte_image_u8c3){rw, rh, 3 * rw, mem + grey};
        reduce_plane(run->in.bgr.buf, run->in.bgr.stride, rw, rh, k, 3, mem + grey, 3 * (size_t)rw);
    }
    return CLI_EXIT_OK;
}

/* The options given in the photo's pixels, in the reduced image's. */
static void reduce_params(rte_grasp_params *p, int32_t k)
{
    p->min_area = (int32_t)rte_div_round64(p->min_area, (int64_t)k * k);
    p->max_area = (int32_t)rte_div_round64(p->max_area, (int64_t)k * k);
    p->gripper_min_px = (int32_t)rte_div_round64(p->gripper_min_px, k);
    p->gripper_max_px = (int32_t)rte_div_round64(p->gripper_max_px, k);
    p->margin_px = (int32_t)rte_div_round64(p->margin_px, k);
    p->finger_px = (int32_t)rte_div_round64(p->finger_px, k);
}

/* A position (x or y, 1/256 px) in the reduced image, in the photo's: a
 * reduced pixel's centre is the middle of its k x k block. */
static int64_t at_q8(const grasp_run *run, int32_t v)
{
    return (int64_t)v * run->reduce + (int64_t)(run->reduce - 1) * 128;
}

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
    if ((rc = reduce_input(run)) != CLI_EXIT_OK) {
        cli_image_free(&run->in);
        return rc;
    }
    const int32_t w = run->reduced.gray.width, h = run->reduced.gray.height;
    if (!tutorial)
        cli_pipeline_scale_sizes(&run->opts, run->in.gray.width, run->in.gray.height);
    cli_pipeline_config(self->name, &run->opts, w, h, &config);
    reduce_params(&config.params, run->reduce);
    rte_status st = rte_grasp_create(&config, &run->ctx);
    if (st == RTE_OK)
        st = cli_grasp_process(run->ctx, &run->reduced, &run->result);
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        rte_grasp_destroy(run->ctx);
        free(run->reduced.memory);
        cli_image_free(&run->in);
        return CLI_EXIT_FAILURE;
    }
    return CLI_EXIT_OK;
}

static void grasp_end(grasp_run *run)
{
    rte_grasp_destroy(run->ctx);
    free(run->reduced.memory);
    cli_image_free(&run->in);
}

static int32_t q8_px(int64_t v) { return (int32_t)((v + 128) >> 8); }

/* Draws the objects with draw and writes the overlay. */
static int overlay(grasp_run *run, void (*draw)(rte_overlay *, const grasp_run *))
{
    if (!run->overlay)
        return CLI_EXIT_OK;
    rte_overlay o = {.scale_q16 = 65536 * run->reduce};
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

/* A position in the photo's pixels. */
static void print_point(const grasp_run *run, int32_t x_q8, int32_t y_q8)
{
    printf("[");
    cli_print_q8(at_q8(run, x_q8));
    printf(",");
    cli_print_q8(at_q8(run, y_q8));
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
        "of --margin + --finger) on both sides. Unless given, --min-area, --gripper-min,\n"
        "--gripper-max, --margin and --finger are for a 640 px side and grow with a larger\n"
        "photo's longest side (the area with its square). Prints "
        "{\"objects\":[{\"center\",\"angle\",\n"
        "\"width\",\"opening\",\"jaws\",\"clearance\",\"score\",\"area\",\"shape\",\"box\"}],\n"
        "\"reduced\",...}, "
        "best score first (equal scores: largest first).",
        100, false);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    const rte_grasp_result *r = &run.result;
    const int64_t k = run.reduce;
    printf("{\"objects\":[");
    for (int32_t i = 0; i < r->n_objects; i++) {
        const rte_grasp_object *o = &r->objects[i];
        printf("%s{\"center\":", i ? "," : "");
        print_point(&run, o->x_q8, o->y_q8);
        printf(",\"angle\":");
        cli_print_q16(o->angle_q16);
        printf(",\"width\":");
        cli_print_q8((int64_t)o->width_q8 * k);
        printf(",\"opening\":");
        cli_print_q8((int64_t)o->opening_q8 * k);
        printf(",\"jaws\":[");
        print_point(&run, o->jaws_q8[0][0], o->jaws_q8[0][1]);
        printf(",");
        print_point(&run, o->jaws_q8[1][0], o->jaws_q8[1][1]);
        printf("],\"clearance\":");
        cli_print_q8((int64_t)o->clearance_q8 * k);
        printf(",\"score\":");
        cli_print_q16(o->score_q16);
        printf(",\"area\":");
        cli_print_q8(o->info.area2 * 128 * k * k);
        printf(",\"shape\":\"%s\",\"box\":[", rte_grasp_shape_name(o->info.shape));
        for (int c = 0; c < 4; c++) {
            printf(c ? "," : "");
            print_point(&run, o->info.box.corners_q8[c][0], o->info.box.corners_q8[c][1]);
        }
        printf("]}");
    }
    const rte_grasp_timing *t = &r->timing;
    printf("],\"reduced\":%d,\"threshold\":%d,\"truncated\":%s,\"dropped_objects\":%d,"
           "\"split_parts\":%d,"
           "\"timing_ns\":{\"blur\":%lld,\"binarize\":%lld,\"contours\":%lld,\"split\":%lld,"
           "\"features\":%lld,\"total\":%lld}}\n",
           (int)run.reduce, (int)r->threshold, r->truncated ? "true" : "false",
           (int)r->dropped_objects, (int)r->split_parts, (long long)t->blur_ns,
           (long long)t->binarize_ns, (long long)t->contours_ns, (long long)t->split_ns,
           (long long)t->features_ns, (long long)t->total_ns);
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
        const int32_t x = q8_px(at_q8(run, g->x_q8)), y = q8_px(at_q8(run, g->y_q8));
        rte_draw_dot(&o->canvas, x, y, 2, c);
        rte_overlay_label(&o->canvas, x - 20, y + 5, rte_grasp_shape_name(g->info.shape), c);
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
        const double k = run.reduce;
        printf("%-3d %-10s %10.1f %10.2f %8.3f %7.3f %8.2f %8.2f\n", (int)i,
               rte_grasp_shape_name(s->shape), s->area2 / 2.0 * k * k,
               s->perimeter_q16 / 65536.0 * k, s->solidity_q16 / 65536.0, s->aspect_q16 / 65536.0,
               at_q8(&run, r->objects[i].x_q8) / 256.0, at_q8(&run, r->objects[i].y_q8) / 256.0);
    }
    if (r->truncated)
        printf("(truncated: %d more objects)\n", (int)r->dropped_objects);
    rc = overlay(&run, draw_shapes);
    grasp_end(&run);
    return rc;
}
