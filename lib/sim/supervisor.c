/*
 * The recovery supervisor (supervisor.h; touchdown/model.h td_recovery; docs/theory.md, "Recovery
 * supervisor"). A pair's two laws sample at the same instants, so the pair is sampled as one. At
 * sample k (time t_k), with the sensed radius r_k = max over the pair's AMBs of hypot(xs_x, xs_y):
 *
 *   1. the rule leading away from the law the pair runs towards is judged: detect (on the nominal)
 *      r_k > f_d c, release (on the recovery law) r_k < f_r c; `count` is the run of consecutive
 *      samples that met it, and it has held for its dwell once count - 1 >= ceil(dwell rate);
 *   2. then, unless a blend is still in progress at t_k, the pair switches at t_s = t_k: the
 *      incoming law starts from rest (x = 0) and the event is queued;
 *   3. every law that weighs computes i = C x + D e and updates x; the held current is
 *      (1 - b) i_old + b i_new, b = min(1, (k - k_s) / (blend rate)) = min(1, (t_k - t_s) / blend)
 *      (blend 0: b = 1), the old law alone before any switch and the new one alone from b = 1 on:
 *      the old law stops when its weight 1 - b reaches 0.
 *
 * So with blend > 0 the held current at a switch sample is the old law's (b = 0): the force has no
 * jump there (blend 0 is a step; an incoming law with a delay of d samples gives 0 for d samples,
 * which only a blend of many samples hides), and a law that does not weigh does not run, so its
 * internal model (a resonant block) cannot wind up in standby.
 */
#include "sim/supervisor.h"
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The sampler's record of system law l. */
static int record_of(const td_sim_sampler *sp, int l)
{
    int i;
    for (i = 0; i < sp->n; i++)
        if (sp->law[i].law == l)
            return i;
    return -1;
}

/* Pair p's records, rules, AMBs (those its nominal's outputs drive) and held current. */
static td_status make_pair(td_sim *s, td_sim_supervisor *sv, int p, td_error *err)
{
    td_sim_pair *q = &sv->pair[p];
    const td_lti_law *law;
    int i, j;
    q->law[0] = record_of(s->sampler, sv->rec.nominal[p]);
    q->law[1] = record_of(s->sampler, sv->rec.controller[p]);
    if (q->law[0] < 0 || q->law[1] < 0) /* the model's rule: both sampled */
        return td_error_set(err, TD_ERR_INVALID, "recovery: pair %d: a law is not sampled", p);
    s->sampler->law[q->law[0]].pair = s->sampler->law[q->law[1]].pair = p;
    q->running[0] = 1;
    law = &s->sys->laws[sv->rec.nominal[p]];
    q->need[0] = td_recovery_dwell_samples(sv->rec.detect.dwell, law->sample_rate);
    q->need[1] = td_recovery_dwell_samples(sv->rec.release.dwell, law->sample_rate);
    q->ambs = malloc((size_t)law->nout * sizeof *q->ambs);
    q->held = calloc((size_t)law->nout, sizeof *q->held);
    if (!q->ambs || !q->held)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    for (i = 0; i < law->nout; i++) {
        int amb = law->out_axis[i] / 2;
        for (j = 0; j < q->n_ambs && q->ambs[j] != amb; j++)
            ;
        if (j == q->n_ambs)
            q->ambs[q->n_ambs++] = amb;
    }
    return TD_OK;
}

td_status td_sim_supervisor_create(td_sim *s, td_error *err)
{
    td_sim_supervisor *sv;
    td_status st = TD_OK;
    int p, i;
    if (td_model_get_recovery(s->model, NULL) == 0)
        return TD_OK;
    sv = calloc(1, sizeof *sv);
    s->sampler->supervisor = sv;
    if (!sv)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    sv->n = td_model_get_recovery(s->model, &sv->rec);
    sv->last_return = TD_UNDEFINED;
    sv->clearance = INFINITY;
    for (i = 0; i < td_model_retainer_count(s->model); i++) {
        td_retainer r;
        td_model_get_retainer(s->model, i, &r);
        sv->clearance = fmin(sv->clearance, r.clearance);
    }
    sv->pair = calloc((size_t)sv->n, sizeof *sv->pair);
    if (!sv->pair)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    for (p = 0; st == TD_OK && p < sv->n; p++)
        st = make_pair(s, sv, p, err);
    return st;
}

void td_sim_supervisor_free(td_sim *s)
{
    td_sim_supervisor *sv = s->sampler ? s->sampler->supervisor : NULL;
    int p;
    if (!sv)
        return;
    for (p = 0; sv->pair && p < sv->n; p++) {
        free(sv->pair[p].ambs);
        free(sv->pair[p].held);
    }
    free(sv->pair);
    free(sv);
    s->sampler->supervisor = NULL;
}

/* r_k: the largest over the pair's AMBs of the radius sensed there (the values the laws read). */
static double sensed_radius(const td_sim *s, const td_sim_pair *q)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    double r = 0.0;
    int j;
    for (j = 0; j < q->n_ambs; j++) {
        const td_amb_axis *ax = &s->sys->amb_axes[2 * q->ambs[j]], *ay = ax + 1;
        r = fmax(r, hypot(y[s->dae.oq + ax->sensor_dof], y[s->dae.oq + ay->sensor_dof]));
    }
    return r;
}

/* Switch pair p to its other law at this sample (time s->dae.t), judged on radius r. */
static void take_switch(td_sim *s, td_sim_supervisor *sv, int p, double r)
{
    td_sim_pair *q = &sv->pair[p];
    td_sim_sampled *in;
    const td_lti_law *law;
    td_event ev;
    int to = 1 - q->target;
    in = &s->sampler->law[q->law[to]];
    law = &s->sys->laws[in->law];
    memset(in->x, 0, (size_t)law->n * sizeof *in->x); /* the incoming law starts from rest */
    in->reset_due = law->plugin != NULL;              /* a plug-in by its reset, before its next step */
    q->running[to] = 1;
    q->target = to;
    q->k_switch = in->k_next;
    q->count = 0;
    sv->switches++;
    if (to == 1) {
        q->since = s->dae.t;
    } else {
        sv->recovery_time += s->dae.t - q->since;
        sv->last_return = s->dae.t + s->monitor.leapt; /* the run's clock (projective leap) */
    }
    ev = td_sim_event_at(s, TD_EVENT_CONTROLLER_SWITCH, -1);
    ev.controller = in->law; /* the system's laws are the model's controllers, in order */
    ev.sensed_radius = r;
    td_sim_queue_event(s, &ev);
}

/* Steps 1 and 2 of the header: the rule on r, then a switch when it has held and no blend runs. */
static void judge(td_sim *s, td_sim_supervisor *sv, int p, double r)
{
    td_sim_pair *q = &sv->pair[p];
    int met = q->target == 0 ? r > sv->rec.detect.radius_fraction * sv->clearance
                             : r < sv->rec.release.radius_fraction * sv->clearance;
    q->count = met ? q->count + 1 : 0;
    if (sv->rec.enabled && !(q->running[0] && q->running[1]) && q->count > 0 &&
        (double)(q->count - 1) >= q->need[q->target])
        take_switch(s, sv, p, r);
}

/* The weight b of the law the pair runs towards at sample k (step 3 of the header); once it is 1
 * the blend is over and the old law, which no longer weighs, stops. */
static double end_blend(const td_sim_supervisor *sv, td_sim_pair *q, long k, double rate)
{
    double b = 1.0;
    if (q->running[0] && q->running[1] && sv->rec.blend > 0.0)
        b = fmin(1.0, (double)(k - q->k_switch) / (sv->rec.blend * rate));
    if (b >= 1.0)
        q->running[1 - q->target] = 0;
    return b;
}

double td_sim_supervisor_judge(td_sim *s, int p, long k, double *r)
{
    td_sim_supervisor *sv = s->sampler->supervisor;
    td_sim_pair *q = &sv->pair[p];
    double rate = s->sys->laws[s->sampler->law[q->law[0]].law].sample_rate;
    *r = sensed_radius(s, q);
    end_blend(sv, q, k, rate); /* a blend that ends here lets a switch start here */
    judge(s, sv, p, *r);
    return end_blend(sv, q, k, rate);
}

void td_sim_supervisor_stats(const td_sim *s, td_sim_stats *out)
{
    const td_sim_supervisor *sv = s->sampler ? s->sampler->supervisor : NULL;
    int p;
    out->controller_switches = 0;
    out->time_on_recovery = 0.0;
    out->last_return_time = TD_UNDEFINED;
    if (!sv)
        return;
    out->controller_switches = sv->switches;
    out->time_on_recovery = sv->recovery_time;
    for (p = 0; p < sv->n; p++)
        if (sv->pair[p].target == 1)
            out->time_on_recovery += s->dae.t - sv->pair[p].since;
    out->last_return_time = sv->last_return;
}

void td_sim_supervisor_set_hook(td_sim *s, td_sim_switch_hook hook, void *data)
{
    if (!s->sampler || !s->sampler->supervisor)
        return;
    s->sampler->supervisor->hook = hook;
    s->sampler->supervisor->hook_data = data;
}
