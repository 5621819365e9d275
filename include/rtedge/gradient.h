/* Image derivatives of 8-bit images to int16: Sobel, Scharr, Laplacian, and
 * the saturated absolute value back to 8 bits.
 *
 * Bit-exact with OpenCV 4.6 for 8-bit input:
 *   rte_sobel_s16      = cv::Sobel(src, dst, CV_16S, dx, dy, ksize)
 *   rte_scharr_s16     = cv::Scharr(src, dst, CV_16S, dx, dy)
 *   rte_laplacian_s16  = cv::Laplacian(src, dst, CV_16S, ksize)   (ksize 1, 3)
 *   rte_abs_s16_u8     = cv::convertScaleAbs(src, dst)
 * with scale 1, delta 0 and the default border BORDER_REFLECT_101 (mirror
 * without repeating the edge pixel; a 1-pixel side repeats that pixel).
 * Images smaller than the kernel are handled as OpenCV does (the mirror is
 * folded again until it lands inside the image). Results saturate to int16.
 *
 * A Laplacian of Gaussian is a Gaussian blur (include/rtedge/blur.h)
 * followed by rte_laplacian_s16.
 *
 * All kernels keep a few rows of int16 in the caller's arena (sized by the
 * matching *_scratch_size) and reset the arena before returning. dst must
 * have the size of src and must not overlap it. */
#ifndef RTEDGE_GRADIENT_H
#define RTEDGE_GRADIENT_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sobel derivative of order dx in x and dy in y, each 0..2, not both 0.
 * ksize 1, 3, 5 or 7; ksize 1 means a 3-tap derivative along each axis with
 * a non-zero order and no smoothing (1 tap) along an axis with order 0, as
 * OpenCV. RTE_ERR_ARGUMENT for other orders or sizes. */
RTE_API rte_status rte_sobel_s16(const rte_image_u8 *src, rte_image_s16 *dst, int32_t dx,
                                 int32_t dy, int32_t ksize, rte_arena *scratch);
RTE_API size_t rte_sobel_scratch_size(int32_t max_width, int32_t max_height, int32_t ksize);

/* Scharr 3x3 first derivative: (dx, dy) is (1, 0) or (0, 1). */
RTE_API rte_status rte_scharr_s16(const rte_image_u8 *src, rte_image_s16 *dst, int32_t dx,
                                  int32_t dy, rte_arena *scratch);
RTE_API size_t rte_scharr_scratch_size(int32_t max_width, int32_t max_height);

/* Laplacian. ksize 1: [0 1 0; 1 -4 1; 0 1 0]; ksize 3: [2 0 2; 0 -8 0; 2 0 2]. */
RTE_API rte_status rte_laplacian_s16(const rte_image_u8 *src, rte_image_s16 *dst, int32_t ksize,
                                     rte_arena *scratch);
RTE_API size_t rte_laplacian_scratch_size(int32_t max_width, int32_t max_height, int32_t ksize);

/* dst = min(|src|, 255) (|-32768| saturates to 255 too). No scratch. */
RTE_API rte_status rte_abs_s16_u8(const rte_image_s16 *src, rte_image_u8 *dst);

#ifdef __cplusplus
}
#endif
#endif
