// cv::erode / cv::dilate / cv::morphologyEx(OPEN, CLOSE) with elements from
// cv::getStructuringElement (RECT, CROSS, ELLIPSE, odd and even sizes) and
// custom masks, iterations 1..3, default border, against rtedge.
#include "oracle.hpp"

#include <cstdio>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/morphology.h"
}

static const char *op_name(int op)
{
    static const char *names[] = {"erode", "dilate", "open", "close"};
    return names[op];
}

static void run_opencv(const cv::Mat &src, cv::Mat &dst, int op, const cv::Mat &kernel,
                       int iterations)
{
    if (op == RTE_MORPH_ERODE)
        cv::erode(src, dst, kernel, cv::Point(-1, -1), iterations);
    else if (op == RTE_MORPH_DILATE)
        cv::dilate(src, dst, kernel, cv::Point(-1, -1), iterations);
    else
        cv::morphologyEx(src, dst, op == RTE_MORPH_OPEN ? cv::MORPH_OPEN : cv::MORPH_CLOSE, kernel,
                         cv::Point(-1, -1), iterations);
}

struct Checker {
    oracle::Tally t{"morphology"};
    oracle::Arena scratch;

    void check(const std::string &name, const cv::Mat &gray, int op, const rte_morph_element &e,
               const cv::Mat &kernel, cv::Point anchor, int iterations, std::mt19937 &rng)
    {
        std::string what = name + " " + op_name(op) + " " + std::to_string(e.width) + "x" +
                           std::to_string(e.height) + " it " + std::to_string(iterations);
        cv::Mat expected;
        if (anchor == cv::Point(-1, -1))
            run_opencv(gray, expected, op, kernel, iterations);
        else if (op == RTE_MORPH_ERODE)
            cv::erode(gray, expected, kernel, anchor, iterations);
        else
            cv::dilate(gray, expected, kernel, anchor, iterations);

        size_t need = rte_morphology_scratch_size(gray.cols, gray.rows, &e, iterations);
        scratch.reserve(need);
        rte_arena &arena = scratch.arena;

        std::vector<uint8_t> sbuf, dbuf;
        rte_image_u8 src = oracle::padded_u8(gray, sbuf, rng);
        bool in_place = rng() % 4 == 0;
        rte_image_u8 dst = in_place ? src : oracle::blank_u8(gray.cols, gray.rows, dbuf, rng);
        int st = rte_morphology_u8(&src, &dst, (rte_morph_op)op, &e, iterations, &arena);
        if (st != RTE_OK) {
            t.call_failed(what, st);
            return;
        }
        if (arena.used != 0 || arena.high_water > need) {
            t.call_failed(what + " (arena not reset or overrun)", -1);
            return;
        }
        t.add(what + (in_place ? " in place" : ""), expected, oracle::to_mat(dst));
    }

    void check_shape(const std::string &name, const cv::Mat &gray, int op, int shape, int kw,
                     int kh, int iterations, std::mt19937 &rng)
    {
        rte_morph_element e;
        int st = rte_morphology_element_init(&e, (rte_morph_shape)shape, kw, kh);
        std::string what = name + " shape " + std::to_string(shape);
        if (st != RTE_OK) {
            t.call_failed(what + " element", st);
            return;
        }
        cv::Mat kernel = cv::getStructuringElement(shape, cv::Size(kw, kh));
        // The element itself must equal OpenCV's.
        cv::Mat mask(kh, kw, CV_8UC1, e.mask);
        t.add(what + " element " + std::to_string(kw) + "x" + std::to_string(kh), kernel,
              mask.clone());
        check(what, gray, op, e, kernel, cv::Point(-1, -1), iterations, rng);
    }
};

int main()
{
    Checker c;
    std::mt19937 rng = oracle::make_rng();
    const cv::Size sizes[] = {{3, 3},   {5, 5}, {2, 2},   {4, 6}, {7, 3},   {1, 9}, {9, 1},
                              {15, 15}, {6, 4}, {11, 13}, {1, 1}, {31, 31}, {2, 7}, {14, 10}};
    const int nsizes = (int)(sizeof sizes / sizeof sizes[0]);

    // Every element shape at every size (elements only).
    for (int shape = 0; shape <= 2; shape++)
        for (int kh = 1; kh <= RTE_MORPH_MAX_KSIZE; kh++)
            for (int kw = 1; kw <= RTE_MORPH_MAX_KSIZE; kw++) {
                rte_morph_element e;
                int st = rte_morphology_element_init(&e, (rte_morph_shape)shape, kw, kh);
                if (st != RTE_OK) {
                    c.t.call_failed("element", st);
                    continue;
                }
                c.t.add("element shape " + std::to_string(shape) + " " + std::to_string(kw) + "x" +
                            std::to_string(kh),
                        cv::getStructuringElement(shape, cv::Size(kw, kh)),
                        cv::Mat(kh, kw, CV_8UC1, e.mask).clone());
            }

    // File inputs: every shape x op x iterations 1..3, two sizes per file
    // (the sizes rotate over the files so all of them are covered).
    int file_no = 0;
    for (const auto &in : oracle::file_inputs()) {
        for (int s = 0; s < 2; s++) {
            cv::Size k = sizes[(file_no * 2 + s) % nsizes];
            for (int shape = 0; shape <= 2; shape++)
                for (int op = 0; op <= 3; op++)
                    for (int it = 1; it <= 3; it++)
                        c.check_shape(in.name, in.gray, op, shape, k.width, k.height, it, rng);
        }
        file_no++;
    }

    // Random images: random shape, size, op, iterations; a custom mask with
    // a random anchor now and then.
    for (const auto &in : oracle::random_inputs(rng)) {
        for (int rep = 0; rep < 3; rep++) {
            int op = (int)(rng() % 4), it = 1 + (int)(rng() % 3);
            if (rep == 2) {
                int kw = 1 + (int)(rng() % 9), kh = 1 + (int)(rng() % 9);
                cv::Mat mask(kh, kw, CV_8UC1);
                for (int i = 0; i < kw * kh; i++)
                    mask.data[i] = (uint8_t)(rng() % 3 != 0);
                mask.data[rng() % (unsigned)(kw * kh)] = 1;
                int ax = (int)(rng() % (unsigned)kw), ay = (int)(rng() % (unsigned)kh);
                rte_morph_element e;
                int st = rte_morphology_element_from_mask(&e, mask.data, kw, kh, ax, ay);
                if (st != RTE_OK) {
                    c.t.call_failed(in.name + " mask element", st);
                    continue;
                }
                c.check(in.name + " custom mask anchor " + std::to_string(ax) + "," +
                            std::to_string(ay),
                        in.gray, op & 1, e, mask, cv::Point(ax, ay), it, rng);
                continue;
            }
            int shape = (int)(rng() % 3);
            int kw = 1 + (int)(rng() % 15), kh = 1 + (int)(rng() % 15);
            c.check_shape(in.name, in.gray, op, shape, kw, kh, it, rng);
        }
    }
    return c.t.finish();
}
