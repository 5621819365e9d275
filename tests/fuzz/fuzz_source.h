/* What the recording targets share: reading an open source as --loop does. */
#ifndef RTEDGE_FUZZ_SOURCE_H
#define RTEDGE_FUZZ_SOURCE_H

#include "fuzz.h"

#include "sources/recorded_source.h"

typedef struct fuzz_passes {
    uint64_t good[2], bad[2]; /* frames delivered and slots refused, per pass */
    uint32_t bad_kinds;       /* 1 << status of each refusal */
    bool capped[2];           /* the pass stopped at max_slots, not at the end */
} fuzz_passes;

/* Two passes of at most max_slots each with a rewind between them. Every
 * message must be NUL-terminated; every frame valid, within the source's
 * maxima and in its format, and each plane's last byte readable (ASan: the
 * pixels lie inside what was read). */
static inline void fuzz_read_passes(rte_source *src, int max_slots, fuzz_passes *out)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    memset(out, 0, sizeof *out);
    for (int pass = 0; pass < 2; pass++) {
        out->capped[pass] = true;
        for (int i = 0; i < max_slots; i++) {
            rte_source_frame f;
            rte_status st = rte_source_next(src, &f, 0, msg, sizeof msg);
            fuzz_check_message(msg, sizeof msg);
            if (st == RTE_ERR_END) {
                out->capped[pass] = false;
                break;
            }
            if (st != RTE_OK) {
                out->bad[pass]++;
                out->bad_kinds |= 1u << st;
                continue;
            }
            const rte_frame *fr = &f.frame;
            FUZZ_ASSERT(rte_frame_check(fr) == RTE_OK);
            FUZZ_ASSERT(fr->width <= src->max_width && fr->height <= src->max_height);
            FUZZ_ASSERT(fr->format == src->format);
            rte_frame packed;
            uint8_t probe;
            FUZZ_ASSERT(rte_frame_packed(&packed, fr->format, fr->width, 1, &probe, SIZE_MAX) ==
                        RTE_OK);
            for (int p = 0; p < RTE_FRAME_MAX_PLANES && fr->plane[p]; p++) {
                int32_t rows = p ? (fr->height + 1) / 2 : fr->height;
                volatile uint8_t last = fr->plane[p][(size_t)(rows - 1) * (size_t)fr->stride[p] +
                                                     (size_t)packed.stride[p] - 1];
                (void)last;
            }
            out->good[pass]++;
        }
        FUZZ_ASSERT(rte_recorded_source_rewind(src) == RTE_OK);
    }
}

#endif
