/* BGR/RGB to grey rows for aarch64 NEON (see rows.h; the C reference is in
 * src/algo/color.c). Intrinsics (<arm_neon.h>; NEON is aarch64's baseline,
 * no flags). vld3q deinterleaves 16 pixels; the weighted sum is
 * formed in 32 bits (the weights do not fit in 8) and vrshrn adds 2^14 and
 * shifts by 15 in one step: the same sum as the C reference. */
#include "rows.h"

#ifdef RTE_SIMD_NEON
#include <arm_neon.h>

static inline uint16x4_t gray4_neon(uint16x4_t c0, uint16x4_t c1, uint16x4_t c2, uint16_t w0,
                                    uint16_t w2)
{
    uint32x4_t sum = vmull_n_u16(c0, w0);
    sum = vmlal_n_u16(sum, c1, RTE_GRAY_G);
    sum = vmlal_n_u16(sum, c2, w2);
    return vrshrn_n_u32(sum, RTE_GRAY_SHIFT);
}

static inline uint8x8_t gray8_neon(uint8x8_t c0, uint8x8_t c1, uint8x8_t c2, uint16_t w0,
                                   uint16_t w2)
{
    uint16x8_t a = vmovl_u8(c0), b = vmovl_u8(c1), c = vmovl_u8(c2);
    uint16x4_t lo = gray4_neon(vget_low_u16(a), vget_low_u16(b), vget_low_u16(c), w0, w2);
    uint16x4_t hi = gray4_neon(vget_high_u16(a), vget_high_u16(b), vget_high_u16(c), w0, w2);
    return vmovn_u16(vcombine_u16(lo, hi));
}

static inline void c3_to_gray_neon(const uint8_t *src, uint8_t *dst, int32_t width, uint16_t w0,
                                   uint16_t w2, rte_row_c3_to_gray_fn tail)
{
    int32_t x = 0;
    for (; x + 16 <= width; x += 16) {
        uint8x16x3_t px = vld3q_u8(src + 3 * x);
        uint8x8_t lo = gray8_neon(vget_low_u8(px.val[0]), vget_low_u8(px.val[1]),
                                  vget_low_u8(px.val[2]), w0, w2);
        uint8x8_t hi = gray8_neon(vget_high_u8(px.val[0]), vget_high_u8(px.val[1]),
                                  vget_high_u8(px.val[2]), w0, w2);
        vst1q_u8(dst + x, vcombine_u8(lo, hi));
    }
    if (x < width)
        tail(src + 3 * x, dst + x, width - x);
}

void rte_row_bgr_to_gray_neon(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_to_gray_neon(src, dst, width, RTE_GRAY_B, RTE_GRAY_R, rte_row_bgr_to_gray_c);
}

void rte_row_rgb_to_gray_neon(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_to_gray_neon(src, dst, width, RTE_GRAY_R, RTE_GRAY_B, rte_row_rgb_to_gray_c);
}

#endif
