/* The run's grid clock (clock.h). */
#include "run/clock.h"

#include <float.h>
#include <math.h>

int td_run_reached(double t, double end)
{
    return t >= end - TD_RUN_REACHED_ULPS * DBL_EPSILON * fmax(fmax(fabs(t), fabs(end)), 1.0);
}
