/* The lane path's colour cue row for AVX2 and AVX-512: the C reference's
 * loop (src/pipeline/lane_cue_rows.h) as byte compares and blends on 32 or
 * 64 pixels; compiler-vectorised (rows.h). */
#include <stdbool.h>
#include <stdint.h>

#include "rows.h"

#ifdef RTE_SIMD_X86
#include "pipeline/lane_cue_rows.h"

void RTE_SIMD_NAME(rte_lane_cue_row)(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst,
                                     int32_t width, const rte_lane_cue *cue, bool rgb)
{
    lane_cue_row(gray, bgr, dst, width, cue, rgb);
}

#endif
