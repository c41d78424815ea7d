/*
 * The AMB axis law of docs/reference-rig.md ("AMBs" row), one lateral axis at a time:
 *   F = ks x + Fc,   tau dFc/dt = -Fc - ki (kp xs + kd dxs/dt),   F clipped to +-capacity (saturation).
 * The paper linearises the bearing ("linearised magnetic bearing characteristics", with eq. 1);
 * the lag and the clipping are this project's reconstruction.
 */
#include "model/system_internal.h"

double td_amb_axis_command(const td_amb_axis *a, double xs, double vs)
{
    return -a->ki * (a->kp * xs + a->kd * vs);
}

double td_amb_axis_filter_rate(const td_amb_axis *a, double xs, double vs, double fc)
{
    return (td_amb_axis_command(a, xs, vs) - fc) / a->tau;
}

double td_amb_axis_force(const td_amb_axis *a, int enabled, double x, double fc, double *dfdx, double *dfdfc)
{
    double f, dx = a->ks, dfc = 1.0;
    if (!enabled) {
        f = dx = dfc = 0.0; /* a failed AMB exerts nothing */
    } else {
        f = a->ks * x + fc;
        if (a->saturation && (f > a->capacity || f < -a->capacity)) {
            /* clipped: the force no longer depends on x or Fc */
            f = f > 0.0 ? a->capacity : -a->capacity;
            dx = dfc = 0.0;
        }
    }
    if (dfdx)
        *dfdx = dx;
    if (dfdfc)
        *dfdfc = dfc;
    return f;
}
