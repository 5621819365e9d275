/* Golden outputs: every kernel of librtedge, their configuration tables and
 * both pipelines (lane, grasp) run on the fixtures, one line per output:
 *
 *     INPUT  KERNEL/PARAMETERS  HASH  NOTE
 *
 * HASH is a 64-bit FNV-1a of the output's pixels (the width of each row,
 * little-endian for int16) or of its fields (each as a little-endian
 * int64, so struct padding and bool sizes never enter); NOTE is a short
 * readable summary (nonzero pixels, counts, the status of a refused call).
 * Every destination has guard bytes after each row: a kernel that writes
 * there is reported in the note, and so changes the line.
 *
 *   golden write OUT FILE...   writes the lines to OUT
 *   golden check REF FILE...   computes the lines and compares them with REF
 *
 * The test suite builds it twice in a cross build (tests/golden/meson.build):
 * for the build machine (x86-64), which writes the reference with the plain
 * C kernels (RTE_FORCE_C=1), and for the host (aarch64 under qemu), which
 * checks against it with its NEON kernels and again with RTE_FORCE_C=1. A
 * native build checks its SSE/AVX kernels against its own C path. So every
 * output must be bit-identical across CPUs and paths. FILE is an image
 * (PGM, PPM, PNG, JPEG) or a Y4M clip (its first frame through every
 * kernel, every frame through the lane tracker). */
#include <inttypes.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rtedge/arena.h"
#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/color.h"
#include "rtedge/contours.h"
#include "rtedge/cpu.h"
#include "rtedge/gradient.h"
#include "rtedge/grasp.h"
#include "rtedge/hough.h"
#include "rtedge/imageio.h"
#include "rtedge/lane.h"
#include "rtedge/morphology.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/shape.h"
#include "rtedge/threshold.h"
#include "rtedge/y4m.h"

#define GOLDEN_PI 3.14159265358979323846
/* Rows of every image carry guard elements (an odd count, so rows start
 * unaligned and the SIMD kernels take their unaligned and tail paths). */
enum { GUARD = 7, GUARD_BYTE = 0xEE, MAX_SHAPES = 400, MAX_OWNED = 64 };
#define GUARD_S16 ((int16_t)0x7EEE)
#define ARENA_BYTES ((size_t)192 << 20)

__attribute__((format(printf, 1, 2), noreturn)) static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("golden: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(2);
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p)
        die("out of memory (%zu bytes)", n);
    return p;
}

/* ---- hashing ---- */

typedef struct digest {
    uint64_t h;
} digest;

static digest dg_new(void)
{
    digest d = {UINT64_C(0xcbf29ce484222325)};
    return d;
}

/* FNV-1a over little-endian 64-bit words (then the tail bytes), with a
 * xor-shift per word so that high bits reach the low ones. */
static void dg_bytes(digest *d, const uint8_t *p, size_t n)
{
    const uint64_t prime = UINT64_C(0x100000001b3);
    uint64_t h = d->h;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t w = 0;
        for (int k = 0; k < 8; k++)
            w |= (uint64_t)p[i + k] << (8 * k);
        h = (h ^ w) * prime;
        h ^= h >> 29;
    }
    for (; i < n; i++)
        h = (h ^ p[i]) * prime;
    d->h = h;
}

static void dg_int(digest *d, int64_t v)
{
    uint8_t b[8];
    for (int i = 0; i < 8; i++)
        b[i] = (uint8_t)((uint64_t)v >> (8 * i));
    dg_bytes(d, b, 8);
}

/* Records made only of int32_t fields (rectangles, circles, segments) are
 * hashed as one int32_t array of INT32_FIELDS(record) per record. */
#define INT32_FIELDS(record) ((int32_t)(sizeof(record) / sizeof(int32_t)))
_Static_assert(sizeof(rte_rect) == 4 * sizeof(int32_t), "int32_t fields only");
_Static_assert(sizeof(rte_circle) == 3 * sizeof(int32_t), "int32_t fields only");
_Static_assert(sizeof(rte_rotated_rect) == 13 * sizeof(int32_t), "int32_t fields only");
_Static_assert(sizeof(rte_hough_segment) == 4 * sizeof(int32_t), "int32_t fields only");
_Static_assert(sizeof(rte_hough_circle) == 4 * sizeof(int32_t), "int32_t fields only");

static void dg_int32s(digest *d, const int32_t *v, int64_t n)
{
    for (int64_t i = 0; i < n; i++)
        dg_int(d, v[i]);
}

/* ---- the collected lines ---- */

typedef struct golden {
    char **lines;
    size_t n_lines, cap;
    const char *input;
    rte_arena arena;
    void *owned[MAX_OWNED]; /* image buffers of the current input */
    int n_owned;
} golden;

__attribute__((format(printf, 4, 5))) static void emit(golden *g, const char *what, uint64_t hash,
                                                       const char *fmt, ...)
{
    char note[160], line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(note, sizeof note, fmt, ap);
    va_end(ap);
    snprintf(line, sizeof line, "%s %s %016" PRIx64 " %s", g->input, what, hash, note);
    if (g->n_lines == g->cap) {
        g->cap = g->cap ? 2 * g->cap : 1024;
        char **grown = realloc(g->lines, g->cap * sizeof *grown);
        if (!grown)
            die("out of memory");
        g->lines = grown;
    }
    g->lines[g->n_lines] = xmalloc(strlen(line) + 1);
    strcpy(g->lines[g->n_lines++], line);
}

/* A refused call is an output too: its status must match everywhere. */
static bool emit_status(golden *g, const char *what, rte_status st)
{
    if (st == RTE_OK)
        return false;
    emit(g, what, 0, "status=%d(%s)", (int)st, rte_status_message(st));
    return true;
}

static void *own(golden *g, size_t bytes)
{
    if (g->n_owned == MAX_OWNED)
        die("too many buffers");
    return g->owned[g->n_owned++] = xmalloc(bytes);
}

static void free_owned(golden *g)
{
    while (g->n_owned > 0)
        free(g->owned[--g->n_owned]);
}

/* ---- images with guard elements ---- */

static rte_image_u8 new_u8(golden *g, int32_t w, int32_t h)
{
    rte_image_u8 img = {w, h, w + GUARD, NULL};
    img.buf = own(g, (size_t)img.stride * (size_t)h);
    memset(img.buf, GUARD_BYTE, (size_t)img.stride * (size_t)h);
    return img;
}

static rte_image_s16 new_s16(golden *g, int32_t w, int32_t h)
{
    rte_image_s16 img = {w, h, w + GUARD, NULL};
    img.buf = own(g, (size_t)img.stride * (size_t)h * sizeof(int16_t));
    for (size_t i = 0; i < (size_t)img.stride * (size_t)h; i++)
        img.buf[i] = GUARD_S16;
    return img;
}

static rte_image_u8c3 new_u8c3(golden *g, int32_t w, int32_t h)
{
    rte_image_u8c3 img = {w, h, 3 * w + GUARD, NULL};
    img.buf = own(g, (size_t)img.stride * (size_t)h);
    memset(img.buf, GUARD_BYTE, (size_t)img.stride * (size_t)h);
    return img;
}

static rte_image_u8 copy_u8(golden *g, const rte_image_u8 *src)
{
    rte_image_u8 img = new_u8(g, src->width, src->height);
    for (int32_t y = 0; y < src->height; y++)
        memcpy(rte_u8_row(&img, y), rte_u8_row(src, y), (size_t)src->width);
    return img;
}

/* Hash of the pixels; *guard_ok says whether the guards are intact. */
static uint64_t hash_u8(const rte_image_u8 *img, int64_t *nonzero, bool *guard_ok)
{
    digest d = dg_new();
    int64_t nz = 0;
    bool ok = true;
    for (int32_t y = 0; y < img->height; y++) {
        const uint8_t *row = rte_u8_row(img, y);
        dg_bytes(&d, row, (size_t)img->width);
        for (int32_t x = 0; x < img->width; x++)
            nz += row[x] != 0;
        for (int32_t x = img->width; x < img->stride; x++)
            ok &= row[x] == GUARD_BYTE;
    }
    *nonzero = nz;
    *guard_ok = ok;
    return d.h;
}

static void emit_u8(golden *g, const char *what, const rte_image_u8 *img)
{
    int64_t nz;
    bool ok;
    uint64_t h = hash_u8(img, &nz, &ok);
    emit(g, what, h, "nonzero=%" PRId64 "%s", nz, ok ? "" : " GUARD-OVERWRITTEN");
}

static void emit_s16(golden *g, const char *what, const rte_image_s16 *img)
{
    digest d = dg_new();
    int64_t sum = 0;
    bool ok = true;
    uint8_t *bytes = xmalloc(2 * (size_t)img->width);
    for (int32_t y = 0; y < img->height; y++) {
        const int16_t *row = rte_s16_row(img, y);
        for (int32_t x = 0; x < img->width; x++) {
            bytes[2 * x] = (uint8_t)((uint16_t)row[x] & 0xff);
            bytes[2 * x + 1] = (uint8_t)((uint16_t)row[x] >> 8);
            sum += row[x] < 0 ? -row[x] : row[x];
        }
        dg_bytes(&d, bytes, 2 * (size_t)img->width);
        for (int32_t x = img->width; x < img->stride; x++)
            ok &= row[x] == GUARD_S16;
    }
    free(bytes);
    emit(g, what, d.h, "abs-sum=%" PRId64 "%s", sum, ok ? "" : " GUARD-OVERWRITTEN");
}

/* ---- the per-input state ---- */

typedef struct input {
    rte_image_u8 gray;
    rte_image_u8c3 bgr;
    int32_t w, h;
} input;

/* ---- colour to grey ---- */

static void run_color(golden *g, const input *in)
{
    rte_image_u8 dst = new_u8(g, in->w, in->h);
    if (!emit_status(g, "gray.bgr", rte_color_bgr_to_gray(&in->bgr, &dst)))
        emit_u8(g, "gray.bgr", &dst);
    dst = new_u8(g, in->w, in->h);
    if (!emit_status(g, "gray.rgb", rte_color_rgb_to_gray(&in->bgr, &dst)))
        emit_u8(g, "gray.rgb", &dst);

    /* Packed YUV frames: Y from the grey image, chroma from the colour. */
    const rte_pixel_format formats[] = {RTE_PIXEL_YUYV, RTE_PIXEL_UYVY, RTE_PIXEL_NV12,
                                        RTE_PIXEL_BGR24, RTE_PIXEL_GREY};
    for (size_t f = 0; f < sizeof formats / sizeof formats[0]; f++) {
        size_t bytes = rte_frame_packed_size(formats[f], in->w, in->h);
        uint8_t *buf = own(g, bytes);
        for (size_t i = 0; i < bytes; i++)
            buf[i] = in->bgr.buf[(i * 7) % ((size_t)in->bgr.stride * (size_t)in->h)];
        for (int32_t y = 0; y < in->h; y++)
            for (int32_t x = 0; x < in->w; x++) {
                uint8_t v = rte_u8_row(&in->gray, y)[x];
                size_t i = (size_t)y * (size_t)in->w + (size_t)x;
                if (formats[f] == RTE_PIXEL_YUYV)
                    buf[2 * i] = v;
                else if (formats[f] == RTE_PIXEL_UYVY)
                    buf[2 * i + 1] = v;
                else if (formats[f] != RTE_PIXEL_BGR24)
                    buf[i] = v; /* NV12 Y plane, GREY */
            }
        rte_frame frame;
        char what[64];
        snprintf(what, sizeof what, "gray.frame.%s", rte_pixel_format_name(formats[f]));
        dst = new_u8(g, in->w, in->h);
        rte_status st = rte_frame_packed(&frame, formats[f], in->w, in->h, buf, bytes);
        if (st == RTE_OK)
            st = rte_frame_to_gray(&frame, &dst);
        if (!emit_status(g, what, st))
            emit_u8(g, what, &dst);
    }
}

/* ---- blur ---- */

static void run_blur(golden *g, const input *in)
{
    static const struct {
        int32_t kx, ky;
        double sx, sy;
    } cases[] = {{3, 3, 0, 0},   {5, 5, 0, 0},   {7, 7, 0, 0}, {9, 9, 0, 0}, {11, 11, 0, 0},
                 {15, 15, 0, 0}, {5, 5, 1.2, 0}, {3, 9, 0, 0}, {1, 7, 0, 0}, {0, 0, 2.0, 0.7}};
    rte_image_u8 dst = new_u8(g, in->w, in->h);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char what[80];
        snprintf(what, sizeof what, "gaussian.%dx%d.s%.1f,%.1f", cases[i].kx, cases[i].ky,
                 cases[i].sx, cases[i].sy);
        rte_gaussian_kernel k;
        if (emit_status(
                g, what,
                rte_gaussian_kernel_init(&k, cases[i].kx, cases[i].ky, cases[i].sx, cases[i].sy)))
            continue;
        digest d = dg_new();
        dg_int(&d, k.ksize_x);
        dg_int(&d, k.ksize_y);
        for (int32_t t = 0; t < k.ksize_x; t++)
            dg_int(&d, k.taps_x[t]);
        for (int32_t t = 0; t < k.ksize_y; t++)
            dg_int(&d, k.taps_y[t]);
        char taps[96];
        snprintf(taps, sizeof taps, "%s.taps", what);
        emit(g, taps, d.h, "%dx%d", k.ksize_x, k.ksize_y);
        if (!emit_status(g, what, rte_gaussian_blur_u8(&in->gray, &dst, &k, &g->arena)))
            emit_u8(g, what, &dst);
    }
    for (int32_t k = 3; k <= 5; k += 2) {
        char what[32];
        snprintf(what, sizeof what, "median.%d", k);
        if (!emit_status(g, what, rte_median_blur_u8(&in->gray, &dst, k, &g->arena)))
            emit_u8(g, what, &dst);
    }
}

/* ---- gradients ---- */

static void run_gradient(golden *g, const input *in)
{
    static const int32_t orders[][2] = {{1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}, {2, 1}};
    rte_image_s16 dst = new_s16(g, in->w, in->h);
    char what[64];
    for (int32_t ksize = 1; ksize <= 7; ksize += 2)
        for (size_t o = 0; o < sizeof orders / sizeof orders[0]; o++) {
            snprintf(what, sizeof what, "sobel.k%d.d%d%d", ksize, orders[o][0], orders[o][1]);
            if (!emit_status(
                    g, what,
                    rte_sobel_s16(&in->gray, &dst, orders[o][0], orders[o][1], ksize, &g->arena)))
                emit_s16(g, what, &dst);
        }
    for (int32_t o = 0; o < 2; o++) {
        snprintf(what, sizeof what, "scharr.d%d%d", 1 - o, o);
        if (!emit_status(g, what, rte_scharr_s16(&in->gray, &dst, 1 - o, o, &g->arena)))
            emit_s16(g, what, &dst);
    }
    for (int32_t ksize = 1; ksize <= 3; ksize += 2) {
        snprintf(what, sizeof what, "laplacian.k%d", ksize);
        if (!emit_status(g, what, rte_laplacian_s16(&in->gray, &dst, ksize, &g->arena)))
            emit_s16(g, what, &dst);
        rte_image_u8 abs_dst = new_u8(g, in->w, in->h);
        snprintf(what, sizeof what, "abs.laplacian.k%d", ksize);
        if (!emit_status(g, what, rte_abs_s16_u8(&dst, &abs_dst)))
            emit_u8(g, what, &abs_dst);
    }
}

/* ---- Canny ---- */

static void run_canny(golden *g, const input *in)
{
    static const double thresholds[][2] = {{50, 150}, {20, 60}, {300, 100}};
    rte_image_u8 dst = new_u8(g, in->w, in->h);
    char what[80];
    for (int32_t aperture = 3; aperture <= 7; aperture += 2)
        for (int l2 = 0; l2 <= 1; l2++)
            for (size_t t = 0; t < sizeof thresholds / sizeof thresholds[0]; t++) {
                snprintf(what, sizeof what, "canny.a%d.%s.%g,%g", aperture, l2 ? "L2" : "L1",
                         thresholds[t][0], thresholds[t][1]);
                rte_canny_params p;
                if (emit_status(g, what,
                                rte_canny_params_init(&p, thresholds[t][0], thresholds[t][1],
                                                      aperture, l2 != 0)))
                    continue;
                char params[96];
                snprintf(params, sizeof params, "%s.params", what);
                digest d = dg_new();
                dg_int(&d, p.aperture);
                dg_int(&d, p.l2_gradient);
                dg_int(&d, p.low);
                dg_int(&d, p.high);
                emit(g, params, d.h, "low=%d high=%d", p.low, p.high);
                if (!emit_status(g, what, rte_canny_u8(&in->gray, &dst, &p, &g->arena)))
                    emit_u8(g, what, &dst);
            }
    rte_image_s16 dx = new_s16(g, in->w, in->h), dy = new_s16(g, in->w, in->h);
    if (emit_status(g, "canny.gradient", rte_sobel_s16(&in->gray, &dx, 1, 0, 3, &g->arena)) ||
        emit_status(g, "canny.gradient", rte_sobel_s16(&in->gray, &dy, 0, 1, 3, &g->arena)))
        return;
    for (int l2 = 0; l2 <= 1; l2++) {
        rte_canny_params p;
        snprintf(what, sizeof what, "canny.gradient.%s.40,120", l2 ? "L2" : "L1");
        if (!emit_status(g, what, rte_canny_params_init(&p, 40, 120, 3, l2 != 0)) &&
            !emit_status(g, what, rte_canny_from_gradient_u8(&dx, &dy, &dst, &p, &g->arena)))
            emit_u8(g, what, &dst);
    }
}

/* ---- threshold, histogram, Otsu ---- */

/* The binary image of the later stages: Otsu, objects bright. */
static rte_image_u8 otsu_binary(golden *g, const input *in)
{
    rte_threshold_params p;
    rte_image_u8 bin = new_u8(g, in->w, in->h);
    if (rte_threshold_params_init(&p, RTE_THRESH_BINARY, 0, 255, true) != RTE_OK ||
        rte_threshold_u8(&in->gray, &bin, &p, NULL) != RTE_OK)
        die("%s: Otsu threshold failed", g->input);
    return bin;
}

static void run_threshold(golden *g, const input *in)
{
    rte_image_u8 dst = new_u8(g, in->w, in->h);
    char what[64];
    static const struct {
        double thresh, maxval;
        bool otsu;
    } cases[] = {
        {127, 255, false}, {200.5, 100, false}, {-1, 255, false}, {0, 255, true}, {0, 180, true}};
    for (int type = RTE_THRESH_BINARY; type <= RTE_THRESH_TOZERO_INV; type++)
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
            snprintf(what, sizeof what, "threshold.t%d.%g,%g%s", type, cases[c].thresh,
                     cases[c].maxval, cases[c].otsu ? ".otsu" : "");
            rte_threshold_params p;
            int32_t used = 0;
            if (emit_status(g, what,
                            rte_threshold_params_init(&p, (rte_threshold_type)type, cases[c].thresh,
                                                      cases[c].maxval, cases[c].otsu)) ||
                emit_status(g, what, rte_threshold_u8(&in->gray, &dst, &p, &used)))
                continue;
            int64_t nz;
            bool ok;
            uint64_t h = hash_u8(&dst, &nz, &ok);
            emit(g, what, h, "used=%d nonzero=%" PRId64 "%s", used, nz,
                 ok ? "" : " GUARD-OVERWRITTEN");
        }
    uint32_t hist[256];
    if (emit_status(g, "histogram", rte_histogram_u8(&in->gray, hist)))
        return;
    digest d = dg_new();
    for (int i = 0; i < 256; i++)
        dg_int(&d, hist[i]);
    emit(g, "histogram", d.h, "%s", "");
    int32_t otsu = -1, lo = -1, hi = -1;
    if (!emit_status(g, "otsu", rte_threshold_otsu_u8(&in->gray, &otsu)))
        emit(g, "otsu", (uint64_t)otsu, "t=%d", otsu);
    if (!emit_status(
            g, "auto-canny.median",
            rte_threshold_auto_canny_median(hist, RTE_AUTO_CANNY_SIGMA_PERMILLE, &lo, &hi)))
        emit(g, "auto-canny.median", (uint64_t)lo << 32 | (uint32_t)hi, "%d,%d", lo, hi);
    if (!emit_status(g, "auto-canny.otsu", rte_threshold_auto_canny_otsu(hist, &lo, &hi)))
        emit(g, "auto-canny.otsu", (uint64_t)lo << 32 | (uint32_t)hi, "%d,%d", lo, hi);
}

/* ---- morphology ---- */

static void run_morphology(golden *g, const input *in, const rte_image_u8 *bin)
{
    static const int32_t sizes[][2] = {{3, 3}, {5, 5}, {7, 3}, {1, 9}};
    static const char *shape_names[] = {"rect", "cross", "ellipse"};
    static const char *op_names[] = {"erode", "dilate", "open", "close"};
    rte_morph_element *e = own(g, sizeof *e);
    rte_image_u8 dst = new_u8(g, in->w, in->h);
    char what[80];
    for (int src_i = 0; src_i < 2; src_i++) {
        const rte_image_u8 *src = src_i ? bin : &in->gray;
        for (int shape = RTE_MORPH_RECT; shape <= RTE_MORPH_ELLIPSE; shape++)
            for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
                snprintf(what, sizeof what, "morph.%s.%s.%dx%d", src_i ? "binary" : "gray",
                         shape_names[shape], sizes[s][0], sizes[s][1]);
                if (emit_status(g, what,
                                rte_morphology_element_init(e, (rte_morph_shape)shape, sizes[s][0],
                                                            sizes[s][1])))
                    continue;
                for (int op = RTE_MORPH_ERODE; op <= RTE_MORPH_CLOSE; op++) {
                    char w2[112];
                    int32_t iterations = s == 0 && op >= RTE_MORPH_OPEN ? 2 : 1;
                    snprintf(w2, sizeof w2, "%s.%s.i%d", what, op_names[op], iterations);
                    if (!emit_status(g, w2,
                                     rte_morphology_u8(src, &dst, (rte_morph_op)op, e, iterations,
                                                       &g->arena)))
                        emit_u8(g, w2, &dst);
                }
            }
    }
    /* An irregular element with its anchor off centre, and in place. */
    static const uint8_t mask[] = {1, 0, 0, 1, 1, 1, 0, 1, 1, 0, 0, 0, 1, 0, 1};
    rte_image_u8 inplace = copy_u8(g, &in->gray);
    if (!emit_status(g, "morph.gray.mask5x3.dilate.inplace",
                     rte_morphology_element_from_mask(e, mask, 5, 3, 3, 0)) &&
        !emit_status(g, "morph.gray.mask5x3.dilate.inplace",
                     rte_morphology_dilate_u8(&inplace, &inplace, e, 1, &g->arena)))
        emit_u8(g, "morph.gray.mask5x3.dilate.inplace", &inplace);
}

/* ---- polygon masks ---- */

static void run_polygon(golden *g, const input *in)
{
    const rte_vertex frac[] = {{0, 65536}, {29491, 39322}, {36045, 39322}, {65536, 65536}};
    rte_vertex trapezoid[4];
    rte_image_u8 mask = new_u8(g, in->w, in->h), dst = new_u8(g, in->w, in->h);
    if (emit_status(g, "polygon.mask",
                    rte_polygon_from_fractions(frac, 4, in->w, in->h, trapezoid)))
        return;
    rte_polygon poly = {trapezoid, 4};
    if (!emit_status(g, "polygon.mask", rte_polygon_mask_build(&mask, &poly, 1, &g->arena))) {
        emit_u8(g, "polygon.mask", &mask);
        if (!emit_status(g, "polygon.apply", rte_polygon_mask_apply(&in->gray, &mask, &dst)))
            emit_u8(g, "polygon.apply", &dst);
    }
    /* A self-intersecting star beside a triangle partly outside the image. */
    int32_t w = in->w, h = in->h;
    const rte_vertex star[] = {
        {w / 2, 0}, {w * 4 / 5, h - 1}, {0, h / 3}, {w - 1, h / 3}, {w / 5, h - 1}};
    const rte_vertex tri[] = {{-w / 4, h / 2}, {w / 3, h + h / 5}, {w / 3, h / 3}};
    const rte_polygon polys[] = {{star, 5}, {tri, 3}};
    rte_image_u8 filled = copy_u8(g, &in->gray);
    if (!emit_status(g, "polygon.fill", rte_polygon_fill_u8(&filled, polys, 2, 77, &g->arena)))
        emit_u8(g, "polygon.fill", &filled);
}

/* ---- contours and shape features ---- */

static rte_contours new_contours(golden *g, const input *in)
{
    rte_contours c;
    memset(&c, 0, sizeof c);
    c.max_points = 2 * in->w * in->h + 64;
    c.max_contours = in->w * in->h / 2 + 64;
    c.points = own(g, (size_t)c.max_points * sizeof *c.points);
    c.contours = own(g, (size_t)c.max_contours * sizeof *c.contours);
    return c;
}

static uint64_t hash_contours(const rte_contours *c)
{
    digest d = dg_new();
    dg_int(&d, c->n_contours);
    dg_int(&d, c->n_points);
    dg_int(&d, c->truncated);
    dg_int(&d, c->dropped_contours);
    dg_int(&d, c->dropped_points);
    for (int32_t i = 0; i < c->n_contours; i++) {
        const rte_contour *k = &c->contours[i];
        dg_int(&d, k->offset);
        dg_int(&d, k->count);
        for (int j = 0; j < 4; j++)
            dg_int(&d, k->hierarchy[j]);
        dg_int(&d, k->is_hole);
        for (int32_t j = 0; j < k->count; j++) {
            dg_int(&d, c->points[k->offset + j].x);
            dg_int(&d, c->points[k->offset + j].y);
        }
    }
    return d.h;
}

static void run_contours(golden *g, const input *in, const rte_image_u8 *bin, rte_contours *c)
{
    static const char *mode_names[] = {"external", "list", "ccomp", "tree"};
    char what[64];
    for (int mode = RTE_CONTOURS_EXTERNAL; mode <= RTE_CONTOURS_TREE; mode++)
        for (int method = RTE_CONTOURS_APPROX_NONE; method <= RTE_CONTOURS_APPROX_SIMPLE;
             method++) {
            snprintf(what, sizeof what, "contours.%s.%s", mode_names[mode],
                     method == RTE_CONTOURS_APPROX_NONE ? "none" : "simple");
            if (!emit_status(g, what,
                             rte_contours_find(bin, (rte_contour_mode)mode,
                                               (rte_contour_method)method, c, &g->arena)))
                emit(g, what, hash_contours(c), "contours=%d points=%d", c->n_contours,
                     c->n_points);
        }
    /* Leaves the external, simple contours of the binary image in *c. */
    if (emit_status(g, "contours",
                    rte_contours_find(bin, RTE_CONTOURS_EXTERNAL, RTE_CONTOURS_APPROX_SIMPLE, c,
                                      &g->arena)))
        c->n_contours = 0;
}

static void dg_rotated_rect(digest *d, const rte_rotated_rect *r)
{
    dg_int32s(d, &r->cx_q8, INT32_FIELDS(*r));
}

static void dg_circle(digest *d, const rte_circle *c) { dg_int32s(d, &c->cx_q8, INT32_FIELDS(*c)); }

static void dg_rect(digest *d, rte_rect r) { dg_int32s(d, &r.x, INT32_FIELDS(r)); }

static void dg_shape_info(digest *d, const rte_shape_info *s)
{
    dg_int(d, s->shape);
    dg_int(d, s->vertices);
    dg_int(d, s->vertices_coarse);
    dg_int(d, s->area2);
    dg_int(d, s->perimeter_q16);
    dg_rect(d, s->bounds);
    dg_int(d, s->aspect_q16);
    dg_int(d, s->extent_q16);
    dg_int(d, s->solidity_q16);
    dg_int(d, s->circularity_q16);
    dg_int(d, s->hull_circularity_q16);
    dg_rotated_rect(d, &s->box);
    dg_circle(d, &s->circle);
    dg_int(d, s->cx_q16);
    dg_int(d, s->cy_q16);
}

static void dg_moments(digest *d, const rte_moments *m)
{
    const int64_t v[] = {
        m->s00,      m->s10,      m->s01,      m->s20,      m->s11,     m->s02,      m->s30,
        m->s21,      m->s12,      m->s03,      m->cx_q16,   m->cy_q16,  m->mu20_q8,  m->mu11_q8,
        m->mu02_q8,  m->mu30_q8,  m->mu21_q8,  m->mu12_q8,  m->mu03_q8, m->nu20_q32, m->nu11_q32,
        m->nu02_q32, m->nu30_q32, m->nu21_q32, m->nu12_q32, m->nu03_q32};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        dg_int(d, v[i]);
    for (int i = 0; i < 7; i++)
        dg_int(d, m->hu_q32[i]);
}

/* Every shape feature of every external contour (the first MAX_SHAPES),
 * one line per feature. A refused call hashes its status. */
static void run_shapes(golden *g, const rte_contours *c)
{
    enum { AREA, PERIMETER, BOUNDS, MOMENTS, HULL, DEFECTS, APPROX, BOX, CIRCLE, CLASSIFY, N };
    static const char *names[N] = {
        "area",    "perimeter", "bounds",        "moments",          "hull",
        "defects", "approx",    "min-area-rect", "enclosing-circle", "classify"};
    digest d[N];
    for (int i = 0; i < N; i++)
        d[i] = dg_new();
    int32_t count = c->n_contours < MAX_SHAPES ? c->n_contours : MAX_SHAPES;
    int32_t max_n = 0;
    for (int32_t i = 0; i < count; i++)
        max_n = c->contours[i].count > max_n ? c->contours[i].count : max_n;
    int32_t *hull_idx = xmalloc((size_t)(max_n + 1) * sizeof *hull_idx);
    rte_point *pts_out = xmalloc((size_t)(max_n + 1) * sizeof *pts_out);
    rte_defect *defects = xmalloc((size_t)(max_n + 1) * sizeof *defects);
    for (int32_t i = 0; i < count; i++) {
        const rte_point *pts = c->points + c->contours[i].offset;
        int32_t n = c->contours[i].count;
        dg_int(&d[AREA], rte_shape_area2(pts, n));
        dg_int(&d[PERIMETER], rte_shape_perimeter_q16(pts, n, 1));
        dg_int(&d[PERIMETER], rte_shape_perimeter_q16(pts, n, 0));
        dg_rect(&d[BOUNDS], rte_shape_bounding_rect(pts, n));

        rte_moments m;
        rte_status st = rte_shape_moments(pts, n, &m);
        dg_int(&d[MOMENTS], st);
        if (st == RTE_OK)
            dg_moments(&d[MOMENTS], &m);

        int32_t n_hull = 0;
        st = rte_shape_convex_hull(pts, n, hull_idx, pts_out, &n_hull, &g->arena);
        dg_int(&d[HULL], st);
        for (int32_t j = 0; st == RTE_OK && j < n_hull; j++) {
            dg_int(&d[HULL], hull_idx[j]);
            dg_int(&d[HULL], pts_out[j].x);
            dg_int(&d[HULL], pts_out[j].y);
        }
        int32_t n_def = 0;
        rte_status dst =
            st == RTE_OK ? rte_shape_convexity_defects(pts, n, hull_idx, n_hull, defects, &n_def)
                         : st;
        dg_int(&d[DEFECTS], dst);
        for (int32_t j = 0; dst == RTE_OK && j < n_def; j++) {
            dg_int(&d[DEFECTS], defects[j].start);
            dg_int(&d[DEFECTS], defects[j].end);
            dg_int(&d[DEFECTS], defects[j].farthest);
            dg_int(&d[DEFECTS], defects[j].depth_q8);
        }

        /* epsilon 2 px and 2% of the perimeter (below 1024 px) */
        int64_t perimeter = rte_shape_perimeter_q16(pts, n, 1);
        uint32_t eps[2] = {2u << 16, (uint32_t)(perimeter / 50 < (INT64_C(1000) << 16)
                                                    ? perimeter / 50
                                                    : INT64_C(1000) << 16)};
        for (int e = 0; e < 2; e++) {
            int32_t n_out = 0;
            st = rte_shape_approx_poly(pts, n, eps[e], pts_out, &n_out, &g->arena);
            dg_int(&d[APPROX], st);
            for (int32_t j = 0; st == RTE_OK && j < n_out; j++) {
                dg_int(&d[APPROX], pts_out[j].x);
                dg_int(&d[APPROX], pts_out[j].y);
            }
        }
        rte_rotated_rect r;
        st = rte_shape_min_area_rect(pts, n, &r, &g->arena);
        dg_int(&d[BOX], st);
        if (st == RTE_OK)
            dg_rotated_rect(&d[BOX], &r);
        rte_circle circle;
        st = rte_shape_enclosing_circle(pts, n, &circle, &g->arena);
        dg_int(&d[CIRCLE], st);
        if (st == RTE_OK)
            dg_circle(&d[CIRCLE], &circle);
        rte_shape_info info;
        st = rte_shape_classify(pts, n, &info, &g->arena);
        dg_int(&d[CLASSIFY], st);
        if (st == RTE_OK)
            dg_shape_info(&d[CLASSIFY], &info);
    }
    for (int i = 0; i < N; i++) {
        char what[48];
        snprintf(what, sizeof what, "shape.%s", names[i]);
        emit(g, what, d[i].h, "contours=%d", count);
    }
    free(hull_idx);
    free(pts_out);
    free(defects);
}

/* ---- Hough ---- */

static void emit_records(golden *g, const char *what, const char *noun, const int32_t *first,
                         int32_t count, int32_t fields, bool truncated)
{
    digest d = dg_new();
    dg_int(&d, count);
    dg_int(&d, truncated);
    dg_int32s(&d, first, (int64_t)count * fields);
    emit(g, what, d.h, "%s=%d truncated=%d", noun, count, (int)truncated);
}

static void run_hough(golden *g, const input *in, rte_hough_config *cfg)
{
    rte_image_u8 blurred = new_u8(g, in->w, in->h), edges = new_u8(g, in->w, in->h);
    rte_gaussian_kernel k;
    rte_canny_params cp;
    if (rte_gaussian_kernel_init(&k, 5, 5, 0, 0) != RTE_OK ||
        rte_gaussian_blur_u8(&in->gray, &blurred, &k, &g->arena) != RTE_OK ||
        rte_canny_params_init(&cp, 50, 150, 3, false) != RTE_OK ||
        rte_canny_u8(&blurred, &edges, &cp, &g->arena) != RTE_OK)
        die("%s: edges for the Hough transforms failed", g->input);
    static const struct {
        double rho, theta, min_theta, max_theta;
        int32_t threshold;
    } line_cases[] = {{1, GOLDEN_PI / 180, 0, GOLDEN_PI, 80},
                      {2, GOLDEN_PI / 360, 0.3, 2.8, 60},
                      {0.7, GOLDEN_PI / 90, -0.5, 1.0, 40}};
    enum { MAX_LINES = 512, MAX_SEGMENTS = 4096, MAX_CIRCLES = 256 };
    rte_hough_line *lines = own(g, MAX_LINES * sizeof *lines);
    rte_hough_segment *segs = own(g, MAX_SEGMENTS * sizeof *segs);
    rte_hough_circle *circles = own(g, MAX_CIRCLES * sizeof *circles);
    char what[96];
    for (size_t i = 0; i < sizeof line_cases / sizeof line_cases[0]; i++) {
        snprintf(what, sizeof what, "hough.config.r%g.t%g.%g-%g", line_cases[i].rho,
                 line_cases[i].theta, line_cases[i].min_theta, line_cases[i].max_theta);
        if (emit_status(g, what,
                        rte_hough_config_init(cfg, in->w, in->h, line_cases[i].rho,
                                              line_cases[i].theta, line_cases[i].min_theta,
                                              line_cases[i].max_theta)))
            continue;
        digest d = dg_new();
        const int32_t fields[] = {cfg->num_angles, cfg->trig_shift, cfg->inv_rho_q16,
                                  cfg->rho_q16,    cfg->theta0_q16, cfg->theta_q16};
        for (size_t f = 0; f < sizeof fields / sizeof fields[0]; f++)
            dg_int(&d, fields[f]);
        for (int32_t a = 0; a < cfg->num_angles; a++) {
            dg_int(&d, cfg->rho_cos[a]);
            dg_int(&d, cfg->rho_sin[a]);
            dg_int(&d, cfg->unit_cos[a]);
            dg_int(&d, cfg->unit_sin[a]);
        }
        emit(g, what, d.h, "angles=%d", cfg->num_angles);

        snprintf(what, sizeof what, "hough.lines.r%g.t%g.%g-%g.v%d", line_cases[i].rho,
                 line_cases[i].theta, line_cases[i].min_theta, line_cases[i].max_theta,
                 line_cases[i].threshold);
        int32_t count = 0;
        bool truncated = false;
        if (!emit_status(g, what,
                         rte_hough_lines(cfg, &edges, line_cases[i].threshold, &g->arena, lines,
                                         MAX_LINES, &count, &truncated))) {
            d = dg_new();
            dg_int(&d, count);
            dg_int(&d, truncated);
            for (int32_t j = 0; j < count; j++) {
                dg_int(&d, lines[j].rho_bin);
                dg_int(&d, lines[j].theta_bin);
                dg_int(&d, lines[j].votes);
                dg_int(&d, rte_hough_line_rho_q16(cfg, &lines[j]));
                dg_int(&d, rte_hough_line_theta_q16(cfg, &lines[j]));
            }
            emit(g, what, d.h, "lines=%d truncated=%d", count, (int)truncated);
        }
        if (line_cases[i].min_theta != 0 || line_cases[i].max_theta != GOLDEN_PI)
            continue; /* segments take the full half turn */
        static const rte_hough_segments_params seg_cases[] = {
            {50, 30, 10, 0}, {20, 10, 3, 0}, {80, 60, 25, 0}, {50, 30, 10, 0x9E3779B9u}};
        for (size_t s = 0; s < sizeof seg_cases / sizeof seg_cases[0]; s++) {
            snprintf(what, sizeof what, "hough.segments.r%g.v%d.l%d.g%d%s%.0x", line_cases[i].rho,
                     seg_cases[s].threshold, seg_cases[s].min_length, seg_cases[s].max_gap,
                     seg_cases[s].seed ? ".s" : "",
                     seg_cases[s].seed); /* the seed, when not the default */
            if (emit_status(g, what,
                            rte_hough_segments(cfg, &edges, &seg_cases[s], &g->arena, segs,
                                               MAX_SEGMENTS, &count, &truncated)))
                continue;
            emit_records(g, what, "segments", &segs[0].x0, count, INT32_FIELDS(segs[0]), truncated);
        }
    }

    /* Circles: edges Canny(param1 / 2, param1) of the blurred image, 3x3 Sobel. */
    rte_image_s16 dx = new_s16(g, in->w, in->h), dy = new_s16(g, in->w, in->h);
    if (rte_canny_params_init(&cp, 50, 100, 3, false) != RTE_OK ||
        rte_canny_u8(&blurred, &edges, &cp, &g->arena) != RTE_OK ||
        rte_sobel_s16(&blurred, &dx, 1, 0, 3, &g->arena) != RTE_OK ||
        rte_sobel_s16(&blurred, &dy, 0, 1, 3, &g->arena) != RTE_OK)
        die("%s: gradients for the Hough circles failed", g->input);
    static const rte_hough_circles_params circle_cases[] = {
        {256, 20, 30, 5, 40, 0, 0}, {384, 10, 20, 0, 24, 0, 0}, {512, 40, 15, 20, 60, 0, 0}};
    for (size_t i = 0; i < sizeof circle_cases / sizeof circle_cases[0]; i++) {
        const rte_hough_circles_params *p = &circle_cases[i];
        snprintf(what, sizeof what, "hough.circles.dp%d.d%d.v%d.r%d-%d", p->dp_q8, p->min_dist,
                 p->acc_threshold, p->min_radius, p->max_radius);
        int32_t count = 0;
        bool truncated = false;
        if (emit_status(g, what,
                        rte_hough_circles(&edges, &dx, &dy, p, &g->arena, circles, MAX_CIRCLES,
                                          &count, &truncated)))
            continue;
        emit_records(g, what, "circles", &circles[0].x_q4, count, INT32_FIELDS(circles[0]),
                     truncated);
    }
}

/* ---- the lane path ---- */

static void emit_lane(golden *g, const char *what, const rte_lane_result *r)
{
    digest d = dg_new();
    for (int s = 0; s < 2; s++) {
        const rte_lane *l = &r->lane[s];
        const int64_t v[] = {l->found,     l->predicted, l->lost_frames, l->x_bottom_q8,
                             l->x_top_q8,  l->y_bottom,  l->y_top,       l->confidence_permille,
                             l->support_px};
        for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
            dg_int(&d, v[i]);
    }
    const int64_t v[] = {r->centre_valid, r->offset_q8, r->offset_permille, r->heading_tan_q16,
                         r->heading_mrad, r->canny_low, r->canny_high,      r->segment_count,
                         r->truncated,    r->t_ns};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        dg_int(&d, v[i]);
    for (int32_t i = 0; i < r->segment_count; i++) {
        const rte_lane_segment *s = &r->segments[i];
        dg_int(&d, s->x0);
        dg_int(&d, s->y0);
        dg_int(&d, s->x1);
        dg_int(&d, s->y1);
        dg_int(&d, s->use);
    }
    emit(g, what, d.h, "left=%d right=%d offset_q8=%d segments=%d", r->lane[0].found,
         r->lane[1].found, r->offset_q8, r->segment_count);
}

static rte_lane_context *lane_create(int32_t w, int32_t h, int variant)
{
    rte_lane_config cfg;
    rte_lane_config_default(&cfg, w, h);
    if (variant == 1) {
        cfg.params.fit = RTE_LANE_FIT_THEIL_SEN;
        cfg.params.canny_mode = RTE_LANE_CANNY_OTSU;
    } else if (variant == 2) {
        cfg.params.canny_mode = RTE_LANE_CANNY_FIXED;
        cfg.params.canny_low = 40;
        cfg.params.canny_high = 120;
        cfg.params.use_color = false;
        cfg.blur_ksize = 7;
    }
    rte_lane_context *ctx = NULL;
    if (rte_lane_create(&cfg, &ctx) != RTE_OK)
        die("rte_lane_create failed for %dx%d", w, h);
    return ctx;
}

static void run_lane(golden *g, const input *in)
{
    static const char *names[] = {"lane.default", "lane.theil-sen.otsu", "lane.fixed.blur7.grey"};
    for (int variant = 0; variant < 3; variant++) {
        rte_lane_context *ctx = lane_create(in->w, in->h, variant);
        rte_lane_result r;
        if (!emit_status(g, names[variant],
                         rte_lane_process_gray(ctx, &in->gray, &in->bgr, 1000, &r)))
            emit_lane(g, names[variant], &r);
        rte_lane_destroy(ctx);
    }
}

/* ---- the grasp path ---- */

static void run_grasp(golden *g, const input *in)
{
    static const struct {
        const char *name;
        rte_grasp_binarize binarize;
        rte_grasp_polarity polarity;
        int32_t threshold, skip_border;
    } cases[] = {{"grasp.otsu.auto", RTE_GRASP_OTSU, RTE_GRASP_AUTO, 0, 0},
                 {"grasp.fixed100.dark.skip-border", RTE_GRASP_FIXED, RTE_GRASP_DARK, 100, 1},
                 {"grasp.canny-close", RTE_GRASP_CANNY_CLOSE, RTE_GRASP_AUTO, 0, 0}};
    if (in->w > RTE_SHAPE_MAX_COORD + 1 || in->h > RTE_SHAPE_MAX_COORD + 1)
        return;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rte_grasp_config cfg;
        rte_grasp_config_default(&cfg);
        cfg.max_width = in->w;
        cfg.max_height = in->h;
        cfg.params.binarize = cases[i].binarize;
        cfg.params.polarity = cases[i].polarity;
        cfg.params.threshold = cases[i].threshold;
        cfg.params.skip_border = cases[i].skip_border;
        rte_grasp_ctx *ctx = NULL;
        rte_grasp_result r;
        if (emit_status(g, cases[i].name, rte_grasp_create(&cfg, &ctx)))
            continue;
        if (!emit_status(g, cases[i].name, rte_grasp_process(ctx, &in->gray, &r))) {
            digest d = dg_new();
            const int64_t v[] = {r.n_objects,        r.truncated, r.dropped_objects,
                                 r.dropped_contours, r.threshold, r.polarity};
            for (size_t j = 0; j < sizeof v / sizeof v[0]; j++)
                dg_int(&d, v[j]);
            for (int32_t j = 0; j < r.n_objects; j++) {
                const rte_grasp_object *o = &r.objects[j];
                dg_int(&d, o->x_q8);
                dg_int(&d, o->y_q8);
                dg_int(&d, o->angle_q16);
                dg_int(&d, o->width_q8);
                dg_int(&d, o->opening_q8);
                for (int k = 0; k < 4; k++)
                    dg_int(&d, o->jaws_q8[k / 2][k % 2]);
                dg_int(&d, o->clearance_q8);
                dg_int(&d, o->score_q16);
                dg_int(&d, o->contour);
                dg_int(&d, o->touches_border);
                dg_shape_info(&d, &o->info);
            }
            dg_int(&d, (int64_t)hash_contours(r.contours));
            int64_t nz;
            bool ok;
            dg_int(&d, (int64_t)hash_u8(r.binary, &nz, &ok));
            emit(g, cases[i].name, d.h, "objects=%d threshold=%d", r.n_objects, r.threshold);
        }
        rte_grasp_destroy(ctx);
    }
}

/* ---- inputs ---- */

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static bool has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

static void run_all(golden *g, const input *in, rte_hough_config *cfg)
{
    digest d = dg_new();
    for (int32_t y = 0; y < in->h; y++)
        dg_bytes(&d, in->bgr.buf + (size_t)y * (size_t)in->bgr.stride, 3 * (size_t)in->w);
    emit(g, "input.bgr", d.h, "%dx%d", in->w, in->h);
    run_color(g, in);
    run_blur(g, in);
    run_gradient(g, in);
    run_canny(g, in);
    run_threshold(g, in);
    rte_image_u8 bin = otsu_binary(g, in);
    run_morphology(g, in, &bin);
    run_polygon(g, in);
    rte_contours c = new_contours(g, in);
    run_contours(g, in, &bin, &c);
    run_shapes(g, &c);
    run_hough(g, in, cfg);
    run_lane(g, in);
    run_grasp(g, in);
}

/* The grey image of `in` from its BGR (as cv::cvtColor, the library's own
 * conversion: its output is checked by the gray.bgr line). */
static void make_gray(golden *g, input *in)
{
    in->gray = new_u8(g, in->w, in->h);
    if (rte_color_bgr_to_gray(&in->bgr, &in->gray) != RTE_OK)
        die("%s: grey conversion failed", g->input);
}

static void run_image(golden *g, const char *path, rte_hough_config *cfg)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_info info;
    if (rte_image_probe(path, &info, msg, sizeof msg) != RTE_OK)
        die("%s", msg);
    input in = {.w = info.width, .h = info.height};
    rte_image_reader *reader = rte_image_reader_create(in.w, in.h);
    if (!reader)
        die("%s: no reader", path);
    in.bgr = new_u8c3(g, in.w, in.h);
    if (rte_image_read_bgr(reader, path, &in.bgr, msg, sizeof msg) != RTE_OK)
        die("%s", msg);
    rte_image_reader_destroy(reader);
    make_gray(g, &in);
    run_all(g, &in, cfg);
}

/* A clip: its first frame through everything, every frame through the
 * lane tracker (one line per frame, so a divergence shows where it starts). */
static void run_y4m(golden *g, const char *path, rte_hough_config *cfg)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_y4m_reader *reader = NULL;
    rte_y4m_info info;
    if (rte_y4m_open(path, 0, 0, &reader, &info, msg, sizeof msg) != RTE_OK)
        die("%s", msg);
    input in = {.w = info.width, .h = info.height};
    rte_image_u8 frame = new_u8(g, in.w, in.h);
    rte_lane_context *ctx = lane_create(in.w, in.h, 0);
    rte_status st;
    int32_t n = 0;
    while ((st = rte_y4m_read_gray(reader, &frame, msg, sizeof msg)) == RTE_OK) {
        char what[48];
        snprintf(what, sizeof what, "lane.sequence.frame%03d", n);
        rte_lane_result r;
        if (!emit_status(g, what,
                         rte_lane_process_gray(ctx, &frame, NULL, (int64_t)n * 40000000, &r)))
            emit_lane(g, what, &r);
        if (n++ == 0) { /* the first frame, as a colour image of grey pixels */
            in.gray = copy_u8(g, &frame);
            in.bgr = new_u8c3(g, in.w, in.h);
            for (int32_t y = 0; y < in.h; y++)
                for (int32_t x = 0; x < in.w; x++)
                    memset(in.bgr.buf + (size_t)y * (size_t)in.bgr.stride + 3 * (size_t)x,
                           rte_u8_row(&frame, y)[x], 3);
        }
    }
    if (st != RTE_ERR_END)
        die("%s", msg);
    rte_lane_destroy(ctx);
    rte_y4m_close(reader);
    if (n > 0)
        run_all(g, &in, cfg);
}

/* ---- main ---- */

static char **read_lines(const char *path, size_t *n)
{
    FILE *f = fopen(path, "r");
    if (!f)
        die("cannot open %s", path);
    char **lines = NULL, buf[1024];
    size_t cap = 0;
    *n = 0;
    while (fgets(buf, sizeof buf, f)) {
        buf[strcspn(buf, "\n")] = '\0';
        if (*n == cap) {
            cap = cap ? 2 * cap : 1024;
            char **grown = realloc(lines, cap * sizeof *grown);
            if (!grown)
                die("out of memory");
            lines = grown;
        }
        lines[*n] = xmalloc(strlen(buf) + 1);
        strcpy(lines[(*n)++], buf);
    }
    fclose(f);
    return lines;
}

static const char *path_name(void)
{
    uint32_t f = rte_cpu_features();
    if (f == 0)
        return rte_cpu_features_hw() ? "plain C (RTE_FORCE_C)" : "plain C";
    if (f & RTE_CPU_ARM_NEON)
        return "NEON";
    if ((f & RTE_CPU_X86_AVX2) && (f & RTE_CPU_X86_AVX512))
        return "AVX-512";
    if (f & RTE_CPU_X86_AVX2)
        return "AVX2";
    return "SSE";
}

int main(int argc, char **argv)
{
    if (argc < 4 || (strcmp(argv[1], "write") != 0 && strcmp(argv[1], "check") != 0)) {
        fprintf(stderr, "usage: golden write OUT FILE... | golden check REF FILE...\n");
        return 2;
    }
    golden g;
    memset(&g, 0, sizeof g);
    void *arena_mem = xmalloc(ARENA_BYTES);
    rte_arena_init(&g.arena, arena_mem, ARENA_BYTES);
    rte_hough_config *cfg = xmalloc(sizeof *cfg);
    for (int i = 3; i < argc; i++) {
        g.input = base_name(argv[i]);
        if (has_suffix(argv[i], ".y4m"))
            run_y4m(&g, argv[i], cfg);
        else
            run_image(&g, argv[i], cfg);
        free_owned(&g);
    }
    free(cfg);
    free(arena_mem);

    int failed = 0;
    if (strcmp(argv[1], "write") == 0) {
        FILE *f = fopen(argv[2], "w");
        if (!f)
            die("cannot write %s", argv[2]);
        for (size_t i = 0; i < g.n_lines; i++)
            fprintf(f, "%s\n", g.lines[i]);
        if (fclose(f) != 0)
            die("cannot write %s", argv[2]);
        printf("golden: %zu outputs of %d inputs written to %s (%s kernels)\n", g.n_lines, argc - 3,
               argv[2], path_name());
    } else {
        size_t n_ref;
        char **ref = read_lines(argv[2], &n_ref);
        size_t differ = 0, n = n_ref < g.n_lines ? n_ref : g.n_lines;
        for (size_t i = 0; i < n; i++)
            if (strcmp(ref[i], g.lines[i]) != 0 && differ++ < 40)
                printf("differs:\n  reference %s\n  this      %s\n", ref[i], g.lines[i]);
        if (n_ref != g.n_lines)
            printf("different number of outputs: reference %zu, this %zu\n", n_ref, g.n_lines);
        printf("golden: %zu outputs of %d inputs compared with %s (%s kernels): %zu differ\n",
               g.n_lines, argc - 3, argv[2], path_name(), differ);
        failed = differ > 0 || n_ref != g.n_lines || g.n_lines == 0;
        for (size_t i = 0; i < n_ref; i++)
            free(ref[i]);
        free(ref);
    }
    for (size_t i = 0; i < g.n_lines; i++)
        free(g.lines[i]);
    free(g.lines);
    return failed;
}
