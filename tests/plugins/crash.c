/*
 * A bad plug-in for the tests: its init writes through a null pointer (SIGSEGV). The library cannot
 * survive that in its own process (it never catches signals): the tool runs a plug-in's init in a
 * child first and reports the signal. Loading it (td_model_add_plugin_controller) calls no init and
 * must succeed.
 */
#include "touchdown/plugin.h"

#include <stddef.h>

static void *crash_init(const td_plugin_setup *s, char *message, int message_size)
{
    volatile int *nowhere = NULL;
    (void)s, (void)message, (void)message_size;
    *nowhere = 1;
    return NULL;
}

static int crash_step(void *instance, long k, double t, const double *sensed, double *command, char *message,
                      int message_size)
{
    (void)instance, (void)k, (void)t, (void)sensed, (void)command, (void)message, (void)message_size;
    return 1;
}

static int crash_reset(void *instance, char *message, int message_size)
{
    (void)instance, (void)message, (void)message_size;
    return 1;
}

static void crash_free(void *instance)
{
    (void)instance;
}

static const td_plugin_controller table = {TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, crash_init, crash_step,
                                           crash_reset,           crash_free};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
