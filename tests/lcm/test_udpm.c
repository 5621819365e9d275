/* udpm:// inside a private network namespace (run by netns.sh): the
 * publisher's messages reach a subscriber, publishing makes no heap call,
 * lcm-logger records them into a log rtedge reads, and lcm-logplayer plays
 * a log rtedge wrote. */
#include <fcntl.h>
#include <setjmp.h>
#include <signal.h>
#include <spawn.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "heapcount.h"
#include "lcm_log.h"
#include "messages.h"
#include "publish/publish.h"
#include "sources/recorded_source.h"

extern char **environ;

#define URL "udpm://239.255.76.67:7667?ttl=0"

static const rte_publish_limits limits = {
    .max_text = 64,
    .max_roi_points = 8,
    .max_segments = 16,
    .max_objects = 4,
    .max_params = 4,
    .max_image_bytes = 100000,
    .max_metadata = 2,
};

static void publish_one(rte_publisher *pub, int i, const samples *s)
{
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    if (sample_publish(pub, i, s, msg, sizeof msg) != RTE_OK)
        fail_msg("publish %s: %s", sample_channels[i], msg);
}

/* The encoding of sample message i, for comparing with what arrived. */
static int encode_sample(int i, const samples *s, uint8_t *buf, int size)
{
    switch (i) {
    case 0: return rtedge_lane_detection_t_encode(buf, 0, size, &s->lane);
    case 1: return rtedge_grasp_detection_t_encode(buf, 0, size, &s->grasp);
    case 2: return rtedge_status_t_encode(buf, 0, size, &s->status);
    case 3: return rtedge_params_t_encode(buf, 0, size, &s->paramset);
    default: return rtedge_image_t_encode(buf, 0, size, &s->image);
    }
}

static void check_bytes(int i, const samples *s, const char *channel, const void *data, int size)
{
    static uint8_t expect[131072];
    int n = encode_sample(i, s, expect, sizeof expect);
    assert_string_equal(channel, sample_channels[i]);
    assert_int_equal(size, n);
    assert_memory_equal(data, expect, (size_t)n);
}

static struct {
    char channel[64];
    uint8_t data[131072];
    int size, count;
} got;

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)user;
    snprintf(got.channel, sizeof got.channel, "%s", channel);
    memcpy(got.data, rbuf->data, rbuf->data_size);
    got.size = (int)rbuf->data_size;
    got.count++;
}

static void test_udpm_round_trip_without_heap_calls(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 11);
    rte_publisher *pub = NULL;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    assert_int_equal(rte_publisher_create(&pub, URL, &limits, msg, sizeof msg), RTE_OK);
    lcm_t *sub_lcm = lcm_create(URL);
    assert_non_null(sub_lcm);
    lcm_subscription_t *sub = lcm_subscribe(sub_lcm, ".*", on_message, NULL);
    int counting = heapcount_active();
    for (int round = 0; round < 3; round++)
        for (int i = 0; i < 5; i++) {
            got.count = 0;
            heapcount_reset();
            publish_one(pub, i, &s);
            heapcount_counts c;
            heapcount_get(&c);
            /* The first message may set things up; after it, none. */
            if (counting && round > 0 && heapcount_calls(&c) != 0)
                fail_msg("publishing %s over udpm made %llu heap calls", sample_channels[i],
                         (unsigned long long)heapcount_calls(&c));
            while (got.count == 0)
                assert_true(lcm_handle_timeout(sub_lcm, 2000) > 0);
            check_bytes(i, &s, got.channel, got.data, got.size);
        }
    /* An image over 64 KB: liblcm sends it in fragments, still from the
     * caller's buffer. */
    static uint8_t big[90000];
    for (size_t i = 0; i < sizeof big; i++)
        big[i] = (uint8_t)(i * 13);
    rtedge_image_t img = {7,   300, 300, 300, RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY, (int32_t)sizeof big,
                          big, 0,   NULL};
    for (int round = 0; round < 3; round++) {
        got.count = 0;
        heapcount_reset();
        assert_int_equal(rte_publish_image(pub, "BIG", &img, msg, sizeof msg), RTE_OK);
        /* This thread's calls: liblcm's receive thread, reassembling the
         * fragments for the subscriber in this process, allocates. */
        heapcount_counts c;
        heapcount_get_thread(&c);
        if (counting && round > 0)
            assert_int_equal(heapcount_calls(&c), 0);
        while (got.count == 0)
            assert_true(lcm_handle_timeout(sub_lcm, 2000) > 0);
        assert_string_equal(got.channel, "BIG");
        rtedge_image_t d;
        assert_int_equal(rtedge_image_t_decode(got.data, 0, got.size, &d), got.size);
        assert_int_equal(d.size, (int32_t)sizeof big);
        assert_memory_equal(d.data, big, sizeof big);
        rtedge_image_t_decode_cleanup(&d);
        heapcount_get(&c);
        if (counting && round == 2)
            print_message("a fragmented image over udpm: publishing thread 0 heap calls, "
                          "process (receiving) %llu\n",
                          (unsigned long long)heapcount_calls(&c));
    }
    if (!counting)
        print_message("heapcount is not interposed: heap calls not counted\n");
    lcm_unsubscribe(sub_lcm, sub);
    lcm_destroy(sub_lcm);
    rte_publisher_destroy(pub);
}

static pid_t spawn(char *const argv[])
{
    pid_t pid;
    assert_int_equal(posix_spawnp(&pid, argv[0], NULL, NULL, argv, environ), 0);
    return pid;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000};
    nanosleep(&ts, NULL);
}

/* lcm-logger records what rtedge publishes; rtedge reads its log. */
static void test_lcm_logger_records_our_messages(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 12);
    char path[512], msg[RTE_PUBLISH_MESSAGE_SIZE];
    snprintf(path, sizeof path, "%s/logger.%d.lcmlog", getenv("RTE_TEST_TMP"), (int)getpid());
    char *argv[] = {(char *)"lcm-logger", (char *)"-f", (char *)"--lcm-url=" URL, path, NULL};
    pid_t logger = spawn(argv);
    rte_publisher *pub = NULL;
    assert_int_equal(rte_publisher_create(&pub, URL, &limits, msg, sizeof msg), RTE_OK);
    /* Until the logger has subscribed: publish pings until one is in its log. */
    rte_lcm_log_reader r;
    rte_lcm_log_event ev;
    int ready = 0;
    for (int tries = 0; tries < 100 && !ready; tries++) {
        publish_one(pub, 2, &s);
        sleep_ms(100);
        if (rte_lcm_log_reader_open(&r, path, 131072, msg, sizeof msg) == RTE_OK) {
            ready = rte_lcm_log_read(&r, &ev, msg, sizeof msg) == RTE_OK;
            rte_lcm_log_reader_close(&r);
        }
    }
    assert_true(ready);
    for (int i = 0; i < 5; i++)
        publish_one(pub, i, &s);
    sleep_ms(500); /* the logger flushes every 100 ms */
    kill(logger, SIGINT);
    int status;
    assert_int_equal(waitpid(logger, &status, 0), logger);
    rte_publisher_destroy(pub);

    assert_int_equal(rte_lcm_log_reader_open(&r, path, 131072, msg, sizeof msg), RTE_OK);
    int found = 0;
    for (;;) {
        rte_status st = rte_lcm_log_read(&r, &ev, msg, sizeof msg);
        if (st == RTE_ERR_END)
            break;
        assert_int_equal(st, RTE_OK);
        /* pings (STATUS) first, then the five in order */
        if (found == 0 && strcmp(ev.channel, "LANES") != 0)
            continue;
        assert_true(found < 5);
        check_bytes(found, &s, ev.channel, ev.data, ev.size);
        found++;
    }
    assert_int_equal(found, 5);
    rte_lcm_log_reader_close(&r);
    unlink(path);
}

/* lcm-logplayer plays a log rtedge wrote. */
static void test_lcm_logplayer_plays_our_log(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 13);
    char path[512], url[600], msg[RTE_PUBLISH_MESSAGE_SIZE];
    snprintf(path, sizeof path, "%s/player.%d.lcmlog", getenv("RTE_TEST_TMP"), (int)getpid());
    snprintf(url, sizeof url, "file://%s", path);
    rte_publisher *pub = NULL;
    assert_int_equal(rte_publisher_create(&pub, url, &limits, msg, sizeof msg), RTE_OK);
    for (int i = 0; i < 5; i++)
        publish_one(pub, i, &s);
    rte_publisher_destroy(pub);

    lcm_t *sub_lcm = lcm_create(URL);
    assert_non_null(sub_lcm);
    lcm_subscription_t *sub = lcm_subscribe(sub_lcm, ".*", on_message, NULL);
    char *argv[] = {(char *)"lcm-logplayer", (char *)"--speed=10", (char *)"--lcm-url=" URL, path,
                    NULL};
    pid_t player = spawn(argv);
    for (int i = 0; i < 5; i++) {
        got.count = 0;
        while (got.count == 0)
            assert_true(lcm_handle_timeout(sub_lcm, 5000) > 0);
        check_bytes(i, &s, got.channel, got.data, got.size);
    }
    int status;
    assert_int_equal(waitpid(player, &status, 0), player);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    lcm_unsubscribe(sub_lcm, sub);
    lcm_destroy(sub_lcm);
    unlink(path);
}

/* The live image_t source: newest frame first, timeouts, bad messages,
 * and no heap call per frame after the first. */
static void test_live_lcm_source(void **state)
{
    (void)state;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_source src;
    rte_lcm_source_config cfg = {URL, "CAMERA", RTE_PIXEL_GREY, 64, 48};
    assert_int_equal(rte_lcm_live_source_open(&src, &cfg, msg, sizeof msg), RTE_OK);
    assert_string_equal(src.ops->kind, "lcm");
    rte_publisher *pub = NULL;
    assert_int_equal(rte_publisher_create(&pub, URL, &limits, msg, sizeof msg), RTE_OK);
    static uint8_t pixels[64 * 48];
    rtedge_image_t img = {0,       64,     48, 64,  RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY,
                          64 * 48, pixels, 0,  NULL};
    rte_source_frame f;
    assert_int_equal(rte_source_next(&src, &f, 50, msg, sizeof msg), RTE_ERR_TIMEOUT);
    assert_int_equal(rte_recorded_source_rewind(&src), RTE_ERR_UNSUPPORTED); /* live */

    /* Three images before next(): it hands out the newest. The receive
     * thread takes them in turn, so wait until all three are there. */
    for (int k = 1; k <= 3; k++) {
        img.utime = 1000 * k;
        pixels[0] = (uint8_t)k;
        assert_int_equal(rte_publish_image(pub, "CAMERA", &img, msg, sizeof msg), RTE_OK);
    }
    sleep_ms(200);
    assert_int_equal(rte_source_next(&src, &f, 1000, msg, sizeof msg), RTE_OK);
    assert_int_equal(f.frame.plane[0][0], 3);
    assert_int_equal(f.recorded_ns, 3000 * 1000);
    assert_int_equal(f.dropped, 2);
    rte_source_stats stats;
    rte_source_get_stats(&src, &stats);
    assert_int_equal(stats.skipped, 2);

    /* Not an image_t on the channel: a bad frame. */
    samples s;
    samples_fill(&s, 14);
    assert_int_equal(rte_publish_status(pub, "CAMERA", &s.status, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_source_next(&src, &f, 1000, msg, sizeof msg), RTE_ERR_FORMAT);

    /* Steady state: publish, receive; count the source's heap calls. */
    int counting = heapcount_active();
    uint64_t calls = 0;
    for (int k = 0; k < 20; k++) {
        img.utime = 10000 + k;
        pixels[0] = (uint8_t)(100 + k);
        assert_int_equal(rte_publish_image(pub, "CAMERA", &img, msg, sizeof msg), RTE_OK);
        heapcount_reset();
        assert_int_equal(rte_source_next(&src, &f, 1000, msg, sizeof msg), RTE_OK);
        heapcount_counts c;
        heapcount_get(&c);
        if (k > 0)
            calls += heapcount_calls(&c);
        assert_int_equal(f.frame.plane[0][0], 100 + k);
        assert_int_equal(f.dropped, 0);
    }
    if (counting) {
        print_message("live lcm source: %llu heap calls in 19 frames\n", (unsigned long long)calls);
        assert_int_equal(calls, 0);
    }
    rte_source_get_stats(&src, &stats);
    assert_int_equal(stats.frames, 21);
    assert_int_equal(stats.bad_frames, 1);
    rte_source_close(&src);

    /* Images over 64 KB arrive in fragments: liblcm's receive thread
     * allocates a reassembly buffer per message and lcm_handle frees it
     * (liblcm's, not rtedge's: measured and reported). */
    rte_lcm_source_config big_cfg = {URL, "BIG", RTE_PIXEL_GREY, 320, 240};
    assert_int_equal(rte_lcm_live_source_open(&src, &big_cfg, msg, sizeof msg), RTE_OK);
    static uint8_t big[320 * 240];
    rtedge_image_t big_img = {
        0, 320, 240, 320, RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY, (int32_t)sizeof big, big, 0, NULL};
    for (int k = 0; k < 4; k++) {
        big[0] = (uint8_t)k;
        heapcount_reset();
        assert_int_equal(rte_publish_image(pub, "BIG", &big_img, msg, sizeof msg), RTE_OK);
        assert_int_equal(rte_source_next(&src, &f, 1000, msg, sizeof msg), RTE_OK);
        heapcount_counts process, self;
        heapcount_get(&process);
        heapcount_get_thread(&self);
        assert_int_equal(f.frame.plane[0][0], k);
        if (counting && k > 0) {
            /* The caller only frees what the receive thread allocated. */
            assert_int_equal(heapcount_allocations(&self), 0);
            assert_true(self.free_calls <= 1);
            if (k == 3)
                print_message("live lcm source, a %zu-byte image: %llu heap calls in all, "
                              "%llu allocations in liblcm's receive thread, %llu free in "
                              "lcm_handle (the caller's thread)\n",
                              sizeof big, (unsigned long long)heapcount_calls(&process),
                              (unsigned long long)heapcount_allocations(&process),
                              (unsigned long long)self.free_calls);
        }
    }
    rte_publisher_destroy(pub);
    rte_source_close(&src);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_udpm_round_trip_without_heap_calls),
        cmocka_unit_test(test_lcm_logger_records_our_messages),
        cmocka_unit_test(test_lcm_logplayer_plays_our_log),
        cmocka_unit_test(test_live_lcm_source),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
