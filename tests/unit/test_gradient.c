/* Sobel, Scharr, Laplacian and |x| saturation: hand-checked cases and a
 * direct 2-D reference with its own border folding on small images. */
#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/gradient.h"

static uint8_t arena_memory[1 << 16];

static rte_arena make_arena(void)
{
    rte_arena a;
    rte_arena_init(&a, arena_memory, sizeof arena_memory);
    return a;
}

/* Sobel taps written out by hand: [ksize index][order]. */
static const int sobel_taps[4][3][7] = {
    {{1}},                                                                          /* ksize 1 */
    {{1, 2, 1}, {-1, 0, 1}, {1, -2, 1}},                                            /* ksize 3 */
    {{1, 4, 6, 4, 1}, {-1, -2, 0, 2, 1}, {1, 0, -2, 0, 1}},                         /* ksize 5 */
    {{1, 6, 15, 20, 15, 6, 1}, {-1, -4, -5, 0, 5, 4, 1}, {1, 2, -1, -4, -1, 2, 1}}, /* 7 */
};

/* Reflect-101 is periodic with period 2 * (len - 1). */
static int fold101(int p, int len)
{
    if (len == 1)
        return 0;
    int period = 2 * (len - 1);
    p %= period;
    if (p < 0)
        p += period;
    return p < len ? p : period - p;
}

static int16_t sat16(long v) { return (int16_t)(v > 32767 ? 32767 : v < -32768 ? -32768 : v); }

/* 2-D correlation with an n x n kernel k (row-major), reflect-101. */
static void reference(const rte_image_u8 *src, const int *k, int n, int16_t *out)
{
    int r = n / 2;
    for (int y = 0; y < src->height; y++)
        for (int x = 0; x < src->width; x++) {
            long s = 0;
            for (int j = 0; j < n; j++)
                for (int i = 0; i < n; i++)
                    s += (long)k[j * n + i] *
                         src->buf[fold101(y + j - r, src->height) * src->stride +
                                  fold101(x + i - r, src->width)];
            out[y * src->width + x] = sat16(s);
        }
}

/* The 2-D Sobel kernel (square, the shorter axis zero-padded). */
static int sobel_kernel(int dx, int dy, int ksize, int *k)
{
    int nx = (ksize == 1 && dx > 0) ? 3 : ksize, ny = (ksize == 1 && dy > 0) ? 3 : ksize;
    int n = nx > ny ? nx : ny;
    const int *kx = sobel_taps[nx / 2][dx], *ky = sobel_taps[ny / 2][dy];
    memset(k, 0, sizeof(int) * (size_t)(n * n));
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            k[(j + (n - ny) / 2) * n + i + (n - nx) / 2] = kx[i] * ky[j];
    return n;
}

static void fill_random(rte_image_u8 *img, uint32_t *rng)
{
    int kind = (int)(unit_rand(rng) % 3);
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            img->buf[y * img->stride + x] = (uint8_t)(kind == 0   ? unit_rand(rng)
                                                      : kind == 1 ? (unit_rand(rng) & 1) * 255
                                                                  : (x * 37 + y * 11) & 255);
}

static void assert_matches(const rte_image_s16 *dst, const int16_t *expected)
{
    for (int y = 0; y < dst->height; y++)
        for (int x = 0; x < dst->width; x++)
            assert_int_equal(dst->buf[y * dst->stride + x], expected[y * dst->width + x]);
    unit_assert_padding_s16(dst);
}

static void sobel_dx3_of_ramp(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(5, 4, 3, 0);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 5; x++)
            src.buf[y * src.stride + x] = (uint8_t)(10 * x);
    rte_image_s16 dst = unit_image_s16(5, 4, 2);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 3, &a), RTE_OK);
    /* Inside: (s[x+1] - s[x-1]) * (1+2+1) = 80; the mirrored edges give 0. */
    static const int16_t row[5] = {0, 80, 80, 80, 0};
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 5; x++)
            assert_int_equal(dst.buf[y * dst.stride + x], row[x]);
    /* ksize 1: no smoothing, so 20 inside. */
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 1, &a), RTE_OK);
    assert_int_equal(dst.buf[2 * dst.stride + 2], 20);
    /* dy of a horizontal ramp is 0. */
    assert_int_equal(rte_sobel_s16(&src, &dst, 0, 1, 3, &a), RTE_OK);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 5; x++)
            assert_int_equal(dst.buf[y * dst.stride + x], 0);
    unit_assert_padding_s16(&dst);
    assert_int_equal(rte_arena_mark(&a), 0);
    test_free(src.buf);
    test_free(dst.buf);
}

/* The response to an impulse is the kernel turned by 180 degrees. */
static void sobel_impulse_response_is_the_kernel(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(15, 15, 1, 0);
    src.buf[7 * src.stride + 7] = 3;
    rte_image_s16 dst = unit_image_s16(15, 15, 5);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 5, &a), RTE_OK);
    static const int kx[5] = {-1, -2, 0, 2, 1}, ky[5] = {1, 4, 6, 4, 1};
    for (int y = 0; y < 15; y++)
        for (int x = 0; x < 15; x++) {
            int i = 7 - x + 2, j = 7 - y + 2;
            int want = (i >= 0 && i < 5 && j >= 0 && j < 5) ? 3 * kx[i] * ky[j] : 0;
            assert_int_equal(dst.buf[y * dst.stride + x], want);
        }
    test_free(src.buf);
    test_free(dst.buf);
}

static void sobel7_saturates(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(16, 9, 2, 0);
    for (int y = 0; y < 9; y++)
        memset(src.buf + y * src.stride + 8, 255, 8);
    rte_image_s16 dst = unit_image_s16(16, 9, 0);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 7, &a), RTE_OK);
    /* 255 * (5 + 4 + 1) * 64 = 163200 -> 32767. */
    assert_int_equal(dst.buf[4 * dst.stride + 7], 32767);
    for (int y = 0; y < 9; y++)
        for (int x = 0; x < 16; x++)
            src.buf[y * src.stride + x] = (uint8_t)(255 - src.buf[y * src.stride + x]);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 7, &a), RTE_OK);
    assert_int_equal(dst.buf[4 * dst.stride + 7], -32768);
    test_free(src.buf);
    test_free(dst.buf);
}

static void laplacian_impulse(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(5, 5, 1, 0);
    src.buf[2 * src.stride + 2] = 1;
    rte_image_s16 dst = unit_image_s16(5, 5, 1);
    assert_int_equal(rte_laplacian_s16(&src, &dst, 1, &a), RTE_OK);
    assert_int_equal(dst.buf[2 * dst.stride + 2], -4);
    assert_int_equal(dst.buf[1 * dst.stride + 2], 1);
    assert_int_equal(dst.buf[2 * dst.stride + 3], 1);
    assert_int_equal(dst.buf[1 * dst.stride + 1], 0);
    assert_int_equal(rte_laplacian_s16(&src, &dst, 3, &a), RTE_OK);
    assert_int_equal(dst.buf[2 * dst.stride + 2], -8);
    assert_int_equal(dst.buf[1 * dst.stride + 2], 0);
    assert_int_equal(dst.buf[1 * dst.stride + 1], 2);
    assert_int_equal(dst.buf[3 * dst.stride + 3], 2);
    unit_assert_padding_s16(&dst);
    test_free(src.buf);
    test_free(dst.buf);
}

/* Every order and size, Scharr and Laplacian on widths 1..67 (heights 1..9)
 * with stride > width, against the direct reference. */
static void all_kernels_match_reference(void **state)
{
    static int16_t expected[67 * 9];
    int k[49];
    uint32_t rng = 12345;
    rte_arena a = make_arena();
    for (int w = 1; w <= 67; w++) {
        int h = 1 + (int)(unit_rand(&rng) % 9);
        rte_image_u8 src = unit_image_u8(w, h, (int)(unit_rand(&rng) % 5), 0);
        fill_random(&src, &rng);
        rte_image_s16 dst = unit_image_s16(w, h, (int)(unit_rand(&rng) % 5));
        for (int ks = 1; ks <= 7; ks += 2)
            for (int dy = 0; dy <= 2; dy++)
                for (int dx = 0; dx <= 2; dx++) {
                    if (dx + dy == 0)
                        continue;
                    int n = sobel_kernel(dx, dy, ks, k);
                    reference(&src, k, n, expected);
                    assert_int_equal(rte_sobel_s16(&src, &dst, dx, dy, ks, &a), RTE_OK);
                    assert_matches(&dst, expected);
                }
        static const int scharr_x[9] = {-3, 0, 3, -10, 0, 10, -3, 0, 3};
        static const int scharr_y[9] = {-3, -10, -3, 0, 0, 0, 3, 10, 3};
        static const int lap1[9] = {0, 1, 0, 1, -4, 1, 0, 1, 0};
        static const int lap3[9] = {2, 0, 2, 0, -8, 0, 2, 0, 2};
        reference(&src, scharr_x, 3, expected);
        assert_int_equal(rte_scharr_s16(&src, &dst, 1, 0, &a), RTE_OK);
        assert_matches(&dst, expected);
        reference(&src, scharr_y, 3, expected);
        assert_int_equal(rte_scharr_s16(&src, &dst, 0, 1, &a), RTE_OK);
        assert_matches(&dst, expected);
        reference(&src, lap1, 3, expected);
        assert_int_equal(rte_laplacian_s16(&src, &dst, 1, &a), RTE_OK);
        assert_matches(&dst, expected);
        reference(&src, lap3, 3, expected);
        assert_int_equal(rte_laplacian_s16(&src, &dst, 3, &a), RTE_OK);
        assert_matches(&dst, expected);
        assert_int_equal(rte_arena_mark(&a), 0);
        test_free(src.buf);
        test_free(dst.buf);
    }
}

static void flat_images_have_no_gradient(void **state)
{
    static const uint8_t levels[3] = {0, 255, 77};
    rte_arena a = make_arena();
    for (int l = 0; l < 3; l++) {
        rte_image_u8 src = unit_image_u8(9, 6, 3, levels[l]);
        rte_image_s16 dst = unit_image_s16(9, 6, 1);
        for (int ks = 1; ks <= 7; ks += 2) {
            assert_int_equal(rte_sobel_s16(&src, &dst, 2, 1, ks, &a), RTE_OK);
            for (int y = 0; y < 6; y++)
                for (int x = 0; x < 9; x++)
                    assert_int_equal(dst.buf[y * dst.stride + x], 0);
        }
        assert_int_equal(rte_laplacian_s16(&src, &dst, 3, &a), RTE_OK);
        for (int y = 0; y < 6; y++)
            for (int x = 0; x < 9; x++)
                assert_int_equal(dst.buf[y * dst.stride + x], 0);
        unit_assert_padding_s16(&dst);
        test_free(src.buf);
        test_free(dst.buf);
    }
}

static void one_pixel_image(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(1, 1, 0, 200);
    rte_image_s16 dst = unit_image_s16(1, 1, 1);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 1, 7, &a), RTE_OK);
    assert_int_equal(dst.buf[0], 0);
    assert_int_equal(rte_laplacian_s16(&src, &dst, 1, &a), RTE_OK);
    assert_int_equal(dst.buf[0], 0);
    unit_assert_padding_s16(&dst);
    test_free(src.buf);
    test_free(dst.buf);
}

static void abs_saturates(void **state)
{
    static const int16_t in[6] = {-32768, -5, 0, 7, 255, 300};
    static const uint8_t want[6] = {255, 5, 0, 7, 255, 255};
    rte_image_s16 src = unit_image_s16(6, 2, 3);
    for (int y = 0; y < 2; y++)
        memcpy(src.buf + y * src.stride, in, sizeof in);
    rte_image_u8 dst = unit_image_u8(6, 2, 4, 0);
    assert_int_equal(rte_abs_s16_u8(&src, &dst), RTE_OK);
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 6; x++)
            assert_int_equal(dst.buf[y * dst.stride + x], want[x]);
    unit_assert_padding_u8(&dst);
    rte_image_u8 small = unit_image_u8(5, 2, 0, 0);
    assert_int_equal(rte_abs_s16_u8(&src, &small), RTE_ERR_SIZE);
    assert_int_equal(rte_abs_s16_u8(NULL, &dst), RTE_ERR_ARGUMENT);
    test_free(src.buf);
    test_free(dst.buf);
    test_free(small.buf);
}

static void bad_arguments(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(40, 3, 0, 1);
    rte_image_s16 dst = unit_image_s16(40, 3, 0);
    rte_image_s16 other = unit_image_s16(39, 3, 0);
    assert_int_equal(rte_sobel_s16(&src, &dst, 0, 0, 3, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_sobel_s16(&src, &dst, 3, 0, 3, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_sobel_s16(&src, &dst, -1, 1, 3, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 2, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 9, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 3, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_sobel_s16(&src, &other, 1, 0, 3, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_sobel_s16(NULL, &dst, 1, 0, 3, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_scharr_s16(&src, &dst, 1, 1, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_scharr_s16(&src, &dst, 2, 0, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_laplacian_s16(&src, &dst, 5, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_laplacian_s16(&src, &other, 1, &a), RTE_ERR_SIZE);

    /* An arena one byte short of the stated size fails cleanly; the stated
     * size works at any alignment of the memory. */
    static uint8_t mem[4096];
    size_t need = rte_sobel_scratch_size(40, 3, 7);
    size_t need_lap = rte_laplacian_scratch_size(40, 3, 3);
    for (size_t off = 0; off < RTE_ARENA_ALIGN; off += 7) {
        rte_arena small;
        rte_arena_init(&small, mem + off, need - 1);
        if (rte_sobel_s16(&src, &dst, 1, 0, 7, &small) != RTE_OK)
            assert_int_equal(small.used, 0);
        rte_arena_init(&small, mem + off, need);
        assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 7, &small), RTE_OK);
        rte_arena_init(&small, mem + off, need_lap);
        assert_int_equal(rte_laplacian_s16(&src, &dst, 3, &small), RTE_OK);
    }
    rte_arena none;
    rte_arena_init(&none, mem, 16);
    assert_int_equal(rte_sobel_s16(&src, &dst, 1, 0, 3, &none), RTE_ERR_NO_MEMORY);
    assert_int_equal(rte_laplacian_s16(&src, &dst, 3, &none), RTE_ERR_NO_MEMORY);
    assert_int_equal(none.used, 0);
    test_free(src.buf);
    test_free(dst.buf);
    test_free(other.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sobel_dx3_of_ramp),
        cmocka_unit_test(sobel_impulse_response_is_the_kernel),
        cmocka_unit_test(sobel7_saturates),
        cmocka_unit_test(laplacian_impulse),
        cmocka_unit_test(all_kernels_match_reference),
        cmocka_unit_test(flat_images_have_no_gradient),
        cmocka_unit_test(one_pixel_image),
        cmocka_unit_test(abs_saturates),
        cmocka_unit_test(bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
