// Frame to grey against OpenCV 4.6's cvtColor: BGR24, RGB24, YUYV, UYVY,
// NV12 and GREY frames built from every file input and every random image,
// with padded strides, through rte_frame_to_gray and the specific functions.
#include "oracle.hpp"

#include <cstring>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/color.h"
}

namespace
{

int uniform(std::mt19937 &rng, int lo, int hi)
{
    return std::uniform_int_distribution<int>(lo, hi)(rng);
}

// A copy of `m` (any channel count) with rows `pad` bytes longer than needed.
struct Padded {
    std::vector<uint8_t> bytes;
    int32_t stride = 0;
    uint8_t *data() { return bytes.data(); }
};

Padded pad_copy(const cv::Mat &m, std::mt19937 &rng)
{
    Padded p;
    size_t row = m.cols * m.elemSize();
    p.stride = (int32_t)row + uniform(rng, 0, 3) * uniform(rng, 0, 37);
    p.bytes.assign((size_t)p.stride * m.rows + 1, 0x5A);
    for (int y = 0; y < m.rows; y++)
        std::memcpy(p.bytes.data() + (size_t)y * p.stride, m.ptr(y), row);
    return p;
}

struct Checker {
    oracle::Tally &t;
    std::mt19937 &rng;

    // rte_frame_to_gray on `frame` into a padded destination, against expected.
    void frame(const std::string &what, const rte_frame &f, const cv::Mat &expected)
    {
        std::vector<uint8_t> storage;
        rte_image_u8 dst = oracle::blank_u8(f.width, f.height, storage, rng);
        rte_status st = rte_frame_to_gray(&f, &dst);
        if (st != RTE_OK)
            t.call_failed(what + " frame_to_gray", st);
        else
            t.add(what + " frame_to_gray", expected, oracle::to_mat(dst));
    }

    void image(const std::string &what, rte_status st, const rte_image_u8 &dst,
               const cv::Mat &expected)
    {
        if (st != RTE_OK)
            t.call_failed(what, st);
        else
            t.add(what, expected, oracle::to_mat(dst));
    }

    // BGR24 and RGB24 from the same 3-channel bytes.
    void three_channel(const std::string &name, const cv::Mat &bgr)
    {
        int w = bgr.cols, h = bgr.rows;
        Padded p = pad_copy(bgr, rng);
        rte_image_u8c3 src{w, h, p.stride, p.data()};
        cv::Mat expected_bgr, expected_rgb;
        cv::cvtColor(bgr, expected_bgr, cv::COLOR_BGR2GRAY);
        cv::cvtColor(bgr, expected_rgb, cv::COLOR_RGB2GRAY);

        std::vector<uint8_t> storage;
        rte_image_u8 dst = oracle::blank_u8(w, h, storage, rng);
        image(name + " bgr_to_gray", rte_color_bgr_to_gray(&src, &dst), dst, expected_bgr);
        dst = oracle::blank_u8(w, h, storage, rng);
        image(name + " rgb_to_gray", rte_color_rgb_to_gray(&src, &dst), dst, expected_rgb);

        frame(name + " BGR24", rte_frame{RTE_PIXEL_BGR24, w, h, {p.data(), nullptr}, {p.stride, 0}},
              expected_bgr);
        frame(name + " RGB24", rte_frame{RTE_PIXEL_RGB24, w, h, {p.data(), nullptr}, {p.stride, 0}},
              expected_rgb);
    }

    // YUYV and UYVY from the same 2-byte-per-pixel bytes (odd widths too).
    void packed422(const std::string &name, const cv::Mat &yuv2)
    {
        int w = yuv2.cols, h = yuv2.rows;
        Padded p = pad_copy(yuv2, rng);
        cv::Mat expected_yuyv, expected_uyvy;
        cv::cvtColor(yuv2, expected_yuyv, cv::COLOR_YUV2GRAY_YUY2);
        cv::cvtColor(yuv2, expected_uyvy, cv::COLOR_YUV2GRAY_UYVY);

        std::vector<uint8_t> storage;
        rte_image_u8 dst = oracle::blank_u8(w, h, storage, rng);
        image(name + " yuyv_to_gray", rte_color_yuyv_to_gray(p.data(), p.stride, &dst), dst,
              expected_yuyv);
        dst = oracle::blank_u8(w, h, storage, rng);
        image(name + " uyvy_to_gray", rte_color_uyvy_to_gray(p.data(), p.stride, &dst), dst,
              expected_uyvy);

        frame(name + " YUYV", rte_frame{RTE_PIXEL_YUYV, w, h, {p.data(), nullptr}, {p.stride, 0}},
              expected_yuyv);
        frame(name + " UYVY", rte_frame{RTE_PIXEL_UYVY, w, h, {p.data(), nullptr}, {p.stride, 0}},
              expected_uyvy);
    }

    // NV12 in separately padded planes; OpenCV needs even sizes and one
    // buffer of height*3/2 rows, rtedge also takes odd sizes (then the
    // expected result is the Y plane itself).
    void nv12(const std::string &name, const cv::Mat &y_plane, const cv::Mat &uv_plane)
    {
        int w = y_plane.cols, h = y_plane.rows;
        cv::Mat expected;
        if (w % 2 == 0 && h % 2 == 0) {
            cv::Mat whole;
            cv::vconcat(y_plane, uv_plane.reshape(1, h / 2), whole);
            cv::cvtColor(whole, expected, cv::COLOR_YUV2GRAY_NV12);
        } else {
            expected = y_plane.clone();
        }
        Padded py = pad_copy(y_plane, rng), puv = pad_copy(uv_plane, rng);
        rte_frame f{RTE_PIXEL_NV12, w, h, {py.data(), puv.data()}, {py.stride, puv.stride}};
        frame(name + " NV12", f, expected);
        rte_image_u8 view;
        rte_status st = rte_frame_gray_view(&f, &view);
        image(name + " NV12 view", st, view, expected);
    }

    void grey(const std::string &name, const cv::Mat &g)
    {
        Padded p = pad_copy(g, rng);
        rte_frame f{RTE_PIXEL_GREY, g.cols, g.rows, {p.data(), nullptr}, {p.stride, 0}};
        frame(name + " GREY", f, g);
        rte_image_u8 view;
        image(name + " GREY view", rte_frame_gray_view(&f, &view), view, g);
    }

    // Every format from one input: its colour bytes reinterpreted as packed
    // 4:2:2 and NV12 data, so photos give photo-like samples.
    void all(const std::string &name, const cv::Mat &bgr, const cv::Mat &gray)
    {
        three_channel(name, bgr);
        grey(name, gray);
        int w = bgr.cols, h = bgr.rows;
        // the first 2*w bytes of each BGR row as a YUYV/UYVY image of width w
        cv::Mat yuv2(h, w, CV_8UC2);
        for (int y = 0; y < h; y++)
            std::memcpy(yuv2.ptr(y), bgr.ptr(y), (size_t)w * 2);
        packed422(name, yuv2);
        // Y = the grey image, UV = the first bytes of the colour rows
        int cw = (w + 1) / 2, ch = (h + 1) / 2;
        cv::Mat uv(ch, cw, CV_8UC2);
        for (int y = 0; y < ch; y++)
            std::memcpy(uv.ptr(y), bgr.ptr(y), (size_t)cw * 2);
        nv12(name, gray, uv);
    }
};

} // namespace

int main()
{
    oracle::Tally t("color");
    std::mt19937 rng = oracle::make_rng();
    Checker c{t, rng};

    for (const auto &in : oracle::file_inputs())
        c.all(in.name, in.bgr, in.gray);

    // Random images, and packed frames of random bytes and random sizes.
    for (const auto &in : oracle::random_inputs(rng)) {
        c.all(in.name, in.bgr, in.gray);
        int w = uniform(rng, 0, 1) ? uniform(rng, 1, 67) : uniform(rng, 1, 1280);
        int h = uniform(rng, 0, 1) ? uniform(rng, 1, 67) : uniform(rng, 1, 720);
        cv::Mat bytes3(h, w, CV_8UC3), bytes2(h, w, CV_8UC2), y(h, w, CV_8UC1),
            uv((h + 1) / 2, (w + 1) / 2, CV_8UC2);
        cv::randu(bytes3, 0, 256);
        cv::randu(bytes2, 0, 256);
        cv::randu(y, 0, 256);
        cv::randu(uv, 0, 256);
        std::string name = "random bytes " + std::to_string(w) + "x" + std::to_string(h);
        c.three_channel(name, bytes3);
        c.packed422(name, bytes2);
        c.nv12(name, y, uv);
        c.grey(name, y);
    }
    return t.finish();
}
