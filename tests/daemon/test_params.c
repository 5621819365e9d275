/* The params_t channel as an attacker sees it: the hand-written decoder
 * (params.c) on malformed and forged messages, the step to a configuration
 * (kinds, ranges, runtime and listed keys), the daemon's handler on the
 * cases of issue 18 (each refused whole, with its reason, the configuration
 * in force unchanged), a stream of hostile messages handled with no heap
 * call, the rate limit through memq://, and the frame-size checks.
 *   test_params BUILD_DIR */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>
#include <lcm/lcm.h>

#include "config.h"
#include "daemon.h"
#include "daemon_fixtures.h"
#include "heapcount.h"
#include "params.h"
#include "rtedge_param_state_t.h"
#include "rtedge_params_t.h"

static const char *build_dir;

/* ---- writing params_t by hand, malformed or not ---- */

typedef struct writer {
    uint8_t buf[70000];
    size_t n;
} writer;

static void put_u32(writer *w, uint32_t v)
{
    for (int i = 3; i >= 0; i--)
        w->buf[w->n++] = (uint8_t)(v >> (8 * i));
}

static void put_u64(writer *w, uint64_t v)
{
    put_u32(w, (uint32_t)(v >> 32));
    put_u32(w, (uint32_t)v);
}

static void put_bytes(writer *w, const void *p, size_t n)
{
    memcpy(w->buf + w->n, p, n);
    w->n += n;
}

static void put_head_action(writer *w, int64_t request_id, int8_t action, uint32_t nparams)
{
    w->n = 0;
    put_u64(w, (uint64_t)__rtedge_params_t_get_hash());
    put_u64(w, 123456);
    put_u64(w, (uint64_t)request_id);
    w->buf[w->n++] = (uint8_t)action;
    put_u32(w, nparams);
}

static void put_head(writer *w, int64_t request_id, uint32_t nparams)
{
    put_head_action(w, request_id, RTEDGE_PARAMS_T_ACTION_SET, nparams);
}

/* A value with a proper name and text: length with the NUL, bytes, NUL. */
static void put_text_value(writer *w, const char *name, int8_t kind, int64_t i, double r,
                           const char *text)
{
    put_u32(w, (uint32_t)strlen(name) + 1);
    put_bytes(w, name, strlen(name) + 1);
    w->buf[w->n++] = (uint8_t)kind;
    put_u64(w, (uint64_t)i);
    uint64_t bits;
    memcpy(&bits, &r, sizeof bits);
    put_u64(w, bits);
    put_u32(w, (uint32_t)strlen(text) + 1);
    put_bytes(w, text, strlen(text) + 1);
}

static void put_value(writer *w, const char *name, int8_t kind, int64_t i, double r)
{
    put_text_value(w, name, kind, i, r, "");
}

static bool decode(const writer *w, rted_params_request *r, char *why, size_t why_size)
{
    return rted_params_decode(w->buf, w->n, r, why, why_size);
}

static void expect_decode_refused(const writer *w, const char *reason)
{
    static rted_params_request r;
    char why[RTED_MSG] = "";
    assert_false(decode(w, &r, why, sizeof why));
    if (!strstr(why, reason))
        print_error("decode refused with '%s', expected '%s'\n", why, reason);
    assert_non_null(strstr(why, reason));
}

/* ---- the decoder ---- */

static void test_decode_valid(void **state)
{
    writer w;
    put_head(&w, 42, 3);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 920, 0);
    put_value(&w, "deadline.ms", RTEDGE_PARAM_T_KIND_REAL, 0, 25.5);
    put_text_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "0,1;0.5,0.5;1,1");
    static rted_params_request r;
    char why[RTED_MSG];
    assert_true(decode(&w, &r, why, sizeof why));
    assert_int_equal(r.request_id, 42);
    assert_int_equal(r.action, RTEDGE_PARAMS_T_ACTION_SET);
    assert_int_equal(r.count, 3);
    assert_string_equal(r.params[0].name, "grasp.min_area");
    assert_int_equal(r.params[0].kind, RTEDGE_PARAM_T_KIND_INT);
    assert_int_equal(r.params[0].int_value, 920);
    assert_string_equal(r.params[1].name, "deadline.ms");
    assert_true(r.params[1].real_value == 25.5);
    assert_int_equal(r.params[2].kind, RTEDGE_PARAM_T_KIND_TEXT);
    assert_string_equal(r.params[2].text_value, "0,1;0.5,0.5;1,1");
    /* The same bytes as lcm-gen's encoder writes. */
    rtedge_param_t p[3] = {
        {.name = "grasp.min_area",
         .kind = RTEDGE_PARAM_T_KIND_INT,
         .int_value = 920,
         .text_value = ""},
        {.name = "deadline.ms",
         .kind = RTEDGE_PARAM_T_KIND_REAL,
         .real_value = 25.5,
         .text_value = ""},
        {.name = "lane.roi", .kind = RTEDGE_PARAM_T_KIND_TEXT, .text_value = "0,1;0.5,0.5;1,1"}};
    rtedge_params_t m = {.utime = 123456, .request_id = 42, .nparams = 3, .params = p};
    uint8_t gen[512];
    int len = rtedge_params_t_encode(gen, 0, sizeof gen, &m);
    assert_int_equal(len, (int)w.n);
    assert_memory_equal(gen, w.buf, w.n);
    /* A save request carries no values. */
    put_head_action(&w, 43, RTEDGE_PARAMS_T_ACTION_SAVE, 0);
    assert_true(decode(&w, &r, why, sizeof why));
    assert_int_equal(r.action, RTEDGE_PARAMS_T_ACTION_SAVE);
    assert_int_equal(r.count, 0);
}

static void test_decode_counts(void **state)
{
    writer w;
    /* Issue 18's crash: 53 bytes with nparams = 0x7fffffff (the generated
     * decoder malloc'd 32 x nparams and wrote through NULL). */
    put_head(&w, 1, 0x7fffffff);
    memset(w.buf + w.n, 0x41, 53 - w.n);
    w.n = 53;
    expect_decode_refused(&w, "nparams = 2147483647 (1..32 allowed)");
    put_head(&w, 1, 0xffffffffu);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    expect_decode_refused(&w, "nparams = -1");
    put_head(&w, 1, 0);
    expect_decode_refused(&w, "nparams = 0");
    /* Actions: a save carries no values; no other action exists. */
    put_head_action(&w, 1, RTEDGE_PARAMS_T_ACTION_SAVE, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    expect_decode_refused(&w, "ACTION_SAVE with nparams = 1 (0 allowed)");
    put_head_action(&w, 1, 5, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    expect_decode_refused(&w, "action 5 is neither ACTION_SET (0) nor ACTION_SAVE (1)");
    put_head(&w, 1, RTED_PARAMS_MAX + 1);
    for (int i = 0; i <= RTED_PARAMS_MAX; i++)
        put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    expect_decode_refused(&w, "nparams = 33 (1..32 allowed)");
    /* Two values announced, one there. */
    put_head(&w, 1, 2);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    expect_decode_refused(&w, "value 2: cut short before its name");
    /* Bytes after the last value. */
    put_head(&w, 1, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    put_u32(&w, 0);
    expect_decode_refused(&w, "4 bytes after the last value");
    /* Cut inside a value. */
    put_head(&w, 1, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    w.n -= 3;
    expect_decode_refused(&w, "value 1 (grasp.min_area): cut short");
    /* Another type's fingerprint. */
    put_head(&w, 1, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 1, 0);
    w.buf[3] ^= 1;
    expect_decode_refused(&w, "not a params_t (fingerprint");
    /* Too short to be anything; a 57 KB message (issue 18's leak). */
    w.n = 10;
    expect_decode_refused(&w, "a message of 10 bytes");
    put_head(&w, 1, 1);
    w.n = 57000;
    expect_decode_refused(&w, "a message of 57000 bytes");
}

static void test_decode_names(void **state)
{
    writer w;
    /* A name without its NUL (liblcm's decoder does not check; it was
     * printed with %s beyond the message). */
    put_head(&w, 1, 1);
    put_u32(&w, 14);
    put_bytes(&w, "grasp.min_area", 14);
    w.buf[w.n++] = RTEDGE_PARAM_T_KIND_INT;
    put_u64(&w, 5);
    put_u64(&w, 0);
    expect_decode_refused(&w, "value 1: the name does not end with a NUL byte");
    /* Issue 18's injection: '=' and spaces in the name. */
    put_head(&w, 1, 1);
    put_value(&w, "lane.canny_mode=fixed     ", RTEDGE_PARAM_T_KIND_INT, 0, 0);
    expect_decode_refused(&w, "byte 15 of the name is 0x3d");
    /* A NUL inside the name. */
    put_head(&w, 1, 1);
    put_u32(&w, 18);
    put_bytes(&w, "grasp.min_area\0xy", 18);
    w.buf[w.n++] = RTEDGE_PARAM_T_KIND_INT;
    put_u64(&w, 5);
    put_u64(&w, 0);
    expect_decode_refused(&w, "byte 14 of the name is 0x00");
    /* Lengths: huge, negative, zero, over the bound. */
    uint32_t lengths[] = {0x7fffffffu, 0xffffffffu, 0, 1, RTED_PARAM_NAME_MAX + 1};
    for (size_t i = 0; i < sizeof lengths / sizeof lengths[0]; i++) {
        put_head(&w, 1, 1);
        put_u32(&w, lengths[i]);
        memset(w.buf + w.n, 'a', 100);
        w.n += 100;
        expect_decode_refused(&w, "value 1: a name of");
    }
    /* Upper case and other bytes. */
    put_head(&w, 1, 1);
    put_value(&w, "Grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 0, 0);
    expect_decode_refused(&w, "byte 0 of the name is 0x47");
}

static void test_decode_texts(void **state)
{
    writer w;
    /* Control bytes (a newline would start a line of its own in a saved
     * rtedged.conf) and bytes beyond ASCII. */
    put_head(&w, 1, 1);
    put_text_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "0,1;1,1\n[params]");
    expect_decode_refused(&w, "value 1 (lane.roi): byte 7 of the text is 0x0a");
    put_head(&w, 1, 1);
    put_text_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "0,1;\xc3\xa9");
    expect_decode_refused(&w, "byte 4 of the text is 0xc3");
    /* Without its NUL; lengths huge, zero and over the bound. */
    put_head(&w, 1, 1);
    put_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0);
    w.n -= 5;
    put_u32(&w, 3);
    put_bytes(&w, "abc", 3);
    expect_decode_refused(&w, "value 1 (lane.roi): the text does not end with a NUL byte");
    uint32_t lengths[] = {0x7fffffffu, 0, RTED_PARAM_TEXT_MAX + 1};
    for (size_t i = 0; i < sizeof lengths / sizeof lengths[0]; i++) {
        put_head(&w, 1, 1);
        put_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0);
        w.n -= 5;
        put_u32(&w, lengths[i]);
        memset(w.buf + w.n, 'a', 300);
        w.n += 300;
        expect_decode_refused(&w, "value 1 (lane.roi): a text of");
    }
    /* Cut short before and inside it. */
    put_head(&w, 1, 1);
    put_text_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "0,1;0.5,0.5;1,1");
    w.n -= 17;
    expect_decode_refused(&w, "cut short before its text");
    put_head(&w, 1, 1);
    put_text_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "0,1;0.5,0.5;1,1");
    w.n -= 3;
    expect_decode_refused(&w, "cut short in its text");
}

/* ---- from a request to a configuration ---- */

static bool to_config(const rted_config *now, const char *name, int8_t kind, int64_t i, double r,
                      rted_config *next, char *why, size_t why_size)
{
    writer w;
    put_head(&w, 9, 1);
    put_value(&w, name, kind, i, r);
    static rted_params_request req;
    assert_true(decode(&w, &req, why, why_size));
    return rted_params_to_config(&req, now, next, why, why_size);
}

static bool text_to_config(const rted_config *now, const char *name, const char *text,
                           rted_config *next, char *why, size_t why_size)
{
    writer w;
    put_head(&w, 9, 1);
    put_text_value(&w, name, RTEDGE_PARAM_T_KIND_TEXT, 0, 0, text);
    static rted_params_request req;
    assert_true(decode(&w, &req, why, why_size));
    return rted_params_to_config(&req, now, next, why, why_size);
}

static void expect_text_refused(const rted_config *now, const char *name, const char *text,
                                const char *reason)
{
    rted_config next;
    char why[RTED_MSG] = "";
    bool ok = text_to_config(now, name, text, &next, why, sizeof why);
    if (ok || !strstr(why, reason))
        print_error("%s = '%s': %s '%s', expected '%s'\n", name, text,
                    ok ? "applied" : "refused with", why, reason);
    assert_false(ok);
    assert_non_null(strstr(why, reason));
}

static void expect_refused(const rted_config *now, const char *name, int8_t kind, int64_t i,
                           double r, const char *reason)
{
    rted_config next;
    char why[RTED_MSG] = "";
    bool ok = to_config(now, name, kind, i, r, &next, why, sizeof why);
    if (ok || !strstr(why, reason))
        print_error("%s: %s '%s', expected '%s'\n", name, ok ? "applied" : "refused with", why,
                    reason);
    assert_false(ok);
    assert_non_null(strstr(why, reason));
}

static void test_to_config(void **state)
{
    rted_config c, next;
    rted_config_defaults(&c);
    char why[RTED_MSG];
    const int8_t I = RTEDGE_PARAM_T_KIND_INT, R = RTEDGE_PARAM_T_KIND_REAL,
                 B = RTEDGE_PARAM_T_KIND_BOOL;
    assert_true(to_config(&c, "lane.canny_low", I, 40, 0, &next, why, sizeof why));
    assert_int_equal(next.lane_canny_low, 40);
    assert_true(to_config(&c, "deadline.ms", R, 0, 12.5, &next, why, sizeof why));
    assert_true(next.deadline_ms == 12.5);
    assert_true(to_config(&c, "grasp.skip_border", B, 1, 0, &next, why, sizeof why));
    assert_true(next.grasp_skip_border);
    /* The kind must be the key's. */
    expect_refused(&c, "lane.canny_low", R, 0, 40.0, "takes KIND_INT, not KIND_REAL");
    expect_refused(&c, "deadline.ms", I, 20, 0, "takes KIND_REAL, not KIND_INT");
    expect_refused(&c, "grasp.skip_border", I, 1, 0, "takes KIND_BOOL, not KIND_INT");
    expect_refused(&c, "grasp.min_area", 7, 1, 0, "kind 7 is none of");
    expect_refused(&c, "grasp.skip_border", B, 2, 0, "a KIND_BOOL value is 0 or 1, not 2");
    /* Choice and text keys take KIND_TEXT, checked as the file's text is. */
    assert_true(text_to_config(&c, "lane.canny_mode", "fixed", &next, why, sizeof why));
    assert_int_equal(next.lane_canny_mode, 0);
    assert_true(
        text_to_config(&c, "lane.roi", "0,1;0.4,0.55;0.6,0.55;1,1", &next, why, sizeof why));
    assert_string_equal(next.lane_roi, "0,1;0.4,0.55;0.6,0.55;1,1");
    assert_true(text_to_config(&c, "grasp.polarity", "dark", &next, why, sizeof why));
    expect_refused(&c, "lane.canny_mode", I, 0, 0, "takes KIND_TEXT, not KIND_INT");
    expect_refused(&c, "lane.canny_low", RTEDGE_PARAM_T_KIND_TEXT, 0, 0,
                   "takes KIND_INT, not KIND_TEXT");
    expect_text_refused(&c, "lane.canny_mode", "sobel", "'sobel' is not one of fixed median otsu");
    expect_text_refused(&c, "lane.roi", " 0,1;0.5,0.5;1,1", "starts or ends with a blank");
    expect_text_refused(&c, "lane.roi", "0,1;0.5,0.5;1,1 # x", "begins a comment");
    expect_text_refused(&c, "publish.url", "memq://", "cannot change while running");
    expect_refused(&c, "lane.max_segments", I, 10, 0, "cannot change while running");
    expect_refused(&c, "publish.url", I, 0, 0, "cannot change while running");
    expect_refused(&c, "params.max_per_second", I, 1000, 0, "cannot change while running");
    expect_refused(&c, "lane.no_such_key", I, 0, 0, "no such key");
    expect_refused(&c, "lane", I, 0, 0, "no such key");
    /* Ranges, issue 18's nonsense among them. */
    expect_refused(&c, "deadline.ms", R, 0, 1e-300, "out of range 0.1..10000 (or 0)");
    expect_refused(&c, "deadline.ms", R, 0, -5, "out of range");
    expect_refused(&c, "deadline.ms", R, 0, NAN, "not a finite number");
    expect_refused(&c, "deadline.ms", R, 0, INFINITY, "not a finite number");
    expect_refused(&c, "lane.hough_threshold", I, 100000, 0, "100000 is out of range 1..16384");
    expect_refused(&c, "lane.hough_threshold", I, 0, 0, "out of range 1..16384 (or -1)");
    expect_refused(&c, "grasp.min_area", I, 100000000, 0, "out of range 0..67108864");
    expect_refused(&c, "grasp.min_area", I, -5, 0, "-5 is out of range");
    expect_refused(&c, "grasp.threshold", I, INT64_MIN, 0, "out of range 0..255");
    expect_refused(&c, "lane.hough_seed", I, (int64_t)INT32_MAX + 1, 0, "out of range");
    /* params.keys: only the listed keys. */
    rted_config listed = c;
    snprintf(listed.params_keys, sizeof listed.params_keys, "grasp.min_area, lane.canny_low");
    char msg[RTED_MSG];
    assert_true(rted_config_validate(&listed, msg, sizeof msg));
    assert_true(to_config(&listed, "lane.canny_low", I, 40, 0, &next, why, sizeof why));
    expect_refused(&listed, "lane.canny_high", I, 40, 0, "not in params.keys");
    expect_refused(&listed, "lane.canny", I, 40, 0, "no such key");
}

static void test_to_config_whole(void **state)
{
    rted_config c, next;
    rted_config_defaults(&c);
    writer w;
    put_head(&w, 3, 3);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 920, 0);
    put_value(&w, "deadline.ms", RTEDGE_PARAM_T_KIND_REAL, 0, 30);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 10, 0);
    static rted_params_request r;
    char why[RTED_MSG];
    assert_true(decode(&w, &r, why, sizeof why));
    assert_false(rted_params_to_config(&r, &c, &next, why, sizeof why));
    assert_non_null(strstr(why, "value 3 (grasp.min_area): given twice (values 1 and 3)"));
}

/* `set` applied to a copy of c is refused: by the cross-key checks or, with
 * frame, by the checks against a 160x120 frame; the reason contains `why`. */
static void expect_invalid(const rted_config *c, const char *set, bool frame, const char *why)
{
    rted_config t = *c;
    char msg[RTED_MSG];
    assert_true(rted_config_set(&t, set, "test", msg, sizeof msg));
    bool valid = rted_config_validate(&t, msg, sizeof msg);
    assert_true(valid == frame);
    if (frame)
        assert_false(rted_config_check_frame(&t, OW, OH, msg, sizeof msg));
    if (!strstr(msg, why))
        print_error("%s: '%s'\n", set, msg);
    assert_non_null(strstr(msg, why));
}

static void test_config_lists(void **state)
{
    rted_config c;
    rted_config_defaults(&c);
    char msg[RTED_MSG];
    const char *bad[][2] = {
        {"params.keys=publish.url", "params.keys: 'publish.url' is not a runtime key"},
        {"params.keys=lane.max_segments", "not a runtime key"},
        {"params.keys=grasp.min_area,,lane.canny_low", "an empty or overlong name"},
        {"params.keys=nosuch.key", "'nosuch.key' is not a key"},
        {"params.channel=RTEDGE_.*", "is not a channel name"},
        {"params.channel=RTEDGE_LANES", "also one of the channels rtedged publishes on"},
        {"params.channel=RTEDGE_PARAM_STATE", "also one of the channels rtedged publishes on"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        expect_invalid(&c, bad[i][0], false, bad[i][1]);
    /* The frame checks: values that could never find anything on 160x120. */
    const char *frame[][2] = {
        {"grasp.min_area=19201",
         "grasp.min_area = 19201 px is beyond the 160x120 frame's 19200 px"},
        {"lane.hough_threshold=281", "lane.hough_threshold = 281 is beyond"},
        {"lane.min_length=1000", "lane.min_length = 1000 is beyond"},
        {"lane.roi=0.5,0.5;0.51,0.5;0.5,0.51", "covers 3x2 px of the 160x120 frame"},
        {"lane.roi=2,2;3,2;3,3", "covers 0x0 px"},
        {"lane.roi=0,0;0.5,0.5;1,1", "encloses less than 1/1000"},
    };
    for (size_t i = 0; i < sizeof frame / sizeof frame[0]; i++)
        expect_invalid(&c, frame[i][0], true, frame[i][1]);
    assert_true(rted_config_check_frame(&c, OW, OH, msg, sizeof msg));
    assert_true(rted_config_check_frame(&c, 1280, 720, msg, sizeof msg));
    /* A path that does not run is not checked: an arm's tiny frames, no lane path. */
    rted_config arm = c;
    arm.lane_enabled = false;
    assert_false(rted_config_check_frame(&c, 24, 20, msg, sizeof msg));
    assert_true(rted_config_check_frame(&arm, 24, 20, msg, sizeof msg));
    arm.grasp_min_area = 1000;
    assert_false(rted_config_check_frame(&arm, 24, 20, msg, sizeof msg));
    arm.grasp_enabled = false;
    assert_true(rted_config_check_frame(&arm, 24, 20, msg, sizeof msg));
}

/* ---- the daemon's handler ---- */

static void path(char *out, size_t size, const char *name)
{
    snprintf(out, size, "%s/params_%s", build_dir, name);
}

static rted_daemon *objects_daemon(const char *name, rted_config *c)
{
    char y4m[512];
    path(y4m, sizeof y4m, name);
    looping_objects_config(c, y4m, 5);
    c->params_enabled = true;
    c->status_period_ms = 60000;
    return open_daemon(c, NULL);
}

typedef struct hostile {
    const char *what;
    writer w;
} hostile;

/* The cases of issue 18, as messages. */
static int issue_cases(hostile *h)
{
    static const struct {
        const char *what, *name;
        int8_t kind;
        int64_t i;
        double r;
        uint32_t count;
    } values[] = {
        {"injection", "lane.canny_mode=fixed   ", RTEDGE_PARAM_T_KIND_INT, 0, 0, 1},
        {"REAL for an INT key", "grasp.min_area", RTEDGE_PARAM_T_KIND_REAL, 0, 5000, 1},
        {"kind 7", "grasp.min_area", 7, 5000, 0, 1},
        {"a negative count", "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 5000, 0, 0x80000000u},
        {"deadline.ms = 1e-300", "deadline.ms", RTEDGE_PARAM_T_KIND_REAL, 0, 1e-300, 1},
        {"lane.hough_threshold = 100000", "lane.hough_threshold", RTEDGE_PARAM_T_KIND_INT, 100000,
         0, 1},
        {"grasp.min_area = 1e8", "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 100000000, 0, 1},
        {"grasp.min_area beyond the frame", "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, OW * OH + 1,
         0, 1},
    };
    int n = 0;
    h[n].what = "nparams = 0x7fffffff";
    put_head(&h[n].w, 1, 0x7fffffff);
    memset(h[n].w.buf + h[n].w.n, 0, 53 - h[n].w.n);
    h[n++].w.n = 53;
    h[n].what = "a name without its NUL";
    put_head(&h[n].w, 2, 1);
    put_u32(&h[n].w, 14);
    put_bytes(&h[n].w, "grasp.min_area", 14);
    put_bytes(&h[n].w, "\1\0\0\0\0\0\0\0\5\0\0\0\0\0\0\0\0", 17);
    n++;
    h[n].what = "57 KB malformed";
    put_head(&h[n].w, 3, 1);
    memset(h[n].w.buf + h[n].w.n, 0xff, 57000 - h[n].w.n);
    h[n++].w.n = 57000;
    for (size_t k = 0; k < sizeof values / sizeof values[0]; k++, n++) {
        h[n].what = values[k].what;
        put_head(&h[n].w, n + 1, values[k].count);
        put_value(&h[n].w, values[k].name, values[k].kind, values[k].i, values[k].r);
    }
    h[n].what = "a good value and a bad one";
    put_head(&h[n].w, n + 1, 2);
    put_value(&h[n].w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 920, 0);
    put_value(&h[n++].w, "lane.canny_low", RTEDGE_PARAM_T_KIND_INT, 5000, 0);
    return n;
}

/* One frame analysed (a step may rewind the looping recording first). */
static void step_frame(rted_daemon *d)
{
    rted_step st = rted_daemon_step(d);
    if (st == RTED_STEP_IDLE)
        st = rted_daemon_step(d);
    assert_int_equal(st, RTED_STEP_FRAME);
}

static void test_handler_issue_cases(void **state)
{
    rted_config c;
    rted_daemon *d = objects_daemon("cases.y4m", &c);
    static hostile h[16];
    int n = issue_cases(h);
    assert_int_equal(rted_daemon_step(d), RTED_STEP_FRAME);
    rted_counters before, after;
    rted_daemon_get_counters(d, &before);
    for (int i = 0; i < n; i++) {
        rted_daemon_handle_params(d, h[i].w.buf, h[i].w.n);
        rted_daemon_get_counters(d, &after);
        if (after.refused != before.refused + (uint64_t)i + 1)
            print_error("%s: not refused\n", h[i].what);
        assert_int_equal(after.refused, before.refused + (uint64_t)i + 1);
        assert_int_equal(after.reloads, before.reloads);
        step_frame(d);
    }
    /* A good request still goes through. */
    writer w;
    put_head(&w, 99, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 920, 0);
    rted_daemon_handle_params(d, w.buf, w.n);
    rted_daemon_get_counters(d, &after);
    assert_int_equal(after.reloads, before.reloads + 1);
    assert_int_equal(after.params_received, before.params_received + (uint64_t)n + 1);
    rted_daemon_close(d);
}

static uint32_t rnd(uint32_t *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return *seed >> 8;
}

/* Random hostile messages: a valid request mutated (bytes flipped, cut,
 * lengths and counts forged), or random bytes. */
static void hostile_message(writer *w, uint32_t *seed)
{
    static const char *const names[] = {
        "grasp.min_area",    "lane.canny_low",    "deadline.ms",         "lane.roi",
        "grasp.skip_border", "lane.max_segments", "lane.hough_threshold"};
    uint32_t count = 1 + rnd(seed) % 4;
    put_head(w, (int64_t)rnd(seed), count);
    for (uint32_t i = 0; i < count; i++) {
        double r;
        uint64_t bits = (uint64_t)rnd(seed) << 40;
        bits ^= (uint64_t)rnd(seed) << 20;
        bits ^= rnd(seed);
        memcpy(&r, &bits, sizeof r);
        const char *name = names[rnd(seed) % 7];
        int8_t kind = (int8_t)(rnd(seed) % 5);
        put_value(w, name, kind, (int64_t)(rnd(seed) % 3000) - 100, r);
    }
    uint32_t how = rnd(seed) % 6;
    if (how == 0) {
        size_t at = rnd(seed) % w->n;
        w->buf[at] ^= (uint8_t)(1u << (rnd(seed) % 8));
    } else if (how == 1) {
        w->n = rnd(seed) % w->n;
    } else if (how == 2) { /* forge the count or the first name's length */
        size_t at = rnd(seed) % 2 ? 24 : 28;
        uint32_t v = rnd(seed) % 2 ? 0x7fffffffu : rnd(seed) * 1021u;
        for (int k = 0; k < 4; k++)
            w->buf[at + (size_t)k] = (uint8_t)(v >> (24 - 8 * k));
    } else if (how == 3) {
        w->n = rnd(seed) % 4000;
        for (size_t k = 0; k < w->n; k++)
            w->buf[k] = (uint8_t)rnd(seed);
    } /* else well formed; values may still be wrong */
}

static void test_handler_hostile_stream_no_heap(void **state)
{
    if (!heapcount_active())
        skip();
    rted_config c;
    rted_daemon *d = objects_daemon("stream.y4m", &c);
    assert_int_equal(rted_daemon_step(d), RTED_STEP_FRAME);
    enum { N = 20000 };
    static writer stream[64];
    static hostile cases[16];
    int n_cases = issue_cases(cases);
    rted_counters before, after;
    rted_daemon_get_counters(d, &before);
    uint32_t seed = 12345;
    uint64_t frames = 0, calls = 0;
    for (int done = 0; done < N;) {
        /* Made before counting (the test's own buffers), then handled. */
        for (int k = 0; k < 64; k++)
            hostile_message(&stream[k], &seed);
        heapcount_reset();
        for (int k = 0; k < 64 && done < N; k++, done++) {
            rted_daemon_handle_params(d, stream[k].buf, stream[k].n);
            if (k % 8 == 0) {
                const hostile *h = &cases[(size_t)(done / 8) % (size_t)n_cases];
                rted_daemon_handle_params(d, h->w.buf, h->w.n);
                frames += rted_daemon_step(d) == RTED_STEP_FRAME;
            }
        }
        heapcount_counts hc;
        heapcount_get(&hc);
        calls += heapcount_calls(&hc);
    }
    rted_daemon_get_counters(d, &after);
    print_message("%d hostile messages and %d of issue 18's cases, %llu frames: %llu applied, "
                  "%llu refused, %llu heap calls\n",
                  N, N / 8, (unsigned long long)frames,
                  (unsigned long long)(after.reloads - before.reloads),
                  (unsigned long long)(after.refused - before.refused), (unsigned long long)calls);
    assert_int_equal(calls, 0);
    assert_int_equal(after.params_received - before.params_received, N + N / 8);
    assert_true(frames > 0);
    rted_daemon_close(d);
}

static void drain(lcm_t *lcm)
{
    while (lcm_handle_timeout(lcm, 0) > 0)
        ;
}

/* params.max_per_second through the real channel (memq://): the excess is
 * counted and dropped, not queued for later. */
static void test_rate_limit(void **state)
{
    rted_config c;
    rted_daemon *d = objects_daemon("rate.y4m", &c);
    assert_int_equal(c.params_max_per_second, 10);
    lcm_t *lcm = rted_daemon_lcm(d);
    writer w;
    put_head(&w, 5, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 920, 0);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = 0; i < 40; i++)
        assert_int_equal(lcm_publish(lcm, c.params_channel, w.buf, (unsigned)w.n), 0);
    for (int i = 0; i < 4; i++)
        rted_daemon_step(d);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    drain(lcm);
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    print_message("40 requests at once: %llu handled, %llu rate-limited\n",
                  (unsigned long long)n.params_received, (unsigned long long)n.rate_limited);
    assert_int_equal(n.params_received + n.rate_limited, 40);
    if (t1.tv_sec - t0.tv_sec < 1) /* all within one second's window */
        assert_int_equal(n.params_received, 10);
    assert_true(n.params_received >= 10 && n.params_received <= 20);
    assert_int_equal(n.reloads, n.params_received);
    rted_daemon_close(d);
}

/* A run-time change that would make a path fail or find nothing on the
 * source's frames is refused with the reason, the configuration in force
 * kept. */
/* ---- param_state_t: the schema, values and outcomes a tuning tool sees ---- */

typedef struct state_seen {
    int count;
    rtedge_param_state_t last;
} state_seen;

static void on_state(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    state_seen *s = user;
    if (s->count)
        rtedge_param_state_t_decode_cleanup(&s->last);
    assert_true(rtedge_param_state_t_decode(rb->data, 0, (int)rb->data_size, &s->last) > 0);
    s->count++;
}

static const rtedge_param_info_t *state_key(const rtedge_param_state_t *m, const char *name)
{
    for (int32_t i = 0; i < m->nkeys; i++)
        if (!strcmp(m->keys[i].name, name))
            return &m->keys[i];
    return NULL;
}

/* Sends w through memq:// and handles it: the state that came back. */
static const rtedge_param_state_t *request(rted_daemon *d, state_seen *s, const writer *w)
{
    lcm_t *lcm = rted_daemon_lcm(d);
    int before = s->count;
    lcm_publish(lcm, "RTEDGE_PARAMS", w->buf, (unsigned)w->n);
    rted_daemon_step(d);
    drain(lcm);
    assert_int_equal(s->count, before + 1);
    return &s->last;
}

static rted_daemon *state_daemon(const char *name, rted_config *c, const char *save_path,
                                 const char *keys, bool enabled)
{
    char y4m[512];
    path(y4m, sizeof y4m, name);
    looping_objects_config(c, y4m, 5);
    c->params_enabled = enabled;
    c->status_period_ms = 60000;
    snprintf(c->params_save_path, sizeof c->params_save_path, "%s", save_path);
    snprintf(c->params_keys, sizeof c->params_keys, "%s", keys);
    return open_daemon(c, NULL);
}

static void test_param_state(void **state)
{
    char saved[512];
    path(saved, sizeof saved, "saved.conf");
    remove(saved);
    rted_config c;
    rted_daemon *d = state_daemon("state.y4m", &c, saved, "", true);
    lcm_t *lcm = rted_daemon_lcm(d);
    static state_seen s;
    memset(&s, 0, sizeof s);
    lcm_subscription_t *sub = lcm_subscribe(lcm, "RTEDGE_PARAM_STATE", on_state, &s);
    writer w;
    /* A choice, a text and two numbers at once: applied, and the state shows them. */
    put_head(&w, 501, 4);
    put_text_value(&w, "lane.canny_mode", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "fixed");
    put_value(&w, "lane.canny_low", RTEDGE_PARAM_T_KIND_INT, 30, 0);
    put_value(&w, "lane.canny_high", RTEDGE_PARAM_T_KIND_INT, 90, 0);
    put_text_value(&w, "lane.roi", RTEDGE_PARAM_T_KIND_TEXT, 0, 0, "0,1;0.4,0.5;0.6,0.5;1,1");
    const rtedge_param_state_t *m = request(d, &s, &w);
    assert_int_equal(m->request_id, 501);
    assert_int_equal(m->outcome, RTEDGE_PARAM_STATE_T_OUTCOME_APPLIED);
    assert_true(m->enabled && m->save_writes_file);
    assert_string_equal(m->params_channel, "RTEDGE_PARAMS");
    assert_string_equal(m->saved_config, "");
    assert_int_equal(rted_daemon_config(d)->lane_canny_low, 30);
    /* The schema: only runtime keys, each with its type, range, unit and value. */
    assert_null(state_key(m, "publish.url"));
    assert_null(state_key(m, "lane.max_segments"));
    const rtedge_param_info_t *k = state_key(m, "lane.canny_low");
    assert_non_null(k);
    assert_int_equal(k->type, RTEDGE_PARAM_INFO_T_TYPE_INT);
    assert_true(k->min == 0 && k->max == 2040 && k->has_unset && k->unset_value == -1);
    assert_string_equal(k->unit, "L1 gradient");
    assert_int_equal(k->int_value, 30);
    assert_true(k->settable);
    k = state_key(m, "lane.canny_mode");
    assert_int_equal(k->type, RTEDGE_PARAM_INFO_T_TYPE_CHOICE);
    assert_int_equal(k->nchoices, 3);
    assert_string_equal(k->choices[0], "fixed");
    assert_string_equal(k->choices[2], "otsu");
    assert_string_equal(k->text_value, "fixed");
    k = state_key(m, "lane.roi");
    assert_int_equal(k->type, RTEDGE_PARAM_INFO_T_TYPE_TEXT);
    assert_string_equal(k->text_value, "0,1;0.4,0.5;0.6,0.5;1,1");
    k = state_key(m, "deadline.ms");
    assert_int_equal(k->type, RTEDGE_PARAM_INFO_T_TYPE_REAL);
    assert_string_equal(k->unit, "ms");
    k = state_key(m, "grasp.skip_border");
    assert_int_equal(k->type, RTEDGE_PARAM_INFO_T_TYPE_BOOL);
    assert_true(strlen(k->help) > 10);
    assert_int_equal(m->config_hash, (int64_t)rted_config_hash(rted_daemon_config(d)));
    /* Refused: the reason, the configuration in force unchanged. */
    put_head(&w, 502, 1);
    put_value(&w, "lane.canny_high", RTEDGE_PARAM_T_KIND_INT, 5000, 0);
    m = request(d, &s, &w);
    assert_int_equal(m->request_id, 502);
    assert_int_equal(m->outcome, RTEDGE_PARAM_STATE_T_OUTCOME_REFUSED);
    assert_non_null(strstr(m->reason, "value 1 (lane.canny_high): 5000 is out of range 0..2040"));
    assert_int_equal(state_key(m, "lane.canny_high")->int_value, 90);
    put_head(&w, 503, 1);
    put_value(&w, "lane.canny_low", RTEDGE_PARAM_T_KIND_INT, 100, 0);
    m = request(d, &s, &w);
    assert_int_equal(m->outcome, RTEDGE_PARAM_STATE_T_OUTCOME_REFUSED);
    assert_non_null(strstr(m->reason, "canny_low"));
    /* A malformed message: refused, with no request id to echo. */
    put_head(&w, 504, 1);
    put_value(&w, "lane.canny_low", RTEDGE_PARAM_T_KIND_INT, 40, 0);
    w.buf[3] ^= 1;
    m = request(d, &s, &w);
    assert_int_equal(m->request_id, 0);
    assert_non_null(strstr(m->reason, "not a params_t"));
    /* Save: the file reads back to the configuration in force. */
    put_head_action(&w, 505, RTEDGE_PARAMS_T_ACTION_SAVE, 0);
    m = request(d, &s, &w);
    assert_int_equal(m->request_id, 505);
    assert_int_equal(m->outcome, RTEDGE_PARAM_STATE_T_OUTCOME_SAVED);
    assert_non_null(strstr(m->reason, "saved to"));
    FILE *f = fopen(saved, "rb");
    assert_non_null(f);
    static char text[RTED_CONFIG_TEXT_MAX];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    assert_string_equal(text, m->saved_config);
    rted_config back;
    char why[RTED_MSG];
    rted_config_defaults(&back);
    assert_true(rted_config_load(&back, saved, why, sizeof why));
    assert_true(rted_config_validate(&back, why, sizeof why));
    assert_int_equal(rted_config_hash(&back), rted_config_hash(rted_daemon_config(d)));
    assert_int_equal(back.lane_canny_low, 30);
    assert_string_equal(back.lane_roi, "0,1;0.4,0.5;0.6,0.5;1,1");
    lcm_unsubscribe(lcm, sub);
    rted_daemon_close(d);
    rtedge_param_state_t_decode_cleanup(&s.last);

    /* No save path: the text only; an allow list: settable only where listed. */
    d = state_daemon("state2.y4m", &c, "", "grasp.min_area", true);
    lcm = rted_daemon_lcm(d);
    memset(&s, 0, sizeof s);
    sub = lcm_subscribe(lcm, "RTEDGE_PARAM_STATE", on_state, &s);
    put_head_action(&w, 601, RTEDGE_PARAMS_T_ACTION_SAVE, 0);
    m = request(d, &s, &w);
    assert_int_equal(m->outcome, RTEDGE_PARAM_STATE_T_OUTCOME_SAVED);
    assert_non_null(strstr(m->reason, "not written on the robot (params.save_path is empty)"));
    assert_non_null(strstr(m->saved_config, "\n[lane]\n"));
    assert_false(m->save_writes_file);
    assert_true(state_key(m, "grasp.min_area")->settable);
    assert_false(state_key(m, "lane.canny_low")->settable);
    put_head(&w, 602, 1);
    put_value(&w, "lane.canny_low", RTEDGE_PARAM_T_KIND_INT, 40, 0);
    m = request(d, &s, &w);
    assert_non_null(strstr(m->reason, "not in params.keys"));
    lcm_unsubscribe(lcm, sub);
    rted_daemon_close(d);
    rtedge_param_state_t_decode_cleanup(&s.last);

    /* The channel off: the state says so, requests go unheard. */
    char y4m[512];
    path(y4m, sizeof y4m, "state3.y4m");
    looping_objects_config(&c, y4m, 5);
    c.status_period_ms = 60000;
    c.params_state_period_ms = 100;
    d = open_daemon(&c, NULL);
    lcm = rted_daemon_lcm(d);
    memset(&s, 0, sizeof s);
    sub = lcm_subscribe(lcm, "RTEDGE_PARAM_STATE", on_state, &s);
    put_head(&w, 701, 1);
    put_value(&w, "grasp.min_area", RTEDGE_PARAM_T_KIND_INT, 920, 0);
    lcm_publish(lcm, "RTEDGE_PARAMS", w.buf, (unsigned)w.n);
    rted_daemon_step(d);
    drain(lcm);
    assert_int_equal(s.count, 0);
    assert_int_equal(rted_daemon_config(d)->grasp_min_area, c.grasp_min_area);
    /* The periodic state goes out with the first status after its period. */
    struct timespec pause = {0, 120000000};
    nanosleep(&pause, NULL);
    rted_daemon_publish_status(d);
    drain(lcm);
    assert_int_equal(s.count, 1);
    assert_false(s.last.enabled);
    assert_false(state_key(&s.last, "grasp.min_area")->settable);
    rtedge_param_state_t_decode_cleanup(&s.last);
    lcm_unsubscribe(lcm, sub);
    rted_daemon_close(d);
}

static void test_apply_frame_checks(void **state)
{
    rted_config c;
    rted_daemon *d = objects_daemon("apply.y4m", &c);
    char msg[RTED_MSG];
    rted_config next = c;
    snprintf(next.lane_roi, sizeof next.lane_roi, "0.5,0.5;0.51,0.5;0.5,0.51");
    assert_false(rted_daemon_apply(d, &next, msg, sizeof msg));
    assert_non_null(strstr(msg, "lane.roi"));
    next = c;
    next.grasp_min_area = OW * OH + 1;
    assert_false(rted_daemon_apply(d, &next, msg, sizeof msg));
    assert_non_null(strstr(msg, "no object could ever be found"));
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.refused, 2);
    assert_int_equal(n.reloads, 0);
    for (int i = 0; i < 8; i++)
        step_frame(d);
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.path_errors, 0);
    assert_int_equal(n.publish_errors, 0);
    rted_daemon_close(d);
    /* At start, the same checks refuse to open. */
    char y4m[512];
    path(y4m, sizeof y4m, "apply.y4m");
    base_config(&c, y4m, "memq://");
    c.grasp_min_area = OW * OH + 1;
    rted_daemon *bad;
    assert_false(rted_daemon_open(&bad, &c, NULL, msg, sizeof msg));
    assert_non_null(strstr(msg, "the configuration does not fit the source: grasp.min_area"));
}

int main(int argc, char **argv)
{
    build_dir = argc > 1 ? argv[1] : ".";
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode_valid),
        cmocka_unit_test(test_decode_counts),
        cmocka_unit_test(test_decode_names),
        cmocka_unit_test(test_decode_texts),
        cmocka_unit_test(test_to_config),
        cmocka_unit_test(test_to_config_whole),
        cmocka_unit_test(test_config_lists),
        cmocka_unit_test(test_handler_issue_cases),
        cmocka_unit_test(test_handler_hostile_stream_no_heap),
        cmocka_unit_test(test_rate_limit),
        cmocka_unit_test(test_apply_frame_checks),
        cmocka_unit_test(test_param_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
