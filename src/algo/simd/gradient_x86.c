/* The gradient family's row loops for AVX2: the C reference's loops
 * (src/algo/gradient_loops.h) in 16-bit lanes of 256-bit registers.
 * Compiler-vectorised, no intrinsics: built with -mavx2 -O3 whatever the
 * build type (src/meson.build: rtedge_simd_autovec). Safe because the loops
 * are integer only, so vectorising them only reorders exact operations and
 * the bytes stay the C reference's. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/gradient_loops.h"

RTE_GRAD_ROWS_DEFINE(avx2)

#endif
