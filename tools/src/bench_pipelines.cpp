// Benchmark cases for the pipelines: the grasp path end to end against the
// same pipeline written with OpenCV calls (single thread), in the OpenCV
// tutorial's form (Otsu, no split, border objects kept) and with the grasp
// path's defaults (the table's light subtracted, both sides, hysteresis,
// touching objects split, border objects dropped).
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
    bool defaults; // the grasp path's defaults, else the tutorial's
    cv::Mat gray, blurred, bin, grid, table, diff, bright, dark, labels, keep, dist, markers;
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

    GraspBench(const Frame &f, bool use_defaults) : defaults(use_defaults), gray(f.gray.clone())
    {
        rte_grasp_config c;
        rte_grasp_config_default(&c);
        c.max_width = gray.cols;
        c.max_height = gray.rows;
        if (!defaults) {
            c.params.binarize = RTE_GRASP_OTSU;
            c.params.split = 0;
            c.params.skip_border = 0;
        }
        rte_grasp_create(&c, &ctx);
    }
    ~GraspBench() { rte_grasp_destroy(ctx); }

    void rte()
    {
        rte_image_u8 in = bench::u8(gray);
        rte_grasp_process(ctx, &in, &result);
    }

    // One side of the difference: regions beyond low (8-connected) that
    // have a pixel beyond high, as 255 in `out`.
    void hysteresis(const cv::Mat &side, double low, double high, cv::Mat &out)
    {
        cv::Mat weak = side > low;
        int n = cv::connectedComponents(weak, labels, 8, CV_32S);
        std::vector<uint8_t> strong(n, 0);
        for (int y = 0; y < side.rows; y++) {
            const uint8_t *s = side.ptr<uint8_t>(y);
            const int *l = labels.ptr<int>(y);
            for (int x = 0; x < side.cols; x++)
                if (s[x] > high)
                    strong[l[x]] = 255;
        }
        strong[0] = 0;
        out.create(side.size(), CV_8U);
        for (int y = 0; y < side.rows; y++) {
            const int *l = labels.ptr<int>(y);
            uint8_t *o = out.ptr<uint8_t>(y);
            for (int x = 0; x < side.cols; x++)
                o[x] = strong[l[x]];
        }
    }

    // The grasp path's binarisation in OpenCV calls: the table from a grid
    // of cell means (INTER_AREA) with a median over 9 x 9 cells, the
    // difference both ways with Otsu's threshold and hysteresis.
    void background_binary()
    {
        const int cell = std::max(4, blurred.cols / 40);
        cv::resize(blurred, grid,
                   cv::Size((blurred.cols + cell - 1) / cell, (blurred.rows + cell - 1) / cell), 0,
                   0, cv::INTER_AREA);
        cv::medianBlur(grid, grid, 9);
        cv::resize(grid, table, blurred.size(), 0, 0, cv::INTER_LINEAR);
        cv::absdiff(blurred, table, diff);
        double high =
            std::max(20.0, cv::threshold(diff, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
        cv::subtract(blurred, table, bright);
        cv::subtract(table, blurred, dark);
        hysteresis(bright, high * 2 / 3, high, bin);
        hysteresis(dark, high * 2 / 3, high, keep);
        cv::bitwise_or(bin, keep, bin);
    }

    // Touching objects apart, as the OpenCV tutorial on watershed does: for
    // each contour of solidity below 0.95 (within the grasp path's size
    // limits), markers where the distance exceeds 0.6 of its peak,
    // cv::watershed on the crop, ridges cleared.
    void split()
    {
        cv::findContours(bin, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
        for (const auto &c : contours) {
            const double area = cv::contourArea(c);
            if (area < 200)
                continue;
            cv::convexHull(c, hull);
            if (area >= 0.95 * cv::contourArea(hull))
                continue;
            // the grasp path's limits: a quarter of the frame, twice the
            // gripper's 160 px opening across
            cv::Rect r = cv::boundingRect(c) & cv::Rect(0, 0, bin.cols, bin.rows);
            cv::RotatedRect box = cv::minAreaRect(c);
            if (4.0 * r.area() > (double)bin.total() ||
                std::min(box.size.width, box.size.height) > 320)
                continue;
            cv::Mat crop = bin(r);
            cv::distanceTransform(crop, dist, cv::DIST_L2, 3);
            double peak;
            cv::minMaxLoc(dist, nullptr, &peak);
            cv::Mat sure = dist > 0.6 * peak;
            int n = cv::connectedComponents(sure, markers, 8, CV_32S);
            if (n < 3)
                continue;
            cv::Mat colour;
            cv::cvtColor(blurred(r), colour, cv::COLOR_GRAY2BGR);
            markers.setTo(n, crop == 0); // the table around: one more basin
            cv::watershed(colour, markers);
            crop.setTo(0, markers == -1);
        }
    }

    void opencv()
    {
        cv::GaussianBlur(gray, blurred, cv::Size(5, 5), 0);
        if (defaults) {
            background_binary();
            split();
            features(true);
            return;
        }
        double t = cv::threshold(blurred, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
        // objects are on the side of the threshold the border is not
        cv::Scalar border = (cv::mean(blurred.row(0)) + cv::mean(blurred.row(blurred.rows - 1)) +
                             cv::mean(blurred.col(0)) + cv::mean(blurred.col(blurred.cols - 1))) /
                            4;
        if (border[0] > t)
            cv::threshold(blurred, bin, t, 255, cv::THRESH_BINARY_INV);
        features(false);
    }

    void features(bool skip_border)
    {
        cv::findContours(bin, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
        objects.clear();
        for (const auto &c : contours) {
            double area = cv::contourArea(c);
            if (area < 100)
                continue;
            if (skip_border) {
                cv::Rect b = cv::boundingRect(c);
                if (b.x == 0 || b.y == 0 || b.x + b.width == bin.cols || b.y + b.height == bin.rows)
                    continue;
            }
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
    auto b = std::make_shared<GraspBench>(f, true);
    return Runners{[b] { b->rte(); }, [b] { b->opencv(); }};
}

static Register grasp_tutorial("pipeline", "grasp, tutorial (blur 5, otsu, contours, features)",
                               [](const Frame &f) {
                                   auto b = std::make_shared<GraspBench>(f, false);
                                   return Runners{[b] { b->rte(); }, [b] { b->opencv(); }};
                               });
static Register grasp("pipeline", "grasp (blur 5, table subtracted, split, features)",
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
