/* Publishing the daemon's messages over LCM (lcmtypes/, package rtedge).
 *
 * A publisher is created once for an LCM URL and the largest messages it
 * will send (rte_publish_limits); it allocates then, once, one encode buffer
 * large enough for any of them. Publishing a message encodes it into that
 * buffer with lcm-gen's _encode (the generated _publish would allocate one
 * buffer per call) and hands the bytes on without allocating:
 *
 *   udpm://...   lcm_publish (liblcm 1.3.1 sends from the caller's buffer
 *                with sendmsg: no heap call, measured in tests/lcm).
 *   memq://      lcm_publish; no heap call while nobody in the process has
 *                subscribed to the channel; with a subscriber, three mallocs
 *                per message (measured: memq queues a copy of it), freed by
 *                lcm_handle. memq is an in-process test transport.
 *   file://PATH  written here, not through liblcm: liblcm's log provider
 *                callocs an event (channel + data) and frees it for every
 *                message. The file is the LCM log format (lcm-logplayer,
 *                lcm_eventlog and lcm-gen's readers read it), one writev()
 *                per event from a preallocated event header. Options:
 *                ?mode=w (truncate, default) or ?mode=a (append).
 *
 * Nothing waits for subscribers: udpm sends a datagram (the kernel drops it
 * when nobody listens), memq queues, file:// writes to the file. A publisher
 * is for one thread. */
#ifndef RTEDGE_PUBLISH_H
#define RTEDGE_PUBLISH_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "rtedge/status.h"
#include "rtedge_grasp_detection_t.h"
#include "rtedge_image_t.h"
#include "rtedge_lane_detection_t.h"
#include "rtedge_param_state_t.h"
#include "rtedge_params_t.h"
#include "rtedge_status_t.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RTE_PUBLISH_MESSAGE_SIZE 256
/* status_t.nstages at most. */
#define RTE_PUBLISH_MAX_STAGES 16

/* The largest message of each kind the publisher must carry. Messages
 * beyond them are refused (RTE_ERR_TOO_LARGE): the caller bounds its arrays
 * and sets the message's *_truncated flag. */
typedef struct rte_publish_limits {
    int32_t max_text;        /* bytes of any string field (source_id), NUL excluded */
    int32_t max_roi_points;  /* header.roi_npoints */
    int32_t max_segments;    /* lane_detection_t.nsegments */
    int32_t max_objects;     /* grasp_detection_t.nobjects */
    int32_t max_params;      /* params_t.nparams */
    int32_t max_image_bytes; /* image_t.size (0: images are not published) */
    int32_t max_metadata;    /* image_t.nmetadata, each at most max_text bytes of key and value */
    int32_t max_state_bytes; /* an encoded param_state_t (0: none is published) */
} rte_publish_limits;

typedef struct rte_publish_stats {
    uint64_t messages; /* published */
    uint64_t bytes;    /* encoded bytes published */
    uint64_t refused;  /* over the limits or failed to send */
} rte_publish_stats;

typedef struct rte_publisher rte_publisher;

/* Opens `url` (memq://, udpm://..., file://PATH[?mode=w|a]) and allocates
 * the encode buffer. */
rte_status rte_publisher_create(rte_publisher **out, const char *url,
                                const rte_publish_limits *limits, char *msg, size_t msg_size);
void rte_publisher_destroy(rte_publisher *pub);

/* The encode buffer's size: the largest encoded message within the limits. */
size_t rte_publisher_buffer_size(const rte_publisher *pub);

rte_status rte_publish_lane(rte_publisher *pub, const char *channel,
                            const rtedge_lane_detection_t *m, char *msg, size_t msg_size);
rte_status rte_publish_grasp(rte_publisher *pub, const char *channel,
                             const rtedge_grasp_detection_t *m, char *msg, size_t msg_size);
rte_status rte_publish_status(rte_publisher *pub, const char *channel, const rtedge_status_t *m,
                              char *msg, size_t msg_size);
rte_status rte_publish_image(rte_publisher *pub, const char *channel, const rtedge_image_t *m,
                             char *msg, size_t msg_size);
rte_status rte_publish_params(rte_publisher *pub, const char *channel, const rtedge_params_t *m,
                              char *msg, size_t msg_size);
/* The caller's message, whole: its encoded size at most max_state_bytes. */
rte_status rte_publish_param_state(rte_publisher *pub, const char *channel,
                                   const rtedge_param_state_t *m, char *msg, size_t msg_size);

/* The publisher's lcm_t (memq://, udpm://) for subscribing on the same
 * instance (memq delivers only within it); NULL for file://. */
lcm_t *rte_publisher_lcm(rte_publisher *pub);

void rte_publisher_get_stats(const rte_publisher *pub, rte_publish_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
