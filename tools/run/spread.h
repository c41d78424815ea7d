/* touchdown run --spread N: the other members of the run's ensemble and the spread of its answers
 * (touchdown/run.h, td_spread_run in touchdown/job.h). */
#ifndef TD_TOOLS_RUN_SPREAD_H
#define TD_TOOLS_RUN_SPREAD_H

#include "touchdown/job.h"

#include <signal.h>

/* --spread N: an odd whole number TD_SPREAD_MIN_MEMBERS..TD_SPREAD_MAX_MEMBERS into *n; else a
 * one-line error and TD_EXIT_USAGE. Returns 0 when it is one. */
int td_run_spread_parse(const char *text, int *n);

/* Run members 1..n-1 of the ensemble of `job`, whose run as given is `run` (member 0), with a
 * progress line on stderr when `progress` (a terminal), stopping when *cancel is set; gather the
 * spread into `out`. Prints a line on stderr when the ensemble was interrupted. Returns 0, or the
 * exit code of an interrupted ensemble (its members not run are counted as failed in `out`);
 * out->members is 0 when nothing could be gathered (no memory). */
int td_run_spread(const td_job *job, const td_run_summary *run, int n, int progress, volatile sig_atomic_t *cancel,
                  td_spread *out);

#endif
