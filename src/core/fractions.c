/* "x,y;x,y;..." polygons: see fractions.h. */
#include "core/fractions.h"

#include <math.h>
#include <stdlib.h>

int32_t rte_parse_fractions(const char *text, rte_vertex *out, int32_t max)
{
    int32_t n = 0;
    const char *s = text;
    while (*s) {
        char *end;
        double fx = strtod(s, &end);
        if (end == s || *end != ',' || n >= max)
            return -1;
        s = end + 1;
        double fy = strtod(s, &end);
        if (end == s || (*end && *end != ';') || !(fx >= -64 && fx <= 64 && fy >= -64 && fy <= 64))
            return -1;
        out[n].x = (int32_t)lround(fx * RTE_POLYGON_FRACTION_ONE);
        out[n].y = (int32_t)lround(fy * RTE_POLYGON_FRACTION_ONE);
        n++;
        s = *end ? end + 1 : end;
    }
    return n >= 3 ? n : -1;
}
