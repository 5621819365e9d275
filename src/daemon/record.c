/* source.record: every frame the source delivers, packed (one stride for
 * every plane, as the lcm-log source reads them back), published as
 * image_t on a file:// publisher of its own. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"

/* image_t's code for a delivered pixel format. */
static int32_t image_t_format(rte_pixel_format f)
{
    switch (f) {
    case RTE_PIXEL_GREY: return RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY;
    case RTE_PIXEL_BGR24: return RTEDGE_IMAGE_T_PIXEL_FORMAT_BGR;
    case RTE_PIXEL_RGB24: return RTEDGE_IMAGE_T_PIXEL_FORMAT_RGB;
    case RTE_PIXEL_YUYV: return RTEDGE_IMAGE_T_PIXEL_FORMAT_YUYV;
    case RTE_PIXEL_UYVY: return RTEDGE_IMAGE_T_PIXEL_FORMAT_UYVY;
    case RTE_PIXEL_NV12: return RTEDGE_IMAGE_T_PIXEL_FORMAT_NV12;
    }
    return RTEDGE_IMAGE_T_PIXEL_FORMAT_INVALID;
}

/* The rows of one image_t: one stride for every plane (NV12's chroma rows
 * are as long as its luma rows, rounded up to even), as the lcm-log source
 * reads them back. */
static int32_t record_stride(rte_pixel_format f, int32_t width)
{
    rte_frame layout;
    uint8_t probe;
    if (rte_frame_packed(&layout, f, width, 1, &probe, SIZE_MAX) != RTE_OK)
        return 0;
    return layout.stride[1] > layout.stride[0] ? layout.stride[1] : layout.stride[0];
}

static size_t record_bytes(rte_pixel_format f, int32_t width, int32_t height)
{
    size_t rows = (size_t)height + (f == RTE_PIXEL_NV12 ? (size_t)(height + 1) / 2 : 0);
    return rows * (size_t)record_stride(f, width);
}

/* source.record: a file:// publisher of its own, sized for the source's
 * largest frame. */
bool rted_open_recording(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    size_t bytes = record_bytes(d->source.format, d->width, d->height);
    if (!bytes || bytes > (1u << 30)) {
        snprintf(msg, msg_size, "source.record: cannot record %dx%d %s frames", d->width, d->height,
                 rte_pixel_format_name(d->source.format));
        return false;
    }
    d->rec_buf = malloc(bytes);
    if (!d->rec_buf) {
        rted_msgf(msg, msg_size, "out of memory");
        return false;
    }
    char url[RTED_TEXT + 16], why[RTE_PUBLISH_MESSAGE_SIZE] = "";
    snprintf(url, sizeof url, "%s%s", strncmp(c->record_path, "file://", 7) ? "file://" : "",
             c->record_path);
    rte_publish_limits lim = {RTED_TEXT + 16, 0, 0, 0, 0, (int32_t)bytes, 0, 0};
    if (rte_publisher_create(&d->rec, url, &lim, why, sizeof why) != RTE_OK) {
        snprintf(msg, msg_size, "source.record: %s", why);
        return false;
    }
    d->rec_msg.pixelformat = image_t_format(d->source.format);
    d->rec_msg.data = d->rec_buf;
    return true;
}

/* Copies the frame, row by row, into the recording's buffer and logs it. */
void rted_record_frame(rted_daemon *d, const rte_source_frame *f)
{
    const rte_frame *fr = &f->frame;
    rte_frame layout;
    uint8_t probe;
    int32_t stride = record_stride(fr->format, fr->width);
    if (fr->width > d->width || fr->height > d->height || !stride ||
        rte_frame_packed(&layout, fr->format, fr->width, 1, &probe, SIZE_MAX) != RTE_OK) {
        d->n.publish_errors++;
        return;
    }
    for (int p = 0; p < RTE_FRAME_MAX_PLANES && fr->plane[p]; p++) {
        int32_t rows = p ? (fr->height + 1) / 2 : fr->height;
        uint8_t *dst = d->rec_buf + (p ? (size_t)stride * (size_t)fr->height : 0);
        for (int32_t y = 0; y < rows; y++)
            memcpy(dst + (size_t)y * (size_t)stride,
                   fr->plane[p] + (size_t)y * (size_t)fr->stride[p], (size_t)layout.stride[p]);
    }
    rtedge_image_t *m = &d->rec_msg;
    m->utime = rte_clock_wall_us(f->capture_ns);
    m->width = fr->width;
    m->height = fr->height;
    m->row_stride = stride;
    m->size = (int32_t)record_bytes(fr->format, fr->width, fr->height);
    m->nmetadata = 0;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (rte_publish_image(d->rec, d->cfg.image_channel, m, msg, sizeof msg) != RTE_OK)
        d->n.publish_errors++;
}
