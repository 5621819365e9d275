/* Erosion and dilation with flat structuring elements (per frame, integer
 * only). See include/rtedge/morphology.h.
 *
 * Pixels outside the image never win (OpenCV's default border), so rows
 * outside the image are simply left out and each loaded row is padded on
 * both sides with the neutral value (255 for min, 0 for max).
 *
 * Long horizontal windows use doubling tables: level k of a padded row
 * holds the min (max) of 2^k consecutive pixels, and any run of length len
 * is the min of two overlapping level-k windows with 2^k <= len < 2^(k+1).
 * Short windows are reduced tap by tap, up to five rows (or shifted
 * views of one row) per pass over the output.
 *  - A full rectangle is separable: the column window straight from the
 *    source rows into a padded row, then the row window into dst.
 *  - Any other element: every source row's padded copy and its levels
 *    stream through a ring of `height` slots; each output row combines,
 *    for every run, two reads of the levels of the run's source row.
 *  - Or, when it costs less (crosses, small ellipses): the element's rows
 *    with equal runs form groups; each output row reduces each group's
 *    source rows first, then takes a tap per pixel of the group's runs.
 * dst == src is safe: the ring (for the separable path, a ring of plain
 * row copies, used only then) takes each source row before the output row
 * that overwrites it. */
#include "rtedge/morphology.h"

#include <stdbool.h>
#include <string.h>

#include "morphology_rows.h"
#include "rtedge/cpu.h"
#include "simd/rows.h"

/* Widest row window and tallest column window reduced tap by tap; wider
 * rows use the doubling levels, taller columns van Herk / Gil-Werman
 * (three passes per row whatever the height). */
#define DIRECT_TAPS 6
#define DIRECT_ROWS 7

/* Largest k with 2^k <= n (n >= 1). */
static int32_t floor_log2(int32_t n)
{
    int32_t k = 0;
    while ((2 << k) <= n)
        k++;
    return k;
}

static size_t round_up64(size_t n) { return (n + 63) & ~(size_t)63; }

/* What one pass needs: the effective window and the ring geometry. */
typedef struct morph_plan {
    int32_t kw, kh, ax, ay; /* effective element size and anchor */
    int32_t levels;         /* doubling levels kept per padded row */
    bool separable;         /* full rectangle: column window, then row window */
    bool blocks;            /* separable with a tall window: van Herk / Gil-Werman columns */
    bool grouped;           /* any other element, when grouping_pays */
    int32_t groups;         /* grouped: element rows with the same runs */
    uint32_t group_rows[RTE_MORPH_MAX_KSIZE]; /* their rows (bit dy) */
    int32_t group_row[RTE_MORPH_MAX_KSIZE];   /* the first of them, whose runs the group takes */
    bool group_direct[RTE_MORPH_MAX_KSIZE];   /* its only run is the anchor's column */
    size_t padded;                            /* bytes per padded row, rounded up */
    size_t slot;                              /* bytes per ring slot */
} morph_plan;

/* Whether element rows a and b have the same runs (in the same order). */
static bool same_runs(const rte_morph_element *e, int32_t a, int32_t b)
{
    int32_t i = 0, j = 0;
    for (;;) {
        while (i < e->run_count && e->runs[i].dy != a)
            i++;
        while (j < e->run_count && e->runs[j].dy != b)
            j++;
        if (i == e->run_count || j == e->run_count)
            return i == e->run_count && j == e->run_count;
        if (e->runs[i].dx != e->runs[j].dx || e->runs[i].len != e->runs[j].len)
            return false;
        i++;
        j++;
    }
}

/* Rows with the same runs can share their runs' taps: the column window
 * of their source rows first (into a padded row), then one tap per
 * pixel of each run of the group. A 5x5 ellipse is then a 3-row column
 * window, then five taps and the two single pixels above and below in one
 * pass: two passes per output row instead of three per source row (copy,
 * two levels) and two more per output row for eight level reads.
 * p->grouped when it costs less (grouping_pays). */
static void row_groups(morph_plan *p, const rte_morph_element *e)
{
    p->groups = 0;
    for (int32_t dy = 0; dy < e->height; dy++) {
        bool has_run = false;
        for (int32_t i = 0; i < e->run_count && !has_run; i++)
            has_run = e->runs[i].dy == dy;
        if (!has_run)
            continue;
        int32_t g = 0;
        while (g < p->groups && !same_runs(e, p->group_row[g], dy))
            g++;
        if (g == p->groups) {
            p->group_row[g] = dy;
            p->group_rows[g] = 0;
            p->groups++;
        }
        p->group_rows[g] |= (uint32_t)1 << dy;
    }
    for (int32_t g = 0; g < p->groups; g++) {
        int32_t runs = 0, anchor_runs = 0;
        for (int32_t i = 0; i < e->run_count; i++)
            if (e->runs[i].dy == p->group_row[g]) {
                runs++;
                anchor_runs += e->runs[i].dx == e->anchor_x && e->runs[i].len == 1;
            }
        p->group_direct[g] = runs == 1 && anchor_runs == 1;
    }
}

/* The cost of a pass over a row reading `inputs` rows, in row reads: a
 * pass costs as much as about eight reads (fitted to the times of both
 * paths on crosses and ellipses of 3 to 31 pixels at 1280x720). */
static int32_t pass_cost(int32_t inputs) { return 8 + inputs; }

/* The reduction of `taps` rows into one: ROW_PASS_MAX rows in the first
 * pass, then the result and ROW_PASS_MAX - 1 more per pass. */
static int32_t reduce_cost(int32_t taps)
{
    int32_t cost = pass_cost(taps < ROW_PASS_MAX ? taps : ROW_PASS_MAX);
    for (taps -= ROW_PASS_MAX; taps > 0; taps -= ROW_PASS_MAX - 1)
        cost += pass_cost(1 + (taps < ROW_PASS_MAX - 1 ? taps : ROW_PASS_MAX - 1));
    return cost;
}

/* Cost per output row: the padded copy and doubling levels of a source
 * row and two level reads per run (one for a power of two), against a
 * column window per group and a tap per run pixel. */
static bool grouping_pays(const morph_plan *p, const rte_morph_element *e)
{
    int32_t level_taps = 0, group_cost = 0, group_taps = 0;
    for (int32_t i = 0; i < e->run_count; i++)
        level_taps += e->runs[i].len == 1 << floor_log2(e->runs[i].len) ? 1 : 2;
    for (int32_t g = 0; g < p->groups; g++) {
        const int32_t rows = __builtin_popcount(p->group_rows[g]);
        if (p->group_direct[g]) {
            group_taps += rows;
            continue;
        }
        group_cost += pass_cost(rows);
        for (int32_t i = 0; i < e->run_count; i++)
            if (e->runs[i].dy == p->group_row[g])
                group_taps += e->runs[i].len;
    }
    const int32_t level_cost =
        pass_cost(1) + (p->levels - 1) * pass_cost(2) + reduce_cost(level_taps);
    return group_cost + reduce_cost(group_taps) < level_cost;
}

static morph_plan make_plan(int32_t width, const rte_morph_element *e, int32_t iterations)
{
    morph_plan p;
    p.separable = e->full != 0;
    if (p.separable) {
        /* OpenCV's rule for iterated rectangles: one rectangle of
         * k + (n - 1)(k - 1) with the anchor scaled by n; iterating the
         * small one gives the same pixels. */
        p.kw = e->width + (iterations - 1) * (e->width - 1);
        p.kh = e->height + (iterations - 1) * (e->height - 1);
        p.ax = e->anchor_x * iterations;
        p.ay = e->anchor_y * iterations;
        p.levels = floor_log2(p.kw) + 1;
    } else {
        p.kw = e->width;
        p.kh = e->height;
        p.ax = e->anchor_x;
        p.ay = e->anchor_y;
        p.levels = floor_log2(e->max_run) + 1;
    }
    p.padded = round_up64((size_t)width + (size_t)p.kw - 1);
    p.blocks = p.separable && p.kh > DIRECT_ROWS;
    p.grouped = false;
    if (!p.separable) {
        row_groups(&p, e);
        p.grouped = grouping_pays(&p, e);
    }
    /* separable and grouped: raw source rows (only used in place);
     * otherwise the levels */
    p.slot = p.separable || p.grouped ? round_up64((size_t)width) : p.padded * (size_t)p.levels;
    return p;
}

/* Separable: a padded row and two rows for its levels, and for tall
 * windows one block of suffix rows, a prefix row and a neutral row.
 * Grouped: a padded row per group. */
static size_t work_bytes(const morph_plan *p)
{
    if (p->grouped)
        return (size_t)p->groups * p->padded;
    if (!p->separable)
        return 0;
    return 3 * p->padded + (p->blocks ? ((size_t)p->kh + 2) * p->slot : 0);
}

/* The ring plus the work rows. */
static size_t plan_bytes(const morph_plan *p)
{
    size_t bytes = rte_arena_piece_size(p->slot * (size_t)p->kh);
    if (work_bytes(p))
        bytes += rte_arena_piece_size(work_bytes(p));
    return bytes;
}

/* The element is caller memory: check every field the passes index with. */
static bool valid_element(const rte_morph_element *e)
{
    if (!e || e->width < 1 || e->width > RTE_MORPH_MAX_KSIZE || e->height < 1 ||
        e->height > RTE_MORPH_MAX_KSIZE || e->anchor_x < 0 || e->anchor_x >= e->width ||
        e->anchor_y < 0 || e->anchor_y >= e->height || e->run_count < 1 ||
        e->run_count > (int32_t)(sizeof e->runs / sizeof e->runs[0]) || e->max_run < 1 ||
        e->max_run > e->width)
        return false;
    for (int32_t i = 0; i < e->run_count; i++) {
        const rte_morph_run r = e->runs[i];
        if (r.dy < 0 || r.dy >= e->height || r.dx < 0 || r.len < 1 || r.len > e->max_run ||
            r.dx + r.len > e->width)
            return false;
    }
    return true;
}

/* Iterated rectangles grow; keep every size inside int32_t arithmetic. */
#define MAX_ITERATIONS 1000

size_t rte_morphology_scratch_size(int32_t max_width, int32_t max_height,
                                   const rte_morph_element *element, int32_t iterations)
{
    if (!valid_element(element) || max_width < 1 || max_height < 1 || iterations < 1 ||
        iterations > MAX_ITERATIONS)
        return 0;
    morph_plan p = make_plan(max_width, element, iterations);
    return plan_bytes(&p);
}

/* The row kernels, once per instruction set (see simd/rows.h). */
void rte_morph_row_op2_c(uint8_t *d, const uint8_t *a, const uint8_t *b, int32_t n, bool is_max)
{
    row_op2(d, a, b, n, is_max);
}

void rte_morph_reduce_rows_c(uint8_t *d, const uint8_t *const *r, int32_t count, bool accumulate,
                             int32_t n, bool is_max)
{
    reduce_rows(d, r, count, accumulate, n, is_max);
}

rte_morph_rows rte_morph_rows_select(uint32_t features)
{
    return RTE_SIMD_PICK(features, ((rte_morph_rows){rte_morph_row_op2_c, rte_morph_reduce_rows_c}),
                         ((rte_morph_rows){rte_morph_row_op2_avx2, rte_morph_reduce_rows_avx2}),
                         ((rte_morph_rows){rte_morph_row_op2_avx512, rte_morph_reduce_rows_avx512}),
                         ((rte_morph_rows){rte_morph_row_op2_c, rte_morph_reduce_rows_c}));
}

/* Copies a source row into `pad` with p->ax neutral pixels before it and
 * kw - 1 - ax after it. */
static void load_padded(uint8_t *pad, const uint8_t *row, int32_t width, const morph_plan *p,
                        uint8_t neutral)
{
    memset(pad, neutral, (size_t)p->ax);
    memcpy(pad + p->ax, row, (size_t)width);
    memset(pad + p->ax + width, neutral, (size_t)(p->kw - 1 - p->ax));
}

/* Level k from level k - 1 of a padded row of n pixels: valid for x <= n - 2^k. */
static void next_level(const rte_morph_rows *kr, uint8_t *dst, const uint8_t *prev, int32_t n,
                       int32_t k, bool is_max)
{
    int32_t half = 1 << (k - 1);
    kr->op2(dst, prev, prev + half, n - 2 * half + 1, is_max);
}

/* Source rows when dst == src: each is copied into a ring of kh slots
 * before the output row that overwrites it, and read from there. */
typedef struct source_rows {
    const rte_image_u8 *src;
    uint8_t *ring; /* NULL: not in place, the rows are read from src */
    size_t slot;
    int32_t kh, loaded; /* loaded: the next row to copy */
} source_rows;

static source_rows source_rows_init(const rte_image_u8 *src, const rte_image_u8 *dst, uint8_t *ring,
                                    const morph_plan *p)
{
    return (source_rows){src, src->buf == dst->buf ? ring : NULL, p->slot, p->kh, 0};
}

/* Copies the rows up to `last` (at most the image's last) into the ring
 * (in place only). */
static void source_rows_load(source_rows *s, int32_t last)
{
    if (s->ring)
        for (; s->loaded <= last && s->loaded < s->src->height; s->loaded++)
            memcpy(s->ring + (size_t)(s->loaded % s->kh) * s->slot, rte_u8_row(s->src, s->loaded),
                   (size_t)s->src->width);
}

/* Source row v, inside the image. */
static const uint8_t *source_row(const source_rows *s, int32_t v)
{
    return s->ring ? s->ring + (size_t)(v % s->kh) * s->slot : rte_u8_row(s->src, v);
}

/* Full rectangle, separable: the column window first, straight from the
 * source rows (or from copies of them when dst == src, so that rows still
 * needed are not lost), into the middle of a padded row; then the row
 * window from there into dst. */
static void separable_pass(const rte_morph_rows *kr, const rte_image_u8 *src, rte_image_u8 *dst,
                           const morph_plan *p, uint8_t *ring, uint8_t *work, bool is_max)
{
    const int32_t w = src->width, h = src->height, kh = p->kh;
    const int32_t n = w + p->kw - 1;
    const uint8_t neutral = is_max ? 0 : 255;
    source_rows rows_in = source_rows_init(src, dst, ring, p);
    uint8_t *pad = work, *lv_a = work + p->padded, *lv_b = work + 2 * p->padded;
    uint8_t *suffix = work + 3 * p->padded, *prefix = suffix + (size_t)kh * p->slot;
    uint8_t *neutral_row = prefix + p->slot;
    memset(pad, neutral, (size_t)n); /* the margins stay neutral; the middle is rewritten per row */
    if (p->blocks)
        memset(neutral_row, neutral, (size_t)w);
        /* Source row v of the column window: rows outside the image are neutral. */
#define SRC_ROW(v) ((v) < 0 || (v) >= h ? neutral_row : source_row(&rows_in, (v)))
    for (int32_t y = 0; y < h; y++) {
        const int32_t v0 = y - p->ay; /* the column window is v0 .. v0 + kh - 1 */
        int32_t r0 = v0 < 0 ? 0 : v0;
        int32_t last = v0 + kh - 1 > h - 1 ? h - 1 : v0 + kh - 1;
        source_rows_load(&rows_in, last);
        uint8_t *d = rte_u8_row(dst, y);
        uint8_t *column = p->kw == 1 ? d : pad + p->ax;
        if (p->blocks) {
            /* Windows start at v0 = y - ay; blocks of kh windows share one
             * suffix table of their first window's rows, and the rows past
             * it accumulate in a running prefix. */
            const int32_t o = y % kh;
            if (o == 0) {
                memcpy(suffix + (size_t)(kh - 1) * p->slot, SRC_ROW(v0 + kh - 1), (size_t)w);
                for (int32_t j = kh - 2; j >= 1; j--)
                    kr->op2(suffix + (size_t)j * p->slot, SRC_ROW(v0 + j),
                            suffix + (size_t)(j + 1) * p->slot, w, is_max);
                kr->op2(column, SRC_ROW(v0), suffix + p->slot, w, is_max);
            } else {
                const uint8_t *entering = SRC_ROW(v0 + kh - 1);
                if (o == 1)
                    memcpy(prefix, entering, (size_t)w);
                else
                    kr->op2(prefix, prefix, entering, w, is_max);
                kr->op2(column, suffix + (size_t)o * p->slot, prefix, w, is_max);
            }
        } else {
            const uint8_t *rows[DIRECT_ROWS];
            for (int32_t v = r0; v <= last; v++)
                rows[v - r0] = SRC_ROW(v);
            kr->reduce(column, rows, last - r0 + 1, false, w, is_max);
        }
        if (p->kw == 1)
            continue;
        if (p->kw <= DIRECT_TAPS) {
            const uint8_t *taps[DIRECT_TAPS];
            for (int32_t i = 0; i < p->kw; i++)
                taps[i] = pad + i;
            kr->reduce(d, taps, p->kw, false, w, is_max);
            continue;
        }
        const uint8_t *level = pad;
        for (int32_t k = 1; k < p->levels; k++) {
            uint8_t *next = level == lv_a ? lv_b : lv_a;
            next_level(kr, next, level, n, k, is_max);
            level = next;
        }
        kr->op2(d, level, level + p->kw - (1 << (p->levels - 1)), w, is_max);
    }
#undef SRC_ROW
}

/* The rows one output row is reduced from, handed to the row kernel up to
 * 64 at a time. */
typedef struct tap_list {
    const uint8_t *rows[64];
    int32_t count;
    bool any; /* some were reduced into the output row already */
} tap_list;

static void taps_flush(const rte_morph_rows *kr, tap_list *t, uint8_t *d, int32_t w, bool is_max)
{
    if (t->count == 0)
        return;
    kr->reduce(d, t->rows, t->count, t->any, w, is_max);
    t->any = true;
    t->count = 0;
}

/* Room for `more` rows in the list, flushing it into d if needed. */
static void taps_room(const rte_morph_rows *kr, tap_list *t, int32_t more, uint8_t *d, int32_t w,
                      bool is_max)
{
    if (t->count + more > (int32_t)(sizeof t->rows / sizeof t->rows[0]))
        taps_flush(kr, t, d, w, is_max);
}

/* The rest of the list into d; the neutral value when no row of the
 * element was inside the image. */
static void taps_finish(const rte_morph_rows *kr, tap_list *t, uint8_t *d, int32_t w, bool is_max)
{
    taps_flush(kr, t, d, w, is_max);
    if (!t->any)
        memset(d, is_max ? 0 : 255, (size_t)w);
}

/* Elements whose rows fall into few groups of equal runs (row_groups):
 * per output row, the column window of each group's source rows goes into
 * the middle of that group's padded row, and the runs take one tap per
 * pixel from there; a group whose only run is the anchor's column takes
 * its source rows directly. Rows outside the image are left out; when
 * dst == src, a ring of row copies keeps the rows still needed (as
 * separable_pass). */
static void grouped_pass(const rte_morph_rows *kr, const rte_image_u8 *src, rte_image_u8 *dst,
                         const morph_plan *p, const rte_morph_element *e, uint8_t *ring,
                         uint8_t *work, bool is_max)
{
    const int32_t w = src->width, h = src->height;
    source_rows rows_in = source_rows_init(src, dst, ring, p);
    /* the margins stay neutral; the middle is rewritten per output row */
    memset(work, is_max ? 0 : 255, (size_t)p->groups * p->padded);
    for (int32_t y = 0; y < h; y++) {
        source_rows_load(&rows_in, y - p->ay + p->kh - 1);
        uint8_t *d = rte_u8_row(dst, y);
        tap_list t; /* rows[] is filled before it is read */
        t.count = 0;
        t.any = false;
        for (int32_t g = 0; g < p->groups; g++) {
            const uint8_t *rows[RTE_MORPH_MAX_KSIZE];
            int32_t nrows = 0;
            for (uint32_t m = p->group_rows[g]; m; m &= m - 1) {
                const int32_t v = y + __builtin_ctz(m) - p->ay;
                if (v >= 0 && v < h)
                    rows[nrows++] = source_row(&rows_in, v);
            }
            if (nrows == 0)
                continue;
            /* a group adds at most max(kw, kh) rows */
            taps_room(kr, &t, RTE_MORPH_MAX_KSIZE, d, w, is_max);
            if (p->group_direct[g]) {
                for (int32_t i = 0; i < nrows; i++)
                    t.rows[t.count++] = rows[i];
            } else {
                uint8_t *pad = work + (size_t)g * p->padded;
                kr->reduce(pad + p->ax, rows, nrows, false, w, is_max);
                for (int32_t i = 0; i < e->run_count; i++)
                    if (e->runs[i].dy == p->group_row[g])
                        for (int32_t k = 0; k < e->runs[i].len; k++)
                            t.rows[t.count++] = pad + e->runs[i].dx + k;
            }
        }
        taps_finish(kr, &t, d, w, is_max);
    }
}

/* Any other element: per source row, the doubling levels of its padded
 * copy in the ring; per output row, two reads per run. */
static void general_pass(const rte_morph_rows *kr, const rte_image_u8 *src, rte_image_u8 *dst,
                         const morph_plan *p, const rte_morph_element *e, uint8_t *ring,
                         bool is_max)
{
    const int32_t w = src->width, h = src->height;
    const int32_t n = w + p->kw - 1;
    const uint8_t neutral = is_max ? 0 : 255;
    int32_t loaded = 0; /* next source row to bring into the ring */
    for (int32_t y = 0; y < h; y++) {
        int32_t last = y - p->ay + p->kh - 1 > h - 1 ? h - 1 : y - p->ay + p->kh - 1;
        for (; loaded <= last; loaded++) {
            uint8_t *slot = ring + (size_t)(loaded % p->kh) * p->slot;
            load_padded(slot, rte_u8_row(src, loaded), w, p, neutral);
            for (int32_t k = 1; k < p->levels; k++)
                next_level(kr, slot + (size_t)k * p->padded, slot + (size_t)(k - 1) * p->padded, n,
                           k, is_max);
        }
        /* Every run gives one or two rows of the levels. */
        uint8_t *d = rte_u8_row(dst, y);
        tap_list t; /* rows[] is filled before it is read */
        t.count = 0;
        t.any = false;
        for (int32_t i = 0; i < e->run_count; i++) {
            const rte_morph_run run = e->runs[i];
            int32_t r = y + run.dy - p->ay;
            if (r < 0 || r >= h)
                continue;
            int32_t k = floor_log2(run.len);
            const uint8_t *level = ring + (size_t)(r % p->kh) * p->slot + (size_t)k * p->padded;
            taps_room(kr, &t, 2, d, w, is_max);
            t.rows[t.count++] = level + run.dx;
            if (run.len != 1 << k)
                t.rows[t.count++] = level + run.dx + run.len - (1 << k);
        }
        taps_finish(kr, &t, d, w, is_max);
    }
}

rte_status rte_morphology_u8(const rte_image_u8 *src, rte_image_u8 *dst, rte_morph_op op,
                             const rte_morph_element *element, int32_t iterations, rte_arena *arena)
{
    rte_status st = rte_image_u8_check_pair(src, dst);
    if (st != RTE_OK)
        return st;
    if (!valid_element(element) || !arena || (unsigned)op > RTE_MORPH_CLOSE || iterations < 1 ||
        iterations > MAX_ITERATIONS)
        return RTE_ERR_ARGUMENT;

    const size_t mark = rte_arena_mark(arena);
    morph_plan p = make_plan(src->width, element, iterations);
    uint8_t *ring = (uint8_t *)rte_arena_alloc(arena, p.slot * (size_t)p.kh);
    const size_t work_size = work_bytes(&p);
    uint8_t *work = work_size ? (uint8_t *)rte_arena_alloc(arena, work_size) : NULL;
    if (!ring || (work_size && !work)) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    /* Passes: the rectangle covers all iterations in one pass per operation. */
    const int32_t repeat = p.separable ? 1 : iterations;
    bool first_max = op == RTE_MORPH_DILATE || op == RTE_MORPH_CLOSE;
    int32_t stages = (op == RTE_MORPH_OPEN || op == RTE_MORPH_CLOSE) ? 2 : 1;
    const rte_morph_rows kr = rte_morph_rows_select(rte_cpu_features());
    const rte_image_u8 *in = src;
    for (int32_t s = 0; s < stages; s++) {
        bool is_max = s == 0 ? first_max : !first_max;
        for (int32_t i = 0; i < repeat; i++) {
            if (p.separable)
                separable_pass(&kr, in, dst, &p, ring, work, is_max);
            else if (p.grouped)
                grouped_pass(&kr, in, dst, &p, element, ring, work, is_max);
            else
                general_pass(&kr, in, dst, &p, element, ring, is_max);
            in = dst;
        }
    }
    rte_arena_reset(arena, mark);
    return RTE_OK;
}

rte_status rte_morphology_erode_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                   const rte_morph_element *element, int32_t iterations,
                                   rte_arena *arena)
{
    return rte_morphology_u8(src, dst, RTE_MORPH_ERODE, element, iterations, arena);
}

rte_status rte_morphology_dilate_u8(const rte_image_u8 *src, rte_image_u8 *dst,
                                    const rte_morph_element *element, int32_t iterations,
                                    rte_arena *arena)
{
    return rte_morphology_u8(src, dst, RTE_MORPH_DILATE, element, iterations, arena);
}
