/*
 * The start state of a run: the steady orbit of the contact-free machine (lib/modal) or rest, as
 * the options ask and the machine allows, the races and the spin at their start, and the
 * retainers touched at the start brought into contact.
 */
#include "sim/sim_internal.h"
#include "touchdown/modal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdio.h>

/* A start orbit at most this far outside a clearance circle (relative) counts as touching it. */
#define TD_START_TOUCH_TOLERANCE 1e-6

/* The size of the start's eigenproblem: the first-order form's states and, for a sampled
 * controller, its own (lib/modal/sampled.c closes the held plant with them). */
static int stability_state_count(const td_system *sys)
{
    int n = td_modal_state_count(sys), i;
    for (i = 0; i < sys->n_laws; i++)
        if (sys->laws[i].sample_rate > 0.0 && !sys->laws[i].standby) /* as lib/modal/sampled.c counts */
            n += sys->laws[i].n;
    return n;
}

/* Stability of the contact-free closed loop at the start speed, from the eigenvalues of its
 * first-order form (lib/modal, AMB filter states included). A model too big for a quick dense
 * eigen-solve, or one the analysis refuses (a plug-in controller has no linear law) or fails on,
 * stays unchecked, with the reason: the check informs, it never blocks. */
void td_sim_start_stability(td_sim *s)
{
    int unstable = 0, n = stability_state_count(s->sys);
    td_error merr;
    s->start.stability = TD_STABILITY_UNCHECKED;
    s->start.max_real_part = NAN;
    s->start.unchecked[0] = '\0';
    if (n > TD_SIM_STABILITY_MAX_STATES) {
        snprintf(s->start.unchecked, sizeof s->start.unchecked,
                 "%d first-order states, more than %d for a check at the start (touchdown modal does it)", n,
                 TD_SIM_STABILITY_MAX_STATES);
        return;
    }
    td_error_clear(&merr);
    if (td_modal_stability(s->sys, s->machine.omega, &s->start.max_real_part, &unstable, &merr) != TD_OK) {
        snprintf(s->start.unchecked, sizeof s->start.unchecked, "%.250s",
                 merr.message[0] ? merr.message : "no eigen-solution");
        s->start.max_real_part = NAN;
        return;
    }
    s->start.stability = unstable ? TD_STABILITY_UNSTABLE : TD_STABILITY_STABLE;
}

/* First retainer whose start radius exceeds its clearance by more than the grazing tolerance
 * (its radius in *rad), -1 if none. */
static int first_outside(const td_sim *s, const double *y, double *rad)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double x, yy, vx, vy;
        td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
        *rad = hypot(x, yy);
        if (*rad - r->r.clearance > TD_START_TOUCH_TOLERANCE * r->r.clearance)
            return k;
    }
    return -1;
}

/* The rotor's state [q (ndof) | v (ndof) | w] at the start of y, as the modal analysis writes it,
 * moved to its places when races add DOFs after the rotor's (y = [q (n) | v (n) | w ...]). */
static void spread_rotor_state(const td_sim *s, double *y)
{
    int nd = s->sys->ndof, i;
    if (s->dae.n == nd)
        return;
    for (i = s->dae.nw - 1; i >= 0; i--) /* back to front: the blocks only move up */
        y[s->dae.ow + i] = y[2 * nd + i];
    for (i = nd - 1; i >= 0; i--)
        y[s->dae.ov + i] = y[nd + i];
    for (i = nd; i < s->dae.ov; i++) /* the races' q, and the gap the rotor's v left */
        y[s->dae.oq + i] = 0.0;
    for (i = s->dae.ov + nd; i < s->dae.ow; i++)
        y[i] = 0.0;
}

/* The time whose phase omega t the steady orbit takes: the start time, or with a ramp the time at
 * which a constant speed would have turned the spin angle the ramp has turned. */
static double orbit_phase_time(const td_sim *s)
{
    double angle;
    if (s->machine.spin < 0 || !(s->machine.omega > 0.0))
        return s->dae.t;
    td_model_speed_at(s->model, s->dae.t, NULL, &angle);
    return angle / s->machine.omega;
}

/* An orbit start of a model with plug-in controller k: "orbit" refuses it, "auto" starts at rest
 * with the reason. */
static td_status plugin_no_orbit(td_sim *s, int k, int strict, td_error *err)
{
    const char *name = s->sys->laws[k].plugin->name;
    if (strict)
        return td_error_set(err, TD_ERR_INVALID,
                            "start = \"orbit\": controller %d (\"%s\") is a plug-in, and the steady orbit is computed "
                            "for linear controllers only; use start = \"rest\"",
                            k, name);
    snprintf(s->start.reason, sizeof s->start.reason, "controller %d (\"%s\") is a plug-in: no steady orbit computed",
             k, name);
    return TD_OK;
}

/* The steady orbit into y. An unstable system has none that the motion would stay on: "orbit"
 * refuses it, "auto" stays at rest; "auto" also stays at rest when the orbit is not contact-free.
 * s->start.used says which start y holds. */
static td_status orbit_start(td_sim *s, double *y, td_error *err)
{
    int strict = s->opt.start == TD_START_ORBIT, k;
    double gx, gy, rad = 0.0;
    td_error merr;
    td_status st;
    if (s->start.stability == TD_STABILITY_UNSTABLE) {
        if (strict)
            return td_error_set(err, TD_ERR_INVALID,
                                "start = \"orbit\": the contact-free system is unstable at %.6g rad/s (rightmost "
                                "eigenvalue real part %.6g 1/s), so it has no steady orbit; use start = \"rest\"",
                                s->machine.omega, s->start.max_real_part);
        snprintf(s->start.reason, sizeof s->start.reason,
                 "the contact-free system is unstable (rightmost eigenvalue real part %.6g 1/s)",
                 s->start.max_real_part);
        return TD_OK;
    }
    for (k = 0; k < s->sys->n_laws; k++)
        if (s->sys->laws[k].plugin) /* no linear law: no orbit to compute */
            return plugin_no_orbit(s, k, strict, err);
    for (k = 0; k < s->sys->n_laws; k++)
        if (s->sys->laws[k].state < 0) { /* its state is the sampler's, outside the first-order form */
            if (strict)
                return td_error_set(err, TD_ERR_INVALID,
                                    "start = \"orbit\": controller %d is sampled, and the steady orbit is computed "
                                    "for continuous controllers only; use start = \"rest\"",
                                    k);
            snprintf(s->start.reason, sizeof s->start.reason, "controller %d is sampled: no steady orbit computed", k);
            return TD_OK;
        }
    td_model_gravity(s->model, &gx, &gy);
    st = td_modal_start_state(s->sys, s->machine.omega, s->machine.unb, s->machine.nu, gx != 0.0 || gy != 0.0,
                              orbit_phase_time(s), y + s->dae.oq, &merr);
    if (st == TD_ERR_NUMERIC) { /* no steady state: nothing holds the rotor against gravity, a resonance */
        N_VConst(0.0, s->dae.y);
        if (strict)
            return td_error_set(err, TD_ERR_INVALID,
                                "start = \"orbit\": %s, so there is no steady orbit; use "
                                "start = \"rest\"",
                                merr.message);
        snprintf(s->start.reason, sizeof s->start.reason, "no steady orbit: %.200s", merr.message);
        return TD_OK;
    }
    if (st != TD_OK)
        return td_error_set(err, st, "%s", merr.message);
    spread_rotor_state(s, y);
    s->start.used = TD_START_ORBIT;
    if (strict || (k = first_outside(s, y, &rad)) < 0)
        return TD_OK;
    snprintf(s->start.reason, sizeof s->start.reason,
             "the steady orbit lies outside the clearance of retainer %d (r = %.6g m > c = %.6g m)", k, rad,
             s->contacts.ret[k].r.clearance);
    N_VConst(0.0, s->dae.y);
    s->start.used = TD_START_REST;
    return TD_OK;
}

td_status td_sim_start_state(td_sim *s, td_error *err)
{
    double *y = N_VGetArrayPointer(s->dae.y);
    int *touching = s->contacts.touching;
    int k;
    td_status st;
    N_VConst(0.0, s->dae.y);
    N_VConst(0.0, s->dae.yp);
    s->start.requested = s->opt.start;
    s->start.used = TD_START_REST;
    s->start.reason[0] = '\0';
    if (s->opt.start != TD_START_REST && (st = orbit_start(s, y, err)) != TD_OK)
        return st;
    td_sim_races_start(s, y);
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_retainer *r = &s->contacts.ret[k];
        double x, yy, vx, vy, rad, c = r->r.clearance;
        td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
        rad = hypot(x, yy);
        touching[k] = 0;
        if (rad <= c)
            continue;
        if (td_sim_penalty_model(s, k)) {
            r->mode = TD_RMODE_PENETRATING;
            td_sim_init_slip(s, k, y);
        } else if (rad - c <= TD_START_TOUCH_TOLERANCE * c) {
            touching[k] = 1; /* grazing start: into contact as at an onset, if it presses */
        } else {
            return td_error_set(err, TD_ERR_INVALID,
                                "the start state is outside the clearance of retainer %d (r = %.9g m > c = %.9g m): "
                                "the free orbit is not contact-free; use start = \"auto\" or \"rest\", or reduce "
                                "the unbalance",
                                k, rad, c);
        }
    }
    st = td_sim_start_contacts(s, touching);
    return st == TD_OK ? TD_OK : td_error_set(err, st, "inconsistent start state: %s", s->errmsg);
}
