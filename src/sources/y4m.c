/* YUV4MPEG2 source (what `ffmpeg -i in.mp4 -pix_fmt gray out.y4m` or
 * `-pix_fmt yuv420p` writes): mono frames as GREY, 4:2:0 as NV12.
 *
 * Memory: open() allocates the source, its stdio buffer, the frame and the
 * chroma planes; next() allocates nothing. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "recorded.h"

#define Y4M_LINE_MAX 1024
#define Y4M_STDIO_BUFFER (64 * 1024)

typedef struct y4m_source {
    rte_recording rec; /* first: see recorded.h */
    FILE *file;
    char *stdio_buf;
    long long data_start;       /* offset of the first FRAME */
    int32_t width, height, fps_num, fps_den;
    int mono;
    size_t y_bytes, c_bytes;    /* one plane of luma, one of chroma */
    uint8_t *frame;             /* Y, then (4:2:0) interleaved UV */
    uint8_t *chroma;            /* U then V as read */
    size_t frame_size;
    char path_name[128];        /* for messages: the file name part */
} y4m_source;

/* One header line (without its '\n') into line; -1 at EOF before any
 * byte, -2 when longer than Y4M_LINE_MAX or cut by EOF. */
static int read_line(FILE *f, char *line)
{
    int n = 0, c;
    while ((c = getc(f)) != EOF && c != '\n') {
        if (n == Y4M_LINE_MAX - 1)
            return -2;
        line[n++] = (char)c;
    }
    line[n] = '\0';
    if (c == EOF)
        return n == 0 ? -1 : -2;
    return n;
}

/* Parses the stream header's tags. */
static rte_status parse_header(y4m_source *s, char *line, char *msg, size_t msg_size)
{
    if (strncmp(line, "YUV4MPEG2", 9) != 0 || (line[9] != ' ' && line[9] != '\0')) {
        rte_source_msgf(msg, msg_size, "%s: not a YUV4MPEG2 file", s->path_name);
        return RTE_ERR_FORMAT;
    }
    const char *colour = "420jpeg";
    char *save = NULL;
    for (char *tok = strtok_r(line + 9, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        char *end = NULL;
        switch (tok[0]) {
        case 'W':
            s->width = (int32_t)strtol(tok + 1, &end, 10);
            break;
        case 'H':
            s->height = (int32_t)strtol(tok + 1, &end, 10);
            break;
        case 'F':
            s->fps_num = (int32_t)strtol(tok + 1, &end, 10);
            if (*end == ':')
                s->fps_den = (int32_t)strtol(end + 1, &end, 10);
            break;
        case 'I':
            if (tok[1] != 'p' && tok[1] != '?') {
                rte_source_msgf(msg, msg_size, "%s: interlaced (%s) is not supported",
                                s->path_name, tok);
                return RTE_ERR_UNSUPPORTED;
            }
            break;
        case 'C':
            colour = tok + 1;
            break;
        default: /* A (aspect), X (extensions): nothing to do */
            break;
        }
        if (end && *end != '\0') {
            rte_source_msgf(msg, msg_size, "%s: bad header tag %s", s->path_name, tok);
            return RTE_ERR_FORMAT;
        }
    }
    if (strcmp(colour, "mono") == 0)
        s->mono = 1;
    else if (strncmp(colour, "420", 3) != 0 ||
             !(colour[3] == '\0' || strcmp(colour + 3, "jpeg") == 0 ||
               strcmp(colour + 3, "paldv") == 0 || strcmp(colour + 3, "mpeg2") == 0)) {
        rte_source_msgf(msg, msg_size, "%s: colour space C%s is not supported (mono and 420 are)",
                        s->path_name, colour);
        return RTE_ERR_UNSUPPORTED;
    }
    if (s->width < 1 || s->height < 1 || s->width > RTE_MAX_SIDE || s->height > RTE_MAX_SIDE) {
        rte_source_msgf(msg, msg_size, "%s: bad size %dx%d", s->path_name, s->width, s->height);
        return RTE_ERR_FORMAT;
    }
    if (s->fps_num == 0 && s->fps_den == 0) {
        s->fps_num = RTE_RECORDED_DEFAULT_FPS;
        s->fps_den = 1;
    }
    return rte_recording_check_fps(&s->fps_num, &s->fps_den, msg, msg_size);
}

static void y4m_rewind(void *impl)
{
    y4m_source *s = impl;
    fseeko(s->file, (off_t)s->data_start, SEEK_SET);
}

/* After a bad FRAME header that started at `at`: on to the next "FRAME"
 * followed by ' ' or '\n' (or to the end). */
static void skip_to_next_frame(y4m_source *s, long long at)
{
    static const char magic[] = "FRAME";
    fseeko(s->file, (off_t)(at + 1), SEEK_SET);
    long long pos = at + 1;
    size_t matched = 0;
    int c;
    while ((c = getc(s->file)) != EOF) {
        pos++;
        if (matched == 5) {
            if (c == ' ' || c == '\n') {
                fseeko(s->file, (off_t)(pos - 6), SEEK_SET);
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
    long long at = (long long)ftello(s->file);
    char line[Y4M_LINE_MAX];
    int n = read_line(s->file, line);
    if (n == -1)
        return rte_recording_end(&s->rec, msg, msg_size);
    if (n < 0 && feof(s->file)) {
        rte_source_msgf(msg, msg_size, "%s: frame %llu: header cut short", s->path_name,
                        (unsigned long long)s->rec.index);
        return rte_recording_bad(&s->rec, RTE_ERR_TRUNCATED);
    }
    if (n < 5 || strncmp(line, "FRAME", 5) != 0 || (line[5] != ' ' && line[5] != '\0')) {
        skip_to_next_frame(s, at);
        rte_source_msgf(msg, msg_size, "%s: offset %lld: not a FRAME header, skipped to %lld",
                        s->path_name, at, (long long)ftello(s->file));
        return rte_recording_bad(&s->rec, RTE_ERR_CORRUPT);
    }
    size_t got = fread(s->frame, 1, s->y_bytes, s->file);
    if (got == s->y_bytes && !s->mono)
        got += fread(s->chroma, 1, 2 * s->c_bytes, s->file);
    size_t want = s->y_bytes + (s->mono ? 0 : 2 * s->c_bytes);
    if (got != want) {
        rte_source_msgf(msg, msg_size, "%s: frame %llu cut short: %zu of %zu bytes%s%s",
                        s->path_name, (unsigned long long)s->rec.index, got, want,
                        ferror(s->file) ? ": " : "", ferror(s->file) ? strerror(errno) : "");
        return rte_recording_bad(&s->rec, ferror(s->file) ? RTE_ERR_IO : RTE_ERR_TRUNCATED);
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
    if (s->file)
        fclose(s->file);
    free(s->stdio_buf);
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
    s->file = fopen(path, "rb");
    s->stdio_buf = malloc(Y4M_STDIO_BUFFER);
    if (!s->file) {
        rte_source_msgf(msg, msg_size, "%s: %s", path, strerror(errno));
        st = RTE_ERR_IO;
    } else if (!s->stdio_buf) {
        st = RTE_ERR_NO_MEMORY;
    } else {
        setvbuf(s->file, s->stdio_buf, _IOFBF, Y4M_STDIO_BUFFER);
        char line[Y4M_LINE_MAX];
        if (read_line(s->file, line) < 0) {
            rte_source_msgf(msg, msg_size, "%s: no YUV4MPEG2 header", s->path_name);
            st = RTE_ERR_FORMAT;
        } else {
            st = parse_header(s, line, msg, msg_size);
        }
    }
    if (st == RTE_OK) {
        s->data_start = (long long)ftello(s->file);
        s->y_bytes = (size_t)s->width * (size_t)s->height;
        s->c_bytes = s->mono ? 0 : (size_t)((s->width + 1) / 2) * (size_t)((s->height + 1) / 2);
        s->frame_size = rte_frame_packed_size(s->mono ? RTE_PIXEL_GREY : RTE_PIXEL_NV12,
                                              s->width, s->height);
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
    source->ops = &rte_y4m_source_ops;
    source->impl = s;
    source->max_width = s->width;
    source->max_height = s->height;
    source->format = s->mono ? RTE_PIXEL_GREY : RTE_PIXEL_NV12;
    rte_source_msgf(msg, msg_size, "%s: %dx%d %s at %d/%d fps", s->path_name, s->width,
                    s->height, s->mono ? "mono" : "4:2:0", s->fps_num, s->fps_den);
    return RTE_OK;
}
