/* Camera frames to grey, bit-exact with OpenCV 4.6's cvtColor (8-bit). */
#include <stdbool.h>
#include <string.h>

#include "rtedge/color.h"
#include "rtedge/cpu.h"
#include "simd/rows.h"

/* Bytes of one row of plane 0 for a format, 0 when the format is unknown. */
static int32_t plane0_row_bytes(rte_pixel_format format, int32_t width)
{
    switch (format) {
    case RTE_PIXEL_GREY:
    case RTE_PIXEL_NV12: return width;
    case RTE_PIXEL_YUYV:
    case RTE_PIXEL_UYVY: return 2 * width;
    case RTE_PIXEL_BGR24:
    case RTE_PIXEL_RGB24: return 3 * width;
    }
    return 0;
}

/* NV12's chroma plane: one U,V pair per 2x2 block, odd sizes rounded up. */
static int32_t nv12_uv_row_bytes(int32_t width) { return 2 * ((width + 1) / 2); }
static int32_t nv12_uv_rows(int32_t height) { return (height + 1) / 2; }

static int size_ok(int32_t width, int32_t height)
{
    return width >= 1 && height >= 1 && width <= RTE_MAX_SIDE && height <= RTE_MAX_SIDE;
}

rte_status rte_frame_check(const rte_frame *frame)
{
    if (!frame)
        return RTE_ERR_ARGUMENT;
    if (plane0_row_bytes(frame->format, 1) == 0 || !frame->plane[0])
        return RTE_ERR_ARGUMENT;
    if (!size_ok(frame->width, frame->height) ||
        frame->stride[0] < plane0_row_bytes(frame->format, frame->width))
        return RTE_ERR_SIZE;
    if (frame->format == RTE_PIXEL_NV12) {
        if (!frame->plane[1])
            return RTE_ERR_ARGUMENT;
        if (frame->stride[1] < nv12_uv_row_bytes(frame->width))
            return RTE_ERR_SIZE;
    }
    return RTE_OK;
}

size_t rte_frame_packed_size(rte_pixel_format format, int32_t width, int32_t height)
{
    if (!size_ok(width, height))
        return 0;
    size_t size = (size_t)plane0_row_bytes(format, width) * (size_t)height;
    if (format == RTE_PIXEL_NV12)
        size += (size_t)nv12_uv_row_bytes(width) * (size_t)nv12_uv_rows(height);
    return size;
}

rte_status rte_frame_packed(rte_frame *frame, rte_pixel_format format, int32_t width,
                            int32_t height, void *buf, size_t size)
{
    if (!frame || !buf)
        return RTE_ERR_ARGUMENT;
    if (!size_ok(width, height))
        return RTE_ERR_SIZE;
    size_t need = rte_frame_packed_size(format, width, height);
    if (need == 0)
        return RTE_ERR_ARGUMENT;
    if (size < need)
        return RTE_ERR_SIZE;
    rte_frame f = {format, width, height, {(uint8_t *)buf, NULL}, {0, 0}};
    f.stride[0] = plane0_row_bytes(format, width);
    if (format == RTE_PIXEL_NV12) {
        f.plane[1] = f.plane[0] + (size_t)f.stride[0] * (size_t)height;
        f.stride[1] = nv12_uv_row_bytes(width);
    }
    *frame = f;
    return RTE_OK;
}

static const struct {
    const char *name;
    rte_pixel_format format;
} format_names[] = {
    {"grey", RTE_PIXEL_GREY}, {"bgr24", RTE_PIXEL_BGR24}, {"rgb24", RTE_PIXEL_RGB24},
    {"yuyv", RTE_PIXEL_YUYV}, {"uyvy", RTE_PIXEL_UYVY},   {"nv12", RTE_PIXEL_NV12},
    {"gray", RTE_PIXEL_GREY}, {"yuy2", RTE_PIXEL_YUYV},
};
#define FORMAT_NAME_COUNT (sizeof format_names / sizeof format_names[0])

const char *rte_pixel_format_name(rte_pixel_format format)
{
    for (size_t i = 0; i < FORMAT_NAME_COUNT; i++)
        if (format_names[i].format == format)
            return format_names[i].name;
    return "unknown";
}

static int ascii_lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

rte_pixel_format rte_pixel_format_parse(const char *name)
{
    if (!name)
        return (rte_pixel_format)0;
    for (size_t i = 0; i < FORMAT_NAME_COUNT; i++) {
        const char *a = format_names[i].name, *b = name;
        while (*a && ascii_lower((unsigned char)*b) == *a)
            a++, b++;
        if (!*a && !*b)
            return format_names[i].format;
    }
    return (rte_pixel_format)0;
}

/* One interleaved 3-byte row to grey; c0/c2 are the weights of the first and
 * third byte. Inlined with constants so each order gets its own loop. This
 * is the reference for the SIMD rows in simd/color_*.c and what runs when
 * the CPU has none of them or RTE_FORCE_C is set. */
static inline void c3_row_to_gray(const uint8_t *restrict src, uint8_t *restrict dst, int32_t width,
                                  uint32_t c0, uint32_t c2)
{
    for (int32_t x = 0; x < width; x++) {
        uint32_t v = src[3 * x] * c0 + src[3 * x + 1] * (uint32_t)RTE_GRAY_G + src[3 * x + 2] * c2;
        dst[x] = (uint8_t)((v + (1u << (RTE_GRAY_SHIFT - 1))) >> RTE_GRAY_SHIFT);
    }
}

void rte_row_bgr_to_gray_c(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_row_to_gray(src, dst, width, RTE_GRAY_B, RTE_GRAY_R);
}

void rte_row_rgb_to_gray_c(const uint8_t *src, uint8_t *dst, int32_t width)
{
    c3_row_to_gray(src, dst, width, RTE_GRAY_R, RTE_GRAY_B);
}

rte_row_c3_to_gray_fn rte_row_c3_to_gray_select(uint32_t features, bool rgb)
{
#ifdef RTE_SIMD_X86
    if (features & RTE_CPU_X86_AVX2)
        return rgb ? rte_row_rgb_to_gray_avx2 : rte_row_bgr_to_gray_avx2;
    if (features & RTE_CPU_X86_SSSE3)
        return rgb ? rte_row_rgb_to_gray_ssse3 : rte_row_bgr_to_gray_ssse3;
#endif
#ifdef RTE_SIMD_NEON
    if (features & RTE_CPU_ARM_NEON)
        return rgb ? rte_row_rgb_to_gray_neon : rte_row_bgr_to_gray_neon;
#endif
    (void)features;
    return rgb ? rte_row_rgb_to_gray_c : rte_row_bgr_to_gray_c;
}

/* The row kernel is chosen once per image. */
static void c3_rows_to_gray(const uint8_t *src, int32_t src_stride, rte_image_u8 *dst,
                            rte_row_c3_to_gray_fn row)
{
    for (int32_t y = 0; y < dst->height; y++)
        row(src + (ptrdiff_t)y * src_stride, rte_u8_row(dst, y), dst->width);
}

static void bgr_rows_to_gray(const uint8_t *src, int32_t src_stride, rte_image_u8 *dst)
{
    c3_rows_to_gray(src, src_stride, dst, rte_row_c3_to_gray_select(rte_cpu_features(), false));
}

static void rgb_rows_to_gray(const uint8_t *src, int32_t src_stride, rte_image_u8 *dst)
{
    c3_rows_to_gray(src, src_stride, dst, rte_row_c3_to_gray_select(rte_cpu_features(), true));
}

/* Every second byte: the Y samples of one packed 4:2:2 row (s points at
 * the first Y). */
static void packed422_row_to_gray(const uint8_t *restrict s, uint8_t *restrict d, int32_t width)
{
    for (int32_t x = 0; x < width; x++)
        d[x] = s[2 * x];
}

static void packed422_rows_to_gray(const uint8_t *src, int32_t src_stride, int32_t first,
                                   rte_image_u8 *dst)
{
    for (int32_t y = 0; y < dst->height; y++)
        packed422_row_to_gray(src + (ptrdiff_t)y * src_stride + first, rte_u8_row(dst, y),
                              dst->width);
}

static void copy_rows(const uint8_t *src, int32_t src_stride, rte_image_u8 *dst)
{
    if (src == dst->buf && src_stride == dst->stride)
        return; /* converting a frame into itself */
    for (int32_t y = 0; y < dst->height; y++)
        memmove(rte_u8_row(dst, y), src + (ptrdiff_t)y * src_stride, (size_t)dst->width);
}

static rte_status check_c3_pair(const rte_image_u8c3 *src, rte_image_u8 *dst)
{
    rte_status st = rte_image_u8c3_check(src);
    if (st == RTE_OK)
        st = rte_image_u8_check(dst);
    if (st == RTE_OK && (src->width != dst->width || src->height != dst->height))
        st = RTE_ERR_SIZE;
    return st;
}

rte_status rte_color_bgr_to_gray(const rte_image_u8c3 *src, rte_image_u8 *dst)
{
    rte_status st = check_c3_pair(src, dst);
    if (st == RTE_OK)
        bgr_rows_to_gray(src->buf, src->stride, dst);
    return st;
}

rte_status rte_color_rgb_to_gray(const rte_image_u8c3 *src, rte_image_u8 *dst)
{
    rte_status st = check_c3_pair(src, dst);
    if (st == RTE_OK)
        rgb_rows_to_gray(src->buf, src->stride, dst);
    return st;
}

static rte_status packed422_to_gray(const uint8_t *src, int32_t src_stride, int32_t first,
                                    rte_image_u8 *dst)
{
    rte_status st = rte_image_u8_check(dst);
    if (st != RTE_OK)
        return st;
    if (!src)
        return RTE_ERR_ARGUMENT;
    if (src_stride < 2 * dst->width)
        return RTE_ERR_SIZE;
    packed422_rows_to_gray(src, src_stride, first, dst);
    return RTE_OK;
}

rte_status rte_color_yuyv_to_gray(const uint8_t *src, int32_t src_stride, rte_image_u8 *dst)
{
    return packed422_to_gray(src, src_stride, 0, dst);
}

rte_status rte_color_uyvy_to_gray(const uint8_t *src, int32_t src_stride, rte_image_u8 *dst)
{
    return packed422_to_gray(src, src_stride, 1, dst);
}

rte_status rte_frame_gray_view(const rte_frame *src, rte_image_u8 *view)
{
    rte_status st = rte_frame_check(src);
    if (st != RTE_OK)
        return st;
    if (!view)
        return RTE_ERR_ARGUMENT;
    if (src->format != RTE_PIXEL_GREY && src->format != RTE_PIXEL_NV12)
        return RTE_ERR_UNSUPPORTED;
    rte_image_u8 v = {src->width, src->height, src->stride[0], src->plane[0]};
    *view = v;
    return RTE_OK;
}

rte_status rte_frame_to_gray(const rte_frame *src, rte_image_u8 *dst)
{
    rte_status st = rte_frame_check(src);
    if (st == RTE_OK)
        st = rte_image_u8_check(dst);
    if (st != RTE_OK)
        return st;
    if (src->width != dst->width || src->height != dst->height)
        return RTE_ERR_SIZE;
    const uint8_t *p = src->plane[0];
    int32_t stride = src->stride[0];
    switch (src->format) {
    case RTE_PIXEL_GREY:
    case RTE_PIXEL_NV12: copy_rows(p, stride, dst); break;
    case RTE_PIXEL_BGR24: bgr_rows_to_gray(p, stride, dst); break;
    case RTE_PIXEL_RGB24: rgb_rows_to_gray(p, stride, dst); break;
    case RTE_PIXEL_YUYV: packed422_rows_to_gray(p, stride, 0, dst); break;
    case RTE_PIXEL_UYVY: packed422_rows_to_gray(p, stride, 1, dst); break;
    }
    return RTE_OK;
}

/* BT.601 full-range chroma (JPEG's Cb, Cr) of the sum s of four R, G, B
 * samples, in Q16 with the division by 4 folded into the shift. */
static inline uint8_t chroma_of_sum4(int32_t r4, int32_t g4, int32_t b4, bool cr)
{
    const int64_t v = cr ? 32768 * (int64_t)r4 - 27439 * (int64_t)g4 - 5329 * (int64_t)b4
                         : -11059 * (int64_t)r4 - 21709 * (int64_t)g4 + 32768 * (int64_t)b4;
    const int64_t q = (v + ((int64_t)128 << 18) + (1 << 17)) >> 18; /* >= 0: no sign shift */
    return (uint8_t)(q > 255 ? 255 : q);
}

/* The chroma of one-plane frames: three-channel ones from the mean colour
 * of each 2x2 block, packed 4:2:2 ones from the mean of the block's two
 * rows' U and V (an odd width's last pixel has a U but no V of its own and
 * takes the V before it, or 128 in a one-pixel row); the last row and
 * column repeated at odd sizes. */
static void packed_chroma_half(const rte_frame *f, rte_image_u8 *cb, rte_image_u8 *cr)
{
    const bool c3 = f->format == RTE_PIXEL_BGR24 || f->format == RTE_PIXEL_RGB24;
    const int r = f->format == RTE_PIXEL_BGR24 ? 2 : 0, b = 2 - r; /* c3: byte offsets */
    const int u = f->format == RTE_PIXEL_UYVY ? 0 : 1, v = u + 2;  /* 4:2:2: byte offsets */
    for (int32_t y = 0; y < cb->height; y++) {
        const uint8_t *s0 = f->plane[0] + (ptrdiff_t)(2 * y) * f->stride[0];
        const uint8_t *s1 = 2 * y + 1 < f->height ? s0 + f->stride[0] : s0;
        uint8_t *db = rte_u8_row(cb, y), *dr = rte_u8_row(cr, y);
        for (int32_t x = 0; x < cb->width; x++) {
            if (c3) {
                const int32_t a = 6 * x, c = 2 * x + 1 < f->width ? a + 3 : a;
                const int32_t rs = s0[a + r] + s0[c + r] + s1[a + r] + s1[c + r];
                const int32_t gs = s0[a + 1] + s0[c + 1] + s1[a + 1] + s1[c + 1];
                const int32_t bs = s0[a + b] + s0[c + b] + s1[a + b] + s1[c + b];
                db[x] = chroma_of_sum4(rs, gs, bs, false);
                dr[x] = chroma_of_sum4(rs, gs, bs, true);
                continue;
            }
            const int32_t a = 4 * x;
            db[x] = (uint8_t)((s0[a + u] + s1[a + u] + 1) >> 1);
            if (4 * x + 4 <= 2 * f->width)
                dr[x] = (uint8_t)((s0[a + v] + s1[a + v] + 1) >> 1);
            else
                dr[x] = x > 0 ? dr[x - 1] : 128;
        }
    }
}

rte_status rte_frame_chroma_half(const rte_frame *src, rte_image_u8 *cb, rte_image_u8 *cr)
{
    rte_status st = rte_frame_check(src);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(cb, cr);
    if (st != RTE_OK)
        return st;
    if (cb->width != (src->width + 1) / 2 || cb->height != (src->height + 1) / 2)
        return RTE_ERR_SIZE;
    switch (src->format) {
    case RTE_PIXEL_GREY: return RTE_ERR_UNSUPPORTED;
    case RTE_PIXEL_BGR24:
    case RTE_PIXEL_RGB24:
    case RTE_PIXEL_YUYV:
    case RTE_PIXEL_UYVY: packed_chroma_half(src, cb, cr); break;
    case RTE_PIXEL_NV12:
        for (int32_t y = 0; y < cb->height; y++) {
            const uint8_t *s = src->plane[1] + (ptrdiff_t)y * src->stride[1];
            uint8_t *db = rte_u8_row(cb, y), *dr = rte_u8_row(cr, y);
            for (int32_t x = 0; x < cb->width; x++) {
                db[x] = s[2 * x];
                dr[x] = s[2 * x + 1];
            }
        }
        break;
    }
    return RTE_OK;
}
