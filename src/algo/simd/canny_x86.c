/* Canny's row kernels (aperture 3, L1) built for AVX2: the same C loops as
 * the reference (src/algo/canny_rows.h), vectorised by the compiler in
 * 16-bit lanes of 256-bit registers (the sector test's multiply becomes
 * vpmulhuw). Same integer operations, same bytes. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "algo/canny_rows.h"

RTE_CANNY_ROWS_DEFINE(avx2)

#endif
