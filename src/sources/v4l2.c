/* V4L2 capture source: the real syscalls, the helpers every part of the
 * source uses, and its life: open (the configuration checked, the device
 * set up, the MJPEG decoder allocated) and close. v4l2_internal.h lists
 * the other files: negotiation, controls, streaming, reconnection, listing.
 *
 * Memory: open() allocates the source and, for MJPEG, the decode buffer;
 * next() and the reconnection allocate nothing (the mmap buffers belong to
 * the kernel and must fit the open-time sizes when the device returns). */
#include "sources/v4l2_internal.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include "core/clock.h"
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
    return rte_clock_now_ns();
}

const rte_v4l2_ops rte_v4l2_system_ops = {
    sys_open, sys_close, sys_ioctl, sys_poll, sys_mmap, sys_munmap, sys_now_ns, NULL,
};

/* ---- helpers ---- */

void rte_v4l2_copy_string(char *dst, size_t size, const void *src, size_t src_size)
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
bool rte_v4l2_names_equal(const char *a, const char *b)
{
    while (*a && !isalnum((unsigned char)*a))
        a++;
    while (*b && !isalnum((unsigned char)*b))
        b++;
    for (;;) {
        if (!*a || !*b)
            return !*a && !*b;
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return false;
        a++;
        b++;
        bool sep_a = false, sep_b = false;
        while (*a && !isalnum((unsigned char)*a)) {
            a++;
            sep_a = true;
        }
        while (*b && !isalnum((unsigned char)*b)) {
            b++;
            sep_b = true;
        }
        /* A separator inside one name must be matched by one in the other. */
        if (sep_a != sep_b && *a && *b)
            return false;
    }
}

int rte_v4l2_xioctl(v4l2_source *s, unsigned long request, void *arg)
{
    int r;
    do
        r = s->ops->ioctl(s->ops->ctx, s->fd, request, arg);
    while (r < 0 && errno == EINTR);
    return r;
}

void rte_v4l2_close_fd(v4l2_source *s)
{
    if (s->fd >= 0)
        s->ops->close(s->ops->ctx, s->fd);
    s->fd = -1;
}

/* ---- the source ---- */

#define DEFAULT_BUFFERS 4
#define DEFAULT_RECONNECT_MIN_MS 100
#define DEFAULT_RECONNECT_MAX_MS 2000
#define WAIT_MIN_MS 500
#define WAIT_MAX_MS 8000

static void describe(const v4l2_source *s, char *msg, size_t msg_size)
{
    char adjustments[RTE_SOURCE_MESSAGE_SIZE], name[5];
    rte_v4l2_copy_string(adjustments, sizeof(adjustments), msg ? msg : "", msg ? msg_size : 1);
    const rte_v4l2_info *i = &s->info;
    rte_source_msgf(msg, msg_size, "%s (%s, %s): %s %dx%d, %u/%u s per frame, %d buffers%s",
                    i->path, i->card, i->bus_info, rte_v4l2_fourcc_name(i->fourcc, name), i->width,
                    i->height, i->interval_num, i->interval_den, i->buffers, adjustments);
}

static void v4l2_get_stats(const void *impl, rte_source_stats *stats)
{
    *stats = ((const v4l2_source *)impl)->stats;
}

static void v4l2_close(void *impl)
{
    v4l2_source *s = impl;
    rte_v4l2_stop_device(s);
    if (s->tj)
        tjDestroy(s->tj);
    free(s->decoded);
    free(s);
}

const rte_source_ops rte_v4l2_source_ops = {"v4l2", rte_v4l2_next, v4l2_get_stats, v4l2_close};

/* The driver's timestamp type is only known from a dequeued buffer's
 * flags; QUERYBUF returns them too, so look at buffer 0 after streaming
 * started. */
void rte_v4l2_check_timestamps(v4l2_source *s)
{
    struct v4l2_buffer b;
    memset(&b, 0, sizeof(b));
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = 0;
    s->info.timestamps_monotonic =
        rte_v4l2_xioctl(s, VIDIOC_QUERYBUF, &b) == 0 &&
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
    if (rte_v4l2_delivered_format(fourcc, decode_to) == 0 ||
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
    rte_v4l2_copy_string(s->info.path, sizeof(s->info.path), s->device, sizeof(s->device));

    rte_status st = rte_v4l2_setup_device(s, false, msg, msg_size);
    bool waiting = st == RTE_ERR_DEVICE && config->wait;
    if (st == RTE_OK) {
        s->streamed = true;
        s->open_fourcc = s->info.fourcc;
        s->max_width = s->info.width;
        s->max_height = s->info.height;
        rte_v4l2_check_timestamps(s);
    } else if (waiting) {
        /* sized for what was asked: the device must come with that */
        rte_v4l2_wait_for_device(s, WAIT_MIN_MS, WAIT_MAX_MS);
        s->info.fourcc = s->open_fourcc = fourcc;
        s->info.width = s->max_width = config->width;
        s->info.height = s->max_height = config->height;
        st = RTE_OK;
    }
    if (st == RTE_OK) {
        s->out_format = rte_v4l2_delivered_format(s->open_fourcc, decode_to);
        if (s->open_fourcc == V4L2_PIX_FMT_MJPEG) {
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
    if (waiting) {
        char name[5];
        rte_source_msg_append(msg, msg_size, "; waiting for it (sized for %s %dx%d)",
                              rte_v4l2_fourcc_name(fourcc, name), s->max_width, s->max_height);
    } else {
        describe(s, msg, msg_size);
    }
    if (info)
        *info = s->info;
    source->ops = &rte_v4l2_source_ops;
    source->impl = s;
    source->max_width = s->max_width;
    source->max_height = s->max_height;
    source->format = s->out_format;
    return RTE_OK;
}
