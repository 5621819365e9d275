/* Image files for the CLI, the tools and recorded-frame sources: PGM/PPM,
 * PNG (libspng) and JPEG (libjpeg-turbo) in; PGM, PPM, PNG and NumPy .npy
 * out (libspng and libjpeg-turbo are librtedge's only dependencies besides
 * libcamera; the algorithms use none).
 *
 * Decoded pixels are what OpenCV 4.6's cv::imread(path, IMREAD_COLOR) gives,
 * bit for bit: BGR order, 16-bit PNG samples reduced to their high byte,
 * alpha dropped (not blended), palettes expanded, 1/2/4-bit grey scaled to
 * 0..255, JPEG decoded with the accurate integer IDCT and smooth ("fancy")
 * chroma upsampling, and the EXIF orientation of a JPEG (first APP1) or a
 * PNG (first eXIf chunk) applied. A grey file (PGM, grey PNG, grey JPEG)
 * can also be read as one channel.
 *
 * Stricter than imread, on purpose: a JPEG that libjpeg only warns about (cut
 * short and padded with grey, damaged entropy data) is an error, as is a PNG
 * that ends before IEND; 16-bit PGM/PPM, PBM, CMYK/12-bit/lossless JPEG are
 * RTE_ERR_UNSUPPORTED.
 *
 * Reading goes through an rte_image_reader created once for a maximum image
 * size: it holds every decode buffer, so reading a frame makes no allocation
 * of rtedge's own (the codec libraries still allocate inside: see
 * rte_image_reader_create). Sizes are checked against the maxima before
 * anything large is allocated or decoded.
 *
 * Every function returns an rte_status and, unless `msg` is NULL, writes a
 * NUL-terminated message naming the file and the problem into msg (at most
 * msg_size bytes, RTE_IO_MESSAGE_SIZE is always enough), e.g.
 * "road.pgm: truncated: expected 307200 pixel bytes, found 1200". On success
 * msg holds "". */
#ifndef RTEDGE_IMAGEIO_H
#define RTEDGE_IMAGEIO_H

#include <stddef.h>
#include <stdbool.h>
#include <stdint.h>

#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Room for any message, file name included (longer names are shortened). */
#define RTE_IO_MESSAGE_SIZE 512

typedef enum rte_file_format {
    RTE_FILE_UNKNOWN = 0,
    RTE_FILE_PGM, /* P2 (text) or P5 (binary), maxval 1..255 */
    RTE_FILE_PPM, /* P3 (text) or P6 (binary), maxval 1..255 */
    RTE_FILE_PNG,
    RTE_FILE_JPEG,
    RTE_FILE_NPY, /* written only */
} rte_file_format;

/* What a file holds, from its header. */
typedef struct rte_image_info {
    int32_t width, height;
    /* 1 when the file is grey (PGM, grey or grey+alpha PNG, grey JPEG),
     * 3 when it is colour; rte_image_read() delivers this many channels. */
    int32_t channels;
    rte_file_format format;
} rte_image_info;

/* Reads the header of `path` (format from the content, not the name): size,
 * channels, format. Reads only the headers (JPEG: the markers up to the
 * first scan; PNG: every chunk header up to IEND) and needs no decode buffers (fopen's FILE aside); fails with RTE_ERR_TOO_LARGE beyond RTE_MAX_SIDE. A JPEG or PNG
 * whose EXIF orientation swaps the axes reports the swapped (displayed) size. */
RTE_API rte_status rte_image_probe(const char *path, rte_image_info *info, char *msg,
                                   size_t msg_size);

/* A reader: decode buffers for images up to max_width x max_height
 * (1..RTE_MAX_SIDE each), allocated once here: one row buffer, a whole-file
 * buffer for JPEG (rte_image_reader_max_file_bytes), a BGR image for
 * reorienting EXIF-rotated files, a 64 KB stdio buffer and the TurboJPEG
 * handle; about 7.5 MB for 1280x720. NULL on bad sizes or when memory runs
 * out. A reader is not thread-safe: one per thread.
 *
 * Per read, outside rtedge's control: fopen allocates its FILE (about 0.5 KB;
 * the stdio buffer is the reader's); libspng allocates its context, inflate
 * state and scanline buffers (measured: 9 allocations, about 55 KB for a
 * 413x356 RGB PNG); libjpeg-turbo allocates its per-image pools (about 9
 * allocations, 45-70 KB for a baseline 1280x720 JPEG, but the whole
 * coefficient array, about 2 MB at 960x540, for a progressive one), freed
 * when the image is done. Neither codec can reuse them across files. */
typedef struct rte_image_reader rte_image_reader;

RTE_API rte_image_reader *rte_image_reader_create(int32_t max_width, int32_t max_height);
RTE_API void rte_image_reader_destroy(rte_image_reader *reader);

/* The largest file (bytes) the reader loads whole (JPEG only: PNM and PNG
 * are streamed): room for the least compressible 4:4:4 JPEG of the maximum
 * size plus 1 MiB of metadata. */
RTE_API size_t rte_image_reader_max_file_bytes(const rte_image_reader *reader);

/* Decodes `path` into buf (capacity bytes) as info->channels interleaved
 * channels (grey, or BGR), rows packed: stride width * channels bytes. The
 * size is checked against the reader's maxima and the capacity before
 * decoding. `info` receives the header (also on most errors after it). */
RTE_API rte_status rte_image_read(rte_image_reader *reader, const char *path, void *buf,
                                  size_t capacity, rte_image_info *info, char *msg,
                                  size_t msg_size);

/* Decodes `path` as BGR into dst, whose width and height must equal the
 * image's (RTE_ERR_SIZE otherwise, before decoding); any stride. Grey files
 * are replicated to B = G = R, as IMREAD_COLOR does. */
RTE_API rte_status rte_image_read_bgr(rte_image_reader *reader, const char *path,
                                      const rte_image_u8c3 *dst, char *msg, size_t msg_size);

/* Decodes a grey file into dst (same size rule as rte_image_read_bgr).
 * A colour file gives RTE_ERR_UNSUPPORTED: read it with rte_image_read_bgr
 * and convert with rte_bgr_to_gray, which matches cv::cvtColor. */
RTE_API rte_status rte_image_read_gray(rte_image_reader *reader, const char *path,
                                       const rte_image_u8 *dst, char *msg, size_t msg_size);

/* Whether a file name ends in an image extension the readers take (.png,
 * .jpg, .jpeg, .pgm, .ppm, .pnm; any case): how directories of frames are
 * listed. The readers themselves go by content, not by name. */
RTE_API bool rte_image_path_has_image_extension(const char *path);

/* Writers; the format comes from the extension of `path` (case-insensitive).
 * Any stride. The file is written whole or an error is returned (a partial
 * file may remain). Writers are not for per-frame use: PNG encoding
 * allocates (libspng, and one row for BGR -> RGB).
 *   grey:  .pgm (P5), .png (8-bit grey), .npy (|u1, shape (h, w))
 *   bgr:   .ppm (P6), .png (8-bit RGB),  .npy (|u1, shape (h, w, 3), BGR order)
 *   s16:   .npy (<i2, shape (h, w)) */
RTE_API rte_status rte_image_write_gray(const char *path, const rte_image_u8 *img, char *msg,
                                        size_t msg_size);
RTE_API rte_status rte_image_write_bgr(const char *path, const rte_image_u8c3 *img, char *msg,
                                       size_t msg_size);
RTE_API rte_status rte_image_write_s16(const char *path, const rte_image_s16 *img, char *msg,
                                       size_t msg_size);

#ifdef __cplusplus
}
#endif
#endif
