/* rted_daemon_open(): everything sized once from the configuration and the
 * source's maxima, in this order: the source, the pacer, the lane and grasp
 * contexts, one arena for the grey buffer and the message arrays, the
 * param_state_t message, the debug stream's canvas and JPEG encoder, the
 * publisher (its encode buffer), the params
 * channel, the recording, then the real-time settings and the grasp thread
 * (realtime.c). A frame then makes no heap call. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"

/* Pacing: recordings at their pace, live sources as they come. */
static bool open_pacer(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    rte_pacer_config pc = {RTE_PACE_FAST, 1000, 1, 1, -1, 0};
    if (d->recorded && c->pace == RTED_PACE_RECORDED)
        pc.mode = RTE_PACE_RECORDED;
    else if (d->recorded && c->pace == RTED_PACE_FPS)
        pc.mode = RTE_PACE_FPS;
    pc.speed_permille = (int32_t)lround(c->speed * 1000);
    if (pc.speed_permille < 1)
        pc.speed_permille = 1;
    pc.fps_num = (int32_t)lround(c->fps * 1000);
    pc.fps_den = 1000;
    pc.max_late_ns = c->max_late_ms < 0 ? -1 : (int64_t)llround(c->max_late_ms * 1e6);
    pc.max_pause_ns = (int64_t)c->max_pause_ms * 1000000;
    if (rte_pacer_init(&d->pacer, &pc) != RTE_OK) {
        rted_msgf(msg, msg_size, "bad pacing (source.fps, source.speed)");
        return false;
    }
    return true;
}

/* The lane context when lane.enabled; its frame-size defaults are kept for
 * run-time changes either way. */
static bool open_lane(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    rte_lane_config_default(&d->lane_base, d->width, d->height);
    d->lane_base.max_width = d->width;
    d->lane_base.max_height = d->height;
    d->lane_base.max_segments = c->lane_max_segments;
    d->lane_base.blur_ksize = c->lane_blur_ksize;
    if (!c->lane_enabled)
        return true;
    rte_lane_config lc = d->lane_base;
    if (!rted_lane_params(d, c, &lc.params)) {
        rted_msgf(msg, msg_size, "the lane configuration is invalid for this source");
        return false;
    }
    if (!rted_lane_thresholds_ok(c, &lc.params, msg, msg_size))
        return false;
    rte_status st = rte_lane_create(&lc, &d->lane);
    if (st != RTE_OK) {
        rted_msgf(msg, msg_size, "lane path: %s", rte_status_message(st));
        return false;
    }
    return true;
}

static bool open_grasp(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    if (!c->grasp_enabled)
        return true;
    rte_grasp_config gc;
    rte_grasp_config_default(&gc);
    gc.max_width = d->width;
    gc.max_height = d->height;
    gc.max_contours = c->grasp_max_contours;
    gc.max_points = c->grasp_max_points;
    gc.max_objects = c->grasp_max_objects;
    gc.blur_ksize = c->grasp_blur_ksize;
    rted_grasp_params(c, &gc.params);
    rte_status st = rte_grasp_create(&gc, &d->grasp);
    if (st != RTE_OK) {
        rted_msgf(msg, msg_size, "the grasp configuration is invalid for this source: %s",
                  rte_status_message(st));
        return false;
    }
    return true;
}

/* One arena for the grey frame and the message arrays. */
static bool open_memory(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    size_t gray_bytes = (size_t)d->width * (size_t)d->height;
    const int32_t hw = (d->width + 1) / 2, hh = (d->height + 1) / 2;
    size_t chroma_bytes = (size_t)hw * (size_t)hh;
    size_t seg_bytes = (size_t)c->lane_max_segments * sizeof(rtedge_segment_t);
    size_t obj_bytes = (size_t)c->grasp_max_objects * sizeof(rtedge_grasp_object_t);
    size_t total = rte_arena_piece_size(gray_bytes) + 2 * rte_arena_piece_size(chroma_bytes) +
                   rte_arena_piece_size(seg_bytes) + rte_arena_piece_size(obj_bytes) +
                   RTE_ARENA_ALIGN;
    d->memory = malloc(total);
    if (!d->memory) {
        rted_msgf(msg, msg_size, "out of memory");
        return false;
    }
    rte_arena_init(&d->arena, d->memory, total);
    d->gray = (rte_image_u8){d->width, d->height, d->width, rte_arena_alloc(&d->arena, gray_bytes)};
    d->cb = (rte_image_u8){hw, hh, hw, rte_arena_alloc(&d->arena, chroma_bytes)};
    d->cr = (rte_image_u8){hw, hh, hw, rte_arena_alloc(&d->arena, chroma_bytes)};
    d->segments = rte_arena_alloc(&d->arena, seg_bytes);
    d->objects = rte_arena_alloc(&d->arena, obj_bytes);
    memset(d->objects, 0, obj_bytes);
    memset(d->segments, 0, seg_bytes);
    return true;
}

/* The publisher, its encode buffer sized for the largest message. */
static bool open_publisher(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    size_t gray_bytes = (size_t)d->width * (size_t)d->height;
    const int32_t gray_image = c->publish_images ? (int32_t)gray_bytes : 0;
    const int32_t debug_image = rted_debug_max_bytes(d);
    const int32_t image_bytes = gray_image > debug_image ? gray_image : debug_image;
    rte_publish_limits lim = {RTED_TEXT + 16,
                              RTE_LANE_MAX_ROI_VERTICES,
                              c->lane_max_segments,
                              c->grasp_max_objects,
                              RTED_MAX_SETS,
                              image_bytes,
                              0,
                              d->state_max_bytes};
    char why[RTED_MSG];
    if (rte_publisher_create(&d->pub, c->lcm_url, &lim, why, sizeof why) != RTE_OK) {
        snprintf(msg, msg_size, "cannot publish to %s: %s", c->lcm_url, why);
        return false;
    }
    return true;
}

/* The steps after the source, in order; false and *msg at the first that fails. */
static bool open_after_source(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    char why[RTED_MSG];
    if (!rted_config_check_frame(c, d->width, d->height, why, sizeof why)) {
        rted_msgf(msg, msg_size, "the configuration does not fit the source: %s", why);
        return false;
    }
    if (!open_pacer(d, msg, msg_size) || !open_lane(d, msg, msg_size) ||
        !open_grasp(d, msg, msg_size) || !open_memory(d, msg, msg_size) ||
        !rted_param_state_init(d, msg, msg_size) || !rted_debug_open(d, msg, msg_size) ||
        !open_publisher(d, msg, msg_size))
        return false;
    rted_params_open(d);
    return !c->record_path[0] || rted_open_recording(d, msg, msg_size);
}

bool rted_daemon_open(rted_daemon **out, const rted_config *cfg, const char *config_path, char *msg,
                      size_t msg_size)
{
    *out = NULL;
    rted_daemon *d = calloc(1, sizeof *d);
    if (!d) {
        rted_msgf(msg, msg_size, "out of memory");
        return false;
    }
    d->cfg = *cfg;
    d->config_path = config_path;
    char why[RTED_MSG];
    if (!rted_notify_open(&d->notify, why, sizeof why))
        rted_warn("%s (no notifications to systemd)", why);
    d->log_frames = (rted_log_limit){.what = "bad-frame", .burst = 5};
    if (!rted_open_source(d, msg, msg_size) || !open_after_source(d, msg, msg_size)) {
        rted_daemon_close(d);
        return false;
    }
    rted_messages_init(d);
    rted_derive(d);
    if (!rted_realtime_start(d, msg, msg_size)) {
        rted_daemon_close(d);
        return false;
    }
    d->window_start_ns = rte_clock_now_ns();
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    if (ss.state == RTE_SOURCE_RECONNECTING)
        rted_notify_status(&d->notify, NULL, "waiting for camera %s", d->cfg.source_path);
    else
        rted_notify_status(&d->notify, NULL, "%s open, waiting for the first frame", d->source_id);
    /* A first status says the daemon is up; it also makes liblcm cache the
     * channel (memq:// strdup()s a channel's name on its first message). */
    rted_daemon_publish_status(d); /* with the first param_state_t before it */
    *out = d;
    return true;
}

void rted_daemon_close(rted_daemon *d)
{
    if (!d)
        return;
    rted_realtime_stop(d);
    rted_params_close(d);
    rted_notify_close(&d->notify);
    rte_publisher_destroy(d->pub);
    rte_publisher_destroy(d->rec);
    free(d->rec_buf);
    rted_param_state_close(d);
    rted_debug_close(d);
    rte_grasp_destroy(d->grasp);
    rte_lane_destroy(d->lane);
    rte_source_close(&d->source);
    free(d->memory);
    free(d);
}

lcm_t *rted_daemon_lcm(rted_daemon *d) { return rte_publisher_lcm(d->pub); }

void rted_daemon_get_counters(const rted_daemon *d, rted_counters *c) { *c = d->n; }

const rted_config *rted_daemon_config(const rted_daemon *d) { return &d->cfg; }

void rted_daemon_set_overrides(rted_daemon *d, char *const *sets, int n_sets)
{
    d->sets = sets;
    d->n_sets = n_sets;
}
