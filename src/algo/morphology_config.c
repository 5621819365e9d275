/* Structuring elements (configuration time; the ellipse uses floating
 * point exactly as cv::getStructuringElement does). */
#include <math.h>
#include <string.h>

#include "rtedge/morphology.h"

rte_status rte_morphology_element_from_mask(rte_morph_element *element, const uint8_t *mask,
                                            int32_t width, int32_t height, int32_t anchor_x,
                                            int32_t anchor_y)
{
    if (!element || !mask || width < 1 || height < 1 || width > RTE_MORPH_MAX_KSIZE ||
        height > RTE_MORPH_MAX_KSIZE)
        return RTE_ERR_ARGUMENT;
    if (anchor_x == -1)
        anchor_x = width / 2;
    if (anchor_y == -1)
        anchor_y = height / 2;
    if (anchor_x < 0 || anchor_x >= width || anchor_y < 0 || anchor_y >= height)
        return RTE_ERR_ARGUMENT;

    rte_morph_element e;
    memset(&e, 0, sizeof e);
    e.width = width;
    e.height = height;
    e.anchor_x = anchor_x;
    e.anchor_y = anchor_y;
    int32_t set = 0;
    for (int32_t dy = 0; dy < height; dy++) {
        for (int32_t dx = 0; dx < width;) {
            if (!mask[dy * width + dx]) {
                dx++;
                continue;
            }
            int32_t len = 0;
            while (dx + len < width && mask[dy * width + dx + len]) {
                e.mask[dy * width + dx + len] = 1;
                len++;
            }
            e.runs[e.run_count++] = (rte_morph_run){(int16_t)dy, (int16_t)dx, (int16_t)len};
            if (len > e.max_run)
                e.max_run = len;
            set += len;
            dx += len;
        }
    }
    if (set == 0)
        return RTE_ERR_ARGUMENT;
    e.full = set == width * height;
    *element = e;
    return RTE_OK;
}

rte_status rte_morphology_element_init(rte_morph_element *element, rte_morph_shape shape,
                                       int32_t width, int32_t height)
{
    if (!element || width < 1 || height < 1 || width > RTE_MORPH_MAX_KSIZE ||
        height > RTE_MORPH_MAX_KSIZE || (unsigned)shape > RTE_MORPH_ELLIPSE)
        return RTE_ERR_ARGUMENT;
    uint8_t mask[RTE_MORPH_MAX_KSIZE * RTE_MORPH_MAX_KSIZE];
    const int32_t ax = width / 2, ay = height / 2;
    /* The ellipse's half-axes are the integer halves of the size, and each
     * row's half-width is rounded (half to even) from a double, as in
     * OpenCV; even sizes therefore give lopsided ellipses there too. */
    const int32_t r = height / 2, c = width / 2;
    const double inv_r2 = r ? 1.0 / ((double)r * r) : 0.0;
    for (int32_t i = 0; i < height; i++) {
        int32_t j1 = 0, j2 = 0;
        if (shape == RTE_MORPH_RECT || (width == 1 && height == 1) ||
            (shape == RTE_MORPH_CROSS && i == ay)) {
            j2 = width;
        } else if (shape == RTE_MORPH_CROSS) {
            j1 = ax;
            j2 = ax + 1;
        } else {
            int32_t dy = i - r;
            if (dy >= -r && dy <= r) {
                int32_t dx = (int32_t)lrint(c * sqrt((r * r - dy * dy) * inv_r2));
                j1 = c - dx > 0 ? c - dx : 0;
                j2 = c + dx + 1 < width ? c + dx + 1 : width;
            }
        }
        for (int32_t j = 0; j < width; j++)
            mask[i * width + j] = (uint8_t)(j >= j1 && j < j2);
    }
    return rte_morphology_element_from_mask(element, mask, width, height, ax, ay);
}
