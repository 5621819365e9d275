/* The status message and the latency window it reports: capture-to-publish
 * latencies in a fixed ring, sorted in place when a status goes out (an
 * integer heap sort: bounded time, no allocation); and the whole run's
 * latencies in a fixed histogram, for --bench. */
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"

static void sift(int32_t *a, uint32_t root, uint32_t n)
{
    for (;;) {
        uint32_t child = 2 * root + 1;
        if (child >= n)
            return;
        if (child + 1 < n && a[child + 1] > a[child])
            child++;
        if (a[root] >= a[child])
            return;
        int32_t t = a[root];
        a[root] = a[child];
        a[child] = t;
        root = child;
    }
}

/* In-place heap sort: bounded time, no allocation. */
static void sort_i32(int32_t *a, uint32_t n)
{
    for (uint32_t i = n / 2; i-- > 0;)
        sift(a, i, n);
    for (uint32_t i = n; i-- > 1;) {
        int32_t t = a[0];
        a[0] = a[i];
        a[i] = t;
        sift(a, 0, i);
    }
}

static void window_latency(rted_daemon *d, int32_t *p50, int32_t *p99, int32_t *max)
{
    uint32_t n = d->ring_n < RTED_RING ? d->ring_n : RTED_RING;
    *p50 = *p99 = 0;
    *max = d->window_max;
    if (!n)
        return;
    memcpy(d->sorted, d->ring, n * sizeof d->ring[0]);
    sort_i32(d->sorted, n);
    *p50 = d->sorted[(uint64_t)(n - 1) * 50 / 100];
    *p99 = d->sorted[(uint64_t)(n - 1) * 99 / 100];
}

void rted_record_stage(rted_daemon *d, int stage, int64_t ns)
{
    d->stage_sum_ns[stage] += ns;
    if (ns > d->stage_max_ns[stage])
        d->stage_max_ns[stage] = ns;
    d->stage_frames[stage]++;
}

/* The window's stage times into the message's arrays, and a new window. */
static void stage_times(rted_daemon *d)
{
    for (int i = 0; i < RTED_STAGES; i++) {
        int64_t mean = d->stage_frames[i] ? d->stage_sum_ns[i] / d->stage_frames[i] : 0;
        d->stage_mean_us[i] = (int32_t)(mean / 1000);
        d->stage_max_us[i] =
            (int32_t)(d->stage_max_ns[i] / 1000 > INT32_MAX ? INT32_MAX
                                                            : d->stage_max_ns[i] / 1000);
        d->stage_sum_ns[i] = d->stage_max_ns[i] = 0;
        d->stage_frames[i] = 0;
    }
}

void rted_daemon_publish_status(rted_daemon *d)
{
    int64_t t = rte_clock_now_ns();
    /* param_state_t when due, before the status (which ends a run's log) */
    if (t >= d->state_due_ns)
        rted_param_state_publish(d);
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    rtedge_status_t *s = &d->status_msg;
    s->utime = rte_clock_wall_us(t);
    s->source_state = (int8_t)ss.state;
    d->reported_state = ss.state;
    s->frames_received = (int64_t)d->n.received;
    s->frames_processed = (int64_t)d->n.processed;
    d->n.bad_frames = ss.bad_frames;
    s->frames_dropped = (int64_t)(d->n.dropped + ss.driver_drops + ss.skipped);
    s->deadline_misses = (int64_t)d->n.deadline_misses;
    s->stages_skipped = (int64_t)d->n.stages_skipped;
    s->frames_bad = (int64_t)ss.bad_frames;
    s->source_reconnects = (int64_t)ss.reconnects;
    s->config_reloads = (int64_t)d->n.reloads;
    s->config_refused = (int64_t)d->n.refused;
    s->config_rate_limited = (int64_t)d->n.rate_limited;
    s->path_errors = (int64_t)d->n.path_errors;
    s->window_us = (t - d->window_start_ns) / 1000;
    window_latency(d, &s->latency_p50_us, &s->latency_p99_us, &s->latency_max_us);
    s->fps =
        s->window_us > 0 ? (float)((double)d->window_processed * 1e6 / (double)s->window_us) : 0.0f;
    s->arena_bytes = (int64_t)d->arena.size;
    s->arena_peak_bytes = (int64_t)d->arena.high_water;
    s->config_hash = (int64_t)d->config_hash;
    stage_times(d);
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (ss.state == RTE_SOURCE_STREAMING && d->n.received) {
        const int32_t fps10 = (int32_t)(s->fps * 10.0f + 0.5f);
        rted_notify_status(
            &d->notify, NULL, "streaming %s, %d.%d fps, p99 %d us, %lld deadline misses",
            d->source_id, fps10 / 10, fps10 % 10, s->latency_p99_us, (long long)s->deadline_misses);
    }
    if (rte_publish_status(d->pub, d->cfg.status_channel, s, msg, sizeof msg) == RTE_OK)
        d->n.status_sent++;
    else
        d->n.publish_errors++;
    d->ring_n = 0;
    d->window_max = 0;
    d->window_processed = 0;
    d->window_start_ns = t;
    rted_log_flush(&d->log_frames, t);
    rted_log_flush(&d->log_params, t);
}

/* The histogram bucket of v >= 0 microseconds, and the middle of a
 * bucket's range. */
static uint32_t hist_bucket(int32_t v)
{
    if (v < RTED_HIST_SUB)
        return (uint32_t)v;
    const uint32_t e = 31 - (uint32_t)__builtin_clz((uint32_t)v); /* >= 6 */
    const uint32_t shift = e - 6;
    return RTED_HIST_SUB + shift * RTED_HIST_SUB + (((uint32_t)v >> shift) - RTED_HIST_SUB);
}

static int32_t hist_value(uint32_t b)
{
    if (b < RTED_HIST_SUB)
        return (int32_t)b;
    const uint32_t shift = (b - RTED_HIST_SUB) / RTED_HIST_SUB;
    const uint32_t low = (RTED_HIST_SUB + (b - RTED_HIST_SUB) % RTED_HIST_SUB) << shift;
    return (int32_t)(low + ((1u << shift) >> 1));
}

/* The value of 0-based rank r of the run's latencies. */
static int32_t hist_rank(const rted_daemon *d, uint64_t r)
{
    uint64_t seen = 0;
    for (uint32_t b = 0; b < RTED_HIST_BUCKETS; b++) {
        seen += d->run_hist[b];
        if (seen > r)
            return hist_value(b) < d->run_max ? hist_value(b) : d->run_max;
    }
    return d->run_max;
}

void rted_daemon_latency(const rted_daemon *d, int32_t *p50, int32_t *p99, int32_t *max)
{
    *p50 = *p99 = *max = 0;
    if (d->run_n == 0)
        return;
    *p50 = hist_rank(d, (d->run_n - 1) * 50 / 100);
    *p99 = hist_rank(d, (d->run_n - 1) * 99 / 100);
    *max = d->run_max;
}

void rted_record_latency(rted_daemon *d, int64_t lat_ns)
{
    int64_t us = lat_ns / 1000;
    int32_t v = us > INT32_MAX ? INT32_MAX : us < 0 ? 0 : (int32_t)us;
    d->ring[d->ring_n % RTED_RING] = v;
    d->ring_n++;
    if (v > d->window_max)
        d->window_max = v;
    d->run_hist[hist_bucket(v)]++;
    d->run_n++;
    if (v > d->run_max)
        d->run_max = v;
}
