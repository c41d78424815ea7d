/*
 * The rule of a rotor at rest (touchdown/run.h td_run_at_rest) and of the runs that may end there
 * (end_at_rest): what the summary's ending "at rest", the run's stop at rest and the case reader's
 * refusal of end_at_rest share, and the projective leap's check of its options against the model
 * (td_run_leap_check). Below lib/run and lib/case, which both apply them: they ask the model and
 * the options alone.
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

/* The last time the model prescribes a change of its motion (touchdown/run.h). The housing's kinks
 * (td_model_housing_next_kink: every pulse's start, peak and end, the history's first and last time)
 * are walked to their last: after it a shock is over, a history's acceleration is zero, a rotation's
 * rate is zero or (a ramp) held. */
double td_run_rest_after(const td_model *m)
{
    double t = -HUGE_VAL, kink;
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
    for (kink = td_model_housing_next_kink(m, -HUGE_VAL); kink < HUGE_VAL; kink = td_model_housing_next_kink(m, kink))
        t = fmax(t, kink);
    return t;
}

int td_run_rest_refused(const td_model *m, char *why, size_t size)
{
    double w = td_model_speed(m);
    td_speed_point last;
    int n;
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
    n = td_model_speed_point_count(m); /* a ramp holds its last point's speed after it */
    if (n > 0 && td_model_get_speed_point(m, n - 1, &last) == TD_OK && !td_run_at_rest(w, last.speed)) {
        snprintf(why, size,
                 "the speed_ramp ends at %g rad/s (at %g s) and holds that speed: the rotor never comes to rest "
                 "(end the ramp below %g rad/s)",
                 last.speed, last.time, fmax(REST_FRACTION * fabs(w), REST_SPEED));
        return 1;
    }
    return 0;
}

/* projective leap: the options' own values (td_output_options.leap_*), burst > 0 */
static td_leap_fault leap_values(const td_output_options *o, char *why, size_t size)
{
    if (!(isfinite(o->leap_burst) && o->leap_burst > 0.0)) {
        snprintf(why, size, "must be 0 (no leaps) or a finite time > 0 s (got %g)", o->leap_burst);
        return TD_LEAP_BURST;
    }
    if (o->leap_burst * o->sample_rate < 1.0) { /* the rates are read at grid samples: one interval at least */
        snprintf(why, size, "%g s is shorter than the sample interval 1 / output.sample_rate = %g s", o->leap_burst,
                 1.0 / o->sample_rate);
        return TD_LEAP_BURST;
    }
    if (!(isfinite(o->leap_factor) && o->leap_factor >= 1.0)) {
        snprintf(why, size, "must be >= 1 (got %g)", o->leap_factor);
        return TD_LEAP_FACTOR;
    }
    if (!(isfinite(o->leap_heal) && o->leap_heal >= 0.0)) {
        snprintf(why, size, "must be a finite time >= 0 s (got %g)", o->leap_heal);
        return TD_LEAP_HEAL;
    }
    if (!(isfinite(o->leap_start) && o->leap_start >= 0.0)) {
        snprintf(why, size, "must be a finite time >= 0 s (got %g)", o->leap_start);
        return TD_LEAP_START;
    }
    return TD_LEAP_FINE;
}

/* projective leap: the housing's motion that never ends (a ramp: its shock's acceleration or its
 * rotation's rate held for ever after the rise) named into why, else 0 */
static int perpetual_housing(const td_model *m, char *why, size_t size)
{
    td_housing_pulse p;
    int i;
    for (i = 0; i < td_model_housing_shock_count(m); i++)
        if (td_model_get_housing_shock(m, i, &p) == TD_OK && p.shape == TD_PULSE_RAMP)
            return snprintf(why, size, "housing.shocks[%d] (a ramp) holds its acceleration for ever", i), 1;
    for (i = 0; i < td_model_housing_rotation_count(m); i++)
        if (td_model_get_housing_rotation(m, i, &p) == TD_OK && p.shape == TD_PULSE_RAMP)
            return snprintf(why, size, "housing.rotation[%d] (a ramp) turns the housing for ever", i), 1;
    return 0;
}

td_leap_fault td_run_leap_check(const td_model *m, const td_output_options *o, double t_end, char *why, size_t size)
{
    td_spin sp;
    td_leap_fault f;
    double last;
    char what[96];
    if (o->leap_burst == 0.0) /* no leaps asked for: the other options are not read */
        return TD_LEAP_FINE;
    if ((f = leap_values(o, why, size)) != TD_LEAP_FINE)
        return f;
    td_model_spin(m, &sp);
    if (!sp.free) {
        snprintf(why, size, "a leap needs the speed as a free state (spin.free = true)");
        return TD_LEAP_MODEL;
    }
    if (td_model_retainer_count(m) > TD_LEAP_MAX_RETAINERS) {
        snprintf(why, size, "a leap handles at most %d retainers (the model has %d)", TD_LEAP_MAX_RETAINERS,
                 td_model_retainer_count(m));
        return TD_LEAP_MODEL;
    }
    /* the simulation's clock, on which every prescribed change runs, does not move in a leap */
    if (perpetual_housing(m, what, sizeof what)) {
        snprintf(why, size, "%s: the housing's motion never ends, and a leap does not move the clock it runs on", what);
        return TD_LEAP_MODEL;
    }
    last = td_run_rest_after(m);
    if (last > o->leap_start) {
        snprintf(why, size,
                 "%g s is before the last prescribed change, at %g s (a schedule entry, a speed_ramp point, the end "
                 "of a housing shock, rotation or history): a leap would move it",
                 o->leap_start, last);
        return TD_LEAP_START;
    }
    /* the run's end, on the run's clock as the start is: an end_at_rest run's end_time is its cap,
     * and a leap may begin only before it (one at or after it never happens) */
    if (!(o->leap_start < t_end)) {
        snprintf(why, size,
                 "%g s is not before end_time = %g s: the run ends before a leap may begin (leap.burst = 0 runs "
                 "without leaps)",
                 o->leap_start, t_end);
        return TD_LEAP_START;
    }
    return TD_LEAP_FINE;
}
