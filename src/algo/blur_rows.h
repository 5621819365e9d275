/* Border handling shared by the blur kernels (private to src/algo): source
 * rows are copied into a padded row once, so the filter loops read
 * neighbours without any border test. */
#ifndef RTEDGE_ALGO_BLUR_ROWS_H
#define RTEDGE_ALGO_BLUR_ROWS_H

#include <stdint.h>
#include <string.h>

#include "rtedge/image.h"

/* Valid, equally sized views; working in place is allowed only on the very
 * same view (same buf and stride), which both kernels support. */
static inline rte_status rte_blur_check_views(const rte_image_u8 *src, const rte_image_u8 *dst)
{
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st == RTE_OK && src->buf == dst->buf && src->stride != dst->stride)
        return RTE_ERR_ARGUMENT;
    return st;
}

/* OpenCV's borderInterpolate for BORDER_REFLECT_101 (gfedcb|abcdefgh|gfedcba):
 * reflects repeatedly, so it also works when i is more than n away; n == 1
 * always gives 0. */
static inline int32_t rte_blur_reflect101(int32_t i, int32_t n)
{
    if (n == 1)
        return 0;
    while (i < 0 || i >= n) {
        if (i < 0)
            i = -i;
        if (i >= n)
            i = 2 * n - 2 - i;
    }
    return i;
}

static inline int32_t rte_blur_clamp(int32_t i, int32_t n)
{
    return i < 0 ? 0 : i >= n ? n - 1 : i;
}

/* line[r .. r + width) holds a row; fills line[0 .. r) and
 * line[r + width .. width + 2r) with its BORDER_REFLECT_101 continuation. */
static inline void rte_blur_reflect101_borders_u16(uint16_t *line, int32_t width, int32_t r)
{
    for (int32_t i = 1; i <= r; i++) {
        line[r - i] = line[r + rte_blur_reflect101(-i, width)];
        line[r + width - 1 + i] = line[r + rte_blur_reflect101(width - 1 + i, width)];
    }
}

/* pad[0 .. width + 2r) = row[clamp(x - r)] (BORDER_REPLICATE). */
static inline void rte_blur_pad_row_replicate(const uint8_t *row, uint8_t *pad, int32_t width,
                                              int32_t r)
{
    memcpy(pad + r, row, (size_t)width);
    for (int32_t i = 1; i <= r; i++) {
        pad[r - i] = row[0];
        pad[r + width - 1 + i] = row[width - 1];
    }
}

#endif
