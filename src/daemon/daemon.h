/* The daemon's loop (loop.c): a source, the pacer, the lane and grasp paths
 * and the publisher, all sized at rted_daemon_open() from the
 * configuration; rted_daemon_step() then makes no heap call (the sources'
 * image-file codecs and a memq:// subscriber aside: see publish.h). */
#ifndef RTEDGED_DAEMON_H
#define RTEDGED_DAEMON_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "config.h"

typedef struct rted_daemon rted_daemon;

/* Counters since start (the status message carries them too). */
typedef struct rted_counters {
    uint64_t received; /* frames the source handed out */
    uint64_t processed;
    uint64_t dropped;    /* stale (pacer) plus the source's own drops */
    uint64_t bad_frames; /* unreadable frames the source skipped */
    uint64_t deadline_misses;
    uint64_t stages_skipped; /* grasp paths, images, overlays skipped to keep the deadline */
    uint64_t published;
    uint64_t publish_errors;
    uint64_t status_sent;
    uint64_t reloads;         /* configurations applied at run time (SIGHUP, params_t) */
    uint64_t refused;         /* run-time changes refused (fixed keys, bad values) */
    uint64_t rewinds;         /* a looping recording started again */
    uint64_t params_received; /* params_t messages handled (applied or refused) */
    uint64_t rate_limited;    /* params_t messages dropped over params.max_per_second */
    uint64_t path_errors;     /* frames a path could not process (e.g. a ROI that misses them) */
    uint64_t debug_frames;    /* debug overlays published */
    uint64_t saves;           /* params_t save requests answered (ACTION_SAVE) */
    uint64_t states_sent;     /* param_state_t messages published */
} rted_counters;

/* rtedged's exit codes (docs/daemon.md). */
enum {
    RTED_EXIT_OK = 0,     /* the recording ended, max_frames, or SIGINT/SIGTERM */
    RTED_EXIT_FAILED = 1, /* cannot start (source, transport, memory) or the source failed */
    RTED_EXIT_CONFIG = 2, /* a bad configuration or command line */
    RTED_EXIT_NO_FRAMES =
        3, /* a recording (or a whole pass of a looping one) had no readable frame */
};

typedef enum rted_step {
    RTED_STEP_FRAME = 0, /* a frame was processed */
    RTED_STEP_IDLE,      /* nothing processed (waited, dropped, bad frame, timeout) */
    RTED_STEP_END,       /* the recording ended (and does not loop) or max_frames reached */
    RTED_STEP_FAILED,    /* the source failed */
    RTED_STEP_EMPTY,     /* a recording, or a pass of a looping one, had no readable frame */
} rted_step;

/* config_path: re-read on SIGHUP (NULL: reload refused). */
bool rted_daemon_open(rted_daemon **out, const rted_config *cfg, const char *config_path, char *msg,
                      size_t msg_size);
void rted_daemon_close(rted_daemon *d);
/* One frame: read, pace, analyse, publish; status when due. */
rted_step rted_daemon_step(rted_daemon *d);
/* Steps until *stop, the end or a failure; *reload re-reads the file.
 * Publishes a final status. Returns the process exit code. */
int rted_daemon_run(rted_daemon *d, volatile sig_atomic_t *stop, volatile sig_atomic_t *reload);
/* Applies a new configuration's runtime keys (false and *msg: a fixed key
 * changed or a value is invalid; counted in refused). */
bool rted_daemon_apply(rted_daemon *d, const rted_config *next, char *msg, size_t msg_size);
/* Re-reads the configuration file (and the command-line overrides given to
 * rted_daemon_set_overrides) and applies it. */
bool rted_daemon_reload(rted_daemon *d, char *msg, size_t msg_size);
void rted_daemon_set_overrides(rted_daemon *d, char *const *sets, int n_sets);
void rted_daemon_publish_status(rted_daemon *d);
void rted_daemon_get_counters(const rted_daemon *d, rted_counters *c);
/* The configuration in force. */
const rted_config *rted_daemon_config(const rted_daemon *d);
/* One params_t message as it arrived (params.max_per_second is the
 * caller's): decoded without allocating, checked, applied whole or refused
 * with the reason on stderr; counted in params_received and reloads or
 * refused. What the params channel's callback runs; tests and fuzzers call
 * it directly. */
void rted_daemon_handle_params(rted_daemon *d, const void *data, size_t size);
/* The publisher's lcm_t (memq://, udpm://), for in-process subscribers. */
lcm_t *rted_daemon_lcm(rted_daemon *d);
/* Capture-to-publish latency over the whole run, microseconds: p50 and p99
 * (within 1.6%: a log-linear histogram) and the max (exact); 0 before the
 * first frame. */
void rted_daemon_latency(const rted_daemon *d, int32_t *p50, int32_t *p99, int32_t *max);

#endif
