/*
 * The run's grid clock: the one rule of a grid time that has reached an end time (a leap's phase,
 * a window summary's). Grid times are t0 + k / rate, rounded: one computed for an end time may fall
 * a few ulps of t short of it, so the tolerance scales with the time itself (its ulps), and with 1 s
 * below it (a clock near 0 s).
 */
#ifndef TD_RUN_CLOCK_H
#define TD_RUN_CLOCK_H

/** Relative tolerance of td_run_reached: far above rounding (1e-16 of t), far below a sample
 *  interval of a run from 0 s (TD_MAX_SAMPLES, touchdown/limits.h, keeps 1 / sample_rate above 1e-8
 *  of end_time). */
#define TD_RUN_REACHED_TOLERANCE 1e-9

/** 1 if the grid time t has reached `end` (s): t >= end - 1e-9 max(|end|, 1 s). */
int td_run_reached(double t, double end);

#endif
