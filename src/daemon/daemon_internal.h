/* What the daemon's files share (internal to src/daemon): the daemon's
 * state, and the functions one file provides to the others.
 *   open.c         rted_daemon_open(): sizing and opening everything, close
 *   source_open.c  which source a path names, and opening it
 *   record.c       source.record: the delivered frames into an LCM log
 *   messages.c     filling and publishing the lane, grasp and image messages
 *   loop.c         the per-frame step and the run loop
 *   reconfigure.c  run-time configuration: SIGHUP, the params_t channel
 *   param_state.c  the param_state_t message: runtime keys, last outcome
 *   debug_stream.c debug.enabled: the overlay stream (JPEG image_t)
 *   realtime.c     [realtime]: memory lock, affinity, SCHED_FIFO, the grasp thread
 *   status.c       the latency window and the status message
 *   notify.c       systemd's notifications (READY, STATUS, WATCHDOG, ...) */
#ifndef RTEDGED_DAEMON_INTERNAL_H
#define RTEDGED_DAEMON_INTERNAL_H

#include <pthread.h>
#include <semaphore.h>
#include <stdint.h>

#include "daemon.h"
#include "log.h"
#include "notify.h"
#include "params.h"
#include "rtedge/arena.h"
#include "rtedge/grasp.h"
#include "rtedge/lane.h"
#include "sources/pacer.h"
#include "publish/publish.h"
#include "rtedge/source.h"
#include "io/jpeg_encoder.h"

/* Latencies kept per status window (the newest ones when more frames came). */
#define RTED_RING 8192
/* The whole run's latencies (--bench): a log-linear histogram of
 * microseconds, exact below RTED_HIST_SUB, then RTED_HIST_SUB buckets per
 * power of two (each under 1/64 = 1.6% wide) up to 2^31. */
#define RTED_HIST_SUB 64
#define RTED_HIST_BUCKETS (RTED_HIST_SUB * 26)
#define RTED_MAX_SETS 64
/* params_t messages handled per step at most (the rest wait in the socket,
 * where the kernel drops what does not fit). */
#define RTED_PARAMS_PER_STEP 16
/* Runtime keys in param_state_t at most (checked at open). */
#define RTED_STATE_MAX_KEYS 64
/* Stages timed in status_t: the lane path's, the grasp path's five, the
 * debug overlay. */
#define RTED_GRASP_STAGE0 RTE_LANE_STAGES
#define RTED_GRASP_STAGES 5
#define RTED_DEBUG_STAGE (RTED_GRASP_STAGE0 + RTED_GRASP_STAGES)
#define RTED_STAGES (RTED_DEBUG_STAGE + 1)

/* One frame's grey image and grasp path (realtime.c): run in line, or on the
 * grasp thread between rted_grasp_job_post() and rted_grasp_job_wait(). */
typedef struct rted_grasp_job {
    const rte_source_frame *frame;
    bool need_gray; /* the grey image: the grasp path, publish.images or the overlay */
    rte_image_u8 gray;
    bool skipped; /* the budget left was short of deadline.grasp_min_budget_ms */
    bool ran;     /* status and result are the grasp path's */
    rte_status status;
    rte_grasp_result result;
} rted_grasp_job;

struct rted_daemon {
    rted_config cfg;
    const char *config_path;
    char *const *sets;
    int n_sets;
    uint64_t config_hash;
    int64_t deadline_ns, grasp_min_ns;

    rte_source source;
    bool recorded;
    char source_id[RTED_TEXT + 16];
    int32_t width, height; /* the source's maxima */
    rte_pacer pacer;
    uint64_t passes;         /* rewinds of a looping recording so far */
    uint64_t pass_frames;    /* frames the source delivered in this pass */
    int64_t capture_wall_us; /* the frame in hand's capture time on the wall clock */

    rte_lane_context *lane;
    rte_lane_config lane_base; /* defaults for the frame size, before the file's keys */
    rte_grasp_ctx *grasp;
    rte_publisher *pub;

    /* The params_t channel: at most params_max_per_second messages in each
     * second from params_window_ns, decoded into params_req. */
    lcm_subscription_t *params_sub;
    int64_t params_window_ns;
    int32_t params_in_window;
    rted_params_request params_req;
    /* param_state_t: one row per runtime key over the key table's strings,
     * the last request's outcome, the next periodic publication; a saved
     * configuration's text (RTED_CONFIG_TEXT_MAX bytes). */
    rtedge_param_state_t state_msg;
    rtedge_param_info_t state_keys[RTED_STATE_MAX_KEYS];
    const rted_key *state_key_of[RTED_STATE_MAX_KEYS];
    char state_names[RTED_STATE_MAX_KEYS][RTED_PARAM_NAME_MAX];
    char state_reason[RTED_MSG];
    int32_t state_max_bytes;
    int64_t state_due_ns;
    char *config_text;

    /* debug.enabled: a canvas for the largest frame, the JPEG encoder, the
     * message, the layers and quality in force, when the next overlay is
     * due (capture time). */
    rte_jpeg_encoder *jpeg;
    uint8_t *debug_canvas;
    rtedge_image_t debug_msg;
    uint32_t debug_layers;
    int32_t debug_quality;
    int64_t debug_next_ns;

    /* source.record: every delivered frame, packed, as image_t. */
    rte_publisher *rec;
    uint8_t *rec_buf;
    rtedge_image_t rec_msg;

    void *memory;
    rte_arena arena;
    rte_image_u8 gray;
    rte_image_u8 cb, cr; /* the frame's chroma at half size, for grasp.chroma */
    rtedge_segment_t *segments;
    rtedge_grasp_object_t *objects;
    rtedge_point_t roi[RTE_LANE_MAX_ROI_VERTICES];
    rtedge_point_t grasp_roi[RTE_GRASP_MAX_ROI_VERTICES]; /* the workspace, in pixels */
    rtedge_lane_detection_t lane_msg;
    rtedge_grasp_detection_t grasp_msg;
    rtedge_image_t image_msg;
    rtedge_status_t status_msg;

    /* Per stage over the status window: time summed, largest, frames. */
    int64_t stage_sum_ns[RTED_STAGES], stage_max_ns[RTED_STAGES];
    uint32_t stage_frames[RTED_STAGES];
    int32_t stage_mean_us[RTED_STAGES], stage_max_us[RTED_STAGES];
    char *stage_names[RTED_STAGES]; /* status_t's: "lane.gray", ..., "debug" */

    rted_counters n;
    int32_t ring[RTED_RING], sorted[RTED_RING];
    uint32_t ring_n; /* latencies in the window (may exceed RTED_RING) */
    int32_t window_max;
    uint32_t run_hist[RTED_HIST_BUCKETS];
    uint64_t run_n;
    int32_t run_max;
    uint64_t window_processed;
    int64_t window_start_ns;
    rte_source_state state;
    rte_source_state reported_state; /* the source's state in the last status */
    volatile sig_atomic_t *stop;     /* rted_daemon_run's flag: ends a wait for a frame's time */
    rted_notify notify;              /* NOTIFY_SOCKET: READY=1 at the first frame, watchdog */

    /* stderr lines that could repeat without end */
    rted_log_limit log_frames, log_params;
    rte_status path_said[2]; /* the lane's and grasp path's last failure said */

    /* realtime.cpu_dma_latency_us: the open PM QoS request */
    bool wake_latency_held;
    int wake_latency_fd;

    /* realtime.threads = 2 (and both paths): the grasp thread and its job */
    bool threaded;
    pthread_t job_thread;
    sem_t job_go, job_done;
    bool job_quit;
    rted_grasp_job job;
};

/* source_open.c */
/* Opens the source that d->cfg names (source.kind, or guessed from
 * source.path); sets d->recorded, d->source_id and the maxima d->width and
 * d->height. false and *msg otherwise. */
bool rted_open_source(rted_daemon *d, char *msg, size_t msg_size);

/* record.c */
/* The recording's publisher and a buffer for the source's largest frame. */
bool rted_open_recording(rted_daemon *d, char *msg, size_t msg_size);
/* Copies f, packed, into the recording (a failure counts a publish error). */
void rted_record_frame(rted_daemon *d, const rte_source_frame *f);

/* debug_stream.c */
/* The canvas and the encoder when debug.enabled (false and *msg when
 * there is no memory for them). */
bool rted_debug_open(rted_daemon *d, char *msg, size_t msg_size);
void rted_debug_close(rted_daemon *d);
/* The largest JPEG the stream publishes (0 when it is off). */
int32_t rted_debug_max_bytes(const rted_daemon *d);
/* debug.layers and debug.quality from d->cfg (no allocation). */
void rted_debug_apply(rted_daemon *d);
/* true when the stream is on and an overlay is due for a frame captured at t_ns. */
bool rted_debug_due(const rted_daemon *d, int64_t t_ns);
/* The overlay of this frame's results (either may be NULL) over gray. */
void rted_debug_publish(rted_daemon *d, const rte_source_frame *f, const rte_image_u8 *gray,
                        const rte_lane_result *lane, const rte_grasp_result *grasp);

/* messages.c */
/* Points the messages at d's source id, ROI and arrays. */
void rted_messages_init(rted_daemon *d);
/* A message sent, or one that could not be (counted, not said: status_t
 * carries publish_errors). */
void rted_count_publish(rted_daemon *d, rte_status st);
void rted_publish_lane(rted_daemon *d, const rte_source_frame *f, const rte_lane_result *r);
void rted_publish_grasp(rted_daemon *d, const rte_source_frame *f, const rte_grasp_result *r);
/* g: the frame's grey image (copied into d->gray when not packed). */
void rted_publish_image(rted_daemon *d, const rte_source_frame *f, const rte_image_u8 *g);

/* reconfigure.c */
/* The lane parameters: the frame size's defaults with c's keys over them
 * (false: c's ROI does not parse). */
bool rted_lane_params(const rted_daemon *d, const rted_config *c, rte_lane_params *p);
void rted_grasp_params(const rted_config *c, rte_grasp_params *p);
/* Canny low at most high, either of them the lane default (-1); false and
 * *msg otherwise. */
bool rted_lane_thresholds_ok(const rted_config *c, const rte_lane_params *p, char *msg,
                             size_t msg_size);
/* What follows from d->cfg: deadline, hash, the messages' ROI. */
void rted_derive(rted_daemon *d);
/* Subscribes to params.channel when params.enabled (a warning when the
 * transport has no LCM). */
void rted_params_open(rted_daemon *d);
void rted_params_close(rted_daemon *d);
/* Handles the params_t messages waiting, within the rate and per-step limits. */
void rted_params_poll(rted_daemon *d);

/* param_state.c */
/* Builds the message over the runtime keys, sizes its largest encoding
 * (d->state_max_bytes) and allocates the save buffer. */
bool rted_param_state_init(rted_daemon *d, char *msg, size_t msg_size);
void rted_param_state_close(rted_daemon *d);
/* The values in force, the hash and what is settable, from d->cfg. */
void rted_param_state_refresh(rted_daemon *d);
/* Publishes now and schedules the next after params.state_period_ms. */
void rted_param_state_publish(rted_daemon *d);
/* A request's outcome (RTEDGE_PARAM_STATE_T_OUTCOME_*) and reason,
 * published at once; saved: with d->config_text as saved_config. */
void rted_param_state_outcome(rted_daemon *d, int64_t request_id, int8_t outcome,
                              const char *reason, bool saved);

/* realtime.c */
/* [realtime]: mlockall, the CPUs' wake-up latency, the main thread's CPU
 * and SCHED_FIFO priority (warnings where not permitted), then the grasp
 * thread when realtime.threads = 2 and both paths run (false and *msg
 * when it cannot be made). */
bool rted_realtime_start(rted_daemon *d, char *msg, size_t msg_size);
/* Joins the grasp thread (between frames) and drops the latency request. */
void rted_realtime_stop(rted_daemon *d);
/* The job's grey image, then the grasp path when d has one and the budget
 * holds it; j->frame and j->need_gray set. */
void rted_grasp_job_run(rted_daemon *d, rted_grasp_job *j);
/* d->job to the grasp thread, and back. */
void rted_grasp_job_post(rted_daemon *d);
void rted_grasp_job_wait(rted_daemon *d);

/* status.c */
void rted_record_latency(rted_daemon *d, int64_t lat_ns);
/* One frame's time in stage (0 .. RTED_STAGES - 1). */
void rted_record_stage(rted_daemon *d, int stage, int64_t ns);

#endif
