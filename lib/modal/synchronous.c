/*
 * The synchronous unbalance response in second-order (dynamic-stiffness) form, for the many speeds
 * of the API 617 sweep (api617.c).
 *
 * td_harmonic_compute solves (i W I - A) Z = [0; M^-1 F; 0] with the first-order A of state_space.c:
 * a Cholesky factor of M and a solve with its ndof x n right-hand side at every speed, then a complex
 * LU of order n = 2 ndof + nfilter. With Z = [Q; V; S], M v' = R z + F (R = [R_q | R_v | R_s], the
 * right-hand blocks of state_space.c) and the filter rows s' = P z (P = [P_q | P_v | P_s]), the rows
 * of Z read
 *
 *   V = i W Q,
 *   (i W I - P_s) S = (P_q + i W P_v) Q = (i W I - P_s) X Q,
 *   (-W^2 M - R_q - i W R_v - R_s X) Q = F,
 *
 * the same solution, by elimination: one complex LU of order ndof (about 1/8 of the flops) after a
 * small one of order nfilter, and no M^-1. The roundings differ from td_harmonic_compute's, so the
 * results agree to rounding only: the simulations' start state keeps td_harmonic_compute.
 */
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <math.h>
#include <stdlib.h>

struct td_synchronous {
    const td_system *sys;
    int nd, nf, n;
    int mass_ok;            /* M is positive definite (as the first-order form requires) */
    gsl_matrix *M;          /* nd x nd */
    gsl_matrix *R;          /* nd x n: the right-hand blocks at the current speed */
    gsl_matrix *P;          /* nf x n: the filter rows (speed-independent) */
    gsl_matrix_complex *D;  /* nd x nd: the dynamic stiffness, then its LU */
    gsl_matrix_complex *Sf; /* nf x nf: i W I - P_s, then its LU */
    gsl_matrix_complex *X;  /* nf x nd: S = X Q */
    gsl_permutation *pd, *pf;
    gsl_vector_complex *q; /* nd */
    gsl_vector_complex *x; /* nf: a column of X */
    double *f;             /* 2 nd: the forces, re then im */
    double *z;             /* 2 n: the state, re then im */
};

void td_synchronous_free(td_synchronous **s)
{
    if (!s || !*s)
        return;
    gsl_matrix_free((*s)->M);
    gsl_matrix_free((*s)->R);
    gsl_matrix_free((*s)->P);
    gsl_matrix_complex_free((*s)->D);
    gsl_matrix_complex_free((*s)->Sf);
    gsl_matrix_complex_free((*s)->X);
    gsl_permutation_free((*s)->pd);
    gsl_permutation_free((*s)->pf);
    gsl_vector_complex_free((*s)->q);
    gsl_vector_complex_free((*s)->x);
    free((*s)->f);
    free((*s)->z);
    free(*s);
    *s = NULL;
}

/* The speed-independent parts: M (and whether it is positive definite) and the filter rows P. */
static void fill_constant(td_synchronous *s)
{
    size_t nd = (size_t)s->nd, i, j;
    td_entry_sink mk = {NULL, NULL, 0, 1};
    gsl_matrix *L = gsl_matrix_alloc(nd, nd);
    mk.dense = s->M;
    gsl_matrix_set_zero(s->M);
    td_entry_add_matrix(&mk, s->sys->M, 0, 1.0);
    if (L) { /* as factor_mass of state_space.c refuses it */
        gsl_matrix_memcpy(L, s->M);
        s->mass_ok = gsl_linalg_cholesky_decomp1(L) == GSL_SUCCESS;
    }
    gsl_matrix_free(L);
    if (s->nf > 0) { /* the rows 2 nd .. n of the first-order A, shifted to row 0 */
        gsl_matrix *A = gsl_matrix_calloc((size_t)s->n, (size_t)s->n);
        td_entry_sink ak = {NULL, NULL, 0, 1};
        ak.dense = A;
        if (A) {
            td_state_space_filter_rows(s->sys, &ak);
            for (i = 0; i < (size_t)s->nf; i++)
                for (j = 0; j < (size_t)s->n; j++)
                    gsl_matrix_set(s->P, i, j, gsl_matrix_get(A, 2 * nd + i, j));
        } else
            s->mass_ok = -1;
        gsl_matrix_free(A);
    }
}

td_status td_synchronous_create(const td_system *sys, td_synchronous **out, td_error *err)
{
    td_synchronous *s;
    size_t nd, nf, one = 1;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_synchronous_create: NULL output pointer");
    *out = NULL;
    if (!sys)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL system");
    if (td_state_space_supported(sys, err) != TD_OK)
        return TD_ERR_INVALID;
    td_modal_gsl_quiet();
    s = calloc(1, sizeof *s);
    if (!s)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the synchronous response");
    s->sys = sys;
    s->nd = sys->ndof;
    s->nf = sys->n_controller_states;
    s->n = td_modal_state_count(sys);
    nd = (size_t)s->nd;
    nf = (size_t)(s->nf > 0 ? s->nf : 1); /* GSL has no empty matrices */
    s->M = gsl_matrix_alloc(nd, nd);
    s->R = gsl_matrix_alloc(nd, (size_t)s->n);
    s->P = gsl_matrix_calloc(nf, (size_t)s->n);
    s->D = gsl_matrix_complex_alloc(nd, nd);
    s->Sf = gsl_matrix_complex_alloc(nf, nf);
    s->X = gsl_matrix_complex_calloc(nf, nd);
    s->pd = gsl_permutation_alloc(nd);
    s->pf = gsl_permutation_alloc(nf);
    s->q = gsl_vector_complex_alloc(nd);
    s->x = gsl_vector_complex_alloc(nf > one ? nf : one);
    s->f = malloc(2 * nd * sizeof *s->f);
    s->z = malloc(2u * (size_t)s->n * sizeof *s->z);
    if (s->M && s->R && s->P && s->D && s->Sf && s->X && s->pd && s->pf && s->q && s->x && s->f && s->z)
        fill_constant(s);
    if (!s->M || !s->R || !s->P || !s->D || !s->Sf || !s->X || !s->pd || !s->pf || !s->q || !s->x || !s->f || !s->z ||
        s->mass_ok < 0) {
        td_synchronous_free(&s);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the synchronous response");
    }
    *out = s;
    return TD_OK;
}

/* A zero LU pivot (or a non-finite one): the matrix is singular. */
static int lu_singular(const gsl_matrix_complex *LU)
{
    size_t i;
    for (i = 0; i < LU->size1; i++) {
        double a = gsl_complex_abs(gsl_matrix_complex_get(LU, i, i));
        if (a == 0.0 || !isfinite(a))
            return 1;
    }
    return 0;
}

/* X = (i W I - P_s)^-1 (P_q + i W P_v); 0 when i W I - P_s is singular (i W is a root of the filters alone). */
static int filter_elimination(td_synchronous *s, double W)
{
    size_t nd = (size_t)s->nd, nf = (size_t)s->nf, i, j;
    int sign;
    for (i = 0; i < nf; i++) {
        for (j = 0; j < nf; j++)
            gsl_matrix_complex_set(s->Sf, i, j,
                                   gsl_complex_rect(-gsl_matrix_get(s->P, i, 2 * nd + j), i == j ? W : 0.0));
        for (j = 0; j < nd; j++)
            gsl_matrix_complex_set(s->X, i, j,
                                   gsl_complex_rect(gsl_matrix_get(s->P, i, j), W * gsl_matrix_get(s->P, i, nd + j)));
    }
    if (gsl_linalg_complex_LU_decomp(s->Sf, s->pf, &sign) != GSL_SUCCESS || lu_singular(s->Sf))
        return 0;
    for (j = 0; j < nd; j++) {
        gsl_vector_complex_view col = gsl_matrix_complex_column(s->X, j);
        gsl_vector_complex_view x = gsl_vector_complex_subvector(s->x, 0, nf);
        gsl_vector_complex_memcpy(&x.vector, &col.vector);
        if (gsl_linalg_complex_LU_solve(s->Sf, s->pf, &x.vector, &col.vector) != GSL_SUCCESS)
            return 0;
    }
    return 1;
}

/* D = -W^2 M - R_q - i W R_v - R_s X (the right-hand blocks R at speed W already in s->R). */
static void dynamic_stiffness(td_synchronous *s, double W)
{
    size_t nd = (size_t)s->nd, nf = (size_t)s->nf, i, j, k;
    for (i = 0; i < nd; i++)
        for (j = 0; j < nd; j++)
            gsl_matrix_complex_set(s->D, i, j,
                                   gsl_complex_rect(-W * W * gsl_matrix_get(s->M, i, j) - gsl_matrix_get(s->R, i, j),
                                                    -W * gsl_matrix_get(s->R, i, nd + j)));
    for (i = 0; i < nd; i++)
        for (k = 0; k < nf; k++) {
            double r = gsl_matrix_get(s->R, i, 2 * nd + k);
            if (r == 0.0) /* R_s is sparse: the force of a lag state, a law's current */
                continue;
            for (j = 0; j < nd; j++) {
                gsl_complex *d = gsl_matrix_complex_ptr(s->D, i, j);
                gsl_complex xv = gsl_matrix_complex_get(s->X, k, j);
                GSL_SET_COMPLEX(d, GSL_REAL(*d) - r * GSL_REAL(xv), GSL_IMAG(*d) - r * GSL_IMAG(xv));
            }
        }
}

/* The state Z = [Q; i W Q; X Q] into s->z (re then im) from the force F (s->f); 0 when singular. */
static int solve_state(td_synchronous *s, double W)
{
    size_t nd = (size_t)s->nd, nf = (size_t)s->nf, n = (size_t)s->n, i, j;
    double *re = s->z, *im = s->z + n;
    int sign;
    td_entry_sink rk = {NULL, NULL, 0, 1};
    rk.dense = s->R;
    gsl_matrix_set_zero(s->R);
    td_state_space_rhs_blocks(s->sys, W, &rk);
    if (nf > 0 && !filter_elimination(s, W))
        return 0;
    dynamic_stiffness(s, W);
    for (i = 0; i < nd; i++)
        gsl_vector_complex_set(s->q, i, gsl_complex_rect(s->f[i], s->f[nd + i]));
    if (gsl_linalg_complex_LU_decomp(s->D, s->pd, &sign) != GSL_SUCCESS || lu_singular(s->D) ||
        gsl_linalg_complex_LU_svx(s->D, s->pd, s->q) != GSL_SUCCESS)
        return 0;
    for (i = 0; i < nd; i++) {
        gsl_complex qi = gsl_vector_complex_get(s->q, i);
        re[i] = GSL_REAL(qi);
        im[i] = GSL_IMAG(qi);
        re[nd + i] = -W * GSL_IMAG(qi); /* V = i W Q */
        im[nd + i] = W * GSL_REAL(qi);
    }
    for (i = 0; i < nf; i++) { /* S = X Q */
        gsl_complex sum = gsl_complex_rect(0.0, 0.0);
        for (j = 0; j < nd; j++)
            sum = gsl_complex_add(sum,
                                  gsl_complex_mul(gsl_matrix_complex_get(s->X, i, j), gsl_vector_complex_get(s->q, j)));
        re[2 * nd + i] = GSL_REAL(sum);
        im[2 * nd + i] = GSL_IMAG(sum);
    }
    return 1;
}

td_status td_synchronous_response(td_synchronous *s, double omega, const td_unbalance *u, int n_u, td_harmonic **out,
                                  td_error *err)
{
    size_t nd, i;
    int any = 0;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_synchronous_response: NULL output pointer");
    *out = NULL;
    if (!s)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL synchronous solver");
    if (!TD_SPEED_VALID(omega))
        return td_error_set(err, TD_ERR_INVALID, "modal: speed must be finite and >= 0 rad/s (got %g)", omega);
    if (!s->mass_ok)
        return td_error_set(err, TD_ERR_NUMERIC,
                            "modal: the mass matrix is not positive definite (a DOF without mass or inertia?)");
    nd = (size_t)s->nd;
    st = td_unbalance_forces(s->sys, omega, u, n_u, s->f, s->f + nd, err);
    if (st != TD_OK)
        return st;
    for (i = 0; i < 2 * nd; i++)
        any |= s->f[i] != 0.0;
    if (!any) /* no force: the response is zero, as td_harmonic_compute's */
        for (i = 0; i < 2u * (size_t)s->n; i++)
            s->z[i] = 0.0;
    else if (!solve_state(s, omega))
        return td_error_set(err, TD_ERR_NUMERIC, "modal: i*%g is an eigenvalue of the system (undamped resonance)",
                            omega);
    return td_harmonic_from_state(s->sys, omega, s->n, s->z, s->z + s->n, out, err);
}
