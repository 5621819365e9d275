/* Hough circles, step 3: the radius of each candidate centre from the
 * distances of the edge pixels around it, then the centre refined to where
 * their gradient lines meet (the votes and the rest: hough_circles.c). */
#include "hough_circles_internal.h"

#include "core/int_math.h"
#include "geom_fixed.h"
#include "rtedge/image.h"

void rte_circle_radius_table_init(radius_table *t, const circle_geom *g)
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
    /* A centre's x and y are 1/16 pixel; one in pixel row cy lies 16 k - f
     * (0 <= f < 16) above row cy + k: at least 16 k - 15 for k > 0, 0 for
     * k = 0 and 16 |k| for k < 0. */
    const int64_t rmax2 = t->sq[g->nbins - 1];
    for (int32_t row = -g->max_r - 1; row <= g->max_r + 1; row++) {
        const int64_t dy = row > 0 ? 16 * (int64_t)row - 15 : -16 * (int64_t)row;
        t->reach[row + g->max_r + 1] =
            dy * dy > rmax2 ? -1 : (int32_t)rte_isqrt64((uint64_t)(rmax2 - dy * dy));
    }
}

static inline int32_t radius_bin(const radius_table *t, int64_t d2)
{
    int32_t k = t->coarse[(d2 - t->rmin2) >> t->shift];
    while (t->sq[k + 1] <= d2)
        k++;
    return k;
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

size_t rte_circle_radius_offsets_size(const circle_geom *g)
{
    const int64_t rows = 2 * (int64_t)g->max_r + 3, cols = 2 * ((int64_t)g->max_r + BLOCK + 1) + 1;
    if (2 * (int64_t)g->nbins > INT16_MAX || rows * cols > RADIUS_OFFSETS_MAX)
        return 0;
    return (size_t)(rows * cols);
}

void rte_circle_radius_offsets_init(radius_offsets *o, const circle_geom *g, const radius_table *rt,
                                    int32_t fx, int32_t fy)
{
    const int64_t rmin2 = rt->rmin2, rmax2 = rt->sq[g->nbins - 1];
    o->half_w = g->max_r + BLOCK + 1;
    o->cols = 2 * o->half_w + 1;
    o->fx = fx;
    o->fy = fy;
    for (int32_t ry = -g->max_r - 1; ry <= g->max_r + 1; ry++) {
        const int64_t ddy = (int64_t)ry * 16 - fy;
        int16_t *row = o->bin2 + (size_t)(ry + g->max_r + 1) * (size_t)o->cols + o->half_w;
        for (int32_t rx = -o->half_w; rx <= o->half_w; rx++) {
            const int64_t ddx = (int64_t)rx * 16 - fx, d2 = ddx * ddx + ddy * ddy;
            row[rx] = (int16_t)(2 * (d2 < rmin2 || d2 > rmax2 ? g->nbins : radius_bin(rt, d2)));
        }
    }
}

/* From the largest radius down: each non-empty bin opens a window of
 * `window` bins; a window wins when count / radius is at least the best so
 * far (so ties go to the smaller radius). The pairs are cleared as they are
 * read, for the next centre (a memset per centre, a rep stos, cost a tenth
 * of step 3 on AMD Zen 3). */
static int32_t best_radius(int32_t *pairs, const circle_geom *g, int32_t *radius_q4)
{
    int32_t best_count = 0, best_r = 0;
    for (int32_t j = g->nbins - 1; j >= 0; j--) {
        if (!(pairs[2 * j] | pairs[2 * j + 1]))
            continue;
        int32_t up = j, cnt = 0;
        for (; j > up - g->window && j >= 0; j--) {
            cnt += pairs[2 * j] + pairs[2 * j + 1];
            pairs[2 * j] = pairs[2 * j + 1] = 0;
        }
        int32_t r = g->min_r * 16 + (up + j + 1) / 2;
        if ((int64_t)cnt * best_r >= (int64_t)best_count * r ||
            (best_r == 0 && cnt >= best_count)) {
            best_r = r;
            best_count = cnt;
        }
        j++; /* the loop's j-- moves to the first bin below the window */
    }
    pairs[2 * g->nbins] = pairs[2 * g->nbins + 1] = 0;
    if (best_count == 0) /* no pixel in range (a window counts at least one) */
        return 0;
    *radius_q4 = best_r;
    return best_count;
}

/* Step 3 for one centre (cx, cy in 1/16 pixel): support and radius. Bin k
 * counts in pairs[2 k] and pairs[2 k + 1], from the even and odd pixels of
 * the scan: the pixels where a row crosses the ring fall into the same bin
 * one after the other, and one counter's increments would wait on each
 * other. Pairs 2 nbins and 2 nbins + 1 take the table's pixels out of
 * range. */
int32_t rte_circle_radius(const uint32_t *pts, const int32_t *blk, int32_t nblk, int32_t h,
                          const circle_geom *g, const radius_table *rt, const radius_offsets *o,
                          int32_t cx, int32_t cy, int32_t *pairs, int32_t *radius_q4)
{
    const int64_t rmin2 = rt->rmin2, rmax2 = rt->sq[g->nbins - 1]; /* (min_r 16)^2, (max_r 16)^2 */
    int32_t y_lo = (cy >> 4) - g->max_r - 1, y_hi = (cy >> 4) + g->max_r + 1;
    y_lo = y_lo < 0 ? 0 : y_lo;
    y_hi = y_hi > h - 1 ? h - 1 : y_hi;
    for (int32_t y = y_lo; y <= y_hi; y++) {
        /* only the columns of the row within max_r of the centre: the
         * square around it holds a third more pixels than its disc */
        const int32_t r16 = rt->reach[y - (cy >> 4) + g->max_r + 1];
        if (r16 < 0)
            continue;
        if (o) {
            /* the pixels of the blocks: the table's entries beyond max_r
             * are out of range, and a scan that stops at a pixel
             * mispredicts */
            int32_t i, end;
            ring_window(blk, nblk, y, cx, r16, &i, &end);
            const int16_t *row = o->bin2 + (size_t)(y - (cy >> 4) + g->max_r + 1) * (size_t)o->cols;
            const int32_t shift = o->half_w - (cx >> 4);
            for (; i < end; i++)
                pairs[row[(int32_t)(pts[i] & 0xFFFF) + shift] + (i & 1)]++;
            continue;
        }
        const int32_t x_lo = cx - r16 <= 0 ? 0 : (cx - r16 + 15) >> 4, x_hi = (cx + r16) >> 4;
        const int32_t *rb = blk + (size_t)y * nblk;
        int32_t i = rb[x_lo / BLOCK < nblk - 1 ? x_lo / BLOCK : nblk - 1];
        const int32_t end = rb[nblk - 1];
        while (i < end && (int32_t)(pts[i] & 0xFFFF) < x_lo)
            i++;
        const int64_t ddy = (int64_t)y * 16 - cy;
        for (; i < end; i++) {
            const int32_t x = (int32_t)(pts[i] & 0xFFFF);
            if (x > x_hi)
                break;
            const int64_t ddx = (int64_t)x * 16 - cx, d2 = ddx * ddx + ddy * ddy;
            if (d2 < rmin2 || d2 > rmax2)
                continue;
            pairs[2 * radius_bin(rt, d2) + (i & 1)]++;
        }
    }
    return best_radius(pairs, g, radius_q4);
}

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

/* Step 3b: the centre refined to the point nearest to the gradient lines of
 * the circle's edge pixels (those within 1.5 px of the radius whose
 * gradient points within ~14 degrees of the centre, not on the image
 * border, where the derivatives depend on the border rule): the least-squares
 * intersection sum (I - u u^T) c = sum (I - u u^T) p with unit gradients u
 * in Q8. It works on arcs too, and is not held to the accumulator grid. The
 * radius becomes the mean distance to the refined centre. A move of more
 * than 2 dp, too few pixels or a degenerate system keep the grid centre;
 * radii over 1000 px (where the sums would need more than 64 bits) too. */
void rte_circle_refine(const circle_pixels *cp, int32_t *cx, int32_t *cy, int32_t *r_q4)
{
    const uint32_t *pts = cp->pts;
    const int32_t *blk = cp->blk;
    const int32_t nblk = cp->nblk, h = cp->h;
    const rte_image_s16 *dx = cp->dx, *dy = cp->dy;
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
            /* listed pixels have a gradient, unless the caller's gradient
             * images share memory with the arena (a skipped pixel, not a
             * division by zero) */
            if (gm == 0)
                continue;
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
    const int64_t lim = circle_refine_limit(cp->dp_q8);
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
