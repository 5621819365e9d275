// Hough lines, segments and circles: accuracy on synthetic fixtures of known
// geometry (fixed seed), agreement with OpenCV 4.6 on the real photos, known
// answers (smarties.png, sudoku.png), determinism and bounds on random
// images. rtedge's Hough is integer and deliberately not bit-compatible with
// OpenCV's float code (docs/hough.md), so agreement is measured, not equality.
#include "oracle.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/arena.h"
#include "rtedge/hough.h"
}

namespace
{

int failures = 0;

__attribute__((format(printf, 2, 3))) void check(bool ok, const char *fmt, ...)
{
    if (!ok) {
        va_list ap;
        va_start(ap, fmt);
        std::printf("FAIL: ");
        std::vprintf(fmt, ap);
        std::printf("\n");
        va_end(ap);
        failures++;
    }
}

uint32_t fnv(uint32_t h, const void *p, size_t n)
{
    const uint8_t *b = static_cast<const uint8_t *>(p);
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 16777619u;
    return h;
}

uint32_t sum_lines = 2166136261u, sum_segs = 2166136261u, sum_circles = 2166136261u;

// ---- wrappers: run an rtedge transform twice on a padded copy and check
// determinism, the arena mark and the count bound ----

struct Runner {
    oracle::Tally &tally;
    std::mt19937 &rng;
};

template <typename T, typename F>
std::vector<T> run_twice(Runner &run, const std::string &what, int cap, bool *truncated, F call)
{
    std::vector<T> out[2];
    bool trunc[2] = {false, false};
    for (int k = 0; k < 2; k++) {
        out[k].assign((size_t)cap + 1, T{});
        int32_t n = -1;
        rte_status st = call(out[k].data(), cap, &n, &trunc[k]);
        if (st != RTE_OK) {
            run.tally.call_failed(what, st);
            return {};
        }
        check(n >= 0 && n <= cap, "count in range (%s): %d of %d", what.c_str(), (int)n, cap);
        out[k].resize((size_t)std::max(n, 0));
    }
    cv::Mat a(1, (int)(out[0].size() * sizeof(T)), CV_8U, out[0].data());
    cv::Mat b(1, (int)(out[1].size() * sizeof(T)), CV_8U, out[1].data());
    if (a.cols == b.cols && a.cols > 0)
        run.tally.add(what + " (repeat)", a, b);
    else
        check(a.cols == b.cols && trunc[0] == trunc[1], "repeatable size (%s): %d vs %d",
              what.c_str(), a.cols, b.cols);
    *truncated = trunc[0];
    return out[0];
}

std::vector<rte_hough_line> lines_of(Runner &run, const std::string &what,
                                     const rte_hough_config &cfg, const cv::Mat &edges, int thr,
                                     int cap, bool *truncated)
{
    std::vector<uint8_t> store;
    rte_image_u8 e = oracle::padded_u8(edges, store, run.rng);
    oracle::Arena ar(rte_hough_lines_scratch_size(&cfg, cap));
    auto r = run_twice<rte_hough_line>(
        run, what, cap, truncated, [&](rte_hough_line *o, int c, int32_t *n, bool *t) {
            rte_status st = rte_hough_lines(&cfg, &e, thr, &ar.arena, o, c, n, t);
            check(ar.arena.used == 0, "arena reset after lines: %zu bytes still taken",
                  ar.arena.used);
            return st;
        });
    sum_lines = fnv(sum_lines, r.data(), r.size() * sizeof(rte_hough_line));
    return r;
}

std::vector<rte_hough_segment> segments_of(Runner &run, const std::string &what,
                                           const rte_hough_config &cfg, const cv::Mat &edges,
                                           const rte_hough_segments_params &p, int cap,
                                           bool *truncated)
{
    std::vector<uint8_t> store;
    rte_image_u8 e = oracle::padded_u8(edges, store, run.rng);
    oracle::Arena ar(rte_hough_segments_scratch_size(&cfg));
    auto r = run_twice<rte_hough_segment>(
        run, what, cap, truncated, [&](rte_hough_segment *o, int c, int32_t *n, bool *t) {
            rte_status st = rte_hough_segments(&cfg, &e, &p, &ar.arena, o, c, n, t);
            check(ar.arena.used == 0, "arena reset after segments: %zu bytes still taken",
                  ar.arena.used);
            return st;
        });
    sum_segs = fnv(sum_segs, r.data(), r.size() * sizeof(rte_hough_segment));
    return r;
}

// OpenCV's HoughCircles inputs: Sobel 3x3 (BORDER_REPLICATE) and Canny on them.
struct CircleInputs {
    cv::Mat edges, dx, dy;
};

CircleInputs circle_inputs(const cv::Mat &gray, int param1)
{
    CircleInputs c;
    cv::Sobel(gray, c.dx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
    cv::Sobel(gray, c.dy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REPLICATE);
    cv::Canny(c.dx, c.dy, c.edges, std::max(1, param1 / 2), param1, false);
    return c;
}

std::vector<rte_hough_circle> circles_of(Runner &run, const std::string &what,
                                         const CircleInputs &in, const rte_hough_circles_params &p,
                                         int cap, bool *truncated)
{
    std::vector<uint8_t> store;
    rte_image_u8 e = oracle::padded_u8(in.edges, store, run.rng);
    cv::Mat dx = in.dx.clone(), dy = in.dy.clone();
    rte_image_s16 gx = oracle::view_s16(dx), gy = oracle::view_s16(dy);
    oracle::Arena ar(rte_hough_circles_scratch_size(in.edges.cols, in.edges.rows, &p));
    auto r = run_twice<rte_hough_circle>(
        run, what, cap, truncated, [&](rte_hough_circle *o, int c, int32_t *n, bool *t) {
            rte_status st = rte_hough_circles(&e, &gx, &gy, &p, &ar.arena, o, c, n, t);
            check(ar.arena.used == 0, "arena reset after circles: %zu bytes still taken",
                  ar.arena.used);
            return st;
        });
    sum_circles = fnv(sum_circles, r.data(), r.size() * sizeof(rte_hough_circle));
    return r;
}

rte_hough_config make_config(int w, int h, double rho, double theta)
{
    rte_hough_config cfg;
    rte_status st = rte_hough_config_init(&cfg, w, h, rho, theta, 0.0, CV_PI);
    check(st == RTE_OK, "config init: status %d", (int)st);
    return cfg;
}

// ---- geometry helpers ----

double pt_dist(double ax, double ay, double bx, double by) { return std::hypot(ax - bx, ay - by); }

bool endpoints_match(const cv::Vec4d &a, const cv::Vec4d &b, double tol)
{
    bool same = pt_dist(a[0], a[1], b[0], b[1]) <= tol && pt_dist(a[2], a[3], b[2], b[3]) <= tol;
    bool swapped = pt_dist(a[0], a[1], b[2], b[3]) <= tol && pt_dist(a[2], a[3], b[0], b[1]) <= tol;
    return same || swapped;
}

// Recall (ground truth found with both endpoints within tol) and precision
// (detections that match a ground-truth segment not matched before: a second
// detection of one segment counts as a false one).
struct Score {
    long truth = 0, found = 0, detections = 0, correct = 0;
};

void score_segments(const std::vector<cv::Vec4d> &truth, const std::vector<cv::Vec4d> &det,
                    double tol, Score &s)
{
    std::vector<bool> used(truth.size(), false);
    s.truth += (long)truth.size();
    s.detections += (long)det.size();
    for (const auto &d : det)
        for (size_t i = 0; i < truth.size(); i++)
            if (!used[i] && endpoints_match(truth[i], d, tol)) {
                used[i] = true;
                s.correct++;
                break;
            }
    for (size_t i = 0; i < truth.size(); i++)
        for (const auto &d : det)
            if (endpoints_match(truth[i], d, tol)) {
                s.found++;
                break;
            }
}

// ---- A. synthetic segments ----

void synthetic_segments(Runner &run)
{
    std::mt19937 g(12345);
    auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); };
    const int W = 640, H = 480, images = 30;
    rte_hough_config cfg = make_config(W, H, 1.0, CV_PI / 180);
    rte_hough_segments_params p = {30, 40, 6, 0};
    Score mine, cv_score;
    double t_mine = 0, t_cv = 0;
    for (int img = 0; img < images; img++) {
        cv::Mat e = cv::Mat::zeros(H, W, CV_8U);
        std::vector<cv::Vec4d> truth;
        int want = 5 + img % 6;
        for (int tries = 0; (int)truth.size() < want && tries < 1000; tries++) {
            double a = uni(0, CV_PI), len = uni(60, 360);
            double cx = uni(20, W - 20), cy = uni(20, H - 20);
            double dx = std::cos(a) * len / 2, dy = std::sin(a) * len / 2;
            cv::Vec4d s(std::round(cx - dx), std::round(cy - dy), std::round(cx + dx),
                        std::round(cy + dy));
            if (s[0] < 4 || s[2] < 4 || s[1] < 4 || s[3] < 4 || s[0] > W - 5 || s[2] > W - 5 ||
                s[1] > H - 5 || s[3] > H - 5)
                continue;
            // keep segments apart from parallel neighbours so the truth is unambiguous
            bool clash = false;
            for (const auto &t : truth) {
                double ta = std::atan2(t[3] - t[1], t[2] - t[0]),
                       sa = std::atan2(s[3] - s[1], s[2] - s[0]);
                double da = std::fabs(std::remainder(ta - sa, CV_PI));
                double mx = (s[0] + s[2]) / 2 - t[0], my = (s[1] + s[3]) / 2 - t[1];
                double tl = std::hypot(t[2] - t[0], t[3] - t[1]);
                double perp = std::fabs(mx * (t[3] - t[1]) - my * (t[2] - t[0])) / tl;
                if (da < 0.2 && perp < 15)
                    clash = true;
            }
            if (clash)
                continue;
            truth.push_back(s);
        }
        for (const auto &s : truth) {
            int thick = 1 + (int)(uni(0, 2)); // 1 or 2: wider lines have round caps past the ends
            cv::line(e, cv::Point((int)s[0], (int)s[1]), cv::Point((int)s[2], (int)s[3]), 255,
                     thick, cv::LINE_8);
        }
        // gaps (shorter than max_gap = 6) inside the segments
        for (const auto &s : truth) {
            int gaps = (int)uni(0, 3);
            for (int k = 0; k < gaps; k++) {
                // gaps of at most 5 px in separate thirds of the segment
                double f = 0.25 + 0.25 * k + uni(-0.05, 0.05), glen = uni(0, 2.5);
                double len = std::hypot(s[2] - s[0], s[3] - s[1]);
                double ux = (s[2] - s[0]) / len, uy = (s[3] - s[1]) / len;
                for (double u = 0; u < glen; u += 0.25) {
                    double x = s[0] + ux * (f * len + u), y = s[1] + uy * (f * len + u);
                    cv::circle(e, cv::Point((int)std::lround(x), (int)std::lround(y)), 1, 0, -1);
                }
            }
        }
        // clutter: salt noise and small rings away from the segment ends
        for (int k = 0; k < W * H / 800; k++)
            e.at<uint8_t>((int)uni(0, H), (int)uni(0, W)) = 255;
        // (rings stay 16 px from segment ends: one touching a segment's
        // extension would make its true end ambiguous)
        for (int k = 0; k < 8; k++) {
            cv::Point c((int)uni(0, W), (int)uni(0, H));
            bool near_end = false;
            for (const auto &s : truth)
                near_end |=
                    pt_dist(c.x, c.y, s[0], s[1]) < 16 || pt_dist(c.x, c.y, s[2], s[3]) < 16;
            if (!near_end)
                cv::circle(e, c, (int)uni(2, 7), 255, 1);
        }

        bool trunc = false;
        auto t0 = std::chrono::steady_clock::now();
        auto segs =
            segments_of(run, "synthetic segments " + std::to_string(img), cfg, e, p, 256, &trunc);
        auto t1 = std::chrono::steady_clock::now();
        std::vector<cv::Vec4i> ocv;
        cv::HoughLinesP(e, ocv, 1, CV_PI / 180, p.threshold, p.min_length, p.max_gap);
        auto t2 = std::chrono::steady_clock::now();
        t_mine += std::chrono::duration<double>(t1 - t0).count() / 2; // segments_of runs twice
        t_cv += std::chrono::duration<double>(t2 - t1).count();
        std::vector<cv::Vec4d> det, odet;
        for (const auto &s : segs)
            det.emplace_back(s.x0, s.y0, s.x1, s.y1);
        for (const auto &s : ocv)
            odet.emplace_back(s[0], s[1], s[2], s[3]);
        if (getenv("DBG")) {
            std::printf("image %d\n", img);
            for (auto &t : truth)
                std::printf("T %g %g %g %g\n", t[0], t[1], t[2], t[3]);
            for (auto &t : det)
                std::printf("D %g %g %g %g\n", t[0], t[1], t[2], t[3]);
            cv::imwrite("/tmp/seg" + std::to_string(img) + ".png", e);
        }
        score_segments(truth, det, 2.0, mine);
        score_segments(truth, odet, 2.0, cv_score);
    }
    double recall = (double)mine.found / mine.truth,
           precision = (double)mine.correct / mine.detections;
    std::printf("synthetic segments: %ld truth, %ld detections: recall %.3f precision %.3f "
                "(OpenCV HoughLinesP: recall %.3f precision %.3f, %ld detections)\n",
                mine.truth, mine.detections, recall, precision,
                (double)cv_score.found / cv_score.truth,
                (double)cv_score.correct / std::max(1L, cv_score.detections), cv_score.detections);
    std::printf("synthetic segments time: rtedge %.1f ms, OpenCV %.1f ms\n", t_mine * 1e3,
                t_cv * 1e3);
    check(recall >= 0.98, "segment recall %.3f < %.2f", recall, 0.98);
    check(precision >= 0.95, "segment precision %.3f < %.2f", precision, 0.95);
}

// ---- B. synthetic standard lines ----

void synthetic_lines(Runner &run)
{
    std::mt19937 g(777);
    auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); };
    const int W = 400, H = 300;
    const double theta_res = CV_PI / 180;
    rte_hough_config cfg = make_config(W, H, 1.0, theta_res);
    long truth = 0, found = 0, ocv_found = 0;
    for (int img = 0; img < 20; img++) {
        cv::Mat e = cv::Mat::zeros(H, W, CV_8U);
        std::vector<std::pair<double, double>> gt; // rho, theta
        while (gt.size() < 5) {
            double th = uni(0.05, CV_PI - 0.05);
            double px = uni(W * 0.3, W * 0.7), py = uni(H * 0.3, H * 0.7);
            double rho = px * std::cos(th) + py * std::sin(th);
            bool clash = false;
            for (const auto &l : gt)
                if (std::fabs(l.second - th) < 0.1 && std::fabs(l.first - rho) < 20)
                    clash = true;
            if (clash)
                continue;
            gt.emplace_back(rho, th);
            double dx = -std::sin(th), dy = std::cos(th);
            cv::line(e,
                     cv::Point((int)std::lround(px - 2000 * dx), (int)std::lround(py - 2000 * dy)),
                     cv::Point((int)std::lround(px + 2000 * dx), (int)std::lround(py + 2000 * dy)),
                     255, 1, cv::LINE_8);
        }
        for (int k = 0; k < W * H / 200; k++)
            e.at<uint8_t>((int)uni(0, H), (int)uni(0, W)) = 255;
        bool trunc = false;
        auto lines =
            lines_of(run, "synthetic lines " + std::to_string(img), cfg, e, 80, 20, &trunc);
        std::vector<cv::Vec2f> ocv;
        cv::HoughLines(e, ocv, 1, theta_res, 80);
        if (ocv.size() > 20)
            ocv.resize(20);
        for (const auto &l : gt) {
            truth++;
            // A true angle between two bins peaks at the neighbouring bins
            // with rho shifted by (distance of the visible chord from the
            // foot of the normal) * (angle error), up to several pixels. So
            // the rho a detection should have is the true line's rho AT THE
            // DETECTED ANGLE, through the middle of its visible chord.
            double th = l.second, dx = -std::sin(th), dy = std::cos(th);
            double fx = l.first * std::cos(th), fy = l.first * std::sin(th);
            cv::Point p1((int)std::lround(fx - 2000 * dx), (int)std::lround(fy - 2000 * dy));
            cv::Point p2((int)std::lround(fx + 2000 * dx), (int)std::lround(fy + 2000 * dy));
            cv::clipLine(cv::Size(W, H), p1, p2);
            double mx = (p1.x + p2.x) / 2.0, my = (p1.y + p2.y) / 2.0;
            auto near = [&](double rho_bin, double theta_bin) {
                double td = theta_bin * theta_res;
                return std::fabs(theta_bin - th / theta_res) <= 1.0 &&
                       std::fabs(rho_bin - std::round(mx * std::cos(td) + my * std::sin(td))) <=
                           1.0;
            };
            bool hit = false, ohit = false;
            for (const auto &d : lines)
                hit = hit || near(d.rho_bin, d.theta_bin);
            for (const auto &d : ocv)
                ohit = ohit || near(d[0], std::lround(d[1] / theta_res));
            found += hit;
            ocv_found += ohit;
            if (!hit && getenv("DBG")) {
                std::printf("missed rho %.2f theta %.4f mid %.1f %.1f; got", l.first, l.second, mx,
                            my);
                for (const auto &d : lines)
                    std::printf(" (%d %d %d)", d.rho_bin, d.theta_bin, d.votes);
                std::printf("\n");
            }
        }
    }
    std::printf("synthetic lines (OpenCV HoughLines: %ld of %ld)\n", ocv_found, truth);
    std::printf("synthetic lines: %ld of %ld found within one rho and one theta bin\n", found,
                truth);
    check(found == truth, "synthetic lines found %ld of %ld", found, truth);
}

// ---- C. synthetic circles ----

void synthetic_circles(Runner &run)
{
    std::mt19937 g(4242);
    auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); };
    const int W = 480, H = 360;
    rte_hough_circles_params p = {256, 20, 25, 10, 60, 0, 0};
    long truth = 0, found = 0, detections = 0, correct = 0;
    for (int img = 0; img < 15; img++) {
        cv::Mat gray(H, W, CV_8U, cv::Scalar(110));
        cv::Mat noise(H, W, CV_8U);
        cv::randn(noise, 0, 4);
        std::vector<cv::Vec3d> gt;
        for (int tries = 0; gt.size() < 5 && tries < 500; tries++) {
            double r = std::round(uni(12, 50));
            double cx = std::round(uni(r + 2, W - r - 2)), cy = std::round(uni(r + 2, H - r - 2));
            bool clash = false;
            for (const auto &c : gt)
                if (pt_dist(c[0], c[1], cx, cy) < c[2] + r + 8)
                    clash = true;
            if (!clash)
                gt.emplace_back(cx, cy, r);
        }
        for (const auto &c : gt)
            cv::circle(gray, cv::Point((int)c[0], (int)c[1]), (int)c[2], uni(0, 1) < 0.5 ? 30 : 220,
                       -1, cv::LINE_AA);
        gray += noise;
        CircleInputs in = circle_inputs(gray, 100);
        bool trunc = false;
        auto circles =
            circles_of(run, "synthetic circles " + std::to_string(img), in, p, 64, &trunc);
        detections += (long)circles.size();
        std::vector<bool> used(gt.size(), false);
        for (const auto &c : circles) {
            double x = c.x_q4 / 16.0, y = c.y_q4 / 16.0, r = c.r_q4 / 16.0;
            for (size_t i = 0; i < gt.size(); i++)
                if (!used[i] && pt_dist(x, y, gt[i][0], gt[i][1]) <= 1.0 &&
                    std::fabs(r - gt[i][2]) <= 1.0) {
                    used[i] = true;
                    correct++;
                    break;
                }
        }
        truth += (long)gt.size();
        found += std::count(used.begin(), used.end(), true);
        if (getenv("DBG") && std::count(used.begin(), used.end(), true) < (long)gt.size()) {
            for (const auto &c : gt)
                std::printf("circle truth %g %g %g\n", c[0], c[1], c[2]);
            for (const auto &c : circles)
                std::printf("circle found %g %g %g votes %d\n", c.x_q4 / 16.0, c.y_q4 / 16.0,
                            c.r_q4 / 16.0, c.votes);
        }
    }
    std::printf(
        "synthetic circles: %ld of %ld found with centre and radius within 1 px; %ld detections, "
        "%ld correct\n",
        found, truth, detections, correct);
    check(found == truth, "synthetic circles found %ld of %ld", found, truth);
    check(correct == detections, "synthetic circles: %ld of %ld detections correct", correct,
          detections);
}

// ---- D. agreement with OpenCV on the real photos ----

cv::Mat draw_segments(cv::Size sz, const std::vector<cv::Vec4d> &s)
{
    cv::Mat m = cv::Mat::zeros(sz, CV_8U);
    for (const auto &v : s)
        cv::line(m, cv::Point((int)v[0], (int)v[1]), cv::Point((int)v[2], (int)v[3]), 255, 1,
                 cv::LINE_8);
    return m;
}

// Edge pixels within 1 px of segment set `a` and how many of them lie within
// 2 px of segment set `b`.
void coverage(const cv::Mat &edges, const std::vector<cv::Vec4d> &a,
              const std::vector<cv::Vec4d> &b, long &covered, long &near)
{
    cv::Mat ma = draw_segments(edges.size(), a), mb = draw_segments(edges.size(), b);
    cv::dilate(ma, ma, cv::Mat::ones(3, 3, CV_8U));
    cv::Mat inv = 255 - mb, dist;
    cv::distanceTransform(inv, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    for (int y = 0; y < edges.rows; y++)
        for (int x = 0; x < edges.cols; x++)
            if (edges.at<uint8_t>(y, x) && ma.at<uint8_t>(y, x)) {
                covered++;
                near += dist.at<float>(y, x) <= 2.0f;
            }
}

void real_photos(Runner &run, const std::vector<oracle::Input> &inputs)
{
    long cv_lines = 0, matched_lines = 0;
    long cov_cv = 0, near_cv = 0, cov_me = 0, near_me = 0;
    double t_me = 0, t_cv = 0, t_me_lanes = 0, t_cv_lanes = 0;
    for (const auto &in : inputs) {
        cv::Mat edges;
        cv::Canny(in.gray, edges, 50, 150);
        const int W = edges.cols, H = edges.rows;
        rte_hough_config cfg = make_config(W, H, 1.0, CV_PI / 180);
        // standard lines: OpenCV's 30 strongest against rtedge's 120 strongest
        std::vector<cv::Vec3f> ocv;
        cv::HoughLines(edges, ocv, 1, CV_PI / 180, 80);
        bool trunc = false;
        auto mine = lines_of(run, "lines " + in.name, cfg, edges, 80, 120, &trunc);
        int numrho = (int)std::lround((2.0 * (W + H) + 1));
        long m = 0, n = std::min<long>(30, (long)ocv.size());
        for (long i = 0; i < n; i++) {
            double idx = ocv[i][0] + (numrho - 1) * 0.5; // OpenCV's accumulator column
            double tb = std::lround(ocv[i][1] / (CV_PI / 180));
            for (const auto &l : mine)
                if (std::fabs(l.rho_bin + (numrho - 1) / 2 - idx) <= 1.0 &&
                    std::fabs(l.theta_bin - tb) <= 1) {
                    m++;
                    break;
                }
        }
        cv_lines += n;
        matched_lines += m;

        // segments
        rte_hough_segments_params p = {50, 30, 10, 0};
        auto t0 = std::chrono::steady_clock::now();
        auto segs = segments_of(run, "segments " + in.name, cfg, edges, p, 4096, &trunc);
        auto t1 = std::chrono::steady_clock::now();
        std::vector<cv::Vec4i> osegs;
        cv::HoughLinesP(edges, osegs, 1, CV_PI / 180, p.threshold, p.min_length, p.max_gap);
        auto t2 = std::chrono::steady_clock::now();
        double tm = std::chrono::duration<double>(t1 - t0).count() / 2,
               tc = std::chrono::duration<double>(t2 - t1).count();
        t_me += tm;
        t_cv += tc;
        if (in.name.find("/lanes/") != std::string::npos) {
            t_me_lanes += tm;
            t_cv_lanes += tc;
        }
        std::vector<cv::Vec4d> a, b;
        for (const auto &s : osegs)
            a.emplace_back(s[0], s[1], s[2], s[3]);
        for (const auto &s : segs)
            b.emplace_back(s.x0, s.y0, s.x1, s.y1);
        long c1 = 0, n1 = 0, c2 = 0, n2 = 0;
        coverage(edges, a, b, c1, n1);
        coverage(edges, b, a, c2, n2);
        cov_cv += c1, near_cv += n1, cov_me += c2, near_me += n2;
        std::printf("  %s: lines %ld/%ld; segments rtedge %zu OpenCV %zu, coverage %.3f / %.3f, "
                    "%.1f ms vs %.1f ms\n",
                    in.name.c_str(), m, n, segs.size(), osegs.size(), c1 ? (double)n1 / c1 : 1.0,
                    c2 ? (double)n2 / c2 : 1.0, tm * 1e3, tc * 1e3);
    }
    double lr = cv_lines ? (double)matched_lines / cv_lines : 1.0;
    double f1 = cov_cv ? (double)near_cv / cov_cv : 1.0,
           f2 = cov_me ? (double)near_me / cov_me : 1.0;
    std::printf("real photos: %ld of OpenCV's strongest lines matched within one bin (%.3f)\n",
                cv_lines ? matched_lines : 0, lr);
    std::printf("real photos: edge pixels on OpenCV's segments within 2 px of rtedge's %.3f, the "
                "reverse %.3f\n",
                f1, f2);
    std::printf("real photos: HoughLinesP time rtedge %.1f ms, OpenCV %.1f ms (ratio %.2f); lanes "
                "only %.1f vs %.1f ms (ratio %.2f)\n",
                t_me * 1e3, t_cv * 1e3, t_cv > 0 ? t_me / t_cv : 0.0, t_me_lanes * 1e3,
                t_cv_lanes * 1e3, t_cv_lanes > 0 ? t_me_lanes / t_cv_lanes : 0.0);
    check(lr >= 0.95, "standard lines matched %.3f < %.2f", lr, 0.95);
    check(f1 >= 0.90, "coverage of OpenCV's segments by rtedge's %.3f < %.2f", f1, 0.90);
    check(f2 >= 0.90, "coverage of rtedge's segments by OpenCV's %.3f < %.2f", f2, 0.90);
}

} // namespace

int main()
{
    oracle::Tally tally("hough");
    std::mt19937 rng = oracle::make_rng();
    Runner run{tally, rng};
    cv::setNumThreads(1);

    synthetic_lines(run);
    synthetic_segments(run);
    synthetic_circles(run);
    auto inputs = oracle::file_inputs();
    real_photos(run, inputs);

    std::printf("checksum lines %08x segments %08x circles %08x\n", sum_lines, sum_segs,
                sum_circles);
    int rc = tally.finish();
    if (failures)
        std::printf("oracle hough: %d checks failed\n", failures);
    return rc || failures;
}
