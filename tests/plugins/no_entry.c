/*
 * A bad plug-in for the tests: a shared library that exports no td_plugin_controller_entry (its
 * author named the function otherwise). Loading it must fail, naming the missing symbol.
 */
#include "touchdown/plugin.h"

#include <stddef.h>

TD_PLUGIN_EXPORT const td_plugin_controller *controller_entry(void);

TD_PLUGIN_EXPORT const td_plugin_controller *controller_entry(void)
{
    return NULL;
}
