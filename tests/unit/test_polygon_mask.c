/* Filled polygons, ROI masks and masking. */
#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/polygon_mask.h"

static uint8_t arena_memory[1 << 14];

static rte_arena make_arena(void)
{
    rte_arena a;
    rte_arena_init(&a, arena_memory, sizeof arena_memory);
    return a;
}

static uint8_t px(const rte_image_u8 *img, int32_t x, int32_t y)
{
    return img->buf[(size_t)y * img->stride + x];
}

/* Fills the polygon into a fresh mask (padding 0xEE) and checks the arena
 * is given back. */
static rte_image_u8 mask_of(int32_t w, int32_t h, const rte_vertex *v, int32_t n)
{
    rte_arena arena = make_arena();
    rte_image_u8 mask = unit_image_u8(w, h, 3, 0x11);
    rte_polygon poly = {v, n};
    assert_int_equal(rte_polygon_mask_build(&mask, &poly, 1, &arena), RTE_OK);
    assert_int_equal(arena.used, 0);
    unit_assert_padding_u8(&mask);
    return mask;
}

/* Pixels of `mask` equal to 255 exactly inside [x0, x1] x [y0, y1]. */
static void assert_rectangle(const rte_image_u8 *mask, int32_t x0, int32_t y0, int32_t x1,
                             int32_t y1)
{
    for (int32_t y = 0; y < mask->height; y++)
        for (int32_t x = 0; x < mask->width; x++) {
            int inside = x >= x0 && x <= x1 && y >= y0 && y <= y1;
            assert_int_equal(px(mask, x, y), inside ? 255 : 0);
        }
}

static void square_fills_its_closed_area(void **state)
{
    rte_vertex v[] = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};
    rte_image_u8 mask = mask_of(5, 5, v, 4);
    assert_rectangle(&mask, 1, 1, 3, 3);
    test_free(mask.buf);
}

static void triangle_by_hand(void **state)
{
    /* Right triangle (0,0), (4,0), (0,4) on 6x6: the hypotenuse is the
     * diagonal x + y = 4 and everything on or below-left of it is set. */
    rte_vertex v[] = {{0, 0}, {4, 0}, {0, 4}};
    rte_image_u8 mask = mask_of(6, 6, v, 3);
    for (int32_t y = 0; y < 6; y++)
        for (int32_t x = 0; x < 6; x++)
            assert_int_equal(px(&mask, x, y), x + y <= 4 ? 255 : 0);
    test_free(mask.buf);
}

static void degenerate_polygons_draw_their_outline(void **state)
{
    /* one point: one pixel */
    rte_vertex one[] = {{2, 1}};
    rte_image_u8 mask = mask_of(4, 3, one, 1);
    assert_rectangle(&mask, 2, 1, 2, 1);
    test_free(mask.buf);

    /* two points, and collinear points: the segment */
    rte_vertex two[] = {{1, 2}, {5, 2}};
    mask = mask_of(7, 4, two, 2);
    assert_rectangle(&mask, 1, 2, 5, 2);
    test_free(mask.buf);
    rte_vertex line[] = {{2, 0}, {2, 5}, {2, 3}};
    mask = mask_of(4, 7, line, 3);
    assert_rectangle(&mask, 2, 0, 2, 5);
    test_free(mask.buf);

    /* repeated points change nothing */
    rte_vertex rep[] = {{1, 1}, {1, 1}, {3, 1}, {3, 3}, {3, 3}, {1, 3}};
    mask = mask_of(5, 5, rep, 6);
    assert_rectangle(&mask, 1, 1, 3, 3);
    test_free(mask.buf);
}

static void bow_tie_fills_both_halves(void **state)
{
    /* (0,0) -> (4,4) -> (4,0) -> (0,4): a left and a right triangle meeting
     * at (2,2) */
    rte_vertex v[] = {{0, 0}, {4, 4}, {4, 0}, {0, 4}};
    rte_image_u8 mask = mask_of(5, 5, v, 4);
    for (int32_t y = 0; y < 5; y++)
        for (int32_t x = 0; x < 5; x++) {
            int in_x = x <= 2 ? (y >= x && y <= 4 - x) : (y >= 4 - x && y <= x);
            assert_int_equal(px(&mask, x, y), in_x ? 255 : 0);
        }
    test_free(mask.buf);
}

static void overlapping_polygons_cancel_inside(void **state)
{
    /* The same square twice: the even-odd rule leaves its inside empty,
     * only the drawn outline remains. */
    rte_vertex v[] = {{1, 1}, {6, 1}, {6, 5}, {1, 5}};
    rte_polygon polys[2] = {{v, 4}, {v, 4}};
    rte_arena arena = make_arena();
    rte_image_u8 mask = unit_image_u8(8, 7, 2, 0x33);
    assert_int_equal(rte_polygon_mask_build(&mask, polys, 2, &arena), RTE_OK);
    for (int32_t y = 0; y < 7; y++)
        for (int32_t x = 0; x < 8; x++) {
            int in = x >= 1 && x <= 6 && y >= 1 && y <= 5;
            int border = in && (x == 1 || x == 6 || y == 1 || y == 5);
            assert_int_equal(px(&mask, x, y), border ? 255 : 0);
        }
    unit_assert_padding_u8(&mask);
    test_free(mask.buf);
}

static void rectangles_of_every_width_clip_to_the_image(void **state)
{
    uint32_t seed = 4242;
    for (int32_t w = 1; w <= 67; w++)
        for (int rep = 0; rep < 6; rep++) {
            int32_t h = 1 + (int32_t)(unit_rand(&seed) % 9);
            /* corners anywhere from far outside to inside */
            int32_t xa = (int32_t)(unit_rand(&seed) % (3u * w + 40)) - w - 20;
            int32_t xb = (int32_t)(unit_rand(&seed) % (3u * w + 40)) - w - 20;
            int32_t ya = (int32_t)(unit_rand(&seed) % 40) - 15;
            int32_t yb = (int32_t)(unit_rand(&seed) % 40) - 15;
            if (rep == 0) { /* far away corners */
                xa = -100000;
                xb = 100000;
            }
            rte_vertex v[] = {{xa, ya}, {xb, ya}, {xb, yb}, {xa, yb}};
            rte_image_u8 mask = mask_of(w, h, v, 4);
            int32_t x0 = xa < xb ? xa : xb, x1 = xa < xb ? xb : xa;
            int32_t y0 = ya < yb ? ya : yb, y1 = ya < yb ? yb : ya;
            assert_rectangle(&mask, x0, y0, x1, y1);
            test_free(mask.buf);
        }
}

static void fill_keeps_other_pixels_and_uses_the_value(void **state)
{
    rte_arena arena = make_arena();
    rte_image_u8 img = unit_image_u8(6, 4, 5, 200);
    rte_vertex v[] = {{2, 1}, {4, 1}, {4, 2}, {2, 2}};
    rte_polygon poly = {v, 4};
    assert_int_equal(rte_polygon_fill_u8(&img, &poly, 1, 7, &arena), RTE_OK);
    for (int32_t y = 0; y < 4; y++)
        for (int32_t x = 0; x < 6; x++)
            assert_int_equal(px(&img, x, y), x >= 2 && x <= 4 && y >= 1 && y <= 2 ? 7 : 200);
    unit_assert_padding_u8(&img);

    /* wholly outside, 1x1 and Nx1 images */
    rte_vertex far[] = {{50, 50}, {60, 50}, {55, 70}};
    poly.vertex = far;
    poly.count = 3;
    assert_int_equal(rte_polygon_fill_u8(&img, &poly, 1, 0, &arena), RTE_OK);
    assert_int_equal(px(&img, 0, 0), 200);
    test_free(img.buf);

    rte_vertex cover[] = {{-5, -5}, {5, -5}, {0, 9}};
    poly.vertex = cover;
    rte_image_u8 one = unit_image_u8(1, 1, 2, 0);
    assert_int_equal(rte_polygon_fill_u8(&one, &poly, 1, 255, &arena), RTE_OK);
    assert_int_equal(one.buf[0], 255);
    unit_assert_padding_u8(&one);
    test_free(one.buf);

    rte_image_u8 col = unit_image_u8(1, 9, 1, 0);
    assert_int_equal(rte_polygon_fill_u8(&col, &poly, 1, 255, &arena), RTE_OK);
    /* the apex (0, 9) is below the image; at row 8 the sides are at
     * x = -+5/14, so every row of the column is inside */
    for (int32_t y = 0; y < 9; y++)
        assert_int_equal(col.buf[y * col.stride], 255);
    unit_assert_padding_u8(&col);
    test_free(col.buf);
    assert_int_equal(arena.used, 0);
}

static void arena_and_argument_errors(void **state)
{
    rte_vertex v[] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
    rte_polygon poly = {v, 4};
    rte_image_u8 img = unit_image_u8(4, 4, 0, 9);

    /* 64 bytes cannot hold 4 edges; scratch_size(4) can, even from a
     * misaligned start */
    rte_arena small;
    rte_arena_init(&small, arena_memory, 64);
    assert_int_equal(rte_polygon_fill_u8(&img, &poly, 1, 1, &small), RTE_ERR_NO_MEMORY);
    assert_int_equal(small.used, 0);
    assert_int_equal(img.buf[5], 9); /* nothing drawn */
    assert_int_equal(rte_polygon_mask_build(&img, &poly, 1, &small), RTE_ERR_NO_MEMORY);
    for (int i = 0; i < 16; i++)
        assert_int_equal(img.buf[i], 9); /* not even cleared */
    assert_true(rte_polygon_mask_scratch_size(4) < rte_polygon_mask_scratch_size(400));
    rte_arena exact;
    rte_arena_init(&exact, arena_memory + 1, rte_polygon_mask_scratch_size(4));
    assert_int_equal(rte_polygon_fill_u8(&img, &poly, 1, 1, &exact), RTE_OK);
    assert_int_equal(img.buf[5], 1);
    assert_int_equal(exact.used, 0);

    rte_arena arena = make_arena();
    assert_int_equal(rte_polygon_fill_u8(&img, &poly, 1, 1, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_fill_u8(&img, NULL, 1, 1, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_fill_u8(&img, &poly, -1, 1, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_fill_u8(NULL, &poly, 1, 1, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_fill_u8(&img, NULL, 0, 1, &arena), RTE_OK);
    rte_polygon bad = {NULL, 3};
    assert_int_equal(rte_polygon_fill_u8(&img, &bad, 1, 1, &arena), RTE_ERR_ARGUMENT);
    bad.count = -1;
    assert_int_equal(rte_polygon_mask_build(&img, &bad, 1, &arena), RTE_ERR_ARGUMENT);
    rte_vertex huge[] = {{0, 0}, {RTE_POLYGON_MAX_COORD + 1, 0}, {0, 3}};
    rte_polygon hp = {huge, 3};
    assert_int_equal(rte_polygon_fill_u8(&img, &hp, 1, 1, &arena), RTE_ERR_ARGUMENT);
    huge[1].x = -RTE_POLYGON_MAX_COORD;
    assert_int_equal(rte_polygon_fill_u8(&img, &hp, 1, 1, &arena), RTE_OK);
    rte_polygon empty = {NULL, 0};
    assert_int_equal(rte_polygon_mask_build(&img, &empty, 1, &arena), RTE_OK);
    for (int i = 0; i < 16; i++)
        assert_int_equal(img.buf[i], 0);
    assert_int_equal(rte_polygon_mask_build(&img, &poly, 1, NULL), RTE_ERR_ARGUMENT);
    rte_image_u8 zero = img;
    zero.width = 0;
    assert_int_equal(rte_polygon_mask_build(&zero, &poly, 1, &arena), RTE_ERR_SIZE);
    test_free(img.buf);
}

static void apply_keeps_pixels_where_the_mask_is_set(void **state)
{
    uint32_t seed = 31;
    for (int32_t w = 1; w <= 67; w++) {
        int32_t h = 1 + w % 3;
        rte_image_u8 src = unit_image_u8(w, h, 2, 0), mask = unit_image_u8(w, h, 5, 0);
        rte_image_u8 dst = unit_image_u8(w, h, 1, 0x42);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                src.buf[y * src.stride + x] = (uint8_t)unit_rand(&seed);
                uint32_t r = unit_rand(&seed);
                mask.buf[y * mask.stride + x] = (uint8_t)(r & 1 ? 0 : r >> 8);
            }
        assert_int_equal(rte_polygon_mask_apply(&src, &mask, &dst), RTE_OK);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++)
                assert_int_equal(px(&dst, x, y), px(&mask, x, y) ? px(&src, x, y) : 0);
        unit_assert_padding_u8(&dst);
        /* in place */
        assert_int_equal(rte_polygon_mask_apply(&src, &mask, &src), RTE_OK);
        for (int32_t y = 0; y < h; y++)
            assert_memory_equal(src.buf + y * src.stride, dst.buf + y * dst.stride, (size_t)w);
        unit_assert_padding_u8(&src);
        test_free(src.buf);
        test_free(mask.buf);
        test_free(dst.buf);
    }

    uint8_t s[3] = {10, 20, 30}, m[3] = {0, 255, 1}, d[3];
    rte_image_u8 si = {3, 1, 3, s}, mi = {3, 1, 3, m}, di = {3, 1, 3, d};
    assert_int_equal(rte_polygon_mask_apply(&si, &mi, &di), RTE_OK);
    assert_memory_equal(d, ((uint8_t[]){0, 20, 30}), 3);
    mi.width = 2;
    assert_int_equal(rte_polygon_mask_apply(&si, &mi, &di), RTE_ERR_SIZE);
    assert_int_equal(rte_polygon_mask_apply(&si, NULL, &di), RTE_ERR_ARGUMENT);
}

/* keep = build + apply, in one pass; its argument errors leave dst as it was. */
static void keep_is_build_then_apply(void **state)
{
    (void)state;
    uint32_t seed = 7;
    /* a bow tie whose crossing and slanted outline leave pixels beyond the
     * spans' rounded ends, and a polygon partly off the image */
    const rte_vertex tie[] = {{1, 1}, {40, 17}, {40, 2}, {2, 19}};
    const rte_vertex off[] = {{-9, 12}, {30, -4}, {47, 25}, {12, 30}};
    const rte_polygon polys[2] = {{tie, 4}, {off, 4}};
    for (int32_t count = 1; count <= 2; count++) {
        rte_image_u8 src = unit_image_u8(43, 23, 2, 0), mask = unit_image_u8(43, 23, 0, 0);
        rte_image_u8 want = unit_image_u8(43, 23, 0, 0), dst = unit_image_u8(43, 23, 4, 0x42);
        for (int32_t y = 0; y < src.height; y++)
            for (int32_t x = 0; x < src.width; x++)
                src.buf[y * src.stride + x] = (uint8_t)(1 + unit_rand(&seed) % 255);
        rte_arena arena = make_arena();
        assert_int_equal(rte_polygon_mask_build(&mask, polys, count, &arena), RTE_OK);
        assert_int_equal(rte_polygon_mask_apply(&src, &mask, &want), RTE_OK);
        assert_int_equal(rte_polygon_keep_u8(&src, polys, count, &dst, &arena), RTE_OK);
        assert_int_equal(arena.used, 0);
        for (int32_t y = 0; y < dst.height; y++)
            assert_memory_equal(dst.buf + y * dst.stride, want.buf + y * want.stride, 43);
        unit_assert_padding_u8(&dst);
        test_free(src.buf);
        test_free(mask.buf);
        test_free(want.buf);
        test_free(dst.buf);
    }

    uint8_t s[16], d[16];
    memset(s, 5, sizeof s);
    memset(d, 9, sizeof d);
    rte_image_u8 si = {4, 4, 4, s}, di = {4, 4, 4, d};
    rte_arena small;
    rte_arena_init(&small, arena_memory, 64);
    assert_int_equal(rte_polygon_keep_u8(&si, polys, 1, &di, &small), RTE_ERR_NO_MEMORY);
    assert_int_equal(small.used, 0);
    rte_arena arena = make_arena();
    assert_int_equal(rte_polygon_keep_u8(&si, polys, 1, &di, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_keep_u8(&si, NULL, 1, &di, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_keep_u8(&si, polys, 1, &si, &arena), RTE_ERR_ARGUMENT);
    rte_image_u8 lower_half = {4, 2, 4, s + 8};
    rte_image_u8 upper_half = {4, 2, 4, s + 4}; /* overlaps it by a row */
    assert_int_equal(rte_polygon_keep_u8(&lower_half, polys, 1, &upper_half, &arena),
                     RTE_ERR_ARGUMENT);
    rte_image_u8 narrow = {3, 4, 4, d};
    assert_int_equal(rte_polygon_keep_u8(&si, polys, 1, &narrow, &arena), RTE_ERR_SIZE);
    for (int i = 0; i < 16; i++)
        assert_int_equal(d[i], 9); /* untouched by every refusal */
    assert_int_equal(rte_polygon_keep_u8(&si, NULL, 0, &di, &arena), RTE_OK);
    for (int i = 0; i < 16; i++)
        assert_int_equal(d[i], 0); /* no polygon: nothing kept */
}

static void fractions_round_to_the_nearest_pixel(void **state)
{
    rte_vertex frac[] = {
        {0, 0},
        {RTE_POLYGON_FRACTION_ONE, RTE_POLYGON_FRACTION_ONE},
        {RTE_POLYGON_FRACTION_ONE / 2, RTE_POLYGON_FRACTION_ONE / 4},
        {-RTE_POLYGON_FRACTION_ONE / 2, 2 * RTE_POLYGON_FRACTION_ONE},
        {1, 65535},
    };
    rte_vertex out[5];
    assert_int_equal(rte_polygon_from_fractions(frac, 5, 960, 540, out), RTE_OK);
    assert_int_equal(out[0].x, 0);
    assert_int_equal(out[0].y, 0);
    assert_int_equal(out[1].x, 960);
    assert_int_equal(out[1].y, 540);
    assert_int_equal(out[2].x, 480);
    assert_int_equal(out[2].y, 135);
    assert_int_equal(out[3].x, -480);
    assert_int_equal(out[3].y, 1080);
    assert_int_equal(out[4].x, 0);   /* 960/65536 = 0.015 */
    assert_int_equal(out[4].y, 540); /* 539.99 */

    /* halves round up, also below zero: 0.5 -> 1, -0.5 -> 0, -1.5 -> -1 */
    rte_vertex half[] = {{RTE_POLYGON_FRACTION_ONE / 2, -RTE_POLYGON_FRACTION_ONE / 2},
                         {-3 * RTE_POLYGON_FRACTION_ONE / 2, 0}};
    assert_int_equal(rte_polygon_from_fractions(half, 2, 1, 1, half), RTE_OK); /* in place */
    assert_int_equal(half[0].x, 1);
    assert_int_equal(half[0].y, 0);
    assert_int_equal(half[1].x, -1);

    rte_vertex far[] = {{RTE_POLYGON_MAX_FRACTION + 1, 0}};
    assert_int_equal(rte_polygon_from_fractions(far, 1, 10, 10, out), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_from_fractions(frac, 1, 0, 10, out), RTE_ERR_SIZE);
    assert_int_equal(rte_polygon_from_fractions(NULL, 1, 10, 10, out), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_polygon_from_fractions(frac, -1, 10, 10, out), RTE_ERR_ARGUMENT);

    /* the largest fractions on the largest image stay valid vertices */
    far[0].x = -RTE_POLYGON_MAX_FRACTION;
    assert_int_equal(rte_polygon_from_fractions(far, 1, RTE_MAX_SIDE, RTE_MAX_SIDE, out), RTE_OK);
    assert_int_equal(out[0].x, -64 * RTE_MAX_SIDE);
    assert_true(out[0].x >= -RTE_POLYGON_MAX_COORD);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(square_fills_its_closed_area),
        cmocka_unit_test(triangle_by_hand),
        cmocka_unit_test(degenerate_polygons_draw_their_outline),
        cmocka_unit_test(bow_tie_fills_both_halves),
        cmocka_unit_test(overlapping_polygons_cancel_inside),
        cmocka_unit_test(rectangles_of_every_width_clip_to_the_image),
        cmocka_unit_test(fill_keeps_other_pixels_and_uses_the_value),
        cmocka_unit_test(arena_and_argument_errors),
        cmocka_unit_test(apply_keeps_pixels_where_the_mask_is_set),
        cmocka_unit_test(keep_is_build_then_apply),
        cmocka_unit_test(fractions_round_to_the_nearest_pixel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
