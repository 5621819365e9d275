/* Hough segments: the 8-bit accumulator cells, and their widening to 16
 * bits when a count passes threshold + 126, against a copy of
 * src/algo/hough_segments.c built with 16-bit cells only
 * (HOUGH_CELL8_MAX_THRESHOLD=0, symbols renamed hough16_*): the same
 * segments, count and truncation flag, on maps made to wrap a cell and on
 * random maps. */
#include "unit.h"

#include <stdlib.h>
#include <string.h>

#include "rtedge/hough.h"

#define PI 3.14159265358979323846

rte_status hough16_segments(const rte_hough_config *cfg, const rte_image_u8 *edges,
                            const rte_hough_segments_params *params, rte_arena *arena,
                            rte_hough_segment *segments, int32_t max_segments, int32_t *count,
                            bool *truncated);
size_t hough16_segments_scratch_size(const rte_hough_config *cfg);

enum { MAX_SEGS = 512 };

static uint32_t next_rand(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* Runs both builds on the map; fails when they differ. Returns the count. */
static int32_t same_segments(const rte_image_u8 *e, const rte_hough_segments_params *p,
                             int32_t max_segments)
{
    rte_hough_config cfg;
    assert_int_equal(rte_hough_config_init(&cfg, e->width, e->height, 1.0, PI / 180, 0.0, PI),
                     RTE_OK);
    const size_t bytes = rte_hough_segments_scratch_size(&cfg);
    assert_int_equal(bytes, hough16_segments_scratch_size(&cfg));
    rte_arena a;
    rte_arena_init(&a, test_malloc(bytes), bytes);
    static rte_hough_segment s8[MAX_SEGS], s16[MAX_SEGS];
    int32_t n8 = -1, n16 = -1;
    bool t8 = true, t16 = true; /* both calls must clear them */
    assert_int_equal(rte_hough_segments(&cfg, e, p, &a, s8, max_segments, &n8, &t8), RTE_OK);
    assert_int_equal(hough16_segments(&cfg, e, p, &a, s16, max_segments, &n16, &t16), RTE_OK);
    assert_int_equal(a.used, 0);
    test_free(a.base);
    if (n8 != n16 || t8 != t16 || memcmp(s8, s16, (size_t)n8 * sizeof s8[0]) != 0)
        fail_msg("%dx%d threshold %d: 8-bit cells give %d segments (truncated %d), 16-bit %d "
                 "(truncated %d)",
                 (int)e->width, (int)e->height, (int)p->threshold, (int)n8, (int)t8, (int)n16,
                 (int)t16);
    return n8;
}

/* Rows of dots 3 px apart (gaps of 2 > max_gap 1): every walk from a dot
 * finds the dot alone, too short, so the votes of the row's cell (theta 90
 * degrees) stay and its count climbs to the number of dots, past
 * threshold + 127, which wraps an 8-bit cell. Solid segments drawn after
 * must still be found. */
static void test_wrapped_cells_widen(void **state)
{
    (void)state;
    static const int32_t thresholds[] = {1, 10, 50, 127, 128};
    for (size_t t = 0; t < sizeof thresholds / sizeof thresholds[0]; t++) {
        rte_image_u8 e = unit_image_u8(900, 300, 3, 0);
        for (int32_t row = 20; row < 300; row += 140)
            for (int32_t x = 0; x < 900; x += 3)
                e.buf[(size_t)row * e.stride + x] = 255; /* 300 dots > 128 + 127 */
        for (int32_t i = 0; i < 280; i++) {
            e.buf[(size_t)(10 + i) * e.stride + 100 + i / 4] = 255; /* steep */
            e.buf[(size_t)(10 + i) * e.stride + 700] = 255;         /* a column */
        }
        const rte_hough_segments_params p = {thresholds[t], 30, 1, 0};
        assert_true(same_segments(&e, &p, MAX_SEGS) >= 2); /* the solid ones */
        unit_assert_padding_u8(&e);
        test_free(e.buf);
    }
}

/* Random segments, dotted rows and columns and noise, random thresholds
 * 1..160 (8-bit and 16-bit starts), gaps and lengths; some runs truncate. */
static void test_random_maps(void **state)
{
    (void)state;
    uint32_t seed = 0x5EC8u;
    for (int k = 0; k < 40; k++) {
        const int32_t w = 40 + (int32_t)(next_rand(&seed) % 600),
                      h = 40 + (int32_t)(next_rand(&seed) % 400);
        rte_image_u8 e = unit_image_u8(w, h, 1 + (int32_t)(next_rand(&seed) % 9), 0);
        const int32_t nlines = (int32_t)(next_rand(&seed) % 30);
        for (int32_t l = 0; l < nlines; l++) {
            const int32_t x0 = (int32_t)(next_rand(&seed) % (uint32_t)w),
                          y0 = (int32_t)(next_rand(&seed) % (uint32_t)h);
            const int32_t x1 = (int32_t)(next_rand(&seed) % (uint32_t)w),
                          y1 = (int32_t)(next_rand(&seed) % (uint32_t)h);
            const int32_t steps = abs(x1 - x0) > abs(y1 - y0) ? abs(x1 - x0) : abs(y1 - y0);
            const int32_t every = 1 + (int32_t)(next_rand(&seed) % 4); /* dotted lines too */
            for (int32_t i = 0; i <= steps; i += every) {
                const int32_t x = steps ? x0 + (x1 - x0) * i / steps : x0,
                              y = steps ? y0 + (y1 - y0) * i / steps : y0;
                e.buf[(size_t)y * e.stride + x] = 255;
            }
        }
        const int32_t noise = (int32_t)(next_rand(&seed) % (uint32_t)(w * h / 8));
        for (int32_t i = 0; i < noise; i++)
            e.buf[(size_t)(next_rand(&seed) % (uint32_t)h) * e.stride +
                  next_rand(&seed) % (uint32_t)w] = 255;
        const rte_hough_segments_params p = {1 + (int32_t)(next_rand(&seed) % 160),
                                             (int32_t)(next_rand(&seed) % 60),
                                             (int32_t)(next_rand(&seed) % 12), next_rand(&seed)};
        same_segments(&e, &p, k % 5 == 0 ? 3 : MAX_SEGS);
        unit_assert_padding_u8(&e);
        test_free(e.buf);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrapped_cells_widen),
        cmocka_unit_test(test_random_maps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
