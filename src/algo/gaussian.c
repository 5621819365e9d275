/* Per-frame Gaussian blur, bit-exact with OpenCV 4.6's fixed-point path for
 * 8-bit images (GaussianBlurFixedPoint): integers only.
 *
 *  - Row pass: each source row is copied into a padded u16 row
 *    (BORDER_REFLECT_101 on both sides), then convolved with the Q8 x taps
 *    into u16. The sum cannot overflow: the taps add up to 256, so it is at
 *    most 255 * 256.
 *  - Column pass: the last ksize_y filtered rows live in a ring buffer; each
 *    output row is sum(tap_y * row) rounded from Q16: (v + 2^15) >> 16.
 *    That sum needs 24 bits; to keep the arithmetic in u16 lanes (twice as
 *    many per vector as u32) the row pass stores each filtered value v as
 *    two planes, v >> 8 and v & 255, and the column pass sums each plane
 *    separately (see column_taps).
 *
 * Both sums are exact, so the order of additions does not matter and the
 * result equals OpenCV's whatever vector path it takes. */
#include <string.h>

#include "blur_rows.h"
#include "rtedge/blur.h"

/* Ring planes are padded to whole 64-byte lines so every one starts aligned.
 * A ring row is two planes (high and low bytes of the filtered values). */
static size_t ring_stride(int32_t width)
{
    return ((size_t)width + 31) & ~(size_t)31;
}

static int kernel_is_valid(const rte_gaussian_kernel *k)
{
    const int32_t sizes[2] = { k->ksize_x, k->ksize_y };
    const uint16_t *taps[2] = { k->taps_x, k->taps_y };
    for (int a = 0; a < 2; a++) {
        int32_t n = sizes[a];
        if (n < 1 || n > RTE_GAUSSIAN_MAX_KSIZE || (n & 1) == 0)
            return 0;
        /* The overflow-free u16 row sums need taps summing to 256; the row
         * and column kernels fold symmetric taps together. */
        uint32_t sum = 0;
        for (int32_t i = 0; i < n; i++) {
            if (taps[a][i] != taps[a][n - 1 - i])
                return 0;
            sum += taps[a][i];
        }
        if (sum != 256)
            return 0;
    }
    return 1;
}

size_t rte_gaussian_blur_u8_scratch_size(int32_t max_width, int32_t max_height,
                                         const rte_gaussian_kernel *kernel)
{
    if (!kernel || !kernel_is_valid(kernel) || max_width < 1 || max_width > RTE_MAX_SIDE ||
        max_height < 1 || max_height > RTE_MAX_SIDE)
        return 0;
    int32_t rx = kernel->ksize_x / 2;
    return rte_arena_piece_size((size_t)kernel->ksize_y * 2 * ring_stride(max_width) * sizeof(uint16_t)) +
           rte_arena_piece_size(((size_t)max_width + 2 * (size_t)rx) * sizeof(uint16_t));
}

/* v = sum_j taps[j] * pad[x + j] (taps symmetric), stored as hi = v >> 8
 * and lo = v & 255. The radius r is a constant in each caller so the tap
 * loop unrolls and the x loop vectorises in u16 lanes. */
static inline void row_taps(const uint16_t *restrict pad, uint16_t *restrict hi,
                            uint16_t *restrict lo, int32_t width, const uint16_t *restrict taps,
                            int32_t r)
{
    for (int32_t x = 0; x < width; x++) {
        uint16_t s = (uint16_t)(taps[r] * pad[x + r]);
        for (int32_t j = 0; j < r; j++)
            s = (uint16_t)(s + taps[j] * (uint16_t)(pad[x + j] + pad[x + 2 * r - j]));
        hi[x] = (uint16_t)(s >> 8);
        lo[x] = (uint16_t)(s & 255);
    }
}

static void row_pass(const uint16_t *pad, uint16_t *hi, uint16_t *lo, int32_t width,
                     const uint16_t *taps, int32_t ksize)
{
    switch (ksize / 2) {
    case 0: row_taps(pad, hi, lo, width, taps, 0); break;
    case 1: row_taps(pad, hi, lo, width, taps, 1); break;
    case 2: row_taps(pad, hi, lo, width, taps, 2); break;
    case 3: row_taps(pad, hi, lo, width, taps, 3); break;
    case 4: row_taps(pad, hi, lo, width, taps, 4); break;
    case 5: row_taps(pad, hi, lo, width, taps, 5); break;
    case 6: row_taps(pad, hi, lo, width, taps, 6); break;
    default: row_taps(pad, hi, lo, width, taps, 7); break;
    }
}

/* dst[x] = (sum_j taps[j] * v_j[x] + 2^15) >> 16 where row j holds
 * v_j = 256 * hi_j + lo_j. With H = sum taps * hi_j and L = sum taps * lo_j
 * (each at most 255 * 256, so u16):
 *   sum = 256 * H + L  and  (sum + 2^15) >> 16 = (H + (L >> 8) + 128) >> 8,
 * where H + (L >> 8) <= 255 * 256 (as sum <= 255 * 2^16), so nothing
 * overflows. rows[j] is the high plane of row j, rows[j] + plane the low. */
static inline void column_taps(const uint16_t *const *restrict rows, size_t plane,
                               uint8_t *restrict dst, int32_t width, const uint16_t *restrict taps,
                               int32_t r)
{
    const uint16_t *restrict mid = rows[r];
    for (int32_t x = 0; x < width; x++) {
        uint16_t hs = (uint16_t)(taps[r] * mid[x]);
        uint16_t ls = (uint16_t)(taps[r] * mid[x + plane]);
        for (int32_t j = 0; j < r; j++) {
            const uint16_t *a = rows[j], *b = rows[2 * r - j];
            hs = (uint16_t)(hs + taps[j] * (uint16_t)(a[x] + b[x]));
            ls = (uint16_t)(ls + taps[j] * (uint16_t)(a[x + plane] + b[x + plane]));
        }
        dst[x] = (uint8_t)((uint16_t)(hs + (ls >> 8) + 128) >> 8);
    }
}

static void column_pass(const uint16_t *const *rows, size_t plane, uint8_t *dst, int32_t width,
                        const uint16_t *taps, int32_t ksize)
{
    switch (ksize / 2) {
    case 0: column_taps(rows, plane, dst, width, taps, 0); break;
    case 1: column_taps(rows, plane, dst, width, taps, 1); break;
    case 2: column_taps(rows, plane, dst, width, taps, 2); break;
    case 3: column_taps(rows, plane, dst, width, taps, 3); break;
    case 4: column_taps(rows, plane, dst, width, taps, 4); break;
    case 5: column_taps(rows, plane, dst, width, taps, 5); break;
    case 6: column_taps(rows, plane, dst, width, taps, 6); break;
    default: column_taps(rows, plane, dst, width, taps, 7); break;
    }
}

rte_status rte_gaussian_blur_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                const rte_gaussian_kernel *kernel, rte_arena *arena)
{
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    if (!kernel || !arena || !kernel_is_valid(kernel))
        return RTE_ERR_ARGUMENT;

    const int32_t width = src->width, height = src->height;
    const int32_t kx = kernel->ksize_x, ky = kernel->ksize_y;
    const int32_t rx = kx / 2, ry = ky / 2;
    const size_t rstride = ring_stride(width);

    const size_t mark = rte_arena_mark(arena);
    uint16_t *ring = rte_arena_alloc(arena, (size_t)ky * 2 * rstride * sizeof(uint16_t));
    uint16_t *pad = rte_arena_alloc(arena, ((size_t)width + 2 * (size_t)rx) * sizeof(uint16_t));
    if (!ring || !pad) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    /* Source rows are filtered into ring slot (y % ky) just before the first
     * output row that needs them. An output row needs source rows within
     * ry of it only (reflection stays inside that window), so writing dst
     * row y after filtering row y + ry also works in place. */
    int32_t filtered = 0;
    for (int32_t y = 0; y < height; y++) {
        int32_t last = y + ry < height ? y + ry : height - 1;
        for (; filtered <= last; filtered++) {
            uint16_t *hi = ring + (size_t)(filtered % ky) * 2 * rstride;
            rte_blur_pad_row_reflect101_u16(rte_u8_row(src, filtered), pad, width, rx);
            row_pass(pad, hi, hi + rstride, width, kernel->taps_x, kx);
        }
        const uint16_t *rows[RTE_GAUSSIAN_MAX_KSIZE];
        for (int32_t j = 0; j < ky; j++) {
            int32_t sy = rte_blur_reflect101(y - ry + j, height);
            rows[j] = ring + (size_t)(sy % ky) * 2 * rstride;
        }
        column_pass(rows, rstride, rte_u8_row(dst, y), width, kernel->taps_y, ky);
    }

    rte_arena_reset(arena, mark);
    return RTE_OK;
}
