/* Argument checks shared by kernels that take images of several kinds
 * (internal to librtedge; the public single-image checks are in
 * rtedge/image.h). */
#ifndef RTEDGE_CORE_IMAGE_CHECKS_H
#define RTEDGE_CORE_IMAGE_CHECKS_H

#include <stdint.h>

#include "rtedge/image.h"
#include "rtedge/status.h"

/* A pair of derivative images (dx, dy, as Canny and the circle transform
 * take them): both valid and width x height. */
rte_status rte_image_s16_check_gradient(const rte_image_s16 *dx, const rte_image_s16 *dy,
                                        int32_t width, int32_t height);

#endif
