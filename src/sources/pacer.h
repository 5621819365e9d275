/* Pacing recorded frames: when to process a frame and which stale frames to
 * drop. The sources do not pace (recorded_source.h); the daemon's loop asks
 * the pacer about each frame with the frame's recorded_ns and the current
 * time, and waits, processes or drops. Integer arithmetic, no clock of its
 * own (the caller passes the time: tests use a fake clock), no allocation.
 *
 * Modes:
 *   RTE_PACE_RECORDED  at the recording's own pace (recorded_ns), sped up or
 *                      slowed by speed_permille (1000: real time, 2000: twice
 *                      as fast);
 *   RTE_PACE_FPS       at a fixed rate, fps_num/fps_den frames a second;
 *   RTE_PACE_FAST      as fast as possible (never waits, never drops).
 * The first frame sets the origin: it is due at once, and frame k is due at
 * origin + (recorded_ns(k) - recorded_ns(first)) * 1000 / speed_permille
 * (RECORDED) or origin + k / fps (FPS, k counting frames processed or
 * dropped). A frame more than max_late_ns past its due time is dropped
 * (stale: processing it would only delay the ones after it); negative: never
 * drop. Looping (--loop) needs nothing here: a rewound recording's
 * recorded_ns keeps growing (rte_recorded_source_rewind).
 * RECORDED starts the pace again (the frame is due at once and becomes the
 * new origin) when a frame was recorded before the previous one (a log
 * with another appended) or more than max_pause_ns after it (a pause in the
 * recording, or a damaged timestamp that would otherwise be waited out). */
#ifndef RTEDGE_PACER_H
#define RTEDGE_PACER_H

#include <stdint.h>

#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rte_pace_mode {
    RTE_PACE_RECORDED = 0,
    RTE_PACE_FPS,
    RTE_PACE_FAST,
} rte_pace_mode;

typedef struct rte_pacer_config {
    rte_pace_mode mode;
    int32_t speed_permille;   /* RECORDED: 1..1000000 (0: 1000) */
    int32_t fps_num, fps_den; /* FPS: both > 0 */
    int64_t max_late_ns;      /* drop frames later than this; < 0: never */
    int64_t max_pause_ns;     /* RECORDED: longer pauses start the pace again; <= 0: none */
} rte_pacer_config;

typedef enum rte_pace_action {
    RTE_PACE_PROCESS = 0, /* process it now */
    RTE_PACE_WAIT,        /* not due yet: wait *wait_ns, then ask again */
    RTE_PACE_DROP,        /* stale: skip it */
} rte_pace_action;

typedef struct rte_pacer {
    rte_pacer_config config;
    int started;
    int64_t origin_ns; /* when the first frame was due */
    int64_t first_recorded_ns;
    int64_t last_recorded_ns; /* of the last frame processed or dropped */
    uint64_t frames;          /* processed or dropped since the origin */
    uint64_t dropped;
    uint64_t restarts; /* RECORDED: pace started again (back in time, a pause) */
} rte_pacer;

/* RTE_ERR_ARGUMENT for a bad mode, speed or frame rate. */
rte_status rte_pacer_init(rte_pacer *pacer, const rte_pacer_config *config);

/* What to do with a frame recorded at recorded_ns, at time now_ns (any
 * monotonic clock, the same in every call). WAIT leaves the pacer as it was
 * (ask again with the same frame); PROCESS and DROP count the frame. */
rte_pace_action rte_pacer_decide(rte_pacer *pacer, int64_t recorded_ns, int64_t now_ns,
                                 int64_t *wait_ns);

/* Forgets the origin: the next frame is due at once (after a pause, or when
 * the source restarts with unrelated timestamps). */
void rte_pacer_restart(rte_pacer *pacer);

#ifdef __cplusplus
}
#endif
#endif
