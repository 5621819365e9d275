// rte_distance_transform_u8 against cv::distanceTransform (mask 3): L1 and
// C bit-exact, with BORDER_FAR as OpenCV calls it and with BORDER_ZERO as
// OpenCV on the image framed by zeros; CHAMFER34 / 3 within
// [2*sqrt(2)/3, sqrt(10)/3] of DIST_L2 with DIST_MASK_PRECISE (Euclidean).
// Inputs: every file thresholded (Otsu both ways, and at 128), random
// images thresholded at a random level, and 1xN, Nx1, all-zero and all-one
// images.
#include "oracle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/distance.h"
}

namespace
{

const double kLow = 2.0 * std::sqrt(2.0) / 3.0; // 4/3 against sqrt(2) on a diagonal
const double kHigh = std::sqrt(10.0) / 3.0;     // (1 + t/3) / sqrt(1 + t^2) at its peak, t = 1/3

struct Checker {
    oracle::Tally t{"distance"};
    double min_ratio = 10, max_ratio = 0;
    long chamfer_pixels = 0, chamfer_outside = 0;

    // Our result as float32, in a padded u16 destination whose padding must stay.
    cv::Mat run(const cv::Mat &bin, rte_dist_metric metric, rte_dist_border border,
                const std::string &what, std::mt19937 &rng)
    {
        std::vector<uint8_t> sbuf;
        rte_image_u8 src = oracle::padded_u8(bin, sbuf, rng);
        int pad = (int)(rng() % 9);
        std::vector<uint16_t> dbuf((size_t)(bin.cols + pad) * bin.rows, 0xA5A5);
        rte_image_u16 dst = {bin.cols, bin.rows, bin.cols + pad, dbuf.data()};
        int st = rte_distance_transform_u8(&src, &dst, metric, border);
        if (st != RTE_OK) {
            t.call_failed(what, st);
            return cv::Mat();
        }
        for (int y = 0; y < bin.rows; y++)
            for (int x = bin.cols; x < bin.cols + pad; x++)
                if (dbuf[(size_t)y * dst.stride + x] != 0xA5A5) {
                    t.call_failed(what + " (row padding written)", -1);
                    return cv::Mat();
                }
        cv::Mat out;
        cv::Mat(bin.rows, bin.cols, CV_16UC1, dbuf.data(), (size_t)dst.stride * 2)
            .convertTo(out, CV_32F);
        return out;
    }

    void check(const std::string &name, const cv::Mat &bin, std::mt19937 &rng)
    {
        const struct {
            rte_dist_metric metric;
            int cv;
            const char *label;
        } exact[] = {{RTE_DIST_L1, cv::DIST_L1, "L1"}, {RTE_DIST_C, cv::DIST_C, "C"}};
        for (const auto &m : exact) {
            cv::Mat expected;
            cv::distanceTransform(bin, expected, m.cv, 3);
            std::string what = name + " " + m.label;
            cv::Mat got = run(bin, m.metric, RTE_DIST_BORDER_FAR, what, rng);
            if (!got.empty())
                t.add(what, expected, got);
            cv::Mat framed, framed_dist;
            cv::copyMakeBorder(bin, framed, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
            cv::distanceTransform(framed, framed_dist, m.cv, 3);
            got = run(bin, m.metric, RTE_DIST_BORDER_ZERO, what + " zero border", rng);
            if (!got.empty())
                t.add(what + " zero border", framed_dist(cv::Rect(1, 1, bin.cols, bin.rows)), got);
        }
        check_chamfer(name, bin, rng);
    }

    // CHAMFER34 against the Euclidean distance, where OpenCV's is finite
    // (the image has a zero pixel: outside the image is no zero pixel in
    // either).
    void check_chamfer(const std::string &name, const cv::Mat &bin, std::mt19937 &rng)
    {
        if (cv::countNonZero(bin) == (int)bin.total())
            return;
        cv::Mat euclid;
        cv::distanceTransform(bin, euclid, cv::DIST_L2, cv::DIST_MASK_PRECISE);
        std::string what = name + " chamfer34";
        cv::Mat got = run(bin, RTE_DIST_CHAMFER34, RTE_DIST_BORDER_FAR, what, rng);
        if (got.empty())
            return;
        long outside = 0;
        for (int y = 0; y < bin.rows; y++)
            for (int x = 0; x < bin.cols; x++) {
                double e = euclid.at<float>(y, x), c = got.at<float>(y, x) / 3.0;
                if (e == 0 || c == 0) {
                    outside += (e == 0) != (c == 0);
                    continue;
                }
                double r = c / e;
                min_ratio = std::min(min_ratio, r);
                max_ratio = std::max(max_ratio, r);
                chamfer_pixels++;
                outside += r < kLow * (1 - 1e-6) || r > kHigh * (1 + 1e-6);
            }
        t.cases++;
        if (outside)
            std::fprintf(stderr, "DIFF %s: %ld pixels outside the tolerance\n", what.c_str(),
                         outside);
        t.differing += outside;
        chamfer_outside += outside;
    }
};

cv::Mat binary(const cv::Mat &gray, int thresh, int type)
{
    cv::Mat bin;
    cv::threshold(gray, bin, thresh, 255, type);
    return bin;
}

} // namespace

int main()
{
    Checker c;
    std::mt19937 rng = oracle::make_rng();
    for (const auto &in : oracle::file_inputs()) {
        c.check(in.name + " otsu", binary(in.gray, 0, cv::THRESH_BINARY | cv::THRESH_OTSU), rng);
        c.check(in.name + " otsu inv", binary(in.gray, 0, cv::THRESH_BINARY_INV | cv::THRESH_OTSU),
                rng);
        c.check(in.name + " 128", binary(in.gray, 128, cv::THRESH_BINARY), rng);
    }
    for (const auto &in : oracle::random_inputs(rng))
        c.check(in.name, binary(in.gray, (int)(rng() % 256), cv::THRESH_BINARY), rng);
    // Lines, columns, all zero, all one, and sparse zeros in large ones.
    for (int i = 0; i < 40; i++) {
        int n = 1 + (int)(rng() % 3000);
        cv::Mat m(i % 2 ? n : 1, i % 2 ? 1 : n, CV_8UC1);
        cv::RNG cvrng(rng());
        cvrng.fill(m, cv::RNG::UNIFORM, 0, 256);
        m = binary(m, (int)(rng() % 256), cv::THRESH_BINARY);
        c.check("line " + std::to_string(m.cols) + "x" + std::to_string(m.rows), m, rng);
    }
    for (int i = 0; i < 8; i++) {
        int w = 1 + (int)(rng() % 700), h = 1 + (int)(rng() % 500);
        c.check("zeros " + std::to_string(w) + "x" + std::to_string(h),
                cv::Mat::zeros(h, w, CV_8UC1), rng);
        cv::Mat ones(h, w, CV_8UC1, cv::Scalar(1 + rng() % 255));
        c.check("ones " + std::to_string(w) + "x" + std::to_string(h), ones, rng);
        ones.at<uint8_t>((int)(rng() % (unsigned)h), (int)(rng() % (unsigned)w)) = 0;
        c.check("ones with one zero " + std::to_string(w) + "x" + std::to_string(h), ones, rng);
    }
    // The cap: a zero at one end of a long row.
    cv::Mat row(3, 12000, CV_8UC1, cv::Scalar(255));
    row.at<uint8_t>(1, 0) = 0;
    c.check("row 12000 with one zero", row, rng);
    std::printf("chamfer34 / 3 over Euclidean: %.4f .. %.4f over %ld pixels (bound %.4f .. %.4f), "
                "%ld outside\n",
                c.min_ratio, c.max_ratio, c.chamfer_pixels, kLow, kHigh, c.chamfer_outside);
    return c.t.finish();
}
