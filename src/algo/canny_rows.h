/* Canny's row kernels for 8-bit images with aperture 3 and the L1 magnitude
 * (private to src/algo): included by canny.c, which builds them for the
 * baseline target as the C reference, and by simd/canny_x86.c, which builds
 * the very same loops for AVX2. simd/canny_neon.c writes them with NEON
 * intrinsics. tests/unit/test_simd.c checks that all give the same bytes.
 *
 * With aperture 3, |dx| and |dy| are at most 4 * 255 = 1020 and |dx| + |dy|
 * at most 2040, so everything runs in 16-bit lanes (8 per SSE2 or NEON
 * register, 16 per AVX2 one), the sector test included (see nms_row). */
#ifndef RTEDGE_ALGO_CANNY_ROWS_H
#define RTEDGE_ALGO_CANNY_ROWS_H

#include <stdint.h>

/* tan(22.5 deg) in Q15, OpenCV's sector boundary. */
#define RTE_CANNY_TG22_Q15 13573

/* Sobel 3x3 of one pixel from three rows (up, mid, down) at columns l, x, r. */
static inline void canny_sobel_px(const uint8_t *a, const uint8_t *b, const uint8_t *c, int32_t l,
                                  int32_t x, int32_t r, int16_t *dx, int16_t *dy, int16_t *mag)
{
    const int32_t gx = (a[r] + 2 * b[r] + c[r]) - (a[l] + 2 * b[l] + c[l]);
    const int32_t gy = (c[l] + 2 * c[x] + c[r]) - (a[l] + 2 * a[x] + a[r]);
    dx[x] = (int16_t)gx;
    dy[x] = (int16_t)gy;
    mag[x] = (int16_t)((gx < 0 ? -gx : gx) + (gy < 0 ? -gy : gy));
}

/* dx, dy (Sobel 3x3) and |dx| + |dy| of the row between `up` and `down`;
 * columns beyond the row replicate its ends (BORDER_REPLICATE, as Canny). */
static inline void canny_sobel_row(const uint8_t *restrict a, const uint8_t *restrict b,
                                   const uint8_t *restrict c, int16_t *restrict ox,
                                   int16_t *restrict oy, int16_t *restrict om, int32_t width)
{
    if (width == 1) {
        canny_sobel_px(a, b, c, 0, 0, 0, ox, oy, om);
        return;
    }
    canny_sobel_px(a, b, c, 0, 0, 1, ox, oy, om);
    for (int32_t x = 1; x < width - 1; x++) {
        const int16_t gx =
            (int16_t)((a[x + 1] + 2 * b[x + 1] + c[x + 1]) - (a[x - 1] + 2 * b[x - 1] + c[x - 1]));
        const int16_t gy =
            (int16_t)((c[x - 1] + 2 * c[x] + c[x + 1]) - (a[x - 1] + 2 * a[x] + a[x + 1]));
        ox[x] = gx;
        oy[x] = gy;
        om[x] = (int16_t)((gx < 0 ? -gx : gx) + (gy < 0 ? -gy : gy));
    }
    canny_sobel_px(a, b, c, width - 2, width - 1, width - 1, ox, oy, om);
}

/* Non-maximum suppression of one row into map codes: 1 = not an edge, 0 =
 * maybe (a local maximum above low), 2 = edge (a local maximum above high).
 * up, cur and down are magnitude rows with a 0 at index -1 and width.
 *
 * OpenCV's sector test in 32 bits, with ax = |dx|, ay = |dy|:
 *   horizontal  ay << 15 < ax * 13573
 *   vertical    ay << 15 > ax * 13573 + (ax << 16)
 * 13573 is odd, so for 0 < ax < 2^15 the quotient q = ax * 13573 / 2^15 is
 * never a whole number, and with t = floor(q) (the high half of
 * ax * 27146, one 16-bit multiply):
 *   horizontal  ay < q       <=>  ay <= t       (and ax != 0: ay < 0 is false)
 *   vertical    ay - 2ax > q <=>  ay > 2ax + t  (for ax = 0 too: t = 0)
 * Horizontal ties go to the right pixel, vertical ones to the lower pixel
 * (>=), diagonal ones to neither (>), as OpenCV. */
static inline void canny_nms_row(const int16_t *restrict u, const int16_t *restrict c,
                                 const int16_t *restrict d, const int16_t *restrict gx,
                                 const int16_t *restrict gy, uint8_t *restrict out, int32_t width,
                                 int16_t low, int16_t high)
{
    for (int32_t x = 0; x < width; x++) {
        const int16_t m = c[x];
        const uint16_t ax = (uint16_t)(gx[x] < 0 ? -gx[x] : gx[x]);
        const uint16_t ay = (uint16_t)(gy[x] < 0 ? -gy[x] : gy[x]);
        const uint16_t t = (uint16_t)(((uint32_t)ax * (2u * RTE_CANNY_TG22_Q15)) >> 16);
        /* All neighbours are loaded, then selected: no branches. */
        const int16_t ul = u[x - 1], uc = u[x], ur = u[x + 1];
        const int16_t cl = c[x - 1], cr = c[x + 1];
        const int16_t dl = d[x - 1], dc = d[x], dr = d[x + 1];
        const int16_t same_sign = (int16_t)((gx[x] ^ gy[x]) >= 0);
        const int16_t diag_a = same_sign ? ul : ur;
        const int16_t diag_b = same_sign ? dr : dl;
        /* vertical excludes horizontal: t < 2ax + t when ax != 0 */
        const int16_t horizontal = (int16_t)((ay <= t) & (ax != 0));
        const int16_t vertical = (int16_t)(ay > (uint16_t)(2 * ax + t));
        const int16_t keep_h = (int16_t)((m > cl) & (m >= cr));
        const int16_t keep_v = (int16_t)((m > uc) & (m >= dc));
        const int16_t keep_d = (int16_t)((m > diag_a) & (m > diag_b));
        const int16_t keep = (int16_t)((horizontal & keep_h) | (vertical & keep_v) |
                                       (((horizontal | vertical) == 0) & keep_d));
        out[x] = (uint8_t)(1 + (keep & (m > low)) * ((m > high) * 2 - 1));
    }
}

/* Defines rte_canny_sobel_row_<isa> and rte_canny_nms_row_<isa> (declared
 * in simd/rows.h) as the loops above, built for the including file's target. */
#define RTE_CANNY_ROWS_DEFINE(isa)                                                             \
    void rte_canny_sobel_row_##isa(const uint8_t *up, const uint8_t *mid, const uint8_t *down, \
                                   int16_t *dx, int16_t *dy, int16_t *mag, int32_t width)      \
    {                                                                                          \
        canny_sobel_row(up, mid, down, dx, dy, mag, width);                                    \
    }                                                                                          \
    void rte_canny_nms_row_##isa(const int16_t *up, const int16_t *cur, const int16_t *down,   \
                                 const int16_t *dx, const int16_t *dy, uint8_t *map,           \
                                 int32_t width, int16_t low, int16_t high)                     \
    {                                                                                          \
        canny_nms_row(up, cur, down, dx, dy, map, width, low, high);                           \
    }

#endif
