/*
 * A bad plug-in for the tests: its init ends the process with exit(0), a success status though it
 * never returned. The tool's probe of its init, step and free in a child must not take that status
 * for a probe that went through; nor may the run that follows. Loading it
 * (td_model_add_plugin_controller) calls no init and must succeed.
 */
#include "touchdown/plugin.h"

#include <stddef.h>
#include <stdlib.h>

static void *exits_init(const td_plugin_setup *s, char *message, int message_size)
{
    (void)s, (void)message, (void)message_size;
    exit(0);
}

static int exits_step(void *instance, long k, double t, const double *sensed, double *command, char *message,
                      int message_size)
{
    (void)instance, (void)k, (void)t, (void)sensed, (void)command, (void)message, (void)message_size;
    return 1;
}

static int exits_reset(void *instance, char *message, int message_size)
{
    (void)instance, (void)message, (void)message_size;
    return 1;
}

static void exits_free(void *instance)
{
    (void)instance;
}

static const td_plugin_controller table = {TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, exits_init, exits_step,
                                           exits_reset,           exits_free};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
