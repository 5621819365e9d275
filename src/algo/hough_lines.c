/* Standard Hough lines (cv::HoughLines semantics), integer only.
 *
 * The edge points are listed once, packed as y << 16 | x. Voting then runs
 * angle by angle: the rho bins of a block of points come from one vector
 * kernel (simd/rows.h), and each bin is one increment of a 16-bit cell.
 * Consecutive points often fall in the same bin (a run of pixels along a
 * line), and an increment that waits on the previous one to the same cell
 * is slow, so points vote in turn into RTE_HOUGH_LINE_COPIES copies of the
 * angle's row, which a second kernel adds into a 32-bit row afterwards.
 * Only three 32-bit rows are kept: an angle's peaks are found as soon as
 * the next angle is voted. All rows stay in L1. */
#include "rtedge/hough.h"

#include <string.h>

#include "hough_internal.h"
#include "hough_rows.h"
#include "simd/rows.h"

enum {
    LINE_COPIES = RTE_HOUGH_LINE_COPIES, /* rows the points vote into in turn */
    LINE_BLOCK = 512,                    /* points whose bins are computed at once */
    /* Points voted between two sums of the copies into the 32-bit row: a
     * copy then counts at most LINE_CHUNK / LINE_COPIES < 65536 votes. */
    LINE_CHUNK = 510 * LINE_BLOCK,
};

_Static_assert(LINE_COPIES == 4, "vote_angle and hough_sum_copies_row use 4 copies");

void rte_hough_point_bins_c(const uint32_t *pts, int32_t n, int32_t rho_cos, int32_t rho_sin,
                            int32_t bias, int32_t shift, int32_t *idx)
{
    hough_point_bins_row(pts, n, rho_cos, rho_sin, bias, shift, idx);
}

void rte_hough_sum_copies_c(int32_t *cells, uint16_t *copies, int32_t cstep, int32_t n)
{
    hough_sum_copies_row(cells, copies, cstep, n);
}

rte_hough_line_rows rte_hough_line_rows_select(uint32_t features)
{
    return RTE_SIMD_PICK(
        features, ((rte_hough_line_rows){rte_hough_point_bins_c, rte_hough_sum_copies_c}),
        ((rte_hough_line_rows){rte_hough_point_bins_avx2, rte_hough_sum_copies_avx2}),
        /* the point bins are written with AVX2 intrinsics */
        ((rte_hough_line_rows){rte_hough_point_bins_avx2, rte_hough_sum_copies_avx512}),
        ((rte_hough_line_rows){rte_hough_point_bins_c, rte_hough_sum_copies_c}));
}

size_t rte_hough_lines_scratch_size(const rte_hough_config *cfg, int32_t max_lines)
{
    if (!cfg || max_lines < 0)
        return 0;
    size_t pixels = (size_t)cfg->max_width * (size_t)cfg->max_height;
    size_t astep = (size_t)rte_hough_rho_bins(cfg, cfg->max_width, cfg->max_height) + 2;
    return rte_arena_piece_size(pixels * sizeof(uint32_t)) +
           rte_arena_piece_size(LINE_BLOCK * sizeof(int32_t)) +
           rte_arena_piece_size(LINE_COPIES * astep * sizeof(uint16_t)) +
           rte_arena_piece_size(3 * astep * sizeof(int32_t)) +
           rte_arena_piece_size((size_t)max_lines * sizeof(uint64_t));
}

int64_t rte_hough_line_rho_q16(const rte_hough_config *cfg, const rte_hough_line *line)
{
    return (int64_t)line->rho_bin * cfg->rho_q16;
}

int64_t rte_hough_line_theta_q16(const rte_hough_config *cfg, const rte_hough_line *line)
{
    return (int64_t)cfg->theta0_q16 + (int64_t)line->theta_bin * cfg->theta_q16;
}

/* One angle's 32-bit row, non-zero only in [lo, hi]. */
typedef struct line_row {
    int32_t *cells; /* cells[-1] and cells[numrho] stay 0 */
    int32_t lo, hi;
} line_row;

/* What voting one angle needs. */
typedef struct line_vote {
    rte_hough_line_rows rows;
    const uint32_t *pts;
    int32_t npts;
    int32_t *idx;     /* LINE_BLOCK bins */
    uint16_t *copies; /* LINE_COPIES rows of cstep cells, all 0 between angles */
    int32_t cstep;
    int32_t bias, shift;
    int32_t xmax, ylo, yhi; /* the points lie in [0, xmax] x [ylo, yhi] */
} line_vote;

/* The votes of every point at angle (c, s) into row->cells (which are 0),
 * setting row->lo, row->hi to the bins the points can reach. */
static void vote_angle(const line_vote *v, int32_t c, int32_t s, line_row *row)
{
    /* x c + y s is linear: its extremes over the points' box are corners */
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int k = 0; k < 4; k++) {
        int64_t r = (int64_t)((k & 1) ? v->xmax : 0) * c +
                    (int64_t)((k & 2) ? v->yhi : v->ylo) * s + v->bias;
        lo = r < lo ? r : lo;
        hi = r > hi ? r : hi;
    }
    row->lo = (int32_t)(lo >> v->shift);
    row->hi = (int32_t)(hi >> v->shift);
    uint16_t *c0 = v->copies, *c1 = c0 + v->cstep, *c2 = c1 + v->cstep, *c3 = c2 + v->cstep;
    for (int32_t start = 0; start < v->npts; start += LINE_CHUNK) {
        const int32_t end = v->npts - start > LINE_CHUNK ? start + LINE_CHUNK : v->npts;
        for (int32_t b = start; b < end; b += LINE_BLOCK) {
            const int32_t m = end - b > LINE_BLOCK ? LINE_BLOCK : end - b;
            v->rows.bins(v->pts + b, m, c, s, v->bias, v->shift, v->idx);
            const int32_t *restrict idx = v->idx;
            int32_t i = 0;
            for (; i + 4 <= m; i += 4) {
                c0[idx[i]]++;
                c1[idx[i + 1]]++;
                c2[idx[i + 2]]++;
                c3[idx[i + 3]]++;
            }
            for (; i < m; i++)
                c0[idx[i]]++;
        }
        if (row->hi >= row->lo)
            v->rows.sum(row->cells + row->lo, c0 + row->lo, v->cstep, row->hi - row->lo + 1);
    }
}

rte_status rte_hough_lines(const rte_hough_config *cfg, const rte_image_u8 *edges,
                           int32_t threshold, rte_arena *arena, rte_hough_line *lines,
                           int32_t max_lines, int32_t *count, bool *truncated)
{
    if (!arena || !count || !truncated || threshold < 0 || max_lines < 0 ||
        (max_lines > 0 && !lines))
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_hough_begin(cfg, edges, count, truncated);
    if (st != RTE_OK)
        return st;
    const int32_t w = edges->width, h = edges->height;

    const int32_t numrho = rte_hough_rho_bins(cfg, w, h), numangle = cfg->num_angles;
    const int32_t astep = numrho + 2;
    const size_t pixels = (size_t)w * (size_t)h;
    const size_t mark = rte_arena_mark(arena);
    uint32_t *pts = rte_arena_alloc(arena, pixels * sizeof(uint32_t));
    int32_t *idx = rte_arena_alloc(arena, LINE_BLOCK * sizeof(int32_t));
    uint16_t *copies = rte_arena_alloc(arena, LINE_COPIES * (size_t)astep * sizeof(uint16_t));
    int32_t *rows = rte_arena_alloc(arena, 3 * (size_t)astep * sizeof(int32_t));
    uint64_t *keys = rte_arena_alloc(arena, (size_t)max_lines * sizeof(uint64_t));
    if (!pts || !idx || !copies || !rows || !keys) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    memset(copies, 0, LINE_COPIES * (size_t)astep * sizeof(uint16_t));
    memset(rows, 0, 3 * (size_t)astep * sizeof(int32_t));

    const int32_t npts = rte_hough_list_points(edges, NULL, pts);
    const line_vote v = {rte_hough_line_rows_select(rte_cpu_features()),
                         pts,
                         npts,
                         idx,
                         copies,
                         astep,
                         rte_hough_rho_bias(cfg, numrho),
                         cfg->trig_shift,
                         w - 1,
                         npts ? (int32_t)(pts[0] >> 16) : 0,
                         npts ? (int32_t)(pts[npts - 1] >> 16) : 0};

    /* Ring of three rows: angle n in ring[n % 3]. Before angle n's peaks
     * are found, angle n + 1 is voted into the row angle n - 2 left (all 0
     * again); past the last angle that row stays 0, as does ring[2] before
     * angle 0. */
    line_row ring[3];
    for (int k = 0; k < 3; k++)
        ring[k] = (line_row){rows + (size_t)k * astep + 1, 0, -1};
    rte_hough_topk top = {keys, max_lines, 0, 0};
    if (npts > 0)
        vote_angle(&v, cfg->rho_cos[0], cfg->rho_sin[0], &ring[0]);
    for (int32_t n = 0; n < numangle && npts > 0; n++) {
        line_row *cur = &ring[n % 3], *next = &ring[(n + 1) % 3], *prev = &ring[(n + 2) % 3];
        if (n + 1 < numangle)
            vote_angle(&v, cfg->rho_cos[n + 1], cfg->rho_sin[n + 1], next);
        const int32_t *a = cur->cells, *below = prev->cells, *above = next->cells;
        for (int32_t r = cur->lo; r <= cur->hi; r++) {
            int32_t x = a[r];
            if (x > threshold && x > a[r - 1] && x >= a[r + 1] && x > below[r] && x >= above[r])
                rte_hough_topk_push(&top, rte_hough_key(x, (uint32_t)(n * numrho + r)));
        }
        for (int32_t r = prev->lo; r <= prev->hi; r++)
            prev->cells[r] = 0;
        prev->lo = 0;
        prev->hi = -1;
    }
    rte_hough_topk_sort(&top);
    for (int32_t i = 0; i < top.size; i++) {
        uint32_t id = rte_hough_key_index(top.keys[i]);
        lines[i].theta_bin = (int32_t)(id / (uint32_t)numrho);
        lines[i].rho_bin = (int32_t)(id % (uint32_t)numrho) - (numrho - 1) / 2;
        lines[i].votes = rte_hough_key_votes(top.keys[i]);
    }
    *count = top.size;
    *truncated = top.seen > top.size;
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
