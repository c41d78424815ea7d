/*
 * projective leap: the run loop's side of the leap (td_output_options.leap_*; docs/case-format.md,
 * "Projective leap"). After `start`, the run integrates a healing stretch, then a burst whose ends give
 * the slow rates (sim/leap.h), then leaps `factor` bursts at those rates, and so on. The simulation's
 * clock does not move in a leap: the run's time is the simulation's plus the leaps so far, and every
 * sample, event and window the files get is of integrated motion, the leapt stretches the gaps between.
 */
#ifndef TD_RUN_LEAP_H
#define TD_RUN_LEAP_H

#include "sim/leap.h"
#include "touchdown/options.h"
#include "touchdown/sim.h"

/* The run's counters a leap moves on with its rates, as the loop keeps them (td_run_summary). */
typedef struct td_run_leap_counts {
    long events, contacts;
    double contact_time;
} td_run_leap_counts;

typedef struct td_run_leap {
    double burst, factor, heal, start; /* the options */
    double speed0;                     /* rad/s: the run's start speed (the at-rest rule's) */
    double offset;                     /* s leapt so far: run time = simulation time + offset */
    int phase;                         /* 0 before start, 1 healing, 2 in a burst */
    double until;                      /* run time the phase ends */
    td_sim_leap_state from;            /* the slow state where the burst began */
    td_run_leap_counts counts;         /* and the run's counters there */
    long leaps;                        /* leaps made */
    double dw_power, dw_rate, rate_sq; /* over the leaps: the speed changes made (from the bursts' net
                                          power), those the bursts' dOmega/dt gave, its square sum */
} td_run_leap;

/* Options o's leaps for a run starting at speed0 rad/s; 0 when o asks for none (then leave *l). */
int td_run_leap_init(td_run_leap *l, const td_output_options *o, double speed0);

/* At a grid sample at run time t (the counters as they are): the leap's length due now (s, a whole
 * number of sample intervals 1 / rate, t + length before t_end), 0 for none; its rates into *rate. */
double td_run_leap_due(td_run_leap *l, const td_sim *sim, double t, double rate, double t_end,
                       const td_run_leap_counts *now, td_sim_leap_state *rate_out, td_error *err);

/* The leap of `length` s at `rate` made at run time t: the simulation's slow state moved on, the
 * counters in *now moved on at the burst's rates, the offset grown, the next healing begun. */
td_status td_run_leap_make(td_run_leap *l, td_sim *sim, double t, double length, const td_sim_leap_state *rate,
                           td_run_leap_counts *now, td_error *err);

#endif
