/* A grasp a parallel-jaw gripper can execute (rte_grasp_object): the
 * narrowest width by rotating calipers (rte_shape_calipers) against known
 * answers, where it differs from the minimum-area box's short side (a
 * triangle, an L); the opening, jaws, score (solidity, width within the
 * gripper's range, room for the fingers) and the order by score. */
#include "unit.h"

#include <math.h>
#include <stdlib.h>

#include "rtedge/grasp.h"
#include "rtedge/polygon_mask.h"
#include "algo/geom_fixed.h"

static uint8_t arena_mem[1 << 16];

static double width_px(const rte_caliper *c) { return c->width_q8 / 256.0; }
static double angle_deg(int32_t q16) { return q16 / 65536.0; }

static double angle_diff(double a, double b)
{
    double d = fmod(fabs(a - b), 180.0);
    return d > 90 ? 180 - d : d;
}

/* The narrowest of a convex polygon's calipers. */
static rte_caliper narrowest(const rte_point *v, int32_t n)
{
    rte_caliper c[16];
    int32_t nc = 0;
    assert_int_equal(rte_shape_calipers(v, n, c, &nc), RTE_OK);
    assert_int_equal(nc, n);
    rte_caliper best = c[0];
    for (int32_t i = 1; i < nc; i++)
        if (c[i].width_q8 < best.width_q8)
            best = c[i];
    return best;
}

/* Exact vertices: the narrowest width of a triangle is its smallest
 * altitude, across the longest side; either orientation gives the same. */
static void calipers_triangle(void **state)
{
    (void)state;
    /* AB (126.5) longest, twice the area 9600: altitudes 75.89, 93.20, 101.19 */
    rte_point t[3] = {{20, 20}, {140, 60}, {50, 110}};
    const double alt = 9600 / sqrt(120.0 * 120 + 40 * 40);
    const double dir = atan2(40, 120) * 180 / 3.14159265358979323846 - 90; /* -71.57 */
    for (int flip = 0; flip < 2; flip++) {
        const rte_caliper c = narrowest(t, 3);
        assert_true(fabs(width_px(&c) - alt) <= 1 / 256.0);
        assert_true(angle_diff(angle_deg(c.angle_q16), dir) < 0.001);
        assert_int_equal(t[c.far].x, 50); /* C, across AB */
        /* the unit vector points the way the angle does */
        assert_true(fabs(c.ux_q16 / 65536.0 - cos(dir * 3.14159265358979323846 / 180)) < 1e-4);
        assert_true(fabs(c.uy_q16 / 65536.0 - sin(dir * 3.14159265358979323846 / 180)) < 1e-4);
        const rte_point s = t[1]; /* the other orientation */
        t[1] = t[2];
        t[2] = s;
    }
    /* degenerate hulls: a point, a segment, collinear points; errors */
    rte_caliper c[4];
    int32_t nc = 0;
    const rte_point seg[3] = {{0, 0}, {10, 10}, {20, 20}};
    assert_int_equal(rte_shape_calipers(seg, 1, c, &nc), RTE_OK);
    assert_int_equal(nc, 1);
    assert_int_equal(c[0].width_q8, 0);
    assert_int_equal(rte_shape_calipers(seg, 3, c, &nc), RTE_OK);
    assert_int_equal(nc, 1);
    assert_int_equal(c[0].width_q8, 0);
    assert_int_equal(c[0].angle_q16, -45 * 65536);
    const rte_point twice[3] = {{0, 0}, {0, 0}, {5, 9}};
    assert_int_equal(rte_shape_calipers(twice, 3, c, &nc), RTE_ERR_ARGUMENT);
    const rte_point far[3] = {{0, 0}, {4000, 0}, {5, 9}};
    assert_int_equal(rte_shape_calipers(far, 3, c, &nc), RTE_ERR_TOO_LARGE);
    assert_int_equal(rte_shape_calipers(seg, 0, c, &nc), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_shape_calipers(NULL, 3, c, &nc), RTE_ERR_ARGUMENT);
}

/* What the grasp path computes once per contour equals the public calls:
 * the widths-only calipers with the directions filled in equal
 * rte_shape_calipers, and the box and circle of a hull at hand those of its
 * points; on the hulls of random point sets (a few collinear, some single
 * points) and the degenerate hulls. */
static void hull_shortcuts_match_the_public_calls(void **state)
{
    (void)state;
    uint32_t rng = 77;
    rte_arena a;
    rte_arena_init(&a, arena_mem, sizeof arena_mem);
    rte_point pts[64], hull[65], copy[65];
    rte_caliper full[65], lazy[65];
    for (int t = 0; t < 300; t++) {
        const int32_t n = 1 + (int32_t)(unit_rand(&rng) % 60);
        const int32_t span = 2 + (int32_t)(unit_rand(&rng) % (t % 3 ? 400 : 3));
        for (int32_t i = 0; i < n; i++) {
            pts[i].x = (int32_t)(unit_rand(&rng) % (uint32_t)span);
            pts[i].y = t % 7 == 0 ? pts[i].x : (int32_t)(unit_rand(&rng) % (uint32_t)span);
        }
        int32_t nh = 0, nf = 0, nl = 0;
        assert_int_equal(rte_shape_convex_hull(pts, n, NULL, hull, &nh, &a), RTE_OK);
        assert_int_equal(rte_shape_calipers(hull, nh, full, &nf), RTE_OK);
        assert_int_equal(rte_shape_caliper_widths(hull, nh, lazy, &nl), RTE_OK);
        assert_int_equal(nl, nf);
        for (int32_t i = 0; i < nl; i++) {
            assert_int_equal(lazy[i].width_q8, full[i].width_q8);
            rte_caliper_direction(hull, nh, &lazy[i]);
            assert_memory_equal(&lazy[i], &full[i], sizeof full[i]);
        }
        rte_rotated_rect r1, r2;
        rte_circle c1, c2;
        assert_int_equal(rte_shape_min_area_rect(pts, n, &r1, &a), RTE_OK);
        rte_shape_min_area_rect_of_hull(hull, nh, &r2);
        assert_memory_equal(&r1, &r2, sizeof r1);
        assert_int_equal(rte_shape_enclosing_circle(pts, n, &c1, &a), RTE_OK);
        memcpy(copy, hull, (size_t)nh * sizeof *copy);
        rte_shape_enclosing_circle_of_hull(copy, nh, &c2);
        assert_memory_equal(&c1, &c2, sizeof c1);
        assert_int_equal(a.used, 0);
    }
}

/* A context for w x h: no blur, dark objects below grey 120. */
static rte_grasp_ctx *new_ctx(int32_t w, int32_t h)
{
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    c.max_width = w;
    c.max_height = h;
    c.blur_ksize = 1;
    c.params.binarize = RTE_GRASP_FIXED;
    c.params.threshold = 120;
    c.params.polarity = RTE_GRASP_DARK;
    rte_grasp_ctx *ctx = NULL;
    assert_int_equal(rte_grasp_create(&c, &ctx), RTE_OK);
    return ctx;
}

static void fill(rte_image_u8 *img, const rte_vertex *v, int32_t n)
{
    rte_arena a;
    rte_arena_init(&a, arena_mem, sizeof arena_mem);
    const rte_polygon poly = {v, n};
    assert_int_equal(rte_polygon_fill_u8(img, &poly, 1, 30, &a), RTE_OK);
}

static void set_gripper(rte_grasp_ctx *ctx, int32_t lo, int32_t hi, int32_t margin, int32_t finger)
{
    rte_grasp_params p;
    assert_int_equal(rte_grasp_get_params(ctx, &p), RTE_OK);
    p.gripper_min_px = lo;
    p.gripper_max_px = hi;
    p.margin_px = margin;
    p.finger_px = finger;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
}

/* A scene of one polygon on a w x h table, through the grasp path: its one
 * object (the image and the context for the caller to free). */
typedef struct one_scene {
    rte_image_u8 img;
    rte_grasp_ctx *ctx;
    rte_grasp_result r;
} one_scene;

static const rte_grasp_object *one_object(one_scene *sc, int32_t w, int32_t h, const rte_vertex *v,
                                          int32_t n)
{
    sc->img = unit_image_u8(w, h, 0, 200);
    fill(&sc->img, v, n);
    sc->ctx = new_ctx(w, h);
    assert_int_equal(rte_grasp_process(sc->ctx, &sc->img, &sc->r), RTE_OK);
    assert_int_equal(sc->r.n_objects, 1);
    return &sc->r.objects[0];
}

static void free_scene(one_scene *sc)
{
    rte_grasp_destroy(sc->ctx);
    test_free(sc->img.buf);
}

/* The jaws: on the closing line through the grasp point, opening apart. */
static void check_jaws(const rte_grasp_object *o)
{
    const double jx = (o->jaws_q8[1][0] - o->jaws_q8[0][0]) / 256.0,
                 jy = (o->jaws_q8[1][1] - o->jaws_q8[0][1]) / 256.0;
    assert_true(fabs(sqrt(jx * jx + jy * jy) - o->opening_q8 / 256.0) < 0.05);
    assert_true(angle_diff(atan2(jy, jx) * 180 / 3.14159265358979323846, angle_deg(o->angle_q16)) <
                0.1);
    /* the grasp point lies on the segment between them */
    const double px = (o->x_q8 - o->jaws_q8[0][0]) / 256.0,
                 py = (o->y_q8 - o->jaws_q8[0][1]) / 256.0;
    assert_true(fabs(px * jy - py * jx) / sqrt(jx * jx + jy * jy) < 0.05);
    assert_true(px * jx + py * jy > 0 && px * jx + py * jy < jx * jx + jy * jy);
}

/* The triangle drawn: the width across its longest side, not the box's. */
static void triangle_scene(void **state)
{
    (void)state;
    const rte_vertex t[3] = {{20, 20}, {140, 60}, {50, 110}};
    one_scene sc;
    const rte_grasp_object *o = one_object(&sc, 200, 160, t, 3);
    const double alt = 9600 / sqrt(120.0 * 120 + 40 * 40);
    print_message("triangle: width %.2f px at %.2f deg (altitude %.2f); box short side %.2f px "
                  "at %.2f deg\n",
                  o->width_q8 / 256.0, angle_deg(o->angle_q16), alt, o->info.box.width_q8 / 256.0,
                  angle_deg(o->info.box.angle_q16) + 90);
    /* pixel centres of the filled triangle: within a pixel of the edges;
     * the minimum-area box lies along another side (a triangle's boxes
     * along its sides all have twice its area) */
    assert_true(fabs(o->width_q8 / 256.0 - alt) < 1.0);
    assert_true(o->info.box.width_q8 / 256.0 > alt + 10);
    assert_true(angle_diff(angle_deg(o->angle_q16), -71.565) < 1.0);
    assert_int_equal(o->opening_q8, o->width_q8 + 16 * 256); /* margin 8 each side */
    assert_true(o->score_q16 > 65536 * 95 / 100); /* convex but for the pixel staircase */
    check_jaws(o);
    free_scene(&sc);
}

/* A 100 x 40 rectangle turned by 30 degrees: closes across the 40 px side. */
static void rotated_rectangle(void **state)
{
    (void)state;
    const double th = 30 * 3.14159265358979323846 / 180, c = cos(th), s = sin(th);
    const double px[4] = {-50, 50, 50, -50}, py[4] = {-20, -20, 20, 20};
    rte_vertex v[4];
    for (int i = 0; i < 4; i++)
        v[i] = (rte_vertex){(int32_t)lround(100 + px[i] * c - py[i] * s),
                            (int32_t)lround(100 + px[i] * s + py[i] * c)};
    one_scene sc;
    const rte_grasp_object *o = one_object(&sc, 200, 200, v, 4);
    print_message("rectangle at 30 deg: width %.2f px at %.2f deg\n", o->width_q8 / 256.0,
                  angle_deg(o->angle_q16));
    assert_true(angle_diff(angle_deg(o->angle_q16), -60) < 1.5);
    assert_true(fabs(o->width_q8 / 256.0 - 40) < 1.5);
    assert_true(abs(o->x_q8 - 100 * 256) < 128 && abs(o->y_q8 - 100 * 256) < 128);
    assert_true(o->score_q16 > 65536 * 95 / 100);
    check_jaws(o);
    /* the jaws straddle the rectangle symmetrically about its centre */
    const int32_t mx = (o->jaws_q8[0][0] + o->jaws_q8[1][0]) / 2,
                  my = (o->jaws_q8[0][1] + o->jaws_q8[1][1]) / 2;
    assert_true(abs(mx - o->x_q8) < 256 && abs(my - o->y_q8) < 256);
    free_scene(&sc);
}

/* A non-convex L (arms 100 x 20): the hull's narrowest width runs from the
 * outer corner to both arms' tips, 120 / sqrt(2) = 84.85 px at -45 degrees,
 * where the box's short side is 100 px; the centroid lies off the L, and
 * the score is the solidity, 3600 / 6800. */
static void l_shape(void **state)
{
    (void)state;
    const rte_vertex v[6] = {{20, 20}, {40, 20}, {40, 100}, {120, 100}, {120, 120}, {20, 120}};
    one_scene sc;
    const rte_grasp_object *o = one_object(&sc, 180, 180, v, 6);
    print_message("L: width %.2f px at %.2f deg, box short side %.2f px; score %.3f, solidity "
                  "%.3f\n",
                  o->width_q8 / 256.0, angle_deg(o->angle_q16), o->info.box.width_q8 / 256.0,
                  o->score_q16 / 65536.0, o->info.solidity_q16 / 65536.0);
    assert_true(fabs(o->width_q8 / 256.0 - 120 / sqrt(2)) < 1.5);
    assert_true(angle_diff(angle_deg(o->angle_q16), -45) < 1.0);
    assert_true(o->info.box.width_q8 / 256.0 > 98);
    const int32_t gx = (o->x_q8 + 128) >> 8, gy = (o->y_q8 + 128) >> 8;
    assert_int_equal(sc.img.buf[(size_t)gy * sc.img.stride + gx], 200); /* table, not L */
    assert_int_equal(o->score_q16, o->info.solidity_q16);
    assert_true(fabs(o->score_q16 / 65536.0 - 3600.0 / 6800) < 0.03);
    check_jaws(o);
    free_scene(&sc);
}

/* A 60 px wide bar against the gripper's range: too wide, margin cut,
 * fits; too narrow for the jaws to close on. */
static void gripper_range(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(200, 200, 0, 200);
    const rte_vertex v[4] = {{70, 40}, {130, 40}, {130, 160}, {70, 160}}; /* 60 x 120 */
    fill(&img, v, 4);
    rte_grasp_ctx *ctx = new_ctx(200, 200);
    rte_grasp_result r;
    const struct {
        int32_t lo, hi, score_q16;
    } cases[] = {
        {0, 50, 0},                      /* too wide */
        {0, 70, (70 - 60) * 65536 / 16}, /* 10 of the 16 px of margin */
        {0, 76, 65536},                  /* 60 + 2 x 8 */
        {0, 200, 65536},                 /* */
        {61, 200, 0},                    /* too narrow */
        {60, 60, 0},                     /* margin: none left */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        set_gripper(ctx, cases[i].lo, cases[i].hi, 8, 8);
        assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
        assert_int_equal(r.n_objects, 1);
        assert_int_equal(r.objects[0].width_q8, 60 * 256);
        assert_int_equal(r.objects[0].angle_q16, 0);
        assert_int_equal(r.objects[0].opening_q8, 76 * 256);
        assert_int_equal(r.objects[0].score_q16, cases[i].score_q16);
    }
    /* the parameters' bounds */
    rte_grasp_params p;
    rte_grasp_get_params(ctx, &p);
    p.gripper_min_px = 10;
    p.gripper_max_px = 9;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p.gripper_max_px = RTE_GRASP_MAX_OPENING_PX + 1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p.gripper_max_px = 100;
    p.margin_px = -1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p.margin_px = 0;
    p.finger_px = RTE_GRASP_MAX_CLEARANCE_PX + 1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* Two 30 x 80 bars side by side, `gap` px of table between them: the
 * clearance (and score) of each, closing across them towards the other. */
static void pair(int32_t gap, rte_grasp_result *r, rte_grasp_ctx *ctx, rte_image_u8 *img)
{
    for (int32_t y = 0; y < img->height; y++)
        for (int32_t x = 0; x < img->width; x++)
            img->buf[(size_t)y * img->stride + x] = 200;
    const int32_t x0 = 100 - gap / 2 - 30;
    const rte_vertex a[4] = {{x0, 40}, {x0 + 29, 40}, {x0 + 29, 119}, {x0, 119}};
    const rte_vertex b[4] = {
        {x0 + 30 + gap, 40}, {x0 + 59 + gap, 40}, {x0 + 59 + gap, 119}, {x0 + 30 + gap, 119}};
    fill(img, a, 4);
    fill(img, b, 4);
    assert_int_equal(rte_grasp_process(ctx, img, r), RTE_OK);
    assert_int_equal(r->n_objects, 2);
}

static void clearance(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(200, 160, 0, 200);
    rte_grasp_ctx *ctx = new_ctx(200, 160);
    rte_grasp_result r;
    pair(40, &r, ctx, &img); /* far apart: 40 px, more than margin + finger */
    int32_t far_score = r.objects[0].score_q16;
    for (int k = 0; k < 2; k++) {
        assert_int_equal(r.objects[k].angle_q16, 0);
        assert_int_equal(r.objects[k].clearance_q8, 16 * 256);
        assert_int_equal(r.objects[k].score_q16, 65536);
    }
    pair(6, &r, ctx, &img); /* close: 6 px of table between them */
    print_message("bars 6 px apart: clearance %.1f px, score %.3f (40 px apart: %.3f)\n",
                  r.objects[0].clearance_q8 / 256.0, r.objects[0].score_q16 / 65536.0,
                  far_score / 65536.0);
    for (int k = 0; k < 2; k++) {
        assert_int_equal(r.objects[k].angle_q16, 0);
        assert_int_equal(r.objects[k].clearance_q8, 6 * 256);
        assert_int_equal(r.objects[k].score_q16, 6 * 65536 / 16);
        assert_true(r.objects[k].score_q16 < far_score);
    }
    /* no finger room needed: the same score as far apart */
    set_gripper(ctx, 4, 160, 0, 0);
    pair(6, &r, ctx, &img);
    assert_int_equal(r.objects[0].score_q16, 65536);
    /* a disc chooses the side with room: a neighbour to the right only */
    set_gripper(ctx, 4, 160, 8, 8);
    rte_image_u8 d = unit_image_u8(200, 160, 0, 200);
    for (int32_t y = 0; y < 160; y++)
        for (int32_t x = 0; x < 200; x++)
            if ((x - 80) * (x - 80) + (y - 80) * (y - 80) <= 20 * 20 || (x >= 104 && x < 120))
                d.buf[(size_t)y * d.stride + x] = 30;
    assert_int_equal(rte_grasp_process(ctx, &d, &r), RTE_OK);
    const rte_grasp_object *disc = NULL;
    for (int32_t k = 0; k < r.n_objects; k++)
        if (abs(r.objects[k].x_q8 - 80 * 256) < 256)
            disc = &r.objects[k];
    assert_non_null(disc);
    print_message("disc beside a wall: angle %.1f deg, clearance %.1f px\n",
                  angle_deg(disc->angle_q16), disc->clearance_q8 / 256.0);
    assert_int_equal(disc->clearance_q8, 16 * 256);
    assert_true(angle_diff(angle_deg(disc->angle_q16), 90) < 45);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
    test_free(d.buf);
}

/* The order: best score first whatever the areas; equal scores by area. */
static void sorted_by_score(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(400, 200, 0, 200);
    const rte_vertex wide[4] = {{10, 10}, {189, 10}, {189, 189}, {10, 189}};   /* 180 px */
    const rte_vertex small[4] = {{220, 20}, {249, 20}, {249, 59}, {220, 59}};  /* 30 x 40 */
    const rte_vertex bigger[4] = {{300, 20}, {349, 20}, {349, 79}, {300, 79}}; /* 50 x 60 */
    const rte_vertex ell[6] = {{220, 100}, {230, 100}, {230, 170},
                               {290, 170}, {290, 180}, {220, 180}}; /* an L: solidity about 0.4 */
    fill(&img, wide, 4);
    fill(&img, small, 4);
    fill(&img, bigger, 4);
    fill(&img, ell, 6);
    rte_grasp_ctx *ctx = new_ctx(400, 200);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 4);
    for (int32_t k = 0; k < 4; k++)
        print_message("%d: score %.3f area %.0f\n", (int)k, r.objects[k].score_q16 / 65536.0,
                      r.objects[k].info.area2 / 2.0);
    /* the two bars score 1 (larger first), the L its solidity, the block 0 */
    assert_int_equal(r.objects[0].info.bounds.x, 300);
    assert_int_equal(r.objects[1].info.bounds.x, 220);
    assert_int_equal(r.objects[1].info.bounds.y, 20);
    assert_int_equal(r.objects[0].score_q16, 65536);
    assert_int_equal(r.objects[1].score_q16, 65536);
    assert_int_equal(r.objects[2].info.bounds.y, 100);
    assert_true(r.objects[2].score_q16 > 0 && r.objects[2].score_q16 < 65536 / 2);
    assert_int_equal(r.objects[3].info.bounds.x, 10);
    assert_int_equal(r.objects[3].score_q16, 0);
    /* with room for one: the best, not the largest */
    rte_grasp_params p;
    rte_grasp_get_params(ctx, &p);
    p.max_objects = 1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.dropped_objects, 3);
    assert_int_equal(r.objects[0].info.bounds.x, 300);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(calipers_triangle),
        cmocka_unit_test(hull_shortcuts_match_the_public_calls),
        cmocka_unit_test(triangle_scene),
        cmocka_unit_test(rotated_rectangle),
        cmocka_unit_test(l_shape),
        cmocka_unit_test(gripper_range),
        cmocka_unit_test(clearance),
        cmocka_unit_test(sorted_by_score),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
