/* Shared by the rtedge_io sources: error messages, the decode target and
 * the reader's buffers. */
#ifndef RTEDGE_IO_INTERNAL_H
#define RTEDGE_IO_INTERNAL_H

#include <stdint.h>
#include <stdio.h>

#include "rtedge/imageio.h"

/* Where a message goes: the file it names and the caller's buffer. */
typedef struct io_msg {
    const char *path;
    char *buf;
    size_t size;
} io_msg;

/* Writes "<path>: <formatted text>" into the caller's buffer and returns st. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
rte_status
io_fail(const io_msg *m, rte_status st, const char *fmt, ...);

/* The same for a failed stdio call: appends strerror(errno). */
rte_status io_fail_errno(const io_msg *m, rte_status st, const char *what);

/* Where decoded pixels go: `channels` (1 grey, 3 BGR) interleaved, rows
 * `stride` bytes apart, exactly width x height. */
typedef struct io_target {
    uint8_t *buf;
    size_t stride;
    int32_t width, height;
    int32_t channels;
} io_target;

static inline uint8_t *io_target_row(const io_target *t, int32_t y)
{
    return t->buf + (size_t)y * t->stride;
}

enum { IO_BUFFER_SIZE = 1 << 16 };

struct rte_image_reader {
    int32_t max_width, max_height;
    uint8_t *row;  /* one decoded row of any format: max_width * 8 bytes */
    uint8_t *file; /* a whole JPEG file */
    size_t file_capacity;
    uint8_t *pixels; /* a whole decoded image before EXIF reorientation */
    size_t pixels_capacity;
    void *tj;        /* libjpeg-turbo decompressor (tjhandle) */
    char *io_buffer; /* stdio's buffer for the file being read */
};

/* The formats. probe reads the header of f (positioned at its start);
 * decode reads f from its start into the target, after the caller checked
 * the probed size against the target and the reader. */
rte_status pnm_probe(FILE *f, const io_msg *m, rte_image_info *info);
rte_status pnm_decode(rte_image_reader *r, FILE *f, const io_msg *m, const io_target *dst);
rte_status png_probe(FILE *f, const io_msg *m, rte_image_info *info);
rte_status png_decode(rte_image_reader *r, FILE *f, const io_msg *m, const io_target *dst);
rte_status jpeg_probe(FILE *f, const io_msg *m, rte_image_info *info);
rte_status jpeg_decode(rte_image_reader *r, FILE *f, const io_msg *m, const io_target *dst);

/* The libjpeg-turbo decompressor a reader keeps (NULL when out of memory). */
void *jpeg_decoder_new(void);
void jpeg_decoder_free(void *tj);

/* The largest JPEG file a reader of this size loads. */
size_t jpeg_max_file_bytes(int32_t max_width, int32_t max_height);

/* Writers: rows of `channels` bytes per pixel (BGR when 3). */
rte_status pnm_write(FILE *f, const io_msg *m, const uint8_t *buf, size_t stride, int32_t w,
                     int32_t h, int channels);
rte_status png_write(FILE *f, const io_msg *m, const uint8_t *buf, size_t stride, int32_t w,
                     int32_t h, int channels);
/* dtype "|u1" or "<i2"; shape (h, w) or (h, w, 3) when channels is 3. */
rte_status npy_write(FILE *f, const io_msg *m, const void *buf, size_t stride_bytes, int32_t w,
                     int32_t h, int channels, const char *dtype, size_t elem_size);

/* Reads n bytes at absolute offset pos; 0 when the file is shorter. */
int io_read_at(FILE *f, long pos, uint8_t *out, size_t n);

/* The orientation (1..8; 1 when absent or not understood) in the TIFF
 * structure at [tiff, tiff + len) of f, as OpenCV's ExifReader finds it:
 * byte order, 0x002A, IFD0, the first orientation entry's 16-bit value;
 * entries beyond the data end the search. */
int io_exif_orientation(FILE *f, long tiff, long len);

/* dst = src (sw x sh, c channels, packed) turned by an EXIF orientation,
 * as OpenCV's ExifTransform does; dst is sh x sw for 5..8. */
void io_reorient(const uint8_t *src, int32_t sw, int32_t sh, int c, int orientation,
                 const io_target *dst);

/* Fills info from a coded size; orientations 5..8 swap the axes. */
rte_status io_set_info(rte_image_info *info, int32_t coded_width, int32_t coded_height,
                       int orientation, int32_t channels, rte_file_format format);

/* Grey row -> target row (copy or replicate to BGR). */
void io_put_gray_row(const io_target *t, int32_t y, const uint8_t *gray);
/* RGB row -> target row (BGR; the target has 3 channels). */
void io_put_rgb_row(const io_target *t, int32_t y, const uint8_t *rgb);

#endif
