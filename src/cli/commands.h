/* The table of rtedge subcommands and the functions behind them. */
#ifndef RTEDGE_CLI_COMMANDS_H
#define RTEDGE_CLI_COMMANDS_H

typedef struct cli_entry cli_entry;
struct cli_entry {
    const char *name;
    const char *summary;
    int (*run)(const cli_entry *self, int argc, char **argv);
};

/* Terminated by an entry with name == NULL. */
extern const cli_entry cli_commands[];

/* cmd_filters.c, cmd_derivatives.c: the image kernels of librtedge;
 * cmd_compare.c: the edge operators side by side. */
int cmd_gray(const cli_entry *self, int argc, char **argv);
int cmd_blur(const cli_entry *self, int argc, char **argv);
int cmd_median(const cli_entry *self, int argc, char **argv);
int cmd_sobel(const cli_entry *self, int argc, char **argv);
int cmd_scharr(const cli_entry *self, int argc, char **argv);
int cmd_laplacian(const cli_entry *self, int argc, char **argv);
int cmd_log(const cli_entry *self, int argc, char **argv);
int cmd_canny(const cli_entry *self, int argc, char **argv);
int cmd_compare(const cli_entry *self, int argc, char **argv);
int cmd_threshold(const cli_entry *self, int argc, char **argv);
int cmd_morphology(const cli_entry *self, int argc, char **argv);
int cmd_mask(const cli_entry *self, int argc, char **argv);

/* cmd_contours.c, cmd_grasp.c: contours, shape features, the grasp path. */
int cmd_contours(const cli_entry *self, int argc, char **argv);
int cmd_shapes(const cli_entry *self, int argc, char **argv);
int cmd_grasp(const cli_entry *self, int argc, char **argv);

/* cmd_hough.c: Hough lines, segments and circles. */
int cmd_lines(const cli_entry *self, int argc, char **argv);
int cmd_segments(const cli_entry *self, int argc, char **argv);
int cmd_circles(const cli_entry *self, int argc, char **argv);
/* cmd_lanes.c: the lane pipeline. */
int cmd_lanes(const cli_entry *self, int argc, char **argv);

#endif
