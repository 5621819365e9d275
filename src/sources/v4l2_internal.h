/* What the files of the V4L2 source share (internal to src/sources; the
 * API is v4l2_source.h). The files, in the order a camera is used:
 *
 *   v4l2.c            the real syscalls, the shared helpers, open, close
 *   v4l2_negotiate.c  finding the node, format and frame rate, and the
 *                     whole set-up from open(2) to STREAMON
 *   v4l2_controls.c   controls by name
 *   v4l2_stream.c     the mmap buffers and next(): dequeueing, the newest
 *                     frame, MJPEG decoding
 *   v4l2_reconnect.c  a device lost and reopened with backoff
 *   v4l2_list.c       listing the capture nodes */
#ifndef RTEDGE_V4L2_INTERNAL_H
#define RTEDGE_V4L2_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <linux/videodev2.h>
#include <turbojpeg.h>

#include "retry.h"
#include "rtedge/v4l2_source.h"

/* Nodes looked at when a device is named by card or bus: /dev/video0..63. */
#define MAX_DEVICE_NODES 64

typedef struct v4l2_mapping {
    void *start;
    size_t length;
} v4l2_mapping;

typedef struct v4l2_source {
    rte_v4l2_config cfg;
    char device[64]; /* cfg.device points here */
    const rte_v4l2_ops *ops;
    int fd; /* -1 while the device is lost */
    rte_v4l2_info info;

    /* Fixed at open: what a reopened device must fit into. */
    uint32_t open_fourcc;
    rte_pixel_format out_format;
    int32_t max_width, max_height;

    v4l2_mapping buf[RTE_V4L2_MAX_BUFFERS];
    int32_t n_buf;
    int32_t held; /* buffer handed out by the last next(), -1: none */

    /* Sequence bookkeeping, reset when the device is reopened. */
    bool have_seq;
    uint32_t last_seq; /* last sequence dequeued */
    bool have_delivered;
    uint32_t last_delivered; /* last sequence handed out */

    rte_retry retry; /* reconnection, or the wait at open */
    bool streamed;   /* false while a device missing at open is waited for */
    rte_source_stats stats;

    tjhandle tj; /* MJPEG only */
    uint8_t *decoded;
    size_t decoded_size;
} v4l2_source;

/* ---- v4l2.c ---- */

/* The source's rte_source_ops (set_control checks a source against it). */
extern const rte_source_ops rte_v4l2_source_ops;

/* Copies the string in src (src_size bytes at most, NUL or not) into dst,
 * truncated to fit and NUL-terminated. */
void rte_v4l2_copy_string(char *dst, size_t size, const void *src, size_t src_size);
/* True when two control or card names are the same as v4l2-ctl spells
 * them. */
bool rte_v4l2_names_equal(const char *a, const char *b);
/* ioctl on the source's fd through its ops, retried on EINTR. */
int rte_v4l2_xioctl(v4l2_source *s, unsigned long request, void *arg);
/* Closes the fd, if open; fd is -1 after. */
void rte_v4l2_close_fd(v4l2_source *s);
/* Once streaming: whether the driver's timestamps are CLOCK_MONOTONIC. */
void rte_v4l2_check_timestamps(v4l2_source *s);

/* ---- v4l2_negotiate.c ---- */

/* What rtedge delivers for a V4L2 format (0: a format it does not read). */
rte_pixel_format rte_v4l2_delivered_format(uint32_t fourcc, rte_pixel_format decode_to);
/* Bytes a raw frame of the negotiated layout needs in its buffer. */
size_t rte_v4l2_raw_frame_bytes(const rte_v4l2_info *info);
/* QUERYCAP on the open fd: RTE_OK for a capture node with streaming I/O. */
rte_status rte_v4l2_query_node(v4l2_source *s, struct v4l2_capability *cap);
/* Opens cfg.device and fills info's path, driver, card and bus_info. */
rte_status rte_v4l2_open_node(v4l2_source *s, char *msg, size_t msg_size);
/* Everything from open(2) to STREAMON; reopening: the device must fit the
 * sizes fixed at open. */
rte_status rte_v4l2_setup_device(v4l2_source *s, bool reopening, char *msg, size_t msg_size);

/* ---- v4l2_controls.c ---- */

rte_status rte_v4l2_set_control(v4l2_source *s, const char *name, int32_t value, char *msg,
                                size_t msg_size);
/* Sets the configured controls, in order; stops at the first failure. */
rte_status rte_v4l2_apply_controls(v4l2_source *s, char *msg, size_t msg_size);

/* ---- v4l2_stream.c ---- */

/* REQBUFS, QUERYBUF and mmap of every buffer, QBUF of all, STREAMON. */
rte_status rte_v4l2_start_streaming(v4l2_source *s, char *msg, size_t msg_size);
void rte_v4l2_stop_device(v4l2_source *s);
/* rte_source_ops.next. */
rte_status rte_v4l2_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                         size_t msg_size);

/* ---- v4l2_reconnect.c ---- */

rte_status rte_v4l2_device_lost(v4l2_source *s, const char *what, int err, char *msg,
                                size_t msg_size);
/* A device missing at open (cfg.wait): waited for with backoff from
 * min_ms doubling to max_ms. */
void rte_v4l2_wait_for_device(v4l2_source *s, int32_t min_ms, int32_t max_ms);
rte_status rte_v4l2_reconnect(v4l2_source *s, int64_t deadline_ns, char *msg, size_t msg_size);

#endif
