/*
 * touchdown/limits.h - the bounds every run and every case file must respect, in one place.
 *
 * A run's work grows with the number of output samples, with the number of solver steps and
 * with the number of shaft revolutions (the default step is a fraction of the whirl period).
 * The case reader checks these bounds before anything runs, naming the key that breaks them
 * (docs/case-format.md, "Limits"); td_run checks them again for callers of the API.
 */
#ifndef TOUCHDOWN_LIMITS_H
#define TOUCHDOWN_LIMITS_H

/** Most output samples of one run: sample_rate x (end time - start time). */
#define TD_MAX_SAMPLES 1e8
/** Most solver steps a run may be forced into by solver.max_step: (end time - start time) /
 *  max_step (max_step 0, the default, is bounded through TD_MAX_REVOLUTIONS). */
#define TD_MAX_STEPS 1e8
/** Most shaft revolutions of one run: |speed| x (end time - start time) / (2 pi). The default
 *  solver step is 1/20 of a revolution, so this also bounds the default step count (2e7). */
#define TD_MAX_REVOLUTIONS 1e6

/** Largest solver.atol as a fraction of the machine's smallest gap (a retainer's clearance or an
 *  AMB's air gap). Displacements are controlled to atol, and everything the run reports happens in
 *  the gap c - r: at 1e-3 the gap is resolved to 0.1 % of the clearance, as fine as the run resolves
 *  impacts (slower ones are plastic: 1e-3 of c times the bearing frequency, lib/sim/setup.c). An atol
 *  of the order of the clearance lets the integrator step across contacts unchecked: forces grow
 *  without bound and the run stops progressing (the drop case at atol = 1e6 m advanced 2e-6 s in
 *  35 s of steps). */
#define TD_MAX_ATOL_FRACTION 1e-3

/** Largest unbalance force U Omega^2 at the case speed, N (of every unbalance and schedule
 *  entry). Real machines stay below 1e7 N; far larger forces only overflow the start orbit. */
#define TD_MAX_UNBALANCE_FORCE 1e12

/** Most settings and values one case may hand to the parser (every key, every list or array
 *  entry, counted over the case file and its @include files). */
#define TD_CASE_MAX_SETTINGS 200000
/** Most keys of one group { ... } (no group of the format has more than 17). */
#define TD_CASE_MAX_GROUP_KEYS 64
/** Deepest nesting of groups, lists and arrays (the format needs 4). */
#define TD_CASE_MAX_NESTING 16

#endif /* TOUCHDOWN_LIMITS_H */
