/* The debug overlay stream: the JPEG encoder on its own (decoded again by
 * libturbojpeg, sizes, qualities, errors, no heap call per image) and in
 * the daemon (image_t of MJPEG on debug.channel at debug.scale, the layers
 * it is asked for, debug.rate_hz, changes over params_t, off by default).
 *   test_debug_stream BUILD_DIR   (BUILD_DIR holds road_straight.y4m) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>
#include <lcm/lcm.h>
#include <turbojpeg.h>

#include "config.h"
#include "daemon.h"
#include "daemon_fixtures.h"
#include "heapcount.h"
#include "io/jpeg_encoder.h"
#include "rtedge_image_t.h"
#include "rtedge_param_t.h"
#include "rtedge_params_t.h"

static const char *build_dir;

/* A BGR test picture: gradients and a few sharp squares. */
static void picture(uint8_t *bgr, int32_t w, int32_t h, int32_t stride)
{
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            uint8_t *p = bgr + (size_t)y * (size_t)stride + 3 * (size_t)x;
            const bool square = ((x / 24) + (y / 24)) % 5 == 0;
            p[0] = (uint8_t)(square ? 230 : x * 255 / (w > 1 ? w - 1 : 1));
            p[1] = (uint8_t)(square ? 20 : y * 255 / (h > 1 ? h - 1 : 1));
            p[2] = (uint8_t)((x + y) & 0xff);
        }
}

/* Decodes a JPEG to BGR with libturbojpeg (another decoder than the
 * encoder's library); returns the PSNR against ref in dB. */
static double decoded_psnr(const uint8_t *jpeg, size_t size, const uint8_t *ref, int32_t w,
                           int32_t h, int32_t stride)
{
    tjhandle tj = tjInitDecompress();
    int jw, jh, sub, cs;
    assert_int_equal(tjDecompressHeader3(tj, jpeg, (unsigned long)size, &jw, &jh, &sub, &cs), 0);
    assert_int_equal(jw, w);
    assert_int_equal(jh, h);
    assert_int_equal(sub, TJSAMP_420);
    uint8_t *out = malloc((size_t)w * (size_t)h * 3);
    assert_int_equal(tjDecompress2(tj, jpeg, (unsigned long)size, out, w, w * 3, h, TJPF_BGR, 0),
                     0);
    tjDestroy(tj);
    double se = 0;
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < 3 * w; x++) {
            double e = (double)out[(size_t)y * 3 * (size_t)w + (size_t)x] -
                       ref[(size_t)y * (size_t)stride + (size_t)x];
            se += e * e;
        }
    free(out);
    double mse = se / ((double)w * h * 3);
    return mse == 0 ? 99 : 10 * log10(255.0 * 255.0 / mse);
}

/* The JPEG libturbojpeg's TurboJPEG API makes of the same image. */
static void assert_tj_same(const uint8_t *jpeg, size_t size, const uint8_t *bgr, int32_t w,
                           int32_t h, int32_t stride, int quality)
{
    tjhandle tj = tjInitCompress();
    unsigned char *ref = NULL;
    unsigned long ref_size = 0;
    assert_int_equal(tjCompress2(tj, bgr, w, stride, h, TJPF_BGR, &ref, &ref_size, TJSAMP_420,
                                 quality, TJFLAG_ACCURATEDCT),
                     0);
    assert_int_equal(ref_size, size);
    assert_memory_equal(ref, jpeg, size);
    tjFree(ref);
    tjDestroy(tj);
}

static void test_encoder_round_trip(void **state)
{
    rte_jpeg_encoder *enc;
    char msg[256];
    assert_int_equal(rte_jpeg_encoder_create(&enc, 640, 360, 90, msg, sizeof msg), RTE_OK);
    rte_jpeg_encoder_stats s0;
    rte_jpeg_encoder_get_stats(enc, &s0);
    assert_true(s0.arena_peak_bytes <= s0.arena_bytes);
    assert_true(s0.output_capacity >= 640u * 360u * 3u);
    /* Sizes from one pixel to the largest, odd ones and a padded stride. */
    const int32_t sizes[][2] = {{1, 1}, {17, 9}, {33, 200}, {640, 360}, {639, 1}, {320, 180}};
    static uint8_t bgr[(640 + 16) * 360 * 3];
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        const int32_t w = sizes[i][0], h = sizes[i][1], stride = w * 3 + 48;
        picture(bgr, w, h, stride);
        rte_image_u8c3 img = {w, h, stride, bgr};
        const uint8_t *jpeg;
        size_t size;
        assert_int_equal(rte_jpeg_encode_bgr(enc, &img, &jpeg, &size, msg, sizeof msg), RTE_OK);
        double psnr = decoded_psnr(jpeg, size, bgr, w, h, stride);
        print_message("%dx%d: %zu bytes, PSNR %.1f dB\n", w, h, size, psnr);
        /* 4:2:0 at quality 90 on sharp coloured squares and a sawtooth */
        assert_true(psnr > 28);
        assert_tj_same(jpeg, size, bgr, w, h, stride, 90);
    }
    /* Quality: fewer bytes at 10 than at 95, and at each the same bytes as
     * libturbojpeg's own API writes (tjCompress2, 4:2:0, same library). */
    picture(bgr, 320, 180, 960);
    rte_image_u8c3 img = {320, 180, 960, bgr};
    const uint8_t *jpeg;
    size_t low, high;
    assert_int_equal(rte_jpeg_encoder_set_quality(enc, 10), RTE_OK);
    assert_int_equal(rte_jpeg_encode_bgr(enc, &img, &jpeg, &low, msg, sizeof msg), RTE_OK);
    assert_tj_same(jpeg, low, bgr, 320, 180, 960, 10);
    assert_int_equal(rte_jpeg_encoder_set_quality(enc, 95), RTE_OK);
    assert_int_equal(rte_jpeg_encode_bgr(enc, &img, &jpeg, &high, msg, sizeof msg), RTE_OK);
    assert_tj_same(jpeg, high, bgr, 320, 180, 960, 95);
    assert_true(low * 2 < high);
    /* The permanent arena does not grow with images. */
    rte_jpeg_encoder_stats s1;
    rte_jpeg_encoder_get_stats(enc, &s1);
    assert_int_equal(s1.permanent_bytes, s0.permanent_bytes);
    assert_true(s1.arena_peak_bytes <= s1.arena_bytes);
    /* Refused: larger than the maximum, a short stride, bad qualities. */
    rte_image_u8c3 big = {641, 10, 641 * 3, bgr};
    assert_int_equal(rte_jpeg_encode_bgr(enc, &big, &jpeg, &low, msg, sizeof msg), RTE_ERR_SIZE);
    assert_non_null(strstr(msg, "641x10"));
    rte_image_u8c3 narrow = {100, 10, 299, bgr};
    assert_int_equal(rte_jpeg_encode_bgr(enc, &narrow, &jpeg, &low, msg, sizeof msg), RTE_ERR_SIZE);
    assert_int_equal(rte_jpeg_encoder_set_quality(enc, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_jpeg_encoder_set_quality(enc, 101), RTE_ERR_ARGUMENT);
    rte_jpeg_encoder_destroy(enc);
    rte_jpeg_encoder *bad;
    assert_int_equal(rte_jpeg_encoder_create(&bad, 4, 360, 90, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_jpeg_encoder_create(&bad, 64, 64, 0, msg, sizeof msg), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_jpeg_encoder_create(&bad, 20000, 64, 80, msg, sizeof msg),
                     RTE_ERR_ARGUMENT);
}

static void test_encoder_no_heap(void **state)
{
    if (!heapcount_active())
        skip();
    rte_jpeg_encoder *enc;
    char msg[256];
    assert_int_equal(rte_jpeg_encoder_create(&enc, 1280, 720, 80, msg, sizeof msg), RTE_OK);
    static uint8_t bgr[1280 * 720 * 3];
    picture(bgr, 1280, 720, 1280 * 3);
    heapcount_reset();
    size_t total = 0;
    for (int i = 0; i < 60; i++) {
        /* sizes change as debug.scale would change them */
        const int32_t w = 1280 - 37 * (i % 20), h = 720 - 21 * (i % 20);
        rte_image_u8c3 img = {w, h, 1280 * 3, bgr};
        const uint8_t *jpeg;
        size_t size;
        if (i == 30)
            assert_int_equal(rte_jpeg_encoder_set_quality(enc, 50), RTE_OK);
        assert_int_equal(rte_jpeg_encode_bgr(enc, &img, &jpeg, &size, msg, sizeof msg), RTE_OK);
        total += size;
    }
    heapcount_counts hc;
    heapcount_get(&hc);
    print_message("60 images up to 1280x720, %zu bytes of JPEG: %llu heap calls\n", total,
                  (unsigned long long)heapcount_calls(&hc));
    assert_int_equal(heapcount_calls(&hc), 0);
    rte_jpeg_encoder_destroy(enc);
}

/* ---- the daemon's stream ---- */

typedef struct debug_seen {
    int count;
    int32_t width, height, pixelformat;
    size_t size;
    uint8_t *bgr; /* the last overlay, decoded */
} debug_seen;

static void on_debug(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    debug_seen *s = user;
    rtedge_image_t m;
    assert_true(rtedge_image_t_decode(rb->data, 0, (int)rb->data_size, &m) > 0);
    s->count++;
    s->width = m.width;
    s->height = m.height;
    s->pixelformat = m.pixelformat;
    s->size = (size_t)m.size;
    free(s->bgr);
    s->bgr = malloc((size_t)m.width * (size_t)m.height * 3);
    tjhandle tj = tjInitDecompress();
    assert_int_equal(tjDecompress2(tj, m.data, (unsigned long)m.size, s->bgr, m.width, m.width * 3,
                                   m.height, TJPF_BGR, 0),
                     0);
    tjDestroy(tj);
    rtedge_image_t_decode_cleanup(&m);
}

/* Pixels that are clearly coloured (a drawn layer on a grey frame):
 * saturated blue, red, or yellow-ish. */
static int coloured(const debug_seen *s, int which)
{
    int n = 0;
    for (int32_t i = 0; i < s->width * s->height; i++) {
        const uint8_t *p = s->bgr + 3 * (size_t)i;
        const int b = p[0], g = p[1], r = p[2];
        n += which == 0   ? (b > 180 && r < 90 && g < 90)   /* blue: left lane */
             : which == 1 ? (r > 180 && b < 90 && g < 90)   /* red: right lane, grasp point */
                          : (r > 180 && g > 180 && b < 90); /* yellow: ROI, closing line */
    }
    return n;
}

static void drain(lcm_t *lcm)
{
    while (lcm_handle_timeout(lcm, 0) > 0)
        ;
}

/* One params_t, handled at the next step. */
static void send_param(rted_daemon *d, const rtedge_param_t *p)
{
    rtedge_params_t m = {.request_id = 1, .nparams = 1, .params = (rtedge_param_t *)p};
    uint8_t buf[1024];
    int len = rtedge_params_t_encode(buf, 0, sizeof buf, &m);
    assert_true(len > 0);
    lcm_publish(rted_daemon_lcm(d), "RTEDGE_PARAMS", buf, (unsigned)len);
}

static void set_text(rted_daemon *d, const char *name, const char *value)
{
    rtedge_param_t p = {
        .name = (char *)name, .kind = RTEDGE_PARAM_T_KIND_TEXT, .text_value = (char *)value};
    send_param(d, &p);
}

static void set_real(rted_daemon *d, const char *name, double value)
{
    rtedge_param_t p = {.name = (char *)name,
                        .kind = RTEDGE_PARAM_T_KIND_REAL,
                        .real_value = value,
                        .text_value = ""};
    send_param(d, &p);
}

static void debug_config(rted_config *c, const char *y4m, double scale, const char *layers)
{
    base_config(c, y4m, "memq://");
    c->loop = true;
    c->debug_enabled = true;
    c->debug_scale = scale;
    c->debug_rate_hz = 100;
    c->params_enabled = true;
    snprintf(c->debug_layers, sizeof c->debug_layers, "%s", layers);
}

/* A daemon opened on c with a subscriber to its debug channel. */
typedef struct watched {
    rted_daemon *d;
    lcm_t *lcm;
    lcm_subscription_t *sub;
    debug_seen s;
} watched;

static void watch(watched *w, const rted_config *c)
{
    memset(w, 0, sizeof *w);
    w->d = open_daemon(c, NULL);
    w->lcm = rted_daemon_lcm(w->d);
    w->sub = lcm_subscribe(w->lcm, "RTEDGE_DEBUG", on_debug, &w->s);
}

static void unwatch(watched *w)
{
    lcm_unsubscribe(w->lcm, w->sub);
    rted_daemon_close(w->d);
    free(w->s.bgr);
}

/* A step after the rate's period, so that its frame gets an overlay. */
static void step_due(rted_daemon *d)
{
    struct timespec pause = {0, 12000000};
    nanosleep(&pause, NULL);
    rted_step st;
    while ((st = rted_daemon_step(d)) == RTED_STEP_IDLE) /* a rewind */
        ;
    assert_int_equal(st, RTED_STEP_FRAME);
    drain(rted_daemon_lcm(d));
}

static void test_daemon_stream(void **state)
{
    char y4m[512];
    snprintf(y4m, sizeof y4m, "%s/road_straight.y4m", build_dir);
    rted_config c;
    debug_config(&c, y4m, 0.5, "");
    static watched w;
    watch(&w, &c);
    rted_daemon *d = w.d;
    debug_seen *s = &w.s;
    /* No layers: the grey frame alone, at half size, as MJPEG. */
    step_due(d);
    assert_int_equal(s->count, 1);
    assert_int_equal(s->pixelformat, RTEDGE_IMAGE_T_PIXEL_FORMAT_MJPEG);
    int32_t fw = 0, fh = 0;
    {
        FILE *f = fopen(y4m, "rb");
        assert_non_null(f);
        assert_int_equal(fscanf(f, "YUV4MPEG2 W%d H%d", &fw, &fh), 2);
        fclose(f);
    }
    assert_int_equal(s->width, (fw + 1) / 2);
    assert_int_equal(s->height, (fh + 1) / 2);
    assert_int_equal(coloured(s, 0) + coloured(s, 1) + coloured(s, 2), 0);
    /* The lanes over params_t (a text key): left blue, right red. */
    set_text(d, "debug.layers", "lanes");
    step_due(d);
    step_due(d);
    print_message("lanes layer: %d blue, %d red pixels\n", coloured(s, 0), coloured(s, 1));
    assert_true(coloured(s, 0) > 50 && coloured(s, 1) > 50);
    assert_int_equal(coloured(s, 2), 0);
    /* The ROI adds yellow; full size doubles the sides. */
    set_text(d, "debug.layers", "roi,lanes");
    step_due(d);
    step_due(d);
    assert_true(coloured(s, 2) > 50);
    set_real(d, "debug.scale", 1);
    step_due(d);
    step_due(d);
    assert_int_equal(s->width, fw);
    /* A bad layer name is refused whole; the stream goes on as it was. */
    set_text(d, "debug.layers", "lanes,sky");
    rted_counters n0, n1;
    rted_daemon_get_counters(d, &n0);
    step_due(d);
    rted_daemon_get_counters(d, &n1);
    assert_int_equal(n1.refused, n0.refused + 1);
    assert_string_equal(rted_daemon_config(d)->debug_layers, "roi,lanes");
    assert_int_equal(n1.debug_frames, (uint64_t)s->count);
    unwatch(&w);
}

static void test_daemon_grasp_layers_and_rate(void **state)
{
    char y4m[512];
    snprintf(y4m, sizeof y4m, "%s/debug_objects.y4m", build_dir);
    write_objects_y4m(y4m, 10, 0);
    rted_config c;
    debug_config(&c, y4m, 1, "contours,grasp");
    static watched w;
    watch(&w, &c);
    rted_daemon *d = w.d;
    debug_seen *s = &w.s;
    step_due(d);
    assert_int_equal(s->count, 1);
    assert_int_equal(s->width, OW);
    /* two grasp points (red) and two closing lines (yellow) */
    print_message("grasp layers: %d red, %d yellow pixels\n", coloured(s, 1), coloured(s, 2));
    assert_true(coloured(s, 1) >= 2 * 20 && coloured(s, 2) >= 2 * 8);
    /* At 0.1 Hz, frames as fast as they come: none of the next 20 is due. */
    set_real(d, "debug.rate_hz", 0.1);
    step_due(d);
    const int before = s->count;
    for (int frames = 0; frames < 20;) {
        rted_step st = rted_daemon_step(d);
        assert_true(st == RTED_STEP_FRAME || st == RTED_STEP_IDLE); /* IDLE: a rewind */
        frames += st == RTED_STEP_FRAME;
    }
    drain(w.lcm);
    assert_int_equal(s->count, before);
    unwatch(&w);

    /* Off by default: nothing on the channel. */
    base_config(&c, y4m, "memq://");
    watch(&w, &c);
    step_due(w.d);
    assert_int_equal(w.s.count, 0);
    unwatch(&w);
}

int main(int argc, char **argv)
{
    build_dir = argc > 1 ? argv[1] : ".";
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_encoder_round_trip),
        cmocka_unit_test(test_encoder_no_heap),
        cmocka_unit_test(test_daemon_stream),
        cmocka_unit_test(test_daemon_grasp_layers_and_rate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
