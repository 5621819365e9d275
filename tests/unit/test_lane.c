/* Lane pipeline (include/rtedge/lane.h) and the Y4M reader it is fed from.
 *
 * Small drawn roads check the geometry, the colour cue, the tracker and the
 * runtime parameters; the synthetic sequences of tools/make_road_fixtures.py
 * (generated into the build directory, passed as argv[1]) check accuracy
 * and tracking against their known lines; the 17 real road photos check the
 * bottom-row x of each lane against values read by eye. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "unit.h"

#include "rtedge/color.h"
#include "rtedge/imageio.h"
#include "rtedge/lane.h"
#include "rtedge/y4m.h"

static const char *g_roads_dir = ".";

/* ---- drawn roads ---- */

/* A road of w x h (stride w + pad, padding 0xEE): background `road`, lane
 * markings from (xl, h-1) and (xr, h-1) to (xlt, yt) and (xrt, yt), `half`
 * pixels either side of the centre line at the bottom, narrowing to 1. */
typedef struct drawn_lane {
    int32_t xb, xt; /* centre x at the bottom row and at row yt */
    bool present;
} drawn_lane;

static void draw_road(rte_image_u8 *img, uint8_t road, uint8_t paint, int32_t yt,
                      const drawn_lane *l, int32_t nl)
{
    const int32_t h = img->height;
    for (int32_t y = 0; y < h; y++) {
        uint8_t *row = rte_u8_row(img, y);
        memset(row, road, (size_t)img->width);
        if (y < yt - 10)
            continue;
        for (int32_t i = 0; i < nl; i++) {
            if (!l[i].present)
                continue;
            /* centre x at row y in 1/256 px, half width 1..4 px */
            const int64_t num = (int64_t)(l[i].xt - l[i].xb) * (h - 1 - y);
            const int64_t xc = (int64_t)l[i].xb * 256 + num * 256 / (h - 1 - yt);
            const int32_t hw = 1 + 3 * y / h;
            const int32_t x0 = (int32_t)((xc >> 8) - hw), x1 = (int32_t)((xc >> 8) + hw);
            for (int32_t x = x0 < 0 ? 0 : x0; x <= x1 && x < img->width; x++)
                row[x] = paint;
        }
    }
}

static rte_lane_context *make_ctx(int32_t w, int32_t h, rte_lane_config *cfg)
{
    rte_lane_config local;
    if (!cfg)
        cfg = &local;
    rte_lane_config_default(cfg, w, h);
    rte_lane_context *ctx = NULL;
    assert_int_equal(rte_lane_create(cfg, &ctx), RTE_OK);
    assert_non_null(ctx);
    return ctx;
}

static void assert_lane_near(const rte_lane *l, double xb, double xt, double tol_b, double tol_t)
{
    assert_true(l->found);
    const double b = l->x_bottom_q8 / 256.0, t = l->x_top_q8 / 256.0;
    if (b < xb - tol_b || b > xb + tol_b || t < xt - tol_t || t > xt + tol_t)
        fail_msg("lane at %.2f..%.2f, expected %.2f..%.2f", b, t, xb, xt);
}

static void test_arguments(void **state)
{
    (void)state;
    rte_lane_config cfg;
    rte_lane_context *ctx = NULL;
    assert_int_equal(rte_lane_create(NULL, &ctx), RTE_ERR_ARGUMENT);
    assert_null(ctx);
    rte_lane_config_default(&cfg, 64, 48);
    assert_int_equal(rte_lane_create(&cfg, NULL), RTE_ERR_ARGUMENT);
    cfg.max_width = 0;
    assert_int_equal(rte_lane_create(&cfg, &ctx), RTE_ERR_ARGUMENT);
    rte_lane_config_default(&cfg, 64, 48);
    cfg.max_segments = 0;
    assert_int_equal(rte_lane_create(&cfg, &ctx), RTE_ERR_ARGUMENT);
    rte_lane_config_default(&cfg, 64, 48);
    cfg.blur_ksize = 4;
    assert_int_equal(rte_lane_create(&cfg, &ctx), RTE_ERR_ARGUMENT);
    rte_lane_config_default(&cfg, 64, 48);
    cfg.params.roi_count = 2;
    assert_int_equal(rte_lane_create(&cfg, &ctx), RTE_ERR_ARGUMENT);
    assert_null(ctx);

    ctx = make_ctx(64, 48, &cfg);
    rte_lane_params p = cfg.params;
    p.canny_low = 200;
    p.canny_high = 100;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p = cfg.params;
    p.alpha_q8 = 0;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    p = cfg.params;
    p.left_max_slope_q8 = p.left_min_slope_q8 - 1;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_lane_set_params(NULL, &p), RTE_ERR_ARGUMENT);

    rte_lane_result r;
    rte_image_u8 big = unit_image_u8(65, 48, 0, 0);
    assert_int_equal(rte_lane_process_gray(ctx, &big, NULL, 0, &r), RTE_ERR_SIZE);
    test_free(big.buf);
    rte_image_u8 g = unit_image_u8(64, 48, 3, 90);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_lane_process_gray(NULL, &g, NULL, 0, &r), RTE_ERR_ARGUMENT);
    uint8_t bgrbuf[64 * 3 * 47];
    rte_image_u8c3 bgr = {64, 47, 64 * 3, bgrbuf};
    assert_int_equal(rte_lane_process_gray(ctx, &g, &bgr, 0, &r), RTE_ERR_SIZE);
    /* An ROI entirely outside the frame. */
    p = cfg.params;
    for (int i = 0; i < p.roi_count; i++)
        p.roi[i].x += 2 * RTE_POLYGON_FRACTION_ONE;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_ERR_ARGUMENT);
    unit_assert_padding_u8(&g);
    test_free(g.buf);
    rte_lane_destroy(ctx);
    rte_lane_destroy(NULL);
}

/* Tiny and thin frames: a clean status, no lanes, nothing written outside. */
static void test_tiny_frames(void **state)
{
    (void)state;
    rte_lane_context *ctx = make_ctx(67, 67, NULL);
    const int32_t sizes[][2] = {{1, 1},  {1, 9},  {9, 1},  {2, 2}, {3, 3},
                                {67, 1}, {1, 67}, {5, 67}, {67, 5}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        rte_image_u8 g = unit_image_u8(sizes[i][0], sizes[i][1], 5, 255);
        rte_lane_result r;
        rte_status st = rte_lane_process_gray(ctx, &g, NULL, 0, &r);
        assert_true(st == RTE_OK || st == RTE_ERR_ARGUMENT);
        if (st == RTE_OK) {
            assert_false(r.lane[0].found);
            assert_false(r.lane[1].found);
        }
        unit_assert_padding_u8(&g);
        test_free(g.buf);
    }
    rte_lane_destroy(ctx);
}

/* Two drawn lanes on a 320x180 frame (stride > width). */
static void test_drawn_lanes(void **state)
{
    (void)state;
    const int32_t w = 320, h = 180, yt = 108; /* default ROI top: 0.6 * 180 */
    rte_lane_config cfg;
    rte_lane_context *ctx = make_ctx(w, h, &cfg);
    rte_image_u8 g = unit_image_u8(w, h, 13, 0);
    const drawn_lane lanes[2] = {{40, 150, true}, {300, 175, true}};
    draw_road(&g, 70, 230, yt, lanes, 2);
    rte_lane_result r;
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 1234, &r), RTE_OK);
    assert_int_equal(r.t_ns, 1234);
    assert_lane_near(&r.lane[RTE_LANE_LEFT], 40, 150, 2, 2);
    assert_lane_near(&r.lane[RTE_LANE_RIGHT], 300, 175, 2, 2);
    assert_int_equal(r.lane[0].y_bottom, h - 1);
    assert_int_equal(r.lane[0].y_top, yt);
    assert_false(r.lane[0].predicted);
    assert_true(r.lane[0].confidence_permille > 500);
    /* lane centre 170 vs image centre 159.5: positive offset, lane width 260 */
    assert_true(r.centre_valid);
    assert_true(r.offset_q8 > 9 * 256 && r.offset_q8 < 12 * 256);
    assert_true(r.offset_permille > 30 && r.offset_permille < 47);
    /* the centre line leans right going up: (162.5 - 170) is left, negative */
    assert_true(r.heading_mrad < 0 && r.heading_tan_q16 < 0);
    int32_t left = 0, right = 0;
    for (int32_t i = 0; i < r.segment_count; i++) {
        left += r.segments[i].use == RTE_LANE_SEG_LEFT;
        right += r.segments[i].use == RTE_LANE_SEG_RIGHT;
    }
    assert_true(left > 0 && right > 0);
    assert_false(r.truncated);
    for (int i = 0; i < RTE_LANE_STAGES; i++)
        assert_true(r.stage_ns[i] >= 0);

    /* Mirrored: the offset changes sign. */
    rte_lane_reset(ctx);
    const drawn_lane mirrored[2] = {{319 - 300, 319 - 175, true}, {319 - 40, 319 - 150, true}};
    draw_road(&g, 70, 230, yt, mirrored, 2);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_lane_near(&r.lane[RTE_LANE_LEFT], 19, 144, 2, 2);
    assert_lane_near(&r.lane[RTE_LANE_RIGHT], 279, 169, 2, 2);
    assert_true(r.offset_q8 < -9 * 256 && r.heading_mrad > 0);

    /* The Theil-Sen fit finds them too (within a marking's half width). */
    rte_lane_params p = cfg.params;
    p.fit = RTE_LANE_FIT_THEIL_SEN;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    rte_lane_reset(ctx);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_lane_near(&r.lane[RTE_LANE_LEFT], 19, 144, 4, 3);
    assert_lane_near(&r.lane[RTE_LANE_RIGHT], 279, 169, 4, 3);

    /* Few segments allowed: the list is cut and says so. */
    rte_lane_destroy(ctx);
    cfg.max_segments = 1;
    assert_int_equal(rte_lane_create(&cfg, &ctx), RTE_OK);
    assert_non_null(ctx);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_int_equal(r.segment_count, 1);
    assert_true(r.truncated);
    unit_assert_padding_u8(&g);
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* Glare lowers the confidence, not the lanes: the same bright block on the
 * road between them, at 249 (not glare) and at 255 (glare), rows y0..h-1. */
static void glare_run(rte_lane_context *ctx, rte_image_u8 *g, int32_t y0, uint8_t level,
                      rte_lane_result *r)
{
    const int32_t yt = 108;
    const drawn_lane lanes[2] = {{40, 150, true}, {300, 175, true}};
    draw_road(g, 70, 230, yt, lanes, 2);
    for (int32_t y = y0; y < g->height; y++)
        memset(rte_u8_row(g, y) + 110, level, 100);
    rte_lane_reset(ctx);
    assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    assert_lane_near(&r->lane[RTE_LANE_LEFT], 40, 150, 2, 2);
    assert_lane_near(&r->lane[RTE_LANE_RIGHT], 300, 175, 2, 2);
}

static void test_glare_confidence(void **state)
{
    (void)state;
    rte_lane_context *ctx = make_ctx(320, 180, NULL);
    rte_image_u8 g = unit_image_u8(320, 180, 13, 0);
    rte_lane_result dim, glare;
    /* 100 x 12 px: about a tenth of the ROI */
    glare_run(ctx, &g, 168, 249, &dim);
    glare_run(ctx, &g, 168, 255, &glare);
    for (int side = 0; side < 2; side++) {
        assert_int_equal(dim.lane[side].confidence_permille, 1000);
        assert_in_range(glare.lane[side].confidence_permille, 400, 800);
    }
    /* 100 x 40 px: over a quarter of it, nothing left */
    glare_run(ctx, &g, 140, 249, &dim);
    glare_run(ctx, &g, 140, 255, &glare);
    for (int side = 0; side < 2; side++) {
        assert_int_equal(dim.lane[side].confidence_permille, 1000);
        assert_int_equal(glare.lane[side].confidence_permille, 0);
        assert_true(glare.lane[side].found);
    }
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* Near-horizontal lines and lines with the wrong slope sign for their side
 * are rejected. */
static void test_slope_filter(void **state)
{
    (void)state;
    const int32_t w = 320, h = 180;
    rte_lane_context *ctx = make_ctx(w, h, NULL);
    rte_image_u8 g = unit_image_u8(w, h, 0, 70);
    /* a near-horizontal bar (slope 0.1) across the lower half */
    for (int32_t x = 20; x < 300; x++)
        for (int32_t t = -2; t <= 2; t++)
            rte_u8_row(&g, 150 + (x - 20) / 10 + t)[x] = 230;
    /* a right-leaning line on the left half: positive slope, wrong side */
    const drawn_lane wrong[1] = {{150, 60, true}};
    rte_image_u8 tmp = unit_image_u8(w, h, 0, 70);
    draw_road(&tmp, 70, 230, 108, wrong, 1);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++)
            if (rte_u8_row(&tmp, y)[x] == 230)
                rte_u8_row(&g, y)[x] = 230;
    rte_lane_result r;
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_false(r.lane[0].found);
    assert_false(r.lane[1].found);
    assert_true(r.segment_count > 0);
    for (int32_t i = 0; i < r.segment_count; i++)
        assert_int_equal(r.segments[i].use, RTE_LANE_SEG_REJECTED_SLOPE);
    test_free(tmp.buf);
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* A 320x180 road: a yellow line whose grey equals the road's on the left,
 * a white one on the right, into bgr (B,G,R) and rgb (R,G,B, may be NULL). */
static void colour_road(int32_t w, int32_t h, uint8_t *bgr, uint8_t *rgb)
{
    /* yellow B=0 G=185 R=205: grey (19235*185 + 9798*205 + 16384) >> 15 = 170 */
    const uint8_t yellow[3] = {0, 185, 205}, road[3] = {170, 170, 170}, white[3] = {255, 255, 255};
    rte_image_u8 mark = unit_image_u8(w, h, 0, 0);
    const drawn_lane lanes[2] = {{40, 150, true}, {300, 175, false}};
    const drawn_lane right[2] = {{40, 150, false}, {300, 175, true}};
    draw_road(&mark, 0, 1, 108, lanes, 2);
    rte_image_u8 mark_r = unit_image_u8(w, h, 0, 0);
    draw_road(&mark_r, 0, 1, 108, right, 2);
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            const uint8_t *c = rte_u8_row(&mark, y)[x]     ? yellow
                               : rte_u8_row(&mark_r, y)[x] ? white
                                                           : road;
            uint8_t *d = bgr + ((size_t)y * w + x) * 3;
            d[0] = c[0], d[1] = c[1], d[2] = c[2];
            if (rgb) {
                uint8_t *e = rgb + ((size_t)y * w + x) * 3;
                e[0] = c[2], e[1] = c[1], e[2] = c[0];
            }
        }
    test_free(mark.buf);
    test_free(mark_r.buf);
}

/* A yellow line whose grey equals the road's is invisible in grey; the
 * colour cue finds it, and rte_lane_process gives the same for BGR24 and
 * RGB24 frames. */
static void test_color_cue(void **state)
{
    (void)state;
    const int32_t w = 320, h = 180;
    rte_lane_context *ctx = make_ctx(w, h, NULL);
    uint8_t *bgr = test_malloc((size_t)w * h * 3), *rgb = test_malloc((size_t)w * h * 3);
    colour_road(w, h, bgr, rgb);
    rte_image_u8c3 bgr_img = {w, h, w * 3, bgr};
    rte_image_u8 g = unit_image_u8(w, h, 0, 0);
    assert_int_equal(rte_color_bgr_to_gray(&bgr_img, &g), RTE_OK);
    rte_lane_result r;
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_false(r.lane[RTE_LANE_LEFT].found); /* grey only: nothing to see */
    assert_true(r.lane[RTE_LANE_RIGHT].found);
    rte_lane_reset(ctx);
    assert_int_equal(rte_lane_process_gray(ctx, &g, &bgr_img, 0, &r), RTE_OK);
    assert_lane_near(&r.lane[RTE_LANE_LEFT], 40, 150, 2, 2);
    assert_lane_near(&r.lane[RTE_LANE_RIGHT], 300, 175, 2, 2);
    const int32_t xl = r.lane[0].x_bottom_q8, xr = r.lane[1].x_bottom_q8;

    rte_frame f = {RTE_PIXEL_BGR24, w, h, {bgr, NULL}, {w * 3, 0}};
    rte_lane_reset(ctx);
    assert_int_equal(rte_lane_process(ctx, &f, 0, &r), RTE_OK);
    assert_int_equal(r.lane[0].x_bottom_q8, xl);
    assert_int_equal(r.lane[1].x_bottom_q8, xr);
    f.format = RTE_PIXEL_RGB24;
    f.plane[0] = rgb;
    rte_lane_reset(ctx);
    assert_int_equal(rte_lane_process(ctx, &f, 0, &r), RTE_OK);
    assert_int_equal(r.lane[0].x_bottom_q8, xl);
    assert_int_equal(r.lane[1].x_bottom_q8, xr);
    /* A grey frame: the grey path. */
    rte_frame fg = {RTE_PIXEL_GREY, w, h, {g.buf, NULL}, {g.stride, 0}};
    rte_lane_reset(ctx);
    assert_int_equal(rte_lane_process(ctx, &fg, 0, &r), RTE_OK);
    assert_false(r.lane[RTE_LANE_LEFT].found);
    test_free(bgr);
    test_free(rgb);
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* Full-range BT.601 (JPEG) Y of a B,G,R pixel, and its Cb and Cr in
 * 1/65536 added to *cb, *cr (a block's sums). */
static void ycc_of(const uint8_t *c, int32_t *y, int32_t *cb, int32_t *cr)
{
    const int32_t b = c[0], g = c[1], r = c[2];
    *y = (19595 * r + 38470 * g + 7471 * b + 32768) >> 16;
    *cb += 128 * 65536 - 11059 * r - 21709 * g + 32768 * b;
    *cr += 128 * 65536 + 32768 * r - 27439 * g - 5329 * b;
}

/* The rounded mean of n values summed in 1/65536. */
static uint8_t chroma_mean(int32_t sum, int32_t n)
{
    const int32_t v = (sum / n + 32768) >> 16;
    return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* The road of test_color_cue as NV12, YUYV and UYVY (chroma of each 2x2 or
 * 2x1 block averaged; even sizes): rte_lane_process finds the yellow line
 * from the chroma, with the default ROI (its crop from row 108, column 0)
 * and with one whose crop starts on row 107 and column 1, the second pixel
 * of a chroma block; not with the colour cue off. */
static void test_color_cue_yuv(void **state)
{
    (void)state;
    const int32_t w = 320, h = 180;
    uint8_t *bgr = test_malloc((size_t)w * h * 3), *nv12 = test_malloc((size_t)w * h * 3 / 2);
    uint8_t *yuyv = test_malloc((size_t)w * h * 2), *uyvy = test_malloc((size_t)w * h * 2);
    colour_road(w, h, bgr, NULL);
    for (int32_t y = 0; y < h; y += 2)
        for (int32_t x = 0; x < w; x += 2) {
            int32_t cb = 0, cr = 0, luma[2][2];
            int32_t row_cb[2] = {0, 0}, row_cr[2] = {0, 0};
            for (int32_t j = 0; j < 2; j++)
                for (int32_t i = 0; i < 2; i++) {
                    int32_t pcb = 0, pcr = 0;
                    ycc_of(bgr + ((size_t)(y + j) * w + x + i) * 3, &luma[j][i], &pcb, &pcr);
                    cb += pcb, cr += pcr, row_cb[j] += pcb, row_cr[j] += pcr;
                    nv12[(size_t)(y + j) * w + x + i] = (uint8_t)luma[j][i];
                }
            nv12[(size_t)w * h + (size_t)(y / 2) * w + x] = chroma_mean(cb, 4);
            nv12[(size_t)w * h + (size_t)(y / 2) * w + x + 1] = chroma_mean(cr, 4);
            for (int32_t j = 0; j < 2; j++) {
                uint8_t *p = yuyv + (size_t)(y + j) * w * 2 + (size_t)x * 2;
                uint8_t *q = uyvy + (size_t)(y + j) * w * 2 + (size_t)x * 2;
                const uint8_t u = chroma_mean(row_cb[j], 2), v = chroma_mean(row_cr[j], 2);
                p[0] = (uint8_t)luma[j][0], p[1] = u, p[2] = (uint8_t)luma[j][1], p[3] = v;
                q[0] = u, q[1] = (uint8_t)luma[j][0], q[2] = v, q[3] = (uint8_t)luma[j][1];
            }
        }
    const rte_frame frames[3] = {{RTE_PIXEL_NV12, w, h, {nv12, nv12 + (size_t)w * h}, {w, w}},
                                 {RTE_PIXEL_YUYV, w, h, {yuyv, NULL}, {2 * w, 0}},
                                 {RTE_PIXEL_UYVY, w, h, {uyvy, NULL}, {2 * w, 0}}};
    for (int odd = 0; odd < 2; odd++) {
        rte_lane_config cfg;
        rte_lane_context *ctx = make_ctx(w, h, &cfg);
        rte_lane_params p = cfg.params;
        if (odd) { /* x 205/65536 of 320 = 1, y 38958/65536 of 180 = 107 */
            p.roi[0].x = 205;
            p.roi[1].y = p.roi[2].y = 38958;
            assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
        }
        rte_lane_result r;
        for (int k = 0; k < 3; k++) {
            rte_lane_reset(ctx);
            assert_int_equal(rte_lane_process(ctx, &frames[k], 0, &r), RTE_OK);
            assert_int_equal(r.edges_x0, odd ? 1 : 0);
            assert_int_equal(r.edges_y0, odd ? 107 : 108);
            /* a pixel wider than from B,G,R: chroma blocks straddle the edges */
            assert_lane_near(&r.lane[RTE_LANE_LEFT], 40, 150, 2, 3);
            assert_lane_near(&r.lane[RTE_LANE_RIGHT], 300, 175, 2, 3);
        }
        p.use_color = false;
        assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
        for (int k = 0; k < 3; k++) {
            rte_lane_reset(ctx);
            assert_int_equal(rte_lane_process(ctx, &frames[k], 0, &r), RTE_OK);
            assert_false(r.lane[RTE_LANE_LEFT].found); /* grey only: nothing to see */
            assert_true(r.lane[RTE_LANE_RIGHT].found);
        }
        rte_lane_destroy(ctx);
    }
    test_free(bgr);
    test_free(nv12);
    test_free(yuyv);
    test_free(uyvy);
}

/* Two lanes on a 320x180 road, tracked over four frames. */
typedef struct tracked_road {
    rte_lane_config cfg;
    rte_lane_context *ctx;
    rte_image_u8 g;
    drawn_lane lanes[2];
    rte_lane_result r;
} tracked_road;

static void track_two_lanes(tracked_road *t)
{
    t->ctx = make_ctx(320, 180, &t->cfg);
    t->g = unit_image_u8(320, 180, 0, 0);
    t->lanes[0] = (drawn_lane){40, 150, true};
    t->lanes[1] = (drawn_lane){300, 175, true};
    for (int k = 0; k < 4; k++) {
        draw_road(&t->g, 70, 230, 108, t->lanes, 2);
        assert_int_equal(rte_lane_process_gray(t->ctx, &t->g, NULL, k, &t->r), RTE_OK);
        assert_lane_near(&t->r.lane[1], 300, 175, 2, 2);
    }
}

/* A lane whose marking disappears is held as predicted for hold_frames,
 * then dropped; a small shift is damped, a jump off the paint taken. */
static void test_tracking(void **state)
{
    (void)state;
    tracked_road t;
    track_two_lanes(&t);
    rte_lane_context *ctx = t.ctx;
    rte_image_u8 *g = &t.g;
    drawn_lane *lanes = t.lanes;
    rte_lane_result *r = &t.r;
    lanes[1].present = false;
    draw_road(g, 70, 230, 108, lanes, 2);
    for (int k = 0; k < t.cfg.params.hold_frames; k++) {
        assert_int_equal(rte_lane_process_gray(ctx, g, NULL, k, r), RTE_OK);
        assert_true(r->lane[1].found);
        assert_true(r->lane[1].predicted);
        assert_int_equal(r->lane[1].lost_frames, k + 1);
        assert_lane_near(&r->lane[1], 300, 175, 2, 2);
        assert_false(r->lane[0].predicted);
    }
    assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    assert_false(r->lane[1].found);
    assert_false(r->centre_valid);
    /* Re-acquired; then a shift of 6 px at the bottom, within the
     * marking's band, is damped (taken in steps), and a jump of 30 px,
     * which leaves the tracked lane on bare road, is taken at once. */
    lanes[1].present = true;
    draw_road(g, 70, 230, 108, lanes, 2);
    assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    assert_lane_near(&r->lane[1], 300, 175, 2, 2);
    lanes[1].xb = 294;
    draw_road(g, 70, 230, 108, lanes, 2);
    rte_lane_params p = t.cfg.params;
    p.gate_px = 100; /* let the jumped line through the gate */
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    const double b = r->lane[1].x_bottom_q8 / 256.0;
    assert_true(b < 299 && b > 295); /* moved towards 294, not all the way */
    for (int k = 0; k < 20; k++)
        assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    assert_lane_near(&r->lane[1], 294, 175, 2, 2);
    lanes[1].xb = 264;
    draw_road(g, 70, 230, 108, lanes, 2);
    assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    assert_false(r->lane[1].predicted);
    assert_lane_near(&r->lane[1], 264, 175, 2, 2);
    /* Without the gate widened, a far line is ignored: segments marked. */
    assert_int_equal(rte_lane_set_params(ctx, &t.cfg.params), RTE_OK);
    lanes[1].xb = 200;
    lanes[1].xt = 200;
    draw_road(g, 70, 230, 108, lanes, 2);
    assert_int_equal(rte_lane_process_gray(ctx, g, NULL, 0, r), RTE_OK);
    assert_true(r->lane[1].predicted);
    test_free(g->buf);
    rte_lane_destroy(ctx);
}

/* A tracked side whose marking shows up outside the gate: a stripe there
 * restarts the lane at once (found, not predicted); a plain edge there (a
 * shadow's border: no paint) leaves it held. */
static void test_reacquire(void **state)
{
    (void)state;
    tracked_road t;
    track_two_lanes(&t);
    assert_true(t.cfg.params.gate_px < 50);
    /* the right edge of the road: a bright step, no stripe */
    t.lanes[1] = (drawn_lane){265, 145, false};
    draw_road(&t.g, 70, 230, 108, t.lanes, 2);
    for (int32_t y = 98; y < 180; y++) {
        const int32_t x0 = 265 + (145 - 265) * (179 - y) / (179 - 108);
        for (int32_t x = x0 < 0 ? 0 : x0; x < 320; x++)
            rte_u8_row(&t.g, y)[x] = 160;
    }
    assert_int_equal(rte_lane_process_gray(t.ctx, &t.g, NULL, 0, &t.r), RTE_OK);
    assert_true(t.r.lane[1].found && t.r.lane[1].predicted);
    assert_lane_near(&t.r.lane[1], 300, 175, 2, 2);
    /* the marking 35 px in (30 at the top): taken whole, in this frame */
    t.lanes[1].present = true;
    draw_road(&t.g, 70, 230, 108, t.lanes, 2);
    assert_int_equal(rte_lane_process_gray(t.ctx, &t.g, NULL, 0, &t.r), RTE_OK);
    assert_false(t.r.lane[1].predicted);
    assert_lane_near(&t.r.lane[1], 265, 145, 2, 2);
    assert_lane_near(&t.r.lane[0], 40, 150, 2, 2);
    assert_int_equal(rte_lane_process_gray(t.ctx, &t.g, NULL, 0, &t.r), RTE_OK);
    assert_lane_near(&t.r.lane[1], 265, 145, 2, 2);
    test_free(t.g.buf);
    rte_lane_destroy(t.ctx);
}

/* Rows y0..y1 of a 5 px stripe of value v on tracked_road's frame, along
 * the line from x = xb on its bottom row to x = xt on row 108. */
static void paint_stripe(rte_image_u8 *g, int32_t xb, int32_t xt, int32_t y0, int32_t y1, uint8_t v)
{
    for (int32_t y = y0; y <= y1; y++) {
        const int32_t xc = xb + (xt - xb) * (179 - y) / (179 - 108);
        for (int32_t x = xc - 2; x <= xc + 2; x++)
            rte_u8_row(g, y)[x] = v;
    }
}

/* A tracked side that its gated segments show on little paint (a dash of
 * the old marking left inside the gate: 8 of the lane's 72 rows, more
 * than the sixteenth that counts as seen, fewer than an eighth) while the
 * marking has moved out of the gate: all its segments, fitted without the
 * tracked slope, show the marking on more rows and restart the lane there
 * (without the refit it stays on the dash, at confidence 0; a dash of 6
 * rows or fewer is not seen, and re-acquisition takes the marking). */
static void test_weak_side_refit(void **state)
{
    (void)state;
    tracked_road t;
    track_two_lanes(&t);
    t.lanes[1] = (drawn_lane){265, 145, true};
    draw_road(&t.g, 70, 230, 108, t.lanes, 2);
    paint_stripe(&t.g, 300, 175, 171, 178, 230); /* the dash: the old marking's rows 171..178 */
    assert_int_equal(rte_lane_process_gray(t.ctx, &t.g, NULL, 0, &t.r), RTE_OK);
    assert_false(t.r.lane[1].predicted);
    assert_lane_near(&t.r.lane[1], 265, 145, 2, 2);
    /* the segments marked the right lane's are the new marking's; the
     * dash's are not */
    int32_t marked = 0;
    for (int32_t i = 0; i < t.r.segment_count; i++) {
        const rte_lane_segment *s = &t.r.segments[i];
        if (s->use != RTE_LANE_SEG_RIGHT)
            continue;
        marked++;
        for (int32_t e = 0; e < 2; e++) {
            const int32_t x = e ? s->x1 : s->x0, y = e ? s->y1 : s->y0;
            assert_in_range(x, 265 + (145 - 265) * (179 - y) / (179 - 108) - 6,
                            265 + (145 - 265) * (179 - y) / (179 - 108) + 6);
        }
    }
    assert_true(marked > 0);
    test_free(t.g.buf);
    rte_lane_destroy(t.ctx);
}

/* A tracked right marking gone and a dark stripe (a tar seam: edges, no
 * paint) outside the gate: the stripe's segments do not restart the lane,
 * which is held, and they stay marked as rejected by the gate. */
static void test_gated_stripe_marks(void **state)
{
    (void)state;
    tracked_road t;
    track_two_lanes(&t);
    t.lanes[1].present = false;
    draw_road(&t.g, 70, 230, 108, t.lanes, 2);
    paint_stripe(&t.g, 250, 170, 108, 179, 15);
    assert_int_equal(rte_lane_process_gray(t.ctx, &t.g, NULL, 0, &t.r), RTE_OK);
    assert_true(t.r.lane[1].predicted);
    int32_t gated = 0;
    for (int32_t i = 0; i < t.r.segment_count; i++) {
        assert_int_not_equal(t.r.segments[i].use, RTE_LANE_SEG_RIGHT);
        gated += t.r.segments[i].use == RTE_LANE_SEG_REJECTED_GATE;
    }
    assert_true(gated > 0);
    test_free(t.g.buf);
    rte_lane_destroy(t.ctx);
}

/* One frame (no tracking): a solid left marking, and on the right only
 * three dashes too short for the Hough search (4 rows each of the lane's
 * 72). The right side is found from the left one, on the line through
 * their vanishing point (rte_lane_partner), with no segment of its own;
 * without the dashes it is not found. */
static void test_partner_from_one_side(void **state)
{
    (void)state;
    const int32_t w = 320, h = 180, yt = 108;
    for (int dashes = 1; dashes >= 0; dashes--) {
        rte_lane_context *ctx = make_ctx(w, h, NULL);
        rte_image_u8 g = unit_image_u8(w, h, 8, 0);
        const drawn_lane lanes[2] = {{60, 150, true}, {0, 0, false}};
        draw_road(&g, 70, 230, yt, lanes, 2);
        if (dashes) {
            for (int32_t y = 160; y > 110; y -= 18)
                paint_stripe(&g, 280, 175, y, y + 3, 230);
        }
        rte_lane_result r;
        assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
        assert_lane_near(&r.lane[0], 60, 150, 3, 3);
        for (int32_t i = 0; i < r.segment_count; i++)
            assert_int_not_equal(r.segments[i].use, RTE_LANE_SEG_RIGHT);
        if (dashes) {
            assert_lane_near(&r.lane[1], 280, 175, 6, 4);
            assert_false(r.lane[1].predicted);
        } else {
            assert_false(r.lane[1].found);
        }
        unit_assert_padding_u8(&g);
        test_free(g.buf);
        rte_lane_destroy(ctx);
    }
}

/* Rows y0..y1 of a stripe (half-width 2) of value v along the line
 * through (x_vp, y_vp) and (xb, the bottom row). */
static void paint_ray(rte_image_u8 *g, double x_vp, double y_vp, double xb, int32_t y0, int32_t y1)
{
    const int32_t yb = g->height - 1;
    for (int32_t y = y0; y <= y1; y++) {
        const int32_t xc = (int32_t)(x_vp + (xb - x_vp) * (y - y_vp) / (yb - y_vp) + 0.5);
        for (int32_t x = xc - 2; x <= xc + 2; x++)
            rte_u8_row(g, y)[x] = 230;
    }
}

/* 640x360, both lanes tracked, the right marking never painted in the
 * lane's lowest quarter (so no lane width is held); then it turns about
 * the vanishing point (its bottom end 20 px left, its point on the horizon
 * kept) and shows only three dashes too short for the Hough search, the
 * highest inside the band searched along the prediction. The prediction
 * moved onto that dash is a translation, its bottom end 19 px right of the
 * marking, on paint on 6 rows; the side found from the left one through
 * the three dashes (14 rows) is the measurement instead. */
static void test_partner_replaces_held_dash(void **state)
{
    (void)state;
    const int32_t w = 640, h = 360, yt = 216;
    rte_lane_context *ctx = make_ctx(w, h, NULL);
    rte_image_u8 g = unit_image_u8(w, h, 0, 0);
    const drawn_lane lanes[2] = {{80, 300, true}, {0, 0, false}};
    /* the lanes meet where 80 + 220 d / 143 = 600 - 250 d / 143 */
    const double d = 520.0 * 143 / 470, y_vp = 359 - d, x_vp = 80 + 220 * d / 143;
    rte_lane_result r;
    for (int k = 0; k < 4; k++) {
        draw_road(&g, 70, 230, yt, lanes, 2);
        paint_ray(&g, x_vp, y_vp, 600, yt, 318); /* no paint in the lowest quarter */
        assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, k, &r), RTE_OK);
        assert_lane_near(&r.lane[1], 600, 350, 3, 3);
    }
    const double xb = 580;
    draw_road(&g, 70, 230, yt, lanes, 2);
    paint_ray(&g, x_vp, y_vp, xb, 220, 227);
    paint_ray(&g, x_vp, y_vp, xb, 262, 267);
    paint_ray(&g, x_vp, y_vp, xb, 310, 315);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 4, &r), RTE_OK);
    const double xt = x_vp + (xb - x_vp) * (yt - y_vp) / (359 - y_vp);
    /* the tracker takes a share of the measurement (580 -> 590.7; moved
     * onto the top dash: 598.7) */
    assert_lane_near(&r.lane[1], xb, xt, 12, 3);
    assert_false(r.lane[1].predicted);
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* Random roads, run under the sanitizers in CI: one solid marking and one
 * dashed, both meeting at a random point, moving between frames, on noise
 * with glare pixels, at random sizes, in sequences of 1 to 6 frames (the
 * searches for a side from the other, tracked and not, run on many). Every
 * call returns RTE_OK and every lane keeps its contract. */
static void test_random_roads(void **state)
{
    (void)state;
    uint32_t seed = 20261207;
    for (int it = 0; it < 300; it++) {
        const int32_t w = 16 + (int32_t)(unit_rand(&seed) % 400);
        const int32_t h = 16 + (int32_t)(unit_rand(&seed) % 300);
        rte_lane_config cfg;
        rte_lane_context *ctx = make_ctx(w, h, &cfg);
        rte_image_u8 g = unit_image_u8(w, h, 3, 0);
        const int32_t frames = 1 + (int32_t)(unit_rand(&seed) % 6);
        const int32_t x_vp = (int32_t)(unit_rand(&seed) % (uint32_t)w);
        const int32_t y_vp = (int32_t)(unit_rand(&seed) % (uint32_t)(h * 6 / 10));
        const int32_t x_solid = (int32_t)(unit_rand(&seed) % (uint32_t)w);
        int32_t x_dashed = (int32_t)(unit_rand(&seed) % (uint32_t)w);
        for (int32_t f = 0; f < frames; f++) {
            const uint32_t spread = 1 + unit_rand(&seed) % 40;
            for (int32_t y = 0; y < h; y++)
                for (int32_t x = 0; x < w; x++)
                    rte_u8_row(&g, y)[x] = (uint8_t)(60 + unit_rand(&seed) % spread);
            for (int32_t y = y_vp + 1; y < h; y++) {
                const int32_t xs = x_vp + (x_solid - x_vp) * (y - y_vp) / (h - 1 - y_vp);
                const int32_t xd = x_vp + (x_dashed - x_vp) * (y - y_vp) / (h - 1 - y_vp);
                for (int32_t x = xs - 2; x <= xs + 2; x++)
                    if (x >= 0 && x < w)
                        rte_u8_row(&g, y)[x] = 230;
                if ((y / 6) % 3 == 0)
                    for (int32_t x = xd - 2; x <= xd + 2; x++)
                        if (x >= 0 && x < w)
                            rte_u8_row(&g, y)[x] = 220;
            }
            if (unit_rand(&seed) % 5 == 0)
                for (int32_t k = 0; k < w * h / 3; k++)
                    g.buf[(unit_rand(&seed) % (uint32_t)h) * (uint32_t)g.stride +
                          unit_rand(&seed) % (uint32_t)w] = 255;
            rte_lane_result r;
            assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, f, &r), RTE_OK);
            assert_in_range(r.segment_count, 0, cfg.max_segments);
            for (int side = 0; side < 2; side++) {
                const rte_lane *l = &r.lane[side];
                if (!l->found)
                    continue;
                assert_int_equal(l->y_bottom, h - 1);
                assert_in_range(l->y_top, 0, h - 1);
                assert_in_range(l->confidence_permille, 0, 1000);
                assert_in_range(l->far_count, 0, RTE_LANE_FAR_POINTS);
            }
            x_dashed += (int32_t)(unit_rand(&seed) % 21) - 10;
        }
        unit_assert_padding_u8(&g);
        test_free(g.buf);
        rte_lane_destroy(ctx);
    }
}

/* Thresholds and ROI change at run time. */
static void test_runtime_params(void **state)
{
    (void)state;
    const int32_t w = 320, h = 180;
    rte_lane_config cfg;
    rte_lane_context *ctx = make_ctx(w, h, &cfg);
    rte_image_u8 g = unit_image_u8(w, h, 0, 0);
    const drawn_lane lanes[2] = {{40, 150, true}, {300, 175, true}};
    draw_road(&g, 70, 230, 90, lanes, 2);
    rte_lane_params p = cfg.params;
    p.canny_mode = RTE_LANE_CANNY_FIXED;
    p.canny_low = 40;
    p.canny_high = 120;
    const int32_t one = RTE_POLYGON_FRACTION_ONE;
    const rte_vertex roi[4] = {
        {0, one}, {one * 4 / 10, one / 2}, {one * 6 / 10, one / 2}, {one, one}};
    memcpy(p.roi, roi, sizeof roi);
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    rte_lane_result r;
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_int_equal(r.canny_low, 40);
    assert_int_equal(r.canny_high, 120);
    assert_int_equal(r.lane[0].y_top, 90);
    assert_lane_near(&r.lane[0], 40, 150, 2, 2);
    /* thresholds above any edge: nothing (the tracker holds the lanes) */
    p.canny_low = p.canny_high = 2040;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_int_equal(r.segment_count, 0);
    assert_true(r.lane[0].predicted);
    /* the Otsu rule */
    p.canny_mode = RTE_LANE_CANNY_OTSU;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
    assert_true(r.canny_high > 70 && r.canny_high <= 230 && r.canny_low == r.canny_high / 2);
    assert_false(r.lane[0].predicted);
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* ---- Y4M reader ---- */

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

static void test_y4m(void **state)
{
    (void)state;
    char path[] = "/tmp/rtedge_test_y4m_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    /* 3x2, 4:2:0 (chroma 2 * 2x1 = 4 bytes per frame), two frames */
    const char data[] = "YUV4MPEG2 W3 H2 F30:1 Ip A1:1 C420jpeg XYSCSS=420JPEG\n"
                        "FRAME\n\x01\x02\x03\x04\x05\x06"
                        "abcd"
                        "FRAME Ixyz\n\x11\x12\x13\x14\x15\x16"
                        "abcd";
    write_file(path, data, sizeof data - 1);
    rte_y4m_reader *rd;
    rte_y4m_info info;
    char msg[128];
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(info.width, 3);
    assert_int_equal(info.height, 2);
    assert_int_equal(info.fps_num, 30);
    assert_int_equal(info.chroma_bytes, 4);
    rte_image_u8 img = unit_image_u8(3, 2, 2, 0);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_OK);
    assert_int_equal(img.buf[0], 1);
    assert_int_equal(img.buf[img.stride + 2], 6);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_OK);
    assert_int_equal(img.buf[1], 0x12);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_ERR_END);
    unit_assert_padding_u8(&img);
    rte_y4m_close(rd);
    assert_int_equal(rte_y4m_open(path, 2, 2, &rd, &info, msg, sizeof msg), RTE_ERR_TOO_LARGE);

    /* the same stream as NV12: U "ab" and V "cd" interleaved, padding kept */
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_y4m_frame_format(&info), RTE_PIXEL_NV12);
    uint8_t nv12[2][8 + 6];
    memset(nv12, 0xEE, sizeof nv12);
    const rte_frame yuv = {RTE_PIXEL_NV12, 3, 2, {nv12[0], nv12[1]}, {7, 6}};
    assert_int_equal(rte_y4m_read_frame(rd, &yuv, msg, sizeof msg), RTE_OK);
    assert_memory_equal(nv12[0], "\x01\x02\x03\xEE\xEE\xEE\xEE\x04\x05\x06", 10);
    assert_memory_equal(nv12[1], "acbd\xEE", 5);
    assert_int_equal(rte_y4m_read_frame(rd, &yuv, msg, sizeof msg), RTE_OK);
    assert_int_equal(nv12[0][7], 0x14);
    assert_int_equal(rte_y4m_read_frame(rd, &yuv, msg, sizeof msg), RTE_ERR_END);
    rte_y4m_close(rd);

    /* 4:2:2: its Y plane only (the chroma skipped), never as NV12 */
    const char c422[] = "YUV4MPEG2 W3 H2 C422\nFRAME\nABCDEFabcdefghFRAME\nGHIJKLabcdefgh";
    write_file(path, c422, sizeof c422 - 1);
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_y4m_frame_format(&info), RTE_PIXEL_GREY);
    assert_int_equal(rte_y4m_read_frame(rd, &yuv, msg, sizeof msg), RTE_ERR_UNSUPPORTED);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_OK);
    assert_int_equal(img.buf[0], 'G');
    assert_int_equal(img.buf[img.stride + 2], 'L');
    rte_y4m_close(rd);

    /* mono, truncated second frame */
    const char mono[] = "YUV4MPEG2 W3 H2 Cmono\nFRAME\nabcdefFRAME\nab";
    write_file(path, mono, sizeof mono - 1);
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(info.chroma_bytes, 0);
    assert_int_equal(rte_y4m_frame_format(&info), RTE_PIXEL_GREY);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_OK);
    assert_int_equal(img.buf[img.stride], 'd');
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_ERR_TRUNCATED);
    rte_y4m_close(rd);

    const char *bad[] = {"YUV4MPEG W3 H2\n",          "YUV4MPEG2 W3\n",    "YUV4MPEG2 W3 H2 It\n",
                         "YUV4MPEG2 W3 H2 C420p10\n", "YUV4MPEG2 W0 H2\n", "YUV4MPEG2 W3 H2"};
    const rte_status expect[] = {RTE_ERR_FORMAT,      RTE_ERR_FORMAT, RTE_ERR_UNSUPPORTED,
                                 RTE_ERR_UNSUPPORTED, RTE_ERR_FORMAT, RTE_ERR_FORMAT};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_file(path, bad[i], strlen(bad[i]));
        assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), expect[i]);
        assert_true(msg[0] != 0);
    }
    /* a frame without its marker */
    const char nomark[] = "YUV4MPEG2 W3 H2 Cmono\nFRAMX\nabcdef";
    write_file(path, nomark, sizeof nomark - 1);
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_y4m_read_gray(rd, &img, msg, sizeof msg), RTE_ERR_FORMAT);
    rte_image_u8 wrong = unit_image_u8(2, 2, 0, 0);
    assert_int_equal(rte_y4m_read_gray(rd, &wrong, msg, sizeof msg), RTE_ERR_SIZE);
    rte_y4m_close(rd);
    test_free(wrong.buf);
    test_free(img.buf);
    unlink(path);
    close(fd);
}

/* The Hough search's point orders the accuracy tests run with: the
 * default and three that, before the fit was refined on edge pixels, moved
 * lanes on dashed markings past the limits (tests/unit and docs/lanes.md,
 * "Independence from the Hough point order"). */
static const uint32_t hough_seeds[] = {0, 0x0BADF00Du, 0x7F4A7C15u, 0x31415926u};
#define HOUGH_SEEDS (sizeof hough_seeds / sizeof hough_seeds[0])

/* A lane context for w x h frames whose Hough search uses `seed`. */
static rte_lane_context *make_ctx_seeded(int32_t w, int32_t h, uint32_t seed)
{
    rte_lane_config cfg;
    rte_lane_context *ctx = make_ctx(w, h, &cfg);
    rte_lane_params p = cfg.params;
    p.hough_seed = seed;
    assert_int_equal(rte_lane_set_params(ctx, &p), RTE_OK);
    return ctx;
}

/* ---- synthetic road sequences ---- */

typedef struct truth_row {
    double lb, lt, rb, rt;
    int lv, rv;
} truth_row;

static void check_road(const char *name, uint32_t seed, int *total_good, int *total_measured)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/road_%s.csv", g_roads_dir, name);
    FILE *csv = fopen(path, "r");
    if (!csv)
        fail_msg("%s: missing (run tools/make_road_fixtures.py)", path);
    char line[256];
    assert_non_null(fgets(line, sizeof line, csv)); /* header */
    snprintf(path, sizeof path, "%s/road_%s.y4m", g_roads_dir, name);
    rte_y4m_reader *rd;
    rte_y4m_info info;
    char msg[256];
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    rte_lane_context *ctx = make_ctx_seeded(info.width, info.height, seed);
    rte_image_u8 g = unit_image_u8(info.width, info.height, 7, 0);
    int frames = 0, measured = 0, good = 0, held = 0, held_ok = 0, sign_ok = 0, sign_n = 0;
    double worst_b = 0, worst_t = 0;
    truth_row t;
    int k;
    while (fscanf(csv, "%d,%lf,%lf,%lf,%lf,%d,%d", &k, &t.lb, &t.lt, &t.rb, &t.rt, &t.lv, &t.rv) ==
           7) {
        assert_int_equal(rte_y4m_read_gray(rd, &g, msg, sizeof msg), RTE_OK);
        rte_lane_result r;
        assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, (int64_t)k * 33333333, &r), RTE_OK);
        frames++;
        const rte_lane *L = &r.lane[0], *R = &r.lane[1];
        const double eb[2] = {fabs(L->x_bottom_q8 / 256.0 - t.lb),
                              fabs(R->x_bottom_q8 / 256.0 - t.rb)};
        const double et[2] = {fabs(L->x_top_q8 / 256.0 - t.lt), fabs(R->x_top_q8 / 256.0 - t.rt)};
        if (t.lv && t.rv) {
            measured++;
            const bool ok =
                L->found && R->found && eb[0] <= 5 && eb[1] <= 5 && et[0] <= 10 && et[1] <= 10;
            good += ok;
            if (!ok)
                printf("  %s seed %#x frame %d: left %s %.1f/%.1f, right %s %.1f/%.1f px off\n",
                       name, seed, k, L->found ? "found" : "MISSING", eb[0], et[0],
                       R->found ? "found" : "MISSING", eb[1], et[1]);
            worst_b = fmax(worst_b, fmax(eb[0], eb[1]));
            worst_t = fmax(worst_t, fmax(et[0], et[1]));
        } else {
            /* the worn marking: held as predicted, near its place */
            const int side = t.lv ? 1 : 0;
            const rte_lane *l = &r.lane[side];
            held++;
            held_ok += l->found && l->predicted && eb[side] <= 10 && et[side] <= 10;
            if (!(l->found && l->predicted))
                printf("  %s seed %#x frame %d: worn %s lane not held\n", name, seed, k,
                       side ? "right" : "left");
        }
        if (r.centre_valid) {
            /* offset sign: lane centre vs image centre from the truth */
            const double truth = (t.lb + t.rb) / 2 - (info.width - 1) / 2.0;
            sign_n++;
            sign_ok += (truth > 0) == (r.offset_q8 > 0) || fabs(truth) < 1.0;
        }
    }
    assert_int_equal(rte_y4m_read_gray(rd, &g, msg, sizeof msg), RTE_ERR_END);
    printf("lane road %s, seed %#x: %d frames, both lanes within 5/10 px in %d of %d measured, "
           "worst %.1f/%.1f px; "
           "worn marking held in %d of %d; offset sign right in %d of %d\n",
           name, seed, frames, good, measured, worst_b, worst_t, held_ok, held, sign_ok, sign_n);
    assert_true(frames >= 30);
    assert_true(held >= 3);
    assert_int_equal(held_ok, held);
    assert_int_equal(sign_n, frames);
    assert_int_equal(sign_ok, sign_n);
    *total_good += good;
    *total_measured += measured;
    fclose(csv);
    rte_y4m_close(rd);
    test_free(g.buf);
    rte_lane_destroy(ctx);
}

/* Both sequences, with each of the Hough point orders: both lanes found,
 * within 5 px at the bottom row and 10 px at the ROI top, in at least 98%
 * of the frames where both markings are painted; the worn marking held
 * (predicted) through its 3 frames; the offset sign right in every frame. */
static void test_synthetic_roads(void **state)
{
    (void)state;
    for (size_t i = 0; i < HOUGH_SEEDS; i++) {
        int good = 0, measured = 0;
        check_road("straight", hough_seeds[i], &good, &measured);
        check_road("bend", hough_seeds[i], &good, &measured);
        printf("lane roads, seed %#x: both lanes right in %d of %d frames (%.1f%%)\n",
               hough_seeds[i], good, measured, 100.0 * good / measured);
        assert_true(good * 100 >= measured * 98);
    }
}

/* ---- real photos ---- */

/* Each lane read by eye from each photo, twice:
 * - left_x, right_x: its x on the bottom row (zoomed crops of the lower part
 *   with a pixel ruler; the lines extended over the bonnet where it hides
 *   them);
 * - poly: its centre line as a polyline, every 20 rows from the bottom row
 *   up through the lower 38% of the frame, on the rows the bonnet leaves
 *   visible. Method: on the lower part of the photo drawn with a 50 px
 *   grid, three or four points of each marking's centre were read by eye;
 *   each was moved onto the middle of the paint nearest it (the run of
 *   white or yellow pixels within 25 px on that row, when there was one;
 *   left where it was otherwise, as on test2's worn right line); a
 *   quadratic (or, for dashed lines, a straight line; piecewise straight
 *   on test2's right) through them gave the rows; each polyline was then
 *   drawn on the photo and looked at, and moved where it left the paint
 *   (or, for dashes, the line through them).
 * known_failure: why a photo cannot pass yet (it is then reported as an
 * expected failure; a pass is reported too). */
#define PHOTO_LABEL_ROWS 14
typedef struct photo_point {
    int32_t y; /* 0: past the last point */
    double x;
} photo_point;

typedef struct photo_case {
    const char *name;
    int32_t left_x, right_x;
    const char *known_failure;
    photo_point poly[2][PHOTO_LABEL_ROWS];
} photo_case;

static const photo_case photos[] = {
    {"challange00101.jpg",
     182,
     886,
     NULL,
     {{{499, 246.6},
       {479, 273.1},
       {459, 299.3},
       {439, 325.1},
       {419, 350.5},
       {399, 375.6},
       {379, 400.2},
       {359, 424.4},
       {339, 448.3}},
      {{499, 823.3},
       {479, 779.8},
       {459, 738.5},
       {439, 699.3},
       {419, 662.4},
       {399, 627.7},
       {379, 595.1},
       {359, 564.7},
       {339, 536.5}}}},
    {"challange00111.jpg",
     153,
     891,
     NULL,
     {{{499, 217.8},
       {479, 245.8},
       {459, 274.3},
       {439, 303.2},
       {419, 332.6},
       {399, 362.4},
       {379, 392.5},
       {359, 423.2},
       {339, 454.2}},
      {{499, 794.1},
       {479, 762.0},
       {459, 729.8},
       {439, 697.7},
       {419, 665.5},
       {399, 633.4},
       {379, 601.2},
       {359, 569.1},
       {339, 536.9}}}},
    {"challange00136.jpg",
     118,
     857,
     NULL,
     {{{499, 191.8},
       {479, 222.1},
       {459, 253.1},
       {439, 284.8},
       {419, 317.3},
       {399, 350.5},
       {379, 384.5},
       {359, 419.2},
       {339, 454.7}},
      {{499, 783.1},
       {479, 751.4},
       {459, 719.7},
       {439, 688.0},
       {419, 656.2},
       {399, 624.5},
       {379, 592.8},
       {359, 561.0},
       {339, 529.3}}}},
    {"solidWhiteCurve.jpg",
     180,
     890,
     NULL,
     {{{539, 187.7},
       {519, 213.0},
       {499, 238.3},
       {479, 263.6},
       {459, 288.9},
       {439, 314.3},
       {419, 339.6},
       {399, 364.9},
       {379, 390.2},
       {359, 415.6},
       {339, 440.9}},
      {{539, 888.2},
       {519, 853.3},
       {499, 818.2},
       {479, 783.1},
       {459, 747.8},
       {439, 712.4},
       {419, 677.0},
       {399, 641.5},
       {379, 605.8},
       {359, 570.1},
       {339, 534.3}}}},
    {"solidWhiteRight.jpg",
     153,
     852,
     NULL,
     {{{539, 150.5},
       {519, 179.0},
       {499, 207.5},
       {479, 236.0},
       {459, 264.5},
       {439, 293.0},
       {419, 321.4},
       {399, 349.9},
       {379, 378.4},
       {359, 406.9},
       {339, 435.4}},
      {{539, 844.9},
       {519, 814.2},
       {499, 783.4},
       {479, 752.4},
       {459, 721.3},
       {439, 690.1},
       {419, 658.8},
       {399, 627.3},
       {379, 595.6},
       {359, 563.9},
       {339, 532.0}}}},
    {"solidYellowCurve.jpg",
     158,
     862,
     NULL,
     {{{539, 165.0},
       {519, 193.0},
       {499, 220.8},
       {479, 248.5},
       {459, 276.0},
       {439, 303.3},
       {419, 330.4},
       {399, 357.4},
       {379, 384.2},
       {359, 410.8},
       {339, 437.2}},
      {{539, 858.6},
       {519, 825.0},
       {499, 791.3},
       {479, 757.6},
       {459, 724.0},
       {439, 690.3},
       {419, 656.6},
       {399, 622.9},
       {379, 589.3},
       {359, 555.6},
       {339, 521.9}}}},
    {"solidYellowCurve2.jpg",
     162,
     868,
     NULL,
     {{{539, 171.2},
       {519, 197.2},
       {499, 223.3},
       {479, 249.7},
       {459, 276.2},
       {439, 302.9},
       {419, 329.8},
       {399, 356.8},
       {379, 384.1},
       {359, 411.5},
       {339, 439.1}},
      {{539, 863.2},
       {519, 829.8},
       {499, 796.4},
       {479, 762.9},
       {459, 729.5},
       {439, 696.1},
       {419, 662.7},
       {399, 629.2},
       {379, 595.8},
       {359, 562.4},
       {339, 529.0}}}},
    {"solidYellowLeft.jpg",
     142,
     858,
     NULL,
     {{{539, 148.3},
       {519, 177.7},
       {499, 206.8},
       {479, 235.7},
       {459, 264.3},
       {439, 292.6},
       {419, 320.7},
       {399, 348.6},
       {379, 376.1},
       {359, 403.4},
       {339, 430.5}},
      {{539, 846.9},
       {519, 815.5},
       {499, 784.0},
       {479, 752.5},
       {459, 721.0},
       {439, 689.6},
       {419, 658.1},
       {399, 626.6},
       {379, 595.1},
       {359, 563.6},
       {339, 532.2}}}},
    {"straight_lines1.jpg",
     197,
     1114,
     NULL,
     {{{679, 263.3},
       {659, 293.4},
       {639, 323.4},
       {619, 353.2},
       {599, 382.7},
       {579, 412.1},
       {559, 441.3},
       {539, 470.4},
       {519, 499.2},
       {499, 527.8},
       {479, 556.3},
       {459, 584.5}},
      {{659, 1012.7},
       {639, 981.4},
       {619, 950.0},
       {599, 918.7},
       {579, 887.3},
       {559, 856.0},
       {539, 824.6},
       {519, 793.3},
       {499, 761.9},
       {479, 730.6},
       {459, 699.2}}}},
    {"straight_lines2.jpg",
     231,
     1108,
     NULL,
     {{{679, 275.0},
       {659, 302.9},
       {639, 330.9},
       {619, 358.8},
       {599, 386.8},
       {579, 414.7},
       {559, 442.6},
       {539, 470.6},
       {519, 498.5},
       {499, 526.4},
       {479, 554.4},
       {459, 582.3}},
      {{659, 1016.2},
       {639, 984.9},
       {619, 953.6},
       {599, 922.3},
       {579, 891.0},
       {559, 859.7},
       {539, 828.4},
       {519, 797.1},
       {499, 765.7},
       {479, 734.4},
       {459, 703.1}}}},
    {"test1.jpg",
     233,
     1165,
     NULL,
     {{{679, 304.4},
       {659, 327.1},
       {639, 350.7},
       {619, 375.1},
       {599, 400.4},
       {579, 426.6},
       {559, 453.7},
       {539, 481.6},
       {519, 510.4},
       {499, 540.0},
       {479, 570.6},
       {459, 602.0}},
      {{659, 1057.2},
       {639, 1024.1},
       {619, 991.0},
       {599, 957.9},
       {579, 924.8},
       {559, 891.8},
       {539, 858.7},
       {519, 825.6},
       {499, 792.5},
       {479, 759.4},
       {459, 726.4}}}},
    {"test2.jpg",
     278,
     1149,
     NULL,
     {{{679, 341.0},
       {659, 364.4},
       {639, 387.4},
       {619, 410.1},
       {599, 432.4},
       {579, 454.4},
       {559, 476.0},
       {539, 497.3},
       {519, 518.2},
       {499, 538.8},
       {479, 559.0},
       {459, 578.8}},
      {{659, 1043.2},
       {639, 1011.1},
       {619, 979.1},
       {599, 947.0},
       {579, 915.0},
       {559, 882.9},
       {539, 850.9},
       {519, 818.8},
       {499, 775.5},
       {479, 731.7},
       {459, 688.0}}}},
    {"test3.jpg",
     230,
     1162,
     NULL,
     {{{679, 289.9},
       {659, 316.0},
       {639, 342.9},
       {619, 370.5},
       {599, 398.8},
       {579, 427.9},
       {559, 457.7},
       {539, 488.2},
       {519, 519.5},
       {499, 551.5},
       {479, 584.2},
       {459, 617.6}},
      {{659, 1045.3},
       {639, 1010.1},
       {619, 975.7},
       {599, 942.3},
       {579, 909.7},
       {559, 877.9},
       {539, 847.1},
       {519, 817.1},
       {499, 788.1},
       {479, 759.9},
       {459, 732.6}}}},
    {"test4.jpg",
     260,
     1205,
     NULL,
     {{{679, 317.1},
       {659, 342.2},
       {639, 367.4},
       {619, 392.5},
       {599, 417.7},
       {579, 442.9},
       {559, 468.0},
       {539, 493.2},
       {519, 518.4},
       {499, 543.6},
       {479, 568.7},
       {459, 593.9}},
      {{659, 1091.6},
       {639, 1053.2},
       {619, 1014.8},
       {599, 976.4},
       {579, 938.0},
       {559, 899.5},
       {539, 861.1},
       {519, 822.7},
       {499, 784.3},
       {479, 745.9},
       {459, 707.5}}}},
    {"test5.jpg",
     152,
     1147,
     NULL,
     {{{679, 231.6},
       {659, 261.8},
       {639, 292.5},
       {619, 323.8},
       {599, 355.7},
       {579, 388.0},
       {559, 421.0},
       {539, 454.4},
       {519, 488.4},
       {499, 523.0},
       {479, 558.1},
       {459, 593.7}},
      {{659, 1050.9},
       {639, 1013.7},
       {619, 977.6},
       {599, 942.6},
       {579, 908.7},
       {559, 875.9},
       {539, 844.3},
       {519, 813.7},
       {499, 784.3},
       {479, 756.0},
       {459, 728.8}}}},
    {"test6.jpg",
     245,
     1170,
     NULL,
     {{{679, 309.4},
       {659, 335.3},
       {639, 361.6},
       {619, 388.4},
       {599, 415.6},
       {579, 443.2},
       {559, 471.3},
       {539, 499.8},
       {519, 528.8},
       {499, 558.1},
       {479, 588.0},
       {459, 618.2}},
      {{659, 1052.0},
       {639, 1020.2},
       {619, 988.4},
       {599, 956.6},
       {579, 924.8},
       {559, 892.9},
       {539, 861.1},
       {519, 829.3},
       {499, 797.5},
       {479, 765.7},
       {459, 733.8}}}},
    {"whiteCarLaneSwitch.jpg",
     186,
     884,
     NULL,
     {{{539, 187.2},
       {519, 212.8},
       {499, 238.5},
       {479, 264.3},
       {459, 290.2},
       {439, 316.1},
       {419, 342.1},
       {399, 368.2},
       {379, 394.4},
       {359, 420.7},
       {339, 447.1}},
      {{539, 875.4},
       {519, 841.0},
       {499, 806.6},
       {479, 772.3},
       {459, 737.9},
       {439, 703.5},
       {419, 669.1},
       {399, 634.8},
       {379, 600.4},
       {359, 566.0},
       {339, 531.6}}}},
};

/* The largest distance (px) of the lane from the labelled points; a lane
 * not found is infinitely far. */
static double polyline_error(const rte_lane *lane, const photo_point *pts)
{
    if (!lane->found)
        return 1e9;
    double worst = 0;
    for (int i = 0; i < PHOTO_LABEL_ROWS && pts[i].y; i++) {
        const double e = fabs(rte_lane_x_q8(lane, pts[i].y) / 256.0 - pts[i].x);
        worst = e > worst ? e : worst;
    }
    return worst;
}

/* A photo read as BGR and grey into one test_malloc'd block (*mem). */
typedef struct photo_image {
    rte_image_u8c3 bgr;
    rte_image_u8 gray;
    uint8_t *mem;
} photo_image;

static photo_image read_photo(const char *path)
{
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_info info;
    assert_int_equal(rte_image_probe(path, &info, msg, sizeof msg), RTE_OK);
    rte_image_reader *reader = rte_image_reader_create(info.width, info.height);
    assert_non_null(reader);
    uint8_t *mem = test_malloc((size_t)info.width * info.height * 4);
    const photo_image im = {
        {info.width, info.height, info.width * 3, mem},
        {info.width, info.height, info.width, mem + (size_t)info.width * info.height * 3},
        mem};
    rte_image_u8c3 bgr = im.bgr;
    rte_image_u8 g = im.gray;
    assert_int_equal(rte_image_read_bgr(reader, path, &bgr, msg, sizeof msg), RTE_OK);
    assert_int_equal(rte_color_bgr_to_gray(&bgr, &g), RTE_OK);
    rte_image_reader_destroy(reader);
    return im;
}

static void test_real_photos(void **state)
{
    (void)state;
    const char *dir = getenv("RTE_SHARED_DATA_DIR");
    if (!dir)
        skip();
    int passed = 0, unexpected = 0, confident = 0, confident_right = 0;
    for (size_t i = 0; i < sizeof photos / sizeof photos[0]; i++) {
        const photo_case *c = &photos[i];
        char path[1024];
        snprintf(path, sizeof path, "%s/lanes/%s", dir, c->name);
        photo_image im = read_photo(path);
        const rte_image_info info = {.width = im.gray.width, .height = im.gray.height};
        rte_image_u8c3 bgr = im.bgr;
        rte_image_u8 g = im.gray;
        for (size_t k = 0; k < HOUGH_SEEDS; k++) {
            rte_lane_context *ctx = make_ctx_seeded(info.width, info.height, hough_seeds[k]);
            rte_lane_result r;
            assert_int_equal(rte_lane_process_gray(ctx, &g, &bgr, 0, &r), RTE_OK);
            const rte_lane *L = &r.lane[0], *R = &r.lane[1];
            const double tol = info.width * 0.04;
            const double el = L->found ? fabs(L->x_bottom_q8 / 256.0 - c->left_x) : 1e9;
            const double er = R->found ? fabs(R->x_bottom_q8 / 256.0 - c->right_x) : 1e9;
            /* slope signs: the left lane rises to the right (x grows going up) */
            const bool signs = L->found && R->found && L->x_top_q8 > L->x_bottom_q8 &&
                               R->x_top_q8 < R->x_bottom_q8;
            const double poly_l = polyline_error(L, c->poly[0]),
                         poly_r = polyline_error(R, c->poly[1]);
            const bool ok = signs && el <= tol && er <= tol && poly_l <= info.width * 0.03 &&
                            poly_r <= info.width * 0.03;
            if (k == 0 || !ok) /* the table for the default order, failures for the others */
                printf("lane photo %-24s left %7.1f (eye %4d, %4.1f%%, polyline %4.1f%%)  right "
                       "%7.1f (eye %4d, %4.1f%%, polyline %4.1f%%)  %s%s%s",
                       c->name, L->x_bottom_q8 / 256.0, c->left_x, el * 100 / info.width,
                       poly_l * 100 / info.width, R->x_bottom_q8 / 256.0, c->right_x,
                       er * 100 / info.width, poly_r * 100 / info.width, ok ? "ok" : "FAIL",
                       c->known_failure ? " (known failure: " : "",
                       c->known_failure ? c->known_failure : "");
            if (k == 0 || !ok)
                printf(k ? "  (seed %#x)\n" : "\n", hough_seeds[k]);
            if (c->known_failure && (k == 0 || !ok))
                printf("%s\n", ok ? "  known failure now passes: remove it from the list" : ")");
            passed += ok;
            unexpected += !ok && !c->known_failure;
            /* the confidence's calibration: sides found with >= 0.5 */
            for (int side = 0; side < 2; side++) {
                const rte_lane *l = &r.lane[side];
                if (l->found && l->confidence_permille >= 500) {
                    confident++;
                    confident_right += (side ? poly_r : poly_l) <= info.width * 0.03;
                }
            }
            rte_lane_destroy(ctx);
        }
        test_free(im.mem);
    }
    printf("lane photos: %d of %zu right (bottom-row x within 4%% of the width, slope signs, "
           "every polyline point within 3%%) over %zu point orders of the Hough search\n",
           passed, HOUGH_SEEDS * (sizeof photos / sizeof photos[0]), HOUGH_SEEDS);
    printf("lane photos: %d sides found with confidence >= 0.5, %d of them right (every polyline "
           "point within 3%%)\n",
           confident, confident_right);
    assert_int_equal(unexpected, 0);
    assert_true(confident > 0 && confident_right * 100 >= confident * 95);
}

/* The real clip (fixtures/solidWhiteRight_clip.y4m, grey): both lanes in
 * every frame, moving smoothly. */
static void test_real_clip(void **state)
{
    (void)state;
    const char *dir = getenv("RTE_FIXTURES_DIR");
    if (!dir)
        skip();
    char path[1024], msg[256];
    snprintf(path, sizeof path, "%s/solidWhiteRight_clip.y4m", dir);
    rte_y4m_reader *rd;
    rte_y4m_info info;
    assert_int_equal(rte_y4m_open(path, 0, 0, &rd, &info, msg, sizeof msg), RTE_OK);
    rte_lane_context *ctx = make_ctx(info.width, info.height, NULL);
    rte_image_u8 g = unit_image_u8(info.width, info.height, 0, 0);
    rte_lane_result r;
    int32_t prev[2] = {0, 0};
    int frames = 0;
    while (rte_y4m_read_gray(rd, &g, msg, sizeof msg) == RTE_OK) {
        assert_int_equal(rte_lane_process_gray(ctx, &g, NULL, 0, &r), RTE_OK);
        for (int s = 0; s < 2; s++) {
            assert_true(r.lane[s].found);
            assert_false(r.lane[s].predicted);
            if (frames > 0)
                assert_true(abs(r.lane[s].x_bottom_q8 - prev[s]) <= 8 * 256);
            prev[s] = r.lane[s].x_bottom_q8;
        }
        /* the camera sits a little left of the lane centre in this clip */
        assert_true(r.offset_permille > -100 && r.offset_permille < 100);
        frames++;
    }
    printf("lane clip: %d frames, both lanes found in all\n", frames);
    assert_int_equal(frames, 22);
    test_free(g.buf);
    rte_lane_destroy(ctx);
    rte_y4m_close(rd);
}

/* A dashed side seen only far up takes no bend that throws its near end
 * away (lane_curve.c, moves_unseen_end): fixtures/lanes/challenge02_0456.jpg,
 * a freeway whose right dashes lie above row 580 only, where the joint bend
 * put the right lane 70 px off its label. Labels from
 * fixtures/lanes/labels.json; both within 3% of the width. */
static void test_far_dashes_bend(void **state)
{
    (void)state;
    const char *dir = getenv("RTE_FIXTURES_DIR");
    if (!dir)
        skip();
    char path[1024];
    snprintf(path, sizeof path, "%s/lanes/challenge02_0456.jpg", dir);
    photo_image im = read_photo(path);
    static const photo_point labels[2][PHOTO_LABEL_ROWS] = {
        {{680, 343.3},
         {660, 368.9},
         {640, 395.7},
         {620, 423.2},
         {600, 450.2},
         {580, 475.9},
         {560, 501.4},
         {540, 528.8},
         {520, 554.4},
         {500, 578.7},
         {480, 601.8},
         {460, 621.0}},
        {{560, 861.2}, {540, 829.5}, {520, 797.6}, {500, 764.8}, {480, 730.2}, {460, 694.0}}};
    rte_lane_context *ctx = make_ctx(im.gray.width, im.gray.height, NULL);
    rte_lane_result r;
    assert_int_equal(rte_lane_process_gray(ctx, &im.gray, &im.bgr, 0, &r), RTE_OK);
    for (int side = 0; side < 2; side++) {
        const double e = polyline_error(&r.lane[side], labels[side]);
        printf("lane challenge02_0456 %s: worst %.1f px off its label\n", side ? "right" : "left",
               e);
        assert_true(e <= 0.03 * im.gray.width);
    }
    rte_lane_destroy(ctx);
    test_free(im.mem);
}

/* ---- the far trace (rte_lane.far_count) ---- */

/* x at a row and the polyline of a lane with a far trace: the curve below
 * its first point, its pieces above, the last one extended; the polyline
 * ends with its points, within max_points; a far_count out of range is no
 * trace. */
static void test_far_trace_contract(void **state)
{
    (void)state;
    rte_lane l = {.found = true,
                  .x_bottom_q8 = 100 * 256,
                  .x_top_q8 = 200 * 256,
                  .y_bottom = 359,
                  .y_top = 219,
                  .y_horizon = 200,
                  .y_supported = 359};
    rte_lane curve = l;
    const int32_t fx[3] = {176 * 256, 230 * 256, 300 * 256}, fy[3] = {260, 250, 244};
    l.far_count = 3;
    for (int i = 0; i < 3; i++) {
        l.far_x_q8[i] = fx[i];
        l.far_y[i] = fy[i];
    }
    for (int32_t y = 359; y > 260; y--)
        assert_int_equal(rte_lane_x_q8(&l, y), rte_lane_x_q8(&curve, y));
    assert_int_equal(rte_lane_x_q8(&l, 260), 176 * 256);
    assert_int_equal(rte_lane_x_q8(&l, 250), 230 * 256);
    assert_int_equal(rte_lane_x_q8(&l, 255), 203 * 256);
    assert_int_equal(rte_lane_x_q8(&l, 244), 300 * 256);
    /* beyond the end: the last piece (70 px over 6 rows) extended */
    assert_int_equal(rte_lane_x_q8(&l, 238), (300 + 70) * 256);

    int32_t xs[32], ys[32];
    int32_t n = rte_lane_polyline(&l, 32, xs, ys);
    assert_true(n >= 4);
    assert_int_equal(ys[0], 359);
    assert_int_equal(ys[n - 3], 260);
    assert_int_equal(ys[n - 2], 250);
    assert_int_equal(xs[n - 2], 230 * 256);
    assert_int_equal(ys[n - 1], 244);
    assert_int_equal(xs[n - 1], 300 * 256);
    for (int32_t i = 1; i < n; i++)
        assert_true(ys[i] < ys[i - 1]);
    /* too few points: the curve keeps its bottom row, the far trace its
     * last points */
    n = rte_lane_polyline(&l, 3, xs, ys);
    assert_int_equal(n, 3);
    assert_int_equal(ys[0], 359);
    assert_int_equal(ys[1], 250);
    assert_int_equal(ys[2], 244);

    /* without a trace, up to the supported row: the end takes the place
     * of a point within half a step of it (359 - 18 * 10 = 179 is one row
     * below the end 178), one further away stays */
    rte_lane seen = curve;
    seen.y_top = 100;
    for (int32_t end = 178; end >= 174; end -= 4) {
        seen.y_supported = end;
        n = rte_lane_polyline(&seen, 32, xs, ys);
        assert_int_equal(ys[n - 1], end);
        assert_int_equal(xs[n - 1], rte_lane_x_q8(&seen, end));
        assert_int_equal(ys[n - 2], end == 178 ? 189 : 179);
    }

    /* any values a caller fills in: no overflow, x clamped */
    rte_lane wild = l;
    wild.far_count = 2;
    wild.far_x_q8[0] = INT32_MIN;
    wild.far_x_q8[1] = INT32_MAX;
    wild.far_y[0] = 0;
    wild.far_y[1] = -1;
    assert_int_equal(rte_lane_x_q8(&wild, INT32_MIN), INT32_MAX);
    wild.far_y[1] = 0;
    assert_int_equal(rte_lane_x_q8(&wild, -5), INT32_MIN);
    for (int32_t bad = -1; bad <= RTE_LANE_FAR_POINTS + 1; bad += RTE_LANE_FAR_POINTS + 2) {
        l.far_count = bad;
        assert_int_equal(rte_lane_x_q8(&l, 244), rte_lane_x_q8(&curve, 244));
    }
}

/* Paints a marking along the polyline pts[0..n) ({x, y} pairs), a square
 * brush of 2 * half + 1 pixels. */
static void paint_marking(rte_image_u8 *img, const double (*pts)[2], int n, int half, uint8_t v)
{
    for (int i = 0; i + 1 < n; i++) {
        const double dx = pts[i + 1][0] - pts[i][0], dy = pts[i + 1][1] - pts[i][1];
        const int steps = (int)(4 * (fabs(dx) + fabs(dy))) + 1;
        for (int s = 0; s <= steps; s++) {
            const int xc = (int)lround(pts[i][0] + dx * s / steps);
            const int yc = (int)lround(pts[i][1] + dy * s / steps);
            for (int y = yc - half; y <= yc + half; y++)
                for (int x = xc - half; x <= xc + half; x++)
                    if (x >= 0 && y >= 0 && x < img->width && y < img->height)
                        rte_u8_row(img, y)[x] = v;
        }
    }
}

/* The lanes of one 640x360 grey frame: a left marking along the polyline
 * left[0..n) and a straight right one, both 5 px wide (r's segments point
 * into the context, destroyed here: only the lanes are read). */
static void far_road_lanes(const double (*left)[2], int n, rte_lane_result *r)
{
    const int32_t w = 640, h = 360;
    rte_image_u8 img = {w, h, w, test_malloc((size_t)w * h)};
    memset(img.buf, 90, (size_t)w * h);
    static const double right[][2] = {{490, 359}, {393, 216}};
    paint_marking(&img, left, n, 2, 230);
    paint_marking(&img, right, 2, 2, 230);
    rte_lane_context *ctx = make_ctx(w, h, NULL);
    assert_int_equal(rte_lane_process_gray(ctx, &img, NULL, 0, r), RTE_OK);
    r->segments = NULL;
    r->segment_count = 0;
    rte_lane_destroy(ctx);
    test_free(img.buf);
}

/* A drawn road whose left marking turns sharply right near the top, to
 * run nearly along the rows: the far trace follows it where the curve
 * cannot (every drawn vertex within 2% of the width within a row of it,
 * but the end, where the marking runs 30 px a row); the straight right
 * marking gets none. Without the trace the lane is 45 px off near row 236. */
static void test_far_trace_drawn(void **state)
{
    (void)state;
    const int32_t w = 640;
    static const double left[][2] = {{150, 359}, {237, 262}, {250, 252}, {275, 245},
                                     {310, 240}, {360, 236}, {420, 234}};
    rte_lane_result r;
    far_road_lanes(left, 7, &r);
    const rte_lane *L = &r.lane[RTE_LANE_LEFT], *R = &r.lane[RTE_LANE_RIGHT];
    assert_true(L->found && R->found);
    assert_true(L->far_count >= 2);
    assert_int_equal(R->far_count, 0);
    for (int i = 0; i < 6; i++) {
        /* within a row of the vertex: where the marking runs 10 px a row,
         * a row's x is that uncertain */
        double err = 1e9, x = 0;
        for (int32_t dy = -1; dy <= 1; dy++) {
            const double xr = rte_lane_x_q8(L, (int32_t)left[i][1] + dy) / 256.0;
            if (fabs(xr - left[i][0]) < err) {
                err = fabs(xr - left[i][0]);
                x = xr;
            }
        }
        if (err > 0.02 * w)
            fail_msg("left near row %.0f: %.1f, drawn at %.1f", left[i][1], x, left[i][0]);
    }
}

/* test_far_trace_drawn's marking, but turning onto a bright ridge that runs
 * exactly along a row (the far edge of a crest, a kerb across the road)
 * instead of climbing on: the far trace does not follow the ridge, which
 * would throw the lane along its last piece beyond the paint's end (to
 * x = 1088 on row 230 when followed; the paint ends at 450). */
static void test_far_trace_flat_ridge(void **state)
{
    (void)state;
    static const double left[][2] = {{150, 359}, {237, 262}, {250, 252},
                                     {275, 245}, {310, 242}, {450, 242}};
    rte_lane_result r;
    far_road_lanes(left, 6, &r);
    const rte_lane *L = &r.lane[RTE_LANE_LEFT];
    assert_true(L->found);
    for (int32_t y = 230; y <= 262; y += 2) {
        const double x = rte_lane_x_q8(L, y) / 256.0;
        if (x < 150 || x > 450)
            fail_msg("left at row %d: %.1f, beyond the paint (150..450)", y, x);
    }
}

int main(int argc, char **argv)
{
    if (argc > 1)
        g_roads_dir = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_arguments),
        cmocka_unit_test(test_tiny_frames),
        cmocka_unit_test(test_drawn_lanes),
        cmocka_unit_test(test_slope_filter),
        cmocka_unit_test(test_color_cue),
        cmocka_unit_test(test_color_cue_yuv),
        cmocka_unit_test(test_tracking),
        cmocka_unit_test(test_runtime_params),
        cmocka_unit_test(test_y4m),
        cmocka_unit_test(test_synthetic_roads),
        cmocka_unit_test(test_real_photos),
        cmocka_unit_test(test_real_clip),
        cmocka_unit_test(test_far_trace_contract),
        cmocka_unit_test(test_far_trace_drawn),
        cmocka_unit_test(test_glare_confidence),
        cmocka_unit_test(test_reacquire),
        cmocka_unit_test(test_weak_side_refit),
        cmocka_unit_test(test_gated_stripe_marks),
        cmocka_unit_test(test_partner_from_one_side),
        cmocka_unit_test(test_partner_replaces_held_dash),
        cmocka_unit_test(test_random_roads),
        cmocka_unit_test(test_far_dashes_bend),
        cmocka_unit_test(test_far_trace_flat_ridge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
