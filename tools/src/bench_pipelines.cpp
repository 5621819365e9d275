// Benchmark cases for the pipelines (issue 5): the grasp path end to end
// against the same pipeline written with OpenCV calls (single thread).
#include "bench.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/grasp.h"
}

namespace
{

using bench::Frame;
using bench::Register;
using bench::Runners;

struct GraspBench {
    cv::Mat gray, blurred, bin;
    rte_grasp_ctx *ctx = nullptr;
    rte_grasp_result result{};
    // OpenCV's side: the same stages, the same features per object
    std::vector<std::vector<cv::Point>> contours;
    std::vector<cv::Point> hull, approx;
    struct Object {
        double area;
        cv::Point2d center;
        cv::RotatedRect box;
        double solidity;
        int vertices, vertices_coarse;
    };
    std::vector<Object> objects;

    explicit GraspBench(const Frame &f) : gray(f.gray.clone())
    {
        rte_grasp_config c;
        rte_grasp_config_default(&c);
        c.max_width = gray.cols;
        c.max_height = gray.rows;
        rte_grasp_create(&c, &ctx);
    }
    ~GraspBench() { rte_grasp_destroy(ctx); }

    void rte()
    {
        rte_image_u8 in = bench::u8(gray);
        rte_grasp_process(ctx, &in, &result);
    }

    void opencv()
    {
        cv::GaussianBlur(gray, blurred, cv::Size(5, 5), 0);
        double t = cv::threshold(blurred, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
        // objects are on the side of the threshold the border is not
        cv::Scalar border = (cv::mean(blurred.row(0)) + cv::mean(blurred.row(blurred.rows - 1)) +
                             cv::mean(blurred.col(0)) + cv::mean(blurred.col(blurred.cols - 1))) /
                            4;
        if (border[0] > t)
            cv::threshold(blurred, bin, t, 255, cv::THRESH_BINARY_INV);
        cv::findContours(bin, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
        objects.clear();
        for (const auto &c : contours) {
            double area = cv::contourArea(c);
            if (area < 100)
                continue;
            cv::Moments m = cv::moments(c);
            double per = cv::arcLength(c, true);
            cv::convexHull(c, hull);
            double hull_area = cv::contourArea(hull);
            double hull_per = cv::arcLength(hull, true);
            cv::approxPolyDP(c, approx, 0.02 * per, true);
            int v = (int)approx.size();
            cv::approxPolyDP(c, approx, 0.04 * per, true);
            cv::Point2f cc;
            float r;
            cv::minEnclosingCircle(c, cc, r);
            cv::Rect b = cv::boundingRect(c);
            Object o{area,
                     {m.m10 / m.m00, m.m01 / m.m00},
                     cv::minAreaRect(c),
                     hull_area > 0 ? area / hull_area + 0 * (hull_per + r + b.width) : 0,
                     v,
                     (int)approx.size()};
            objects.push_back(o);
        }
        std::sort(objects.begin(), objects.end(),
                  [](const Object &a, const Object &b) { return a.area > b.area; });
        if (objects.size() > 64)
            objects.resize(64);
    }
};

} // namespace

bench::Runners bench::grasp_path_runners(const Frame &f)
{
    auto b = std::make_shared<GraspBench>(f);
    return Runners{[b] { b->rte(); }, [b] { b->opencv(); }};
}

static Register grasp("pipeline", "grasp (blur 5, otsu, external contours, features)",
                      bench::grasp_path_runners);

// What the daemon runs on every frame: the lane path on the colour frame,
// then the grasp path on the grey one.
static Register end_to_end("pipeline", "end to end (lane + grasp)", [](const Frame &f) {
    Runners lane = bench::lane_path_runners(f), grasp = bench::grasp_path_runners(f);
    return Runners{[lane, grasp] {
                       lane.rtedge();
                       grasp.rtedge();
                   },
                   [lane, grasp] {
                       lane.opencv();
                       grasp.opencv();
                   }};
});
