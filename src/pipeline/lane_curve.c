/* The curve model of a lane, per frame (integer only; see
 * include/rtedge/lane.h and docs/lanes.md, "Curves").
 *
 * On a flat road a marking at lateral offset X0, with the road's heading
 * psi and curvature kappa, lies at X(z) = X0 + psi z + kappa z^2 / 2 at
 * distance z; a camera at height h and focal length f sees it at
 * x = a d + b + c / d, d = y - y_horizon (rows below the horizon), with
 * a = X0 / h, b = x_centre + f psi and c = f^2 h kappa / 2. The straight
 * fit (segments, then the refit on the edge pixels) gives a line; windows
 * of rows then follow the marking up the image (lane_windows.c). Both
 * sides' windows are then fitted together, b and c shared and a per side,
 * so a dashed side takes the solid side's bend. The horizon row is where the
 * two straight lines meet, else an eighth of the lane above the ROI's top
 * row (lane_horizon_row). The curve replaces the lines only when it
 * explains the windows much better than they do (bend_pays). */
#include "lane_windows.h"

#include "algo/geom_fixed.h"

/* A bow below this (1/256 px) is no curve: the straight fit stands. */
#define CURVE_MIN_BOW_Q8 192 /* 3/4 px */

/* The joint model of both sides over their windows, in normalised
 * variables: x = A_side delta + B + C gamma, delta = d / d_bottom and
 * gamma = d_top / d (both 1/65536), x in 1/256 px. B (the vanishing
 * point's x) and C (the bend) are the road's, shared; A is each marking's
 * lateral offset. A_side is eliminated per side (each side's 1, gamma and
 * x with their component along delta removed), leaving 2x2 normal
 * equations for B and C. */
typedef struct side_sums {
    rte_i128 sdd, sd1, sdg, sdx; /* sums of w delta f, f = delta, 1, gamma, x */
} side_sums;

/* A side's sums of w delta f over its windows. */
static side_sums sums_of(const curve_side *cs)
{
    side_sums t = {0, 0, 0, 0};
    for (int32_t i = 0; i < cs->n; i++) {
        const curve_window *w = &cs->win[i];
        const rte_i128 dl = cs->bs[i].delta_q16, g = cs->bs[i].q_q16, x = w->x_q8;
        t.sdd += w->weight * (dl * dl >> 16);
        t.sd1 += w->weight * dl;
        t.sdg += w->weight * (dl * g >> 16);
        t.sdx += w->weight * (dl * x >> 16);
    }
    return t;
}

static bool joint_fit(const curve_side cs[2], const bool use[2], int64_t *b_q8, int64_t *c_q8,
                      side_sums ss[2])
{
    rte_i128 m11 = 0, m1g = 0, mgg = 0, v1 = 0, vg = 0;
    for (int side = 0; side < 2; side++) {
        side_sums *t = &ss[side];
        *t = use[side] ? sums_of(&cs[side]) : (side_sums){0, 0, 0, 0};
        if (t->sdd <= 0)
            continue;
        /* components along delta: f~ = f - delta * sum(w delta f) / sdd */
        for (int32_t i = 0; i < cs[side].n; i++) {
            const curve_window *w = &cs[side].win[i];
            const rte_i128 dl = cs[side].bs[i].delta_q16, g = cs[side].bs[i].q_q16, x = w->x_q8;
            const rte_i128 o = 65536 - dl * t->sd1 / t->sdd; /* 1~, 1/65536 */
            const rte_i128 gt = g - dl * t->sdg / t->sdd;    /* gamma~ */
            const rte_i128 xt = x - dl * t->sdx / t->sdd;    /* x~, 1/256 px */
            m11 += w->weight * (o * o >> 16);
            m1g += w->weight * (o * gt >> 16);
            mgg += w->weight * (gt * gt >> 16);
            v1 += w->weight * o * xt;
            vg += w->weight * gt * xt;
        }
    }
    const rte_i128 det = m11 * mgg - m1g * m1g;
    if (det <= 0)
        return false;
    /* B, C in 1/256 px: (v 2^16 / m) with m in 1/65536 */
    const rte_i128 b = (v1 * mgg - vg * m1g) / det, c = (vg * m11 - v1 * m1g) / det;
    if (b > ((rte_i128)1 << 40) || b < -((rte_i128)1 << 40) || c > ((rte_i128)1 << 40) ||
        c < -((rte_i128)1 << 40))
        return false;
    *b_q8 = (int64_t)b;
    *c_q8 = (int64_t)c;
    return true;
}

/* A side's lateral term A (1/256 px per unit of delta) for the road's B
 * and C, from its windows' sums (ss->sdd > 0). */
static int64_t side_offset(const side_sums *ss, int64_t b, int64_t c)
{
    return (int64_t)(((rte_i128)ss->sdx * 65536 - b * ss->sd1 - c * ss->sdg) / ss->sdd);
}

/* The row where the two straight lines meet (the vanishing point's), when
 * it lies between a lane's length above the ROI top and its top row. */
static bool vanishing_row(const lane_line line[2], const lane_fit_hint *h, int32_t *row)
{
    const int64_t ds = line[0].slope_q16 - line[1].slope_q16; /* x per row, 1/65536 */
    if (ds <= 0)                                              /* left leans right going up */
        return false;
    const int64_t y = h->y_bottom, gap = lane_line_x_q8(&line[1], y) - lane_line_x_q8(&line[0], y);
    const int64_t up = gap * 256 / ds; /* rows above the bottom row */
    const int64_t v = y - up, span = h->y_bottom - h->y_top;
    if (v > h->y_top - 2 || v < h->y_top - span)
        return false;
    *row = (int32_t)v;
    return true;
}

/* The weighted squared residuals (1/65536 px^2) of side's windows to
 * the straight line through them (least squares on 1 and u). */
static rte_i128 straight_sse(const curve_side *cs)
{
    rte_i128 w = 0, su = 0, suu = 0, sx = 0, sux = 0;
    for (int32_t i = 0; i < cs->n; i++) {
        const rte_i128 wi = cs->win[i].weight, u = cs->bs[i].u_q16, x = cs->win[i].x_q8;
        w += wi, su += wi * u, suu += wi * (u * u >> 16), sx += wi * x, sux += wi * (u * x >> 16);
    }
    const rte_i128 det = w * suu - (su * su >> 16);
    if (cs->n < 3 || det <= 0)
        return 0;
    const rte_i128 b1 = (w * sux - su * sx / 65536) * 65536 / det; /* x per unit u, 1/256 px */
    const rte_i128 b0 = (sx - (b1 * su >> 16)) / w;
    rte_i128 sse = 0;
    for (int32_t i = 0; i < cs->n; i++) {
        const rte_i128 e = cs->win[i].x_q8 - b0 - (b1 * cs->bs[i].u_q16 >> 16);
        sse += cs->win[i].weight * e * e;
    }
    return sse;
}

/* The weighted squared residuals (1/65536 px^2) of a side's windows to
 * the bend b, c with the side's own lateral term A (from its sums ss),
 * and their weight in *w. */
static rte_i128 side_curve_sse(const curve_side *cs, const side_sums *ss, int64_t b, int64_t c,
                               rte_i128 *w)
{
    const rte_i128 a = side_offset(ss, b, c);
    rte_i128 sse = 0;
    for (int32_t i = 0; i < cs->n; i++) {
        const curve_window *wi = &cs->win[i];
        const rte_i128 e =
            wi->x_q8 - (a * cs->bs[i].delta_q16 >> 16) - b - (c * cs->bs[i].q_q16 >> 16);
        sse += wi->weight * e * e;
        *w += wi->weight;
    }
    return sse;
}

/* Whether the bend explains the windows: on the sides with three windows
 * or more, the curves' squared residuals at most a third of the straight
 * lines', and the straight lines off by more than 1.5 px (RMS). Paint
 * that a straight line fits stays straight. */
static bool bend_pays(const curve_side cs[2], const bool use[2], int64_t b, int64_t c,
                      const side_sums ss[2])
{
    rte_i128 sse_line = 0, sse_curve = 0, w = 0;
    for (int side = 0; side < 2; side++) {
        if (!use[side] || cs[side].n < 3 || ss[side].sdd <= 0)
            continue;
        sse_line += straight_sse(&cs[side]);
        sse_curve += side_curve_sse(&cs[side], &ss[side], b, c, &w);
    }
    return w > 0 && 3 * sse_curve <= sse_line && sse_line > w * 147456;
}

/* Whether a side left out of the bend (its windows disagreed with the
 * joint fit) still follows it: its windows, with their own lateral term
 * A, as close to the road's bend as to their own straight line (1.5 px
 * RMS of slack). Roads are parallel: a side whose paint stops short (a
 * glare patch, a dash) then takes the bend beyond it instead of running
 * straight on. *ss gets the side's sums. */
static bool follows_bend(const curve_side *cs, int64_t b, int64_t c, side_sums *ss)
{
    *ss = sums_of(cs);
    if (cs->n < 3 || ss->sdd <= 0)
        return false;
    rte_i128 w = 0;
    return side_curve_sse(cs, ss, b, c, &w) <= straight_sse(cs) + w * 147456;
}

/* The windows' bases for the horizon of *h. */
static void set_basis(curve_side *cs, const lane_fit_hint *h)
{
    for (int32_t i = 0; i < cs->n; i++)
        cs->bs[i] = basis_at(h, cs->win[i].y);
}

/* The bow of the bend c under the horizon of *hint: the 1/d term's
 * distance from its chord at mid-height (1/256 px). */
static int64_t bow_of(const lane_fit_hint *hint, int64_t c)
{
    const int32_t span = hint->y_bottom - hint->y_top;
    const curve_basis bottom = basis_at(hint, hint->y_bottom);
    const curve_basis mid = basis_at(hint, hint->y_bottom - span / 2);
    const int64_t sag_q16 = mid.q_q16 - (bottom.q_q16 + 65536) / 2;
    return c * sag_q16 >> 16;
}

/* A bow beyond the lane's height is no bend of a road. */
static bool bow_beyond_lane(const lane_fit_hint *hint, int64_t bow)
{
    return rte_abs64(bow) > (int64_t)(hint->y_bottom - hint->y_top) * 256;
}

/* The horizon row under which the bend fits the windows of the sides in
 * use best (least squared residuals), into *h, and the windows' bases for
 * it; for a side bent alone. On a flat road the horizon is where the two
 * lines meet, but a road that climbs or drops, or a camera that pitches,
 * moves it: on a winding mountain road the markings' own horizon lay
 * anywhere from a lane's length above the ROI's top row to just above it.
 * Candidates from a lane's length above the top row to two rows above it,
 * closer together near it, where the bend's shape changes fastest. (For
 * the joint fit the horizon stays where the lines meet: chosen freely
 * there, it fits an S-bend's reversal, which the model cannot follow, and
 * the tracked shape then leads a dashed side astray.) A horizon whose bend
 * bows by more than the lane's height is passed over: fit_bend refuses
 * that bow, and a marking that turns sharply at its far end (a mountain
 * road beyond a crest) would otherwise stay straight instead of taking
 * the next best horizon's bend. */
static void choose_horizon(curve_side cs[2], const bool use[2], lane_fit_hint *h)
{
    static const int32_t steps_64[] = {0, 1, 2, 4, 8, 16, 32, 64}; /* of the span, /64 */
    const int32_t span = h->y_bottom - h->y_top;
    const int32_t n_steps = (int32_t)(sizeof steps_64 / sizeof steps_64[0]);
    rte_i128 reference = -1, best = -1;
    lane_fit_hint chosen = *h;
    /* k = -1: the hint's own horizon (where the lines meet, else the
     * default), the reference the others must halve: a horizon chosen for
     * a few pixels' gain turns a dashed side's bend */
    for (int32_t k = -1; k < n_steps; k++) {
        lane_fit_hint t = *h;
        if (k >= 0) {
            t.y_horizon = h->y_top - 2 - span * steps_64[k] / 64;
            t.has_horizon = true;
        }
        for (int side = 0; side < 2; side++)
            if (use[side])
                set_basis(&cs[side], &t);
        int64_t b, c;
        side_sums ss[2];
        if (!joint_fit(cs, use, &b, &c, ss) || (k >= 0 && bow_beyond_lane(&t, bow_of(&t, c))))
            continue;
        rte_i128 sse = 0, w = 0;
        for (int side = 0; side < 2; side++)
            if (use[side] && ss[side].sdd > 0)
                sse += side_curve_sse(&cs[side], &ss[side], b, c, &w);
        if (k < 0)
            reference = sse;
        else if ((reference < 0 || 2 * sse < reference) && (best < 0 || sse < best)) {
            best = sse;
            chosen = t;
        }
    }
    *h = chosen;
    for (int side = 0; side < 2; side++)
        if (use[side])
            set_basis(&cs[side], h);
}

/* The bend of the sides in use[]: b, c and the bow (the 1/d term's
 * distance from its chord at mid-height, 1/256 px) when the windows
 * support one and it pays; false otherwise. */
static bool fit_bend(const curve_side cs[2], const bool use[2], const lane_fit_hint *hint,
                     int64_t *b, int64_t *c, int64_t *bow, side_sums ss[2])
{
    if (!joint_fit(cs, use, b, c, ss))
        return false;
    *bow = bow_of(hint, *c);
    if (rte_abs64(*bow) < CURVE_MIN_BOW_Q8 || bow_beyond_lane(hint, *bow))
        return false;
    return bend_pays(cs, use, *b, *c, ss);
}

/* One side's bend: b, c and the bow (as fit_bend gives them), the highest
 * row it is reported to and the hint with its horizon. */
typedef struct side_bend {
    bool bent;
    int64_t b, c, bow;
    int32_t y_supported;
    lane_fit_hint hint;
} side_bend;

/* When the joint fit fails (the markings disagree: paint of something
 * else, a worn line, a road that is not flat, so that the two do not
 * share one horizon), or when only one side has windows and the default
 * horizon does not suit its bend: each side alone, with its own horizon,
 * and a side that does not bend alone takes the other's bend when its
 * windows agree with it (follows_bend). */
static void bend_each_side(curve_side cs[2], const bool supports[2], const int64_t weight[2],
                           side_sums ss[2], side_bend sb[2])
{
    side_sums alone_ss[2];
    for (int side = 0; side < 2; side++) {
        const bool alone[2] = {side == 0, side == 1};
        side_bend *t = &sb[side];
        choose_horizon(cs, alone, &t->hint);
        /* alone, its windows must start in the lane's lowest quarter: a
         * line that missed the near paint would otherwise bend to the far */
        t->bent = supports[side] && cs[side].bs[0].u_q16 <= 16384 &&
                  fit_bend(cs, alone, &t->hint, &t->b, &t->c, &t->bow, alone_ss);
        ss[side] = alone_ss[side];
        t->y_supported = cs[side].y_supported;
    }
    /* A road bends one way: bends of opposite signs mean one side lies on
     * something else, and the better supported one is kept. */
    if (sb[0].bent && sb[1].bent && (sb[0].c < 0) != (sb[1].c < 0))
        sb[weight[0] >= weight[1] ? 1 : 0].bent = false;
    for (int side = 0; side < 2; side++) {
        const side_bend *o = &sb[1 - side];
        if (sb[side].bent || !o->bent)
            continue;
        set_basis(&cs[side], &o->hint);
        if (follows_bend(&cs[side], o->b, o->c, &ss[side]))
            sb[side] = *o;
    }
}

/* Whether a bend moved the bottom end of a side seen only in the lane's
 * upper half (its lowest window above the middle, or no window) by more
 * than 3/8 of the lane's height from its straight line. Its offset A then
 * comes from far windows alone, where the 1/d term dominates: a bend that
 * is a little off there, or far paint that owes its place to the road's
 * pitch rather than a bend, throws the near end far away. On the synthetic
 * roads (a flat road seen by an exact pinhole camera, bends down to 22 m)
 * a bend moves such an end by 0.36 of the lane's height at most; on the
 * real freeway of fixtures/lanes by half of it in the median and up to
 * all of it, the dashed side swinging 100-200 px from frame to frame. */
static bool moves_unseen_end(const curve_side *cs, const lane_fit_hint *hint,
                             const lane_line *straight, const lane_line *bent)
{
    if (cs->n > 0 && cs->bs[0].u_q16 <= 32768)
        return false;
    const int64_t moved =
        rte_abs64(lane_line_x_q8(bent, hint->y_bottom) - lane_line_x_q8(straight, hint->y_bottom));
    return moved * 8 > (int64_t)(hint->y_bottom - hint->y_top) * 3 * 256;
}

/* A bent side's line becomes its chord and *curve gets its bow. ss: the
 * side's window sums under its bend's horizon. */
static void apply_bend(const side_bend *sb, const side_sums *ss, lane_line *line, lane_curve *curve)
{
    const lane_fit_hint *hs = &sb->hint;
    const int32_t span = hs->y_bottom - hs->y_top;
    const curve_basis bottom = basis_at(hs, hs->y_bottom);
    const int64_t delta_top = delta_at(hs, hs->y_top);
    /* A: from its windows, else where its straight line is. */
    int64_t a;
    if (ss->sdd > 0) {
        a = side_offset(ss, sb->b, sb->c);
    } else {
        const curve_basis at = basis_at(hs, line->y_mid);
        a = (lane_line_x_q8(line, line->y_mid) - sb->b - (sb->c * at.q_q16 >> 16)) * 65536 /
            at.delta_q16;
    }
    const int64_t xb = a + sb->b + (sb->c * bottom.q_q16 >> 16);
    const int64_t xt = (a * delta_top >> 16) + sb->b + sb->c;
    line->y_mid = hs->y_bottom;
    line->x_mid_q8 = xb;
    line->slope_q16 = (xt - xb) * 256 / -span;
    curve->bow_q8 = sb->bow;
    curve->y_supported = sb->y_supported;
    curve->y_horizon = (int32_t)lane_horizon_row(hs);
}

void rte_lane_curves_fit(const lane_maps *maps, const lane_fit_hint *base, const bool seen[2],
                         lane_line line[2], lane_curve curve[2])
{
    lane_fit_hint h = *base;
    h.has_horizon = seen[0] && seen[1] && vanishing_row(line, base, &h.y_horizon);
    const lane_fit_hint *hint = &h;
    const int32_t span = hint->y_bottom - hint->y_top;
    const int32_t y_horizon = (int32_t)lane_horizon_row(hint);
    curve_side cs[2];
    side_sums ss[2];
    bool use[2] = {false, false}, supports[2] = {false, false};
    int64_t weight[2] = {0, 0};
    for (int side = 0; side < 2; side++) {
        curve[side] = (lane_curve){0, hint->y_bottom, y_horizon, hint->y_bottom};
        cs[side].n = 0;
        if (!seen[side] || span < 2 * CURVE_WINDOWS)
            continue;
        rte_lane_walk_side(maps, hint, &line[side], &cs[side]);
        if (cs[side].n > 0)
            curve[side].y_lowest = (int32_t)cs[side].win[0].y;
        use[side] = cs[side].n >= 1;
        /* A curve needs one side's windows up to the lane's upper half. */
        supports[side] = cs[side].n >= 4 && cs[side].bs[cs[side].n - 1].u_q16 >= 32768;
        for (int32_t i = 0; i < cs[side].n; i++)
            weight[side] += cs[side].win[i].weight;
    }
    if (!supports[0] && !supports[1])
        return;
    /* Both sides' windows together, one bend for the road, else each side
     * alone (bend_each_side). */
    side_bend sb[2];
    sb[0] = sb[1] = (side_bend){false, 0, 0, 0, hint->y_bottom, h};
    side_bend joint = sb[0];
    if (fit_bend(cs, use, hint, &joint.b, &joint.c, &joint.bow, ss)) {
        /* The shared bend carries a dashed side up to where the other is
         * seen. */
        for (int side = 0; side < 2; side++)
            if (use[side] && cs[side].y_supported < joint.y_supported)
                joint.y_supported = cs[side].y_supported;
        for (int side = 0; side < 2; side++) {
            sb[side] = joint;
            sb[side].bent = seen[side];
        }
    } else if (use[0] || use[1]) {
        bend_each_side(cs, supports, weight, ss, sb);
    }
    for (int side = 0; side < 2; side++) {
        if (!sb[side].bent)
            continue;
        const lane_line straight = line[side];
        const lane_curve plain = curve[side];
        apply_bend(&sb[side], &ss[side], &line[side], &curve[side]);
        if (moves_unseen_end(&cs[side], hint, &straight, &line[side])) {
            line[side] = straight;
            curve[side] = plain;
        }
    }
}
