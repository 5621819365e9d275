/* rte_split_u8: argument checks, synthetic touching and single objects
 * with known answers for each metric at its defaults, and the smarties
 * photo. A part is an 8-connected component of the output; rte_contours_find
 * (RETR_EXTERNAL) must see exactly as many outer contours. */
#include "unit.h"

#include <math.h>
#include <stdio.h>

#include "rtedge/color.h"
#include "rtedge/contours.h"
#include "rtedge/distance.h"
#include "rtedge/imageio.h"
#include "rtedge/split.h"
#include "rtedge/threshold.h"

#define W 200
#define H 160

typedef struct scene {
    rte_image_u8 bin, out;
    rte_image_u16 dist;
    int32_t *labels;
    uint8_t *arena_mem;
    rte_arena arena;
} scene;

static scene scene_new(int32_t w, int32_t h)
{
    scene s;
    s.bin = unit_image_u8(w, h, 3, 0);
    s.out = unit_image_u8(w, h, 5, 0);
    uint16_t *d = (uint16_t *)test_malloc((size_t)w * h * sizeof(uint16_t));
    s.dist = (rte_image_u16){w, h, w, d};
    s.labels = (int32_t *)test_malloc((size_t)w * h * sizeof(int32_t));
    size_t need = rte_split_scratch_size(w, h);
    size_t contours = rte_contours_scratch_size(w, h, 256);
    size_t bytes = need > contours ? need : contours;
    s.arena_mem = (uint8_t *)test_malloc(bytes);
    rte_arena_init(&s.arena, s.arena_mem, bytes);
    return s;
}

static void scene_free(scene *s)
{
    test_free(s->bin.buf);
    test_free(s->out.buf);
    test_free(s->dist.buf);
    test_free(s->labels);
    test_free(s->arena_mem);
}

static void disc(scene *s, double cx, double cy, double r)
{
    for (int32_t y = 0; y < s->bin.height; y++)
        for (int32_t x = 0; x < s->bin.width; x++)
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
                rte_u8_row(&s->bin, y)[x] = 255;
}

static void ellipse(scene *s, double cx, double cy, double a, double b, double angle)
{
    double c = cos(angle), sn = sin(angle);
    for (int32_t y = 0; y < s->bin.height; y++)
        for (int32_t x = 0; x < s->bin.width; x++) {
            double u = (x - cx) * c + (y - cy) * sn, v = -(x - cx) * sn + (y - cy) * c;
            if (u * u / (a * a) + v * v / (b * b) <= 1.0)
                rte_u8_row(&s->bin, y)[x] = 255;
        }
}

static void clear(scene *s, double cx, double cy, double r)
{
    for (int32_t y = 0; y < s->bin.height; y++)
        for (int32_t x = 0; x < s->bin.width; x++)
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
                rte_u8_row(&s->bin, y)[x] = 0;
}

static void box(scene *s, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    for (int32_t y = y0; y <= y1; y++)
        memset(rte_u8_row(&s->bin, y) + x0, 255, (size_t)(x1 - x0 + 1));
}

/* 8-connected components of s->out into s->labels (0: background);
 * returns their number. */
static int32_t label_parts(scene *s)
{
    const int32_t w = s->out.width, h = s->out.height;
    int32_t *stack = (int32_t *)test_malloc((size_t)w * h * sizeof(int32_t));
    memset(s->labels, 0, (size_t)w * h * sizeof(int32_t));
    int32_t n = 0;
    for (int32_t i = 0; i < w * h; i++) {
        if (!rte_u8_row(&s->out, i / w)[i % w] || s->labels[i])
            continue;
        int32_t top = 0;
        stack[top++] = i;
        s->labels[i] = ++n;
        while (top) {
            int32_t p = stack[--top], px = p % w, py = p / w;
            for (int32_t dy = -1; dy <= 1; dy++)
                for (int32_t dx = -1; dx <= 1; dx++) {
                    int32_t x = px + dx, y = py + dy;
                    if (x < 0 || y < 0 || x >= w || y >= h || s->labels[y * w + x] ||
                        !rte_u8_row(&s->out, y)[x])
                        continue;
                    s->labels[y * w + x] = n;
                    stack[top++] = y * w + x;
                }
        }
    }
    test_free(stack);
    return n;
}

static int32_t external_contours(scene *s)
{
    rte_point *pts = (rte_point *)test_malloc(sizeof(rte_point) * 20000);
    rte_contour contours[256];
    rte_contours out = {pts, contours, 20000, 256, 0, 0, false, 0, 0};
    assert_int_equal(rte_contours_find(&s->out, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_NONE,
                                       &out, &s->arena),
                     RTE_OK);
    assert_false(out.truncated);
    test_free(pts);
    return out.n_contours;
}

/* Distance (BORDER_ZERO) and split with the metric's defaults; returns
 * the number of parts after checking the result's own count, the
 * contours, that only object pixels were cut and the arena. */
static int32_t split(scene *s, rte_dist_metric metric, const rte_split_params *override)
{
    rte_split_params p;
    assert_int_equal(rte_split_params_default(&p, metric), RTE_OK);
    if (override)
        p = *override;
    assert_int_equal(rte_distance_transform_u8(&s->bin, &s->dist, metric, RTE_DIST_BORDER_ZERO),
                     RTE_OK);
    rte_split_result r;
    assert_int_equal(rte_split_u8(&s->bin, &s->dist, &s->out, &p, &s->arena, &r), RTE_OK);
    assert_int_equal(s->arena.used, 0);
    assert_true(s->arena.high_water <= rte_split_scratch_size(s->bin.width, s->bin.height));
    int32_t cut = 0;
    for (int32_t y = 0; y < s->bin.height; y++)
        for (int32_t x = 0; x < s->bin.width; x++) {
            uint8_t b = rte_u8_row(&s->bin, y)[x], o = rte_u8_row(&s->out, y)[x];
            assert_true(o == b || o == 0);
            cut += o != b;
        }
    assert_int_equal(cut, r.cut_pixels);
    unit_assert_padding_u8(&s->out);
    int32_t parts = label_parts(s);
    assert_int_equal(parts, r.parts);
    assert_int_equal(external_contours(s), parts);
    return parts;
}

static int32_t label_at(const scene *s, double x, double y)
{
    return s->labels[(int32_t)lround(y) * s->out.width + (int32_t)lround(x)];
}

static const rte_dist_metric metrics[] = {RTE_DIST_L1, RTE_DIST_C, RTE_DIST_CHAMFER34};

/* Two discs touching (overlap of 2 px) at several angles and radii: two
 * parts, one centre in each, every cut pixel within 2.5 px of the point of
 * contact along the line of centres and within the neck across it
 * (CHAMFER34), each part at least 80% of its disc (every metric). L1's and
 * C's bisectors are not lines (the L1 bisector of two diagonal points is a
 * quadrant, C's of two points in a row too), and their cuts turn a corner
 * or a chevron around the contact, up to 6 px into the smaller disc. L1 does not split the disc of radius 10 touching
 * one of 20 at 29 degrees: its dynamic is below L1's own ripple (see
 * docs/distance.md); CHAMFER34 and C do. */
static void pairs(void **state)
{
    static const double cases[][4] = {
        {20, 20, 0.0, 2}, {20, 20, 0.785, 2}, {20, 14, 0.0, 2},
        {20, 10, 0.5, 2}, {16, 16, 1.571, 1},
    };
    for (int m = 0; m < 3; m++)
        for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
            double r1 = cases[k][0], r2 = cases[k][1], a = cases[k][2], overlap = cases[k][3];
            double d = r1 + r2 - overlap;
            double x1 = 60, y1 = 70, x2 = x1 + d * cos(a), y2 = y1 + d * sin(a);
            if (metrics[m] == RTE_DIST_L1 && r2 == 10)
                continue;
            scene s = scene_new(W, H);
            disc(&s, x1, y1, r1);
            disc(&s, x2, y2, r2);
            int32_t parts = split(&s, metrics[m], NULL);
            if (parts != 2)
                fail_msg("metric %d, radii %g %g at %g rad: %d parts", (int)metrics[m], r1, r2, a,
                         parts);
            assert_true(label_at(&s, x1, y1) != label_at(&s, x2, y2));
            assert_true(label_at(&s, x1, y1) > 0 && label_at(&s, x2, y2) > 0);
            double contact = r1 - overlap / 2;
            /* half the chord where the discs' outlines cross */
            double xc = (d * d + r1 * r1 - r2 * r2) / (2 * d), neck = sqrt(r1 * r1 - xc * xc);
            for (int32_t y = 0; y < H; y++)
                for (int32_t x = 0; x < W; x++)
                    if (rte_u8_row(&s.bin, y)[x] && !rte_u8_row(&s.out, y)[x]) {
                        double t = ((x - x1) * cos(a) + (y - y1) * sin(a));
                        double across = fabs(-(x - x1) * sin(a) + (y - y1) * cos(a));
                        if (metrics[m] == RTE_DIST_CHAMFER34 &&
                            (fabs(t - contact) > 2.5 || across > neck + 1.5))
                            fail_msg("metric %d, radii %g %g at %g rad: cut pixel (%d, %d) %.1f px "
                                     "along the centres, the contact at %.1f",
                                     (int)metrics[m], r1, r2, a, x, y, t, contact);
                    }
            int32_t area1 = 0, area2 = 0, l1 = label_at(&s, x1, y1), l2 = label_at(&s, x2, y2);
            for (int32_t i = 0; i < W * H; i++) {
                area1 += s.labels[i] == l1;
                area2 += s.labels[i] == l2;
            }
            if (area1 < 0.8 * 3.14159 * r1 * r1 || area2 < 0.8 * 3.14159 * r2 * r2)
                fail_msg("metric %d, radii %g %g at %g rad: parts of %d and %d px", (int)metrics[m],
                         r1, r2, a, area1, area2);
            scene_free(&s);
        }
}

/* Three discs in a triangle, in a row, and of unequal radii. */
static void triples(void **state)
{
    static const double cases[][3][3] = {
        {{60, 60, 18}, {95, 60, 18}, {78, 91, 18}},
        {{50, 60, 18}, {85, 60, 18}, {120, 60, 18}},
        {{60, 60, 22}, {98, 64, 15}, {70, 96, 12}},
    };
    for (int m = 0; m < 3; m++)
        for (size_t k = 0; k < 3; k++) {
            scene s = scene_new(W, H);
            for (int i = 0; i < 3; i++)
                disc(&s, cases[k][i][0], cases[k][i][1], cases[k][i][2]);
            assert_int_equal(split(&s, metrics[m], NULL), 3);
            int32_t a = label_at(&s, cases[k][0][0], cases[k][0][1]);
            int32_t b = label_at(&s, cases[k][1][0], cases[k][1][1]);
            int32_t c = label_at(&s, cases[k][2][0], cases[k][2][1]);
            assert_true(a > 0 && b > 0 && c > 0 && a != b && b != c && a != c);
            scene_free(&s);
        }
}

/* Two boxes side by side, the second shifted down by half its side: a
 * neck of half the side. */
static void offset_boxes(void **state)
{
    for (int m = 0; m < 3; m++) {
        scene s = scene_new(W, H);
        box(&s, 20, 40, 60, 80);
        box(&s, 61, 60, 101, 100);
        assert_int_equal(split(&s, metrics[m], NULL), 2);
        assert_true(label_at(&s, 40, 60) != label_at(&s, 81, 80));
        scene_free(&s);
    }
}

/* Single objects stay whole: not one pixel is cut. */
static void assert_whole(scene *s, rte_dist_metric metric, const char *what)
{
    int32_t parts = split(s, metric, NULL);
    int32_t cut = 0;
    for (int32_t y = 0; y < s->bin.height; y++)
        for (int32_t x = 0; x < s->bin.width; x++)
            cut += rte_u8_row(&s->bin, y)[x] != rte_u8_row(&s->out, y)[x];
    if (parts != 1 || cut != 0)
        fail_msg("%s, metric %d: %d parts, %d pixels cut", what, (int)metric, parts, cut);
}

static void singles(void **state)
{
    for (int m = 0; m < 3; m++) {
        scene s = scene_new(W, H);
        disc(&s, 80, 80, 30);
        assert_whole(&s, metrics[m], "disc");
        scene_free(&s);

        s = scene_new(W, H);
        ellipse(&s, 100, 80, 60, 15, 0.0);
        assert_whole(&s, metrics[m], "ellipse 4:1");
        scene_free(&s);

        s = scene_new(W, H);
        ellipse(&s, 100, 80, 60, 15, 0.35);
        assert_whole(&s, metrics[m], "ellipse 4:1 at 20 degrees");
        scene_free(&s);

        s = scene_new(W, H);
        disc(&s, 80, 80, 40);
        clear(&s, 80, 80, 28);
        assert_whole(&s, metrics[m], "ring 40/28");
        scene_free(&s);

        s = scene_new(W, H);
        disc(&s, 80, 80, 50);
        clear(&s, 80, 80, 42);
        assert_whole(&s, metrics[m], "ring 50/42");
        scene_free(&s);
    }
}

/* A 200x20 rectangle (10:1) whose long edges move by -2..2 px from column
 * to column, and a disc of radius 30 +- 2 px: not split. */
static void noisy_outlines(void **state)
{
    uint32_t seed = 12345;
    for (int rep = 0; rep < 8; rep++)
        for (int m = 0; m < 3; m++) {
            scene s = scene_new(260, 100);
            for (int32_t x = 30; x < 230; x++) {
                int32_t top = 40 + (int32_t)(unit_rand(&seed) % 5) - 2;
                int32_t bottom = 59 + (int32_t)(unit_rand(&seed) % 5) - 2;
                for (int32_t y = top; y <= bottom; y++)
                    rte_u8_row(&s.bin, y)[x] = 255;
            }
            assert_whole(&s, metrics[m], "rectangle 10:1, noisy edges");
            scene_free(&s);

            s = scene_new(W, H);
            for (int32_t y = 0; y < H; y++)
                for (int32_t x = 0; x < W; x++) {
                    double a = atan2(y - 80.0, x - 80.0), r = hypot(x - 80.0, y - 80.0);
                    /* a radius that wanders by up to 2 px around the outline */
                    double bump = 2.0 * sin(7 * a + rep) * cos(3 * a - 2 * rep);
                    if (r <= 30 + bump)
                        rte_u8_row(&s.bin, y)[x] = 255;
                }
            assert_whole(&s, metrics[m], "disc, noisy outline");
            scene_free(&s);
        }
}

/* The ratio decides: discs of radius 20 overlapping by 8 px (a neck of
 * 12 px half-width, a dynamic of 40% of the radius) split at 30% and not
 * at 45% (CHAMFER34; in C a disc's peak is only r / sqrt(2), its inscribed
 * square's). */
static void ratio_decides(void **state)
{
    rte_split_params low = {6, 300}, high = {6, 450};
    scene s = scene_new(W, H);
    disc(&s, 60, 70, 20);
    disc(&s, 92, 70, 20);
    assert_int_equal(split(&s, RTE_DIST_CHAMFER34, &low), 2);
    assert_int_equal(split(&s, RTE_DIST_CHAMFER34, &high), 1);
    scene_free(&s);
}

/* The centres of the whole sweets in smarties.png, read by eye from the
 * photo (the middle of each sweet's visible disc); two more are cut by the
 * image's lower edge. */
static const int32_t sweets[][2] = {
    {377, 81},  {268, 117}, {386, 170}, {204, 211}, {289, 214}, {33, 228},
    {346, 237}, {99, 259},  {154, 271}, {219, 306}, {293, 320}, {133, 327},
};
#define N_SWEETS ((int32_t)(sizeof sweets / sizeof sweets[0]))

/* Otsu (objects darker than the table), the distance with BORDER_ZERO and
 * the split at each metric's defaults: every whole sweet is its own part
 * of at least 1000 pixels (the sweets are about 2100-2500), there are no
 * other such parts, and the two sweets cut by the border stay one part
 * each (14 parts of 300 pixels or more). */
static void smarties(void **state)
{
    const char *dir = getenv("RTE_FIXTURES_DIR");
    if (!dir)
        fail_msg("RTE_FIXTURES_DIR is not set (meson test sets it)");
    char path[512], msg[RTE_IO_MESSAGE_SIZE];
    snprintf(path, sizeof path, "%s/smarties.png", dir);
    rte_image_reader *reader = rte_image_reader_create(413, 356);
    assert_non_null(reader);
    scene s = scene_new(413, 356);
    rte_image_u8 gray = unit_image_u8(413, 356, 0, 0);
    uint8_t *bgr_buf = (uint8_t *)test_malloc((size_t)413 * 356 * 3);
    rte_image_u8c3 bgr = {413, 356, 413 * 3, bgr_buf};
    if (rte_image_read_bgr(reader, path, &bgr, msg, sizeof msg) != RTE_OK)
        fail_msg("%s", msg);
    assert_int_equal(rte_color_bgr_to_gray(&bgr, &gray), RTE_OK);
    test_free(bgr_buf);
    rte_threshold_params tp;
    assert_int_equal(rte_threshold_params_init(&tp, RTE_THRESH_BINARY_INV, 0, 255, true), RTE_OK);
    assert_int_equal(rte_threshold_u8(&gray, &s.bin, &tp, NULL), RTE_OK);

    for (int m = 0; m < 3; m++) {
        int32_t parts = split(&s, metrics[m], NULL);
        int32_t *area = (int32_t *)test_calloc((size_t)parts + 1, sizeof(int32_t));
        for (int32_t i = 0; i < 413 * 356; i++)
            area[s.labels[i]]++;
        int32_t big = 0, medium = 0;
        for (int32_t k = 1; k <= parts; k++) {
            big += area[k] >= 1000;
            medium += area[k] >= 300;
        }
        for (int32_t i = 0; i < N_SWEETS; i++) {
            int32_t li = label_at(&s, sweets[i][0], sweets[i][1]);
            assert_true(li > 0 && area[li] >= 1000);
            for (int32_t j = 0; j < i; j++)
                assert_int_not_equal(li, label_at(&s, sweets[j][0], sweets[j][1]));
        }
        print_message("smarties, metric %d: %d parts, %d of >= 1000 px, %d of >= 300 px\n",
                      (int)metrics[m], parts, big, medium);
        assert_int_equal(big, N_SWEETS);
        assert_int_equal(medium, N_SWEETS + 2);
        test_free(area);
    }
    test_free(gray.buf);
    scene_free(&s);
    rte_image_reader_destroy(reader);
}

static void arguments(void **state)
{
    scene s = scene_new(40, 30);
    disc(&s, 12, 15, 8);
    disc(&s, 26, 15, 8);
    rte_split_params p;
    assert_int_equal(rte_split_params_default(&p, RTE_DIST_CHAMFER34), RTE_OK);
    assert_int_equal(p.min_dynamic, 6);
    assert_int_equal(rte_split_params_default(&p, (rte_dist_metric)0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_split_params_default(NULL, RTE_DIST_L1), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_split_params_default(&p, RTE_DIST_L1), RTE_OK);
    assert_int_equal(rte_distance_transform_u8(&s.bin, &s.dist, RTE_DIST_L1, RTE_DIST_BORDER_ZERO),
                     RTE_OK);
    assert_int_equal(rte_split_scratch_size(0, 5), 0);
    assert_int_equal(rte_split_scratch_size(5, RTE_MAX_SIDE + 1), 0);

    rte_split_result r;
    assert_int_equal(rte_split_u8(NULL, &s.dist, &s.out, &p, &s.arena, &r), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_split_u8(&s.bin, NULL, &s.out, &p, &s.arena, &r), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, NULL, &p, &s.arena, &r), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, NULL, &s.arena, &r), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, &p, NULL, &r), RTE_ERR_ARGUMENT);
    rte_split_params bad = p;
    bad.min_dynamic = 0;
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, &bad, &s.arena, &r), RTE_ERR_ARGUMENT);
    bad = p;
    bad.min_ratio_permille = 1001;
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, &bad, &s.arena, &r), RTE_ERR_ARGUMENT);
    bad.min_ratio_permille = -1;
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, &bad, &s.arena, &r), RTE_ERR_ARGUMENT);
    rte_image_u16 dist = s.dist;
    dist.height = 29;
    assert_int_equal(rte_split_u8(&s.bin, &dist, &s.out, &p, &s.arena, &r), RTE_ERR_SIZE);
    dist = s.dist;
    dist.stride = 39;
    assert_int_equal(rte_split_u8(&s.bin, &dist, &s.out, &p, &s.arena, &r), RTE_ERR_SIZE);
    rte_image_u8 out = s.out;
    out.width = 41;
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &out, &p, &s.arena, &r), RTE_ERR_SIZE);

    /* an arena too small for the histogram: RTE_ERR_NO_MEMORY, dst
     * untouched, the arena back at its mark */
    size_t need = rte_split_scratch_size(40, 30);
    rte_arena small;
    rte_arena_init(&small, s.arena_mem, need - rte_arena_piece_size(65537 * sizeof(uint32_t)));
    memset(s.out.buf, 7, (size_t)s.out.stride * 30 - 5);
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, &p, &small, &r), RTE_ERR_NO_MEMORY);
    assert_int_equal(small.used, 0);
    assert_int_equal(rte_u8_row(&s.out, 15)[20], 7);

    /* exactly enough; then in place gives the same pixels */
    rte_arena exact;
    rte_arena_init(&exact, s.arena_mem, need);
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.out, &p, &exact, &r), RTE_OK);
    assert_int_equal(r.parts, 2);
    assert_true(r.cut_pixels > 0);
    assert_int_equal(rte_split_u8(&s.bin, &s.dist, &s.bin, &p, &exact, NULL), RTE_OK);
    for (int32_t y = 0; y < 30; y++)
        assert_memory_equal(rte_u8_row(&s.bin, y), rte_u8_row(&s.out, y), 40);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(arguments),     cmocka_unit_test(pairs),
        cmocka_unit_test(triples),       cmocka_unit_test(offset_boxes),
        cmocka_unit_test(singles),       cmocka_unit_test(noisy_outlines),
        cmocka_unit_test(ratio_decides), cmocka_unit_test(smarties),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
