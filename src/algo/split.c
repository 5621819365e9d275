/* Split of touching objects by the dynamics of their distance transform
 * (rtedge/split.h): a flood in decreasing distance with a union-find over
 * the pixels. */
#include "rtedge/split.h"

#include <stdbool.h>
#include <string.h>

#define LEVELS (UINT16_MAX + 1)
#define CUT_PIXEL 2 /* flood_meeting's answer for a cut pixel */

rte_status rte_split_params_default(rte_split_params *params, rte_dist_metric metric)
{
    int32_t unit = rte_distance_unit(metric);
    if (!params || unit == 0)
        return RTE_ERR_ARGUMENT;
    /* measured on smarties.png and the synthetic shapes of
     * tests/unit/test_split.c (docs/distance.md): inside the ratios that split
     * every pair and triple and no single object. C's is lower because its
     * peaks are lower (a disc's is r / sqrt(2)); L1's is higher because its
     * ripple on a ring's ridge reaches 29%. */
    params->min_dynamic = 2 * unit;
    params->min_ratio_permille = metric == RTE_DIST_C ? 250 : metric == RTE_DIST_L1 ? 350 : 300;
    return RTE_OK;
}

/* The union-find runs on the image framed by one pixel on each side:
 * pixel (x, y) is i = (y + 1) * (width + 2) + x + 1, so every pixel has
 * eight neighbours without bounds checks, and i still grows in raster
 * order (which breaks ties between roots). parent[i] is 0 for a pixel in no
 * basin (the frame, the background, an object pixel not flooded yet or
 * cut), i for a basin's root, or another pixel of its basin. 0 is the
 * frame's corner, never a pixel. The peak of a basin is the distance of its
 * root, where the flood started it. */
static size_t framed_pixels(int32_t width, int32_t height)
{
    return ((size_t)width + 2) * ((size_t)height + 2);
}

/* Room in order[] for the object pixels and, behind them, the list of runs
 * that sort_pixels keeps between its passes: per row, pixels + runs <=
 * width + 1, plus a header per row. */
static size_t order_entries(int32_t width, int32_t height)
{
    return (size_t)width * (size_t)height + 2 * (size_t)height;
}

size_t rte_split_scratch_size(int32_t max_width, int32_t max_height)
{
    if (max_width < 1 || max_height < 1 || max_width > RTE_MAX_SIDE || max_height > RTE_MAX_SIDE)
        return 0;
    return rte_arena_piece_size(framed_pixels(max_width, max_height) * sizeof(uint32_t)) +
           rte_arena_piece_size(order_entries(max_width, max_height) * sizeof(uint32_t)) +
           rte_arena_piece_size((LEVELS + 1) * sizeof(uint32_t));
}

typedef struct split_ctx {
    uint32_t *parent;
    uint32_t stride; /* width + 2 */
    const rte_image_u16 *dist;
    uint32_t min_dynamic, ratio;
} split_ctx;

static inline uint32_t find_root(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i) {
        uint32_t up = parent[i];
        parent[i] = parent[up]; /* path halving */
        i = up;
    }
    return i;
}

static inline uint32_t peak_of(const split_ctx *c, uint32_t root)
{
    return rte_u16_row(c->dist, (int32_t)(root / c->stride) - 1)[root % c->stride - 1];
}

static inline bool significant(const split_ctx *c, uint32_t peak, uint32_t level)
{
    uint32_t dynamic = peak - level;
    return dynamic >= c->min_dynamic && dynamic * 1000u >= c->ratio * peak;
}

/* Adds the basin of neighbour j to roots[0..n) unless it is there already
 * or j is in none; returns the new n. */
static inline int32_t add_root(uint32_t *parent, uint32_t j, uint32_t roots[8], int32_t n)
{
    if (parent[j] == 0)
        return n;
    uint32_t r = find_root(parent, j);
    for (int32_t k = 0; k < n; k++)
        if (roots[k] == r)
            return n;
    roots[n] = r;
    return n + 1;
}

/* The distinct basins among the flooded 8-neighbours of framed pixel i;
 * returns their number. Cut pixels belong to none. */
static int32_t neighbour_roots(const split_ctx *c, uint32_t i, uint32_t roots[8])
{
    uint32_t *parent = c->parent;
    const uint32_t up = i - c->stride, down = i + c->stride;
    int32_t n = add_root(parent, up - 1, roots, 0);
    n = add_root(parent, up, roots, n);
    n = add_root(parent, up + 1, roots, n);
    n = add_root(parent, i - 1, roots, n);
    n = add_root(parent, i + 1, roots, n);
    n = add_root(parent, down - 1, roots, n);
    n = add_root(parent, down, roots, n);
    return add_root(parent, down + 1, roots, n);
}

/* Floods framed pixel i at `level` in the general case: a new basin, a
 * member of its neighbours' merged basin, or a cut pixel where two
 * significant basins meet. Returns the change in the number of basins
 * (-7..1), or CUT_PIXEL. Out of line: the common case (the flood loop)
 * needs few registers. */
static __attribute__((noinline)) int32_t flood_meeting(const split_ctx *c, uint32_t i,
                                                       uint32_t level)
{
    uint32_t *parent = c->parent;
    uint32_t roots[8];
    int32_t n = neighbour_roots(c, i, roots);
    if (n == 0) {
        parent[i] = i;
        return 1;
    }
    if (n == 1) {
        parent[i] = roots[0];
        return 0;
    }
    uint32_t best = roots[0];
    uint32_t best_peak = peak_of(c, best);
    int32_t n_significant = significant(c, best_peak, level);
    for (int32_t k = 1; k < n; k++) {
        uint32_t peak = peak_of(c, roots[k]);
        if (peak > best_peak || (peak == best_peak && roots[k] < best)) {
            best = roots[k];
            best_peak = peak;
        }
        n_significant += significant(c, peak, level);
    }
    if (n_significant >= 2)
        return CUT_PIXEL; /* parent[i] stays 0 */
    for (int32_t k = 0; k < n; k++)
        if (roots[k] != best)
            parent[roots[k]] = best;
    parent[i] = best;
    return 1 - n;
}

/* Floods framed pixel i when every flooded neighbour is, or points straight
 * at, one root: the common case, tested without branches on the
 * neighbours (at the edge of a level, flooded and unflooded neighbours
 * follow no pattern). With the neighbours' parents g (0 for no basin), the
 * OR o of all g and the AND a of all g - 1 (where each g = 0 is all ones):
 * a + 1 <= the least non-zero g <= the largest <= o, so a + 1 == o exactly
 * when the non-zero g are all equal (o == 0: no flooded neighbour).
 * Returns false, changing nothing, when the case is another. */
static inline bool flood_common(uint32_t *parent, uint32_t stride, uint32_t i)
{
    const uint32_t *up = parent + i - stride - 1, *mid = parent + i - 1,
                   *down = parent + i + stride - 1;
    const uint32_t g[8] = {up[0], up[1], up[2], mid[0], mid[2], down[0], down[1], down[2]};
    uint32_t o = 0, a = UINT32_MAX;
    for (int32_t k = 0; k < 8; k++) {
        o |= g[k];
        a &= g[k] - 1u;
    }
    if (o == 0 || a + 1u != o || parent[o] != o)
        return false;
    parent[i] = o;
    return true;
}

/* The first x1 >= x of row s with s[x1] != 0, or width: 32 bytes at a
 * time (most of a row is background), then 8, then one. */
static inline int32_t skip_background(const uint8_t *s, int32_t x, int32_t width)
{
    for (; x + 32 <= width; x += 32) {
        uint64_t w[4];
        memcpy(w, s + x, sizeof w);
        if (w[0] | w[1] | w[2] | w[3])
            break;
    }
    for (; x + 8 <= width; x += 8) {
        uint64_t w;
        memcpy(&w, s + x, sizeof w);
        if (w)
            break;
    }
    while (x < width && !s[x])
        x++;
    return x;
}

/* The first x1 >= x of row s with s[x1] == 0, or width: 8 bytes at a
 * time while none is zero, then one. */
static inline int32_t skip_object(const uint8_t *s, int32_t x, int32_t width)
{
    const uint64_t ones = 0x0101010101010101u;
    for (; x + 8 <= width; x += 8) {
        uint64_t w;
        memcpy(&w, s + x, sizeof w);
        if ((w - ones) & ~w & (ones << 7)) /* a zero byte */
            break;
    }
    while (x < width && s[x])
        x++;
    return x;
}

#define RUN_ROW 0x80000000u /* a row header in the list of runs */

/* order[] = the object pixels as framed indices, in decreasing distance
 * and raster order within a distance (a counting sort); on return hist[v]
 * is the end in order[] of level v, whose pixels start at hist[v + 1]
 * (0 for the top level). Returns a level >= the top one (an OR of all, at
 * most twice the top: the levels above the top are empty). Sets parent[]
 * to 0 around each run of object pixels: the flood reads no other entry.
 *
 * The first pass finds the runs of object pixels and the top level, and
 * lists the runs at the end of order[], backwards: RUN_ROW | y before the
 * runs of row y, x0 | x1 << 16 for the run [x0, x1). The second (the
 * histogram, of the levels up to the top only) and the third (the scatter)
 * read them back to front, in raster order; the scatter writes below the
 * list only: the P pixels need P entries and the list takes the rest. */
static uint32_t sort_pixels(const rte_image_u8 *src, const rte_image_u16 *dist, uint32_t *parent,
                            uint32_t stride, uint32_t *hist, uint32_t *order)
{
    const int32_t width = src->width, height = src->height;
    const uint32_t entries = (uint32_t)order_entries(width, height);
    uint32_t list = entries;
    uint32_t top = 0;
    for (int32_t y = 0; y < height; y++) {
        const uint8_t *s = rte_u8_row(src, y);
        const uint16_t *d = rte_u16_row(dist, y);
        int32_t x = skip_background(s, 0, width);
        if (x < width)
            order[--list] = RUN_ROW | (uint32_t)y;
        while (x < width) {
            const int32_t end = skip_object(s, x, width);
            order[--list] = (uint32_t)x | (uint32_t)end << 16;
            for (; x < end; x++)
                top |= d[x];
            x = skip_background(s, x, width);
        }
    }
    /* only the levels up to the top are cleared (an object's distances
     * rarely reach a thousand; all LEVELS are 256 KiB) */
    memset(hist, 0, ((size_t)top + 1) * sizeof(uint32_t));
    {
        const uint16_t *d = NULL;
        for (uint32_t k = entries; k-- > list;) {
            const uint32_t run = order[k];
            if (run & RUN_ROW) {
                d = rte_u16_row(dist, (int32_t)(run & ~RUN_ROW));
                continue;
            }
            for (uint32_t x = run & 0xffffu; x < run >> 16; x++)
                hist[d[x]]++;
        }
    }
    /* hist[v] becomes the first position of level v: higher levels first */
    uint32_t pos = 0;
    for (uint32_t v = top + 1; v-- > 0;) {
        const uint32_t count = hist[v];
        hist[v] = pos;
        pos += count;
    }
    const uint16_t *d = NULL;
    uint32_t row = 0; /* the framed index of the row's x = 0 */
    for (uint32_t k = entries; k-- > list;) {
        const uint32_t run = order[k];
        if (run & RUN_ROW) {
            const int32_t y = (int32_t)(run & ~RUN_ROW);
            d = rte_u16_row(dist, y);
            row = (uint32_t)(y + 1) * stride + 1u;
            continue;
        }
        const uint32_t x0 = run & 0xffffu, x1 = run >> 16;
        const size_t bytes = (size_t)(x1 - x0 + 2) * sizeof(uint32_t);
        memset(parent + row - stride + x0 - 1, 0, bytes);
        memset(parent + row + x0 - 1, 0, bytes);
        memset(parent + row + stride + x0 - 1, 0, bytes);
        for (uint32_t x = x0; x < x1; x++)
            order[hist[d[x]]++] = row + x;
    }
    return top;
}

static rte_status check_args(const rte_image_u8 *src, const rte_image_u16 *dist,
                             const rte_image_u8 *dst, const rte_split_params *params,
                             const rte_arena *arena)
{
    if (!src || !dist || !dst || !params || !arena)
        return RTE_ERR_ARGUMENT;
    if (params->min_dynamic < 1 || params->min_ratio_permille < 0 ||
        params->min_ratio_permille > 1000)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st == RTE_OK)
        st = rte_image_u16_check(dist);
    if (st == RTE_OK && (dist->width != src->width || dist->height != src->height))
        st = RTE_ERR_SIZE;
    return st;
}

rte_status rte_split_u8(const rte_image_u8 *src, const rte_image_u16 *dist, rte_image_u8 *dst,
                        const rte_split_params *params, rte_arena *arena, rte_split_result *result)
{
    rte_status st = check_args(src, dist, dst, params, arena);
    if (st != RTE_OK)
        return st;
    const int32_t width = src->width, height = src->height;
    const size_t framed = framed_pixels(width, height);
    const size_t mark = rte_arena_mark(arena);
    uint32_t *parent = (uint32_t *)rte_arena_alloc(arena, framed * sizeof(uint32_t));
    uint32_t *order =
        (uint32_t *)rte_arena_alloc(arena, order_entries(width, height) * sizeof(uint32_t));
    uint32_t *hist = (uint32_t *)rte_arena_alloc(arena, (LEVELS + 1) * sizeof(uint32_t));
    if (!parent || !order || !hist) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    split_ctx c = {parent, (uint32_t)width + 2, dist, (uint32_t)params->min_dynamic,
                   (uint32_t)params->min_ratio_permille};
    const uint32_t top = sort_pixels(src, dist, parent, c.stride, hist, order);

    /* the flood, level by level; the cut pixels are listed, in flood
     * order, at the front of order[] (never past the pixel being read) */
    int32_t parts = 0;
    uint32_t n_cut = 0, begin = 0;
    for (uint32_t v = top + 1; v-- > 0;) {
        const uint32_t end = hist[v];
        for (uint32_t k = begin; k < end; k++) {
            const uint32_t i = order[k];
            if (flood_common(parent, c.stride, i))
                continue;
            const int32_t change = flood_meeting(&c, i, v);
            if (change == CUT_PIXEL)
                order[n_cut++] = i;
            else
                parts += change;
        }
        begin = end;
    }
    /* gives back each cut pixel whose flooded neighbours lie in one basin */
    uint32_t n_kept = 0;
    for (uint32_t k = 0; k < n_cut; k++) {
        const uint32_t i = order[k];
        uint32_t roots[8];
        if (neighbour_roots(&c, i, roots) == 1)
            parent[i] = roots[0];
        else
            order[n_kept++] = i;
    }

    if (dst->buf != src->buf || dst->stride != src->stride)
        for (int32_t y = 0; y < height; y++)
            memmove(rte_u8_row(dst, y), rte_u8_row(src, y), (size_t)width);
    for (uint32_t k = 0; k < n_kept; k++) {
        const int32_t y = (int32_t)(order[k] / c.stride) - 1;
        const int32_t x = (int32_t)(order[k] % c.stride) - 1;
        rte_u8_row(dst, y)[x] = 0;
    }
    if (result)
        *result = (rte_split_result){parts, (int32_t)n_kept};
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
