/* rtedged's loop: source -> pacer -> lane path -> grasp path -> LCM.
 *
 * A step reads one frame, waits for its time (the pacer), runs the paths
 * (with realtime.threads = 2, the grasp path on the grasp thread beside the
 * lane path: realtime.c) and publishes from this thread; a frame makes no
 * heap call (everything was sized by
 * rted_daemon_open(), open.c). Latency is capture -> publish on
 * CLOCK_MONOTONIC; a frame whose budget runs short skips the grasp path
 * (counted). The loop pings systemd's watchdog (notify.h): a loop that
 * stalls stops the pings. */
#include <time.h>

#include "daemon_internal.h"
#include "sources/recorded_source.h"
#include "core/clock.h"

/* A path (0 lane, 1 grasp) that could not process a frame: counted, and
 * said once for each new reason (a failure that persists, such as a ROI
 * that misses smaller frames of an image directory, is not repeated). */
static void path_error(rted_daemon *d, int path, const rte_source_frame *f, rte_status st)
{
    if (st == RTE_OK) {
        d->path_said[path] = RTE_OK;
        return;
    }
    d->n.path_errors++;
    if (d->path_said[path] == st)
        return;
    d->path_said[path] = st;
    rted_log("%s path: frame %llu (%dx%d) not processed: %s (said once; status_t counts "
             "path_errors)",
             path ? "grasp" : "lane", (unsigned long long)f->sequence, f->frame.width,
             f->frame.height, rte_status_message(st));
}

/* The lane path's result published and its stages recorded (true: *lr holds it). */
static bool lane_path(rted_daemon *d, const rte_source_frame *f, rte_lane_result *lr)
{
    rte_status st = rte_lane_process(d->lane, &f->frame, f->recorded_ns, lr);
    if (st == RTE_OK) {
        rted_publish_lane(d, f, lr);
        for (int i = 0; i < RTE_LANE_STAGES; i++)
            rted_record_stage(d, i, lr->stage_ns[i]);
    }
    path_error(d, 0, f, st);
    return st == RTE_OK;
}

/* The grasp job's outcome, on the main thread: counted, published, its
 * stages recorded (true: j->result holds it). */
static bool grasp_outcome(rted_daemon *d, const rte_source_frame *f, const rted_grasp_job *j)
{
    if (j->skipped)
        d->n.stages_skipped++;
    if (!j->ran)
        return false;
    if (j->status == RTE_OK) {
        rted_publish_grasp(d, f, &j->result);
        const rte_grasp_timing *t = &j->result.timing;
        const int64_t ns[RTED_GRASP_STAGES] = {t->blur_ns, t->binarize_ns, t->contours_ns,
                                               t->split_ns, t->features_ns};
        for (int i = 0; i < RTED_GRASP_STAGES; i++)
            rted_record_stage(d, RTED_GRASP_STAGE0 + i, ns[i]);
    }
    path_error(d, 1, f, j->status);
    return j->status == RTE_OK;
}

static rted_step analyse(rted_daemon *d, const rte_source_frame *f)
{
    const int64_t t0 = f->capture_ns;
    rte_lane_result lr;
    bool have_lane = false;
    const bool debug = rted_debug_due(d, t0);
    rted_grasp_job *j = &d->job;
    j->frame = f;
    j->need_gray = d->grasp || d->cfg.publish_images || debug;
    if (d->threaded) {
        /* the grey image and the grasp path beside the lane path */
        rted_grasp_job_post(d);
        have_lane = lane_path(d, f, &lr);
        rted_grasp_job_wait(d);
    } else {
        if (d->lane)
            have_lane = lane_path(d, f, &lr);
        rted_grasp_job_run(d, j);
    }
    const bool have_grasp = grasp_outcome(d, f, j);
    if (d->cfg.publish_images) {
        if (d->deadline_ns - (rte_clock_now_ns() - t0) < d->grasp_min_ns)
            d->n.stages_skipped++;
        else
            rted_publish_image(d, f, &j->gray);
    }
    /* The results are out: the latency is theirs. The overlay follows,
     * within what is left of the budget. */
    int64_t lat = rte_clock_now_ns() - t0;
    rted_record_latency(d, lat);
    if (lat > d->deadline_ns)
        d->n.deadline_misses++;
    if (debug) {
        if (d->deadline_ns - lat < d->grasp_min_ns)
            d->n.stages_skipped++;
        else {
            const int64_t t1 = rte_clock_now_ns();
            rted_debug_publish(d, f, &j->gray, have_lane ? &lr : NULL,
                               have_grasp ? &j->result : NULL);
            rted_record_stage(d, RTED_DEBUG_STAGE, rte_clock_now_ns() - t1);
        }
    }
    d->n.processed++;
    d->window_processed++;
    return RTED_STEP_FRAME;
}

/* The end of a recording: start again (source.loop), or stop. A pass that
 * gave no readable frame stops the daemon either way, rather than rewinding
 * without end or ending as if all was well. A rewind is not a reconnection:
 * no message, no status, the latency window goes on. */
static rted_step end_of_pass(rted_daemon *d)
{
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    d->n.bad_frames = ss.bad_frames;
    d->state = RTE_SOURCE_ENDED;
    if (!d->pass_frames) {
        rted_error("%s: %s gave no readable frame (%llu bad frames in all): stopping", d->source_id,
                   d->passes ? "a whole pass of the recording" : "the recording",
                   (unsigned long long)ss.bad_frames);
        return RTED_STEP_EMPTY;
    }
    if (!d->cfg.loop || rte_recorded_source_rewind(&d->source) != RTE_OK)
        return RTED_STEP_END;
    d->state = RTE_SOURCE_STREAMING;
    d->n.rewinds++;
    d->passes++;
    d->pass_frames = 0;
    return RTED_STEP_IDLE;
}

static void sleep_ns(int64_t ns)
{
    struct timespec ts = {ns / 1000000000, ns % 1000000000};
    nanosleep(&ts, NULL);
}

/* Waits until the pacer lets f through (true), or drops it (counted) or a
 * stop comes (false); a status still goes out when due while waiting. */
static bool wait_for_pace(rted_daemon *d, rte_source_frame *f)
{
    bool waited = false;
    for (;;) {
        int64_t wait = 0;
        rte_pace_action a = rte_pacer_decide(&d->pacer, f->recorded_ns, rte_clock_now_ns(), &wait);
        if (a == RTE_PACE_DROP) {
            d->n.dropped++;
            return false;
        }
        if (a == RTE_PACE_PROCESS)
            break;
        if (d->stop && *d->stop)
            return false;
        sleep_ns(wait > 50000000 ? 50000000 : wait);
        rted_notify_watchdog(&d->notify, rte_clock_now_ns());
        waited = true;
        if (d->cfg.status_period_ms &&
            rte_clock_now_ns() - d->window_start_ns >= (int64_t)d->cfg.status_period_ms * 1000000)
            rted_daemon_publish_status(d);
    }
    /* Recordings: the frame is "captured" when it is due, not when it was
     * read ahead of its time. */
    if (d->recorded && waited)
        f->capture_ns = rte_clock_now_ns();
    return true;
}

/* The source's state changed (a camera lost, back, or there at last): said
 * at once, on stderr, to systemd and in a status message. */
static void source_state_changed(rted_daemon *d, const rte_source_stats *ss, const char *why)
{
    if (ss->state == RTE_SOURCE_STREAMING && !d->n.received) {
        rted_log("%s: the camera is there, streaming", d->source_id);
        rted_notify_status(&d->notify, NULL, "%s: the camera is there, waiting for a frame",
                           d->source_id);
    } else if (ss->state == RTE_SOURCE_STREAMING) {
        rted_log("source streaming again (reconnection %llu)", (unsigned long long)ss->reconnects);
        rted_notify_status(&d->notify, NULL, "streaming %s again (reconnection %llu)", d->source_id,
                           (unsigned long long)ss->reconnects);
    } else if (ss->state == RTE_SOURCE_RECONNECTING) {
        rted_notify_status(&d->notify, NULL, "reconnecting: %s", why);
    }
    rted_daemon_publish_status(d);
}

/* A source error: a camera waited for or reconnecting (said to systemd
 * too), or a bad frame of a recording. */
static void source_error(rted_daemon *d, rte_status st, const rte_source_stats *ss, const char *why)
{
    if (!why[0])
        why = rte_status_message(st);
    if (ss->state == RTE_SOURCE_RECONNECTING) {
        const char *what = d->n.received ? "reconnecting" : "waiting for camera";
        rted_log_limited(&d->log_frames, RTED_LOG_WARNING, "%s: %s", what, why);
        rted_notify_status(&d->notify, NULL, "%s: %s", what, why);
        return;
    }
    /* A looping recording's bad frames were said in its first pass. */
    if (!d->passes)
        rted_log_limited(&d->log_frames, RTED_LOG_WARNING, "%s: %s",
                         st == RTE_ERR_DEVICE ? "source" : "frame skipped", why);
}

/* The first frame: systemd is told the daemon is ready. */
static void first_frame(rted_daemon *d, const rte_source_frame *f)
{
    rted_log("ready: %s streaming, first frame %dx%d", d->source_id, f->frame.width,
             f->frame.height);
    rted_notify_status(&d->notify, "READY=1", "streaming %s %dx%d", d->source_id, f->frame.width,
                       f->frame.height);
}

rted_step rted_daemon_step(rted_daemon *d)
{
    rted_notify_watchdog(&d->notify, rte_clock_now_ns());
    if (d->cfg.max_frames && d->n.processed >= (uint64_t)d->cfg.max_frames)
        return RTED_STEP_END;
    rted_params_poll(d);
    if (rte_clock_now_ns() - d->window_start_ns >= (int64_t)d->cfg.status_period_ms * 1000000)
        rted_daemon_publish_status(d);

    rte_source_frame f;
    char why[RTE_SOURCE_MESSAGE_SIZE] = "";
    rte_status st = rte_source_next(&d->source, &f, 100, why, sizeof why);
    if (st == RTE_ERR_END)
        return end_of_pass(d);
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    d->n.bad_frames = ss.bad_frames;
    if (ss.state != d->reported_state)
        source_state_changed(d, &ss, why);
    if (st == RTE_ERR_TIMEOUT)
        return RTED_STEP_IDLE;
    if (st != RTE_OK) {
        if (ss.state == RTE_SOURCE_FAILED) {
            rted_error("source failed: %s", why);
            rted_notify_status(&d->notify, NULL, "source failed: %s", why);
            return RTED_STEP_FAILED;
        }
        source_error(d, st, &ss, why);
        return RTED_STEP_IDLE;
    }
    d->pass_frames++;
    if (!d->n.received++)
        first_frame(d, &f);
    if (d->rec)
        rted_record_frame(d, &f);
    if (!wait_for_pace(d, &f))
        return RTED_STEP_IDLE;
    /* once, so that every message of the frame carries the same utime */
    d->capture_wall_us = rte_clock_wall_us(f.capture_ns);
    return analyse(d, &f);
}

/* SIGHUP: systemd hears RELOADING=1, then READY=1 with the outcome. */
static void reload(rted_daemon *d)
{
    char msg[RTED_MSG];
    snprintf(msg, sizeof msg, "RELOADING=1\nMONOTONIC_USEC=%lld",
             (long long)(rte_clock_now_ns() / 1000));
    rted_notify_send(&d->notify, msg);
    if (rted_daemon_reload(d, msg, sizeof msg)) {
        rted_log("configuration re-read and applied (hash %016llx)",
                 (unsigned long long)d->config_hash);
        rted_notify_status(&d->notify, "READY=1",
                           "configuration re-read and applied (hash %016llx)",
                           (unsigned long long)d->config_hash);
    } else {
        rted_warn("configuration change refused: %s", msg);
        rted_notify_status(&d->notify, "READY=1", "configuration change refused: %s", msg);
    }
}

int rted_daemon_run(rted_daemon *d, volatile sig_atomic_t *stop, volatile sig_atomic_t *reload_flag)
{
    int code = RTED_EXIT_OK;
    d->stop = stop;
    while (!*stop) {
        if (*reload_flag) {
            *reload_flag = 0;
            reload(d);
        }
        rted_step s = rted_daemon_step(d);
        if (s == RTED_STEP_END)
            break;
        if (s == RTED_STEP_FAILED || s == RTED_STEP_EMPTY) {
            code = s == RTED_STEP_FAILED ? RTED_EXIT_FAILED : RTED_EXIT_NO_FRAMES;
            break;
        }
    }
    rted_notify_status(&d->notify, "STOPPING=1", "stopping: %s",
                       *stop                         ? "signal"
                       : code == RTED_EXIT_FAILED    ? "the source failed"
                       : code == RTED_EXIT_NO_FRAMES ? "no readable frame"
                                                     : "the end of the source");
    rted_daemon_publish_status(d);
    return code;
}
