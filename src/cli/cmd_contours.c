/* `rtedge contours`: every contour of a binarised image with all its
 * features, as JSON (fixed-point values printed as decimals). */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "cli_image.h"
#include "cli_pipeline.h"
#include "commands.h"
#include "rtedge/contours.h"
#include "rtedge/grasp.h"
#include "rtedge/shape.h"

static void print_point(rte_point p) { printf("[%d,%d]", (int)p.x, (int)p.y); }

static void print_points(const rte_point *p, int32_t n)
{
    printf("[");
    for (int32_t i = 0; i < n; i++) {
        printf(i ? "," : "");
        print_point(p[i]);
    }
    printf("]");
}

static void print_q8_pair(int64_t x, int64_t y)
{
    printf("[");
    cli_print_q8(x);
    printf(",");
    cli_print_q8(y);
    printf("]");
}

/* Buffers for the features of one contour of up to n points. */
typedef struct feature_buffers {
    int32_t *hull_idx;
    rte_point *hull, *approx;
    rte_defect *defects;
    rte_arena arena;
    void *arena_memory;
} feature_buffers;

static rte_status print_features(const rte_point *pts, int32_t n, feature_buffers *b)
{
    rte_shape_info s;
    rte_moments m;
    int32_t nh = 0, nd = 0, na = 0;
    rte_status st = rte_shape_classify(pts, n, &s, &b->arena);
    if (st == RTE_OK)
        st = rte_shape_moments(pts, n, &m);
    if (st == RTE_OK)
        st = rte_shape_convex_hull(pts, n, b->hull_idx, b->hull, &nh, &b->arena);
    if (st == RTE_OK) /* self-intersecting contours have no defects (RTE_ERR_ARGUMENT) */
        if (rte_shape_convexity_defects(pts, n, b->hull_idx, nh, b->defects, &nd) != RTE_OK)
            nd = 0;
    /* the tutorial's epsilon: 0.02 x perimeter */
    const int64_t eps = (s.perimeter_q16 * 2 + 50) / 100;
    if (st == RTE_OK)
        st = rte_shape_approx_poly(pts, n, (uint32_t)(eps < (1 << 26) ? eps : (1 << 26) - 1),
                                   b->approx, &na, &b->arena);
    if (st != RTE_OK)
        return st;
    printf(",\"area\":");
    cli_print_q8(s.area2 * 128);
    printf(",\"perimeter\":");
    cli_print_q16(s.perimeter_q16);
    printf(",\"centroid\":");
    if (m.s00 > 0) {
        printf("[");
        cli_print_q16(m.cx_q16);
        printf(",");
        cli_print_q16(m.cy_q16);
        printf("]");
    } else
        printf("null");
    printf(",\"bbox\":[%d,%d,%d,%d]", (int)s.bounds.x, (int)s.bounds.y, (int)s.bounds.width,
           (int)s.bounds.height);
    printf(",\"min_rect\":{\"center\":");
    print_q8_pair(s.box.cx_q8, s.box.cy_q8);
    printf(",\"size\":");
    print_q8_pair(s.box.length_q8, s.box.width_q8);
    printf(",\"angle\":");
    cli_print_q16(s.box.angle_q16);
    printf(",\"corners\":[");
    for (int k = 0; k < 4; k++) {
        printf(k ? "," : "");
        print_q8_pair(s.box.corners_q8[k][0], s.box.corners_q8[k][1]);
    }
    printf("]},\"circle\":{\"center\":");
    print_q8_pair(s.circle.cx_q8, s.circle.cy_q8);
    printf(",\"r\":");
    cli_print_q8(s.circle.r_q8);
    printf("},\"hull\":");
    print_points(b->hull, nh);
    printf(",\"defects\":[");
    for (int32_t i = 0; i < nd; i++) {
        printf("%s[%d,%d,%d,", i ? "," : "", (int)b->defects[i].start, (int)b->defects[i].end,
               (int)b->defects[i].farthest);
        cli_print_q8(b->defects[i].depth_q8);
        printf("]");
    }
    printf("],\"approx\":");
    print_points(b->approx, na);
    printf(",\"shape\":\"%s\",\"solidity\":", rte_grasp_shape_name(s.shape));
    cli_print_q16(s.solidity_q16);
    printf(",\"extent\":");
    cli_print_q16(s.extent_q16);
    printf(",\"aspect\":");
    cli_print_q16(s.aspect_q16);
    return RTE_OK;
}

/* The contour list and the feature buffers for config's limits on a w x h
 * image; false when one could not be allocated (the others are freed by
 * contour_buffers_free either way). */
static bool contour_buffers_new(const char *command, const rte_grasp_config *config, int32_t w,
                                int32_t h, rte_contours *cs, feature_buffers *b)
{
    cs->max_points = config->max_points;
    cs->max_contours = config->max_contours;
    cs->points = malloc((size_t)cs->max_points * sizeof *cs->points);
    cs->contours = malloc((size_t)cs->max_contours * sizeof *cs->contours);
    const int32_t maxp = cs->max_points;
    b->hull_idx = malloc((size_t)maxp * sizeof *b->hull_idx);
    b->hull = malloc((size_t)maxp * sizeof *b->hull);
    b->approx = malloc((size_t)maxp * sizeof *b->approx);
    b->defects = malloc((size_t)maxp * sizeof *b->defects);
    size_t scratch = rte_contours_scratch_size(w, h, cs->max_contours);
    scratch = cli_max_size(scratch, rte_shape_classify_scratch_size(maxp));
    scratch = cli_max_size(scratch, rte_shape_hull_scratch_size(maxp));
    scratch = cli_max_size(scratch, rte_shape_approx_scratch_size(maxp));
    b->arena_memory = cli_new_arena(command, scratch, &b->arena);
    return cs->points && cs->contours && b->hull_idx && b->hull && b->approx && b->defects &&
           b->arena_memory;
}

static void contour_buffers_free(rte_contours *cs, feature_buffers *b)
{
    free(cs->points);
    free(cs->contours);
    free(b->hull_idx);
    free(b->hull);
    free(b->approx);
    free(b->defects);
    free(b->arena_memory);
}

/* The JSON document: every contour of at least min_area px with its
 * features (stops at the first that fails, leaving the document open). */
static rte_status print_contours(const rte_contours *cs, feature_buffers *b, int min_area,
                                 int32_t threshold)
{
    rte_status st = RTE_OK;
    printf("{\"contours\":[");
    int first = 1;
    for (int32_t i = 0; i < cs->n_contours && st == RTE_OK; i++) {
        const rte_contour *c = &cs->contours[i];
        const rte_point *pts = cs->points + c->offset;
        int64_t a2 = rte_shape_area2(pts, c->count);
        if ((a2 < 0 ? -a2 : a2) < 2 * (int64_t)min_area)
            continue;
        printf("%s{\"index\":%d,\"points\":", first ? "" : ",", (int)i);
        first = 0;
        print_points(pts, c->count);
        printf(",\"hierarchy\":[%d,%d,%d,%d]", (int)c->hierarchy[0], (int)c->hierarchy[1],
               (int)c->hierarchy[2], (int)c->hierarchy[3]);
        st = print_features(pts, c->count, b);
        printf("}");
    }
    printf("],\"threshold\":%d,\"truncated\":%s}\n", (int)threshold,
           cs->truncated ? "true" : "false");
    return st;
}

int cmd_contours(const cli_entry *self, int argc, char **argv)
{
    static const char *const modes[] = {"external", "list", "ccomp", "tree", NULL};
    static const char *const methods[] = {"none", "simple", NULL};
    cli_pipeline_options o;
    cli_pipeline_defaults(&o, 1, 0, true);
    int mode = RTE_CONTOURS_LIST, method = 1;
    cli_option options[CLI_PIPELINE_OPTIONS + 3];
    int n = cli_pipeline_option_table(options, &o, false);
    options[n] =
        (cli_option){"mode", CLI_CHOICE, &mode, 0, 0, modes, "retrieval mode (= RETR_*)", NULL};
    options[n + 1] = (cli_option){"method",
                                  CLI_CHOICE,
                                  &method,
                                  0,
                                  0,
                                  methods,
                                  "chain approximation (= CHAIN_APPROX_NONE / SIMPLE)",
                                  NULL};
    options[n + 2] = (cli_option){0};
    cli_command cmd = {
        self->name,
        "IN",
        self->summary,
        "IN: PGM/PPM, PNG or JPEG. Binarised as the grasp path does (no blur by default):\n"
        "a fixed threshold N with --polarity bright is cv2.threshold(img, N, 255, THRESH_BINARY);\n"
        "then = cv2.findContours(bin, mode, method). Contours smaller than --min-area are\n"
        "left out; \"index\" and \"hierarchy\" refer to the full list.\n"
        "Prints "
        "{\"contours\":[{\"index\",\"points\",\"hierarchy\",\"area\",\"perimeter\",\"centroid\",\n"
        "\"bbox\",\"min_rect\",\"circle\",\"hull\",\"defects\",\"approx\",\"shape\",\"solidity\",\n"
        "\"extent\",\"aspect\"}],\"truncated\":false}.",
        options,
        1};
    const char *path[1];
    int rc = cli_parse(&cmd, argc, argv, path);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    rte_grasp_config config;
    if ((rc = cli_pipeline_config(self->name, &o, 1, 1, &config)) != CLI_EXIT_OK)
        return rc;
    cli_image in;
    if ((rc = cli_load(self->name, path[0], &in)) != CLI_EXIT_OK)
        return rc;
    const int32_t w = in.gray.width, h = in.gray.height;
    if (w > RTE_SHAPE_MAX_COORD + 1 || h > RTE_SHAPE_MAX_COORD + 1) {
        cli_error(self->name, "%s: %dx%d is larger than %d px a side", path[0], w, h,
                  RTE_SHAPE_MAX_COORD + 1);
        cli_image_free(&in);
        return CLI_EXIT_INPUT;
    }
    cli_pipeline_config(self->name, &o, w, h, &config);
    /* the grasp path binarises; its contours are not used here */
    rte_grasp_ctx *ctx = NULL;
    rte_grasp_result r;
    rte_status st = rte_grasp_create(&config, &ctx);
    if (st == RTE_OK)
        st = cli_grasp_process(ctx, &in, &r);

    rte_contours cs = {0};
    feature_buffers b = {0};
    if (!contour_buffers_new(self->name, &config, w, h, &cs, &b) && st == RTE_OK)
        st = RTE_ERR_NO_MEMORY;
    if (st == RTE_OK)
        st = rte_contours_find(r.binary, (rte_contour_mode)mode,
                               method ? RTE_CONTOURS_APPROX_SIMPLE : RTE_CONTOURS_APPROX_NONE, &cs,
                               &b.arena);
    if (st == RTE_OK)
        st = print_contours(&cs, &b, o.min_area, r.threshold);
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        rc = CLI_EXIT_FAILURE;
    }
    contour_buffers_free(&cs, &b);
    rte_grasp_destroy(ctx);
    cli_image_free(&in);
    return rc;
}
