/* `rtedged --list-cameras`: every camera rtedge can open. */
#include "sources/v4l2_source.h"

#ifdef RTE_HAVE_LIBCAMERA
#include "sources/libcamera_source.h"
#endif

int rte_list_cameras(FILE *out)
{
    int n = rte_v4l2_list(out, NULL);
#ifdef RTE_HAVE_LIBCAMERA
    n += rte_libcamera_list(out);
#endif
    return n;
}
