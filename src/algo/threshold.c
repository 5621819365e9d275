/* Thresholding, histogram, Otsu and automatic Canny thresholds (per frame,
 * integer only). See include/rtedge/threshold.h. */
#include "rtedge/threshold.h"

#include <string.h>

#include "binary64.h"
#include "rtedge/cpu.h"
#include "simd/rows.h"
#include "threshold_rows.h"

/* Partial histograms, one per byte of an 8-byte load: consecutive equal
 * pixels would otherwise serialise on one counter's load-increment-store
 * (eight take 12 % less time than four on the road photos). */
#define HIST_PARTS 8
/* Each partial histogram padded to 272 counters (1088 bytes): at 256 the
 * same grey level's counters of parts k and k + 4 lay 4096 bytes apart,
 * which the CPU's store-to-load check (on the low 12 address bits) takes
 * for one address, stalling the next part's load behind the last store
 * (6-10% of the time of rte_threshold_otsu_u8 at 1280x720). */
#define HIST_ROW 272
/* The image is counted as four horizontal bands side by side, one row of
 * each per step, each into its own parts: pixels of a uniform area fall on
 * the same counters, and four areas far apart rarely are at the same grey
 * level, so four times as many increments run between two of one counter
 * (a fifth less time than one band on the photos at 1280x720; the 35 KB
 * of counters stay in L1). */
#define HIST_BANDS 4
_Static_assert(HIST_BANDS == 4, "histogram_band_rows and histogram_run write out four bands");

typedef uint32_t hist_parts[HIST_PARTS][HIST_ROW];

/* Adds the 8 pixels at p to part (one 8-byte load; byte order cannot
 * matter here). */
static inline void histogram_chunk(const uint8_t *p, hist_parts part)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
    part[0][v & 0xFF]++;
    part[1][(v >> 8) & 0xFF]++;
    part[2][(v >> 16) & 0xFF]++;
    part[3][(v >> 24) & 0xFF]++;
    part[4][(v >> 32) & 0xFF]++;
    part[5][(v >> 40) & 0xFF]++;
    part[6][(v >> 48) & 0xFF]++;
    part[7][v >> 56]++;
}

/* A run of n pixels at p: its four quarters side by side, as the bands
 * of an image (pixels far apart rarely share a grey level), the rest
 * into the first parts. */
static void histogram_run(const uint8_t *p, int32_t n, hist_parts part[HIST_BANDS])
{
    const int32_t q = n / (8 * HIST_BANDS) * 8;
    for (int32_t x = 0; x < q; x += 8) {
        histogram_chunk(p + x, part[0]);
        histogram_chunk(p + q + x, part[1]);
        histogram_chunk(p + 2 * q + x, part[2]);
        histogram_chunk(p + 3 * q + x, part[3]);
    }
    int32_t x = HIST_BANDS * q;
    for (; x + 8 <= n; x += 8)
        histogram_chunk(p + x, part[0]);
    for (; x < n; x++)
        part[0][0][p[x]]++;
}

/* Whether a byte of m is 0. */
static inline uint64_t zero_bytes(uint64_t m)
{
    return (m - 0x0101010101010101u) & ~m & 0x8080808080808080u;
}

/* The first x from x on (or n) where mask[x] is not 0 (set) or is 0
 * (!set): 32 bytes a step, then 8, then one. */
static int32_t mask_boundary(const uint8_t *mask, int32_t x, int32_t n, bool set)
{
    uint64_t m[4];
    for (; x + 32 <= n; x += 32) {
        memcpy(m, mask + x, sizeof m);
        if (set ? (m[0] | m[1] | m[2] | m[3]) != 0
                : (zero_bytes(m[0]) | zero_bytes(m[1]) | zero_bytes(m[2]) | zero_bytes(m[3])) != 0)
            break;
    }
    for (; x + 8 <= n; x += 8) {
        memcpy(m, mask + x, sizeof m[0]);
        if (set ? m[0] != 0 : zero_bytes(m[0]) != 0)
            break;
    }
    while (x < n && (mask[x] != 0) != set)
        x++;
    return x;
}

/* What a histogram counts: the whole image, the pixels under a mask, or
 * a span of each row. */
typedef struct hist_region {
    const rte_image_u8 *mask;
    const int32_t *x0, *x1;
} hist_region;

/* The first run of row y that region counts, [*start, *end). */
static inline void region_run(const rte_image_u8 *src, const hist_region *g, int32_t y,
                              int32_t *start, int32_t *end)
{
    const int32_t n = src->width;
    if (g->mask) {
        const uint8_t *m = rte_u8_row(g->mask, y);
        *start = mask_boundary(m, 0, n, true);
        *end = mask_boundary(m, *start, n, false);
    } else if (g->x0) {
        *start = g->x0[y] < 0 ? 0 : g->x0[y] > n ? n : g->x0[y];
        *end = g->x1[y] < *start ? *start : g->x1[y] > n ? n : g->x1[y];
    } else {
        *start = 0;
        *end = n;
    }
}

/* The runs of row y after the first one, under a mask. */
static void mask_later_runs(const rte_image_u8 *src, const hist_region *g, int32_t y, int32_t x,
                            hist_parts part[HIST_BANDS])
{
    const uint8_t *row = rte_u8_row(src, y), *m = rte_u8_row(g->mask, y);
    const int32_t n = src->width;
    for (x = mask_boundary(m, x, n, true); x < n;) {
        const int32_t end = mask_boundary(m, x, n, false);
        histogram_run(row + x, end - x, part);
        x = mask_boundary(m, end, n, true);
    }
}

/* Row y of each of the four bands (`band` rows apart): their first runs
 * side by side for as long as the shortest, then the rest of each. */
static inline __attribute__((always_inline)) void histogram_band_rows(const rte_image_u8 *src,
                                                                      const hist_region *g,
                                                                      int32_t y, int32_t band,
                                                                      hist_parts part[HIST_BANDS])
{
    const uint8_t *r[HIST_BANDS];
    int32_t start[HIST_BANDS], end[HIST_BANDS], common = src->width;
    for (int b = 0; b < HIST_BANDS; b++) {
        region_run(src, g, y + b * band, &start[b], &end[b]);
        r[b] = rte_u8_row(src, y + b * band) + start[b];
        common = end[b] - start[b] < common ? end[b] - start[b] : common;
    }
    common &= ~7;
    /* written out: the four bands' increments interleave */
    for (int32_t x = 0; x < common; x += 8) {
        histogram_chunk(r[0] + x, part[0]);
        histogram_chunk(r[1] + x, part[1]);
        histogram_chunk(r[2] + x, part[2]);
        histogram_chunk(r[3] + x, part[3]);
    }
    for (int b = 0; b < HIST_BANDS; b++) {
        histogram_run(r[b] + common, end[b] - start[b] - common, part);
        if (g->mask)
            mask_later_runs(src, g, y + b * band, end[b], part);
    }
}

/* Inlined into each caller, so that the whole image's loop carries no
 * test for a mask or spans. */
static inline __attribute__((always_inline)) rte_status
histogram(const rte_image_u8 *src, const hist_region *g, uint32_t hist[256])
{
    hist_parts part[HIST_BANDS];
    memset(part, 0, sizeof part);
    const int32_t band = src->height / HIST_BANDS;
    for (int32_t y = 0; y < band; y++)
        histogram_band_rows(src, g, y, band, part);
    for (int32_t y = band * HIST_BANDS; y < src->height; y++) { /* the last few rows */
        int32_t start, end;
        region_run(src, g, y, &start, &end);
        histogram_run(rte_u8_row(src, y) + start, end - start, part);
        if (g->mask)
            mask_later_runs(src, g, y, end, part);
    }
    for (int32_t v = 0; v < 256; v++) {
        uint32_t sum = 0;
        for (int b = 0; b < HIST_BANDS; b++)
            for (int k = 0; k < HIST_PARTS; k++)
                sum += part[b][k][v];
        hist[v] = sum;
    }
    return RTE_OK;
}

rte_status rte_histogram_u8(const rte_image_u8 *src, uint32_t hist[256])
{
    rte_status st = rte_image_u8_check(src);
    if (st != RTE_OK)
        return st;
    if (!hist)
        return RTE_ERR_ARGUMENT;
    const hist_region all = {NULL, NULL, NULL};
    return histogram(src, &all, hist);
}

rte_status rte_histogram_masked_u8(const rte_image_u8 *src, const rte_image_u8 *mask,
                                   uint32_t hist[256])
{
    if (!mask || !hist)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check_pair(src, mask);
    if (st != RTE_OK)
        return st;
    const hist_region under = {mask, NULL, NULL};
    return histogram(src, &under, hist);
}

rte_status rte_histogram_spans_u8(const rte_image_u8 *src, const int32_t *x0, const int32_t *x1,
                                  uint32_t hist[256])
{
    rte_status st = rte_image_u8_check(src);
    if (st != RTE_OK)
        return st;
    if (!x0 || !x1 || !hist)
        return RTE_ERR_ARGUMENT;
    const hist_region spans = {NULL, x0, x1};
    return histogram(src, &spans, hist);
}

/* FLT_EPSILON (2^-23) and 1 - FLT_EPSILON as binary64 bit patterns. */
#define F64_FLT_EPSILON UINT64_C(0x3E80000000000000)
#define F64_ONE_MINUS_FLT_EPSILON UINT64_C(0x3FEFFFFFC0000000)

/* Images up to this many pixels may be decided by otsu_exact. */
#define OTSU_EXACT_MAX_PIXELS (UINT64_C(1) << 22)

/* Otsu's threshold decided in exact integers, when no near-tie needs
 * OpenCV's double rounding; -1 when one does (the caller then replays the
 * doubles). With N pixels summing to M, and H_i pixels summing to M_i in
 * the bins up to i, the between-class variance OpenCV computes at bin i is,
 * up to its rounding,
 *     sigma_i = (M H_i - N M_i)^2 / (N^2 H_i (N - H_i)).
 * For N <= 2^22 OpenCV's skip test (q1 or q2 below FLT_EPSILON = 2^-23,
 * or above 1 - FLT_EPSILON) holds exactly where H_i is 0 or N: otherwise
 * both are at least 1/N >= 2^-22, and q1, a sum of at most 256 rounded
 * terms, is off by less than 2^-44. Its sigma is then within 2^-25 of the
 * exact value (rounding through q2 = 1 - q1 and mu2 = (mu - q1 mu1) / q2
 * dominates; 2^-31 was the worst seen over 9000 adversarial histograms in
 * Python's doubles). So when the exact maximum leads every other bin by
 * more than 2 x 2^-16, OpenCV's doubles pick that bin too. The values are
 * kept as sigma N^2 (below 2^58), floored. */
static int32_t otsu_exact(const uint32_t hist[256], uint64_t total, uint64_t moment)
{
    if (total > OTSU_EXACT_MAX_PIXELS)
        return -1;
    const int64_t n = (int64_t)total, m = (int64_t)moment; /* m < 2^30 */
    int64_t h = 0, mi = 0;
    uint64_t best = 0, second = 0;
    int32_t best_bin = -1;
    for (int32_t i = 0; i < 256; i++) {
        h += hist[i];
        mi += (int64_t)i * hist[i];
        if (h == 0 || h == n)
            continue; /* OpenCV's skipped bins */
        best_bin = best_bin < 0 ? i : best_bin;
        const int64_t d = m * h - n * mi; /* |d| < 2^52 */
        const uint64_t ad = (uint64_t)(d < 0 ? -d : d);
        const uint64_t v = (uint64_t)((f64_u128)ad * ad / ((uint64_t)h * (uint64_t)(n - h)));
        if (v > best) {
            second = best;
            best = v;
            best_bin = i;
        } else if (v > second) {
            second = v;
        }
    }
    if (best_bin < 0)
        return 0; /* every bin skipped: OpenCV keeps 0 */
    /* 2^-15 N^2, plus the floors (a best of 0 never passes) */
    const uint64_t margin = (((uint64_t)n * (uint64_t)n) >> 15) + 2;
    return best - second > margin ? best_bin : -1;
}

rte_status rte_threshold_otsu_histogram(const uint32_t hist[256], int32_t *thresh)
{
    if (!hist || !thresh)
        return RTE_ERR_ARGUMENT;
    uint64_t total = 0, moment = 0;
    for (uint32_t v = 0; v < 256; v++) {
        total += hist[v];
        moment += (uint64_t)v * hist[v];
    }
    if (total == 0)
        return RTE_ERR_ARGUMENT;
    const int32_t exact = otsu_exact(hist, total, moment);
    if (exact >= 0) {
        *thresh = exact;
        return RTE_OK;
    }

    /* The same double operations, in the same order, as OpenCV 4.6's
     * getThreshVal_Otsu_8u: mu is a sum of exact integer products, so one
     * conversion of the integer sum gives the identical double. Note that
     * OpenCV multiplies mu1 by q1 before the skip test and only divides it
     * again on bins that are not skipped; that order is kept. */
    const rte_f64 scale = rte_f64_div(RTE_F64_ONE, rte_f64_from_u64(total));
    const rte_f64 mu = rte_f64_mul(rte_f64_from_u64(moment), scale);
    rte_f64 mu1 = 0, q1 = 0, max_sigma = 0;
    int32_t best = 0;
    for (uint32_t i = 0; i < 256; i++) {
        rte_f64 p_i = rte_f64_mul(rte_f64_from_u64(hist[i]), scale);
        mu1 = rte_f64_mul(mu1, q1);
        q1 = rte_f64_add(q1, p_i);
        rte_f64 q2 = rte_f64_sub(RTE_F64_ONE, q1);
        /* min(q1, q2) < FLT_EPSILON || max(q1, q2) > 1 - FLT_EPSILON */
        if (rte_f64_lt(q1, F64_FLT_EPSILON) || rte_f64_lt(q2, F64_FLT_EPSILON) ||
            rte_f64_lt(F64_ONE_MINUS_FLT_EPSILON, q1) || rte_f64_lt(F64_ONE_MINUS_FLT_EPSILON, q2))
            continue;
        mu1 = rte_f64_div(rte_f64_add(mu1, rte_f64_mul(rte_f64_from_u64(i), p_i)), q1);
        rte_f64 mu2 = rte_f64_div(rte_f64_sub(mu, rte_f64_mul(q1, mu1)), q2);
        rte_f64 d = rte_f64_sub(mu1, mu2);
        rte_f64 sigma = rte_f64_mul(rte_f64_mul(rte_f64_mul(q1, q2), d), d);
        if (rte_f64_lt(max_sigma, sigma)) { /* strictly greater: ties keep the lowest bin */
            max_sigma = sigma;
            best = (int32_t)i;
        }
    }
    *thresh = best;
    return RTE_OK;
}

rte_status rte_threshold_otsu_u8(const rte_image_u8 *src, int32_t *thresh)
{
    uint32_t hist[256];
    rte_status st = rte_histogram_u8(src, hist);
    if (st != RTE_OK)
        return st;
    return rte_threshold_otsu_histogram(hist, thresh);
}

/* The row kernel, once per instruction set (see simd/rows.h). */
void rte_threshold_row_c(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                         uint8_t maxval)
{
    threshold_row(s, d, n, type, t, maxval);
}

rte_threshold_row_fn rte_threshold_row_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, rte_threshold_row_c, rte_threshold_row_avx2,
                         rte_threshold_row_avx512, rte_threshold_row_neon);
}

static void fill_rows(rte_image_u8 *dst, uint8_t v)
{
    for (int32_t y = 0; y < dst->height; y++)
        memset(rte_u8_row(dst, y), v, (size_t)dst->width);
}

static void copy_rows(const rte_image_u8 *src, rte_image_u8 *dst)
{
    if (src->buf == dst->buf && src->stride == dst->stride)
        return;
    for (int32_t y = 0; y < src->height; y++)
        memmove(rte_u8_row(dst, y), rte_u8_row(src, y), (size_t)src->width);
}

rte_status rte_threshold_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                            const rte_threshold_params *params, int32_t *used_thresh)
{
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    if (!params || (uint32_t)params->type > RTE_THRESH_TOZERO_INV)
        return RTE_ERR_ARGUMENT;
    /* In place is fine (each pixel is read before it is written); other
     * overlaps between src and dst are not. */
    int32_t t = params->thresh;
    if (params->otsu) {
        st = rte_threshold_otsu_u8(src, &t);
        if (st != RTE_OK)
            return st;
    }
    if (used_thresh)
        *used_thresh = t;
    const rte_threshold_type type = params->type;
    const uint8_t maxval = (uint8_t)(params->maxval < 0     ? 0
                                     : params->maxval > 255 ? 255
                                                            : params->maxval);

    if (t < 0 || t >= 255) {
        /* Every pixel is on one side of t: OpenCV fills or copies. */
        bool above = t < 0; /* every pixel is > t */
        switch (type) {
        case RTE_THRESH_BINARY: fill_rows(dst, above ? maxval : 0); break;
        case RTE_THRESH_BINARY_INV: fill_rows(dst, above ? 0 : maxval); break;
        case RTE_THRESH_TRUNC: /* min(src, t) */
            if (above)
                fill_rows(dst, 0); /* OpenCV saturates t < 0 to 0 */
            else
                copy_rows(src, dst);
            break;
        case RTE_THRESH_TOZERO:
            if (above)
                copy_rows(src, dst);
            else
                fill_rows(dst, 0);
            break;
        case RTE_THRESH_TOZERO_INV:
            if (above)
                fill_rows(dst, 0);
            else
                copy_rows(src, dst);
            break;
        }
        return RTE_OK;
    }

    const rte_threshold_row_fn row = rte_threshold_row_select(rte_cpu_features());
    for (int32_t y = 0; y < src->height; y++)
        row(rte_u8_row(src, y), rte_u8_row(dst, y), src->width, (int)type, (uint8_t)t, maxval);
    return RTE_OK;
}
/* The value at 0-based rank `k` of the sorted pixels. */
static int32_t value_at_rank(const uint32_t hist[256], uint64_t k)
{
    uint64_t seen = 0;
    for (int32_t v = 0; v < 256; v++) {
        seen += hist[v];
        if (seen > k)
            return v;
    }
    return 255;
}

rte_status rte_threshold_auto_canny_median(const uint32_t hist[256], int32_t sigma_permille,
                                           int32_t *low, int32_t *high)
{
    if (!hist || !low || !high || sigma_permille < 0 || sigma_permille > 10000)
        return RTE_ERR_ARGUMENT;
    uint64_t total = 0;
    for (int32_t v = 0; v < 256; v++)
        total += hist[v];
    if (total == 0)
        return RTE_ERR_ARGUMENT;
    /* twice numpy's median: the two middle values (the same one for an odd count) */
    int32_t median2 = value_at_rank(hist, (total - 1) / 2) + value_at_rank(hist, total / 2);
    /* (1 -/+ s) * m = (1000 -/+ sigma_permille) * median2 / 2000, floored */
    int32_t lo = sigma_permille >= 1000 ? 0 : (1000 - sigma_permille) * median2 / 2000;
    int32_t hi = (1000 + sigma_permille) * median2 / 2000;
    *low = lo;
    *high = hi > 255 ? 255 : hi;
    return RTE_OK;
}

rte_status rte_threshold_auto_canny_otsu(const uint32_t hist[256], int32_t *low, int32_t *high)
{
    if (!low || !high)
        return RTE_ERR_ARGUMENT;
    int32_t t;
    rte_status st = rte_threshold_otsu_histogram(hist, &t);
    if (st != RTE_OK)
        return st;
    *high = t;
    *low = t / 2;
    return RTE_OK;
}
