/* Integer square root and a bounded top-k selection shared by the Hough
 * transforms: candidates are ranked without allocating and without qsort
 * (whose scratch and order on ties differ between C libraries). */
#include "hough_internal.h"

uint32_t rte_hough_isqrt64(uint64_t v)
{
    uint64_t r = 0, bit = (uint64_t)1 << 62;
    while (bit > v)
        bit >>= 2;
    while (bit) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)r;
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
