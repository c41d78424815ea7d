/*
 * long runs: the window summaries (windows.h). A window's counts and sums are the differences of the
 * retainers' running totals (td_sim_retainer_totals: exact at the output time) between its ends; its
 * peak is the largest normal force at the points inside it: its samples, the forces right after its
 * events and the integrator's accepted points since it opened (td_sim_retainer_peak_since, the points
 * of the run's own peak). Never an event's whole-contact peak: a contact that ends in this window
 * may have peaked in an earlier one.
 */
#include "run/windows.h"

#include "run/clock.h"
#include "touchdown/dofs.h"
#include "touchdown/model.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

struct td_run_windows {
    double length, t_begin;
    int n;                     /* retainers */
    long count;                /* windows written */
    td_retainer_totals *begin; /* the totals where the open window began */
    td_retainer_totals *now;   /* scratch: the totals where it ends */
    long *onsets;              /* per retainer in the open window */
    double *peak, *fraction, *friction, *temperature;
};

static void totals_now(const td_sim *sim, int n, td_retainer_totals *t)
{
    int k;
    for (k = 0; k < n; k++)
        td_sim_retainer_totals(sim, k, &t[k]);
}

/* Open a window at t: the totals there, nothing counted yet (the accepted points' peak from here). */
static void open_window(td_run_windows *w, td_sim *sim, double t)
{
    int k;
    double since;
    w->t_begin = t;
    totals_now(sim, w->n, w->begin);
    for (k = 0; k < w->n; k++) {
        w->onsets[k] = 0;
        w->peak[k] = 0.0;
        td_sim_retainer_peak_since(sim, k, &since);
    }
}

td_status td_run_windows_create(td_sim *sim, double length, double t0, td_run_windows **out, td_error *err)
{
    td_run_windows *w;
    size_t n;
    *out = NULL;
    if (!(length > 0.0))
        return TD_OK;
    if (!(w = calloc(1, sizeof *w)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the window summaries");
    w->length = length;
    w->n = td_model_retainer_count(td_sim_model(sim));
    n = (size_t)(w->n > 0 ? w->n : 1);
    w->begin = calloc(n, sizeof *w->begin);
    w->now = calloc(n, sizeof *w->now);
    w->onsets = calloc(n, sizeof *w->onsets);
    w->peak = calloc(4 * n, sizeof *w->peak); /* peak, fraction, friction, temperature */
    if (!w->begin || !w->now || !w->onsets || !w->peak) {
        td_run_windows_free(&w);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the window summaries");
    }
    w->fraction = w->peak + n;
    w->friction = w->peak + 2 * n;
    w->temperature = w->peak + 3 * n;
    open_window(w, sim, t0);
    *out = w;
    return TD_OK;
}

static void note(td_run_windows *w, int k, double f)
{
    if (k >= 0 && k < w->n && f > w->peak[k])
        w->peak[k] = f;
}

void td_run_windows_sample(td_run_windows *w, const td_retainer_state *ret, int n)
{
    int k;
    for (k = 0; w && k < n && k < w->n; k++)
        if (ret[k].in_contact)
            note(w, k, ret[k].normal_force);
}

void td_run_windows_event(td_run_windows *w, const td_event *ev)
{
    if (!w || ev->retainer < 0 || ev->retainer >= w->n)
        return;
    if (td_event_is_onset(ev->kind))
        w->onsets[ev->retainer]++;
    note(w, ev->retainer, ev->normal_force);
}

int td_run_windows_due(const td_run_windows *w, double t)
{
    return w && td_run_reached(t, w->t_begin + w->length);
}

td_status td_run_windows_close(td_run_windows *w, td_sim *sim, const td_retainer_state *ret, double t, td_recorder *rec,
                               td_error *err)
{
    td_retainer_totals *now;
    td_window_summary s;
    td_energy e;
    int k, n;
    td_status st;
    if (!w || !(t > w->t_begin))
        return TD_OK;
    now = w->now;
    n = w->n;
    totals_now(sim, n, now); /* the sample at t was noted when the run took it (td_run_windows_sample) */
    for (k = 0; k < n; k++) {
        double since;
        w->fraction[k] = (now[k].contact_time - w->begin[k].contact_time) / (t - w->t_begin);
        w->friction[k] = now[k].friction_work - w->begin[k].friction_work;
        w->temperature[k] = ret[k].race_temperature;
        if (td_sim_retainer_peak_since(sim, k, &since) == TD_OK)
            note(w, k, since);
    }
    s.t_start = w->t_begin;
    s.t_end = t;
    s.speed = td_sim_speed(sim);
    s.energy_kinetic = s.energy_residual = TD_UNDEFINED;
    if (td_sim_energy(sim, &e) == TD_OK) {
        s.energy_kinetic = e.kinetic;
        s.energy_residual = e.residual;
    }
    s.contacts = w->onsets;
    s.contact_fraction = w->fraction;
    s.peak_normal_force = w->peak;
    s.friction_work = w->friction;
    s.race_temperature = w->temperature;
    if ((st = td_recorder_window(rec, &s, err)) != TD_OK)
        return st;
    w->count++;
    open_window(w, sim, t);
    return TD_OK;
}

void td_run_windows_reopen(td_run_windows *w, td_sim *sim, double t)
{
    if (w)
        open_window(w, sim, t);
}

long td_run_windows_count(const td_run_windows *w)
{
    return w ? w->count : 0;
}

void td_run_windows_free(td_run_windows **w)
{
    if (!w || !*w)
        return;
    free((*w)->begin);
    free((*w)->now);
    free((*w)->onsets);
    free((*w)->peak);
    free(*w);
    *w = NULL;
}
