/* The table estimate's and its threshold's rows for AVX2 and AVX-512: the C
 * reference's loops (src/algo/background_rows.h) on 32 or 64 bytes (8 or 16
 * values) at a time; compiler-vectorised (rows.h). */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/background_rows.h"

RTE_SIMD_APPLY(RTE_BACKGROUND_ROWS_DEFINE)

#endif
