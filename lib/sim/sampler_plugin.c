/*
 * A plug-in law's samples (touchdown/plugin.h; the sampler's, sampler.h): its instance made by its
 * init when the simulation is created and released with it, and at each sample k
 *
 *   xs_k = -e_k (exact: a negation),   c_k = step(k, t_k, xs_k),
 *   i_k = c_k (TD_PLUGIN_CURRENT) or c_k / ki (TD_PLUGIN_FORCE: the amplifier's force ki i is c_k),
 *   held  i_{k - delay} (0 for the first `delay` samples: the law starts at rest)
 *
 * the delay as a built-in law's z^-delay (td_controller_delay). A nonzero return, or a command
 * that is not finite, fails the run there with the plug-in's reason: the held currents stay those
 * of the sample before, and the simulation refuses to go on (sampler.failed).
 */
#include "sim/sampler.h"
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

/* A plug-in's reason as one line: NUL-terminated inside its buffer, cut at the first line break,
 * and never empty. */
static const char *one_line(char *why, size_t size, const char *none)
{
    why[size - 1] = '\0';
    why[strcspn(why, "\r\n")] = '\0';
    return why[0] ? why : none;
}

/* A new instance of law l's plug-in (init) into *instance; TD_ERR_INVALID with its reason. */
static td_status new_instance(const td_sim *s, const td_sim_sampled *l, void **instance, td_error *err)
{
    const td_plugin_spec *p = s->sys->laws[l->law].plugin;
    td_plugin_setup setup;
    char why[TD_ERROR_MESSAGE_SIZE / 2];
    td_plugin_spec_setup(p, &setup);
    why[0] = '\0';
    *instance = p->functions->init(&setup, why, (int)sizeof why);
    if (!*instance)
        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"controller", l->law, NULL}, &no_site,
                                 "plug-in \"%s\" init failed: %s", p->name,
                                 one_line(why, sizeof why, "no reason given"));
    return TD_OK;
}

/* The probe's displacement, m: a power of two, so that c(-h e_j) / h is a linear plug-in's gain to
 * the last bit, and small, so that a plug-in that clips its command still answers linearly. */
#define TD_PLUGIN_PROBE 0x1p-20

/* Law l's direct gain into l->gain (nout x nin, column-major): a linear law's D, the current per
 * unit error e = -xs at the sample it is read (a force table's force per unit error over ki),
 * which sets the scale of the amplifier's force for the tolerances and the step bound
 * (lib/sim/setup.c), never the dynamics. From a second instance at rest: its first command for
 * xs = -h e_j less its first for xs = 0, over h, reset between, then freed. A probe that fails, or
 * is not finite, leaves the gain 0 (the run reports the failure where it happens), as does a
 * non-linear law that does not answer h (a deadband wider than it): setup.c's law_gain then takes
 * the magnet's |ks| as the scale, never 0. */
static td_status probe_gain(const td_sim *s, td_sim_sampled *l, td_error *err)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    const td_plugin_controller *f = law->plugin->functions;
    double *c0 = l->cmd, *c1 = l->gain + (size_t)law->nin * (size_t)law->nout, t0 = l->t0;
    char why[TD_ERROR_MESSAGE_SIZE / 2];
    void *probe = NULL;
    int i, j, ok;
    td_status st = new_instance(s, l, &probe, err);
    if (st != TD_OK)
        return st;
    memset(l->xs, 0, (size_t)law->nin * sizeof *l->xs);
    ok = f->step(probe, 0, t0, l->xs, c0, why, (int)sizeof why) == 0;
    for (j = 0; ok && j < law->nin; j++) {
        ok = f->reset(probe, why, (int)sizeof why) == 0;
        l->xs[j] = -TD_PLUGIN_PROBE;
        ok = ok && f->step(probe, 0, t0, l->xs, c1, why, (int)sizeof why) == 0;
        l->xs[j] = 0.0;
        for (i = 0; ok && i < law->nout; i++) {
            double g = (c1[i] - c0[i]) / TD_PLUGIN_PROBE;
            if (f->output == TD_PLUGIN_FORCE) /* N/m: the current's gain is that over ki (ki != 0, model) */
                g /= s->sys->amb_axes[law->out_axis[i]].ki;
            l->gain[i + (size_t)law->nout * (size_t)j] = isfinite(g) ? g : 0.0;
        }
    }
    f->free(probe);
    if (!ok)
        memset(l->gain, 0, (size_t)law->nin * (size_t)law->nout * sizeof *l->gain);
    return TD_OK;
}

td_status td_sim_plugin_init(td_sim *s, td_sim_sampled *l, td_error *err)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    size_t nq = (size_t)law->plugin->delay * (size_t)law->nout, nin = (size_t)law->nin, nout = (size_t)law->nout;
    td_status st;
    l->xs = calloc(nin, sizeof *l->xs);
    l->cmd = calloc(nout, sizeof *l->cmd);
    l->queue = calloc(nq + 1, sizeof *l->queue);
    l->gain = calloc(nin * nout + nout, sizeof *l->gain); /* + the probe's commands */
    if (!l->xs || !l->cmd || !l->queue || !l->gain)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    st = new_instance(s, l, &l->instance, err);
    if (st == TD_OK)
        st = probe_gain(s, l, err);
    return st;
}

double td_sim_plugin_gain(const td_sim *s, int law, int output)
{
    const td_lti_law *L = &s->sys->laws[law];
    double g = 0.0;
    int i, m;
    for (i = 0; s->sampler && i < s->sampler->n; i++)
        if (s->sampler->law[i].law == law)
            for (m = 0; m < L->nin; m++)
                g = fmax(g, fabs(s->sampler->law[i].gain[output + (size_t)m * (size_t)L->nout]));
    return g;
}

void td_sim_plugin_free(const td_sim *s, td_sim_sampled *l)
{
    if (l->instance)
        s->sys->laws[l->law].plugin->functions->free(l->instance);
    l->instance = NULL;
    free(l->xs);
    free(l->cmd);
    free(l->queue);
    free(l->gain);
}

/* The run stops at law l's sample k: its error, the controller its site, kept by the sampler and its
 * message in s->errmsg. Returns -1. */
static int plugin_failed(td_sim *s, const td_sim_sampled *l, long k, double t, const char *reason)
{
    const td_plugin_spec *p = s->sys->laws[l->law].plugin;
    td_error_set_site(&s->sampler->failure, TD_ERR_INVALID, &(td_error_site){"controller", l->law, NULL}, &no_site,
                      "plug-in \"%s\" failed at sample %ld (t = %.9g s): %s", p->name, k, t, reason);
    s->sampler->failed = 1;
    memcpy(s->errmsg, s->sampler->failure.message, sizeof s->errmsg);
    return -1;
}

int td_sim_plugin_error(const td_sim *s, td_status st, td_error *err)
{
    const td_sim_sampler *sp = s->sampler;
    if (!sp || !sp->failed || st != TD_ERR_INVALID || strcmp(s->errmsg, sp->failure.message) != 0)
        return 0;
    if (err)
        *err = sp->failure;
    return 1;
}

/* The commands of step k as currents, each finite; -1 (failed) otherwise. */
static int plugin_currents(td_sim *s, td_sim_sampled *l, long k, double t)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    int force = law->plugin->functions->output == TD_PLUGIN_FORCE, j;
    for (j = 0; j < law->nout; j++) {
        const td_amb_axis *a = &s->sys->amb_axes[law->out_axis[j]];
        char why[160];
        if (!isfinite(l->cmd[j])) {
            snprintf(why, sizeof why, "command %d (AMB %d %s) is %g, not a finite %s", j, a->amb, a->axis ? "y" : "x",
                     l->cmd[j], force ? "force" : "current");
            return plugin_failed(s, l, k, t, why);
        }
        if (force) /* the amplifier makes ki i: the current whose force is the command (ki != 0, model) */
            l->cmd[j] /= a->ki;
    }
    return 0;
}

int td_sim_plugin_step(td_sim *s, td_sim_sampled *l, long k, double t)
{
    const td_lti_law *law = &s->sys->laws[l->law];
    const td_plugin_controller *f = law->plugin->functions;
    int delay = law->plugin->delay, j;
    char why[TD_ERROR_MESSAGE_SIZE / 2];
    why[0] = '\0';
    if (l->reset_due) {
        l->reset_due = 0;
        memset(l->queue, 0, (size_t)delay * (size_t)law->nout * sizeof *l->queue);
        if (f->reset(l->instance, why, (int)sizeof why) != 0)
            return plugin_failed(s, l, k, t, one_line(why, sizeof why, "reset failed (no reason given)"));
    }
    for (j = 0; j < law->nin; j++)
        l->xs[j] = -l->e[j];
    for (j = 0; j < law->nout; j++)
        l->cmd[j] = NAN; /* a command the step leaves unwritten is not finite: caught */
    if (f->step(l->instance, k, t, l->xs, l->cmd, why, (int)sizeof why) != 0)
        return plugin_failed(s, l, k, t, one_line(why, sizeof why, "step failed (no reason given)"));
    if (plugin_currents(s, l, k, t))
        return -1;
    for (j = 0; j < law->nout; j++) {
        double *slot = delay > 0 ? &l->queue[(size_t)(k % delay) * (size_t)law->nout + (size_t)j] : NULL;
        l->u[j] = slot ? *slot : l->cmd[j];
        if (slot)
            *slot = l->cmd[j];
    }
    return 0;
}
