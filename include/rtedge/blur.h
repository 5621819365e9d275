/* Blur family: Gaussian and median smoothing of 8-bit single-channel images,
 * bit-exact with OpenCV 4.6 (cv::GaussianBlur with the default border
 * BORDER_REFLECT_101, and cv::medianBlur with ksize 3 or 5).
 *
 * Gaussian blur is split in two: rte_gaussian_kernel_init() runs once at
 * configuration time (it uses floating point, like OpenCV's kernel builder)
 * and fills a small caller-owned table of Q8 taps; rte_gaussian_blur_u8()
 * runs per frame in integers only, one output row at a time, with a line
 * of scratch from the caller's arena (no intermediate image).
 *
 * Both kernels work in place: dst may be the same view as src (same buf and
 * stride; the same buf with another stride is refused, RTE_ERR_ARGUMENT).
 * Any other overlap of src and dst is not allowed. */
#ifndef RTEDGE_BLUR_H
#define RTEDGE_BLUR_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest Gaussian kernel side rtedge supports (OpenCV allows more). */
#define RTE_GAUSSIAN_MAX_KSIZE 15

/* Separable Gaussian kernel in OpenCV's bit-exact 8-bit form: each axis has
 * ksize taps in Q8 (fixed point, 8 fractional bits) that sum to 256 exactly.
 * ksize 1 (a single tap of 256) leaves that axis unblurred. */
typedef struct rte_gaussian_kernel {
    int32_t ksize_x, ksize_y;
    uint16_t taps_x[RTE_GAUSSIAN_MAX_KSIZE];
    uint16_t taps_y[RTE_GAUSSIAN_MAX_KSIZE];
} rte_gaussian_kernel;

/* Builds the kernel of cv::GaussianBlur(src, dst, (ksize_x, ksize_y),
 * sigma_x, sigma_y) for 8-bit images (configuration time, uses floats).
 *  - ksize_x, ksize_y: odd 1..RTE_GAUSSIAN_MAX_KSIZE, or 0 to derive the size
 *    from the sigma of that axis as OpenCV does (round(sigma * 6 + 1) | 1).
 *  - sigma_x: > 0, or <= 0 to derive it from ksize_x (OpenCV's rule).
 *  - sigma_y: <= 0 means "same as sigma_x" (as in OpenCV).
 * Returns RTE_ERR_ARGUMENT for an even or negative size, a size of 0 with no
 * positive sigma, or a NaN or infinite sigma; RTE_ERR_UNSUPPORTED for a
 * size, given or derived, above RTE_GAUSSIAN_MAX_KSIZE. OpenCV 4.6 takes its
 * bit-exact path for every other parameter (checked for sigmas up to 1000),
 * so all of them are inside the bit-exactness guarantee; see
 * src/algo/gaussian_kernel.c for how the taps are reproduced. */
RTE_API rte_status rte_gaussian_kernel_init(rte_gaussian_kernel *kernel, int32_t ksize_x,
                                            int32_t ksize_y, double sigma_x, double sigma_y);

/* Arena bytes rte_gaussian_blur_u8() needs for images up to max_width wide
 * with this kernel, in place or not (one padded line of column sums, plus
 * copies of ksize_y source rows when dst is src; max_height is accepted for
 * symmetry, nothing depends on it). 0 for invalid arguments. */
RTE_API size_t rte_gaussian_blur_u8_scratch_size(int32_t max_width, int32_t max_height,
                                                 const rte_gaussian_kernel *kernel);

/* dst = cv::GaussianBlur(src) with BORDER_REFLECT_101, as OpenCV computes it
 * for a whole Mat (or a ROI with BORDER_ISOLATED; for a plain ROI OpenCV reads
 * the pixels around it and uses a floating-point path). src and dst must have
 * the same width and height. Scratch comes from `arena` and is given back
 * before returning. Errors: RTE_ERR_ARGUMENT (NULL or a malformed kernel),
 * RTE_ERR_SIZE (bad or mismatched images), RTE_ERR_NO_MEMORY (arena too
 * small; dst is then untouched). */
RTE_API rte_status rte_gaussian_blur_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                        const rte_gaussian_kernel *kernel, rte_arena *arena);

/* Arena bytes rte_median_blur_u8() needs for images up to max_width wide with
 * aperture ksize (3 or 5). 0 for invalid arguments. */
RTE_API size_t rte_median_blur_u8_scratch_size(int32_t max_width, int32_t max_height,
                                               int32_t ksize);

/* dst = cv::medianBlur(src, ksize) for ksize 1 (a copy), 3 or 5: the median of
 * the ksize x ksize neighbourhood, pixels outside the image replicated from
 * the nearest edge (BORDER_REPLICATE). Errors as rte_gaussian_blur_u8(), and
 * RTE_ERR_ARGUMENT for any other ksize. */
RTE_API rte_status rte_median_blur_u8(const rte_image_u8 *src, rte_image_u8 *dst, int32_t ksize,
                                      rte_arena *arena);

#ifdef __cplusplus
}
#endif
#endif
