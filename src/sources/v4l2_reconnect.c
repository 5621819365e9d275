/* Losing a V4L2 device and reopening it: the source reports the loss
 * once, then each next() call waits for the next attempt (within its own
 * deadline) and tries, with the delay doubling up to the configured
 * maximum. A device missing at open (rte_v4l2_config.wait) is waited for
 * the same way. */
#include "sources/v4l2_internal.h"

#include <string.h>

#include "source_msg.h"

/* The device failed: close it, report, and reopen it later. */
rte_status rte_v4l2_device_lost(v4l2_source *s, const char *what, int err, char *msg,
                                size_t msg_size)
{
    rte_v4l2_stop_device(s);
    s->stats.state = RTE_SOURCE_RECONNECTING;
    s->stats.errors++;
    rte_retry_start(&s->retry, s->ops->now_ns(s->ops->ctx), s->cfg.reconnect_min_ms,
                    s->cfg.reconnect_max_ms);
    rte_source_msgf(msg, msg_size, "%s: %s: %s; reconnecting", s->info.path, what,
                    err ? strerror(err) : "error condition");
    return RTE_ERR_DEVICE;
}

void rte_v4l2_wait_for_device(v4l2_source *s, int32_t min_ms, int32_t max_ms)
{
    s->stats.state = RTE_SOURCE_RECONNECTING;
    rte_retry_start(&s->retry, s->ops->now_ns(s->ops->ctx), min_ms, max_ms);
}

/* Sleeps until the next attempt (within the caller's deadline), then tries
 * to reopen. RTE_OK when streaming again. */
rte_status rte_v4l2_reconnect(v4l2_source *s, int64_t deadline_ns, char *msg, size_t msg_size)
{
    int64_t now = s->ops->now_ns(s->ops->ctx);
    int64_t wake = s->retry.at_ns;
    if (deadline_ns >= 0 && deadline_ns < wake)
        wake = deadline_ns;
    if (wake > now)
        s->ops->poll(s->ops->ctx, NULL, 0, (int)((wake - now + 999999) / 1000000));
    now = s->ops->now_ns(s->ops->ctx);
    if (now < s->retry.at_ns) {
        rte_source_msgf(msg, msg_size, "%s: %s, next attempt in %lld ms", s->info.path,
                        s->streamed ? "reconnecting" : "waiting for the camera",
                        (long long)rte_retry_wait_ms(&s->retry, now));
        return RTE_ERR_TIMEOUT;
    }
    rte_status st = rte_v4l2_setup_device(s, true, msg, msg_size);
    if (st != RTE_OK) {
        s->stats.errors++;
        rte_retry_failed(&s->retry, now);
        rte_source_msg_append(msg, msg_size, "; retrying in %d ms", s->retry.delay_ms);
        return RTE_ERR_DEVICE;
    }
    s->stats.state = RTE_SOURCE_STREAMING;
    if (!s->streamed) /* the first time: not a reconnection */
        rte_v4l2_check_timestamps(s);
    else
        s->stats.reconnects++;
    s->streamed = true;
    return RTE_OK;
}
