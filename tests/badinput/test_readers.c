/* Bad input for the image readers: truncated files of every format (cut at
 * every byte of small files), wrong magic numbers, impossible headers, huge
 * sizes on tiny bodies, corrupt PNG chunks and corrupt JPEG markers. Each
 * must give an error status and a message naming the file; the sanitizer
 * build checks that nothing crashes, reads out of bounds or leaks. The bad
 * files are made here from good ones. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <turbojpeg.h>
#include <zlib.h>

#include "rtedge/imageio.h"

#define ANY_ERROR (-1)

static char dir[64];
static char path[128];
static rte_image_reader *reader;
static uint8_t *pixels; /* room for the reader's largest image, BGR */
enum { MAX_SIDE = 640 };

static uint32_t seed = 2463534242u;
static uint32_t rnd(void)
{
    seed ^= seed << 13;
    seed ^= seed >> 17;
    seed ^= seed << 5;
    return seed;
}

static int setup(void **state)
{
    snprintf(dir, sizeof dir, "/tmp/rtedge_badinput_XXXXXX");
    if (!mkdtemp(dir))
        return -1;
    snprintf(path, sizeof path, "%s/bad-file.img", dir);
    reader = rte_image_reader_create(MAX_SIDE, MAX_SIDE);
    pixels = malloc((size_t)MAX_SIDE * MAX_SIDE * 3);
    return reader && pixels ? 0 : -1;
}

static int teardown(void **state)
{
    rte_image_reader_destroy(reader);
    free(pixels);
    remove(path);
    return rmdir(dir);
}

static void write_file(const uint8_t *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* Every reading function on the current file: each must fail (with
 * `expected` when it is not ANY_ERROR) and name the file. Returns the
 * status of the full read. */
static rte_status check_fails(const uint8_t *data, size_t n, int expected, const char *what)
{
    write_file(data, n);
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_info info;
    rte_status st = rte_image_read(reader, path, pixels, (size_t)MAX_SIDE * MAX_SIDE * 3, &info,
                                   msg, sizeof msg);
    if (st == RTE_OK || (expected != ANY_ERROR && (int)st != expected) ||
        !strstr(msg, "bad-file.img: "))
        fail_msg("%s (%zu bytes): status %d, message \"%s\"", what, n, (int)st, msg);

    /* Through a view too, sized from the probe when the header is fine. */
    rte_status pst = rte_image_probe(path, &info, msg, sizeof msg);
    if (pst != RTE_OK && !strstr(msg, "bad-file.img: "))
        fail_msg("%s: probe message \"%s\"", what, msg);
    if (pst == RTE_OK && info.width <= MAX_SIDE && info.height <= MAX_SIDE) {
        rte_image_u8c3 dst = {info.width, info.height, info.width * 3, pixels};
        rte_status st2 = rte_image_read_bgr(reader, path, &dst, msg, sizeof msg);
        if (st2 == RTE_OK || !strstr(msg, "bad-file.img: "))
            fail_msg("%s: read_bgr status %d, message \"%s\"", what, (int)st2, msg);
    }
    return st;
}

static void check_fails_str(const char *text, int expected)
{
    check_fails((const uint8_t *)text, strlen(text), expected, text);
}

/* Each prefix of data [from, n) must fail. */
static void check_every_cut(const uint8_t *data, size_t from, size_t n, const char *what)
{
    for (size_t cut = from; cut < n; cut++)
        check_fails(data, cut, ANY_ERROR, what);
}

/* ---- good files to start from ---- */

typedef struct blob {
    uint8_t *data;
    size_t size;
} blob;

static blob load(const char *file)
{
    blob b = {NULL, 0};
    FILE *f = fopen(file, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    b.size = (size_t)ftell(f);
    rewind(f);
    b.data = malloc(b.size);
    assert_non_null(b.data);
    assert_int_equal(fread(b.data, 1, b.size, f), b.size);
    fclose(f);
    return b;
}

/* A small image written by rte_image_write_* and read back as bytes. */
static blob make_file(const char *name, int32_t w, int32_t h, int channels)
{
    uint8_t *px = malloc((size_t)w * h * 3);
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        px[i] = (uint8_t)(rnd() >> 7 & 0x3F); /* smooth enough to compress */
    char file[160];
    snprintf(file, sizeof file, "%s/%s", dir, name);
    char msg[RTE_IO_MESSAGE_SIZE];
    if (channels == 1) {
        rte_image_u8 img = {w, h, w, px};
        assert_int_equal(rte_image_write_gray(file, &img, msg, sizeof msg), RTE_OK);
    } else {
        rte_image_u8c3 img = {w, h, w * 3, px};
        assert_int_equal(rte_image_write_bgr(file, &img, msg, sizeof msg), RTE_OK);
    }
    free(px);
    blob b = load(file);
    remove(file);
    return b;
}

static blob make_jpeg(int32_t w, int32_t h, int subsamp, int flags)
{
    uint8_t *px = malloc((size_t)w * h * 3);
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        px[i] = (uint8_t)rnd();
    tjhandle tj = tjInitCompress();
    unsigned char *jpg = NULL;
    unsigned long size = 0;
    assert_int_equal(tjCompress2(tj, px, w, w * 3, h, TJPF_BGR, &jpg, &size, subsamp, 75, flags),
                     0);
    blob b = {malloc(size), size};
    memcpy(b.data, jpg, size);
    tjFree(jpg);
    tjDestroy(tj);
    free(px);
    return b;
}

/* The good file really is good: the mutations below are what fails. */
static void assert_reads(const blob *b)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_info info;
    write_file(b->data, b->size);
    if (rte_image_read(reader, path, pixels, (size_t)MAX_SIDE * MAX_SIDE * 3, &info, msg,
                       sizeof msg) != RTE_OK)
        fail_msg("good file fails: %s", msg);
}

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* Offset of the first chunk of `type` in a PNG, 0 when absent. */
static size_t find_chunk(const blob *b, const char *type)
{
    for (size_t pos = 8; pos + 12 <= b->size; pos += 12 + be32(b->data + pos))
        if (memcmp(b->data + pos + 4, type, 4) == 0)
            return pos;
    return 0;
}

static void fix_crc(uint8_t *png, size_t chunk)
{
    uint32_t len = be32(png + chunk);
    put_be32(png + chunk + 8 + len, (uint32_t)crc32(0, png + chunk + 4, len + 4));
}

/* ---- the tests ---- */

static void empty_and_unknown_files(void **state)
{
    check_fails((const uint8_t *)"", 0, RTE_ERR_TRUNCATED, "empty");
    check_fails_str("P", RTE_ERR_FORMAT);
    check_fails_str("hello world", RTE_ERR_FORMAT);
    check_fails_str("GIF89a\x01\x00\x01\x00", RTE_ERR_FORMAT);
    check_fails_str("BM\x3a\x00\x00\x00", RTE_ERR_FORMAT);
    check_fails((const uint8_t *)"\x89PNX\r\n\x1a\n0000", 12, RTE_ERR_FORMAT, "bad PNG signature");
    check_fails((const uint8_t *)"\x89PN", 3, RTE_ERR_TRUNCATED, "cut PNG signature");
    check_fails((const uint8_t *)"\xff", 1, RTE_ERR_TRUNCATED, "one 0xff byte");
    check_fails((const uint8_t *)"\xff\xd9", 2, RTE_ERR_FORMAT, "EOI only");
    uint8_t noise[300];
    for (int i = 0; i < 50; i++) {
        for (size_t k = 0; k < sizeof noise; k++)
            noise[k] = (uint8_t)rnd();
        check_fails(noise, sizeof noise, ANY_ERROR, "noise");
    }
}

static void pnm_headers(void **state)
{
    check_fails_str("P1 2 1\n1 0\n", RTE_ERR_UNSUPPORTED);
    check_fails_str("P4 8 1\n\x80", RTE_ERR_UNSUPPORTED);
    check_fails_str("P7\nWIDTH 1\n", RTE_ERR_UNSUPPORTED);
    check_fails_str("P8 1 1 255\n\x01", RTE_ERR_FORMAT);
    check_fails_str("P5#c\n1 1 255\n\x01", RTE_ERR_FORMAT);
    check_fails_str(" P5 1 1 255\n\x01", RTE_ERR_FORMAT);
    check_fails_str("P5 1 1 0\n\x01", RTE_ERR_FORMAT);            /* maxval 0 */
    check_fails_str("P5 1 1 256\n\x01\x02", RTE_ERR_UNSUPPORTED); /* 16-bit */
    check_fails_str("P5 1 1 65536\n\x01\x02", RTE_ERR_FORMAT);
    check_fails_str("P2 1 1 -1\n0\n", RTE_ERR_FORMAT);
    check_fails_str("P5 0 2 255\n", RTE_ERR_FORMAT); /* zero sizes */
    check_fails_str("P5 2 0 255\n", RTE_ERR_FORMAT);
    check_fails_str("P5 -3 2 255\n\x01", RTE_ERR_FORMAT); /* negative */
    check_fails_str("P5 +3 2 255\n\x01", RTE_ERR_FORMAT);
    check_fails_str("P5 3x 2 255\n\x01", RTE_ERR_FORMAT); /* garbage */
    check_fails_str("P5 3 2 25z\n\x01", RTE_ERR_FORMAT);
    check_fails_str("P5 3.5 2 255\n\x01", RTE_ERR_FORMAT);
    check_fails_str("P5 65536 65536 255\n\x01\x02\x03", RTE_ERR_TOO_LARGE);
    check_fails_str("P5 4294967297 2 255\n\x01", RTE_ERR_TOO_LARGE); /* overflows 32 bits */
    check_fails_str("P6 99999999999999999999 1 255\n\x01", RTE_ERR_TOO_LARGE);
    check_fails_str("P5 30000 30000 255\n\x01\x02",
                    RTE_ERR_TOO_LARGE); /* valid, beyond the reader */
    check_fails_str("P2 2 1 255\n1 -2\n", RTE_ERR_FORMAT);
    check_fails_str("P2 2 1 255\n1 x\n", RTE_ERR_FORMAT);
    check_fails_str("P3 1 1 255\n1 2 3z\n", RTE_ERR_FORMAT);
    check_fails_str("P5 1 1 255", RTE_ERR_TRUNCATED); /* no byte after maxval */
    check_fails_str("P5 1 1 255#\n\x01", RTE_ERR_FORMAT);
}

static void pnm_truncated(void **state)
{
    blob pgm = make_file("t.pgm", 13, 7, 1), ppm = make_file("t.ppm", 9, 5, 3);
    assert_reads(&pgm);
    assert_reads(&ppm);
    check_every_cut(pgm.data, 0, pgm.size, "cut PGM");
    check_every_cut(ppm.data, 0, ppm.size, "cut PPM");
    /* The message counts what is there. */
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_info info;
    write_file(pgm.data, pgm.size - 5);
    assert_int_equal(rte_image_read(reader, path, pixels, 100, &info, msg, sizeof msg),
                     RTE_ERR_TRUNCATED);
    assert_non_null(strstr(msg, "bad-file.img: truncated: expected 91 pixel bytes, found 86"));

    /* A text PGM: every cut before the last value starts fails. */
    const char text[] = "P2\n# text\n3 2\n200\n0 10 20\n30 40 255\n";
    check_every_cut((const uint8_t *)text, 0, strlen(text) - 4, "cut P2");
    const char text3[] = "P3 2 1 255\n1 2 3 4 5 6\n";
    check_every_cut((const uint8_t *)text3, 0, strlen(text3) - 2, "cut P3");
    free(pgm.data);
    free(ppm.data);
}

static void png_truncated_and_corrupt(void **state)
{
    blob gray = make_file("t.png", 21, 9, 1), rgb = make_file("c.png", 12, 10, 3);
    assert_reads(&gray);
    assert_reads(&rgb);
    check_every_cut(gray.data, 0, gray.size, "cut grey PNG");
    check_every_cut(rgb.data, 0, rgb.size, "cut RGB PNG");

    uint8_t *p = malloc(rgb.size + 64);
    size_t ihdr = find_chunk(&rgb, "IHDR"), idat = find_chunk(&rgb, "IDAT"),
           iend = find_chunk(&rgb, "IEND");
    assert_true(ihdr && idat && iend);
    uint32_t idat_len = be32(rgb.data + idat);

    /* Bad CRCs: IHDR, IDAT, IEND. */
    size_t crcs[] = {ihdr + 8 + 13, idat + 8 + idat_len, iend + 8};
    for (int i = 0; i < 3; i++) {
        memcpy(p, rgb.data, rgb.size);
        p[crcs[i]] ^= 0x40;
        check_fails(p, rgb.size, RTE_ERR_CORRUPT, "bad CRC");
    }
    /* A flipped byte inside IDAT with its CRC fixed: zlib/filter/adler errors. */
    for (uint32_t k = 0; k < idat_len; k++) {
        memcpy(p, rgb.data, rgb.size);
        p[idat + 8 + k] ^= (uint8_t)(1u << (k % 8));
        fix_crc(p, idat);
        write_file(p, rgb.size);
        char msg[RTE_IO_MESSAGE_SIZE];
        rte_image_info info;
        rte_status st = rte_image_read(reader, path, pixels, (size_t)MAX_SIDE * MAX_SIDE * 3, &info,
                                       msg, sizeof msg);
        /* A flip in the filter bytes or literals may still decode: then fine. */
        if (st != RTE_OK && !strstr(msg, "bad-file.img: "))
            fail_msg("IDAT flip: %s", msg);
    }
    /* Bad chunk lengths: huge, beyond the file, 2^31 and more, zero IDAT. */
    const uint32_t lens[] = {0x7FFFFFFFu,     0x80000000u,  0xFFFFFFFFu,
                             idat_len + 1000, idat_len + 1, 0};
    for (int i = 0; i < 6; i++) {
        memcpy(p, rgb.data, rgb.size);
        put_be32(p + idat, lens[i]);
        check_fails(p, rgb.size, ANY_ERROR, "bad IDAT length");
    }
    memcpy(p, rgb.data, rgb.size);
    put_be32(p + ihdr, 14);
    check_fails(p, rgb.size, RTE_ERR_CORRUPT, "bad IHDR length");
    /* IHDR fields: zero and huge sizes, bad depth/colour type, interlace 2. */
    struct {
        size_t off;
        uint32_t value;
        int bytes, expected;
    } fields[] = {
        {8 + 8, 0, 4, RTE_ERR_FORMAT},        {8 + 12, 0, 4, RTE_ERR_FORMAT},
        {8 + 8, 65536, 4, RTE_ERR_TOO_LARGE}, {8 + 12, 0x80000000u, 4, RTE_ERR_FORMAT},
        {8 + 8, 30000, 4, RTE_ERR_TOO_LARGE}, {8 + 16, 3, 1, RTE_ERR_FORMAT},
        {8 + 17, 5, 1, RTE_ERR_FORMAT},       {8 + 18, 1, 1, RTE_ERR_FORMAT},
        {8 + 20, 2, 1, RTE_ERR_FORMAT},       {8 + 17, 3, 1, ANY_ERROR}, /* palette, no PLTE */
    };
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++) {
        memcpy(p, rgb.data, rgb.size);
        if (fields[i].bytes == 4)
            put_be32(p + fields[i].off, fields[i].value);
        else
            p[fields[i].off] = (uint8_t)fields[i].value;
        fix_crc(p, ihdr);
        check_fails(p, rgb.size, fields[i].expected, "bad IHDR field");
    }
    /* A 65536 x 65536 header on a tiny body. */
    memcpy(p, rgb.data, idat);
    put_be32(p + 16, 65536);
    put_be32(p + 20, 65536);
    fix_crc(p, ihdr);
    memcpy(p + idat, rgb.data + iend, 12);
    check_fails(p, idat + 12, RTE_ERR_TOO_LARGE, "65536 x 65536 PNG");
    /* IDAT missing: IHDR then IEND. */
    memcpy(p, rgb.data, idat);
    memcpy(p + idat, rgb.data + iend, 12);
    check_fails(p, idat + 12, ANY_ERROR, "no IDAT");
    /* IEND missing. */
    check_fails(rgb.data, iend, RTE_ERR_TRUNCATED, "no IEND");
    /* An unknown critical chunk before IDAT. */
    memcpy(p, rgb.data, idat);
    static const uint8_t crit[12] = {0, 0, 0, 0, 'X', 'y', 'Z', 'w', 0, 0, 0, 0};
    memcpy(p + idat, crit, 12);
    fix_crc(p, idat);
    memcpy(p + idat + 12, rgb.data + idat, rgb.size - idat);
    check_fails(p, rgb.size + 12, RTE_ERR_CORRUPT, "unknown critical chunk");
    free(p);
    free(gray.data);
    free(rgb.data);
}

static void jpeg_truncated_and_corrupt(void **state)
{
    blob jpg = make_jpeg(19, 11, TJSAMP_420, 0),
         prog = make_jpeg(17, 9, TJSAMP_444, TJFLAG_PROGRESSIVE);
    blob grey = make_jpeg(8, 8, TJSAMP_GRAY, 0);
    assert_reads(&jpg);
    assert_reads(&prog);
    assert_reads(&grey);
    check_every_cut(jpg.data, 0, jpg.size, "cut JPEG");
    check_every_cut(prog.data, 0, prog.size, "cut progressive JPEG");
    check_every_cut(grey.data, 0, grey.size, "cut grey JPEG");

    uint8_t *p = malloc(jpg.size + 16);
    /* Garbage after SOI. */
    for (int i = 0; i < 40; i++) {
        memcpy(p, jpg.data, jpg.size);
        for (size_t k = 2; k < 2 + 1 + rnd() % 40 && k < jpg.size; k++)
            p[k] = (uint8_t)rnd();
        check_fails(p, jpg.size, ANY_ERROR, "garbage after SOI");
    }
    /* Bad markers and segment lengths in the headers (before the scan). */
    size_t sos = 0, sof = 0, dqt = 0, dht = 0;
    for (size_t pos = 2; pos + 4 <= jpg.size;) {
        int m = jpg.data[pos + 1];
        if (m == 0xDA) {
            sos = pos;
            break;
        }
        if (m == 0xC0)
            sof = pos;
        if (m == 0xDB && !dqt)
            dqt = pos;
        if (m == 0xC4 && !dht)
            dht = pos;
        pos += 2 + (size_t)(jpg.data[pos + 2] << 8 | jpg.data[pos + 3]);
    }
    assert_true(sos && sof && dqt && dht);
    struct {
        size_t off;
        uint8_t value;
        int expected;
    } edits[] = {
        {dqt, 0x12, RTE_ERR_CORRUPT},     /* not a marker */
        {dqt + 1, 0xD8, RTE_ERR_CORRUPT}, /* SOI again */
        {dqt + 1, 0xD9, RTE_ERR_CORRUPT}, /* EOI in the headers */
        {dqt + 1, 0x00, RTE_ERR_CORRUPT}, /* stuffed zero */
        {dqt + 3, 0x00, ANY_ERROR},       /* length 0 or 1 */
        {dqt + 3, 0x01, ANY_ERROR},
        {dqt + 2, 0xFF, ANY_ERROR},           /* length beyond the file */
        {dht + 4, 0x37, ANY_ERROR},           /* bad table class/index */
        {sof + 1, 0xC3, RTE_ERR_UNSUPPORTED}, /* lossless */
        {sof + 4, 12, RTE_ERR_UNSUPPORTED},   /* 12-bit */
        {sof + 6, 0, RTE_ERR_UNSUPPORTED},    /* height 0 (DNL); the high byte is 0 */
        {sof + 8, 0, RTE_ERR_UNSUPPORTED},    /* width 0 */
        {sof + 5, 0xFF, RTE_ERR_TOO_LARGE},   /* 65291 rows */
        {sof + 7, 0xFF, RTE_ERR_TOO_LARGE},
        {sof + 9, 4, ANY_ERROR}, /* 4 components (length wrong) */
        {sof + 9, 0, ANY_ERROR},
        {sof + 11, 0x55, ANY_ERROR}, /* bad sampling factors */
        {sof + 12, 9, ANY_ERROR},    /* quantisation table 9 */
        {sos + 1, 0xC0, ANY_ERROR},  /* SOS turned into a second SOF */
        {sos + 5, 7, ANY_ERROR},     /* scan names a missing component */
        {sos + 6, 0x77, ANY_ERROR},  /* missing Huffman tables */
    };
    for (size_t i = 0; i < sizeof edits / sizeof edits[0]; i++) {
        memcpy(p, jpg.data, jpg.size);
        p[edits[i].off] = edits[i].value;
        char what[64];
        snprintf(what, sizeof what, "JPEG header edit %zu", i);
        check_fails(p, jpg.size, edits[i].expected, what);
    }
    /* A 65535 x 65535 frame header on a tiny body. */
    memcpy(p, jpg.data, jpg.size);
    p[sof + 5] = p[sof + 6] = p[sof + 7] = p[sof + 8] = 0xFF;
    check_fails(p, sos + 4, RTE_ERR_TOO_LARGE, "huge JPEG");
    /* No frame header at all: SOI then SOS. */
    memcpy(p, jpg.data, 2);
    memcpy(p + 2, jpg.data + sos, jpg.size - sos);
    check_fails(p, 2 + jpg.size - sos, RTE_ERR_CORRUPT, "no SOF");
    /* Garbage EXIF in an APP1 segment: whatever orientation comes out, no
     * read beyond the segment and no crash. */
    uint8_t *q = malloc(jpg.size + 80);
    for (int i = 0; i < 200; i++) {
        static const uint8_t head[14] = {0xFF, 0xD8, 0xFF, 0xE1, 0, 66,  'E',
                                         'x',  'i',  'f',  0,    0, 'I', 'I'};
        memcpy(q, head, sizeof head);
        if (i & 1)
            q[12] = q[13] = 'M';
        q[14] = (i & 1) ? 0 : 0x2A;
        q[15] = (i & 1) ? 0x2A : 0;
        for (int k = 16; k < 70; k++)
            q[k] = (uint8_t)(rnd() % 4 == 0 ? rnd() % 12 : rnd());
        memcpy(q + 70, jpg.data + 2, jpg.size - 2);
        write_file(q, jpg.size + 68);
        char msg[RTE_IO_MESSAGE_SIZE];
        rte_image_info info;
        rte_status st = rte_image_read(reader, path, pixels, (size_t)MAX_SIDE * MAX_SIDE * 3, &info,
                                       msg, sizeof msg);
        if (st != RTE_OK)
            fail_msg("garbage EXIF: %s", msg);
    }
    free(q);
    /* Entropy-coded data replaced with 0xFF runs and markers. */
    memcpy(p, jpg.data, jpg.size);
    size_t data = sos + 2 + (size_t)(jpg.data[sos + 2] << 8 | jpg.data[sos + 3]);
    for (size_t k = data; k + 2 < jpg.size; k += 2) {
        p[k] = 0xFF;
        p[k + 1] = (uint8_t)(0xC0 + k % 16);
    }
    check_fails(p, jpg.size, ANY_ERROR, "markers in the scan");
    free(p);
    free(jpg.data);
    free(prog.data);
    free(grey.data);
}

/* The real fixtures, cut at interesting points and with flipped bytes. */
static void real_files(void **state)
{
    const char *fixtures = getenv("RTE_FIXTURES_DIR");
    if (!fixtures)
        skip();
    const char *names[] = {"smarties.png", "stuff.jpg", "smarties.ppm"};
    for (int i = 0; i < 3; i++) {
        char file[512];
        snprintf(file, sizeof file, "%s/%s", fixtures, names[i]);
        blob b = load(file);
        assert_reads(&b);
        /* Header region byte by byte, then spaced cuts through the data. */
        check_every_cut(b.data, 0, b.size < 700 ? b.size : 700, names[i]);
        for (size_t cut = 700; cut < b.size; cut += 1 + b.size / 97)
            check_fails(b.data, cut, ANY_ERROR, names[i]);
        check_fails(b.data, b.size - 1, ANY_ERROR, names[i]);
        /* Random flips must not crash (some still decode). */
        uint8_t *p = malloc(b.size);
        for (int k = 0; k < 30; k++) {
            memcpy(p, b.data, b.size);
            for (int f = 0; f < 4; f++)
                p[rnd() % b.size] ^= (uint8_t)(1u << (rnd() % 8));
            write_file(p, b.size);
            char msg[RTE_IO_MESSAGE_SIZE];
            rte_image_info info;
            rte_status st = rte_image_read(reader, path, pixels, (size_t)MAX_SIDE * MAX_SIDE * 3,
                                           &info, msg, sizeof msg);
            if (st != RTE_OK && !strstr(msg, "bad-file.img: "))
                fail_msg("%s flipped: %s", names[i], msg);
        }
        free(p);
        free(b.data);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(empty_and_unknown_files),
        cmocka_unit_test(pnm_headers),
        cmocka_unit_test(pnm_truncated),
        cmocka_unit_test(png_truncated_and_corrupt),
        cmocka_unit_test(jpeg_truncated_and_corrupt),
        cmocka_unit_test(real_files),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
