/* touchdown sweep: the worker processes that run a sweep's points (tools/sweep_pool.c). */
#ifndef TD_TOOLS_SWEEP_POOL_H
#define TD_TOOLS_SWEEP_POOL_H

#include "cli.h"
#include "sweep_journal.h"
#include "touchdown/sweep.h"

/* Most worker processes (-j). */
#define TD_SWEEP_POOL_MAX 256

/* What every point shares: the case file, the fixed overrides and the grid (all borrowed), the
 * journal that records each row as it arrives (NULL: none), and the directory of the points' own
 * result files (NULL: none; else DIR/point-NNNNNN.h5, and .csv when point_csv). */
typedef struct sweep_job {
    const char *case_path;
    const td_cli_sets *sets;
    const td_sweep_grid *grid;
    sweep_journal *journal;
    const char *point_dir;
    int point_csv;
} sweep_job;

/* The name of point `point`'s result file with extension `ext` (".h5", ".csv") in `dir`. */
#define SWEEP_POINT_FILE "%s/point-%06ld%s"

/* The overrides of `point`: the fixed ones, then one "KEY=VALUE" per swept key, into items
 * (pointers into store, which holds TD_SWEEP_MAX_KEYS strings). Returns their number. */
int sweep_point_overrides(const sweep_job *job, long point, const char **items,
                          char store[][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE]);

/* Run every point whose row is still "not run" (the others were resumed from the journal) in up to
 * `jobs` worker processes, one point per process, each point handed to the next free worker, and
 * put each point's row at rows[point], recording in the journal the rows the points' runs sent. Stops early when
 * *cancel becomes nonzero: running workers are killed and their points stay "not run". Failed points are reported on
 * stderr as they end. Returns the number of points left not run. */
long sweep_pool_run(const sweep_job *job, int jobs, td_sweep_row *rows, volatile sig_atomic_t *cancel);

#endif
