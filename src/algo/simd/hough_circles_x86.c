/* The votes of a Hough circles edge pixel for AVX2 and AVX-512: the cells of
 * a vector of steps at a time (compiler-vectorised, rows.h), then the
 * increments, scalar since two steps can hit one cell. The C reference is
 * the plain loop rte_circle_votes_c in src/algo/hough_circles.c, not this
 * one: GCC 12 at -O3 with SSE2 or SSE4.1 vectors (not AVX2) computes the
 * upper four lanes of this loop wrong. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86

void RTE_SIMD_NAME(rte_circle_votes)(int32_t *restrict acc, uint32_t mask, uint32_t astep,
                                     uint32_t ux, uint32_t uy, uint32_t sx, uint32_t sy, int32_t n)
{
    /* The cells of a vector of steps at a time (the last group may run past n: its
     * extra cells are not counted), then the increments. */
    enum { LANES = RTE_SIMD_BYTES / 4, CHUNK = 64 };
    uint32_t idx[CHUNK], px[LANES], py[LANES];
    for (int k = 0; k < LANES; k++) {
        px[k] = ux + (uint32_t)k * sx;
        py[k] = uy + (uint32_t)k * sy;
    }
    for (int32_t done = 0; done <= n; done += CHUNK) {
        const int32_t m = n + 1 - done < CHUNK ? n + 1 - done : CHUNK;
        const int32_t groups = (m + LANES - 1) / LANES;
        for (int32_t gi = 0; gi < groups; gi++)
            for (int k = 0; k < LANES; k++) {
                idx[gi * LANES + k] = ((py[k] >> 10) & mask) * astep + (px[k] >> 10);
                px[k] += LANES * sx;
                py[k] += LANES * sy;
            }
        int32_t j = 0;
        for (; j + LANES <= m; j += LANES)
            for (int k = 0; k < LANES; k++)
                acc[idx[j + k]]++;
        for (; j < m; j++)
            acc[idx[j]]++;
    }
}

#endif
