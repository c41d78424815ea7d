/* The machine's smallest gap and the bound it sets on solver.atol (TD_MAX_ATOL_FRACTION of
 * touchdown/limits.h), and C_min, the smallest retainer clearance (td_model_min_retainer_clearance,
 * one definition for the run's zones and the modal report's). A question about the model, so it
 * lives with the model: util/ stays below every part of the library. */
#include "model/gap.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdio.h>

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

double td_model_min_retainer_clearance(const td_model *m)
{
    double c = TD_UNDEFINED;
    int i;
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        if (td_model_get_retainer(m, i, &r) == TD_OK && (td_is_undefined(c) || r.clearance < c))
            c = r.clearance;
    }
    return c;
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
