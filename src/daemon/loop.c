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
#include "daemon.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>

#include <linux/videodev2.h>

#include "rtedge/arena.h"
#include "rtedge/grasp.h"
#ifdef RTE_HAVE_LIBCAMERA
#include "rtedge/libcamera_source.h"
#endif
#include "rtedge/lane.h"
#include "rtedge/pacer.h"
#include "rtedge/publish.h"
#include "rtedge/recorded_source.h"
#include "rtedge/v4l2_source.h"

/* Latencies kept per status window (the newest ones when more frames came). */
#define RTED_RING 8192
#define RTED_MAX_SETS 64

struct rted_daemon {
    rted_config cfg;
    const char *config_path;
    char *const *sets;
    int n_sets;
    uint64_t config_hash;
    int64_t deadline_ns, grasp_min_ns;

    rte_source source;
    bool recorded;
    char source_id[RTED_TEXT + 16];
    int32_t width, height; /* the source's maxima */
    rte_pacer pacer;

    rte_lane_context *lane;
    rte_lane_config lane_base; /* defaults for the frame size, before the file's keys */
    rte_grasp_ctx *grasp;
    rte_publisher *pub;
    lcm_subscription_t *params_sub;

    /* source.record: every delivered frame, packed, as image_t. */
    rte_publisher *rec;
    uint8_t *rec_buf;
    rtedge_image_t rec_msg;

    void *memory;
    rte_arena arena;
    rte_image_u8 gray;
    rtedge_segment_t *segments;
    rtedge_grasp_object_t *objects;
    rtedge_point_t roi[RTE_LANE_MAX_ROI_VERTICES];
    rtedge_lane_detection_t lane_msg;
    rtedge_grasp_detection_t grasp_msg;
    rtedge_image_t image_msg;
    rtedge_status_t status_msg;

    rted_counters n;
    int32_t ring[RTED_RING], sorted[RTED_RING];
    uint32_t ring_n;          /* latencies in the window (may exceed RTED_RING) */
    int32_t window_max;
    uint64_t window_processed;
    int64_t window_start_ns;
    rte_source_state state;
    rte_source_state reported_state; /* the source's state in the last status */
    volatile sig_atomic_t *stop; /* rted_daemon_run's flag: ends a wait for a frame's time */
};

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static void say(char *msg, size_t size, const char *what, const char *detail)
{
    snprintf(msg, size, "%s%s%s", what, detail && *detail ? ": " : "", detail ? detail : "");
}

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
        say(msg, msg_size, "source.format: a V4L2 camera is read as yuyv, uyvy, grey, nv12 or "
            "mjpeg, not", c->source_format);
        return false;
    }
    rte_pixel_format fmt = c->source_format[0] && kind != RTED_SOURCE_V4L2
                               ? rte_pixel_format_parse(c->source_format) : 0;
    if (c->source_format[0] && kind != RTED_SOURCE_V4L2 && !fmt) {
        say(msg, msg_size, "source.format: unknown pixel format", c->source_format);
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
        char *end;
        long index = strtol(c->source_path, &end, 10);
        if (*end || end == c->source_path)
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
        fprintf(stderr, "rtedged: %s source: %s\n", kind_name(kind), why);
    d->recorded = kind != RTED_SOURCE_LCM && kind != RTED_SOURCE_V4L2 &&
                  kind != RTED_SOURCE_LIBCAMERA;
    snprintf(d->source_id, sizeof d->source_id, "%s:%s", kind_name(kind), c->source_path);
    d->width = d->source.max_width;
    d->height = d->source.max_height;
    return true;
}

/* The lane parameters: the size's defaults with the configured keys over them. */
static bool lane_params(const rted_daemon *d, const rted_config *c, rte_lane_params *p)
{
    *p = d->lane_base.params;
    int32_t xy[2 * RTE_LANE_MAX_ROI_VERTICES];
    int32_t n = rted_parse_roi(c->lane_roi, xy, RTE_LANE_MAX_ROI_VERTICES);
    if (n < 0)
        return false;
    for (int32_t i = 0; i < n; i++) {
        p->roi[i].x = xy[2 * i];
        p->roi[i].y = xy[2 * i + 1];
    }
    p->roi_count = n;
    p->canny_mode = (rte_lane_canny_mode)c->lane_canny_mode;
    if (c->lane_canny_low >= 0) {
        p->canny_low = c->lane_canny_low;
        p->canny_high = c->lane_canny_high;
    }
    if (c->lane_hough_threshold >= 0)
        p->hough_threshold = c->lane_hough_threshold;
    if (c->lane_min_length >= 0)
        p->min_length = c->lane_min_length;
    if (c->lane_max_gap >= 0)
        p->max_gap = c->lane_max_gap;
    p->hough_seed = (uint32_t)c->lane_hough_seed;
    if (c->lane_hold_frames >= 0)
        p->hold_frames = c->lane_hold_frames;
    if (c->lane_gate_px >= 0)
        p->gate_px = c->lane_gate_px;
    p->use_color = c->lane_use_color;
    return true;
}

static void grasp_params(const rted_config *c, rte_grasp_params *p)
{
    p->binarize = (rte_grasp_binarize)c->grasp_binarize;
    p->threshold = c->grasp_threshold;
    p->polarity = (rte_grasp_polarity)c->grasp_polarity;
    p->min_area = c->grasp_min_area;
    p->max_area = c->grasp_max_area;
    p->skip_border = c->grasp_skip_border;
    p->max_objects = c->grasp_max_objects;
}

static void derive(rted_daemon *d)
{
    const rted_config *c = &d->cfg;
    double ms = c->deadline_ms > 0 ? c->deadline_ms : 1000.0 / c->fps;
    d->deadline_ns = (int64_t)llround(ms * 1e6);
    d->grasp_min_ns = (int64_t)llround(c->grasp_min_budget_ms * 1e6);
    d->config_hash = rted_config_hash(c);
    /* The header's ROI in pixels of the analysed frame. */
    const rte_lane_params *p = &d->lane_base.params;
    rte_lane_params lp;
    if (!lane_params(d, c, &lp))
        lp = *p;
    for (int32_t i = 0; i < lp.roi_count; i++) {
        d->roi[i].x = (int32_t)(((int64_t)lp.roi[i].x * d->width + 32768) >> 16);
        d->roi[i].y = (int32_t)(((int64_t)lp.roi[i].y * d->height + 32768) >> 16);
    }
    d->lane_msg.header.roi_npoints = (int16_t)lp.roi_count;
    d->grasp_msg.header.roi_npoints = 0;
}

static void on_params(const lcm_recv_buf_t *rbuf, const char *channel, void *user);

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
        say(msg, msg_size, "out of memory", NULL);
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
        fprintf(stderr, "rtedged: warning: mlockall: %s (memory not locked)\n", strerror(errno));
    if (c->rt_cpu >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(c->rt_cpu, &set);
        if (sched_setaffinity(0, sizeof set, &set) != 0)
            fprintf(stderr, "rtedged: warning: CPU affinity %d: %s (not pinned)\n", c->rt_cpu,
                    strerror(errno));
    }
    if (c->rt_priority > 0) {
        struct sched_param sp = {.sched_priority = c->rt_priority};
        if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0)
            fprintf(stderr, "rtedged: warning: SCHED_FIFO priority %d: %s (normal scheduling)\n",
                    c->rt_priority, strerror(errno));
    }
}

bool rted_daemon_open(rted_daemon **out, const rted_config *cfg, const char *config_path,
                      char *msg, size_t msg_size)
{
    *out = NULL;
    rted_daemon *d = calloc(1, sizeof *d);
    if (!d) {
        say(msg, msg_size, "out of memory", NULL);
        return false;
    }
    d->cfg = *cfg;
    d->config_path = config_path;
    if (!open_source(d, msg, msg_size))
        goto fail;
    const rted_config *c = &d->cfg;

    /* Pacing: recordings at their pace, live sources as they come. */
    rte_pacer_config pc = {RTE_PACE_FAST, 1000, 1, 1, -1};
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
    if (rte_pacer_init(&d->pacer, &pc) != RTE_OK) {
        say(msg, msg_size, "bad pacing (source.fps, source.speed)", NULL);
        goto fail;
    }

    rte_lane_config_default(&d->lane_base, d->width, d->height);
    d->lane_base.max_width = d->width;
    d->lane_base.max_height = d->height;
    d->lane_base.max_segments = c->lane_max_segments;
    d->lane_base.blur_ksize = c->lane_blur_ksize;
    if (c->lane_enabled) {
        rte_lane_config lc = d->lane_base;
        if (!lane_params(d, c, &lc.params)) {
            say(msg, msg_size, "the lane configuration is invalid for this source", NULL);
            goto fail;
        }
        rte_status st = rte_lane_create(&lc, &d->lane);
        if (st != RTE_OK) {
            say(msg, msg_size, "lane path: %s", rte_status_message(st));
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
        grasp_params(c, &gc.params);
        rte_status st = rte_grasp_create(&gc, &d->grasp);
        if (st != RTE_OK) {
            say(msg, msg_size, "the grasp configuration is invalid for this source",
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
        say(msg, msg_size, "out of memory", NULL);
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
    char why[RTE_PUBLISH_MESSAGE_SIZE] = "";
    if (rte_publisher_create(&d->pub, c->lcm_url, &lim, why, sizeof why) != RTE_OK) {
        snprintf(msg, msg_size, "cannot publish to %s: %s", c->lcm_url, why);
        goto fail;
    }
    if (c->params_enabled) {
        lcm_t *lcm = rte_publisher_lcm(d->pub);
        if (!lcm)
            fprintf(stderr, "rtedged: warning: publish.params_enabled needs an LCM transport, "
                            "not %s: no params channel\n", c->lcm_url);
        else
            d->params_sub = lcm_subscribe(lcm, c->params_channel, on_params, d);
    }

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
    derive(d);
    realtime(c);
    d->window_start_ns = now_ns();
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
    if (d->params_sub && d->pub)
        lcm_unsubscribe(rte_publisher_lcm(d->pub), d->params_sub);
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

void rted_daemon_set_overrides(rted_daemon *d, char *const *sets, int n_sets)
{
    d->sets = sets;
    d->n_sets = n_sets;
}

/* ---- run-time configuration ---- */

bool rted_daemon_apply(rted_daemon *d, const rted_config *next, char *msg, size_t msg_size)
{
    char fixed[160];
    if (rted_config_fixed_change(&d->cfg, next, fixed, sizeof fixed)) {
        snprintf(msg, msg_size, "%s cannot change while running (it fixes sizes or the source): "
                 "restart rtedged", fixed);
        d->n.refused++;
        return false;
    }
    if (!rted_config_validate(next, msg, msg_size)) {
        d->n.refused++;
        return false;
    }
    rte_lane_params lp;
    if (d->lane && (!lane_params(d, next, &lp) || rte_lane_set_params(d->lane, &lp) != RTE_OK)) {
        snprintf(msg, msg_size, "the lane parameters were refused by the lane path");
        d->n.refused++;
        return false;
    }
    if (d->grasp) {
        rte_grasp_params gp;
        rte_grasp_get_params(d->grasp, &gp);
        grasp_params(next, &gp);
        if (rte_grasp_set_params(d->grasp, &gp) != RTE_OK) {
            snprintf(msg, msg_size, "the grasp parameters were refused by the grasp path");
            d->n.refused++;
            return false;
        }
    }
    d->cfg = *next;
    derive(d);
    d->n.reloads++;
    msg[0] = 0;
    return true;
}

bool rted_daemon_reload(rted_daemon *d, char *msg, size_t msg_size)
{
    if (!d->config_path) {
        snprintf(msg, msg_size, "no configuration file to re-read (started without --config)");
        d->n.refused++;
        return false;
    }
    rted_config next;
    rted_config_defaults(&next);
    bool ok = rted_config_load(&next, d->config_path, msg, msg_size);
    for (int i = 0; ok && i < d->n_sets; i++)
        ok = rted_config_set(&next, d->sets[i], "--set", msg, msg_size);
    if (!ok) {
        d->n.refused++;
        return false;
    }
    return rted_daemon_apply(d, &next, msg, msg_size);
}

/* params_t: each "section.key" set on a copy, then applied as one change. */
static void on_params(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    rted_daemon *d = user;
    rtedge_params_t m;
    char msg[RTED_MSG];
    if (rtedge_params_t_decode(rbuf->data, 0, (int)rbuf->data_size, &m) < 0) {
        fprintf(stderr, "rtedged: %s: not a params_t message: ignored\n", channel);
        d->n.refused++;
        return;
    }
    rted_config next = d->cfg;
    bool ok = true;
    for (int32_t i = 0; ok && i < m.nparams; i++) {
        const rtedge_param_t *p = &m.params[i];
        char set[RTED_TEXT + 128];
        if (p->kind == RTEDGE_PARAM_T_KIND_REAL)
            snprintf(set, sizeof set, "%s=%.17g", p->name, p->real_value);
        else if (p->kind == RTEDGE_PARAM_T_KIND_BOOL)
            snprintf(set, sizeof set, "%s=%s", p->name, p->int_value ? "true" : "false");
        else
            snprintf(set, sizeof set, "%s=%lld", p->name, (long long)p->int_value);
        ok = rted_config_set(&next, set, channel, msg, sizeof msg);
    }
    if (!ok)
        d->n.refused++;
    else
        ok = rted_daemon_apply(d, &next, msg, sizeof msg);
    if (!ok)
        fprintf(stderr, "rtedged: params request %lld refused: %s\n", (long long)m.request_id, msg);
    else
        fprintf(stderr, "rtedged: params request %lld applied (%d values)\n",
                (long long)m.request_id, m.nparams);
    rtedge_params_t_decode_cleanup(&m);
}

static void poll_params(rted_daemon *d)
{
    if (!d->params_sub)
        return;
    lcm_t *lcm = rte_publisher_lcm(d->pub);
    struct pollfd pfd = {lcm_get_fileno(lcm), POLLIN, 0};
    while (poll(&pfd, 1, 0) > 0 && (pfd.revents & POLLIN))
        if (lcm_handle(lcm) != 0)
            break;
}

/* ---- latency window ---- */

static void sift(int32_t *a, uint32_t root, uint32_t n)
{
    for (;;) {
        uint32_t child = 2 * root + 1;
        if (child >= n)
            return;
        if (child + 1 < n && a[child + 1] > a[child])
            child++;
        if (a[root] >= a[child])
            return;
        int32_t t = a[root];
        a[root] = a[child];
        a[child] = t;
        root = child;
    }
}

/* In-place heap sort: bounded time, no allocation. */
static void sort_i32(int32_t *a, uint32_t n)
{
    for (uint32_t i = n / 2; i-- > 0;)
        sift(a, i, n);
    for (uint32_t i = n; i-- > 1;) {
        int32_t t = a[0];
        a[0] = a[i];
        a[i] = t;
        sift(a, 0, i);
    }
}

static void window_latency(rted_daemon *d, int32_t *p50, int32_t *p99, int32_t *max)
{
    uint32_t n = d->ring_n < RTED_RING ? d->ring_n : RTED_RING;
    *p50 = *p99 = 0;
    *max = d->window_max;
    if (!n)
        return;
    memcpy(d->sorted, d->ring, n * sizeof d->ring[0]);
    sort_i32(d->sorted, n);
    *p50 = d->sorted[(uint64_t)(n - 1) * 50 / 100];
    *p99 = d->sorted[(uint64_t)(n - 1) * 99 / 100];
}

void rted_daemon_publish_status(rted_daemon *d)
{
    int64_t t = now_ns();
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    rtedge_status_t *s = &d->status_msg;
    s->utime = t / 1000;
    s->source_state = (int8_t)ss.state;
    d->reported_state = ss.state;
    s->frames_received = (int64_t)d->n.received;
    s->frames_processed = (int64_t)d->n.processed;
    d->n.bad_frames = ss.bad_frames;
    s->frames_dropped = (int64_t)(d->n.dropped + ss.driver_drops + ss.skipped);
    s->deadline_misses = (int64_t)d->n.deadline_misses;
    s->stages_skipped = (int64_t)d->n.stages_skipped;
    s->frames_bad = (int64_t)ss.bad_frames;
    s->source_reconnects = (int64_t)ss.reconnects;
    s->config_reloads = (int64_t)d->n.reloads;
    s->config_refused = (int64_t)d->n.refused;
    s->window_us = (t - d->window_start_ns) / 1000;
    window_latency(d, &s->latency_p50_us, &s->latency_p99_us, &s->latency_max_us);
    s->fps = s->window_us > 0 ? (float)((double)d->window_processed * 1e6 / (double)s->window_us)
                              : 0.0f;
    s->arena_bytes = (int64_t)d->arena.size;
    s->arena_peak_bytes = (int64_t)d->arena.high_water;
    s->config_hash = (int64_t)d->config_hash;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (rte_publish_status(d->pub, d->cfg.status_channel, s, msg, sizeof msg) == RTE_OK)
        d->n.status_sent++;
    else
        d->n.publish_errors++;
    d->ring_n = 0;
    d->window_max = 0;
    d->window_processed = 0;
    d->window_start_ns = t;
}

void rted_daemon_latency(const rted_daemon *d, int32_t *p50, int32_t *p99, int32_t *max)
{
    *p50 = d->status_msg.latency_p50_us;
    *p99 = d->status_msg.latency_p99_us;
    *max = d->status_msg.latency_max_us;
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
    fill_header(d, &m->header, f, now_ns());
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
    fill_header(d, &m->header, f, now_ns());
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

static void record_latency(rted_daemon *d, int64_t lat_ns)
{
    int64_t us = lat_ns / 1000;
    int32_t v = us > INT32_MAX ? INT32_MAX : (int32_t)us;
    d->ring[d->ring_n % RTED_RING] = v;
    d->ring_n++;
    if (v > d->window_max)
        d->window_max = v;
}

static rted_step analyse(rted_daemon *d, const rte_source_frame *f)
{
    const int64_t t0 = f->capture_ns;
    if (d->lane) {
        rte_lane_result lr;
        if (rte_lane_process(d->lane, &f->frame, f->recorded_ns, &lr) == RTE_OK)
            publish_lane(d, f, &lr);
        else
            d->n.publish_errors++;
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
        if (d->deadline_ns - (now_ns() - t0) < d->grasp_min_ns) {
            d->n.stages_skipped++;
        } else {
            rte_grasp_result gr;
            if (rte_grasp_process(d->grasp, &gray, &gr) == RTE_OK)
                publish_grasp(d, f, &gr);
            else
                d->n.publish_errors++;
        }
    }
    if (d->cfg.publish_images) {
        if (d->deadline_ns - (now_ns() - t0) < d->grasp_min_ns)
            d->n.stages_skipped++;
        else
            publish_image(d, f, &gray);
    }
    int64_t lat = now_ns() - t0;
    record_latency(d, lat);
    if (lat > d->deadline_ns)
        d->n.deadline_misses++;
    d->n.processed++;
    d->window_processed++;
    return RTED_STEP_FRAME;
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
    poll_params(d);
    if (now_ns() - d->window_start_ns >= (int64_t)d->cfg.status_period_ms * 1000000)
        rted_daemon_publish_status(d);

    rte_source_frame f;
    char why[RTE_SOURCE_MESSAGE_SIZE] = "";
    rte_status st = rte_source_next(&d->source, &f, 100, why, sizeof why);
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    d->n.bad_frames = ss.bad_frames;
    if (ss.state != d->reported_state) {
        /* A camera lost or back: said at once, not at the next period. */
        if (ss.state == RTE_SOURCE_STREAMING)
            fprintf(stderr, "rtedged: source streaming again (reconnection %llu)\n",
                    (unsigned long long)ss.reconnects);
        rted_daemon_publish_status(d);
    }
    if (st == RTE_ERR_END) {
        if (d->cfg.loop && rte_recorded_source_rewind(&d->source) == RTE_OK) {
            d->n.rewinds++;
            return RTED_STEP_IDLE;
        }
        d->state = RTE_SOURCE_ENDED;
        return RTED_STEP_END;
    }
    if (st == RTE_ERR_TIMEOUT)
        return RTED_STEP_IDLE;
    if (st != RTE_OK) {
        if (ss.state == RTE_SOURCE_FAILED) {
            fprintf(stderr, "rtedged: source failed: %s\n", why);
            return RTED_STEP_FAILED;
        }
        fprintf(stderr, "rtedged: %s: %s\n", st == RTE_ERR_DEVICE ? "source" : "frame skipped",
                why[0] ? why : rte_status_message(st));
        return RTED_STEP_IDLE;
    }
    d->n.received++;
    if (d->rec)
        record_frame(d, &f);
    bool waited = false;
    for (;;) {
        int64_t wait = 0;
        rte_pace_action a = rte_pacer_decide(&d->pacer, f.recorded_ns, now_ns(), &wait);
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
            now_ns() - d->window_start_ns >= (int64_t)d->cfg.status_period_ms * 1000000)
            rted_daemon_publish_status(d);
    }
    /* Recordings: the frame is "captured" when it is due, not when it was
     * read ahead of its time. */
    if (d->recorded && waited)
        f.capture_ns = now_ns();
    return analyse(d, &f);
}

int rted_daemon_run(rted_daemon *d, volatile sig_atomic_t *stop, volatile sig_atomic_t *reload)
{
    int code = 0;
    d->stop = stop;
    while (!*stop) {
        if (*reload) {
            *reload = 0;
            char msg[RTED_MSG];
            if (rted_daemon_reload(d, msg, sizeof msg))
                fprintf(stderr, "rtedged: configuration re-read and applied (hash %016llx)\n",
                        (unsigned long long)d->config_hash);
            else
                fprintf(stderr, "rtedged: configuration change refused: %s\n", msg);
        }
        rted_step s = rted_daemon_step(d);
        if (s == RTED_STEP_END)
            break;
        if (s == RTED_STEP_FAILED) {
            code = 1;
            break;
        }
    }
    rted_daemon_publish_status(d);
    return code;
}
