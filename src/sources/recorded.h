/* What the recorded-frame sources share (internal to src/sources): the
 * counters, sequence numbers and recorded times across rewinds. Every
 * recorded source's impl struct starts with an rte_recording. */
#ifndef RTEDGE_RECORDED_H
#define RTEDGE_RECORDED_H

#include <stdint.h>

#include "sources/recorded_source.h"
#include "source_msg.h"

typedef struct rte_recording {
    rte_source_stats stats;
    void (*rewind)(void *impl); /* back to the first frame; NULL: live */
    uint64_t index;             /* frame slots read in this pass (bad ones too) */
    uint64_t sequence_base;     /* sequence of this pass's first frame */
    int64_t frame_ns;           /* nominal frame interval */
    int64_t first_ns;           /* the recording's time of its first frame (-1: none yet) */
    int64_t ns_offset;          /* added to recorded times: grows with each rewind */
    int64_t last_ns;            /* the last recorded_ns delivered */
} rte_recording;

/* frame_ns: the interval a rewind leaves between the last frame and the
 * first one again. */
void rte_recording_init(rte_recording *rec, int64_t frame_ns, void (*rewind)(void *impl));

/* Fills *source once the impl is open. */
void rte_recording_attach(rte_source *source, const rte_source_ops *ops, void *impl,
                          int32_t max_width, int32_t max_height, rte_pixel_format format);
/* Hands out a frame read from slot rec->index (then advances it). */
void rte_recording_deliver(rte_recording *rec, rte_source_frame *out, const rte_frame *frame,
                           int64_t recorded_ns);
/* A frame slot that could not be read: counted, st returned. */
rte_status rte_recording_bad(rte_recording *rec, rte_status st);
/* The end of the recording. */
rte_status rte_recording_end(rte_recording *rec, char *msg, size_t msg_size);
/* recorded_ns of frame `index` at fps_num/fps_den frames per second. */
int64_t rte_recording_frame_ns(uint64_t index, int32_t fps_num, int32_t fps_den);
/* fps_num/fps_den defaulted and checked (RTE_ERR_ARGUMENT). */
rte_status rte_recording_check_fps(int32_t *fps_num, int32_t *fps_den, char *msg, size_t msg_size);
void rte_recording_get_stats(const void *impl, rte_source_stats *stats);

/* The ops of the recordings that can rewind. */
extern const rte_source_ops rte_images_source_ops, rte_y4m_source_ops, rte_raw_source_ops,
    rte_lcm_log_source_ops;

#endif
