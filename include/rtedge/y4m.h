/* YUV4MPEG2 (.y4m) recordings: a small reader for 8-bit streams, giving
 * each frame's Y plane as a grey image, or a 4:2:0 frame as NV12 (its
 * colour for the lane path's cue). Chroma tags C420* (jpeg, paldv, mpeg2 and plain 420), C422, C444
 * and Cmono are understood; a missing C tag means 420, as the format says.
 * Memory is allocated once, at open. (`ffmpeg -i drive.mp4 -pix_fmt
 * yuv420p drive.y4m` turns a video into one.) */
#ifndef RTEDGE_Y4M_H
#define RTEDGE_Y4M_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/color.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rte_y4m_reader rte_y4m_reader;

typedef struct rte_y4m_info {
    int32_t width, height;
    int32_t fps_num, fps_den; /* F tag (0/0 when absent) */
    int32_t chroma_bytes;     /* bytes of chroma after each Y plane */
    char chroma[16];          /* the C tag's value, e.g. "420jpeg", "mono" */
} rte_y4m_info;

/* Parses a stream header line ("YUV4MPEG2 W.. H.. ...", without its '\n';
 * the line is split in place) into *info. Sizes must be 1..RTE_MAX_SIDE
 * and F's numerator and denominator 0..INT32_MAX (F0:0: unknown), each
 * number whole and without overflow. RTE_ERR_FORMAT (not a header, a bad
 * or missing size, a bad rate) or RTE_ERR_UNSUPPORTED (interlaced, chroma
 * other than 420*, 422, 444 or mono), with the reason in why. */
RTE_API rte_status rte_y4m_parse_header(char *line, rte_y4m_info *info, char *why, size_t why_size);

/* The format rte_y4m_read_frame gives a stream's frames in, from its
 * header: RTE_PIXEL_NV12 for 4:2:0 (its colour kept), RTE_PIXEL_GREY for
 * mono, 4:2:2 and 4:4:4 (the Y plane). */
RTE_API rte_pixel_format rte_y4m_frame_format(const rte_y4m_info *info);
/* Opens `path` and reads its header. RTE_ERR_FORMAT for a file that is not
 * YUV4MPEG2 or has no size, RTE_ERR_UNSUPPORTED for interlacing other than
 * progressive/unknown or chroma of more than 8 bits, RTE_ERR_TOO_LARGE when
 * the size exceeds max_width x max_height (<= 0: RTE_MAX_SIDE). */
RTE_API rte_status rte_y4m_open(const char *path, int32_t max_width, int32_t max_height,
                                rte_y4m_reader **reader, rte_y4m_info *info, char *msg,
                                size_t msg_size);
/* The next frame's Y plane into dst (of the stream's size). RTE_ERR_END
 * after the last frame, RTE_ERR_TRUNCATED for a frame cut short,
 * RTE_ERR_FORMAT for a missing FRAME marker. */
RTE_API rte_status rte_y4m_read_gray(rte_y4m_reader *reader, const rte_image_u8 *dst, char *msg,
                                     size_t msg_size);
/* The next frame into dst (of the stream's size): its Y plane for a GREY
 * frame (any chroma is skipped), and for an NV12 frame also the U and V
 * planes of a 4:2:0 stream, interleaved (RTE_ERR_UNSUPPORTED for other
 * streams and formats). Errors as rte_y4m_read_gray. */
RTE_API rte_status rte_y4m_read_frame(rte_y4m_reader *reader, const rte_frame *dst, char *msg,
                                      size_t msg_size);
RTE_API void rte_y4m_close(rte_y4m_reader *reader);

#ifdef __cplusplus
}
#endif
#endif
