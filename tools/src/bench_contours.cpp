// Benchmark cases for contours and shape features (issue 4): border
// following, then every feature of every contour, against OpenCV's calls.
#include "bench.hpp"

#include <memory>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/contours.h"
#include "rtedge/shape.h"
#include "rtedge/threshold.h"
}

namespace
{

using bench::Frame;
using bench::Register;
using bench::Runners;

// The frame binarised once (Otsu), and room for everything.
struct Buffers {
    cv::Mat bin;
    std::vector<rte_point> points, hull, approx;
    std::vector<rte_contour> contours;
    std::vector<int32_t> hull_idx;
    std::vector<rte_defect> defects;
    std::vector<uint8_t> scratch;
    rte_contours out{};
    rte_arena arena{};
    // OpenCV's outputs, reused across runs as a real caller would
    std::vector<std::vector<cv::Point>> cv_contours;
    std::vector<cv::Vec4i> cv_hierarchy;
    std::vector<int> cv_hull;
    std::vector<cv::Vec4i> cv_defects;
    std::vector<cv::Point> cv_approx;
    double sink = 0;

    explicit Buffers(const Frame &f)
    {
        cv::threshold(f.gray, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
        const int32_t w = bin.cols, h = bin.rows;
        const int32_t max_contours = w * h / 2 + 1, max_points = 2 * w * h + 4;
        points.resize(max_points);
        contours.resize(max_contours);
        hull.resize(max_points);
        approx.resize(max_points);
        hull_idx.resize(max_points);
        defects.resize(max_points);
        size_t s = rte_contours_scratch_size(w, h, max_contours);
        s = std::max(s, rte_shape_hull_scratch_size(max_points));
        s = std::max(s, rte_shape_approx_scratch_size(max_points));
        s = std::max(s, rte_shape_min_area_rect_scratch_size(max_points));
        s = std::max(s, rte_shape_enclosing_circle_scratch_size(max_points));
        scratch.resize(s + 1);
        rte_arena_init(&arena, scratch.data(), s);
        out.points = points.data();
        out.contours = contours.data();
        out.max_points = max_points;
        out.max_contours = max_contours;
    }

    void rte_find()
    {
        rte_image_u8 in = bench::u8(bin);
        rte_contours_find(&in, RTE_CONTOURS_LIST, RTE_CONTOURS_APPROX_SIMPLE, &out, &arena);
    }

    void rte_features()
    {
        for (int32_t i = 0; i < out.n_contours; i++) {
            const rte_point *p = out.points + out.contours[i].offset;
            const int32_t n = out.contours[i].count;
            rte_moments m;
            rte_rotated_rect r;
            rte_circle c;
            int32_t nh = 0, nd = 0, na = 0;
            int64_t area2 = rte_shape_area2(p, n);
            int64_t per = rte_shape_perimeter_q16(p, n, 1);
            rte_shape_moments(p, n, &m);
            rte_rect b = rte_shape_bounding_rect(p, n);
            rte_shape_min_area_rect(p, n, &r, &arena);
            rte_shape_enclosing_circle(p, n, &c, &arena);
            rte_shape_convex_hull(p, n, hull_idx.data(), nullptr, &nh, &arena);
            if (n > 3 && nh > 2)
                rte_shape_convexity_defects(p, n, hull_idx.data(), nh, defects.data(), &nd);
            rte_shape_approx_poly(p, n,
                                  (uint32_t)std::min<int64_t>((per * 2 + 50) / 100, (1 << 26) - 1),
                                  approx.data(), &na, &arena);
            sink += (double)(area2 + per + m.s00 + b.width + r.width_q8 + c.r_q8 + nh + nd + na);
        }
    }

    void cv_find()
    {
        cv::findContours(bin, cv_contours, cv_hierarchy, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
    }

    void cv_features()
    {
        for (const auto &c : cv_contours) {
            double area = cv::contourArea(c), per = cv::arcLength(c, true);
            cv::Moments m = cv::moments(c);
            cv::Rect b = cv::boundingRect(c);
            cv::RotatedRect r = cv::minAreaRect(c);
            cv::Point2f center;
            float radius = 0;
            cv::minEnclosingCircle(c, center, radius);
            cv::convexHull(c, cv_hull, false, false);
            cv_defects.clear();
            if (c.size() > 3 && cv_hull.size() > 2) {
                try { // self-intersecting contours make OpenCV throw
                    cv::convexityDefects(c, cv_hull, cv_defects);
                } catch (const cv::Exception &) {
                }
            }
            cv::approxPolyDP(c, cv_approx, 0.02 * per, true);
            sink += area + per + m.m00 + b.width + r.size.width + radius + (double)cv_hull.size() +
                    (double)cv_defects.size() + (double)cv_approx.size();
        }
    }
};

Register find("contours", "findContours list simple", [](const Frame &f) {
    auto b = std::make_shared<Buffers>(f);
    return Runners{[b] { b->rte_find(); }, [b] { b->cv_find(); }};
});

Register features("contours", "findContours + all features", [](const Frame &f) {
    auto b = std::make_shared<Buffers>(f);
    return Runners{[b] {
                       b->rte_find();
                       b->rte_features();
                   },
                   [b] {
                       b->cv_find();
                       b->cv_features();
                   }};
});

} // namespace
