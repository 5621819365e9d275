/* Helpers shared by the Hough files (not public). */
#ifndef RTEDGE_HOUGH_INTERNAL_H
#define RTEDGE_HOUGH_INTERNAL_H

#include <stdint.h>

/* floor(sqrt(v)), exact for every 64-bit value. */
uint32_t rte_hough_isqrt64(uint64_t v);

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
