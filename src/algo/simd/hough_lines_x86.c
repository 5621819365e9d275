/* The rho bins of many points at one angle for AVX2 (Hough lines; see
 * rows.h, the C reference is in src/algo/hough_lines.c). Intrinsics
 * (<immintrin.h>), built for AVX2 by a target attribute.
 *
 * A packed point y << 16 | x is a pair of 16-bit lanes (x, y), both below
 * 32768. With the trig values split as rho_cos = ch * 2^15 + cl (0 <= cl <
 * 2^15, ch in int16; likewise rho_sin), pmaddwd gives x * cl + y * sl and
 * x * ch + y * sh exactly in 32 bits, so
 *   x * rho_cos + y * rho_sin = ((x * ch + y * sh) << 15) + x * cl + y * sl
 * holds modulo 2^32, and exactly, since the sum lies in [0, 2^31): one
 * pmaddwd per term instead of two 32-bit multiplies, and the same bins as
 * the C reference. ch fits int16 because |rho_cos| < 2^30 (rows.h). */
#include "rows.h"

#ifdef RTE_SIMD_X86
#include <immintrin.h>

#include "algo/hough_rows.h"

#define TARGET_AVX2 __attribute__((target("avx2")))

/* (lo, hi) as the two 16-bit lanes of a 32-bit word. */
static inline int32_t lane_pair(int32_t lo, int32_t hi)
{
    return (int32_t)(((uint32_t)lo & 0xFFFFu) | ((uint32_t)hi & 0xFFFFu) << 16);
}

TARGET_AVX2 void rte_hough_point_bins_avx2(const uint32_t *pts, int32_t n, int32_t rho_cos,
                                           int32_t rho_sin, int32_t bias, int32_t shift,
                                           int32_t *idx)
{
    const int32_t limit = 1 << 30;
    int32_t i = 0;
    if (rho_cos > -limit && rho_cos < limit && rho_sin > -limit && rho_sin < limit) {
        const int32_t cl = rho_cos & 0x7FFF, sl = rho_sin & 0x7FFF;
        const int32_t ch = (rho_cos - cl) / 32768, sh = (rho_sin - sl) / 32768;
        const __m256i low = _mm256_set1_epi32(lane_pair(cl, sl));
        const __m256i high = _mm256_set1_epi32(lane_pair(ch, sh));
        const __m256i b = _mm256_set1_epi32(bias);
        const __m128i count = _mm_cvtsi32_si128(shift);
        for (; i + 8 <= n; i += 8) {
            const __m256i p = _mm256_loadu_si256((const __m256i *)(const void *)(pts + i));
            const __m256i sum = _mm256_add_epi32(_mm256_slli_epi32(_mm256_madd_epi16(p, high), 15),
                                                 _mm256_add_epi32(_mm256_madd_epi16(p, low), b));
            _mm256_storeu_si256((__m256i *)(void *)(idx + i), _mm256_sra_epi32(sum, count));
        }
    }
    hough_point_bins_row(pts + i, n - i, rho_cos, rho_sin, bias, shift, idx + i);
}

#endif
