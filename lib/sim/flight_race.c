/*
 * The races' spin in the closed-form free flight (flight_internal.h). A free race's speed Omega_b is
 * braked by its drag alone (docs/theory.md "Retainer bearings as bodies"; race.c puts the viscous
 * part c_b in C, retainer.c td_sim_race_drag the constant part T_0, regularised over the band
 * |Omega_b| < w_b = v_reg / R_b as friction is):
 *
 *     J Omega_b' = -c_b Omega_b - T_0 phi(Omega_b / w_b),   phi(u) = sgn(u) (|u| >= 1), u (inside),
 *
 * uncoupled from every other state while the retainer is free. It is not linear (phi), so the
 * modal decomposition leaves the race's angle and speed out (flight_modal.c: the map), and they are
 * carried here piecewise in closed form: with a = c_b / J, b = T_0 / J and s = sgn(Omega_0),
 *
 *     outside the band   Omega(t) = Omega_0 e^{-a t} - s b t phi1(a t),
 *                        theta(t) = theta_0 + Omega_0 t phi1(a t) - s b t^2 phi2(a t),
 *
 * until |Omega| reaches w_b, then inside it (a linear law) with a_in = a + b / w_b
 *
 *                        Omega(t) = Omega_b e^{-a_in t},   theta(t) = theta_b + Omega_b t phi1(a_in t),
 *
 * phi1(x) = (1 - e^-x)/x, phi2(x) = (x - 1 + e^-x)/x^2 (thermal.c td_sim_phis: no cancellation for
 * a small a t, and exact for a = 0). Inside the band the speed only decays: it never leaves it.
 */
#include "sim/flight_internal.h"
#include "sim/thermal.h"

#include <math.h>

/* Retainer r's race from speed w0, t seconds later: its angle change and speed. */
static void race_free(const td_sim_retainer *r, double w0, double t, double *angle, double *w)
{
    const td_race *b = &r->r.race;
    double a = b->drag_viscous / b->inertia, d = b->drag_torque > 0.0 ? b->drag_torque / b->inertia : 0.0;
    double band = TD_CONTACT_SLIP_BAND / r->r.bore_radius, sg = w0 < 0.0 ? -1.0 : 1.0, p1, p2;
    *angle = 0.0;
    if (d > 0.0 && fabs(w0) > band) { /* outside the band until |Omega| = w_b at tb */
        double tb = a > 0.0 ? log1p((fabs(w0) - band) / (band + d / a)) / a : (fabs(w0) - band) / d;
        double tau = fmin(t, tb);
        td_sim_phis(a * tau, &p1, &p2);
        *angle = w0 * tau * p1 - sg * d * tau * tau * p2;
        if (t <= tb) {
            *w = w0 * exp(-a * t) - sg * d * t * p1;
            return;
        }
        w0 = sg * band;
        t -= tb;
    }
    if (d > 0.0) /* inside the band: the constant drag is the damper T_0 / w_b */
        a += d / band;
    td_sim_phis(a * t, &p1, &p2);
    *angle += w0 * t * p1;
    *w = w0 * exp(-a * t);
}

void td_sim_flight_race_anchor(const td_sim *s, td_sim_flight *f)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    int i;
    for (i = 0; i < f->nrace; i++) {
        const td_sim_retainer *r = &s->contacts.ret[f->race[i].k];
        f->race[i].angle = y[s->dae.oq + r->rs];
        f->race[i].speed = y[s->dae.ov + r->rs];
    }
    f->t_race = s->dae.t;
}

void td_sim_flight_race_state(const td_sim *s, const td_sim_flight *f, double t, double *y, double *yp)
{
    int i;
    for (i = 0; i < f->nrace; i++) {
        const td_sim_retainer *r = &s->contacts.ret[f->race[i].k];
        double angle, w;
        race_free(r, f->race[i].speed, t - f->t_race, &angle, &w);
        y[s->dae.oq + r->rs] = f->race[i].angle + angle;
        y[s->dae.ov + r->rs] = w;
        if (yp) { /* the law itself at the state reached */
            yp[s->dae.oq + r->rs] = w;
            yp[s->dae.ov + r->rs] =
                -(r->r.race.drag_viscous * w + td_sim_race_drag(s, f->race[i].k, y, NULL)) / r->r.race.inertia;
        }
    }
}
