/* Two-pass 3x3 chamfer distance transform (rtedge/distance.h). Values are
 * kept clamped to the metric's cap in every step: min(a, cap) + w clamped
 * again equals min(a + w, cap), so clamping as we go gives the capped
 * exact result. Pixels outside the image act as neighbours at the cap
 * (RTE_DIST_BORDER_FAR: never zero pixels) or at 0 (_ZERO). */
#include "rtedge/distance.h"

#include <stdbool.h>

typedef struct dist_weights {
    uint32_t hv, diag, cap;
    uint32_t outside; /* the value of a neighbour outside the image */
} dist_weights;

int32_t rte_distance_unit(rte_dist_metric metric)
{
    switch (metric) {
    case RTE_DIST_L1:
    case RTE_DIST_C: return 1;
    case RTE_DIST_CHAMFER34: return 3;
    }
    return 0;
}

static bool weights_of(rte_dist_metric metric, dist_weights *w)
{
    switch (metric) {
    case RTE_DIST_L1: *w = (dist_weights){1, 2, RTE_DIST_CAP, RTE_DIST_CAP}; return true;
    case RTE_DIST_C: *w = (dist_weights){1, 1, RTE_DIST_CAP, RTE_DIST_CAP}; return true;
    case RTE_DIST_CHAMFER34: *w = (dist_weights){3, 4, UINT16_MAX, UINT16_MAX}; return true;
    }
    return false;
}

static inline uint32_t min_u32(uint32_t a, uint32_t b) { return a < b ? a : b; }

/* Row y of the forward pass; `up` is row y - 1 of the result, NULL on the
 * first row. */
static void forward_row(const uint8_t *s, uint16_t *d, const uint16_t *up, int32_t width,
                        dist_weights w)
{
    uint32_t left = w.outside; /* the pixel to the left */
    for (int32_t x = 0; x < width; x++) {
        if (!s[x]) {
            d[x] = 0;
            left = 0;
            continue;
        }
        uint32_t t = left + w.hv;
        if (up) {
            uint32_t ul = x > 0 ? up[x - 1] : w.outside;
            uint32_t ur = x + 1 < width ? up[x + 1] : w.outside;
            t = min_u32(t, (uint32_t)up[x] + w.hv);
            t = min_u32(t, min_u32(ul, ur) + w.diag);
        } else {
            t = min_u32(t, w.outside + w.hv);
        }
        left = min_u32(t, w.cap);
        d[x] = (uint16_t)left;
    }
}

/* Row y of the backward pass, right to left; `down` is row y + 1, NULL on
 * the last row. Zero pixels stay 0, other values only decrease. */
static void backward_row(uint16_t *d, const uint16_t *down, int32_t width, dist_weights w)
{
    uint32_t right = w.outside;
    for (int32_t x = width - 1; x >= 0; x--) {
        uint32_t t = d[x];
        if (t != 0) {
            t = min_u32(t, right + w.hv);
            if (down) {
                uint32_t dl = x > 0 ? down[x - 1] : w.outside;
                uint32_t dr = x + 1 < width ? down[x + 1] : w.outside;
                t = min_u32(t, (uint32_t)down[x] + w.hv);
                t = min_u32(t, min_u32(dl, dr) + w.diag);
            } else {
                t = min_u32(t, w.outside + w.hv);
            }
            d[x] = (uint16_t)t;
        }
        right = t;
    }
}

rte_status rte_distance_transform_u8(const rte_image_u8 *src, rte_image_u16 *dst,
                                     rte_dist_metric metric, rte_dist_border border)
{
    dist_weights w;
    if (!src || !dst || !weights_of(metric, &w) ||
        (border != RTE_DIST_BORDER_FAR && border != RTE_DIST_BORDER_ZERO))
        return RTE_ERR_ARGUMENT;
    if (border == RTE_DIST_BORDER_ZERO)
        w.outside = 0;
    rte_status st = rte_image_u8_check(src);
    if (st == RTE_OK)
        st = rte_image_u16_check(dst);
    if (st != RTE_OK)
        return st;
    if (src->width != dst->width || src->height != dst->height)
        return RTE_ERR_SIZE;

    const int32_t width = src->width, height = src->height;
    for (int32_t y = 0; y < height; y++)
        forward_row(rte_u8_row(src, y), rte_u16_row(dst, y), y > 0 ? rte_u16_row(dst, y - 1) : NULL,
                    width, w);
    for (int32_t y = height - 1; y >= 0; y--)
        backward_row(rte_u16_row(dst, y), y + 1 < height ? rte_u16_row(dst, y + 1) : NULL, width,
                     w);
    return RTE_OK;
}
