/* The V4L2 source's logic, driven through its ops table by a scripted fake
 * driver: format negotiation, frame views, MJPEG decoding, newest-frame
 * selection with requeueing, sequence gaps, bad buffers, timestamps,
 * reconnection with backoff, controls and the listing. (The real driver,
 * vivid, runs in the `vm` suite.) */
#define _GNU_SOURCE /* open_memstream, memmem */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>

#include <linux/videodev2.h>
#include <turbojpeg.h>

#include "rtedge/v4l2_source.h"
#include "unit.h"

/* ---- the fake driver ---- */

#define FAKE_NODES 2 /* /dev/video0: metadata only; /dev/video1: the camera */
#define FAKE_BUFS 8
#define FAKE_BUF_BYTES (64 * 1024)
#define FAKE_MAX_FORMATS 4
#define FAKE_MAX_CONTROLS 4

typedef struct fake_control {
    uint32_t id, type, flags;
    const char *name;
    int32_t min, max, value;
    int sets;
} fake_control;

typedef struct fake {
    /* What the driver is. */
    int present; /* the camera node exists */
    uint32_t formats[FAKE_MAX_FORMATS];
    int n_formats;
    uint32_t max_w, max_h;     /* S_FMT clamps to these, width rounded down to even */
    uint32_t force_w, force_h; /* when set, S_FMT always gives this size */
    uint32_t line_pad;         /* bytesperline = width * bpp + line_pad */
    uint32_t grant_max;        /* REQBUFS grants at most this many */
    int timeperframe;          /* supports S_PARM */
    uint32_t fps_allowed;      /* S_PARM always settles on this */
    uint32_t ts_flag;          /* timestamp type in the buffer flags */
    fake_control controls[FAKE_MAX_CONTROLS];
    int n_controls;

    /* Faults, one-shot. */
    int poll_error;
    int dqbuf_errno, qbuf_errno, streamon_errno;

    /* Every poll that finds nothing produces a frame one period later. */
    int auto_frames;
    int64_t period_ns;

    /* State. */
    int64_t now;
    int open_fds;
    int streaming;
    uint32_t n_bufs;
    uint32_t fourcc, width, height, bytesperline, sizeimage;
    uint32_t interval_den;
    int queued[FAKE_BUFS];
    uint32_t fifo[FAKE_BUFS], n_fifo;   /* queued buffers in queue order */
    uint32_t ready[FAKE_BUFS], n_ready; /* filled buffers in completion order */
    struct v4l2_buffer done[FAKE_BUFS]; /* what DQBUF returns for each */
    uint32_t next_seq;
    int mapped;
    int owner_fd; /* the handle that requested the buffers */

    /* Counters. */
    int opens, closes, streamons, qbufs, sleeps;
    uint8_t mem[FAKE_BUFS][FAKE_BUF_BYTES];
    /* What the next filled buffer holds (NULL: the sequence number). */
    const uint8_t *payload;
    uint32_t payload_size;
} fake;

static int32_t bpp(uint32_t fourcc)
{
    return fourcc == V4L2_PIX_FMT_YUYV || fourcc == V4L2_PIX_FMT_UYVY ? 2 : 1;
}

static int supported(const fake *f, uint32_t fourcc)
{
    for (int i = 0; i < f->n_formats; i++)
        if (f->formats[i] == fourcc)
            return 1;
    return 0;
}

/* Fills the oldest queued buffer as frame `seq` (a driver drop when none
 * is queued). Returns the buffer index or -1. */
static int fake_complete(fake *f, uint32_t seq, uint32_t flags, uint32_t bytesused)
{
    f->next_seq = seq + 1;
    if (!f->streaming || f->n_fifo == 0)
        return -1;
    uint32_t index = f->fifo[0];
    memmove(f->fifo, f->fifo + 1, (f->n_fifo - 1) * sizeof(f->fifo[0]));
    f->n_fifo--;
    f->queued[index] = 0;
    struct v4l2_buffer *b = &f->done[index];
    memset(b, 0, sizeof(*b));
    b->type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b->memory = V4L2_MEMORY_MMAP;
    b->index = index;
    b->sequence = seq;
    b->flags = flags | f->ts_flag;
    b->bytesused = bytesused ? bytesused : f->sizeimage;
    b->timestamp.tv_sec = (time_t)(f->now / 1000000000);
    b->timestamp.tv_usec = (suseconds_t)(f->now % 1000000000 / 1000);
    if (f->payload) {
        memcpy(f->mem[index], f->payload, f->payload_size);
        b->bytesused = f->payload_size;
    } else {
        memset(f->mem[index], (int)(seq & 0xff), f->sizeimage);
    }
    f->ready[f->n_ready++] = index;
    return (int)index;
}

static int fake_frame(fake *f) { return fake_complete(f, f->next_seq, 0, 0); }

/* Each open gets its own fd (10 + node + 100 * open count), as the kernel
 * gives each open its own file handle. */
static int node_of(int fd) { return (fd - 10) % 100; }

static int fake_open(void *ctx, const char *path, int flags)
{
    fake *f = ctx;
    (void)flags;
    assert_true(flags & O_NONBLOCK);
    for (int i = 0; i < FAKE_NODES; i++) {
        char p[32];
        snprintf(p, sizeof(p), "/dev/video%d", i);
        if (strcmp(p, path) == 0 && (i == 0 || f->present)) {
            f->opens++;
            f->open_fds++;
            return 10 + i + 100 * (f->opens % 1000);
        }
    }
    errno = ENOENT;
    return -1;
}

static int fake_close(void *ctx, int fd)
{
    fake *f = ctx;
    assert_true(node_of(fd) >= 0 && node_of(fd) < FAKE_NODES);
    f->closes++;
    f->open_fds--;
    if (node_of(fd) == 1 && fd == f->owner_fd) {
        /* Closing the streaming fd stops streaming and frees the buffers. */
        f->owner_fd = 0;
        f->streaming = 0;
        f->n_fifo = f->n_ready = 0;
        memset(f->queued, 0, sizeof(f->queued));
    }
    return 0;
}

static int fail_with(int err)
{
    errno = err;
    return -1;
}

static fake_control *find_ctrl(fake *f, uint32_t id)
{
    for (int i = 0; i < f->n_controls; i++)
        if (f->controls[i].id == id)
            return &f->controls[i];
    return NULL;
}

static int fake_ioctl(void *ctx, int fd, unsigned long request, void *arg)
{
    fake *f = ctx;
    int node = node_of(fd);
    assert_true(node >= 0 && node < FAKE_NODES);
    if (node == 1 && !f->present)
        return fail_with(ENODEV);
    switch (request) {
    case VIDIOC_QUERYCAP: {
        struct v4l2_capability *c = arg;
        memset(c, 0, sizeof(*c));
        strcpy((char *)c->driver, "fake");
        strcpy((char *)c->card, node ? "Fake-Camera  1" : "Fake Metadata");
        strcpy((char *)c->bus_info, node ? "usb-0000:00:14.0-1" : "usb-0000:00:14.0-2");
        c->device_caps = node ? V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING
                              : V4L2_CAP_META_CAPTURE | V4L2_CAP_STREAMING;
        c->capabilities = c->device_caps | V4L2_CAP_DEVICE_CAPS;
        return 0;
    }
    case VIDIOC_S_FMT: {
        struct v4l2_format *fm = arg;
        struct v4l2_pix_format *p = &fm->fmt.pix;
        assert_int_equal(fm->type, V4L2_BUF_TYPE_VIDEO_CAPTURE);
        if (!supported(f, p->pixelformat))
            p->pixelformat = f->formats[0];
        p->width = p->width > f->max_w ? f->max_w : p->width & ~1u;
        p->height = p->height > f->max_h ? f->max_h : p->height;
        if (f->force_w) {
            p->width = f->force_w;
            p->height = f->force_h;
        }
        p->field = V4L2_FIELD_NONE;
        p->bytesperline = p->pixelformat == V4L2_PIX_FMT_MJPEG
                              ? 0
                              : p->width * (uint32_t)bpp(p->pixelformat) + f->line_pad;
        p->sizeimage =
            p->pixelformat == V4L2_PIX_FMT_MJPEG
                ? FAKE_BUF_BYTES / 2
                : p->bytesperline * p->height * (p->pixelformat == V4L2_PIX_FMT_NV12 ? 3 : 2) / 2;
        if (p->pixelformat == V4L2_PIX_FMT_NV12)
            p->sizeimage = p->bytesperline * (p->height + (p->height + 1) / 2);
        else if (p->pixelformat != V4L2_PIX_FMT_MJPEG)
            p->sizeimage = p->bytesperline * p->height;
        assert_true(p->sizeimage <= FAKE_BUF_BYTES);
        f->fourcc = p->pixelformat;
        f->width = p->width;
        f->height = p->height;
        f->bytesperline = p->bytesperline;
        f->sizeimage = p->sizeimage;
        return 0;
    }
    case VIDIOC_G_PARM:
    case VIDIOC_S_PARM: {
        struct v4l2_streamparm *sp = arg;
        if (request == VIDIOC_S_PARM) {
            assert_true(f->timeperframe);
            f->interval_den = f->fps_allowed;
        }
        memset(&sp->parm, 0, sizeof(sp->parm));
        sp->parm.capture.capability = f->timeperframe ? V4L2_CAP_TIMEPERFRAME : 0;
        sp->parm.capture.timeperframe.numerator = 1;
        sp->parm.capture.timeperframe.denominator = f->interval_den;
        return 0;
    }
    case VIDIOC_QUERYCTRL: {
        struct v4l2_queryctrl *q = arg;
        uint32_t id = q->id & ~V4L2_CTRL_FLAG_NEXT_CTRL;
        fake_control *c = NULL;
        for (int i = 0; i < f->n_controls; i++)
            if ((q->id & V4L2_CTRL_FLAG_NEXT_CTRL) ? f->controls[i].id > id
                                                   : f->controls[i].id == id) {
                c = &f->controls[i];
                break;
            }
        if (!c)
            return fail_with(EINVAL);
        memset(q, 0, sizeof(*q));
        q->id = c->id;
        q->type = c->type;
        q->flags = c->flags;
        q->minimum = c->min;
        q->maximum = c->max;
        strncpy((char *)q->name, c->name, sizeof(q->name) - 1);
        return 0;
    }
    case VIDIOC_S_CTRL: {
        struct v4l2_control *ctl = arg;
        fake_control *c = find_ctrl(f, ctl->id);
        if (!c)
            return fail_with(EINVAL);
        c->value = ctl->value;
        c->sets++;
        return 0;
    }
    case VIDIOC_REQBUFS: {
        struct v4l2_requestbuffers *r = arg;
        assert_int_equal(r->memory, V4L2_MEMORY_MMAP);
        assert_false(f->streaming);
        if (f->owner_fd && f->owner_fd != fd)
            return fail_with(EBUSY);
        f->owner_fd = fd;
        f->n_bufs = r->count > f->grant_max ? f->grant_max : r->count;
        r->count = f->n_bufs;
        return 0;
    }
    case VIDIOC_QUERYBUF: {
        struct v4l2_buffer *b = arg;
        if (b->index >= f->n_bufs)
            return fail_with(EINVAL);
        b->length = f->sizeimage;
        b->m.offset = b->index * FAKE_BUF_BYTES;
        b->flags = f->ts_flag;
        return 0;
    }
    case VIDIOC_QBUF: {
        struct v4l2_buffer *b = arg;
        if (f->qbuf_errno) {
            int e = f->qbuf_errno;
            f->qbuf_errno = 0;
            return fail_with(e);
        }
        assert_true(b->index < f->n_bufs);
        assert_false(f->queued[b->index]); /* never queued twice */
        f->queued[b->index] = 1;
        f->fifo[f->n_fifo++] = b->index;
        f->qbufs++;
        return 0;
    }
    case VIDIOC_DQBUF: {
        struct v4l2_buffer *b = arg;
        if (f->dqbuf_errno) {
            int e = f->dqbuf_errno;
            f->dqbuf_errno = 0;
            return fail_with(e);
        }
        if (f->n_ready == 0)
            return fail_with(EAGAIN);
        *b = f->done[f->ready[0]];
        memmove(f->ready, f->ready + 1, (f->n_ready - 1) * sizeof(f->ready[0]));
        f->n_ready--;
        return 0;
    }
    case VIDIOC_STREAMON:
        if (f->streamon_errno) {
            int e = f->streamon_errno;
            f->streamon_errno = 0;
            return fail_with(e);
        }
        f->streaming = 1;
        f->streamons++;
        f->next_seq = 0; /* sequence numbers restart with streaming */
        return 0;
    case VIDIOC_STREAMOFF:
        f->streaming = 0;
        f->n_fifo = f->n_ready = 0;
        memset(f->queued, 0, sizeof(f->queued));
        return 0;
    case VIDIOC_ENUM_FMT: {
        struct v4l2_fmtdesc *d = arg;
        if (node == 0 || d->index >= (uint32_t)f->n_formats)
            return fail_with(EINVAL);
        d->pixelformat = f->formats[d->index];
        snprintf((char *)d->description, sizeof(d->description), "format %u", d->index);
        return 0;
    }
    case VIDIOC_ENUM_FRAMESIZES: {
        struct v4l2_frmsizeenum *s = arg;
        if (s->pixel_format == V4L2_PIX_FMT_GREY && s->index == 0) {
            s->type = V4L2_FRMSIZE_TYPE_STEPWISE;
            s->stepwise.min_width = 16;
            s->stepwise.min_height = 8;
            s->stepwise.max_width = f->max_w;
            s->stepwise.max_height = f->max_h;
            s->stepwise.step_width = 2;
            s->stepwise.step_height = 1;
            return 0;
        }
        if (s->pixel_format == V4L2_PIX_FMT_GREY || s->index >= 2)
            return fail_with(EINVAL);
        s->type = V4L2_FRMSIZE_TYPE_DISCRETE;
        s->discrete.width = s->index ? 32 : 64;
        s->discrete.height = s->index ? 24 : 48;
        return 0;
    }
    case VIDIOC_ENUM_FRAMEINTERVALS: {
        struct v4l2_frmivalenum *iv = arg;
        if (iv->index >= 2)
            return fail_with(EINVAL);
        iv->type = V4L2_FRMIVAL_TYPE_DISCRETE;
        iv->discrete.numerator = iv->index ? 2 : 1;
        iv->discrete.denominator = iv->index ? 25 : 30;
        return 0;
    }
    default: return fail_with(ENOTTY);
    }
}

static int fake_poll(void *ctx, struct pollfd *fds, nfds_t nfds, int timeout_ms)
{
    fake *f = ctx;
    if (!fds) {
        assert_int_equal(nfds, 0);
        assert_true(timeout_ms >= 0);
        f->sleeps++;
        f->now += (int64_t)timeout_ms * 1000000;
        return 0;
    }
    assert_int_equal(nfds, 1);
    if (f->poll_error) {
        f->poll_error = 0;
        fds[0].revents = POLLERR;
        return 1;
    }
    if (f->n_ready == 0 && f->auto_frames && f->streaming &&
        (timeout_ms < 0 || (int64_t)timeout_ms * 1000000 >= f->period_ns)) {
        f->now += f->period_ns;
        fake_frame(f);
    }
    if (f->n_ready) {
        fds[0].revents = POLLIN;
        return 1;
    }
    assert_true(timeout_ms >= 0); /* a test would hang */
    f->now += (int64_t)timeout_ms * 1000000;
    fds[0].revents = 0;
    return 0;
}

static void *fake_mmap(void *ctx, size_t length, int prot, int flags, int fd, off_t offset)
{
    fake *f = ctx;
    assert_int_equal(node_of(fd), 1);
    assert_true(prot & PROT_READ);
    assert_true(flags & MAP_SHARED);
    size_t index = (size_t)offset / FAKE_BUF_BYTES;
    assert_true(index < f->n_bufs && length <= FAKE_BUF_BYTES);
    f->mapped++;
    return f->mem[index];
}

static int fake_munmap(void *ctx, void *addr, size_t length)
{
    fake *f = ctx;
    (void)addr;
    (void)length;
    f->mapped--;
    return 0;
}

static int64_t fake_now(void *ctx) { return ((fake *)ctx)->now; }

/* ---- fixtures ---- */

static fake *F;
static rte_v4l2_ops OPS;

static int setup(void **state)
{
    (void)state;
    F = test_calloc(1, sizeof(*F));
    F->present = 1;
    F->formats[0] = V4L2_PIX_FMT_YUYV;
    F->formats[1] = V4L2_PIX_FMT_GREY;
    F->formats[2] = V4L2_PIX_FMT_NV12;
    F->n_formats = 3;
    F->max_w = 64;
    F->max_h = 48;
    F->line_pad = 16;
    F->grant_max = FAKE_BUFS;
    F->timeperframe = 1;
    F->fps_allowed = 30;
    F->interval_den = 30;
    F->ts_flag = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
    F->period_ns = 33000000;
    F->now = 1000000000;
    F->controls[0] = (fake_control){
        V4L2_CID_BRIGHTNESS, V4L2_CTRL_TYPE_INTEGER, 0, "Brightness", 0, 255, 128, 0};
    F->controls[1] = (fake_control){V4L2_CID_AUTO_WHITE_BALANCE,
                                    V4L2_CTRL_TYPE_BOOLEAN,
                                    0,
                                    "White Balance, Automatic",
                                    0,
                                    1,
                                    1,
                                    0};
    F->controls[2] = (fake_control){V4L2_CID_EXPOSURE_ABSOLUTE,
                                    V4L2_CTRL_TYPE_INTEGER,
                                    0,
                                    "Exposure Time, Absolute",
                                    1,
                                    5000,
                                    100,
                                    0};
    F->controls[3] = (fake_control){V4L2_CID_EXPOSURE_ABSOLUTE + 1,
                                    V4L2_CTRL_TYPE_INTEGER,
                                    V4L2_CTRL_FLAG_READ_ONLY,
                                    "Temperature",
                                    0,
                                    100,
                                    40,
                                    0};
    F->n_controls = 4;
    OPS = (rte_v4l2_ops){fake_open, fake_close,  fake_ioctl, fake_poll,
                         fake_mmap, fake_munmap, fake_now,   F};
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    /* Whatever happened, nothing is left open or mapped. */
    assert_int_equal(F->open_fds, 0);
    assert_int_equal(F->mapped, 0);
    test_free(F);
    return 0;
}

static rte_v4l2_config config(uint32_t fourcc)
{
    rte_v4l2_config c;
    memset(&c, 0, sizeof(c));
    c.device = "/dev/video1";
    c.fourcc = fourcc;
    c.width = 64;
    c.height = 48;
    c.buffers = 4;
    c.ops = &OPS;
    return c;
}

static void open_ok(rte_source *src, const rte_v4l2_config *c, rte_v4l2_info *info)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_status st = rte_v4l2_source_open(src, c, info, msg, sizeof(msg));
    if (st != RTE_OK)
        fail_msg("open: %s", msg);
}

static rte_status next(rte_source *src, rte_source_frame *fr, int32_t timeout_ms)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    return rte_source_next(src, fr, timeout_ms, msg, sizeof(msg));
}

static rte_source_stats stats_of(const rte_source *src)
{
    rte_source_stats s;
    rte_source_get_stats(src, &s);
    return s;
}

static uint32_t queued_count(void) { return F->n_fifo; }

/* ---- negotiation ---- */

static void test_open_plain(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    c.fps = 30;
    rte_v4l2_info info;
    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_v4l2_source_open(&src, &c, &info, msg, sizeof(msg)), RTE_OK);
    assert_string_equal(msg, "/dev/video1 (Fake-Camera  1, usb-0000:00:14.0-1): YUYV 64x48, "
                             "1/30 s per frame, 4 buffers");
    assert_false(info.adjusted);
    assert_int_equal(info.fourcc, V4L2_PIX_FMT_YUYV);
    assert_int_equal(info.bytesperline, 64 * 2 + 16);
    assert_int_equal(info.buffers, 4);
    assert_true(info.timestamps_monotonic);
    assert_string_equal(info.driver, "fake");
    assert_int_equal(src.format, RTE_PIXEL_YUYV);
    assert_int_equal(src.max_width, 64);
    assert_int_equal(src.max_height, 48);
    assert_int_equal(F->streamons, 1);
    assert_int_equal(queued_count(), 4);
    assert_int_equal(F->mapped, 4);
    rte_source_close(&src);
    assert_null(src.ops);
}

/* The driver rounds the width, clamps the height and picks another frame
 * rate: all accepted and reported. */
static void test_open_driver_adjusts_size_and_rate(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_NV12);
    c.width = 63;
    c.height = 100;
    c.fps = 60;
    rte_v4l2_info info;
    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_v4l2_source_open(&src, &c, &info, msg, sizeof(msg)), RTE_OK);
    assert_true(info.adjusted);
    assert_int_equal(info.width, 62);
    assert_int_equal(info.height, 48);
    assert_int_equal(info.interval_den, 30);
    assert_non_null(strstr(msg, "driver adjusted NV12 63x100 to NV12 62x48"));
    assert_non_null(strstr(msg, "driver adjusted 60 fps to 1/30 s per frame"));
    assert_int_equal(src.format, RTE_PIXEL_NV12);
    assert_int_equal(src.max_width, 62);

    /* The NV12 view: UV after bytesperline * height, same stride. */
    fake_frame(F);
    rte_source_frame fr;
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.frame.format, RTE_PIXEL_NV12);
    assert_int_equal(fr.frame.width, 62);
    assert_int_equal(fr.frame.height, 48);
    assert_int_equal(fr.frame.stride[0], 62 + 16);
    assert_int_equal(fr.frame.stride[1], 62 + 16);
    assert_ptr_equal(fr.frame.plane[1], fr.frame.plane[0] + (62 + 16) * 48);
    /* A valid rte_frame whose grey image is its Y plane. */
    assert_int_equal(rte_frame_check(&fr.frame), RTE_OK);
    rte_image_u8 grey;
    assert_int_equal(rte_frame_gray_view(&fr.frame, &grey), RTE_OK);
    assert_ptr_equal(grey.buf, fr.frame.plane[0]);
    assert_int_equal(grey.stride, 62 + 16);
    rte_source_close(&src);
}

/* Asked for UYVY, the driver only has YUYV (which rtedge reads too). */
static void test_open_driver_changes_format(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_UYVY);
    rte_v4l2_info info;
    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_v4l2_source_open(&src, &c, &info, msg, sizeof(msg)), RTE_OK);
    assert_true(info.adjusted);
    assert_int_equal(info.fourcc, V4L2_PIX_FMT_YUYV);
    assert_int_equal(src.format, RTE_PIXEL_YUYV);
    assert_non_null(strstr(msg, "driver adjusted UYVY 64x48 to YUYV 64x48"));
    rte_source_close(&src);
}

/* A driver that offers only a format rtedge does not read. */
static void test_open_unreadable_format(void **state)
{
    (void)state;
    F->formats[0] = V4L2_PIX_FMT_SBGGR8;
    F->n_formats = 1;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_UNSUPPORTED);
    assert_non_null(strstr(msg, "asked for YUYV, the driver offers BA81"));
    assert_null(src.ops);
    assert_int_equal(F->opens, F->closes);
}

static void test_open_errors(void **state)
{
    (void)state;
    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);

    assert_int_equal(rte_v4l2_source_open(NULL, &c, NULL, msg, sizeof(msg)), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_v4l2_source_open(&src, NULL, NULL, msg, sizeof(msg)), RTE_ERR_ARGUMENT);
    c.width = 0;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, NULL, 0), RTE_ERR_ARGUMENT);
    c = config(V4L2_PIX_FMT_YUYV);
    c.buffers = 1;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_ARGUMENT);
    c.buffers = RTE_V4L2_MAX_BUFFERS + 1;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_ARGUMENT);
    c = config(V4L2_PIX_FMT_SBGGR8);
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_UNSUPPORTED);
    c = config(V4L2_PIX_FMT_MJPEG);
    c.decode_to = RTE_PIXEL_NV12;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_UNSUPPORTED);
    assert_int_equal(F->opens, 0);

    /* No such node, a node that is not a capture device, one buffer granted. */
    c = config(V4L2_PIX_FMT_YUYV);
    c.device = "/dev/video7";
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_DEVICE);
    c.device = "/dev/video0";
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_UNSUPPORTED);
    assert_non_null(strstr(msg, "not a video capture node"));
    c.device = "No Such Camera";
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_string_equal(msg, "no capture device with card or bus \"No Such Camera\"");
    c = config(V4L2_PIX_FMT_YUYV);
    F->grant_max = 1;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "granted 1 buffers"));
    F->grant_max = FAKE_BUFS;
    F->streamon_errno = EIO;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "VIDIOC_STREAMON"));
    assert_int_equal(F->opens, F->closes);
}

/* By card (names compare like control names) or by bus; the metadata node
 * at /dev/video0 is passed over. */
static void test_open_by_name(void **state)
{
    (void)state;
    const char *names[] = {"fake camera 1", "FAKE_CAMERA_1", "usb-0000:00:14.0-1"};
    for (int i = 0; i < 3; i++) {
        rte_v4l2_config c = config(V4L2_PIX_FMT_GREY);
        c.device = names[i];
        rte_v4l2_info info;
        rte_source src;
        open_ok(&src, &c, &info);
        assert_string_equal(info.path, "/dev/video1");
        assert_int_equal(src.format, RTE_PIXEL_GREY);
        rte_source_close(&src);
    }
    rte_v4l2_config c = config(V4L2_PIX_FMT_GREY);
    c.device = "fakecamera1";
    rte_source src;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, NULL, 0), RTE_ERR_DEVICE);
}

/* ---- controls ---- */

static void test_controls(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    c.n_controls = 3;
    strcpy(c.controls[0].name, "white_balance_automatic");
    c.controls[0].value = 0;
    strcpy(c.controls[1].name, "EXPOSURE time absolute");
    c.controls[1].value = 250;
    strcpy(c.controls[2].name, " brightness ");
    c.controls[2].value = 7;
    rte_source src;
    open_ok(&src, &c, NULL);
    assert_int_equal(F->controls[1].value, 0);
    assert_int_equal(F->controls[2].value, 250);
    assert_int_equal(F->controls[0].value, 7);

    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_v4l2_source_set_control(&src, "Brightness", 9, msg, sizeof(msg)), RTE_OK);
    assert_int_equal(F->controls[0].value, 9);
    assert_int_equal(rte_v4l2_source_set_control(&src, "brightness", 256, msg, sizeof(msg)),
                     RTE_ERR_ARGUMENT);
    assert_string_equal(msg, "control \"Brightness\": 256 is outside 0..255");
    assert_int_equal(
        rte_v4l2_source_set_control(&src, "whitebalance automatic", 1, msg, sizeof(msg)),
        RTE_ERR_ARGUMENT);
    assert_string_equal(msg, "/dev/video1 has no control \"whitebalance automatic\"");
    assert_int_equal(rte_v4l2_source_set_control(&src, "temperature", 1, msg, sizeof(msg)),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(F->controls[3].sets, 0);
    assert_int_equal(rte_v4l2_source_set_control(NULL, "Brightness", 1, msg, sizeof(msg)),
                     RTE_ERR_ARGUMENT);
    rte_source_close(&src);

    /* A bad control in the config fails the open and closes the device. */
    c.n_controls = 1;
    strcpy(c.controls[0].name, "Exposure Time Absolute");
    c.controls[0].value = 0;
    assert_int_equal(rte_v4l2_source_open(&src, &c, NULL, msg, sizeof(msg)), RTE_ERR_ARGUMENT);
    assert_string_equal(msg, "control \"Exposure Time, Absolute\": 0 is outside 1..5000");
    assert_int_equal(F->opens, F->closes);
}

/* A control set from another file handle while the source streams (what
 * an operator's tool, or the vm suite's fault injection, does): by path or
 * card name, the fd closed again, the stream undisturbed. */
static void test_device_control(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    rte_source src;
    open_ok(&src, &c, NULL);
    int opens = F->opens, closes = F->closes;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(
        rte_v4l2_set_device_control("/dev/video1", "brightness", 42, &OPS, msg, sizeof(msg)),
        RTE_OK);
    assert_int_equal(F->controls[0].value, 42);
    assert_int_equal(
        rte_v4l2_set_device_control("fake camera 1", "Brightness", 43, &OPS, msg, sizeof(msg)),
        RTE_OK);
    assert_int_equal(F->controls[0].value, 43);
    assert_int_equal(
        rte_v4l2_set_device_control("/dev/video1", "brightness", 300, &OPS, msg, sizeof(msg)),
        RTE_ERR_ARGUMENT);
    assert_string_equal(msg, "control \"Brightness\": 300 is outside 0..255");
    assert_int_equal(
        rte_v4l2_set_device_control("/dev/video7", "brightness", 1, &OPS, msg, sizeof(msg)),
        RTE_ERR_DEVICE);
    assert_int_equal(rte_v4l2_set_device_control(NULL, "brightness", 1, &OPS, msg, sizeof(msg)),
                     RTE_ERR_ARGUMENT);
    /* Every handle it opened is closed; the source's is untouched. */
    assert_int_equal(F->opens - opens, 4); /* by name: /dev/video0 is tried first */
    assert_int_equal(F->closes - closes, 4);
    assert_int_equal(F->streaming, 1);
    fake_frame(F);
    rte_source_frame fr;
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    rte_source_close(&src);
}

/* ---- frames ---- */

/* Three frames ready: the newest is handed out, the two older ones go
 * straight back to the driver and are counted as skipped. */
static void test_newest_frame(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    rte_source src;
    open_ok(&src, &c, NULL);
    rte_source_frame fr;

    fake_frame(F);
    fake_frame(F);
    fake_frame(F);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 2);
    assert_int_equal(fr.dropped, 0);
    assert_int_equal(fr.frame.plane[0][0], 2); /* the buffer that holds frame 2 */
    assert_int_equal(fr.frame.plane[0][64 * 2 - 1], 2);
    assert_int_equal(fr.frame.stride[0], 64 * 2 + 16);
    assert_int_equal(rte_frame_check(&fr.frame), RTE_OK);
    assert_int_equal(queued_count(), 3); /* all but the one handed out */
    rte_source_stats s = stats_of(&src);
    assert_int_equal(s.skipped, 2);
    assert_int_equal(s.frames, 1);
    assert_int_equal(s.driver_drops, 0);

    /* The held buffer goes back on the next call. */
    fake_frame(F);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 3);
    assert_int_equal(fr.dropped, 0);
    assert_int_equal(fr.frame.plane[0][0], 3);
    assert_int_equal(queued_count(), 3);

    fake_frame(F);
    fake_frame(F);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 5);
    assert_int_equal(fr.dropped, 1); /* frame 4, skipped */
    s = stats_of(&src);
    assert_int_equal(s.skipped, 3);
    assert_int_equal(s.frames, 3);
    assert_int_equal(s.state, RTE_SOURCE_STREAMING);

    /* Nothing ready: a timeout after the time asked for. */
    int64_t before = F->now;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_source_next(&src, &fr, 40, msg, sizeof(msg)), RTE_ERR_TIMEOUT);
    assert_string_equal(msg, "/dev/video1: no frame within 40 ms");
    assert_int_equal(F->now - before, 40000000);
    assert_int_equal(queued_count(), 4);
    rte_source_close(&src);
}

/* Gaps in the driver's sequence are driver drops, also across the 32-bit
 * wrap; a frame the driver could not fill (no buffer queued) is one too. */
static void test_sequence_gaps(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_GREY);
    c.buffers = 2;
    rte_source src;
    open_ok(&src, &c, NULL);
    rte_source_frame fr;

    fake_complete(F, 10, 0, 0);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 10);
    fake_complete(F, 13, 0, 0); /* 11, 12 lost */
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 13);
    assert_int_equal(fr.dropped, 2);
    assert_int_equal(stats_of(&src).driver_drops, 2);

    /* Frame 13 is held, 14 fills the other buffer, 15 finds none queued. */
    assert_true(fake_complete(F, 14, 0, 0) >= 0);
    assert_int_equal(fake_complete(F, 15, 0, 0), -1);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 14);
    assert_int_equal(fr.dropped, 0);
    fake_frame(F); /* 16 */
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 16);
    assert_int_equal(fr.dropped, 1);
    assert_int_equal(stats_of(&src).driver_drops, 3);

    /* A jump by 2^31 or more (or backwards, or a repeat) is a restart, not
     * a loss; the 32-bit wrap is counted like any other step. */
    fake_complete(F, 16, 0, 0); /* vivid repeats one now and then */
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 16);
    assert_int_equal(fr.dropped, 0);
    fake_complete(F, 0xFFFFFFFEu, 0, 0);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.dropped, 0);
    assert_int_equal(stats_of(&src).driver_drops, 3);
    fake_complete(F, 0xFFFFFFF0u, 0, 0); /* backwards */
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.dropped, 0);
    fake_complete(F, 0xFFFFFFFEu, 0, 0); /* 0xFFFFFFF1 .. 0xFFFFFFFD lost */
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.dropped, 13);
    fake_complete(F, 0xFFFFFFFFu, 0, 0);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    fake_complete(F, 0, 0, 0);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.dropped, 0);
    fake_complete(F, 2, 0, 0);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.dropped, 1);
    rte_source_stats s = stats_of(&src);
    assert_int_equal(s.driver_drops, 17);
    assert_int_equal(s.skipped, 0);
    rte_source_close(&src);
}

/* Buffers flagged bad or too short are skipped, counted and requeued. */
static void test_bad_buffers(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    rte_source src;
    open_ok(&src, &c, NULL);
    rte_source_frame fr;
    char msg[RTE_SOURCE_MESSAGE_SIZE];

    fake_complete(F, 0, V4L2_BUF_FLAG_ERROR, 0);
    assert_int_equal(rte_source_next(&src, &fr, 0, msg, sizeof(msg)), RTE_ERR_CORRUPT);
    assert_string_equal(msg, "/dev/video1: the driver marked frame 0 bad (skipped)");
    assert_int_equal(queued_count(), 4);
    fake_complete(F, 1, 0, 100); /* shorter than a frame */
    assert_int_equal(next(&src, &fr, 0), RTE_ERR_CORRUPT);
    /* A bad one between good ones: the newest good one comes out. */
    fake_complete(F, 2, 0, 0);
    fake_complete(F, 3, V4L2_BUF_FLAG_ERROR, 0);
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.sequence, 2);
    rte_source_stats s = stats_of(&src);
    assert_int_equal(s.bad_frames, 3);
    assert_int_equal(s.frames, 1);
    assert_int_equal(s.errors, 2);
    assert_int_equal(s.state, RTE_SOURCE_STREAMING);
    assert_int_equal(queued_count(), 3);
    rte_source_close(&src);
}

static void test_timestamps(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    rte_source src;
    rte_source_frame fr;
    rte_v4l2_info info;
    open_ok(&src, &c, &info);
    F->now = 5123456789;
    fake_frame(F);
    F->now += 7000000; /* dequeued later: the driver's time counts */
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.capture_ns, 5123456000); /* microsecond resolution */
    assert_int_equal(fr.recorded_ns, fr.capture_ns);
    /* Stamped ahead of the clock (from the driver's schedule): the time
     * of dequeueing, as no frame is captured later than that. */
    fake_frame(F);
    F->now -= 3000000;
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.capture_ns, F->now);
    rte_source_close(&src);

    /* Not monotonic: the time of dequeueing instead. */
    F->ts_flag = V4L2_BUF_FLAG_TIMESTAMP_COPY;
    open_ok(&src, &c, &info);
    assert_false(info.timestamps_monotonic);
    fake_frame(F);
    F->now += 7000000;
    assert_int_equal(next(&src, &fr, 0), RTE_OK);
    assert_int_equal(fr.capture_ns, F->now);
    rte_source_close(&src);
}

/* ---- MJPEG ---- */

static unsigned char *make_jpeg(int w, int h, unsigned long *size, uint8_t *bgr)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            bgr[(y * w + x) * 3 + 0] = (uint8_t)(x * 4);
            bgr[(y * w + x) * 3 + 1] = (uint8_t)(y * 5);
            bgr[(y * w + x) * 3 + 2] = (uint8_t)(128);
        }
    tjhandle tj = tjInitCompress();
    assert_non_null(tj);
    unsigned char *jpeg = NULL;
    assert_int_equal(tjCompress2(tj, bgr, w, w * 3, h, TJPF_BGR, &jpeg, size, TJSAMP_444, 95, 0),
                     0);
    tjDestroy(tj);
    return jpeg;
}

static void test_mjpeg(void **state)
{
    (void)state;
    F->formats[3] = V4L2_PIX_FMT_MJPEG;
    F->n_formats = 4;
    static uint8_t bgr[64 * 48 * 3];
    unsigned long size;
    unsigned char *jpeg = make_jpeg(64, 48, &size, bgr);
    /* What libturbojpeg itself makes of it, as the reference. */
    tjhandle tj = tjInitDecompress();
    static uint8_t ref_bgr[64 * 48 * 3], ref_grey[64 * 48];
    assert_int_equal(
        tjDecompress2(tj, jpeg, size, ref_bgr, 64, 64 * 3, 48, TJPF_BGR, TJFLAG_FASTDCT), 0);
    assert_int_equal(tjDecompress2(tj, jpeg, size, ref_grey, 64, 64, 48, TJPF_GRAY, TJFLAG_FASTDCT),
                     0);
    tjDestroy(tj);

    for (int as_bgr = 0; as_bgr < 2; as_bgr++) {
        rte_v4l2_config c = config(V4L2_PIX_FMT_MJPEG);
        c.decode_to = as_bgr ? RTE_PIXEL_BGR24 : RTE_PIXEL_GREY;
        rte_source src;
        open_ok(&src, &c, NULL);
        assert_int_equal(src.format, as_bgr ? RTE_PIXEL_BGR24 : RTE_PIXEL_GREY);
        F->payload = jpeg;
        F->payload_size = (uint32_t)size;
        fake_frame(F);
        fake_frame(F);
        rte_source_frame fr;
        char msg[RTE_SOURCE_MESSAGE_SIZE];
        if (rte_source_next(&src, &fr, 0, msg, sizeof(msg)) != RTE_OK)
            fail_msg("next: %s", msg);
        assert_int_equal(fr.frame.width, 64);
        assert_int_equal(fr.frame.height, 48);
        assert_int_equal(fr.frame.stride[0], as_bgr ? 64 * 3 : 64);
        assert_int_equal(fr.sequence, 1);
        assert_int_equal(rte_frame_check(&fr.frame), RTE_OK);
        assert_memory_equal(fr.frame.plane[0], as_bgr ? ref_bgr : ref_grey,
                            as_bgr ? sizeof(ref_bgr) : sizeof(ref_grey));
        /* Decoded into our own buffer: every driver buffer is back. */
        assert_int_equal(queued_count(), 4);
        assert_int_equal(stats_of(&src).skipped, 1);

        /* Garbage is skipped and counted. */
        static const uint8_t junk[64] = {0xff, 0xd8, 0x01, 0x02};
        F->payload = junk;
        F->payload_size = sizeof(junk);
        fake_frame(F);
        assert_int_equal(rte_source_next(&src, &fr, 0, msg, sizeof(msg)), RTE_ERR_CORRUPT);
        assert_non_null(strstr(msg, "bad JPEG frame"));
        assert_int_equal(stats_of(&src).bad_frames, 1);
        assert_int_equal(queued_count(), 4);
        F->payload = NULL;
        rte_source_close(&src);
    }

    /* A JPEG larger than the stream's size never overflows the buffer. */
    rte_v4l2_config c = config(V4L2_PIX_FMT_MJPEG);
    c.width = 32;
    c.height = 24;
    rte_source src;
    open_ok(&src, &c, NULL);
    F->payload = jpeg;
    F->payload_size = (uint32_t)size;
    fake_frame(F);
    rte_source_frame fr;
    assert_int_equal(next(&src, &fr, 0), RTE_ERR_FORMAT);
    F->payload = NULL;
    rte_source_close(&src);
    tjFree(jpeg);
}

/* ---- loss and reconnection ---- */

/* Opens with frames coming on demand, takes one, then the device reports
 * POLLERR: the loss is reported once and everything is closed. */
static void open_and_lose(rte_source *src, const rte_v4l2_config *c)
{
    rte_source_frame fr;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    open_ok(src, c, NULL);
    F->auto_frames = 1;
    assert_int_equal(next(src, &fr, 100), RTE_OK);
    F->poll_error = 1;
    assert_int_equal(rte_source_next(src, &fr, 100, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_string_equal(msg, "/dev/video1: poll: error condition; reconnecting");
    assert_int_equal(F->open_fds, 0);
    assert_int_equal(F->mapped, 0);
    assert_int_equal(stats_of(src).state, RTE_SOURCE_RECONNECTING);
}

/* POLLERR: the device is closed (all buffers unmapped), RTE_ERR_DEVICE is
 * reported once and the source reopens it on later calls, with a backoff
 * that doubles up to the maximum while the device stays away. */
static void test_reconnect_backoff(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    c.reconnect_min_ms = 100;
    c.reconnect_max_ms = 500;
    rte_source src;
    rte_source_frame fr;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    open_and_lose(&src, &c);
    F->present = 0; /* and the node stays away */

    /* Attempts at +100, then +200, +400, +500, +500 ms. */
    int64_t lost = F->now;
    const int64_t expect_ms[] = {100, 300, 700, 1200, 1700};
    for (int i = 0; i < 5; i++) {
        int opens = F->opens;
        assert_int_equal(rte_source_next(&src, &fr, 1000, msg, sizeof(msg)), RTE_ERR_DEVICE);
        assert_int_equal(F->opens, opens); /* the node is gone: open fails */
        assert_int_equal(F->now - lost, expect_ms[i] * 1000000);
        assert_non_null(strstr(msg, "No such file"));
    }
    assert_non_null(strstr(msg, "retrying in 500 ms"));
    /* A short wait before the next attempt is due: a timeout, no attempt. */
    int64_t before = F->now;
    assert_int_equal(rte_source_next(&src, &fr, 30, msg, sizeof(msg)), RTE_ERR_TIMEOUT);
    assert_int_equal(F->now - before, 30000000);
    assert_non_null(strstr(msg, "reconnecting, next attempt in 470 ms"));
    rte_source_stats s = stats_of(&src);
    assert_int_equal(s.state, RTE_SOURCE_RECONNECTING);
    assert_int_equal(s.errors, 6);
    assert_int_equal(s.reconnects, 0);

    /* Back, but STREAMON fails once: one more round of backoff. */
    F->present = 1;
    F->streamon_errno = EIO;
    assert_int_equal(rte_source_next(&src, &fr, 1000, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "VIDIOC_STREAMON"));
    assert_int_equal(F->open_fds, 0);
    assert_int_equal(F->mapped, 0);
    assert_int_equal(next(&src, &fr, 1000), RTE_OK);
    s = stats_of(&src);
    assert_int_equal(s.state, RTE_SOURCE_STREAMING);
    assert_int_equal(s.reconnects, 1);
    assert_int_equal(F->mapped, 4);
    assert_int_equal(F->open_fds, 1);
    /* Sequence numbers restart with the device: no gap counted. */
    assert_int_equal(fr.dropped, 0);
    assert_int_equal(s.driver_drops, 0);

    /* The backoff starts from the minimum again after a success. */
    F->dqbuf_errno = ENODEV;
    assert_int_equal(next(&src, &fr, 100), RTE_ERR_DEVICE);
    before = F->now;
    assert_int_equal(next(&src, &fr, 1000), RTE_OK);
    assert_true(F->now - before >= 100000000 && F->now - before < 200000000);
    assert_int_equal(stats_of(&src).reconnects, 2);

    /* EIO from QBUF (giving back the held buffer) is a loss too. */
    F->qbuf_errno = EIO;
    assert_int_equal(rte_source_next(&src, &fr, 100, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "VIDIOC_QBUF"));
    assert_int_equal(next(&src, &fr, 1000), RTE_OK);
    assert_int_equal(stats_of(&src).reconnects, 3);
    rte_source_close(&src);
}

/* A device that comes back larger than at open is not taken: the source
 * never grows beyond its open-time sizes. */
static void test_reconnect_size_changed(void **state)
{
    (void)state;
    rte_v4l2_config c = config(V4L2_PIX_FMT_YUYV);
    c.width = 32;
    c.height = 24;
    rte_source src;
    rte_source_frame fr;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    open_and_lose(&src, &c);
    F->force_w = 64;
    F->force_h = 48;
    assert_int_equal(rte_source_next(&src, &fr, 1000, msg, sizeof(msg)), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "came back with YUYV 64x48, not the 32x24 it had"));
    assert_int_equal(F->open_fds, 0);
    /* Smaller is fine (frames carry their size). */
    F->force_w = 16;
    F->force_h = 8;
    assert_int_equal(next(&src, &fr, 1000), RTE_OK);
    assert_int_equal(fr.frame.width, 16);
    assert_int_equal(fr.frame.height, 8);
    assert_int_equal(src.max_width, 32);
    rte_source_close(&src);
}

/* ---- listing ---- */

static void test_list(void **state)
{
    (void)state;
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    assert_non_null(out);
    assert_int_equal(rte_v4l2_list(out, &OPS), 1);
    fclose(out);
    const char *expected =
        "v4l2 /dev/video1: Fake-Camera  1 (driver fake, bus usb-0000:00:14.0-1)\n"
        "    YUYV (format 0)\n"
        "      64x48 @ 30, 25/2 fps\n"
        "      32x24 @ 30, 25/2 fps\n"
        "    GREY (format 1)\n"
        "      16x8 .. 64x48 (steps 2x1)\n"
        "    NV12 (format 2)\n"
        "      64x48 @ 30, 25/2 fps\n"
        "      32x24 @ 30, 25/2 fps\n";
    assert_string_equal(text, expected);
    free(text);
    assert_int_equal(F->open_fds, 0);
}

static void test_fourcc_name(void **state)
{
    (void)state;
    char buf[5];
    assert_string_equal(rte_v4l2_fourcc_name(V4L2_PIX_FMT_MJPEG, buf), "MJPG");
    assert_string_equal(rte_v4l2_fourcc_name(0x00010203, buf), "....");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_open_plain, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_driver_adjusts_size_and_rate, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_driver_changes_format, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_unreadable_format, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_by_name, setup, teardown),
        cmocka_unit_test_setup_teardown(test_controls, setup, teardown),
        cmocka_unit_test_setup_teardown(test_device_control, setup, teardown),
        cmocka_unit_test_setup_teardown(test_newest_frame, setup, teardown),
        cmocka_unit_test_setup_teardown(test_sequence_gaps, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_buffers, setup, teardown),
        cmocka_unit_test_setup_teardown(test_timestamps, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mjpeg, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reconnect_backoff, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reconnect_size_changed, setup, teardown),
        cmocka_unit_test_setup_teardown(test_list, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fourcc_name, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
