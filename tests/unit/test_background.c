/* The table's brightness and the two-sided threshold against it, on
 * synthetic tables whose light and objects are known: a vignette falling
 * off 90 grey levels to the corners, objects lighter and darker than the
 * table, one wider than the estimate's window, a shadow, a two-tone object,
 * weak and strong regions, and the run table's bound. */
#include "unit.h"

#include <stdlib.h>

#include "rtedge/background.h"

#define W 320
#define H 240

/* 190 in the middle, 100 in the corners (quadratic in the distance). */
static int32_t vignette(int32_t x, int32_t y)
{
    const int64_t dx = 2 * x + 1 - W, dy = 2 * y + 1 - H;
    return 190 - (int32_t)(90 * (dx * dx + dy * dy) / ((int64_t)W * W + (int64_t)H * H));
}

static uint8_t *at(rte_image_u8 *img, int32_t x, int32_t y)
{
    return &img->buf[(size_t)y * img->stride + x];
}

/* Which object a pixel belongs to (0: table). */
static int object_at(int32_t x, int32_t y)
{
    const int32_t dx = x - 70, dy = y - 60;
    if (dx * dx + dy * dy <= 25 * 25)
        return 1; /* a lighter disc */
    if (x >= 200 && x < 240 && y >= 40 && y < 70)
        return 2; /* a darker box */
    if (x >= 110 && x < 280 && y >= 120 && y < 215)
        return 3; /* a darker tray, wider than the 9 x 9 cell window */
    if (x >= 20 && x < 60 && y >= 150 && y < 200)
        return 4; /* a lighter box over the dark corner */
    return 0;
}

static const int object_delta[5] = {0, 50, -60, -45, 40};

/* The vignetted table with the objects, a 3 x 3 box blur's worth of soft
 * edges left out (the objects are sharp), and +-3 of noise. */
static rte_image_u8 table_scene(void)
{
    rte_image_u8 img = unit_image_u8(W, H, 7, 0);
    uint32_t rng = 12345;
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            int32_t v = vignette(x, y) + object_delta[object_at(x, y)];
            v += (int32_t)(unit_rand(&rng) % 7) - 3;
            *at(&img, x, y) = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
        }
    return img;
}

static rte_arena new_arena(void)
{
    size_t n = rte_background_scratch_size(W, H, RTE_BACKGROUND_MIN_CELL);
    const size_t m = rte_background_threshold_scratch_size(W, H);
    n = n > m ? n : m;
    rte_arena a;
    rte_arena_init(&a, test_malloc(n + RTE_ARENA_ALIGN), n + RTE_ARENA_ALIGN);
    return a;
}

/* The arena's memory from its first RTE_ARENA_ALIGN-aligned byte: the
 * scratch sizes are for aligned memory. */
static uint8_t *aligned(const rte_arena *a)
{
    return (uint8_t *)(((uintptr_t)a->base + RTE_ARENA_ALIGN - 1) &
                       ~(uintptr_t)(RTE_ARENA_ALIGN - 1));
}

static void estimate_follows_the_vignette_under_objects(void **state)
{
    (void)state;
    rte_image_u8 img = table_scene(), bg = unit_image_u8(W, H, 3, 0);
    rte_arena arena = new_arena();
    rte_background_params p;
    rte_background_params_default(&p, W);
    assert_int_equal(p.cell, 8);
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_OK);
    assert_int_equal(arena.used, 0);
    unit_assert_padding_u8(&bg);
    /* the estimate is the table's light within 6 grey levels on the table
     * (the vignette's curvature over a window) and within 20 under the
     * objects (under the tray, from the table cells around it) */
    int32_t worst[2] = {0, 0};
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            int32_t e = (int32_t)*at(&bg, x, y) - vignette(x, y);
            e = e < 0 ? -e : e;
            int32_t *wo = &worst[object_at(x, y) != 0];
            *wo = e > *wo ? e : *wo;
        }
    print_message("background: worst error %d grey levels on the table, %d under objects\n",
                  worst[0], worst[1]);
    assert_true(worst[0] <= 6);
    assert_true(worst[1] <= 20);

    /* a flat table is its own estimate, exactly */
    rte_image_u8 flat = unit_image_u8(W, H, 1, 137);
    assert_int_equal(rte_background_estimate_u8(&flat, &bg, &p, &arena), RTE_OK);
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++)
            assert_int_equal(*at(&bg, x, y), 137);
    test_free(flat.buf);
    test_free(img.buf);
    test_free(bg.buf);
    test_free(arena.base);
}

/* The estimate as include/rtedge/background.h and background.c define it,
 * written plainly: each cell's lower median of its samples (every other
 * row and column from 8 px cells) by sorting; the table region by a flood
 * fill; each cell's plane through the table cells of its window from sums
 * taken cell by cell, else the mean within 1, 2, 4, ... times the radius;
 * then bilinear between cell centres (Q4 values, Q8 weights, rounded). */
static int compare_u8(const void *a, const void *b)
{
    return (int)*(const uint8_t *)a - (int)*(const uint8_t *)b;
}

static void interpolation_ref(int32_t p, int32_t cell, int32_t n, int32_t *i, int32_t *frac)
{
    const int32_t num = 2 * p + 1 - cell;
    *i = num <= 0 ? 0 : num / (2 * cell);
    *frac = num <= 0 ? 0 : ((num - *i * 2 * cell) << 8) / (2 * cell);
    if (*i >= n - 1) {
        *i = n - 1;
        *frac = 0;
    }
}

static void estimate_ref(const rte_image_u8 *src, const rte_background_params *p, uint8_t *out)
{
    const int32_t w = src->width, h = src->height, c = p->cell, r0 = p->radius;
    const int32_t gw = (w + c - 1) / c, gh = (h + c - 1) / c, n = gw * gh;
    const int32_t step = c >= 8 ? 2 : 1;
    uint8_t *med = test_malloc((size_t)n), *samples = test_malloc((size_t)c * c);
    int32_t *region = test_malloc((size_t)n * sizeof *region);
    int32_t *stack = test_malloc((size_t)n * sizeof *stack);
    int32_t *grid = test_malloc((size_t)n * sizeof *grid);
    for (int32_t k = 0; k < n; k++) {
        const int32_t i = k % gw, j = k / gw;
        int32_t m = 0;
        for (int32_t y = j * c; y < (j + 1) * c && y < h; y += step)
            for (int32_t x = i * c; x < (i + 1) * c && x < w; x += step)
                samples[m++] = *at((rte_image_u8 *)src, x, y);
        qsort(samples, (size_t)m, 1, compare_u8);
        med[k] = samples[(m + 1) / 2 - 1];
        region[k] = -1;
    }
    int32_t best = -1, best_edge = -1, best_size = 0;
    for (int32_t seed = 0; seed < n; seed++) {
        if (region[seed] >= 0)
            continue;
        int32_t top = 0, size = 0, edge = 0;
        region[seed] = seed;
        stack[top++] = seed;
        while (top > 0) {
            const int32_t k = stack[--top], i = k % gw, j = k / gw;
            size++;
            edge += i == 0 || j == 0 || i == gw - 1 || j == gh - 1;
            const int32_t nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
            for (int e = 0; e < 4; e++) {
                const int32_t ni = nb[e][0], nj = nb[e][1], m = nj * gw + ni;
                if (ni >= 0 && nj >= 0 && ni < gw && nj < gh && region[m] < 0 &&
                    abs((int32_t)med[m] - med[k]) <= p->step) {
                    region[m] = seed;
                    stack[top++] = m;
                }
            }
        }
        if (edge > best_edge || (edge == best_edge && size > best_size)) {
            best = seed;
            best_edge = edge;
            best_size = size;
        }
    }
    for (int32_t k = 0; k < n; k++) {
        const int32_t i = k % gw, j = k / gw;
        int64_t cnt = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0, sz = 0, suz = 0, svz = 0;
        int32_t lo = 255, hi = 0;
        for (int32_t jj = j - r0; jj <= j + r0; jj++)
            for (int32_t ii = i - r0; ii <= i + r0; ii++) {
                if (ii < 0 || jj < 0 || ii >= gw || jj >= gh || region[jj * gw + ii] != best)
                    continue;
                const int64_t u = ii - i, v = jj - j, z = med[jj * gw + ii];
                cnt++;
                su += u;
                sv += v;
                suu += u * u;
                suv += u * v;
                svv += v * v;
                sz += z;
                suz += u * z;
                svz += v * z;
                lo = z < lo ? (int32_t)z : lo;
                hi = z > hi ? (int32_t)z : hi;
            }
        const int64_t m11 = suu * svv - suv * suv, m12 = su * svv - suv * sv,
                      m13 = su * suv - suu * sv, det = cnt * m11 - su * m12 + sv * m13;
        if (cnt >= 6 && det > 0) {
            const int64_t num = (sz * m11 - suz * m12 + svz * m13) * 16;
            int64_t a = (num + (num >= 0 ? det / 2 : -det / 2)) / det;
            a = a < (lo - p->tolerance) * 16 ? (lo - p->tolerance) * 16 : a;
            a = a > (hi + p->tolerance) * 16 ? (hi + p->tolerance) * 16 : a;
            grid[k] = (int32_t)(a < 0 ? 0 : a > 255 * 16 ? 255 * 16 : a);
            continue;
        }
        int64_t sum = 0, m = 0;
        for (int32_t r = r0; m == 0; r *= 2)
            for (int32_t jj = j - r; jj <= j + r; jj++)
                for (int32_t ii = i - r; ii <= i + r; ii++)
                    if (ii >= 0 && jj >= 0 && ii < gw && jj < gh && region[jj * gw + ii] == best) {
                        sum += med[jj * gw + ii];
                        m++;
                    }
        grid[k] = (int32_t)((sum * 16 + m / 2) / m);
    }
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            int32_t i, fx, j, fy;
            interpolation_ref(x, c, gw, &i, &fx);
            interpolation_ref(y, c, gh, &j, &fy);
            const int32_t i1 = i + 1 < gw ? i + 1 : i, j1 = j + 1 < gh ? j + 1 : j;
            const int64_t v = (int64_t)grid[j * gw + i] * (256 - fx) * (256 - fy) +
                              (int64_t)grid[j * gw + i1] * fx * (256 - fy) +
                              (int64_t)grid[j1 * gw + i] * (256 - fx) * fy +
                              (int64_t)grid[j1 * gw + i1] * fx * fy + (1 << 19);
            out[(size_t)y * w + x] = (uint8_t)(v >> 20);
        }
    test_free(med);
    test_free(samples);
    test_free(region);
    test_free(stack);
    test_free(grid);
}

/* Random tables (tilted light, blobs lighter and darker, noise, some with a
 * flat table or scattered levels) of random sizes and parameters: the
 * estimate equals the plain one byte for byte. */
static void estimate_matches_the_plain_definition(void **state)
{
    (void)state;
    rte_arena arena = new_arena();
    uint32_t rng = 2024;
    uint8_t *ref = test_malloc((size_t)W * H);
    for (int t = 0; t < 60; t++) {
        const int32_t w = 9 + (int32_t)(unit_rand(&rng) % (W - 8));
        const int32_t h = 9 + (int32_t)(unit_rand(&rng) % (H - 8));
        rte_background_params p = {.cell = 2 + (int32_t)(unit_rand(&rng) % 39),
                                   .radius = 1 + (int32_t)(unit_rand(&rng) % 8),
                                   .tolerance = (int32_t)(unit_rand(&rng) % 30),
                                   .step = (int32_t)(unit_rand(&rng) % 16)};
        rte_image_u8 img = unit_image_u8(w, h, (int32_t)(unit_rand(&rng) % 9), 0),
                     bg = unit_image_u8(w, h, 5, 0);
        const int32_t gx = (int32_t)(unit_rand(&rng) % 9) - 4,
                      gy = (int32_t)(unit_rand(&rng) % 9) - 4;
        const int32_t noise = 1 + (int32_t)(unit_rand(&rng) % (t % 5 == 4 ? 200 : 8));
        const int32_t bx = (int32_t)(unit_rand(&rng) % w), by = (int32_t)(unit_rand(&rng) % h);
        const int32_t br = 3 + (int32_t)(unit_rand(&rng) % 60);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                int32_t v = 120 + gx * x / 8 + gy * y / 8 + (int32_t)(unit_rand(&rng) % noise);
                if ((x - bx) * (x - bx) + (y - by) * (y - by) < br * br)
                    v += t % 2 ? 70 : -70;
                if (x % 97 < 20 && y % 61 < 15)
                    v -= 50;
                *at(&img, x, y) = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
            }
        assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_OK);
        estimate_ref(&img, &p, ref);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++)
                if (*at(&bg, x, y) != ref[(size_t)y * w + x])
                    fail_msg("case %d (%dx%d, cell %d, radius %d, tolerance %d, step %d): (%d, %d) "
                             "is %d, the definition gives %d",
                             t, w, h, p.cell, p.radius, p.tolerance, p.step, x, y, *at(&bg, x, y),
                             ref[(size_t)y * w + x]);
        unit_assert_padding_u8(&bg);
        test_free(img.buf);
        test_free(bg.buf);
    }
    test_free(ref);
    test_free(arena.base);
}

static void threshold_finds_lighter_and_darker_objects(void **state)
{
    (void)state;
    rte_image_u8 img = table_scene(), bg = unit_image_u8(W, H, 0, 0);
    rte_image_u8 bin = unit_image_u8(W, H, 5, 0);
    rte_arena arena = new_arena();
    rte_background_params p;
    rte_background_params_default(&p, W);
    rte_background_threshold_params tp;
    rte_background_threshold_params_default(&tp, W);
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_OK);
    rte_background_threshold_result r;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, &r), RTE_OK);
    assert_int_equal(arena.used, 0);
    unit_assert_padding_u8(&bin);
    assert_true(r.high >= tp.min_contrast && r.high < 40);
    assert_int_equal(r.low, r.high * 2 / 3);
    assert_int_equal(r.dropped_pixels, 0);
    /* every object pixel found, no table pixel taken */
    int32_t wrong[5] = {0}, table_wrong = 0;
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            const int o = object_at(x, y);
            const bool is = *at(&bin, x, y) == 255;
            assert_true(*at(&bin, x, y) == 0 || is);
            if (o && !is)
                wrong[o]++;
            table_wrong += !o && is;
        }
    for (int o = 1; o <= 4; o++)
        assert_int_equal(wrong[o], 0);
    assert_int_equal(table_wrong, 0);

    /* one side only */
    tp.dark = false;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, NULL), RTE_OK);
    assert_int_equal(*at(&bin, 70, 60), 255);
    assert_int_equal(*at(&bin, 220, 55), 0);
    assert_int_equal(*at(&bin, 200, 170), 0);
    tp.dark = true;
    tp.bright = false;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, NULL), RTE_OK);
    assert_int_equal(*at(&bin, 70, 60), 0);
    assert_int_equal(*at(&bin, 220, 55), 255);
    assert_int_equal(*at(&bin, 200, 170), 255);
    test_free(img.buf);
    test_free(bg.buf);
    test_free(bin.buf);
    test_free(arena.base);
}

/* A flat table (150) with what `paint` draws; returns the binary image. */
static rte_image_u8 threshold_of(void (*paint)(rte_image_u8 *), bool drop_shadows,
                                 rte_background_threshold_result *r)
{
    rte_image_u8 img = unit_image_u8(W, H, 0, 150), bg = unit_image_u8(W, H, 0, 150);
    rte_image_u8 bin = unit_image_u8(W, H, 0, 0);
    paint(&img);
    rte_arena arena = new_arena();
    rte_background_threshold_params tp;
    rte_background_threshold_params_default(&tp, W);
    tp.high = 20; /* the shadow's 30 is strong too */
    tp.drop_shadows = drop_shadows;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, r), RTE_OK);
    test_free(img.buf);
    test_free(bg.buf);
    test_free(arena.base);
    return bin;
}

/* A lit ball (+80) with its shadow (-30) beside it, 2 px of table between. */
static void ball_and_shadow(rte_image_u8 *img)
{
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            const int32_t bx = x - 100, by = y - 100, sx = x - 130, sy = y - 115;
            if (bx * bx + by * by <= 40 * 40)
                *at(img, x, y) = 230;
            else if (bx * bx + by * by > 42 * 42 && sx * sx + sy * sy <= 40 * 40)
                *at(img, x, y) = 120;
        }
}

/* A dark pen (-100) with a small bright metal tip (+60) touching it. */
static void pen_with_tip(rte_image_u8 *img)
{
    for (int32_t y = 100; y < 110; y++)
        for (int32_t x = 40; x < 200; x++)
            *at(img, x, y) = x < 55 ? 210 : 50;
}

static void shadows_dropped_and_two_tone_objects_kept(void **state)
{
    (void)state;
    rte_background_threshold_result r;
    rte_image_u8 bin = threshold_of(ball_and_shadow, true, &r);
    assert_int_equal(r.shadows, 1);
    assert_int_equal(*at(&bin, 100, 100), 255); /* the ball */
    assert_int_equal(*at(&bin, 150, 140), 0);   /* its shadow */
    test_free(bin.buf);
    bin = threshold_of(ball_and_shadow, false, &r);
    assert_int_equal(r.shadows, 0);
    assert_int_equal(*at(&bin, 150, 140), 255);
    test_free(bin.buf);
    /* the tip is brighter but smaller and of lower contrast than the pen:
     * the pen is no shadow of it, and both stay */
    bin = threshold_of(pen_with_tip, true, &r);
    assert_int_equal(r.shadows, 0);
    assert_int_equal(*at(&bin, 45, 105), 255);
    assert_int_equal(*at(&bin, 150, 105), 255);
    test_free(bin.buf);
}

/* Two faint patches (+18, beyond low but not high), one of them touching a
 * strong object (+60). */
static void faint_patches(rte_image_u8 *img)
{
    for (int32_t y = 20; y < 60; y++)
        for (int32_t x = 20; x < 60; x++)
            *at(img, x, y) = 168;
    for (int32_t y = 100; y < 140; y++)
        for (int32_t x = 100; x < 180; x++)
            *at(img, x, y) = x < 140 ? 168 : 210;
}

static void hysteresis_keeps_faint_parts_of_strong_regions(void **state)
{
    (void)state;
    /* fixed high 24: low 16; the patches' 18 lies between */
    rte_image_u8 img = unit_image_u8(W, H, 0, 150), bg = unit_image_u8(W, H, 0, 150);
    rte_image_u8 bin = unit_image_u8(W, H, 0, 0);
    faint_patches(&img);
    rte_arena arena = new_arena();
    rte_background_threshold_params tp;
    rte_background_threshold_params_default(&tp, W);
    tp.high = 24;
    rte_background_threshold_result r;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, &r), RTE_OK);
    assert_int_equal(r.high, 24);
    assert_int_equal(r.low, 16);
    assert_int_equal(r.regions, 2);
    assert_int_equal(*at(&bin, 40, 40), 0);     /* faint alone: dropped */
    assert_int_equal(*at(&bin, 120, 120), 255); /* faint, touching the strong part */
    assert_int_equal(*at(&bin, 160, 120), 255);
    /* min_contrast raises a lower high threshold */
    tp.high = 10;
    tp.min_contrast = 30;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, &r), RTE_OK);
    assert_int_equal(r.high, 30);
    assert_int_equal(*at(&bin, 120, 120), 0);
    assert_int_equal(*at(&bin, 160, 120), 255);
    test_free(img.buf);
    test_free(bg.buf);
    test_free(bin.buf);
    test_free(arena.base);
}

/* Every pixel flipping side: more runs than the table holds. */
static void a_full_run_table_is_reported(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(W, H, 0, 0), bg = unit_image_u8(W, H, 0, 128);
    rte_image_u8 bin = unit_image_u8(W, H, 2, 0);
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++)
            *at(&img, x, y) = (x + y) % 2 ? 200 : 56;
    rte_arena arena = new_arena();
    rte_background_threshold_params tp;
    rte_background_threshold_params_default(&tp, W);
    rte_background_threshold_result r;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, &r), RTE_OK);
    assert_true(r.dropped_pixels > 0);
    assert_true(r.dropped_pixels < (int64_t)W * H);
    unit_assert_padding_u8(&bin);
    test_free(img.buf);
    test_free(bg.buf);
    test_free(bin.buf);
    test_free(arena.base);
}

/* The tint written out per pixel, independently of the row kernels. */
static uint8_t tint_ref(int s, int b, int c, int least, bool bright, bool dark)
{
    const int ad = s > b ? s - b : b - s;
    if (c < least || c <= ad)
        return (uint8_t)s;
    const bool up = !dark || (bright && (s > b || (s == b && b < 128)));
    const int v = up ? b + c : b - c;
    return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* A frame of random size, 1..70 x 1..9, odd and even (padded rows): grey
 * src s and table b, and the four half-size chroma planes (cb, its table,
 * cr, its table); the callers fill them. */
typedef struct colour_frame {
    int32_t w, h, hw, hh;
    rte_image_u8 s, b, pl[4];
} colour_frame;

static colour_frame colour_frame_new(uint32_t *seed)
{
    colour_frame f;
    f.w = 1 + (int32_t)(unit_rand(seed) % 70);
    f.h = 1 + (int32_t)(unit_rand(seed) % 9);
    f.hw = (f.w + 1) / 2;
    f.hh = (f.h + 1) / 2;
    f.s = unit_image_u8(f.w, f.h, 3, 0);
    f.b = unit_image_u8(f.w, f.h, 0, 0);
    for (int k = 0; k < 4; k++)
        f.pl[k] = unit_image_u8(f.hw, f.hh, k, 0);
    return f;
}

static void colour_frame_free(colour_frame *f)
{
    test_free(f->s.buf);
    test_free(f->b.buf);
    for (int k = 0; k < 4; k++)
        test_free(f->pl[k].buf);
}

/* rte_background_tint_u8 against tint_ref on random frames of odd and even
 * sizes (padded rows), each side setting and threshold; then refusals. */
static void tint_puts_colour_differences_in_place(void **state)
{
    (void)state;
    uint32_t seed = 31;
    for (int trial = 0; trial < 60; trial++) {
        colour_frame f = colour_frame_new(&seed);
        const int32_t w = f.w, h = f.h, hw = f.hw, hh = f.hh;
        rte_image_u8 s = f.s, b = f.b, *pl = f.pl;
        rte_image_u8 d = unit_image_u8(w, h, 5, 0);
        /* small differences often, so that every branch is taken */
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                const int base = (int)(unit_rand(&seed) % 256);
                s.buf[y * s.stride + x] = (uint8_t)base;
                const int off = (int)(unit_rand(&seed) % 61) - 30;
                const int bv = unit_rand(&seed) % 4 ? base + off : base;
                b.buf[y * b.stride + x] = (uint8_t)(bv < 0 ? 0 : bv > 255 ? 255 : bv);
            }
        for (int k = 0; k < 4; k++)
            for (int32_t y = 0; y < hh; y++)
                for (int32_t x = 0; x < hw; x++)
                    pl[k].buf[y * pl[k].stride + x] =
                        (uint8_t)(k & 1 ? pl[k - 1].buf[y * pl[k - 1].stride + x] +
                                              (int)(unit_rand(&seed) % 41) - 20
                                        : (int)(unit_rand(&seed) % 256));
        const rte_background_tint_params p = {.least = 1 + (int32_t)(unit_rand(&seed) % 20),
                                              .bright = trial % 3 != 1,
                                              .dark = trial % 3 != 2};
        assert_int_equal(rte_background_tint_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &d, &p),
                         RTE_OK);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                const int32_t hx = x / 2;
                const int db = abs(pl[0].buf[(y / 2) * pl[0].stride + hx] -
                                   pl[1].buf[(y / 2) * pl[1].stride + hx]);
                const int dr = abs(pl[2].buf[(y / 2) * pl[2].stride + hx] -
                                   pl[3].buf[(y / 2) * pl[3].stride + hx]);
                const int c = db + dr > 255 ? 255 : db + dr;
                assert_int_equal(d.buf[y * d.stride + x],
                                 tint_ref(s.buf[y * s.stride + x], b.buf[y * b.stride + x], c,
                                          p.least, p.bright, p.dark));
            }
        unit_assert_padding_u8(&d);
        /* refusals: planes of another size, dst on src, least out of range */
        rte_image_u8 small = pl[1];
        small.width = hw > 1 ? hw - 1 : 2;
        assert_int_equal(rte_background_tint_u8(&s, &b, &pl[0], &small, &pl[2], &pl[3], &d, &p),
                         RTE_ERR_SIZE);
        assert_int_equal(rte_background_tint_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &s, &p),
                         RTE_ERR_ARGUMENT);
        rte_background_tint_params bad = p;
        bad.least = 0;
        assert_int_equal(rte_background_tint_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &d, &bad),
                         RTE_ERR_ARGUMENT);
        assert_int_equal(rte_background_tint_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &d, NULL),
                         RTE_ERR_ARGUMENT);
        test_free(d.buf);
        colour_frame_free(&f);
    }
}

/* shade by the formula in background.h, per chroma sample (its 2x2
 * block's top-left pixel s, t) */
static uint8_t shade_ref(int s, int t, int cb, int cbt, int cr, int crt,
                         const rte_background_shade_params *p)
{
    if (t == 0)
        return 0;
    const long eb = labs((long)(cb - 128) * t - (long)s * (cbt - 128));
    const long er = labs((long)(cr - 128) * t - (long)s * (crt - 128));
    return (uint8_t)(s * 1000 >= p->darkest_permille * t && s * 1000 <= p->lightest_permille * t &&
                             eb + er <= (long)p->chroma * t
                         ? 255
                         : 0);
}

/* rte_background_shade_u8 against shade_ref on random frames of odd and
 * even sizes (padded rows), near-shadow pixels often; then refusals. */
static void shade_marks_the_dimmed_table(void **state)
{
    (void)state;
    uint32_t seed = 77;
    int marked = 0;
    for (int trial = 0; trial < 60; trial++) {
        colour_frame f = colour_frame_new(&seed);
        const int32_t w = f.w, h = f.h, hw = f.hw, hh = f.hh;
        rte_image_u8 s = f.s, b = f.b, *pl = f.pl;
        rte_image_u8 m = unit_image_u8(hw, hh, 5, 0);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                const int t = (int)(unit_rand(&seed) % 256);
                b.buf[y * b.stride + x] = (uint8_t)t;
                s.buf[y * s.stride + x] = (uint8_t)(t * (int)(unit_rand(&seed) % 120) / 100);
            }
        for (int32_t y = 0; y < hh; y++)
            for (int32_t x = 0; x < hw; x++) {
                /* the table's chroma, and the frame's: that dimmed by the
                 * pixel's ratio, give or take a few */
                const int sv = s.buf[2 * y * s.stride + 2 * x],
                          tv = b.buf[2 * y * b.stride + 2 * x];
                for (int k = 0; k < 4; k += 2) {
                    const int table = 128 + (int)(unit_rand(&seed) % 41) - 20;
                    const int dim = tv ? 128 + (table - 128) * sv / tv : 128;
                    const int v = dim + (int)(unit_rand(&seed) % 31) - 15;
                    pl[k + 1].buf[y * pl[k + 1].stride + x] = (uint8_t)table;
                    pl[k].buf[y * pl[k].stride + x] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
                }
            }
        const int32_t lo = (int32_t)(unit_rand(&seed) % 600);
        const rte_background_shade_params p = {
            .darkest_permille = lo,
            .lightest_permille = lo + (int32_t)(unit_rand(&seed) % (1001 - (uint32_t)lo)),
            .chroma = (int32_t)(unit_rand(&seed) % 30)};
        assert_int_equal(rte_background_shade_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &m, &p),
                         RTE_OK);
        for (int32_t y = 0; y < hh; y++)
            for (int32_t x = 0; x < hw; x++) {
                const uint8_t want =
                    shade_ref(s.buf[2 * y * s.stride + 2 * x], b.buf[2 * y * b.stride + 2 * x],
                              pl[0].buf[y * pl[0].stride + x], pl[1].buf[y * pl[1].stride + x],
                              pl[2].buf[y * pl[2].stride + x], pl[3].buf[y * pl[3].stride + x], &p);
                assert_int_equal(m.buf[y * m.stride + x], want);
                marked += want != 0;
            }
        unit_assert_padding_u8(&m);
        /* refusals: a full-size mask, the mask on src, bounds out of order */
        assert_int_equal(rte_background_shade_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &s, &p),
                         w > 1 || h > 1 ? RTE_ERR_SIZE : RTE_ERR_ARGUMENT);
        rte_background_shade_params bad = p;
        bad.lightest_permille = bad.darkest_permille - 1;
        assert_int_equal(rte_background_shade_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &m, &bad),
                         RTE_ERR_ARGUMENT);
        bad = p;
        bad.chroma = 256;
        assert_int_equal(rte_background_shade_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &m, &bad),
                         RTE_ERR_ARGUMENT);
        assert_int_equal(rte_background_shade_u8(&s, &b, &pl[0], &pl[1], &pl[2], &pl[3], &m, NULL),
                         RTE_ERR_ARGUMENT);
        test_free(m.buf);
        colour_frame_free(&f);
    }
    assert_true(marked > 100); /* the random frames mark pixels often */
}

/* The table (grey 180, cb 120, cr 132) under a dark teal disc (grey 60, cb
 * 150, cr 110) that casts a neutral shadow (the table at 55%) to its lower
 * right; elsewhere a grey patch alone (the table at 55%, no core beside
 * it), and a dark bar (grey 50) whose middle is a grey band (the table at
 * 55%) between its two halves. */
static void shadow_scene(rte_image_u8 *g, rte_image_u8 *cb, rte_image_u8 *cr, rte_image_u8 *bg,
                         rte_image_u8 *cbt, rte_image_u8 *crt)
{
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            const int32_t dx = x - 80, dy = y - 80, sx = x - 92, sy = y - 92;
            int v = 180, b = 120, r = 132;
            if (dx * dx + dy * dy <= 30 * 30) {
                v = 60, b = 150, r = 110;
            } else if (sx * sx + sy * sy <= 30 * 30 || (x >= 220 && x < 260 && y >= 40 && y < 80) ||
                       (x >= 150 && x < 170 && y >= 170 && y < 200)) {
                v = 99, b = 128 + (120 - 128) * 99 / 180, r = 128 + (132 - 128) * 99 / 180;
            } else if (x >= 100 && x < 220 && y >= 170 && y < 200) {
                v = 50, b = 128, r = 128;
            }
            *at(g, x, y) = (uint8_t)v;
            *at(bg, x, y) = 180;
            if (!(x & 1) && !(y & 1)) {
                cb->buf[(y / 2) * cb->stride + x / 2] = (uint8_t)b;
                cr->buf[(y / 2) * cr->stride + x / 2] = (uint8_t)r;
                cbt->buf[(y / 2) * cbt->stride + x / 2] = 120;
                crt->buf[(y / 2) * crt->stride + x / 2] = 132;
            }
        }
}

/* A dark object's neutral cast shadow is dropped with the shade mask (and
 * kept without it); a grey patch alone and a grey band inside a dark object
 * are kept; the disc's own pixels are the same either way. */
static void cast_shadows_are_told_from_grey_objects(void **state)
{
    (void)state;
    rte_image_u8 g = unit_image_u8(W, H, 2, 0), bg = unit_image_u8(W, H, 0, 0);
    rte_image_u8 pl[4], m = unit_image_u8(W / 2, H / 2, 1, 0);
    for (int k = 0; k < 4; k++)
        pl[k] = unit_image_u8(W / 2, H / 2, k, 0);
    shadow_scene(&g, &pl[0], &pl[2], &bg, &pl[1], &pl[3]);
    const rte_background_shade_params sp = {400, 900, 15};
    assert_int_equal(rte_background_shade_u8(&g, &bg, &pl[0], &pl[1], &pl[2], &pl[3], &m, &sp),
                     RTE_OK);
    assert_int_equal(m.buf[50 * m.stride + 53], 255); /* the shadow, at (106, 100) */
    assert_int_equal(m.buf[40 * m.stride + 40], 0);   /* the disc */
    assert_int_equal(m.buf[10 * m.stride + 10], 0);   /* the table */
    rte_arena arena = new_arena();
    rte_background_threshold_params tp;
    rte_background_threshold_params_default(&tp, W);
    rte_image_u8 with = unit_image_u8(W, H, 0, 0), without = unit_image_u8(W, H, 0, 0);
    rte_background_threshold_result r, r0;
    assert_int_equal(rte_background_threshold_shaded_u8(&g, &bg, &m, &with, &tp, &arena, &r),
                     RTE_OK);
    assert_int_equal(rte_background_threshold_u8(&g, &bg, &without, &tp, &arena, &r0), RTE_OK);
    assert_int_equal(r.shadows, r0.shadows + 1);
    assert_int_equal(*at(&without, 106, 100), 255); /* the shadow joins the disc without */
    assert_int_equal(*at(&with, 106, 100), 0);      /* and is dropped with the mask */
    assert_int_equal(*at(&with, 240, 60), 255);     /* the grey patch alone */
    assert_int_equal(*at(&with, 160, 185), 255);    /* the grey band in the bar */
    for (int32_t y = 0; y < H; y++)                 /* the disc the same */
        for (int32_t x = 0; x < W; x++) {
            const int32_t dx = x - 80, dy = y - 80;
            if (dx * dx + dy * dy <= 28 * 28)
                assert_int_equal(*at(&with, x, y), *at(&without, x, y));
        }
    /* refusals: a full-size mask */
    assert_int_equal(rte_background_threshold_shaded_u8(&g, &bg, &g, &with, &tp, &arena, NULL),
                     RTE_ERR_SIZE);
    test_free(g.buf);
    test_free(bg.buf);
    test_free(m.buf);
    test_free(with.buf);
    test_free(without.buf);
    for (int k = 0; k < 4; k++)
        test_free(pl[k].buf);
    test_free(arena.base);
}

static void bad_arguments(void **state)
{
    (void)state;
    rte_image_u8 img = unit_image_u8(W, H, 0, 100), bg = unit_image_u8(W, H, 0, 0);
    rte_image_u8 small = unit_image_u8(W - 1, H, 0, 0);
    rte_arena arena = new_arena();
    rte_background_params p;
    rte_background_params_default(&p, W);
    const rte_background_params good = p;
    assert_int_equal(rte_background_estimate_u8(&img, &small, &p, &arena), RTE_ERR_SIZE);
    assert_int_equal(rte_background_estimate_u8(&img, &img, &p, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_background_estimate_u8(&img, &bg, NULL, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, NULL), RTE_ERR_ARGUMENT);
    p.cell = 1;
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_ERR_ARGUMENT);
    p = good;
    p.radius = RTE_BACKGROUND_MAX_RADIUS + 1;
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_ERR_ARGUMENT);
    p = good;
    p.step = 256;
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_ERR_ARGUMENT);
    p = good;
    p.tolerance = -1;
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &p, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_background_scratch_size(0, H, 8), 0);
    assert_int_equal(rte_background_scratch_size(W, H, 1), 0);
    assert_int_equal(rte_background_threshold_scratch_size(W, 0), 0);

    /* an arena short of the need fails cleanly and is left as it was */
    const size_t need = rte_background_scratch_size(W, H, good.cell);
    rte_arena tight;
    rte_arena_init(&tight, aligned(&arena), need / 2);
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &good, &tight), RTE_ERR_NO_MEMORY);
    assert_int_equal(tight.used, 0);
    rte_arena_init(&tight, aligned(&arena), need);
    assert_int_equal(rte_background_estimate_u8(&img, &bg, &good, &tight), RTE_OK);

    rte_image_u8 bin = unit_image_u8(W, H, 0, 0);
    rte_background_threshold_params tp;
    rte_background_threshold_params_default(&tp, W);
    const rte_background_threshold_params tgood = tp;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &small, &tp, &arena, NULL),
                     RTE_ERR_SIZE);
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &img, &tp, &arena, NULL),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bg, &tp, &arena, NULL),
                     RTE_ERR_ARGUMENT);
    tp.min_contrast = 0;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, NULL),
                     RTE_ERR_ARGUMENT);
    tp = tgood;
    tp.high = 256;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, NULL),
                     RTE_ERR_ARGUMENT);
    tp = tgood;
    tp.shadow_gap = RTE_BACKGROUND_MAX_SHADOW_GAP + 1;
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tp, &arena, NULL),
                     RTE_ERR_ARGUMENT);
    rte_arena_init(&tight, aligned(&arena), rte_background_threshold_scratch_size(W, H) / 2);
    assert_int_equal(rte_background_threshold_u8(&img, &bg, &bin, &tgood, &tight, NULL),
                     RTE_ERR_NO_MEMORY);
    assert_int_equal(tight.used, 0);
    test_free(img.buf);
    test_free(bg.buf);
    test_free(small.buf);
    test_free(bin.buf);
    test_free(arena.base);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(estimate_follows_the_vignette_under_objects),
        cmocka_unit_test(estimate_matches_the_plain_definition),
        cmocka_unit_test(threshold_finds_lighter_and_darker_objects),
        cmocka_unit_test(shadows_dropped_and_two_tone_objects_kept),
        cmocka_unit_test(hysteresis_keeps_faint_parts_of_strong_regions),
        cmocka_unit_test(a_full_run_table_is_reported),
        cmocka_unit_test(tint_puts_colour_differences_in_place),
        cmocka_unit_test(shade_marks_the_dimmed_table),
        cmocka_unit_test(cast_shadows_are_told_from_grey_objects),
        cmocka_unit_test(bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
