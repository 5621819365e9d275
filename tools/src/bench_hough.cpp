// Benchmark cases for the Hough transforms (issue 3). Lines and segments
// run on cv::Canny(grey, 50, 150) of the frame, made before timing; circles
// time the whole of cv::HoughCircles, so the rtedge side includes the Sobel
// derivatives and Canny that OpenCV computes inside.
#include "bench.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/canny.h"
#include "rtedge/gradient.h"
#include "rtedge/hough.h"
}

namespace
{

using bench::Frame;
using bench::Register;
using bench::Runners;
using bench::s16;
using bench::u8;

struct HoughBuffers {
    cv::Mat gray, edges, dx, dy, cedges;
    rte_hough_config cfg;
    std::vector<uint8_t> scratch;
    rte_arena arena;
    std::vector<rte_hough_line> lines;
    std::vector<rte_hough_segment> segments;
    std::vector<rte_hough_circle> circles;
    std::vector<cv::Vec2f> cv_lines;
    std::vector<cv::Vec4i> cv_segments;
    std::vector<cv::Vec3f> cv_circles;
    HoughBuffers(const Frame &f, size_t scratch_bytes)
        : gray(f.gray.clone()), dx(f.gray.size(), CV_16SC1), dy(f.gray.size(), CV_16SC1),
          cedges(f.gray.size(), CV_8UC1), scratch(scratch_bytes + 1), lines(4096), segments(4096),
          circles(256)
    {
        cv::Canny(gray, edges, 50, 150);
        rte_arena_init(&arena, scratch.data(), scratch_bytes);
    }
};

std::shared_ptr<HoughBuffers> make(const Frame &f, size_t (*scratch)(const rte_hough_config &))
{
    rte_hough_config cfg;
    rte_hough_config_init(&cfg, f.gray.cols, f.gray.rows, 1.0, CV_PI / 180, 0.0, CV_PI);
    auto b = std::make_shared<HoughBuffers>(f, scratch(cfg));
    b->cfg = cfg;
    return b;
}

Register lines("hough", "lines (Canny 50/150, threshold 100)", [](const Frame &f) {
    auto b =
        make(f, [](const rte_hough_config &c) { return rte_hough_lines_scratch_size(&c, 4096); });
    return Runners{[b] {
                       rte_image_u8 e = u8(b->edges);
                       int32_t n;
                       bool t;
                       rte_hough_lines(&b->cfg, &e, 100, &b->arena, b->lines.data(), 4096, &n, &t);
                   },
                   [b] { cv::HoughLines(b->edges, b->cv_lines, 1, CV_PI / 180, 100); }};
});

Register segments("hough", "segments (threshold 50, length 30, gap 10)", [](const Frame &f) {
    auto b = make(f, [](const rte_hough_config &c) { return rte_hough_segments_scratch_size(&c); });
    return Runners{[b] {
                       rte_image_u8 e = u8(b->edges);
                       rte_hough_segments_params p = {50, 30, 10, 0};
                       int32_t n;
                       bool t;
                       rte_hough_segments(&b->cfg, &e, &p, &b->arena, b->segments.data(), 4096, &n,
                                          &t);
                   },
                   [b] { cv::HoughLinesP(b->edges, b->cv_segments, 1, CV_PI / 180, 50, 30, 10); }};
});

const rte_hough_circles_params circle_params = {256, 20, 30, 10, 40, 0, 0};

Register circles("hough", "circles (Sobel + Canny 50/100 + transform, r 10..40)",
                 [](const Frame &f) {
                     size_t scratch = std::max(
                         rte_hough_circles_scratch_size(f.gray.cols, f.gray.rows, &circle_params),
                         rte_canny_scratch_size(f.gray.cols, f.gray.rows, 3));
                     auto b = std::make_shared<HoughBuffers>(f, scratch);
                     return Runners{[b] {
                                        rte_image_u8 g = u8(b->gray), e = u8(b->cedges);
                                        rte_image_s16 gx = s16(b->dx), gy = s16(b->dy);
                                        rte_canny_params cp;
                                        rte_canny_params_init(&cp, 50, 100, 3, false);
                                        rte_canny_gradient_u8(&g, &e, &gx, &gy, &cp, &b->arena);
                                        int32_t n;
                                        bool t;
                                        rte_hough_circles(&e, &gx, &gy, &circle_params, &b->arena,
                                                          b->circles.data(), 256, &n, &t);
                                    },
                                    [b] {
                                        cv::HoughCircles(b->gray, b->cv_circles, cv::HOUGH_GRADIENT,
                                                         1, 20, 100, 30, 10, 40);
                                    }};
                 });

} // namespace
