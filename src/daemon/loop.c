/* rtedged's loop: source -> pacer -> lane path -> grasp path -> LCM.
 *
 * Everything is sized in rted_daemon_open() from the configuration and the
 * source's maxima: the lane and grasp contexts, the grey buffer and the
 * message arrays (from one arena), the publisher's encode buffer. A frame
 * then makes no heap call: the messages are the generated C structs filled
 * in place, pointing at the preallocated arrays, and the publisher encodes
 * into its own buffer. Latency is capture -> publish on CLOCK_MONOTONIC; a
 * frame whose budget runs short skips the grasp path (counted). */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>

#include <linux/videodev2.h>

#include "daemon_internal.h"
#ifdef RTE_HAVE_LIBCAMERA
#include "sources/libcamera_source.h"
#endif
#include "sources/recorded_source.h"
#include "sources/v4l2_source.h"
#include "core/clock.h"

static bool ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && !strcasecmp(s + a - b, suffix);
}

static rted_source_kind guess_kind(const char *path)
{
    struct stat st;
    if (!strncmp(path, "udpm://", 7) || !strncmp(path, "memq://", 7))
        return RTED_SOURCE_LCM;
    if (!strncmp(path, "/dev/video", 10))
        return RTED_SOURCE_V4L2;
    if (ends_with(path, ".y4m"))
        return RTED_SOURCE_Y4M;
    if (ends_with(path, ".lcm") || ends_with(path, ".log") || !strncmp(path, "file://", 7) ||
        strstr(path, "lcmlog"))
        return RTED_SOURCE_LCM_LOG;
    if (ends_with(path, ".raw") || ends_with(path, ".yuv"))
        return RTED_SOURCE_RAW;
    if (strpbrk(path, "*?[") || (stat(path, &st) == 0 && S_ISDIR(st.st_mode)))
        return RTED_SOURCE_IMAGES;
    return RTED_SOURCE_Y4M;
}

static const char *kind_name(rted_source_kind k)
{
    static const char *const names[] = {"auto", "y4m",  "images", "raw",
                                        "lcm-log", "lcm", "v4l2", "libcamera"};
    return names[k];
}

/* source.format for a V4L2 camera: what the camera is asked to send (the
 * pixel format names, or mjpeg). */
static bool v4l2_format(const char *name, uint32_t *fourcc)
{
    if (!strcasecmp(name, "mjpeg")) {
        *fourcc = V4L2_PIX_FMT_MJPEG;
        return true;
    }
    switch (name[0] ? rte_pixel_format_parse(name) : RTE_PIXEL_YUYV) {
    case RTE_PIXEL_YUYV: *fourcc = V4L2_PIX_FMT_YUYV; return true;
    case RTE_PIXEL_UYVY: *fourcc = V4L2_PIX_FMT_UYVY; return true;
    case RTE_PIXEL_GREY: *fourcc = V4L2_PIX_FMT_GREY; return true;
    case RTE_PIXEL_NV12: *fourcc = V4L2_PIX_FMT_NV12; return true;
    default: return false;
    }
}

static bool open_source(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    rted_source_kind kind = c->source_kind ? (rted_source_kind)c->source_kind
                                           : guess_kind(c->source_path);
    uint32_t fourcc = 0;
    if (kind == RTED_SOURCE_V4L2 && !v4l2_format(c->source_format, &fourcc)) {
        rted_msgf(msg, msg_size, "source.format: a V4L2 camera is read as yuyv, uyvy, grey, nv12 or "
            "mjpeg, not: %s", c->source_format);
        return false;
    }
    rte_pixel_format fmt = c->source_format[0] && kind != RTED_SOURCE_V4L2
                               ? rte_pixel_format_parse(c->source_format) : 0;
    if (c->source_format[0] && kind != RTED_SOURCE_V4L2 && !fmt) {
        rted_msgf(msg, msg_size, "source.format: unknown pixel format: %s", c->source_format);
        return false;
    }
    char why[RTE_SOURCE_MESSAGE_SIZE] = "";
    rte_status st = RTE_ERR_ARGUMENT;
    int32_t fps_den = 1000, fps_num = (int32_t)lround(c->fps * 1000);
    switch (kind) {
    case RTED_SOURCE_Y4M:
        st = rte_y4m_source_open(&d->source, c->source_path, why, sizeof why);
        break;
    case RTED_SOURCE_IMAGES: {
        rte_images_source_config ic = {c->source_path, fmt ? fmt : RTE_PIXEL_BGR24, c->width,
                                       c->height, fps_num, fps_den};
        st = rte_images_source_open(&d->source, &ic, why, sizeof why);
        break;
    }
    case RTED_SOURCE_RAW: {
        rte_raw_source_config rc = {c->source_path, fmt ? fmt : RTE_PIXEL_GREY, c->width,
                                    c->height, fps_num, fps_den};
        st = rte_raw_source_open(&d->source, &rc, why, sizeof why);
        break;
    }
    case RTED_SOURCE_LCM_LOG:
    case RTED_SOURCE_LCM: {
        rte_lcm_source_config lc = {c->source_path, c->source_channel[0] ? c->source_channel : NULL,
                                    fmt, c->width, c->height};
        st = kind == RTED_SOURCE_LCM ? rte_lcm_live_source_open(&d->source, &lc, why, sizeof why)
                                     : rte_lcm_log_source_open(&d->source, &lc, why, sizeof why);
        break;
    }
    case RTED_SOURCE_V4L2: {
        rte_v4l2_config vc;
        memset(&vc, 0, sizeof vc);
        vc.device = c->source_path;
        vc.fourcc = fourcc;
        vc.width = c->width ? c->width : 1280;
        vc.height = c->height ? c->height : 720;
        vc.fps = (int32_t)lround(c->fps);
        vc.n_controls = rted_parse_controls(c->source_controls, vc.controls, RTE_V4L2_MAX_CONTROLS);
        rte_v4l2_info info;
        st = rte_v4l2_source_open(&d->source, &vc, &info, why, sizeof why);
        break;
    }
    case RTED_SOURCE_LIBCAMERA: {
#ifdef RTE_HAVE_LIBCAMERA
        rte_libcamera_config lc = {NULL, 0, fmt, c->width, c->height, 0};
        /* An index in --list-cameras (a few digits), else the camera's id. */
        char *end;
        errno = 0;
        long index = strtol(c->source_path, &end, 10);
        if (*end || end == c->source_path || errno || index < 0 || index > 1000)
            lc.camera = c->source_path;
        else
            lc.index = (int32_t)index;
        rte_libcamera_info info;
        st = rte_libcamera_source_open(&d->source, &lc, &info, why, sizeof why);
#else
        snprintf(why, sizeof why, "rtedge was built without libcamera");
        st = RTE_ERR_UNSUPPORTED;
#endif
        break;
    }
    case RTED_SOURCE_AUTO:
        break;
    }
    if (st != RTE_OK) {
        snprintf(msg, msg_size, "cannot open %s source %s: %s", kind_name(kind), c->source_path,
                 why[0] ? why : rte_status_message(st));
        return false;
    }
    /* Cameras say what they settled on (size, format, rate, adjustments). */
    if (why[0] && (kind == RTED_SOURCE_V4L2 || kind == RTED_SOURCE_LIBCAMERA))
        rted_log("%s source: %s", kind_name(kind), why);
    d->recorded = kind != RTED_SOURCE_LCM && kind != RTED_SOURCE_V4L2 &&
                  kind != RTED_SOURCE_LIBCAMERA;
    snprintf(d->source_id, sizeof d->source_id, "%s:%s", kind_name(kind), c->source_path);
    d->width = d->source.max_width;
    d->height = d->source.max_height;
    return true;
}

/* image_t's code for a delivered pixel format. */
static int32_t image_t_format(rte_pixel_format f)
{
    switch (f) {
    case RTE_PIXEL_GREY: return RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY;
    case RTE_PIXEL_BGR24: return RTEDGE_IMAGE_T_PIXEL_FORMAT_BGR;
    case RTE_PIXEL_RGB24: return RTEDGE_IMAGE_T_PIXEL_FORMAT_RGB;
    case RTE_PIXEL_YUYV: return RTEDGE_IMAGE_T_PIXEL_FORMAT_YUYV;
    case RTE_PIXEL_UYVY: return RTEDGE_IMAGE_T_PIXEL_FORMAT_UYVY;
    case RTE_PIXEL_NV12: return RTEDGE_IMAGE_T_PIXEL_FORMAT_NV12;
    }
    return RTEDGE_IMAGE_T_PIXEL_FORMAT_INVALID;
}

/* The rows of one image_t: one stride for every plane (NV12's chroma rows
 * are as long as its luma rows, rounded up to even), as the lcm-log source
 * reads them back. */
static int32_t record_stride(rte_pixel_format f, int32_t width)
{
    rte_frame layout;
    uint8_t probe;
    if (rte_frame_packed(&layout, f, width, 1, &probe, SIZE_MAX) != RTE_OK)
        return 0;
    return layout.stride[1] > layout.stride[0] ? layout.stride[1] : layout.stride[0];
}

static size_t record_bytes(rte_pixel_format f, int32_t width, int32_t height)
{
    size_t rows = (size_t)height + (f == RTE_PIXEL_NV12 ? (size_t)(height + 1) / 2 : 0);
    return rows * (size_t)record_stride(f, width);
}

/* source.record: a file:// publisher of its own, sized for the source's
 * largest frame. */
static bool open_recording(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    size_t bytes = record_bytes(d->source.format, d->width, d->height);
    if (!bytes || bytes > (1u << 30)) {
        snprintf(msg, msg_size, "source.record: cannot record %dx%d %s frames", d->width,
                 d->height, rte_pixel_format_name(d->source.format));
        return false;
    }
    d->rec_buf = malloc(bytes);
    if (!d->rec_buf) {
        rted_msgf(msg, msg_size, "out of memory");
        return false;
    }
    char url[RTED_TEXT + 16], why[RTE_PUBLISH_MESSAGE_SIZE] = "";
    snprintf(url, sizeof url, "%s%s", strncmp(c->record_path, "file://", 7) ? "file://" : "",
             c->record_path);
    rte_publish_limits lim = {RTED_TEXT + 16, 0, 0, 0, 0, (int32_t)bytes, 0};
    if (rte_publisher_create(&d->rec, url, &lim, why, sizeof why) != RTE_OK) {
        snprintf(msg, msg_size, "source.record: %s", why);
        return false;
    }
    d->rec_msg.pixelformat = image_t_format(d->source.format);
    d->rec_msg.data = d->rec_buf;
    return true;
}

/* Copies the frame, row by row, into the recording's buffer and logs it. */
static void record_frame(rted_daemon *d, const rte_source_frame *f)
{
    const rte_frame *fr = &f->frame;
    rte_frame layout;
    uint8_t probe;
    int32_t stride = record_stride(fr->format, fr->width);
    if (fr->width > d->width || fr->height > d->height || !stride ||
        rte_frame_packed(&layout, fr->format, fr->width, 1, &probe, SIZE_MAX) != RTE_OK) {
        d->n.publish_errors++;
        return;
    }
    for (int p = 0; p < RTE_FRAME_MAX_PLANES && fr->plane[p]; p++) {
        int32_t rows = p ? (fr->height + 1) / 2 : fr->height;
        uint8_t *dst = d->rec_buf + (p ? (size_t)stride * (size_t)fr->height : 0);
        for (int32_t y = 0; y < rows; y++)
            memcpy(dst + (size_t)y * (size_t)stride, fr->plane[p] + (size_t)y * (size_t)fr->stride[p],
                   (size_t)layout.stride[p]);
    }
    rtedge_image_t *m = &d->rec_msg;
    m->utime = f->capture_ns / 1000;
    m->width = fr->width;
    m->height = fr->height;
    m->row_stride = stride;
    m->size = (int32_t)record_bytes(fr->format, fr->width, fr->height);
    m->nmetadata = 0;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (rte_publish_image(d->rec, d->cfg.image_channel, m, msg, sizeof msg) != RTE_OK)
        d->n.publish_errors++;
}

static void realtime(const rted_config *c)
{
    if (c->rt_mlockall && mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
        rted_log("warning: mlockall: %s (memory not locked)", strerror(errno));
    if (c->rt_cpu >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(c->rt_cpu, &set);
        if (sched_setaffinity(0, sizeof set, &set) != 0)
            rted_log("warning: CPU affinity %d: %s (not pinned)", c->rt_cpu, strerror(errno));
    }
    if (c->rt_priority > 0) {
        struct sched_param sp = {.sched_priority = c->rt_priority};
        if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0)
            rted_log("warning: SCHED_FIFO priority %d: %s (normal scheduling)", c->rt_priority,
                     strerror(errno));
    }
}

bool rted_daemon_open(rted_daemon **out, const rted_config *cfg, const char *config_path,
                      char *msg, size_t msg_size)
{
    *out = NULL;
    rted_daemon *d = calloc(1, sizeof *d);
    if (!d) {
        rted_msgf(msg, msg_size, "out of memory");
        return false;
    }
    d->cfg = *cfg;
    d->config_path = config_path;
    d->log_frames = (rted_log_limit){.what = "bad-frame", .burst = 5};
    if (!open_source(d, msg, msg_size))
        goto fail;
    const rted_config *c = &d->cfg;
    char why[RTED_MSG];
    if (!rted_config_check_frame(c, d->width, d->height, why, sizeof why)) {
        rted_msgf(msg, msg_size, "the configuration does not fit the source: %s", why);
        goto fail;
    }

    /* Pacing: recordings at their pace, live sources as they come. */
    rte_pacer_config pc = {RTE_PACE_FAST, 1000, 1, 1, -1, 0};
    if (d->recorded && c->pace == RTED_PACE_RECORDED)
        pc.mode = RTE_PACE_RECORDED;
    else if (d->recorded && c->pace == RTED_PACE_FPS)
        pc.mode = RTE_PACE_FPS;
    pc.speed_permille = (int32_t)lround(c->speed * 1000);
    if (pc.speed_permille < 1)
        pc.speed_permille = 1;
    pc.fps_num = (int32_t)lround(c->fps * 1000);
    pc.fps_den = 1000;
    pc.max_late_ns = c->max_late_ms < 0 ? -1 : (int64_t)llround(c->max_late_ms * 1e6);
    pc.max_pause_ns = (int64_t)c->max_pause_ms * 1000000;
    if (rte_pacer_init(&d->pacer, &pc) != RTE_OK) {
        rted_msgf(msg, msg_size, "bad pacing (source.fps, source.speed)");
        goto fail;
    }

    rte_lane_config_default(&d->lane_base, d->width, d->height);
    d->lane_base.max_width = d->width;
    d->lane_base.max_height = d->height;
    d->lane_base.max_segments = c->lane_max_segments;
    d->lane_base.blur_ksize = c->lane_blur_ksize;
    if (c->lane_enabled) {
        rte_lane_config lc = d->lane_base;
        if (!rted_lane_params(d, c, &lc.params)) {
            rted_msgf(msg, msg_size, "the lane configuration is invalid for this source");
            goto fail;
        }
        rte_status st = rte_lane_create(&lc, &d->lane);
        if (st != RTE_OK) {
            rted_msgf(msg, msg_size, "lane path: %s", rte_status_message(st));
            goto fail;
        }
    }
    if (c->grasp_enabled) {
        rte_grasp_config gc;
        rte_grasp_config_default(&gc);
        gc.max_width = d->width;
        gc.max_height = d->height;
        gc.max_contours = c->grasp_max_contours;
        gc.max_points = c->grasp_max_points;
        gc.max_objects = c->grasp_max_objects;
        gc.blur_ksize = c->grasp_blur_ksize;
        rted_grasp_params(c, &gc.params);
        rte_status st = rte_grasp_create(&gc, &d->grasp);
        if (st != RTE_OK) {
            rted_msgf(msg, msg_size, "the grasp configuration is invalid for this source: %s",
                rte_status_message(st));
            goto fail;
        }
    }

    /* One arena for the grey frame and the message arrays. */
    size_t gray_bytes = (size_t)d->width * (size_t)d->height;
    size_t seg_bytes = (size_t)c->lane_max_segments * sizeof(rtedge_segment_t);
    size_t obj_bytes = (size_t)c->grasp_max_objects * sizeof(rtedge_grasp_object_t);
    size_t total = rte_arena_piece_size(gray_bytes) + rte_arena_piece_size(seg_bytes) +
                   rte_arena_piece_size(obj_bytes) + RTE_ARENA_ALIGN;
    d->memory = malloc(total);
    if (!d->memory) {
        rted_msgf(msg, msg_size, "out of memory");
        goto fail;
    }
    rte_arena_init(&d->arena, d->memory, total);
    d->gray = (rte_image_u8){d->width, d->height, d->width, rte_arena_alloc(&d->arena, gray_bytes)};
    d->segments = rte_arena_alloc(&d->arena, seg_bytes);
    d->objects = rte_arena_alloc(&d->arena, obj_bytes);
    memset(d->objects, 0, obj_bytes);
    memset(d->segments, 0, seg_bytes);

    rte_publish_limits lim = {RTED_TEXT + 16, RTE_LANE_MAX_ROI_VERTICES, c->lane_max_segments,
                              c->grasp_max_objects, RTED_MAX_SETS,
                              c->publish_images ? (int32_t)gray_bytes : 0, 0};
    if (rte_publisher_create(&d->pub, c->lcm_url, &lim, why, sizeof why) != RTE_OK) {
        snprintf(msg, msg_size, "cannot publish to %s: %s", c->lcm_url, why);
        goto fail;
    }
    rted_params_open(d);

    if (c->record_path[0] && !open_recording(d, msg, msg_size))
        goto fail;

    d->lane_msg.header.source_id = d->source_id;
    d->lane_msg.header.roi = d->roi;
    d->lane_msg.segments = d->segments;
    d->grasp_msg.header.source_id = d->source_id;
    d->grasp_msg.header.roi = d->roi;
    d->grasp_msg.objects = d->objects;
    d->status_msg.source_id = d->source_id;
    d->image_msg.pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY;
    rted_derive(d);
    realtime(c);
    d->window_start_ns = rte_clock_now_ns();
    /* A first status says the daemon is up; it also makes liblcm cache the
     * channel (memq:// strdup()s a channel's name on its first message). */
    rted_daemon_publish_status(d);
    *out = d;
    return true;
fail:
    rted_daemon_close(d);
    return false;
}

void rted_daemon_close(rted_daemon *d)
{
    if (!d)
        return;
    rted_params_close(d);
    rte_publisher_destroy(d->pub);
    rte_publisher_destroy(d->rec);
    free(d->rec_buf);
    rte_grasp_destroy(d->grasp);
    rte_lane_destroy(d->lane);
    rte_source_close(&d->source);
    free(d->memory);
    free(d);
}

lcm_t *rted_daemon_lcm(rted_daemon *d) { return rte_publisher_lcm(d->pub); }

void rted_daemon_get_counters(const rted_daemon *d, rted_counters *c) { *c = d->n; }

const rted_config *rted_daemon_config(const rted_daemon *d) { return &d->cfg; }

void rted_daemon_set_overrides(rted_daemon *d, char *const *sets, int n_sets)
{
    d->sets = sets;
    d->n_sets = n_sets;
}

/* ---- one frame ---- */

static void fill_header(rted_daemon *d, rtedge_header_t *h, const rte_source_frame *f,
                        int64_t t_pub)
{
    h->capture_utime = f->capture_ns / 1000;
    h->publish_utime = t_pub / 1000;
    h->sequence = (int64_t)f->sequence;
    h->width = f->frame.width;
    h->height = f->frame.height;
    int64_t lat = (t_pub - f->capture_ns) / 1000;
    h->latency_us = lat > INT32_MAX ? INT32_MAX : (int32_t)lat;
    h->deadline_us = (int32_t)(d->deadline_ns / 1000);
    h->deadline_met = h->latency_us <= h->deadline_us;
}

static void fill_lane(rtedge_lane_t *m, const rte_lane *l)
{
    m->found = l->found;
    m->predicted = l->predicted;
    m->x1 = (float)l->x_bottom_q8 / RTE_LANE_ONE;
    m->y1 = (float)l->y_bottom;
    m->x2 = (float)l->x_top_q8 / RTE_LANE_ONE;
    m->y2 = (float)l->y_top;
    int32_t dy = l->y_top - l->y_bottom;
    m->slope = dy ? (m->x2 - m->x1) / (float)dy : 0.0f;
    m->confidence = (float)l->confidence_permille / 1000.0f;
}

static void publish_lane(rted_daemon *d, const rte_source_frame *f, const rte_lane_result *r)
{
    rtedge_lane_detection_t *m = &d->lane_msg;
    int32_t n = r->segment_count < d->cfg.lane_max_segments ? r->segment_count
                                                            : d->cfg.lane_max_segments;
    for (int32_t i = 0; i < n; i++)
        d->segments[i] = (rtedge_segment_t){r->segments[i].x0, r->segments[i].y0,
                                            r->segments[i].x1, r->segments[i].y1};
    m->nsegments = n;
    m->segments_truncated = r->truncated || n < r->segment_count;
    fill_lane(&m->left, &r->lane[RTE_LANE_LEFT]);
    fill_lane(&m->right, &r->lane[RTE_LANE_RIGHT]);
    m->centre_valid = r->centre_valid;
    m->centre_offset_px = (float)r->offset_q8 / RTE_LANE_ONE;
    m->centre_offset_frac = (float)r->offset_permille / 1000.0f;
    m->heading_rad = (float)r->heading_mrad / 1000.0f;
    fill_header(d, &m->header, f, rte_clock_now_ns());
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (rte_publish_lane(d->pub, d->cfg.lane_channel, m, msg, sizeof msg) == RTE_OK)
        d->n.published++;
    else
        d->n.publish_errors++;
}

static void publish_grasp(rted_daemon *d, const rte_source_frame *f, const rte_grasp_result *r)
{
    rtedge_grasp_detection_t *m = &d->grasp_msg;
    int32_t n = r->n_objects < d->cfg.grasp_max_objects ? r->n_objects : d->cfg.grasp_max_objects;
    for (int32_t i = 0; i < n; i++) {
        const rte_grasp_object *o = &r->objects[i];
        const rte_shape_info *s = &o->info;
        rtedge_grasp_object_t *g = &d->objects[i];
        g->centroid_x = (float)((double)s->cx_q16 / 65536);
        g->centroid_y = (float)((double)s->cy_q16 / 65536);
        g->area = (float)((double)s->area2 / 2);
        g->perimeter = (float)((double)s->perimeter_q16 / 65536);
        g->bbox_x = s->bounds.x;
        g->bbox_y = s->bounds.y;
        g->bbox_width = s->bounds.width;
        g->bbox_height = s->bounds.height;
        g->rect_centre_x = (float)s->box.cx_q8 / 256;
        g->rect_centre_y = (float)s->box.cy_q8 / 256;
        g->rect_width = (float)s->box.length_q8 / 256;
        g->rect_height = (float)s->box.width_q8 / 256;
        g->rect_angle_deg = (float)s->box.angle_q16 / 65536;
        for (int k = 0; k < 4; k++) {
            g->rect_corners_x[k] = (float)s->box.corners_q8[k][0] / 256;
            g->rect_corners_y[k] = (float)s->box.corners_q8[k][1] / 256;
        }
        g->shape = (int8_t)s->shape;
        g->vertices = s->vertices;
        g->solidity = (float)s->solidity_q16 / 65536;
        g->extent = (float)s->extent_q16 / 65536;
        g->aspect_ratio = (float)s->aspect_q16 / 65536;
        g->grasp_x = (float)o->x_q8 / 256;
        g->grasp_y = (float)o->y_q8 / 256;
        g->approach_angle_deg = (float)o->angle_q16 / 65536;
        g->opening_width_px = (float)o->width_q8 / 256;
    }
    m->nobjects = n;
    m->objects_truncated = r->truncated || n < r->n_objects;
    fill_header(d, &m->header, f, rte_clock_now_ns());
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (rte_publish_grasp(d->pub, d->cfg.grasp_channel, m, msg, sizeof msg) == RTE_OK)
        d->n.published++;
    else
        d->n.publish_errors++;
}

static void publish_image(rted_daemon *d, const rte_source_frame *f, const rte_image_u8 *g)
{
    rtedge_image_t *m = &d->image_msg;
    /* A view of the grey image when it is packed, else the daemon's copy. */
    if (g->stride != g->width) {
        for (int32_t y = 0; y < g->height; y++)
            memcpy(d->gray.buf + (size_t)y * (size_t)g->width, g->buf + (size_t)y * (size_t)g->stride,
                   (size_t)g->width);
        g = &d->gray;
    }
    m->utime = f->capture_ns / 1000;
    m->width = g->width;
    m->height = g->height;
    m->row_stride = g->width;
    m->size = g->width * g->height;
    m->data = g->buf;
    m->nmetadata = 0;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (rte_publish_image(d->pub, d->cfg.image_channel, m, msg, sizeof msg) == RTE_OK)
        d->n.published++;
    else
        d->n.publish_errors++;
}

/* A path (0 lane, 1 grasp) that could not process a frame: counted, and
 * said once for each new reason (a failure that persists, such as a ROI
 * that misses smaller frames of an image directory, is not repeated). */
static void path_error(rted_daemon *d, int path, const rte_source_frame *f, rte_status st)
{
    if (st == RTE_OK) {
        d->path_said[path] = RTE_OK;
        return;
    }
    d->n.path_errors++;
    if (d->path_said[path] == st)
        return;
    d->path_said[path] = st;
    rted_log("%s path: frame %llu (%dx%d) not processed: %s (said once; status_t counts "
             "path_errors)", path ? "grasp" : "lane", (unsigned long long)f->sequence,
             f->frame.width, f->frame.height, rte_status_message(st));
}

static rted_step analyse(rted_daemon *d, const rte_source_frame *f)
{
    const int64_t t0 = f->capture_ns;
    if (d->lane) {
        rte_lane_result lr;
        rte_status st = rte_lane_process(d->lane, &f->frame, f->recorded_ns, &lr);
        if (st == RTE_OK)
            publish_lane(d, f, &lr);
        path_error(d, 0, f, st);
    }
    rte_image_u8 gray;
    bool need_gray = d->grasp || d->cfg.publish_images;
    if (need_gray && rte_frame_gray_view(&f->frame, &gray) != RTE_OK) {
        gray = d->gray;
        gray.width = f->frame.width;
        gray.height = f->frame.height;
        rte_frame_to_gray(&f->frame, &gray);
    }
    if (d->grasp) {
        /* The optional stage: only when the budget still holds it. */
        if (d->deadline_ns - (rte_clock_now_ns() - t0) < d->grasp_min_ns) {
            d->n.stages_skipped++;
        } else {
            rte_grasp_result gr;
            rte_status st = rte_grasp_process(d->grasp, &gray, &gr);
            if (st == RTE_OK)
                publish_grasp(d, f, &gr);
            path_error(d, 1, f, st);
        }
    }
    if (d->cfg.publish_images) {
        if (d->deadline_ns - (rte_clock_now_ns() - t0) < d->grasp_min_ns)
            d->n.stages_skipped++;
        else
            publish_image(d, f, &gray);
    }
    int64_t lat = rte_clock_now_ns() - t0;
    rted_record_latency(d, lat);
    if (lat > d->deadline_ns)
        d->n.deadline_misses++;
    d->n.processed++;
    d->window_processed++;
    return RTED_STEP_FRAME;
}

/* The end of a recording: start again (source.loop), or stop. A pass that
 * gave no readable frame stops the daemon either way, rather than rewinding
 * without end or ending as if all was well. A rewind is not a reconnection:
 * no message, no status, the latency window goes on. */
static rted_step end_of_pass(rted_daemon *d)
{
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    d->n.bad_frames = ss.bad_frames;
    d->state = RTE_SOURCE_ENDED;
    if (!d->pass_frames) {
        rted_log("%s: %s gave no readable frame (%llu bad frames in all): stopping",
                 d->source_id, d->passes ? "a whole pass of the recording" : "the recording",
                 (unsigned long long)ss.bad_frames);
        return RTED_STEP_EMPTY;
    }
    if (!d->cfg.loop || rte_recorded_source_rewind(&d->source) != RTE_OK)
        return RTED_STEP_END;
    d->state = RTE_SOURCE_STREAMING;
    d->n.rewinds++;
    d->passes++;
    d->pass_frames = 0;
    return RTED_STEP_IDLE;
}

static void sleep_ns(int64_t ns)
{
    struct timespec ts = {ns / 1000000000, ns % 1000000000};
    nanosleep(&ts, NULL);
}

rted_step rted_daemon_step(rted_daemon *d)
{
    if (d->cfg.max_frames && d->n.processed >= (uint64_t)d->cfg.max_frames)
        return RTED_STEP_END;
    rted_params_poll(d);
    if (rte_clock_now_ns() - d->window_start_ns >= (int64_t)d->cfg.status_period_ms * 1000000)
        rted_daemon_publish_status(d);

    rte_source_frame f;
    char why[RTE_SOURCE_MESSAGE_SIZE] = "";
    rte_status st = rte_source_next(&d->source, &f, 100, why, sizeof why);
    if (st == RTE_ERR_END)
        return end_of_pass(d);
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    d->n.bad_frames = ss.bad_frames;
    if (ss.state != d->reported_state) {
        /* A camera lost or back: said at once, not at the next period. */
        if (ss.state == RTE_SOURCE_STREAMING)
            rted_log("source streaming again (reconnection %llu)",
                     (unsigned long long)ss.reconnects);
        rted_daemon_publish_status(d);
    }
    if (st == RTE_ERR_TIMEOUT)
        return RTED_STEP_IDLE;
    if (st != RTE_OK) {
        if (ss.state == RTE_SOURCE_FAILED) {
            rted_log("source failed: %s", why);
            return RTED_STEP_FAILED;
        }
        /* A looping recording's bad frames were said in its first pass. */
        if (!d->passes)
            rted_log_limited(&d->log_frames, "%s: %s",
                             st == RTE_ERR_DEVICE ? "source" : "frame skipped",
                             why[0] ? why : rte_status_message(st));
        return RTED_STEP_IDLE;
    }
    d->pass_frames++;
    d->n.received++;
    if (d->rec)
        record_frame(d, &f);
    bool waited = false;
    for (;;) {
        int64_t wait = 0;
        rte_pace_action a = rte_pacer_decide(&d->pacer, f.recorded_ns, rte_clock_now_ns(), &wait);
        if (a == RTE_PACE_DROP) {
            d->n.dropped++;
            return RTED_STEP_IDLE;
        }
        if (a == RTE_PACE_PROCESS)
            break;
        if (d->stop && *d->stop)
            return RTED_STEP_IDLE;
        sleep_ns(wait > 50000000 ? 50000000 : wait);
        waited = true;
        if (d->cfg.status_period_ms &&
            rte_clock_now_ns() - d->window_start_ns >= (int64_t)d->cfg.status_period_ms * 1000000)
            rted_daemon_publish_status(d);
    }
    /* Recordings: the frame is "captured" when it is due, not when it was
     * read ahead of its time. */
    if (d->recorded && waited)
        f.capture_ns = rte_clock_now_ns();
    return analyse(d, &f);
}

int rted_daemon_run(rted_daemon *d, volatile sig_atomic_t *stop, volatile sig_atomic_t *reload)
{
    int code = RTED_EXIT_OK;
    d->stop = stop;
    while (!*stop) {
        if (*reload) {
            *reload = 0;
            char msg[RTED_MSG];
            if (rted_daemon_reload(d, msg, sizeof msg))
                rted_log("configuration re-read and applied (hash %016llx)",
                         (unsigned long long)d->config_hash);
            else
                rted_log("configuration change refused: %s", msg);
        }
        rted_step s = rted_daemon_step(d);
        if (s == RTED_STEP_END)
            break;
        if (s == RTED_STEP_FAILED || s == RTED_STEP_EMPTY) {
            code = s == RTED_STEP_FAILED ? RTED_EXIT_FAILED : RTED_EXIT_NO_FRAMES;
            break;
        }
    }
    rted_daemon_publish_status(d);
    return code;
}
