/* Contour features and shape classes: hand-checked values and errors. */
#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/contours.h"
#include "rtedge/shape.h"

static uint8_t arena_mem[1 << 20];

static rte_arena new_arena(void)
{
    rte_arena a;
    rte_arena_init(&a, arena_mem, sizeof arena_mem);
    return a;
}

/* The outer border of a 10 x 10 polygon, as findContours orders it. */
static const rte_point square10[4] = {{0, 0}, {0, 10}, {10, 10}, {10, 0}};

static void area_perimeter_and_bounds(void **state)
{
    assert_int_equal(rte_shape_area2(square10, 4), -200);
    const rte_point hole[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    assert_int_equal(rte_shape_area2(hole, 4), 200);
    assert_int_equal(rte_shape_area2(square10, 2), 0);
    assert_int_equal(rte_shape_perimeter_q16(square10, 4, 1), 40 * 65536);
    assert_int_equal(rte_shape_perimeter_q16(square10, 4, 0), 30 * 65536);
    const rte_point diag[2] = {{0, 0}, {3, 4}};
    assert_int_equal(rte_shape_perimeter_q16(diag, 2, 0), 5 * 65536);
    const rte_point unit_diag[2] = {{0, 0}, {1, 1}};
    assert_int_equal(rte_shape_perimeter_q16(unit_diag, 2, 0), 92682); /* sqrt(2) in Q16 */
    rte_rect r = rte_shape_bounding_rect(square10, 4);
    assert_int_equal(r.x, 0);
    assert_int_equal(r.y, 0);
    assert_int_equal(r.width, 11);
    assert_int_equal(r.height, 11);
    r = rte_shape_bounding_rect(square10, 0);
    assert_int_equal(r.width, 0);
}

static void moments_of_a_square(void **state)
{
    rte_moments m;
    assert_int_equal(rte_shape_moments(square10, 4, &m), RTE_OK);
    assert_int_equal(m.s00, 200);    /* m00 = 100 */
    assert_int_equal(m.s10, 3000);   /* m10 = 500 */
    assert_int_equal(m.s20, 40000);  /* m20 = 3333.33 */
    assert_int_equal(m.s11, 60000);  /* m11 = 2500 */
    assert_int_equal(m.s30, 500000); /* m30 = 25000 */
    assert_int_equal(m.cx_q16, 5 * 65536);
    assert_int_equal(m.cy_q16, 5 * 65536);
    assert_int_equal(m.mu20_q8, 213333); /* 833.33 */
    assert_int_equal(m.mu11_q8, 0);
    assert_int_equal(m.mu30_q8, 0);
    assert_int_equal(m.nu20_q32, 357913941); /* 1/12 */
    assert_int_equal(m.nu30_q32, 0);
    assert_int_equal(m.hu_q32[0], 2 * 357913941); /* 1/6 */
    assert_int_equal(m.hu_q32[1], 0);

    /* a translated copy has the same central moments */
    rte_point moved[4];
    for (int i = 0; i < 4; i++)
        moved[i] = (rte_point){square10[i].x + 1000, square10[i].y + 700};
    rte_moments m2;
    assert_int_equal(rte_shape_moments(moved, 4, &m2), RTE_OK);
    assert_int_equal(m2.mu20_q8, m.mu20_q8);
    assert_int_equal(m2.nu20_q32, m.nu20_q32);
    assert_int_equal(m2.cx_q16, 1005 * 65536);

    /* degenerate and invalid inputs */
    assert_int_equal(rte_shape_moments(square10, 2, &m), RTE_OK);
    assert_int_equal(m.s00, 0);
    const rte_point far[3] = {{0, 0}, {RTE_SHAPE_MAX_COORD + 1, 0}, {0, 5}};
    assert_int_equal(rte_shape_moments(far, 3, &m), RTE_ERR_TOO_LARGE);
    assert_int_equal(rte_shape_moments(NULL, 3, &m), RTE_ERR_ARGUMENT);
}

static void hull_is_clockwise_on_screen_without_collinear_points(void **state)
{
    rte_arena a = new_arena();
    /* square corners, an edge midpoint, an inside point and a duplicate */
    const rte_point p[7] = {{2, 2}, {0, 0}, {4, 4}, {2, 0}, {4, 0}, {0, 4}, {4, 4}};
    int32_t idx[7], n = 0;
    rte_point hp[7];
    assert_int_equal(rte_shape_convex_hull(p, 7, idx, hp, &n, &a), RTE_OK);
    assert_int_equal(n, 4);
    static const int expect[4][2] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    /* the same cycle as OpenCV's [0,0],[4,0],[4,4],[0,4], from some start */
    int start = -1;
    for (int i = 0; i < 4; i++)
        if (hp[i].x == 0 && hp[i].y == 0)
            start = i;
    assert_true(start >= 0);
    for (int k = 0; k < 4; k++) {
        assert_int_equal(hp[(start + k) % 4].x, expect[k][0]);
        assert_int_equal(hp[(start + k) % 4].y, expect[k][1]);
        assert_int_equal(p[idx[(start + k) % 4]].x, expect[k][0]);
    }
    assert_int_equal(a.used, 0);

    /* one point, and all points equal */
    const rte_point same[3] = {{5, 5}, {5, 5}, {5, 5}};
    assert_int_equal(rte_shape_convex_hull(same, 3, idx, NULL, &n, &a), RTE_OK);
    assert_int_equal(n, 1);
    assert_int_equal(rte_shape_convex_hull(same, 0, idx, NULL, &n, &a), RTE_OK);
    assert_int_equal(n, 0);
    assert_int_equal(rte_shape_convex_hull(same, 3, NULL, NULL, &n, &a), RTE_ERR_ARGUMENT);
    uint8_t tiny[32];
    rte_arena small;
    rte_arena_init(&small, tiny, sizeof tiny);
    assert_int_equal(rte_shape_convex_hull(p, 7, idx, NULL, &n, &small), RTE_ERR_NO_MEMORY);
}

static void defects_of_a_notch(void **state)
{
    rte_arena a = new_arena();
    /* a 10 x 10 square with a notch 4 deep in its top edge (y down) */
    const rte_point c[7] = {{0, 0}, {0, 10}, {10, 10}, {10, 0}, {7, 0}, {5, 4}, {3, 0}};
    int32_t idx[7], n = 0, nd = 0;
    assert_int_equal(rte_shape_convex_hull(c, 7, idx, NULL, &n, &a), RTE_OK);
    assert_int_equal(n, 4);
    rte_defect d[7];
    assert_int_equal(rte_shape_convexity_defects(c, 7, idx, n, d, &nd), RTE_OK);
    assert_int_equal(nd, 1);
    assert_int_equal(d[0].farthest, 5);
    assert_int_equal(d[0].depth_q8, 4 * 256);
    assert_int_equal(c[d[0].start].x, 10);
    assert_int_equal(c[d[0].end].x, 0);
    /* non-monotonic hull indices are refused, like OpenCV */
    const int32_t bad[4] = {0, 2, 1, 3};
    assert_int_equal(rte_shape_convexity_defects(c, 7, bad, 4, d, &nd), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_shape_convexity_defects(c, 3, idx, n, d, &nd), RTE_OK);
    assert_int_equal(nd, 0);
}

static void approximation_keeps_the_corners(void **state)
{
    rte_arena a = new_arena();
    /* the border of a 6 x 4 rectangle, every pixel (NONE order) */
    rte_point c[32];
    int n = 0;
    for (int y = 0; y < 4; y++)
        c[n++] = (rte_point){0, y};
    for (int x = 0; x < 6; x++)
        c[n++] = (rte_point){x, 4};
    for (int y = 4; y > 0; y--)
        c[n++] = (rte_point){6, y};
    for (int x = 6; x > 0; x--)
        c[n++] = (rte_point){x, 0};
    rte_point out[32];
    int32_t no = 0;
    assert_int_equal(rte_shape_approx_poly(c, n, 65536, out, &no, &a), RTE_OK);
    assert_int_equal(no, 4);
    for (int i = 0; i < no; i++) {
        assert_true(out[i].x == 0 || out[i].x == 6);
        assert_true(out[i].y == 0 || out[i].y == 4);
    }
    /* epsilon 0 keeps the corners too (no collinear middle points survive
     * the splits) */
    assert_int_equal(rte_shape_approx_poly(c, n, 0, out, &no, &a), RTE_OK);
    assert_int_equal(no, 4);
    assert_int_equal(a.used, 0);
    assert_int_equal(rte_shape_approx_poly(c, n, 1u << 26, out, &no, &a), RTE_ERR_ARGUMENT);
}

static void rotated_rectangle_convention(void **state)
{
    rte_arena a = new_arena();
    rte_rotated_rect r;
    /* axis-aligned 10 x 4: angle 0, boxPoints order BL, TL, TR, BR */
    const rte_point box[4] = {{0, 0}, {0, 4}, {10, 4}, {10, 0}};
    assert_int_equal(rte_shape_min_area_rect(box, 4, &r, &a), RTE_OK);
    assert_int_equal(r.length_q8, 10 * 256);
    assert_int_equal(r.width_q8, 4 * 256);
    assert_int_equal(r.angle_q16, 0);
    assert_int_equal(r.cx_q8, 5 * 256);
    assert_int_equal(r.cy_q8, 2 * 256);
    static const int corners[4][2] = {{0, 4}, {0, 0}, {10, 0}, {10, 4}};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(r.corners_q8[k][0], corners[k][0] * 256);
        assert_int_equal(r.corners_q8[k][1], corners[k][1] * 256);
    }
    /* standing 4 x 10: the long side is vertical, angle 90 */
    const rte_point tall[4] = {{0, 0}, {0, 10}, {4, 10}, {4, 0}};
    assert_int_equal(rte_shape_min_area_rect(tall, 4, &r, &a), RTE_OK);
    assert_int_equal(r.angle_q16, 90 * 65536);
    assert_int_equal(r.length_q8, 10 * 256);
    /* a bar along the diagonal (down-right on screen): +45 degrees */
    const rte_point bar[4] = {{0, 1}, {1, 0}, {11, 10}, {10, 11}};
    assert_int_equal(rte_shape_min_area_rect(bar, 4, &r, &a), RTE_OK);
    assert_true(abs(r.angle_q16 - 45 * 65536) < 66);
    /* and the other diagonal: -45 */
    const rte_point bar2[4] = {{0, 10}, {1, 11}, {11, 1}, {10, 0}};
    assert_int_equal(rte_shape_min_area_rect(bar2, 4, &r, &a), RTE_OK);
    assert_true(abs(r.angle_q16 + 45 * 65536) < 66);
    assert_int_equal(a.used, 0);
}

static void enclosing_circles(void **state)
{
    rte_arena a = new_arena();
    rte_circle c;
    const rte_point two[2] = {{0, 0}, {10, 0}};
    assert_int_equal(rte_shape_enclosing_circle(two, 2, &c, &a), RTE_OK);
    assert_int_equal(c.cx_q8, 5 * 256);
    assert_int_equal(c.cy_q8, 0);
    assert_int_equal(c.r_q8, 5 * 256);
    /* right triangle: the hypotenuse is a diameter */
    const rte_point tri[3] = {{0, 0}, {6, 0}, {0, 8}};
    assert_int_equal(rte_shape_enclosing_circle(tri, 3, &c, &a), RTE_OK);
    assert_int_equal(c.cx_q8, 3 * 256);
    assert_int_equal(c.cy_q8, 4 * 256);
    assert_int_equal(c.r_q8, 5 * 256);
    /* points on a circle of radius 5 and an inner point */
    const rte_point ring[5] = {{5, 0}, {0, 5}, {-5, 0}, {3, -4}, {1, 1}};
    assert_int_equal(rte_shape_enclosing_circle(ring, 5, &c, &a), RTE_OK);
    assert_int_equal(c.cx_q8, 0);
    assert_int_equal(c.cy_q8, 0);
    assert_int_equal(c.r_q8, 5 * 256);
    assert_int_equal(rte_shape_enclosing_circle(ring, 0, &c, &a), RTE_ERR_ARGUMENT);
}

/* Draws a filled shape into a w x h image: inside() decides per pixel. */
typedef int (*inside_fn)(int x, int y, const int *p);

static int in_disc(int x, int y, const int *p)
{
    return (x - p[0]) * (x - p[0]) + (y - p[1]) * (y - p[1]) <= p[2] * p[2];
}

static int in_box(int x, int y, const int *p)
{
    return x >= p[0] && x <= p[1] && y >= p[2] && y <= p[3];
}

static int in_triangle(int x, int y, const int *p)
{
    int s = 0, neg = 0;
    for (int k = 0; k < 3; k++) {
        const int *a = p + 2 * k, *b = p + 2 * ((k + 1) % 3);
        int c = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
        s += c > 0;
        neg += c < 0;
    }
    return s == 0 || neg == 0;
}

static rte_shape_class classify_drawn(inside_fn f, const int *p)
{
    enum { W = 120, H = 100 };
    rte_image_u8 img = unit_image_u8(W, H, 3, 0);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            img.buf[y * img.stride + x] = f(x, y, p) ? 255 : 0;
    static rte_point pts[4096];
    static rte_contour cs[16];
    rte_contours r = {pts, cs, 4096, 16, 0, 0, 0, 0, 0};
    rte_arena a = new_arena();
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_SIMPLE, &r, &a), RTE_OK);
    assert_int_equal(r.n_contours, 1);
    rte_shape_info info;
    assert_true(rte_shape_classify_scratch_size(r.n_points) <= sizeof arena_mem);
    assert_int_equal(rte_shape_classify(pts + cs[0].offset, cs[0].count, &info, &a), RTE_OK);
    assert_int_equal(a.used, 0);
    test_free(img.buf);
    return info.shape;
}

static void drawn_shapes_are_classified(void **state)
{
    const int disc[3] = {60, 50, 30};
    assert_int_equal(classify_drawn(in_disc, disc), RTE_SHAPE_CIRCLE);
    const int sq[4] = {20, 60, 20, 60};
    assert_int_equal(classify_drawn(in_box, sq), RTE_SHAPE_SQUARE);
    const int rect[4] = {10, 100, 30, 60};
    assert_int_equal(classify_drawn(in_box, rect), RTE_SHAPE_RECTANGLE);
    const int tri[6] = {60, 10, 100, 80, 20, 80};
    assert_int_equal(classify_drawn(in_triangle, tri), RTE_SHAPE_TRIANGLE);
    const int dot[4] = {5, 6, 5, 6};
    assert_int_equal(classify_drawn(in_box, dot), RTE_SHAPE_OTHER);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(area_perimeter_and_bounds),
        cmocka_unit_test(moments_of_a_square),
        cmocka_unit_test(hull_is_clockwise_on_screen_without_collinear_points),
        cmocka_unit_test(defects_of_a_notch),
        cmocka_unit_test(approximation_keeps_the_corners),
        cmocka_unit_test(rotated_rectangle_convention),
        cmocka_unit_test(enclosing_circles),
        cmocka_unit_test(drawn_shapes_are_classified),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
