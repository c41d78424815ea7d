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
    double dw_power, dw_rate;          /* over the leaps: the speed changes made (from the bursts' net
                                          power), those the bursts' dOmega/dt gave */
    double rate_mean, rate_m2;         /* the bursts' dOmega/dt's time-weighted running mean and sum of
                                          squared deviations (West's weighted Welford: no cancellation) */
} td_run_leap;

/* Options o's leaps for a run starting at speed0 rad/s; 0 when o asks for none (then leave *l). */
int td_run_leap_init(td_run_leap *l, const td_output_options *o, double speed0);

/* At a grid sample at run time t (the counters as they are): the leap's length due now (s, a whole
 * number of sample intervals 1 / rate, t + length before t_end), 0 for none; its rates into *rate. */
double td_run_leap_due(td_run_leap *l, const td_sim *sim, double t, double rate, double t_end,
                       const td_run_leap_counts *now, td_sim_leap_state *rate_out, td_error *err);

/* 1 if a leap of `length` s at `rate` can be made on sim now: td_sim_leap_speed_change finds the
 * speed change it will make, and that leaves the rotor's speed off rest (the last approach to rest is
 * integrated); 0 if not (the run then integrates on). */
int td_run_leap_feasible(const td_run_leap *l, const td_sim *sim, double length, const td_sim_leap_state *rate);

/* The leap of `length` s at `rate` made at run time t: the simulation's slow state moved on, the
 * counters in *now moved on at the burst's rates, the offset grown, the next healing begun. */
td_status td_run_leap_make(td_run_leap *l, td_sim *sim, double t, double length, const td_sim_leap_state *rate,
                           td_run_leap_counts *now, td_error *err);

/* The time-weighted sd of the bursts' dOmega/dt over the leaps made: TD_UNDEFINED below 2 leaps (one
 * leap has no spread, which 0 would claim). */
double td_run_leap_decel_sd(const td_run_leap *l);

#endif
