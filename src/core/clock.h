/* The monotonic clock every part of rtedge times with (stage timings,
 * pacing, deadlines, rate limits). Internal: not an installed header. */
#ifndef RTEDGE_CORE_CLOCK_H
#define RTEDGE_CORE_CLOCK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* CLOCK_MONOTONIC in nanoseconds. */
int64_t rte_clock_now_ns(void);

#ifdef __cplusplus
}
#endif
#endif
