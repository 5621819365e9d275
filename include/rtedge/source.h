/* Frame sources: cameras (V4L2, libcamera) and recordings (image files,
 * Y4M, raw dumps, LCM logs), all behind one interface so the daemon's loop
 * does not care where frames come from.
 *
 * A source is opened by its own function (rte_v4l2_source_open, ...), which
 * allocates everything it will ever need for the configured maximum frame
 * size; rte_source_next() then hands out frames without allocating. A frame
 * is a view of the source's own buffer and stays valid until the next call
 * of rte_source_next() or rte_source_close() on that source. */
#ifndef RTEDGE_SOURCE_H
#define RTEDGE_SOURCE_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/color.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Room for any source message. */
#define RTE_SOURCE_MESSAGE_SIZE 256

typedef struct rte_source_frame {
    rte_frame frame;     /* pixels: a view of the source's buffer */
    int64_t capture_ns;  /* capture time on CLOCK_MONOTONIC (for recordings: when it was read) */
    int64_t recorded_ns; /* the recording's own timestamp (pacing); live sources: = capture_ns */
    uint64_t sequence;   /* the source's frame number: the driver's, or the index in a recording */
    uint32_t dropped;    /* frames lost just before this one, as far as the source can tell
                             (gaps in the driver's sequence numbers and older frames skipped
                             in favour of this one) */
} rte_source_frame;

typedef enum rte_source_state {
    RTE_SOURCE_STREAMING = 0, /* frames are coming */
    RTE_SOURCE_RECONNECTING,  /* a device went away; it is being reopened with backoff */
    RTE_SOURCE_ENDED,         /* a recording is finished */
    RTE_SOURCE_FAILED,        /* cannot go on */
} rte_source_state;

/* Counters a source keeps for the daemon's status message. */
typedef struct rte_source_stats {
    rte_source_state state;
    uint64_t frames;       /* frames handed out */
    uint64_t driver_drops; /* frames the driver or recording lost (sequence gaps) */
    uint64_t skipped;      /* frames that were ready but not handed out because a newer one
                               was (live sources deliver the newest frame) */
    uint64_t bad_frames;   /* frames skipped because they could not be decoded */
    uint64_t reconnects;   /* successful reopenings after a device loss */
    uint64_t errors;       /* errors reported through next() */
} rte_source_stats;

typedef struct rte_source_ops {
    const char *kind; /* "v4l2", "libcamera", "images", "y4m", "raw", "lcm-log", "lcm" */
    /* Waits up to timeout_ms (-1: no limit) for the next frame. Returns
     * RTE_OK with *frame filled; RTE_ERR_TIMEOUT when nothing came;
     * RTE_ERR_END at the end of a recording; RTE_ERR_DEVICE when a device
     * failed (the source then reopens it on later calls, with backoff);
     * RTE_ERR_FORMAT/_CORRUPT/_TRUNCATED for a frame that could not be read
     * (skipped and counted: the next call goes on with the frame after it).
     * msg (may be NULL) says what happened. */
    rte_status (*next)(void *impl, rte_source_frame *frame, int32_t timeout_ms, char *msg,
                       size_t msg_size);
    void (*get_stats)(const void *impl, rte_source_stats *stats);
    void (*close)(void *impl);
} rte_source_ops;

typedef struct rte_source {
    const rte_source_ops *ops;
    void *impl;
    /* The largest frame this source can deliver (fixed at open): the daemon
     * sizes its buffers from it. */
    int32_t max_width, max_height;
    rte_pixel_format format; /* the format of the frames it delivers */
} rte_source;

static inline rte_status rte_source_next(rte_source *source, rte_source_frame *frame,
                                         int32_t timeout_ms, char *msg, size_t msg_size)
{
    return source->ops->next(source->impl, frame, timeout_ms, msg, msg_size);
}

static inline void rte_source_get_stats(const rte_source *source, rte_source_stats *stats)
{
    source->ops->get_stats(source->impl, stats);
}

/* Frees everything the source holds; the rte_source is zeroed. */
static inline void rte_source_close(rte_source *source)
{
    if (source->ops)
        source->ops->close(source->impl);
    source->ops = NULL;
    source->impl = NULL;
}

#ifdef __cplusplus
}
#endif
#endif
