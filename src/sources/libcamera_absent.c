/* The libcamera source's functions in a build without libcamera (meson's
 * `libcamera` feature off or not found): the API stays the same, and
 * opening a camera says why it cannot. */
#include <stdio.h>

#include "rtedge/libcamera_source.h"

rte_status rte_libcamera_source_open(rte_source *source, const rte_libcamera_config *config,
                                     rte_libcamera_info *info, char *msg, size_t msg_size)
{
    if (msg && msg_size)
        snprintf(msg, msg_size, "rtedge was built without libcamera");
    return RTE_ERR_UNSUPPORTED;
}

int rte_libcamera_list(FILE *out) { return 0; }
