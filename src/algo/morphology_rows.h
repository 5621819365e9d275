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

/* d = op(d, op(a, b)) elementwise. */
static inline void row_acc2(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n, bool is_max)
{
    if (is_max)
        for (int32_t x = 0; x < n; x++) {
            uint8_t v = a[x] > b[x] ? a[x] : b[x];
            d[x] = d[x] > v ? d[x] : v;
        }
    else
        for (int32_t x = 0; x < n; x++) {
            uint8_t v = a[x] < b[x] ? a[x] : b[x];
            d[x] = d[x] < v ? d[x] : v;
        }
}

/* d = op(a, b, c) elementwise. */
static inline void row_op3(uint8_t *d, const uint8_t *a, const uint8_t *b, const uint8_t *c, int32_t n, bool is_max)
{
    if (is_max)
        for (int32_t x = 0; x < n; x++) {
            uint8_t v = a[x] > b[x] ? a[x] : b[x];
            d[x] = v > c[x] ? v : c[x];
        }
    else
        for (int32_t x = 0; x < n; x++) {
            uint8_t v = a[x] < b[x] ? a[x] : b[x];
            d[x] = v < c[x] ? v : c[x];
        }
}

#define MIN8(u, v) ((u) < (v) ? (u) : (v))
#define MAX8(u, v) ((u) > (v) ? (u) : (v))

/* d = op(a, b, c, e) elementwise: four rows in one pass. */
static inline void row_op4(uint8_t *d, const uint8_t *a, const uint8_t *b, const uint8_t *c, const uint8_t *e,
                    int32_t n, bool is_max)
{
    if (is_max)
        for (int32_t x = 0; x < n; x++) {
            uint8_t u = MAX8(a[x], b[x]), v = MAX8(c[x], e[x]);
            d[x] = MAX8(u, v);
        }
    else
        for (int32_t x = 0; x < n; x++) {
            uint8_t u = MIN8(a[x], b[x]), v = MIN8(c[x], e[x]);
            d[x] = MIN8(u, v);
        }
}

/* d = op(a, b, c, e, f) elementwise: five rows in one pass. */
static inline void row_op5(uint8_t *d, const uint8_t *a, const uint8_t *b, const uint8_t *c, const uint8_t *e,
                    const uint8_t *f, int32_t n, bool is_max)
{
    if (is_max)
        for (int32_t x = 0; x < n; x++) {
            uint8_t u = MAX8(a[x], b[x]), v = MAX8(c[x], e[x]);
            u = MAX8(u, f[x]);
            d[x] = MAX8(u, v);
        }
    else
        for (int32_t x = 0; x < n; x++) {
            uint8_t u = MIN8(a[x], b[x]), v = MIN8(c[x], e[x]);
            u = MIN8(u, f[x]);
            d[x] = MIN8(u, v);
        }
}

/* d = op of the `count` rows r[0..count-1], or of d and them when
 * `accumulate` is set: up to five rows in the first pass, then two per
 * pass. */
static inline void reduce_rows(uint8_t *d, const uint8_t *const *r, int32_t count, bool accumulate, int32_t n,
                        bool is_max)
{
    int32_t i = 0;
    if (!accumulate) {
        if (count == 1) {
            memcpy(d, r[0], (size_t)n);
            return;
        }
        /* an even remainder after the first pass keeps the pairs whole */
        int32_t head = count <= 5 ? count : 5 - (count - 5) % 2;
        if (head == 2)
            row_op2(d, r[0], r[1], n, is_max);
        else if (head == 3)
            row_op3(d, r[0], r[1], r[2], n, is_max);
        else if (head == 4)
            row_op4(d, r[0], r[1], r[2], r[3], n, is_max);
        else
            row_op5(d, r[0], r[1], r[2], r[3], r[4], n, is_max);
        i = head;
    }
    for (; i + 1 < count; i += 2)
        row_acc2(d, r[i], r[i + 1], n, is_max);
    if (i < count)
        row_op2(d, d, r[i], n, is_max);
}

#endif
