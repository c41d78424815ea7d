/*
 * A PD plug-in controller (touchdown/plugin.h) for the tests: on each of its axes j (input j read,
 * output j commanded; n_inputs == n_outputs),
 *
 *   i_j(k) = -(b0 xs_j(k) + b1 xs_j(k - 1)),   b0 = kp + kd fs,  b1 = -kd fs,   xs_j(-1) = 0,
 *
 * the PD kp xs + kd (xs(k) - xs(k - 1)) fs with a backward-difference derivative at the sample rate
 * fs, written as its difference equation: term by term the sampled transfer function
 * b0 + b1 z^-1 (touchdown/controller.h) acting on e = -xs. Parameters: kp (A/m) and kd (A s/m),
 * both required; force_gain (N/A, default 1) multiplies the commands, for a table whose output is
 * TD_PLUGIN_FORCE (the simulation divides by ki). Nothing but this header and the C library.
 */
#include "touchdown/plugin.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct pd {
    int n;
    double b0, b1, gain;
    double *last; /* xs(k - 1) per axis */
} pd;

/* Parameter `name` of the setup into *v; 0 when it is not given. */
static int parameter(const td_plugin_setup *s, const char *name, double *v)
{
    int i;
    for (i = 0; i < s->n_parameters; i++)
        if (strcmp(s->parameter_names[i], name) == 0) {
            *v = s->parameter_values[i];
            return 1;
        }
    return 0;
}

static void *pd_init(const td_plugin_setup *s, char *message, int message_size)
{
    double kp, kd;
    pd *c;
    int i;
    if (s->n_inputs != s->n_outputs) {
        snprintf(message, (size_t)message_size, "pd: %d inputs but %d outputs (one output per input)", s->n_inputs,
                 s->n_outputs);
        return NULL;
    }
    for (i = 0; i < s->n_parameters; i++)
        if (strcmp(s->parameter_names[i], "kp") && strcmp(s->parameter_names[i], "kd") &&
            strcmp(s->parameter_names[i], "force_gain")) {
            snprintf(message, (size_t)message_size, "pd: unknown parameter \"%s\" (kp, kd, force_gain)",
                     s->parameter_names[i]);
            return NULL;
        }
    if (!parameter(s, "kp", &kp) || !parameter(s, "kd", &kd)) {
        snprintf(message, (size_t)message_size, "pd: parameters kp and kd are required");
        return NULL;
    }
    c = calloc(1, sizeof *c);
    if (!c || !(c->last = calloc((size_t)s->n_inputs, sizeof *c->last))) {
        free(c);
        snprintf(message, (size_t)message_size, "pd: out of memory");
        return NULL;
    }
    c->n = s->n_inputs;
    c->b0 = kp + kd * s->sample_rate;
    c->b1 = -kd * s->sample_rate;
    c->gain = 1.0;
    parameter(s, "force_gain", &c->gain);
    return c;
}

static int pd_step(void *instance, long k, double t, const double *sensed, double *command, char *message,
                   int message_size)
{
    pd *c = instance;
    int j;
    (void)k, (void)t, (void)message, (void)message_size;
    for (j = 0; j < c->n; j++) {
        command[j] = -(c->b0 * sensed[j] + c->b1 * c->last[j]);
        if (c->gain != 1.0)
            command[j] *= c->gain;
        c->last[j] = sensed[j];
    }
    return 0;
}

static int pd_reset(void *instance, char *message, int message_size)
{
    pd *c = instance;
    (void)message, (void)message_size;
    memset(c->last, 0, (size_t)c->n * sizeof *c->last);
    return 0;
}

static void pd_free(void *instance)
{
    pd *c = instance;
    if (c)
        free(c->last);
    free(c);
}

static const td_plugin_controller table = {
    TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, pd_init, pd_step, pd_reset, pd_free};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
