/* Canny: threshold conversion, hand-checked edges (steps, hysteresis,
 * 1xN / Nx1 / 1x1), arena sizing and argument errors; the fused front end
 * (rte_canny_blurred_u8) against blur-then-Canny; the derivatives handed
 * out by rte_canny_gradient_u8. */
#include <math.h>

#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/canny.h"

static uint8_t arena_memory[1 << 17];

static rte_arena make_arena(void)
{
    rte_arena a;
    rte_arena_init(&a, arena_memory, sizeof arena_memory);
    return a;
}

static void params_convert_thresholds(void **state)
{
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 100, 50, 3, false), RTE_OK); /* swapped */
    assert_int_equal(p.low, 50);
    assert_int_equal(p.high, 100);
    assert_int_equal(p.aperture, 3);
    assert_false(p.l2_gradient);
    assert_int_equal(rte_canny_params_init(&p, 20.7, 60.2, 5, false), RTE_OK); /* floored */
    assert_int_equal(p.low, 20);
    assert_int_equal(p.high, 60);
    assert_int_equal(rte_canny_params_init(&p, 10.5, 40000, 3, true), RTE_OK);
    assert_int_equal(p.low, 110);            /* floor(10.5^2) */
    assert_int_equal(p.high, 32767 * 32767); /* clamped, then squared */
    assert_int_equal(rte_canny_params_init(&p, -5.5, 0, 3, true), RTE_OK);
    assert_int_equal(p.low, -6); /* negative: not squared */
    assert_int_equal(p.high, 0);
    /* Beyond int32: OpenCV's x86-64 floor gives INT32_MIN above, INT32_MAX below. */
    assert_int_equal(rte_canny_params_init(&p, -1e10, 1e10, 3, false), RTE_OK);
    assert_int_equal(p.low, INT32_MAX);
    assert_int_equal(p.high, INT32_MIN);
    assert_int_equal(rte_canny_params_init(&p, 1, 2, 4, false), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_params_init(&p, 1, 2, 9, false), RTE_ERR_ARGUMENT);
    /* Aperture 7: thresholds divided by 16 first (OpenCV scales that Sobel by 1/16). */
    assert_int_equal(rte_canny_params_init(&p, 160, 50, 7, true), RTE_OK);
    assert_int_equal(p.low, 9);    /* floor((50/16)^2) = floor(9.77) */
    assert_int_equal(p.high, 100); /* (160/16)^2 */
    assert_int_equal(rte_canny_params_init(&p, NAN, 2, 3, false), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_params_init(NULL, 1, 2, 3, false), RTE_ERR_ARGUMENT);
}

static void assert_edges(const rte_image_u8 *dst, const char *const *rows)
{
    for (int y = 0; y < dst->height; y++)
        for (int x = 0; x < dst->width; x++)
            assert_int_equal(dst->buf[y * dst->stride + x], rows[y][x] == '#' ? 255 : 0);
    unit_assert_padding_u8(dst);
}

/* A vertical step 0 | 200: |dx| = 4 * 200 on both sides of the step; the
 * left one wins (m > left, m >= right). */
static void step_edge_is_one_pixel_wide(void **state)
{
    rte_arena a = make_arena();
    for (int ap = 3; ap <= 7; ap += 2) {
        rte_image_u8 src = unit_image_u8(10, 8, 3, 0);
        for (int y = 0; y < 8; y++)
            memset(src.buf + y * src.stride + 5, 200, 5);
        rte_image_u8 dst = unit_image_u8(10, 8, 2, 0x11);
        rte_canny_params p;
        assert_int_equal(rte_canny_params_init(&p, 100, 200, ap, ap == 5), RTE_OK);
        assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
        static const char *const want[8] = {"....#.....", "....#.....", "....#.....", "....#.....",
                                            "....#.....", "....#.....", "....#.....", "....#....."};
        assert_edges(&dst, want);
        assert_int_equal(rte_arena_mark(&a), 0);
        test_free(src.buf);
        test_free(dst.buf);
    }
}

/* A weak step (|dx| = 160, between the thresholds) is kept only where it
 * connects to a strong part (row 0: 60 instead of 40 gives 240 > 200). */
static void hysteresis_follows_weak_edges_from_seeds(void **state)
{
    rte_arena a = make_arena();
    rte_image_u8 src = unit_image_u8(10, 8, 1, 0);
    for (int y = 0; y < 8; y++)
        memset(src.buf + y * src.stride + 5, 40, 5);
    rte_image_u8 dst = unit_image_u8(10, 8, 0, 0);
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 100, 200, 3, false), RTE_OK);
    assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
    static const char *const none[8] = {"..........", "..........", "..........", "..........",
                                        "..........", "..........", "..........", ".........."};
    assert_edges(&dst, none);

    memset(src.buf + 5, 60, 5);
    assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
    static const char *const chain[8] = {".....#....", ".....#....", "....#.....", "....#.....",
                                         "....#.....", "....#.....", "....#.....", "....#....."};
    assert_edges(&dst, chain);
    test_free(src.buf);
    test_free(dst.buf);
}

static void thin_images(void **state)
{
    rte_arena a = make_arena();
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 100, 200, 3, false), RTE_OK);
    /* 1x6 row: |dx| = 800 at x = 2 and 3, dy = 0; x = 2 wins. */
    static const uint8_t row[6] = {0, 0, 0, 200, 200, 200};
    rte_image_u8 src = unit_image_u8(6, 1, 4, 0);
    memcpy(src.buf, row, 6);
    rte_image_u8 dst = unit_image_u8(6, 1, 4, 0);
    assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
    static const char *const want_row[1] = {"..#..."};
    assert_edges(&dst, want_row);
    test_free(src.buf);
    test_free(dst.buf);

    /* 6x1 column: the same along y. */
    src = unit_image_u8(1, 6, 2, 0);
    dst = unit_image_u8(1, 6, 3, 0);
    for (int y = 0; y < 6; y++)
        src.buf[y * src.stride] = row[y];
    assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
    static const char *const want_col[6] = {".", ".", "#", ".", ".", "."};
    assert_edges(&dst, want_col);
    test_free(src.buf);
    test_free(dst.buf);

    /* 1x1 and flat images: no gradient, no edges, even with thresholds 0. */
    assert_int_equal(rte_canny_params_init(&p, 0, 0, 5, true), RTE_OK);
    static const uint8_t levels[3] = {0, 255, 90};
    for (int l = 0; l < 3; l++)
        for (int w = 1; w <= 67; w += 11) {
            src = unit_image_u8(w, w / 3 + 1, 5, levels[l]);
            dst = unit_image_u8(w, w / 3 + 1, 1, 0x33);
            assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
            for (int y = 0; y < dst.height; y++)
                for (int x = 0; x < w; x++)
                    assert_int_equal(dst.buf[y * dst.stride + x], 0);
            unit_assert_padding_u8(&dst);
            test_free(src.buf);
            test_free(dst.buf);
        }
}

/* From given derivatives: a single strong pixel is an edge; its weak
 * 8-neighbours that are local maxima join it. */
static void from_gradient(void **state)
{
    rte_arena a = make_arena();
    rte_image_s16 dx = unit_image_s16(7, 5, 2), dy = unit_image_s16(7, 5, 0);
    for (int y = 0; y < 5; y++)
        for (int x = 0; x < 7; x++) {
            dx.buf[y * dx.stride + x] = 0;
            dy.buf[y * dy.stride + x] = 0;
        }
    /* Column 3 holds a vertical ridge of horizontal gradient: weak 60, one strong 300. */
    for (int y = 0; y < 5; y++)
        dx.buf[y * dx.stride + 3] = -60;
    dx.buf[2 * dx.stride + 3] = 300;
    rte_image_u8 dst = unit_image_u8(7, 5, 2, 0);
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 50, 200, 3, false), RTE_OK);
    assert_int_equal(rte_canny_from_gradient_u8(&dx, &dy, &dst, &p, &a), RTE_OK);
    static const char *const want[5] = {"...#...", "...#...", "...#...", "...#...", "...#..."};
    assert_edges(&dst, want);
    /* Raise low above 60: only the seed remains. */
    assert_int_equal(rte_canny_params_init(&p, 61, 200, 3, false), RTE_OK);
    assert_int_equal(rte_canny_from_gradient_u8(&dx, &dy, &dst, &p, &a), RTE_OK);
    static const char *const seed[5] = {".......", ".......", "...#...", ".......", "......."};
    assert_edges(&dst, seed);
    /* L2 with the same thresholds: 60^2 > 50^2, 300^2 > 200^2. */
    assert_int_equal(rte_canny_params_init(&p, 50, 200, 3, true), RTE_OK);
    assert_int_equal(rte_canny_from_gradient_u8(&dx, &dy, &dst, &p, &a), RTE_OK);
    assert_edges(&dst, want);

    rte_image_u8 wrong = unit_image_u8(6, 5, 0, 0);
    assert_int_equal(rte_canny_from_gradient_u8(&dx, &dy, &wrong, &p, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_canny_from_gradient_u8(&dx, NULL, &dst, &p, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_params_init(&p, 50, 200, 7, false), RTE_OK);
    assert_int_equal(rte_canny_from_gradient_u8(&dx, &dy, &dst, &p, &a), RTE_ERR_ARGUMENT);
    test_free(wrong.buf);
    test_free(dx.buf);
    test_free(dy.buf);
    test_free(dst.buf);
}

/* rte_canny_gradient_u8: the edges of rte_canny_u8, and derivatives that
 * are the 3x3 Sobel with BORDER_REPLICATE (a plain loop here) and give the
 * same edges through rte_canny_from_gradient_u8 (aperture 5 too); the
 * padding untouched; aperture 7, a missing, misfitting or shared
 * derivative image refused. */
static void handing_out_derivatives(void **state)
{
    enum { W = 37, H = 19 };
    rte_arena a = make_arena();
    uint32_t rng = 7;
    rte_image_u8 src = unit_image_u8(W, H, 3, 0), want = unit_image_u8(W, H, 1, 0),
                 got = unit_image_u8(W, H, 2, 0), again = unit_image_u8(W, H, 0, 0);
    rte_image_s16 dx = unit_image_s16(W, H, 2), dy = unit_image_s16(W, H, 1);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            src.buf[y * src.stride + x] =
                (uint8_t)((x / 6 + y / 5) % 2 ? 200 : 40) ^ (uint8_t)(unit_rand(&rng) % 16);
    for (int ap = 3; ap <= 5; ap += 2)
        for (int l2 = 0; l2 <= 1; l2++) {
            rte_canny_params p;
            assert_int_equal(rte_canny_params_init(&p, 60, 180, ap, l2), RTE_OK);
            assert_int_equal(rte_canny_u8(&src, &want, &p, &a), RTE_OK);
            assert_int_equal(rte_canny_gradient_u8(&src, &got, &dx, &dy, &p, &a), RTE_OK);
            for (int y = 0; y < H; y++)
                assert_memory_equal(got.buf + y * got.stride, want.buf + y * want.stride, W);
            assert_int_equal(rte_canny_from_gradient_u8(&dx, &dy, &again, &p, &a), RTE_OK);
            for (int y = 0; y < H; y++)
                assert_memory_equal(again.buf + y * again.stride, want.buf + y * want.stride, W);
            unit_assert_padding_u8(&got);
            unit_assert_padding_s16(&dx);
            unit_assert_padding_s16(&dy);
        }
    /* aperture 3, L1: the derivatives against the plain loop */
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 60, 180, 3, false), RTE_OK);
    assert_int_equal(rte_canny_gradient_u8(&src, &got, &dx, &dy, &p, &a), RTE_OK);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const int ym = y > 0 ? y - 1 : 0, yp = y < H - 1 ? y + 1 : y;
            const int xm = x > 0 ? x - 1 : 0, xp = x < W - 1 ? x + 1 : x;
#define S(yy, xx) src.buf[(yy)*src.stride + (xx)]
            assert_int_equal(dx.buf[y * dx.stride + x], S(ym, xp) + 2 * S(y, xp) + S(yp, xp) -
                                                            S(ym, xm) - 2 * S(y, xm) - S(yp, xm));
            assert_int_equal(dy.buf[y * dy.stride + x], S(yp, xm) + 2 * S(yp, x) + S(yp, xp) -
                                                            S(ym, xm) - 2 * S(ym, x) - S(ym, xp));
#undef S
        }

    rte_image_s16 narrow = unit_image_s16(W - 1, H, 0);
    assert_int_equal(rte_canny_gradient_u8(&src, &got, &narrow, &dy, &p, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_canny_gradient_u8(&src, &got, &dx, NULL, &p, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_gradient_u8(&src, &got, &dx, &dx, &p, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_params_init(&p, 60, 180, 7, false), RTE_OK);
    assert_int_equal(rte_canny_gradient_u8(&src, &got, &dx, &dy, &p, &a), RTE_ERR_ARGUMENT);
    test_free(narrow.buf);
    test_free(src.buf);
    test_free(want.buf);
    test_free(got.buf);
    test_free(again.buf);
    test_free(dx.buf);
    test_free(dy.buf);
}

/* Noise: every edge pixel is 255, the rest 0, padding untouched, and the
 * stated arena size is enough at any alignment while half of it fails. */
static void arena_size_and_arguments(void **state)
{
    static uint8_t mem[1 << 16];
    uint32_t rng = 99;
    rte_image_u8 src = unit_image_u8(67, 23, 3, 0);
    for (int y = 0; y < 23; y++)
        for (int x = 0; x < 67; x++)
            src.buf[y * src.stride + x] = (uint8_t)unit_rand(&rng);
    rte_image_u8 dst = unit_image_u8(67, 23, 5, 0);
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 30, 90, 5, false), RTE_OK);
    size_t need = rte_canny_scratch_size(67, 23, 5);
    assert_true(need <= sizeof mem - RTE_ARENA_ALIGN);
    int edges = 0;
    for (size_t off = 0; off < RTE_ARENA_ALIGN; off += 13) {
        rte_arena a;
        rte_arena_init(&a, mem + off, need);
        assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_OK);
        assert_int_equal(a.used, 0);
        for (int y = 0; y < 23; y++)
            for (int x = 0; x < 67; x++) {
                uint8_t v = dst.buf[y * dst.stride + x];
                assert_true(v == 0 || v == 255);
                edges += v == 255;
            }
        unit_assert_padding_u8(&dst);
    }
    assert_true(edges > 0);
    rte_arena a;
    rte_arena_init(&a, mem, need / 2); /* the flood stack alone is half */
    assert_int_equal(rte_canny_u8(&src, &dst, &p, &a), RTE_ERR_NO_MEMORY);
    assert_int_equal(a.used, 0);

    rte_arena_init(&a, mem, sizeof mem);
    rte_image_u8 other = unit_image_u8(66, 23, 0, 0);
    assert_int_equal(rte_canny_u8(&src, &other, &p, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_canny_u8(&src, &dst, NULL, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_u8(&src, &dst, &p, NULL), RTE_ERR_ARGUMENT);
    rte_canny_params bad = p;
    bad.aperture = 9;
    assert_int_equal(rte_canny_u8(&src, &dst, &bad, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_scratch_size(0, 10, 3), 0);
    test_free(other.buf);
    test_free(src.buf);
    test_free(dst.buf);
}

/* rte_canny_blurred_u8 gives the bytes of rte_gaussian_blur_u8 followed by
 * rte_canny_u8: widths 1..67, heights 1..9 and a few taller, odd strides,
 * every aperture, L1 and L2, square and unequal kernels, and in place. */
static void blurred_equals_blur_then_canny(void **state)
{
    static uint8_t mem[1 << 18];
    rte_arena a;
    rte_arena_init(&a, mem, sizeof mem);
    uint32_t rng = 4242;
    static const int32_t ks[][2] = {{5, 5}, {3, 3}, {1, 1}, {9, 3}, {1, 7}, {15, 15}};
    for (int32_t w = 1; w <= 67; w++) {
        const int32_t h = w % 9 == 0 ? 30 + w % 17 : 1 + w % 9;
        const int32_t pad = 1 + 2 * (w % 4);
        rte_image_u8 src = unit_image_u8(w, h, pad, 0);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++)
                src.buf[y * src.stride + x] =
                    (uint8_t)(w % 5 == 0 ? (unit_rand(&rng) & 1) * 255 : unit_rand(&rng));
        const int32_t ap = 3 + 2 * (w % 3);
        const bool l2 = (w / 3) % 2;
        rte_gaussian_kernel k;
        assert_int_equal(rte_gaussian_kernel_init(&k, ks[w % 6][0], ks[w % 6][1], 0, 0), RTE_OK);
        rte_canny_params p;
        assert_int_equal(rte_canny_params_init(&p, 20 + w, 60 + 3 * w, ap, l2), RTE_OK);
        rte_image_u8 blurred = unit_image_u8(w, h, pad, 0);
        rte_image_u8 want = unit_image_u8(w, h, pad, 0x11), got = unit_image_u8(w, h, pad, 0x22);
        assert_int_equal(rte_gaussian_blur_u8(&src, &blurred, &k, &a), RTE_OK);
        assert_int_equal(rte_canny_u8(&blurred, &want, &p, &a), RTE_OK);
        assert_int_equal(rte_canny_blurred_u8(&src, &got, &k, &p, &a), RTE_OK);
        assert_int_equal(a.used, 0);
        assert_memory_equal(want.buf, got.buf, (size_t)want.stride * h);
        unit_assert_padding_u8(&got);
        /* in place: dst is written only after the last source row is read */
        assert_int_equal(rte_canny_blurred_u8(&src, &src, &k, &p, &a), RTE_OK);
        assert_memory_equal(want.buf, src.buf, (size_t)want.stride * h);
        test_free(src.buf);
        test_free(blurred.buf);
        test_free(want.buf);
        test_free(got.buf);
    }
}

/* The stated arena size is enough at any alignment and a smaller one fails
 * cleanly; bad arguments are refused. */
static void blurred_arena_size_and_arguments(void **state)
{
    static uint8_t mem[1 << 16];
    rte_image_u8 src = unit_image_u8(61, 17, 3, 0);
    uint32_t rng = 5;
    for (int y = 0; y < 17; y++)
        for (int x = 0; x < 61; x++)
            src.buf[y * src.stride + x] = (uint8_t)(unit_rand(&rng) % 64 + 96 * (x > 30));
    rte_image_u8 dst = unit_image_u8(61, 17, 2, 0);
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(&k, 7, 7, 0, 0), RTE_OK);
    rte_canny_params p;
    assert_int_equal(rte_canny_params_init(&p, 30, 90, 3, false), RTE_OK);
    const size_t need = rte_canny_blurred_scratch_size(61, 17, &k, 3);
    assert_true(need > rte_canny_scratch_size(61, 17, 3));
    assert_true(need <= sizeof mem - RTE_ARENA_ALIGN);
    for (size_t off = 0; off < RTE_ARENA_ALIGN; off += 13) {
        rte_arena a;
        rte_arena_init(&a, mem + off, need);
        assert_int_equal(rte_canny_blurred_u8(&src, &dst, &k, &p, &a), RTE_OK);
        assert_int_equal(a.used, 0);
        unit_assert_padding_u8(&dst);
    }
    int edges = 0;
    for (int y = 0; y < 17; y++)
        edges += dst.buf[y * dst.stride + 31] == 255 || dst.buf[y * dst.stride + 30] == 255;
    assert_int_equal(edges, 17); /* the step at x = 30.5 is found on every row */
    rte_arena a;
    rte_arena_init(&a, mem, need / 2);
    assert_int_equal(rte_canny_blurred_u8(&src, &dst, &k, &p, &a), RTE_ERR_NO_MEMORY);
    assert_int_equal(a.used, 0);

    rte_arena_init(&a, mem, sizeof mem);
    rte_gaussian_kernel bad_k = k;
    bad_k.taps_x[0]++; /* no longer sums to 256 */
    assert_int_equal(rte_canny_blurred_u8(&src, &dst, &bad_k, &p, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_blurred_u8(&src, &dst, NULL, &p, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_blurred_u8(&src, &dst, &k, NULL, &a), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_canny_blurred_u8(&src, &dst, &k, &p, NULL), RTE_ERR_ARGUMENT);
    rte_canny_params bad_p = p;
    bad_p.aperture = 4;
    assert_int_equal(rte_canny_blurred_u8(&src, &dst, &k, &bad_p, &a), RTE_ERR_ARGUMENT);
    rte_image_u8 other = unit_image_u8(60, 17, 0, 0);
    assert_int_equal(rte_canny_blurred_u8(&src, &other, &k, &p, &a), RTE_ERR_SIZE);
    assert_int_equal(rte_canny_blurred_scratch_size(0, 17, &k, 3), 0);
    assert_int_equal(rte_canny_blurred_scratch_size(61, 17, NULL, 3), 0);
    assert_int_equal(rte_canny_blurred_scratch_size(61, 17, &bad_k, 3), 0);
    test_free(other.buf);
    test_free(src.buf);
    test_free(dst.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(params_convert_thresholds),
        cmocka_unit_test(step_edge_is_one_pixel_wide),
        cmocka_unit_test(hysteresis_follows_weak_edges_from_seeds),
        cmocka_unit_test(thin_images),
        cmocka_unit_test(from_gradient),
        cmocka_unit_test(handing_out_derivatives),
        cmocka_unit_test(arena_size_and_arguments),
        cmocka_unit_test(blurred_equals_blur_then_canny),
        cmocka_unit_test(blurred_arena_size_and_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
