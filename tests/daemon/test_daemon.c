/* rtedged in process: the loop on synthetic sequences with known answers,
 * publishing over memq:// (decoded by a subscriber in the same process) and
 * to file:// logs (read back with lcm_eventlog); deadline accounting;
 * damaged frames; run-time configuration (file reload, params_t); an LCM
 * log source round trip; a camera missing at start waited for; the
 * heap-call count after the first frame (with systemd's notifications on);
 * realtime.threads = 2 against one thread on the recorded road clip.
 *   test_daemon BUILD_DIR CLIP_Y4M
 * (BUILD_DIR holds road_straight.{y4m,csv}; CLIP_Y4M is the recorded clip) */
#include <math.h>
#include <poll.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>
#include <lcm/eventlog.h>
#include <lcm/lcm.h>

#include "config.h"
#include "daemon.h"
#include "daemon_fixtures.h"
#include "daemon_internal.h"
#include "heapcount.h"
#include "publish/publish.h"

static const char *build_dir, *clip_y4m;

static void path(char *out, size_t size, const char *name)
{
    snprintf(out, size, "%s/daemon_%s", build_dir, name);
}

/* ---- a memq:// subscriber ---- */

typedef struct seen {
    int lanes, grasps, statuses, images;
    int grasp_ok;          /* grasp messages whose objects match the drawn ones */
    int last_objects;      /* objects in the last grasp message */
    double last_x, last_y; /* its first object's centre */
    int workspace_ok;      /* with grasp.roi: only the object inside, and the ROI in the header */
    int lane_match;        /* lane messages within tolerance of the CSV */
    int lane_checked;
    int deadline_met;
    int64_t last_sequence;
    bool sequence_ok;
    double csv[128][4];
    int csv_visible[128][2];
    int csv_rows;
    rtedge_status_t last_status;
} seen;

static bool near(double a, double b, double tol) { return fabs(a - b) <= tol; }

static void check_grasp(seen *s, const rtedge_grasp_detection_t *m)
{
    rect r[2];
    objects_at((int)m->header.sequence, r);
    if (m->nobjects != 2)
        return;
    int ok = 0;
    for (int i = 0; i < 2; i++) {
        const rtedge_grasp_object_t *o = &m->objects[i];
        for (int j = 0; j < 2; j++) {
            double cx = r[j].x0 + (r[j].w - 1) / 2.0, cy = r[j].y0 + (r[j].h - 1) / 2.0;
            double short_side = r[j].w < r[j].h ? r[j].w : r[j].h;
            if (near(o->centroid_x, cx, 0.75) && near(o->centroid_y, cy, 0.75) &&
                near(o->grasp_x, cx, 0.75) && near(o->grasp_y, cy, 0.75) &&
                near(o->narrowest_width_px, short_side - 1, 2.5) &&
                near(o->opening_width_px, o->narrowest_width_px + 16, 0.01) && /* margin 8 */
                o->score >= 0 && o->score <= 1 && o->bbox_width >= r[j].w - 2 &&
                o->bbox_width <= r[j].w + 2)
                ok++;
        }
    }
    if (ok == 2)
        s->grasp_ok++;
}

/* workspace_config's run: object 1 is inside the workspace, object 0 left
 * of it; the header carries the workspace in pixels. */
static void check_workspace(seen *s, const rtedge_grasp_detection_t *m)
{
    rect r[2];
    objects_at((int)m->header.sequence, r);
    if (m->header.roi_npoints != 4 || m->header.roi[0].x != 88 || m->header.roi[0].y != 36 ||
        m->nobjects != 1)
        return;
    const double cx = r[1].x0 + (r[1].w - 1) / 2.0, cy = r[1].y0 + (r[1].h - 1) / 2.0;
    if (near(m->objects[0].centroid_x, cx, 0.75) && near(m->objects[0].centroid_y, cy, 0.75))
        s->workspace_ok++;
}

static void check_lane(seen *s, const rtedge_lane_detection_t *m)
{
    int64_t k = m->header.sequence;
    if (k < 0 || k >= s->csv_rows)
        return;
    if (!s->csv_visible[k][0] || !s->csv_visible[k][1] || k < 5)
        return; /* the tracker settles in the first frames; worn markings are held */
    s->lane_checked++;
    if (m->left.found && m->right.found && near(m->left.x1, s->csv[k][0], 10) &&
        near(m->right.x1, s->csv[k][2], 10) && near(m->left.x2, s->csv[k][1], 10) &&
        near(m->right.x2, s->csv[k][3], 10))
        s->lane_match++;
}

static void on_message(const lcm_recv_buf_t *rb, const char *channel, void *user)
{
    seen *s = user;
    if (!strcmp(channel, "RTEDGE_LANES")) {
        rtedge_lane_detection_t m;
        assert_true(rtedge_lane_detection_t_decode(rb->data, 0, (int)rb->data_size, &m) > 0);
        if (s->lanes && m.header.sequence != s->last_sequence + 1)
            s->sequence_ok = false;
        s->last_sequence = m.header.sequence;
        s->lanes++;
        s->deadline_met += m.header.deadline_met;
        assert_true(m.header.latency_us >= 0);
        assert_int_equal(m.header.deadline_met, m.header.latency_us <= m.header.deadline_us);
        assert_int_equal(m.header.roi_npoints, 4);
        /* a found lane's polyline starts at its bottom endpoint and goes up */
        const rtedge_lane_t *sides[2] = {&m.left, &m.right};
        for (int i = 0; i < 2; i++) {
            const rtedge_lane_t *l = sides[i];
            assert_true(l->npoints >= 0 && l->npoints <= RTEDGE_LANE_T_MAX_POINTS);
            if (!l->found) {
                assert_int_equal(l->npoints, 0);
                continue;
            }
            assert_true(l->npoints >= 2);
            assert_true(l->points_y[0] == l->y1 && near(l->points_x[0], l->x1, 0.01));
            for (int k = 1; k < l->npoints; k++)
                assert_true(l->points_y[k] < l->points_y[k - 1]);
        }
        check_lane(s, &m);
        rtedge_lane_detection_t_decode_cleanup(&m);
    } else if (!strcmp(channel, "RTEDGE_GRASP")) {
        rtedge_grasp_detection_t m;
        assert_true(rtedge_grasp_detection_t_decode(rb->data, 0, (int)rb->data_size, &m) > 0);
        s->grasps++;
        s->last_objects = m.nobjects;
        if (m.nobjects > 0) {
            s->last_x = m.objects[0].grasp_x;
            s->last_y = m.objects[0].grasp_y;
        }
        check_grasp(s, &m);
        check_workspace(s, &m);
        rtedge_grasp_detection_t_decode_cleanup(&m);
    } else if (!strcmp(channel, "RTEDGE_STATUS")) {
        rtedge_status_t m;
        assert_true(rtedge_status_t_decode(rb->data, 0, (int)rb->data_size, &m) > 0);
        s->statuses++;
        rtedge_status_t_decode_cleanup(&s->last_status);
        s->last_status = m;
    } else if (!strcmp(channel, "RTEDGE_IMAGE")) {
        s->images++;
    }
}

static void drain(lcm_t *lcm)
{
    struct pollfd p = {lcm_get_fileno(lcm), POLLIN, 0};
    while (poll(&p, 1, 0) > 0 && (p.revents & POLLIN))
        lcm_handle(lcm);
}

static void run_memq(rted_daemon *d, seen *s)
{
    lcm_t *lcm = rted_daemon_lcm(d);
    assert_non_null(lcm);
    lcm_subscription_t *sub = lcm_subscribe(lcm, "RTEDGE_.*", on_message, s);
    s->sequence_ok = true;
    for (;;) {
        rted_step st = rted_daemon_step(d);
        drain(lcm);
        if (st == RTED_STEP_END || st == RTED_STEP_FAILED)
            break;
    }
    rted_daemon_publish_status(d);
    drain(lcm);
    lcm_unsubscribe(lcm, sub);
}

/* The daemon on c to the end, over memq://: what the subscriber saw, the
 * counters. */
static void run_config(const rted_config *c, seen *s, rted_counters *n)
{
    rted_daemon *d = open_daemon(c, NULL);
    run_memq(d, s);
    rted_daemon_get_counters(d, n);
    rted_daemon_close(d);
}

static void read_csv(seen *s, const char *file)
{
    FILE *f = fopen(file, "r");
    assert_non_null(f);
    char line[256];
    assert_non_null(fgets(line, sizeof line, f));
    int k, lv, rv;
    double a, b, c, e;
    while (fgets(line, sizeof line, f) &&
           sscanf(line, "%d,%lf,%lf,%lf,%lf,%d,%d", &k, &a, &b, &c, &e, &lv, &rv) == 7 && k < 128) {
        s->csv[k][0] = a;
        s->csv[k][1] = b;
        s->csv[k][2] = c;
        s->csv[k][3] = e;
        s->csv_visible[k][0] = lv;
        s->csv_visible[k][1] = rv;
        s->csv_rows = k + 1;
    }
    fclose(f);
}

/* ---- tests ---- */

static void test_memq_road_lanes(void **state)
{
    char y4m[512], csv[512];
    snprintf(y4m, sizeof y4m, "%s/road_straight.y4m", build_dir);
    snprintf(csv, sizeof csv, "%s/road_straight.csv", build_dir);
    static seen s;
    memset(&s, 0, sizeof s);
    read_csv(&s, csv);
    assert_int_equal(s.csv_rows, 60);
    rted_config c;
    base_config(&c, y4m, "memq://");
    c.grasp_enabled = false;
    rted_counters n;
    run_config(&c, &s, &n);
    assert_int_equal(n.processed, 60);
    assert_int_equal(s.lanes, 60);
    assert_int_equal(s.grasps, 0);
    assert_true(s.sequence_ok);
    assert_int_equal(s.deadline_met, 60);
    print_message("road_straight: %d of %d frames with both lanes within 10 px of the truth\n",
                  s.lane_match, s.lane_checked);
    assert_true(s.lane_checked > 40);
    assert_true(s.lane_match * 10 >= s.lane_checked * 9);
    assert_true(s.statuses >= 1);
    assert_int_equal(s.last_status.frames_processed, 60);
    assert_int_equal(s.last_status.deadline_misses, 0);
    assert_true(s.last_status.latency_max_us >= s.last_status.latency_p99_us);
    assert_true(s.last_status.latency_p99_us >= s.last_status.latency_p50_us);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

/* The daemon over memq:// on a fresh objects sequence (damaged or not),
 * with `tweak` applied to the test configuration. */
static void objects_run(const char *name, int frames, int damage, void (*tweak)(rted_config *),
                        seen *s, rted_counters *n)
{
    char y4m[512];
    path(y4m, sizeof y4m, name);
    write_objects_y4m(y4m, frames, damage);
    memset(s, 0, sizeof *s);
    rted_config c;
    base_config(&c, y4m, "memq://");
    if (tweak)
        tweak(&c);
    run_config(&c, s, n);
}

static void with_images(rted_config *c) { c->publish_images = true; }
static void tiny_deadline(rted_config *c) { c->deadline_ms = 0.001; /* 1 us: no frame makes it */ }

static void test_memq_objects(void **state)
{
    static seen s;
    rted_counters n;
    objects_run("objects.y4m", 20, 0, with_images, &s, &n);
    assert_int_equal(s.lanes, 20);
    assert_int_equal(s.grasps, 20);
    assert_int_equal(s.images, 20);
    assert_int_equal(s.grasp_ok, 20);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

static void workspace_config(rted_config *c)
{
    snprintf(c->grasp_roi, sizeof c->grasp_roi, "0.55,0.3;0.95,0.3;0.95,0.95;0.55,0.95");
}

/* grasp.roi: objects outside the workspace are not reported. */
static void test_grasp_workspace(void **state)
{
    static seen s;
    rted_counters n;
    objects_run("objects_workspace.y4m", 20, 0, workspace_config, &s, &n);
    assert_int_equal(s.grasps, 20);
    assert_int_equal(s.workspace_ok, 20);
    assert_int_equal(s.grasp_ok, 0); /* never both objects */
    rtedge_status_t_decode_cleanup(&s.last_status);
}

/* A 4:2:0 y4m of a red table with a green square as grey as it (Y 107 on
 * 117, U and V far apart): `frames` frames. */
static void write_colour_y4m(const char *file, int frames)
{
    enum { W = 160, H = 120 };
    FILE *f = fopen(file, "wb");
    assert_non_null(f);
    fprintf(f, "YUV4MPEG2 W%d H%d F30:1 Ip A1:1 C420jpeg\n", W, H);
    static uint8_t y[W * H], u[W * H / 4], v[W * H / 4];
    for (int r = 0; r < H; r++)
        for (int c = 0; c < W; c++) {
            const bool in = c >= 60 && c < 100 && r >= 40 && r < 80;
            y[r * W + c] = in ? 107 : 117;
            if (!(r & 1) && !(c & 1)) {
                u[(r / 2) * (W / 2) + c / 2] = in ? 133 : 88;
                v[(r / 2) * (W / 2) + c / 2] = in ? 85 : 185;
            }
        }
    for (int k = 0; k < frames; k++) {
        fputs("FRAME\n", f);
        fwrite(y, 1, sizeof y, f);
        fwrite(u, 1, sizeof u, f);
        fwrite(v, 1, sizeof v, f);
    }
    fclose(f);
}

/* grasp.chroma: the daemon reads the frame's colour, so the square as grey
 * as the table is found by it, at its centre, on one thread and on two;
 * with grasp.chroma = false it is not. */
static void test_grasp_colour(void **state)
{
    char y4m[512];
    path(y4m, sizeof y4m, "colour.y4m");
    write_colour_y4m(y4m, 3);
    for (int run = 0; run < 3; run++) {
        static seen s;
        memset(&s, 0, sizeof s);
        rted_counters n;
        rted_config c;
        base_config(&c, y4m, "memq://");
        c.grasp_chroma = run < 2;
        c.rt_threads = run == 1 ? 2 : 1;
        run_config(&c, &s, &n);
        assert_int_equal(s.grasps, 3);
        assert_int_equal(s.last_objects, run < 2 ? 1 : 0);
        if (run < 2) {
            assert_true(near(s.last_x, 79.5, 1.0));
            assert_true(near(s.last_y, 59.5, 1.0));
        }
        rtedge_status_t_decode_cleanup(&s.last_status);
    }
}

static void test_deadline_accounting(void **state)
{
    static seen s;
    rted_counters n;
    objects_run("objects_deadline.y4m", 10, 0, tiny_deadline, &s, &n);
    assert_int_equal(n.processed, 10);
    assert_int_equal(n.deadline_misses, 10);
    assert_int_equal(n.stages_skipped, 10); /* the grasp path, every frame */
    assert_int_equal(s.lanes, 10);
    assert_int_equal(s.grasps, 0);
    assert_int_equal(s.deadline_met, 0);
    assert_int_equal(s.last_status.deadline_misses, 10);
    assert_int_equal(s.last_status.stages_skipped, 10);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

static void test_damaged_frames(void **state)
{
    static seen s;
    rted_counters n;
    objects_run("objects_damaged.y4m", 12, 1, NULL, &s, &n);
    print_message("damaged: %llu processed, %llu bad\n", (unsigned long long)n.processed,
                  (unsigned long long)n.bad_frames);
    assert_true(n.bad_frames >= 2);
    assert_int_equal(s.last_status.frames_bad, (int64_t)n.bad_frames); /* the final status */
    assert_true(n.processed >= 9 && n.processed <= 10);
    assert_int_equal(s.grasps, (int)n.processed);
    assert_int_equal(s.grasp_ok, (int)n.processed);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

/* A directory of six objects frames as PGM files; frame `tiny` (-1: none)
 * is 2x2 instead. */
static void write_objects_pgm_dir(const char *dir, int tiny)
{
    mkdir(dir, 0755);
    static uint8_t img[OW * OH];
    for (int k = 0; k < 6; k++) {
        char file[600];
        snprintf(file, sizeof file, "%s/frame_%02d.pgm", dir, k);
        FILE *f = fopen(file, "wb");
        assert_non_null(f);
        objects_frame(k, img);
        int w = k == tiny ? 2 : OW, h = k == tiny ? 2 : OH;
        fprintf(f, "P5\n%d %d\n255\n", w, h);
        fwrite(img, 1, (size_t)(w * h), f);
        fclose(f);
    }
}

/* An image directory (PGM files) as the source. */
static void test_images_source(void **state)
{
    char dir[512];
    path(dir, sizeof dir, "images");
    write_objects_pgm_dir(dir, -1);
    static seen s;
    memset(&s, 0, sizeof s);
    rted_config c;
    base_config(&c, dir, "memq://");
    rted_daemon *d = open_daemon(&c, NULL);
    run_memq(d, &s);
    rted_daemon_close(d);
    assert_int_equal(s.grasps, 6);
    assert_int_equal(s.grasp_ok, 6);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

typedef struct log_counts {
    int lanes, grasps, statuses, states, other, grasp_ok;
} log_counts;

static void read_log(const char *file, log_counts *lc)
{
    memset(lc, 0, sizeof *lc);
    lcm_eventlog_t *log = lcm_eventlog_create(file, "r");
    assert_non_null(log);
    lcm_eventlog_event_t *e;
    seen s;
    memset(&s, 0, sizeof s);
    while ((e = lcm_eventlog_read_next_event(log))) {
        if (!strcmp(e->channel, "RTEDGE_LANES")) {
            rtedge_lane_detection_t m;
            assert_true(rtedge_lane_detection_t_decode(e->data, 0, e->datalen, &m) > 0);
            rtedge_lane_detection_t_decode_cleanup(&m);
            lc->lanes++;
        } else if (!strcmp(e->channel, "RTEDGE_GRASP")) {
            rtedge_grasp_detection_t m;
            assert_true(rtedge_grasp_detection_t_decode(e->data, 0, e->datalen, &m) > 0);
            check_grasp(&s, &m);
            rtedge_grasp_detection_t_decode_cleanup(&m);
            lc->grasps++;
        } else if (!strcmp(e->channel, "RTEDGE_STATUS")) {
            rtedge_status_t m;
            assert_true(rtedge_status_t_decode(e->data, 0, e->datalen, &m) > 0);
            rtedge_status_t_decode_cleanup(&m);
            lc->statuses++;
        } else if (!strcmp(e->channel, "RTEDGE_PARAM_STATE")) {
            rtedge_param_state_t m;
            assert_true(rtedge_param_state_t_decode(e->data, 0, e->datalen, &m) > 0);
            assert_true(m.nkeys > 10);
            rtedge_param_state_t_decode_cleanup(&m);
            lc->states++;
        } else {
            lc->other++;
        }
        lcm_eventlog_free_event(e);
    }
    lcm_eventlog_destroy(log);
    lc->grasp_ok = s.grasp_ok;
}

static void run_to_end(rted_daemon *d)
{
    rted_step st;
    while ((st = rted_daemon_step(d)) != RTED_STEP_END)
        assert_int_not_equal(st, RTED_STEP_FAILED);
    rted_daemon_publish_status(d);
}

static void test_file_log(void **state)
{
    char y4m[512], log[512], url[600];
    path(y4m, sizeof y4m, "objects_file.y4m");
    path(log, sizeof log, "file.lcm");
    write_objects_y4m(y4m, 15, 0);
    snprintf(url, sizeof url, "file://%s", log);
    rted_config c;
    base_config(&c, y4m, url);
    rted_daemon *d = open_daemon(&c, NULL);
    run_to_end(d);
    rted_daemon_close(d);
    log_counts lc;
    read_log(log, &lc);
    assert_int_equal(lc.lanes, 15);
    assert_int_equal(lc.grasps, 15);
    assert_int_equal(lc.grasp_ok, 15);
    assert_true(lc.statuses >= 1);
    assert_true(lc.states >= 1);
    assert_int_equal(lc.other, 0);
}

/* Frames recorded as image_t in an LCM log, replayed into the daemon. */
static void test_lcm_log_source(void **state)
{
    char frames[512], url[600], out[512], out_url[600];
    path(frames, sizeof frames, "frames.lcm");
    path(out, sizeof out, "from_log.lcm");
    snprintf(url, sizeof url, "file://%s", frames);
    snprintf(out_url, sizeof out_url, "file://%s", out);
    rte_publish_limits lim = {64, 8, 1, 1, 1, OW * OH, 0, 0};
    rte_publisher *pub;
    char msg[256];
    assert_int_equal(rte_publisher_create(&pub, url, &lim, msg, sizeof msg), RTE_OK);
    static uint8_t img[OW * OH];
    for (int k = 0; k < 8; k++) {
        objects_frame(k, img);
        rtedge_image_t m = {.utime = 1000000 + k * 33333,
                            .width = OW,
                            .height = OH,
                            .row_stride = OW,
                            .pixelformat = RTEDGE_IMAGE_T_PIXEL_FORMAT_GRAY,
                            .size = OW * OH,
                            .data = img};
        assert_int_equal(rte_publish_image(pub, "CAMERA", &m, msg, sizeof msg), RTE_OK);
    }
    rte_publisher_destroy(pub);
    rted_config c;
    base_config(&c, frames, out_url);
    c.source_kind = RTED_SOURCE_LCM_LOG;
    snprintf(c.source_channel, sizeof c.source_channel, "CAMERA");
    rted_daemon *d = open_daemon(&c, NULL);
    run_to_end(d);
    rted_daemon_close(d);
    log_counts lc;
    read_log(out, &lc);
    assert_int_equal(lc.grasps, 8);
    assert_int_equal(lc.grasp_ok, 8);
}

static void write_file(const char *file, const char *text)
{
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_reload(void **state)
{
    char y4m[512], conf[512], text[2048], msg[RTED_MSG];
    path(y4m, sizeof y4m, "objects_reload.y4m");
    path(conf, sizeof conf, "reload.conf");
    write_objects_y4m(y4m, 5, 0);
    snprintf(text, sizeof text,
             "[source]\npath = %s\npace = fast\nloop = true\n[publish]\nurl = memq://\n"
             "[grasp]\nmin_area = 100\n",
             y4m);
    write_file(conf, text);
    rted_config c;
    rted_config_defaults(&c);
    assert_true(rted_config_load(&c, conf, msg, sizeof msg));
    rted_daemon *d = open_daemon(&c, conf);
    static seen s;
    memset(&s, 0, sizeof s);
    lcm_t *lcm = rted_daemon_lcm(d);
    lcm_subscription_t *sub = lcm_subscribe(lcm, "RTEDGE_GRASP", on_message, &s);
    for (int i = 0; i < 3; i++)
        rted_daemon_step(d);
    drain(lcm);
    assert_int_equal(s.grasp_ok, 3);
    /* The larger rectangle is 960 px, the smaller 900: a minimum of 920 keeps one. */
    snprintf(text, sizeof text,
             "[source]\npath = %s\npace = fast\nloop = true\n[publish]\nurl = memq://\n"
             "[grasp]\nmin_area = 920\n",
             y4m);
    write_file(conf, text);
    assert_true(rted_daemon_reload(d, msg, sizeof msg));
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.reloads, 1);
    s.grasps = 0;
    rted_daemon_step(d);
    drain(lcm);
    assert_int_equal(s.grasps, 1);
    /* A size change is refused and the old configuration stays. */
    snprintf(text, sizeof text,
             "[source]\npath = %s\npace = fast\nloop = true\n[publish]\nurl = memq://\n"
             "[grasp]\nmin_area = 920\nmax_objects = 64\n",
             y4m);
    write_file(conf, text);
    assert_false(rted_daemon_reload(d, msg, sizeof msg));
    assert_non_null(strstr(msg, "grasp.max_objects"));
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.refused, 1);
    assert_int_equal(n.reloads, 1);
    /* params_t: a runtime value applied, an out-of-range one and a size refused. */
    rtedge_param_t p[1] = {{.name = "grasp.min_area",
                            .kind = RTEDGE_PARAM_T_KIND_INT,
                            .int_value = 100,
                            .text_value = ""}};
    rtedge_params_t pm = {.utime = 0, .request_id = 7, .nparams = 1, .params = p};
    uint8_t buf[512];
    int len = rtedge_params_t_encode(buf, 0, sizeof buf, &pm);
    assert_true(len > 0);
    /* params are off by default: nothing happens */
    lcm_publish(lcm, "RTEDGE_PARAMS", buf, (unsigned)len);
    rted_daemon_step(d);
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.reloads, 1);
    lcm_unsubscribe(lcm, sub);
    rted_daemon_close(d);
}

static void test_params_channel(void **state)
{
    char y4m[512];
    path(y4m, sizeof y4m, "objects_params.y4m");
    rted_config c;
    looping_objects_config(&c, y4m, 5);
    c.params_enabled = true;
    rted_daemon *d = open_daemon(&c, NULL);
    lcm_t *lcm = rted_daemon_lcm(d);
    static seen s;
    memset(&s, 0, sizeof s);
    lcm_subscription_t *sub = lcm_subscribe(lcm, "RTEDGE_GRASP", on_message, &s);
    rtedge_param_t p[2] = {{.name = "grasp.min_area",
                            .kind = RTEDGE_PARAM_T_KIND_INT,
                            .int_value = 920,
                            .text_value = ""},
                           {.name = "deadline.ms",
                            .kind = RTEDGE_PARAM_T_KIND_REAL,
                            .real_value = 900,
                            .text_value = ""}};
    rtedge_params_t pm = {.request_id = 1, .nparams = 2, .params = p};
    uint8_t buf[512];
    int len = rtedge_params_t_encode(buf, 0, sizeof buf, &pm);
    lcm_publish(lcm, "RTEDGE_PARAMS", buf, (unsigned)len);
    rted_daemon_step(d);
    drain(lcm);
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.reloads, 1);
    assert_int_equal(s.grasps, 1);
    assert_int_equal(s.grasp_ok, 0); /* one object left */
    /* out of range, then a fixed size: both refused */
    p[0].int_value = -5;
    pm.nparams = 1;
    len = rtedge_params_t_encode(buf, 0, sizeof buf, &pm);
    lcm_publish(lcm, "RTEDGE_PARAMS", buf, (unsigned)len);
    rted_daemon_step(d);
    p[0] = (rtedge_param_t){.name = "lane.max_segments",
                            .kind = RTEDGE_PARAM_T_KIND_INT,
                            .int_value = 10,
                            .text_value = ""};
    len = rtedge_params_t_encode(buf, 0, sizeof buf, &pm);
    lcm_publish(lcm, "RTEDGE_PARAMS", buf, (unsigned)len);
    rted_daemon_step(d);
    drain(lcm);
    rted_daemon_get_counters(d, &n);
    assert_int_equal(n.reloads, 1);
    assert_int_equal(n.refused, 2);
    /* subscribers learn of both outcomes from the status message */
    lcm_subscription_t *status_sub = lcm_subscribe(lcm, "RTEDGE_STATUS", on_message, &s);
    rted_daemon_publish_status(d);
    drain(lcm);
    assert_int_equal(s.last_status.config_reloads, 1);
    assert_int_equal(s.last_status.config_refused, 2);
    rtedge_status_t_decode_cleanup(&s.last_status);
    memset(&s.last_status, 0, sizeof s.last_status);
    lcm_unsubscribe(lcm, status_sub);
    lcm_unsubscribe(lcm, sub);
    rted_daemon_close(d);
}

/* A looping recording: a rewind is not a reconnection (no status between
 * the first and the final one, so the latency window spans the run). */
static void test_loop_rewinds_quietly(void **state)
{
    char y4m[512];
    path(y4m, sizeof y4m, "objects_loop.y4m");
    rted_config c;
    looping_objects_config(&c, y4m, 5);
    c.max_frames = 23;
    c.status_period_ms = 60000;
    rted_daemon *d = open_daemon(&c, NULL);
    static seen s;
    memset(&s, 0, sizeof s);
    run_memq(d, &s);
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    int32_t p50, p99, max;
    rted_daemon_latency(d, &p50, &p99, &max);
    rted_daemon_close(d);
    assert_int_equal(n.processed, 23);
    assert_int_equal(n.rewinds, 4);
    /* Only the final status (the one at start went out before the subscriber
     * came); each rewind used to publish two, and reset the window. */
    assert_int_equal(s.statuses, 1);
    assert_int_equal(s.last_status.frames_processed, 23);
    assert_int_equal(s.last_status.source_reconnects, 0);
    assert_true(s.last_status.fps > 0);
    assert_true(p50 > 0 && p50 <= p99 && p99 <= max);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

/* --bench's latency covers the whole run, whatever the status windows
 * (the last one may be empty): 1..1000 us in a shuffled order give p50
 * and p99 within the histogram's 1.6%, the max exactly; out-of-range
 * latencies are clamped. */
static void test_run_latency(void **state)
{
    char y4m[512];
    path(y4m, sizeof y4m, "objects_loop.y4m");
    rted_config c;
    looping_objects_config(&c, y4m, 5);
    rted_daemon *d = open_daemon(&c, NULL);
    int32_t p50, p99, max;
    rted_daemon_latency(d, &p50, &p99, &max);
    assert_true(p50 == 0 && p99 == 0 && max == 0);
    for (int64_t i = 0; i < 1000; i++)
        rted_record_latency(d, (i * 389 % 1000 + 1) * 1000); /* 389 is prime to 1000 */
    rted_daemon_latency(d, &p50, &p99, &max);
    assert_true(abs(p50 - 500) <= 8 && abs(p99 - 990) <= 16);
    assert_int_equal(max, 1000);
    rted_record_latency(d, INT64_MAX);
    rted_record_latency(d, -5);
    rted_daemon_latency(d, &p50, &p99, &max);
    assert_int_equal(max, INT32_MAX);
    assert_true(p50 > 0 && p50 <= p99 && p99 <= max);
    rted_daemon_close(d);
}

/* A Y4M of the given frames: 'g' good, 'c' cut short (only at the end), 'x'
 * a damaged FRAME header. */
static void write_frames_y4m(const char *file, const char *frames)
{
    FILE *f = fopen(file, "wb");
    assert_non_null(f);
    fprintf(f, "YUV4MPEG2 W%d H%d F30:1 Ip A1:1 Cmono\n", OW, OH);
    static uint8_t img[OW * OH];
    for (int k = 0; frames[k]; k++) {
        objects_frame(k, img);
        fputs(frames[k] == 'x' ? "FRAMX\n" : "FRAME\n", f);
        fwrite(img, 1, frames[k] == 'c' ? OW * OH / 3 : OW * OH, f);
    }
    fclose(f);
}

/* A recording with no readable frame stops with RTED_STEP_EMPTY (exit code
 * 3) instead of rewinding without end; one with a readable frame loops. */
static void test_loop_without_good_frame(void **state)
{
    const struct {
        const char *frames;
        bool loop;
        rted_step last;
        int max_steps;
    } cases[] = {
        {"c", true, RTED_STEP_EMPTY, 3}, /* issue 18: one cut-short frame */
        {"", true, RTED_STEP_EMPTY, 1},  /* a header only */
        {"xc", true, RTED_STEP_EMPTY, 4},
        {"", false, RTED_STEP_EMPTY, 1},
        {"gc", false, RTED_STEP_END, 4},
        {"xgc", true, RTED_STEP_END, 40}, /* loops until max_frames */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char y4m[512];
        path(y4m, sizeof y4m, "nogood.y4m");
        write_frames_y4m(y4m, cases[i].frames);
        rted_config c;
        base_config(&c, y4m, "memq://");
        c.loop = cases[i].loop;
        c.max_frames = 10;
        rted_daemon *d = open_daemon(&c, NULL);
        rted_step st = RTED_STEP_IDLE;
        int steps = 0;
        while (steps < 100 && (st == RTED_STEP_IDLE || st == RTED_STEP_FRAME)) {
            st = rted_daemon_step(d);
            steps++;
        }
        rted_counters n;
        rted_daemon_get_counters(d, &n);
        rted_daemon_close(d);
        print_message("'%s'%s: step %d gave %d (%llu frames, %llu bad, %llu rewinds)\n",
                      cases[i].frames, cases[i].loop ? " looped" : "", steps, st,
                      (unsigned long long)n.processed, (unsigned long long)n.bad_frames,
                      (unsigned long long)n.rewinds);
        assert_int_equal(st, cases[i].last);
        assert_true(steps <= cases[i].max_steps);
    }
}

/* A frame a path cannot process (here a 2x2 image among 160x120 ones: the
 * lane ROI leaves it no rows) is counted in path_errors, not as a publish
 * error, and the daemon goes on. */
static void test_path_errors(void **state)
{
    char dir[512];
    path(dir, sizeof dir, "images_tiny");
    write_objects_pgm_dir(dir, 3);
    static seen s;
    memset(&s, 0, sizeof s);
    rted_config c;
    base_config(&c, dir, "memq://");
    rted_counters n;
    run_config(&c, &s, &n);
    assert_int_equal(n.processed, 6);
    assert_int_equal(n.path_errors, 1);
    assert_int_equal(n.publish_errors, 0);
    assert_int_equal(s.lanes, 5);
    assert_int_equal(s.last_status.path_errors, 1);
    rtedge_status_t_decode_cleanup(&s.last_status);
}

/* A camera missing at start: without source.wait rtedged cannot start;
 * with it the daemon opens, sized for the size asked, and its steps go on
 * with the status message saying the source is not there. */
static void test_camera_waited_for(void **state)
{
    rted_config c;
    base_config(&c, "/dev/video99", "memq://");
    c.wait_camera = false;
    rted_daemon *d;
    char msg[RTED_MSG];
    assert_false(rted_daemon_open(&d, &c, NULL, msg, sizeof msg));
    assert_non_null(strstr(msg, "cannot open v4l2 source /dev/video99"));
    c.wait_camera = true;
    c.width = 320;
    c.height = 240;
    d = open_daemon(&c, NULL);
    assert_int_equal(d->width, 320);
    static seen s;
    memset(&s, 0, sizeof s);
    lcm_t *lcm = rted_daemon_lcm(d);
    lcm_subscription_t *sub = lcm_subscribe(lcm, "RTEDGE_STATUS", on_message, &s);
    /* 0.8 s: the first try after 0.5 s fails */
    for (int i = 0; i < 8; i++)
        assert_int_equal(rted_daemon_step(d), RTED_STEP_IDLE);
    rted_daemon_publish_status(d);
    drain(lcm);
    assert_true(s.statuses >= 1);
    assert_int_equal(s.last_status.source_state, RTEDGE_STATUS_T_SOURCE_RECONNECTING);
    assert_int_equal(s.last_status.frames_received, 0);
    assert_int_equal(s.last_status.source_reconnects, 0);
    rte_source_stats ss;
    rte_source_get_stats(&d->source, &ss);
    assert_true(ss.errors >= 1); /* a try was made */
    rtedge_status_t_decode_cleanup(&s.last_status);
    lcm_unsubscribe(lcm, sub);
    rted_daemon_close(d);
}

/* systemd's notification socket, as a service has it (NOTIFY_SOCKET, a
 * watchdog ping at most every millisecond): the daemon opens it when
 * NOTIFY_SOCKET is set. */
static int notify_listen(const char *file)
{
    int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK, 0);
    assert_true(fd >= 0);
    struct sockaddr_un a = {.sun_family = AF_UNIX};
    assert_true(strlen(file) < sizeof a.sun_path);
    memcpy(a.sun_path, file, strlen(file) + 1);
    unlink(file);
    assert_int_equal(bind(fd, (struct sockaddr *)&a, sizeof a), 0);
    char pid[24];
    snprintf(pid, sizeof pid, "%d", (int)getpid());
    setenv("NOTIFY_SOCKET", file, 1);
    setenv("WATCHDOG_USEC", "2000", 1);
    setenv("WATCHDOG_PID", pid, 1);
    return fd;
}

/* The datagrams waiting: how many start with prefix. */
static int notify_count(int fd, const char *prefix)
{
    char buf[512];
    ssize_t r;
    int n = 0;
    while ((r = recv(fd, buf, sizeof buf - 1, 0)) > 0) {
        buf[r] = 0;
        n += !strncmp(buf, prefix, strlen(prefix));
    }
    return n;
}

/* 1000 frames, looped, as fast as possible, lane and grasp paths (on
 * `threads` threads), status messages (and the frames recorded: record !=
 * NULL), systemd's notifications: no heap call after the first frame, in
 * any thread. */
static void heap_run(const char *url, bool images, const char *record, int threads)
{
    char y4m[512];
    path(y4m, sizeof y4m, "objects_heap.y4m");
    write_objects_y4m(y4m, 10, 0);
    rted_config c;
    base_config(&c, y4m, url);
    c.loop = true;
    c.max_frames = 1000;
    c.status_period_ms = 10;
    c.publish_images = images;
    /* everything on: the debug overlay stream at full size as often as it
     * may, the params channel, param_state_t every 100 ms */
    c.debug_enabled = true;
    c.debug_scale = 1;
    c.debug_rate_hz = 100;
    c.params_enabled = true;
    c.params_state_period_ms = 100;
    c.rt_threads = threads;
    if (record)
        snprintf(c.record_path, sizeof c.record_path, "%s", record);
    char sock[100], cwd[64] = "";
    /* NOTIFY_SOCKET is absolute, and a socket path is short */
    if (build_dir[0] != '/')
        assert_non_null(getcwd(cwd, sizeof cwd));
    snprintf(sock, sizeof sock, "%s/rtedged-notify-%d", cwd[0] ? cwd : "/tmp", (int)getpid());
    const int notify_fd = notify_listen(sock);
    rted_daemon *d = open_daemon(&c, NULL);
    unsetenv("NOTIFY_SOCKET");
    assert_int_equal(d->threaded, threads == 2);
    assert_int_equal(rted_daemon_step(d), RTED_STEP_FRAME);
    assert_int_equal(notify_count(notify_fd, "READY=1\nSTATUS=streaming"), 1);
    const uint64_t notified0 = d->notify.sent + d->notify.failed;
    rted_counters n0;
    rted_daemon_get_counters(d, &n0);
    heapcount_reset();
    rted_step st;
    while ((st = rted_daemon_step(d)) != RTED_STEP_END)
        assert_int_not_equal(st, RTED_STEP_FAILED);
    /* at least one param_state_t inside the counted steps */
    struct timespec pause = {0, 110000000};
    nanosleep(&pause, NULL);
    rted_daemon_publish_status(d);
    heapcount_counts hc;
    heapcount_get(&hc);
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    const uint64_t notified = d->notify.sent + d->notify.failed - notified0;
    rted_daemon_close(d);
    /* (the socket's queue may have filled: failed sends are dropped) */
    const int pings = notify_count(notify_fd, "WATCHDOG=1");
    close(notify_fd);
    unlink(sock);
    print_message("%s: %llu notifications in the counted steps, %d watchdog pings received\n", url,
                  (unsigned long long)notified, pings);
    assert_true(pings >= 1);
    assert_true(notified >= n.status_sent);
    assert_int_equal(n.processed, 1000);
    print_message(
        "%s, %d thread(s): 999 frames, %llu messages (%llu debug overlays), %llu status, %llu "
        "param states, %llu rewinds: %llu heap calls (malloc %llu calloc %llu realloc "
        "%llu free %llu)\n",
        url, threads, (unsigned long long)n.published, (unsigned long long)n.debug_frames,
        (unsigned long long)n.status_sent, (unsigned long long)(n.states_sent - n0.states_sent),
        (unsigned long long)n.rewinds, (unsigned long long)heapcount_calls(&hc),
        (unsigned long long)hc.malloc_calls, (unsigned long long)hc.calloc_calls,
        (unsigned long long)hc.realloc_calls, (unsigned long long)hc.free_calls);
    /* Nothing allocates. The only calls allowed are glibc's fseeko()
     * calling free(NULL) (its backup read area) when the Y4M source seeks
     * back for a rewind: at most one per rewind, none per frame. */
    assert_int_equal(heapcount_allocations(&hc), 0);
    assert_true(n.debug_frames >= 2);
    assert_true(n.states_sent > n0.states_sent);
    assert_int_equal(n.rewinds, 99);
    assert_true(hc.free_calls == 0 || hc.free_calls == n.rewinds);
}

static void test_no_heap_calls_file(void **state)
{
    if (!heapcount_active())
        skip();
    char log[512], url[600], record[512];
    path(log, sizeof log, "heap.lcm");
    path(record, sizeof record, "heap_record.lcm");
    snprintf(url, sizeof url, "file://%s", log);
    heap_run(url, true, record, 1);
    /* Every frame was recorded. */
    FILE *f = fopen(record, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fclose(f);
    assert_true(size > 1000L * OW * OH);
    remove(record);
}

static void test_no_heap_calls_memq(void **state)
{
    if (!heapcount_active())
        skip();
    heap_run("memq://", false, NULL, 1);
}

/* realtime.threads = 2: the grasp thread makes no heap call either (file://
 * with images and the overlay, which read its grey image and result). */
static void test_no_heap_calls_two_threads(void **state)
{
    if (!heapcount_active())
        skip();
    char log[512], url[600];
    path(log, sizeof log, "heap2.lcm");
    snprintf(url, sizeof url, "file://%s", log);
    heap_run(url, true, NULL, 2);
    heap_run("memq://", false, NULL, 2);
}

/* ---- realtime.threads = 2 publishes what one thread does ---- */

#define CLIP_FRAMES 44 /* the recorded clip twice: the grasp defaults, then the tutorial's form */

/* The next lane or grasp message of a log (NULL at its end). */
static lcm_eventlog_event_t *next_result(lcm_eventlog_t *log)
{
    lcm_eventlog_event_t *e;
    while ((e = lcm_eventlog_read_next_event(log)) && strcmp(e->channel, "RTEDGE_LANES") &&
           strcmp(e->channel, "RTEDGE_GRASP"))
        lcm_eventlog_free_event(e);
    return e;
}

static void untimed(rtedge_header_t *h)
{
    h->utime = h->capture_utime = h->publish_utime = 0;
    h->latency_us = 0;
    h->deadline_met = 0;
}

/* e's message encoded again without its timing fields into buf (of
 * e->datalen bytes): the encoded size. Counts lanes found and objects. */
static int untimed_encoding(const lcm_eventlog_event_t *e, uint8_t *buf, int *lanes, int *objects)
{
    int n;
    if (!strcmp(e->channel, "RTEDGE_LANES")) {
        rtedge_lane_detection_t m;
        assert_true(rtedge_lane_detection_t_decode(e->data, 0, e->datalen, &m) > 0);
        untimed(&m.header);
        *lanes += m.left.found + m.right.found;
        n = rtedge_lane_detection_t_encode(buf, 0, e->datalen, &m);
        rtedge_lane_detection_t_decode_cleanup(&m);
    } else {
        rtedge_grasp_detection_t m;
        assert_true(rtedge_grasp_detection_t_decode(e->data, 0, e->datalen, &m) > 0);
        untimed(&m.header);
        *objects += m.nobjects;
        n = rtedge_grasp_detection_t_encode(buf, 0, e->datalen, &m);
        rtedge_grasp_detection_t_decode_cleanup(&m);
    }
    assert_true(n > 0);
    return n;
}

/* The clip on `threads` threads into log; after its first pass the grasp
 * path switches to the tutorial's form (binarize = otsu, split = false)
 * between two frames, as params_t or SIGHUP would. */
static void clip_run(int threads, const char *log)
{
    char url[600], msg[RTED_MSG];
    snprintf(url, sizeof url, "file://%s", log);
    remove(log);
    rted_config c;
    base_config(&c, clip_y4m, url);
    c.loop = true;
    c.max_frames = CLIP_FRAMES;
    c.rt_threads = threads;
    rted_daemon *d = open_daemon(&c, NULL);
    assert_int_equal(d->threaded, threads == 2);
    rted_step st;
    int frames = 0;
    while ((st = rted_daemon_step(d)) != RTED_STEP_END) {
        assert_int_not_equal(st, RTED_STEP_FAILED);
        if (st == RTED_STEP_FRAME && ++frames == CLIP_FRAMES / 2) {
            rted_config next = *rted_daemon_config(d);
            assert_true(rted_config_set_text(&next, rted_config_find_key("grasp.binarize"), "otsu",
                                             msg, sizeof msg));
            next.grasp_split = false;
            assert_true(rted_daemon_apply(d, &next, msg, sizeof msg));
        }
    }
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    rted_daemon_close(d);
    assert_int_equal(n.processed, CLIP_FRAMES);
    assert_int_equal(n.stages_skipped, 0);
    assert_int_equal(n.path_errors, 0);
    assert_int_equal(n.reloads, 1);
}

static void test_two_threads_same_messages(void **state)
{
    char log1[512], log2[512];
    path(log1, sizeof log1, "threads1.lcm");
    path(log2, sizeof log2, "threads2.lcm");
    clip_run(1, log1);
    clip_run(2, log2);
    lcm_eventlog_t *a = lcm_eventlog_create(log1, "r"), *b = lcm_eventlog_create(log2, "r");
    assert_non_null(a);
    assert_non_null(b);
    int count[2] = {0, 0}, lanes[2] = {0, 0}, objects[2] = {0, 0};
    lcm_eventlog_event_t *ea, *eb;
    for (;;) {
        ea = next_result(a);
        eb = next_result(b);
        if (!ea || !eb)
            break;
        assert_string_equal(ea->channel, eb->channel);
        uint8_t *ba = malloc((size_t)ea->datalen), *bb = malloc((size_t)eb->datalen);
        assert_true(ba && bb);
        const int na = untimed_encoding(ea, ba, &lanes[0], &objects[0]);
        const int nb = untimed_encoding(eb, bb, &lanes[1], &objects[1]);
        const bool same = na == nb && !memcmp(ba, bb, (size_t)na);
        if (!same)
            print_error("%s message %d differs (%d and %d bytes)\n", ea->channel,
                        count[ea->channel[7] == 'G'], na, nb);
        assert_true(same);
        count[ea->channel[7] == 'G']++;
        free(ba);
        free(bb);
        lcm_eventlog_free_event(ea);
        lcm_eventlog_free_event(eb);
    }
    const bool both_ended = !ea && !eb; /* the same number of messages */
    if (ea)
        lcm_eventlog_free_event(ea);
    if (eb)
        lcm_eventlog_free_event(eb);
    lcm_eventlog_destroy(a);
    lcm_eventlog_destroy(b);
    print_message("two threads: %d lane and %d grasp messages as one thread's (%d lanes found, "
                  "%d objects)\n",
                  count[0], count[1], lanes[1], objects[1]);
    assert_true(both_ended);
    assert_int_equal(count[0], CLIP_FRAMES);
    assert_int_equal(count[1], CLIP_FRAMES);
    assert_true(lanes[1] > CLIP_FRAMES);
    assert_true(objects[1] > 0);
    remove(log1);
    remove(log2);
}

int main(int argc, char **argv)
{
    build_dir = argc > 1 ? argv[1] : ".";
    clip_y4m = argc > 2 ? argv[2] : "fixtures/solidWhiteRight_clip.y4m";
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memq_road_lanes),
        cmocka_unit_test(test_memq_objects),
        cmocka_unit_test(test_grasp_workspace),
        cmocka_unit_test(test_grasp_colour),
        cmocka_unit_test(test_deadline_accounting),
        cmocka_unit_test(test_damaged_frames),
        cmocka_unit_test(test_file_log),
        cmocka_unit_test(test_images_source),
        cmocka_unit_test(test_lcm_log_source),
        cmocka_unit_test(test_reload),
        cmocka_unit_test(test_params_channel),
        cmocka_unit_test(test_loop_rewinds_quietly),
        cmocka_unit_test(test_run_latency),
        cmocka_unit_test(test_loop_without_good_frame),
        cmocka_unit_test(test_path_errors),
        cmocka_unit_test(test_camera_waited_for),
        cmocka_unit_test(test_no_heap_calls_file),
        cmocka_unit_test(test_no_heap_calls_memq),
        cmocka_unit_test(test_no_heap_calls_two_threads),
        cmocka_unit_test(test_two_threads_same_messages),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
