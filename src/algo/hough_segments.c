/* Line segments: the progressive probabilistic Hough transform of
 * cv::HoughLinesP, integer only and with its known flaws fixed (see
 * docs/hough.md):
 *   - the point order is a Fisher-Yates shuffle driven by a fixed-seed
 *     xorshift32, so the output is the same on every run and platform;
 *   - the walk of the cell's quantised line accepts pixels one pixel
 *     across it too; the line is then refitted (integer principal axis of
 *     the pixels found) and followed again, taking only pixels on it, so a
 *     long edge is not lost where the quantised angle drifts off it and the
 *     ends stop where the edge leaves the line;
 *   - a segment consumes the run of edge pixels across it (up to two
 *     pixels either side), so a 2-pixel-thick edge gives one segment, not
 *     several overlapping ones;
 *   - only points that voted are un-voted when a line is consumed, so a
 *     cell never goes negative and 16 bits hold it (cell_bound); cells
 *     start at 8 bits and widen to 16 the first time one overflows
 *     (see vote_cells);
 *   - the minimum length is Euclidean. */
#include "rtedge/hough.h"

#include <stddef.h>
#include <string.h>

#include "hough_internal.h"
#include "hough_rows.h"
#include "simd/rows.h"

#include "hough_walk.h"

void rte_hough_bins_c(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n, int32_t x,
                      int32_t y, int32_t bias, int32_t shift, const int32_t *row_base, int32_t *idx)
{
    hough_bins_row(rho_cos, rho_sin, n, x, y, bias, shift, row_base, idx);
}

rte_hough_bins_fn rte_hough_bins_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, rte_hough_bins_c, rte_hough_bins_avx2, rte_hough_bins_avx512,
                         rte_hough_bins_c);
}

/* Everything the search shares. */
typedef struct seg_ctx {
    const rte_hough_config *cfg;
    rte_hough_bins_fn bins;
    const int32_t *row_base; /* where each angle's rho bins start in acc (compact_rows) */
    void *acc;               /* cells of 8 bits, or 16 once wide: see vote_cells */
    int wide;
    size_t ncells;
    int32_t *idx; /* the cells of one point, one per angle */
    int32_t numangle, bias;
    int64_t min_len2;
    uint32_t *gone; /* voted pixels of the segment being consumed */
    walk_ctx wc;
    rte_hough_segment *segments; /* the output */
    int32_t max_segments, nseg;
    bool truncated;
} seg_ctx;

/* The accumulator cells of the point (x, y), one per angle. */
static inline void cells(const seg_ctx *sc, int32_t x, int32_t y, int32_t *idx)
{
    sc->bins(sc->cfg->rho_cos, sc->cfg->rho_sin, sc->numangle, x, y, sc->bias, sc->cfg->trig_shift,
             sc->row_base, idx);
}

/* Cells hold a count biased so that bit 7 (8-bit cells) or bit 15 (16-bit
 * cells) of a cell's value before an increment is set exactly when the
 * increment brings the count to the threshold or above: the value is
 * count + CELL_TOP + 1 - threshold. An OR of the old values then tells
 * whether a point reached the threshold: one instruction per increment and
 * no chain of comparisons from one increment to the next (they overlap).
 *
 * Cells start at 8 bits, which halves the accumulator (0.23 MB at
 * 1280x720, where the vote runs at the speed of the second-level cache),
 * and hold counts up to threshold + 126. A count goes past the threshold
 * only while the walks from its cell fail, so that is rare; the increment
 * that passes it wraps a cell to 0, which no count can give otherwise, and
 * the whole accumulator widens to 16 bits in place there and then
 * (widen). Thresholds above 128 start at 16 bits. */
#define CELL8_TOP 128u
#define CELL16_TOP 32768u
/* The largest threshold that starts with 8-bit cells. tests/unit builds a
 * copy of this file with 0 (16-bit cells only) as the reference the 8-bit
 * path and its widening must match. */
#ifndef HOUGH_CELL8_MAX_THRESHOLD
#define HOUGH_CELL8_MAX_THRESHOLD 128
#endif

/* The accumulator as 8-bit or 16-bit cells; wide is a constant in each
 * copy of the loops that use it. Both views are restrict (no other pointer
 * reaches the cells) and a copy uses only one of them. */
typedef struct cells_view {
    uint8_t *restrict c8;
    uint16_t *restrict c16;
} cells_view;

static inline cells_view cells_of(const seg_ctx *sc) { return (cells_view){sc->acc, sc->acc}; }

static inline uint32_t cell_get(cells_view v, const int wide, int32_t i)
{
    return wide ? v.c16[i] : v.c8[i];
}

static inline void cell_set(cells_view v, const int wide, int32_t i, uint32_t x)
{
    if (wide)
        v.c16[i] = (uint16_t)x;
    else
        v.c8[i] = (uint8_t)x;
}

/* Adds the votes of the point (x, y) (its cells in sc->idx); returns
 * nonzero when one of them reached the threshold. */
static inline __attribute__((always_inline)) uint32_t vote_cells(const seg_ctx *sc, const int wide)
{
    /* locals: a byte store may alias any field of *sc */
    const int32_t *restrict idx = sc->idx, n = sc->numangle;
    const cells_view acc = cells_of(sc);
    uint32_t o0 = 0, o1 = 0, o2 = 0, o3 = 0;
    int32_t a = 0;
    /* the four bins are read before any cell is written: a byte store may
     * alias idx, and the compiler would read each bin again after it */
    for (; a + 4 <= n; a += 4) {
        const int32_t i0 = idx[a], i1 = idx[a + 1], i2 = idx[a + 2], i3 = idx[a + 3];
        const uint32_t v0 = cell_get(acc, wide, i0), v1 = cell_get(acc, wide, i1);
        cell_set(acc, wide, i0, v0 + 1);
        cell_set(acc, wide, i1, v1 + 1);
        const uint32_t v2 = cell_get(acc, wide, i2), v3 = cell_get(acc, wide, i3);
        cell_set(acc, wide, i2, v2 + 1);
        cell_set(acc, wide, i3, v3 + 1);
        o0 |= v0;
        o1 |= v1;
        o2 |= v2;
        o3 |= v3;
    }
    for (; a < n; a++) {
        const int32_t i0 = idx[a];
        const uint32_t v = cell_get(acc, wide, i0);
        cell_set(acc, wide, i0, v + 1);
        o0 |= v;
    }
    return (o0 | o1 | o2 | o3) & (wide ? CELL16_TOP : CELL8_TOP);
}

/* 8-bit cells to 16 in place (the memory holds 16-bit cells): from the top
 * down, so each 8-bit cell is read before its bytes are written over. A 0
 * is a wrapped count of threshold + 127, the only way to reach 0. */
static void widen(seg_ctx *sc)
{
    const uint8_t *narrow = sc->acc;
    uint16_t *wide = sc->acc;
    for (size_t i = sc->ncells; i-- > 0;) {
        const uint32_t v = narrow[i];
        wide[i] = (uint16_t)((v ? v : 256u) + (CELL16_TOP - CELL8_TOP));
    }
    sc->wide = 1;
}

/* The first angle holding the most votes among the cells of the point just
 * voted: OpenCV's `max_val < val` scan. Only for points that reach the
 * threshold. An 8-bit cell the vote wrapped (0) counts as 256, above the
 * rest (the counts follow the values' order otherwise), and is reported in
 * *wrapped. */
static inline __attribute__((always_inline)) int32_t
strongest_cell(const seg_ctx *sc, const int wide, uint32_t *wrapped)
{
    const int32_t *idx = sc->idx, n = sc->numangle;
    int32_t best_a = 0;
    uint32_t best = 0, zero = 0;
    for (int32_t a = 0; a < n; a++) {
        uint32_t v = cell_get(cells_of(sc), wide, idx[a]);
        if (!wide) {
            zero |= v == 0;
            v = ((v - 1) & 0xFFu) + 1; /* 0 -> 256 */
        }
        best_a = v > best ? a : best_a; /* selects, not branches: the maximum moves often */
        best = v > best ? v : best;
    }
    *wrapped = zero;
    return best_a;
}

/* The strongest angle of the point just voted; widens 8-bit cells when its
 * vote wrapped one (the only place a wrap can happen: it passes the
 * threshold). */
static int32_t strongest_angle(seg_ctx *sc)
{
    uint32_t wrapped;
    if (sc->wide)
        return strongest_cell(sc, 1, &wrapped);
    const int32_t a = strongest_cell(sc, 0, &wrapped);
    if (wrapped)
        widen(sc);
    return a;
}

/* Removes the votes of a list of packed points, point by point: they are
 * neighbours along a line, so consecutive points hit the same or adjacent
 * cells at every angle. */
static inline __attribute__((always_inline)) void
unvote_cells(const seg_ctx *sc, const uint32_t *pts, int32_t n, const int wide)
{
    int32_t *restrict idx = sc->idx;
    const int32_t numangle = sc->numangle;
    for (int32_t i = 0; i < n; i++) {
        cells(sc, (int32_t)(pts[i] & 0xFFFF), (int32_t)(pts[i] >> 16), idx);
        const cells_view acc = cells_of(sc);
        int32_t a = 0;
        for (; a + 4 <= numangle; a += 4) {
            cell_set(acc, wide, idx[a], cell_get(acc, wide, idx[a]) - 1);
            cell_set(acc, wide, idx[a + 1], cell_get(acc, wide, idx[a + 1]) - 1);
            cell_set(acc, wide, idx[a + 2], cell_get(acc, wide, idx[a + 2]) - 1);
            cell_set(acc, wide, idx[a + 3], cell_get(acc, wide, idx[a + 3]) - 1);
        }
        for (; a < numangle; a++)
            cell_set(acc, wide, idx[a], cell_get(acc, wide, idx[a]) - 1);
    }
}

static void unvote(const seg_ctx *sc, const uint32_t *pts, int32_t n)
{
    if (sc->wide)
        unvote_cells(sc, pts, n, 1);
    else
        unvote_cells(sc, pts, n, 0);
}

/* The cell (best_n) of the point (x, y) reached the threshold: follow the
 * line, refit, follow the refitted line. Returns 1 and the segment when it
 * is long enough, after consuming its pixels and removing their votes. */
static int take_segment(seg_ctx *sc, int32_t x, int32_t y, int32_t best_n, rte_hough_segment *out)
{
    walk_ctx *wc = &sc->wc;
    const rte_hough_config *cfg = sc->cfg;
    const int32_t w = wc->w, h = wc->h;
    /* The line of the winning cell through this point: direction
     * (-sin, cos). Its walk takes pixels beside the line too (the cell's
     * angle is quantised); the walk of the refitted line takes only the
     * pixels on it, so its ends stop where the edge leaves the line (a
     * curve, a crossing edge, texture), not a pixel further. */
    line_q16 l = {(int64_t)x << 16, (int64_t)y << 16, -cfg->unit_sin[best_n],
                  cfg->unit_cos[best_n]};
    stepper s = rte_hough_walk_stepper(&l, x, y);
    int32_t kmin, kmax;
    wc->strict = false;
    rte_hough_walk_follow(wc, &s, &kmin, &kmax);
    line_q16 f = l;
    if (rte_hough_walk_fit(wc, &f)) {
        l = f;
        s = rte_hough_walk_stepper(&l, x, y);
        wc->strict = true;
        rte_hough_walk_follow(wc, &s, &kmin, &kmax);
    }
    if (wc->nhits == 0)
        return 0;

    /* Ends: the outermost hits projected onto the line. */
    int32_t x0, y0, x1, y1;
    rte_hough_walk_project(&l, wc->end2[0], wc->end2[1], &x0, &y0);
    rte_hough_walk_project(&l, wc->end2[2], wc->end2[3], &x1, &y1);
    int64_t ddx = x1 - x0, ddy = y1 - y0;
    if (ddx * ddx + ddy * ddy < sc->min_len2) {
        /* Too short: as OpenCV, the pixels on the walked line are dropped
         * (their votes stay), so the crowded cell does not start the same
         * walk again; pixels beside the line stay for other lines. */
        for (int32_t k = kmin; k <= kmax; k++) {
            int32_t px, py;
            stepper_at(&s, k, &px, &py);
            if ((uint32_t)px < (uint32_t)w && (uint32_t)py < (uint32_t)h &&
                live(wc->mask[(size_t)py * w + px]))
                wc->mask[(size_t)py * w + px] = PX_NONE;
        }
        return 0;
    }

    /* Consume the pixels along the segment: one pixel either side of the
     * line, and further out (up to CONSUME_REACH) while the edge run across
     * the line continues, so thick edges go in one piece. */
    const int32_t ox = s.major_x ? 0 : 1, oy = s.major_x ? 1 : 0;
    int32_t ngone = 0;
    for (int32_t k = kmin; k <= kmax; k++) {
        int32_t px, py;
        stepper_at(&s, k, &px, &py);
        for (int32_t dir = -1; dir <= 1; dir += 2) {
            for (int32_t o = dir == 1 ? 0 : -1; o >= -CONSUME_REACH && o <= CONSUME_REACH;
                 o += dir) {
                int32_t qx = px + o * ox, qy = py + o * oy;
                if ((uint32_t)qx >= (uint32_t)w || (uint32_t)qy >= (uint32_t)h)
                    break;
                uint8_t *q = wc->mask + (size_t)qy * w + qx;
                if (!live(*q)) {
                    if (o > 1 || o < -1)
                        break;
                    continue;
                }
                if (*q == PX_VOTED)
                    sc->gone[ngone++] = ((uint32_t)qy << 16) | (uint32_t)qx;
                *q = PX_USED;
            }
        }
    }
    unvote(sc, sc->gone, ngone);

    /* The projection can fall a fraction outside the image. */
    out->x0 = x0 < 0 ? 0 : x0 >= w ? w - 1 : x0;
    out->x1 = x1 < 0 ? 0 : x1 >= w ? w - 1 : x1;
    out->y0 = y0 < 0 ? 0 : y0 >= h ? h - 1 : y0;
    out->y1 = y1 < 0 ? 0 : y1 >= h ? h - 1 : y1;
    return 1;
}

/* The point (x, y) reached the threshold: take its segment if there is
 * one (8-bit cells may widen on the way). Returns 0 when the output is full
 * (the search stops). */
static int reached(seg_ctx *sc, int32_t x, int32_t y)
{
    rte_hough_segment seg;
    if (!take_segment(sc, x, y, strongest_angle(sc), &seg))
        return 1;
    if (sc->nseg == sc->max_segments) {
        sc->truncated = true;
        return 0;
    }
    sc->segments[sc->nseg++] = seg;
    return 1;
}

/* How far ahead in the point order the mask is fetched. */
#define MASK_AHEAD 8

/* Votes the points from i on, in their order, with cells of one width (a
 * constant in each copy). Returns where it stopped: npts at the end or
 * when the output is full (sc->truncated), the point after the one whose
 * vote widened 8-bit cells (the caller goes on with 16-bit ones). */
static inline __attribute__((always_inline)) int32_t search(seg_ctx *sc, const uint32_t *pts,
                                                            int32_t i, int32_t npts, const int wide)
{
    uint8_t *mask = sc->wc.mask;
    const size_t w = (size_t)sc->wc.w;
    for (; i < npts; i++) {
        /* the points come in a random order: fetch the mask byte of one
         * further on while this one votes */
        if (i + MASK_AHEAD < npts)
            __builtin_prefetch(mask + (pts[i + MASK_AHEAD] >> 16) * w +
                               (pts[i + MASK_AHEAD] & 0xFFFF));
        const int32_t x = (int32_t)(pts[i] & 0xFFFF), y = (int32_t)(pts[i] >> 16);
        uint8_t *m = mask + (size_t)y * w + (size_t)x;
        if (*m != PX_EDGE)
            continue; /* consumed by an earlier line */
        *m = PX_VOTED;
        cells(sc, x, y, sc->idx);
        if (!vote_cells(sc, wide))
            continue;
        if (!reached(sc, x, y))
            return npts;
        if (sc->wide != wide)
            return i + 1; /* widened: go on with 16-bit cells */
    }
    return npts;
}

/* The most votes one cell can hold. A cell counts the pixels whose
 * x cos + y sin falls in one rho bin (each pixel votes once; only voted
 * pixels are un-voted): along the line's major axis, at most
 * floor(rho sqrt 2) + 1 per column or row, plus one for the fixed-point
 * rounding, so at most max(w, h) (rho sqrt 2 + 2) and never more than w h.
 * 16-bit cells hold the count plus 32769 - threshold (see vote_cells), so
 * configurations where a count could pass 32767 are refused (rho 1: a side
 * above 10922 pixels). */
static int64_t cell_bound(const rte_hough_config *cfg)
{
    const int64_t side = cfg->max_width > cfg->max_height ? cfg->max_width : cfg->max_height;
    const int64_t per_line =
        (((int64_t)cfg->rho_q16 * 92682) >> 32) + 2; /* 92682 / 65536 > sqrt 2 */
    const int64_t pixels = (int64_t)cfg->max_width * cfg->max_height;
    return side * per_line < pixels ? side * per_line : pixels;
}

/* The accumulator holds, for each angle, only the rho bins that pixels of
 * a w x h map reach: x cos + y sin is linear, so its extremes over the map
 * are at the corners. A row of ((vmax - vmin) >> shift) + 2 cells holds
 * them whatever the bias (floor(A/d) - floor(B/d) <= floor((A-B)/d) + 1),
 * and a smaller map never needs more. That is about 2 (w + h) / pi bins per
 * angle instead of OpenCV's 2 (w + h): 0.46 MB instead of 1.44 at
 * 1280x720, which stays in a 1 MB L2 cache (the vote is bound by its cache
 * misses). Returns the cells; fills row_base (the index of bin 0 of each
 * angle, a bin below its row's start) when given. */
static size_t compact_rows(const rte_hough_config *cfg, int32_t w, int32_t h, int32_t bias,
                           int32_t *row_base)
{
    size_t cells = 0;
    for (int32_t a = 0; a < cfg->num_angles; a++) {
        const int64_t xs = (int64_t)(w - 1) * cfg->rho_cos[a],
                      ys = (int64_t)(h - 1) * cfg->rho_sin[a];
        const int64_t vmin = (xs < 0 ? xs : 0) + (ys < 0 ? ys : 0),
                      vmax = (xs > 0 ? xs : 0) + (ys > 0 ? ys : 0);
        if (row_base)
            row_base[a] = (int32_t)cells - (int32_t)((vmin + bias) >> cfg->trig_shift);
        cells += (size_t)((vmax - vmin) >> cfg->trig_shift) + 2;
    }
    return cells;
}

/* Pixels one segment can consume: CONSUME_REACH either side of each step. */
static size_t gone_capacity(size_t side) { return (2 * CONSUME_REACH + 1) * (side + 2); }

size_t rte_hough_segments_scratch_size(const rte_hough_config *cfg)
{
    if (!cfg || cell_bound(cfg) >= (int64_t)CELL16_TOP)
        return 0;
    size_t pixels = (size_t)cfg->max_width * (size_t)cfg->max_height;
    size_t cells = compact_rows(cfg, cfg->max_width, cfg->max_height, 0, NULL);
    size_t side = (size_t)(cfg->max_width > cfg->max_height ? cfg->max_width : cfg->max_height);
    return rte_arena_piece_size(pixels * sizeof(uint32_t)) + rte_arena_piece_size(pixels) +
           rte_arena_piece_size(cells * sizeof(uint16_t)) +
           rte_arena_piece_size(gone_capacity(side) * sizeof(uint32_t)) +
           2 * rte_arena_piece_size((size_t)cfg->num_angles * sizeof(int32_t)) +
           rte_arena_piece_size((2 * side + 4) * sizeof(uint32_t));
}

/* Fisher-Yates with xorshift32 and a multiply-shift range reduction: the
 * same order everywhere for a seed. */
static void shuffle_points(uint32_t *pts, int32_t npts, uint32_t seed)
{
    uint32_t rng = seed;
    for (int32_t i = npts - 1; i > 0; i--) {
        rng ^= rng << 13;
        rng ^= rng >> 17;
        rng ^= rng << 5;
        int32_t j = (int32_t)(((uint64_t)rng * (uint32_t)(i + 1)) >> 32);
        uint32_t t = pts[i];
        pts[i] = pts[j];
        pts[j] = t;
    }
}

rte_status rte_hough_segments(const rte_hough_config *cfg, const rte_image_u8 *edges,
                              const rte_hough_segments_params *params, rte_arena *arena,
                              rte_hough_segment *segments, int32_t max_segments, int32_t *count,
                              bool *truncated)
{
    if (!params || !arena || !count || !truncated || max_segments < 0 ||
        (max_segments > 0 && !segments) || params->threshold < 1 || params->min_length < 0 ||
        params->max_gap < 0 || params->min_length > 65535)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_hough_begin(cfg, edges, count, truncated);
    if (st != RTE_OK)
        return st;
    const int64_t bound = cell_bound(cfg);
    if (bound >= (int64_t)CELL16_TOP)
        return RTE_ERR_ARGUMENT;
    if (params->threshold > bound)
        return RTE_OK; /* no cell can reach it: no segments */
    const int32_t w = edges->width, h = edges->height;

    const int32_t numangle = cfg->num_angles,
                  bias = rte_hough_rho_bias(cfg, rte_hough_rho_bins(cfg, w, h));
    const size_t pixels = (size_t)w * (size_t)h;
    const size_t side = (size_t)(w > h ? w : h);
    const size_t mark = rte_arena_mark(arena);
    uint32_t *pts = rte_arena_alloc(arena, pixels * sizeof(uint32_t));
    uint8_t *mask = rte_arena_alloc(arena, pixels);
    int32_t *row_base = rte_arena_alloc(arena, (size_t)numangle * sizeof(int32_t));
    const size_t ncells = row_base ? compact_rows(cfg, w, h, bias, row_base) : 0;
    void *acc = rte_arena_alloc(arena, ncells * sizeof(uint16_t)); /* 16-bit cells once wide */
    uint32_t *gone = rte_arena_alloc(arena, gone_capacity(side) * sizeof(uint32_t));
    int32_t *idx = rte_arena_alloc(arena, (size_t)numangle * sizeof(int32_t));
    uint32_t *hits = rte_arena_alloc(arena, (2 * side + 4) * sizeof(uint32_t));
    if (!pts || !mask || !acc || !row_base || !gone || !idx || !hits) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    const int32_t npts = rte_hough_list_points(edges, mask, pts);
    /* 16 bits: count + 32769 - threshold stays in [1, 65535] (counts up to
     * bound <= 32767, 1 <= threshold <= bound); 8 bits: count + 129 -
     * threshold in [1, 255] until a wrap widens the cells */
    const int wide = params->threshold > HOUGH_CELL8_MAX_THRESHOLD;
    if (wide) {
        uint16_t *cells16 = acc;
        for (size_t i = 0; i < ncells; i++)
            cells16[i] = (uint16_t)(CELL16_TOP + 1 - (uint32_t)params->threshold);
    } else {
        memset(acc, (int)(CELL8_TOP + 1 - (uint32_t)params->threshold), ncells);
    }

    shuffle_points(pts, npts, params->seed ? params->seed : RTE_HOUGH_SEGMENTS_SEED);

    seg_ctx sc = {cfg,      rte_hough_bins_select(rte_cpu_features()),
                  row_base, acc,
                  wide,     ncells,
                  idx,      numangle,
                  bias,     (int64_t)params->min_length * params->min_length,
                  gone,     {mask, w, h, params->max_gap, hits, 0, {0, 0, 0, 0}, 0},
                  segments, max_segments,
                  0,        false};
    /* 8-bit cells, then 16-bit ones from where they widened (if they do) */
    const int32_t next = wide ? 0 : search(&sc, pts, 0, npts, 0);
    if (!sc.truncated)
        search(&sc, pts, next, npts, 1);
    *count = sc.nseg;
    *truncated = sc.truncated;
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
