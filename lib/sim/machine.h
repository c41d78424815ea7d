/*
 * The machine's record: the machine as it is now (the speed and spin, the unbalances, the AMBs'
 * modes and held forces, the schedule's position), which the schedule (schedule.c) and the
 * td_sim_set_* calls change and the DAE reads, and the scales the set-up derives from it.
 * spin.c owns the spin DOF's fields, schedule.c the rest; setup.c fills it once.
 */
#ifndef TD_SIM_MACHINE_H
#define TD_SIM_MACHINE_H

#include "touchdown/model.h"
#include "touchdown/sim.h"

/* Linear coefficients of one AMB axis law (probed from model/amb.c, exact for the linear law). */
typedef struct td_sim_amb_coef {
    double cmd_x, cmd_v, cmd_e;            /* d(command)/d(xs, vs, e) */
    double rate_x, rate_v, rate_e, rate_w; /* d(dFc/dt)/d(xs, vs, e, Fc), tau > 0 only */
    double target_i, rate_i;               /* a driven axis's d(target)/d(current), d(dFc/dt)/d(current) */
    double gain_x; /* |d(command)/d(xs)| of the law's direct part (the scale of its force per metre):
                    * ki kp for the shorthand, ki max|D| for a linear controller (setup.c) */
} td_sim_amb_coef;

typedef struct td_sim_machine {
    double omega; /* rad/s: the speed, or with a spin DOF the speed D = C + omega G was built at */
    int spin;     /* the spin DOF (spin.c), -1: the speed is omega, prescribed */
    int spin_free;
    double spin_inertia;         /* J, kg m^2 */
    double spin_ref, t_spin_ref; /* spin angle phi(t) = spin_ref + omega (t - t_spin_ref) */
    int nu;
    td_unbalance *unb;
    td_amb_mode *amb_mode;     /* per AMB */
    td_amb_mode *amb_drive;    /* per AMB: how it is driven while it works (TD_AMB_PD, or the last of
                                * TD_AMB_EXTERNAL, TD_AMB_CURRENT the caller chose); a schedule's
                                * restore (TD_CHANGE_AMB_ON) returns it to this */
    double *amb_control;       /* per AMB, x and y: held control force (TD_AMB_EXTERNAL) */
    double *held_current;      /* per AMB axis: the current command (A) a sampled controller holds
                                * on it between its samples (sampler.c writes it, the residual reads
                                * it); 0 for an axis no sampled controller drives */
    double *amb_current;       /* per AMB axis (2 amb + axis): the caller's held current command (A) for
                                * TD_AMB_CURRENT (td_sim_set_amb_current) */
    int next_change;           /* first schedule entry not yet applied */
    td_sim_amb_coef *amb_coef; /* per AMB axis */

    /* scales (setup.c) */
    double freq_scale;     /* rad/s, the bearing frequency or the speed: step bound, rebound speed */
    double freq_max;       /* rad/s, estimate of the highest natural frequency: velocity tolerance */
    double stiff_scale;    /* N/m, forces ~ stiff_scale * displacements */
    double rearm_eps;      /* m, hysteresis of the onset root (constraint model) */
    double rebound_min;    /* m/s, radial speed below which an impact with e > 0 becomes plastic */
    double constraint_tol; /* m: |g| of every contact at an accepted Newton iterate */
} td_sim_machine;

#endif
