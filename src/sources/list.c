/* `rtedged --list-cameras`: every camera rtedge can open. */
#include "rtedge/libcamera_source.h"
#include "rtedge/v4l2_source.h"

int rte_list_cameras(FILE *out)
{
    int n = rte_v4l2_list(out, NULL);
    n += rte_libcamera_list(out); /* 0 without libcamera */
    return n;
}
