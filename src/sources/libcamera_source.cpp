// libcamera source: the only C++ in rtedge. One stream, one request per
// buffer, every buffer mapped once at open; next() hands out the newest
// completed buffer as a view and gives the older ones straight back.
// Everything is allocated in open(); the completion callback (libcamera's
// thread) only stores the request in a fixed ring.
#include "rtedge/libcamera_source.h"

#include <sys/mman.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include <libcamera/libcamera.h>

#include "source_msg.h"

namespace
{

using namespace libcamera;

struct FormatPair {
    rte_pixel_format rte;
    PixelFormat lc;
};

// libcamera names formats after DRM, which lists components from the most
// significant bit: its BGR888 is R,G,B in memory.
const FormatPair kFormats[] = {
    {RTE_PIXEL_GREY, formats::R8},      {RTE_PIXEL_RGB24, formats::BGR888},
    {RTE_PIXEL_BGR24, formats::RGB888}, {RTE_PIXEL_YUYV, formats::YUYV},
    {RTE_PIXEL_UYVY, formats::UYVY},    {RTE_PIXEL_NV12, formats::NV12},
};

rte_pixel_format to_rte(const PixelFormat &f)
{
    for (const FormatPair &p : kFormats)
        if (p.lc == f)
            return p.rte;
    return static_cast<rte_pixel_format>(0);
}

PixelFormat to_libcamera(rte_pixel_format f)
{
    for (const FormatPair &p : kFormats)
        if (p.rte == f)
            return p.lc;
    return PixelFormat();
}

struct Mapping {
    void *base = MAP_FAILED;
    size_t length = 0;
};

class Source
{
  public:
    ~Source();
    rte_status open(const rte_libcamera_config &cfg, rte_libcamera_info *info, char *msg,
                    size_t msg_size);
    rte_status next(rte_source_frame *out, int32_t timeout_ms, char *msg, size_t msg_size);

    rte_source_stats stats{};
    rte_pixel_format format{};
    int32_t width = 0, height = 0;

  private:
    void on_complete(Request *request);
    void on_disconnect();
    rte_status find_camera(const rte_libcamera_config &cfg, char *msg, size_t msg_size);
    rte_status configure_stream(const rte_libcamera_config &cfg, bool *adjusted, char *msg,
                                size_t msg_size);
    rte_status map_buffers(char *msg, size_t msg_size);
    rte_status create_requests(char *msg, size_t msg_size);
    rte_status start_capture(char *msg, size_t msg_size);
    void describe(bool adjusted, rte_libcamera_info *info, char *msg, size_t msg_size);
    bool requeue(Request *request);
    rte_status fail(const char *why, char *msg, size_t msg_size);
    rte_status requeue_held(char *msg, size_t msg_size);
    size_t wait_completed(int32_t timeout_ms, Request **taken, bool *gone);
    void note_sequence(uint32_t seq);
    rte_status keep_newest(Request *const *taken, size_t n, Request **newest, bool *bad, char *msg,
                           size_t msg_size);
    void deliver(Request *newest, rte_source_frame *out);

    std::unique_ptr<CameraManager> manager_;
    std::shared_ptr<Camera> camera_;
    bool acquired_ = false, started_ = false;
    std::unique_ptr<CameraConfiguration> config_;
    Stream *stream_ = nullptr;
    std::unique_ptr<FrameBufferAllocator> allocator_;
    std::vector<std::unique_ptr<Request>> requests_;
    // Per request (by cookie), per plane: the mapping and where the plane starts in it.
    std::vector<Mapping> maps_;
    std::vector<uint8_t *> planes_;
    int32_t stride_ = 0;
    size_t n_planes_ = 0;

    std::mutex lock_;
    std::condition_variable ready_;
    Request *done_[RTE_LIBCAMERA_MAX_BUFFERS] = {};
    size_t n_done_ = 0;
    bool disconnected_ = false;

    Request *held_ = nullptr;
    bool have_seq_ = false, have_delivered_ = false;
    uint32_t last_seq_ = 0, last_delivered_ = 0;
};

Source::~Source()
{
    if (camera_) {
        if (started_)
            camera_->stop();
        camera_->requestCompleted.disconnect(this);
        camera_->disconnected.disconnect(this);
    }
    for (Mapping &m : maps_)
        if (m.base != MAP_FAILED)
            munmap(m.base, m.length);
    requests_.clear();
    if (allocator_ && stream_)
        allocator_->free(stream_);
    allocator_.reset();
    config_.reset();
    if (camera_ && acquired_)
        camera_->release();
    camera_.reset();
    manager_.reset(); // stops the camera manager
}

void Source::on_complete(Request *request)
{
    std::lock_guard<std::mutex> guard(lock_);
    if (n_done_ < RTE_LIBCAMERA_MAX_BUFFERS)
        done_[n_done_++] = request;
    ready_.notify_one();
}

void Source::on_disconnect()
{
    std::lock_guard<std::mutex> guard(lock_);
    disconnected_ = true;
    ready_.notify_one();
}

rte_status Source::map_buffers(char *msg, size_t msg_size)
{
    const auto &buffers = allocator_->buffers(stream_);
    n_planes_ = format == RTE_PIXEL_NV12 ? 2 : 1;
    maps_.resize(buffers.size() * n_planes_);
    planes_.resize(buffers.size() * n_planes_);
    for (size_t b = 0; b < buffers.size(); b++) {
        const std::vector<FrameBuffer::Plane> &planes = buffers[b]->planes();
        if (planes.empty()) {
            rte_source_msgf(msg, msg_size, "libcamera buffer without planes");
            return RTE_ERR_DEVICE;
        }
        for (size_t p = 0; p < n_planes_; p++) {
            // NV12 may come as one plane holding both: UV after Y.
            const FrameBuffer::Plane &plane = planes[p < planes.size() ? p : 0];
            size_t offset = plane.offset;
            if (p >= planes.size())
                offset += static_cast<size_t>(stride_) * static_cast<size_t>(height);
            Mapping &m = maps_[b * n_planes_ + p];
            m.length = plane.offset + plane.length;
            m.base = mmap(nullptr, m.length, PROT_READ, MAP_SHARED, plane.fd.get(), 0);
            if (m.base == MAP_FAILED) {
                rte_source_msgf(msg, msg_size, "mmap of a libcamera buffer: %s", strerror(errno));
                return RTE_ERR_DEVICE;
            }
            planes_[b * n_planes_ + p] = static_cast<uint8_t *>(m.base) + offset;
        }
    }
    return RTE_OK;
}

// Starts the camera manager, finds the camera by id or index and acquires it.
rte_status Source::find_camera(const rte_libcamera_config &cfg, char *msg, size_t msg_size)
{
    manager_ = std::make_unique<CameraManager>();
    if (manager_->start() != 0) {
        manager_.reset();
        rte_source_msgf(msg, msg_size, "the libcamera camera manager does not start");
        return RTE_ERR_DEVICE;
    }
    if (cfg.camera) {
        camera_ = manager_->get(cfg.camera);
    } else {
        std::vector<std::shared_ptr<Camera>> cameras = manager_->cameras();
        if (cfg.index < static_cast<int32_t>(cameras.size()))
            camera_ = cameras[static_cast<size_t>(cfg.index)];
    }
    if (!camera_) {
        if (cfg.camera)
            rte_source_msgf(msg, msg_size, "no libcamera camera \"%s\"", cfg.camera);
        else
            rte_source_msgf(msg, msg_size, "no libcamera camera %d (%zu found)", cfg.index,
                            manager_->cameras().size());
        return RTE_ERR_DEVICE;
    }
    if (camera_->acquire() != 0) {
        rte_source_msgf(msg, msg_size, "libcamera camera %s is in use", camera_->id().c_str());
        return RTE_ERR_DEVICE;
    }
    acquired_ = true;
    return RTE_OK;
}

// One video stream with the configured format, size and buffer count, as
// libcamera validates them (*adjusted: it changed them); the result must be
// a format rtedge reads, within its limits.
rte_status Source::configure_stream(const rte_libcamera_config &cfg, bool *adjusted, char *msg,
                                    size_t msg_size)
{
    config_ = camera_->generateConfiguration({StreamRole::VideoRecording});
    if (!config_ || config_->size() != 1) {
        rte_source_msgf(msg, msg_size, "%s: no video stream", camera_->id().c_str());
        return RTE_ERR_UNSUPPORTED;
    }
    StreamConfiguration &sc = config_->at(0);
    if (cfg.format)
        sc.pixelFormat = to_libcamera(cfg.format);
    if (cfg.width > 0 && cfg.height > 0)
        sc.size = Size(static_cast<unsigned>(cfg.width), static_cast<unsigned>(cfg.height));
    sc.bufferCount = static_cast<unsigned>(cfg.buffers ? cfg.buffers : 4);
    CameraConfiguration::Status status = config_->validate();
    if (status == CameraConfiguration::Invalid) {
        rte_source_msgf(msg, msg_size, "%s: configuration %s is invalid", camera_->id().c_str(),
                        sc.toString().c_str());
        return RTE_ERR_UNSUPPORTED;
    }
    format = to_rte(sc.pixelFormat);
    if (!format) {
        rte_source_msgf(msg, msg_size, "%s: libcamera settled on %s, which rtedge does not read",
                        camera_->id().c_str(), sc.pixelFormat.toString().c_str());
        return RTE_ERR_UNSUPPORTED;
    }
    if (sc.bufferCount < 2 || sc.bufferCount > RTE_LIBCAMERA_MAX_BUFFERS ||
        sc.size.width > RTE_MAX_SIDE || sc.size.height > RTE_MAX_SIDE) {
        rte_source_msgf(msg, msg_size, "%s: %s is out of range", camera_->id().c_str(),
                        sc.toString().c_str());
        return RTE_ERR_UNSUPPORTED;
    }
    if (camera_->configure(config_.get()) != 0) {
        rte_source_msgf(msg, msg_size, "%s: configure %s failed", camera_->id().c_str(),
                        sc.toString().c_str());
        return RTE_ERR_DEVICE;
    }
    stream_ = sc.stream();
    width = static_cast<int32_t>(sc.size.width);
    height = static_cast<int32_t>(sc.size.height);
    stride_ = static_cast<int32_t>(sc.stride);
    *adjusted = status == CameraConfiguration::Adjusted;
    return RTE_OK;
}

// Allocates and maps the stream's buffers, and a request for each.
rte_status Source::create_requests(char *msg, size_t msg_size)
{
    allocator_ = std::make_unique<FrameBufferAllocator>(camera_);
    if (allocator_->allocate(stream_) < 2) {
        rte_source_msgf(msg, msg_size, "%s: buffer allocation failed", camera_->id().c_str());
        return RTE_ERR_NO_MEMORY;
    }
    rte_status st = map_buffers(msg, msg_size);
    if (st != RTE_OK)
        return st;
    const auto &buffers = allocator_->buffers(stream_);
    for (size_t b = 0; b < buffers.size(); b++) {
        std::unique_ptr<Request> request = camera_->createRequest(b);
        if (!request || request->addBuffer(stream_, buffers[b].get()) != 0) {
            rte_source_msgf(msg, msg_size, "%s: cannot create requests", camera_->id().c_str());
            return RTE_ERR_DEVICE;
        }
        requests_.push_back(std::move(request));
    }
    return RTE_OK;
}

// Connects the callbacks, starts the camera and queues every request.
rte_status Source::start_capture(char *msg, size_t msg_size)
{
    camera_->requestCompleted.connect(this, &Source::on_complete);
    camera_->disconnected.connect(this, &Source::on_disconnect);
    if (camera_->start() != 0) {
        rte_source_msgf(msg, msg_size, "%s: start failed", camera_->id().c_str());
        return RTE_ERR_DEVICE;
    }
    started_ = true;
    for (std::unique_ptr<Request> &r : requests_)
        if (camera_->queueRequest(r.get()) != 0) {
            rte_source_msgf(msg, msg_size, "%s: queueing a request failed", camera_->id().c_str());
            return RTE_ERR_DEVICE;
        }
    return RTE_OK;
}

// Says what was set up, in msg and in info (may be NULL).
void Source::describe(bool adjusted, rte_libcamera_info *info, char *msg, size_t msg_size)
{
    const StreamConfiguration &sc = config_->at(0);
    size_t n_buffers = allocator_->buffers(stream_).size();
    rte_source_msgf(msg, msg_size, "libcamera %s: %s, stride %d, %zu buffers%s",
                    camera_->id().c_str(), sc.toString().c_str(), stride_, n_buffers,
                    adjusted ? " (adjusted from the request)" : "");
    if (info) {
        memset(info, 0, sizeof(*info));
        snprintf(info->id, sizeof(info->id), "%s", camera_->id().c_str());
        info->format = format;
        info->width = width;
        info->height = height;
        info->stride = stride_;
        info->buffers = static_cast<int32_t>(n_buffers);
        info->adjusted = adjusted;
    }
}

rte_status Source::open(const rte_libcamera_config &cfg, rte_libcamera_info *info, char *msg,
                        size_t msg_size)
{
    bool adjusted = false;
    rte_status st = find_camera(cfg, msg, msg_size);
    if (st == RTE_OK)
        st = configure_stream(cfg, &adjusted, msg, msg_size);
    if (st == RTE_OK)
        st = create_requests(msg, msg_size);
    if (st == RTE_OK)
        st = start_capture(msg, msg_size);
    if (st != RTE_OK)
        return st;
    describe(adjusted, info, msg, msg_size);
    return RTE_OK;
}

bool Source::requeue(Request *request)
{
    request->reuse(Request::ReuseBuffers);
    return camera_->queueRequest(request) == 0;
}

// The camera cannot go on: the source ends.
rte_status Source::fail(const char *why, char *msg, size_t msg_size)
{
    stats.state = RTE_SOURCE_FAILED;
    stats.errors++;
    rte_source_msgf(msg, msg_size, "%s", why);
    return RTE_ERR_DEVICE;
}

// Gives the request handed out by the last next() back to the camera.
rte_status Source::requeue_held(char *msg, size_t msg_size)
{
    if (!held_)
        return RTE_OK;
    Request *r = held_;
    held_ = nullptr;
    if (!requeue(r))
        return fail("libcamera: queueing a request failed", msg, msg_size);
    return RTE_OK;
}

// Waits up to timeout_ms (< 0: without end) for completed requests and
// takes them all into taken; *gone: the camera was disconnected.
size_t Source::wait_completed(int32_t timeout_ms, Request **taken, bool *gone)
{
    std::unique_lock<std::mutex> guard(lock_);
    auto ready = [this] { return n_done_ > 0 || disconnected_; };
    if (timeout_ms < 0)
        ready_.wait(guard, ready);
    else
        ready_.wait_for(guard, std::chrono::milliseconds(timeout_ms), ready);
    size_t n = n_done_;
    std::memcpy(taken, done_, n * sizeof(taken[0]));
    n_done_ = 0;
    *gone = disconnected_;
    return n;
}

// Counts the gap between the last sequence completed and this one.
void Source::note_sequence(uint32_t seq)
{
    uint32_t gap = seq - last_seq_ - 1;
    if (have_seq_ && gap != 0 && gap < 0x80000000u)
        stats.driver_drops += gap;
    have_seq_ = true;
    last_seq_ = seq;
}

// Keeps the newest good request of those taken (nullptr: none) and gives
// the others back; *bad: a frame failed.
rte_status Source::keep_newest(Request *const *taken, size_t n, Request **newest, bool *bad,
                               char *msg, size_t msg_size)
{
    // Completion order is capture order: the last good one is the newest.
    *newest = nullptr;
    *bad = false;
    for (size_t i = 0; i < n; i++) {
        Request *r = taken[i];
        FrameBuffer *fb = r->findBuffer(stream_);
        bool good = r->status() == Request::RequestComplete && fb &&
                    fb->metadata().status == FrameMetadata::FrameSuccess;
        if (fb && r->status() == Request::RequestComplete)
            note_sequence(fb->metadata().sequence);
        Request *give_back = r;
        if (good) {
            if (*newest)
                stats.skipped++;
            give_back = *newest;
            *newest = r;
        } else {
            stats.bad_frames++;
            *bad = true;
        }
        if (give_back && !requeue(give_back))
            return fail("libcamera: queueing a request failed", msg, msg_size);
    }
    return RTE_OK;
}

// Hands out the newest request's buffer as a view, held until the next call.
void Source::deliver(Request *newest, rte_source_frame *out)
{
    const FrameMetadata &md = newest->findBuffer(stream_)->metadata();
    size_t b = static_cast<size_t>(newest->cookie());
    std::memset(out, 0, sizeof(*out));
    out->frame.format = format;
    out->frame.width = width;
    out->frame.height = height;
    for (size_t p = 0; p < n_planes_; p++) {
        out->frame.plane[p] = planes_[b * n_planes_ + p];
        out->frame.stride[p] = stride_;
    }
    out->capture_ns = static_cast<int64_t>(md.timestamp);
    out->recorded_ns = out->capture_ns;
    out->sequence = md.sequence;
    out->dropped = have_delivered_ ? md.sequence - last_delivered_ - 1 : 0;
    have_delivered_ = true;
    last_delivered_ = md.sequence;
    held_ = newest;
    stats.frames++;
}

rte_status Source::next(rte_source_frame *out, int32_t timeout_ms, char *msg, size_t msg_size)
{
    if (msg && msg_size)
        msg[0] = 0;
    if (stats.state == RTE_SOURCE_FAILED) {
        rte_source_msgf(msg, msg_size, "the libcamera camera is gone");
        return RTE_ERR_DEVICE;
    }
    rte_status st = requeue_held(msg, msg_size);
    if (st != RTE_OK)
        return st;

    Request *taken[RTE_LIBCAMERA_MAX_BUFFERS];
    bool gone = false;
    size_t n = wait_completed(timeout_ms, taken, &gone);
    if (gone)
        return fail("the libcamera camera was disconnected", msg, msg_size);
    if (n == 0) {
        rte_source_msgf(msg, msg_size, "libcamera: no frame within %d ms", timeout_ms);
        return RTE_ERR_TIMEOUT;
    }

    Request *newest = nullptr;
    bool bad = false;
    st = keep_newest(taken, n, &newest, &bad, msg, msg_size);
    if (st != RTE_OK)
        return st;
    if (!newest) {
        stats.errors++;
        rte_source_msgf(msg, msg_size, "libcamera: frame failed%s", bad ? " (skipped)" : "");
        return RTE_ERR_CORRUPT;
    }
    deliver(newest, out);
    return RTE_OK;
}

rte_status source_next(void *impl, rte_source_frame *frame, int32_t timeout_ms, char *msg,
                       size_t msg_size)
{
    return static_cast<Source *>(impl)->next(frame, timeout_ms, msg, msg_size);
}

void source_get_stats(const void *impl, rte_source_stats *stats)
{
    *stats = static_cast<const Source *>(impl)->stats;
}

void source_close(void *impl) { delete static_cast<Source *>(impl); }

const rte_source_ops kOps = {"libcamera", source_next, source_get_stats, source_close};

} // namespace

extern "C" rte_status rte_libcamera_source_open(rte_source *source,
                                                const rte_libcamera_config *config,
                                                rte_libcamera_info *info, char *msg,
                                                size_t msg_size)
{
    if (!source || !config || config->index < 0 || config->width < 0 || config->height < 0 ||
        config->buffers < 0 || config->buffers == 1 ||
        config->buffers > RTE_LIBCAMERA_MAX_BUFFERS ||
        (config->format && to_libcamera(config->format) == PixelFormat())) {
        rte_source_msgf(msg, msg_size, "invalid libcamera source configuration");
        return RTE_ERR_ARGUMENT;
    }
    std::memset(source, 0, sizeof(*source));
    Source *s = new (std::nothrow) Source;
    if (!s) {
        rte_source_msgf(msg, msg_size, "out of memory");
        return RTE_ERR_NO_MEMORY;
    }
    rte_status st;
    try {
        st = s->open(*config, info, msg, msg_size);
    } catch (const std::bad_alloc &) {
        rte_source_msgf(msg, msg_size, "out of memory");
        st = RTE_ERR_NO_MEMORY;
    }
    if (st != RTE_OK) {
        delete s;
        return st;
    }
    source->ops = &kOps;
    source->impl = s;
    source->max_width = s->width;
    source->max_height = s->height;
    source->format = s->format;
    return RTE_OK;
}

extern "C" int rte_libcamera_list(FILE *out)
{
    CameraManager manager;
    if (manager.start() != 0)
        return 0;
    int n = 0;
    for (const std::shared_ptr<Camera> &camera : manager.cameras()) {
        n++;
        std::fprintf(out, "libcamera %s\n", camera->id().c_str());
        std::unique_ptr<CameraConfiguration> cfg =
            camera->generateConfiguration({StreamRole::VideoRecording});
        if (!cfg || cfg->size() == 0)
            continue;
        const StreamFormats &formats = cfg->at(0).formats();
        for (const PixelFormat &pf : formats.pixelformats()) {
            std::fprintf(out, "    %s%s:", pf.toString().c_str(),
                         to_rte(pf) ? "" : " [not read by rtedge]");
            std::vector<Size> sizes = formats.sizes(pf);
            if (sizes.empty())
                std::fprintf(out, " %s", formats.range(pf).toString().c_str());
            for (const Size &sz : sizes)
                std::fprintf(out, " %s", sz.toString().c_str());
            std::fprintf(out, "\n");
        }
    }
    return n;
}
