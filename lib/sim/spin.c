/*
 * The rotor's spin as a degree of freedom (model.h td_spin and td_speed_point; docs/theory.md,
 * "Speed transients"), appended after the races' DOFs when the speed varies: its angle phi in q,
 * its speed Omega in v, the rotor's polar inertia J on M's diagonal.
 *
 *   a ramp:       phi = phi(t), Omega = Omega(t), exactly (algebraic rows): the drive holds the
 *                 prescribed speed whatever the friction torques
 *   a free spin:  J Omega' = T_drive - T_drag sgn(Omega) - c_drag Omega - sum_k R_s F_t,k
 *                            - sum_u U (y_u'' cos - x_u'' sin)(phi + phase_u)
 *
 * c_drag sits in C (so it is a damping loss of the energy account), the friction torques come in
 * through the contact columns (retainer.c, sim_residual.c). The unbalance turns with phi:
 * U (Omega^2 cos + alpha sin, Omega^2 sin - alpha cos)(phi + phase), alpha = Omega'; on a free
 * spin the alpha term and the last torque above (the unbalance mass dragged round by the node's
 * acceleration) are the two halves of one inertial coupling, the Lagrangian's mass entries
 * (-U sin, U cos) between the node and the spin (sim_residual.c unbalance_spin_coupling): the
 * spin pays for the energy the unbalance feeds the whirl. The gyroscopic matrix follows Omega:
 * D = C + Omega G.
 */
#include "sim/sim_internal.h"

#include <math.h>

void td_sim_spin_layout(td_sim *s)
{
    td_spin sp;
    s->machine.spin = -1;
    s->machine.spin_free = 0;
    s->machine.spin_inertia = 0.0;
    if (!td_model_speed_varies(s->model))
        return;
    td_model_spin(s->model, &sp);
    s->machine.spin = s->dae.n++;
    s->machine.spin_free = sp.free != 0;
    s->machine.spin_inertia = sp.inertia > 0.0 ? sp.inertia : td_model_polar_inertia(s->model);
}

void td_sim_spin_diagonal(const td_sim *s, char which, double *d)
{
    td_spin sp;
    if (s->machine.spin < 0)
        return;
    td_model_spin(s->model, &sp);
    d[s->machine.spin] = which == 'M'                           ? s->machine.spin_inertia
                         : which == 'C' && s->machine.spin_free ? sp.drag_viscous
                                                                : 0.0;
}

double td_sim_rotor_speed(const td_sim *s, const double *y)
{
    return s->machine.spin >= 0 ? y[s->dae.ov + s->machine.spin] : s->machine.omega;
}

double td_sim_rotor_angle(const td_sim *s, double t, const double *y)
{
    return s->machine.spin >= 0 ? y[s->dae.oq + s->machine.spin]
                                : s->machine.spin_ref + s->machine.omega * (t - s->machine.t_spin_ref);
}

double td_sim_spin_drag(const td_sim *s, const double *y, double *dT)
{
    td_spin sp;
    double dphi = 0.0, phi;
    if (dT)
        *dT = 0.0;
    if (!s->machine.spin_free)
        return 0.0;
    td_model_spin(s->model, &sp);
    phi = td_contact_slip_factor(y[s->dae.ov + s->machine.spin], TD_SIM_SPIN_BAND, &dphi);
    if (dT)
        *dT = sp.drag_torque * dphi;
    return sp.drag_torque * phi;
}

/*
 * A ramp's slope over the interval the integrator is covering, (s->dae.t, t]: IDA stops at every ramp
 * point (td_sim_next_stop), so that interval lies inside one segment, and a step that ends on a
 * point belongs to the segment before it. The slope at the point itself (td_model_speed_at: the next
 * segment's) would drive that whole step with the next segment's alpha, losing the U alpha h of the
 * unbalance's impulse. At t = s->dae.t (a restart: the consistent rates there) the segment is the one
 * that starts there.
 */
static double ramp_rate(const td_sim *s, double t)
{
    double rate;
    td_model_speed_at(s->model, t > s->dae.t ? 0.5 * (s->dae.t + t) : t, &rate, NULL);
    return rate;
}

double td_sim_spin_torque(const td_sim *s, double t)
{
    td_spin sp;
    if (s->machine.spin < 0)
        return 0.0;
    if (!s->machine.spin_free)
        return s->machine.spin_inertia * ramp_rate(s, t);
    td_model_spin(s->model, &sp);
    return sp.drive_torque;
}

void td_sim_spin_start(const td_sim *s, double *y)
{
    double angle;
    if (s->machine.spin < 0)
        return;
    y[s->dae.ov + s->machine.spin] = td_model_speed_at(s->model, s->dae.t, NULL, &angle);
    y[s->dae.oq + s->machine.spin] = angle;
}

void td_sim_spin_hold(const td_sim *s, double t, double *y, double *yp)
{
    /* IDA's interpolant and Newton iterate hold a ramp's algebraic rows only to the tolerance (up to
     * 2e-4 of the speed early in a ramp at the default ones); the drive holds the profile exactly */
    double angle, w;
    if (s->machine.spin < 0 || s->machine.spin_free)
        return;
    w = td_model_speed_at(s->model, t, NULL, &angle);
    y[s->dae.oq + s->machine.spin] = angle;
    y[s->dae.ov + s->machine.spin] = w;
    if (yp) {
        yp[s->dae.oq + s->machine.spin] = w;
        yp[s->dae.ov + s->machine.spin] = ramp_rate(s, t);
    }
}

void td_sim_spin_wrap(const td_sim *s, double *y)
{
    /* keep a free spin's angle small, so that its relative tolerance stays an absolute one (a
     * ramp's is the prescribed angle itself) */
    if (s->machine.spin_free)
        y[s->dae.oq + s->machine.spin] = fmod(y[s->dae.oq + s->machine.spin], 2.0 * TD_PI);
}
