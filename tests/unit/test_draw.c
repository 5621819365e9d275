/* rtedge_draw: pixels where they belong, clipping, nothing past the width. */
#include "unit.h"

#include "rtedge/draw.h"

enum { W = 23, H = 17, PAD = 5 };

typedef struct canvas {
    rte_image_u8c3 img;
    uint8_t *mem;
} canvas;

static canvas new_canvas(void)
{
    const int32_t stride = 3 * W + PAD;
    canvas c = {{W, H, stride, NULL}, test_malloc((size_t)stride * H)};
    memset(c.mem, 0xEE, (size_t)stride * H);
    for (int32_t y = 0; y < H; y++)
        memset(c.mem + (size_t)y * stride, 0, 3 * W);
    c.img.buf = c.mem;
    return c;
}

static int lit(const canvas *c, int32_t x, int32_t y)
{
    const uint8_t *p = c->img.buf + (size_t)y * c->img.stride + 3 * x;
    return p[0] == 1 && p[1] == 2 && p[2] == 3;
}

static int count(const canvas *c)
{
    int n = 0;
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++)
            n += lit(c, x, y);
    return n;
}

static void padding_intact(const canvas *c)
{
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 3 * W; x < c->img.stride; x++)
            assert_int_equal(c->img.buf[(size_t)y * c->img.stride + x], 0xEE);
}

static const rte_draw_color col = {1, 2, 3};

static void lines(void **state)
{
    (void)state;
    canvas c = new_canvas();
    assert_int_equal(rte_draw_line(&c.img, 2, 3, 12, 3, col, 1), RTE_OK);
    assert_int_equal(count(&c), 11);
    assert_true(lit(&c, 2, 3) && lit(&c, 12, 3) && !lit(&c, 13, 3));
    /* a diagonal: one pixel per step */
    assert_int_equal(rte_draw_line(&c.img, 0, 5, 5, 10, col, 1), RTE_OK);
    assert_int_equal(count(&c), 17);
    assert_true(lit(&c, 3, 8));
    /* thickness 3 widens a horizontal line to three rows */
    assert_int_equal(rte_draw_line(&c.img, 15, 14, 20, 14, col, 3), RTE_OK);
    assert_true(lit(&c, 15, 13) && lit(&c, 20, 15) && !lit(&c, 20, 16));
    /* far outside, crossing, and entirely off the image */
    assert_int_equal(rte_draw_line(&c.img, -1000000, 1, 1000000, 1, col, 1), RTE_OK);
    for (int32_t x = 0; x < W; x++)
        assert_true(lit(&c, x, 1));
    const int before = count(&c);
    assert_int_equal(rte_draw_line(&c.img, -50, -5, 100, -9, col, 2), RTE_OK);
    assert_int_equal(rte_draw_line(&c.img, INT32_MIN, INT32_MIN, INT32_MAX, INT32_MIN, col, 1),
                     RTE_OK);
    assert_int_equal(count(&c), before);
    assert_int_equal(rte_draw_line(&c.img, 0, 0, 1, 1, col, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_draw_line(NULL, 0, 0, 1, 1, col, 1), RTE_ERR_ARGUMENT);
    padding_intact(&c);
    test_free(c.mem);
}

static void polylines_circles_dots(void **state)
{
    (void)state;
    canvas c = new_canvas();
    const rte_point sq[4] = {{2, 2}, {6, 2}, {6, 6}, {2, 6}};
    assert_int_equal(rte_draw_polyline(&c.img, sq, 4, 1, col, 1), RTE_OK);
    assert_int_equal(count(&c), 16); /* the outline of a 5 x 5 square */
    assert_true(lit(&c, 2, 4) && !lit(&c, 4, 4));
    assert_int_equal(rte_draw_polyline(&c.img, sq, -1, 1, col, 1), RTE_ERR_ARGUMENT);
    test_free(c.mem);

    c = new_canvas();
    assert_int_equal(rte_draw_circle(&c.img, 11, 8, 5, col, 1), RTE_OK);
    assert_true(lit(&c, 16, 8) && lit(&c, 6, 8) && lit(&c, 11, 3) && lit(&c, 11, 13) &&
                !lit(&c, 11, 8));
    /* symmetric about the centre */
    for (int32_t y = 3; y <= 13; y++)
        for (int32_t x = 6; x <= 16; x++)
            assert_int_equal(lit(&c, x, y), lit(&c, 22 - x, y));
    test_free(c.mem);

    c = new_canvas();
    assert_int_equal(rte_draw_dot(&c.img, 11, 8, 2, col), RTE_OK);
    /* r = 2: dx^2 + dy^2 <= 6: 21 pixels */
    assert_int_equal(count(&c), 21);
    assert_int_equal(rte_draw_dot(&c.img, 0, 0, 40, col), RTE_OK); /* clipped */
    assert_int_equal(rte_draw_circle(&c.img, 1000, 1000, 3, col, 1), RTE_OK);
    assert_int_equal(rte_draw_dot(&c.img, 0, 0, -1, col), RTE_ERR_ARGUMENT);
    padding_intact(&c);
    test_free(c.mem);
}

static void text(void **state)
{
    (void)state;
    canvas c = new_canvas();
    /* "1": .#.. ##.. and so on: 10 pixels in the 5x7 glyph */
    assert_int_equal(rte_draw_text(&c.img, 0, 0, "1", col, 1), RTE_OK);
    assert_int_equal(count(&c), 10);
    assert_true(lit(&c, 2, 0) && lit(&c, 1, 1) && lit(&c, 1, 6) && !lit(&c, 0, 0));
    /* lower case is upper case; unknown characters are blank */
    canvas d = new_canvas();
    rte_draw_text(&c.img, 6, 0, "a", col, 1);
    rte_draw_text(&d.img, 6, 0, "A", col, 1);
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++)
            assert_int_equal(lit(&c, x, y) || (x < 6 && lit(&c, x, y)),
                             lit(&d, x, y) || (x < 6 && lit(&c, x, y)));
    test_free(d.mem);
    d = new_canvas();
    rte_draw_text(&d.img, 0, 0, "\x01~", col, 1);
    assert_int_equal(count(&d), 0);
    /* scale 2 quadruples the pixels; partly outside is clipped */
    rte_draw_text(&d.img, 0, 0, "1", col, 2);
    assert_int_equal(count(&d), 40);
    rte_draw_text(&d.img, 20, 14, "88888", col, 3);
    assert_int_equal(rte_draw_text(&d.img, 0, 0, "1", col, 0), RTE_ERR_ARGUMENT);
    padding_intact(&d);
    int32_t tw, th;
    rte_draw_text_size("abc", 2, &tw, &th);
    assert_int_equal(tw, (3 * RTE_DRAW_CELL_W - 1) * 2);
    assert_int_equal(th, 14);
    test_free(c.mem);
    test_free(d.mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lines),
        cmocka_unit_test(polylines_circles_dots),
        cmocka_unit_test(text),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
