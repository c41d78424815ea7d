/*
 * touchdown/sweep.h - parameter sweeps: a grid of points over case keys, one summary row per
 * point, and the table of rows written to CSV and HDF5 (docs/output-format.md, "Sweep table").
 *
 * A point is the case loaded with the caller's fixed overrides followed by one "KEY=VALUE"
 * override per swept key (td_sweep_grid_override), so any key that td_case_load accepts can be
 * swept and is checked exactly as `--set` is. Running the points (in worker processes, threads or
 * one after another) is the caller's business: the library builds the grid, turns a run summary
 * into a row, and writes the table.
 */
#ifndef TOUCHDOWN_SWEEP_H
#define TOUCHDOWN_SWEEP_H

#include <stddef.h>

#include "touchdown/case.h"
#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/run.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most points in one sweep (the product of the axes' counts); bounds the table's memory
 *  (about 1.5 kB a row) before anything runs. */
#define TD_SWEEP_MAX_POINTS 100000L
/** Most axes (the factors of the full grid). */
#define TD_SWEEP_MAX_AXES 8
/** Most swept keys in all, zipped keys included. */
#define TD_SWEEP_MAX_KEYS 16
/** Longest value text of one point on one axis, NUL included. */
#define TD_SWEEP_VALUE_SIZE 128
/** Longest swept key, NUL included. */
#define TD_SWEEP_KEY_SIZE 128

typedef struct td_sweep_grid td_sweep_grid;

/** A new grid without axes (one point: the case itself). Caller frees with td_sweep_grid_free.
 *  Returns TD_OK, TD_ERR_NOMEM or TD_ERR_INVALID (NULL out). */
TD_API td_status td_sweep_grid_create(td_sweep_grid **out, td_error *err);

/** Free a grid and set *g to NULL. Accepts NULL and *g == NULL. */
TD_API void td_sweep_grid_free(td_sweep_grid **g);

/**
 * Add an axis from `spec` (copied):
 *   "KEY=START:STOP:N"         N >= 1 points from START to STOP evenly spaced, both included
 *                              (N = 1: START alone); "KEY=START:STOP:N:linear" is the same;
 *   "KEY=START:STOP:N:log"     N points in geometric progression (a constant ratio), START and
 *                              STOP > 0, both included exactly;
 *   "KEY=V1,V2,..."            a list of values as --set takes them (numbers, true/false,
 *                              "quoted strings", bare strings; commas inside quotes or brackets
 *                              do not split).
 * The first axis added varies slowest. Returns TD_OK, or TD_ERR_PARSE with one line
 * "--vary 'SPEC': why" (bad syntax, N < 1, a log end <= 0, a range with N > 2 whose STOP - START
 * (linear) or STOP / START (log) a double cannot hold, an empty value, a key given twice,
 * more than TD_SWEEP_MAX_AXES axes, TD_SWEEP_MAX_KEYS keys or TD_SWEEP_MAX_POINTS points in all);
 * the grid is unchanged on failure. The key itself is checked only when a point's case is loaded.
 */
TD_API td_status td_sweep_grid_vary(td_sweep_grid *g, const char *spec, td_error *err);

/**
 * Add key `spec` (the forms of td_sweep_grid_vary) to the last axis added: zipped, it moves with
 * that axis's keys, its i-th value going with theirs, so it must have as many values. Errors as
 * td_sweep_grid_vary, "--with 'SPEC': why"; a count that differs names both keys, and a grid
 * without axes has nothing to join.
 */
TD_API td_status td_sweep_grid_with(td_sweep_grid *g, const char *spec, td_error *err);

/**
 * Judge the case's `sweep` group (td_case_sweep_spec) on its own by the rules of
 * td_sweep_grid_vary and td_sweep_grid_with, in the order of the file. td_case_load checks only
 * the group's shape (its keys, the types of their values, a key to sweep); these rules are the
 * grid's, so call this once a case is loaded (the tool does for every command, so that a bad
 * group is found whichever command loads the case). Returns TD_OK (also without a group),
 * TD_ERR_INVALID (NULL c), TD_ERR_NOMEM, or TD_ERR_PARSE with one line naming the entry and the
 * setting at fault, "FILE:LINE: sweep.vary[i].points: why" ("...vary[i].with[j].values: ...",
 * "...vary[i]: ..." for the entry as a whole).
 */
TD_API td_status td_sweep_check_case(const td_case *c, td_error *err);

/**
 * Add the axes of the case's `sweep` group (td_case_sweep_spec) after g's own: each axis of the
 * case that has a key g already sweeps is left out whole (the caller's axes replace the file's).
 * The group is judged first (td_sweep_check_case, its errors; g is then unchanged); what is left
 * to fail is a limit on axes, keys or points reached with g's own, an error "FILE:LINE:
 * sweep.vary[i]: why". Each axis added has that "FILE:LINE: sweep.vary[i]" as its origin
 * (td_sweep_grid_origin).
 */
TD_API td_status td_sweep_grid_from_case(td_sweep_grid *g, const td_case *c, td_error *err);

/** Number of points (1 for a grid without axes). */
TD_API long td_sweep_grid_points(const td_sweep_grid *g);
/** Number of axes. */
TD_API int td_sweep_grid_axes(const td_sweep_grid *g);
/** Number of swept keys (at least the number of axes; more with zipped keys). Keys are numbered
 *  0 .. td_sweep_grid_keys - 1 in the order added; the functions below take such a number `k`. */
TD_API int td_sweep_grid_keys(const td_sweep_grid *g);
/** The swept key `k` (borrowed). */
TD_API const char *td_sweep_grid_key(const td_sweep_grid *g, int k);
/** The spec key `k` was made from, as given (borrowed). */
TD_API const char *td_sweep_grid_spec(const td_sweep_grid *g, int k);
/** The axis of key `k` (keys on one axis are zipped). */
TD_API int td_sweep_grid_axis(const td_sweep_grid *g, int k);
/** Where the axis of key `k` came from (borrowed): "command line" for td_sweep_grid_vary, the
 *  case file's "FILE:LINE: sweep.vary[i]" for td_sweep_grid_from_case. */
TD_API const char *td_sweep_grid_origin(const td_sweep_grid *g, int k);
/** 1 if every value of key `k` is a number (the table then stores it as a double). */
TD_API int td_sweep_grid_numeric(const td_sweep_grid *g, int k);
/** The value text of key `k` at `point` (0 <= point < td_sweep_grid_points), borrowed. Range
 *  values are printed with the fewest digits (15-17) that read back to the same double. */
TD_API const char *td_sweep_grid_value(const td_sweep_grid *g, long point, int k);
/** "KEY=VALUE" of key `k` at `point` into buf (n bytes, always NUL-terminated when n > 0);
 *  returns the length needed, like snprintf. */
TD_API int td_sweep_grid_override(const td_sweep_grid *g, long point, int k, char *buf, size_t n);

/** What became of a point. */
typedef enum td_sweep_state {
    TD_SWEEP_NOT_RUN = 0, /**< never run, or stopped by an interrupt of the sweep */
    TD_SWEEP_DONE = 1,    /**< the run reached its end */
    TD_SWEEP_FAILED = 2   /**< the run failed (its status and message say why) or its worker died */
} td_sweep_state;

/** One row of the table: what a point's run summary leads with. A point that did not run to its
 *  end (failed, timed out, worker died, not run) has no answers: its numbers are TD_UNDEFINED
 *  (touchdown/dofs.h) but t_reached and wall_time when its run says them, its counts and flags -1,
 *  which the table writes as NaN (docs/output-format.md, "Undefined values"). */
typedef struct td_sweep_row {
    int state;                            /**< td_sweep_state */
    char status[32];                      /**< td_strerror of the run's status, "not run", "worker died" */
    char message[TD_ERROR_MESSAGE_SIZE];  /**< why the point failed ("" if it did not) */
    double peak_housing_force;            /**< N */
    double total_impulse;                 /**< N s */
    double friction_work;                 /**< J */
    double contact_time;                  /**< s */
    long contacts;                        /**< contact onsets (-1: unknown) */
    double first_contact_time;            /**< s, TD_UNDEFINED if none */
    char ending[96];                      /**< td_run_summary.ending */
    double ending_whirl_frequency;        /**< Hz, signed like the spin (< 0 backward); TD_UNDEFINED: no whirl */
    int returned_to_free_orbit;           /**< 1, 0, TD_RUN_NOT_APPLICABLE (no contact), -1 undetermined */
    double final_speed;                   /**< rad/s */
    double peak_amb_load;                 /**< largest AMB axis force / capacity, TD_UNDEFINED without a working AMB */
    double t_reached;                     /**< s, the last time reached */
    char warnings[TD_ERROR_MESSAGE_SIZE]; /**< the run's warnings (td_run_summary.warnings) joined by "; ",
                                               cut to fit; "" for none */
    double wall_time;                     /**< s, wall-clock time of the point (set by the caller) */
    char regime[16];                      /**< td_regime_name(td_run_summary_regime): "free", "rub",
                                               "bounce", "backward whirl", "failed" (also without a summary) */
    long section_count;                   /**< crossings of the once-per-revolution section (-1: unknown) */
    int section_kept;                     /**< radii kept in section_radius (td_run_summary.section_kept) */
    double section_radius_min;            /**< m, the smallest and largest kept radius (NaN: none) */
    double section_radius_max;
    double section_clearance;                      /**< m, the sampled retainer's radial clearance (NaN: none) */
    double section_radius[TD_RUN_SECTION_SAMPLES]; /**< m, the last section radii, oldest first (NaN
                                                        beyond section_kept) */
    /* life (td_run_summary.life_kept; docs/theory.md, "Touchdown bearing life") */
    int life_kept;           /**< 1: the point's bearings have a dynamic rating: the table has drops_to_failure */
    double drops_to_failure; /**< the fewest over the retainers (the first bearing to fail); TD_UNDEFINED: none */
    /* clearance margin (td_run_summary.min_clearance_margin, contact_happened, shock_outcome) */
    double min_clearance_margin; /**< m (TD_UNDEFINED: a failed point) */
    int contact_happened;        /**< 1, 0, -1: undetermined */
    char shock_outcome[16]; /**< td_shock_outcome_name: "none", "touch", "rub", "drop", "unsettled"; "" for a failed
                                 point */
    /* projective leap and long runs (td_run_summary.leap, leaps, leapt_time, end_at_rest, ended_at_rest) */
    int leap;          /**< 1: the point was asked to leap: the table has leaps and leapt_time */
    long leaps;        /**< leaps made (-1: not asked to leap, or unknown) */
    double leapt_time; /**< s of the run leapt, not integrated (TD_UNDEFINED: not asked to leap, or unknown) */
    int end_at_rest;   /**< 1: the point was asked to end at rest: the table has ended_at_rest */
    int ended_at_rest; /**< 1: it ended at rest, 0: it reached end_time at speed, -1: not asked, or undetermined
                            (failed) */
} td_sweep_row;

/** The row of a point whose run ended with summary `s` (state DONE if s->status is TD_OK, else
 *  FAILED with its message); wall_time is s->wall_time. */
TD_API void td_sweep_row_from_summary(td_sweep_row *row, const td_run_summary *s);

/** A row without a summary: `state`, `status` and `message` (NULL: "") copied, numbers unknown. */
TD_API void td_sweep_row_unknown(td_sweep_row *row, td_sweep_state state, const char *status, const char *message);

/** A sweep's table: every point's row, in point order (all borrowed). */
typedef struct td_sweep_table {
    const td_sweep_grid *grid;
    const td_sweep_row *rows; /**< td_sweep_grid_points(grid) rows */
    const char *case_text;    /**< the case as read with the fixed overrides (td_case_text) */
    const char *const *sets;  /**< the fixed overrides, n_sets of them (may be NULL when 0) */
    int n_sets;
    int complete;       /**< 1: every point was run (each DONE or FAILED) */
    const char *reason; /**< why not complete (NULL or "" when complete) */
} td_sweep_table;

/**
 * Write the table to `path` (CSV: a header naming every column with its unit, one line per
 * point, then "# name = value" attribute lines and last "# complete" or "# incomplete: REASON";
 * HDF5: one dataset per column over the dimension `point`, attributes, `complete` written last).
 * Both write PATH.XXXXXX.partial and rename it to PATH once it is on disk. Returns TD_OK,
 * TD_ERR_INVALID (NULL argument), TD_ERR_IO (nothing is left at PATH).
 */
TD_API td_status td_sweep_write_csv(const char *path, const td_sweep_table *t, td_error *err);
TD_API td_status td_sweep_write_hdf5(const char *path, const td_sweep_table *t, td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_SWEEP_H */
