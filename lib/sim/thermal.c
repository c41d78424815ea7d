/*
 * The retainers' thermal networks (thermal.h): the closed-form step, and the networks' states kept
 * at the same points as the retainers' totals (totals.c), heated by each retainer's friction power
 * F_t v_s and its race's drag power (T_drag sgn(Omega_b) + c_drag Omega_b) Omega_b, both linear
 * between the points as the totals' trapezoids take them, so that the heat into a network is
 * friction_work + drag_work.
 */
#include "sim/thermal.h"
#include "sim/sim_internal.h"

#include <math.h>
#include <string.h>

/* phi1(x) = (1 - e^-x)/x and phi2(x) = (x - 1 + e^-x)/x^2, their Taylor series near 0 (the
 * closed forms cancel there): sum (-x)^k / (k+1)! and sum (-x)^k / (k+2)!, 20 terms for |x| < 0.5
 * (the first left out below 0.5^20 / 21! ~ 2e-26). The loop stops early once both next terms are
 * below half an ulp of their sums (|term| < 2^-54 |s| < ulp(s) / 2): the terms shrink from there on
 * (|x| / (k + 2) < 1), so each further addition would round back to the same sum, and the result
 * is bit for bit that of the 20 terms. A run's steps are microseconds against the networks'
 * seconds (x ~ 1e-8): three terms instead of twenty, at every output point. */
static void phis(double x, double *phi1, double *phi2)
{
    if (fabs(x) < 0.5) {
        double term1 = 1.0, term2 = 0.5, s1 = 0.0, s2 = 0.0;
        int k;
        for (k = 0; k < 20; k++) {
            s1 += term1;
            s2 += term2;
            term1 *= -x / (double)(k + 2);
            term2 *= -x / (double)(k + 3);
            if (fabs(term1) < 0x1p-54 * fabs(s1) && fabs(term2) < 0x1p-54 * fabs(s2))
                break;
        }
        *phi1 = s1;
        *phi2 = s2;
        return;
    }
    *phi1 = -expm1(-x) / x;
    *phi2 = (x + expm1(-x)) / (x * x);
}

void td_thermal_network_init(td_thermal_network *n, const td_retainer_thermal *t)
{
    double g = t->race_housing_conductance, ga = t->housing_ambient_conductance;
    double a = g / t->race_capacity, d = (g + ga) / t->housing_capacity;
    double c = -g / sqrt(t->race_capacity * t->housing_capacity);
    double det = g * ga / (t->race_capacity * t->housing_capacity); /* a d - c^2 without the cancellation */
    double theta, tn, cs, sn, l0, l1;
    n->capacity[0] = t->race_capacity;
    n->capacity[1] = t->housing_capacity;
    /* one Jacobi rotation diagonalises the symmetric 2x2 [a c; c d] (c < 0 here) */
    theta = (d - a) / (2.0 * c);
    tn = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
    cs = 1.0 / sqrt(tn * tn + 1.0);
    sn = tn * cs;
    l0 = a - tn * c;
    l1 = d + tn * c;
    /* the smaller eigenvalue from the determinant: exact when the network is stiff or insulated */
    if (l0 > l1)
        l1 = det / l0;
    else
        l0 = det / l1;
    n->lambda[0] = l0;
    n->lambda[1] = l1;
    n->q[0][0] = cs;
    n->q[1][0] = -sn;
    n->q[0][1] = sn;
    n->q[1][1] = cs;
}

void td_thermal_network_step(const td_thermal_network *n, double T[2], double h, double p0, double p1)
{
    double u[2], z[2], b, phi1, phi2;
    int i;
    u[0] = sqrt(n->capacity[0]) * T[0];
    u[1] = sqrt(n->capacity[1]) * T[1];
    for (i = 0; i < 2; i++) {
        double x = n->lambda[i] * h;
        phis(x, &phi1, &phi2);
        b = n->q[0][i] / sqrt(n->capacity[0]); /* the heat enters at the race node */
        z[i] = n->q[0][i] * u[0] + n->q[1][i] * u[1];
        z[i] = exp(-x) * z[i] + b * h * (p0 * (phi1 - phi2) + p1 * phi2);
    }
    T[0] = (n->q[0][0] * z[0] + n->q[0][1] * z[1]) / sqrt(n->capacity[0]);
    T[1] = (n->q[1][0] * z[0] + n->q[1][1] * z[1]) / sqrt(n->capacity[1]);
}

double td_thermal_network_reach(const td_thermal_network *n, double h)
{
    return fmax(n->lambda[0], n->lambda[1]) * fabs(h);
}

/* ---- the networks in a run ----------------------------------------------------------------- */

void td_sim_thermal_setup(td_sim *s)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_thermal *h = &s->monitor.thermal[k];
        td_retainer_thermal t;
        memset(h, 0, sizeof *h);
        h->on = td_model_get_retainer_thermal(s->model, k, &t);
        h->growth_per_kelvin = TD_UNDEFINED;
        if (!h->on)
            continue;
        td_thermal_network_init(&h->net, &t);
        if (!td_is_undefined(t.expansion))
            h->growth_per_kelvin = t.expansion * s->contacts.ret[k].r.bore_radius;
    }
}

double td_sim_friction_power(const td_sim *s, int k, const double *y)
{
    if (s->contacts.ret[k].mode == TD_RMODE_FREE)
        return 0.0;
    return td_sim_friction_force(s, k, y) * td_sim_sliding_velocity(s, k, y);
}

/* The power of retainer k's race drag at y, W (>= 0): the constant and the viscous torque, both
 * braking the race speed Omega_b (race.c: the viscous drag sits in C, the constant in the residual). */
static double drag_power(const td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double w;
    if (r->rs < 0)
        return 0.0;
    w = y[s->dae.ov + r->rs];
    return (td_sim_race_drag(s, k, y, NULL) + r->r.race.drag_viscous * w) * w;
}

void td_sim_thermal_point(td_sim *s, int k, double dt, double friction, td_retainer_totals *t)
{
    td_sim_thermal *h = &s->monitor.thermal[k];
    double drag = drag_power(s, k, N_VGetArrayPointer(s->dae.y)), power = friction + drag;
    if (dt > 0.0) {
        t->drag_work += 0.5 * dt * (h->drag + drag);
        if (h->on) {
            memcpy(h->T_before, h->T, sizeof h->T);
            h->t_before = s->monitor.totals_t;
            h->power_before = h->power;
            td_thermal_network_step(&h->net, h->T, dt, h->power, power);
        }
    }
    t->heat = t->friction_work + t->drag_work;
    h->drag = drag;
    h->power = power;
}

/* Retainer k's rises at s->dae.t, the last point lying dt beyond it, the heat power there `power`:
 * the last segment's part beyond s->dae.t taken back in closed form, as the totals take back their
 * trapezoid, so that the network holds what heat says; from the point before when the step reaches
 * far into a fast network (taking back would magnify the round-off by exp(lambda dt)). */
static void rises_back(const td_sim_thermal *h, double t, double dt, double power, double T[2])
{
    if (td_thermal_network_reach(&h->net, dt) <= 1.0) {
        memcpy(T, h->T, 2 * sizeof *T);
        td_thermal_network_step(&h->net, T, -dt, h->power, power);
        return;
    }
    memcpy(T, h->T_before, 2 * sizeof *T);
    td_thermal_network_step(&h->net, T, t - h->t_before, h->power_before, power);
}

void td_sim_thermal_back(const td_sim *s, int k, td_retainer_totals *t, double T[2])
{
    const td_sim_thermal *h = &s->monitor.thermal[k];
    const double *y = N_VGetArrayPointer(s->dae.y);
    double dt = s->monitor.totals_t - s->dae.t, drag, Tn[2];
    Tn[0] = h->T[0];
    Tn[1] = h->T[1];
    if (dt > 0.0) {
        drag = drag_power(s, k, y);
        t->drag_work -= 0.5 * dt * (h->drag + drag);
        if (h->on)
            rises_back(h, s->dae.t, dt, td_sim_friction_power(s, k, y) + drag, Tn);
    }
    t->heat = t->friction_work + t->drag_work;
    t->peak_temperature_rise = h->on ? fmax(h->peak, Tn[0]) : TD_UNDEFINED;
    t->peak_thermal_growth = h->on ? h->growth_per_kelvin * t->peak_temperature_rise : TD_UNDEFINED;
    if (T) {
        T[0] = h->on ? Tn[0] : TD_UNDEFINED;
        T[1] = h->on ? Tn[1] : TD_UNDEFINED;
    }
}

void td_sim_thermal_rewind(td_sim *s, int k)
{
    td_sim_thermal *h = &s->monitor.thermal[k];
    const double *y = N_VGetArrayPointer(s->dae.y);
    double T[2];
    td_sim_thermal_back(s, k, &s->monitor.totals[k].t, T);
    h->drag = drag_power(s, k, y);
    h->power = td_sim_friction_power(s, k, y) + h->drag;
    if (!h->on)
        return;
    memcpy(h->T, T, sizeof T);
    memcpy(h->T_before, T, sizeof T);
    h->t_before = s->dae.t;
    h->power_before = h->power;
    h->peak = fmax(h->peak, T[0]); /* the run has reached s->dae.t */
}

void td_sim_thermal_peak(td_sim *s, int k)
{
    td_sim_thermal *h = &s->monitor.thermal[k];
    if (h->on)
        h->peak = fmax(h->peak, h->T[0]);
}

void td_sim_thermal_now(const td_sim *s, int k, double T[2])
{
    td_retainer_totals scratch;
    memset(&scratch, 0, sizeof scratch);
    td_sim_thermal_back(s, k, &scratch, T);
}
