// Image file reading against cv::imread (OpenCV 4.6): every file input, then
// files written by OpenCV from random images (PNG, PGM/PPM binary and text,
// JPEG with several encoder settings), PNGs of every colour type, bit depth
// and interlacing written by a small encoder here, and JPEGs with an EXIF
// orientation. Decoded pixels must equal imread's: 0 differing pixels.
#include "oracle.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <turbojpeg.h>
#include <zlib.h>

extern "C" {
#include "rtedge/imageio.h"
}

namespace fs = std::filesystem;

namespace
{

struct Checker {
    oracle::Tally &t;
    rte_image_reader *reader;
    std::mt19937 &rng;

    // Reports a failed call (with its message); true when st is RTE_OK.
    bool ok(rte_status st, const char *msg, const std::string &what)
    {
        if (st == RTE_OK)
            return true;
        std::fprintf(stderr, "%s\n", msg);
        t.call_failed(what, st);
        return false;
    }

    // Our BGR decode (padded destination), or an empty Mat on failure.
    cv::Mat read_bgr(const std::string &path, int w, int h)
    {
        int stride = w * 3 + (int)(rng() % 40);
        std::vector<uint8_t> buf((size_t)stride * h, 0xA5);
        rte_image_u8c3 dst = {w, h, stride, buf.data()};
        char msg[RTE_IO_MESSAGE_SIZE];
        if (!ok(rte_image_read_bgr(reader, path.c_str(), &dst, msg, sizeof msg), msg,
                "read_bgr " + path))
            return cv::Mat();
        return cv::Mat(h, w, CV_8UC3, buf.data(), (size_t)stride).clone();
    }

    cv::Mat read_gray(const std::string &path, int w, int h)
    {
        std::vector<uint8_t> buf;
        rte_image_u8 dst = oracle::blank_u8(w, h, buf, rng);
        char msg[RTE_IO_MESSAGE_SIZE];
        if (!ok(rte_image_read_gray(reader, path.c_str(), &dst, msg, sizeof msg), msg,
                "read_gray " + path))
            return cv::Mat();
        return oracle::to_mat(dst);
    }

    // Every way of reading `path` against imread.
    void check(const std::string &path, const std::string &label)
    {
        cv::Mat color = cv::imread(path, cv::IMREAD_COLOR);
        if (color.empty()) {
            std::fprintf(stderr, "oracle io: OpenCV cannot read %s\n", path.c_str());
            t.call_failed("imread " + path, -1);
            return;
        }
        rte_image_info info;
        char msg[RTE_IO_MESSAGE_SIZE];
        if (!ok(rte_image_probe(path.c_str(), &info, msg, sizeof msg), msg, "probe " + path))
            return;
        t.add(label + " bgr", color, read_bgr(path, info.width, info.height));

        // The packed read in the file's own channels.
        std::vector<uint8_t> packed((size_t)info.width * info.height * info.channels + 7, 0xA5);
        rte_image_info info2;
        if (!ok(rte_image_read(reader, path.c_str(), packed.data(), packed.size(), &info2, msg,
                               sizeof msg),
                msg, "read " + path))
            return;
        cv::Mat native(info.height, info.width, info.channels == 3 ? CV_8UC3 : CV_8UC1,
                       packed.data());
        if (info.channels == 1) {
            cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
            t.add(label + " gray", gray, read_gray(path, info.width, info.height));
            t.add(label + " native", gray, native.clone());
            cv::Mat rep;
            cv::cvtColor(gray, rep, cv::COLOR_GRAY2BGR);
            t.add(label + " gray==bgr", color, rep);
        } else {
            t.add(label + " native", color, native.clone());
        }
    }
};

// ---- a small independent PNG encoder: any colour type, depth, interlace ----

void put32(std::vector<uint8_t> &v, uint32_t x)
{
    for (int s = 24; s >= 0; s -= 8)
        v.push_back((uint8_t)(x >> s));
}

void chunk(std::vector<uint8_t> &png, const char *type, const std::vector<uint8_t> &data)
{
    put32(png, (uint32_t)data.size());
    size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    put32(png, (uint32_t)crc32(0, png.data() + start, (uInt)(png.size() - start)));
}

// samples: h rows of w * spp values (each < 2^depth), written as given.
std::vector<uint8_t> encode_png(int w, int h, int color_type, int depth, bool interlace,
                                const std::vector<uint16_t> &samples,
                                const std::vector<uint8_t> &plte, const std::vector<uint8_t> &trns,
                                const std::vector<uint8_t> &before_idat = {},
                                const std::vector<uint8_t> &after_idat = {})
{
    int spp = color_type == 2 ? 3 : color_type == 4 ? 2 : color_type == 6 ? 4 : 1;
    std::vector<uint8_t> raw;
    static const int xs[7] = {0, 4, 0, 2, 0, 1, 0}, dxs[7] = {8, 8, 4, 4, 2, 2, 1};
    static const int ys[7] = {0, 0, 4, 0, 2, 0, 1}, dys[7] = {8, 8, 8, 4, 4, 2, 2};
    for (int pass = interlace ? 0 : 6; pass < 7; pass++) {
        int x0 = interlace ? xs[pass] : 0, dx = interlace ? dxs[pass] : 1;
        int y0 = interlace ? ys[pass] : 0, dy = interlace ? dys[pass] : 1;
        if (x0 >= w || y0 >= h)
            continue;
        for (int y = y0; y < h; y += dy) {
            raw.push_back(0); // filter: none
            int bits = 0, acc = 0;
            for (int x = x0; x < w; x += dx)
                for (int s = 0; s < spp; s++) {
                    unsigned v = samples[((size_t)y * w + x) * spp + s];
                    if (depth == 16) {
                        raw.push_back((uint8_t)(v >> 8));
                        raw.push_back((uint8_t)v);
                    } else {
                        acc = acc << depth | (int)v;
                        bits += depth;
                        if (bits == 8) {
                            raw.push_back((uint8_t)acc);
                            acc = bits = 0;
                        }
                    }
                }
            if (bits)
                raw.push_back((uint8_t)(acc << (8 - bits)));
        }
    }
    uLongf zlen = compressBound((uLong)raw.size());
    std::vector<uint8_t> z(zlen);
    compress2(z.data(), &zlen, raw.data(), (uLong)raw.size(), 6);
    z.resize(zlen);

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> ihdr;
    put32(ihdr, (uint32_t)w);
    put32(ihdr, (uint32_t)h);
    ihdr.push_back((uint8_t)depth);
    ihdr.push_back((uint8_t)color_type);
    ihdr.push_back(0);
    ihdr.push_back(0);
    ihdr.push_back(interlace ? 1 : 0);
    chunk(png, "IHDR", ihdr);
    if (!plte.empty())
        chunk(png, "PLTE", plte);
    if (!trns.empty())
        chunk(png, "tRNS", trns);
    png.insert(png.end(), before_idat.begin(), before_idat.end());
    // Split the data over two IDAT chunks when it is long enough.
    size_t half = z.size() > 64 ? z.size() / 2 : z.size();
    chunk(png, "IDAT", std::vector<uint8_t>(z.begin(), z.begin() + (long)half));
    if (half < z.size())
        chunk(png, "IDAT", std::vector<uint8_t>(z.begin() + (long)half, z.end()));
    png.insert(png.end(), after_idat.begin(), after_idat.end());
    chunk(png, "IEND", {});
    return png;
}

void write_bytes(const std::string &path, const std::vector<uint8_t> &bytes)
{
    FILE *f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) {
        std::fprintf(stderr, "cannot write %s\n", path.c_str());
        std::exit(2);
    }
    std::fclose(f);
}

// A TIFF structure whose IFD0 holds a resolution unit and the orientation.
std::vector<uint8_t> exif_tiff(int orientation, bool little)
{
    std::vector<uint8_t> tiff;
    auto u16 = [&](unsigned v) {
        if (little) {
            tiff.push_back((uint8_t)v);
            tiff.push_back((uint8_t)(v >> 8));
        } else {
            tiff.push_back((uint8_t)(v >> 8));
            tiff.push_back((uint8_t)v);
        }
    };
    auto u32 = [&](uint32_t v) {
        if (little) {
            u16(v & 0xFFFF);
            u16(v >> 16);
        } else {
            u16(v >> 16);
            u16(v & 0xFFFF);
        }
    };
    tiff.push_back(little ? 'I' : 'M');
    tiff.push_back(little ? 'I' : 'M');
    u16(0x2A);
    u32(8);
    u16(2); // two entries: a resolution unit, then the orientation
    u16(0x0128), u16(3), u32(1), u16(2), u16(0);
    u16(0x0112), u16(3), u32(1), u16((unsigned)orientation), u16(0);
    u32(0);
    return tiff;
}

// An APP1 EXIF segment with that TIFF structure, inserted after SOI.
std::vector<uint8_t> with_orientation(const std::vector<uint8_t> &jpg, int orientation, bool little)
{
    std::vector<uint8_t> tiff = exif_tiff(orientation, little);
    std::vector<uint8_t> seg = {0xFF, 0xE1, 0, 0, 'E', 'x', 'i', 'f', 0, 0};
    seg.insert(seg.end(), tiff.begin(), tiff.end());
    size_t len = seg.size() - 2;
    seg[2] = (uint8_t)(len >> 8);
    seg[3] = (uint8_t)len;
    std::vector<uint8_t> out = jpg; // SOI, then the segment
    out.insert(out.begin() + 2, seg.begin(), seg.end());
    return out;
}

cv::Mat colour_of(const oracle::Input &in, std::mt19937 &rng)
{
    cv::Mat noise(in.gray.size(), CV_8UC1), inv;
    cv::RNG r((uint64_t)rng());
    r.fill(noise, cv::RNG::UNIFORM, 0, 256);
    cv::bitwise_not(in.gray, inv);
    cv::Mat bgr;
    cv::merge(std::vector<cv::Mat>{in.gray, inv, (rng() & 1) ? noise : in.gray / 2 + 60}, bgr);
    return bgr;
}

} // namespace

int main()
{
    oracle::Tally t("io");
    std::mt19937 rng = oracle::make_rng();
    rte_image_reader *reader = rte_image_reader_create(2048, 2048);
    if (!reader) {
        std::fprintf(stderr, "cannot create a reader\n");
        return 1;
    }
    Checker c{t, reader, rng};

    // 1. Every file input (fixtures and the shared real photos).
    for (const char *env : {"RTE_FIXTURES_DIR", "RTE_SHARED_DATA_DIR"}) {
        const char *dir = std::getenv(env);
        if (!dir || !fs::is_directory(dir)) {
            std::fprintf(stderr, "oracle io: %s is not a folder; skipped\n", env);
            continue;
        }
        std::vector<std::string> paths;
        for (const auto &e : fs::recursive_directory_iterator(dir)) {
            std::string ext = e.path().extension().string();
            for (auto &ch : ext)
                ch = (char)std::tolower((unsigned char)ch);
            if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg" ||
                                        ext == ".pgm" || ext == ".ppm"))
                paths.push_back(e.path().string());
        }
        std::sort(paths.begin(), paths.end());
        for (const auto &p : paths)
            c.check(p, p);
    }

    // 2. Random images written by OpenCV.
    char tmpl[] = "/tmp/rtedge_oracle_io_XXXXXX";
    if (!mkdtemp(tmpl)) {
        std::perror("mkdtemp");
        return 1;
    }
    std::string tmp = tmpl;
    std::vector<oracle::Input> inputs = oracle::random_inputs(rng);
    size_t n = std::min<size_t>(inputs.size(), 60);
    for (size_t i = 0; i < n; i++) {
        const oracle::Input &in = inputs[i];
        cv::Mat bgr = colour_of(in, rng);
        std::string base = tmp + "/r" + std::to_string(i);
        std::string label = "random " + std::to_string(i) + " " + std::to_string(in.gray.cols) +
                            "x" + std::to_string(in.gray.rows);
        struct Out {
            std::string ext;
            const cv::Mat *m;
            std::vector<int> params;
        };
        int q = 30 + (int)(rng() % 71);
        std::vector<Out> outs = {
            {"_g.png", &in.gray, {cv::IMWRITE_PNG_COMPRESSION, (int)(rng() % 10)}},
            {"_c.png", &bgr, {}},
            {"_g.pgm", &in.gray, {}},
            {"_c.ppm", &bgr, {}},
            {"_gt.pgm", &in.gray, {cv::IMWRITE_PXM_BINARY, 0}},
            {"_ct.ppm", &bgr, {cv::IMWRITE_PXM_BINARY, 0}},
            {"_g.jpg", &in.gray, {cv::IMWRITE_JPEG_QUALITY, q}},
            {"_c.jpg", &bgr, {cv::IMWRITE_JPEG_QUALITY, q}},
            // progressive + optimised Huffman tables + restart markers
            {"_cp.jpg",
             &bgr,
             {cv::IMWRITE_JPEG_PROGRESSIVE, 1, cv::IMWRITE_JPEG_OPTIMIZE, 1,
              cv::IMWRITE_JPEG_RST_INTERVAL, 1 + (int)(rng() % 8)}},
            // different luma/chroma quality: OpenCV then writes 4:4:4
            {"_c444.jpg",
             &bgr,
             {cv::IMWRITE_JPEG_LUMA_QUALITY, q, cv::IMWRITE_JPEG_CHROMA_QUALITY, 100 - q / 2}},
        };
        for (const auto &o : outs) {
            std::string path = base + o.ext;
            if (!cv::imwrite(path, *o.m, o.params)) {
                t.call_failed("imwrite " + path, -1);
                continue;
            }
            c.check(path, label + o.ext);
            std::remove(path.c_str());
        }
        // 16-bit and 4-channel PNGs from OpenCV.
        cv::Mat bgra, g16, c16;
        cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
        in.gray.convertTo(g16, CV_16U, 257.0 - (rng() % 3));
        bgr.convertTo(c16, CV_16U, 255.0 + (rng() % 3));
        for (auto &o : std::vector<Out>{
                 {"_a.png", &bgra, {}}, {"_g16.png", &g16, {}}, {"_c16.png", &c16, {}}}) {
            std::string path = base + o.ext;
            cv::imwrite(path, *o.m);
            c.check(path, label + o.ext);
            std::remove(path.c_str());
        }
        // Our writers, read back by OpenCV.
        {
            std::vector<uint8_t> gs, cs;
            rte_image_u8 g = oracle::padded_u8(in.gray, gs, rng);
            int cstride = bgr.cols * 3 + (int)(rng() % 11);
            cs.assign((size_t)cstride * bgr.rows, 0xA5);
            for (int y = 0; y < bgr.rows; y++)
                std::memcpy(cs.data() + (size_t)y * cstride, bgr.ptr(y), (size_t)bgr.cols * 3);
            rte_image_u8c3 cimg = {bgr.cols, bgr.rows, cstride, cs.data()};
            char msg[RTE_IO_MESSAGE_SIZE];
            for (const char *ext : {".pgm", ".png"}) {
                std::string path = base + "_w" + ext;
                if (c.ok(rte_image_write_gray(path.c_str(), &g, msg, sizeof msg), msg,
                         "write " + path))
                    t.add(label + " written" + ext, in.gray,
                          cv::imread(path, cv::IMREAD_UNCHANGED));
                std::remove(path.c_str());
            }
            for (const char *ext : {".ppm", ".png"}) {
                std::string path = base + "_wc" + ext;
                if (c.ok(rte_image_write_bgr(path.c_str(), &cimg, msg, sizeof msg), msg,
                         "write " + path))
                    t.add(label + " written" + ext, bgr, cv::imread(path, cv::IMREAD_UNCHANGED));
                std::remove(path.c_str());
            }
        }
        // EXIF orientation on a small colour JPEG.
        if (i < 12) {
            std::vector<uint8_t> jpg;
            cv::imencode(".jpg", bgr, jpg);
            for (int orient = 1; orient <= 8; orient++) {
                std::string path = base + "_o" + std::to_string(orient) + ".jpg";
                write_bytes(path, with_orientation(jpg, orient, (orient & 1) != 0));
                c.check(path, label + " orientation " + std::to_string(orient));
                std::remove(path.c_str());
            }
        }
    }

    // 3. PNGs of every colour type, bit depth and interlacing.
    struct Kind {
        int color_type, depth;
    };
    const Kind kinds[] = {{0, 1}, {0, 2}, {0, 4}, {0, 8}, {0, 16}, {2, 8}, {2, 16}, {3, 1},
                          {3, 2}, {3, 4}, {3, 8}, {4, 8}, {4, 16}, {6, 8}, {6, 16}};
    const int sizes[][2] = {{1, 1}, {1, 9}, {9, 1}, {3, 5}, {8, 8}, {13, 7}, {67, 33}, {250, 131}};
    int k = 0;
    for (const Kind &kind : kinds)
        for (const auto &sz : sizes)
            for (int interlace = 0; interlace < 2; interlace++) {
                int w = sz[0], h = sz[1];
                int spp = kind.color_type == 2   ? 3
                          : kind.color_type == 4 ? 2
                          : kind.color_type == 6 ? 4
                                                 : 1;
                int entries = kind.color_type == 3 ? 1 + (int)(rng() % (1u << kind.depth)) : 0;
                std::vector<uint16_t> s((size_t)w * h * spp);
                for (auto &v : s)
                    v = (uint16_t)(rng() % (1u << kind.depth));
                std::vector<uint8_t> plte, trns;
                for (int e = 0; e < entries * 3; e++)
                    plte.push_back((uint8_t)rng());
                if (kind.color_type == 3 && (rng() & 1))
                    for (int e = 0; e < entries; e++)
                        trns.push_back((uint8_t)rng());
                if ((kind.color_type == 0 || kind.color_type == 2) &&
                    (rng() & 1)) { // a transparent colour
                    for (int e = 0; e < (kind.color_type == 2 ? 3 : 1); e++) {
                        unsigned v = (unsigned)(rng() % (1u << kind.depth));
                        trns.push_back((uint8_t)(v >> 8));
                        trns.push_back((uint8_t)v);
                    }
                }
                // Every third image gets eXIf chunks: before or after the
                // data, sometimes a first one libpng drops (bad CRC or byte
                // order) so the second one counts.
                std::vector<uint8_t> before, after;
                int orient = 1, variant = k % 3 == 0 ? (int)(rng() % 4) : -1;
                if (variant >= 0) {
                    orient = 1 + (int)(rng() % 8);
                    std::vector<uint8_t> good;
                    chunk(good, "eXIf", exif_tiff(orient, (rng() & 1) != 0));
                    std::vector<uint8_t> other;
                    chunk(other, "eXIf", exif_tiff(1 + (int)(rng() % 8), (rng() & 1) != 0));
                    if (variant == 1)
                        other[other.size() - 1] ^= 1; // bad CRC
                    if (variant == 2) {
                        other[9] = 'M'; // "IM": bad byte order
                        std::vector<uint8_t> data(other.begin() + 8, other.end() - 4);
                        other.clear();
                        chunk(other, "eXIf", data);
                    }
                    if (variant > 0) // the bad one first
                        before = other;
                    std::vector<uint8_t> &where = (rng() & 1) ? before : after;
                    where.insert(where.end(), good.begin(), good.end());
                }
                std::string path = tmp + "/k" + std::to_string(k++) + ".png";
                write_bytes(path, encode_png(w, h, kind.color_type, kind.depth, interlace != 0, s,
                                             plte, trns, before, after));
                char label[128];
                std::snprintf(label, sizeof label, "png type %d depth %d %dx%d%s exif %d/%d",
                              kind.color_type, kind.depth, w, h, interlace ? " interlaced" : "",
                              variant, orient);
                c.check(path, label);
                std::remove(path.c_str());
            }

    // 4. PGM/PPM that OpenCV does not write: text and binary with maxval
    // 1..254, values above maxval, comments, and every kind of whitespace.
    for (int i = 0; i < 40; i++) {
        int w = 1 + (int)(rng() % 23), h = 1 + (int)(rng() % 17);
        bool ppm = (i & 1) != 0, text = (i & 2) != 0;
        int maxval = i % 5 == 0 ? 255 : 1 + (int)(rng() % 254);
        const char *ws[] = {" ", "\n", "\t", "\r\n", "  \n ", "\v", "\f"};
        auto sep = [&] { return std::string(ws[rng() % 7]); };
        std::string head = std::string("P") + (char)('2' + (ppm ? 1 : 0) + (text ? 0 : 3)) + sep();
        if (rng() & 1)
            head += "# a comment\n";
        head += std::to_string(w) + sep() + (rng() & 1 ? "#c\r" : "") + std::to_string(h) + sep() +
                std::to_string(maxval) + (text ? sep() : std::string(ws[rng() % 3]));
        std::vector<uint8_t> bytes(head.begin(), head.end());
        int n = w * h * (ppm ? 3 : 1);
        for (int k = 0; k < n; k++) {
            int v = (int)(rng() % 256); // above maxval too
            if (text) {
                std::string tok = std::to_string(v) + (k % 7 == 6 ? std::string("\n") : sep());
                bytes.insert(bytes.end(), tok.begin(), tok.end());
            } else {
                bytes.push_back((uint8_t)v);
            }
        }
        std::string path = tmp + "/p" + std::to_string(i) + (ppm ? ".ppm" : ".pgm");
        write_bytes(path, bytes);
        c.check(path, "pnm " + std::to_string(i) + (text ? " text" : " binary") + " maxval " +
                          std::to_string(maxval));
        std::remove(path.c_str());
    }

    // 5. JPEG chroma subsamplings OpenCV does not write (libjpeg-turbo's
    // encoder), grey JPEGs with an orientation.
    const int samps[] = {TJSAMP_444, TJSAMP_422, TJSAMP_420, TJSAMP_440, TJSAMP_411, TJSAMP_GRAY};
    for (int i = 0; i < 36; i++) {
        const oracle::Input &in = inputs[(size_t)i % n];
        cv::Mat bgr = colour_of(in, rng);
        int samp = samps[i % 6];
        unsigned char *jpg = nullptr;
        unsigned long size = 0;
        int q = 40 + (int)(rng() % 60);
        // A fresh compressor each time: libjpeg-turbo 2.1 keeps progressive
        // scan settings across calls on one handle.
        tjhandle tj = tjInitCompress();
        int rc = tjCompress2(tj, bgr.data, bgr.cols, (int)bgr.step, bgr.rows, TJPF_BGR, &jpg, &size,
                             samp, q, (i % 4 == 3 ? TJFLAG_PROGRESSIVE : 0));
        tjDestroy(tj);
        if (rc != 0) {
            t.call_failed("tjCompress2", -1);
            continue;
        }
        std::vector<uint8_t> bytes(jpg, jpg + size);
        tjFree(jpg);
        int orient = samp == TJSAMP_GRAY ? 1 + (int)(rng() % 8) : 1;
        std::string path = tmp + "/s" + std::to_string(i) + ".jpg";
        write_bytes(path, orient == 1 ? bytes : with_orientation(bytes, orient, (rng() & 1) != 0));
        c.check(path, "jpeg subsampling " + std::to_string(samp) + " " + std::to_string(bgr.cols) +
                          "x" + std::to_string(bgr.rows) + " orientation " +
                          std::to_string(orient));
        std::remove(path.c_str());
    }
    fs::remove_all(tmp);
    rte_image_reader_destroy(reader);
    return t.finish();
}
