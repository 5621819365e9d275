/* Sample messages for the LCM tests: every field set from a seed, so a
 * round trip that loses or swaps anything is seen. */
#ifndef RTEDGE_TEST_MESSAGES_H
#define RTEDGE_TEST_MESSAGES_H

#include <stdint.h>

#include "publish/publish.h"

#define SAMPLE_SEGMENTS 7
#define SAMPLE_OBJECTS 3
#define SAMPLE_ROI 4
#define SAMPLE_PARAMS 3
#define SAMPLE_IMAGE_W 33
#define SAMPLE_IMAGE_H 5

typedef struct samples {
    rtedge_point_t roi[SAMPLE_ROI];
    rtedge_segment_t segments[SAMPLE_SEGMENTS];
    rtedge_grasp_object_t objects[SAMPLE_OBJECTS];
    rtedge_param_t params[SAMPLE_PARAMS];
    uint8_t pixels[SAMPLE_IMAGE_W * SAMPLE_IMAGE_H];
    uint8_t meta_value[3];
    rtedge_image_metadata_t metadata[1];

    rtedge_lane_detection_t lane;
    rtedge_grasp_detection_t grasp;
    rtedge_status_t status;
    char *stage_names[2];
    int32_t stage_mean_us[2], stage_max_us[2];
    rtedge_params_t paramset;
    rtedge_image_t image;
} samples;

static inline float sample_f(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return (float)(*s % 100000) / 64.0f;
}

static inline int32_t sample_i(uint32_t *s) { return (int32_t)(sample_f(s) * 64.0f) - 50000; }

static inline void sample_header(rtedge_header_t *h, samples *s, uint32_t *r)
{
    h->capture_utime = 1700000000000000LL + sample_i(r);
    h->publish_utime = h->capture_utime + 1234;
    h->sequence = 42 + sample_i(r);
    h->source_id = (char *)"v4l2:/dev/video0";
    h->width = 1280;
    h->height = 720;
    h->roi_npoints = SAMPLE_ROI;
    for (int i = 0; i < SAMPLE_ROI; i++) {
        s->roi[i].x = sample_i(r);
        s->roi[i].y = sample_i(r);
    }
    h->roi = s->roi;
    h->latency_us = 1234;
    h->deadline_us = 20000;
    h->deadline_met = 1;
}

static inline void sample_lane(rtedge_lane_t *l, uint32_t *r)
{
    l->found = 1;
    l->predicted = 0;
    l->x1 = sample_f(r);
    l->y1 = sample_f(r);
    l->x2 = sample_f(r);
    l->y2 = sample_f(r);
    l->slope = sample_f(r);
    l->confidence = 0.75f;
    l->curvature = -0.001f;
    l->npoints = 3;
    for (int i = 0; i < RTEDGE_LANE_T_MAX_POINTS; i++) {
        l->points_x[i] = i < 3 ? sample_f(r) : 0.0f;
        l->points_y[i] = i < 3 ? 700.0f - 10.0f * (float)i : 0.0f;
    }
}

/* Fills every sample message; arrays point into s. */
static inline void samples_fill(samples *s, uint32_t seed)
{
    uint32_t r = seed | 1;
    rtedge_lane_detection_t *lane = &s->lane;
    sample_header(&lane->header, s, &r);
    for (int i = 0; i < SAMPLE_SEGMENTS; i++) {
        s->segments[i].x1 = sample_i(&r);
        s->segments[i].y1 = sample_i(&r);
        s->segments[i].x2 = sample_i(&r);
        s->segments[i].y2 = sample_i(&r);
    }
    lane->nsegments = SAMPLE_SEGMENTS;
    lane->segments = s->segments;
    lane->segments_truncated = 1;
    sample_lane(&lane->left, &r);
    sample_lane(&lane->right, &r);
    lane->right.predicted = 1;
    lane->centre_valid = 1;
    lane->centre_offset_px = sample_f(&r);
    lane->centre_offset_frac = 0.125f;
    lane->heading_rad = -0.5f;

    rtedge_grasp_detection_t *grasp = &s->grasp;
    sample_header(&grasp->header, s, &r);
    for (int i = 0; i < SAMPLE_OBJECTS; i++) {
        rtedge_grasp_object_t *o = &s->objects[i];
        float *fields[] = {&o->centroid_x,
                           &o->centroid_y,
                           &o->area,
                           &o->perimeter,
                           &o->rect_centre_x,
                           &o->rect_centre_y,
                           &o->rect_width,
                           &o->rect_height,
                           &o->rect_angle_deg,
                           &o->solidity,
                           &o->extent,
                           &o->aspect_ratio,
                           &o->grasp_x,
                           &o->grasp_y,
                           &o->approach_angle_deg,
                           &o->opening_width_px,
                           &o->narrowest_width_px,
                           &o->clearance_px};
        for (unsigned k = 0; k < sizeof fields / sizeof fields[0]; k++)
            *fields[k] = sample_f(&r);
        for (int k = 0; k < 2; k++) {
            o->jaw_x[k] = sample_f(&r);
            o->jaw_y[k] = sample_f(&r);
        }
        o->score = 0.25f * (float)i;
        for (int k = 0; k < 4; k++) {
            o->rect_corners_x[k] = sample_f(&r);
            o->rect_corners_y[k] = sample_f(&r);
        }
        o->bbox_x = sample_i(&r);
        o->bbox_y = sample_i(&r);
        o->bbox_width = 10 + i;
        o->bbox_height = 20 + i;
        o->shape = RTEDGE_GRASP_OBJECT_T_SHAPE_HEXAGON;
        o->vertices = 6;
    }
    grasp->nobjects = SAMPLE_OBJECTS;
    grasp->objects = s->objects;
    grasp->objects_truncated = 0;

    rtedge_status_t *st = &s->status;
    st->utime = 1000000 + sample_i(&r);
    st->source_id = (char *)"images:/data/*.png";
    st->source_state = RTEDGE_STATUS_T_SOURCE_ENDED;
    s->stage_names[0] = (char *)"lane.canny";
    s->stage_names[1] = (char *)"debug";
    s->stage_mean_us[0] = 1200;
    s->stage_mean_us[1] = 800;
    s->stage_max_us[0] = 2500;
    s->stage_max_us[1] = 1900;
    st->nstages = 2;
    st->stage_names = s->stage_names;
    st->stage_mean_us = s->stage_mean_us;
    st->stage_max_us = s->stage_max_us;
    st->frames_received = 1000;
    st->frames_processed = 990;
    st->frames_dropped = 10;
    st->deadline_misses = 3;
    st->stages_skipped = 1;
    st->window_us = 1000000;
    st->latency_p50_us = 4000;
    st->latency_p99_us = 9000;
    st->latency_max_us = 12000;
    st->fps = 29.97f;
    st->arena_bytes = 8 << 20;
    st->arena_peak_bytes = 5 << 20;
    st->config_hash = (int64_t)0x8badf00ddeadbeefULL;

    s->params[0] =
        (rtedge_param_t){(char *)"lane.canny_low", RTEDGE_PARAM_T_KIND_INT, 50, 0.0, (char *)""};
    s->params[1] =
        (rtedge_param_t){(char *)"deadline.ms", RTEDGE_PARAM_T_KIND_REAL, 0, 0.25, (char *)""};
    s->params[2] = (rtedge_param_t){(char *)"lane.canny_mode", RTEDGE_PARAM_T_KIND_TEXT, 0, 0.0,
                                    (char *)"fixed"};
    s->paramset =
        (rtedge_params_t){123456, 7, RTEDGE_PARAMS_T_ACTION_SET, SAMPLE_PARAMS, s->params};

    for (int i = 0; i < SAMPLE_IMAGE_W * SAMPLE_IMAGE_H; i++)
        s->pixels[i] = (uint8_t)sample_i(&r);
    s->meta_value[0] = 1;
    s->meta_value[1] = 2;
    s->meta_value[2] = 3;
    s->metadata[0] = (rtedge_image_metadata_t){(char *)"exposure", 3, s->meta_value};
    s->image = (rtedge_image_t){1700000000000001LL,
                                SAMPLE_IMAGE_W,
                                SAMPLE_IMAGE_H,
                                SAMPLE_IMAGE_W,
                                RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY,
                                SAMPLE_IMAGE_W * SAMPLE_IMAGE_H,
                                s->pixels,
                                1,
                                s->metadata};
}

/* The channels the samples go on, in sample_publish's order. */
static const char *const sample_channels[5] = {"LANES", "GRASP", "STATUS", "PARAMS", "IMAGE"};

/* Publishes sample message i (0..4: lane, grasp, status, params, image) on
 * sample_channels[i]. */
static inline rte_status sample_publish(rte_publisher *pub, int i, const samples *s, char *msg,
                                        size_t msg_size)
{
    const char *ch = sample_channels[i];
    switch (i) {
    case 0: return rte_publish_lane(pub, ch, &s->lane, msg, msg_size);
    case 1: return rte_publish_grasp(pub, ch, &s->grasp, msg, msg_size);
    case 2: return rte_publish_status(pub, ch, &s->status, msg, msg_size);
    case 3: return rte_publish_params(pub, ch, &s->paramset, msg, msg_size);
    default: return rte_publish_image(pub, ch, &s->image, msg, msg_size);
    }
}

#endif
