/*
 * Free flight in closed form (sim_internal.h "flight.c").
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
#include "sim/sim_internal.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* s: a step this short to a root that the function approaches is the root (far below any
 * tolerance the results are read at, far above the rounding of t) */
#define FLIGHT_ROOT_TOL 1e-13
/* s: the longest step, which bounds the growth of a mode with a positive real part in the bounds */
#define FLIGHT_MAX_STEP 1e-2
/* steps in one call after which the flight hands over to the integrator (a safety net) */
#define FLIGHT_MAX_STEPS 1000000L
/* relative accuracy of the AMB peak load found in flight */
#define FLIGHT_PEAK_RTOL 1e-6
/* the decomposition is used when A V = V diag(lambda) and V V^-1 = I hold to this */
#define FLIGHT_DECOMPOSITION_TOL 1e-9

/* One observed linear function of the state, o(t) = Re(sum_j c_j e^{lambda_j (t - ta)} + harmonic):
 * a retainer node's x or y, an AMB axis force. */
typedef struct flight_obs {
    double complex *w;         /* nz: its row in modal coordinates, a^T V */
    double complex *c;         /* nz: w_j d_j at the anchor */
    double *m0, *m1, *m2;      /* nz: |c_j|, |c_j lambda_j|, |c_j| |lambda_j|^2 */
    double complex h0, hp, hm; /* constant and harmonic parts: a0 + w.p0, w.pp, w.pm */
    double offset;             /* a0: its value at z = 0 */
} flight_obs;

/* An observation's value, rate and bounds from now on (|o|, |o'|, |o''| <= b0, b1, b2). */
typedef struct flight_val {
    double v, d, b0, b1, b2;
} flight_val;

struct td_sim_flight {
    int nz;
    int handover; /* the flight gave up (step budget, creeping steps): IDA goes on until its next step */
    /* the machine: valid for machine_key */
    int machine_ok;
    double *machine_key, *key_work;
    int nkey_m;
    double complex *lam, *V, *Vinv; /* V, V^-1 row-major nz x nz */
    double *grow;                   /* nz: e^{max(0, Re lambda) FLIGHT_MAX_STEP} */
    int *keep, nkeep;               /* the modes summed: one of each conjugate pair (z is real) */
    int *order;                     /* nkeep: the kept modes by |lambda|, slowest first */
    double *weight;                 /* nz: 2 for a kept mode with a conjugate partner, else 1 */
    /* the forcing: valid for forcing_key */
    int forcing_ok;
    double *forcing_key;
    int nkey_f;
    double tf, omega;
    double complex *p0, *pp, *pm;
    /* the anchor */
    int anchored;
    double ta, t_step;     /* the anchor's time; where the flight's last step ended (>= s->t) */
    double t_root;         /* the last root the flight stopped at */
    double complex *d, *e; /* nz: homogeneous amplitudes at ta, e^{lambda (t - ta)} at t_e */
    double t_e;
    double *ae; /* nz: |e_j| grow_j */
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

/* ---- eligibility and keys ---------------------------------------------------------------- */

int td_sim_flight_eligible(const td_sim *s)
{
    int k;
    if (!s->opt.solver.free_flight || s->opt.energy || s->spin >= 0 || td_model_speed_varies(s->model) || s->pending)
        return 0;
    for (k = 0; k < s->sys->n_amb_axes; k++)
        if (s->sys->amb_axes[k].saturation)
            return 0;
    for (k = 0; k < s->nr; k++) {
        const td_sim_retainer *r = &s->ret[k];
        if ((r->compliant && !r->armed) || r->rx >= 0 || r->rs >= 0 || r->mode != TD_RMODE_FREE || r->rolling)
            return 0;
    }
    return 1;
}

/* What A depends on: the speed and the AMBs' modes. */
static int machine_key(const td_sim *s, double *key)
{
    int a, n = 0, na = td_model_amb_count(s->model);
    key[n++] = s->omega;
    for (a = 0; a < na; a++)
        key[n++] = (double)s->amb_mode[a];
    return n;
}

/* What b(t) depends on beyond A: the spin angle, the unbalances and the held AMB forces. */
static int forcing_key(const td_sim *s, double *key)
{
    int i, n = 0, na = td_model_amb_count(s->model);
    key[n++] = s->spin_ref;
    key[n++] = s->t_spin_ref;
    for (i = 0; i < s->nu; i++) {
        key[n++] = s->unb[i].magnitude;
        key[n++] = s->unb[i].phase;
    }
    for (i = 0; i < 2 * na; i++)
        key[n++] = s->amb_control[i];
    return n;
}

/* 1 if key (n entries, freshly made in f->key_work) differs from *stored; then stores it. */
static int key_changed(td_sim_flight *f, double *stored, int n)
{
    if (memcmp(stored, f->key_work, sizeof(double) * (size_t)n) == 0)
        return 0;
    memcpy(stored, f->key_work, sizeof(double) * (size_t)n);
    return 1;
}

/* ---- the first-order rates, probed from the residual ------------------------------------ */

/* z' at (t, z) with every retainer free: -F(t, y, 0) on the q and w rows, M^-1 (-F) on the v rows. */
static void rates(const td_sim *s, td_sim_flight *f, double t, const double *z, double *rate)
{
    int i;
    memset(f->y, 0, sizeof(double) * (size_t)s->neq);
    memcpy(f->y, z, sizeof(double) * (size_t)f->nz);
    td_sim_residual(s, t, f->y, f->yp, f->res);
    for (i = 0; i < f->nz; i++)
        rate[i] = -f->res[i];
    td_sim_mass_solve(s, rate + s->ov);
}

/* Probe size of state i: half the smallest clearance for a displacement (a penalty contact stays
 * out of reach at the centre), 1 in the other states' units; the law is linear, so only the
 * rounding depends on it. */
static double probe_size(const td_sim *s, int i)
{
    double c = INFINITY;
    int k;
    if (i >= s->n)
        return 1.0;
    for (k = 0; k < s->nr; k++)
        c = fmin(c, s->ret[k].r.clearance);
    return isfinite(c) ? 0.5 * c : 1.0;
}

/* ---- the machine: A and its eigen-decomposition ----------------------------------------- */

/* A in the scaled states z_i / S_i, S the integrator's absolute tolerances (each state in its
 * tolerance's units: the eigenvectors come out balanced, and their checks mean something). */
static void fill_matrix(const td_sim *s, td_sim_flight *f, gsl_matrix *A)
{
    const double *S = N_VGetArrayPointer(s->atol);
    double *z = f->b[0];
    int i, j, nz = f->nz;
    memset(z, 0, sizeof(double) * (size_t)nz);
    rates(s, f, s->t, z, f->rate0);
    for (j = 0; j < nz; j++) {
        double h = probe_size(s, j);
        z[j] = h;
        rates(s, f, s->t, z, f->rate);
        z[j] = 0.0;
        for (i = 0; i < nz; i++)
            gsl_matrix_set(A, (size_t)i, (size_t)j, (f->rate[i] - f->rate0[i]) / h * S[j] / S[i]);
    }
}

/* V <- S V, V^-1 <- V^-1 S^-1: the modes of the unscaled states. */
static void unscale_modes(const td_sim *s, td_sim_flight *f)
{
    const double *S = N_VGetArrayPointer(s->atol);
    size_t i, j, nz = (size_t)f->nz;
    for (i = 0; i < nz; i++)
        for (j = 0; j < nz; j++) {
            f->V[i * nz + j] *= S[i];
            f->Vinv[i * nz + j] /= S[j];
        }
}

/* The decomposition's quality: the largest of max_i |A v_j - lambda_j v_j| / (|lambda_j| max_i |v_j|)
 * over the modes j (the phase error per radian of each mode) and max |V V^-1 - I|. */
static double decomposition_error(const td_sim_flight *f, const gsl_matrix *A)
{
    int i, j, k, nz = f->nz;
    double worst = 0.0;
    for (j = 0; j < nz; j++) {
        double res = 0.0, vmax = 0.0;
        for (i = 0; i < nz; i++) {
            double complex av = -f->V[i * nz + j] * f->lam[j], vv = 0.0;
            for (k = 0; k < nz; k++) {
                av += gsl_matrix_get(A, (size_t)i, (size_t)k) * f->V[k * nz + j];
                vv += f->V[i * nz + k] * f->Vinv[k * nz + j];
            }
            res = fmax(res, cabs(av));
            vmax = fmax(vmax, cabs(f->V[i * nz + j]));
            worst = fmax(worst, cabs(vv - (i == j ? 1.0 : 0.0)));
        }
        worst = fmax(worst, res / (cabs(f->lam[j]) * vmax));
    }
    return worst;
}

static int invert_modes(td_sim_flight *f, const gsl_matrix_complex *evec)
{
    size_t nz = (size_t)f->nz, i, j;
    gsl_matrix_complex *lu = gsl_matrix_complex_alloc(nz, nz), *inv = gsl_matrix_complex_alloc(nz, nz);
    gsl_permutation *p = gsl_permutation_alloc(nz);
    int signum, ok = lu && inv && p;
    if (ok) {
        gsl_matrix_complex_memcpy(lu, evec);
        ok = gsl_linalg_complex_LU_decomp(lu, p, &signum) == GSL_SUCCESS &&
             gsl_linalg_complex_LU_invert(lu, p, inv) == GSL_SUCCESS;
    }
    for (i = 0; ok && i < nz; i++)
        for (j = 0; j < nz; j++) {
            gsl_complex v = gsl_matrix_complex_get(evec, i, j), w = gsl_matrix_complex_get(inv, i, j);
            f->V[i * nz + j] = GSL_REAL(v) + I * GSL_IMAG(v);
            f->Vinv[i * nz + j] = GSL_REAL(w) + I * GSL_IMAG(w);
        }
    gsl_permutation_free(p);
    gsl_matrix_complex_free(inv);
    gsl_matrix_complex_free(lu);
    return ok;
}

/* One mode of each conjugate pair (GSL gives a pair's two columns side by side, exactly
 * conjugate): the real part of a sum over both is twice that over one. */
static void pair_modes(td_sim_flight *f)
{
    int i, j, nz = f->nz;
    f->nkeep = 0;
    for (j = 0; j < nz; j++) {
        int paired = j + 1 < nz && cimag(f->lam[j]) > 0.0 && f->lam[j + 1] == conj(f->lam[j]);
        for (i = 0; paired && i < nz; i++)
            paired = f->V[i * nz + j + 1] == conj(f->V[i * nz + j]);
        f->keep[f->nkeep++] = j;
        f->weight[j] = paired ? 2.0 : 1.0;
        if (paired)
            f->weight[++j] = 0.0;
    }
    for (i = 0; i < f->nkeep; i++) { /* insertion sort by |lambda|: once per machine */
        int m = f->keep[i], p = i;
        for (; p > 0 && cabs(f->lam[f->order[p - 1]]) > cabs(f->lam[m]); p--)
            f->order[p] = f->order[p - 1];
        f->order[p] = m;
    }
}

/* A's modes; 0 if A cannot be trusted to them (defective, ill-conditioned, a zero or resonant
 * eigenvalue, a mode growing faster than the bounds allow). */
static int decompose(const td_sim *s, td_sim_flight *f)
{
    size_t nz = (size_t)f->nz;
    gsl_matrix *A = gsl_matrix_alloc(nz, nz), *Acopy = gsl_matrix_alloc(nz, nz);
    gsl_vector_complex *eval = gsl_vector_complex_alloc(nz);
    gsl_matrix_complex *evec = gsl_matrix_complex_alloc(nz, nz);
    gsl_eigen_nonsymmv_workspace *w = gsl_eigen_nonsymmv_alloc(nz);
    int ok = A && Acopy && eval && evec && w;
    size_t j;
    gsl_set_error_handler_off();
    if (ok) {
        fill_matrix(s, f, A);
        gsl_matrix_memcpy(Acopy, A);
        gsl_eigen_nonsymmv_params(1, w);
        ok = gsl_eigen_nonsymmv(A, eval, evec, w) == GSL_SUCCESS && invert_modes(f, evec);
    }
    for (j = 0; ok && j < nz; j++) {
        gsl_complex l = gsl_vector_complex_get(eval, j);
        f->lam[j] = GSL_REAL(l) + I * GSL_IMAG(l);
        if (!(cabs(f->lam[j]) > 0.0) || GSL_REAL(l) * FLIGHT_MAX_STEP > 1.0)
            ok = 0;
        f->grow[j] = exp(fmax(0.0, GSL_REAL(l)) * FLIGHT_MAX_STEP);
    }
    if (ok)
        ok = decomposition_error(f, Acopy) < FLIGHT_DECOMPOSITION_TOL;
    if (ok) {
        unscale_modes(s, f);
        pair_modes(f);
    }
    gsl_eigen_nonsymmv_free(w);
    gsl_matrix_complex_free(evec);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(Acopy);
    gsl_matrix_free(A);
    return ok;
}

/* ---- the forcing --------------------------------------------------------------------------- */

/* out = V^-1 x, x complex */
static void to_modal(const td_sim_flight *f, const double complex *x, double complex *out)
{
    int i, j, nz = f->nz;
    for (i = 0; i < nz; i++) {
        double complex acc = 0.0;
        const double complex *row = f->Vinv + (size_t)i * (size_t)nz;
        for (j = 0; j < nz; j++)
            acc += row[j] * x[j];
        out[i] = acc;
    }
}

/* The block of first-order state i: 0 the displacements q, 1 the velocities v, 2 the AMB states w. */
static int forcing_block(const td_sim *s, int i)
{
    return i < s->n ? 0 : i < 2 * s->n ? 1 : 2;
}

/* b(t) at tf, tf + T/4, tf + T/2 (T = 2 pi / W) gives b0, bc, bs; tf + T/8 checks that b is
 * that harmonic. Returns 0 if it is not. */
static int probe_forcing(const td_sim *s, td_sim_flight *f)
{
    double *z = f->rate0, w = f->omega, q = w != 0.0 ? M_PI / w : 0.0;
    double complex *bp = f->e, *bm = f->d; /* work until the anchor */
    double scale[3] = {0.0, 0.0, 0.0};
    int i, nz = f->nz, ok = 1;
    memset(z, 0, sizeof(double) * (size_t)nz);
    rates(s, f, f->tf, z, f->b[0]);
    rates(s, f, f->tf + 0.5 * q, z, f->b[1]);
    rates(s, f, f->tf + q, z, f->b[2]);
    rates(s, f, f->tf + 0.25 * q, z, f->b[3]);
    for (i = 0; i < nz; i++) /* each block's size: the rounding of the mass solve is relative to it */
        scale[forcing_block(s, i)] = fmax(scale[forcing_block(s, i)], fabs(f->b[0][i]) + fabs(f->b[1][i]));
    for (i = 0; i < nz; i++) {
        double b0 = w != 0.0 ? 0.5 * (f->b[0][i] + f->b[2][i]) : f->b[0][i];
        double bc = f->b[0][i] - b0, bs = w != 0.0 ? f->b[1][i] - b0 : 0.0;
        double check = b0 + M_SQRT1_2 * (bc + bs);
        if (fabs(check - f->b[3][i]) > 1e-10 * scale[forcing_block(s, i)] + 1e-300)
            ok = 0;
        f->b[0][i] = b0;
        bp[i] = 0.5 * (bc - I * bs);
        bm[i] = 0.5 * (bc + I * bs);
    }
    to_modal(f, bp, f->pp); /* beta+, beta-, beta0: build_forcing divides them */
    to_modal(f, bm, f->pm);
    for (i = 0; i < nz; i++)
        bp[i] = f->b[0][i];
    to_modal(f, bp, f->p0);
    return ok;
}

/* The particular solution's modal coefficients; 0 if the forcing is not harmonic at the speed or
 * resonant with a mode. */
static int build_forcing(const td_sim *s, td_sim_flight *f)
{
    int j;
    f->tf = s->t;
    f->omega = s->omega;
    if (!probe_forcing(s, f))
        return 0;
    for (j = 0; j < f->nz; j++) {
        double complex l = f->lam[j];
        if (cabs(I * f->omega - l) == 0.0 || cabs(-I * f->omega - l) == 0.0)
            return 0;
        f->p0[j] = -f->p0[j] / l;
        f->pp[j] = f->pp[j] / (I * f->omega - l);
        f->pm[j] = f->pm[j] / (-I * f->omega - l);
    }
    return 1;
}

/* ---- observations ---------------------------------------------------------------------------- */

/* Observation o as the real row a (nz) with value a0 at z = 0. */
static void set_obs_row(td_sim_flight *f, flight_obs *o, const double *a, double a0)
{
    int i, j, nz = f->nz;
    for (j = 0; j < nz; j++) {
        double complex acc = 0.0;
        for (i = 0; i < nz; i++)
            if (a[i] != 0.0)
                acc += a[i] * f->V[(size_t)i * (size_t)nz + (size_t)j];
        o->w[j] = acc;
    }
    o->offset = a0;
}

/* The rows of the observations: retainer nodes' x, y; AMB axis forces (probed, linear). */
static void build_observations(const td_sim *s, td_sim_flight *f)
{
    double *a = f->rate;
    int i, k, nz = f->nz;
    for (k = 0; k < s->nr; k++) {
        memset(a, 0, sizeof(double) * (size_t)nz);
        a[s->oq + s->ret[k].dx] = 1.0;
        set_obs_row(f, &f->obs[2 * k], a, 0.0);
        a[s->oq + s->ret[k].dx] = 0.0;
        a[s->oq + s->ret[k].dy] = 1.0;
        set_obs_row(f, &f->obs[2 * k + 1], a, 0.0);
    }
    for (k = 0; k < s->sys->n_amb_axes; k++) {
        double f0;
        memset(f->y, 0, sizeof(double) * (size_t)s->neq);
        f0 = td_sim_amb_axis_force(s, k, f->y);
        for (i = 0; i < nz; i++) {
            double h = probe_size(s, i);
            f->y[i] = h;
            a[i] = (td_sim_amb_axis_force(s, k, f->y) - f0) / h;
            f->y[i] = 0.0;
        }
        set_obs_row(f, &f->obs[2 * s->nr + k], a, f0);
    }
}

/* The observations' particular parts for the current forcing. */
static void observe_forcing(td_sim_flight *f)
{
    int o, j;
    for (o = 0; o < f->nobs; o++) {
        flight_obs *b = &f->obs[o];
        b->h0 = b->offset;
        b->hp = b->hm = 0.0;
        for (j = 0; j < f->nz; j++) {
            b->h0 += b->w[j] * f->p0[j];
            b->hp += b->w[j] * f->pp[j];
            b->hm += b->w[j] * f->pm[j];
        }
    }
}

/* ---- the anchor and evaluation -------------------------------------------------------------- */

static double complex harmonic_phase(const td_sim_flight *f, double t)
{
    return cexp(I * f->omega * (t - f->tf));
}

/* The particular solution's modal coordinates at t into out. */
static void particular(const td_sim_flight *f, double t, double complex *out)
{
    double complex ep = harmonic_phase(f, t), em = conj(ep);
    int j;
    for (j = 0; j < f->nz; j++)
        out[j] = f->p0[j] + f->pp[j] * ep + f->pm[j] * em;
}

/* Anchor the flight at s->t on the state in s->y. */
static void anchor(td_sim *s, td_sim_flight *f)
{
    const double *y = N_VGetArrayPointer(s->y);
    int j, o, nz = f->nz;
    for (j = 0; j < nz; j++)
        f->e[j] = y[j];
    to_modal(f, f->e, f->d);
    particular(f, s->t, f->e);
    for (j = 0; j < nz; j++)
        f->d[j] -= f->e[j];
    f->ta = s->t;
    f->t_e = NAN; /* e is stale */
    for (o = 0; o < f->nobs; o++) {
        flight_obs *b = &f->obs[o];
        for (j = 0; j < nz; j++) {
            double l = cabs(f->lam[j]);
            b->c[j] = f->weight[j] * b->w[j] * f->d[j];
            b->m0[j] = cabs(b->c[j]);
            b->m1[j] = b->m0[j] * l;
            b->m2[j] = b->m1[j] * l;
        }
    }
    f->anchored = 1;
}

/* e_j = e^{lambda_j (t - ta)} and the bound factors |e_j| grow_j, for the time t. */
static void propagate(td_sim_flight *f, double t)
{
    double dt = t - f->ta;
    int i;
    if (t == f->t_e)
        return;
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double m = exp(creal(f->lam[j]) * dt);
        f->e[j] = m * (cos(cimag(f->lam[j]) * dt) + I * sin(cimag(f->lam[j]) * dt));
        f->ae[j] = m * f->grow[j];
    }
    f->t_e = t;
}

/* Observation o at the time of the last propagate (t). */
static flight_val observe(const td_sim_flight *f, int o, double t)
{
    const flight_obs *b = &f->obs[o];
    double complex ep = harmonic_phase(f, t), v = 0.0, d = 0.0;
    double w = fabs(f->omega), h = cabs(b->hp) + cabs(b->hm);
    flight_val r = {0.0, 0.0, 0.0, 0.0, 0.0};
    int i;
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double complex ce = b->c[j] * f->e[j];
        v += ce;
        d += ce * f->lam[j];
        r.b0 += b->m0[j] * f->ae[j];
        r.b1 += b->m1[j] * f->ae[j];
        r.b2 += b->m2[j] * f->ae[j];
    }
    v += b->h0 + b->hp * ep + b->hm * conj(ep);
    d += I * f->omega * (b->hp * ep - b->hm * conj(ep));
    r.v = creal(v);
    r.d = creal(d);
    r.b0 += cabs(b->h0) + h;
    r.b1 += w * h;
    r.b2 += w * w * h;
    return r;
}

/* The modal coordinates at t (propagated), weighted for the kept modes, into f->b-sized complex
 * work `a`; with `rate`, their time derivatives into `da`. */
static void modal_state(const td_sim_flight *f, double t, double complex *a, double complex *da)
{
    double complex ep = harmonic_phase(f, t), em = conj(ep);
    int i;
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double complex h = f->d[j] * f->e[j], p = f->pp[j] * ep, m = f->pm[j] * em;
        a[i] = f->weight[j] * (h + f->p0[j] + p + m);
        if (da)
            da[i] = f->weight[j] * (f->lam[j] * h + I * f->omega * (p - m));
    }
}

/* The state z at t into y (and its rate into yp with `rate`; the rest of yp: zero in free flight). */
static void materialise(td_sim *s, td_sim_flight *f, double t, int rate)
{
    double *y = N_VGetArrayPointer(s->y), *yp = N_VGetArrayPointer(s->yp);
    double complex *a = f->work, *da = rate ? f->work + f->nz : NULL;
    int i, k, nz = f->nz;
    propagate(f, t);
    modal_state(f, t, a, da);
    for (i = 0; i < nz; i++) {
        const double complex *row = f->V + (size_t)i * (size_t)nz;
        double z = 0.0, zd = 0.0;
        for (k = 0; k < f->nkeep; k++) {
            double complex v = row[f->keep[k]];
            z += creal(v) * creal(a[k]) - cimag(v) * cimag(a[k]);
            if (rate)
                zd += creal(v) * creal(da[k]) - cimag(v) * cimag(da[k]);
        }
        y[i] = z;
        if (rate)
            yp[i] = zd;
    }
    for (i = nz; rate && i < s->neq; i++)
        yp[i] = 0.0;
}

/* The displacements z at t into y[0..nz) from the anchored flight, leaving the flight's own cache
 * (e, t_e) untouched: the modal coordinates go to the caller's `work` (2 neq doubles). */
int td_sim_flight_peek(const td_sim *s, double t, double *y, double *work)
{
    const td_sim_flight *f = s->flight;
    double complex *e = (double complex *)(void *)work;
    double complex ep, em;
    int i, k;
    if (!f || !f->anchored)
        return 0;
    ep = harmonic_phase(f, t);
    em = conj(ep);
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double dt = t - f->ta, m = exp(creal(f->lam[j]) * dt);
        double complex h = f->d[j] * (m * (cos(cimag(f->lam[j]) * dt) + I * sin(cimag(f->lam[j]) * dt)));
        e[i] = f->weight[j] * (h + f->p0[j] + f->pp[j] * ep + f->pm[j] * em);
    }
    for (i = 0; i < f->nz; i++) {
        const double complex *row = f->V + (size_t)i * (size_t)f->nz;
        double z = 0.0;
        for (k = 0; k < f->nkeep; k++)
            z += creal(row[f->keep[k]]) * creal(e[k]) - cimag(row[f->keep[k]]) * cimag(e[k]);
        y[i] = z;
    }
    return 1;
}

void td_sim_flight_rates(td_sim *s)
{
    if (s->flight && s->flight->anchored)
        materialise(s, s->flight, s->t, 1);
}

/* ---- the next root -------------------------------------------------------------------------- */

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
    propagate(f, t2);
    x = observe(f, 2 * k, t2);
    y = observe(f, 2 * k + 1, t2);
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

/* The node inside radius R until F(tau) = R - m - a tau^2 / 2 - |p + v tau| reaches zero (F is
 * concave: one crossing, found by bisection to a 2^-30 of the longest step); 0 if F(0) <= 0. */
static double inside_until(double R, double m, double a, const double p[2], const double v[2])
{
    double lo = 0.0, hi = FLIGHT_MAX_STEP;
    int i;
#define INSIDE(tau) (R - m - 0.5 * a * (tau) * (tau)-hypot(p[0] + v[0] * (tau), p[1] + v[1] * (tau)))
    if (INSIDE(0.0) <= 0.0)
        return 0.0;
    if (INSIDE(hi) > 0.0)
        return hi;
    for (i = 0; i < 30; i++) {
        double mid = 0.5 * (lo + hi);
        if (INSIDE(mid) > 0.0)
            lo = mid;
        else
            hi = mid;
    }
#undef INSIDE
    return lo;
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
    double complex ep = harmonic_phase(f, t);
    double p[2], v[2], a[2], m[2] = {0.0, 0.0}, best = 0.0, w = f->omega;
    int c, i = 0, stride = f->nkeep / FLIGHT_SPLITS + 1;
    for (c = 0; c < 2; c++) { /* start: the forcing slow, every mode fast */
        p[c] = creal(o[c]->h0 + o[c]->hp * ep + o[c]->hm * conj(ep));
        v[c] = creal(I * w * (o[c]->hp * ep - o[c]->hm * conj(ep)));
        a[c] = w * w * (cabs(o[c]->hp) + cabs(o[c]->hm));
        for (i = 0; i < f->nkeep; i++)
            m[c] += o[c]->m0[f->keep[i]] * f->ae[f->keep[i]];
    }
    for (i = 0; i <= f->nkeep; i++) {
        int j;
        if (i % stride == 0 || i == f->nkeep)
            best = fmax(best, inside_until(R, hypot(fmax(m[0], 0.0), fmax(m[1], 0.0)), hypot(a[0], a[1]), p, v));
        if (i == f->nkeep)
            break;
        j = f->order[i]; /* mode j joins the slow side */
        for (c = 0; c < 2; c++) {
            double complex ce = o[c]->c[j] * f->e[j];
            p[c] += creal(ce);
            v[c] += creal(ce * f->lam[j]);
            a[c] += o[c]->m2[j] * f->ae[j];
            m[c] -= o[c]->m0[j] * f->ae[j];
        }
    }
    return best;
}

/* Retainer k's root functions at the last propagate (time t): the safe step to each (contact,
 * rearm: INFINITY where there is none) and whether each is converged on its root: within
 * FLIGHT_ROOT_TOL of it and crossing it: surely by the bound on its curvature, else as evaluated
 * FLIGHT_ROOT_TOL ahead (a graze that turns back before its root is no contact). The bound matters
 * for a slow approach: the safe steps creep up to the root and may stop a rounding error short of
 * it or beyond it, where the evaluation ahead is itself at the rounding level; missed there, the
 * flight hands over to IDA with the root behind IDA's restart, and the node passes through the
 * retainer unseen. */
static void retainer_roots(const td_sim *s, td_sim_flight *f, int k, double t, double tau[2], int hit[2])
{
    const td_sim_retainer *r = &s->ret[k];
    flight_val x = observe(f, 2 * k, t), y = observe(f, 2 * k + 1, t);
    double c = r->r.clearance, r2 = x.v * x.v + y.v * y.v, dr2 = 2.0 * (x.v * x.d + y.v * y.d);
    double p = hypot(x.b0, y.b0), v = hypot(x.b1, y.b1), a = hypot(x.b2, y.b2);
    double bound = 2.0 * (v * v + p * a);
    /* the radii of td_sim_roots' functions: gap + off = 0 (contact), gap - eps = 0 (rearm) */
    double contact2 = c * c + (r->armed ? 0.0 : 2.0 * c * s->rearm_eps);
    double rearm2 = c * c - 2.0 * c * s->rearm_eps;
    tau[0] = safe_step(contact2 - r2, -dr2, bound);
    hit[0] = tau[0] < FLIGHT_ROOT_TOL && dr2 > 0.0 &&
             (surely_crossed(contact2 - r2, dr2, bound) || crosses(f, k, t, contact2, 1.0, (contact2 - r2) / dr2));
    if (!hit[0]) {
        propagate(f, t); /* crosses() may have moved it */
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

/* The step from t that cannot pass a root; the roots reached (to FLIGHT_ROOT_TOL) flagged in
 * s->rootsfound (*root: any). */
static double next_step(td_sim *s, td_sim_flight *f, double t, int *root)
{
    int k, i;
    double step = INFINITY;
    *root = 0;
    memset(s->rootsfound, 0, sizeof(int) * (size_t)s->nroots);
    for (k = 0; k < s->nr; k++) {
        double tau[2];
        int hit[2];
        propagate(f, t); /* crosses() moves it */
        retainer_roots(s, f, k, t, tau, hit);
        for (i = 0; i < 2; i++) {
            if (hit[i]) {
                s->rootsfound[TD_ROOTS_PER_RETAINER * k + (i == 0 ? TD_ROOT_CONTACT : TD_ROOT_REARM)] = i == 0 ? -1 : 1;
                *root = 1;
            }
            step = fmin(step, tau[i]);
        }
    }
    return *root ? 0.0 : step;
}

/* ---- the AMBs' peak load between points -------------------------------------------------- */

static void record_amb_load(td_sim *s, int k, double force, double t)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    double load = fabs(force) / a->capacity;
    if (load > s->stats.peak_amb_load) {
        s->stats.peak_amb_load = load;
        s->stats.peak_amb_force = fabs(force);
        s->stats.peak_amb_time = t;
        s->stats.peak_amb = a->amb;
    }
}

/* AMB axis k's force at t (recorded in the peak load). */
static double amb_force_at(td_sim *s, td_sim_flight *f, int k, double t)
{
    flight_val v;
    propagate(f, t);
    v = observe(f, 2 * s->nr + k, t);
    record_amb_load(s, k, v.v, t);
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
            s->stats.peak_amb_load * a->capacity * (1.0 + FLIGHT_PEAK_RTOL) ||
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
    int k;
    for (k = 0; k < s->sys->n_amb_axes; k++) {
        flight_val v = observe(f, 2 * s->nr + k, t);
        fa[k] = v.v;
        if (b2)
            b2[k] = v.b2;
        if (record && s->amb_mode[s->sys->amb_axes[k].amb] != TD_AMB_OFF)
            record_amb_load(s, k, v.v, t);
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
        double peak = s->stats.peak_amb_load * a->capacity * (1.0 + FLIGHT_PEAK_RTOL);
        if (s->amb_mode[a->amb] == TD_AMB_OFF || fmax(fabs(fa[k]), fabs(fb[k])) + 0.125 * b2[k] * h * h <= peak)
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
        propagate(f, a);
        amb_forces(s, f, a, f->amb_p, NULL, 1);
        fa = f->amb_p;
    }
    propagate(f, b);
    amb_forces(s, f, b, f->amb_b, NULL, 1);
    amb_peaks(s, f, a, b - a, fa, f->amb_b, b2);
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

/* The pending part of the last step (amb_past_output) up to this call's output time. */
static void amb_pending_part(td_sim *s, td_sim_flight *f, double t_out)
{
    double end = fmin(f->t_step, t_out);
    if (!(f->amb_pending < f->t_step))
        return;
    amb_span(s, f, f->amb_pending, end, NULL, f->amb_b2p);
    f->amb_pending = end < f->t_step ? end : INFINITY;
}

/* ---- life cycle ----------------------------------------------------------------------------- */

static void free_obs(flight_obs *o)
{
    free(o->w);
    free(o->c);
    free(o->m0);
    free(o->m1);
    free(o->m2);
}

void td_sim_flight_free(td_sim *s)
{
    td_sim_flight *f = s->flight;
    int i;
    if (!f)
        return;
    for (i = 0; f->obs && i < f->nobs; i++)
        free_obs(&f->obs[i]);
    free(f->obs);
    free(f->machine_key);
    free(f->forcing_key);
    free(f->key_work);
    free(f->lam);
    free(f->V);
    free(f->Vinv);
    free(f->grow);
    free(f->keep);
    free(f->order);
    free(f->weight);
    free(f->work);
    free(f->p0);
    free(f->pp);
    free(f->pm);
    free(f->d);
    free(f->e);
    free(f->ae);
    free(f->y);
    free(f->yp);
    free(f->res);
    free(f->rate);
    free(f->rate0);
    for (i = 0; i < 4; i++)
        free(f->b[i]);
    free(f->amb_a);
    free(f->amb_b);
    free(f->amb_b2);
    free(f->amb_p);
    free(f->amb_b2p);
    free(f);
    s->flight = NULL;
}

static int alloc_obs(flight_obs *o, size_t nz)
{
    o->w = calloc(nz, sizeof *o->w);
    o->c = calloc(nz, sizeof *o->c);
    o->m0 = calloc(nz, sizeof *o->m0);
    o->m1 = calloc(nz, sizeof *o->m1);
    o->m2 = calloc(nz, sizeof *o->m2);
    return o->w && o->c && o->m0 && o->m1 && o->m2;
}

/* The flight's arrays; 0 when out of memory (the integrator then carries the machine). */
static int flight_alloc(td_sim *s)
{
    td_sim_flight *f = calloc(1, sizeof *f);
    size_t nz = (size_t)(2 * s->n + s->nw), neq = (size_t)s->neq, nk, na;
    int i, ok = f != NULL;
    if (!ok)
        return 0;
    s->flight = f;
    f->nz = (int)nz;
    f->nobs = 2 * s->nr + s->sys->n_amb_axes;
    nk = (size_t)(3 + 2 * s->nu + 3 * td_model_amb_count(s->model));
    f->machine_key = calloc(nk, sizeof(double));
    f->forcing_key = calloc(nk, sizeof(double));
    f->key_work = calloc(nk, sizeof(double));
    f->lam = calloc(nz, sizeof *f->lam);
    f->V = calloc(nz * nz, sizeof *f->V);
    f->Vinv = calloc(nz * nz, sizeof *f->Vinv);
    f->grow = calloc(nz, sizeof *f->grow);
    f->keep = calloc(nz, sizeof *f->keep);
    f->order = calloc(nz, sizeof *f->order);
    f->weight = calloc(nz, sizeof *f->weight);
    f->work = calloc(2 * nz, sizeof *f->work);
    f->p0 = calloc(nz, sizeof *f->p0);
    f->pp = calloc(nz, sizeof *f->pp);
    f->pm = calloc(nz, sizeof *f->pm);
    f->d = calloc(nz, sizeof *f->d);
    f->e = calloc(nz, sizeof *f->e);
    f->ae = calloc(nz, sizeof *f->ae);
    f->y = calloc(neq, sizeof *f->y);
    f->yp = calloc(neq, sizeof *f->yp);
    f->res = calloc(neq, sizeof *f->res);
    f->rate = calloc(nz, sizeof *f->rate);
    f->rate0 = calloc(nz, sizeof *f->rate0);
    for (i = 0; i < 4; i++)
        ok = ok && (f->b[i] = calloc(nz, sizeof(double))) != NULL;
    f->obs = calloc((size_t)(f->nobs > 0 ? f->nobs : 1), sizeof *f->obs);
    na = (size_t)(s->sys->n_amb_axes > 0 ? s->sys->n_amb_axes : 1);
    f->amb_a = calloc(na, sizeof(double));
    f->amb_b = calloc(na, sizeof(double));
    f->amb_b2 = calloc(na, sizeof(double));
    f->amb_p = calloc(na, sizeof(double));
    f->amb_b2p = calloc(na, sizeof(double));
    ok = ok && f->amb_a && f->amb_b && f->amb_b2 && f->amb_p && f->amb_b2p;
    ok = ok && f->machine_key && f->forcing_key && f->key_work && f->lam && f->V && f->Vinv && f->grow && f->keep &&
         f->order && f->weight && f->work && f->p0 && f->pp && f->pm && f->d && f->e && f->ae && f->y && f->yp &&
         f->res && f->rate && f->rate0 && f->obs;
    for (i = 0; ok && i < f->nobs; i++)
        ok = alloc_obs(&f->obs[i], nz);
    f->nkey_m = f->nkey_f = -1;
    f->t_root = -INFINITY;
    if (!ok)
        td_sim_flight_free(s);
    return ok;
}

void td_sim_flight_forget(td_sim *s)
{
    if (s->flight) {
        s->flight->anchored = 0;
        s->flight->handover = 0;
        s->flight->t_step = -INFINITY;
    }
}

/* The decomposition and the forcing brought up to date with the machine; 0 if the flight cannot
 * carry it. */
static int flight_ready(td_sim *s)
{
    td_sim_flight *f;
    int n;
    if (!s->flight && !flight_alloc(s))
        return 0;
    f = s->flight;
    if (f->handover)
        return 0;
    n = machine_key(s, f->key_work);
    if (key_changed(f, f->machine_key, n) || n != f->nkey_m) {
        f->nkey_m = n;
        f->machine_ok = decompose(s, f);
        if (f->machine_ok)
            build_observations(s, f);
        f->nkey_f = -1;
        f->anchored = 0;
    }
    if (!f->machine_ok)
        return 0;
    n = forcing_key(s, f->key_work);
    if (key_changed(f, f->forcing_key, n) || n != f->nkey_f) {
        f->nkey_f = n;
        f->forcing_ok = build_forcing(s, f);
        if (f->forcing_ok)
            observe_forcing(f);
        f->anchored = 0;
    }
    if (!f->forcing_ok)
        return 0;
    if (!f->anchored) {
        anchor(s, f);
        f->t_step = -INFINITY;
    }
    return 1;
}

/* Every root function positive at s->t: the flight starts clear of every root. */
static int clear_of_roots(td_sim *s, td_sim_flight *f)
{
    int root;
    propagate(f, s->t);
    return next_step(s, f, s->t, &root) > 0.0 && !root;
}

/*
 * The flight's own steps run on from where the last one ended (f->t_step, which may lie beyond
 * s->t): outputs only evaluate the solution, so the steps, the roots and the peaks found do not
 * depend on the output times (as IDA's do not). A stop (t_stop: a schedule change) ends a step.
 */
int td_sim_flight_advance(td_sim *s, double t_out, double t_stop, int *root)
{
    td_sim_flight *f;
    double t, t_end = fmin(t_out, t_stop);
    long steps = 0;
    *root = 0;
    if (!td_sim_flight_eligible(s) || !flight_ready(s))
        return 0;
    f = s->flight;
    if (f->t_step < s->t || f->t_step > t_stop) { /* a fresh flight */
        if (!clear_of_roots(s, f))
            return 0;
        f->t_step = s->t;
        f->amb_pending = INFINITY;
        propagate(f, f->t_step);
        amb_forces(s, f, f->t_step, f->amb_a, f->amb_b2, 1);
    }
    amb_pending_part(s, f, t_out);
    t = f->t_step;
    while (t < t_end) {
        double h, tn;
        if ((s->interrupt && *s->interrupt) || steps >= FLIGHT_MAX_STEPS) {
            f->handover = steps >= FLIGHT_MAX_STEPS;
            break;
        }
        propagate(f, t);
        h = next_step(s, f, t, root);
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
        h = fmin(h, FLIGHT_MAX_STEP);
        tn = t + h < t_stop - FLIGHT_ROOT_TOL ? t + h : t_stop; /* no sliver of a step before the stop */
        if (tn <= t_out) {
            propagate(f, tn);
            amb_forces(s, f, tn, f->amb_b, NULL, 1);
            amb_peaks(s, f, t, tn - t, f->amb_a, f->amb_b, f->amb_b2);
        } else {
            amb_past_output(s, f, t, t_out);
        }
        propagate(f, tn);
        amb_forces(s, f, tn, f->amb_a, f->amb_b2, tn <= t_out);
        t = tn;
    }
    f->t_step = t;
    if (t == s->t && t < t_end && !*root) /* no progress (a grazing start): IDA's turn, nothing moved */
        return 0;
    if (t > t_end && !*root) /* the last step ran past the output: the state there */
        t = t_end;
    materialise(s, f, t, 0);
    s->stats.flight_steps += steps;
    s->stats.flight_time += t - s->t;
    s->t = t;
    return 1;
}
