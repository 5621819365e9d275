// Canny against OpenCV 4.6: apertures 3 and 5 (and 7), L1 and L2, threshold pairs
// (swapped, zero, negative, fractional, very high) on every file image;
// random parameters on the random images; Canny from given dx/dy, including
// full-range random derivatives; the fused front end (rte_canny_blurred_u8)
// against cv::GaussianBlur then cv::Canny; Canny that hands out its
// derivatives (rte_canny_gradient_u8) against cv::Sobel with BORDER_REPLICATE
// then cv::Canny(dx, dy), all three outputs.
#include "oracle.hpp"

#include <cstdio>
#include <string>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/canny.h"
}

namespace
{

std::string describe(double lo, double hi, int ap, bool l2)
{
    char b[128];
    std::snprintf(b, sizeof b, " canny(%g, %g, ap=%d, %s)", lo, hi, ap, l2 ? "L2" : "L1");
    return b;
}

// cv::Canny of gray, or with ksize > 0 of cv::GaussianBlur(gray, ksize,
// sigma) against the fused rte_canny_blurred_u8.
void check(oracle::Tally &t, const std::string &name, const cv::Mat &gray, double lo, double hi,
           int ap, bool l2, rte_arena *arena, std::mt19937 &rng, int ksize = 0, double sigma = 0)
{
    std::string what = name + describe(lo, hi, ap, l2);
    cv::Mat blurred, expected;
    rte_gaussian_kernel k;
    rte_canny_params p;
    rte_status st = rte_canny_params_init(&p, lo, hi, ap, l2);
    if (ksize > 0) {
        char b[64];
        std::snprintf(b, sizeof b, " blurred(%d, %g)", ksize, sigma);
        what += b;
        cv::GaussianBlur(gray, blurred, cv::Size(ksize, ksize), sigma);
        if (st == RTE_OK)
            st = rte_gaussian_kernel_init(&k, ksize, ksize, sigma, sigma);
    }
    cv::Canny(ksize > 0 ? blurred : gray, expected, lo, hi, ap, l2);
    if (st != RTE_OK) {
        t.call_failed(what + " (params)", st);
        return;
    }
    std::vector<uint8_t> sbuf, dbuf;
    rte_image_u8 src = oracle::padded_u8(gray, sbuf, rng);
    rte_image_u8 dst = oracle::blank_u8(gray.cols, gray.rows, dbuf, rng);
    size_t mark = rte_arena_mark(arena);
    st = ksize > 0 ? rte_canny_blurred_u8(&src, &dst, &k, &p, arena)
                   : rte_canny_u8(&src, &dst, &p, arena);
    t.check(what, st, arena, mark, expected, dst);
}

rte_image_s16 padded_s16(const cv::Mat &m, std::vector<int16_t> &storage, std::mt19937 &rng)
{
    rte_image_s16 img = oracle::blank_s16(m.cols, m.rows, storage, rng);
    for (int y = 0; y < m.rows; y++)
        std::copy(m.ptr<int16_t>(y), m.ptr<int16_t>(y) + m.cols, img.buf + (size_t)y * img.stride);
    return img;
}

void check_gradient(oracle::Tally &t, const std::string &name, const cv::Mat &dx, const cv::Mat &dy,
                    double lo, double hi, bool l2, rte_arena *arena, std::mt19937 &rng)
{
    std::string what = name + " from dx/dy" + describe(lo, hi, 0, l2);
    cv::Mat expected;
    cv::Canny(dx, dy, expected, lo, hi, l2);
    rte_canny_params p;
    rte_status st = rte_canny_params_init(&p, lo, hi, 3, l2);
    if (st != RTE_OK) {
        t.call_failed(what + " (params)", st);
        return;
    }
    std::vector<int16_t> xbuf, ybuf;
    std::vector<uint8_t> dbuf;
    rte_image_s16 gx = padded_s16(dx, xbuf, rng), gy = padded_s16(dy, ybuf, rng);
    rte_image_u8 dst = oracle::blank_u8(dx.cols, dx.rows, dbuf, rng);
    st = rte_canny_from_gradient_u8(&gx, &gy, &dst, &p, arena);
    if (st != RTE_OK) {
        t.call_failed(what, st);
        return;
    }
    t.add(what, expected, oracle::to_mat(dst));
}

// rte_canny_gradient_u8 against what cv::HoughCircles computes inside:
// cv::Sobel (BORDER_REPLICATE) then cv::Canny(dx, dy); edges, dx and dy.
void check_handing_out(oracle::Tally &t, const std::string &name, const cv::Mat &gray, double lo,
                       double hi, int ap, bool l2, rte_arena *arena, std::mt19937 &rng)
{
    std::string what = name + " with its derivatives" + describe(lo, hi, ap, l2);
    cv::Mat dx, dy, expected;
    cv::Sobel(gray, dx, CV_16S, 1, 0, ap, 1, 0, cv::BORDER_REPLICATE);
    cv::Sobel(gray, dy, CV_16S, 0, 1, ap, 1, 0, cv::BORDER_REPLICATE);
    cv::Canny(dx, dy, expected, lo, hi, l2);
    rte_canny_params p;
    rte_status st = rte_canny_params_init(&p, lo, hi, ap, l2);
    if (st != RTE_OK) {
        t.call_failed(what + " (params)", st);
        return;
    }
    std::vector<uint8_t> sbuf, dbuf;
    std::vector<int16_t> xbuf, ybuf;
    rte_image_u8 src = oracle::padded_u8(gray, sbuf, rng);
    rte_image_u8 dst = oracle::blank_u8(gray.cols, gray.rows, dbuf, rng);
    rte_image_s16 gx = oracle::blank_s16(gray.cols, gray.rows, xbuf, rng);
    rte_image_s16 gy = oracle::blank_s16(gray.cols, gray.rows, ybuf, rng);
    size_t mark = rte_arena_mark(arena);
    st = rte_canny_gradient_u8(&src, &dst, &gx, &gy, &p, arena);
    t.check(what, st, arena, mark, expected, dst);
    if (st != RTE_OK)
        return;
    t.add(what + " dx", dx, oracle::to_mat(gx));
    t.add(what + " dy", dy, oracle::to_mat(gy));
}

double random_threshold(std::mt19937 &rng)
{
    switch (rng() % 6) {
    case 0: return 0;
    case 1: return (double)(rng() % 2000) / 7.0; // fractional
    case 2: return (double)(rng() % 60000);      // beyond any aperture-3 magnitude
    case 3: return -(double)(rng() % 50);
    default: return (double)(rng() % 400);
    }
}

} // namespace

int main()
{
    cv::setNumThreads(1);
    oracle::Tally t("canny");
    std::mt19937 rng = oracle::make_rng();
    rte_gaussian_kernel largest;
    rte_gaussian_kernel_init(&largest, 9, 9, 0, 0);
    oracle::Arena scratch(rte_canny_blurred_scratch_size(1280, 720, &largest, 7));

    // (low, high): ordinary, swapped, zero, negative, fractional, equal,
    // above every magnitude, and beyond int32 (OpenCV's x86-64 floor wraps).
    const double pairs[][2] = {{50, 150},     {200, 60},     {0, 0},
                               {-5, 100},     {20.5, 60.75}, {100.9, 100.2},
                               {1000, 30000}, {100, 1e10},   {-1e10, 100}};
    for (const oracle::Input &in : oracle::file_inputs()) {
        if ((size_t)in.gray.cols > 1280 || in.gray.rows > 720) {
            t.call_failed(in.name + " (larger than the test arena)", -1);
            continue;
        }
        for (int ap : {3, 5})
            for (bool l2 : {false, true})
                for (const auto &pr : pairs)
                    check(t, in.name, in.gray, pr[0], pr[1], ap, l2, &scratch.arena, rng);
        // Aperture 7 (offered, not promised: OpenCV's float path).
        for (bool l2 : {false, true}) {
            check(t, in.name, in.gray, 400, 1200, 7, l2, &scratch.arena, rng);
            check(t, in.name, in.gray, 2000.5, 900, 7, l2, &scratch.arena, rng);
        }
        // Fused front end: the lane and grasp settings, other kernels and apertures.
        check(t, in.name, in.gray, 50, 150, 3, false, &scratch.arena, rng, 5, 0);
        check(t, in.name, in.gray, 0, 0, 3, false, &scratch.arena, rng, 3, 0);
        check(t, in.name, in.gray, 200, 60, 3, false, &scratch.arena, rng, 9, 2.5);
        check(t, in.name, in.gray, 60, 180, 5, true, &scratch.arena, rng, 7, 0);
        cv::Mat dx, dy;
        cv::Sobel(in.gray, dx, CV_16S, 1, 0, 3);
        cv::Sobel(in.gray, dy, CV_16S, 0, 1, 3);
        check_gradient(t, in.name + " sobel3", dx, dy, 40, 120, false, &scratch.arena, rng);
        check_gradient(t, in.name + " sobel3", dx, dy, 120.5, 40, true, &scratch.arena, rng);
        check_handing_out(t, in.name, in.gray, 50, 100, 3, false, &scratch.arena, rng);
        check_handing_out(t, in.name, in.gray, 200, 60, 5, true, &scratch.arena, rng);
    }

    for (const oracle::Input &in : oracle::random_inputs(rng)) {
        int ap = 3 + 2 * (int)(rng() % 3);
        bool l2 = rng() & 1;
        double lo = random_threshold(rng), hi = random_threshold(rng);
        if (ap >= 5 && (rng() & 1)) { // aperture-5 magnitudes reach 48960
            lo *= 8;
            hi *= 8;
        }
        check(t, in.name, in.gray, lo, hi, ap, l2, &scratch.arena, rng);
        check(t, in.name, in.gray, lo, hi, ap, l2, &scratch.arena, rng, 1 + 2 * (int)(rng() % 5),
              (rng() % 3) * 0.7);
        if (ap < 7)
            check_handing_out(t, in.name, in.gray, lo, hi, ap, l2, &scratch.arena, rng);
        // Full-range derivatives: the wrapped L2 sum and sector test.
        cv::Mat dx(in.gray.rows, in.gray.cols, CV_16S), dy(in.gray.rows, in.gray.cols, CV_16S);
        if (rng() & 1) {
            cv::randu(dx, -32768, 32768);
            cv::randu(dy, -32768, 32768);
            if (l2) {
                dx.at<int16_t>(0, 0) = dy.at<int16_t>(0, 0) = -32768;
            } else {
                // OpenCV's vector L1 magnitude takes |-32768| as -32768 in
                // its SIMD lanes (but 32768 in its scalar tail); rtedge uses
                // 32768 everywhere (documented in canny.h).
                cv::max(dx, -32767, dx);
                cv::max(dy, -32767, dy);
            }
            check_gradient(t, in.name + " random", dx, dy, lo * 100, hi * 100, l2, &scratch.arena,
                           rng);
        } else {
            cv::Sobel(in.gray, dx, CV_16S, 1, 0, 5, 1, 0, cv::BORDER_REFLECT);
            cv::Sobel(in.gray, dy, CV_16S, 0, 1, 5, 1, 0, cv::BORDER_REFLECT);
            check_gradient(t, in.name + " sobel5", dx, dy, lo * 8, hi * 8, l2, &scratch.arena, rng);
        }
    }
    return t.finish();
}
