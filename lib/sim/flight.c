/*
 * Free flight in closed form (flight_internal.h): whether the machine may fly, the flight's steps
 * from root to root (flight_roots.c) on the modal solution (flight_modal.c), and the AMBs' peak
 * load between its points.
 */
#include "sim/flight_internal.h"

#include <complex.h>
#include <math.h>
#include <string.h>

/* 1 if the machine may fly in closed form now: free flight on (td_solver_options), no energy
 * account, a prescribed constant speed, no housing motion or body, no races, no AMB saturation or slew
 * limit (the flight has no root function for their kinks and would step across one unseen, and its
 * probes of the residual, half a clearance and 1 m/s, would reach a clip), every retainer free (one
 * with a force law only once its gap has opened by eps after its last exit). The decomposition may
 * still refuse it (td_sim_flight_advance). The step loop flies only with no stop pending. */
static int flight_eligible(const td_sim *s)
{
    int k;
    if (!s->opt.solver.free_flight || s->opt.energy || s->machine.spin >= 0 || td_model_speed_varies(s->model))
        return 0;
    /* housing motion: its loads vary in time (the flight's forcing is harmonic, probed ahead of now) */
    if (s->sys->base_load[0])
        return 0;
    if (s->sys->nbody > 0) /* housing body: its unbalance share is not in the flight's forcing */
        return 0;
    for (k = 0; k < s->sys->n_amb_axes; k++)
        if (s->sys->amb_axes[k].saturation || s->sys->amb_axes[k].slew_rate > 0.0)
            return 0;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        if ((r->compliant && !r->armed) || r->rx >= 0 || r->rs >= 0 || r->mode != TD_RMODE_FREE || r->rolling)
            return 0;
    }
    return 1;
}

/* ---- the AMBs' peak load between points -------------------------------------------------- */

/* AMB axis k's force at t (recorded in the peak load). */
static double amb_force_at(td_sim *s, td_sim_flight *f, int k, double t)
{
    flight_val v;
    td_sim_flight_propagate(f, t);
    v = td_sim_flight_observe(f, 2 * s->dae.nr + k, t);
    td_sim_monitor_amb_load(s, k, v.v, t);
    return v.v;
}

/* The largest load of AMB axis k on [ta, ta + h] (forces fa, fb at the ends) to FLIGHT_PEAK_RTOL:
 * |F| exceeds the larger end by at most |F''|max h^2 / 8 (b2 bounds |F''|); halve the interval
 * while that could beat the peak so far. */
static void amb_peak_search(td_sim *s, td_sim_flight *f, int k, double ta, double h, double fa, double fb, double b2,
                            int depth)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    double fm;
    if (fmax(fabs(fa), fabs(fb)) + 0.125 * b2 * h * h <=
            s->monitor.stats.peak_amb_load * a->capacity * (1.0 + FLIGHT_PEAK_RTOL) ||
        depth >= 60)
        return;
    fm = amb_force_at(s, f, k, ta + 0.5 * h);
    amb_peak_search(s, f, k, ta, 0.5 * h, fa, fm, b2, depth + 1);
    amb_peak_search(s, f, k, ta + 0.5 * h, 0.5 * h, fm, fb, b2, depth + 1);
}

/* The AMBs' forces at the last propagate (time t) into fa, their bounds |F''| into b2; the peak
 * load updated if `record` (t is not beyond the output time). */
static void amb_forces(td_sim *s, td_sim_flight *f, double t, double *fa, double *b2, int record)
{
    int k, n = s->sys->n_amb_axes, o = 2 * s->dae.nr;
    flight_val v[2];
    for (k = 0; k < n; k++) {
        if (k % 2 == 0 && k + 1 < n) /* two axes in one pass over the modes */
            td_sim_flight_observe2(f, o + k, o + k + 1, t, &v[0], &v[1]);
        else if (k % 2 == 0)
            v[0] = td_sim_flight_observe(f, o + k, t);
        fa[k] = v[k % 2].v;
        if (b2)
            b2[k] = v[k % 2].b2;
        if (record && s->machine.amb_mode[s->sys->amb_axes[k].amb] != TD_AMB_OFF)
            td_sim_monitor_amb_load(s, k, v[k % 2].v, t);
    }
}

/* The AMBs' peak load inside [t, t + h], forces fa at t and fb at t + h, |F''| <= b2 from t on.
 * Leaves f->e anywhere. */
static void amb_peaks(td_sim *s, td_sim_flight *f, double t, double h, const double *fa, const double *fb,
                      const double *b2)
{
    int k;
    for (k = 0; k < s->sys->n_amb_axes; k++) {
        const td_amb_axis *a = &s->sys->amb_axes[k];
        double peak = s->monitor.stats.peak_amb_load * a->capacity * (1.0 + FLIGHT_PEAK_RTOL);
        if (s->machine.amb_mode[a->amb] == TD_AMB_OFF || fmax(fabs(fa[k]), fabs(fb[k])) + 0.125 * b2[k] * h * h <= peak)
            continue;
        amb_peak_search(s, f, k, t, h, fa[k], fb[k], b2[k], 0);
    }
}

/* The AMBs' peak over [a, b], part of a step whose |F''| bounds are b2 (forces at a: fa, or
 * evaluated if NULL). Leaves f->e anywhere. */
static void amb_span(td_sim *s, td_sim_flight *f, double a, double b, const double *fa, const double *b2)
{
    if (!(b > a))
        return;
    if (!fa) {
        td_sim_flight_propagate(f, a);
        amb_forces(s, f, a, f->amb_p, NULL, 1);
        fa = f->amb_p;
    }
    td_sim_flight_propagate(f, b);
    amb_forces(s, f, b, f->amb_b, NULL, 1);
    amb_peaks(s, f, a, b - a, fa, f->amb_b, b2);
}

/* ---- clearance margin: the retainers' largest radius between points ------------------------ */

/* Retainer k's node at the last propagate (time t): r^2 into *r2, the bound on |(r^2)''| from t over
 * the next h_max into *bound (as flight_roots.c's root functions; may be NULL). */
static void margin_value(const td_sim_flight *f, int k, double t, double *r2, double *bound)
{
    flight_val x, y;
    if (bound) {
        *bound = td_sim_flight_node(f, k, t, &x, &y);
    } else {
        x = td_sim_flight_observe(f, 2 * k, t);
        y = td_sim_flight_observe(f, 2 * k + 1, t);
    }
    *r2 = x.v * x.v + y.v * y.v;
}

/* The largest radius of retainer k's node on [ta, ta + h] (r^2 = fa, fb at the ends, |(r^2)''| <= b2) to
 * TD_MARGIN_RTOL of its clearance: r^2 exceeds the larger end by at most b2 h^2 / 8; halve the interval
 * while that could beat the largest radius so far by more. A time the run has reached. */
static void margin_search(td_sim *s, td_sim_flight *f, int k, double ta, double h, double fa, double fb, double b2,
                          int depth)
{
    double c = s->contacts.ret[k].r.clearance, reach = c - s->monitor.totals[k].margin + TD_MARGIN_RTOL * c, fm;
    if (fmax(fa, fb) + 0.125 * b2 * h * h <= reach * reach || depth >= 40)
        return;
    td_sim_flight_propagate(f, ta + 0.5 * h);
    margin_value(f, k, ta + 0.5 * h, &fm, NULL);
    td_sim_margin_note(s, k, sqrt(fm));
    margin_search(s, f, k, ta, 0.5 * h, fa, fm, b2, depth + 1);
    margin_search(s, f, k, ta + 0.5 * h, 0.5 * h, fm, fb, b2, depth + 1);
}

/* The flight's point t (the last propagate there; `reached`: a time the run has reached, its radii
 * noted): each retainer's r^2 and bound kept for the step from t. */
static void margin_point(td_sim *s, td_sim_flight *f, double t, int reached)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        margin_value(f, k, t, &tk->flight_r2, &tk->flight_b2);
        if (reached)
            td_sim_margin_note(s, k, sqrt(tk->flight_r2));
    }
}

/* The part [a, b] of the step from a (its values kept by margin_point), b a time the run has reached:
 * the radii at b and the largest between. With `to_end` b ends the step (the last propagate is at b):
 * b's values are kept for the next one. Leaves f->e anywhere. */
static void margin_part(td_sim *s, td_sim_flight *f, double a, double b, int to_end)
{
    int k;
    if (!to_end)
        td_sim_flight_propagate(f, b);
    for (k = 0; k < s->dae.nr; k++) /* every value at b first: the searches move f->e */
        margin_value(f, k, b, &s->monitor.totals[k].flight_r2b, &s->monitor.totals[k].flight_b2b);
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        td_sim_margin_note(s, k, sqrt(tk->flight_r2b));
        margin_search(s, f, k, a, b - a, tk->flight_r2, tk->flight_r2b, tk->flight_b2, 0);
        if (to_end) {
            tk->flight_r2 = tk->flight_r2b;
            tk->flight_b2 = tk->flight_b2b;
        }
    }
}

/* The retainers' largest radii over [a, b] (the pending part of a step, b - a <= h_max), from a's bounds;
 * b a time the run has reached. Leaves f->e anywhere; the values kept for the step (those at its end,
 * which margin_point would compute again with the same bits) are kept as they were. */
static void margin_span(td_sim *s, td_sim_flight *f, double a, double b)
{
    int k;
    if (!(b > a))
        return;
    td_sim_flight_propagate(f, a);
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        tk->flight_r2s = tk->flight_r2;
        tk->flight_b2s = tk->flight_b2;
        margin_value(f, k, a, &tk->flight_r2, &tk->flight_b2);
    }
    margin_part(s, f, a, b, 0);
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        tk->flight_r2 = tk->flight_r2s;
        tk->flight_b2 = tk->flight_b2s;
    }
}

/* A step [t, tn] ran past the output time t_out: the AMBs' peak up to t_out now, the rest
 * (pending from t_out, with the step's bounds) when the next call's output time is known, so that
 * no peak is recorded beyond the time reached. */
static void amb_past_output(td_sim *s, td_sim_flight *f, double t, double t_out)
{
    amb_span(s, f, t, t_out, f->amb_a, f->amb_b2);
    f->amb_pending = fmax(t, t_out);
    memcpy(f->amb_b2p, f->amb_b2, sizeof(double) * (size_t)s->sys->n_amb_axes);
}

/* The pending part of the last step (amb_past_output) up to this call's output time; 1 if there was
 * one (the clearance margin's values at the step's end are then still those kept, beyond s->dae.t). */
static int amb_pending_part(td_sim *s, td_sim_flight *f, double t_out)
{
    double end = fmin(f->t_step, t_out);
    if (!(f->amb_pending < f->t_step))
        return 0;
    amb_span(s, f, f->amb_pending, end, NULL, f->amb_b2p);
    margin_span(s, f, f->amb_pending, end); /* clearance margin: the bounds from the part's start */
    f->amb_pending = end < f->t_step ? end : INFINITY;
    return 1;
}

/*
 * The samples just taken at a stop the flight reached (s->dae.t, where its last step ended): the
 * currents they hold go into the flight's forcing (td_sim_flight_shift_held) and it carries on from
 * there. Between samples the machine with its held currents is linear, so each sample is taken from
 * the exact state (to rounding) and the flight needs no restart. 0 if the flight cannot go on from
 * here: the caller restarts the integrator instead.
 */
int td_sim_flight_hold(td_sim *s)
{
    td_sim_flight *f = s->flight;
    if (!f || !f->anchored || f->handover || f->t_step != s->dae.t || f->amb_pending < f->t_step || !flight_eligible(s))
        return 0;
    td_sim_flight_shift_held(s, f, 1);
    td_sim_flight_propagate(f, s->dae.t);
    amb_forces(s, f, s->dae.t, f->amb_a, f->amb_b2, 1); /* the new bounds; without a lag the force jumps */
    return 1;
}

/*
 * The flight's own steps run on from where the last one ended (f->t_step, which may lie beyond
 * s->dae.t): outputs only evaluate the solution, so the steps, the roots and the peaks found do not
 * depend on the output times (as IDA's do not). A stop (t_stop: a schedule change) ends a step.
 */
int td_sim_flight_advance(td_sim *s, const double *scale, double t_out, double t_stop, int *root)
{
    td_sim_flight *f;
    double t, t_end = fmin(t_out, t_stop);
    long steps = 0;
    *root = 0;
    if (!flight_eligible(s) || !td_sim_flight_ready(s, scale))
        return 0;
    f = s->flight;
    if (f->t_step < s->dae.t || f->t_step > t_stop) { /* a fresh flight */
        if (!td_sim_flight_clear_of_roots(s, f))
            return 0;
        f->t_step = s->dae.t;
        f->amb_pending = INFINITY;
        td_sim_flight_propagate(f, f->t_step);
        amb_forces(s, f, f->t_step, f->amb_a, f->amb_b2, 1);
    }
    if (!amb_pending_part(s, f, t_out)) {
        td_sim_flight_propagate(f, f->t_step); /* clearance margin: the bounds of this anchor and forcing */
        margin_point(s, f, f->t_step, f->t_step <= s->dae.t);
    }
    t = f->t_step;
    while (t < t_end) {
        double h, tn;
        if ((s->interrupt && *s->interrupt) || steps >= FLIGHT_MAX_STEPS) {
            f->handover = steps >= FLIGHT_MAX_STEPS;
            break;
        }
        td_sim_flight_propagate(f, t);
        h = td_sim_flight_next_step(s, f, t, root);
        steps++;
        if (*root && t <= f->t_root) { /* the same root again: its event changed nothing the flight sees */
            *root = 0;
            f->handover = 1;
            break;
        }
        if (*root) {
            f->t_root = t;
            break;
        }
        if (h < FLIGHT_ROOT_TOL) { /* on a root function's wrong side, or creeping: IDA's turn */
            f->handover = 1;
            break;
        }
        h = fmin(h, f->h_max);
        tn = t + h < t_stop - FLIGHT_ROOT_TOL ? t + h : t_stop; /* no sliver of a step before the stop */
        if (tn <= t_out) {
            td_sim_flight_propagate(f, tn);
            amb_forces(s, f, tn, f->amb_b, NULL, 1);
            amb_peaks(s, f, t, tn - t, f->amb_a, f->amb_b, f->amb_b2);
        } else {
            amb_past_output(s, f, t, t_out);
            if (t_out > t) /* clearance margin: up to the output, the rest with the pending part */
                margin_part(s, f, t, t_out, 0);
        }
        td_sim_flight_propagate(f, tn);
        amb_forces(s, f, tn, f->amb_a, f->amb_b2, tn <= t_out);
        if (tn <= t_out) /* clearance margin: the step's end, and the largest radius inside it */
            margin_part(s, f, t, tn, 1);
        else
            margin_point(s, f, tn, 0);
        t = tn;
    }
    f->t_step = t;
    if (t == s->dae.t && t < t_end && !*root) /* no progress (a grazing start): IDA's turn, nothing moved */
        return 0;
    if (t > t_end && !*root) /* the last step ran past the output: the state there */
        t = t_end;
    td_sim_margin_rewind(s); /* clearance margin: a step of IDA's held beyond s->dae.t counts up to it */
    s->monitor.margin_flown = 1;
    td_sim_flight_materialise(s, f, t, 0);
    s->monitor.stats.flight_steps += steps;
    s->monitor.stats.flight_time += t - s->dae.t;
    s->dae.t = t;
    return 1;
}
