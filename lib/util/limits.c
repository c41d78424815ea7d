/* The run-work bounds (touchdown/limits.h). The products are formed in double and compared
 * with the bound, so an overflow to infinity is caught as "too many" as well. */
#include "util/limits.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdio.h>

td_run_limit td_run_limit_check(double duration, double speed, double sample_rate, double max_step, char *why, size_t n)
{
    double samples = sample_rate * duration;
    double steps = max_step > 0.0 ? duration / max_step : 0.0;
    double revolutions = fabs(speed) * duration / (2.0 * TD_PI);
    if (!(samples <= TD_MAX_SAMPLES)) {
        snprintf(why, n, "%g Hz over %g s makes %.3g output samples (at most %.0e)", sample_rate, duration, samples,
                 TD_MAX_SAMPLES);
        return TD_LIMIT_SAMPLES;
    }
    if (!(steps <= TD_MAX_STEPS)) {
        snprintf(why, n, "max_step %g s over %g s forces %.3g solver steps (at most %.0e)", max_step, duration, steps,
                 TD_MAX_STEPS);
        return TD_LIMIT_STEPS;
    }
    if (!(revolutions <= TD_MAX_REVOLUTIONS)) {
        snprintf(why, n, "%g rad/s over %g s makes %.3g shaft revolutions (at most %.0e)", speed, duration, revolutions,
                 TD_MAX_REVOLUTIONS);
        return TD_LIMIT_REVOLUTIONS;
    }
    return TD_LIMIT_NONE;
}

int td_run_window_check(double window, double sample_rate, char *why, size_t n)
{
    double periods = window * sample_rate, whole = floor(periods + 0.5);
    if (!(window > 0.0))
        return 0;
    if (periods < 1.0 - 1e-9) {
        snprintf(why, n, "%g s is shorter than the sample interval 1 / sample_rate = %g s", window, 1.0 / sample_rate);
        return 1;
    }
    /* grid times are t0 + k / rate in floating point: a relative 1e-9 is a whole number */
    if (fabs(periods - whole) > 1e-9 * whole) {
        snprintf(why, n,
                 "%g s is not a whole number of sample intervals 1 / sample_rate = %g s (%.6g of them): a window "
                 "closes at a grid sample; write %g or %g",
                 window, 1.0 / sample_rate, periods, floor(periods) / sample_rate, ceil(periods) / sample_rate);
        return 1;
    }
    return 0;
}
