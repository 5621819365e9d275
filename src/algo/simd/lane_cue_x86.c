/* The lane path's colour cue rows (from B,G,R and from Y with chroma) for
 * AVX2 and AVX-512: the C reference's loops (src/pipeline/lane_cue_rows.h)
 * as byte compares and blends on 32 or 64 pixels; compiler-vectorised
 * (rows.h). */
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

void RTE_SIMD_NAME(rte_lane_cue_chroma_row)(const uint8_t *const g[2], const uint8_t *cb,
                                            const uint8_t *cr, bool interleaved,
                                            uint8_t *const d[2], int32_t width, bool odd,
                                            const rte_lane_cue *cue)
{
    lane_cue_chroma_rows(g, cb, cr, interleaved, d, width, odd, cue);
}

#endif
