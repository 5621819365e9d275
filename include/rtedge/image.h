/* Image views: a size, a stride and a pointer to memory the caller owns.
 *
 * The stride is counted in elements (pixels of the element type), not bytes,
 * and is >= width. Row y starts at buf + y * stride. rtedge never allocates
 * or frees image memory: a view only describes it. */
#ifndef RTEDGE_IMAGE_H
#define RTEDGE_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest side rtedge accepts anywhere; keeps every index and
 * width * height product inside int32_t. */
#define RTE_MAX_SIDE 32767

typedef struct rte_image_u8 {
    int32_t width, height, stride;
    uint8_t *buf;
} rte_image_u8;

typedef struct rte_image_s16 {
    int32_t width, height, stride;
    int16_t *buf;
} rte_image_s16;

typedef struct rte_image_u16 {
    int32_t width, height, stride;
    uint16_t *buf;
} rte_image_u16;

typedef struct rte_image_s32 {
    int32_t width, height, stride;
    int32_t *buf;
} rte_image_s32;

/* Interleaved 3-channel 8-bit image (BGR or RGB); stride in bytes. */
typedef struct rte_image_u8c3 {
    int32_t width, height, stride;
    uint8_t *buf;
} rte_image_u8c3;

/* A view of caller memory; stride 0 means tightly packed. */
RTE_API rte_image_u8 rte_image_u8_view(void *buf, int32_t width, int32_t height, int32_t stride);
RTE_API rte_image_s16 rte_image_s16_view(void *buf, int32_t width, int32_t height, int32_t stride);

/* RTE_OK when 1 <= width, height <= RTE_MAX_SIDE, stride >= width and buf is set. */
RTE_API rte_status rte_image_u8_check(const rte_image_u8 *img);
RTE_API rte_status rte_image_s16_check(const rte_image_s16 *img);
RTE_API rte_status rte_image_u16_check(const rte_image_u16 *img);
RTE_API rte_status rte_image_u8c3_check(const rte_image_u8c3 *img);

/* RTE_OK when both are valid and have the same width and height. */
RTE_API rte_status rte_image_u8_check_pair(const rte_image_u8 *a, const rte_image_u8 *b);

static inline uint8_t *rte_u8_row(const rte_image_u8 *img, int32_t y)
{
    return img->buf + (ptrdiff_t)y * img->stride;
}

static inline int16_t *rte_s16_row(const rte_image_s16 *img, int32_t y)
{
    return img->buf + (ptrdiff_t)y * img->stride;
}

static inline uint16_t *rte_u16_row(const rte_image_u16 *img, int32_t y)
{
    return img->buf + (ptrdiff_t)y * img->stride;
}

#ifdef __cplusplus
}
#endif
#endif
