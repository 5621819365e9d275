/* LCM publisher: see publish.h. Every message goes through
 * publish_encoded(): encode into the one preallocated buffer, then either
 * lcm_publish (memq, udpm) or our own log writer (file://). */
#include "publish/publish.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "lcm_log.h"
#include "sources/source_msg.h"

struct rte_publisher {
    lcm_t *lcm;             /* memq://, udpm:// */
    rte_lcm_log_writer log; /* file:// (log.fd >= 0) */
    rte_publish_limits limits;
    uint8_t *buf;
    size_t capacity;
    rte_publish_stats stats;
};

/* ---- sizing: the generated _encoded_size of worst-case messages ---- */

/* The worst-case messages' arrays, zeroed (sizes do not depend on values,
 * strings aside). */
typedef struct worst_case {
    char *text;
    rtedge_point_t *roi;
    rtedge_segment_t *segments;
    rtedge_grasp_object_t *objects;
    rtedge_param_t *params;
    rtedge_image_metadata_t *metadata;
    uint8_t *bytes;
} worst_case;

static void *zalloc(size_t n, size_t size) { return calloc(n ? n : 1, size); }

static size_t max_size(size_t a, size_t b) { return a > b ? a : b; }

static size_t worst_case_size(const rte_publish_limits *l)
{
    worst_case w = {
        zalloc((size_t)l->max_text + 1, 1),
        zalloc((size_t)l->max_roi_points, sizeof(rtedge_point_t)),
        zalloc((size_t)l->max_segments, sizeof(rtedge_segment_t)),
        zalloc((size_t)l->max_objects, sizeof(rtedge_grasp_object_t)),
        zalloc((size_t)l->max_params, sizeof(rtedge_param_t)),
        zalloc((size_t)l->max_metadata, sizeof(rtedge_image_metadata_t)),
        zalloc((size_t)l->max_text + 1, 1),
    };
    size_t size = 0;
    if (w.text && w.roi && w.segments && w.objects && w.params && w.metadata && w.bytes) {
        memset(w.text, 'x', (size_t)l->max_text);
        rtedge_header_t h = {0};
        h.source_id = w.text;
        h.roi_npoints = (int16_t)l->max_roi_points;
        h.roi = w.roi;

        rtedge_lane_detection_t lane = {0};
        lane.header = h;
        lane.nsegments = l->max_segments;
        lane.segments = w.segments;
        size = max_size(size, (size_t)rtedge_lane_detection_t_encoded_size(&lane));

        rtedge_grasp_detection_t grasp = {0};
        grasp.header = h;
        grasp.nobjects = l->max_objects;
        grasp.objects = w.objects;
        size = max_size(size, (size_t)rtedge_grasp_detection_t_encoded_size(&grasp));

        char *stage_names[RTE_PUBLISH_MAX_STAGES];
        int32_t stage_us[RTE_PUBLISH_MAX_STAGES] = {0};
        for (int i = 0; i < RTE_PUBLISH_MAX_STAGES; i++)
            stage_names[i] = w.text;
        rtedge_status_t status = {0};
        status.source_id = w.text;
        status.nstages = RTE_PUBLISH_MAX_STAGES;
        status.stage_names = stage_names;
        status.stage_mean_us = status.stage_max_us = stage_us;
        size = max_size(size, (size_t)rtedge_status_t_encoded_size(&status));

        for (int32_t i = 0; i < l->max_params; i++)
            w.params[i].name = w.params[i].text_value = w.text;
        rtedge_params_t params = {0};
        params.nparams = l->max_params;
        params.params = w.params;
        size = max_size(size, (size_t)rtedge_params_t_encoded_size(&params));

        /* The image's data is counted, not built: it can be megabytes. */
        for (int32_t i = 0; i < l->max_metadata; i++) {
            w.metadata[i].key = w.text;
            w.metadata[i].n = l->max_text;
            w.metadata[i].value = w.bytes;
        }
        rtedge_image_t image = {0};
        image.nmetadata = l->max_metadata;
        image.metadata = w.metadata;
        size = max_size(size,
                        (size_t)rtedge_image_t_encoded_size(&image) + (size_t)l->max_image_bytes);
        size = max_size(size, (size_t)l->max_state_bytes);
    }
    free(w.text);
    free(w.roi);
    free(w.segments);
    free(w.objects);
    free(w.params);
    free(w.metadata);
    free(w.bytes);
    return size;
}

/* ---- creating ---- */

/* file://PATH[?mode=w|a] into path (capacity bytes) and *append. */
static rte_status parse_file_url(const char *url, char *path, size_t capacity, int *append,
                                 char *msg, size_t msg_size)
{
    const char *p = url + strlen("file://");
    const char *q = strchr(p, '?');
    size_t len = q ? (size_t)(q - p) : strlen(p);
    if (len == 0 || len >= capacity) {
        rte_source_msgf(msg, msg_size, "%s: no file name, or one too long", url);
        return RTE_ERR_ARGUMENT;
    }
    memcpy(path, p, len);
    path[len] = '\0';
    *append = 0;
    if (q) {
        if (strcmp(q, "?mode=a") == 0)
            *append = 1;
        else if (strcmp(q, "?mode=w") != 0) {
            rte_source_msgf(msg, msg_size, "%s: the only option is mode=w or mode=a", url);
            return RTE_ERR_ARGUMENT;
        }
    }
    return RTE_OK;
}

static int limits_ok(const rte_publish_limits *l)
{
    return l->max_text >= 0 && l->max_text <= 65535 && l->max_roi_points >= 0 &&
           l->max_roi_points <= INT16_MAX && l->max_segments >= 0 && l->max_segments <= 1000000 &&
           l->max_objects >= 0 && l->max_objects <= 100000 && l->max_params >= 0 &&
           l->max_params <= 10000 && l->max_image_bytes >= 0 && l->max_image_bytes <= (1 << 30) &&
           l->max_metadata >= 0 && l->max_metadata <= 1000;
}

rte_status rte_publisher_create(rte_publisher **out, const char *url,
                                const rte_publish_limits *limits, char *msg, size_t msg_size)
{
    if (!out || !url || !limits) {
        rte_source_msgf(msg, msg_size, "publisher: missing argument");
        return RTE_ERR_ARGUMENT;
    }
    *out = NULL;
    if (!limits_ok(limits)) {
        rte_source_msgf(msg, msg_size, "publisher: limits out of range");
        return RTE_ERR_ARGUMENT;
    }
    rte_publisher *pub = calloc(1, sizeof *pub);
    if (!pub) {
        rte_source_msgf(msg, msg_size, "publisher: no memory");
        return RTE_ERR_NO_MEMORY;
    }
    pub->log.fd = -1;
    pub->limits = *limits;
    pub->capacity = worst_case_size(limits);
    pub->buf = pub->capacity ? malloc(pub->capacity) : NULL;
    if (!pub->buf) {
        rte_source_msgf(msg, msg_size, "publisher: no memory for a %zu-byte buffer", pub->capacity);
        rte_publisher_destroy(pub);
        return RTE_ERR_NO_MEMORY;
    }
    rte_status st = RTE_OK;
    if (strncmp(url, "file://", 7) == 0) {
        char path[4096];
        int append;
        st = parse_file_url(url, path, sizeof path, &append, msg, msg_size);
        if (st == RTE_OK)
            st = rte_lcm_log_writer_open(&pub->log, path, append, msg, msg_size);
    } else {
        pub->lcm = lcm_create(url);
        if (!pub->lcm) {
            rte_source_msgf(msg, msg_size, "%s: liblcm cannot open it", url);
            st = RTE_ERR_IO;
        }
    }
    if (st != RTE_OK) {
        rte_publisher_destroy(pub);
        return st;
    }
    rte_source_msgf(msg, msg_size, "%s", "");
    *out = pub;
    return RTE_OK;
}

void rte_publisher_destroy(rte_publisher *pub)
{
    if (!pub)
        return;
    if (pub->lcm)
        lcm_destroy(pub->lcm);
    rte_lcm_log_writer_close(&pub->log);
    free(pub->buf);
    free(pub);
}

size_t rte_publisher_buffer_size(const rte_publisher *pub) { return pub->capacity; }

lcm_t *rte_publisher_lcm(rte_publisher *pub) { return pub->lcm; }

void rte_publisher_get_stats(const rte_publisher *pub, rte_publish_stats *stats)
{
    *stats = pub->stats;
}

/* ---- publishing ---- */

static int64_t realtime_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static rte_status refuse(rte_publisher *pub, rte_status st, char *msg, size_t msg_size,
                         const char *fmt, ...) __attribute__((format(printf, 5, 6)));

static rte_status refuse(rte_publisher *pub, rte_status st, char *msg, size_t msg_size,
                         const char *fmt, ...)
{
    pub->stats.refused++;
    if (msg && msg_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, msg_size, fmt, ap);
        va_end(ap);
    }
    return st;
}

static rte_status send_encoded(rte_publisher *pub, const char *channel, int len, char *msg,
                               size_t msg_size)
{
    if (len < 0)
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                      "%s: the message does not fit the %zu-byte buffer", channel, pub->capacity);
    if (pub->lcm) {
        if (lcm_publish(pub->lcm, channel, pub->buf, (unsigned int)len) != 0)
            return refuse(pub, RTE_ERR_IO, msg, msg_size, "%s: lcm_publish failed", channel);
    } else {
        /* The log's timestamp is wall-clock time, as lcm-logger writes it. */
        rte_status st = rte_lcm_log_write(&pub->log, realtime_utime(), channel, pub->buf,
                                          (size_t)len, msg, msg_size);
        if (st != RTE_OK)
            return refuse(pub, st, NULL, 0, "%s", "");
    }
    pub->stats.messages++;
    pub->stats.bytes += (uint64_t)len;
    rte_source_msgf(msg, msg_size, "%s", "");
    return RTE_OK;
}

static int text_ok(const char *s, int32_t max)
{
    return s && strnlen(s, (size_t)max + 1) <= (size_t)max;
}

static rte_status check_header(rte_publisher *pub, const char *channel, const rtedge_header_t *h,
                               char *msg, size_t msg_size)
{
    const rte_publish_limits *l = &pub->limits;
    if (!text_ok(h->source_id, l->max_text))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                      "%s: source_id missing or longer than %d bytes", channel, l->max_text);
    if (h->roi_npoints < 0 || h->roi_npoints > l->max_roi_points || (h->roi_npoints > 0 && !h->roi))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size, "%s: %d ROI points, at most %d",
                      channel, h->roi_npoints, l->max_roi_points);
    return RTE_OK;
}

static int count_ok(int32_t n, const void *array, int32_t max)
{
    return n >= 0 && n <= max && (n == 0 || array);
}

static rte_status check_channel(rte_publisher *pub, const char *channel, const void *m, char *msg,
                                size_t msg_size)
{
    if (!channel || !m || channel[0] == '\0' ||
        strnlen(channel, RTE_LCM_LOG_MAX_CHANNEL + 1) > RTE_LCM_LOG_MAX_CHANNEL)
        return refuse(pub, RTE_ERR_ARGUMENT, msg, msg_size,
                      "publish: missing message or channel, or a channel over %d bytes",
                      RTE_LCM_LOG_MAX_CHANNEL);
    return RTE_OK;
}

/* The maxlen argument of lcm-gen's _encode: the buffer, as an int. */
static int encode_limit(const rte_publisher *pub)
{
    return pub->capacity > INT32_MAX ? INT32_MAX : (int)pub->capacity;
}

rte_status rte_publish_lane(rte_publisher *pub, const char *channel,
                            const rtedge_lane_detection_t *m, char *msg, size_t msg_size)
{
    rte_status st = check_channel(pub, channel, m, msg, msg_size);
    if (st == RTE_OK)
        st = check_header(pub, channel, &m->header, msg, msg_size);
    if (st != RTE_OK)
        return st;
    if (!count_ok(m->nsegments, m->segments, pub->limits.max_segments))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size, "%s: %d segments, at most %d", channel,
                      m->nsegments, pub->limits.max_segments);
    int len = rtedge_lane_detection_t_encode(pub->buf, 0, encode_limit(pub), m);
    return send_encoded(pub, channel, len, msg, msg_size);
}

rte_status rte_publish_grasp(rte_publisher *pub, const char *channel,
                             const rtedge_grasp_detection_t *m, char *msg, size_t msg_size)
{
    rte_status st = check_channel(pub, channel, m, msg, msg_size);
    if (st == RTE_OK)
        st = check_header(pub, channel, &m->header, msg, msg_size);
    if (st != RTE_OK)
        return st;
    if (!count_ok(m->nobjects, m->objects, pub->limits.max_objects))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size, "%s: %d objects, at most %d", channel,
                      m->nobjects, pub->limits.max_objects);
    int len = rtedge_grasp_detection_t_encode(pub->buf, 0, encode_limit(pub), m);
    return send_encoded(pub, channel, len, msg, msg_size);
}

rte_status rte_publish_status(rte_publisher *pub, const char *channel, const rtedge_status_t *m,
                              char *msg, size_t msg_size)
{
    rte_status st = check_channel(pub, channel, m, msg, msg_size);
    if (st != RTE_OK)
        return st;
    if (!text_ok(m->source_id, pub->limits.max_text))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                      "%s: source_id missing or longer than %d bytes", channel,
                      pub->limits.max_text);
    if (m->nstages < 0 || m->nstages > RTE_PUBLISH_MAX_STAGES ||
        (m->nstages > 0 && (!m->stage_names || !m->stage_mean_us || !m->stage_max_us)))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size, "%s: %d stages, at most %d", channel,
                      m->nstages, RTE_PUBLISH_MAX_STAGES);
    for (int32_t i = 0; i < m->nstages; i++)
        if (!text_ok(m->stage_names[i], pub->limits.max_text))
            return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                          "%s: stage %d's name missing or over %d bytes", channel, i,
                          pub->limits.max_text);
    int len = rtedge_status_t_encode(pub->buf, 0, encode_limit(pub), m);
    return send_encoded(pub, channel, len, msg, msg_size);
}

rte_status rte_publish_image(rte_publisher *pub, const char *channel, const rtedge_image_t *m,
                             char *msg, size_t msg_size)
{
    rte_status st = check_channel(pub, channel, m, msg, msg_size);
    if (st != RTE_OK)
        return st;
    const rte_publish_limits *l = &pub->limits;
    if (!count_ok(m->size, m->data, l->max_image_bytes) ||
        !count_ok(m->nmetadata, m->metadata, l->max_metadata))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                      "%s: image of %d bytes with %d metadata, at most %d and %d", channel, m->size,
                      m->nmetadata, l->max_image_bytes, l->max_metadata);
    for (int32_t i = 0; i < m->nmetadata; i++)
        if (!text_ok(m->metadata[i].key, l->max_text) ||
            !count_ok(m->metadata[i].n, m->metadata[i].value, l->max_text))
            return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size, "%s: metadata %d over %d bytes",
                          channel, i, l->max_text);
    int len = rtedge_image_t_encode(pub->buf, 0, encode_limit(pub), m);
    return send_encoded(pub, channel, len, msg, msg_size);
}

rte_status rte_publish_params(rte_publisher *pub, const char *channel, const rtedge_params_t *m,
                              char *msg, size_t msg_size)
{
    rte_status st = check_channel(pub, channel, m, msg, msg_size);
    if (st != RTE_OK)
        return st;
    if (!count_ok(m->nparams, m->params, pub->limits.max_params))
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size, "%s: %d parameters, at most %d",
                      channel, m->nparams, pub->limits.max_params);
    for (int32_t i = 0; i < m->nparams; i++)
        if (!text_ok(m->params[i].name, pub->limits.max_text) ||
            !text_ok(m->params[i].text_value, pub->limits.max_text))
            return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                          "%s: parameter %d's name or text missing or over %d bytes", channel, i,
                          pub->limits.max_text);
    int len = rtedge_params_t_encode(pub->buf, 0, encode_limit(pub), m);
    return send_encoded(pub, channel, len, msg, msg_size);
}

rte_status rte_publish_param_state(rte_publisher *pub, const char *channel,
                                   const rtedge_param_state_t *m, char *msg, size_t msg_size)
{
    rte_status st = check_channel(pub, channel, m, msg, msg_size);
    if (st != RTE_OK)
        return st;
    /* Its strings are the daemon's own (never NULL); the size is what counts. */
    int size = rtedge_param_state_t_encoded_size(m);
    if (size < 0 || size > pub->limits.max_state_bytes)
        return refuse(pub, RTE_ERR_TOO_LARGE, msg, msg_size,
                      "%s: param_state_t of %d bytes, at most %d", channel, size,
                      pub->limits.max_state_bytes);
    int len = rtedge_param_state_t_encode(pub->buf, 0, encode_limit(pub), m);
    return send_encoded(pub, channel, len, msg, msg_size);
}
