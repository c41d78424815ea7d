/* The wall clock the library measures its own run times with. */
#ifndef TD_UTIL_CLOCK_H
#define TD_UTIL_CLOCK_H

/** Seconds on the monotonic clock (an arbitrary origin: only differences mean anything). */
double td_wall_clock(void);

#endif
