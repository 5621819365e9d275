/* rtedge compare: the edge operators of the tutorial side by side (its
 * Exercise 1), each cell exactly what the single command writes:
 *   sobel: rtedge sobel --magnitude --ksize 3 | 5 | 7
 *   log:   rtedge log --blur 0 --sigma 0.5 | 1 | 2
 *   canny: rtedge canny --low 20 --high 60 | 50/150 | 100/200
 * The grid is written as a colour image with a caption above each cell,
 * and its layout printed as JSON (where each cell lies), so a reader or a
 * test can cut the cells out again. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_canny.h"
#include "cli_derivative.h"
#include "cli_filter.h"
#include "cli_image.h"
#include "commands.h"
#include "rtedge/draw.h"

#define COMPARE_ROWS 3
#define COMPARE_COLS 3
#define COMPARE_GAP 4 /* pixels between two cells of a row */

typedef struct compare_cell {
    char caption[32];
    derivative_options deriv;
    canny_options canny;
    filter_spec spec;
} compare_cell;

static const char *const row_names[COMPARE_ROWS] = {"sobel", "log", "canny"};

/* Cell col of row `row` (an index into row_names), prepared. */
static int cell_init(const char *name, int row, int col, compare_cell *c)
{
    static const int sobel_ksize[COMPARE_COLS] = {3, 5, 7};
    static const double log_sigma[COMPARE_COLS] = {0.5, 1, 2};
    static const double canny_low[COMPARE_COLS] = {20, 50, 100},
                        canny_high[COMPARE_COLS] = {60, 150, 200};
    memset(c, 0, sizeof *c);
    if (row == 0) {
        c->deriv = (derivative_options){
            .kind = DERIV_SOBEL, .dx = 1, .ksize = sobel_ksize[col], .magnitude = true};
        snprintf(c->caption, sizeof c->caption, "SOBEL MAGNITUDE K=%d", sobel_ksize[col]);
    } else if (row == 1) {
        c->deriv = (derivative_options){.kind = DERIV_LAPLACIAN,
                                        .ksize = 1,
                                        .blur_first = true,
                                        .blur = {.sigma = log_sigma[col], .ksize_y = -1}};
        snprintf(c->caption, sizeof c->caption, "LOG SIGMA=%g", log_sigma[col]);
    } else {
        c->canny = cli_canny_defaults();
        c->canny.low = canny_low[col];
        c->canny.high = canny_high[col];
        snprintf(c->caption, sizeof c->caption, "CANNY %g/%g", canny_low[col], canny_high[col]);
    }
    if (row < 2)
        c->spec = (filter_spec){.ctx = &c->deriv,
                                .prepare = cli_derivative_prepare,
                                .scratch = cli_derivative_scratch,
                                .apply = cli_derivative_apply,
                                .int16 = true};
    else
        c->spec = (filter_spec){.ctx = &c->canny,
                                .prepare = cli_canny_prepare,
                                .scratch = cli_canny_scratch,
                                .apply = cli_canny_apply};
    return c->spec.prepare(name, c->spec.ctx);
}

/* The rows named in `list` ("sobel,log,canny" or any of them, in any
 * order) as indices into rows[]; how many, or -1 after a message. */
static int parse_rows(const char *name, const char *list, int rows[COMPARE_ROWS])
{
    int n = 0;
    for (const char *p = list;; p++) {
        const size_t len = strcspn(p, ",");
        int row = -1;
        for (int i = 0; i < COMPARE_ROWS; i++)
            if (strlen(row_names[i]) == len && strncmp(p, row_names[i], len) == 0)
                row = i;
        if (row < 0 || n == COMPARE_ROWS) {
            cli_error(name, "--rows: '%.*s' is not one of sobel, log, canny (at most 3 rows)",
                      (int)len, p);
            return -1;
        }
        rows[n++] = row;
        p += len;
        if (!*p)
            return n;
    }
}

/* Grey cell `cell` into the grid at (x, y), as grey BGR. */
static void blit_grey(rte_image_u8c3 *grid, int32_t x, int32_t y, const rte_image_u8 *cell)
{
    for (int32_t r = 0; r < cell->height; r++) {
        const uint8_t *src = rte_u8_row(cell, r);
        uint8_t *dst = grid->buf + (size_t)(y + r) * (size_t)grid->stride + (size_t)x * 3;
        for (int32_t c = 0; c < cell->width; c++)
            dst[3 * c] = dst[3 * c + 1] = dst[3 * c + 2] = src[c];
    }
}

int cmd_compare(const cli_entry *self, int argc, char **argv)
{
    const char *rows_list = "sobel,log,canny";
    cli_option options[] = {{"rows", CLI_STRING, &rows_list, 0, 0, NULL,
                             "the rows, in order: any of sobel, log, canny, comma-separated", NULL},
                            {0}};
    cli_command cmd = {
        self->name,
        "IN OUT",
        self->summary,
        "IN: PGM/PPM, PNG or JPEG (as grey, like the single commands). OUT: .png or .ppm,\n"
        "a grid of three cells per row, each with its caption above it:\n"
        "  sobel  = rtedge sobel IN OUT.png --magnitude --ksize 3 | 5 | 7\n"
        "  log    = rtedge log IN OUT.png --blur 0 --sigma 0.5 | 1 | 2\n"
        "  canny  = rtedge canny IN OUT.png --low 20 --high 60 | 50/150 | 100/200\n"
        "Prints the layout as JSON: {\"cells\": [{\"row\", \"caption\", \"x\", \"y\",\n"
        "\"width\", \"height\"}, ...]}, each cell's top-left corner in OUT.",
        options,
        2};
    const char *paths[2];
    int rc = cli_parse(&cmd, argc, argv, paths);
    if (rc != CLI_EXIT_OK)
        return rc < 0 ? CLI_EXIT_OK : rc;
    int rows[COMPARE_ROWS];
    const int n_rows = parse_rows(self->name, rows_list, rows);
    if (n_rows < 0)
        return CLI_EXIT_USAGE;
    static compare_cell cells[COMPARE_ROWS][COMPARE_COLS];
    for (int r = 0; r < n_rows; r++)
        for (int c = 0; c < COMPARE_COLS; c++)
            if ((rc = cell_init(self->name, rows[r], c, &cells[r][c])) != CLI_EXIT_OK)
                return rc;

    cli_image in;
    if ((rc = cli_load(self->name, paths[0], &in)) != CLI_EXIT_OK)
        return rc;
    const int32_t w = in.gray.width, h = in.gray.height;
    const int32_t scale = w / 320 > 1 ? w / 320 : 1, caption_h = RTE_DRAW_CELL_H * scale + 4;
    const int64_t grid_w = (int64_t)COMPARE_COLS * w + (COMPARE_COLS - 1) * COMPARE_GAP;
    const int64_t grid_h = (int64_t)n_rows * (caption_h + h);
    rte_image_u8 out;
    rte_image_s16 d;
    void *out_memory = cli_new_u8(self->name, w, h, &out);
    void *d_memory = cli_new_s16(self->name, w, h, &d);
    uint8_t *grid_memory =
        grid_w * grid_h <= INT32_MAX / 3 ? calloc((size_t)(grid_w * grid_h), 3) : NULL;
    rte_status st = out_memory && d_memory && grid_memory ? RTE_OK : RTE_ERR_NO_MEMORY;
    rte_image_u8c3 grid = {(int32_t)grid_w, (int32_t)grid_h, (int32_t)grid_w * 3, grid_memory};
    const rte_draw_color white = {255, 255, 255};
    if (st == RTE_OK)
        printf("{\"cells\":[");
    for (int r = 0; r < n_rows && st == RTE_OK; r++) {
        for (int c = 0; c < COMPARE_COLS && st == RTE_OK; c++) {
            const int32_t x = c * (w + COMPARE_GAP), y = r * (caption_h + h) + caption_h;
            st = cli_filter_apply(self->name, &cells[r][c].spec, &in.gray, &out, &d, true);
            if (st != RTE_OK)
                break;
            blit_grey(&grid, x, y, &out);
            rte_draw_text(&grid, x + 2, y - caption_h + 2, cells[r][c].caption, white, scale);
            printf("%s{\"row\":\"%s\",\"caption\":\"%s\",\"x\":%d,\"y\":%d,\"width\":%d,"
                   "\"height\":%d}",
                   r + c > 0 ? "," : "", row_names[rows[r]], cells[r][c].caption, x, y, w, h);
        }
    }
    if (st != RTE_OK) {
        cli_error(self->name, "%s", rte_status_message(st));
        rc = CLI_EXIT_FAILURE;
    } else {
        printf("]}\n");
        rc = cli_save_bgr(self->name, paths[1], &grid);
    }
    cli_image_free(&in);
    free(out_memory);
    free(d_memory);
    free(grid_memory);
    return rc;
}
