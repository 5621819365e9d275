/* Listing the V4L2 capture nodes: formats, frame sizes, frame intervals. */
#include "sources/v4l2_internal.h"

#include <fcntl.h>
#include <stdio.h>
#include <string.h>

static void print_interval(FILE *out, const struct v4l2_fract *t)
{
    if (t->numerator && t->denominator % t->numerator == 0)
        fprintf(out, " %u", t->denominator / t->numerator);
    else
        fprintf(out, " %u/%u", t->denominator, t->numerator);
}

static void list_intervals(v4l2_source *s, uint32_t fourcc, uint32_t w, uint32_t h, FILE *out)
{
    struct v4l2_frmivalenum iv;
    memset(&iv, 0, sizeof(iv));
    iv.pixel_format = fourcc;
    iv.width = w;
    iv.height = h;
    bool any = false;
    for (; rte_v4l2_xioctl(s, VIDIOC_ENUM_FRAMEINTERVALS, &iv) == 0; iv.index++) {
        fprintf(out, "%s", any ? "," : " @");
        any = true;
        if (iv.type == V4L2_FRMIVAL_TYPE_DISCRETE) {
            print_interval(out, &iv.discrete);
        } else {
            print_interval(out, &iv.stepwise.max);
            fprintf(out, " ..");
            print_interval(out, &iv.stepwise.min);
            break;
        }
    }
    if (any)
        fprintf(out, " fps");
}

static void list_sizes(v4l2_source *s, uint32_t fourcc, FILE *out)
{
    struct v4l2_frmsizeenum fs;
    memset(&fs, 0, sizeof(fs));
    fs.pixel_format = fourcc;
    for (; rte_v4l2_xioctl(s, VIDIOC_ENUM_FRAMESIZES, &fs) == 0; fs.index++) {
        if (fs.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
            fprintf(out, "      %ux%u", fs.discrete.width, fs.discrete.height);
            list_intervals(s, fourcc, fs.discrete.width, fs.discrete.height, out);
            fprintf(out, "\n");
        } else {
            fprintf(out, "      %ux%u .. %ux%u (steps %ux%u)\n", fs.stepwise.min_width,
                    fs.stepwise.min_height, fs.stepwise.max_width, fs.stepwise.max_height,
                    fs.stepwise.step_width, fs.stepwise.step_height);
            break;
        }
    }
}

int rte_v4l2_list(FILE *out, const rte_v4l2_ops *ops)
{
    v4l2_source s;
    memset(&s, 0, sizeof(s));
    s.ops = ops ? ops : &rte_v4l2_system_ops;
    int found = 0;
    for (int i = 0; i < MAX_DEVICE_NODES; i++) {
        char path[RTE_V4L2_NAME_SIZE], name[5];
        struct v4l2_capability cap;
        snprintf(path, sizeof(path), "/dev/video%d", i);
        s.fd = s.ops->open(s.ops->ctx, path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
        if (s.fd < 0)
            continue;
        if (rte_v4l2_query_node(&s, &cap) == RTE_OK) {
            found++;
            fprintf(out, "v4l2 %s: %.32s (driver %.16s, bus %.32s)\n", path, (const char *)cap.card,
                    (const char *)cap.driver, (const char *)cap.bus_info);
            struct v4l2_fmtdesc fd;
            memset(&fd, 0, sizeof(fd));
            fd.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
            for (; rte_v4l2_xioctl(&s, VIDIOC_ENUM_FMT, &fd) == 0; fd.index++) {
                bool usable = rte_v4l2_delivered_format(fd.pixelformat, RTE_PIXEL_GREY) != 0;
                fprintf(out, "    %s (%.32s)%s\n", rte_v4l2_fourcc_name(fd.pixelformat, name),
                        (const char *)fd.description, usable ? "" : " [not read by rtedge]");
                list_sizes(&s, fd.pixelformat, out);
            }
        }
        rte_v4l2_close_fd(&s);
    }
    return found;
}
