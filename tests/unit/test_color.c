/* Frames and their conversion to grey. */
#include "unit.h"

#include <math.h>

#include "rtedge/color.h"

/* The BT.601 Q15 weights, written out independently of the library. */
static uint8_t luma(unsigned b, unsigned g, unsigned r)
{
    return (uint8_t)((3735u * b + 19235u * g + 9798u * r + 16384u) >> 15);
}

static uint8_t *random_bytes(size_t n, uint32_t *seed)
{
    uint8_t *p = test_malloc(n);
    for (size_t i = 0; i < n; i++)
        p[i] = (uint8_t)unit_rand(seed);
    return p;
}

static void primaries_give_hand_computed_grey(void **state)
{
    /* B, G, R, white, black as BGR bytes */
    uint8_t px[15] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0};
    rte_image_u8c3 src = {5, 1, 15, px};
    rte_image_u8 dst = unit_image_u8(5, 1, 3, 0);
    assert_int_equal(rte_color_bgr_to_gray(&src, &dst), RTE_OK);
    /* 3735*255/32768 = 29.07, 19235*255/32768 = 149.7, 9798*255/32768 = 76.2 */
    assert_int_equal(dst.buf[0], 29);
    assert_int_equal(dst.buf[1], 150);
    assert_int_equal(dst.buf[2], 76);
    assert_int_equal(dst.buf[3], 255);
    assert_int_equal(dst.buf[4], 0);
    assert_int_equal(rte_color_rgb_to_gray(&src, &dst), RTE_OK);
    assert_int_equal(dst.buf[0], 76);
    assert_int_equal(dst.buf[1], 150);
    assert_int_equal(dst.buf[2], 29);
    unit_assert_padding_u8(&dst);
    test_free(dst.buf);
}

static void bgr_and_rgb_rows_of_every_width(void **state)
{
    uint32_t seed = 12345;
    for (int32_t w = 1; w <= 67; w++) {
        int32_t h = 1 + w % 5, stride = 3 * w + (int32_t)(unit_rand(&seed) % 9);
        uint8_t *buf = random_bytes((size_t)stride * h, &seed);
        rte_image_u8c3 src = {w, h, stride, buf};
        rte_image_u8 bgr = unit_image_u8(w, h, 1 + w % 7, 0);
        rte_image_u8 rgb = unit_image_u8(w, h, 2, 0);
        rte_image_u8 fr = unit_image_u8(w, h, 5, 0);
        assert_int_equal(rte_color_bgr_to_gray(&src, &bgr), RTE_OK);
        assert_int_equal(rte_color_rgb_to_gray(&src, &rgb), RTE_OK);
        rte_frame f = {RTE_PIXEL_RGB24, w, h, {buf, NULL}, {stride, 0}};
        assert_int_equal(rte_frame_to_gray(&f, &fr), RTE_OK);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                const uint8_t *p = buf + (size_t)y * stride + 3 * x;
                assert_int_equal(bgr.buf[y * bgr.stride + x], luma(p[0], p[1], p[2]));
                assert_int_equal(rgb.buf[y * rgb.stride + x], luma(p[2], p[1], p[0]));
                assert_int_equal(fr.buf[y * fr.stride + x], luma(p[2], p[1], p[0]));
            }
        unit_assert_padding_u8(&bgr);
        unit_assert_padding_u8(&rgb);
        unit_assert_padding_u8(&fr);
        test_free(buf);
        test_free(bgr.buf);
        test_free(rgb.buf);
        test_free(fr.buf);
    }
}

static void grey_colours_stay_grey(void **state)
{
    /* equal B, G, R give that value back: the weights sum to 1.0 exactly */
    uint8_t px[3 * 256];
    for (int v = 0; v < 256; v++)
        px[3 * v] = px[3 * v + 1] = px[3 * v + 2] = (uint8_t)v;
    rte_image_u8c3 src = {256, 1, sizeof px, px};
    rte_image_u8 dst = unit_image_u8(256, 1, 4, 0);
    assert_int_equal(rte_color_bgr_to_gray(&src, &dst), RTE_OK);
    for (int v = 0; v < 256; v++)
        assert_int_equal(dst.buf[v], v);
    unit_assert_padding_u8(&dst);
    test_free(dst.buf);
}

static void packed_422_takes_the_y_samples(void **state)
{
    /* width 3 (odd): Y0 U Y1 V | Y2 U' */
    uint8_t row[2][8] = {{10, 20, 30, 40, 50, 60, 0xEE, 0xEE},
                         {11, 21, 31, 41, 51, 61, 0xEE, 0xEE}};
    rte_image_u8 dst = unit_image_u8(3, 2, 2, 0);
    assert_int_equal(rte_color_yuyv_to_gray(&row[0][0], 8, &dst), RTE_OK);
    assert_memory_equal(dst.buf, ((uint8_t[]){10, 30, 50}), 3);
    assert_memory_equal(dst.buf + dst.stride, ((uint8_t[]){11, 31, 51}), 3);
    assert_int_equal(rte_color_uyvy_to_gray(&row[0][0], 8, &dst), RTE_OK);
    assert_memory_equal(dst.buf, ((uint8_t[]){20, 40, 60}), 3);
    assert_memory_equal(dst.buf + dst.stride, ((uint8_t[]){21, 41, 61}), 3);

    rte_frame f = {RTE_PIXEL_YUYV, 3, 2, {&row[0][0], NULL}, {8, 0}};
    assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
    assert_memory_equal(dst.buf + dst.stride, ((uint8_t[]){11, 31, 51}), 3);
    f.format = RTE_PIXEL_UYVY;
    assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
    assert_memory_equal(dst.buf, ((uint8_t[]){20, 40, 60}), 3);
    unit_assert_padding_u8(&dst);

    /* a stride shorter than 2 * width */
    assert_int_equal(rte_color_yuyv_to_gray(&row[0][0], 5, &dst), RTE_ERR_SIZE);
    assert_int_equal(rte_color_uyvy_to_gray(NULL, 8, &dst), RTE_ERR_ARGUMENT);
    test_free(dst.buf);
}

static void packed_422_of_every_width(void **state)
{
    uint32_t seed = 777;
    for (int32_t w = 1; w <= 67; w++) {
        int32_t h = 1 + w % 4, stride = 2 * w + (int32_t)(unit_rand(&seed) % 5);
        uint8_t *buf = random_bytes((size_t)stride * h, &seed);
        rte_image_u8 yuyv = unit_image_u8(w, h, 3, 0), uyvy = unit_image_u8(w, h, 1, 0);
        assert_int_equal(rte_color_yuyv_to_gray(buf, stride, &yuyv), RTE_OK);
        assert_int_equal(rte_color_uyvy_to_gray(buf, stride, &uyvy), RTE_OK);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                assert_int_equal(yuyv.buf[y * yuyv.stride + x], buf[y * stride + 2 * x]);
                assert_int_equal(uyvy.buf[y * uyvy.stride + x], buf[y * stride + 2 * x + 1]);
            }
        unit_assert_padding_u8(&yuyv);
        unit_assert_padding_u8(&uyvy);
        test_free(buf);
        test_free(yuyv.buf);
        test_free(uyvy.buf);
    }
}

static void nv12_and_grey_give_their_y_plane(void **state)
{
    uint32_t seed = 99;
    /* 5x3 NV12 packed: Y rows of 5, then 2 rows of 3 U,V pairs */
    size_t size = rte_frame_packed_size(RTE_PIXEL_NV12, 5, 3);
    assert_int_equal(size, 15 + 2 * 6);
    uint8_t *buf = random_bytes(size, &seed);
    rte_frame f;
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_NV12, 5, 3, buf, size - 1), RTE_ERR_SIZE);
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_NV12, 5, 3, buf, size), RTE_OK);
    assert_ptr_equal(f.plane[1], buf + 15);
    assert_int_equal(f.stride[0], 5);
    assert_int_equal(f.stride[1], 6);

    rte_image_u8 dst = unit_image_u8(5, 3, 4, 0);
    assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
    for (int32_t y = 0; y < 3; y++)
        assert_memory_equal(dst.buf + y * dst.stride, buf + 5 * y, 5);
    unit_assert_padding_u8(&dst);

    rte_image_u8 view;
    assert_int_equal(rte_frame_gray_view(&f, &view), RTE_OK);
    assert_ptr_equal(view.buf, buf);
    assert_int_equal(view.stride, 5);
    assert_int_equal(view.width, 5);
    assert_int_equal(view.height, 3);

    /* GREY: a copy, also into itself */
    f.format = RTE_PIXEL_GREY;
    f.plane[1] = NULL;
    f.stride[1] = 0;
    memset(dst.buf, 0, 5);
    assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
    assert_memory_equal(dst.buf, buf, 5);
    rte_image_u8 self = {5, 3, 5, buf};
    uint8_t before[15];
    memcpy(before, buf, 15);
    assert_int_equal(rte_frame_to_gray(&f, &self), RTE_OK);
    assert_memory_equal(buf, before, 15);

    f.format = RTE_PIXEL_YUYV;
    f.stride[0] = 10;
    assert_int_equal(rte_frame_gray_view(&f, &view), RTE_ERR_UNSUPPORTED);
    test_free(buf);
    test_free(dst.buf);
}

static void one_pixel_frames(void **state)
{
    uint8_t px[6] = {1, 2, 3, 4, 5, 6};
    rte_image_u8 dst = unit_image_u8(1, 1, 2, 0);
    static const struct {
        rte_pixel_format format;
        uint8_t expected;
    } cases[] = {
        {RTE_PIXEL_GREY, 1},
        {RTE_PIXEL_YUYV, 1},
        {RTE_PIXEL_UYVY, 2},
        {RTE_PIXEL_NV12, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rte_frame f;
        assert_int_equal(rte_frame_packed(&f, cases[i].format, 1, 1, px, sizeof px), RTE_OK);
        assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
        assert_int_equal(dst.buf[0], cases[i].expected);
    }
    rte_frame f;
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_BGR24, 1, 1, px, sizeof px), RTE_OK);
    assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
    assert_int_equal(dst.buf[0], luma(1, 2, 3));
    unit_assert_padding_u8(&dst);
    test_free(dst.buf);
}

static void constant_frames_of_all_formats(void **state)
{
    static const rte_pixel_format formats[] = {RTE_PIXEL_GREY, RTE_PIXEL_BGR24, RTE_PIXEL_RGB24,
                                               RTE_PIXEL_YUYV, RTE_PIXEL_UYVY,  RTE_PIXEL_NV12};
    static const uint8_t values[] = {0, 255, 77};
    for (size_t v = 0; v < sizeof values; v++)
        for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++) {
            int32_t w = 37, h = 1 + (int32_t)i;
            size_t size = rte_frame_packed_size(formats[i], w, h);
            uint8_t *buf = test_malloc(size);
            memset(buf, values[v], size);
            rte_frame f;
            assert_int_equal(rte_frame_packed(&f, formats[i], w, h, buf, size), RTE_OK);
            rte_image_u8 dst = unit_image_u8(w, h, 3, 1);
            assert_int_equal(rte_frame_to_gray(&f, &dst), RTE_OK);
            for (int32_t y = 0; y < h; y++)
                for (int32_t x = 0; x < w; x++)
                    assert_int_equal(dst.buf[y * dst.stride + x], values[v]);
            unit_assert_padding_u8(&dst);
            test_free(buf);
            test_free(dst.buf);
        }
}

/* JPEG's Cb and Cr, written out independently of the library (doubles,
 * rounded half up: the library rounds its Q16 sums the same way). */
static uint8_t ref_chroma(double r, double g, double b, int cr)
{
    double v = cr ? 128 + 0.5 * r - 0.418688 * g - 0.081312 * b
                  : 128 - 0.168736 * r - 0.331264 * g + 0.5 * b;
    v = floor(v + 0.5);
    return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* Chroma at half size from every colour format: NV12's plane as it is,
 * 4:2:2 averaged over two rows, BGR and RGB from each block's mean, odd
 * sizes repeating the last row and column; grey frames have none. */
static void chroma_half_of_every_format(void **state)
{
    (void)state;
    uint32_t seed = 7;
    for (int32_t w = 1; w <= 6; w++)
        for (int32_t h = 1; h <= 4; h++) {
            const int32_t hw = (w + 1) / 2, hh = (h + 1) / 2;
            rte_image_u8 cb = unit_image_u8(hw, hh, 3, 0), cr = unit_image_u8(hw, hh, 1, 0);
            /* BGR24 and RGB24: the same colours in both byte orders */
            uint8_t *bgr = random_bytes((size_t)3 * w * h, &seed);
            uint8_t *rgb = test_malloc((size_t)3 * w * h);
            for (int32_t i = 0; i < w * h; i++)
                for (int k = 0; k < 3; k++)
                    rgb[3 * i + k] = bgr[3 * i + 2 - k];
            for (int order = 0; order < 2; order++) {
                rte_frame f;
                assert_int_equal(rte_frame_packed(&f, order ? RTE_PIXEL_RGB24 : RTE_PIXEL_BGR24, w,
                                                  h, order ? rgb : bgr, (size_t)3 * w * h),
                                 RTE_OK);
                assert_int_equal(rte_frame_chroma_half(&f, &cb, &cr), RTE_OK);
                for (int32_t y = 0; y < hh; y++)
                    for (int32_t x = 0; x < hw; x++) {
                        double s[3] = {0, 0, 0}; /* B, G, R */
                        for (int32_t dy = 0; dy < 2; dy++)
                            for (int32_t dx = 0; dx < 2; dx++) {
                                const int32_t yy = 2 * y + dy < h ? 2 * y + dy : h - 1;
                                const int32_t xx = 2 * x + dx < w ? 2 * x + dx : w - 1;
                                for (int k = 0; k < 3; k++)
                                    s[k] += bgr[3 * (yy * w + xx) + k] / 4.0;
                            }
                        assert_int_equal(cb.buf[y * cb.stride + x],
                                         ref_chroma(s[2], s[1], s[0], 0));
                        assert_int_equal(cr.buf[y * cr.stride + x],
                                         ref_chroma(s[2], s[1], s[0], 1));
                    }
            }
            /* YUYV and UYVY: U and V of each pair, rows averaged (rounded up) */
            uint8_t *p422 = random_bytes((size_t)2 * w * h, &seed);
            for (int uyvy = 0; uyvy < 2; uyvy++) {
                rte_frame f;
                assert_int_equal(rte_frame_packed(&f, uyvy ? RTE_PIXEL_UYVY : RTE_PIXEL_YUYV, w, h,
                                                  p422, (size_t)2 * w * h),
                                 RTE_OK);
                assert_int_equal(rte_frame_chroma_half(&f, &cb, &cr), RTE_OK);
                const int u = uyvy ? 0 : 1, v = uyvy ? 2 : 3;
                for (int32_t y = 0; y < hh; y++)
                    for (int32_t x = 0; x < hw; x++) {
                        const uint8_t *r0 = p422 + (size_t)2 * w * (2 * y);
                        const uint8_t *r1 = 2 * y + 1 < h ? r0 + 2 * w : r0;
                        assert_int_equal(cb.buf[y * cb.stride + x],
                                         (r0[4 * x + u] + r1[4 * x + u] + 1) / 2);
                        /* an odd width's last pixel has no V: the one before, or 128 */
                        const int32_t xv = 4 * x + 4 <= 2 * w ? x : x - 1;
                        const int expect_v =
                            xv < 0 ? 128 : (r0[4 * xv + v] + r1[4 * xv + v] + 1) / 2;
                        assert_int_equal(cr.buf[y * cr.stride + x], expect_v);
                    }
            }
            /* NV12: the interleaved plane */
            const size_t nv = rte_frame_packed_size(RTE_PIXEL_NV12, w, h);
            uint8_t *n12 = random_bytes(nv, &seed);
            rte_frame f;
            assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_NV12, w, h, n12, nv), RTE_OK);
            assert_int_equal(rte_frame_chroma_half(&f, &cb, &cr), RTE_OK);
            for (int32_t y = 0; y < hh; y++)
                for (int32_t x = 0; x < hw; x++) {
                    assert_int_equal(cb.buf[y * cb.stride + x],
                                     f.plane[1][y * f.stride[1] + 2 * x]);
                    assert_int_equal(cr.buf[y * cr.stride + x],
                                     f.plane[1][y * f.stride[1] + 2 * x + 1]);
                }
            unit_assert_padding_u8(&cb);
            unit_assert_padding_u8(&cr);
            /* no colour in a grey frame; planes of the wrong size; a NULL plane */
            assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_GREY, w, h, n12, nv), RTE_OK);
            assert_int_equal(rte_frame_chroma_half(&f, &cb, &cr), RTE_ERR_UNSUPPORTED);
            assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_NV12, w, h, n12, nv), RTE_OK);
            rte_image_u8 wide = cb;
            wide.width = hw + 1;
            wide.stride = hw + 3;
            assert_int_equal(rte_frame_chroma_half(&f, &wide, &wide), RTE_ERR_SIZE);
            assert_int_equal(rte_frame_chroma_half(&f, &cb, NULL), RTE_ERR_ARGUMENT);
            assert_int_equal(rte_frame_chroma_half(NULL, &cb, &cr), RTE_ERR_ARGUMENT);
            test_free(bgr);
            test_free(rgb);
            test_free(p422);
            test_free(n12);
            test_free(cb.buf);
            test_free(cr.buf);
        }
    /* saturated colours: the Q16 sums reach the ends without wrapping */
    uint8_t blue[12] = {255, 0, 0, 255, 0, 0, 255, 0, 0, 255, 0, 0};
    rte_frame f;
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_BGR24, 2, 2, blue, sizeof blue), RTE_OK);
    uint8_t b1 = 0, r1 = 0;
    rte_image_u8 cb = {1, 1, 1, &b1}, cr = {1, 1, 1, &r1};
    assert_int_equal(rte_frame_chroma_half(&f, &cb, &cr), RTE_OK);
    assert_int_equal(b1, 255);
    assert_int_equal(r1, ref_chroma(0, 0, 255, 1));
}

static void frame_checks_reject_bad_frames(void **state)
{
    uint8_t px[64];
    rte_frame ok = {RTE_PIXEL_YUYV, 4, 2, {px, NULL}, {8, 0}};
    assert_int_equal(rte_frame_check(&ok), RTE_OK);
    assert_int_equal(rte_frame_check(NULL), RTE_ERR_ARGUMENT);

    rte_frame bad = ok;
    bad.format = (rte_pixel_format)0;
    assert_int_equal(rte_frame_check(&bad), RTE_ERR_ARGUMENT);
    bad.format = (rte_pixel_format)99;
    assert_int_equal(rte_frame_check(&bad), RTE_ERR_ARGUMENT);
    bad = ok;
    bad.plane[0] = NULL;
    assert_int_equal(rte_frame_check(&bad), RTE_ERR_ARGUMENT);
    bad = ok;
    bad.stride[0] = 7;
    assert_int_equal(rte_frame_check(&bad), RTE_ERR_SIZE);
    bad = ok;
    bad.width = 0;
    assert_int_equal(rte_frame_check(&bad), RTE_ERR_SIZE);
    bad = ok;
    bad.height = RTE_MAX_SIDE + 1;
    assert_int_equal(rte_frame_check(&bad), RTE_ERR_SIZE);

    rte_frame nv = {RTE_PIXEL_NV12, 5, 2, {px, NULL}, {5, 6}};
    assert_int_equal(rte_frame_check(&nv), RTE_ERR_ARGUMENT); /* no UV plane */
    nv.plane[1] = px + 10;
    assert_int_equal(rte_frame_check(&nv), RTE_OK);
    nv.stride[1] = 5; /* 3 pairs need 6 bytes */
    assert_int_equal(rte_frame_check(&nv), RTE_ERR_SIZE);

    rte_frame bgr = {RTE_PIXEL_BGR24, 4, 2, {px, NULL}, {11, 0}};
    assert_int_equal(rte_frame_check(&bgr), RTE_ERR_SIZE);

    /* conversions check their arguments */
    rte_image_u8 dst = unit_image_u8(4, 2, 0, 0);
    assert_int_equal(rte_frame_to_gray(&ok, &dst), RTE_OK);
    assert_int_equal(rte_frame_to_gray(&bad, &dst), RTE_ERR_SIZE);
    assert_int_equal(rte_frame_to_gray(&ok, NULL), RTE_ERR_ARGUMENT);
    rte_image_u8 small = dst;
    small.width = 3;
    assert_int_equal(rte_frame_to_gray(&ok, &small), RTE_ERR_SIZE);
    rte_image_u8c3 c3 = {4, 2, 12, px};
    assert_int_equal(rte_color_bgr_to_gray(&c3, &small), RTE_ERR_SIZE);
    assert_int_equal(rte_color_rgb_to_gray(NULL, &dst), RTE_ERR_ARGUMENT);
    c3.stride = 11;
    assert_int_equal(rte_color_bgr_to_gray(&c3, &dst), RTE_ERR_SIZE);
    assert_int_equal(rte_frame_gray_view(&ok, NULL), RTE_ERR_ARGUMENT);
    test_free(dst.buf);

    assert_int_equal(rte_frame_packed_size((rte_pixel_format)0, 4, 4), 0);
    assert_int_equal(rte_frame_packed_size(RTE_PIXEL_RGB24, 0, 4), 0);
    assert_int_equal(rte_frame_packed_size(RTE_PIXEL_RGB24, 4, 4), 48);
    rte_frame f;
    assert_int_equal(rte_frame_packed(&f, (rte_pixel_format)0, 4, 4, px, sizeof px),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_GREY, 4, 4, NULL, 64), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_GREY, -1, 4, px, 64), RTE_ERR_SIZE);
}

static void format_names_round_trip(void **state)
{
    static const rte_pixel_format formats[] = {RTE_PIXEL_GREY, RTE_PIXEL_BGR24, RTE_PIXEL_RGB24,
                                               RTE_PIXEL_YUYV, RTE_PIXEL_UYVY,  RTE_PIXEL_NV12};
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        assert_int_equal(rte_pixel_format_parse(rte_pixel_format_name(formats[i])), formats[i]);
    assert_string_equal(rte_pixel_format_name(RTE_PIXEL_YUYV), "yuyv");
    assert_string_equal(rte_pixel_format_name((rte_pixel_format)42), "unknown");
    assert_int_equal(rte_pixel_format_parse("NV12"), RTE_PIXEL_NV12);
    assert_int_equal(rte_pixel_format_parse("Gray"), RTE_PIXEL_GREY);
    assert_int_equal(rte_pixel_format_parse("YUY2"), RTE_PIXEL_YUYV);
    assert_int_equal(rte_pixel_format_parse("nv1"), 0);
    assert_int_equal(rte_pixel_format_parse("nv121"), 0);
    assert_int_equal(rte_pixel_format_parse(""), 0);
    assert_int_equal(rte_pixel_format_parse(NULL), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(primaries_give_hand_computed_grey),
        cmocka_unit_test(bgr_and_rgb_rows_of_every_width),
        cmocka_unit_test(grey_colours_stay_grey),
        cmocka_unit_test(packed_422_takes_the_y_samples),
        cmocka_unit_test(packed_422_of_every_width),
        cmocka_unit_test(nv12_and_grey_give_their_y_plane),
        cmocka_unit_test(one_pixel_frames),
        cmocka_unit_test(constant_frames_of_all_formats),
        cmocka_unit_test(chroma_half_of_every_format),
        cmocka_unit_test(frame_checks_reject_bad_frames),
        cmocka_unit_test(format_names_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
