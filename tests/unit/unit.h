/* Helpers shared by the CMocka unit tests. */
#ifndef RTEDGE_TESTS_UNIT_H
#define RTEDGE_TESTS_UNIT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "rtedge/image.h"

/* An image of w x h with `pad` extra elements per row; the padding is filled
 * with 0xEE so a kernel that writes past its width shows up. */
static inline rte_image_u8 unit_image_u8(int32_t w, int32_t h, int32_t pad, uint8_t fill)
{
    int32_t stride = w + pad;
    uint8_t *buf = (uint8_t *)test_malloc((size_t)stride * h);
    memset(buf, 0xEE, (size_t)stride * h);
    for (int32_t y = 0; y < h; y++)
        memset(buf + (size_t)y * stride, fill, (size_t)w);
    rte_image_u8 img = {w, h, stride, buf};
    return img;
}

static inline rte_image_s16 unit_image_s16(int32_t w, int32_t h, int32_t pad)
{
    int32_t stride = w + pad;
    int16_t *buf = (int16_t *)test_malloc((size_t)stride * h * sizeof(int16_t));
    for (size_t i = 0; i < (size_t)stride * h; i++)
        buf[i] = (int16_t)0x7EEE;
    rte_image_s16 img = {w, h, stride, buf};
    return img;
}

/* Asserts that the padding of every row still holds 0xEE. */
static inline void unit_assert_padding_u8(const rte_image_u8 *img)
{
    for (int32_t y = 0; y < img->height; y++)
        for (int32_t x = img->width; x < img->stride; x++)
            assert_int_equal(img->buf[(size_t)y * img->stride + x], 0xEE);
}

static inline void unit_assert_padding_s16(const rte_image_s16 *img)
{
    for (int32_t y = 0; y < img->height; y++)
        for (int32_t x = img->width; x < img->stride; x++)
            assert_int_equal(img->buf[(size_t)y * img->stride + x], (int16_t)0x7EEE);
}

/* A small deterministic generator for random cases (xorshift32). */
static inline uint32_t unit_rand(uint32_t *state)
{
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return *state = x;
}

#endif
