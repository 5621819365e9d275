// Oracle for the blur family: rte_gaussian_blur_u8 against cv::GaussianBlur
// and rte_median_blur_u8 against cv::medianBlur, pixel for pixel.
//  1. Kernel sweep: every size (and size 0) against a dense grid of sigmas on
//     small images, so any tap that differs from OpenCV's shows up.
//  2. Every file input: every ksize 1..15 with sigma 0 and several sigmas,
//     ksize 0 from sigma, asymmetric sizes and sigmas, median 3 and 5.
//  3. The random inputs with random parameters, padded strides, in place.
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "oracle.hpp"

extern "C" {
#include "rtedge/arena.h"
#include "rtedge/blur.h"
}

namespace
{

struct Gauss {
    int kx, ky;
    double sx, sy;
};

std::string describe(const Gauss &g)
{
    char s[96];
    std::snprintf(s, sizeof s, "gaussian (%d,%d) sigma (%.6g,%.6g)", g.kx, g.ky, g.sx, g.sy);
    return s;
}

// The whole destination rows, padding included: the padding must still hold
// blank_u8's fill (0xA5), so a kernel writing past the width shows up.
cv::Mat with_padding(const cv::Mat &expected, int stride)
{
    cv::Mat m(expected.rows, stride, CV_8UC1, cv::Scalar(0xA5));
    expected.copyTo(m(cv::Rect(0, 0, expected.cols, expected.rows)));
    return m;
}

struct Runner {
    oracle::Tally &tally;
    std::mt19937 &rng;
    oracle::Arena scratch;

    Runner(oracle::Tally &t, std::mt19937 &r) : tally(t), rng(r)
    {
        // Sized once for the largest image, as a daemon would.
        rte_gaussian_kernel worst;
        rte_gaussian_kernel_init(&worst, 15, 15, 0, 0);
        size_t need = std::max(rte_gaussian_blur_u8_scratch_size(1280, 720, &worst),
                               rte_median_blur_u8_scratch_size(1280, 720, 5));
        scratch.reserve(need);
    }

    void check(const std::string &what, const cv::Mat &expected, const rte_image_u8 &dst)
    {
        rte_image_u8 whole = dst;
        whole.width = dst.stride;
        tally.add(what, with_padding(expected, dst.stride), oracle::to_mat(whole));
    }

    // Runs `blur(src view, dst view)` on a padded copy of the input, writing
    // to a padded blank destination or (in_place) over the copy itself.
    template <class Blur>
    void compare(const std::string &what, const cv::Mat &src, const cv::Mat &expected,
                 bool in_place, Blur blur)
    {
        std::vector<uint8_t> s_mem, d_mem;
        rte_image_u8 s = oracle::padded_u8(src, s_mem, rng);
        rte_image_u8 d = in_place ? s : oracle::blank_u8(src.cols, src.rows, d_mem, rng);
        rte_status st = blur(&s, &d);
        if (st != RTE_OK || scratch.arena.used != 0) {
            tally.call_failed(what, st != RTE_OK ? st : -1);
            return;
        }
        if (in_place)
            tally.add(what, expected, oracle::to_mat(d));
        else
            check(what, expected, d);
    }

    void gaussian(const std::string &name, const cv::Mat &src, const Gauss &g,
                  bool in_place = false)
    {
        std::string what = name + " " + describe(g) + (in_place ? " in place" : "");
        rte_gaussian_kernel k;
        rte_status st = rte_gaussian_kernel_init(&k, g.kx, g.ky, g.sx, g.sy);
        if (st != RTE_OK) {
            tally.call_failed(what + " (kernel)", st);
            return;
        }
        cv::Mat expected;
        cv::GaussianBlur(src, expected, cv::Size(g.kx, g.ky), g.sx, g.sy);
        compare(what, src, expected, in_place, [&](const rte_image_u8 *s, rte_image_u8 *d) {
            return rte_gaussian_blur_u8(s, d, &k, &scratch.arena);
        });
    }

    void median(const std::string &name, const cv::Mat &src, int ksize, bool in_place = false)
    {
        std::string what =
            name + " median " + std::to_string(ksize) + (in_place ? " in place" : "");
        cv::Mat expected;
        cv::medianBlur(src, expected, ksize);
        compare(what, src, expected, in_place, [&](const rte_image_u8 *s, rte_image_u8 *d) {
            return rte_median_blur_u8(s, d, ksize, &scratch.arena);
        });
    }
};

// OpenCV's automatic size for 8-bit images, to keep random parameters inside
// the supported range.
int auto_size(double sigma) { return cvRound(sigma * 6 + 1) | 1; }

} // namespace

int main()
{
    oracle::Tally tally("blur");
    std::mt19937 rng = oracle::make_rng();
    Runner run(tally, rng);

    // 1. Kernel sweep. A random image and an impulse, blurred along one axis
    // at a time: a single differing tap changes some output pixel.
    cv::Mat noise(3, 61, CV_8UC1), impulse = cv::Mat::zeros(3, 31, CV_8UC1);
    cv::RNG(7).fill(noise, cv::RNG::UNIFORM, 0, 256);
    impulse.at<uint8_t>(1, 15) = 255;
    for (int k = 0; k <= 15; k += (k == 0 ? 1 : 2)) {
        for (int i = 0; i <= 1200; i++) {
            double sigma = i == 0 ? 0.0 : 0.01 * i * (i > 800 ? 1.0 + (i - 800) * 0.05 : 1.0);
            if (k == 0 && (sigma <= 0 || auto_size(sigma) > 15))
                continue;
            run.gaussian("sweep noise", noise, Gauss{k, 1, sigma, 0});
            run.gaussian("sweep impulse", impulse.t(), Gauss{1, k, 0, sigma});
        }
    }

    // 2. File inputs: every parameter family.
    std::vector<Gauss> file_cases;
    for (int k = 1; k <= 15; k += 2)
        file_cases.push_back({k, k, 0, 0});
    for (int k = 3; k <= 15; k += 2)
        for (double s : {0.6, 1.2, 2.5, 5.0})
            file_cases.push_back({k, k, s, s});
    for (double s : {0.3, 0.8, 1.5, 2.2})
        file_cases.push_back({0, 0, s, 0});
    for (Gauss g : {Gauss{3, 9, 0, 0}, Gauss{15, 5, 0, 0}, Gauss{1, 7, 0, 0}, Gauss{13, 1, 2.0, 0},
                    Gauss{7, 11, 1.1, 2.3}, Gauss{0, 0, 0.7, 1.9}, Gauss{5, 0, 1.0, 1.3},
                    Gauss{11, 11, 0, 1.6}})
        file_cases.push_back(g);
    for (const oracle::Input &in : oracle::file_inputs()) {
        for (const Gauss &g : file_cases)
            run.gaussian(in.name, in.gray, g);
        run.gaussian(in.name, in.gray, Gauss{5, 5, 0, 0}, true);
        for (int k : {3, 5})
            run.median(in.name, in.gray, k);
        run.median(in.name, in.gray, 5, true);
    }

    // 3. Random inputs, random parameters.
    std::uniform_int_distribution<int> size_pick(0, 8), coin(0, 3);
    std::uniform_real_distribution<double> sigma_pick(0.05, 4.0);
    for (const oracle::Input &in : oracle::random_inputs(rng)) {
        for (int rep = 0; rep < 2; rep++) {
            Gauss g;
            g.kx = 2 * size_pick(rng) - 1; // -1 stands for 0 (size from sigma)
            g.ky = 2 * size_pick(rng) - 1;
            g.sx = coin(rng) == 0 ? 0.0 : sigma_pick(rng);
            g.sy = coin(rng) == 0 ? 0.0 : sigma_pick(rng);
            double sy = g.sy > 0 ? g.sy : g.sx;
            if (g.kx < 0)
                g.kx = g.sx > 0 && auto_size(g.sx) <= 15 ? 0 : 3;
            if (g.ky < 0)
                g.ky = sy > 0 && auto_size(sy) <= 15 ? 0 : 5;
            run.gaussian(in.name, in.gray, g, rep == 1);
        }
        run.median(in.name, in.gray, 3 + 2 * (int)(rng() & 1), (rng() & 3) == 0);
    }
    return tally.finish();
}
