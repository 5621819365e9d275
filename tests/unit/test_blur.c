/* Blur family: Gaussian kernel construction, Gaussian blur and median blur.
 * The blurs are checked against direct (slow, obviously correct) reference
 * implementations written here; the taps against values read from OpenCV
 * 4.6 (cv2.GaussianBlur responses). */
#include "unit.h"

#include <math.h>

#include "rtedge/arena.h"
#include "rtedge/blur.h"

static uint8_t arena_memory[1 << 16];

static rte_arena make_arena(void)
{
    rte_arena a;
    rte_arena_init(&a, arena_memory, sizeof arena_memory);
    return a;
}

static void fill_random(rte_image_u8 *img, uint32_t *seed, uint32_t levels)
{
    for (int32_t y = 0; y < img->height; y++)
        for (int32_t x = 0; x < img->width; x++)
            rte_u8_row(img, y)[x] = (uint8_t)(unit_rand(seed) % levels * (255 / (levels - 1)));
}

static void assert_same_pixels(const rte_image_u8 *a, const rte_image_u8 *b)
{
    for (int32_t y = 0; y < a->height; y++)
        assert_memory_equal(rte_u8_row(a, y), rte_u8_row(b, y), (size_t)a->width);
}

static void assert_taps(const uint16_t *taps, const uint16_t *expected, int32_t n)
{
    for (int32_t i = 0; i < n; i++)
        assert_int_equal(taps[i], expected[i]);
}

/* One blur under test and its direct reference, with a parameter each. */
typedef struct blur_case {
    rte_status (*run)(const rte_image_u8 *src, rte_image_u8 *dst, const void *param, rte_arena *a);
    void (*reference)(const rte_image_u8 *src, rte_image_u8 *dst, const void *param);
    const void *param;
} blur_case;

/* Blurs src into a padded destination and, on a copy, in place; both must
 * equal the reference, leave all padding alone and give the arena back. */
static void assert_blur_matches_reference(const rte_image_u8 *src, const blur_case *c)
{
    rte_image_u8 dst = unit_image_u8(src->width, src->height, 3, 0);
    rte_image_u8 ref = unit_image_u8(src->width, src->height, 0, 0);
    rte_arena a = make_arena();
    assert_int_equal(c->run(src, &dst, c->param, &a), RTE_OK);
    assert_int_equal(a.used, 0);
    c->reference(src, &ref, c->param);
    assert_same_pixels(&dst, &ref);
    unit_assert_padding_u8(&dst);
    unit_assert_padding_u8(src);
    for (int32_t y = 0; y < src->height; y++)
        memcpy(rte_u8_row(&dst, y), rte_u8_row(src, y), (size_t)src->width);
    assert_int_equal(c->run(&dst, &dst, c->param, &a), RTE_OK);
    assert_same_pixels(&dst, &ref);
    unit_assert_padding_u8(&dst);
    test_free(dst.buf);
    test_free(ref.buf);
}

/* ---- kernel construction ---- */

static void kernel_sigma0_uses_opencv_tables(void **state)
{
    static const uint16_t k3[] = {64, 128, 64};
    static const uint16_t k9[] = {4, 13, 30, 51, 60, 51, 30, 13, 4};
    static const uint16_t k11[] = {2, 7, 17, 31, 45, 52, 45, 31, 17, 7, 2};
    static const uint16_t k15[] = {1, 3, 6, 12, 20, 30, 36, 40, 36, 30, 20, 12, 6, 3, 1};
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, 9, 0, 0), RTE_OK);
    assert_int_equal(k.ksize_x, 3);
    assert_int_equal(k.ksize_y, 9);
    assert_taps(k.taps_x, k3, 3);
    assert_taps(k.taps_y, k9, 9);
    assert_int_equal(rte_gaussian_kernel_init(&k, 11, 15, 0, 0), RTE_OK);
    assert_taps(k.taps_x, k11, 11);
    assert_taps(k.taps_y, k15, 15);
    assert_int_equal(rte_gaussian_kernel_init(&k, 1, 1, 0, 0), RTE_OK);
    assert_int_equal(k.taps_x[0], 256);
}

static void kernel_from_sigma_and_size_from_sigma(void **state)
{
    static const uint16_t s05[] = {27, 202, 27};
    static const uint16_t s10[] = {14, 62, 104, 62, 14};
    static const uint16_t s20[] = {7, 17, 32, 46, 52, 46, 32, 17, 7};
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, 5, 0.5, 1.0), RTE_OK);
    assert_taps(k.taps_x, s05, 3);
    assert_taps(k.taps_y, s10, 5);
    /* sigma_y 0 means sigma_x; size 0 is round(6 sigma + 1) | 1 */
    assert_int_equal(rte_gaussian_kernel_init(&k, 9, 0, 2.0, 0), RTE_OK);
    assert_int_equal(k.ksize_y, 13);
    assert_taps(k.taps_x, s20, 9);
    assert_int_equal(rte_gaussian_kernel_init(&k, 0, 0, 1.0, 0.25), RTE_OK);
    assert_int_equal(k.ksize_x, 7);
    assert_int_equal(k.ksize_y, 3);
    assert_int_equal(rte_gaussian_kernel_init(&k, 0, 0, 2.3, 0), RTE_OK);
    assert_int_equal(k.ksize_x, 15);
    for (int32_t n = 1; n <= 15; n += 2) {
        for (double s = 0; s < 30; s += 0.37) {
            assert_int_equal(rte_gaussian_kernel_init(&k, n, n, s, s), RTE_OK);
            uint32_t sum = 0;
            for (int32_t i = 0; i < n; i++) {
                sum += k.taps_x[i];
                assert_int_equal(k.taps_x[i], k.taps_x[n - 1 - i]);
                assert_int_equal(k.taps_x[i], k.taps_y[i]);
            }
            assert_int_equal(sum, 256);
        }
    }
}

static void kernel_rejects_bad_parameters(void **state)
{
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(NULL, 3, 3, 0, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 4, 3, 0, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, -1, 0, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 0, 3, 0, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, 0, -1.0, -1.0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, 3, NAN, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, 3, 1.0, INFINITY), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_kernel_init(&k, 17, 3, 0, 0), RTE_ERR_UNSUPPORTED);
    assert_int_equal(rte_gaussian_kernel_init(&k, 0, 3, 2.5, 0), RTE_ERR_UNSUPPORTED);
    assert_int_equal(rte_gaussian_kernel_init(&k, 0, 3, 1e300, 0), RTE_ERR_UNSUPPORTED);
}

/* ---- Gaussian blur ---- */

static int32_t reflect101(int32_t i, int32_t n)
{
    if (n == 1)
        return 0;
    while (i < 0 || i >= n)
        i = i < 0 ? -i : 2 * n - 2 - i;
    return i;
}

/* OpenCV's fixed-point Gaussian, computed directly per pixel. */
static void reference_gaussian(const rte_image_u8 *src, rte_image_u8 *dst,
                               const rte_gaussian_kernel *k)
{
    int32_t rx = k->ksize_x / 2, ry = k->ksize_y / 2;
    for (int32_t y = 0; y < src->height; y++) {
        for (int32_t x = 0; x < src->width; x++) {
            uint64_t sum = 0;
            for (int32_t j = 0; j < k->ksize_y; j++) {
                const uint8_t *row = rte_u8_row(src, reflect101(y + j - ry, src->height));
                uint32_t h = 0;
                for (int32_t i = 0; i < k->ksize_x; i++)
                    h += k->taps_x[i] * row[reflect101(x + i - rx, src->width)];
                sum += (uint64_t)k->taps_y[j] * h;
            }
            rte_u8_row(dst, y)[x] = (uint8_t)((sum + (1u << 15)) >> 16);
        }
    }
}

static void gaussian_hand_checked_row(void **state)
{
    uint8_t in[5] = {0, 0, 255, 0, 0}, out[5];
    static const uint8_t expected[5] = {0, 64, 128, 64, 0};
    rte_image_u8 src = rte_image_u8_view(in, 5, 1, 0), dst = rte_image_u8_view(out, 5, 1, 0);
    rte_gaussian_kernel k;
    rte_arena a = make_arena();
    assert_int_equal(rte_gaussian_kernel_init(&k, 3, 3, 0, 0), RTE_OK);
    assert_int_equal(rte_gaussian_blur_u8(&src, &dst, &k, &a), RTE_OK);
    assert_memory_equal(out, expected, 5);
    /* the same as a column; the edge reflects (101): pixel 0 sees 0,0,0 */
    rte_image_u8 col_src = rte_image_u8_view(in, 1, 5, 1),
                 col_dst = rte_image_u8_view(out, 1, 5, 1);
    assert_int_equal(rte_gaussian_blur_u8(&col_src, &col_dst, &k, &a), RTE_OK);
    assert_memory_equal(out, expected, 5);
    assert_int_equal(a.used, 0);
}

static rte_status run_gaussian(const rte_image_u8 *src, rte_image_u8 *dst, const void *param,
                               rte_arena *a)
{
    return rte_gaussian_blur_u8(src, dst, (const rte_gaussian_kernel *)param, a);
}

static void gaussian_reference(const rte_image_u8 *src, rte_image_u8 *dst, const void *param)
{
    reference_gaussian(src, dst, (const rte_gaussian_kernel *)param);
}

static void gaussian_matches_direct_reference(void **state)
{
    uint32_t seed = 12345;
    static const int32_t sizes[][2] = {{3, 3}, {5, 5},  {15, 15}, {1, 7},
                                       {9, 1}, {13, 3}, {7, 11},  {1, 1}};
    for (int32_t w = 1; w <= 67; w += (w < 20 ? 1 : 7)) {
        int32_t h = 1 + (int32_t)(unit_rand(&seed) % 24);
        rte_image_u8 src = unit_image_u8(w, h, (int32_t)(unit_rand(&seed) % 5), 0);
        fill_random(&src, &seed, w % 3 ? 256 : 2);
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
            rte_gaussian_kernel k;
            double sigma = (s & 1) ? 0.0 : 0.4 + (s * 0.7);
            assert_int_equal(rte_gaussian_kernel_init(&k, sizes[s][0], sizes[s][1], sigma, 0),
                             RTE_OK);
            blur_case c = {run_gaussian, gaussian_reference, &k};
            assert_blur_matches_reference(&src, &c);
        }
        test_free(src.buf);
    }
}

static void gaussian_keeps_constants_and_works_in_place(void **state)
{
    static const uint8_t levels[] = {0, 255, 77};
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(&k, 15, 7, 3.0, 0.9), RTE_OK);
    for (size_t i = 0; i < sizeof levels; i++) {
        rte_image_u8 img = unit_image_u8(23, 9, 2, levels[i]);
        rte_arena a = make_arena();
        assert_int_equal(rte_gaussian_blur_u8(&img, &img, &k, &a), RTE_OK);
        for (int32_t y = 0; y < img.height; y++)
            for (int32_t x = 0; x < img.width; x++)
                assert_int_equal(rte_u8_row(&img, y)[x], levels[i]);
        unit_assert_padding_u8(&img);
        test_free(img.buf);
    }
    uint32_t seed = 99;
    rte_image_u8 img = unit_image_u8(40, 31, 5, 0), ref = unit_image_u8(40, 31, 0, 0);
    fill_random(&img, &seed, 256);
    reference_gaussian(&img, &ref, &k);
    rte_arena a = make_arena();
    assert_int_equal(rte_gaussian_blur_u8(&img, &img, &k, &a), RTE_OK);
    assert_same_pixels(&img, &ref);
    unit_assert_padding_u8(&img);
    test_free(img.buf);
    test_free(ref.buf);
}

static void gaussian_scratch_size_is_enough_and_checked(void **state)
{
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(&k, 15, 15, 0, 0), RTE_OK);
    size_t need = rte_gaussian_blur_u8_scratch_size(61, 10, &k);
    assert_true(need > 0);
    assert_int_equal(rte_gaussian_blur_u8_scratch_size(0, 10, &k), 0);
    assert_int_equal(rte_gaussian_blur_u8_scratch_size(10, 0, &k), 0);
    assert_int_equal(rte_gaussian_blur_u8_scratch_size(10, 10, NULL), 0);

    rte_image_u8 src = unit_image_u8(61, 10, 1, 9), dst = unit_image_u8(61, 10, 1, 200);
    for (size_t offset = 0; offset < RTE_ARENA_ALIGN; offset += 13) {
        rte_arena a;
        rte_arena_init(&a, arena_memory + offset, need);
        assert_int_equal(rte_gaussian_blur_u8(&src, &dst, &k, &a), RTE_OK);
        assert_int_equal(a.used, 0);
        assert_int_equal(rte_gaussian_blur_u8(&dst, &dst, &k, &a),
                         RTE_OK); /* in place needs most */
        assert_int_equal(a.used, 0);
        assert_true(a.high_water <= need);
    }
    /* too small: an error, the arena and the destination untouched */
    rte_arena a;
    rte_arena_init(&a, arena_memory, 64);
    memset(dst.buf, 200, (size_t)dst.stride * (size_t)dst.height);
    assert_int_equal(rte_gaussian_blur_u8(&src, &dst, &k, &a), RTE_ERR_NO_MEMORY);
    assert_int_equal(a.used, 0);
    for (int32_t y = 0; y < dst.height; y++)
        for (int32_t x = 0; x < dst.width; x++)
            assert_int_equal(rte_u8_row(&dst, y)[x], 200);
    test_free(src.buf);
    test_free(dst.buf);
}

static void gaussian_rejects_bad_arguments(void **state)
{
    uint8_t px[64];
    rte_image_u8 a8 = rte_image_u8_view(px, 8, 4, 0), b8 = rte_image_u8_view(px + 32, 8, 4, 0);
    rte_image_u8 other = rte_image_u8_view(px + 32, 7, 4, 0);
    rte_gaussian_kernel k;
    rte_arena a = make_arena();
    assert_int_equal(rte_gaussian_kernel_init(&k, 5, 5, 0, 0), RTE_OK);
    assert_int_equal(rte_gaussian_blur_u8(NULL, &b8, &k, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_blur_u8(&a8, &other, &k, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_gaussian_blur_u8(&a8, &b8, NULL, &a), RTE_ERR_ARGUMENT);
    rte_image_u8 same_buf = rte_image_u8_view(px, 8, 4, 9); /* same memory, another stride */
    assert_int_equal(rte_gaussian_blur_u8(&a8, &same_buf, &k, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_blur_u8(&a8, &b8, &k, NULL), RTE_ERR_ARGUMENT);
    rte_gaussian_kernel bad = k;
    bad.taps_x[0] = 17; /* asymmetric and no longer summing to 256 */
    assert_int_equal(rte_gaussian_blur_u8(&a8, &b8, &bad, &a), RTE_ERR_ARGUMENT);
    bad = k;
    bad.ksize_y = 4;
    assert_int_equal(rte_gaussian_blur_u8(&a8, &b8, &bad, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_gaussian_blur_u8_scratch_size(8, 4, &bad), 0);
    bad = k;
    bad.taps_y[0] = bad.taps_y[4] = 40; /* symmetric, sum 304: would overflow u16 */
    assert_int_equal(rte_gaussian_blur_u8(&a8, &b8, &bad, &a), RTE_ERR_ARGUMENT);
}

/* ---- median blur ---- */

static int32_t clamp(int32_t i, int32_t n) { return i < 0 ? 0 : i >= n ? n - 1 : i; }

static void reference_median(const rte_image_u8 *src, rte_image_u8 *dst, int32_t ksize)
{
    int32_t r = ksize / 2;
    for (int32_t y = 0; y < src->height; y++) {
        for (int32_t x = 0; x < src->width; x++) {
            uint32_t hist[256] = {0};
            for (int32_t j = -r; j <= r; j++)
                for (int32_t i = -r; i <= r; i++)
                    hist[rte_u8_row(src, clamp(y + j, src->height))[clamp(x + i, src->width)]]++;
            uint32_t seen = 0, v = 0;
            while ((seen += hist[v]) <= (uint32_t)(ksize * ksize / 2))
                v++;
            rte_u8_row(dst, y)[x] = (uint8_t)v;
        }
    }
}

static rte_status run_median(const rte_image_u8 *src, rte_image_u8 *dst, const void *param,
                             rte_arena *a)
{
    return rte_median_blur_u8(src, dst, *(const int32_t *)param, a);
}

static void median_reference(const rte_image_u8 *src, rte_image_u8 *dst, const void *param)
{
    reference_median(src, dst, *(const int32_t *)param);
}

static void median_matches_direct_reference(void **state)
{
    uint32_t seed = 777;
    for (int32_t w = 1; w <= 67; w += (w < 24 ? 1 : 5)) {
        int32_t h = 1 + (int32_t)(unit_rand(&seed) % 20);
        rte_image_u8 src = unit_image_u8(w, h, (int32_t)(unit_rand(&seed) % 4), 0);
        fill_random(&src, &seed, (w & 1) ? 256 : 3);
        for (int32_t ksize = 1; ksize <= 5; ksize += 2) {
            blur_case c = {run_median, median_reference, &ksize};
            assert_blur_matches_reference(&src, &c);
        }
        test_free(src.buf);
    }
}

/* The median kernels are min/max networks, so by the 0-1 principle they are
 * right for every input if they are right for every 0/1 input. 3x3: all 512
 * binary windows (the centre pixel sees no border). */
static void median3_network_proven_on_all_binary_windows(void **state)
{
    uint8_t in[9], out[9];
    rte_image_u8 src = rte_image_u8_view(in, 3, 3, 0), dst = rte_image_u8_view(out, 3, 3, 0);
    for (uint32_t bits = 0; bits < 512; bits++) {
        uint32_t ones = 0;
        for (int i = 0; i < 9; i++) {
            in[i] = (bits >> i) & 1 ? 255 : 0;
            ones += (bits >> i) & 1;
        }
        rte_arena a = make_arena();
        assert_int_equal(rte_median_blur_u8(&src, &dst, 3, &a), RTE_OK);
        assert_int_equal(out[4], ones >= 5 ? 255 : 0);
    }
}

/* 5x5: the kernel first sorts each column with a 5-sorting network, so after
 * that step a 0/1 window is five columns of the form 0..01..1: checking the
 * sort on all 32 binary columns and the rest on all 6^5 sorted-column windows
 * covers all 2^25 binary windows. */
static void median5_network_proven_on_all_binary_windows(void **state)
{
    uint8_t in[25], out[25];
    rte_image_u8 src = rte_image_u8_view(in, 5, 5, 0), dst = rte_image_u8_view(out, 5, 5, 0);
    for (uint32_t bits = 0; bits < 32; bits++) { /* one column, the others all 0 or all 1 */
        for (int32_t fill = 0; fill <= 1; fill++) {
            uint32_t ones = 0;
            for (int32_t i = 0; i < 25; i++) {
                int32_t one = (i % 5 == 2) ? (int32_t)((bits >> (i / 5)) & 1) : fill;
                in[i] = one ? 255 : 0;
                ones += (uint32_t)one;
            }
            rte_arena a = make_arena();
            assert_int_equal(rte_median_blur_u8(&src, &dst, 5, &a), RTE_OK);
            assert_int_equal(out[12], ones >= 13 ? 255 : 0);
        }
    }
    for (uint32_t code = 0; code < 7776; code++) {
        uint32_t c = code, ones = 0;
        for (int32_t x = 0; x < 5; x++, c /= 6) {
            uint32_t zeros = c % 6; /* the first `zeros` rows of column x are 0 */
            for (int32_t y = 0; y < 5; y++)
                in[y * 5 + x] = (uint32_t)y < zeros ? 0 : 255;
            ones += 5 - zeros;
        }
        rte_arena a = make_arena();
        assert_int_equal(rte_median_blur_u8(&src, &dst, 5, &a), RTE_OK);
        assert_int_equal(out[12], ones >= 13 ? 255 : 0);
    }
}

static void median_small_and_thin_images(void **state)
{
    uint32_t seed = 4242;
    static const int32_t dims[][2] = {{1, 1}, {1, 9}, {9, 1}, {2, 2}, {4, 3}, {33, 17}};
    for (size_t d = 0; d < sizeof dims / sizeof dims[0]; d++) {
        rte_image_u8 src = unit_image_u8(dims[d][0], dims[d][1], 3, 0);
        fill_random(&src, &seed, 256);
        for (int32_t ksize = 3; ksize <= 5; ksize += 2) {
            blur_case c = {run_median, median_reference, &ksize};
            assert_blur_matches_reference(&src, &c);
        }
        test_free(src.buf);
    }
}

static void median_scratch_and_arguments(void **state)
{
    uint8_t px[64];
    rte_image_u8 a8 = rte_image_u8_view(px, 8, 4, 0), b8 = rte_image_u8_view(px + 32, 8, 4, 0);
    rte_image_u8 other = rte_image_u8_view(px + 32, 8, 3, 0);
    rte_arena a = make_arena();
    assert_int_equal(rte_median_blur_u8(&a8, &b8, 7, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_median_blur_u8(&a8, &b8, 4, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_median_blur_u8(&a8, &b8, 3, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_median_blur_u8(&a8, &other, 3, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_median_blur_u8(&a8, NULL, 3, &a), RTE_ERR_ARGUMENT);
    rte_image_u8 same_buf = rte_image_u8_view(px, 8, 4, 9); /* same memory, another stride */
    assert_int_equal(rte_median_blur_u8(&a8, &same_buf, 3, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_median_blur_u8_scratch_size(8, 4, 7), 0);
    assert_int_equal(rte_median_blur_u8_scratch_size(0, 4, 3), 0);

    for (int32_t ksize = 3; ksize <= 5; ksize += 2) {
        size_t need = rte_median_blur_u8_scratch_size(100, 7, ksize);
        rte_image_u8 src = unit_image_u8(100, 7, 0, 1), dst = unit_image_u8(100, 7, 0, 2);
        rte_arena_init(&a, arena_memory + 5, need);
        assert_int_equal(rte_median_blur_u8(&src, &dst, ksize, &a), RTE_OK);
        assert_true(a.high_water <= need);
        assert_int_equal(dst.buf[0], 1);
        rte_arena_init(&a, arena_memory, need / 2);
        memset(dst.buf, 2, 700);
        assert_int_equal(rte_median_blur_u8(&src, &dst, ksize, &a), RTE_ERR_NO_MEMORY);
        assert_int_equal(dst.buf[0], 2);
        test_free(src.buf);
        test_free(dst.buf);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kernel_sigma0_uses_opencv_tables),
        cmocka_unit_test(kernel_from_sigma_and_size_from_sigma),
        cmocka_unit_test(kernel_rejects_bad_parameters),
        cmocka_unit_test(gaussian_hand_checked_row),
        cmocka_unit_test(gaussian_matches_direct_reference),
        cmocka_unit_test(gaussian_keeps_constants_and_works_in_place),
        cmocka_unit_test(gaussian_scratch_size_is_enough_and_checked),
        cmocka_unit_test(gaussian_rejects_bad_arguments),
        cmocka_unit_test(median_matches_direct_reference),
        cmocka_unit_test(median3_network_proven_on_all_binary_windows),
        cmocka_unit_test(median5_network_proven_on_all_binary_windows),
        cmocka_unit_test(median_small_and_thin_images),
        cmocka_unit_test(median_scratch_and_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
