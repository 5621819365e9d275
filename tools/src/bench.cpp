// The benchmark driver. Usage:
//   rtedge-bench [--rounds N] [--sizes 640x480,1280x720] [--filter TEXT] [--images DIR]...
// prints a Markdown table: stage, size, rtedge median, OpenCV median, ratio.
#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace bench {

std::vector<Case> &registry()
{
    static std::vector<Case> cases;
    return cases;
}

Register::Register(std::string group, std::string name, std::function<Runners(const Frame &)> prepare)
{
    registry().push_back(Case{std::move(group), std::move(name), std::move(prepare)});
}

} // namespace bench

namespace {

using bench::Frame;

double now_us()
{
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

std::vector<std::string> image_paths(const std::vector<std::string> &dirs)
{
    std::vector<std::string> paths;
    for (const auto &d : dirs) {
        if (!std::filesystem::is_directory(d)) {
            std::fprintf(stderr, "bench: %s is not a folder; skipped\n", d.c_str());
            continue;
        }
        for (const auto &e : std::filesystem::directory_iterator(d)) {
            std::string ext = e.path().extension().string();
            if (ext == ".jpg" || ext == ".png" || ext == ".pgm" || ext == ".ppm")
                paths.push_back(e.path().string());
        }
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

std::vector<cv::Size> parse_sizes(const char *text)
{
    std::vector<cv::Size> sizes;
    const char *p = text;
    while (*p) {
        int w = 0, h = 0, used = 0;
        if (std::sscanf(p, "%dx%d%n", &w, &h, &used) != 2 || w < 1 || h < 1) {
            std::fprintf(stderr, "bench: bad size list '%s' (want e.g. 640x480,1280x720)\n", text);
            std::exit(2);
        }
        sizes.emplace_back(w, h);
        p += used;
        if (*p == ',')
            p++;
    }
    return sizes;
}

} // namespace

int main(int argc, char **argv)
{
    int rounds = 30;
    std::vector<cv::Size> sizes = {{640, 480}, {1280, 720}, {1920, 1080}};
    std::vector<std::string> dirs, filters;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        auto next = [&]() -> const char * {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "bench: %s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--rounds")
            rounds = std::max(1, std::atoi(next()));
        else if (a == "--sizes")
            sizes = parse_sizes(next());
        else if (a == "--filter")
            filters.push_back(next());
        else if (a == "--images")
            dirs.push_back(next());
        else if (a == "--list") {
            for (const auto &c : bench::registry())
                std::printf("%s: %s\n", c.group.c_str(), c.name.c_str());
            return 0;
        } else {
            std::fprintf(stderr,
                         "usage: rtedge-bench [--rounds N] [--sizes WxH,...] [--filter TEXT]... "
                         "[--images DIR]... [--list]\n");
            return 2;
        }
    }
    if (dirs.empty()) {
        std::fprintf(stderr, "bench: no --images folder given\n");
        return 2;
    }
    cv::setNumThreads(1);
    std::vector<std::string> paths = image_paths(dirs);
    if (paths.empty()) {
        std::fprintf(stderr, "bench: no images found\n");
        return 2;
    }

    std::printf("OpenCV %s, single thread; %d rounds x %zu photos per figure, interleaved; "
                "times are medians per frame.\n\n",
                CV_VERSION, rounds, paths.size());
    std::printf("| stage | size | rtedge (us) | OpenCV (us) | ratio |\n|---|---|---:|---:|---:|\n");
    for (const cv::Size &size : sizes) {
        std::vector<Frame> frames;
        for (const auto &p : paths) {
            cv::Mat img = cv::imread(p, cv::IMREAD_COLOR);
            if (img.empty())
                continue;
            Frame f;
            f.name = p;
            cv::resize(img, f.bgr, size, 0, 0, cv::INTER_AREA);
            cv::cvtColor(f.bgr, f.gray, cv::COLOR_BGR2GRAY);
            frames.push_back(f);
        }
        for (const auto &c : bench::registry()) {
            std::string label = c.group + ": " + c.name;
            if (!filters.empty() &&
                std::none_of(filters.begin(), filters.end(),
                             [&](const std::string &f) { return label.find(f) != std::string::npos; }))
                continue;
            std::vector<bench::Runners> runners;
            for (const Frame &f : frames)
                runners.push_back(c.prepare(f));
            for (auto &r : runners) { // warm caches and lazy initialisation
                r.rtedge();
                r.opencv();
            }
            std::vector<double> t_rte, t_cv;
            for (int round = 0; round < rounds; round++) {
                for (auto &r : runners) {
                    // Alternate which goes first so neither always gets the warmer cache.
                    bool rte_first = (round & 1) == 0;
                    for (int k = 0; k < 2; k++) {
                        bool do_rte = (k == 0) == rte_first;
                        double t0 = now_us();
                        if (do_rte)
                            r.rtedge();
                        else
                            r.opencv();
                        double dt = now_us() - t0;
                        (do_rte ? t_rte : t_cv).push_back(dt);
                    }
                }
            }
            double m_rte = median(t_rte), m_cv = median(t_cv);
            std::printf("| %s | %dx%d | %.1f | %.1f | %.2f |\n", label.c_str(), size.width, size.height,
                        m_rte, m_cv, m_cv > 0 ? m_rte / m_cv : 0.0);
            std::fflush(stdout);
        }
    }
    return 0;
}
