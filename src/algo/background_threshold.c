/* The two-sided threshold of a frame against the table's brightness (see
 * include/rtedge/background.h; the brightness is background.c, the colour
 * against the table background_colour.c). Per
 * frame, integer only. */
#include <stdint.h>
#include <string.h>

#include "rtedge/background.h"
#include "rtedge/threshold.h"

#include "row_scan.h"
#include "rtedge/cpu.h"
#include "simd/rows.h"

void rte_background_threshold_params_default(rte_background_threshold_params *params, int32_t width)
{
    const int32_t gap = width / 200;
    *params = (rte_background_threshold_params){.high = 0,
                                                .min_contrast = 20,
                                                .bright = true,
                                                .dark = true,
                                                .drop_shadows = true,
                                                .shadow_gap = gap < 3 ? 3 : gap,
                                                .region_share_permille = 400,
                                                .shadow_min_area = 64};
}

/* Regions are labelled by runs: a run is a maximal horizontal stretch of
 * pixels of one side; runs of one side that touch (8-connected) in
 * consecutive rows are united (union-find over run indices). A region's
 * root run holds its pixel count, sum of |d| and flags. */
enum {
    REGION_STRONG = 1,
    REGION_DARK = 2,
    REGION_SHADOW = 4,
    REGION_SHADE = 8 /* side 3: dark and in the shade mask */
};

typedef struct run_table {
    int32_t *x0, *x1, *parent, *count;
    /* with a shade mask: object[] unites dark and shade runs alike (the
     * object, as without the mask); on an object's root, core[] is its
     * core and first[] its first run left (settle_shade) */
    int32_t *object, *core, *first;
    bool shade; /* runs of side 3 are labelled (objects[] is kept) */
    int64_t *sum;
    uint8_t *flags;
    int32_t *row_start; /* runs of row y: row_start[y] .. row_start[y + 1] - 1 */
    uint8_t *row;       /* a row's classes, then its floors (paint_regions) */
    int32_t capacity;
} run_table;

/* Runs the table holds for a w x h frame: an average of one per 4 pixels
 * (every other pixel flipping side, all over the frame, exceeds it). */
static int32_t run_capacity(int32_t w, int32_t h)
{
    const int64_t n = (int64_t)w * h / 4 + h;
    return n > INT32_MAX ? INT32_MAX : (int32_t)n;
}

size_t rte_background_threshold_scratch_size(int32_t max_width, int32_t max_height)
{
    if (max_width < 1 || max_height < 1)
        return 0;
    const size_t runs = (size_t)run_capacity(max_width, max_height);
    /* per run: x0, x1, parent, count, and the shade's object, core, first */
    return rte_arena_piece_size(runs * sizeof(int32_t)) * 7 +
           rte_arena_piece_size(runs * sizeof(int64_t)) + /* sum */
           rte_arena_piece_size(runs) +                   /* flags */
           rte_arena_piece_size(((size_t)max_height + 1) * sizeof(int32_t)) +
           rte_arena_piece_size((size_t)max_width); /* a row's classes */
}

static int32_t find_root(int32_t *parent, int32_t a)
{
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

/* Unites two trees under the smaller root index (roots precede their runs). */
static void unite(int32_t *parent, int32_t a, int32_t b)
{
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* A pixel's class for the labelling (background_rows.h's classify row):
 * its side where |d| > low and the side is looked for, else 0; the side
 * again two bits up where |d| > high. Side 3 is a dark pixel that may be
 * shade (rte_background_shade_u8). */
enum { CLASS_SIDE = 3, CLASS_STRONG = 12 };

/* The end of the run of side `side` that starts at x (the first x1 > x
 * whose class has another side, or w); *classes gets the OR of the run's
 * classes. Eight bytes at a time. */
static inline int32_t run_end(const uint8_t *c, int32_t x, int32_t w, uint32_t side,
                              uint32_t *classes)
{
    const uint64_t ones = 0x0101010101010101u, want = ones * side;
    uint64_t seen = 0;
    for (; x + 8 <= w; x += 8) {
        uint64_t v;
        memcpy(&v, c + x, sizeof v);
        const uint64_t other = (v ^ want) & ones * CLASS_SIDE;
        if (other) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
            const int32_t k = __builtin_ctzll(other) >> 3;
            seen |= v & ((UINT64_C(1) << (8 * k)) - 1); /* k < 8 */
            x += k;
            seen |= seen >> 32;
            seen |= seen >> 16;
            seen |= seen >> 8;
            *classes = (uint32_t)seen & 0xFF;
            return x;
#else
            break;
#endif
        }
        seen |= v;
    }
    seen |= seen >> 32;
    seen |= seen >> 16;
    seen |= seen >> 8;
    uint32_t acc = (uint32_t)seen & 0xFF;
    for (; x < w && (c[x] & CLASS_SIDE) == side; x++)
        acc |= c[x];
    *classes = acc;
    return x;
}

/* The sum of a[0..n): a loop the compiler vectorises. */
static inline int64_t sum_bytes(const uint8_t *a, int32_t n)
{
    uint32_t sum = 0; /* n <= 2^23 (RTE_MAX_SIDE) */
    for (int32_t k = 0; k < n; k++)
        sum += a[k];
    return sum;
}

/* One row's runs, appended to the table; unites them with the touching runs
 * of the previous row. a: |d| of the row; c: the classes of its pixels
 * (classify_row). A run is a maximal stretch of pixels of one side (class
 * 1 or 2). Returns the pixels left out for want of room. */
static int64_t label_row(run_table *t, int32_t y, const uint8_t *a, const uint8_t *c, int32_t w,
                         int32_t *n_runs)
{
    int64_t dropped = 0;
    int32_t n = *n_runs;
    t->row_start[y] = n;
    for (int32_t x = rte_row_skip_run(c, 0, w, 0); x < w; x = rte_row_skip_run(c, x, w, 0)) {
        const int32_t x0 = x;
        const uint32_t side = c[x] & CLASS_SIDE;
        uint32_t classes;
        x = run_end(c, x, w, side, &classes);
        if (n == t->capacity) {
            dropped += x - x0;
            continue;
        }
        t->x0[n] = x0;
        t->x1[n] = x - 1;
        t->parent[n] = n;
        t->object[n] = n;
        t->count[n] = x - x0;
        t->sum[n] = sum_bytes(a + x0, x - x0);
        t->flags[n] = (uint8_t)(((classes & CLASS_STRONG) ? REGION_STRONG : 0) |
                                (side == 1 ? 0 : REGION_DARK) | (side == 3 ? REGION_SHADE : 0));
        n++;
    }
    t->row_start[y + 1] = n;
    /* dark and shade runs side by side are one object */
    for (int32_t r = t->row_start[y] + 1; r < n && t->shade; r++)
        if ((t->flags[r] & t->flags[r - 1] & REGION_DARK) && t->x1[r - 1] + 1 == t->x0[r])
            unite(t->object, r - 1, r);
    if (y > 0) { /* 8-connected: runs overlapping or meeting at a corner */
        int32_t p = t->row_start[y - 1];
        const int32_t p_end = t->row_start[y];
        for (int32_t r = t->row_start[y]; r < n; r++) {
            while (p < p_end && t->x1[p] < t->x0[r] - 1)
                p++;
            for (int32_t q = p; q < p_end && t->x0[q] <= t->x1[r] + 1; q++) {
                if (((t->flags[q] ^ t->flags[r]) & (REGION_DARK | REGION_SHADE)) == 0)
                    unite(t->parent, q, r);
                if (t->shade && (t->flags[q] & t->flags[r] & REGION_DARK))
                    unite(t->object, q, r);
            }
        }
    }
    *n_runs = n;
    return dropped;
}

/* Whether dark run r's region is the shadow of a bright region within
 * `gap` px of it: one both larger and of higher mean contrast (compared as
 * sum_b * count_d > sum_d * count_b). cursor[k] is the first run of row
 * y - gap + k that may reach r: runs of a row come in x order, so the
 * cursors only move on along row y. */
static bool casts_shadow_on(const run_table *t, int32_t y, int32_t h, int32_t gap, int32_t rd,
                            int32_t r, int32_t *cursor)
{
    for (int32_t k = 0; k <= 2 * gap; k++) {
        const int32_t yy = y - gap + k;
        if (yy < 0 || yy >= h)
            continue;
        const int32_t end = t->row_start[yy + 1];
        while (cursor[k] < end && t->x1[cursor[k]] < t->x0[r] - gap)
            cursor[k]++;
        for (int32_t q = cursor[k]; q < end && t->x0[q] <= t->x1[r] + gap; q++) {
            const int32_t rb = t->parent[q];
            if ((t->flags[rb] & (REGION_DARK | REGION_STRONG)) == REGION_STRONG &&
                t->count[rb] > t->count[rd] &&
                t->sum[rb] * t->count[rd] > t->sum[rd] * t->count[rb])
                return true;
        }
    }
    return false;
}

/* dst holds |d|: each kept region's pixels beyond its own floor (share per
 * mille of its mean |d|) become 255, everything else 0. Per row: the
 * floors of the kept runs, 255 elsewhere (|d| is never above it), then one
 * compare over the row. */
static void paint_regions(const run_table *t, rte_image_u8 *dst, int32_t share,
                          const rte_background_rows *rows)
{
    uint8_t *fl = t->row;
    for (int32_t y = 0; y < dst->height; y++) {
        uint8_t *out = rte_u8_row(dst, y);
        memset(fl, 255, (size_t)dst->width);
        for (int32_t r = t->row_start[y]; r < t->row_start[y + 1]; r++) {
            const int32_t root = t->parent[r];
            if ((t->flags[root] & (REGION_STRONG | REGION_SHADOW | REGION_SHADE)) != REGION_STRONG)
                continue;
            /* floor = share of the region's mean |d| (sum <= 255 count) */
            const int32_t floor =
                (int32_t)(t->sum[root] * share / ((int64_t)t->count[root] * 1000));
            memset(fl + t->x0[r], floor, (size_t)(t->x1[r] + 1 - t->x0[r]));
        }
        rows->above_floor(out, fl, dst->width);
    }
}

enum { NO_CORE = -1, CORES = -2 };

/* An object (dark and shade runs connected) whose dark pixels outside
 * the shade mask form one core (a region of min_area px or more: specks
 * of noise do not count) may lie beside its cast shadow: a shade region
 * of min_area px or more, at least a twentieth of the core and lighter
 * than it (mean |d|). Those are dropped (flagged REGION_SHADOW); the rest
 * of every object becomes one region, as without the mask (an object with
 * two or more cores keeps its shade: a grey band between two dark parts).
 * Returns how many were dropped. */
static int32_t settle_shade(run_table *t, int32_t n, int32_t min_area)
{
    /* every run straight to its root in both (roots come first: parent[r]
     * <= r), the areas and sums of |d| on the roots (the statistics pass
     * after this adds what the unions below move) */
    for (int32_t r = 0; r < n; r++) {
        t->object[r] = t->object[t->object[r]];
        t->core[r] = NO_CORE;
        const int32_t root = t->parent[t->parent[r]];
        t->parent[r] = root;
        if (root == r)
            continue;
        t->count[root] += t->count[r];
        t->sum[root] += t->sum[r];
        t->count[r] = 0;
        t->sum[r] = 0;
    }
    /* each object's core, on the object's root */
    for (int32_t r = 0; r < n; r++) {
        if ((t->flags[r] & (REGION_DARK | REGION_SHADE)) != REGION_DARK || t->parent[r] != r ||
            t->count[r] < min_area)
            continue;
        int32_t *c = &t->core[t->object[r]];
        *c = *c == NO_CORE ? r : CORES;
    }
    /* the shadows: beside their object's one core, large enough and
     * lighter (sum_s / count_s < sum_c / count_c) */
    int32_t dropped = 0;
    for (int32_t r = 0; r < n; r++) {
        if (!(t->flags[r] & REGION_SHADE) || t->parent[r] != r)
            continue;
        const int32_t c = t->core[t->object[r]];
        if (c >= 0 && t->count[r] >= min_area && t->count[r] * 20 >= t->count[c] &&
            t->sum[r] * t->count[c] < t->sum[c] * t->count[r]) {
            t->flags[r] |= REGION_SHADOW;
            dropped++;
        }
    }
    /* the rest of each object into one region, under its first run left */
    for (int32_t r = 0; r < n; r++)
        t->first[r] = -1;
    for (int32_t r = 0; r < n; r++) {
        if (!(t->flags[r] & REGION_DARK) || (t->flags[t->parent[r]] & REGION_SHADOW))
            continue;
        t->flags[r] &= (uint8_t)~REGION_SHADE;
        int32_t *first = &t->first[t->object[r]];
        if (*first < 0)
            *first = r;
        else
            unite(t->parent, *first, r);
    }
    return dropped;
}

/* The runs of the frame's pixels beyond low (absd: |src - background|),
 * of dark pixels in shade (a half-size mask) on a side of their own.
 * Returns the pixels left out for want of room; *n_runs the runs. */
static int64_t label_frame(run_table *t, const rte_image_u8 *src, const rte_image_u8 *background,
                           const rte_image_u8 *shade, const rte_image_u8 *absd, int32_t low,
                           int32_t high, const rte_background_threshold_params *params,
                           const rte_background_rows *rows, int32_t *n_runs)
{
    const int32_t w = src->width;
    int64_t dropped = 0;
    for (int32_t y = 0; y < src->height; y++) {
        const uint8_t *a = rte_u8_row(absd, y);
        rows->classify(a, rte_u8_row(src, y), rte_u8_row(background, y), t->row, w, (uint8_t)low,
                       (uint8_t)high, params->bright ? 1 : 0, params->dark ? 2 : 0);
        if (shade)
            rows->shade_class(t->row, rte_u8_row(shade, y >> 1), w);
        dropped += label_row(t, y, a, t->row, w, n_runs);
    }
    return dropped;
}

/* Flags the shadows (see rte_background_threshold_u8) and counts them. */
static int32_t mark_shadows(run_table *t, int32_t n, int32_t h,
                            const rte_background_threshold_params *params)
{
    int32_t shadows = 0;
    /* Only strong dark regions smaller than the largest strong bright one
     * can be a shadow that matters (weak ones are not painted), and only
     * those of shadow_min_area pixels or more are looked at. */
    int32_t largest_bright = 0;
    for (int32_t r = 0; r < n; r++)
        if (t->parent[r] == r && (t->flags[r] & (REGION_DARK | REGION_STRONG)) == REGION_STRONG)
            largest_bright = t->count[r] > largest_bright ? t->count[r] : largest_bright;
    int32_t cursor[2 * RTE_BACKGROUND_MAX_SHADOW_GAP + 1];
    for (int32_t y = 0; y < h; y++) {
        for (int32_t k = 0; k <= 2 * params->shadow_gap; k++) {
            const int32_t yy = y - params->shadow_gap + k;
            cursor[k] = yy >= 0 && yy < h ? t->row_start[yy] : 0;
        }
        for (int32_t r = t->row_start[y]; r < t->row_start[y + 1]; r++) {
            const int32_t rd = t->parent[r];
            if ((t->flags[rd] & (REGION_DARK | REGION_STRONG | REGION_SHADOW | REGION_SHADE)) !=
                    (REGION_DARK | REGION_STRONG) ||
                t->count[rd] >= largest_bright || t->count[rd] < params->shadow_min_area)
                continue;
            if (casts_shadow_on(t, y, h, params->shadow_gap, rd, r, cursor)) {
                t->flags[rd] |= REGION_SHADOW;
                shadows++;
            }
        }
    }
    return shadows;
}

rte_status rte_background_threshold_u8(const rte_image_u8 *src, const rte_image_u8 *background,
                                       rte_image_u8 *dst,
                                       const rte_background_threshold_params *params,
                                       rte_arena *arena, rte_background_threshold_result *result)
{
    return rte_background_threshold_shaded_u8(src, background, NULL, dst, params, arena, result);
}

rte_status rte_background_threshold_shaded_u8(const rte_image_u8 *src,
                                              const rte_image_u8 *background,
                                              const rte_image_u8 *shade, rte_image_u8 *dst,
                                              const rte_background_threshold_params *params,
                                              rte_arena *arena,
                                              rte_background_threshold_result *result)
{
    rte_status st = rte_image_u8_check_pair(src, background);
    if (st == RTE_OK)
        st = rte_image_u8_check_pair(src, dst);
    if (st == RTE_OK && shade)
        st = rte_image_u8_check(shade);
    if (st != RTE_OK)
        return st;
    if (shade && (shade->width != (src->width + 1) / 2 || shade->height != (src->height + 1) / 2))
        return RTE_ERR_SIZE;
    if (!params || !arena || params->high < 0 || params->high > 255 || params->min_contrast < 1 ||
        params->min_contrast > 255 || params->shadow_gap < 0 ||
        params->shadow_gap > RTE_BACKGROUND_MAX_SHADOW_GAP || params->region_share_permille < 0 ||
        params->region_share_permille > 1000 || params->shadow_min_area < 0 ||
        dst->buf == src->buf || dst->buf == background->buf || (shade && dst->buf == shade->buf))
        return RTE_ERR_ARGUMENT;
    const int32_t w = src->width, h = src->height;
    const size_t mark = rte_arena_mark(arena);
    run_table t = {.capacity = run_capacity(w, h), .shade = shade != NULL};
    const size_t runs = (size_t)t.capacity;
    t.x0 = rte_arena_alloc(arena, runs * sizeof *t.x0);
    t.x1 = rte_arena_alloc(arena, runs * sizeof *t.x1);
    t.parent = rte_arena_alloc(arena, runs * sizeof *t.parent);
    t.count = rte_arena_alloc(arena, runs * sizeof *t.count);
    t.object = rte_arena_alloc(arena, runs * sizeof *t.object);
    t.core = rte_arena_alloc(arena, runs * sizeof *t.core);
    t.first = rte_arena_alloc(arena, runs * sizeof *t.first);
    t.sum = rte_arena_alloc(arena, runs * sizeof *t.sum);
    t.flags = rte_arena_alloc(arena, runs);
    t.row_start = rte_arena_alloc(arena, ((size_t)h + 1) * sizeof *t.row_start);
    t.row = rte_arena_alloc(arena, (size_t)w);
    if (!t.x0 || !t.x1 || !t.parent || !t.object || !t.count || !t.core || !t.first || !t.sum ||
        !t.flags || !t.row_start || !t.row) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    /* |d| into dst first (the regions are painted over it at the end) */
    const rte_background_rows rows = rte_background_rows_select(rte_cpu_features());
    for (int32_t y = 0; y < h; y++)
        rows.absdiff(rte_u8_row(src, y), rte_u8_row(background, y), rte_u8_row(dst, y), w);
    int32_t high = params->high;
    if (high == 0) {
        uint32_t hist[256];
        rte_histogram_u8(dst, hist);
        rte_threshold_otsu_histogram(hist, &high);
    }
    if (high < params->min_contrast)
        high = params->min_contrast;
    const int32_t low = high * 2 / 3; /* nearer half the contrast: the edge of a blurred step */

    int32_t n = 0;
    const int64_t dropped =
        label_frame(&t, src, background, shade, dst, low, high, params, &rows, &n);
    int32_t shadows = shade ? settle_shade(&t, n, params->shadow_min_area) : 0;
    /* Statistics to the roots; every run then points at its root. */
    int32_t regions = 0;
    for (int32_t r = 0; r < n; r++) {
        const int32_t root = find_root(t.parent, r);
        t.parent[r] = root;
        if (root == r) {
            regions++;
            continue;
        }
        t.count[root] += t.count[r];
        t.sum[root] += t.sum[r];
        t.flags[root] |= t.flags[r] & REGION_STRONG;
    }
    if (params->drop_shadows && params->bright && params->dark)
        shadows += mark_shadows(&t, n, h, params);
    paint_regions(&t, dst, params->region_share_permille, &rows);
    if (result)
        *result = (rte_background_threshold_result){.high = high,
                                                    .low = low,
                                                    .regions = regions,
                                                    .shadows = shadows,
                                                    .dropped_pixels = dropped};
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
