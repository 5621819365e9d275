// The benchmark driver. Usage:
//   rtedge-bench [--rounds N] [--sizes 640x480,1280x720] [--filter TEXT]... [--images DIR]...
//                [--max-images N] [--readme FILE] [--instructions]
// prints a Markdown table: stage, size, median and p99 time per frame of
// rtedge and of OpenCV on one thread, and the ratio of the medians; then the
// median of OpenCV with its default thread count (what a user gets) and the
// ratio to it. Last come the lines `end-to-end ratio against OpenCV with N
// threads R2` and `end-to-end ratio R` (lane + grasp at 1280x720; R against
// one thread).
//
// --instructions runs the same cases once under valgrind's callgrind and
// reports instructions per frame instead of time: figures that do not move
// with machine noise (client requests zero and dump the counters around each
// side of each case); single thread only.
#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h> // client requests only: no library to link
#define BENCH_HAVE_CALLGRIND 1
#else
#define BENCH_HAVE_CALLGRIND 0 // tools/bench installs valgrind; the test build need not
#define CALLGRIND_ZERO_STATS
#define CALLGRIND_DUMP_STATS_AT(name) (void)(name)
#endif

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace bench
{

std::vector<Case> &registry()
{
    static std::vector<Case> cases;
    return cases;
}

Register::Register(std::string group, std::string name,
                   std::function<Runners(const Frame &)> prepare)
{
    registry().push_back(Case{std::move(group), std::move(name), std::move(prepare)});
}

} // namespace bench

namespace
{

using bench::Frame;

const char *const kEndToEnd = "pipeline: end to end (lane + grasp)";
// The README's generated sections: times, and instruction counts.
const char *const kReadmeTimes = "<!-- bench table: tools/bench --readme README.md -->";
const char *const kReadmeInstructions =
    "<!-- bench table: tools/bench --instructions --readme README.md -->";
const char *const kReadmeEnd = "<!-- end of bench table -->";

// OpenCV's thread count before the bench sets it to 1: the default a user gets.
int cv_threads = 1;

double now_us()
{
    return std::chrono::duration<double, std::micro>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// The q-quantile (0..1) by the nearest-rank rule; the median of an even
// count is the mean of the middle two.
double quantile(std::vector<double> v, double q)
{
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    if (q == 0.5)
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    size_t rank = (size_t)std::ceil(q * (double)n);
    return v[std::min(n, std::max<size_t>(rank, 1)) - 1];
}

std::vector<std::string> image_paths(const std::vector<std::string> &dirs, size_t max_images)
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
    if (max_images && paths.size() > max_images) { // an even spread over the folders
        std::vector<std::string> some;
        for (size_t i = 0; i < max_images; i++)
            some.push_back(paths[i * paths.size() / max_images]);
        paths.swap(some);
    }
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

std::string size_text(const cv::Size &s)
{
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

std::vector<Frame> load_frames(const std::vector<std::string> &paths, const cv::Size &size)
{
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
    return frames;
}

struct Options {
    int rounds = 30;
    size_t max_images = 0;
    std::vector<cv::Size> sizes = {{640, 480}, {1280, 720}, {1920, 1080}};
    std::vector<std::string> dirs, filters;
    std::string readme;
    bool instructions = false, instructions_child = false;
    std::vector<std::string> passed_on; // the arguments a callgrind child gets
};

bool selected(const Options &o, const std::string &label)
{
    return o.filters.empty() ||
           std::any_of(o.filters.begin(), o.filters.end(),
                       [&](const std::string &f) { return label.find(f) != std::string::npos; });
}

// One table row.
struct Row {
    std::string label, size;
    double rte_p50, cv_p50, rte_p99, cv_p99; // us, or instructions per frame
    double cvt_p50;                          // us, OpenCV with cv_threads (times only)
};

std::string table(const std::vector<Row> &rows, bool instructions)
{
    std::ostringstream t;
    char line[512];
    if (instructions) {
        t << "| stage | size | rtedge (instructions) | OpenCV (instructions) | ratio |\n"
             "|---|---|---:|---:|---:|\n";
        for (const Row &r : rows) {
            std::snprintf(line, sizeof line, "| %s | %s | %.0f | %.0f | %.2f |\n", r.label.c_str(),
                          r.size.c_str(), r.rte_p50, r.cv_p50,
                          r.cv_p50 > 0 ? r.rte_p50 / r.cv_p50 : 0.0);
            t << line;
        }
    } else {
        // the threads columns last: tools/bench_daemon reads columns by position
        t << "| stage | size | rtedge p50 (us) | OpenCV p50 (us) | ratio | rtedge p99 (us) | "
             "OpenCV p99 (us) | OpenCV threads p50 (us) | ratio (threads) |\n"
             "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Row &r : rows) {
            std::snprintf(line, sizeof line,
                          "| %s | %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.1f | %.2f |\n",
                          r.label.c_str(), r.size.c_str(), r.rte_p50, r.cv_p50,
                          r.cv_p50 > 0 ? r.rte_p50 / r.cv_p50 : 0.0, r.rte_p99, r.cv_p99, r.cvt_p50,
                          r.cvt_p50 > 0 ? r.rte_p50 / r.cvt_p50 : 0.0);
            t << line;
        }
    }
    return t.str();
}

// Runs one of a frame's three contestants: 0 rtedge, 1 OpenCV on one
// thread, 2 OpenCV with cv_threads. Returns the time in us; the thread
// count is switched outside the timed region.
double run_one(bench::Runners &r, int which)
{
    if (which == 2)
        cv::setNumThreads(cv_threads);
    double t0 = now_us();
    if (which == 0)
        r.rtedge();
    else
        r.opencv();
    double dt = now_us() - t0;
    if (which == 2)
        cv::setNumThreads(1);
    return dt;
}

// Times every selected case: per frame, rtedge, OpenCV on one thread and
// OpenCV with its threads in turn, `rounds` times, after one warm-up pass.
Row time_case(const bench::Case &c, const std::vector<Frame> &frames, int rounds,
              const std::string &size)
{
    std::vector<bench::Runners> runners;
    for (const Frame &f : frames)
        runners.push_back(c.prepare(f));
    for (auto &r : runners) // warm caches and lazy initialisation
        for (int which = 0; which < 3; which++)
            run_one(r, which);
    std::vector<double> t[3];
    for (int round = 0; round < rounds; round++) {
        for (auto &r : runners) {
            // Rotate which goes first so none always gets the warmer cache.
            for (int k = 0; k < 3; k++) {
                int which = (round + k) % 3;
                t[which].push_back(run_one(r, which));
            }
        }
    }
    return Row{c.group + ": " + c.name, size,
               quantile(t[0], 0.5),     quantile(t[1], 0.5),
               quantile(t[0], 0.99),    quantile(t[1], 0.99),
               quantile(t[2], 0.5)};
}

// Under callgrind: each side of each case runs once over all frames between
// a zeroing and a dump named "rtedge-bench N rte|cv"; stdout says what N is.
void count_case(const bench::Case &c, const std::vector<Frame> &frames, int index,
                const std::string &size)
{
    std::vector<bench::Runners> runners;
    for (const Frame &f : frames)
        runners.push_back(c.prepare(f));
    for (auto &r : runners) {
        r.rtedge();
        r.opencv();
    }
    // named strings: the macros keep the pointer beyond a temporary's life
    std::string rte_dump = "rtedge-bench " + std::to_string(index) + " rte";
    std::string cv_dump = "rtedge-bench " + std::to_string(index) + " cv";
    CALLGRIND_ZERO_STATS;
    for (auto &r : runners)
        r.rtedge();
    CALLGRIND_DUMP_STATS_AT(rte_dump.c_str());
    for (auto &r : runners)
        r.opencv();
    CALLGRIND_DUMP_STATS_AT(cv_dump.c_str());
    std::printf("case %d\t%zu\t%s\t%s: %s\n", index, frames.size(), size.c_str(), c.group.c_str(),
                c.name.c_str());
    std::fflush(stdout);
}

// Runs this program again under callgrind and reads its dumps.
std::vector<Row> instructions_under_callgrind(const Options &o, char *self)
{
    char dir_template[] = "/tmp/rtedge-bench.XXXXXX";
    if (!mkdtemp(dir_template)) {
        std::perror("bench: mkdtemp");
        std::exit(1);
    }
    std::string dir = dir_template;
    std::string cmd = "valgrind --tool=callgrind --callgrind-out-file=" + dir + "/cg.out " + self +
                      " --instructions-child";
    for (const auto &a : o.passed_on)
        cmd += " '" + a + "'";
    cmd += " > " + dir + "/cases.txt 2> " + dir + "/valgrind.txt";
    std::fflush(stdout);
    std::fprintf(stderr, "bench: counting instructions under callgrind (slow)...\n");
    if (std::system(cmd.c_str()) != 0) {
        std::fprintf(stderr, "bench: '%s' failed; see %s/valgrind.txt\n", cmd.c_str(), dir.c_str());
        std::exit(1);
    }
    std::map<std::string, double> totals; // dump name -> instructions
    for (const auto &e : std::filesystem::directory_iterator(dir)) {
        std::ifstream in(e.path());
        std::string line, name;
        while (std::getline(in, line)) {
            const std::string trigger = "desc: Trigger: Client Request: ";
            if (line.rfind(trigger, 0) == 0)
                name = line.substr(trigger.size());
            else if (line.rfind("totals: ", 0) == 0 && !name.empty())
                totals[name] = std::atof(line.c_str() + 8);
        }
    }
    std::vector<Row> rows;
    std::ifstream cases(dir + "/cases.txt");
    std::string line;
    while (std::getline(cases, line)) {
        int index = 0;
        size_t frames = 0;
        char size[32], label[400];
        if (std::sscanf(line.c_str(), "case %d\t%zu\t%31[^\t]\t%399[^\n]", &index, &frames, size,
                        label) != 4 ||
            frames == 0)
            continue;
        std::string name = "rtedge-bench " + std::to_string(index);
        double rte = totals[name + " rte"] / (double)frames,
               cv = totals[name + " cv"] / (double)frames;
        rows.push_back(Row{label, size, rte, cv, rte, cv, 0.0});
    }
    std::filesystem::remove_all(dir);
    return rows;
}

// Puts the table between the README's markers.
void update_readme(const std::string &path, const char *begin_marker, const std::string &text)
{
    std::ifstream in(path);
    std::stringstream buf;
    buf << in.rdbuf();
    std::string doc = buf.str();
    size_t b = doc.find(begin_marker), e = b == std::string::npos ? b : doc.find(kReadmeEnd, b);
    if (e == std::string::npos) {
        std::fprintf(stderr, "bench: %s has no '%s' ... '%s' section\n", path.c_str(), begin_marker,
                     kReadmeEnd);
        std::exit(1);
    }
    b += std::strlen(begin_marker);
    doc.replace(b, e - b, "\n" + text);
    std::ofstream(path) << doc;
    std::fprintf(stderr, "bench: table written into %s\n", path.c_str());
}

Options parse(int argc, char **argv)
{
    Options o;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        auto next = [&]() -> const char * {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "bench: %s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        auto pass = [&](const char *v) {
            o.passed_on.push_back(a);
            o.passed_on.push_back(v);
            return v;
        };
        if (a == "--rounds")
            o.rounds = std::max(1, std::atoi(next()));
        else if (a == "--sizes")
            o.sizes = parse_sizes(pass(next()));
        else if (a == "--filter")
            o.filters.push_back(pass(next()));
        else if (a == "--images")
            o.dirs.push_back(pass(next()));
        else if (a == "--max-images")
            o.max_images = (size_t)std::max(1, std::atoi(pass(next())));
        else if (a == "--readme")
            o.readme = next();
        else if (a == "--instructions")
            o.instructions = true;
        else if (a == "--instructions-child")
            o.instructions_child = true;
        else if (a == "--list") {
            for (const auto &c : bench::registry())
                std::printf("%s: %s\n", c.group.c_str(), c.name.c_str());
            std::exit(0);
        } else {
            std::fprintf(
                stderr,
                "usage: rtedge-bench [--rounds N] [--sizes WxH,...] [--filter TEXT]... "
                "[--images DIR]... [--max-images N] [--readme FILE] [--instructions] [--list]\n");
            std::exit(2);
        }
    }
    if ((o.instructions || o.instructions_child) && !BENCH_HAVE_CALLGRIND) {
        std::fprintf(
            stderr, "bench: built without valgrind's callgrind.h: --instructions needs valgrind\n");
        std::exit(2);
    }
    if (o.dirs.empty()) {
        std::fprintf(stderr, "bench: no --images folder given\n");
        std::exit(2);
    }
    return o;
}

} // namespace

int main(int argc, char **argv)
{
    Options o = parse(argc, argv);
    cv_threads = cv::getNumThreads();
    cv::setNumThreads(1);
    std::vector<std::string> paths = image_paths(o.dirs, o.max_images);
    if (paths.empty()) {
        std::fprintf(stderr, "bench: no images found\n");
        return 2;
    }

    if (o.instructions_child) {
        int index = 0;
        for (const cv::Size &size : o.sizes) {
            std::vector<Frame> frames = load_frames(paths, size);
            for (const auto &c : bench::registry())
                if (selected(o, c.group + ": " + c.name))
                    count_case(c, frames, index++, size_text(size));
        }
        return 0;
    }

    std::string intro;
    std::vector<Row> rows;
    if (o.instructions) {
        intro = "OpenCV " + std::string(CV_VERSION) +
                ", single thread only (OpenCV with its default threads is timed, not counted); "
                "instructions per frame counted by valgrind's callgrind over " +
                std::to_string(paths.size()) +
                " photos (one run: the counts "
                "do not depend on machine load).\n\n";
        std::printf("%s", intro.c_str());
        rows = instructions_under_callgrind(o, argv[0]);
        std::printf("%s", table(rows, true).c_str());
    } else {
        intro = "OpenCV " + std::string(CV_VERSION) + ", single thread, and with its default " +
                std::to_string(cv_threads) + " threads in the threads columns; " +
                std::to_string(o.rounds) + " interleaved rounds x " + std::to_string(paths.size()) +
                " photos per figure; times per frame (median and 99th percentile).\n\n";
        std::printf("%s%s", intro.c_str(), table({}, false).c_str());
        for (const cv::Size &size : o.sizes) {
            std::vector<Frame> frames = load_frames(paths, size);
            for (const auto &c : bench::registry()) {
                if (!selected(o, c.group + ": " + c.name))
                    continue;
                rows.push_back(time_case(c, frames, o.rounds, size_text(size)));
                std::printf("%s",
                            table({rows.back()}, false).substr(table({}, false).size()).c_str());
                std::fflush(stdout);
            }
        }
    }
    std::string verdict;
    for (const Row &r : rows)
        if (r.label == kEndToEnd && r.size == "1280x720" && r.cv_p50 > 0) {
            char line[256];
            std::snprintf(line, sizeof line, "end-to-end %sratio %.2f\n",
                          o.instructions ? "instruction " : "", r.rte_p50 / r.cv_p50);
            verdict = line;
            if (!o.instructions && r.cvt_p50 > 0) { // the single-thread line stays last
                std::snprintf(line, sizeof line,
                              "end-to-end ratio against OpenCV with %d threads %.2f\n", cv_threads,
                              r.rte_p50 / r.cvt_p50);
                verdict = line + verdict;
            }
        }
    std::printf("\n%s", verdict.c_str());
    if (!o.readme.empty())
        update_readme(o.readme, o.instructions ? kReadmeInstructions : kReadmeTimes,
                      intro + table(rows, o.instructions) + "\n" + verdict);
    return 0;
}
