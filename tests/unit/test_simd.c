/* SIMD row kernels against their plain C references, byte for byte, on
 * random rows (as libyuv tests its rows): every width 1..300 and random
 * larger ones, unaligned starts, odd strides. Each kernel family runs
 * under every feature mask of its CPU family (none, SSE2, +SSSE3, +SSE4.1,
 * +AVX2, +AVX-512 on x86; none, NEON on aarch64): the variant that the family's
 * *_select(mask) picks is compared with the C reference, one CMocka test
 * per family and mask, and a mask this CPU lacks is reported as skipped.
 * Every variant must be picked by some mask, and never one that needs a
 * feature outside its mask. Sources end exactly at the row's last byte
 * (an over-read shows under ASan) and destinations have guard bytes after
 * the row (an over-write shows here). Also: RTE_FORCE_C selects the C
 * path. */
#include "unit.h"

#include <stdbool.h>
#include <stdio.h>

#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/color.h"
#include "rtedge/cpu.h"
#include "rtedge/hough.h"
#include "rtedge/threshold.h"

#include "algo/gradient_rows.h"
#include "algo/hough_internal.h"
#include "algo/simd/rows.h"

#define PI_SIMD 3.14159265358979323846

enum { GUARD = 64, MAX_OFFSET = 32 };

#define COUNT_OF(a) (sizeof(a) / sizeof((a)[0]))

/* The feature masks every family runs under, each with the instruction
 * sets of the ones before it. */
typedef struct feature_mask {
    const char *name;
    uint32_t bits; /* RTE_CPU_* */
} feature_mask;

static const feature_mask feature_masks[] = {
    {"none", 0},
#ifdef RTE_SIMD_X86
    {"sse2", RTE_CPU_X86_SSE2},
    {"ssse3", RTE_CPU_X86_SSE2 | RTE_CPU_X86_SSSE3},
    {"sse41", RTE_CPU_X86_SSE2 | RTE_CPU_X86_SSSE3 | RTE_CPU_X86_SSE41},
    {"avx2", RTE_CPU_X86_SSE2 | RTE_CPU_X86_SSSE3 | RTE_CPU_X86_SSE41 | RTE_CPU_X86_AVX2},
    {"avx512", RTE_CPU_X86_SSE2 | RTE_CPU_X86_SSSE3 | RTE_CPU_X86_SSE41 | RTE_CPU_X86_AVX2 |
                   RTE_CPU_X86_AVX512},
#endif
#ifdef RTE_SIMD_NEON
    {"neon", RTE_CPU_ARM_NEON},
#endif
};

/* The RTE_CPU_* bits as names ("ssse3 avx2"), for messages. */
static const char *feature_names(uint32_t bits, char *buf, size_t size)
{
    static const feature_mask names[] = {
        {"sse2", RTE_CPU_X86_SSE2}, {"ssse3", RTE_CPU_X86_SSSE3},   {"sse41", RTE_CPU_X86_SSE41},
        {"avx2", RTE_CPU_X86_AVX2}, {"avx512", RTE_CPU_X86_AVX512}, {"neon", RTE_CPU_ARM_NEON},
    };
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < COUNT_OF(names) && used < size; i++)
        if (bits & names[i].bits)
            used +=
                (size_t)snprintf(buf + used, size - used, "%s%s", used ? " " : "", names[i].name);
    return used ? buf : "none";
}

/* The first member of every variant struct below. */
typedef struct variant_head {
    const char *name;
    uint32_t needs; /* RTE_CPU_* bits */
} variant_head;

/* NAME_pick(features): the index in TABLE (of TYPE) of the variant that
 * SELECT, the family's own choice for `features`, gives as `p` (SAME
 * tells whether the table's `v` is it), or -1 if it is not in the table. */
#define DEFINE_PICK(NAME, TABLE, TYPE, PICKED_TYPE, SELECT, SAME) \
    static int NAME##_pick(uint32_t features)                     \
    {                                                             \
        const PICKED_TYPE p = SELECT;                             \
        for (size_t i = 0; i < COUNT_OF(TABLE); i++) {            \
            const TYPE *v = &TABLE[i];                            \
            if (SAME)                                             \
                return (int)i;                                    \
        }                                                         \
        return -1;                                                \
    }

/* BGR and RGB rows to grey; the reference against itself (the "none"
 * mask) keeps the harness honest on any CPU. */
typedef struct c3_variant {
    variant_head head;
    rte_row_c3_to_gray_fn fn, ref;
} c3_variant;

static const c3_variant bgr_variants[] = {
#ifdef RTE_SIMD_X86
    {{"bgr_to_gray_ssse3", RTE_CPU_X86_SSSE3}, rte_row_bgr_to_gray_ssse3, rte_row_bgr_to_gray_c},
    {{"bgr_to_gray_avx2", RTE_CPU_X86_AVX2}, rte_row_bgr_to_gray_avx2, rte_row_bgr_to_gray_c},
#endif
#ifdef RTE_SIMD_NEON
    {{"bgr_to_gray_neon", RTE_CPU_ARM_NEON}, rte_row_bgr_to_gray_neon, rte_row_bgr_to_gray_c},
#endif
    {{"bgr_to_gray_c", 0}, rte_row_bgr_to_gray_c, rte_row_bgr_to_gray_c},
};

static const c3_variant rgb_variants[] = {
#ifdef RTE_SIMD_X86
    {{"rgb_to_gray_ssse3", RTE_CPU_X86_SSSE3}, rte_row_rgb_to_gray_ssse3, rte_row_rgb_to_gray_c},
    {{"rgb_to_gray_avx2", RTE_CPU_X86_AVX2}, rte_row_rgb_to_gray_avx2, rte_row_rgb_to_gray_c},
#endif
#ifdef RTE_SIMD_NEON
    {{"rgb_to_gray_neon", RTE_CPU_ARM_NEON}, rte_row_rgb_to_gray_neon, rte_row_rgb_to_gray_c},
#endif
    {{"rgb_to_gray_c", 0}, rte_row_rgb_to_gray_c, rte_row_rgb_to_gray_c},
};

DEFINE_PICK(bgr, bgr_variants, c3_variant, rte_row_c3_to_gray_fn,
            rte_row_c3_to_gray_select(features, false), v->fn == p)
DEFINE_PICK(rgb, rgb_variants, c3_variant, rte_row_c3_to_gray_fn,
            rte_row_c3_to_gray_select(features, true), v->fn == p)

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
                fail_msg("%s width %d: byte %zd is %u, reference %u", v->head.name, (int)width,
                         (ptrdiff_t)i - (ptrdiff_t)dof, got[i], want[i]);
    }
    test_free(sbuf);
    test_free(want);
    test_free(got);
}

static void c3_to_gray_rows(const void *variant, uint32_t *seed)
{
    const c3_variant *v = variant;
    for (int32_t w = 1; w <= 300; w++)
        check_c3_row(v, w, seed);
    for (int k = 0; k < 40; k++)
        check_c3_row(v, 301 + (int32_t)(unit_rand(seed) % 4000), seed);
}

/* Gaussian passes: each variant against the C build of the same loops. */
typedef struct gaussian_variant {
    variant_head head;
    rte_gaussian_column_fn column;
    rte_gaussian_row_fn row;
} gaussian_variant;

static const gaussian_variant gaussian_variants[] = {
#ifdef RTE_SIMD_X86
    {{"gaussian_avx2", RTE_CPU_X86_AVX2},
     rte_gaussian_column_pass_avx2,
     rte_gaussian_row_pass_avx2},
    {{"gaussian_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     rte_gaussian_column_pass_avx512,
     rte_gaussian_row_pass_avx512},
#endif
    {{"gaussian_c", 0}, rte_gaussian_column_pass_c, rte_gaussian_row_pass_c},
};

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
        fail_msg("%s column pass width %d ksize %d split %d differs", v->head.name, (int)width,
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
        fail_msg("%s row pass width %d ksize %d split %d differs", v->head.name, (int)width,
                 (int)ksize, split);
    test_free(hi);
    test_free(lo);
    test_free(dwant);
    test_free(dgot);
}

static void gaussian_passes(const void *variant, uint32_t *seed)
{
    const gaussian_variant *v = variant;
    for (int32_t ksize = 1; ksize <= RTE_GAUSSIAN_MAX_KSIZE; ksize += 2)
        for (int split = 0; split <= 1; split++) {
            for (int32_t w = 1; w <= 80; w++)
                check_gaussian(v, w, ksize, split, seed);
            for (int k = 0; k < 4; k++)
                check_gaussian(v, 81 + (int32_t)(unit_rand(seed) % 2000), ksize, split, seed);
        }
}

DEFINE_PICK(gaussian, gaussian_variants, gaussian_variant, rte_gaussian_rows,
            rte_gaussian_rows_select(features), v->column == p.column && v->row == p.row)

/* Morphology rows: each variant against the C build of the same loops. */
typedef struct morph_variant {
    variant_head head;
    rte_morph_op2_fn op2;
    rte_morph_reduce_fn reduce;
} morph_variant;

static const morph_variant morph_variants[] = {
#ifdef RTE_SIMD_X86
    {{"morph_avx2", RTE_CPU_X86_AVX2}, rte_morph_row_op2_avx2, rte_morph_reduce_rows_avx2},
    {{"morph_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     rte_morph_row_op2_avx512,
     rte_morph_reduce_rows_avx512},
#endif
    {{"morph_c", 0}, rte_morph_row_op2_c, rte_morph_reduce_rows_c},
};

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
        fail_msg("%s reduce width %d count %d acc %d max %d differs", v->head.name, (int)width,
                 (int)count, accumulate, is_max);
    /* op2, also in place (d == a) */
    rte_morph_row_op2_c(want, want, rows[0], width, is_max);
    v->op2(got, got, rows[0], width, is_max);
    if (memcmp(want, got, n) != 0)
        fail_msg("%s op2 width %d max %d differs", v->head.name, (int)width, is_max);
    test_free(src);
    test_free(want);
    test_free(got);
}

static void morph_rows(const void *variant, uint32_t *seed)
{
    const morph_variant *v = variant;
    for (int32_t count = 1; count <= MORPH_MAX_ROWS; count++)
        for (int m = 0; m < 4; m++) {
            bool accumulate = m & 1, is_max = m & 2;
            for (int32_t w = 1; w <= 70; w++)
                check_morph(v, w, count, accumulate, is_max, seed);
            check_morph(v, 71 + (int32_t)(unit_rand(seed) % 2000), count, accumulate, is_max, seed);
        }
}

DEFINE_PICK(morph, morph_variants, morph_variant, rte_morph_rows, rte_morph_rows_select(features),
            v->op2 == p.op2 && v->reduce == p.reduce)

/* Canny rows (aperture 3, L1): each variant against the C reference. */
typedef struct canny_variant {
    variant_head head;
    rte_canny_sobel_fn sobel;
    rte_canny_nms_fn nms;
} canny_variant;

static const canny_variant canny_variants[] = {
#ifdef RTE_SIMD_X86
    {{"canny_avx2", RTE_CPU_X86_AVX2}, rte_canny_sobel_row_avx2, rte_canny_nms_row_avx2},
    {{"canny_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     rte_canny_sobel_row_avx512,
     rte_canny_nms_row_avx512},
#endif
#ifdef RTE_SIMD_NEON
    {{"canny_neon", RTE_CPU_ARM_NEON}, rte_canny_sobel_row_neon, rte_canny_nms_row_neon},
#endif
    {{"canny_c", 0}, rte_canny_sobel_row_c, rte_canny_nms_row_c},
};

/* A random int16 in [-range, range]. */
static int16_t rand_s16(uint32_t *seed, int32_t range)
{
    return (int16_t)((int32_t)(unit_rand(seed) % (uint32_t)(2 * range + 1)) - range);
}

/* Sobel rows: three rows `stride` apart in one buffer (stride odd and
 * larger than the row, the last row ending at the buffer's end). */
static void check_canny_sobel(const canny_variant *v, int32_t width, uint32_t *seed)
{
    const size_t stride = (size_t)width + 1 + 2 * (unit_rand(seed) % 8);
    const size_t bytes = 2 * stride + (size_t)width;
    uint8_t *src = test_malloc(bytes);
    fill_random(src, bytes, seed, width % 7 == 0);
    const size_t n = (size_t)width + GUARD;
    int16_t *want = test_malloc(3 * n * sizeof *want), *got = test_malloc(3 * n * sizeof *got);
    for (size_t i = 0; i < 3 * n; i++)
        want[i] = got[i] = (int16_t)0x7EEE;
    rte_canny_sobel_row_c(src, src + stride, src + 2 * stride, want, want + n, want + 2 * n, width);
    v->sobel(src, src + stride, src + 2 * stride, got, got + n, got + 2 * n, width);
    for (size_t i = 0; i < 3 * n; i++)
        if (want[i] != got[i])
            fail_msg("%s sobel width %d: %s[%zu] is %d, reference %d", v->head.name, (int)width,
                     i < n       ? "dx"
                     : i < 2 * n ? "dy"
                                 : "mag",
                     i % n, got[i], want[i]);
    test_free(src);
    test_free(want);
    test_free(got);
}

/* Suppression rows: magnitude rows with their zero ends; `range` small
 * makes ties between neighbours and zero derivatives common. */
static void check_canny_nms(const canny_variant *v, int32_t width, int32_t range, uint32_t *seed)
{
    const size_t padded = (size_t)width + 2;
    int16_t *mag = test_malloc(3 * padded * sizeof *mag);
    int16_t *grad = test_malloc(2 * (size_t)width * sizeof *grad);
    for (size_t r = 0; r < 3; r++) {
        int16_t *row = mag + r * padded;
        for (size_t x = 0; x < padded; x++)
            row[x] = (int16_t)(unit_rand(seed) % (uint32_t)(2 * range + 1));
        row[0] = row[padded - 1] = 0;
    }
    for (size_t x = 0; x < 2 * (size_t)width; x++)
        grad[x] = rand_s16(seed, range);
    /* thresholds anywhere from -1 to just above the largest magnitude */
    const int16_t low = (int16_t)((int32_t)(unit_rand(seed) % (uint32_t)(2 * range + 3)) - 1);
    const int16_t high = (int16_t)(low + (int32_t)(unit_rand(seed) % (uint32_t)(2 * range + 2)));
    const size_t n = (size_t)width + GUARD;
    uint8_t *want = test_malloc(n), *got = test_malloc(n);
    memset(want, 0xEE, n);
    memset(got, 0xEE, n);
    rte_canny_nms_row_c(mag + 1, mag + padded + 1, mag + 2 * padded + 1, grad, grad + width, want,
                        width, low, high);
    v->nms(mag + 1, mag + padded + 1, mag + 2 * padded + 1, grad, grad + width, got, width, low,
           high);
    for (size_t i = 0; i < n; i++)
        if (want[i] != got[i])
            fail_msg("%s nms width %d range %d: code %zu is %u, reference %u", v->head.name,
                     (int)width, (int)range, i, got[i], want[i]);
    test_free(mag);
    test_free(grad);
    test_free(want);
    test_free(got);
}

static void canny_rows(const void *variant, uint32_t *seed)
{
    const canny_variant *v = variant;
    static const int32_t ranges[] = {1, 3, 40, 1020};
    for (int32_t w = 1; w <= 67; w++)
        for (int k = 0; k < 8; k++) {
            check_canny_sobel(v, w, seed);
            check_canny_nms(v, w, ranges[k % 4], seed);
        }
    for (int k = 0; k < 16; k++) {
        const int32_t w = 68 + (int32_t)(unit_rand(seed) % 2000);
        check_canny_sobel(v, w, seed);
        check_canny_nms(v, w, ranges[k % 4], seed);
    }
}

DEFINE_PICK(canny, canny_variants, canny_variant, rte_canny_rows, rte_canny_rows_select(features),
            v->sobel == p.sobel && v->nms == p.nms)

/* Threshold rows: each variant against the C reference, every type, also
 * in place. */
typedef struct threshold_variant {
    variant_head head;
    rte_threshold_row_fn row;
} threshold_variant;

static const threshold_variant threshold_variants[] = {
#ifdef RTE_SIMD_X86
    {{"threshold_avx2", RTE_CPU_X86_AVX2}, rte_threshold_row_avx2},
    {{"threshold_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512}, rte_threshold_row_avx512},
#endif
#ifdef RTE_SIMD_NEON
    {{"threshold_neon", RTE_CPU_ARM_NEON}, rte_threshold_row_neon},
#endif
    {{"threshold_c", 0}, rte_threshold_row_c},
};

static void check_threshold(const threshold_variant *v, int32_t width, int type, uint32_t *seed)
{
    const size_t so = unit_rand(seed) % MAX_OFFSET, n = (size_t)width + GUARD;
    uint8_t *src = test_malloc(so + (size_t)width);
    fill_random(src + so, (size_t)width, seed, width % 7 == 0);
    const uint8_t t = (uint8_t)(unit_rand(seed) % 255), maxval = (uint8_t)unit_rand(seed);
    uint8_t *want = test_malloc(n), *got = test_malloc(n);
    memset(want, 0xEE, n);
    memset(got, 0xEE, n);
    rte_threshold_row_c(src + so, want, width, type, t, maxval);
    v->row(src + so, got, width, type, t, maxval);
    if (memcmp(want, got, n) != 0)
        fail_msg("%s width %d type %d t %u differs", v->head.name, (int)width, type, t);
    /* in place */
    memcpy(got, src + so, (size_t)width);
    v->row(got, got, width, type, t, maxval);
    if (memcmp(want, got, n) != 0)
        fail_msg("%s in place width %d type %d t %u differs", v->head.name, (int)width, type, t);
    test_free(src);
    test_free(want);
    test_free(got);
}

static void threshold_rows(const void *variant, uint32_t *seed)
{
    const threshold_variant *v = variant;
    for (int type = RTE_THRESH_BINARY; type <= RTE_THRESH_TOZERO_INV; type++) {
        for (int32_t w = 1; w <= 67; w++)
            for (int k = 0; k < 4; k++)
                check_threshold(v, w, type, seed);
        for (int k = 0; k < 8; k++)
            check_threshold(v, 68 + (int32_t)(unit_rand(seed) % 3000), type, seed);
    }
}

DEFINE_PICK(threshold, threshold_variants, threshold_variant, rte_threshold_row_fn,
            rte_threshold_row_select(features), v->row == p)

/* Gradient rows (Sobel, Scharr, Laplacian, Canny's apertures 5 and 7):
 * each variant against the C reference, random taps of every length and
 * the special Sobel 3 taps, every row mode. */
typedef struct grad_variant {
    variant_head head;
    rte_grad_column_fn column;
    rte_grad_row_fn row;
} grad_variant;

static const grad_variant grad_variants[] = {
#ifdef RTE_SIMD_X86
    {{"grad_avx2", RTE_CPU_X86_AVX2}, rte_grad_column_avx2, rte_grad_row_avx2},
    {{"grad_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     rte_grad_column_avx512,
     rte_grad_row_avx512},
#endif
    {{"grad_c", 0}, rte_grad_column_c, rte_grad_row_c},
};

/* n taps: [1 2 1] or [-1 0 1] for some 3-tap cases, else random with
 * sum |tap| <= `l1`. */
static void random_grad_taps(int16_t *taps, int32_t n, int32_t l1, uint32_t *seed)
{
    static const int16_t sobel[2][3] = {{1, 2, 1}, {-1, 0, 1}};
    const uint32_t r = unit_rand(seed) % 4;
    if (n == 3 && r < 2) {
        memcpy(taps, sobel[r], sizeof sobel[r]);
        return;
    }
    for (int32_t i = 0; i < n; i++)
        taps[i] = rand_s16(seed, l1 / n);
}

static void check_grad(const grad_variant *v, int32_t width, int32_t n, int mode, uint32_t *seed)
{
    const size_t guard = (size_t)width + GUARD;
    int16_t taps[RTE_GRAD_MAX_TAPS];
    /* column pass: |sum| <= 128 * 255 fits int16 */
    random_grad_taps(taps, n, 128, seed);
    const uint8_t *rows[RTE_GRAD_MAX_TAPS];
    uint8_t *src = test_malloc((size_t)width + (size_t)n);
    fill_random(src, (size_t)width + (size_t)n, seed, width % 7 == 0);
    for (int32_t j = 0; j < n; j++)
        rows[j] = src + unit_rand(seed) % (uint32_t)(n + 1);
    int16_t *want = test_malloc(guard * sizeof *want), *got = test_malloc(guard * sizeof *got);
    for (size_t i = 0; i < guard; i++)
        want[i] = got[i] = (int16_t)0x7EEE;
    rte_grad_column_c(rows, width, taps, n, want);
    v->column(rows, width, taps, n, got);
    if (memcmp(want, got, guard * sizeof *want) != 0)
        fail_msg("%s column pass width %d taps %d differs", v->head.name, (int)width, (int)n);
    /* row pass over a padded row: small values when the sums must fit */
    random_grad_taps(taps, n, mode == RTE_ROW_FITS ? 64 : 4096, seed);
    int16_t *padded = test_malloc(((size_t)width + (size_t)n) * sizeof *padded);
    for (size_t i = 0; i < (size_t)width + (size_t)n; i++)
        padded[i] = rand_s16(seed, mode == RTE_ROW_FITS ? 511 : 32767);
    for (size_t i = 0; i < guard; i++)
        want[i] = got[i] = (int16_t)0x7EEE;
    rte_grad_row_c(padded + n / 2, taps, n, want, width, mode);
    v->row(padded + n / 2, taps, n, got, width, mode);
    if (memcmp(want, got, guard * sizeof *want) != 0)
        fail_msg("%s row pass width %d taps %d mode %d differs", v->head.name, (int)width, (int)n,
                 mode);
    test_free(src);
    test_free(padded);
    test_free(want);
    test_free(got);
}

static void grad_rows(const void *variant, uint32_t *seed)
{
    const grad_variant *v = variant;
    for (int32_t n = 1; n <= RTE_GRAD_MAX_TAPS; n += 2)
        for (int mode = RTE_ROW_FITS; mode <= RTE_ROW_ROUND_DIV16; mode++) {
            for (int32_t w = 1; w <= 67; w++)
                check_grad(v, w, n, mode, seed);
            for (int k = 0; k < 4; k++)
                check_grad(v, 68 + (int32_t)(unit_rand(seed) % 2000), n, mode, seed);
        }
}

DEFINE_PICK(grad, grad_variants, grad_variant, rte_grad_rows, rte_grad_rows_select(features),
            v->column == p.column && v->row == p.row)

/* The lane path's colour cue rows: each variant against the C reference,
 * random thresholds (256 as an "off" mask too), both channel orders. */
typedef struct lane_cue_variant {
    variant_head head;
    rte_lane_cue_row_fn row;
} lane_cue_variant;

static const lane_cue_variant lane_cue_variants[] = {
#ifdef RTE_SIMD_X86
    {{"lane_cue_avx2", RTE_CPU_X86_AVX2}, rte_lane_cue_row_avx2},
    {{"lane_cue_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512}, rte_lane_cue_row_avx512},
#endif
    {{"lane_cue_c", 0}, rte_lane_cue_row_c},
};

/* Rules from the random word r (bits 0-27): thresholds anywhere near
 * their defaults, each test off (threshold 256) a quarter of the time. */
static rte_lane_cue random_cue(uint32_t r)
{
    return (rte_lane_cue){
        .white_min = (uint8_t)(150 + r % 100),
        .white_on = (r >> 8) % 4 ? 0xFF : 0,
        .yellow_min = (uint8_t)(100 + (r >> 10) % 120),
        .yellow_on = (r >> 17) % 4 ? 0xFF : 0,
        .yellow_b_margin = (uint8_t)((r >> 19) % 80),
        .dim_q8 = (uint16_t)((r >> 23) % 257),
    };
}

/* check(v, width, seed) on every width 1..67 eight times, then on 32
 * random widths up to 3067 (and `extra` widths from extra_from). */
static void each_width(void (*check)(const void *, int32_t, uint32_t *), const void *v,
                       uint32_t *seed, int32_t extra_from, int32_t extra)
{
    for (int32_t w = 1; w <= 67; w++)
        for (int k = 0; k < 8; k++)
            check(v, w, seed);
    for (int32_t w = extra_from; w < extra_from + extra; w++)
        check(v, w, seed);
    for (int k = 0; k < 32; k++)
        check(v, 68 + (int32_t)(unit_rand(seed) % 3000), seed);
}

static void check_lane_cue(const void *variant, int32_t width, uint32_t *seed)
{
    const lane_cue_variant *v = variant;
    const size_t so = unit_rand(seed) % MAX_OFFSET, n = (size_t)width + GUARD;
    uint8_t *bgr = test_malloc(so + 3 * (size_t)width), *gray = test_malloc((size_t)width);
    /* extremes often, and colours near the thresholds below */
    fill_random(bgr + so, 3 * (size_t)width, seed, width % 7 == 0);
    fill_random(gray, (size_t)width, seed, 0);
    const uint32_t r = unit_rand(seed);
    const rte_lane_cue cue = random_cue(r);
    const bool rgb = (r >> 31) != 0;
    uint8_t *want = test_malloc(n), *got = test_malloc(n);
    memset(want, 0xEE, n);
    memset(got, 0xEE, n);
    rte_lane_cue_row_c(gray, bgr + so, want, width, &cue, rgb);
    v->row(gray, bgr + so, got, width, &cue, rgb);
    if (memcmp(want, got, n) != 0)
        fail_msg("%s width %d rgb %d differs", v->head.name, (int)width, rgb);
    test_free(bgr);
    test_free(gray);
    test_free(want);
    test_free(got);
}

static void lane_cue_rows(const void *variant, uint32_t *seed)
{
    each_width(check_lane_cue, variant, seed, 0, 0);
}

DEFINE_PICK(lane_cue, lane_cue_variants, lane_cue_variant, rte_lane_cue_row_fn,
            rte_lane_cue_row_select(features), v->row == p)

/* The same cue from Y and half-resolution chroma: each variant against the
 * C reference, one and two rows, planar and interleaved chroma, both
 * parities, widths across the kernel's 128-block steps, chroma near
 * neutral as often as anywhere. */
typedef struct lane_cue_chroma_variant {
    variant_head head;
    rte_lane_cue_chroma_row_fn row;
} lane_cue_chroma_variant;

static const lane_cue_chroma_variant lane_cue_chroma_variants[] = {
#ifdef RTE_SIMD_X86
    {{"lane_cue_chroma_avx2", RTE_CPU_X86_AVX2}, rte_lane_cue_chroma_row_avx2},
    {{"lane_cue_chroma_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     rte_lane_cue_chroma_row_avx512},
#endif
    {{"lane_cue_chroma_c", 0}, rte_lane_cue_chroma_row_c},
};

static void check_lane_cue_chroma(const void *variant, int32_t width, uint32_t *seed)
{
    const lane_cue_chroma_variant *v = variant;
    const uint32_t r = unit_rand(seed);
    const bool odd = (r >> 30) & 1, two = (r >> 29) & 1, interleaved = (r >> 28) & 1;
    const size_t n = (size_t)width + GUARD, blocks = ((size_t)width + odd + 1) / 2;
    const size_t so = unit_rand(seed) % MAX_OFFSET;
    uint8_t *gray = test_malloc(so + 2 * (size_t)width), *chroma = test_malloc(2 * blocks);
    fill_random(gray + so, 2 * (size_t)width, seed, width % 7 == 0);
    for (size_t i = 0; i < 2 * blocks; i++) { /* half near neutral, half anywhere */
        const uint32_t c = unit_rand(seed);
        chroma[i] = (uint8_t)(c & 1 ? 108u + (c >> 1) % 41 : c >> 8);
    }
    const uint8_t *cb = chroma, *cr = interleaved ? chroma + 1 : chroma + blocks;
    const rte_lane_cue cue = random_cue(r);
    uint8_t *want = test_malloc(2 * n), *got = test_malloc(2 * n);
    memset(want, 0xEE, 2 * n);
    memset(got, 0xEE, 2 * n);
    const uint8_t *g[2] = {gray + so, two ? gray + so + width : NULL};
    uint8_t *dw[2] = {want, two ? want + n : NULL}, *dg[2] = {got, two ? got + n : NULL};
    rte_lane_cue_chroma_row_c(g, cb, cr, interleaved, dw, width, odd, &cue);
    v->row(g, cb, cr, interleaved, dg, width, odd, &cue);
    if (memcmp(want, got, 2 * n) != 0)
        fail_msg("%s width %d odd %d rows %d interleaved %d differs", v->head.name, (int)width, odd,
                 two ? 2 : 1, interleaved);
    test_free(gray);
    test_free(chroma);
    test_free(want);
    test_free(got);
}

static void lane_cue_chroma_rows(const void *variant, uint32_t *seed)
{
    each_width(check_lane_cue_chroma, variant, seed, 250, 13); /* the 128-block step */
}

DEFINE_PICK(lane_cue_chroma, lane_cue_chroma_variants, lane_cue_chroma_variant,
            rte_lane_cue_chroma_row_fn, rte_lane_cue_chroma_row_select(features), v->row == p)

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
        rte_image_u8c3 img = {w, h, stride, src};
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

/* A random Hough configuration for the kernel tests: w x h up to 4000 x
 * 4000 (w below max_w + 1), rho and theta picked by k; its rho bins and
 * rho bias. */
typedef struct hough_case {
    int32_t w, h, numrho, bias;
} hough_case;

static hough_case random_hough_config(rte_hough_config *cfg, int k, uint32_t max_w, uint32_t *seed)
{
    static const double rhos[] = {1.0, 0.5, 2.5},
                        thetas[] = {PI_SIMD / 180, PI_SIMD / 360, PI_SIMD / 1024};
    hough_case c;
    c.w = 1 + (int32_t)(unit_rand(seed) % max_w);
    c.h = 1 + (int32_t)(unit_rand(seed) % 4000);
    assert_int_equal(
        rte_hough_config_init(cfg, c.w, c.h, rhos[k % 3], thetas[(k / 3) % 3], 0.0, PI_SIMD),
        RTE_OK);
    c.numrho = rte_hough_rho_bins(cfg, c.w, c.h);
    c.bias = rte_hough_rho_bias(cfg, c.numrho);
    return c;
}

/* Hough segment bins: each variant against the C reference on the trig
 * tables of random configurations (sizes, rho, theta), random points of
 * the configured size, angle counts that end anywhere in a vector. */
typedef struct hough_bins_variant {
    variant_head head;
    rte_hough_bins_fn bins;
} hough_bins_variant;

static const hough_bins_variant hough_bins_variants[] = {
#ifdef RTE_SIMD_X86
    {{"hough_bins_avx2", RTE_CPU_X86_AVX2}, rte_hough_bins_avx2},
    {{"hough_bins_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512}, rte_hough_bins_avx512},
#endif
    {{"hough_bins_c", 0}, rte_hough_bins_c},
};

static void hough_bins(const void *variant, uint32_t *seed)
{
    const hough_bins_variant *v = variant;
    static rte_hough_config cfg;
    int32_t want[RTE_HOUGH_MAX_ANGLES + GUARD], got[RTE_HOUGH_MAX_ANGLES + GUARD],
        row_base[RTE_HOUGH_MAX_ANGLES];
    for (int k = 0; k < 60; k++) {
        const hough_case hc = random_hough_config(&cfg, k, 4000, seed);
        const int32_t w = hc.w, h = hc.h, numrho = hc.numrho, bias = hc.bias;
        for (int32_t a = 0; a < cfg.num_angles; a++)
            row_base[a] = a * numrho;
        for (int p = 0; p < 20; p++) {
            const int32_t n =
                p == 0 ? cfg.num_angles : 1 + (int32_t)(unit_rand(seed) % (uint32_t)cfg.num_angles);
            const int32_t x = (int32_t)(unit_rand(seed) % (uint32_t)w),
                          y = (int32_t)(unit_rand(seed) % (uint32_t)h);
            memset(want, 0xEE, sizeof want);
            memset(got, 0xEE, sizeof got);
            rte_hough_bins_c(cfg.rho_cos, cfg.rho_sin, n, x, y, bias, cfg.trig_shift, row_base,
                             want);
            v->bins(cfg.rho_cos, cfg.rho_sin, n, x, y, bias, cfg.trig_shift, row_base, got);
            if (memcmp(want, got, sizeof want) != 0)
                fail_msg("%s %dx%d point (%d, %d) n %d differs", v->head.name, (int)w, (int)h,
                         (int)x, (int)y, (int)n);
            for (int32_t a = 0; a < n; a++)
                assert_true(got[a] >= a * numrho && got[a] < (a + 1) * numrho);
        }
    }
}

DEFINE_PICK(hough_bins, hough_bins_variants, hough_bins_variant, rte_hough_bins_fn,
            rte_hough_bins_select(features), v->bins == p)

/* Hough line rows: each variant against the C reference. Bins on the trig
 * tables of random configurations, blocks of random packed points of the
 * configured size (every count 1..40 and random larger ones, so blocks end
 * anywhere in a vector), every angle in turn; sums of random copies (up to
 * 65535 each) into random cells, at every length 1..40 and random longer
 * ones, with guard cells after the rows. */
typedef struct hough_line_rows_variant {
    variant_head head;
    rte_hough_line_rows rows;
} hough_line_rows_variant;

static const hough_line_rows_variant hough_line_rows_variants[] = {
#ifdef RTE_SIMD_X86
    {{"hough_line_rows_avx2", RTE_CPU_X86_AVX2},
     {rte_hough_point_bins_avx2, rte_hough_sum_copies_avx2}},
    {{"hough_line_rows_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     {rte_hough_point_bins_avx2, rte_hough_sum_copies_avx512}},
#endif
    {{"hough_line_rows_c", 0}, {rte_hough_point_bins_c, rte_hough_sum_copies_c}},
};

static void hough_line_sums(const hough_line_rows_variant *v, uint32_t *seed)
{
    enum { MAX_CELLS = 900, CSTEP = MAX_CELLS + GUARD };
    static uint16_t want_copies[RTE_HOUGH_LINE_COPIES * CSTEP],
        got_copies[RTE_HOUGH_LINE_COPIES * CSTEP];
    static int32_t want[MAX_CELLS + GUARD], got[MAX_CELLS + GUARD];
    for (int k = 0; k < 60; k++) {
        const int32_t n = k < 40 ? k + 1 : 1 + (int32_t)(unit_rand(seed) % MAX_CELLS);
        for (size_t i = 0; i < COUNT_OF(want_copies); i++)
            want_copies[i] = (uint16_t)(k % 3 == 0 ? 65535 : unit_rand(seed));
        for (size_t i = 0; i < COUNT_OF(want); i++)
            want[i] = (int32_t)(unit_rand(seed) >> 2);
        memcpy(got_copies, want_copies, sizeof got_copies);
        memcpy(got, want, sizeof got);
        rte_hough_sum_copies_c(want, want_copies, CSTEP, n);
        v->rows.sum(got, got_copies, CSTEP, n);
        if (memcmp(want, got, sizeof want) != 0 ||
            memcmp(want_copies, got_copies, sizeof want_copies) != 0)
            fail_msg("%s sum of %d cells differs", v->head.name, (int)n);
        for (int32_t c = 0; c < RTE_HOUGH_LINE_COPIES; c++)
            for (int32_t i = 0; i < n; i++)
                assert_int_equal(got_copies[c * CSTEP + i], 0);
    }
}

static void hough_line_rows(const void *variant, uint32_t *seed)
{
    const hough_line_rows_variant *v = variant;
    enum { MAX_POINTS = 700 };
    static rte_hough_config cfg;
    uint32_t pts[MAX_POINTS];
    int32_t want[MAX_POINTS + GUARD], got[MAX_POINTS + GUARD];
    for (int k = 0; k < 60; k++) {
        /* every 4th map at most 3 pixels wide: the largest trig values */
        const hough_case hc = random_hough_config(&cfg, k, k % 4 ? 4000 : 3, seed);
        const int32_t w = hc.w, h = hc.h, numrho = hc.numrho, bias = hc.bias;
        const int32_t n = k < 40 ? k + 1 : 1 + (int32_t)(unit_rand(seed) % MAX_POINTS);
        for (int32_t i = 0; i < n; i++)
            pts[i] = (unit_rand(seed) % (uint32_t)h) << 16 | (unit_rand(seed) % (uint32_t)w);
        if (k == 0)
            pts[0] = (uint32_t)(h - 1) << 16 | (uint32_t)(w - 1); /* the far corner */
        for (int32_t a = 0; a < cfg.num_angles; a++) {
            const int32_t c = cfg.rho_cos[a], s = cfg.rho_sin[a];
            memset(want, 0xEE, sizeof want);
            memset(got, 0xEE, sizeof got);
            rte_hough_point_bins_c(pts, n, c, s, bias, cfg.trig_shift, want);
            v->rows.bins(pts, n, c, s, bias, cfg.trig_shift, got);
            if (memcmp(want, got, sizeof want) != 0)
                fail_msg("%s %dx%d angle %d n %d differs", v->head.name, (int)w, (int)h, (int)a,
                         (int)n);
            for (int32_t i = 0; i < n; i++)
                assert_true(got[i] >= 0 && got[i] < numrho);
        }
    }
    hough_line_sums(v, seed);
}

DEFINE_PICK(hough_line_rows, hough_line_rows_variants, hough_line_rows_variant, rte_hough_line_rows,
            rte_hough_line_rows_select(features), v->rows.bins == p.bins && v->rows.sum == p.sum)
/* Hough circle votes: each variant against the C reference on random
 * steps (any direction, up to a pixel), run lengths that end anywhere in a
 * vector and beyond a chunk, ring masks, from a start whose whole run stays
 * inside the accumulator. */
typedef struct circle_votes_variant {
    variant_head head;
    rte_circle_votes_fn votes;
} circle_votes_variant;

static const circle_votes_variant circle_votes_variants[] = {
#ifdef RTE_SIMD_X86
    {{"circle_votes_avx2", RTE_CPU_X86_AVX2}, rte_circle_votes_avx2},
    {{"circle_votes_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512}, rte_circle_votes_avx512},
#endif
    {{"circle_votes_c", 0}, rte_circle_votes_c},
};

static void circle_votes(const void *variant, uint32_t *seed)
{
    const circle_votes_variant *v = variant;
    enum { ROWS = 256, STEP = 300 };
    static int32_t want[ROWS * STEP], got[ROWS * STEP];
    for (int k = 0; k < 400; k++) {
        const int32_t n = (int32_t)(unit_rand(seed) % 140);
        const int32_t sx = (int32_t)(unit_rand(seed) % 2049) - 1024,
                      sy = (int32_t)(unit_rand(seed) % 2049) - 1024;
        const uint32_t mask = k % 2 ? ROWS - 1 : 127;
        /* columns 0 .. 290 and rows 0 .. mask at both ends of the run */
        const int32_t span_x = n * abs(sx), span_y = n * abs(sy);
        if (span_x > 290 * 1024 || span_y > (int32_t)mask * 1024)
            continue;
        const uint32_t ux =
                           (uint32_t)((sx < 0 ? span_x : 0) +
                                      (int32_t)(unit_rand(seed) % (uint32_t)(291 * 1024 - span_x))),
                       uy = (uint32_t)((sy < 0 ? span_y : 0) +
                                       (int32_t)(unit_rand(seed) % (uint32_t)(1024 + span_y)) +
                                       (int32_t)(unit_rand(seed) % 4) * (int32_t)(mask + 1) * 1024);
        memset(want, 0, sizeof want);
        memset(got, 0, sizeof got);
        rte_circle_votes_c(want, mask, STEP, ux, uy, (uint32_t)sx, (uint32_t)sy, n);
        v->votes(got, mask, STEP, ux, uy, (uint32_t)sx, (uint32_t)sy, n);
        if (memcmp(want, got, sizeof want) != 0)
            fail_msg("%s n %d step (%d, %d) differs", v->head.name, (int)n, (int)sx, (int)sy);
        int64_t total = 0;
        for (int32_t i = 0; i < ROWS * STEP; i++)
            total += got[i];
        assert_int_equal(total, n + 1);
    }
}

DEFINE_PICK(circle_votes, circle_votes_variants, circle_votes_variant, rte_circle_votes_fn,
            rte_circle_votes_select(features), v->votes == p)

/* The background rows (table estimate and threshold): each kernel of each
 * variant against the C reference on one random row, unaligned, with guard
 * bytes after the outputs; values to add within +-2^29 (no overflow). */
typedef struct background_variant {
    variant_head head;
    rte_background_rows rows;
} background_variant;

static const background_variant background_variants[] = {
#ifdef RTE_SIMD_X86
    {{"background_avx2", RTE_CPU_X86_AVX2},
     {rte_background_add_row_avx2, rte_background_store_row_avx2, rte_background_absdiff_row_avx2,
      rte_background_classify_row_avx2, rte_background_above_floor_row_avx2,
      rte_background_chroma_diff_row_avx2, rte_background_tint_row_avx2,
      rte_background_shade_row_avx2, rte_background_shade_class_row_avx2}},
    {{"background_avx512", RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512},
     {rte_background_add_row_avx512, rte_background_store_row_avx512,
      rte_background_absdiff_row_avx512, rte_background_classify_row_avx512,
      rte_background_above_floor_row_avx512, rte_background_chroma_diff_row_avx512,
      rte_background_tint_row_avx512, rte_background_shade_row_avx512,
      rte_background_shade_class_row_avx512}},
#endif
    {{"background_c", 0},
     {rte_background_add_row_c, rte_background_store_row_c, rte_background_absdiff_row_c,
      rte_background_classify_row_c, rte_background_above_floor_row_c,
      rte_background_chroma_diff_row_c, rte_background_tint_row_c, rte_background_shade_row_c,
      rte_background_shade_class_row_c}},
};

static void random_values(int32_t *p, int32_t n, uint32_t *seed)
{
    for (int32_t i = 0; i < n; i++)
        p[i] = (int32_t)(unit_rand(seed) % (1u << 30)) - (1 << 29);
}

static void check_background_row(const background_variant *v, int32_t w, uint32_t *seed)
{
    const rte_background_rows *c = &background_variants[COUNT_OF(background_variants) - 1].rows;
    const size_t o = unit_rand(seed) % MAX_OFFSET, n = o + (size_t)w + GUARD;
    uint8_t *s = test_malloc(n), *b = test_malloc(n), *t = test_malloc(n), *want = test_malloc(n),
            *got = test_malloc(n);
    int32_t *va = test_malloc(n * sizeof *va), *vb = test_malloc(n * sizeof *vb),
            *add = test_malloc(n * sizeof *add);
    fill_random(s, n, seed, w % 7 == 0);
    fill_random(b, n, seed, w % 5 == 0);
    fill_random(t, n, seed, w % 3 == 0);
    random_values(va, (int32_t)n, seed);
    random_values(add, (int32_t)n, seed);
    memcpy(vb, va, n * sizeof *va);
    c->add(va + o, add + o, w);
    v->rows.add(vb + o, add + o, w);
    if (memcmp(va, vb, n * sizeof *va) != 0)
        fail_msg("%s add width %d differs", v->head.name, (int)w);
    const struct {
        const char *name;
        int which;
    } bytes[] = {{"store", 0}, {"absdiff", 1},     {"classify", 2}, {"above_floor", 3},
                 {"tint", 4},  {"chroma_diff", 5}, {"shade", 6},    {"shade_class", 7}};
    const uint8_t low = (uint8_t)unit_rand(seed), high = (uint8_t)unit_rand(seed);
    const uint8_t bright = (uint8_t)(unit_rand(seed) % 3), dark = (uint8_t)(unit_rand(seed) % 3);
    uint8_t *mask = test_malloc(n);
    for (size_t i = 0; i < n; i++)
        mask[i] = unit_rand(seed) % 4 ? 255 : 0;
    const int32_t lo = (int32_t)(unit_rand(seed) % 1001),
                  hi = lo + (int32_t)(unit_rand(seed) % (uint32_t)(1001 - lo)),
                  tol = (int32_t)(unit_rand(seed) % 256);
    for (size_t k = 0; k < COUNT_OF(bytes); k++) {
        memset(want, 0xEE, n);
        memset(got, 0xEE, n);
        const rte_background_rows *r[2] = {c, &v->rows};
        uint8_t *out[2] = {want, got};
        for (int j = 0; j < 2; j++) {
            switch (bytes[k].which) {
            case 0: r[j]->store(va + o, out[j] + o, w); break;
            case 1: r[j]->absdiff(s + o, b + o, out[j] + o, w); break;
            case 2:
                r[j]->classify(s + o, b + o, t + o, out[j] + o, w, low, high, bright, dark);
                break;
            case 3:
                memcpy(out[j] + o, s + o, (size_t)w);
                r[j]->above_floor(out[j] + o, b + o, w);
                break;
            case 4:
                memcpy(out[j] + o, t + o, (size_t)w);
                r[j]->tint(s + o, b + o, out[j] + o, w, low, bright & 1, dark & 1);
                break;
            case 5: /* half as many samples, each written twice */
                r[j]->chroma_diff(s + o, b + o, t + o, s + n - GUARD - (size_t)(w + 1) / 2,
                                  out[j] + o, (w + 1) / 2);
                break;
            case 7: /* mask: a half-size row */
                memcpy(out[j] + o, s + o, (size_t)w);
                r[j]->shade_class(out[j] + o, mask + o, w);
                break;
            default: /* one output per chroma sample, from pixel 2h of each pair */
                r[j]->shade(s + o, b + o, t + o, s + n - GUARD - (size_t)w / 2,
                            b + n - GUARD - (size_t)w / 2, t + n - GUARD - (size_t)w / 2,
                            out[j] + o, w / 2, lo, hi, tol);
            }
        }
        if (memcmp(want, got, n) != 0)
            fail_msg("%s %s width %d differs", v->head.name, bytes[k].name, (int)w);
    }
    test_free(s);
    test_free(b);
    test_free(t);
    test_free(mask);
    test_free(want);
    test_free(got);
    test_free(va);
    test_free(vb);
    test_free(add);
}

static void background_rows(const void *variant, uint32_t *seed)
{
    const background_variant *v = variant;
    for (int32_t w = 1; w <= 67; w++)
        for (int k = 0; k < 4; k++)
            check_background_row(v, w, seed);
    for (int k = 0; k < 8; k++)
        check_background_row(v, 68 + (int32_t)(unit_rand(seed) % 3000), seed);
}

DEFINE_PICK(background, background_variants, background_variant, rte_background_rows,
            rte_background_rows_select(features), v->rows.add == p.add && v->rows.store == p.store)

/* A kernel family: its variants (structs that start with a variant_head),
 * which of them its *_select picks for a mask, and the comparison of one
 * variant with the C reference. */
typedef struct kernel_family {
    const char *name;
    const void *variants;
    size_t count, size;
    int (*pick)(uint32_t features);
    void (*check)(const void *variant, uint32_t *seed);
    uint32_t seed;
} kernel_family;

#define FAMILY(NAME, TABLE, CHECK, SEED)                                         \
    {                                                                            \
#NAME, TABLE, COUNT_OF(TABLE), sizeof TABLE[0], NAME##_pick, CHECK, SEED \
    }

static const kernel_family families[] = {
    FAMILY(bgr, bgr_variants, c3_to_gray_rows, 0x9E3779B9u),
    FAMILY(rgb, rgb_variants, c3_to_gray_rows, 0x7F4A7C15u),
    FAMILY(gaussian, gaussian_variants, gaussian_passes, 0xC0FFEEu),
    FAMILY(morph, morph_variants, morph_rows, 0xBADC0DEu),
    FAMILY(canny, canny_variants, canny_rows, 0x5EED1u),
    FAMILY(threshold, threshold_variants, threshold_rows, 0x7E57u),
    FAMILY(lane_cue, lane_cue_variants, lane_cue_rows, 0xC0105u),
    FAMILY(lane_cue_chroma, lane_cue_chroma_variants, lane_cue_chroma_rows, 0xC0C0Au),
    FAMILY(grad, grad_variants, grad_rows, 0x6AD1u),
    FAMILY(hough_bins, hough_bins_variants, hough_bins, 0x4B0Fu),
    FAMILY(hough_line_rows, hough_line_rows_variants, hough_line_rows, 0x11E5u),
    FAMILY(circle_votes, circle_votes_variants, circle_votes, 0xC1C1Eu),
    FAMILY(background, background_variants, background_rows, 0xBAC6u),
};

enum { FAMILY_COUNT = COUNT_OF(families), MASK_COUNT = COUNT_OF(feature_masks) };

static const variant_head *family_variant(const kernel_family *f, int i)
{
    return (const variant_head *)(const void *)((const char *)f->variants + (size_t)i * f->size);
}

/* The variant f picks for mask m; it must be one of f's and need nothing
 * outside the mask (else it would run on a CPU without its features). */
static int checked_pick(const kernel_family *f, const feature_mask *m)
{
    const int i = f->pick(m->bits);
    if (i < 0)
        fail_msg("%s: mask %s picks a variant that is not in the test's table", f->name, m->name);
    const variant_head *v = family_variant(f, i);
    if ((v->needs & ~m->bits) != 0)
        fail_msg("%s: mask %s picks %s, which needs features outside the mask", f->name, m->name,
                 v->name);
    return i;
}

/* One family under one mask (the test's state): the picked variant
 * against the C reference, unless this CPU lacks the features the variant
 * needs (skipped, and CMocka lists it) or an earlier mask picked it. */
typedef struct family_mask {
    const kernel_family *family;
    const feature_mask *mask;
} family_mask;

static void family_under_mask(void **state)
{
    const family_mask *fm = *state;
    const kernel_family *f = fm->family;
    const int i = checked_pick(f, fm->mask);
    const variant_head *v = family_variant(f, i);
    const uint32_t hw = rte_cpu_features_hw();
    if ((v->needs & ~hw) != 0) {
        char needs[64], has[64];
        print_message("%s under %s picks %s, which needs %s: this CPU has %s\n", f->name,
                      fm->mask->name, v->name, feature_names(v->needs, needs, sizeof needs),
                      feature_names(hw, has, sizeof has));
        skip();
    }
    for (const feature_mask *m = feature_masks; m < fm->mask; m++)
        if (f->pick(m->bits) == i) {
            print_message("%s under %s picks %s, compared under %s\n", f->name, fm->mask->name,
                          v->name, m->name);
            return;
        }
    print_message("%s under %s picks %s: against the C reference\n", f->name, fm->mask->name,
                  v->name);
    uint32_t seed = f->seed + (uint32_t)(fm->mask - feature_masks);
    f->check(v, &seed);
}

/* Whatever this CPU has: every variant of the tables is what some mask
 * picks (a variant no mask reaches would be tested here but never run). */
static void every_variant_is_picked(void **state)
{
    (void)state;
    for (size_t k = 0; k < FAMILY_COUNT; k++) {
        const kernel_family *f = &families[k];
        for (size_t i = 0; i < f->count; i++) {
            size_t m = 0;
            while (m < MASK_COUNT && checked_pick(f, &feature_masks[m]) != (int)i)
                m++;
            if (m == MASK_COUNT)
                fail_msg("%s: no feature mask picks %s", f->name, family_variant(f, (int)i)->name);
        }
    }
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
    if (hw & RTE_CPU_X86_AVX2) {
        const bool wide = (hw & RTE_CPU_X86_AVX512) != 0; /* the AVX-512 builds, else AVX2 */
        assert_true(rte_canny_rows_select(hw).sobel ==
                    (wide ? rte_canny_sobel_row_avx512 : rte_canny_sobel_row_avx2));
        assert_true(rte_threshold_row_select(hw) ==
                    (wide ? rte_threshold_row_avx512 : rte_threshold_row_avx2));
        assert_true(rte_hough_bins_select(hw) ==
                    (wide ? rte_hough_bins_avx512 : rte_hough_bins_avx2));
        assert_true(rte_hough_line_rows_select(hw).bins == rte_hough_point_bins_avx2);
        assert_true(rte_hough_line_rows_select(hw).sum ==
                    (wide ? rte_hough_sum_copies_avx512 : rte_hough_sum_copies_avx2));
        assert_true(rte_circle_votes_select(hw) ==
                    (wide ? rte_circle_votes_avx512 : rte_circle_votes_avx2));
        assert_true(rte_background_rows_select(hw).classify ==
                    (wide ? rte_background_classify_row_avx512 : rte_background_classify_row_avx2));
    }
#endif
#ifdef RTE_SIMD_NEON
    assert_true(hw & RTE_CPU_ARM_NEON);
    assert_true(rte_row_c3_to_gray_select(hw, false) == rte_row_bgr_to_gray_neon);
    assert_true(rte_canny_rows_select(hw).nms == rte_canny_nms_row_neon);
    assert_true(rte_threshold_row_select(hw) == rte_threshold_row_neon);
#endif
    assert_int_equal(setenv("RTE_FORCE_C", "1", 1), 0);
    assert_int_equal(rte_cpu_features(), 0);
    assert_true(rte_row_c3_to_gray_select(rte_cpu_features(), false) == rte_row_bgr_to_gray_c);
    assert_true(rte_row_c3_to_gray_select(rte_cpu_features(), true) == rte_row_rgb_to_gray_c);
    rte_gaussian_rows g = rte_gaussian_rows_select(rte_cpu_features());
    assert_true(g.column == rte_gaussian_column_pass_c && g.row == rte_gaussian_row_pass_c);
    rte_morph_rows m = rte_morph_rows_select(rte_cpu_features());
    assert_true(m.op2 == rte_morph_row_op2_c && m.reduce == rte_morph_reduce_rows_c);
    rte_canny_rows c = rte_canny_rows_select(rte_cpu_features());
    assert_true(c.sobel == rte_canny_sobel_row_c && c.nms == rte_canny_nms_row_c);
    assert_true(rte_threshold_row_select(rte_cpu_features()) == rte_threshold_row_c);
    assert_true(rte_hough_bins_select(rte_cpu_features()) == rte_hough_bins_c);
    rte_hough_line_rows hl = rte_hough_line_rows_select(rte_cpu_features());
    assert_true(hl.bins == rte_hough_point_bins_c && hl.sum == rte_hough_sum_copies_c);
    assert_true(rte_circle_votes_select(rte_cpu_features()) == rte_circle_votes_c);
    assert_true(rte_background_rows_select(rte_cpu_features()).absdiff ==
                rte_background_absdiff_row_c);
    assert_true(rte_lane_cue_row_select(rte_cpu_features()) == rte_lane_cue_row_c);
    assert_true(rte_lane_cue_chroma_row_select(rte_cpu_features()) == rte_lane_cue_chroma_row_c);
    rte_grad_rows gr = rte_grad_rows_select(rte_cpu_features());
    assert_true(gr.column == rte_grad_column_c && gr.row == rte_grad_row_c);
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
    rte_image_u8c3 img = {w, h, stride, src};
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

/* Random images of widths 1..67 with odd strides through the public
 * Canny (apertures 3 and 5, plain and fused) and threshold calls: forced
 * C and dispatched give the same bytes and leave the padding alone. */
static void forced_and_dispatched_canny_and_threshold_agree(void **state)
{
    (void)state;
    static uint8_t arena_memory[1 << 18];
    rte_arena arena;
    rte_arena_init(&arena, arena_memory, sizeof arena_memory);
    rte_gaussian_kernel k;
    assert_int_equal(rte_gaussian_kernel_init(&k, 5, 5, 0, 0), RTE_OK);
    uint32_t seed = 777;
    for (int32_t w = 1; w <= 67; w++) {
        const int32_t h = 1 + (int32_t)(unit_rand(&seed) % 40);
        const int32_t pad = 1 + 2 * (int32_t)(unit_rand(&seed) % 5); /* odd strides */
        rte_image_u8 src = unit_image_u8(w, h, pad, 0);
        for (int32_t y = 0; y < h; y++)
            fill_random(src.buf + (size_t)y * src.stride, (size_t)w, &seed, w % 7 == 0);
        rte_canny_params p, p5;
        const double low = unit_rand(&seed) % 300, high = unit_rand(&seed) % 600;
        assert_int_equal(rte_canny_params_init(&p, low, high, 3, false), RTE_OK);
        /* aperture 5, L2: the gradient rows */
        assert_int_equal(rte_canny_params_init(&p5, 8 * low, 8 * high, 5, true), RTE_OK);
        rte_threshold_params tp;
        assert_int_equal(rte_threshold_params_init(&tp, (rte_threshold_type)(w % 5),
                                                   unit_rand(&seed) % 256, 200, false),
                         RTE_OK);
        rte_image_u8 out[2][4];
        for (int forced = 0; forced < 2; forced++) {
            if (forced)
                assert_int_equal(setenv("RTE_FORCE_C", "1", 1), 0);
            for (int j = 0; j < 4; j++)
                out[forced][j] = unit_image_u8(w, h, pad, 0x11);
            assert_int_equal(rte_canny_u8(&src, &out[forced][0], &p, &arena), RTE_OK);
            assert_int_equal(rte_canny_blurred_u8(&src, &out[forced][1], &k, &p, &arena), RTE_OK);
            assert_int_equal(rte_threshold_u8(&src, &out[forced][2], &tp, NULL), RTE_OK);
            assert_int_equal(rte_canny_u8(&src, &out[forced][3], &p5, &arena), RTE_OK);
            assert_int_equal(unsetenv("RTE_FORCE_C"), 0);
        }
        for (int j = 0; j < 4; j++) {
            assert_memory_equal(out[0][j].buf, out[1][j].buf, (size_t)src.stride * h);
            unit_assert_padding_u8(&out[0][j]);
            test_free(out[0][j].buf);
            test_free(out[1][j].buf);
        }
        test_free(src.buf);
    }
}

int main(void)
{
    const struct CMUnitTest rest[] = {
        cmocka_unit_test(every_variant_is_picked),
        cmocka_unit_test(every_colour_matches_reference),
        cmocka_unit_test(force_c_selects_the_reference),
        cmocka_unit_test(forced_and_dispatched_images_agree),
        cmocka_unit_test(forced_and_dispatched_canny_and_threshold_agree),
    };
    /* first one test per family and mask, named family/mask */
    static family_mask states[FAMILY_COUNT * MASK_COUNT];
    static char names[FAMILY_COUNT * MASK_COUNT][48];
    static struct CMUnitTest tests[FAMILY_COUNT * MASK_COUNT + COUNT_OF(rest)];
    size_t n = 0;
    for (size_t k = 0; k < FAMILY_COUNT; k++)
        for (size_t m = 0; m < MASK_COUNT; m++, n++) {
            states[n] = (family_mask){&families[k], &feature_masks[m]};
            snprintf(names[n], sizeof names[n], "%s/%s", families[k].name, feature_masks[m].name);
            tests[n] = (struct CMUnitTest){names[n], family_under_mask, NULL, NULL, &states[n]};
        }
    memcpy(tests + n, rest, sizeof rest);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
