/* `touchdown info`'s account of a case's linear controllers. */
#ifndef TD_TOOLS_CONTROLLER_PRINT_H
#define TD_TOOLS_CONTROLLER_PRINT_H

#include "touchdown/case.h"

#include <stdio.h>

/* The controller that drives AMB `amb` of model m (an output on one of its axes), or -1. */
int td_amb_controller(const td_model *m, int amb);
/* Each controller of the case: its name, AMBs, coordinates, order, timing (continuous, or its
 * sample rate, discretisation (or "written in z") and delay), then its poles in Hz with their damping ratios. */
void td_print_controllers(FILE *f, const td_case *c);

#endif
