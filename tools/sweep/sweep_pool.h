/* touchdown sweep: the worker processes that run a sweep's points (tools/sweep/sweep_pool.c). */
#ifndef TD_TOOLS_SWEEP_POOL_H
#define TD_TOOLS_SWEEP_POOL_H

#include "common/cli.h"
#include "touchdown/sweep.h"

/* Most worker processes (-j). */
#define TD_SWEEP_POOL_MAX 256
/* Longest --point-timeout, s (a year). */
#define TD_SWEEP_POOL_TIMEOUT_MAX 3.2e7

/* What every point shares: the case file, the fixed overrides and the grid (all borrowed), and
 * the directory of the points' own result files (NULL: none; else DIR/point-NNNNNN.h5, and .csv
 * when point_csv), and the wall time a point may take before its worker is stopped (0: no limit). */
typedef struct sweep_job {
    const char *case_path;
    const td_cli_sets *sets;
    const td_sweep_grid *grid;
    const char *point_dir;
    int point_csv;
    double point_timeout;
} sweep_job;

/* The result files of `point` kept by --point-files into out's paths: DIR/point-NNNNNN.h5, and
 * DIR/point-NNNNNN.csv with --point-csv (its events file follows from it); "" for a file not kept.
 * Returns 0, or -1 when a path does not fit (its path is then ""). */
int sweep_point_paths(const sweep_job *job, long point, td_output_options *out);

/* The overrides of `point`: the fixed ones, then one "KEY=VALUE" per swept key, into items
 * (pointers into store, which holds TD_SWEEP_MAX_KEYS strings). Returns their number. */
int sweep_point_overrides(const sweep_job *job, long point, const char **items,
                          char store[][TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE]);

/* sweep_feed.next: no point now (ask again next turn), or none ever again. */
#define SWEEP_FEED_WAIT (-1L)
#define SWEEP_FEED_END (-2L)

/* Where a pool's points come from and where their rows go: the points of this process alone, or
 * those rank 0 of an MPI run hands out (tools/sweep/sweep_mpi.c). */
typedef struct sweep_feed {
    /* The next point to run, SWEEP_FEED_WAIT or SWEEP_FEED_END. */
    long (*next)(void *ctx);
    /* The row of `point`: its run's (ran = 1), or "worker died" (ran = 0: not recorded in a
     * journal, so that a resume retries it). */
    void (*finished)(void *ctx, long point, const td_sweep_row *row, int ran);
    /* Once a turn, after the wait for the workers (may be NULL): nonzero stops the pool as a
     * signal does. */
    int (*service)(void *ctx);
    void *ctx;
    int wait_ms; /* longest wait for the workers in a turn: how soon service runs */
} sweep_feed;

/* Run the points `feed` gives in up to `jobs` worker processes, one point per process, each
 * point handed to the next free worker, until the feed has no more and every worker has ended.
 * Stops early when *cancel becomes nonzero or the feed's service says so: running workers are
 * killed and their points get no row. */
void sweep_pool_serve(const sweep_job *job, int jobs, const sweep_feed *feed, volatile sig_atomic_t *cancel);

/* Report a failed point on stderr: "touchdown sweep: point P (KEY=VALUE ...): STATUS: MESSAGE". */
void sweep_report_failure(const sweep_job *job, long point, const td_sweep_row *row);

#endif
