/* rte_distance_transform_u8: argument checks, hand-worked values, the
 * border rules and the caps (the oracle suite compares it with OpenCV). */
#include "unit.h"

#include "rtedge/distance.h"

static rte_image_u16 image_u16(int32_t w, int32_t h, int32_t pad)
{
    int32_t stride = w + pad;
    uint16_t *buf = (uint16_t *)test_malloc((size_t)stride * h * sizeof(uint16_t));
    for (size_t i = 0; i < (size_t)stride * h; i++)
        buf[i] = 0xEEEE;
    rte_image_u16 img = {w, h, stride, buf};
    return img;
}

static void assert_padding_u16(const rte_image_u16 *img)
{
    for (int32_t y = 0; y < img->height; y++)
        for (int32_t x = img->width; x < img->stride; x++)
            assert_int_equal(img->buf[(size_t)y * img->stride + x], 0xEEEE);
}

static uint16_t at(const rte_image_u16 *img, int32_t x, int32_t y)
{
    return rte_u16_row(img, y)[x];
}

static void arguments(void **state)
{
    rte_image_u8 src = unit_image_u8(6, 4, 2, 255);
    rte_image_u16 dst = image_u16(6, 4, 1);
    assert_int_equal(rte_distance_transform_u8(NULL, &dst, RTE_DIST_L1, RTE_DIST_BORDER_FAR),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_distance_transform_u8(&src, NULL, RTE_DIST_L1, RTE_DIST_BORDER_FAR),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_distance_transform_u8(&src, &dst, (rte_dist_metric)2, RTE_DIST_BORDER_FAR),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_distance_transform_u8(&src, &dst, RTE_DIST_C, (rte_dist_border)2),
                     RTE_ERR_ARGUMENT);
    rte_image_u16 other = dst;
    other.width = 5;
    assert_int_equal(rte_distance_transform_u8(&src, &other, RTE_DIST_C, RTE_DIST_BORDER_FAR),
                     RTE_ERR_SIZE);
    other = dst;
    other.height = 3;
    assert_int_equal(rte_distance_transform_u8(&src, &other, RTE_DIST_C, RTE_DIST_BORDER_FAR),
                     RTE_ERR_SIZE);
    other = dst;
    other.stride = 5;
    assert_int_equal(rte_distance_transform_u8(&src, &other, RTE_DIST_C, RTE_DIST_BORDER_FAR),
                     RTE_ERR_SIZE);
    other.buf = NULL;
    other.stride = 7;
    assert_int_equal(rte_distance_transform_u8(&src, &other, RTE_DIST_C, RTE_DIST_BORDER_FAR),
                     RTE_ERR_ARGUMENT);
    rte_image_u8 bad = src;
    bad.width = 0;
    assert_int_equal(rte_distance_transform_u8(&bad, &dst, RTE_DIST_C, RTE_DIST_BORDER_FAR),
                     RTE_ERR_SIZE);
    /* nothing was written */
    for (int32_t y = 0; y < 4; y++)
        for (int32_t x = 0; x < 6; x++)
            assert_int_equal(at(&dst, x, y), 0xEEEE);
    assert_int_equal(rte_distance_unit(RTE_DIST_L1), 1);
    assert_int_equal(rte_distance_unit(RTE_DIST_C), 1);
    assert_int_equal(rte_distance_unit(RTE_DIST_CHAMFER34), 3);
    assert_int_equal(rte_distance_unit((rte_dist_metric)0), 0);
    test_free(src.buf);
    test_free(dst.buf);
}

/* One zero pixel at (3, 2) of a 7x5 image: each metric's distance from it,
 * written out by hand. */
static void one_zero_pixel(void **state)
{
    static const uint16_t l1[5][7] = {{5, 4, 3, 2, 3, 4, 5},
                                      {4, 3, 2, 1, 2, 3, 4},
                                      {3, 2, 1, 0, 1, 2, 3},
                                      {4, 3, 2, 1, 2, 3, 4},
                                      {5, 4, 3, 2, 3, 4, 5}};
    static const uint16_t c[5][7] = {{3, 2, 2, 2, 2, 2, 3},
                                     {3, 2, 1, 1, 1, 2, 3},
                                     {3, 2, 1, 0, 1, 2, 3},
                                     {3, 2, 1, 1, 1, 2, 3},
                                     {3, 2, 2, 2, 2, 2, 3}};
    static const uint16_t ch[5][7] = {{11, 8, 7, 6, 7, 8, 11},
                                      {10, 7, 4, 3, 4, 7, 10},
                                      {9, 6, 3, 0, 3, 6, 9},
                                      {10, 7, 4, 3, 4, 7, 10},
                                      {11, 8, 7, 6, 7, 8, 11}};
    const rte_dist_metric metrics[] = {RTE_DIST_L1, RTE_DIST_C, RTE_DIST_CHAMFER34};
    const uint16_t(*expected[])[7] = {l1, c, ch};
    rte_image_u8 src = unit_image_u8(7, 5, 3, 1);
    src.buf[2 * src.stride + 3] = 0;
    for (int m = 0; m < 3; m++) {
        rte_image_u16 dst = image_u16(7, 5, 2);
        assert_int_equal(rte_distance_transform_u8(&src, &dst, metrics[m], RTE_DIST_BORDER_FAR),
                         RTE_OK);
        for (int32_t y = 0; y < 5; y++)
            for (int32_t x = 0; x < 7; x++)
                assert_int_equal(at(&dst, x, y), expected[m][y][x]);
        assert_padding_u16(&dst);
        test_free(dst.buf);
    }
    unit_assert_padding_u8(&src);
    test_free(src.buf);
}

/* No zero pixel: OpenCV's cap with BORDER_FAR, the distance to the frame
 * with BORDER_ZERO; 1xN and Nx1 images. */
static void borders_and_caps(void **state)
{
    rte_image_u8 src = unit_image_u8(9, 4, 0, 200);
    rte_image_u16 dst = image_u16(9, 4, 0);
    assert_int_equal(rte_distance_transform_u8(&src, &dst, RTE_DIST_L1, RTE_DIST_BORDER_FAR),
                     RTE_OK);
    for (int32_t y = 0; y < 4; y++)
        for (int32_t x = 0; x < 9; x++)
            assert_int_equal(at(&dst, x, y), RTE_DIST_CAP);
    assert_int_equal(rte_distance_transform_u8(&src, &dst, RTE_DIST_CHAMFER34, RTE_DIST_BORDER_FAR),
                     RTE_OK);
    assert_int_equal(at(&dst, 4, 2), UINT16_MAX);
    assert_int_equal(
        rte_distance_transform_u8(&src, &dst, RTE_DIST_CHAMFER34, RTE_DIST_BORDER_ZERO), RTE_OK);
    for (int32_t y = 0; y < 4; y++)
        for (int32_t x = 0; x < 9; x++) {
            int32_t to_frame = 1 + (y < 3 - y ? y : 3 - y);
            int32_t side = 1 + (x < 8 - x ? x : 8 - x);
            assert_int_equal(at(&dst, x, y), 3 * (to_frame < side ? to_frame : side));
        }
    test_free(src.buf);
    test_free(dst.buf);

    /* a row 1x20000 with a zero at its start: the distance climbs to the cap */
    src = unit_image_u8(20000, 1, 0, 1);
    dst = image_u16(20000, 1, 0);
    src.buf[0] = 0;
    assert_int_equal(rte_distance_transform_u8(&src, &dst, RTE_DIST_C, RTE_DIST_BORDER_FAR),
                     RTE_OK);
    assert_int_equal(at(&dst, 0, 0), 0);
    assert_int_equal(at(&dst, 8191, 0), 8191);
    assert_int_equal(at(&dst, 8192, 0), 8192);
    assert_int_equal(at(&dst, 19999, 0), 8192);
    test_free(src.buf);
    test_free(dst.buf);

    /* a column with BORDER_ZERO: the distance to the nearer end */
    src = unit_image_u8(1, 7, 2, 255);
    dst = image_u16(1, 7, 1);
    assert_int_equal(rte_distance_transform_u8(&src, &dst, RTE_DIST_L1, RTE_DIST_BORDER_ZERO),
                     RTE_OK);
    static const uint16_t column[7] = {1, 1, 1, 1, 1, 1, 1};
    for (int32_t y = 0; y < 7; y++)
        assert_int_equal(at(&dst, 0, y), column[y]);
    assert_padding_u16(&dst);
    test_free(src.buf);
    test_free(dst.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(arguments),
        cmocka_unit_test(one_zero_pixel),
        cmocka_unit_test(borders_and_caps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
