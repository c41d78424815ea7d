/*
 * Rotor-retainer contact laws, inside the library only: small pure functions of the state of
 * one retainer node (x, y and their rates), unit-tested on their own (tests/test_contact.c).
 *
 * Conventions (touchdown/dofs.h): the normal n = (x, y)/r points outward, the tangent
 * t = (-y, x)/r along the whirl direction; a normal force N >= 0 pushes the rotor along -n,
 * a friction force F_t acts along t (the rotor feels -sgn(v_s) mu N t, eq. 17).
 *
 * The constraint of eq. (5), f1 = c^2 - x^2 - y^2, is used divided by -2c:
 *
 *     g(q) = (x^2 + y^2 - c^2) / (2c),      J = dg/dq = (x, y)/c on the node's x, y DOFs,
 *
 * so g has units of length, J is dimensionless (|J| = 1 on the circle) and the Lagrange
 * multiplier lambda of M q'' + ... + J^T lambda = f (eq. 6) is the normal force in N.
 */
#ifndef TD_CONTACT_H
#define TD_CONTACT_H

#include "touchdown/model.h"
#include "touchdown/options.h"

/* ---- geometry ---------------------------------------------------------------------------- */

/* Outward normal n = (x, y)/r and whirl tangent t = (-y, x)/r; returns r. At r == 0 the frame
 * is undefined: n = (1, 0), t = (0, 1) are returned. */
double td_contact_frame(double x, double y, double n[2], double t[2]);

/* Radial velocity (x vx + y vy)/r, positive outward (0 at r == 0). */
double td_contact_radial_velocity(double x, double y, double vx, double vy);

/* Tangential velocity (x vy - y vx)/r, positive along the whirl direction (0 at r == 0). */
double td_contact_tangential_velocity(double x, double y, double vx, double vy);

/* ---- constrained contact (eqs. 5-15, scaled as above) ------------------------------------ */

/* g = (x^2 + y^2 - c^2)/(2c): negative inside the clearance circle, 0 on it. */
double td_contact_constraint(double x, double y, double c);

/* J = (x, y)/c. */
void td_contact_constraint_jacobian(double x, double y, double c, double J[2]);

/* The D term of eqs. (13b)/(14) in this scaling: Jdot v = (vx^2 + vy^2)/c, so that
 * g'' = J v' + D and the acceleration-level constraint reads J v' = -D. */
double td_contact_constraint_dterm(double vx, double vy, double c);

/* ---- penalty contact (eq. 4 and its generalisations) ------------------------------------- */

typedef struct td_penalty_law {
    double stiffness;           /* Kc, N/m^p */
    double exponent;            /* p >= 1 */
    td_contact_damping damping; /* none, Hunt-Crossley, Kelvin-Voigt */
    double coefficient;         /* s/m (Hunt-Crossley) or N s/m (Kelvin-Voigt) */
} td_penalty_law;

/* Normal force F_n(delta, rate) of penetration delta = r - c (m) and its rate (m/s):
 *   none:          Kc delta^p
 *   Hunt-Crossley: Kc delta^p (1 + d rate)
 *   Kelvin-Voigt:  Kc delta^p + d rate
 * all clipped at >= 0 (a contact never pulls) and 0 for delta <= 0. *dF_ddelta and
 * *dF_drate (may be NULL) receive the partial derivatives (0 where the force is clipped). */
double td_contact_penalty_force(const td_penalty_law *law, double delta, double rate, double *dF_ddelta,
                                double *dF_drate);

/* ---- friction (eqs. 16, 17) -------------------------------------------------------------- */

/* Sliding velocity eq. (16): v = R_s Omega + (R_b - R_s) dtheta/dt - R_b Omega_b with the race
 * speed Omega_b = race_speed and the whirl rate dtheta/dt = (x vy - y vx)/r^2 (0 at r == 0); x, y,
 * vx, vy are the node's position and velocity relative to the race centre. d v / d Omega_b = -R_b. */
double td_contact_sliding_velocity(const td_retainer *ret, double omega, double race_speed, double x, double y,
                                   double vx, double vy);

/* Partial derivatives of v_s (eq. 16) by (x, y, vx, vy) into g[4] (0 at r == 0). */
void td_contact_sliding_velocity_gradient(const td_retainer *ret, double x, double y, double vx, double vy,
                                          double g[4]);

/* Half-width v_reg of the slip-regularised band of Coulomb's law, m/s (docs/theory.md, friction):
 * a micro-slip (creep) speed, small against the sliding speeds of a touchdown (metres per second;
 * 2 m/s in cases A and B) and large against the integrator's velocity noise. */
#define TD_CONTACT_SLIP_BAND 1e-4

/* Slip factor phi of the regularised eq. (17): sgn(v_s) for |v_s| >= vreg, v_s / vreg inside the
 * band. *dphi (may be NULL) receives d phi / d v_s (1/vreg inside the band, 0 outside). */
double td_contact_slip_factor(double vs, double vreg, double *dphi);

/* Friction force on the rotor along the whirl tangent t: -phi mu N (eq. 17 regularised; phi the
 * slip factor, +-1 when sliding). */
double td_contact_friction_force(double mu, double phi, double normal_force);

/* ---- impact map ------------------------------------------------------------------------- */

/* One sparse constraint row: two entries on the x, y DOFs of a node (count 2), the opposite two on
 * the x, y DOFs of the race centre when the race moves on a mount (count 4: the contact sees the
 * node relative to the race), and one on the race speed (count up to 5: the rolling constraint). */
typedef struct td_contact_row {
    int count;
    int dof[6]; /* node x, y; race centre x, y; race speed; rotor speed */
    double j[6];
} td_contact_row;

/* J_k x. */
double td_contact_row_dot(const td_contact_row *row, const double *x);
/* x += J_k^T. */
void td_contact_row_scatter(const td_contact_row *row, double *x);

/* Generalised Newton impact law for m simultaneous constraints on an n-DOF system:
 *
 *     P = (J M^-1 J^T)^-1 diag(1 + e) J v-,      v+ = v- - M^-1 J^T P,
 *
 * so J_k v+ = -e_k J_k v- (the constraint rate is reversed and scaled by the restitution), and the
 * momentum M v changes only along the columns of J^T: u^T M v is kept for every u with J u = 0.
 * minv_jt holds M^-1 J^T column-major (n x m, column k = M^-1 J_k^T, computed by the caller from its
 * factorisation of M). On return v holds v+ and impulse[k] = P_k (N s, along -J_k^T on the rotor:
 * positive pushes it inward). work has room for m * (m + 1) doubles.
 * Returns 0, or -1 when J M^-1 J^T is singular (v unchanged). */
int td_contact_impact_map(int n, int m, const td_contact_row *rows, const double *minv_jt, const double *restitution,
                          double *v, double *impulse, double *work);

/* Solve the small dense system A x = b (m x m, column-major, overwritten) by Gaussian elimination
 * with partial pivoting; b is replaced by x. Returns 0, or -1 when A is singular. */
int td_contact_dense_solve(int m, double *A, double *b);

#endif
