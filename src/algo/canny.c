/* Canny edge detector (see include/rtedge/canny.h), integer only.
 *
 * One pass over the rows: for row i the Sobel derivatives and magnitude are
 * computed, then row i-1 is suppressed against rows i-2, i-1 and i, so only
 * three magnitude rows and two derivative rows are alive. The fused front
 * end (rte_canny_blurred_u8) blurs each source row just before the Sobel
 * needs it, into a ring of `aperture` rows, so the blurred image is never
 * stored either. Aperture 3 with the L1 magnitude on 8-bit images (the
 * common case) runs in 16-bit row kernels with SIMD variants (canny_rows.h,
 * simd/rows.h); the other cases in the generic 32-bit rows below. Suppression writes
 * an edge map with a 1-pixel frame: 1 = not an edge, 0 = maybe (a local
 * maximum above low), 2 = edge. Seeds (local maxima above high) go on a
 * stack, and the flood through 8-connected "maybe" pixels follows when all
 * rows are done. Each pixel is pushed at most once (when it becomes 2), so a
 * stack of width*height entries cannot overflow. */
#include <stdint.h>
#include <string.h>

#include "rtedge/canny.h"
#include "rtedge/cpu.h"

#include "canny_rows.h"
#include "core/image_checks.h"
#include "gaussian_line.h"
#include "gradient_rows.h"
#include "simd/rows.h"

static size_t map_bytes(int32_t w, int32_t h) { return ((size_t)w + 2) * ((size_t)h + 2); }
static size_t stack_bytes(int32_t w, int32_t h) { return (size_t)w * (size_t)h * sizeof(int32_t); }
static size_t mag_row_bytes(int32_t w) { return ((size_t)w + 2) * sizeof(int32_t); }
static size_t column_row_bytes(int32_t w)
{
    return ((size_t)w + 2 * (RTE_GRAD_MAX_TAPS / 2)) * sizeof(int16_t);
}
static size_t deriv_row_bytes(int32_t w) { return (size_t)w * sizeof(int16_t); }

/* The fused front end's ring of blurred rows: `aperture` rows of whole
 * 64-byte lines. */
static size_t blur_ring_stride(int32_t w) { return ((size_t)w + 63) / 64 * 64; }

size_t rte_canny_scratch_size(int32_t max_width, int32_t max_height, int32_t aperture)
{
    if (max_width <= 0 || max_height <= 0)
        return 0;
    /* Where size_t is 32 bits, the largest images do not fit at all. */
    if ((uint64_t)max_width * (uint64_t)max_height * 8u > (uint64_t)(SIZE_MAX / 2))
        return SIZE_MAX;
    return rte_arena_piece_size(map_bytes(max_width, max_height)) +
           rte_arena_piece_size(stack_bytes(max_width, max_height)) +
           3 * rte_arena_piece_size(mag_row_bytes(max_width)) +
           2 * rte_arena_piece_size(column_row_bytes(max_width)) +
           4 * rte_arena_piece_size(deriv_row_bytes(max_width));
}

size_t rte_canny_blurred_scratch_size(int32_t max_width, int32_t max_height,
                                      const rte_gaussian_kernel *kernel, int32_t aperture)
{
    const size_t canny = rte_canny_scratch_size(max_width, max_height, aperture);
    if (canny == 0 || canny == SIZE_MAX || !kernel || !rte_gaussian_kernel_is_valid(kernel) ||
        aperture < 1 || aperture > RTE_GRAD_MAX_TAPS)
        return canny == SIZE_MAX ? SIZE_MAX : 0;
    return canny + rte_gaussian_line_scratch_size(max_width, kernel) +
           rte_arena_piece_size((size_t)aperture * blur_ring_stride(max_width));
}

/* The row kernels of aperture 3 with L1, once per instruction set. */
RTE_CANNY_ROWS_DEFINE(c)

rte_canny_rows rte_canny_rows_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, ((rte_canny_rows){rte_canny_sobel_row_c, rte_canny_nms_row_c}),
                         ((rte_canny_rows){rte_canny_sobel_row_avx2, rte_canny_nms_row_avx2}),
                         ((rte_canny_rows){rte_canny_sobel_row_avx512, rte_canny_nms_row_avx512}),
                         ((rte_canny_rows){rte_canny_sobel_row_neon, rte_canny_nms_row_neon}));
}

/* A threshold for the 16-bit kernels: magnitudes are 0..2040 there, so
 * clamping to -1..INT16_MAX keeps every comparison m > t. */
static int16_t threshold16(int32_t t)
{
    return (int16_t)(t < -1 ? -1 : t > INT16_MAX ? INT16_MAX : t);
}

static void magnitude_row(const int16_t *restrict dx, const int16_t *restrict dy,
                          int32_t *restrict mag, int32_t w, bool l2)
{
    if (l2) {
        /* 32-bit wrap-around as OpenCV's (only -32768 in both can wrap). */
        for (int32_t x = 0; x < w; x++)
            mag[x] = (int32_t)((uint32_t)(dx[x] * dx[x]) + (uint32_t)(dy[x] * dy[x]));
    } else {
        for (int32_t x = 0; x < w; x++)
            mag[x] = (dx[x] < 0 ? -dx[x] : dx[x]) + (dy[x] < 0 ? -dy[x] : dy[x]);
    }
    mag[-1] = mag[w] = 0;
}

/* Non-maximum suppression of one row into map codes 0/1/2 (see top). The
 * gradient direction picks the two neighbours across the edge: horizontal
 * when |dy| < |dx| tan 22.5, vertical when |dy| > |dx| tan 67.5, else the
 * diagonal whose slope has the sign of dx*dy. Ties go to the later pixel
 * along the row or column (>=), strictly on diagonals, as OpenCV. */
static void suppress_row(const int32_t *restrict up, const int32_t *restrict cur,
                         const int32_t *restrict down, const int16_t *restrict dx,
                         const int16_t *restrict dy, uint8_t *restrict map, int32_t w, int32_t low,
                         int32_t high)
{
    for (int32_t x = 0; x < w; x++) {
        const int32_t m = cur[x];
        const int32_t xs = dx[x], ys = dy[x];
        const int32_t ax = xs < 0 ? -xs : xs;
        const int32_t ay = (ys < 0 ? -ys : ys) << 15;
        const int32_t tg22 = ax * RTE_CANNY_TG22_Q15;
        /* tan 67.5 = tan 22.5 + 2; wraps in 32 bits as OpenCV's for |dx| > 27145. */
        const int32_t tg67 = (int32_t)((uint32_t)tg22 + ((uint32_t)ax << 16));
        /* All neighbours are loaded, then selected: no branches, so the
         * loop vectorises. */
        const int32_t ul = up[x - 1], uc = up[x], ur = up[x + 1];
        const int32_t cl = cur[x - 1], cr = cur[x + 1];
        const int32_t dl = down[x - 1], dc = down[x], dr = down[x + 1];
        const int32_t same_sign = (xs ^ ys) >= 0;
        const int32_t diag_a = same_sign ? ul : ur;
        const int32_t diag_b = same_sign ? dr : dl;
        const int32_t keep_h = (m > cl) & (m >= cr);
        const int32_t keep_v = (m > uc) & (m >= dc);
        const int32_t keep_d = (m > diag_a) & (m > diag_b);
        /* Horizontal is tested first: with a wrapped tg67 both tests can hold. */
        const int32_t horizontal = ay < tg22;
        const int32_t vertical = !horizontal & (ay > tg67);
        const int32_t keep =
            ((horizontal & keep_h) | (vertical & keep_v) | (!horizontal & !vertical & keep_d)) &
            (m > low);
        map[x] = (uint8_t)(keep ? ((m > high) << 1) : 1);
    }
}

/* Pushes the offsets of the seeds (code 2) of a map row. Seeds are sparse:
 * 8 codes at a time are skipped when none has bit 1 set. The stack never
 * holds more entries than pixels seen so far. */
static int32_t push_seeds(const uint8_t *mrow, int32_t w, int32_t base, int32_t *restrict stack,
                          int32_t top)
{
    int32_t x = 0;
    for (; x + 8 <= w; x += 8) {
        uint64_t codes;
        memcpy(&codes, mrow + x, sizeof codes);
        if (!(codes & 0x0202020202020202u))
            continue;
        for (int32_t k = x; k < x + 8; k++) {
            stack[top] = base + k;
            top += mrow[k] == 2;
        }
    }
    for (; x < w; x++) {
        stack[top] = base + x;
        top += mrow[x] == 2;
    }
    return top;
}

/* Where the derivative rows come from: the Sobel of src, of its blur
 * (fused front end: blur != NULL), or the given gx, gy. With out_dx and
 * out_dy, the Sobel rows of src are written there instead of to scratch. */
typedef struct canny_input {
    const rte_image_u8 *src;
    const rte_image_s16 *gx, *gy;
    const rte_image_s16 *out_dx, *out_dy;
    const rte_gaussian_line *blur;
    uint8_t *ring; /* blurred row r in slot r % aperture */
    size_t ring_stride;
    int32_t blurred; /* rows blurred so far */
    uint32_t features;
} canny_input;

/* The `ap` rows of the 8-bit image around row i (replicated at the top and
 * bottom, as Canny's Sobel), blurring the rows not yet blurred. A window of
 * ap consecutive rows never shares a ring slot. */
static void input_rows(canny_input *in, int32_t i, int32_t ap, const uint8_t **rows)
{
    const int32_t h = in->src->height, r = ap / 2;
    if (in->blur) {
        const int32_t last = i + r < h ? i + r : h - 1;
        for (; in->blurred <= last; in->blurred++)
            rte_gaussian_line_of_image(in->blur, in->src, in->blurred,
                                       in->ring + (size_t)(in->blurred % ap) * in->ring_stride);
    }
    for (int32_t k = 0; k < ap; k++) {
        const int32_t y = rte_border_fold(i + k - r, h, RTE_BORDER_REPLICATE);
        rows[k] = in->blur ? in->ring + (size_t)(y % ap) * in->ring_stride : rte_u8_row(in->src, y);
    }
}

/* Hysteresis: grow the edges through "maybe" pixels; the frame of 1s
 * stops the flood at the image border. */
static void grow_edges(uint8_t *map, ptrdiff_t ms, int32_t *stack, int32_t top)
{
    const ptrdiff_t nb[8] = {-ms - 1, -ms, -ms + 1, -1, 1, ms - 1, ms, ms + 1};
    while (top > 0) {
        const int32_t p = stack[--top];
        for (int k = 0; k < 8; k++) {
            uint8_t *q = map + p + nb[k];
            if (*q == 0) {
                *q = 2;
                stack[top++] = (int32_t)(p + nb[k]);
            }
        }
    }
}

/* (w and h as values: through dst, each byte stored could change them,
 * and the loop would neither keep them in registers nor vectorise) */
static void write_edges(const uint8_t *map, ptrdiff_t ms, rte_image_u8 *dst, int32_t w, int32_t h)
{
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *restrict mrow = map + (ptrdiff_t)(y + 1) * ms + 1;
        uint8_t *restrict d = rte_u8_row(dst, y);
        for (int32_t x = 0; x < w; x++)
            d[x] = (uint8_t)(mrow[x] == 2 ? 255 : 0);
    }
}

/* canny_run's scratch: the edge map with its frame, the seed stack, three
 * magnitude rows and, from an 8-bit image, the derivative rows. */
typedef struct canny_buffers {
    uint8_t *map;
    int32_t *stack;
    int32_t *ring[3];
    int16_t *vs, *vd, *dxb[2], *dyb[2];
} canny_buffers;

static bool alloc_buffers(canny_buffers *b, rte_arena *scratch, int32_t w, int32_t h,
                          bool from_image)
{
    *b = (canny_buffers){0};
    b->map = rte_arena_alloc(scratch, map_bytes(w, h));
    b->stack = rte_arena_alloc(scratch, stack_bytes(w, h));
    bool ok = b->map && b->stack;
    for (int k = 0; k < 3; k++) {
        b->ring[k] = rte_arena_alloc(scratch, mag_row_bytes(w));
        ok = ok && b->ring[k];
    }
    if (!from_image)
        return ok;
    b->vs = rte_arena_alloc(scratch, column_row_bytes(w));
    b->vd = rte_arena_alloc(scratch, column_row_bytes(w));
    ok = ok && b->vs && b->vd;
    for (int k = 0; k < 2; k++) {
        b->dxb[k] = rte_arena_alloc(scratch, deriv_row_bytes(w));
        b->dyb[k] = rte_arena_alloc(scratch, deriv_row_bytes(w));
        ok = ok && b->dxb[k] && b->dyb[k];
    }
    return ok;
}

/* Derivative row y (dx: which 0, dy: 1): the caller's, the scratch pair's,
 * or the given gradient's. */
static int16_t *deriv_row(const canny_input *in, const canny_buffers *b, int which, int32_t y)
{
    const rte_image_s16 *img =
        which ? (in->src ? in->out_dy : in->gy) : (in->src ? in->out_dx : in->gx);
    if (img)
        return rte_s16_row(img, y);
    return which ? b->dyb[y & 1] : b->dxb[y & 1];
}

static rte_status canny_run(canny_input *in, rte_image_u8 *dst, const rte_canny_params *params,
                            rte_arena *scratch)
{
    const rte_image_u8 *src = in->src;
    const int32_t w = dst->width, h = dst->height;
    const ptrdiff_t ms = (ptrdiff_t)w + 2;
    const size_t mark = rte_arena_mark(scratch);
    canny_buffers b;
    if (!alloc_buffers(&b, scratch, w, h, src != NULL)) {
        rte_arena_reset(scratch, mark);
        return RTE_ERR_NO_MEMORY;
    }
    uint8_t *map = b.map;
    int32_t *stack = b.stack, **ring = b.ring;
    int16_t *vs = b.vs, *vd = b.vd;

    const int32_t ap = params->aperture;
    /* Apertures 3 and 5 stay inside int16 (|dx| <= 255 * 6 * 16); OpenCV
     * scales aperture 7 by 1/16 (exactly, in float, then rounds to even). */
    const rte_row_mode row_mode = ap == 7 ? RTE_ROW_ROUND_DIV16 : RTE_ROW_FITS;
    int16_t smooth[RTE_GRAD_MAX_TAPS], deriv[RTE_GRAD_MAX_TAPS];
    if (src) {
        rte_sobel_taps(0, ap, smooth);
        rte_sobel_taps(1, ap, deriv);
        vs += RTE_GRAD_MAX_TAPS / 2;
        vd += RTE_GRAD_MAX_TAPS / 2;
    }

    /* Aperture 3 with L1 on 8-bit input: 16-bit kernels, magnitude rows
     * as int16 in the same ring. */
    const bool fast = src && ap == 3 && !params->l2_gradient;
    const rte_canny_rows kernels = rte_canny_rows_select(in->features);
    const rte_grad_rows grad = rte_grad_rows_select(in->features);
    const int16_t low16 = threshold16(params->low), high16 = threshold16(params->high);
    int16_t *ring16[3] = {(int16_t *)ring[0], (int16_t *)ring[1], (int16_t *)ring[2]};

    memset(map, 1, (size_t)ms);
    memset(map + (ptrdiff_t)(h + 1) * ms, 1, (size_t)ms);
    memset(ring[2], 0, mag_row_bytes(w)); /* row -1: magnitudes outside are 0 */
    int32_t top = 0;

    /* Magnitude row r lives in ring[r % 3]; row y is suppressed once row
     * y + 1 exists. */
    for (int32_t i = 0; i <= h; i++) {
        int32_t *next = ring[i % 3] + 1;
        int16_t *next16 = ring16[i % 3] + 1;
        if (i < h) {
            const uint8_t *rows[RTE_GRAD_MAX_TAPS];
            if (src)
                input_rows(in, i, ap, rows);
            int16_t *dxr = deriv_row(in, &b, 0, i), *dyr = deriv_row(in, &b, 1, i);
            if (fast) {
                kernels.sobel(rows[0], rows[1], rows[2], dxr, dyr, next16, w);
                next16[-1] = next16[w] = 0;
            } else {
                if (src) {
                    rte_grad_column_rows(&grad, rows, w, smooth, ap, RTE_BORDER_REPLICATE, vs,
                                         ap / 2);
                    rte_grad_column_rows(&grad, rows, w, deriv, ap, RTE_BORDER_REPLICATE, vd,
                                         ap / 2);
                    grad.row(vs, deriv, ap, dxr, w, (int)row_mode);
                    grad.row(vd, smooth, ap, dyr, w, (int)row_mode);
                }
                magnitude_row(dxr, dyr, next, w, params->l2_gradient);
            }
        } else {
            memset(next - 1, 0, mag_row_bytes(w));
        }
        if (i == 0)
            continue;

        const int32_t y = i - 1;
        const int16_t *dxr = deriv_row(in, &b, 0, y), *dyr = deriv_row(in, &b, 1, y);
        uint8_t *mrow = map + (ptrdiff_t)(y + 1) * ms + 1;
        mrow[-1] = mrow[w] = 1;
        if (fast)
            kernels.nms(ring16[(y + 2) % 3] + 1, ring16[y % 3] + 1, next16, dxr, dyr, mrow, w,
                        low16, high16);
        else
            suppress_row(ring[(y + 2) % 3] + 1, ring[y % 3] + 1, next, dxr, dyr, mrow, w,
                         params->low, params->high);
        top = push_seeds(mrow, w, (int32_t)((y + 1) * ms + 1), stack, top);
    }

    grow_edges(map, ms, stack, top);
    write_edges(map, ms, dst, w, h);
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}

static bool params_are_valid(const rte_canny_params *params)
{
    return params && (params->aperture == 3 || params->aperture == 5 || params->aperture == 7);
}

rte_status rte_canny_u8(const rte_image_u8 *src, rte_image_u8 *dst, const rte_canny_params *params,
                        rte_arena *scratch)
{
    if (!params_are_valid(params) || !scratch)
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    canny_input in = {.src = src, .features = rte_cpu_features()};
    return canny_run(&in, dst, params, scratch);
}

rte_status rte_canny_gradient_u8(const rte_image_u8 *src, rte_image_u8 *dst, rte_image_s16 *dx,
                                 rte_image_s16 *dy, const rte_canny_params *params,
                                 rte_arena *scratch)
{
    /* Aperture 7's derivatives are scaled by 1/16 inside Canny: not cv::Sobel's. */
    if (!params || !scratch || (params->aperture != 3 && params->aperture != 5))
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st == RTE_OK)
        st = rte_image_s16_check_gradient(dx, dy, src->width, src->height);
    if (st != RTE_OK)
        return st;
    if (dx->buf == dy->buf)
        return RTE_ERR_ARGUMENT;
    canny_input in = {.src = src, .out_dx = dx, .out_dy = dy, .features = rte_cpu_features()};
    return canny_run(&in, dst, params, scratch);
}

rte_status rte_canny_blurred_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                const rte_gaussian_kernel *kernel, const rte_canny_params *params,
                                rte_arena *scratch)
{
    if (!params_are_valid(params) || !scratch || !kernel || !rte_gaussian_kernel_is_valid(kernel))
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    const int32_t ap = params->aperture;
    canny_input in = {
        .src = src, .features = rte_cpu_features(), .ring_stride = blur_ring_stride(src->width)};
    const size_t mark = rte_arena_mark(scratch);
    rte_gaussian_line line;
    const bool ok = rte_gaussian_line_init(&line, kernel, src->width, in.features, scratch);
    in.ring = rte_arena_alloc(scratch, (size_t)ap * in.ring_stride);
    in.blur = &line;
    st = ok && in.ring ? canny_run(&in, dst, params, scratch) : RTE_ERR_NO_MEMORY;
    rte_arena_reset(scratch, mark);
    return st;
}

rte_status rte_canny_from_gradient_u8(const rte_image_s16 *dx, const rte_image_s16 *dy,
                                      rte_image_u8 *dst, const rte_canny_params *params,
                                      rte_arena *scratch)
{
    /* Aperture-7 params hold thresholds divided by 16: not for given dx, dy. */
    if (!params || !scratch || (params->aperture != 3 && params->aperture != 5))
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_image_s16_check(dx);
    if (st == RTE_OK)
        st = rte_image_s16_check(dy);
    if (st == RTE_OK)
        st = rte_image_u8_check(dst);
    if (st != RTE_OK)
        return st;
    if (dx->width != dst->width || dx->height != dst->height || dy->width != dst->width ||
        dy->height != dst->height)
        return RTE_ERR_SIZE;
    canny_input in = {.gx = dx, .gy = dy, .features = rte_cpu_features()};
    return canny_run(&in, dst, params, scratch);
}
