/*
 * The rule of a rotor at rest (touchdown/run.h td_run_at_rest) and of the runs that may end there
 * (end_at_rest): what the summary's ending "at rest", the run's stop at rest and the case reader's
 * refusal of end_at_rest share. Below lib/run and lib/case, which both apply it: it asks the model
 * alone.
 */
#include "touchdown/run.h"

#include <math.h>
#include <stdio.h>

/* long runs: the rest rule's speeds, rad/s: a rotor below either is at rest */
#define REST_FRACTION 0.01 /* of the start speed */
#define REST_SPEED 1.0

int td_run_at_rest(double speed0, double speed)
{
    return fabs(speed) < REST_FRACTION * fabs(speed0) || fabs(speed) < REST_SPEED;
}

double td_run_rest_after(const td_model *m)
{
    double t = -HUGE_VAL;
    int i;
    for (i = 0; i < td_model_change_count(m); i++) {
        td_change c;
        if (td_model_get_change(m, i, &c) == TD_OK && c.time > t)
            t = c.time;
    }
    for (i = 0; i < td_model_speed_point_count(m); i++) {
        td_speed_point p;
        if (td_model_get_speed_point(m, i, &p) == TD_OK && p.time > t)
            t = p.time;
    }
    return t;
}

int td_run_rest_refused(const td_model *m, char *why, size_t size)
{
    double w = td_model_speed(m);
    if (!(fabs(w) > REST_SPEED)) {
        snprintf(why, size,
                 "the start speed %g rad/s is already at rest (at most %g rad/s): the run would end at its first "
                 "sample",
                 w, REST_SPEED);
        return 1;
    }
    if (!td_model_speed_varies(m)) {
        snprintf(why, size,
                 "the speed is held at %g rad/s (neither a free spin nor a speed_ramp): the rotor never comes to rest",
                 w);
        return 1;
    }
    return 0;
}
