/*
 * td_run: the loop that steps a simulation over a uniform output grid, records events, keeps the
 * contact bookkeeping of the summary, and leaves complete or honestly incomplete files
 * (touchdown/run.h, docs/output-format.md).
 */
#include "touchdown/run.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "run/recorder.h"
#include "sim/sim_internal.h"
#include "touchdown/output.h"
#include "touchdown/version.h"
#include "util/error_internal.h"
#include "util/limits.h"
#include "util/numeric.h"

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
} run_state;

static double wall_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
    if (now_in_contact && r->s->first_contact_time < 0.0) {
        r->s->first_contact_time = t;
        r->solver_wall_at_contact = r->s->solver_wall_time;
    }
    r->in_contact = now_in_contact;
    r->mark = t;
}

/* ---- one sample, one event --------------------------------------------------------------- */

static td_status take_sample(run_state *r, double t, int on_grid, td_error *err)
{
    td_status st = td_recorder_sample(r->rec, r->sim, t, err);
    if (st != TD_OK)
        return st;
    r->s->samples++;
    if (on_grid)
        r->s->grid_samples++;
    peak_from_retainers(r, t);
    return TD_OK;
}

static int is_onset(td_event_kind k)
{
    return k == TD_EVENT_CONTACT_ONSET || k == TD_EVENT_PENALTY_ENTER;
}

/* td_sim_step stopped at an event: sample there (once per instant: several events at one time
 * share the sample), then record the event. */
static td_status handle_event(run_state *r, td_error *err)
{
    td_event ev;
    double t = td_sim_time(r->sim);
    td_status st = td_sim_last_event(r->sim, &ev);
    if (st != TD_OK)
        return td_error_set(err, st, "reading the event at t = %.17g s: %s", t, td_sim_errmsg(r->sim));
    if (!(r->event_sample_row >= 0 && r->event_sample_time == t)) {
        if ((st = take_sample(r, t, 0, err)) != TD_OK)
            return st;
        r->event_sample_row = r->s->samples - 1;
        r->event_sample_time = t;
    }
    r->s->events++;
    if (is_onset(ev.kind)) {
        r->s->contacts++;
        if (r->s->first_contact_time < 0.0) {
            r->s->first_contact_time = ev.time;
            r->solver_wall_at_contact = r->s->solver_wall_time;
        }
    }
    note_peak(r->s, ev.normal_force, ev.time, ev.retainer);
    contact_advance(r, t, any_in_contact(r->rec));
    return td_recorder_event(r->rec, &ev, r->event_sample_row, err);
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

/* Step over the grid to t_end. Returns TD_OK at t_end, else the failure with `err` filled. */
static td_status loop(run_state *r, td_error *err)
{
    const double t0 = r->s->t_start, t_end = r->s->t_end;
    /* A grid time this close to t_end is t_end (a millionth of a sample interval). */
    const double tol = 1e-6 / r->rate;
    td_status st;
    long k = 1;
    if ((st = take_sample(r, t0, 1, err)) != TD_OK)
        return st;
    contact_advance(r, t0, any_in_contact(r->rec));
    if (progress(r, t0, 0))
        return td_error_set(err, TD_ERR_INTERRUPTED, "stopped by the progress callback at t = %.10f s", t0);
    for (;;) {
        double target = grid_time(t0, r->rate, k), now;
        int last = target >= t_end - tol;
        if (last)
            target = t_end;
        if (cancelled(r->hooks))
            return td_error_set(err, TD_ERR_INTERRUPTED, "interrupted at t = %.10f s", td_sim_time(r->sim));
        now = td_sim_time(r->sim);
        /* After an event exactly at the grid time the state is already there: no step (IDA
         * rejects an output time that is not ahead of the current one). */
        if (target - now > 4.0 * DBL_EPSILON * max2(fabs(target), 1.0)) {
            double w0 = wall_clock(), reached = now;
            td_error step_err;
            st = td_sim_step(r->sim, target, &reached, &step_err);
            r->s->solver_wall_time += wall_clock() - w0;
            if (st == TD_EVENT) {
                if ((st = handle_event(r, err)) != TD_OK)
                    return st;
                continue;
            }
            if (st == TD_ERR_INTERRUPTED) { /* the cancel flag, seen inside the step */
                /* the sim stopped at its last good step: record the state there (off the grid),
                 * unless it has not moved since the last sample */
                if (reached > now && (st = take_sample(r, reached, 0, err)) != TD_OK)
                    return st;
                return td_error_set(err, TD_ERR_INTERRUPTED, "interrupted at t = %.10f s", reached);
            }
            if (st != TD_OK)
                return td_error_set(err, st, "simulation failed at t = %.10f s on the way to %.10f s: %s",
                                    td_sim_time(r->sim), target, step_err.message);
        }
        if ((st = take_sample(r, target, 1, err)) != TD_OK)
            return st;
        if (progress(r, target, last))
            return td_error_set(err, TD_ERR_INTERRUPTED, "stopped by the progress callback at t = %.10f s", target);
        if (last)
            return TD_OK;
        k++;
    }
}

/* ---- summary ----------------------------------------------------------------------------- */

static void summary_init(td_run_summary *s, double t0, double t_end, double speed)
{
    memset(s, 0, sizeof *s);
    s->status = TD_OK;
    s->t_start = t0;
    s->t_end = t_end;
    s->t_reached = t0;
    s->speed = speed;
    s->first_contact_time = -1.0;
    s->last_contact_time = -1.0;
    s->peak_time = -1.0;
    s->peak_retainer = -1;
    s->free_window = -1.0;
    s->free_at_end = -1;
    s->returned_to_free_orbit = -1;
    s->wall_time_per_revolution = -1.0;
    s->realtime_factor = -1.0;
    s->stats.first_contact_time = -1.0;
    s->stats.peak_time = -1.0;
    s->stats.peak_retainer = -1;
    s->start.requested = s->start.used = TD_START_REST;
    s->start.stability = TD_STABILITY_UNCHECKED;
    s->start.max_real_part = NAN;
}

void td_run_summary_failed(td_run_summary *s, double t_start, double t_end, double speed, td_start requested,
                           td_status st, const char *message)
{
    if (!s)
        return;
    summary_init(s, t_start, t_end, speed);
    s->start.requested = requested;
    s->status = st;
    snprintf(s->message, sizeof s->message, "%s", message ? message : td_strerror(st));
}

/* The files td_run writes: those of `out`, the events CSV beside the samples CSV. */
static void summary_paths(td_run_summary *s, const td_output_options *out)
{
    snprintf(s->hdf5_path, sizeof s->hdf5_path, "%s", out->hdf5_path);
    snprintf(s->csv_path, sizeof s->csv_path, "%s", out->csv_path);
    if (out->csv_path[0])
        td_writer_events_path(out->csv_path, s->events_path, sizeof s->events_path);
}

/* Everything derived once the loop has stopped. */
static void summary_finish(run_state *r, double wall_start)
{
    td_run_summary *s = r->s;
    double span, rev_period;
    s->t_reached = td_sim_time(r->sim);
    contact_advance(r, s->t_reached, r->in_contact);
    if (r->in_contact)
        s->last_contact_time = s->t_reached;
    td_sim_stats_get(r->sim, &s->stats);
    note_peak(s, s->stats.peak_normal_force, s->stats.peak_time, s->stats.peak_retainer);
    span = s->t_reached - s->t_start;
    s->contact_fraction = span > 0.0 ? s->contact_time / span : 0.0;
    s->revolutions = s->speed * span / (2.0 * TD_PI);
    if (s->first_contact_time >= 0.0)
        s->revolutions_after_contact = s->speed * (s->t_reached - s->first_contact_time) / (2.0 * TD_PI);
    if (s->revolutions_after_contact > 0.0)
        s->wall_time_per_revolution = (s->solver_wall_time - r->solver_wall_at_contact) / s->revolutions_after_contact;
    if (s->speed > 0.0) {
        rev_period = 2.0 * TD_PI / s->speed;
        s->free_window = TD_RUN_FREE_REVOLUTIONS * rev_period;
        if (r->in_contact || (s->last_contact_time >= 0.0 && s->t_reached - s->last_contact_time < s->free_window))
            s->free_at_end = 0;
        else if (span >= s->free_window)
            s->free_at_end = 1;
    }
    if (s->contacts == 0)
        s->returned_to_free_orbit = TD_RUN_NOT_APPLICABLE;
    else if (s->free_at_end < 0)
        s->returned_to_free_orbit = -1;
    else
        s->returned_to_free_orbit = s->free_at_end == 1;
    s->wall_time = wall_clock() - wall_start;
    if (s->wall_time > 0.0)
        s->realtime_factor = span / s->wall_time;
}

/* The summary and run parameters as attributes of every file. */
static td_status write_summary(td_recorder *rec, const td_run_summary *s, const char *case_text, td_error *err)
{
    const struct {
        const char *name;
        double value;
    } reals[] = {{"t_start", s->t_start},
                 {"t_end", s->t_end},
                 {"t_reached", s->t_reached},
                 {"speed", s->speed},
                 {"summary_first_contact_time", s->first_contact_time},
                 {"summary_last_contact_time", s->last_contact_time},
                 {"summary_peak_normal_force", s->peak_normal_force},
                 {"summary_contact_time", s->contact_time},
                 {"summary_contact_fraction", s->contact_fraction},
                 {"summary_free_window", s->free_window},
                 {"summary_revolutions", s->revolutions},
                 {"summary_revolutions_after_contact", s->revolutions_after_contact},
                 {"summary_wall_time", s->wall_time},
                 {"summary_solver_wall_time", s->solver_wall_time},
                 {"summary_wall_time_per_revolution", s->wall_time_per_revolution},
                 {"summary_realtime_factor", s->realtime_factor}};
    const struct {
        const char *name;
        long value;
    } counts[] = {
        {"summary_samples", s->samples},         {"summary_grid_samples", s->grid_samples},
        {"summary_events", s->events},           {"summary_contacts", s->contacts},
        {"summary_free_at_end", s->free_at_end}, {"summary_returned_to_free_orbit", s->returned_to_free_orbit}};
    size_t i;
    td_status st = td_recorder_set_string(rec, "case_text", case_text ? case_text : "", err);
    if (st == TD_OK)
        st = td_recorder_set_string(rec, "status", td_strerror(s->status), err);
    if (st == TD_OK)
        st = td_recorder_set_stats(rec, &s->stats, err);
    for (i = 0; st == TD_OK && i < sizeof reals / sizeof reals[0]; i++)
        st = td_recorder_set_double(rec, reals[i].name, reals[i].value, err);
    for (i = 0; st == TD_OK && i < sizeof counts / sizeof counts[0]; i++)
        st = td_recorder_set_long(rec, counts[i].name, counts[i].value, err);
    return st;
}

static td_status check_args(const td_sim *sim, const td_model *model, double t_end, const td_output_options *out,
                            td_error *err)
{
    char why[256];
    double t0;
    if (!sim || !model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_run: NULL simulation, model or output options");
    if (td_model_dof_count(model) != td_sim_dof_count(sim))
        return td_error_set(err, TD_ERR_INVALID, "td_run: the model has %d DOFs but the simulation %d",
                            td_model_dof_count(model), td_sim_dof_count(sim));
    t0 = td_sim_time(sim);
    if (!isfinite(t_end) || !(t_end > t0))
        return td_error_set(err, TD_ERR_INVALID, "td_run: t_end = %.10f s is not after the current time %.10f s", t_end,
                            t0);
    /* the bounds of touchdown/limits.h, also checked (with the key) by the case reader */
    if (td_run_limit_check(t_end - t0, td_model_speed(model), out->sample_rate, sim->opt.solver.max_step, why,
                           sizeof why) != TD_LIMIT_NONE)
        return td_error_set(err, TD_ERR_INVALID, "td_run: %s", why);
    return TD_OK;
}

td_status td_run(td_sim *sim, const td_model *model, double t_end, const td_output_options *out,
                 const td_run_hooks *hooks, const char *case_text, td_run_summary *summary, td_error *err)
{
    td_run_summary local_summary;
    run_state r;
    td_error loop_err, close_err;
    double wall_start = wall_clock();
    td_status st, cst;
    if (!summary)
        summary = &local_summary;
    if ((st = check_args(sim, model, t_end, out, err)) != TD_OK) {
        td_run_summary_failed(summary, sim ? td_sim_time(sim) : 0.0, t_end, model ? td_model_speed(model) : 0.0,
                              TD_START_REST, st, err ? err->message : NULL);
        if (sim)
            summary->start_known = td_sim_start_info_get(sim, &summary->start) == TD_OK;
        return st;
    }
    summary_init(summary, td_sim_time(sim), t_end, td_model_speed(model));
    summary->start_known = td_sim_start_info_get(sim, &summary->start) == TD_OK;
    memset(&r, 0, sizeof r);
    r.sim = sim;
    r.hooks = hooks;
    r.s = summary;
    r.rate = out->sample_rate;
    r.mark = summary->t_start;
    r.next_progress = summary->t_start;
    r.event_sample_row = -1;
    if ((st = td_recorder_create(model, out, &r.rec, err)) != TD_OK) {
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
    summary->status = st;
    td_error_clear(&close_err);
    cst = write_summary(r.rec, summary, case_text, &close_err);
    if (cst == TD_OK)
        cst = td_recorder_close(&r.rec, st == TD_OK, loop_err.message, &close_err);
    else
        td_recorder_close(&r.rec, 0, close_err.message, NULL);
    if (st == TD_OK && cst != TD_OK) {
        st = cst;
        loop_err = close_err;
    }
    summary->status = st;
    summary->complete = st == TD_OK;
    snprintf(summary->message, sizeof summary->message, "%s", st == TD_OK ? "" : loop_err.message);
    summary->wall_time = wall_clock() - wall_start;
    if (st != TD_OK)
        return td_error_set(err, st, "%s", loop_err.message);
    return TD_OK;
}

/* ---- formatting -------------------------------------------------------------------------- */

/* snprintf into a growing position; keeps the total length even when the buffer is too small. */
typedef struct text_buf {
    char *buf;
    size_t n, len;
} text_buf;

static void tb_printf(text_buf *b, const char *fmt, ...) TD_PRINTF(2, 3);
static void tb_printf(text_buf *b, const char *fmt, ...)
{
    va_list ap;
    int k;
    va_start(ap, fmt);
    k = vsnprintf(b->len < b->n ? b->buf + b->len : NULL, b->len < b->n ? b->n - b->len : 0, fmt, ap);
    va_end(ap);
    if (k > 0)
        b->len += (size_t)k;
}

static int tb_done(text_buf *b)
{
    if (b->n > 0 && b->len >= b->n)
        b->buf[b->n - 1] = '\0';
    return (int)b->len;
}

/* An empty text in `buf` (n bytes, may be 0 to measure). */
static void tb_init(text_buf *b, char *buf, size_t n)
{
    b->buf = buf;
    b->n = n;
    b->len = 0;
    if (n > 0)
        buf[0] = '\0';
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

static void format_start(text_buf *b, const td_run_summary *s)
{
    const td_sim_start_info *si = &s->start;
    if (!s->start_known) {
        tb_printf(b, "start                       n/a (start = \"%s\", no simulation was set up)\n",
                  start_name(si->requested));
        return;
    }
    tb_printf(b, "start                       %s", start_name(si->used));
    if (si->requested == TD_START_AUTO)
        tb_printf(b, " (start = \"auto\"%s%s)", si->reason[0] ? ": " : "", si->reason);
    tb_printf(b, "\n");
    if (si->stability == TD_STABILITY_UNCHECKED)
        tb_printf(b, "contact-free system         stability not checked (more than %d states, or no eigen-solution)\n",
                  TD_SIM_STABILITY_MAX_STATES);
    else
        tb_printf(b, "contact-free system         %s at %.6g rad/s (rightmost eigenvalue real part %.6g 1/s)\n",
                  stability_name(si->stability), s->speed, si->max_real_part);
}

static void format_files(text_buf *b, const td_run_summary *s)
{
    const char *p[3];
    int i, n = 0;
    p[0] = s->hdf5_path, p[1] = s->csv_path, p[2] = s->events_path;
    tb_printf(b, "files                      ");
    for (i = 0; i < 3; i++)
        if (p[i][0])
            tb_printf(b, "%s %s", n++ ? "," : "", p[i]);
    tb_printf(b, "%s%s\n", n ? "" : " none", n && !s->complete ? " (marked incomplete)" : "");
}

int td_run_summary_format(char *buf, size_t n, const td_run_summary *s)
{
    text_buf b;
    tb_init(&b, buf, n);
    if (!s)
        return 0;
    if (s->complete)
        tb_printf(&b, "status                      complete\n");
    else
        tb_printf(&b, "status                      INCOMPLETE (%s): %s\n", td_strerror(s->status), s->message);
    tb_printf(&b, "simulated                   %.10f s to %.10f s (requested %.10f s)\n", s->t_start, s->t_reached,
              s->t_end);
    format_start(&b, s);
    tb_printf(&b, "speed                       %.6g rad/s, %.4f revolutions\n", s->speed, s->revolutions);
    tb_printf(&b, "samples                     %ld (%ld on the grid, %ld at events)\n", s->samples, s->grid_samples,
              s->samples - s->grid_samples);
    tb_printf(&b, "events                      %ld, contact onsets %ld\n", s->events, s->contacts);
    if (s->first_contact_time >= 0.0) {
        tb_printf(&b, "first contact               %.10f s\n", s->first_contact_time);
        tb_printf(&b, "last contact ended          %.10f s\n", s->last_contact_time);
    } else {
        tb_printf(&b, "first contact               none\n");
    }
    tb_printf(&b, "time in contact             %.10f s (%.4f %% of the run)\n", s->contact_time,
              100.0 * s->contact_fraction);
    if (s->peak_retainer >= 0)
        tb_printf(&b, "peak normal force           %.6g N at %.10f s, retainer %d\n", s->peak_normal_force,
                  s->peak_time, s->peak_retainer);
    else
        tb_printf(&b, "peak normal force           none (no contact force)\n");
    if (s->free_window > 0.0)
        tb_printf(&b, "free at end                 %s (no contact in the last %d revolutions = %.10f s)\n",
                  tri(s->free_at_end), TD_RUN_FREE_REVOLUTIONS, s->free_window);
    else
        tb_printf(&b, "free at end                 %s\n", tri(s->free_at_end));
    tb_printf(&b, "returned to free orbit      %s\n", tri(s->returned_to_free_orbit));
    tb_printf(&b, "solver steps                %ld (residuals %ld, Jacobians %ld, restarts %ld)\n", s->stats.steps,
              s->stats.residual_evals, s->stats.jacobian_evals, s->stats.restarts);
    if (s->stats.worst_drift > 0.0 || s->contacts == 0)
        tb_printf(&b, "worst constraint drift      %.3e m\n", s->stats.worst_drift);
    else /* contacts, none of them constrained: a penalty model has no constraint to drift from */
        tb_printf(&b, "worst constraint drift      none (no constrained contact)\n");
    tb_printf(&b, "wall time                   %.3f s (solver %.3f s), real-time factor %.4g\n", s->wall_time,
              s->solver_wall_time, s->realtime_factor);
    if (s->wall_time_per_revolution >= 0.0)
        tb_printf(&b, "wall time per revolution    %.6g s after first contact (%.4f revolutions)\n",
                  s->wall_time_per_revolution, s->revolutions_after_contact);
    else
        tb_printf(&b, "wall time per revolution    n/a (no contact or no revolution after it)\n");
    format_files(&b, s);
    return tb_done(&b);
}

/* A JSON number, or null for a "none" sentinel or a non-finite value. */
static void json_real(text_buf *b, const char *key, double v, int negative_is_null, int comma)
{
    if (!isfinite(v) || (negative_is_null && v < 0.0))
        tb_printf(b, "\"%s\":null%s", key, comma ? "," : "");
    else
        tb_printf(b, "\"%s\":%.17g%s", key, v, comma ? "," : "");
}

/* A JSON string with the escapes RFC 8259 requires; "" as null when empty_is_null. */
static void json_text(text_buf *b, const char *key, const char *v, int empty_is_null)
{
    if (empty_is_null && !v[0]) {
        tb_printf(b, "\"%s\":null,", key);
        return;
    }
    tb_printf(b, "\"%s\":\"", key);
    for (; *v; v++) {
        unsigned char c = (unsigned char)*v;
        if (c == '"' || c == '\\')
            tb_printf(b, "\\%c", c);
        else if (c < 0x20)
            tb_printf(b, "\\u%04x", c);
        else
            tb_printf(b, "%c", c);
    }
    tb_printf(b, "\",");
}

static void json_string(text_buf *b, const char *key, const char *v)
{
    json_text(b, key, v, 0);
}

static void json_start(text_buf *b, const td_run_summary *s)
{
    const td_sim_start_info *si = &s->start;
    json_string(b, "start_requested", start_name(si->requested));
    if (!s->start_known) {
        tb_printf(b, "\"start\":null,\"start_reason\":null,\"stability\":null,\"max_real_part\":null,");
        return;
    }
    json_string(b, "start", start_name(si->used));
    json_text(b, "start_reason", si->reason, 1);
    json_string(b, "stability", stability_name(si->stability));
    json_real(b, "max_real_part", si->stability == TD_STABILITY_UNCHECKED ? NAN : si->max_real_part, 0, 1);
}

static void json_files(text_buf *b, const td_run_summary *s)
{
    json_text(b, "hdf5_path", s->hdf5_path, 1);
    json_text(b, "csv_path", s->csv_path, 1);
    json_text(b, "events_path", s->events_path, 1);
}

int td_run_summary_json(char *buf, size_t n, const td_run_summary *s)
{
    text_buf b;
    tb_init(&b, buf, n);
    if (!s)
        return 0;
    tb_printf(&b, "{\"library_version\":\"%s\",", td_version());
    tb_printf(&b, "\"complete\":%s,", s->complete ? "true" : "false");
    json_string(&b, "status", td_strerror(s->status));
    json_string(&b, "message", s->message);
    json_real(&b, "t_start", s->t_start, 0, 1);
    json_real(&b, "t_end", s->t_end, 0, 1);
    json_real(&b, "t_reached", s->t_reached, 0, 1);
    json_real(&b, "speed", s->speed, 0, 1);
    json_start(&b, s);
    json_files(&b, s);
    tb_printf(&b, "\"samples\":%ld,\"grid_samples\":%ld,\"events\":%ld,\"contacts\":%ld,", s->samples, s->grid_samples,
              s->events, s->contacts);
    json_real(&b, "first_contact_time", s->first_contact_time, 1, 1);
    json_real(&b, "last_contact_time", s->last_contact_time, 1, 1);
    json_real(&b, "peak_normal_force", s->peak_normal_force, 0, 1);
    json_real(&b, "peak_time", s->peak_time, 1, 1);
    if (s->peak_retainer >= 0)
        tb_printf(&b, "\"peak_retainer\":%d,", s->peak_retainer);
    else
        tb_printf(&b, "\"peak_retainer\":null,");
    json_real(&b, "contact_time", s->contact_time, 0, 1);
    json_real(&b, "contact_fraction", s->contact_fraction, 0, 1);
    json_real(&b, "free_window", s->free_window, 1, 1);
    tb_printf(&b, "\"free_at_end\":%s,", s->free_at_end < 0 ? "null" : s->free_at_end ? "true" : "false");
    tb_printf(&b, "\"returned_to_free_orbit\":%s,",
              s->returned_to_free_orbit < 0 ? "null"
              : s->returned_to_free_orbit   ? "true"
                                            : "false");
    json_real(&b, "revolutions", s->revolutions, 0, 1);
    json_real(&b, "revolutions_after_contact", s->revolutions_after_contact, 0, 1);
    json_real(&b, "wall_time", s->wall_time, 0, 1);
    json_real(&b, "solver_wall_time", s->solver_wall_time, 0, 1);
    json_real(&b, "wall_time_per_revolution", s->wall_time_per_revolution, 1, 1);
    json_real(&b, "realtime_factor", s->realtime_factor, 1, 1);
    tb_printf(&b,
              "\"stats\":{\"steps\":%ld,\"residual_evals\":%ld,\"jacobian_evals\":%ld,\"linear_setups\":%ld,"
              "\"nonlinear_iters\":%ld,\"error_test_fails\":%ld,\"nonlinear_fails\":%ld,\"restarts\":%ld,"
              "\"events\":%ld,\"contact_onsets\":%ld,\"releases\":%ld,",
              s->stats.steps, s->stats.residual_evals, s->stats.jacobian_evals, s->stats.linear_setups,
              s->stats.nonlinear_iters, s->stats.error_test_fails, s->stats.nonlinear_fails, s->stats.restarts,
              s->stats.events, s->stats.contact_onsets, s->stats.releases);
    json_real(&b, "worst_drift", s->stats.worst_drift, 0, 1);
    json_real(&b, "peak_normal_force", s->stats.peak_normal_force, 0, 1);
    json_real(&b, "time_in_contact", s->stats.time_in_contact, 0, 1);
    json_real(&b, "first_contact_time", s->stats.first_contact_time, 1, 1);
    json_real(&b, "wall_time", s->stats.wall_time, 0, 0);
    tb_printf(&b, "}}");
    return tb_done(&b);
}
