/* Row kernels shared by the gradient family and Canny (internal to
 * librtedge): separable integer filters of an 8-bit image computed one output
 * row at a time, so callers only keep a few int16 rows. */
#ifndef RTEDGE_SRC_ALGO_GRADIENT_ROWS_H
#define RTEDGE_SRC_ALGO_GRADIENT_ROWS_H

#include <stdint.h>

#include "rtedge/image.h"
#include "simd/rows.h"

/* Longest 1-D kernel: Sobel ksize 7. */
#define RTE_GRAD_MAX_TAPS 7

typedef enum rte_border {
    RTE_BORDER_REFLECT_101, /* dcb|abcd|cba, OpenCV's default for filters */
    RTE_BORDER_REPLICATE,   /* aaa|abcd|ddd, what Canny uses */
} rte_border;

/* Index p folded into [0, len) as OpenCV's borderInterpolate (a mirror
 * folds again while it lands outside a short image). */
int32_t rte_border_fold(int32_t p, int32_t len, rte_border border);

/* Column pass for output row y: v[x] = sum_k ky[k] * src(x, y + k - ny/2)
 * for 0 <= x < width, rows folded by `border`; then `pad` columns on each
 * side of v (v[-pad] .. v[width + pad - 1]) are filled as the border gives,
 * ready for a row pass. sum |ky| * 255 must fit int16. The loops are k's
 * (rte_grad_rows_select, once per image). */
void rte_grad_column_pass(const rte_grad_rows *k, const rte_image_u8 *src, int32_t y,
                          const int16_t *ky, int32_t ny, rte_border border, int16_t *v,
                          int32_t pad);

/* The same from the ny source rows themselves (row[k] is source row
 * y + k - ny/2, already folded), each `w` pixels wide. */
void rte_grad_column_rows(const rte_grad_rows *k, const uint8_t *const *row, int32_t w,
                          const int16_t *ky, int32_t ny, rte_border border, int16_t *v,
                          int32_t pad);

/* How a row pass (k->row: out[x] = sum_k kx[k] * v[x + k - nx/2] for
 * 0 <= x < width, v with nx/2 valid columns on each side) turns its int32
 * sums into int16. */
typedef enum rte_row_mode {
    RTE_ROW_FITS,        /* the caller knows the sums fit int16 (fastest) */
    RTE_ROW_SATURATE,    /* saturate to int16 */
    RTE_ROW_ROUND_DIV16, /* sum / 16 rounded half to even (OpenCV's Canny aperture 7) */
} rte_row_mode;

/* sum |taps|: with the column taps' sum times 255 it bounds the result. */
int32_t rte_grad_taps_l1(const int16_t *taps, int32_t n);

/* OpenCV's Sobel taps: order 0 is the binomial row of length ksize, order 1
 * and 2 its differences (ksize 3: [1 2 1], [-1 0 1], [1 -2 1]). */
void rte_sobel_taps(int32_t order, int32_t ksize, int16_t *taps);

#endif
