/* Morphology's row kernels (private to src/algo): elementwise min/max of
 * rows. Included by morphology.c, which builds them for the baseline target
 * as the C reference, and by simd/morphology_x86.c, which builds the same
 * loops for AVX2 (pminub/pmaxub on 32 bytes instead of 16). Bytes only, so
 * every build gives the same result; tests/unit/test_simd.c checks it. */
#ifndef RTEDGE_ALGO_MORPHOLOGY_ROWS_H
#define RTEDGE_ALGO_MORPHOLOGY_ROWS_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

/* d = op(a, b) elementwise. d may be a. */
static inline void row_op2(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n, bool is_max)
{
    if (is_max)
        for (int32_t x = 0; x < n; x++)
            d[x] = a[x] > b[x] ? a[x] : b[x];
    else
        for (int32_t x = 0; x < n; x++)
            d[x] = a[x] < b[x] ? a[x] : b[x];
}

#define MIN8(u, v) ((u) < (v) ? (u) : (v))
#define MAX8(u, v) ((u) > (v) ? (u) : (v))

/* Most rows reduced in one pass. */
#define ROW_PASS_MAX 8

/* d = op of the k rows r[0..k-1] elementwise, 2 <= k <= ROW_PASS_MAX, k a
 * constant in each copy: the row pointers are copied to locals first (a
 * byte store to d may alias the array), so each pass keeps them in
 * registers and the compiler vectorises it. */
static inline __attribute__((always_inline)) void row_opk(uint8_t *d, const uint8_t *const *r,
                                                          const int k, int32_t n, bool is_max)
{
    const uint8_t *p0 = r[0], *p1 = r[1], *p2 = r[k > 2 ? 2 : 0], *p3 = r[k > 3 ? 3 : 0];
    const uint8_t *p4 = r[k > 4 ? 4 : 0], *p5 = r[k > 5 ? 5 : 0], *p6 = r[k > 6 ? 6 : 0];
    const uint8_t *p7 = r[k > 7 ? 7 : 0];
#define ROW_OPK_BODY(OP)              \
    for (int32_t x = 0; x < n; x++) { \
        uint8_t u = OP(p0[x], p1[x]); \
        if (k > 2)                    \
            u = OP(u, p2[x]);         \
        if (k > 3)                    \
            u = OP(u, p3[x]);         \
        if (k > 4)                    \
            u = OP(u, p4[x]);         \
        if (k > 5)                    \
            u = OP(u, p5[x]);         \
        if (k > 6)                    \
            u = OP(u, p6[x]);         \
        if (k > 7)                    \
            u = OP(u, p7[x]);         \
        d[x] = u;                     \
    }
    if (is_max)
        ROW_OPK_BODY(MAX8)
    else
        ROW_OPK_BODY(MIN8)
#undef ROW_OPK_BODY
}

/* d = op of up to ROW_PASS_MAX rows in one pass (2 <= count). */
static inline void row_opn(uint8_t *d, const uint8_t *const *r, int32_t count, int32_t n,
                           bool is_max)
{
    switch (count) {
    case 2: row_opk(d, r, 2, n, is_max); break;
    case 3: row_opk(d, r, 3, n, is_max); break;
    case 4: row_opk(d, r, 4, n, is_max); break;
    case 5: row_opk(d, r, 5, n, is_max); break;
    case 6: row_opk(d, r, 6, n, is_max); break;
    case 7: row_opk(d, r, 7, n, is_max); break;
    default: row_opk(d, r, 8, n, is_max); break;
    }
}

/* d = op of the `count` rows r[0..count-1], or of d and them when
 * `accumulate` is set: up to ROW_PASS_MAX rows per pass, d being one of
 * them after the first. */
static inline void reduce_rows(uint8_t *d, const uint8_t *const *r, int32_t count, bool accumulate,
                               int32_t n, bool is_max)
{
    int32_t i = 0;
    if (!accumulate) {
        if (count == 1) {
            memcpy(d, r[0], (size_t)n);
            return;
        }
        i = count < ROW_PASS_MAX ? count : ROW_PASS_MAX;
        row_opn(d, r, i, n, is_max);
    }
    while (i < count) {
        const uint8_t *rows[ROW_PASS_MAX];
        int32_t k = 1;
        rows[0] = d;
        for (; k < ROW_PASS_MAX && i < count; k++)
            rows[k] = r[i++];
        row_opn(d, rows, k, n, is_max);
    }
}

#endif
