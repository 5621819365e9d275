// cv::threshold (every type, with and without THRESH_OTSU, fractional and
// out-of-range thresh/maxval), Otsu's threshold on adversarial histograms,
// the histogram (also under a mask, as cv::calcHist), and the automatic
// Canny thresholds against references.
#include "oracle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/threshold.h"
}

static cv::Mat scalar_mat(int v)
{
    cv::Mat m(1, 1, CV_16S);
    m.at<int16_t>(0, 0) = (int16_t)v;
    return m;
}

// One cv::threshold call against rte_threshold_u8: pixels and returned threshold.
static void check_threshold(oracle::Tally &t, const std::string &name, const cv::Mat &gray,
                            double thresh, double maxval, int type, bool otsu, std::mt19937 &rng)
{
    std::string what = name + " type " + std::to_string(type) + (otsu ? "|OTSU" : "") + " thresh " +
                       std::to_string(thresh) + " maxval " + std::to_string(maxval);
    cv::Mat expected;
    double ret = cv::threshold(gray, expected, thresh, maxval, type | (otsu ? cv::THRESH_OTSU : 0));

    rte_threshold_params params;
    int st = rte_threshold_params_init(&params, (rte_threshold_type)type, thresh, maxval, otsu);
    if (st != RTE_OK) {
        t.call_failed(what + " (params)", st);
        return;
    }
    std::vector<uint8_t> sbuf, dbuf;
    rte_image_u8 src = oracle::padded_u8(gray, sbuf, rng);
    int32_t used = -12345;
    if (rng() % 4 == 0) { // in place
        st = rte_threshold_u8(&src, &src, &params, &used);
        if (st != RTE_OK) {
            t.call_failed(what, st);
            return;
        }
        t.add(what + " in place", expected, oracle::to_mat(src));
    } else {
        rte_image_u8 dst = oracle::blank_u8(gray.cols, gray.rows, dbuf, rng);
        st = rte_threshold_u8(&src, &dst, &params, &used);
        if (st != RTE_OK) {
            t.call_failed(what, st);
            return;
        }
        t.add(what, expected, oracle::to_mat(dst));
    }
    t.add(what + " returned threshold", scalar_mat((int)ret), scalar_mat(used));
}

// An image whose histogram is `hist` (a rows x cols rectangle when the
// count allows it; the order of the pixels cannot matter to a histogram,
// so only small images are shuffled).
static cv::Mat image_from_histogram(const std::vector<uint32_t> &hist, std::mt19937 &rng)
{
    size_t n = 0;
    for (uint32_t c : hist)
        n += c;
    std::vector<uint8_t> px;
    px.reserve(n);
    for (int v = 0; v < 256; v++)
        px.insert(px.end(), hist[v], (uint8_t)v);
    if (n < 4096)
        std::shuffle(px.begin(), px.end(), rng);
    int rows = 1;
    for (int r : {7, 5, 3, 2})
        if (n % r == 0 && n / r >= 1) {
            rows = r;
            break;
        }
    cv::Mat m((int)(n / rows), rows, CV_8UC1);
    std::copy(px.begin(), px.end(), m.ptr<uint8_t>());
    return m.t();
}

static uint32_t random_count(std::mt19937 &rng, uint32_t max)
{
    // Log-uniform counts: 1 and large counts equally represented.
    int bits = (int)(rng() % 20);
    uint32_t c = 1u + (uint32_t)(rng() % (1u << bits));
    return std::min(c, max);
}

// Adversarial histograms for Otsu: the double rounding in OpenCV decides
// among (near-)equal between-class variances, most of all across empty bins.
static std::vector<uint32_t> adversarial_histogram(int kind, std::mt19937 &rng)
{
    std::vector<uint32_t> h(256, 0);
    auto v = [&]() { return (int)(rng() % 256); };
    switch (kind) {
    case 0: { // two values, often 0 and 255
        int a = rng() % 3 ? 0 : v(), b = rng() % 3 ? 255 : v();
        h[a] += random_count(rng, 200000);
        h[b] += random_count(rng, 200000);
        break;
    }
    case 1: { // two values with equal counts (exact ties in exact arithmetic)
        uint32_t c = random_count(rng, 100000);
        h[v()] += c;
        h[v()] += c;
        break;
    }
    case 2: // three values
        for (int i = 0; i < 3; i++)
            h[v()] += random_count(rng, 100000);
        break;
    case 3: // constant
        h[v()] = random_count(rng, 300000);
        break;
    case 4: { // sparse: a few bins
        int k = 2 + (int)(rng() % 8);
        for (int i = 0; i < k; i++)
            h[v()] += random_count(rng, 50000);
        break;
    }
    case 5: { // symmetric pairs around a centre
        int c = v(), k = 1 + (int)(rng() % 5);
        uint32_t n = random_count(rng, 40000);
        for (int i = 0; i < k; i++) {
            int d = (int)(rng() % 128);
            if (c - d >= 0 && c + d < 256) {
                h[c - d] += n;
                h[c + d] += n;
            }
        }
        h[c] += 1;
        break;
    }
    case 6: // dense random
        for (int i = 0; i < 256; i++)
            h[i] = (uint32_t)(rng() % 1000);
        break;
    default: { // small images: every count tiny
        int k = 1 + (int)(rng() % 12);
        for (int i = 0; i < k; i++)
            h[v()] += 1 + (uint32_t)(rng() % 3);
        break;
    }
    }
    return h;
}

static void check_otsu_histogram(oracle::Tally &t, const std::string &what,
                                 const std::vector<uint32_t> &h, std::mt19937 &rng)
{
    cv::Mat img = image_from_histogram(h, rng), dst;
    double ret = cv::threshold(img, dst, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    int32_t got = -1;
    int st = rte_threshold_otsu_histogram(h.data(), &got);
    if (st != RTE_OK) {
        t.call_failed(what, st);
        return;
    }
    t.add(what, scalar_mat((int)ret), scalar_mat(got));
}

// numpy's median of the pixels, from a sorted copy (independent of the histogram).
static double numpy_median(const cv::Mat &gray)
{
    std::vector<uint8_t> px;
    for (int y = 0; y < gray.rows; y++)
        px.insert(px.end(), gray.ptr<uint8_t>(y), gray.ptr<uint8_t>(y) + gray.cols);
    size_t n = px.size();
    std::nth_element(px.begin(), px.begin() + n / 2, px.end());
    double hi = px[n / 2];
    if (n % 2)
        return hi;
    double lo = *std::max_element(px.begin(), px.begin() + n / 2);
    return (lo + hi) / 2.0;
}

static void check_auto(oracle::Tally &t, const std::string &name, const cv::Mat &gray,
                       std::mt19937 &rng)
{
    std::vector<uint8_t> sbuf, mbuf;
    rte_image_u8 src = oracle::padded_u8(gray, sbuf, rng);
    // A mask of random values, zero in a random share of 8-pixel runs.
    cv::Mat mask(gray.size(), CV_8UC1);
    cv::randu(mask, 0, 256);
    const uint32_t zero_share = rng() % 4;
    for (int y = 0; y < mask.rows; y++) {
        uint8_t *m = mask.ptr<uint8_t>(y);
        for (int x = 0; x < mask.cols; x += 8)
            if (rng() % 4 < zero_share)
                std::fill(m + x, m + std::min(x + 8, mask.cols), 0);
    }
    rte_image_u8 rmask = oracle::padded_u8(mask, mbuf, rng);
    uint32_t hist[256];
    for (bool masked : {true, false}) {
        int st =
            masked ? rte_histogram_masked_u8(&src, &rmask, hist) : rte_histogram_u8(&src, hist);
        if (st != RTE_OK) {
            t.call_failed(name + (masked ? " masked histogram" : " histogram"), st);
            return;
        }
        cv::Mat cvhist;
        int channels[] = {0}, bins[] = {256};
        float range[] = {0, 256};
        const float *ranges[] = {range};
        cv::calcHist(&gray, 1, channels, masked ? mask : cv::Mat(), cvhist, 1, bins, ranges);
        cv::Mat ours(256, 1, CV_32F);
        for (int i = 0; i < 256; i++)
            ours.at<float>(i) = (float)hist[i];
        cv::Mat hist_ne;
        cv::compare(cvhist, ours, hist_ne, cv::CMP_NE);
        t.cases++;
        t.differing += cv::countNonZero(hist_ne);
    }
    // A span of each row (some empty or reaching past the sides) against
    // calcHist under the mask of those spans.
    std::vector<int32_t> x0(gray.rows), x1(gray.rows);
    cv::Mat span_mask = cv::Mat::zeros(gray.size(), CV_8UC1);
    for (int y = 0; y < gray.rows; y++) {
        x0[y] = (int32_t)(rng() % (uint32_t)(gray.cols + 8)) - 4;
        x1[y] = x0[y] + (int32_t)(rng() % (uint32_t)(gray.cols + 8)) - 2;
        const int a = std::clamp(x0[y], 0, gray.cols), b = std::clamp(x1[y], 0, gray.cols);
        if (b > a)
            span_mask.row(y).colRange(a, b).setTo(255);
    }
    uint32_t span_hist[256]; // hist stays the whole image's, for the rules below
    if (int st = rte_histogram_spans_u8(&src, x0.data(), x1.data(), span_hist); st != RTE_OK) {
        t.call_failed(name + " span histogram", st);
        return;
    }
    {
        cv::Mat cvhist;
        int channels[] = {0}, bins[] = {256};
        float range[] = {0, 256};
        const float *ranges[] = {range};
        cv::calcHist(&gray, 1, channels, span_mask, cvhist, 1, bins, ranges);
        int differing = 0;
        for (int i = 0; i < 256; i++)
            differing += cvhist.at<float>(i) != (float)span_hist[i];
        t.cases++;
        t.differing += differing;
    }
    int st = RTE_OK;

    double med = numpy_median(gray);
    // The recipe with s = 0.33 literally, in double: int(max(0, (1 - s) * m)).
    const int sigmas[] = {RTE_AUTO_CANNY_SIGMA_PERMILLE, 0, 100, 250, 500, 999, 1000, 1500,
                          (int)(rng() % 10001)};
    for (int s : sigmas) {
        int32_t lo = -1, hi = -1;
        st = rte_threshold_auto_canny_median(hist, s, &lo, &hi);
        if (st != RTE_OK) {
            t.call_failed(name + " auto median", st);
            continue;
        }
        // Reference in double: (1000 -/+ s) * m is exact and one division by
        // 1000 cannot cross an integer (the quotient is a multiple of 1/2000).
        int rlo = (int)std::max(0.0, std::floor((1000.0 - s) * med / 1000.0));
        int rhi = (int)std::min(255.0, std::floor((1000.0 + s) * med / 1000.0));
        if (s == 330) { // also the popular recipe itself, literally
            double sd = 0.33;
            rlo = (int)std::max(0.0, (1.0 - sd) * med);
            rhi = (int)std::min(255.0, (1.0 + sd) * med);
        }
        std::string what = name + " auto median s=" + std::to_string(s);
        t.add(what + " low", scalar_mat(rlo), scalar_mat(lo));
        t.add(what + " high", scalar_mat(rhi), scalar_mat(hi));
    }
    int32_t lo = -1, hi = -1;
    st = rte_threshold_auto_canny_otsu(hist, &lo, &hi);
    if (st != RTE_OK) {
        t.call_failed(name + " auto otsu", st);
        return;
    }
    cv::Mat dst;
    double otsu = cv::threshold(gray, dst, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    t.add(name + " auto otsu high", scalar_mat((int)otsu), scalar_mat(hi));
    t.add(name + " auto otsu low", scalar_mat((int)std::floor(otsu * 0.5)), scalar_mat(lo));
}

int main()
{
    oracle::Tally t("threshold");
    std::mt19937 rng = oracle::make_rng();
    const double threshes[] = {0,     1,   64,  127, 127.5,   128.49, 200, 254,
                               254.9, 255, 256, 300, -0.0001, -0.5,   -1,  -300};
    const double maxvals[] = {255, 0, 1, 127.5, 128.5, 200.2, 254.5, 255.5, 300, -3};

    for (const auto &in : oracle::file_inputs()) {
        for (int type = 0; type <= 4; type++) {
            for (double th : threshes)
                check_threshold(t, in.name, in.gray, th, maxvals[rng() % 10], type, false, rng);
            for (double mv : maxvals)
                check_threshold(t, in.name, in.gray, 127.5, mv, type, false, rng);
            for (double mv : {255.0, 127.5, 300.0, -3.0})
                check_threshold(t, in.name, in.gray, 0, mv, type, true, rng);
        }
        check_auto(t, in.name, in.gray, rng);
    }

    for (const auto &in : oracle::random_inputs(rng)) {
        for (int rep = 0; rep < 3; rep++) {
            int type = (int)(rng() % 5);
            double th = (double)(int)(rng() % 600) / 2.0 - 20.0;
            double mv = (double)(int)(rng() % 700) / 2.0 - 20.0;
            check_threshold(t, in.name, in.gray, th, mv, type, rep == 2, rng);
        }
        check_auto(t, in.name, in.gray, rng);
    }

    // Adversarial histograms for Otsu (and a few beyond 2^23 pixels, where
    // single-pixel bins fall under FLT_EPSILON).
    for (int i = 0; i < 24000; i++) {
        int kind = i % 8;
        check_otsu_histogram(
            t, "otsu histogram #" + std::to_string(i) + " kind " + std::to_string(kind),
            adversarial_histogram(kind, rng), rng);
    }
    for (int i = 0; i < 4; i++) {
        std::vector<uint32_t> h(256, 0);
        h[rng() % 256] += 1;
        h[rng() % 256] += 9000000;
        h[rng() % 256] += (uint32_t)(rng() % 3);
        h[rng() % 256] += (uint32_t)(rng() % 8000000);
        check_otsu_histogram(t, "otsu large histogram #" + std::to_string(i), h, rng);
    }
    return t.finish();
}
