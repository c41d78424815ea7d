/*
 * The rigid field of a small rigid motion of the housing or of its body: the one place that turns a
 * translation and a rotation about an axial point into the DOFs of a point at axial offset dz from
 * it, after touchdown/dofs.h (theta = -dy/dz, phi = +dx/dz).
 */
#ifndef TD_MODEL_RIGID_MOTION_H
#define TD_MODEL_RIGID_MOTION_H

#include "touchdown/dofs.h"

/* The DOFs (x, y, theta, phi: the TD_DOF_ order) at axial offset dz, m, of the rigid motion `motion`
 * (translation x, y of the point dz = 0; rotation theta about x and phi about y, in the same order):
 * x = x0 + dz phi, y = y0 - dz theta, the rotations the same at every point. The same map takes
 * velocities and accelerations (the rates and rate changes in theta and phi). */
static inline void td_rigid_motion_at(const double motion[TD_DOFS_PER_NODE], double dz, double out[TD_DOFS_PER_NODE])
{
    out[TD_DOF_X] = motion[TD_DOF_X] + dz * motion[TD_DOF_PHI];
    out[TD_DOF_Y] = motion[TD_DOF_Y] - dz * motion[TD_DOF_THETA];
    out[TD_DOF_THETA] = motion[TD_DOF_THETA];
    out[TD_DOF_PHI] = motion[TD_DOF_PHI];
}

/* The unit rigid motion j (the TD_DOF_ order: 0, 1 translation along x, y; 2, 3 rotation about x,
 * y) at axial offset dz: out as td_rigid_motion_at gives it. */
static inline void td_rigid_unit_at(int j, double dz, double out[TD_DOFS_PER_NODE])
{
    double e[TD_DOFS_PER_NODE] = {0.0, 0.0, 0.0, 0.0};
    e[j] = 1.0;
    td_rigid_motion_at(e, dz, out);
}

#endif
