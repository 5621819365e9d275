/* Circles, cv::HoughCircles(HOUGH_GRADIENT) semantics, integer only.
 *
 * 1. Every edge pixel with a non-zero gradient votes along its gradient
 *    line, both ways, at every radius in [min_radius, max_radius]; the step
 *    is the unit gradient in Q10 (from an integer square root), as OpenCV.
 * 2. Centres: accumulator cells above acc_threshold that are local maxima
 *    (> left and up, >= right and down); with more than the budget
 *    (max_centres), only the strongest go on.
 * 3. Radius: a histogram of the distances (1/16 pixel bins) from the centre
 *    to all edge pixels in range; the densest window of dp pixels, with the
 *    count weighed against the radius as OpenCV does, gives the radius and
 *    the support. Circles with support > acc_threshold are kept, their
 *    centre refined to where the gradient lines of their edge pixels meet.
 * 4. Sorted by support, then raster order of the centre; a centre closer
 *    than min_dist to a kept one is dropped.
 * Steps 1 and 2 run together on a ring of accumulator rows (below); step 3
 * only visits the edge pixels near the centre (blocks of each row). */
#include "rtedge/hough.h"

#include <string.h>

#include "core/int_math.h"
#include "hough_internal.h"
#include "simd/rows.h"

typedef struct circle_geom {
    int32_t acols, arows, min_r, max_r, nbins, window;
} circle_geom;

static int params_ok(const rte_hough_circles_params *p)
{
    return p && p->dp_q8 >= 256 && p->dp_q8 <= 256 * 64 && p->min_dist >= 1 &&
           p->acc_threshold >= 1 && p->min_radius <= RTE_MAX_SIDE &&
           p->max_radius <= RTE_MAX_SIDE && p->max_centres >= 0;
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

/* Radius bins without a square root per pixel: floor(sqrt(d2)) - min_r * 16
 * for d2 in [rmin2, rmax2] is the last bin k with sq[k] <= d2. A coarse table
 * gives the bin at the start of each 2^shift-wide range of d2 (at most
 * RADIUS_COARSE entries), and a few steps up find it (the integer Newton
 * square root, with its divisions, took a third of the transform). */
#define RADIUS_COARSE 4096
typedef struct radius_table {
    int64_t *sq;     /* sq[k] = (min_r * 16 + k)^2 for k <= nbins (sq[nbins] stops the steps) */
    int32_t *coarse; /* the bin of rmin2 + (i << shift) */
    int64_t rmin2;
    int32_t shift;
} radius_table;

static void radius_table_init(radius_table *t, const circle_geom *g)
{
    const int64_t r0 = (int64_t)g->min_r * 16;
    for (int32_t k = 0; k <= g->nbins; k++)
        t->sq[k] = (r0 + k) * (r0 + k);
    t->rmin2 = t->sq[0];
    const int64_t span = t->sq[g->nbins - 1] - t->rmin2;
    t->shift = 0;
    while ((span >> t->shift) >= RADIUS_COARSE)
        t->shift++;
    int32_t k = 0;
    for (int64_t i = 0; i <= span >> t->shift; i++) {
        const int64_t d2 = t->rmin2 + (i << t->shift);
        while (t->sq[k + 1] <= d2)
            k++;
        t->coarse[i] = k;
    }
}

static inline int32_t radius_bin(const radius_table *t, int64_t d2)
{
    int32_t k = t->coarse[(d2 - t->rmin2) >> t->shift];
    while (t->sq[k + 1] <= d2)
        k++;
    return k;
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

/* Edge pixels are listed in raster order (packed y << 16 | x) with, for
 * each row, where every BLOCK-pixel block of columns starts, so the scans
 * around a centre go straight to the pixels near it. */
#define BLOCK 16
static int32_t blocks_of(int32_t w) { return (w + BLOCK - 1) / BLOCK + 1; }

static int32_t budget_of(const rte_hough_circles_params *p)
{
    return p->max_centres > 0 ? p->max_centres : RTE_HOUGH_CIRCLES_MAX_CENTRES;
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
           rte_arena_piece_size((size_t)g.nbins * sizeof(int32_t)) +
           rte_arena_piece_size(((size_t)g.nbins + 1) * sizeof(int64_t)) +
           rte_arena_piece_size(RADIUS_COARSE * sizeof(int32_t));
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
    return RTE_SIMD_PICK(features, rte_circle_votes_c, rte_circle_votes_avx2, rte_circle_votes_c);
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
 * and is cleared on the way, for the row that reuses its memory. Four
 * cells at a time are skipped
 * when none is above the threshold: with v + 2^31 - 1 - thr in each 32-bit
 * half of a word (no carry out: votes are below 2^31), bit 31 of a half is
 * set exactly when v > thr. */
static int32_t find_centres_row(const circle_band *b, const circle_geom *g, int32_t a, int32_t thr,
                                int32_t *centres, int32_t ncent)
{
    const int32_t *r = band_row(b, a), *down = band_row(b, a + 1);
    int32_t *up = band_row(b, a - 1);
    const uint64_t zero = 0;
    const uint64_t add = (uint64_t)(0x7FFFFFFFu - (uint32_t)thr) * 0x100000001u,
                   top = 0x8000000080000000u;
    int32_t x = 0;
    for (;;) {
        for (; x + 4 <= g->acols; x += 4) {
            uint64_t w0, w1;
            memcpy(&w0, r + x, sizeof w0);
            memcpy(&w1, r + x + 2, sizeof w1);
            if (((w0 + add) | (w1 + add)) & top)
                break;
            memcpy(up + x, &zero, sizeof zero);
            memcpy(up + x + 2, &zero, sizeof zero);
        }
        const int32_t end = x + 4 < g->acols ? x + 4 : g->acols;
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

/* Steps 1 and 2: every edge pixel's votes, row by row, and the centres of
 * the accumulator rows that no later pixel reaches. Also lists the voting
 * pixels and their blocks. Returns the number of centres; *npts gets the
 * number of pixels. */
static int32_t accumulate(const rte_image_u8 *edges, const rte_image_s16 *dx,
                          const rte_image_s16 *dy, const circle_geom *g, int32_t dp_q8, int32_t thr,
                          circle_band *b, uint32_t *pts, int32_t *blk, int32_t *centres,
                          int32_t *npts)
{
    const int32_t w = edges->width, h = edges->height, nblk = blocks_of(w);
    const int32_t reach = g->max_r * step_bound(dp_q8);
    int32_t n = 0, ncent = 0, next = 0; /* next: the first row not yet searched */
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *e = rte_u8_row(edges, y);
        const int16_t *gx = rte_s16_row(dx, y), *gy = rte_s16_row(dy, y);
        const int32_t y0 = acc_q10(y, dp_q8);
        int32_t *rb = blk + (size_t)y * nblk, nb = 0;
        for (int32_t x8 = 0; x8 < w; x8 += 8) {
            const int32_t x_end = x8 + 8 < w ? x8 + 8 : w;
            if (x_end - x8 == 8) {
                uint64_t word;
                memcpy(&word, e + x8, sizeof word);
                if (!word)
                    continue;
            }
            for (int32_t x = x8; x < x_end; x++) {
                int32_t vx = gx[x], vy = gy[x];
                if (!e[x] || (vx == 0 && vy == 0))
                    continue;
                while (nb * BLOCK <= x)
                    rb[nb++] = n;
                pts[n++] = ((uint32_t)y << 16) | (uint32_t)x;
                /* Unit gradient / dp in Q10: vx * 1024 / (dp * |v|), with |v| in Q10. */
                uint64_t mag_q10 = rte_isqrt64(((uint64_t)(vx * vx) + (uint64_t)(vy * vy)) << 20);
                int64_t den = (int64_t)mag_q10 * dp_q8;
                int32_t sx = (int32_t)rte_div_round64((int64_t)vx * (1 << 28), den);
                int32_t sy = (int32_t)rte_div_round64((int64_t)vy * (1 << 28), den);
                int32_t x0 = acc_q10(x, dp_q8);
                vote_line(b, g, x0 + g->min_r * sx, y0 + g->min_r * sy, sx, sy);
                vote_line(b, g, x0 - g->min_r * sx, y0 - g->min_r * sy, -sx, -sy);
            }
        }
        while (nb < nblk)
            rb[nb++] = n;
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

/* The edge pixels of row y within `reach` (1/16 pixel, plus a pixel) of
 * column cx (1/16 pixel), and a few more in the same blocks (the callers
 * skip those farther away): pts[*first .. *end). */
static inline void ring_window(const int32_t *blk, int32_t nblk, int32_t y, int32_t cx,
                               int32_t reach, int32_t *first, int32_t *end)
{
    const int32_t x_lo = ((cx - reach) >> 4) - 1, x_hi = ((cx + reach) >> 4) + 1;
    const int32_t b_lo = x_lo < 0 ? 0 : x_lo / BLOCK, b_hi = x_hi < 0 ? 0 : x_hi / BLOCK + 1;
    *first = blk[(size_t)y * nblk + (b_lo < nblk - 1 ? b_lo : nblk - 1)];
    *end = blk[(size_t)y * nblk + (b_hi < nblk - 1 ? b_hi : nblk - 1)];
}

/* Step 3 for one centre (cx, cy in 1/16 pixel): support and radius. */
static int32_t estimate_radius(const uint32_t *pts, const int32_t *blk, int32_t nblk, int32_t h,
                               const circle_geom *g, const radius_table *rt, int32_t cx, int32_t cy,
                               int32_t *bins, int32_t *radius_q4)
{
    const int64_t rmin2 = rt->rmin2, rmax2 = rt->sq[g->nbins - 1]; /* (min_r 16)^2, (max_r 16)^2 */
    int32_t y_lo = (cy >> 4) - g->max_r - 1, y_hi = (cy >> 4) + g->max_r + 1;
    y_lo = y_lo < 0 ? 0 : y_lo;
    y_hi = y_hi > h - 1 ? h - 1 : y_hi;
    for (int32_t i = 0; i < g->nbins; i++)
        bins[i] = 0;
    int32_t any = 0;
    for (int32_t y = y_lo; y <= y_hi; y++) {
        int32_t i, end;
        ring_window(blk, nblk, y, cx, g->max_r * 16, &i, &end);
        for (; i < end; i++) {
            int64_t ddx = (int64_t)(pts[i] & 0xFFFF) * 16 - cx, ddy = (int64_t)y * 16 - cy;
            int64_t d2 = ddx * ddx + ddy * ddy;
            if (d2 < rmin2 || d2 > rmax2)
                continue;
            bins[radius_bin(rt, d2)]++;
            any = 1;
        }
    }
    int32_t best_count = 0, best_r = 0;
    if (!any)
        return 0;
    /* From the largest radius down: each non-empty bin opens a window of
     * `window` bins; a window wins when count / radius is at least the best
     * so far (so ties go to the smaller radius). */
    for (int32_t j = g->nbins - 1; j >= 0; j--) {
        if (!bins[j])
            continue;
        int32_t up = j, cnt = 0;
        for (; j > up - g->window && j >= 0; j--)
            cnt += bins[j];
        int32_t r = g->min_r * 16 + (up + j + 1) / 2;
        if ((int64_t)cnt * best_r >= (int64_t)best_count * r ||
            (best_r == 0 && cnt >= best_count)) {
            best_r = r;
            best_count = cnt;
        }
        j++; /* the loop's j-- moves to the first bin below the window */
    }
    *radius_q4 = best_r;
    return best_count;
}

/* Step 3b: the centre refined to the point nearest to the gradient lines of
 * the circle's edge pixels (those within 1.5 px of the radius whose
 * gradient points within ~14 degrees of the centre, not on the image
 * border, where the derivatives depend on the border rule): the least-squares
 * intersection sum (I - u u^T) c = sum (I - u u^T) p with unit gradients u
 * in Q8. It works on arcs too, and is not held to the accumulator grid. The
 * radius becomes the mean distance to the refined centre. A move of more
 * than 2 dp, too few pixels or a degenerate system keep the grid centre;
 * radii over 1000 px (where the sums would need more than 64 bits) too. */
/* The point p (packed y << 16 | x) relative to the centre (1/16 pixel) in
 * (*px, *py) and, when d is not NULL, its distance; 1 when that is within
 * `band` of r. */
static inline int on_ring(uint32_t p, int32_t cx, int32_t cy, int32_t r, int32_t band, int64_t *px,
                          int64_t *py, int64_t *d)
{
    *px = (int64_t)(p & 0xFFFF) * 16 - cx;
    *py = (int64_t)(p >> 16) * 16 - cy;
    /* floor(sqrt(d2)) in [r - band, r + band] <=> (r - band)^2 <= d2 <
     * (r + band + 1)^2: most pixels of the window are off the ring, and
     * need no square root */
    const int64_t d2 = *px * *px + *py * *py, lo = r - band > 0 ? r - band : 0, hi = r + band + 1;
    if (d2 < lo * lo || d2 >= hi * hi)
        return 0;
    if (d)
        *d = (int64_t)rte_isqrt64((uint64_t)d2);
    return 1;
}

static void refine(const uint32_t *pts, const int32_t *blk, int32_t nblk, int32_t h,
                   const rte_image_s16 *dx, const rte_image_s16 *dy, int32_t dp_q8, int32_t *cx,
                   int32_t *cy, int32_t *r_q4)
{
    const int32_t r = *r_q4, band = 24; /* 1.5 px */
    if (r + band >= (1 << 14))
        return;
    int32_t y_lo = ((*cy - r - band) >> 4) - 1, y_hi = ((*cy + r + band) >> 4) + 1;
    y_lo = y_lo < 0 ? 0 : y_lo;
    y_hi = y_hi > h - 1 ? h - 1 : y_hi;
    int64_t a00 = 0, a01 = 0, a11 = 0, b0 = 0, b1 = 0;
    int32_t n = 0;
    for (int32_t y = y_lo; y <= y_hi; y++) {
        int32_t i, end;
        ring_window(blk, nblk, y, *cx, r + band, &i, &end);
        for (; i < end; i++) {
            const int32_t x = (int32_t)(pts[i] & 0xFFFF);
            int64_t px, py;
            if (!on_ring(pts[i], *cx, *cy, r, band, &px, &py, NULL))
                continue;
            if (x == 0 || y == 0 || x == dx->width - 1 || y == h - 1)
                continue; /* derivatives there depend on the border rule */
            const int64_t gx = rte_s16_row(dx, y)[x], gy = rte_s16_row(dy, y)[x];
            const int64_t dot = gx * px + gy * py, cross = gx * py - gy * px;
            if ((cross < 0 ? -cross : cross) * 4 > (dot < 0 ? -dot : dot))
                continue;
            const int64_t gm = (int64_t)rte_isqrt64((uint64_t)(gx * gx + gy * gy));
            const int64_t ux = gx * 256 / gm, uy = gy * 256 / gm; /* Q8 unit vector */
            /* I - u u^T in Q16: [uy^2, -ux uy; -ux uy, ux^2] */
            const int64_t m00 = uy * uy, m01 = -ux * uy, m11 = ux * ux;
            a00 += m00;
            a01 += m01;
            a11 += m11;
            b0 += m00 * px + m01 * py;
            b1 += m01 * px + m11 * py;
            n++;
        }
    }
    if (n < 3)
        return;
    /* Common scale so the products below stay within 64 bits (the solution
     * does not change): a00 + a11 <= 2^24, then |b| <= 2^24 * 2^14. */
    while (a00 + a11 > (1 << 24)) {
        a00 /= 2;
        a01 /= 2;
        a11 /= 2;
        b0 /= 2;
        b1 /= 2;
    }
    const int64_t det = a00 * a11 - a01 * a01;
    if (det <= 0)
        return;
    const int64_t ox = rte_div_round64(a11 * b0 - a01 * b1, det),
                  oy = rte_div_round64(a00 * b1 - a01 * b0, det);
    const int64_t lim = (dp_q8 + 4) / 8; /* 2 dp in 1/16 pixel */
    if (ox > lim || ox < -lim || oy > lim || oy < -lim)
        return;
    *cx += (int32_t)ox;
    *cy += (int32_t)oy;
    /* radius: mean distance of the same pixels to the new centre */
    int64_t sum = 0;
    int32_t m = 0;
    for (int32_t y = y_lo; y <= y_hi; y++) {
        int32_t i, end;
        ring_window(blk, nblk, y, *cx, r + band, &i, &end);
        for (; i < end; i++) {
            int64_t px, py, d;
            if (!on_ring(pts[i], *cx, *cy, r, band, &px, &py, &d))
                continue;
            sum += d;
            m++;
        }
    }
    if (m > 0)
        *r_q4 = (int32_t)rte_div_round64(sum, m);
}

/* Step 4: greedy removal, best first, of centres closer than min_dist to
 * one already kept. Returns how many were kept. */
static int32_t keep_separated(const rte_hough_topk *top, const int32_t *est, int32_t min_dist,
                              rte_hough_circle *circles, int32_t max_circles, bool *truncated)
{
    const int64_t min_d2 = (int64_t)min_dist * min_dist * 256;
    int32_t nout = 0;
    for (int32_t k = 0; k < top->size; k++) {
        int32_t e = (int32_t)rte_hough_key_index(top->keys[k]);
        int32_t cx = est[3 * e], cy = est[3 * e + 1];
        bool ok = true;
        for (int32_t j = 0; j < nout && ok; j++) {
            int64_t ddx = cx - circles[j].x_q4, ddy = cy - circles[j].y_q4;
            ok = ddx * ddx + ddy * ddy >= min_d2;
        }
        if (!ok)
            continue;
        if (nout == max_circles) {
            *truncated = true;
            break;
        }
        rte_hough_circle out = {cx, cy, est[3 * e + 2], rte_hough_key_votes(top->keys[k])};
        circles[nout++] = out;
    }
    return nout;
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
        st = rte_image_s16_check(dx);
    if (st == RTE_OK)
        st = rte_image_s16_check(dy);
    if (st != RTE_OK)
        return st;
    if (dx->width != edges->width || dy->width != edges->width || dx->height != edges->height ||
        dy->height != edges->height)
        return RTE_ERR_SIZE;
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
    int32_t *bins = rte_arena_alloc(arena, (size_t)g.nbins * sizeof(int32_t));
    radius_table rt = {rte_arena_alloc(arena, ((size_t)g.nbins + 1) * sizeof(int64_t)),
                       rte_arena_alloc(arena, RADIUS_COARSE * sizeof(int32_t)), 0, 0};
    if (!band.acc || !pts || !blk || !centres || !keys || !est || !bins || !rt.sq || !rt.coarse) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    memset(band.acc, 0, band_cells * sizeof(int32_t));
    const int32_t thr = params->acc_threshold;
    int32_t npts = 0;
    const int32_t ncent =
        accumulate(edges, dx, dy, &g, params->dp_q8, thr, &band, pts, blk, centres, &npts);
    if (npts == 0) {
        rte_arena_reset(arena, mark);
        return RTE_OK;
    }
    radius_table_init(&rt, &g);

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
        int32_t support = estimate_radius(pts, blk, nblk, h, &g, &rt, cx, cy, bins, &r);
        if (support > thr) {
            refine(pts, blk, nblk, h, dx, dy, params->dp_q8, &cx, &cy, &r);
            est[3 * nest] = cx;
            est[3 * nest + 1] = cy;
            est[3 * nest + 2] = r;
            rte_hough_topk_push(&top, rte_hough_key(support, (uint32_t)nest));
            nest++;
        }
    }
    rte_hough_topk_sort(&top);

    const int32_t nout =
        keep_separated(&top, est, params->min_dist, circles, max_circles, truncated);
    *count = nout;
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
