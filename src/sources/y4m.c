/* YUV4MPEG2 source (what `ffmpeg -i in.mp4 -pix_fmt gray out.y4m` or
 * `-pix_fmt yuv420p` writes): mono frames as GREY, 4:2:0 as NV12.
 *
 * Memory: open() allocates the source, its read buffer, the frame and the
 * chroma planes; next() allocates nothing. Reading uses read(2) through the
 * source's own buffer, not stdio: glibc's fseeko calls free() (on its
 * backup area), and a rewind for --loop must make no heap call. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "recorded.h"
#include "rtedge/y4m.h"

#define Y4M_LINE_MAX 1024
#define Y4M_READ_BUFFER (64 * 1024)

/* A buffered reader on a file descriptor. */
typedef struct y4m_file {
    int fd;
    uint8_t *buf;     /* Y4M_READ_BUFFER bytes */
    size_t pos, len;  /* unread bytes: buf[pos..len) */
    long long offset; /* file offset of buf[pos] */
    int error;        /* errno of a failed read, 0 */
} y4m_file;

static int fill(y4m_file *f)
{
    f->pos = f->len = 0;
    for (;;) {
        ssize_t n = read(f->fd, f->buf, Y4M_READ_BUFFER);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            f->error = errno;
        f->len = n > 0 ? (size_t)n : 0;
        return n > 0;
    }
}

static int next_byte(y4m_file *f)
{
    if (f->pos == f->len && !fill(f))
        return -1;
    f->offset++;
    return f->buf[f->pos++];
}

/* Up to n bytes into dst; the count read (short at the end or on an error). */
static size_t read_bytes(y4m_file *f, uint8_t *dst, size_t n)
{
    size_t got = 0;
    while (got < n) {
        if (f->pos == f->len && !fill(f))
            break;
        size_t k = f->len - f->pos < n - got ? f->len - f->pos : n - got;
        memcpy(dst + got, f->buf + f->pos, k);
        f->pos += k;
        f->offset += (long long)k;
        got += k;
    }
    return got;
}

static void seek_to(y4m_file *f, long long offset)
{
    lseek(f->fd, (off_t)offset, SEEK_SET);
    f->pos = f->len = 0;
    f->offset = offset;
}

typedef struct y4m_source {
    rte_recording rec; /* first: see recorded.h */
    y4m_file file;
    long long data_start; /* offset of the first FRAME */
    int32_t width, height, fps_num, fps_den;
    int mono;
    size_t y_bytes, c_bytes; /* one plane of luma, one of chroma */
    uint8_t *frame;          /* Y, then (4:2:0) interleaved UV */
    uint8_t *chroma;         /* U then V as read */
    size_t frame_size;
    char path_name[128]; /* for messages: the file name part */
} y4m_source;

/* One header line (without its '\n') into line; -1 at EOF before any
 * byte, -2 when longer than Y4M_LINE_MAX or cut by EOF. */
static int read_line(y4m_file *f, char *line)
{
    int n = 0, c;
    while ((c = next_byte(f)) >= 0 && c != '\n') {
        if (n == Y4M_LINE_MAX - 1)
            return -2;
        line[n++] = (char)c;
    }
    line[n] = '\0';
    if (c < 0)
        return n == 0 ? -1 : -2;
    return n;
}

/* The stream header (rte_y4m_parse_header), then what this source delivers:
 * mono as GREY, 4:2:0 as NV12. */
static rte_status parse_header(y4m_source *s, char *line, char *msg, size_t msg_size)
{
    rte_y4m_info info;
    char why[160];
    rte_status st = rte_y4m_parse_header(line, &info, why, sizeof why);
    if (st != RTE_OK) {
        rte_source_msgf(msg, msg_size, "%s: %s", s->path_name, why);
        return st;
    }
    if (strcmp(info.chroma, "mono") == 0) {
        s->mono = 1;
    } else if (rte_y4m_frame_format(&info) != RTE_PIXEL_NV12) {
        rte_source_msgf(msg, msg_size, "%s: colour space C%s is not supported (mono and 420 are)",
                        s->path_name, info.chroma);
        return RTE_ERR_UNSUPPORTED;
    }
    s->width = info.width;
    s->height = info.height;
    s->fps_num = info.fps_num;
    s->fps_den = info.fps_den;
    return rte_recording_check_fps(&s->fps_num, &s->fps_den, msg, msg_size);
}

static void y4m_rewind(void *impl)
{
    y4m_source *s = impl;
    seek_to(&s->file, s->data_start);
}

/* After a bad FRAME header that started at `at`: on to the next "FRAME"
 * followed by ' ' or '\n' (or to the end). */
static void skip_to_next_frame(y4m_source *s, long long at)
{
    static const char magic[] = "FRAME";
    seek_to(&s->file, at + 1);
    size_t matched = 0;
    int c;
    while ((c = next_byte(&s->file)) >= 0) {
        if (matched == 5) {
            if (c == ' ' || c == '\n') {
                seek_to(&s->file, s->file.offset - 6);
                return;
            }
            matched = 0;
        }
        if (c == magic[matched])
            matched++;
        else
            matched = c == 'F' ? 1 : 0;
    }
}

static rte_status y4m_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                           size_t msg_size)
{
    (void)timeout_ms;
    y4m_source *s = impl;
    long long at = s->file.offset;
    char line[Y4M_LINE_MAX];
    s->file.error = 0;
    int n = read_line(&s->file, line);
    if (s->file.error) {
        s->rec.stats.errors++;
        rte_source_msgf(msg, msg_size, "%s: %s", s->path_name, strerror(s->file.error));
        return RTE_ERR_IO;
    }
    if (n == -1)
        return rte_recording_end(&s->rec, msg, msg_size);
    if (n == -2 && s->file.len == 0) {
        rte_source_msgf(msg, msg_size, "%s: frame %llu: header cut short", s->path_name,
                        (unsigned long long)s->rec.index);
        return rte_recording_bad(&s->rec, RTE_ERR_TRUNCATED);
    }
    if (n < 5 || strncmp(line, "FRAME", 5) != 0 || (line[5] != ' ' && line[5] != '\0')) {
        skip_to_next_frame(s, at);
        rte_source_msgf(msg, msg_size, "%s: offset %lld: not a FRAME header, skipped to %lld",
                        s->path_name, at, s->file.offset);
        return rte_recording_bad(&s->rec, RTE_ERR_CORRUPT);
    }
    size_t got = read_bytes(&s->file, s->frame, s->y_bytes);
    if (got == s->y_bytes && !s->mono)
        got += read_bytes(&s->file, s->chroma, 2 * s->c_bytes);
    size_t want = s->y_bytes + (s->mono ? 0 : 2 * s->c_bytes);
    if (got != want) {
        int err = s->file.error;
        rte_source_msgf(msg, msg_size, "%s: frame %llu cut short: %zu of %zu bytes%s%s",
                        s->path_name, (unsigned long long)s->rec.index, got, want, err ? ": " : "",
                        err ? strerror(err) : "");
        return rte_recording_bad(&s->rec, err ? RTE_ERR_IO : RTE_ERR_TRUNCATED);
    }
    if (!s->mono) {
        /* I420 -> NV12: interleave U and V (rows of 2 * cw bytes). */
        uint8_t *uv = s->frame + s->y_bytes;
        const uint8_t *u = s->chroma, *v = s->chroma + s->c_bytes;
        for (size_t i = 0; i < s->c_bytes; i++) {
            uv[2 * i] = u[i];
            uv[2 * i + 1] = v[i];
        }
    }
    rte_frame frame;
    rte_frame_packed(&frame, s->mono ? RTE_PIXEL_GREY : RTE_PIXEL_NV12, s->width, s->height,
                     s->frame, s->frame_size);
    rte_recording_deliver(&s->rec, out, &frame,
                          rte_recording_frame_ns(s->rec.index, s->fps_num, s->fps_den));
    return RTE_OK;
}

static void y4m_close(void *impl)
{
    y4m_source *s = impl;
    if (!s)
        return;
    if (s->file.fd >= 0)
        close(s->file.fd);
    free(s->file.buf);
    free(s->frame);
    free(s->chroma);
    free(s);
}

const rte_source_ops rte_y4m_source_ops = {"y4m", y4m_next, rte_recording_get_stats, y4m_close};

rte_status rte_y4m_source_open(rte_source *source, const char *path, char *msg, size_t msg_size)
{
    if (!source || !path) {
        rte_source_msgf(msg, msg_size, "y4m: missing argument");
        return RTE_ERR_ARGUMENT;
    }
    memset(source, 0, sizeof *source);
    y4m_source *s = calloc(1, sizeof *s);
    if (!s) {
        rte_source_msgf(msg, msg_size, "y4m: no memory");
        return RTE_ERR_NO_MEMORY;
    }
    const char *slash = strrchr(path, '/');
    snprintf(s->path_name, sizeof s->path_name, "%s", slash ? slash + 1 : path);
    rte_status st = RTE_OK;
    s->file.fd = open(path, O_RDONLY | O_CLOEXEC);
    s->file.buf = malloc(Y4M_READ_BUFFER);
    if (s->file.fd < 0) {
        rte_source_msgf(msg, msg_size, "%s: %s", path, strerror(errno));
        st = RTE_ERR_IO;
    } else if (!s->file.buf) {
        st = RTE_ERR_NO_MEMORY;
    } else {
        char line[Y4M_LINE_MAX];
        if (read_line(&s->file, line) < 0) {
            rte_source_msgf(msg, msg_size, "%s: no YUV4MPEG2 header", s->path_name);
            st = RTE_ERR_FORMAT;
        } else {
            st = parse_header(s, line, msg, msg_size);
        }
    }
    if (st == RTE_OK) {
        s->data_start = s->file.offset;
        s->y_bytes = (size_t)s->width * (size_t)s->height;
        s->c_bytes = s->mono ? 0 : (size_t)((s->width + 1) / 2) * (size_t)((s->height + 1) / 2);
        s->frame_size =
            rte_frame_packed_size(s->mono ? RTE_PIXEL_GREY : RTE_PIXEL_NV12, s->width, s->height);
        s->frame = malloc(s->frame_size);
        s->chroma = malloc(s->c_bytes ? 2 * s->c_bytes : 1);
        if (!s->frame || !s->chroma)
            st = RTE_ERR_NO_MEMORY;
    }
    if (st == RTE_ERR_NO_MEMORY)
        rte_source_msgf(msg, msg_size, "%s: no memory for the frame", s->path_name);
    if (st != RTE_OK) {
        y4m_close(s);
        return st;
    }
    rte_recording_init(&s->rec, rte_recording_frame_ns(1, s->fps_num, s->fps_den), y4m_rewind);
    rte_recording_attach(source, &rte_y4m_source_ops, s, s->width, s->height,
                         s->mono ? RTE_PIXEL_GREY : RTE_PIXEL_NV12);
    rte_source_msgf(msg, msg_size, "%s: %dx%d %s at %d/%d fps", s->path_name, s->width, s->height,
                    s->mono ? "mono" : "4:2:0", s->fps_num, s->fps_den);
    return RTE_OK;
}
