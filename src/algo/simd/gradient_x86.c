/* The gradient family's row loops for AVX2 and AVX-512: the C reference's
 * loops (src/algo/gradient_loops.h) in 16-bit lanes of 256-bit or 512-bit
 * registers; compiler-vectorised (rows.h). */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/gradient_loops.h"

RTE_SIMD_APPLY(RTE_GRAD_ROWS_DEFINE)

#endif
