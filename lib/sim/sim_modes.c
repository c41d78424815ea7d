/*
 * Mode switching of the contact DAE: impacts, consistent re-initialisation, the event queue,
 * the schedule, and IDA restarts.
 *
 * Why GGL, and why it holds the rotor on the circle (text for docs/theory.md)
 * -------------------------------------------------------------------------
 * The paper differentiates the contact constraint g(q) = 0 (eq. 5) twice and solves the
 * acceleration-level system (eq. 7) for q'' and lambda. That index-1 form only enforces g'' = 0:
 * g and g' are left to drift with the integration error, which grows linearly (g') and
 * quadratically (g) in time; on a test chain at rtol 1e-6 |g|/c^2 reached 5e-2 in 0.5 s, i.e. the
 * rotor sinks into or floats off the retainer it is supposed to roll on. Baumgarte feedback damps
 * the drift but needs tuned gains and changes the dynamics.
 *
 * The Gear-Gupta-Leimkuhler (GGL) form instead keeps the position AND velocity constraints as
 * algebraic equations of the DAE and adds a second multiplier eta so that the system is not
 * over-determined:
 *
 *     q' = v - J^T eta,    M v' = f - J^T lambda,    g(q) = 0,    J v = 0.
 *
 * On the exact solution eta = 0 (differentiate g = 0: J q' = J v - J J^T eta = -|J|^2 eta = 0), so
 * the physics is unchanged; numerically the BDF corrector solves g(q_n) = 0 and J v_n = 0 at every
 * step together with the dynamics, so the constraint holds to the Newton tolerance at every step,
 * whatever the step count, with no drift to accumulate. The price is an index-2 DAE: lambda and
 * eta are algebraic (IDASetId 0) and excluded from the error test (IDASetSuppressAlg), as is usual
 * for index-2 multipliers, and the constraint rows are scaled (divided by -2c) so that lambda is
 * the normal force in N and the row residuals are in m and m/s, comparable with the tolerances
 * of q and v. IDACalcIC is meant for index-1 systems, so consistent lambda and v' are computed
 * here after every mode switch by one KKT solve (td_sim_make_consistent).
 */
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Queue an event of retainer k at s->dae.t with its node velocities at y. */
static void queue_retainer_event(td_sim *s, td_event_kind kind, int k, const double *y)
{
    td_event ev = td_sim_event_at(s, kind, k);
    td_sim_event_velocities(s, k, y, 0, &ev);
    td_sim_queue_event(s, &ev);
}

/* The D term of eq. (13b) of retainer k at y, from the node's velocity relative to the race. */
static double contact_dterm(const td_sim *s, int k, const double *y)
{
    double x, yy, vx, vy;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    return td_contact_constraint_dterm(vx, vy, s->contacts.ret[k].r.clearance);
}

/* The multipliers of the KKT solve at the current modes into s->kkt.active / s->kkt.active_roll: the
 * normal force of every constrained contact, then the friction force F_t of every rolling
 * retainer. For each, its row (s->kkt.rows), M^-1 times its column (s->kkt.minv_cols) and the velocity
 * term of its acceleration-level constraint (rhs): D of eq. (13b), or h of d v_s / dt. */
static int kkt_multipliers(td_sim *s, const double *y, double *rhs)
{
    int m = 0, k;
    for (k = 0; k < s->dae.nr; k++)
        if (s->contacts.ret[k].mode == TD_RMODE_CONTACT) {
            double *z = s->kkt.minv_cols + (size_t)m * s->dae.n;
            td_sim_contact_column(s, k, y, z);
            td_sim_mass_solve(s, z);
            td_sim_contact_row(s, k, y, &s->kkt.rows[m]);
            rhs[m] = contact_dterm(s, k, y);
            s->kkt.active_roll[m] = 0;
            s->kkt.active[m++] = k;
        }
    for (k = 0; k < s->dae.nr; k++)
        if (s->contacts.ret[k].rolling) {
            double *z = s->kkt.minv_cols + (size_t)m * s->dae.n;
            td_sim_roll_column(s, k, y, z);
            td_sim_mass_solve(s, z);
            td_sim_roll_row(s, k, y, &s->kkt.rows[m], &rhs[m]);
            s->kkt.active_roll[m] = 1;
            s->kkt.active[m++] = k;
        }
    return m;
}

/* One KKT solve with the current modes: [M, B; R, 0][v'; x] = [f; -d] by the Schur complement
 * (R M^-1 B) x = R M^-1 f + d (m x m), v' = M^-1 (f - B x), where the multipliers x are the normal
 * forces of the constrained contacts (rows J_k, d = D, eq. 13b) and the friction forces F_t of the
 * rolling retainers (rows d v_s / dv, d = h: the rolling speed held). Fills yp's v block and y's
 * multiplier entries. Returns the number of multipliers, or -1 if singular. */
static int kkt_solve(td_sim *s, double *y, double *yp)
{
    double *a = s->kkt.minv_f, *S = s->kkt.schur, *rhs = s->kkt.schur_rhs, *vp = yp + s->dae.ov;
    int m, i, j;
    td_sim_forces(s, s->dae.t, y, a);
    td_sim_mass_solve(s, a);
    m = kkt_multipliers(s, y, rhs);
    for (i = 0; i < m; i++) {
        const td_contact_row *row = &s->kkt.rows[i];
        for (j = 0; j < m; j++)
            S[i + j * m] = td_contact_row_dot(row, s->kkt.minv_cols + (size_t)j * s->dae.n);
        rhs[i] = td_contact_row_dot(row, a) + rhs[i];
    }
    if (m > 0 && td_contact_dense_solve(m, S, rhs) != 0)
        return -1;
    for (i = 0; i < s->dae.n; i++)
        vp[i] = a[i];
    for (j = 0; j < m; j++) {
        const double *z = s->kkt.minv_cols + (size_t)j * s->dae.n;
        const td_sim_retainer *r = &s->contacts.ret[s->kkt.active[j]];
        for (i = 0; i < s->dae.n; i++)
            vp[i] -= z[i] * rhs[j];
        y[s->kkt.active_roll[j] ? s->dae.of + r->fi : s->dae.ol + s->kkt.active[j]] = rhs[j];
    }
    return m;
}

/* Rolling retainer k at a restart: the residual slip of the root's location is removed; a slip
 * beyond the band (the speed or the state changed under it: a step) ends rolling. */
static void keep_rolling(td_sim *s, int k, double *y)
{
    double vs = td_sim_sliding_velocity(s, k, y);
    if (fabs(vs) <= TD_CONTACT_SLIP_BAND) {
        td_sim_project_rolling(s, k, y);
        return;
    }
    td_sim_unroll(s, k, y, vs > 0.0 ? 1 : -1);
    if (!s->contacts.roll_tried[k])
        queue_retainer_event(s, TD_EVENT_ROLL_END, k, y);
    s->contacts.roll_tried[k] = 0;
}

/* Multipliers of the modes at restart: eta = 0, lambda of free retainers 0 (nodes in contact
 * projected onto their circles: removes the tolerance-level drift at every restart), F_t of the
 * retainers not rolling 0, and the multipliers' rates 0. */
static void reset_multipliers(td_sim *s, double *y, double *yp)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        y[s->dae.ou + k] = 0.0;
        yp[s->dae.ol + k] = yp[s->dae.ou + k] = 0.0;
        if (r->mode != TD_RMODE_CONTACT)
            y[s->dae.ol + k] = 0.0;
        else
            td_sim_project_onto_circle(s, k, y);
        if (r->fi >= 0) {
            yp[s->dae.of + r->fi] = 0.0;
            if (r->rolling)
                keep_rolling(s, k, y);
            if (!r->rolling)
                y[s->dae.of + r->fi] = 0.0;
        }
    }
}

/* The contact that most needs a pulling force (eq. 10 and the text after it: it is released), or
 * -1; one just entered must press (lambda > 0). */
static int worst_pull(const td_sim *s, const double *y, const int *just_entered)
{
    double worst_lam = 0.0;
    int worst = -1, k;
    for (k = 0; k < s->dae.nr; k++) {
        double lam = y[s->dae.ol + k];
        int reject;
        if (s->contacts.ret[k].mode != TD_RMODE_CONTACT)
            continue;
        reject = (just_entered && just_entered[k]) ? !(lam > 0.0) : lam < 0.0;
        if (reject && (worst < 0 || lam < worst_lam)) {
            worst = k;
            worst_lam = lam;
        }
    }
    return worst;
}

/* The rolling retainer whose friction force F_t exceeds mu N the most (it slips), or -1. */
static int worst_slip(const td_sim *s, const double *y)
{
    double worst_excess = 0.0;
    int worst = -1, k;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double excess;
        if (!r->rolling)
            continue;
        excess = fabs(y[s->dae.of + r->fi]) - r->r.friction * td_sim_normal_force(s, k, y);
        if (excess > worst_excess) {
            worst = k;
            worst_excess = excess;
        }
    }
    return worst;
}

/* Retainer k rolled and slips now, in the direction of the force it needed (+: the shaft drags
 * the race forward, v_s > 0): a rolling end, or, for a roll only tried at this instant
 * (s->contacts.roll_tried), a friction reversal if it slips the other way. */
static void slip_from_roll(td_sim *s, int k, double *y)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    int was = r->slip, slip = y[s->dae.of + r->fi] > 0.0 ? 1 : -1;
    td_sim_unroll(s, k, y, slip);
    if (!s->contacts.roll_tried[k])
        queue_retainer_event(s, TD_EVENT_ROLL_END, k, y);
    else if (slip != was)
        queue_retainer_event(s, TD_EVENT_FRICTION_REVERSAL, k, y);
    s->contacts.roll_tried[k] = 0;
}

td_status td_sim_make_consistent(td_sim *s, const int *just_entered)
{
    double *y = N_VGetArrayPointer(s->dae.y), *yp = N_VGetArrayPointer(s->dae.yp);
    int i, k, pass;
    reset_multipliers(s, y, yp);
    for (pass = 0; pass <= s->dae.nr + s->dae.ns; pass++) {
        int worst;
        if (kkt_solve(s, y, yp) < 0) {
            snprintf(s->errmsg, sizeof s->errmsg,
                     "t = %.9g s: the contact constraints are singular (J M^-1 J^T not invertible)", s->dae.t);
            return TD_ERR_NUMERIC;
        }
        if ((worst = worst_pull(s, y, just_entered)) >= 0) {
            td_sim_release(s, worst, y);
            if (!(just_entered && just_entered[worst]))
                queue_retainer_event(s, TD_EVENT_RELEASE, worst, y);
            else /* touched and left at once */
                td_sim_totals_impact(s, worst, 0.0, 1);
        } else if ((worst = worst_slip(s, y)) >= 0) {
            slip_from_roll(s, worst, y);
        } else {
            break;
        }
    }
    for (k = 0; k < s->dae.nr; k++) /* tried rolls that held */
        if (s->contacts.roll_tried[k]) {
            s->contacts.roll_tried[k] = 0;
            if (s->contacts.ret[k].rolling)
                queue_retainer_event(s, TD_EVENT_ROLL_START, k, y);
        }
    /* q' = v, w' = the filter and integrator rates and the linear controllers' */
    for (i = 0; i < s->dae.n; i++)
        yp[s->dae.oq + i] = y[s->dae.ov + i];
    for (k = 0; k < s->sys->n_amb_axes; k++) {
        const td_amb_axis *a = &s->sys->amb_axes[k];
        if (a->state >= 0)
            yp[s->dae.ow + a->state] = td_sim_amb_axis_lag_rate(s, k, y);
        if (a->integral >= 0)
            yp[s->dae.ow + a->integral] = td_sim_amb_axis_integral_rate(s, k, y);
    }
    td_sim_lti_rates(s, y, yp);
    return TD_OK;
}

/*
 * Outward normal acceleration of retainer k's node in free flight at the state y: the second
 * derivative of g = (r^2 - c^2)/(2c) with no contact force, g'' = J M^-1 f + (x'^2 + y'^2)/c
 * (the right-hand side of eq. 13b as the KKT solve forms it; the second term is the centripetal
 * part). Positive: the rotor is pressed onto the retainer. `a` (length n) is overwritten.
 * Forces of the other active contacts are left out: this only sizes the rebound threshold below.
 */
static double free_normal_acceleration(td_sim *s, int k, const double *y, double *a)
{
    td_contact_row row;
    td_sim_forces(s, s->dae.t, y, a);
    td_sim_mass_solve(s, a);
    td_sim_contact_row(s, k, y, &row);
    return td_contact_row_dot(&row, a) + contact_dterm(s, k, y);
}

/*
 * Restitution of an impact at retainer k with inward radial speed vr (> 0): the retainer's e, or
 * 0 (plastic) if the rebound would be too small to be resolved.
 *
 * Why: without this a rotor pressed onto a retainer (by gravity, the unbalance or the AMBs) would
 * bounce for ever. After a bounce the onset root is disarmed until the gap exceeds rearm_eps; a
 * rebound e vr that, against the outward acceleration a_n, rises less than that (apex height
 * (e vr)^2 / (2 a_n)) is only caught when the node has sunk rearm_eps INTO the retainer, and
 * td_sim_project_onto_circle then pushes it back by rearm_eps against
 * the preload, adding about m a_n rearm_eps of strain energy per bounce. That gain balances the
 * (1 - e^2) kinetic loss at a rebound speed ~ sqrt(2 a_n rearm_eps), so the rebounds never
 * decayed (median 5e-3 / 1.5e-3 / 4.6e-4 m/s at atol 1e-8 / 1e-9 / 1e-10). A bouncing ball on
 * a pressed wall is a Zeno sequence: speeds e^j v0, total time 2 e v0 / (a_n (1 - e)), finite,
 * after which it rests in contact. Ending the sequence once the next apex would be below
 * 4 rearm_eps, i.e. e vr < 2 sqrt(2 a_n rearm_eps), is that physics truncated at the event
 * resolution: every bounce that is still resolved re-arms at the gap and is caught at gap = 0
 * (no penetration, no energy injected), and the kinetic energy discarded at the last one,
 * (1/2) m (e vr)^2 < 4 m a_n rearm_eps, is of the order of the work of the displacement tolerance.
 * The factor 2 (not 1) leaves margin for a_n changing along the flight (the unbalance force turns,
 * the AMB force follows the node). Re-arming at gap = 0 instead would let the rounding-level gap
 * of a just-projected node trigger onsets at once (the reason for the hysteresis), and projecting
 * the whole rotor with M^-1 J^T would still leave the late detection. Rebounds slower than
 * rebound_min are plastic whatever a_n (a scale-based floor for a_n <= 0: pulled away, the node
 * leaves and re-arms by itself). e = 0 never reaches here, so plastic runs are unchanged.
 */
static double impact_restitution(td_sim *s, int k, const double *y, double vr)
{
    double e = s->contacts.ret[k].r.restitution, an, vmin;
    if (!(e > 0.0) || vr < s->machine.rebound_min)
        return 0.0;
    an = free_normal_acceleration(s, k, y, s->kkt.minv_f);
    vmin = an > 0.0 ? 2.0 * sqrt(2.0 * an * s->machine.rearm_eps) : 0.0;
    return e * vr < vmin ? 0.0 : e;
}

/* The contacts of an impact at the retainers flagged in `onset`, into s->kkt.active with their
 * restitution in s->kkt.restitution: every active contact (e = 0 keeps it on the circle) and each
 * onset moving outward (impact_restitution). Returns their number. */
static int impact_contacts(td_sim *s, const int *onset, const double *y)
{
    double *e = s->kkt.restitution;
    int m = 0, k;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double x, yy, vx, vy, vr;
        if (r->mode == TD_RMODE_CONTACT) {
            e[m] = 0.0;
            s->kkt.active[m++] = k;
        } else if (onset[k]) {
            td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
            vr = td_contact_radial_velocity(x, yy, vx, vy);
            if (!(vr > 0.0)) /* touching while already moving inward: no impact, stay free */
                continue;
            e[m] = impact_restitution(s, k, y, vr);
            s->kkt.active[m++] = k;
        }
    }
    return m;
}

/* Rows J_k (s->kkt.rows) and columns M^-1 J_k^T (s->kkt.minv_cols) of the first m contacts in
 * s->kkt.active. */
static void impact_columns(td_sim *s, int m, const double *y)
{
    int i;
    for (i = 0; i < m; i++) {
        double *col = s->kkt.minv_cols + (size_t)i * s->dae.n;
        td_sim_contact_row(s, s->kkt.active[i], y, &s->kkt.rows[i]);
        memset(col, 0, sizeof(double) * (size_t)s->dae.n);
        td_contact_row_scatter(&s->kkt.rows[i], col);
        td_sim_mass_solve(s, col);
    }
}

/* Queue the onset event of every new contact among the first m in s->kkt.active, with the
 * velocities before the impact. Returns how many. */
static int queue_onsets(td_sim *s, const int *onset, int m, const double *y)
{
    int i, k, queued = 0;
    for (i = 0; i < m; i++) {
        k = s->kkt.active[i];
        if (!onset[k] || s->contacts.ret[k].mode == TD_RMODE_CONTACT)
            continue;
        {
            td_event ev = td_sim_event_at(s, TD_EVENT_CONTACT_ONSET, k);
            td_sim_event_velocities(s, k, y, 0, &ev);
            td_sim_queue_event(s, &ev);
            queued++;
        }
    }
    return queued;
}

/* After the impact map: new contacts with e = 0 become CONTACT (tentatively: the KKT solve may
 * still reject them), flagged in entered; bouncing ones stay free, disarmed until the gap opens. */
static void enter_contacts(td_sim *s, const int *onset, int m, const double *y, int *entered)
{
    int i, k;
    for (i = 0; i < m; i++) {
        td_sim_retainer *r;
        k = s->kkt.active[i];
        r = &s->contacts.ret[k];
        if (!onset[k] || r->mode == TD_RMODE_CONTACT)
            continue;
        if (s->kkt.restitution[i] > 0.0) {
            r->armed = 0; /* bounced: free until the gap has opened */
        } else {
            r->mode = TD_RMODE_CONTACT;
            td_sim_init_slip(s, k, y);
            entered[k] = 1;
        }
    }
}

/* Complete the onset events queued from first_event on (in queue order = retainer order) with
 * the velocities after the impact and its impulse. */
static void complete_onsets(td_sim *s, const int *onset, int m, int first_event, const double *y)
{
    int i, k, q;
    for (i = 0; i < m; i++) {
        k = s->kkt.active[i];
        if (!onset[k])
            continue;
        for (q = first_event; q < s->monitor.q_len; q++)
            if (s->monitor.queue[q].retainer == k && s->monitor.queue[q].kind == TD_EVENT_CONTACT_ONSET) {
                td_sim_event_velocities(s, k, y, 1, &s->monitor.queue[q]);
                s->monitor.queue[q].impulse = s->kkt.impulse[i];
            }
    }
}

/* An impact jolts every contact: rolling retainers slip (the impact map is frictionless, so their
 * v_s is no longer held) and try rolling again when v_s next reaches 0. */
static void stop_rolling(td_sim *s, double *y)
{
    int k;
    for (k = 0; k < s->dae.nr; k++)
        if (s->contacts.ret[k].rolling) {
            td_sim_unroll(s, k, y, s->contacts.ret[k].slip);
            queue_retainer_event(s, TD_EVENT_ROLL_END, k, y);
        }
}

/*
 * Impacts at the retainers flagged in `onset` (constraint model): project each node onto its
 * circle, apply the impact map with every contact already active and the new ones
 * (impact_contacts), queue the onset events. entered[k] flags the retainers that came into
 * contact. Returns the number of onset events queued, -1 if the impact map is singular.
 */
static int impacts(td_sim *s, const int *onset, int *entered)
{
    double *y = N_VGetArrayPointer(s->dae.y), before;
    int m, k, queued, first_event = s->monitor.q_len;
    for (k = 0; k < s->dae.nr; k++) {
        entered[k] = 0;
        if (onset[k])
            td_sim_project_onto_circle(s, k, y);
    }
    stop_rolling(s, y);
    m = impact_contacts(s, onset, y);
    impact_columns(s, m, y);
    queued = queue_onsets(s, onset, m, y);
    before = s->opt.energy ? td_sim_kinetic_energy(s, y) : 0.0;
    if (m > 0 && td_contact_impact_map(s->dae.n, m, s->kkt.rows, s->kkt.minv_cols, s->kkt.restitution, y + s->dae.ov,
                                       s->kkt.impulse, s->kkt.impact_work) != 0)
        return -1;
    if (s->opt.energy)
        td_sim_energy_impact(s, before, td_sim_kinetic_energy(s, y));
    for (k = 0; k < m; k++) /* every contact of the impact took its impulse; e > 0 onsets bounced */
        td_sim_totals_impact(s, s->kkt.active[k], s->kkt.impulse[k],
                             onset[s->kkt.active[k]] && s->contacts.ret[s->kkt.active[k]].mode != TD_RMODE_CONTACT &&
                                 s->kkt.restitution[k] > 0.0);
    enter_contacts(s, onset, m, y, entered);
    for (k = 0; k < s->dae.nr; k++) /* stick retainers slide the way the impact left them */
        if (s->contacts.ret[k].r.stick && s->contacts.ret[k].mode == TD_RMODE_CONTACT && !entered[k])
            td_sim_init_slip(s, k, y);
    complete_onsets(s, onset, m, first_event, y);
    /* onsets with no outward velocity: disarm, nothing happened */
    for (k = 0; k < s->dae.nr; k++)
        if (onset[k] && s->contacts.ret[k].mode == TD_RMODE_FREE)
            s->contacts.ret[k].armed = 0;
    return queued;
}

/* A stick retainer sliding against its slip direction: its v_s = 0 root was never crossed (it left
 * a restart at v_s = 0 the other way, e.g. when rolling ended with F_t ~ 0 as N vanished). */
static int stick_out_of_step(const td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    return r->r.stick && r->mode != TD_RMODE_FREE && !r->rolling &&
           r->slip * td_sim_sliding_velocity(s, k, y) < -TD_CONTACT_SLIP_BAND;
}

int td_sim_modes_out_of_step(const td_sim *s, const double *y)
{
    int k;
    for (k = 0; k < s->dae.nr; k++)
        if ((td_sim_penalty_model(s, k) &&
             td_sim_penalty_mode_wanted(s, k, y, s->contacts.ret[k].mode) != s->contacts.ret[k].mode) ||
            stick_out_of_step(s, k, y))
            return 1;
    return 0;
}

/* Penalty model: put retainer k in mode `want`, queueing the enter or exit event. Returns 1 if
 * the mode changed. */
static int penalty_switch(td_sim *s, int k, double *y, td_rmode want)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    if (want == r->mode)
        return 0;
    r->mode = want;
    if (want == TD_RMODE_PENETRATING) {
        td_sim_init_slip(s, k, y);
        queue_retainer_event(s, TD_EVENT_PENALTY_ENTER, k, y);
    } else {
        r->armed = 0; /* left at gap = 0: the flight waits until the gap has opened (grazing guard) */
        td_sim_unroll(s, k, y, r->slip);
        queue_retainer_event(s, TD_EVENT_PENALTY_EXIT, k, y);
    }
    return 1;
}

/* Retainer k's slip root (|v_s| reached v_reg): the friction law has a kink there
 * (docs/theory.md), so the integrator restarts; leaving the band on the other side is a
 * friction reversal. A stick retainer's root is v_s = 0 while sliding (it tries rolling: the
 * consistent restart keeps it if the friction force rolling needs is within mu N, else it slips
 * on, the way that force points) or |F_t| = mu N while rolling (it slips). */
static void slip_root(td_sim *s, int k, double *y)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    if (!r->r.stick) {
        if (td_sim_slip_root(s, k, y))
            queue_retainer_event(s, TD_EVENT_FRICTION_REVERSAL, k, y);
    } else if (r->rolling) {
        td_sim_unroll(s, k, y, y[s->dae.of + r->fi] > 0.0 ? 1 : -1);
        queue_retainer_event(s, TD_EVENT_ROLL_END, k, y);
    } else {
        r->rolling = 1;
        s->contacts.roll_tried[k] = 1;
    }
}

/* Constraint model: the roots `f` of retainer k. An onset root only flags the retainer in *onset
 * (the impacts come after every retainer's roots); a release root frees it at once. Returns 1 if
 * the integrator must restart. */
static int constraint_roots(td_sim *s, int k, double *y, const int *f, int *onset)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    int restart = 0;
    if (f[TD_ROOT_CONTACT] != 0) {
        if (r->mode == TD_RMODE_FREE) {
            *onset = 1;
        } else if (r->mode == TD_RMODE_CONTACT) {
            td_sim_release(s, k, y);
            queue_retainer_event(s, TD_EVENT_RELEASE, k, y);
            restart = 1;
        }
    } else if (f[TD_ROOT_SLIP] != 0 && r->mode != TD_RMODE_FREE) {
        slip_root(s, k, y);
        restart = 1;
    }
    if (f[TD_ROOT_REARM] != 0 && r->mode == TD_RMODE_FREE && !r->armed)
        r->armed = 1; /* internal: only the root function changes (IDA re-evaluates it at tlo) */
    return restart;
}

/* Penalty model: the roots `f` of retainer k (all zero: only bring its mode in step with the
 * state). A contact root asks for the flip of the mode; the state decides outside the noise band
 * (retainer.c td_sim_penalty_mode_wanted). Returns 1 if the integrator must restart. */
static int penalty_roots(td_sim *s, int k, double *y, const int *f)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    int restart = 0;
    td_rmode flip, in_band;
    if (f[TD_ROOT_CONTACT] == 0 && f[TD_ROOT_SLIP] != 0 && r->mode != TD_RMODE_FREE) {
        slip_root(s, k, y);
        restart = 1;
    }
    flip = r->mode == TD_RMODE_FREE ? TD_RMODE_PENETRATING : TD_RMODE_FREE;
    in_band = f[TD_ROOT_CONTACT] != 0 ? flip : r->mode;
    if (penalty_switch(s, k, y, td_sim_penalty_mode_wanted(s, k, y, in_band)))
        restart = 1;
    if (f[TD_ROOT_REARM] != 0 && r->mode == TD_RMODE_FREE && !r->armed)
        r->armed = 1; /* internal, as in constraint_roots */
    return restart;
}

/* Impacts at the retainers flagged in s->kkt.onset (any: some are), or none; s->kkt.entered says which
 * retainers came into contact. */
static td_status onset_impacts(td_sim *s, int any)
{
    int k;
    if (!any) {
        for (k = 0; k < s->dae.nr; k++)
            s->kkt.entered[k] = 0;
        return TD_OK;
    }
    if (impacts(s, s->kkt.onset, s->kkt.entered) < 0) {
        snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: impact map singular", s->dae.t);
        return TD_ERR_NUMERIC;
    }
    return TD_OK;
}

td_status td_sim_handle_roots(td_sim *s, int *restart)
{
    double *y = N_VGetArrayPointer(s->dae.y);
    int k, any_onset = 0, first_event = s->monitor.q_len;
    td_status st;
    *restart = 0;
    for (k = 0; k < s->dae.nr; k++) {
        const int *f = s->dae.rootsfound + TD_ROOTS_PER_RETAINER * k;
        s->kkt.onset[k] = 0;
        if (td_sim_penalty_model(s, k) ? penalty_roots(s, k, y, f) : constraint_roots(s, k, y, f, &s->kkt.onset[k]))
            *restart = 1;
        if (stick_out_of_step(s, k, y)) { /* the missed crossing: the restart rolls or slips the right way */
            slip_root(s, k, y);
            *restart = 1;
        }
        any_onset = any_onset || s->kkt.onset[k];
    }
    for (k = 0; k < s->dae.n_sat_roots; k++) /* an AMB's clip: restart on its kink */
        if (s->dae.rootsfound[TD_ROOTS_PER_RETAINER * s->dae.nr + k])
            *restart = 1;
    st = onset_impacts(s, any_onset);
    if (st != TD_OK)
        return st;
    if (any_onset)
        *restart = 1;
    if (!*restart)
        return TD_OK;
    st = td_sim_make_consistent(s, s->kkt.entered);
    if (st != TD_OK)
        return st;
    /* record the normal force right after each event of this instant */
    for (k = first_event; k < s->monitor.q_len; k++)
        if (s->monitor.queue[k].retainer >= 0)
            s->monitor.queue[k].normal_force = td_sim_normal_force(s, s->monitor.queue[k].retainer, y);
    return TD_OK;
}

td_status td_sim_start_contacts(td_sim *s, const int *touching)
{
    int k, any = 0;
    td_status st;
    for (k = 0; k < s->dae.nr; k++) {
        s->kkt.onset[k] = touching[k];
        any = any || s->kkt.onset[k];
    }
    st = onset_impacts(s, any);
    return st == TD_OK ? td_sim_make_consistent(s, s->kkt.entered) : st;
}
