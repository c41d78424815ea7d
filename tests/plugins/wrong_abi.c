/*
 * A bad plug-in for the tests: built for the next plug-in ABI version (TD_PLUGIN_ABI_VERSION + 1),
 * whose calls this touchdown does not know. Loading it must fail, naming both versions, before any
 * of its functions is called.
 */
#include "touchdown/plugin.h"

#include <stddef.h>

static const td_plugin_controller table = {TD_PLUGIN_ABI_VERSION + 1, TD_PLUGIN_CURRENT, NULL, NULL, NULL, NULL};

TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void)
{
    return &table;
}
