/* Why a run's result may be suspect: the rules, each checked once, at the end of td_run
 * (lib/run/warnings.c; docs/output-format.md, "Warnings"). */
#ifndef TD_RUN_WARNINGS_H
#define TD_RUN_WARNINGS_H

#include "touchdown/output.h"
#include "touchdown/run.h"

/** Append the warnings of a run of model `m` with output options `out` from s->t_start towards
 *  s->t_end that ended with summary `s` (its statistics and section filled) to s->warnings. */
void td_run_check_warnings(td_run_summary *s, const td_model *m, const td_output_options *out);

#endif
