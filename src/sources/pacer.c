/* Pacing: see rtedge/pacer.h. */
#include "rtedge/pacer.h"

#include <string.h>

rte_status rte_pacer_init(rte_pacer *pacer, const rte_pacer_config *config)
{
    if (!pacer || !config)
        return RTE_ERR_ARGUMENT;
    rte_pacer_config c = *config;
    if (c.speed_permille == 0)
        c.speed_permille = 1000;
    int ok = (c.mode == RTE_PACE_RECORDED && c.speed_permille > 0 &&
              c.speed_permille <= 1000000) ||
             (c.mode == RTE_PACE_FPS && c.fps_num > 0 && c.fps_den > 0 &&
              c.fps_num <= 1000000 && c.fps_den <= 1000000) ||
             c.mode == RTE_PACE_FAST;
    if (!ok)
        return RTE_ERR_ARGUMENT;
    memset(pacer, 0, sizeof *pacer);
    pacer->config = c;
    return RTE_OK;
}

void rte_pacer_restart(rte_pacer *pacer)
{
    pacer->started = 0;
    pacer->frames = 0;
}

/* Offset of frame `frames` from the origin at fps_num/fps_den. */
static int64_t fps_offset_ns(uint64_t frames, int32_t num, int32_t den)
{
    uint64_t q = frames * (uint64_t)den;
    return (int64_t)(q / (uint64_t)num * 1000000000u + q % (uint64_t)num * 1000000000u / (uint64_t)num);
}

rte_pace_action rte_pacer_decide(rte_pacer *pacer, int64_t recorded_ns, int64_t now_ns,
                                 int64_t *wait_ns)
{
    const rte_pacer_config *c = &pacer->config;
    *wait_ns = 0;
    if (c->mode == RTE_PACE_FAST) {
        pacer->frames++;
        return RTE_PACE_PROCESS;
    }
    if (!pacer->started) {
        pacer->started = 1;
        pacer->origin_ns = now_ns;
        pacer->first_recorded_ns = recorded_ns;
    }
    int64_t offset;
    if (c->mode == RTE_PACE_FPS) {
        offset = fps_offset_ns(pacer->frames, c->fps_num, c->fps_den);
    } else {
        /* A recording that goes back in time (a new log appended) is due
         * at once, not in the past. */
        int64_t span = recorded_ns - pacer->first_recorded_ns;
        offset = span <= 0 ? 0 : span / c->speed_permille * 1000 +
                                     span % c->speed_permille * 1000 / c->speed_permille;
    }
    int64_t due = pacer->origin_ns + offset;
    if (due > now_ns) {
        *wait_ns = due - now_ns;
        return RTE_PACE_WAIT;
    }
    pacer->frames++;
    if (c->max_late_ns >= 0 && now_ns - due > c->max_late_ns) {
        pacer->dropped++;
        return RTE_PACE_DROP;
    }
    return RTE_PACE_PROCESS;
}
