/* The public entry points: format detection, the reader, size checks
 * before decoding, and writers chosen by file extension. */
#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"

rte_status io_fail(const io_msg *m, rte_status st, const char *fmt, ...)
{
    if (!m->buf || m->size == 0)
        return st;
    /* Keep the tail of a long path: the file name is the useful part. */
    const char *path = m->path ? m->path : "(null)";
    size_t len = strlen(path);
    const size_t keep = 200;
    int n = len > keep ? snprintf(m->buf, m->size, "...%s: ", path + len - keep)
                       : snprintf(m->buf, m->size, "%s: ", path);
    if (n >= 0 && (size_t)n < m->size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(m->buf + n, m->size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return st;
}

rte_status io_fail_errno(const io_msg *m, rte_status st, const char *what)
{
    int e = errno;
    return io_fail(m, st, "%s: %s", what, e ? strerror(e) : "unknown error");
}

void io_put_gray_row(const io_target *t, int32_t y, const uint8_t *gray)
{
    uint8_t *restrict d = io_target_row(t, y);
    const int32_t w = t->width; /* a local: byte stores could alias t->width */
    if (t->channels == 1) {
        memcpy(d, gray, (size_t)w);
        return;
    }
    for (int32_t x = 0; x < w; x++) {
        uint8_t v = gray[x];
        d[3 * x] = v;
        d[3 * x + 1] = v;
        d[3 * x + 2] = v;
    }
}

void io_put_rgb_row(const io_target *t, int32_t y, const uint8_t *rgb)
{
    uint8_t *restrict d = io_target_row(t, y);
    const int32_t w = t->width;
    for (int32_t x = 0; x < w; x++) {
        d[3 * x] = rgb[3 * x + 2];
        d[3 * x + 1] = rgb[3 * x + 1];
        d[3 * x + 2] = rgb[3 * x];
    }
}

/* ------------------------------------------------------------------ */
/* Probing */

rte_status io_set_info(rte_image_info *info, int32_t coded_width, int32_t coded_height,
                       int orientation, int32_t channels, rte_file_format format)
{
    int swap = orientation >= 5;
    info->width = swap ? coded_height : coded_width;
    info->height = swap ? coded_width : coded_height;
    info->channels = channels;
    info->format = format;
    return RTE_OK;
}

static void clear_msg(char *msg, size_t msg_size)
{
    if (msg && msg_size)
        msg[0] = '\0';
}

/* Format from the first bytes; f is rewound. */
static rte_status detect_and_probe(FILE *f, const io_msg *m, rte_image_info *info)
{
    uint8_t sig[8];
    size_t n = fread(sig, 1, sizeof sig, f);
    if (ferror(f))
        return io_fail_errno(m, RTE_ERR_IO, "cannot read");
    rewind(f);
    memset(info, 0, sizeof *info);
    if (n == 0)
        return io_fail(m, RTE_ERR_TRUNCATED, "empty file");

    static const uint8_t png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (sig[0] == 0x89) {
        if (n < 8)
            return memcmp(sig, png_sig, n) == 0
                       ? io_fail(m, RTE_ERR_TRUNCATED,
                                 "truncated: PNG signature cut after %zu bytes", n)
                       : io_fail(m, RTE_ERR_FORMAT,
                                 "unknown file format (not PGM/PPM, PNG or JPEG)");
        if (memcmp(sig, png_sig, 8) != 0)
            return io_fail(m, RTE_ERR_FORMAT, "bad PNG signature");
        return png_probe(f, m, info);
    }
    if (sig[0] == 0xFF) {
        if (n < 2)
            return io_fail(m, RTE_ERR_TRUNCATED, "truncated: file is 1 byte");
        if (sig[1] != 0xD8)
            return io_fail(m, RTE_ERR_FORMAT, "unknown file format (not PGM/PPM, PNG or JPEG)");
        return jpeg_probe(f, m, info);
    }
    if (sig[0] == 'P')
        return pnm_probe(f, m, info);
    return io_fail(m, RTE_ERR_FORMAT, "unknown file format (not PGM/PPM, PNG or JPEG)");
}

static FILE *open_read(const io_msg *m, rte_status *st)
{
    FILE *f = fopen(m->path, "rb");
    *st = f ? RTE_OK : io_fail_errno(m, RTE_ERR_IO, "cannot open");
    return f;
}

rte_status rte_image_probe(const char *path, rte_image_info *info, char *msg, size_t msg_size)
{
    io_msg m = {path, msg, msg_size};
    clear_msg(msg, msg_size);
    if (!path || !info)
        return io_fail(&m, RTE_ERR_ARGUMENT, "no path or no info");
    rte_status st;
    FILE *f = open_read(&m, &st);
    if (!f)
        return st;
    st = detect_and_probe(f, &m, info);
    fclose(f);
    return st;
}

/* ------------------------------------------------------------------ */
/* The reader */

rte_image_reader *rte_image_reader_create(int32_t max_width, int32_t max_height)
{
    if (max_width < 1 || max_height < 1 || max_width > RTE_MAX_SIDE || max_height > RTE_MAX_SIDE)
        return NULL;
    rte_image_reader *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->max_width = max_width;
    r->max_height = max_height;
    /* A raw PNG scanline (up to 8 bytes per pixel, plus a partial byte)
     * followed by its 8-bit conversion (up to 3 bytes per pixel). */
    r->row = malloc((size_t)max_width * 11 + 16);
    r->file_capacity = jpeg_max_file_bytes(max_width, max_height);
    r->file = malloc(r->file_capacity);
    r->pixels_capacity = (size_t)max_width * (size_t)max_height * 3;
    r->pixels = malloc(r->pixels_capacity);
    r->tj = jpeg_decoder_new();
    r->io_buffer = malloc(IO_BUFFER_SIZE);
    if (!r->row || !r->file || !r->pixels || !r->tj || !r->io_buffer) {
        rte_image_reader_destroy(r);
        return NULL;
    }
    return r;
}

void rte_image_reader_destroy(rte_image_reader *reader)
{
    if (!reader)
        return;
    jpeg_decoder_free(reader->tj);
    free(reader->io_buffer);
    free(reader->pixels);
    free(reader->file);
    free(reader->row);
    free(reader);
}

size_t rte_image_reader_max_file_bytes(const rte_image_reader *reader)
{
    return reader ? reader->file_capacity : 0;
}

typedef enum want { WANT_NATIVE, WANT_BGR, WANT_GRAY } want;

/* Everything before decoding is checked here: the size against the reader,
 * and against the caller's buffer or view. */
static rte_status read_file(rte_image_reader *r, const io_msg *m, want w, io_target *t,
                            size_t capacity, rte_image_info *info)
{
    rte_status st;
    FILE *f = open_read(m, &st);
    if (!f)
        return st;
    /* The reader's buffer instead of one stdio would allocate per file. */
    setvbuf(f, r->io_buffer, _IOFBF, IO_BUFFER_SIZE);
    st = detect_and_probe(f, m, info);
    if (st != RTE_OK)
        goto done;
    if (info->width > r->max_width || info->height > r->max_height) {
        st = io_fail(m, RTE_ERR_TOO_LARGE, "image is %dx%d, the reader holds at most %dx%d",
                     (int)info->width, (int)info->height, (int)r->max_width, (int)r->max_height);
        goto done;
    }
    if (w == WANT_NATIVE) {
        size_t need = (size_t)info->width * (size_t)info->height * (size_t)info->channels;
        if (capacity < need) {
            st = io_fail(m, RTE_ERR_NO_MEMORY,
                         "%dx%dx%d image needs %zu bytes, the buffer holds %zu", (int)info->width,
                         (int)info->height, (int)info->channels, need, capacity);
            goto done;
        }
        t->width = info->width;
        t->height = info->height;
        t->channels = info->channels;
        t->stride = (size_t)info->width * (size_t)info->channels;
    } else {
        if (w == WANT_GRAY && info->channels != 1) {
            st = io_fail(m, RTE_ERR_UNSUPPORTED,
                         "is a colour image: read it as BGR and convert with rte_bgr_to_gray");
            goto done;
        }
        if (t->width != info->width || t->height != info->height) {
            st = io_fail(m, RTE_ERR_SIZE, "image is %dx%d, the destination is %dx%d",
                         (int)info->width, (int)info->height, (int)t->width, (int)t->height);
            goto done;
        }
    }
    rewind(f);
    switch (info->format) {
    case RTE_FILE_PGM:
    case RTE_FILE_PPM: st = pnm_decode(r, f, m, t); break;
    case RTE_FILE_PNG: st = png_decode(r, f, m, t); break;
    case RTE_FILE_JPEG: st = jpeg_decode(r, f, m, t); break;
    default: st = io_fail(m, RTE_ERR_UNSUPPORTED, "cannot decode this format"); break;
    }
done:
    fclose(f);
    return st;
}

rte_status rte_image_read(rte_image_reader *reader, const char *path, void *buf, size_t capacity,
                          rte_image_info *info, char *msg, size_t msg_size)
{
    io_msg m = {path, msg, msg_size};
    clear_msg(msg, msg_size);
    if (!reader || !path || !buf || !info)
        return io_fail(&m, RTE_ERR_ARGUMENT, "no reader, path, buffer or info");
    io_target t = {(uint8_t *)buf, 0, 0, 0, 0};
    return read_file(reader, &m, WANT_NATIVE, &t, capacity, info);
}

rte_status rte_image_read_bgr(rte_image_reader *reader, const char *path, const rte_image_u8c3 *dst,
                              char *msg, size_t msg_size)
{
    io_msg m = {path, msg, msg_size};
    clear_msg(msg, msg_size);
    if (!reader || !path)
        return io_fail(&m, RTE_ERR_ARGUMENT, "no reader or path");
    rte_status st = rte_image_u8c3_check(dst);
    if (st != RTE_OK)
        return io_fail(&m, st, "bad destination image");
    io_target t = {dst->buf, (size_t)dst->stride, dst->width, dst->height, 3};
    rte_image_info info;
    return read_file(reader, &m, WANT_BGR, &t, 0, &info);
}

rte_status rte_image_read_gray(rte_image_reader *reader, const char *path, const rte_image_u8 *dst,
                               char *msg, size_t msg_size)
{
    io_msg m = {path, msg, msg_size};
    clear_msg(msg, msg_size);
    if (!reader || !path)
        return io_fail(&m, RTE_ERR_ARGUMENT, "no reader or path");
    rte_status st = rte_image_u8_check(dst);
    if (st != RTE_OK)
        return io_fail(&m, st, "bad destination image");
    io_target t = {dst->buf, (size_t)dst->stride, dst->width, dst->height, 1};
    rte_image_info info;
    return read_file(reader, &m, WANT_GRAY, &t, 0, &info);
}

/* ------------------------------------------------------------------ */
/* Writers */

static bool has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    if (n < e)
        return false;
    for (size_t i = 0; i < e; i++) {
        char c = path[n - e + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != ext[i])
            return false;
    }
    return true;
}

bool rte_image_path_has_image_extension(const char *path)
{
    static const char *const exts[] = {".png", ".jpg", ".jpeg", ".pgm", ".ppm", ".pnm"};
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++)
        if (strlen(path) > strlen(exts[i]) && has_ext(path, exts[i]))
            return true;
    return false;
}

struct write_job {
    const void *buf;
    size_t stride_bytes;
    int32_t w, h;
    int channels;
    rte_file_format format;
    const char *dtype;
    size_t elem;
};

static rte_status write_file(const io_msg *m, const struct write_job *j)
{
    FILE *f = fopen(m->path, "wb");
    if (!f)
        return io_fail_errno(m, RTE_ERR_IO, "cannot create");
    rte_status st;
    switch (j->format) {
    case RTE_FILE_PGM:
    case RTE_FILE_PPM:
        st = pnm_write(f, m, j->buf, j->stride_bytes, j->w, j->h, j->channels);
        break;
    case RTE_FILE_PNG:
        st = png_write(f, m, j->buf, j->stride_bytes, j->w, j->h, j->channels);
        break;
    default:
        st = npy_write(f, m, j->buf, j->stride_bytes, j->w, j->h, j->channels, j->dtype, j->elem);
        break;
    }
    /* fclose flushes: a full disk shows up here. */
    if (fclose(f) != 0 && st == RTE_OK)
        st = io_fail_errno(m, RTE_ERR_IO, "cannot write");
    return st;
}

struct ext_format {
    const char *ext;
    rte_file_format format;
};

/* The checks every writer shares, then the format from the extension. */
static rte_status write_checked(const char *path, char *msg, size_t msg_size,
                                rte_status view_status, struct write_job *j,
                                const struct ext_format *formats, const char *kind)
{
    io_msg m = {path, msg, msg_size};
    clear_msg(msg, msg_size);
    if (!path)
        return io_fail(&m, RTE_ERR_ARGUMENT, "no path");
    if (view_status != RTE_OK)
        return io_fail(&m, view_status, "bad image");
    for (; formats->ext; formats++)
        if (has_ext(path, formats->ext)) {
            j->format = formats->format;
            return write_file(&m, j);
        }
    return io_fail(&m, RTE_ERR_ARGUMENT, "unknown extension for %s", kind);
}

rte_status rte_image_write_gray(const char *path, const rte_image_u8 *img, char *msg,
                                size_t msg_size)
{
    static const struct ext_format formats[] = {{".pgm", RTE_FILE_PGM},
                                                {".png", RTE_FILE_PNG},
                                                {".npy", RTE_FILE_NPY},
                                                {NULL, RTE_FILE_UNKNOWN}};
    rte_status st = rte_image_u8_check(img);
    struct write_job j = {0};
    if (st == RTE_OK)
        j = (struct write_job){img->buf, (size_t)img->stride, img->width, img->height,
                               1,        RTE_FILE_UNKNOWN,    "|u1",      1};
    return write_checked(path, msg, msg_size, st, &j, formats,
                         "a grey image (use .pgm, .png or .npy)");
}

rte_status rte_image_write_bgr(const char *path, const rte_image_u8c3 *img, char *msg,
                               size_t msg_size)
{
    static const struct ext_format formats[] = {{".ppm", RTE_FILE_PPM},
                                                {".png", RTE_FILE_PNG},
                                                {".npy", RTE_FILE_NPY},
                                                {NULL, RTE_FILE_UNKNOWN}};
    rte_status st = rte_image_u8c3_check(img);
    struct write_job j = {0};
    if (st == RTE_OK)
        j = (struct write_job){img->buf, (size_t)img->stride, img->width, img->height,
                               3,        RTE_FILE_UNKNOWN,    "|u1",      1};
    return write_checked(path, msg, msg_size, st, &j, formats,
                         "a colour image (use .ppm, .png or .npy)");
}

rte_status rte_image_write_s16(const char *path, const rte_image_s16 *img, char *msg,
                               size_t msg_size)
{
    static const struct ext_format formats[] = {{".npy", RTE_FILE_NPY}, {NULL, RTE_FILE_UNKNOWN}};
    rte_status st = rte_image_s16_check(img);
    struct write_job j = {0};
    if (st == RTE_OK)
        j = (struct write_job){img->buf,   (size_t)img->stride * sizeof(int16_t),
                               img->width, img->height,
                               1,          RTE_FILE_UNKNOWN,
                               "<i2",      2};
    return write_checked(path, msg, msg_size, st, &j, formats, "an int16 image (use .npy)");
}
