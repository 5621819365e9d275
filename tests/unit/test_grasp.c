/* The grasp path on synthetic table-top scenes with known objects: every
 * object found, centroid within 1 px, approach angle within 2 degrees,
 * shape class right, no phantoms; then the bounds, run-time parameters and
 * argument errors. */
#include "unit.h"

#include <math.h>

#include "rtedge/color.h"
#include "rtedge/grasp.h"
#include "rtedge/polygon_mask.h"

#define PI 3.14159265358979323846

typedef struct truth {
    rte_shape_class shape;
    double cx, cy; /* centroid of the shape as drawn */
    double angle;  /* closing direction (rectangles), degrees in (-90, 90] */
    int has_angle;
} truth;

enum { MAX_TRUTH = 16 };

typedef struct scene {
    rte_image_u8 img;
    truth t[MAX_TRUTH];
    int n;
} scene;

static uint8_t arena_mem[1 << 16];

/* Fills the polygon (integer vertices) with `value` and records its centroid. */
static void fill_polygon(rte_image_u8 *img, const rte_vertex *v, int n, uint8_t value, truth *t)
{
    rte_arena a;
    rte_arena_init(&a, arena_mem, sizeof arena_mem);
    rte_polygon poly = {v, n};
    assert_int_equal(rte_polygon_fill_u8(img, &poly, 1, value, &a), RTE_OK);
    double a2 = 0, sx = 0, sy = 0;
    for (int i = 0; i < n; i++) {
        const double x0 = v[i].x, y0 = v[i].y, x1 = v[(i + 1) % n].x, y1 = v[(i + 1) % n].y;
        const double c = x0 * y1 - x1 * y0;
        a2 += c;
        sx += (x0 + x1) * c;
        sy += (y0 + y1) * c;
    }
    t->cx = sx / (3 * a2);
    t->cy = sy / (3 * a2);
}

static void fill_disc(rte_image_u8 *img, int cx, int cy, int r, uint8_t value, truth *t)
{
    for (int y = cy - r; y <= cy + r; y++)
        for (int x = cx - r; x <= cx + r; x++)
            if (x >= 0 && y >= 0 && x < img->width && y < img->height &&
                (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
                img->buf[(size_t)y * img->stride + x] = value;
    t->cx = cx;
    t->cy = cy;
}

static double rnd(uint32_t *s, double lo, double hi)
{
    return lo + (hi - lo) * (unit_rand(s) % 100000) / 100000.0;
}

/* A regular polygon or rectangle of half sizes (hl, hw) turned by th. */
static void rect_vertices(double cx, double cy, double hl, double hw, double th, rte_vertex *v)
{
    const double c = cos(th), s = sin(th);
    const double px[4] = {-hl, hl, hl, -hl}, py[4] = {-hw, -hw, hw, hw};
    for (int i = 0; i < 4; i++) {
        v[i].x = (int32_t)lround(cx + px[i] * c - py[i] * s);
        v[i].y = (int32_t)lround(cy + px[i] * s + py[i] * c);
    }
}

/* One object of the given class centred near (cx, cy) in a cell of `cell` px. */
static void draw_object(scene *sc, rte_shape_class shape, double cx, double cy, int cell,
                        uint8_t value, uint32_t *rng)
{
    truth *t = &sc->t[sc->n++];
    t->shape = shape;
    t->has_angle = 0;
    const double th = rnd(rng, 0, PI);
    rte_vertex v[4];
    if (shape == RTE_SHAPE_RECTANGLE) {
        const double hl = rnd(rng, 0.28, 0.38) * cell, hw = hl / rnd(rng, 1.6, 2.6);
        rect_vertices(cx, cy, hl, hw, th, v);
        fill_polygon(&sc->img, v, 4, value, t);
        /* long side from the drawn vertices; the gripper closes across it */
        double a = atan2(v[1].y - v[0].y, v[1].x - v[0].x) * 180 / PI + 90;
        while (a > 90)
            a -= 180;
        while (a <= -90)
            a += 180;
        t->angle = a;
        t->has_angle = 1;
    } else if (shape == RTE_SHAPE_SQUARE) {
        const double h = rnd(rng, 0.18, 0.28) * cell;
        rect_vertices(cx, cy, h, h, th, v);
        fill_polygon(&sc->img, v, 4, value, t);
    } else if (shape == RTE_SHAPE_TRIANGLE) {
        const double r = rnd(rng, 0.25, 0.38) * cell;
        for (int i = 0; i < 3; i++) {
            v[i].x = (int32_t)lround(cx + r * cos(th + i * 2 * PI / 3));
            v[i].y = (int32_t)lround(cy + r * sin(th + i * 2 * PI / 3));
        }
        fill_polygon(&sc->img, v, 3, value, t);
    } else {
        fill_disc(&sc->img, (int)lround(cx), (int)lround(cy),
                  (int)lround(rnd(rng, 0.16, 0.3) * cell), value, t);
    }
}

/* A w x h table (grey `table` +- noise) with objects in a grid of cells. */
static scene make_scene(uint32_t seed, int32_t w, int32_t h, int pad, uint8_t table, uint8_t object)
{
    scene sc = {.img = unit_image_u8(w, h, pad, table)};
    uint32_t rng = seed;
    const int cell = 150, cols = w / cell, rows = h / cell;
    static const rte_shape_class classes[4] = {RTE_SHAPE_RECTANGLE, RTE_SHAPE_SQUARE,
                                               RTE_SHAPE_TRIANGLE, RTE_SHAPE_CIRCLE};
    for (int r = 0; r < rows; r++)
        for (int c = 0; c < cols && sc.n < MAX_TRUTH; c++) {
            if (unit_rand(&rng) % 5 == 0)
                continue; /* an empty cell */
            const double cx = c * cell + cell / 2.0 + rnd(&rng, -10, 10);
            const double cy = r * cell + cell / 2.0 + rnd(&rng, -10, 10);
            draw_object(&sc, classes[unit_rand(&rng) % 4], cx, cy, cell, object, &rng);
        }
    /* sensor noise on everything */
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            uint8_t *p = &sc.img.buf[(size_t)y * sc.img.stride + x];
            *p = (uint8_t)(*p + (int)(unit_rand(&rng) % 17) - 8);
        }
    return sc;
}

static rte_grasp_ctx *new_ctx_blur(int32_t w, int32_t h, rte_grasp_binarize mode, int32_t blur)
{
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    c.max_width = w;
    c.max_height = h;
    c.params.binarize = mode;
    c.params.skip_border = 0; /* the tests that drop border objects say so */
    c.params.split = 0;       /* and those that split */
    c.blur_ksize = blur;
    rte_grasp_ctx *ctx = NULL;
    assert_int_equal(rte_grasp_create(&c, &ctx), RTE_OK);
    assert_non_null(ctx);
    return ctx;
}

static rte_grasp_ctx *new_ctx(int32_t w, int32_t h, rte_grasp_binarize mode)
{
    return new_ctx_blur(w, h, mode, 5);
}

static double angle_diff(double a, double b)
{
    double d = fmod(fabs(a - b), 180.0);
    return d > 90 ? 180 - d : d;
}

/* The largest errors seen, printed by the scene tests. */
static double worst_px, worst_deg;

/* Every object of the scene matches one result (and the counts agree). */
static void check_scene(const scene *sc, const rte_grasp_result *r, double tol_px, int check_class)
{
    assert_int_equal(r->n_objects, sc->n);
    assert_int_equal(r->truncated, 0);
    int used[MAX_TRUTH] = {0};
    for (int i = 0; i < sc->n; i++) {
        const truth *t = &sc->t[i];
        int best = -1;
        double bd = 1e9;
        for (int k = 0; k < r->n_objects; k++) {
            const double dx = r->objects[k].x_q8 / 256.0 - t->cx,
                         dy = r->objects[k].y_q8 / 256.0 - t->cy;
            const double d = sqrt(dx * dx + dy * dy);
            if (!used[k] && d < bd) {
                bd = d;
                best = k;
            }
        }
        assert_true(best >= 0);
        if (bd > tol_px)
            fail_msg("object %d (class %d) at %.2f,%.2f: nearest result %.2f px away", i, t->shape,
                     t->cx, t->cy, bd);
        used[best] = 1;
        worst_px = bd > worst_px ? bd : worst_px;
        const rte_grasp_object *o = &r->objects[best];
        if (check_class && o->info.shape != t->shape)
            fail_msg("object %d at %.1f,%.1f: class %d, expected %d", i, t->cx, t->cy,
                     o->info.shape, t->shape);
        if (t->has_angle && angle_diff(o->angle_q16 / 65536.0, t->angle) > worst_deg)
            worst_deg = angle_diff(o->angle_q16 / 65536.0, t->angle);
        if (t->has_angle && angle_diff(o->angle_q16 / 65536.0, t->angle) > 2.0)
            fail_msg("rectangle at %.1f,%.1f: angle %.2f, expected %.2f", t->cx, t->cy,
                     o->angle_q16 / 65536.0, t->angle);
    }
    for (int k = 1; k < r->n_objects; k++) { /* by score, then area */
        const rte_grasp_object *a = &r->objects[k - 1], *b = &r->objects[k];
        assert_true(a->score_q16 > b->score_q16 ||
                    (a->score_q16 == b->score_q16 && a->info.area2 >= b->info.area2));
    }
}

static void synthetic_scenes(void **state)
{
    (void)state;
    const int32_t w = 640, h = 480;
    rte_grasp_ctx *ctx = new_ctx(w, h, RTE_GRASP_OTSU);
    int objects = 0;
    worst_px = worst_deg = 0;
    for (uint32_t seed = 1; seed <= 24; seed++) {
        /* dark objects on a light table, then bright ones on a dark table */
        const int dark = seed & 1;
        scene sc = make_scene(seed * 2654435761u, w, h, (int)(seed % 3) * 7, dark ? 190 : 60,
                              dark ? 50 : 200);
        rte_grasp_result r;
        assert_int_equal(rte_grasp_process(ctx, &sc.img, &r), RTE_OK);
        assert_int_equal(r.polarity, dark ? RTE_GRASP_DARK : RTE_GRASP_BRIGHT);
        check_scene(&sc, &r, 1.0, 1);
        unit_assert_padding_u8(&sc.img);
        objects += sc.n;
        test_free(sc.img.buf);
    }
    assert_true(objects > 150);
    print_message("otsu: %d objects, largest centroid error %.3f px, angle error %.3f deg\n",
                  objects, worst_px, worst_deg);
    rte_grasp_destroy(ctx);
}

/* Canny + close finds the same objects by their outlines. */
static void canny_close_scenes(void **state)
{
    (void)state;
    const int32_t w = 640, h = 480;
    rte_grasp_ctx *ctx = new_ctx(w, h, RTE_GRASP_CANNY_CLOSE);
    worst_px = worst_deg = 0;
    for (uint32_t seed = 1; seed <= 6; seed++) {
        scene sc = make_scene(seed * 40503u, w, h, 3, 170, 70);
        rte_grasp_result r;
        assert_int_equal(rte_grasp_process(ctx, &sc.img, &r), RTE_OK);
        assert_int_equal(r.threshold, -1);
        check_scene(&sc, &r, 1.0, 1);
        test_free(sc.img.buf);
    }
    print_message("canny-close: largest centroid error %.3f px, angle error %.3f deg\n", worst_px,
                  worst_deg);
    rte_grasp_destroy(ctx);
}

/* A context with the library's defaults for w x h frames. */
static rte_grasp_ctx *default_ctx(int32_t w, int32_t h)
{
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    c.max_width = w;
    c.max_height = h;
    rte_grasp_ctx *ctx = NULL;
    assert_int_equal(rte_grasp_create(&c, &ctx), RTE_OK);
    return ctx;
}

/* The synthetic scenes under a lamp: the table falls off from 200 in the
 * middle to 110 in the corners, objects both darker and lighter than it.
 * The default configuration (background, split, border rule) finds every
 * object and nothing on the dark corners. */
static void vignetted_scenes(void **state)
{
    (void)state;
    const int32_t w = 640, h = 480;
    rte_grasp_ctx *ctx = default_ctx(w, h);
    worst_px = worst_deg = 0;
    int objects = 0;
    for (uint32_t seed = 1; seed <= 8; seed++) {
        const int dark = seed & 1; /* objects 100 below or 45 above the table */
        scene sc = make_scene(seed * 2246822519u, w, h, 3, 128, dark ? 28 : 173);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                const double dx = (x - w / 2.0) / (w / 2.0), dy = (y - h / 2.0) / (h / 2.0);
                uint8_t *px = &sc.img.buf[(size_t)y * sc.img.stride + x];
                *px = (uint8_t)(*px + 72 - (int)lround(45 * (dx * dx + dy * dy)));
            }
        rte_grasp_result r;
        assert_int_equal(rte_grasp_process(ctx, &sc.img, &r), RTE_OK);
        check_scene(&sc, &r, 1.0, 1);
        objects += sc.n;
        test_free(sc.img.buf);
    }
    print_message("background: %d objects under a vignette, largest centroid error %.3f px, "
                  "angle error %.3f deg\n",
                  objects, worst_px, worst_deg);
    rte_grasp_destroy(ctx);
}

/* Touching discs (a pair, a row of three, a triangle of three) come apart
 * at their necks, each with its own grasp point near its centre; a bar with
 * a bulging end, and two squares sharing a whole edge (no neck), stay one. */
static void touching_objects_split(void **state)
{
    (void)state;
    const int32_t w = 400, h = 300;
    rte_grasp_ctx *ctx = default_ctx(w, h);
    static const struct {
        int n;
        int x[3], y[3], r[3];
    } groups[] = {
        {2, {100, 140}, {80, 80}, {22, 22}},
        {2, {260, 297}, {90, 96}, {24, 18}},
        {3, {80, 120, 160}, {200, 200, 200}, {22, 22, 22}},
        {3, {270, 313, 292}, {200, 200, 237}, {22, 22, 22}}, /* just touching: packed
                                                               * closer, three discs are one
                                                               * round blob without necks */
    };
    rte_image_u8 img = unit_image_u8(w, h, 1, 190);
    truth t[12];
    int n = 0;
    for (size_t g = 0; g < sizeof groups / sizeof groups[0]; g++)
        for (int i = 0; i < groups[g].n; i++, n++)
            fill_disc(&img, groups[g].x[i], groups[g].y[i], groups[g].r[i], 50, &t[n]);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, n);
    assert_int_equal(r.split_parts, n - 4);
    for (int i = 0; i < n; i++) {
        double best = 1e9;
        for (int k = 0; k < r.n_objects; k++) {
            const double dx = r.objects[k].x_q8 / 256.0 - t[i].cx,
                         dy = r.objects[k].y_q8 / 256.0 - t[i].cy;
            best = fmin(best, sqrt(dx * dx + dy * dy));
        }
        print_message("split: disc at %.0f,%.0f found %.2f px from its centre\n", t[i].cx, t[i].cy,
                      best);
        assert_true(best < 2.0); /* the cut line takes a pixel or two off one side */
    }

    /* stays one: a pen with a bulging tip, two squares side by side */
    rte_image_u8 one = unit_image_u8(w, h, 1, 190);
    const rte_vertex pen[4] = {{60, 100}, {260, 100}, {260, 109}, {60, 109}};
    const rte_vertex sq1[4] = {{100, 180}, {159, 180}, {159, 239}, {100, 239}};
    const rte_vertex sq2[4] = {{160, 180}, {219, 180}, {219, 239}, {160, 239}};
    fill_polygon(&one, pen, 4, 50, &t[0]);
    fill_disc(&one, 266, 104, 9, 50, &t[1]);
    fill_polygon(&one, sq1, 4, 50, &t[2]);
    fill_polygon(&one, sq2, 4, 50, &t[3]);
    assert_int_equal(rte_grasp_process(ctx, &one, &r), RTE_OK);
    assert_int_equal(r.n_objects, 2);
    assert_int_equal(r.split_parts, 0);
    rte_grasp_params p;
    assert_int_equal(rte_grasp_get_params(ctx, &p), RTE_OK);
    p.split = 0;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 4); /* without the split: one object per group */
    rte_grasp_destroy(ctx);
    test_free(img.buf);
    test_free(one.buf);
}

/* The cut between touching objects runs along the grey edge between them:
 * a light disc and a dark one with the dark shadow of the crevice between
 * them, which widens the neck. The distance alone cuts in the shadow's
 * middle and gives the light disc half of it; the cut goes to the light
 * disc's outline, and the shadow, as dark as the dark disc, goes with it. */
static void cut_follows_the_grey_edge(void **state)
{
    (void)state;
    const int32_t w = 320, h = 240;
    rte_grasp_ctx *ctx = default_ctx(w, h);
    rte_image_u8 img = unit_image_u8(w, h, 1, 220);
    const rte_vertex crevice[4] = {{166, 134}, {187, 134}, {187, 166}, {166, 166}};
    truth light, dark, shadow;
    fill_polygon(&img, crevice, 4, 50, &shadow);
    fill_disc(&img, 150, 150, 26, 110, &light); /* the distance alone: 2.9 px off */
    fill_disc(&img, 203, 150, 26, 30, &dark);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 2);
    assert_int_equal(r.split_parts, 1);
    const rte_grasp_object *a = &r.objects[0], *b = &r.objects[1];
    if (a->x_q8 > b->x_q8) {
        a = &r.objects[1];
        b = &r.objects[0];
    }
    const double ex = a->x_q8 / 256.0 - light.cx, ey = a->y_q8 / 256.0 - light.cy;
    print_message("cut: the light disc's centre %.2f px off, the dark one's at %.1f,%.1f\n",
                  sqrt(ex * ex + ey * ey), b->x_q8 / 256.0, b->y_q8 / 256.0);
    assert_true(sqrt(ex * ex + ey * ey) < 0.5);
    assert_true(b->x_q8 / 256.0 < dark.cx); /* the shadow is the dark disc's */
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* A box shaded from dark to light across the table's grey: the threshold
 * cuts it where it matches the table and leaves two pieces whose outline
 * runs, on one side, across the smooth ramp: not on an edge, so they are
 * dropped; a disc beside it, all edge, is kept. Without the edge test the
 * pieces are objects. */
static void outlines_off_the_edges_are_dropped(void **state)
{
    (void)state;
    const int32_t w = 320, h = 240;
    rte_grasp_ctx *ctx = default_ctx(w, h);
    rte_image_u8 img = unit_image_u8(w, h, 1, 128);
    for (int y = 60; y < 180; y++)
        for (int x = 30; x < 130; x++) /* 20 .. 236, 2.2 levels a pixel */
            img.buf[(size_t)y * img.stride + x] = (uint8_t)(20 + (x - 30) * 216 / 99);
    truth disc;
    fill_disc(&img, 240, 120, 20, 40, &disc);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.objects[0].x_q8, 240 * 256);
    assert_int_equal(r.objects[0].y_q8, 120 * 256);

    rte_grasp_params p;
    assert_int_equal(rte_grasp_get_params(ctx, &p), RTE_OK);
    assert_int_equal(p.edge_support_permille, 750);
    p.edge_support_permille = 0;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 3); /* the disc and the box's two ends */
    p.edge_support_permille = 1001;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p.edge_support_permille = -1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* Two squares sharing an edge are one blob: one object, no phantom. */
static void touching_objects_merge(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(200, 120, 5, 200);
    truth t;
    const rte_vertex a[4] = {{40, 30}, {99, 30}, {99, 89}, {40, 89}};
    const rte_vertex b[4] = {{100, 30}, {159, 30}, {159, 89}, {100, 89}};
    fill_polygon(&img, a, 4, 40, &t);
    fill_polygon(&img, b, 4, 40, &t);
    rte_grasp_ctx *ctx = new_ctx(200, 120, RTE_GRASP_OTSU);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.objects[0].info.shape, RTE_SHAPE_RECTANGLE);
    assert_int_equal(r.objects[0].x_q8, (int32_t)(99.5 * 256));
    assert_int_equal(r.objects[0].y_q8, (int32_t)(59.5 * 256));
    /* a 120 x 60 block: closes vertically, opens to 59 px (pixel centres) */
    assert_int_equal(r.objects[0].angle_q16, 90 * 65536);
    assert_int_equal(r.objects[0].width_q8, 59 * 256);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* Objects on the image border: kept and flagged, or skipped. Area limits. */
static void border_and_area_filters(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(160, 100, 0, 210);
    truth t;
    const rte_vertex edge[4] = {
        {0, 10}, {29, 10}, {29, 49}, {0, 49}}; /* 30 x 40, on the left border */
    const rte_vertex mid[4] = {{70, 30}, {119, 30}, {119, 69}, {70, 69}};    /* 50 x 40 */
    const rte_vertex tiny[4] = {{140, 80}, {145, 80}, {145, 85}, {140, 85}}; /* 6 x 6 */
    fill_polygon(&img, edge, 4, 30, &t);
    fill_polygon(&img, mid, 4, 30, &t);
    fill_polygon(&img, tiny, 4, 30, &t);
    rte_grasp_ctx *ctx = new_ctx_blur(160, 100, RTE_GRASP_FIXED, 1); /* exact areas */
    rte_grasp_params p;
    assert_int_equal(rte_grasp_get_params(ctx, &p), RTE_OK);
    p.threshold = 120;
    p.polarity = RTE_GRASP_DARK;
    p.min_area = 20;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.threshold, 120);
    /* by score: the middle one (room all round), the small one (15 px to
     * the right border: less than margin + finger), the one on the border */
    assert_int_equal(r.n_objects, 3);
    assert_int_equal(r.objects[0].touches_border, 0);
    assert_int_equal(r.objects[0].score_q16, 65536);
    assert_int_equal(r.objects[1].info.area2, 2 * 25);
    assert_true(r.objects[1].score_q16 > 0 && r.objects[1].score_q16 < 65536);
    assert_int_equal(r.objects[2].touches_border, 1);
    assert_int_equal(r.objects[2].score_q16, 0);

    p.skip_border = 1;
    p.min_area = 26; /* the 6 x 6 square's contour encloses 5 x 5 */
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.objects[0].x_q8, (int32_t)(94.5 * 256));

    p.skip_border = 0;
    p.max_area = 49 * 39 - 1; /* drops the middle one */
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.objects[0].touches_border, 1);

    /* the wrong polarity sees the table as one object touching the border */
    p.max_area = 0;
    p.polarity = RTE_GRASP_BRIGHT;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.objects[0].touches_border, 1);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* A workspace polygon: objects outside it are not seen, one across its
 * edge touches the border (dropped with skip_border, clipped without), and
 * the one inside is found exactly as without a workspace. */
static void workspace(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(160, 100, 0, 210);
    truth t;
    const rte_vertex outside[4] = {{5, 5}, {24, 5}, {24, 24}, {5, 24}};      /* 20 x 20 */
    const rte_vertex across[4] = {{30, 40}, {59, 40}, {59, 69}, {30, 69}};   /* 30 x 30 */
    const rte_vertex inside[4] = {{90, 40}, {129, 40}, {129, 59}, {90, 59}}; /* 40 x 20 */
    fill_polygon(&img, outside, 4, 30, &t);
    fill_polygon(&img, across, 4, 30, &t);
    fill_polygon(&img, inside, 4, 30, &t);
    rte_grasp_ctx *ctx = new_ctx_blur(160, 100, RTE_GRASP_FIXED, 1);
    rte_grasp_params p;
    assert_int_equal(rte_grasp_get_params(ctx, &p), RTE_OK);
    p.threshold = 120;
    p.polarity = RTE_GRASP_DARK;
    p.min_area = 20;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 3); /* by area: across, inside, outside */
    const int32_t inside_x = r.objects[1].x_q8, inside_y = r.objects[1].y_q8;
    const int32_t inside_angle = r.objects[1].angle_q16;
    assert_int_equal(inside_x, (int32_t)(109.5 * 256));

    /* x from 0.25 to 0.95, y from 0.2 to 0.9 of 160 x 100: columns 40..152,
     * rows 20..90; `across` spans columns 30..59 */
    const int32_t q = RTE_POLYGON_FRACTION_ONE;
    const rte_vertex roi[4] = {
        {q / 4, q / 5}, {q * 95 / 100, q / 5}, {q * 95 / 100, q * 9 / 10}, {q / 4, q * 9 / 10}};
    memcpy(p.roi, roi, sizeof roi);
    p.roi_count = 4;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 2);
    assert_int_equal(r.objects[0].x_q8, inside_x); /* the larger now: across is cut to 20 x 30 */
    assert_int_equal(r.objects[0].touches_border, 0);
    assert_int_equal(r.objects[0].y_q8, inside_y);
    assert_int_equal(r.objects[0].angle_q16, inside_angle);
    assert_int_equal(r.objects[1].touches_border, 1);
    assert_true(r.objects[1].info.bounds.x >= 40);

    p.skip_border = 1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_int_equal(r.objects[0].x_q8, inside_x);

    /* a smaller frame rebuilds the mask for its size */
    rte_image_u8 half = rte_image_u8_view(img.buf, 80, 50, img.stride);
    assert_int_equal(rte_grasp_process(ctx, &half, &r), RTE_OK);
    assert_int_equal(r.n_objects, 0); /* only `across`, on the workspace's edge */

    p.roi_count = 2;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p.roi_count = 4;
    p.roi[1].x = RTE_POLYGON_MAX_FRACTION + 1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* More objects than room: the best are kept (equal scores: the largest),
 * the rest counted. */
static void object_bound(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(400, 60, 2, 220);
    truth t;
    for (int i = 0; i < 10; i++) {
        const int s = 10 + 2 * i; /* sizes 10..28 */
        const rte_vertex v[4] = {
            {5 + 38 * i, 5}, {5 + 38 * i + s, 5}, {5 + 38 * i + s, 5 + s}, {5 + 38 * i, 5 + s}};
        fill_polygon(&img, v, 4, 20, &t);
    }
    rte_grasp_ctx *ctx = new_ctx(400, 60, RTE_GRASP_OTSU);
    rte_grasp_params p;
    rte_grasp_get_params(ctx, &p);
    p.min_area = 0;
    p.max_objects = 3;
    p.margin_px = p.finger_px = 0; /* (squares 10 px apart: every score 1) */
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 3);
    assert_int_equal(r.truncated, 1);
    assert_int_equal(r.dropped_objects, 7);
    assert_true(r.objects[0].info.area2 > r.objects[1].info.area2);
    assert_true(r.objects[1].info.area2 > r.objects[2].info.area2);
    assert_int_equal(r.objects[0].info.bounds.x, 5 + 38 * 9);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* Tiny and degenerate images: no objects, no crash; sizes and arguments. */
static void sizes_and_errors(void **state)
{
    (void)state;
    rte_grasp_ctx *ctx = new_ctx(67, 67, RTE_GRASP_OTSU);
    rte_grasp_result r;
    const int32_t sizes[][2] = {{1, 1}, {1, 67}, {67, 1}, {2, 2}, {67, 67}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        rte_image_u8 img = unit_image_u8(sizes[i][0], sizes[i][1], 3, 128);
        assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
        assert_int_equal(r.n_objects, 0);
        unit_assert_padding_u8(&img);
        test_free(img.buf);
    }
    rte_image_u8 big = unit_image_u8(68, 10, 0, 0);
    assert_int_equal(rte_grasp_process(ctx, &big, &r), RTE_ERR_SIZE);
    assert_int_equal(rte_grasp_process(NULL, &big, &r), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_grasp_process(ctx, &big, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_grasp_process(ctx, NULL, &r), RTE_ERR_ARGUMENT);
    test_free(big.buf);

    rte_grasp_params p, old;
    rte_grasp_get_params(ctx, &old);
    p = old;
    p.threshold = 256;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p = old;
    p.max_objects = 65;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p = old;
    p.binarize = (rte_grasp_binarize)4;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p = old;
    p.canny_high = 2041;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    rte_grasp_get_params(ctx, &p);
    assert_memory_equal(&p, &old, sizeof p);
    rte_grasp_destroy(ctx);
    rte_grasp_destroy(NULL);

    rte_grasp_config c;
    rte_grasp_config_default(&c);
    assert_true(rte_grasp_memory_size(&c) > 3 * 1280 * 720);
    rte_grasp_ctx *bad = (rte_grasp_ctx *)&c;
    c.blur_ksize = 4;
    assert_int_equal(rte_grasp_create(&c, &bad), RTE_ERR_ARGUMENT);
    assert_null(bad);
    assert_int_equal(rte_grasp_memory_size(&c), 0);
    rte_grasp_config_default(&c);
    c.max_width = RTE_SHAPE_MAX_COORD + 2;
    assert_int_equal(rte_grasp_create(&c, &bad), RTE_ERR_ARGUMENT);
    rte_grasp_config_default(&c);
    c.params.max_objects = c.max_objects + 1;
    assert_int_equal(rte_grasp_create(&c, &bad), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_grasp_create(NULL, &bad), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_grasp_create(&c, NULL), RTE_ERR_ARGUMENT);
    assert_string_equal(rte_grasp_shape_name(RTE_SHAPE_CIRCLE), "circle");
    assert_string_equal(rte_grasp_shape_name((rte_shape_class)99), "other");
}

/* A w x h BGR frame of the colour `table` with the square [x0, x1) x
 * [y0, y1) of `object`, as grey and half-size chroma (caller frees .buf). */
static void colour_scene(int32_t w, int32_t h, const uint8_t table[3], const uint8_t object[3],
                         int32_t x0, int32_t y0, int32_t x1, int32_t y1, rte_image_u8 *gray,
                         rte_image_u8 *cb, rte_image_u8 *cr)
{
    uint8_t *bgr = test_malloc((size_t)3 * w * h);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            const bool in = x >= x0 && x < x1 && y >= y0 && y < y1;
            memcpy(bgr + 3 * ((size_t)y * w + x), in ? object : table, 3);
        }
    rte_frame f;
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_BGR24, w, h, bgr, (size_t)3 * w * h), RTE_OK);
    *gray = unit_image_u8(w, h, 1, 0);
    *cb = unit_image_u8((w + 1) / 2, (h + 1) / 2, 2, 0);
    *cr = unit_image_u8((w + 1) / 2, (h + 1) / 2, 0, 0);
    assert_int_equal(rte_frame_to_gray(&f, gray), RTE_OK);
    assert_int_equal(rte_frame_chroma_half(&f, cb, cr), RTE_OK);
    test_free(bgr);
}

/* Background mode with colour: a green square as grey as the red table
 * (grey 107 on 117, below the contrast of 20) is found by its colour, at
 * its centre; not with grey alone or params.chroma off. A grey scene gives
 * the same objects with its (neutral) chroma as without. */
static void colour_contrast(void **state)
{
    (void)state;
    const int32_t w = 97, h = 73;
    rte_grasp_ctx *ctx = new_ctx(w, h, RTE_GRASP_BACKGROUND);
    rte_grasp_result r;
    rte_image_u8 gray, cb, cr;
    const uint8_t red[3] = {40, 90, 200}, green[3] = {60, 150, 40};
    colour_scene(w, h, red, green, 30, 20, 62, 48, &gray, &cb, &cr);
    assert_int_equal(gray.buf[0], 117);
    assert_int_equal(gray.buf[30 * gray.stride + 40], 107);
    assert_int_equal(rte_grasp_process(ctx, &gray, &r), RTE_OK);
    assert_int_equal(r.n_objects, 0);
    assert_int_equal(rte_grasp_process_chroma(ctx, &gray, &cb, &cr, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_true(fabs(r.objects[0].x_q8 / 256.0 - 45.5) <= 1.0);
    assert_true(fabs(r.objects[0].y_q8 / 256.0 - 33.5) <= 1.0);
    rte_grasp_params p;
    rte_grasp_get_params(ctx, &p);
    p.chroma = 0;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process_chroma(ctx, &gray, &cb, &cr, &r), RTE_OK);
    assert_int_equal(r.n_objects, 0);
    p.chroma = 2;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_ERR_ARGUMENT);

    /* the planes must come in pairs, at half the frame's size */
    rte_image_u8 big = unit_image_u8(cb.width + 1, cb.height, 0, 128);
    assert_int_equal(rte_grasp_process_chroma(ctx, &gray, &cb, NULL, &r), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_grasp_process_chroma(ctx, &gray, &big, &big, &r), RTE_ERR_SIZE);
    test_free(big.buf);
    test_free(gray.buf);
    test_free(cb.buf);
    test_free(cr.buf);

    const uint8_t light[3] = {170, 170, 170}, dark[3] = {60, 60, 60};
    colour_scene(w, h, light, dark, 30, 20, 62, 48, &gray, &cb, &cr);
    rte_grasp_result plain;
    assert_int_equal(rte_grasp_process(ctx, &gray, &plain), RTE_OK);
    assert_int_equal(plain.n_objects, 1);
    const rte_grasp_object first = plain.objects[0];
    p.chroma = 1;
    assert_int_equal(rte_grasp_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_grasp_process_chroma(ctx, &gray, &cb, &cr, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_memory_equal(&r.objects[0], &first, sizeof first);
    test_free(gray.buf);
    test_free(cb.buf);
    test_free(cr.buf);
    rte_grasp_destroy(ctx);
}

/* A dark blue box (x 50..79, y 40..69) on a beige table casts a neutral
 * shadow 12 px wide to its right and below (the table at 55%). With
 * colour the shadow is told from the box and the grasp is at the box's
 * centre; grey alone takes the shadow for part of the box. */
static void cast_shadow_leaves_the_grasp(void **state)
{
    (void)state;
    const int32_t w = 160, h = 120;
    uint8_t *bgr = test_malloc((size_t)3 * w * h);
    const uint8_t table[3] = {170, 178, 186}, box[3] = {120, 40, 20};
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            uint8_t *p = bgr + 3 * ((size_t)y * w + x);
            const bool in_box = x >= 50 && x < 80 && y >= 40 && y < 70;
            const bool in_shadow = x >= 56 && x < 92 && y >= 46 && y < 82;
            for (int k = 0; k < 3; k++)
                p[k] = in_box ? box[k] : in_shadow ? (uint8_t)(table[k] * 55 / 100) : table[k];
        }
    rte_frame f;
    assert_int_equal(rte_frame_packed(&f, RTE_PIXEL_BGR24, w, h, bgr, (size_t)3 * w * h), RTE_OK);
    rte_image_u8 gray = unit_image_u8(w, h, 1, 0), cb = unit_image_u8(w / 2, h / 2, 2, 0),
                 cr = unit_image_u8(w / 2, h / 2, 0, 0);
    assert_int_equal(rte_frame_to_gray(&f, &gray), RTE_OK);
    assert_int_equal(rte_frame_chroma_half(&f, &cb, &cr), RTE_OK);
    rte_grasp_ctx *ctx = new_ctx(w, h, RTE_GRASP_BACKGROUND);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process_chroma(ctx, &gray, &cb, &cr, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_true(fabs(r.objects[0].x_q8 / 256.0 - 64.5) <= 1.0);
    assert_true(fabs(r.objects[0].y_q8 / 256.0 - 54.5) <= 1.0);
    assert_int_equal(rte_grasp_process(ctx, &gray, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_true(r.objects[0].x_q8 / 256.0 > 66.5 && r.objects[0].y_q8 / 256.0 > 56.5);
    rte_grasp_destroy(ctx);
    test_free(bgr);
    test_free(gray.buf);
    test_free(cb.buf);
    test_free(cr.buf);
}

/* Too few contour slots: the result says so instead of failing. */
static void contour_bound(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(100, 20, 0, 220);
    for (int i = 0; i < 10; i++)
        img.buf[10 * img.stride + 5 + 9 * i] = 0; /* ten dots */
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    c.max_width = 100;
    c.max_height = 20;
    c.max_contours = 4;
    c.blur_ksize = 1;
    c.params.min_area = 0;
    rte_grasp_ctx *ctx = NULL;
    assert_int_equal(rte_grasp_create(&c, &ctx), RTE_OK);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.truncated, 1);
    assert_int_equal(r.dropped_contours, 6);
    assert_int_equal(r.n_objects, 4);
    rte_grasp_destroy(ctx);
    test_free(img.buf);
}

/* The context in caller memory: any alignment, exact size, too small. */
static void caller_memory(void **state)
{
    (void)state;
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    c.max_width = 200;
    c.max_height = 120;
    c.max_contours = 64;
    c.max_points = 4096;
    c.max_objects = 4;
    c.params.max_objects = 4;
    const size_t bytes = rte_grasp_memory_size(&c);
    assert_true(bytes > 3 * 200 * 120);
    uint8_t *mem = test_malloc(bytes + 1);
    rte_grasp_ctx *ctx = (rte_grasp_ctx *)mem;
    assert_int_equal(rte_grasp_init(&c, mem + 1, bytes - 1, &ctx), RTE_ERR_NO_MEMORY);
    assert_null(ctx);
    assert_int_equal(rte_grasp_init(&c, NULL, bytes, &ctx), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_grasp_init(&c, mem + 1, bytes, &ctx), RTE_OK); /* unaligned start */
    assert_true((uint8_t *)ctx >= mem + 1 && (uint8_t *)ctx < mem + bytes);

    rte_image_u8 img = unit_image_u8(200, 120, 5, 200);
    truth t;
    const rte_vertex a[4] = {{40, 30}, {99, 30}, {99, 59}, {40, 59}};
    fill_polygon(&img, a, 4, 40, &t);
    rte_grasp_result r;
    assert_int_equal(rte_grasp_process(ctx, &img, &r), RTE_OK);
    assert_int_equal(r.n_objects, 1);
    assert_true((const uint8_t *)r.objects > mem && (const uint8_t *)r.objects < mem + bytes + 1);
    assert_int_equal(r.objects[0].info.shape, RTE_SHAPE_RECTANGLE);
    rte_grasp_destroy(ctx); /* nothing to free: the memory is ours */
    test_free(img.buf);
    test_free(mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(synthetic_scenes),
        cmocka_unit_test(canny_close_scenes),
        cmocka_unit_test(touching_objects_merge),
        cmocka_unit_test(vignetted_scenes),
        cmocka_unit_test(touching_objects_split),
        cmocka_unit_test(cut_follows_the_grey_edge),
        cmocka_unit_test(border_and_area_filters),
        cmocka_unit_test(object_bound),
        cmocka_unit_test(sizes_and_errors),
        cmocka_unit_test(contour_bound),
        cmocka_unit_test(caller_memory),
        cmocka_unit_test(workspace),
        cmocka_unit_test(colour_contrast),
        cmocka_unit_test(cast_shadow_leaves_the_grasp),
        cmocka_unit_test(outlines_off_the_edges_are_dropped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
