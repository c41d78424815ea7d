/*
 * The sweep grid's rules shared with the case reader (lib/case/case_sweep.c): the reader turns
 * the case file's `sweep` group into the same specs as --vary and --with and checks them with
 * td_sweep_grid_add on a dry grid (counts only, no values), so that one set of rules, in
 * sweep_grid.c, judges both the command line and the case file.
 */
#ifndef TD_RUN_SWEEP_INTERNAL_H
#define TD_RUN_SWEEP_INTERNAL_H

#include "touchdown/sweep.h"

/* The part of a spec a rule found wrong, so that the case reader can name the setting. */
typedef enum td_sweep_part {
    TD_SWEEP_PART_SPEC,    /* the spec as a whole (form, limits on axes, keys and points) */
    TD_SWEEP_PART_KEY,     /* the key (too long, swept twice) */
    TD_SWEEP_PART_START,   /* a range's first value */
    TD_SWEEP_PART_STOP,    /* a range's last value */
    TD_SWEEP_PART_N,       /* a range's number of points */
    TD_SWEEP_PART_SPACING, /* a range's spacing */
    TD_SWEEP_PART_VALUES,  /* a list's values */
    TD_SWEEP_PART_COUNT    /* the number of values of a zipped key (points or values) */
} td_sweep_part;

/* A grid that keeps the keys and counts of its axes but no values: for checking specs. */
td_status td_sweep_grid_create_dry(td_sweep_grid **out, td_error *err);

/* Add `spec` as a new axis (with = 0) or zipped onto the last axis (with = 1), the axis's origin
 * being `origin` (copied; for a zipped key ignored). On failure the grid is unchanged, *part
 * names the part at fault and reason (n bytes) says why, without any prefix. */
td_status td_sweep_grid_add(td_sweep_grid *g, const char *spec, int with, const char *origin, td_sweep_part *part,
                            char *reason, size_t n);

/* x with the fewest significant digits (15, 16 or 17) that read back to x, as range values are. */
void td_sweep_print_number(char *buf, size_t n, double x);

#endif
