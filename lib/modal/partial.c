/*
 * The lowest modes of a large system by shift-invert subspace iteration on the sparse pencil of the
 * first-order system (touchdown/modal.h), E z' = F z with
 *
 *   E = diag(I, M, I),   F = [0 I 0; R; filter rows],   A = E^-1 F,
 *
 * R = [-K_eff | -C_eff | B_w] and the filter rows as state_space.c builds them for the dense A.
 * The operator OP = (F - sigma E)^-1 E (one sparse LU, KLU) has the eigenvectors of A with the
 * eigenvalues nu = 1 / (s - sigma): the roots s nearest the shift converge first. A block of p
 * vectors is iterated (Y = OP Q) and projected (Rayleigh-Ritz: the p x p matrix Q^T OP Q, solved by
 * the same dense GSL solver as td_modal_solve), so degenerate pairs (an isotropic rotor at rest),
 * which a single-vector Krylov method cannot resolve, come out like any other. Cost per iteration:
 * p sparse solves and O(n p^2), instead of O(n^3) for the dense solve of everything.
 *
 * Completeness: the k converged Ritz pairs of largest |nu| are the k roots nearest sigma, so every
 * root with |s - sigma| < rho (the largest distance among them) is found. A vibration mode
 * (zeta < TD_MODAL_OVERDAMPED_ZETA) has |s| = omega_d / sqrt(1 - zeta^2) < omega_d / sqrt(1 - Z^2),
 * so every vibration mode with omega_d < (rho - |sigma|) sqrt(1 - Z^2) is found: the analysis keeps
 * the oscillatory roots below that bound (td_modal_complete_below) and iterates, or doubles the
 * block, until the demanded modes lie below it.
 */
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <klu.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Systems beyond this many states are never handed to the dense solver (memory n^2, time n^3). */
#define TD_MODAL_DENSE_FALLBACK_MAX 4000
/* Damping ratio up to which the partial solution is complete below its bound (file comment). */
#define TD_PARTIAL_ZETA_COVER 0.9
/* Iterations with one block size before the block is doubled. */
#define TD_SUBSPACE_MAX_ITER 40
/* A Ritz pair counts as converged when |OP x - nu x| <= this * |nu_max| |x| (nu_max: the largest Ritz value). */
#define TD_SUBSPACE_TOL 1e-10
/* Shift used when F itself is singular (a free rotor's rigid-body roots s = 0), rad/s. */
#define TD_FREE_BODY_SHIFT (-1.0)

/* The factored pencil F - sigma E and the mass matrix for E x. */
typedef struct pencil {
    int n, nd;
    double sigma;
    const cs_di *M;
    cs_di *P;
    klu_symbolic *sym;
    klu_numeric *num;
    klu_common common;
} pencil;

static void pencil_free(pencil *p)
{
    if (p->num)
        klu_free_numeric(&p->num, &p->common);
    if (p->sym)
        klu_free_symbolic(&p->sym, &p->common);
    cs_di_spfree(p->P);
    p->P = NULL;
}

/* F - sigma E in compressed columns, or NULL when out of memory. */
static cs_di *pencil_matrix(const td_system *sys, double omega, double sigma)
{
    int nd = sys->ndof, n = td_modal_state_count(sys), i;
    cs_di *T = cs_di_spalloc(n, n, 4 * (sys->K->p[nd] + sys->C->p[nd] + sys->M->p[nd]) + 4 * n, 1, 1), *C = NULL;
    td_entry_sink k = {NULL, NULL, 0, 1};
    if (!T)
        return NULL;
    k.triplet = T;
    for (i = 0; i < nd; i++) { /* q' = v */
        td_entry_add(&k, i, nd + i, 1.0);
        td_entry_add(&k, i, i, -sigma);
    }
    k.row0 = nd; /* M v' = R z */
    td_state_space_rhs_blocks(sys, omega, &k);
    td_entry_add_matrix(&k, sys->M, nd, -sigma);
    k.row0 = 0;
    td_state_space_filter_rows(sys, &k);
    for (i = 2 * nd; i < n; i++)
        td_entry_add(&k, i, i, -sigma);
    if (k.ok && (C = cs_di_compress(T)) != NULL && !cs_di_dupl(C)) {
        cs_di_spfree(C);
        C = NULL;
    }
    cs_di_spfree(T);
    return C;
}

/* Build and factor F - sigma E. TD_ERR_NUMERIC when it is singular. */
static td_status pencil_factor(const td_system *sys, double omega, double sigma, pencil *p, td_error *err)
{
    p->n = td_modal_state_count(sys);
    p->nd = sys->ndof;
    p->sigma = sigma;
    p->M = sys->M;
    p->sym = NULL;
    p->num = NULL;
    p->P = NULL;
    klu_defaults(&p->common);
    if (td_state_space_supported(sys, err) != TD_OK)
        return TD_ERR_INVALID;
    if (!(p->P = pencil_matrix(sys, omega, sigma)))
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the sparse %d-state system", p->n);
    p->sym = klu_analyze(p->n, p->P->p, p->P->i, &p->common);
    if (p->sym)
        p->num = klu_factor(p->P->p, p->P->i, p->P->x, p->sym, &p->common);
    if (!p->num) {
        td_status st = p->common.status == KLU_OUT_OF_MEMORY ? TD_ERR_NOMEM : TD_ERR_NUMERIC;
        pencil_free(p);
        return td_error_set(err, st, "modal: the shifted system at %g rad/s is singular", omega);
    }
    return TD_OK;
}

/* y = (F - sigma E)^-1 E x */
static int apply_op(pencil *p, const double *x, double *y)
{
    int i;
    for (i = 0; i < p->n; i++)
        y[i] = i >= p->nd && i < 2 * p->nd ? 0.0 : x[i];
    cs_di_gaxpy(p->M, x + p->nd, y + p->nd);
    return klu_solve(p->sym, p->num, p->n, 1, y, &p->common);
}

/* ---- subspace iteration ------------------------------------------------------------------- */

/* The block of the iteration: Q (n x p, orthonormal columns, column-major) and Y = OP Q. */
typedef struct block {
    int n, p;
    double *Q, *Y;
} block;

static void block_free(block *b)
{
    free(b->Q);
    free(b->Y);
    b->Q = b->Y = NULL;
}

static double dot(const double *a, const double *b, int n)
{
    double s = 0.0;
    int i;
    for (i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* A fixed pseudo-random column (the same run gives the same modes). */
static void seed_column(double *q, int n, int j)
{
    int i;
    for (i = 0; i < n; i++)
        q[i] = sin(12.9898 * (double)(i + 1) + 78.233 * (double)(j + 1));
}

/* Orthonormalise the columns of Q in place (modified Gram-Schmidt, twice); a column that collapses
 * into the span of the others is replaced by a fresh seed. */
static void orthonormalise(double *Q, int n, int p)
{
    int j, k, pass, tries, i;
    for (j = 0; j < p; j++) {
        double *q = Q + (size_t)j * (size_t)n;
        for (tries = 0; tries < 4; tries++) {
            double before = sqrt(dot(q, q, n)), after;
            for (pass = 0; pass < 2; pass++)
                for (k = 0; k < j; k++) {
                    const double *u = Q + (size_t)k * (size_t)n;
                    double c = dot(u, q, n);
                    for (i = 0; i < n; i++)
                        q[i] -= c * u[i];
                }
            after = sqrt(dot(q, q, n));
            if (after > 1e-13 * before && after > 0.0) {
                for (i = 0; i < n; i++)
                    q[i] /= after;
                break;
            }
            seed_column(q, n, j + p * (tries + 1));
        }
    }
}

/* A Ritz pair of OP: nu, its column in the Ritz vector matrix, its relative residual. */
typedef struct ritz_ref {
    gsl_complex nu;
    size_t col;
    double resid;
} ritz_ref;

static int cmp_magnitude_desc(const void *a, const void *b)
{
    double x = gsl_complex_abs(((const ritz_ref *)a)->nu), y = gsl_complex_abs(((const ritz_ref *)b)->nu);
    if (x != y)
        return x > y ? -1 : 1;
    return GSL_IMAG(((const ritz_ref *)a)->nu) > GSL_IMAG(((const ritz_ref *)b)->nu) ? -1 : 1;
}

/* The Ritz pairs of one Rayleigh-Ritz step, by descending |nu|; vectors are the columns of x (n x p). */
typedef struct ritz {
    int p;
    ritz_ref *refs;
    gsl_matrix_complex *x;
    double *Wr; /* p x p real basis of the Ritz coefficients: Re w, Im w of each pair, w of a real root */
} ritz;

static void ritz_free(ritz *r)
{
    free(r->refs);
    free(r->Wr);
    gsl_matrix_complex_free(r->x);
    r->refs = NULL;
    r->Wr = NULL;
    r->x = NULL;
}

/* Ritz vector x = Q w and its residual |Y w - nu x| / (|nu| |x|) (Y w = OP x). */
static double ritz_vector(const block *b, const gsl_matrix_complex *W, size_t col, gsl_complex nu,
                          gsl_matrix_complex *x)
{
    double rr = 0.0, xx = 0.0;
    int i, k;
    for (i = 0; i < b->n; i++) {
        double xr = 0.0, xi = 0.0, yr = 0.0, yi = 0.0, rre, rim;
        for (k = 0; k < b->p; k++) {
            gsl_complex w = gsl_matrix_complex_get(W, (size_t)k, col);
            double q = b->Q[i + (size_t)k * (size_t)b->n], y = b->Y[i + (size_t)k * (size_t)b->n];
            xr += q * GSL_REAL(w);
            xi += q * GSL_IMAG(w);
            yr += y * GSL_REAL(w);
            yi += y * GSL_IMAG(w);
        }
        gsl_matrix_complex_set(x, (size_t)i, col, gsl_complex_rect(xr, xi));
        rre = yr - (GSL_REAL(nu) * xr - GSL_IMAG(nu) * xi);
        rim = yi - (GSL_REAL(nu) * xi + GSL_IMAG(nu) * xr);
        rr += rre * rre + rim * rim;
        xx += xr * xr + xi * xi;
    }
    return sqrt(rr) / (gsl_complex_abs(nu) * sqrt(xx) + 1e-300);
}

/* Rayleigh-Ritz on the block: H = Q^T Y (p x p), solved by the dense GSL eigen-solver. */
static td_status rayleigh_ritz(const block *b, ritz *r, td_error *err)
{
    size_t p = (size_t)b->p, j, k;
    gsl_matrix *H = gsl_matrix_alloc(p, p);
    gsl_vector_complex *eval = gsl_vector_complex_alloc(p);
    gsl_matrix_complex *W = gsl_matrix_complex_alloc(p, p);
    gsl_eigen_nonsymmv_workspace *ws = gsl_eigen_nonsymmv_alloc(p);
    td_status st = TD_OK;
    r->p = b->p;
    r->refs = malloc(p * sizeof *r->refs);
    r->x = gsl_matrix_complex_alloc((size_t)b->n, p);
    r->Wr = malloc(p * p * sizeof *r->Wr);
    if (!H || !eval || !W || !ws || !r->refs || !r->x || !r->Wr)
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for a %d-vector subspace", b->p);
    for (j = 0; st == TD_OK && j < p; j++)
        for (k = 0; k < p; k++)
            gsl_matrix_set(H, j, k, dot(b->Q + j * (size_t)b->n, b->Y + k * (size_t)b->n, b->n));
    if (st == TD_OK) {
        gsl_eigen_nonsymmv_params(1, ws);
        if (gsl_eigen_nonsymmv(H, eval, W, ws) != GSL_SUCCESS)
            st = td_error_set(err, TD_ERR_NUMERIC, "modal: the projected eigen-problem did not converge");
    }
    for (j = 0; st == TD_OK && j < p; j++) {
        r->refs[j].nu = gsl_vector_complex_get(eval, j);
        r->refs[j].col = j;
        r->refs[j].resid = ritz_vector(b, W, j, r->refs[j].nu, r->x);
    }
    for (j = 0; st == TD_OK && j < p; j++) { /* GSL stores a pair as neighbours, Im > 0 first */
        int second = j > 0 && GSL_IMAG(gsl_vector_complex_get(eval, j)) < 0.0;
        for (k = 0; k < p; k++) {
            gsl_complex w = gsl_matrix_complex_get(W, k, j);
            r->Wr[k + j * p] = second ? GSL_IMAG(w) : GSL_REAL(w);
        }
    }
    if (st == TD_OK)
        qsort(r->refs, p, sizeof *r->refs, cmp_magnitude_desc);
    else
        ritz_free(r);
    gsl_eigen_nonsymmv_free(ws);
    gsl_matrix_complex_free(W);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(H);
    return st;
}

/* Y = OP Q, column by column. */
static td_status apply_block(pencil *pc, block *b, td_error *err)
{
    int j;
    for (j = 0; j < b->p; j++)
        if (apply_op(pc, b->Q + (size_t)j * (size_t)b->n, b->Y + (size_t)j * (size_t)b->n) != 1)
            return td_error_set(err, TD_ERR_NUMERIC, "modal: solving the shifted system failed");
    return TD_OK;
}

/* Root s = sigma + 1/nu. */
static gsl_complex root_of(const pencil *pc, gsl_complex nu)
{
    return gsl_complex_add_real(gsl_complex_inverse(nu), pc->sigma);
}

/* The leading Ritz pairs converged to `tol`, kept as a td_modal when they make a complete answer:
 * *out stays NULL when more iterations or a larger block are needed. */
static td_status try_collect(const td_system *sys, double omega, const pencil *pc, const ritz *r, int count,
                             double wmax, td_modal **out, td_error *err)
{
    gsl_vector_complex *eval = NULL;
    gsl_matrix_complex *evec = NULL;
    double rho = 0.0, bound;
    size_t n = r->x->size1, m = 0, i;
    int k = 0, j, vib = 0;
    td_status st = TD_OK;
    *out = NULL;
    while (k < r->p &&
           r->refs[k].resid * gsl_complex_abs(r->refs[k].nu) <= TD_SUBSPACE_TOL * gsl_complex_abs(r->refs[0].nu))
        k++;
    if (k < r->p && k > 0 && GSL_IMAG(r->refs[k - 1].nu) != 0.0 &&
        gsl_complex_abs(gsl_complex_sub(r->refs[k - 1].nu, gsl_complex_conjugate(r->refs[k].nu))) == 0.0)
        k--; /* a pair split by the cut: leave both out */
    for (j = 0; j < k; j++)
        rho = fmax(rho, gsl_complex_abs(gsl_complex_sub_real(root_of(pc, r->refs[j].nu), pc->sigma)));
    bound = (rho - fabs(pc->sigma)) * sqrt(1.0 - TD_PARTIAL_ZETA_COVER * TD_PARTIAL_ZETA_COVER);
    for (j = 0; j < k; j++) {
        gsl_complex s = root_of(pc, r->refs[j].nu);
        double zeta = -GSL_REAL(s) / gsl_complex_abs(s);
        if (GSL_IMAG(s) > 0.0 && GSL_IMAG(s) < bound && zeta < TD_MODAL_OVERDAMPED_ZETA)
            vib++;
    }
    if (k == 0 || vib < count || !(bound > wmax))
        return TD_OK;
    eval = gsl_vector_complex_alloc((size_t)k);
    evec = gsl_matrix_complex_alloc(n, (size_t)k);
    if (!eval || !evec)
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory storing modes");
    for (j = 0; st == TD_OK && j < k; j++) {
        gsl_complex s = root_of(pc, r->refs[j].nu);
        if (fabs(GSL_IMAG(s)) >= bound)
            continue;
        gsl_vector_complex_set(eval, m, s);
        for (i = 0; i < n; i++)
            gsl_matrix_complex_set(evec, i, m, gsl_matrix_complex_get(r->x, i, r->refs[j].col));
        m++;
    }
    if (st == TD_OK) {
        gsl_vector_complex_view ev = gsl_vector_complex_subvector(eval, 0, m);
        gsl_matrix_complex_view vv = gsl_matrix_complex_submatrix(evec, 0, 0, n, m);
        st = td_modal_collect_system(&ev.vector, &vv.matrix, sys, omega, out, err);
    }
    if (st == TD_OK) {
        (*out)->n_computed = k;
        (*out)->complete_below = bound;
    }
    gsl_vector_complex_free(eval);
    gsl_matrix_complex_free(evec);
    return st;
}

/* Next block: Q = orth(Y Wr), the images of the Ritz vectors (kept apart, so that converged columns
 * do not merge). */
static void next_block(block *b, const ritz *r)
{
    size_t n = (size_t)b->n, p = (size_t)b->p, i, j, k;
    for (j = 0; j < p; j++) {
        double *q = b->Q + j * n;
        for (i = 0; i < n; i++)
            q[i] = 0.0;
        for (k = 0; k < p; k++) {
            double w = r->Wr[k + j * p];
            const double *y = b->Y + k * n;
            if (w != 0.0)
                for (i = 0; i < n; i++)
                    q[i] += w * y[i];
        }
    }
    orthonormalise(b->Q, b->n, b->p);
}

/* Subspace iteration with a block of p vectors until the answer is complete or the iteration
 * limit is reached (*out NULL then). */
static td_status iterate(const td_system *sys, double omega, pencil *pc, block *b, int count, double wmax,
                         td_modal **out, td_error *err)
{
    int it;
    td_status st = TD_OK;
    *out = NULL;
    orthonormalise(b->Q, b->n, b->p);
    for (it = 0; it < TD_SUBSPACE_MAX_ITER && st == TD_OK && !*out; it++) {
        ritz r = {0, NULL, NULL, NULL};
        if ((st = apply_block(pc, b, err)) != TD_OK)
            break;
        if ((st = rayleigh_ritz(b, &r, err)) != TD_OK)
            break;
        st = try_collect(sys, omega, pc, &r, count, wmax, out, err);
        next_block(b, &r);
        ritz_free(&r);
    }
    return st;
}

/* Dense solve of a system too small for the iteration to pay, or too demanding a request. */
static td_status dense_fallback(const td_system *sys, double omega, int count, td_modal **out, td_error *err)
{
    int n = td_modal_state_count(sys);
    if (n > TD_MODAL_DENSE_FALLBACK_MAX)
        return td_error_set(err, TD_ERR_INVALID,
                            "modal: %d modes asked of a %d-state system: too many for the partial eigen-solver and too "
                            "large for the dense one (at most %d states); ask for fewer modes or a lower speed range",
                            count, n, TD_MODAL_DENSE_FALLBACK_MAX);
    return td_modal_solve(sys, omega, out, err);
}

/* Grow the block to p columns, keeping the old ones as the start of the new iteration. */
static int block_grow(block *b, int p)
{
    double *Q = realloc(b->Q, (size_t)b->n * (size_t)p * sizeof *Q), *Y;
    int j;
    if (!Q)
        return 0;
    b->Q = Q;
    Y = realloc(b->Y, (size_t)b->n * (size_t)p * sizeof *Y);
    if (!Y)
        return 0;
    b->Y = Y;
    for (j = b->p; j < p; j++)
        seed_column(b->Q + (size_t)j * (size_t)b->n, b->n, j);
    b->p = p;
    return 1;
}

td_status td_modal_lowest(const td_system *sys, double omega, int count, double wmax, int force_sparse, td_modal **out,
                          td_error *err)
{
    pencil pc;
    block b = {0, 0, NULL, NULL};
    td_status st;
    int n, p;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_modal_solve_lowest: NULL output pointer");
    *out = NULL;
    if (!sys || count < 1 || !TD_SPEED_VALID(omega))
        return td_error_set(err, TD_ERR_INVALID, "td_modal_solve_lowest: bad system, speed or mode count");
    n = td_modal_state_count(sys);
    if (!force_sparse && n <= TD_MODAL_DENSE_MAX_STATES)
        return td_modal_solve(sys, omega, out, err);
    td_modal_gsl_quiet();
    st = pencil_factor(sys, omega, 0.0, &pc, err);
    if (st == TD_ERR_NUMERIC) /* F singular: a root at s = 0 */
        st = pencil_factor(sys, omega, TD_FREE_BODY_SHIFT, &pc, err);
    if (st != TD_OK)
        return st;
    b.n = n;
    for (p = 4 * count + 16; st == TD_OK && !*out; p *= 2) {
        if (2 * p > n) {
            block_free(&b);
            pencil_free(&pc);
            return dense_fallback(sys, omega, count, out, err);
        }
        if (!block_grow(&b, p))
            st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for a %d-vector subspace", p);
        else
            st = iterate(sys, omega, &pc, &b, count, wmax, out, err);
    }
    block_free(&b);
    pencil_free(&pc);
    return st;
}

td_status td_modal_solve_lowest(const td_system *sys, double omega, int count, td_modal **out, td_error *err)
{
    return td_modal_lowest(sys, omega, count, 0.0, 0, out, err);
}

double td_modal_complete_below(const td_modal *m)
{
    return m ? m->complete_below : NAN;
}

int td_modal_computed_count(const td_modal *m)
{
    return m ? m->n_computed : 0;
}
