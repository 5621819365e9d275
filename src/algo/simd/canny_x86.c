/* Canny's row kernels (aperture 3, L1) for AVX2 and AVX-512: the C
 * reference's loops (src/algo/canny_rows.h) in 16-bit lanes of 256-bit or
 * 512-bit registers (the sector test's multiply becomes vpmulhuw).
 * Compiler-vectorised, no intrinsics: built twice, -mavx2 and AVX-512
 * (rows.h), at -O3 whatever the build type (src/meson.build:
 * rtedge_simd_autovec). Safe because the loops are integer only, so
 * vectorising them only reorders exact operations and the bytes stay the C
 * reference's. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/canny_rows.h"

RTE_SIMD_APPLY(RTE_CANNY_ROWS_DEFINE)

#endif
