/*
 * The spread of a run's answers over an ensemble of equally accurate runs (touchdown/run.h,
 * touchdown/job.h): the members, run through the job API with solver.atol scaled; their answers
 * gathered (least, median, greatest, spread, whether it settles); the text and JSON forms.
 */
#include "touchdown/job.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/summary.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"
#include "util/text.h"

/* Each answer: its JSON name (as in the summary's JSON), its label in the text and its unit. */
static const struct {
    const char *name, *label, *unit;
} answers[TD_SPREAD_ANSWERS] = {{"peak_housing_force", "peak housing force", "N"},
                                {"total_impulse", "total impulse", "N s"},
                                {"friction_work", "friction work", "J"},
                                {"final_speed", "final speed", "rad/s"},
                                {"contacts", "contacts", ""},
                                {"contact_time", "time in contact", "s"},
                                {"first_contact_time", "first contact", "s"},
                                {"peak_normal_force", "peak normal force", "N"},
                                {"peak_amb_force", "peak AMB force", "N"}};

int td_spread_members_valid(int n)
{
    return n >= TD_SPREAD_MIN_MEMBERS && n <= TD_SPREAD_MAX_MEMBERS && n % 2 == 1;
}

double td_spread_atol_factor(int member, int n)
{
    int m, k;
    double whole;
    if (!td_spread_members_valid(n) || member < 0 || member >= n)
        return TD_UNDEFINED;
    if (member == 0)
        return 1.0;
    m = (n - 1) / 2;
    k = (member + 1) / 2;
    /* 1 +- w k / m as (m / w +- k) / (m / w): m / w is an integer (100 m, exact in a double), so
     * the one rounding is the division's: the double nearest the rational (1.005 for m = 2, k = 1) */
    whole = m / TD_SPREAD_ATOL_WIDTH;
    return (member % 2 == 1 ? whole + k : whole - k) / whole;
}

const char *td_spread_answer_name(td_spread_answer a)
{
    return (int)a >= 0 && a < TD_SPREAD_ANSWERS ? answers[a].name : NULL;
}

/* A completed member's value of an answer (TD_UNDEFINED where it has none). */
static double answer_value(const td_run_summary *s, td_spread_answer a)
{
    switch (a) {
    case TD_SPREAD_PEAK_HOUSING_FORCE: return s->peak_housing_force;
    case TD_SPREAD_TOTAL_IMPULSE: return s->total_impulse;
    case TD_SPREAD_FRICTION_WORK: return s->friction_work;
    case TD_SPREAD_FINAL_SPEED: return s->final_speed;
    case TD_SPREAD_CONTACTS: return (double)s->contacts;
    case TD_SPREAD_CONTACT_TIME: return s->contact_time;
    case TD_SPREAD_FIRST_CONTACT_TIME: return s->first_contact_time;
    case TD_SPREAD_PEAK_NORMAL_FORCE: return s->peak_normal_force;
    case TD_SPREAD_PEAK_AMB_FORCE: return s->stats.peak_amb >= 0 ? s->stats.peak_amb_force : TD_UNDEFINED;
    default: return TD_UNDEFINED;
    }
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The statistics of one answer over the members' values (TD_UNDEFINED: none). */
static void gather(td_spread_stat *st, int n)
{
    double v[TD_SPREAD_MAX_MEMBERS];
    int k, c = 0;
    for (k = 0; k < n; k++)
        if (!td_is_undefined(st->values[k]))
            v[c++] = st->values[k];
    st->run = st->values[0];
    st->count = c;
    st->least = st->median = st->greatest = st->spread = TD_UNDEFINED;
    st->settles = -1;
    if (c == 0)
        return;
    qsort(v, (size_t)c, sizeof v[0], compare_doubles);
    st->least = v[0];
    st->greatest = v[c - 1];
    st->median = c % 2 ? v[c / 2] : 0.5 * (v[c / 2 - 1] + v[c / 2]);
    if (c < 2)
        return;
    if (st->greatest == st->least)
        st->spread = 0.0;
    else if (st->median != 0.0)
        st->spread = (st->greatest - st->least) / fabs(st->median);
    if (!td_is_undefined(st->spread))
        st->settles = st->spread <= TD_SPREAD_SETTLE_LIMIT;
}

/* The ending as a kind, without the whirl frequency of "backward whirl at F Hz, ..." (a number,
 * which moves from member to member like any other): "backward whirl, rolling". */
static void ending_kind(const char *ending, char *kind, size_t n)
{
    const char *at = strstr(ending, " at ");
    const char *hz = at ? strstr(at, " Hz") : NULL;
    if (!hz)
        snprintf(kind, n, "%s", ending);
    else
        snprintf(kind, n, "%.*s%s", (int)(at - ending), ending, hz + 3);
}

/* Completed members that ended as member 0 did: its regime and its ending's kind. */
static int same_endings(const td_run_summary *members, int n)
{
    char first[sizeof members[0].ending], other[sizeof members[0].ending];
    int k, same = 0;
    if (members[0].status != TD_OK)
        return 0;
    ending_kind(members[0].ending, first, sizeof first);
    for (k = 0; k < n; k++) {
        if (members[k].status != TD_OK || td_run_summary_regime(&members[k]) != td_run_summary_regime(&members[0]))
            continue;
        ending_kind(members[k].ending, other, sizeof other);
        same += strcmp(first, other) == 0;
    }
    return same;
}

td_status td_spread_collect(const td_run_summary *members, int n, td_spread *out, td_error *err)
{
    int a, k;
    if (!members || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_spread_collect: NULL argument");
    if (!td_spread_members_valid(n))
        return td_error_set(err, TD_ERR_INVALID, "td_spread_collect: %d members: an ensemble has an odd number, %d..%d",
                            n, TD_SPREAD_MIN_MEMBERS, TD_SPREAD_MAX_MEMBERS);
    memset(out, 0, sizeof *out);
    out->members = n;
    for (k = 0; k < n; k++) {
        out->status[k] = members[k].status;
        out->atol_factor[k] = td_spread_atol_factor(k, n);
        out->completed += members[k].status == TD_OK;
    }
    out->failed = n - out->completed;
    out->same_ending = same_endings(members, n);
    snprintf(out->ending, sizeof out->ending, "%s", members[0].status == TD_OK ? members[0].ending : "");
    for (a = 0; a < TD_SPREAD_ANSWERS; a++) {
        td_spread_stat *st = &out->answers[a];
        for (k = 0; k < TD_SPREAD_MAX_MEMBERS; k++)
            st->values[k] = k < n && members[k].status == TD_OK ? answer_value(&members[k], a) : TD_UNDEFINED;
        gather(st, n);
    }
    return TD_OK;
}

/* ---- text and JSON ------------------------------------------------------------------------- */

/* "VALUE UNIT" (%.6g, as the summary writes its answers), or "none". */
static void format_value(td_text *b, double v, const char *unit)
{
    if (td_is_undefined(v))
        td_text_printf(b, "none");
    else
        td_text_printf(b, "%.6g%s%s", v, unit[0] ? " " : "", unit);
}

/* One answer's line: member 0's value; the range, median and spread over the members with a
 * value; whether it settles. */
static void format_answer(td_text *b, const td_spread *sp, int a)
{
    const td_spread_stat *st = &sp->answers[a];
    const char *unit = answers[a].unit;
    td_text_printf(b, "  %-26s", answers[a].label);
    format_value(b, st->run, unit);
    if (st->count == 0) {
        td_text_printf(b, " in every run\n");
        return;
    }
    td_text_printf(b, "; %d run%s: ", st->count, st->count == 1 ? "" : "s");
    td_text_printf(b, "%.6g .. ", st->least);
    format_value(b, st->greatest, unit);
    td_text_printf(b, ", median ");
    format_value(b, st->median, unit);
    if (st->settles < 0)
        td_text_printf(b, ", spread n/a (%s)\n", st->count < 2 ? "one value" : "median 0");
    else
        td_text_printf(b, ", spread %.2g %%: %s\n", 100.0 * st->spread, st->settles ? "settles" : "does not settle");
}

int td_spread_format(char *buf, size_t n, const td_spread *sp)
{
    td_text b;
    int a;
    td_text_fixed(&b, buf, n);
    if (!sp) {
        td_text_printf(&b, "%-28snot measured (the run did not reach its end)\n", "spread");
        return (int)b.len;
    }
    td_text_printf(&b,
                   "%-28s%d runs, solver.atol x %.6g .. %.6g (+-%g %%), all else as given: %d reached their "
                   "end, %d failed; %d ended as the run did",
                   "spread", sp->members, 1.0 - TD_SPREAD_ATOL_WIDTH, 1.0 + TD_SPREAD_ATOL_WIDTH,
                   100.0 * TD_SPREAD_ATOL_WIDTH, sp->completed, sp->failed, sp->same_ending);
    if (sp->ending[0])
        td_text_printf(&b, " (%s)", sp->ending);
    td_text_printf(&b, "\n");
    for (a = 0; a < TD_SPREAD_ANSWERS; a++)
        format_answer(&b, sp, a);
    td_text_printf(&b,
                   "  %-26san answer settles when its spread, (greatest - least) / median, is at most %g %%, "
                   "the range of solver.atol (docs/validation.md)\n",
                   "rule", 100.0 * TD_SPREAD_SETTLE_LIMIT);
    return (int)b.len;
}

/* "key":NUMBER-or-null, */
static void json_key_real(td_text *b, const char *key, double v)
{
    td_text_printf(b, "\"%s\":", key);
    td_text_json_real(b, v);
    td_text_append(b, ",", 1);
}

static void json_answer(td_text *b, const td_spread *sp, int a)
{
    const td_spread_stat *st = &sp->answers[a];
    int k;
    td_text_printf(b, "\"%s\":{", answers[a].name);
    json_key_real(b, "run", st->run);
    td_text_printf(b, "\"count\":%d,", st->count);
    json_key_real(b, "least", st->least);
    json_key_real(b, "median", st->median);
    json_key_real(b, "greatest", st->greatest);
    json_key_real(b, "spread", st->spread);
    td_text_printf(b, "\"settles\":%s,\"values\":[", st->settles < 0 ? "null" : st->settles ? "true" : "false");
    for (k = 0; k < sp->members; k++) {
        td_text_printf(b, "%s", k ? "," : "");
        td_text_json_real(b, st->values[k]);
    }
    td_text_printf(b, "]}");
}

static void json_spread(td_text *b, const td_spread *sp)
{
    int a, k;
    td_text_printf(b, "{\"members\":%d,\"completed\":%d,\"failed\":%d,\"same_ending\":%d,\"ending\":", sp->members,
                   sp->completed, sp->failed, sp->same_ending);
    if (sp->ending[0])
        td_text_json_string(b, sp->ending);
    else
        td_text_printf(b, "null");
    td_text_printf(b, ",\"atol_width\":");
    td_text_json_real(b, TD_SPREAD_ATOL_WIDTH);
    td_text_printf(b, ",\"settle_limit\":");
    td_text_json_real(b, TD_SPREAD_SETTLE_LIMIT);
    td_text_printf(b, ",\"atol_factors\":[");
    for (k = 0; k < sp->members; k++) {
        td_text_printf(b, "%s", k ? "," : "");
        td_text_json_real(b, sp->atol_factor[k]);
    }
    td_text_printf(b, "],\"status\":[");
    for (k = 0; k < sp->members; k++) {
        td_text_printf(b, "%s", k ? "," : "");
        td_text_json_string(b, td_strerror(sp->status[k]));
    }
    td_text_printf(b, "],\"answers\":{");
    for (a = 0; a < TD_SPREAD_ANSWERS; a++) {
        td_text_printf(b, "%s", a ? "," : "");
        json_answer(b, sp, a);
    }
    td_text_printf(b, "}}");
}

int td_spread_json(char *buf, size_t n, const td_spread *sp)
{
    td_text b;
    td_text_fixed(&b, buf, n);
    if (!sp)
        return 0;
    json_spread(&b, sp);
    return (int)b.len;
}

int td_run_summary_json_spread(char *buf, size_t n, const td_run_summary *s, const td_spread *sp)
{
    td_text b;
    td_text_fixed(&b, buf, n);
    if (!s)
        return 0;
    td_run_summary_json_members(&b, s);
    td_text_printf(&b, ",\"spread\":");
    if (sp)
        json_spread(&b, sp);
    else
        td_text_printf(&b, "null");
    td_text_printf(&b, "}");
    return (int)b.len;
}

/* ---- running the members ------------------------------------------------------------------- */

/* The progress of one member as the fraction of the members done: the caller's callback. */
typedef struct member_progress {
    const td_run_hooks *hooks;
    int done, total;
} member_progress;

static int on_member_progress(double t, double fraction, long contacts, void *user)
{
    const member_progress *p = user;
    return p->hooks->progress(t, (p->done + fraction) / p->total, contacts, p->hooks->user);
}

/* Member k of n: a job of the job's model with its settings, solver.atol scaled, no files. */
static td_status run_member(const td_job *job, int k, int n, const td_run_hooks *hooks, td_run_summary *out)
{
    td_job_settings set = *td_job_settings_get(job);
    td_job *member = NULL;
    td_error err;
    td_status st;
    td_error_clear(&err);
    set.sim.solver.atol *= td_spread_atol_factor(k, n);
    set.out.hdf5_path[0] = set.out.csv_path[0] = '\0';
    st = td_job_create_model(td_job_model(job), &set, NULL, &member, &err);
    if (st != TD_OK) {
        td_run_summary_failed(out, set.sim.t0, set.t_end, td_model_speed(td_job_model(job)), set.sim.start, st,
                              err.message);
        return st;
    }
    st = td_job_run(member, hooks, out, &err);
    td_job_free(&member);
    return st;
}

td_status td_spread_run(const td_job *job, int n, const td_run_hooks *hooks, td_run_summary *members, td_error *err)
{
    const td_job_settings *set;
    member_progress prog;
    td_run_hooks member_hooks;
    td_status st = TD_OK;
    int k, finished = 0;
    if (!job || !members)
        return td_error_set(err, TD_ERR_INVALID, "td_spread_run: NULL argument");
    if (!td_spread_members_valid(n))
        return td_error_set(err, TD_ERR_INVALID, "td_spread_run: %d members: an ensemble has an odd number, %d..%d", n,
                            TD_SPREAD_MIN_MEMBERS, TD_SPREAD_MAX_MEMBERS);
    set = td_job_settings_get(job);
    memset(&member_hooks, 0, sizeof member_hooks);
    prog.hooks = hooks;
    prog.total = n - 1;
    if (hooks) {
        member_hooks = *hooks;
        member_hooks.progress = hooks->progress ? on_member_progress : NULL;
        member_hooks.user = &prog;
    }
    for (k = 1; k < n; k++) {
        prog.done = k - 1;
        if (st == TD_ERR_INTERRUPTED || (hooks && hooks->cancel && *hooks->cancel)) {
            st = TD_ERR_INTERRUPTED;
            td_run_summary_failed(&members[k], set->sim.t0, set->t_end, td_model_speed(td_job_model(job)),
                                  set->sim.start, st, "not run: the spread was interrupted");
            continue;
        }
        if (run_member(job, k, n, &member_hooks, &members[k]) == TD_ERR_INTERRUPTED)
            st = TD_ERR_INTERRUPTED;
        else
            finished++;
    }
    if (st != TD_OK)
        return td_error_set(err, st, "the spread was interrupted after %d of its %d further runs", finished, n - 1);
    return TD_OK;
}
