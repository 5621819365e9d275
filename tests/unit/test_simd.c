/* SIMD row kernels against their plain C references, byte for byte, on
 * random rows (as libyuv tests its rows): every width 1..300 and random
 * larger ones, unaligned starts, for every variant this CPU runs. Sources
 * end exactly at the row's last byte (an over-read shows under ASan) and
 * destinations have guard bytes after the row (an over-write shows here).
 * Also: RTE_FORCE_C selects the C path. */
#include "unit.h"

#include <stdbool.h>

#include "rtedge/blur.h"
#include "rtedge/color.h"
#include "rtedge/cpu.h"

#include "../../src/algo/simd/rows.h"

enum { GUARD = 64, MAX_OFFSET = 32 };

/* Whether this CPU runs a variant that needs the RTE_CPU_* bits `needs`
 * (the others are skipped, and say so). */
static bool cpu_runs(const char *name, uint32_t needs)
{
    if ((rte_cpu_features_hw() & needs) == needs)
        return true;
    print_message("skipping %s: not supported by this CPU\n", name);
    return false;
}

typedef struct c3_variant {
    const char *name;
    uint32_t needs; /* RTE_CPU_* bits */
    rte_row_c3_to_gray_fn fn, ref;
} c3_variant;

static const c3_variant c3_variants[] = {
#ifdef RTE_SIMD_X86
    { "bgr_to_gray_ssse3", RTE_CPU_X86_SSSE3, rte_row_bgr_to_gray_ssse3, rte_row_bgr_to_gray_c },
    { "rgb_to_gray_ssse3", RTE_CPU_X86_SSSE3, rte_row_rgb_to_gray_ssse3, rte_row_rgb_to_gray_c },
    { "bgr_to_gray_avx2", RTE_CPU_X86_AVX2, rte_row_bgr_to_gray_avx2, rte_row_bgr_to_gray_c },
    { "rgb_to_gray_avx2", RTE_CPU_X86_AVX2, rte_row_rgb_to_gray_avx2, rte_row_rgb_to_gray_c },
#endif
#ifdef RTE_SIMD_NEON
    { "bgr_to_gray_neon", RTE_CPU_ARM_NEON, rte_row_bgr_to_gray_neon, rte_row_bgr_to_gray_c },
    { "rgb_to_gray_neon", RTE_CPU_ARM_NEON, rte_row_rgb_to_gray_neon, rte_row_rgb_to_gray_c },
#endif
    /* the reference against itself keeps the harness honest on any CPU */
    { "bgr_to_gray_c", 0, rte_row_bgr_to_gray_c, rte_row_bgr_to_gray_c },
};
#define C3_VARIANT_COUNT (sizeof c3_variants / sizeof c3_variants[0])

/* Random bytes; every 7th row uses only 0 and 255 so that the extremes
 * (and the rounding at the top of the range) are hit often. */
static void fill_random(uint8_t *p, size_t n, uint32_t *seed, int extremes)
{
    for (size_t i = 0; i < n; i++) {
        uint32_t r = unit_rand(seed);
        p[i] = extremes ? (uint8_t)((r & 1) ? 255 : 0) : (uint8_t)r;
    }
}

/* One row of `width` pixels: src at byte offset `so` of its buffer and
 * ending at the buffer's end, dst at offset `dof` with guard bytes after. */
static void check_c3_row(const c3_variant *v, int32_t width, uint32_t *seed)
{
    size_t so = unit_rand(seed) % MAX_OFFSET, dof = unit_rand(seed) % MAX_OFFSET;
    size_t src_bytes = 3 * (size_t)width;
    uint8_t *sbuf = test_malloc(so + src_bytes);
    uint8_t *want = test_malloc(dof + (size_t)width + GUARD);
    uint8_t *got = test_malloc(dof + (size_t)width + GUARD);
    fill_random(sbuf + so, src_bytes, seed, width % 7 == 0);
    memset(want, 0xEE, dof + (size_t)width + GUARD);
    memset(got, 0xEE, dof + (size_t)width + GUARD);
    v->ref(sbuf + so, want + dof, width);
    v->fn(sbuf + so, got + dof, width);
    if (memcmp(want, got, dof + (size_t)width + GUARD) != 0) {
        for (size_t i = 0; i < dof + (size_t)width + GUARD; i++)
            if (want[i] != got[i])
                fail_msg("%s width %d: byte %zd is %u, reference %u", v->name, (int)width,
                         (ptrdiff_t)i - (ptrdiff_t)dof, got[i], want[i]);
    }
    test_free(sbuf);
    test_free(want);
    test_free(got);
}

static void c3_to_gray_rows_match_reference(void **state)
{
    (void)state;
    int ran = 0;
    for (size_t i = 0; i < C3_VARIANT_COUNT; i++) {
        const c3_variant *v = &c3_variants[i];
        if (!cpu_runs(v->name, v->needs))
            continue;
        uint32_t seed = 0x9E3779B9u + (uint32_t)i;
        for (int32_t w = 1; w <= 300; w++)
            check_c3_row(v, w, &seed);
        for (int k = 0; k < 40; k++)
            check_c3_row(v, 301 + (int32_t)(unit_rand(&seed) % 4000), &seed);
        ran++;
    }
    assert_true(ran >= 1);
}

/* Gaussian passes: each variant against the C build of the same loops. */
typedef struct gaussian_variant {
    const char *name;
    uint32_t needs;
    rte_gaussian_column_fn column;
    rte_gaussian_row_fn row;
} gaussian_variant;

static const gaussian_variant gaussian_variants[] = {
#ifdef RTE_SIMD_X86
    { "gaussian_avx2", RTE_CPU_X86_AVX2, rte_gaussian_column_pass_avx2, rte_gaussian_row_pass_avx2 },
#endif
    { "gaussian_c", 0, rte_gaussian_column_pass_c, rte_gaussian_row_pass_c },
};
#define GAUSSIAN_VARIANT_COUNT (sizeof gaussian_variants / sizeof gaussian_variants[0])

/* Symmetric random taps summing to 256, as rte_gaussian_kernel holds (the
 * middle tap takes the remainder). */
static void random_taps(uint16_t *taps, int32_t ksize, uint32_t *seed)
{
    int32_t r = ksize / 2, left = 256;
    for (int32_t i = 0; i < r; i++) {
        uint16_t t = (uint16_t)(unit_rand(seed) % (uint32_t)(left / (2 * (r - i)) + 1));
        taps[i] = taps[ksize - 1 - i] = t;
        left -= 2 * t;
    }
    taps[r] = (uint16_t)left;
}

static uint16_t *random_u16(size_t n, uint32_t *seed, uint16_t max)
{
    uint16_t *p = test_malloc(n * sizeof *p);
    for (size_t i = 0; i < n; i++)
        p[i] = (uint16_t)(unit_rand(seed) % ((uint32_t)max + 1));
    return p;
}

static void check_gaussian(const gaussian_variant *v, int32_t width, int32_t ksize, int split,
                           uint32_t *seed)
{
    uint16_t taps[RTE_GAUSSIAN_MAX_KSIZE];
    random_taps(taps, ksize, seed);
    /* column pass: ksize rows, each ending at its allocation's end */
    const uint8_t *rows[RTE_GAUSSIAN_MAX_KSIZE];
    uint8_t *row_bufs[RTE_GAUSSIAN_MAX_KSIZE];
    for (int32_t j = 0; j < ksize; j++) {
        row_bufs[j] = test_malloc((size_t)width);
        fill_random(row_bufs[j], (size_t)width, seed, width % 7 == 0);
        rows[j] = row_bufs[j];
    }
    size_t n = (size_t)width + GUARD;
    uint16_t *want = test_malloc(2 * n * sizeof *want), *got = test_malloc(2 * n * sizeof *got);
    for (size_t i = 0; i < 2 * n; i++)
        want[i] = got[i] = 0x7EEE;
    rte_gaussian_column_pass_c(rows, want, want + n, width, taps, ksize, split);
    v->column(rows, got, got + n, width, taps, ksize, split);
    if (memcmp(want, got, 2 * n * sizeof *want) != 0)
        fail_msg("%s column pass width %d ksize %d split %d differs", v->name, (int)width,
                 (int)ksize, split);
    for (int32_t j = 0; j < ksize; j++)
        test_free(row_bufs[j]);
    test_free(want);
    test_free(got);

    /* row pass: padded planes of values the column pass can produce */
    size_t padded = (size_t)width + 2 * (size_t)(ksize / 2);
    uint16_t *hi = random_u16(padded, seed, split ? 255 : 65535);
    uint16_t *lo = random_u16(padded, seed, 255);
    uint8_t *dwant = test_malloc(n), *dgot = test_malloc(n);
    memset(dwant, 0xEE, n);
    memset(dgot, 0xEE, n);
    rte_gaussian_row_pass_c(hi, lo, dwant, width, taps, ksize, split);
    v->row(hi, lo, dgot, width, taps, ksize, split);
    if (memcmp(dwant, dgot, n) != 0)
        fail_msg("%s row pass width %d ksize %d split %d differs", v->name, (int)width,
                 (int)ksize, split);
    test_free(hi);
    test_free(lo);
    test_free(dwant);
    test_free(dgot);
}

static void gaussian_passes_match_reference(void **state)
{
    (void)state;
    int ran = 0;
    for (size_t i = 0; i < GAUSSIAN_VARIANT_COUNT; i++) {
        const gaussian_variant *v = &gaussian_variants[i];
        if (!cpu_runs(v->name, v->needs))
            continue;
        uint32_t seed = 0xC0FFEEu + (uint32_t)i;
        for (int32_t ksize = 1; ksize <= RTE_GAUSSIAN_MAX_KSIZE; ksize += 2)
            for (int split = 0; split <= 1; split++) {
                for (int32_t w = 1; w <= 80; w++)
                    check_gaussian(v, w, ksize, split, &seed);
                for (int k = 0; k < 4; k++)
                    check_gaussian(v, 81 + (int32_t)(unit_rand(&seed) % 2000), ksize, split,
                                   &seed);
            }
        ran++;
    }
    assert_true(ran >= 1);
}

/* Morphology rows: each variant against the C build of the same loops. */
typedef struct morph_variant {
    const char *name;
    uint32_t needs;
    rte_morph_op2_fn op2;
    rte_morph_reduce_fn reduce;
} morph_variant;

static const morph_variant morph_variants[] = {
#ifdef RTE_SIMD_X86
    { "morph_avx2", RTE_CPU_X86_AVX2, rte_morph_row_op2_avx2, rte_morph_reduce_rows_avx2 },
#endif
    { "morph_c", 0, rte_morph_row_op2_c, rte_morph_reduce_rows_c },
};
#define MORPH_VARIANT_COUNT (sizeof morph_variants / sizeof morph_variants[0])

enum { MORPH_MAX_ROWS = 64 };

/* `count` rows as the kernels see them: shifted views into one buffer that
 * ends where the last view ends (as the taps of one padded row), so
 * unaligned starts and over-reads both show. */
static void check_morph(const morph_variant *v, int32_t width, int32_t count, bool accumulate,
                        bool is_max, uint32_t *seed)
{
    size_t span = (size_t)width + (size_t)count;
    uint8_t *src = test_malloc(span);
    fill_random(src, span, seed, width % 7 == 0);
    const uint8_t *rows[MORPH_MAX_ROWS];
    for (int32_t i = 0; i < count; i++)
        rows[i] = src + unit_rand(seed) % (uint32_t)(count + 1);
    size_t n = (size_t)width + GUARD;
    uint8_t *want = test_malloc(n), *got = test_malloc(n);
    fill_random(want, (size_t)width, seed, 0); /* what accumulating starts from */
    memset(want + width, 0xEE, GUARD);
    memcpy(got, want, n);
    rte_morph_reduce_rows_c(want, rows, count, accumulate, width, is_max);
    v->reduce(got, rows, count, accumulate, width, is_max);
    if (memcmp(want, got, n) != 0)
        fail_msg("%s reduce width %d count %d acc %d max %d differs", v->name, (int)width,
                 (int)count, accumulate, is_max);
    /* op2, also in place (d == a) */
    rte_morph_row_op2_c(want, want, rows[0], width, is_max);
    v->op2(got, got, rows[0], width, is_max);
    if (memcmp(want, got, n) != 0)
        fail_msg("%s op2 width %d max %d differs", v->name, (int)width, is_max);
    test_free(src);
    test_free(want);
    test_free(got);
}

static void morph_rows_match_reference(void **state)
{
    (void)state;
    int ran = 0;
    for (size_t i = 0; i < MORPH_VARIANT_COUNT; i++) {
        const morph_variant *v = &morph_variants[i];
        if (!cpu_runs(v->name, v->needs))
            continue;
        uint32_t seed = 0xBADC0DEu + (uint32_t)i;
        for (int32_t count = 1; count <= MORPH_MAX_ROWS; count++)
            for (int m = 0; m < 4; m++) {
                bool accumulate = m & 1, is_max = m & 2;
                for (int32_t w = 1; w <= 70; w++)
                    check_morph(v, w, count, accumulate, is_max, &seed);
                check_morph(v, 71 + (int32_t)(unit_rand(&seed) % 2000), count, accumulate,
                            is_max, &seed);
            }
        ran++;
    }
    assert_true(ran >= 1);
}

/* Every colour through the dispatched whole-image path: 2^24 pixels as a
 * 4096 x 4096 image would be 48 MB, so a strided 256 x 256 window per red
 * value, which also checks that each row restarts at its stride. */
static void every_colour_matches_reference(void **state)
{
    (void)state;
    const int32_t w = 256, h = 256, stride = 3 * w + 5;
    uint8_t *src = test_malloc((size_t)stride * h);
    rte_image_u8 got = unit_image_u8(w, h, 3, 0), want = unit_image_u8(w, h, 3, 0);
    for (int r = 0; r < 256; r++) {
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                uint8_t *p = src + (size_t)y * stride + 3 * (size_t)x;
                p[0] = (uint8_t)x, p[1] = (uint8_t)y, p[2] = (uint8_t)r;
            }
        rte_image_u8c3 img = { w, h, stride, src };
        assert_int_equal(rte_color_bgr_to_gray(&img, &got), RTE_OK);
        for (int32_t y = 0; y < h; y++)
            rte_row_bgr_to_gray_c(src + (size_t)y * stride, want.buf + (size_t)y * want.stride, w);
        assert_memory_equal(got.buf, want.buf, (size_t)want.stride * h);
    }
    unit_assert_padding_u8(&got);
    test_free(src);
    test_free(got.buf);
    test_free(want.buf);
}

static void force_c_selects_the_reference(void **state)
{
    (void)state;
    uint32_t hw = rte_cpu_features_hw();
    assert_int_equal(unsetenv("RTE_FORCE_C"), 0);
    assert_int_equal(rte_cpu_features(), hw);
#ifdef RTE_SIMD_X86
    /* x86-64 always has SSE2; the probe must see it */
    assert_true(hw & RTE_CPU_X86_SSE2);
    if (hw & RTE_CPU_X86_SSSE3)
        assert_true(rte_row_c3_to_gray_select(hw, false) != rte_row_bgr_to_gray_c);
#endif
#ifdef RTE_SIMD_NEON
    assert_true(hw & RTE_CPU_ARM_NEON);
    assert_true(rte_row_c3_to_gray_select(hw, false) == rte_row_bgr_to_gray_neon);
#endif
    assert_int_equal(setenv("RTE_FORCE_C", "1", 1), 0);
    assert_int_equal(rte_cpu_features(), 0);
    assert_true(rte_row_c3_to_gray_select(rte_cpu_features(), false) == rte_row_bgr_to_gray_c);
    assert_true(rte_row_c3_to_gray_select(rte_cpu_features(), true) == rte_row_rgb_to_gray_c);
    rte_gaussian_rows g = rte_gaussian_rows_select(rte_cpu_features());
    assert_true(g.column == rte_gaussian_column_pass_c && g.row == rte_gaussian_row_pass_c);
    rte_morph_rows m = rte_morph_rows_select(rte_cpu_features());
    assert_true(m.op2 == rte_morph_row_op2_c && m.reduce == rte_morph_reduce_rows_c);
    assert_int_equal(rte_cpu_features_hw(), hw);
    /* "0" and "" mean "not forced" */
    assert_int_equal(setenv("RTE_FORCE_C", "0", 1), 0);
    assert_int_equal(rte_cpu_features(), hw);
    assert_int_equal(setenv("RTE_FORCE_C", "", 1), 0);
    assert_int_equal(rte_cpu_features(), hw);
    assert_int_equal(unsetenv("RTE_FORCE_C"), 0);
}

/* The same image through the public API, forced C and dispatched. */
static void forced_and_dispatched_images_agree(void **state)
{
    (void)state;
    uint32_t seed = 12345;
    const int32_t w = 333, h = 7, stride = 3 * w + 11;
    uint8_t *src = test_malloc((size_t)stride * h);
    fill_random(src, (size_t)stride * h, &seed, 0);
    rte_image_u8c3 img = { w, h, stride, src };
    rte_image_u8 a = unit_image_u8(w, h, 9, 0), b = unit_image_u8(w, h, 9, 0);
    assert_int_equal(setenv("RTE_FORCE_C", "1", 1), 0);
    assert_int_equal(rte_color_rgb_to_gray(&img, &a), RTE_OK);
    assert_int_equal(unsetenv("RTE_FORCE_C"), 0);
    assert_int_equal(rte_color_rgb_to_gray(&img, &b), RTE_OK);
    assert_memory_equal(a.buf, b.buf, (size_t)a.stride * h);
    unit_assert_padding_u8(&b);
    test_free(src);
    test_free(a.buf);
    test_free(b.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(c3_to_gray_rows_match_reference),
        cmocka_unit_test(every_colour_matches_reference),
        cmocka_unit_test(gaussian_passes_match_reference),
        cmocka_unit_test(morph_rows_match_reference),
        cmocka_unit_test(force_c_selects_the_reference),
        cmocka_unit_test(forced_and_dispatched_images_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
