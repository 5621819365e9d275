/* The table's brightness (see include/rtedge/background.h; the threshold
 * against it is background_threshold.c). Per frame, integer only. */
#include "rtedge/background.h"

#include <stdint.h>
#include <string.h>

#include "background_rows.h"
#include "rtedge/cpu.h"
#include "simd/rows.h"

/* Grid values carry 4 fractional bits; bilinear weights 8. */
#define GRID_SHIFT 4
#define WEIGHT_SHIFT 8
_Static_assert(GRID_SHIFT + 2 * WEIGHT_SHIFT == RTE_BACKGROUND_VALUE_SHIFT,
               "background_rows.h stores values of this many fractional bits");

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

/* The C references of the background row family (background_rows.h;
 * the threshold's rows are used by background_threshold.c). */
RTE_BACKGROUND_ROWS_DEFINE(c)

rte_background_rows rte_background_rows_select(uint32_t features)
{
#define RTE_BACKGROUND_ROWS_OF(isa)                                                     \
    {                                                                                   \
        rte_background_add_row_##isa, rte_background_store_row_##isa,                   \
            rte_background_absdiff_row_##isa, rte_background_classify_row_##isa,        \
            rte_background_above_floor_row_##isa, rte_background_chroma_diff_row_##isa, \
            rte_background_tint_row_##isa, rte_background_shade_row_##isa,              \
            rte_background_shade_class_row_##isa                                        \
    }
    static const rte_background_rows c = RTE_BACKGROUND_ROWS_OF(c);
#ifdef RTE_SIMD_X86
    static const rte_background_rows avx2 = RTE_BACKGROUND_ROWS_OF(avx2);
    static const rte_background_rows avx512 = RTE_BACKGROUND_ROWS_OF(avx512);
#endif
#undef RTE_BACKGROUND_ROWS_OF
    return RTE_SIMD_PICK(features, c, avx2, avx512, c);
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
    const rte_background_rows rows = rte_background_rows_select(rte_cpu_features());
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
            rows.add(v, qs, w);
            if (fy - row_fy == step + 1)
                rows.add(v, q, w);
        }
        row_j = j;
        row_fy = fy;
        rows.store(v, rte_u8_row(background, y), w);
    }
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
