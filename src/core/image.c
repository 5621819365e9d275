#include "rtedge/image.h"

#include "core/image_checks.h"

rte_image_u8 rte_image_u8_view(void *buf, int32_t width, int32_t height, int32_t stride)
{
    rte_image_u8 img = {width, height, stride ? stride : width, (uint8_t *)buf};
    return img;
}

rte_image_s16 rte_image_s16_view(void *buf, int32_t width, int32_t height, int32_t stride)
{
    rte_image_s16 img = {width, height, stride ? stride : width, (int16_t *)buf};
    return img;
}

static rte_status check_view(const void *buf, int32_t width, int32_t height, int32_t stride,
                             int32_t min_stride)
{
    if (!buf)
        return RTE_ERR_ARGUMENT;
    if (width < 1 || height < 1 || width > RTE_MAX_SIDE || height > RTE_MAX_SIDE)
        return RTE_ERR_SIZE;
    if (stride < min_stride)
        return RTE_ERR_SIZE;
    return RTE_OK;
}

rte_status rte_image_u8_check(const rte_image_u8 *img)
{
    return img ? check_view(img->buf, img->width, img->height, img->stride, img->width)
               : RTE_ERR_ARGUMENT;
}

rte_status rte_image_s16_check(const rte_image_s16 *img)
{
    return img ? check_view(img->buf, img->width, img->height, img->stride, img->width)
               : RTE_ERR_ARGUMENT;
}

rte_status rte_image_u16_check(const rte_image_u16 *img)
{
    return img ? check_view(img->buf, img->width, img->height, img->stride, img->width)
               : RTE_ERR_ARGUMENT;
}

rte_status rte_image_u8c3_check(const rte_image_u8c3 *img)
{
    return img ? check_view(img->buf, img->width, img->height, img->stride, img->width * 3)
               : RTE_ERR_ARGUMENT;
}

rte_status rte_image_s16_check_gradient(const rte_image_s16 *dx, const rte_image_s16 *dy,
                                        int32_t width, int32_t height)
{
    rte_status st = rte_image_s16_check(dx);
    if (st == RTE_OK)
        st = rte_image_s16_check(dy);
    if (st == RTE_OK &&
        (dx->width != width || dx->height != height || dy->width != width || dy->height != height))
        st = RTE_ERR_SIZE;
    return st;
}

rte_status rte_image_u8_check_pair(const rte_image_u8 *a, const rte_image_u8 *b)
{
    rte_status st = rte_image_u8_check(a);
    if (st == RTE_OK)
        st = rte_image_u8_check(b);
    if (st == RTE_OK && (a->width != b->width || a->height != b->height))
        st = RTE_ERR_SIZE;
    return st;
}
