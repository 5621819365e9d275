/* V4L2 streaming: the mmap buffers and next(), which dequeues every ready
 * buffer, keeps the newest, gives the older ones back and hands out a view
 * of it (or, for MJPEG, the image decoded from it). */
#include "sources/v4l2_internal.h"

#include <errno.h>
#include <stdbool.h>
#include <string.h>
#include <sys/mman.h>

#include "source_msg.h"

/* ---- buffers ---- */

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
void rte_v4l2_stop_device(v4l2_source *s)
{
    if (s->fd >= 0) {
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        rte_v4l2_xioctl(s, VIDIOC_STREAMOFF, &type);
    }
    unmap_buffers(s);
    rte_v4l2_close_fd(s);
    s->held = -1;
}

static int queue_buffer(v4l2_source *s, uint32_t index)
{
    struct v4l2_buffer b;
    memset(&b, 0, sizeof(b));
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = index;
    return rte_v4l2_xioctl(s, VIDIOC_QBUF, &b);
}

rte_status rte_v4l2_start_streaming(v4l2_source *s, char *msg, size_t msg_size)
{
    struct v4l2_requestbuffers req;
    memset(&req, 0, sizeof(req));
    req.count = (uint32_t)s->cfg.buffers;
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (rte_v4l2_xioctl(s, VIDIOC_REQBUFS, &req) < 0) {
        rte_source_msgf(msg, msg_size, "%s: VIDIOC_REQBUFS: %s", s->info.path, strerror(errno));
        return RTE_ERR_DEVICE;
    }
    /* One buffer is held by the caller between next() calls: two is the
     * least that keeps the driver capturing. */
    if (req.count < 2 || req.count > RTE_V4L2_MAX_BUFFERS) {
        rte_source_msgf(msg, msg_size, "%s: the driver granted %u buffers", s->info.path,
                        req.count);
        return RTE_ERR_DEVICE;
    }
    for (uint32_t i = 0; i < req.count; i++) {
        struct v4l2_buffer b;
        memset(&b, 0, sizeof(b));
        b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        b.memory = V4L2_MEMORY_MMAP;
        b.index = i;
        if (rte_v4l2_xioctl(s, VIDIOC_QUERYBUF, &b) < 0) {
            rte_source_msgf(msg, msg_size, "%s: VIDIOC_QUERYBUF: %s", s->info.path,
                            strerror(errno));
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
        if (s->info.fourcc != V4L2_PIX_FMT_MJPEG && b.length < rte_v4l2_raw_frame_bytes(&s->info)) {
            rte_source_msgf(msg, msg_size, "%s: buffer of %u bytes for %u-byte frames",
                            s->info.path, b.length, (unsigned)rte_v4l2_raw_frame_bytes(&s->info));
            return RTE_ERR_FORMAT;
        }
    }
    for (int32_t i = 0; i < s->n_buf; i++)
        if (queue_buffer(s, (uint32_t)i) < 0) {
            rte_source_msgf(msg, msg_size, "%s: VIDIOC_QBUF: %s", s->info.path, strerror(errno));
            return RTE_ERR_DEVICE;
        }
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (rte_v4l2_xioctl(s, VIDIOC_STREAMON, &type) < 0) {
        rte_source_msgf(msg, msg_size, "%s: VIDIOC_STREAMON: %s", s->info.path, strerror(errno));
        return RTE_ERR_DEVICE;
    }
    s->info.buffers = s->n_buf;
    return RTE_OK;
}

/* ---- next() ---- */

/* Frames lost between sequence numbers last and seq: a step back, a repeat
 * (vivid repeats one when its thread wakes twice in a frame period) or a
 * jump by 2^31 or more is a restart, not a loss; the 32-bit wrap is a step
 * like any other. */
static uint32_t sequence_gap(uint32_t last, uint32_t seq)
{
    uint32_t gap = seq - last - 1;
    return gap < 0x80000000u ? gap : 0;
}

/* Counts the gap between the last sequence dequeued and this one. */
static void note_sequence(v4l2_source *s, uint32_t seq)
{
    if (s->have_seq)
        s->stats.driver_drops += sequence_gap(s->last_seq, seq);
    s->have_seq = true;
    s->last_seq = seq;
}

static bool buffer_usable(const v4l2_source *s, const struct v4l2_buffer *b)
{
    if (b->flags & V4L2_BUF_FLAG_ERROR)
        return false;
    if (s->info.fourcc == V4L2_PIX_FMT_MJPEG)
        return b->bytesused > 0 && b->bytesused <= s->buf[b->index].length;
    return b->bytesused >= rte_v4l2_raw_frame_bytes(&s->info);
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
        rte_source_msgf(msg, msg_size, "%s: bad JPEG frame: %s", s->info.path,
                        tjGetErrorStr2(s->tj));
        return RTE_ERR_CORRUPT;
    }
    if (w > s->max_width || h > s->max_height) {
        rte_source_msgf(msg, msg_size, "%s: JPEG frame of %dx%d in a %dx%d stream", s->info.path, w,
                        h, s->max_width, s->max_height);
        return RTE_ERR_FORMAT;
    }
    bool bgr = s->out_format == RTE_PIXEL_BGR24;
    int pitch = w * (bgr ? 3 : 1);
    if (tjDecompress2(s->tj, jpeg, size, s->decoded, w, pitch, h, bgr ? TJPF_BGR : TJPF_GRAY,
                      TJFLAG_FASTDCT) != 0 &&
        tjGetErrorCode(s->tj) == TJERR_FATAL) {
        rte_source_msgf(msg, msg_size, "%s: bad JPEG frame: %s", s->info.path,
                        tjGetErrorStr2(s->tj));
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

/* Gives the buffer the last next() handed out back to the driver. */
static rte_status requeue_held(v4l2_source *s, char *msg, size_t msg_size)
{
    if (s->stats.state != RTE_SOURCE_STREAMING || s->held < 0)
        return RTE_OK;
    uint32_t index = (uint32_t)s->held;
    s->held = -1;
    if (queue_buffer(s, index) < 0)
        return rte_v4l2_device_lost(s, "VIDIOC_QBUF", errno, msg, msg_size);
    return RTE_OK;
}

/* Polls until the device is readable: RTE_OK, RTE_ERR_TIMEOUT once the
 * deadline (-1: none) passes, RTE_ERR_DEVICE when the device is lost. */
static rte_status wait_readable(v4l2_source *s, int64_t deadline, int32_t timeout_ms, char *msg,
                                size_t msg_size)
{
    for (;;) {
        int64_t now = s->ops->now_ns(s->ops->ctx);
        int wait_ms = -1;
        if (deadline >= 0)
            wait_ms = now >= deadline ? 0 : (int)((deadline - now + 999999) / 1000000);
        struct pollfd pfd = {s->fd, POLLIN, 0};
        int r = s->ops->poll(s->ops->ctx, &pfd, 1, wait_ms);
        if (r < 0) {
            if (errno == EINTR)
                continue;
            return rte_v4l2_device_lost(s, "poll", errno, msg, msg_size);
        }
        if (r == 0) {
            rte_source_msgf(msg, msg_size, "%s: no frame within %d ms", s->info.path, timeout_ms);
            return RTE_ERR_TIMEOUT;
        }
        if (pfd.revents & (POLLERR | POLLHUP | POLLNVAL))
            return rte_v4l2_device_lost(s, "poll", 0, msg, msg_size);
        return RTE_OK;
    }
}

/* What one round of dequeueing found. */
typedef struct dequeue_round {
    struct v4l2_buffer newest; /* the newest usable buffer, still dequeued */
    bool have_newest;
    bool bad; /* a buffer was marked bad or too short */
} dequeue_round;

/* Takes everything that is ready; keeps the newest, gives the older ones
 * straight back. */
static rte_status dequeue_newest(v4l2_source *s, dequeue_round *d, char *msg, size_t msg_size)
{
    memset(d, 0, sizeof(*d));
    for (;;) {
        struct v4l2_buffer b;
        memset(&b, 0, sizeof(b));
        b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        b.memory = V4L2_MEMORY_MMAP;
        if (rte_v4l2_xioctl(s, VIDIOC_DQBUF, &b) < 0) {
            if (errno == EAGAIN)
                return RTE_OK;
            return rte_v4l2_device_lost(s, "VIDIOC_DQBUF", errno, msg, msg_size);
        }
        if (b.index >= (uint32_t)s->n_buf)
            return rte_v4l2_device_lost(s, "VIDIOC_DQBUF", EINVAL, msg, msg_size);
        note_sequence(s, b.sequence);
        uint32_t give_back = b.index;
        if (buffer_usable(s, &b)) {
            if (!d->have_newest) {
                d->have_newest = true;
                d->newest = b;
                continue;
            }
            s->stats.skipped++;
            give_back = d->newest.index;
            d->newest = b;
        } else {
            s->stats.bad_frames++;
            d->bad = true;
        }
        if (queue_buffer(s, give_back) < 0)
            return rte_v4l2_device_lost(s, "VIDIOC_QBUF", errno, msg, msg_size);
    }
}

/* The frame in buffer b: a view of it, held until the next call, or for
 * MJPEG the image decoded from it (the buffer goes straight back). */
static rte_status frame_from_buffer(v4l2_source *s, const struct v4l2_buffer *b, rte_frame *frame,
                                    char *msg, size_t msg_size)
{
    uint8_t *data = s->buf[b->index].start;
    if (s->info.fourcc != V4L2_PIX_FMT_MJPEG) {
        frame_view(s, data, frame);
        s->held = (int32_t)b->index;
        return RTE_OK;
    }
    rte_status st = decode_mjpeg(s, data, b->bytesused, frame, msg, msg_size);
    if (queue_buffer(s, b->index) < 0)
        return rte_v4l2_device_lost(s, "VIDIOC_QBUF", errno, msg, msg_size);
    if (st != RTE_OK) {
        s->stats.bad_frames++;
        s->stats.errors++;
    }
    return st;
}

/* The driver's timestamp when it is on CLOCK_MONOTONIC and not later than
 * the dequeueing, else the time of the dequeueing. */
static int64_t capture_time(const v4l2_source *s, const struct v4l2_buffer *b)
{
    int64_t dequeued = s->ops->now_ns(s->ops->ctx);
    /* A driver may stamp a frame from its schedule rather than from the
     * clock (vivid stamps the end of the exposure, up to 0.9 frame
     * periods ahead): no frame is captured after it was dequeued. */
    if ((b->flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC) {
        int64_t stamped =
            (int64_t)b->timestamp.tv_sec * 1000000000 + (int64_t)b->timestamp.tv_usec * 1000;
        if (stamped < dequeued)
            return stamped;
    }
    return dequeued;
}

/* Hands the frame out with its time and sequence, counting the frames
 * dropped since the last one handed out. */
static void deliver(v4l2_source *s, const struct v4l2_buffer *b, const rte_frame *frame,
                    rte_source_frame *out)
{
    memset(out, 0, sizeof(*out));
    out->frame = *frame;
    out->capture_ns = capture_time(s, b);
    out->recorded_ns = out->capture_ns;
    out->sequence = b->sequence;
    out->dropped = s->have_delivered ? sequence_gap(s->last_delivered, b->sequence) : 0;
    s->have_delivered = true;
    s->last_delivered = b->sequence;
    s->stats.frames++;
}

rte_status rte_v4l2_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                         size_t msg_size)
{
    v4l2_source *s = impl;
    const int64_t start = s->ops->now_ns(s->ops->ctx);
    const int64_t deadline = timeout_ms < 0 ? -1 : start + (int64_t)timeout_ms * 1000000;
    rte_source_msgf(msg, msg_size, "%s", "");

    rte_status st = requeue_held(s, msg, msg_size);
    if (st != RTE_OK)
        return st;
    if (s->stats.state == RTE_SOURCE_RECONNECTING) {
        st = rte_v4l2_reconnect(s, deadline, msg, msg_size);
        if (st != RTE_OK)
            return st;
    }

    dequeue_round d;
    for (;;) {
        st = wait_readable(s, deadline, timeout_ms, msg, msg_size);
        if (st == RTE_OK)
            st = dequeue_newest(s, &d, msg, msg_size);
        if (st != RTE_OK)
            return st;
        if (d.have_newest)
            break;
        if (d.bad) {
            s->stats.errors++;
            rte_source_msgf(msg, msg_size, "%s: the driver marked frame %u bad (skipped)",
                            s->info.path, s->last_seq);
            return RTE_ERR_CORRUPT;
        }
        /* woken without a buffer: wait again */
    }

    rte_frame frame;
    st = frame_from_buffer(s, &d.newest, &frame, msg, msg_size);
    if (st != RTE_OK)
        return st;
    deliver(s, &d.newest, &frame, out);
    return RTE_OK;
}
