/* Configuration-time part of the Hough transforms: the fixed-point trig
 * tables (built with floating point, once) and the float conversion helpers.
 * The per-frame code in hough_lines.c / hough_segments.c only reads the
 * tables. */
#include <math.h>

#include "rtedge/hough.h"

static int32_t round_to_i32(double v) { return (int32_t)lround(v); }

rte_status rte_hough_config_init(rte_hough_config *cfg, int32_t max_width, int32_t max_height,
                                 double rho, double theta, double min_theta, double max_theta)
{
    if (!cfg || !(rho > 0.0) || !(theta > 0.0) || !(max_theta >= min_theta) || !isfinite(rho) ||
        !isfinite(theta) || !isfinite(min_theta) || !isfinite(max_theta) ||
        fabs(min_theta) > 64.0 || fabs(max_theta) > 64.0 || rho < 1.0 / 64 || rho > 65536.0)
        return RTE_ERR_ARGUMENT;
    if (max_width < 1 || max_height < 1 || max_width > RTE_MAX_SIDE || max_height > RTE_MAX_SIDE)
        return RTE_ERR_SIZE;
    double n = floor((max_theta - min_theta) / theta + 0.5);
    if (n < 1.0)
        n = 1.0;
    if (n > RTE_HOUGH_MAX_ANGLES)
        return RTE_ERR_ARGUMENT;

    cfg->max_width = max_width;
    cfg->max_height = max_height;
    cfg->num_angles = (int32_t)n;
    cfg->rho = rho;
    cfg->theta = theta;
    cfg->min_theta = min_theta;
    cfg->rho_q16 = round_to_i32(rho * 65536.0);
    cfg->inv_rho_q16 = round_to_i32(65536.0 / rho);
    cfg->theta0_q16 = round_to_i32(min_theta * 65536.0);
    cfg->theta_q16 = round_to_i32(theta * 65536.0);

    /* The most fraction bits for which x*cos + y*sin plus the rho offset
     * (about 2 * (w + h) / rho bins) stays below 2^31 for the largest map. */
    double span = 4.0 * ((double)max_width + max_height + 2) / rho;
    int32_t shift = 24;
    while (shift > 0 && span * ldexp(1.0, shift) >= 2147483648.0)
        shift--;
    cfg->trig_shift = shift;
    double scale = ldexp(1.0, shift) / rho;
    for (int32_t i = 0; i < RTE_HOUGH_MAX_ANGLES; i++) {
        double a = min_theta + i * theta;
        int in_range = i < cfg->num_angles;
        cfg->rho_cos[i] = in_range ? round_to_i32(cos(a) * scale) : 0;
        cfg->rho_sin[i] = in_range ? round_to_i32(sin(a) * scale) : 0;
        cfg->unit_cos[i] = in_range ? round_to_i32(cos(a) * 65536.0) : 0;
        cfg->unit_sin[i] = in_range ? round_to_i32(sin(a) * 65536.0) : 0;
    }
    return RTE_OK;
}

double rte_hough_line_rho(const rte_hough_config *cfg, const rte_hough_line *line)
{
    return line->rho_bin * cfg->rho;
}

double rte_hough_line_theta(const rte_hough_config *cfg, const rte_hough_line *line)
{
    return cfg->min_theta + line->theta_bin * cfg->theta;
}
