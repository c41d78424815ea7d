/*
 * touchdown/dofs.h - the one place that states DOF ordering, units and sign conventions.
 *
 * Every other file refers here rather than restating these facts.
 *
 * Units: SI throughout. Lengths m, masses kg, inertias kg m^2, forces N, moments N m, angles rad,
 * speeds rad/s (rpm only for display: TD_RPM_FROM_RAD_S), time s, stiffness N/m, damping N s/m, unbalance kg m, AMB
 * gains ki N/A, kp A/m, kd A s/m, currents A.
 *
 * Axes: the shaft axis is z, running from node 0 (the non-driven end, NDE) to the last node
 * (the driven end, DE). x and y are fixed (non-rotating) lateral axes with x, y, z right-handed.
 * The rotor spins about +z at speed Omega >= 0 (forward spin: from x towards y). Every speed the
 * library takes is one of these (TD_SPEED_VALID): the forward and backward whirl of the modal
 * analysis, the rolling direction of a race and the sign of the friction work are all counted
 * from this spin. A machine that turns the other way is the same machine seen from its other end:
 * number its nodes from the driven end and its spin is about +z again.
 *
 * Degrees of freedom: four per node, interleaved node by node (this keeps the matrices banded):
 *
 *   q[4 i + TD_DOF_X]      x_i      lateral displacement along x                       (m)
 *   q[4 i + TD_DOF_Y]      y_i      lateral displacement along y                       (m)
 *   q[4 i + TD_DOF_THETA]  theta_i  small rotation about the x axis,  theta = -dy/dz   (rad)
 *   q[4 i + TD_DOF_PHI]    phi_i    small rotation about the y axis,  phi   = +dx/dz   (rad)
 *
 * This is the paper's q = [x, y, theta, phi] (eq. 2) regrouped per node, and the convention of
 * Friswell et al., "Dynamics of Rotating Machines" (2010), which ross-rotordynamics also follows.
 *
 * Equations of motion of the contact-free rotor (the paper's eq. 1 with gyroscopics explicit):
 *
 *   M q'' + (C + Omega G) q' + K q = f(t)
 *
 * with G skew-symmetric; for a disc G has +Ip at (theta, phi) and -Ip at (phi, theta), so the
 * forward whirl frequency rises with speed.
 *
 * Forces: a force on the rotor is positive along +x / +y; a contact normal force N >= 0 pushes
 * the rotor towards the retainer centre; a friction force is tangential, positive along the
 * whirl direction t = (-sin(whirl angle), cos(whirl angle)).
 *
 * Undefined values: a quantity that has no value is TD_UNDEFINED (a quiet NaN) and nothing
 * else, never 0 or a negative sentinel: the answers of a run that did not reach its end or of a
 * sweep point that failed, timed out or was not run, a time or frequency of something that did
 * not happen (no contact: no first-contact time; no whirl: no whirl frequency). Test it with
 * td_is_undefined. The outputs carry it as null in JSON and NaN in HDF5 and CSV (written `nan`),
 * always with a status beside it that says why (docs/output-format.md, "Undefined values").
 * Counts and indices are whole numbers: a count of a run is never undefined (a sweep table's row
 * of a point with no run has NaN counts, as its other answers), an index that names nothing is -1
 * (JSON null).
 */
#ifndef TOUCHDOWN_DOFS_H
#define TOUCHDOWN_DOFS_H

#include <float.h>
#include <math.h>

#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Degrees of freedom per node. */
#define TD_DOFS_PER_NODE 4

/** Offsets of the four nodal DOFs inside a node's block. */
enum td_dof_offset {
    TD_DOF_X = 0,     /**< x displacement, m */
    TD_DOF_Y = 1,     /**< y displacement, m */
    TD_DOF_THETA = 2, /**< rotation about x (= -dy/dz), rad */
    TD_DOF_PHI = 3    /**< rotation about y (= +dx/dz), rad */
};

/** Global index of DOF `offset` (a td_dof_offset) at node `node`. */
#define TD_DOF(node, offset) (TD_DOFS_PER_NODE * (node) + (offset))

/** 1 if w is a rotor speed the library takes: finite and >= 0 rad/s (the spin is about +z). */
#define TD_SPEED_VALID(w) ((w) >= 0.0 && (w) <= DBL_MAX)

/** pi: angles are in rad, speeds in rad/s. */
#define TD_PI 3.14159265358979323846

/** A speed in rad/s as rpm (revolutions per minute: one revolution is 2 pi rad, a minute 60 s),
 *  and back; only for display, the library takes and gives rad/s. */
#define TD_RPM_FROM_RAD_S(w) ((w)*30.0 / TD_PI)

/** 1 g, m/s^2: the standard acceleration of gravity (CGPM 1901), the unit `g` of shocks and of a
 *  housing history's columns; the library takes and gives m/s^2. */
#define TD_STANDARD_GRAVITY 9.80665

/** The value of a quantity that has none (see "Undefined values" above). */
#define TD_UNDEFINED ((double)NAN)

/** 1 if x is TD_UNDEFINED (any NaN), else 0. */
TD_API int td_is_undefined(double x);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_DOFS_H */
