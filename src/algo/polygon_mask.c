/* Filled polygons (cv::fillPoly, LINE_8, shift 0) and ROI masking.
 *
 * OpenCV 4.6 fills a polygon set in two steps, both reproduced here:
 *  1. every edge, from the previous vertex to the current one, is drawn
 *     with its 8-connected line iterator, after clipping to the image with
 *     its clipLine (integer, order dependent: the second end point is
 *     clipped against the already clipped first one);
 *  2. every non-horizontal edge becomes a Q16 edge (x of its top vertex,
 *     slope ((x1 - x0) << 16) / (y1 - y0) truncated towards zero) active on
 *     rows y0 <= y < y1; on each row the active x values are sorted and
 *     taken in pairs (even-odd rule across all polygons), and the pixels
 *     from ceil(left) to floor(right) are set.
 * Rows above the image are skipped by starting each edge at the first
 * visible row: x + (row - y0) * dx equals OpenCV's row-by-row sum. */
#include <stdbool.h>
#include <string.h>

#include "rtedge/polygon_mask.h"

enum { EDGE_SHIFT = 16 };

typedef struct poly_edge {
    int64_t x;  /* Q16 x on the current row */
    int64_t dx; /* Q16 step per row */
    int32_t y0, y1;
} poly_edge;

size_t rte_polygon_mask_scratch_size(int32_t max_vertices)
{
    if (max_vertices < 1)
        max_vertices = 1;
    return rte_arena_piece_size((size_t)max_vertices * sizeof(poly_edge)) +
           rte_arena_piece_size((size_t)max_vertices * sizeof(int32_t));
}

/* floor(v / 2^16) and ceil(v / 2^16) without relying on >> of negatives. */
static int64_t floor_q16(int64_t v)
{
    return v >= 0 ? v >> EDGE_SHIFT : -((-v + ((1 << EDGE_SHIFT) - 1)) >> EDGE_SHIFT);
}

static int64_t ceil_q16(int64_t v) { return -floor_q16(-v); }

/* OpenCV's clipLine on the rectangle [0, w-1] x [0, h-1]: false when the
 * segment misses it. The updates are sequential on purpose: each one uses
 * the coordinates as already changed, as OpenCV does. */
static int clip_line(int64_t w, int64_t h, int64_t *x1, int64_t *y1, int64_t *x2, int64_t *y2)
{
    int64_t right = w - 1, bottom = h - 1;
    int c1 = (*x1 < 0) + (*x1 > right) * 2 + (*y1 < 0) * 4 + (*y1 > bottom) * 8;
    int c2 = (*x2 < 0) + (*x2 > right) * 2 + (*y2 < 0) * 4 + (*y2 > bottom) * 8;

    if ((c1 & c2) == 0 && (c1 | c2) != 0) {
        if (c1 & 12) {
            int64_t a = c1 < 8 ? 0 : bottom;
            *x1 += (a - *y1) * (*x2 - *x1) / (*y2 - *y1);
            *y1 = a;
            c1 = (*x1 < 0) + (*x1 > right) * 2;
        }
        if (c2 & 12) {
            int64_t a = c2 < 8 ? 0 : bottom;
            *x2 += (a - *y2) * (*x2 - *x1) / (*y2 - *y1);
            *y2 = a;
            c2 = (*x2 < 0) + (*x2 > right) * 2;
        }
        if ((c1 & c2) == 0 && (c1 | c2) != 0) {
            if (c1) {
                int64_t a = c1 == 1 ? 0 : right;
                *y1 += (a - *x1) * (*y2 - *y1) / (*x2 - *x1);
                *x1 = a;
                c1 = 0;
            }
            if (c2) {
                int64_t a = c2 == 1 ? 0 : right;
                *y2 += (a - *x2) * (*y2 - *y1) / (*x2 - *x1);
                *x2 = a;
                c2 = 0;
            }
        }
    }
    return (c1 | c2) == 0;
}

/* OpenCV's 8-connected line (LineIterator, left to right): walk the major
 * axis from the left end point; step the minor axis when the error term is
 * negative, which rounds halves towards the start. Its pixels get `value`,
 * or with `from` (an image of img's size) from's pixels there. */
static void draw_line(rte_image_u8 *img, const rte_image_u8 *from, int64_t x1, int64_t y1,
                      int64_t x2, int64_t y2, uint8_t value)
{
    int64_t w = img->width, h = img->height;
    if (x1 < 0 || x1 >= w || x2 < 0 || x2 >= w || y1 < 0 || y1 >= h || y2 < 0 || y2 >= h) {
        if (!clip_line(w, h, &x1, &y1, &x2, &y2))
            return;
    }
    int32_t x = (int32_t)x1, y = (int32_t)y1;
    int32_t dx = (int32_t)(x2 - x1), dy = (int32_t)(y2 - y1);
    if (dx < 0) {
        x = (int32_t)x2;
        y = (int32_t)y2;
        dx = -dx;
        dy = -dy;
    }
    int32_t ystep = 1;
    if (dy < 0) {
        dy = -dy;
        ystep = -1;
    }
    /* offsets into img and into from: x + y * stride, for both strides */
    ptrdiff_t p = (ptrdiff_t)y * img->stride + x, q = from ? (ptrdiff_t)y * from->stride + x : 0;
    const ptrdiff_t row_step = (ptrdiff_t)ystep * img->stride;
    const ptrdiff_t from_row_step = from ? (ptrdiff_t)ystep * from->stride : 0;
    ptrdiff_t major_step = 1, minor_step = row_step, from_major = 1, from_minor = from_row_step;
    int32_t major = dx, minor = dy;
    if (dy > dx) {
        major = dy;
        minor = dx;
        major_step = row_step;
        minor_step = 1;
        from_major = from_row_step;
        from_minor = 1;
    }
    int32_t err = major - 2 * minor;
    for (int32_t i = 0; i <= major; i++) {
        img->buf[p] = from ? from->buf[q] : value;
        int neg = err < 0;
        err += -2 * minor + (neg ? 2 * major : 0);
        p += major_step + (neg ? minor_step : 0);
        q += from_major + (neg ? from_minor : 0);
    }
}

/* Heap sort of the edges by first row: bounded time, no extra memory. */
static void sift_down(poly_edge *e, int32_t root, int32_t n)
{
    for (;;) {
        int32_t child = 2 * root + 1;
        if (child >= n)
            return;
        if (child + 1 < n && e[child + 1].y0 > e[child].y0)
            child++;
        if (e[root].y0 >= e[child].y0)
            return;
        poly_edge t = e[root];
        e[root] = e[child];
        e[child] = t;
        root = child;
    }
}

static void sort_edges_by_y0(poly_edge *e, int32_t n)
{
    for (int32_t i = n / 2 - 1; i >= 0; i--)
        sift_down(e, i, n);
    for (int32_t end = n - 1; end > 0; end--) {
        poly_edge t = e[0];
        e[0] = e[end];
        e[end] = t;
        sift_down(e, 0, end);
    }
}

/* Draws the polygons' outlines (draw_line's value or from). */
static void draw_outlines(rte_image_u8 *img, const rte_image_u8 *from, const rte_polygon *polygons,
                          int32_t polygon_count, uint8_t value)
{
    for (int32_t p = 0; p < polygon_count; p++) {
        const rte_polygon *poly = &polygons[p];
        if (poly->count <= 0)
            continue;
        rte_vertex p0 = poly->vertex[poly->count - 1];
        for (int32_t i = 0; i < poly->count; i++) {
            rte_vertex p1 = poly->vertex[i];
            draw_line(img, from, p0.x, p0.y, p1.x, p1.y, value);
            p0 = p1;
        }
    }
}

/* Appends the polygon's non-horizontal edges. */
static int32_t collect_edges(const rte_polygon *poly, poly_edge *edges, int32_t n)
{
    const rte_vertex *v = poly->vertex;
    rte_vertex p0 = v[poly->count - 1];
    for (int32_t i = 0; i < poly->count; i++) {
        rte_vertex p1 = v[i];
        if (p0.y != p1.y) {
            const rte_vertex *top = p0.y < p1.y ? &p0 : &p1;
            const rte_vertex *bottom = p0.y < p1.y ? &p1 : &p0;
            poly_edge e;
            e.y0 = top->y;
            e.y1 = bottom->y;
            e.x = (int64_t)top->x * (1 << EDGE_SHIFT);
            e.dx = ((int64_t)(p1.x - p0.x) * (1 << EDGE_SHIFT)) / (p1.y - p0.y);
            edges[n++] = e;
        }
        p0 = p1;
    }
    return n;
}

/* Zeroes rows *done..y1 - 1 (none when y1 <= *done) and moves *done on. */
static void clear_rows(rte_image_u8 *img, int32_t *done, int32_t y1)
{
    for (; *done < y1; (*done)++)
        memset(rte_u8_row(img, *done), 0, (size_t)img->width);
}

/* The edge table walked row by row (even-odd over all edges): the rows
 * that may hold spans, each with its active edges sorted by x. */
typedef struct edge_walk {
    poly_edge *edges;
    int32_t *active;
    int32_t n, nact, next;
    int32_t y, y_end; /* the row, and the row past the last one with edges */
} edge_walk;

static void edge_walk_start(edge_walk *w, poly_edge *edges, int32_t n, int32_t *active,
                            int32_t height)
{
    sort_edges_by_y0(edges, n);
    int32_t y_end = 0;
    for (int32_t i = 0; i < n; i++)
        if (edges[i].y1 > y_end)
            y_end = edges[i].y1;
    *w = (edge_walk){
        edges, active, n, 0, 0, edges[0].y0 > 0 ? edges[0].y0 : 0, y_end < height ? y_end : height};
}

/* Moves to the next row at or below w->y that may hold spans, with its
 * active edges in active[0..nact) sorted by x; false past the last one. */
static bool edge_walk_row(edge_walk *w)
{
    poly_edge *edges = w->edges;
    int32_t *active = w->active;
    int32_t y = w->y;
    if (y >= w->y_end)
        return false;
    int32_t k = 0;
    for (int32_t i = 0; i < w->nact; i++)
        if (edges[active[i]].y1 > y)
            active[k++] = active[i];
    w->nact = k;
    if (w->nact == 0 && w->next < w->n && edges[w->next].y0 > y)
        y = edges[w->next].y0; /* skip empty rows */
    if (y >= w->y_end)
        return false;
    for (; w->next < w->n && edges[w->next].y0 <= y; w->next++) {
        poly_edge *e = &edges[w->next];
        if (e->y1 > y) { /* starts here, or above the image */
            e->x += (int64_t)(y - e->y0) * e->dx;
            active[w->nact++] = w->next;
        }
    }
    /* Order by x. From row to row only crossing edges swap and new ones
     * join at the end, so the list is nearly sorted: insertion sort. */
    for (int32_t i = 1; i < w->nact; i++) {
        int32_t a = active[i], j = i;
        while (j > 0 && edges[active[j - 1]].x > edges[a].x) {
            active[j] = active[j - 1];
            j--;
        }
        active[j] = a;
    }
    w->y = y;
    return true;
}

/* On to the row below. */
static void edge_walk_next(edge_walk *w)
{
    for (int32_t i = 0; i < w->nact; i++)
        w->edges[w->active[i]].x += w->edges[w->active[i]].dx;
    w->y++;
}

/* The pixels of span i of the walk's row: ceil(left) to floor(right),
 * clipped to the row; false when it holds none. */
static bool walk_span(const edge_walk *w, int32_t i, int32_t width, int32_t *x1, int32_t *x2)
{
    int64_t a = ceil_q16(w->edges[w->active[2 * i]].x);
    int64_t b = floor_q16(w->edges[w->active[2 * i + 1]].x);
    a = a < 0 ? 0 : a;
    b = b > width - 1 ? width - 1 : b;
    *x1 = (int32_t)a;
    *x2 = (int32_t)b;
    return a <= b;
}

/* Scanline fill of the edge table. With `clear` every row is zeroed as the
 * fill reaches it, while it is in cache: one pass over the image instead
 * of a clear and then a fill. */
static void fill_edges(rte_image_u8 *img, poly_edge *edges, int32_t n, int32_t *active,
                       uint8_t value, bool clear)
{
    edge_walk w;
    edge_walk_start(&w, edges, n, active, img->height);
    int32_t cleared = clear ? 0 : img->height;
    while (edge_walk_row(&w)) {
        clear_rows(img, &cleared, w.y + 1);
        uint8_t *row = rte_u8_row(img, w.y);
        int32_t x1, x2;
        for (int32_t i = 0; 2 * i + 1 < w.nact; i++)
            if (walk_span(&w, i, img->width, &x1, &x2))
                memset(row + x1, value, (size_t)(x2 - x1 + 1));
        edge_walk_next(&w);
    }
    clear_rows(img, &cleared, img->height);
}

static rte_status check_polygons(const rte_polygon *polygons, int32_t polygon_count, int32_t *total)
{
    if (polygon_count < 0 || (polygon_count > 0 && !polygons))
        return RTE_ERR_ARGUMENT;
    int64_t sum = 0;
    for (int32_t p = 0; p < polygon_count; p++) {
        const rte_polygon *poly = &polygons[p];
        if (poly->count < 0 || (poly->count > 0 && !poly->vertex))
            return RTE_ERR_ARGUMENT;
        for (int32_t i = 0; i < poly->count; i++) {
            rte_vertex v = poly->vertex[i];
            if (v.x < -RTE_POLYGON_MAX_COORD || v.x > RTE_POLYGON_MAX_COORD ||
                v.y < -RTE_POLYGON_MAX_COORD || v.y > RTE_POLYGON_MAX_COORD)
                return RTE_ERR_ARGUMENT;
        }
        sum += poly->count;
        if (sum > INT32_MAX / 2)
            return RTE_ERR_TOO_LARGE;
    }
    *total = (int32_t)sum;
    return RTE_OK;
}

/* The polygons' non-horizontal edges, in scratch from the arena (*mark:
 * where to reset it), after checking them: *n edges. */
static rte_status collect_polygon_edges(const rte_polygon *polygons, int32_t polygon_count,
                                        rte_arena *arena, size_t *mark, poly_edge **edges,
                                        int32_t **active, int32_t *n)
{
    int32_t total = 0;
    rte_status st = check_polygons(polygons, polygon_count, &total);
    if (st != RTE_OK)
        return st;
    if (!arena)
        return RTE_ERR_ARGUMENT;
    *mark = rte_arena_mark(arena);
    *edges = NULL;
    *active = NULL;
    if (total > 0) {
        *edges = rte_arena_alloc(arena, (size_t)total * sizeof(poly_edge));
        *active = rte_arena_alloc(arena, (size_t)total * sizeof(int32_t));
        if (!*edges || !*active) {
            rte_arena_reset(arena, *mark);
            return RTE_ERR_NO_MEMORY;
        }
    }
    *n = 0;
    for (int32_t p = 0; p < polygon_count; p++)
        if (polygons[p].count > 0)
            *n = collect_edges(&polygons[p], *edges, *n);
    return RTE_OK;
}

/* Shared by fill and mask_build: checks everything and takes the scratch
 * before touching the image, so a failing call leaves it as it was. With
 * `clear` the image is zeroed first. The outlines are drawn after the fill
 * (OpenCV draws them first): both write the same value, so the order
 * cannot show. */
static rte_status fill_polygons(rte_image_u8 *img, const rte_polygon *polygons,
                                int32_t polygon_count, uint8_t value, bool clear, rte_arena *arena)
{
    rte_status st = rte_image_u8_check(img);
    size_t mark = 0;
    poly_edge *edges = NULL;
    int32_t *active = NULL, n = 0;
    if (st != RTE_OK || (st = collect_polygon_edges(polygons, polygon_count, arena, &mark, &edges,
                                                    &active, &n)) != RTE_OK)
        return st;
    if (n >= 2) {
        fill_edges(img, edges, n, active, value, clear);
    } else if (clear) {
        int32_t cleared = 0;
        clear_rows(img, &cleared, img->height);
    }
    draw_outlines(img, NULL, polygons, polygon_count, value);
    rte_arena_reset(arena, mark);
    return RTE_OK;
}

rte_status rte_polygon_fill_u8(rte_image_u8 *img, const rte_polygon *polygons,
                               int32_t polygon_count, uint8_t value, rte_arena *arena)
{
    return fill_polygons(img, polygons, polygon_count, value, false, arena);
}

rte_status rte_polygon_mask_build(rte_image_u8 *mask, const rte_polygon *polygons,
                                  int32_t polygon_count, rte_arena *arena)
{
    return fill_polygons(mask, polygons, polygon_count, 255, true, arena);
}

enum { MASK_BLOCK = 64 };

/* d = s where m != 0, else 0, block by block: a block the mask leaves out
 * entirely is zeroed without reading s (most of a lane ROI's frame). Not
 * restrict: d may be s (element-wise, so that is safe; the compiler checks
 * overlap at run time). */
static void mask_row(const uint8_t *s, const uint8_t *m, uint8_t *d, int32_t width)
{
    int32_t x = 0;
    for (; x + MASK_BLOCK <= width; x += MASK_BLOCK) {
        uint8_t any = 0;
        for (int32_t i = 0; i < MASK_BLOCK; i++)
            any |= m[x + i];
        if (!any) {
            memset(d + x, 0, MASK_BLOCK);
            continue;
        }
        for (int32_t i = 0; i < MASK_BLOCK; i++)
            d[x + i] = (uint8_t)(s[x + i] & (uint8_t) - (m[x + i] != 0));
    }
    for (; x < width; x++)
        d[x] = (uint8_t)(s[x] & (uint8_t) - (m[x] != 0));
}

rte_status rte_polygon_mask_apply(const rte_image_u8 *src, const rte_image_u8 *mask,
                                  rte_image_u8 *dst)
{
    rte_status st = rte_image_u8_check_pair(src, mask);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    for (int32_t y = 0; y < dst->height; y++)
        mask_row(rte_u8_row(src, y), rte_u8_row(mask, y), rte_u8_row(dst, y), dst->width);
    return RTE_OK;
}

/* One row of dst: src's pixels on the walk's spans, 0 between them. Spans
 * come in order and may share their end pixel. */
static void keep_spans(const edge_walk *w, const uint8_t *s, uint8_t *d, int32_t width)
{
    int32_t pos = 0, x1, x2;
    for (int32_t i = 0; 2 * i + 1 < w->nact; i++) {
        if (!walk_span(w, i, width, &x1, &x2) || x2 < pos)
            continue;
        if (x1 > pos)
            memset(d + pos, 0, (size_t)(x1 - pos));
        else
            x1 = pos;
        memcpy(d + x1, s + x1, (size_t)(x2 - x1 + 1));
        pos = x2 + 1;
    }
    if (pos < width)
        memset(d + pos, 0, (size_t)(width - pos));
}

static bool images_overlap(const rte_image_u8 *a, const rte_image_u8 *b)
{
    const uint8_t *a_end = a->buf + (size_t)(a->height - 1) * (size_t)a->stride + a->width;
    const uint8_t *b_end = b->buf + (size_t)(b->height - 1) * (size_t)b->stride + b->width;
    return a->buf < b_end && b->buf < a_end;
}

rte_status rte_polygon_keep_u8(const rte_image_u8 *src, const rte_polygon *polygons,
                               int32_t polygon_count, rte_image_u8 *dst, rte_arena *arena)
{
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    if (images_overlap(src, dst))
        return RTE_ERR_ARGUMENT;
    size_t mark = 0;
    poly_edge *edges = NULL;
    int32_t *active = NULL, n = 0;
    st = collect_polygon_edges(polygons, polygon_count, arena, &mark, &edges, &active, &n);
    if (st != RTE_OK)
        return st;
    /* The fill's spans row by row, then the outlines, which may reach a
     * pixel or a run beyond a span's rounded ends: their pixels from src
     * (the mask is 255 there). */
    int32_t cleared = 0;
    if (n >= 2) {
        edge_walk w;
        edge_walk_start(&w, edges, n, active, dst->height);
        while (edge_walk_row(&w)) {
            clear_rows(dst, &cleared, w.y);
            keep_spans(&w, rte_u8_row(src, w.y), rte_u8_row(dst, w.y), dst->width);
            cleared = w.y + 1;
            edge_walk_next(&w);
        }
    }
    clear_rows(dst, &cleared, dst->height);
    draw_outlines(dst, src, polygons, polygon_count, 0);
    rte_arena_reset(arena, mark);
    return RTE_OK;
}

/* floor((f * size + 2^15) / 2^16): the nearest pixel, halves up. */
static int32_t fraction_to_pixel(int32_t f, int32_t size)
{
    return (int32_t)floor_q16((int64_t)f * size + (1 << (EDGE_SHIFT - 1)));
}

rte_status rte_polygon_from_fractions(const rte_vertex *frac, int32_t count, int32_t width,
                                      int32_t height, rte_vertex *out)
{
    if (count < 0 || (count > 0 && (!frac || !out)))
        return RTE_ERR_ARGUMENT;
    if (width < 1 || height < 1 || width > RTE_MAX_SIDE || height > RTE_MAX_SIDE)
        return RTE_ERR_SIZE;
    for (int32_t i = 0; i < count; i++) {
        rte_vertex f = frac[i];
        if (f.x < -RTE_POLYGON_MAX_FRACTION || f.x > RTE_POLYGON_MAX_FRACTION ||
            f.y < -RTE_POLYGON_MAX_FRACTION || f.y > RTE_POLYGON_MAX_FRACTION)
            return RTE_ERR_ARGUMENT;
    }
    for (int32_t i = 0; i < count; i++) {
        rte_vertex f = frac[i];
        out[i].x = fraction_to_pixel(f.x, width);
        out[i].y = fraction_to_pixel(f.y, height);
    }
    return RTE_OK;
}
