/*
 * A PID controller as a touchdown plug-in (touchdown/plugin.h): the code a DSP would run, loaded by
 * the simulation from a shared library and called at every sample. On each axis j it reads the
 * sensed displacement xs and commands the amplifier's current
 *
 *   e_k = -xs_k,   i_k = q1 e_{k-1} + s_k + q0 e_k,   s_{k+1} = s_k + (ki / fs) e_k,
 *
 * with q0 = kp + kd fs and q1 = -kd fs: kp e + kd times the backward-difference velocity
 * (e_k - e_{k-1}) fs + ki times the running sum of e / fs, at the sample rate fs. Each axis's
 * sensor drives its own amplifier (a decentralised law), so the controller takes the same axes in
 * and out. The sum is formed in the order touchdown's own sampled law forms i = C x + D e (from 0,
 * the state terms first), so the built-in law with the same numbers gives the same bits
 * (README.md here).
 *
 * Parameters (the case's `plugin.parameters`): kp (A/m), kd (A s/m), ki (A/(m s)); each 0 when
 * absent. Build: make (needs only the installed touchdown/plugin.h).
 */
#include <touchdown/plugin.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct pid {
    int n;             /* axes */
    double q0, q1, kt; /* kp + kd fs, -kd fs, ki / fs */
    double *e_prev;    /* e_{k-1} per axis */
    double *sum;       /* s_k per axis */
} pid;

static void pid_free(void *instance)
{
    pid *c = instance;
    if (!c)
        return;
    free(c->e_prev);
    free(c->sum);
    free(c);
}

/* The gains from the parameters: kp, kd and ki, each once; anything else is refused by name. */
static int read_gains(const td_plugin_setup *s, double *kp, double *kd, double *ki, char *message, int size)
{
    int i;
    *kp = *kd = *ki = 0.0;
    for (i = 0; i < s->n_parameters; i++) {
        const char *name = s->parameter_names[i];
        double v = s->parameter_values[i];
        if (strcmp(name, "kp") == 0)
            *kp = v;
        else if (strcmp(name, "kd") == 0)
            *kd = v;
        else if (strcmp(name, "ki") == 0)
            *ki = v;
        else {
            snprintf(message, (size_t)size, "unknown parameter '%s' (this PID takes kp, kd and ki)", name);
            return -1;
        }
    }
    return 0;
}

static void *pid_init(const td_plugin_setup *s, char *message, int size)
{
    double kp, kd, ki;
    pid *c;
    int j;
    if (read_gains(s, &kp, &kd, &ki, message, size))
        return NULL;
    if (s->n_inputs != s->n_outputs) {
        snprintf(message, (size_t)size, "each sensor drives its own amplifier: %d inputs, %d outputs", s->n_inputs,
                 s->n_outputs);
        return NULL;
    }
    for (j = 0; j < s->n_inputs; j++)
        if (s->input_axes[j] != s->output_axes[j]) {
            snprintf(message, (size_t)size, "input %d reads axis %d but output %d drives axis %d", j, s->input_axes[j],
                     j, s->output_axes[j]);
            return NULL;
        }
    c = calloc(1, sizeof *c);
    if (!c || !(c->e_prev = calloc((size_t)s->n_inputs, sizeof(double))) ||
        !(c->sum = calloc((size_t)s->n_inputs, sizeof(double)))) {
        pid_free(c);
        snprintf(message, (size_t)size, "out of memory");
        return NULL;
    }
    c->n = s->n_inputs;
    c->q0 = kp + kd * s->sample_rate;
    c->q1 = -kd * s->sample_rate;
    c->kt = ki / s->sample_rate;
    return c; /* at rest: e_{-1} = 0, s_0 = 0 */
}

static int pid_step(void *instance, long k, double t, const double *sensed, double *command, char *message, int size)
{
    pid *c = instance;
    int j;
    (void)k;
    (void)t;
    (void)message;
    (void)size;
    for (j = 0; j < c->n; j++) {
        double e = -sensed[j], i = 0.0;
        i += c->q1 * c->e_prev[j];
        i += c->sum[j];
        i += c->q0 * e;
        command[j] = i;
        c->e_prev[j] = e;
        c->sum[j] += c->kt * e;
    }
    return 0;
}

static int pid_reset(void *instance, char *message, int size)
{
    pid *c = instance;
    (void)message;
    (void)size;
    memset(c->e_prev, 0, (size_t)c->n * sizeof(double));
    memset(c->sum, 0, (size_t)c->n * sizeof(double));
    return 0;
}

static const td_plugin_controller table = {
    TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, pid_init, pid_step, pid_reset, pid_free};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
