/*
 * The sweep grid's rules (grid.c) shared with the judge of the case file's `sweep` group
 * (case_group.c): the case reader keeps the group as the same specs as --vary and --with, and the
 * judge checks them with td_sweep_grid_add on a dry grid (counts only, no values), so that one set
 * of rules judges both the command line and the case file.
 */
#ifndef TD_SWEEP_SWEEP_INTERNAL_H
#define TD_SWEEP_SWEEP_INTERNAL_H

#include "touchdown/sweep.h"

/* The part of a spec a rule found wrong, so that the judge of the case's group can name the setting. */
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

#endif
