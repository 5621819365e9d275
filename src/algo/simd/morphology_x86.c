/* Morphology's row kernels for AVX2 and AVX-512: the C reference's loops
 * (src/algo/morphology_rows.h) as vpminub/vpmaxub on 32 or 64 bytes;
 * compiler-vectorised (rows.h). */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/morphology_rows.h"

void RTE_SIMD_NAME(rte_morph_row_op2)(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n,
                                      bool is_max)
{
    row_op2(d, a, b, n, is_max);
}

void RTE_SIMD_NAME(rte_morph_reduce_rows)(uint8_t *d, const uint8_t *const *r, int32_t count,
                                          bool accumulate, int32_t n, bool is_max)
{
    reduce_rows(d, r, count, accumulate, n, is_max);
}

#endif
