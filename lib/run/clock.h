/*
 * The run's grid clock: the one rule of a grid time that has reached an end time (the run's end, a
 * leap's phase, a window summary's). Grid times are t0 + k / rate, rounded: one computed for an end
 * time may fall a few ulps of t short of it, so the tolerance scales with the times themselves (their
 * ulps), not with a sample interval: a run may start late (td_run runs from the simulation's current
 * time t0), and there a tolerance of a fixed part of end would be a sample interval or more.
 */
#ifndef TD_RUN_CLOCK_H
#define TD_RUN_CLOCK_H

/** Tolerance of td_run_reached in units of DBL_EPSILON of the larger of the two times (and 1 s below
 *  it: a clock near 0 s): each of t0 + k / rate and the end (a grid time plus a length) rounds by at
 *  most about an ulp per operation, DBL_EPSILON |t| bounds an ulp of t, so 16 holds several times the
 *  few ulps two such sums can differ by. It stays a small part of a sample interval while t rate is
 *  far below 1 / (16 DBL_EPSILON) = 2.8e14 (a day at 1e9 Hz): TD_MAX_SAMPLES (touchdown/limits.h)
 *  bounds the run's length in samples, and a clock that late could not tell grid times apart anyway. */
#define TD_RUN_REACHED_ULPS 16.0

/** 1 if the grid time t has reached `end` (s): t >= end - 16 DBL_EPSILON max(|t|, |end|, 1 s). */
int td_run_reached(double t, double end);

#endif
