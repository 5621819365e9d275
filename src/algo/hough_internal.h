/* Helpers shared by the Hough files (not public). */
#ifndef RTEDGE_HOUGH_INTERNAL_H
#define RTEDGE_HOUGH_INTERNAL_H

#include <stdint.h>
#include <string.h>

#include "rtedge/hough.h"

#include "geom_fixed.h" /* rte_isqrt64 */

/* Rho bins for a w x h map: round((2 * (w + h) + 1) / rho), as OpenCV. */
int32_t rte_hough_rho_bins(const rte_hough_config *cfg, int32_t w, int32_t h);

/* The checks lines and segments share: a usable configuration (as
 * rte_hough_config_init leaves it), a valid edge map no larger than the
 * configured maximum; clears *count and *truncated. */
rte_status rte_hough_begin(const rte_hough_config *cfg, const rte_image_u8 *edges, int32_t *count,
                           bool *truncated);

/* Offset added to x * rho_cos + y * rho_sin so that >> trig_shift gives the
 * rounded rho bin with bin 0 at rho = -(numrho - 1) / 2, never negative (a
 * right shift of a negative value is not portable C). */
static inline int32_t rte_hough_rho_bias(const rte_hough_config *cfg, int32_t numrho)
{
    const int32_t shift = cfg->trig_shift;
    return (int32_t)(((int64_t)((numrho - 1) / 2) << shift) + (shift ? (1 << (shift - 1)) : 0));
}

/* The edge pixels' packed coordinates y << 16 | x in raster order into
 * pts and, when mask is not NULL, 1 for an edge pixel and 0 for another
 * into the packed w x h mask; returns their number. Edge maps are sparse: 8
 * empty pixels are skipped at a time. Inline, so that the copy without a
 * mask has no mask code. */
static inline int32_t rte_hough_list_points(const rte_image_u8 *edges, uint8_t *mask, uint32_t *pts)
{
    const int32_t w = edges->width, h = edges->height;
    int32_t npts = 0;
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *row = rte_u8_row(edges, y);
        uint8_t *mrow = mask ? mask + (size_t)y * w : NULL;
        int32_t x = 0;
        for (;;) {
            uint64_t word;
            for (; x + 8 <= w; x += 8) {
                memcpy(&word, row + x, sizeof word);
                if (word)
                    break;
                if (mrow)
                    memcpy(mrow + x, &word, sizeof word); /* 8 zeros */
            }
            const int32_t end = x + 8 <= w ? x + 8 : w;
            if (x >= end)
                break;
            for (; x < end; x++) {
                uint8_t e = row[x] != 0;
                if (mrow)
                    mrow[x] = e;
                pts[npts] = ((uint32_t)y << 16) | (uint32_t)x;
                npts += e; /* branch-free compaction */
            }
        }
    }
    return npts;
}

/* Keeps the `capacity` largest of a stream of distinct 64-bit keys in a
 * min-heap; `seen` counts every key offered, so seen > capacity means some
 * were dropped. */
typedef struct rte_hough_topk {
    uint64_t *keys;
    int32_t capacity, size;
    int64_t seen;
} rte_hough_topk;

void rte_hough_topk_push(rte_hough_topk *t, uint64_t key);
/* Sorts the kept keys into descending order (in t->keys[0 .. size-1]). */
void rte_hough_topk_sort(rte_hough_topk *t);

/* A key that sorts by `votes` (more first), then by `index` (smaller first). */
static inline uint64_t rte_hough_key(int32_t votes, uint32_t index)
{
    return ((uint64_t)(uint32_t)votes << 32) | (uint32_t)~index;
}
static inline uint32_t rte_hough_key_index(uint64_t key) { return ~(uint32_t)key; }
static inline int32_t rte_hough_key_votes(uint64_t key) { return (int32_t)(key >> 32); }

#endif
