/* Debug overlays: see overlay.h. */
#include "rtedge/overlay.h"

#include <stdio.h>
#include <string.h>

static const rte_draw_color ROI_COLOR = {0, 255, 255}, EDGE_COLOR = {255, 0, 255},
                            USED_COLOR = {0, 255, 0}, UNUSED_COLOR = {128, 128, 128},
                            LEFT_COLOR = {255, 0, 0}, RIGHT_COLOR = {0, 0, 255},
                            WHITE = {255, 255, 255}, YELLOW = {0, 255, 255}, RED = {0, 0, 255},
                            GREY = {160, 160, 160};

int32_t rte_overlay_layer_named(const char *name, size_t len)
{
    static const char *const names[] = {"roi",      "edges", "segments", "lanes",
                                        "contours", "grasp", "labels"};
    if (len == 3 && !strncmp(name, "all", 3))
        return RTE_OVERLAY_ALL;
    for (int32_t i = 0; i < 7; i++)
        if (strlen(names[i]) == len && !strncmp(name, names[i], len))
            return 1 << i;
    return -1;
}

/* Frame pixels to canvas pixels, and Q8 frame pixels to canvas pixels. */
static int32_t px(const rte_overlay *o, int32_t v)
{
    return (int32_t)(((int64_t)v * o->scale_q16 + 32768) >> 16);
}

static int32_t px_q8(const rte_overlay *o, int32_t v)
{
    return (int32_t)(((int64_t)v * o->scale_q16 + ((int64_t)1 << 23)) >> 24);
}

/* A thickness of t frame pixels on the canvas, at least 1. */
static int32_t thick(const rte_overlay *o, int32_t t)
{
    int32_t s = px(o, t);
    return s < 1 ? 1 : s;
}

void rte_overlay_size(int32_t frame_width, int32_t frame_height, int32_t scale_q16, int32_t *width,
                      int32_t *height)
{
    const rte_overlay o = {{0, 0, 0, NULL}, scale_q16};
    *width = px(&o, frame_width);
    *height = px(&o, frame_height);
    *width = *width < 1 ? 1 : *width;
    *height = *height < 1 ? 1 : *height;
}

void rte_overlay_fill_gray(rte_overlay *o, const rte_image_u8 *gray)
{
    const rte_image_u8c3 *c = &o->canvas;
    /* source column of canvas column x: x * step >> 16 */
    const int64_t step_x = ((int64_t)gray->width << 16) / c->width;
    const int64_t step_y = ((int64_t)gray->height << 16) / c->height;
    for (int32_t y = 0; y < c->height; y++) {
        const uint8_t *s = gray->buf + (size_t)((y * step_y) >> 16) * (size_t)gray->stride;
        uint8_t *d = c->buf + (size_t)y * (size_t)c->stride;
        for (int32_t x = 0; x < c->width; x++, d += 3)
            d[0] = d[1] = d[2] = s[(x * step_x) >> 16];
    }
}

void rte_overlay_roi(rte_overlay *o, const rte_point *roi, int32_t n)
{
    rte_point p[RTE_LANE_MAX_ROI_VERTICES];
    if (n > RTE_LANE_MAX_ROI_VERTICES)
        n = RTE_LANE_MAX_ROI_VERTICES;
    for (int32_t i = 0; i < n; i++)
        p[i] = (rte_point){px(o, roi[i].x), px(o, roi[i].y)};
    rte_draw_polyline(&o->canvas, p, n, 1, ROI_COLOR, 2);
}

/* Every edge pixel marked where it falls on the canvas (a reduced canvas
 * keeps thin edges that sampling would miss). */
static void draw_edges(rte_overlay *o, const rte_lane_result *r)
{
    const rte_image_u8 *e = &r->edges;
    rte_image_u8c3 *c = &o->canvas;
    for (int32_t y = 0; y < e->height; y++) {
        const uint8_t *row = e->buf + (size_t)y * (size_t)e->stride;
        const int32_t cy = px(o, r->edges_y0 + y);
        if (cy < 0 || cy >= c->height)
            continue;
        uint8_t *d = c->buf + (size_t)cy * (size_t)c->stride;
        for (int32_t x = 0; x < e->width; x++) {
            if (!row[x])
                continue;
            const int32_t cx = px(o, r->edges_x0 + x);
            if (cx >= 0 && cx < c->width)
                memcpy(d + 3 * cx, &EDGE_COLOR, 3);
        }
    }
}

void rte_overlay_lanes(rte_overlay *o, const rte_lane_result *r, uint32_t layers)
{
    if ((layers & RTE_OVERLAY_EDGES) && r->edges.buf)
        draw_edges(o, r);
    if (layers & RTE_OVERLAY_SEGMENTS)
        for (int32_t i = 0; i < r->segment_count; i++) {
            const rte_lane_segment *s = &r->segments[i];
            const bool used = s->use == RTE_LANE_SEG_LEFT || s->use == RTE_LANE_SEG_RIGHT;
            rte_draw_line(&o->canvas, px(o, s->x0), px(o, s->y0), px(o, s->x1), px(o, s->y1),
                          used ? USED_COLOR : UNUSED_COLOR, 1);
        }
    if (layers & RTE_OVERLAY_LANES)
        for (int side = 0; side < 2; side++) {
            const rte_lane *l = &r->lane[side];
            int32_t xs[RTE_LANE_POLYLINE_POINTS], ys[RTE_LANE_POLYLINE_POINTS];
            const int32_t n = l->found ? rte_lane_polyline(l, RTE_LANE_POLYLINE_POINTS, xs, ys) : 0;
            for (int32_t i = 0; i + 1 < n; i++)
                rte_draw_line(&o->canvas, px_q8(o, xs[i]), px(o, ys[i]), px_q8(o, xs[i + 1]),
                              px(o, ys[i + 1]), side == RTE_LANE_LEFT ? LEFT_COLOR : RIGHT_COLOR,
                              l->predicted ? 1 : thick(o, 3));
        }
    if ((layers & RTE_OVERLAY_LABELS) && r->centre_valid) {
        char text[48];
        snprintf(text, sizeof text, "offset %+d px", (int)((r->offset_q8 + 128) >> 8));
        rte_overlay_label(&o->canvas, 4, o->canvas.height - 14, text, WHITE);
    }
}

/* Canvas point of a Q8 frame point. */
static rte_point point_q8(const rte_overlay *o, int32_t x_q8, int32_t y_q8)
{
    return (rte_point){px_q8(o, x_q8), px_q8(o, y_q8)};
}

static void draw_object(rte_overlay *o, const rte_grasp_result *r, int32_t i, uint32_t layers)
{
    const rte_grasp_object *g = &r->objects[i];
    const rte_draw_color color = rte_overlay_color(i);
    if (layers & RTE_OVERLAY_CONTOURS) {
        const rte_contour *ct = &r->contours->contours[g->contour];
        const rte_point *pts = r->contours->points + ct->offset;
        for (int32_t k = 0; k < ct->count; k++) {
            const rte_point a = pts[k], b = pts[(k + 1) % ct->count];
            rte_draw_line(&o->canvas, px(o, a.x), px(o, a.y), px(o, b.x), px(o, b.y), color, 1);
        }
    }
    if (layers & RTE_OVERLAY_GRASP) {
        /* The closing line between the opened jaws, each jaw a bar across
         * it (half the object's width long, at least 8 px); grey when the
         * score is 0 (the gripper cannot take it). */
        const rte_draw_color jaw = g->score_q16 > 0 ? YELLOW : GREY;
        const int32_t(*j)[2] = g->jaws_q8;
        const int32_t dx = j[1][0] - j[0][0], dy = j[1][1] - j[0][1];
        const int64_t len = (int64_t)dx * dx + (int64_t)dy * dy > 0 ? g->opening_q8 : 1;
        const int64_t half = g->width_q8 / 4 > 4 * 256 ? g->width_q8 / 4 : 4 * 256;
        const int32_t bx = (int32_t)(-dy * half / len), by = (int32_t)(dx * half / len);
        const rte_point a = point_q8(o, j[0][0], j[0][1]), b = point_q8(o, j[1][0], j[1][1]);
        rte_draw_line(&o->canvas, a.x, a.y, b.x, b.y, jaw, 1);
        for (int k = 0; k < 2; k++) {
            const rte_point p0 = point_q8(o, j[k][0] - bx, j[k][1] - by);
            const rte_point p1 = point_q8(o, j[k][0] + bx, j[k][1] + by);
            rte_draw_line(&o->canvas, p0.x, p0.y, p1.x, p1.y, jaw, thick(o, 3));
        }
        const rte_point p = point_q8(o, g->x_q8, g->y_q8);
        rte_draw_dot(&o->canvas, p.x, p.y, thick(o, 3), RED);
    }
    if (layers & RTE_OVERLAY_LABELS) {
        char label[48];
        snprintf(label, sizeof label, "%d %s %d%%", (int)i, rte_grasp_shape_name(g->info.shape),
                 (int)(((int64_t)g->score_q16 * 100 + 32768) >> 16));
        rte_overlay_label(&o->canvas, px(o, g->info.bounds.x), px(o, g->info.bounds.y) - 10, label,
                          color);
    }
}

void rte_overlay_grasp(rte_overlay *o, const rte_grasp_result *r, uint32_t layers)
{
    for (int32_t i = r->n_objects - 1; i >= 0; i--)
        draw_object(o, r, i, layers);
}

void rte_overlay_label(rte_image_u8c3 *canvas, int32_t x, int32_t y, const char *text,
                       rte_draw_color c)
{
    int32_t tw, th;
    rte_draw_text_size(text, 1, &tw, &th);
    if (x + tw + 2 > canvas->width)
        x = canvas->width - tw - 2;
    if (y + th + 2 > canvas->height)
        y = canvas->height - th - 2;
    x = x < 1 ? 1 : x;
    y = y < 1 ? 1 : y;
    const rte_draw_color black = {0, 0, 0};
    for (int32_t yy = y - 1; yy <= y + th; yy++)
        rte_draw_line(canvas, x - 1, yy, x + tw, yy, black, 1);
    rte_draw_text(canvas, x, y, text, c, 1);
}

rte_draw_color rte_overlay_color(int32_t i)
{
    static const rte_draw_color palette[] = {
        {0, 0, 255},   {0, 200, 0},   {255, 160, 0}, {0, 200, 255},
        {255, 0, 255}, {255, 255, 0}, {0, 128, 255}, {128, 0, 255},
    };
    return palette[(uint32_t)i % (sizeof palette / sizeof palette[0])];
}
