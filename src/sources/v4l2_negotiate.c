/* Bringing a V4L2 device up: finding the node, agreeing on the format,
 * size and frame rate with the driver, then (with the controls and the
 * buffers of the other files) everything from open(2) to STREAMON. */
#include "sources/v4l2_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>

#include "source_msg.h"

/* ---- formats ---- */

/* The formats rtedge reads, and what it delivers for each. */
rte_pixel_format rte_v4l2_delivered_format(uint32_t fourcc, rte_pixel_format decode_to)
{
    switch (fourcc) {
    case V4L2_PIX_FMT_YUYV: return RTE_PIXEL_YUYV;
    case V4L2_PIX_FMT_UYVY: return RTE_PIXEL_UYVY;
    case V4L2_PIX_FMT_GREY: return RTE_PIXEL_GREY;
    case V4L2_PIX_FMT_NV12: return RTE_PIXEL_NV12;
    case V4L2_PIX_FMT_MJPEG: return decode_to;
    default: return (rte_pixel_format)0;
    }
}

/* Bytes per pixel of the first plane (0 for compressed formats). */
static int32_t bytes_per_pixel(uint32_t fourcc)
{
    switch (fourcc) {
    case V4L2_PIX_FMT_YUYV:
    case V4L2_PIX_FMT_UYVY: return 2;
    case V4L2_PIX_FMT_GREY:
    case V4L2_PIX_FMT_NV12: return 1;
    default: return 0;
    }
}

/* Bytes a raw frame of the negotiated layout needs in its buffer. */
size_t rte_v4l2_raw_frame_bytes(const rte_v4l2_info *info)
{
    size_t rows = (size_t)info->height;
    if (info->fourcc == V4L2_PIX_FMT_NV12)
        rows += (size_t)(info->height + 1) / 2;
    return rows * (size_t)info->bytesperline;
}

/* ---- the node ---- */

static uint32_t device_caps(const struct v4l2_capability *cap)
{
    return (cap->capabilities & V4L2_CAP_DEVICE_CAPS) ? cap->device_caps : cap->capabilities;
}

static bool is_capture_node(const struct v4l2_capability *cap)
{
    uint32_t caps = device_caps(cap);
    return (caps & V4L2_CAP_VIDEO_CAPTURE) && (caps & V4L2_CAP_STREAMING);
}

rte_status rte_v4l2_query_node(v4l2_source *s, struct v4l2_capability *cap)
{
    memset(cap, 0, sizeof(*cap));
    if (rte_v4l2_xioctl(s, VIDIOC_QUERYCAP, cap) < 0)
        return RTE_ERR_DEVICE;
    return is_capture_node(cap) ? RTE_OK : RTE_ERR_UNSUPPORTED;
}

/* Opens cfg.device: a path, or the first capture node whose card or
 * bus_info matches. */
rte_status rte_v4l2_open_node(v4l2_source *s, char *msg, size_t msg_size)
{
    const int flags = O_RDWR | O_NONBLOCK | O_CLOEXEC;
    struct v4l2_capability cap;
    const char *want = s->cfg.device;

    if (strchr(want, '/')) {
        s->fd = s->ops->open(s->ops->ctx, want, flags);
        if (s->fd < 0) {
            int err = errno;
            rte_source_msgf(msg, msg_size, "%s: %s", want, strerror(err));
            return err == ENOENT || err == ENODEV || err == ENXIO || err == EIO ? RTE_ERR_DEVICE
                                                                                : RTE_ERR_IO;
        }
        rte_status st = rte_v4l2_query_node(s, &cap);
        if (st != RTE_OK) {
            rte_source_msgf(msg, msg_size, "%s: %s", want,
                            st == RTE_ERR_DEVICE ? strerror(errno)
                                                 : "not a video capture node with streaming I/O");
            rte_v4l2_close_fd(s);
            return st;
        }
        rte_v4l2_copy_string(s->info.path, sizeof(s->info.path), want, strlen(want) + 1);
    } else {
        int i;
        for (i = 0; i < MAX_DEVICE_NODES; i++) {
            char path[RTE_V4L2_NAME_SIZE];
            snprintf(path, sizeof(path), "/dev/video%d", i);
            s->fd = s->ops->open(s->ops->ctx, path, flags);
            if (s->fd < 0)
                continue;
            if (rte_v4l2_query_node(s, &cap) == RTE_OK &&
                (rte_v4l2_names_equal(want, (const char *)cap.card) ||
                 strncmp(want, (const char *)cap.bus_info, sizeof(cap.bus_info)) == 0)) {
                rte_v4l2_copy_string(s->info.path, sizeof(s->info.path), path, sizeof(path));
                break;
            }
            rte_v4l2_close_fd(s);
        }
        if (i == MAX_DEVICE_NODES) {
            rte_source_msgf(msg, msg_size, "no capture device with card or bus \"%s\"", want);
            return RTE_ERR_DEVICE;
        }
    }
    rte_v4l2_copy_string(s->info.driver, sizeof(s->info.driver), cap.driver, sizeof(cap.driver));
    rte_v4l2_copy_string(s->info.card, sizeof(s->info.card), cap.card, sizeof(cap.card));
    rte_v4l2_copy_string(s->info.bus_info, sizeof(s->info.bus_info), cap.bus_info,
                         sizeof(cap.bus_info));
    return RTE_OK;
}

/* ---- format and frame rate ---- */

/* S_FMT with the configured format and size; accepts what the driver
 * adjusts as long as rtedge reads the result. On a reopening the result
 * must fit what open() sized. */
static rte_status negotiate_format(v4l2_source *s, bool reopening, char *msg, size_t msg_size)
{
    char want_name[5], got_name[5];
    struct v4l2_format f;
    memset(&f, 0, sizeof(f));
    f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    f.fmt.pix.width = (uint32_t)s->cfg.width;
    f.fmt.pix.height = (uint32_t)s->cfg.height;
    f.fmt.pix.pixelformat = s->cfg.fourcc;
    f.fmt.pix.field = V4L2_FIELD_NONE;
    if (rte_v4l2_xioctl(s, VIDIOC_S_FMT, &f) < 0) {
        int err = errno;
        rte_source_msgf(msg, msg_size, "%s: VIDIOC_S_FMT: %s", s->info.path, strerror(err));
        return err == EBUSY ? RTE_ERR_IO : RTE_ERR_DEVICE;
    }
    const struct v4l2_pix_format *p = &f.fmt.pix;
    rte_v4l2_fourcc_name(s->cfg.fourcc, want_name);
    rte_v4l2_fourcc_name(p->pixelformat, got_name);

    if (rte_v4l2_delivered_format(p->pixelformat, s->cfg.decode_to) == 0) {
        rte_source_msgf(msg, msg_size,
                        "%s: asked for %s, the driver offers %s, which rtedge does not read",
                        s->info.path, want_name, got_name);
        return RTE_ERR_UNSUPPORTED;
    }
    if (p->field != V4L2_FIELD_NONE && p->field != V4L2_FIELD_ANY) {
        rte_source_msgf(msg, msg_size, "%s: the driver sends interlaced fields (%u)", s->info.path,
                        p->field);
        return RTE_ERR_UNSUPPORTED;
    }
    if (p->width < 1 || p->height < 1 || p->width > RTE_MAX_SIDE || p->height > RTE_MAX_SIDE) {
        rte_source_msgf(msg, msg_size, "%s: the driver settled on %ux%u", s->info.path, p->width,
                        p->height);
        return RTE_ERR_TOO_LARGE;
    }
    uint32_t min_line = (uint32_t)bytes_per_pixel(p->pixelformat) * p->width;
    uint32_t line = p->bytesperline ? p->bytesperline : min_line;
    if (line < min_line || line > INT32_MAX / 4) {
        rte_source_msgf(msg, msg_size, "%s: bytesperline %u does not hold a %u-pixel row",
                        s->info.path, p->bytesperline, p->width);
        return RTE_ERR_FORMAT;
    }
    rte_v4l2_info got = s->info;
    got.fourcc = p->pixelformat;
    got.width = (int32_t)p->width;
    got.height = (int32_t)p->height;
    got.bytesperline = (int32_t)line;
    got.sizeimage = p->sizeimage;
    if (got.fourcc != V4L2_PIX_FMT_MJPEG && got.sizeimage < rte_v4l2_raw_frame_bytes(&got)) {
        rte_source_msgf(msg, msg_size, "%s: sizeimage %u is smaller than a %dx%d %s frame",
                        s->info.path, got.sizeimage, got.width, got.height, got_name);
        return RTE_ERR_FORMAT;
    }
    if (reopening &&
        (got.fourcc != s->open_fourcc || got.width > s->max_width || got.height > s->max_height)) {
        rte_source_msgf(msg, msg_size, "%s %s with %s %dx%d, not the %dx%d %s", s->info.path,
                        s->streamed ? "came back" : "appeared", got_name, got.width, got.height,
                        s->max_width, s->max_height, s->streamed ? "it had" : "asked for at start");
        return RTE_ERR_TOO_LARGE;
    }
    if (got.fourcc != s->cfg.fourcc || got.width != s->cfg.width || got.height != s->cfg.height) {
        got.adjusted = true;
        rte_source_msg_append(msg, msg_size, "; driver adjusted %s %dx%d to %s %dx%d", want_name,
                              s->cfg.width, s->cfg.height, got_name, got.width, got.height);
    }
    s->info = got;
    return RTE_OK;
}

/* S_PARM with 1/fps when asked for and the driver allows it; reports the
 * interval in force either way. Frame rates are advisory: never fatal. */
static void set_frame_rate(v4l2_source *s, char *msg, size_t msg_size)
{
    struct v4l2_streamparm parm;
    memset(&parm, 0, sizeof(parm));
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    s->info.interval_num = s->info.interval_den = 0;
    if (rte_v4l2_xioctl(s, VIDIOC_G_PARM, &parm) < 0) {
        if (s->cfg.fps > 0)
            rte_source_msg_append(msg, msg_size, "; no frame rate control (VIDIOC_G_PARM: %s)",
                                  strerror(errno));
        return;
    }
    if (s->cfg.fps > 0) {
        if (!(parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME)) {
            rte_source_msg_append(msg, msg_size, "; the driver does not set the frame rate");
            s->info.adjusted = true;
        } else {
            parm.parm.capture.timeperframe.numerator = 1;
            parm.parm.capture.timeperframe.denominator = (uint32_t)s->cfg.fps;
            if (rte_v4l2_xioctl(s, VIDIOC_S_PARM, &parm) < 0) {
                rte_source_msg_append(msg, msg_size, "; VIDIOC_S_PARM: %s", strerror(errno));
                s->info.adjusted = true;
            }
        }
    }
    const struct v4l2_fract *t = &parm.parm.capture.timeperframe;
    s->info.interval_num = t->numerator;
    s->info.interval_den = t->denominator;
    if (s->cfg.fps > 0 && t->numerator &&
        (uint64_t)t->denominator != (uint64_t)s->cfg.fps * t->numerator) {
        s->info.adjusted = true;
        rte_source_msg_append(msg, msg_size, "; driver adjusted %d fps to %u/%u s per frame",
                              s->cfg.fps, t->numerator, t->denominator);
    }
}

/* ---- open(2) to STREAMON ---- */

/* Everything from open(2) to STREAMON; on failure the device is closed.
 * The message gets the adjustments the driver made. */
rte_status rte_v4l2_setup_device(v4l2_source *s, bool reopening, char *msg, size_t msg_size)
{
    rte_source_msgf(msg, msg_size, "%s", "");
    rte_status st = rte_v4l2_open_node(s, msg, msg_size);
    if (st != RTE_OK)
        return st;
    st = negotiate_format(s, reopening, msg, msg_size);
    if (st == RTE_OK) {
        set_frame_rate(s, msg, msg_size);
        st = rte_v4l2_apply_controls(s, msg, msg_size);
    }
    if (st == RTE_OK)
        st = rte_v4l2_start_streaming(s, msg, msg_size);
    if (st != RTE_OK) {
        rte_v4l2_stop_device(s);
        return st;
    }
    s->have_seq = false;
    s->have_delivered = false;
    s->held = -1;
    return RTE_OK;
}
