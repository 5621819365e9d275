/* JPEG through libjpeg-turbo's TurboJPEG API, decoded as OpenCV 4.6's
 * imread does with the same library: the accurate integer IDCT (JDCT_ISLOW),
 * smooth ("fancy") chroma upsampling, YCbCr -> RGB in libjpeg's integer
 * tables, grey replicated for BGR output, and the EXIF orientation of the
 * first APP1 segment applied afterwards (OpenCV's ExifReader reads the first
 * APP1 segment whatever it holds, and IFD0's orientation tag).
 *
 * Stricter than OpenCV: libjpeg's warnings (a file cut short, which libjpeg
 * pads with grey, or damaged entropy data) are errors here. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <turbojpeg.h>

#include "io_internal.h"

typedef struct jpeg_header {
    int32_t width, height; /* as coded, before reorientation */
    int components;
    int orientation; /* 1..8, 1 when absent or unknown */
} jpeg_header;

void *jpeg_decoder_new(void) { return tjInitDecompress(); }

void jpeg_decoder_free(void *tj)
{
    if (tj)
        tjDestroy(tj);
}

size_t jpeg_max_file_bytes(int32_t max_width, int32_t max_height)
{
    unsigned long n = tjBufSize(max_width, max_height, TJSAMP_444);
    return (n == (unsigned long)-1 ? (size_t)max_width * (size_t)max_height * 6 : (size_t)n) +
           ((size_t)1 << 20);
}

static bool is_sof(int marker)
{
    return (marker >= 0xC0 && marker <= 0xCF) && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

/* Walks the markers from SOI to the first SOS: frame size, components and
 * the orientation from the first APP1. */
static rte_status read_header(FILE *f, const io_msg *m, jpeg_header *h)
{
    uint8_t b[8];
    long pos = 2, app1 = -1, app1_size = 0;
    int have_sof = 0;
    h->orientation = 1;
    if (!io_read_at(f, 0, b, 2) || b[0] != 0xFF || b[1] != 0xD8)
        return io_fail(m, RTE_ERR_FORMAT, "not a JPEG file (no SOI marker)");
    for (;;) {
        if (!io_read_at(f, pos, b, 2))
            return io_fail(m, RTE_ERR_TRUNCATED,
                           "truncated JPEG: the file ends in the headers at byte %ld", pos);
        if (b[0] != 0xFF)
            return io_fail(m, RTE_ERR_CORRUPT,
                           "corrupt JPEG: expected a marker at byte %ld, found 0x%02x", pos, b[0]);
        int marker = b[1];
        if (marker == 0xFF) { /* fill byte */
            pos++;
            continue;
        }
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
            pos += 2;
            continue;
        }
        if (marker == 0xD8 || marker == 0xD9 || marker == 0x00)
            return io_fail(m, RTE_ERR_CORRUPT, "corrupt JPEG: unexpected marker 0x%02x at byte %ld",
                           marker, pos);
        if (!io_read_at(f, pos + 2, b, 2))
            return io_fail(m, RTE_ERR_TRUNCATED,
                           "truncated JPEG: the file ends in the headers at byte %ld", pos);
        long len = (long)(b[0] << 8 | b[1]);
        if (len < 2)
            return io_fail(m, RTE_ERR_CORRUPT,
                           "corrupt JPEG: marker 0x%02x at byte %ld has length %ld", marker, pos,
                           len);
        if (marker == 0xDA)
            break;
        if (is_sof(marker)) {
            if (len < 8 || !io_read_at(f, pos + 4, b, 6))
                return len < 8 ? io_fail(m, RTE_ERR_CORRUPT, "corrupt JPEG: short frame header")
                               : io_fail(m, RTE_ERR_TRUNCATED,
                                         "truncated JPEG: the frame header is cut");
            if (have_sof)
                return io_fail(m, RTE_ERR_CORRUPT, "corrupt JPEG: two frame headers");
            if (marker == 0xC3 || marker == 0xC7 || marker == 0xCB || marker == 0xCF)
                return io_fail(m, RTE_ERR_UNSUPPORTED, "lossless JPEG is not supported");
            if (b[0] != 8)
                return io_fail(m, RTE_ERR_UNSUPPORTED, "%d-bit JPEG samples are not supported",
                               b[0]);
            h->height = b[1] << 8 | b[2];
            h->width = b[3] << 8 | b[4];
            h->components = b[5];
            have_sof = 1;
        } else if (marker == 0xE1 && app1 < 0) {
            app1 = pos + 4;
            app1_size = len - 2;
        }
        pos += 2 + len;
    }
    if (!have_sof)
        return io_fail(m, RTE_ERR_CORRUPT, "corrupt JPEG: no frame header before the scan");
    if (h->width == 0 || h->height == 0)
        return io_fail(m, RTE_ERR_UNSUPPORTED,
                       "JPEG with size %dx%d (zero or set by DNL) is not supported", (int)h->width,
                       (int)h->height);
    if (h->width > RTE_MAX_SIDE || h->height > RTE_MAX_SIDE)
        return io_fail(m, RTE_ERR_TOO_LARGE, "size %dx%d exceeds the maximum side %d",
                       (int)h->width, (int)h->height, RTE_MAX_SIDE);
    if (h->components != 1 && h->components != 3)
        return io_fail(m, RTE_ERR_UNSUPPORTED, "JPEG with %d components (CMYK?) is not supported",
                       h->components);
    if (app1 >= 0)
        h->orientation = app1_size > 6 ? io_exif_orientation(f, app1 + 6, app1_size - 6) : 1;
    return RTE_OK;
}

rte_status jpeg_probe(FILE *f, const io_msg *m, rte_image_info *info)
{
    jpeg_header h = {0};
    rte_status st = read_header(f, m, &h);
    if (st != RTE_OK)
        return st;
    return io_set_info(info, h.width, h.height, h.orientation, h.components == 1 ? 1 : 3,
                       RTE_FILE_JPEG);
}

rte_status jpeg_decode(rte_image_reader *r, FILE *f, const io_msg *m, const io_target *dst)
{
    jpeg_header h = {0};
    rte_status st = read_header(f, m, &h);
    if (st != RTE_OK)
        return st;
    if (fseek(f, 0, SEEK_END) != 0)
        return io_fail_errno(m, RTE_ERR_IO, "cannot seek");
    long size = ftell(f);
    if (size < 0)
        return io_fail_errno(m, RTE_ERR_IO, "cannot tell the size");
    if ((unsigned long)size > r->file_capacity)
        return io_fail(m, RTE_ERR_TOO_LARGE, "the file is %ld bytes, the reader holds at most %zu",
                       size, r->file_capacity);
    rewind(f);
    if (fread(r->file, 1, (size_t)size, f) != (size_t)size)
        return io_fail_errno(m, RTE_ERR_IO, "read error");

    /* The frame size comes from our own header walk: tjDecompressHeader3
     * is not used because after an error it leaves the handle mid-header,
     * and the next file would fail. */
    int w = h.width, ht = h.height;
    tjhandle tj = r->tj;
    if (!tj)
        return io_fail(m, RTE_ERR_NO_MEMORY,
                       "no JPEG decoder (out of memory after an earlier error)");

    int pf = dst->channels == 1 ? TJPF_GRAY : TJPF_BGR;
    /* Warnings (e.g. premature end of data) are errors; progressive files
     * are limited to 500 scans (a known denial-of-service guard). */
    int flags = TJFLAG_ACCURATEDCT | TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS;
    int rc;
    if (h.orientation == 1) {
        rc = tjDecompress2(tj, r->file, (unsigned long)size, dst->buf, w, (int)dst->stride, ht, pf,
                           flags);
    } else {
        rc = tjDecompress2(tj, r->file, (unsigned long)size, r->pixels, w, w * dst->channels, ht,
                           pf, flags);
        if (rc == 0)
            io_reorient(r->pixels, w, ht, dst->channels, h.orientation, dst);
    }
    if (rc != 0) {
        const char *text = tjGetErrorStr2(tj);
        bool truncated = strstr(text, "Premature end") != NULL;
        st = io_fail(m, truncated ? RTE_ERR_TRUNCATED : RTE_ERR_CORRUPT, "%s JPEG: %s",
                     truncated ? "truncated" : "corrupt", text);
        /* A fresh handle after an error, so no state of the bad file can
         * affect the next one (the only allocation on this path). */
        tjDestroy(tj);
        r->tj = tjInitDecompress();
        return st;
    }
    return RTE_OK;
}
