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

/* A histogram's bins. */
#define HIST_BINS 256

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

/* Sums over the table cells of a window, in grid coordinates (ii, jj) and
 * median z: the count, then those of ii, jj, ii^2, ii jj, jj^2, z, ii z and
 * jj z, in that order. */
enum { M_N, M_I, M_J, M_II, M_IJ, M_JJ, M_Z, M_IZ, M_JZ, MOMENTS };

/* Scratch of table_estimates for a grid gw x gh, in int64: the columns'
 * sums (5 gw), their prefix sums along the row (MOMENTS (gw + 1)), the
 * columns' median ranges (gw, two int32 each) and the summed-area tables of
 * the count and the medians (2 (gw + 1) (gh + 1)). */
static size_t estimate_scratch(size_t gw, size_t gh)
{
    return (5 * gw + MOMENTS * (gw + 1) + gw + 2 * (gw + 1) * (gh + 1)) * sizeof(int64_t);
}

/* The arena pieces of the estimate, in the order taken. */
static size_t estimate_pieces(int32_t w, int32_t h, int32_t cell)
{
    const size_t gw = (size_t)cells(w, cell), gh = (size_t)cells(h, cell);
    return rte_arena_piece_size(gw * gh) * 2 +                       /* medians, table flags */
           rte_arena_piece_size(gw * gh * sizeof(int32_t)) * 3 +     /* queue, regions, grid */
           rte_arena_piece_size(gw * HIST_BINS * sizeof(uint16_t)) + /* a row of histograms */
           rte_arena_piece_size(estimate_scratch(gw, gh)) +
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
 * quarter of the histogram updates. A row of samples goes across the cells
 * (the k-th sample of every cell, then the (k+1)-th): consecutive counts go
 * to different cells' histograms, where along a flat cell most would add
 * to the bin the last one did, a chain of read-modify-writes of one
 * address. The search for the median skips along sums of 16 bins. */
static void cell_medians(const rte_image_u8 *src, int32_t cell, int32_t gw, int32_t gh,
                         uint8_t *med, uint16_t *hist)
{
    const int32_t w = src->width, h = src->height, step = cell >= 8 ? 2 : 1;
    const int32_t full = w / cell; /* cells of full width */
    for (int32_t j = 0; j < gh; j++) {
        const int32_t y0 = j * cell, y1 = y0 + cell < h ? y0 + cell : h;
        memset(hist, 0, (size_t)gw * HIST_BINS * sizeof *hist);
        for (int32_t y = y0; y < y1; y += step) {
            const uint8_t *row = rte_u8_row(src, y);
            for (int32_t k = 0; k < cell; k += step)
                for (int32_t i = 0; i < full; i++)
                    hist[i * HIST_BINS + row[i * cell + k]]++;
            for (int32_t x = full * cell; x < w; x += step)
                hist[full * HIST_BINS + row[x]]++;
        }
        const int32_t rows = (y1 - y0 + step - 1) / step;
        for (int32_t i = 0; i < gw; i++) {
            const int32_t x0 = i * cell, x1 = (i + 1) * cell < w ? (i + 1) * cell : w;
            const int32_t half = (rows * ((x1 - x0 + step - 1) / step) + 1) / 2;
            const uint16_t *hc = hist + (size_t)i * HIST_BINS;
            int32_t v = 0, sum = 0;
            for (;; v += 16) {
                int32_t s16 = 0;
                for (int32_t k = 0; k < 16; k++)
                    s16 += hc[v + k];
                if (sum + s16 >= half)
                    break;
                sum += s16;
            }
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

/* A window's table cells' plane by least squares, evaluated at the
 * window's cell (i, j) (Q4), from their sums m and the range [lo, hi] of
 * their medians; false when they are too few or in a line. Exact for light
 * that changes linearly, also where the window is cut by the frame's edge
 * (a mean is biased there, towards the frame's inside). The sums are
 * re-centred on (i, j) exactly; every one, and every 3 x 3 determinant,
 * fits 64 bits for windows of radius <= 8. */
static bool table_plane(const int64_t *m, int32_t lo, int32_t hi, int32_t i, int32_t j, int32_t tol,
                        int32_t *value)
{
    const int64_t n = m[M_N];
    if (n < 6)
        return false;
    const int64_t su = m[M_I] - n * i, sv = m[M_J] - n * j;
    const int64_t suu = m[M_II] - 2 * i * m[M_I] + n * i * i;
    const int64_t svv = m[M_JJ] - 2 * j * m[M_J] + n * j * j;
    const int64_t suv = m[M_IJ] - (int64_t)i * m[M_J] - (int64_t)j * m[M_I] + n * i * j;
    const int64_t sz = m[M_Z], suz = m[M_IZ] - i * sz, svz = m[M_JZ] - j * sz;
    /* Cramer's rule for the plane's value at (0, 0) */
    const int64_t m11 = suu * svv - suv * suv, m12 = su * svv - suv * sv, m13 = su * suv - suu * sv;
    const int64_t det = n * m11 - su * m12 + sv * m13;
    if (det <= 0)
        return false;
    const int64_t num = sz * m11 - suz * m12 + svz * m13;
    int64_t a = (num * (1 << GRID_SHIFT) + (num >= 0 ? det / 2 : -det / 2)) / det;
    /* no further than tol beyond the cells it was fitted to */
    const int64_t a_lo = (int64_t)(lo - tol) * (1 << GRID_SHIFT),
                  a_hi = (int64_t)(hi + tol) * (1 << GRID_SHIFT);
    a = a < a_lo ? a_lo : a > a_hi ? a_hi : a;
    a = a < 0 ? 0 : a > (255 << GRID_SHIFT) ? (255 << GRID_SHIFT) : a;
    *value = (int32_t)a;
    return true;
}

/* Row jj's table cells into the columns' sums (sign +1) or out (-1). */
static void column_sums_add(const uint8_t *med, const uint8_t *table, int32_t gw, int32_t jj,
                            int64_t sign, int64_t *col)
{
    int64_t *cn = col, *cj = col + gw, *cjj = col + 2 * gw, *cz = col + 3 * gw, *cjz = col + 4 * gw;
    for (int32_t ii = 0; ii < gw; ii++) {
        const int64_t t = sign * table[jj * gw + ii], z = t * med[jj * gw + ii];
        cn[ii] += t;
        cj[ii] += t * jj;
        cjj[ii] += t * jj * jj;
        cz[ii] += z;
        cjz[ii] += z * jj;
    }
}

/* Each cell's estimate, Q4: the plane through the table cells of its
 * window of radius r0; where there are too few, the mean of the table
 * cells within 1, 2, 4, ... times r0 (a cell inside a large object). The
 * windows' sums come from columns' sums that slide down the grid, prefix
 * summed along each row; the means' from summed-area tables. */
static void table_estimates(const uint8_t *med, const uint8_t *table, int32_t gw, int32_t gh,
                            int32_t r0, int32_t tol, int32_t *grid, int64_t *scratch)
{
    int64_t *col = scratch, *pre = col + 5 * gw, *range = pre + MOMENTS * (gw + 1);
    int64_t *sat_n = range + gw, *sat_z = sat_n + (size_t)(gw + 1) * (gh + 1);
    int32_t *lo_of = (int32_t *)range, *hi_of = lo_of + gw;
    const int32_t sw = gw + 1;
    for (int32_t i = 0; i <= gw; i++)
        sat_n[i] = sat_z[i] = 0;
    for (int32_t jj = 0; jj < gh; jj++) {
        int64_t rn = 0, rz = 0;
        sat_n[(jj + 1) * sw] = sat_z[(jj + 1) * sw] = 0;
        for (int32_t ii = 0; ii < gw; ii++) {
            rn += table[jj * gw + ii];
            rz += table[jj * gw + ii] * med[jj * gw + ii];
            sat_n[(jj + 1) * sw + ii + 1] = sat_n[jj * sw + ii + 1] + rn;
            sat_z[(jj + 1) * sw + ii + 1] = sat_z[jj * sw + ii + 1] + rz;
        }
    }

    memset(col, 0, 5 * (size_t)gw * sizeof *col);
    for (int32_t jj = 0; jj <= r0 && jj < gh; jj++)
        column_sums_add(med, table, gw, jj, 1, col);
    for (int32_t j = 0; j < gh; j++) {
        const int32_t j0 = j > r0 ? j - r0 : 0, j1 = j + r0 < gh ? j + r0 : gh - 1;
        if (j > 0 && j + r0 < gh)
            column_sums_add(med, table, gw, j + r0, 1, col);
        if (j - r0 - 1 >= 0)
            column_sums_add(med, table, gw, j - r0 - 1, -1, col);
        const int64_t *cn = col, *cj = col + gw, *cjj = col + 2 * gw, *cz = col + 3 * gw,
                      *cjz = col + 4 * gw;
        for (int32_t k = 0; k < MOMENTS; k++)
            pre[k] = 0;
        for (int32_t ii = 0; ii < gw; ii++) {
            const int64_t *p = pre + ii * MOMENTS;
            int64_t *q = pre + (ii + 1) * MOMENTS;
            q[M_N] = p[M_N] + cn[ii];
            q[M_I] = p[M_I] + ii * cn[ii];
            q[M_J] = p[M_J] + cj[ii];
            q[M_II] = p[M_II] + (int64_t)ii * ii * cn[ii];
            q[M_IJ] = p[M_IJ] + ii * cj[ii];
            q[M_JJ] = p[M_JJ] + cjj[ii];
            q[M_Z] = p[M_Z] + cz[ii];
            q[M_IZ] = p[M_IZ] + ii * cz[ii];
            q[M_JZ] = p[M_JZ] + cjz[ii];
            int32_t lo = 255, hi = 0;
            for (int32_t jj = j0; jj <= j1; jj++)
                if (table[jj * gw + ii]) {
                    const int32_t z = med[jj * gw + ii];
                    lo = z < lo ? z : lo;
                    hi = z > hi ? z : hi;
                }
            lo_of[ii] = lo;
            hi_of[ii] = hi;
        }
        for (int32_t i = 0; i < gw; i++) {
            const int32_t i0 = i > r0 ? i - r0 : 0, i1 = i + r0 < gw ? i + r0 : gw - 1;
            int64_t m[MOMENTS];
            for (int32_t k = 0; k < MOMENTS; k++)
                m[k] = pre[(i1 + 1) * MOMENTS + k] - pre[i0 * MOMENTS + k];
            int32_t lo = 255, hi = 0;
            for (int32_t ii = i0; ii <= i1; ii++) {
                lo = lo_of[ii] < lo ? lo_of[ii] : lo;
                hi = hi_of[ii] > hi ? hi_of[ii] : hi;
            }
            if (table_plane(m, lo, hi, i, j, tol, &grid[j * gw + i]))
                continue;
            int64_t sum = 0, n = 0;
            for (int32_t r = r0; n == 0; r *= 2) {
                const int32_t b0 = j > r ? j - r : 0, b1 = j + r < gh ? j + r + 1 : gh;
                const int32_t a0 = i > r ? i - r : 0, a1 = i + r < gw ? i + r + 1 : gw;
                n = sat_n[b1 * sw + a1] - sat_n[b0 * sw + a1] - sat_n[b1 * sw + a0] +
                    sat_n[b0 * sw + a0];
                sum = sat_z[b1 * sw + a1] - sat_z[b0 * sw + a1] - sat_z[b1 * sw + a0] +
                      sat_z[b0 * sw + a0];
            }
            grid[j * gw + i] = (int32_t)((sum * (1 << GRID_SHIFT) + n / 2) / n);
        }
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
    int64_t *sums = rte_arena_alloc(arena, estimate_scratch((size_t)gw, (size_t)gh));
    int32_t *col = rte_arena_alloc(arena, (size_t)w * 6 * sizeof *col);
    if (!med || !table || !queue || !region || !grid || !sums || !hist || !col) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    cell_medians(src, cell, gw, gh, med, hist);
    table_cells(med, gw, gh, params->step, table, region, queue);
    table_estimates(med, table, gw, gh, params->radius, params->tolerance, grid, sums);

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
