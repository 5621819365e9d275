/* Runs inside the test VM against vimc through the libcamera source:
 * opens camera 0 at 640x480 (vimc adjusts the width), captures frames and
 * checks sizes, sequence numbers and CLOCK_MONOTONIC timestamps, then
 * opens it again by id after a clean stop. Prints
 * "RTE-VM PASS|FAIL libcamera-vimc: detail". */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "rtedge/libcamera_source.h"
#include "core/clock.h"

#define FRAMES 20

int main(void)
{
    char msg[RTE_SOURCE_MESSAGE_SIZE], why[512] = "";
    rte_libcamera_config cfg;
    memset(&cfg, 0, sizeof(cfg));
    cfg.index = 0;
    cfg.format = RTE_PIXEL_RGB24; /* vimc's BGR888 */
    cfg.width = 640;
    cfg.height = 480;
    cfg.buffers = 4;
    rte_libcamera_info info;
    rte_source src;
    rte_status st = rte_libcamera_source_open(&src, &cfg, &info, msg, sizeof(msg));
    if (st != RTE_OK) {
        printf("RTE-VM FAIL libcamera-vimc: open: %s (%s)\n", rte_status_message(st), msg);
        return 1;
    }
    printf("libcamera source: %s\n", msg);
    int64_t t0 = rte_clock_now_ns(), prev_ns = 0;
    uint64_t prev_seq = 0;
    int n = 0, varied = 0;
    for (; n < FRAMES; n++) {
        rte_source_frame f;
        st = rte_source_next(&src, &f, 5000, msg, sizeof(msg));
        if (st != RTE_OK) {
            snprintf(why, sizeof(why), "frame %d: %s (%s)", n, rte_status_message(st), msg);
            break;
        }
        int64_t now = rte_clock_now_ns();
        if (f.frame.width != info.width || f.frame.height != info.height ||
            f.frame.format != RTE_PIXEL_RGB24 || f.frame.stride[0] < 3 * f.frame.width) {
            snprintf(why, sizeof(why), "frame %d: format %d %dx%d stride %d", n, f.frame.format,
                     f.frame.width, f.frame.height, f.frame.stride[0]);
            break;
        }
        if (f.capture_ns > now || now - f.capture_ns > 2000000000 ||
            (n > 0 && (f.capture_ns <= prev_ns || f.sequence <= prev_seq))) {
            snprintf(why, sizeof(why),
                     "frame %d: time %lld (now %lld, previous %lld), sequence %llu after %llu", n,
                     (long long)f.capture_ns, (long long)now, (long long)prev_ns,
                     (unsigned long long)f.sequence, (unsigned long long)prev_seq);
            break;
        }
        /* What the daemon does next: the frame to grey. */
        static uint8_t grey_buf[1920 * 1080];
        rte_image_u8 grey = {f.frame.width, f.frame.height, f.frame.width, grey_buf};
        st = (size_t)f.frame.width * (size_t)f.frame.height > sizeof(grey_buf)
                 ? RTE_ERR_TOO_LARGE
                 : rte_frame_to_gray(&f.frame, &grey);
        if (st != RTE_OK) {
            snprintf(why, sizeof(why), "frame %d: rte_frame_to_gray: %s", n,
                     rte_status_message(st));
            break;
        }
        const uint8_t *row = grey_buf + (size_t)grey.stride * (size_t)(grey.height / 2);
        for (int x = 1; x < grey.width && !varied; x++)
            varied = row[x] != row[0];
        prev_ns = f.capture_ns;
        prev_seq = f.sequence;
    }
    int64_t ms = (rte_clock_now_ns() - t0) / 1000000;
    rte_source_stats stats;
    rte_source_get_stats(&src, &stats);
    rte_source_close(&src);

    /* A clean stop releases the camera: it opens again at once, by id. */
    cfg.camera = info.id;
    st = rte_libcamera_source_open(&src, &cfg, NULL, msg, sizeof(msg));
    int reopened = st == RTE_OK;
    if (reopened) {
        rte_source_frame f;
        for (int i = 0; i < 3 && reopened; i++)
            reopened = rte_source_next(&src, &f, 5000, msg, sizeof(msg)) == RTE_OK;
        rte_source_close(&src);
    }
    if (!reopened && !why[0])
        snprintf(why, sizeof(why), "reopening: %s", msg);
    int ok = n == FRAMES && varied && info.adjusted && stats.frames == FRAMES && reopened;
    printf("RTE-VM %s libcamera-vimc: %s %dx%d stride %d, adjusted %d; %d frames in %lld ms, "
           "driver drops %llu, skipped %llu, varied %d, reopened %d; %s\n",
           ok ? "PASS" : "FAIL", info.id, info.width, info.height, info.stride, info.adjusted, n,
           (long long)ms, (unsigned long long)stats.driver_drops, (unsigned long long)stats.skipped,
           varied, reopened, why);
    return ok ? 0 : 1;
}
