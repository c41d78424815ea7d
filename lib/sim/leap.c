/*
 * The projective leap (leap.h): the slow state read at a burst's ends, its mean rates, and the
 * step of the slow state by a leap at those rates. Projective forward Euler (Gear and Kevrekidis
 * 2003): x(t + L) = x(t) + L (x(t) - x(t - B)) / B over a burst B of the full model, applied to the
 * speeds (a coast-down on the retainers loses speed at a rate that the bounce's statistics set,
 * steady over many bursts) and to every additive total, so that works, heat, times, counts and
 * damage, and the energy account, cover the leapt time. Powers go with the speed (a sliding
 * contact's and a drag's power are a force times a speed that follows the rotor's): over the leap
 * each power is the burst's mean times speed / the burst's mean speed. The rotor's speed is not
 * extrapolated from the burst's own dOmega/dt, which carries the change of the lateral motion's
 * energy over the burst (a fluctuation of the bounce) and would multiply it by L / B in the
 * account: it moves so that the kinetic energy pays exactly the net power the leap books (the
 * inputs less every loss), and the account closes across the leap to rounding (test_leap). The
 * two rates differ by that fluctuation's share (the run reports both, td_run_summary).
 */
#include "sim/leap.h"
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
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
    out->events = (double)s->monitor.stats.events;
    out->contact_onsets = (double)s->monitor.stats.contact_onsets;
    out->releases = (double)s->monitor.stats.releases;
    out->time_in_contact = s->monitor.stats.time_in_contact;
    out->time_slewing = s->monitor.stats.time_slewing;
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
    rate->events = (b->events - a->events) / dt;
    rate->contact_onsets = (b->contact_onsets - a->contact_onsets) / dt;
    rate->releases = (b->releases - a->releases) / dt;
    rate->time_in_contact = (b->time_in_contact - a->time_in_contact) / dt;
    rate->time_slewing = (b->time_slewing - a->time_slewing) / dt;
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

/* The statistics of the motion (td_sim_stats) moved on by L s at `rate`, as the totals are; the
 * solver's counters (steps, evaluations, restarts, flight, controller samples) are of the
 * integration, which a leap skips, and stay as they are. */
static void leap_stats(td_sim *s, double L, const td_sim_leap_state *rate)
{
    td_sim_stats *st = &s->monitor.stats;
    st->events += lround(L * rate->events);
    st->contact_onsets += lround(L * rate->contact_onsets);
    st->releases += lround(L * rate->releases);
    st->time_in_contact += L * rate->time_in_contact;
    st->time_slewing += L * rate->time_slewing;
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

/* The burst's net power: what the inputs put in less every loss the account books (td_energy). */
static double net_power(const td_energy *r)
{
    return r->external_work + r->drive_work + r->housing_work - r->damping_loss - r->contact_loss - r->drag_loss -
           r->impact_loss;
}

/* The velocities a unit change of the rotor's speed moves: the spin, and each race in contact at
 * R_s / R_b (its sliding velocity R_s Omega + r theta' - R_b Omega_b stays as it was: a rolling race
 * keeps rolling, the fast state carried over). A free race moves at its burst's rate instead (*e). */
static void spin_directions(const td_sim *s, double L, const td_sim_leap_state *rate, double *d, double *e)
{
    int k;
    memset(d, 0, sizeof(double) * (size_t)s->dae.n);
    memset(e, 0, sizeof(double) * (size_t)s->dae.n);
    d[s->machine.spin] = 1.0;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        if (r->rs < 0)
            continue;
        if (r->mode != TD_RMODE_FREE)
            d[r->rs] = r->r.shaft_radius / r->r.bore_radius;
        else
            e[r->rs] = L * rate->race_speed[k];
    }
}

/* The rotor's speed change x over a leap of L whose kinetic energy change pays the burst's net
 * power P at the speed's scale: 1/2 (v+e+xd)' M (v+e+xd) - 1/2 v'Mv = L P (w0 + x/2) / mean_speed,
 * a quadratic c2 x^2 + (c1 - beta) x + (c0 - alpha) = 0 (M constant); its root nearest 0, in the
 * form that does not cancel. Without the energy account, the burst's dOmega/dt. 0 on success. */
static int energy_speed_change(const td_sim *s, double L, const td_sim_leap_state *rate, double *d, double *e,
                               double *x)
{
    const double *v = N_VGetArrayPointer(s->dae.y) + s->dae.ov;
    double w0 = td_sim_rotor_speed(s, N_VGetArrayPointer(s->dae.y)), P, c0, c1, c2, alpha, beta, b, c, disc;
    int i;
    spin_directions(s, L, rate, d, e);
    if (!rate->energy_on) {
        *x = L * rate->speed;
        return 0;
    }
    P = net_power(&rate->energy);
    for (i = 0; i < s->dae.n; i++)
        e[i] += v[i]; /* e is now v + e */
    c0 = 0.5 * td_sim_mass_form(s, e, e) - 0.5 * td_sim_mass_form(s, v, v);
    c1 = td_sim_mass_form(s, d, e);
    c2 = 0.5 * td_sim_mass_form(s, d, d);
    alpha = L * P * w0 / rate->mean_speed;
    beta = 0.5 * L * P / rate->mean_speed;
    b = c1 - beta;
    c = c0 - alpha;
    disc = b * b - 4.0 * c2 * c;
    if (!(disc >= 0.0) || b == 0.0)
        return -1;
    *x = -2.0 * c / (b + copysign(sqrt(disc), b));
    return isfinite(*x) ? 0 : -1;
}

/* The speeds and angles moved on: the rotor's by x, a race in contact with it (d), a free race at
 * its burst's rate (v + e holds its new velocity); each angle by its mean speed over the leap. */
static void leap_motion(td_sim *s, double L, double x, const double *d, const double *e, int energy_on)
{
    double *y = N_VGetArrayPointer(s->dae.y);
    int i;
    for (i = 0; i < s->dae.n; i++) {
        double v0 = y[s->dae.ov + i], v1 = (energy_on ? e[i] : v0 + e[i]) + x * d[i];
        if (v1 == v0)
            continue;
        y[s->dae.oq + i] += 0.5 * L * (v0 + v1);
        y[s->dae.ov + i] = v1;
    }
    td_sim_spin_wrap(s, y);
}

td_status td_sim_leap_speed_change(const td_sim *s, double L, const td_sim_leap_state *rate, double *change,
                                   td_error *err)
{
    double *work;
    int bad;
    if (!s || !rate || !change)
        return td_error_set(err, TD_ERR_INVALID, "leap: NULL argument");
    if (!(work = malloc(2 * sizeof(double) * (size_t)s->dae.n)))
        return td_error_set(err, TD_ERR_NOMEM, "leap: out of memory");
    bad = !s->machine.spin_free || energy_speed_change(s, L, rate, work, work + s->dae.n, change);
    free(work);
    return bad ? td_error_set(err, TD_ERR_INVALID, "leap: no speed pays the burst's net power over %g s", L) : TD_OK;
}

/* The checks of a leap of L at `rate` on s (a message into err). */
static td_status leap_refused(const td_sim *s, double L, const td_sim_leap_state *rate, td_error *err)
{
    if (!(L > 0.0) || !isfinite(L) || rate->retainers != s->dae.nr || rate->energy_on != (s->opt.energy != 0) ||
        !(rate->mean_speed > 0.0) || !isfinite(rate->speed))
        return td_error_set(err, TD_ERR_INVALID, "leap: a leap of %g s at rates of another run", L);
    if (!s->machine.spin_free)
        return td_error_set(err, TD_ERR_INVALID, "leap: the rotor's speed is not free (spin.free)");
    return TD_OK;
}

td_status td_sim_leap(td_sim *s, double L, const td_sim_leap_state *rate, td_error *err)
{
    double w0, x = 0.0, f0, f1, *work;
    int k, bad;
    td_status st;
    if (!s || !rate)
        return td_error_set(err, TD_ERR_INVALID, "leap: NULL argument");
    if ((st = leap_refused(s, L, rate, err)) != TD_OK)
        return st;
    if (!(work = malloc(2 * sizeof(double) * (size_t)s->dae.n)))
        return td_error_set(err, TD_ERR_NOMEM, "leap: out of memory");
    td_sim_totals_rewind(s); /* the accounts end at s->dae.t (an output inside the last step) */
    w0 = td_sim_rotor_speed(s, N_VGetArrayPointer(s->dae.y));
    bad = energy_speed_change(s, L, rate, work, work + s->dae.n, &x);
    if (bad || !(w0 + x > 0.0)) {
        free(work);
        return td_error_set(err, TD_ERR_INVALID, "leap: %g s at %g rad/s^2 would stop the rotor (%g rad/s now)", L,
                            bad ? rate->speed : x / L, w0);
    }
    f0 = w0 / rate->mean_speed;
    f1 = (w0 + x) / rate->mean_speed;
    for (k = 0; k < s->dae.nr; k++) {
        leap_totals(s, k, L, 0.5 * (f0 + f1), rate);
        leap_heat(s, k, L, f0, f1, rate);
    }
    leap_stats(s, L, rate);
    if (s->opt.energy)
        leap_energy(s, L * 0.5 * (f0 + f1), &rate->energy);
    leap_motion(s, L, x, work, work + s->dae.n, rate->energy_on);
    free(work);
    s->monitor.leapt += L; /* the statistics' and the section's time stamps are the run's */
    if ((st = td_sim_restart_between_steps(s)) != TD_OK)
        return td_error_set(err, st, "leap: the restart after the leap failed: %s", s->errmsg);
    return TD_OK;
}
