/* The lane fit refined on the edge pixels themselves, per frame (integer
 * only; see include/rtedge/lane.h and docs/lanes.md). */
#include <string.h>

#include "lane_fixed.h"

/* Half-width of the band of edge pixels around a fitted lane at row y:
 * `tol` on the bottom row, shrinking in perspective towards the horizon to
 * about a quarter of it on the ROI's top row (near the top the two lanes
 * are only tens of pixels apart), at least 5 px so both edges of a narrow
 * far marking stay in, and at most LANE_BAND_MAX. */
#define LANE_BAND_MAX 64
int64_t rte_lane_band_px(const lane_fit_hint *h, int64_t tol, int32_t y)
{
    const int64_t span = h->y_bottom - h->y_top, q = 3 * (span / 8 + 1);
    const int64_t b = span > 0 ? tol * (lane_rows_below_top(h, y) + q) / (span + q) : tol;
    return b < 5 ? 5 : b > LANE_BAND_MAX ? LANE_BAND_MAX : b;
}

/* Eight bytes, the first in the lowest bits whatever the byte order. */
static inline uint64_t load_le64(const uint8_t *p)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return v;
}

/* Adds column x to *px and, when there is one, to the list (at most cap
 * columns). */
static inline void band_add(band_pixels *px, int64_t x, int32_t *list, int64_t cap)
{
    if (list && px->n < cap)
        list[px->n] = (int32_t)x;
    px->n++;
    px->sum_x += x;
    px->first = x < px->first ? x : px->first;
    px->last = x > px->last ? x : px->last;
}

/* The edge pixels in columns xa..xb (inside the map) of row y of `edges`
 * that run along a line of slope_q16 (x per row): each needs an edge pixel
 * in the row above or below at one of the two columns the slope reaches
 * there, so edges crossing the line (shadows, patch borders, car bumpers)
 * do not count (LANE_SLOPE_ANY: every edge pixel counts). Eight pixels at
 * a time away from the map's borders. */
static inline band_pixels band_scan(const rte_image_u8 *edges, int32_t y, int64_t xa, int64_t xb,
                                    int64_t slope_q16, int32_t *list, int64_t cap)
{
    band_pixels px = {0, 0, INT64_MAX, INT64_MIN};
    const uint8_t *row = rte_u8_row(edges, y);
    const uint8_t *up = y > 0 ? row - edges->stride : NULL;
    const uint8_t *down = y < edges->height - 1 ? row + edges->stride : NULL;
    /* below: x + slope lies in [x + step, x + step + 1]; above: x - slope
     * in [x - back, x - back + 1] */
    const bool any = slope_q16 == LANE_SLOPE_ANY;
    const int64_t step = any ? 0 : slope_q16 >> 16;
    const int64_t back = any ? 0 : step + ((slope_q16 & 0xFFFF) != 0);
    const int64_t words_end = xa + ((xb - xa) / 8 + 1) * 8; /* the word loop reads up to here + 1 */
    if (up && down && xa - back >= 0 && xa + step >= 0 && words_end + 1 - back <= edges->width &&
        words_end + 1 + step <= edges->width && words_end <= edges->width) {
        const uint64_t low7 = 0x7F7F7F7F7F7F7F7Fu;
        for (int64_t x = xa; x <= xb; x += 8) {
            uint64_t h = load_le64(row + x);
            if (xb - x < 7)
                h &= ((uint64_t)1 << (8 * (xb - x + 1))) - 1; /* bytes past xb */
            if (!h)
                continue;
            const uint64_t m =
                any ? h
                    : h & (load_le64(up + x - back) | load_le64(up + x - back + 1) |
                           load_le64(down + x + step) | load_le64(down + x + step + 1));
            /* the top bit of each nonzero byte of m */
            for (uint64_t nz = (((m & low7) + low7) | m) & ~low7; nz; nz &= nz - 1)
                band_add(&px, x + (__builtin_ctzll(nz) >> 3), list, cap);
        }
        return px;
    }
    for (int64_t x = xa; x <= xb; x++) {
        if (!row[x])
            continue;
        bool along = any;
        for (int64_t k = 0; k <= 1 && !along; k++) {
            const int64_t xu = x - back + k, xd = x + step + k;
            along = (up && xu >= 0 && xu < edges->width && up[xu]) ||
                    (down && xd >= 0 && xd < edges->width && down[xd]);
        }
        if (along)
            band_add(&px, x, list, cap);
    }
    return px;
}

band_pixels rte_lane_band_row(const rte_image_u8 *edges, int32_t y, int64_t xa, int64_t xb,
                              int64_t slope_q16)
{
    return band_scan(edges, y, xa, xb, slope_q16, NULL, 0);
}

/* Paint between the outermost edges: its brightest pixel between them
 * brighter by LANE_RIDGE_MIN grey levels than both sides (two pixels
 * outside), so a car's flank, a shadow's border or a seam, with one bright
 * side only, is not taken for a marking. The brightest, not the middle:
 * the middle of a double line is the road between its two lines. Either
 * image may show it: the colour cue (a yellow line on light concrete) or
 * grey (where glare brightens the road
 * beside white paint until the cue takes it for paint too). A side
 * saturated in grey (glare) tells nothing and is left out; one side must
 * remain, so paint inside glare does not count. */
static bool ridge_in(const uint8_t *row, int64_t first, int64_t last, bool skip_a, bool skip_b)
{
    int32_t mid = row[(first + last) / 2];
    for (int64_t x = first + 1; x < last; x++)
        mid = row[x] > mid ? row[x] : mid;
    const int32_t a = row[first - 2], b = row[last + 2];
    return (skip_a || mid >= a + LANE_RIDGE_MIN) && (skip_b || mid >= b + LANE_RIDGE_MIN);
}

bool rte_lane_is_ridge(const lane_maps *maps, int32_t y, int64_t first, int64_t last)
{
    if (first < 2 || last + 2 > maps->src->width - 1)
        return false;
    const uint8_t *grey = rte_u8_row(maps->gray, y);
    const bool glare_a = grey[first - 2] >= LANE_SATURATED,
               glare_b = grey[last + 2] >= LANE_SATURATED;
    if (glare_a && glare_b)
        return false;
    return ridge_in(rte_u8_row(maps->src, y), first, last, glare_a, glare_b) ||
           (maps->src->buf != maps->gray->buf && ridge_in(grey, first, last, glare_a, glare_b));
}

/* The gap of a double line: edges at first and last (row y of the crop)
 * with road between them, each flanked by a line of paint (brighter than
 * the gap's darkest pixel by LANE_RIDGE_MIN) that ends within `reach` (an
 * edge pixel, and darker road beyond it). Near the camera a double centre line is wider
 * than the search band, which then holds only its two inner edges; their
 * middle is the marking's centre. */
static bool double_gap(const lane_maps *maps, int32_t y, int64_t first, int64_t last, int64_t reach)
{
    if (last - first < 2 || first - reach - 2 < 0 || last + reach + 2 > maps->src->width - 1)
        return false;
    const uint8_t *row = rte_u8_row(maps->src, y), *edge = rte_u8_row(maps->edges, y);
    int32_t gap = 255; /* the gap's darkest pixel (the edge pixels may lie on the paint) */
    for (int64_t x = first + 1; x < last; x++)
        gap = row[x] < gap ? row[x] : gap;
    const int32_t a = row[first - 2], b = row[last + 2];
    if (a < gap + LANE_RIDGE_MIN || b < gap + LANE_RIDGE_MIN)
        return false;
    int64_t l = first - 3, r = last + 3;
    while (l >= first - reach && !edge[l])
        l--;
    while (r <= last + reach && !edge[r])
        r++;
    return l >= first - reach && r <= last + reach && row[l - 2] + LANE_RIDGE_MIN <= a &&
           row[r + 2] + LANE_RIDGE_MIN <= b;
}

bool rte_lane_paint_row(const lane_maps *maps, int32_t y, int64_t xa, int64_t xb, int64_t slope_q16,
                        band_pixels *px)
{
    if (xa < 0 || xb > maps->edges->width - 1)
        return false;
    *px = rte_lane_band_row(maps->edges, y - maps->cy0, xa, xb, slope_q16);
    /* one edge alone would pull the row to it */
    return px->n >= 2 && px->last != px->first &&
           (rte_lane_is_ridge(maps, y - maps->cy0, px->first, px->last) ||
            double_gap(maps, y - maps->cy0, px->first, px->last, xb - xa));
}

/* The marking nearest column x (frame coordinates) of frame row y, its
 * middle within `reach` of x: the edge pixels along slope_q16 there,
 * grouped into edges (runs of pixels at most two apart); each two
 * neighbouring edges with paint between them (rte_lane_is_ridge) or a
 * double line's gap between them (double_gap), at most twice `reach`
 * apart, are a marking, and the one whose middle is nearest x wins (a
 * double line's gap before the lines beside it). *px gets its two edges'
 * pixels. Used where the marking has left the band the lane predicts (a
 * bend sharper near the horizon than the rows below it showed). */
#define LANE_NEAR_MAX 512
bool rte_lane_paint_near(const lane_maps *maps, int32_t y, int64_t x, int64_t reach,
                         int64_t slope_q16, band_pixels *px)
{
    const int32_t yc = y - maps->cy0, w = maps->edges->width;
    reach = reach < LANE_NEAR_MAX / 4 - 1 ? reach : LANE_NEAR_MAX / 4 - 1;
    /* a marking's middle within reach and its width within twice that */
    int64_t xa = x - maps->cx0 - 2 * reach, xb = x - maps->cx0 + 2 * reach;
    xa = xa < 2 ? 2 : xa;
    xb = xb > w - 3 ? w - 3 : xb;
    if (xb - xa < 2 || yc < 1 || yc > maps->edges->height - 2)
        return false;
    /* the edge pixels, then the edges: [start, end] column runs */
    int32_t cols[LANE_NEAR_MAX], start[LANE_NEAR_MAX], end[LANE_NEAR_MAX], n_edges = 0;
    const band_pixels all = band_scan(maps->edges, yc, xa, xb, slope_q16, cols, LANE_NEAR_MAX);
    for (int64_t i = 0; i < all.n && i < LANE_NEAR_MAX; i++) {
        if (n_edges > 0 && cols[i] - end[n_edges - 1] <= 2)
            end[n_edges - 1] = cols[i];
        else
            start[n_edges] = end[n_edges] = cols[i], n_edges++;
    }
    int64_t best = INT64_MAX, best_first = 0, best_last = 0;
    bool best_gap = false;
    for (int32_t i = 0; i + 1 < n_edges; i++) {
        const int64_t first = start[i], last = end[i + 1];
        const int64_t d = rte_abs64(first + last - 2 * (x - maps->cx0));
        if (last - first > 2 * reach || d > 2 * reach)
            continue;
        const bool gap = double_gap(maps, yc, end[i], start[i + 1], reach);
        if (!gap && !rte_lane_is_ridge(maps, yc, first, last))
            continue;
        if ((gap && !best_gap) || (gap == best_gap && d < best)) {
            best = d;
            best_gap = gap;
            best_first = first;
            best_last = last;
        }
    }
    if (best == INT64_MAX)
        return false;
    *px = rte_lane_band_row(maps->edges, yc, best_first, best_last, slope_q16);
    return px->n >= 2;
}

bool rte_lane_paint_along(const lane_maps *maps, const lane_fit_hint *hint, const rte_lane *lane,
                          int32_t band_scale, int32_t y, int64_t *lane_x_q8, band_pixels *px)
{
    const int64_t band = band_scale * rte_lane_band_px(hint, maps->tol, y);
    const int64_t lx = rte_lane_x_q8(lane, y), xa = ((lx + 128) >> 8) - band - maps->cx0;
    /* the curve's direction here, x per row downwards */
    const int64_t slope = ((int64_t)rte_lane_x_q8(lane, y + 1) - lx) * 256;
    *lane_x_q8 = lx;
    return rte_lane_paint_row(maps, y, xa, xa + 2 * band, slope, px);
}

/* Where the marking near a lane `pred` is: the mean offset from it of the
 * rows (within band_scale times the refit's band around it) that show a
 * marking, i.e. two edges with paint between them (rte_lane_is_ridge), in
 * *offset_q8. Returns those rows. */
int32_t rte_lane_find_marking(const lane_maps *maps, const lane_fit_hint *hint,
                              const rte_lane *pred, int32_t band_scale, int64_t *offset_q8)
{
    const int32_t cx0 = maps->cx0, cy0 = maps->cy0;
    int64_t sum_r = 0, n = 0;
    int32_t rows = 0;
    for (int32_t y = hint->y_bottom; y >= hint->y_top; y--) {
        if (y < cy0 || y > cy0 + maps->edges->height - 1)
            continue;
        int64_t lx;
        band_pixels px;
        if (!rte_lane_paint_along(maps, hint, pred, band_scale, y, &lx, &px))
            continue;
        sum_r += (px.sum_x + px.n * cx0) * 256 - px.n * lx;
        n += px.n;
        rows++;
    }
    *offset_q8 = n > 0 ? sum_r / n : 0;
    return rows;
}

/* The segment fit refined on the edge pixels themselves: the edge pixels
 * within band_px of the line that run along it (band_row; `edges` is the
 * crop at (cx0, cy0)) enter a weighted
 * least-squares fit of their horizontal residuals to the line (row weights
 * as for segments, the tracked slope as a prior). Up to three passes, each
 * in the band around the line of the one before, until the line's ends
 * move less than a quarter of a pixel (with two, 2 of the 136 photo runs
 * of tests/unit/test_lane.c over eight point orders of the Hough search
 * fail; with three or four, none). Short dashes and paint that the Hough
 * search left without a segment (or split differently) then count by
 * their pixels, so the lane does not depend on which segments the search
 * happened to find, and a marking's two edges put the line on its centre. */
void rte_lane_refine_on_edges(const rte_image_u8 *edges, int32_t cx0, int32_t cy0,
                              const lane_fit_hint *hint, int64_t tol, lane_line *line)
{
    const int32_t y0 = hint->y_top > cy0 ? hint->y_top : cy0;
    const int32_t y1 =
        hint->y_bottom < cy0 + edges->height - 1 ? hint->y_bottom : cy0 + edges->height - 1;
    const int64_t half_span = (hint->y_bottom - hint->y_top) / 2 + 1;
    for (int pass = 0; pass < 3; pass++) {
        /* Sums over the pixels of rw, rw Y, rw r, rw Y^2 and rw Y r, with
         * rw the row weight (<= 257, /256), Y = y - y_mid (|Y| <= 4096 px)
         * and r the residual to the line (|r| <= 65 px, in 1/256 px): at
         * most 8192 rows of 129 pixels keep every sum, and the products
         * with the mean below, under 2^63. */
        int64_t sw = 0, sy = 0, sr = 0, syy = 0, syr = 0;
        for (int32_t y = y0; y <= y1; y++) {
            const int64_t band = rte_lane_band_px(hint, tol, y);
            const int64_t lx = lane_line_x_q8(line, y), xa = ((lx + 128) >> 8) - band - cx0,
                          xb = xa + 2 * band;
            /* Only rows where the whole band is inside the crop: where
             * its border cuts a marking, the edge on the inside alone
             * would pull the line off the marking's centre. */
            if (xa < 0 || xb > edges->width - 1)
                continue;
            const band_pixels px = rte_lane_band_row(edges, y - cy0, xa, xb, line->slope_q16);
            /* Both edges of the marking, one either side of the line: a row
             * where one of them is missing (worn paint, a shadow's border on
             * it, the end of a dash) would pull the line to the other. */
            if (px.n == 0 || (px.first + cx0) * 256 >= lx || (px.last + cx0) * 256 <= lx)
                continue;
            const int64_t rw = lane_row_weight_q8(hint, y), Y = y - line->y_mid;
            const int64_t r = (px.sum_x + px.n * cx0) * 256 - px.n * lx; /* sum of the residuals */
            sw += rw * px.n;
            sy += rw * px.n * Y;
            sr += rw * r;
            syy += rw * px.n * Y * Y;
            syr += rw * Y * r;
        }
        if (sw < 256 * 8)
            return;                          /* hardly any paint near the line: keep it */
        const int64_t my_q8 = sy * 256 / sw; /* mean Y */
        const int64_t cyy = syy - ((my_q8 * sy) >> 8), cyr = syr - ((my_q8 * sr) >> 8);
        /* The tracked slope as a prior with the weight of a marking along a
         * fifth of the lane (both its edges: R^3 rw / 6 in these units). */
        const int64_t prior = hint->weight / 6;
        int64_t dslope_q16 = 0;
        if (prior > 0)
            dslope_q16 = lane_div_q16(cyr + (prior * (hint->slope_q16 - line->slope_q16) >> 8),
                                      (cyy + prior) * 256);
        else if (cyy >= sw * 64) /* rows spread over ~8 px at least */
            dslope_q16 = lane_div_q16(cyr, cyy * 256);
        const int64_t slope = line->slope_q16 + dslope_q16;
        if (rte_abs64(slope) > 64 * 65536)
            return;
        const int64_t dx_mid = sr / sw - ((dslope_q16 * my_q8) >> 16);
        line->x_mid_q8 += dx_mid;
        line->slope_q16 = slope;
        /* settled: both ends moved less than a quarter of a pixel */
        if (rte_abs64(dx_mid) + ((rte_abs64(dslope_q16) * half_span) >> 8) < 64)
            return;
    }
}
