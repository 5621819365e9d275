/* BGR/RGB to grey rows for x86: SSSE3 and AVX2 (see rows.h; the C
 * reference is in src/algo/color.c). Intrinsics (<immintrin.h>), each
 * function built for its own instruction set by a target attribute, so the
 * SSSE3 rows hold no AVX (the file has no -m flags).
 *
 * Four pixels (12 bytes) at a time: pshufb spreads them into 16-bit lanes
 * as pairs (c0, c1) and (c2, 1), and pmaddwd with (w0, wG) and (w2, 16384)
 * gives w0*c0 + wG*c1 + w2*c2 + 16384 in 32 bits, then >> 15: the same sum
 * as the C reference, so the same bytes. All weights fit in int16. */
#include "rows.h"

#ifdef RTE_SIMD_X86
#include <immintrin.h>

#define TARGET_SSSE3 __attribute__((target("ssse3")))
#define TARGET_AVX2 __attribute__((target("avx2")))

/* The shuffles for 4 pixels starting at byte `o` of a 16-byte load
 * (o = 0, or 4 for the last group of a block, so no load passes its end). */
#define PAIR_SHUFFLE(o)                                                                        \
    (o) + 0, -1, (o) + 1, -1, (o) + 3, -1, (o) + 4, -1, (o) + 6, -1, (o) + 7, -1, (o) + 9, -1, \
        (o) + 10, -1
#define THIRD_SHUFFLE(o) \
    (o) + 2, -1, -1, -1, (o) + 5, -1, -1, -1, (o) + 8, -1, -1, -1, (o) + 11, -1, -1, -1

static inline int32_t pair_weights(int32_t lo, int32_t hi) { return lo | hi << 16; }

TARGET_SSSE3 static inline __m128i gray4_ssse3(__m128i v, __m128i sh_pair, __m128i sh_third,
                                               __m128i w01, __m128i w2r, __m128i one_hi)
{
    __m128i p01 = _mm_shuffle_epi8(v, sh_pair);
    __m128i p2 = _mm_or_si128(_mm_shuffle_epi8(v, sh_third), one_hi);
    __m128i sum = _mm_add_epi32(_mm_madd_epi16(p01, w01), _mm_madd_epi16(p2, w2r));
    return _mm_srli_epi32(sum, RTE_GRAY_SHIFT);
}

/* w0, w2: weights of the first and third byte of a pixel. */
TARGET_SSSE3 static inline void c3_to_gray_ssse3(const uint8_t *src, uint8_t *dst, int32_t width,
                                                 int32_t w0, int32_t w2, rte_row_c3_to_gray_fn tail)
{
    const __m128i sh_pair = _mm_setr_epi8(PAIR_SHUFFLE(0));
    const __m128i sh_third = _mm_setr_epi8(THIRD_SHUFFLE(0));
    const __m128i sh_pair4 = _mm_setr_epi8(PAIR_SHUFFLE(4));
    const __m128i sh_third4 = _mm_setr_epi8(THIRD_SHUFFLE(4));
    const __m128i w01 = _mm_set1_epi32(pair_weights(w0, RTE_GRAY_G));
    const __m128i w2r = _mm_set1_epi32(pair_weights(w2, 1 << (RTE_GRAY_SHIFT - 1)));
    const __m128i one_hi = _mm_set1_epi32(1 << 16);
    int32_t x = 0;
    for (; x + 16 <= width; x += 16) {
        const uint8_t *s = src + 3 * x;
        __m128i a =
            gray4_ssse3(_mm_loadu_si128((const __m128i *)s), sh_pair, sh_third, w01, w2r, one_hi);
        __m128i b = gray4_ssse3(_mm_loadu_si128((const __m128i *)(s + 12)), sh_pair, sh_third, w01,
                                w2r, one_hi);
        __m128i c = gray4_ssse3(_mm_loadu_si128((const __m128i *)(s + 24)), sh_pair, sh_third, w01,
                                w2r, one_hi);
        __m128i d = gray4_ssse3(_mm_loadu_si128((const __m128i *)(s + 32)), sh_pair4, sh_third4,
                                w01, w2r, one_hi);
        __m128i g = _mm_packus_epi16(_mm_packs_epi32(a, b), _mm_packs_epi32(c, d));
        _mm_storeu_si128((__m128i *)(dst + x), g);
    }
    if (x < width)
        tail(src + 3 * x, dst + x, width - x);
}

TARGET_SSSE3 void rte_row_bgr_to_gray_ssse3(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_to_gray_ssse3(src, dst, width, RTE_GRAY_B, RTE_GRAY_R, rte_row_bgr_to_gray_c);
}

TARGET_SSSE3 void rte_row_rgb_to_gray_ssse3(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_to_gray_ssse3(src, dst, width, RTE_GRAY_R, RTE_GRAY_B, rte_row_rgb_to_gray_c);
}

/* Two 16-byte loads into the two lanes of a ymm register (pshufb works
 * within each lane). */
TARGET_AVX2 static inline __m256i load_lanes(const uint8_t *lo, const uint8_t *hi)
{
    return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128((const __m128i *)lo)),
                                   _mm_loadu_si128((const __m128i *)hi), 1);
}

TARGET_AVX2 static inline __m256i gray8_avx2(__m256i v, __m256i sh_pair, __m256i sh_third,
                                             __m256i w01, __m256i w2r, __m256i one_hi)
{
    __m256i p01 = _mm256_shuffle_epi8(v, sh_pair);
    __m256i p2 = _mm256_or_si256(_mm256_shuffle_epi8(v, sh_third), one_hi);
    __m256i sum = _mm256_add_epi32(_mm256_madd_epi16(p01, w01), _mm256_madd_epi16(p2, w2r));
    return _mm256_srli_epi32(sum, RTE_GRAY_SHIFT);
}

/* 32 pixels (96 bytes) a step. Lanes hold groups (0,4), (1,5), (2,6),
 * (3,7) of 4 pixels, so the lane-wise packs put all 32 in order. */
TARGET_AVX2 static inline void c3_to_gray_avx2(const uint8_t *src, uint8_t *dst, int32_t width,
                                               int32_t w0, int32_t w2, rte_row_c3_to_gray_fn rest)
{
    const __m256i sh_pair = _mm256_setr_epi8(PAIR_SHUFFLE(0), PAIR_SHUFFLE(0));
    const __m256i sh_third = _mm256_setr_epi8(THIRD_SHUFFLE(0), THIRD_SHUFFLE(0));
    const __m256i sh_pair_last = _mm256_setr_epi8(PAIR_SHUFFLE(0), PAIR_SHUFFLE(4));
    const __m256i sh_third_last = _mm256_setr_epi8(THIRD_SHUFFLE(0), THIRD_SHUFFLE(4));
    const __m256i w01 = _mm256_set1_epi32(pair_weights(w0, RTE_GRAY_G));
    const __m256i w2r = _mm256_set1_epi32(pair_weights(w2, 1 << (RTE_GRAY_SHIFT - 1)));
    const __m256i one_hi = _mm256_set1_epi32(1 << 16);
    int32_t x = 0;
    for (; x + 32 <= width; x += 32) {
        const uint8_t *s = src + 3 * x;
        __m256i a = gray8_avx2(load_lanes(s, s + 48), sh_pair, sh_third, w01, w2r, one_hi);
        __m256i b = gray8_avx2(load_lanes(s + 12, s + 60), sh_pair, sh_third, w01, w2r, one_hi);
        __m256i c = gray8_avx2(load_lanes(s + 24, s + 72), sh_pair, sh_third, w01, w2r, one_hi);
        __m256i d =
            gray8_avx2(load_lanes(s + 36, s + 80), sh_pair_last, sh_third_last, w01, w2r, one_hi);
        __m256i g = _mm256_packus_epi16(_mm256_packs_epi32(a, b), _mm256_packs_epi32(c, d));
        _mm256_storeu_si256((__m256i *)(dst + x), g);
    }
    if (x < width)
        rest(src + 3 * x, dst + x, width - x);
}

TARGET_AVX2 void rte_row_bgr_to_gray_avx2(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_to_gray_avx2(src, dst, width, RTE_GRAY_B, RTE_GRAY_R, rte_row_bgr_to_gray_ssse3);
}

TARGET_AVX2 void rte_row_rgb_to_gray_avx2(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_to_gray_avx2(src, dst, width, RTE_GRAY_R, RTE_GRAY_B, rte_row_rgb_to_gray_ssse3);
}

#endif
