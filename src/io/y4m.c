/* YUV4MPEG2 reader: header "YUV4MPEG2 W.. H.. [F..] [I..] [A..] [C..] [X..]",
 * then per frame "FRAME[ params]\n", the Y plane and the chroma planes. */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rtedge/y4m.h"

struct rte_y4m_reader {
    FILE *file;
    rte_y4m_info info;
};

static rte_status y4m_fail(rte_status st, char *msg, size_t msg_size, const char *what,
                           const char *path)
{
    if (msg && msg_size)
        snprintf(msg, msg_size, "%s: %s", path ? path : "y4m", what);
    return st;
}

/* Reads one line (without '\n') of at most cap-1 bytes. 0 on success, -1 at
 * end of file before any byte, -2 when the line is too long or cut short. */
static int y4m_line(FILE *f, char *buf, size_t cap)
{
    size_t n = 0;
    int c;
    while ((c = getc(f)) != EOF && c != '\n') {
        if (n + 1 >= cap)
            return -2;
        buf[n++] = (char)c;
    }
    buf[n] = 0;
    if (c == EOF)
        return n == 0 ? -1 : -2;
    return 0;
}

/* Chroma bytes per frame for a C tag value; -1 when not supported. */
static int64_t y4m_chroma_bytes(const char *tag, int64_t w, int64_t h)
{
    if (strcmp(tag, "mono") == 0)
        return 0;
    if (strncmp(tag, "420", 3) == 0 &&
        (tag[3] == 0 || strcmp(tag + 3, "jpeg") == 0 || strcmp(tag + 3, "paldv") == 0 ||
         strcmp(tag + 3, "mpeg2") == 0))
        return 2 * ((w + 1) / 2) * ((h + 1) / 2);
    if (strcmp(tag, "422") == 0)
        return 2 * ((w + 1) / 2) * h;
    if (strcmp(tag, "444") == 0)
        return 2 * w * h;
    return -1;
}

/* A decimal number in lo..hi that ends at the end of the text or at `stop`
 * (then *rest points past it); false for anything else, overflow included. */
static bool y4m_number(const char *text, long lo, long hi, char stop, long *value,
                       const char **rest)
{
    if (*text < '0' || *text > '9')
        return false;
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || v < lo || v > hi || (*end && (*end != stop || !rest)))
        return false;
    if (rest)
        *rest = *end ? end + 1 : end;
    *value = v;
    return true;
}

rte_status rte_y4m_parse_header(char *line, rte_y4m_info *info, char *why, size_t why_size)
{
    rte_y4m_info in = {0};
    strcpy(in.chroma, "420jpeg");
    if (strncmp(line, "YUV4MPEG2", 9) != 0 || (line[9] != ' ' && line[9] != 0)) {
        snprintf(why, why_size, "not a YUV4MPEG2 file");
        return RTE_ERR_FORMAT;
    }
    char *save = NULL;
    for (char *tok = strtok_r(line + 9, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        long a, b;
        const char *rest;
        switch (tok[0]) {
        case 'W':
        case 'H':
            if (!y4m_number(tok + 1, 1, RTE_MAX_SIDE, 0, &a, NULL)) {
                snprintf(why, why_size, "bad frame %s in tag '%.32s' (1..%d)",
                         tok[0] == 'W' ? "width" : "height", tok, RTE_MAX_SIDE);
                return RTE_ERR_FORMAT;
            }
            *(tok[0] == 'W' ? &in.width : &in.height) = (int32_t)a;
            break;
        case 'F':
            if (!y4m_number(tok + 1, 0, INT32_MAX, ':', &a, &rest) ||
                !y4m_number(rest, 0, INT32_MAX, 0, &b, NULL) || (a == 0) != (b == 0)) {
                snprintf(why, why_size, "bad frame rate tag '%.32s' (F<num>:<den>)", tok);
                return RTE_ERR_FORMAT;
            }
            in.fps_num = (int32_t)a; /* 0:0 is "unknown" */
            in.fps_den = (int32_t)b;
            break;
        case 'I':
            if (tok[1] != 'p' && tok[1] != '?') {
                snprintf(why, why_size, "interlaced streams (%.32s) are not supported", tok);
                return RTE_ERR_UNSUPPORTED;
            }
            break;
        case 'C':
            if (strlen(tok + 1) >= sizeof in.chroma) {
                snprintf(why, why_size, "unknown chroma tag '%.32s'", tok);
                return RTE_ERR_UNSUPPORTED;
            }
            strcpy(in.chroma, tok + 1);
            break;
        default: break; /* A (aspect), X (extensions) */
        }
    }
    if (in.width == 0 || in.height == 0) {
        snprintf(why, why_size, "no frame size (W and H tags)");
        return RTE_ERR_FORMAT;
    }
    int64_t chroma = y4m_chroma_bytes(in.chroma, in.width, in.height);
    if (chroma < 0) {
        snprintf(why, why_size, "chroma C%s is not supported (8-bit 420, 422, 444 and mono are)",
                 in.chroma);
        return RTE_ERR_UNSUPPORTED;
    }
    in.chroma_bytes = (int32_t)chroma;
    *info = in;
    return RTE_OK;
}

rte_status rte_y4m_open(const char *path, int32_t max_width, int32_t max_height,
                        rte_y4m_reader **reader, rte_y4m_info *info, char *msg, size_t msg_size)
{
    if (msg && msg_size)
        msg[0] = 0;
    if (!path || !reader)
        return RTE_ERR_ARGUMENT;
    *reader = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return y4m_fail(RTE_ERR_IO, msg, msg_size, "cannot open", path);
    char line[512], why[160] = "";
    rte_y4m_info in;
    rte_status st = RTE_OK;
    if (y4m_line(f, line, sizeof line) != 0) {
        st = RTE_ERR_FORMAT;
        snprintf(why, sizeof why, "not a YUV4MPEG2 file");
    } else {
        st = rte_y4m_parse_header(line, &in, why, sizeof why);
    }
    if (st == RTE_OK &&
        ((max_width > 0 && in.width > max_width) || (max_height > 0 && in.height > max_height))) {
        st = RTE_ERR_TOO_LARGE;
        snprintf(why, sizeof why, "frame larger than allowed");
    }
    rte_y4m_reader *r = st == RTE_OK ? calloc(1, sizeof *r) : NULL;
    if (st == RTE_OK && !r) {
        st = RTE_ERR_NO_MEMORY;
        snprintf(why, sizeof why, "out of memory");
    }
    if (st != RTE_OK) {
        fclose(f);
        return y4m_fail(st, msg, msg_size, why, path);
    }
    r->file = f;
    r->info = in;
    if (info)
        *info = in;
    *reader = r;
    return RTE_OK;
}

rte_pixel_format rte_y4m_frame_format(const rte_y4m_info *info)
{
    return strncmp(info->chroma, "420", 3) == 0 ? RTE_PIXEL_NV12 : RTE_PIXEL_GREY;
}

/* Reads n bytes into dst; false when the file ends first. */
static bool y4m_read(FILE *f, uint8_t *dst, size_t n) { return fread(dst, 1, n, f) == n; }

rte_status rte_y4m_read_frame(rte_y4m_reader *r, const rte_frame *dst, char *msg, size_t msg_size)
{
    if (msg && msg_size)
        msg[0] = 0;
    if (!r || !dst || rte_frame_check(dst) != RTE_OK)
        return RTE_ERR_ARGUMENT;
    if (dst->width != r->info.width || dst->height != r->info.height)
        return RTE_ERR_SIZE;
    const int32_t w = dst->width, h = dst->height, cw = (w + 1) / 2, ch = (h + 1) / 2;
    const bool nv12 = dst->format == RTE_PIXEL_NV12;
    if (dst->format != RTE_PIXEL_GREY && dst->format != rte_y4m_frame_format(&r->info))
        return RTE_ERR_UNSUPPORTED;
    char line[256];
    int rc = y4m_line(r->file, line, sizeof line);
    if (rc == -1)
        return RTE_ERR_END;
    if (rc != 0 || strncmp(line, "FRAME", 5) != 0 || (line[5] != 0 && line[5] != ' '))
        return y4m_fail(rc == -2 && strncmp(line, "FRAME", 5) == 0 ? RTE_ERR_TRUNCATED
                                                                   : RTE_ERR_FORMAT,
                        msg, msg_size, "missing FRAME marker", NULL);
    for (int32_t y = 0; y < h; y++)
        if (!y4m_read(r->file, dst->plane[0] + (size_t)y * (size_t)dst->stride[0], (size_t)w))
            return y4m_fail(RTE_ERR_TRUNCATED, msg, msg_size, "frame cut short", NULL);
    if (!nv12)
        return r->info.chroma_bytes > 0 && fseek(r->file, r->info.chroma_bytes, SEEK_CUR) != 0
                   ? y4m_fail(RTE_ERR_IO, msg, msg_size, "cannot skip chroma", NULL)
                   : RTE_OK;
    /* The U plane, then V, each cw x ch: into the even and odd bytes of the
     * UV rows (NV12), through a small buffer. */
    uint8_t part[512];
    for (int plane = 0; plane < 2; plane++)
        for (int32_t y = 0; y < ch; y++) {
            uint8_t *uv = dst->plane[1] + (size_t)y * (size_t)dst->stride[1] + plane;
            for (int32_t x = 0; x < cw; x += (int32_t)sizeof part) {
                const int32_t n = cw - x < (int32_t)sizeof part ? cw - x : (int32_t)sizeof part;
                if (!y4m_read(r->file, part, (size_t)n))
                    return y4m_fail(RTE_ERR_TRUNCATED, msg, msg_size, "frame cut short", NULL);
                for (int32_t i = 0; i < n; i++)
                    uv[2 * (x + i)] = part[i];
            }
        }
    return RTE_OK;
}

rte_status rte_y4m_read_gray(rte_y4m_reader *r, const rte_image_u8 *dst, char *msg, size_t msg_size)
{
    if (!r || !dst || !dst->buf)
        return RTE_ERR_ARGUMENT;
    if (dst->width != r->info.width || dst->height != r->info.height || dst->stride < dst->width)
        return RTE_ERR_SIZE;
    const rte_frame grey = {
        RTE_PIXEL_GREY, dst->width, dst->height, {dst->buf, NULL}, {dst->stride, 0}};
    return rte_y4m_read_frame(r, &grey, msg, msg_size);
}

void rte_y4m_close(rte_y4m_reader *r)
{
    if (!r)
        return;
    fclose(r->file);
    free(r);
}
