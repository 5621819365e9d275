/* Integer helpers shared by the kernels and the overlays. Internal: not
 * an installed header. */
#ifndef RTEDGE_CORE_INT_MATH_H
#define RTEDGE_CORE_INT_MATH_H

#include <stdint.h>

static inline int64_t rte_abs64(int64_t v) { return v < 0 ? -v : v; }

/* num / den rounded to nearest, halves away from zero; any signs, den != 0. */
static inline int64_t rte_div_round64(int64_t num, int64_t den)
{
    if (den < 0) {
        num = -num;
        den = -den;
    }
    return num >= 0 ? (num + den / 2) / den : -((-num + den / 2) / den);
}

#endif
