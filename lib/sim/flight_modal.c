/*
 * The closed-form free flight's modal machinery (flight_internal.h): the machine's decomposition
 * and its forcing, probed from the residual, the observed functions, the anchor, the evaluation of
 * the state at any time, and the flight's life cycle.
 */
#include "sim/flight_internal.h"
#include "sim/sampler.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

/* What A depends on: the speed and the AMBs' modes. */
static int machine_key(const td_sim *s, double *key)
{
    int a, n = 0, na = td_model_amb_count(s->model);
    key[n++] = s->machine.omega;
    for (a = 0; a < na; a++)
        key[n++] = (double)s->machine.amb_mode[a];
    return n;
}

/* What b(t) depends on beyond A: the spin angle, the unbalances, the held AMB forces and the caller's
 * held currents (TD_AMB_CURRENT). */
static int forcing_key(const td_sim *s, double *key)
{
    int i, n = 0, na = td_model_amb_count(s->model);
    key[n++] = s->machine.spin_ref;
    key[n++] = s->machine.t_spin_ref;
    for (i = 0; i < s->machine.nu; i++) {
        key[n++] = s->machine.unb[i].magnitude;
        key[n++] = s->machine.unb[i].phase;
    }
    for (i = 0; i < 2 * na; i++)
        key[n++] = s->machine.amb_control[i];
    for (i = 0; i < 2 * na; i++)
        key[n++] = s->machine.amb_current[i];
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
    memset(f->y, 0, sizeof(double) * (size_t)s->dae.neq);
    memcpy(f->y, z, sizeof(double) * (size_t)f->nz);
    td_sim_residual(s, t, f->y, f->yp, f->res);
    for (i = 0; i < f->nz; i++)
        rate[i] = -f->res[i];
    td_sim_mass_solve(s, rate + s->dae.ov);
}

/* Probe size of state i: half the smallest clearance for a displacement (a penalty contact stays
 * out of reach at the centre), 1 in the other states' units; the law is linear, so only the
 * rounding depends on it. */
static double probe_size(const td_sim *s, int i)
{
    double c = INFINITY;
    int k;
    if (i >= s->dae.n)
        return 1.0;
    for (k = 0; k < s->dae.nr; k++)
        c = fmin(c, s->contacts.ret[k].r.clearance);
    return isfinite(c) ? 0.5 * c : 1.0;
}

/* ---- the machine: A and its eigen-decomposition ----------------------------------------- */

/* A in the scaled states z_i / S_i, S the integrator's absolute tolerances (each state in its
 * tolerance's units: the eigenvectors come out balanced, and their checks mean something). */
static void fill_matrix(const td_sim *s, td_sim_flight *f, gsl_matrix *A, const double *S)
{
    double *z = f->b[0];
    int i, j, nz = f->nz;
    memset(z, 0, sizeof(double) * (size_t)nz);
    rates(s, f, s->dae.t, z, f->rate0);
    for (j = 0; j < nz; j++) {
        double h = probe_size(s, j);
        z[j] = h;
        rates(s, f, s->dae.t, z, f->rate);
        z[j] = 0.0;
        for (i = 0; i < nz; i++)
            gsl_matrix_set(A, (size_t)i, (size_t)j, (f->rate[i] - f->rate0[i]) / h * S[j] / S[i]);
    }
}

/* V <- S V, V^-1 <- V^-1 S^-1: the modes of the unscaled states. */
static void unscale_modes(td_sim_flight *f, const double *S)
{
    size_t i, j, nz = (size_t)f->nz;
    for (i = 0; i < nz; i++)
        for (j = 0; j < nz; j++) {
            f->V[i * nz + j] *= S[i];
            f->Vinv[i * nz + j] /= S[j];
        }
}

/* The decomposition's quality: the largest of max_i |A v_j - lambda_j v_j| / (|lambda_j| max_i |v_j|)
 * over the modes j (the phase error per radian of each mode) and max |V V^-1 - I|. */
static double decomposition_error(td_sim_flight *f, const gsl_matrix *A)
{
    int i, j, k, nz = f->nz;
    double worst = 0.0;
    double complex *vj = f->work, *wj = f->work + nz; /* column j of V and of V^-1, contiguous */
    for (j = 0; j < nz; j++) {
        double res = 0.0, vmax = 0.0;
        for (k = 0; k < nz; k++) {
            vj[k] = f->V[k * nz + j];
            wj[k] = f->Vinv[k * nz + j];
        }
        for (i = 0; i < nz; i++) {
            const double *ai = A->data + (size_t)i * A->tda; /* row i: gsl_matrix_get(A, i, k) = ai[k] */
            const double complex *vi = f->V + (size_t)i * (size_t)nz;
            double complex av = -f->V[i * nz + j] * f->lam[j], vv = 0.0;
            for (k = 0; k < nz; k++) {
                av += ai[k] * vj[k];
                vv += vi[k] * wj[k];
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

/* The kept modes' columns of V, real and imaginary parts apart, mode after mode (f->vr, f->vi):
 * the state is sum_k Re(V_ik a_k) over them, and this order sums it row-wise in one pass. */
static void kept_columns(td_sim_flight *f)
{
    size_t i, k, nz = (size_t)f->nz;
    for (k = 0; k < (size_t)f->nkeep; k++)
        for (i = 0; i < nz; i++) {
            double complex v = f->V[i * nz + (size_t)f->keep[k]];
            f->vr[k * nz + i] = creal(v);
            f->vi[k * nz + i] = cimag(v);
        }
}

/* A's modes; 0 if A cannot be trusted to them (defective, ill-conditioned, a zero or resonant
 * eigenvalue, a mode growing faster than the bounds allow: by more than e over a step of h_max; with
 * a current held between samples the magnets' negative stiffness makes modes grow at ~144 s^-1, which
 * 1e-4 s allows and FLIGHT_MAX_STEP does not). */
static int decompose(const td_sim *s, td_sim_flight *f, const double *scale)
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
        fill_matrix(s, f, A, scale);
        gsl_matrix_memcpy(Acopy, A);
        gsl_eigen_nonsymmv_params(1, w);
        ok = gsl_eigen_nonsymmv(A, eval, evec, w) == GSL_SUCCESS && invert_modes(f, evec);
    }
    for (j = 0; ok && j < nz; j++) {
        gsl_complex l = gsl_vector_complex_get(eval, j);
        f->lam[j] = GSL_REAL(l) + I * GSL_IMAG(l);
        if (!(cabs(f->lam[j]) > 0.0) || GSL_REAL(l) * f->h_max > 1.0)
            ok = 0;
        f->grow[j] = exp(fmax(0.0, GSL_REAL(l)) * f->h_max);
    }
    if (ok)
        ok = decomposition_error(f, Acopy) < FLIGHT_DECOMPOSITION_TOL;
    if (ok) {
        unscale_modes(f, scale);
        pair_modes(f);
        kept_columns(f);
    }
    gsl_eigen_nonsymmv_free(w);
    gsl_matrix_complex_free(evec);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(Acopy);
    gsl_matrix_free(A);
    return ok;
}

/* ---- the forcing --------------------------------------------------------------------------- */

/* (V^-1 x)_i, x complex */
static double complex modal_row(const td_sim_flight *f, int i, const double complex *x)
{
    double complex acc = 0.0;
    const double complex *row = f->Vinv + (size_t)i * (size_t)f->nz;
    int j;
    for (j = 0; j < f->nz; j++)
        acc += row[j] * x[j];
    return acc;
}

/* out = V^-1 x, x complex */
static void to_modal(const td_sim_flight *f, const double complex *x, double complex *out)
{
    int i;
    for (i = 0; i < f->nz; i++)
        out[i] = modal_row(f, i, x);
}

/* The block of first-order state i: 0 the displacements q, 1 the velocities v, 2 the AMB states w. */
static int forcing_block(const td_sim *s, int i)
{
    return i < s->dae.n ? 0 : i < 2 * s->dae.n ? 1 : 2;
}

/* b(t) at tf, tf + T/4, tf + T/2 (T = 2 pi / W) gives b0, bc, bs; tf + T/8 checks that b is
 * that harmonic. Returns 0 if it is not. */
static int probe_forcing(const td_sim *s, td_sim_flight *f)
{
    double *z = f->rate0, w = f->omega, q = w != 0.0 ? M_PI / w : 0.0;
    double complex *bp = f->e, *bm = f->d; /* work until the anchor (which makes e stale) */
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

/* The AMB force observations' values at z = 0 with what is held now: the caller's force
 * (TD_AMB_EXTERNAL, part of the forcing, not of the machine), a sampled law's current (ki i where
 * tau = 0: the force follows the held current at once; 0 behind an amplifier lag, whose state
 * carries it). */
static void held_offsets(const td_sim *s, td_sim_flight *f)
{
    int k;
    memset(f->y, 0, sizeof(double) * (size_t)s->dae.neq);
    for (k = 0; k < s->sys->n_amb_axes; k++)
        f->obs[2 * s->dae.nr + k].offset = td_sim_amb_axis_force(s, k, f->y);
}

/* The particular solution's modal coefficients; 0 if the forcing is not harmonic at the speed or
 * resonant with a mode. */
static int build_forcing(const td_sim *s, td_sim_flight *f)
{
    int j;
    f->tf = s->dae.t;
    f->omega = s->machine.omega;
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
    for (j = 0; j < f->nheld; j++)
        f->held[j] = s->machine.held_current[f->held_axis[j]];
    held_offsets(s, f); /* a held force may have changed without the machine */
    return 1;
}

/* G: V^-1 times the change of z' (at z = 0) per ampere held on each sampled axis, probed from the
 * residual like A (it is linear in the held current, so only the rounding depends on the probe). */
static void probe_held(td_sim *s, td_sim_flight *f)
{
    double *z = f->b[0];
    double complex *col = f->work, *mod = f->work + f->nz;
    int c, i, nz = f->nz;
    memset(z, 0, sizeof(double) * (size_t)nz);
    for (c = 0; c < f->nheld; c++) {
        double *u = &s->machine.held_current[f->held_axis[c]], u0 = *u;
        rates(s, f, s->dae.t, z, f->rate0);
        *u = u0 + 1.0;
        rates(s, f, s->dae.t, z, f->rate);
        *u = u0;
        for (i = 0; i < nz; i++)
            col[i] = f->rate[i] - f->rate0[i];
        to_modal(f, col, mod);
        for (i = 0; i < nz; i++)
            f->G[(size_t)i * (size_t)f->nheld + (size_t)c] = mod[i];
    }
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
    for (k = 0; k < s->dae.nr; k++) {
        memset(a, 0, sizeof(double) * (size_t)nz);
        a[s->dae.oq + s->contacts.ret[k].dx] = 1.0;
        set_obs_row(f, &f->obs[2 * k], a, 0.0);
        a[s->dae.oq + s->contacts.ret[k].dx] = 0.0;
        a[s->dae.oq + s->contacts.ret[k].dy] = 1.0;
        set_obs_row(f, &f->obs[2 * k + 1], a, 0.0);
    }
    for (k = 0; k < s->sys->n_amb_axes; k++) {
        double f0;
        memset(f->y, 0, sizeof(double) * (size_t)s->dae.neq);
        f0 = td_sim_amb_axis_force(s, k, f->y);
        for (i = 0; i < nz; i++) {
            double h = probe_size(s, i);
            f->y[i] = h;
            a[i] = (td_sim_amb_axis_force(s, k, f->y) - f0) / h;
            f->y[i] = 0.0;
        }
        set_obs_row(f, &f->obs[2 * s->dae.nr + k], a, f0);
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
        b->seen_t = NAN;
        for (j = 0; j < f->nz; j++) {
            b->h0 += b->w[j] * f->p0[j];
            b->hp += b->w[j] * f->pp[j];
            b->hm += b->w[j] * f->pm[j];
        }
        b->h0_abs = cabs(b->h0);
        b->h_abs = cabs(b->hp) + cabs(b->hm);
    }
}

/* ---- the anchor and evaluation -------------------------------------------------------------- */

double complex td_sim_flight_phase(const td_sim_flight *f, double t)
{
    return cexp(I * f->omega * (t - f->tf));
}

/* The particular solution's modal coordinates at t into out. */
static void particular(const td_sim_flight *f, double t, double complex *out)
{
    double complex ep = td_sim_flight_phase(f, t), em = conj(ep);
    int j;
    for (j = 0; j < f->nz; j++)
        out[j] = f->p0[j] + f->pp[j] * ep + f->pm[j] * em;
}

/* The observations' homogeneous parts for the amplitudes d at the anchor ta. */
static void anchor_observations(td_sim_flight *f)
{
    int i, o;
    f->t_e = f->t_e2 = NAN; /* e is stale, and the one kept before it */
    for (o = 0; o < f->nobs; o++) {
        flight_obs *b = &f->obs[o];
        for (i = 0; i < f->nkeep; i++) { /* the kept modes: the others are never summed */
            int j = f->keep[i];
            double l = cabs(f->lam[j]);
            b->c[j] = f->weight[j] * b->w[j] * f->d[j];
            b->m0[j] = cabs(b->c[j]);
            b->m1[j] = b->m0[j] * l;
            b->m2[j] = b->m1[j] * l;
        }
        b->seen_t = NAN;
    }
    f->anchored = 1;
}

/* Anchor the flight at s->dae.t on the state in s->dae.y. */
static void anchor(td_sim *s, td_sim_flight *f)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    int j, nz = f->nz;
    for (j = 0; j < nz; j++)
        f->e[j] = y[j];
    for (j = 0; j < f->nkeep; j++) /* the kept modes' amplitudes: the others are never summed */
        f->d[f->keep[j]] = modal_row(f, f->keep[j], f->e);
    particular(f, s->dae.t, f->e);
    for (j = 0; j < nz; j++)
        f->d[j] -= f->e[j];
    f->ta = s->dae.t;
    anchor_observations(f);
}

/* e_j = e^{lambda_j (t - ta)} and the bound factors |e_j| grow_j, for the time t. The last two
 * times' are kept (the flight's bookkeeping goes back and forth between a step's ends and the
 * output time): the earlier one is swapped back in as it was computed. */
void td_sim_flight_propagate(td_sim_flight *f, double t)
{
    double dt = t - f->ta, *ae = f->ae, te = f->t_e;
    double complex *e = f->e, ep = f->ep;
    int i;
    if (t == f->t_e)
        return;
    f->e = f->e2, f->ae = f->ae2, f->t_e = f->t_e2, f->ep = f->ep2;
    f->e2 = e, f->ae2 = ae, f->t_e2 = te, f->ep2 = ep;
    if (t == f->t_e)
        return;
    f->ep = td_sim_flight_phase(f, t); /* shared by every observation at t */
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double m = exp(creal(f->lam[j]) * dt);
        f->e[j] = m * (cos(cimag(f->lam[j]) * dt) + I * sin(cimag(f->lam[j]) * dt));
        f->ae[j] = m * f->grow[j];
    }
    f->t_e = t;
}

/*
 * A held current steps by du at t = s->dae.t: the constant forcing beta0 by G du, so p0 = -beta0 /
 * lambda by -G du / lambda (eq. of flight_internal.h), and the homogeneous amplitudes, re-anchored at
 * t, by the opposite amount: a(t) = d e^{lambda (t - ta)} + p(t) is unchanged; the AMB forces'
 * offsets follow the held currents. O(nz nheld + nobs nz) per sample, against four residual probes
 * and three O(nz^2) projections for a new forcing.
 */
void td_sim_flight_shift_held(td_sim *s, td_sim_flight *f, int reanchor)
{
    double complex *dp = f->work;
    int c, i, j, nz = f->nz;
    for (j = 0; j < nz; j++)
        dp[j] = 0.0;
    for (c = 0; c < f->nheld; c++) {
        double u = s->machine.held_current[f->held_axis[c]], du = u - f->held[c];
        f->held[c] = u;
        for (j = 0; du != 0.0 && j < nz; j++)
            dp[j] -= f->G[(size_t)j * (size_t)f->nheld + (size_t)c] * du;
    }
    for (j = 0; j < nz; j++) {
        dp[j] /= f->lam[j];
        f->p0[j] += dp[j];
    }
    held_offsets(s, f);
    observe_forcing(f);
    if (!reanchor) {
        f->anchored = 0;
        return;
    }
    td_sim_flight_propagate(f, s->dae.t);
    for (i = 0; i < f->nkeep; i++) { /* the kept modes: the others are never summed */
        j = f->keep[i];
        f->d[j] = f->d[j] * f->e[j] - dp[j];
    }
    f->ta = s->dae.t;
    anchor_observations(f);
}

/* The constant and harmonic parts of observation b (phase ep) added to its modal sums r. */
static void observe_tail(const td_sim_flight *f, const flight_obs *b, double complex ep, flight_val *r)
{
    double w = fabs(f->omega), h = b->h_abs;
    r->v += creal(b->h0 + b->hp * ep + b->hm * conj(ep));
    r->d += creal(I * f->omega * (b->hp * ep - b->hm * conj(ep)));
    r->b0 += b->h0_abs + h;
    r->b1 += w * h;
    r->b2 += w * w * h;
}

/* Observation o at the time of the last propagate (t). Kept (flight_obs.seen): the same t again
 * with the same propagate gives the same bits without the sums (e at t depends on t and the anchor
 * only, and an anchor or a forcing clears what was kept). */
flight_val td_sim_flight_observe(const td_sim_flight *f, int o, double t)
{
    flight_obs *b = &f->obs[o];
    double complex ep;
    flight_val r = {0.0, 0.0, 0.0, 0.0, 0.0};
    int i;
    if (t == b->seen_t && t == f->t_e)
        return b->seen;
    ep = t == f->t_e ? f->ep : td_sim_flight_phase(f, t);
    for (i = 0; i < f->nkeep; i++) { /* the real parts of sum c e and sum c e lambda, as complex */
        int j = f->keep[i];
        double ce[2];
        flight_mul(b->c[j], f->e[j], ce);
        r.v += ce[0];
        r.d += ce[0] * creal(f->lam[j]) - ce[1] * cimag(f->lam[j]);
        r.b0 += b->m0[j] * f->ae[j];
        r.b1 += b->m1[j] * f->ae[j];
        r.b2 += b->m2[j] * f->ae[j];
    }
    observe_tail(f, b, ep, &r);
    b->seen_t = t;
    b->seen = r;
    b->seen_bound = NAN;
    return r;
}

/* Observations o1, o2 at the last propagate (t) into r1, r2, as td_sim_flight_observe gives and keeps
 * them: the two sums side by side in packed doubles where neither is kept already. */
void td_sim_flight_observe2(const td_sim_flight *f, int o1, int o2, double t, flight_val *r1, flight_val *r2)
{
#ifdef __SSE2__
    flight_obs *a = &f->obs[o1], *b = &f->obs[o2];
    double out[5][2];
    __m128d v = _mm_setzero_pd(), d = v, b0 = v, b1 = v, b2 = v;
    int i, q;
    if ((t == a->seen_t || t == b->seen_t) || t != f->t_e) {
#endif
        *r1 = td_sim_flight_observe(f, o1, t);
        *r2 = td_sim_flight_observe(f, o2, t);
#ifdef __SSE2__
        return;
    }
    for (i = 0; i < f->nkeep; i++) { /* each lane td_sim_flight_observe's sum for its observation */
        int j = f->keep[i];
        __m128d cr = _mm_set_pd(creal(b->c[j]), creal(a->c[j])), ci = _mm_set_pd(cimag(b->c[j]), cimag(a->c[j]));
        __m128d er = _mm_set1_pd(creal(f->e[j])), ei = _mm_set1_pd(cimag(f->e[j])), ae = _mm_set1_pd(f->ae[j]);
        __m128d ce0 = _mm_sub_pd(_mm_mul_pd(cr, er), _mm_mul_pd(ci, ei));
        __m128d ce1 = _mm_add_pd(_mm_mul_pd(cr, ei), _mm_mul_pd(ci, er));
        v = _mm_add_pd(v, ce0);
        d = _mm_add_pd(d, _mm_sub_pd(_mm_mul_pd(ce0, _mm_set1_pd(creal(f->lam[j]))),
                                     _mm_mul_pd(ce1, _mm_set1_pd(cimag(f->lam[j])))));
        b0 = _mm_add_pd(b0, _mm_mul_pd(_mm_set_pd(b->m0[j], a->m0[j]), ae));
        b1 = _mm_add_pd(b1, _mm_mul_pd(_mm_set_pd(b->m1[j], a->m1[j]), ae));
        b2 = _mm_add_pd(b2, _mm_mul_pd(_mm_set_pd(b->m2[j], a->m2[j]), ae));
    }
    _mm_storeu_pd(out[0], v);
    _mm_storeu_pd(out[1], d);
    _mm_storeu_pd(out[2], b0);
    _mm_storeu_pd(out[3], b1);
    _mm_storeu_pd(out[4], b2);
    for (q = 0; q < 2; q++) {
        flight_obs *o = q ? b : a;
        flight_val r = {out[0][q], out[1][q], out[2][q], out[3][q], out[4][q]};
        observe_tail(f, o, f->ep, &r);
        o->seen_t = t;
        o->seen = r;
        o->seen_bound = NAN;
        *(q ? r2 : r1) = r;
    }
#endif
}

/* The modal coordinates at t (propagated), weighted for the kept modes, into f->b-sized complex
 * work `a`; with `rate`, their time derivatives into `da`. */
static void modal_state(const td_sim_flight *f, double t, double complex *a, double complex *da)
{
    double complex ep = t == f->t_e ? f->ep : td_sim_flight_phase(f, t), em = conj(ep);
    int i;
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double complex h = f->d[j] * f->e[j], p = f->pp[j] * ep, m = f->pm[j] * em;
        a[i] = f->weight[j] * (h + f->p0[j] + p + m);
        if (da)
            da[i] = f->weight[j] * (f->lam[j] * h + I * f->omega * (p - m));
    }
}

/* The states z = Re(V a) over the kept modes (a: nkeep, weighted, modal_state) into y: per state the
 * same terms in the same order as a row of V times a, summed for all states at once. */
static void state_sum(const td_sim_flight *f, const double complex *a, double *y)
{
    int i, k, nz = f->nz;
    for (i = 0; i < nz; i++)
        y[i] = 0.0;
    for (k = 0; k + 1 < f->nkeep; k += 2) { /* two modes a pass: y_i + term_k, then + term_k+1 */
        const double *vr = f->vr + (size_t)k * (size_t)nz, *vi = f->vi + (size_t)k * (size_t)nz;
        const double *wr = vr + nz, *wi = vi + nz;
        double ar = creal(a[k]), ai = cimag(a[k]), br = creal(a[k + 1]), bi = cimag(a[k + 1]);
        i = 0;
#ifdef __SSE2__
        { /* two rows at a time in packed doubles: each lane the scalar loop's operations, the same bits */
            __m128d par = _mm_set1_pd(ar), pai = _mm_set1_pd(ai), pbr = _mm_set1_pd(br), pbi = _mm_set1_pd(bi);
            for (; i + 1 < nz; i += 2) {
                __m128d t = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(vr + i), par), _mm_mul_pd(_mm_loadu_pd(vi + i), pai));
                __m128d u = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(wr + i), pbr), _mm_mul_pd(_mm_loadu_pd(wi + i), pbi));
                _mm_storeu_pd(y + i, _mm_add_pd(_mm_add_pd(_mm_loadu_pd(y + i), t), u));
            }
        }
#endif
        for (; i < nz; i++)
            y[i] = (y[i] + (vr[i] * ar - vi[i] * ai)) + (wr[i] * br - wi[i] * bi);
    }
    for (; k < f->nkeep; k++) {
        const double *vr = f->vr + (size_t)k * (size_t)nz, *vi = f->vi + (size_t)k * (size_t)nz;
        double ar = creal(a[k]), ai = cimag(a[k]);
        for (i = 0; i < nz; i++)
            y[i] += vr[i] * ar - vi[i] * ai;
    }
}

/* The state z at t into y (and its rate into yp with `rate`; the rest of yp: zero in free flight). */
void td_sim_flight_materialise(td_sim *s, td_sim_flight *f, double t, int rate)
{
    double *y = N_VGetArrayPointer(s->dae.y), *yp = N_VGetArrayPointer(s->dae.yp);
    double complex *a = f->work, *da = rate ? f->work + f->nz : NULL;
    int i;
    td_sim_flight_propagate(f, t);
    modal_state(f, t, a, da);
    state_sum(f, a, y);
    if (rate)
        state_sum(f, da, yp);
    for (i = f->nz; rate && i < s->dae.neq; i++)
        yp[i] = 0.0;
}

/* The displacements z at t into y[0..nz) from the anchored flight, leaving the flight's own cache
 * (e, t_e) untouched: the modal coordinates go to the caller's `work` (2 neq doubles). */
int td_sim_flight_peek(const td_sim *s, double t, double *y, double *work)
{
    const td_sim_flight *f = s->flight;
    double complex *e = (double complex *)(void *)work;
    double complex ep, em;
    int i;
    if (!f || !f->anchored)
        return 0;
    ep = td_sim_flight_phase(f, t);
    em = conj(ep);
    for (i = 0; i < f->nkeep; i++) {
        int j = f->keep[i];
        double dt = t - f->ta, m = exp(creal(f->lam[j]) * dt);
        double complex h = f->d[j] * (m * (cos(cimag(f->lam[j]) * dt) + I * sin(cimag(f->lam[j]) * dt)));
        e[i] = f->weight[j] * (h + f->p0[j] + f->pp[j] * ep + f->pm[j] * em);
    }
    state_sum(f, e, y);
    return 1;
}

void td_sim_flight_rates(td_sim *s)
{
    if (s->flight && s->flight->anchored)
        td_sim_flight_materialise(s, s->flight, s->dae.t, 1);
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
    free(f->vr);
    free(f->vi);
    free(f->grow);
    free(f->keep);
    free(f->order);
    free(f->weight);
    free(f->work);
    free(f->p0);
    free(f->pp);
    free(f->pm);
    free(f->held_axis);
    free(f->held);
    free(f->G);
    free(f->d);
    free(f->e);
    free(f->ae);
    free(f->e2);
    free(f->ae2);
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
    o->seen_t = o->seen_bound = NAN;
    return o->w && o->c && o->m0 && o->m1 && o->m2;
}

/* The sampled laws' output axes (f->held_axis, in law order) and the longest step their periods
 * allow (f->h_max); 0 when out of memory. */
static int alloc_held(const td_sim *s, td_sim_flight *f)
{
    const td_sim_sampler *sp = s->sampler;
    int i, o, n = 0;
    f->h_max = FLIGHT_MAX_STEP;
    for (i = 0; sp && i < sp->n; i++) {
        f->h_max = fmin(f->h_max, 1.0 / sp->law[i].rate);
        n += s->sys->laws[sp->law[i].law].nout;
    }
    if (n == 0)
        return 1;
    f->held_axis = calloc((size_t)n, sizeof *f->held_axis);
    f->held = calloc((size_t)n, sizeof *f->held);
    f->G = calloc((size_t)n * (size_t)f->nz, sizeof *f->G);
    if (!f->held_axis || !f->held || !f->G)
        return 0;
    for (i = 0; i < sp->n; i++)
        for (o = 0; o < s->sys->laws[sp->law[i].law].nout; o++) {
            int a = s->sys->laws[sp->law[i].law].out_axis[o], c = 0;
            while (c < f->nheld && f->held_axis[c] != a) /* each axis once, however many laws name it */
                c++;
            if (c == f->nheld)
                f->held_axis[f->nheld++] = a;
        }
    return 1;
}

/* The flight's arrays; 0 when out of memory (the integrator then carries the machine). */
static int flight_alloc(td_sim *s)
{
    td_sim_flight *f = calloc(1, sizeof *f);
    size_t nz = (size_t)(2 * s->dae.n + s->dae.nw), neq = (size_t)s->dae.neq, nk, na;
    int i, ok = f != NULL;
    if (!ok)
        return 0;
    s->flight = f;
    f->nz = (int)nz;
    f->nobs = 2 * s->dae.nr + s->sys->n_amb_axes;
    nk = (size_t)(3 + 2 * s->machine.nu + 5 * td_model_amb_count(s->model));
    f->machine_key = calloc(nk, sizeof(double));
    f->forcing_key = calloc(nk, sizeof(double));
    f->key_work = calloc(nk, sizeof(double));
    f->lam = calloc(nz, sizeof *f->lam);
    f->V = calloc(nz * nz, sizeof *f->V);
    f->Vinv = calloc(nz * nz, sizeof *f->Vinv);
    f->vr = calloc(nz * nz, sizeof *f->vr);
    f->vi = calloc(nz * nz, sizeof *f->vi);
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
    f->e2 = calloc(nz, sizeof *f->e2);
    f->ae2 = calloc(nz, sizeof *f->ae2);
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
    ok = ok && f->vr && f->vi;
    ok = ok && f->machine_key && f->forcing_key && f->key_work && f->lam && f->V && f->Vinv && f->grow && f->keep &&
         f->order && f->weight && f->work && f->p0 && f->pp && f->pm && f->d && f->e && f->ae && f->e2 && f->ae2 &&
         f->y && f->yp && f->res && f->rate && f->rate0 && f->obs;
    for (i = 0; ok && i < f->nobs; i++)
        ok = alloc_obs(&f->obs[i], nz);
    ok = ok && alloc_held(s, f);
    f->nkey_m = f->nkey_f = -1;
    f->t_root = -INFINITY;
    f->t_e = f->t_e2 = NAN;
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

/* 1 if a held current differs from the one the forcing was made for. */
static int held_changed(const td_sim *s, const td_sim_flight *f)
{
    int c;
    for (c = 0; c < f->nheld; c++)
        if (s->machine.held_current[f->held_axis[c]] != f->held[c])
            return 1;
    return 0;
}

/* The decomposition and the forcing brought up to date with the machine; 0 if the flight cannot
 * carry it. */
int td_sim_flight_ready(td_sim *s, const double *scale)
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
        f->machine_ok = decompose(s, f, scale);
        if (f->machine_ok) {
            build_observations(s, f);
            probe_held(s, f);
        }
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
    if (held_changed(s, f)) /* a sample taken since (at a stop the flight did not reach) */
        td_sim_flight_shift_held(s, f, 0);
    if (!f->anchored) {
        anchor(s, f);
        f->t_step = -INFINITY;
    }
    return 1;
}
