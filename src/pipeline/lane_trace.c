/* A lane's marking followed beyond its curve, per frame (integer only;
 * see rte_lane.far_count in include/rtedge/lane.h and docs/lanes.md,
 * "Far trace"). Where a road turns sharply past a crest, its markings run
 * nearly along the rows near the horizon: faster than the curve model
 * (one bend for the whole lane) can turn, and along the rows, where a
 * search across a row finds no stripe. There the marking is followed
 * as a ridge of paint: from a point on it, short segments in a fan of
 * directions around the last one are scored by how much brighter they are
 * than the road on both sides, the best is stepped along and the point
 * put back on the ridge's middle. */
#include "lane_fixed.h"

/* Unit vectors of 64 directions, 2 pi k / 64 (x right, y down), 1/256. */
#define TRACE_DIRS 64
static const int16_t trace_dir[TRACE_DIRS][2] = {
    {256, 0},     {255, 25},    {251, 50},    {245, 74},    {237, 98},    {226, 121},
    {213, 142},   {198, 162},   {181, 181},   {162, 198},   {142, 213},   {121, 226},
    {98, 237},    {74, 245},    {50, 251},    {25, 255},    {0, 256},     {-25, 255},
    {-50, 251},   {-74, 245},   {-98, 237},   {-121, 226},  {-142, 213},  {-162, 198},
    {-181, 181},  {-198, 162},  {-213, 142},  {-226, 121},  {-237, 98},   {-245, 74},
    {-251, 50},   {-255, 25},   {-256, 0},    {-255, -25},  {-251, -50},  {-245, -74},
    {-237, -98},  {-226, -121}, {-213, -142}, {-198, -162}, {-181, -181}, {-162, -198},
    {-142, -213}, {-121, -226}, {-98, -237},  {-74, -245},  {-50, -251},  {-25, -255},
    {0, -256},    {25, -255},   {50, -251},   {74, -245},   {98, -237},   {121, -226},
    {142, -213},  {162, -198},  {181, -181},  {198, -162},  {213, -142},  {226, -121},
    {237, -98},   {245, -74},   {251, -50},   {255, -25}};

#define TRACE_STEP 4       /* pixels stepped along the chosen direction */
#define TRACE_SEG 8        /* pixels of the segment scored per direction */
#define TRACE_FAN 4        /* directions either side of the last one (22 degrees) */
#define TRACE_MAX_STEPS 96 /* enough to cross a 1920-wide frame's lane */
#define TRACE_MISSES 5     /* the trace stops at this many steps in a row without paint */
#define TRACE_CENTRE 3     /* the middle is searched this far either side */
#define TRACE_RUN_ROWS 16  /* the start: paint on a quarter of these rows */
#define TRACE_MIN_STEPS 3  /* steps beyond the curve's band needed to replace it */
#define TRACE_RECENT 4     /* scores a step's is compared with */
/* Directions climbing less than this (1/256 per pixel: 6 degrees) are
 * not followed: a lane that runs along the rows below the horizon is
 * paint across the road (a stop line, a crossing), or a shadow's edge. */
#define TRACE_RISE_MIN 25
/* Steps over which the trace must climb a quarter of TRACE_RISE_MIN (1.5
 * degrees) in all. */
#define TRACE_FLAT_STEPS 12
/* The points of the far trace kept (see rte_lane_trace_far). */
#define TRACE_POINT_ROWS 4
#define TRACE_POINT_COLS 16
#define TRACE_END_ROWS 8

typedef struct trace_point {
    int64_t x_q8, y_q8;
} trace_point;

/* The map's pixel nearest (x_q8, y_q8) in frame coordinates; -1 outside. */
static int32_t map_at(const lane_maps *maps, const rte_image_u8 *img, int64_t x_q8, int64_t y_q8)
{
    const int64_t x = ((x_q8 + 128) >> 8) - maps->cx0, y = ((y_q8 + 128) >> 8) - maps->cy0;
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return -1;
    return rte_u8_row(img, (int32_t)y)[x];
}

/* How much brighter p is than the road w and 2w pixels to either side
 * across unit normal n (the darker of the two on each side: the second
 * line of a double marking may lie at w), in the image the edges came
 * from; INT32_MIN outside the maps or where both sides are glare. */
static int32_t ridge_contrast(const lane_maps *maps, trace_point p, const int16_t n[2], int64_t w)
{
    const int32_t c = map_at(maps, maps->src, p.x_q8, p.y_q8);
    int32_t side = 0, glare = 0;
    for (int s = -1; s <= 1; s += 2) {
        const int64_t dx = s * w * n[0], dy = s * w * n[1];
        const int32_t a = map_at(maps, maps->src, p.x_q8 + dx, p.y_q8 + dy);
        const int32_t b = map_at(maps, maps->src, p.x_q8 + 2 * dx, p.y_q8 + 2 * dy);
        if (c < 0 || a < 0 || b < 0)
            return INT32_MIN;
        const int32_t road = a < b ? a : b;
        side = road > side ? road : side;
        glare += map_at(maps, maps->gray, p.x_q8 + dx, p.y_q8 + dy) >= LANE_SATURATED;
    }
    return glare == 2 ? INT32_MIN : c - side;
}

/* The score of the segment from p along direction k: the sum of its
 * points' contrast (each at most 4 LANE_RIDGE_MIN, so one bright patch
 * does not carry it); -1 unless three quarters of them are paint. */
static int64_t segment_score(const lane_maps *maps, trace_point p, int32_t k, int64_t w)
{
    const int16_t *u = trace_dir[k];
    const int16_t n[2] = {(int16_t)-u[1], u[0]};
    int64_t sum = 0;
    int32_t paint = 0;
    for (int64_t t = 1; t <= TRACE_SEG; t++) {
        const trace_point q = {p.x_q8 + t * u[0], p.y_q8 + t * u[1]};
        const int32_t c = ridge_contrast(maps, q, n, w);
        if (c == INT32_MIN)
            return -1;
        paint += c >= LANE_RIDGE_MIN;
        sum += c < 4 * LANE_RIDGE_MIN ? c : 4 * LANE_RIDGE_MIN;
    }
    return paint * 4 >= TRACE_SEG * 3 ? sum : -1;
}

/* p moved across direction k onto the middle of the ridge near it: the
 * run of pixels within 8 grey levels of the brightest one among
 * TRACE_CENTRE either side. */
static trace_point centre_on_ridge(const lane_maps *maps, trace_point p, int32_t k)
{
    const int16_t n[2] = {(int16_t)-trace_dir[k][1], trace_dir[k][0]};
    int32_t v[2 * TRACE_CENTRE + 1], best = 0;
    for (int32_t j = 0; j <= 2 * TRACE_CENTRE; j++) {
        const int64_t o = j - TRACE_CENTRE;
        v[j] = map_at(maps, maps->src, p.x_q8 + o * n[0], p.y_q8 + o * n[1]);
        if (v[j] > v[best] || (v[j] == v[best] && rte_abs64(o) < rte_abs64(best - TRACE_CENTRE)))
            best = j;
    }
    int32_t lo = best, hi = best;
    while (lo > 0 && v[lo - 1] >= v[best] - 8)
        lo--;
    while (hi < 2 * TRACE_CENTRE && v[hi + 1] >= v[best] - 8)
        hi++;
    const int64_t o2 = lo + hi - 2 * TRACE_CENTRE; /* twice the offset */
    return (trace_point){p.x_q8 + o2 * n[0] / 2, p.y_q8 + o2 * n[1] / 2};
}

/* The table direction nearest (dx, dy). */
static int32_t nearest_dir(int64_t dx, int64_t dy)
{
    int32_t best = 0;
    int64_t best_dot = INT64_MIN;
    for (int32_t k = 0; k < TRACE_DIRS; k++) {
        const int64_t dot = dx * trace_dir[k][0] + dy * trace_dir[k][1];
        if (dot > best_dot) {
            best_dot = dot;
            best = k;
        }
    }
    return best;
}

/* The paint's x per row (downwards, 1/256 px) over the rows of a run
 * (xs_q8[i] on row y + i where seen[i]): least squares. */
static int64_t run_slope_q8(const bool seen[TRACE_RUN_ROWS], const int64_t xs_q8[TRACE_RUN_ROWS])
{
    int64_t n = 0, sy = 0, sx = 0, syy = 0, syx = 0;
    for (int64_t i = 0; i < TRACE_RUN_ROWS; i++) {
        if (!seen[i])
            continue;
        const int64_t x = xs_q8[i] - xs_q8[0];
        n++;
        sy += i;
        sx += x;
        syy += i * i;
        syx += i * x;
    }
    const int64_t var = n * syy - sy * sy;
    return var > 0 ? (n * syx - sy * sx) / var : 0;
}

/* Where the trace starts: the run of TRACE_RUN_ROWS rows highest up on
 * which the lane's curve lies on paint (in the refit's band) on its top
 * row and on a quarter of its rows (a run of the marking, not paint the
 * curve crosses); the paint on its lowest such row (at its top the
 * marking may be leaving the band already, cut by it), and the paint's
 * direction over the run as a step up (the marking's own: where it turns
 * away, the curve lags). False when there is no such run. */
static bool trace_start(const lane_maps *maps, const lane_fit_hint *rows, const rte_lane *lane,
                        trace_point *at, int32_t *dir)
{
    /* Down from the top row, so the search ends at the first run: row r
     * in slot (r - y_lo) % TRACE_RUN_ROWS; the run from row y is complete
     * at row y + TRACE_RUN_ROWS - 1 (cut at y_hi near the bottom). */
    bool seen[TRACE_RUN_ROWS] = {false};
    int64_t xs_q8[TRACE_RUN_ROWS] = {0};
    const int32_t y_lo = rows->y_top > maps->cy0 ? rows->y_top : maps->cy0;
    const int32_t y_hi = rows->y_bottom < maps->cy0 + maps->edges->height - 1
                             ? rows->y_bottom
                             : maps->cy0 + maps->edges->height - 1;
    int32_t in_run = 0; /* paint rows among the last TRACE_RUN_ROWS */
    for (int32_t r = y_lo; r <= y_hi + TRACE_RUN_ROWS - 1; r++) {
        const int32_t slot = (r - y_lo) % TRACE_RUN_ROWS;
        bool paint = false;
        band_pixels px = {0, 0, 0, 0};
        int64_t lx;
        if (r <= y_hi)
            paint = rte_lane_paint_along(maps, rows, lane, 1, r, &lx, &px);
        in_run += (int32_t)paint - (int32_t)seen[slot];
        seen[slot] = paint;
        xs_q8[slot] = paint ? (px.sum_x + px.n * maps->cx0) * 256 / px.n : 0;
        const int32_t y = r - (TRACE_RUN_ROWS - 1); /* the run's top row */
        if (y < y_lo || !seen[(y - y_lo) % TRACE_RUN_ROWS] || in_run < TRACE_RUN_ROWS / 4)
            continue;
        /* the run from row y down: run_seen[i] on row y + i */
        bool run_seen[TRACE_RUN_ROWS];
        int64_t run_xs[TRACE_RUN_ROWS];
        int32_t low = 0;
        for (int32_t i = 0; i < TRACE_RUN_ROWS; i++) {
            const int32_t k = (y - y_lo + i) % TRACE_RUN_ROWS;
            run_seen[i] = seen[k] && y + i <= y_hi;
            run_xs[i] = xs_q8[k];
            low = run_seen[i] ? i : low;
        }
        *at = (trace_point){run_xs[low], (int64_t)(y + low) * 256};
        *dir = nearest_dir(-run_slope_q8(run_seen, run_xs), -256);
        return true;
    }
    return false;
}

/* The marking followed from `at` (on its middle) along direction `dir`
 * (a step up the image) until TRACE_MISSES steps in a row find no paint, it would turn
 * down the image, or it reaches the ROI's top row: its points into
 * pts[], returns how many. */
static int32_t trace_follow(const lane_maps *maps, const lane_fit_hint *rows, trace_point at,
                            int32_t dir, trace_point pts[TRACE_MAX_STEPS])
{
    int32_t n = 0, misses = 0;
    /* the last TRACE_RECENT scores taken: a step scoring less than half
     * the best of them has left the marking for something fainter beside
     * its end (a pavement seam, a crack) */
    int64_t recent[TRACE_RECENT] = {0};
    for (int32_t step = 0; step < TRACE_MAX_STEPS && misses < TRACE_MISSES; step++) {
        /* the road either side: past half the band (a marking's half-width
         * near the camera, more than it far up) */
        const int64_t w = rte_lane_band_px(rows, maps->tol, (int32_t)(at.y_q8 >> 8)) / 2 + 2;
        int32_t best = -1;
        int64_t best_score = -1;
        for (int32_t d = -TRACE_FAN; d <= TRACE_FAN; d++) {
            const int32_t k = (dir + d + TRACE_DIRS) % TRACE_DIRS;
            if (trace_dir[k][1] > -TRACE_RISE_MIN)
                continue; /* up the image only */
            const int64_t s = segment_score(maps, at, k, w);
            if (s > best_score || (s == best_score && s >= 0 && d == 0)) {
                best_score = s;
                best = k;
            }
        }
        const int32_t k = best_score >= 0 ? best : dir;
        trace_point next = {at.x_q8 + TRACE_STEP * trace_dir[k][0],
                            at.y_q8 + TRACE_STEP * trace_dir[k][1]};
        if (next.y_q8 < (int64_t)rows->y_top * 256)
            break;
        int64_t reference = 0;
        for (int32_t i = 0; i < TRACE_RECENT; i++)
            reference = recent[i] > reference ? recent[i] : reference;
        if (best_score < 0 || 2 * best_score < reference) {
            misses++;
            at = next; /* on along the last direction, over a worn patch */
            continue;
        }
        misses = 0;
        recent[n % TRACE_RECENT] = best_score;
        dir = k;
        at = centre_on_ridge(maps, next, k);
        pts[n++] = at;
        /* the points put back on the ridge may run along the rows although
         * each step climbs: TRACE_FLAT_STEPS that climbed by less than 1.5
         * degrees follow a ridge across the road (the far edge of a crest),
         * not the marking, which beyond a crest still climbs (by 2 degrees
         * in test_far_trace_drawn); the trace ends where they began */
        if (n > TRACE_FLAT_STEPS && pts[n - 1 - TRACE_FLAT_STEPS].y_q8 - pts[n - 1].y_q8 <
                                        TRACE_RISE_MIN * TRACE_STEP * TRACE_FLAT_STEPS / 4)
            return n - TRACE_FLAT_STEPS;
    }
    return n;
}

void rte_lane_trace_far(const lane_maps *maps, const lane_fit_hint *rows, rte_lane *lane)
{
    lane->far_count = 0;
    trace_point at = {0, 0}, pts[TRACE_MAX_STEPS];
    int32_t dir = 0;
    if (!lane->found || lane->predicted || !trace_start(maps, rows, lane, &at, &dir))
        return;
    at = centre_on_ridge(maps, at, dir);
    const int32_t n = trace_follow(maps, rows, at, dir, pts);
    /* The trace replaces the curve from where it leaves it by more than
     * one and a half bands (within that it wanders no more than a far
     * marking's width), and only when it goes on for TRACE_MIN_STEPS
     * beyond that: the last steps may be paint beside the marking's worn
     * or shaded end. */
    int32_t leave = 0;
    while (leave < n) {
        const int32_t y = (int32_t)((pts[leave].y_q8 + 128) >> 8);
        if (rte_abs64(pts[leave].x_q8 - rte_lane_x_q8(lane, y)) >
            3 * rte_lane_band_px(rows, maps->tol, y) * 128)
            break;
        leave++;
    }
    if (n - leave < TRACE_MIN_STEPS)
        return;
    const trace_point from = leave > 0 ? pts[leave - 1] : at;
    lane->far_x_q8[0] = lane_clamp32(from.x_q8, INT32_MIN, INT32_MAX);
    lane->far_y[0] = (int32_t)((from.y_q8 + 128) >> 8);
    /* Points TRACE_POINT_ROWS rows apart, or TRACE_POINT_COLS columns and
     * two rows where the marking runs nearly along the rows, then the end,
     * TRACE_END_ROWS rows, or twice TRACE_POINT_COLS columns and two rows,
     * from the point before it: a reader extending the last piece beyond the end then
     * follows the trace's last stretch, not its last step's noise. */
    const trace_point end = pts[n - 1];
    const int32_t y_end = (int32_t)((end.y_q8 + 128) >> 8);
    if (lane->far_y[0] - y_end < TRACE_END_ROWS)
        return; /* sideways more than up: not a lane's far part */
    int32_t k = 1;
    for (int32_t i = leave; i < n - 1 && k < RTE_LANE_FAR_POINTS - 1; i++) {
        const int32_t y = (int32_t)((pts[i].y_q8 + 128) >> 8);
        const int32_t rise = lane->far_y[k - 1] - y;
        const int64_t run = rte_abs64(pts[i].x_q8 - lane->far_x_q8[k - 1]);
        const bool apart = rise >= TRACE_POINT_ROWS || (rise >= 2 && run >= TRACE_POINT_COLS * 256);
        const bool before_end =
            y - y_end >= TRACE_END_ROWS ||
            (y - y_end >= 2 && rte_abs64(end.x_q8 - pts[i].x_q8) >= 2 * TRACE_POINT_COLS * 256);
        if (!apart || !before_end)
            continue;
        lane->far_x_q8[k] = lane_clamp32(pts[i].x_q8, INT32_MIN, INT32_MAX);
        lane->far_y[k++] = y;
    }
    lane->far_x_q8[k] = lane_clamp32(pts[n - 1].x_q8, INT32_MIN, INT32_MAX);
    lane->far_y[k++] = y_end;
    lane->far_count = k >= 2 ? k : 0;
}
