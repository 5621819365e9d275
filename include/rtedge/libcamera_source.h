/* libcamera camera source (built when meson's `libcamera` feature finds
 * libcamera; without it rte_libcamera_source_open() is RTE_ERR_UNSUPPORTED
 * and rte_libcamera_list() lists nothing). A small C++ shim behind
 * a C interface: one stream, a request per buffer, the completed buffers
 * mapped and handed out as views (newest first, like the V4L2 source). */
#ifndef RTEDGE_LIBCAMERA_SOURCE_H
#define RTEDGE_LIBCAMERA_SOURCE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "rtedge/source.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RTE_LIBCAMERA_MAX_BUFFERS 16
#define RTE_LIBCAMERA_ID_SIZE 128

typedef struct rte_libcamera_config {
    const char *camera; /* the camera's id (as `cam -l` shows it); NULL: by index */
    int32_t index;      /* position in the camera manager's list when camera is NULL */
    /* RTE_PIXEL_GREY (R8), _RGB24 (BGR888), _BGR24 (RGB888), _YUYV, _UYVY
     * or _NV12 (0: the camera's default, which must be one of these). */
    rte_pixel_format format;
    int32_t width, height; /* 0, 0: the camera's default size */
    int32_t buffers;       /* 2..RTE_LIBCAMERA_MAX_BUFFERS (0: 4) */
} rte_libcamera_config;

typedef struct rte_libcamera_info {
    char id[RTE_LIBCAMERA_ID_SIZE];
    rte_pixel_format format;
    int32_t width, height, stride;
    int32_t buffers;
    bool adjusted; /* libcamera changed the size or format asked for */
} rte_libcamera_info;

/* Starts the camera manager, acquires and configures the camera, allocates
 * and maps its buffers and starts capturing. `msg` says what was set up
 * (adjustments included) or what failed. A camera that disconnects ends
 * the source (RTE_ERR_DEVICE, state RTE_SOURCE_FAILED): unlike the V4L2
 * source it is not reopened. rte_source_close() stops the camera and
 * releases it. */
RTE_API rte_status rte_libcamera_source_open(rte_source *source, const rte_libcamera_config *config,
                                             rte_libcamera_info *info, char *msg, size_t msg_size);

/* Lists the libcamera cameras with their stream formats and sizes. Returns
 * the number of cameras (0 also when the camera manager does not start).
 * Not while a libcamera source is open: libcamera allows one camera
 * manager per process. */
RTE_API int rte_libcamera_list(FILE *out);

#ifdef __cplusplus
}
#endif
#endif
