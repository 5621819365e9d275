/* Runs inside the test VM against the kernel's vivid driver, through the
 * V4L2 source: capture, sequence gaps, bad buffers, fatal streaming errors,
 * a failing STREAMON on reopening, and a disconnect with the module
 * reloaded. Prints one "RTE-VM PASS|FAIL name: detail" line per test (the
 * host parses the console log).
 *
 *   vm_vivid DEVICE UNLOAD_COMMAND LOAD_COMMAND
 * DEVICE: the vivid capture node; the commands unload and load vivid. */
#include <linux/videodev2.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rtedge/v4l2_source.h"
#include "core/clock.h"

static int failures;

static void result(int ok, const char *name, const char *detail)
{
    printf("RTE-VM %s %s: %s\n", ok ? "PASS" : "FAIL", name, detail);
    fflush(stdout);
    failures += !ok;
}

static rte_v4l2_config config(const char *device, uint32_t fourcc)
{
    rte_v4l2_config c;
    memset(&c, 0, sizeof(c));
    c.device = device;
    c.fourcc = fourcc;
    c.width = 640;
    c.height = 480;
    c.fps = 30;
    c.buffers = 4;
    c.reconnect_min_ms = 50;
    c.reconnect_max_ms = 400;
    return c;
}

/* n frames: the right format and size, strictly increasing timestamps and
 * sequence numbers, timestamps on CLOCK_MONOTONIC (not in the future, not
 * older than two seconds), pixels that are not all the same. */
static int capture(rte_source *src, int n, char *why, size_t why_size)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    int64_t prev_ns = 0;
    uint64_t prev_seq = 0;
    for (int i = 0; i < n; i++) {
        rte_source_frame f;
        rte_status st = rte_source_next(src, &f, 3000, msg, sizeof(msg));
        if (st != RTE_OK) {
            snprintf(why, why_size, "frame %d: %s (%s)", i, rte_status_message(st), msg);
            return 0;
        }
        int64_t now = rte_clock_now_ns();
        if (f.frame.format != src->format || f.frame.width != 640 || f.frame.height != 480 ||
            f.frame.stride[0] < 640) {
            snprintf(why, why_size, "frame %d: format %d %dx%d stride %d", i, f.frame.format,
                     f.frame.width, f.frame.height, f.frame.stride[0]);
            return 0;
        }
        /* vivid stamps the end of the exposure from its schedule, up to
         * 0.9 frame periods ahead of the clock; the source takes the time
         * of dequeueing then. (Another clock would be off by far more than
         * the 2 s allowed behind.) */
        if (f.capture_ns > now || now - f.capture_ns > 2000000000) {
            snprintf(why, why_size, "frame %d: capture time %lld ns, now %lld ns", i,
                     (long long)f.capture_ns, (long long)now);
            return 0;
        }
        /* vivid's thread repeats a sequence number when it wakes twice in
         * one frame period (seen under a loaded TCG guest): equal is a new
         * frame, smaller is not; either way nothing counts as dropped. */
        if (i > 0 && (f.capture_ns <= prev_ns || f.sequence < prev_seq ||
                      f.dropped != (f.sequence > prev_seq ? f.sequence - prev_seq - 1 : 0))) {
            snprintf(why, why_size,
                     "frame %d: time %lld after %lld, sequence %llu after %llu, dropped %u", i,
                     (long long)f.capture_ns, (long long)prev_ns, (unsigned long long)f.sequence,
                     (unsigned long long)prev_seq, (unsigned)f.dropped);
            return 0;
        }
        /* What the daemon does next: the frame to grey. */
        static uint8_t grey_buf[640 * 480];
        rte_image_u8 grey = {640, 480, 640, grey_buf};
        st = rte_frame_to_gray(&f.frame, &grey);
        if (st != RTE_OK) {
            snprintf(why, why_size, "frame %d: rte_frame_to_gray: %s", i, rte_status_message(st));
            return 0;
        }
        const uint8_t *row = grey_buf + 640 * 240;
        int varied = 0;
        for (int x = 1; x < 640 && !varied; x++)
            varied = row[x] != row[0];
        if (!varied) {
            snprintf(why, why_size, "frame %d: a constant grey row", i);
            return 0;
        }
        prev_ns = f.capture_ns;
        prev_seq = f.sequence;
    }
    return 1;
}

static void test_capture(const char *name, const char *device, uint32_t fourcc, int frames)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE], detail[512];
    rte_v4l2_config c = config(device, fourcc);
    rte_v4l2_info info;
    rte_source src;
    rte_status st = rte_v4l2_source_open(&src, &c, &info, msg, sizeof(msg));
    if (st != RTE_OK) {
        snprintf(detail, sizeof(detail), "open: %s (%s)", rte_status_message(st), msg);
        result(0, name, detail);
        return;
    }
    int64_t t0 = rte_clock_now_ns();
    char why[512] = "";
    int ok = capture(&src, frames, why, sizeof(why));
    int64_t ms = (rte_clock_now_ns() - t0) / 1000000;
    rte_source_stats stats;
    rte_source_get_stats(&src, &stats);
    ok = ok && info.fourcc == fourcc && info.timestamps_monotonic &&
         stats.frames == (uint64_t)frames;
    snprintf(detail, sizeof(detail),
             "%s; %d frames in %lld ms, driver drops %llu, skipped %llu, monotonic %d; %s", msg,
             frames, (long long)ms, (unsigned long long)stats.driver_drops,
             (unsigned long long)stats.skipped, info.timestamps_monotonic, why);
    result(ok, name, detail);
    rte_source_close(&src);
}

static int open_source(rte_source *src, const char *device, const char *name)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE], detail[512];
    rte_v4l2_config c = config(device, V4L2_PIX_FMT_YUYV);
    rte_status st = rte_v4l2_source_open(src, &c, NULL, msg, sizeof(msg));
    if (st != RTE_OK) {
        snprintf(detail, sizeof(detail), "open: %s (%s)", rte_status_message(st), msg);
        result(0, name, detail);
        return 0;
    }
    return 1;
}

static int press(rte_source *src, const char *control, int32_t value, const char *name)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE], detail[512];
    rte_status st = rte_v4l2_source_set_control(src, control, value, msg, sizeof(msg));
    if (st != RTE_OK) {
        snprintf(detail, sizeof(detail), "control %s: %s (%s)", control, rte_status_message(st),
                 msg);
        result(0, name, detail);
        return 0;
    }
    return 1;
}

/* "Percentage of Dropped Buffers": vivid skips frames but counts them in
 * the sequence; the source must count the gaps as driver drops. */
static void test_drops(const char *device)
{
    const char *name = "vivid-drops";
    rte_source src;
    if (!open_source(&src, device, name))
        return;
    char msg[RTE_SOURCE_MESSAGE_SIZE], detail[512];
    uint64_t gaps = 0;
    int frames = 0;
    /* The name as v4l2-ctl spells it: matching ignores case and punctuation. */
    if (press(&src, "percentage_of_dropped_buffers", 50, name)) {
        for (int i = 0; i < 30; i++) {
            rte_source_frame f;
            if (rte_source_next(&src, &f, 3000, msg, sizeof(msg)) != RTE_OK)
                break;
            gaps += f.dropped;
            frames++;
        }
        rte_source_stats stats;
        rte_source_get_stats(&src, &stats);
        snprintf(detail, sizeof(detail),
                 "%d frames, driver drops %llu, skipped %llu, gaps seen %llu", frames,
                 (unsigned long long)stats.driver_drops, (unsigned long long)stats.skipped,
                 (unsigned long long)gaps);
        /* Gaps before the first delivered frame are not in any frame's
         * `dropped`, hence only > 0. */
        result(frames == 30 && stats.driver_drops > 0 && gaps > 0, name, detail);
        press(&src, "Percentage of Dropped Buffers", 0, name);
    }
    rte_source_close(&src);
}

/* "Inject V4L2_BUF_FLAG_ERROR": one buffer comes back marked bad; the
 * source skips and counts it and goes on. */
static void test_buf_error(const char *device)
{
    const char *name = "vivid-buf-error";
    rte_source src;
    if (!open_source(&src, device, name))
        return;
    char msg[RTE_SOURCE_MESSAGE_SIZE], detail[512], why[256] = "";
    int ok = 0;
    if (press(&src, "Inject V4L2_BUF_FLAG_ERROR", 0, name)) {
        int corrupt = 0, good = 0;
        for (int i = 0; i < 20 && good < 10; i++) {
            rte_source_frame f;
            rte_status st = rte_source_next(&src, &f, 3000, msg, sizeof(msg));
            if (st == RTE_ERR_CORRUPT)
                corrupt++;
            else if (st == RTE_OK)
                good++;
            else
                break;
        }
        rte_source_stats stats;
        rte_source_get_stats(&src, &stats);
        /* The bad buffer may come with a good newer one in the same next(). */
        ok = stats.bad_frames == 1 && good == 10 && stats.state == RTE_SOURCE_STREAMING &&
             capture(&src, 10, why, sizeof(why));
        snprintf(detail, sizeof(detail), "bad frames %llu, CORRUPT returned %d, good %d; %s",
                 (unsigned long long)stats.bad_frames, corrupt, good, why);
        result(ok, name, detail);
    }
    rte_source_close(&src);
}

/* Calls next() until frames come again; returns the number of calls and
 * counts RTE_ERR_DEVICE returns. */
static int recover(rte_source *src, int max_calls, int *device_errors, char *last, size_t size)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    for (int i = 1; i <= max_calls; i++) {
        rte_source_frame f;
        rte_status st = rte_source_next(src, &f, 500, msg, sizeof(msg));
        if (st == RTE_ERR_DEVICE) {
            ++*device_errors;
            snprintf(last, size, "%s", msg);
        }
        if (st == RTE_OK)
            return i;
    }
    return 0;
}

/* "Inject Fatal Streaming Error" (vb2_queue_error: POLLERR, DQBUF EIO);
 * with `streamon_too`, also "Inject VIDIOC_STREAMON Error" first so the
 * first reopening fails and the backoff must retry. */
static void test_fatal(const char *device, int streamon_too)
{
    const char *name = streamon_too ? "vivid-streamon-error" : "vivid-fatal-error";
    rte_source src;
    if (!open_source(&src, device, name))
        return;
    char detail[1024], last[RTE_SOURCE_MESSAGE_SIZE] = "", why[256] = "";
    if ((!streamon_too || press(&src, "Inject VIDIOC_STREAMON Error", 0, name)) &&
        press(&src, "Inject Fatal Streaming Error", 0, name)) {
        int errors = 0;
        int calls = recover(&src, 40, &errors, last, sizeof(last));
        rte_source_stats stats;
        rte_source_get_stats(&src, &stats);
        int ok = calls > 0 && stats.reconnects == 1 && stats.state == RTE_SOURCE_STREAMING &&
                 errors >= (streamon_too ? 2 : 1) && capture(&src, 10, why, sizeof(why));
        snprintf(
            detail, sizeof(detail),
            "back after %d calls, %d device errors, reconnects %llu, errors %llu; last: %s; %s",
            calls, errors, (unsigned long long)stats.reconnects, (unsigned long long)stats.errors,
            last, why);
        result(ok, name, detail);
    }
    rte_source_close(&src);
}

/* "Disconnect": vivid 6.1 marks its nodes unregistered (ENODEV, POLLERR)
 * and registers them again when the last file handle is closed. The
 * source must report the loss, close its fd and so get the device back. */
static void test_disconnect(const char *device)
{
    const char *name = "vivid-disconnect";
    rte_source src;
    if (!open_source(&src, device, name))
        return;
    char detail[1536], last[RTE_SOURCE_MESSAGE_SIZE] = "", why[512] = "";
    if (press(&src, "Disconnect", 0, name)) {
        int errors = 0;
        int calls = recover(&src, 40, &errors, last, sizeof(last));
        rte_source_stats stats;
        rte_source_get_stats(&src, &stats);
        int ok = calls > 1 && errors >= 1 && stats.reconnects == 1 &&
                 stats.state == RTE_SOURCE_STREAMING && capture(&src, 10, why, sizeof(why));
        snprintf(detail, sizeof(detail),
                 "back after %d calls, %d device errors, reconnects %llu; last: %s; %s", calls,
                 errors, (unsigned long long)stats.reconnects, last, why);
        result(ok, name, detail);
    }
    rte_source_close(&src);
}

/* The device goes away for good: after the disconnect the module is
 * unloaded (possible because the source closed its fd). The source must
 * stay RECONNECTING, retrying with backoff, and come back when the module
 * is loaded again. Opened by bus name, as a reloaded driver may get
 * another node. */
static void test_reload(const char *unload, const char *load)
{
    const char *name = "vivid-reload";
    rte_source src;
    if (!open_source(&src, "platform:vivid-000", name))
        return;
    char msg[RTE_SOURCE_MESSAGE_SIZE], detail[1536], last[RTE_SOURCE_MESSAGE_SIZE] = "",
                                                     why[512] = "";
    if (press(&src, "Disconnect", 0, name)) {
        rte_source_frame f;
        rte_status first = rte_source_next(&src, &f, 1000, msg, sizeof(msg));
        int unload_status = system(unload);
        int errors = first == RTE_ERR_DEVICE, frames_while_gone = 0;
        for (int i = 0; i < 8; i++) {
            rte_status st = rte_source_next(&src, &f, 200, msg, sizeof(msg));
            errors += st == RTE_ERR_DEVICE;
            frames_while_gone += st == RTE_OK;
            if (st == RTE_ERR_DEVICE)
                snprintf(last, sizeof(last), "%s", msg);
        }
        rte_source_stats gone;
        rte_source_get_stats(&src, &gone);
        int load_status = system(load);
        int calls = recover(&src, 40, &errors, msg, sizeof(msg));
        rte_source_stats stats;
        rte_source_get_stats(&src, &stats);
        int ok = first == RTE_ERR_DEVICE && unload_status == 0 &&
                 gone.state == RTE_SOURCE_RECONNECTING && errors >= 3 && frames_while_gone == 0 &&
                 load_status == 0 && calls > 0 && stats.reconnects == 1 &&
                 stats.state == RTE_SOURCE_STREAMING && capture(&src, 10, why, sizeof(why));
        snprintf(detail, sizeof(detail),
                 "first: %s; unload %d; while gone: state %d, %d device errors, last: %s; "
                 "load %d; back after %d calls, reconnects %llu; %s",
                 rte_status_message(first), unload_status, gone.state, errors, last, load_status,
                 calls, (unsigned long long)stats.reconnects, why);
        result(ok, name, detail);
    }
    rte_source_close(&src);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: vm_vivid DEVICE UNLOAD_COMMAND LOAD_COMMAND\n");
        return 2;
    }
    const char *device = argv[1];
    test_capture("vivid-yuyv", device, V4L2_PIX_FMT_YUYV, 100);
    test_capture("vivid-grey", "vivid", V4L2_PIX_FMT_GREY, 100); /* by card name */
    test_capture("vivid-uyvy", device, V4L2_PIX_FMT_UYVY, 20);
    test_capture("vivid-nv12", device, V4L2_PIX_FMT_NV12, 20);
    test_drops(device);
    test_buf_error(device);
    test_fatal(device, 0);
    test_fatal(device, 1);
    test_disconnect(device);
    test_reload(argv[2], argv[3]);
    return failures ? 1 : 0;
}
