/* What the recorded sources share: see recorded.h. */
#include "recorded.h"
#include "core/clock.h"

#include <string.h>
#include <time.h>

void rte_recording_init(rte_recording *rec, int64_t frame_ns, void (*rewind)(void *impl))
{
    memset(rec, 0, sizeof *rec);
    rec->stats.state = RTE_SOURCE_STREAMING;
    rec->rewind = rewind;
    rec->frame_ns = frame_ns;
    rec->first_ns = -1;
    rec->last_ns = -1;
}

void rte_recording_attach(rte_source *source, const rte_source_ops *ops, void *impl,
                          int32_t max_width, int32_t max_height, rte_pixel_format format)
{
    source->ops = ops;
    source->impl = impl;
    source->max_width = max_width;
    source->max_height = max_height;
    source->format = format;
}

void rte_recording_deliver(rte_recording *rec, rte_source_frame *out, const rte_frame *frame,
                           int64_t recorded_ns)
{
    if (rec->first_ns < 0)
        rec->first_ns = recorded_ns;
    out->frame = *frame;
    out->capture_ns = rte_clock_now_ns();
    out->recorded_ns = recorded_ns + rec->ns_offset;
    out->sequence = rec->sequence_base + rec->index;
    out->dropped = 0;
    rec->last_ns = out->recorded_ns;
    rec->index++;
    rec->stats.frames++;
}

rte_status rte_recording_bad(rte_recording *rec, rte_status st)
{
    rec->index++;
    rec->stats.bad_frames++;
    return st;
}

rte_status rte_recording_end(rte_recording *rec, char *msg, size_t msg_size)
{
    rec->stats.state = RTE_SOURCE_ENDED;
    rte_source_msgf(msg, msg_size, "end of the recording after %llu frames",
                    (unsigned long long)rec->index);
    return RTE_ERR_END;
}

int64_t rte_recording_frame_ns(uint64_t index, int32_t fps_num, int32_t fps_den)
{
    /* index * den / num seconds without overflow for any realistic index */
    uint64_t q = index * (uint64_t)fps_den;
    return (int64_t)(q / (uint64_t)fps_num * 1000000000u +
                     q % (uint64_t)fps_num * 1000000000u / (uint64_t)fps_num);
}

rte_status rte_recording_check_fps(int32_t *fps_num, int32_t *fps_den, char *msg, size_t msg_size)
{
    if (*fps_num == 0 && *fps_den == 0) {
        *fps_num = RTE_RECORDED_DEFAULT_FPS;
        *fps_den = 1;
    }
    if (*fps_num <= 0 || *fps_den <= 0 || *fps_num > 1000000 || *fps_den > 1000000) {
        rte_source_msgf(msg, msg_size, "bad frame rate %d/%d", *fps_num, *fps_den);
        return RTE_ERR_ARGUMENT;
    }
    return RTE_OK;
}

void rte_recording_get_stats(const void *impl, rte_source_stats *stats)
{
    *stats = ((const rte_recording *)impl)->stats;
}

rte_status rte_recorded_source_rewind(rte_source *source)
{
    const rte_source_ops *ops = source ? source->ops : NULL;
    if (ops != &rte_images_source_ops && ops != &rte_y4m_source_ops && ops != &rte_raw_source_ops &&
        ops != &rte_lcm_log_source_ops)
        return RTE_ERR_UNSUPPORTED;
    rte_recording *rec = source->impl;
    /* Keep time and sequence growing: the first frame again comes one frame
     * interval after the last one. Recorded times are at most
     * RTE_RECORDED_MAX_UTIME microseconds; an offset that could overflow
     * with them starts the times over (the pacer takes that as a restart). */
    int64_t offset;
    const int64_t max_ns = RTE_RECORDED_MAX_UTIME * 1000;
    if (rec->last_ns >= 0 && rec->first_ns >= 0 &&
        !__builtin_add_overflow(rec->last_ns, rec->frame_ns, &offset))
        rec->ns_offset = offset - rec->first_ns <= INT64_MAX - max_ns ? offset - rec->first_ns : 0;
    rec->sequence_base += rec->index;
    rec->index = 0;
    rec->stats.state = RTE_SOURCE_STREAMING;
    rec->rewind(source->impl);
    return RTE_OK;
}
