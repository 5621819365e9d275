/* Row kernels with SIMD variants (internal to librtedge; the unit test
 * tests/unit/test_simd.c includes it to compare every variant with its C
 * reference byte for byte).
 *
 * Each kernel has a plain C reference named *_c, kept in the family's own
 * source file (compiled with -mgeneral-regs-only), and variants in
 * src/algo/simd/ named after the instruction set (rte_..._ssse3, _avx2,
 * _avx512, _neon; x86 ones in NAME_x86.c, NEON ones in NAME_neon.c, each compiling
 * to nothing on the other CPU family): the build suite relies on these
 * names to check that every variant holds vector instructions of its kind
 * (tests/build/check_simd_objects.py). A *_select(features) function picks
 * the best variant for a feature word from rte_cpu_features(); the
 * families call it once per image, and the unit test calls it under every
 * feature mask. Every variant handles any width >= 1, any alignment, and
 * writes exactly `width` bytes. */
#ifndef RTEDGE_SIMD_ROWS_H
#define RTEDGE_SIMD_ROWS_H

#include <stdbool.h>
#include <stdint.h>

#include "rtedge/cpu.h"

#if defined(__x86_64__) || defined(__i386__)
#define RTE_SIMD_X86 1
#endif
#if defined(__aarch64__)
#define RTE_SIMD_NEON 1
#endif

/* The variant for a feature word: `avx512` on x86 with AVX2 and AVX-512,
 * `avx2` on x86 with AVX2, `neon` on aarch64 with NEON, else the C
 * reference `c` (pass the next best again for a variant that does not
 * exist). Only the current CPU family's arguments are compiled, so the
 * others may name functions built for other CPUs. */
#if defined(RTE_SIMD_X86)
#define RTE_SIMD_PICK(features, c, avx2, avx512, neon)                       \
    ((~(features) & (RTE_CPU_X86_AVX2 | RTE_CPU_X86_AVX512)) == 0 ? (avx512) \
     : ((features)&RTE_CPU_X86_AVX2)                              ? (avx2)   \
                                                                  : (c))
#elif defined(RTE_SIMD_NEON)
#define RTE_SIMD_PICK(features, c, avx2, avx512, neon) \
    (((features)&RTE_CPU_ARM_NEON) ? (neon) : (c))
#else
#define RTE_SIMD_PICK(features, c, avx2, avx512, neon) ((void)(features), (c))
#endif

/* The compiler-vectorised x86 files (simd/NAME_x86.c without intrinsics:
 * the C references' loops, included from the family's *_rows.h or written
 * out) are built twice, at -O3 whatever the build type (src/meson.build:
 * rtedge_simd_autovec): for AVX2, and with RTE_SIMD_ISA = avx512 for
 * AVX-512 (F, BW, VL, 512-bit vectors). Safe because the loops are integer
 * only: vectorising them only reorders exact operations, so the bytes stay
 * the C references' (tests/unit/test_simd.c compares them, and
 * tests/build/check_simd_objects.py checks that each object holds vector
 * code of its width). RTE_SIMD_NAME(rte_x) is rte_x_avx2 or rte_x_avx512,
 * RTE_SIMD_APPLY(M) is M(avx2) or M(avx512), and RTE_SIMD_BYTES the vector
 * width. */
#ifndef RTE_SIMD_ISA
#define RTE_SIMD_ISA avx2
#endif
#define RTE_SIMD_PASTE_(a, b) a##_##b
#define RTE_SIMD_PASTE(a, b) RTE_SIMD_PASTE_(a, b)
#define RTE_SIMD_NAME(name) RTE_SIMD_PASTE(name, RTE_SIMD_ISA)
#define RTE_SIMD_APPLY_(macro, isa) macro(isa)
#define RTE_SIMD_APPLY(macro) RTE_SIMD_APPLY_(macro, RTE_SIMD_ISA)
#ifdef __AVX512BW__
#define RTE_SIMD_BYTES 64
#else
#define RTE_SIMD_BYTES 32
#endif

/* 3-byte pixels (B,G,R or R,G,B) to grey with BT.601 luma weights in Q15.
 * OpenCV 4.6 has a Q14 table too, but every 8-bit BGR2GRAY/RGB2GRAY row
 * (SIMD body and scalar tail alike) goes through these: checked on all
 * 2^24 colours at widths 1..65 and 4096. */
enum { RTE_GRAY_B = 3735, RTE_GRAY_G = 19235, RTE_GRAY_R = 9798, RTE_GRAY_SHIFT = 15 };
typedef void (*rte_row_c3_to_gray_fn)(const uint8_t *src, uint8_t *dst, int32_t width);

void rte_row_bgr_to_gray_c(const uint8_t *src, uint8_t *dst, int32_t width);
void rte_row_rgb_to_gray_c(const uint8_t *src, uint8_t *dst, int32_t width);
/* rgb: R,G,B order, else B,G,R. */
rte_row_c3_to_gray_fn rte_row_c3_to_gray_select(uint32_t features, bool rgb);

/* Gaussian blur (src/algo/gaussian.c, gaussian_rows.h): the column pass
 * of ksize source rows into the u16 planes hi/lo, and the row pass of the
 * padded planes into dst. */
typedef void (*rte_gaussian_column_fn)(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,
                                       int32_t width, const uint16_t *taps, int32_t ksize,
                                       int split);
typedef void (*rte_gaussian_row_fn)(const uint16_t *hi, const uint16_t *lo, uint8_t *dst,
                                    int32_t width, const uint16_t *taps, int32_t ksize, int split);
typedef struct rte_gaussian_rows {
    rte_gaussian_column_fn column;
    rte_gaussian_row_fn row;
} rte_gaussian_rows;

void rte_gaussian_column_pass_c(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,
                                int32_t width, const uint16_t *taps, int32_t ksize, int split);
void rte_gaussian_row_pass_c(const uint16_t *hi, const uint16_t *lo, uint8_t *dst, int32_t width,
                             const uint16_t *taps, int32_t ksize, int split);
rte_gaussian_rows rte_gaussian_rows_select(uint32_t features);

/* Morphology (src/algo/morphology.c, morphology_rows.h): d = min or max of
 * a and b, and of `count` rows (with d's own values when accumulating). */
typedef void (*rte_morph_op2_fn)(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n,
                                 bool is_max);
typedef void (*rte_morph_reduce_fn)(uint8_t *d, const uint8_t *const *r, int32_t count,
                                    bool accumulate, int32_t n, bool is_max);
typedef struct rte_morph_rows {
    rte_morph_op2_fn op2;
    rte_morph_reduce_fn reduce;
} rte_morph_rows;

void rte_morph_row_op2_c(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n, bool is_max);
void rte_morph_reduce_rows_c(uint8_t *d, const uint8_t *const *r, int32_t count, bool accumulate,
                             int32_t n, bool is_max);
rte_morph_rows rte_morph_rows_select(uint32_t features);

/* Canny with aperture 3 and the L1 magnitude on 8-bit images (src/algo/
 * canny.c, canny_rows.h): Sobel dx, dy and |dx| + |dy| of the row between
 * three source rows (columns replicated at the ends), and the non-maximum
 * suppression of a magnitude row (up, cur, down hold 0 at index -1 and
 * width) into map codes 1 / 0 / 2 (not an edge / maybe / edge). */
typedef void (*rte_canny_sobel_fn)(const uint8_t *up, const uint8_t *mid, const uint8_t *down,
                                   int16_t *dx, int16_t *dy, int16_t *mag, int32_t width);
typedef void (*rte_canny_nms_fn)(const int16_t *up, const int16_t *cur, const int16_t *down,
                                 const int16_t *dx, const int16_t *dy, uint8_t *map, int32_t width,
                                 int16_t low, int16_t high);
typedef struct rte_canny_rows {
    rte_canny_sobel_fn sobel;
    rte_canny_nms_fn nms;
} rte_canny_rows;

/* rte_canny_sobel_row_<isa> and rte_canny_nms_row_<isa>, of the types above. */
#define RTE_CANNY_ROWS_DECLARE(isa)                                                            \
    void rte_canny_sobel_row_##isa(const uint8_t *up, const uint8_t *mid, const uint8_t *down, \
                                   int16_t *dx, int16_t *dy, int16_t *mag, int32_t width);     \
    void rte_canny_nms_row_##isa(const int16_t *up, const int16_t *cur, const int16_t *down,   \
                                 const int16_t *dx, const int16_t *dy, uint8_t *map,           \
                                 int32_t width, int16_t low, int16_t high);
RTE_CANNY_ROWS_DECLARE(c)
rte_canny_rows rte_canny_rows_select(uint32_t features);

/* Fixed-level threshold of a row (src/algo/threshold.c, threshold_rows.h),
 * `type` an rte_threshold_type, 0 <= t < 255; s == d (in place) allowed. */
typedef void (*rte_threshold_row_fn)(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                                     uint8_t maxval);
void rte_threshold_row_c(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                         uint8_t maxval);
rte_threshold_row_fn rte_threshold_row_select(uint32_t features);

/* The table estimate and its threshold (src/algo/background.c and
 * background_threshold.c, background_rows.h): the interpolated values'
 * next row and their grey levels, |s - b|, the side classes and the
 * floors. */
typedef struct rte_background_rows {
    void (*add)(int32_t *v, const int32_t *add, int32_t w);
    void (*store)(const int32_t *v, uint8_t *out, int32_t w);
    void (*absdiff)(const uint8_t *s, const uint8_t *b, uint8_t *a, int32_t w);
    void (*classify)(const uint8_t *a, const uint8_t *s, const uint8_t *b, uint8_t *c, int32_t w,
                     uint8_t low, uint8_t high, uint8_t bright_class, uint8_t dark_class);
    void (*above_floor)(uint8_t *a, const uint8_t *fl, int32_t w);
    void (*chroma_diff)(const uint8_t *cb, const uint8_t *cbt, const uint8_t *cr,
                        const uint8_t *crt, uint8_t *c2, int32_t hw);
    void (*tint)(const uint8_t *s, const uint8_t *b, uint8_t *cd, int32_t w, uint8_t least,
                 uint8_t up_only, uint8_t either);
    void (*shade)(const uint8_t *s, const uint8_t *t, const uint8_t *cb, const uint8_t *cbt,
                  const uint8_t *cr, const uint8_t *crt, uint8_t *out, int32_t hw, int32_t lo,
                  int32_t hi, int32_t tol);
    void (*shade_class)(uint8_t *c, const uint8_t *m, int32_t w);
} rte_background_rows;

/* rte_background_<kernel>_row_<isa> for every kernel of the family, and
 * (DEFINE) their bodies from background_rows.h. */
#define RTE_BACKGROUND_ROWS_DECLARE(isa)                                                           \
    void rte_background_add_row_##isa(int32_t *v, const int32_t *add, int32_t w);                  \
    void rte_background_store_row_##isa(const int32_t *v, uint8_t *out, int32_t w);                \
    void rte_background_absdiff_row_##isa(const uint8_t *s, const uint8_t *b, uint8_t *a,          \
                                          int32_t w);                                              \
    void rte_background_classify_row_##isa(const uint8_t *a, const uint8_t *s, const uint8_t *b,   \
                                           uint8_t *c, int32_t w, uint8_t low, uint8_t high,       \
                                           uint8_t bright_class, uint8_t dark_class);              \
    void rte_background_above_floor_row_##isa(uint8_t *a, const uint8_t *fl, int32_t w);           \
    void rte_background_chroma_diff_row_##isa(const uint8_t *cb, const uint8_t *cbt,               \
                                              const uint8_t *cr, const uint8_t *crt, uint8_t *c2,  \
                                              int32_t hw);                                         \
    void rte_background_tint_row_##isa(const uint8_t *s, const uint8_t *b, uint8_t *cd, int32_t w, \
                                       uint8_t least, uint8_t up_only, uint8_t either);            \
    void rte_background_shade_row_##isa(const uint8_t *s, const uint8_t *t, const uint8_t *cb,     \
                                        const uint8_t *cbt, const uint8_t *cr, const uint8_t *crt, \
                                        uint8_t *out, int32_t hw, int32_t lo, int32_t hi,          \
                                        int32_t tol);                                              \
    void rte_background_shade_class_row_##isa(uint8_t *c, const uint8_t *m, int32_t w);

#define RTE_BACKGROUND_ROWS_DEFINE(isa)                                                            \
    void rte_background_add_row_##isa(int32_t *v, const int32_t *add, int32_t w)                   \
    {                                                                                              \
        background_add_row(v, add, w);                                                             \
    }                                                                                              \
    void rte_background_store_row_##isa(const int32_t *v, uint8_t *out, int32_t w)                 \
    {                                                                                              \
        background_store_row(v, out, w);                                                           \
    }                                                                                              \
    void rte_background_absdiff_row_##isa(const uint8_t *s, const uint8_t *b, uint8_t *a,          \
                                          int32_t w)                                               \
    {                                                                                              \
        background_absdiff_row(s, b, a, w);                                                        \
    }                                                                                              \
    void rte_background_classify_row_##isa(const uint8_t *a, const uint8_t *s, const uint8_t *b,   \
                                           uint8_t *c, int32_t w, uint8_t low, uint8_t high,       \
                                           uint8_t bright_class, uint8_t dark_class)               \
    {                                                                                              \
        background_classify_row(a, s, b, c, w, low, high, bright_class, dark_class);               \
    }                                                                                              \
    void rte_background_above_floor_row_##isa(uint8_t *a, const uint8_t *fl, int32_t w)            \
    {                                                                                              \
        background_above_floor_row(a, fl, w);                                                      \
    }                                                                                              \
    void rte_background_chroma_diff_row_##isa(const uint8_t *cb, const uint8_t *cbt,               \
                                              const uint8_t *cr, const uint8_t *crt, uint8_t *c2,  \
                                              int32_t hw)                                          \
    {                                                                                              \
        background_chroma_diff_row(cb, cbt, cr, crt, c2, hw);                                      \
    }                                                                                              \
    void rte_background_tint_row_##isa(const uint8_t *s, const uint8_t *b, uint8_t *cd, int32_t w, \
                                       uint8_t least, uint8_t up_only, uint8_t either)             \
    {                                                                                              \
        background_tint_row(s, b, cd, w, least, up_only, either);                                  \
    }                                                                                              \
    void rte_background_shade_row_##isa(const uint8_t *s, const uint8_t *t, const uint8_t *cb,     \
                                        const uint8_t *cbt, const uint8_t *cr, const uint8_t *crt, \
                                        uint8_t *out, int32_t hw, int32_t lo, int32_t hi,          \
                                        int32_t tol)                                               \
    {                                                                                              \
        background_shade_row(s, t, cb, cbt, cr, crt, out, hw, lo, hi, tol);                        \
    }                                                                                              \
    void rte_background_shade_class_row_##isa(uint8_t *c, const uint8_t *m, int32_t w)             \
    {                                                                                              \
        background_shade_class_row(c, m, w);                                                       \
    }
RTE_BACKGROUND_ROWS_DECLARE(c)
rte_background_rows rte_background_rows_select(uint32_t features);

/* Separable integer filters of the gradient family (src/algo/gradient.c,
 * gradient_loops.h; also Canny's apertures 5 and 7 and L2): the column
 * pass of ny source rows into int16, and the row pass of a padded int16
 * row (mode an rte_row_mode of gradient_rows.h). */
typedef void (*rte_grad_column_fn)(const uint8_t *const *rows, int32_t width, const int16_t *ky,
                                   int32_t ny, int16_t *out);
typedef void (*rte_grad_row_fn)(const int16_t *v, const int16_t *kx, int32_t nx, int16_t *out,
                                int32_t width, int mode);
typedef struct rte_grad_rows {
    rte_grad_column_fn column;
    rte_grad_row_fn row;
} rte_grad_rows;

/* rte_grad_column_<isa> and rte_grad_row_<isa>, of the types above. */
#define RTE_GRAD_ROWS_DECLARE(isa)                                                           \
    void rte_grad_column_##isa(const uint8_t *const *rows, int32_t width, const int16_t *ky, \
                               int32_t ny, int16_t *out);                                    \
    void rte_grad_row_##isa(const int16_t *v, const int16_t *kx, int32_t nx, int16_t *out,   \
                            int32_t width, int mode);
RTE_GRAD_ROWS_DECLARE(c)
rte_grad_rows rte_grad_rows_select(uint32_t features);

/* The lane path's colour cue (src/pipeline/lane_cue.c, lane_cue_rows.h):
 * white or yellow paint in a B,G,R row (R,G,B when rgb) -> 255, other
 * pixels gray * dim_q8 / 256. Thresholds of 256 are given as *_on = 0. */
typedef struct rte_lane_cue {
    uint8_t white_min, white_on, yellow_min, yellow_on, yellow_b_margin;
    uint16_t dim_q8;
} rte_lane_cue;
typedef void (*rte_lane_cue_row_fn)(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst,
                                    int32_t width, const rte_lane_cue *cue, bool rgb);
void rte_lane_cue_row_c(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst, int32_t width,
                        const rte_lane_cue *cue, bool rgb);
rte_lane_cue_row_fn rte_lane_cue_row_select(uint32_t features);
/* The same cue on the one or two Y rows (g[1], d[1] NULL for one) that
 * share a row of half-resolution chroma blocks: block i's Cb, Cr at
 * cb[i], cr[i], or at cb[2 i], cr[2 i] when interleaved (NV12); block 0
 * begins one pixel left of the rows when odd is set. */
typedef void (*rte_lane_cue_chroma_row_fn)(const uint8_t *const g[2], const uint8_t *cb,
                                           const uint8_t *cr, bool interleaved, uint8_t *const d[2],
                                           int32_t width, bool odd, const rte_lane_cue *cue);
void rte_lane_cue_chroma_row_c(const uint8_t *const g[2], const uint8_t *cb, const uint8_t *cr,
                               bool interleaved, uint8_t *const d[2], int32_t width, bool odd,
                               const rte_lane_cue *cue);
rte_lane_cue_chroma_row_fn rte_lane_cue_chroma_row_select(uint32_t features);

/* Hough segments (src/algo/hough_segments.c, hough_rows.h): the
 * accumulator index of the point (x, y) at each of n angles,
 * idx[a] = row_base[a] + ((x * rho_cos[a] + y * rho_sin[a] + bias) >> shift),
 * the sum in [0, 2^31); row_base[a] places the rho bins of angle a. */
typedef void (*rte_hough_bins_fn)(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n,
                                  int32_t x, int32_t y, int32_t bias, int32_t shift,
                                  const int32_t *row_base, int32_t *idx);
void rte_hough_bins_c(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n, int32_t x,
                      int32_t y, int32_t bias, int32_t shift, const int32_t *row_base,
                      int32_t *idx);
rte_hough_bins_fn rte_hough_bins_select(uint32_t features);

/* Hough lines (src/algo/hough_lines.c, hough_rows.h): `bins`, the rho bin
 * of each of n packed points pts[i] = y << 16 | x at one angle,
 * idx[i] = (x * rho_cos + y * rho_sin + bias) >> shift, the sum in
 * [0, 2^31) and |rho_cos|, |rho_sin| < 2^30 (rte_hough_config_init keeps
 * them below 2^31 / (4 (w + h + 2)) <= 2^27); `sum`, the RTE_HOUGH_LINE_COPIES rows of 16-bit votes at
 * copies + k * cstep added into cells (cells[r] += every copy's [r] for
 * r < n) and cleared. */
enum { RTE_HOUGH_LINE_COPIES = 4 };
typedef void (*rte_hough_point_bins_fn)(const uint32_t *pts, int32_t n, int32_t rho_cos,
                                        int32_t rho_sin, int32_t bias, int32_t shift, int32_t *idx);
typedef void (*rte_hough_sum_copies_fn)(int32_t *cells, uint16_t *copies, int32_t cstep, int32_t n);
typedef struct rte_hough_line_rows {
    rte_hough_point_bins_fn bins;
    rte_hough_sum_copies_fn sum;
} rte_hough_line_rows;

/* rte_hough_point_bins_<isa> and rte_hough_sum_copies_<isa>, of the types above. */
#define RTE_HOUGH_LINE_ROWS_DECLARE(isa)                                                         \
    void rte_hough_point_bins_##isa(const uint32_t *pts, int32_t n, int32_t rho_cos,             \
                                    int32_t rho_sin, int32_t bias, int32_t shift, int32_t *idx); \
    void rte_hough_sum_copies_##isa(int32_t *cells, uint16_t *copies, int32_t cstep, int32_t n);
RTE_HOUGH_LINE_ROWS_DECLARE(c)
rte_hough_line_rows rte_hough_line_rows_select(uint32_t features);
/* Hough circles (src/algo/hough_circles.c; the AVX2 variant is its own
 * loop, simd/hough_circles_x86.c): the n + 1 votes of an edge pixel along
 * one direction, all inside the accumulator. */
typedef void (*rte_circle_votes_fn)(int32_t *acc, uint32_t mask, uint32_t astep, uint32_t ux,
                                    uint32_t uy, uint32_t sx, uint32_t sy, int32_t n);
void rte_circle_votes_c(int32_t *acc, uint32_t mask, uint32_t astep, uint32_t ux, uint32_t uy,
                        uint32_t sx, uint32_t sy, int32_t n);
rte_circle_votes_fn rte_circle_votes_select(uint32_t features);

#ifdef RTE_SIMD_X86
void rte_row_bgr_to_gray_ssse3(const uint8_t *src, uint8_t *dst, int32_t width);
void rte_row_rgb_to_gray_ssse3(const uint8_t *src, uint8_t *dst, int32_t width);
void rte_row_bgr_to_gray_avx2(const uint8_t *src, uint8_t *dst, int32_t width);
void rte_row_rgb_to_gray_avx2(const uint8_t *src, uint8_t *dst, int32_t width);
void rte_hough_point_bins_avx2(const uint32_t *pts, int32_t n, int32_t rho_cos, int32_t rho_sin,
                               int32_t bias, int32_t shift, int32_t *idx);
/* The compiler-vectorised families, once per instruction set. */
#define RTE_SIMD_AUTOVEC_DECLARE(isa)                                                            \
    RTE_CANNY_ROWS_DECLARE(isa)                                                                  \
    RTE_GRAD_ROWS_DECLARE(isa)                                                                   \
    RTE_BACKGROUND_ROWS_DECLARE(isa)                                                             \
    void rte_lane_cue_row_##isa(const uint8_t *gray, const uint8_t *bgr, uint8_t *dst,           \
                                int32_t width, const rte_lane_cue *cue, bool rgb);               \
    void rte_lane_cue_chroma_row_##isa(const uint8_t *const g[2], const uint8_t *cb,             \
                                       const uint8_t *cr, bool interleaved, uint8_t *const d[2], \
                                       int32_t width, bool odd, const rte_lane_cue *cue);        \
    void rte_threshold_row_##isa(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,   \
                                 uint8_t maxval);                                                \
    void rte_morph_row_op2_##isa(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n,      \
                                 bool is_max);                                                   \
    void rte_morph_reduce_rows_##isa(uint8_t *d, const uint8_t *const *r, int32_t count,         \
                                     bool accumulate, int32_t n, bool is_max);                   \
    void rte_gaussian_column_pass_##isa(const uint8_t *const *rows, uint16_t *hi, uint16_t *lo,  \
                                        int32_t width, const uint16_t *taps, int32_t ksize,      \
                                        int split);                                              \
    void rte_gaussian_row_pass_##isa(const uint16_t *hi, const uint16_t *lo, uint8_t *dst,       \
                                     int32_t width, const uint16_t *taps, int32_t ksize,         \
                                     int split);                                                 \
    void rte_hough_bins_##isa(const int32_t *rho_cos, const int32_t *rho_sin, int32_t n,         \
                              int32_t x, int32_t y, int32_t bias, int32_t shift,                 \
                              const int32_t *row_base, int32_t *idx);                            \
    void rte_hough_sum_copies_##isa(int32_t *cells, uint16_t *copies, int32_t cstep, int32_t n); \
    void rte_circle_votes_##isa(int32_t *acc, uint32_t mask, uint32_t astep, uint32_t ux,        \
                                uint32_t uy, uint32_t sx, uint32_t sy, int32_t n);
RTE_SIMD_AUTOVEC_DECLARE(avx2)
RTE_SIMD_AUTOVEC_DECLARE(avx512)
#endif
#ifdef RTE_SIMD_NEON
void rte_row_bgr_to_gray_neon(const uint8_t *src, uint8_t *dst, int32_t width);
void rte_row_rgb_to_gray_neon(const uint8_t *src, uint8_t *dst, int32_t width);
RTE_CANNY_ROWS_DECLARE(neon)
void rte_threshold_row_neon(const uint8_t *s, uint8_t *d, int32_t n, int type, uint8_t t,
                            uint8_t maxval);
#endif

#endif
