/* Configuration-time conversion of OpenCV's double threshold arguments
 * (floating point allowed here; see threshold.h for the rules). */
#include <math.h>

#include "rtedge/threshold.h"

rte_status rte_threshold_params_init(rte_threshold_params *params, rte_threshold_type type,
                                     double thresh, double maxval, bool otsu)
{
    if (!params || (unsigned)type > RTE_THRESH_TOZERO_INV)
        return RTE_ERR_ARGUMENT;
    /* NaN fails both comparisons. */
    if (!(thresh >= INT32_MIN && thresh < 2147483648.0) ||
        !(maxval >= INT32_MIN && maxval < 2147483647.5))
        return RTE_ERR_ARGUMENT;
    params->type = type;
    params->thresh = (int32_t)floor(thresh);     /* cvFloor */
    params->maxval = (int32_t)nearbyint(maxval); /* cvRound: half to even in the default mode */
    params->otsu = otsu;
    return RTE_OK;
}
