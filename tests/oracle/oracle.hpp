// Shared harness for the OpenCV 4.6 oracle tests: the images every kernel is
// checked on (fixtures/, ../shared/data/real/, and random images), views of
// cv::Mat as rtedge images, and the pixel comparison that must come out 0.
#ifndef RTEDGE_TESTS_ORACLE_HPP
#define RTEDGE_TESTS_ORACLE_HPP

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

extern "C" {
#include "rtedge/arena.h"
#include "rtedge/image.h"
}

namespace oracle {

// Caller-owned scratch for the kernels: memory behind an rte_arena.
// reserve(n) makes it exactly n bytes long (growing the memory when
// needed), so a kernel that asks for more than its *_scratch_size fails.
struct Arena {
    std::vector<uint8_t> memory;
    rte_arena arena;
    explicit Arena(size_t bytes = 0) { reserve(bytes); }
    void reserve(size_t bytes)
    {
        if (memory.size() < bytes)
            memory.resize(bytes);
        rte_arena_init(&arena, memory.data(), bytes);
    }
};

// One input image: a name for messages and its 8-bit pixels.
struct Input {
    std::string name;
    cv::Mat gray; // CV_8UC1
    cv::Mat bgr;  // CV_8UC3 (for colour kernels); grey replicated for random images
};

// Every image file in $RTE_FIXTURES_DIR (not its subfolders) and under
// $RTE_SHARED_DATA_DIR (png, jpg, pgm, ppm), read the way cv2.imread +
// cvtColor(BGR2GRAY) does. A missing folder is reported on stderr and
// skipped.
std::vector<Input> file_inputs();

// Random test images: the count comes from $RTE_ORACLE_RANDOM (default 200),
// the seed from $RTE_ORACLE_SEED (default 20261122). Sizes run from 1x1 to
// 1280x720 with small and thin images over-represented; content is noise,
// gradients, blocks, sparse dots, constants (0, 255, other) or blurred noise.
std::vector<Input> random_inputs(std::mt19937 &rng);
std::mt19937 make_rng();
int random_count();

// Copies `m` into memory with extra row padding (random 0..37 elements) so
// every kernel is exercised with stride > width. `storage` owns the memory.
rte_image_u8 padded_u8(const cv::Mat &m, std::vector<uint8_t> &storage, std::mt19937 &rng);
rte_image_u8 view_u8(cv::Mat &m);
rte_image_s16 view_s16(cv::Mat &m);
// A destination image of the given size with padding, filled with 0xA5 so
// untouched pixels show up.
rte_image_u8 blank_u8(int w, int h, std::vector<uint8_t> &storage, std::mt19937 &rng);
rte_image_s16 blank_s16(int w, int h, std::vector<int16_t> &storage, std::mt19937 &rng);
// Copy of an rtedge image as a cv::Mat (for comparison).
cv::Mat to_mat(const rte_image_u8 &img);
cv::Mat to_mat(const rte_image_s16 &img);

// Counts differing elements; on a difference prints the case and the first
// few differing positions.
long diff(const std::string &what, const cv::Mat &expected, const cv::Mat &actual);

// Tally of cases and differences for a suite; finish() prints
// "oracle NAME: C cases, D differing pixels" and returns the exit code.
struct Tally {
    std::string suite;
    long cases = 0;
    long differing = 0;
    long failed_calls = 0;
    explicit Tally(std::string s) : suite(std::move(s)) {}
    void add(const std::string &what, const cv::Mat &expected, const cv::Mat &actual);
    // One kernel call into a blank_u8/blank_s16 destination: its status,
    // that the arena is back at `mark` (arena may be NULL), the pixels
    // against OpenCV's, and that the destination's row padding is untouched.
    void check(const std::string &what, int status, const rte_arena *arena, size_t mark,
               const cv::Mat &expected, const rte_image_u8 &dst);
    void check(const std::string &what, int status, const rte_arena *arena, size_t mark,
               const cv::Mat &expected, const rte_image_s16 &dst);
    void call_failed(const std::string &what, int status);
    int finish() const;
};

} // namespace oracle

#endif
