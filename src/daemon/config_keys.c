/* The configuration table (see config.h). One row per key: everything
 * about a key lives in its row, so the reader (config_file.c), the
 * validator (config_check.c), `--help-config`, the effective-config
 * printer, the hash and the SIGHUP rule (runtime keys apply, fixed keys
 * are refused) cannot disagree. */
#include "config_table.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "log.h"
#include "rtedge/grasp.h"
#include "rtedge/lane.h"
#include "rtedge/polygon_mask.h"
#include "rtedge/shape.h"

#define K_INT RTED_KEY_INT
#define K_REAL RTED_KEY_REAL
#define K_BOOL RTED_KEY_BOOL
#define K_TEXT RTED_KEY_TEXT
#define K_ENUM RTED_KEY_CHOICE

typedef struct rted_key key_def;

static const char *const source_kinds[] = {"auto", "y4m",  "images",    "raw", "lcm-log",
                                           "lcm",  "v4l2", "libcamera", NULL};
static const char *const paces[] = {"recorded", "fps", "fast", NULL};
static const char *const canny_modes[] = {"fixed", "median", "otsu", NULL};
static const char *const binarizers[] = {"otsu", "fixed", "canny-close", "background", NULL};
static const char *const polarities[] = {"auto", "dark", "bright", NULL};

#define OFF(f) offsetof(rted_config, f)
/* A number key: type t, unit u, range lo..hi, and (has_un) a value `un`
 * meaning "the default" besides the range. */
#define NUM(t, s, k, f, u, has_un, un, lo, hi, rt, d, h)          \
    {                                                             \
        s, k, t, OFF(f), 0, u, lo, hi, has_un, un, NULL, rt, d, h \
    }
#define INT(s, k, f, u, lo, hi, rt, d, h) NUM(K_INT, s, k, f, u, false, 0, lo, hi, rt, d, h)
#define INTU(s, k, f, u, un, lo, hi, rt, d, h) NUM(K_INT, s, k, f, u, true, un, lo, hi, rt, d, h)
#define REAL(s, k, f, u, lo, hi, rt, d, h) NUM(K_REAL, s, k, f, u, false, 0, lo, hi, rt, d, h)
#define REALU(s, k, f, u, un, lo, hi, rt, d, h) NUM(K_REAL, s, k, f, u, true, un, lo, hi, rt, d, h)
#define BOOL(s, k, f, rt, d, h)                                     \
    {                                                               \
        s, k, K_BOOL, OFF(f), 0, "", 0, 1, false, 0, NULL, rt, d, h \
    }
#define TEXT(s, k, f, rt, d, h)                                                                 \
    {                                                                                           \
        s, k, K_TEXT, OFF(f), sizeof(((rted_config *)0)->f), "", 0, 0, false, 0, NULL, rt, d, h \
    }
#define ENUM(s, k, f, ch, rt, d, h)                               \
    {                                                             \
        s, k, K_ENUM, OFF(f), 0, "", 0, 0, false, 0, ch, rt, d, h \
    }

static const key_def keys[] = {
    ENUM("source", "kind", source_kind, source_kinds, false, "auto",
         "what `path` is; auto: *.y4m, a directory or glob of images, *.lcm/*.log\n"
         "(an LCM log of image_t), udpm:// or memq:// (live image_t), /dev/video*;\n"
         "libcamera: path is the camera id, or its index in `cam -l`"),
    TEXT("source", "path", source_path, false, "/dev/video0",
         "the recording, image directory or glob, LCM URL, V4L2 device or camera"),
    TEXT("source", "channel", source_channel, false, "",
         "LCM sources: the image_t channel (a log: empty = every channel)"),
    TEXT("source", "format", source_format, false, "",
         "images, raw, v4l2, libcamera: pixel format (grey, bgr24, rgb24, yuyv,\n"
         "uyvy, nv12; v4l2 also mjpeg, decoded to grey); empty: bgr24 (images),\n"
         "yuyv (v4l2), the camera's choice (libcamera)"),
    INT("source", "width", width, "px", 0, 8192, false, "0",
        "largest frame width (raw, v4l2: the frame width); 0: from the source"),
    INT("source", "height", height, "px", 0, 8192, false, "0", "largest frame height, as width"),
    ENUM("source", "pace", pace, paces, false, "recorded",
         "recorded: the recording's timestamps scaled by speed; fps: a fixed rate;\n"
         "fast: as fast as possible (never drops)"),
    REAL("source", "fps", fps, "Hz", 0.1, 1000, false, "30", "the rate of pace = fps"),
    REAL("source", "speed", speed, "x", 0.001, 1000, false, "1",
         "pace = recorded: 2 = twice real time"),
    INT("source", "max_pause_ms", max_pause_ms, "ms", 0, 86400000, false, "10000",
        "pace = recorded: a frame recorded longer than this after the one before\n"
        "is due at once, and the pace starts again from it (a pause in a log, a\n"
        "damaged timestamp); 0: wait out any pause"),
    BOOL("source", "loop", loop, false, "false", "start a recording again at its end"),
    INT("source", "max_frames", max_frames, "frames", 0, 2147483647, false, "0",
        "stop after this many processed frames; 0: never"),
    TEXT("source", "controls", source_controls, false, "",
         "v4l2: controls set at open and at each reopening, 'name=value' pairs,\n"
         "';'-separated, names as `v4l2-ctl -l` prints them (e.g. brightness=140;\n"
         "auto_exposure=1;exposure_time_absolute=100)"),
    BOOL("source", "wait", wait_camera, false, "true",
         "v4l2, libcamera: a camera missing at start is waited for (tried again\n"
         "after 0.5 s, doubling to 8 s), with the daemon sized for width x height\n"
         "(0: 1280x720) and, for libcamera, format (which must then be set);\n"
         "false: rtedged exits 1"),
    TEXT("source", "record", record_path, false, "",
         "write every frame the source delivers to this LCM log of image_t (the\n"
         "frames as delivered, on publish.image_channel); replay it with\n"
         "path = the log; empty: no recording"),

    BOOL("lane", "enabled", lane_enabled, false, "true", "run the lane path"),
    INT("lane", "max_segments", lane_max_segments, "segments", 1, 65536, false, "512",
        "Hough segments kept and published per frame"),
    INT("lane", "blur_ksize", lane_blur_ksize, "px", 1, 15, false, "5",
        "Gaussian kernel size (odd)"),
    ENUM("lane", "canny_mode", lane_canny_mode, canny_modes, true, "median",
         "Canny thresholds: fixed (canny_low/high) or from the ROI's histogram"),
    INTU("lane", "canny_low", lane_canny_low, "L1 gradient", -1, 0, 2040, true, "-1",
         "fixed mode, L1 gradient; -1: the lane default (50); at most canny_high"),
    INTU("lane", "canny_high", lane_canny_high, "L1 gradient", -1, 0, 2040, true, "-1",
         "fixed mode, L1 gradient; -1: the lane default (150)"),
    INTU("lane", "hough_threshold", lane_hough_threshold, "votes", -1, 1, 16384, true, "-1",
         "Hough votes; -1: the lane default for the frame height; at most the\n"
         "frame's width + height (more could never be reached)"),
    INTU("lane", "min_length", lane_min_length, "px", -1, 0, 16384, true, "-1",
         "shortest segment, pixels; -1: default for the frame height; at most\n"
         "the frame's width + height"),
    INTU("lane", "max_gap", lane_max_gap, "px", -1, 0, 16384, true, "-1",
         "largest gap joined in a segment; -1: default for the frame height; at\n"
         "most the frame's width + height"),
    INT("lane", "hough_seed", lane_hough_seed, "", 0, INT32_MAX, true, "0",
        "point order of the Hough search; 0: the built-in seed"),
    INTU("lane", "hold_frames", lane_hold_frames, "frames", -1, 0, 1000, true, "-1",
         "frames a lost lane is predicted; -1: the lane default"),
    INTU("lane", "gate_px", lane_gate_px, "px", -1, 0, 16384, true, "-1",
         "segments farther from a tracked lane are ignored; -1: default; at most\n"
         "the frame's width + height"),
    BOOL("lane", "use_color", lane_use_color, true, "true",
         "colour frames: white/yellow paint cue"),
    BOOL("lane", "curves", lane_curves, true, "true",
         "follow bends: a curve model per lane beside the straight fit (docs/lanes.md)"),
    TEXT("lane", "roi", lane_roi, true, "0,1;0.45,0.6;0.55,0.6;1,1",
         "ROI polygon, 3..8 'x,y' fractions of width and height, ';'-separated"),

    BOOL("grasp", "enabled", grasp_enabled, false, "true",
         "run the grasp path (optional stage: skipped first when the deadline is short)"),
    INT("grasp", "max_objects", grasp_max_objects, "objects", 1, 1024, false, "32",
        "objects kept and published per frame"),
    INT("grasp", "max_contours", grasp_max_contours, "contours", 1, 1000000, false, "4096",
        "contours stored per frame"),
    INT("grasp", "max_points", grasp_max_points, "points", 16, 50000000, false, "262144",
        "contour points stored per frame"),
    INT("grasp", "blur_ksize", grasp_blur_ksize, "px", 1, 15, false, "5", "Gaussian size (odd)"),
    ENUM("grasp", "binarize", grasp_binarize, binarizers, true, "background",
         "object mask: Otsu, a fixed threshold, closed Canny edges, or the\n"
         "difference from the table's estimated brightness, both ways (uneven\n"
         "light, objects lighter and darker than the table)"),
    INT("grasp", "contrast", grasp_contrast, "grey levels", 1, 255, true, "20",
        "binarize = background: the least difference from the table of an object"),
    INTU("grasp", "background_cell", grasp_background_cell, "px", 0, 2, 255, true, "0",
         "binarize = background: cells of the table's estimate; objects\n"
         "over about 9 cells across may join the table if as even as it; 0: a\n"
         "40th of the frame's width"),
    BOOL("grasp", "chroma", grasp_chroma, true, "true",
         "binarize = background, colour frames: a pixel's colour difference\n"
         "from the table's counts as contrast where it exceeds its grey one (an\n"
         "object as grey as the table but of another colour is found), and a\n"
         "dark object's cast shadow (the table dimmed, its colour kept) is\n"
         "dropped"),
    REAL("grasp", "edge_support", grasp_edge_support, "share", 0, 1, true, "0.75",
         "binarize = background: the least share of an object's outline beside\n"
         "the table that steps from it by a fifth of contrast or more; less is a\n"
         "threshold across a smooth ramp (a shaded box crossing the table's\n"
         "grey, a soft shadow's rim), dropped; 0: off"),
    INT("grasp", "threshold", grasp_threshold, "grey level", 0, 255, true, "128",
        "binarize = fixed"),
    ENUM("grasp", "polarity", grasp_polarity, polarities, true, "auto",
         "objects darker or brighter than the table; auto: both (background),\n"
         "else not the border's side"),
    INT("grasp", "min_area", grasp_min_area, "px²", 0, 67108864, true, "100",
        "smallest object, px; at most the frame's area"),
    INTU("grasp", "max_area", grasp_max_area, "px²", 0, 1, 67108864, true, "0",
         "largest object, px; 0: no limit"),
    BOOL("grasp", "split", grasp_split, true, "true",
         "split touching objects at their necks (chamfer distance of each\n"
         "contour of solidity below 0.95; parts alike in size only)"),
    BOOL("grasp", "skip_border", grasp_skip_border, true, "true",
         "drop objects touching the image border (or the workspace's)"),
    TEXT("grasp", "roi", grasp_roi, true, "",
         "the workspace: 3..8 'x,y' fractions of width and height, ';'-separated\n"
         "(e.g. 0.1,0.1;0.9,0.1;0.9,0.9;0.1,0.9); objects are looked for inside\n"
         "it only, and one reaching its edge touches the border; empty: the\n"
         "whole frame"),
    INT("grasp", "gripper_min_px", grasp_gripper_min_px, "px", 0, RTE_GRASP_MAX_OPENING_PX, true,
        "4",
        "narrowest object the jaws can close on (score 0 below); at most\n"
        "gripper_max_px"),
    INT("grasp", "gripper_max_px", grasp_gripper_max_px, "px", 0, RTE_GRASP_MAX_OPENING_PX, true,
        "160", "widest opening of the jaws (score 0 for wider objects)"),
    INT("grasp", "margin_px", grasp_margin_px, "px", 0, RTE_GRASP_MAX_CLEARANCE_PX, true, "8",
        "the jaws open this much wider than the object on each side"),
    INT("grasp", "finger_px", grasp_finger_px, "px", 0, RTE_GRASP_MAX_CLEARANCE_PX, true, "8",
        "free room each finger needs beyond its opened jaw face; the score\n"
        "falls with the room found on the closing line (docs/gripper.md)"),

    TEXT("publish", "url", lcm_url, false, "udpm://239.255.76.67:7667?ttl=0",
         "LCM URL: udpm://..., memq:// (tests), file://PATH[?mode=w|a] (a log)"),
    TEXT("publish", "lane_channel", lane_channel, false, "RTEDGE_LANES", "lane_detection_t"),
    TEXT("publish", "grasp_channel", grasp_channel, false, "RTEDGE_GRASP", "grasp_detection_t"),
    TEXT("publish", "status_channel", status_channel, false, "RTEDGE_STATUS",
         "status_t, once per status_period_ms"),
    BOOL("publish", "images", publish_images, false, "false",
         "also publish each analysed grey frame as image_t (for tools/render_log)"),
    TEXT("publish", "image_channel", image_channel, false, "RTEDGE_IMAGE", "image_t"),
    INT("publish", "status_period_ms", status_period_ms, "ms", 10, 60000, false, "1000",
        "status_t period and latency window"),

    BOOL("params", "enabled", params_enabled, false, "false",
         "take run-time parameter changes (params_t) on `channel`. The channel is\n"
         "unauthenticated: anyone who can send to publish.url can change the keys\n"
         "below; keep udpm:// on a private interface (docs/daemon.md)"),
    TEXT("params", "channel", params_channel, false, "RTEDGE_PARAMS",
         "params_t in (udpm://, memq://)"),
    TEXT("params", "keys", params_keys, false, "",
         "the keys params_t may change, 'section.key' separated by ','; empty:\n"
         "every runtime key"),
    INT("params", "max_per_second", params_max_per_second, "1/s", 1, 1000, false, "10",
        "params_t messages handled per second (a burst of as many); more are\n"
        "counted in status_t's config_rate_limited and dropped, not queued"),
    TEXT("params", "state_channel", params_state_channel, false, "RTEDGE_PARAM_STATE",
         "param_state_t out: every runtime key's type, range and value, and the\n"
         "last request's outcome; at start, after each change, every state_period_ms"),
    INT("params", "state_period_ms", params_state_period_ms, "ms", 100, 60000, false, "2000",
        "param_state_t period"),
    TEXT("params", "save_path", params_save_path, false, "",
         "params_t ACTION_SAVE writes the configuration in force here as an\n"
         "rtedged.conf (replacing the file whole); empty: the text is only returned\n"
         "in param_state_t"),

    BOOL("debug", "enabled", debug_enabled, false, "false",
         "publish a debug overlay stream: the analysed frame with the layers below,\n"
         "JPEG-encoded (image_t, MJPEG) on `channel`; memory for it is set aside at\n"
         "start, and nothing is allocated per frame"),
    TEXT("debug", "channel", debug_channel, false, "RTEDGE_DEBUG", "image_t (MJPEG) out"),
    REAL("debug", "rate_hz", debug_rate_hz, "Hz", 0.1, 100, true, "10",
         "at most this many overlay frames a second (frames in between are skipped)"),
    REAL("debug", "scale", debug_scale, "x", 0.05, 1, true, "0.5",
         "the overlay's size as a fraction of the frame's"),
    TEXT("debug", "layers", debug_layers, true, "roi,edges,segments,lanes,contours,grasp,labels",
         "what the overlay shows, ','-separated: roi, edges, segments, lanes,\n"
         "contours, grasp, labels, or all; empty: the frame alone"),
    INT("debug", "quality", debug_quality, "", 1, 100, true, "80", "JPEG quality"),

    REALU("deadline", "ms", deadline_ms, "ms", 0, 0.1, 10000, true, "0",
          "per-frame budget, capture to publish; 0: 1000 / source.fps"),
    REAL("deadline", "grasp_min_budget_ms", grasp_min_budget_ms, "ms", 0, 10000, true, "2",
         "skip the optional stages (the grasp path, publish.images, the debug\n"
         "overlay) when less than this is left of the budget"),
    REALU("deadline", "max_late_ms", max_late_ms, "ms", -1, 0, 60000, false, "100",
          "drop frames later than this behind their pace; -1: never"),

    INT("realtime", "priority", rt_priority, "", 0, 99, false, "0",
        "SCHED_FIFO priority; 0: normal scheduling (a warning if not permitted)"),
    INT("realtime", "cpu", rt_cpu, "", -1, 1023, false, "-1", "pin to this CPU; -1: no affinity"),
    BOOL("realtime", "mlockall", rt_mlockall, false, "false",
         "lock all memory (a warning if not permitted)"),
    INT("realtime", "cpu_dma_latency_us", rt_cpu_dma_latency_us, "us", -1, 1000000, false, "-1",
        "while rtedged runs, keep the CPUs out of idle states that take longer\n"
        "than this to wake from (/dev/cpu_dma_latency, a warning if not\n"
        "permitted); 0: they only poll; -1: the kernel's own choice"),
    INT("realtime", "threads", rt_threads, "", 1, 2, false, "1",
        "2: the grasp path runs on a second thread, made at start, beside the\n"
        "lane path (the same results, published by the main thread), pinned to\n"
        "the CPU after `cpu` when `cpu` is set; 1: one thread runs both in turn"),
};
#define N_KEYS (sizeof keys / sizeof keys[0])
_Static_assert(N_KEYS <= RTED_CONFIG_MAX_KEYS, "raise RTED_CONFIG_MAX_KEYS");

const rted_key *rted_config_lookup(const char *section, const char *key, bool *section_known)
{
    *section_known = false;
    for (size_t i = 0; i < N_KEYS; i++) {
        if (strcmp(keys[i].section, section) != 0)
            continue;
        *section_known = true;
        if (strcmp(keys[i].key, key) == 0)
            return &keys[i];
    }
    return NULL;
}

bool rted_config_section_exists(const char *section)
{
    for (size_t i = 0; i < N_KEYS; i++)
        if (!strcmp(keys[i].section, section))
            return true;
    return false;
}

size_t rted_key_index(const rted_key *k) { return (size_t)(k - keys); }

/* " (or -1)" for keys with an unset value, "" for the others. */
static const char *unset_text(const key_def *k, char *buf, size_t size)
{
    if (!k->has_unset)
        return "";
    snprintf(buf, size, " (or %g)", k->unset);
    return buf;
}

/* Integer keys: v in range (or the unset value), stored. */
static bool store_int(rted_config *c, const key_def *k, long long v, char *why, size_t why_size)
{
    if (!(k->has_unset && (double)v == k->unset) && ((double)v < k->min || (double)v > k->max)) {
        char u[32];
        rted_msgf(why, why_size, "%lld is out of range %.0f..%.0f%s", v, k->min, k->max,
                  unset_text(k, u, sizeof u));
        return false;
    }
    *(int32_t *)((char *)c + k->offset) = (int32_t)v;
    return true;
}

/* Real keys: finite, in range (or the unset value), stored. */
static bool store_real(rted_config *c, const key_def *k, double v, char *why, size_t why_size)
{
    if (!isfinite(v)) {
        rted_msgf(why, why_size, "%g is not a finite number", v);
        return false;
    }
    if (!(k->has_unset && v == k->unset) && (v < k->min || v > k->max)) {
        char u[32];
        rted_msgf(why, why_size, "%g is out of range %g..%g%s", v, k->min, k->max,
                  unset_text(k, u, sizeof u));
        return false;
    }
    *(double *)((char *)c + k->offset) = v;
    return true;
}

/* Stores `value` (text, as in the file) into the key's field; false and a
 * reason otherwise. */
bool rted_config_store(rted_config *c, const rted_key *k, const char *value, char *why,
                       size_t why_size)
{
    char *field = (char *)c + k->offset;
    char *end;
    switch (k->type) {
    case K_INT: {
        errno = 0;
        long long v = strtoll(value, &end, 10);
        if (end == value || *end || errno) {
            rted_msgf(why, why_size, "'%s' is not an integer%s", value,
                      errno == ERANGE ? " of 64 bits" : "");
            return false;
        }
        return store_int(c, k, v, why, why_size);
    }
    case K_REAL: {
        errno = 0;
        double v = strtod(value, &end);
        if (end == value || *end || errno || !isfinite(v)) {
            rted_msgf(why, why_size, "'%s' is not a number", value);
            return false;
        }
        return store_real(c, k, v, why, why_size);
    }
    case K_BOOL:
        if (!strcasecmp(value, "true") || !strcasecmp(value, "yes") || !strcmp(value, "1") ||
            !strcasecmp(value, "on"))
            *(bool *)field = true;
        else if (!strcasecmp(value, "false") || !strcasecmp(value, "no") || !strcmp(value, "0") ||
                 !strcasecmp(value, "off"))
            *(bool *)field = false;
        else {
            rted_msgf(why, why_size, "'%s' is not a boolean (true/false)", value);
            return false;
        }
        return true;
    case K_TEXT:
        if (strlen(value) >= k->size) {
            rted_msgf(why, why_size, "longer than %zu characters", k->size - 1);
            return false;
        }
        if (value[0] && (strchr(" \t", value[0]) || strchr(" \t", value[strlen(value) - 1]))) {
            /* the file would read it back without them */
            rted_msgf(why, why_size, "'%s' starts or ends with a blank", value);
            return false;
        }
        for (const char *p = value; *p; p++)
            if ((unsigned char)*p < 0x20 || *p == 0x7f) {
                rted_msgf(why, why_size, "a control character (0x%02x) in the text", *p);
                return false;
            }
        if (value[0] == '#' || strstr(value, " #") || strstr(value, "\t#")) {
            /* the file would read it back as a comment (config_file.c) */
            rted_msgf(why, why_size, "'%s': a '#' at the start or after a blank begins a comment",
                      value);
            return false;
        }
        memcpy(field, value, strlen(value) + 1);
        return true;
    case K_ENUM:
        for (int32_t i = 0; k->choices[i]; i++)
            if (!strcasecmp(value, k->choices[i])) {
                *(int32_t *)field = i;
                return true;
            }
        {
            int n = snprintf(why, why_size, "'%s' is not one of", value);
            for (int32_t i = 0; k->choices[i] && n > 0 && (size_t)n < why_size; i++)
                n += snprintf(why + n, why_size - (size_t)n, " %s", k->choices[i]);
        }
        return false;
    }
    return false;
}

const rted_key *rted_config_find_key(const char *name)
{
    const char *dot = strchr(name, '.');
    char section[64];
    bool known;
    if (!dot || (size_t)(dot - name) >= sizeof section)
        return NULL;
    memcpy(section, name, (size_t)(dot - name));
    section[dot - name] = 0;
    return rted_config_lookup(section, dot + 1, &known);
}

const rted_key *rted_config_key_at(size_t index) { return index < N_KEYS ? &keys[index] : NULL; }

void rted_key_get_name(const rted_key *k, char *name, size_t name_size)
{
    snprintf(name, name_size, "%s.%s", k->section, k->key);
}

rted_key_type rted_key_get_type(const rted_key *k) { return k->type; }

bool rted_key_is_runtime(const rted_key *k) { return k->runtime; }

static bool wrong_type(const key_def *k, const char *given, char *why, size_t why_size)
{
    static const char *const names[] = {"an integer", "a real number", "a boolean", "text",
                                        "a choice"};
    rted_msgf(why, why_size, "%s.%s takes %s, not %s", k->section, k->key, names[k->type], given);
    return false;
}

bool rted_config_set_int(rted_config *c, const rted_key *k, int64_t value, char *why,
                         size_t why_size)
{
    if (k->type != K_INT)
        return wrong_type(k, "an integer", why, why_size);
    return store_int(c, k, (long long)value, why, why_size);
}

bool rted_config_set_real(rted_config *c, const rted_key *k, double value, char *why,
                          size_t why_size)
{
    if (k->type != K_REAL)
        return wrong_type(k, "a real number", why, why_size);
    return store_real(c, k, value, why, why_size);
}

bool rted_config_set_bool(rted_config *c, const rted_key *k, bool value, char *why, size_t why_size)
{
    if (k->type != K_BOOL)
        return wrong_type(k, "a boolean", why, why_size);
    *(bool *)((char *)c + k->offset) = value;
    return true;
}

bool rted_config_set_text(rted_config *c, const rted_key *k, const char *value, char *why,
                          size_t why_size)
{
    if (k->type != K_TEXT && k->type != K_ENUM)
        return wrong_type(k, "text", why, why_size);
    return rted_config_store(c, k, value, why, why_size);
}

void rted_config_defaults(rted_config *c)
{
    memset(c, 0, sizeof *c);
    char why[RTED_MSG];
    for (size_t i = 0; i < N_KEYS; i++)
        if (!rted_config_store(c, &keys[i], keys[i].def, why, sizeof why))
            abort(); /* a bad default in the table is a programming error */
}

void rted_key_describe(const rted_key *k, rted_key_desc *d)
{
    *d = (rted_key_desc){k->unit, k->help, k->min, k->max, k->has_unset, k->unset, k->choices};
}

void rted_config_get(const rted_config *c, const rted_key *k, int64_t *int_value,
                     double *real_value, const char **text_value)
{
    const char *field = (const char *)c + k->offset;
    *int_value = 0;
    *real_value = 0;
    *text_value = "";
    switch (k->type) {
    case K_INT: *int_value = *(const int32_t *)field; break;
    case K_REAL: *real_value = *(const double *)field; break;
    case K_BOOL: *int_value = *(const bool *)field; break;
    case K_TEXT: *text_value = field; break;
    case K_ENUM: *text_value = k->choices[*(const int32_t *)field]; break;
    }
}

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

uint64_t rted_config_hash(const rted_config *c)
{
    uint64_t h = 14695981039346656037ull;
    for (size_t i = 0; i < N_KEYS; i++) {
        const char *field = (const char *)c + keys[i].offset;
        size_t n = keys[i].type == K_TEXT   ? strlen(field)
                   : keys[i].type == K_REAL ? sizeof(double)
                   : keys[i].type == K_BOOL ? sizeof(bool)
                                            : sizeof(int32_t);
        h = fnv(h, keys[i].key, strlen(keys[i].key));
        h = fnv(h, field, n);
    }
    return h;
}

bool rted_config_fixed_change(const rted_config *now, const rted_config *next, char *name,
                              size_t name_size)
{
    for (size_t i = 0; i < N_KEYS; i++) {
        const key_def *k = &keys[i];
        if (k->runtime)
            continue;
        const char *a = (const char *)now + k->offset, *b = (const char *)next + k->offset;
        bool same = k->type == K_TEXT   ? !strcmp(a, b)
                    : k->type == K_REAL ? *(const double *)a == *(const double *)b
                    : k->type == K_BOOL ? *(const bool *)a == *(const bool *)b
                                        : *(const int32_t *)a == *(const int32_t *)b;
        if (!same) {
            snprintf(name, name_size, "%s.%s", k->section, k->key);
            return true;
        }
    }
    return false;
}
