/* Canny configuration: the floating-point thresholds become the integer
 * comparison values the per-frame code uses. Configuration time only; this
 * file may use floating point. */
#include <math.h>

#include "rtedge/canny.h"

/* OpenCV's cvFloor as the x86-64 build of 4.6 computes it: truncate (an
 * out-of-range value truncates to INT32_MIN, as cvttsd2si does), then
 * subtract one when the truncation rounded up, wrapping at INT32_MIN. So a
 * threshold >= 2^31 becomes INT32_MIN and one below -2^31 becomes INT32_MAX. */
static int32_t opencv_floor(double v)
{
    int32_t i = (v >= -2147483648.0 && v < 2147483648.0) ? (int32_t)v : INT32_MIN;
    if ((double)i > v)
        i = (i == INT32_MIN) ? INT32_MAX : i - 1;
    return i;
}

rte_status rte_canny_params_init(rte_canny_params *params, double low_threshold,
                                 double high_threshold, int32_t aperture, bool l2_gradient)
{
    if (!params || (aperture != 3 && aperture != 5 && aperture != 7) || isnan(low_threshold) ||
        isnan(high_threshold))
        return RTE_ERR_ARGUMENT;
    if (aperture == 7) { /* the gradient is scaled by 1/16 too */
        low_threshold /= 16.0;
        high_threshold /= 16.0;
    }
    if (low_threshold > high_threshold) {
        double t = low_threshold;
        low_threshold = high_threshold;
        high_threshold = t;
    }
    if (l2_gradient) {
        /* The magnitude is dx*dx + dy*dy: compare with squared thresholds. */
        low_threshold = fmin(32767.0, low_threshold);
        high_threshold = fmin(32767.0, high_threshold);
        if (low_threshold > 0)
            low_threshold *= low_threshold;
        if (high_threshold > 0)
            high_threshold *= high_threshold;
    }
    params->aperture = aperture;
    params->l2_gradient = l2_gradient;
    params->low = opencv_floor(low_threshold);
    params->high = opencv_floor(high_threshold);
    return RTE_OK;
}
