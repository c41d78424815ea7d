/*
 * The td_system record and the AMB axis law, inside the library only.
 * Matrices are CXSparse (SuiteSparse) compressed-column, duplicates summed, square ndof x ndof.
 */
#ifndef TD_SYSTEM_INTERNAL_H
#define TD_SYSTEM_INTERNAL_H

#include "touchdown/dofs.h"
#include "touchdown/model.h"
#include "touchdown/system.h"

#include <suitesparse/cs.h>

/* One lateral axis (x or y) of one AMB. Two per AMB, x first: axis index 2 * amb + (0 x | 1 y). */
typedef struct td_amb_axis {
    int amb;          /* index of the AMB in the model */
    int axis;         /* 0: x, 1: y */
    int actuator_dof; /* global DOF the force acts on */
    int sensor_dof;   /* global DOF the controller reads */
    double ks, ki, kp, kd, tau, capacity;
    int saturation;
    int state;      /* index of its lag state Fc among the controller states, or -1 when tau == 0 */
    int integral;   /* index of its integrator state e among the controller states, or -1 when kint == 0 */
    double kint;    /* integral gain, A/(m s) */
    int off;        /* 1: the AMB is off (failed) in the machine the system describes now: no force,
                     * its integrator holds (td_system_set_amb_off); 0 as built */
    int law;        /* -1: the shorthand law above (kp, kd, kint); else the index in td_system.laws of
                     * the linear controller that drives this axis */
    int law_output; /* the output of that controller that commands this axis; -1 for the shorthand */

    /* the amplifier's slew-rate limit, A/s (td_amb.slew_rate); 0: none. Last, so that positional
     * initialisers without it keep their meaning */
    double slew_rate;
} td_amb_axis;

/* One controller of the model (touchdown/controller.h, or a plug-in: touchdown/plugin.h) as the
 * system runs it. */
typedef struct td_lti_law {
    int n, nin, nout;
    double *A, *B, *C, *D; /* column-major, owned */
    double *D1;            /* nout x nin velocity feedthrough, owned; NULL when zero (always when sampled) */
    double sample_rate;    /* Hz; 0: continuous */
    int *in_axis;          /* nin AMB axis indices (2 amb + axis) whose sensors it reads, e = -xs */
    int *out_axis;         /* nout AMB axis indices whose amplifiers it commands */
    int state;             /* continuous: index of its first state among the controller states (after
                            * every shorthand state); -1 when sampled (its state is the simulation's) */
    int standby;           /* 1: the recovery law of a supervised pair (td_recovery): it shares its nominal's
                            * axes but drives none of them (amb_axes[].law is the nominal's) until the
                            * supervisor switches to it, and the analyses leave it out */
    /* a plug-in controller's spec (the system's model's, td_model_get_plugin): sampled, n = 0 and
     * D = 0 (no linear law: the analyses refuse it), its commands the plug-in's
     * (lib/sim/sampler_plugin.c); NULL for a linear law */
    const td_plugin_spec *plugin;
} td_lti_law;

struct td_system {
    td_model *model; /* owned copy */
    int nnodes;
    int ndof;  /* generalized coordinates q (touchdown/system.h) */
    int nphys; /* physical DOFs, 4 nnodes */
    /* the Craig-Bampton reduction (reduce.c); all NULL / 0 for the full model */
    int *phys_to_q; /* nphys: index in q of each physical DOF, -1 for an interior node's */
    int *q_node;    /* ndof: node of coordinate i, -1 for a fixed-interface modal coordinate */
    double *T;      /* nphys x ndof, column-major: q_phys = T q */
    int n_modes;    /* modal coordinates ndof - n_modes .. ndof - 1: the fixed-interface modes kept,
                     * then n_static static corrections of the gravity load (reduce.c) */
    int n_static;
    double *mode_freq; /* n_modes, Hz (a static correction's: its Rayleigh quotient) */
    double *mode_amp;  /* n_modes: largest nodal x or y of the mass-normalised mode, m per unit coordinate */
    cs_di *M;
    cs_di *K;
    cs_di *C;
    cs_di *G;
    int n_amb_axes; /* 2 * number of AMBs */
    td_amb_axis *amb_axes;
    int n_controller_states; /* AMB controller states: a lag state Fc per axis with tau > 0, then an
                              * integrator state e per axis with kint > 0, then the states of each
                              * continuous linear controller in turn */
    int n_laws;              /* linear controllers, in the model's order */
    td_lti_law *laws;
    double *gravity_load; /* M g, length ndof: the weight as nodal forces */
    /* housing motion (touchdown/housing.h): all NULL when the model has none */
    double *base_load[4]; /* ndof: M R_x, M R_y, M T_x, M T_y: the inertial load of a unit base acceleration
                           * (translation x, y; rotation about x, y at z_ref); projected like gravity_load */
    double *base_gyro[2]; /* ndof: G T_x, G T_y (per unit speed): the gyroscopic load of a unit base rate */
    /* housing body */
    int nbody;          /* the housing body's DOFs (assemble_body.c), the last nbody coordinates of q; 0: none */
    double *body_field; /* (ndof - nbody) x nbody, column-major: R, the rotor's rigid displacement of a unit
                         * body DOF (translation, or rotation about the body's centre); NULL: no body */
};

/* Mark AMB `amb`'s axes off (off != 0) or working, so that the contact-free system's analyses
 * (touchdown/modal.h) are of the machine with the AMBs that work now. */
void td_system_set_amb_off(td_system *s, int amb, int off);

/* Replace M, K, C, G and the gravity load (all physical on entry) by their Craig-Bampton reduction
 * at the model's cut-off and fill the reduction fields (reduce.c). */
td_status td_system_reduce(td_system *s, td_error *err);
/* Free the reduction fields. */
void td_system_reduction_free(td_system *s);
/* Generalized load f_q = T^T f_phys (ndof long) of a physical load f_phys (nphys long); a copy for
 * the full model. A housing body's rows are 0: td_system_body_share adds its share of a load from
 * outside the machine. */
void td_system_project_load(const td_system *s, const double *f_phys, double *f_q);
/* Node of coordinate i of q and its offset in *offset; -1 for a fixed-interface modal coordinate. */
int td_system_coordinate_node(const td_system *s, int i, int *offset);
/* Displacement scale of coordinate i: 1 for a physical DOF, the mode's largest nodal amplitude
 * (m per unit coordinate) for a modal one. */
double td_system_coordinate_amplitude(const td_system *s, int i);

/* Triplets -> compressed column, duplicates summed, rows sorted (sparse.c); NULL on out-of-memory. */
cs_di *td_system_compress(const cs_di *T);

/* housing body */
/* Append the housing body's DOFs to q (assemble_body.c): the coupled M and G, the mounts' K and C,
 * the whole machine's weight on them. After the reduction; nothing without a body. */
td_status td_system_add_housing_body(td_system *s, td_error *err);
/* f[body rows] += R^T f[rotor rows] (f ndof long): the body's share of a load on the rotor from
 * outside the machine (a weight, an unbalance), not of a force between rotor and housing. */
void td_system_body_share(const td_system *s, double *f);
/* The rigid field at node `node`'s axial position: its x (rx) and y (ry) displacement per unit body
 * DOF (4 each; 0 past the body's DOFs, all 0 without a body). */
void td_system_body_point_field(const td_system *s, int node, double rx[4], double ry[4]);
/* The body's share of a point force (fx, fy) at node `node`'s axial position (on the rotor or on a
 * race there): f[body rows] += its R^T (fx, fy); nothing without a body. */
void td_system_body_point_force(const td_system *s, int node, double fx, double fy, double *f);
/* The body's static displacement dh (nbody) under the load `load` (nbody) on its DOFs, on its mounts. */
void td_system_body_static(const td_system *s, const double *load, double *dh);

/* --- The AMB axis law (docs/reference-rig.md), one place for modal analysis and simulation. --- */

/* Lag-free control force -ki (kp xs + kd vs + kint e): the current-controlled force when
 * tau == 0, and the target the lagged force Fc relaxes to otherwise (e: the integrator state, 0
 * without one). */
double td_amb_axis_command(const td_amb_axis *a, double xs, double vs, double e);

/* The force target ki i of the amplifier commanded with the current i (A): what a current command
 * (a linear controller's output, or the loop analysis's input, touchdown/modal.h) asks of it. */
double td_amb_axis_current_command(const td_amb_axis *a, double current);

/* The amplifier lag dFc/dt = (command - Fc) / tau towards a force target `command`, for tau > 0. */
double td_amb_axis_lag_rate(const td_amb_axis *a, double command, double fc);

/* Filter rate dFc/dt = (command - Fc) / tau, for tau > 0. */
double td_amb_axis_filter_rate(const td_amb_axis *a, double xs, double vs, double e, double fc);

/* The amplifier's slew-rate limit on the lag's rate `rate` (td_amb_axis_filter_rate, or a linear
 * controller's (ki i - Fc)/tau): 1 while rate > ki slew_rate (the amplifier slews up, dFc/dt held
 * at ki slew_rate), -1 while rate < -ki slew_rate, else 0 (always 0 without a limit). */
int td_amb_axis_slewing(const td_amb_axis *a, double rate);

/* dFc/dt = clip(rate, +-ki slew_rate): `rate` itself (no operation on it) without a limit or
 * inside it. */
double td_amb_axis_slew(const td_amb_axis *a, double rate);

/* Integrator rate de/dt: xs while the controller runs (`running`: the AMB on and under its own
 * control), 0 while it is off, and 0 while the force `f` (td_amb_axis_force) is clipped or the
 * amplifier slews (the lag's unclipped rate `rate`, td_amb_axis_slewing) and integrating xs would
 * push it deeper into the clip (anti-windup by clamping). `rate` matters only with a slew limit. */
double td_amb_axis_integral_rate(const td_amb_axis *a, int running, double xs, double f, double rate);

/* Total force on the rotor ks x + fc, clipped to +-capacity when saturation is on and
 * `enabled`; 0 when not enabled (failed AMB). *dfdx and *dfdfc (may be NULL) receive the
 * partial derivatives of the returned force with respect to x and fc. */
double td_amb_axis_force(const td_amb_axis *a, int enabled, double x, double fc, double *dfdx, double *dfdfc);

#endif
