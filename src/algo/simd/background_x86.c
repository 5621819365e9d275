/* The table estimate's and its threshold's rows for AVX2: the C
 * reference's loops (src/algo/background_rows.h) on 32 bytes or 8 values
 * at a time. Compiler-vectorised, no intrinsics: built with -mavx2 -O3
 * whatever the build type (src/meson.build: rtedge_simd_autovec). */
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "algo/background_rows.h"

RTE_BACKGROUND_ROWS_DEFINE(avx2)

#endif
