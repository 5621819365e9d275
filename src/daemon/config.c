/* The configuration table and the INI reader (see config.h). One row per
 * key: everything about a key lives in its row, so the reader, the
 * validator, `--help-config`, the effective-config printer, the hash and
 * the SIGHUP rule (runtime keys apply, fixed keys are refused) cannot
 * disagree. */
#include "config.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef enum key_type { K_INT, K_REAL, K_BOOL, K_TEXT, K_ENUM } key_type;

typedef struct key_def {
    const char *section, *key;
    key_type type;
    size_t offset, size;      /* size: K_TEXT capacity */
    double min, max;          /* K_INT, K_REAL */
    const char *const *choices; /* K_ENUM, NULL-terminated */
    bool runtime;             /* may change while running (SIGHUP, params_t) */
    const char *def;
    const char *help;
} key_def;

static const char *const source_kinds[] = {"auto", "y4m", "images", "raw", "lcm-log", "lcm",
                                           "v4l2", "libcamera", NULL};
static const char *const paces[] = {"recorded", "fps", "fast", NULL};
static const char *const canny_modes[] = {"fixed", "median", "otsu", NULL};
static const char *const binarizers[] = {"otsu", "fixed", "canny-close", NULL};
static const char *const polarities[] = {"auto", "dark", "bright", NULL};

#define OFF(f) offsetof(rted_config, f)
#define INT(s, k, f, lo, hi, rt, d, h) {s, k, K_INT, OFF(f), 0, lo, hi, NULL, rt, d, h}
#define REAL(s, k, f, lo, hi, rt, d, h) {s, k, K_REAL, OFF(f), 0, lo, hi, NULL, rt, d, h}
#define BOOL(s, k, f, rt, d, h) {s, k, K_BOOL, OFF(f), 0, 0, 1, NULL, rt, d, h}
#define TEXT(s, k, f, rt, d, h) {s, k, K_TEXT, OFF(f), sizeof(((rted_config *)0)->f), 0, 0, NULL, rt, d, h}
#define ENUM(s, k, f, ch, rt, d, h) {s, k, K_ENUM, OFF(f), 0, 0, 0, ch, rt, d, h}

static const key_def keys[] = {
    ENUM("source", "kind", source_kind, source_kinds, false, "auto",
         "what `path` is; auto: *.y4m, a directory or glob of images, *.lcm/*.log\n"
         "(an LCM log of image_t), udpm:// or memq:// (live image_t), /dev/video*;\n"
         "libcamera: path is the camera id, or its index in `cam -l`"),
    TEXT("source", "path", source_path, false, "fixtures/solidWhiteRight_clip.y4m",
         "the recording, image directory or glob, LCM URL, V4L2 device or camera"),
    TEXT("source", "channel", source_channel, false, "",
         "LCM sources: the image_t channel (a log: empty = every channel)"),
    TEXT("source", "format", source_format, false, "",
         "images, raw, v4l2, libcamera: pixel format (grey, bgr24, rgb24, yuyv,\n"
         "uyvy, nv12; v4l2 also mjpeg, decoded to grey); empty: bgr24 (images),\n"
         "yuyv (v4l2), the camera's choice (libcamera)"),
    INT("source", "width", width, 0, 8192, false, "0",
        "largest frame width (raw, v4l2: the frame width); 0: from the source"),
    INT("source", "height", height, 0, 8192, false, "0", "largest frame height, as width"),
    ENUM("source", "pace", pace, paces, false, "recorded",
         "recorded: the recording's timestamps scaled by speed; fps: a fixed rate;\n"
         "fast: as fast as possible (never drops)"),
    REAL("source", "fps", fps, 0.1, 1000, false, "30", "the rate of pace = fps"),
    REAL("source", "speed", speed, 0.001, 1000, false, "1", "pace = recorded: 2 = twice real time"),
    BOOL("source", "loop", loop, false, "false", "start a recording again at its end"),
    INT("source", "max_frames", max_frames, 0, 2147483647, false, "0",
        "stop after this many processed frames; 0: never"),
    TEXT("source", "controls", source_controls, false, "",
         "v4l2: controls set at open and at each reopening, 'name=value' pairs,\n"
         "';'-separated, names as `v4l2-ctl -l` prints them (e.g. brightness=140;\n"
         "auto_exposure=1;exposure_time_absolute=100)"),
    TEXT("source", "record", record_path, false, "",
         "write every frame the source delivers to this LCM log of image_t (the\n"
         "frames as delivered, on publish.image_channel); replay it with\n"
         "path = the log; empty: no recording"),

    BOOL("lane", "enabled", lane_enabled, false, "true", "run the lane path"),
    INT("lane", "max_segments", lane_max_segments, 1, 65536, false, "512",
        "Hough segments kept and published per frame"),
    INT("lane", "blur_ksize", lane_blur_ksize, 1, 15, false, "5", "Gaussian kernel size (odd)"),
    ENUM("lane", "canny_mode", lane_canny_mode, canny_modes, true, "median",
         "Canny thresholds: fixed (canny_low/high) or from the ROI's histogram"),
    INT("lane", "canny_low", lane_canny_low, -1, 2040, true, "-1",
        "fixed mode, L1 gradient; -1: the lane default"),
    INT("lane", "canny_high", lane_canny_high, -1, 2040, true, "-1", "as canny_low"),
    INT("lane", "hough_threshold", lane_hough_threshold, -1, 100000, true, "-1",
        "Hough votes; -1: the lane default for the frame height"),
    INT("lane", "min_length", lane_min_length, -1, 8192, true, "-1",
        "shortest segment, pixels; -1: default for the frame height"),
    INT("lane", "max_gap", lane_max_gap, -1, 8192, true, "-1",
        "largest gap joined in a segment; -1: default for the frame height"),
    INT("lane", "hough_seed", lane_hough_seed, 0, INT32_MAX, true, "0",
        "point order of the Hough search; 0: the built-in seed"),
    INT("lane", "hold_frames", lane_hold_frames, -1, 1000, true, "-1",
        "frames a lost lane is predicted; -1: the lane default"),
    INT("lane", "gate_px", lane_gate_px, -1, 8192, true, "-1",
        "segments farther from a tracked lane are ignored; -1: default"),
    BOOL("lane", "use_color", lane_use_color, true, "true",
         "colour frames: white/yellow paint cue"),
    TEXT("lane", "roi", lane_roi, true, "0,1;0.45,0.6;0.55,0.6;1,1",
         "ROI polygon, 3..8 'x,y' fractions of width and height, ';'-separated"),

    BOOL("grasp", "enabled", grasp_enabled, false, "true",
         "run the grasp path (optional stage: skipped first when the deadline is short)"),
    INT("grasp", "max_objects", grasp_max_objects, 1, 1024, false, "32",
        "objects kept and published per frame"),
    INT("grasp", "max_contours", grasp_max_contours, 1, 1000000, false, "4096",
        "contours stored per frame"),
    INT("grasp", "max_points", grasp_max_points, 16, 50000000, false, "262144",
        "contour points stored per frame"),
    INT("grasp", "blur_ksize", grasp_blur_ksize, 1, 15, false, "5", "Gaussian size (odd)"),
    ENUM("grasp", "binarize", grasp_binarize, binarizers, true, "otsu",
         "object mask: Otsu, a fixed threshold, or closed Canny edges"),
    INT("grasp", "threshold", grasp_threshold, 0, 255, true, "128", "binarize = fixed"),
    ENUM("grasp", "polarity", grasp_polarity, polarities, true, "auto",
         "objects darker or brighter than the table; auto: not the border's side"),
    INT("grasp", "min_area", grasp_min_area, 0, 100000000, true, "100", "smallest object, px"),
    INT("grasp", "max_area", grasp_max_area, 0, 100000000, true, "0",
        "largest object, px; 0: no limit"),
    BOOL("grasp", "skip_border", grasp_skip_border, true, "false",
         "drop objects touching the image border"),

    TEXT("publish", "url", lcm_url, false, "udpm://239.255.76.67:7667?ttl=0",
         "LCM URL: udpm://..., memq:// (tests), file://PATH[?mode=w|a] (a log)"),
    TEXT("publish", "lane_channel", lane_channel, false, "RTEDGE_LANES", "lane_detection_t"),
    TEXT("publish", "grasp_channel", grasp_channel, false, "RTEDGE_GRASP", "grasp_detection_t"),
    TEXT("publish", "status_channel", status_channel, false, "RTEDGE_STATUS",
         "status_t, once per status_period_ms"),
    TEXT("publish", "params_channel", params_channel, false, "RTEDGE_PARAMS",
         "params_t in: runtime parameters (udpm://, memq://)"),
    BOOL("publish", "params_enabled", params_enabled, false, "false",
         "listen on params_channel (an unauthenticated control input: off by default)"),
    BOOL("publish", "images", publish_images, false, "false",
         "also publish each analysed grey frame as image_t (for tools/render_log)"),
    TEXT("publish", "image_channel", image_channel, false, "RTEDGE_IMAGE", "image_t"),
    INT("publish", "status_period_ms", status_period_ms, 10, 60000, false, "1000",
        "status_t period and latency window"),

    REAL("deadline", "ms", deadline_ms, 0, 60000, true, "0",
         "per-frame budget, capture to publish; 0: 1000 / source.fps"),
    REAL("deadline", "grasp_min_budget_ms", grasp_min_budget_ms, 0, 60000, true, "2",
         "skip the grasp path when less than this is left of the budget"),
    REAL("deadline", "max_late_ms", max_late_ms, -1, 60000, false, "100",
         "drop frames later than this behind their pace; -1: never"),

    INT("realtime", "priority", rt_priority, 0, 99, false, "0",
        "SCHED_FIFO priority; 0: normal scheduling (a warning if not permitted)"),
    INT("realtime", "cpu", rt_cpu, -1, 1023, false, "-1", "pin to this CPU; -1: no affinity"),
    BOOL("realtime", "mlockall", rt_mlockall, false, "false",
         "lock all memory (a warning if not permitted)"),
};
#define N_KEYS (sizeof keys / sizeof keys[0])

static void say(char *msg, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
}

static const key_def *find_key(const char *section, const char *key, bool *section_known)
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

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n'))
        *--e = 0;
    return s;
}

/* Stores `value` into the key's field; false and a reason otherwise. */
static bool set_value(rted_config *c, const key_def *k, const char *value, char *why,
                      size_t why_size)
{
    char *field = (char *)c + k->offset;
    char *end;
    switch (k->type) {
    case K_INT:
    case K_REAL: {
        /* Both parsed to double: every int32 is exact in it, and the table's
         * ranges are doubles. */
        const bool integer = k->type == K_INT;
        errno = 0;
        double v = integer ? (double)strtoll(value, &end, 10) : strtod(value, &end);
        if (end == value || *end || errno || !isfinite(v)) {
            say(why, why_size, "'%s' is not %s", value, integer ? "an integer" : "a number");
            return false;
        }
        if (v < k->min || v > k->max) {
            say(why, why_size, integer ? "%.0f is out of range %.0f..%.0f" : "%g is out of range %g..%g", v,
                k->min, k->max);
            return false;
        }
        if (integer)
            *(int32_t *)field = (int32_t)v;
        else
            *(double *)field = v;
        return true;
    }
    case K_BOOL:
        if (!strcasecmp(value, "true") || !strcasecmp(value, "yes") || !strcmp(value, "1") ||
            !strcasecmp(value, "on"))
            *(bool *)field = true;
        else if (!strcasecmp(value, "false") || !strcasecmp(value, "no") ||
                 !strcmp(value, "0") || !strcasecmp(value, "off"))
            *(bool *)field = false;
        else {
            say(why, why_size, "'%s' is not a boolean (true/false)", value);
            return false;
        }
        return true;
    case K_TEXT:
        if (strlen(value) >= k->size) {
            say(why, why_size, "longer than %zu characters", k->size - 1);
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

void rted_config_defaults(rted_config *c)
{
    memset(c, 0, sizeof *c);
    char why[RTED_MSG];
    for (size_t i = 0; i < N_KEYS; i++)
        if (!set_value(c, &keys[i], keys[i].def, why, sizeof why))
            abort(); /* a bad default in the table is a programming error */
}

bool rted_config_load(rted_config *c, const char *path, char *msg, size_t msg_size)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        say(msg, msg_size, "%s: %s", path, strerror(errno));
        return false;
    }
    bool seen[N_KEYS] = {false};
    char line[1024], section[64] = "";
    int lineno = 0;
    bool ok = true;
    while (ok && fgets(line, sizeof line, f)) {
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) {
            say(msg, msg_size, "%s:%d: line longer than %zu characters", path, lineno,
                sizeof line - 2);
            ok = false;
            break;
        }
        char *s = trim(line);
        if (!*s || *s == '#' || *s == ';')
            continue;
        if (*s == '[') {
            char *e = strchr(s, ']');
            if (!e || e[1] || (size_t)(e - s - 1) >= sizeof section) {
                say(msg, msg_size, "%s:%d: bad section header '%s'", path, lineno, s);
                ok = false;
                break;
            }
            *e = 0;
            snprintf(section, sizeof section, "%s", trim(s + 1));
            bool known = false;
            for (size_t i = 0; i < N_KEYS; i++)
                known |= !strcmp(keys[i].section, section);
            if (!known) {
                say(msg, msg_size, "%s:%d: unknown section [%s]", path, lineno, section);
                ok = false;
            }
            continue;
        }
        char *eq = strchr(s, '=');
        if (!eq) {
            say(msg, msg_size, "%s:%d: expected 'key = value', not '%s'", path, lineno, s);
            ok = false;
            break;
        }
        *eq = 0;
        char *key = trim(s), *value = trim(eq + 1);
        if (!*section) {
            say(msg, msg_size, "%s:%d: key '%s' outside a [section]", path, lineno, key);
            ok = false;
            break;
        }
        bool known;
        const key_def *k = find_key(section, key, &known);
        if (!k) {
            say(msg, msg_size, "%s:%d: unknown key '%s' in [%s]", path, lineno, key, section);
            ok = false;
            break;
        }
        if (seen[k - keys]) {
            say(msg, msg_size, "%s:%d: duplicate key %s.%s", path, lineno, section, key);
            ok = false;
            break;
        }
        seen[k - keys] = true;
        char why[RTED_MSG];
        if (!set_value(c, k, value, why, sizeof why)) {
            say(msg, msg_size, "%s:%d: %s.%s: %s", path, lineno, section, key, why);
            ok = false;
        }
    }
    fclose(f);
    return ok;
}

bool rted_config_set(rted_config *c, const char *assignment, const char *origin, char *msg,
                     size_t msg_size)
{
    char buf[RTED_TEXT + 128];
    snprintf(buf, sizeof buf, "%s", assignment);
    char *eq = strchr(buf, '=');
    char *dot = strchr(buf, '.');
    if (!eq || !dot || dot > eq) {
        say(msg, msg_size, "%s: expected section.key=value, not '%s'", origin, assignment);
        return false;
    }
    *eq = *dot = 0;
    bool known;
    const key_def *k = find_key(trim(buf), trim(dot + 1), &known);
    if (!k) {
        say(msg, msg_size, known ? "%s: unknown key '%s.%s'" : "%s: unknown section '%s'%.0s",
            origin, trim(buf), trim(dot + 1));
        return false;
    }
    char why[RTED_MSG];
    if (!set_value(c, k, trim(eq + 1), why, sizeof why)) {
        say(msg, msg_size, "%s: %s.%s: %s", origin, k->section, k->key, why);
        return false;
    }
    return true;
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

int32_t rted_parse_roi(const char *text, int32_t *xy_q16, int32_t max_vertices)
{
    int32_t n = 0;
    const char *s = text;
    while (*s) {
        char *end;
        double fx = strtod(s, &end);
        if (end == s || *end != ',' || n >= max_vertices)
            return -1;
        s = end + 1;
        double fy = strtod(s, &end);
        if (end == s || (*end && *end != ';') || !(fx >= -64 && fx <= 64 && fy >= -64 && fy <= 64))
            return -1;
        xy_q16[2 * n] = (int32_t)lround(fx * 65536);
        xy_q16[2 * n + 1] = (int32_t)lround(fy * 65536);
        n++;
        s = *end ? end + 1 : end;
    }
    return n >= 3 ? n : -1;
}

bool rted_config_validate(const rted_config *c, char *msg, size_t msg_size)
{
    int32_t xy[16];
    if (rted_parse_roi(c->lane_roi, xy, 8) < 0) {
        say(msg, msg_size, "lane.roi: '%s' is not 3..8 'x,y' fractions separated by ';'",
            c->lane_roi);
        return false;
    }
    if (c->lane_canny_low >= 0 && c->lane_canny_high >= 0 && c->lane_canny_low > c->lane_canny_high) {
        say(msg, msg_size, "lane.canny_low (%d) exceeds lane.canny_high (%d)", c->lane_canny_low,
            c->lane_canny_high);
        return false;
    }
    if ((c->lane_canny_low < 0) != (c->lane_canny_high < 0)) {
        say(msg, msg_size, "lane.canny_low and lane.canny_high: set both or neither");
        return false;
    }
    if (c->lane_blur_ksize % 2 == 0 || c->grasp_blur_ksize % 2 == 0) {
        say(msg, msg_size, "lane.blur_ksize and grasp.blur_ksize must be odd");
        return false;
    }
    if (c->grasp_max_area && c->grasp_max_area < c->grasp_min_area) {
        say(msg, msg_size, "grasp.max_area is below grasp.min_area");
        return false;
    }
    if (!c->source_path[0]) {
        say(msg, msg_size, "source.path is empty");
        return false;
    }
    if (rted_parse_controls(c->source_controls, NULL, 0) < 0) {
        say(msg, msg_size, "source.controls: '%s' is not 'name=value;...' with at most %d "
            "integer values and names of at most %d characters", c->source_controls,
            RTE_V4L2_MAX_CONTROLS, RTE_V4L2_NAME_SIZE - 1);
        return false;
    }
    if (!c->lcm_url[0]) {
        say(msg, msg_size, "publish.url is empty");
        return false;
    }
    return true;
}

static void print_value(const rted_config *c, const key_def *k, FILE *f)
{
    const char *field = (const char *)c + k->offset;
    switch (k->type) {
    case K_INT: fprintf(f, "%d", *(const int32_t *)field); break;
    case K_REAL: fprintf(f, "%g", *(const double *)field); break;
    case K_BOOL: fputs(*(const bool *)field ? "true" : "false", f); break;
    case K_TEXT: fputs(field, f); break;
    case K_ENUM: fputs(k->choices[*(const int32_t *)field], f); break;
    }
}

void rted_config_print(const rted_config *c, FILE *f)
{
    const char *section = "";
    for (size_t i = 0; i < N_KEYS; i++) {
        if (strcmp(section, keys[i].section)) {
            section = keys[i].section;
            fprintf(f, "%s[%s]\n", i ? "\n" : "", section);
        }
        fprintf(f, "%s = ", keys[i].key);
        print_value(c, &keys[i], f);
        fputc('\n', f);
    }
}

void rted_config_print_help(FILE *f)
{
    fputs("# rtedged.conf: the rtedge daemon's configuration (INI). Every key with its\n"
          "# default; a line `key = value` under its [section], '#' starts a comment.\n"
          "# Override any key with `rtedged --set section.key=value`. Keys marked\n"
          "# (runtime) may change while running: SIGHUP re-reads this file and\n"
          "# params_t messages set them; the others fix sizes at start and a change\n"
          "# is refused until a restart. Generated by `rtedged --help-config`.\n",
          f);
    const char *section = "";
    for (size_t i = 0; i < N_KEYS; i++) {
        const key_def *k = &keys[i];
        if (strcmp(section, k->section)) {
            section = k->section;
            fprintf(f, "\n[%s]\n", section);
        }
        fputs("\n# ", f);
        for (const char *h = k->help; *h; h++) {
            fputc(*h, f);
            if (*h == '\n')
                fputs("# ", f);
        }
        fputs("\n# ", f);
        switch (k->type) {
        case K_INT: fprintf(f, "integer %.0f..%.0f", k->min, k->max); break;
        case K_REAL: fprintf(f, "number %g..%g", k->min, k->max); break;
        case K_BOOL: fputs("true or false", f); break;
        case K_TEXT: fprintf(f, "text, at most %zu characters", k->size - 1); break;
        case K_ENUM:
            fputs("one of", f);
            for (int32_t j = 0; k->choices[j]; j++)
                fprintf(f, " %s", k->choices[j]);
            break;
        }
        fprintf(f, "; default %s%s\n%s = %s\n", k->def[0] ? k->def : "(empty)",
                k->runtime ? " (runtime)" : "", k->key, k->def);
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
        size_t n = keys[i].type == K_TEXT ? strlen(field)
                   : keys[i].type == K_REAL ? sizeof(double)
                   : keys[i].type == K_BOOL ? sizeof(bool) : sizeof(int32_t);
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
        bool same = k->type == K_TEXT ? !strcmp(a, b)
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
