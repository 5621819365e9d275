/* Suzuki-Abe border following with OpenCV 4.6's exact conventions.
 *
 * The image is copied into a label map one pixel larger on every side
 * (int8: 0 background, 1 object, +label for a traced border pixel, and
 * label - 128 (negative) for a border pixel whose east neighbour was
 * examined and found to be background). The raster scan, the start rules,
 * the label cycling 2..127 and the parent search through per-label lists
 * all follow the legacy cv::findContours, because the hierarchy and the
 * output order depend on each of them. */
#include "rtedge/contours.h"

#include <string.h>

#include "row_scan.h"

/* Working record of one stored contour, in discovery order. */
typedef struct node {
    int32_t ox, oy;         /* start pixel in label-map coordinates */
    int32_t rx, ry, rw, rh; /* bounding box in label-map coordinates */
    bool is_hole;
    int32_t parent;     /* discovery index; -1 = the image frame */
    int32_t label_next; /* next stored contour with the same label */
    int32_t first_child, next_sibling;
    int32_t offset, count;
    int32_t out; /* index in the output order */
} node;

enum { NO_NODE = -1, UNSET = -2 };

static const int8_t chain_dx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
static const int8_t chain_dy[8] = {0, -1, -1, -1, 0, 1, 1, 1};

typedef struct tracer {
    int32_t delta[16]; /* chain code -> offset in the label map, twice over */
    bool simple;
    rte_point *points; /* where the next point goes; NULL when counting only */
    int32_t room;      /* points that still fit */
} tracer;

typedef struct box {
    int32_t x0, y0, x1, y1;
} box;

/* Follows one border from `i0` (label map) and labels it. Writes up to
 * t->room points (image coordinates, i.e. minus the padding) and returns how
 * many points the border has. */
static int32_t follow(const tracer *t, int8_t *i0, int32_t x, int32_t y, bool is_hole,
                      int32_t label, box *bb)
{
    const int32_t *d = t->delta;
    const int8_t mark = (int8_t)label, right_mark = (int8_t)(label - 128);
    int32_t n = 0;
    int s = is_hole ? 0 : 4, s_end = s;
    int8_t *i1;

    bb->x0 = bb->x1 = x;
    bb->y0 = bb->y1 = y;
    /* Clockwise search for the last neighbour before the start direction. */
    do {
        s = (s - 1) & 7;
        i1 = i0 + d[s];
    } while (*i1 == 0 && s != s_end);

    if (s == s_end) { /* isolated pixel */
        *i0 = right_mark;
        if (t->room > 0)
            t->points[0] = (rte_point){x - 1, y - 1};
        return 1;
    }

    int8_t *i3 = i0, *i4 = i0;
    int prev_s = s ^ 4;
    for (;;) {
        s_end = s;
        /* Counter-clockwise search for the next border pixel. */
        while (s < 15) {
            i4 = i3 + d[++s];
            if (*i4 != 0)
                break;
        }
        s &= 7;
        /* The east neighbour was passed over (it is background): this pixel
         * ends a run, which the raster scan must not take as a new start. */
        if ((unsigned)(s - 1) < (unsigned)s_end)
            *i3 = right_mark;
        else if (*i3 == 1)
            *i3 = mark;

        if (s != prev_s || !t->simple) {
            if (n < t->room)
                t->points[n] = (rte_point){x - 1, y - 1};
            n++;
            bb->x0 = x < bb->x0 ? x : bb->x0;
            bb->x1 = x > bb->x1 ? x : bb->x1;
            bb->y0 = y < bb->y0 ? y : bb->y0;
            bb->y1 = y > bb->y1 ? y : bb->y1;
        }
        prev_s = s;
        x += chain_dx[s];
        y += chain_dy[s];
        if (i4 == i0 && i3 == i1)
            break;
        i3 = i4;
        s = (s + 4) & 7;
    }
    return n;
}

/* Is the border starting at i0 the one a raster scan last crossed at
 * `stop`? (OpenCV's test that decides between two candidate parents sharing
 * a label.) A pixel can lie on several borders; when it ends a run (negative
 * label) only the pass that leaves it with no border pixel between the
 * arrival and the east direction counts. */
static int passes_through(const int32_t *d, const int8_t *i0, const int8_t *stop, bool is_hole)
{
    int s = is_hole ? 0 : 4, s_end = s;
    const int8_t *i1, *i3 = i0, *i4 = i0;

    do {
        s = (s - 1) & 7;
        i1 = i0 + d[s];
    } while (*i1 == 0 && s != s_end);

    if (s == s_end) /* isolated pixel */
        return i0 == stop;
    for (;;) {
        while (s < 15) {
            i4 = i3 + d[++s];
            if (*i4 != 0)
                break;
        }
        if (i3 == stop) {
            if (*i3 >= 0)
                return 1;
            for (int k = s;;) {
                k = (k - 1) & 7;
                if (i3[d[k]] != 0)
                    break;
                if (k == 0)
                    return 1;
            }
        }
        if (i4 == i0 && i3 == i1)
            return 0;
        i3 = i4;
        s = (s + 4) & 7;
    }
}

static size_t label_map_bytes(int32_t w, int32_t h) { return (size_t)(w + 2) * (size_t)(h + 2); }

size_t rte_contours_scratch_size(int32_t max_width, int32_t max_height, int32_t max_contours)
{
    if (max_width < 1 || max_height < 1 || max_contours < 0)
        return 0;
    return rte_arena_piece_size(label_map_bytes(max_width, max_height)) +
           rte_arena_piece_size((size_t)max_contours * sizeof(node) + 1);
}

/* Copies src into the label map as 0/1 with a zero frame. The width is a
 * local: with src->width in the loop test, each byte store (which may
 * alias it) forced a reload and kept the loop scalar. */
static void fill_label_map(const rte_image_u8 *src, int8_t *map, int32_t ms)
{
    const int32_t w = src->width, h = src->height;
    memset(map, 0, (size_t)ms);
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *restrict s = rte_u8_row(src, y);
        int8_t *restrict m = map + (size_t)(y + 1) * ms;
        m[0] = 0;
        for (int32_t x = 0; x < w; x++)
            m[x + 1] = (int8_t)(s[x] != 0);
        m[ms - 1] = 0;
    }
    memset(map + (size_t)(h + 1) * ms, 0, (size_t)ms);
}

/* Finds the parent of a border starting on row y whose nearest border pixel
 * to the left (lnbd) is at row + lx, as OpenCV does: the newest stored border
 * with lnbd's label whose box holds lnbd, checked by tracing when several
 * do; then a border of the same kind hands over its own parent. */
static int32_t find_parent(node *nodes, const int32_t *heads, const int32_t *d, const int8_t *map,
                           int32_t ms, const int8_t *row, int32_t lx, int32_t y, bool is_hole)
{
    int32_t par = UNSET;
    for (int32_t cur = heads[row[lx] & 0x7f]; cur != NO_NODE; cur = nodes[cur].label_next) {
        const node *c = &nodes[cur];
        if ((uint32_t)(lx - c->rx) < (uint32_t)c->rw && (uint32_t)(y - c->ry) < (uint32_t)c->rh) {
            if (par != UNSET && passes_through(d, map + (size_t)nodes[par].oy * ms + nodes[par].ox,
                                               row + lx, nodes[par].is_hole))
                break;
            par = cur;
        }
    }
    if (par == UNSET) /* cannot happen for a consistent label map */
        return NO_NODE;
    if (nodes[par].is_hole == is_hole)
        par = nodes[par].parent;
    return par;
}

/* Writes the stored contours in OpenCV's order: depth-first pre-order,
 * children and top-level contours newest first. */
static void emit(node *nodes, int32_t top, rte_contours *out)
{
    int32_t k = 0;
    for (int32_t n = top; n != NO_NODE;) {
        nodes[n].out = k++;
        if (nodes[n].first_child != NO_NODE) {
            n = nodes[n].first_child;
            continue;
        }
        while (n != NO_NODE && nodes[n].next_sibling == NO_NODE)
            n = nodes[n].parent;
        if (n != NO_NODE)
            n = nodes[n].next_sibling;
    }
    for (int32_t i = 0; i < out->n_contours; i++)
        out->contours[i].hierarchy[1] = -1;
    for (int32_t i = 0; i < out->n_contours; i++) {
        const node *n = &nodes[i];
        rte_contour *c = &out->contours[n->out];
        c->offset = n->offset;
        c->count = n->count;
        c->is_hole = n->is_hole;
        c->hierarchy[0] = n->next_sibling == NO_NODE ? -1 : nodes[n->next_sibling].out;
        c->hierarchy[2] = n->first_child == NO_NODE ? -1 : nodes[n->first_child].out;
        c->hierarchy[3] = n->parent == NO_NODE ? -1 : nodes[n->parent].out;
        if (n->next_sibling != NO_NODE)
            out->contours[nodes[n->next_sibling].out].hierarchy[1] = n->out;
    }
}

/* The scan's state: the tracer, the stored contours with their label
 * chains and the top-level list, and whether a bound has been hit (from
 * then on borders are only counted). */
typedef struct finder {
    tracer t;
    node *nodes;
    int32_t heads[128];
    int32_t top, n_nodes, label;
    bool hierarchic, full;
    rte_contours *out;
} finder;

/* Traces the border starting at row + x0 (label map row y) with parent
 * par, and stores it or counts it as dropped. */
static void trace_border(finder *f, int8_t *row, int32_t x0, int32_t y, bool is_hole, int32_t par)
{
    rte_contours *out = f->out;
    int32_t lval = 2;
    if (f->hierarchic) {
        lval = f->label;
        f->label = (f->label + 1) & 127;
        f->label += f->label == 0 ? 3 : 0;
    }
    if (!f->full && f->n_nodes == out->max_contours)
        f->full = true;
    f->t.points = f->full ? NULL : out->points + out->n_points;
    f->t.room = f->full ? 0 : out->max_points - out->n_points;
    box bb;
    int32_t n = follow(&f->t, row + x0, x0, y, is_hole, lval, &bb);
    if (!f->full && n > f->t.room)
        f->full = true;
    if (f->full) {
        out->truncated = true;
        out->dropped_contours++;
        out->dropped_points += n;
        return;
    }
    node *c = &f->nodes[f->n_nodes];
    c->ox = x0;
    c->oy = y;
    c->rx = bb.x0;
    c->ry = bb.y0;
    c->rw = bb.x1 - bb.x0 + 1;
    c->rh = bb.y1 - bb.y0 + 1;
    c->is_hole = is_hole;
    c->parent = par;
    c->label_next = f->heads[lval];
    f->heads[lval] = f->n_nodes;
    c->first_child = NO_NODE;
    int32_t *first = par == NO_NODE ? &f->top : &f->nodes[par].first_child;
    c->next_sibling = *first;
    *first = f->n_nodes;
    c->offset = out->n_points;
    c->count = n;
    out->n_points += n;
    f->n_nodes++;
}

/* The raster scan over the label map: starts a border where the rules
 * say so and keeps lnbd, the last border pixel seen on the row. */
static void scan_borders(finder *f, int8_t *map, int32_t ms, int32_t mh, rte_contour_mode mode)
{
    for (int32_t y = 1; y < mh - 1; y++) {
        int8_t *row = map + (size_t)y * ms;
        int32_t lnbd = 0;
        int prev = 0;
        for (int32_t x = 1; x < ms - 1; x++) {
            x = rte_row_skip_run((const uint8_t *)row, x, ms - 1, (uint8_t)prev);
            if (x >= ms - 1)
                break;
            int p = row[x];
            bool is_hole = false;
            if (!(prev == 0 && p == 1)) {
                if (p != 0 || prev < 1)
                    goto resume;
                if (prev & -2)
                    lnbd = x - 1;
                is_hole = true;
            }
            if (mode == RTE_CONTOURS_EXTERNAL && (is_hole || row[lnbd] > 0))
                goto resume;

            int32_t par = NO_NODE;
            if (!f->full && f->hierarchic && !(mode == RTE_CONTOURS_CCOMP && !is_hole) && lnbd > 0)
                par = find_parent(f->nodes, f->heads, f->t.delta, map, ms, row, lnbd, y, is_hole);
            lnbd = x - is_hole;
            trace_border(f, row, x - is_hole, y, is_hole, par);
            prev = row[x]; /* the start pixel now carries its label */
            continue;
        resume:
            prev = p;
            if (prev & -2)
                lnbd = x;
        }
    }
}

rte_status rte_contours_find(const rte_image_u8 *src, rte_contour_mode mode,
                             rte_contour_method method, rte_contours *out, rte_arena *scratch)
{
    rte_status st = rte_image_u8_check(src);
    if (st != RTE_OK)
        return st;
    if (!out || !scratch || (unsigned)mode > RTE_CONTOURS_TREE ||
        (method != RTE_CONTOURS_APPROX_NONE && method != RTE_CONTOURS_APPROX_SIMPLE) ||
        out->max_points < 0 || out->max_contours < 0 || (out->max_points && !out->points) ||
        (out->max_contours && !out->contours))
        return RTE_ERR_ARGUMENT;
    out->n_points = out->n_contours = 0;
    out->truncated = false;
    out->dropped_contours = 0;
    out->dropped_points = 0;

    const size_t mark = rte_arena_mark(scratch);
    const int32_t ms = src->width + 2, mh = src->height + 2;
    int8_t *map = (int8_t *)rte_arena_alloc(scratch, label_map_bytes(src->width, src->height));
    node *nodes = (node *)rte_arena_alloc(scratch, (size_t)out->max_contours * sizeof(node) + 1);
    if (!map || !nodes) {
        rte_arena_reset(scratch, mark);
        return RTE_ERR_NO_MEMORY;
    }
    fill_label_map(src, map, ms);

    finder f = {.nodes = nodes,
                .top = NO_NODE,
                .label = 2,
                .out = out,
                .hierarchic = mode >= RTE_CONTOURS_CCOMP};
    for (int k = 0; k < 16; k++) {
        int c = k & 7;
        f.t.delta[k] = chain_dy[c] * ms + chain_dx[c];
    }
    f.t.simple = method == RTE_CONTOURS_APPROX_SIMPLE;
    for (int k = 0; k < 128; k++)
        f.heads[k] = NO_NODE;

    scan_borders(&f, map, ms, mh, mode);
    out->n_contours = f.n_nodes;
    emit(nodes, f.top, out);
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}
