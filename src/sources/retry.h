/* Retrying with a delay that doubles up to a maximum: the V4L2 source's
 * reconnection and the waiting source's first open share it. */
#ifndef RTEDGE_SOURCES_RETRY_H
#define RTEDGE_SOURCES_RETRY_H

#include <stdint.h>

typedef struct rte_retry {
    int64_t at_ns; /* the next attempt */
    int32_t delay_ms, max_ms;
} rte_retry;

/* The first attempt min_ms after now_ns; later ones up to max_ms apart. */
static inline void rte_retry_start(rte_retry *r, int64_t now_ns, int32_t min_ms, int32_t max_ms)
{
    r->delay_ms = min_ms;
    r->max_ms = max_ms;
    r->at_ns = now_ns + (int64_t)min_ms * 1000000;
}

/* An attempt failed at now_ns: the next one after twice the delay (at most
 * max_ms). */
static inline void rte_retry_failed(rte_retry *r, int64_t now_ns)
{
    r->delay_ms = r->delay_ms > r->max_ms / 2 ? r->max_ms : 2 * r->delay_ms;
    r->at_ns = now_ns + (int64_t)r->delay_ms * 1000000;
}

/* Whole milliseconds from now_ns to the next attempt, rounded up; 0 when
 * it is due. */
static inline int64_t rte_retry_wait_ms(const rte_retry *r, int64_t now_ns)
{
    return now_ns < r->at_ns ? (r->at_ns - now_ns + 999999) / 1000000 : 0;
}

#endif
