/* The gradient family's row loops built for AVX2: the same C loops as the
 * reference (src/algo/gradient_loops.h), vectorised by the compiler in
 * 16-bit lanes of 256-bit registers. Same integer operations, same bytes. */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "algo/gradient_loops.h"

RTE_GRAD_ROWS_DEFINE(avx2)

#endif
