/*
 * Eigen-analysis of the first-order system at one speed (gsl_eigen_nonsymmv, with balancing:
 * the state mixes metres, metres per second and newtons, and the v rows carry M^-1 K, so the
 * unbalanced A spans many decades). Complex pairs are kept once (omega_d > 0), real eigenvalues
 * apart; each mode gets its normalised shape and its whirl sense (touchdown/modal.h).
 */
#include "modal/modal_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A node whose squared amplitude is below this fraction of the largest one does not vote on the whirl. */
#define TD_WHIRL_AMPLITUDE_FLOOR 1e-8
/* |h| below this at a voting node counts as planar (no sense). */
#define TD_WHIRL_SENSE_FLOOR 1e-6

/* An eigenvalue and the column of its eigenvector, for sorting. */
typedef struct eig_ref {
    double re, im;
    size_t col;
} eig_ref;

static int cmp_oscillatory(const void *a, const void *b)
{
    const eig_ref *x = a, *y = b;
    if (x->im != y->im)
        return x->im < y->im ? -1 : 1;
    if (x->re != y->re)
        return x->re < y->re ? -1 : 1;
    return 0;
}

static int cmp_desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x > y ? -1 : (x < y ? 1 : 0);
}

/* A pair whose imaginary part is this small against |s| is a (numerically split) real double root. */
static int is_real(gsl_complex s)
{
    return fabs(GSL_IMAG(s)) <= 64.0 * DBL_EPSILON * gsl_complex_abs(s);
}

/* Normalise the nodal X, Y of eigenvector column `col` into shape[4 nnodes] and classify the whirl. */
static void shape_and_whirl(const gsl_matrix_complex *V, size_t col, int nnodes, double *shape, td_mode *mode)
{
    double *xr = shape, *xi = shape + nnodes, *yr = shape + 2 * nnodes, *yi = shape + 3 * nnodes;
    gsl_complex big = gsl_complex_rect(1.0, 0.0);
    double bigabs = -1.0, wmax = 0.0, cross = 0.0, total = 0.0;
    int k, nfwd = 0, nbwd = 0, nplanar = 0;
    for (k = 0; k < nnodes; k++) {
        gsl_complex X = gsl_matrix_complex_get(V, (size_t)TD_DOF(k, TD_DOF_X), col);
        gsl_complex Y = gsl_matrix_complex_get(V, (size_t)TD_DOF(k, TD_DOF_Y), col);
        if (gsl_complex_abs(X) > bigabs) {
            bigabs = gsl_complex_abs(X);
            big = X;
        }
        if (gsl_complex_abs(Y) > bigabs) {
            bigabs = gsl_complex_abs(Y);
            big = Y;
        }
    }
    for (k = 0; k < nnodes; k++) {
        gsl_complex X = gsl_matrix_complex_get(V, (size_t)TD_DOF(k, TD_DOF_X), col);
        gsl_complex Y = gsl_matrix_complex_get(V, (size_t)TD_DOF(k, TD_DOF_Y), col);
        double w;
        if (bigabs > 0.0) {
            X = gsl_complex_div(X, big);
            Y = gsl_complex_div(Y, big);
        }
        xr[k] = GSL_REAL(X);
        xi[k] = GSL_IMAG(X);
        yr[k] = GSL_REAL(Y);
        yi[k] = GSL_IMAG(Y);
        w = gsl_complex_abs2(X) + gsl_complex_abs2(Y);
        if (w > wmax)
            wmax = w;
    }
    for (k = 0; k < nnodes; k++) {
        /* Im(conj(X) Y) = xr yi - xi yr; forward (x towards y) when it is negative */
        double c = xr[k] * yi[k] - xi[k] * yr[k];
        double w = xr[k] * xr[k] + xi[k] * xi[k] + yr[k] * yr[k] + yi[k] * yi[k];
        double h;
        cross += c;
        total += w;
        if (w <= TD_WHIRL_AMPLITUDE_FLOOR * wmax)
            continue;
        h = -2.0 * c / w;
        if (h > TD_WHIRL_SENSE_FLOOR)
            nfwd++;
        else if (h < -TD_WHIRL_SENSE_FLOOR)
            nbwd++;
        else
            nplanar++;
    }
    mode->whirl_index = total > 0.0 ? -2.0 * cross / total : 0.0;
    if (nfwd > 0 && nbwd == 0 && nplanar == 0)
        mode->whirl = TD_WHIRL_FORWARD;
    else if (nbwd > 0 && nfwd == 0 && nplanar == 0)
        mode->whirl = TD_WHIRL_BACKWARD;
    else
        mode->whirl = TD_WHIRL_MIXED;
}

/* Two eigenvalues closer than this (relative) are one degenerate pair (an isotropic rotor at rest,
 * or one without gyroscopic coupling), whose eigenvectors the solver returns in an arbitrary basis. */
#define TD_DEGENERATE_RTOL 1e-8
/* A rotated basis vector counts as a pure whirl when its other-sense part is this small (energy). */
#define TD_PURE_WHIRL_TOL 1e-6

/* Circular parts of an eigenvector: the forward part X + iY, Theta + i Phi (zero for a backward
 * whirl) when sense = +1, the backward part X - iY, Theta - i Phi when sense = -1. A forward
 * circular whirl x = cos, y = sin has Y = -iX and, as theta = -dy/dz, Theta = i Phi. */
static gsl_complex circular_part(const gsl_matrix_complex *V, size_t col, int node, int rot, int sense)
{
    size_t a = (size_t)TD_DOF(node, rot ? TD_DOF_THETA : TD_DOF_X),
           b = (size_t)TD_DOF(node, rot ? TD_DOF_PHI : TD_DOF_Y);
    gsl_complex u = gsl_matrix_complex_get(V, a, col), v = gsl_matrix_complex_get(V, b, col);
    return gsl_complex_add(u, gsl_complex_mul(gsl_complex_rect(0.0, (double)sense), v));
}

/* Unit c minimising |c1 p(u1) + c2 p(u2)|^2 (p the circular part of `sense`): the eigenvector of the
 * smallest eigenvalue of the Hermitian Gram matrix. Returns that eigenvalue over the trace. */
static double null_combination(const gsl_matrix_complex *V, size_t c1, size_t c2, int nnodes, int sense,
                               gsl_complex c[2])
{
    double a = 0.0, d = 0.0, lam, nrm;
    gsl_complex z = GSL_COMPLEX_ZERO, v1, v2;
    int k, r;
    for (k = 0; k < nnodes; k++)
        for (r = 0; r < 2; r++) {
            gsl_complex p1 = circular_part(V, c1, k, r, sense), p2 = circular_part(V, c2, k, r, sense);
            a += gsl_complex_abs2(p1);
            d += gsl_complex_abs2(p2);
            z = gsl_complex_add(z, gsl_complex_mul(gsl_complex_conjugate(p1), p2));
        }
    lam = 0.5 * (a + d) - sqrt(0.25 * (a - d) * (a - d) + gsl_complex_abs2(z));
    if (gsl_complex_abs(z) > 0.0) {
        v1 = z;
        v2 = gsl_complex_rect(lam - a, 0.0);
    } else {
        v1 = gsl_complex_rect(a <= d ? 1.0 : 0.0, 0.0);
        v2 = gsl_complex_rect(a <= d ? 0.0 : 1.0, 0.0);
    }
    nrm = sqrt(gsl_complex_abs2(v1) + gsl_complex_abs2(v2));
    c[0] = gsl_complex_div_real(v1, nrm);
    c[1] = gsl_complex_div_real(v2, nrm);
    return a + d > 0.0 ? lam / (a + d) : 1.0;
}

/* Rotate the eigenvectors of a degenerate pair (columns lo, hi) into the pure backward whirl
 * (stored in lo, the lower eigenvalue) and the pure forward whirl (in hi), as gyroscopic stiffening
 * would order them at the slightest speed. Left alone unless both pure whirls exist in the span. */
static void resolve_degenerate_pair(gsl_matrix_complex *V, size_t lo, size_t hi, int nnodes)
{
    gsl_complex cf[2], cb[2];
    size_t i;
    double rf = null_combination(V, lo, hi, nnodes, -1, cf); /* forward: no backward part */
    double rb = null_combination(V, lo, hi, nnodes, +1, cb); /* backward: no forward part */
    if (rf > TD_PURE_WHIRL_TOL || rb > TD_PURE_WHIRL_TOL)
        return;
    for (i = 0; i < V->size1; i++) {
        gsl_complex u1 = gsl_matrix_complex_get(V, i, lo), u2 = gsl_matrix_complex_get(V, i, hi);
        gsl_complex f = gsl_complex_add(gsl_complex_mul(cf[0], u1), gsl_complex_mul(cf[1], u2));
        gsl_complex b = gsl_complex_add(gsl_complex_mul(cb[0], u1), gsl_complex_mul(cb[1], u2));
        gsl_matrix_complex_set(V, i, lo, b);
        gsl_matrix_complex_set(V, i, hi, f);
    }
}

/* Find degenerate pairs among the sorted oscillatory eigenvalues and resolve them. */
static void resolve_degenerate(gsl_matrix_complex *V, const eig_ref *osc, int nosc, int nnodes)
{
    int k = 0;
    while (k + 1 < nosc) {
        double scale = hypot(osc[k].re, osc[k].im);
        int close = hypot(osc[k + 1].re - osc[k].re, osc[k + 1].im - osc[k].im) <= TD_DEGENERATE_RTOL * scale;
        int triple =
            k + 2 < nosc && hypot(osc[k + 2].re - osc[k].re, osc[k + 2].im - osc[k].im) <= TD_DEGENERATE_RTOL * scale;
        if (close && !triple) {
            resolve_degenerate_pair(V, osc[k].col, osc[k + 1].col, nnodes);
            k += 2;
        } else
            k++;
    }
}

static td_modal *modal_alloc(int nnodes, int nmodes, int nreal)
{
    td_modal *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    m->nnodes = nnodes;
    m->modes = calloc((size_t)(nmodes > 0 ? nmodes : 1), sizeof *m->modes);
    m->shapes = calloc((size_t)(nmodes > 0 ? nmodes : 1) * 4u * (size_t)nnodes, sizeof *m->shapes);
    m->real = calloc((size_t)(nreal > 0 ? nreal : 1), sizeof *m->real);
    if (!m->modes || !m->shapes || !m->real)
        td_modal_free(&m);
    return m;
}

/* The eigenvector columns with their q rows expanded to the nodes' DOFs, q_phys = T q (a reduced
 * rotor, touchdown/system.h): 4 nnodes rows, every column of evec. NULL on out-of-memory. */
static gsl_matrix_complex *expand_vectors(const td_system *sys, const gsl_matrix_complex *evec)
{
    size_t np = (size_t)sys->nphys, nq = (size_t)sys->ndof, i, j, c;
    gsl_matrix_complex *X = gsl_matrix_complex_calloc(np, evec->size2);
    if (!X)
        return NULL;
    for (c = 0; c < evec->size2; c++)
        for (j = 0; j < nq; j++) {
            gsl_complex v = gsl_matrix_complex_get(evec, j, c);
            for (i = 0; i < np; i++) {
                double t = sys->T[i + j * np];
                gsl_complex *x = gsl_matrix_complex_ptr(X, i, c);
                GSL_SET_COMPLEX(x, GSL_REAL(*x) + t * GSL_REAL(v), GSL_IMAG(*x) + t * GSL_IMAG(v));
            }
        }
    return X;
}

td_status td_modal_collect_system(const gsl_vector_complex *eval, gsl_matrix_complex *evec, const td_system *sys,
                                  double omega, td_modal **out, td_error *err)
{
    gsl_matrix_complex *X;
    td_status st;
    if (!td_system_is_reduced(sys))
        return td_modal_collect(eval, evec, sys->nnodes, omega, out, err);
    X = expand_vectors(sys, evec);
    if (!X)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory expanding the mode shapes");
    st = td_modal_collect(eval, X, sys->nnodes, omega, out, err);
    gsl_matrix_complex_free(X);
    return st;
}

td_status td_modal_collect(const gsl_vector_complex *eval, gsl_matrix_complex *evec, int nnodes, double omega,
                           td_modal **out, td_error *err)
{
    size_t n = eval->size, i;
    eig_ref *osc = malloc(n * sizeof *osc);
    int nosc = 0, nreal = 0, k;
    double maxre = -HUGE_VAL;
    td_modal *m;
    if (!osc)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory sorting eigenvalues");
    for (i = 0; i < n; i++) {
        gsl_complex s = gsl_vector_complex_get(eval, i);
        if (GSL_REAL(s) > maxre)
            maxre = GSL_REAL(s);
        if (is_real(s))
            nreal++;
        else if (GSL_IMAG(s) > 0.0) {
            osc[nosc].re = GSL_REAL(s);
            osc[nosc].im = GSL_IMAG(s);
            osc[nosc].col = i;
            nosc++;
        }
    }
    m = modal_alloc(nnodes, nosc, nreal);
    if (!m) {
        free(osc);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory storing modes");
    }
    m->omega = omega;
    m->max_real = maxre;
    m->n_computed = (int)n;
    m->complete_below = HUGE_VAL;
    qsort(osc, (size_t)nosc, sizeof *osc, cmp_oscillatory);
    resolve_degenerate(evec, osc, nosc, nnodes);
    for (k = 0; k < nosc; k++) {
        td_mode *md = &m->modes[k];
        md->sigma = osc[k].re;
        md->omega_d = osc[k].im;
        md->freq_hz = osc[k].im / (2.0 * TD_PI);
        md->omega_n = hypot(osc[k].re, osc[k].im);
        md->zeta = -osc[k].re / md->omega_n;
        shape_and_whirl(evec, osc[k].col, nnodes, m->shapes + (size_t)k * 4u * (size_t)nnodes, md);
    }
    m->n_modes = nosc;
    for (i = 0; i < n; i++) {
        gsl_complex s = gsl_vector_complex_get(eval, i);
        if (is_real(s))
            m->real[m->n_real++] = GSL_REAL(s);
    }
    qsort(m->real, (size_t)m->n_real, sizeof *m->real, cmp_desc);
    free(osc);
    *out = m;
    return TD_OK;
}

/*
 * Rigid-body freedom: the dimension of the null space of A (a zero root for each motion no bearing
 * or AMB holds: A z = 0 means v = 0 and a static deflection q with its AMB states w, e that no force
 * opposes). Its rows past q' = v (v', w', e') over its columns but v's, rows and columns scaled to
 * unit largest entry (the stiffness spans many decades: a penalty clamp, a soft bearing), then the
 * singular values: those below NULL_REL of the largest are the null space's. 0 when it cannot be
 * had (memory). The scaled singular value of a held rotor's softest static mode is orders above it
 * (about (1/elements)^4 for a shaft on stiff bearings), a free one's is rounding.
 */
#define NULL_REL 1e-11

static int rigid_nullity(const td_state_space *ss)
{
    int nd = ss->ndof, nr = ss->n - nd, i, j, null = 0;
    gsl_matrix *S = gsl_matrix_alloc((size_t)nr, (size_t)nr), *V = gsl_matrix_alloc((size_t)nr, (size_t)nr);
    gsl_vector *sv = gsl_vector_alloc((size_t)nr), *work = gsl_vector_alloc((size_t)nr);
    if (S && V && sv && work) {
        for (i = 0; i < nr; i++) /* rows nd.. of A, columns q (0..nd-1) and w, e (2 nd..) */
            for (j = 0; j < nr; j++)
                gsl_matrix_set(S, (size_t)i, (size_t)j,
                               gsl_matrix_get(ss->A, (size_t)(nd + i), (size_t)(j < nd ? j : j + nd)));
        for (i = 0; i < nr; i++) {
            gsl_vector_view r = gsl_matrix_row(S, (size_t)i);
            double mx = fabs(gsl_vector_get(&r.vector, gsl_blas_idamax(&r.vector)));
            if (mx > 0.0)
                gsl_vector_scale(&r.vector, 1.0 / mx);
        }
        for (j = 0; j < nr; j++) {
            gsl_vector_view c = gsl_matrix_column(S, (size_t)j);
            double mx = fabs(gsl_vector_get(&c.vector, gsl_blas_idamax(&c.vector)));
            if (mx > 0.0)
                gsl_vector_scale(&c.vector, 1.0 / mx);
        }
        if (gsl_linalg_SV_decomp(S, V, sv, work) == GSL_SUCCESS)
            for (i = 0; i < nr; i++)
                null += gsl_vector_get(sv, (size_t)i) <= NULL_REL * gsl_vector_get(sv, 0);
    }
    gsl_matrix_free(S), gsl_matrix_free(V), gsl_vector_free(sv), gsl_vector_free(work);
    return null;
}

/* Remove mode k (and its shape) or real root k from m. */
static void remove_mode(td_modal *m, int k)
{
    size_t per = 4u * (size_t)m->nnodes;
    memmove(m->modes + k, m->modes + k + 1, (size_t)(m->n_modes - k - 1) * sizeof *m->modes);
    memmove(m->shapes + (size_t)k * per, m->shapes + (size_t)(k + 1) * per,
            (size_t)(m->n_modes - k - 1) * per * sizeof *m->shapes);
    m->n_modes--;
}

static void remove_real(td_modal *m, int k)
{
    memmove(m->real + k, m->real + k + 1, (size_t)(m->n_real - k - 1) * sizeof *m->real);
    m->n_real--;
}

/* The `zeros` roots (a rigid-body motion gives one or two: a double zero, or one beside a
 * gyroscopic nutation or a damping root) of least |s|, among those within TD_MODAL_ROUNDOFF_ROOT of
 * the spectral radius, leave the modes and real roots: they are rounding of zero, no modes. A
 * complex pair counts two. */
static void drop_zero_roots(td_modal *m, int zeros)
{
    m->rounding_bound = TD_MODAL_ROUNDOFF_ROOT * td_modal_spectral_radius(m);
    while (m->n_rounding < zeros) {
        int i, best = -1, real = 0;
        double least = m->rounding_bound;
        for (i = 0; i < m->n_modes; i++)
            if (m->modes[i].omega_n <= least)
                least = m->modes[i].omega_n, best = i, real = 0;
        for (i = 0; i < m->n_real; i++)
            if (fabs(m->real[i]) <= least)
                least = fabs(m->real[i]), best = i, real = 1;
        if (best < 0)
            return;
        if (real)
            remove_real(m, best);
        else
            remove_mode(m, best);
        m->n_rounding += real ? 1 : 2;
    }
}

/* mu -> s = ln(mu) rate for the eigenvalues of a sampled loop (sampled.c); a root at mu = 0 (a
 * delay's) is taken at |mu| = DBL_MIN, the fastest decay a double can say. */
static void sampled_to_continuous(gsl_vector_complex *eval, double rate)
{
    size_t i;
    for (i = 0; i < eval->size; i++) {
        gsl_complex mu = gsl_vector_complex_get(eval, i);
        double r = fmax(gsl_complex_abs(mu), DBL_MIN), arg = gsl_complex_arg(mu);
        if (GSL_IMAG(mu) == 0.0 && GSL_REAL(mu) > 0.0)
            arg = 0.0; /* a real root stays real */
        gsl_vector_complex_set(eval, i, gsl_complex_rect(log(r) * rate, arg * rate));
    }
}

/* td_modal_solve for a system with sampled controllers: the eigen-pairs of the loop over one sample
 * (sampled.c), its eigenvalues as s = ln(mu) rate; the plant's rows of each eigenvector are the
 * mode's shape. */
static td_status solve_sampled(const td_system *sys, double omega, td_modal **out, td_error *err)
{
    gsl_matrix *P = NULL;
    gsl_vector_complex *eval = NULL;
    gsl_matrix_complex *evec = NULL;
    gsl_eigen_nonsymmv_workspace *w = NULL;
    double rate;
    td_status st = td_sampled_closed_loop(sys, omega, &P, &rate, err);
    if (st != TD_OK)
        return st;
    eval = gsl_vector_complex_alloc(P->size1);
    evec = gsl_matrix_complex_alloc(P->size1, P->size1);
    w = gsl_eigen_nonsymmv_alloc(P->size1);
    if (!eval || !evec || !w)
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the eigen-solver (%d states)", (int)P->size1);
    else {
        gsl_eigen_nonsymmv_params(1, w); /* balance */
        if (gsl_eigen_nonsymmv(P, eval, evec, w) != GSL_SUCCESS)
            st = td_error_set(err, TD_ERR_NUMERIC, "modal: the eigen-solver did not converge at %g rad/s", omega);
        else {
            sampled_to_continuous(eval, rate);
            st = td_modal_collect_system(eval, evec, sys, omega, out, err);
            if (st == TD_OK)
                (*out)->sample_rate = rate;
        }
    }
    gsl_eigen_nonsymmv_free(w);
    gsl_matrix_complex_free(evec);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(P);
    return st;
}

td_status td_modal_solve(const td_system *sys, double omega, td_modal **out, td_error *err)
{
    td_state_space ss;
    gsl_vector_complex *eval = NULL;
    gsl_matrix_complex *evec = NULL;
    gsl_eigen_nonsymmv_workspace *w = NULL;
    td_status st;
    int zeros;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_modal_solve: NULL output pointer");
    *out = NULL;
    if (td_system_has_sampled_law(sys))
        return solve_sampled(sys, omega, out, err);
    st = td_state_space_build(sys, omega, &ss, err);
    if (st != TD_OK)
        return st;
    zeros = 2 * rigid_nullity(&ss); /* before the eigen-solver overwrites A */
    eval = gsl_vector_complex_alloc((size_t)ss.n);
    evec = gsl_matrix_complex_alloc((size_t)ss.n, (size_t)ss.n);
    w = gsl_eigen_nonsymmv_alloc((size_t)ss.n);
    if (!eval || !evec || !w)
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the eigen-solver (%d states)", ss.n);
    else {
        gsl_eigen_nonsymmv_params(1, w); /* balance */
        if (gsl_eigen_nonsymmv(ss.A, eval, evec, w) != GSL_SUCCESS)
            st = td_error_set(err, TD_ERR_NUMERIC, "modal: the eigen-solver did not converge at %g rad/s", omega);
        else
            st = td_modal_collect_system(eval, evec, sys, omega, out, err);
        if (st == TD_OK)
            drop_zero_roots(*out, zeros);
    }
    gsl_eigen_nonsymmv_free(w);
    gsl_matrix_complex_free(evec);
    gsl_vector_complex_free(eval);
    td_state_space_free(&ss);
    return st;
}

/* The one test of growth: a real part beyond the rounding of a marginal root, TD_MODAL_MARGINAL_REAL_PART
 * of the scale the roots round against (modal.h says why): a continuous system's roots s are those of
 * its state matrix, rounded relative to the spectral radius; a sampled loop's are s = ln(mu) rate
 * with mu those of the loop over one sample, rounded relative to |mu| ~ 1, so growth is
 * ln |mu| > TD_MODAL_MARGINAL_REAL_PART, max_real > TD_MODAL_MARGINAL_REAL_PART rate. Its spectral
 * radius would not do: a root mu ~ 0 (a delay's, a fast decay's) has an ln that rounding sets. */
static double rounding_scale(double radius, double sample_rate)
{
    return sample_rate > 0.0 ? sample_rate : radius;
}

static int grows(double max_real, double radius, double sample_rate)
{
    return max_real > TD_MODAL_MARGINAL_REAL_PART * rounding_scale(radius, sample_rate);
}

/* Largest real part and spectral radius of the eigenvalues in eval. */
static void rightmost(const gsl_vector_complex *eval, double *max_real, double *radius)
{
    size_t i;
    *max_real = -INFINITY;
    *radius = 0.0;
    for (i = 0; i < eval->size; i++) {
        gsl_complex z = gsl_vector_complex_get(eval, i);
        *max_real = fmax(*max_real, GSL_REAL(z));
        *radius = fmax(*radius, gsl_complex_abs(z));
    }
}

td_status td_modal_stability(const td_system *sys, double omega, double *max_real_part, int *unstable, td_error *err)
{
    td_state_space ss = {0, 0, 0, 0.0, NULL, NULL};
    gsl_matrix *A = NULL, *P = NULL;
    gsl_vector_complex *eval = NULL;
    gsl_eigen_nonsymm_workspace *w = NULL;
    double max_real = NAN, radius = 0.0, rate = 0.0;
    /* a sampled loop: the eigenvalues over one sample (sampled.c), as s = ln(mu) rate */
    td_status st = td_system_has_sampled_law(sys) ? td_sampled_closed_loop(sys, omega, &P, &rate, err)
                                                  : td_state_space_build(sys, omega, &ss, err);
    if (st != TD_OK)
        return st;
    A = P ? P : ss.A;
    eval = gsl_vector_complex_alloc(A->size1);
    w = gsl_eigen_nonsymm_alloc(A->size1);
    if (!eval || !w)
        st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the eigen-solver (%d states)", (int)A->size1);
    else {
        gsl_eigen_nonsymm_params(0, 1, w); /* eigenvalues only, balanced as in td_modal_solve */
        if (gsl_eigen_nonsymm(A, eval, w) != GSL_SUCCESS)
            st = td_error_set(err, TD_ERR_NUMERIC, "modal: the eigen-solver did not converge at %g rad/s", omega);
        else {
            if (P)
                sampled_to_continuous(eval, rate);
            rightmost(eval, &max_real, &radius);
        }
    }
    gsl_eigen_nonsymm_free(w);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(P);
    td_state_space_free(&ss);
    if (st == TD_OK && max_real_part)
        *max_real_part = max_real;
    if (st == TD_OK && unstable)
        *unstable = grows(max_real, radius, rate);
    return st;
}

void td_modal_free(td_modal **m)
{
    if (!m || !*m)
        return;
    free((*m)->modes);
    free((*m)->shapes);
    free((*m)->real);
    free(*m);
    *m = NULL;
}

double td_modal_speed(const td_modal *m)
{
    return m ? m->omega : NAN;
}
int td_modal_mode_count(const td_modal *m)
{
    return m ? m->n_modes : 0;
}
int td_modal_real_count(const td_modal *m)
{
    return m ? m->n_real : 0;
}

int td_modal_rounding_count(const td_modal *m)
{
    return m ? m->n_rounding : 0;
}

double td_modal_rounding_bound(const td_modal *m)
{
    return m ? m->rounding_bound : 0.0;
}
int td_modal_node_count(const td_modal *m)
{
    return m ? m->nnodes : 0;
}
double td_modal_max_real_part(const td_modal *m)
{
    return m ? m->max_real : NAN;
}
double td_modal_spectral_radius(const td_modal *m)
{
    double radius = 0.0;
    int i;
    for (i = 0; m && i < m->n_modes; i++)
        radius = fmax(radius, m->modes[i].omega_n);
    for (i = 0; m && i < m->n_real; i++)
        radius = fmax(radius, fabs(m->real[i]));
    return radius;
}
double td_modal_sample_rate(const td_modal *m)
{
    return m ? m->sample_rate : 0.0;
}
double td_modal_rounding_scale(const td_modal *m)
{
    return m ? rounding_scale(td_modal_spectral_radius(m), m->sample_rate) : 0.0;
}
int td_modal_is_unstable(const td_modal *m)
{
    return m && grows(m->max_real, td_modal_spectral_radius(m), m->sample_rate);
}

td_status td_modal_get_mode(const td_modal *m, int i, td_mode *out)
{
    if (!m || !out || i < 0 || i >= m->n_modes)
        return TD_ERR_INVALID;
    *out = m->modes[i];
    return TD_OK;
}

double td_modal_real_eigenvalue(const td_modal *m, int i)
{
    if (!m || i < 0 || i >= m->n_real)
        return NAN;
    return m->real[i];
}

td_status td_modal_mode_shape(const td_modal *m, int i, double *x_re, double *x_im, double *y_re, double *y_im)
{
    const double *s;
    size_t nn;
    if (!m || i < 0 || i >= m->n_modes)
        return TD_ERR_INVALID;
    nn = (size_t)m->nnodes;
    s = m->shapes + (size_t)i * 4u * nn;
    if (x_re)
        memcpy(x_re, s, nn * sizeof *s);
    if (x_im)
        memcpy(x_im, s + nn, nn * sizeof *s);
    if (y_re)
        memcpy(y_re, s + 2 * nn, nn * sizeof *s);
    if (y_im)
        memcpy(y_im, s + 3 * nn, nn * sizeof *s);
    return TD_OK;
}
