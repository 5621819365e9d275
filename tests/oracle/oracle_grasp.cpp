// The grasp path against the same pipeline written with OpenCV 4.6 calls:
// GaussianBlur 5x5 -> threshold (Otsu or fixed, side chosen from the border)
// or Canny + morphologyEx(CLOSE, ellipse) -> findContours(EXTERNAL, SIMPLE)
// -> area filter -> sorted by area. The binary image, the kept contours and
// their order must be identical; per object the centroid (Q8), the
// minimum-area box (area, opening, direction) agree within the precision
// shape.h states. Every file input with each mode, random images with one
// mode each, padded strides.
#include "oracle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/grasp.h"
}

namespace
{

struct Mode {
    const char *name;
    rte_grasp_binarize binarize;
    int threshold;
    rte_grasp_polarity polarity;
};

const Mode modes[] = {
    {"otsu-auto", RTE_GRASP_OTSU, 0, RTE_GRASP_AUTO},
    {"fixed-100-dark", RTE_GRASP_FIXED, 100, RTE_GRASP_DARK},
    {"fixed-160-bright", RTE_GRASP_FIXED, 160, RTE_GRASP_BRIGHT},
    {"canny-close", RTE_GRASP_CANNY_CLOSE, 0, RTE_GRASP_AUTO},
};

const int kMinArea = 100, kMaxObjects = 4096; // every object kept: the order is by score

// The border rule of grasp.c: the rounded mean of the outermost rows and
// columns (a one-row image counts its row twice).
int border_mean(const cv::Mat &g)
{
    const int w = g.cols, h = g.rows;
    uint64_t sum = 0, n = 2 * (uint64_t)w;
    for (int x = 0; x < w; x++)
        sum += g.at<uint8_t>(0, x) + g.at<uint8_t>(h - 1, x);
    for (int y = 1; y + 1 < h; y++) {
        sum += g.at<uint8_t>(y, 0) + g.at<uint8_t>(y, w - 1);
        n += 2;
    }
    return (int)((sum + n / 2) / n);
}

cv::Mat opencv_binary(const cv::Mat &gray, const Mode &m)
{
    cv::Mat blurred, bin;
    cv::GaussianBlur(gray, blurred, cv::Size(5, 5), 0);
    if (m.binarize == RTE_GRASP_CANNY_CLOSE) {
        cv::Mat edges;
        cv::Canny(blurred, edges, 50, 150);
        cv::morphologyEx(edges, bin, cv::MORPH_CLOSE,
                         cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)),
                         cv::Point(-1, -1), 2);
        return bin;
    }
    int t = m.threshold;
    if (m.binarize == RTE_GRASP_OTSU)
        t = (int)cv::threshold(blurred, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    bool dark =
        m.polarity == RTE_GRASP_DARK || (m.polarity == RTE_GRASP_AUTO && border_mean(blurred) > t);
    cv::threshold(blurred, bin, t, 255, dark ? cv::THRESH_BINARY_INV : cv::THRESH_BINARY);
    return bin;
}

struct Stats {
    long objects = 0, tol_cases = 0, tol_fail = 0;
    double worst_centre = 0, worst_width = 0, worst_angle = 0, worst_area_rel = 0;
};

void near(oracle::Tally &t, Stats &s, const std::string &what, double e, double a, double tol,
          double &worst)
{
    s.tol_cases++;
    t.cases++;
    worst = std::max(worst, std::fabs(e - a));
    if (!(std::fabs(e - a) <= tol)) {
        s.tol_fail++;
        t.differing++;
        if (s.tol_fail < 20)
            std::fprintf(stderr, "TOL %s: opencv=%.9g rtedge=%.9g (tol %g)\n", what.c_str(), e, a,
                         tol);
    }
}

void run_case(oracle::Tally &t, Stats &s, const std::string &name, const cv::Mat &gray,
              const Mode &m, rte_grasp_ctx *ctx, std::mt19937 &rng)
{
    rte_grasp_params p;
    rte_grasp_get_params(ctx, &p);
    p.binarize = m.binarize;
    p.threshold = m.threshold;
    p.polarity = m.polarity;
    p.min_area = kMinArea;
    p.skip_border = 0; // the reference keeps objects on the border
    p.max_objects = kMaxObjects;
    p.split = 0; // OpenCV's contours are of the binary image as it is
    if (rte_grasp_set_params(ctx, &p) != RTE_OK) {
        t.call_failed(name + " set_params", -1);
        return;
    }
    std::vector<uint8_t> storage;
    rte_image_u8 in = oracle::padded_u8(gray, storage, rng);
    rte_grasp_result r;
    const std::string what = name + " " + m.name;
    rte_status st = rte_grasp_process(ctx, &in, &r);
    if (st != RTE_OK) {
        t.call_failed(what, st);
        return;
    }
    cv::Mat bin = opencv_binary(gray, m);
    t.add(what + " binary", bin, oracle::to_mat(*r.binary));

    std::vector<std::vector<cv::Point>> cs;
    cv::findContours(bin, cs, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    struct Kept {
        int64_t area2;
        int index;
    };
    std::vector<Kept> kept;
    for (int i = 0; i < (int)cs.size(); i++) {
        // contourArea is exact on integer points (a multiple of 0.5)
        const int64_t a2 = (int64_t)std::llround(2 * cv::contourArea(cs[i]));
        if (a2 >= 2 * kMinArea)
            kept.push_back({a2, i});
    }
    std::stable_sort(kept.begin(), kept.end(),
                     [](const Kept &a, const Kept &b) { return a.area2 > b.area2; });
    if ((int)kept.size() > kMaxObjects)
        kept.resize(kMaxObjects);
    std::vector<int> e, a;
    for (const Kept &k : kept) {
        e.push_back((int)k.area2);
        e.push_back(k.index);
    }
    // rtedge orders its objects by grasp score: compare them in OpenCV's
    // order (area, then contour)
    std::vector<int> order(r.n_objects);
    for (int i = 0; i < r.n_objects; i++)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&r](int x, int y) {
        const rte_grasp_object &ox = r.objects[x], &oy = r.objects[y];
        return ox.info.area2 != oy.info.area2 ? ox.info.area2 > oy.info.area2
                                              : ox.contour < oy.contour;
    });
    for (int i : order) {
        a.push_back((int)r.objects[i].info.area2);
        a.push_back(r.objects[i].contour);
    }
    e.push_back(-7); // never empty
    a.push_back(-7);
    t.add(what + " objects (area, contour)", cv::Mat(e, true), cv::Mat(a, true));
    if (e != a)
        return;
    for (int i = 0; i < r.n_objects; i++) {
        const rte_grasp_object &o = r.objects[order[i]];
        const std::vector<cv::Point> &c = cs[kept[i].index];
        const std::string w = what + " #" + std::to_string(i);
        s.objects++;
        // the grasp point is the centroid of the contour's convex hull
        std::vector<cv::Point> hull;
        cv::convexHull(c, hull);
        cv::Moments mo = cv::moments(hull);
        // Q8 centroid: rounding 1/512 plus the Q16 step before it
        near(t, s, w + " cx", mo.m10 / mo.m00, o.x_q8 / 256.0, 0.5 / 256 + 1.0 / 65536,
             s.worst_centre);
        near(t, s, w + " cy", mo.m01 / mo.m00, o.y_q8 / 256.0, 0.5 / 256 + 1.0 / 65536,
             s.worst_centre);
        cv::RotatedRect box = cv::minAreaRect(c);
        const double lo = std::min(box.size.width, box.size.height),
                     hi = std::max(box.size.width, box.size.height);
        // the minimum area is unique; the box is not when areas tie, so the
        // opening and direction are compared where OpenCV's box is clearly
        // the only one (not a square, more than a few pixels)
        // both sides are rounded to Q8 (OpenCV's are float): the product
        // moves by up to (length + width) / 256
        double area_diff = 0;
        near(t, s, w + " box area", lo * hi,
             (o.info.box.length_q8 / 256.0) * (o.info.box.width_q8 / 256.0),
             (lo + hi) / 256 + 1e-5 * lo * hi, area_diff);
        s.worst_area_rel = std::max(s.worst_area_rel, area_diff / std::max(1.0, lo * hi));
        if (hi < 1.05 * lo || lo < 4)
            continue;
        near(t, s, w + " box width", lo, o.info.box.width_q8 / 256.0, 0.02, s.worst_width);
        // OpenCV's long side direction against the box's, mod 180
        cv::Point2f pt[4];
        box.points(pt);
        cv::Point2f d1 = pt[1] - pt[0], d2 = pt[2] - pt[1];
        cv::Point2f longer = std::hypot(d1.x, d1.y) >= std::hypot(d2.x, d2.y) ? d1 : d2;
        double long_deg = std::atan2(longer.y, longer.x) * 180 / CV_PI;
        double diff = std::fmod(std::fabs(long_deg - o.info.box.angle_q16 / 65536.0), 180.0);
        diff = std::min(diff, 180 - diff);
        near(t, s, w + " angle", 0, diff, 0.01, s.worst_angle);
    }
}

} // namespace

int main()
{
    oracle::Tally t("grasp");
    Stats s;
    std::mt19937 rng = oracle::make_rng();
    rte_grasp_config c;
    rte_grasp_config_default(&c);
    c.max_width = 2048;
    c.max_height = 2048;
    c.max_contours = 1 << 20;
    c.max_points = 1 << 23;
    c.max_objects = kMaxObjects;
    rte_grasp_ctx *ctx = nullptr;
    if (rte_grasp_create(&c, &ctx) != RTE_OK) {
        std::fprintf(stderr, "rte_grasp_create failed\n");
        return 1;
    }
    for (const oracle::Input &in : oracle::file_inputs()) {
        if (in.gray.cols > 2048 || in.gray.rows > 2048)
            continue;
        for (const Mode &m : modes)
            run_case(t, s, in.name, in.gray, m, ctx, rng);
    }
    std::vector<oracle::Input> randoms = oracle::random_inputs(rng);
    for (size_t i = 0; i < randoms.size(); i++)
        run_case(t, s, randoms[i].name, randoms[i].gray, modes[i % 4], ctx, rng);
    rte_grasp_destroy(ctx);
    std::printf("grasp: %ld objects compared; largest differences: centre %.5f px, box area %.2e "
                "(relative), opening %.5f px, angle %.5f deg; %ld of %ld tolerance checks failed\n",
                s.objects, s.worst_centre, s.worst_area_rel, s.worst_width, s.worst_angle,
                s.tol_fail, s.tol_cases);
    return t.finish();
}
