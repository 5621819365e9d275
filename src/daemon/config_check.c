/* Checks across keys (config.h): the whole configuration, against a
 * frame size, and the list-valued keys' parsers. */
#include "config.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/fractions.h"
#include "rtedge/overlay.h"
#include "log.h"
#include "rtedge/lane.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/shape.h"

/* Calls each(name, len, user) for the ','-separated names of a list (blanks
 * around them trimmed); stops and returns false when each does. */
static bool each_listed(const char *list, bool (*each)(const char *name, size_t len, void *user),
                        void *user)
{
    const char *s = list;
    while (*s) {
        const char *e = strchr(s, ',');
        if (!e)
            e = s + strlen(s);
        const char *a = s, *b = e;
        while (a < b && (*a == ' ' || *a == '\t'))
            a++;
        while (b > a && (b[-1] == ' ' || b[-1] == '\t'))
            b--;
        if (!each(a, (size_t)(b - a), user))
            return false;
        s = *e ? e + 1 : e;
    }
    return true;
}

typedef struct name_match {
    const char *name;
    bool found;
} name_match;

static bool match_name(const char *name, size_t len, void *user)
{
    name_match *m = user;
    m->found = strlen(m->name) == len && !strncmp(m->name, name, len);
    return !m->found;
}

bool rted_config_params_allowed(const rted_config *c, const char *name)
{
    if (!c->params_keys[0])
        return true;
    name_match m = {name, false};
    each_listed(c->params_keys, match_name, &m);
    return m.found;
}

typedef struct list_check {
    char *msg;
    size_t msg_size;
} list_check;

/* params.keys: every name a runtime key. */
static bool check_listed(const char *name, size_t len, void *user)
{
    list_check *lc = user;
    char buf[128];
    if (len == 0 || len >= sizeof buf) {
        rted_msgf(lc->msg, lc->msg_size, "params.keys: an empty or overlong name in the list");
        return false;
    }
    memcpy(buf, name, len);
    buf[len] = 0;
    const rted_key *k = rted_config_find_key(buf);
    if (!k || !rted_key_is_runtime(k)) {
        rted_msgf(lc->msg, lc->msg_size, "params.keys: '%s' is not %s", buf,
                  !k ? "a key" : "a runtime key (it fixes sizes or the source)");
        return false;
    }
    return true;
}

typedef struct layer_list {
    int32_t mask;
    char *bad;
    size_t bad_size;
} layer_list;

static bool add_layer(const char *name, size_t len, void *user)
{
    layer_list *l = user;
    int32_t bit = rte_overlay_layer_named(name, len);
    if (bit < 0)
        snprintf(l->bad, l->bad_size, "%.*s", (int)(len > 64 ? 64 : len), name);
    else
        l->mask |= bit;
    return bit >= 0;
}

int32_t rted_parse_debug_layers(const char *text, char *bad, size_t bad_size)
{
    layer_list l = {0, bad, bad_size};
    return each_listed(text, add_layer, &l) ? l.mask : -1;
}

int32_t rted_parse_controls(const char *text, rte_v4l2_control *out, int32_t max)
{
    if (!out)
        max = RTE_V4L2_MAX_CONTROLS;
    int32_t n = 0;
    const char *s = text;
    while (*s) {
        const char *eq = strchr(s, '=');
        size_t len = eq ? (size_t)(eq - s) : 0;
        while (len && s[len - 1] == ' ')
            len--;
        while (len && *s == ' ') {
            s++;
            len--;
        }
        if (!eq || !len || len >= RTE_V4L2_NAME_SIZE || n >= max)
            return -1;
        char *end;
        errno = 0;
        long v = strtol(eq + 1, &end, 0);
        while (*end == ' ')
            end++;
        if (end == eq + 1 || errno || v < INT32_MIN || v > INT32_MAX || (*end && *end != ';'))
            return -1;
        if (out) {
            memcpy(out[n].name, s, len);
            out[n].name[len] = 0;
            out[n].value = (int32_t)v;
        }
        n++;
        s = *end ? end + 1 : end;
    }
    return n;
}

bool rted_config_validate(const rted_config *c, char *msg, size_t msg_size)
{
    rte_vertex roi[RTE_LANE_MAX_ROI_VERTICES > RTE_GRASP_MAX_ROI_VERTICES
                       ? RTE_LANE_MAX_ROI_VERTICES
                       : RTE_GRASP_MAX_ROI_VERTICES];
    if (rte_parse_fractions(c->lane_roi, roi, RTE_LANE_MAX_ROI_VERTICES) < 0) {
        rted_msgf(msg, msg_size, "lane.roi: '%s' is not 3..8 'x,y' fractions separated by ';'",
                  c->lane_roi);
        return false;
    }
    if (c->grasp_roi[0] && rte_parse_fractions(c->grasp_roi, roi, RTE_GRASP_MAX_ROI_VERTICES) < 0) {
        rted_msgf(msg, msg_size,
                  "grasp.roi: '%s' is not 3..8 'x,y' fractions separated by ';' (or empty)",
                  c->grasp_roi);
        return false;
    }
    if (c->lane_canny_low >= 0 && c->lane_canny_high >= 0 &&
        c->lane_canny_low > c->lane_canny_high) {
        rted_msgf(msg, msg_size, "lane.canny_low (%d) exceeds lane.canny_high (%d)",
                  c->lane_canny_low, c->lane_canny_high);
        return false;
    }
    if (c->lane_blur_ksize % 2 == 0 || c->grasp_blur_ksize % 2 == 0) {
        rted_msgf(msg, msg_size, "lane.blur_ksize and grasp.blur_ksize must be odd");
        return false;
    }
    if (c->grasp_max_area && c->grasp_max_area < c->grasp_min_area) {
        rted_msgf(msg, msg_size, "grasp.max_area is below grasp.min_area");
        return false;
    }
    if (c->grasp_gripper_min_px > c->grasp_gripper_max_px) {
        rted_msgf(msg, msg_size, "grasp.gripper_min_px (%d) exceeds grasp.gripper_max_px (%d)",
                  c->grasp_gripper_min_px, c->grasp_gripper_max_px);
        return false;
    }
    if (!c->source_path[0]) {
        rted_msgf(msg, msg_size, "source.path is empty");
        return false;
    }
    if (rted_parse_controls(c->source_controls, NULL, 0) < 0) {
        rted_msgf(msg, msg_size,
                  "source.controls: '%s' is not 'name=value;...' with at most %d "
                  "integer values and names of at most %d characters",
                  c->source_controls, RTE_V4L2_MAX_CONTROLS, RTE_V4L2_NAME_SIZE - 1);
        return false;
    }
    if (!c->lcm_url[0]) {
        rted_msgf(msg, msg_size, "publish.url is empty");
        return false;
    }
    list_check lc = {msg, msg_size};
    if (!each_listed(c->params_keys, check_listed, &lc))
        return false;
    char bad[80];
    if (rted_parse_debug_layers(c->debug_layers, bad, sizeof bad) < 0) {
        rted_msgf(msg, msg_size,
                  "debug.layers: '%s' is none of roi, edges, segments, lanes, contours, grasp, "
                  "labels, all",
                  bad);
        return false;
    }
    /* liblcm takes a subscription's channel as a regular expression: a plain
     * name only, and none of the daemon's own (it would read its output). */
    if (!c->params_channel[0] ||
        strspn(c->params_channel,
               "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
               "abcdefghijklmnopqrstuvwxyz0123456789_-") != strlen(c->params_channel)) {
        rted_msgf(msg, msg_size,
                  "params.channel: '%s' is not a channel name of letters, digits, "
                  "'_' and '-'",
                  c->params_channel);
        return false;
    }
    const char *own[] = {c->lane_channel,  c->grasp_channel,        c->status_channel,
                         c->image_channel, c->params_state_channel, c->debug_channel};
    for (size_t i = 0; i < sizeof own / sizeof own[0]; i++)
        if (!strcmp(own[i], c->params_channel)) {
            rted_msgf(msg, msg_size,
                      "params.channel: %s is also one of the channels rtedged "
                      "publishes on",
                      c->params_channel);
            return false;
        }
    return true;
}

bool rted_config_check_frame(const rted_config *c, int32_t width, int32_t height, char *msg,
                             size_t msg_size)
{
    const int64_t span = (int64_t)width + height, area = (int64_t)width * height;
    const struct {
        const char *name;
        int32_t value;
    } lengths[] = {{"lane.hough_threshold", c->lane_hough_threshold},
                   {"lane.min_length", c->lane_min_length},
                   {"lane.max_gap", c->lane_max_gap},
                   {"lane.gate_px", c->lane_gate_px}};
    for (size_t i = 0; c->lane_enabled && i < sizeof lengths / sizeof lengths[0]; i++)
        if (lengths[i].value > span) {
            rted_msgf(msg, msg_size,
                      "%s = %d is beyond the %dx%d frame's width + height (%lld): "
                      "nothing could ever reach it",
                      lengths[i].name, lengths[i].value, width, height, (long long)span);
            return false;
        }
    if (c->grasp_enabled && c->grasp_min_area > area) {
        rted_msgf(msg, msg_size,
                  "grasp.min_area = %d px is beyond the %dx%d frame's %lld px: no "
                  "object could ever be found",
                  c->grasp_min_area, width, height, (long long)area);
        return false;
    }
    if (!c->lane_enabled)
        return true;
    rte_vertex q16[RTE_LANE_MAX_ROI_VERTICES], px[RTE_LANE_MAX_ROI_VERTICES];
    int32_t n = rte_parse_fractions(c->lane_roi, q16, RTE_LANE_MAX_ROI_VERTICES);
    if (n < 0) {
        rted_msgf(msg, msg_size, "lane.roi: '%s' is not 3..8 'x,y' fractions separated by ';'",
                  c->lane_roi);
        return false;
    }
    if (rte_polygon_from_fractions(q16, n, width, height, px) != RTE_OK) {
        rted_msgf(msg, msg_size, "lane.roi: '%s' cannot be placed on a %dx%d frame", c->lane_roi,
                  width, height);
        return false;
    }
    rte_point pts[RTE_LANE_MAX_ROI_VERTICES];
    for (int32_t i = 0; i < n; i++)
        pts[i] = (rte_point){px[i].x, px[i].y};
    /* The part of the bounding box inside the frame (as the lane path crops). */
    rte_rect box = rte_shape_bounding_rect(pts, n);
    int32_t x0 = box.x < 0 ? 0 : box.x, y0 = box.y < 0 ? 0 : box.y;
    int32_t x1 = box.x + box.width > width ? width : box.x + box.width;
    int32_t y1 = box.y + box.height > height ? height : box.y + box.height;
    int64_t inside_w = x1 - x0, inside_h = y1 - y0;
    if (inside_w < RTED_ROI_MIN_SIDE || inside_h < RTED_ROI_MIN_SIDE) {
        rted_msgf(msg, msg_size,
                  "lane.roi: '%s' covers %lldx%lld px of the %dx%d frame: at least "
                  "%dx%d are needed",
                  c->lane_roi, inside_w > 0 ? (long long)inside_w : 0,
                  inside_h > 0 ? (long long)inside_h : 0, width, height, RTED_ROI_MIN_SIDE,
                  RTED_ROI_MIN_SIDE);
        return false;
    }
    if (llabs(rte_shape_area2(pts, n)) * 1000 < 2 * area) {
        rted_msgf(msg, msg_size, "lane.roi: '%s' encloses less than 1/1000 of the %dx%d frame",
                  c->lane_roi, width, height);
        return false;
    }
    return true;
}
