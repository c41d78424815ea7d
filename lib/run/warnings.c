/*
 * The warnings of a run (touchdown/run.h td_run_summary.warnings): a result the library computed
 * as asked but that the case probably did not mean. Each rule is checked here and only here.
 */
#include "run/warnings.h"

#include <stdarg.h>
#include <stdio.h>

#include "touchdown/dofs.h"

/* One more warning. Past TD_RUN_MAX_WARNINGS the last slot becomes a notice of how many were left
 * out: the warning it held and each one after it. */
static void warn(td_run_summary *s, const char *fmt, ...)
{
    va_list ap;
    if (s->warning_count >= TD_RUN_MAX_WARNINGS) {
        s->warnings_left_out += s->warnings_left_out == 0 ? 2 : 1;
        snprintf(s->warnings[TD_RUN_MAX_WARNINGS - 1], TD_RUN_WARNING_SIZE,
                 "%d more warnings left out: a summary keeps %d and this notice", s->warnings_left_out,
                 TD_RUN_MAX_WARNINGS - 1);
        return;
    }
    va_start(ap, fmt);
    vsnprintf(s->warnings[s->warning_count++], TD_RUN_WARNING_SIZE, fmt, ap);
    va_end(ap);
}

/* An AMB whose force went past its capacity with saturation off: a real amplifier cannot give it.
 * A saturating AMB is clipped at its capacity (load <= 1), so a peak load above 1 is always that
 * of an AMB without saturation. */
static void check_amb_capacity(td_run_summary *s, const td_model *m)
{
    td_amb a;
    int k = s->stats.peak_amb;
    if (k < 0 || !(s->stats.peak_amb_load > 1.0) || td_model_get_amb(m, k, &a) != TD_OK || a.saturation)
        return;
    warn(s,
         "AMB %d reached %.4g N, %.4g %% of its force capacity %.6g N, at t = %.6g s with saturation off: a real "
         "amplifier clips at its capacity (ambs[%d].saturation = true models that)",
         k, s->stats.peak_amb_force, 100.0 * s->stats.peak_amb_load, a.force_capacity, s->stats.peak_amb_time, k);
}

/* Schedule entries at or after the end time never happen. */
static void check_schedule(td_run_summary *s, const td_model *m)
{
    int i, n = td_model_change_count(m);
    td_change c;
    for (i = 0; i < n; i++)
        if (td_model_get_change(m, i, &c) == TD_OK && c.time >= s->t_end)
            warn(s, "schedule[%d] at t = %.6g s is at or after the end time %.6g s: it never happens",
                 td_model_change_entry(m, i), c.time, s->t_end); /* the entry as written, not its rank in time */
}

/* A clearance larger than the shaft radius at its retainer is out of all proportion (touchdown
 * bearings leave a few tenths of a millimetre, about half the AMB air gap, round a shaft of tens
 * of millimetres; a clearance of the radius's size is a slip of units). An AMB air gap, when the
 * case states one, bounds every clearance already (td_model_validate). */
static void check_clearances(td_run_summary *s, const td_model *m)
{
    int i, n = td_model_retainer_count(m);
    td_retainer r;
    td_amb a;
    for (i = 0; i < td_model_amb_count(m); i++)
        if (td_model_get_amb(m, i, &a) == TD_OK && a.air_gap > 0.0)
            return;
    for (i = 0; i < n; i++)
        if (td_model_get_retainer(m, i, &r) == TD_OK && r.clearance > r.shaft_radius)
            warn(s,
                 "retainers[%d].clearance %.6g m is larger than the shaft radius there (%.6g m) and no AMB air gap "
                 "bounds it: a clearance in mm instead of m?",
                 i, r.clearance, r.shaft_radius);
}

/* A rotor past an AMB's air gap at its sensor would strike the AMB's stator: the model has no stator
 * contact (only the retainers'), so from there on the result is not physical. The peak is the one
 * while the AMB worked (td_sim_sensor_peak_displacement); an AMB with no air gap stated is not judged. */
static void check_air_gaps(td_run_summary *s, const td_model *m)
{
    int k;
    td_amb a;
    for (k = 0; k < s->sensor_count && k < TD_RUN_SUMMARY_AMBS; k++)
        if (td_model_get_amb(m, k, &a) == TD_OK && a.air_gap > 0.0 && s->sensor_peak_displacement[k] > a.air_gap)
            warn(s,
                 "AMB %d's sensor saw the rotor %.4g m from centre, past the AMB's air gap %.6g m (ambs[%d].air_gap): "
                 "it would strike the AMB's stator, which the model does not hold, so the result is not physical "
                 "from there",
                 k, s->sensor_peak_displacement[k], a.air_gap, k);
}

/* A section from a few crossings cannot tell a period-n orbit from a spread. */
static void check_section(td_run_summary *s)
{
    if (s->status != TD_OK || !td_run_section_too_few((double)s->section_count))
        return;
    warn(s,
         "the once-per-revolution section has only %ld crossings after the transient (from t = %.6g s; at least %d "
         "tell an orbit): lengthen end_time or lower output.section_after",
         s->section_count, s->section_start, TD_RUN_SECTION_MIN_CROSSINGS);
}

/* long runs: end_at_rest asked, and the run reached end_time at speed (the last sample is tested like
 * the others): the ending and every answer are those of end_time, not of rest (a drive that outruns
 * the drag, a rub that holds the rotor's speed, an end_time too short; a speed held, or a speed_ramp
 * ending at speed, is refused at load by td_run_rest_refused, so a longer end_time is the advice). A load-time refusal
 * cannot decide it: contact friction and the unbalance's mean drag brake the spin too, by amounts only the run knows.
 */
static void check_rest(td_run_summary *s, const td_model *m)
{
    td_spin spin;
    if (s->status != TD_OK || !s->end_at_rest || s->ended_at_rest)
        return;
    td_model_spin(m, &spin);
    if (spin.free && spin.drive_torque > spin.drag_torque)
        warn(s,
             "end_at_rest: the rotor did not come to rest by end_time %.6g s (speed %.6g rad/s at the end, %.6g at "
             "the start): its spin.drive_torque %g N m exceeds its spin.drag_torque %g N m, so only contact "
             "friction and the unbalance's drag can stop it",
             s->t_reached, s->final_speed, s->speed, spin.drive_torque, spin.drag_torque);
    else
        warn(s,
             "end_at_rest: the rotor did not come to rest by end_time %.6g s (speed %.6g rad/s at the end, %.6g at "
             "the start): the answers are those of end_time; lengthen end_time to follow it to rest",
             s->t_reached, s->final_speed, s->speed);
}

/* projective leap: a leap group (leap.burst > 0) under which the run, complete, made no leap at all:
 * the case asked for leaps and got a run integrated throughout. A leap is made at the end of a burst
 * that follows a healing from leap.start (or the run's start, if later), and only with room for a
 * healing and a burst after it before end_time (run/leap.c, leap_length); past that, each leap due
 * was refused (shorter than a sample interval, or ending near rest). */
static void check_leaps(td_run_summary *s, const td_output_options *out)
{
    const double from = out->leap_start > s->t_start ? out->leap_start : s->t_start,
                 first = from + out->leap_heal + out->leap_burst, need = first + out->leap_heal + out->leap_burst;
    char why[256];
    if (s->status != TD_OK || !s->leap || s->leaps > 0)
        return;
    if (s->t_reached < first)
        snprintf(why, sizeof why, "the run ended at t = %.6g s, before its first burst ended at %.6g s", s->t_reached,
                 first);
    else if (s->t_end <= need)
        snprintf(why, sizeof why,
                 "end_time %.6g s leaves no room after the first burst (ending at %.6g s) for the healing and the "
                 "burst a leap must end before it: it would need to be past %.6g s",
                 s->t_end, first, need);
    else
        snprintf(why, sizeof why,
                 "each leap due was refused (shorter than a sample interval once a healing and a burst before "
                 "end_time are left, or ending near rest)");
    warn(s,
         "the leap group made no leap: %s (leap.start %.6g s, leap.heal %.6g s, leap.burst %.6g s); the run was "
         "integrated throughout",
         why, out->leap_start, out->leap_heal, out->leap_burst);
}

void td_run_check_warnings(td_run_summary *s, const td_model *m, const td_output_options *out)
{
    check_amb_capacity(s, m);
    check_schedule(s, m);
    check_clearances(s, m);
    check_section(s);
    check_air_gaps(s, m);
    check_rest(s, m);    /* long runs */
    check_leaps(s, out); /* projective leap */
}
