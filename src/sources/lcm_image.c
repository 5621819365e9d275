/* image_t sources: an LCM log (read with rtedge's allocation-free reader,
 * src/publish/lcm_log.c) and a live LCM channel (lcm_handle_timeout).
 * Both decode image_t by hand into a frame that views the message buffer:
 * lcm-gen's _decode would allocate the pixel array for every message.
 *
 * Memory: open() allocates the source and one message buffer; next()
 * allocates nothing of rtedge's own. */
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "lcm_log.h"
#include "lcm_wire.h"
#include "recorded.h"
#include "rtedge_image_t.h"

/* hash, utime, width, height, row_stride, pixelformat, size */
#define IMAGE_FIXED_BYTES (8 + 8 + 5 * 4)
/* Room for metadata and row padding beyond the packed pixels. */
#define IMAGE_SLACK_BYTES (256 * 1024)

static rte_pixel_format format_of(int32_t pixelformat)
{
    switch (pixelformat) {
    case RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY: return RTE_PIXEL_GREY;
    case RTEDGE_IMAGE_T_PIXEL_FORMAT_BGR: return RTE_PIXEL_BGR24;
    case RTEDGE_IMAGE_T_PIXEL_FORMAT_RGB: return RTE_PIXEL_RGB24;
    case RTEDGE_IMAGE_T_PIXEL_FORMAT_YUYV: return RTE_PIXEL_YUYV;
    case RTEDGE_IMAGE_T_PIXEL_FORMAT_UYVY: return RTE_PIXEL_UYVY;
    case RTEDGE_IMAGE_T_PIXEL_FORMAT_NV12: return RTE_PIXEL_NV12;
    default: return (rte_pixel_format)0;
    }
}

static int32_t row_bytes(rte_pixel_format f, int32_t width)
{
    switch (f) {
    case RTE_PIXEL_BGR24:
    case RTE_PIXEL_RGB24: return 3 * width;
    case RTE_PIXEL_YUYV:
    case RTE_PIXEL_UYVY: return 2 * width;
    default: return width; /* GREY, NV12's Y plane */
    }
}

/* Is this an image_t (by fingerprint)? */
static bool is_image(const uint8_t *data, int32_t size)
{
    return size >= 8 && (int64_t)rte_lcm_get_u64(data) == __rtedge_image_t_get_hash();
}

/* An image_t's fields before its pixels. */
typedef struct image_header {
    int64_t utime;
    rte_pixel_format format;
    int32_t width, height, stride;
} image_header;

/* Decodes and checks an image_t's header: of a message of `size` bytes, only
 * the first IMAGE_FIXED_BYTES are read. want: the required format (0: any). */
static rte_status decode_header(const uint8_t *data, int32_t size, rte_pixel_format want,
                                int32_t max_w, int32_t max_h, image_header *hd, char *msg,
                                size_t msg_size)
{
    if (!is_image(data, size)) {
        rte_source_msgf(msg, msg_size, "not an image_t (fingerprint)");
        return RTE_ERR_FORMAT;
    }
    if (size < IMAGE_FIXED_BYTES) {
        rte_source_msgf(msg, msg_size, "image_t of %d bytes: cut short", size);
        return RTE_ERR_TRUNCATED;
    }
    hd->utime = (int64_t)rte_lcm_get_u64(data + 8);
    if (hd->utime < 0 || hd->utime > RTE_RECORDED_MAX_UTIME) {
        rte_source_msgf(msg, msg_size, "image_t utime %lld is outside 0..2^52 microseconds",
                        (long long)hd->utime);
        return RTE_ERR_CORRUPT;
    }
    int32_t w = (int32_t)rte_lcm_get_u32(data + 16), h = (int32_t)rte_lcm_get_u32(data + 20);
    int32_t stride = (int32_t)rte_lcm_get_u32(data + 24);
    int32_t pixelformat = (int32_t)rte_lcm_get_u32(data + 28);
    int32_t bytes = (int32_t)rte_lcm_get_u32(data + 32);
    rte_pixel_format f = format_of(pixelformat);
    if (f == 0) {
        rte_source_msgf(msg, msg_size, "image_t pixel format %d is not supported", pixelformat);
        return RTE_ERR_UNSUPPORTED;
    }
    if (want != 0 && f != want) {
        rte_source_msgf(msg, msg_size, "image_t in %s, the source delivers %s",
                        rte_pixel_format_name(f), rte_pixel_format_name(want));
        return RTE_ERR_FORMAT;
    }
    if (w < 1 || h < 1 || w > max_w || h > max_h) {
        rte_source_msgf(msg, msg_size, "image_t of %dx%d, at most %dx%d", w, h, max_w, max_h);
        return RTE_ERR_TOO_LARGE;
    }
    if (stride <= 0)
        stride = f == RTE_PIXEL_NV12 ? w + (w & 1) : row_bytes(f, w);
    /* Bytes the pixels need: the last row need not be padded. */
    int64_t need = (int64_t)stride * (h - 1) + row_bytes(f, w);
    if (f == RTE_PIXEL_NV12)
        need = (int64_t)stride * h + (int64_t)stride * ((h + 1) / 2 - 1) + (w + 1) / 2 * 2;
    if (stride < row_bytes(f, w) || bytes < 0 || need > bytes ||
        (int64_t)IMAGE_FIXED_BYTES + bytes > size) {
        rte_source_msgf(msg, msg_size,
                        "image_t %dx%d, stride %d, %d data bytes in a %d-byte "
                        "message: inconsistent",
                        w, h, stride, bytes, size);
        return RTE_ERR_CORRUPT;
    }
    *hd = (image_header){hd->utime, f, w, h, stride};
    return RTE_OK;
}

/* Decodes a whole image_t and makes *frame a view of its pixels. */
static rte_status decode_image(const uint8_t *data, int32_t size, rte_pixel_format want,
                               int32_t max_w, int32_t max_h, rte_frame *frame, int64_t *utime,
                               char *msg, size_t msg_size)
{
    image_header hd;
    rte_status st = decode_header(data, size, want, max_w, max_h, &hd, msg, msg_size);
    if (st != RTE_OK)
        return st;
    *utime = hd.utime;
    uint8_t *pixels = (uint8_t *)(uintptr_t)(data + IMAGE_FIXED_BYTES);
    *frame = (rte_frame){hd.format, hd.width, hd.height, {pixels, NULL}, {hd.stride, 0}};
    if (hd.format == RTE_PIXEL_NV12) {
        frame->plane[1] = pixels + (size_t)hd.stride * (size_t)hd.height;
        frame->stride[1] = hd.stride;
    }
    st = rte_frame_check(frame);
    if (st != RTE_OK)
        rte_source_msgf(msg, msg_size, "image_t %dx%d: %s", hd.width, hd.height,
                        rte_status_message(st));
    return st;
}

/* The message buffer for frames up to max_w x max_h of format f. */
static size_t message_capacity(rte_pixel_format f, int32_t max_w, int32_t max_h)
{
    return IMAGE_FIXED_BYTES + rte_frame_packed_size(f, max_w, max_h) + IMAGE_SLACK_BYTES;
}

/* ---- log ---- */

typedef struct lcm_log_source {
    rte_recording rec; /* first: see recorded.h */
    rte_lcm_log_reader reader;
    char channel[RTE_LCM_LOG_MAX_CHANNEL + 1]; /* "" for any */
    rte_pixel_format format;
    int32_t max_w, max_h;
} lcm_log_source;

static void lcm_log_rewind(void *impl)
{
    lcm_log_source *s = impl;
    s->reader.offset = 0;
}

static rte_status lcm_log_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                               size_t msg_size)
{
    (void)timeout_ms;
    lcm_log_source *s = impl;
    for (;;) {
        rte_lcm_log_event ev;
        rte_status st = rte_lcm_log_read(&s->reader, &ev, msg, msg_size);
        if (st == RTE_ERR_END)
            return rte_recording_end(&s->rec, msg, msg_size);
        if (st == RTE_ERR_IO) {
            s->rec.stats.errors++;
            return st;
        }
        if (st != RTE_OK)
            return rte_recording_bad(&s->rec, st);
        if (s->channel[0] ? strcmp(ev.channel, s->channel) != 0 : !is_image(ev.data, ev.size))
            continue; /* other traffic in the log */
        rte_frame frame;
        int64_t utime;
        st = decode_image(ev.data, ev.size, s->format, s->max_w, s->max_h, &frame, &utime, msg,
                          msg_size);
        if (st != RTE_OK)
            return rte_recording_bad(&s->rec, st);
        rte_recording_deliver(&s->rec, out, &frame, utime * 1000);
        return RTE_OK;
    }
}

static void lcm_log_close(void *impl)
{
    lcm_log_source *s = impl;
    if (!s)
        return;
    rte_lcm_log_reader_close(&s->reader);
    free(s);
}

const rte_source_ops rte_lcm_log_source_ops = {"lcm-log", lcm_log_next, rte_recording_get_stats,
                                               lcm_log_close};

static const char *log_path(const char *url)
{
    return strncmp(url, "file://", 7) == 0 ? url + 7 : url;
}

/* The format and size of the log's first decodable image_t on the channel. */
static rte_status peek_first_image(const char *path, const char *channel, rte_pixel_format *f,
                                   int32_t *w, int32_t *h, char *msg, size_t msg_size)
{
    /* Only each event's first bytes: the image_t header decides. */
    rte_lcm_log_reader r;
    rte_status st = rte_lcm_log_reader_open(&r, path, IMAGE_FIXED_BYTES, msg, msg_size);
    if (st != RTE_OK)
        return st;
    for (;;) {
        rte_lcm_log_event ev;
        st = rte_lcm_log_read_head(&r, &ev, msg, msg_size);
        if (st == RTE_ERR_END || st == RTE_ERR_IO)
            break;
        if (st != RTE_OK || (channel[0] && strcmp(ev.channel, channel) != 0))
            continue;
        image_header hd;
        if (decode_header(ev.data, ev.size, *f, RTE_MAX_SIDE, RTE_MAX_SIDE, &hd, NULL, 0) ==
            RTE_OK) {
            *f = hd.format;
            *w = hd.width;
            *h = hd.height;
            break;
        }
    }
    rte_lcm_log_reader_close(&r);
    if (st == RTE_OK)
        return RTE_OK;
    if (st == RTE_ERR_END)
        rte_source_msgf(msg, msg_size, "%s: no image_t%s%s in the log", path,
                        channel[0] ? " on " : "", channel);
    return st == RTE_ERR_END ? RTE_ERR_FORMAT : st;
}

static rte_status check_config(const rte_lcm_source_config *c, int live, char *msg, size_t msg_size)
{
    if (!c || !c->url || (live && !c->channel)) {
        rte_source_msgf(msg, msg_size, "lcm: missing url%s", live ? " or channel" : "");
        return RTE_ERR_ARGUMENT;
    }
    if (c->channel && strlen(c->channel) > RTE_LCM_LOG_MAX_CHANNEL) {
        rte_source_msgf(msg, msg_size, "lcm: channel name over %d bytes", RTE_LCM_LOG_MAX_CHANNEL);
        return RTE_ERR_ARGUMENT;
    }
    int sized = c->max_width > 0 && c->max_height > 0 && c->format != 0;
    int unsized = c->max_width == 0 && c->max_height == 0;
    if ((live && !sized) || !(sized || unsized) ||
        (sized && rte_frame_packed_size(c->format, c->max_width, c->max_height) == 0)) {
        rte_source_msgf(msg, msg_size, "lcm: bad format or maximum size (%s %dx%d)",
                        rte_pixel_format_name(c->format), c->max_width, c->max_height);
        return RTE_ERR_ARGUMENT;
    }
    return RTE_OK;
}

/* Checks the configuration and allocates a zeroed impl of `size` bytes;
 * NULL with *st set when either fails. */
static void *open_impl(rte_source *source, const rte_lcm_source_config *config, int live,
                       size_t size, rte_status *st, char *msg, size_t msg_size)
{
    *st = RTE_ERR_ARGUMENT;
    if (!source)
        return NULL;
    memset(source, 0, sizeof *source);
    *st = check_config(config, live, msg, msg_size);
    if (*st != RTE_OK)
        return NULL;
    void *impl = calloc(1, size);
    if (!impl) {
        rte_source_msgf(msg, msg_size, "%s: no memory", config->url);
        *st = RTE_ERR_NO_MEMORY;
    }
    return impl;
}

rte_status rte_lcm_log_source_open(rte_source *source, const rte_lcm_source_config *config,
                                   char *msg, size_t msg_size)
{
    rte_status st;
    lcm_log_source *s = open_impl(source, config, 0, sizeof *s, &st, msg, msg_size);
    if (!s)
        return st;
    s->reader.fd = -1;
    snprintf(s->channel, sizeof s->channel, "%s", config->channel ? config->channel : "");
    s->format = config->format;
    s->max_w = config->max_width;
    s->max_h = config->max_height;
    const char *path = log_path(config->url);
    if (s->max_w == 0)
        st = peek_first_image(path, s->channel, &s->format, &s->max_w, &s->max_h, msg, msg_size);
    if (st == RTE_OK)
        st = rte_lcm_log_reader_open(
            &s->reader, path, message_capacity(s->format, s->max_w, s->max_h), msg, msg_size);
    if (st != RTE_OK) {
        lcm_log_close(s);
        return st;
    }
    /* Frame interval after a rewind: unknown in general, 1/30 s. */
    rte_recording_init(&s->rec, rte_recording_frame_ns(1, RTE_RECORDED_DEFAULT_FPS, 1),
                       lcm_log_rewind);
    rte_recording_attach(source, &rte_lcm_log_source_ops, s, s->max_w, s->max_h, s->format);
    rte_source_msgf(msg, msg_size, "%s: image_t %s up to %dx%d", path,
                    rte_pixel_format_name(s->format), s->max_w, s->max_h);
    return RTE_OK;
}

/* ---- live ---- */

typedef struct lcm_live_source {
    rte_recording rec; /* first: see recorded.h */
    lcm_t *lcm;
    lcm_subscription_t *sub;
    rte_pixel_format format;
    int32_t max_w, max_h;
    uint8_t *buf; /* the newest message */
    size_t capacity;
    int32_t size;      /* of the message in buf; -1: it did not fit */
    int pending;       /* buf holds a message not handed out yet */
    uint32_t replaced; /* messages replaced by newer ones since the last frame */
} lcm_live_source;

static void on_image(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    lcm_live_source *s = user;
    if (s->pending) {
        s->rec.stats.skipped++; /* a newer one replaces it */
        s->replaced++;
    }
    s->pending = 1;
    if (rbuf->data_size > s->capacity) {
        s->size = -1;
        return;
    }
    memcpy(s->buf, rbuf->data, rbuf->data_size);
    s->size = (int32_t)rbuf->data_size;
}

static rte_status lcm_live_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                                size_t msg_size)
{
    lcm_live_source *s = impl;
    if (!s->pending) {
        int r = timeout_ms < 0 ? lcm_handle(s->lcm) : lcm_handle_timeout(s->lcm, timeout_ms);
        if (r < 0) {
            s->rec.stats.errors++;
            rte_source_msgf(msg, msg_size, "lcm: handling failed");
            return RTE_ERR_IO;
        }
    }
    /* Newest first: take whatever else has arrived meanwhile. */
    while (s->pending && lcm_handle_timeout(s->lcm, 0) > 0)
        ;
    if (!s->pending) {
        rte_source_msgf(msg, msg_size, "no image within %d ms", timeout_ms);
        return RTE_ERR_TIMEOUT;
    }
    s->pending = 0;
    if (s->size < 0) {
        rte_source_msgf(msg, msg_size, "image_t message over %zu bytes", s->capacity);
        return rte_recording_bad(&s->rec, RTE_ERR_TOO_LARGE);
    }
    rte_frame frame;
    int64_t utime;
    rte_status st =
        decode_image(s->buf, s->size, s->format, s->max_w, s->max_h, &frame, &utime, msg, msg_size);
    if (st != RTE_OK)
        return rte_recording_bad(&s->rec, st);
    rte_recording_deliver(&s->rec, out, &frame, utime * 1000);
    out->dropped = s->replaced;
    s->replaced = 0;
    return RTE_OK;
}

static void lcm_live_close(void *impl)
{
    lcm_live_source *s = impl;
    if (!s)
        return;
    if (s->lcm) {
        if (s->sub)
            lcm_unsubscribe(s->lcm, s->sub);
        lcm_destroy(s->lcm);
    }
    free(s->buf);
    free(s);
}

static const rte_source_ops lcm_live_source_ops = {"lcm", lcm_live_next, rte_recording_get_stats,
                                                   lcm_live_close};

rte_status rte_lcm_live_source_open(rte_source *source, const rte_lcm_source_config *config,
                                    char *msg, size_t msg_size)
{
    rte_status st;
    lcm_live_source *s = open_impl(source, config, 1, sizeof *s, &st, msg, msg_size);
    if (!s)
        return st;
    rte_recording_init(&s->rec, 0, NULL);
    s->format = config->format;
    s->max_w = config->max_width;
    s->max_h = config->max_height;
    s->capacity = message_capacity(s->format, s->max_w, s->max_h);
    s->buf = malloc(s->capacity);
    s->lcm = s->buf ? lcm_create(config->url) : NULL;
    if (s->lcm)
        s->sub = lcm_subscribe(s->lcm, config->channel, on_image, s);
    if (!s->sub) {
        rte_source_msgf(msg, msg_size, "%s: %s", config->url,
                        !s->buf   ? "no memory"
                        : !s->lcm ? "liblcm cannot open it"
                                  : "cannot subscribe");
        st = !s->buf ? RTE_ERR_NO_MEMORY : RTE_ERR_IO;
        lcm_live_close(s);
        return st;
    }
    rte_recording_attach(source, &lcm_live_source_ops, s, s->max_w, s->max_h, s->format);
    rte_source_msgf(msg, msg_size, "%s channel %s: image_t %s up to %dx%d", config->url,
                    config->channel, rte_pixel_format_name(s->format), s->max_w, s->max_h);
    return RTE_OK;
}
