/* rtedged's configuration: an INI file plus command-line overrides, read
 * through one table of keys (config_keys.c) that gives each key its type, range,
 * default, help text and whether it may change while running (SIGHUP,
 * params_t) or fixes a size at start. The same table prints
 * `rtedged --help-config` (which is also the documented rtedged.conf). */
#ifndef RTEDGED_CONFIG_H
#define RTEDGED_CONFIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "rtedge/v4l2_source.h"

#define RTED_TEXT 256
#define RTED_MSG 512

typedef enum rted_source_kind {
    RTED_SOURCE_AUTO = 0,
    RTED_SOURCE_Y4M,
    RTED_SOURCE_IMAGES,
    RTED_SOURCE_RAW,
    RTED_SOURCE_LCM_LOG,
    RTED_SOURCE_LCM,
    RTED_SOURCE_V4L2,
    RTED_SOURCE_LIBCAMERA,
} rted_source_kind;

typedef enum rted_pace { RTED_PACE_RECORDED = 0, RTED_PACE_FPS, RTED_PACE_FAST } rted_pace;

typedef struct rted_config {
    /* [source] */
    int32_t source_kind;
    char source_path[RTED_TEXT];
    char source_channel[RTED_TEXT];
    char source_format[16];
    int32_t width, height; /* maxima (raw: the frame size); 0 = from the source */
    int32_t pace;
    double fps;
    double speed;
    bool loop;
    int32_t max_frames;              /* stop after this many processed frames; 0 = never */
    int32_t max_pause_ms;            /* pace = recorded: longer pauses are not waited out */
    char source_controls[RTED_TEXT]; /* v4l2: "name=value;..." */
    bool wait_camera;                /* a camera missing at start is waited for */
    char record_path[RTED_TEXT];     /* LCM log of the delivered frames; "" = none */
    /* [lane] */
    bool lane_enabled;
    int32_t lane_max_segments, lane_blur_ksize;
    int32_t lane_canny_mode, lane_canny_low, lane_canny_high;
    int32_t lane_hough_threshold, lane_min_length, lane_max_gap, lane_hough_seed;
    int32_t lane_hold_frames, lane_gate_px;
    bool lane_use_color;
    bool lane_curves;
    char lane_roi[RTED_TEXT];
    /* [grasp] */
    bool grasp_enabled;
    int32_t grasp_max_objects, grasp_max_contours, grasp_max_points, grasp_blur_ksize;
    int32_t grasp_binarize, grasp_threshold, grasp_polarity, grasp_contrast, grasp_background_cell;
    int32_t grasp_min_area, grasp_max_area;
    bool grasp_skip_border, grasp_split, grasp_chroma;
    double grasp_edge_support;
    char grasp_roi[RTED_TEXT]; /* "": the whole frame */
    int32_t grasp_gripper_min_px, grasp_gripper_max_px, grasp_margin_px, grasp_finger_px;
    /* [publish] */
    char lcm_url[RTED_TEXT];
    char lane_channel[64], grasp_channel[64], status_channel[64];
    char image_channel[64];
    bool publish_images;
    int32_t status_period_ms;
    /* [params] */
    bool params_enabled;
    char params_channel[64];
    char params_keys[RTED_TEXT]; /* "section.key,..."; "" = every runtime key */
    int32_t params_max_per_second;
    char params_state_channel[64];
    int32_t params_state_period_ms;
    char params_save_path[RTED_TEXT]; /* ACTION_SAVE's file; "" = refused */
    /* [debug] */
    bool debug_enabled;
    char debug_channel[64];
    double debug_rate_hz, debug_scale;
    char debug_layers[RTED_TEXT];
    int32_t debug_quality;
    /* [deadline] */
    double deadline_ms;         /* 0 = 1000 / fps (or 1000 / 30) */
    double grasp_min_budget_ms; /* skip grasp when less than this is left */
    double max_late_ms;         /* pacer: drop frames later than this; < 0 never */
    /* [realtime] */
    int32_t rt_priority; /* 0 = no SCHED_FIFO */
    int32_t rt_cpu;      /* -1 = no affinity */
    bool rt_mlockall;
    int32_t rt_cpu_dma_latency_us; /* -1 = no PM QoS request */
    int32_t rt_threads;            /* 2 = the grasp path on a thread of its own */
} rted_config;

/* One key of the table (config_keys.c), for typed access (params_t). */
typedef struct rted_key rted_key;
typedef enum rted_key_type {
    RTED_KEY_INT = 0,
    RTED_KEY_REAL,
    RTED_KEY_BOOL,
    RTED_KEY_TEXT,
    RTED_KEY_CHOICE,
} rted_key_type;

/* The key named "section.key" (NULL when there is none). */
const rted_key *rted_config_find_key(const char *name);
/* The table's keys in order: index 0, 1, ... until NULL. */
const rted_key *rted_config_key_at(size_t index);
/* "section.key" into name (at most name_size bytes, NUL-terminated). */
void rted_key_get_name(const rted_key *k, char *name, size_t name_size);
rted_key_type rted_key_get_type(const rted_key *k);
/* true for keys that may change while running (SIGHUP, params_t). */
bool rted_key_is_runtime(const rted_key *k);
/* Typed setters: the value is checked against the key's type and range as
 * the file's text would be; false and *why otherwise (c unchanged). */
bool rted_config_set_int(rted_config *c, const rted_key *k, int64_t value, char *why,
                         size_t why_size);
bool rted_config_set_real(rted_config *c, const rted_key *k, double value, char *why,
                          size_t why_size);
bool rted_config_set_bool(rted_config *c, const rted_key *k, bool value, char *why,
                          size_t why_size);
/* Text and choice keys (a choice by its name). */
bool rted_config_set_text(rted_config *c, const rted_key *k, const char *value, char *why,
                          size_t why_size);
/* What param_state_t tells of a key besides its name and type. */
typedef struct rted_key_desc {
    const char *unit, *help;
    double min, max; /* RTED_KEY_INT, RTED_KEY_REAL */
    bool has_unset;  /* `unset` is valid too: "the default" */
    double unset;
    const char *const *choices; /* RTED_KEY_CHOICE: NULL-terminated */
} rted_key_desc;
void rted_key_describe(const rted_key *k, rted_key_desc *d);
/* The key's value in c: integers and booleans (0, 1) in *int_value, reals
 * in *real_value, text and a choice's name in *text_value (pointing into
 * c or the table); the others 0 or "". */
void rted_config_get(const rted_config *c, const rted_key *k, int64_t *int_value,
                     double *real_value, const char **text_value);
/* true when params.keys lets params_t change `name` ("section.key"). */
bool rted_config_params_allowed(const rted_config *c, const char *name);

/* Fills the table's defaults. */
void rted_config_defaults(rted_config *c);
/* Reads an INI file over *c. false and *msg ("file:line: why") on the
 * first error (unknown section or key, bad value, duplicate key). */
bool rted_config_load(rted_config *c, const char *path, char *msg, size_t msg_size);
/* One "section.key=value" override (origin names it in messages). */
bool rted_config_set(rted_config *c, const char *assignment, const char *origin, char *msg,
                     size_t msg_size);
/* Cross-key checks (canny low <= high, ROI syntax, ...). */
bool rted_config_validate(const rted_config *c, char *msg, size_t msg_size);
/* Checks against the source's largest frame (width x height): a lane ROI
 * that leaves less than RTED_ROI_MIN_SIDE x RTED_ROI_MIN_SIDE pixels of the
 * frame or encloses less than 1/1000 of it, Hough lengths and thresholds
 * beyond width + height, a grasp.min_area beyond the frame's area: values
 * with which a path could never find anything (or fails every frame). A
 * path that is not enabled is not checked. */
bool rted_config_check_frame(const rted_config *c, int32_t width, int32_t height, char *msg,
                             size_t msg_size);
#define RTED_ROI_MIN_SIDE 16
/* The effective configuration as INI, values only (--check-config). */
void rted_config_print(const rted_config *c, FILE *f);
/* The largest text rted_config_write makes (checked where it is used). */
#define RTED_CONFIG_TEXT_MAX 65536
/* c as an rtedged.conf that rted_config_load reads back to c: "# title",
 * then every key with its help, range and default, as --help-config has
 * them, set to its value in c. Returns the length written into buf
 * (NUL-terminated), 0 when it does not fit in size bytes. */
size_t rted_config_write(const rted_config *c, const char *title, char *buf, size_t size);
/* rted_config_write (in buf, size bytes, titled with the hash) into the
 * file `path` ("-": stdout; NULL: the text in buf only), replacing it
 * whole (a temporary file beside it, renamed over it). false and *why
 * otherwise. */
bool rted_config_save(const rted_config *c, const char *path, char *buf, size_t size, char *why,
                      size_t why_size);
/* The documented default file: every key with help, range and default. */
void rted_config_print_help(FILE *f);
/* The key table as JSON (`--help-config=json`): {"keys": [{"section", "key",
 * "type" (int, real, bool, text, choice), "runtime", "default", "unit",
 * "min", "max" (numbers), "unset" (a value meaning "the default", where a
 * key has one), "max_length" (text), "choices" (choice), "help"}, ...]}. */
void rted_config_print_json(FILE *f);
/* FNV-1a of the printed configuration's values. */
uint64_t rted_config_hash(const rted_config *c);
/* true and the name of the first fixed (start-up only) key whose value differs. */
bool rted_config_fixed_change(const rted_config *now, const rted_config *next, char *name,
                              size_t name_size);
/* Parses source.controls ("name=value;..."; "" is none) into out (NULL:
 * only checks). Returns the number of controls, -1 when malformed or more
 * than max (max is RTE_V4L2_MAX_CONTROLS when out is NULL). */
int32_t rted_parse_controls(const char *text, rte_v4l2_control *out, int32_t max);
/* Parses debug.layers (rte_overlay_layer bits); -1 and the first unknown
 * name in bad otherwise. */
int32_t rted_parse_debug_layers(const char *text, char *bad, size_t bad_size);

#endif
