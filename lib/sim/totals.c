/*
 * The retainers' running totals (touchdown/records.h td_retainer_totals): time integrals over the
 * integrator's steps, peaks, and the contact intervals told apart from touch-and-go impacts.
 *
 * Points come in order: every accepted step and every stop (a root, a schedule time) closes a
 * segment with the trapezoid rule from the previous point; the state right after a restart opens
 * the next one without advancing time (a mode switch, an impact or a change jumps lambda, F_t or
 * the velocities there). Between two points the modes are fixed (they change at restarts only),
 * so time in contact and rolling is the segment's length in the mode at its end.
 */
#include "sim/sim_internal.h"
#include "touchdown/assess.h"

#include <math.h>
#include <string.h>

/* The integrands of retainer k at y. */
typedef struct integrands {
    double n, n2, power, whirl_rate;
} integrands;

static integrands integrands_at(const td_sim *s, int k, const double *y)
{
    integrands v = {0.0, 0.0, 0.0, 0.0};
    double x, yy, vx, vy, r2;
    if (s->contacts.ret[k].mode == TD_RMODE_FREE)
        return v;
    v.n = td_sim_normal_force(s, k, y);
    v.n2 = v.n * v.n;
    v.power = td_sim_friction_power(s, k, y);
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    r2 = x * x + yy * yy;
    v.whirl_rate = r2 > 0.0 ? (x * vy - yy * vx) / r2 : 0.0;
    return v;
}

/* Force retainer k passes to the housing at y: the mount's spring and damper on a mount, else the
 * contact force itself, normal and friction. */
static double housing_force(const td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double n, f;
    if (r->rx >= 0) {
        double fx = r->r.race.mount_stiffness * y[s->dae.oq + r->rx] + r->r.race.mount_damping * y[s->dae.ov + r->rx];
        double fy = r->r.race.mount_stiffness * y[s->dae.oq + r->ry] + r->r.race.mount_damping * y[s->dae.ov + r->ry];
        return hypot(fx, fy);
    }
    if (r->mode == TD_RMODE_FREE && !(r->compliant && td_sim_penalty_force(s, k, y, NULL, NULL) > 0.0))
        return 0.0;
    n = td_sim_normal_force(s, k, y);
    f = td_sim_friction_force(s, k, y);
    return hypot(n, f);
}

/* Retainer k's contact interval ends: a contact if it swept TD_TOUCH_AND_GO_ANGLE, else an impact. */
static void interval_ends(td_sim *s, int k)
{
    td_sim_totals *tk = &s->monitor.totals[k];
    if (fabs(tk->t.whirl_angle - tk->whirl_at_onset) >= TD_TOUCH_AND_GO_ANGLE)
        tk->t.contacts++;
    else
        tk->t.touch_and_go++;
}

/* Open and close contact intervals as retainer k's mode says at this point. */
static void track_interval(td_sim *s, int k)
{
    td_sim_totals *tk = &s->monitor.totals[k];
    int in = s->contacts.ret[k].mode != TD_RMODE_FREE;
    if (in && !tk->in_contact)
        tk->whirl_at_onset = tk->t.whirl_angle;
    else if (!in && tk->in_contact)
        interval_ends(s, k);
    tk->in_contact = in;
}

/* The bearing's duty at y: retainer k's sliding, friction power and PV in contact, its race speed
 * always; the race's width from the model's bearing (0: none, PV stays 0 here, TD_UNDEFINED in
 * td_sim_totals_get). */
static void duty_peaks(td_sim *s, int k, const double *y)
{
    td_retainer_totals *t = &s->monitor.totals[k].t;
    td_retainer_bearing b;
    t->peak_race_speed = fmax(t->peak_race_speed, fabs(td_sim_race_speed(s, k, y)));
    if (s->contacts.ret[k].mode != TD_RMODE_FREE) {
        double vs = fabs(td_sim_sliding_velocity(s, k, y));
        t->peak_sliding_velocity = fmax(t->peak_sliding_velocity, vs);
        t->peak_friction_power =
            fmax(t->peak_friction_power, td_sim_friction_force(s, k, y) * td_sim_sliding_velocity(s, k, y));
        if (td_model_get_retainer_bearing(s->model, k, &b) == TD_OK && b.width > 0.0)
            t->peak_pv = fmax(t->peak_pv,
                              td_sim_normal_force(s, k, y) / (2.0 * s->contacts.ret[k].r.shaft_radius * b.width) * vs);
    }
}

/* The largest 0-peak displacement at each AMB's sensor while the AMB works (ISO 14839-2's D). */
static void sensor_peaks(td_sim *s, const double *y)
{
    int j;
    for (j = 0; j < s->sys->n_amb_axes / 2; j++) {
        const td_amb_axis *ax = &s->sys->amb_axes[2 * j], *ay = &s->sys->amb_axes[2 * j + 1];
        if (s->machine.amb_mode[ax->amb] == TD_AMB_OFF)
            continue;
        s->monitor.sensor_peak[ax->amb] =
            fmax(s->monitor.sensor_peak[ax->amb], hypot(y[s->dae.oq + ax->sensor_dof], y[s->dae.oq + ay->sensor_dof]));
    }
}

void td_sim_totals_peaks(td_sim *s, const double *y)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        tk->t.peak_housing_force = fmax(tk->t.peak_housing_force, housing_force(s, k, y));
        if (s->contacts.ret[k].mode != TD_RMODE_FREE) { /* as integrands_at's n */
            double fn = td_sim_normal_force(s, k, y);
            tk->t.peak_normal_force = fmax(tk->t.peak_normal_force, fn);
            tk->mark_peak = fmax(tk->mark_peak, fn); /* long runs: a window's peak */
        }
        duty_peaks(s, k, y);
        td_sim_thermal_peak(s, k);  /* heat */
        td_sim_life_point(s, k, y); /* life: a point reached, into the rainflow count */
    }
    sensor_peaks(s, y);
}

void td_sim_totals_point(td_sim *s, double t, int restart)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    double dt = restart ? 0.0 : t - s->monitor.totals_t;
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        integrands now = integrands_at(s, k, y);
        if (dt > 0.0) {
            tk->t.impulse += 0.5 * dt * (tk->prev.n + now.n);
            tk->t.normal_force_sq += 0.5 * dt * (tk->prev.n2 + now.n2);
            tk->t.friction_work += 0.5 * dt * (tk->prev.power + now.power);
            tk->t.whirl_angle += 0.5 * dt * (tk->prev.whirl_rate + now.whirl_rate);
            if (s->contacts.ret[k].mode != TD_RMODE_FREE)
                tk->t.contact_time += dt;
            if (s->contacts.ret[k].rolling)
                tk->t.rolling_time += dt;
        }
        td_sim_thermal_point(s, k, dt, now.power, &tk->t); /* heat */
        tk->prev.n = now.n;
        tk->prev.n2 = now.n2;
        tk->prev.power = now.power;
        tk->prev.whirl_rate = now.whirl_rate;
        if (restart || dt > 0.0)
            track_interval(s, k);
        { /* life: the race's revolutions under load (load_cycles.c) */
            double rate = td_sim_life_rate(s, k, y);
            if (dt > 0.0)
                tk->t.damage += 0.5 * dt * (tk->life_rate_prev + rate);
            tk->life_rate_prev = rate;
        }
    }
    if (!(s->monitor.ahead && s->monitor.ahead_t == t))
        td_sim_totals_peaks(s, y);
    td_sim_margin_point(s, t); /* clearance margin */
    if (s->opt.energy)
        td_sim_energy_point(s, t, restart, dt);
    if (t > s->monitor.totals_t || restart)
        s->monitor.totals_t = t;
}

void td_sim_totals_impact(td_sim *s, int k, double impulse, int bounced)
{
    s->monitor.totals[k].t.impulse += impulse;
    s->monitor.totals[k].t.impact_impulse += impulse;
    if (bounced) /* a rebound: in and out at one instant */
        s->monitor.totals[k].t.touch_and_go++;
}

/* The totals of retainer k at s->dae.t when the last point lies beyond it (an output inside the
 * integrator's last step): the trapezoid from s->dae.t to that point taken back. */
static void back_to_now(const td_sim *s, int k, td_retainer_totals *t)
{
    const td_sim_totals *tk = &s->monitor.totals[k];
    double dt = s->monitor.totals_t - s->dae.t;
    integrands now;
    if (!(dt > 0.0))
        return;
    now = integrands_at(s, k, N_VGetArrayPointer(s->dae.y));
    t->impulse -= 0.5 * dt * (tk->prev.n + now.n);
    t->normal_force_sq -= 0.5 * dt * (tk->prev.n2 + now.n2);
    t->friction_work -= 0.5 * dt * (tk->prev.power + now.power);
    t->whirl_angle -= 0.5 * dt * (tk->prev.whirl_rate + now.whirl_rate);
    if (s->contacts.ret[k].mode != TD_RMODE_FREE)
        t->contact_time -= dt;
    if (s->contacts.ret[k].rolling)
        t->rolling_time -= dt;
    t->damage -= 0.5 * dt * (tk->life_rate_prev + td_sim_life_rate(s, k, N_VGetArrayPointer(s->dae.y))); /* life */
}

void td_sim_totals_rewind(td_sim *s)
{
    int k;
    if (!(s->monitor.totals_t > s->dae.t))
        return;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        integrands now = integrands_at(s, k, N_VGetArrayPointer(s->dae.y));
        back_to_now(s, k, &tk->t);
        td_sim_thermal_rewind(s, k); /* heat */
        tk->prev.n = now.n;
        tk->prev.n2 = now.n2;
        tk->prev.power = now.power;
        tk->prev.whirl_rate = now.whirl_rate;
        tk->life_rate_prev = td_sim_life_rate(s, k, N_VGetArrayPointer(s->dae.y)); /* life */
    }
    td_sim_energy_rewind(s);
    td_sim_margin_rewind(s); /* clearance margin */
    s->monitor.totals_t = s->dae.t;
}

/* The duty's quantities that need the bearing: undefined without it, the Hertz stress at the peak load. */
static void duty_get(const td_sim *s, int k, td_retainer_totals *out)
{
    td_retainer_bearing b;
    if (td_model_get_retainer_bearing(s->model, k, &b) != TD_OK)
        memset(&b, 0, sizeof b);
    if (!(b.width > 0.0))
        out->peak_pv = TD_UNDEFINED;
    out->peak_contact_stress = b.balls > 0
                                   ? td_ball_inner_contact_stress(out->peak_normal_force, b.balls, b.ball_diameter,
                                                                  b.pitch_diameter, b.groove_conformity)
                                   : TD_UNDEFINED;
}

void td_sim_totals_get(const td_sim *s, int k, td_retainer_totals *out)
{
    const td_sim_totals *tk = &s->monitor.totals[k];
    *out = tk->t;
    back_to_now(s, k, out);
    /* heat */
    td_sim_thermal_back(s, k, out, NULL);
    if (tk->in_contact) /* the interval still open counts as a contact */
        out->contacts++;
    duty_get(s, k, out);
    td_sim_life_get(s, k, out); /* life: the rainflow cycles added, the end's included */
    /* clearance margin */
    out->min_clearance_margin = td_sim_margin_get(s, k);
}

void td_sim_sensor_peak_get(const td_sim *s, int amb, double *out)
{
    *out = s->monitor.sensor_peak[amb];
}
