/*
 * The recovery supervisor as the simulation runs it (supervisor.c; the model's td_recovery,
 * touchdown/model.h; docs/theory.md, "Recovery supervisor"). Each pair of sampled laws (nominal,
 * recovery) is sampled as one: at each of its samples the supervisor reads the sensors, judges the
 * sensed radius against the rule that leads away from the law the pair runs towards, switches when
 * the rule has held for its dwell, runs the laws that weigh, and holds the blend of their outputs.
 */
#ifndef TD_SIM_SUPERVISOR_H
#define TD_SIM_SUPERVISOR_H

#include "touchdown/model.h"
#include "touchdown/records.h"
#include "touchdown/sim.h"

#include "sim/sampler.h"

/* A callback told of every sample of every pair (tests): pair p's sample k at time t (the state it
 * read), its inputs e (nin), the sensed radius r (m), the blend weight b of the law the pair runs
 * towards (`target`: 0 nominal, 1 recovery), each law's own output u[0], u[1] (nout each; a law
 * that does not run this sample: NULL) and the held current (nout). */
typedef struct td_sim_pair_sample {
    int pair;
    long k;
    double t;
    const double *e;
    int nin;
    double r, b;
    int target;
    const double *u[2];
    const double *held;
    int nout;
} td_sim_pair_sample;
typedef void (*td_sim_switch_hook)(void *data, const td_sim_pair_sample *ps);

/* One pair as the simulation runs it. */
typedef struct td_sim_pair {
    int law[2];     /* the sampler's records (td_sim_sampler.law) of the nominal (0) and the recovery (1) law */
    int target;     /* the law the pair runs towards: 0 nominal, 1 recovery */
    int running[2]; /* 1 while law i weighs (> 0): it updates its state */
    long k_switch;  /* the sample of the last switch */
    long count;     /* consecutive samples, up to this one, that met the rule leading away from target */
    double need[2]; /* samples beyond the first that the rule must hold: detect (target 0), release (1) */
    double since;   /* s: when the pair last switched to its recovery law */
    int n_ambs;     /* the AMBs the pair drives, whose sensors make the sensed radius */
    int *ambs;      /* n_ambs */
    double *held;   /* the held current of each output (the nominal's nout) */
} td_sim_pair;

typedef struct td_sim_supervisor {
    td_recovery rec;      /* the model's */
    double clearance;     /* m: the smallest retainer clearance, c */
    int n;                /* pairs */
    td_sim_pair *pair;    /* n */
    long switches;        /* switches taken so far, both ways */
    double recovery_time; /* s, over the pairs: time on the recovery law up to each one's last switch back */
    double last_return;   /* s: the last switch back to a nominal law; TD_UNDEFINED before any */
    td_sim_switch_hook hook;
    void *hook_data;
} td_sim_supervisor;

/* s->sampler->supervisor for the model's recovery pairs (each law's record already made, its
 * `pair` set); none when the model has no supervisor. */
td_status td_sim_supervisor_create(td_sim *s, td_error *err);
void td_sim_supervisor_free(td_sim *s);
/* Steps 1 and 2 of pair p's sample k (supervisor.c's header) from the state at s->dae.t: the sensed
 * radius into *r, the rule, a switch (its event queued, the incoming law's state at rest). Returns
 * the weight b of the law the pair now runs towards; pair.running says which laws run (the
 * sampler runs them and holds the blend, step 3). */
double td_sim_supervisor_judge(td_sim *s, int p, long k, double *r);
/* The supervisor's account into *out at the simulation's time: controller_switches,
 * time_on_recovery (a pair on its recovery law counts up to now) and last_return_time. */
void td_sim_supervisor_stats(const td_sim *s, td_sim_stats *out);
/* Tell `hook` of every pair's sample from now on (nothing without a supervisor). */
void td_sim_supervisor_set_hook(td_sim *s, td_sim_switch_hook hook, void *data);

#endif
