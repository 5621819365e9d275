/* Hough transforms: hand-checked geometry (a row, a column, a disc), bounds
 * and truncation on all-255 maps, sizes 1x1..67xN with stride > width,
 * standard lines against a plain one-accumulator vote (C path and
 * dispatched), argument errors, and that the arena is back at its mark
 * afterwards. */
#include "unit.h"

#include <math.h>
#include <stdlib.h>

#include "rtedge/hough.h"

#include "algo/hough_internal.h"

#define PI 3.14159265358979323846

static rte_hough_config config_of(int32_t w, int32_t h)
{
    rte_hough_config cfg;
    assert_int_equal(rte_hough_config_init(&cfg, w, h, 1.0, PI / 180, 0.0, PI), RTE_OK);
    return cfg;
}

static rte_arena arena_of(size_t bytes)
{
    rte_arena a;
    rte_arena_init(&a, test_malloc(bytes + 64), bytes + 64);
    return a;
}

static void test_config_errors(void **state)
{
    (void)state;
    rte_hough_config cfg;
    assert_int_equal(rte_hough_config_init(NULL, 8, 8, 1, 0.1, 0, 1), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&cfg, 8, 8, 0, 0.1, 0, 1), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&cfg, 8, 8, 1, 0, 0, 1), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&cfg, 8, 8, 1, 0.1, 1, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&cfg, 8, 8, 1, NAN, 0, 1), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&cfg, 8, 8, 1, PI / 4096, 0, PI), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&cfg, 0, 8, 1, 0.1, 0, 1), RTE_ERR_SIZE);
    assert_int_equal(rte_hough_config_init(&cfg, 8, 8, 1, PI / 180, 0, PI), RTE_OK);
    assert_int_equal(cfg.num_angles, 180);
}

/* A row of 36 edge pixels at y = 5: the strongest line is theta = 90
 * degrees, rho = 5, with 36 votes (a shorter one also fills the cell of 89
 * degrees, which then wins the tie by its smaller angle, as in OpenCV). A column at x = 7: theta 0, rho 7. */
static void test_lines_row_and_column(void **state)
{
    (void)state;
    rte_hough_config cfg = config_of(40, 40);
    rte_arena a = arena_of(rte_hough_lines_scratch_size(&cfg, 8));
    for (int col = 0; col < 2; col++) {
        rte_image_u8 e = unit_image_u8(40, 39, 5, 0);
        for (int i = 2; i < 38; i++)
            e.buf[col ? (size_t)i * e.stride + 7 : 5 * (size_t)e.stride + i] = 255;
        rte_hough_line l[8];
        int32_t n = -1;
        bool tr = true;
        assert_int_equal(rte_hough_lines(&cfg, &e, 10, &a, l, 8, &n, &tr), RTE_OK);
        assert_true(n >= 1);
        assert_false(tr);
        assert_int_equal(l[0].theta_bin, col ? 0 : 90);
        assert_int_equal(l[0].rho_bin, col ? 7 : 5);
        assert_int_equal(l[0].votes, 36);
        for (int32_t i = 1; i < n; i++)
            assert_true(l[i].votes <= l[i - 1].votes);
        assert_int_equal(a.used, 0);
        unit_assert_padding_u8(&e);
        test_free(e.buf);
    }
    test_free(a.base);
}

/* Standard lines the plain way: one 32-bit accumulator for every angle,
 * each point voting cell by cell, every local maximum above the threshold
 * collected and sorted by votes, then theta bin, then rho bin. */
static int compare_lines(const void *pa, const void *pb)
{
    const rte_hough_line *a = pa, *b = pb;
    if (a->votes != b->votes)
        return a->votes > b->votes ? -1 : 1;
    if (a->theta_bin != b->theta_bin)
        return a->theta_bin < b->theta_bin ? -1 : 1;
    return (a->rho_bin > b->rho_bin) - (a->rho_bin < b->rho_bin);
}

static int32_t plain_lines(const rte_hough_config *cfg, const rte_image_u8 *e, int32_t threshold,
                           rte_hough_line *out)
{
    const int32_t numrho = rte_hough_rho_bins(cfg, e->width, e->height), astep = numrho + 2;
    const int32_t bias = rte_hough_rho_bias(cfg, numrho), shift = cfg->trig_shift;
    int32_t *acc = test_calloc((size_t)(cfg->num_angles + 2) * astep, sizeof(int32_t));
    for (int32_t y = 0; y < e->height; y++)
        for (int32_t x = 0; x < e->width; x++)
            if (e->buf[(size_t)y * e->stride + x])
                for (int32_t n = 0; n < cfg->num_angles; n++) {
                    int32_t r = (x * cfg->rho_cos[n] + y * cfg->rho_sin[n] + bias) >> shift;
                    assert_true(r >= 0 && r < numrho);
                    acc[(n + 1) * astep + r + 1]++;
                }
    int32_t count = 0;
    for (int32_t n = 0; n < cfg->num_angles; n++)
        for (int32_t r = 0; r < numrho; r++) {
            const int32_t *a = acc + (n + 1) * astep + r + 1, v = *a;
            if (v > threshold && v > a[-1] && v >= a[1] && v > a[-astep] && v >= a[astep])
                out[count++] = (rte_hough_line){r - (numrho - 1) / 2, n, v};
        }
    qsort(out, (size_t)count, sizeof *out, compare_lines);
    test_free(acc);
    return count;
}

/* rte_hough_lines against plain_lines, forced C and dispatched, for every
 * output size up to all the lines. */
static void check_lines_plain(const rte_hough_config *cfg, const rte_image_u8 *e, int32_t threshold)
{
    const int32_t cells = cfg->num_angles * rte_hough_rho_bins(cfg, e->width, e->height);
    rte_hough_line *want = test_malloc((size_t)cells * sizeof *want);
    const int32_t total = plain_lines(cfg, e, threshold, want);
    const int32_t sizes[] = {0, 1, total / 2, total, total + 1};
    rte_hough_line *got = test_malloc((size_t)(total + 1) * sizeof *got);
    for (int forced = 0; forced < 2; forced++) {
        if (forced)
            assert_int_equal(setenv("RTE_FORCE_C", "1", 1), 0);
        for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
            const int32_t max = sizes[k];
            rte_arena a = arena_of(rte_hough_lines_scratch_size(cfg, max));
            int32_t n = -1;
            bool tr = false;
            assert_int_equal(rte_hough_lines(cfg, e, threshold, &a, got, max, &n, &tr), RTE_OK);
            assert_int_equal(n, max < total ? max : total);
            assert_int_equal(tr, max < total);
            for (int32_t i = 0; i < n; i++)
                if (got[i].rho_bin != want[i].rho_bin || got[i].theta_bin != want[i].theta_bin ||
                    got[i].votes != want[i].votes)
                    fail_msg("%dx%d line %d: (%d, %d, %d), plain (%d, %d, %d)", (int)e->width,
                             (int)e->height, (int)i, (int)got[i].rho_bin, (int)got[i].theta_bin,
                             (int)got[i].votes, (int)want[i].rho_bin, (int)want[i].theta_bin,
                             (int)want[i].votes);
            assert_int_equal(a.used, 0);
            test_free(a.base);
        }
        assert_int_equal(unsetenv("RTE_FORCE_C"), 0);
    }
    test_free(got);
    test_free(want);
}

/* Random maps of straight runs (rows, columns, diagonals: long runs of
 * points in one cell) and scattered pixels, on maps as large as the
 * configuration and smaller, several rho and theta resolutions and angle
 * ranges; then maps where one cell counts more than 65535 votes (rho 300,
 * all 255, so several blocks of points are summed into it). */
static void test_lines_match_plain_vote(void **state)
{
    (void)state;
    static const double rhos[] = {1.0, 0.5, 3.0}, thetas[] = {PI / 180, PI / 45, PI / 1000};
    uint32_t seed = 0x11E5u;
    for (int k = 0; k < 9; k++) {
        const int32_t w = 9 + (int32_t)(unit_rand(&seed) % 300),
                      h = 5 + (int32_t)(unit_rand(&seed) % 200);
        rte_hough_config cfg;
        assert_int_equal(rte_hough_config_init(&cfg, w + k % 2 * 7, h, rhos[k % 3], thetas[k / 3],
                                               k == 4 ? 0.5 : 0.0, PI),
                         RTE_OK);
        rte_image_u8 e = unit_image_u8(w, h, 3, 0);
        for (int run = 0; run < 12; run++) {
            int32_t x = (int32_t)(unit_rand(&seed) % (uint32_t)w),
                    y = (int32_t)(unit_rand(&seed) % (uint32_t)h);
            const int dir = (int)(unit_rand(&seed) % 4), len = (int)(unit_rand(&seed) % 150);
            for (int i = 0; i < len && x >= 0 && x < w && y < h; i++) {
                e.buf[(size_t)y * e.stride + x] = 255;
                x += dir == 0 ? 1 : dir == 2 ? -1 : dir == 3 ? 1 : 0;
                y += dir == 0 ? 0 : 1;
            }
        }
        for (int i = 0; i < w * h / 50; i++)
            e.buf[(unit_rand(&seed) % (uint32_t)h) * (size_t)e.stride +
                  unit_rand(&seed) % (uint32_t)w] = (uint8_t)(1 + unit_rand(&seed) % 255);
        check_lines_plain(&cfg, &e, k % 3 * 4);
        unit_assert_padding_u8(&e);
        test_free(e.buf);
    }
    for (int k = 0; k < 2; k++) {
        const int32_t w = 700 + k, h = 400;
        rte_hough_config cfg;
        assert_int_equal(rte_hough_config_init(&cfg, w, h, 300.0, PI / 8, 0.0, PI), RTE_OK);
        rte_image_u8 e = unit_image_u8(w, h, 1, 255);
        check_lines_plain(&cfg, &e, 1000);
        test_free(e.buf);
    }
}

/* All-255 maps of every small size: results within bounds, truncation set
 * when the output is too small, nothing for an all-0 map. */
static void test_sizes_and_truncation(void **state)
{
    (void)state;
    for (int32_t w = 1; w <= 67; w += 11) {
        for (int32_t h = 1; h <= 9; h += 4) {
            rte_hough_config cfg = config_of(w, h);
            rte_arena a = arena_of(rte_hough_lines_scratch_size(&cfg, 2) +
                                   rte_hough_segments_scratch_size(&cfg));
            for (int fill = 0; fill <= 255; fill += 255) {
                rte_image_u8 e = unit_image_u8(w, h, 3, (uint8_t)fill);
                rte_hough_line l[2];
                rte_hough_segment s[1];
                int32_t n = -1;
                bool tr = true;
                assert_int_equal(rte_hough_lines(&cfg, &e, 0, &a, l, 2, &n, &tr), RTE_OK);
                assert_true(n >= 0 && n <= 2);
                if (!fill)
                    assert_int_equal(n, 0);
                assert_int_equal(a.used, 0);
                rte_hough_segments_params p = {1, 0, 0, 0};
                assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 1, &n, &tr), RTE_OK);
                assert_int_equal(a.used, 0);
                assert_int_equal(n, fill ? 1 : 0);
                if (fill && (w > 1 && h > 2))
                    assert_true(tr); /* more than one segment in a filled map */
                for (int32_t i = 0; i < n; i++)
                    assert_true(s[i].x0 >= 0 && s[i].x0 < w && s[i].x1 >= 0 && s[i].x1 < w &&
                                s[i].y0 >= 0 && s[i].y0 < h && s[i].y1 >= 0 && s[i].y1 < h);
                unit_assert_padding_u8(&e);
                test_free(e.buf);
            }
            test_free(a.base);
        }
    }
}

/* A dashed diagonal with 3-pixel gaps: one segment end to end with
 * max_gap 4, none longer than min_length with max_gap 2. */
static void test_segments_gap_and_length(void **state)
{
    (void)state;
    rte_hough_config cfg = config_of(64, 64);
    rte_arena a = arena_of(rte_hough_segments_scratch_size(&cfg));
    rte_image_u8 e = unit_image_u8(64, 64, 7, 0);
    for (int i = 5; i <= 55; i++)
        if (i % 10 < 7)
            e.buf[(size_t)i * e.stride + i] = 255;
    rte_hough_segment s[8];
    int32_t n = -1;
    bool tr = true;
    rte_hough_segments_params p = {10, 30, 4, 0};
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 8, &n, &tr), RTE_OK);
    assert_int_equal(n, 1);
    assert_false(tr);
    int32_t lo = s[0].x0 < s[0].x1 ? 0 : 1;
    assert_true(abs((lo ? s[0].x1 : s[0].x0) - 5) <= 1 && abs((lo ? s[0].y1 : s[0].y0) - 5) <= 1);
    assert_true(abs((lo ? s[0].x0 : s[0].x1) - 55) <= 1 && abs((lo ? s[0].y0 : s[0].y1) - 55) <= 1);
    p.max_gap = 2;
    p.min_length = 12;
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 8, &n, &tr), RTE_OK);
    assert_int_equal(n, 0);
    assert_int_equal(a.used, 0);
    /* thresholds up to the most votes a cell can hold (64 * 3 here; cells
     * keep count + 129 or 32769 - threshold): a full 64-pixel column reaches 64,
     * and a threshold above the bound finds nothing without running */
    for (int32_t y = 0; y < 64; y++)
        memset(e.buf + (size_t)y * e.stride, 255, 64);
    p = (rte_hough_segments_params){64, 30, 4, 0};
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 8, &n, &tr), RTE_OK);
    assert_true(n >= 1);
    p.threshold = 192;
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 8, &n, &tr), RTE_OK);
    assert_int_equal(n, 0);
    p.threshold = 193;
    n = -1;
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 8, &n, &tr), RTE_OK);
    assert_int_equal(n, 0);
    assert_false(tr);
    assert_int_equal(a.used, 0);
    unit_assert_padding_u8(&e);
    test_free(e.buf);
    test_free(a.base);
}

/* The point order comes from params->seed alone: 0 is the default seed,
 * a seed gives the same segments on every call, and another seed visits
 * the points in another order (on clutter, other segments). */
static void test_segments_seed(void **state)
{
    (void)state;
    rte_hough_config cfg = config_of(96, 96);
    rte_arena a = arena_of(rte_hough_segments_scratch_size(&cfg));
    rte_image_u8 e = unit_image_u8(96, 96, 5, 0);
    uint32_t r = 7;
    for (int i = 0; i < 2500; i++) /* clutter: lines through it depend on the order */
        e.buf[(size_t)(unit_rand(&r) % 96) * e.stride + unit_rand(&r) % 96] = 255;
    for (int i = 4; i < 92; i++) {
        e.buf[(size_t)i * e.stride + i] = 255;
        e.buf[(size_t)40 * e.stride + i] = 255;
    }
    enum { CAP = 64 };
    rte_hough_segment s[4][CAP];
    int32_t n[4];
    bool tr;
    const uint32_t seeds[4] = {0, RTE_HOUGH_SEGMENTS_SEED, 0, 12345};
    for (int k = 0; k < 4; k++) {
        rte_hough_segments_params p = {10, 10, 1, seeds[k]};
        memset(s[k], 0, sizeof s[k]);
        assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s[k], CAP, &n[k], &tr), RTE_OK);
        assert_false(tr);
        assert_true(n[k] >= 2); /* the diagonal and the row at least */
    }
    assert_int_equal(n[0], n[1]);
    assert_memory_equal(s[0], s[1], sizeof s[0]);
    assert_int_equal(n[0], n[2]);
    assert_memory_equal(s[0], s[2], sizeof s[0]);
    assert_true(n[3] != n[0] || memcmp(s[3], s[0], sizeof s[0]) != 0);
    unit_assert_padding_u8(&e);
    test_free(e.buf);
    test_free(a.base);
}

/* Edge map and 3x3 Sobel derivatives (BORDER_REPLICATE) of a disc of
 * radius r at (cx, cy) on a w x h image, as cv::HoughCircles makes them. */
static void disc_inputs(int32_t w, int32_t h, int32_t cx, int32_t cy, int32_t r, rte_image_u8 *e,
                        rte_image_s16 *gx, rte_image_s16 *gy)
{
    static uint8_t img[64][64];
    assert_true(w <= 64 && h <= 64);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++)
            img[y][x] = (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r ? 200 : 40;
    *e = unit_image_u8(w, h, 3, 0);
    *gx = unit_image_s16(w, h, 2);
    *gy = unit_image_s16(w, h, 2);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            int32_t xm = x > 0 ? x - 1 : 0, xp = x < w - 1 ? x + 1 : x, ym = y > 0 ? y - 1 : 0,
                    yp = y < h - 1 ? y + 1 : y;
            int32_t sx = img[ym][xp] + 2 * img[y][xp] + img[yp][xp] - img[ym][xm] - 2 * img[y][xm] -
                         img[yp][xm];
            int32_t sy = img[yp][xm] + 2 * img[yp][x] + img[yp][xp] - img[ym][xm] - 2 * img[ym][x] -
                         img[ym][xp];
            gx->buf[(size_t)y * gx->stride + x] = (int16_t)sx;
            gy->buf[(size_t)y * gy->stride + x] = (int16_t)sy;
            /* pixels with a neighbour of the other side */
            int v = img[y][x];
            int border = img[ym][x] != v || img[yp][x] != v || img[y][xm] != v || img[y][xp] != v;
            e->buf[(size_t)y * e->stride + x] = border ? 255 : 0;
        }
}

/* Runs rte_hough_circles in an arena of its scratch size; checks the
 * status and that the arena is back at its mark. Returns the count. */
static int32_t circles_of(const rte_image_u8 *e, const rte_image_s16 *gx, const rte_image_s16 *gy,
                          const rte_hough_circles_params *p, rte_hough_circle *c, int32_t cap,
                          bool *tr)
{
    rte_arena a = arena_of(rte_hough_circles_scratch_size(e->width, e->height, p));
    int32_t n = -1;
    assert_int_equal(rte_hough_circles(e, gx, gy, p, &a, c, cap, &n, tr), RTE_OK);
    assert_int_equal(a.used, 0);
    test_free(a.base);
    return n;
}

/* A disc of radius 12 at (31, 27): one circle at the centre. */
static void test_circle_disc(void **state)
{
    (void)state;
    const int32_t w = 64, h = 56, cx = 31, cy = 27, r = 12;
    rte_image_u8 e;
    rte_image_s16 gx, gy;
    disc_inputs(w, h, cx, cy, r, &e, &gx, &gy);
    rte_hough_circles_params p = {256, 10, 8, 5, 30, 0, 0};
    rte_hough_circle c[4];
    bool tr = true;
    assert_int_equal(circles_of(&e, &gx, &gy, &p, c, 4, &tr), 1);
    assert_false(tr);
    assert_true(abs(c[0].x_q4 - cx * 16) <= 16 && abs(c[0].y_q4 - cy * 16) <= 16);
    assert_true(abs(c[0].r_q4 - r * 16) <= 16);
    /* no room: one qualifies, none written, truncated */
    assert_int_equal(circles_of(&e, &gx, &gy, &p, c, 0, &tr), 0);
    assert_true(tr);
    rte_arena a = arena_of(rte_hough_circles_scratch_size(w, h, &p));
    int32_t n = -1;
    /* argument errors */
    rte_hough_circles_params bad = p;
    bad.dp_q8 = 255;
    assert_int_equal(rte_hough_circles(&e, &gx, &gy, &bad, &a, c, 4, &n, &tr), RTE_ERR_ARGUMENT);
    bad = p;
    bad.min_dist = 0;
    assert_int_equal(rte_hough_circles(&e, &gx, &gy, &bad, &a, c, 4, &n, &tr), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_circles(&e, &gx, &gy, &p, &a, NULL, 4, &n, &tr), RTE_ERR_ARGUMENT);
    gy.width = w - 1;
    assert_int_equal(rte_hough_circles(&e, &gx, &gy, &p, &a, c, 4, &n, &tr), RTE_ERR_SIZE);
    gy.width = w;
    unit_assert_padding_u8(&e);
    test_free(e.buf);
    test_free(gx.buf);
    test_free(gy.buf);
    test_free(a.base);
}

/* Discs centred on column 0 and on row 0 (half outside the image): the
 * centre is found there too (the accumulator's first row and column are
 * searched like the others; they used to be skipped). */
static void test_circle_on_border(void **state)
{
    (void)state;
    const int32_t w = 48, h = 40, r = 10;
    const int32_t centres[2][2] = {{0, 20}, {24, 0}};
    for (int k = 0; k < 2; k++) {
        rte_image_u8 e;
        rte_image_s16 gx, gy;
        disc_inputs(w, h, centres[k][0], centres[k][1], r, &e, &gx, &gy);
        rte_hough_circles_params p = {256, 10, 6, 5, 20, 0, 0};
        rte_hough_circle c[4];
        bool tr = true;
        assert_true(circles_of(&e, &gx, &gy, &p, c, 4, &tr) >= 1);
        /* within 1.5 px: only half of the edge is there to fit */
        assert_true(abs(c[0].x_q4 - centres[k][0] * 16) <= 24 &&
                    abs(c[0].y_q4 - centres[k][1] * 16) <= 24);
        assert_true(abs(c[0].r_q4 - r * 16) <= 16);
        test_free(e.buf);
        test_free(gx.buf);
        test_free(gy.buf);
    }
}

/* Discs of radius 9 on a 96 x 64 image (edges and 3x3 Sobel derivatives
 * as disc_inputs makes them); the edges of the last `halves` discs are
 * kept on their upper half only, so their centres get fewer votes. */
static void discs_inputs(const int32_t (*c)[2], int32_t nd, int32_t halves, rte_image_u8 *e,
                         rte_image_s16 *gx, rte_image_s16 *gy)
{
    enum { W = 96, H = 64, R = 9 };
    static uint8_t img[H][W];
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            img[y][x] = 40;
            for (int32_t k = 0; k < nd; k++)
                if ((x - c[k][0]) * (x - c[k][0]) + (y - c[k][1]) * (y - c[k][1]) <= R * R)
                    img[y][x] = 200;
        }
    *e = unit_image_u8(W, H, 3, 0);
    *gx = unit_image_s16(W, H, 2);
    *gy = unit_image_s16(W, H, 2);
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            int32_t xm = x > 0 ? x - 1 : 0, xp = x < W - 1 ? x + 1 : x, ym = y > 0 ? y - 1 : 0,
                    yp = y < H - 1 ? y + 1 : y;
            gx->buf[(size_t)y * gx->stride + x] =
                (int16_t)(img[ym][xp] + 2 * img[y][xp] + img[yp][xp] - img[ym][xm] -
                          2 * img[y][xm] - img[yp][xm]);
            gy->buf[(size_t)y * gy->stride + x] =
                (int16_t)(img[yp][xm] + 2 * img[yp][x] + img[yp][xp] - img[ym][xm] -
                          2 * img[ym][x] - img[ym][xp]);
            int v = img[y][x];
            int border = img[ym][x] != v || img[yp][x] != v || img[y][xm] != v || img[y][xp] != v;
            for (int32_t k = nd - halves; k < nd; k++)
                if (abs(x - c[k][0]) <= R + 1 && abs(y - c[k][1]) <= R + 1 && y > c[k][1])
                    border = 0;
            e->buf[(size_t)y * e->stride + x] = border ? 255 : 0;
        }
}

/* Whether circle o's centre lies within 1.5 px (24 in q4) of disc c. */
static bool near_disc(const rte_hough_circle *o, const int32_t c[2])
{
    return abs(o->x_q4 - c[0] * 16) <= 24 && abs(o->y_q4 - c[1] * 16) <= 24;
}

/* The four discs of discs_inputs (the last `halves` on their upper half)
 * and their circles at the default budgets (r 5..20, votes 6), not
 * truncated; returns their number. */
static int32_t discs_circles(const int32_t (*c)[2], int32_t halves, rte_image_u8 *e,
                             rte_image_s16 *gx, rte_image_s16 *gy, rte_hough_circles_params *p,
                             rte_hough_circle *all)
{
    discs_inputs(c, 4, halves, e, gx, gy);
    const rte_hough_circles_params d = {256, 10, 6, 5, 20, 0, 0};
    *p = d;
    bool tr = true;
    const int32_t n = circles_of(e, gx, gy, p, all, 16, &tr);
    assert_false(tr);
    return n;
}

/* The vote budget: one under which every edge pixel votes gives the
 * default's circles (the four discs and more), not truncated; one for the
 * pixels of the upper half finds the two upper discs and nothing below,
 * truncated; one below a pixel's votes finds none. */
static void test_circle_vote_budget(void **state)
{
    (void)state;
    const int32_t c[4][2] = {{16, 16}, {44, 16}, {20, 46}, {72, 44}};
    rte_image_u8 e;
    rte_image_s16 gx, gy;
    rte_hough_circles_params p;
    rte_hough_circle all[16], some[16];
    const int32_t n = discs_circles(c, 0, &e, &gx, &gy, &p, all);
    bool tr = true;
    assert_true(n >= 4);
    int32_t upper = 0, every = 0; /* voting pixels: edges with a gradient */
    for (int32_t y = 0; y < e.height; y++)
        for (int32_t x = 0; x < e.width; x++) {
            const size_t i = (size_t)y * e.stride + x, j = (size_t)y * gx.stride + x;
            const int32_t votes = e.buf[i] && (gx.buf[j] || gy.buf[j]);
            every += votes;
            upper += votes && y < 32;
        }
    assert_true(upper > 0 && upper < every);
    p.max_votes = every * 2 * 16; /* r 5..20: 16 steps each way */
    assert_int_equal(circles_of(&e, &gx, &gy, &p, some, 16, &tr), n);
    assert_false(tr);
    assert_memory_equal(some, all, (size_t)n * sizeof all[0]);
    p.max_votes = upper * 2 * 16;
    const int32_t m = circles_of(&e, &gx, &gy, &p, some, 16, &tr);
    assert_true(tr);
    int found[2] = {0, 0};
    for (int32_t i = 0; i < m; i++) {
        assert_true(some[i].y_q4 < 32 * 16);
        for (int32_t k = 0; k < 2; k++)
            found[k] |= near_disc(&some[i], c[k]);
    }
    assert_true(found[0] && found[1]);
    p.max_votes = 31;
    assert_int_equal(circles_of(&e, &gx, &gy, &p, some, 16, &tr), 0);
    assert_true(tr);
    p.max_votes = -1;
    assert_int_equal(rte_hough_circles_scratch_size(96, 64, &p), 0);
    test_free(e.buf);
    test_free(gx.buf);
    test_free(gy.buf);
}

/* The budget of candidate centres: a map under it gives the same circles
 * as an unlimited one, not truncated; a budget of six keeps the centres of
 * the two whole discs (each has a few neighbouring accumulator maxima, the
 * strongest of all) and so the two strongest circles, drops the two half
 * discs and sets truncated. */
static void test_circle_budget(void **state)
{
    (void)state;
    const int32_t c[4][2] = {{16, 16}, {72, 44}, {44, 16}, {20, 46}};
    rte_image_u8 e;
    rte_image_s16 gx, gy;
    rte_hough_circles_params p;
    rte_hough_circle all[16], some[16];
    const int32_t n = discs_circles(c, 2, &e, &gx, &gy, &p, all);
    bool tr = true;
    assert_int_equal(n, 4);
    for (int32_t k = 0; k < 4; k++) /* whole discs first, by support */
        assert_true(near_disc(&all[k], c[k]));
    p.max_centres = 1 << 20; /* under the budget: unchanged */
    tr = true;
    assert_int_equal(circles_of(&e, &gx, &gy, &p, some, 16, &tr), n);
    assert_false(tr);
    assert_memory_equal(some, all, (size_t)n * sizeof all[0]);
    p.max_centres = 6;
    assert_int_equal(circles_of(&e, &gx, &gy, &p, some, 16, &tr), 2);
    assert_true(tr);
    assert_memory_equal(some, all, 2 * sizeof all[0]);
    p.max_centres = -1;
    assert_int_equal(rte_hough_circles_scratch_size(96, 64, &p), 0);
    unit_assert_padding_u8(&e);
    test_free(e.buf);
    test_free(gx.buf);
    test_free(gy.buf);
}

/* The worst case at the configured maximum size (1920x1080, the largest
 * frame the bench and the lane configurations use): an all-255 edge map runs
 * in an arena of exactly the *_scratch_size bytes (cmocka's guard blocks and
 * ASan catch a write past it) and reports truncation. Circles get
 * derivatives that point every pixel at the nearest node of a 128-pixel
 * grid, so a hundred centres qualify. */
static void test_maximum_size_all_255(void **state)
{
    (void)state;
    const int32_t w = 1920, h = 1080;
    rte_hough_config cfg = config_of(w, h);
    rte_image_u8 e = unit_image_u8(w, h, 1, 255);
    int32_t n = -1;
    bool tr = true;

    size_t bytes = rte_hough_lines_scratch_size(&cfg, 16);
    rte_arena a;
    rte_arena_init(&a, test_malloc(bytes), bytes);
    rte_hough_line l[16];
    assert_int_equal(rte_hough_lines(&cfg, &e, 100, &a, l, 16, &n, &tr), RTE_OK);
    assert_int_equal(n, 16);
    assert_true(tr);
    assert_int_equal(a.used, 0);
    test_free(a.base);

    bytes = rte_hough_segments_scratch_size(&cfg);
    rte_arena_init(&a, test_malloc(bytes), bytes);
    rte_hough_segment sg[4];
    rte_hough_segments_params sp = {50, 30, 10, 0};
    assert_int_equal(rte_hough_segments(&cfg, &e, &sp, &a, sg, 4, &n, &tr), RTE_OK);
    assert_int_equal(n, 4);
    assert_true(tr);
    assert_int_equal(a.used, 0);
    for (int32_t i = 0; i < n; i++)
        assert_true(sg[i].x0 >= 0 && sg[i].x0 < w && sg[i].x1 >= 0 && sg[i].x1 < w &&
                    sg[i].y0 >= 0 && sg[i].y0 < h && sg[i].y1 >= 0 && sg[i].y1 < h);
    test_free(a.base);

    rte_image_s16 gx = unit_image_s16(w, h, 1), gy = unit_image_s16(w, h, 1);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            int32_t vx = (x + 64) / 128 * 128 - x, vy = (y + 64) / 128 * 128 - y;
            gx.buf[(size_t)y * gx.stride + x] = (int16_t)(vx ? vx * 16 : 1);
            gy.buf[(size_t)y * gy.stride + x] = (int16_t)(vy * 16);
        }
    rte_hough_circles_params cp = {256, 20, 150, 35, 40, 0, 0};
    bytes = rte_hough_circles_scratch_size(w, h, &cp);
    rte_arena_init(&a, test_malloc(bytes), bytes);
    rte_hough_circle c[4];
    assert_int_equal(rte_hough_circles(&e, &gx, &gy, &cp, &a, c, 4, &n, &tr), RTE_OK);
    assert_int_equal(n, 4);
    assert_true(tr);
    assert_int_equal(a.used, 0);
    test_free(a.base);
    unit_assert_padding_u8(&e);
    test_free(gx.buf);
    test_free(gy.buf);
    test_free(e.buf);
}

static void test_argument_errors(void **state)
{
    (void)state;
    rte_hough_config cfg = config_of(16, 16);
    rte_arena a =
        arena_of(rte_hough_lines_scratch_size(&cfg, 4) + rte_hough_segments_scratch_size(&cfg));
    rte_image_u8 e = unit_image_u8(16, 16, 1, 0);
    rte_image_u8 big = unit_image_u8(17, 16, 1, 0);
    rte_hough_line l[4];
    rte_hough_segment s[4];
    int32_t n;
    bool tr;
    rte_hough_segments_params p = {5, 5, 2, 0};
    assert_int_equal(rte_hough_lines(NULL, &e, 1, &a, l, 4, &n, &tr), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_lines(&cfg, &e, -1, &a, l, 4, &n, &tr), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_lines(&cfg, &e, 1, &a, NULL, 4, &n, &tr), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_lines(&cfg, &big, 1, &a, l, 4, &n, &tr), RTE_ERR_TOO_LARGE);
    assert_int_equal(rte_hough_segments(&cfg, &big, &p, &a, s, 4, &n, &tr), RTE_ERR_TOO_LARGE);
    assert_int_equal(rte_hough_segments(&cfg, &e, NULL, &a, s, 4, &n, &tr), RTE_ERR_ARGUMENT);
    p.threshold = 0;
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 4, &n, &tr), RTE_ERR_ARGUMENT);
    p.threshold = 5;
    p.max_gap = -1;
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &a, s, 4, &n, &tr), RTE_ERR_ARGUMENT);
    /* configurations where a segment accumulator cell could count 32768
     * pixels or more (it holds count + 32769 - threshold in 16 bits) are
     * refused; rho 1 up to a side of 10922 and any rho on a small map
     * are fine */
    rte_hough_config wide;
    assert_int_equal(rte_hough_config_init(&wide, 1920, 1080, 20.0, PI / 180, 0.0, PI), RTE_OK);
    assert_int_equal(rte_hough_segments_scratch_size(&wide), 0);
    assert_int_equal(rte_hough_segments(&wide, &e, &p, &a, s, 4, &n, &tr), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_hough_config_init(&wide, 10923, 4, 1.0, PI / 180, 0.0, PI), RTE_OK);
    assert_int_equal(rte_hough_segments_scratch_size(&wide), 0);
    assert_int_equal(rte_hough_config_init(&wide, 10922, 4, 1.0, PI / 180, 0.0, PI), RTE_OK);
    assert_true(rte_hough_segments_scratch_size(&wide) > 0);
    assert_int_equal(rte_hough_config_init(&wide, 16, 16, 40.0, PI / 180, 0.0, PI), RTE_OK);
    assert_true(rte_hough_segments_scratch_size(&wide) > 0);
    /* an arena too small: no memory, arena untouched */
    rte_arena tiny = arena_of(64);
    p.max_gap = 2;
    assert_int_equal(rte_hough_segments(&cfg, &e, &p, &tiny, s, 4, &n, &tr), RTE_ERR_NO_MEMORY);
    assert_int_equal(rte_hough_lines(&cfg, &e, 1, &tiny, l, 4, &n, &tr), RTE_ERR_NO_MEMORY);
    assert_int_equal(tiny.used, 0);
    test_free(tiny.base);
    test_free(e.buf);
    test_free(big.buf);
    test_free(a.base);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_config_errors),        cmocka_unit_test(test_lines_row_and_column),
        cmocka_unit_test(test_sizes_and_truncation), cmocka_unit_test(test_segments_gap_and_length),
        cmocka_unit_test(test_segments_seed),        cmocka_unit_test(test_circle_disc),
        cmocka_unit_test(test_circle_on_border),     cmocka_unit_test(test_maximum_size_all_255),
        cmocka_unit_test(test_circle_budget),        cmocka_unit_test(test_circle_vote_budget),
        cmocka_unit_test(test_argument_errors),      cmocka_unit_test(test_lines_match_plain_vote),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
