/* Which source a path names (source.kind = auto: URL schemes, /dev/video,
 * file suffixes, directories and globs), and opening it with the
 * [source] keys; the source's maxima then size everything else. */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <linux/videodev2.h>

#include "daemon_internal.h"
#include "rtedge/libcamera_source.h"
#include "rtedge/v4l2_source.h"
#include "sources/recorded_source.h"
#include "sources/waiting.h"

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
    static const char *const names[] = {"auto",    "y4m", "images", "raw",
                                        "lcm-log", "lcm", "v4l2",   "libcamera"};
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

static rte_status open_v4l2(rte_source *source, const rted_config *c, uint32_t fourcc, char *why,
                            size_t why_size)
{
    rte_v4l2_config vc;
    memset(&vc, 0, sizeof vc);
    vc.device = c->source_path;
    vc.fourcc = fourcc;
    vc.width = c->width ? c->width : 1280;
    vc.height = c->height ? c->height : 720;
    vc.fps = (int32_t)lround(c->fps);
    vc.wait = c->wait_camera;
    vc.n_controls = rted_parse_controls(c->source_controls, vc.controls, RTE_V4L2_MAX_CONTROLS);
    rte_v4l2_info info;
    return rte_v4l2_source_open(source, &vc, &info, why, why_size);
}

static rte_status open_libcamera(rte_source *source, const rted_config *c, rte_pixel_format fmt,
                                 char *why, size_t why_size)
{
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
    return rte_libcamera_source_open(source, &lc, &info, why, why_size);
}

/* The waiting source's opener: the configuration is the daemon's own. */
static rte_status reopen_libcamera(void *ctx, rte_source *source, char *why, size_t why_size)
{
    const rted_config *c = ctx;
    return open_libcamera(source, c, rte_pixel_format_parse(c->source_format), why, why_size);
}

/* A libcamera camera missing at start (source.wait), which has no
 * reconnection of its own: waited for through a waiting source, announced
 * at source.width x height (1280x720 when 0) in source.format. why holds
 * libcamera's reason on entry. */
static rte_status wait_for_libcamera(rted_daemon *d, rte_pixel_format fmt, char *why,
                                     size_t why_size)
{
    const rted_config *c = &d->cfg;
    if (!fmt) {
        size_t n = strlen(why);
        snprintf(why + n, why_size - n,
                 "%sto wait for the camera, set source.format (its frames are sized before it "
                 "appears)",
                 n ? "; " : "");
        return RTE_ERR_DEVICE;
    }
    rte_waiting_config wc = {.open = reopen_libcamera,
                             .ctx = &d->cfg,
                             .name = c->source_path,
                             .max_width = c->width ? c->width : 1280,
                             .max_height = c->height ? c->height : 720,
                             .format = fmt};
    rted_log("waiting for libcamera camera %s (%s), sized for %s %dx%d", c->source_path, why,
             rte_pixel_format_name(fmt), wc.max_width, wc.max_height);
    return rte_waiting_source_open(&d->source, &wc, why, why_size);
}

bool rted_open_source(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    rted_source_kind kind =
        c->source_kind ? (rted_source_kind)c->source_kind : guess_kind(c->source_path);
    uint32_t fourcc = 0;
    if (kind == RTED_SOURCE_V4L2 && !v4l2_format(c->source_format, &fourcc)) {
        rted_msgf(msg, msg_size,
                  "source.format: a V4L2 camera is read as yuyv, uyvy, grey, nv12 or "
                  "mjpeg, not: %s",
                  c->source_format);
        return false;
    }
    rte_pixel_format fmt = c->source_format[0] && kind != RTED_SOURCE_V4L2
                               ? rte_pixel_format_parse(c->source_format)
                               : 0;
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
        rte_images_source_config ic = {
            c->source_path, fmt ? fmt : RTE_PIXEL_BGR24, c->width, c->height, fps_num, fps_den};
        st = rte_images_source_open(&d->source, &ic, why, sizeof why);
        break;
    }
    case RTED_SOURCE_RAW: {
        rte_raw_source_config rc = {
            c->source_path, fmt ? fmt : RTE_PIXEL_GREY, c->width, c->height, fps_num, fps_den};
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
    case RTED_SOURCE_V4L2: st = open_v4l2(&d->source, c, fourcc, why, sizeof why); break;
    case RTED_SOURCE_LIBCAMERA:
        st = open_libcamera(&d->source, c, fmt, why, sizeof why);
        if (st == RTE_ERR_DEVICE && c->wait_camera)
            st = wait_for_libcamera(d, fmt, why, sizeof why);
        break;
    case RTED_SOURCE_AUTO: break;
    }
    if (st != RTE_OK) {
        snprintf(msg, msg_size, "cannot open %s source %s: %s", kind_name(kind), c->source_path,
                 why[0] ? why : rte_status_message(st));
        return false;
    }
    /* Cameras say what they settled on (size, format, rate, adjustments). */
    if (why[0] && (kind == RTED_SOURCE_V4L2 || kind == RTED_SOURCE_LIBCAMERA))
        rted_log("%s source: %s", kind_name(kind), why);
    d->recorded =
        kind != RTED_SOURCE_LCM && kind != RTED_SOURCE_V4L2 && kind != RTED_SOURCE_LIBCAMERA;
    snprintf(d->source_id, sizeof d->source_id, "%s:%s", kind_name(kind), c->source_path);
    d->width = d->source.max_width;
    d->height = d->source.max_height;
    return true;
}
