/*
 * The projective leap (leap.c): a step of the slow variables over a statistically stationary fast
 * motion (Gear and Kevrekidis' projective integration, a heterogeneous multiscale method). The
 * caller integrates a burst of the full model, reads the slow state at its two ends
 * (td_sim_leap_read), takes their mean rates (td_sim_leap_rates) and moves the slow state on by a
 * leap at those rates (td_sim_leap): the rotor's and the races' speeds, the thermal networks, and
 * every additive total (works, heat, times, impulses, counts, damage, the energy account), so that
 * the accounts stay whole. The fast state (the lateral motion, the contacts) is carried over as
 * it is and re-settles in the integration that follows. The simulation's clock does not move: the
 * caller owns the leapt time (the time a user reads is the simulation's plus the leaps so far).
 */
#ifndef TD_SIM_LEAP_H
#define TD_SIM_LEAP_H

#include "touchdown/records.h"
#include "touchdown/sim.h"

/* Retainers a leap handles (a model with more is refused: td_run_leap_check). */
#define TD_SIM_LEAP_RETAINERS TD_LEAP_MAX_RETAINERS

/* The slow state at one time, or (td_sim_leap_rates) its mean rates over a burst. */
typedef struct td_sim_leap_state {
    double t;                                         /* s: the simulation's time; for rates, the burst's length */
    double speed;                                     /* rad/s: the rotor's speed; for rates, rad/s^2 */
    double mean_speed;                                /* rates only: rad/s, the burst's mean speed (trapezoid) */
    int retainers;                                    /* how many follow */
    double race_speed[TD_SIM_LEAP_RETAINERS];         /* rad/s (0 for a race without a speed of its own) */
    td_retainer_totals totals[TD_SIM_LEAP_RETAINERS]; /* for rates: the additive ones a second */
    double contacts[TD_SIM_LEAP_RETAINERS];           /* the totals' counts (contacts, touch_and_go): for rates, */
    double touch_and_go[TD_SIM_LEAP_RETAINERS];       /* a second, not rounded */
    double events, contact_onsets, releases;          /* td_sim_stats' counts of the motion (for rates, a second) */
    double time_in_contact, time_slewing;             /* and its times (s; for rates, s a second) */
    int energy_on;                                    /* the run keeps the energy account (td_sim_options.energy) */
    td_energy energy;
} td_sim_leap_state;

/* The slow state of `sim` now into *out. TD_ERR_INVALID for NULL arguments or more than
 * TD_SIM_LEAP_RETAINERS retainers. */
td_status td_sim_leap_read(const td_sim *sim, td_sim_leap_state *out, td_error *err);

/* The mean rates between a and b (b later) into *rate: (b - a) / (b.t - a.t) for the speeds and
 * the additive totals, rate->t = b.t - a.t, rate->mean_speed = (a.speed + b.speed) / 2. The peaks
 * and the clearance margin are not rates (left 0). TD_ERR_INVALID unless b.t > a.t and both read
 * the same machine. */
td_status td_sim_leap_rates(const td_sim_leap_state *a, const td_sim_leap_state *b, td_sim_leap_state *rate,
                            td_error *err);

/* The rotor's speed change a leap of `duration` s at `rate` would make on `sim` now, into *change:
 * with the energy account on, the change whose kinetic energy pays the burst's net power (its
 * inputs less every loss the account books) at the speed's scale over the leap; without it, the
 * burst's dOmega/dt times duration. TD_ERR_INVALID when no speed pays it. */
td_status td_sim_leap_speed_change(const td_sim *sim, double duration, const td_sim_leap_state *rate, double *change,
                                   td_error *err);

/* Move the slow state of `sim` on by `duration` s at `rate` (td_sim_leap_rates), and restart the
 * integrator there (the simulation's time stays; its once-per-revolution section's clock moves on
 * with the run's). The works, heat and energy terms at the burst's powers scaled by the speed
 * (speed / rate->mean_speed: sliding and drag powers go with the speed); the rotor's speed by
 * td_sim_leap_speed_change, so that with the energy account on its kinetic energy pays exactly the
 * terms booked and the account closes across the leap to rounding; a race in contact with the rotor
 * with it (its sliding velocity kept), a free race at its burst's rate; times, impulses, counts and
 * damage at the burst's rates, and so the statistics' counts and times of the motion (td_sim_stats:
 * events, contact_onsets, releases, time_in_contact, time_slewing), not the solver's own (a leap takes
 * no step); the thermal networks in closed form under that heat. TD_ERR_INVALID for a duration not
 * > 0, a rate of another machine, a model without a free spin, or a leap that would turn the rotor
 * backwards; a failed restart its status. */
td_status td_sim_leap(td_sim *sim, double duration, const td_sim_leap_state *rate, td_error *err);

#endif
