/*
 * A bad plug-in for the tests: its init refuses every setup with a reason (a parameter it needs is
 * missing, say). The simulation must not be created, and must say the plug-in's reason.
 */
#include "touchdown/plugin.h"

#include <stdio.h>

static void *refuse_init(const td_plugin_setup *s, char *message, int message_size)
{
    snprintf(message, (size_t)message_size, "refuse: gain schedule \"%s\" needs parameter \"table\"", s->name);
    return NULL;
}

static int refuse_step(void *instance, long k, double t, const double *sensed, double *command, char *message,
                       int message_size)
{
    (void)instance, (void)k, (void)t, (void)sensed, (void)command, (void)message, (void)message_size;
    return 1;
}

static int refuse_reset(void *instance, char *message, int message_size)
{
    (void)instance, (void)message, (void)message_size;
    return 1;
}

static void refuse_free(void *instance)
{
    (void)instance;
}

static const td_plugin_controller table = {TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, refuse_init,
                                           refuse_step,           refuse_reset,      refuse_free};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
