/*
 * The monitor's record: what the simulation has seen so far, kept at the accepted points and the
 * events (monitor.c: statistics and the event queue; totals.c: the retainers' running totals;
 * energy.c: the energy account), which own it. The layers above add to it (the flight its steps,
 * the mode switching the details of the events it queued, the integrator its restarts) and report
 * it (sim.c); the layers below never see it.
 */
#ifndef TD_SIM_MONITOR_H
#define TD_SIM_MONITOR_H

#include "sim/thermal.h"
#include "touchdown/assess.h"
#include "touchdown/records.h"
#include "touchdown/sim.h"

/* clearance margin: a point of a retainer node's radial motion (margin.c) */
typedef struct td_sim_margin_sample {
    double t, r, v; /* s, m (radius from the race centre), m/s (dr/dt) */
} td_sim_margin_sample;

/* One retainer's running totals (totals.c): the public record, the integrands at the last point
 * and the contact interval's bookkeeping. */
typedef struct td_sim_totals {
    td_retainer_totals t;
    struct {
        double n, n2, power, whirl_rate;
    } prev;
    int in_contact;        /* in contact at the last point */
    double whirl_at_onset; /* t.whirl_angle when the open interval began */
    double interval_peak;  /* N, the largest normal force of the open (or the last) contact interval
                              at the accepted points (monitor.c, td_sim_monitor_at) */
    double mark_peak;      /* long runs: N, the largest normal force at the points reached since
                              td_sim_retainer_peak_since last read it (totals.c) */
    /* life (load_cycles.c): t.damage sums the rolling damage over the steps as the other integrals */
    td_life_law law;       /* the bearing's ratings; dynamic_rating 0: none, no life */
    td_rainflow *cycles;   /* the contact load's rainflow count at the points the run has reached */
    double cycle_damage;   /* Miner sum of the cycles it has closed */
    double closed_cycles;  /* their count */
    double life_rate_prev; /* the rolling damage rate at the last point */
    int life_failed;       /* the counter could not grow: the life is undefined */
    /* clearance margin (margin.c): the node's radius r and dr/dt at the last point, and the segment to a
     * held point (an integrator step's end beyond the output time), which counts up to the time reached */
    double margin;               /* m, the smallest clearance - r over the time reached before the held segment */
    td_sim_margin_sample m_last; /* the last point */
    td_sim_margin_sample m_from; /* the held segment's start (m_held) */
    td_sim_margin_sample m_to;   /* and its end, beyond s->dae.t until the run reaches it */
    int m_held;
    /* the closed-form flight's point (flight.c): r^2 and the bound on |(r^2)''| from it, at the start of
     * its step and (b) at the end of the part searched; (s) the step's, kept while a pending part is searched */
    double flight_r2, flight_b2, flight_r2b, flight_b2b, flight_r2s, flight_b2s;
} td_sim_totals;

/* heat: retainer k's drag power and thermal network at the points of the totals (thermal.c) */
typedef struct td_sim_thermal {
    double drag;            /* W, the race's drag power at the last point */
    double power;           /* W, the heat into the race at the last point: friction + drag */
    int on;                 /* the retainer has a network (td_model_get_retainer_thermal) */
    td_thermal_network net; /* its modal form */
    double T[2];            /* K above the ambient, race and housing, at the last point (totals_t) */
    double T_before[2];     /* at the point before it (t_before), with the heat power there */
    double t_before, power_before;
    double peak;              /* K, the race's largest rise at the points reached */
    double growth_per_kelvin; /* m/K, alpha R_b (TD_UNDEFINED without expansion) */
} td_sim_thermal;

typedef struct td_sim_monitor {
    /* projective leap (leap.h): s the run's clock is ahead of the simulation's (the time leapt); the
     * time stamps of the statistics (first contact, peaks) and of the section are the run's */
    double leapt;
    /* events waiting to be reported (monitor.c), the last one reported */
    td_event *queue;
    int q_len, q_pos, q_cap;
    td_event last;
    int have_last;

    /* the retainers' totals (totals.c), nr of them, and the time of their last point */
    td_sim_totals *totals;
    double totals_t;
    td_energy energy;      /* the energy account (energy.c) */
    double energy_prev[5]; /* its powers at the last point: external, drive, damping, contact, drag */
    double *energy_f;      /* n: the external forces at a point */
    int energy_started;    /* the initial energy is set */
    double housing_prev;   /* the housing motion's power at the last point (energy.c) */

    /* statistics (monitor.c) */
    td_sim_stats stats; /* event totals, drift, forces, times (counters filled on demand) */
    double t_acc;       /* contact time accounted up to here (monitor.c) */
    int slewing;        /* AMB axes slewing at the last point (slew_t) */
    double slew_t;      /* time_slewing is accounted up to here (monitor.c) */
    int slew_kink;      /* the last stop was on a slew's kink (sim_modes.c td_sim_handle_roots) */

    /* heat: the retainers' drag power and thermal networks (thermal.c), nr of them */
    td_sim_thermal *thermal;

    /* an integrator step's end beyond the output time (monitor.c td_sim_monitor_step_ahead): its
     * peaks wait until the run reaches it (td_sim_monitor_at, td_sim_monitor_settle) */
    int ahead;       /* a point is held */
    double ahead_t;  /* its time, beyond s->dae.t */
    double *ahead_y; /* neq: its state */

    /* the bearing's duty: the largest 0-peak displacement at each AMB's sensor while it works (totals.c) */
    double *sensor_peak; /* n_amb */
    /* clearance margin: the segment ending at the next point was covered by the closed-form flight's own
     * search (flight.c), not by the Hermite of the points */
    int margin_flown;
} td_sim_monitor;

#endif
