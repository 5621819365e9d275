/* The monotonic clock every part of rtedge times with (stage timings,
 * pacing, deadlines, rate limits), and the wall clock of its instants.
 * Internal: not an installed header. */
#ifndef RTEDGE_CORE_CLOCK_H
#define RTEDGE_CORE_CLOCK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* CLOCK_MONOTONIC in nanoseconds. */
int64_t rte_clock_now_ns(void);
/* The wall clock (CLOCK_REALTIME, microseconds since the epoch) at the
 * CLOCK_MONOTONIC instant mono_ns, for messages whose `utime` is bot_core's
 * wall-clock time. */
int64_t rte_clock_wall_us(int64_t mono_ns);

#ifdef __cplusplus
}
#endif
#endif
