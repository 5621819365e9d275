/* Fixed-level thresholding, Otsu's threshold, the 256-bin histogram and
 * automatic Canny thresholds, for 8-bit single-channel images.
 *
 * Results are bit-identical with OpenCV 4.6 cv::threshold() on CV_8UC1,
 * including THRESH_OTSU and the threshold value it returns. OpenCV takes
 * thresh and maxval as doubles; rte_threshold_params_init() converts them
 * once, at configuration time, the way OpenCV does for 8-bit images:
 *   thresh -> floor(thresh)                 (127.5 -> 127, -0.5 -> -1)
 *   maxval -> round-half-even(maxval), then saturated to 0..255 when used
 *             (300 -> 255, 127.5 -> 128, 128.5 -> 128, -3 -> 0)
 * A floored threshold below 0 or at/above 255 gives OpenCV's constant or
 * copy results (e.g. BINARY with thresh 300 is all 0, TOZERO with -1 is a
 * copy). The per-frame functions use integers only. */
#ifndef RTEDGE_THRESHOLD_H
#define RTEDGE_THRESHOLD_H

#include <stdbool.h>
#include <stdint.h>

#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Same numbering as OpenCV's cv::ThresholdTypes. */
typedef enum rte_threshold_type {
    RTE_THRESH_BINARY = 0,     /* dst = src > t ? maxval : 0 */
    RTE_THRESH_BINARY_INV = 1, /* dst = src > t ? 0 : maxval */
    RTE_THRESH_TRUNC = 2,      /* dst = src > t ? t : src */
    RTE_THRESH_TOZERO = 3,     /* dst = src > t ? src : 0 */
    RTE_THRESH_TOZERO_INV = 4, /* dst = src > t ? 0 : src */
} rte_threshold_type;

typedef struct rte_threshold_params {
    rte_threshold_type type;
    int32_t thresh; /* integer threshold t (OpenCV's floor(thresh)); any value */
    int32_t maxval; /* integer maxval (OpenCV's cvRound(maxval)); saturated to 0..255 */
    bool otsu;      /* true: t is Otsu's threshold of each frame (THRESH_OTSU) */
} rte_threshold_params;

/* Configuration time: fills `params` from OpenCV-style double arguments.
 * RTE_ERR_ARGUMENT for an unknown type or a thresh/maxval that is NaN or
 * outside the int32 range. */
RTE_API rte_status rte_threshold_params_init(rte_threshold_params *params, rte_threshold_type type,
                                             double thresh, double maxval, bool otsu);

/* cv::threshold(src, dst, thresh, maxval, type [| THRESH_OTSU]).
 * `dst` has the size of `src` and may be `src` itself (in place).
 * `used_thresh` (may be NULL) receives the threshold OpenCV returns:
 * floor(thresh), or Otsu's threshold when params->otsu is set. */
RTE_API rte_status rte_threshold_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                    const rte_threshold_params *params, int32_t *used_thresh);

/* hist[v] = number of pixels equal to v (the counts fit uint32_t because
 * every side is at most RTE_MAX_SIDE). Its partial counters take 35 KB of
 * the caller's stack (no other memory). */
RTE_API rte_status rte_histogram_u8(const rte_image_u8 *src, uint32_t hist[256]);

/* The same over the pixels where mask (same size as src) is not 0, as
 * cv::calcHist with a mask. */
RTE_API rte_status rte_histogram_masked_u8(const rte_image_u8 *src, const rte_image_u8 *mask,
                                           uint32_t hist[256]);

/* The same over the pixels x0[y] <= x < x1[y] of each row y (x0, x1: one
 * entry a row, clipped to the image; a row with x1[y] <= x0[y] adds
 * nothing): a convex region such as an ROI polygon's, its spans worked out
 * once, counted without reading a mask. */
RTE_API rte_status rte_histogram_spans_u8(const rte_image_u8 *src, const int32_t *x0,
                                          const int32_t *x1, uint32_t hist[256]);

/* Otsu's threshold of a histogram exactly as OpenCV 4.6 computes it for
 * THRESH_OTSU: OpenCV works in IEEE double precision, and near-ties (for
 * example every empty bin between the two levels of a two-valued image)
 * are decided by its rounding. rtedge finds the bin of largest
 * between-class variance in exact integers and, when another bin comes
 * within 2^-15 of it or the histogram holds more than 2^22 pixels, replays
 * OpenCV's double operations in integer arithmetic instead (about 1 us
 * against 30 per histogram). A histogram with all pixels in one bin
 * gives 0. RTE_ERR_ARGUMENT when the histogram is empty. */
RTE_API rte_status rte_threshold_otsu_histogram(const uint32_t hist[256], int32_t *thresh);

/* Otsu's threshold of an image (its histogram, then the above). */
RTE_API rte_status rte_threshold_otsu_u8(const rte_image_u8 *src, int32_t *thresh);

/* Automatic Canny thresholds from a histogram (see rte_histogram_u8).
 *
 * Median rule (the popular "auto_canny" recipe): with m = numpy's median
 * of the pixels (the mean of the two middle values for an even count) and
 * s = sigma_permille / 1000,
 *     low  = floor(max(0,   (1 - s) * m))
 *     high = floor(min(255, (1 + s) * m))
 * computed exactly in integers (the recipe's int() truncates; the products
 * are exact rationals here, so no double rounding can move them).
 * sigma_permille is 0..10000; 330 is the recipe's s = 0.33
 * (RTE_AUTO_CANNY_SIGMA_PERMILLE). */
#define RTE_AUTO_CANNY_SIGMA_PERMILLE 330
RTE_API rte_status rte_threshold_auto_canny_median(const uint32_t hist[256], int32_t sigma_permille,
                                                   int32_t *low, int32_t *high);

/* Otsu rule: high = Otsu's threshold, low = high / 2 rounded down (Canny
 * floors its thresholds, so this gives the same edges as high * 0.5). */
RTE_API rte_status rte_threshold_auto_canny_otsu(const uint32_t hist[256], int32_t *low,
                                                 int32_t *high);

#ifdef __cplusplus
}
#endif
#endif
