/* Polygons given as text, "x,y;x,y;..." fractions of the frame's width and
 * height (the lane ROI, the grasp workspace): one parser for the daemon's
 * configuration and the rtedge tool's --roi. Configuration time only. */
#ifndef RTEDGE_CORE_FRACTIONS_H
#define RTEDGE_CORE_FRACTIONS_H

#include <stdint.h>

#include "rtedge/polygon_mask.h"

/* Parses text into Q16 vertices (rte_polygon_from_fractions' input), each
 * coordinate within -64..64 and rounded half away from zero. Returns the
 * number of vertices, or -1 for anything but 3..max well-formed ones. */
int32_t rte_parse_fractions(const char *text, rte_vertex *out, int32_t max);

#endif
