/* The waiting source (src/sources/waiting.c): a camera that is not there
 * at start, driven with a scripted opener and a fake clock. */
#include "unit.h"

#include <stdbool.h>
#include <stdio.h>

#include "sources/waiting.h"

/* The fake camera: frames numbered from 0; its size and format are what
 * the script says when it opens. */
typedef struct camera {
    uint8_t pixel[4];
    uint64_t next_sequence;
    bool closed;
} camera;

static rte_status camera_next(void *impl, rte_source_frame *frame, int32_t timeout_ms, char *msg,
                              size_t msg_size)
{
    camera *c = impl;
    memset(frame, 0, sizeof *frame);
    frame->frame.plane[0] = c->pixel;
    frame->sequence = c->next_sequence++;
    return RTE_OK;
}

static void camera_stats(const void *impl, rte_source_stats *stats)
{
    const camera *c = impl;
    *stats = (rte_source_stats){.state = RTE_SOURCE_STREAMING, .frames = c->next_sequence};
}

static void camera_close(void *impl) { ((camera *)impl)->closed = true; }

static const rte_source_ops camera_ops = {"fake", camera_next, camera_stats, camera_close};

/* The world: the clock, the sleeps, and what each opening attempt finds. */
typedef struct world {
    int64_t now_ns;
    int64_t slept_ms;
    int attempts;
    int absent_attempts;   /* attempts that find no camera */
    int32_t width, height; /* the camera's size when it is there */
    rte_pixel_format format;
    camera cam;
} world;

static int64_t world_now(void *ctx) { return ((world *)ctx)->now_ns; }

static void world_sleep(void *ctx, int32_t ms)
{
    world *w = ctx;
    w->slept_ms += ms;
    w->now_ns += (int64_t)ms * 1000000;
}

static rte_status world_open(void *ctx, rte_source *source, char *msg, size_t msg_size)
{
    world *w = ctx;
    if (++w->attempts <= w->absent_attempts) {
        snprintf(msg, msg_size, "no camera with that id");
        return RTE_ERR_DEVICE;
    }
    w->cam = (camera){{1, 2, 3, 4}, 0, false};
    *source = (rte_source){&camera_ops, &w->cam, w->width, w->height, w->format};
    return RTE_OK;
}

static rte_waiting_config config_for(world *w)
{
    return (rte_waiting_config){.open = world_open,
                                .ctx = w,
                                .name = "cam0",
                                .max_width = 640,
                                .max_height = 480,
                                .format = RTE_PIXEL_NV12,
                                .retry_min_ms = 500,
                                .retry_max_ms = 2000,
                                .now_ns = world_now,
                                .sleep_ms = world_sleep};
}

static void bad_configurations(void **state)
{
    world w = {0};
    rte_source s;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_waiting_config c = config_for(&w);
    c.open = NULL;
    assert_int_equal(rte_waiting_source_open(&s, &c, msg, sizeof msg), RTE_ERR_ARGUMENT);
    c = config_for(&w);
    c.max_width = 0;
    assert_int_equal(rte_waiting_source_open(&s, &c, msg, sizeof msg), RTE_ERR_ARGUMENT);
    c = config_for(&w);
    c.format = 0;
    assert_int_equal(rte_waiting_source_open(&s, &c, msg, sizeof msg), RTE_ERR_ARGUMENT);
}

/* Absent for three attempts (0.5 s, then 1 s, 2 s, 2 s apart), then there:
 * the caller's timeouts are kept, the reasons said, and the camera's frames
 * handed out once it opens. */
static void waits_then_streams(void **state)
{
    world w = {.absent_attempts = 3, .width = 640, .height = 480, .format = RTE_PIXEL_NV12};
    rte_waiting_config c = config_for(&w);
    rte_source s;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_waiting_source_open(&s, &c, msg, sizeof msg), RTE_OK);
    assert_int_equal(s.max_width, 640);
    assert_int_equal(s.format, RTE_PIXEL_NV12);
    rte_source_stats st;
    rte_source_get_stats(&s, &st);
    assert_int_equal(st.state, RTE_SOURCE_RECONNECTING);

    rte_source_frame f;
    /* 100 ms at a time: no attempt before 500 ms. */
    for (int i = 0; i < 4; i++) {
        assert_int_equal(rte_source_next(&s, &f, 100, msg, sizeof msg), RTE_ERR_TIMEOUT);
        assert_non_null(strstr(msg, "waiting for the camera"));
    }
    assert_int_equal(w.attempts, 0);
    assert_int_equal(w.slept_ms, 400);
    assert_int_equal(rte_source_next(&s, &f, 100, msg, sizeof msg), RTE_ERR_DEVICE);
    assert_int_equal(w.attempts, 1);
    assert_string_equal(msg, "cam0: no camera with that id; retrying in 1000 ms");
    /* No limit on the wait: each call sleeps to the next attempt. */
    assert_int_equal(rte_source_next(&s, &f, -1, msg, sizeof msg), RTE_ERR_DEVICE);
    assert_string_equal(msg, "cam0: no camera with that id; retrying in 2000 ms");
    assert_int_equal(rte_source_next(&s, &f, -1, msg, sizeof msg), RTE_ERR_DEVICE);
    assert_string_equal(msg, "cam0: no camera with that id; retrying in 2000 ms"); /* the cap */
    assert_int_equal(w.slept_ms, 500 + 1000 + 2000);
    rte_source_get_stats(&s, &st);
    assert_int_equal(st.state, RTE_SOURCE_RECONNECTING);
    assert_int_equal(st.errors, 3);

    assert_int_equal(rte_source_next(&s, &f, -1, msg, sizeof msg), RTE_OK);
    assert_int_equal(w.attempts, 4);
    assert_int_equal(f.sequence, 0);
    assert_int_equal(f.frame.plane[0][2], 3);
    assert_int_equal(rte_source_next(&s, &f, 0, msg, sizeof msg), RTE_OK);
    assert_int_equal(f.sequence, 1);
    assert_int_equal(w.attempts, 4);
    rte_source_get_stats(&s, &st);
    assert_int_equal(st.state, RTE_SOURCE_STREAMING);
    assert_int_equal(st.frames, 2);
    assert_int_equal(st.errors, 3); /* the attempts before it came */
    rte_source_close(&s);
    assert_true(w.cam.closed);
    assert_null(s.ops);
}

/* A camera larger than announced, or in another format, is closed again and
 * refused; the waiting goes on. */
static void refuses_what_does_not_fit(void **state)
{
    world w = {.width = 1280, .height = 720, .format = RTE_PIXEL_NV12};
    rte_waiting_config c = config_for(&w);
    rte_source s;
    rte_source_frame f;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    assert_int_equal(rte_waiting_source_open(&s, &c, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&s, &f, -1, msg, sizeof msg), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "cam0 came up as 1280x720"));
    assert_non_null(strstr(msg, "not within 640x480"));
    assert_true(w.cam.closed);
    w.width = 640, w.height = 480, w.format = RTE_PIXEL_YUYV;
    assert_int_equal(rte_source_next(&s, &f, -1, msg, sizeof msg), RTE_ERR_DEVICE);
    assert_non_null(strstr(msg, "came up as 640x480"));
    assert_true(w.cam.closed);
    w.width = 320, w.height = 240, w.format = RTE_PIXEL_NV12; /* smaller fits */
    assert_int_equal(rte_source_next(&s, &f, -1, msg, sizeof msg), RTE_OK);
    assert_false(w.cam.closed);
    rte_source_close(&s);
    assert_true(w.cam.closed);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bad_configurations),
        cmocka_unit_test(waits_then_streams),
        cmocka_unit_test(refuses_what_does_not_fit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
