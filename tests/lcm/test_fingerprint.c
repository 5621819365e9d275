/* rtedge.image_t is wire-compatible with libbot's bot_core.image_t: the same
 * fingerprint (which covers field names, types and order, recursively) and
 * the same bytes for the same image, each decodable as the other. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "bot_core_image_t.h"
#include "rtedge_image_t.h"
#include "rtedge_status_t.h"

static void test_fingerprints_equal(void **state)
{
    (void)state;
    assert_int_equal(__rtedge_image_t_get_hash(), __bot_core_image_t_get_hash());
    assert_int_equal(__rtedge_image_metadata_t_get_hash(), __bot_core_image_metadata_t_get_hash());
    /* ... and the comparison can fail: another type's differs. */
    assert_int_not_equal(__rtedge_status_t_get_hash(), __bot_core_image_t_get_hash());
}

static void test_same_bytes(void **state)
{
    (void)state;
    uint8_t pixels[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    uint8_t value[2] = {0xAB, 0xCD};
    rtedge_image_metadata_t rm = {(char *)"gain", 2, value};
    bot_core_image_metadata_t bm = {(char *)"gain", 2, value};
    rtedge_image_t r = {123456789, 4, 3, 4, RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY, 12, pixels, 1, &rm};
    bot_core_image_t b = {123456789, 4, 3, 4, 1497715271, 12, pixels, 1, &bm};
    uint8_t rb[256], bb[256];
    int rn = rtedge_image_t_encode(rb, 0, sizeof rb, &r);
    int bn = bot_core_image_t_encode(bb, 0, sizeof bb, &b);
    assert_true(rn > 0);
    assert_int_equal(rn, bn);
    assert_memory_equal(rb, bb, (size_t)rn);

    bot_core_image_t decoded;
    assert_int_equal(bot_core_image_t_decode(rb, 0, rn, &decoded), rn);
    assert_int_equal(decoded.pixelformat, 1497715271);
    assert_memory_equal(decoded.data, pixels, 12);
    assert_string_equal(decoded.metadata[0].key, "gain");
    bot_core_image_t_decode_cleanup(&decoded);
}

static void test_pixel_formats_are_fourccs(void **state)
{
    (void)state;
#define FOURCC(a, b, c, d) \
    ((int32_t)((uint32_t)(a) | (uint32_t)(b) << 8 | (uint32_t)(c) << 16 | (uint32_t)(d) << 24))
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_UYVY, 1498831189);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_UYVY, FOURCC('U', 'Y', 'V', 'Y'));
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_YUYV, 1448695129);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_NV12, 842094158);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY, 1497715271);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY, FOURCC('G', 'R', 'E', 'Y'));
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_RGB, 859981650);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_BGR, 861030210);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_MJPEG, 1196444237);
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_I420, FOURCC('I', '4', '2', '0'));
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_RGBA, FOURCC('R', 'G', 'B', '4'));
    assert_int_equal(RTEDGE_IMAGE_T_PIXEL_FORMAT_BGRA, FOURCC('B', 'G', 'R', '4'));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fingerprints_equal),
        cmocka_unit_test(test_same_bytes),
        cmocka_unit_test(test_pixel_formats_are_fourccs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
