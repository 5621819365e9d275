/* Camera frames and their conversion to grey.
 *
 * An rte_frame describes one frame as the daemon's sources deliver it (V4L2
 * mmap buffers, libcamera requests, recorded files): a pixel format, a size
 * and up to two planes with byte strides. The memory belongs to the caller;
 * a frame is only a view of it, like rte_image_u8.
 *
 * The grey conversions are bit-exact with OpenCV 4.6's cv::cvtColor for 8-bit
 * data:
 *   BGR24 -> COLOR_BGR2GRAY, RGB24 -> COLOR_RGB2GRAY
 *       grey = (3735*B + 19235*G + 9798*R + 16384) >> 15  (BT.601 in Q15:
 *       OpenCV 4.6 uses these, not its Q14 table, for every 8-bit row)
 *   YUYV  -> COLOR_YUV2GRAY_YUY2, UYVY -> COLOR_YUV2GRAY_UYVY (the Y samples)
 *   NV12  -> COLOR_YUV2GRAY_NV12 (the Y plane)
 *   GREY  -> a copy. */
#ifndef RTEDGE_COLOR_H
#define RTEDGE_COLOR_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Formats name the byte order in memory (as V4L2 does; libcamera's and DRM's
 * "BGR888" is R,G,B in memory, i.e. RTE_PIXEL_RGB24). */
typedef enum rte_pixel_format {
    RTE_PIXEL_GREY = 1, /* 1 plane, 1 byte per pixel: Y (V4L2 GREY) */
    RTE_PIXEL_BGR24,    /* 1 plane, 3 bytes per pixel: B,G,R (V4L2 BGR3, OpenCV's order) */
    RTE_PIXEL_RGB24,    /* 1 plane, 3 bytes per pixel: R,G,B (V4L2 RGB3) */
    RTE_PIXEL_YUYV,     /* 1 plane, 2 bytes per pixel: Y0,U,Y1,V (V4L2 YUYV, OpenCV YUY2) */
    RTE_PIXEL_UYVY,     /* 1 plane, 2 bytes per pixel: U,Y0,V,Y1 (V4L2 UYVY) */
    RTE_PIXEL_NV12,     /* 2 planes: Y (width bytes per row), then interleaved U,V at
                           half resolution ((width+1)/2 pairs, (height+1)/2 rows) */
} rte_pixel_format;

#define RTE_FRAME_MAX_PLANES 2

/* One frame. plane[1]/stride[1] are used by NV12 only (set them to NULL/0
 * otherwise). Strides are in bytes. A YUYV or UYVY row holds 2*width bytes
 * (2 bytes per pixel, as a 2-channel cv::Mat); odd widths are allowed, as in
 * OpenCV. NV12 may have odd sizes too (OpenCV wants even ones). */
typedef struct rte_frame {
    rte_pixel_format format;
    int32_t width, height;
    uint8_t *plane[RTE_FRAME_MAX_PLANES];
    int32_t stride[RTE_FRAME_MAX_PLANES];
} rte_frame;

/* RTE_OK when the format is known, 1 <= width, height <= RTE_MAX_SIDE, the
 * planes the format uses are set and each stride holds a row. */
RTE_API rte_status rte_frame_check(const rte_frame *frame);

/* Bytes of one tightly packed frame (all planes, NV12's UV plane after its Y
 * plane), 0 for an unknown format or a size out of range. */
RTE_API size_t rte_frame_packed_size(rte_pixel_format format, int32_t width, int32_t height);

/* Fills *frame as a view of a tightly packed frame at `buf` (layout as in
 * rte_frame_packed_size: what a raw .yuv/.rgb file or a V4L2 buffer without
 * padding holds). RTE_ERR_SIZE when `size` is smaller than that. */
RTE_API rte_status rte_frame_packed(rte_frame *frame, rte_pixel_format format, int32_t width,
                                    int32_t height, void *buf, size_t size);

/* "grey", "bgr24", "rgb24", "yuyv", "uyvy", "nv12"; "unknown" otherwise. */
RTE_API const char *rte_pixel_format_name(rte_pixel_format format);
/* The format with that name (as above, case-insensitive, also "gray",
 * "yuy2"), or 0 when there is none. */
RTE_API rte_pixel_format rte_pixel_format_parse(const char *name);

/* Any supported frame to grey, written into dst (same width and height). */
RTE_API rte_status rte_frame_to_gray(const rte_frame *src, rte_image_u8 *dst);

/* For GREY and NV12 frames the grey image is already in memory: *view is set
 * to it without copying (RTE_ERR_UNSUPPORTED for the other formats). */
RTE_API rte_status rte_frame_gray_view(const rte_frame *src, rte_image_u8 *view);

/* The frame's colour as two chroma planes at half its size (cb and cr
 * both ((width + 1) / 2) x ((height + 1) / 2), 128 = no colour): NV12's
 * U and V as they are; YUYV's and UYVY's averaged over each block's two
 * rows; BGR24's and RGB24's as BT.601 full-range (JPEG) Cb and Cr of each
 * 2x2 block's mean colour. Rows and columns past an odd size repeat the
 * last. RTE_ERR_UNSUPPORTED for GREY frames (no colour). */
RTE_API rte_status rte_frame_chroma_half(const rte_frame *src, rte_image_u8 *cb, rte_image_u8 *cr);

/* The conversions one by one. src and dst have the same width and height. */
RTE_API rte_status rte_color_bgr_to_gray(const rte_image_u8c3 *src, rte_image_u8 *dst);
RTE_API rte_status rte_color_rgb_to_gray(const rte_image_u8c3 *src, rte_image_u8 *dst);
/* Packed 4:2:2: `src` rows of 2*dst->width bytes, `src_stride` bytes apart. */
RTE_API rte_status rte_color_yuyv_to_gray(const uint8_t *src, int32_t src_stride,
                                          rte_image_u8 *dst);
RTE_API rte_status rte_color_uyvy_to_gray(const uint8_t *src, int32_t src_stride,
                                          rte_image_u8 *dst);

#ifdef __cplusplus
}
#endif
#endif
