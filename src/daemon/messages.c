/* The published messages: the generated LCM structs, filled in place each
 * frame from a path's result and pointing at the arrays rted_daemon_open()
 * sized, so that publishing allocates nothing. */
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"

void rted_messages_init(rted_daemon *d)
{
    d->lane_msg.header.source_id = d->source_id;
    d->lane_msg.header.roi = d->roi;
    d->lane_msg.segments = d->segments;
    d->grasp_msg.header.source_id = d->source_id;
    d->grasp_msg.header.roi = d->grasp_roi;
    d->grasp_msg.objects = d->objects;
    d->status_msg.source_id = d->source_id;
    /* the stages' names, as status_t lists them */
    static const char *const grasp_stages[RTED_GRASP_STAGES] = {
        "grasp.blur", "grasp.binarize", "grasp.contours", "grasp.split", "grasp.features"};
    static const char *const lane_stages[RTE_LANE_STAGES] = {"lane.gray", "lane.blur", "lane.canny",
                                                             "lane.hough", "lane.fit"};
    for (int i = 0; i < RTE_LANE_STAGES; i++)
        d->stage_names[i] = (char *)lane_stages[i];
    for (int i = 0; i < RTED_GRASP_STAGES; i++)
        d->stage_names[RTED_GRASP_STAGE0 + i] = (char *)grasp_stages[i];
    d->stage_names[RTED_DEBUG_STAGE] = (char *)"debug";
    d->status_msg.nstages = RTED_STAGES;
    d->status_msg.stage_names = d->stage_names;
    d->status_msg.stage_mean_us = d->stage_mean_us;
    d->status_msg.stage_max_us = d->stage_max_us;
    d->image_msg.pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY;
}

void rted_count_publish(rted_daemon *d, rte_status st)
{
    if (st == RTE_OK)
        d->n.published++;
    else
        d->n.publish_errors++;
}

static void fill_header(rted_daemon *d, rtedge_header_t *h, const rte_source_frame *f,
                        int64_t t_pub)
{
    h->utime = d->capture_wall_us;
    h->capture_utime = f->capture_ns / 1000;
    h->publish_utime = t_pub / 1000;
    h->sequence = (int64_t)f->sequence;
    h->width = f->frame.width;
    h->height = f->frame.height;
    int64_t lat = (t_pub - f->capture_ns) / 1000;
    h->latency_us = lat > INT32_MAX ? INT32_MAX : (int32_t)lat;
    h->deadline_us = (int32_t)(d->deadline_ns / 1000);
    h->deadline_met = h->latency_us <= h->deadline_us;
}

static void fill_lane(rtedge_lane_t *m, const rte_lane *l)
{
    m->found = l->found;
    m->predicted = l->predicted;
    m->x1 = (float)l->x_bottom_q8 / RTE_LANE_ONE;
    m->y1 = (float)l->y_bottom;
    m->x2 = (float)l->x_top_q8 / RTE_LANE_ONE;
    m->y2 = (float)l->y_top;
    int32_t dy = l->y_top - l->y_bottom;
    m->slope = dy ? (m->x2 - m->x1) / (float)dy : 0.0f;
    m->confidence = (float)l->confidence_permille / 1000.0f;
    m->curvature = (float)rte_lane_curvature(l);
    int32_t xs[RTEDGE_LANE_T_MAX_POINTS], ys[RTEDGE_LANE_T_MAX_POINTS];
    const int32_t n = rte_lane_polyline(l, RTEDGE_LANE_T_MAX_POINTS, xs, ys);
    m->npoints = (int8_t)n;
    for (int32_t i = 0; i < RTEDGE_LANE_T_MAX_POINTS; i++) {
        m->points_x[i] = i < n ? (float)xs[i] / RTE_LANE_ONE : 0.0f;
        m->points_y[i] = i < n ? (float)ys[i] : 0.0f;
    }
}

void rted_publish_lane(rted_daemon *d, const rte_source_frame *f, const rte_lane_result *r)
{
    rtedge_lane_detection_t *m = &d->lane_msg;
    int32_t n =
        r->segment_count < d->cfg.lane_max_segments ? r->segment_count : d->cfg.lane_max_segments;
    for (int32_t i = 0; i < n; i++)
        d->segments[i] = (rtedge_segment_t){r->segments[i].x0, r->segments[i].y0, r->segments[i].x1,
                                            r->segments[i].y1};
    m->nsegments = n;
    m->segments_truncated = r->truncated || n < r->segment_count;
    fill_lane(&m->left, &r->lane[RTE_LANE_LEFT]);
    fill_lane(&m->right, &r->lane[RTE_LANE_RIGHT]);
    m->centre_valid = r->centre_valid;
    m->centre_offset_px = (float)r->offset_q8 / RTE_LANE_ONE;
    m->centre_offset_frac = (float)r->offset_permille / 1000.0f;
    m->heading_rad = (float)r->heading_mrad / 1000.0f;
    fill_header(d, &m->header, f, rte_clock_now_ns());
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    rted_count_publish(d, rte_publish_lane(d->pub, d->cfg.lane_channel, m, msg, sizeof msg));
}

static void fill_grasp_object(rtedge_grasp_object_t *g, const rte_grasp_object *o)
{
    const rte_shape_info *s = &o->info;
    g->centroid_x = (float)((double)s->cx_q16 / 65536);
    g->centroid_y = (float)((double)s->cy_q16 / 65536);
    g->area = (float)((double)s->area2 / 2);
    g->perimeter = (float)((double)s->perimeter_q16 / 65536);
    g->bbox_x = s->bounds.x;
    g->bbox_y = s->bounds.y;
    g->bbox_width = s->bounds.width;
    g->bbox_height = s->bounds.height;
    g->rect_centre_x = (float)s->box.cx_q8 / 256;
    g->rect_centre_y = (float)s->box.cy_q8 / 256;
    g->rect_width = (float)s->box.length_q8 / 256;
    g->rect_height = (float)s->box.width_q8 / 256;
    g->rect_angle_deg = (float)s->box.angle_q16 / 65536;
    for (int k = 0; k < 4; k++) {
        g->rect_corners_x[k] = (float)s->box.corners_q8[k][0] / 256;
        g->rect_corners_y[k] = (float)s->box.corners_q8[k][1] / 256;
    }
    g->shape = (int8_t)s->shape;
    g->vertices = s->vertices;
    g->solidity = (float)s->solidity_q16 / 65536;
    g->extent = (float)s->extent_q16 / 65536;
    g->aspect_ratio = (float)s->aspect_q16 / 65536;
    g->grasp_x = (float)o->x_q8 / 256;
    g->grasp_y = (float)o->y_q8 / 256;
    g->approach_angle_deg = (float)o->angle_q16 / 65536;
    g->opening_width_px = (float)o->opening_q8 / 256;
    g->narrowest_width_px = (float)o->width_q8 / 256;
    for (int k = 0; k < 2; k++) {
        g->jaw_x[k] = (float)o->jaws_q8[k][0] / 256;
        g->jaw_y[k] = (float)o->jaws_q8[k][1] / 256;
    }
    g->clearance_px = (float)o->clearance_q8 / 256;
    g->score = (float)o->score_q16 / 65536;
}

void rted_publish_grasp(rted_daemon *d, const rte_source_frame *f, const rte_grasp_result *r)
{
    rtedge_grasp_detection_t *m = &d->grasp_msg;
    int32_t n = r->n_objects < d->cfg.grasp_max_objects ? r->n_objects : d->cfg.grasp_max_objects;
    for (int32_t i = 0; i < n; i++)
        fill_grasp_object(&d->objects[i], &r->objects[i]);
    m->nobjects = n;
    m->objects_truncated = r->truncated || n < r->n_objects;
    fill_header(d, &m->header, f, rte_clock_now_ns());
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    rted_count_publish(d, rte_publish_grasp(d->pub, d->cfg.grasp_channel, m, msg, sizeof msg));
}

void rted_publish_image(rted_daemon *d, const rte_source_frame *f, const rte_image_u8 *g)
{
    rtedge_image_t *m = &d->image_msg;
    /* A view of the grey image when it is packed, else the daemon's copy. */
    if (g->stride != g->width) {
        for (int32_t y = 0; y < g->height; y++)
            memcpy(d->gray.buf + (size_t)y * (size_t)g->width,
                   g->buf + (size_t)y * (size_t)g->stride, (size_t)g->width);
        g = &d->gray;
    }
    m->utime = d->capture_wall_us;
    m->width = g->width;
    m->height = g->height;
    m->row_stride = g->width;
    m->size = g->width * g->height;
    m->data = g->buf;
    m->nmetadata = 0;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    rted_count_publish(d, rte_publish_image(d->pub, d->cfg.image_channel, m, msg, sizeof msg));
}
