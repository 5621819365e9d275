/* The other side of a lane found from one side alone (per frame, integer
 * only; see docs/lanes.md, "One side seen").
 *
 * On a flat road both markings follow x = a d + b + c / d (lane_curve.c):
 * b and c are the road's, a each marking's. Less the seen lane's bend
 * (its curve less its chord), both become lines that meet on the horizon
 * row; on a straight road that is where its line crosses the horizon,
 * near the ROI's top row (the default trapezoid is drawn up to it). A
 * dashed side between two dashes may show one short dash and a few far
 * ones, too short for the Hough search: seen from that point they line
 * up, so every edge pixel on the unseen side, less the bend, votes for
 * where the line from the point through it crosses the bottom row. The
 * strongest crossings are checked for paint along the whole lane. */
#include <string.h>

#include "lane_fixed.h"

/* Vanishing rows tried on a straight road: the ROI's top row, and an
 * eighth and a sixteenth of the lane above it and a sixteenth below (the
 * three recordings' lanes meet 30 rows above to 20 below it at 1280x720);
 * on a bend, the curve's horizon row alone. */
#define PARTNER_ROWS 4
static const int32_t partner_row_16ths[PARTNER_ROWS] = {-2, -1, 0, 1};
/* Bottom-row crossings counted, from a quarter to one and a quarter of
 * the frame's width beside the seen side's. */
#define PARTNER_BINS 128
/* Crossings checked for paint per vanishing row. */
#define PARTNER_PEAKS 3

typedef struct partner_votes {
    int32_t y_vp;
    int64_t x_vp_q8;
    int32_t bin[PARTNER_BINS];
} partner_votes;

/* The edge pixels of frame rows y_top..y_bottom beyond the seen line
 * (toward side `dir`: +1 right, -1 left) into each vanishing row's bins. */
static void partner_vote(const lane_maps *maps, const lane_fit_hint *rows, const rte_lane *seen,
                         int dir, int64_t lo_q8, int64_t bin_q8, partner_votes v[PARTNER_ROWS],
                         int nrows)
{
    const rte_image_u8 *e = maps->edges;
    const int64_t xs_bottom = seen->x_bottom_q8;
    const int32_t span = rows->y_bottom - rows->y_top;
    for (int32_t y = rows->y_bottom; y >= rows->y_top; y--) {
        const int32_t cy = y - maps->cy0;
        if (cy < 0 || cy >= e->height)
            continue;
        const uint8_t *r = rte_u8_row(e, cy);
        /* half the band beyond the seen lane: its own edges stay out */
        const int64_t x_seen = rte_lane_x_q8(seen, y), bend = x_seen - lane_chord_x_q8(seen, y);
        const int64_t xs = (x_seen >> 8) - maps->cx0 + dir * (maps->tol / 2 + 2);
        const int32_t x0 = dir > 0 ? lane_clamp32(xs, 0, e->width) : 0;
        const int32_t x1 = dir > 0 ? e->width : lane_clamp32(xs + 1, 0, e->width);
        int64_t scale_q16[PARTNER_ROWS];
        for (int k = 0; k < nrows; k++) {
            const int64_t d = y - v[k].y_vp;
            /* rows this near the vanishing point say little of the angle */
            scale_q16[k] = d > span / 8 ? ((int64_t)(rows->y_bottom - v[k].y_vp) << 16) / d : 0;
        }
        for (int32_t x = x0; x < x1; x++) {
            /* the edge map is sparse: eight empty pixels skipped at a time */
            if (x + 8 <= x1) {
                uint64_t word;
                memcpy(&word, r + x, sizeof word);
                if (word == 0) {
                    x += 7;
                    continue;
                }
            }
            if (!r[x])
                continue;
            const int64_t xq8 = (int64_t)(x + maps->cx0) * 256 - bend;
            for (int k = 0; k < nrows; k++) {
                if (!scale_q16[k])
                    continue;
                /* the crossing of the line from the point through (x, y) */
                const int64_t xb = v[k].x_vp_q8 + (((xq8 - v[k].x_vp_q8) * scale_q16[k]) >> 16);
                const int64_t off = (xb - xs_bottom) * dir - lo_q8;
                if (off >= 0 && off < bin_q8 * PARTNER_BINS)
                    v[k].bin[off / bin_q8]++;
            }
        }
    }
}

/* The rows with paint along lane `cand` (within twice the refit's band:
 * the bins are coarse) where its band stays clear of the seen lane's
 * (near their vanishing point the seen marking's paint would count). */
static int32_t partner_rows(const lane_maps *maps, const lane_fit_hint *rows, const rte_lane *cand,
                            const rte_lane *seen)
{
    int32_t n = 0;
    for (int32_t y = rows->y_bottom; y >= rows->y_top; y--) {
        if (y < maps->cy0 || y > maps->cy0 + maps->edges->height - 1)
            continue;
        const int64_t apart = rte_lane_x_q8(cand, y) - rte_lane_x_q8(seen, y);
        if (rte_abs64(apart) < 5 * 256 * rte_lane_band_px(rows, maps->tol, y))
            continue;
        int64_t lx;
        band_pixels px;
        n += rte_lane_paint_along(maps, rows, cand, 2, y, &lx, &px);
    }
    return n;
}

int32_t rte_lane_partner(const lane_maps *maps, const lane_fit_hint *rows, int seen_side,
                         const rte_lane *seen, int32_t width, rte_lane *found)
{
    const int32_t span = rows->y_bottom - rows->y_top;
    if (span < 16 || width < 16)
        return 0;
    const int dir = seen_side == RTE_LANE_LEFT ? 1 : -1;
    const int64_t lo_q8 = (int64_t)width * 256 / 4;
    const int64_t bin_q8 = ((int64_t)width * 256 + PARTNER_BINS - 1) / PARTNER_BINS;
    const int64_t xs_bottom = seen->x_bottom_q8;
    /* a bent lane's horizon is the one its bend is drawn from */
    const int nrows = seen->bow_q8 != 0 ? 1 : PARTNER_ROWS;
    partner_votes v[PARTNER_ROWS];
    for (int k = 0; k < nrows; k++) {
        memset(v[k].bin, 0, sizeof v[k].bin);
        v[k].y_vp = nrows == 1 ? seen->y_horizon : rows->y_top + partner_row_16ths[k] * (span / 16);
        v[k].x_vp_q8 = lane_chord_x_q8(seen, v[k].y_vp);
    }
    partner_vote(maps, rows, seen, dir, lo_q8, bin_q8, v, nrows);

    int32_t best_rows = 0;
    for (int k = 0; k < nrows; k++) {
        for (int peak = 0; peak < PARTNER_PEAKS; peak++) {
            /* the strongest three neighbouring bins left */
            int32_t top = -1, top_votes = 0;
            for (int32_t b = 1; b + 1 < PARTNER_BINS; b++) {
                const int32_t s = v[k].bin[b - 1] + v[k].bin[b] + v[k].bin[b + 1];
                if (s > top_votes) {
                    top_votes = s;
                    top = b;
                }
            }
            if (top < 0)
                break;
            v[k].bin[top - 1] = v[k].bin[top] = v[k].bin[top + 1] = 0;
            const int64_t xb = xs_bottom + dir * (lo_q8 + top * bin_q8 + bin_q8 / 2);
            /* the line through the vanishing point and that crossing */
            const lane_line chord = lane_line_of_chord(xb, v[k].x_vp_q8, v[k].y_vp, rows->y_bottom);
            const rte_lane lane =
                lane_of_line(&chord, seen->bow_q8, seen->y_horizon, rows->y_top, rows->y_bottom);
            const int32_t n = partner_rows(maps, rows, &lane, seen);
            if (n > best_rows) {
                best_rows = n;
                *found = lane;
            }
        }
    }
    return best_rows;
}

/* The share of the ROI in glare (permille) above which no side is
 * searched for from the other: glare makes kerbs and sunlit road paint. */
#define LANE_PARTNER_MAX_GLARE 50

/* Paint rows along a side's lane (line and curve), in the refit's band. */
static int32_t side_paint_rows(const lane_maps *maps, const lane_fit_hint *rows,
                               const lane_line *line, const lane_curve *curve)
{
    const rte_lane lane =
        lane_of_line(line, curve->bow_q8, curve->y_horizon, rows->y_top, rows->y_bottom);
    int64_t offset_q8;
    return rte_lane_find_marking(maps, rows, &lane, 1, &offset_q8);
}

/* In little glare, with one side (`have`) seen on paint along a quarter of
 * its rows at least, the other is searched for on the lanes of the same
 * road (rte_lane_partner) when it is
 *   - neither seen nor tracked: taken when it shows paint on a sixteenth
 *     of the lane's rows;
 *   - tracked and seen on paint along fewer than an eighth of its rows (a
 *     dashed side held on one dash, the prediction moved onto it) on a
 *     straight road: its line is replaced when the search finds paint on
 *     twice as many rows with its bottom end within two bands of it.
 * The side found takes the seen side's bend when that is more than an
 * eighth of the lane's rows (a smaller one is taken as none: a straight
 * road's lanes meet on one point). No refit on the edge pixels: its band
 * would take the seen marking's near their vanishing point. */
void rte_lane_fit_partner(rte_lane_context *ctx, const lane_maps *maps, const lane_fit_hint *rows,
                          int32_t glare_permille, int32_t w, bool seen[2], lane_line line[2],
                          lane_curve curve[2], int64_t support[2], bool fresh[2])
{
    if ((!seen[0] && !seen[1]) || ctx->params.fit != RTE_LANE_FIT_LEAST_SQUARES ||
        glare_permille > LANE_PARTNER_MAX_GLARE)
        return;
    const int64_t span = rows->y_bottom - rows->y_top;
    /* the side looked for: the unseen one, or the tracked one of less support */
    const int other = seen[0] != seen[1] ? (seen[0] ? 1 : 0) : support[0] <= support[1] ? 0 : 1;
    const int have = 1 - other;
    int32_t weak_paint = 0;
    if (seen[other]) {
        if (!ctx->track[other].valid ||
            (weak_paint = side_paint_rows(maps, rows, &line[other], &curve[other])) >= span / 8)
            return;
    } else if (ctx->track[other].valid) {
        return;
    }
    if (side_paint_rows(maps, rows, &line[have], &curve[have]) < span / 4)
        return;
    const int64_t bow = curve[have].bow_q8;
    const bool bent = rte_abs64(bow) > span * 256 / 8;
    if (seen[other] && bent)
        return;
    const rte_lane lane = lane_of_line(&line[have], bent ? bow : 0, curve[have].y_horizon,
                                       rows->y_top, rows->y_bottom);
    rte_lane found;
    const int32_t paint = rte_lane_partner(maps, rows, have, &lane, w, &found);
    if (paint < lane_min_rows(&lane) || paint < 2 * weak_paint)
        return;
    if (seen[other]) {
        const int64_t moved = lane_line_x_q8(&line[other], rows->y_bottom) - found.x_bottom_q8;
        if (rte_abs64(moved) > 2 * 256 * maps->tol)
            return;
    }
    if (bent)
        curve[other] = curve[have];
    line[other] =
        lane_line_of_chord(found.x_bottom_q8, found.x_top_q8, rows->y_top, rows->y_bottom);
    support[other] = paint;
    fresh[other] = !seen[other];
    seen[other] = true;
}
