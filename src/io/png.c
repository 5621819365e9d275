/* PNG through libspng, with the pixel semantics of OpenCV 4.6's imread
 * (libpng with strip_16, strip_alpha, palette_to_rgb and
 * expand_gray_1_2_4_to_8): 16-bit samples keep their high byte, alpha and
 * tRNS are dropped, palettes are expanded (indices beyond the palette are
 * black, as in libpng's zeroed 256-entry palette), 1/2/4-bit grey is scaled
 * by 255, 85 and 17. No gamma or colour management.
 *
 * Scanlines are decoded one at a time in the file's own format (SPNG_FMT_RAW)
 * into the reader's row buffer and converted here; interlaced images are
 * scattered pass by pass, so no whole-image buffer is needed. */
#include <spng.h>
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"

/* Ancillary chunks (text, ICC profiles) are not used: bound what libspng
 * may keep of them. */
enum { PNG_CHUNK_LIMIT = 1 << 24, PNG_CACHE_LIMIT = 1 << 26 };

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* CRC-32 of PNG chunks, continued over pieces: start with crc = 0. Only
 * headers and small chunks go through it (libspng checks the pixel data). */
static uint32_t crc32_update(uint32_t crc, const uint8_t *p, size_t n)
{
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

/* The CRC of the chunk at pos (type and data) equals the stored one. */
static int chunk_crc_ok(FILE *f, long pos, uint32_t len)
{
    uint8_t b[256];
    uint32_t crc = 0;
    long at = pos + 4, end = pos + 8 + (long)len;
    while (at < end) {
        size_t n = end - at < (long)sizeof b ? (size_t)(end - at) : sizeof b;
        if (!io_read_at(f, at, b, n))
            return 0;
        crc = crc32_update(crc, b, n);
        at += (long)n;
    }
    return io_read_at(f, end, b, 4) && be32(b) == crc;
}

/* Walks the chunk headers to IEND. libspng stops reading once the pixels
 * are done, but libpng (OpenCV) reads on to IEND and fails on a file cut
 * after its pixel data: so does this. On the way it finds the EXIF
 * orientation as OpenCV 4.6 does: the first eXIf chunk that libpng keeps
 * (good CRC, "II" or "MM"), before or after the image data. */
static rte_status walk_chunks(FILE *f, const io_msg *m, int *orientation)
{
    long pos = 8;
    uint8_t b[8];
    *orientation = 1;
    int have_exif = 0;
    for (;;) {
        if (!io_read_at(f, pos, b, 8))
            return io_fail(m, RTE_ERR_TRUNCATED,
                           "truncated PNG: the file ends at byte %ld, before IEND", pos);
        uint32_t len = be32(b);
        if (len > 0x7FFFFFFFu)
            return io_fail(m, RTE_ERR_CORRUPT, "corrupt PNG: chunk length %u at byte %ld",
                           (unsigned)len, pos);
        if (memcmp(b + 4, "IEND", 4) == 0) {
            if (len != 0)
                return io_fail(m, RTE_ERR_CORRUPT, "corrupt PNG: IEND has length %u",
                               (unsigned)len);
            if (!io_read_at(f, pos + 8, b, 4))
                return io_fail(m, RTE_ERR_TRUNCATED, "truncated PNG: the IEND chunk is cut");
            if (!chunk_crc_ok(f, pos, 0))
                return io_fail(m, RTE_ERR_CORRUPT, "corrupt PNG: IEND CRC mismatch");
            rewind(f);
            return RTE_OK;
        }
        if (!have_exif && memcmp(b + 4, "eXIf", 4) == 0 && len >= 2 &&
            io_read_at(f, pos + 8, b, 2) && b[0] == b[1] && (b[0] == 'I' || b[0] == 'M') &&
            chunk_crc_ok(f, pos, len)) {
            have_exif = 1;
            *orientation = io_exif_orientation(f, pos + 8, (long)len);
        }
        pos += 12 + (long)len;
    }
}

static int valid_depth(int color_type, int depth)
{
    switch (color_type) {
    case 0: return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3: return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6: return depth == 8 || depth == 16;
    default: return 0;
    }
}

rte_status png_probe(FILE *f, const io_msg *m, rte_image_info *info)
{
    uint8_t h[33];
    size_t n = fread(h, 1, sizeof h, f);
    if (n < sizeof h)
        return io_fail(m, RTE_ERR_TRUNCATED, "truncated: PNG header cut after %zu of 33 bytes", n);
    if (be32(h + 8) != 13 || memcmp(h + 12, "IHDR", 4) != 0)
        return io_fail(m, RTE_ERR_CORRUPT, "corrupt PNG: the first chunk is not a 13-byte IHDR");
    if (crc32_update(0, h + 12, 17) != be32(h + 29))
        return io_fail(m, RTE_ERR_CORRUPT, "corrupt PNG: IHDR CRC mismatch");
    uint32_t w = be32(h + 16), ht = be32(h + 20);
    int depth = h[24], color_type = h[25];
    if (w == 0 || ht == 0 || w > 0x7FFFFFFFu || ht > 0x7FFFFFFFu)
        return io_fail(m, RTE_ERR_FORMAT, "bad PNG header: size %ux%u", (unsigned)w, (unsigned)ht);
    if (!valid_depth(color_type, depth))
        return io_fail(m, RTE_ERR_FORMAT, "bad PNG header: colour type %d with bit depth %d",
                       color_type, depth);
    if (h[26] != 0 || h[27] != 0 || h[28] > 1)
        return io_fail(m, RTE_ERR_FORMAT,
                       "bad PNG header: unknown compression, filter or interlace method");
    if (w > RTE_MAX_SIDE || ht > RTE_MAX_SIDE)
        return io_fail(m, RTE_ERR_TOO_LARGE, "size %ux%u exceeds the maximum side %d", (unsigned)w,
                       (unsigned)ht, RTE_MAX_SIDE);
    int orientation;
    rte_status st = walk_chunks(f, m, &orientation);
    if (st != RTE_OK)
        return st;
    return io_set_info(info, (int32_t)w, (int32_t)ht, orientation,
                       (color_type == 0 || color_type == 4) ? 1 : 3, RTE_FILE_PNG);
}

static rte_status spng_status(const io_msg *m, int err)
{
    rte_status st;
    switch (err) {
    case SPNG_IO_EOF:
    case SPNG_EIDAT_TOO_SHORT:
    case SPNG_EOF: st = RTE_ERR_TRUNCATED; break;
    case SPNG_IO_ERROR:
    case SPNG_EIO: st = RTE_ERR_IO; break;
    case SPNG_EMEM: st = RTE_ERR_NO_MEMORY; break;
    case SPNG_EUSER_WIDTH:
    case SPNG_EUSER_HEIGHT:
    case SPNG_ECHUNK_LIMITS: st = RTE_ERR_TOO_LARGE; break;
    default: st = RTE_ERR_CORRUPT; break;
    }
    if (st == RTE_ERR_TRUNCATED)
        return io_fail(m, st, "truncated PNG: %s", spng_strerror(err));
    return io_fail(m, st, "corrupt PNG: %s", spng_strerror(err));
}

/* n pixels of a raw scanline -> 8-bit grey (out_channels 1) or RGB (3). */
static void convert_scanline(const uint8_t *restrict raw, uint8_t *restrict out, uint32_t n,
                             int color_type, int depth, const uint8_t (*plte)[3])
{
    if (depth < 8) { /* grey or palette, packed from the most significant bit */
        int per_byte = 8 / depth, mask = (1 << depth) - 1;
        int scale = depth == 1 ? 255 : depth == 2 ? 85 : 17;
        for (uint32_t i = 0; i < n; i++) {
            int shift = 8 - depth * (int)(i % (uint32_t)per_byte + 1);
            int v = (raw[i / (uint32_t)per_byte] >> shift) & mask;
            if (color_type == 0) {
                out[i] = (uint8_t)(v * scale);
            } else {
                memcpy(out + 3 * i, plte[v], 3);
            }
        }
        return;
    }
    int bytes = depth / 8; /* a 16-bit sample keeps its first (high) byte */
    switch (color_type) {
    case 0:
    case 4: {
        int step = bytes * (color_type == 4 ? 2 : 1);
        for (uint32_t i = 0; i < n; i++)
            out[i] = raw[(size_t)i * step];
        break;
    }
    case 2:
    case 6: {
        int step = bytes * (color_type == 6 ? 4 : 3);
        for (uint32_t i = 0; i < n; i++) {
            const uint8_t *p = raw + (size_t)i * step;
            out[3 * i] = p[0];
            out[3 * i + 1] = p[bytes];
            out[3 * i + 2] = p[2 * bytes];
        }
        break;
    }
    case 3:
        for (uint32_t i = 0; i < n; i++)
            memcpy(out + 3 * i, plte[raw[i]], 3);
        break;
    default: break;
    }
}

/* Converted pixels (grey or RGB) to target columns x0, x0 + dx, ... of row y. */
static void scatter(const io_target *t, int32_t y, const uint8_t *px, int px_channels, uint32_t n,
                    uint32_t x0, uint32_t dx)
{
    if (dx == 1) {
        if (px_channels == 1)
            io_put_gray_row(t, y, px);
        else
            io_put_rgb_row(t, y, px);
        return;
    }
    uint8_t *d = io_target_row(t, y);
    for (uint32_t i = 0; i < n; i++) {
        uint8_t *o = d + (size_t)(x0 + i * dx) * (size_t)t->channels;
        if (px_channels == 3) {
            o[0] = px[3 * i + 2];
            o[1] = px[3 * i + 1];
            o[2] = px[3 * i];
        } else if (t->channels == 3) {
            o[0] = o[1] = o[2] = px[i];
        } else {
            o[0] = px[i];
        }
    }
}

static rte_status decode_rows(spng_ctx *ctx, rte_image_reader *r, const io_msg *m,
                              const io_target *dst)
{
    struct spng_ihdr ihdr;
    int err = spng_get_ihdr(ctx, &ihdr);
    if (err)
        return spng_status(m, err);
    if ((int32_t)ihdr.width != dst->width || (int32_t)ihdr.height != dst->height)
        return io_fail(m, RTE_ERR_SIZE, "changed while being read");

    uint8_t plte[256][3];
    memset(plte, 0, sizeof plte);
    if (ihdr.color_type == 3) {
        struct spng_plte p;
        err = spng_get_plte(ctx, &p);
        if (err)
            return spng_status(m, err);
        for (uint32_t i = 0; i < p.n_entries && i < 256; i++) {
            plte[i][0] = p.entries[i].red;
            plte[i][1] = p.entries[i].green;
            plte[i][2] = p.entries[i].blue;
        }
    }

    err = spng_decode_image(ctx, NULL, 0, SPNG_FMT_RAW, SPNG_DECODE_PROGRESSIVE);
    if (err)
        return spng_status(m, err);

    static const uint8_t x_start[7] = {0, 4, 0, 2, 0, 1, 0};
    static const uint8_t x_step[7] = {8, 8, 4, 4, 2, 2, 1};
    int samples = ihdr.color_type == 2   ? 3
                  : ihdr.color_type == 4 ? 2
                  : ihdr.color_type == 6 ? 4
                                         : 1;
    size_t raw_capacity = (size_t)r->max_width * 8 + 8;
    uint8_t *raw = r->row, *px = r->row + raw_capacity;
    int px_channels = (ihdr.color_type == 0 || ihdr.color_type == 4) ? 1 : 3;
    for (;;) {
        struct spng_row_info ri;
        err = spng_get_row_info(ctx, &ri);
        if (err == SPNG_EOI)
            break;
        if (err)
            return spng_status(m, err);
        int pass = ihdr.interlace_method ? ri.pass : 6;
        uint32_t x0 = ihdr.interlace_method ? x_start[pass] : 0;
        uint32_t dx = ihdr.interlace_method ? x_step[pass] : 1;
        uint32_t n = (ihdr.width - x0 + dx - 1) / dx;
        size_t len = ((size_t)n * (size_t)(samples * ihdr.bit_depth) + 7) / 8;
        err = spng_decode_scanline(ctx, raw, len);
        if (err && err != SPNG_EOI)
            return spng_status(m, err);
        convert_scanline(raw, px, n, ihdr.color_type, ihdr.bit_depth, (const uint8_t(*)[3])plte);
        scatter(dst, (int32_t)ri.row_num, px, px_channels, n, x0, dx);
        if (err == SPNG_EOI)
            break;
    }
    /* Read on to IEND, as libpng's png_read_end does for OpenCV: a file cut
     * after its pixel data is truncated. */
    err = spng_decode_chunks(ctx);
    if (err)
        return spng_status(m, err);
    return RTE_OK;
}

rte_status png_decode(rte_image_reader *r, FILE *f, const io_msg *m, const io_target *dst)
{
    int orientation;
    rte_status st = walk_chunks(f, m, &orientation);
    if (st != RTE_OK)
        return st;
    /* An EXIF-turned image is decoded into the reader's image buffer first. */
    io_target coded = *dst;
    if (orientation != 1) {
        int swap = orientation >= 5;
        coded.buf = r->pixels;
        coded.width = swap ? dst->height : dst->width;
        coded.height = swap ? dst->width : dst->height;
        coded.stride = (size_t)coded.width * (size_t)dst->channels;
    }
    spng_ctx *ctx = spng_ctx_new(0);
    if (!ctx)
        return io_fail(m, RTE_ERR_NO_MEMORY, "out of memory for the PNG decoder");
    int err = spng_set_png_file(ctx, f);
    /* The reader's maxima hold for the displayed size; the pixel buffers
     * were checked for that, so either side may take the larger maximum. */
    uint32_t max_side = (uint32_t)(r->max_width > r->max_height ? r->max_width : r->max_height);
    if (!err)
        err = spng_set_image_limits(ctx, max_side, max_side);
    if (!err)
        err = spng_set_chunk_limits(ctx, PNG_CHUNK_LIMIT, PNG_CACHE_LIMIT);
    /* As libpng: a bad CRC in a critical chunk is an error, in an ancillary
     * chunk the chunk is dropped. */
    if (!err)
        err = spng_set_crc_action(ctx, SPNG_CRC_ERROR, SPNG_CRC_DISCARD);
    st = err ? spng_status(m, err) : decode_rows(ctx, r, m, &coded);
    spng_ctx_free(ctx);
    if (st == RTE_OK && orientation != 1)
        io_reorient(coded.buf, coded.width, coded.height, dst->channels, orientation, dst);
    return st;
}

/* Writes 8-bit grey or RGB (from BGR rows) progressively, row by row. */
rte_status png_write(FILE *f, const io_msg *m, const uint8_t *buf, size_t stride, int32_t w,
                     int32_t h, int channels)
{
    spng_ctx *ctx = spng_ctx_new(SPNG_CTX_ENCODER);
    uint8_t *rgb = channels == 3 ? malloc((size_t)w * 3) : NULL;
    rte_status st = RTE_OK;
    if (!ctx || (channels == 3 && !rgb)) {
        st = io_fail(m, RTE_ERR_NO_MEMORY, "out of memory for the PNG encoder");
        goto done;
    }
    struct spng_ihdr ihdr = {(uint32_t)w, (uint32_t)h, 8, (uint8_t)(channels == 3 ? 2 : 0),
                             0,           0,           0};
    int err = spng_set_png_file(ctx, f);
    if (!err)
        err = spng_set_ihdr(ctx, &ihdr);
    if (!err)
        err = spng_encode_image(ctx, NULL, 0, SPNG_FMT_PNG,
                                SPNG_ENCODE_PROGRESSIVE | SPNG_ENCODE_FINALIZE);
    size_t row_bytes = (size_t)w * (size_t)channels;
    for (int32_t y = 0; !err && y < h; y++) {
        const uint8_t *row = buf + (size_t)y * stride;
        if (channels == 3) {
            for (int32_t x = 0; x < w; x++) {
                rgb[3 * x] = row[3 * x + 2];
                rgb[3 * x + 1] = row[3 * x + 1];
                rgb[3 * x + 2] = row[3 * x];
            }
            row = rgb;
        }
        err = spng_encode_row(ctx, row, row_bytes);
        if (err == SPNG_EOI && y == h - 1)
            err = 0;
    }
    if (err)
        st = io_fail(m, err == SPNG_IO_ERROR ? RTE_ERR_IO : RTE_ERR_ARGUMENT,
                     "cannot write PNG: %s", spng_strerror(err));
done:
    free(rgb);
    spng_ctx_free(ctx);
    return st;
}
