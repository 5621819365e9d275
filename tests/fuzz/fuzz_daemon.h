/* The daemon the params_t targets talk to: opened once, on a looping
 * recording of a few synthetic frames in a memory file, memq://, params
 * enabled; put back to its base configuration before each input, so that
 * an input's outcome does not depend on the ones before it. */
#ifndef RTEDGE_FUZZ_DAEMON_H
#define RTEDGE_FUZZ_DAEMON_H

#include "fuzz.h"

#include "config.h"
#include "daemon.h"

#define FUZZ_W 96
#define FUZZ_H 72

static rted_config fuzz_base;

static inline rted_daemon *fuzz_daemon(void)
{
    static rted_daemon *d;
    if (d)
        return d;
    /* Four frames: a bright box moving on a dark table, a bright band below. */
    static uint8_t y4m[64 + 4 * (6 + FUZZ_W * FUZZ_H)];
    size_t n = (size_t)snprintf((char *)y4m, 64, "YUV4MPEG2 W%d H%d F30:1 Cmono\n", FUZZ_W, FUZZ_H);
    for (int k = 0; k < 4; k++) {
        memcpy(y4m + n, "FRAME\n", 6);
        n += 6;
        for (int y = 0; y < FUZZ_H; y++)
            for (int x = 0; x < FUZZ_W; x++)
                y4m[n++] = (x >= 20 + k && x < 50 + k && y >= 10 && y < 30) ||
                                   (y > 50 && (x - y / 2) % 40 < 4)
                               ? 220
                               : 40;
    }
    static char path[64];
    fuzz_file(y4m, n, path, sizeof path); /* kept open for the process */
    rted_config_defaults(&fuzz_base);
    snprintf(fuzz_base.source_path, sizeof fuzz_base.source_path, "%s", path);
    snprintf(fuzz_base.lcm_url, sizeof fuzz_base.lcm_url, "memq://");
    fuzz_base.pace = RTED_PACE_FAST;
    fuzz_base.loop = true;
    fuzz_base.params_enabled = true;
    fuzz_base.status_period_ms = 60000;
    fuzz_base.deadline_ms = 1000;
    char msg[RTED_MSG];
    if (!rted_daemon_open(&d, &fuzz_base, NULL, msg, sizeof msg)) {
        fprintf(stderr, "fuzz: cannot open the daemon: %s\n", msg);
        abort();
    }
    return d;
}

/* The daemon at its base configuration. */
static inline rted_daemon *fuzz_daemon_reset(void)
{
    rted_daemon *d = fuzz_daemon();
    char msg[RTED_MSG];
    FUZZ_ASSERT(rted_daemon_apply(d, &fuzz_base, msg, sizeof msg));
    return d;
}

/* After a request: exactly one outcome counted, the configuration in force
 * valid for the frames, and a frame still analysed with it. */
static inline void fuzz_daemon_check(rted_daemon *d, const rted_counters *before)
{
    rted_counters after;
    rted_daemon_get_counters(d, &after);
    FUZZ_ASSERT(after.params_received == before->params_received + 1);
    FUZZ_ASSERT(after.reloads + after.refused + after.saves ==
                before->reloads + before->refused + before->saves + 1);
    const rted_config *c = rted_daemon_config(d);
    char msg[RTED_MSG];
    FUZZ_ASSERT(rted_config_validate(c, msg, sizeof msg));
    FUZZ_ASSERT(rted_config_check_frame(c, FUZZ_W, FUZZ_H, msg, sizeof msg));
    FUZZ_ASSERT(!rted_config_fixed_change(&fuzz_base, c, msg, sizeof msg));
    rted_step st = rted_daemon_step(d);
    if (st == RTED_STEP_IDLE) /* a rewind */
        st = rted_daemon_step(d);
    FUZZ_ASSERT(st == RTED_STEP_FRAME);
    rted_daemon_get_counters(d, &after);
    FUZZ_ASSERT(after.path_errors == 0);
}

#endif
