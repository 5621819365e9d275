/* Canny's row kernels (aperture 3, L1) for aarch64 NEON (see rows.h; the
 * C reference is src/algo/canny_rows.h, whose comments give the maths).
 * Intrinsics (<arm_neon.h>; NEON is aarch64's baseline, no flags), 8 pixels
 * per 16-bit vector. The sector test's floor(|dx| * 13573 / 2^15)
 * is vqdmulh by 13573 (the high half of 2 * |dx| * 13573; no saturation
 * since |dx| <= 1020). */
#include "rows.h"

#ifdef RTE_SIMD_NEON
#include <arm_neon.h>

#include "algo/canny_rows.h"

/* Sum a[x-1] + 2 a[x] + a[x+1] style taps, widened to 16 bits. */
static inline int16x8_t smooth3(const uint8_t *p)
{
    const uint16x8_t l = vmovl_u8(vld1_u8(p - 1)), c = vmovl_u8(vld1_u8(p)),
                     r = vmovl_u8(vld1_u8(p + 1));
    return vreinterpretq_s16_u16(vaddq_u16(vaddq_u16(l, r), vshlq_n_u16(c, 1)));
}

static inline int16x8_t column3(const uint8_t *a, const uint8_t *b, const uint8_t *c)
{
    const uint16x8_t s = vaddq_u16(vaddl_u8(vld1_u8(a), vld1_u8(c)), vshll_n_u8(vld1_u8(b), 1));
    return vreinterpretq_s16_u16(s);
}

void rte_canny_sobel_row_neon(const uint8_t *up, const uint8_t *mid, const uint8_t *down,
                              int16_t *dx, int16_t *dy, int16_t *mag, int32_t width)
{
    if (width < 10) {
        rte_canny_sobel_row_c(up, mid, down, dx, dy, mag, width);
        return;
    }
    canny_sobel_px(up, mid, down, 0, 0, 1, dx, dy, mag);
    int32_t x = 1;
    /* columns x - 1 .. x + 8 are read: stay inside the row */
    for (; x + 9 <= width; x += 8) {
        const int16x8_t gx = vsubq_s16(column3(up + x + 1, mid + x + 1, down + x + 1),
                                       column3(up + x - 1, mid + x - 1, down + x - 1));
        const int16x8_t gy = vsubq_s16(smooth3(down + x), smooth3(up + x));
        vst1q_s16(dx + x, gx);
        vst1q_s16(dy + x, gy);
        vst1q_s16(mag + x, vaddq_s16(vabsq_s16(gx), vabsq_s16(gy)));
    }
    for (; x < width - 1; x++)
        canny_sobel_px(up, mid, down, x - 1, x, x + 1, dx, dy, mag);
    canny_sobel_px(up, mid, down, width - 2, width - 1, width - 1, dx, dy, mag);
}

void rte_canny_nms_row_neon(const int16_t *up, const int16_t *cur, const int16_t *down,
                            const int16_t *dx, const int16_t *dy, uint8_t *map, int32_t width,
                            int16_t low, int16_t high)
{
    const int16x8_t lowv = vdupq_n_s16(low), highv = vdupq_n_s16(high);
    const uint16x8_t one = vdupq_n_u16(1), two = vdupq_n_u16(2);
    int32_t x = 0;
    for (; x + 8 <= width; x += 8) {
        const int16x8_t m = vld1q_s16(cur + x);
        const int16x8_t gx = vld1q_s16(dx + x), gy = vld1q_s16(dy + x);
        const int16x8_t ax = vabsq_s16(gx), ay = vabsq_s16(gy);
        const int16x8_t t = vqdmulhq_n_s16(ax, RTE_CANNY_TG22_Q15);
        const uint16x8_t horizontal = vandq_u16(vcleq_s16(ay, t), vtstq_s16(ax, ax));
        const uint16x8_t vertical = vcgtq_s16(ay, vaddq_s16(vaddq_s16(ax, ax), t));
        const uint16x8_t same_sign = vcgezq_s16(veorq_s16(gx, gy));
        const int16x8_t diag_a = vbslq_s16(same_sign, vld1q_s16(up + x - 1), vld1q_s16(up + x + 1));
        const int16x8_t diag_b =
            vbslq_s16(same_sign, vld1q_s16(down + x + 1), vld1q_s16(down + x - 1));
        const uint16x8_t keep_h =
            vandq_u16(vcgtq_s16(m, vld1q_s16(cur + x - 1)), vcgeq_s16(m, vld1q_s16(cur + x + 1)));
        const uint16x8_t keep_v =
            vandq_u16(vcgtq_s16(m, vld1q_s16(up + x)), vcgeq_s16(m, vld1q_s16(down + x)));
        const uint16x8_t keep_d = vandq_u16(vcgtq_s16(m, diag_a), vcgtq_s16(m, diag_b));
        const uint16x8_t keep = vandq_u16(
            vbslq_u16(horizontal, keep_h, vbslq_u16(vertical, keep_v, keep_d)), vcgtq_s16(m, lowv));
        const uint16x8_t code = vbslq_u16(keep, vandq_u16(vcgtq_s16(m, highv), two), one);
        vst1_u8(map + x, vmovn_u16(code));
    }
    if (x < width)
        rte_canny_nms_row_c(up + x, cur + x, down + x, dx + x, dy + x, map + x, width - x, low,
                            high);
}

#endif
