/* Per-frame Gaussian blur, bit-exact with OpenCV 4.6's fixed-point path for
 * 8-bit images (GaussianBlurFixedPoint): integers only.
 *
 * OpenCV computes out = (sum_j ty_j * sum_i tx_i * p(i, j) + 2^15) >> 16 with
 * Q8 taps summing to 256. Every partial sum is exact, so the passes may run
 * in either order; this one runs the column pass first because its input is
 * u8 and needs no intermediate rows, only the ksize_y source rows:
 *  - Column pass: v = sum_j ty_j * src(y - ry + j) for one output row, at
 *    most 255 * 256, so u16. Rows beyond the edges reflect (BORDER_REFLECT_101).
 *  - Row pass: out = (sum_i tx_i * v(x - rx + i) + 2^15) >> 16. That sum needs
 *    24 bits; to keep the arithmetic in u16 lanes (twice as many per vector
 *    as u32) v is stored as two planes, v >> 8 and v & 255, each padded
 *    with reflected columns, and summed separately (see row_taps).
 * Narrow path: when the taps of both axes share power-of-two factors worth
 * 8 bits together (OpenCV's sigma-0 kernels of size 3 and 5, any axis of
 * size 1), dividing them out leaves a sum of at most 255 * 256 and the
 * whole filter runs on one u16 plane, about half the work.
 * No intermediate image: per output row only one padded line of scratch, plus
 * (when working in place) copies of the source rows still needed. */
#include <string.h>

#include "blur_rows.h"
#include "gaussian_line.h"
#include "gaussian_rows.h"
#include "rtedge/blur.h"
#include "rtedge/cpu.h"
#include "simd/rows.h"

/* Scratch rows are padded to whole 64-byte lines so each starts aligned. */
static size_t line_elems(int32_t width, size_t elem_size)
{
    return ((size_t)width * elem_size + 63) / 64 * 64 / elem_size;
}

bool rte_gaussian_kernel_is_valid(const rte_gaussian_kernel *k)
{
    const int32_t sizes[2] = {k->ksize_x, k->ksize_y};
    const uint16_t *taps[2] = {k->taps_x, k->taps_y};
    for (int a = 0; a < 2; a++) {
        int32_t n = sizes[a];
        if (n < 1 || n > RTE_GAUSSIAN_MAX_KSIZE || (n & 1) == 0)
            return false;
        /* The overflow-free u16 sums need taps summing to 256; both passes
         * fold symmetric taps together. */
        uint32_t sum = 0;
        for (int32_t i = 0; i < n; i++) {
            if (taps[a][i] != taps[a][n - 1 - i])
                return false;
            sum += taps[a][i];
        }
        if (sum != 256)
            return false;
    }
    return true;
}

/* Scratch: the two planes of one padded line, and for in-place calls a ring
 * of ksize_y source rows. */
static size_t plane_elems(int32_t width, int32_t rx)
{
    return line_elems(width + 2 * rx, sizeof(uint16_t));
}

size_t rte_gaussian_line_scratch_size(int32_t max_width, const rte_gaussian_kernel *kernel)
{
    return rte_arena_piece_size(2 * plane_elems(max_width, kernel->ksize_x / 2) * sizeof(uint16_t));
}

size_t rte_gaussian_blur_u8_scratch_size(int32_t max_width, int32_t max_height,
                                         const rte_gaussian_kernel *kernel)
{
    if (!kernel || !rte_gaussian_kernel_is_valid(kernel) || max_width < 1 ||
        max_width > RTE_MAX_SIDE || max_height < 1 || max_height > RTE_MAX_SIDE)
        return 0;
    return rte_gaussian_line_scratch_size(max_width, kernel) +
           rte_arena_piece_size((size_t)kernel->ksize_y * line_elems(max_width, 1));
}

/* The row kernels, once per instruction set (see simd/rows.h). */
void rte_gaussian_column_pass_c(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,
                                int32_t width, const uint16_t *taps, int32_t ksize, int split)
{
    gaussian_column_pass(rows, hi, lo, width, taps, ksize, split);
}

void rte_gaussian_row_pass_c(const uint16_t *hi, const uint16_t *lo, uint8_t *dst, int32_t width,
                             const uint16_t *taps, int32_t ksize, int split)
{
    gaussian_row_pass(hi, lo, dst, width, taps, ksize, split);
}

rte_gaussian_rows rte_gaussian_rows_select(uint32_t features)
{
    return RTE_SIMD_PICK(
        features, ((rte_gaussian_rows){rte_gaussian_column_pass_c, rte_gaussian_row_pass_c}),
        ((rte_gaussian_rows){rte_gaussian_column_pass_avx2, rte_gaussian_row_pass_avx2}),
        ((rte_gaussian_rows){rte_gaussian_column_pass_avx512, rte_gaussian_row_pass_avx512}),
        ((rte_gaussian_rows){rte_gaussian_column_pass_c, rte_gaussian_row_pass_c}));
}

/* Power-of-two factor shared by all n taps, as a shift, at most `limit`. */
static int32_t common_shift(const uint16_t *taps, int32_t n, int32_t limit)
{
    uint32_t all = 0;
    for (int32_t i = 0; i < n; i++)
        all |= taps[i];
    int32_t shift = 0;
    while (shift < limit && ((all >> shift) & 1) == 0)
        shift++;
    return shift;
}

bool rte_gaussian_line_init(rte_gaussian_line *line, const rte_gaussian_kernel *kernel,
                            int32_t width, uint32_t features, rte_arena *arena)
{
    const int32_t kx = kernel->ksize_x, ky = kernel->ksize_y;
    const size_t plane = plane_elems(width, kx / 2);
    line->hi = rte_arena_alloc(arena, 2 * plane * sizeof(uint16_t));
    if (!line->hi)
        return false;
    line->lo = line->hi + plane;
    line->pass = rte_gaussian_rows_select(features);
    line->ksize_x = kx;
    line->ksize_y = ky;
    /* Narrow path when 8 bits of power-of-two factors can be divided out of
     * the taps (the sum then never exceeds 255 * 256; see the top). */
    const int32_t shift_y = common_shift(kernel->taps_y, ky, 8);
    const int32_t shift_x = common_shift(kernel->taps_x, kx, 8 - shift_y);
    line->split = shift_x + shift_y < 8;
    for (int32_t i = 0; i < kx; i++)
        line->taps_x[i] =
            line->split ? kernel->taps_x[i] : (uint16_t)(kernel->taps_x[i] >> shift_x);
    for (int32_t j = 0; j < ky; j++)
        line->taps_y[j] =
            line->split ? kernel->taps_y[j] : (uint16_t)(kernel->taps_y[j] >> shift_y);
    return true;
}

void rte_gaussian_line_run(const rte_gaussian_line *line, const uint8_t *const *rows, uint8_t *out,
                           int32_t width)
{
    const int32_t rx = line->ksize_x / 2;
    line->pass.column(rows, line->hi + rx, line->lo + rx, width, line->taps_y, line->ksize_y,
                      line->split);
    rte_blur_reflect101_borders_u16(line->hi, width, rx);
    if (line->split)
        rte_blur_reflect101_borders_u16(line->lo, width, rx);
    line->pass.row(line->hi, line->lo, out, width, line->taps_x, line->ksize_x, line->split);
}

void rte_gaussian_line_of_image(const rte_gaussian_line *line, const rte_image_u8 *src, int32_t y,
                                uint8_t *out)
{
    const uint8_t *rows[RTE_GAUSSIAN_MAX_KSIZE];
    const int32_t ry = line->ksize_y / 2;
    for (int32_t j = 0; j < line->ksize_y; j++)
        rows[j] = rte_u8_row(src, rte_blur_reflect101(y - ry + j, src->height));
    rte_gaussian_line_run(line, rows, out, src->width);
}

rte_status rte_gaussian_blur_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                const rte_gaussian_kernel *kernel, rte_arena *arena)
{
    rte_status st = rte_blur_check_views(src, dst);
    if (st != RTE_OK)
        return st;
    if (!kernel || !arena || !rte_gaussian_kernel_is_valid(kernel))
        return RTE_ERR_ARGUMENT;

    const int32_t width = src->width, height = src->height;
    const int32_t ky = kernel->ksize_y, ry = ky / 2;
    const int in_place = src->buf == dst->buf;
    const size_t ring_stride = line_elems(width, 1);

    const size_t mark = rte_arena_mark(arena);
    rte_gaussian_line line;
    const bool ok = rte_gaussian_line_init(&line, kernel, width, rte_cpu_features(), arena);
    uint8_t *ring = in_place ? rte_arena_alloc(arena, (size_t)ky * ring_stride) : NULL;
    if (!ok || (in_place && !ring)) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    /* In place, source row y is copied into ring slot (y % ky) before the
     * first output row that needs it, and dst row y is written after copying
     * row y + ry: an output row reads source rows within ry of it only
     * (reflection stays inside that window). */
    int32_t copied = 0;
    for (int32_t y = 0; y < height; y++) {
        if (!in_place) {
            rte_gaussian_line_of_image(&line, src, y, rte_u8_row(dst, y));
            continue;
        }
        const uint8_t *rows[RTE_GAUSSIAN_MAX_KSIZE];
        int32_t last = y + ry < height ? y + ry : height - 1;
        for (; copied <= last; copied++)
            memcpy(ring + (size_t)(copied % ky) * ring_stride, rte_u8_row(src, copied),
                   (size_t)width);
        for (int32_t j = 0; j < ky; j++)
            rows[j] = ring + (size_t)(rte_blur_reflect101(y - ry + j, height) % ky) * ring_stride;
        rte_gaussian_line_run(&line, rows, rte_u8_row(dst, y), width);
    }

    rte_arena_reset(arena, mark);
    return RTE_OK;
}
