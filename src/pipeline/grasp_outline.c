/* The grasp path's edge test of an outline (grasp_ctx.h,
 * rte_grasp_outline_on_edges), per frame, integer only.
 *
 * An object's outline lies on an edge: across it the image steps from the
 * object to the table. Where a threshold cuts a smooth ramp instead (a box
 * shaded across the table's grey, a soft shadow's penumbra, a lit patch
 * of the table) the outline runs where neighbouring pixels differ by a
 * grey level or two, and the piece it bounds is no object. */
#include <stdint.h>

#include "grasp_ctx.h"

/* Whether bin holds an object pixel one or two steps beyond (x, y) along
 * (dx, dy): the background pixel there is then a split's cut or a crack
 * between objects, not the table. */
static bool object_beyond(const rte_image_u8 *bin, int32_t x, int32_t y, int32_t dx, int32_t dy)
{
    for (int32_t k = 1; k <= 2; k++) {
        const int32_t bx = x + k * dx, by = y + k * dy;
        if (bx < 0 || by < 0 || bx >= bin->width || by >= bin->height)
            return false;
        if (rte_u8_row(bin, by)[bx])
            return true;
    }
    return false;
}

int32_t rte_grasp_outline_on_edges(const rte_image_u8 *img, const rte_image_u8 *bin,
                                   const rte_point *pts, int32_t n, int32_t step)
{
    static const int8_t dx4[4] = {1, -1, 0, 0}, dy4[4] = {0, 0, 1, -1};
    int64_t counted = 0, on_edge = 0;
    for (int32_t i = 0; i < n; i++) {
        /* CHAIN_APPROX_SIMPLE: a straight run of one of 8 directions to the
         * next point */
        const rte_point a = pts[i], b = pts[i + 1 < n ? i + 1 : 0];
        const int32_t sx = (b.x > a.x) - (b.x < a.x), sy = (b.y > a.y) - (b.y < a.y);
        for (rte_point q = a;; q.x += sx, q.y += sy) {
            const int32_t g = rte_u8_row(img, q.y)[q.x];
            int32_t most = -1;
            for (int32_t d = 0; d < 4; d++) {
                const int32_t x = q.x + dx4[d], y = q.y + dy4[d];
                if (x < 0 || y < 0 || x >= img->width || y >= img->height ||
                    rte_u8_row(bin, y)[x] || object_beyond(bin, x, y, dx4[d], dy4[d]))
                    continue;
                const int32_t diff = rte_u8_row(img, y)[x] - g, ad = diff < 0 ? -diff : diff;
                most = ad > most ? ad : most;
            }
            counted += most >= 0;
            on_edge += most >= step;
            if (q.x == b.x && q.y == b.y)
                break;
        }
    }
    return counted ? (int32_t)(on_edge * 1000 / counted) : 1000;
}
