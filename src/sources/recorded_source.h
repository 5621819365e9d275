/* Recorded-frame sources (source.h): image files, Y4M, raw frame dumps,
 * LCM logs of image_t, and a live LCM image_t channel.
 *
 * Each open function allocates everything for the largest frame it will
 * deliver; rte_source_next() then reads one frame into the source's own
 * buffer without allocating (image files aside: the codecs allocate per
 * file, see imageio.h). Sources do not pace: every frame carries its
 * recorded time (recorded_ns, from 0 or from the recording's timestamps) and
 * the daemon's loop paces with rte_pacer (pacer.h). A frame that cannot be
 * read (truncated, corrupt, too large, another format) is skipped: next()
 * returns its error once, counts it in bad_frames, and the following call
 * goes on with the next frame. At the end next() returns RTE_ERR_END and
 * the state becomes RTE_SOURCE_ENDED; rte_recorded_source_rewind() starts
 * again (for --loop). */
#ifndef RTEDGE_RECORDED_SOURCE_H
#define RTEDGE_RECORDED_SOURCE_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/source.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Frame spacing for recordings without timestamps, when none is given. */
#define RTE_RECORDED_DEFAULT_FPS 30
/* The latest image_t utime taken (microseconds; 2^52 is the year 2112 as
 * Unix time): later ones, and negative ones, are bad frames, so that a
 * recording's times in nanoseconds never overflow. */
#define RTE_RECORDED_MAX_UTIME ((int64_t)1 << 52)

/* Image files: PGM, PPM, PNG, JPEG. */
typedef struct rte_images_source_config {
    /* A directory (its *.pgm, *.ppm, *.png, *.jpg, *.jpeg, any case) or a
     * glob(3) pattern; frames in strcmp order of the names. */
    const char *path;
    /* RTE_PIXEL_GREY (colour files converted as cv::cvtColor BGR2GRAY
     * does) or RTE_PIXEL_BGR24 (grey files replicated, as IMREAD_COLOR). */
    rte_pixel_format format;
    /* Largest image; 0, 0: the largest header among the files (a file
     * that cannot be probed then counts as a bad frame when its turn
     * comes). Larger files are bad frames. */
    int32_t max_width, max_height;
    int32_t fps_num, fps_den; /* recorded_ns = index * fps_den / fps_num s; 0: 30 fps */
} rte_images_source_config;

rte_status rte_images_source_open(rte_source *source, const rte_images_source_config *config,
                                  char *msg, size_t msg_size);

/* YUV4MPEG2 (.y4m): mono (Cmono) and 4:2:0 (C420, C420jpeg, C420paldv,
 * C420mpeg2; also when no C tag is given), progressive; other chroma
 * formats are RTE_ERR_UNSUPPORTED at open. Mono frames are delivered as
 * RTE_PIXEL_GREY, 4:2:0 as RTE_PIXEL_NV12 (U and V interleaved on reading).
 * recorded_ns from the F tag (30 fps without one). A FRAME header that is
 * not one is a bad frame: the reader skips to the next "FRAME". */
rte_status rte_y4m_source_open(rte_source *source, const char *path, char *msg, size_t msg_size);

/* Raw frames one after another, as `v4l2-ctl --stream-to` writes them
 * (tightly packed: rte_frame_packed_size bytes per frame). A last frame cut
 * short is a bad frame (RTE_ERR_TRUNCATED). */
typedef struct rte_raw_source_config {
    const char *path;
    rte_pixel_format format;
    int32_t width, height;
    int32_t fps_num, fps_den; /* 0: 30 fps */
} rte_raw_source_config;

rte_status rte_raw_source_open(rte_source *source, const rte_raw_source_config *config, char *msg,
                               size_t msg_size);

/* image_t (lcmtypes/rtedge_image_t.lcm, = bot_core.image_t) messages: from
 * an LCM log file, or live from a channel. Formats GRAY, BGR, RGB, YUYV,
 * UYVY and NV12 (row_stride honoured); others and messages that are not an
 * image_t (another fingerprint) are bad frames, as are images of another
 * format than the source's or larger than its maxima. recorded_ns is the
 * message's utime. */
typedef struct rte_lcm_source_config {
    /* The log's path ("file://" prefix allowed) or, live, the LCM URL
     * (udpm://..., memq:// for tests). */
    const char *url;
    const char *channel; /* the log: NULL for every channel; live: required */
    /* The frames' format and largest size. A log may leave them 0: they are
     * then taken from its first image_t. */
    rte_pixel_format format;
    int32_t max_width, max_height;
} rte_lcm_source_config;

rte_status rte_lcm_log_source_open(rte_source *source, const rte_lcm_source_config *config,
                                   char *msg, size_t msg_size);
/* Live: next() waits with lcm_handle_timeout and delivers the newest image
 * that has arrived (older ones pending are counted as skipped and in the
 * frame's `dropped`). Never ends. The image is copied into the source's
 * buffer (liblcm's is valid only during its callback). Heap: none of
 * rtedge's; liblcm itself makes none for a message that fits one UDP
 * datagram, but reassembles a larger (fragmented) one in a buffer its
 * receive thread allocates and lcm_handle frees: measured 2 allocations
 * and 3 frees per 76800-byte image (tests/lcm/test_udpm.c). */
rte_status rte_lcm_live_source_open(rte_source *source, const rte_lcm_source_config *config,
                                    char *msg, size_t msg_size);

/* Starts a recording (images, y4m, raw, lcm-log) from its first frame again;
 * sequence numbers and recorded_ns go on growing, so pacing stays monotonic
 * (recorded_ns starts again from the recording's own times only when going
 * on would overflow; the pacer then starts its pace again).
 * RTE_ERR_UNSUPPORTED for other sources. */
rte_status rte_recorded_source_rewind(rte_source *source);

#ifdef __cplusplus
}
#endif
#endif
