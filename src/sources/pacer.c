/* Pacing: see pacer.h. */
#include "sources/pacer.h"

#include <stdbool.h>
#include <string.h>

#include "recorded.h"

rte_status rte_pacer_init(rte_pacer *pacer, const rte_pacer_config *config)
{
    if (!pacer || !config)
        return RTE_ERR_ARGUMENT;
    rte_pacer_config c = *config;
    if (c.speed_permille == 0)
        c.speed_permille = 1000;
    int ok = (c.mode == RTE_PACE_RECORDED && c.speed_permille > 0 && c.speed_permille <= 1000000) ||
             (c.mode == RTE_PACE_FPS && c.fps_num > 0 && c.fps_den > 0 && c.fps_num <= 1000000 &&
              c.fps_den <= 1000000) ||
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

/* RECORDED: does this frame start the pace again (back in time, or after a
 * pause longer than max_pause_ns)? Differences in unsigned arithmetic: the
 * times may lie anywhere in int64. */
static bool starts_again(const rte_pacer *pacer, int64_t recorded_ns)
{
    const rte_pacer_config *c = &pacer->config;
    if (!pacer->frames)
        return false;
    if (recorded_ns < pacer->last_recorded_ns)
        return true;
    return c->max_pause_ns > 0 &&
           (uint64_t)recorded_ns - (uint64_t)pacer->last_recorded_ns > (uint64_t)c->max_pause_ns;
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
    if (c->mode == RTE_PACE_RECORDED && pacer->started && starts_again(pacer, recorded_ns)) {
        pacer->started = 0;
        pacer->restarts++;
    }
    if (!pacer->started) {
        pacer->started = 1;
        pacer->origin_ns = now_ns;
        pacer->first_recorded_ns = recorded_ns;
    }
    int64_t offset;
    if (c->mode == RTE_PACE_FPS) {
        offset = rte_recording_frame_ns(pacer->frames, c->fps_num, c->fps_den);
    } else {
        /* span * 1000 / speed, clamped far in the future rather than
         * overflowing (only a max_pause_ns of 0 lets spans grow that far). */
        uint64_t span = (uint64_t)recorded_ns - (uint64_t)pacer->first_recorded_ns;
        uint64_t speed = (uint64_t)c->speed_permille, q = span / speed;
        offset = q > (uint64_t)INT64_MAX / 4000 ? INT64_MAX / 4
                                                : (int64_t)(q * 1000 + span % speed * 1000 / speed);
    }
    int64_t due = pacer->origin_ns + offset;
    if (due > now_ns) {
        *wait_ns = due - now_ns;
        return RTE_PACE_WAIT;
    }
    pacer->frames++;
    pacer->last_recorded_ns = recorded_ns;
    if (c->max_late_ns >= 0 && now_ns - due > c->max_late_ns) {
        pacer->dropped++;
        return RTE_PACE_DROP;
    }
    return RTE_PACE_PROCESS;
}
