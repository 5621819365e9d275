// Contour features against OpenCV 4.6 on the contours of every file input and
// of random binary scenes: exact where OpenCV is exact on integer points
// (area, spatial moments, bounding box, hull, approxPolyDP, defect indices),
// within the stated tolerances elsewhere.
#include "oracle.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/shape.h"
}

namespace
{

struct Checker {
    oracle::Tally &t;
    long tol_cases = 0, tol_fail = 0;
    explicit Checker(oracle::Tally &tt) : t(tt) {}

    void exact(const std::string &what, const std::vector<int> &e, const std::vector<int> &a)
    {
        std::vector<int> ee = e, aa = a;
        ee.push_back(-7); // never empty
        aa.push_back(-7);
        t.add(what, cv::Mat(ee, true), cv::Mat(aa, true));
    }
    void near(const std::string &what, double e, double a, double tol)
    {
        tol_cases++;
        t.cases++;
        if (!(std::fabs(e - a) <= tol)) {
            tol_fail++;
            t.differing++;
            if (tol_fail < 20)
                std::fprintf(stderr, "TOL %s: opencv=%.9g rtedge=%.9g (tol %g)\n", what.c_str(), e,
                             a, tol);
        }
    }
};

std::vector<int> flat(const std::vector<cv::Point> &v)
{
    std::vector<int> o;
    for (auto p : v) {
        o.push_back(p.x);
        o.push_back(p.y);
    }
    return o;
}

std::vector<int> flat(const rte_point *p, int n)
{
    std::vector<int> o;
    for (int i = 0; i < n; i++) {
        o.push_back(p[i].x);
        o.push_back(p[i].y);
    }
    return o;
}

double angle_diff_mod(double a, double b, double period)
{
    double d = std::fmod(std::fabs(a - b), period);
    return std::min(d, period - d);
}

void check_contour(Checker &c, const std::string &name, const std::vector<cv::Point> &cv_pts)
{
    const int n = (int)cv_pts.size();
    const rte_point *pts = reinterpret_cast<const rte_point *>(cv_pts.data());
    oracle::Arena s(rte_shape_hull_scratch_size(n) + rte_shape_approx_scratch_size(n) +
                    rte_shape_min_area_rect_scratch_size(n) +
                    rte_shape_enclosing_circle_scratch_size(n) + 4096);

    // area, perimeter, bounding box
    double area = cv::contourArea(cv_pts, true);
    c.exact(name + " area2", {(int)std::llround(area * 2)}, {(int)rte_shape_area2(pts, n)});
    double per = cv::arcLength(cv_pts, true);
    int64_t per_q16 = rte_shape_perimeter_q16(pts, n, 1);
    c.near(name + " perimeter", per, per_q16 / 65536.0, 1e-3 * per + 1e-9);
    cv::Rect br = cv::boundingRect(cv_pts);
    rte_rect rr = rte_shape_bounding_rect(pts, n);
    c.exact(name + " bounds", {br.x, br.y, br.width, br.height}, {rr.x, rr.y, rr.width, rr.height});

    // moments
    cv::Moments m = cv::moments(cv_pts);
    rte_moments rm;
    if (rte_shape_moments(pts, n, &rm) != RTE_OK) {
        c.t.call_failed(name + " moments", -1);
        return;
    }
    c.exact(name + " m00", {(int)std::llround(m.m00 * 2)}, {(int)rm.s00});
    const double sp[] = {m.m10, m.m01, m.m20, m.m11, m.m02, m.m30, m.m21, m.m12, m.m03};
    const double ours[] = {rm.s10 / 6.0,  rm.s01 / 6.0,  rm.s20 / 12.0,
                           rm.s11 / 24.0, rm.s02 / 12.0, rm.s30 / 20.0,
                           rm.s21 / 60.0, rm.s12 / 60.0, rm.s03 / 20.0};
    for (int k = 0; k < 9; k++)
        c.near(name + " m" + std::to_string(k), sp[k], ours[k], 1e-12 * std::fabs(sp[k]) + 1e-9);
    if (m.m00 > 0) {
        c.near(name + " cx", m.m10 / m.m00, rm.cx_q16 / 65536.0, 1.0 / 65536);
        c.near(name + " cy", m.m01 / m.m00, rm.cy_q16 / 65536.0, 1.0 / 65536);
        const double mu[] = {m.mu20, m.mu11, m.mu02, m.mu30, m.mu21, m.mu12, m.mu03};
        const int64_t rmu[] = {rm.mu20_q8, rm.mu11_q8, rm.mu02_q8, rm.mu30_q8,
                               rm.mu21_q8, rm.mu12_q8, rm.mu03_q8};
        for (int k = 0; k < 7; k++)
            c.near(name + " mu" + std::to_string(k), mu[k], rmu[k] / 256.0,
                   1e-9 * std::fabs(mu[k]) + 1.0 / 256);
        // OpenCV's third-order central moments cancel large raw moments in
        // double: for small contours far from the origin its own error is
        // about 1e-16 of the raw moments' scale (ours are exact).
        const double cond =
            1e-15 * (std::fabs(m.m30) + std::fabs(m.m21) + std::fabs(m.m12) + std::fabs(m.m03)) /
            std::pow(m.m00, 2.5);
        const double nu[] = {m.nu20, m.nu11, m.nu02, m.nu30, m.nu21, m.nu12, m.nu03};
        const int64_t rnu[] = {rm.nu20_q32, rm.nu11_q32, rm.nu02_q32, rm.nu30_q32,
                               rm.nu21_q32, rm.nu12_q32, rm.nu03_q32};
        for (int k = 0; k < 7; k++)
            c.near(name + " nu" + std::to_string(k), nu[k], rnu[k] / 4294967296.0,
                   1e-6 * std::fabs(nu[k]) + 1e-6 + (k >= 3 ? cond : 0));
        // Hu invariants multiply third-order terms: scale the allowance by them
        const double s3 =
            std::fabs(m.nu30) + std::fabs(m.nu21) + std::fabs(m.nu12) + std::fabs(m.nu03);
        const double hu_cond = 10 * cond * (1 + s3) * (1 + s3) * (1 + s3);
        double hu[7];
        cv::HuMoments(m, hu);
        for (int k = 0; k < 7; k++)
            c.near(name + " hu" + std::to_string(k), hu[k], rm.hu_q32[k] / 4294967296.0,
                   1e-5 * std::fabs(hu[k]) + 1e-6 + hu_cond);
    }

    // convex hull, both ways
    std::vector<int> hidx;
    std::vector<cv::Point> hpts;
    cv::convexHull(cv_pts, hidx, false, false);
    cv::convexHull(cv_pts, hpts, false, true);
    std::vector<int32_t> ridx((size_t)n + 1);
    std::vector<rte_point> rpts((size_t)n + 1);
    int32_t nh = 0;
    if (rte_shape_convex_hull(pts, n, ridx.data(), rpts.data(), &nh, &s.arena) != RTE_OK) {
        c.t.call_failed(name + " hull", -1);
        return;
    }
    c.exact(name + " hull indices", hidx, std::vector<int>(ridx.begin(), ridx.begin() + nh));
    c.exact(name + " hull points", flat(hpts), flat(rpts.data(), nh));

    // convexity defects (OpenCV refuses non-monotonic hulls; so do we)
    if (n > 3 && nh >= 3) {
        std::vector<cv::Vec4i> defects;
        bool cv_ok = true;
        try {
            cv::convexityDefects(cv_pts, hidx, defects);
        } catch (const cv::Exception &) {
            cv_ok = false;
        }
        std::vector<rte_defect> rd((size_t)nh);
        int32_t nd = 0;
        int st = rte_shape_convexity_defects(pts, n, ridx.data(), nh, rd.data(), &nd);
        c.exact(name + " defects accepted", {cv_ok ? 0 : 1}, {st == RTE_OK ? 0 : 1});
        if (cv_ok && st == RTE_OK) {
            std::vector<int> e, a;
            for (auto &d : defects)
                e.insert(e.end(), {d[0], d[1], d[2]});
            for (int i = 0; i < nd; i++)
                a.insert(a.end(), {rd[i].start, rd[i].end, rd[i].farthest});
            c.exact(name + " defects", e, a);
            for (size_t i = 0; i < defects.size() && (int)i < nd; i++)
                c.near(name + " defect depth", defects[i][3], rd[i].depth_q8, 1.0);
        }
    }

    // approxPolyDP with the tutorial's epsilon, given to OpenCV as the exact
    // double our fixed-point epsilon stands for
    for (int pct : {1, 2, 5}) {
        uint32_t eps_q16 = (uint32_t)((per_q16 * pct + 50) / 100);
        if (eps_q16 >= (1u << 26))
            continue;
        std::vector<cv::Point> ap;
        cv::approxPolyDP(cv_pts, ap, eps_q16 / 65536.0, true);
        std::vector<rte_point> out((size_t)n + 1);
        int32_t no = 0;
        if (rte_shape_approx_poly(pts, n, eps_q16, out.data(), &no, &s.arena) != RTE_OK) {
            c.t.call_failed(name + " approx", -1);
            continue;
        }
        c.exact(name + " approx " + std::to_string(pct), flat(ap), flat(out.data(), no));
    }

    // rotated rectangle: corners within 0.5 px, angle within 0.5 degree
    {
        cv::RotatedRect box = cv::minAreaRect(cv_pts);
        rte_rotated_rect rb;
        if (rte_shape_min_area_rect(pts, n, &rb, &s.arena) != RTE_OK) {
            c.t.call_failed(name + " min_area_rect", -1);
        } else {
            cv::Point2f corners[4];
            box.points(corners);
            // match every OpenCV corner to the nearest of ours
            double worst = 0;
            for (auto &p : corners) {
                double best = 1e30;
                for (int k = 0; k < 4; k++)
                    best = std::min(best, std::hypot(p.x - rb.corners_q8[k][0] / 256.0,
                                                     p.y - rb.corners_q8[k][1] / 256.0));
                worst = std::max(worst, best);
            }
            // a tie (two minimal rectangles, e.g. small triangles) passes when
            // ours is as small and holds every point
            double area_cv = (double)box.size.width * box.size.height;
            double area_ours = (rb.length_q8 / 256.0) * (rb.width_q8 / 256.0);
            bool holds = true;
            for (const auto &p : cv_pts) {
                std::vector<cv::Point2f> poly;
                for (int k = 0; k < 4; k++)
                    poly.emplace_back(rb.corners_q8[k][0] / 256.f, rb.corners_q8[k][1] / 256.f);
                if (cv::pointPolygonTest(poly, cv::Point2f((float)p.x, (float)p.y), true) < -0.02)
                    holds = false;
            }
            // ours may be a different minimal rectangle (a tie) or smaller
            // than OpenCV's float calipers found; it must hold every point
            const double area_tol =
                (rb.length_q8 + rb.width_q8) / 256.0 / 256.0 + 1e-3 * area_cv + 0.02;
            c.near(name + " rect holds points", 1, holds ? 1 : 0, 0);
            c.near(name + " rect not larger", 0, std::max(0.0, area_ours - area_cv), area_tol);
            bool alternative = holds && area_ours <= area_cv + area_tol;
            c.near(name + " rect corners", 0, alternative ? 0 : worst, 0.5);
            if (worst > 0.5)
                return;
            double len = std::max(box.size.width, box.size.height),
                   wid = std::min(box.size.width, box.size.height);
            c.near(name + " rect length", len, rb.length_q8 / 256.0, 0.5);
            c.near(name + " rect width", wid, rb.width_q8 / 256.0, 0.5);
            if (len - wid > 1.0 && wid > 1.0) {
                // OpenCV 4.6: angle of `width` in [0, 90]; convert to the long side
                double a = box.size.width >= box.size.height ? box.angle : box.angle - 90.0;
                c.near(name + " rect angle", 0, angle_diff_mod(a, rb.angle_q16 / 65536.0, 180.0),
                       0.5);
            }
            // ours: the documented boxPoints order of (length, width, angle)
            cv::RotatedRect mine(cv::Point2f(rb.cx_q8 / 256.f, rb.cy_q8 / 256.f),
                                 cv::Size2f(rb.length_q8 / 256.f, rb.width_q8 / 256.f),
                                 rb.angle_q16 / 65536.f);
            cv::Point2f mc[4];
            mine.points(mc);
            double worst_order = 0;
            for (int k = 0; k < 4; k++)
                worst_order = std::max(worst_order,
                                       (double)std::hypot(mc[k].x - rb.corners_q8[k][0] / 256.0,
                                                          mc[k].y - rb.corners_q8[k][1] / 256.0));
            c.near(name + " rect corner order", 0, worst_order, 0.05);
        }
    }

    // enclosing circle within 0.5 px
    {
        cv::Point2f cc;
        float r;
        cv::minEnclosingCircle(cv_pts, cc, r);
        rte_circle rc;
        if (rte_shape_enclosing_circle(pts, n, &rc, &s.arena) != RTE_OK) {
            c.t.call_failed(name + " circle", -1);
        } else {
            c.near(name + " circle r", r, rc.r_q8 / 256.0, 0.5);
            c.near(name + " circle c", 0,
                   std::hypot(cc.x - rc.cx_q8 / 256.0, cc.y - rc.cy_q8 / 256.0), 0.5);
        }
    }
}

void check_image(Checker &c, const std::string &name, const cv::Mat &bin, size_t max_contours)
{
    for (int method : {cv::CHAIN_APPROX_NONE, cv::CHAIN_APPROX_SIMPLE}) {
        std::vector<std::vector<cv::Point>> cs;
        cv::findContours(bin, cs, cv::RETR_LIST, method);
        // the largest contours plus a stride through the rest keeps the time bounded
        size_t step = cs.size() > max_contours ? cs.size() / max_contours : 1;
        for (size_t i = 0; i < cs.size(); i += step)
            check_contour(c, name + " m" + std::to_string(method) + " #" + std::to_string(i),
                          cs[i]);
    }
}

cv::Mat random_scene(std::mt19937 &rng)
{
    auto U = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    int w = U(1, 300), h = U(1, 300);
    cv::Mat m(h, w, CV_8UC1, cv::Scalar(0));
    int n = U(1, 8);
    for (int i = 0; i < n; i++) {
        cv::Point c(U(-3, w + 2), U(-3, h + 2));
        int r = U(0, std::max(w, h) / 2 + 1);
        int v = U(0, 3) == 0 ? 0 : 255;
        switch (U(0, 4)) {
        case 0: cv::circle(m, c, r, v, cv::FILLED); break;
        case 1: cv::ellipse(m, c, cv::Size(r, U(0, r)), U(0, 359), 0, 360, v, cv::FILLED); break;
        case 2: cv::line(m, c, cv::Point(U(0, w), U(0, h)), v, U(1, 3)); break;
        case 3: m.at<uint8_t>(U(0, h - 1), U(0, w - 1)) = (uint8_t)v; break;
        default: {
            std::vector<cv::Point> poly;
            for (int j = U(3, 9); j > 0; j--)
                poly.push_back(c + cv::Point(U(-r, r), U(-r, r)));
            cv::fillPoly(m, std::vector<std::vector<cv::Point>>{poly}, v);
        }
        }
    }
    return m;
}

// Synthetic shapes: regular polygons, rectangles and discs of 20 px and
// more at any rotation, drawn with sub-pixel vertices, half of them with
// noisy edges (edge pixels flipped at random).
cv::Mat synthetic_shape(std::mt19937 &rng, int kind)
{
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double size = 20 + U(rng) * 130, rot = U(rng) * 2 * CV_PI;
    int W = (int)(size * 2.2) + 10;
    cv::Mat img(W, W, CV_8UC1, cv::Scalar(0));
    cv::Point2d c(W / 2.0 + U(rng) * 4 - 2, W / 2.0 + U(rng) * 4 - 2);
    if (kind == RTE_SHAPE_CIRCLE) {
        cv::circle(img, cv::Point((int)(c.x * 16), (int)(c.y * 16)), (int)(size / 2 * 16), 255,
                   cv::FILLED, cv::LINE_8, 4);
    } else {
        std::vector<cv::Point2d> p;
        if (kind == RTE_SHAPE_RECTANGLE) {
            double ar = 1.4 + U(rng) * 1.6, w = size, h = size / ar;
            p = {{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}};
        } else {
            int k = kind == RTE_SHAPE_TRIANGLE   ? 3
                    : kind == RTE_SHAPE_SQUARE   ? 4
                    : kind == RTE_SHAPE_PENTAGON ? 5
                                                 : 6;
            double R = k == 4 ? size / 2 * std::sqrt(2.0) : size / 2;
            for (int i = 0; i < k; i++)
                p.push_back({R * std::cos(2 * CV_PI * i / k), R * std::sin(2 * CV_PI * i / k)});
        }
        std::vector<cv::Point> q;
        for (auto &v : p)
            q.push_back(cv::Point(
                (int)std::lround((c.x + v.x * std::cos(rot) - v.y * std::sin(rot)) * 16),
                (int)std::lround((c.y + v.x * std::sin(rot) + v.y * std::cos(rot)) * 16)));
        cv::fillPoly(img, std::vector<std::vector<cv::Point>>{q}, 255, cv::LINE_8, 4);
    }
    if (rng() & 1) {
        cv::Mat edges;
        cv::Canny(img, edges, 50, 150);
        for (int y = 0; y < W; y++)
            for (int x = 0; x < W; x++)
                if (edges.at<uint8_t>(y, x) && U(rng) < 0.06)
                    img.at<uint8_t>(y, x) = (uint8_t)(255 - img.at<uint8_t>(y, x));
    }
    return img;
}

void check_classes(oracle::Tally &t, std::mt19937 &rng, int per_class)
{
    static const char *names[] = {"other",    "triangle", "square", "rectangle",
                                  "pentagon", "hexagon",  "circle"};
    oracle::Arena scratch(1 << 22);
    long wrong = 0, total = 0;
    for (int kind = RTE_SHAPE_TRIANGLE; kind <= RTE_SHAPE_CIRCLE; kind++) {
        for (int i = 0; i < per_class; i++) {
            cv::Mat img = synthetic_shape(rng, kind);
            std::vector<std::vector<cv::Point>> cs;
            cv::findContours(img, cs, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
            size_t big = 0;
            for (size_t k = 1; k < cs.size(); k++)
                if (cv::contourArea(cs[k]) > cv::contourArea(cs[big]))
                    big = k;
            rte_shape_info info;
            int st = rte_shape_classify(reinterpret_cast<const rte_point *>(cs[big].data()),
                                        (int)cs[big].size(), &info, &scratch.arena);
            total++;
            if (st != RTE_OK || (int)info.shape != kind) {
                wrong++;
                std::fprintf(stderr,
                             "CLASS %s #%d: got %s (v %d, hull circ %.3f, aspect %.3f, solidity "
                             "%.3f, %d px, r %.2f)\n",
                             names[kind], i, names[st == RTE_OK ? info.shape : 0], info.vertices,
                             info.hull_circularity_q16 / 65536.0, info.aspect_q16 / 65536.0,
                             info.solidity_q16 / 65536.0, info.bounds.width,
                             info.circle.r_q8 / 256.0);
            }
        }
    }
    std::printf("oracle shape: %ld synthetic shapes, %ld misclassified\n", total, wrong);
    t.cases += total;
    t.differing += wrong;
}

} // namespace

int main()
{
    oracle::Tally t("shape");
    Checker c(t);
    std::mt19937 rng = oracle::make_rng();
    for (const auto &in : oracle::file_inputs()) {
        for (int thr : {100, 200})
            check_image(c, in.name + " >" + std::to_string(thr), in.gray > thr, 60);
    }
    int n = oracle::random_count();
    for (int i = 0; i < n; i++)
        check_image(c, "random#" + std::to_string(i), random_scene(rng), 40);
    check_classes(t, rng, 200);
    std::printf("oracle shape: %ld tolerance checks, %ld outside tolerance\n", c.tol_cases,
                c.tol_fail);
    return t.finish();
}
