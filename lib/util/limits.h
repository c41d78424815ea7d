/* The run-work bounds of touchdown/limits.h as one check shared by the case reader and td_run. */
#ifndef TD_UTIL_LIMITS_H
#define TD_UTIL_LIMITS_H

#include <stddef.h>

#include "touchdown/limits.h"

/* Which bound a run breaks. */
typedef enum td_run_limit {
    TD_LIMIT_NONE = 0,
    TD_LIMIT_SAMPLES = 1,     /* sample_rate x duration > TD_MAX_SAMPLES */
    TD_LIMIT_STEPS = 2,       /* duration / max_step > TD_MAX_STEPS */
    TD_LIMIT_REVOLUTIONS = 3, /* |speed| x duration / 2 pi > TD_MAX_REVOLUTIONS */
    TD_LIMIT_ATOL = 4         /* solver.atol > TD_MAX_ATOL_FRACTION x the smallest gap */
} td_run_limit;

/* The first bound a run of `duration` s at `speed` rad/s, sampled at `sample_rate` Hz with the
 * largest solver step `max_step` s (0: the default) breaks; TD_LIMIT_NONE if none. When one is
 * broken, `why` (n bytes) explains it, e.g. "makes 1e+15 output samples (at most 1e+08)". */
td_run_limit td_run_limit_check(double duration, double speed, double sample_rate, double max_step, char *why,
                                size_t n);

/* long runs: 1 if a window of `window` s (td_output_options.window, > 0) cannot be one at a rate of
 * `sample_rate` Hz, with the reason into `why` (n bytes): a window closes at a grid sample, so it is
 * a whole number (at least one) of sample intervals; any other length would silently become the
 * next whole number of them. 0 when it can (or there is no window). */
int td_run_window_check(double window, double sample_rate, char *why, size_t n);

#endif
