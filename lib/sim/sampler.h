/*
 * The sampler's record (sampler.c): the sampled linear controllers of the model (td_lti_law with
 * sample_rate > 0) as the simulation runs them, outside the DAE. Each keeps its state x_k and the
 * integer k_next of its next sample; sample k falls at t_k = t0 + k / sample_rate, computed from k
 * every time, so that no rounding accumulates over a run. Between samples the command is held
 * (zero-order hold) in machine.held_current, which the residual reads. A computation delay is part
 * of the realisation (td_controller_delay), so the sampler never adds one to a linear law; a plug-in
 * law's (touchdown/plugin.h) is the sampler's queue. A plug-in's instance lives as long as the
 * simulation.
 */
#ifndef TD_SIM_SAMPLER_H
#define TD_SIM_SAMPLER_H

#include "touchdown/error.h"

/* A callback told of every sample as it is taken (tests): law (its index in td_system.laws), k, the
 * time of the state it read (t_k, bit for bit when the integrator stopped there), its inputs e_k
 * (nin) and its output i_k (nout). */
typedef void (*td_sim_sample_hook)(void *data, int law, long k, double t, const double *e, int nin, const double *u,
                                   int nout);

/* One sampled law. */
typedef struct td_sim_sampled {
    int law;        /* index in td_system.laws */
    double t0;      /* s: the time of sample 0, the run's start */
    double rate;    /* Hz */
    long k_next;    /* the next sample to take */
    double *x, *xn; /* n: the state x_k, and x_{k+1} while it is computed */
    double *e, *u;  /* the last sample's nin inputs e_k = -xs and nout outputs i_k */
    int pair;       /* the recovery supervisor's pair it is a law of (supervisor.h), or -1 */
    /* a plug-in law's (td_lti_law.plugin; all NULL / 0 for a linear law) */
    void *instance; /* its init's instance, freed with the simulation */
    double *xs;     /* nin: the sensed displacements it reads, xs = -e_k */
    double *cmd;    /* nout: the commands its step returns */
    double *queue;  /* delay x nout: the currents of samples k - delay .. k - 1, sample j's at row j mod delay */
    double *gain;   /* nout x nin: its direct gain, measured at creation (sampler_plugin.c) */
    int reset_due;  /* 1: reset it before its next step (the supervisor switched to it: it starts from rest) */
} td_sim_sampled;

typedef struct td_sim_sampler {
    int n;               /* sampled laws (> 0: the record exists only when the model has one) */
    td_sim_sampled *law; /* n */
    td_sim_sample_hook hook;
    void *hook_data;
    struct td_sim_supervisor *supervisor; /* supervisor.h; NULL: no recovery supervisor */
    int failed;                           /* 1: a plug-in failed (failure): the run goes no further */
    td_error failure;                     /* its error, the failed controller its site */
} td_sim_sampler;

#endif
