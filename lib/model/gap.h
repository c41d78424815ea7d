/* The machine's smallest gap and the solver.atol bound it sets, shared by the case reader and the
 * simulation. */
#ifndef TD_MODEL_GAP_H
#define TD_MODEL_GAP_H

#include <stddef.h>

#include "touchdown/model.h"
#include "util/limits.h"

/* The machine's smallest gap: the least retainer clearance and nonzero AMB air gap of model m, m;
 * infinity when it has none. *retainer and *amb (either may be NULL) get the index of the part
 * that has it (-1 for the other kind, both -1 when none). */
double td_model_smallest_gap(const td_model *m, int *retainer, int *amb);

/* solver.atol against the smallest gap of m (TD_MAX_ATOL_FRACTION): TD_LIMIT_NONE, or
 * TD_LIMIT_ATOL with `why` (n bytes) saying which gap bounds it and by how much. */
td_run_limit td_atol_limit_check(const td_model *m, double atol, char *why, size_t n);

#endif
