/* Border following: hand-checked contours, hierarchy, bounds and errors. */
#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/contours.h"

#define MAXC 64
#define MAXP 4096

typedef struct fixture {
    uint8_t *arena_mem;
    rte_arena arena;
    rte_point points[MAXP];
    rte_contour contours[MAXC];
    rte_contours r;
} fixture;

static fixture *fx_new(int32_t w, int32_t h)
{
    fixture *f = test_calloc(1, sizeof *f);
    size_t n = rte_contours_scratch_size(w, h, MAXC);
    f->arena_mem = test_malloc(n);
    rte_arena_init(&f->arena, f->arena_mem, n);
    f->r.points = f->points;
    f->r.contours = f->contours;
    f->r.max_points = MAXP;
    f->r.max_contours = MAXC;
    return f;
}

static void fx_free(fixture *f)
{
    assert_int_equal(f->arena.used, 0); /* the arena is given back */
    test_free(f->arena_mem);
    test_free(f);
}

static void find_ok(fixture *f, const rte_image_u8 *img, rte_contour_mode mode,
                    rte_contour_method method)
{
    assert_int_equal(rte_contours_find(img, mode, method, &f->r, &f->arena), RTE_OK);
}

static void fill_rect(rte_image_u8 *img, int x0, int y0, int x1, int y1, uint8_t v)
{
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++)
            img->buf[y * img->stride + x] = v;
}

static void assert_points(const rte_contours *r, int i, const int *xy, int n)
{
    const rte_contour *c = &r->contours[i];
    assert_int_equal(c->count, n);
    for (int k = 0; k < n; k++) {
        assert_int_equal(r->points[c->offset + k].x, xy[2 * k]);
        assert_int_equal(r->points[c->offset + k].y, xy[2 * k + 1]);
    }
}

static void assert_hier(const rte_contours *r, int i, int next, int prev, int child, int parent)
{
    const int32_t *h = r->contours[i].hierarchy;
    assert_int_equal(h[0], next);
    assert_int_equal(h[1], prev);
    assert_int_equal(h[2], child);
    assert_int_equal(h[3], parent);
}

static void filled_rectangle_is_traced_downward_first(void **state)
{
    rte_image_u8 img = unit_image_u8(9, 8, 5, 0);
    fill_rect(&img, 2, 2, 6, 5, 200);
    fixture *f = fx_new(9, 8);
    find_ok(f, &img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_SIMPLE);
    assert_int_equal(f->r.n_contours, 1);
    static const int simple[] = {2, 2, 2, 5, 6, 5, 6, 2};
    assert_points(&f->r, 0, simple, 4);
    assert_hier(&f->r, 0, -1, -1, -1, -1);
    assert_int_equal(f->r.truncated, 0);

    find_ok(f, &img, RTE_CONTOURS_TREE, RTE_CONTOURS_APPROX_NONE);
    assert_int_equal(f->r.n_contours, 1);
    assert_int_equal(f->r.contours[0].count, 14); /* 2*(4+3) border pixels */
    assert_int_equal(f->r.points[1].x, 2);
    assert_int_equal(f->r.points[1].y, 3);
    /* the input is unchanged and its padding untouched */
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 9; x++)
            assert_int_equal(img.buf[y * img.stride + x],
                             (x >= 2 && x <= 6 && y >= 2 && y <= 5) ? 200 : 0);
    unit_assert_padding_u8(&img);
    fx_free(f);
    test_free(img.buf);
}

static void ring_with_island_builds_the_tree(void **state)
{
    /* outer square 0..8, hole 2..6, island at 4,4 */
    rte_image_u8 img = unit_image_u8(9, 9, 3, 0);
    fill_rect(&img, 0, 0, 8, 8, 1);
    fill_rect(&img, 2, 2, 6, 6, 0);
    fill_rect(&img, 4, 4, 4, 4, 9);
    fixture *f = fx_new(9, 9);
    find_ok(f, &img, RTE_CONTOURS_TREE, RTE_CONTOURS_APPROX_SIMPLE);
    assert_int_equal(f->r.n_contours, 3);
    static const int outer[] = {0, 0, 0, 8, 8, 8, 8, 0};
    /* the hole is traced from the pixel left of its first 0, clockwise on
     * screen, through the object pixels around it (checked with OpenCV) */
    static const int hole[] = {1, 2, 2, 1, 6, 1, 7, 2, 7, 6, 6, 7, 2, 7, 1, 6};
    static const int island[] = {4, 4};
    assert_points(&f->r, 0, outer, 4);
    assert_hier(&f->r, 0, -1, -1, 1, -1);
    assert_int_equal(f->r.contours[1].is_hole, 1);
    assert_points(&f->r, 1, hole, 8);
    assert_hier(&f->r, 1, -1, -1, 2, 0);
    assert_points(&f->r, 2, island, 1);
    assert_hier(&f->r, 2, -1, -1, -1, 1);

    /* CCOMP: the island is an outer border again, so a top-level contour */
    find_ok(f, &img, RTE_CONTOURS_CCOMP, RTE_CONTOURS_APPROX_SIMPLE);
    assert_int_equal(f->r.n_contours, 3);
    assert_points(&f->r, 0, island, 1); /* newest top-level first */
    assert_hier(&f->r, 0, 1, -1, -1, -1);
    assert_points(&f->r, 1, outer, 4);
    assert_hier(&f->r, 1, -1, 0, 2, -1);
    assert_hier(&f->r, 2, -1, -1, -1, 1);

    /* EXTERNAL: only the outer square */
    find_ok(f, &img, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_SIMPLE);
    assert_int_equal(f->r.n_contours, 1);
    assert_points(&f->r, 0, outer, 4);
    fx_free(f);
    test_free(img.buf);
}

static void list_puts_the_bottom_blob_first(void **state)
{
    rte_image_u8 img = unit_image_u8(5, 9, 0, 0);
    fill_rect(&img, 1, 0, 1, 0, 1);
    fill_rect(&img, 2, 4, 2, 4, 1);
    fill_rect(&img, 3, 8, 4, 8, 1);
    fixture *f = fx_new(5, 9);
    find_ok(f, &img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE);
    assert_int_equal(f->r.n_contours, 3);
    static const int bottom[] = {3, 8, 4, 8};
    static const int middle[] = {2, 4};
    static const int top[] = {1, 0};
    assert_points(&f->r, 0, bottom, 2);
    assert_points(&f->r, 1, middle, 1);
    assert_points(&f->r, 2, top, 1);
    assert_hier(&f->r, 0, 1, -1, -1, -1);
    assert_hier(&f->r, 1, 2, 0, -1, -1);
    assert_hier(&f->r, 2, -1, 1, -1, -1);
    fx_free(f);
    test_free(img.buf);
}

static void tiny_and_constant_images(void **state)
{
    for (int w = 1; w <= 67; w += 11) {
        for (int h = 1; h <= 3; h++) {
            for (int v = 0; v < 256; v += 255) {
                rte_image_u8 img = unit_image_u8(w, h, 2, (uint8_t)v);
                fixture *f = fx_new(w, h);
                find_ok(f, &img, RTE_CONTOURS_TREE, RTE_CONTOURS_APPROX_SIMPLE);
                assert_int_equal(f->r.n_contours, v ? 1 : 0);
                if (v) {
                    /* one box covering the whole image: corners only */
                    const rte_contour *c = &f->r.contours[0];
                    assert_int_equal(f->r.points[c->offset].x, 0);
                    assert_int_equal(f->r.points[c->offset].y, 0);
                    int expect = (w == 1 && h == 1) ? 1 : (w == 1 || h == 1) ? 2 : 4;
                    assert_int_equal(c->count, expect);
                }
                unit_assert_padding_u8(&img);
                fx_free(f);
                test_free(img.buf);
            }
        }
    }
}

/* A checkerboard of single pixels at 1280x720 with small maxima: stays in
 * bounds, reports the truncation and keeps a consistent prefix. */
static void checkerboard_truncates_within_bounds(void **state)
{
    const int w = 1280, h = 720;
    rte_image_u8 img = unit_image_u8(w, h, 1, 0);
    for (int y = 0; y < h; y++)
        for (int x = (y & 1); x < w; x += 2)
            img.buf[y * img.stride + x] = 255;
    size_t n = rte_contours_scratch_size(w, h, 100);
    uint8_t *mem = test_malloc(n);
    rte_arena arena;
    rte_arena_init(&arena, mem, n);
    enum { GUARD = 16 };
    for (int limit_points = 0; limit_points < 2; limit_points++) {
        int maxc = limit_points ? 100 : 37, maxp = limit_points ? 250 : 1000;
        rte_point *pts = test_malloc((maxp + GUARD) * sizeof *pts);
        rte_contour *cs = test_malloc((maxc + GUARD) * sizeof *cs);
        memset(pts, 0xEE, (maxp + GUARD) * sizeof *pts);
        memset(cs, 0xEE, (maxc + GUARD) * sizeof *cs);
        rte_contours r = {pts, cs, maxp, maxc, 0, 0, 0, 0, 0};
        assert_int_equal(
            rte_contours_find(&img, RTE_CONTOURS_TREE, RTE_CONTOURS_APPROX_NONE, &r, &arena),
            RTE_OK);
        assert_int_equal(r.truncated, 1);
        assert_true(r.n_contours <= maxc);
        assert_true(r.n_points <= maxp);
        /* 8-connected diagonals join a whole checkerboard into one blob with
         * many single-pixel holes. */
        assert_true(r.n_contours + r.dropped_contours > 1000);
        assert_true(r.dropped_points > 0);
        for (int i = 0; i < r.n_contours; i++) {
            assert_true(cs[i].offset >= 0 && cs[i].offset + cs[i].count <= r.n_points);
            for (int k = 0; k < 4; k++)
                assert_true(cs[i].hierarchy[k] >= -1 && cs[i].hierarchy[k] < r.n_contours);
        }
        const uint8_t *gp = (const uint8_t *)(pts + maxp), *gc = (const uint8_t *)(cs + maxc);
        for (size_t k = 0; k < GUARD * sizeof *pts; k++)
            assert_int_equal(gp[k], 0xEE);
        for (size_t k = 0; k < GUARD * sizeof *cs; k++)
            assert_int_equal(gc[k], 0xEE);
        test_free(pts);
        test_free(cs);
    }
    assert_int_equal(arena.used, 0);
    test_free(mem);
    test_free(img.buf);
}

static void bad_arguments_are_rejected(void **state)
{
    rte_image_u8 img = unit_image_u8(4, 4, 0, 1);
    fixture *f = fx_new(4, 4);
    assert_int_equal(
        rte_contours_find(NULL, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE, &f->r, &f->arena),
        RTE_ERR_ARGUMENT);
    assert_int_equal(
        rte_contours_find(&img, (rte_contour_mode)4, RTE_CONTOURS_APPROX_NONE, &f->r, &f->arena),
        RTE_ERR_ARGUMENT);
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_LIST, (rte_contour_method)0, &f->r, &f->arena),
        RTE_ERR_ARGUMENT);
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE, NULL, &f->arena),
        RTE_ERR_ARGUMENT);
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE, &f->r, NULL),
        RTE_ERR_ARGUMENT);
    rte_contours bad = f->r;
    bad.points = NULL;
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE, &bad, &f->arena),
        RTE_ERR_ARGUMENT);
    uint8_t small_mem[64];
    rte_arena small;
    rte_arena_init(&small, small_mem, sizeof small_mem);
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE, &f->r, &small),
        RTE_ERR_NO_MEMORY);
    assert_int_equal(small.used, 0);
    img.stride = 3;
    assert_int_equal(
        rte_contours_find(&img, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_NONE, &f->r, &f->arena),
        RTE_ERR_SIZE);
    assert_int_equal(rte_contours_scratch_size(0, 5, 1), 0);
    fx_free(f);
    test_free(img.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(filled_rectangle_is_traced_downward_first),
        cmocka_unit_test(ring_with_island_builds_the_tree),
        cmocka_unit_test(list_puts_the_bottom_blob_first),
        cmocka_unit_test(tiny_and_constant_images),
        cmocka_unit_test(checkerboard_truncates_within_bounds),
        cmocka_unit_test(bad_arguments_are_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
