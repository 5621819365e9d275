/* Image files: write-then-read round trips in every format and odd stride,
 * header parsing, .npy layout, and argument errors. */
#include "unit.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "rtedge/imageio.h"

static char tmp_dir[64];
static char msg[RTE_IO_MESSAGE_SIZE];

static int setup_dir(void **state)
{
    snprintf(tmp_dir, sizeof tmp_dir, "/tmp/rtedge_test_io_XXXXXX");
    return mkdtemp(tmp_dir) ? 0 : -1;
}

static int remove_dir(void **state) { return rmdir(tmp_dir); }

static const char *tmp_path(const char *name)
{
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
    return path;
}

static void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static size_t read_bytes(const char *path, uint8_t *out, size_t cap)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    size_t n = fread(out, 1, cap, f);
    fclose(f);
    return n;
}

static void fill_random(uint8_t *buf, size_t n, uint32_t *seed)
{
    for (size_t i = 0; i < n; i++)
        buf[i] = (uint8_t)unit_rand(seed);
}

static rte_image_u8c3 unit_image_u8c3(int32_t w, int32_t h, int32_t pad)
{
    int32_t stride = 3 * w + pad;
    uint8_t *buf = test_malloc((size_t)stride * h);
    memset(buf, 0xEE, (size_t)stride * h);
    rte_image_u8c3 img = {w, h, stride, buf};
    return img;
}

static void assert_padding_u8c3(const rte_image_u8c3 *img)
{
    for (int32_t y = 0; y < img->height; y++)
        for (int32_t x = 3 * img->width; x < img->stride; x++)
            assert_int_equal(img->buf[(size_t)y * img->stride + x], 0xEE);
}

static const int32_t sizes[][2] = {{1, 1}, {1, 7},  {7, 1},  {2, 2},
                                   {3, 5}, {17, 3}, {67, 9}, {31, 40}};

static void gray_round_trips(void **state)
{
    uint32_t seed = 12345;
    rte_image_reader *r = rte_image_reader_create(80, 80);
    assert_non_null(r);
    const char *exts[] = {"g.pgm", "g.png", "G.PNG"};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int32_t w = sizes[s][0], h = sizes[s][1];
        rte_image_u8 src = unit_image_u8(w, h, (int32_t)(s % 5), 0);
        for (int32_t y = 0; y < h; y++)
            fill_random(rte_u8_row(&src, y), (size_t)w, &seed);
        for (size_t e = 0; e < 3; e++) {
            const char *path = tmp_path(exts[e]);
            assert_int_equal(rte_image_write_gray(path, &src, msg, sizeof msg), RTE_OK);
            assert_string_equal(msg, "");

            rte_image_info info;
            assert_int_equal(rte_image_probe(path, &info, msg, sizeof msg), RTE_OK);
            assert_int_equal(info.width, w);
            assert_int_equal(info.height, h);
            assert_int_equal(info.channels, 1);
            assert_int_equal(info.format, e == 0 ? RTE_FILE_PGM : RTE_FILE_PNG);

            rte_image_u8 back = unit_image_u8(w, h, 3, 0);
            assert_int_equal(rte_image_read_gray(r, path, &back, msg, sizeof msg), RTE_OK);
            for (int32_t y = 0; y < h; y++)
                assert_memory_equal(rte_u8_row(&back, y), rte_u8_row(&src, y), (size_t)w);
            unit_assert_padding_u8(&back);

            rte_image_u8c3 bgr = unit_image_u8c3(w, h, 5);
            assert_int_equal(rte_image_read_bgr(r, path, &bgr, msg, sizeof msg), RTE_OK);
            for (int32_t y = 0; y < h; y++)
                for (int32_t x = 0; x < w; x++)
                    for (int c = 0; c < 3; c++)
                        assert_int_equal(bgr.buf[(size_t)y * bgr.stride + 3 * x + c],
                                         rte_u8_row(&src, y)[x]);
            assert_padding_u8c3(&bgr);

            uint8_t packed[80 * 80];
            assert_int_equal(rte_image_read(r, path, packed, (size_t)w * h, &info, msg, sizeof msg),
                             RTE_OK);
            for (int32_t y = 0; y < h; y++)
                assert_memory_equal(packed + (size_t)y * w, rte_u8_row(&src, y), (size_t)w);
            assert_int_equal(remove(path), 0);
            test_free(bgr.buf);
            test_free(back.buf);
        }
        test_free(src.buf);
    }
    rte_image_reader_destroy(r);
}

static void bgr_round_trips(void **state)
{
    uint32_t seed = 777;
    rte_image_reader *r = rte_image_reader_create(67, 40);
    assert_non_null(r);
    const char *exts[] = {"c.ppm", "c.png", "c.PPM"};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int32_t w = sizes[s][0], h = sizes[s][1];
        rte_image_u8c3 src = unit_image_u8c3(w, h, (int32_t)(s % 4));
        for (int32_t y = 0; y < h; y++)
            fill_random(src.buf + (size_t)y * src.stride, (size_t)w * 3, &seed);
        for (size_t e = 0; e < 3; e++) {
            const char *path = tmp_path(exts[e]);
            assert_int_equal(rte_image_write_bgr(path, &src, msg, sizeof msg), RTE_OK);
            rte_image_info info;
            assert_int_equal(rte_image_probe(path, &info, msg, sizeof msg), RTE_OK);
            assert_int_equal(info.channels, 3);
            assert_int_equal(info.format, e == 1 ? RTE_FILE_PNG : RTE_FILE_PPM);

            rte_image_u8c3 back = unit_image_u8c3(w, h, 7);
            assert_int_equal(rte_image_read_bgr(r, path, &back, msg, sizeof msg), RTE_OK);
            for (int32_t y = 0; y < h; y++)
                assert_memory_equal(back.buf + (size_t)y * back.stride,
                                    src.buf + (size_t)y * src.stride, (size_t)w * 3);
            assert_padding_u8c3(&back);

            /* A colour file is not read as grey: that is rte_bgr_to_gray's job. */
            rte_image_u8 gray = unit_image_u8(w, h, 0, 0);
            assert_int_equal(rte_image_read_gray(r, path, &gray, msg, sizeof msg),
                             RTE_ERR_UNSUPPORTED);
            assert_non_null(strstr(msg, path));
            test_free(gray.buf);

            uint8_t packed[67 * 40 * 3];
            assert_int_equal(rte_image_read(r, path, packed, sizeof packed, &info, msg, sizeof msg),
                             RTE_OK);
            for (int32_t y = 0; y < h; y++)
                assert_memory_equal(packed + (size_t)y * w * 3, src.buf + (size_t)y * src.stride,
                                    (size_t)w * 3);
            assert_int_equal(remove(path), 0);
            test_free(back.buf);
        }
        test_free(src.buf);
    }
    rte_image_reader_destroy(r);
}

/* Parses a .npy header and checks the layout rules of format 1.0. */
static size_t check_npy_header(const uint8_t *file, size_t n, const char *dict)
{
    assert_true(n >= 10);
    assert_memory_equal(file, "\x93NUMPY\x01\x00", 8);
    size_t len = (size_t)file[8] | (size_t)file[9] << 8;
    assert_int_equal((10 + len) % 64, 0);
    assert_true(10 + len <= n);
    assert_int_equal(file[10 + len - 1], '\n');
    size_t d = strlen(dict);
    assert_memory_equal(file + 10, dict, d);
    for (size_t i = 10 + d; i < 10 + len - 1; i++)
        assert_int_equal(file[i], ' ');
    return 10 + len;
}

static void npy_layout(void **state)
{
    static uint8_t file[8192];
    rte_image_s16 s16 = unit_image_s16(5, 3, 2);
    for (int32_t y = 0; y < 3; y++)
        for (int32_t x = 0; x < 5; x++)
            rte_s16_row(&s16, y)[x] = (int16_t)(y * 1000 - x * 3001);
    const char *path = tmp_path("a.npy");
    assert_int_equal(rte_image_write_s16(path, &s16, msg, sizeof msg), RTE_OK);
    size_t n = read_bytes(path, file, sizeof file);
    size_t off =
        check_npy_header(file, n, "{'descr': '<i2', 'fortran_order': False, 'shape': (3, 5), }");
    assert_int_equal(n, off + 3 * 5 * 2);
    for (int32_t i = 0; i < 15; i++) {
        int16_t v = (int16_t)(file[off + 2 * i] | file[off + 2 * i + 1] << 8);
        assert_int_equal(v, rte_s16_row(&s16, i / 5)[i % 5]);
    }
    test_free(s16.buf);

    rte_image_u8 u8 = unit_image_u8(1, 4, 3, 9);
    rte_u8_row(&u8, 2)[0] = 200;
    assert_int_equal(rte_image_write_gray(path, &u8, msg, sizeof msg), RTE_OK);
    n = read_bytes(path, file, sizeof file);
    off = check_npy_header(file, n, "{'descr': '|u1', 'fortran_order': False, 'shape': (4, 1), }");
    assert_int_equal(n, off + 4);
    assert_int_equal(file[off + 1], 9);
    assert_int_equal(file[off + 2], 200);
    test_free(u8.buf);

    rte_image_u8c3 c3 = unit_image_u8c3(2, 1, 1);
    memcpy(c3.buf, "\x01\x02\x03\x04\x05\x06", 6);
    assert_int_equal(rte_image_write_bgr(path, &c3, msg, sizeof msg), RTE_OK);
    n = read_bytes(path, file, sizeof file);
    off =
        check_npy_header(file, n, "{'descr': '|u1', 'fortran_order': False, 'shape': (1, 2, 3), }");
    assert_int_equal(n, off + 6);
    assert_memory_equal(file + off, "\x01\x02\x03\x04\x05\x06", 6);
    test_free(c3.buf);

    /* Large shapes push the header over 64 bytes: still aligned. */
    rte_image_s16 big = unit_image_s16(RTE_MAX_SIDE, 1, 0);
    assert_int_equal(rte_image_write_s16(path, &big, msg, sizeof msg), RTE_OK);
    n = read_bytes(path, file, 128);
    check_npy_header(file, n, "{'descr': '<i2', 'fortran_order': False, 'shape': (1, 32767), }");
    test_free(big.buf);
    assert_int_equal(remove(path), 0);
}

/* Netpbm headers: comments, any whitespace, text scaling, binary as is. */
static void pnm_header_parsing(void **state)
{
    rte_image_reader *r = rte_image_reader_create(8, 8);
    const char *path = tmp_path("h.pgm");
    uint8_t out[64];
    rte_image_info info;

    static const char text[] = "P2\n# comment\n3#after a number\r2\t\v\f4\n0 1 2\n3 4 9\n";
    write_bytes(path, text, sizeof text - 1);
    assert_int_equal(rte_image_read(r, path, out, sizeof out, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(info.width, 3);
    assert_int_equal(info.height, 2);
    /* v * 255 / 4, values above maxval clamp to it */
    static const uint8_t want_text[6] = {0, 63, 127, 191, 255, 255};
    assert_memory_equal(out, want_text, 6);

    static const char bin[] = "P5 2 2 15\n\x00\x07\x0f\x14";
    write_bytes(path, bin, sizeof bin - 1);
    assert_int_equal(rte_image_read(r, path, out, sizeof out, &info, msg, sizeof msg), RTE_OK);
    assert_memory_equal(out, "\x00\x07\x0f\x14", 4); /* binary: unscaled, as OpenCV */

    /* The one whitespace after maxval may be a space: the next space is data. */
    static const char two_spaces[] = "P5 2 1 255  \x05";
    write_bytes(path, two_spaces, sizeof two_spaces - 1);
    assert_int_equal(rte_image_read(r, path, out, sizeof out, &info, msg, sizeof msg), RTE_OK);
    assert_memory_equal(out, " \x05", 2);

    static const char ppm_text[] = "P3 1 1 100 10 20 130";
    write_bytes(path, ppm_text, sizeof ppm_text - 1);
    assert_int_equal(rte_image_read(r, path, out, sizeof out, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(info.channels, 3);
    assert_int_equal(info.format, RTE_FILE_PPM);
    assert_memory_equal(out, "\xff\x33\x19", 3); /* BGR of (25, 51, 255) */

    static const char maxval1[] = "P2 2 1 1 1 0";
    write_bytes(path, maxval1, sizeof maxval1 - 1);
    assert_int_equal(rte_image_read(r, path, out, sizeof out, &info, msg, sizeof msg), RTE_OK);
    assert_memory_equal(out, "\xff\x00", 2);

    static const char bad_end[] = "P5 2 1 255#\n\x01\x02";
    write_bytes(path, bad_end, sizeof bad_end - 1);
    assert_int_equal(rte_image_read(r, path, out, sizeof out, &info, msg, sizeof msg),
                     RTE_ERR_FORMAT);
    assert_non_null(strstr(msg, "whitespace"));

    static const char p16[] = "P5 1 1 65535\n\x01\x02";
    write_bytes(path, p16, sizeof p16 - 1);
    assert_int_equal(rte_image_probe(path, &info, msg, sizeof msg), RTE_ERR_UNSUPPORTED);
    assert_non_null(strstr(msg, "h.pgm: maxval 65535"));

    assert_int_equal(remove(path), 0);
    rte_image_reader_destroy(r);
}

static void argument_errors(void **state)
{
    rte_image_reader *r = rte_image_reader_create(4, 4);
    assert_non_null(r);
    assert_null(rte_image_reader_create(0, 4));
    assert_null(rte_image_reader_create(4, RTE_MAX_SIDE + 1));
    assert_true(rte_image_reader_max_file_bytes(r) > 4 * 4 * 3);

    uint8_t px[64] = {0};
    rte_image_u8 g = rte_image_u8_view(px, 4, 4, 0);
    char path[128];
    snprintf(path, sizeof path, "%s", tmp_path("e.pgm"));
    assert_int_equal(rte_image_write_gray(path, &g, msg, sizeof msg), RTE_OK);

    rte_image_info info;
    assert_int_equal(rte_image_read(NULL, path, px, sizeof px, &info, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_image_read(r, NULL, px, sizeof px, &info, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_image_read(r, path, px, 15, &info, msg, sizeof msg), RTE_ERR_NO_MEMORY);
    assert_non_null(strstr(msg, "e.pgm: 4x4x1 image needs 16 bytes, the buffer holds 15"));
    rte_image_u8 small = rte_image_u8_view(px, 3, 4, 0);
    assert_int_equal(rte_image_read_gray(r, path, &small, msg, sizeof msg), RTE_ERR_SIZE);
    rte_image_u8 bad = g;
    bad.stride = 2;
    assert_int_equal(rte_image_read_gray(r, path, &bad, msg, sizeof msg), RTE_ERR_SIZE);
    assert_int_equal(rte_image_read_bgr(r, path, NULL, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_image_probe(tmp_path("missing.png"), &info, msg, sizeof msg), RTE_ERR_IO);
    assert_non_null(strstr(msg, "missing.png: cannot open"));

    /* The reader's maximum is enforced before decoding. */
    rte_image_reader *tiny = rte_image_reader_create(3, 4);
    assert_int_equal(rte_image_read(tiny, path, px, sizeof px, &info, msg, sizeof msg),
                     RTE_ERR_TOO_LARGE);
    assert_non_null(strstr(msg, "reader holds at most 3x4"));
    rte_image_reader_destroy(tiny);

    /* Writers: extensions, views; a NULL message buffer is allowed. */
    assert_int_equal(rte_image_write_gray(tmp_path("x.jpg"), &g, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
    assert_non_null(strstr(msg, "x.jpg: unknown extension"));
    assert_int_equal(rte_image_write_gray(path, &bad, NULL, 0), RTE_ERR_SIZE);
    rte_image_s16 s = rte_image_s16_view(px, 2, 2, 0);
    assert_int_equal(rte_image_write_s16(tmp_path("s.pgm"), &s, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_image_write_gray("/nonexistent-dir/a.pgm", &g, msg, sizeof msg),
                     RTE_ERR_IO);
    assert_non_null(strstr(msg, "/nonexistent-dir/a.pgm: cannot create"));

    /* A short message buffer is cut, still terminated. */
    char shortmsg[8];
    assert_int_equal(rte_image_read(r, path, px, 1, &info, shortmsg, sizeof shortmsg),
                     RTE_ERR_NO_MEMORY);
    assert_int_equal(strlen(shortmsg), 7);

    assert_int_equal(remove(path), 0);
    rte_image_reader_destroy(r);
}

/* The fixtures: the PPM was made from the PNG, so their pixels agree. */
static void fixtures_agree(void **state)
{
    const char *dir = getenv("RTE_FIXTURES_DIR");
    if (!dir)
        skip();
    char png[512], ppm[512];
    snprintf(png, sizeof png, "%s/smarties.png", dir);
    snprintf(ppm, sizeof ppm, "%s/smarties.ppm", dir);
    rte_image_info a, b;
    assert_int_equal(rte_image_probe(png, &a, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_image_probe(ppm, &b, msg, sizeof msg), RTE_OK);
    assert_int_equal(a.width, 413);
    assert_int_equal(a.height, 356);
    assert_int_equal(b.width, a.width);
    assert_int_equal(b.height, a.height);
    rte_image_reader *r = rte_image_reader_create(a.width, a.height);
    size_t n = (size_t)a.width * a.height * 3;
    uint8_t *p1 = test_malloc(n), *p2 = test_malloc(n);
    assert_int_equal(rte_image_read(r, png, p1, n, &a, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_image_read(r, ppm, p2, n, &b, msg, sizeof msg), RTE_OK);
    assert_memory_equal(p1, p2, n);
    test_free(p1);
    test_free(p2);
    rte_image_reader_destroy(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gray_round_trips), cmocka_unit_test(bgr_round_trips),
        cmocka_unit_test(npy_layout),       cmocka_unit_test(pnm_header_parsing),
        cmocka_unit_test(argument_errors),  cmocka_unit_test(fixtures_agree),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
