/* Sobel, Scharr and Laplacian of 8-bit images to int16, and |int16| to u8.
 *
 * Every derivative here is an integer separable filter (the Laplacian a sum
 * of two), so the result is exact whatever the summation order and matches
 * OpenCV bit for bit. One output row at a time: a column pass over ksize
 * source rows into an int16 row with folded border columns, then a row pass
 * into the destination. Only two int16 rows of scratch are used. */
#include "rtedge/gradient.h"
#include "rtedge/cpu.h"

#include "gradient_loops.h"
#include "gradient_rows.h"
#include "simd/rows.h"

int32_t rte_border_fold(int32_t p, int32_t len, rte_border border)
{
    if (p >= 0 && p < len)
        return p;
    if (border == RTE_BORDER_REPLICATE || len == 1)
        return p < 0 ? 0 : len - 1;
    do /* reflect-101; repeats for kernels wider than the image */
        p = p < 0 ? -p : 2 * (len - 1) - p;
    while (p < 0 || p >= len);
    return p;
}

void rte_sobel_taps(int32_t order, int32_t ksize, int16_t *taps)
{
    taps[0] = 1;
    for (int32_t i = 1; i < ksize; i++)
        taps[i] = 0;
    /* (ksize - 1 - order) smoothing steps [1 1], then `order` steps [-1 1]. */
    for (int32_t s = 0; s < ksize - 1 - order; s++)
        for (int32_t j = ksize - 1; j > 0; j--)
            taps[j] = (int16_t)(taps[j] + taps[j - 1]);
    for (int32_t s = 0; s < order; s++) {
        for (int32_t j = ksize - 1; j > 0; j--)
            taps[j] = (int16_t)(taps[j - 1] - taps[j]);
        taps[0] = (int16_t)-taps[0];
    }
}

void rte_grad_column_pass(const rte_grad_rows *k, const rte_image_u8 *src, int32_t y,
                          const int16_t *ky, int32_t ny, rte_border border, int16_t *v, int32_t pad)
{
    const int32_t r = ny / 2;
    const uint8_t *row[RTE_GRAD_MAX_TAPS];
    for (int32_t j = 0; j < ny; j++)
        row[j] = rte_u8_row(src, rte_border_fold(y + j - r, src->height, border));
    rte_grad_column_rows(k, row, src->width, ky, ny, border, v, pad);
}

void rte_grad_column_rows(const rte_grad_rows *k, const uint8_t *const *row, int32_t w,
                          const int16_t *ky, int32_t ny, rte_border border, int16_t *v, int32_t pad)
{
    k->column(row, w, ky, ny, v);
    /* A column filter commutes with column folding: border columns are
     * copies of the folded ones. */
    for (int32_t x = 1; x <= pad; x++) {
        v[-x] = v[rte_border_fold(-x, w, border)];
        v[w - 1 + x] = v[rte_border_fold(w - 1 + x, w, border)];
    }
}

/* The row loops, once per instruction set (see simd/rows.h). */
RTE_GRAD_ROWS_DEFINE(c)

rte_grad_rows rte_grad_rows_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, ((rte_grad_rows){rte_grad_column_c, rte_grad_row_c}),
                         ((rte_grad_rows){rte_grad_column_avx2, rte_grad_row_avx2}),
                         ((rte_grad_rows){rte_grad_column_avx512, rte_grad_row_avx512}),
                         ((rte_grad_rows){rte_grad_column_c, rte_grad_row_c}));
}

int32_t rte_grad_taps_l1(const int16_t *taps, int32_t n)
{
    int32_t s = 0;
    for (int32_t i = 0; i < n; i++)
        s += taps[i] < 0 ? -taps[i] : taps[i];
    return s;
}

/* Bytes of one padded int16 row for images up to max_width. */
static size_t padded_row_bytes(int32_t max_width)
{
    return ((size_t)max_width + 2 * (RTE_GRAD_MAX_TAPS / 2)) * sizeof(int16_t);
}

/* Both images valid and of the same size (either may be the source). */
static rte_status check_u8_s16(const rte_image_u8 *a, const rte_image_s16 *b)
{
    rte_status st = rte_image_u8_check(a);
    if (st != RTE_OK)
        return st;
    st = rte_image_s16_check(b);
    if (st != RTE_OK)
        return st;
    if (a->width != b->width || a->height != b->height)
        return RTE_ERR_SIZE;
    return RTE_OK;
}

/* dst = kx (rows) x ky (columns), REFLECT_101. */
static rte_status separable(const rte_image_u8 *src, rte_image_s16 *dst, const int16_t *kx,
                            int32_t nx, const int16_t *ky, int32_t ny, rte_arena *scratch)
{
    rte_status st = check_u8_s16(src, dst);
    if (st != RTE_OK)
        return st;
    if (!scratch)
        return RTE_ERR_ARGUMENT;
    const rte_grad_rows k = rte_grad_rows_select(rte_cpu_features());
    const size_t mark = rte_arena_mark(scratch);
    int16_t *v = rte_arena_alloc(scratch, padded_row_bytes(src->width));
    if (!v)
        return RTE_ERR_NO_MEMORY;
    v += RTE_GRAD_MAX_TAPS / 2;
    /* Only Sobel 7 can leave int16 (up to 255 * 64 * 64). */
    const rte_row_mode mode = rte_grad_taps_l1(kx, nx) * rte_grad_taps_l1(ky, ny) * 255 > INT16_MAX
                                  ? RTE_ROW_SATURATE
                                  : RTE_ROW_FITS;
    for (int32_t y = 0; y < src->height; y++) {
        rte_grad_column_pass(&k, src, y, ky, ny, RTE_BORDER_REFLECT_101, v, nx / 2);
        k.row(v, kx, nx, rte_s16_row(dst, y), src->width, (int)mode);
    }
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}

rte_status rte_sobel_s16(const rte_image_u8 *src, rte_image_s16 *dst, int32_t dx, int32_t dy,
                         int32_t ksize, rte_arena *scratch)
{
    if (dx < 0 || dx > 2 || dy < 0 || dy > 2 || dx + dy == 0)
        return RTE_ERR_ARGUMENT;
    if (ksize != 1 && ksize != 3 && ksize != 5 && ksize != 7)
        return RTE_ERR_ARGUMENT;
    /* ksize 1: 3 taps along a derivative axis, 1 tap (no smoothing) else. */
    const int32_t nx = (ksize == 1 && dx > 0) ? 3 : ksize;
    const int32_t ny = (ksize == 1 && dy > 0) ? 3 : ksize;
    int16_t kx[RTE_GRAD_MAX_TAPS], ky[RTE_GRAD_MAX_TAPS];
    rte_sobel_taps(dx, nx, kx);
    rte_sobel_taps(dy, ny, ky);
    return separable(src, dst, kx, nx, ky, ny, scratch);
}

size_t rte_sobel_scratch_size(int32_t max_width, int32_t max_height, int32_t ksize)
{
    return max_width > 0 ? rte_arena_piece_size(padded_row_bytes(max_width)) : 0;
}

rte_status rte_scharr_s16(const rte_image_u8 *src, rte_image_s16 *dst, int32_t dx, int32_t dy,
                          rte_arena *scratch)
{
    static const int16_t smooth[3] = {3, 10, 3}, deriv[3] = {-1, 0, 1};
    if (!((dx == 1 && dy == 0) || (dx == 0 && dy == 1)))
        return RTE_ERR_ARGUMENT;
    return separable(src, dst, dx ? deriv : smooth, 3, dy ? deriv : smooth, 3, scratch);
}

size_t rte_scharr_scratch_size(int32_t max_width, int32_t max_height)
{
    return rte_sobel_scratch_size(max_width, max_height, 3);
}

rte_status rte_laplacian_s16(const rte_image_u8 *src, rte_image_s16 *dst, int32_t ksize,
                             rte_arena *scratch)
{
    if (ksize != 1 && ksize != 3)
        return RTE_ERR_ARGUMENT;
    rte_status st = check_u8_s16(src, dst);
    if (st != RTE_OK)
        return st;
    if (!scratch)
        return RTE_ERR_ARGUMENT;
    const rte_grad_rows k = rte_grad_rows_select(rte_cpu_features());
    const size_t mark = rte_arena_mark(scratch);
    int16_t *outer = rte_arena_alloc(scratch, padded_row_bytes(src->width));
    int16_t *mid = rte_arena_alloc(scratch, padded_row_bytes(src->width));
    if (!outer || !mid) {
        rte_arena_reset(scratch, mark);
        return RTE_ERR_NO_MEMORY;
    }
    outer += RTE_GRAD_MAX_TAPS / 2;
    mid += RTE_GRAD_MAX_TAPS / 2;
    /* The 3x3 kernel from two columns sums: the rows above plus below, and
     * the centre row. Both stay far inside int16 (|result| <= 8 * 255). */
    static const int16_t pick_outer[3] = {1, 0, 1}, pick_mid[1] = {1};
    const int32_t w = src->width;
    for (int32_t y = 0; y < src->height; y++) {
        rte_grad_column_pass(&k, src, y, pick_outer, 3, RTE_BORDER_REFLECT_101, outer, 1);
        const int16_t *restrict o = outer;
        int16_t *restrict d = rte_s16_row(dst, y);
        if (ksize == 1) {
            rte_grad_column_pass(&k, src, y, pick_mid, 1, RTE_BORDER_REFLECT_101, mid, 1);
            const int16_t *restrict m = mid;
            for (int32_t x = 0; x < w; x++)
                d[x] = (int16_t)(o[x] + m[x - 1] + m[x + 1] - 4 * m[x]);
        } else { /* the centre row is only needed at x itself */
            const uint8_t *restrict m = rte_u8_row(src, y);
            for (int32_t x = 0; x < w; x++)
                d[x] = (int16_t)(2 * (o[x - 1] + o[x + 1]) - 8 * m[x]);
        }
    }
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}

size_t rte_laplacian_scratch_size(int32_t max_width, int32_t max_height, int32_t ksize)
{
    return max_width > 0 ? 2 * rte_arena_piece_size(padded_row_bytes(max_width)) : 0;
}

rte_status rte_abs_s16_u8(const rte_image_s16 *src, rte_image_u8 *dst)
{
    rte_status st = check_u8_s16(dst, src);
    if (st != RTE_OK)
        return st;
    const int32_t w = src->width;
    for (int32_t y = 0; y < src->height; y++) {
        const int16_t *restrict s = rte_s16_row(src, y);
        uint8_t *restrict d = rte_u8_row(dst, y);
        for (int32_t x = 0; x < w; x++) {
            int32_t a = s[x] < 0 ? -(int32_t)s[x] : s[x];
            d[x] = (uint8_t)(a > 255 ? 255 : a);
        }
    }
    return RTE_OK;
}
