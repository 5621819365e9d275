#include "cli_pipeline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fractions.h"
#include "core/int_math.h"
#include "rtedge/blur.h"
#include "rtedge/color.h"
#include "rtedge/morphology.h"

const char *const cli_polarities[] = {"auto", "dark", "bright", NULL};

void cli_pipeline_defaults(cli_pipeline_options *o, int blur, int min_area, bool tutorial)
{
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    *o = (cli_pipeline_options){
        .binarize = tutorial ? "otsu" : "background",
        .polarity = 0,
        .blur = blur,
        .min_area = min_area,
        .max_area = 0,
        .max_objects = c.max_objects,
        .canny_low = c.params.canny_low,
        .canny_high = c.params.canny_high,
        .close = c.close_ksize,
        .close_iterations = c.close_iterations,
        .contrast = c.params.contrast,
        .edge_support = c.params.edge_support_permille / 1000.0,
        .skip_border = !tutorial && c.params.skip_border,
        .split = !tutorial && c.params.split,
        .gripper_min = c.params.gripper_min_px,
        .gripper_max = c.params.gripper_max_px,
        .margin = c.params.margin_px,
        .finger = c.params.finger_px,
    };
}

/* The object options of shapes and grasp: filters, workspace, gripper. */
static int object_options(cli_option *t, cli_pipeline_options *o)
{
    int n = 0;
    t[n++] = (cli_option){
        "max-area", CLI_INT, &o->max_area, 0, 4194304, NULL, "largest object, px (0 = no limit)",
        NULL};
    t[n++] = (cli_option){"skip-border",
                          CLI_FLAG,
                          &o->skip_border,
                          0,
                          0,
                          NULL,
                          "drop objects touching the image border (or the workspace's)",
                          NULL};
    t[n++] = (cli_option){
        "keep-border", CLI_FLAG, &o->keep_border, 0, 0, NULL, "keep them (flagged touches_border)",
        NULL};
    t[n++] = (cli_option){"split",
                          CLI_FLAG,
                          &o->split,
                          0,
                          0,
                          NULL,
                          "split touching objects at their necks (chamfer distance)",
                          NULL};
    t[n++] = (cli_option){
        "no-split", CLI_FLAG, &o->no_split, 0, 0, NULL, "keep touching objects as one", NULL};
    t[n++] = (cli_option){"roi",
                          CLI_STRING,
                          &o->roi,
                          0,
                          0,
                          NULL,
                          "the workspace: 3..8 'x,y' fractions of width and height, "
                          "';'-separated; objects outside it are not looked for",
                          NULL};
    t[n++] = (cli_option){"max-objects",
                          CLI_INT,
                          &o->max_objects,
                          1,
                          4096,
                          NULL,
                          "objects reported (the best scores)",
                          NULL};
    t[n++] = (cli_option){"gripper-min",
                          CLI_INT,
                          &o->gripper_min,
                          0,
                          RTE_GRASP_MAX_OPENING_PX,
                          NULL,
                          "narrowest object the jaws can close on, px",
                          &o->given_gripper_min};
    t[n++] = (cli_option){"gripper-max",
                          CLI_INT,
                          &o->gripper_max,
                          0,
                          RTE_GRASP_MAX_OPENING_PX,
                          NULL,
                          "widest opening of the jaws, px",
                          &o->given_gripper_max};
    t[n++] = (cli_option){"margin",
                          CLI_INT,
                          &o->margin,
                          0,
                          RTE_GRASP_MAX_CLEARANCE_PX,
                          NULL,
                          "jaws open this much wider than the object on each side, px",
                          &o->given_margin};
    t[n++] = (cli_option){"finger",
                          CLI_INT,
                          &o->finger,
                          0,
                          RTE_GRASP_MAX_CLEARANCE_PX,
                          NULL,
                          "free room each finger needs beyond its opened jaw face, px",
                          &o->given_finger};
    return n;
}

int cli_pipeline_option_table(cli_option *t, cli_pipeline_options *o, bool grasp)
{
    int n = 0;
    t[n++] = (cli_option){"binarize",
                          CLI_STRING,
                          &o->binarize,
                          0,
                          0,
                          NULL,
                          "background (|image - table| both ways), otsu, canny (edges closed "
                          "by an ellipse) or a fixed threshold 0..255",
                          NULL};
    t[n++] = (cli_option){"contrast",
                          CLI_INT,
                          &o->contrast,
                          1,
                          255,
                          NULL,
                          "background: the least |image - table| of an object",
                          NULL};
    t[n++] = (cli_option){"no-chroma",
                          CLI_FLAG,
                          &o->no_chroma,
                          0,
                          0,
                          NULL,
                          "background: grey only (colour differences from the table are not "
                          "contrast, cast shadows are not told apart)",
                          NULL};
    t[n++] = (cli_option){"edge-support",
                          CLI_DOUBLE,
                          &o->edge_support,
                          0,
                          1,
                          NULL,
                          "background: the least share of an object's outline beside the "
                          "table on an edge (a step of a fifth of --contrast); less is a "
                          "threshold across a smooth ramp, dropped (0: off)",
                          NULL};
    t[n++] = (cli_option){"polarity",
                          CLI_CHOICE,
                          &o->polarity,
                          0,
                          0,
                          cli_polarities,
                          "objects darker or brighter than the table; auto: both (background), "
                          "else the image border is table",
                          NULL};
    t[n++] = (cli_option){"blur",
                          CLI_INT,
                          &o->blur,
                          1,
                          RTE_GAUSSIAN_MAX_KSIZE,
                          NULL,
                          "odd Gaussian size before binarising (1 = none)",
                          NULL};
    t[n++] = (cli_option){
        "canny-low", CLI_INT, &o->canny_low, 0, 2040, NULL, "canny: lower threshold", NULL};
    t[n++] = (cli_option){"canny-high", CLI_INT, &o->canny_high,           0,
                          2040,         NULL,    "canny: upper threshold", NULL};
    t[n++] = (cli_option){"close",
                          CLI_INT,
                          &o->close,
                          1,
                          RTE_MORPH_MAX_KSIZE,
                          NULL,
                          "canny: odd size of the closing ellipse",
                          NULL};
    t[n++] = (cli_option){"close-iterations",          CLI_INT, &o->close_iterations, 1, 8, NULL,
                          "canny: closing iterations", NULL};
    t[n++] = (cli_option){"min-area", CLI_INT, &o->min_area,          0,
                          4194304,    NULL,    "smallest object, px", &o->given_min_area};
    if (grasp)
        n += object_options(t + n, o);
    t[n] = (cli_option){0};
    return n;
}

/* v * num / den, rounded, at most max. */
static int scaled(int v, int64_t num, int64_t den, int max)
{
    const int64_t s = rte_div_round64((int64_t)v * num, den);
    return s < max ? (int)s : max;
}

void cli_pipeline_scale_sizes(cli_pipeline_options *o, int32_t w, int32_t h)
{
    const int64_t side = w > h ? w : h, ref = 640;
    if (side <= ref)
        return;
    if (!o->given_min_area)
        o->min_area = scaled(o->min_area, side * side, ref * ref, 4194304);
    if (!o->given_gripper_min)
        o->gripper_min = scaled(o->gripper_min, side, ref, RTE_GRASP_MAX_OPENING_PX);
    if (!o->given_gripper_max)
        o->gripper_max = scaled(o->gripper_max, side, ref, RTE_GRASP_MAX_OPENING_PX);
    if (!o->given_margin)
        o->margin = scaled(o->margin, side, ref, RTE_GRASP_MAX_CLEARANCE_PX);
    if (!o->given_finger)
        o->finger = scaled(o->finger, side, ref, RTE_GRASP_MAX_CLEARANCE_PX);
}

int cli_pipeline_config(const char *command, const cli_pipeline_options *o, int32_t w, int32_t h,
                        rte_grasp_config *c)
{
    rte_grasp_config_default(c);
    rte_grasp_params *p = &c->params;
    if (strcmp(o->binarize, "background") == 0) {
        p->binarize = RTE_GRASP_BACKGROUND;
    } else if (strcmp(o->binarize, "otsu") == 0) {
        p->binarize = RTE_GRASP_OTSU;
    } else if (strcmp(o->binarize, "canny") == 0) {
        p->binarize = RTE_GRASP_CANNY_CLOSE;
    } else {
        char *end;
        long t = strtol(o->binarize, &end, 10);
        if (end == o->binarize || *end || t < 0 || t > 255) {
            cli_error(command,
                      "--binarize must be background, otsu, canny or a threshold 0..255, not "
                      "\"%s\"",
                      o->binarize);
            return CLI_EXIT_USAGE;
        }
        p->binarize = RTE_GRASP_FIXED;
        p->threshold = (int32_t)t;
    }
    if (o->blur % 2 == 0 || o->close % 2 == 0) {
        cli_error(command, "--blur and --close must be odd");
        return CLI_EXIT_USAGE;
    }
    c->max_width = w;
    c->max_height = h;
    /* room for every contour and point the image can hold, up to the
     * library's bounds (beyond them the result says truncated) */
    const int64_t contours = (int64_t)w * h / 2 + 1, points = 2 * (int64_t)w * h + 4;
    c->max_contours =
        (int32_t)(contours < RTE_GRASP_MAX_CONTOURS ? contours : RTE_GRASP_MAX_CONTOURS);
    c->max_points = (int32_t)(points < RTE_GRASP_MAX_POINTS ? points : RTE_GRASP_MAX_POINTS);
    c->max_objects = o->max_objects;
    c->blur_ksize = o->blur;
    c->close_ksize = o->close;
    c->close_iterations = o->close_iterations;
    p->polarity = (rte_grasp_polarity)o->polarity;
    p->canny_low = o->canny_low;
    p->canny_high = o->canny_high;
    p->min_area = o->min_area;
    p->max_area = o->max_area;
    p->skip_border = o->skip_border && !o->keep_border;
    p->split = o->split && !o->no_split;
    p->contrast = o->contrast;
    p->chroma = !o->no_chroma;
    p->edge_support_permille = (int32_t)lround(o->edge_support * 1000);
    p->max_objects = o->max_objects;
    if (o->gripper_min > o->gripper_max) {
        cli_error(command, "--gripper-min (%d) exceeds --gripper-max (%d)", o->gripper_min,
                  o->gripper_max);
        return CLI_EXIT_USAGE;
    }
    p->gripper_min_px = o->gripper_min;
    p->gripper_max_px = o->gripper_max;
    p->margin_px = o->margin;
    p->finger_px = o->finger;
    p->roi_count = o->roi ? rte_parse_fractions(o->roi, p->roi, RTE_GRASP_MAX_ROI_VERTICES) : 0;
    if (p->roi_count < 0) {
        cli_error(command, "--roi takes 3 to %d 'x,y' fractions separated by ';', not '%s'",
                  RTE_GRASP_MAX_ROI_VERTICES, o->roi);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

/* Prints v / 2^shift with `places` decimals, rounded, without trailing zeros. */
static void print_fixed(int64_t v, int shift, int places)
{
    int64_t scale = 1;
    for (int i = 0; i < places; i++)
        scale *= 10;
    const int neg = v < 0;
    uint64_t a = neg ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    /* integer part, then the fraction rounded to `places` decimals */
    uint64_t ip = a >> shift;
    uint64_t fp =
        ((a & (((uint64_t)1 << shift) - 1)) * (uint64_t)scale + ((uint64_t)1 << (shift - 1))) >>
        shift;
    if (fp == (uint64_t)scale) {
        ip++;
        fp = 0;
    }
    const uint64_t q = ip | fp;
    printf("%s%llu", neg && q ? "-" : "", (unsigned long long)ip);
    if (fp) {
        char digits[24];
        snprintf(digits, sizeof digits, "%0*llu", places, (unsigned long long)fp);
        size_t n = strlen(digits);
        while (n > 0 && digits[n - 1] == '0')
            digits[--n] = '\0';
        printf(".%s", digits);
    }
}

void cli_print_q8(int64_t v) { print_fixed(v, 8, 2); }
void cli_print_q16(int64_t v) { print_fixed(v, 16, 4); }

void *cli_overlay_canvas(const char *command, const cli_image *in, rte_image_u8c3 *canvas)
{
    const int32_t w = in->gray.width, h = in->gray.height;
    uint8_t *mem = malloc((size_t)w * (size_t)h * 3);
    if (!mem) {
        cli_error(command, "not enough memory for a %dx%d overlay", w, h);
        return NULL;
    }
    *canvas = (rte_image_u8c3){w, h, 3 * w, mem};
    for (int32_t y = 0; y < h; y++) {
        uint8_t *d = mem + (size_t)y * 3 * (size_t)w;
        if (in->bgr.buf) {
            memcpy(d, in->bgr.buf + (size_t)y * (size_t)in->bgr.stride, (size_t)w * 3);
        } else {
            const uint8_t *s = rte_u8_row(&in->gray, y);
            for (int32_t x = 0; x < w; x++)
                d[3 * x] = d[3 * x + 1] = d[3 * x + 2] = s[x];
        }
    }
    return mem;
}

rte_status cli_grasp_process(rte_grasp_ctx *ctx, const cli_image *in, rte_grasp_result *out)
{
    rte_grasp_params p;
    rte_grasp_get_params(ctx, &p);
    if (!in->bgr.buf || !p.chroma || p.binarize != RTE_GRASP_BACKGROUND)
        return rte_grasp_process(ctx, &in->gray, out); /* no colour read */
    const int32_t w = in->gray.width, h = in->gray.height, hw = (w + 1) / 2, hh = (h + 1) / 2;
    const rte_frame f = {RTE_PIXEL_BGR24, w, h, {in->bgr.buf}, {in->bgr.stride}};
    uint8_t *chroma = malloc(2 * (size_t)hw * (size_t)hh);
    rte_image_u8 cb = {hw, hh, hw, chroma}, cr = {hw, hh, hw, chroma + (size_t)hw * (size_t)hh};
    rte_status st = chroma ? rte_frame_chroma_half(&f, &cb, &cr) : RTE_ERR_NO_MEMORY;
    if (st == RTE_OK)
        st = rte_grasp_process_chroma(ctx, &in->gray, &cb, &cr, out);
    free(chroma);
    return st;
}
