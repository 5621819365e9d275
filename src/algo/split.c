/* Split of touching objects by the dynamics of their distance transform
 * (rtedge/split.h): a flood in decreasing distance with a union-find over
 * the pixels. */
#include "rtedge/split.h"

#include <stdbool.h>

/* parent[i] of pixel i (y * width + x): another pixel of its basin, or one
 * of these marks. A root holds ROOT_BASE - peak, so finding a basin's root
 * also gives its peak. */
#define UNSEEN (-1)
#define CUT (-2)
#define ROOT_BASE (-3)
#define LEVELS (UINT16_MAX + 1)

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

size_t rte_split_scratch_size(int32_t max_width, int32_t max_height)
{
    if (max_width < 1 || max_height < 1 || max_width > RTE_MAX_SIDE || max_height > RTE_MAX_SIDE)
        return 0;
    size_t pixels = (size_t)max_width * (size_t)max_height;
    return 2 * rte_arena_piece_size(pixels * sizeof(int32_t)) +
           rte_arena_piece_size((LEVELS + 1) * sizeof(uint32_t));
}

typedef struct split_ctx {
    int32_t width, height;
    int32_t *parent;
    uint32_t min_dynamic, ratio;
} split_ctx;

static inline int32_t find_root(int32_t *parent, int32_t i)
{
    while (parent[i] >= 0) {
        int32_t up = parent[i];
        if (parent[up] >= 0)
            parent[i] = parent[up]; /* path halving */
        i = up;
    }
    return i;
}

static inline uint32_t peak_of(const int32_t *parent, int32_t root)
{
    return (uint32_t)(ROOT_BASE - parent[root]);
}

static inline bool significant(const split_ctx *c, uint32_t peak, uint32_t level)
{
    uint32_t dynamic = peak - level;
    return dynamic >= c->min_dynamic && dynamic * 1000u >= c->ratio * peak;
}

/* The distinct basins among the flooded 8-neighbours of (x, y); returns
 * their number. Cut pixels belong to none. */
static int32_t neighbour_roots(const split_ctx *c, int32_t x, int32_t y, int32_t roots[8])
{
    int32_t n = 0;
    for (int32_t dy = -1; dy <= 1; dy++) {
        int32_t ny = y + dy;
        if (ny < 0 || ny >= c->height)
            continue;
        for (int32_t dx = -1; dx <= 1; dx++) {
            int32_t nx = x + dx;
            if ((dx == 0 && dy == 0) || nx < 0 || nx >= c->width)
                continue;
            int32_t j = ny * c->width + nx;
            if (c->parent[j] == UNSEEN || c->parent[j] == CUT)
                continue;
            int32_t r = find_root(c->parent, j);
            int32_t k = 0;
            while (k < n && roots[k] != r)
                k++;
            if (k == n)
                roots[n++] = r;
        }
    }
    return n;
}

/* Floods pixel i at `level`: a new basin, a member of its neighbours'
 * merged basin, or a cut pixel where two significant basins meet. */
static void flood_pixel(split_ctx *c, int32_t i, int32_t x, int32_t y, uint32_t level)
{
    int32_t roots[8];
    int32_t n = neighbour_roots(c, x, y, roots);
    if (n == 0) {
        c->parent[i] = ROOT_BASE - (int32_t)level;
        return;
    }
    int32_t best = roots[0];
    int32_t n_significant = 0;
    for (int32_t k = 0; k < n; k++) {
        uint32_t peak = peak_of(c->parent, roots[k]);
        uint32_t best_peak = peak_of(c->parent, best);
        if (peak > best_peak || (peak == best_peak && roots[k] < best))
            best = roots[k];
        n_significant += significant(c, peak, level);
    }
    if (n_significant >= 2) {
        c->parent[i] = CUT;
        return;
    }
    for (int32_t k = 0; k < n; k++)
        if (roots[k] != best)
            c->parent[roots[k]] = best;
    c->parent[i] = best;
}

/* order[] = the object pixels as (y << 16 | x), in decreasing distance
 * and raster order within a distance (a counting sort); returns their
 * number. */
static uint32_t sort_pixels(const rte_image_u8 *src, const rte_image_u16 *dist, uint32_t *hist,
                            uint32_t *order)
{
    uint32_t top = 0;
    for (int32_t y = 0; y < src->height; y++) {
        const uint8_t *s = rte_u8_row(src, y);
        const uint16_t *d = rte_u16_row(dist, y);
        for (int32_t x = 0; x < src->width; x++)
            if (s[x] && d[x] > top)
                top = d[x];
    }
    for (uint32_t v = 0; v <= top + 1; v++)
        hist[v] = 0;
    for (int32_t y = 0; y < src->height; y++) {
        const uint8_t *s = rte_u8_row(src, y);
        const uint16_t *d = rte_u16_row(dist, y);
        for (int32_t x = 0; x < src->width; x++)
            hist[d[x]] += s[x] != 0;
    }
    /* hist[v] becomes the first position of level v: higher levels first */
    uint32_t pos = 0;
    for (uint32_t v = top + 1; v-- > 0;) {
        uint32_t count = hist[v];
        hist[v] = pos;
        pos += count;
    }
    for (int32_t y = 0; y < src->height; y++) {
        const uint8_t *s = rte_u8_row(src, y);
        const uint16_t *d = rte_u16_row(dist, y);
        for (int32_t x = 0; x < src->width; x++)
            if (s[x])
                order[hist[d[x]]++] = (uint32_t)y << 16 | (uint32_t)x;
    }
    return pos;
}

/* Gives back each cut pixel whose flooded neighbours lie in one basin. */
static void thin_cuts(split_ctx *c, const uint32_t *order, uint32_t count)
{
    for (uint32_t k = 0; k < count; k++) {
        int32_t x = (int32_t)(order[k] & 0xffffu), y = (int32_t)(order[k] >> 16);
        int32_t i = y * c->width + x;
        if (c->parent[i] != CUT)
            continue;
        int32_t roots[8];
        if (neighbour_roots(c, x, y, roots) == 1)
            c->parent[i] = roots[0];
    }
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
    const size_t pixels = (size_t)width * (size_t)height;
    const size_t mark = rte_arena_mark(arena);
    int32_t *parent = (int32_t *)rte_arena_alloc(arena, pixels * sizeof(int32_t));
    uint32_t *order = (uint32_t *)rte_arena_alloc(arena, pixels * sizeof(uint32_t));
    uint32_t *hist = (uint32_t *)rte_arena_alloc(arena, (LEVELS + 1) * sizeof(uint32_t));
    if (!parent || !order || !hist) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    split_ctx c = {width, height, parent, (uint32_t)params->min_dynamic,
                   (uint32_t)params->min_ratio_permille};
    for (size_t i = 0; i < pixels; i++)
        parent[i] = UNSEEN;
    const uint32_t count = sort_pixels(src, dist, hist, order);
    for (uint32_t k = 0; k < count; k++) {
        int32_t x = (int32_t)(order[k] & 0xffffu), y = (int32_t)(order[k] >> 16);
        flood_pixel(&c, y * width + x, x, y, rte_u16_row(dist, y)[x]);
    }
    thin_cuts(&c, order, count);

    rte_split_result r = {0, 0};
    for (int32_t y = 0; y < height; y++) {
        const uint8_t *s = rte_u8_row(src, y);
        uint8_t *d = rte_u8_row(dst, y);
        const int32_t *p = parent + (size_t)y * (size_t)width;
        for (int32_t x = 0; x < width; x++) {
            r.parts += p[x] <= ROOT_BASE;
            r.cut_pixels += p[x] == CUT;
            d[x] = p[x] == CUT ? 0 : s[x];
        }
    }
    if (result)
        *result = r;
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
