/* Thresholding, histogram, Otsu (against a double-precision replay of
 * OpenCV's loop), the binary64 emulation and the automatic Canny rules. */
#include "unit.h"

#include <float.h>
#include <math.h>

#include "rtedge/threshold.h"

#include "algo/binary64.h"

static rte_threshold_params params(rte_threshold_type type, double thresh, double maxval, bool otsu)
{
    rte_threshold_params p;
    assert_int_equal(rte_threshold_params_init(&p, type, thresh, maxval, otsu), RTE_OK);
    return p;
}

static void apply_row(const uint8_t *in, int n, rte_threshold_type type, double thresh,
                      double maxval, const uint8_t *want)
{
    rte_image_u8 src = unit_image_u8(n, 1, 3, 0), dst = unit_image_u8(n, 1, 5, 0);
    memcpy(src.buf, in, (size_t)n);
    rte_threshold_params p = params(type, thresh, maxval, false);
    int32_t used = -7;
    assert_int_equal(rte_threshold_u8(&src, &dst, &p, &used), RTE_OK);
    assert_int_equal(used, (int32_t)floor(thresh));
    assert_memory_equal(dst.buf, want, (size_t)n);
    unit_assert_padding_u8(&dst);
    unit_assert_padding_u8(&src);
    test_free(src.buf);
    test_free(dst.buf);
}

static void every_type_on_a_hand_checked_row(void **state)
{
    const uint8_t in[6] = {0, 100, 127, 128, 200, 255};
    apply_row(in, 6, RTE_THRESH_BINARY, 127, 200, (const uint8_t[]){0, 0, 0, 200, 200, 200});
    apply_row(in, 6, RTE_THRESH_BINARY_INV, 127, 200, (const uint8_t[]){200, 200, 200, 0, 0, 0});
    apply_row(in, 6, RTE_THRESH_TRUNC, 127, 200, (const uint8_t[]){0, 100, 127, 127, 127, 127});
    apply_row(in, 6, RTE_THRESH_TOZERO, 127, 200, (const uint8_t[]){0, 0, 0, 128, 200, 255});
    apply_row(in, 6, RTE_THRESH_TOZERO_INV, 127, 200, (const uint8_t[]){0, 100, 127, 0, 0, 0});
    /* fractional threshold floors, fractional maxval rounds half to even */
    apply_row(in, 6, RTE_THRESH_BINARY, 127.9, 127.5, (const uint8_t[]){0, 0, 0, 128, 128, 128});
    apply_row(in, 6, RTE_THRESH_BINARY, 99.5, 128.5, (const uint8_t[]){0, 128, 128, 128, 128, 128});
    apply_row(in, 6, RTE_THRESH_BINARY, 0, 300, (const uint8_t[]){0, 255, 255, 255, 255, 255});
    apply_row(in, 6, RTE_THRESH_BINARY, 254, -3, (const uint8_t[]){0, 0, 0, 0, 0, 0});
    apply_row(in, 6, RTE_THRESH_BINARY, 254, 77, (const uint8_t[]){0, 0, 0, 0, 0, 77});
}

static void out_of_range_thresholds_fill_or_copy(void **state)
{
    const uint8_t in[4] = {0, 1, 254, 255};
    const uint8_t zero[4] = {0}, full[4] = {9, 9, 9, 9};
    /* below 0: every pixel is above */
    apply_row(in, 4, RTE_THRESH_BINARY, -0.5, 9, full);
    apply_row(in, 4, RTE_THRESH_BINARY_INV, -1, 9, zero);
    apply_row(in, 4, RTE_THRESH_TRUNC, -1, 9, zero);
    apply_row(in, 4, RTE_THRESH_TOZERO, -300, 9, in);
    apply_row(in, 4, RTE_THRESH_TOZERO_INV, -1, 9, zero);
    /* 255 and above: no pixel is above */
    apply_row(in, 4, RTE_THRESH_BINARY, 255, 9, zero);
    apply_row(in, 4, RTE_THRESH_BINARY_INV, 300, 9, full);
    apply_row(in, 4, RTE_THRESH_TRUNC, 255.5, 9, in);
    apply_row(in, 4, RTE_THRESH_TOZERO, 256, 9, zero);
    apply_row(in, 4, RTE_THRESH_TOZERO_INV, 1e9, 9, in);
}

static void params_follow_opencv_rounding(void **state)
{
    rte_threshold_params p = params(RTE_THRESH_TRUNC, 127.5, 127.5, true);
    assert_int_equal(p.thresh, 127);
    assert_int_equal(p.maxval, 128);
    assert_true(p.otsu);
    p = params(RTE_THRESH_BINARY, -0.0001, 128.5, false);
    assert_int_equal(p.thresh, -1);
    assert_int_equal(p.maxval, 128);
    p = params(RTE_THRESH_BINARY, 300, 300, false);
    assert_int_equal(p.thresh, 300);
    assert_int_equal(p.maxval, 300);
    p = params(RTE_THRESH_BINARY, 2.5, -2.5, false);
    assert_int_equal(p.maxval, -2);

    assert_int_equal(rte_threshold_params_init(&p, RTE_THRESH_BINARY, NAN, 1, false),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_params_init(&p, RTE_THRESH_BINARY, 1, NAN, false),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_params_init(&p, RTE_THRESH_BINARY, 1e12, 1, false),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_params_init(&p, (rte_threshold_type)5, 1, 1, false),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_params_init(NULL, RTE_THRESH_BINARY, 1, 1, false),
                     RTE_ERR_ARGUMENT);
}

static uint8_t reference_pixel(uint8_t v, rte_threshold_type type, int32_t t, int32_t maxval)
{
    int32_t m = maxval < 0 ? 0 : maxval > 255 ? 255 : maxval;
    int above = v > t;
    switch (type) {
    case RTE_THRESH_BINARY: return (uint8_t)(above ? m : 0);
    case RTE_THRESH_BINARY_INV: return (uint8_t)(above ? 0 : m);
    case RTE_THRESH_TRUNC: return (uint8_t)(above ? (t < 0 ? 0 : t) : v);
    case RTE_THRESH_TOZERO: return (uint8_t)(above ? v : 0);
    default: return (uint8_t)(above ? 0 : v);
    }
}

static void random_images_all_widths_and_in_place(void **state)
{
    uint32_t rng = 12345;
    for (int32_t w = 1; w <= 67; w++) {
        int32_t h = 1 + (int32_t)(unit_rand(&rng) % 5);
        rte_image_u8 src = unit_image_u8(w, h, (int32_t)(unit_rand(&rng) % 9), 0);
        rte_image_u8 dst = unit_image_u8(w, h, (int32_t)(unit_rand(&rng) % 9), 0);
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++)
                src.buf[y * src.stride + x] = (uint8_t)unit_rand(&rng);
        for (int32_t type = 0; type <= 4; type++) {
            rte_threshold_params p;
            p.type = (rte_threshold_type)type;
            p.thresh = (int32_t)(unit_rand(&rng) % 300) - 20;
            p.maxval = (int32_t)(unit_rand(&rng) % 300) - 20;
            p.otsu = false;
            assert_int_equal(rte_threshold_u8(&src, &dst, &p, NULL), RTE_OK);
            for (int32_t y = 0; y < h; y++)
                for (int32_t x = 0; x < w; x++)
                    assert_int_equal(
                        dst.buf[y * dst.stride + x],
                        reference_pixel(src.buf[y * src.stride + x], p.type, p.thresh, p.maxval));
            unit_assert_padding_u8(&dst);
            /* in place gives the same */
            rte_image_u8 copy = unit_image_u8(w, h, 2, 0);
            for (int32_t y = 0; y < h; y++)
                memcpy(copy.buf + y * copy.stride, src.buf + y * src.stride, (size_t)w);
            assert_int_equal(rte_threshold_u8(&copy, &copy, &p, NULL), RTE_OK);
            for (int32_t y = 0; y < h; y++)
                assert_memory_equal(copy.buf + y * copy.stride, dst.buf + y * dst.stride,
                                    (size_t)w);
            unit_assert_padding_u8(&copy);
            test_free(copy.buf);
        }
        test_free(src.buf);
        test_free(dst.buf);
    }
}

static void histogram_counts_every_pixel(void **state)
{
    uint32_t rng = 777, hist[256];
    for (int32_t w = 1; w <= 67; w += 3) {
        int32_t h = 1 + w % 7;
        rte_image_u8 img = unit_image_u8(w, h, 4, 0);
        uint32_t want[256] = {0};
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                uint8_t v = (uint8_t)(unit_rand(&rng) % (w < 20 ? 3 : 256));
                img.buf[y * img.stride + x] = v;
                want[v]++;
            }
        assert_int_equal(rte_histogram_u8(&img, hist), RTE_OK);
        assert_memory_equal(hist, want, sizeof want);
        test_free(img.buf);
    }
    rte_image_u8 c = unit_image_u8(1, 1, 0, 255);
    assert_int_equal(rte_histogram_u8(&c, hist), RTE_OK);
    assert_int_equal(hist[255], 1);
    assert_int_equal(hist[0], 0);
    assert_int_equal(rte_histogram_u8(&c, NULL), RTE_ERR_ARGUMENT);
    c.width = 0;
    assert_int_equal(rte_histogram_u8(&c, hist), RTE_ERR_SIZE);
    test_free(c.buf);
}

/* Only pixels under a non-zero mask count: masks of runs (whole 8-byte
 * chunks on, off and mixed) and of scattered values 1..255, odd strides. */
static void masked_histogram_counts_pixels_under_the_mask(void **state)
{
    uint32_t rng = 31337, hist[256];
    for (int32_t w = 1; w <= 67; w++) {
        const int32_t h = 1 + w % 5;
        rte_image_u8 img = unit_image_u8(w, h, 1 + 2 * (w % 3), 0);
        rte_image_u8 mask = unit_image_u8(w, h, 2 + w % 4, 0);
        uint32_t want[256] = {0};
        for (int32_t y = 0; y < h; y++)
            for (int32_t x = 0; x < w; x++) {
                const uint8_t v = (uint8_t)(unit_rand(&rng) % (w < 20 ? 3 : 256));
                const uint32_t r = unit_rand(&rng);
                const uint8_t m = w % 2 ? (uint8_t)(((x / 8 + y) % 3 == 0) ? 0 : 255)
                                        : (uint8_t)(r % 4 == 0 ? 0 : 1 + r % 255);
                img.buf[y * img.stride + x] = v;
                mask.buf[y * mask.stride + x] = m;
                want[v] += m != 0;
            }
        assert_int_equal(rte_histogram_masked_u8(&img, &mask, hist), RTE_OK);
        assert_memory_equal(hist, want, sizeof want);
        test_free(img.buf);
        test_free(mask.buf);
    }
    rte_image_u8 a = unit_image_u8(9, 2, 0, 7), b = unit_image_u8(8, 2, 0, 255);
    assert_int_equal(rte_histogram_masked_u8(&a, &b, hist), RTE_ERR_SIZE);
    assert_int_equal(rte_histogram_masked_u8(&a, NULL, hist), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_histogram_masked_u8(&a, &a, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_histogram_masked_u8(&a, &a, hist), RTE_OK); /* a mask of 7s */
    assert_int_equal(hist[7], 18);
    test_free(a.buf);
    test_free(b.buf);
}

/* Spans of each row, clipped: random spans (some empty, reversed, or
 * reaching past either side) on sizes up to 300 x 40, and the same region
 * as a mask (runs long enough to be counted in quarters). */
static void span_histogram_counts_each_rows_span(void **state)
{
    uint32_t rng = 4242, hist[256], masked[256];
    for (int32_t round = 0; round < 60; round++) {
        const int32_t w = 1 + (int32_t)(unit_rand(&rng) % 300),
                      h = 1 + (int32_t)(unit_rand(&rng) % 40);
        rte_image_u8 img = unit_image_u8(w, h, (int32_t)(unit_rand(&rng) % 9), 0);
        rte_image_u8 mask = unit_image_u8(w, h, 0, 0);
        int32_t x0[40], x1[40];
        uint32_t want[256] = {0};
        for (int32_t y = 0; y < h; y++) {
            x0[y] = (int32_t)(unit_rand(&rng) % (uint32_t)(w + 20)) - 10;
            x1[y] = round % 3 == 0 ? x0[y] - 1
                                   : x0[y] + (int32_t)(unit_rand(&rng) % (uint32_t)(w + 10));
            for (int32_t x = 0; x < w; x++) {
                const uint8_t v = (uint8_t)(unit_rand(&rng) % (round % 2 ? 4 : 256));
                const bool in = x >= x0[y] && x < x1[y];
                img.buf[y * img.stride + x] = v;
                mask.buf[y * mask.stride + x] = in ? 255 : 0;
                want[v] += in;
            }
        }
        assert_int_equal(rte_histogram_spans_u8(&img, x0, x1, hist), RTE_OK);
        assert_memory_equal(hist, want, sizeof want);
        assert_int_equal(rte_histogram_masked_u8(&img, &mask, masked), RTE_OK);
        assert_memory_equal(masked, want, sizeof want);
        test_free(img.buf);
        test_free(mask.buf);
    }
    rte_image_u8 a = unit_image_u8(9, 2, 0, 7);
    const int32_t x0[2] = {0, 4}, x1[2] = {9, 5};
    assert_int_equal(rte_histogram_spans_u8(&a, NULL, x1, hist), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_histogram_spans_u8(&a, x0, NULL, hist), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_histogram_spans_u8(&a, x0, x1, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_histogram_spans_u8(&a, x0, x1, hist), RTE_OK);
    assert_int_equal(hist[7], 10);
    a.width = 0;
    assert_int_equal(rte_histogram_spans_u8(&a, x0, x1, hist), RTE_ERR_SIZE);
    a.width = 9;
    test_free(a.buf);
}

/* OpenCV 4.6's Otsu loop in hardware doubles (the tests may use the FPU). */
static int32_t otsu_double(const uint32_t hist[256])
{
    double total = 0, mu = 0;
    for (int i = 0; i < 256; i++) {
        total += hist[i];
        mu += i * (double)hist[i];
    }
    double scale = 1. / total;
    mu *= scale;
    double mu1 = 0, q1 = 0, max_sigma = 0;
    int32_t best = 0;
    for (int i = 0; i < 256; i++) {
        double p_i = hist[i] * scale, q2, mu2, sigma;
        mu1 *= q1;
        q1 += p_i;
        q2 = 1. - q1;
        if (fmin(q1, q2) < FLT_EPSILON || fmax(q1, q2) > 1. - FLT_EPSILON)
            continue;
        mu1 = (mu1 + i * p_i) / q1;
        mu2 = (mu - q1 * mu1) / q2;
        sigma = q1 * q2 * (mu1 - mu2) * (mu1 - mu2);
        if (sigma > max_sigma) {
            max_sigma = sigma;
            best = i;
        }
    }
    return best;
}

/* Few bins (ties and near-ties: the double replay decides), all bins, and
 * smooth photo-like mixtures (decided in exact integers), with totals on
 * both sides of the 2^22 pixels up to which the integers may decide. */
static void otsu_matches_double_replay_on_adversarial_histograms(void **state)
{
    uint32_t rng = 99;
    for (int n = 0; n < 40000; n++) {
        uint32_t hist[256] = {0};
        int kind = n % 7, bins = kind == 0   ? 2
                                 : kind == 1 ? 3
                                 : kind == 2 ? 1
                                 : kind == 3 ? 6
                                             : 256;
        if (kind >= 5) {
            /* two or three bumps, 10^3 to 2^23 pixels in all */
            const uint32_t scale = 1u << (unit_rand(&rng) % 14);
            for (int bump = 0; bump < 2 + kind % 2; bump++) {
                const int32_t centre = (int32_t)(unit_rand(&rng) % 256),
                              width = 2 + (int32_t)(unit_rand(&rng) % 40);
                const uint32_t height = 1 + unit_rand(&rng) % 1000;
                for (int32_t v = centre - 3 * width; v <= centre + 3 * width; v++)
                    if (v >= 0 && v < 256) {
                        const int32_t dv = v - centre, dist = dv < 0 ? -dv : dv;
                        hist[v] +=
                            height * scale * (uint32_t)(3 * width - dist) / (uint32_t)(3 * width) +
                            unit_rand(&rng) % 8;
                    }
            }
            hist[unit_rand(&rng) % 256] += 1;
        } else {
            for (int b = 0; b < bins; b++) {
                uint32_t v = kind == 0 && b == 0 && n % 3 ? 0
                             : kind == 0 && n % 3         ? 255
                                                          : unit_rand(&rng) % 256;
                hist[v] += 1 + unit_rand(&rng) % (1u << (unit_rand(&rng) % 21));
            }
        }
        int32_t got = -1;
        assert_int_equal(rte_threshold_otsu_histogram(hist, &got), RTE_OK);
        assert_int_equal(got, otsu_double(hist));
    }
}

static void otsu_hand_checked_and_errors(void **state)
{
    uint32_t hist[256] = {0};
    int32_t t = -1;
    assert_int_equal(rte_threshold_otsu_histogram(hist, &t), RTE_ERR_ARGUMENT); /* empty */
    hist[77] = 1000;
    assert_int_equal(rte_threshold_otsu_histogram(hist, &t), RTE_OK);
    assert_int_equal(t, 0); /* constant: every bin skipped */
    /* 10 and 200: the threshold separates them */
    hist[77] = 0;
    hist[10] = 30;
    hist[200] = 70;
    assert_int_equal(rte_threshold_otsu_histogram(hist, &t), RTE_OK);
    assert_true(t >= 10 && t < 200);
    assert_int_equal(t, otsu_double(hist));

    /* an image with Otsu through rte_threshold_u8 */
    rte_image_u8 img = unit_image_u8(10, 10, 3, 10);
    for (int i = 0; i < 70; i++)
        img.buf[(i / 10) * img.stride + i % 10] = 200;
    rte_image_u8 dst = unit_image_u8(10, 10, 1, 0);
    rte_threshold_params p = params(RTE_THRESH_BINARY, 0, 255, true);
    int32_t used = -1;
    assert_int_equal(rte_threshold_u8(&img, &dst, &p, &used), RTE_OK);
    assert_int_equal(used, t);
    for (int i = 0; i < 100; i++)
        assert_int_equal(dst.buf[(i / 10) * dst.stride + i % 10], i < 70 ? 255 : 0);
    unit_assert_padding_u8(&dst);
    int32_t t2 = -1;
    assert_int_equal(rte_threshold_otsu_u8(&img, &t2), RTE_OK);
    assert_int_equal(t2, t);
    assert_int_equal(rte_threshold_otsu_histogram(NULL, &t), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_otsu_histogram(hist, NULL), RTE_ERR_ARGUMENT);
    test_free(img.buf);
    test_free(dst.buf);
}

static uint64_t bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static double from_bits(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static void binary64_emulation_matches_the_fpu(void **state)
{
    uint32_t rng = 4242;
    for (int n = 0; n < 200000; n++) {
        uint64_t a = (uint64_t)unit_rand(&rng) << 32 | unit_rand(&rng);
        uint64_t b = (uint64_t)unit_rand(&rng) << 32 | unit_rand(&rng);
        /* keep exponents near each other (cancellation, rounding ties) or small (subnormals) */
        if (n % 3 == 0)
            b = (a & UINT64_C(0xFFF0000000000000)) | (b & 0xFFFFF);
        if (n % 5 == 0) {
            a &= UINT64_C(0x800FFFFFFFFFFFFF) | ((uint64_t)0x3F << 52);
            b &= UINT64_C(0x800FFFFFFFFFFFFF) | ((uint64_t)0x3F << 52);
        }
        double x = from_bits(a), y = from_bits(b);
        if (isnan(x) || isnan(y) || isinf(x) || isinf(y))
            continue;
        double r[4] = {x + y, x - y, x * y, x / y};
        rte_f64 e[4] = {rte_f64_add(a, b), rte_f64_sub(a, b), rte_f64_mul(a, b), rte_f64_div(a, b)};
        for (int k = 0; k < 4; k++)
            if (!isinf(r[k]) && !isnan(r[k]))
                assert_int_equal(e[k], bits(r[k]));
        assert_int_equal(rte_f64_lt(a, b), x < y);
        uint64_t v = a >> (unit_rand(&rng) % 64);
        assert_int_equal(rte_f64_from_u64(v), bits((double)v));
    }
    assert_int_equal(rte_f64_sub(bits(1.5), bits(1.5)), bits(0.0));
    assert_int_equal(rte_f64_mul(bits(-2.0), 0), bits(-0.0));
}

static void auto_canny_median_rule(void **state)
{
    uint32_t hist[256] = {0};
    int32_t lo = -1, hi = -1;
    hist[10] = hist[20] = hist[30] = hist[40] = 1; /* median 25 */
    assert_int_equal(rte_threshold_auto_canny_median(hist, 330, &lo, &hi), RTE_OK);
    assert_int_equal(lo, 16); /* 0.67 * 25 = 16.75 */
    assert_int_equal(hi, 33); /* 1.33 * 25 = 33.25 */
    memset(hist, 0, sizeof hist);
    hist[100] = 3; /* odd count, median 100 */
    assert_int_equal(rte_threshold_auto_canny_median(hist, 330, &lo, &hi), RTE_OK);
    assert_int_equal(lo, 67);
    assert_int_equal(hi, 133);
    assert_int_equal(rte_threshold_auto_canny_median(hist, 1500, &lo, &hi), RTE_OK);
    assert_int_equal(lo, 0);
    assert_int_equal(hi, 250);
    hist[250] = 4; /* median 250 */
    assert_int_equal(rte_threshold_auto_canny_median(hist, 330, &lo, &hi), RTE_OK);
    assert_int_equal(lo, 167); /* 0.67 * 250 = 167.5 */
    assert_int_equal(hi, 255);
    assert_int_equal(rte_threshold_auto_canny_median(hist, 0, &lo, &hi), RTE_OK);
    assert_int_equal(lo, 250);
    assert_int_equal(hi, 250);
    assert_int_equal(rte_threshold_auto_canny_median(hist, -1, &lo, &hi), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_auto_canny_median(hist, 10001, &lo, &hi), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_auto_canny_median(hist, 330, NULL, &hi), RTE_ERR_ARGUMENT);
    memset(hist, 0, sizeof hist);
    assert_int_equal(rte_threshold_auto_canny_median(hist, 330, &lo, &hi), RTE_ERR_ARGUMENT);
}

static void auto_canny_otsu_rule(void **state)
{
    uint32_t hist[256] = {0};
    hist[20] = 50;
    hist[181] = 50;
    int32_t lo = -1, hi = -1, t = -1;
    assert_int_equal(rte_threshold_auto_canny_otsu(hist, &lo, &hi), RTE_OK);
    assert_int_equal(rte_threshold_otsu_histogram(hist, &t), RTE_OK);
    assert_int_equal(hi, t);
    assert_int_equal(lo, t / 2);
    assert_true(hi >= 20 && hi < 181);
    assert_int_equal(rte_threshold_auto_canny_otsu(hist, NULL, &hi), RTE_ERR_ARGUMENT);
}

static void threshold_argument_errors(void **state)
{
    rte_image_u8 a = unit_image_u8(4, 4, 0, 1), b = unit_image_u8(4, 3, 0, 1);
    rte_threshold_params p = params(RTE_THRESH_BINARY, 1, 2, false);
    assert_int_equal(rte_threshold_u8(&a, &b, &p, NULL), RTE_ERR_SIZE);
    assert_int_equal(rte_threshold_u8(&a, &a, NULL, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_threshold_u8(NULL, &a, &p, NULL), RTE_ERR_ARGUMENT);
    p.type = (rte_threshold_type)7;
    assert_int_equal(rte_threshold_u8(&a, &a, &p, NULL), RTE_ERR_ARGUMENT);
    test_free(a.buf);
    test_free(b.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_type_on_a_hand_checked_row),
        cmocka_unit_test(out_of_range_thresholds_fill_or_copy),
        cmocka_unit_test(params_follow_opencv_rounding),
        cmocka_unit_test(random_images_all_widths_and_in_place),
        cmocka_unit_test(histogram_counts_every_pixel),
        cmocka_unit_test(masked_histogram_counts_pixels_under_the_mask),
        cmocka_unit_test(span_histogram_counts_each_rows_span),
        cmocka_unit_test(otsu_matches_double_replay_on_adversarial_histograms),
        cmocka_unit_test(otsu_hand_checked_and_errors),
        cmocka_unit_test(binary64_emulation_matches_the_fpu),
        cmocka_unit_test(auto_canny_median_rule),
        cmocka_unit_test(auto_canny_otsu_rule),
        cmocka_unit_test(threshold_argument_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
