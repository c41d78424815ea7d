/*
 * The synchronous unbalance response in second-order (dynamic-stiffness) form, for the many speeds
 * of the API 617 sweep (api617.c; its cost and accuracy: docs/api617.md).
 *
 * td_harmonic_compute solves (i W I - A) Z = [0; M^-1 F; 0] with the first-order A of state_space.c:
 * a Cholesky factor of M and a solve with its ndof x n right-hand side at every speed, then a complex
 * LU of order n = 2 ndof + nfilter. With Z = [Q; V; S], M v' = R z + F (R = [R_q | R_v | R_s], the
 * right-hand blocks of state_space.c) and the filter rows s' = P z (P = [P_q | P_v | P_s]), the rows
 * of Z read V = i W Q and
 *
 *   (-W^2 M - R_q - i W R_v) Q - R_s S = F,
 *   -(P_q + i W P_v) Q + (i W I - P_s) S = 0,
 *
 * the same solution: one pivoted complex LU of order ndof + nfilter, and no M^-1. The [Q; S] system
 * is bordered, not reduced to Q by eliminating S: i W I - P_s alone is singular where i W is a pole
 * of a controller (an undamped resonant block at its own frequency, a PID integrator at W = 0)
 * although the closed loop i W I - A is regular there.
 */
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <stdlib.h>

struct td_synchronous {
    const td_system *sys;
    int nd, nf, n;
    td_error mass_err;     /* code TD_OK (calloc), or why M is refused (as the first-order form refuses it) */
    gsl_matrix *M;         /* nd x nd */
    gsl_matrix *R;         /* nd x n: the right-hand blocks at the current speed */
    gsl_matrix *P;         /* max(nf, 1) x n: the filter rows (speed-independent) */
    gsl_matrix_complex *T; /* nd + nf square: the bordered dynamic stiffness, then its LU */
    gsl_permutation *p;    /* nd + nf */
    gsl_vector_complex *b; /* nd + nf: [F; 0], then [Q; S] */
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
    gsl_matrix_complex_free((*s)->T);
    gsl_permutation_free((*s)->p);
    gsl_vector_complex_free((*s)->b);
    free((*s)->f);
    free((*s)->z);
    free(*s);
    *s = NULL;
}

/* The speed-independent parts: M (and whether the first-order form accepts it) and the filter rows P. */
static td_status fill_constant(td_synchronous *s, td_error *err)
{
    td_entry_sink mk = {NULL, NULL, 0, 1}, pk = {NULL, NULL, 0, 1};
    gsl_matrix *L = gsl_matrix_alloc((size_t)s->nd, (size_t)s->nd);
    if (!L)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the synchronous response");
    td_state_space_factor_mass(s->sys, L, &s->mass_err);
    gsl_matrix_free(L);
    mk.dense = s->M;
    gsl_matrix_set_zero(s->M);
    td_entry_add_matrix(&mk, s->sys->M, 0, 1.0);
    pk.dense = s->P;
    pk.row0 = -2 * s->nd; /* the rows 2 nd .. n of the first-order A, from row 0 */
    td_state_space_filter_rows(s->sys, &pk);
    return TD_OK;
}

td_status td_synchronous_create(const td_system *sys, td_synchronous **out, td_error *err)
{
    td_synchronous *s;
    size_t nd, N;
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
    N = nd + (size_t)s->nf;
    s->M = gsl_matrix_alloc(nd, nd);
    s->R = gsl_matrix_alloc(nd, (size_t)s->n);
    s->P = gsl_matrix_calloc((size_t)(s->nf > 0 ? s->nf : 1), (size_t)s->n); /* GSL has no empty matrices */
    s->T = gsl_matrix_complex_alloc(N, N);
    s->p = gsl_permutation_alloc(N);
    s->b = gsl_vector_complex_alloc(N);
    s->f = malloc(2 * nd * sizeof *s->f);
    s->z = malloc(2u * (size_t)s->n * sizeof *s->z);
    if (!s->M || !s->R || !s->P || !s->T || !s->p || !s->b || !s->f || !s->z) {
        td_synchronous_free(&s);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the synchronous response");
    }
    if (fill_constant(s, err) != TD_OK) {
        td_synchronous_free(&s);
        return TD_ERR_NOMEM;
    }
    *out = s;
    return TD_OK;
}

/* T = [-W^2 M - R_q - i W R_v, -R_s; -(P_q + i W P_v), i W I - P_s] (R at speed W already in s->R). */
static void bordered_stiffness(td_synchronous *s, double W)
{
    size_t nd = (size_t)s->nd, nf = (size_t)s->nf, i, j;
    for (i = 0; i < nd; i++) {
        for (j = 0; j < nd; j++)
            gsl_matrix_complex_set(s->T, i, j,
                                   gsl_complex_rect(-W * W * gsl_matrix_get(s->M, i, j) - gsl_matrix_get(s->R, i, j),
                                                    -W * gsl_matrix_get(s->R, i, nd + j)));
        for (j = 0; j < nf; j++)
            gsl_matrix_complex_set(s->T, i, nd + j, gsl_complex_rect(-gsl_matrix_get(s->R, i, 2 * nd + j), 0.0));
    }
    for (i = 0; i < nf; i++) {
        for (j = 0; j < nd; j++)
            gsl_matrix_complex_set(s->T, nd + i, j,
                                   gsl_complex_rect(-gsl_matrix_get(s->P, i, j), -W * gsl_matrix_get(s->P, i, nd + j)));
        for (j = 0; j < nf; j++)
            gsl_matrix_complex_set(s->T, nd + i, nd + j,
                                   gsl_complex_rect(-gsl_matrix_get(s->P, i, 2 * nd + j), i == j ? W : 0.0));
    }
}

/* The state Z = [Q; i W Q; S] into s->z (re then im) from the force F (s->f); 0 when singular. */
static int solve_state(td_synchronous *s, double W)
{
    size_t nd = (size_t)s->nd, nf = (size_t)s->nf, n = (size_t)s->n, i;
    double *re = s->z, *im = s->z + n;
    int sign;
    td_entry_sink rk = {NULL, NULL, 0, 1};
    rk.dense = s->R;
    gsl_matrix_set_zero(s->R);
    td_state_space_rhs_blocks(s->sys, W, &rk);
    bordered_stiffness(s, W);
    for (i = 0; i < nd + nf; i++)
        gsl_vector_complex_set(s->b, i, i < nd ? gsl_complex_rect(s->f[i], s->f[nd + i]) : gsl_complex_rect(0.0, 0.0));
    if (gsl_linalg_complex_LU_decomp(s->T, s->p, &sign) != GSL_SUCCESS || td_complex_lu_singular(s->T) ||
        gsl_linalg_complex_LU_svx(s->T, s->p, s->b) != GSL_SUCCESS)
        return 0;
    for (i = 0; i < nd; i++) {
        gsl_complex qi = gsl_vector_complex_get(s->b, i);
        re[i] = GSL_REAL(qi);
        im[i] = GSL_IMAG(qi);
        re[nd + i] = -W * GSL_IMAG(qi); /* V = i W Q */
        im[nd + i] = W * GSL_REAL(qi);
    }
    for (i = 0; i < nf; i++) {
        gsl_complex si = gsl_vector_complex_get(s->b, nd + i);
        re[2 * nd + i] = GSL_REAL(si);
        im[2 * nd + i] = GSL_IMAG(si);
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
    if (s->mass_err.code != TD_OK) {
        if (err)
            *err = s->mass_err;
        return s->mass_err.code;
    }
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
        return td_resonance_error(err, omega);
    return td_harmonic_from_state(s->sys, omega, s->n, s->z, s->z + s->n, out, err);
}
