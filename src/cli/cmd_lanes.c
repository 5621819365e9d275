/* rtedge lanes: the lane pipeline (include/rtedge/lane.h) on one image, or
 * with tracking over a sequence (a directory of images in name order, or a
 * .y4m file), printing JSON. The overlay is drawn here with a minimal
 * integer line routine (no drawing module in librtedge yet). */
#include <dirent.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli.h"
#include "core/fractions.h"
#include "cli_image.h"
#include "cli_pipeline.h"
#include "commands.h"
#include "rtedge/overlay.h"
#include "rtedge/imageio.h"
#include "rtedge/lane.h"
#include "rtedge/y4m.h"

typedef struct lanes_options {
    const char *overlay;
    const char *sequence;
    const char *roi;
    int canny_low, canny_high;
    int auto_canny;
    int fit;
    bool no_color, no_curves;
    int hough_threshold, min_length, max_gap;
    int hold, gate, blur;
    int alpha, beta;
    int max_segments;
    int hough_seed;
} lanes_options;

static const char *const auto_choices[] = {"none", "median", "otsu", NULL};
static const char *const fit_choices[] = {"lsq", "theil-sen", NULL};

/* The configuration for frames of w x h from the defaults and the options. */
static int lanes_config(const char *name, const lanes_options *o, int32_t w, int32_t h,
                        rte_lane_config *cfg)
{
    rte_lane_config_default(cfg, w, h);
    rte_lane_params *p = &cfg->params;
    int32_t n = o->roi ? rte_parse_fractions(o->roi, p->roi, RTE_LANE_MAX_ROI_VERTICES) : 0;
    if (n < 0) {
        cli_error(name, "--roi takes 3 to %d 'x,y' fractions separated by ';', not '%s'",
                  RTE_LANE_MAX_ROI_VERTICES, o->roi);
        return CLI_EXIT_USAGE;
    }
    if (o->roi)
        p->roi_count = n;
    if (o->canny_low >= 0)
        p->canny_low = o->canny_low;
    if (o->canny_high >= 0)
        p->canny_high = o->canny_high;
    if (p->canny_low > p->canny_high) {
        cli_error(name, "--canny-low must not exceed --canny-high");
        return CLI_EXIT_USAGE;
    }
    p->canny_mode = (rte_lane_canny_mode)o->auto_canny;
    p->fit = (rte_lane_fit)o->fit;
    p->use_color = !o->no_color;
    p->curves = !o->no_curves;
    if (o->hough_threshold > 0)
        p->hough_threshold = o->hough_threshold;
    if (o->min_length >= 0)
        p->min_length = o->min_length;
    if (o->max_gap >= 0)
        p->max_gap = o->max_gap;
    p->hough_seed = (uint32_t)o->hough_seed;
    if (o->hold >= 0)
        p->hold_frames = o->hold;
    if (o->gate >= 0)
        p->gate_px = o->gate;
    if (o->alpha > 0)
        p->alpha_q8 = o->alpha;
    if (o->beta >= 0)
        p->beta_q8 = o->beta;
    cfg->blur_ksize = o->blur;
    cfg->max_segments = o->max_segments;
    return CLI_EXIT_OK;
}

/* The lane context for cfg; a usage error for a configuration out of range. */
static int lanes_create(const char *name, const rte_lane_config *cfg, rte_lane_context **ctx)
{
    rte_status st = rte_lane_create(cfg, ctx);
    if (st == RTE_OK)
        return CLI_EXIT_OK;
    cli_error(name, "lane configuration: %s", rte_status_message(st));
    return st == RTE_ERR_NO_MEMORY ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
}

static void print_lane(const char *key, const rte_lane *l)
{
    printf("\"%s\":{\"found\":%s", key, l->found ? "true" : "false");
    if (l->found) {
        printf(",\"predicted\":%s,\"x1\":%.2f,\"y1\":%d,\"x2\":%.2f,\"y2\":%d,\"confidence\":%.3f",
               l->predicted ? "true" : "false", l->x_bottom_q8 / 256.0, l->y_bottom,
               l->x_top_q8 / 256.0, l->y_top, l->confidence_permille / 1000.0);
        printf(",\"curvature\":%.6f,\"points\":[", rte_lane_curvature(l));
        int32_t xs[RTE_LANE_POLYLINE_POINTS], ys[RTE_LANE_POLYLINE_POINTS];
        const int32_t n = rte_lane_polyline(l, RTE_LANE_POLYLINE_POINTS, xs, ys);
        for (int32_t i = 0; i < n; i++)
            printf("%s[%.2f,%d]", i ? "," : "", xs[i] / 256.0, ys[i]);
        printf("]");
    }
    printf("}");
}

static void print_result(const rte_lane_result *r, long frame, bool segments)
{
    static const char *const uses[] = {"slope", "gate", "outlier", "left", "right"};
    printf("{");
    if (frame >= 0)
        printf("\"frame\":%ld,", frame);
    print_lane("left", &r->lane[RTE_LANE_LEFT]);
    printf(",");
    print_lane("right", &r->lane[RTE_LANE_RIGHT]);
    if (r->centre_valid)
        printf(",\"offset_px\":%.2f,\"offset_fraction\":%.3f,\"heading_mrad\":%d",
               r->offset_q8 / 256.0, r->offset_permille / 1000.0, r->heading_mrad);
    else
        printf(",\"offset_px\":null,\"offset_fraction\":null,\"heading_mrad\":null");
    printf(",\"canny\":[%d,%d],\"segment_count\":%d,\"truncated\":%s", r->canny_low, r->canny_high,
           r->segment_count, r->truncated ? "true" : "false");
    if (segments) {
        printf(",\"segments\":[");
        for (int32_t i = 0; i < r->segment_count; i++) {
            const rte_lane_segment *s = &r->segments[i];
            printf("%s[%d,%d,%d,%d,\"%s\"]", i ? "," : "", s->x0, s->y0, s->x1, s->y1,
                   uses[s->use]);
        }
        printf("]");
    }
    printf(",\"stage_ns\":{");
    for (int i = 0; i < RTE_LANE_STAGES; i++)
        printf("%s\"%s\":%lld", i ? "," : "", rte_lane_stage_name((rte_lane_stage)i),
               (long long)r->stage_ns[i]);
    printf("}}\n");
}

static int write_overlay(const char *name, const char *path, const cli_image *in,
                         const rte_lane_result *r)
{
    rte_overlay o = {.scale_q16 = 65536};
    void *mem = cli_overlay_canvas(name, in, &o.canvas);
    if (!mem)
        return CLI_EXIT_FAILURE;
    rte_overlay_lanes(&o, r, RTE_OVERLAY_SEGMENTS | RTE_OVERLAY_LANES);
    int rc = cli_save_bgr(name, path, &o.canvas);
    free(mem);
    return rc;
}

static int lanes_image(const char *name, const lanes_options *o, const char *path)
{
    cli_image in;
    int rc = cli_load(name, path, &in);
    if (rc != CLI_EXIT_OK)
        return rc;
    rte_lane_config cfg;
    rte_lane_context *ctx = NULL;
    if ((rc = lanes_config(name, o, in.gray.width, in.gray.height, &cfg)) == CLI_EXIT_OK)
        rc = lanes_create(name, &cfg, &ctx);
    if (rc == CLI_EXIT_OK) {
        rte_lane_result r;
        rte_status st = rte_lane_process_gray(ctx, &in.gray, in.bgr.buf ? &in.bgr : NULL, 0, &r);
        if (st != RTE_OK) {
            cli_error(name, "%s", rte_status_message(st));
            rc = CLI_EXIT_FAILURE;
        } else {
            print_result(&r, -1, true);
            if (o->overlay)
                rc = write_overlay(name, o->overlay, &in, &r);
        }
    }
    rte_lane_destroy(ctx);
    cli_image_free(&in);
    return rc;
}

static int image_filter(const struct dirent *d)
{
    return d->d_name[0] != '.' && rte_image_path_has_image_extension(d->d_name);
}

/* Runs the tracker over a directory of images. Frames larger than the
 * first are refused (the context is sized from it). */
static int lanes_directory(const char *name, const lanes_options *o, const char *dir)
{
    struct dirent **list = NULL;
    int n = scandir(dir, &list, image_filter, alphasort);
    if (n <= 0) {
        cli_error(name, "%s: no images", dir);
        free(list);
        return CLI_EXIT_INPUT;
    }
    int rc = CLI_EXIT_OK;
    rte_lane_context *ctx = NULL;
    char path[4096];
    for (int i = 0; i < n && rc == CLI_EXIT_OK; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, list[i]->d_name);
        cli_image in;
        if ((rc = cli_load(name, path, &in)) != CLI_EXIT_OK)
            break;
        rte_lane_config cfg;
        if (!ctx &&
            (rc = lanes_config(name, o, in.gray.width, in.gray.height, &cfg)) == CLI_EXIT_OK)
            rc = lanes_create(name, &cfg, &ctx);
        if (rc == CLI_EXIT_OK) {
            rte_lane_result r;
            rte_status st =
                rte_lane_process_gray(ctx, &in.gray, in.bgr.buf ? &in.bgr : NULL, i, &r);
            if (st != RTE_OK) {
                cli_error(name, "%s: %s", path, rte_status_message(st));
                rc = CLI_EXIT_FAILURE;
            } else {
                print_result(&r, i, false);
            }
        }
        cli_image_free(&in);
    }
    for (int i = 0; i < n; i++)
        free(list[i]);
    free(list);
    rte_lane_destroy(ctx);
    return rc;
}

static int lanes_y4m(const char *name, const lanes_options *o, const char *path)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_y4m_reader *reader;
    rte_y4m_info info;
    rte_status st = rte_y4m_open(path, 0, 0, &reader, &info, msg, sizeof msg);
    if (st != RTE_OK) {
        cli_error(name, "%s", msg);
        return CLI_EXIT_INPUT;
    }
    /* 4:2:0 streams as NV12, so that the lanes see their colour (as rtedged
     * does); others as their grey plane */
    const rte_pixel_format format = rte_y4m_frame_format(&info);
    const size_t size = rte_frame_packed_size(format, info.width, info.height);
    rte_lane_config cfg;
    rte_lane_context *ctx = NULL;
    uint8_t *mem = malloc(size);
    int rc = lanes_config(name, o, info.width, info.height, &cfg);
    if (rc == CLI_EXIT_OK && !mem) {
        cli_error(name, "out of memory");
        rc = CLI_EXIT_FAILURE;
    }
    if (rc == CLI_EXIT_OK)
        rc = lanes_create(name, &cfg, &ctx);
    rte_frame frame;
    if (rc == CLI_EXIT_OK)
        rte_frame_packed(&frame, format, info.width, info.height, mem, size);
    const int64_t frame_ns =
        info.fps_num > 0 ? (int64_t)1000000000 * info.fps_den / info.fps_num : 0;
    for (long i = 0; rc == CLI_EXIT_OK; i++) {
        st = rte_y4m_read_frame(reader, &frame, msg, sizeof msg);
        if (st == RTE_ERR_END)
            break;
        rte_lane_result r;
        if (st != RTE_OK) {
            cli_error(name, "%s: frame %ld: %s", path, i, msg[0] ? msg : rte_status_message(st));
            rc = CLI_EXIT_INPUT;
        } else if ((st = rte_lane_process(ctx, &frame, i * frame_ns, &r)) != RTE_OK) {
            cli_error(name, "%s", rte_status_message(st));
            rc = CLI_EXIT_FAILURE;
        } else {
            print_result(&r, i, false);
        }
    }
    rte_lane_destroy(ctx);
    rte_y4m_close(reader);
    free(mem);
    return rc;
}

int cmd_lanes(const cli_entry *self, int argc, char **argv)
{
    lanes_options o = {.canny_low = -1,
                       .canny_high = -1,
                       .auto_canny = 1,
                       .hough_threshold = -1,
                       .min_length = -1,
                       .max_gap = -1,
                       .hold = -1,
                       .gate = -1,
                       .blur = 5,
                       .alpha = -1,
                       .beta = -1,
                       .max_segments = 512};
    cli_option options[] = {
        {"overlay", CLI_STRING, &o.overlay, 0, 0, NULL,
         "write IN with the lanes drawn (left blue, right red)", NULL},
        {"sequence", CLI_STRING, &o.sequence, 0, 0, NULL,
         "track over a directory of images or a .y4m file", NULL},
        {"roi", CLI_STRING, &o.roi, 0, 0, NULL,
         "ROI polygon 'x,y;x,y;...' in fractions (default: trapezoid)", NULL},
        {"canny-low", CLI_INT, &o.canny_low, -1, 2040, NULL, "Canny low threshold, -1 = 50", NULL},
        {"canny-high", CLI_INT, &o.canny_high, -1, 2040, NULL, "Canny high threshold, -1 = 150",
         NULL},
        {"auto-canny", CLI_CHOICE, &o.auto_canny, 0, 0, auto_choices,
         "thresholds from the ROI histogram (none: --canny-low/high)", NULL},
        {"fit", CLI_CHOICE, &o.fit, 0, 0, fit_choices, "per-side line fit", NULL},
        {"no-color", CLI_FLAG, &o.no_color, 0, 0, NULL, "ignore colour (grey edges only)", NULL},
        {"no-curves", CLI_FLAG, &o.no_curves, 0, 0, NULL, "straight lanes only (no curve model)",
         NULL},
        {"hough-threshold", CLI_INT, &o.hough_threshold, -1, 100000, NULL,
         "segment votes, -1 = by height", NULL},
        {"min-length", CLI_INT, &o.min_length, -1, 100000, NULL, "shortest segment, -1 = by height",
         NULL},
        {"max-gap", CLI_INT, &o.max_gap, -1, 100000, NULL, "longest gap bridged, -1 = by height",
         NULL},
        {"hough-seed", CLI_INT, &o.hough_seed, 0, INT32_MAX, NULL,
         "point order of the Hough search, 0 = built in", NULL},
        {"hold", CLI_INT, &o.hold, -1, 1000, NULL, "frames a lost lane is predicted, -1 = 5", NULL},
        {"gate", CLI_INT, &o.gate, -1, 10000, NULL,
         "segment gate around tracked lanes (px), -1 = by height", NULL},
        {"alpha", CLI_INT, &o.alpha, -1, 256, NULL,
         "tracker: share of a measurement taken, /256 (256 = no smoothing)", NULL},
        {"beta", CLI_INT, &o.beta, -1, 256, NULL,
         "tracker: share of the innovation into the velocity, /256", NULL},
        {"blur", CLI_INT, &o.blur, 1, 31, NULL, "Gaussian kernel size (odd)", NULL},
        {"max-segments", CLI_INT, &o.max_segments, 1, RTE_LANE_MAX_SEGMENTS, NULL,
         "segments kept per frame", NULL},
        {0}};
    /* With --sequence there is no IN. */
    int positionals = 1;
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--sequence") == 0 || strncmp(argv[i], "--sequence=", 11) == 0)
            positionals = 0;
    cli_command cmd = {
        self->name,
        "IN | --sequence DIR_OR_Y4M",
        self->summary,
        "Prints the lanes as JSON: (x1, y1) on the bottom row, (x2, y2) on the ROI's\n"
        "top row (the chord), points [[x, y], ...] every 10 rows up the lane (then\n"
        "the far trace's, where a sharply turning marking is followed beyond the\n"
        "curve) and its curvature at the bottom row (1/px, > 0: bends right going up);\n"
        "offset_px = lane centre minus image centre on the bottom row.\n"
        "With --sequence, one JSON line per frame, tracked; a 4:2:0 .y4m file is\n"
        "read as NV12, its chroma giving the colour cue (as in rtedged).",
        options,
        positionals};
    const char *in = NULL;
    int rc = cli_parse(&cmd, argc, argv, &in);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    if (o.blur % 2 == 0) {
        cli_error(self->name, "--blur must be odd");
        return CLI_EXIT_USAGE;
    }
    if (!o.sequence)
        return lanes_image(self->name, &o, in);
    if (o.overlay) {
        cli_error(self->name, "--overlay works on a single image");
        return CLI_EXIT_USAGE;
    }
    struct stat sb;
    if (stat(o.sequence, &sb) != 0) {
        cli_error(self->name, "%s: cannot open", o.sequence);
        return CLI_EXIT_INPUT;
    }
    return S_ISDIR(sb.st_mode) ? lanes_directory(self->name, &o, o.sequence)
                               : lanes_y4m(self->name, &o, o.sequence);
}
