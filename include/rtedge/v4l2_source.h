/* V4L2 camera source: plain ioctls on a /dev/videoN capture node with mmap
 * streaming, as a frame source for the daemon (see source.h).
 *
 * Open negotiates the format, size and frame rate, sets controls, maps the
 * driver's buffers and starts streaming; it allocates everything the source
 * will ever need. rte_source_next() then always hands out the NEWEST frame:
 * older ready frames are given back to the driver and counted as skipped.
 * When the device fails (ENODEV, EIO, POLLERR) the source closes it, reports
 * RTE_ERR_DEVICE once and reopens it with backoff on later next() calls,
 * without allocating (the new buffers must fit the open-time sizes).
 *
 * Every syscall goes through an rte_v4l2_ops table so the logic can be
 * driven by a scripted fake in the unit tests. */
#ifndef RTEDGE_V4L2_SOURCE_H
#define RTEDGE_V4L2_SOURCE_H

#include <poll.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/types.h>

#include "rtedge/source.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RTE_V4L2_MAX_BUFFERS 32
#define RTE_V4L2_MAX_CONTROLS 16
#define RTE_V4L2_NAME_SIZE 32

/* The syscalls, with their usual meaning and errno convention. `ctx` is
 * passed through to every call. */
typedef struct rte_v4l2_ops {
    int (*open)(void *ctx, const char *path, int flags);
    int (*close)(void *ctx, int fd);
    int (*ioctl)(void *ctx, int fd, unsigned long request, void *arg);
    /* fds == NULL, nfds == 0 sleeps (used for the reconnect backoff). */
    int (*poll)(void *ctx, struct pollfd *fds, nfds_t nfds, int timeout_ms);
    void *(*mmap)(void *ctx, size_t length, int prot, int flags, int fd, off_t offset);
    int (*munmap)(void *ctx, void *addr, size_t length);
    int64_t (*now_ns)(void *ctx); /* CLOCK_MONOTONIC */
    void *ctx;
} rte_v4l2_ops;

/* The real syscalls. */
RTE_API extern const rte_v4l2_ops rte_v4l2_system_ops;

typedef struct rte_v4l2_control {
    char name[RTE_V4L2_NAME_SIZE]; /* matched case-insensitively; runs of spaces, underscores and
                                      punctuation are equivalent ("white_balance_automatic" is
                                      "White Balance, Automatic"), as v4l2-ctl names them */
    int32_t value;
} rte_v4l2_control;

typedef struct rte_v4l2_config {
    /* "/dev/video0" (any path with a '/'), or a name matched against the
     * card (as the controls' names are) or the exact bus_info of the
     * capture nodes /dev/video0..63: "vivid", "platform:vivid-000". */
    const char *device;
    /* What the camera sends: V4L2_PIX_FMT_YUYV, _UYVY, _GREY, _NV12 or
     * _MJPEG (0: YUYV). */
    uint32_t fourcc;
    /* For MJPEG, what the frames are decoded to: RTE_PIXEL_GREY or
     * RTE_PIXEL_BGR24 (0: GREY). Ignored for the raw formats. */
    rte_pixel_format decode_to;
    int32_t width, height;    /* requested; the driver may adjust them */
    int32_t fps;              /* requested frames per second; 0 keeps the driver's */
    int32_t buffers;          /* mmap buffers, 2..RTE_V4L2_MAX_BUFFERS (0: 4) */
    int32_t reconnect_min_ms; /* first reopening delay after a loss (0: 100) */
    int32_t reconnect_max_ms; /* the delay doubles up to this (0: 2000) */
    /* A device missing at open (no such node, no card of that name, a node
     * that fails its set-up) is waited for: open succeeds with the source
     * RTE_SOURCE_RECONNECTING and sized for width x height in fourcc, and
     * next() tries the device with the reconnection's backoff, from 500 ms
     * doubling to 8 s. The device must then stream that format at most
     * that size. false: open fails. */
    bool wait;
    int32_t n_controls;
    rte_v4l2_control controls[RTE_V4L2_MAX_CONTROLS]; /* set at open and at each reopening */
    const rte_v4l2_ops *ops;                          /* NULL: rte_v4l2_system_ops */
} rte_v4l2_config;

/* What open found and the driver settled on. */
typedef struct rte_v4l2_info {
    char path[RTE_V4L2_NAME_SIZE];
    char driver[16], card[RTE_V4L2_NAME_SIZE], bus_info[RTE_V4L2_NAME_SIZE];
    uint32_t fourcc;       /* the format streamed (may differ from the config's) */
    int32_t width, height; /* as adjusted by the driver */
    int32_t bytesperline;  /* stride of the first plane */
    uint32_t sizeimage;
    uint32_t interval_num, interval_den; /* time per frame in seconds (0/0: unknown) */
    int32_t buffers;                     /* buffers the driver granted */
    bool timestamps_monotonic; /* false: the driver's timestamps are not CLOCK_MONOTONIC and
                                     capture_ns is taken when the buffer is dequeued */
    bool adjusted;             /* the driver changed the size, format or frame rate */
} rte_v4l2_info;

/* Opens the camera and starts streaming. `info` (may be NULL) receives what
 * the driver settled on; `msg` says it in words (adjustments included) or
 * what failed. On failure nothing is left open. */
RTE_API rte_status rte_v4l2_source_open(rte_source *source, const rte_v4l2_config *config,
                                        rte_v4l2_info *info, char *msg, size_t msg_size);

/* Sets one control by name while streaming (e.g. exposure from the
 * daemon's command channel); the same matching as in the config.
 * RTE_ERR_ARGUMENT when there is no such control or the value is out of its
 * range, RTE_ERR_DEVICE when the device is gone. */
RTE_API rte_status rte_v4l2_source_set_control(rte_source *source, const char *name, int32_t value,
                                               char *msg, size_t msg_size);

/* Sets one control by name on a device that another file handle (another
 * process) may be streaming from: opens `device` (a path or a name, as in
 * rte_v4l2_config), sets the control and closes it again. ops: NULL for
 * the real syscalls. The same errors as rte_v4l2_source_set_control. */
RTE_API rte_status rte_v4l2_set_device_control(const char *device, const char *name, int32_t value,
                                               const rte_v4l2_ops *ops, char *msg, size_t msg_size);

/* "YUYV", "MJPG", ... into buf[5]. */
RTE_API const char *rte_v4l2_fourcc_name(uint32_t fourcc, char buf[5]);

/* Lists the capture nodes /dev/video0..63 with their formats, frame sizes
 * and frame intervals, one device per paragraph. Returns the number of
 * capture devices found. */
RTE_API int rte_v4l2_list(FILE *out, const rte_v4l2_ops *ops);

/* For `rtedged --list-cameras`: V4L2 devices, then the libcamera cameras
 * when rtedge is built with libcamera. Returns the number of cameras. */
RTE_API int rte_list_cameras(FILE *out);

#ifdef __cplusplus
}
#endif
#endif
