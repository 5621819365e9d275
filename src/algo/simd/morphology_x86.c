/* Morphology's row kernels built for AVX2: the same C loops as the
 * reference (src/algo/morphology_rows.h), vectorised by the compiler as
 * pminub/pmaxub on 32 bytes. Same byte operations, same bytes. */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "algo/morphology_rows.h"

void rte_morph_row_op2_avx2(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n,
                            bool is_max)
{
    row_op2(d, a, b, n, is_max);
}

void rte_morph_reduce_rows_avx2(uint8_t *d, const uint8_t *const *r, int32_t count,
                                bool accumulate, int32_t n, bool is_max)
{
    reduce_rows(d, r, count, accumulate, n, is_max);
}

#endif
