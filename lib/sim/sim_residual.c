/*
 * The contact DAE of sim_internal.h: generalised forces, residual, analytic Jacobian, root
 * functions. Everything here is a pure function of the sim's current modes and machine state.
 */
#include "sim/sim_internal.h"

#include <math.h>
#include <string.h>

double td_sim_spin_angle(const td_sim *s, double t)
{
    return s->machine.spin_ref + s->machine.omega * (t - s->machine.t_spin_ref);
}

/* dOmega/dt at (t, y): the ramp's slope on the interval being integrated, (s->dae.t, t] (at t = s->dae.t
 * the segment starting there), or a free spin's torque balance over J (spin.c). */
static double rotor_rate(const td_sim *s, double t, const double *y)
{
    td_spin sp;
    double torque;
    int k;
    if (s->machine.spin < 0)
        return 0.0;
    torque = td_sim_spin_torque(s, t);
    if (!s->machine.spin_free)
        return torque / s->machine.spin_inertia;
    td_model_spin(s->model, &sp);
    torque -= td_sim_spin_drag(s, y, NULL) + sp.drag_viscous * y[s->dae.ov + s->machine.spin];
    for (k = 0; k < s->dae.nr; k++) /* zero for a free retainer: no normal force */
        torque -= s->contacts.ret[k].r.shaft_radius * td_sim_friction_force(s, k, y);
    return torque / s->machine.spin_inertia;
}

/* The integrator state e of an AMB axis (0 for a PD axis). */
static double amb_axis_integral(const td_sim *s, const td_amb_axis *a, const double *y)
{
    return a->integral >= 0 ? y[s->dae.ow + a->integral] : 0.0;
}

/* The controller's command -ki (kp xs + kd vs + kint e) of an AMB axis at y. */
static double amb_axis_command(const td_sim *s, const td_amb_axis *a, const double *y)
{
    return td_amb_axis_command(a, y[s->dae.oq + a->sensor_dof], y[s->dae.ov + a->sensor_dof],
                               amb_axis_integral(s, a, y));
}

/* The target force ki i of the current command i of an axis a linear controller drives. */
static double amb_axis_current_target(const td_sim *s, const td_amb_axis *a, const double *y)
{
    return td_amb_axis_current_command(a, td_sim_lti_current(s, a, y));
}

/* The target force ki i of the current the caller holds on an axis (TD_AMB_CURRENT), as a sampled
 * law's held current (td_sim_lti_current) enters amb_axis_current_target. */
static double amb_axis_caller_target(const td_sim *s, const td_amb_axis *a)
{
    return td_amb_axis_current_command(a, s->machine.amb_current[2 * a->amb + a->axis]);
}

/* Control force Fc of AMB axis k that enters F = ks x + Fc: the lagged state (tau > 0), the
 * lag-free command (tau == 0: the shorthand's, ki i of a linear controller's current or of the
 * caller's held current) or the caller's held force (TD_AMB_EXTERNAL). */
static double amb_axis_fc(const td_sim *s, int k, const double *y)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    if (s->machine.amb_mode[a->amb] == TD_AMB_EXTERNAL)
        return s->machine.amb_control[2 * a->amb + a->axis];
    if (a->state >= 0)
        return y[s->dae.ow + a->state];
    if (s->machine.amb_mode[a->amb] == TD_AMB_CURRENT)
        return amb_axis_caller_target(s, a);
    if (a->law >= 0)
        return amb_axis_current_target(s, a, y);
    return amb_axis_command(s, a, y);
}

double td_sim_amb_axis_force(const td_sim *s, int k, const double *y)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    int enabled = s->machine.amb_mode[a->amb] != TD_AMB_OFF;
    return td_amb_axis_force(a, enabled, y[s->dae.oq + a->actuator_dof], amb_axis_fc(s, k, y), NULL, NULL);
}

/* The lag's rate (command - Fc)/tau of AMB axis k (tau > 0) at y, before the amplifier's slew
 * limit (model/amb.c td_amb_axis_slew): towards the shorthand's command, or the target ki i of its
 * linear controller's current or of the caller's (TD_AMB_CURRENT). */
static double amb_axis_lag_rate(const td_sim *s, const td_amb_axis *a, const double *y)
{
    if (s->machine.amb_mode[a->amb] == TD_AMB_CURRENT)
        return td_amb_axis_lag_rate(a, amb_axis_caller_target(s, a), y[s->dae.ow + a->state]);
    if (a->law >= 0)
        return td_amb_axis_lag_rate(a, amb_axis_current_target(s, a, y), y[s->dae.ow + a->state]);
    return td_amb_axis_filter_rate(a, y[s->dae.oq + a->sensor_dof], y[s->dae.ov + a->sensor_dof],
                                   amb_axis_integral(s, a, y), y[s->dae.ow + a->state]);
}

/* 1 or -1 while AMB axis k's amplifier slews up or down at y (td_amb_axis_slewing), else 0; 0
 * without a slew limit, with no rate computed. */
static int amb_axis_slews(const td_sim *s, const td_amb_axis *a, const double *y)
{
    if (!(a->slew_rate > 0.0) || a->state < 0)
        return 0;
    return td_amb_axis_slewing(a, amb_axis_lag_rate(s, a, y));
}

int td_sim_amb_slewing_axes(const td_sim *s, const double *y)
{
    int k, n = 0;
    for (k = 0; k < s->sys->n_amb_axes && s->dae.n_slew_roots > 0; k++)
        n += amb_axis_slews(s, &s->sys->amb_axes[k], y) != 0;
    return n;
}

double td_sim_amb_axis_lag_rate(const td_sim *s, int k, const double *y)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    return td_amb_axis_slew(a, amb_axis_lag_rate(s, a, y));
}

double td_sim_amb_axis_integral_rate(const td_sim *s, int k, const double *y)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    if (a->integral < 0)
        return 0.0;
    /* the unclipped lag rate only where a slew limit reads it: a case without one computes nothing more */
    return td_amb_axis_integral_rate(a, s->machine.amb_mode[a->amb] == TD_AMB_PD, y[s->dae.oq + a->sensor_dof],
                                     td_sim_amb_axis_force(s, k, y),
                                     a->slew_rate > 0.0 && a->state >= 0 ? amb_axis_lag_rate(s, a, y) : 0.0);
}

/* out = M vp + D v + K q (D = C + Omega G), row by row over the union pattern; vp == NULL
 * leaves out M vp. One pass over the indices instead of one per matrix. */
static void structural(const td_sim *s, const double *q, const double *v, const double *vp, double *out)
{
    const int *rp = s->ops.st_rowptr, *col = s->ops.st_col;
    const double *Mx = s->ops.st_M, *Kx = s->ops.st_K, *Dx = s->ops.st_D;
    int i, p;
    if (vp) {
        for (i = 0; i < s->dae.n; i++) {
            double acc = 0.0;
            for (p = rp[i]; p < rp[i + 1]; p++) {
                int j = col[p];
                acc += Mx[p] * vp[j] + Dx[p] * v[j] + Kx[p] * q[j];
            }
            out[i] = acc;
        }
    } else {
        for (i = 0; i < s->dae.n; i++) {
            double acc = 0.0;
            for (p = rp[i]; p < rp[i + 1]; p++) {
                int j = col[p];
                acc += Dx[p] * v[j] + Kx[p] * q[j];
            }
            out[i] = acc;
        }
    }
}

/* out += (Omega - omega) G v: with a spin DOF the structural operator was built at s->machine.omega and
 * the gyroscopic term follows the speed Omega of the state (spin.c). */
static void gyroscopic_follow(const td_sim *s, const double *y, double *out)
{
    const cs_di *G = s->dae.G;
    const double *v = y + s->dae.ov;
    double dw;
    int j, p;
    if (s->machine.spin < 0 || (dw = td_sim_rotor_speed(s, y) - s->machine.omega) == 0.0)
        return;
    for (j = 0; j < G->n; j++)
        for (p = G->p[j]; p < G->p[j + 1]; p++)
            out[G->i[p]] += dw * G->x[p] * v[j];
}

/* f += sign * the force of retainer k's penalty contact: -F_n (n + s mu t) on the rotor (eqs. 4,
 * 17), F_n > 0 only when penetrating; the opposite on a mounted race, and the friction torque
 * R_b s mu F_n on a race that spins. */
static void penalty_forces(const td_sim *s, int k, const double *y, double sign, double *f)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, rad, fn, sm, fx, fy;
    fn = sign * td_sim_penalty_force(s, k, y, NULL, NULL);
    if (fn == 0.0)
        return;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    sm = td_sim_slip_factor(s, k, y, NULL) * r->r.friction;
    fx = fn * (x - sm * yy) / rad;
    fy = fn * (yy + sm * x) / rad;
    f[r->dx] -= fx;
    f[r->dy] -= fy;
    if (r->rx >= 0) {
        f[r->rx] += fx;
        f[r->ry] += fy;
    }
    if (r->rs >= 0)
        f[r->rs] += r->r.bore_radius * sm * fn;
    if (s->machine.spin_free)
        f[s->machine.spin] -= r->r.shaft_radius * sm * fn;
}

/* f += sign * the applied forces: gravity, unbalance, AMBs, penalty contacts and the races'
 * constant drag (everything of f but the structural -(C + Omega G) v - K q). */
void td_sim_external_forces(const td_sim *s, double t, const double *y, double sign, double *f)
{
    const td_system *sys = s->sys;
    double w = td_sim_rotor_speed(s, y), w2 = w * w, phi = td_sim_rotor_angle(s, t, y);
    double alpha = s->machine.nu > 0 ? rotor_rate(s, t, y) : 0.0; /* a free spin's sums the torques */
    int i, k;
    for (i = 0; i < sys->ndof; i++)
        f[i] += sign * sys->gravity_load[i];
    td_sim_races_gravity(s, f, sign);
    /* unbalance: U Omega^2 (cos, sin)(phi + phase) at its node (touchdown/model.h), and while the
     * speed changes U alpha (sin, -cos)(phi + phase) (spin.c) */
    for (i = 0; i < s->machine.nu; i++) {
        const td_unbalance *u = &s->machine.unb[i];
        double a = sign * u->magnitude * w2;
        f[td_system_node_dof(s->sys, u->node, TD_DOF_X)] += a * cos(phi + u->phase);
        f[td_system_node_dof(s->sys, u->node, TD_DOF_Y)] += a * sin(phi + u->phase);
        /* from outside the machine: a housing body carries it too (no body: nothing) */
        td_system_body_point_force(sys, u->node, a * cos(phi + u->phase), a * sin(phi + u->phase), f);
        if (alpha != 0.0) {
            double b = sign * u->magnitude * alpha;
            f[td_system_node_dof(s->sys, u->node, TD_DOF_X)] += b * sin(phi + u->phase);
            f[td_system_node_dof(s->sys, u->node, TD_DOF_Y)] -= b * cos(phi + u->phase);
            td_system_body_point_force(sys, u->node, b * sin(phi + u->phase), -b * cos(phi + u->phase), f);
        }
    }
    if (s->machine.spin >= 0)
        f[s->machine.spin] += sign * td_sim_spin_torque(s, t);
    for (k = 0; k < sys->n_amb_axes; k++)
        f[sys->amb_axes[k].actuator_dof] += sign * td_sim_amb_axis_force(s, k, y);
    if (sys->base_load[0])
        td_sim_housing_forces(s, t, y, sign, f);
}

/* f += sign * the housing motion's inertial loads (touchdown/housing.h, docs/theory.md "Base motion"):
 * -M R a - M T alpha - Omega G T w on the rotor at the speed Omega it has now (also a varying one),
 * the races' share beside it (race.c). They depend on the state only through a free spin's Omega;
 * the Jacobian leaves that column's G T w out (a load of the order Ip w, which the Newton iteration
 * absorbs as it does any inexact Jacobian). */
void td_sim_housing_forces(const td_sim *s, double t, const double *y, double sign, double *f)
{
    const td_system *sys = s->sys;
    double w = td_sim_rotor_speed(s, y), c[6];
    td_housing_motion hm;
    int i;
    if (!sys->base_load[0])
        return;
    td_model_housing_motion_at(s->model, t, &hm);
    c[0] = -sign * hm.acceleration[0], c[1] = -sign * hm.acceleration[1];
    c[2] = -sign * hm.rate_change[0], c[3] = -sign * hm.rate_change[1];
    c[4] = -sign * w * hm.rate[0], c[5] = -sign * w * hm.rate[1];
    for (i = 0; i < sys->ndof; i++)
        f[i] += c[0] * sys->base_load[0][i] + c[1] * sys->base_load[1][i] + c[2] * sys->base_load[2][i] +
                c[3] * sys->base_load[3][i] + c[4] * sys->base_gyro[0][i] + c[5] * sys->base_gyro[1][i];
    td_sim_races_housing(s, &hm, f, sign);
}

static void applied_forces(const td_sim *s, double t, const double *y, double sign, double *f)
{
    int k;
    td_sim_external_forces(s, t, y, sign, f);
    for (k = 0; k < s->dae.nr; k++) {
        if (td_sim_penalty_model(s, k))
            penalty_forces(s, k, y, sign, f);
        if (s->contacts.ret[k].rs >= 0)
            f[s->contacts.ret[k].rs] -= sign * td_sim_race_drag(s, k, y, NULL);
    }
    if (s->machine.spin_free)
        f[s->machine.spin] -= sign * td_sim_spin_drag(s, y, NULL);
}

void td_sim_forces(const td_sim *s, double t, const double *y, double *f)
{
    int i;
    structural(s, y + s->dae.oq, y + s->dae.ov, NULL, f);
    gyroscopic_follow(s, y, f);
    for (i = 0; i < s->dae.n; i++)
        f[i] = -f[i];
    applied_forces(s, t, y, 1.0, f);
}

/* Rows of retainer k in constrained contact: + B_k lambda in the v rows (eq. 6 with the friction
 * of eq. 17, N = lambda; the race's opposite share and torque), - J^T eta in the q rows (GGL), and
 * the constraint and its rate (eqs. 5 and 13a, divided by -2c) in its multiplier rows. */
static void constraint_rows(const td_sim *s, int k, const double *y, double *rq, double *rv, double *res)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double lam = y[s->dae.ol + k], eta = y[s->dae.ou + k];
    double x, yy, vx, vy, c = r->r.clearance, rad, sm = td_sim_slip_factor(s, k, y, NULL) * r->r.friction, bx, by;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    bx = lam * (x / c - sm * yy / rad);
    by = lam * (yy / c + sm * x / rad);
    rv[r->dx] += bx;
    rv[r->dy] += by;
    rq[r->dx] += eta * x / c;
    rq[r->dy] += eta * yy / c;
    if (r->rx >= 0) {
        rv[r->rx] -= bx;
        rv[r->ry] -= by;
        rq[r->rx] -= eta * x / c;
        rq[r->ry] -= eta * yy / c;
    }
    if (r->rs >= 0)
        rv[r->rs] -= r->r.bore_radius * sm * lam;
    if (s->machine.spin_free)
        rv[s->machine.spin] += r->r.shaft_radius * sm * lam;
    res[s->dae.ol + k] = td_contact_constraint(x, yy, c); /* eq. (5) / (-2c) */
    res[s->dae.ou + k] = (x * vx + yy * vy) / c;          /* eq. (13a) / (-2c) */
}

/* Rows of stick retainer k: rolling, the friction force F_t on the race along t (the rotor node
 * feels -F_t t, the race's centre +F_t t and its speed the torque R_b F_t) and the rolling
 * constraint v_s = 0 (eq. 16) in F_t's row; otherwise F_t = 0. */
static void roll_rows(const td_sim *s, int k, const double *y, double *rv, double *res)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double ft = y[s->dae.of + r->fi], x, yy, vx, vy, n[2], t[2];
    if (!r->rolling) {
        res[s->dae.of + r->fi] = ft;
        return;
    }
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    td_contact_frame(x, yy, n, t);
    rv[r->dx] += ft * t[0];
    rv[r->dy] += ft * t[1];
    if (r->rx >= 0) {
        rv[r->rx] -= ft * t[0];
        rv[r->ry] -= ft * t[1];
    }
    if (r->rs >= 0)
        rv[r->rs] -= r->r.bore_radius * ft;
    if (s->machine.spin_free)
        rv[s->machine.spin] += r->r.shaft_radius * ft;
    res[s->dae.of + r->fi] = td_sim_sliding_velocity(s, k, y);
}

double td_sim_unbalance_spin_coupling(const td_sim *s, double t, const double *y, const double *yp, double *rv)
{
    double phi, dw, power = 0.0;
    int i;
    if (!s->machine.spin_free || s->machine.nu == 0)
        return 0.0;
    phi = td_sim_rotor_angle(s, t, y);
    dw = yp[s->dae.ov + s->machine.spin] - rotor_rate(s, t, y); /* the forces took alpha from the torques */
    for (i = 0; i < s->machine.nu; i++) {
        const td_unbalance *u = &s->machine.unb[i];
        double c = cos(phi + u->phase), sn = sin(phi + u->phase), U = u->magnitude;
        int x = td_system_node_dof(s->sys, u->node, TD_DOF_X), yy = td_system_node_dof(s->sys, u->node, TD_DOF_Y);
        double fx = U * sn * dw, fy = -U * c * dw, torque = -U * (c * yp[s->dae.ov + yy] - sn * yp[s->dae.ov + x]);
        if (rv) {
            rv[x] -= fx;
            rv[yy] -= fy;
            rv[s->machine.spin] -= torque;
        }
        power += fx * y[s->dae.ov + x] + fy * y[s->dae.ov + yy] + torque * y[s->dae.ov + s->machine.spin];
    }
    return power;
}

void td_sim_residual(const td_sim *s, double t, const double *y, const double *yp, double *res)
{
    const td_system *sys = s->sys;
    const double *v = y + s->dae.ov;
    double *rq = res + s->dae.oq, *rv = res + s->dae.ov;
    int i, k;

    /* q rows: q' - v (+ J^T eta below) */
    for (i = 0; i < s->dae.n; i++)
        rq[i] = yp[s->dae.oq + i] - v[i];
    /* v rows: M v' - f = M v' + (C + Omega G) v + K q - applied forces */
    structural(s, y + s->dae.oq, v, yp + s->dae.ov, rv);
    gyroscopic_follow(s, y, rv);
    applied_forces(s, t, y, -1.0, rv);
    td_sim_unbalance_spin_coupling(s, t, y, yp, rv);
    /* w rows: the AMB force lag and integrator */
    for (k = 0; k < sys->n_amb_axes; k++) {
        const td_amb_axis *a = &sys->amb_axes[k];
        if (a->state >= 0)
            res[s->dae.ow + a->state] = yp[s->dae.ow + a->state] - td_sim_amb_axis_lag_rate(s, k, y);
        if (a->integral >= 0)
            res[s->dae.ow + a->integral] = yp[s->dae.ow + a->integral] - td_sim_amb_axis_integral_rate(s, k, y);
    }
    /* and the linear controllers' states */
    td_sim_lti_rows(s, y, yp, res);
    /* retainer rows */
    for (k = 0; k < s->dae.nr; k++) {
        if (s->contacts.ret[k].mode == TD_RMODE_CONTACT) {
            constraint_rows(s, k, y, rq, rv, res);
        } else {
            res[s->dae.ol + k] = y[s->dae.ol + k];
            res[s->dae.ou + k] = y[s->dae.ou + k];
        }
        if (s->contacts.ret[k].fi >= 0)
            roll_rows(s, k, y, rv, res);
    }
    if (s->machine.spin >= 0 && !s->machine.spin_free) { /* a ramp: angle and speed are the prescribed ones, exactly */
        double angle, w = td_model_speed_at(s->model, t, NULL, &angle);
        rq[s->machine.spin] = y[s->dae.oq + s->machine.spin] - angle;
        rv[s->machine.spin] = y[s->dae.ov + s->machine.spin] - w;
    }
}

/* jdata[pos(row, col)] += v; the pattern is a superset of every entry written here. */
static void jadd(td_sim *s, int row, int col, double v)
{
    int p = td_sim_pattern_find(s, row, col);
    if (p >= 0)
        s->ops.jdata[p] += v;
}

/* Add the stored entries of a system matrix times `scale` through its position map. */
static void jadd_matrix(td_sim *s, const cs_di *A, const int *map, double scale)
{
    int p, nz = A->p[A->n];
    if (scale == 0.0)
        return;
    for (p = 0; p < nz; p++)
        s->ops.jdata[map[p]] += scale * A->x[p];
}

static void jacobian_amb(td_sim *s, const double *y)
{
    const td_system *sys = s->sys;
    int k;
    for (k = 0; k < sys->n_amb_axes; k++) {
        const td_amb_axis *a = &sys->amb_axes[k];
        const td_sim_amb_coef *co = &s->machine.amb_coef[k];
        td_amb_mode mode = s->machine.amb_mode[a->amb];
        int act = a->actuator_dof, sen = a->sensor_dof;
        double dfdx, dfdfc;
        td_amb_axis_force(a, mode != TD_AMB_OFF, y[s->dae.oq + act], amb_axis_fc(s, k, y), &dfdx, &dfdfc);
        /* v rows carry -f_amb */
        jadd(s, s->dae.ov + act, s->dae.oq + act, -dfdx);
        if (mode == TD_AMB_CURRENT && a->state >= 0) { /* Fc is the lag's state; its target is held */
            jadd(s, s->dae.ov + act, s->dae.ow + a->state, -dfdfc);
        } else if (mode == TD_AMB_PD) {
            if (a->state >= 0) {
                jadd(s, s->dae.ov + act, s->dae.ow + a->state, -dfdfc);
            } else {
                jadd(s, s->dae.ov + act, s->dae.oq + sen, -dfdfc * co->cmd_x);
                jadd(s, s->dae.ov + act, s->dae.ov + sen, -dfdfc * co->cmd_v);
                if (a->integral >= 0)
                    jadd(s, s->dae.ov + act, s->dae.ow + a->integral, -dfdfc * co->cmd_e);
                if (a->law >= 0) /* d target / d i = ki */
                    td_sim_lti_jacobian_current(s, a, s->dae.ov + act, -dfdfc * co->target_i);
            }
        }
        if (a->state >= 0 && mode == TD_AMB_CURRENT && !amb_axis_slews(s, a, y)) { /* (ki i - Fc)/tau */
            jadd(s, s->dae.ow + a->state, s->dae.ow + a->state, -co->rate_w);
        } else if (a->state >= 0 && !amb_axis_slews(s, a, y)) { /* slewing, dFc/dt = +-ki slew_rate: constant */
            int row = s->dae.ow + a->state;
            jadd(s, row, s->dae.oq + sen, -co->rate_x);
            jadd(s, row, s->dae.ov + sen, -co->rate_v);
            jadd(s, row, row, -co->rate_w);
            if (a->integral >= 0)
                jadd(s, row, s->dae.ow + a->integral, -co->rate_e);
            if (a->law >= 0)
                td_sim_lti_jacobian_current(s, a, row, -co->rate_i);
        }
        /* e' = xs while integrating; the clamp's switch is left to the error test, as the clip's */
        if (a->integral >= 0 && td_sim_amb_axis_integral_rate(s, k, y) != 0.0)
            jadd(s, s->dae.ow + a->integral, s->dae.oq + sen, -1.0);
    }
}

/*
 * The contact's entries come in pairs: a term of the node's row a (0: x, 1: y) that depends on the
 * relative coordinate b (node minus race centre) at level lvl (s->dae.oq or s->dae.ov) also enters, with
 * the opposite sign, through the race centre's column b, and the race's row carries the opposite of
 * the node's term (the race feels the opposite force, the GGL correction the opposite share).
 * Without a mount these are the node's entries alone.
 */
static void jadd_rel(td_sim *s, const td_sim_retainer *r, int rlvl, int a, int lvl, int b, double value)
{
    int nrow = rlvl + (a ? r->dy : r->dx), ncol = lvl + (b ? r->dy : r->dx);
    jadd(s, nrow, ncol, value);
    if (r->rx >= 0) {
        int rrow = rlvl + (a ? r->ry : r->rx), rcol = lvl + (b ? r->ry : r->rx);
        jadd(s, nrow, rcol, -value);
        jadd(s, rrow, ncol, -value);
        jadd(s, rrow, rcol, value);
    }
}

/* A term of the node's row a that depends on an absolute column (a multiplier, the race speed). */
static void jadd_node(td_sim *s, const td_sim_retainer *r, int rlvl, int a, int col, double value)
{
    jadd(s, rlvl + (a ? r->dy : r->dx), col, value);
    if (r->rx >= 0)
        jadd(s, rlvl + (a ? r->ry : r->rx), col, -value);
}

/* A term of row `row` (a multiplier's or the race speed's) that depends on relative coordinate b. */
static void jadd_row_rel(td_sim *s, const td_sim_retainer *r, int row, int lvl, int b, double value)
{
    jadd(s, row, lvl + (b ? r->dy : r->dx), value);
    if (r->rx >= 0)
        jadd(s, row, lvl + (b ? r->ry : r->rx), -value);
}

/* The rotor speed's share of the slip band (spin.c): v_s depends on Omega (d v_s / d Omega = R_s),
 * and a free spin's row carries the friction torque R_s phi mu fn, which depends on v_s. */
static void jacobian_slip_band_spin(td_sim *s, int k, const double *y, double a)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, rad, gv[4], Rs = r->r.shaft_radius, Rb = r->r.bore_radius;
    int wz = s->dae.ov + s->machine.spin, i;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    jadd_node(s, r, s->dae.ov, 0, wz, -a * Rs * yy / rad);
    jadd_node(s, r, s->dae.ov, 1, wz, a * Rs * x / rad);
    if (r->rs >= 0)
        jadd(s, s->dae.ov + r->rs, wz, -Rb * a * Rs);
    if (!s->machine.spin_free)
        return;
    td_sim_sliding_gradient(s, k, y, gv);
    for (i = 0; i < 4; i++)
        jadd_row_rel(s, r, wz, i < 2 ? s->dae.oq : s->dae.ov, i % 2, Rs * a * gv[i]);
    if (r->rs >= 0)
        jadd(s, wz, s->dae.ov + r->rs, Rs * a * (-Rb));
    jadd(s, wz, wz, Rs * a * Rs);
}

/* Inside the slip band the friction of a contact with normal force fn depends on v_s, i.e. on the
 * relative coordinates (gradient gv) and on the race speed (d v_s / d Omega_b = -R_b): the terms
 * -phi mu fn (y, -x)/r of the node's rows and -R_b phi mu fn of the race speed's row. */
static void jacobian_slip_band(td_sim *s, int k, const double *y, double fn, double dphi)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, rad, gv[4], a = fn * r->r.friction * dphi, Rb = r->r.bore_radius;
    int i;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    td_sim_sliding_gradient(s, k, y, gv);
    for (i = 0; i < 4; i++) {
        int lvl = i < 2 ? s->dae.oq : s->dae.ov, b = i % 2;
        jadd_rel(s, r, s->dae.ov, 0, lvl, b, -a * gv[i] * yy / rad);
        jadd_rel(s, r, s->dae.ov, 1, lvl, b, a * gv[i] * x / rad);
        if (r->rs >= 0)
            jadd_row_rel(s, r, s->dae.ov + r->rs, lvl, b, -Rb * a * gv[i]);
    }
    if (r->rs >= 0) {
        int ws = s->dae.ov + r->rs;
        jadd_node(s, r, s->dae.ov, 0, ws, -a * (-Rb) * yy / rad);
        jadd_node(s, r, s->dae.ov, 1, ws, a * (-Rb) * x / rad);
        jadd(s, ws, ws, -Rb * a * (-Rb));
    }
    if (s->machine.spin >= 0)
        jacobian_slip_band_spin(s, k, y, a);
}

/* Constrained contact k: d/dq of lambda (J^T + s mu t) and the GGL and constraint rows. */
static void jacobian_contact(td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, c = r->r.clearance, rad, r3, dphi, sm;
    double lam = y[s->dae.ol + k], eta = y[s->dae.ou + k];
    int lk = s->dae.ol + k, uk = s->dae.ou + k, oq = s->dae.oq, ov = s->dae.ov;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    r3 = rad * rad * rad;
    sm = td_sim_slip_factor(s, k, y, &dphi) * r->r.friction;
    /* lambda (x/c - sm y/r, y/c + sm x/r) */
    jadd_rel(s, r, ov, 0, oq, 0, lam * (1.0 / c + sm * x * yy / r3));
    jadd_rel(s, r, ov, 0, oq, 1, lam * (-sm * x * x / r3));
    jadd_rel(s, r, ov, 1, oq, 0, lam * (sm * yy * yy / r3));
    jadd_rel(s, r, ov, 1, oq, 1, lam * (1.0 / c - sm * x * yy / r3));
    jadd_node(s, r, ov, 0, lk, x / c - sm * yy / rad);
    jadd_node(s, r, ov, 1, lk, yy / c + sm * x / rad);
    if (r->rs >= 0) /* the friction torque -R_b sm lambda */
        jadd(s, ov + r->rs, lk, -r->r.bore_radius * sm);
    if (s->machine.spin_free) /* and R_s sm lambda on a free spin */
        jadd(s, ov + s->machine.spin, lk, r->r.shaft_radius * sm);
    if (dphi != 0.0) /* inside the slip band: sm = mu v_s / v_reg depends on q, v and Omega_b */
        jacobian_slip_band(s, k, y, lam, dphi);
    /* q rows: eta (x, y)/c */
    jadd_rel(s, r, oq, 0, oq, 0, eta / c);
    jadd_rel(s, r, oq, 1, oq, 1, eta / c);
    jadd_node(s, r, oq, 0, uk, x / c);
    jadd_node(s, r, oq, 1, uk, yy / c);
    /* g row and J v row */
    jadd_row_rel(s, r, lk, oq, 0, x / c);
    jadd_row_rel(s, r, lk, oq, 1, yy / c);
    jadd_row_rel(s, r, uk, oq, 0, vx / c);
    jadd_row_rel(s, r, uk, oq, 1, vy / c);
    jadd_row_rel(s, r, uk, ov, 0, x / c);
    jadd_row_rel(s, r, uk, ov, 1, yy / c);
}

/* A torque row m F_n of a penalty contact: d F_n / d(x, y) = (f_x, f_y), d F_n / d(vx, vy) = (g_x, g_y). */
static void jacobian_penalty_torque(td_sim *s, const td_sim_retainer *r, int row, double m, double f_x, double f_y,
                                    double g_x, double g_y)
{
    jadd_row_rel(s, r, row, s->dae.oq, 0, m * f_x);
    jadd_row_rel(s, r, row, s->dae.oq, 1, m * f_y);
    jadd_row_rel(s, r, row, s->dae.ov, 0, m * g_x);
    jadd_row_rel(s, r, row, s->dae.ov, 1, m * g_y);
}

/* Penalty contact k: d/dq and d/dv of F_n(delta, rate) u, u = (x - sm y, y + sm x)/r, and of the
 * friction torque R_b sm F_n on a race that spins. */
static void jacobian_penalty(td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, rad, r3, sm, dphi, fd, fr, fn, rate;
    double d_x, d_y, rt_x, rt_y, rt_vx, rt_vy, f_x, f_y, u1, u2, u1x, u1y, u2x, u2y;
    int oq = s->dae.oq, ov = s->dae.ov;
    fn = td_sim_penalty_force(s, k, y, &fd, &fr);
    if (fn == 0.0 && fd == 0.0 && fr == 0.0)
        return; /* not penetrating */
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    r3 = rad * rad * rad;
    sm = td_sim_slip_factor(s, k, y, &dphi) * r->r.friction;
    rate = (x * vx + yy * vy) / rad;
    d_x = x / rad;
    d_y = yy / rad;
    rt_x = vx / rad - rate * x / (rad * rad);
    rt_y = vy / rad - rate * yy / (rad * rad);
    rt_vx = x / rad;
    rt_vy = yy / rad;
    f_x = fd * d_x + fr * rt_x;
    f_y = fd * d_y + fr * rt_y;
    u1 = (x - sm * yy) / rad;
    u2 = (yy + sm * x) / rad;
    u1x = 1.0 / rad - (x - sm * yy) * x / r3;
    u1y = -sm / rad - (x - sm * yy) * yy / r3;
    u2x = sm / rad - (yy + sm * x) * x / r3;
    u2y = 1.0 / rad - (yy + sm * x) * yy / r3;
    jadd_rel(s, r, ov, 0, oq, 0, u1 * f_x + fn * u1x);
    jadd_rel(s, r, ov, 0, oq, 1, u1 * f_y + fn * u1y);
    jadd_rel(s, r, ov, 1, oq, 0, u2 * f_x + fn * u2x);
    jadd_rel(s, r, ov, 1, oq, 1, u2 * f_y + fn * u2y);
    jadd_rel(s, r, ov, 0, ov, 0, u1 * fr * rt_vx);
    jadd_rel(s, r, ov, 0, ov, 1, u1 * fr * rt_vy);
    jadd_rel(s, r, ov, 1, ov, 0, u2 * fr * rt_vx);
    jadd_rel(s, r, ov, 1, ov, 1, u2 * fr * rt_vy);
    if (r->rs >= 0) /* the torque row -R_b sm F_n */
        jacobian_penalty_torque(s, r, ov + r->rs, -r->r.bore_radius * sm, f_x, f_y, fr * rt_vx, fr * rt_vy);
    if (s->machine.spin_free) /* and R_s sm F_n on a free spin */
        jacobian_penalty_torque(s, r, ov + s->machine.spin, r->r.shaft_radius * sm, f_x, f_y, fr * rt_vx, fr * rt_vy);
    if (dphi != 0.0) /* inside the slip band: sm = mu v_s / v_reg depends on q, v and Omega_b */
        jacobian_slip_band(s, k, y, fn, dphi);
}

/* Stick retainer k: rolling, d/dy of the F_t terms and of the rolling row v_s; otherwise F_t's
 * row is F_t itself. d t / d(x, y) for t = (-y, x)/r: ((x y, -x^2), (y^2, -x y)) / r^3. */
static void jacobian_roll(td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double ft, x, yy, vx, vy, rad, r3, n[2], t[2], gv[4];
    int fk = s->dae.of + r->fi, oq = s->dae.oq, ov = s->dae.ov, i;
    if (!r->rolling) {
        jadd(s, fk, fk, 1.0);
        return;
    }
    ft = y[fk];
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = td_contact_frame(x, yy, n, t);
    r3 = rad * rad * rad;
    jadd_rel(s, r, ov, 0, oq, 0, ft * x * yy / r3);
    jadd_rel(s, r, ov, 0, oq, 1, -ft * x * x / r3);
    jadd_rel(s, r, ov, 1, oq, 0, ft * yy * yy / r3);
    jadd_rel(s, r, ov, 1, oq, 1, -ft * x * yy / r3);
    jadd_node(s, r, ov, 0, fk, t[0]);
    jadd_node(s, r, ov, 1, fk, t[1]);
    if (r->rs >= 0) {
        jadd(s, ov + r->rs, fk, -r->r.bore_radius);
        jadd(s, fk, ov + r->rs, -r->r.bore_radius); /* eq. (16): d v_s / d Omega_b */
    }
    if (s->machine.spin >= 0) {
        jadd(s, fk, ov + s->machine.spin, r->r.shaft_radius); /* eq. (16): d v_s / d Omega */
        if (s->machine.spin_free)
            jadd(s, ov + s->machine.spin, fk, r->r.shaft_radius);
    }
    td_sim_sliding_gradient(s, k, y, gv);
    for (i = 0; i < 4; i++)
        jadd_row_rel(s, r, fk, i < 2 ? oq : ov, i % 2, gv[i]);
}

/* The constant drag torque of retainer k's race, regularised near standstill. */
static void jacobian_drag(td_sim *s, int k, const double *y)
{
    double dT;
    td_sim_race_drag(s, k, y, &dT);
    if (dT != 0.0)
        jadd(s, s->dae.ov + s->contacts.ret[k].rs, s->dae.ov + s->contacts.ret[k].rs, dT);
}

/* The spin DOF's columns (spin.c): d(Omega G v)/d Omega = G v, the unbalance's d/d(phi, Omega),
 * and the free spin's drag. */
static void jacobian_spin(td_sim *s, double t, const double *y)
{
    const cs_di *G = s->dae.G;
    const double *v = y + s->dae.ov;
    double w = td_sim_rotor_speed(s, y), phi = td_sim_rotor_angle(s, t, y), alpha = rotor_rate(s, t, y), dT;
    int qz = s->dae.oq + s->machine.spin, wz = s->dae.ov + s->machine.spin, i, j, p;
    for (j = 0; j < G->n; j++) /* jadd through the positions found once (sim_pattern.c) */
        for (p = G->p[j]; p < G->p[j + 1]; p++)
            if (s->ops.map_Gw[p] >= 0)
                s->ops.jdata[s->ops.map_Gw[p]] += G->x[p] * v[j];
    for (i = 0; i < s->machine.nu; i++) { /* v rows carry -f */
        const td_unbalance *u = &s->machine.unb[i];
        double c = cos(phi + u->phase), sn = sin(phi + u->phase), U = u->magnitude;
        int x = s->dae.ov + td_system_node_dof(s->sys, u->node, TD_DOF_X),
            yrow = s->dae.ov + td_system_node_dof(s->sys, u->node, TD_DOF_Y);
        jadd(s, x, qz, -U * (-w * w * sn + alpha * c));
        jadd(s, yrow, qz, -U * (w * w * c + alpha * sn));
        jadd(s, x, wz, -2.0 * U * w * c);
        jadd(s, yrow, wz, -2.0 * U * w * sn);
    }
    td_sim_spin_drag(s, y, &dT); /* the row carries + drag */
    if (dT != 0.0)
        jadd(s, wz, wz, dT);
}

/* A free spin's inertial coupling with the unbalances' nodes (td_sim_unbalance_spin_coupling):
 * the mass entries (-U sin, U cos)(phi + phase), both ways, times cj. */
static void jacobian_unbalance_spin(td_sim *s, double t, double cj, const double *y)
{
    double phi = td_sim_rotor_angle(s, t, y);
    int wz = s->dae.ov + s->machine.spin, i;
    for (i = 0; i < s->machine.nu; i++) {
        const td_unbalance *u = &s->machine.unb[i];
        double mx = -u->magnitude * sin(phi + u->phase), my = u->magnitude * cos(phi + u->phase);
        int x = s->dae.ov + td_system_node_dof(s->sys, u->node, TD_DOF_X),
            yrow = s->dae.ov + td_system_node_dof(s->sys, u->node, TD_DOF_Y);
        jadd(s, x, wz, cj * mx);
        jadd(s, yrow, wz, cj * my);
        jadd(s, wz, x, cj * mx);
        jadd(s, wz, yrow, cj * my);
    }
}

/* A ramp's spin rows are angle - phi(t) and speed - Omega(t) (td_sim_residual): the identity in
 * place of the differential rows' entries (nothing else writes into them for a ramp). */
static void jacobian_ramp_rows(td_sim *s)
{
    int qz = s->dae.oq + s->machine.spin, wz = s->dae.ov + s->machine.spin;
    s->ops.jdata[td_sim_pattern_find(s, qz, qz)] = 1.0;
    s->ops.jdata[td_sim_pattern_find(s, qz, wz)] = 0.0;
    s->ops.jdata[td_sim_pattern_find(s, wz, wz)] = 1.0;
}

void td_sim_jacobian(td_sim *s, double t, double cj, const double *y)
{
    int i, k;
    memset(s->ops.jdata, 0, sizeof(double) * (size_t)s->ops.nnz);
    for (i = 0; i < s->dae.n; i++) {
        jadd(s, s->dae.oq + i, s->dae.oq + i, cj);
        jadd(s, s->dae.oq + i, s->dae.ov + i, -1.0);
    }
    for (i = 0; i < s->dae.nw; i++)
        jadd(s, s->dae.ow + i, s->dae.ow + i, cj);
    jadd_matrix(s, s->dae.M, s->ops.map_M, cj);
    jadd_matrix(s, s->dae.C, s->ops.map_C, 1.0);
    jadd_matrix(s, s->dae.G, s->ops.map_G, td_sim_rotor_speed(s, y));
    if (s->machine.spin >= 0)
        jacobian_spin(s, t, y);
    if (s->machine.spin_free)
        jacobian_unbalance_spin(s, t, cj, y);
    jadd_matrix(s, s->dae.K, s->ops.map_K, 1.0);
    jacobian_amb(s, y);
    td_sim_lti_jacobian_rows(s);
    for (k = 0; k < s->dae.nr; k++) {
        if (s->contacts.ret[k].rs >= 0)
            jacobian_drag(s, k, y);
        if (s->contacts.ret[k].fi >= 0)
            jacobian_roll(s, k, y);
        if (s->contacts.ret[k].mode == TD_RMODE_CONTACT) {
            jacobian_contact(s, k, y);
            continue;
        }
        if (td_sim_penalty_model(s, k))
            jacobian_penalty(s, k, y); /* zero where the node does not penetrate */
        /* free and penalty contacts: the multiplier rows are lambda = eta = 0 */
        jadd(s, s->dae.ol + k, s->dae.ol + k, 1.0);
        jadd(s, s->dae.ou + k, s->dae.ou + k, 1.0);
    }
    if (s->machine.spin >= 0 && !s->machine.spin_free)
        jacobian_ramp_rows(s);
}

/* Slot 1 of retainer k in contact with friction (see below). */
static double slip_root_function(const td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double vs, vreg = TD_CONTACT_SLIP_BAND;
    if (r->rolling)
        return r->r.friction * td_sim_normal_force(s, k, y) - fabs(y[s->dae.of + r->fi]);
    vs = td_sim_sliding_velocity(s, k, y);
    if (r->r.stick)
        return r->slip * vs;
    return r->slip != 0 ? r->slip * vs - vreg : (vreg * vreg - vs * vs) / (2.0 * vreg);
}

/*
 * Root functions, three per retainer, by mode:
 *   slot 0  free, constraint model, armed:     gap = (c^2 - r^2)/(2c), decreasing  -> onset
 *           free, constraint model, disarmed:  gap + eps, decreasing                -> onset (late)
 *           free, penalty model:               gap, decreasing                      -> penalty enter
 *           contact:                           lambda, decreasing                   -> release
 *           penetrating:                       gap, increasing                      -> penalty exit
 *   slot 1  contact or penetrating with mu > 0, sliding (slip = +-1):
 *                                              slip v_s - v_reg, decreasing         -> into the slip band
 *           ... inside the band (slip = 0):    (v_reg^2 - v_s^2)/(2 v_reg), decr.   -> out of the band
 *                                              (a friction reversal if on the other side)
 *           stick retainers, sliding:          slip v_s, decreasing                 -> try rolling
 *           stick retainers, rolling:          mu N - |F_t|, decreasing             -> slip
 *   slot 2  free, disarmed (either model):     gap - eps, increasing                -> re-arm (internal)
 * Unused slots hold the constant 1, which never has a root.
 * Then, when an AMB saturates, two per AMB axis: ks x + Fc - capacity and ks x + Fc + capacity,
 * either direction, the kinks of the clip (entering or leaving it; 1 while the AMB is off or the
 * axis does not saturate). The force is continuous there but its slope jumps, and so does the
 * integrator's rate (anti-windup): a step across the kink would carry the wrong law over part of
 * itself, so the integrator restarts on it.
 * Then, when an amplifier has a slew limit, two per AMB axis: r - ki slew_rate and r + ki slew_rate,
 * r the lag's unclipped rate, either direction: the kinks of dFc/dt = clip(r) (1 on an axis without a
 * limit), for the same reason. They hold while the AMB is off, as the lag runs on.
 */
static void saturation_roots(const td_sim *s, const double *y, double *g)
{
    int k;
    for (k = 0; k < s->sys->n_amb_axes && s->dae.n_sat_roots > 0; k++) {
        const td_amb_axis *a = &s->sys->amb_axes[k];
        double f = a->ks * y[s->dae.oq + a->actuator_dof] + amb_axis_fc(s, k, y);
        int on = a->saturation && s->machine.amb_mode[a->amb] != TD_AMB_OFF;
        g[2 * k] = on ? f - a->capacity : 1.0;
        g[2 * k + 1] = on ? f + a->capacity : 1.0;
    }
}

static void slew_roots(const td_sim *s, const double *y, double *g)
{
    int k;
    for (k = 0; k < s->sys->n_amb_axes && s->dae.n_slew_roots > 0; k++) {
        const td_amb_axis *a = &s->sys->amb_axes[k];
        int on = a->slew_rate > 0.0 && a->state >= 0;
        double r = on ? amb_axis_lag_rate(s, a, y) : 0.0, limit = fabs(a->ki) * a->slew_rate;
        g[2 * k] = on ? r - limit : 1.0;
        g[2 * k + 1] = on ? r + limit : 1.0;
    }
}

void td_sim_roots(const td_sim *s, double t, const double *y, double *g)
{
    int k;
    (void)t;
    saturation_roots(s, y, g + TD_ROOTS_PER_RETAINER * s->dae.nr);
    slew_roots(s, y, g + TD_ROOTS_PER_RETAINER * s->dae.nr + s->dae.n_sat_roots);
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double *gk = g + TD_ROOTS_PER_RETAINER * k;
        double x, yy, vx, vy, gap;
        td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
        gap = -td_contact_constraint(x, yy, r->r.clearance);
        gk[TD_ROOT_CONTACT] = 1.0;
        gk[TD_ROOT_SLIP] = 1.0;
        gk[TD_ROOT_REARM] = 1.0;
        switch (r->mode) {
        case TD_RMODE_FREE:
            gk[TD_ROOT_CONTACT] = r->armed || r->compliant ? gap : gap + s->machine.rearm_eps;
            if (!r->armed)
                gk[TD_ROOT_REARM] = gap - s->machine.rearm_eps;
            break;
        case TD_RMODE_CONTACT: gk[TD_ROOT_CONTACT] = y[s->dae.ol + k]; break;
        case TD_RMODE_PENETRATING: gk[TD_ROOT_CONTACT] = gap; break;
        }
        if (r->mode != TD_RMODE_FREE && r->r.friction > 0.0)
            gk[TD_ROOT_SLIP] = slip_root_function(s, k, y);
    }
}

void td_sim_root_directions(const td_sim *s, int *dir)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        int *dk = dir + TD_ROOTS_PER_RETAINER * k;
        dk[TD_ROOT_CONTACT] = s->contacts.ret[k].mode == TD_RMODE_PENETRATING ? 1 : -1;
        dk[TD_ROOT_SLIP] = -1;
        dk[TD_ROOT_REARM] = 1;
    }
    for (k = 0; k < s->dae.n_sat_roots + s->dae.n_slew_roots; k++)
        dir[TD_ROOTS_PER_RETAINER * s->dae.nr + k] = 0;
}
