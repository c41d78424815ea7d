/*
 * The projective leap (leap.h): the slow state read at a burst's ends, its mean rates, and the
 * step of the slow state by a leap at those rates. Projective forward Euler (Gear and Kevrekidis
 * 2003): x(t + L) = x(t) + L (x(t) - x(t - B)) / B over a burst B of the full model, applied to the
 * speeds (a coast-down on the retainers loses speed at a rate that the bounce's statistics set,
 * steady over many bursts) and to every additive total, so that works, heat, times, counts and
 * damage, and the energy account, cover the leapt time. Powers go with the speed (a sliding
 * contact's and a drag's power are a force times a speed that follows the rotor's): over the leap
 * each power is the burst's mean times speed / the burst's mean speed: the rotor's kinetic energy
 * changes by J Omega_mid dOmega across the leap, the burst's powers by the same factor, so the
 * account closes across the leap up to the change of the lateral motion's energy over the burst
 * (a fluctuation of the bounce), which the burst's speed rate carries and the leap multiplies by
 * L / B; the closed form of a spin-down, with no lateral motion, closes to round-off (test_leap).
 */
#include "sim/leap.h"
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <string.h>

td_status td_sim_leap_read(const td_sim *s, td_sim_leap_state *out, td_error *err)
{
    const double *y;
    int k;
    if (!s || !out)
        return td_error_set(err, TD_ERR_INVALID, "leap: NULL argument");
    if (s->dae.nr > TD_SIM_LEAP_RETAINERS)
        return td_error_set(err, TD_ERR_INVALID, "leap: %d retainers, at most %d", s->dae.nr, TD_SIM_LEAP_RETAINERS);
    memset(out, 0, sizeof *out);
    y = N_VGetArrayPointer(s->dae.y);
    out->t = s->dae.t;
    out->speed = td_sim_rotor_speed(s, y);
    out->retainers = s->dae.nr;
    for (k = 0; k < s->dae.nr; k++) {
        out->race_speed[k] = td_sim_race_speed(s, k, y);
        td_sim_totals_get(s, k, &out->totals[k]);
        out->contacts[k] = (double)out->totals[k].contacts;
        out->touch_and_go[k] = (double)out->totals[k].touch_and_go;
    }
    out->energy_on = s->opt.energy != 0;
    if (out->energy_on)
        td_sim_energy_get(s, &out->energy);
    return TD_OK;
}

/* (b - a) / dt of a total; an undefined one (no bearing rating, say) stays undefined. */
static double per_second(double a, double b, double dt)
{
    return td_is_undefined(a) || td_is_undefined(b) ? TD_UNDEFINED : (b - a) / dt;
}

static void totals_rates(const td_retainer_totals *a, const td_retainer_totals *b, double dt, td_retainer_totals *r)
{
    memset(r, 0, sizeof *r);
    r->impulse = per_second(a->impulse, b->impulse, dt);
    r->impact_impulse = per_second(a->impact_impulse, b->impact_impulse, dt);
    r->contact_time = per_second(a->contact_time, b->contact_time, dt);
    r->rolling_time = per_second(a->rolling_time, b->rolling_time, dt);
    r->normal_force_sq = per_second(a->normal_force_sq, b->normal_force_sq, dt);
    r->friction_work = per_second(a->friction_work, b->friction_work, dt);
    r->whirl_angle = per_second(a->whirl_angle, b->whirl_angle, dt);
    r->drag_work = per_second(a->drag_work, b->drag_work, dt);
    r->heat = per_second(a->heat, b->heat, dt);
    r->damage = per_second(a->damage, b->damage, dt);
    r->load_cycles = per_second(a->load_cycles, b->load_cycles, dt);
}

static void energy_rates(const td_energy *a, const td_energy *b, double dt, td_energy *r)
{
    memset(r, 0, sizeof *r);
    r->external_work = (b->external_work - a->external_work) / dt;
    r->drive_work = (b->drive_work - a->drive_work) / dt;
    r->damping_loss = (b->damping_loss - a->damping_loss) / dt;
    r->contact_loss = (b->contact_loss - a->contact_loss) / dt;
    r->drag_loss = (b->drag_loss - a->drag_loss) / dt;
    r->impact_loss = (b->impact_loss - a->impact_loss) / dt;
    r->housing_work = (b->housing_work - a->housing_work) / dt;
}

td_status td_sim_leap_rates(const td_sim_leap_state *a, const td_sim_leap_state *b, td_sim_leap_state *rate,
                            td_error *err)
{
    double dt;
    int k;
    if (!a || !b || !rate)
        return td_error_set(err, TD_ERR_INVALID, "leap: NULL argument");
    dt = b->t - a->t;
    if (!(dt > 0.0) || a->retainers != b->retainers || a->energy_on != b->energy_on)
        return td_error_set(err, TD_ERR_INVALID, "leap: the burst's ends are not of one run, in order");
    memset(rate, 0, sizeof *rate);
    rate->t = dt;
    rate->speed = (b->speed - a->speed) / dt;
    rate->mean_speed = 0.5 * (a->speed + b->speed);
    rate->retainers = a->retainers;
    rate->energy_on = a->energy_on;
    for (k = 0; k < a->retainers; k++) {
        rate->race_speed[k] = (b->race_speed[k] - a->race_speed[k]) / dt;
        totals_rates(&a->totals[k], &b->totals[k], dt, &rate->totals[k]);
        rate->contacts[k] = (b->contacts[k] - a->contacts[k]) / dt;
        rate->touch_and_go[k] = (b->touch_and_go[k] - a->touch_and_go[k]) / dt;
    }
    if (a->energy_on)
        energy_rates(&a->energy, &b->energy, dt, &rate->energy);
    return TD_OK;
}

/* Retainer k's additive totals and counts moved on by L s at `rate`, the works at the powers
 * scaled by f (the speed at the leap's middle over the burst's mean speed). */
static void leap_totals(td_sim *s, int k, double L, double f, const td_sim_leap_state *rate)
{
    td_sim_totals *tk = &s->monitor.totals[k];
    const td_retainer_totals *r = &rate->totals[k];
    tk->t.impulse += L * r->impulse;
    tk->t.impact_impulse += L * r->impact_impulse;
    tk->t.contact_time += L * r->contact_time;
    tk->t.rolling_time += L * r->rolling_time;
    tk->t.normal_force_sq += L * r->normal_force_sq;
    tk->t.whirl_angle += L * r->whirl_angle;
    tk->t.friction_work += L * f * r->friction_work;
    tk->t.drag_work += L * f * r->drag_work;
    tk->t.heat = tk->t.friction_work + tk->t.drag_work;
    tk->t.contacts += lround(L * rate->contacts[k]);
    tk->t.touch_and_go += lround(L * rate->touch_and_go[k]);
    if (!td_is_undefined(r->damage) && tk->cycles && !tk->life_failed) { /* life */
        tk->t.damage += L * r->damage;
        tk->closed_cycles += L * r->load_cycles;
    }
}

/* Retainer k's network under the burst's heat, scaled by the speed from f0 to f1 over the leap
 * (the power linear between, as td_thermal_network_step takes it: exact in closed form). */
static void leap_heat(td_sim *s, int k, double L, double f0, double f1, const td_sim_leap_state *rate)
{
    td_sim_thermal *h = &s->monitor.thermal[k];
    double p = rate->totals[k].friction_work + rate->totals[k].drag_work;
    if (!h->on)
        return;
    td_thermal_network_step(&h->net, h->T, L, f0 * p, f1 * p);
    memcpy(h->T_before, h->T, sizeof h->T);
    h->t_before = s->dae.t;
    h->peak = fmax(h->peak, h->T[0]); /* a network under a steady heat rises or falls monotonically */
}

static void leap_energy(td_sim *s, double Lf, const td_energy *r)
{
    td_energy *e = &s->monitor.energy;
    e->external_work += Lf * r->external_work;
    e->drive_work += Lf * r->drive_work;
    e->damping_loss += Lf * r->damping_loss;
    e->contact_loss += Lf * r->contact_loss;
    e->drag_loss += Lf * r->drag_loss;
    e->impact_loss += Lf * r->impact_loss;
    e->housing_work += Lf * r->housing_work;
}

/* The speeds and angles moved on: the rotor's speed linearly, its angle by the mean speed times L;
 * a race in contact moves with the rotor so that its sliding velocity R_s Omega + r theta' - R_b Omega_b
 * stays as it was (a rolling race keeps rolling: the fast state carried over), a free race at its
 * burst's rate; the race's angle by its mean speed. */
static void leap_motion(td_sim *s, double L, const td_sim_leap_state *rate)
{
    double *y = N_VGetArrayPointer(s->dae.y);
    double *w = &y[s->dae.ov + s->machine.spin], dw = L * rate->speed;
    int k;
    y[s->dae.oq + s->machine.spin] += L * (*w + 0.5 * dw);
    *w += dw;
    td_sim_spin_wrap(s, y);
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double dwb;
        if (r->rs < 0)
            continue;
        dwb = r->mode != TD_RMODE_FREE ? r->r.shaft_radius / r->r.bore_radius * dw : L * rate->race_speed[k];
        y[s->dae.oq + r->rs] += L * (y[s->dae.ov + r->rs] + 0.5 * dwb);
        y[s->dae.ov + r->rs] += dwb;
    }
}

td_status td_sim_leap(td_sim *s, double L, const td_sim_leap_state *rate, td_error *err)
{
    double w0, w1, f0, f1;
    int k;
    if (!s || !rate)
        return td_error_set(err, TD_ERR_INVALID, "leap: NULL argument");
    if (!(L > 0.0) || !isfinite(L) || rate->retainers != s->dae.nr || rate->energy_on != (s->opt.energy != 0) ||
        !(rate->mean_speed > 0.0) || !isfinite(rate->speed))
        return td_error_set(err, TD_ERR_INVALID, "leap: a leap of %g s at rates of another run", L);
    if (!s->machine.spin_free)
        return td_error_set(err, TD_ERR_INVALID, "leap: the rotor's speed is not free (spin.free)");
    w0 = td_sim_rotor_speed(s, N_VGetArrayPointer(s->dae.y));
    w1 = w0 + L * rate->speed;
    if (!(w1 > 0.0))
        return td_error_set(err, TD_ERR_INVALID, "leap: %g s at %g rad/s^2 would stop the rotor (%g rad/s now)", L,
                            rate->speed, w0);
    td_sim_totals_rewind(s); /* the accounts end at s->dae.t (an output inside the last step) */
    f0 = w0 / rate->mean_speed;
    f1 = w1 / rate->mean_speed;
    for (k = 0; k < s->dae.nr; k++) {
        leap_totals(s, k, L, 0.5 * (f0 + f1), rate);
        leap_heat(s, k, L, f0, f1, rate);
    }
    if (s->opt.energy)
        leap_energy(s, L * 0.5 * (f0 + f1), &rate->energy);
    leap_motion(s, L, rate);
    {
        td_status st = td_sim_restart_between_steps(s);
        if (st != TD_OK)
            return td_error_set(err, st, "leap: the restart after the leap failed: %s", s->errmsg);
    }
    return TD_OK;
}
