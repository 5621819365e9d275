/* EXIF orientation as OpenCV 4.6 reads and applies it (ExifReader and
 * ExifTransform), shared by the JPEG and PNG readers. */
#include <string.h>

#include "io_internal.h"

/* Reads n bytes at absolute offset pos; 0 when the file is shorter. */
int io_read_at(FILE *f, long pos, uint8_t *out, size_t n)
{
    return fseek(f, pos, SEEK_SET) == 0 && fread(out, 1, n, f) == n;
}

int io_exif_orientation(FILE *f, long tiff, long len)
{
    uint8_t b[12];
    if (len < 8 || !io_read_at(f, tiff, b, 8))
        return 1;
    int le;
    if (b[0] == 'I' && b[1] == 'I')
        le = 1;
    else if (b[0] == 'M' && b[1] == 'M')
        le = 0;
    else
        return 1;
#define U16(p) (le ? (unsigned)((p)[0] | (p)[1] << 8) : (unsigned)((p)[0] << 8 | (p)[1]))
#define U32(p)                                                                       \
    (le ? ((uint32_t)(p)[0] | (uint32_t)(p)[1] << 8 | (uint32_t)(p)[2] << 16 |       \
           (uint32_t)(p)[3] << 24)                                                   \
        : ((uint32_t)(p)[0] << 24 | (uint32_t)(p)[1] << 16 | (uint32_t)(p)[2] << 8 | \
           (uint32_t)(p)[3]))
    if (U16(b + 2) != 0x2A)
        return 1;
    uint32_t ifd = U32(b + 4);
    if ((long)ifd + 2 > len || !io_read_at(f, tiff + (long)ifd, b, 2))
        return 1;
    unsigned count = U16(b);
    for (unsigned i = 0; i < count; i++) {
        long entry = (long)ifd + 2 + 12 * (long)i;
        if (entry + 10 > len || !io_read_at(f, tiff + entry, b, 10))
            return 1;
        if (U16(b) == 0x0112) {
            unsigned v = U16(b + 8);
            return v >= 1 && v <= 8 ? (int)v : 1;
        }
    }
    return 1;
#undef U16
#undef U32
}

/* dst = src turned as OpenCV's ExifTransform does: flips for 2-4, a
 * transpose followed by the same flips for 5-8. */
void io_reorient(const uint8_t *src, int32_t sw, int32_t sh, int c, int orientation,
                 const io_target *dst)
{
    ptrdiff_t sstride = (ptrdiff_t)sw * c;
    /* The source pixel of dst (0, y) and the steps per x and per y. */
    ptrdiff_t origin = 0, step_x = c, step_y = sstride;
    switch (orientation) {
    case 2:
        origin = (sw - 1) * c;
        step_x = -c;
        step_y = sstride;
        break;
    case 3:
        origin = (sh - 1) * sstride + (sw - 1) * c;
        step_x = -c;
        step_y = -sstride;
        break;
    case 4:
        origin = (sh - 1) * sstride;
        step_x = c;
        step_y = -sstride;
        break;
    case 5:
        origin = 0;
        step_x = sstride;
        step_y = c;
        break;
    case 6:
        origin = (sh - 1) * sstride;
        step_x = -sstride;
        step_y = c;
        break;
    case 7:
        origin = (sh - 1) * sstride + (sw - 1) * c;
        step_x = -sstride;
        step_y = -c;
        break;
    case 8:
        origin = (sw - 1) * c;
        step_x = sstride;
        step_y = -c;
        break;
    default: break;
    }
    const int32_t w = dst->width, h = dst->height; /* locals: byte stores could alias them */
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *s = src + origin + step_y * y;
        uint8_t *d = io_target_row(dst, y);
        for (int32_t x = 0; x < w; x++, s += step_x)
            memcpy(d + (size_t)x * (size_t)c, s, (size_t)c);
    }
}
