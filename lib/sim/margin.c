/*
 * clearance margin: each retainer's smallest clearance - r over the run (touchdown/records.h
 * td_retainer_totals.min_clearance_margin), r the node's radius from the race centre.
 *
 * It is kept at the points of the totals (totals.c td_sim_totals_point). Between two points the
 * radius is the cubic Hermite through r and dr/dt at both ends, and its largest value counts: an
 * orbit that comes near the clearance between the integrator's points (a near miss) is not lost. The
 * segment to a point the monitor holds (an integrator step's end beyond the output time) counts only
 * up to the time reached: the margin at an output time is the margin up to it. A segment the
 * closed-form flight covered has been searched by the flight itself (flight.c), which notes its
 * values here (td_sim_margin_note).
 */
#include "sim/sim_internal.h"

#include <math.h>

/* Retainer k's node at y as a point at time t. */
static td_sim_margin_sample point_at(const td_sim *s, int k, double t, const double *y)
{
    td_sim_margin_sample p;
    double x, yy, vx, vy;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    p.t = t;
    p.r = hypot(x, yy);
    p.v = td_contact_radial_velocity(x, yy, vx, vy);
    return p;
}

/* The cubic Hermite through (a.r, a.v) at a.t and (b.r, b.v) at b.t, at s = (t - a.t) / h. */
static double hermite(const td_sim_margin_sample *a, const td_sim_margin_sample *b, double s)
{
    double h = b->t - a->t, s2 = s * s, s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * a->r + (s3 - 2.0 * s2 + s) * h * a->v + (3.0 * s2 - 2.0 * s3) * b->r +
           (s3 - s2) * h * b->v;
}

/* The largest radius of the Hermite from a to b over [a.t, min(b.t, t_end)]: its value there and at
 * its stationary points inside (the roots of its derivative, a quadratic in s). */
static double hermite_max(const td_sim_margin_sample *a, const td_sim_margin_sample *b, double t_end)
{
    double h = b->t - a->t, s_end, best, qa, qb, qc, disc, roots[2];
    int i, n = 0;
    if (!(h > 0.0))
        return a->r;
    s_end = t_end >= b->t ? 1.0 : (t_end - a->t) / h;
    if (!(s_end > 0.0))
        return a->r;
    best = fmax(a->r, hermite(a, b, s_end));
    /* H'(s) = qa s^2 + qb s + qc */
    qa = 6.0 * (a->r - b->r) + 3.0 * h * (a->v + b->v);
    qb = 6.0 * (b->r - a->r) - h * (4.0 * a->v + 2.0 * b->v);
    qc = h * a->v;
    if (qa == 0.0) {
        if (qb != 0.0)
            roots[n++] = -qc / qb;
    } else if ((disc = qb * qb - 4.0 * qa * qc) >= 0.0) {
        double q = -0.5 * (qb + copysign(sqrt(disc), qb)); /* without cancellation */
        roots[n++] = q / qa;
        if (q != 0.0)
            roots[n++] = qc / q;
    }
    for (i = 0; i < n; i++)
        if (roots[i] > 0.0 && roots[i] < s_end)
            best = fmax(best, hermite(a, b, roots[i]));
    return best;
}

/* 0 if the Hermite from a to b cannot come nearer retainer k's clearance than its margin so far: on
 * [0, 1] its basis functions hold h00 + h01 = 1 (both >= 0), 0 <= h10 <= 4/27, -4/27 <= h11 <= 0, so
 * it stays below max(a.r, b.r) + 4/27 h (|a.v| + |b.v|), evaluated within 2^-40 of its terms' sizes
 * (a few ulps). */
static int may_come_nearer(const td_sim *s, int k, const td_sim_margin_sample *a, const td_sim_margin_sample *b)
{
    double dv = fabs(b->t - a->t) * (fabs(a->v) + fabs(b->v));
    double top = fmax(a->r, b->r) + (4.0 / 27.0) * dv + 0x1p-40 * (fabs(a->r) + fabs(b->r) + dv);
    return !(s->contacts.ret[k].r.clearance - top >= s->monitor.totals[k].margin);
}

void td_sim_margin_start(td_sim *s)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        s->monitor.totals[k].margin = INFINITY;
        s->monitor.totals[k].m_last.t = INFINITY; /* the first point has nothing before it */
        s->monitor.totals[k].m_held = 0;
    }
    s->monitor.margin_flown = 0;
}

void td_sim_margin_note(td_sim *s, int k, double r)
{
    td_sim_totals *tk = &s->monitor.totals[k];
    tk->margin = fmin(tk->margin, s->contacts.ret[k].r.clearance - r);
}

/* Retainer k's held segment counted whole (the run has reached its end). */
static void settle_held(td_sim *s, int k)
{
    td_sim_totals *tk = &s->monitor.totals[k];
    if (!tk->m_held)
        return;
    td_sim_margin_note(s, k, hermite_max(&tk->m_from, &tk->m_to, tk->m_to.t));
    tk->m_held = 0;
}

void td_sim_margin_point(td_sim *s, double t)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    int held = s->monitor.ahead && s->monitor.ahead_t == t, k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        td_sim_margin_sample now = point_at(s, k, t, y);
        if (tk->m_held && t >= tk->m_to.t)
            settle_held(s, k);
        if (t > tk->m_last.t && !s->monitor.margin_flown) {
            if (held) { /* counts as the run reaches it (td_sim_margin_get, td_sim_margin_rewind) */
                tk->m_from = tk->m_last;
                tk->m_to = now;
                tk->m_held = 1;
            } else if (may_come_nearer(s, k, &tk->m_last, &now)) {
                td_sim_margin_note(s, k, hermite_max(&tk->m_last, &now, t));
            }
        } else if (!held) {
            td_sim_margin_note(s, k, now.r);
        }
        tk->m_last = now;
    }
    s->monitor.margin_flown = 0;
}

void td_sim_margin_rewind(td_sim *s)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_totals *tk = &s->monitor.totals[k];
        if (!tk->m_held)
            continue;
        if (s->dae.t >= tk->m_to.t) {
            settle_held(s, k);
            continue;
        }
        td_sim_margin_note(s, k, hermite_max(&tk->m_from, &tk->m_to, s->dae.t));
        tk->m_held = 0;
        tk->m_last = point_at(s, k, s->dae.t, y);
    }
}

double td_sim_margin_get(const td_sim *s, int k)
{
    const td_sim_totals *tk = &s->monitor.totals[k];
    double m = tk->margin;
    if (tk->m_held)
        m = fmin(m, s->contacts.ret[k].r.clearance - hermite_max(&tk->m_from, &tk->m_to, s->dae.t));
    return m;
}
