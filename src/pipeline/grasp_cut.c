/* The grasp path's placement of the cut between split parts (grasp_ctx.h,
 * rte_grasp_refine_cut), per frame, integer only.
 *
 * The distance split cuts at the narrowest point of an outline, which the
 * shadow between two touching objects or their soft edges may move
 * towards one of them: a red sweet loses its side to a brown one. So the
 * pixels within a band around the cut (half the smallest part's inscribed
 * radius, in 8-connected steps) are flooded again from the parts beyond the
 * band and from the table beside it, in order of grey difference: a
 * priority flood as cv::watershed's from its markers (each pixel takes the
 * part of the 4-neighbour it is reached from at the least difference, and
 * is the line between two parts where they meet). The parts then meet at
 * the strongest grey edge between them; on an even grey in the band's
 * middle, where the distance cut; band pixels the table reaches first (a
 * shadow's light rim) are cleared. */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "grasp_ctx.h"

/* the band's half-width: the smallest part's inscribed radius / this */
#define BAND_DIVISOR 2

/* the crop's labels: 1..LABEL_MAX are parts */
#define LABEL_WALL 0     /* not the object's, or a line between parts */
#define LABEL_MAX 252    /* parts */
#define LABEL_TABLE 253  /* the table: floods the band too */
#define LABEL_BAND 254   /* to flood */
#define LABEL_QUEUED 255 /* in the flood's queue */

static bool is_part(uint8_t label) { return label != LABEL_WALL && label <= LABEL_MAX; }

static bool is_seed(uint8_t label) { return label != LABEL_WALL && label <= LABEL_TABLE; }

typedef struct band_box {
    int32_t x0, y0, x1, y1; /* inclusive */
} band_box;

/* A bucket queue of crop pixels by level 0..255, first in first out
 * within a level. */
typedef struct grey_flood {
    int32_t *next;     /* per crop pixel: the next in its level's list */
    int32_t head[256]; /* -1: empty */
    int32_t tail[256];
    int32_t lowest; /* no level below it holds a pixel */
} grey_flood;

static void flood_push(grey_flood *f, int32_t i, int32_t level)
{
    f->next[i] = -1;
    if (f->head[level] < 0)
        f->head[level] = i;
    else
        f->next[f->tail[level]] = i;
    f->tail[level] = i;
    f->lowest = level < f->lowest ? level : f->lowest;
}

static int32_t flood_pop(grey_flood *f)
{
    while (f->lowest < 256 && f->head[f->lowest] < 0)
        f->lowest++;
    if (f->lowest == 256)
        return -1;
    const int32_t i = f->head[f->lowest];
    f->head[f->lowest] = f->next[i];
    return i;
}

/* The fills' stacks and queues hold a pixel as y << 16 | x (a crop side
 * is at most RTE_SHAPE_MAX_COORD + 1): no division per pixel. */
#define PACK(x, y) ((y) << 16 | (x))
#define PACKED_X(p) ((p)&0xFFFF)
#define PACKED_Y(p) ((p) >> 16)

/* Labels the 8-connected parts of own (1, 2, ...) in lab, where the
 * object's pixels are LABEL_BAND; stack[] holds the fill. Returns the
 * parts, 0 when more than LABEL_MAX; *band_px: the band's half-width. */
static int32_t label_parts(const uint8_t *own, const uint16_t *dist, int32_t cw, int32_t ch,
                           int64_t min_area, uint8_t *lab, int32_t *stack, int32_t *band_px)
{
    int32_t parts = 0, least = INT32_MAX;
    for (int32_t y = 0; y < ch; y++)
        for (int32_t x = 0; x < cw; x++) {
            const int32_t i = y * cw + x;
            if (!own[i] || lab[i] != LABEL_BAND)
                continue;
            if (parts == LABEL_MAX)
                return 0;
            lab[i] = (uint8_t)++parts;
            int32_t top = 0, peak = 0, area = 0;
            stack[top++] = PACK(x, y);
            while (top) {
                const int32_t p = stack[--top], jx = PACKED_X(p), jy = PACKED_Y(p);
                const int32_t j = jy * cw + jx;
                peak = dist[j] > peak ? dist[j] : peak;
                area++;
                for (int32_t ny = jy - 1; ny <= jy + 1; ny++)
                    for (int32_t nx = jx - 1; nx <= jx + 1; nx++) {
                        const int32_t k = ny * cw + nx;
                        if (nx < 0 || ny < 0 || nx >= cw || ny >= ch || !own[k] ||
                            lab[k] != LABEL_BAND)
                            continue;
                        lab[k] = (uint8_t)parts;
                        stack[top++] = PACK(nx, ny);
                    }
            }
            if (area >= min_area && peak < least)
                least = peak;
        }
    /* the split's CHAMFER34 distance is in thirds of a pixel */
    *band_px = least == INT32_MAX ? 0 : least / (3 * BAND_DIVISOR);
    return parts;
}

/* Turns the part pixels within band_px 8-connected steps of the cut (the
 * object's pixels left LABEL_BAND) to LABEL_BAND too; queue[] is the
 * breadth-first queue. Returns the band's box. */
static band_box widen_band(uint8_t *lab, int32_t cw, int32_t ch, int32_t band_px, int32_t *queue)
{
    band_box b = {cw, ch, -1, -1};
    int32_t end = 0;
    for (int32_t y = 0; y < ch; y++)
        for (int32_t x = 0; x < cw; x++)
            if (lab[y * cw + x] == LABEL_BAND)
                queue[end++] = PACK(x, y);
    for (int32_t start = 0, step = 0; start < end; step++) {
        const int32_t layer_end = end;
        for (; start < layer_end; start++) {
            const int32_t x = PACKED_X(queue[start]), y = PACKED_Y(queue[start]);
            b = (band_box){x < b.x0 ? x : b.x0, y < b.y0 ? y : b.y0, x > b.x1 ? x : b.x1,
                           y > b.y1 ? y : b.y1};
            for (int32_t ny = y - 1; ny <= y + 1 && step < band_px; ny++)
                for (int32_t nx = x - 1; nx <= x + 1; nx++) {
                    const int32_t k = ny * cw + nx;
                    if (nx < 0 || ny < 0 || nx >= cw || ny >= ch || !is_part(lab[k]))
                        continue;
                    lab[k] = LABEL_BAND;
                    queue[end++] = PACK(nx, ny);
                }
        }
    }
    return b;
}

/* The seed (part or table) of the 4-neighbour of pixel (x, y) nearest in
 * grey, and that difference in *diff; LABEL_WALL when there is none, or
 * where two parts meet (the line between them). */
static uint8_t nearest_seed(const uint8_t *lab, const rte_image_u8 *grey, int32_t cw, int32_t ch,
                            int32_t x, int32_t y, int32_t *diff)
{
    static const int8_t dx4[4] = {-1, 1, 0, 0}, dy4[4] = {0, 0, -1, 1};
    const int32_t g = rte_u8_row(grey, y)[x];
    uint8_t best = LABEL_WALL, part = LABEL_WALL;
    *diff = 256;
    for (int32_t d = 0; d < 4; d++) {
        const int32_t nx = x + dx4[d], ny = y + dy4[d];
        if (nx < 0 || ny < 0 || nx >= cw || ny >= ch || !is_seed(lab[ny * cw + nx]))
            continue;
        const uint8_t l = lab[ny * cw + nx];
        if (is_part(l) && part != LABEL_WALL && l != part)
            return LABEL_WALL;
        part = is_part(l) ? l : part;
        const int32_t gd = rte_u8_row(grey, ny)[nx] - g, ad = gd < 0 ? -gd : gd;
        if (ad < *diff) {
            *diff = ad;
            best = l;
        }
    }
    return best;
}

/* Floods the band (inside box b) from its seeds, the least grey
 * difference first. */
static void flood_band(uint8_t *lab, const rte_image_u8 *grey, int32_t cw, int32_t ch, band_box b,
                       int32_t *next)
{
    static const int8_t dx4[4] = {-1, 1, 0, 0}, dy4[4] = {0, 0, -1, 1};
    grey_flood f = {.next = next, .lowest = 256};
    memset(f.head, -1, sizeof f.head);
    for (int32_t y = b.y0; y <= b.y1; y++)
        for (int32_t x = b.x0; x <= b.x1; x++) {
            int32_t diff;
            if (lab[y * cw + x] == LABEL_BAND && nearest_seed(lab, grey, cw, ch, x, y, &diff)) {
                flood_push(&f, y * cw + x, diff);
                lab[y * cw + x] = LABEL_QUEUED;
            }
        }
    for (int32_t i; (i = flood_pop(&f)) >= 0;) {
        const int32_t x = i % cw, y = i / cw, g = rte_u8_row(grey, y)[x];
        int32_t diff;
        lab[i] = nearest_seed(lab, grey, cw, ch, x, y, &diff);
        if (lab[i] == LABEL_WALL)
            continue;
        for (int32_t d = 0; d < 4; d++) {
            const int32_t nx = x + dx4[d], ny = y + dy4[d], k = ny * cw + nx;
            if (nx < 0 || ny < 0 || nx >= cw || ny >= ch || lab[k] != LABEL_BAND)
                continue;
            const int32_t gd = rte_u8_row(grey, ny)[nx] - g;
            flood_push(&f, k, gd < 0 ? -gd : gd);
            lab[k] = LABEL_QUEUED;
        }
    }
}

/* own = the parts of lab in box b and a pixel around it (outside, own is
 * already its parts), cut apart 8-connectivity safe: a pixel with an
 * 8-neighbour in a part of lower label is cleared. */
static void draw_parts(const uint8_t *lab, int32_t cw, int32_t ch, band_box b, uint8_t *own)
{
    const int32_t x0 = b.x0 > 0 ? b.x0 - 1 : 0, x1 = b.x1 < cw - 1 ? b.x1 + 1 : cw - 1;
    const int32_t y0 = b.y0 > 0 ? b.y0 - 1 : 0, y1 = b.y1 < ch - 1 ? b.y1 + 1 : ch - 1;
    for (int32_t y = y0; y <= y1; y++)
        for (int32_t x = x0; x <= x1; x++) {
            const uint8_t l = lab[y * cw + x];
            bool keep = is_part(l);
            for (int32_t ny = y - 1; ny <= y + 1 && keep; ny++)
                for (int32_t nx = x - 1; nx <= x + 1 && keep; nx++)
                    if (nx >= 0 && ny >= 0 && nx < cw && ny < ch)
                        keep = !is_part(lab[ny * cw + nx]) || lab[ny * cw + nx] >= l;
            own[y * cw + x] = keep ? 255 : 0;
        }
}

rte_status rte_grasp_refine_cut(rte_grasp_ctx *ctx, const rte_image_u8 *grey,
                                const rte_image_u8 *box, const uint8_t *inside, uint8_t *own,
                                const uint16_t *dist, int32_t cw, int32_t ch)
{
    const size_t mark = rte_arena_mark(&ctx->arena), n = (size_t)cw * (size_t)ch;
    uint8_t *lab = rte_arena_alloc(&ctx->arena, n);
    int32_t *next = rte_arena_alloc(&ctx->arena, n * sizeof *next);
    if (!lab || !next) {
        rte_arena_reset(&ctx->arena, mark);
        return RTE_ERR_NO_MEMORY;
    }
    for (int32_t y = 0; y < ch; y++) {
        const uint8_t *b = rte_u8_row(box, y), *in = inside + (size_t)y * cw;
        for (int32_t x = 0; x < cw; x++)
            lab[y * cw + x] = !b[x] ? LABEL_TABLE : in[x] ? LABEL_BAND : LABEL_WALL;
    }
    int32_t band_px = 0;
    if (label_parts(own, dist, cw, ch, ctx->params.min_area, lab, next, &band_px) >= 2 &&
        band_px > 0) {
        const band_box b = widen_band(lab, cw, ch, band_px, next);
        flood_band(lab, grey, cw, ch, b, next);
        draw_parts(lab, cw, ch, b, own);
    }
    rte_arena_reset(&ctx->arena, mark);
    return RTE_OK;
}
