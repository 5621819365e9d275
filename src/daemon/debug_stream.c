/* debug.enabled: the overlay stream. At most debug.rate_hz times a second
 * the analysed grey frame, reduced to debug.scale, gets the layers of
 * debug.layers drawn on it (src/draw/overlay.c), is JPEG-encoded into the
 * encoder's own buffer (src/io/jpeg_encoder.c) and goes out as an image_t
 * of bot_core's MJPEG format on debug.channel. The canvas and the encoder
 * are sized at open for the largest frame at scale 1, so debug.scale,
 * debug.layers and debug.quality can change while running; a frame
 * allocates nothing. */
#include <stdlib.h>
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"
#include "rtedge/overlay.h"

bool rted_debug_open(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    if (!c->debug_enabled)
        return true;
    int32_t w = d->width < 8 ? 8 : d->width, h = d->height < 8 ? 8 : d->height;
    d->debug_canvas = malloc((size_t)w * (size_t)h * 3);
    if (!d->debug_canvas) {
        rted_msgf(msg, msg_size, "out of memory for the %dx%d debug overlay", w, h);
        return false;
    }
    char why[RTED_MSG];
    if (rte_jpeg_encoder_create(&d->jpeg, w, h, c->debug_quality, why, sizeof why) != RTE_OK) {
        rted_msgf(msg, msg_size, "debug stream: %s", why);
        return false;
    }
    d->debug_quality = c->debug_quality;
    d->debug_msg.pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_MJPEG;
    return true;
}

int32_t rted_debug_max_bytes(const rted_daemon *d)
{
    if (!d->jpeg)
        return 0;
    rte_jpeg_encoder_stats s;
    rte_jpeg_encoder_get_stats(d->jpeg, &s);
    return s.output_capacity > INT32_MAX ? INT32_MAX : (int32_t)s.output_capacity;
}

void rted_debug_apply(rted_daemon *d)
{
    char bad[80];
    int32_t layers = rted_parse_debug_layers(d->cfg.debug_layers, bad, sizeof bad);
    d->debug_layers = layers < 0 ? 0 : (uint32_t)layers; /* validated before */
    if (d->jpeg && d->cfg.debug_quality != d->debug_quality &&
        rte_jpeg_encoder_set_quality(d->jpeg, d->cfg.debug_quality) == RTE_OK)
        d->debug_quality = d->cfg.debug_quality;
}

bool rted_debug_due(const rted_daemon *d, int64_t t_ns)
{
    return d->jpeg && t_ns >= d->debug_next_ns;
}

void rted_debug_publish(rted_daemon *d, const rte_source_frame *f, const rte_image_u8 *gray,
                        const rte_lane_result *lane, const rte_grasp_result *grasp)
{
    rte_overlay o = {.scale_q16 = (int32_t)(d->cfg.debug_scale * 65536 + 0.5)};
    int32_t w, h;
    rte_overlay_size(gray->width, gray->height, o.scale_q16, &w, &h);
    o.canvas = (rte_image_u8c3){w, h, w * 3, d->debug_canvas};
    rte_overlay_fill_gray(&o, gray);
    if (d->debug_layers & RTE_OVERLAY_ROI) {
        /* the lane ROI, then the grasp path's workspace when it has one */
        rte_point roi[RTE_LANE_MAX_ROI_VERTICES];
        int32_t n = d->lane_msg.header.roi_npoints;
        for (int32_t i = 0; i < n; i++)
            roi[i] = (rte_point){d->roi[i].x, d->roi[i].y};
        rte_overlay_roi(&o, roi, n);
        n = grasp ? d->grasp_msg.header.roi_npoints : 0;
        for (int32_t i = 0; i < n; i++)
            roi[i] = (rte_point){d->grasp_roi[i].x, d->grasp_roi[i].y};
        if (n)
            rte_overlay_roi(&o, roi, n);
    }
    if (lane)
        rte_overlay_lanes(&o, lane, d->debug_layers);
    if (grasp)
        rte_overlay_grasp(&o, grasp, d->debug_layers);
    const uint8_t *jpeg;
    size_t size;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    /* The next one a period after this one was due, so that frames which
     * do not fall on the period still give debug.rate_hz on average; a
     * period after this frame when the stream fell behind. */
    const int64_t period = (int64_t)(1e9 / d->cfg.debug_rate_hz);
    d->debug_next_ns = f->capture_ns - d->debug_next_ns < period ? d->debug_next_ns + period
                                                                 : f->capture_ns + period;
    if (rte_jpeg_encode_bgr(d->jpeg, &o.canvas, &jpeg, &size, msg, sizeof msg) != RTE_OK) {
        d->n.publish_errors++;
        rted_log_limited(&d->log_frames, RTED_LOG_WARNING, "debug stream: %s", msg);
        return;
    }
    rtedge_image_t *m = &d->debug_msg;
    m->utime = d->capture_wall_us;
    m->width = w;
    m->height = h;
    m->row_stride = 0; /* compressed */
    m->size = (int32_t)size;
    m->data = (uint8_t *)jpeg;
    m->nmetadata = 0;
    rte_status st = rte_publish_image(d->pub, d->cfg.debug_channel, m, msg, sizeof msg);
    rted_count_publish(d, st);
    d->n.debug_frames += st == RTE_OK;
}

void rted_debug_close(rted_daemon *d)
{
    rte_jpeg_encoder_destroy(d->jpeg);
    d->jpeg = NULL;
    free(d->debug_canvas);
    d->debug_canvas = NULL;
}
