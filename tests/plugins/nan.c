/*
 * A bad plug-in for the tests: it commands 0 A on its outputs for samples 0, 1 and 2 and NaN from
 * sample 3 on (a division by zero in a user's law, say). The simulation must stop at sample 3 with
 * the reason, never integrate the NaN.
 */
#include "touchdown/plugin.h"

#include <math.h>
#include <stdlib.h>

typedef struct nan_law {
    int n;
} nan_law;

static void *nan_init(const td_plugin_setup *s, char *message, int message_size)
{
    nan_law *c = malloc(sizeof *c);
    (void)message, (void)message_size;
    if (c)
        c->n = s->n_outputs;
    return c;
}

static int nan_step(void *instance, long k, double t, const double *sensed, double *command, char *message,
                    int message_size)
{
    const nan_law *c = instance;
    int j;
    (void)t, (void)sensed, (void)message, (void)message_size;
    for (j = 0; j < c->n; j++)
        command[j] = k >= 3 ? NAN : 0.0;
    return 0;
}

static int nan_reset(void *instance, char *message, int message_size)
{
    (void)instance, (void)message, (void)message_size;
    return 0;
}

static void nan_free(void *instance)
{
    free(instance);
}

static const td_plugin_controller table = {
    TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, nan_init, nan_step, nan_reset, nan_free};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
