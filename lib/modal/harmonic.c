/*
 * Steady-state (harmonic) unbalance response and the steady starting state.
 *
 * With z' = A z + b(t) and b(t) = Re(B e^{i W t}), B = [0; M^-1 F; 0] (F the complex unbalance
 * forces of touchdown/model.h at W = Omega), the periodic solution is z = Re(Z e^{i W t}) with
 * (i W I - A) Z = B, solved by complex LU. The static sag under gravity solves A z_s = -[0; M^-1 f_g; 0].
 */
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct td_harmonic {
    double omega;
    int nnodes;
    int n;        /* states */
    double *re;   /* n */
    double *im;   /* n */
    double *q_re; /* 4 nnodes: the nodes' displacements, expanded from q (td_system_expand) */
    double *q_im;
};

void td_harmonic_free(td_harmonic **h)
{
    if (!h || !*h)
        return;
    free((*h)->re);
    free((*h)->im);
    free((*h)->q_re);
    free((*h)->q_im);
    free(*h);
    *h = NULL;
}

int td_complex_lu_singular(const gsl_matrix_complex *LU)
{
    size_t i;
    for (i = 0; i < LU->size1; i++) {
        double a = gsl_complex_abs(gsl_matrix_complex_get(LU, i, i));
        if (a == 0.0 || !isfinite(a))
            return 1;
    }
    return 0;
}

td_status td_resonance_error(td_error *err, double W)
{
    return td_error_set(err, TD_ERR_NUMERIC, "modal: i*%g is an eigenvalue of the system (undamped resonance)", W);
}

/* Z (re, im; ss->n entries) of the response to complex forces F = fre + i fim at frequency W. */
static td_status solve_harmonic(const td_state_space *ss, double W, const double *fre, const double *fim, double *zre,
                                double *zim, td_error *err)
{
    size_t n = (size_t)ss->n, i, j;
    gsl_matrix_complex *T = gsl_matrix_complex_alloc(n, n);
    gsl_vector_complex *b = gsl_vector_complex_alloc(n);
    gsl_permutation *p = gsl_permutation_alloc(n);
    td_status st = TD_OK;
    int sign;
    if (!T || !b || !p) {
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the harmonic solve");
        goto done;
    }
    /* b = [0; M^-1 F; 0], real and imaginary parts separately */
    st = td_state_space_load(ss, fre, zre, err);
    if (st == TD_OK)
        st = td_state_space_load(ss, fim, zim, err);
    if (st != TD_OK)
        goto done;
    for (i = 0; i < n; i++)
        gsl_vector_complex_set(b, i, gsl_complex_rect(zre[i], zim[i]));
    /* T = i W I - A */
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            gsl_matrix_complex_set(T, i, j, gsl_complex_rect(-gsl_matrix_get(ss->A, i, j), i == j ? W : 0.0));
    if (gsl_linalg_complex_LU_decomp(T, p, &sign) != GSL_SUCCESS || td_complex_lu_singular(T) ||
        gsl_linalg_complex_LU_svx(T, p, b) != GSL_SUCCESS) {
        st = td_resonance_error(err, W);
        goto done;
    }
    for (i = 0; i < n; i++) {
        zre[i] = GSL_REAL(gsl_vector_complex_get(b, i));
        zim[i] = GSL_IMAG(gsl_vector_complex_get(b, i));
    }
done:
    gsl_permutation_free(p);
    gsl_vector_complex_free(b);
    gsl_matrix_complex_free(T);
    return st;
}

/* Response amplitudes into freshly allocated zre, zim (ss->n each); zero when there is no force. */
static td_status unbalance_response(const td_system *sys, const td_state_space *ss, const td_unbalance *u, int n_u,
                                    double *zre, double *zim, td_error *err)
{
    double *f = malloc(2u * (size_t)sys->ndof * sizeof *f);
    td_status st;
    int i, any = 0;
    if (!f)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the unbalance forces");
    st = td_unbalance_forces(sys, ss->omega, u, n_u, f, f + sys->ndof, err);
    for (i = 0; st == TD_OK && i < 2 * sys->ndof; i++)
        any |= f[i] != 0.0;
    if (st == TD_OK && any)
        st = solve_harmonic(ss, ss->omega, f, f + sys->ndof, zre, zim, err);
    else if (st == TD_OK)
        for (i = 0; i < ss->n; i++)
            zre[i] = zim[i] = 0.0;
    free(f);
    return st;
}

/* A new td_harmonic holding its own copy of the states re, im (n each), its nodes' displacements expanded. */
td_status td_harmonic_from_state(const td_system *sys, double omega, int n, const double *re, const double *im,
                                 td_harmonic **out, td_error *err)
{
    td_harmonic *h = calloc(1, sizeof *h);
    td_status st;
    *out = NULL;
    if (h) {
        h->re = malloc((size_t)n * sizeof *h->re);
        h->im = malloc((size_t)n * sizeof *h->im);
        h->q_re = malloc((size_t)sys->nphys * sizeof *h->q_re);
        h->q_im = malloc((size_t)sys->nphys * sizeof *h->q_im);
    }
    if (!h || !h->re || !h->im || !h->q_re || !h->q_im) {
        td_harmonic_free(&h);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the harmonic response");
    }
    h->omega = omega;
    h->nnodes = sys->nnodes;
    h->n = n;
    memcpy(h->re, re, (size_t)n * sizeof *re);
    memcpy(h->im, im, (size_t)n * sizeof *im);
    st = td_system_expand(sys, h->re, h->q_re, err); /* the displacement rows of the state, q first */
    if (st == TD_OK)
        st = td_system_expand(sys, h->im, h->q_im, err);
    if (st != TD_OK) {
        td_harmonic_free(&h);
        return st;
    }
    *out = h;
    return TD_OK;
}

td_status td_harmonic_compute(const td_system *sys, double omega, const td_unbalance *u, int n_u, td_harmonic **out,
                              td_error *err)
{
    td_state_space ss;
    double *z;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_harmonic_compute: NULL output pointer");
    *out = NULL;
    st = td_state_space_build(sys, omega, &ss, err);
    if (st != TD_OK)
        return st;
    z = malloc(2u * (size_t)ss.n * sizeof *z);
    if (!z) {
        td_state_space_free(&ss);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the harmonic response");
    }
    st = unbalance_response(sys, &ss, u, n_u, z, z + ss.n, err);
    if (st == TD_OK)
        st = td_harmonic_from_state(sys, omega, ss.n, z, z + ss.n, out, err);
    free(z);
    td_state_space_free(&ss);
    return st;
}

double td_harmonic_speed(const td_harmonic *h)
{
    return h ? h->omega : NAN;
}
int td_harmonic_node_count(const td_harmonic *h)
{
    return h ? h->nnodes : 0;
}
int td_harmonic_state_count(const td_harmonic *h)
{
    return h ? h->n : 0;
}

td_status td_harmonic_state(const td_harmonic *h, int i, double *re, double *im)
{
    if (!h || i < 0 || i >= h->n)
        return TD_ERR_INVALID;
    if (re)
        *re = h->re[i];
    if (im)
        *im = h->im[i];
    return TD_OK;
}

td_status td_harmonic_orbit(const td_harmonic *h, int node, td_orbit *o)
{
    int ix, iy;
    if (!h || !o || node < 0 || node >= h->nnodes)
        return TD_ERR_INVALID;
    ix = TD_DOF(node, TD_DOF_X);
    iy = TD_DOF(node, TD_DOF_Y);
    o->x_re = h->q_re[ix];
    o->x_im = h->q_im[ix];
    o->y_re = h->q_re[iy];
    o->y_im = h->q_im[iy];
    o->x_amp = hypot(o->x_re, o->x_im);
    o->y_amp = hypot(o->y_re, o->y_im);
    o->x_phase = atan2(o->x_im, o->x_re);
    o->y_phase = atan2(o->y_im, o->y_re);
    /* x + i y = (X + iY)/2 e^{iWt} + (conj X + i conj Y)/2 e^{-iWt} */
    o->forward = 0.5 * hypot(o->x_re - o->y_im, o->x_im + o->y_re);
    o->backward = 0.5 * hypot(o->x_re + o->y_im, o->x_im - o->y_re);
    o->major = o->forward + o->backward;
    o->minor = fabs(o->forward - o->backward);
    return TD_OK;
}

/* The static problem A z = f has a solution worth having: the reciprocal condition number of A,
 * rows then columns scaled to unit largest entry (LAPACK dgeequ's equilibration: A mixes rows of
 * 1 with rows of K / M), estimated from its pivoted QR, is at least 100 n eps, i.e. the solve's
 * relative error bound n eps / rcond stays below 1 %. A rotor that nothing holds (no bearing and
 * no working AMB: a free rigid-body motion) makes A singular; its rounding leaves rcond at about
 * eps (2e-19 on the rig without AMBs; 7e-9 for the drop case's rig at shaft.refine = 8), so the exact-zero
 * determinant test alone let the LU return a sag of 1e8 m. 1: solvable, 0: singular, -1: no memory. */
static int static_solvable(const gsl_matrix *A)
{
    size_t n = A->size1, i, j;
    gsl_matrix *Q = gsl_matrix_alloc(n, n);
    gsl_vector *tau = gsl_vector_alloc(n), *norm = gsl_vector_alloc(n), *work = gsl_vector_alloc(3 * n);
    gsl_permutation *p = gsl_permutation_alloc(n);
    double rcond = 0.0;
    int sign, ok = -1;
    if (Q && tau && norm && work && p) {
        gsl_matrix_memcpy(Q, A);
        for (i = 0; i < n; i++) { /* rows, then columns, to unit largest entry */
            gsl_vector_view row = gsl_matrix_row(Q, i);
            double big = gsl_vector_max(&row.vector) > -gsl_vector_min(&row.vector) ? gsl_vector_max(&row.vector)
                                                                                    : -gsl_vector_min(&row.vector);
            if (big > 0.0)
                gsl_vector_scale(&row.vector, 1.0 / big);
        }
        for (j = 0; j < n; j++) {
            gsl_vector_view col = gsl_matrix_column(Q, j);
            double big = gsl_vector_max(&col.vector) > -gsl_vector_min(&col.vector) ? gsl_vector_max(&col.vector)
                                                                                    : -gsl_vector_min(&col.vector);
            if (big > 0.0)
                gsl_vector_scale(&col.vector, 1.0 / big);
        }
        ok = gsl_linalg_QRPT_decomp(Q, tau, p, &sign, norm) == GSL_SUCCESS &&
             gsl_linalg_QRPT_rcond(Q, &rcond, work) == GSL_SUCCESS && rcond >= 100.0 * (double)n * DBL_EPSILON;
    }
    gsl_permutation_free(p);
    gsl_vector_free(work);
    gsl_vector_free(norm);
    gsl_vector_free(tau);
    gsl_matrix_free(Q);
    return ok;
}

/* Static state z_s with A z_s = -[0; M^-1 f_g; 0] (real LU), refused when A is singular to
 * rounding (static_solvable). */
static td_status static_state(const td_system *sys, const td_state_space *ss, double *zs, td_error *err)
{
    size_t n = (size_t)ss->n, i;
    gsl_matrix *LU = gsl_matrix_alloc(n, n);
    gsl_permutation *p = gsl_permutation_alloc(n);
    gsl_vector_view x = gsl_vector_view_array(zs, n);
    td_status st;
    int sign, held;
    if (!LU || !p) {
        gsl_matrix_free(LU);
        gsl_permutation_free(p);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the static solve");
    }
    st = td_state_space_load(ss, sys->gravity_load, zs, err);
    if (st == TD_OK && (held = static_solvable(ss->A)) <= 0)
        st = held < 0 ? td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the static solve")
                      : td_error_set(err, TD_ERR_NUMERIC,
                                     "modal: the static deflection under gravity is undefined (the rotor is not "
                                     "held: no bearing or working AMB stops a rigid-body motion)");
    if (st == TD_OK) {
        for (i = 0; i < n; i++)
            zs[i] = -zs[i];
        gsl_matrix_memcpy(LU, ss->A);
        if (gsl_linalg_LU_decomp(LU, p, &sign) != GSL_SUCCESS || gsl_linalg_LU_det(LU, sign) == 0.0 ||
            gsl_linalg_LU_svx(LU, p, &x.vector) != GSL_SUCCESS)
            st = td_error_set(err, TD_ERR_NUMERIC,
                              "modal: the static deflection under gravity is undefined (the rotor is not held)");
    }
    gsl_permutation_free(p);
    gsl_matrix_free(LU);
    return st;
}

static int has_gravity(const td_system *sys)
{
    int i;
    for (i = 0; sys->gravity_load && i < sys->ndof; i++)
        if (sys->gravity_load[i] != 0.0)
            return 1;
    return 0;
}

td_status td_modal_start_state(const td_system *sys, double omega, const td_unbalance *u, int n_u, int with_gravity,
                               double t, double *z, td_error *err)
{
    td_state_space ss;
    double *work;
    td_status st;
    int i;
    if (!z || !isfinite(t))
        return td_error_set(err, TD_ERR_INVALID, "td_modal_start_state: NULL state or non-finite time");
    st = td_state_space_build(sys, omega, &ss, err);
    if (st != TD_OK)
        return st;
    work = malloc(3u * (size_t)ss.n * sizeof *work);
    if (!work) {
        td_state_space_free(&ss);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the start state");
    }
    st = unbalance_response(sys, &ss, u, n_u, work, work + ss.n, err);
    for (i = 0; i < ss.n; i++)
        work[2 * ss.n + i] = 0.0;
    if (st == TD_OK && with_gravity && has_gravity(sys))
        st = static_state(sys, &ss, work + 2 * ss.n, err);
    if (st == TD_OK) {
        double c = cos(omega * t), s = sin(omega * t);
        /* Re((re + i im)(c + i s)) = re c - im s */
        for (i = 0; i < ss.n; i++)
            z[i] = work[i] * c - work[ss.n + i] * s + work[2 * ss.n + i];
    }
    free(work);
    td_state_space_free(&ss);
    return st;
}
