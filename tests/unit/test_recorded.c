/* Recorded-frame sources and the pacer: image directories and globs, Y4M,
 * raw dumps and LCM logs of image_t, each with damaged input (skipped and
 * counted, the source goes on), rewinding, and pacing on a fake clock. */
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "heapcount.h"
#include "rtedge/imageio.h"
#include "sources/pacer.h"
#include "publish/publish.h"
#include "sources/recorded_source.h"
#include "rtedge/y4m.h"

static char tmpdir[512];

static int setup_tmp(void **state)
{
    (void)state;
    const char *base = getenv("RTE_TEST_TMP");
    snprintf(tmpdir, sizeof tmpdir, "%s/recorded.%d", base ? base : "/tmp", (int)getpid());
    mkdir(tmpdir, 0755);
    return 0;
}

static int teardown_tmp(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

static const char *tmp_path(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", tmpdir, name);
    return buf;
}

static void write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, size, f), size);
    fclose(f);
}

/* A w x h grey image whose pixels are value + x + y. */
static void write_gray(const char *path, int32_t w, int32_t h, uint8_t value)
{
    uint8_t *buf = malloc((size_t)w * (size_t)h);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++)
            buf[y * w + x] = (uint8_t)(value + x + y);
    rte_image_u8 img = {w, h, w, buf};
    char msg[RTE_IO_MESSAGE_SIZE];
    assert_int_equal(rte_image_write_gray(path, &img, msg, sizeof msg), RTE_OK);
    free(buf);
}

/* write_gray into dir/name; the path is left in path. */
static void write_gray_in(char *path, size_t size, const char *dir, const char *name, int32_t w,
                          int32_t h, uint8_t value)
{
    snprintf(path, size, "%s/%s", dir, name);
    write_gray(path, w, h, value);
}

static void expect_stats(const rte_source *src, uint64_t frames, uint64_t bad,
                         rte_source_state state)
{
    rte_source_stats st;
    rte_source_get_stats(src, &st);
    assert_int_equal(st.frames, frames);
    assert_int_equal(st.bad_frames, bad);
    assert_int_equal(st.state, state);
}

/* ---- image files ---- */

static void test_images_directory_with_corrupt_png(void **state)
{
    (void)state;
    char dir[600], path[700];
    tmp_path(dir, sizeof dir, "images");
    mkdir(dir, 0755);
    write_gray_in(path, sizeof path, dir, "a.pgm", 8, 6, 10);
    write_gray_in(path, sizeof path, dir, "b.png", 8, 6, 20);
    /* c.png: a PNG cut in the middle of its data */
    write_gray_in(path, sizeof path, dir, "c.png", 8, 6, 30);
    struct stat sb;
    assert_int_equal(stat(path, &sb), 0);
    assert_int_equal(truncate(path, sb.st_size / 2), 0);
    write_gray_in(path, sizeof path, dir, "d.PNG", 5, 4, 40);
    /* e.png: whole, but a byte of its image data flipped (CRC mismatch) */
    write_gray_in(path, sizeof path, dir, "e.png", 8, 6, 50);
    assert_int_equal(stat(path, &sb), 0);
    int fd = open(path, O_RDWR);
    assert_true(fd >= 0);
    uint8_t byte;
    assert_int_equal(pread(fd, &byte, 1, sb.st_size - 20), 1);
    byte ^= 0x55;
    assert_int_equal(pwrite(fd, &byte, 1, sb.st_size - 20), 1);
    close(fd);
    snprintf(path, sizeof path, "%s/notes.txt", dir);
    write_file(path, "x", 1);

    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_images_source_config cfg = {dir, RTE_PIXEL_GREY, 0, 0, 0, 0};
    assert_int_equal(rte_images_source_open(&src, &cfg, msg, sizeof msg), RTE_OK);
    assert_string_equal(src.ops->kind, "images");
    assert_int_equal(src.max_width, 8);
    assert_int_equal(src.max_height, 6);
    assert_int_equal(src.format, RTE_PIXEL_GREY);

    rte_source_frame f;
    const uint8_t firsts[] = {10, 20, 0, 40, 0};
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < 5; i++) {
            rte_status st = rte_source_next(&src, &f, 0, msg, sizeof msg);
            if (i == 2 || i == 4) {
                assert_int_equal(st, i == 2 ? RTE_ERR_TRUNCATED : RTE_ERR_CORRUPT);
                assert_non_null(strstr(msg, i == 2 ? "c.png" : "e.png"));
                continue;
            }
            assert_int_equal(st, RTE_OK);
            assert_int_equal(f.frame.format, RTE_PIXEL_GREY);
            assert_int_equal(f.frame.width, i == 3 ? 5 : 8);
            assert_int_equal(f.frame.plane[0][0], firsts[i]);
            assert_int_equal(f.frame.plane[0][f.frame.stride[0] + 2], firsts[i] + 3);
            assert_int_equal(f.sequence, (uint64_t)(pass * 5 + i));
            /* 30 fps by default; after the rewind, one frame after d.PNG */
            assert_int_equal(f.recorded_ns, (int64_t)(pass * 4 + i) * 1000000000 / 30);
        }
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
        expect_stats(&src, (uint64_t)(pass + 1) * 3, (uint64_t)(pass + 1) * 2, RTE_SOURCE_ENDED);
        assert_int_equal(rte_recorded_source_rewind(&src), RTE_OK);
    }
    rte_source_close(&src);
    assert_null(src.ops);

    /* Colour output, a glob, a maximum smaller than one file. */
    snprintf(path, sizeof path, "%s/[ab]*", dir);
    rte_images_source_config bgr = {path, RTE_PIXEL_BGR24, 8, 6, 10, 1};
    assert_int_equal(rte_images_source_open(&src, &bgr, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(f.frame.format, RTE_PIXEL_BGR24);
    assert_int_equal(f.frame.stride[0], 24);
    assert_memory_equal(f.frame.plane[0], "\x0a\x0a\x0a\x0b\x0b\x0b", 6);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(f.recorded_ns, 100000000); /* 10 fps */
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
    rte_source_close(&src);

    rte_images_source_config small = {dir, RTE_PIXEL_GREY, 6, 6, 0, 0};
    assert_int_equal(rte_images_source_open(&src, &small, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    rte_source_close(&src);

    rte_images_source_config none = {"/nonexistent/*.png", RTE_PIXEL_GREY, 0, 0, 0, 0};
    assert_int_equal(rte_images_source_open(&src, &none, msg, sizeof msg), RTE_ERR_IO);
    rte_images_source_config yuyv = {dir, RTE_PIXEL_YUYV, 0, 0, 0, 0};
    assert_int_equal(rte_images_source_open(&src, &yuyv, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_null(src.ops);
}

/* Colour files read as grey: what rte_color_bgr_to_gray gives. */
static void test_images_colour_to_grey(void **state)
{
    (void)state;
    char path[700];
    tmp_path(path, sizeof path, "colour.ppm");
    uint8_t bgr[4 * 3 * 3];
    for (size_t i = 0; i < sizeof bgr; i++)
        bgr[i] = (uint8_t)(i * 37);
    rte_image_u8c3 img = {4, 3, 12, bgr};
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_image_write_bgr(path, &img, msg, sizeof msg), RTE_OK);
    uint8_t expect[12];
    rte_image_u8 gray = {4, 3, 4, expect};
    assert_int_equal(rte_color_bgr_to_gray(&img, &gray), RTE_OK);
    rte_source src;
    rte_images_source_config cfg = {path, RTE_PIXEL_GREY, 0, 0, 0, 0};
    assert_int_equal(rte_images_source_open(&src, &cfg, msg, sizeof msg), RTE_OK);
    rte_source_frame f;
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_memory_equal(f.frame.plane[0], expect, 12);
    rte_source_close(&src);
}

/* ---- Y4M ---- */

/* A Y4M file: header, then `frames` frames whose luma is base + i + frame and
 * chroma U = 100 + i + frame, V = 200 - i - frame; `extra` appended. */
static void write_y4m(const char *path, const char *header, int32_t w, int32_t h, int mono,
                      int frames, const char *extra, size_t extra_size)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(header, f);
    int32_t cw = (w + 1) / 2, ch = (h + 1) / 2;
    for (int k = 0; k < frames; k++) {
        fputs(k == 1 ? "FRAME Ixyz\n" : "FRAME\n", f);
        for (int32_t i = 0; i < w * h; i++)
            fputc((uint8_t)(i + k), f);
        if (!mono) {
            for (int32_t i = 0; i < cw * ch; i++)
                fputc((uint8_t)(100 + i + k), f);
            for (int32_t i = 0; i < cw * ch; i++)
                fputc((uint8_t)(200 - i - k), f);
        }
    }
    if (extra_size)
        fwrite(extra, 1, extra_size, f);
    fclose(f);
}

static void check_y4m_frame(const rte_source_frame *f, int32_t w, int32_t h, int mono, int k)
{
    assert_int_equal(f->frame.format, mono ? RTE_PIXEL_GREY : RTE_PIXEL_NV12);
    assert_int_equal(f->frame.width, w);
    assert_int_equal(f->frame.height, h);
    assert_int_equal(rte_frame_check(&f->frame), RTE_OK);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++)
            assert_int_equal(f->frame.plane[0][y * f->frame.stride[0] + x],
                             (uint8_t)(y * w + x + k));
    if (mono)
        return;
    int32_t cw = (w + 1) / 2, ch = (h + 1) / 2;
    for (int32_t y = 0; y < ch; y++)
        for (int32_t x = 0; x < cw; x++) {
            const uint8_t *uv = f->frame.plane[1] + y * f->frame.stride[1] + 2 * x;
            assert_int_equal(uv[0], (uint8_t)(100 + y * cw + x + k));
            assert_int_equal(uv[1], (uint8_t)(200 - (y * cw + x) - k));
        }
}

static void test_y4m_mono_and_420(void **state)
{
    (void)state;
    char path[700], msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_source src;
    rte_source_frame f;
    struct {
        const char *header;
        int32_t w, h;
        int mono;
        int64_t fps_num, fps_den;
    } cases[] = {
        {"YUV4MPEG2 W7 H5 F25:1 Ip A1:1 Cmono\n", 7, 5, 1, 25, 1},
        {"YUV4MPEG2 W7 H5 F30000:1001 Ip C420jpeg XYSCSS=420JPEG\n", 7, 5, 0, 30000, 1001},
        {"YUV4MPEG2 W4 H2\n", 4, 2, 0, 30, 1},
        {"YUV4MPEG2 W1 H1 F1:1 C420mpeg2\n", 1, 1, 0, 1, 1},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        tmp_path(path, sizeof path, "clip.y4m");
        write_y4m(path, cases[c].header, cases[c].w, cases[c].h, cases[c].mono, 3, NULL, 0);
        assert_int_equal(rte_y4m_source_open(&src, path, msg, sizeof msg), RTE_OK);
        assert_string_equal(src.ops->kind, "y4m");
        assert_int_equal(src.max_width, cases[c].w);
        for (int k = 0; k < 3; k++) {
            assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
            check_y4m_frame(&f, cases[c].w, cases[c].h, cases[c].mono, k);
            assert_int_equal(f.sequence, (uint64_t)k);
            assert_int_equal(f.recorded_ns, k * cases[c].fps_den * 1000000000 / cases[c].fps_num);
        }
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
        assert_int_equal(rte_recorded_source_rewind(&src), RTE_OK);
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
        check_y4m_frame(&f, cases[c].w, cases[c].h, cases[c].mono, 0);
        assert_int_equal(f.sequence, 3);
        expect_stats(&src, 4, 0, RTE_SOURCE_STREAMING);
        rte_source_close(&src);
    }
}

static void test_y4m_damaged(void **state)
{
    (void)state;
    char path[700], msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_source src;
    rte_source_frame f;
    /* Cut in the middle of the fourth frame. */
    tmp_path(path, sizeof path, "cut.y4m");
    write_y4m(path, "YUV4MPEG2 W8 H4 F10:1 C420\n", 8, 4, 0, 3, "FRAME\n\x01\x02\x03", 9);
    assert_int_equal(rte_y4m_source_open(&src, path, msg, sizeof msg), RTE_OK);
    for (int k = 0; k < 3; k++)
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_TRUNCATED);
    assert_non_null(strstr(msg, "cut short"));
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
    expect_stats(&src, 3, 1, RTE_SOURCE_ENDED);
    rte_source_close(&src);

    /* A bad FRAME header on the second frame: skipped, the third read. */
    tmp_path(path, sizeof path, "badframe.y4m");
    write_y4m(path, "YUV4MPEG2 W6 H2 Cmono\n", 6, 2, 1, 3, NULL, 0);
    int fd = open(path, O_RDWR);
    assert_true(fd >= 0);
    off_t second = (off_t)strlen("YUV4MPEG2 W6 H2 Cmono\n") + 6 + 12;
    assert_int_equal(pwrite(fd, "FRAXE", 5, second), 5);
    close(fd);
    assert_int_equal(rte_y4m_source_open(&src, path, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    check_y4m_frame(&f, 6, 2, 1, 0);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_CORRUPT);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    check_y4m_frame(&f, 6, 2, 1, 2);
    assert_int_equal(f.sequence, 2);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
    expect_stats(&src, 2, 1, RTE_SOURCE_ENDED);
    rte_source_close(&src);

    /* Headers rtedge refuses. */
    /* Headers rtedge refuses, numbers that overflow an int32 or a long
     * among them (W4294967300 used to wrap to a width of 4). */
    const struct {
        const char *header;
        rte_status st;
        const char *why;
    } bad[] = {
        {"YUV4MPEG2 W6 H2 C444\n", RTE_ERR_UNSUPPORTED, "colour space C444"},
        {"YUV4MPEG2 W0 H2\n", RTE_ERR_FORMAT, "bad frame width in tag 'W0'"},
        {"YUV4MPEG W6 H2\n", RTE_ERR_FORMAT, "not a YUV4MPEG2 file"},
        {"YUV4MPEG2 W6 H2 It\n", RTE_ERR_UNSUPPORTED, "interlaced"},
        {"YUV4MPEG2 W6x H2\n", RTE_ERR_FORMAT, "bad frame width"},
        {"YUV4MPEG2 W6 H2", RTE_ERR_FORMAT, "no YUV4MPEG2 header"},
        {"YUV4MPEG2 W4294967300 H2\n", RTE_ERR_FORMAT, "bad frame width in tag 'W4294967300'"},
        {"YUV4MPEG2 W6 H18446744073709551620\n", RTE_ERR_FORMAT, "bad frame height"},
        {"YUV4MPEG2 W-6 H2\n", RTE_ERR_FORMAT, "bad frame width"},
        {"YUV4MPEG2 W6 H40000\n", RTE_ERR_FORMAT, "bad frame height in tag 'H40000' (1..32767)"},
        {"YUV4MPEG2 W6 H2 F4294967326:1\n", RTE_ERR_FORMAT, "bad frame rate tag"},
        {"YUV4MPEG2 W6 H2 F30:-1\n", RTE_ERR_FORMAT, "bad frame rate tag"},
        {"YUV4MPEG2 W6 H2 F30\n", RTE_ERR_FORMAT, "bad frame rate tag"},
        {"YUV4MPEG2 W6 H2 F0:1\n", RTE_ERR_FORMAT, "bad frame rate tag"},
        {"YUV4MPEG2 W6 H2 F2000000:1\n", RTE_ERR_ARGUMENT, "bad frame rate 2000000/1"},
        {"YUV4MPEG2 H2\n", RTE_ERR_FORMAT, "no frame size"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_file(path, bad[i].header, strlen(bad[i].header));
        assert_int_equal(rte_y4m_source_open(&src, path, msg, sizeof msg), bad[i].st);
        if (!strstr(msg, bad[i].why))
            print_error("%s: '%s'\n", bad[i].header, msg);
        assert_non_null(strstr(msg, bad[i].why));
        assert_null(src.ops);
        /* rtedge_io's reader parses the same header. */
        rte_y4m_reader *r;
        if (bad[i].st == RTE_ERR_FORMAT)
            assert_int_equal(rte_y4m_open(path, 0, 0, &r, NULL, msg, sizeof msg), RTE_ERR_FORMAT);
    }
    assert_int_equal(rte_y4m_source_open(&src, "/nonexistent.y4m", msg, sizeof msg), RTE_ERR_IO);
}

/* What ffmpeg writes (when it is installed): the same pixels as the PGM. */
static void test_y4m_from_ffmpeg(void **state)
{
    (void)state;
    if (system("command -v ffmpeg >/dev/null 2>&1") != 0) {
        print_message("ffmpeg not installed\n");
        skip();
    }
    char pgm[700], y4m[700], cmd[2000], msg[RTE_SOURCE_MESSAGE_SIZE];
    tmp_path(pgm, sizeof pgm, "ff.pgm");
    tmp_path(y4m, sizeof y4m, "ff.y4m");
    write_gray(pgm, 32, 16, 50);
    snprintf(cmd, sizeof cmd,
             "ffmpeg -loglevel error -y -loop 1 -i '%s' -frames:v 3 -pix_fmt gray '%s'", pgm, y4m);
    assert_int_equal(system(cmd), 0);
    rte_source src;
    rte_source_frame f;
    assert_int_equal(rte_y4m_source_open(&src, y4m, msg, sizeof msg), RTE_OK);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
        assert_int_equal(f.frame.format, RTE_PIXEL_GREY);
        assert_int_equal(f.frame.plane[0][0], 50);
        assert_int_equal(f.frame.plane[0][15 * f.frame.stride[0] + 31], 50 + 15 + 31);
    }
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
    rte_source_close(&src);
}

/* ffmpeg's 4:2:0 Y4M of a picture (odd size) and ffmpeg's repacking of that
 * Y4M into raw NV12: the Y4M source (I420 interleaved on reading) and the
 * raw source deliver the same bytes. */
static void test_y4m_420_and_raw_nv12_from_ffmpeg(void **state)
{
    (void)state;
    if (system("command -v ffmpeg >/dev/null 2>&1") != 0) {
        print_message("ffmpeg not installed\n");
        skip();
    }
    char ppm[700], y4m[700], nv12[700], cmd[3000], msg[RTE_SOURCE_MESSAGE_SIZE];
    tmp_path(ppm, sizeof ppm, "ff.ppm");
    tmp_path(y4m, sizeof y4m, "ff420.y4m");
    tmp_path(nv12, sizeof nv12, "ff.nv12");
    enum { W = 33, H = 17 };
    static uint8_t bgr[W * H * 3];
    uint32_t r = 12345;
    for (size_t i = 0; i < sizeof bgr; i++) {
        r ^= r << 13;
        r ^= r >> 17;
        r ^= r << 5;
        bgr[i] = (uint8_t)r;
    }
    rte_image_u8c3 img = {W, H, W * 3, bgr};
    assert_int_equal(rte_image_write_bgr(ppm, &img, msg, sizeof msg), RTE_OK);
    snprintf(cmd, sizeof cmd,
             "ffmpeg -loglevel error -y -i '%s' -pix_fmt yuv420p '%s' && "
             "ffmpeg -loglevel error -y -i '%s' -f rawvideo -pix_fmt nv12 '%s'",
             ppm, y4m, y4m, nv12);
    assert_int_equal(system(cmd), 0);
    rte_source a, b;
    rte_source_frame fa, fb;
    assert_int_equal(rte_y4m_source_open(&a, y4m, msg, sizeof msg), RTE_OK);
    rte_raw_source_config rc = {nv12, RTE_PIXEL_NV12, W, H, 0, 0};
    assert_int_equal(rte_raw_source_open(&b, &rc, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&a, &fa, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&b, &fb, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(fa.frame.format, RTE_PIXEL_NV12);
    size_t size = rte_frame_packed_size(RTE_PIXEL_NV12, W, H);
    assert_int_equal(fa.frame.plane[1] - fa.frame.plane[0], W * H);
    assert_memory_equal(fa.frame.plane[0], fb.frame.plane[0], size);
    assert_int_equal(rte_source_next(&a, &fa, 0, msg, sizeof msg), RTE_ERR_END);
    assert_int_equal(rte_source_next(&b, &fb, 0, msg, sizeof msg), RTE_ERR_END);
    rte_source_close(&a);
    rte_source_close(&b);
}

/* ---- raw dumps ---- */

static void test_raw_frames(void **state)
{
    (void)state;
    char path[700], msg[RTE_SOURCE_MESSAGE_SIZE];
    tmp_path(path, sizeof path, "dump.yuyv");
    size_t frame = (size_t)2 * 6 * 4;
    uint8_t data[2 * 2 * 6 * 4 + 10];
    for (size_t i = 0; i < sizeof data; i++)
        data[i] = (uint8_t)i;
    write_file(path, data, sizeof data); /* two frames and a tail of 10 bytes */
    rte_source src;
    rte_source_frame f;
    rte_raw_source_config cfg = {path, RTE_PIXEL_YUYV, 6, 4, 15, 1};
    assert_int_equal(rte_raw_source_open(&src, &cfg, msg, sizeof msg), RTE_OK);
    assert_string_equal(src.ops->kind, "raw");
    for (int k = 0; k < 2; k++) {
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
        assert_int_equal(f.frame.format, RTE_PIXEL_YUYV);
        assert_int_equal(f.frame.stride[0], 12);
        assert_memory_equal(f.frame.plane[0], data + k * frame, frame);
        assert_int_equal(f.recorded_ns, (int64_t)k * 1000000000 / 15);
    }
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_TRUNCATED);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
    expect_stats(&src, 2, 1, RTE_SOURCE_ENDED);
    assert_int_equal(rte_recorded_source_rewind(&src), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_memory_equal(f.frame.plane[0], data, frame);
    assert_int_equal(f.sequence, 3); /* slots 0, 1, 2 (bad) before the rewind */
    /* one frame interval after the last frame delivered */
    assert_int_equal(f.recorded_ns, 2 * (1000000000LL / 15));
    rte_source_close(&src);

    rte_raw_source_config bad = {path, RTE_PIXEL_YUYV, 0, 4, 0, 0};
    assert_int_equal(rte_raw_source_open(&src, &bad, msg, sizeof msg), RTE_ERR_ARGUMENT);
    bad = (rte_raw_source_config){path, RTE_PIXEL_GREY, 4, 4, -1, 1};
    assert_int_equal(rte_raw_source_open(&src, &bad, msg, sizeof msg), RTE_ERR_ARGUMENT);
    bad = (rte_raw_source_config){"/nonexistent.raw", RTE_PIXEL_GREY, 4, 4, 0, 0};
    assert_int_equal(rte_raw_source_open(&src, &bad, msg, sizeof msg), RTE_ERR_IO);
}

/* ---- LCM logs of image_t ---- */

static void test_lcm_log_images(void **state)
{
    (void)state;
    char path[700], url[800], msg[RTE_SOURCE_MESSAGE_SIZE];
    tmp_path(path, sizeof path, "images.lcmlog");
    snprintf(url, sizeof url, "file://%s", path);
    rte_publish_limits limits = {32, 0, 0, 0, 0, 4096, 1, 0};
    rte_publisher *pub;
    assert_int_equal(rte_publisher_create(&pub, url, &limits, msg, sizeof msg), RTE_OK);
    uint8_t pixels[20 * 10];
    for (size_t i = 0; i < sizeof pixels; i++)
        pixels[i] = (uint8_t)(i * 7);
    rtedge_image_t img = {1000,    9,      10, 20,  RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY,
                          20 * 10, pixels, 0,  NULL};
    rtedge_status_t status = {0};
    status.source_id = (char *)"x";
    for (int k = 0; k < 5; k++) {
        img.utime = 1000 + 33333 * k;
        if (k == 2)
            img.pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_BGR; /* another format: bad */
        else
            img.pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY;
        if (k == 3)
            img.size = 50; /* too few bytes for 9x10 with stride 20: corrupt */
        assert_int_equal(rte_publish_image(pub, "CAM", &img, msg, sizeof msg), RTE_OK);
        img.size = 200;
        assert_int_equal(rte_publish_status(pub, "STATUS", &status, msg, sizeof msg), RTE_OK);
        assert_int_equal(rte_publish_image(pub, "OTHER_CAM", &img, msg, sizeof msg), RTE_OK);
    }
    rte_publisher_destroy(pub);

    rte_source src;
    rte_source_frame f;
    /* Format and size from the log's first image on CAM. */
    rte_lcm_source_config cfg = {url, "CAM", 0, 0, 0};
    assert_int_equal(rte_lcm_log_source_open(&src, &cfg, msg, sizeof msg), RTE_OK);
    assert_string_equal(src.ops->kind, "lcm-log");
    assert_int_equal(src.format, RTE_PIXEL_GREY);
    assert_int_equal(src.max_width, 9);
    assert_int_equal(src.max_height, 10);
    const rte_status expect[] = {RTE_OK, RTE_OK, RTE_ERR_FORMAT, RTE_ERR_CORRUPT, RTE_OK};
    for (int k = 0; k < 5; k++) {
        rte_status st = rte_source_next(&src, &f, 0, msg, sizeof msg);
        assert_int_equal(st, expect[k]);
        if (st != RTE_OK)
            continue;
        assert_int_equal(f.recorded_ns, (1000 + 33333LL * k) * 1000);
        assert_int_equal(f.frame.stride[0], 20);
        assert_int_equal(f.frame.plane[0][20 + 3], pixels[23]);
        assert_int_equal(f.sequence, (uint64_t)k);
    }
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_END);
    expect_stats(&src, 3, 2, RTE_SOURCE_ENDED);
    rte_source_close(&src);

    /* Any channel: every image_t, the status messages passed over. */
    rte_lcm_source_config any = {path, NULL, RTE_PIXEL_GREY, 16, 16};
    assert_int_equal(rte_lcm_log_source_open(&src, &any, msg, sizeof msg), RTE_OK);
    int ok = 0, bad = 0;
    rte_status st;
    while ((st = rte_source_next(&src, &f, 0, msg, sizeof msg)) != RTE_ERR_END)
        st == RTE_OK ? ok++ : bad++;
    assert_int_equal(ok, 7);
    assert_int_equal(bad, 3);
    rte_source_close(&src);

    /* Smaller than the images: each one is a bad frame. */
    rte_lcm_source_config small = {path, "CAM", RTE_PIXEL_GREY, 8, 8};
    assert_int_equal(rte_lcm_log_source_open(&src, &small, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    rte_source_close(&src);

    rte_lcm_source_config nothing = {path, "NOBODY", 0, 0, 0};
    assert_int_equal(rte_lcm_log_source_open(&src, &nothing, msg, sizeof msg), RTE_ERR_FORMAT);
    rte_lcm_source_config half = {path, "CAM", RTE_PIXEL_GREY, 8, 0};
    assert_int_equal(rte_lcm_log_source_open(&src, &half, msg, sizeof msg), RTE_ERR_ARGUMENT);
    rte_lcm_source_config live = {"memq://", NULL, RTE_PIXEL_GREY, 8, 8};
    assert_int_equal(rte_lcm_live_source_open(&src, &live, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_null(src.ops);

    /* Forged times (found by fuzz_lcm_log: utime * 1000 overflowed): bad
     * frames, the ones after them read. */
    assert_int_equal(rte_publisher_create(&pub, url, &limits, msg, sizeof msg), RTE_OK);
    const int64_t utimes[] = {-1, INT64_MAX, RTE_RECORDED_MAX_UTIME + 1, 5000,
                              RTE_RECORDED_MAX_UTIME};
    img.pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY;
    for (int k = 0; k < 5; k++) {
        img.utime = utimes[k];
        assert_int_equal(rte_publish_image(pub, "CAM", &img, msg, sizeof msg), RTE_OK);
    }
    rte_publisher_destroy(pub);
    assert_int_equal(rte_lcm_log_source_open(&src, &any, msg, sizeof msg), RTE_OK);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_ERR_CORRUPT);
        assert_non_null(strstr(msg, "is outside 0..2^52 microseconds"));
    }
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(f.recorded_ns, 5000000);
    assert_int_equal(rte_source_next(&src, &f, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(f.recorded_ns, RTE_RECORDED_MAX_UTIME * 1000);
    /* Rewinds cannot overflow the times either (UBSan in the sanitizer run). */
    for (int pass = 0; pass < 4; pass++) {
        assert_int_equal(rte_recorded_source_rewind(&src), RTE_OK);
        while ((st = rte_source_next(&src, &f, 0, msg, sizeof msg)) != RTE_ERR_END)
            if (st == RTE_OK)
                assert_true(f.recorded_ns >= 0);
    }
    rte_source_close(&src);
}

/* ---- no heap calls per frame ---- */

/* Heap calls of `frames` next() calls after the first, with a rewind at the
 * end of the recording. */
static uint64_t heap_calls_per_run(rte_source *src, int frames)
{
    rte_source_frame f;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_source_next(src, &f, 0, msg, sizeof msg), RTE_OK);
    heapcount_reset();
    for (int i = 0; i < frames; i++) {
        rte_status st = rte_source_next(src, &f, 0, msg, sizeof msg);
        if (st == RTE_ERR_END) {
            assert_int_equal(rte_recorded_source_rewind(src), RTE_OK);
            st = rte_source_next(src, &f, 0, msg, sizeof msg);
        }
        assert_int_equal(st, RTE_OK);
    }
    heapcount_counts c;
    heapcount_get(&c);
    rte_source_close(src);
    return heapcount_calls(&c);
}

static void test_no_heap_calls_per_frame(void **state)
{
    (void)state;
    if (!heapcount_active()) {
        print_message("heapcount is not interposed (sanitizer build?): not counted\n");
        skip();
    }
    char path[700], url[800], msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_source src;
    tmp_path(path, sizeof path, "heap.y4m");
    write_y4m(path, "YUV4MPEG2 W64 H48 C420\n", 64, 48, 0, 4, NULL, 0);
    assert_int_equal(rte_y4m_source_open(&src, path, msg, sizeof msg), RTE_OK);
    assert_int_equal(heap_calls_per_run(&src, 10), 0);

    tmp_path(path, sizeof path, "heap.raw");
    static uint8_t raw[3 * 64 * 48 * 3];
    write_file(path, raw, sizeof raw);
    rte_raw_source_config rc = {path, RTE_PIXEL_BGR24, 64, 48, 0, 0};
    assert_int_equal(rte_raw_source_open(&src, &rc, msg, sizeof msg), RTE_OK);
    assert_int_equal(heap_calls_per_run(&src, 10), 0);

    tmp_path(path, sizeof path, "heap.lcmlog");
    snprintf(url, sizeof url, "file://%s", path);
    rte_publish_limits limits = {32, 0, 0, 0, 0, 64 * 48, 1, 0};
    rte_publisher *pub;
    assert_int_equal(rte_publisher_create(&pub, url, &limits, msg, sizeof msg), RTE_OK);
    rtedge_image_t img = {0, 64, 48, 64, RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY, 64 * 48, raw, 0, NULL};
    for (int k = 0; k < 3; k++)
        assert_int_equal(rte_publish_image(pub, "CAM", &img, msg, sizeof msg), RTE_OK);
    rte_publisher_destroy(pub);
    rte_lcm_source_config lc = {path, "CAM", 0, 0, 0};
    assert_int_equal(rte_lcm_log_source_open(&src, &lc, msg, sizeof msg), RTE_OK);
    assert_int_equal(heap_calls_per_run(&src, 10), 0);

    /* Image files: the codecs' and stdio's own (documented in imageio.h). */
    char dir[600];
    tmp_path(dir, sizeof dir, "heapimages");
    mkdir(dir, 0755);
    write_gray_in(path, sizeof path, dir, "a.pgm", 64, 48, 1);
    write_gray_in(path, sizeof path, dir, "b.png", 64, 48, 2);
    rte_images_source_config ic = {dir, RTE_PIXEL_GREY, 0, 0, 0, 0};
    assert_int_equal(rte_images_source_open(&src, &ic, msg, sizeof msg), RTE_OK);
    print_message("images source, 10 frames of PGM and PNG: %llu heap calls (fopen, libspng)\n",
                  (unsigned long long)heap_calls_per_run(&src, 10));
}

/* ---- pacing on a fake clock ---- */

#define MS 1000000LL

static void test_pacer_recorded(void **state)
{
    (void)state;
    rte_pacer p;
    rte_pacer_config c = {RTE_PACE_RECORDED, 2000, 0, 0, 50 * MS, 0}; /* twice as fast */
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    int64_t wait;
    /* frames recorded every 100 ms from t = 5 s; the clock starts at 1000 */
    assert_int_equal(rte_pacer_decide(&p, 5000 * MS, 1000 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 5100 * MS, 1010 * MS, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 40 * MS); /* due at 1050 */
    assert_int_equal(rte_pacer_decide(&p, 5100 * MS, 1050 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(wait, 0);
    /* late by 30 ms: still processed; late by 60 ms: dropped */
    assert_int_equal(rte_pacer_decide(&p, 5200 * MS, 1130 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 5300 * MS, 1210 * MS, &wait), RTE_PACE_DROP);
    assert_int_equal(rte_pacer_decide(&p, 5400 * MS, 1210 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(p.dropped, 1);
    assert_int_equal(p.frames, 5);
    /* time going back (a second log): due at once, the pace starts again from it */
    assert_int_equal(rte_pacer_decide(&p, 100 * MS, 1220 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(p.restarts, 1);
    assert_int_equal(rte_pacer_decide(&p, 110 * MS, 1220 * MS, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 5 * MS);
    rte_pacer_restart(&p);
    assert_int_equal(rte_pacer_decide(&p, 110 * MS, 1300 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 120 * MS, 1300 * MS, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 5 * MS);

    /* A pause longer than max_pause_ns (a damaged timestamp 30 years on) is
     * not waited out: the pace starts again. */
    c = (rte_pacer_config){RTE_PACE_RECORDED, 1000, 0, 0, -1, 10000 * MS};
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    assert_int_equal(rte_pacer_decide(&p, 0, 0, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 33 * MS, 33 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 9000 * MS, 40 * MS, &wait),
                     RTE_PACE_WAIT); /* 9 s: waited */
    assert_int_equal(rte_pacer_decide(&p, 9000 * MS, 9000 * MS, &wait), RTE_PACE_PROCESS);
    const int64_t forged = 946080000000000000LL;
    assert_int_equal(rte_pacer_decide(&p, forged, 9010 * MS, &wait), RTE_PACE_PROCESS);
    assert_int_equal(p.restarts, 1);
    assert_int_equal(rte_pacer_decide(&p, forged + 33 * MS, 9010 * MS, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 33 * MS);
    /* Without a limit, spans that would overflow once scaled wait "for ever"
     * (a quarter of int64) instead. */
    c = (rte_pacer_config){RTE_PACE_RECORDED, 1, 0, 0, -1, 0};
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    assert_int_equal(rte_pacer_decide(&p, INT64_MIN, 0, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, INT64_MAX, 0, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, INT64_MAX / 4);

    /* real time, never dropping */
    c = (rte_pacer_config){RTE_PACE_RECORDED, 0, 0, 0, -1, 0};
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    assert_int_equal(rte_pacer_decide(&p, 0, 0, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 33 * MS, 10 * MS, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 23 * MS);
    assert_int_equal(rte_pacer_decide(&p, 66 * MS, 100000 * MS, &wait), RTE_PACE_PROCESS);
    /* a quarter speed */
    c.speed_permille = 250;
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    assert_int_equal(rte_pacer_decide(&p, 7, 0, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 7 + 10 * MS, 0, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 40 * MS);
}

static void test_pacer_fps_and_fast(void **state)
{
    (void)state;
    rte_pacer p;
    rte_pacer_config c = {RTE_PACE_FPS, 0, 30000, 1001, 100 * MS, 0};
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    int64_t wait;
    /* recorded times do not matter */
    assert_int_equal(rte_pacer_decide(&p, 999, 0, &wait), RTE_PACE_PROCESS);
    assert_int_equal(rte_pacer_decide(&p, 0, 0, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 33366666);
    assert_int_equal(rte_pacer_decide(&p, 0, 33366666, &wait), RTE_PACE_PROCESS);
    /* frame 1000 due at 33.366666 s exactly */
    p.frames = 1000;
    assert_int_equal(rte_pacer_decide(&p, 0, 33366666666LL - 1, &wait), RTE_PACE_WAIT);
    assert_int_equal(wait, 1);
    assert_int_equal(rte_pacer_decide(&p, 0, 33366666666LL + 200 * MS, &wait), RTE_PACE_DROP);

    c = (rte_pacer_config){RTE_PACE_FAST, 0, 0, 0, 0, 0};
    assert_int_equal(rte_pacer_init(&p, &c), RTE_OK);
    for (int i = 0; i < 3; i++) {
        assert_int_equal(rte_pacer_decide(&p, 1000000 * MS * i, 0, &wait), RTE_PACE_PROCESS);
        assert_int_equal(wait, 0);
    }

    rte_pacer_config bad[] = {{RTE_PACE_FPS, 0, 0, 1, 0, 0},
                              {RTE_PACE_FPS, 0, 30, -1, 0, 0},
                              {RTE_PACE_RECORDED, -5, 0, 0, 0, 0},
                              {(rte_pace_mode)7, 0, 0, 0, 0, 0}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(rte_pacer_init(&p, &bad[i]), RTE_ERR_ARGUMENT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_images_directory_with_corrupt_png),
        cmocka_unit_test(test_images_colour_to_grey),
        cmocka_unit_test(test_y4m_mono_and_420),
        cmocka_unit_test(test_y4m_damaged),
        cmocka_unit_test(test_y4m_from_ffmpeg),
        cmocka_unit_test(test_y4m_420_and_raw_nv12_from_ffmpeg),
        cmocka_unit_test(test_raw_frames),
        cmocka_unit_test(test_lcm_log_images),
        cmocka_unit_test(test_no_heap_calls_per_frame),
        cmocka_unit_test(test_pacer_recorded),
        cmocka_unit_test(test_pacer_fps_and_fast),
    };
    return cmocka_run_group_tests(tests, setup_tmp, teardown_tmp);
}
