// The lane path end to end (rte_lane_process on a BGR frame) against the
// same pipeline written with OpenCV as the lane tutorials do: cvtColor,
// GaussianBlur 5x5, Canny 50/150, fillPoly + bitwise_and with the same ROI
// trapezoid, HoughLinesP with the same parameters, then the same slope
// filter and length-weighted least-squares fit (with one outlier pass) in
// plain C++ doubles. Single thread. Also the lane path's Hough stage alone
// against cv::HoughLinesP on the same edge map.
//
// Differences worth knowing when reading the ratio: rtedge also computes
// its colour cue and its automatic (median) Canny thresholds each frame,
// and blurs and runs Canny on the ROI's bounding box only (the OpenCV
// version processes the whole frame, as the tutorials do).
#include "bench.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/lane.h"
}

namespace
{

using bench::Frame;
using bench::Register;
using bench::Runners;

struct CvLane {
    bool found = false;
    double x_bottom = 0, x_top = 0;
};

// x = a*y + b by length-weighted least squares over segments (each taken as
// its two end points), one pass dropping segments farther than tol.
CvLane fit_side(const std::vector<cv::Vec4i> &segs, int y_bottom, int y_top, double tol)
{
    CvLane out;
    std::vector<cv::Vec4i> use = segs;
    for (int pass = 0; pass < 2 && !use.empty(); pass++) {
        double w = 0, sy = 0, sx = 0, syy = 0, sxy = 0;
        for (const auto &s : use) {
            double len = std::hypot(s[2] - s[0], s[3] - s[1]);
            for (int e = 0; e < 2; e++) {
                double x = s[2 * e], y = s[2 * e + 1];
                w += len, sx += len * x, sy += len * y, syy += len * y * y, sxy += len * x * y;
            }
        }
        double det = w * syy - sy * sy;
        if (det <= 0)
            return out;
        double a = (w * sxy - sx * sy) / det, b = (sx - a * sy) / w;
        out = CvLane{true, a * y_bottom + b, a * y_top + b};
        std::vector<cv::Vec4i> kept;
        for (const auto &s : use)
            if (std::fabs(s[0] - (a * s[1] + b)) <= tol && std::fabs(s[2] - (a * s[3] + b)) <= tol)
                kept.push_back(s);
        use.swap(kept);
    }
    return out;
}

// The tutorial's edge map: grey, 5x5 Gaussian blur, Canny 50/150, then
// only the pixels inside the ROI trapezoid.
struct CvLaneEdges {
    cv::Mat gray, blurred, edges, mask, masked;
    std::vector<cv::Point> roi;

    CvLaneEdges(const Frame &f, const rte_lane_params &p)
    {
        std::vector<rte_vertex> px(p.roi_count);
        rte_polygon_from_fractions(p.roi, p.roi_count, f.bgr.cols, f.bgr.rows, px.data());
        for (const auto &v : px)
            roi.emplace_back(v.x, v.y);
        mask = cv::Mat::zeros(f.bgr.size(), CV_8UC1);
        std::vector<std::vector<cv::Point>> polys{roi};
        cv::fillPoly(mask, polys, 255);
    }

    void run(const cv::Mat &bgr)
    {
        cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
        cv::GaussianBlur(gray, blurred, cv::Size(5, 5), 0);
        cv::Canny(blurred, edges, 50, 150);
        masked = cv::Mat::zeros(edges.size(), CV_8UC1);
        cv::bitwise_and(edges, mask, masked);
    }
};

struct CvPipeline {
    CvLaneEdges in;
    rte_lane_params p;
    std::vector<cv::Vec4i> lines, left, right;
    CvLane lanes[2];

    CvPipeline(const Frame &f, const rte_lane_config &cfg) : in(f, cfg.params), p(cfg.params) {}

    void run(const cv::Mat &bgr)
    {
        in.run(bgr);
        cv::HoughLinesP(in.masked, lines, 1, CV_PI / 180, p.hough_threshold, p.min_length,
                        p.max_gap);
        left.clear();
        right.clear();
        const int w = bgr.cols;
        for (const auto &l : lines) {
            int dx = l[2] - l[0], dy = l[3] - l[1];
            if (dx == 0)
                continue;
            double slope = (double)dy / dx;
            if (std::fabs(slope) < p.left_min_slope_q8 / 256.0)
                continue;
            if (slope < 0 && l[0] + l[2] < w)
                left.push_back(l);
            else if (slope > 0 && l[0] + l[2] >= w)
                right.push_back(l);
        }
        int y_top = bgr.rows;
        for (const auto &v : in.roi)
            y_top = std::min(y_top, v.y);
        lanes[0] = fit_side(left, bgr.rows - 1, y_top, p.outlier_px);
        lanes[1] = fit_side(right, bgr.rows - 1, y_top, p.outlier_px);
    }
};

struct RteState {
    rte_lane_context *ctx = nullptr;
    cv::Mat bgr;
    rte_lane_result result{};
    ~RteState() { rte_lane_destroy(ctx); }
};

} // namespace

bench::Runners bench::lane_path_runners(const Frame &f)
{
    rte_lane_config cfg;
    rte_lane_config_default(&cfg, f.bgr.cols, f.bgr.rows);
    auto r = std::make_shared<RteState>();
    if (rte_lane_create(&cfg, &r->ctx) != RTE_OK)
        throw std::runtime_error("rte_lane_create failed");
    r->bgr = f.bgr.clone();
    auto cv_side = std::make_shared<CvPipeline>(f, cfg);
    auto bgr = std::make_shared<cv::Mat>(f.bgr.clone());
    return Runners{[r] {
                       rte_frame fr{RTE_PIXEL_BGR24,
                                    r->bgr.cols,
                                    r->bgr.rows,
                                    {r->bgr.ptr<uint8_t>(), nullptr},
                                    {(int32_t)r->bgr.step, 0}};
                       rte_lane_reset(r->ctx); // every frame judged on its own, as the OpenCV side
                       rte_lane_process(r->ctx, &fr, 0, &r->result);
                   },
                   [cv_side, bgr] { cv_side->run(*bgr); }};
}

static Register lane_path("pipeline", "lane path (rte_lane_process vs OpenCV lane tutorial)",
                          bench::lane_path_runners);

namespace
{

// The Hough stage alone, as the lane path runs it: the tutorial's edge map
// (made before timing), the lane parameters for the frame height (threshold,
// minimum length, gap, seed), against cv::HoughLinesP with the same
// parameters on the same map. The output holds 4096 segments, so the search
// is not cut short where OpenCV's goes on (rte_lane_create's default is 512;
// the preparation checks). The generic segments case (bench_hough.cpp) runs
// on unmasked edges instead.
struct LaneSegments {
    rte_lane_config cfg;
    CvLaneEdges in;
    rte_hough_config hough;
    std::vector<uint8_t> scratch;
    rte_arena arena;
    std::vector<rte_hough_segment> segments;
    std::vector<cv::Vec4i> cv_segments;
    bool truncated = false;
    LaneSegments(const Frame &f, const rte_lane_config &c) : cfg(c), in(f, c.params), segments(4096)
    {
        in.run(f.bgr);
        if (rte_hough_config_init(&hough, f.bgr.cols, f.bgr.rows, 1.0, CV_PI / 180, 0.0, CV_PI) !=
            RTE_OK)
            throw std::runtime_error("rte_hough_config_init failed");
        scratch.resize(rte_hough_segments_scratch_size(&hough));
        rte_arena_init(&arena, scratch.data(), scratch.size());
        if (run_rtedge() != RTE_OK || truncated) // either would time as faster
            throw std::runtime_error("rte_hough_segments failed or filled its output");
    }

    rte_status run_rtedge()
    {
        const rte_lane_params &p = cfg.params;
        const rte_hough_segments_params hp = {p.hough_threshold, p.min_length, p.max_gap,
                                              p.hough_seed};
        rte_image_u8 e = bench::u8(in.masked);
        int32_t n;
        return rte_hough_segments(&hough, &e, &hp, &arena, segments.data(),
                                  (int32_t)segments.size(), &n, &truncated);
    }

    void run_opencv()
    {
        const rte_lane_params &p = cfg.params;
        cv::HoughLinesP(in.masked, cv_segments, 1, CV_PI / 180, p.hough_threshold, p.min_length,
                        p.max_gap);
    }
};

Register lane_segments("hough", "segments, lane path (tutorial's ROI edges, lane parameters)",
                       [](const Frame &f) {
                           rte_lane_config cfg;
                           rte_lane_config_default(&cfg, f.bgr.cols, f.bgr.rows);
                           auto b = std::make_shared<LaneSegments>(f, cfg);
                           return Runners{[b] { b->run_rtedge(); }, [b] { b->run_opencv(); }};
                       });

} // namespace
