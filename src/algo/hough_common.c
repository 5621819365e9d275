/* Argument checks, rho bins and a bounded top-k selection shared by the
 * Hough transforms: candidates are ranked without allocating and without qsort
 * (whose scratch and order on ties differ between C libraries). */
#include "hough_internal.h"

int32_t rte_hough_rho_bins(const rte_hough_config *cfg, int32_t w, int32_t h)
{
    int64_t n = ((int64_t)(2 * (w + h) + 1) * cfg->inv_rho_q16 + 32768) >> 16;
    return n < 1 ? 1 : (int32_t)n;
}

rte_status rte_hough_begin(const rte_hough_config *cfg, const rte_image_u8 *edges, int32_t *count,
                           bool *truncated)
{
    if (!cfg || cfg->num_angles < 1 || cfg->num_angles > RTE_HOUGH_MAX_ANGLES ||
        cfg->trig_shift < 0 || cfg->trig_shift > 30 || cfg->inv_rho_q16 <= 0 ||
        cfg->max_width < 1 || cfg->max_height < 1 || cfg->max_width > RTE_MAX_SIDE ||
        cfg->max_height > RTE_MAX_SIDE)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check(edges);
    if (st != RTE_OK)
        return st;
    if (edges->width > cfg->max_width || edges->height > cfg->max_height)
        return RTE_ERR_TOO_LARGE;
    *count = 0;
    *truncated = false;
    return RTE_OK;
}

static void sift_down(uint64_t *h, int32_t n, int32_t i)
{
    uint64_t v = h[i];
    for (;;) {
        int32_t c = 2 * i + 1;
        if (c >= n)
            break;
        if (c + 1 < n && h[c + 1] < h[c])
            c++;
        if (h[c] >= v)
            break;
        h[i] = h[c];
        i = c;
    }
    h[i] = v;
}

void rte_hough_topk_push(rte_hough_topk *t, uint64_t key)
{
    t->seen++;
    if (t->capacity <= 0)
        return;
    if (t->size < t->capacity) {
        int32_t i = t->size++;
        while (i > 0) {
            int32_t p = (i - 1) / 2;
            if (t->keys[p] <= key)
                break;
            t->keys[i] = t->keys[p];
            i = p;
        }
        t->keys[i] = key;
    } else if (key > t->keys[0]) {
        t->keys[0] = key;
        sift_down(t->keys, t->size, 0);
    }
}

void rte_hough_topk_sort(rte_hough_topk *t)
{
    /* Heapsort of a min-heap: popping the minimum to the end leaves the keys
     * in descending order. */
    for (int32_t n = t->size - 1; n > 0; n--) {
        uint64_t m = t->keys[0];
        t->keys[0] = t->keys[n];
        t->keys[n] = m;
        sift_down(t->keys, n, 0);
    }
}
