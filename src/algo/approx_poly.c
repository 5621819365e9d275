/* Douglas-Peucker polygon approximation with cv::approxPolyDP's exact
 * decisions (closed curves).
 *
 * OpenCV compares squared distances against eps^2 * |segment|^2 in double.
 * With eps = E / 65536 every operand is an integer or a dyadic rational,
 * so each double operation is "the exact value rounded to 53 significant
 * bits"; round53() reproduces that rounding in 128-bit integers and the
 * comparisons then agree with OpenCV's bit for bit. */
#include "rtedge/shape.h"

#include "geom_fixed.h"

/* The exact value v rounded to a double's 53-bit significand (ties to
 * even), still as an integer. */
static rte_u128 round53(rte_u128 v)
{
    if (v < ((rte_u128)1 << 53))
        return v;
    int bits = 0;
    for (rte_u128 t = v; t; t >>= 1)
        bits++;
    const int shift = bits - 53;
    const rte_u128 one = (rte_u128)1 << shift, half = one >> 1;
    rte_u128 keep = v >> shift, rem = v & (one - 1);
    if (rem > half || (rem == half && (keep & 1)))
        keep++;
    return keep << shift;
}

typedef struct eps_cmp {
    rte_u128 e2; /* double(eps * eps) * 2^32, an integer */
} eps_cmp;

static uint64_t abs64(int64_t v) { return (uint64_t)(v < 0 ? -v : v); }

/* d2 <= eps * eps (d2 an exact integer). */
static bool within_eps2(const eps_cmp *e, uint64_t d2) { return ((rte_u128)d2 << 32) <= e->e2; }

/* double(c * c) <= double(scale * eps^2 * len2), scale = 1 or 1/2. */
static bool within_eps_seg(const eps_cmp *e, uint64_t c, uint64_t len2, int half)
{
    rte_u128 lhs = round53((rte_u128)c * c) << (32 + half);
    rte_u128 rhs = round53(e->e2 * len2);
    /* e2 < 2^53 and len2 < 2^25 for RTE_SHAPE_MAX_COORD, so no overflow */
    return lhs <= rhs;
}

size_t rte_shape_approx_scratch_size(int32_t max_points)
{
    if (max_points < 0)
        return 0;
    return rte_arena_piece_size(((size_t)max_points + 2) * 2 * sizeof(int32_t));
}

/* Step 1: three rounds of "farthest point from the current start" give
 * the first split, pushed as two slices; a curve within epsilon of its
 * start collapses to that point. Returns the stack's new top. */
static int32_t push_first_split(const rte_point *pts, int32_t count, const eps_cmp *e,
                                int32_t *stack, rte_point *out, int32_t *new_count)
{
    int32_t top = 0, pos = 0, far = 0;
    bool le_eps = false;
    rte_point start = pts[0];
    for (int iter = 0; iter < 3; iter++) {
        uint64_t max_d2 = 0;
        pos = (pos + far) % count;
        start = pts[pos];
        int32_t p = pos + 1 >= count ? 0 : pos + 1;
        for (int32_t j = 1; j < count; j++) {
            int64_t dx = (int64_t)pts[p].x - start.x, dy = (int64_t)pts[p].y - start.y;
            uint64_t d2 = (uint64_t)(dx * dx + dy * dy);
            if (d2 > max_d2) {
                max_d2 = d2;
                far = j;
            }
            p = p + 1 >= count ? 0 : p + 1;
        }
        le_eps = within_eps2(e, max_d2);
    }
    if (!le_eps) {
        int32_t s0 = pos % count, s1 = (far + s0) % count;
        /* right slice [s1, s0] below, slice [s0, s1] on top */
        stack[top++] = s1;
        stack[top++] = s0;
        stack[top++] = s0;
        stack[top++] = s1;
    } else {
        out[(*new_count)++] = start;
    }
    return top;
}

/* Step 2: split until every slice is within epsilon, emitting each
 * slice's start point. */
static void split_slices(const rte_point *pts, int32_t count, const eps_cmp *e, int32_t *stack,
                         int32_t top, rte_point *out, int32_t *new_count)
{
    while (top > 0) {
        int32_t s_end = stack[--top], s_start = stack[--top];
        const rte_point end = pts[s_end];
        int32_t p = s_start + 1 >= count ? 0 : s_start + 1;
        const rte_point start = pts[s_start];
        if (p != s_end) {
            const int64_t dx = (int64_t)end.x - start.x, dy = (int64_t)end.y - start.y;
            uint64_t max_c = 0;
            int32_t split = s_start;
            while (p != s_end) {
                uint64_t c =
                    abs64(((int64_t)pts[p].y - start.y) * dx - ((int64_t)pts[p].x - start.x) * dy);
                if (c > max_c) {
                    max_c = c;
                    split = p;
                }
                p = p + 1 >= count ? 0 : p + 1;
            }
            if (!within_eps_seg(e, max_c, (uint64_t)(dx * dx + dy * dy), 0)) {
                stack[top++] = split;
                stack[top++] = s_end;
                stack[top++] = s_start;
                stack[top++] = split;
                continue;
            }
        }
        out[(*new_count)++] = start;
    }
}

/* Step 3: drop middle points of nearly straight, non-axis-aligned runs
 * (in place, in OpenCV's order of reads and writes). Returns the count
 * kept. */
static int32_t drop_straight_points(const eps_cmp *e, rte_point *out, int32_t cnt)
{
    int32_t new_count = cnt;
    int32_t rpos = cnt - 1, wpos;
    rte_point s = out[rpos], pt, en;
    rpos = rpos + 1 >= cnt ? 0 : rpos + 1;
    wpos = rpos;
    pt = out[rpos];
    rpos = rpos + 1 >= cnt ? 0 : rpos + 1;
    for (int32_t i = 0; i < cnt && new_count > 2; i++) {
        en = out[rpos];
        rpos = rpos + 1 >= cnt ? 0 : rpos + 1;
        const int64_t dx = (int64_t)en.x - s.x, dy = (int64_t)en.y - s.y;
        const uint64_t c = abs64(((int64_t)pt.x - s.x) * dy - ((int64_t)pt.y - s.y) * dx);
        const int64_t inner =
            ((int64_t)pt.x - s.x) * (en.x - pt.x) + ((int64_t)pt.y - s.y) * (en.y - pt.y);
        if (dx != 0 && dy != 0 && inner >= 0 &&
            within_eps_seg(e, c, (uint64_t)(dx * dx + dy * dy), 1)) {
            new_count--;
            out[wpos] = s = en;
            wpos = wpos + 1 >= cnt ? 0 : wpos + 1;
            pt = out[rpos];
            rpos = rpos + 1 >= cnt ? 0 : rpos + 1;
            i++;
            continue;
        }
        out[wpos] = s = pt;
        wpos = wpos + 1 >= cnt ? 0 : wpos + 1;
        pt = en;
    }
    return new_count;
}

rte_status rte_shape_approx_poly(const rte_point *pts, int32_t n, uint32_t epsilon_q16,
                                 rte_point *out, int32_t *n_out, rte_arena *scratch)
{
    if (!n_out || n < 0 || (n > 0 && (!pts || !out || !scratch)) || epsilon_q16 >= (1u << 26))
        return RTE_ERR_ARGUMENT;
    *n_out = 0;
    if (n == 0)
        return RTE_OK;
    for (int32_t i = 0; i < n; i++)
        if (pts[i].x > RTE_SHAPE_MAX_COORD || pts[i].x < -RTE_SHAPE_MAX_COORD ||
            pts[i].y > RTE_SHAPE_MAX_COORD || pts[i].y < -RTE_SHAPE_MAX_COORD)
            return RTE_ERR_TOO_LARGE;
    const size_t mark = rte_arena_mark(scratch);
    int32_t *stack = rte_arena_alloc(scratch, ((size_t)n + 2) * 2 * sizeof(int32_t));
    if (!stack)
        return RTE_ERR_NO_MEMORY;

    eps_cmp e;
    e.e2 = round53((rte_u128)epsilon_q16 * epsilon_q16);

    int32_t new_count = 0;
    const int32_t top = push_first_split(pts, n, &e, stack, out, &new_count);
    split_slices(pts, n, &e, stack, top, out, &new_count);
    *n_out = drop_straight_points(&e, out, new_count);
    rte_arena_reset(scratch, mark);
    return RTE_OK;
}
