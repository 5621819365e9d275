/* Run-time configuration: a new configuration applied between frames
 * (SIGHUP re-reads the file; params_t messages change single keys). Only
 * runtime keys may change, through rte_lane_set_params and
 * rte_grasp_set_params, which allocate nothing. */
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"
#include "core/fractions.h"

bool rted_lane_thresholds_ok(const rted_config *c, const rte_lane_params *p, char *msg,
                             size_t msg_size)
{
    if (p->canny_low <= p->canny_high)
        return true;
    rted_msgf(msg, msg_size, "lane.canny_low (%d%s) exceeds lane.canny_high (%d%s)", p->canny_low,
              c->lane_canny_low < 0 ? ", the default" : "", p->canny_high,
              c->lane_canny_high < 0 ? ", the default" : "");
    return false;
}

bool rted_lane_params(const rted_daemon *d, const rted_config *c, rte_lane_params *p)
{
    *p = d->lane_base.params;
    int32_t n = rte_parse_fractions(c->lane_roi, p->roi, RTE_LANE_MAX_ROI_VERTICES);
    if (n < 0)
        return false;
    p->roi_count = n;
    p->canny_mode = (rte_lane_canny_mode)c->lane_canny_mode;
    if (c->lane_canny_low >= 0)
        p->canny_low = c->lane_canny_low;
    if (c->lane_canny_high >= 0)
        p->canny_high = c->lane_canny_high;
    if (c->lane_hough_threshold >= 0)
        p->hough_threshold = c->lane_hough_threshold;
    if (c->lane_min_length >= 0)
        p->min_length = c->lane_min_length;
    if (c->lane_max_gap >= 0)
        p->max_gap = c->lane_max_gap;
    p->hough_seed = (uint32_t)c->lane_hough_seed;
    if (c->lane_hold_frames >= 0)
        p->hold_frames = c->lane_hold_frames;
    if (c->lane_gate_px >= 0)
        p->gate_px = c->lane_gate_px;
    p->use_color = c->lane_use_color;
    p->curves = c->lane_curves;
    return true;
}

void rted_grasp_params(const rted_config *c, rte_grasp_params *p)
{
    p->binarize = (rte_grasp_binarize)c->grasp_binarize;
    p->threshold = c->grasp_threshold;
    p->polarity = (rte_grasp_polarity)c->grasp_polarity;
    p->contrast = c->grasp_contrast;
    p->background_cell = c->grasp_background_cell;
    p->chroma = c->grasp_chroma;
    p->edge_support_permille = (int32_t)lround(c->grasp_edge_support * 1000);
    p->min_area = c->grasp_min_area;
    p->max_area = c->grasp_max_area;
    p->skip_border = c->grasp_skip_border;
    p->split = c->grasp_split;
    p->max_objects = c->grasp_max_objects;
    p->gripper_min_px = c->grasp_gripper_min_px;
    p->gripper_max_px = c->grasp_gripper_max_px;
    p->margin_px = c->grasp_margin_px;
    p->finger_px = c->grasp_finger_px;
    int32_t n =
        c->grasp_roi[0] ? rte_parse_fractions(c->grasp_roi, p->roi, RTE_GRASP_MAX_ROI_VERTICES) : 0;
    p->roi_count = n > 0 ? n : 0; /* (validated before: < 0 cannot come) */
}

void rted_derive(rted_daemon *d)
{
    const rted_config *c = &d->cfg;
    double ms = c->deadline_ms > 0 ? c->deadline_ms : 1000.0 / c->fps;
    d->deadline_ns = (int64_t)llround(ms * 1e6);
    d->grasp_min_ns = (int64_t)llround(c->grasp_min_budget_ms * 1e6);
    d->config_hash = rted_config_hash(c);
    rted_debug_apply(d);
    /* The header's ROI in pixels of the analysed frame. */
    const rte_lane_params *p = &d->lane_base.params;
    rte_lane_params lp;
    if (!rted_lane_params(d, c, &lp))
        lp = *p;
    for (int32_t i = 0; i < lp.roi_count; i++) {
        d->roi[i].x = (int32_t)(((int64_t)lp.roi[i].x * d->width + 32768) >> 16);
        d->roi[i].y = (int32_t)(((int64_t)lp.roi[i].y * d->height + 32768) >> 16);
    }
    d->lane_msg.header.roi_npoints = (int16_t)lp.roi_count;
    rte_grasp_params gp = {0};
    rted_grasp_params(c, &gp);
    for (int32_t i = 0; i < gp.roi_count; i++) {
        d->grasp_roi[i].x = (int32_t)(((int64_t)gp.roi[i].x * d->width + 32768) >> 16);
        d->grasp_roi[i].y = (int32_t)(((int64_t)gp.roi[i].y * d->height + 32768) >> 16);
    }
    d->grasp_msg.header.roi_npoints = (int16_t)gp.roi_count;
}

bool rted_daemon_apply(rted_daemon *d, const rted_config *next, char *msg, size_t msg_size)
{
    char fixed[160];
    if (rted_config_fixed_change(&d->cfg, next, fixed, sizeof fixed)) {
        snprintf(msg, msg_size,
                 "%s cannot change while running (it fixes sizes or the source): "
                 "restart rtedged",
                 fixed);
        d->n.refused++;
        return false;
    }
    if (!rted_config_validate(next, msg, msg_size) ||
        !rted_config_check_frame(next, d->width, d->height, msg, msg_size)) {
        d->n.refused++;
        return false;
    }
    rte_lane_params lp;
    const bool lane_ok = rted_lane_params(d, next, &lp);
    if (lane_ok && !rted_lane_thresholds_ok(next, &lp, msg, msg_size)) {
        d->n.refused++;
        return false;
    }
    if (d->lane && (!lane_ok || rte_lane_set_params(d->lane, &lp) != RTE_OK)) {
        snprintf(msg, msg_size, "the lane parameters were refused by the lane path");
        d->n.refused++;
        return false;
    }
    if (d->grasp) {
        rte_grasp_params gp;
        rte_grasp_get_params(d->grasp, &gp);
        rted_grasp_params(next, &gp);
        if (rte_grasp_set_params(d->grasp, &gp) != RTE_OK) {
            /* All or nothing: the lane path goes back to the configuration in force. */
            if (d->lane && rted_lane_params(d, &d->cfg, &lp))
                rte_lane_set_params(d->lane, &lp);
            snprintf(msg, msg_size, "the grasp parameters were refused by the grasp path");
            d->n.refused++;
            return false;
        }
    }
    d->cfg = *next;
    rted_derive(d);
    d->n.reloads++;
    msg[0] = 0;
    return true;
}

bool rted_daemon_reload(rted_daemon *d, char *msg, size_t msg_size)
{
    if (!d->config_path) {
        snprintf(msg, msg_size, "no configuration file to re-read (started without --config)");
        d->n.refused++;
        return false;
    }
    rted_config next;
    rted_config_defaults(&next);
    bool ok = rted_config_load(&next, d->config_path, msg, msg_size);
    for (int i = 0; ok && i < d->n_sets; i++)
        ok = rted_config_set(&next, d->sets[i], "--set", msg, msg_size);
    if (!ok) {
        d->n.refused++;
        return false;
    }
    if (!rted_daemon_apply(d, &next, msg, msg_size))
        return false;
    rted_param_state_publish(d);
    return true;
}

/* ACTION_SAVE: the configuration in force as text, and into
 * params.save_path when that is set. */
static bool save(rted_daemon *d, char *why, size_t why_size)
{
    const char *path = d->cfg.params_save_path[0] ? d->cfg.params_save_path : NULL;
    if (!rted_config_save(&d->cfg, path, d->config_text, RTED_CONFIG_TEXT_MAX, why, why_size))
        return false;
    if (path)
        rted_msgf(why, why_size, "saved to %s (hash %016llx)", path,
                  (unsigned long long)d->config_hash);
    else
        rted_msgf(why, why_size, "not written on the robot (params.save_path is empty)");
    return true;
}

void rted_daemon_handle_params(rted_daemon *d, const void *data, size_t size)
{
    rted_params_request *r = &d->params_req;
    rted_config next;
    char why[RTED_MSG];
    d->n.params_received++;
    if (!rted_params_decode(data, size, r, why, sizeof why)) {
        d->n.refused++;
    } else if (r->action == RTEDGE_PARAMS_T_ACTION_SAVE) {
        if (save(d, why, sizeof why)) {
            d->n.saves++;
            rted_log_limited(&d->log_params, RTED_LOG_INFO, "params request %lld: %s",
                             (long long)r->request_id, why);
            rted_param_state_outcome(d, r->request_id, RTEDGE_PARAM_STATE_T_OUTCOME_SAVED, why,
                                     true);
            return;
        }
        d->n.refused++;
    } else if (!rted_params_to_config(r, &d->cfg, &next, why, sizeof why)) {
        d->n.refused++;
    } else if (rted_daemon_apply(d, &next, why, sizeof why)) {
        rted_log_limited(&d->log_params, RTED_LOG_INFO,
                         "params request %lld applied (%d values, hash %016llx)",
                         (long long)r->request_id, r->count, (unsigned long long)d->config_hash);
        rted_param_state_outcome(d, r->request_id, RTEDGE_PARAM_STATE_T_OUTCOME_APPLIED, "", false);
        return;
    }
    if (r->have_id)
        rted_log_limited(&d->log_params, RTED_LOG_WARNING, "params request %lld refused: %s",
                         (long long)r->request_id, why);
    else
        rted_log_limited(&d->log_params, RTED_LOG_WARNING, "params message refused: %s", why);
    rted_param_state_outcome(d, r->have_id ? r->request_id : 0,
                             RTEDGE_PARAM_STATE_T_OUTCOME_REFUSED, why, false);
}

/* liblcm's callback: within params.max_per_second, else counted and dropped. */
static void on_params(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    rted_daemon *d = user;
    int64_t now = rte_clock_now_ns();
    if (now - d->params_window_ns >= 1000000000) {
        d->params_window_ns = now;
        d->params_in_window = 0;
    }
    if (d->params_in_window >= d->cfg.params_max_per_second) {
        d->n.rate_limited++;
        rted_log_limited(&d->log_params, RTED_LOG_WARNING,
                         "params message dropped: more than %d a second "
                         "(params.max_per_second)",
                         d->cfg.params_max_per_second);
        return;
    }
    d->params_in_window++;
    rted_daemon_handle_params(d, rbuf->data, rbuf->data_size);
}

void rted_params_open(rted_daemon *d)
{
    const rted_config *c = &d->cfg;
    /* A person tuning sends a request now and then: each is said; a flood
     * is not. */
    d->log_params = (rted_log_limit){.what = "params", .burst = 20};
    if (!c->params_enabled)
        return;
    lcm_t *lcm = rte_publisher_lcm(d->pub);
    if (!lcm) {
        rted_warn("params.enabled needs an LCM transport (udpm://, memq://), not %s: "
                  "no params channel",
                  c->lcm_url);
        return;
    }
    d->params_sub = lcm_subscribe(lcm, c->params_channel, on_params, d);
    if (!d->params_sub)
        rted_warn("cannot subscribe to %s: no params channel", c->params_channel);
}

void rted_params_close(rted_daemon *d)
{
    if (d->params_sub && d->pub)
        lcm_unsubscribe(rte_publisher_lcm(d->pub), d->params_sub);
    d->params_sub = NULL;
}

void rted_params_poll(rted_daemon *d)
{
    if (!d->params_sub)
        return;
    lcm_t *lcm = rte_publisher_lcm(d->pub);
    struct pollfd pfd = {lcm_get_fileno(lcm), POLLIN, 0};
    for (int i = 0; i < RTED_PARAMS_PER_STEP && poll(&pfd, 1, 0) > 0 && (pfd.revents & POLLIN); i++)
        if (lcm_handle(lcm) != 0)
            break;
}
