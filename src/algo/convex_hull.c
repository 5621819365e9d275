/* Convex hull (Sklansky's scan over points sorted by x then y, as
 * cv::convexHull) and convexity defects (as cv::convexityDefects). */
#include "rtedge/shape.h"

#include <string.h>

#include "geom_fixed.h"

#define COORD_BIAS (RTE_SHAPE_MAX_COORD + 1)

static int coord_ok(rte_point p)
{
    return p.x >= -RTE_SHAPE_MAX_COORD && p.x <= RTE_SHAPE_MAX_COORD &&
           p.y >= -RTE_SHAPE_MAX_COORD && p.y <= RTE_SHAPE_MAX_COORD;
}

size_t rte_shape_hull_scratch_size(int32_t max_points)
{
    if (max_points < 0)
        return 0;
    size_t n = (size_t)max_points + 2;
    return 2 * rte_arena_piece_size(n * sizeof(uint64_t)) +
           3 * rte_arena_piece_size(n * sizeof(int32_t));
}

/* Sorts point indices by (x, y, index): LSD radix sort of 24-bit keys over
 * 64-bit (key << 32 | index) words, stable, so equal points keep index
 * order, which is OpenCV's tie rule. */
static void sort_points(const rte_point *pts, int32_t n, uint64_t *a, uint64_t *tmp, int32_t *ord)
{
    for (int32_t i = 0; i < n; i++) {
        uint64_t key = (uint64_t)(pts[i].x + COORD_BIAS) << 12 | (uint64_t)(pts[i].y + COORD_BIAS);
        a[i] = key << 32 | (uint32_t)i;
    }
    for (int shift = 32; shift < 56; shift += 8) {
        size_t count[257];
        memset(count, 0, sizeof count);
        for (int32_t i = 0; i < n; i++)
            count[((a[i] >> shift) & 255) + 1]++;
        for (int k = 0; k < 256; k++)
            count[k + 1] += count[k];
        for (int32_t i = 0; i < n; i++)
            tmp[count[(a[i] >> shift) & 255]++] = a[i];
        uint64_t *t = a;
        a = tmp;
        tmp = t;
    }
    /* `a` now points at the fully sorted words (after an odd pass count it
     * is the caller's tmp buffer). */
    for (int32_t i = 0; i < n; i++)
        ord[i] = (int32_t)(uint32_t)a[i];
}

static int sign64(int64_t v) { return (v > 0) - (v < 0); }

static int same_point(rte_point a, rte_point b) { return a.x == b.x && a.y == b.y; }

/* One chain of Sklansky's scan between sorted positions start and end;
 * writes sorted positions to stack and returns their count. nsign rejects
 * steps whose y direction has that sign; sign2 is the convex turn. */
static int32_t sklansky(const rte_point *pts, const int32_t *ord, int32_t start, int32_t end,
                        int32_t *stack, int nsign, int sign2)
{
#define P(k) pts[ord[k]]
    int32_t incr = end > start ? 1 : -1;
    int32_t pprev = start, pcur = pprev + incr, pnext = pcur + incr;
    int32_t size = 3;

    if (start == end || same_point(P(start), P(end))) {
        stack[0] = start;
        return 1;
    }
    stack[0] = pprev;
    stack[1] = pcur;
    stack[2] = pnext;
    end += incr;
    while (pnext != end) {
        int64_t by = (int64_t)P(pnext).y - P(pcur).y;
        if (sign64(by) != nsign) {
            int64_t ax = (int64_t)P(pcur).x - P(pprev).x, ay = (int64_t)P(pcur).y - P(pprev).y;
            int64_t bx = (int64_t)P(pnext).x - P(pcur).x;
            int64_t convexity = ay * bx - ax * by;
            if (sign64(convexity) == sign2 && (ax != 0 || ay != 0)) {
                pprev = pcur;
                pcur = pnext;
                pnext += incr;
                stack[size++] = pnext;
            } else if (pprev == start) {
                pcur = pnext;
                stack[1] = pcur;
                pnext += incr;
                stack[2] = pnext;
            } else {
                stack[size - 2] = pnext;
                pcur = pprev;
                pprev = stack[size - 4];
                size--;
            }
        } else {
            pnext += incr;
            stack[size - 1] = pnext;
        }
    }
    return size - 1;
#undef P
}

/* OpenCV rotates the output so that the indices run monotonically when a
 * rotation can make them; convexityDefects relies on it. */
static void make_monotonic(int32_t *hull, int32_t n, int32_t *tmp)
{
    if (n < 3)
        return;
    int32_t min_i = 0, max_i = 0, lt = 0, i;
    for (i = 1; i < n; i++) {
        int32_t idx = hull[i];
        lt += hull[i - 1] < idx;
        if (lt > 1 && lt <= i - 2)
            break;
        if (idx < hull[min_i])
            min_i = i;
        if (idx > hull[max_i])
            max_i = i;
    }
    int32_t dist = max_i > min_i ? max_i - min_i : min_i - max_i;
    if (!((dist == 1 || dist == n - 1) && (lt <= 1 || lt >= n - 2)))
        return;
    int ascending = (max_i + 1) % n == min_i;
    int32_t i0 = ascending ? min_i : max_i, j = i0;
    if (i0 == 0)
        return;
    for (i = 0; i < n; i++) {
        int32_t cur = tmp[i] = hull[j];
        int32_t nj = j + 1 < n ? j + 1 : 0;
        if (i < n - 1 && (ascending != (cur < hull[nj])))
            break;
        j = nj;
    }
    if (i == n)
        memcpy(hull, tmp, (size_t)n * sizeof *hull);
}

static int32_t hull_indices(const rte_point *pts, int32_t n, const int32_t *ord, int32_t *stack,
                            int32_t *out)
{
#define P(k) pts[ord[k]]
    int32_t miny = 0, maxy = 0, nout = 0;
    for (int32_t i = 1; i < n; i++) {
        if (P(miny).y > P(i).y)
            miny = i;
        if (P(maxy).y < P(i).y)
            maxy = i;
    }
    if (same_point(P(0), P(n - 1))) {
        out[0] = ord[0];
        return 1;
    }
    /* Upper half; for the counter-clockwise (y-up) order the right chain
     * comes first. */
    int32_t *tl = stack;
    int32_t tl_n = sklansky(pts, ord, 0, maxy, tl, -1, 1);
    int32_t *tr = stack + tl_n;
    int32_t tr_n = sklansky(pts, ord, n - 1, maxy, tr, -1, -1);
    int32_t *t = tl;
    tl = tr;
    tr = t;
    int32_t k = tl_n;
    tl_n = tr_n;
    tr_n = k;
    for (int32_t i = 0; i < tl_n - 1; i++)
        out[nout++] = ord[tl[i]];
    for (int32_t i = tr_n - 1; i > 0; i--)
        out[nout++] = ord[tr[i]];
    int32_t stop = tr_n > 2 ? tr[1] : tl_n > 2 ? tl[tl_n - 2] : -1;

    /* Lower half. */
    int32_t *bl = stack;
    int32_t bl_n = sklansky(pts, ord, 0, miny, bl, 1, -1);
    int32_t *br = stack + bl_n;
    int32_t br_n = sklansky(pts, ord, n - 1, miny, br, 1, 1);
    if (stop >= 0) {
        int32_t check = bl_n > 2 ? bl[1] : bl_n + br_n > 2 ? br[2 - bl_n] : -1;
        if (check == stop || (check >= 0 && same_point(P(check), P(stop)))) {
            /* All points on one line: the lower half mirrors the upper. */
            bl_n = bl_n < 2 ? bl_n : 2;
            br_n = br_n < 2 ? br_n : 2;
        }
    }
    for (int32_t i = 0; i < bl_n - 1; i++)
        out[nout++] = ord[bl[i]];
    for (int32_t i = br_n - 1; i > 0; i--)
        out[nout++] = ord[br[i]];
    make_monotonic(out, nout, stack);
    return nout;
#undef P
}

rte_status rte_shape_convex_hull(const rte_point *pts, int32_t n, int32_t *indices, rte_point *hull,
                                 int32_t *n_hull, rte_arena *scratch)
{
    if (!n_hull || n < 0 || (n > 0 && (!pts || !scratch)) || (!indices && !hull))
        return RTE_ERR_ARGUMENT;
    *n_hull = 0;
    if (n == 0)
        return RTE_OK;
    for (int32_t i = 0; i < n; i++)
        if (!coord_ok(pts[i]))
            return RTE_ERR_TOO_LARGE;
    const size_t mark = rte_arena_mark(scratch);
    const size_t m = (size_t)n + 2;
    uint64_t *a = rte_arena_alloc(scratch, m * sizeof *a);
    uint64_t *tmp = rte_arena_alloc(scratch, m * sizeof *tmp);
    int32_t *ord = rte_arena_alloc(scratch, m * sizeof *ord);
    int32_t *stack = rte_arena_alloc(scratch, m * sizeof *stack);
    int32_t *out = rte_arena_alloc(scratch, m * sizeof *out);
    if (!a || !tmp || !ord || !stack || !out) {
        rte_arena_reset(scratch, mark);
        return RTE_ERR_NO_MEMORY;
    }
    sort_points(pts, n, a, tmp, ord);
    int32_t nout = hull_indices(pts, n, ord, stack, out);
    for (int32_t i = 0; i < nout; i++) {
        if (indices)
            indices[i] = out[i];
        if (hull)
            hull[i] = pts[out[i]];
    }
    *n_hull = nout;
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}

rte_status rte_shape_hull_in_arena(const rte_point *pts, int32_t n, rte_arena *scratch,
                                   rte_point **hull, int32_t *n_hull)
{
    if (n < 1 || !pts || !scratch)
        return RTE_ERR_ARGUMENT;
    const size_t mark = rte_arena_mark(scratch);
    rte_point *h = rte_arena_alloc(scratch, ((size_t)n + 1) * sizeof *h);
    if (!h)
        return RTE_ERR_NO_MEMORY;
    rte_status st = rte_shape_convex_hull(pts, n, NULL, h, n_hull, scratch);
    if (st != RTE_OK)
        rte_arena_reset(scratch, mark);
    *hull = h;
    return st;
}

/* round(256 * c / sqrt(l)) for c >= 0, l > 0, exactly: the q with
 * (2q - 1)^2 l <= 4 (256 c)^2 < (2q + 1)^2 l. */
static int32_t depth_q8(int64_t c, int64_t l)
{
    const rte_u128 v = (rte_u128)((rte_u128)c * c) * 65536u * 4u;
    rte_u128 q = rte_isqrt128(v / (rte_u128)l) / 2;
    while ((rte_u128)(2 * q + 1) * (2 * q + 1) * (rte_u128)l <= v)
        q++;
    while (q > 0 && (rte_u128)(2 * q - 1) * (2 * q - 1) * (rte_u128)l > v)
        q--;
    return (int32_t)q;
}

rte_status rte_shape_convexity_defects(const rte_point *pts, int32_t n, const int32_t *hull,
                                       int32_t n_hull, rte_defect *defects, int32_t *n_defects)
{
    if (!n_defects || n < 0 || n_hull < 0 || (n > 0 && !pts) || (n_hull > 0 && (!hull || !defects)))
        return RTE_ERR_ARGUMENT;
    *n_defects = 0;
    if (n <= 3 || n_hull < 3)
        return RTE_OK;
    for (int32_t i = 0; i < n_hull; i++)
        if (hull[i] < 0 || hull[i] >= n)
            return RTE_ERR_ARGUMENT;
    for (int32_t i = 0; i < n; i++)
        if (!coord_ok(pts[i]))
            return RTE_ERR_TOO_LARGE;

    /* Walk the hull in the contour's direction. */
    const int rev = ((hull[1] > hull[0]) + (hull[2] > hull[1]) + (hull[0] > hull[2])) != 2;
    int32_t hcur = hull[rev ? 0 : n_hull - 1], nd = 0;
    int increasing = -1;
    for (int32_t i = 0; i < n_hull; i++) {
        int32_t hnext = hull[rev ? n_hull - i - 1 : i];
        if (increasing < 0)
            increasing = !(hcur < hnext);
        else if (increasing != (hcur < hnext))
            return RTE_ERR_ARGUMENT;
        const rte_point p0 = pts[hcur], p1 = pts[hnext];
        const int64_t dx0 = (int64_t)p1.x - p0.x, dy0 = (int64_t)p1.y - p0.y;
        const int64_t len2 = dx0 * dx0 + dy0 * dy0;
        /* The farthest point has the largest |cross|: the same point as
         * OpenCV's double distances, which are |cross| times one scale. */
        int64_t best = 0;
        int32_t far = -1;
        for (int32_t j = hcur;;) {
            j = j + 1 >= n ? 0 : j + 1;
            if (j == hnext)
                break;
            int64_t c = -dy0 * ((int64_t)pts[j].x - p0.x) + dx0 * ((int64_t)pts[j].y - p0.y);
            c = c < 0 ? -c : c;
            if (len2 > 0 && c > best) {
                best = c;
                far = j;
            }
        }
        if (far >= 0)
            defects[nd++] = (rte_defect){hcur, hnext, far, depth_q8(best, len2)};
        hcur = hnext;
    }
    *n_defects = nd;
    return RTE_OK;
}
