/* V4L2 capture source: plain ioctls, mmap streaming, newest-frame delivery
 * and reconnection. Reads top to bottom: syscall table, helpers, opening
 * (device, format, frame rate, controls, buffers), next(), listing.
 *
 * Memory: open() allocates the source and, for MJPEG, the decode buffer;
 * next() and the reconnection allocate nothing (the mmap buffers belong to
 * the kernel and must fit the open-time sizes when the device returns). */
#include "sources/v4l2_source.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include <linux/videodev2.h>
#include <turbojpeg.h>

#include "source_msg.h"

/* ---- the real syscalls ---- */

static int sys_open(void *ctx, const char *path, int flags)
{
    (void)ctx;
    return open(path, flags);
}

static int sys_close(void *ctx, int fd)
{
    (void)ctx;
    return close(fd);
}

static int sys_ioctl(void *ctx, int fd, unsigned long request, void *arg)
{
    (void)ctx;
    return ioctl(fd, request, arg);
}

static int sys_poll(void *ctx, struct pollfd *fds, nfds_t nfds, int timeout_ms)
{
    (void)ctx;
    return poll(fds, nfds, timeout_ms);
}

static void *sys_mmap(void *ctx, size_t length, int prot, int flags, int fd, off_t offset)
{
    (void)ctx;
    return mmap(NULL, length, prot, flags, fd, offset);
}

static int sys_munmap(void *ctx, void *addr, size_t length)
{
    (void)ctx;
    return munmap(addr, length);
}

static int64_t sys_now_ns(void *ctx)
{
    (void)ctx;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

const rte_v4l2_ops rte_v4l2_system_ops = {
    sys_open, sys_close, sys_ioctl, sys_poll, sys_mmap, sys_munmap, sys_now_ns, NULL,
};

/* ---- the source ---- */

#define MAX_DEVICE_NODES 64
#define DEFAULT_BUFFERS 4
#define DEFAULT_RECONNECT_MIN_MS 100
#define DEFAULT_RECONNECT_MAX_MS 2000

typedef struct v4l2_mapping {
    void *start;
    size_t length;
} v4l2_mapping;

typedef struct v4l2_source {
    rte_v4l2_config cfg;
    char device[64];         /* cfg.device points here */
    const rte_v4l2_ops *ops;
    int fd;                  /* -1 while the device is lost */
    rte_v4l2_info info;

    /* Fixed at open: what a reopened device must fit into. */
    uint32_t open_fourcc;
    rte_pixel_format out_format;
    int32_t max_width, max_height;

    v4l2_mapping buf[RTE_V4L2_MAX_BUFFERS];
    int32_t n_buf;
    int32_t held;            /* buffer handed out by the last next(), -1: none */

    /* Sequence bookkeeping, reset when the device is reopened. */
    int have_seq;
    uint32_t last_seq;       /* last sequence dequeued */
    int have_delivered;
    uint32_t last_delivered; /* last sequence handed out */

    int64_t retry_at_ns;
    int32_t backoff_ms;
    rte_source_stats stats;

    tjhandle tj;             /* MJPEG only */
    uint8_t *decoded;
    size_t decoded_size;
} v4l2_source;

/* ---- helpers ---- */

static void copy_string(char *dst, size_t size, const void *src, size_t src_size)
{
    size_t n = strnlen((const char *)src, src_size);
    if (n >= size)
        n = size - 1;
    memcpy(dst, src, n);
    dst[n] = 0;
}

const char *rte_v4l2_fourcc_name(uint32_t fourcc, char buf[5])
{
    for (int i = 0; i < 4; i++) {
        char c = (char)((fourcc >> (8 * i)) & 0xff);
        buf[i] = isprint((unsigned char)c) ? c : '.';
    }
    buf[4] = 0;
    return buf;
}

/* Control and card names compare as v4l2-ctl spells them: lower case, each
 * run of anything but letters and digits is one separator, none at the
 * ends. "White Balance, Automatic" == "white_balance_automatic". */
static int names_equal(const char *a, const char *b)
{
    while (*a && !isalnum((unsigned char)*a))
        a++;
    while (*b && !isalnum((unsigned char)*b))
        b++;
    for (;;) {
        if (!*a || !*b)
            return !*a && !*b;
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return 0;
        a++;
        b++;
        int sep_a = 0, sep_b = 0;
        while (*a && !isalnum((unsigned char)*a)) {
            a++;
            sep_a = 1;
        }
        while (*b && !isalnum((unsigned char)*b)) {
            b++;
            sep_b = 1;
        }
        /* A separator inside one name must be matched by one in the other. */
        if (sep_a != sep_b && *a && *b)
            return 0;
    }
}

static int xioctl(v4l2_source *s, unsigned long request, void *arg)
{
    int r;
    do
        r = s->ops->ioctl(s->ops->ctx, s->fd, request, arg);
    while (r < 0 && errno == EINTR);
    return r;
}

static uint32_t device_caps(const struct v4l2_capability *cap)
{
    return (cap->capabilities & V4L2_CAP_DEVICE_CAPS) ? cap->device_caps : cap->capabilities;
}

static int is_capture_node(const struct v4l2_capability *cap)
{
    uint32_t caps = device_caps(cap);
    return (caps & V4L2_CAP_VIDEO_CAPTURE) && (caps & V4L2_CAP_STREAMING);
}

/* The formats rtedge reads, and what it delivers for each. */
static rte_pixel_format delivered_format(uint32_t fourcc, rte_pixel_format decode_to)
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
static size_t raw_frame_bytes(const rte_v4l2_info *info)
{
    size_t rows = (size_t)info->height;
    if (info->fourcc == V4L2_PIX_FMT_NV12)
        rows += (size_t)(info->height + 1) / 2;
    return rows * (size_t)info->bytesperline;
}

/* ---- opening ---- */

static rte_status query_node(v4l2_source *s, struct v4l2_capability *cap)
{
    memset(cap, 0, sizeof(*cap));
    if (xioctl(s, VIDIOC_QUERYCAP, cap) < 0)
        return RTE_ERR_DEVICE;
    return is_capture_node(cap) ? RTE_OK : RTE_ERR_UNSUPPORTED;
}

static void close_fd(v4l2_source *s)
{
    if (s->fd >= 0)
        s->ops->close(s->ops->ctx, s->fd);
    s->fd = -1;
}

/* Opens cfg.device: a path, or the first capture node whose card or
 * bus_info matches. */
static rte_status open_node(v4l2_source *s, char *msg, size_t msg_size)
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
        rte_status st = query_node(s, &cap);
        if (st != RTE_OK) {
            rte_source_msgf(msg, msg_size, "%s: %s", want,
                       st == RTE_ERR_DEVICE ? strerror(errno)
                                            : "not a video capture node with streaming I/O");
            close_fd(s);
            return st;
        }
        copy_string(s->info.path, sizeof(s->info.path), want, strlen(want) + 1);
    } else {
        int i;
        for (i = 0; i < MAX_DEVICE_NODES; i++) {
            char path[RTE_V4L2_NAME_SIZE];
            snprintf(path, sizeof(path), "/dev/video%d", i);
            s->fd = s->ops->open(s->ops->ctx, path, flags);
            if (s->fd < 0)
                continue;
            if (query_node(s, &cap) == RTE_OK &&
                (names_equal(want, (const char *)cap.card) ||
                 strncmp(want, (const char *)cap.bus_info, sizeof(cap.bus_info)) == 0)) {
                copy_string(s->info.path, sizeof(s->info.path), path, sizeof(path));
                break;
            }
            close_fd(s);
        }
        if (i == MAX_DEVICE_NODES) {
            rte_source_msgf(msg, msg_size, "no capture device with card or bus \"%s\"", want);
            return RTE_ERR_DEVICE;
        }
    }
    copy_string(s->info.driver, sizeof(s->info.driver), cap.driver, sizeof(cap.driver));
    copy_string(s->info.card, sizeof(s->info.card), cap.card, sizeof(cap.card));
    copy_string(s->info.bus_info, sizeof(s->info.bus_info), cap.bus_info, sizeof(cap.bus_info));
    return RTE_OK;
}

/* S_FMT with the configured format and size; accepts what the driver
 * adjusts as long as rtedge reads the result. On a reopening the result
 * must fit what open() sized. */
static rte_status negotiate_format(v4l2_source *s, int reopening, char *msg, size_t msg_size)
{
    char want_name[5], got_name[5];
    struct v4l2_format f;
    memset(&f, 0, sizeof(f));
    f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    f.fmt.pix.width = (uint32_t)s->cfg.width;
    f.fmt.pix.height = (uint32_t)s->cfg.height;
    f.fmt.pix.pixelformat = s->cfg.fourcc;
    f.fmt.pix.field = V4L2_FIELD_NONE;
    if (xioctl(s, VIDIOC_S_FMT, &f) < 0) {
        int err = errno;
        rte_source_msgf(msg, msg_size, "%s: VIDIOC_S_FMT: %s", s->info.path, strerror(err));
        return err == EBUSY ? RTE_ERR_IO : RTE_ERR_DEVICE;
    }
    const struct v4l2_pix_format *p = &f.fmt.pix;
    rte_v4l2_fourcc_name(s->cfg.fourcc, want_name);
    rte_v4l2_fourcc_name(p->pixelformat, got_name);

    if (delivered_format(p->pixelformat, s->cfg.decode_to) == 0) {
        rte_source_msgf(msg, msg_size, "%s: asked for %s, the driver offers %s, which rtedge does not read",
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
    if (got.fourcc != V4L2_PIX_FMT_MJPEG && got.sizeimage < raw_frame_bytes(&got)) {
        rte_source_msgf(msg, msg_size, "%s: sizeimage %u is smaller than a %dx%d %s frame",
                   s->info.path, got.sizeimage, got.width, got.height, got_name);
        return RTE_ERR_FORMAT;
    }
    if (reopening && (got.fourcc != s->open_fourcc || got.width > s->max_width ||
                      got.height > s->max_height)) {
        rte_source_msgf(msg, msg_size, "%s came back with %s %dx%d, not the %dx%d it had",
                   s->info.path, got_name, got.width, got.height, s->max_width, s->max_height);
        return RTE_ERR_TOO_LARGE;
    }
    if (got.fourcc != s->cfg.fourcc || got.width != s->cfg.width || got.height != s->cfg.height) {
        got.adjusted = 1;
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
    if (xioctl(s, VIDIOC_G_PARM, &parm) < 0) {
        if (s->cfg.fps > 0)
            rte_source_msg_append(msg, msg_size, "; no frame rate control (VIDIOC_G_PARM: %s)",
                       strerror(errno));
        return;
    }
    if (s->cfg.fps > 0) {
        if (!(parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME)) {
            rte_source_msg_append(msg, msg_size, "; the driver does not set the frame rate");
            s->info.adjusted = 1;
        } else {
            parm.parm.capture.timeperframe.numerator = 1;
            parm.parm.capture.timeperframe.denominator = (uint32_t)s->cfg.fps;
            if (xioctl(s, VIDIOC_S_PARM, &parm) < 0) {
                rte_source_msg_append(msg, msg_size, "; VIDIOC_S_PARM: %s", strerror(errno));
                s->info.adjusted = 1;
            }
        }
    }
    const struct v4l2_fract *t = &parm.parm.capture.timeperframe;
    s->info.interval_num = t->numerator;
    s->info.interval_den = t->denominator;
    if (s->cfg.fps > 0 && t->numerator && (uint64_t)t->denominator != (uint64_t)s->cfg.fps * t->numerator) {
        s->info.adjusted = 1;
        rte_source_msg_append(msg, msg_size, "; driver adjusted %d fps to %u/%u s per frame", s->cfg.fps,
                   t->numerator, t->denominator);
    }
}

/* Finds a control by name among all the device's controls. */
static int find_control(v4l2_source *s, const char *name, struct v4l2_queryctrl *qc)
{
    memset(qc, 0, sizeof(*qc));
    qc->id = V4L2_CTRL_FLAG_NEXT_CTRL;
    while (xioctl(s, VIDIOC_QUERYCTRL, qc) == 0) {
        if (qc->type != V4L2_CTRL_TYPE_CTRL_CLASS && !(qc->flags & V4L2_CTRL_FLAG_DISABLED) &&
            names_equal(name, (const char *)qc->name))
            return 1;
        qc->id |= V4L2_CTRL_FLAG_NEXT_CTRL;
    }
    return 0;
}

static rte_status set_control(v4l2_source *s, const char *name, int32_t value, char *msg,
                              size_t msg_size)
{
    struct v4l2_queryctrl qc;
    if (s->fd < 0) {
        rte_source_msgf(msg, msg_size, "control %s: the device is not open", name);
        return RTE_ERR_DEVICE;
    }
    if (!find_control(s, name, &qc)) {
        rte_source_msgf(msg, msg_size, "%s has no control \"%s\"", s->info.path, name);
        return RTE_ERR_ARGUMENT;
    }
    switch (qc.type) {
    case V4L2_CTRL_TYPE_INTEGER:
    case V4L2_CTRL_TYPE_BOOLEAN:
    case V4L2_CTRL_TYPE_MENU:
    case V4L2_CTRL_TYPE_INTEGER_MENU:
        if (value < qc.minimum || value > qc.maximum) {
            rte_source_msgf(msg, msg_size, "control \"%s\": %d is outside %d..%d", qc.name, value,
                       qc.minimum, qc.maximum);
            return RTE_ERR_ARGUMENT;
        }
        break;
    case V4L2_CTRL_TYPE_BUTTON:
        value = 0;
        break;
    default:
        rte_source_msgf(msg, msg_size, "control \"%s\" is not an integer, boolean, menu or button",
                   qc.name);
        return RTE_ERR_UNSUPPORTED;
    }
    if (qc.flags & V4L2_CTRL_FLAG_READ_ONLY) {
        rte_source_msgf(msg, msg_size, "control \"%s\" is read-only", qc.name);
        return RTE_ERR_ARGUMENT;
    }
    struct v4l2_control c = { qc.id, value };
    if (xioctl(s, VIDIOC_S_CTRL, &c) < 0) {
        int err = errno;
        rte_source_msgf(msg, msg_size, "control \"%s\" = %d: %s", qc.name, value, strerror(err));
        return err == ENODEV || err == EIO ? RTE_ERR_DEVICE : RTE_ERR_ARGUMENT;
    }
    return RTE_OK;
}

static rte_status apply_controls(v4l2_source *s, char *msg, size_t msg_size)
{
    for (int32_t i = 0; i < s->cfg.n_controls; i++) {
        const rte_v4l2_control *c = &s->cfg.controls[i];
        rte_status st = set_control(s, c->name, c->value, msg, msg_size);
        if (st != RTE_OK)
            return st;
    }
    return RTE_OK;
}

static void unmap_buffers(v4l2_source *s)
{
    for (int32_t i = 0; i < s->n_buf; i++)
        if (s->buf[i].start)
            s->ops->munmap(s->ops->ctx, s->buf[i].start, s->buf[i].length);
    memset(s->buf, 0, sizeof(s->buf));
    s->n_buf = 0;
}

/* Closes the device (streaming stops with it; the kernel frees the buffers
 * once they are unmapped and the fd is closed). */
static void stop_device(v4l2_source *s)
{
    if (s->fd >= 0) {
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        xioctl(s, VIDIOC_STREAMOFF, &type);
    }
    unmap_buffers(s);
    close_fd(s);
    s->held = -1;
}

static int queue_buffer(v4l2_source *s, uint32_t index)
{
    struct v4l2_buffer b;
    memset(&b, 0, sizeof(b));
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = index;
    return xioctl(s, VIDIOC_QBUF, &b);
}

static rte_status start_streaming(v4l2_source *s, char *msg, size_t msg_size)
{
    struct v4l2_requestbuffers req;
    memset(&req, 0, sizeof(req));
    req.count = (uint32_t)s->cfg.buffers;
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (xioctl(s, VIDIOC_REQBUFS, &req) < 0) {
        rte_source_msgf(msg, msg_size, "%s: VIDIOC_REQBUFS: %s", s->info.path, strerror(errno));
        return RTE_ERR_DEVICE;
    }
    /* One buffer is held by the caller between next() calls: two is the
     * least that keeps the driver capturing. */
    if (req.count < 2 || req.count > RTE_V4L2_MAX_BUFFERS) {
        rte_source_msgf(msg, msg_size, "%s: the driver granted %u buffers", s->info.path, req.count);
        return RTE_ERR_DEVICE;
    }
    for (uint32_t i = 0; i < req.count; i++) {
        struct v4l2_buffer b;
        memset(&b, 0, sizeof(b));
        b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        b.memory = V4L2_MEMORY_MMAP;
        b.index = i;
        if (xioctl(s, VIDIOC_QUERYBUF, &b) < 0) {
            rte_source_msgf(msg, msg_size, "%s: VIDIOC_QUERYBUF: %s", s->info.path, strerror(errno));
            return RTE_ERR_DEVICE;
        }
        void *p = s->ops->mmap(s->ops->ctx, b.length, PROT_READ | PROT_WRITE, MAP_SHARED, s->fd,
                               (off_t)b.m.offset);
        if (p == MAP_FAILED) {
            rte_source_msgf(msg, msg_size, "%s: mmap: %s", s->info.path, strerror(errno));
            return RTE_ERR_DEVICE;
        }
        s->buf[i].start = p;
        s->buf[i].length = b.length;
        s->n_buf = (int32_t)i + 1;
        if (s->info.fourcc != V4L2_PIX_FMT_MJPEG && b.length < raw_frame_bytes(&s->info)) {
            rte_source_msgf(msg, msg_size, "%s: buffer of %u bytes for %u-byte frames", s->info.path,
                       b.length, (unsigned)raw_frame_bytes(&s->info));
            return RTE_ERR_FORMAT;
        }
    }
    for (int32_t i = 0; i < s->n_buf; i++)
        if (queue_buffer(s, (uint32_t)i) < 0) {
            rte_source_msgf(msg, msg_size, "%s: VIDIOC_QBUF: %s", s->info.path, strerror(errno));
            return RTE_ERR_DEVICE;
        }
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(s, VIDIOC_STREAMON, &type) < 0) {
        rte_source_msgf(msg, msg_size, "%s: VIDIOC_STREAMON: %s", s->info.path, strerror(errno));
        return RTE_ERR_DEVICE;
    }
    s->info.buffers = s->n_buf;
    return RTE_OK;
}

/* Everything from open(2) to STREAMON; on failure the device is closed.
 * The message gets the adjustments the driver made. */
static rte_status setup_device(v4l2_source *s, int reopening, char *msg, size_t msg_size)
{
    rte_source_msgf(msg, msg_size, "%s", "");
    rte_status st = open_node(s, msg, msg_size);
    if (st != RTE_OK)
        return st;
    st = negotiate_format(s, reopening, msg, msg_size);
    if (st == RTE_OK) {
        set_frame_rate(s, msg, msg_size);
        st = apply_controls(s, msg, msg_size);
    }
    if (st == RTE_OK)
        st = start_streaming(s, msg, msg_size);
    if (st != RTE_OK) {
        stop_device(s);
        return st;
    }
    s->have_seq = 0;
    s->have_delivered = 0;
    s->held = -1;
    return RTE_OK;
}

static void describe(const v4l2_source *s, char *msg, size_t msg_size)
{
    char adjustments[RTE_SOURCE_MESSAGE_SIZE], name[5];
    copy_string(adjustments, sizeof(adjustments), msg ? msg : "", msg ? msg_size : 1);
    const rte_v4l2_info *i = &s->info;
    rte_source_msgf(msg, msg_size, "%s (%s, %s): %s %dx%d, %u/%u s per frame, %d buffers%s",
               i->path, i->card, i->bus_info, rte_v4l2_fourcc_name(i->fourcc, name), i->width,
               i->height, i->interval_num, i->interval_den, i->buffers, adjustments);
}

/* ---- loss and reconnection ---- */

/* The device failed: close it, report, and reopen it later. */
static rte_status device_lost(v4l2_source *s, const char *what, int err, char *msg,
                              size_t msg_size)
{
    stop_device(s);
    s->stats.state = RTE_SOURCE_RECONNECTING;
    s->stats.errors++;
    s->backoff_ms = s->cfg.reconnect_min_ms;
    s->retry_at_ns = s->ops->now_ns(s->ops->ctx) + (int64_t)s->backoff_ms * 1000000;
    rte_source_msgf(msg, msg_size, "%s: %s: %s; reconnecting", s->info.path, what,
               err ? strerror(err) : "error condition");
    return RTE_ERR_DEVICE;
}

/* Sleeps until the next attempt (within the caller's deadline), then tries
 * to reopen. RTE_OK when streaming again. */
static rte_status reconnect(v4l2_source *s, int64_t deadline_ns, char *msg, size_t msg_size)
{
    int64_t now = s->ops->now_ns(s->ops->ctx);
    int64_t wake = s->retry_at_ns;
    if (deadline_ns >= 0 && deadline_ns < wake)
        wake = deadline_ns;
    if (wake > now)
        s->ops->poll(s->ops->ctx, NULL, 0, (int)((wake - now + 999999) / 1000000));
    now = s->ops->now_ns(s->ops->ctx);
    if (now < s->retry_at_ns) {
        rte_source_msgf(msg, msg_size, "%s: reconnecting, next attempt in %lld ms", s->info.path,
                   (long long)((s->retry_at_ns - now + 999999) / 1000000));
        return RTE_ERR_TIMEOUT;
    }
    rte_status st = setup_device(s, 1, msg, msg_size);
    if (st != RTE_OK) {
        s->stats.errors++;
        s->backoff_ms = s->backoff_ms > s->cfg.reconnect_max_ms / 2 ? s->cfg.reconnect_max_ms
                                                                   : 2 * s->backoff_ms;
        s->retry_at_ns = now + (int64_t)s->backoff_ms * 1000000;
        rte_source_msg_append(msg, msg_size, "; retrying in %d ms", s->backoff_ms);
        return RTE_ERR_DEVICE;
    }
    s->stats.state = RTE_SOURCE_STREAMING;
    s->stats.reconnects++;
    return RTE_OK;
}

/* ---- next() ---- */

/* Counts the gap between the last sequence dequeued and this one. */
static void note_sequence(v4l2_source *s, uint32_t seq)
{
    uint32_t gap = seq - s->last_seq - 1;
    if (s->have_seq && gap != 0 && gap < 0x80000000u)
        s->stats.driver_drops += gap;
    s->have_seq = 1;
    s->last_seq = seq;
}

static int buffer_usable(const v4l2_source *s, const struct v4l2_buffer *b)
{
    if (b->flags & V4L2_BUF_FLAG_ERROR)
        return 0;
    if (s->info.fourcc == V4L2_PIX_FMT_MJPEG)
        return b->bytesused > 0 && b->bytesused <= s->buf[b->index].length;
    return b->bytesused >= raw_frame_bytes(&s->info);
}

static void frame_view(const v4l2_source *s, uint8_t *data, rte_frame *f)
{
    memset(f, 0, sizeof(*f));
    f->format = s->out_format;
    f->width = s->info.width;
    f->height = s->info.height;
    f->plane[0] = data;
    f->stride[0] = s->info.bytesperline;
    if (s->out_format == RTE_PIXEL_NV12) {
        f->plane[1] = data + (size_t)s->info.bytesperline * (size_t)s->info.height;
        f->stride[1] = s->info.bytesperline;
    }
}

/* Decodes an MJPEG buffer into the open-time buffer. */
static rte_status decode_mjpeg(v4l2_source *s, const uint8_t *jpeg, uint32_t size, rte_frame *f,
                               char *msg, size_t msg_size)
{
    int w, h, subsamp, colorspace;
    w = h = 0;
    /* A stream of tables only passes the header check with no size. */
    if (tjDecompressHeader3(s->tj, jpeg, size, &w, &h, &subsamp, &colorspace) != 0 || w < 1 ||
        h < 1) {
        rte_source_msgf(msg, msg_size, "%s: bad JPEG frame: %s", s->info.path, tjGetErrorStr2(s->tj));
        return RTE_ERR_CORRUPT;
    }
    if (w > s->max_width || h > s->max_height) {
        rte_source_msgf(msg, msg_size, "%s: JPEG frame of %dx%d in a %dx%d stream", s->info.path, w, h,
                   s->max_width, s->max_height);
        return RTE_ERR_FORMAT;
    }
    int bgr = s->out_format == RTE_PIXEL_BGR24;
    int pitch = w * (bgr ? 3 : 1);
    if (tjDecompress2(s->tj, jpeg, size, s->decoded, w, pitch, h, bgr ? TJPF_BGR : TJPF_GRAY,
                      TJFLAG_FASTDCT) != 0 &&
        tjGetErrorCode(s->tj) == TJERR_FATAL) {
        rte_source_msgf(msg, msg_size, "%s: bad JPEG frame: %s", s->info.path, tjGetErrorStr2(s->tj));
        return RTE_ERR_CORRUPT;
    }
    memset(f, 0, sizeof(*f));
    f->format = s->out_format;
    f->width = w;
    f->height = h;
    f->plane[0] = s->decoded;
    f->stride[0] = pitch;
    return RTE_OK;
}

static rte_status v4l2_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                            size_t msg_size)
{
    v4l2_source *s = impl;
    const int64_t start = s->ops->now_ns(s->ops->ctx);
    const int64_t deadline = timeout_ms < 0 ? -1 : start + (int64_t)timeout_ms * 1000000;
    rte_source_msgf(msg, msg_size, "%s", "");

    if (s->stats.state == RTE_SOURCE_STREAMING && s->held >= 0) {
        uint32_t index = (uint32_t)s->held;
        s->held = -1;
        if (queue_buffer(s, index) < 0)
            return device_lost(s, "VIDIOC_QBUF", errno, msg, msg_size);
    }
    if (s->stats.state == RTE_SOURCE_RECONNECTING) {
        rte_status st = reconnect(s, deadline, msg, msg_size);
        if (st != RTE_OK)
            return st;
    }

    for (;;) {
        int64_t now = s->ops->now_ns(s->ops->ctx);
        int wait_ms = -1;
        if (deadline >= 0)
            wait_ms = now >= deadline ? 0 : (int)((deadline - now + 999999) / 1000000);
        struct pollfd pfd = { s->fd, POLLIN, 0 };
        int r = s->ops->poll(s->ops->ctx, &pfd, 1, wait_ms);
        if (r < 0) {
            if (errno == EINTR)
                continue;
            return device_lost(s, "poll", errno, msg, msg_size);
        }
        if (r == 0) {
            rte_source_msgf(msg, msg_size, "%s: no frame within %d ms", s->info.path, timeout_ms);
            return RTE_ERR_TIMEOUT;
        }
        if (pfd.revents & (POLLERR | POLLHUP | POLLNVAL))
            return device_lost(s, "poll", 0, msg, msg_size);

        /* Take everything that is ready; keep the newest, give the older
         * ones straight back. */
        struct v4l2_buffer newest;
        memset(&newest, 0, sizeof(newest));
        int have_newest = 0, bad = 0;
        for (;;) {
            struct v4l2_buffer b;
            memset(&b, 0, sizeof(b));
            b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
            b.memory = V4L2_MEMORY_MMAP;
            if (xioctl(s, VIDIOC_DQBUF, &b) < 0) {
                if (errno == EAGAIN)
                    break;
                return device_lost(s, "VIDIOC_DQBUF", errno, msg, msg_size);
            }
            if (b.index >= (uint32_t)s->n_buf)
                return device_lost(s, "VIDIOC_DQBUF", EINVAL, msg, msg_size);
            note_sequence(s, b.sequence);
            uint32_t give_back = b.index;
            if (buffer_usable(s, &b)) {
                if (!have_newest) {
                    have_newest = 1;
                    newest = b;
                    continue;
                }
                s->stats.skipped++;
                give_back = newest.index;
                newest = b;
            } else {
                s->stats.bad_frames++;
                bad = 1;
            }
            if (queue_buffer(s, give_back) < 0)
                return device_lost(s, "VIDIOC_QBUF", errno, msg, msg_size);
        }
        if (!have_newest) {
            if (!bad)
                continue; /* woken without a buffer: wait again */
            s->stats.errors++;
            rte_source_msgf(msg, msg_size, "%s: the driver marked frame %u bad (skipped)",
                       s->info.path, s->last_seq);
            return RTE_ERR_CORRUPT;
        }

        uint8_t *data = s->buf[newest.index].start;
        rte_frame frame;
        if (s->info.fourcc == V4L2_PIX_FMT_MJPEG) {
            rte_status st = decode_mjpeg(s, data, newest.bytesused, &frame, msg, msg_size);
            if (queue_buffer(s, newest.index) < 0)
                return device_lost(s, "VIDIOC_QBUF", errno, msg, msg_size);
            if (st != RTE_OK) {
                s->stats.bad_frames++;
                s->stats.errors++;
                return st;
            }
        } else {
            frame_view(s, data, &frame);
            s->held = (int32_t)newest.index;
        }

        memset(out, 0, sizeof(*out));
        out->frame = frame;
        int64_t dequeued = s->ops->now_ns(s->ops->ctx);
        out->capture_ns = dequeued;
        /* A driver may stamp a frame from its schedule rather than from the
         * clock (vivid stamps the end of the exposure, up to 0.9 frame
         * periods ahead): no frame is captured after it was dequeued. */
        if ((newest.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC) {
            int64_t stamped = (int64_t)newest.timestamp.tv_sec * 1000000000 +
                              (int64_t)newest.timestamp.tv_usec * 1000;
            if (stamped < dequeued)
                out->capture_ns = stamped;
        }
        out->recorded_ns = out->capture_ns;
        out->sequence = newest.sequence;
        out->dropped = s->have_delivered ? newest.sequence - s->last_delivered - 1 : 0;
        s->have_delivered = 1;
        s->last_delivered = newest.sequence;
        s->stats.frames++;
        return RTE_OK;
    }
}

static void v4l2_get_stats(const void *impl, rte_source_stats *stats)
{
    *stats = ((const v4l2_source *)impl)->stats;
}

static void v4l2_close(void *impl)
{
    v4l2_source *s = impl;
    stop_device(s);
    if (s->tj)
        tjDestroy(s->tj);
    free(s->decoded);
    free(s);
}

static const rte_source_ops v4l2_source_ops = { "v4l2", v4l2_next, v4l2_get_stats, v4l2_close };

/* The driver's timestamp type is only known from a dequeued buffer's
 * flags; QUERYBUF returns them too, so look at buffer 0 after streaming
 * started. */
static void check_timestamps(v4l2_source *s)
{
    struct v4l2_buffer b;
    memset(&b, 0, sizeof(b));
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = 0;
    s->info.timestamps_monotonic =
        xioctl(s, VIDIOC_QUERYBUF, &b) == 0 &&
        (b.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
}

rte_status rte_v4l2_source_open(rte_source *source, const rte_v4l2_config *config,
                                rte_v4l2_info *info, char *msg, size_t msg_size)
{
    if (msg && msg_size)
        msg[0] = 0;
    if (!source || !config || !config->device || !config->device[0] ||
        strlen(config->device) >= sizeof(((v4l2_source *)0)->device) || config->width < 1 ||
        config->height < 1 || config->width > RTE_MAX_SIDE || config->height > RTE_MAX_SIDE ||
        config->fps < 0 || config->buffers < 0 || config->buffers > RTE_V4L2_MAX_BUFFERS ||
        config->buffers == 1 || config->n_controls < 0 ||
        config->n_controls > RTE_V4L2_MAX_CONTROLS || config->reconnect_min_ms < 0 ||
        config->reconnect_max_ms < 0) {
        rte_source_msgf(msg, msg_size, "invalid V4L2 source configuration");
        return RTE_ERR_ARGUMENT;
    }
    memset(source, 0, sizeof(*source));
    uint32_t fourcc = config->fourcc ? config->fourcc : V4L2_PIX_FMT_YUYV;
    rte_pixel_format decode_to = config->decode_to ? config->decode_to : RTE_PIXEL_GREY;
    if (delivered_format(fourcc, decode_to) == 0 ||
        (decode_to != RTE_PIXEL_GREY && decode_to != RTE_PIXEL_BGR24)) {
        char name[5];
        rte_source_msgf(msg, msg_size, "V4L2 format %s is not one rtedge reads",
                   rte_v4l2_fourcc_name(fourcc, name));
        return RTE_ERR_UNSUPPORTED;
    }

    v4l2_source *s = calloc(1, sizeof(*s));
    if (!s) {
        rte_source_msgf(msg, msg_size, "out of memory");
        return RTE_ERR_NO_MEMORY;
    }
    s->cfg = *config;
    memcpy(s->device, config->device, strlen(config->device) + 1);
    s->cfg.device = s->device;
    s->cfg.fourcc = fourcc;
    s->cfg.decode_to = decode_to;
    if (!s->cfg.buffers)
        s->cfg.buffers = DEFAULT_BUFFERS;
    if (!s->cfg.reconnect_min_ms)
        s->cfg.reconnect_min_ms = DEFAULT_RECONNECT_MIN_MS;
    if (!s->cfg.reconnect_max_ms)
        s->cfg.reconnect_max_ms = DEFAULT_RECONNECT_MAX_MS;
    if (s->cfg.reconnect_max_ms < s->cfg.reconnect_min_ms)
        s->cfg.reconnect_max_ms = s->cfg.reconnect_min_ms;
    for (int32_t i = 0; i < s->cfg.n_controls; i++)
        s->cfg.controls[i].name[RTE_V4L2_NAME_SIZE - 1] = 0;
    s->ops = config->ops ? config->ops : &rte_v4l2_system_ops;
    s->fd = -1;
    s->held = -1;
    copy_string(s->info.path, sizeof(s->info.path), s->device, sizeof(s->device));

    rte_status st = setup_device(s, 0, msg, msg_size);
    if (st == RTE_OK) {
        s->open_fourcc = s->info.fourcc;
        s->out_format = delivered_format(s->info.fourcc, decode_to);
        s->max_width = s->info.width;
        s->max_height = s->info.height;
        check_timestamps(s);
        if (s->info.fourcc == V4L2_PIX_FMT_MJPEG) {
            s->decoded_size = (size_t)s->max_width * (size_t)s->max_height *
                              (decode_to == RTE_PIXEL_BGR24 ? 3 : 1);
            s->decoded = malloc(s->decoded_size);
            s->tj = tjInitDecompress();
            if (!s->decoded || !s->tj) {
                rte_source_msgf(msg, msg_size, "out of memory for the MJPEG decoder");
                st = RTE_ERR_NO_MEMORY;
            }
        }
    }
    if (st != RTE_OK) {
        v4l2_close(s);
        return st;
    }
    describe(s, msg, msg_size);
    if (info)
        *info = s->info;
    source->ops = &v4l2_source_ops;
    source->impl = s;
    source->max_width = s->max_width;
    source->max_height = s->max_height;
    source->format = s->out_format;
    return RTE_OK;
}

rte_status rte_v4l2_source_set_control(rte_source *source, const char *name, int32_t value,
                                       char *msg, size_t msg_size)
{
    if (!source || source->ops != &v4l2_source_ops || !name) {
        rte_source_msgf(msg, msg_size, "not a V4L2 source");
        return RTE_ERR_ARGUMENT;
    }
    return set_control(source->impl, name, value, msg, msg_size);
}

rte_status rte_v4l2_set_device_control(const char *device, const char *name, int32_t value,
                                       const rte_v4l2_ops *ops, char *msg, size_t msg_size)
{
    v4l2_source s;
    memset(&s, 0, sizeof(s));
    if (!device || !name || strlen(device) >= sizeof(s.device)) {
        rte_source_msgf(msg, msg_size, "no device or control name, or a name too long");
        return RTE_ERR_ARGUMENT;
    }
    s.ops = ops ? ops : &rte_v4l2_system_ops;
    s.fd = -1;
    memcpy(s.device, device, strlen(device) + 1);
    s.cfg.device = s.device;
    copy_string(s.info.path, sizeof(s.info.path), s.device, sizeof(s.device));
    rte_status st = open_node(&s, msg, msg_size);
    if (st != RTE_OK)
        return st;
    st = set_control(&s, name, value, msg, msg_size);
    close_fd(&s);
    return st;
}

/* ---- listing ---- */

static void print_interval(FILE *out, const struct v4l2_fract *t)
{
    if (t->numerator && t->denominator % t->numerator == 0)
        fprintf(out, " %u", t->denominator / t->numerator);
    else
        fprintf(out, " %u/%u", t->denominator, t->numerator);
}

static void list_intervals(v4l2_source *s, uint32_t fourcc, uint32_t w, uint32_t h, FILE *out)
{
    struct v4l2_frmivalenum iv;
    memset(&iv, 0, sizeof(iv));
    iv.pixel_format = fourcc;
    iv.width = w;
    iv.height = h;
    int any = 0;
    for (; xioctl(s, VIDIOC_ENUM_FRAMEINTERVALS, &iv) == 0; iv.index++) {
        fprintf(out, "%s", any ? "," : " @");
        any = 1;
        if (iv.type == V4L2_FRMIVAL_TYPE_DISCRETE) {
            print_interval(out, &iv.discrete);
        } else {
            print_interval(out, &iv.stepwise.max);
            fprintf(out, " ..");
            print_interval(out, &iv.stepwise.min);
            break;
        }
    }
    if (any)
        fprintf(out, " fps");
}

static void list_sizes(v4l2_source *s, uint32_t fourcc, FILE *out)
{
    struct v4l2_frmsizeenum fs;
    memset(&fs, 0, sizeof(fs));
    fs.pixel_format = fourcc;
    for (; xioctl(s, VIDIOC_ENUM_FRAMESIZES, &fs) == 0; fs.index++) {
        if (fs.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
            fprintf(out, "      %ux%u", fs.discrete.width, fs.discrete.height);
            list_intervals(s, fourcc, fs.discrete.width, fs.discrete.height, out);
            fprintf(out, "\n");
        } else {
            fprintf(out, "      %ux%u .. %ux%u (steps %ux%u)\n", fs.stepwise.min_width,
                    fs.stepwise.min_height, fs.stepwise.max_width, fs.stepwise.max_height,
                    fs.stepwise.step_width, fs.stepwise.step_height);
            break;
        }
    }
}

int rte_v4l2_list(FILE *out, const rte_v4l2_ops *ops)
{
    v4l2_source s;
    memset(&s, 0, sizeof(s));
    s.ops = ops ? ops : &rte_v4l2_system_ops;
    int found = 0;
    for (int i = 0; i < MAX_DEVICE_NODES; i++) {
        char path[RTE_V4L2_NAME_SIZE], name[5];
        struct v4l2_capability cap;
        snprintf(path, sizeof(path), "/dev/video%d", i);
        s.fd = s.ops->open(s.ops->ctx, path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
        if (s.fd < 0)
            continue;
        if (query_node(&s, &cap) == RTE_OK) {
            found++;
            fprintf(out, "v4l2 %s: %.32s (driver %.16s, bus %.32s)\n", path, (const char *)cap.card,
                    (const char *)cap.driver, (const char *)cap.bus_info);
            struct v4l2_fmtdesc fd;
            memset(&fd, 0, sizeof(fd));
            fd.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
            for (; xioctl(&s, VIDIOC_ENUM_FMT, &fd) == 0; fd.index++) {
                int usable = delivered_format(fd.pixelformat, RTE_PIXEL_GREY) != 0;
                fprintf(out, "    %s (%.32s)%s\n", rte_v4l2_fourcc_name(fd.pixelformat, name),
                        (const char *)fd.description, usable ? "" : " [not read by rtedge]");
                list_sizes(&s, fd.pixelformat, out);
            }
        }
        close_fd(&s);
    }
    return found;
}
