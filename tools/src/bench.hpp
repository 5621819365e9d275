// tools/bench: rtedge against OpenCV 4.6 on the same frames, in one process.
//
// A benchmark case names a stage and gives two closures that process one
// prepared frame: one with rtedge, one with OpenCV. The driver runs rtedge,
// OpenCV on one thread and OpenCV with its default threads interleaved on
// every frame, many rounds, and reports the median times and the ratios.
#ifndef RTEDGE_TOOLS_BENCH_HPP
#define RTEDGE_TOOLS_BENCH_HPP

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

extern "C" {
#include "rtedge/image.h"
}

namespace bench {

// rtedge views of an OpenCV image's pixels (strides in elements).
inline rte_image_u8 u8(cv::Mat &m) { return rte_image_u8{m.cols, m.rows, (int32_t)m.step1(), m.ptr<uint8_t>()}; }
inline rte_image_s16 s16(cv::Mat &m) { return rte_image_s16{m.cols, m.rows, (int32_t)m.step1(), m.ptr<int16_t>()}; }

// One frame at one size, in the forms the cases need.
struct Frame {
    std::string name;
    cv::Mat bgr;  // CV_8UC3
    cv::Mat gray; // CV_8UC1, = cvtColor(bgr, BGR2GRAY)
};

// A runner works on one frame; `prepare` is called once per frame before
// timing (outside the timed region) and returns the two timed closures.
struct Runners {
    std::function<void()> rtedge;
    std::function<void()> opencv;
};

struct Case {
    std::string group; // e.g. "kernels"
    std::string name;  // e.g. "gaussian 5x5"
    std::function<Runners(const Frame &)> prepare;
};

// Cases register themselves from the bench_*.cpp files at start-up.
std::vector<Case> &registry();
struct Register {
    Register(std::string group, std::string name, std::function<Runners(const Frame &)> prepare);
};

// The two pipelines (bench_lanes.cpp, bench_pipelines.cpp), also run
// together as the end-to-end case.
Runners lane_path_runners(const Frame &f);
Runners grasp_path_runners(const Frame &f);

} // namespace bench

#endif
