/* A camera opened when it appears: see waiting.h. */
#include "sources/waiting.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/clock.h"
#include "retry.h"
#include "source_msg.h"

typedef struct waiting_source {
    rte_waiting_config cfg;
    rte_source camera; /* ops == NULL until it opens */
    rte_source_stats stats;
    rte_retry retry;
} waiting_source;

static int64_t now_ns(const waiting_source *w)
{
    return w->cfg.now_ns ? w->cfg.now_ns(w->cfg.ctx) : rte_clock_now_ns();
}

static void sleep_ms(const waiting_source *w, int32_t ms)
{
    if (w->cfg.sleep_ms) {
        w->cfg.sleep_ms(w->cfg.ctx, ms);
        return;
    }
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000};
    nanosleep(&ts, NULL);
}

/* The camera came up: keep it if it fits what was announced. */
static bool camera_fits(waiting_source *w, char *msg, size_t msg_size)
{
    const rte_source *c = &w->camera;
    if (c->max_width <= w->cfg.max_width && c->max_height <= w->cfg.max_height &&
        c->format == w->cfg.format)
        return true;
    rte_source_msgf(msg, msg_size, "%s came up as %dx%d %s, not within %dx%d %s", w->cfg.name,
                    c->max_width, c->max_height, rte_pixel_format_name(c->format), w->cfg.max_width,
                    w->cfg.max_height, rte_pixel_format_name(w->cfg.format));
    rte_source_close(&w->camera);
    return false;
}

/* Sleeps until the next attempt (within the caller's time), then tries. */
static rte_status try_open(waiting_source *w, int32_t timeout_ms, char *msg, size_t msg_size)
{
    int64_t now = now_ns(w);
    int64_t wait_ms = rte_retry_wait_ms(&w->retry, now);
    if (wait_ms > 0) {
        if (timeout_ms >= 0 && wait_ms > timeout_ms)
            wait_ms = timeout_ms;
        sleep_ms(w, (int32_t)wait_ms);
        now = now_ns(w);
        if ((wait_ms = rte_retry_wait_ms(&w->retry, now)) > 0) {
            rte_source_msgf(msg, msg_size, "%s: waiting for the camera, next attempt in %lld ms",
                            w->cfg.name, (long long)wait_ms);
            return RTE_ERR_TIMEOUT;
        }
    }
    char why[RTE_SOURCE_MESSAGE_SIZE] = "";
    rte_status st = w->cfg.open(w->cfg.ctx, &w->camera, why, sizeof why);
    if (st == RTE_OK && camera_fits(w, why, sizeof why)) {
        w->stats.state = RTE_SOURCE_STREAMING;
        return RTE_OK;
    }
    w->camera = (rte_source){0};
    w->stats.errors++;
    rte_retry_failed(&w->retry, now);
    rte_source_msgf(msg, msg_size, "%s: %s; retrying in %d ms", w->cfg.name,
                    why[0] ? why : rte_status_message(st), w->retry.delay_ms);
    return RTE_ERR_DEVICE;
}

static rte_status waiting_next(void *impl, rte_source_frame *frame, int32_t timeout_ms, char *msg,
                               size_t msg_size)
{
    waiting_source *w = impl;
    if (!w->camera.ops) {
        int64_t start = now_ns(w);
        rte_status st = try_open(w, timeout_ms, msg, msg_size);
        if (st != RTE_OK)
            return st;
        if (timeout_ms >= 0) { /* what is left of the caller's time */
            int64_t spent_ms = (now_ns(w) - start) / 1000000;
            timeout_ms = spent_ms >= timeout_ms ? 0 : timeout_ms - (int32_t)spent_ms;
        }
    }
    return rte_source_next(&w->camera, frame, timeout_ms, msg, msg_size);
}

static void waiting_get_stats(const void *impl, rte_source_stats *stats)
{
    const waiting_source *w = impl;
    if (!w->camera.ops) {
        *stats = w->stats;
        return;
    }
    rte_source_get_stats(&w->camera, stats);
    stats->errors += w->stats.errors; /* the attempts before it came */
}

static void waiting_close(void *impl)
{
    waiting_source *w = impl;
    rte_source_close(&w->camera);
    free(w);
}

static const rte_source_ops waiting_ops = {"waiting", waiting_next, waiting_get_stats,
                                           waiting_close};

rte_status rte_waiting_source_open(rte_source *source, const rte_waiting_config *config, char *msg,
                                   size_t msg_size)
{
    rte_source_msgf(msg, msg_size, "%s", "");
    if (!source || !config || !config->open || !config->name || config->max_width <= 0 ||
        config->max_height <= 0 || !config->format || config->retry_min_ms < 0 ||
        config->retry_max_ms < 0) {
        rte_source_msgf(msg, msg_size, "waiting source: a bad configuration");
        return RTE_ERR_ARGUMENT;
    }
    waiting_source *w = calloc(1, sizeof *w);
    if (!w) {
        rte_source_msgf(msg, msg_size, "waiting source: out of memory");
        return RTE_ERR_NO_MEMORY;
    }
    w->cfg = *config;
    if (!w->cfg.retry_min_ms)
        w->cfg.retry_min_ms = 500;
    if (!w->cfg.retry_max_ms)
        w->cfg.retry_max_ms = 8000;
    if (w->cfg.retry_max_ms < w->cfg.retry_min_ms)
        w->cfg.retry_max_ms = w->cfg.retry_min_ms;
    rte_retry_start(&w->retry, now_ns(w), w->cfg.retry_min_ms, w->cfg.retry_max_ms);
    w->stats.state = RTE_SOURCE_RECONNECTING;
    *source = (rte_source){&waiting_ops, w, config->max_width, config->max_height, config->format};
    return RTE_OK;
}
