/* Canny's row kernels (aperture 3, L1) for AVX2 and AVX-512: the C
 * reference's loops (src/algo/canny_rows.h) in 16-bit lanes of 256-bit or
 * 512-bit registers (the sector test's multiply becomes vpmulhuw);
 * compiler-vectorised (rows.h). */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/canny_rows.h"

RTE_SIMD_APPLY(RTE_CANNY_ROWS_DEFINE)

#endif
