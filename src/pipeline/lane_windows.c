/* The windows of a marking up the image, per frame (integer only; see
 * lane_curve.c for the model and docs/lanes.md, "Curves"): from the bottom
 * row up, windows of rows searched around the straight fit moved by the
 * residual the windows below show (extrapolated, then through a fit of the
 * model to them once there are three), so the search follows the bend the
 * straight line leaves; then, where they lose the marking, the marking
 * traced up row by row. */
#include "lane_windows.h"

#include "algo/geom_fixed.h"

typedef struct curve_walk {
    int64_t o_q8;  /* residual at row y of the last window that saw paint */
    int64_t d_q16; /* its change per row upwards, 1/65536 px */
    int64_t y;
    bool fitted;  /* p holds a fit of the windows so far */
    int64_t p[3]; /* residual = p0 + p1 u + p2 q, 1/256 px */
} curve_walk;

/* The walk's expected residual at row y. */
static int64_t walk_residual(const lane_fit_hint *h, const curve_walk *walk, int64_t y)
{
    if (walk->fitted) {
        const curve_basis b = basis_at(h, y);
        return walk->p[0] + ((walk->p[1] * b.u_q16 + walk->p[2] * b.q_q16) >> 16);
    }
    return walk->o_q8 + ((walk->d_q16 * (walk->y - y)) >> 8);
}

/* The rows y_hi down to y_lo searched around the line plus the walk's
 * expected residual; false when too few rows hold paint. wide: each row's
 * marking nearest the expected column within twice the band instead
 * (rte_lane_paint_near), for a bend sharper than the walk foresaw. */
static bool search_window(const lane_maps *maps, const lane_fit_hint *hint, const lane_line *line,
                          const curve_walk *walk, int32_t y_hi, int32_t y_lo, bool wide,
                          curve_window *out)
{
    const rte_image_u8 *edges = maps->edges;
    const int32_t cx0 = maps->cx0, cy0 = maps->cy0;
    int64_t sum_r = 0, sum_y = 0, n = 0, rows = 0;
    for (int32_t y = y_hi; y >= y_lo; y--) {
        if (y < cy0 + 1 || y > cy0 + edges->height - 1)
            continue;
        const int64_t lx = lane_line_x_q8(line, y), ex = lx + walk_residual(hint, walk, y);
        const int64_t band = rte_lane_band_px(hint, maps->tol, y);
        const int64_t xa = ((ex + 128) >> 8) - band - cx0;
        /* the expected marking's direction here, x per row downwards */
        const int64_t slope =
            line->slope_q16 +
            ((walk_residual(hint, walk, y) - walk_residual(hint, walk, y - 1)) * 256);
        band_pixels px;
        const bool ok = wide ? rte_lane_paint_near(maps, y, (ex + 128) >> 8, 2 * band, slope, &px)
                             : rte_lane_paint_row(maps, y, xa, xa + 2 * band, slope, &px);
        if (!ok)
            continue;
        sum_r += (px.sum_x + px.n * cx0) * 256 - px.n * lx;
        sum_y += px.n * y;
        n += px.n;
        rows++;
    }
    const int64_t need = (y_hi - y_lo + 1) / 3;
    if (n == 0 || rows < (need > 2 ? need : 2))
        return false;
    out->r_q8 = sum_r / n;
    out->y = sum_y / n;
    out->x_q8 = lane_line_x_q8(line, out->y) + out->r_q8;
    out->weight = n;
    return true;
}

/* 3x3 determinant of rows a, b, c. */
static rte_i128 det3(const rte_i128 a[3], const rte_i128 b[3], const rte_i128 c[3])
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* Weighted least squares r = p0 + p1 u + p2 q over the windows (u, q in
 * 1/65536, r and p in 1/256 px); false when ill-posed. The moments are
 * means (weights normalised), so every product stays far inside 128
 * bits. */
static bool fit_model(const curve_window *win, const curve_basis *bs, int32_t n, int64_t p[3])
{
    rte_i128 m[3][3] = {{0}}, v[3] = {0}, w = 0;
    for (int32_t i = 0; i < n; i++) {
        const rte_i128 f[3] = {65536, bs[i].u_q16, bs[i].q_q16};
        for (int j = 0; j < 3; j++) {
            for (int k = 0; k < 3; k++)
                m[j][k] += (f[j] * f[k] >> 16) * win[i].weight;
            v[j] += f[j] * win[i].weight * win[i].r_q8;
        }
        w += win[i].weight;
    }
    if (w <= 0)
        return false;
    for (int j = 0; j < 3; j++) {
        for (int k = 0; k < 3; k++)
            m[j][k] /= w;
        v[j] /= w;
    }
    const rte_i128 det = det3(m[0], m[1], m[2]);
    /* windows bunched too closely to tell a bend from a slope */
    if (det < ((rte_i128)1 << 24))
        return false;
    for (int j = 0; j < 3; j++) {
        rte_i128 c[3][3];
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 3; k++)
                c[r][k] = k == j ? v[r] : m[r][k];
        const rte_i128 q = det3(c[0], c[1], c[2]) / det;
        if (q > ((rte_i128)1 << 40) || q < -((rte_i128)1 << 40))
            return false;
        p[j] = (int64_t)q;
    }
    return true;
}

/* Above the last window, where the windows lost the marking: the marking
 * traced up row by row (every CURVE_TRACE_STEP rows), each row's marking
 * nearest the column the last two points lead to (rte_lane_paint_near,
 * within the band plus the run since the last point, so a marking whose
 * slope doubles, turning almost level, is still found), until two steps in
 * a row find none. Where
 * a road turns sharply beyond a crest its markings run nearly along the
 * rows, faster than a window's band can follow. Each point is a window of
 * its step's rows. */
static void trace_up(const lane_maps *maps, const lane_fit_hint *hint, const lane_line *line,
                     curve_side *cs)
{
    if (cs->n < 3)
        return;
    const curve_window *a = &cs->win[cs->n - 2], *b = &cs->win[cs->n - 1];
    int64_t y = b->y, x_q8 = b->x_q8;
    int64_t dir_q16 = a->y > b->y ? (b->x_q8 - a->x_q8) * 256 / (b->y - a->y) : 0; /* x per row */
    int32_t traced = 0, misses = 0;
    for (int64_t yt = cs->y_supported - 1;
         yt >= hint->y_top && traced < CURVE_TRACE_MAX && misses < 2; yt -= CURVE_TRACE_STEP) {
        if (yt < maps->cy0 + 1 || yt > maps->cy0 + maps->edges->height - 2)
            break;
        const int64_t ex_q8 = x_q8 + ((dir_q16 * (yt - y)) >> 8);
        /* the bend may double the slope since the last point */
        const int64_t run = rte_abs64(dir_q16 * (y - yt)) >> 16;
        const int64_t reach = rte_lane_band_px(hint, maps->tol, (int32_t)yt) + run;
        band_pixels px;
        /* edges of any direction: a marking that turns level turns its
         * edges faster than the last points' slope tells */
        if (!rte_lane_paint_near(maps, (int32_t)yt, (ex_q8 + 128) >> 8, reach, LANE_SLOPE_ANY,
                                 &px)) {
            misses++;
            continue;
        }
        misses = 0;
        const int64_t xn_q8 = (px.sum_x + px.n * maps->cx0) * 256 / px.n;
        dir_q16 = lane_clamp32((xn_q8 - x_q8) * 256 / (yt - y), -16 * 65536, 16 * 65536);
        x_q8 = xn_q8;
        y = yt;
        const int64_t lx = lane_line_x_q8(line, yt);
        cs->bs[cs->n] = basis_at(hint, yt);
        cs->win[cs->n++] = (curve_window){xn_q8 - lx, yt, xn_q8, px.n * CURVE_TRACE_STEP};
        cs->y_supported = (int32_t)yt;
        traced++;
    }
}

void rte_lane_walk_side(const lane_maps *maps, const lane_fit_hint *hint, const lane_line *line,
                        curve_side *cs)
{
    const int32_t span = hint->y_bottom - hint->y_top;
    const int32_t rows = (span + CURVE_WINDOWS) / CURVE_WINDOWS;
    curve_walk walk = {0, 0, hint->y_bottom, false, {0, 0, 0}};
    cs->n = 0;
    cs->y_supported = hint->y_bottom;
    for (int32_t j = 0; j < CURVE_WINDOWS; j++) {
        const int32_t y_hi = hint->y_bottom - j * rows;
        const int32_t y_lo = y_hi - rows + 1 > hint->y_top ? y_hi - rows + 1 : hint->y_top;
        if (y_hi < hint->y_top)
            break;
        curve_window w;
        if (!search_window(maps, hint, line, &walk, y_hi, y_lo, false, &w) &&
            (cs->n == 0 || !search_window(maps, hint, line, &walk, y_hi, y_lo, true, &w)))
            continue;
        /* a change of residual over a few rows only (a first window at
         * the bottom row) would extrapolate noise far up */
        if (walk.y - w.y >= rows / 2)
            walk.d_q16 =
                lane_clamp32((w.r_q8 - walk.o_q8) * 256 / (walk.y - w.y), -2 * 65536, 2 * 65536);
        walk.o_q8 = w.r_q8;
        walk.y = w.y;
        cs->y_supported = y_lo;
        cs->bs[cs->n] = basis_at(hint, w.y);
        cs->win[cs->n++] = w;
        if (cs->n >= 3)
            walk.fitted = fit_model(cs->win, cs->bs, cs->n, walk.p);
    }
    trace_up(maps, hint, line, cs);
}
