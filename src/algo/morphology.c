/* Erosion and dilation with flat structuring elements (per frame, integer
 * only). See include/rtedge/morphology.h.
 *
 * Pixels outside the image never win (OpenCV's default border), so rows
 * outside the image are simply left out and each loaded row is padded on
 * both sides with the neutral value (255 for min, 0 for max).
 *
 * Horizontal runs use doubling tables: level k of a padded row holds the
 * min (max) of 2^k consecutive pixels, and any run of length len is the
 * min of two overlapping level-k windows with 2^k <= len < 2^(k+1). Rows
 * stream through a ring of `height` slots, which also makes dst == src
 * safe: a source row is loaded before the output row that overwrites it.
 *  - A full rectangle is separable: each loaded row is reduced to its
 *    width-W minimum once, then the output row is the minimum of the H
 *    ring rows in its window (clipped to the image).
 *  - Any other element combines, for every run, two reads of the level
 *    tables of the run's source row. */
#include "rtedge/morphology.h"

#include <stdbool.h>
#include <string.h>

/* Largest k with 2^k <= n (n >= 1). */
static int32_t floor_log2(int32_t n)
{
    int32_t k = 0;
    while ((2 << k) <= n)
        k++;
    return k;
}

static size_t round_up64(size_t n) { return (n + 63) & ~(size_t)63; }

/* What one pass needs: the effective window and the ring geometry. */
typedef struct morph_plan {
    int32_t kw, kh, ax, ay; /* effective element size and anchor */
    int32_t levels;         /* doubling levels kept per padded row */
    bool separable;         /* full rectangle: ring rows hold the reduced row */
    size_t padded;          /* bytes per padded row, rounded up */
    size_t slot;            /* bytes per ring slot */
} morph_plan;

static morph_plan make_plan(int32_t width, const rte_morph_element *e, int32_t iterations)
{
    morph_plan p;
    p.separable = e->full != 0;
    if (p.separable) {
        /* OpenCV's rule for iterated rectangles: one rectangle of
         * k + (n - 1)(k - 1) with the anchor scaled by n; iterating the
         * small one gives the same pixels. */
        p.kw = e->width + (iterations - 1) * (e->width - 1);
        p.kh = e->height + (iterations - 1) * (e->height - 1);
        p.ax = e->anchor_x * iterations;
        p.ay = e->anchor_y * iterations;
        p.levels = floor_log2(p.kw) + 1;
    } else {
        p.kw = e->width;
        p.kh = e->height;
        p.ax = e->anchor_x;
        p.ay = e->anchor_y;
        p.levels = floor_log2(e->max_run) + 1;
    }
    p.padded = round_up64((size_t)width + (size_t)p.kw - 1);
    p.slot = p.separable ? round_up64((size_t)width) : p.padded * (size_t)p.levels;
    return p;
}

/* The ring, plus (separable) two padded rows to build the levels in. */
static size_t plan_bytes(const morph_plan *p)
{
    size_t bytes = rte_arena_piece_size(p->slot * (size_t)p->kh);
    if (p->separable)
        bytes += rte_arena_piece_size(2 * p->padded);
    return bytes;
}

static bool valid_element(const rte_morph_element *e)
{
    return e && e->width >= 1 && e->width <= RTE_MORPH_MAX_KSIZE && e->height >= 1 &&
           e->height <= RTE_MORPH_MAX_KSIZE && e->anchor_x >= 0 && e->anchor_x < e->width &&
           e->anchor_y >= 0 && e->anchor_y < e->height && e->run_count >= 1 &&
           e->run_count <= (int32_t)(sizeof e->runs / sizeof e->runs[0]) && e->max_run >= 1 &&
           e->max_run <= e->width;
}

/* Iterated rectangles grow; keep every size inside int32_t arithmetic. */
#define MAX_ITERATIONS 1000

size_t rte_morphology_scratch_size(int32_t max_width, int32_t max_height,
                                   const rte_morph_element *element, int32_t iterations)
{
    if (!valid_element(element) || max_width < 1 || max_height < 1 || iterations < 1 ||
        iterations > MAX_ITERATIONS)
        return 0;
    morph_plan p = make_plan(max_width, element, iterations);
    return plan_bytes(&p);
}

/* d = op(a, b) elementwise. d may be a. */
static void row_op2(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n, bool is_max)
{
    if (is_max)
        for (int32_t x = 0; x < n; x++)
            d[x] = a[x] > b[x] ? a[x] : b[x];
    else
        for (int32_t x = 0; x < n; x++)
            d[x] = a[x] < b[x] ? a[x] : b[x];
}

/* d = op(d, op(a, b)) elementwise. */
static void row_acc2(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n, bool is_max)
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

/* Copies a source row into `pad` with p->ax neutral pixels before it and
 * kw - 1 - ax after it. */
static void load_padded(uint8_t *pad, const uint8_t *row, int32_t width, const morph_plan *p,
                        uint8_t neutral)
{
    memset(pad, neutral, (size_t)p->ax);
    memcpy(pad + p->ax, row, (size_t)width);
    memset(pad + p->ax + width, neutral, (size_t)(p->kw - 1 - p->ax));
}

/* Level k from level k - 1 of a padded row of n pixels: valid for x <= n - 2^k. */
static void next_level(uint8_t *dst, const uint8_t *prev, int32_t n, int32_t k, bool is_max)
{
    int32_t half = 1 << (k - 1);
    row_op2(dst, prev, prev + half, n - 2 * half + 1, is_max);
}

static void one_pass(const rte_image_u8 *src, rte_image_u8 *dst, const morph_plan *p,
                     const rte_morph_element *e, uint8_t *ring, uint8_t *work, bool is_max)
{
    const int32_t w = src->width, h = src->height;
    const int32_t n = w + p->kw - 1; /* padded row length */
    const uint8_t neutral = is_max ? 0 : 255;
    int32_t loaded = 0; /* next source row to bring into the ring */

    for (int32_t y = 0; y < h; y++) {
        int32_t last = y - p->ay + p->kh - 1;
        if (last > h - 1)
            last = h - 1;
        for (; loaded <= last; loaded++) {
            uint8_t *slot = ring + (size_t)(loaded % p->kh) * p->slot;
            const uint8_t *row = rte_u8_row(src, loaded);
            if (p->separable) {
                if (p->kw == 1) {
                    memcpy(slot, row, (size_t)w);
                    continue;
                }
                uint8_t *a = work, *b = work + p->padded;
                load_padded(a, row, w, p, neutral);
                for (int32_t k = 1; k < p->levels; k++) {
                    next_level(b, a, n, k, is_max);
                    uint8_t *t = a; a = b; b = t;
                }
                row_op2(slot, a, a + p->kw - (1 << (p->levels - 1)), w, is_max);
            } else {
                load_padded(slot, row, w, p, neutral);
                for (int32_t k = 1; k < p->levels; k++)
                    next_level(slot + (size_t)k * p->padded, slot + (size_t)(k - 1) * p->padded, n, k,
                               is_max);
            }
        }

        uint8_t *d = rte_u8_row(dst, y);
        if (p->separable) {
            int32_t r0 = y - p->ay < 0 ? 0 : y - p->ay;
            const uint8_t *first = ring + (size_t)(r0 % p->kh) * p->slot;
            if (r0 == last) {
                memcpy(d, first, (size_t)w);
                continue;
            }
            row_op2(d, first, ring + (size_t)((r0 + 1) % p->kh) * p->slot, w, is_max);
            for (int32_t r = r0 + 2; r <= last; r++)
                row_op2(d, d, ring + (size_t)(r % p->kh) * p->slot, w, is_max);
        } else {
            memset(d, neutral, (size_t)w);
            for (int32_t i = 0; i < e->run_count; i++) {
                const rte_morph_run run = e->runs[i];
                int32_t r = y + run.dy - p->ay;
                if (r < 0 || r >= h)
                    continue;
                int32_t k = floor_log2(run.len);
                const uint8_t *level = ring + (size_t)(r % p->kh) * p->slot + (size_t)k * p->padded;
                row_acc2(d, level + run.dx, level + run.dx + run.len - (1 << k), w, is_max);
            }
        }
    }
}

rte_status rte_morphology_u8(const rte_image_u8 *src, rte_image_u8 *dst, rte_morph_op op,
                             const rte_morph_element *element, int32_t iterations,
                             rte_arena *arena)
{
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    if (!valid_element(element) || !arena || (unsigned)op > RTE_MORPH_CLOSE || iterations < 1 ||
        iterations > MAX_ITERATIONS)
        return RTE_ERR_ARGUMENT;

    const size_t mark = rte_arena_mark(arena);
    morph_plan p = make_plan(src->width, element, iterations);
    uint8_t *ring = (uint8_t *)rte_arena_alloc(arena, p.slot * (size_t)p.kh);
    uint8_t *work = p.separable ? (uint8_t *)rte_arena_alloc(arena, 2 * p.padded) : NULL;
    if (!ring || (p.separable && !work)) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    /* Passes: the rectangle covers all iterations in one pass per operation. */
    const int32_t repeat = p.separable ? 1 : iterations;
    bool first_max = op == RTE_MORPH_DILATE || op == RTE_MORPH_CLOSE;
    int32_t stages = (op == RTE_MORPH_OPEN || op == RTE_MORPH_CLOSE) ? 2 : 1;
    const rte_image_u8 *in = src;
    for (int32_t s = 0; s < stages; s++) {
        bool is_max = s == 0 ? first_max : !first_max;
        for (int32_t i = 0; i < repeat; i++) {
            one_pass(in, dst, &p, element, ring, work, is_max);
            in = dst;
        }
    }
    rte_arena_reset(arena, mark);
    return RTE_OK;
}

rte_status rte_morphology_erode_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                   const rte_morph_element *element, int32_t iterations,
                                   rte_arena *arena)
{
    return rte_morphology_u8(src, dst, RTE_MORPH_ERODE, element, iterations, arena);
}

rte_status rte_morphology_dilate_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                    const rte_morph_element *element, int32_t iterations,
                                    rte_arena *arena)
{
    return rte_morphology_u8(src, dst, RTE_MORPH_DILATE, element, iterations, arena);
}
