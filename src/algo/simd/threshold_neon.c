/* The fixed-level threshold row for aarch64 NEON (see rows.h; the C
 * reference is src/algo/threshold_rows.h). Intrinsics (<arm_neon.h>; NEON
 * is aarch64's baseline, no flags): one unsigned compare gives the
 * mask of pixels above t, then a select, an AND or a min, 16 pixels at a
 * time; the C reference finishes the row. */
#include "rows.h"

#ifdef RTE_SIMD_NEON
#include <arm_neon.h>

#include "rtedge/threshold.h"

void rte_threshold_row_neon(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                            uint8_t maxval)
{
    const uint8x16_t tv = vdupq_n_u8(t), mv = vdupq_n_u8(maxval);
    int32_t x = 0;
    for (; x + 16 <= n; x += 16) {
        const uint8x16_t v = vld1q_u8(s + x);
        const uint8x16_t above = vcgtq_u8(v, tv);
        uint8x16_t r;
        switch (type) {
        case RTE_THRESH_BINARY: r = vandq_u8(above, mv); break;
        case RTE_THRESH_BINARY_INV: r = vbicq_u8(mv, above); break;
        case RTE_THRESH_TRUNC: r = vminq_u8(v, tv); break;
        case RTE_THRESH_TOZERO: r = vandq_u8(v, above); break;
        default: r = vbicq_u8(v, above); break; /* RTE_THRESH_TOZERO_INV */
        }
        vst1q_u8(d + x, r);
    }
    if (x < n)
        rte_threshold_row_c(s + x, d + x, n - x, type, t, maxval);
}

#endif
