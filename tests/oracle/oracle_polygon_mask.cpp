// Polygon masks against OpenCV 4.6: cv::fillPoly (LINE_8, shift 0) on random
// polygons of every kind, the lane tutorial's trapezoid on the photos, and
// masking (with a mask, and rte_polygon_keep_u8 without one) against
// cv::bitwise_and.
#include "oracle.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <opencv2/imgproc.hpp>

extern "C" {
#include "rtedge/arena.h"
#include "rtedge/polygon_mask.h"
}

namespace
{

using Poly = std::vector<cv::Point>;

int uniform(std::mt19937 &rng, int lo, int hi)
{
    return std::uniform_int_distribution<int>(lo, hi)(rng);
}

// One random polygon of a random kind around a random centre.
Poly random_polygon(std::mt19937 &rng, int w, int h, std::string &kind, int max_vertices = 12)
{
    int n = uniform(rng, 3, max_vertices);
    int scale_kind = uniform(rng, 0, 9);
    int r; // typical radius
    if (scale_kind <= 1)
        r = uniform(rng, 0, 3); // tiny
    else if (scale_kind <= 6)
        r = uniform(rng, 1, std::max(w, h));
    else if (scale_kind <= 8)
        r = uniform(rng, std::max(w, h), 4 * std::max(w, h) + 8); // covers / crosses the image
    else
        r = uniform(rng, 1000, 100000); // huge coordinates
    int cx, cy;
    int where = uniform(rng, 0, 4);
    if (where <= 2) { // inside
        cx = uniform(rng, 0, w - 1);
        cy = uniform(rng, 0, h - 1);
    } else if (where == 3) { // near or across the border
        cx = uniform(rng, -w, 2 * w);
        cy = uniform(rng, -h, 2 * h);
    } else { // anywhere, often wholly outside
        cx = uniform(rng, -100000 + r / 2, 100000 - r / 2);
        cy = uniform(rng, -100000 + r / 2, 100000 - r / 2);
    }
    auto clampc = [](long v) { return (int)std::max(-100000L, std::min(100000L, v)); };
    Poly p;
    int shape = uniform(rng, 0, 5);
    std::vector<double> angles;
    for (int i = 0; i < n; i++)
        angles.push_back(std::uniform_real_distribution<double>(0, 2 * M_PI)(rng));
    if (shape <= 2)
        std::sort(angles.begin(), angles.end()); // simple polygon (convex or star shaped)
    for (int i = 0; i < n; i++) {
        double rr = shape == 0 ? r : r * std::uniform_real_distribution<double>(0.1, 1.0)(rng);
        p.emplace_back(clampc(std::lround(cx + rr * std::cos(angles[i]))),
                       clampc(std::lround(cy + rr * std::sin(angles[i]))));
    }
    kind = shape == 0 ? "convex" : shape <= 2 ? "star" : "self-intersecting";
    if (shape == 5) { // degenerate: collinear, repeated points, 1 or 2 points
        int d = uniform(rng, 0, 3);
        if (d == 0) { // collinear
            int dx = uniform(rng, -r, r), dy = uniform(rng, -r, r);
            for (int i = 0; i < n; i++) {
                int t = uniform(rng, -4, 4);
                p[i] = cv::Point(clampc(cx + (long)t * dx / 4), clampc(cy + (long)t * dy / 4));
            }
            kind = "collinear";
        } else if (d == 1) { // repeated points
            for (int i = 1; i < n; i++)
                if (rng() & 1)
                    p[i] = p[i - 1];
            kind = "repeated";
        } else {
            p.resize(d == 2 ? 1 : 2);
            kind = std::to_string(p.size()) + " points";
        }
    }
    if (scale_kind <= 1)
        kind += " tiny";
    if (scale_kind == 9)
        kind += " huge";
    return p;
}

rte_polygon as_polygon(const Poly &p)
{
    // cv::Point and rte_vertex are both two packed ints
    return rte_polygon{reinterpret_cast<const rte_vertex *>(p.data()), (int32_t)p.size()};
}

std::string describe(const std::vector<Poly> &polys)
{
    std::string s;
    for (const auto &p : polys) {
        s += "[";
        for (const auto &v : p)
            s += "(" + std::to_string(v.x) + "," + std::to_string(v.y) + ")";
        s += "]";
    }
    return s;
}

// The rtedge view of a polygon set, with an arena sized for it.
struct RtePolygons {
    std::vector<rte_polygon> list;
    oracle::Arena scratch;
    explicit RtePolygons(const std::vector<Poly> &polys)
    {
        int total = 0;
        for (const auto &p : polys) {
            list.push_back(as_polygon(p));
            total += (int)p.size();
        }
        scratch.reserve(rte_polygon_mask_scratch_size(total));
    }
    int32_t count() const { return (int32_t)list.size(); }
};

// rte_polygon_keep_u8 against cv::bitwise_and(src, mask) with that mask.
void check_keep(oracle::Tally &t, const std::string &name, const cv::Mat &src, const cv::Mat &mask,
                const std::vector<Poly> &polys, std::mt19937 &rng)
{
    cv::Mat expected;
    cv::bitwise_and(src, mask, expected);
    RtePolygons rp(polys);
    std::vector<uint8_t> ss, ds;
    rte_image_u8 in = oracle::padded_u8(src, ss, rng);
    rte_image_u8 dst = oracle::blank_u8(src.cols, src.rows, ds, rng);
    rte_status st = rte_polygon_keep_u8(&in, rp.list.data(), rp.count(), &dst, &rp.scratch.arena);
    if (st != RTE_OK) {
        t.call_failed(name + " keep", st);
        return;
    }
    if (rp.scratch.arena.used != 0)
        t.call_failed(name + " keep (arena not reset)", -1);
    t.add(name + " keep", expected, oracle::to_mat(dst));
}

// rte_polygon_mask_build against zeros + cv::fillPoly(mask, polys, 255), and
// rte_polygon_keep_u8 with the same polygons on a random image.
void check_mask(oracle::Tally &t, const std::string &what, int w, int h,
                const std::vector<Poly> &polys, std::mt19937 &rng)
{
    cv::Mat expected = cv::Mat::zeros(h, w, CV_8UC1);
    cv::fillPoly(expected, polys, cv::Scalar(255), cv::LINE_8, 0);

    RtePolygons rp(polys);
    std::vector<uint8_t> storage;
    rte_image_u8 mask = oracle::blank_u8(w, h, storage, rng);
    rte_status st = rte_polygon_mask_build(&mask, rp.list.data(), rp.count(), &rp.scratch.arena);
    std::string name =
        what + " " + std::to_string(w) + "x" + std::to_string(h) + " " + describe(polys);
    if (st != RTE_OK) {
        t.call_failed(name, st);
        return;
    }
    if (rp.scratch.arena.used != 0)
        t.call_failed(name + " (arena not reset)", -1);
    t.add(name, expected, oracle::to_mat(mask));

    cv::Mat src(h, w, CV_8UC1);
    cv::RNG(rng()).fill(src, cv::RNG::UNIFORM, 1, 256); // no zeros: every kept pixel shows
    check_keep(t, name, src, expected, polys, rng);
}

// The lane-finding tutorial's region: a trapezoid from the bottom corners to
// two points near the horizon, both as fixed pixels and as fractions.
void check_lane_trapezoids(oracle::Tally &t, const std::vector<oracle::Input> &files,
                           std::mt19937 &rng)
{
    static const int frac_q16[][2] = {{(int)(0.10 * 65536), (int)(0.95 * 65536)},
                                      {(int)(0.40 * 65536), (int)(0.60 * 65536)},
                                      {(int)(0.60 * 65536), (int)(0.60 * 65536)},
                                      {(int)(0.90 * 65536), (int)(0.95 * 65536)}};
    for (const auto &in : files) {
        if (in.name.find("/lanes/") == std::string::npos)
            continue;
        int w = in.gray.cols, h = in.gray.rows;
        // Udacity "finding lane lines": (0, h), (450, 320), (490, 320), (w, h)
        check_mask(t, in.name + " tutorial trapezoid", w, h,
                   {Poly{{0, h}, {450, 320}, {490, 320}, {w, h}}}, rng);

        // the same idea in fractions of the image size
        rte_vertex frac[4], px[4];
        Poly expected_px;
        for (int i = 0; i < 4; i++) {
            frac[i] = rte_vertex{frac_q16[i][0], frac_q16[i][1]};
            expected_px.emplace_back((int)std::floor(frac_q16[i][0] * (double)w / 65536.0 + 0.5),
                                     (int)std::floor(frac_q16[i][1] * (double)h / 65536.0 + 0.5));
        }
        rte_status st = rte_polygon_from_fractions(frac, 4, w, h, px);
        if (st != RTE_OK) {
            t.call_failed(in.name + " from_fractions", st);
            continue;
        }
        Poly got;
        for (int i = 0; i < 4; i++)
            got.emplace_back(px[i].x, px[i].y);
        t.add(in.name + " fraction vertices", cv::Mat(expected_px, true).reshape(1),
              cv::Mat(got, true).reshape(1));
        check_mask(t, in.name + " fraction trapezoid", w, h, {got}, rng);

        // and the region applied to the photo
        cv::Mat mask = cv::Mat::zeros(h, w, CV_8UC1);
        cv::fillPoly(mask, std::vector<Poly>{got}, cv::Scalar(255));
        cv::Mat expected;
        cv::bitwise_and(in.gray, mask, expected);
        std::vector<uint8_t> ss, ms, ds;
        rte_image_u8 src = oracle::padded_u8(in.gray, ss, rng);
        rte_image_u8 m = oracle::padded_u8(mask, ms, rng);
        rte_image_u8 dst = oracle::blank_u8(w, h, ds, rng);
        st = rte_polygon_mask_apply(&src, &m, &dst);
        if (st != RTE_OK)
            t.call_failed(in.name + " apply", st);
        else
            t.add(in.name + " apply trapezoid", expected, oracle::to_mat(dst));
        check_keep(t, in.name + " trapezoid", in.gray, mask, {got}, rng);
    }
}

// Masking: bitwise_and(img, img, mask=m) for any mask, bitwise_and(img, m)
// for 0/255 masks, also in place.
void check_apply(oracle::Tally &t, const oracle::Input &in, std::mt19937 &rng)
{
    int w = in.gray.cols, h = in.gray.rows;
    cv::Mat anymask(h, w, CV_8UC1), binmask;
    cv::randu(anymask, 0, 256);
    if (rng() & 1)
        anymask.setTo(0, anymask < 128); // many zeros
    cv::threshold(anymask, binmask, 100, 255, cv::THRESH_BINARY);

    std::vector<uint8_t> ss, ms, ds;
    rte_image_u8 src = oracle::padded_u8(in.gray, ss, rng);

    cv::Mat expected;
    cv::bitwise_and(in.gray, in.gray, expected, anymask);
    rte_image_u8 m = oracle::padded_u8(anymask, ms, rng);
    rte_image_u8 dst = oracle::blank_u8(w, h, ds, rng);
    rte_status st = rte_polygon_mask_apply(&src, &m, &dst);
    if (st != RTE_OK)
        t.call_failed(in.name + " apply mask=", st);
    else
        t.add(in.name + " apply mask=", expected, oracle::to_mat(dst));

    cv::bitwise_and(in.gray, binmask, expected);
    m = oracle::padded_u8(binmask, ms, rng);
    st = rte_polygon_mask_apply(&src, &m, &src); // in place
    if (st != RTE_OK)
        t.call_failed(in.name + " apply in place", st);
    else
        t.add(in.name + " apply in place", expected, oracle::to_mat(src));
}

} // namespace

int main()
{
    oracle::Tally t("polygon_mask");
    std::mt19937 rng = oracle::make_rng();
    std::vector<oracle::Input> files = oracle::file_inputs();

    check_lane_trapezoids(t, files, rng);
    for (const auto &in : files)
        check_apply(t, in, rng);

    // Random polygon sets on random image sizes.
    const char *env = std::getenv("RTE_ORACLE_POLYGONS");
    const int polygons = env && *env ? std::atoi(env) : 20000;
    for (int i = 0; i < polygons; i++) {
        int size_kind = uniform(rng, 0, 19);
        int w = size_kind < 5    ? uniform(rng, 1, 8)
                : size_kind < 19 ? uniform(rng, 1, 400)
                                 : uniform(rng, 1, 1280);
        int h = size_kind < 5    ? uniform(rng, 1, 8)
                : size_kind < 19 ? uniform(rng, 1, 300)
                                 : uniform(rng, 1, 720);
        int count = uniform(rng, 0, 4) == 0 ? uniform(rng, 2, 4) : 1;
        std::vector<Poly> polys;
        std::string kind, k;
        for (int c = 0; c < count; c++) {
            polys.push_back(random_polygon(rng, w, h, k));
            kind += (c ? "+" : "") + k;
        }
        check_mask(t, "random#" + std::to_string(i) + " " + kind, w, h, polys, rng);
    }

    // A few polygons at the documented coordinate limit.
    for (int i = 0; i < 20; i++) {
        int w = uniform(rng, 1, 300), h = uniform(rng, 1, 300);
        Poly p;
        for (int k = uniform(rng, 3, 6); k > 0; k--)
            p.emplace_back(uniform(rng, -RTE_POLYGON_MAX_COORD, RTE_POLYGON_MAX_COORD),
                           uniform(rng, -RTE_POLYGON_MAX_COORD, RTE_POLYGON_MAX_COORD));
        if (i % 2)
            p[0] = cv::Point(uniform(rng, 0, w - 1), uniform(rng, 0, h - 1)); // one vertex inside
        check_mask(t, "limit#" + std::to_string(i), w, h, {p}, rng);
    }

    // Polygons with many vertices (contours, drawn outlines).
    for (int i = 0; i < 200; i++) {
        int w = uniform(rng, 1, 640), h = uniform(rng, 1, 480);
        std::string k;
        Poly p = random_polygon(rng, w, h, k, 400);
        check_mask(t, "many#" + std::to_string(i) + " " + k, w, h, {p}, rng);
    }

    // fillPoly onto existing content with another value, and masking, on the
    // random images.
    std::vector<oracle::Input> randoms = oracle::random_inputs(rng);
    for (const auto &in : randoms) {
        int w = in.gray.cols, h = in.gray.rows;
        std::vector<Poly> polys;
        std::string k;
        int count = uniform(rng, 1, 3);
        for (int c = 0; c < count; c++)
            polys.push_back(random_polygon(rng, w, h, k));
        uint8_t value = (uint8_t)uniform(rng, 0, 255);
        cv::Mat expected = in.gray.clone();
        cv::fillPoly(expected, polys, cv::Scalar(value));

        RtePolygons rp(polys);
        std::vector<uint8_t> storage;
        rte_image_u8 img = oracle::padded_u8(in.gray, storage, rng);
        rte_status st =
            rte_polygon_fill_u8(&img, rp.list.data(), rp.count(), value, &rp.scratch.arena);
        std::string name = in.name + " fill " + std::to_string(value) + " " + describe(polys);
        if (st != RTE_OK)
            t.call_failed(name, st);
        else
            t.add(name, expected, oracle::to_mat(img));
        check_apply(t, in, rng);
    }
    return t.finish();
}
