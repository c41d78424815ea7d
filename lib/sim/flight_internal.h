/*
 * Free flight in closed form (sim_internal.h "flight"), inside the flight's files only: flight_modal.c
 * (the decomposition, forcing, evaluation), flight_roots.c (the next root) and flight.c (the steps).
 *
 * While every retainer is free, the speed is prescribed and constant and the AMB laws are linear
 * (no saturation), the machine is linear and time-invariant with harmonic forcing. In the first
 * unknowns of y, z = [q | v | w] (sim_internal.h: y begins with exactly these blocks),
 *
 *   z' = A z + b0 + bc cos W(t - tf) + bs sin W(t - tf)
 *
 * (W the speed: the unbalances; b0: gravity and held AMB forces). With A = V diag(lambda) V^-1 the
 * modal coordinates a = V^-1 z are
 *
 *   a_j(t) = d_j e^{lambda_j (t - ta)} + p0_j + pp_j e^{iW(t - tf)} + pm_j e^{-iW(t - tf)}
 *
 * with p0 = -beta0 / lambda, pp = beta+ / (iW - lambda), pm = beta- / (-iW - lambda), beta0 = V^-1 b0,
 * beta+- = V^-1 (bc -+ i bs) / 2, and d the homogeneous part at the anchor time ta. A and b are
 * probed from the DAE's own residual (sim_residual.c): the flight follows exactly the equations IDA
 * integrates, with rounding as its only error.
 *
 * The next root is found with a step that cannot pass it: for each root function
 * G(t) = R^2 - |p(t)|^2 (p the node's position, R the radius of the root: the clearance, the
 * rearm radius), positive until the root, the modal sum bounds |p|, |p'|, |p''| from now on
 * (|e^{lambda t}| <= 1 for a stable mode), so G'' >= -B with B = 2 (|p'|max^2 + |p|max |p''|max),
 * and G stays positive for tau below the root of G + G' tau - B tau^2 / 2. Stepping by that tau
 * never crosses a root, however grazing, and converges on a simple root like Newton's method.
 */
#ifndef TD_SIM_FLIGHT_INTERNAL_H
#define TD_SIM_FLIGHT_INTERNAL_H

#include "sim/sim_internal.h"

#include <complex.h>

/* s: a step this short to a root that the function approaches is the root (far below any
 * tolerance the results are read at, far above the rounding of t) */
#define FLIGHT_ROOT_TOL 1e-13
/* s: the longest step, which bounds the growth of a mode with a positive real part in the bounds
 * (with sampled controllers the sample period, if shorter: td_sim_flight.h_max) */
#define FLIGHT_MAX_STEP 1e-2
/* steps in one call after which the flight hands over to the integrator (a safety net) */
#define FLIGHT_MAX_STEPS 1000000L
/* relative accuracy of the AMB peak load found in flight */
#define FLIGHT_PEAK_RTOL 1e-6
/* the decomposition is used when A V = V diag(lambda) and V V^-1 = I hold to this */
#define FLIGHT_DECOMPOSITION_TOL 1e-9

/* An observation's value, rate and bounds from now on (|o|, |o'|, |o''| <= b0, b1, b2). */
typedef struct flight_val {
    double v, d, b0, b1, b2;
} flight_val;

/* One observed linear function of the state, o(t) = Re(sum_j c_j e^{lambda_j (t - ta)} + harmonic):
 * a retainer node's x or y, an AMB axis force. */
typedef struct flight_obs {
    double complex *w;         /* nz: its row in modal coordinates, a^T V */
    double complex *c;         /* nz: w_j d_j at the anchor */
    double *m0, *m1, *m2;      /* nz: |c_j|, |c_j lambda_j|, |c_j| |lambda_j|^2 */
    double complex h0, hp, hm; /* constant and harmonic parts: a0 + w.p0, w.pp, w.pm */
    double h0_abs, h_abs;      /* |h0|, |hp| + |hm| */
    double offset;             /* a0: its value at z = 0 */
    /* its last evaluation (td_sim_flight_observe), at seen_t (NaN: none since the anchor or forcing
     * changed): a step's end is observed by the AMBs' peak, the clearance margin and the next step's
     * roots, the same bits each time */
    double seen_t;
    flight_val seen;
    double seen_bound; /* a retainer node's x or y: td_sim_flight_node's bound for seen (NaN: none) */
} flight_obs;

struct td_sim_flight {
    int nz;
    int handover; /* the flight gave up (step budget, creeping steps): IDA goes on until its next step */
    /* the machine: valid for machine_key */
    int machine_ok;
    double *machine_key, *key_work;
    int nkey_m;
    double complex *lam, *V, *Vinv; /* V, V^-1 row-major nz x nz */
    double *vr, *vi;                /* nkeep x nz: the kept modes' columns of V, real, imaginary (kept_columns) */
    double h_max;                   /* s: the longest step, min(FLIGHT_MAX_STEP, the shortest sample period) */
    double *grow;                   /* nz: e^{max(0, Re lambda) h_max} */
    int *keep, nkeep;               /* the modes summed: one of each conjugate pair (z is real) */
    int *order;                     /* nkeep: the kept modes by |lambda|, slowest first */
    double *weight;                 /* nz: 2 for a kept mode with a conjugate partner, else 1 */
    /* the forcing: valid for forcing_key */
    int forcing_ok;
    double *forcing_key;
    int nkey_f;
    double tf, omega;
    double complex *p0, *pp, *pm;
    /* the currents held by sampled controllers (machine.held_current), outside forcing_key: a change
     * of one shifts p0 by -G du / lambda (td_sim_flight_hold) instead of probing the forcing again */
    int nheld;         /* AMB axes driven by a sampled law (0: none, nothing below is used) */
    int *held_axis;    /* nheld: their indices in machine.held_current */
    double *held;      /* nheld: the currents p0 was made for */
    double complex *G; /* nz x nheld row-major: V^-1 times z' per ampere held on each (valid for machine_key) */
    /* the anchor */
    int anchored;
    double ta, t_step;     /* the anchor's time; where the flight's last step ended (>= s->dae.t) */
    double t_root;         /* the last root the flight stopped at */
    double complex *d, *e; /* nz: homogeneous amplitudes at ta, e^{lambda (t - ta)} at t_e */
    double t_e;
    double *ae;             /* nz: |e_j| grow_j */
    double complex *e2;     /* nz: e at the time propagated before t_e, t_e2 (NAN: none) */
    double *ae2, t_e2;      /* nz: its |e_j| grow_j */
    double complex ep, ep2; /* the forcing's phase e^{iW(t - tf)} at t_e and at t_e2 */
    /* observations: x, y of each retainer node, then each AMB axis force */
    int nobs;
    flight_obs *obs;
    /* work */
    double *y, *yp, *res, *rate, *rate0;
    double *b[4];
    double *amb_a, *amb_b, *amb_b2; /* per AMB axis: forces at a step's ends, |F''| bound */
    double *amb_p, *amb_b2p;        /* per AMB axis: forces at and bounds of a pending part */
    double amb_pending;             /* the last step's AMB peak is known up to here (INFINITY: all) */
    double complex *work;           /* 2 nz */
};

/* x y into xy (real, imaginary) as C's complex product (C99 G.5.1: each part one rounding of
 * ac - bd, ad + bc, which the compiled product gives for finite factors), without its check for a
 * NaN: the sums over the modes that need only a real part. */
static inline void flight_mul(double complex x, double complex y, double xy[2])
{
    xy[0] = creal(x) * creal(y) - cimag(x) * cimag(y);
    xy[1] = creal(x) * cimag(y) + cimag(x) * creal(y);
}

/* ---- flight_modal.c ------------------------------------------------------------------------- */

/* The flight allocated, its decomposition (in the states scaled by `scale`, neq) and forcing brought
 * up to date with the machine and anchored at s->dae.t; 0 if the flight cannot carry the machine. */
int td_sim_flight_ready(td_sim *s, const double *scale);
/* e_j = e^{lambda_j (t - ta)} and the bound factors |e_j| grow_j, for the time t. */
void td_sim_flight_propagate(td_sim_flight *f, double t);
/* Observation o at the time of the last propagate (t). */
flight_val td_sim_flight_observe(const td_sim_flight *f, int o, double t);
/* Observations o1 and o2 at the time of the last propagate (t): the same bits as two calls of
 * td_sim_flight_observe, in one pass over the modes. */
void td_sim_flight_observe2(const td_sim_flight *f, int o1, int o2, double t, flight_val *r1, flight_val *r2);
/* e^{iW(t - tf)}: the forcing's phase at t. */
double complex td_sim_flight_phase(const td_sim_flight *f, double t);
/* The held currents of sampled controllers (machine.held_current) now in the forcing: p0 shifted by
 * -G du / lambda for the change du since it was made; with `reanchor` (the flight anchored, its
 * state at s->dae.t the machine's) the homogeneous part takes the opposite shift at s->dae.t, so the
 * state stays continuous there, else the flight is left unanchored. */
void td_sim_flight_shift_held(td_sim *s, td_sim_flight *f, int reanchor);
/* The state z at t into s->dae.y (and its rate into s->dae.yp with `rate`). */
void td_sim_flight_materialise(td_sim *s, td_sim_flight *f, double t, int rate);

/* ---- flight_roots.c ------------------------------------------------------------------------- */

/* The step from t that cannot pass a root (exact up to f->h_max, longer ones at least that); the
 * roots reached (to FLIGHT_ROOT_TOL) flagged in s->dae.rootsfound (*root: any). */
double td_sim_flight_next_step(td_sim *s, td_sim_flight *f, double t, int *root);
/* Retainer k's node at the last propagate (time t): x and y into *x, *y, and the bound
 * B = 2 (|p'|^2 + |p| |p''|) >= |(r^2)''| from t on (r^2 = x^2 + y^2, p = (x, y): |p|, |p'|, |p''| from
 * the modal sums' bounds), shared by the root functions and the clearance margin (kept with the
 * observations: the same t gives the same bits). */
double td_sim_flight_node(const td_sim_flight *f, int k, double t, flight_val *x, flight_val *y);
/* Every root function positive at s->dae.t: the flight starts clear of every root. */
int td_sim_flight_clear_of_roots(td_sim *s, td_sim_flight *f);
/* The node inside radius R until F(tau) = R - m - a tau^2 / 2 - |p + v tau| (concave) reaches zero:
 * the lower end of a 30-step bisection of [0, hi] for the crossing (F > 0 there as computed), hi if
 * F(hi) > 0, 0 if F(0) <= 0; td_sim_flight_inside_until with a few evaluations of F, bit for bit
 * td_sim_flight_inside_bisect's answer (the plain bisection). */
double td_sim_flight_inside_until(double R, double m, double a, const double p[2], const double v[2], double hi);
double td_sim_flight_inside_bisect(double R, double m, double a, const double p[2], const double v[2], double hi);
/* 1 if td_sim_flight_inside_until's answer is at most t (t >= 0) for every hi: F as computed is
 * proven negative from t on (one evaluation); 0 if that is not proven. */
int td_sim_flight_outside_from(double R, double m, double a, const double p[2], const double v[2], double t);

#endif
