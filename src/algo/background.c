/* The table's brightness and the two-sided threshold against it (see
 * include/rtedge/background.h). Per frame, integer only. */
#include "rtedge/background.h"

#include <stdint.h>
#include <string.h>

#include "rtedge/threshold.h"

/* Grid values carry 4 fractional bits; bilinear weights 8. */
#define GRID_SHIFT 4
#define WEIGHT_SHIFT 8

/* A cell's histogram: 256 bins, then 16 coarse ones. */
#define HIST_BINS (256 + 16)

void rte_background_params_default(rte_background_params *params, int32_t width)
{
    int32_t cell = width / 40;
    if (cell < 4)
        cell = 4;
    if (cell > RTE_BACKGROUND_MAX_CELL)
        cell = RTE_BACKGROUND_MAX_CELL;
    *params = (rte_background_params){.cell = cell, .radius = 4, .tolerance = 12, .step = 8};
}

void rte_background_threshold_params_default(rte_background_threshold_params *params, int32_t width)
{
    const int32_t gap = width / 200;
    *params = (rte_background_threshold_params){.high = 0,
                                                .min_contrast = 20,
                                                .bright = true,
                                                .dark = true,
                                                .drop_shadows = true,
                                                .shadow_gap = gap < 3 ? 3 : gap,
                                                .region_share_permille = 400,
                                                .shadow_min_area = 64};
}

static int32_t cells(int32_t size, int32_t cell) { return (size + cell - 1) / cell; }

/* The arena pieces of the estimate, in the order taken. */
static size_t estimate_pieces(int32_t w, int32_t h, int32_t cell)
{
    const size_t gw = (size_t)cells(w, cell), gh = (size_t)cells(h, cell);
    return rte_arena_piece_size(gw * gh) * 2 +                       /* medians, table flags */
           rte_arena_piece_size(gw * gh * sizeof(int32_t)) * 3 +     /* queue, regions, grid */
           rte_arena_piece_size(gw * HIST_BINS * sizeof(uint16_t)) + /* a row of histograms */
           rte_arena_piece_size((size_t)w * 6 *
                                sizeof(int32_t)); /* columns' cells, weights, terms */
}

size_t rte_background_scratch_size(int32_t max_width, int32_t max_height, int32_t min_cell)
{
    if (max_width < 1 || max_height < 1 || min_cell < RTE_BACKGROUND_MIN_CELL ||
        min_cell > RTE_BACKGROUND_MAX_CELL)
        return 0;
    return estimate_pieces(max_width, max_height, min_cell);
}

/* Each cell's median (the lower one for an even count), of every other row
 * and column when cells are 8 px or larger: 16 samples or more, and a
 * quarter of the histogram updates. Each cell's histogram has 256 bins and
 * 16 coarse ones (16 levels each) that the search for the median skips
 * along. */
static void cell_medians(const rte_image_u8 *src, int32_t cell, int32_t gw, int32_t gh,
                         uint8_t *med, uint16_t *hist)
{
    const int32_t w = src->width, h = src->height, step = cell >= 8 ? 2 : 1;
    for (int32_t j = 0; j < gh; j++) {
        const int32_t y0 = j * cell, y1 = y0 + cell < h ? y0 + cell : h;
        memset(hist, 0, (size_t)gw * HIST_BINS * sizeof *hist);
        for (int32_t y = y0; y < y1; y += step) {
            const uint8_t *row = rte_u8_row(src, y);
            for (int32_t i = 0; i < gw; i++) {
                uint16_t *hc = hist + (size_t)i * HIST_BINS;
                const int32_t x1 = (i + 1) * cell < w ? (i + 1) * cell : w;
                for (int32_t x = i * cell; x < x1; x += step) {
                    hc[row[x]]++;
                    hc[256 + (row[x] >> 4)]++;
                }
            }
        }
        const int32_t rows = (y1 - y0 + step - 1) / step;
        for (int32_t i = 0; i < gw; i++) {
            const int32_t x0 = i * cell, x1 = (i + 1) * cell < w ? (i + 1) * cell : w;
            const int32_t half = (rows * ((x1 - x0 + step - 1) / step) + 1) / 2;
            const uint16_t *hc = hist + (size_t)i * HIST_BINS;
            int32_t c = 0, sum = 0;
            while (sum + hc[256 + c] < half)
                sum += hc[256 + c++];
            int32_t v = c * 16;
            while ((sum += hc[v]) < half)
                v++;
            med[j * gw + i] = (uint8_t)v;
        }
    }
}

/* The table's cells. The grid is cut into regions: cells joined through
 * 4-neighbours whose medians differ by at most step. An object's edge is a
 * step larger than that between two cells (a cell's median flips from
 * table to object where the object covers half of it), light falling off
 * across a table is many small steps. The table is the region with the
 * most cells on the frame's edge (a table surrounds the objects on it and
 * runs out of the view; a sheet or tray on it, however large, lies
 * inside), then the most cells. table[] gets 1 on its cells; region[] and
 * queue[] are scratch. */
static void table_cells(const uint8_t *med, int32_t gw, int32_t gh, int32_t step, uint8_t *table,
                        int32_t *region, int32_t *queue)
{
    const int32_t n = gw * gh;
    for (int32_t k = 0; k < n; k++)
        region[k] = -1;
    int32_t best = 0, best_edge = -1, best_size = 0;
    for (int32_t seed = 0; seed < n; seed++) {
        if (region[seed] >= 0)
            continue;
        int32_t head = 0, tail = 0, edge = 0;
        region[seed] = seed;
        queue[tail++] = seed;
        while (head < tail) {
            const int32_t k = queue[head++], i = k % gw, j = k / gw;
            edge += i == 0 || j == 0 || i == gw - 1 || j == gh - 1;
            const int32_t next[4] = {i > 0 ? k - 1 : -1, i + 1 < gw ? k + 1 : -1,
                                     j > 0 ? k - gw : -1, j + 1 < gh ? k + gw : -1};
            for (int32_t e = 0; e < 4; e++) {
                const int32_t m = next[e];
                if (m < 0 || region[m] >= 0)
                    continue;
                const int32_t d = (int32_t)med[m] - med[k];
                if (d <= step && d >= -step) {
                    region[m] = seed;
                    queue[tail++] = m;
                }
            }
        }
        if (edge > best_edge || (edge == best_edge && tail > best_size)) {
            best = seed;
            best_edge = edge;
            best_size = tail;
        }
    }
    for (int32_t k = 0; k < n; k++)
        table[k] = region[k] == best;
}

/* The plane through the table cells of the window of radius r around
 * cell (i, j), by least squares, evaluated at the cell (Q4); false when
 * they are too few or in a line. Exact for light that changes linearly,
 * also where the window is cut by the frame's edge (a mean is biased
 * there, towards the frame's inside). Integer: with r <= 8 every sum and
 * 3 x 3 determinant fits 64 bits. */
static bool table_plane(const uint8_t *med, const uint8_t *table, int32_t gw, int32_t gh, int32_t i,
                        int32_t j, int32_t r, int32_t tol, int32_t *value)
{
    const int32_t j0 = j > r ? j - r : 0, j1 = j + r < gh ? j + r : gh - 1;
    const int32_t i0 = i > r ? i - r : 0, i1 = i + r < gw ? i + r : gw - 1;
    int64_t n = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0, sz = 0, suz = 0, svz = 0;
    int32_t lo = 255, hi = 0;
    for (int32_t jj = j0; jj <= j1; jj++)
        for (int32_t ii = i0; ii <= i1; ii++) {
            if (!table[jj * gw + ii])
                continue;
            const int64_t u = ii - i, v = jj - j, z = med[jj * gw + ii];
            n++;
            su += u;
            sv += v;
            suu += u * u;
            suv += u * v;
            svv += v * v;
            sz += z;
            suz += u * z;
            svz += v * z;
            lo = (int32_t)z < lo ? (int32_t)z : lo;
            hi = (int32_t)z > hi ? (int32_t)z : hi;
        }
    if (n < 6)
        return false;
    /* Cramer's rule for the plane's value at (0, 0) */
    const int64_t m11 = suu * svv - suv * suv, m12 = su * svv - suv * sv, m13 = su * suv - suu * sv;
    const int64_t det = n * m11 - su * m12 + sv * m13;
    if (det <= 0)
        return false;
    const int64_t num = sz * m11 - suz * m12 + svz * m13;
    int64_t a = (num * (1 << GRID_SHIFT) + (num >= 0 ? det / 2 : -det / 2)) / det;
    /* no further than tol beyond the cells it was fitted to */
    const int64_t a_lo = (int64_t)(lo - tol) << GRID_SHIFT, a_hi = (int64_t)(hi + tol)
                                                                   << GRID_SHIFT;
    a = a < a_lo ? a_lo : a > a_hi ? a_hi : a;
    a = a < 0 ? 0 : a > (255 << GRID_SHIFT) ? (255 << GRID_SHIFT) : a;
    *value = (int32_t)a;
    return true;
}

/* Each cell's estimate, Q4: the plane through the table cells of its
 * window of radius r0; where there are too few, the mean of the table
 * cells within 2, 4, ... times r0 (a cell inside a large object). */
static void table_estimates(const uint8_t *med, const uint8_t *table, int32_t gw, int32_t gh,
                            int32_t r0, int32_t tol, int32_t *grid)
{
    for (int32_t j = 0; j < gh; j++)
        for (int32_t i = 0; i < gw; i++) {
            if (table_plane(med, table, gw, gh, i, j, r0, tol, &grid[j * gw + i]))
                continue;
            int32_t sum = 0, n = 0;
            for (int32_t r = r0; n == 0; r *= 2) {
                const int32_t j0 = j > r ? j - r : 0, j1 = j + r < gh ? j + r : gh - 1;
                const int32_t i0 = i > r ? i - r : 0, i1 = i + r < gw ? i + r : gw - 1;
                for (int32_t jj = j0; jj <= j1; jj++)
                    for (int32_t ii = i0; ii <= i1; ii++)
                        if (table[jj * gw + ii]) {
                            sum += med[jj * gw + ii];
                            n++;
                        }
            }
            grid[j * gw + i] = (sum * (1 << GRID_SHIFT) + n / 2) / n;
        }
}

/* The cell below-left of pixel p's centre and p's weight towards the next
 * cell (Q8): cell centres lie at (i + 1/2) cell, pixel centres at p + 1/2;
 * outside the outermost centres the edge cell's value holds. */
static void interpolation_point(int32_t p, int32_t cell, int32_t n, int32_t *i, int32_t *frac)
{
    const int32_t num = 2 * p + 1 - cell; /* (p + 1/2 - cell / 2) in half pixels */
    *i = 0;
    *frac = 0;
    if (num <= 0)
        return;
    *i = num / (2 * cell);
    *frac = ((num - *i * 2 * cell) << WEIGHT_SHIFT) / (2 * cell);
    if (*i >= n - 1) {
        *i = n - 1;
        *frac = 0;
    }
}

/* The bilinear value at column x and row weight fy (Q4 + 2 x Q8) is
 * p[x] + q[x] * fy, with the terms of the cell rows g0 (above) and g1
 * (below): the same integer as interpolating the cell rows to the row
 * first (g0 * (2^8 - fy) + g1 * fy), then along it between cells i and i1
 * with weight fx, expanded. Every term stays below 2^31. */
static void column_terms(const int32_t *g0, const int32_t *g1, const int32_t *col,
                         const int32_t *col_frac, int32_t w, int32_t gw, int32_t *restrict p,
                         int32_t *restrict q)
{
    const int32_t round = 1 << (GRID_SHIFT + 2 * WEIGHT_SHIFT - 1);
    for (int32_t x = 0; x < w; x++) {
        const int32_t i = col[x], i1 = i + 1 < gw ? i + 1 : i, fx = col_frac[x];
        p[x] =
            g0[i] * (1 << 2 * WEIGHT_SHIFT) + round + (g0[i1] - g0[i]) * (1 << WEIGHT_SHIFT) * fx;
        q[x] = (g1[i] - g0[i]) * (1 << WEIGHT_SHIFT) + ((g1[i1] - g0[i1]) - (g1[i] - g0[i])) * fx;
    }
}

/* out[x] = the row's values (Q20) rounded down to grey levels. */
static void store_row(const int32_t *restrict v, uint8_t *restrict out, int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        out[x] = (uint8_t)(v[x] >> (GRID_SHIFT + 2 * WEIGHT_SHIFT));
}

/* v[x] += add[x]: the next row's values (vectorised: no multiply). */
static void add_row(int32_t *restrict v, const int32_t *restrict add, int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        v[x] += add[x];
}

rte_status rte_background_estimate_u8(const rte_image_u8 *src, rte_image_u8 *background,
                                      const rte_background_params *params, rte_arena *arena)
{
    rte_status st = rte_image_u8_check_pair(src, background);
    if (st != RTE_OK)
        return st;
    if (!params || !arena || params->cell < RTE_BACKGROUND_MIN_CELL ||
        params->cell > RTE_BACKGROUND_MAX_CELL || params->radius < 1 ||
        params->radius > RTE_BACKGROUND_MAX_RADIUS || params->tolerance < 0 ||
        params->tolerance > 255 || params->step < 0 || params->step > 255 ||
        src->buf == background->buf)
        return RTE_ERR_ARGUMENT;
    const int32_t w = src->width, h = src->height, cell = params->cell;
    const int32_t gw = cells(w, cell), gh = cells(h, cell);
    const size_t mark = rte_arena_mark(arena);
    uint8_t *med = rte_arena_alloc(arena, (size_t)gw * gh);
    uint8_t *table = rte_arena_alloc(arena, (size_t)gw * gh);
    int32_t *queue = rte_arena_alloc(arena, (size_t)gw * gh * sizeof *queue);
    int32_t *region = rte_arena_alloc(arena, (size_t)gw * gh * sizeof *region);
    int32_t *grid = rte_arena_alloc(arena, (size_t)gw * gh * sizeof *grid);
    uint16_t *hist = rte_arena_alloc(arena, (size_t)gw * HIST_BINS * sizeof *hist);
    int32_t *col = rte_arena_alloc(arena, (size_t)w * 6 * sizeof *col);
    if (!med || !table || !queue || !region || !grid || !hist || !col) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    cell_medians(src, cell, gw, gh, med, hist);
    table_cells(med, gw, gh, params->step, table, region, queue);
    table_estimates(med, table, gw, gh, params->radius, params->tolerance, grid);

    /* Per pixel, the value is p + q * fy between two cell rows (column_terms).
     * fy grows by 2^8 / cell or one more from row to row: v += q * step
     * is then two adds per pixel (qs = q * (2^8 / cell)); any other change
     * of fy (none on frames this code knows of) is a multiply. */
    int32_t *col_frac = col + w, *p = col + 2 * w, *q = col + 3 * w, *qs = col + 4 * w,
            *v = col + 5 * w;
    for (int32_t x = 0; x < w; x++)
        interpolation_point(x, cell, gw, &col[x], &col_frac[x]);
    const int32_t step = (1 << WEIGHT_SHIFT) / cell;
    int32_t row_j = -1, row_fy = 0;
    for (int32_t y = 0; y < h; y++) {
        int32_t j, fy;
        interpolation_point(y, cell, gh, &j, &fy);
        if (j != row_j) {
            const int32_t *g0 = grid + j * gw, *g1 = grid + (j + 1 < gh ? j + 1 : j) * gw;
            column_terms(g0, g1, col, col_frac, w, gw, p, q);
            for (int32_t x = 0; x < w; x++)
                qs[x] = q[x] * step;
        }
        if (j != row_j || (fy != row_fy && fy - row_fy != step && fy - row_fy != step + 1)) {
            for (int32_t x = 0; x < w; x++)
                v[x] = p[x] + q[x] * fy;
        } else if (fy != row_fy) {
            add_row(v, qs, w);
            if (fy - row_fy == step + 1)
                add_row(v, q, w);
        }
        row_j = j;
        row_fy = fy;
        store_row(v, rte_u8_row(background, y), w);
    }
    rte_arena_reset(arena, mark);
    return RTE_OK;
}

/* Regions are labelled by runs: a run is a maximal horizontal stretch of
 * pixels of one side; runs of one side that touch (8-connected) in
 * consecutive rows are united (union-find over run indices). A region's
 * root run holds its pixel count, sum of |d| and flags. */
enum { REGION_STRONG = 1, REGION_DARK = 2, REGION_SHADOW = 4 };

typedef struct run_table {
    int32_t *x0, *x1, *parent, *count;
    int64_t *sum;
    uint8_t *flags;
    int32_t *row_start; /* runs of row y: row_start[y] .. row_start[y + 1] - 1 */
    uint8_t *row;       /* a row's classes, then its floors (paint_regions) */
    int32_t capacity;
} run_table;

/* Runs the table holds for a w x h frame: an average of one per 4 pixels
 * (every other pixel flipping side, all over the frame, exceeds it). */
static int32_t run_capacity(int32_t w, int32_t h)
{
    const int64_t n = (int64_t)w * h / 4 + h;
    return n > INT32_MAX ? INT32_MAX : (int32_t)n;
}

size_t rte_background_threshold_scratch_size(int32_t max_width, int32_t max_height)
{
    if (max_width < 1 || max_height < 1)
        return 0;
    const size_t runs = (size_t)run_capacity(max_width, max_height);
    return rte_arena_piece_size(runs * sizeof(int32_t)) * 4 + /* x0, x1, parent, count */
           rte_arena_piece_size(runs * sizeof(int64_t)) +     /* sum */
           rte_arena_piece_size(runs) +                       /* flags */
           rte_arena_piece_size(((size_t)max_height + 1) * sizeof(int32_t)) +
           rte_arena_piece_size((size_t)max_width); /* row */
}

static int32_t find_root(int32_t *parent, int32_t a)
{
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

/* Unites two trees under the smaller root index (roots precede their runs). */
static void unite(int32_t *parent, int32_t a, int32_t b)
{
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* A pixel's class for the labelling (classify_row): its side where |d| >
 * low and the side is looked for, else 0; the side again two bits up where
 * |d| > high. */
enum { CLASS_SIDE = 3, CLASS_STRONG = 12 };

/* c[x] = the class of pixel x (a: |d|; the side is s > b, bright_class /
 * dark_class 1 / 2 or 0 where not looked for): a loop the compiler
 * vectorises. */
static void classify_row(const uint8_t *restrict a, const uint8_t *restrict s,
                         const uint8_t *restrict b, uint8_t *restrict c, int32_t w, uint8_t low,
                         uint8_t high, uint8_t bright_class, uint8_t dark_class)
{
    for (int32_t x = 0; x < w; x++) {
        const uint8_t side = s[x] > b[x] ? bright_class : dark_class;
        c[x] = (uint8_t)((a[x] > low ? side : 0) | (a[x] > high ? side << 2 : 0));
    }
}

/* The first x1 >= x with c[x1] != 0, or w: eight bytes at a time. */
static inline int32_t skip_zeros(const uint8_t *c, int32_t x, int32_t w)
{
    for (; x + 8 <= w; x += 8) {
        uint64_t v;
        memcpy(&v, c + x, sizeof v);
        if (v) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
            return x + (__builtin_ctzll(v) >> 3);
#else
            break;
#endif
        }
    }
    while (x < w && !c[x])
        x++;
    return x;
}

/* The end of the run of side `side` that starts at x (the first x1 > x
 * whose class has another side, or w); *classes gets the OR of the run's
 * classes. Eight bytes at a time. */
static inline int32_t run_end(const uint8_t *c, int32_t x, int32_t w, uint32_t side,
                              uint32_t *classes)
{
    const uint64_t ones = 0x0101010101010101u, want = ones * side;
    uint64_t seen = 0;
    for (; x + 8 <= w; x += 8) {
        uint64_t v;
        memcpy(&v, c + x, sizeof v);
        const uint64_t other = (v ^ want) & ones * CLASS_SIDE;
        if (other) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
            const int32_t k = __builtin_ctzll(other) >> 3;
            seen |= v & ((UINT64_C(1) << (8 * k)) - 1); /* k < 8 */
            x += k;
            seen |= seen >> 32;
            seen |= seen >> 16;
            seen |= seen >> 8;
            *classes = (uint32_t)seen & 0xFF;
            return x;
#else
            break;
#endif
        }
        seen |= v;
    }
    seen |= seen >> 32;
    seen |= seen >> 16;
    seen |= seen >> 8;
    uint32_t acc = (uint32_t)seen & 0xFF;
    for (; x < w && (c[x] & CLASS_SIDE) == side; x++)
        acc |= c[x];
    *classes = acc;
    return x;
}

/* The sum of a[0..n): a loop the compiler vectorises. */
static inline int64_t sum_bytes(const uint8_t *a, int32_t n)
{
    uint32_t sum = 0; /* n <= 2^23 (RTE_MAX_SIDE) */
    for (int32_t k = 0; k < n; k++)
        sum += a[k];
    return sum;
}

/* One row's runs, appended to the table; unites them with the touching runs
 * of the previous row. a: |d| of the row; c: the classes of its pixels
 * (classify_row). A run is a maximal stretch of pixels of one side (class
 * 1 or 2). Returns the pixels left out for want of room. */
static int64_t label_row(run_table *t, int32_t y, const uint8_t *a, const uint8_t *c, int32_t w,
                         int32_t *n_runs)
{
    int64_t dropped = 0;
    int32_t n = *n_runs;
    t->row_start[y] = n;
    for (int32_t x = skip_zeros(c, 0, w); x < w; x = skip_zeros(c, x, w)) {
        const int32_t x0 = x;
        const uint32_t side = c[x] & CLASS_SIDE;
        uint32_t classes;
        x = run_end(c, x, w, side, &classes);
        if (n == t->capacity) {
            dropped += x - x0;
            continue;
        }
        t->x0[n] = x0;
        t->x1[n] = x - 1;
        t->parent[n] = n;
        t->count[n] = x - x0;
        t->sum[n] = sum_bytes(a + x0, x - x0);
        t->flags[n] = (uint8_t)(((classes & CLASS_STRONG) ? REGION_STRONG : 0) |
                                (side == 1 ? 0 : REGION_DARK));
        n++;
    }
    t->row_start[y + 1] = n;
    if (y > 0) { /* 8-connected: runs overlapping or meeting at a corner */
        int32_t p = t->row_start[y - 1];
        const int32_t p_end = t->row_start[y];
        for (int32_t r = t->row_start[y]; r < n; r++) {
            while (p < p_end && t->x1[p] < t->x0[r] - 1)
                p++;
            for (int32_t q = p; q < p_end && t->x0[q] <= t->x1[r] + 1; q++)
                if (((t->flags[q] ^ t->flags[r]) & REGION_DARK) == 0)
                    unite(t->parent, q, r);
        }
    }
    *n_runs = n;
    return dropped;
}

/* Whether dark run r's region is the shadow of a bright region within
 * `gap` px of it: one both larger and of higher mean contrast (compared as
 * sum_b * count_d > sum_d * count_b). cursor[k] is the first run of row
 * y - gap + k that may reach r: runs of a row come in x order, so the
 * cursors only move on along row y. */
static bool casts_shadow_on(const run_table *t, int32_t y, int32_t h, int32_t gap, int32_t rd,
                            int32_t r, int32_t *cursor)
{
    for (int32_t k = 0; k <= 2 * gap; k++) {
        const int32_t yy = y - gap + k;
        if (yy < 0 || yy >= h)
            continue;
        const int32_t end = t->row_start[yy + 1];
        while (cursor[k] < end && t->x1[cursor[k]] < t->x0[r] - gap)
            cursor[k]++;
        for (int32_t q = cursor[k]; q < end && t->x0[q] <= t->x1[r] + gap; q++) {
            const int32_t rb = t->parent[q];
            if ((t->flags[rb] & (REGION_DARK | REGION_STRONG)) == REGION_STRONG &&
                t->count[rb] > t->count[rd] &&
                t->sum[rb] * t->count[rd] > t->sum[rd] * t->count[rb])
                return true;
        }
    }
    return false;
}

/* a[x] = 255 where a[x] > fl[x], else 0 (vectorised). */
static void above_floor(uint8_t *restrict a, const uint8_t *restrict fl, int32_t w)
{
    for (int32_t x = 0; x < w; x++)
        a[x] = a[x] > fl[x] ? 255 : 0;
}

/* dst holds |d|: each kept region's pixels beyond its own floor (share per
 * mille of its mean |d|) become 255, everything else 0. Per row: the
 * floors of the kept runs, 255 elsewhere (|d| is never above it), then one
 * compare over the row. */
static void paint_regions(const run_table *t, rte_image_u8 *dst, int32_t share)
{
    uint8_t *fl = t->row;
    for (int32_t y = 0; y < dst->height; y++) {
        uint8_t *out = rte_u8_row(dst, y);
        memset(fl, 255, (size_t)dst->width);
        for (int32_t r = t->row_start[y]; r < t->row_start[y + 1]; r++) {
            const int32_t root = t->parent[r];
            if ((t->flags[root] & (REGION_STRONG | REGION_SHADOW)) != REGION_STRONG)
                continue;
            /* floor = share of the region's mean |d| (sum <= 255 count) */
            const int32_t floor =
                (int32_t)(t->sum[root] * share / ((int64_t)t->count[root] * 1000));
            memset(fl + t->x0[r], floor, (size_t)(t->x1[r] + 1 - t->x0[r]));
        }
        above_floor(out, fl, dst->width);
    }
}

/* Flags the shadows (see rte_background_threshold_u8) and counts them. */
static int32_t mark_shadows(run_table *t, int32_t n, int32_t h,
                            const rte_background_threshold_params *params)
{
    int32_t shadows = 0;
    /* Only strong dark regions smaller than the largest strong bright one
     * can be a shadow that matters (weak ones are not painted), and only
     * those of shadow_min_area pixels or more are looked at. */
    int32_t largest_bright = 0;
    for (int32_t r = 0; r < n; r++)
        if (t->parent[r] == r && (t->flags[r] & (REGION_DARK | REGION_STRONG)) == REGION_STRONG)
            largest_bright = t->count[r] > largest_bright ? t->count[r] : largest_bright;
    int32_t cursor[2 * RTE_BACKGROUND_MAX_SHADOW_GAP + 1];
    for (int32_t y = 0; y < h; y++) {
        for (int32_t k = 0; k <= 2 * params->shadow_gap; k++) {
            const int32_t yy = y - params->shadow_gap + k;
            cursor[k] = yy >= 0 && yy < h ? t->row_start[yy] : 0;
        }
        for (int32_t r = t->row_start[y]; r < t->row_start[y + 1]; r++) {
            const int32_t rd = t->parent[r];
            if ((t->flags[rd] & (REGION_DARK | REGION_STRONG | REGION_SHADOW)) !=
                    (REGION_DARK | REGION_STRONG) ||
                t->count[rd] >= largest_bright || t->count[rd] < params->shadow_min_area)
                continue;
            if (casts_shadow_on(t, y, h, params->shadow_gap, rd, r, cursor)) {
                t->flags[rd] |= REGION_SHADOW;
                shadows++;
            }
        }
    }
    return shadows;
}

rte_status rte_background_threshold_u8(const rte_image_u8 *src, const rte_image_u8 *background,
                                       rte_image_u8 *dst,
                                       const rte_background_threshold_params *params,
                                       rte_arena *arena, rte_background_threshold_result *result)
{
    rte_status st = rte_image_u8_check_pair(src, background);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    if (!params || !arena || params->high < 0 || params->high > 255 || params->min_contrast < 1 ||
        params->min_contrast > 255 || params->shadow_gap < 0 ||
        params->shadow_gap > RTE_BACKGROUND_MAX_SHADOW_GAP || params->region_share_permille < 0 ||
        params->region_share_permille > 1000 || params->shadow_min_area < 0 ||
        dst->buf == src->buf || dst->buf == background->buf)
        return RTE_ERR_ARGUMENT;
    const int32_t w = src->width, h = src->height;
    const size_t mark = rte_arena_mark(arena);
    run_table t = {.capacity = run_capacity(w, h)};
    const size_t runs = (size_t)t.capacity;
    t.x0 = rte_arena_alloc(arena, runs * sizeof *t.x0);
    t.x1 = rte_arena_alloc(arena, runs * sizeof *t.x1);
    t.parent = rte_arena_alloc(arena, runs * sizeof *t.parent);
    t.count = rte_arena_alloc(arena, runs * sizeof *t.count);
    t.sum = rte_arena_alloc(arena, runs * sizeof *t.sum);
    t.flags = rte_arena_alloc(arena, runs);
    t.row_start = rte_arena_alloc(arena, ((size_t)h + 1) * sizeof *t.row_start);
    t.row = rte_arena_alloc(arena, (size_t)w);
    if (!t.x0 || !t.x1 || !t.parent || !t.count || !t.sum || !t.flags || !t.row_start || !t.row) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    /* |d| into dst first (the regions are painted over it at the end) */
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *s = rte_u8_row(src, y), *b = rte_u8_row(background, y);
        uint8_t *a = rte_u8_row(dst, y);
        for (int32_t x = 0; x < w; x++) { /* max - min: vectorised */
            const uint8_t hi = s[x] > b[x] ? s[x] : b[x], lo = s[x] > b[x] ? b[x] : s[x];
            a[x] = (uint8_t)(hi - lo);
        }
    }
    int32_t high = params->high;
    if (high == 0) {
        uint32_t hist[256];
        rte_histogram_u8(dst, hist);
        rte_threshold_otsu_histogram(hist, &high);
    }
    if (high < params->min_contrast)
        high = params->min_contrast;
    const int32_t low = high * 2 / 3; /* nearer half the contrast: the edge of a blurred step */

    int32_t n = 0;
    int64_t dropped = 0;
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *a = rte_u8_row(dst, y);
        classify_row(a, rte_u8_row(src, y), rte_u8_row(background, y), t.row, w, (uint8_t)low,
                     (uint8_t)high, params->bright ? 1 : 0, params->dark ? 2 : 0);
        dropped += label_row(&t, y, a, t.row, w, &n);
    }
    /* Statistics to the roots; every run then points at its root. */
    int32_t regions = 0, shadows = 0;
    for (int32_t r = 0; r < n; r++) {
        const int32_t root = find_root(t.parent, r);
        t.parent[r] = root;
        if (root == r) {
            regions++;
            continue;
        }
        t.count[root] += t.count[r];
        t.sum[root] += t.sum[r];
        t.flags[root] |= t.flags[r] & REGION_STRONG;
    }
    if (params->drop_shadows && params->bright && params->dark)
        shadows = mark_shadows(&t, n, h, params);
    paint_regions(&t, dst, params->region_share_permille);
    if (result)
        *result = (rte_background_threshold_result){.high = high,
                                                    .low = low,
                                                    .regions = regions,
                                                    .shadows = shadows,
                                                    .dropped_pixels = dropped};
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
