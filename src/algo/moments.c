/* Area, perimeter, bounding box and moments of a polygon (Green's theorem,
 * as cv::contourArea / arcLength / moments), in exact integers where OpenCV
 * is exact and in stated fixed point elsewhere. */
#include "rtedge/shape.h"

#include "geom_fixed.h"

int64_t rte_shape_area2(const rte_point *pts, int32_t n)
{
    if (!pts || n < 3)
        return 0;
    int64_t a = 0;
    rte_point p = pts[n - 1];
    for (int32_t i = 0; i < n; i++) {
        a += (int64_t)p.x * pts[i].y - (int64_t)pts[i].x * p.y;
        p = pts[i];
    }
    return a;
}

/* Q16 length of a segment; unit steps (the common case for NONE contours)
 * skip the square root. */
static int64_t segment_q16(int64_t dx, int64_t dy)
{
    uint64_t d2 = (uint64_t)(dx * dx + dy * dy);
    if (d2 <= 2)
        return d2 == 0 ? 0 : d2 == 1 ? 65536 : 92682;
    return (int64_t)rte_isqrt64_round(d2 << 32);
}

int64_t rte_shape_perimeter_q16(const rte_point *pts, int32_t n, int closed)
{
    if (!pts || n < 2)
        return 0;
    int64_t len = 0;
    for (int32_t i = 1; i < n; i++)
        len += segment_q16((int64_t)pts[i].x - pts[i - 1].x, (int64_t)pts[i].y - pts[i - 1].y);
    if (closed)
        len += segment_q16((int64_t)pts[0].x - pts[n - 1].x, (int64_t)pts[0].y - pts[n - 1].y);
    return len;
}

rte_rect rte_shape_bounding_rect(const rte_point *pts, int32_t n)
{
    rte_rect r = {0, 0, 0, 0};
    if (!pts || n < 1)
        return r;
    int32_t x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
    for (int32_t i = 1; i < n; i++) {
        x0 = pts[i].x < x0 ? pts[i].x : x0;
        x1 = pts[i].x > x1 ? pts[i].x : x1;
        y0 = pts[i].y < y0 ? pts[i].y : y0;
        y1 = pts[i].y > y1 ? pts[i].y : y1;
    }
    r.x = x0;
    r.y = y0;
    r.width = x1 - x0 + 1;
    r.height = y1 - y0 + 1;
    return r;
}

/* (2^34 * num) / (den * A^3 * ...) style divisions are done in 128 bits. */
static int64_t q_div(rte_i128 num, rte_i128 den) { return (int64_t)rte_div_round128(num, den); }

/* (a * b) >> 32 with rounding, for Q32 products. */
static int64_t q32_mul(int64_t a, int64_t b)
{
    rte_i128 p = (rte_i128)a * b;
    return (int64_t)((p + ((rte_i128)1 << 31)) >> 32);
}

/* n 2^58 / (b c) in two steps that keep about 70 significant bits: first
 * t = n 2^s / b with n 2^s just below 2^125, then t 2^(58-s) / c (the
 * result, |nu| 2^32, is small, so the product cannot overflow). */
static int64_t nu3_q32(rte_i128 n, rte_i128 b, rte_i128 c)
{
    rte_i128 mag = n < 0 ? -n : n;
    int s = 0;
    while (s < 58 && mag < ((rte_i128)1 << 124)) {
        mag <<= 1;
        s++;
    }
    rte_i128 t = rte_div_round128(n * ((rte_i128)1 << s), b);
    return q_div(t * ((rte_i128)1 << (58 - s)), c);
}

static void hu_invariants(rte_moments *m)
{
    const int64_t n20 = m->nu20_q32, n11 = m->nu11_q32, n02 = m->nu02_q32;
    const int64_t n30 = m->nu30_q32, n21 = m->nu21_q32, n12 = m->nu12_q32, n03 = m->nu03_q32;
    int64_t t0 = n30 + n12, t1 = n21 + n03;
    int64_t q0 = q32_mul(t0, t0), q1 = q32_mul(t1, t1);
    int64_t n4 = 4 * n11, s = n20 + n02, d = n20 - n02;
    m->hu_q32[0] = s;
    m->hu_q32[1] = q32_mul(d, d) + q32_mul(n4, n11);
    m->hu_q32[3] = q0 + q1;
    m->hu_q32[5] = q32_mul(d, q0 - q1) + q32_mul(q32_mul(n4, t0), t1);
    int64_t u0 = q32_mul(t0, q0 - 3 * q1), u1 = q32_mul(t1, 3 * q0 - q1);
    int64_t r0 = n30 - 3 * n12, r1 = 3 * n21 - n03;
    m->hu_q32[2] = q32_mul(r0, r0) + q32_mul(r1, r1);
    m->hu_q32[4] = q32_mul(r0, u0) + q32_mul(r1, u1);
    m->hu_q32[6] = q32_mul(r1, u0) - q32_mul(r0, u1);
}

rte_status rte_shape_moments(const rte_point *pts, int32_t n, rte_moments *m)
{
    if (!m || n < 0 || (n > 0 && !pts))
        return RTE_ERR_ARGUMENT;
    *m = (rte_moments){0};
    for (int32_t i = 0; i < n; i++)
        if (pts[i].x > RTE_SHAPE_MAX_COORD || pts[i].x < -RTE_SHAPE_MAX_COORD ||
            pts[i].y > RTE_SHAPE_MAX_COORD || pts[i].y < -RTE_SHAPE_MAX_COORD)
            return RTE_ERR_TOO_LARGE;
    if (n < 3)
        return RTE_OK;

    /* Green's theorem sums. With |coordinates| <= 2047 every term and every
     * final sum fits in 64 bits; partial sums may not, so they wrap in
     * unsigned arithmetic and come out exact. */
    uint64_t u00 = 0, u10 = 0, u01 = 0, u20 = 0, u11 = 0, u02 = 0, u30 = 0, u21 = 0, u12 = 0,
             u03 = 0;
    int64_t xp = pts[n - 1].x, yp = pts[n - 1].y;
    for (int32_t i = 0; i < n; i++) {
        const int64_t x = pts[i].x, y = pts[i].y;
        const int64_t dxy = xp * y - x * yp;
        const int64_t xs = xp + x, ys = yp + y, x2 = x * x, y2 = y * y, xp2 = xp * xp,
                      yp2 = yp * yp;
        u00 += (uint64_t)dxy;
        u10 += (uint64_t)(dxy * xs);
        u01 += (uint64_t)(dxy * ys);
        u20 += (uint64_t)(dxy * (xp * xs + x2));
        u11 += (uint64_t)(dxy * (xp * (ys + yp) + x * (ys + y)));
        u02 += (uint64_t)(dxy * (yp * ys + y2));
        u30 += (uint64_t)(dxy * xs * (xp2 + x2));
        u03 += (uint64_t)(dxy * ys * (yp2 + y2));
        u21 += (uint64_t)(dxy * (xp2 * (3 * yp + y) + 2 * x * xp * ys + x2 * (yp + 3 * y)));
        u12 += (uint64_t)(dxy * (yp2 * (3 * xp + x) + 2 * y * yp * xs + y2 * (xp + 3 * x)));
        xp = x;
        yp = y;
    }
    int64_t a00 = (int64_t)u00, a10 = (int64_t)u10, a01 = (int64_t)u01, a20 = (int64_t)u20,
            a11 = (int64_t)u11, a02 = (int64_t)u02, a30 = (int64_t)u30, a21 = (int64_t)u21,
            a12 = (int64_t)u12, a03 = (int64_t)u03;
    if (a00 == 0)
        return RTE_OK;
    if (a00 < 0) {
        a00 = -a00, a10 = -a10, a01 = -a01, a20 = -a20, a11 = -a11, a02 = -a02;
        a30 = -a30, a21 = -a21, a12 = -a12, a03 = -a03;
    }
    m->s00 = a00, m->s10 = a10, m->s01 = a01, m->s20 = a20, m->s11 = a11, m->s02 = a02;
    m->s30 = a30, m->s21 = a21, m->s12 = a12, m->s03 = a03;

    /* Exact central moments (derived from mu_pq = sum C x^i y^j of the
     * shifted polygon): mu20 = (3 A a20 - 2 X^2) / (36 A) and so on, with
     * A = a00, X = a10, Y = a01. */
    const rte_i128 A = a00, X = a10, Y = a01;
    m->cx_q16 = q_div(X * 65536, 3 * A);
    m->cy_q16 = q_div(Y * 65536, 3 * A);
    const rte_i128 n20 = 3 * A * a20 - 2 * X * X;
    const rte_i128 n11 = 3 * A * a11 - 4 * X * Y;
    const rte_i128 n02 = 3 * A * a02 - 2 * Y * Y;
    const rte_i128 A2 = A * A;
    const rte_i128 n30 = 27 * A2 * a30 - 45 * A * X * a20 + 20 * X * X * X;
    const rte_i128 n21 = 9 * A2 * a21 - 15 * A * X * a11 - 15 * A * Y * a20 + 20 * X * X * Y;
    const rte_i128 n12 = 9 * A2 * a12 - 15 * A * X * a02 - 15 * A * Y * a11 + 20 * X * Y * Y;
    const rte_i128 n03 = 27 * A2 * a03 - 45 * A * Y * a02 + 20 * Y * Y * Y;
    m->mu20_q8 = q_div(n20 * 256, 36 * A);
    m->mu11_q8 = q_div(n11 * 256, 72 * A);
    m->mu02_q8 = q_div(n02 * 256, 36 * A);
    m->mu30_q8 = q_div(n30 * 256, 540 * A2);
    m->mu21_q8 = q_div(n21 * 256, 540 * A2);
    m->mu12_q8 = q_div(n12 * 256, 540 * A2);
    m->mu03_q8 = q_div(n03 * 256, 540 * A2);

    /* nu_pq = mu_pq / m00^(1 + (p+q)/2) with m00 = A / 2.
     * Second order: 4 mu / A^2, i.e. n / (9 A^3) for 20 and 02. */
    const rte_i128 A3 = A2 * A;
    m->nu20_q32 = q_div(n20 * ((rte_i128)1 << 34), 36 * A3);
    m->nu11_q32 = q_div(n11 * ((rte_i128)1 << 34), 72 * A3);
    m->nu02_q32 = q_div(n02 * ((rte_i128)1 << 34), 36 * A3);
    /* Third order: 4 mu / (A^2 sqrt(A/2)) = n 2^58 / (540 A^2 . A^2 sq)
     * with sq = sqrt(A/2) in Q24 (relative error < 5e-8). */
    const rte_i128 sq = (rte_i128)rte_isqrt128((rte_u128)a00 << 47);
    m->nu30_q32 = nu3_q32(n30, 540 * A2, A2 * sq);
    m->nu21_q32 = nu3_q32(n21, 540 * A2, A2 * sq);
    m->nu12_q32 = nu3_q32(n12, 540 * A2, A2 * sq);
    m->nu03_q32 = nu3_q32(n03, 540 * A2, A2 * sq);
    hu_invariants(m);
    return RTE_OK;
}
