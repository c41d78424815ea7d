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

double td_model_smallest_gap(const td_model *m, int *retainer, int *amb)
{
    double gap = INFINITY;
    int i, r = -1, a = -1;
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer ret;
        if (td_model_get_retainer(m, i, &ret) == TD_OK && ret.clearance < gap) {
            gap = ret.clearance;
            r = i;
        }
    }
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb b;
        if (td_model_get_amb(m, i, &b) == TD_OK && b.air_gap > 0.0 && b.air_gap < gap) {
            gap = b.air_gap;
            a = i;
            r = -1;
        }
    }
    if (retainer)
        *retainer = r;
    if (amb)
        *amb = a;
    return gap;
}

td_run_limit td_atol_limit_check(const td_model *m, double atol, char *why, size_t n)
{
    int r, a;
    double gap = td_model_smallest_gap(m, &r, &a);
    if (!(atol > TD_MAX_ATOL_FRACTION * gap))
        return TD_LIMIT_NONE;
    snprintf(why, n,
             "the displacement tolerance %g m must be at most %.0e of the smallest gap, the %s %g m of %s %d "
             "(at most %g m): the contacts would not be resolved",
             atol, TD_MAX_ATOL_FRACTION, r >= 0 ? "clearance" : "air gap", gap, r >= 0 ? "retainer" : "AMB",
             r >= 0 ? r : a, TD_MAX_ATOL_FRACTION * gap);
    return TD_LIMIT_ATOL;
}
