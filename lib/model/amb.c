/*
 * The AMB axis law of docs/reference-rig.md ("AMBs" row), one lateral axis at a time:
 *   F = ks x + Fc,   tau dFc/dt = -Fc - ki (kp xs + kd dxs/dt + kint e),   de/dt = xs,
 *   F clipped to +-capacity (saturation).
 * The paper linearises the bearing ("linearised magnetic bearing characteristics", with eq. 1) and
 * controls it PD; the lag, the clipping and the integral action (PID, docs/theory.md "AMB control")
 * are this project's additions.
 */
#include "model/system_internal.h"

double td_amb_axis_command(const td_amb_axis *a, double xs, double vs, double e)
{
    double u = a->kp * xs + a->kd * vs;
    if (a->kint != 0.0) /* a PD axis adds nothing, not even a signed zero */
        u += a->kint * e;
    return -a->ki * u;
}

double td_amb_axis_current_command(const td_amb_axis *a, double current)
{
    return a->ki * current;
}

double td_amb_axis_lag_rate(const td_amb_axis *a, double command, double fc)
{
    return (command - fc) / a->tau;
}

double td_amb_axis_filter_rate(const td_amb_axis *a, double xs, double vs, double e, double fc)
{
    return td_amb_axis_lag_rate(a, td_amb_axis_command(a, xs, vs, e), fc);
}

double td_amb_axis_integral_rate(const td_amb_axis *a, int running, double xs, double f)
{
    /* the integrator's share of the command is -ki kint e: integrating xs moves the force by
     * -ki kint xs per second, deeper into a clip at +capacity when xs < 0, at -capacity when xs > 0 */
    if (!running)
        return 0.0;
    if (a->saturation && ((f >= a->capacity && xs < 0.0) || (f <= -a->capacity && xs > 0.0)))
        return 0.0;
    return xs;
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
