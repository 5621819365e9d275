/* The frame's colour against the table's (see include/rtedge/background.h):
 * colour differences as contrast (rte_background_tint_u8) and the pixels a
 * shadow may have dimmed (rte_background_shade_u8). Per frame, integer
 * only. */
#include <stdint.h>

#include "rtedge/background.h"

#include "rtedge/cpu.h"
#include "simd/rows.h"

/* The checks rte_background_tint_u8 and rte_background_shade_u8 share:
 * grey planes of one size, chroma planes of half of it, dst of either
 * size (half: the chroma's). */
static rte_status check_colour_planes(const rte_image_u8 *src, const rte_image_u8 *background,
                                      const rte_image_u8 *cb, const rte_image_u8 *cb_background,
                                      const rte_image_u8 *cr, const rte_image_u8 *cr_background,
                                      const rte_image_u8 *dst, bool half)
{
    rte_status st = rte_image_u8_check_pair(src, background);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(half ? cb : src, dst);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(cb, cb_background);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(cb, cr);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(cb, cr_background);
    if (st != RTE_OK)
        return st;
    if (cb->width != (src->width + 1) / 2 || cb->height != (src->height + 1) / 2)
        return RTE_ERR_SIZE;
    if (dst->buf == src->buf || dst->buf == background->buf)
        return RTE_ERR_ARGUMENT;
    return RTE_OK;
}

rte_status rte_background_shade_u8(const rte_image_u8 *src, const rte_image_u8 *background,
                                   const rte_image_u8 *cb, const rte_image_u8 *cb_background,
                                   const rte_image_u8 *cr, const rte_image_u8 *cr_background,
                                   rte_image_u8 *shade, const rte_background_shade_params *params)
{
    rte_status st =
        check_colour_planes(src, background, cb, cb_background, cr, cr_background, shade, true);
    if (st != RTE_OK)
        return st;
    if (!params || params->darkest_permille < 0 ||
        params->lightest_permille < params->darkest_permille || params->lightest_permille > 1000 ||
        params->chroma < 0 || params->chroma > 255)
        return RTE_ERR_ARGUMENT;
    /* one decision per chroma sample (its 2x2 block), on the block's
     * top-left pixel; an odd width's last one through a pair of its own
     * (the row kernel reads whole pairs) */
    const rte_background_rows rows = rte_background_rows_select(rte_cpu_features());
    const int32_t pairs = src->width / 2;
    for (int32_t hy = 0; hy < shade->height; hy++) {
        const uint8_t *s = rte_u8_row(src, 2 * hy), *t = rte_u8_row(background, 2 * hy);
        const uint8_t *b = rte_u8_row(cb, hy), *bt = rte_u8_row(cb_background, hy);
        const uint8_t *r = rte_u8_row(cr, hy), *rt = rte_u8_row(cr_background, hy);
        uint8_t *out = rte_u8_row(shade, hy);
        rows.shade(s, t, b, bt, r, rt, out, pairs, params->darkest_permille,
                   params->lightest_permille, params->chroma);
        if (src->width & 1) {
            const uint8_t sp[2] = {s[2 * pairs], 0}, tp[2] = {t[2 * pairs], 0};
            rows.shade(sp, tp, b + pairs, bt + pairs, r + pairs, rt + pairs, out + pairs, 1,
                       params->darkest_permille, params->lightest_permille, params->chroma);
        }
    }
    return RTE_OK;
}

rte_status rte_background_tint_u8(const rte_image_u8 *src, const rte_image_u8 *background,
                                  const rte_image_u8 *cb, const rte_image_u8 *cb_background,
                                  const rte_image_u8 *cr, const rte_image_u8 *cr_background,
                                  rte_image_u8 *dst, const rte_background_tint_params *params)
{
    rte_status st =
        check_colour_planes(src, background, cb, cb_background, cr, cr_background, dst, false);
    if (st != RTE_OK)
        return st;
    const int32_t w = src->width, h = src->height;
    if (!params || params->least < 1 || params->least > 255)
        return RTE_ERR_ARGUMENT;
    const rte_background_rows rows = rte_background_rows_select(rte_cpu_features());
    const uint8_t up_only = !params->dark, either = params->bright && params->dark;
    for (int32_t y = 0; y < h; y++) {
        /* the colour differences go into dst's row (an odd width's last
         * sample through a pair of its own: the row has room for one),
         * then become the pixels */
        uint8_t *d = rte_u8_row(dst, y);
        const int32_t hy = y >> 1, whole = w >> 1;
        const uint8_t *b = rte_u8_row(cb, hy), *bt = rte_u8_row(cb_background, hy);
        const uint8_t *r = rte_u8_row(cr, hy), *rt = rte_u8_row(cr_background, hy);
        rows.chroma_diff(b, bt, r, rt, d, whole);
        if (w & 1) {
            uint8_t pair[2];
            rows.chroma_diff(b + whole, bt + whole, r + whole, rt + whole, pair, 1);
            d[w - 1] = pair[0];
        }
        rows.tint(rte_u8_row(src, y), rte_u8_row(background, y), d, w, (uint8_t)params->least,
                  up_only, either);
    }
    return RTE_OK;
}
