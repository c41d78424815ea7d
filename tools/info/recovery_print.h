/* `touchdown info`'s account of a case's recovery supervisor. */
#ifndef TD_TOOLS_RECOVERY_PRINT_H
#define TD_TOOLS_RECOVERY_PRINT_H

#include "touchdown/model.h"

#include <stdio.h>

/* The supervisor of model m (nothing when it has none): on or off, its pairs by name, the rules
 * with their thresholds in m (fractions of the smallest retainer clearance) and dwells in samples,
 * and the blend. */
void td_print_recovery(FILE *f, const td_model *m);

#endif
