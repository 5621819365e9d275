/* The lane path's colour cue row built for AVX2: the same C loop as the
 * reference (src/pipeline/lane_cue_rows.h). Same byte operations, same
 * bytes. */
#include <stdbool.h>
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#pragma GCC target("avx2")

#include "pipeline/lane_cue_rows.h"

void rte_lane_cue_row_avx2(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst, int32_t width,
                           const rte_lane_cue *cue, bool rgb)
{
    lane_cue_row(gray, bgr, dst, width, cue, rgb);
}

#endif
