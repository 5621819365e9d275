/* A camera that may not be there yet, as a source: it reports
 * RTE_SOURCE_RECONNECTING and calls its opener again on next() calls, the
 * delay doubling from retry_min_ms to retry_max_ms, until the camera
 * opens; from then on it is that camera. For cameras without a reconnect
 * of their own (libcamera; the V4L2 source waits by itself).
 *
 * The size and format are announced at open (the daemon sizes its buffers
 * from them): a camera that comes up larger or in another format is closed
 * again, refused with the reason, and tried again later. Opening the
 * camera allocates what it needs, as its own open does. */
#ifndef RTEDGE_WAITING_SOURCE_H
#define RTEDGE_WAITING_SOURCE_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/source.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rte_waiting_config {
    /* Opens the camera into *source; RTE_OK or why not in msg. */
    rte_status (*open)(void *ctx, rte_source *source, char *msg, size_t msg_size);
    void *ctx;
    const char *name;              /* the camera, for messages */
    int32_t max_width, max_height; /* announced; the camera's frames must fit */
    rte_pixel_format format;       /* announced; the camera's must be this one */
    int32_t retry_min_ms;          /* first delay (0: 500) */
    int32_t retry_max_ms;          /* the delay doubles up to this (0: 8000) */
    /* Clock and sleep; NULL: CLOCK_MONOTONIC and nanosleep. */
    int64_t (*now_ns)(void *ctx);
    void (*sleep_ms)(void *ctx, int32_t ms);
} rte_waiting_config;

/* The waiting source in *source (nothing opened yet: the first attempt is
 * made retry_min_ms from now). The opener and ctx must outlive it.
 * RTE_ERR_ARGUMENT for a bad configuration, RTE_ERR_NO_MEMORY. */
rte_status rte_waiting_source_open(rte_source *source, const rte_waiting_config *config, char *msg,
                                   size_t msg_size);

#ifdef __cplusplus
}
#endif
#endif
