#include "oracle.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace fs = std::filesystem;

namespace oracle
{

static int env_int(const char *name, int fallback)
{
    const char *v = std::getenv(name);
    return v && *v ? std::atoi(v) : fallback;
}

int random_count() { return env_int("RTE_ORACLE_RANDOM", 200); }

std::mt19937 make_rng() { return std::mt19937((unsigned)env_int("RTE_ORACLE_SEED", 20261122)); }

/* The images of the folder named by env_name, and of its subfolders when
 * `recursive`. */
static void add_folder(const char *env_name, bool recursive, std::vector<Input> &out)
{
    const char *dir = std::getenv(env_name);
    if (!dir || !*dir || !fs::is_directory(dir)) {
        std::fprintf(stderr, "oracle: %s (%s) is not a folder; its images are not checked\n",
                     env_name, dir ? dir : "unset");
        return;
    }
    std::vector<std::string> paths;
    const auto keep = [&paths](const fs::directory_entry &e) {
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
        if (e.is_regular_file() &&
            (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".pgm" || ext == ".ppm"))
            paths.push_back(e.path().string());
    };
    if (recursive)
        std::for_each(fs::recursive_directory_iterator(dir), fs::recursive_directory_iterator(),
                      keep);
    else
        std::for_each(fs::directory_iterator(dir), fs::directory_iterator(), keep);
    std::sort(paths.begin(), paths.end());
    for (const auto &p : paths) {
        Input in;
        in.name = p;
        in.bgr = cv::imread(p, cv::IMREAD_COLOR);
        if (in.bgr.empty()) {
            std::fprintf(stderr, "oracle: OpenCV cannot read %s; skipped\n", p.c_str());
            continue;
        }
        cv::cvtColor(in.bgr, in.gray, cv::COLOR_BGR2GRAY);
        out.push_back(in);
    }
}

std::vector<Input> file_inputs()
{
    std::vector<Input> out;
    /* fixtures/ itself: its subfolders hold the lane tests' labelled
     * frames, road photos like those of the shared folder's lanes/ */
    add_folder("RTE_FIXTURES_DIR", false, out);
    add_folder("RTE_SHARED_DATA_DIR", true, out);
    return out;
}

static int random_side(std::mt19937 &rng, int max)
{
    std::uniform_int_distribution<int> kind(0, 9);
    int k = kind(rng);
    if (k == 0)
        return std::uniform_int_distribution<int>(1, 3)(rng);
    if (k <= 4)
        return std::uniform_int_distribution<int>(1, 67)(rng);
    return std::uniform_int_distribution<int>(1, max)(rng);
}

std::vector<Input> random_inputs(std::mt19937 &rng)
{
    std::vector<Input> out;
    int n = random_count();
    for (int i = 0; i < n; i++) {
        int w = random_side(rng, 1280), h = random_side(rng, 720);
        int kind = std::uniform_int_distribution<int>(0, 7)(rng);
        cv::Mat g(h, w, CV_8UC1);
        cv::Mat bgr(h, w, CV_8UC3);
        cv::RNG cvrng((uint64_t)rng() << 32 | rng());
        switch (kind) {
        case 0: cvrng.fill(g, cv::RNG::UNIFORM, 0, 256); break;
        case 1: { // gradient plus noise
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    g.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(
                        (x * 255) / std::max(1, w - 1) / 2 + (y * 255) / std::max(1, h - 1) / 2 +
                        (int)(rng() % 21) - 10);
            break;
        }
        case 2: { // blocks: rectangles and circles of random grey levels
            g.setTo(cv::Scalar(rng() % 256));
            int shapes = 1 + (int)(rng() % 12);
            for (int s = 0; s < shapes; s++) {
                cv::Point c((int)(rng() % (unsigned)w), (int)(rng() % (unsigned)h));
                int r = 1 + (int)(rng() % (unsigned)(std::max(w, h) / 3 + 1));
                if (rng() & 1)
                    cv::rectangle(g, c, c + cv::Point(r, r / 2 + 1), cv::Scalar(rng() % 256),
                                  cv::FILLED);
                else
                    cv::circle(g, c, r, cv::Scalar(rng() % 256), cv::FILLED);
            }
            break;
        }
        case 3: { // sparse dots on 0
            g.setTo(0);
            int dots = 1 + w * h / 50;
            for (int s = 0; s < dots; s++)
                g.at<uint8_t>((int)(rng() % (unsigned)h), (int)(rng() % (unsigned)w)) =
                    (uint8_t)(rng() % 256);
            break;
        }
        case 4: g.setTo(0); break;
        case 5: g.setTo(255); break;
        case 6: g.setTo(cv::Scalar(rng() % 256)); break;
        default: { // smooth noise: large-scale structure like a photo
            cvrng.fill(g, cv::RNG::UNIFORM, 0, 256);
            if (w >= 3 && h >= 3)
                cv::GaussianBlur(g, g, cv::Size(0, 0), 1.0 + (rng() % 40) / 10.0);
            break;
        }
        }
        if (kind == 0 || kind == 7)
            cvrng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
        else
            cv::cvtColor(g, bgr, cv::COLOR_GRAY2BGR);
        Input in;
        in.name = "random#" + std::to_string(i) + " " + std::to_string(w) + "x" +
                  std::to_string(h) + " kind " + std::to_string(kind);
        in.gray = g;
        in.bgr = bgr;
        out.push_back(in);
    }
    return out;
}

rte_image_u8 padded_u8(const cv::Mat &m, std::vector<uint8_t> &storage, std::mt19937 &rng)
{
    CV_Assert(m.type() == CV_8UC1);
    int pad = (int)(rng() % 38);
    int stride = m.cols + pad;
    storage.assign((size_t)stride * m.rows + 1, 0x5A);
    for (int y = 0; y < m.rows; y++)
        std::copy(m.ptr<uint8_t>(y), m.ptr<uint8_t>(y) + m.cols,
                  storage.data() + (size_t)y * stride);
    return rte_image_u8{m.cols, m.rows, stride, storage.data()};
}

rte_image_u8 view_u8(cv::Mat &m)
{
    CV_Assert(m.type() == CV_8UC1);
    return rte_image_u8{m.cols, m.rows, (int32_t)m.step1(), m.ptr<uint8_t>()};
}

rte_image_s16 view_s16(cv::Mat &m)
{
    CV_Assert(m.type() == CV_16SC1);
    return rte_image_s16{m.cols, m.rows, (int32_t)m.step1(), m.ptr<int16_t>()};
}

rte_image_u8 blank_u8(int w, int h, std::vector<uint8_t> &storage, std::mt19937 &rng)
{
    int stride = w + (int)(rng() % 38);
    storage.assign((size_t)stride * h + 1, 0xA5);
    return rte_image_u8{w, h, stride, storage.data()};
}

rte_image_s16 blank_s16(int w, int h, std::vector<int16_t> &storage, std::mt19937 &rng)
{
    int stride = w + (int)(rng() % 38);
    storage.assign((size_t)stride * h + 1, (int16_t)0x5AA5);
    return rte_image_s16{w, h, stride, storage.data()};
}

cv::Mat to_mat(const rte_image_u8 &img)
{
    return cv::Mat(img.height, img.width, CV_8UC1, img.buf, (size_t)img.stride).clone();
}

cv::Mat to_mat(const rte_image_s16 &img)
{
    return cv::Mat(img.height, img.width, CV_16SC1, img.buf, (size_t)img.stride * 2).clone();
}

long diff(const std::string &what, const cv::Mat &expected, const cv::Mat &actual)
{
    if (expected.size() != actual.size() || expected.type() != actual.type()) {
        std::fprintf(stderr, "DIFF %s: size/type %dx%d/%d vs %dx%d/%d\n", what.c_str(),
                     expected.cols, expected.rows, expected.type(), actual.cols, actual.rows,
                     actual.type());
        return (long)std::max(expected.total(), (size_t)1);
    }
    cv::Mat ne;
    cv::compare(expected.reshape(1), actual.reshape(1), ne, cv::CMP_NE);
    long n = cv::countNonZero(ne);
    if (n) {
        std::fprintf(stderr, "DIFF %s: %ld differing elements", what.c_str(), n);
        std::vector<cv::Point> where;
        cv::findNonZero(ne, where);
        for (size_t i = 0; i < where.size() && i < 5; i++) {
            cv::Point p = where[i];
            double e = expected.reshape(1).depth() == CV_16S ? expected.reshape(1).at<int16_t>(p)
                                                             : expected.reshape(1).at<uint8_t>(p);
            double a = actual.reshape(1).depth() == CV_16S ? actual.reshape(1).at<int16_t>(p)
                                                           : actual.reshape(1).at<uint8_t>(p);
            std::fprintf(stderr, " (%d,%d) opencv=%g rtedge=%g", p.x, p.y, e, a);
        }
        std::fprintf(stderr, "\n");
    }
    return n;
}

void Tally::add(const std::string &what, const cv::Mat &expected, const cv::Mat &actual)
{
    cases++;
    differing += diff(what, expected, actual);
}

// The padding value blank_u8 / blank_s16 fill with.
static bool padding_intact(const rte_image_u8 &img)
{
    for (int y = 0; y < img.height; y++)
        for (int x = img.width; x < img.stride; x++)
            if (img.buf[(size_t)y * img.stride + x] != 0xA5)
                return false;
    return true;
}

static bool padding_intact(const rte_image_s16 &img)
{
    for (int y = 0; y < img.height; y++)
        for (int x = img.width; x < img.stride; x++)
            if (img.buf[(size_t)y * img.stride + x] != (int16_t)0x5AA5)
                return false;
    return true;
}

template <typename Image>
static void check_call(Tally &t, const std::string &what, int status, const rte_arena *arena,
                       size_t mark, const cv::Mat &expected, const Image &dst)
{
    if (status != RTE_OK)
        t.call_failed(what, status);
    else if (arena && rte_arena_mark(arena) != mark)
        t.call_failed(what + " (arena not reset)", -1);
    else if (!padding_intact(dst))
        t.call_failed(what + " (wrote into padding)", -1);
    else
        t.add(what, expected, to_mat(dst));
}

void Tally::check(const std::string &what, int status, const rte_arena *arena, size_t mark,
                  const cv::Mat &expected, const rte_image_u8 &dst)
{
    check_call(*this, what, status, arena, mark, expected, dst);
}

void Tally::check(const std::string &what, int status, const rte_arena *arena, size_t mark,
                  const cv::Mat &expected, const rte_image_s16 &dst)
{
    check_call(*this, what, status, arena, mark, expected, dst);
}

void Tally::call_failed(const std::string &what, int status)
{
    cases++;
    failed_calls++;
    std::fprintf(stderr, "FAIL %s: rtedge returned status %d\n", what.c_str(), status);
}

int Tally::finish() const
{
    std::printf("oracle %s: %ld cases, %ld differing pixels, %ld failed calls\n", suite.c_str(),
                cases, differing, failed_calls);
    return (differing || failed_calls || cases == 0) ? 1 : 0;
}

} // namespace oracle
