/*
 * The closed-form free flight's next root (flight_internal.h): a step that cannot pass a root of
 * any retainer's root functions, from the bounds of the modal sum (flight_modal.c).
 */
#include "sim/flight_internal.h"

#include <complex.h>
#include <math.h>
#include <string.h>

/* The largest tau for which G + G' tau - B tau^2 / 2 > 0 (G > 0): no root of a function with
 * G'' >= -B before it; 0 if G <= 0. */
static double safe_step(double g, double dg, double bound)
{
    double sq;
    if (g <= 0.0)
        return 0.0;
    if (bound <= 0.0)
        return dg < 0.0 ? g / -dg : INFINITY;
    sq = sqrt(dg * dg + 2.0 * bound * g);
    return 2.0 * g / (sq - dg); /* (dg + sq) / bound without its cancellation */
}

/* 1 if sign (R2 - |p|^2) of retainer k's node is negative a little after t, by twice the Newton
 * estimate `newton` of the time to the root (and at least FLIGHT_ROOT_TOL): the function crosses
 * there, it does not only graze its root. Leaves f->e at t + that. */
static int crosses(td_sim_flight *f, int k, double t, double R2, double sign, double newton)
{
    double t2 = t + fmax(2.0 * newton, FLIGHT_ROOT_TOL);
    flight_val x, y;
    td_sim_flight_propagate(f, t2);
    x = td_sim_flight_observe(f, 2 * k, t2);
    y = td_sim_flight_observe(f, 2 * k + 1, t2);
    return sign * (R2 - (x.v * x.v + y.v * y.v)) < 0.0;
}

/* 1 if a root function g, falling at the rate `closing` (g' = -closing) with |g''| <= bound, is
 * below zero FLIGHT_ROOT_TOL from now whatever its curvature: g - closing tau + bound tau^2 / 2 < 0
 * at tau = FLIGHT_ROOT_TOL. (Also when g is already at or below zero, a rounding error past the
 * root, and moving on.) */
static int surely_crossed(double g, double closing, double bound)
{
    double tau = FLIGHT_ROOT_TOL;
    return g - closing * tau + 0.5 * bound * tau * tau < 0.0;
}

/*
 * The node inside radius R until F(tau) = R - m - a tau^2 / 2 - |p + v tau| reaches zero. F is
 * concave: one crossing, which the step takes as the lower end of a 30-step bisection of [0, hi]
 * (a 2^-30 of the longest step hi). The bisection's result is reproduced bit for bit with a few
 * evaluations (td_sim_flight_inside_until): the crossing located by Newton's method, each level of
 * the bisection decided without evaluating F where the sign of F as computed is proven, evaluated
 * with the same expression where it is not.
 *
 * The proof: F as computed is within E(tau) = e0 + e1 tau + e2 tau^2 of the exact F (below). F - E
 * and F + E are concave (E's tau^2 coefficient is far below a / 2). Where F - E > 0 at 0 and at t,
 * it is positive on [0, t], so the computed F is positive there; where F + E < 0 at t (F + E is
 * positive at 0 when the computed F(0) is), it is negative from t on, and so is the computed F.
 * Either holds at t when the computed F there is beyond 2 E(t) (one E for its own rounding).
 *
 * The bound: in IEEE 754 double precision (unit roundoff u = 2^-53) with |p + v tau| rounded by
 * hypot within an ulp, the computed F is within u (3 (R + m) + 2 a tau^2 + 4 |p|_1 + 5 |v|_1 tau)
 * (to first order in u) of the exact F for the computed (R, m, a, p, v) and tau; E takes 256 u
 * times (R + m + |p|_1 + |v|_1 tau + a tau^2 / 2), and 1e-300 for an underflow.
 */
typedef struct inside_fn {
    double R, m, a, p[2], v[2];
    double e0, e1, e2;   /* E(tau) = e0 + e1 tau + e2 tau^2 */
    double t_pos, t_neg; /* proven: computed F > 0 on [0, t_pos] (nothing if t_pos < 0), < 0 on [t_neg, inf) */
} inside_fn;

#define INSIDE_ERR 0x1p-45 /* 256 u */

static inside_fn inside_make(double R, double m, double a, const double p[2], const double v[2])
{
    inside_fn g;
    g.R = R, g.m = m, g.a = a;
    g.p[0] = p[0], g.p[1] = p[1], g.v[0] = v[0], g.v[1] = v[1];
    g.e0 = INSIDE_ERR * (fabs(R) + fabs(m) + fabs(p[0]) + fabs(p[1])) + 1e-300;
    g.e1 = INSIDE_ERR * (fabs(v[0]) + fabs(v[1]));
    g.e2 = INSIDE_ERR * 0.5 * fabs(a);
    g.t_pos = -1.0;
    g.t_neg = INFINITY;
    return g;
}

/* F(tau) as computed: the one expression both searches evaluate; x, y = p + v tau and its length
 * into q (may be NULL) */
static double inside_value(const inside_fn *g, double tau, double q[3])
{
    double x = g->p[0] + g->v[0] * tau, y = g->p[1] + g->v[1] * tau, h = hypot(x, y);
    if (q)
        q[0] = x, q[1] = y, q[2] = h;
    return g->R - g->m - 0.5 * g->a * tau * tau - h;
}

/* F(tau) as computed, its slope into *slope (NaN where |p + v tau| = 0; may be NULL), and what its
 * sign proves (inside_fn.t_pos, t_neg; t_pos only once F(0) was proven positive: t_pos = 0) */
static double inside_eval(inside_fn *g, double tau, double *slope)
{
    double q[3], f = inside_value(g, tau, q), e = 2.0 * (g->e0 + tau * (g->e1 + tau * g->e2));
    if (slope)
        *slope = q[2] > 0.0 ? -g->a * tau - (q[0] * g->v[0] + q[1] * g->v[1]) / q[2] : NAN;
    if (f > e && g->t_pos >= 0.0 && tau > g->t_pos)
        g->t_pos = tau;
    else if (f < -e && tau < g->t_neg)
        g->t_neg = tau;
    return f;
}

double td_sim_flight_inside_bisect(double R, double m, double a, const double p[2], const double v[2], double hi)
{
    inside_fn g = inside_make(R, m, a, p, v);
    double lo = 0.0;
    int i;
    if (inside_value(&g, 0.0, NULL) <= 0.0)
        return 0.0;
    if (inside_value(&g, hi, NULL) > 0.0)
        return hi;
    for (i = 0; i < 30; i++) {
        double mid = 0.5 * (lo + hi);
        if (inside_value(&g, mid, NULL) > 0.0)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The crossing on [0, hi] as a start for Newton's method (F(0) = f0 > 0): |p + v tau| >= |p| + s tau
 * (s = v . p / |p|: the length is convex, above its tangent at 0), so F <= f0 - s tau - a tau^2 / 2,
 * whose root lies at or past the crossing (hi if it has none before). */
static double inside_start(const inside_fn *g, double f0, double hi)
{
    double pn = hypot(g->p[0], g->p[1]), vn = hypot(g->v[0], g->v[1]);
    double s = pn > 0.0 ? (g->p[0] * g->v[0] + g->p[1] * g->v[1]) / pn : -vn, q = s * s + 2.0 * g->a * f0;
    if (q >= 0.0 && s + sqrt(q) > 0.0)
        return fmin(hi, 2.0 * f0 / (s + sqrt(q)));
    return hi;
}

/* The signs of F proven around its crossing on [0, hi] (F(0) = f0 > 0), to within a quarter of the
 * bisection's last interval on each side where F is not flat there; 0 if F(hi) > 0 as computed (the
 * bisection's answer is hi). Newton's method from above: F is concave, so its tangent's root lies at
 * or past the crossing. */
static int inside_locate(inside_fn *g, double f0, double hi)
{
    double lo = 0.0, up = hi, cell = hi * 0x1p-32, t = inside_start(g, f0, hi), f, d, fu = 0.0, du = NAN;
    int it;
    if (t < hi) {
        f = inside_eval(g, t, &d);
        if (f > 0.0)
            lo = t;
        else
            up = t, fu = f, du = d;
    }
    if (g->t_neg > hi) { /* not proven at hi: the bisection's own test there */
        f = inside_eval(g, hi, &d);
        if (f > 0.0)
            return 0;
        if (up == hi)
            fu = f, du = d;
    }
    t = up;
    for (it = 0; it < 16 && up - lo > cell; it++) {
        t = up - fu / du;
        if (du < 0.0 && up - t < cell)
            break;
        if (!(du < 0.0 && t > lo && t < up))
            t = 0.5 * (lo + up);
        f = inside_eval(g, t, &d);
        if (f > 0.0)
            lo = t;
        else
            up = t, fu = f, du = d;
    }
    if (t - cell > g->t_pos)
        inside_eval(g, t - cell, NULL);
    if (t + cell < g->t_neg)
        inside_eval(g, t + cell, NULL);
    return 1;
}

double td_sim_flight_inside_until(double R, double m, double a, const double p[2], const double v[2], double hi)
{
    inside_fn g = inside_make(R, m, a, p, v);
    double f0, lo = 0.0, up = hi;
    int i;
    if (!(hi > 0.0) || !(a >= 0.0) || !isfinite(g.e0 + hi * (g.e1 + hi * g.e2))) /* (F concave: a >= 0) */
        return td_sim_flight_inside_bisect(R, m, a, p, v, hi);
    f0 = inside_eval(&g, 0.0, NULL);
    if (f0 <= 0.0)
        return 0.0;
    if (!isfinite(f0))
        return td_sim_flight_inside_bisect(R, m, a, p, v, hi);
    if (f0 > 2.0 * g.e0)
        g.t_pos = 0.0;
    if (!inside_locate(&g, f0, hi))
        return hi;
    for (i = 0; i < 30; i++) { /* the bisection, its levels decided where proven */
        double mid = 0.5 * (lo + up);
        if (mid <= g.t_pos || (mid < g.t_neg && inside_eval(&g, mid, NULL) > 0.0))
            lo = mid;
        else
            up = mid;
    }
    return lo;
}

int td_sim_flight_outside_from(double R, double m, double a, const double p[2], const double v[2], double t)
{
    inside_fn g = inside_make(R, m, a, p, v);
    if (!(t >= 0.0) || !(a >= 0.0) || !isfinite(g.e0 + t * (g.e1 + t * g.e2)))
        return 0;
    inside_eval(&g, t, NULL);
    return g.t_neg <= t;
}

/* splits of the modal sum tried by split_step */
#define FLIGHT_SPLITS 8

/*
 * A safe step inside radius R for retainer k's node (at the last propagate, time t) from the modal
 * sum split by frequency: the modes above the split bounded by their amplitudes m (they ring, but
 * never further out than that), the slower ones and the forcing by a Taylor expansion with their
 * acceleration bound a: |p(t + tau)| <= |p_s + p_s' tau| + a tau^2 / 2 + m. Near the clearance the
 * ringing 11-13 kHz modes make the acceleration bound of the whole sum (retainer_roots) large and
 * its step short; each split is a bound, the best is taken.
 */
static double split_step(const td_sim_flight *f, int k, double t, double R)
{
    const flight_obs *o[2] = {&f->obs[2 * k], &f->obs[2 * k + 1]};
    double complex ep = td_sim_flight_phase(f, t);
    double p[2], v[2], a[2], m[2] = {0.0, 0.0}, best = 0.0, w = f->omega;
    int c, i = 0, stride = f->nkeep / FLIGHT_SPLITS + 1;
    for (c = 0; c < 2; c++) { /* start: the forcing slow, every mode fast */
        p[c] = creal(o[c]->h0 + o[c]->hp * ep + o[c]->hm * conj(ep));
        v[c] = creal(I * w * (o[c]->hp * ep - o[c]->hm * conj(ep)));
        a[c] = w * w * o[c]->h_abs;
        for (i = 0; i < f->nkeep; i++)
            m[c] += o[c]->m0[f->keep[i]] * f->ae[f->keep[i]];
    }
    for (i = 0; i <= f->nkeep; i++) {
        int j;
        if (i % stride == 0 || i == f->nkeep) {
            double mi = hypot(fmax(m[0], 0.0), fmax(m[1], 0.0)), ai = hypot(a[0], a[1]);
            /* a split that cannot beat the best so far is not searched: its step is at most that */
            if (!(best > 0.0 && td_sim_flight_outside_from(R, mi, ai, p, v, best)))
                best = fmax(best, td_sim_flight_inside_until(R, mi, ai, p, v, f->h_max));
        }
        if (i == f->nkeep || best >= f->h_max) /* no split beats the longest step */
            break;
        j = f->order[i]; /* mode j joins the slow side */
        for (c = 0; c < 2; c++) {
            double ce[2];
            flight_mul(o[c]->c[j], f->e[j], ce);
            p[c] += ce[0];
            v[c] += ce[0] * creal(f->lam[j]) - ce[1] * cimag(f->lam[j]);
            a[c] += o[c]->m2[j] * f->ae[j];
            m[c] -= o[c]->m0[j] * f->ae[j];
        }
    }
    return best;
}

double td_sim_flight_node(const td_sim_flight *f, int k, double t, flight_val *x, flight_val *y)
{
    flight_obs *ox = &f->obs[2 * k], *oy = &f->obs[2 * k + 1];
    double p, v, a;
    td_sim_flight_observe2(f, 2 * k, 2 * k + 1, t, x, y);
    if (!isnan(ox->seen_bound) && ox->seen_bound == oy->seen_bound) /* both kept from this t */
        return ox->seen_bound;
    p = hypot(x->b0, y->b0), v = hypot(x->b1, y->b1), a = hypot(x->b2, y->b2);
    ox->seen_bound = oy->seen_bound = 2.0 * (v * v + p * a);
    return ox->seen_bound;
}

/* Retainer k's root functions at the last propagate (time t): the safe step to each (contact,
 * rearm: INFINITY where there is none) and whether each is converged on its root: within
 * FLIGHT_ROOT_TOL of it and crossing it: surely by the bound on its curvature, else as evaluated
 * FLIGHT_ROOT_TOL ahead (a graze that turns back before its root is no contact). The bound matters
 * for a slow approach: the safe steps creep up to the root and may stop a rounding error short of
 * it or beyond it, where the evaluation ahead is itself at the rounding level; missed there, the
 * flight hands over to IDA with the root behind IDA's restart, and the node passes through the
 * retainer unseen. The contact's step is exact below `cap` (the step is at most that already: the
 * other retainers' and the longest), and at least cap where it is not (no split is searched then). */
static void retainer_roots(const td_sim *s, td_sim_flight *f, int k, double t, double cap, double tau[2], int hit[2])
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    flight_val x, y;
    double bound = td_sim_flight_node(f, k, t, &x, &y);
    double c = r->r.clearance, r2 = x.v * x.v + y.v * y.v, dr2 = 2.0 * (x.v * x.d + y.v * y.d);
    /* the radii of td_sim_roots' functions: gap + off = 0 (contact), gap - eps = 0 (rearm) */
    double contact2 = c * c + (r->armed ? 0.0 : 2.0 * c * s->machine.rearm_eps);
    double rearm2 = c * c - 2.0 * c * s->machine.rearm_eps;
    tau[0] = safe_step(contact2 - r2, -dr2, bound);
    hit[0] = tau[0] < FLIGHT_ROOT_TOL && dr2 > 0.0 &&
             (surely_crossed(contact2 - r2, dr2, bound) || crosses(f, k, t, contact2, 1.0, (contact2 - r2) / dr2));
    if (!hit[0] && !(tau[0] >= cap)) { /* a longer step is not taken */
        td_sim_flight_propagate(f, t); /* crosses() may have moved it */
        tau[0] = fmax(tau[0], split_step(f, k, t, sqrt(contact2)));
    }
    tau[1] = INFINITY;
    hit[1] = 0;
    if (!r->armed) {
        tau[1] = safe_step(r2 - rearm2, dr2, bound);
        hit[1] = tau[1] < FLIGHT_ROOT_TOL && dr2 < 0.0 &&
                 (surely_crossed(r2 - rearm2, -dr2, bound) || crosses(f, k, t, rearm2, -1.0, (r2 - rearm2) / -dr2));
    }
}

/* The step from t that cannot pass a root (exact up to f->h_max, longer ones at least that); the
 * roots reached (to FLIGHT_ROOT_TOL) flagged in s->dae.rootsfound (*root: any). */
double td_sim_flight_next_step(td_sim *s, td_sim_flight *f, double t, int *root)
{
    int k, i;
    double step = INFINITY;
    *root = 0;
    memset(s->dae.rootsfound, 0, sizeof(int) * (size_t)s->dae.nroots);
    for (k = 0; k < s->dae.nr; k++) {
        double tau[2];
        int hit[2];
        td_sim_flight_propagate(f, t); /* crosses() moves it */
        retainer_roots(s, f, k, t, fmin(step, f->h_max), tau, hit);
        for (i = 0; i < 2; i++) {
            if (hit[i]) {
                s->dae.rootsfound[TD_ROOTS_PER_RETAINER * k + (i == 0 ? TD_ROOT_CONTACT : TD_ROOT_REARM)] =
                    i == 0 ? -1 : 1;
                *root = 1;
            }
            step = fmin(step, tau[i]);
        }
    }
    return *root ? 0.0 : step;
}

/* Every root function positive at s->dae.t: the flight starts clear of every root. */
int td_sim_flight_clear_of_roots(td_sim *s, td_sim_flight *f)
{
    int root;
    td_sim_flight_propagate(f, s->dae.t);
    return td_sim_flight_next_step(s, f, s->dae.t, &root) > 0.0 && !root;
}
