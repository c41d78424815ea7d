/*
 * td_run: the loop that steps a simulation over a uniform output grid, records events, keeps the
 * contact bookkeeping of the summary, and leaves complete or honestly incomplete files
 * (touchdown/run.h, docs/output-format.md).
 */
#include "touchdown/run.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/clock.h"
#include "run/duty.h"
#include "run/leap.h"
#include "run/outcome.h"
#include "run/recorder.h"
#include "run/summary.h"
#include "run/warnings.h"
#include "run/windows.h"
#include "sim/section.h"
#include "touchdown/assess.h"
#include "touchdown/dofs.h"
#include "touchdown/output.h"
#include "util/clock.h"
#include "util/error_internal.h"
#include "util/limits.h"

/* Loop state besides the summary. */
typedef struct run_state {
    td_sim *sim;
    td_recorder *rec;
    const td_run_hooks *hooks;
    td_run_summary *s;
    double rate;              /* samples per second */
    double mark;              /* contact bookkeeping is done up to this time */
    int in_contact;           /* some retainer is in contact since `mark` */
    double next_progress;     /* simulated time of the next progress call */
    long event_sample_row;    /* row of the last event sample, -1 before the first */
    double event_sample_time; /* its time */
    double solver_wall_at_contact;
    /* the retainers' totals where the ending's stretch begins (td_run_summary_ending) */
    double t_window;
    int window_taken;
    td_retainer_totals window[TD_RUN_SUMMARY_RETAINERS];
    /* long runs */
    td_run_windows *windows; /* the window summaries, NULL without output.window */
    int omit_events;         /* output.events = false: no event rows, no samples at events */
    int end_at_rest;         /* end_at_rest: stop at the first grid sample at rest */
    double rest_after;       /* end_at_rest: after the model's last prescribed change (td_run_rest_after) */
    int stopped;             /* the run ended at rest before t_end */
    /* projective leap */
    int leaping;         /* the run leaps (td_output_options.leap_burst > 0) */
    td_run_leap leap;    /* its state: run time = simulation time + leap.offset */
    double *leap_start;  /* the leaps made, for the files: each one's start (run time) */
    double *leap_length; /* and length (s) */
    long leap_cap;       /* leaps the two lists hold */
} run_state;

/* long runs: what a sample is for; an event's is not written when the events are omitted */
typedef enum sample_kind { SAMPLE_EVENT = 0, SAMPLE_GRID = 1, SAMPLE_LAST = 2 } sample_kind;

/* projective leap: the run's time, the simulation's plus the time leapt (none without leaps) */
static double leapt(const run_state *r)
{
    return r->leaping ? r->leap.offset : 0.0;
}

static double run_time(const run_state *r)
{
    return td_sim_time(r->sim) + leapt(r);
}

static double max2(double a, double b)
{
    return a > b ? a : b;
}

/* Grid time k: t0 + k / rate, computed afresh each time so the grid never drifts. */
static double grid_time(double t0, double rate, long k)
{
    return t0 + (double)k / rate;
}

/* ---- contact bookkeeping ----------------------------------------------------------------- */

static int any_in_contact(const td_recorder *rec)
{
    const td_retainer_state *ret = td_recorder_retainers(rec);
    int i, n = td_recorder_retainer_count(rec);
    for (i = 0; i < n; i++)
        if (ret[i].in_contact)
            return 1;
    return 0;
}

/* A normal force `f` of retainer `k` at time `t`: the peak keeps its first instant. */
static void note_peak(td_run_summary *s, double f, double t, int k)
{
    if (f > s->peak_normal_force) {
        s->peak_normal_force = f;
        s->peak_time = t;
        s->peak_retainer = k;
    }
}

static void peak_from_retainers(run_state *r, double t)
{
    const td_retainer_state *ret = td_recorder_retainers(r->rec);
    int i, n = td_recorder_retainer_count(r->rec);
    for (i = 0; i < n; i++)
        note_peak(r->s, ret[i].normal_force, t, i);
}

/* Contact can only begin or end at an event, so the state read at t0 and after each event holds
 * until the next one: account [mark, t] with the old state, then take the new one. */
static void contact_advance(run_state *r, double t, int now_in_contact)
{
    if (r->in_contact) {
        r->s->contact_time += t - r->mark;
        if (!now_in_contact)
            r->s->last_contact_time = t;
    }
    if (now_in_contact != r->in_contact) /* the bearing's duty: when the contact open now began */
        r->s->contact_onset = now_in_contact ? t : TD_UNDEFINED;
    if (now_in_contact && td_is_undefined(r->s->first_contact_time)) {
        r->s->first_contact_time = t;
        r->s->contact_speed = td_sim_speed(r->sim);
        r->solver_wall_at_contact = r->s->solver_wall_time;
    }
    r->in_contact = now_in_contact;
    r->mark = t;
}

/* ---- one sample, one event --------------------------------------------------------------- */

/* The start of the stretch the ending is judged over: the last max(5 revolutions at the start
 * speed, a tenth of the run), at most the whole run. */
static double ending_window(const td_run_summary *s)
{
    double span = s->t_end - s->t_start, w = 0.1 * span;
    if (s->speed > 0.0)
        w = max2(w, TD_RUN_FREE_REVOLUTIONS * 2.0 * TD_PI / s->speed);
    return w < span ? w : span;
}

/* The retainers' totals as the ending's stretch begins. */
static void window_snapshot(run_state *r, double t)
{
    int k, n = td_model_retainer_count(td_sim_model(r->sim));
    if (r->window_taken || t < r->t_window)
        return;
    for (k = 0; k < n && k < TD_RUN_SUMMARY_RETAINERS; k++)
        td_sim_retainer_totals(r->sim, k, &r->window[k]);
    r->window_taken = 1;
}

static td_status take_sample(run_state *r, double t, sample_kind kind, td_error *err)
{
    int write = kind != SAMPLE_EVENT || !r->omit_events; /* long runs */
    td_status st = write ? td_recorder_sample(r->rec, r->sim, t, err) : td_recorder_observe(r->rec, r->sim, err);
    if (st != TD_OK)
        return st;
    window_snapshot(r, t);
    r->s->samples += write;
    if (kind == SAMPLE_GRID)
        r->s->grid_samples++;
    peak_from_retainers(r, t);
    td_run_windows_sample(r->windows, td_recorder_retainers(r->rec), td_recorder_retainer_count(r->rec));
    return TD_OK;
}

/* td_sim_step stopped at an event: sample there (once per instant: several events at one time
 * share the sample), then record the event. */
static td_status handle_event(run_state *r, td_error *err)
{
    td_event ev;
    double t = run_time(r);
    td_status st = td_sim_last_event(r->sim, &ev);
    if (st != TD_OK)
        return td_error_set(err, st, "reading the event at t = %.17g s: %s", t, td_sim_errmsg(r->sim));
    if (r->leaping) /* projective leap: the event at the run's time */
        ev.time += r->leap.offset;
    if (!(r->event_sample_row >= 0 && r->event_sample_time == t)) {
        if ((st = take_sample(r, t, SAMPLE_EVENT, err)) != TD_OK)
            return st;
        r->event_sample_row = r->omit_events ? -1 : r->s->samples - 1;
        r->event_sample_time = t;
    }
    td_run_windows_event(r->windows, &ev); /* long runs */
    r->s->events++;
    if (td_event_is_onset(ev.kind)) {
        r->s->contacts++;
        if (td_is_undefined(r->s->first_contact_time)) {
            r->s->first_contact_time = ev.time;
            r->s->contact_speed = td_sim_speed(r->sim);
            r->solver_wall_at_contact = r->s->solver_wall_time;
        }
    }
    note_peak(r->s, ev.normal_force, ev.time, ev.retainer);
    contact_advance(r, t, any_in_contact(r->rec));
    return r->omit_events ? TD_OK : td_recorder_event(r->rec, &ev, r->event_sample_row, err);
}

/* Progress callback after a grid sample; nonzero: the caller asked to stop. */
static int progress(run_state *r, double t, int last)
{
    const td_run_hooks *h = r->hooks;
    double span = r->s->t_end - r->s->t_start;
    if (!h || !h->progress || (!last && t < r->next_progress))
        return 0;
    r->next_progress = t + (h->progress_interval > 0.0 ? h->progress_interval : 0.0);
    return h->progress(t, span > 0.0 ? (t - r->s->t_start) / span : 1.0, r->s->contacts, h->user);
}

static int cancelled(const td_run_hooks *h)
{
    return h && h->cancel && *h->cancel;
}

/* ---- the loop ---------------------------------------------------------------------------- */

/* A failed td_sim_step as the run's error: where the run stopped (and the output time it was going
 * to, when that reads otherwise: a sample that fails at an output time is not on its way there),
 * then the step's message; the part it names (a plug-in controller, touchdown/error.h) kept as the
 * site, its reason offset moved with it, so that a caller can still say which part of the case
 * failed. */
static td_status step_failed(run_state *r, double target, td_status st, const td_error *step_err, td_error *err)
{
    char at[400], to[400], where[900]; /* %.10f of any double fits */
    int len;
    snprintf(at, sizeof at, "%.10f", run_time(r));
    snprintf(to, sizeof to, "%.10f", target);
    if (strcmp(at, to) == 0)
        len = snprintf(where, sizeof where, "simulation failed at t = %s s: ", at);
    else
        len = snprintf(where, sizeof where, "simulation failed at t = %s s on the way to %s s: ", at, to);
    td_error_set(err, st, "%s%s", where, step_err->message);
    if (err && step_err->site.part) {
        err->site = step_err->site;
        err->other = step_err->other;
        err->reason = len + step_err->reason < (int)strlen(err->message) ? len + step_err->reason : 0;
    }
    return st;
}

/* long runs: at a grid sample, close the window due there, or the last one at the run's end. */
static td_status grid_window(run_state *r, double t, int last, td_error *err)
{
    if (!r->windows || !(last || td_run_windows_due(r->windows, t)))
        return TD_OK;
    return td_run_windows_close(r->windows, r->sim, td_recorder_retainers(r->rec), t, r->rec, err);
}

/* projective leap: a leap of n sample intervals from the grid sample at t (index k), shortened so
 * that it does not cross the start of the ending's stretch (t_window): the retainers' totals there
 * are read from integrated motion, and the stretch the ending is judged over begins where it says. */
static long leap_samples(const run_state *r, double t, long k, long n)
{
    long m;
    if (r->window_taken || t >= r->t_window)
        return n;
    m = (long)floor((r->t_window - r->s->t_start) * r->rate) - k + 1; /* a sample past it at most */
    n = m < n ? m : n;
    while (n > 0 && grid_time(r->s->t_start, r->rate, k + n) > r->t_window)
        n--;
    return n;
}

/* projective leap: room in the list of leaps (write_leaps) for one more, made before the leap is, so
 * that a leap made is always listed: an allocation that fails leaves the simulation where it was. The
 * list holds two doubles a leap for the whole run (docs/output-format.md, "Leaps in the files"). */
static td_status reserve_leap(run_state *r, td_error *err)
{
    long n = r->leap.leaps + 1; /* the one about to be made */
    if (n > r->leap_cap) {
        long cap = 2 * n + 16;
        double *at = realloc(r->leap_start, (size_t)cap * sizeof *at), *length;
        if (at)
            r->leap_start = at; /* kept even if the second fails: the capacity is the smaller */
        length = at ? realloc(r->leap_length, (size_t)cap * sizeof *length) : NULL;
        if (!length)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory for the leaps' list");
        r->leap_length = length;
        r->leap_cap = cap;
    }
    return TD_OK;
}

/* projective leap: the leap just made from t to t_after kept in the room reserve_leap made for it. */
static void keep_leap(run_state *r, double t, double t_after)
{
    long n = r->leap.leaps; /* this one counted */
    r->leap_start[n - 1] = t;
    r->leap_length[n - 1] = t_after - t;
}

/* projective leap: at the grid sample at *t (index *k), the leap due there if any: the window open
 * closed at *t (its row is of integrated motion), the slow state and the run's counters moved on,
 * the grid resumed at the sample the leap lands on, which is taken (the state after the leap), and
 * *t moved there (the run's clock, which the progress call after the sample reports). The
 * contact clock is brought to t first, so that the burst's ends and the leap count the contact
 * held since the last event; a leap that cannot be made (td_run_leap_feasible) is not: the run
 * integrates on. */
static td_status leap_at(run_state *r, double *at, long *k, td_error *err)
{
    td_run_leap_counts now;
    td_sim_leap_state rate;
    double L, t_after, t = *at;
    long n;
    td_status st;
    contact_advance(r, t, r->in_contact);
    now.events = r->s->events;
    now.contacts = r->s->contacts;
    now.contact_time = r->s->contact_time;
    if ((L = td_run_leap_due(&r->leap, r->sim, t, r->rate, r->s->t_end, &now, &rate, err)) < 0.0)
        return err ? err->code : TD_ERR_INVALID;
    n = leap_samples(r, t, *k, lround(L * r->rate));
    t_after = grid_time(r->s->t_start, r->rate, *k + n);
    if (n <= 0 || !td_run_leap_feasible(&r->leap, r->sim, t_after - t, &rate))
        return TD_OK;
    if (r->windows &&
        (st = td_run_windows_close(r->windows, r->sim, td_recorder_retainers(r->rec), t, r->rec, err)) != TD_OK)
        return st;
    if ((st = reserve_leap(r, err)) != TD_OK ||
        (st = td_run_leap_make(&r->leap, r->sim, t, t_after - t, &rate, &now, err)) != TD_OK)
        return st;
    keep_leap(r, t, t_after);
    r->s->events = now.events;
    r->s->contacts = now.contacts;
    r->s->contact_time = now.contact_time;
    r->s->leaps = r->leap.leaps;
    r->s->leapt_time = r->leap.offset;
    r->s->leap_decel_power = r->leap.dw_power / r->leap.offset;
    r->s->leap_decel_speed = r->leap.dw_rate / r->leap.offset;
    r->s->leap_decel_sd = td_run_leap_decel_sd(&r->leap);
    r->mark = t_after; /* the contact state carried over holds from the leap's end */
    *k += n;
    *at = t_after;
    td_run_windows_reopen(r->windows, r->sim, t_after);
    return take_sample(r, t_after, SAMPLE_GRID, err);
}

/* Step over the grid to t_end. Returns TD_OK at t_end, else the failure with `err` filled. */
static td_status loop(run_state *r, td_error *err)
{
    const double t0 = r->s->t_start, t_end = r->s->t_end;
    td_status st;
    long k = 1;
    if ((st = take_sample(r, t0, SAMPLE_GRID, err)) != TD_OK)
        return st;
    contact_advance(r, t0, any_in_contact(r->rec));
    if (progress(r, t0, 0))
        return td_error_set(err, TD_ERR_INTERRUPTED, "stopped by the progress callback at t = %.10f s", t0);
    for (;;) {
        double target = grid_time(t0, r->rate, k), now;
        int last = td_run_reached(target, t_end); /* the grid clock's one rule (run/clock.h) */
        if (last)
            target = t_end;
        if (cancelled(r->hooks))
            return td_error_set(err, TD_ERR_INTERRUPTED, "interrupted at t = %.10f s", run_time(r));
        now = run_time(r);
        /* After an event exactly at the grid time the state is already there: no step (IDA
         * rejects an output time that is not ahead of the current one). */
        if (target - now > 4.0 * DBL_EPSILON * max2(fabs(target), 1.0)) {
            double w0 = td_wall_clock(), reached = now;
            td_error step_err;
            st = td_sim_step(r->sim, target - leapt(r), &reached, &step_err);
            reached += leapt(r);
            r->s->solver_wall_time += td_wall_clock() - w0;
            if (st == TD_EVENT) {
                if ((st = handle_event(r, err)) != TD_OK)
                    return st;
                continue;
            }
            if (st == TD_ERR_INTERRUPTED) { /* the cancel flag, seen inside the step */
                /* the sim stopped at its last good step: record the state there (off the grid),
                 * unless it has not moved since the last sample */
                if (reached > now && (st = take_sample(r, reached, SAMPLE_LAST, err)) != TD_OK)
                    return st;
                return td_error_set(err, TD_ERR_INTERRUPTED, "interrupted at t = %.10f s", reached);
            }
            if (st != TD_OK)
                return step_failed(r, target, st, &step_err, err);
        }
        if ((st = take_sample(r, target, SAMPLE_GRID, err)) != TD_OK)
            return st;
        if (r->end_at_rest && target > r->rest_after && td_run_at_rest(r->s->speed, td_sim_speed(r->sim)))
            last = r->stopped = 1;
        if ((st = grid_window(r, target, last, err)) != TD_OK)
            return st;
        if (r->leaping && !last && (st = leap_at(r, &target, &k, err)) != TD_OK) /* projective leap */
            return st;
        if (progress(r, target, last))
            return td_error_set(err, TD_ERR_INTERRUPTED, "stopped by the progress callback at t = %.10f s", target);
        if (last)
            return TD_OK;
        k++;
    }
}

/* ---- summary ----------------------------------------------------------------------------- */

/* The files td_run writes: those of `out`, the events CSV beside the samples CSV unless events are omitted. */
static void summary_paths(td_run_summary *s, const td_output_options *out)
{
    snprintf(s->hdf5_path, sizeof s->hdf5_path, "%s", out->hdf5_path);
    snprintf(s->csv_path, sizeof s->csv_path, "%s", out->csv_path);
    if (out->csv_path[0] && !out->omit_events)
        td_writer_events_path(out->csv_path, s->events_path, sizeof s->events_path);
}

/* 1 if retainer `ret` meets the rotor as a rigid constraint (the run's constraint model and no
 * compliant law of its own): its instantaneous peak force does not converge with the mesh. */
static int rigid_constraint(const td_retainer *ret, const td_sim_options *o)
{
    return o->contact.model == TD_CONTACT_CONSTRAINT && !(ret->contact.stiffness > 0.0);
}

/* The section's crossings of the retainer with the largest peak housing force (retainer 0 without
 * contact), the last TD_RUN_SECTION_SAMPLES of them. */
static void summary_section(run_state *r)
{
    td_run_summary *s = r->s;
    td_retainer ret;
    s->section_count = td_sim_section_count(r->sim);
    s->section_retainer = s->retainer_count > 0 ? (s->peak_housing_retainer >= 0 ? s->peak_housing_retainer : 0) : -1;
    if (s->section_retainer >= 0 && td_model_get_retainer(td_sim_model(r->sim), s->section_retainer, &ret) == TD_OK)
        s->section_clearance = ret.clearance;
    s->section_kept =
        td_sim_section_read(r->sim, s->section_retainer, s->section_time, s->section_radius, TD_RUN_SECTION_SAMPLES);
}

/* life: 1 when some retainer's bearing has a dynamic rating, whose damage the run counts. */
static int life_kept(const td_model *m)
{
    int k, n = td_model_retainer_count(m);
    for (k = 0; k < n; k++) {
        td_retainer_bearing b;
        if (td_model_get_retainer_bearing(m, k, &b) == TD_OK && b.dynamic_rating > 0.0)
            return 1;
    }
    return 0;
}

/* The answers that converge: every retainer's totals, their sums and peaks, the speeds. */
static void summary_totals(run_state *r)
{
    td_run_summary *s = r->s;
    const td_model *m = td_sim_model(r->sim);
    td_sim_options o;
    int k;
    td_sim_options_get(r->sim, &o);
    s->final_speed = td_sim_speed(r->sim);
    s->energy_kept = td_sim_energy(r->sim, &s->energy) == TD_OK;
    s->supervised = td_model_get_recovery(m, NULL) > 0;
    s->housing_motion = td_model_has_housing_motion(m);
    s->retainer_count = td_model_retainer_count(m);
    for (k = 0; k < s->retainer_count; k++) {
        td_retainer_totals t;
        td_retainer ret;
        td_retainer_state st;
        td_sim_retainer_totals(r->sim, k, &t);
        td_model_get_retainer(m, k, &ret);
        s->total_impulse += t.impulse;
        s->friction_work += t.friction_work;
        if (t.peak_housing_force > 0.0 && t.peak_housing_force > s->peak_housing_force) {
            s->peak_housing_force = t.peak_housing_force;
            s->peak_housing_retainer = k;
        }
        if (rigid_constraint(&ret, &o) && t.impulse > 0.0)
            s->peak_converges = 0;
        if (k < TD_RUN_SUMMARY_RETAINERS) {
            s->retainers[k].totals = t;
            /* a state that cannot be read is no speed (touchdown/dofs.h "Undefined values"), never 0 */
            s->retainers[k].race_speed = td_sim_retainer_state(r->sim, k, &st) == TD_OK ? st.race_speed : TD_UNDEFINED;
            td_run_retainer_classify(
                &s->retainers[k], s->final_speed,
                !td_is_undefined(s->first_contact_time) ? s->last_contact_time - s->first_contact_time : 0.0);
            s->retainers[k].drops_to_failure = td_life_runs_to_failure(t.damage); /* life */
        }
    }
    s->life_kept = life_kept(m); /* life */
}

/* How the run ended: judged over the last stretch when the run got through it. */
static void summary_ending(run_state *r)
{
    td_run_summary *s = r->s;
    td_retainer_totals after[TD_RUN_SUMMARY_RETAINERS];
    int k, n = s->retainer_count < TD_RUN_SUMMARY_RETAINERS ? s->retainer_count : TD_RUN_SUMMARY_RETAINERS;
    if (r->stopped) { /* long runs: ended at rest, judged over the whole run, the time it reached */
        s->ending_window = s->t_reached - s->t_start;
        memset(r->window, 0, sizeof r->window);
        for (k = 0; k < n; k++)
            after[k] = s->retainers[k].totals;
        td_run_summary_ending(s, r->window, after, n, s->speed, s->final_speed);
        return;
    }
    if (!r->window_taken || s->t_reached < s->t_end) {
        snprintf(s->ending, sizeof s->ending, "undetermined");
        return;
    }
    for (k = 0; k < n; k++)
        after[k] = s->retainers[k].totals;
    td_run_summary_ending(s, r->window, after, n, s->speed, s->final_speed);
}

/* Everything derived once the loop has stopped. */
static void summary_finish(run_state *r, double wall_start)
{
    td_run_summary *s = r->s;
    double span, rev_period;
    s->t_reached = run_time(r);
    contact_advance(r, s->t_reached, r->in_contact);
    if (r->in_contact)
        s->last_contact_time = s->t_reached;
    td_sim_stats_get(r->sim, &s->stats);
    note_peak(s, s->stats.peak_normal_force, s->stats.peak_time, s->stats.peak_retainer);
    span = s->t_reached - s->t_start;
    s->contact_fraction = span > 0.0 ? s->contact_time / span : TD_UNDEFINED; /* 0/0: no time, no fraction */
    s->revolutions = s->speed * span / (2.0 * TD_PI);
    if (!td_is_undefined(s->first_contact_time))
        s->revolutions_after_contact = s->speed * (s->t_reached - s->first_contact_time) / (2.0 * TD_PI);
    if (s->revolutions_after_contact > 0.0)
        s->wall_time_per_revolution = (s->solver_wall_time - r->solver_wall_at_contact) / s->revolutions_after_contact;
    if (s->speed > 0.0) {
        rev_period = 2.0 * TD_PI / s->speed;
        s->free_window = TD_RUN_FREE_REVOLUTIONS * rev_period;
        if (r->in_contact ||
            (!td_is_undefined(s->last_contact_time) && s->t_reached - s->last_contact_time < s->free_window))
            s->free_at_end = 0;
        else if (span >= s->free_window)
            s->free_at_end = 1;
    }
    summary_totals(r);
    summary_section(r);
    summary_ending(r);
    td_run_duty_collect(s, r->sim); /* after the ending: the time to settle is judged over its stretch */
    td_run_outcome_collect(s, r->sim, r->in_contact); /* clearance margin */
    if (s->contacts == 0)
        s->returned_to_free_orbit = TD_RUN_NOT_APPLICABLE;
    else if (s->free_at_end < 0)
        s->returned_to_free_orbit = -1;
    else
        s->returned_to_free_orbit = s->free_at_end == 1;
    s->wall_time = td_wall_clock() - wall_start;
    if (s->wall_time > 0.0)
        s->realtime_factor = span / s->wall_time;
}

/* The warnings, one a line, as the attribute `warnings` (absent when there is none). */
static td_status write_warnings(td_recorder *rec, const td_run_summary *s, td_error *err)
{
    char text[TD_RUN_MAX_WARNINGS * TD_RUN_WARNING_SIZE];
    size_t len = 0;
    int i;
    text[0] = '\0';
    for (i = 0; i < s->warning_count; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "%s\n", s->warnings[i]);
    return td_recorder_set_string(rec, TD_OUT_WARNINGS, text, err);
}

/* The energy account, when the run kept it, as attributes of every file. */
static td_status write_energy(td_recorder *rec, const td_energy *e, td_error *err)
{
    const struct {
        td_out_id name;
        double value;
    } reals[] = {{TD_OUT_SUM_ENERGY_KINETIC, e->kinetic},           {TD_OUT_SUM_ENERGY_ELASTIC, e->elastic},
                 {TD_OUT_SUM_ENERGY_INITIAL, e->initial},           {TD_OUT_SUM_ENERGY_EXTERNAL_WORK, e->external_work},
                 {TD_OUT_SUM_ENERGY_DRIVE_WORK, e->drive_work},     {TD_OUT_SUM_ENERGY_DAMPING_LOSS, e->damping_loss},
                 {TD_OUT_SUM_ENERGY_CONTACT_LOSS, e->contact_loss}, {TD_OUT_SUM_ENERGY_DRAG_LOSS, e->drag_loss},
                 {TD_OUT_SUM_ENERGY_IMPACT_LOSS, e->impact_loss},   {TD_OUT_SUM_ENERGY_RESIDUAL, e->residual}};
    size_t i;
    td_status st = TD_OK;
    for (i = 0; st == TD_OK && i < sizeof reals / sizeof reals[0]; i++)
        st = td_recorder_set_double(rec, reals[i].name, reals[i].value, err);
    return st;
}

/* The recovery supervisor's account, when the model has one, as attributes of every file. */
static td_status write_recovery(td_recorder *rec, const td_sim_stats *st, td_error *err)
{
    td_status s = td_recorder_set_long(rec, TD_OUT_STAT_CONTROLLER_SWITCHES, st->controller_switches, err);
    if (s == TD_OK)
        s = td_recorder_set_double(rec, TD_OUT_STAT_TIME_ON_RECOVERY, st->time_on_recovery, err);
    return s == TD_OK ? td_recorder_set_double(rec, TD_OUT_STAT_LAST_RETURN_TIME, st->last_return_time, err) : s;
}

/* Every retainer's totals (touchdown/records.h td_retainer_totals) as arrays over the retainers. */
static td_status write_retainer_totals(td_recorder *rec, const td_sim *sim, int reached_end, td_error *err)
{
    static const struct {
        td_out_id name;
        size_t offset;
    } reals[] = {{TD_OUT_RETAINER_IMPULSE, offsetof(td_retainer_totals, impulse)},
                 {TD_OUT_RETAINER_IMPACT_IMPULSE, offsetof(td_retainer_totals, impact_impulse)},
                 {TD_OUT_RETAINER_FRICTION_WORK, offsetof(td_retainer_totals, friction_work)},
                 {TD_OUT_RETAINER_PEAK_HOUSING_FORCE, offsetof(td_retainer_totals, peak_housing_force)},
                 {TD_OUT_RETAINER_PEAK_NORMAL_FORCE, offsetof(td_retainer_totals, peak_normal_force)},
                 {TD_OUT_RETAINER_CONTACT_TIME, offsetof(td_retainer_totals, contact_time)},
                 {TD_OUT_RETAINER_ROLLING_TIME, offsetof(td_retainer_totals, rolling_time)},
                 /* the bearing's duty */
                 {TD_OUT_RETAINER_PEAK_SLIDING_VELOCITY, offsetof(td_retainer_totals, peak_sliding_velocity)},
                 {TD_OUT_RETAINER_PEAK_FRICTION_POWER, offsetof(td_retainer_totals, peak_friction_power)},
                 {TD_OUT_RETAINER_PEAK_PV, offsetof(td_retainer_totals, peak_pv)},
                 {TD_OUT_RETAINER_PEAK_CONTACT_STRESS, offsetof(td_retainer_totals, peak_contact_stress)},
                 {TD_OUT_RETAINER_PEAK_RACE_SPEED, offsetof(td_retainer_totals, peak_race_speed)},
                 /* heat */
                 {TD_OUT_RETAINER_DRAG_WORK, offsetof(td_retainer_totals, drag_work)},
                 {TD_OUT_RETAINER_HEAT, offsetof(td_retainer_totals, heat)},
                 {TD_OUT_RETAINER_PEAK_TEMPERATURE_RISE, offsetof(td_retainer_totals, peak_temperature_rise)},
                 {TD_OUT_RETAINER_PEAK_THERMAL_GROWTH, offsetof(td_retainer_totals, peak_thermal_growth)}};
    int n = td_model_retainer_count(td_sim_model(sim)), k;
    size_t i;
    td_retainer_totals *t = calloc((size_t)(n > 0 ? n : 1), sizeof *t);
    double *v = calloc((size_t)(n > 0 ? n : 1), sizeof *v);
    long *c = calloc((size_t)(n > 0 ? n : 1), sizeof *c), *g = calloc((size_t)(n > 0 ? n : 1), sizeof *g);
    td_status st = t && v && c && g ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory writing the summary");
    for (k = 0; st == TD_OK && k < n; k++) {
        td_sim_retainer_totals(sim, k, &t[k]);
        c[k] = t[k].contacts;
        g[k] = t[k].touch_and_go;
    }
    for (i = 0; st == TD_OK && n > 0 && i < sizeof reals / sizeof reals[0]; i++) {
        for (k = 0; k < n; k++) /* totals of a run that did not reach its end are no answers */
            v[k] = reached_end ? *(const double *)((const char *)&t[k] + reals[i].offset) : TD_UNDEFINED;
        st = td_recorder_set_doubles(rec, reals[i].name, v, n, err);
    }
    if (st == TD_OK && n > 0)
        st = td_recorder_set_longs(rec, TD_OUT_RETAINER_CONTACTS, c, n, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_longs(rec, TD_OUT_RETAINER_TOUCH_AND_GO, g, n, err);
    free(t);
    free(v);
    free(c);
    free(g);
    return st;
}

/* life: every retainer's damage, drops to failure and load cycles as arrays over the retainers, when
 * some bearing has a dynamic rating (TD_UNDEFINED for the others, and for a run that did not reach
 * its end). */
static td_status write_retainer_life(td_recorder *rec, const td_sim *sim, int reached_end, td_error *err)
{
    int n = td_model_retainer_count(td_sim_model(sim)), k;
    size_t sz = (size_t)(n > 0 ? n : 1);
    double *d = calloc(sz, sizeof *d), *f = calloc(sz, sizeof *f), *c = calloc(sz, sizeof *c);
    td_status st = d && f && c ? TD_OK : td_error_set(err, TD_ERR_NOMEM, "out of memory writing the summary");
    for (k = 0; st == TD_OK && k < n; k++) {
        td_retainer_totals t;
        td_sim_retainer_totals(sim, k, &t);
        d[k] = reached_end ? t.damage : TD_UNDEFINED;
        f[k] = td_life_runs_to_failure(d[k]);
        c[k] = reached_end ? t.load_cycles : TD_UNDEFINED;
    }
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_RETAINER_DAMAGE, d, n, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_RETAINER_DROPS_TO_FAILURE, f, n, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_RETAINER_LOAD_CYCLES, c, n, err);
    free(d);
    free(f);
    free(c);
    return st;
}

/* The once-per-revolution section as attributes of every file (docs/output-format.md). */
static td_status write_section(td_recorder *rec, const td_run_summary *s, td_error *err)
{
    td_status st = td_recorder_set_double(rec, TD_OUT_SECTION_START, s->section_start, err);
    if (st == TD_OK)
        st = td_recorder_set_long(rec, TD_OUT_SECTION_COUNT, s->section_count, err);
    if (st == TD_OK)
        st = td_recorder_set_long(rec, TD_OUT_SECTION_RETAINER, s->section_retainer, err);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SECTION_CLEARANCE, s->section_clearance, err);
    if (st == TD_OK && s->section_kept > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_SECTION_TIME, s->section_time, s->section_kept, err);
    if (st == TD_OK && s->section_kept > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_SECTION_RADIUS, s->section_radius, s->section_kept, err);
    return st;
}

/* A yes/no/undetermined flag as a file value: 1, 0, or TD_UNDEFINED (undetermined, n/a). */
static double flag_value(int v)
{
    return v == 0 || v == 1 ? (double)v : TD_UNDEFINED;
}

/* projective leap: the leaps in the files, so that a gap between two rows reads as leapt, not
 * integrated: their count and the time they covered, and each one's start (the run's time of the
 * row before the gap) and length (the gap), absent when none was made. long runs: whether a run
 * asked to end at rest did (1, 0, NaN when it failed: td_run_summary_rest_flag, as the JSON's). */
static td_status write_leaps(td_recorder *rec, const run_state *r, td_error *err)
{
    const td_run_summary *s = r->s;
    int rest = td_run_summary_rest_flag(s);
    td_status st = TD_OK;
    long n = r->leap_length ? s->leaps : 0;
    if (rest != TD_RUN_NOT_APPLICABLE)
        st = td_recorder_set_double(rec, TD_OUT_SUM_ENDED_AT_REST, flag_value(rest), err);
    if (st != TD_OK || !s->leap)
        return st;
    st = td_recorder_set_long(rec, TD_OUT_SUM_LEAPS, s->leaps, err);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SUM_LEAPT_TIME, s->leapt_time, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_LEAP_TIME, r->leap_start, (int)n, err);
    if (st == TD_OK && n > 0)
        st = td_recorder_set_doubles(rec, TD_OUT_LEAP_LENGTH, r->leap_length, (int)n, err);
    return st;
}

/* The summary and run parameters as attributes of every file. */
static td_status write_summary(td_recorder *rec, const td_run_summary *s, const char *case_text, td_error *err)
{
    const struct {
        td_out_id name;
        double value;
    } reals[] = {{TD_OUT_T_START, s->t_start},
                 {TD_OUT_T_END, s->t_end},
                 {TD_OUT_T_REACHED, s->t_reached},
                 {TD_OUT_MODEL_SPEED, s->speed},
                 {TD_OUT_SUM_FIRST_CONTACT_TIME, s->first_contact_time},
                 {TD_OUT_SUM_LAST_CONTACT_TIME, s->last_contact_time},
                 {TD_OUT_SUM_PEAK_NORMAL_FORCE, s->peak_normal_force},
                 {TD_OUT_SUM_PEAK_HOUSING_FORCE, s->peak_housing_force},
                 {TD_OUT_SUM_TOTAL_IMPULSE, s->total_impulse},
                 {TD_OUT_SUM_FRICTION_WORK, s->friction_work},
                 {TD_OUT_SUM_FINAL_SPEED, s->final_speed},
                 {TD_OUT_SUM_ENDING_WHIRL_FREQUENCY, s->ending_whirl_frequency},
                 {TD_OUT_SUM_ENDING_WINDOW, s->ending_window},

                 {TD_OUT_SUM_CONTACT_TIME, s->contact_time},
                 {TD_OUT_SUM_CONTACT_FRACTION, s->contact_fraction},
                 {TD_OUT_SUM_FREE_WINDOW, s->free_window},
                 {TD_OUT_SUM_REVOLUTIONS, s->revolutions},
                 {TD_OUT_SUM_REVOLUTIONS_AFTER_CONTACT, s->revolutions_after_contact},
                 {TD_OUT_SUM_WALL_TIME, s->wall_time},
                 {TD_OUT_SUM_SOLVER_WALL_TIME, s->solver_wall_time},
                 {TD_OUT_SUM_WALL_TIME_PER_REVOLUTION, s->wall_time_per_revolution},
                 {TD_OUT_SUM_REALTIME_FACTOR, s->realtime_factor}};
    const struct {
        td_out_id name;
        long value;
    } counts[] = {{TD_OUT_SUM_SAMPLES, s->samples},
                  {TD_OUT_SUM_GRID_SAMPLES, s->grid_samples},
                  {TD_OUT_SUM_EVENTS, s->events},
                  {TD_OUT_SUM_CONTACTS, s->contacts}};
    size_t i;
    td_status st = td_recorder_set_string(rec, TD_OUT_CASE_TEXT, case_text ? case_text : "", err);
    if (st == TD_OK)
        st = td_recorder_set_string(rec, TD_OUT_STATUS, td_strerror(s->status), err);
    if (st == TD_OK)
        st = td_recorder_set_string(rec, TD_OUT_SUM_ENDING, s->ending, err);
    if (st == TD_OK)
        st = td_recorder_set_stats(rec, &s->stats, err);
    for (i = 0; st == TD_OK && i < sizeof reals / sizeof reals[0]; i++)
        st = td_recorder_set_double(rec, reals[i].name, reals[i].value, err);
    for (i = 0; st == TD_OK && i < sizeof counts / sizeof counts[0]; i++)
        st = td_recorder_set_long(rec, counts[i].name, counts[i].value, err);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SUM_FREE_AT_END, flag_value(s->free_at_end), err);
    if (st == TD_OK)
        st = td_recorder_set_double(rec, TD_OUT_SUM_RETURNED_TO_FREE_ORBIT, flag_value(s->returned_to_free_orbit), err);
    if (st == TD_OK)
        st = td_recorder_set_long(rec, TD_OUT_SUM_PEAK_NORMAL_FORCE_CONVERGES, s->peak_converges, err);
    if (st == TD_OK && s->warning_count > 0)
        st = write_warnings(rec, s, err);
    if (st == TD_OK && s->energy_kept)
        st = write_energy(rec, &s->energy, err);
    if (st == TD_OK && s->energy_kept && s->housing_motion)
        st = td_recorder_set_double(rec, TD_OUT_SUM_ENERGY_HOUSING_WORK, s->energy.housing_work, err);
    if (st == TD_OK && s->supervised)
        st = write_recovery(rec, &s->stats, err);
    if (st == TD_OK)
        st = write_section(rec, s, err);
    return st;
}

/* The summary's attributes, then the leaps' (write_leaps), whose list is spent then. */
static td_status write_run_attributes(td_recorder *rec, run_state *r, const char *case_text, td_error *err)
{
    td_status st = write_summary(rec, r->s, case_text, err);
    if (st == TD_OK)
        st = write_leaps(rec, r, err);
    free(r->leap_start);
    free(r->leap_length);
    r->leap_start = r->leap_length = NULL;
    return st;
}

static td_status check_args(const td_sim *sim, double t_end, const td_output_options *out, td_error *err)
{
    char why[256];
    td_sim_options opt;
    double t0;
    if (!sim || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_run: NULL simulation or output options");
    t0 = td_sim_time(sim);
    if (!isfinite(t_end) || !(t_end > t0))
        return td_error_set(err, TD_ERR_INVALID, "td_run: t_end = %.10f s is not after the current time %.10f s", t_end,
                            t0);
    if (!(out->section_after >= 0.0 && out->section_after <= 1.0))
        return td_error_set(err, TD_ERR_INVALID, "td_run: section_after = %g is not a fraction of the run in [0, 1]",
                            out->section_after);
    if (td_run_window_check(out->window, out->sample_rate, why, sizeof why)) /* long runs */
        return td_error_set(err, TD_ERR_INVALID, "td_run: window: %s", why);
    if (out->end_at_rest && td_run_rest_refused(td_sim_model(sim), why, sizeof why)) /* long runs */
        return td_error_set(err, TD_ERR_INVALID, "td_run: end_at_rest: %s", why);
    if (td_run_leap_check(td_sim_model(sim), out, t_end, why, sizeof why) != TD_LEAP_FINE) /* projective leap */
        return td_error_set(err, TD_ERR_INVALID, "td_run: leap: %s", why);
    td_sim_options_get(sim, &opt);
    /* the bounds of touchdown/limits.h, also checked (with the key) by the case reader */
    if (td_run_limit_check(t_end - t0, td_model_speed(td_sim_model(sim)), out->sample_rate, opt.solver.max_step, why,
                           sizeof why) != TD_LIMIT_NONE)
        return td_error_set(err, TD_ERR_INVALID, "td_run: %s", why);
    return TD_OK;
}

/* The loop's state at the start of the run. */
static void state_init(run_state *r, td_sim *sim, const td_run_hooks *hooks, td_run_summary *summary,
                       const td_output_options *out)
{
    memset(r, 0, sizeof *r);
    r->sim = sim;
    r->hooks = hooks;
    r->s = summary;
    r->rate = out->sample_rate;
    r->mark = summary->t_start;
    r->next_progress = summary->t_start;
    r->event_sample_row = -1;
    r->omit_events = out->omit_events != 0; /* long runs */
    r->end_at_rest = out->end_at_rest != 0;
    r->rest_after = td_run_rest_after(td_sim_model(sim));
    r->leaping = td_run_leap_init(&r->leap, out, summary->speed); /* projective leap */
    summary->leap = r->leaping;
}

td_status td_run(td_sim *sim, double t_end, const td_output_options *out, const td_run_hooks *hooks,
                 const char *case_text, td_run_summary *summary, td_error *err)
{
    const td_model *model = td_sim_model(sim);
    td_run_summary local_summary;
    run_state r;
    td_error loop_err, close_err;
    double wall_start = td_wall_clock();
    td_status st, cst;
    if (!summary)
        summary = &local_summary;
    if ((st = check_args(sim, t_end, out, err)) != TD_OK) {
        td_run_summary_failed(summary, sim ? td_sim_time(sim) : 0.0, t_end, model ? td_model_speed(model) : 0.0,
                              TD_START_REST, st, err ? err->message : NULL);
        if (sim)
            summary->start_known = td_sim_start_info_get(sim, &summary->start) == TD_OK;
        return st;
    }
    td_run_summary_init(summary, td_sim_time(sim), t_end, td_model_speed(model));
    summary->start_known = td_sim_start_info_get(sim, &summary->start) == TD_OK;
    state_init(&r, sim, hooks, summary, out);
    summary->ending_window = ending_window(summary);
    r.t_window = summary->t_end - summary->ending_window;
    summary->section_start = summary->t_start + out->section_after * (summary->t_end - summary->t_start);
    if ((st = td_sim_section_begin(sim, summary->section_start, TD_RUN_SECTION_SAMPLES, err)) != TD_OK ||
        (st = td_run_windows_create(sim, out->window, summary->t_start, &r.windows, err)) != TD_OK ||
        (st = td_recorder_create(model, out, &r.rec, err)) != TD_OK) {
        td_run_windows_free(&r.windows);
        td_sim_section_end(sim);
        summary->status = st;
        snprintf(summary->message, sizeof summary->message, "%s", err ? err->message : td_strerror(st));
        return st;
    }
    summary_paths(summary, out);
    td_error_clear(&loop_err);
    /* the cancel flag is also read inside td_sim_step, before every integrator step */
    td_sim_set_interrupt(sim, hooks ? hooks->cancel : NULL);
    st = loop(&r, &loop_err);
    td_sim_set_interrupt(sim, NULL);
    summary_finish(&r, wall_start);
    summary->ended_at_rest = r.stopped; /* long runs */
    summary->end_at_rest = r.end_at_rest;
    td_run_windows_free(&r.windows);
    td_sim_section_end(sim);
    summary->status = st;
    td_run_check_warnings(summary, model, out);
    if (st != TD_OK) /* no answers from a run that did not reach its end, in the files either */
        td_run_summary_undefine_answers(summary);
    td_error_clear(&close_err);
    cst = write_run_attributes(r.rec, &r, case_text, &close_err);
    if (cst == TD_OK)
        cst = write_retainer_totals(r.rec, sim, st == TD_OK, &close_err);
    if (cst == TD_OK && summary->life_kept)
        cst = write_retainer_life(r.rec, sim, st == TD_OK, &close_err);
    if (cst == TD_OK)
        cst = td_run_duty_write(r.rec, summary, sim, st == TD_OK, &close_err);
    if (cst == TD_OK) /* clearance margin */
        cst = td_run_outcome_write(r.rec, summary, sim, st == TD_OK, &close_err);
    if (cst == TD_OK)
        cst = td_recorder_close(&r.rec, st == TD_OK, loop_err.message, &close_err);
    else
        td_recorder_close(&r.rec, 0, close_err.message, NULL);
    if (st == TD_OK && cst != TD_OK) {
        st = cst;
        loop_err = close_err;
    }
    if (st != TD_OK)
        td_run_summary_undefine_answers(summary);
    summary->status = st;
    summary->complete = st == TD_OK;
    summary->ended_at_rest = r.stopped && st == TD_OK; /* long runs: "ended, complete" (touchdown/run.h) */
    snprintf(summary->message, sizeof summary->message, "%s", st == TD_OK ? "" : loop_err.message);
    summary->wall_time = td_wall_clock() - wall_start;
    if (st != TD_OK && err) { /* the whole record: the part at fault too (step_failed) */
        *err = loop_err;
        err->code = st;
    }
    return st;
}
