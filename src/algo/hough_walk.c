/* The line walk of the segment search: see hough_walk.h, and
 * hough_segments.c for how the search uses it. */
#include "hough_walk.h"

#include <stddef.h>

#include "hough_internal.h"

static inline uint8_t mask_at(const walk_ctx *c, int32_t x, int32_t y)
{
    return ((uint32_t)x < (uint32_t)c->w && (uint32_t)y < (uint32_t)c->h)
               ? c->mask[(size_t)y * c->w + x]
               : 0;
}

stepper rte_hough_walk_stepper(const line_q16 *l, int32_t start_x, int32_t start_y)
{
    stepper s;
    int32_t ax = l->ux < 0 ? -l->ux : l->ux, ay = l->uy < 0 ? -l->uy : l->uy;
    s.major_x = ax >= ay;
    int32_t umaj = s.major_x ? l->ux : l->uy, umin = s.major_x ? l->uy : l->ux;
    int32_t amaj = umaj < 0 ? -umaj : umaj;
    s.dmaj = umaj < 0 ? -1 : 1;
    s.dmin_q16 = ((int64_t)umin * 65536) / amaj;
    /* Start at the point of the line whose major coordinate is the start
     * pixel's: minor = p_min + (start_maj - p_maj) * umin / umaj. */
    int64_t pmaj = s.major_x ? l->px : l->py, pmin = s.major_x ? l->py : l->px;
    s.maj0 = s.major_x ? start_x : start_y;
    s.min0_q16 = pmin + (((int64_t)s.maj0 * 65536 - pmaj) * umin) / umaj;
    return s;
}

/* The mask at `o` pixels across the line from (x, y); `p` is the pixel's
 * byte when the whole reach across the line is inside the map (no bounds
 * checks then), else NULL. major_x is a constant in each copy of follow. */
static inline uint8_t across(const walk_ctx *c, const uint8_t *p, const int major_x, int32_t x,
                             int32_t y, int32_t o)
{
    if (p)
        return p[major_x ? (ptrdiff_t)o * c->w : o];
    return major_x ? mask_at(c, x, y + o) : mask_at(c, x + o, y);
}

/* The edge pixels hit at the step on (x, y) (its major coordinate inside
 * the map): the pixel on the line, else (unless c->strict) a neighbour
 * across the line, extended to the whole run of edge pixels across the line
 * (up to CONSUME_REACH). Returns 1 and the run's centre in half pixels
 * (doubled coordinates, so fits of thick edges follow their middle), 2 when
 * only consumed pixels are there (a bridge), 0 otherwise. */
static inline __attribute__((always_inline)) int
probe(const walk_ctx *c, const int major_x, int32_t x, int32_t y, int32_t *hx2, int32_t *hy2)
{
    const int32_t mn = major_x ? y : x, mn_size = major_x ? c->h : c->w;
    const uint8_t *p =
        mn >= CONSUME_REACH && mn < mn_size - CONSUME_REACH ? c->mask + (size_t)y * c->w + x : NULL;
    uint8_t m0 = across(c, p, major_x, x, y, 0), mlo = across(c, p, major_x, x, y, -1);
    uint8_t mhi = across(c, p, major_x, x, y, 1);
    int32_t lo;
    if (live(m0))
        lo = 0;
    else if (c->strict && (live(mlo) || live(mhi)))
        return 0; /* beside a refitted line: another edge, not this one */
    else if (live(mlo))
        lo = -1;
    else if (live(mhi))
        lo = 1;
    else
        return (m0 | mlo | mhi) ? 2 : 0;
    int32_t hi = lo;
    while (lo > -CONSUME_REACH && live(across(c, p, major_x, x, y, lo - 1)))
        lo--;
    while (hi < CONSUME_REACH && live(across(c, p, major_x, x, y, hi + 1)))
        hi++;
    *hx2 = 2 * x + (major_x ? 0 : lo + hi);
    *hy2 = 2 * y + (major_x ? lo + hi : 0);
    return 1;
}

/* Follows the line both ways from step 0 until more than max_gap steps in a
 * row miss or the line leaves the map (one pixel of slack across the line,
 * so edges along the border count); returns the extreme steps with hits
 * (kmin > kmax when there is none), their hits in c->end2 and records the
 * hits between them. Beyond a gap of more than one step, the end only moves
 * on once two steps in a row hit, so a stray pixel past the end of a line
 * does not lengthen it. One copy per major axis (major_x constant). */
static inline __attribute__((always_inline)) void
follow_axis(walk_ctx *c, const stepper *s, const int major_x, int32_t *kmin, int32_t *kmax)
{
    const uint32_t maj_size = (uint32_t)(major_x ? c->w : c->h),
                   mn_span = (uint32_t)(major_x ? c->h : c->w) + 1;
    c->nhits = 0;
    *kmin = INT32_MAX;
    *kmax = INT32_MIN;
    for (int32_t dir = 1; dir >= -1; dir -= 2) {
        int32_t gap = 0, run = 0, seed_run = 1, kept = c->nhits, gap_before = 0;
        /* stepper_at(s, k), one addition per step */
        const int32_t k0 = dir == 1 ? 0 : -1, dmaj = dir * s->dmaj;
        const int64_t dmin = dir * s->dmin_q16;
        int32_t maj = s->maj0 + k0 * s->dmaj;
        int64_t mq = s->min0_q16 + (int64_t)k0 * s->dmin_q16 + 32768;
        for (int32_t k = k0;; k += dir, maj += dmaj, mq += dmin) {
            int32_t hx2, hy2, mn = floor_q16(mq);
            if ((uint32_t)maj >= maj_size || (uint32_t)(mn + 1) > mn_span)
                break;
            const int32_t x = major_x ? maj : mn, y = major_x ? mn : maj;
            int hit = probe(c, major_x, x, y, &hx2, &hy2);
            if (hit == 1) {
                if (run++ == 0)
                    gap_before = gap;
                gap = 0;
                c->hits[c->nhits++] = ((uint32_t)hy2 << 16) | (uint32_t)hx2;
                if (seed_run || run >= 2 || gap_before <= 1) {
                    kept = c->nhits;
                    if (k > *kmax) {
                        *kmax = k;
                        c->end2[2] = hx2, c->end2[3] = hy2;
                    }
                    if (k < *kmin) {
                        *kmin = k;
                        c->end2[0] = hx2, c->end2[1] = hy2;
                    }
                }
                continue;
            }
            run = 0;
            seed_run &= hit == 2; /* the seed's run goes on across earlier segments */
            if (hit == 2)
                gap = 0;
            else if (++gap > c->max_gap)
                break;
        }
        c->nhits = kept;
    }
}

void rte_hough_walk_follow(walk_ctx *c, const stepper *s, int32_t *kmin, int32_t *kmax)
{
    /* a local copy: the stores of hits could alias the context's fields */
    walk_ctx l = *c;
    int32_t lo, hi;
    if (s->major_x)
        follow_axis(&l, s, 1, &lo, &hi);
    else
        follow_axis(&l, s, 0, &lo, &hi);
    *c = l;
    *kmin = lo;
    *kmax = hi;
}

/* floor(v / 65536 + 1/2) for any sign */
static inline int32_t round_q16(int64_t v) { return floor_q16(v + 32768); }

/* The hit (half pixels) projected onto the line, rounded to a pixel. */
void rte_hough_walk_project(const line_q16 *l, int32_t hx2, int32_t hy2, int32_t *x, int32_t *y)
{
    int64_t dx = ((int64_t)hx2 << 15) - l->px, dy = ((int64_t)hy2 << 15) - l->py;
    int64_t t = (dx * l->ux + dy * l->uy) / 65536; /* Q16 pixels along the line */
    *x = round_q16(l->px + t * l->ux / 65536);
    *y = round_q16(l->py + t * l->uy / 65536);
}

/* Principal axis of the hits (integer): the direction (r + a, b) with
 * a = Cxx - Cyy, b = 2 Cxy, r = |(a, b)| halves the angle of (a, b). */
bool rte_hough_walk_fit(const walk_ctx *c, line_q16 *l)
{
    int32_t n = c->nhits;
    if (n < 3)
        return false;
    int64_t sx = 0, sy = 0;
    for (int32_t i = 0; i < n; i++) {
        sx += c->hits[i] & 0xFFFF;
        sy += c->hits[i] >> 16;
    }
    /* Centroid in Q4 (the hits are in half pixels); coordinates relative to
     * it stay below 2^20, squares below 2^40, sums of up to 2^17 of them
     * below 2^57. */
    int64_t mx = (sx * 8 + n / 2) / n, my = (sy * 8 + n / 2) / n;
    int64_t cxx = 0, cyy = 0, cxy = 0;
    for (int32_t i = 0; i < n; i++) {
        int64_t dx = (int64_t)(c->hits[i] & 0xFFFF) * 8 - mx,
                dy = (int64_t)(c->hits[i] >> 16) * 8 - my;
        cxx += dx * dx;
        cyy += dy * dy;
        cxy += dx * dy;
    }
    int64_t a = cxx - cyy, b = 2 * cxy;
    while (a > (1 << 30) || a < -(1 << 30) || b > (1 << 30) || b < -(1 << 30)) {
        a /= 2;
        b /= 2;
    }
    int64_t r = rte_isqrt64((uint64_t)(a * a + b * b));
    int64_t vx = r + a, vy = b;
    if (vx == 0 && vy == 0)
        return false; /* no elongation: keep the quantised direction */
    uint64_t len = rte_isqrt64((uint64_t)(vx * vx + vy * vy));
    if (len == 0)
        return false;
    l->ux = (int32_t)(vx * 65536 / (int64_t)len);
    l->uy = (int32_t)(vy * 65536 / (int64_t)len);
    if (l->ux == 0 && l->uy == 0)
        return false;
    l->px = mx * 4096;
    l->py = my * 4096;
    return true;
}
