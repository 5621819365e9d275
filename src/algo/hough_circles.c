/* Circles, cv::HoughCircles(HOUGH_GRADIENT) semantics, integer only.
 *
 * 1. Every edge pixel with a non-zero gradient votes along its gradient
 *    line, both ways, at every radius in [min_radius, max_radius]; the step
 *    is the unit gradient in Q10 (from an integer square root), as OpenCV.
 *    Past the vote budget (max_votes), the remaining edge pixels do not vote.
 * 2. Centres: accumulator cells above acc_threshold that are local maxima
 *    (> left and up, >= right and down); with more than the budget
 *    (max_centres), only the strongest go on.
 * 3. Radius: a histogram of the distances (1/16 pixel bins) from the centre
 *    to all edge pixels in range; the densest window of dp pixels, with the
 *    count weighed against the radius as OpenCV does, gives the radius and
 *    the support. Circles with support > acc_threshold go on.
 * 4. Sorted by support, then raster order of the centre; each centre is
 *    refined to where the gradient lines of its edge pixels meet, and
 *    dropped when closer than min_dist to a kept one.
 * Steps 1 and 2 run together on a ring of accumulator rows (below); step 3
 * (hough_circles_radius.c) only visits the edge pixels near the centre
 * (blocks of each row). */
#include "rtedge/hough.h"

#include <string.h>

#include "core/image_checks.h"
#include "core/int_math.h"
#include "hough_circles_internal.h"
#include "hough_circles_step.h"
#include "hough_internal.h"
#include "simd/rows.h"

static int params_ok(const rte_hough_circles_params *p)
{
    return p && p->dp_q8 >= 256 && p->dp_q8 <= 256 * 64 && p->min_dist >= 1 &&
           p->acc_threshold >= 1 && p->min_radius <= RTE_MAX_SIDE &&
           p->max_radius <= RTE_MAX_SIDE && p->max_centres >= 0 && p->max_votes >= 0;
}

static circle_geom geometry(int32_t w, int32_t h, const rte_hough_circles_params *p)
{
    circle_geom g;
    g.acols = (int32_t)(((int64_t)w * 256 + p->dp_q8 - 1) / p->dp_q8);
    g.arows = (int32_t)(((int64_t)h * 256 + p->dp_q8 - 1) / p->dp_q8);
    g.min_r = p->min_radius < 0 ? 0 : p->min_radius;
    g.max_r = p->max_radius;
    if (g.max_r <= 0)
        g.max_r = w > h ? w : h;
    else if (g.max_r <= g.min_r)
        g.max_r = g.min_r + 2;
    g.nbins = (g.max_r - g.min_r) * 16 + 1;
    g.window = (p->dp_q8 + 8) / 16; /* dp pixels in 1/16-pixel bins */
    return g;
}

/* The accumulator is a ring of rows that slides down the image: an edge
 * pixel's votes reach at most `reach` (Q10 accumulator units) above or
 * below it, so once the pixels of a row are in, the accumulator rows above
 * their reach are final; they are searched for centres and their memory is
 * cleared for the rows below. Row a (-1 and arows are the zero borders)
 * lives in ring row a & mask, of astep cells with a border cell at each
 * end; the ring's row count (mask + 1, a power of two) exceeds the rows in
 * use at any time, so no two of those share a ring row. */
typedef struct circle_band {
    int32_t *acc;
    uint32_t mask, astep;
    rte_circle_votes_fn votes;
} circle_band;

/* The largest |step| of a vote, Q10: the unit gradient / dp rounded. */
static int32_t step_bound(int32_t dp_q8) { return (1 << 18) / dp_q8 + 1; }

/* Rows in the ring: a power of two above the rows in use (those between
 * the lowest row a pixel row votes in, less the two being searched, and the
 * highest; or the whole accumulator with its borders). */
static uint32_t band_rows(const circle_geom *g, int32_t dp_q8)
{
    const int64_t reach = (int64_t)g->max_r * step_bound(dp_q8);
    const int64_t need = ((2 * reach) >> 10) + 5;
    const int64_t use = need < g->arows + 2 ? need : g->arows + 2;
    uint32_t rows = 1;
    while (rows < use)
        rows *= 2;
    return rows;
}

static inline int32_t *band_row(const circle_band *b, int32_t a)
{
    return b->acc + ((uint32_t)a & b->mask) * b->astep + 1;
}

static size_t candidates_of(const circle_geom *g)
{
    return (size_t)g->arows * (size_t)(g->acols / 2 + 1) + 1;
}

static int32_t budget_of(const rte_hough_circles_params *p)
{
    return p->max_centres > 0 ? p->max_centres : RTE_HOUGH_CIRCLES_MAX_CENTRES;
}

/* The vote budget as the number of edge pixels that vote: each casts at
 * most 2 (max_r - min_r + 1) votes. */
static int64_t voters_of(const rte_hough_circles_params *p, const circle_geom *g, int32_t w,
                         int32_t h)
{
    const int64_t votes =
        p->max_votes > 0 ? p->max_votes : (int64_t)RTE_HOUGH_CIRCLES_VOTES_PER_PIXEL * w * h;
    return votes / (2 * ((int64_t)g->max_r - g->min_r + 1));
}

/* Entries to set aside for step 3's table: with max_radius <= 0, a smaller
 * image has a smaller max_r, whose table may fit when this one does not. */
static size_t offsets_entries(const circle_geom *g, const rte_hough_circles_params *p)
{
    const size_t n = rte_circle_radius_offsets_size(g);
    return n == 0 && p->max_radius <= 0 ? RADIUS_OFFSETS_MAX : n;
}

size_t rte_hough_circles_scratch_size(int32_t max_width, int32_t max_height,
                                      const rte_hough_circles_params *params)
{
    if (!params_ok(params) || max_width < 1 || max_height < 1 || max_width > RTE_MAX_SIDE ||
        max_height > RTE_MAX_SIDE)
        return 0;
    circle_geom g = geometry(max_width, max_height, params);
    size_t pixels = (size_t)max_width * (size_t)max_height;
    size_t cand = candidates_of(&g), budget = (size_t)budget_of(params);
    size_t kept = budget < cand ? budget : cand;
    return rte_arena_piece_size((size_t)band_rows(&g, params->dp_q8) * (size_t)(g.acols + 2) *
                                sizeof(int32_t)) +
           rte_arena_piece_size(pixels * sizeof(uint32_t)) +
           rte_arena_piece_size((size_t)max_height * (size_t)blocks_of(max_width) *
                                sizeof(int32_t)) +
           rte_arena_piece_size(cand * 2 * sizeof(int32_t)) +
           rte_arena_piece_size(kept * sizeof(uint64_t)) +
           rte_arena_piece_size(kept * 3 * sizeof(int32_t)) +
           rte_arena_piece_size(radius_pairs(&g) * sizeof(int32_t)) +
           rte_arena_piece_size(offsets_entries(&g, params) * sizeof(int16_t)) +
           rte_arena_piece_size(((size_t)g.nbins + 1) * sizeof(int64_t)) +
           rte_arena_piece_size(RADIUS_COARSE * sizeof(int32_t)) +
           rte_arena_piece_size(radius_reach_rows(&g) * sizeof(int32_t));
}

/* Accumulator coordinate of pixel coordinate v, Q10: v / dp rounded. */
static inline int32_t acc_q10(int32_t v, int32_t dp_q8)
{
    return dp_q8 == 256 ? v << 10 : (int32_t)rte_div_round64((int64_t)v << 18, dp_q8);
}

/* n + 1 votes from (ux, uy), Q10, in steps of (sx, sy) (two's complement),
 * all inside the accumulator: step j adds 1 to cell (ux + j sx) >> 10 of
 * ring row ((uy + j sy) >> 10) & mask, rows astep cells apart. The C
 * reference of the kernel family in simd/rows.h. */
void rte_circle_votes_c(int32_t *acc, uint32_t mask, uint32_t astep, uint32_t ux, uint32_t uy,
                        uint32_t sx, uint32_t sy, int32_t n)
{
    for (int32_t i = n; i >= 0; i--, ux += sx, uy += sy)
        acc[((uy >> 10) & mask) * astep + (ux >> 10)]++;
}

rte_circle_votes_fn rte_circle_votes_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, rte_circle_votes_c, rte_circle_votes_avx2,
                         rte_circle_votes_avx512, rte_circle_votes_c);
}

/* One pixel's votes along (sx, sy) from (x1, y1) = its position plus
 * min_r steps, until the line leaves the accumulator or passes max_r. */
static inline void vote_line(const circle_band *b, const circle_geom *g, int32_t x1, int32_t y1,
                             int32_t sx, int32_t sy)
{
    const int32_t n = g->max_r - g->min_r;
    const int32_t xe = x1 + n * sx, ye = y1 + n * sy;
    if ((x1 | y1 | xe | ye) >= 0 && (x1 >> 10) < g->acols && (y1 >> 10) < g->arows &&
        (xe >> 10) < g->acols && (ye >> 10) < g->arows) {
        /* both ends inside, so every step between: no tests */
        b->votes(b->acc + 1, b->mask, b->astep, (uint32_t)x1, (uint32_t)y1, (uint32_t)sx,
                 (uint32_t)sy, n);
        return;
    }
    for (int32_t i = 0; i <= n; i++, x1 += sx, y1 += sy) {
        if (x1 < 0 || y1 < 0)
            break;
        int32_t x2 = x1 >> 10, y2 = y1 >> 10;
        if (x2 >= g->acols || y2 >= g->arows)
            break;
        band_row(b, y2)[x2]++;
    }
}

/* Step 2 on accumulator row a (rows a - 1 .. a + 1 in the ring): local
 * maxima above the threshold (ties broken towards the right and below),
 * appended as (a * acols + x, votes). Row a - 1 is not needed after this
 * and is cleared as the scan passes, for the row that reuses its memory
 * (a memset of the row, a rep stos, took a tenth of the transform on AMD
 * Zen 3). Eight cells at a
 * time are skipped when none is above the threshold: with v + 2^31 - 1 -
 * thr in each 32-bit half of a word (no carry out: votes are below 2^31),
 * bit 31 of a half is set exactly when v > thr. */
static int32_t find_centres_row(const circle_band *b, const circle_geom *g, int32_t a, int32_t thr,
                                int32_t *centres, int32_t ncent)
{
    const int32_t *r = band_row(b, a), *down = band_row(b, a + 1);
    int32_t *up = band_row(b, a - 1);
    const uint64_t add = (uint64_t)(0x7FFFFFFFu - (uint32_t)thr) * 0x100000001u,
                   top = 0x8000000080000000u;
    int32_t x = 0;
    for (;;) {
        for (; x + 8 <= g->acols; x += 8) {
            /* four words, not an array (GCC copies an array through the
             * stack) */
            uint64_t w0, w1, w2, w3;
            memcpy(&w0, r + x, sizeof w0);
            memcpy(&w1, r + x + 2, sizeof w1);
            memcpy(&w2, r + x + 4, sizeof w2);
            memcpy(&w3, r + x + 6, sizeof w3);
            if (((w0 + add) | (w1 + add) | (w2 + add) | (w3 + add)) & top)
                break;
            memset(up + x, 0, 8 * sizeof *up);
        }
        const int32_t end = x + 8 < g->acols ? x + 8 : g->acols;
        if (x >= end)
            break;
        for (; x < end; x++) {
            int32_t v = r[x];
            if (v > thr && v > r[x - 1] && v >= r[x + 1] && v > up[x] && v >= down[x]) {
                centres[2 * ncent] = a * g->acols + x;
                centres[2 * ncent + 1] = v;
                ncent++;
            }
            up[x] = 0;
        }
    }
    return ncent;
}

/* Bit k set when e[k] is nonzero, for k < n <= 8. Eight at once (little
 * endian): the top bit of each nonzero byte, moved to the byte's low bit,
 * then the eight low bits gathered into the top byte by one multiply (the
 * partial products of different bytes fall below it or above 64 bits). */
static inline uint32_t edge_bits(const uint8_t *e, int32_t n)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (n == 8) {
        uint64_t word;
        memcpy(&word, e, sizeof word);
        const uint64_t low7 = 0x7F7F7F7F7F7F7F7Fu;
        const uint64_t ones = ((((word & low7) + low7) | word) >> 7) & 0x0101010101010101u;
        return (uint32_t)((ones * 0x0102040810204080u) >> 56);
    }
#endif
    uint32_t bits = 0;
    for (int32_t k = 0; k < n; k++)
        bits |= (uint32_t)(e[k] != 0) << k;
    return bits;
}

/* Bit k set when e[k] is nonzero, for k < n <= 64. */
static inline uint64_t edge_bits64(const uint8_t *e, int32_t n)
{
    uint64_t bits = 0;
    if (n == 64) { /* unrolled */
        for (int32_t k = 0; k < 64; k += 8)
            bits |= (uint64_t)edge_bits(e + k, 8) << k;
        return bits;
    }
    for (int32_t k = 0; k < n; k += 8)
        bits |= (uint64_t)edge_bits(e + k, n - k < 8 ? n - k : 8) << k;
    return bits;
}

/* A pixel's two vote lines: from its accumulator position (x0, y0, Q10)
 * along its unit step (sx, sy) both ways, starting min_r steps out. */
typedef struct circle_voter {
    int32_t x0, y0, sx, sy;
} circle_voter;

static inline void vote_pixel(const circle_band *b, const circle_geom *g, const circle_voter *v)
{
    vote_line(b, g, v->x0 + g->min_r * v->sx, v->y0 + g->min_r * v->sy, v->sx, v->sy);
    vote_line(b, g, v->x0 - g->min_r * v->sx, v->y0 - g->min_r * v->sy, -v->sx, -v->sy);
}

/* Steps 1 and 2: the edge pixels' votes, row by row, and the centres of
 * the accumulator rows that no later pixel reaches. Also lists the edge
 * pixels (with a non-zero gradient) and their blocks. Only the first
 * `voters` of them vote (the vote budget; *truncated is set when one more
 * would have). Returns the number of centres; *npts gets the number of
 * pixels.
 *
 * A pixel's step (a square root and divisions, about 40 cycles of
 * latency) is computed before the votes of the pixel before it are cast:
 * the votes do not wait for it, so the divider works while the
 * increments run instead of between them. The votes keep their order. */
static int32_t accumulate(const rte_image_u8 *edges, const rte_image_s16 *dx,
                          const rte_image_s16 *dy, const circle_geom *g, int32_t dp_q8, int32_t thr,
                          circle_band *b, int64_t voters, uint32_t *pts, int32_t *blk,
                          int32_t *centres, int32_t *npts, bool *truncated)
{
    const int32_t w = edges->width, h = edges->height, nblk = blocks_of(w);
    const int32_t reach = g->max_r * step_bound(dp_q8);
    int32_t n = 0, ncent = 0, next = 0; /* next: the first row not yet searched */
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *e = rte_u8_row(edges, y);
        const int16_t *gx = rte_s16_row(dx, y), *gy = rte_s16_row(dy, y);
        const int32_t y0 = acc_q10(y, dp_q8);
        int32_t *rb = blk + (size_t)y * nblk;
        circle_voter prev = {0, 0, 0, 0};
        bool pending = false;
        for (int32_t x64 = 0; x64 < w; x64 += 64) {
            /* bit k: pixel x64 + k is an edge (one branch per edge pixel,
             * not one per pixel, and one loop exit per 64 pixels: both
             * mispredict) */
            const uint64_t bits = edge_bits64(e + x64, x64 + 64 < w ? 64 : w - x64);
            int32_t in_block[64 / BLOCK] = {0};
            for (uint64_t left = bits; left; left &= left - 1) {
                const int32_t k = __builtin_ctzll(left), x = x64 + k;
                int32_t vx = gx[x], vy = gy[x];
                if (vx == 0 && vy == 0)
                    continue;
                in_block[k / BLOCK]++;
                pts[n++] = ((uint32_t)y << 16) | (uint32_t)x;
                if (voters == 0) {
                    *truncated = true;
                    continue;
                }
                voters--;
                circle_voter cur = {acc_q10(x, dp_q8), y0, 0, 0};
                circle_step(vx, vy, dp_q8, &cur.sx, &cur.sy);
                if (pending)
                    vote_pixel(b, g, &prev);
                prev = cur;
                pending = true;
            }
            /* the blocks of these 64 pixels start where the pixels listed
             * before them end (counted, not branched on per pixel) */
            _Static_assert(64 % BLOCK == 0, "a block lies in one 64-pixel word");
            int32_t start = n;
            for (int32_t j = 64 / BLOCK - 1; j >= 0; j--) {
                start -= in_block[j];
                if (x64 / BLOCK + j < nblk)
                    rb[x64 / BLOCK + j] = start;
            }
        }
        if (pending)
            vote_pixel(b, g, &prev);
        rb[nblk - 1] = n;
        /* Rows the next pixel row cannot reach are final; a row is searched
         * once the row below it is final too. */
        int32_t final = g->arows + 1;
        if (y + 1 < h) {
            const int32_t lo = acc_q10(y + 1, dp_q8) - reach;
            final = lo < 0 ? 0 : lo >> 10;
        }
        for (; next < g->arows && next + 1 < final; next++)
            ncent = find_centres_row(b, g, next, thr, centres, ncent);
    }
    *npts = n;
    return ncent;
}

/* Step 4: greedy removal, best first, of centres closer than min_dist to
 * one already kept. A centre is refined (step 3b) only when it may be
 * kept: refining moves it at most `lim` along each axis, so one whose box
 * of reachable positions lies within min_dist of a kept centre is dropped
 * as it is (most candidates are neighbours of a circle's best centre, and
 * refining them took a fifth of the transform). Returns how many were
 * kept. */
static int32_t keep_separated(const rte_hough_topk *top, int32_t *est, int32_t min_dist,
                              const circle_pixels *cp, rte_hough_circle *circles,
                              int32_t max_circles, bool *truncated)
{
    const int64_t min_d2 = (int64_t)min_dist * min_dist * 256;
    const int64_t lim = circle_refine_limit(cp->dp_q8);
    int32_t nout = 0;
    for (int32_t k = 0; k < top->size; k++) {
        int32_t e = (int32_t)rte_hough_key_index(top->keys[k]);
        int32_t *c = est + 3 * e;
        bool near = false;
        for (int32_t j = 0; j < nout && !near; j++) {
            const int64_t ddx = rte_abs64(c[0] - circles[j].x_q4) + lim,
                          ddy = rte_abs64(c[1] - circles[j].y_q4) + lim;
            near = ddx * ddx + ddy * ddy < min_d2;
        }
        if (near)
            continue;
        rte_circle_refine(cp, &c[0], &c[1], &c[2]);
        bool ok = true;
        for (int32_t j = 0; j < nout && ok; j++) {
            int64_t ddx = c[0] - circles[j].x_q4, ddy = c[1] - circles[j].y_q4;
            ok = ddx * ddx + ddy * ddy >= min_d2;
        }
        if (!ok)
            continue;
        if (nout == max_circles) {
            *truncated = true;
            break;
        }
        rte_hough_circle out = {c[0], c[1], c[2], rte_hough_key_votes(top->keys[k])};
        circles[nout++] = out;
    }
    return nout;
}

/* Step 3's table for a centre at (cx, cy): made for the first centre's
 * position within its pixel (with an integer dp, every centre's); NULL for
 * the others, which scan the distances, and when there is no table. */
static const radius_offsets *offsets_for(radius_offsets *ro, const circle_geom *g,
                                         const radius_table *rt, int32_t cx, int32_t cy)
{
    if (!ro->bin2)
        return NULL;
    if (ro->fx < 0)
        rte_circle_radius_offsets_init(ro, g, rt, cx & 15, cy & 15);
    return ro->fx == (cx & 15) && ro->fy == (cy & 15) ? ro : NULL;
}

rte_status rte_hough_circles(const rte_image_u8 *edges, const rte_image_s16 *dx,
                             const rte_image_s16 *dy, const rte_hough_circles_params *params,
                             rte_arena *arena, rte_hough_circle *circles, int32_t max_circles,
                             int32_t *count, bool *truncated)
{
    if (!params_ok(params) || !arena || !count || !truncated || max_circles < 0 ||
        (max_circles > 0 && !circles))
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check(edges);
    if (st == RTE_OK)
        st = rte_image_s16_check_gradient(dx, dy, edges->width, edges->height);
    if (st != RTE_OK)
        return st;
    *count = 0;
    *truncated = false;

    const int32_t w = edges->width, h = edges->height, nblk = blocks_of(w);
    const circle_geom g = geometry(w, h, params);
    const size_t cand_cap = candidates_of(&g), budget = (size_t)budget_of(params);
    const size_t kept_cap = budget < cand_cap ? budget : cand_cap;
    const size_t mark = rte_arena_mark(arena);
    circle_band band = {NULL, band_rows(&g, params->dp_q8) - 1, (uint32_t)g.acols + 2,
                        rte_circle_votes_select(rte_cpu_features())};
    const size_t band_cells = ((size_t)band.mask + 1) * band.astep;
    band.acc = rte_arena_alloc(arena, band_cells * sizeof(int32_t));
    uint32_t *pts = rte_arena_alloc(arena, (size_t)w * h * sizeof(uint32_t));
    int32_t *blk = rte_arena_alloc(arena, (size_t)h * (size_t)nblk * sizeof(int32_t));
    int32_t *centres = rte_arena_alloc(arena, cand_cap * 2 * sizeof(int32_t));
    uint64_t *keys = rte_arena_alloc(arena, kept_cap * sizeof(uint64_t));
    int32_t *est = rte_arena_alloc(arena, kept_cap * 3 * sizeof(int32_t));
    int32_t *pairs = rte_arena_alloc(arena, radius_pairs(&g) * sizeof(int32_t));
    const size_t offsets = rte_circle_radius_offsets_size(&g);
    radius_offsets ro = {offsets ? rte_arena_alloc(arena, offsets * sizeof(int16_t)) : NULL, 0, 0,
                         -1, -1};
    radius_table rt = {rte_arena_alloc(arena, ((size_t)g.nbins + 1) * sizeof(int64_t)),
                       rte_arena_alloc(arena, RADIUS_COARSE * sizeof(int32_t)),
                       rte_arena_alloc(arena, radius_reach_rows(&g) * sizeof(int32_t)), 0, 0};
    if (!band.acc || !pts || !blk || !centres || !keys || !est || !pairs || !rt.sq || !rt.coarse ||
        !rt.reach || (offsets && !ro.bin2)) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    memset(band.acc, 0, band_cells * sizeof(int32_t));
    memset(pairs, 0, radius_pairs(&g) * sizeof(int32_t));
    const int32_t thr = params->acc_threshold;
    int32_t npts = 0;
    const int32_t ncent =
        accumulate(edges, dx, dy, &g, params->dp_q8, thr, &band, voters_of(params, &g, w, h), pts,
                   blk, centres, &npts, truncated);
    if (npts == 0) {
        rte_arena_reset(arena, mark);
        return RTE_OK;
    }
    rte_circle_radius_table_init(&rt, &g);

    /* The budget: with more centres than it allows, only the strongest
     * (most votes, then raster order) get a radius. */
    rte_hough_topk top = {keys, (int32_t)kept_cap, 0, 0};
    uint64_t cut = 0;
    if ((size_t)ncent > kept_cap) {
        for (int32_t i = 0; i < ncent; i++)
            rte_hough_topk_push(&top, rte_hough_key(centres[2 * i + 1], (uint32_t)i));
        cut = top.keys[0];
        *truncated = true;
        top.size = 0;
        top.seen = 0;
    }

    /* Step 3: radius and support of every centre. */
    int32_t nest = 0;
    for (int32_t i = 0; i < ncent; i++) {
        if (cut && rte_hough_key(centres[2 * i + 1], (uint32_t)i) < cut)
            continue;
        int32_t ay = centres[2 * i] / g.acols, ax = centres[2 * i] % g.acols;
        /* (a + 0.5) * dp in 1/16 pixel */
        int32_t cx = (int32_t)(((int64_t)(2 * ax + 1) * params->dp_q8 + 16) / 32);
        int32_t cy = (int32_t)(((int64_t)(2 * ay + 1) * params->dp_q8 + 16) / 32);
        int32_t r = 0;
        int32_t support = rte_circle_radius(pts, blk, nblk, h, &g, &rt,
                                            offsets_for(&ro, &g, &rt, cx, cy), cx, cy, pairs, &r);
        if (support > thr) {
            est[3 * nest] = cx;
            est[3 * nest + 1] = cy;
            est[3 * nest + 2] = r;
            rte_hough_topk_push(&top, rte_hough_key(support, (uint32_t)nest));
            nest++;
        }
    }
    rte_hough_topk_sort(&top);

    const circle_pixels cp = {pts, blk, nblk, h, params->dp_q8, dx, dy};
    const int32_t nout =
        keep_separated(&top, est, params->min_dist, &cp, circles, max_circles, truncated);
    *count = nout;
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
