/* One output row of the Gaussian blur at a time (private to src/algo):
 * rte_gaussian_blur_u8 runs it over a whole image, and Canny's fused front
 * end (rte_canny_blurred_u8) over a band of rows that it consumes at once,
 * so no blurred image is ever stored. */
#ifndef RTEDGE_ALGO_GAUSSIAN_LINE_H
#define RTEDGE_ALGO_GAUSSIAN_LINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rtedge/arena.h"
#include "rtedge/blur.h"
#include "simd/rows.h"

typedef struct rte_gaussian_line {
    rte_gaussian_rows pass; /* the row kernels for this CPU */
    int32_t ksize_x, ksize_y;
    int split; /* two planes (hi, lo); else one (narrow path, see gaussian.c) */
    uint16_t taps_x[RTE_GAUSSIAN_MAX_KSIZE], taps_y[RTE_GAUSSIAN_MAX_KSIZE];
    uint16_t *hi, *lo; /* padded planes of column sums, from the arena */
} rte_gaussian_line;

/* A kernel rte_gaussian_blur_u8 accepts (odd sizes, symmetric taps summing to 256). */
bool rte_gaussian_kernel_is_valid(const rte_gaussian_kernel *kernel);

/* Arena bytes of rte_gaussian_line_init for rows up to max_width (kernel valid). */
size_t rte_gaussian_line_scratch_size(int32_t max_width, const rte_gaussian_kernel *kernel);

/* Prepares rows of `width` pixels with a valid kernel, the row kernels
 * chosen from `features`; the planes come from `arena`. false when the
 * arena is too small. */
bool rte_gaussian_line_init(rte_gaussian_line *line, const rte_gaussian_kernel *kernel,
                            int32_t width, uint32_t features, rte_arena *arena);

/* out = blurred row from the ksize_y source rows around it (rows[j] is
 * source row y - ksize_y/2 + j, already reflected), `width` pixels. */
void rte_gaussian_line_run(const rte_gaussian_line *line, const uint8_t *const *rows, uint8_t *out,
                           int32_t width);

/* out = row y of the blur of src (BORDER_REFLECT_101). */
void rte_gaussian_line_of_image(const rte_gaussian_line *line, const rte_image_u8 *src, int32_t y,
                                uint8_t *out);

#endif
