/* The publisher: every message type round trip over memq:// and file://
 * (read back with liblcm's lcm_eventlog and with rtedge's reader), limits,
 * bad URLs, damaged logs, and the heap calls each transport makes per
 * message (counted by tests/heapcount). */
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>
#include <lcm/eventlog.h>

#include "heapcount.h"
#include "lcm_log.h"
#include "messages.h"
#include "publish/publish.h"

static const rte_publish_limits limits = {
    .max_text = 64,
    .max_roi_points = 8,
    .max_segments = 16,
    .max_objects = 4,
    .max_params = 4,
    .max_image_bytes = SAMPLE_IMAGE_W * SAMPLE_IMAGE_H,
    .max_metadata = 2,
};

/* ---- what a subscriber received ---- */

static struct {
    char channel[64];
    uint8_t data[65536];
    int size;
    int count;
} got;

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)user;
    snprintf(got.channel, sizeof got.channel, "%s", channel);
    assert_true(rbuf->data_size <= sizeof got.data);
    memcpy(got.data, rbuf->data, rbuf->data_size);
    got.size = (int)rbuf->data_size;
    got.count++;
}

/* Decodes `data` as TYPE, re-encodes it and compares the bytes with what
 * encoding `orig` gives: every field survived. */
#define CHECK_ROUND_TRIP(TYPE, orig, data, size)                              \
    do {                                                                      \
        TYPE decoded;                                                         \
        assert_int_equal(TYPE##_decode((data), 0, (size), &decoded), (size)); \
        uint8_t *a = malloc((size_t)(size)), *b = malloc((size_t)(size));     \
        assert_int_equal(TYPE##_encode(a, 0, (size), (orig)), (size));        \
        assert_int_equal(TYPE##_encode(b, 0, (size), &decoded), (size));      \
        assert_memory_equal(a, b, (size_t)(size));                            \
        assert_memory_equal(a, (data), (size_t)(size));                       \
        free(a);                                                              \
        free(b);                                                              \
        TYPE##_decode_cleanup(&decoded);                                      \
    } while (0)

static rte_publisher *create(const char *url)
{
    rte_publisher *pub = NULL;
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    rte_status st = rte_publisher_create(&pub, url, &limits, msg, sizeof msg);
    if (st != RTE_OK)
        fail_msg("%s: %s", url, msg);
    return pub;
}

static void publish_all(rte_publisher *pub, const samples *s)
{
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    for (int i = 0; i < 5; i++)
        assert_int_equal(sample_publish(pub, i, s, msg, sizeof msg), RTE_OK);
}

/* The five messages in publish_all's order. */
static void check_message(int index, const char *channel, const uint8_t *data, int size,
                          const samples *s)
{
    assert_string_equal(channel, sample_channels[index]);
    switch (index) {
    case 0: {
        CHECK_ROUND_TRIP(rtedge_lane_detection_t, &s->lane, data, size);
        rtedge_lane_detection_t d;
        rtedge_lane_detection_t_decode(data, 0, size, &d);
        assert_int_equal(d.nsegments, SAMPLE_SEGMENTS);
        assert_int_equal(d.segments[6].y2, s->segments[6].y2);
        assert_string_equal(d.header.source_id, "v4l2:/dev/video0");
        assert_int_equal(d.header.roi[3].x, s->roi[3].x);
        assert_true(d.right.predicted && !d.left.predicted);
        assert_true(d.heading_rad == -0.5f);
        rtedge_lane_detection_t_decode_cleanup(&d);
        break;
    }
    case 1: CHECK_ROUND_TRIP(rtedge_grasp_detection_t, &s->grasp, data, size); break;
    case 2: CHECK_ROUND_TRIP(rtedge_status_t, &s->status, data, size); break;
    case 3: CHECK_ROUND_TRIP(rtedge_params_t, &s->paramset, data, size); break;
    default: {
        CHECK_ROUND_TRIP(rtedge_image_t, &s->image, data, size);
        rtedge_image_t d;
        rtedge_image_t_decode(data, 0, size, &d);
        assert_memory_equal(d.data, s->pixels, sizeof s->pixels);
        assert_string_equal(d.metadata[0].key, "exposure");
        rtedge_image_t_decode_cleanup(&d);
        break;
    }
    }
}

static void test_memq_round_trip(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 1);
    rte_publisher *pub = create("memq://");
    lcm_t *lcm = rte_publisher_lcm(pub);
    assert_non_null(lcm);
    lcm_subscription_t *sub = lcm_subscribe(lcm, ".*", on_message, NULL);
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    for (int i = 0; i < 5; i++) {
        got.count = 0;
        assert_int_equal(sample_publish(pub, i, &s, msg, sizeof msg), RTE_OK);
        assert_true(lcm_handle_timeout(lcm, 1000) > 0);
        assert_int_equal(got.count, 1);
        check_message(i, got.channel, got.data, got.size, &s);
    }
    rte_publish_stats stats;
    rte_publisher_get_stats(pub, &stats);
    assert_int_equal(stats.messages, 5);
    assert_int_equal(stats.refused, 0);
    lcm_unsubscribe(lcm, sub);
    rte_publisher_destroy(pub);
}

static const char *temp_path(char *buf, size_t size, const char *name)
{
    const char *dir = getenv("RTE_TEST_TMP");
    snprintf(buf, size, "%s/%s.%d", dir ? dir : "/tmp", name, (int)getpid());
    return buf;
}

/* A temporary log file's path and its file:// URL. */
static void temp_log(char *path, size_t path_size, char *url, size_t url_size, const char *name)
{
    temp_path(path, path_size, name);
    snprintf(url, url_size, "file://%s", path);
}

static void test_file_log_read_back(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 2);
    char path[512], url[600];
    temp_log(path, sizeof path, url, sizeof url, "publish.lcmlog");
    rte_publisher *pub = create(url);
    assert_null(rte_publisher_lcm(pub));
    publish_all(pub, &s);
    publish_all(pub, &s);
    rte_publisher_destroy(pub);

    /* liblcm's reader */
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    assert_non_null(log);
    for (int n = 0; n < 10; n++) {
        lcm_eventlog_event_t *ev = lcm_eventlog_read_next_event(log);
        assert_non_null(ev);
        assert_int_equal(ev->eventnum, n);
        assert_true(ev->timestamp > 1500000000000000LL); /* wall clock, as lcm-logger */
        check_message(n % 5, ev->channel, ev->data, ev->datalen, &s);
        lcm_eventlog_free_event(ev);
    }
    assert_null(lcm_eventlog_read_next_event(log));
    lcm_eventlog_destroy(log);

    /* rtedge's reader */
    rte_lcm_log_reader r;
    char msg[256];
    assert_int_equal(rte_lcm_log_reader_open(&r, path, 65536, msg, sizeof msg), RTE_OK);
    rte_lcm_log_event ev;
    for (int n = 0; n < 10; n++) {
        assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_OK);
        assert_int_equal(ev.eventnum, n);
        check_message(n % 5, ev.channel, ev.data, ev.size, &s);
    }
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_END);
    rte_lcm_log_reader_close(&r);

    /* mode=a appends, numbering from 0 again as lcm's provider does */
    snprintf(url, sizeof url, "file://%s?mode=a", path);
    pub = create(url);
    assert_int_equal(rte_publish_status(pub, "STATUS", &s.status, msg, sizeof msg), RTE_OK);
    rte_publisher_destroy(pub);
    assert_int_equal(rte_lcm_log_reader_open(&r, path, 65536, msg, sizeof msg), RTE_OK);
    for (int n = 0; n < 11; n++)
        assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_OK);
    assert_string_equal(ev.channel, "STATUS");
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_END);
    rte_lcm_log_reader_close(&r);
    unlink(path);
}

static void test_limits_and_urls(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 3);
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    rte_publisher *pub = create("memq://");
    /* The buffer holds the largest message within the limits. */
    rtedge_lane_detection_t big = s.lane;
    rtedge_segment_t segs[16] = {{0}};
    big.segments = segs;
    big.nsegments = 16;
    assert_int_equal(rte_publish_lane(pub, "LANES", &big, msg, sizeof msg), RTE_OK);
    assert_true(rte_publisher_buffer_size(pub) >=
                (size_t)rtedge_lane_detection_t_encoded_size(&big));
    big.nsegments = 17;
    assert_int_equal(rte_publish_lane(pub, "LANES", &big, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    assert_non_null(strstr(msg, "17 segments"));
    big.nsegments = -1;
    assert_int_equal(rte_publish_lane(pub, "LANES", &big, msg, sizeof msg), RTE_ERR_TOO_LARGE);

    rtedge_grasp_detection_t g = s.grasp;
    g.nobjects = 5;
    assert_int_equal(rte_publish_grasp(pub, "GRASP", &g, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    g = s.grasp;
    g.header.roi_npoints = 9;
    assert_int_equal(rte_publish_grasp(pub, "GRASP", &g, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    g.header.roi_npoints = 0;
    g.header.source_id = NULL;
    assert_int_equal(rte_publish_grasp(pub, "GRASP", &g, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    char long_text[66];
    memset(long_text, 'a', 65);
    long_text[65] = '\0';
    rtedge_status_t st = s.status;
    st.source_id = long_text;
    assert_int_equal(rte_publish_status(pub, "STATUS", &st, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    long_text[64] = '\0';
    assert_int_equal(rte_publish_status(pub, "STATUS", &st, msg, sizeof msg), RTE_OK);
    rtedge_image_t img = s.image;
    img.size += 1;
    assert_int_equal(rte_publish_image(pub, "IMAGE", &img, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    assert_int_equal(rte_publish_status(pub, "", &s.status, msg, sizeof msg), RTE_ERR_ARGUMENT);
    char long_channel[70];
    memset(long_channel, 'C', 69);
    long_channel[69] = '\0';
    assert_int_equal(rte_publish_status(pub, long_channel, &s.status, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
    rte_publish_stats stats;
    rte_publisher_get_stats(pub, &stats);
    assert_int_equal(stats.messages, 2);
    assert_int_equal(stats.refused, 9);
    rte_publisher_destroy(pub);

    rte_publisher *p = NULL;
    assert_int_equal(rte_publisher_create(&p, "file://", &limits, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_publisher_create(&p, "file:///tmp/x?speed=2", &limits, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(
        rte_publisher_create(&p, "file:///nonexistent-dir/x.log", &limits, msg, sizeof msg),
        RTE_ERR_IO);
    assert_int_equal(rte_publisher_create(&p, "nosuch://", &limits, msg, sizeof msg), RTE_ERR_IO);
    rte_publish_limits bad = limits;
    bad.max_segments = -1;
    assert_int_equal(rte_publisher_create(&p, "memq://", &bad, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_null(p);
}

/* A log with a damaged sync word in the second event and cut short in the
 * fourth: the reader reports each and goes on. */
static void test_damaged_log(void **state)
{
    (void)state;
    samples s;
    samples_fill(&s, 4);
    char path[512], url[600], msg[256];
    temp_log(path, sizeof path, url, sizeof url, "damaged.lcmlog");
    rte_publisher *pub = create(url);
    for (int i = 0; i < 4; i++)
        assert_int_equal(rte_publish_status(pub, "STATUS", &s.status, msg, sizeof msg), RTE_OK);
    rte_publisher_destroy(pub);
    struct stat sb;
    assert_int_equal(stat(path, &sb), 0);
    long event = sb.st_size / 4;
    int fd = open(path, O_RDWR);
    assert_true(fd >= 0);
    assert_int_equal(pwrite(fd, "X", 1, event + 1), 1);
    assert_int_equal(ftruncate(fd, sb.st_size - 5), 0);
    close(fd);

    rte_lcm_log_reader r;
    rte_lcm_log_event ev;
    assert_int_equal(rte_lcm_log_reader_open(&r, path, 65536, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_OK);
    assert_int_equal(ev.eventnum, 0);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_CORRUPT);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_OK);
    assert_int_equal(ev.eventnum, 2);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_TRUNCATED);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_END);
    rte_lcm_log_reader_close(&r);

    /* An event larger than the reader's buffer is skipped whole. */
    assert_int_equal(rte_lcm_log_reader_open(&r, path, 16, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_CORRUPT);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_ERR_TOO_LARGE);
    rte_lcm_log_reader_close(&r);
    unlink(path);
}

/* ---- heap calls per message ---- */

static void skip_without_heapcount(void)
{
    if (!heapcount_active()) {
        print_message("heapcount is not interposed (sanitizer build?): not counted\n");
        skip();
    }
}

/* Heap calls made by `rounds` rounds of publish_all after a first one. */
static heapcount_counts count_publishing(rte_publisher *pub, const samples *s, int rounds)
{
    publish_all(pub, s);
    heapcount_reset();
    for (int i = 0; i < rounds; i++)
        publish_all(pub, s);
    heapcount_counts c;
    heapcount_get(&c);
    return c;
}

static void test_heap_calls_file(void **state)
{
    (void)state;
    skip_without_heapcount();
    samples s;
    samples_fill(&s, 5);
    char path[512], url[600];
    temp_log(path, sizeof path, url, sizeof url, "heap.lcmlog");
    rte_publisher *pub = create(url);
    heapcount_counts c = count_publishing(pub, &s, 20);
    assert_int_equal(heapcount_calls(&c), 0);
    rte_publisher_destroy(pub);

    /* What liblcm's own file provider does instead: a calloc and a free
     * per message (the event it builds). */
    snprintf(url, sizeof url, "file://%s?mode=w", path);
    lcm_t *lcm = lcm_create(url);
    assert_non_null(lcm);
    uint8_t buf[64] = {0};
    lcm_publish(lcm, "X", buf, sizeof buf);
    heapcount_reset();
    for (int i = 0; i < 10; i++)
        lcm_publish(lcm, "X", buf, sizeof buf);
    heapcount_get(&c);
    print_message("liblcm file:// provider, 10 messages: %llu calloc, %llu malloc, %llu free\n",
                  (unsigned long long)c.calloc_calls, (unsigned long long)c.malloc_calls,
                  (unsigned long long)c.free_calls);
    assert_int_equal(c.calloc_calls, 10);
    assert_int_equal(c.free_calls, 10);
    lcm_destroy(lcm);

    /* Reading: lcm_eventlog allocates every event it returns; rtedge's
     * reader (the lcm-log source's) reads into its own buffer. */
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    assert_non_null(log);
    lcm_eventlog_free_event(lcm_eventlog_read_next_event(log));
    heapcount_reset();
    for (int i = 0; i < 5; i++)
        lcm_eventlog_free_event(lcm_eventlog_read_next_event(log));
    heapcount_get(&c);
    print_message("lcm_eventlog_read_next_event, 5 events: %llu calloc, %llu free\n",
                  (unsigned long long)c.calloc_calls, (unsigned long long)c.free_calls);
    assert_true(heapcount_allocations(&c) >= 5);
    lcm_eventlog_destroy(log);
    rte_lcm_log_reader r;
    rte_lcm_log_event ev;
    char msg[256];
    assert_int_equal(rte_lcm_log_reader_open(&r, path, 65536, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_OK);
    heapcount_reset();
    for (int i = 0; i < 5; i++)
        assert_int_equal(rte_lcm_log_read(&r, &ev, msg, sizeof msg), RTE_OK);
    heapcount_get(&c);
    assert_int_equal(heapcount_calls(&c), 0);
    rte_lcm_log_reader_close(&r);
    unlink(path);
}

static void test_heap_calls_memq(void **state)
{
    (void)state;
    skip_without_heapcount();
    samples s;
    samples_fill(&s, 6);
    rte_publisher *pub = create("memq://");
    heapcount_counts c = count_publishing(pub, &s, 20);
    assert_int_equal(heapcount_calls(&c), 0);

    /* With a subscriber in the process, memq copies each message into its
     * queue (one malloc for the buffer, and more for the queue entry) and
     * lcm_handle frees them. */
    lcm_t *lcm = rte_publisher_lcm(pub);
    lcm_subscription_t *sub = lcm_subscribe(lcm, "STATUS", on_message, NULL);
    char msg[RTE_PUBLISH_MESSAGE_SIZE];
    assert_int_equal(rte_publish_status(pub, "STATUS", &s.status, msg, sizeof msg), RTE_OK);
    lcm_handle_timeout(lcm, 100);
    heapcount_reset();
    assert_int_equal(rte_publish_status(pub, "STATUS", &s.status, msg, sizeof msg), RTE_OK);
    heapcount_get(&c);
    print_message("memq:// with a subscriber, one message: %llu malloc, %llu calloc, "
                  "%llu realloc, %llu free\n",
                  (unsigned long long)c.malloc_calls, (unsigned long long)c.calloc_calls,
                  (unsigned long long)c.realloc_calls, (unsigned long long)c.free_calls);
    assert_true(heapcount_allocations(&c) > 0);
    heapcount_reset();
    lcm_handle_timeout(lcm, 100);
    heapcount_get(&c);
    print_message("memq:// lcm_handle of it: %llu malloc, %llu free\n",
                  (unsigned long long)c.malloc_calls, (unsigned long long)c.free_calls);
    assert_true(c.free_calls > 0);
    lcm_unsubscribe(lcm, sub);
    rte_publisher_destroy(pub);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memq_round_trip), cmocka_unit_test(test_file_log_read_back),
        cmocka_unit_test(test_limits_and_urls), cmocka_unit_test(test_damaged_log),
        cmocka_unit_test(test_heap_calls_file), cmocka_unit_test(test_heap_calls_memq),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
