/*
 * Sampled linear controllers (sampler.h): their sample instants, which are stops of the step loop
 * like the schedule's changes (td_sim_next_stop), and at each the update from the sensors' values
 * at that instant,
 *
 *   e_k = -xs(t_k),   i_k = C x_k + D e_k,   x_{k+1} = A x_k + B e_k     (touchdown/controller.h)
 *
 * with i_k held on the output axes' amplifiers until the next sample. A sample is taken only by
 * td_sim_sampler_take_due, which moves k_next on by one per sample: none is taken twice, and since
 * the next one is always a stop, none is passed over. The two laws of a recovery supervisor's pair
 * (supervisor.h) are sampled together: the supervisor says which of them run, and the held
 * current is the blend of their outputs.
 */
#include "sim/sampler.h"
#include "sim/sim_internal.h"
#include "sim/supervisor.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The time of sample k of law l: from the integer k, never by adding periods. */
static double sample_time(const td_sim_sampled *l, long k)
{
    return l->t0 + (double)k / l->rate;
}

static int sampled_count(const td_system *sys)
{
    int i, n = 0;
    for (i = 0; i < sys->n_laws; i++)
        if (sys->laws[i].sample_rate > 0.0)
            n++;
    return n;
}

td_status td_sim_sampler_create(td_sim *s, td_error *err)
{
    td_sim_sampler *sp;
    int i, j = 0, n = sampled_count(s->sys);
    if (n == 0)
        return TD_OK; /* s->sampler stays NULL: no sampled law, nothing on the path of the others */
    sp = calloc(1, sizeof *sp);
    s->sampler = sp;
    if (!sp || !(sp->law = calloc((size_t)n, sizeof *sp->law)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    sp->n = n;
    for (i = 0; i < s->sys->n_laws; i++) {
        const td_lti_law *law = &s->sys->laws[i];
        td_sim_sampled *l;
        if (!(law->sample_rate > 0.0))
            continue;
        l = &sp->law[j++];
        l->law = i;
        l->t0 = s->dae.t;
        l->rate = law->sample_rate;
        l->x = calloc((size_t)law->n + 1, sizeof(double)); /* x_0 = 0: the controller starts at rest */
        l->xn = calloc((size_t)law->n + 1, sizeof(double));
        l->e = calloc((size_t)law->nin + 1, sizeof(double));
        l->u = calloc((size_t)law->nout + 1, sizeof(double));
        l->pair = -1;
        if (!l->x || !l->xn || !l->e || !l->u)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
        if (law->plugin && td_sim_plugin_init(s, l, err) != TD_OK)
            return err && err->code != TD_OK ? err->code : TD_ERR_INVALID;
    }
    return td_sim_supervisor_create(s, err);
}

void td_sim_sampler_free(td_sim *s)
{
    int i;
    if (!s->sampler)
        return;
    td_sim_supervisor_free(s);
    for (i = 0; i < s->sampler->n && s->sampler->law; i++) {
        if (s->sys->laws[s->sampler->law[i].law].plugin)
            td_sim_plugin_free(s, &s->sampler->law[i]);
        free(s->sampler->law[i].x);
        free(s->sampler->law[i].xn);
        free(s->sampler->law[i].e);
        free(s->sampler->law[i].u);
    }
    free(s->sampler->law);
    free(s->sampler);
    s->sampler = NULL;
}

void td_sim_sampler_set_hook(td_sim *s, td_sim_sample_hook hook, void *data)
{
    if (!s->sampler)
        return;
    s->sampler->hook = hook;
    s->sampler->hook_data = data;
}

double td_sim_sampler_next_time(const td_sim *s)
{
    double t = INFINITY;
    int i;
    for (i = 0; i < s->sampler->n; i++)
        t = fmin(t, sample_time(&s->sampler->law[i], s->sampler->law[i].k_next));
    return t;
}

/* e_k = -xs of law l's sensors at s->dae.t. */
static void law_read(td_sim *s, td_sim_sampled *l)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    const double *y = N_VGetArrayPointer(s->dae.y);
    int j;
    for (j = 0; j < law->nin; j++) /* the error e = r - xs with r = 0 (touchdown/controller.h) */
        l->e[j] = -y[s->dae.oq + s->sys->amb_axes[law->in_axis[j]].sensor_dof];
}

/* i_k = C x_k + D e_k into l->u. */
static void law_output(const td_sim *s, td_sim_sampled *l)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    int i, j;
    for (i = 0; i < law->nout; i++) {
        double u = 0.0;
        for (j = 0; j < law->n; j++)
            u += law->C[i + law->nout * j] * l->x[j];
        for (j = 0; j < law->nin; j++)
            u += law->D[i + law->nout * j] * l->e[j];
        l->u[i] = u;
    }
}

/* x_{k+1} = A x_k + B e_k (column-major matrices). */
static void law_update(const td_sim *s, td_sim_sampled *l)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    double *swap;
    int i, j;
    for (i = 0; i < law->n; i++) {
        double x = 0.0;
        for (j = 0; j < law->n; j++)
            x += law->A[i + law->n * j] * l->x[j];
        for (j = 0; j < law->nin; j++)
            x += law->B[i + law->n * j] * l->e[j];
        l->xn[i] = x;
    }
    swap = l->x;
    l->x = l->xn;
    l->xn = swap;
}

/* Law l's sample k_next from its inputs e_k: a linear law's i_k = C x_k + D e_k and
 * x_{k+1} = A x_k + B e_k, or a plug-in's step (sampler_plugin.c). Returns 0, or -1 when the
 * plug-in failed (s->errmsg says why). */
static int law_run(td_sim *s, td_sim_sampled *l)
{
    if (s->sys->laws[l->law].plugin)
        return td_sim_plugin_step(s, l, l->k_next, sample_time(l, l->k_next));
    law_output(s, l);
    law_update(s, l);
    return 0;
}

/* The sampler's hook told of law l's sample. */
static void law_told(td_sim *s, const td_sim_sampled *l)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    if (s->sampler->hook)
        s->sampler->hook(s->sampler->hook_data, l->law, l->k_next, s->dae.t, l->e, law->nin, l->u, law->nout);
}

/* Law l's sample k_next from the state at s->dae.t: e_k read, the law run (law_run), i_k held on
 * the output axes, k_next moved on. Returns 0, or -1 when a plug-in failed (nothing held). */
static int take_sample(td_sim *s, td_sim_sampled *l)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    int i;
    law_read(s, l);
    if (law_run(s, l))
        return -1;
    for (i = 0; i < law->nout; i++)
        s->machine.held_current[law->out_axis[i]] = l->u[i];
    law_told(s, l);
    l->k_next++;
    s->monitor.stats.controller_samples++;
    return 0;
}

/* Pair p's sample: both laws' k_next (equal: one rate, one start), e_k read once; the supervisor
 * judges the rule and may switch (supervisor.h), then every law that weighs runs and the held
 * current is the blend (1 - b) i_old + b i_new (the old law alone before any switch, the new one
 * alone once b = 1; so at a switch sample, b = 0, exactly the old law's output). Returns 0, or -1
 * when a plug-in failed (nothing held). */
static int take_pair(td_sim *s, int p)
{
    td_sim_supervisor *sv = s->sampler->supervisor;
    td_sim_pair *q = &sv->pair[p];
    td_sim_sampled *l[2];
    const td_lti_law *law;
    td_sim_pair_sample ps;
    double r, b;
    int i, j, to, from;
    l[0] = &s->sampler->law[q->law[0]];
    l[1] = &s->sampler->law[q->law[1]];
    law = &s->sys->laws[l[0]->law];
    law_read(s, l[0]);
    memcpy(l[1]->e, l[0]->e, (size_t)law->nin * sizeof *l[0]->e); /* the same sensors */
    b = td_sim_supervisor_judge(s, p, l[0]->k_next, &r);
    to = q->target;
    from = 1 - to;
    ps.u[0] = ps.u[1] = NULL;
    for (i = 0; i < 2; i++)
        if (q->running[i]) {
            if (law_run(s, l[i]))
                return -1;
            law_told(s, l[i]);
            ps.u[i] = l[i]->u;
        }
    for (j = 0; j < law->nout; j++) {
        q->held[j] = q->running[from] && b < 1.0 ? (1.0 - b) * ps.u[from][j] + b * ps.u[to][j] : ps.u[to][j];
        s->machine.held_current[law->out_axis[j]] = q->held[j];
    }
    if (sv->hook) {
        ps.pair = p, ps.k = l[0]->k_next, ps.t = s->dae.t, ps.e = l[0]->e, ps.nin = law->nin, ps.r = r, ps.b = b;
        ps.target = to, ps.held = q->held, ps.nout = law->nout;
        sv->hook(sv->hook_data, &ps);
    }
    l[0]->k_next++;
    l[1]->k_next++;
    s->monitor.stats.controller_samples += 2; /* each law's instants */
    return 0;
}

int td_sim_sampler_take_due(td_sim *s)
{
    double due = s->dae.t + TD_SIM_DUE_TOLERANCE(s->dae.t);
    int i, taken = 0;
    if (s->sampler->failed)
        return -1;
    for (i = 0; i < s->sampler->n; i++) {
        td_sim_sampled *l = &s->sampler->law[i];
        /* the times must rise: a rate too high for t's precision would take one instant forever (the
         * model bounds the rate, TD_CONTROLLER_RATE_MAX; the step loop then reports no progress) */
        while (sample_time(l, l->k_next) <= due &&
               (l->k_next == 0 || sample_time(l, l->k_next) > sample_time(l, l->k_next - 1))) {
            if (l->pair >= 0 ? take_pair(s, l->pair) : take_sample(s, l)) /* a pair's laws together */
                return -1;
            taken++;
        }
    }
    return taken;
}

td_status td_sim_sampler_failure(td_sim *s)
{
    if (!s->sampler || !s->sampler->failed)
        return TD_OK;
    memcpy(s->errmsg, s->sampler->failure.message, sizeof s->errmsg);
    return TD_ERR_INVALID;
}
