/* PGM and PPM (Netpbm P2, P3, P5, P6) with maxval 1..255.
 *
 * Pixel values follow OpenCV 4.6's reader, checked against cv2.imread:
 * text files (P2/P3) clamp each value to maxval and scale it by
 * v * 255 / maxval (integer division); binary files (P5/P6) are copied
 * unscaled whatever the maxval. The header follows the Netpbm rules, which
 * are stricter than OpenCV in one place (maxval must be followed by one
 * whitespace character, not any byte) and looser in two (a comment may
 * follow a number directly, and the last text value may end the file). */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "io_internal.h"

typedef struct pnm_header {
    int32_t width, height;
    int maxval;
    int channels;
    int binary;
    int magic; /* '2', '3', '5' or '6' */
} pnm_header;

static bool is_space(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

static const char *describe(int c, char *text, size_t size)
{
    if (c == EOF)
        snprintf(text, size, "the end of the file");
    else if (c > ' ' && c < 127)
        snprintf(text, size, "'%c'", c);
    else
        snprintf(text, size, "byte 0x%02x", (unsigned)c);
    return text;
}

typedef enum number_result {
    NUMBER_OK,
    NUMBER_EOF,     /* the file ends before the number */
    NUMBER_BAD,     /* a byte that cannot start a number (kept in *c) */
    NUMBER_BAD_END, /* a byte that cannot follow a number (kept in *c) */
} number_result;

static void skip_comment(FILE *f)
{
    int c;
    do
        c = getc(f);
    while (c != '\n' && c != '\r' && c != EOF);
}

/* Skips whitespace and comments, then reads a decimal number (saturating
 * at 10^9) and the byte after it: whitespace (consumed), '#' (the comment is
 * skipped) or the end of the file. *end receives that byte. */
static number_result read_number(FILE *f, long *value, int *c_out, int *end)
{
    int c = getc(f);
    for (;;) {
        if (c == '#') {
            skip_comment(f);
            c = getc(f);
        } else if (is_space(c)) {
            c = getc(f);
        } else {
            break;
        }
    }
    *c_out = c;
    if (c == EOF)
        return NUMBER_EOF;
    if (c < '0' || c > '9')
        return NUMBER_BAD;
    long v = 0;
    while (c >= '0' && c <= '9') {
        if (v < 1000000000L)
            v = v * 10 + (c - '0');
        c = getc(f);
    }
    *value = v;
    *end = c;
    *c_out = c;
    if (c == '#') {
        skip_comment(f);
        return NUMBER_OK;
    }
    return c == EOF || is_space(c) ? NUMBER_OK : NUMBER_BAD_END;
}

static rte_status header_number(FILE *f, const io_msg *m, const char *what, long *value, int *end)
{
    int c;
    char text[32];
    switch (read_number(f, value, &c, end)) {
    case NUMBER_OK: return RTE_OK;
    case NUMBER_EOF:
        return io_fail(m, RTE_ERR_TRUNCATED, "truncated: the header ends before the %s", what);
    case NUMBER_BAD:
        return io_fail(m, RTE_ERR_FORMAT, "bad header: expected a number for the %s, found %s",
                       what, describe(c, text, sizeof text));
    case NUMBER_BAD_END:
        return io_fail(m, RTE_ERR_FORMAT, "bad header: %s followed by %s", what,
                       describe(c, text, sizeof text));
    }
    return RTE_ERR_FORMAT;
}

static rte_status read_header(FILE *f, const io_msg *m, pnm_header *h)
{
    int c0 = getc(f), c1 = getc(f), c2 = getc(f);
    if (c0 != 'P')
        return io_fail(m, RTE_ERR_FORMAT, "not a PGM/PPM file");
    if (c1 == '1' || c1 == '4')
        return io_fail(m, RTE_ERR_UNSUPPORTED, "PBM bitmaps (P%c) are not supported", c1);
    if (c1 == '7')
        return io_fail(m, RTE_ERR_UNSUPPORTED, "PAM (P7) files are not supported");
    if (c1 != '2' && c1 != '3' && c1 != '5' && c1 != '6')
        return io_fail(m, RTE_ERR_FORMAT, "not a PGM/PPM file (bad magic number)");
    if (c2 == EOF)
        return io_fail(m, RTE_ERR_TRUNCATED, "truncated: the header ends after the magic number");
    if (!is_space(c2))
        return io_fail(m, RTE_ERR_FORMAT, "bad header: no whitespace after the magic number P%c",
                       c1);
    h->magic = c1;
    h->binary = c1 >= '5';
    h->channels = (c1 == '3' || c1 == '6') ? 3 : 1;

    long w = 0, ht = 0, maxval = 0;
    int end;
    rte_status st = header_number(f, m, "width", &w, &end);
    if (st == RTE_OK)
        st = header_number(f, m, "height", &ht, &end);
    if (st == RTE_OK)
        st = header_number(f, m, "maxval", &maxval, &end);
    if (st != RTE_OK)
        return st;
    if (w == 0 || ht == 0)
        return io_fail(m, RTE_ERR_FORMAT, "bad header: size %ldx%ld (zero width or height)", w, ht);
    if (w > RTE_MAX_SIDE || ht > RTE_MAX_SIDE)
        return io_fail(m, RTE_ERR_TOO_LARGE, "size %ldx%ld exceeds the maximum side %d", w, ht,
                       RTE_MAX_SIDE);
    if (maxval == 0 || maxval > 65535)
        return io_fail(m, RTE_ERR_FORMAT, "bad header: maxval %ld (must be 1..255)", maxval);
    if (maxval > 255)
        return io_fail(m, RTE_ERR_UNSUPPORTED,
                       "maxval %ld: 16-bit samples are not supported (only 1..255)", maxval);
    /* Binary pixels start right after the one whitespace byte ending maxval. */
    if (h->binary && end == '#')
        return io_fail(m, RTE_ERR_FORMAT,
                       "bad header: maxval must be followed by one whitespace character");
    if (h->binary && end == EOF)
        return io_fail(m, RTE_ERR_TRUNCATED, "truncated: expected %ld pixel bytes, found 0",
                       w * ht * h->channels);
    h->width = (int32_t)w;
    h->height = (int32_t)ht;
    h->maxval = (int)maxval;
    return RTE_OK;
}

rte_status pnm_probe(FILE *f, const io_msg *m, rte_image_info *info)
{
    pnm_header h = {0};
    rte_status st = read_header(f, m, &h);
    if (st != RTE_OK)
        return st;
    return io_set_info(info, h.width, h.height, 1, h.channels,
                       h.channels == 3 ? RTE_FILE_PPM : RTE_FILE_PGM);
}

/* One row of text values into `row` (scaled to 0..255). */
static rte_status read_text_row(FILE *f, const io_msg *m, const pnm_header *h, const uint8_t *lut,
                                uint8_t *row, int32_t y)
{
    size_t n = (size_t)h->width * (size_t)h->channels;
    size_t total = n * (size_t)h->height;
    for (size_t i = 0; i < n; i++) {
        long v = 0;
        int c, end;
        char text[32];
        size_t index = (size_t)y * n + i;
        switch (read_number(f, &v, &c, &end)) {
        case NUMBER_OK: break;
        case NUMBER_EOF:
            return io_fail(m, RTE_ERR_TRUNCATED, "truncated: expected %zu pixel values, found %zu",
                           total, index);
        case NUMBER_BAD:
            return io_fail(m, RTE_ERR_FORMAT, "bad pixel value %zu: found %s", index,
                           describe(c, text, sizeof text));
        case NUMBER_BAD_END:
            return io_fail(m, RTE_ERR_FORMAT, "bad pixel value %zu: a number followed by %s", index,
                           describe(c, text, sizeof text));
        }
        row[i] = lut[v > h->maxval ? h->maxval : v];
    }
    return RTE_OK;
}

rte_status pnm_decode(rte_image_reader *r, FILE *f, const io_msg *m, const io_target *dst)
{
    pnm_header h = {0};
    rte_status st = read_header(f, m, &h);
    if (st != RTE_OK)
        return st;
    if (h.width != dst->width || h.height != dst->height)
        return io_fail(m, RTE_ERR_SIZE, "changed while being read");

    uint8_t lut[256];
    for (int v = 0; v <= h.maxval; v++)
        lut[v] = (uint8_t)(v * 255 / h.maxval);

    size_t row_bytes = (size_t)h.width * (size_t)h.channels;
    for (int32_t y = 0; y < h.height; y++) {
        /* Grey into grey needs no conversion: read straight into the target. */
        uint8_t *row =
            (h.channels == dst->channels && h.channels == 1) ? io_target_row(dst, y) : r->row;
        if (h.binary) {
            size_t got = fread(row, 1, row_bytes, f);
            if (got < row_bytes) {
                if (ferror(f))
                    return io_fail_errno(m, RTE_ERR_IO, "read error");
                return io_fail(m, RTE_ERR_TRUNCATED,
                               "truncated: expected %zu pixel bytes, found %zu",
                               row_bytes * (size_t)h.height, row_bytes * (size_t)y + got);
            }
        } else {
            st = read_text_row(f, m, &h, lut, row, y);
            if (st != RTE_OK)
                return st;
        }
        if (h.channels == 3)
            io_put_rgb_row(dst, y, row);
        else if (row != io_target_row(dst, y))
            io_put_gray_row(dst, y, row);
    }
    return RTE_OK;
}

rte_status pnm_write(FILE *f, const io_msg *m, const uint8_t *buf, size_t stride, int32_t w,
                     int32_t h, int channels)
{
    if (fprintf(f, "P%c\n%d %d\n255\n", channels == 3 ? '6' : '5', (int)w, (int)h) < 0)
        return io_fail_errno(m, RTE_ERR_IO, "cannot write");
    uint8_t chunk[3 * 1024];
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *row = buf + (size_t)y * stride;
        if (channels == 1) {
            if (fwrite(row, 1, (size_t)w, f) != (size_t)w)
                return io_fail_errno(m, RTE_ERR_IO, "cannot write");
            continue;
        }
        /* BGR -> RGB through a small buffer: no allocation. */
        for (int32_t x0 = 0; x0 < w; x0 += 1024) {
            int32_t n = w - x0 < 1024 ? w - x0 : 1024;
            const uint8_t *s = row + 3 * (size_t)x0;
            for (int32_t i = 0; i < n; i++) {
                chunk[3 * i] = s[3 * i + 2];
                chunk[3 * i + 1] = s[3 * i + 1];
                chunk[3 * i + 2] = s[3 * i];
            }
            if (fwrite(chunk, 3, (size_t)n, f) != (size_t)n)
                return io_fail_errno(m, RTE_ERR_IO, "cannot write");
        }
    }
    return RTE_OK;
}
