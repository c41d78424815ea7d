/* `touchdown info`'s account of a case's controllers, linear laws and plug-ins. */
#ifndef TD_TOOLS_CONTROLLER_PRINT_H
#define TD_TOOLS_CONTROLLER_PRINT_H

#include "touchdown/case.h"

#include <stdio.h>

/* What the tool shows of controller i of m, a linear law or a plug-in alike. */
typedef struct td_controller_view {
    const char *name;             /* never NULL */
    const td_controller *law;     /* the linear law, or NULL: a plug-in */
    const td_plugin_spec *plugin; /* the plug-in, or NULL: a linear law */
    double sample_rate;           /* Hz; 0: continuous */
    int n_inputs, n_outputs;
    const int *inputs, *outputs; /* AMB axes, 2 amb + axis */
} td_controller_view;
void td_controller_view_get(const td_model *m, int i, td_controller_view *v);

/* The controller that drives AMB `amb` of model m (an output on one of its axes), or -1. */
int td_amb_controller(const td_model *m, int amb);
/* Each controller of the case: its name, AMBs, coordinates, order, timing (continuous, or its
 * sample rate, discretisation (or "written in z") and delay), then its poles in Hz with their
 * damping ratios; a plug-in: its library, ABI, output, rate, delay and parameters. */
void td_print_controllers(FILE *f, const td_case *c);

#endif
