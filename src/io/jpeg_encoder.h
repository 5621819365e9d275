/* A JPEG encoder for debug streams that allocates nothing per image:
 * libjpeg-turbo's libjpeg API with its memory manager's methods pointed at
 * two arenas sized when the encoder is created (libjpeg asks for its
 * per-image buffers again on every image, from the heap), and a
 * destination in a buffer that holds any image of the maximum size.
 *
 * Input is BGR with a stride, at most max_width x max_height; output is a
 * baseline JFIF (YCbCr 4:2:0, the standard Huffman tables), as cv2.imdecode
 * and browsers read it. Internal to rtedge (the daemon's debug stream). */
#ifndef RTEDGE_JPEG_ENCODER_H
#define RTEDGE_JPEG_ENCODER_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/image.h"
#include "rtedge/status.h"

typedef struct rte_jpeg_encoder rte_jpeg_encoder;

/* What an encoder holds and has used (a test checks they do not grow). */
typedef struct rte_jpeg_encoder_stats {
    size_t arena_bytes;      /* both arenas */
    size_t arena_peak_bytes; /* most of them used at once */
    size_t permanent_bytes;  /* the permanent arena's use after creation */
    size_t output_capacity;  /* the largest JPEG it can write */
} rte_jpeg_encoder_stats;

/* Creates an encoder for images up to max_width x max_height at quality
 * 1..100, and encodes one image of that size to prove the arenas suffice.
 * RTE_ERR_ARGUMENT for sizes outside 8..16384 or a quality outside
 * 1..100, RTE_ERR_NO_MEMORY otherwise; *msg says which. */
rte_status rte_jpeg_encoder_create(rte_jpeg_encoder **out, int32_t max_width, int32_t max_height,
                                   int32_t quality, char *msg, size_t msg_size);
void rte_jpeg_encoder_destroy(rte_jpeg_encoder *enc);

/* The quality for the next images, 1..100 (no allocation). */
rte_status rte_jpeg_encoder_set_quality(rte_jpeg_encoder *enc, int32_t quality);

/* Encodes img (BGR, stride in bytes, at least 1x1 and at most the maximum
 * size). *data and *size: the JPEG in the encoder's buffer, valid until the
 * next call. RTE_ERR_ARGUMENT or RTE_ERR_SIZE for a bad image, RTE_ERR_IO
 * with libjpeg's message in *msg should libjpeg fail. */
rte_status rte_jpeg_encode_bgr(rte_jpeg_encoder *enc, const rte_image_u8c3 *img,
                               const uint8_t **data, size_t *size, char *msg, size_t msg_size);

void rte_jpeg_encoder_get_stats(const rte_jpeg_encoder *enc, rte_jpeg_encoder_stats *stats);

#endif
