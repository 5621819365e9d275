/* Standard Hough lines (cv::HoughLines semantics), integer only.
 *
 * Voting runs angle by angle over a packed list of edge points: one
 * accumulator row (a few KB) stays in L1 while the points stream past, and
 * the bin of every point is one multiply-add and a shift. */
#include "rtedge/hough.h"

#include "hough_internal.h"

static size_t accum_cells(const rte_hough_config *cfg)
{
    return (size_t)(cfg->num_angles + 2) *
           (size_t)(rte_hough_rho_bins(cfg, cfg->max_width, cfg->max_height) + 2);
}

size_t rte_hough_lines_scratch_size(const rte_hough_config *cfg, int32_t max_lines)
{
    if (!cfg || max_lines < 0)
        return 0;
    size_t pixels = (size_t)cfg->max_width * (size_t)cfg->max_height;
    return 2 * rte_arena_piece_size(pixels * sizeof(int16_t)) +
           rte_arena_piece_size(accum_cells(cfg) * sizeof(int32_t)) +
           rte_arena_piece_size((size_t)max_lines * sizeof(uint64_t));
}

int64_t rte_hough_line_rho_q16(const rte_hough_config *cfg, const rte_hough_line *line)
{
    return (int64_t)line->rho_bin * cfg->rho_q16;
}

int64_t rte_hough_line_theta_q16(const rte_hough_config *cfg, const rte_hough_line *line)
{
    return (int64_t)cfg->theta0_q16 + (int64_t)line->theta_bin * cfg->theta_q16;
}

rte_status rte_hough_lines(const rte_hough_config *cfg, const rte_image_u8 *edges,
                           int32_t threshold, rte_arena *arena, rte_hough_line *lines,
                           int32_t max_lines, int32_t *count, bool *truncated)
{
    if (!arena || !count || !truncated || threshold < 0 || max_lines < 0 ||
        (max_lines > 0 && !lines))
        return RTE_ERR_ARGUMENT;
    rte_status st = rte_hough_begin(cfg, edges, count, truncated);
    if (st != RTE_OK)
        return st;
    const int32_t w = edges->width, h = edges->height;

    const int32_t numrho = rte_hough_rho_bins(cfg, w, h), numangle = cfg->num_angles;
    const int32_t astep = numrho + 2;
    const size_t pixels = (size_t)w * (size_t)h;
    const size_t mark = rte_arena_mark(arena);
    int16_t *xs = rte_arena_alloc(arena, pixels * sizeof(int16_t));
    int16_t *ys = rte_arena_alloc(arena, pixels * sizeof(int16_t));
    int32_t *acc = rte_arena_alloc(arena, (size_t)(numangle + 2) * astep * sizeof(int32_t));
    uint64_t *keys = rte_arena_alloc(arena, (size_t)max_lines * sizeof(uint64_t) + 8);
    if (!xs || !ys || !acc || !keys) {
        rte_arena_reset(arena, mark);
        return RTE_ERR_NO_MEMORY;
    }

    int32_t npts = 0;
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *row = rte_u8_row(edges, y);
        for (int32_t x = 0; x < w; x++) {
            xs[npts] = (int16_t)x;
            ys[npts] = (int16_t)y;
            npts += row[x] != 0; /* branch-free compaction */
        }
    }

    for (size_t i = 0; i < (size_t)(numangle + 2) * astep; i++)
        acc[i] = 0;
    const int32_t shift = cfg->trig_shift;
    const int32_t bias = rte_hough_rho_bias(cfg, numrho);
    for (int32_t n = 0; n < numangle; n++) {
        int32_t *restrict arow = acc + (size_t)(n + 1) * astep + 1;
        const int32_t c = cfg->rho_cos[n], s = cfg->rho_sin[n];
        for (int32_t i = 0; i < npts; i++)
            arow[(xs[i] * c + ys[i] * s + bias) >> shift]++;
    }

    rte_hough_topk top = {keys, max_lines, 0, 0};
    for (int32_t n = 0; n < numangle; n++) {
        const int32_t *a = acc + (size_t)(n + 1) * astep + 1;
        for (int32_t r = 0; r < numrho; r++) {
            int32_t v = a[r];
            if (v > threshold && v > a[r - 1] && v >= a[r + 1] && v > a[r - astep] &&
                v >= a[r + astep])
                rte_hough_topk_push(&top, rte_hough_key(v, (uint32_t)(n * numrho + r)));
        }
    }
    rte_hough_topk_sort(&top);
    for (int32_t i = 0; i < top.size; i++) {
        uint32_t idx = rte_hough_key_index(top.keys[i]);
        lines[i].theta_bin = (int32_t)(idx / (uint32_t)numrho);
        lines[i].rho_bin = (int32_t)(idx % (uint32_t)numrho) - (numrho - 1) / 2;
        lines[i].votes = rte_hough_key_votes(top.keys[i]);
    }
    *count = top.size;
    *truncated = top.seen > top.size;
    rte_arena_reset(arena, mark);
    return RTE_OK;
}
