/*
 * The run summary: its initial state, and its text and JSON forms (touchdown/run.h).
 */
#include "run/summary.h"
#include "run/duty.h"
#include "run/outcome.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "touchdown/dofs.h"
#include "touchdown/modal.h"
#include "touchdown/version.h"
#include "util/text.h"

void td_run_summary_init(td_run_summary *s, double t0, double t_end, double speed)
{
    memset(s, 0, sizeof *s);
    s->status = TD_OK;
    s->t_start = t0;
    s->t_end = t_end;
    s->t_reached = t0;
    s->speed = speed;
    s->first_contact_time = TD_UNDEFINED;
    s->last_contact_time = TD_UNDEFINED;
    s->revolutions_after_contact = TD_UNDEFINED; /* no contact, no revolutions after it (set with the first) */
    s->peak_time = TD_UNDEFINED;
    s->peak_retainer = -1;
    s->peak_housing_retainer = -1;
    s->peak_converges = 1;
    s->free_window = TD_UNDEFINED;
    s->free_at_end = -1;
    snprintf(s->ending, sizeof s->ending, "undetermined");
    s->returned_to_free_orbit = -1;
    s->ending_whirl_frequency = TD_UNDEFINED;
    s->wall_time_per_revolution = TD_UNDEFINED;
    s->realtime_factor = TD_UNDEFINED;
    s->section_start = TD_UNDEFINED;
    s->leap_decel_power = s->leap_decel_speed = s->leap_decel_sd = TD_UNDEFINED; /* projective leap: none made */
    s->section_retainer = -1;
    s->section_clearance = TD_UNDEFINED;
    s->stats.first_contact_time = TD_UNDEFINED;
    s->stats.peak_time = TD_UNDEFINED;
    s->stats.last_return_time = TD_UNDEFINED;
    s->stats.peak_retainer = -1;
    s->stats.peak_amb_time = TD_UNDEFINED;
    s->stats.peak_amb = -1;
    s->start.requested = s->start.used = TD_START_REST;
    s->start.stability = TD_STABILITY_UNCHECKED;
    s->start.max_real_part = TD_UNDEFINED;
    td_run_duty_init(s);
    td_run_outcome_init(s); /* clearance margin */
}

/* A retainer's answers: its totals' sums and peaks, and what they lead to. */
static void retainer_undefine(td_run_retainer *r)
{
    td_retainer_totals *t = &r->totals;
    t->impulse = t->impact_impulse = t->contact_time = t->rolling_time = t->normal_force_sq = TD_UNDEFINED;
    t->friction_work = t->whirl_angle = t->peak_housing_force = t->peak_normal_force = TD_UNDEFINED;
    t->drag_work = t->heat = t->peak_temperature_rise = t->peak_thermal_growth = TD_UNDEFINED; /* heat */
    r->race_speed = r->mean_normal = r->rms_normal = r->whirl_frequency = TD_UNDEFINED;
    snprintf(r->whirl, sizeof r->whirl, "undetermined");
    t->damage = t->load_cycles = r->drops_to_failure = TD_UNDEFINED; /* life */
}

void td_run_summary_undefine_answers(td_run_summary *s)
{
    int k;
    double *energy[10];
    size_t i;
    s->peak_housing_force = s->total_impulse = s->friction_work = s->final_speed = TD_UNDEFINED;
    s->peak_housing_retainer = -1;
    s->ending_whirl_frequency = s->peak_normal_force = s->peak_time = TD_UNDEFINED;
    s->peak_retainer = -1;
    s->contact_time = s->contact_fraction = TD_UNDEFINED;
    s->free_at_end = s->returned_to_free_orbit = -1; /* undetermined */
    s->stats.peak_normal_force = s->stats.peak_time = s->stats.time_in_contact = s->stats.time_slewing = TD_UNDEFINED;
    s->stats.peak_amb_force = s->stats.peak_amb_load = s->stats.peak_amb_time = TD_UNDEFINED;
    s->stats.peak_amb = s->stats.peak_retainer = -1;
    s->stats.time_on_recovery = s->stats.last_return_time = TD_UNDEFINED; /* a later switch may have come */
    energy[0] = &s->energy.kinetic, energy[1] = &s->energy.elastic, energy[2] = &s->energy.initial;
    energy[3] = &s->energy.external_work, energy[4] = &s->energy.drive_work, energy[5] = &s->energy.damping_loss;
    energy[6] = &s->energy.contact_loss, energy[7] = &s->energy.drag_loss, energy[8] = &s->energy.impact_loss;
    energy[9] = &s->energy.residual;
    for (i = 0; i < sizeof energy / sizeof energy[0]; i++)
        *energy[i] = TD_UNDEFINED;
    s->energy.housing_work = TD_UNDEFINED;
    for (k = 0; k < TD_RUN_SUMMARY_RETAINERS; k++)
        retainer_undefine(&s->retainers[k]);
    snprintf(s->ending, sizeof s->ending, "undetermined");
    s->regime = TD_REGIME_FAILED;
    td_run_duty_undefine(s);
    td_run_outcome_undefine(s); /* clearance margin */
}

/*
 * What a retainer's whirl was, over its contact time: no contact; touch-and-go impacts only (every
 * contact left within TD_TOUCH_AND_GO_ANGLE of whirl); or its direction (the mean whirl rate against
 * the spin: forward or backward), rolling (more than half the contact time without slip) or sliding,
 * and bouncing when it was in contact for less than half of `span`, the time from the run's first
 * contact to the end of its last.
 */
void td_run_retainer_classify(td_run_retainer *out, double speed, double span)
{
    const td_retainer_totals *t = &out->totals;
    double rate;
    out->mean_normal = out->rms_normal = out->whirl_frequency = TD_UNDEFINED;
    if (t->contact_time > 0.0) {
        out->mean_normal = t->impulse / t->contact_time;
        out->rms_normal = sqrt(t->normal_force_sq / t->contact_time);
    }
    if (t->contacts == 0) { /* no sustained contact: no whirl, so no whirl frequency */
        snprintf(out->whirl, sizeof out->whirl, "%s", t->touch_and_go > 0 ? "touch-and-go" : "none");
        return;
    }
    rate = t->contact_time > 0.0 ? t->whirl_angle / t->contact_time : 0.0;
    out->whirl_frequency = (speed < 0.0 ? -rate : rate) / (2.0 * TD_PI);
    snprintf(out->whirl, sizeof out->whirl, "%s %s%s",
             td_whirl_name(out->whirl_frequency < 0.0 ? TD_WHIRL_BACKWARD : TD_WHIRL_FORWARD),
             t->rolling_time > 0.5 * t->contact_time ? "rolling" : "sliding",
             t->contact_time < 0.5 * span ? ", bouncing" : "");
}

/* The retainer in contact longest over the stretch, -1 if none. */
static int busiest(const td_retainer_totals *before, const td_retainer_totals *after, int n)
{
    int k, best = -1;
    double most = 0.0;
    for (k = 0; k < n; k++) {
        double dt = after[k].contact_time - before[k].contact_time;
        if (dt > most) {
            most = dt;
            best = k;
        }
    }
    return best;
}

void td_run_summary_ending(td_run_summary *s, const td_retainer_totals *before, const td_retainer_totals *after, int n,
                           double speed0, double speed)
{
    const double w = s->ending_window;
    int k = busiest(before, after, n);
    double dt, turned, rate, f, spin_f = fabs(speed) / (2.0 * TD_PI);
    const char *how, *bounce;
    int whirls;
    s->ending_whirl_frequency = TD_UNDEFINED; /* no whirl: free, recovered or at rest */
    s->regime = TD_REGIME_FAILED;
    if (!(w > 0.0)) {
        snprintf(s->ending, sizeof s->ending, "undetermined");
        return;
    }
    if (k < 0) {
        snprintf(s->ending, sizeof s->ending, "%s", s->contacts > 0 ? "recovered" : "free (no contact)");
        s->regime = TD_REGIME_FREE;
        return;
    }
    if (td_run_at_rest(speed0, speed)) {
        snprintf(s->ending, sizeof s->ending, "at rest");
        s->regime = TD_REGIME_RUB;
        return;
    }
    dt = after[k].contact_time - before[k].contact_time;
    turned = after[k].whirl_angle - before[k].whirl_angle;
    rate = turned / dt;
    f = (speed < 0.0 ? -rate : rate) / (2.0 * TD_PI);
    s->ending_whirl_frequency = f;
    how = after[k].rolling_time - before[k].rolling_time > 0.5 * dt ? "rolling" : "sliding";
    bounce = dt < 0.5 * w ? ", bouncing" : "";
    /* A whirl goes round: a rotor that bounces and creeps a fraction of a turn while it touches
     * (each landing a little further back) is bouncing, however fast it creeps in contact. */
    whirls = fabs(f) >= 0.05 * spin_f && (!bounce[0] || fabs(turned) >= 2.0 * TD_PI);
    s->regime = whirls && f < 0.0 ? TD_REGIME_BACKWARD_WHIRL : bounce[0] ? TD_REGIME_BOUNCE : TD_REGIME_RUB;
    if (!whirls)
        snprintf(s->ending, sizeof s->ending, "%s on the retainers%s", how, bounce);
    else
        snprintf(s->ending, sizeof s->ending, "%s at %.4g Hz, %s%s", f < 0.0 ? "backward whirl" : "forward rub", f, how,
                 bounce);
}

td_regime td_run_summary_regime(const td_run_summary *s)
{
    return !s || s->status != TD_OK ? TD_REGIME_FAILED : (td_regime)s->regime;
}

int td_run_section_too_few(double crossings)
{
    return crossings > 0.0 && crossings < TD_RUN_SECTION_MIN_CROSSINGS;
}

const char *td_regime_name(td_regime r)
{
    switch (r) {
    case TD_REGIME_FREE: return "free";
    case TD_REGIME_RUB: return "rub";
    case TD_REGIME_BOUNCE: return "bounce";
    case TD_REGIME_BACKWARD_WHIRL: return "backward whirl";
    default: return "failed";
    }
}

void td_run_summary_failed(td_run_summary *s, double t_start, double t_end, double speed, td_start requested,
                           td_status st, const char *message)
{
    if (!s)
        return;
    td_run_summary_init(s, t_start, t_end, speed);
    s->start.requested = requested;
    s->status = st;
    snprintf(s->message, sizeof s->message, "%s", message ? message : td_strerror(st));
    td_run_summary_undefine_answers(s);
}

static double section_min(const td_run_summary *s)
{
    double m = INFINITY;
    int i;
    for (i = 0; i < s->section_kept; i++)
        m = fmin(m, s->section_radius[i]);
    return m;
}

static double section_max(const td_run_summary *s)
{
    double m = -INFINITY;
    int i;
    for (i = 0; i < s->section_kept; i++)
        m = fmax(m, s->section_radius[i]);
    return m;
}

static const char *tri(int v)
{
    return v > 0 ? "yes" : v == 0 ? "no" : v == TD_RUN_NOT_APPLICABLE ? "n/a (no contact)" : "undetermined";
}

static const char *start_name(td_start st)
{
    return st == TD_START_ORBIT ? "orbit" : st == TD_START_REST ? "rest" : "auto";
}

static const char *stability_name(td_stability st)
{
    return st == TD_STABILITY_STABLE ? "stable" : st == TD_STABILITY_UNSTABLE ? "unstable" : "unchecked";
}

static void format_start(td_text *b, const td_run_summary *s)
{
    const td_sim_start_info *si = &s->start;
    if (!s->start_known) {
        td_text_printf(b, "start                       n/a (start = \"%s\", no simulation was set up)\n",
                       start_name(si->requested));
        return;
    }
    td_text_printf(b, "start                       %s", start_name(si->used));
    if (si->requested == TD_START_AUTO)
        td_text_printf(b, " (start = \"auto\"%s%s)", si->reason[0] ? ": " : "", si->reason);
    td_text_printf(b, "\n");
    if (si->stability == TD_STABILITY_UNCHECKED) /* the reason the start gave (lib/sim/start.c) */
        td_text_printf(b, "contact-free system         stability not checked: %s\n",
                       si->unchecked[0] ? si->unchecked : "no reason recorded");
    else
        td_text_printf(b, "contact-free system         %s at %.6g rad/s (rightmost eigenvalue real part %.6g 1/s)\n",
                       stability_name(si->stability), s->speed, si->max_real_part);
}

static void format_files(td_text *b, const td_run_summary *s)
{
    const char *p[3];
    int i, n = 0;
    p[0] = s->hdf5_path, p[1] = s->csv_path, p[2] = s->events_path;
    td_text_printf(b, "files                      ");
    for (i = 0; i < 3; i++)
        if (p[i][0])
            td_text_printf(b, "%s %s", n++ ? "," : "", p[i]);
    td_text_printf(b, "%s%s\n", n ? "" : " none", n && !s->complete ? " (marked incomplete)" : "");
}
/* The energy account: held now and at the start, put in, lost, and the balance's residual. */
static void format_energy(td_text *b, const td_energy *e, int housing)
{
    td_text_printf(b,
                   "energy                      held %.6g J (%.6g J at the start); in: external %.6g J, drive %.6g J\n",
                   e->kinetic + e->elastic, e->initial, e->external_work, e->drive_work);
    td_text_printf(b,
                   "energy lost                 damping %.6g J, contact %.6g J, drag %.6g J, impacts %.6g J; "
                   "residual %.3g J\n",
                   e->damping_loss, e->contact_loss, e->drag_loss, e->impact_loss, e->residual);
    if (housing) /* the residual has it in */
        td_text_printf(b, "energy housing work         %.6g J (work of the housing motion's inertial loads)\n",
                       e->housing_work);
}

/* A retainer's line. Its counts say how it touched: a sustained contact (one that swept at least
 * TD_TOUCH_AND_GO_ANGLE of whirl) or a brief one (touch-and-go), and the share of the run it was in
 * contact, so that "0 sustained" never reads as "never touched". */
static void format_retainer(td_text *b, const td_run_summary *s, int k)
{
    const td_run_retainer *r = &s->retainers[k];
    double span = s->t_reached - s->t_start;
    td_text_printf(b, "retainer %-2d                 %s", k, r->whirl);
    if (r->totals.contacts > 0 && !td_is_undefined(r->whirl_frequency))
        td_text_printf(b, " at %.4g Hz; N mean %.6g N, rms %.6g N over %.6g s", r->whirl_frequency, r->mean_normal,
                       r->rms_normal, r->totals.contact_time);
    td_text_printf(b, "; sustained contacts %ld, brief contacts (touch-and-go) %ld", r->totals.contacts,
                   r->totals.touch_and_go);
    if (span > 0.0 && !td_is_undefined(r->totals.contact_time))
        td_text_printf(b, ", in contact %.3g %% of the run", 100.0 * r->totals.contact_time / span);
    if (td_is_undefined(r->race_speed))
        td_text_printf(b, "; race n/a\n");
    else
        td_text_printf(b, "; race %.6g rad/s\n", r->race_speed);
}

/* life: a retainer's fatigue damage, its load cycles and the drops to failure it leads to (ISO 281
 * L10); "no rating" for a retainer without a dynamic rating, n/a for a run that did not reach its end. */
static void format_life(td_text *b, const td_run_summary *s, int k)
{
    const td_run_retainer *r = &s->retainers[k];
    td_text_printf(b, "retainer %-2d life            ", k);
    if (s->status != TD_OK)
        td_text_printf(b, "n/a (the run did not reach its end)\n");
    else if (td_is_undefined(r->totals.damage))
        td_text_printf(b, "no rating (retainers[%d].bearing.dynamic_rating)\n", k);
    else if (isinf(r->drops_to_failure))
        td_text_printf(
            b,
            "damage 0 over %.6g load cycles, over the run (%.6g s to %.6g s): drops to failure unlimited (no "
            "damage)\n",
            r->totals.load_cycles, s->t_start, s->t_reached);
    else
        td_text_printf(b,
                       "damage %.6g over %.6g load cycles, over the run (%.6g s to %.6g s): %.6g drops to failure "
                       "(ISO 281 L10)%s\n",
                       r->totals.damage, r->totals.load_cycles, s->t_start, s->t_reached, r->drops_to_failure,
                       td_run_at_rest(s->speed, s->final_speed)
                           ? ""
                           : "; the run ended before the rotor came to rest, a whole drop does more damage");
}

/* One answer: its value and unit, or n/a for a run that did not reach its end. */
static void format_answer(td_text *b, const char *label, double v, const char *unit)
{
    if (td_is_undefined(v))
        td_text_printf(b, "%-28sn/a (the run did not reach its end)\n", label);
    else
        td_text_printf(b, "%-28s%.6g %s\n", label, v, unit);
}

/* The recovery supervisor's account (touchdown/records.h td_sim_stats), when the model has one. */
static void format_recovery(td_text *b, const td_run_summary *s)
{
    td_text_printf(b, "controller switches         %ld (recovery supervisor)\n", s->stats.controller_switches);
    format_answer(b, "time on recovery", s->stats.time_on_recovery, "s");
    if (td_is_undefined(s->stats.last_return_time) && s->status == TD_OK)
        td_text_printf(b, "last return to nominal      none\n");
    else
        format_answer(b, "last return to nominal", s->stats.last_return_time, "s");
}

/* heat: a retainer's thermal network, when it has one: the heat into it, the race's peak rise and
 * the bore's growth (an output only: the clearance does not change). */
static void format_retainer_heat(td_text *b, const td_run_summary *s, int k)
{
    const td_retainer_totals *t = &s->retainers[k].totals;
    if (td_is_undefined(t->peak_temperature_rise))
        return;
    td_text_printf(
        b,
        "retainer %-2d heat            %.6g J (friction %.6g J, drag %.6g J); race peak rise %.4g K, over the "
        "run (%.6g s to %.6g s)",
        k, t->heat, t->friction_work, t->drag_work, t->peak_temperature_rise, s->t_start, s->t_reached);
    if (td_is_undefined(t->peak_thermal_growth))
        td_text_printf(b, "\n");
    else
        td_text_printf(b, ", race bore growth %.3g um (widens the touchdown gap; not fed back)\n",
                       1e6 * t->peak_thermal_growth);
}

/* The answers that converge, first: housing force, impulse, friction work, speeds, each retainer. */
static void format_answers(td_text *b, const td_run_summary *s)
{
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    if (s->peak_housing_retainer >= 0)
        td_text_printf(b, "peak housing force          %.6g N, retainer %d\n", s->peak_housing_force,
                       s->peak_housing_retainer);
    else if (td_is_undefined(s->peak_housing_force))
        format_answer(b, "peak housing force", s->peak_housing_force, "N");
    else
        td_text_printf(b, "peak housing force          none (no contact force)\n");
    format_answer(b, "total impulse", s->total_impulse, "N s");
    format_answer(b, "friction work", s->friction_work, "J");
    format_answer(b, "final speed", s->final_speed, "rad/s");
    td_text_printf(b, "ending                      %s (last %.6g s), regime %s\n", s->ending, s->ending_window,
                   td_regime_name(td_run_summary_regime(s)));
    if (td_run_summary_rest_flag(s) == 1) /* long runs */
        td_text_printf(b, "ended at rest               at %.10f s (end_at_rest; end_time %.6g s)\n", s->t_reached,
                       s->t_end);
    else if (s->end_at_rest && s->status == TD_OK)
        td_text_printf(b,
                       "ended at rest               no: at speed at end_time %.6g s (end_at_rest; see the warning)\n",
                       s->t_reached);
    if (s->leap) /* projective leap: never to be taken for integrated motion */
        td_text_printf(b,
                       "leapt (not integrated)      %.6g s of %.6g s in %ld leap%s (projective leap: the files have "
                       "no rows there; the totals, counts and energy include the leaps at their bursts' rates)\n",
                       s->leapt_time, s->t_reached - s->t_start, s->leaps, s->leaps == 1 ? "" : "s");
    if (s->leap && s->leaps > 1)
        td_text_printf(b,
                       "leaps' dspeed/dt            %.6g rad/s^2 from the bursts' net power (what the leaps made), "
                       "%.6g +- %.3g rad/s^2 from their speeds\n",
                       s->leap_decel_power, s->leap_decel_speed, s->leap_decel_sd);
    else if (s->leap && s->leaps > 0) /* one leap: no spread */
        td_text_printf(b,
                       "leaps' dspeed/dt            %.6g rad/s^2 from the burst's net power (what the leap made), "
                       "%.6g rad/s^2 from its speed\n",
                       s->leap_decel_power, s->leap_decel_speed);
    if (s->stats.peak_amb >= 0)
        td_text_printf(b, "peak AMB force              %.6g N, AMB %d, %.4g %% of its capacity, at %.10f s\n",
                       s->stats.peak_amb_force, s->stats.peak_amb, 100.0 * s->stats.peak_amb_load,
                       s->stats.peak_amb_time);
    else
        td_text_printf(b, "peak AMB force              %s\n",
                       td_is_undefined(s->stats.peak_amb_load) ? "n/a (the run did not reach its end)"
                                                               : "none (no working AMB)");
    if (s->stats.time_slewing > 0.0) /* only an amplifier with a slew-rate limit slews */
        td_text_printf(b, "AMB slewing                 %.6g s (summed over the axes at their slew-rate limit)\n",
                       s->stats.time_slewing);
    if (s->supervised)
        format_recovery(b, s);
    if (s->energy_kept && td_is_undefined(s->energy.residual))
        td_text_printf(b, "energy                      n/a (the run did not reach its end)\n");
    else if (s->energy_kept)
        format_energy(b, &s->energy, s->housing_motion);
    for (k = 0; k < n; k++) {
        format_retainer(b, s, k);
        format_retainer_heat(b, s, k);
    }
    for (k = 0; s->life_kept && k < n; k++) /* life */
        format_life(b, s, k);
    td_run_duty_format(b, s);
    td_run_outcome_format(b, s); /* clearance margin */
}

int td_run_summary_format(char *buf, size_t n, const td_run_summary *s)
{
    td_text b;
    td_text_fixed(&b, buf, n);
    if (!s)
        return 0;
    if (s->complete)
        td_text_printf(&b, "status                      complete\n");
    else
        td_text_printf(&b, "status                      INCOMPLETE (%s): %s\n", td_strerror(s->status), s->message);
    td_text_printf(&b, "simulated                   %.10f s to %.10f s (requested %.10f s)\n", s->t_start, s->t_reached,
                   s->t_end);
    format_answers(&b, s);
    format_start(&b, s);
    td_text_printf(&b, "speed                       %.6g rad/s, %.4f revolutions\n", s->speed, s->revolutions);
    td_text_printf(&b, "samples                     %ld (%ld on the grid, %ld at events)\n", s->samples,
                   s->grid_samples, s->samples - s->grid_samples);
    td_text_printf(&b, "events                      %ld, contact onsets %ld\n", s->events, s->contacts);
    if (!td_is_undefined(s->first_contact_time)) {
        td_text_printf(&b, "first contact               %.10f s\n", s->first_contact_time);
        td_text_printf(&b, "last contact ended          %.10f s\n", s->last_contact_time);
    } else {
        td_text_printf(&b, "first contact               none\n");
    }
    if (td_is_undefined(s->contact_time))
        td_text_printf(&b, "time in contact             n/a (the run did not reach its end)\n");
    else if (td_is_undefined(s->contact_fraction))
        td_text_printf(&b, "time in contact             %.10f s (the run covered no time)\n", s->contact_time);
    else
        td_text_printf(&b, "time in contact             %.10f s (%.4f %% of the run)\n", s->contact_time,
                       100.0 * s->contact_fraction);
    if (s->peak_retainer >= 0)
        td_text_printf(&b, "peak normal force           %.6g N at %.10f s, retainer %d%s\n", s->peak_normal_force,
                       s->peak_time, s->peak_retainer,
                       s->peak_converges ? "" : " (rigid constraint: an instantaneous peak that does not converge)");
    else
        td_text_printf(&b, "peak normal force           %s\n",
                       td_is_undefined(s->peak_normal_force) ? "n/a (the run did not reach its end)"
                                                             : "none (no contact force)");
    if (s->free_window > 0.0)
        td_text_printf(&b, "free at end                 %s (no contact in the last %d revolutions = %.10f s)\n",
                       tri(s->free_at_end), TD_RUN_FREE_REVOLUTIONS, s->free_window);
    else
        td_text_printf(&b, "free at end                 %s\n", tri(s->free_at_end));
    td_text_printf(&b, "returned to free orbit      %s\n", tri(s->returned_to_free_orbit));
    td_text_printf(&b, "solver steps                %ld (residuals %ld, Jacobians %ld, restarts %ld)\n", s->stats.steps,
                   s->stats.residual_evals, s->stats.jacobian_evals, s->stats.restarts);
    if (s->section_kept > 0)
        td_text_printf(&b,
                       "once-per-revolution section %ld crossings after %.6g s, node radius %.6g to %.6g m (retainer "
                       "%d, last %d)\n",
                       s->section_count, s->section_start, section_min(s), section_max(s), s->section_retainer,
                       s->section_kept);
    td_text_printf(&b, "free flight in closed form  %.6g s of %.6g s (%ld steps to the next root)\n",
                   s->stats.flight_time, s->t_reached - s->t_start, s->stats.flight_steps);
    if (s->stats.controller_samples > 0)
        td_text_printf(&b, "controller samples          %ld\n", s->stats.controller_samples);
    if (s->stats.worst_drift > 0.0 || s->contacts == 0)
        td_text_printf(&b, "worst constraint drift      %.3e m\n", s->stats.worst_drift);
    else /* contacts, none of them constrained: a penalty model has no constraint to drift from */
        td_text_printf(&b, "worst constraint drift      none (no constrained contact)\n");
    td_text_printf(&b, "wall time                   %.3f s (solver %.3f s), real-time factor %.4g\n", s->wall_time,
                   s->solver_wall_time, s->realtime_factor);
    if (!td_is_undefined(s->wall_time_per_revolution))
        td_text_printf(&b, "wall time per revolution    %.6g s after first contact (%.4f revolutions)\n",
                       s->wall_time_per_revolution, s->revolutions_after_contact);
    else
        td_text_printf(&b, "wall time per revolution    n/a (no contact or no revolution after it)\n");
    format_files(&b, s);
    return (int)b.len;
}

/* A JSON number, or null for TD_UNDEFINED (and any other value JSON cannot hold). */
static void json_real(td_text *b, const char *key, double v, int comma)
{
    td_text_printf(b, "\"%s\":", key);
    td_text_json_real(b, v);
    if (comma)
        td_text_append(b, ",", 1);
}

/* "key":"value", with the escapes of td_text_json_string; "" as null when empty_is_null. */
static void json_text(td_text *b, const char *key, const char *v, int empty_is_null)
{
    if (empty_is_null && !v[0]) {
        td_text_printf(b, "\"%s\":null,", key);
        return;
    }
    td_text_printf(b, "\"%s\":", key);
    td_text_json_string(b, v);
    td_text_printf(b, ",");
}

static void json_string(td_text *b, const char *key, const char *v)
{
    json_text(b, key, v, 0);
}

static void json_start(td_text *b, const td_run_summary *s)
{
    const td_sim_start_info *si = &s->start;
    json_string(b, "start_requested", start_name(si->requested));
    if (!s->start_known) {
        td_text_printf(b, "\"start\":null,\"start_reason\":null,\"stability\":null,\"max_real_part\":null,");
        return;
    }
    json_string(b, "start", start_name(si->used));
    json_text(b, "start_reason", si->reason, 1);
    json_string(b, "stability", stability_name(si->stability));
    json_real(b, "max_real_part", si->stability == TD_STABILITY_UNCHECKED ? TD_UNDEFINED : si->max_real_part, 1);
}

static void json_files(td_text *b, const td_run_summary *s)
{
    json_text(b, "hdf5_path", s->hdf5_path, 1);
    json_text(b, "csv_path", s->csv_path, 1);
    json_text(b, "events_path", s->events_path, 1);
}

/* One array of a per-retainer number over the first TD_RUN_SUMMARY_RETAINERS retainers. */
static void json_retainer_array(td_text *b, const td_run_summary *s, const char *key, size_t offset, int is_long)
{
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    td_text_printf(b, ",\"retainer_%s\":[", key);
    for (k = 0; k < n; k++) {
        const char *base = (const char *)&s->retainers[k] + offset;
        if (is_long)
            td_text_printf(b, "%s%ld", k ? "," : "", *(const long *)base);
        else {
            td_text_printf(b, "%s", k ? "," : "");
            td_text_json_real(b, *(const double *)base); /* null also for an unlimited (infinite) life */
        }
    }
    td_text_printf(b, "]");
}

/* The retainers' answers as arrays "retainer_KEY":[...] over the first TD_RUN_SUMMARY_RETAINERS,
 * last in the object: key names of their own, so that a reader looking for the run's "contacts"
 * or "peak_normal_force" finds only the run's. */
static void json_retainers(td_text *b, const td_run_summary *s)
{
    static const struct {
        const char *key;
        size_t offset;
        int is_long;
    } fields[] = {{"whirl_frequency", offsetof(td_run_retainer, whirl_frequency), 0},
                  {"peak_housing_force", offsetof(td_run_retainer, totals.peak_housing_force), 0},
                  {"impulse", offsetof(td_run_retainer, totals.impulse), 0},
                  {"impact_impulse", offsetof(td_run_retainer, totals.impact_impulse), 0},
                  {"friction_work", offsetof(td_run_retainer, totals.friction_work), 0},
                  {"contact_time", offsetof(td_run_retainer, totals.contact_time), 0},
                  {"rolling_time", offsetof(td_run_retainer, totals.rolling_time), 0},
                  {"mean_normal_force", offsetof(td_run_retainer, mean_normal), 0},
                  {"rms_normal_force", offsetof(td_run_retainer, rms_normal), 0},
                  {"peak_normal_force", offsetof(td_run_retainer, totals.peak_normal_force), 0},
                  {"race_speed", offsetof(td_run_retainer, race_speed), 0},
                  {"contacts", offsetof(td_run_retainer, totals.contacts), 1},
                  {"touch_and_go", offsetof(td_run_retainer, totals.touch_and_go), 1},
                  /* the bearing's duty */
                  {"peak_sliding_velocity", offsetof(td_run_retainer, totals.peak_sliding_velocity), 0},
                  {"peak_friction_power", offsetof(td_run_retainer, totals.peak_friction_power), 0},
                  {"peak_pv", offsetof(td_run_retainer, totals.peak_pv), 0},
                  {"peak_contact_stress", offsetof(td_run_retainer, totals.peak_contact_stress), 0},
                  {"peak_race_speed", offsetof(td_run_retainer, totals.peak_race_speed), 0},
                  {"load_ratio", offsetof(td_run_retainer, load_ratio), 0},
                  /* heat */
                  {"drag_work", offsetof(td_run_retainer, totals.drag_work), 0},
                  {"heat", offsetof(td_run_retainer, totals.heat), 0},
                  {"peak_temperature_rise", offsetof(td_run_retainer, totals.peak_temperature_rise), 0},
                  {"peak_thermal_growth", offsetof(td_run_retainer, totals.peak_thermal_growth), 0},
                  /* clearance margin */
                  {"min_clearance_margin", offsetof(td_run_retainer, totals.min_clearance_margin), 0}};
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    size_t i;
    td_text_printf(b, "\"retainer_whirl\":[");
    for (k = 0; k < n; k++) {
        td_text_printf(b, "%s", k ? "," : "");
        td_text_json_string(b, s->retainers[k].whirl);
    }
    td_text_printf(b, "]");
    for (i = 0; i < sizeof fields / sizeof fields[0]; i++)
        json_retainer_array(b, s, fields[i].key, fields[i].offset, fields[i].is_long);
    if (s->life_kept) { /* life */
        json_retainer_array(b, s, "damage", offsetof(td_run_retainer, totals.damage), 0);
        json_retainer_array(b, s, "drops_to_failure", offsetof(td_run_retainer, drops_to_failure), 0);
        json_retainer_array(b, s, "load_cycles", offsetof(td_run_retainer, totals.load_cycles), 0);
    }
}

/* The once-per-revolution section: where it starts, the crossings taken and the radii kept. */
static void json_section(td_text *b, const td_run_summary *s)
{
    int i;
    json_real(b, "section_start", s->section_start, 1);
    td_text_printf(b, "\"section_count\":%ld,", s->section_count);
    if (s->section_retainer >= 0)
        td_text_printf(b, "\"section_retainer\":%d,\"section_radius\":[", s->section_retainer);
    else
        td_text_printf(b, "\"section_retainer\":null,\"section_radius\":[");
    for (i = 0; i < s->section_kept; i++)
        td_text_printf(b, "%s%.17g", i ? "," : "", s->section_radius[i]);
    td_text_printf(b, "],");
}

/* "warnings":[...], each a string ([] when there is none). */
static void json_warnings(td_text *b, const td_run_summary *s)
{
    int i;
    td_text_printf(b, "\"warnings\":[");
    for (i = 0; i < s->warning_count; i++) {
        td_text_printf(b, "%s", i ? "," : "");
        td_text_json_string(b, s->warnings[i]);
    }
    td_text_printf(b, "],");
}

/* The answers that converge, first (docs/validation.md). */
static void json_answers(td_text *b, const td_run_summary *s)
{
    int rest = td_run_summary_rest_flag(s);
    json_real(b, "peak_housing_force", s->peak_housing_force, 1);
    json_real(b, "total_impulse", s->total_impulse, 1);
    json_real(b, "friction_work", s->friction_work, 1);
    json_real(b, "final_speed", s->final_speed, 1);
    json_string(b, "ending", s->ending);
    json_real(b, "ending_whirl_frequency", s->ending_whirl_frequency, 1);
    json_real(b, "ending_window", s->ending_window, 1);
    json_string(b, "regime", td_regime_name(td_run_summary_regime(s)));
    if (rest != TD_RUN_NOT_APPLICABLE) /* long runs: only a run that asked for it */
        td_text_printf(b, "\"ended_at_rest\":%s,", rest == 1 ? "true" : rest == 0 ? "false" : "null");
    if (s->leap) { /* projective leap: only a run that asked for it */
        td_text_printf(b, "\"leaps\":%ld,", s->leaps);
        json_real(b, "leapt_time", s->leapt_time, 1);
        json_real(b, "leap_decel_power", s->leap_decel_power, 1);
        json_real(b, "leap_decel_speed", s->leap_decel_speed, 1);
        json_real(b, "leap_decel_sd", s->leap_decel_sd, 1);
    }
    json_real(b, "peak_amb_force", s->stats.peak_amb >= 0 ? s->stats.peak_amb_force : TD_UNDEFINED, 1);
    json_real(b, "peak_amb_load", s->stats.peak_amb >= 0 ? s->stats.peak_amb_load : TD_UNDEFINED, 1);
    if (s->stats.peak_amb >= 0)
        td_text_printf(b, "\"peak_amb\":%d,", s->stats.peak_amb);
    else
        td_text_printf(b, "\"peak_amb\":null,");
    if (!s->energy_kept) {
        td_text_printf(b, "\"energy\":null,");
        return;
    }
    td_text_printf(b, "\"energy\":{");
    json_real(b, "kinetic", s->energy.kinetic, 1);
    json_real(b, "elastic", s->energy.elastic, 1);
    json_real(b, "initial", s->energy.initial, 1);
    json_real(b, "external_work", s->energy.external_work, 1);
    json_real(b, "drive_work", s->energy.drive_work, 1);
    json_real(b, "damping_loss", s->energy.damping_loss, 1);
    json_real(b, "contact_loss", s->energy.contact_loss, 1);
    json_real(b, "drag_loss", s->energy.drag_loss, 1);
    json_real(b, "impact_loss", s->energy.impact_loss, 1);
    if (s->housing_motion)
        json_real(b, "housing_work", s->energy.housing_work, 1);
    json_real(b, "residual", s->energy.residual, 0);
    td_text_printf(b, "},");
}

int td_run_summary_rest_flag(const td_run_summary *s)
{
    if (!s->end_at_rest)
        return TD_RUN_NOT_APPLICABLE;
    if (s->status != TD_OK) /* undetermined when it failed, even after a rest sample: a run that stopped at */
        return -1;          /* rest and then failed (its last progress call, a window, the files) did not end there */
    return s->ended_at_rest ? 1 : 0; /* true when it stopped at rest, false when it reached end_time at speed */
}

void td_run_summary_json_members(td_text *b, const td_run_summary *s)
{
    td_text_printf(b, "{\"library_version\":\"%s\",", td_version());
    td_text_printf(b, "\"complete\":%s,", s->complete ? "true" : "false");
    json_string(b, "status", td_strerror(s->status));
    json_string(b, "message", s->message);
    json_answers(b, s);
    json_real(b, "t_start", s->t_start, 1);
    json_real(b, "t_end", s->t_end, 1);
    json_real(b, "t_reached", s->t_reached, 1);
    json_real(b, "speed", s->speed, 1);
    json_start(b, s);
    json_files(b, s);
    td_text_printf(b, "\"samples\":%ld,\"grid_samples\":%ld,\"events\":%ld,\"contacts\":%ld,", s->samples,
                   s->grid_samples, s->events, s->contacts);
    json_real(b, "first_contact_time", s->first_contact_time, 1);
    json_real(b, "last_contact_time", s->last_contact_time, 1);
    json_real(b, "peak_normal_force", s->peak_normal_force, 1);
    td_text_printf(b, "\"peak_normal_force_converges\":%s,", s->peak_converges ? "true" : "false");
    json_real(b, "peak_time", s->peak_time, 1);
    if (s->peak_retainer >= 0)
        td_text_printf(b, "\"peak_retainer\":%d,", s->peak_retainer);
    else
        td_text_printf(b, "\"peak_retainer\":null,");
    json_real(b, "contact_time", s->contact_time, 1);
    json_real(b, "contact_fraction", s->contact_fraction, 1);
    json_real(b, "free_window", s->free_window, 1);
    td_text_printf(b, "\"free_at_end\":%s,", s->free_at_end < 0 ? "null" : s->free_at_end ? "true" : "false");
    td_text_printf(b, "\"returned_to_free_orbit\":%s,",
                   s->returned_to_free_orbit < 0 ? "null"
                   : s->returned_to_free_orbit   ? "true"
                                                 : "false");
    json_real(b, "revolutions", s->revolutions, 1);
    json_real(b, "revolutions_after_contact", s->revolutions_after_contact, 1);
    json_real(b, "wall_time", s->wall_time, 1);
    json_real(b, "solver_wall_time", s->solver_wall_time, 1);
    json_real(b, "wall_time_per_revolution", s->wall_time_per_revolution, 1);
    json_real(b, "realtime_factor", s->realtime_factor, 1);
    if (s->supervised) { /* the recovery supervisor's account (td_sim_stats), at the top level */
        td_text_printf(b, "\"controller_switches\":%ld,", s->stats.controller_switches);
        json_real(b, "time_on_recovery", s->stats.time_on_recovery, 1);
        json_real(b, "last_return_time", s->stats.last_return_time, 1);
    }
    td_text_printf(b,
                   "\"stats\":{\"steps\":%ld,\"residual_evals\":%ld,\"jacobian_evals\":%ld,\"linear_setups\":%ld,"
                   "\"nonlinear_iters\":%ld,\"error_test_fails\":%ld,\"nonlinear_fails\":%ld,\"restarts\":%ld,"
                   "\"events\":%ld,\"contact_onsets\":%ld,\"releases\":%ld,\"flight_steps\":%ld,"
                   "\"controller_samples\":%ld,",
                   s->stats.steps, s->stats.residual_evals, s->stats.jacobian_evals, s->stats.linear_setups,
                   s->stats.nonlinear_iters, s->stats.error_test_fails, s->stats.nonlinear_fails, s->stats.restarts,
                   s->stats.events, s->stats.contact_onsets, s->stats.releases, s->stats.flight_steps,
                   s->stats.controller_samples);
    json_real(b, "flight_time", s->stats.flight_time, 1);
    json_real(b, "worst_drift", s->stats.worst_drift, 1);
    json_real(b, "peak_normal_force", s->stats.peak_normal_force, 1);
    json_real(b, "time_in_contact", s->stats.time_in_contact, 1);
    json_real(b, "time_slewing", s->stats.time_slewing, 1);
    json_real(b, "first_contact_time", s->stats.first_contact_time, 1);
    json_real(b, "wall_time", s->stats.wall_time, 0);
    td_text_printf(b, "},");
    json_section(b, s);
    json_warnings(b, s);
    td_run_duty_json(b, s);
    td_run_outcome_json(b, s); /* clearance margin */
    json_retainers(b, s);
}

int td_run_summary_json(char *buf, size_t n, const td_run_summary *s)
{
    td_text b;
    td_text_fixed(&b, buf, n);
    if (!s)
        return 0;
    td_run_summary_json_members(&b, s);
    td_text_printf(&b, "}");
    return (int)b.len;
}
