// Benchmark cases for the image kernels of issue 2: each rtedge kernel
// against the OpenCV call it reproduces bit for bit.
#include "bench.hpp"

#include <memory>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/blur.h"
#include "rtedge/canny.h"
#include "rtedge/color.h"
#include "rtedge/gradient.h"
#include "rtedge/morphology.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/threshold.h"
}

namespace
{

using bench::Frame;
using bench::Register;
using bench::Runners;
using bench::s16;
using bench::u8;

// Per-frame buffers shared by a case's two closures (kept alive by them).
struct Buffers {
    cv::Mat src, out, out2, s16a, s16b, mask;
    std::vector<uint8_t> scratch;
    rte_arena arena;
    explicit Buffers(const Frame &f, size_t scratch_bytes)
        : src(f.gray.clone()), out(f.gray.size(), CV_8UC1), out2(f.gray.size(), CV_8UC1),
          s16a(f.gray.size(), CV_16SC1), s16b(f.gray.size(), CV_16SC1),
          mask(f.gray.size(), CV_8UC1), scratch(scratch_bytes + 1)
    {
        rte_arena_init(&arena, scratch.data(), scratch_bytes);
    }
};

std::shared_ptr<Buffers> buffers(const Frame &f, size_t scratch)
{
    return std::make_shared<Buffers>(f, scratch);
}

Register gray("kernels", "bgr to grey", [](const Frame &f) {
    auto b = buffers(f, 0);
    auto bgr = std::make_shared<cv::Mat>(f.bgr.clone());
    return Runners{
        [b, bgr] {
            rte_image_u8c3 in{bgr->cols, bgr->rows, (int32_t)bgr->step, bgr->ptr<uint8_t>()};
            rte_image_u8 out = u8(b->out);
            rte_color_bgr_to_gray(&in, &out);
        },
        [b, bgr] { cv::cvtColor(*bgr, b->out2, cv::COLOR_BGR2GRAY); }};
});

void register_gaussian(int ksize)
{
    static std::vector<Register> regs;
    regs.emplace_back(
        "kernels", "gaussian " + std::to_string(ksize) + "x" + std::to_string(ksize),
        [ksize](const Frame &f) {
            rte_gaussian_kernel k;
            rte_gaussian_kernel_init(&k, ksize, ksize, 0, 0);
            auto b = buffers(f, rte_gaussian_blur_u8_scratch_size(f.gray.cols, f.gray.rows, &k));
            return Runners{
                [b, k] {
                    rte_image_u8 in = u8(b->src), out = u8(b->out);
                    rte_gaussian_blur_u8(&in, &out, &k, &b->arena);
                },
                [b, ksize] { cv::GaussianBlur(b->src, b->out2, cv::Size(ksize, ksize), 0); }};
        });
}

struct GaussianCases {
    GaussianCases()
    {
        register_gaussian(3);
        register_gaussian(5);
        register_gaussian(9);
    }
} gaussian_cases;

Register median("kernels", "median 5x5", [](const Frame &f) {
    auto b = buffers(f, rte_median_blur_u8_scratch_size(f.gray.cols, f.gray.rows, 5));
    return Runners{[b] {
                       rte_image_u8 in = u8(b->src), out = u8(b->out);
                       rte_median_blur_u8(&in, &out, 5, &b->arena);
                   },
                   [b] { cv::medianBlur(b->src, b->out2, 5); }};
});

Register sobel("kernels", "sobel dx 3x3", [](const Frame &f) {
    auto b = buffers(f, rte_sobel_scratch_size(f.gray.cols, f.gray.rows, 3));
    return Runners{[b] {
                       rte_image_u8 in = u8(b->src);
                       rte_image_s16 out = s16(b->s16a);
                       rte_sobel_s16(&in, &out, 1, 0, 3, &b->arena);
                   },
                   [b] { cv::Sobel(b->src, b->s16b, CV_16S, 1, 0, 3); }};
});

Register canny("kernels", "canny 50/150 L1", [](const Frame &f) {
    rte_canny_params p;
    rte_canny_params_init(&p, 50, 150, 3, false);
    auto b = buffers(f, rte_canny_scratch_size(f.gray.cols, f.gray.rows, 3));
    return Runners{[b, p] {
                       rte_image_u8 in = u8(b->src), out = u8(b->out);
                       rte_canny_u8(&in, &out, &p, &b->arena);
                   },
                   [b] { cv::Canny(b->src, b->out2, 50, 150, 3, false); }};
});

Register threshold_otsu("kernels", "threshold otsu", [](const Frame &f) {
    rte_threshold_params p;
    rte_threshold_params_init(&p, RTE_THRESH_BINARY, 0, 255, true);
    auto b = buffers(f, 0);
    return Runners{
        [b, p] {
            rte_image_u8 in = u8(b->src), out = u8(b->out);
            int32_t t;
            rte_threshold_u8(&in, &out, &p, &t);
        },
        [b] { cv::threshold(b->src, b->out2, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU); }};
});

void register_morphology(rte_morph_shape shape, int cv_shape, const char *name)
{
    static std::vector<Register> regs;
    regs.emplace_back(
        "kernels", std::string("dilate 5x5 ") + name, [shape, cv_shape](const Frame &f) {
            rte_morph_element e;
            rte_morphology_element_init(&e, shape, 5, 5);
            auto b = buffers(f, rte_morphology_scratch_size(f.gray.cols, f.gray.rows, &e, 1));
            cv::Mat k = cv::getStructuringElement(cv_shape, cv::Size(5, 5));
            return Runners{[b, e] {
                               rte_image_u8 in = u8(b->src), out = u8(b->out);
                               rte_morphology_dilate_u8(&in, &out, &e, 1, &b->arena);
                           },
                           [b, k] { cv::dilate(b->src, b->out2, k); }};
        });
}

struct MorphologyCases {
    MorphologyCases()
    {
        register_morphology(RTE_MORPH_RECT, cv::MORPH_RECT, "rect");
        register_morphology(RTE_MORPH_ELLIPSE, cv::MORPH_ELLIPSE, "ellipse");
    }
} morphology_cases;

Register roi_mask("kernels", "polygon mask + apply", [](const Frame &f) {
    int w = f.gray.cols, h = f.gray.rows;
    auto pts = std::make_shared<std::vector<cv::Point>>(std::vector<cv::Point>{
        {0, h}, {w * 45 / 100, h * 6 / 10}, {w * 55 / 100, h * 6 / 10}, {w, h}});
    auto b = buffers(f, rte_polygon_mask_scratch_size(4));
    return Runners{[b, pts] {
                       rte_vertex v[4];
                       for (int i = 0; i < 4; i++)
                           v[i] = rte_vertex{(*pts)[i].x, (*pts)[i].y};
                       rte_polygon poly{v, 4};
                       rte_image_u8 in = u8(b->src), out = u8(b->out);
                       rte_polygon_keep_u8(&in, &poly, 1, &out, &b->arena);
                   },
                   [b, pts] {
                       b->mask.setTo(0);
                       cv::fillPoly(b->mask, std::vector<std::vector<cv::Point>>{*pts}, 255);
                       cv::bitwise_and(b->src, b->mask, b->out2);
                   }};
});

} // namespace
