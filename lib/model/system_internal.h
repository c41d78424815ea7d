/*
 * The td_system record and the AMB axis law, inside the library only.
 * Matrices are CXSparse (SuiteSparse) compressed-column, duplicates summed, square ndof x ndof.
 */
#ifndef TD_SYSTEM_INTERNAL_H
#define TD_SYSTEM_INTERNAL_H

#include "touchdown/dofs.h"
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
    int state; /* index of its filter state Fc among the filter states, or -1 when tau == 0 */
} td_amb_axis;

struct td_system {
    td_model *model; /* owned copy */
    int nnodes;
    int ndof;
    cs_di *M;
    cs_di *K;
    cs_di *C;
    cs_di *G;
    int n_amb_axes; /* 2 * number of AMBs */
    td_amb_axis *amb_axes;
    int n_filter_states;  /* number of AMB axes with tau > 0 */
    double *gravity_load; /* M g, length ndof: the weight as nodal forces */
};

/* --- The AMB axis law (docs/reference-rig.md), one place for modal analysis and simulation. --- */

/* Lag-free control force -ki (kp xs + kd vs): the current-controlled force when tau == 0,
 * and the target the lagged force Fc relaxes to otherwise. */
double td_amb_axis_command(const td_amb_axis *a, double xs, double vs);

/* Filter rate dFc/dt = (command - Fc) / tau, for tau > 0. */
double td_amb_axis_filter_rate(const td_amb_axis *a, double xs, double vs, double fc);

/* Total force on the rotor ks x + fc, clipped to +-capacity when saturation is on and
 * `enabled`; 0 when not enabled (failed AMB). *dfdx and *dfdfc (may be NULL) receive the
 * partial derivatives of the returned force with respect to x and fc. */
double td_amb_axis_force(const td_amb_axis *a, int enabled, double x, double fc, double *dfdx, double *dfdfc);

#endif
