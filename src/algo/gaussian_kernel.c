/* Configuration-time half of the Gaussian blur: the Q8 taps OpenCV 4.6 uses
 * for 8-bit images (getGaussianKernelBitExact + getGaussianKernelFixedPoint_ED
 * in modules/imgproc/src/smooth.dispatch.cpp). This file may use floating
 * point; the per-frame code in gaussian.c never does.
 *
 * OpenCV computes the kernel in software double precision (softdouble). Its
 * +, -, *, / and fused multiply-add are IEEE-754 double operations, so plain
 * doubles give the same bits as long as the compiler does not contract
 * a * b + c into an fma on its own: the project builds as ISO C11, where GCC
 * and Clang keep -ffp-contract=off. The one place that can differ is exp():
 * OpenCV uses its own softfloat exp, we use libm's. The two agree to the last
 * bit or nearly so, and a one-ulp difference could only change a tap when
 * 256 * tap + diffused error lands within an ulp of a half-integer; the
 * oracle test sweeps a dense grid of sigmas for every size to check this.
 *
 * Within the sizes supported here OpenCV 4.6 always takes its bit-exact path
 * for a whole 8-bit image (any sigma, including huge ones), so no sigma is
 * refused except NaN and infinity. */
#include <math.h>

#include "rtedge/blur.h"

/* The fixed tables OpenCV uses for sigma <= 0 and sizes up to 9, already in
 * Q8 (they are exact multiples of 1/256, so error diffusion leaves them). */
static const uint16_t fixed_3[3] = {64, 128, 64};
static const uint16_t fixed_5[5] = {16, 64, 96, 64, 16};
static const uint16_t fixed_7[7] = {8, 28, 56, 72, 56, 28, 8};
static const uint16_t fixed_9[9] = {4, 13, 30, 51, 60, 51, 30, 13, 4};

static void fixed_taps(uint16_t *taps, int32_t n, const uint16_t *table)
{
    for (int32_t i = 0; i < n; i++)
        taps[i] = table[i];
}

/* One axis: n odd in 1..RTE_GAUSSIAN_MAX_KSIZE, sigma >= 0. */
static void axis_taps(uint16_t *taps, int32_t n, double sigma)
{
    if (sigma <= 0.0) {
        switch (n) {
        case 1: taps[0] = 256; return;
        case 3: fixed_taps(taps, n, fixed_3); return;
        case 5: fixed_taps(taps, n, fixed_5); return;
        case 7: fixed_taps(taps, n, fixed_7); return;
        case 9: fixed_taps(taps, n, fixed_9); return;
        default: break;
        }
        /* ((n - 1) * 0.5 - 1) * 0.3 + 0.8, written as OpenCV's single fma */
        sigma = fma((double)n, 0.15, 0.35);
    }
    const double scale = -0.125 / (sigma * sigma);
    const int32_t half = n / 2;
    double values[RTE_GAUSSIAN_MAX_KSIZE / 2 + 1];
    double sum = 0.0;
    for (int32_t i = 0, x = 1 - n; i < half; i++, x += 2) {
        values[i] = exp((double)(x * x) * scale);
        sum += values[i];
    }
    sum = sum * 2.0 + 1.0; /* the centre tap is exp(0) */
    const double inv_sum = 1.0 / sum;

    /* Error diffusion from the outside in; the centre takes what is left so
     * the taps sum to exactly 256. Rounding is half-to-even as cvRound. */
    double err = 0.0;
    int32_t side_sum = 0;
    for (int32_t i = 0; i < half; i++) {
        double adjusted = values[i] * inv_sum * 256.0 + err;
        double rounded = nearbyint(adjusted);
        err = adjusted - rounded;
        taps[i] = taps[n - 1 - i] = (uint16_t)rounded;
        side_sum += (int32_t)rounded;
    }
    taps[half] = (uint16_t)(256 - 2 * side_sum);
}

/* OpenCV's automatic size for 8-bit images: cvRound(sigma * 3 * 2 + 1) | 1,
 * 0 when it exceeds what rtedge supports. */
static int32_t size_from_sigma(double sigma)
{
    double v = sigma * 3.0 * 2.0 + 1.0;
    if (v > (double)RTE_GAUSSIAN_MAX_KSIZE + 1.0)
        return 0;
    return (int32_t)nearbyint(v) | 1;
}

/* Size 0 means "from sigma", which needs a positive sigma. */
static rte_status resolve_size(int32_t *ksize, double sigma)
{
    if (*ksize != 0)
        return RTE_OK;
    if (sigma <= 0.0)
        return RTE_ERR_ARGUMENT;
    *ksize = size_from_sigma(sigma);
    return *ksize == 0 ? RTE_ERR_UNSUPPORTED : RTE_OK;
}

static int valid_size(int32_t k) { return k >= 1 && k <= RTE_GAUSSIAN_MAX_KSIZE && (k & 1) == 1; }

rte_status rte_gaussian_kernel_init(rte_gaussian_kernel *kernel, int32_t ksize_x, int32_t ksize_y,
                                    double sigma_x, double sigma_y)
{
    if (!kernel || !isfinite(sigma_x) || !isfinite(sigma_y))
        return RTE_ERR_ARGUMENT;
    if (sigma_y <= 0.0)
        sigma_y = sigma_x;
    if (ksize_x < 0 || ksize_y < 0)
        return RTE_ERR_ARGUMENT;
    rte_status st = resolve_size(&ksize_x, sigma_x);
    if (st == RTE_OK)
        st = resolve_size(&ksize_y, sigma_y);
    if (st != RTE_OK)
        return st;
    if ((ksize_x & 1) == 0 || (ksize_y & 1) == 0)
        return RTE_ERR_ARGUMENT;
    if (!valid_size(ksize_x) || !valid_size(ksize_y))
        return RTE_ERR_UNSUPPORTED;

    rte_gaussian_kernel k = {ksize_x, ksize_y, {0}, {0}};
    axis_taps(k.taps_x, ksize_x, sigma_x > 0.0 ? sigma_x : 0.0);
    axis_taps(k.taps_y, ksize_y, sigma_y > 0.0 ? sigma_y : 0.0);
    *kernel = k;
    return RTE_OK;
}
