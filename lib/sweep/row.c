/* A sweep's summary row (touchdown/sweep.h): the quantities a run summary leads with. */
#include "run/summary.h"
#include "touchdown/dofs.h"
#include "touchdown/sweep.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The section's radii, NaN-padded to TD_RUN_SECTION_SAMPLES, and their range. */
static void row_section(td_sweep_row *row, const td_run_summary *s)
{
    int i;
    row->section_count = s->section_count;
    row->section_kept = s->section_kept;
    row->section_clearance = s->section_clearance;
    row->section_radius_min = row->section_radius_max = TD_UNDEFINED;
    for (i = 0; i < TD_RUN_SECTION_SAMPLES; i++) {
        row->section_radius[i] = i < s->section_kept ? s->section_radius[i] : TD_UNDEFINED;
        if (i < s->section_kept) {
            row->section_radius_min =
                i == 0 ? s->section_radius[i] : fmin(row->section_radius_min, s->section_radius[i]);
            row->section_radius_max =
                i == 0 ? s->section_radius[i] : fmax(row->section_radius_max, s->section_radius[i]);
        }
    }
}

/* The run's warnings joined by "; " (cut to the row's field). */
static void row_warnings(td_sweep_row *row, const td_run_summary *s)
{
    size_t len = 0;
    int i;
    row->warnings[0] = '\0';
    for (i = 0; i < s->warning_count && len < sizeof row->warnings - 1; i++)
        len += (size_t)snprintf(row->warnings + len, sizeof row->warnings - len, "%s%s", i ? "; " : "", s->warnings[i]);
}

/* life: the fewest drops to failure over the retainers whose bearing has a rating and took damage. */
static void row_life(td_sweep_row *row, const td_run_summary *s)
{
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    row->life_kept = s->life_kept;
    row->drops_to_failure = TD_UNDEFINED;
    for (k = 0; k < n; k++) {
        double f = s->retainers[k].drops_to_failure;
        if (!td_is_undefined(f) && (td_is_undefined(row->drops_to_failure) || f < row->drops_to_failure))
            row->drops_to_failure = f;
    }
}

/* projective leap and long runs: what the point was asked (its columns), and with `answers` (a
 * point that reached its end) what it made of it: the leaps, and whether it ended at rest as the
 * run's JSON and files say (td_run_summary_rest_flag). A point not asked has none of them, as its
 * JSON has no member: undefined (-1 and TD_UNDEFINED, NaN in the table), never 0 leaps, which
 * would read as a point asked to leap whose every leap was refused. */
static void row_leap(td_sweep_row *row, const td_run_summary *s, int answers)
{
    row->leap = s->leap;
    row->end_at_rest = s->end_at_rest;
    row->leaps = answers && s->leap ? s->leaps : -1;
    row->leapt_time = answers && s->leap ? s->leapt_time : TD_UNDEFINED;
    row->ended_at_rest = answers && s->end_at_rest ? td_run_summary_rest_flag(s) : -1;
}

void td_sweep_row_from_summary(td_sweep_row *row, const td_run_summary *s)
{
    if (s->status != TD_OK) { /* a failed point has no answers: only how far it got and how long */
        td_sweep_row_unknown(row, TD_SWEEP_FAILED, td_strerror(s->status), s->message);
        row->t_reached = s->t_reached;
        row->wall_time = s->wall_time;
        row_warnings(row, s);
        row->life_kept = s->life_kept; /* life: its column, with no number */
        row_leap(row, s, 0);           /* its columns, with no number */
        return;
    }
    memset(row, 0, sizeof *row);
    row->state = TD_SWEEP_DONE;
    snprintf(row->status, sizeof row->status, "%s", td_strerror(s->status));
    row->peak_housing_force = s->peak_housing_force;
    row->total_impulse = s->total_impulse;
    row->friction_work = s->friction_work;
    row->contact_time = s->contact_time;
    row->contacts = s->contacts;
    row->first_contact_time = s->first_contact_time;
    snprintf(row->ending, sizeof row->ending, "%s", s->ending);
    row->ending_whirl_frequency = s->ending_whirl_frequency;
    row->returned_to_free_orbit = s->returned_to_free_orbit;
    row->final_speed = s->final_speed;
    /* as in the run's JSON: no load without a working AMB */
    row->peak_amb_load = s->stats.peak_amb >= 0 ? s->stats.peak_amb_load : TD_UNDEFINED;
    row->t_reached = s->t_reached;
    row->wall_time = s->wall_time;
    snprintf(row->regime, sizeof row->regime, "%s", td_regime_name(td_run_summary_regime(s)));
    row_section(row, s);
    row_warnings(row, s);
    row_life(row, s);
    row_leap(row, s, 1);
    /* clearance margin */
    row->min_clearance_margin = s->min_clearance_margin;
    row->contact_happened = s->contact_happened;
    snprintf(row->shock_outcome, sizeof row->shock_outcome, "%s",
             td_shock_outcome_name((td_shock_outcome)s->shock_outcome)
                 ? td_shock_outcome_name((td_shock_outcome)s->shock_outcome)
                 : "");
}

void td_sweep_row_unknown(td_sweep_row *row, td_sweep_state state, const char *status, const char *message)
{
    int i;
    memset(row, 0, sizeof *row);
    row->state = (int)state;
    snprintf(row->status, sizeof row->status, "%s", status ? status : "");
    snprintf(row->message, sizeof row->message, "%s", message ? message : "");
    row->peak_housing_force = row->total_impulse = row->friction_work = row->contact_time = TD_UNDEFINED;
    row->first_contact_time = row->ending_whirl_frequency = row->final_speed = row->peak_amb_load = TD_UNDEFINED;
    row->t_reached = row->wall_time = TD_UNDEFINED;
    row->drops_to_failure = TD_UNDEFINED; /* life */
    row->contacts = -1;
    row->returned_to_free_orbit = -1;
    snprintf(row->regime, sizeof row->regime, "%s", td_regime_name(TD_REGIME_FAILED));
    row->section_count = -1;
    row->section_radius_min = row->section_radius_max = row->section_clearance = TD_UNDEFINED;
    for (i = 0; i < TD_RUN_SECTION_SAMPLES; i++)
        row->section_radius[i] = TD_UNDEFINED;
    row->min_clearance_margin = TD_UNDEFINED; /* clearance margin */
    row->contact_happened = -1;
    row->leaps = -1; /* projective leap and long runs */
    row->leapt_time = TD_UNDEFINED;
    row->ended_at_rest = -1;
}
