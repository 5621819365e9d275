/* Hough circles' internals: the vote step's square root and division by a
 * reciprocal against plain integer arithmetic, for every gradient of a 3x3
 * Sobel and random larger ones; and step 3, the radius of a centre from
 * the table of bins by pixel offset (rte_circle_radius_offsets_init)
 * against the same step from the distances, on random edge pixels, radii,
 * windows and positions of the centre within its pixel: the same support
 * and radius, and the counters left at zero for the next centre. */
#include "unit.h"

#include <stdlib.h>

#include "algo/hough_circles_internal.h"
#include "algo/hough_circles_step.h"

enum { W = 181, H = 137 };

/* Random edge pixels (about one in `sparse`) listed in raster order with
 * their row blocks, as accumulate() in hough_circles.c lists them. */
static int32_t list_pixels(uint32_t *seed, uint32_t sparse, uint32_t *pts, int32_t *blk)
{
    const int32_t nblk = blocks_of(W);
    int32_t n = 0;
    for (int32_t y = 0; y < H; y++) {
        int32_t *rb = blk + (size_t)y * nblk;
        for (int32_t x = 0; x < W; x++) {
            if (x % BLOCK == 0)
                rb[x / BLOCK] = n;
            if (unit_rand(seed) % sparse == 0)
                pts[n++] = ((uint32_t)y << 16) | (uint32_t)x;
        }
        rb[nblk - 1] = n;
    }
    return n;
}

static void assert_all_zero(const int32_t *pairs, int32_t n)
{
    for (int32_t k = 0; k < n; k++)
        assert_int_equal(pairs[k], 0);
}

static void test_offsets_match_distances(void **state)
{
    (void)state;
    const int32_t nblk = blocks_of(W);
    uint32_t *pts = test_malloc((size_t)W * H * sizeof *pts);
    int32_t *blk = test_malloc((size_t)H * nblk * sizeof *blk);
    uint32_t seed = 0xC12C1Eu;
    int32_t tables = 0, found = 0;
    for (int32_t round = 0; round < 40; round++) {
        list_pixels(&seed, 2 + unit_rand(&seed) % 40, pts, blk);
        circle_geom g = {0, 0, 0, 0, 0, 0};
        g.min_r = (int32_t)(unit_rand(&seed) % 25);
        g.max_r = g.min_r + 2 + (int32_t)(unit_rand(&seed) % (round < 36 ? 60 : 140));
        g.nbins = (g.max_r - g.min_r) * 16 + 1;
        g.window = 16 + (int32_t)(unit_rand(&seed) % 48);
        radius_table rt = {test_malloc(((size_t)g.nbins + 1) * sizeof(int64_t)),
                           test_malloc(RADIUS_COARSE * sizeof(int32_t)),
                           test_malloc(radius_reach_rows(&g) * sizeof(int32_t)), 0, 0};
        rte_circle_radius_table_init(&rt, &g);
        const size_t entries = rte_circle_radius_offsets_size(&g);
        /* the largest radii here make more entries than the table takes */
        assert_true(entries == 0 || entries <= RADIUS_OFFSETS_MAX);
        assert_int_equal(entries == 0, g.max_r > 118);
        const int32_t npairs = (int32_t)radius_pairs(&g);
        int32_t *pairs = test_calloc((size_t)npairs, sizeof *pairs);
        radius_offsets o = {entries ? test_malloc(entries * sizeof(int16_t)) : NULL, 0, 0, 0, 0};
        for (int32_t pos = 0; pos < 4 && o.bin2; pos++) {
            rte_circle_radius_offsets_init(&o, &g, &rt, (int32_t)(unit_rand(&seed) % 16),
                                           (int32_t)(unit_rand(&seed) % 16));
            tables++;
            for (int32_t k = 0; k < 40; k++) {
                const int32_t cx = (int32_t)(unit_rand(&seed) % W) * 16 + o.fx,
                              cy = (int32_t)(unit_rand(&seed) % H) * 16 + o.fy;
                int32_t r_scan = -1, r_table = -1;
                const int32_t s_scan =
                    rte_circle_radius(pts, blk, nblk, H, &g, &rt, NULL, cx, cy, pairs, &r_scan);
                assert_all_zero(pairs, npairs);
                const int32_t s_table =
                    rte_circle_radius(pts, blk, nblk, H, &g, &rt, &o, cx, cy, pairs, &r_table);
                assert_all_zero(pairs, npairs);
                assert_int_equal(s_table, s_scan);
                assert_int_equal(r_table, r_scan);
                found += s_scan > 0;
            }
        }
        test_free(o.bin2);
        test_free(pairs);
        test_free(rt.sq);
        test_free(rt.coarse);
        test_free(rt.reach);
    }
    /* the cases are not vacuous: tables were made and centres had support */
    assert_true(tables >= 100);
    assert_true(found >= 2000);
    test_free(pts);
    test_free(blk);
}

/* round(v 2^28 / den), ties away from zero, by one signed division. */
static int32_t unit_step_plain(int32_t v, int64_t den)
{
    const int64_t a = (int64_t)(v < 0 ? -v : v) << 28, q = (a + den / 2) / den;
    return (int32_t)(v < 0 ? -q : q);
}

static void check_step(int32_t vx, int32_t vy, int32_t dp_q8)
{
    const uint64_t v = ((uint64_t)(vx * vx) + (uint64_t)(vy * vy)) << 20;
    const uint64_t mag = circle_isqrt(v);
    assert_true(mag == rte_isqrt64(v));
    int32_t sx, sy;
    circle_step(vx, vy, dp_q8, &sx, &sy);
    assert_int_equal(sx, unit_step_plain(vx, (int64_t)mag * dp_q8));
    assert_int_equal(sy, unit_step_plain(vy, (int64_t)mag * dp_q8));
}

/* Every squared magnitude of a 3x3 Sobel (|dx|, |dy| <= 1020), each with
 * the steps of a gradient of that magnitude's row; then random gradients
 * of the whole int16 range and random dp. */
static void test_vote_steps(void **state)
{
    (void)state;
    for (uint64_t s = 1; s <= 2 * 1020 * 1020; s++)
        assert_true(circle_isqrt(s << 20) == rte_isqrt64(s << 20));
    for (int32_t vx = -1020; vx <= 1020; vx += 7)
        for (int32_t vy = -1020; vy <= 1020; vy++)
            if (vx || vy)
                check_step(vx, vy, 256);
    /* exact quotients, where the multiply by the reciprocal falls one
     * short: 3 2^28 + den / 2 = 2 den for den = 2^29 */
    const uint64_t den = (uint64_t)1 << 29;
    assert_int_equal(circle_unit_step(3, den, UINT64_MAX / den), 2);
    assert_int_equal(circle_unit_step(-3, den, UINT64_MAX / den), -2);
    for (uint64_t d = (uint64_t)1 << 13; d < ((uint64_t)1 << 46); d = d * 3 + 1)
        for (int32_t v = -32768; v < 32768; v += 97)
            assert_int_equal(circle_unit_step(v, d, UINT64_MAX / d),
                             unit_step_plain(v, (int64_t)d));
    uint32_t seed = 0x57E95u;
    for (int32_t k = 0; k < 1000000; k++) {
        const int32_t vx = (int32_t)(unit_rand(&seed) % 65536) - 32768,
                      vy = (int32_t)(unit_rand(&seed) % 65536) - 32768;
        if (vx || vy)
            check_step(vx, vy, 256 + (int32_t)(unit_rand(&seed) % (256 * 63 + 1)));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vote_steps),
        cmocka_unit_test(test_offsets_match_distances),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
