/* Raw frame dumps (`v4l2-ctl --stream-to=FILE`): tightly packed frames of a
 * given format and size, one after another.
 *
 * Memory: open() allocates the source and one frame; next() nothing. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "recorded.h"

typedef struct raw_source {
    rte_recording rec; /* first: see recorded.h */
    int fd;
    rte_pixel_format format;
    int32_t width, height, fps_num, fps_den;
    size_t frame_size;
    uint8_t *frame;
} raw_source;

static void raw_rewind(void *impl)
{
    raw_source *s = impl;
    lseek(s->fd, 0, SEEK_SET);
}

static rte_status raw_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                           size_t msg_size)
{
    (void)timeout_ms;
    raw_source *s = impl;
    size_t got = 0;
    while (got < s->frame_size) {
        ssize_t n = read(s->fd, s->frame + got, s->frame_size - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            rte_source_msgf(msg, msg_size, "raw frame %llu: %s", (unsigned long long)s->rec.index,
                            strerror(errno));
            s->rec.stats.errors++;
            return RTE_ERR_IO;
        }
        if (n == 0)
            break;
        got += (size_t)n;
    }
    if (got == 0)
        return rte_recording_end(&s->rec, msg, msg_size);
    if (got < s->frame_size) {
        rte_source_msgf(msg, msg_size, "raw frame %llu cut short: %zu of %zu bytes",
                        (unsigned long long)s->rec.index, got, s->frame_size);
        return rte_recording_bad(&s->rec, RTE_ERR_TRUNCATED);
    }
    rte_frame frame;
    rte_frame_packed(&frame, s->format, s->width, s->height, s->frame, s->frame_size);
    rte_recording_deliver(&s->rec, out, &frame,
                          rte_recording_frame_ns(s->rec.index, s->fps_num, s->fps_den));
    return RTE_OK;
}

static void raw_close(void *impl)
{
    raw_source *s = impl;
    if (!s)
        return;
    if (s->fd >= 0)
        close(s->fd);
    free(s->frame);
    free(s);
}

const rte_source_ops rte_raw_source_ops = {"raw", raw_next, rte_recording_get_stats, raw_close};

rte_status rte_raw_source_open(rte_source *source, const rte_raw_source_config *config, char *msg,
                               size_t msg_size)
{
    if (!source || !config || !config->path) {
        rte_source_msgf(msg, msg_size, "raw: missing argument");
        return RTE_ERR_ARGUMENT;
    }
    memset(source, 0, sizeof *source);
    size_t frame_size = rte_frame_packed_size(config->format, config->width, config->height);
    if (frame_size == 0) {
        rte_source_msgf(msg, msg_size, "raw: bad format or size %s %dx%d",
                        rte_pixel_format_name(config->format), config->width, config->height);
        return RTE_ERR_ARGUMENT;
    }
    int32_t fps_num = config->fps_num, fps_den = config->fps_den;
    rte_status st = rte_recording_check_fps(&fps_num, &fps_den, msg, msg_size);
    if (st != RTE_OK)
        return st;
    raw_source *s = calloc(1, sizeof *s);
    if (!s) {
        rte_source_msgf(msg, msg_size, "raw: no memory");
        return RTE_ERR_NO_MEMORY;
    }
    rte_recording_init(&s->rec, rte_recording_frame_ns(1, fps_num, fps_den), raw_rewind);
    s->format = config->format;
    s->width = config->width;
    s->height = config->height;
    s->fps_num = fps_num;
    s->fps_den = fps_den;
    s->frame_size = frame_size;
    s->frame = malloc(frame_size);
    s->fd = open(config->path, O_RDONLY | O_CLOEXEC);
    if (s->fd < 0 || !s->frame) {
        if (s->fd < 0)
            rte_source_msgf(msg, msg_size, "%s: %s", config->path, strerror(errno));
        else
            rte_source_msgf(msg, msg_size, "raw: no memory for a frame");
        st = s->fd < 0 ? RTE_ERR_IO : RTE_ERR_NO_MEMORY;
        raw_close(s);
        return st;
    }
    rte_recording_attach(source, &rte_raw_source_ops, s, config->width, config->height,
                         config->format);
    rte_source_msgf(msg, msg_size, "%s: %s %dx%d, %zu bytes a frame", config->path,
                    rte_pixel_format_name(config->format), config->width, config->height,
                    frame_size);
    return RTE_OK;
}
