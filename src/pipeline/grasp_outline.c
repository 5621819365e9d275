/* The grasp path's edge test of an outline (grasp_ctx.h,
 * rte_grasp_outline_on_edges), per frame, integer only.
 *
 * An object's outline lies on an edge: across it the image steps from the
 * object to the table. Where a threshold cuts a smooth ramp instead (a box
 * shaded across the table's grey, a soft shadow's penumbra, a lit patch
 * of the table) the outline runs where the grey changes by a level or two
 * a pixel, and the piece it bounds is no object. The step is taken over
 * `reach` pixels, which grows with the frame: an edge (and a ramp) spreads
 * over more pixels of a larger frame of the same scene. Only the outline
 * beside the table counts: a background pixel as far from the table's
 * estimate as the threshold is a dark object's cast shadow, dropped, and
 * the object's side against it may be as dark as it. */
#include <stdint.h>

#include "grasp_ctx.h"

/* The grey step from outline pixel (x, y) to the table `reach` pixels
 * away along (dx, dy) (or as far as the frame goes), -1 when the pixel
 * next to it is no table (an object's, or a dropped shadow's), or an
 * object pixel lies within reach + 2 (a split's cut or a crack between
 * objects, not the table). */
static int32_t step_to_table(const grasp_outline_images *im, int32_t x, int32_t y, int32_t dx,
                             int32_t dy, int32_t reach)
{
    const rte_image_u8 *img = &im->img, *bin = &im->bin;
    if (x + dx >= 0 && y + dy >= 0 && x + dx < img->width && y + dy < img->height) {
        const int32_t d = rte_u8_row(img, y + dy)[x + dx] - rte_u8_row(&im->table, y + dy)[x + dx];
        if ((d < 0 ? -d : d) >= im->threshold)
            return -1;
    }
    int32_t far = 0;
    for (int32_t k = 1; k <= reach + 2; k++) {
        const int32_t tx = x + k * dx, ty = y + k * dy;
        if (tx < 0 || ty < 0 || tx >= img->width || ty >= img->height)
            break;
        if (rte_u8_row(bin, ty)[tx])
            return -1;
        far = k <= reach ? k : far;
    }
    if (!far)
        return -1;
    const int32_t d = rte_u8_row(img, y + far * dy)[x + far * dx] - rte_u8_row(img, y)[x];
    return d < 0 ? -d : d;
}

int32_t rte_grasp_outline_on_edges(const grasp_outline_images *im, const rte_point *pts, int32_t n,
                                   int32_t step, int32_t reach)
{
    static const int8_t dx4[4] = {1, -1, 0, 0}, dy4[4] = {0, 0, 1, -1};
    int64_t counted = 0, on_edge = 0;
    for (int32_t i = 0; i < n; i++) {
        /* CHAIN_APPROX_SIMPLE: a straight run of one of 8 directions to the
         * next point */
        const rte_point a = pts[i], b = pts[i + 1 < n ? i + 1 : 0];
        const int32_t sx = (b.x > a.x) - (b.x < a.x), sy = (b.y > a.y) - (b.y < a.y);
        for (rte_point q = a;; q.x += sx, q.y += sy) {
            int32_t most = -1;
            for (int32_t d = 0; d < 4; d++) {
                const int32_t s = step_to_table(im, q.x, q.y, dx4[d], dy4[d], reach);
                most = s > most ? s : most;
            }
            counted += most >= 0;
            on_edge += most >= step;
            if (q.x == b.x && q.y == b.y)
                break;
        }
    }
    return counted ? (int32_t)(on_edge * 1000 / counted) : 1000;
}
