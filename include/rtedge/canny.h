/* Canny edge detector, bit-exact with OpenCV 4.6 for 8-bit input:
 *   rte_canny_u8               = cv::Canny(src, edges, low, high, aperture, l2_gradient)
 *   rte_canny_from_gradient_u8 = cv::Canny(dx, dy, edges, low, high, l2_gradient)
 *   rte_canny_gradient_u8      = cv::Sobel(src, dx / dy, CV_16S, ..., BORDER_REPLICATE);
 *                                cv::Canny(dx, dy, edges, low, high, l2_gradient)
 * for aperture 3 and 5, any thresholds (low > high are swapped, fractional and
 * negative values behave as in OpenCV). Output is 255 on edges, 0 elsewhere.
 *
 * Aperture 7 is offered but not promised bit-exact: OpenCV computes it in
 * floating point (Sobel scaled by 1/16, thresholds divided by 16). rtedge
 * divides the exact integer Sobel sum by 16 rounding half to even, which is
 * what that float path yields and what the oracle tests observe, but it is
 * not an integer specification OpenCV guarantees.
 *
 * Steps: Sobel dx, dy (int16, BORDER_REPLICATE); magnitude |dx|+|dy| (L1) or
 * dx*dx+dy*dy (L2, compared with squared thresholds, no square root);
 * non-maximum suppression along the gradient direction quantised to 4
 * sectors; hysteresis: 8-connected flood from pixels above `high` through
 * pixels above `low`. The per-frame code is integer only: the floating-point
 * thresholds become integer comparison values once, in rte_canny_params_init.
 *
 * Memory: a (width+2)*(height+2) byte edge map, a flood stack that can hold
 * every pixel (so it can never overflow) and a few rows, all from the
 * caller's arena; size it with rte_canny_scratch_size. The arena is reset to
 * its entry mark before returning. */
#ifndef RTEDGE_CANNY_H
#define RTEDGE_CANNY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/blur.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rte_canny_params {
    int32_t aperture; /* Sobel size: 3, 5 or 7 (see above) */
    bool l2_gradient; /* magnitude dx*dx+dy*dy instead of |dx|+|dy| */
    /* Integer comparison values, set by rte_canny_params_init: a pixel is a
     * candidate when its magnitude > low and a seed when > high. */
    int32_t low, high;
} rte_canny_params;

/* Configuration time (uses floating point; not per frame). Thresholds as
 * cv::Canny takes them: divided by 16 for aperture 7; swapped when low >
 * high; with l2_gradient each is clamped to 32767 and squared when positive;
 * then floored to integers as OpenCV's x86-64 build does (a value >= 2^31
 * becomes INT32_MIN, so every local maximum is an edge; one below -2^31
 * becomes INT32_MAX, so nothing is). RTE_ERR_ARGUMENT for an aperture other
 * than 3, 5 or 7, or a NaN threshold. */
RTE_API rte_status rte_canny_params_init(rte_canny_params *params, double low_threshold,
                                         double high_threshold, int32_t aperture, bool l2_gradient);

/* Arena bytes that rte_canny_u8 needs for images up to max_width x
 * max_height with this aperture; rte_canny_from_gradient_u8 needs no more
 * than for aperture 3. */
RTE_API size_t rte_canny_scratch_size(int32_t max_width, int32_t max_height, int32_t aperture);

/* Edges of src into dst (same size, no overlap). */
RTE_API rte_status rte_canny_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                const rte_canny_params *params, rte_arena *scratch);

/* Fused front end: the edges of the Gaussian blur of src, exactly
 *   rte_gaussian_blur_u8(src, tmp, kernel); rte_canny_u8(tmp, dst, params)
 * (= cv::GaussianBlur then cv::Canny), without the blurred image: each
 * source row is blurred just before the Sobel needs it, into a band of
 * `aperture` rows that stays in cache, and Sobel, magnitude and non-maximum
 * suppression follow on the same rows; hysteresis runs at the end as in
 * rte_canny_u8. dst may be src itself (it is written only at the end). */
RTE_API rte_status rte_canny_blurred_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                        const rte_gaussian_kernel *kernel,
                                        const rte_canny_params *params, rte_arena *scratch);

/* Arena bytes rte_canny_blurred_u8 needs for images up to max_width x
 * max_height with this kernel and aperture (0 for invalid arguments). */
RTE_API size_t rte_canny_blurred_scratch_size(int32_t max_width, int32_t max_height,
                                              const rte_gaussian_kernel *kernel, int32_t aperture);

/* rte_canny_u8 that also hands out the derivatives it computes: dx, dy =
 * cv::Sobel(src, CV_16S, 1, 0 / 0, 1, aperture, 1, 0, BORDER_REPLICATE)
 * (Canny's own), same size as src. One pass gives what cv::HoughCircles
 * computes inside and rte_hough_circles takes beside the edges. dx and dy
 * are two images that overlap neither src nor dst. Aperture 3 or 5;
 * aperture 7, whose derivatives Canny scales by 1/16, is rejected with
 * RTE_ERR_ARGUMENT. Scratch: rte_canny_scratch_size. */
RTE_API rte_status rte_canny_gradient_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                         rte_image_s16 *dx, rte_image_s16 *dy,
                                         const rte_canny_params *params, rte_arena *scratch);

/* Edges from given derivatives dx and dy (same size as dst). params must come
 * from rte_canny_params_init with aperture 3 or 5 (both give the same
 * thresholds); aperture-7 params, whose thresholds are divided by 16, are
 * rejected with RTE_ERR_ARGUMENT. The L2 magnitude wraps around in 32 bits exactly as OpenCV's
 * does when dx = dy = -32768, and so does the sector test for |dx| > 27145.
 * One known difference: for the L1 magnitude rtedge takes |-32768| as 32768,
 * while OpenCV's SIMD loop takes it as -32768 (its scalar tail as 32768).
 * Derivatives of 8-bit images never come near these values. */
RTE_API rte_status rte_canny_from_gradient_u8(const rte_image_s16 *dx, const rte_image_s16 *dy,
                                              rte_image_u8 *dst, const rte_canny_params *params,
                                              rte_arena *scratch);

#ifdef __cplusplus
}
#endif
#endif
