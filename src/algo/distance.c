/* Two-pass 3x3 chamfer distance transform (rtedge/distance.h). Values are
 * kept clamped to the metric's cap in every step: min(a, cap) + w clamped
 * again equals min(a + w, cap), so clamping as we go gives the capped
 * exact result. Pixels outside the image act as neighbours at the cap
 * (RTE_DIST_BORDER_FAR: never zero pixels) or at 0 (_ZERO). */
#include "rtedge/distance.h"

#include <stdbool.h>
#include <string.h>

typedef struct dist_weights {
    uint32_t hv, diag, cap;
    uint32_t outside; /* the value of a neighbour outside the image */
} dist_weights;

int32_t rte_distance_unit(rte_dist_metric metric)
{
    switch (metric) {
    case RTE_DIST_L1:
    case RTE_DIST_C: return 1;
    case RTE_DIST_CHAMFER34: return 3;
    }
    return 0;
}

static bool weights_of(rte_dist_metric metric, dist_weights *w)
{
    switch (metric) {
    case RTE_DIST_L1: *w = (dist_weights){1, 2, RTE_DIST_CAP, RTE_DIST_CAP}; return true;
    case RTE_DIST_C: *w = (dist_weights){1, 1, RTE_DIST_CAP, RTE_DIST_CAP}; return true;
    case RTE_DIST_CHAMFER34: *w = (dist_weights){3, 4, UINT16_MAX, UINT16_MAX}; return true;
    }
    return false;
}

static inline uint32_t min_u32(uint32_t a, uint32_t b) { return a < b ? a : b; }

/* Row y of the forward pass; `up` is row y - 1 of the result, NULL on the
 * first row. */
static void forward_row(const uint8_t *s, uint16_t *d, const uint16_t *up, int32_t width,
                        dist_weights w)
{
    uint32_t left = w.outside; /* the pixel to the left */
    for (int32_t x = 0; x < width; x++) {
        if (!s[x]) {
            d[x] = 0;
            left = 0;
            continue;
        }
        uint32_t t = left + w.hv;
        if (up) {
            uint32_t ul = x > 0 ? up[x - 1] : w.outside;
            uint32_t ur = x + 1 < width ? up[x + 1] : w.outside;
            t = min_u32(t, (uint32_t)up[x] + w.hv);
            t = min_u32(t, min_u32(ul, ur) + w.diag);
        } else {
            t = min_u32(t, w.outside + w.hv);
        }
        left = min_u32(t, w.cap);
        d[x] = (uint16_t)left;
    }
}

/* Row y of the backward pass, right to left; `down` is row y + 1, NULL on
 * the last row. Zero pixels stay 0, other values only decrease. */
static void backward_row(uint16_t *d, const uint16_t *down, int32_t width, dist_weights w)
{
    uint32_t right = w.outside;
    for (int32_t x = width - 1; x >= 0; x--) {
        uint32_t t = d[x];
        if (t != 0) {
            t = min_u32(t, right + w.hv);
            if (down) {
                uint32_t dl = x > 0 ? down[x - 1] : w.outside;
                uint32_t dr = x + 1 < width ? down[x + 1] : w.outside;
                t = min_u32(t, (uint32_t)down[x] + w.hv);
                t = min_u32(t, min_u32(dl, dr) + w.diag);
            } else {
                t = min_u32(t, w.outside + w.hv);
            }
            d[x] = (uint16_t)t;
        }
        right = t;
    }
}

/* The rows between the first and the last go by runs of object pixels (the
 * zero pixels between them are 0 and end the chain along the row), each in
 * two steps: the terms from the row above (or below), which do not depend
 * on each other and vectorise, then the chain along the run, a serial
 * minimum. The first and last columns, whose neighbours outside the image
 * count as w.outside, are peeled off the vector loop. */

/* The first x1 >= x of row s where (s[x1] != 0) != object, or width:
 * 32 bytes at a time over the background (most of a row), 8 while all
 * bytes are object pixels, then one. */
static inline int32_t run_end(const uint8_t *s, int32_t x, int32_t width, bool object)
{
    const uint64_t ones = 0x0101010101010101u;
    for (; !object && x + 32 <= width; x += 32) {
        uint64_t v[4];
        memcpy(v, s + x, sizeof v);
        if ((v[0] | v[1] | v[2] | v[3]) != 0)
            break;
    }
    for (; x + 8 <= width; x += 8) {
        uint64_t v;
        memcpy(&v, s + x, sizeof v);
        if ((object ? (v - ones) & ~v & (ones << 7) : v) != 0) /* a zero byte; a non-zero one */
            break;
    }
    while (x < width && (s[x] != 0) == object)
        x++;
    return x;
}

static inline uint16_t min_u16(uint16_t a, uint16_t b) { return a < b ? a : b; }

/* The least of a pixel's three neighbours in another row (l, c, r: left,
 * centre, right) plus their step weights, capped: min(v, cap - w) + w is
 * min(v + w, cap) without leaving 16 bits, which lets the loops below
 * vectorise 8 pixels a step. */
static inline uint16_t row_term(uint16_t l, uint16_t c, uint16_t r, dist_weights w)
{
    const uint16_t straight = (uint16_t)(min_u16(c, (uint16_t)(w.cap - w.hv)) + w.hv);
    const uint16_t diagonal =
        (uint16_t)(min_u16(min_u16(l, r), (uint16_t)(w.cap - w.diag)) + w.diag);
    return min_u16(straight, diagonal);
}

/* The forward pass over the object pixels [x0, x1) of a row; `up` is the
 * row above. Each value is min(left + hv, the capped row term), which
 * equals the capped min of both since left <= cap. */
static inline __attribute__((always_inline)) void forward_run(uint16_t *restrict d,
                                                              const uint16_t *restrict up,
                                                              int32_t x0, int32_t x1, int32_t width,
                                                              dist_weights w)
{
    int32_t a = x0, b = x1;
    if (a == 0) {
        d[0] = row_term((uint16_t)w.outside, up[0], width > 1 ? up[1] : (uint16_t)w.outside, w);
        a = 1;
    }
    if (b == width && b - 1 >= a) {
        d[b - 1] = row_term(up[b - 2], up[b - 1], (uint16_t)w.outside, w);
        b--;
    }
    for (int32_t x = a; x < b; x++)
        d[x] = row_term(up[x - 1], up[x], up[x + 1], w);
    uint32_t left = x0 == 0 ? w.outside : 0;
    int32_t x = x0;
    for (; x + 2 <= x1; x += 2) { /* two steps per link of the chain */
        const uint32_t t0 = d[x], t1 = d[x + 1];
        d[x] = (uint16_t)min_u32(left + w.hv, t0);
        left = min_u32(left + 2 * w.hv, min_u32(t0 + w.hv, t1));
        d[x + 1] = (uint16_t)left;
    }
    if (x < x1)
        d[x] = (uint16_t)min_u32(left + w.hv, d[x]);
}

/* The backward pass over the object pixels [x0, x1) of a row; `down` is
 * the row below. The cap of the row term changes nothing: d <= cap. */
static inline __attribute__((always_inline)) void backward_run(uint16_t *restrict d,
                                                               const uint16_t *restrict down,
                                                               int32_t x0, int32_t x1,
                                                               int32_t width, dist_weights w)
{
    int32_t a = x0, b = x1;
    if (a == 0) {
        d[0] = min_u16(d[0], row_term((uint16_t)w.outside, down[0],
                                      width > 1 ? down[1] : (uint16_t)w.outside, w));
        a = 1;
    }
    if (b == width && b - 1 >= a) {
        d[b - 1] = min_u16(d[b - 1], row_term(down[b - 2], down[b - 1], (uint16_t)w.outside, w));
        b--;
    }
    for (int32_t x = a; x < b; x++)
        d[x] = min_u16(d[x], row_term(down[x - 1], down[x], down[x + 1], w));
    uint32_t right = x1 == width ? w.outside : 0;
    int32_t x = x1;
    for (; x - 2 >= x0; x -= 2) {
        const uint32_t t1 = d[x - 1], t0 = d[x - 2];
        d[x - 1] = (uint16_t)min_u32(right + w.hv, t1);
        right = min_u32(right + 2 * w.hv, min_u32(t1 + w.hv, t0));
        d[x - 2] = (uint16_t)right;
    }
    if (x > x0)
        d[x0] = (uint16_t)min_u32(right + w.hv, d[x0]);
}

/* Both passes; inlined once per metric so that the weights are constants. */
static inline __attribute__((always_inline)) void transform(const rte_image_u8 *src,
                                                            rte_image_u16 *dst, dist_weights w)
{
    const int32_t width = src->width, height = src->height;
    forward_row(rte_u8_row(src, 0), rte_u16_row(dst, 0), NULL, width, w);
    for (int32_t y = 1; y < height; y++) {
        const uint8_t *s = rte_u8_row(src, y);
        uint16_t *d = rte_u16_row(dst, y);
        const uint16_t *up = rte_u16_row(dst, y - 1);
        for (int32_t x = 0; x < width;) {
            const int32_t x0 = run_end(s, x, width, false);
            memset(d + x, 0, (size_t)(x0 - x) * sizeof(uint16_t));
            if (x0 == width)
                break;
            x = run_end(s, x0, width, true);
            forward_run(d, up, x0, x, width, w);
        }
    }
    backward_row(rte_u16_row(dst, height - 1), NULL, width, w);
    for (int32_t y = height - 2; y >= 0; y--) {
        const uint8_t *s = rte_u8_row(src, y);
        uint16_t *d = rte_u16_row(dst, y);
        const uint16_t *down = rte_u16_row(dst, y + 1);
        for (int32_t x = run_end(s, 0, width, false); x < width;) {
            const int32_t x0 = x;
            x = run_end(s, x0, width, true);
            backward_run(d, down, x0, x, width, w);
            x = run_end(s, x, width, false);
        }
    }
}

rte_status rte_distance_transform_u8(const rte_image_u8 *src, rte_image_u16 *dst,
                                     rte_dist_metric metric, rte_dist_border border)
{
    dist_weights w;
    if (!src || !dst || !weights_of(metric, &w) ||
        (border != RTE_DIST_BORDER_FAR && border != RTE_DIST_BORDER_ZERO))
        return RTE_ERR_ARGUMENT;
    if (border == RTE_DIST_BORDER_ZERO)
        w.outside = 0;
    rte_status st = rte_image_u8_check(src);
    if (st == RTE_OK)
        st = rte_image_u16_check(dst);
    if (st != RTE_OK)
        return st;
    if (src->width != dst->width || src->height != dst->height)
        return RTE_ERR_SIZE;

    switch (metric) {
    case RTE_DIST_L1: transform(src, dst, (dist_weights){1, 2, RTE_DIST_CAP, w.outside}); break;
    case RTE_DIST_C: transform(src, dst, (dist_weights){1, 1, RTE_DIST_CAP, w.outside}); break;
    case RTE_DIST_CHAMFER34:
        transform(src, dst, (dist_weights){3, 4, UINT16_MAX, w.outside});
        break;
    }
    return RTE_OK;
}
