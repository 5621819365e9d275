// Sobel / Scharr / Laplacian to CV_16S and convertScaleAbs against OpenCV 4.6:
// every derivative order and size on every file image, random ones on the
// random images (padded strides on both sides).
#include "oracle.hpp"

#include <cstdio>
#include <string>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/gradient.h"
}

namespace
{

enum Op { SOBEL, SCHARR, LAPLACIAN };

void check(oracle::Tally &t, const std::string &name, const cv::Mat &gray, Op op, int dx, int dy,
           int ksize, rte_arena *arena, std::mt19937 &rng)
{
    cv::Mat expected;
    std::string what = name;
    if (op == SOBEL) {
        cv::Sobel(gray, expected, CV_16S, dx, dy, ksize);
        what += " sobel dx=" + std::to_string(dx) + " dy=" + std::to_string(dy) +
                " k=" + std::to_string(ksize);
    } else if (op == SCHARR) {
        cv::Scharr(gray, expected, CV_16S, dx, dy);
        what += " scharr dx=" + std::to_string(dx) + " dy=" + std::to_string(dy);
    } else {
        cv::Laplacian(gray, expected, CV_16S, ksize);
        what += " laplacian k=" + std::to_string(ksize);
    }
    std::vector<uint8_t> sbuf;
    std::vector<int16_t> dbuf;
    rte_image_u8 src = oracle::padded_u8(gray, sbuf, rng);
    rte_image_s16 dst = oracle::blank_s16(gray.cols, gray.rows, dbuf, rng);
    size_t mark = rte_arena_mark(arena);
    rte_status st = op == SOBEL    ? rte_sobel_s16(&src, &dst, dx, dy, ksize, arena)
                    : op == SCHARR ? rte_scharr_s16(&src, &dst, dx, dy, arena)
                                   : rte_laplacian_s16(&src, &dst, ksize, arena);
    t.check(what, st, arena, mark, expected, dst);
}

void check_abs(oracle::Tally &t, const std::string &what, const cv::Mat &s16, std::mt19937 &rng)
{
    cv::Mat expected;
    cv::convertScaleAbs(s16, expected);
    // Copy into a padded int16 image so stride > width.
    std::vector<int16_t> sbuf;
    rte_image_s16 src = oracle::blank_s16(s16.cols, s16.rows, sbuf, rng);
    for (int y = 0; y < s16.rows; y++)
        std::copy(s16.ptr<int16_t>(y), s16.ptr<int16_t>(y) + s16.cols,
                  src.buf + (size_t)y * src.stride);
    std::vector<uint8_t> dbuf;
    rte_image_u8 dst = oracle::blank_u8(s16.cols, s16.rows, dbuf, rng);
    rte_status st = rte_abs_s16_u8(&src, &dst);
    if (st != RTE_OK) {
        t.call_failed(what, st);
        return;
    }
    t.add(what, expected, oracle::to_mat(dst));
}

} // namespace

int main()
{
    oracle::Tally t("gradient");
    std::mt19937 rng = oracle::make_rng();
    const int sizes[] = {1, 3, 5, 7};
    oracle::Arena scratch(rte_laplacian_scratch_size(8192, 1, 3) +
                          rte_sobel_scratch_size(8192, 1, 7));

    for (const oracle::Input &in : oracle::file_inputs()) {
        for (int k : sizes)
            for (int dy = 0; dy <= 2; dy++)
                for (int dx = 0; dx <= 2; dx++)
                    if (dx + dy > 0)
                        check(t, in.name, in.gray, SOBEL, dx, dy, k, &scratch.arena, rng);
        check(t, in.name, in.gray, SCHARR, 1, 0, 0, &scratch.arena, rng);
        check(t, in.name, in.gray, SCHARR, 0, 1, 0, &scratch.arena, rng);
        check(t, in.name, in.gray, LAPLACIAN, 0, 0, 1, &scratch.arena, rng);
        check(t, in.name, in.gray, LAPLACIAN, 0, 0, 3, &scratch.arena, rng);
        cv::Mat d;
        cv::Sobel(in.gray, d, CV_16S, 1, 1, 7); // large values: saturates
        check_abs(t, in.name + " abs(sobel 7)", d, rng);
    }

    std::vector<oracle::Input> randoms = oracle::random_inputs(rng);
    for (const oracle::Input &in : randoms) {
        int k = sizes[rng() % 4], dx = (int)(rng() % 3), dy = (int)(rng() % 3);
        if (dx + dy == 0)
            dx = 1;
        check(t, in.name, in.gray, SOBEL, dx, dy, k, &scratch.arena, rng);
        int sx = (int)(rng() & 1);
        check(t, in.name, in.gray, SCHARR, sx, 1 - sx, 0, &scratch.arena, rng);
        check(t, in.name, in.gray, LAPLACIAN, 0, 0, (rng() & 1) ? 3 : 1, &scratch.arena, rng);
        // Every small size with every kernel: borders folded more than once.
        if (in.gray.cols <= 8 || in.gray.rows <= 8)
            for (int kk : sizes)
                for (int ddy = 0; ddy <= 2; ddy++)
                    for (int ddx = 0; ddx <= 2; ddx++)
                        if (ddx + ddy > 0)
                            check(t, in.name, in.gray, SOBEL, ddx, ddy, kk, &scratch.arena, rng);
        cv::Mat s16(in.gray.rows, in.gray.cols, CV_16S);
        cv::randu(s16, -32768, 32768);
        if (rng() & 1)
            s16.at<int16_t>(0, 0) = -32768;
        check_abs(t, in.name + " abs(random)", s16, rng);
    }
    return t.finish();
}
