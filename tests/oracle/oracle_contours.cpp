// rte_contours_find against cv::findContours: every mode and method, on the
// file inputs (binarised at several thresholds and by Canny) and on random
// binary images made to stress the tracer (holes, nested rings, 1-pixel
// lines, single pixels, shapes on the border, noise). Contours, point order,
// hierarchy and output order must be identical.
#include "oracle.hpp"

#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/contours.h"
}

namespace
{

const int modes[] = {cv::RETR_EXTERNAL, cv::RETR_LIST, cv::RETR_CCOMP, cv::RETR_TREE};
const int methods[] = {cv::CHAIN_APPROX_NONE, cv::CHAIN_APPROX_SIMPLE};

// One contour set flattened: per contour its count, hierarchy and points.
cv::Mat flatten_cv(const std::vector<std::vector<cv::Point>> &cs, const std::vector<cv::Vec4i> &h)
{
    std::vector<int> v;
    for (size_t i = 0; i < cs.size(); i++) {
        v.push_back((int)cs[i].size());
        for (int k = 0; k < 4; k++)
            v.push_back(h[i][k]);
        for (const auto &p : cs[i]) {
            v.push_back(p.x);
            v.push_back(p.y);
        }
    }
    v.push_back(-7);
    return cv::Mat(v, true);
}

cv::Mat flatten_rte(const rte_contours &r)
{
    std::vector<int> v;
    for (int i = 0; i < r.n_contours; i++) {
        const rte_contour &c = r.contours[i];
        v.push_back(c.count);
        for (int k = 0; k < 4; k++)
            v.push_back(c.hierarchy[k]);
        for (int j = 0; j < c.count; j++) {
            v.push_back(r.points[c.offset + j].x);
            v.push_back(r.points[c.offset + j].y);
        }
    }
    v.push_back(-7);
    return cv::Mat(v, true);
}

void check(oracle::Tally &t, const std::string &name, const cv::Mat &bin, std::mt19937 &rng)
{
    std::vector<uint8_t> store;
    rte_image_u8 src = oracle::padded_u8(bin, store, rng);
    const int maxc = bin.cols * bin.rows / 2 + 8; // enough for any image
    const int maxp = bin.cols * bin.rows * 4 + 8;
    std::vector<rte_point> pts((size_t)maxp);
    std::vector<rte_contour> cons((size_t)maxc);
    oracle::Arena ar(rte_contours_scratch_size(bin.cols, bin.rows, maxc));
    for (int mode : modes) {
        for (int method : methods) {
            std::string what =
                name + " mode " + std::to_string(mode) + " method " + std::to_string(method);
            std::vector<std::vector<cv::Point>> cs;
            std::vector<cv::Vec4i> h;
            cv::findContours(bin, cs, h, mode, method);
            rte_contours r{};
            r.points = pts.data();
            r.contours = cons.data();
            r.max_points = maxp;
            r.max_contours = maxc;
            int st = rte_contours_find(&src, (rte_contour_mode)mode, (rte_contour_method)method, &r,
                                       &ar.arena);
            if (st != RTE_OK || r.truncated) {
                t.call_failed(what, st ? st : -1);
                continue;
            }
            t.add(what, flatten_cv(cs, h), flatten_rte(r));
        }
    }
    // The caller's image is not modified.
    t.add(name + " input unchanged", bin, oracle::to_mat(src));
}

// Random binary scenes built from the shapes that stress border following.
cv::Mat random_scene(std::mt19937 &rng, int &kind)
{
    auto U = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    int w, h;
    int sz = U(0, 9);
    if (sz == 0) {
        w = U(1, 4);
        h = U(1, 4);
    } else if (sz < 7) {
        w = U(1, 96);
        h = U(1, 96);
    } else {
        w = U(1, 400);
        h = U(1, 300);
    }
    cv::Mat m(h, w, CV_8UC1, cv::Scalar(0));
    kind = U(0, 5);
    int maxside = std::max(w, h);
    switch (kind) {
    case 0: { // noise of random density
        cv::RNG r((uint64_t)rng());
        cv::Mat u(h, w, CV_8UC1);
        r.fill(u, cv::RNG::UNIFORM, 0, 256);
        int thr = U(10, 245);
        m = u > thr;
        break;
    }
    default: { // shapes: blobs with holes, rings, lines, dots, on and over the border
        int n = U(1, 25);
        for (int i = 0; i < n; i++) {
            cv::Point c(U(-3, w + 2), U(-3, h + 2));
            int r = U(0, maxside / 2 + 1);
            int v = U(0, 4) == 0 ? 0 : U(1, 255);
            switch (U(0, 6)) {
            case 0: cv::circle(m, c, r, v, cv::FILLED, U(0, 1) ? cv::LINE_8 : cv::LINE_4); break;
            case 1: cv::circle(m, c, r, v, U(1, 3), U(0, 1) ? cv::LINE_8 : cv::LINE_4); break;
            case 2:
                cv::rectangle(m, c, c + cv::Point(U(0, r), U(0, r)), v,
                              U(0, 1) ? cv::FILLED : U(1, 2));
                break;
            case 3:
                cv::line(m, c, cv::Point(U(-3, w + 2), U(-3, h + 2)), v, 1,
                         U(0, 1) ? cv::LINE_8 : cv::LINE_4);
                break;
            case 4:
                for (int k = 0; k < 1 + r; k++)
                    m.at<uint8_t>(U(0, h - 1), U(0, w - 1)) = (uint8_t)v;
                break;
            case 5: { // nested rings
                for (int rr = r; rr > 0; rr -= U(2, 4))
                    cv::circle(m, c, rr, (rr / 2) % 2 ? 255 : 0, cv::FILLED);
                break;
            }
            default: { // random polygon
                std::vector<cv::Point> poly;
                int k = U(3, 8);
                for (int j = 0; j < k; j++)
                    poly.push_back(c + cv::Point(U(-r, r), U(-r, r)));
                cv::fillPoly(m, std::vector<std::vector<cv::Point>>{poly}, v);
                break;
            }
            }
        }
        break;
    }
    }
    return m;
}

} // namespace

int main()
{
    oracle::Tally t("contours");
    std::mt19937 rng = oracle::make_rng();

    for (const auto &in : oracle::file_inputs()) {
        for (int thr : {60, 127, 200}) {
            cv::Mat bin = in.gray > thr;
            check(t, in.name + " >" + std::to_string(thr), bin, rng);
        }
        cv::Mat edges;
        cv::Canny(in.gray, edges, 50, 150);
        check(t, in.name + " canny", edges, rng);
    }

    int n = std::max(500, oracle::random_count());
    for (int i = 0; i < n; i++) {
        int kind = 0;
        cv::Mat m = random_scene(rng, kind);
        check(t,
              "random#" + std::to_string(i) + " " + std::to_string(m.cols) + "x" +
                  std::to_string(m.rows) + " kind " + std::to_string(kind),
              m, rng);
    }
    return t.finish();
}
