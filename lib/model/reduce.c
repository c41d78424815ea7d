/*
 * Craig-Bampton reduction of the assembled rotor (docs/theory.md, "Reduced rotor").
 *
 * The physical DOFs are split into boundary b (the four DOFs of every node that carries a part:
 * disc or point mass, AMB actuator or sensor, plain bearing, retainer, unbalance) and interior i.
 * With the boundary held, the interior deflects statically as q_i = Psi q_b,
 *
 *   Psi = -K_ii^-1 K_ib                                   (constraint modes)
 *
 * and vibrates in the fixed-interface modes K_ii phi = w^2 M_ii phi, mass-normalised
 * (phi^T M_ii phi = 1); those with w / (2 pi) below the cut-off are kept as the columns of Phi. Then
 *
 *   q_phys = T q,   T = [I 0; Psi Phi],   q = [q_b; eta]
 *
 * and M_r = T^T M T, likewise K, C, G, and loads f_r = T^T f. The shaft's x-z and y-z planes are
 * uncoupled in M, K and C, so the fixed-interface modes are solved plane by plane: each mode lies in
 * one plane, and the reduced M, K, C keep the planes uncoupled exactly (their cross entries are exact
 * zeros and are not stored), while G couples them as before. The reduced matrices are small and
 * dense; they are stored in the compressed-column form of the full ones so every consumer works on
 * either. The AMBs act at boundary DOFs and stay outside K (system_internal.h).
 */
#include "model/model_internal.h"
#include "model/system_internal.h"
#include "util/error_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The partition of the physical DOFs. */
typedef struct partition {
    int nb, ni;
    int *b; /* nb physical indices of the boundary DOFs, node by node */
    int *i; /* ni physical indices of the interior DOFs, node by node */
} partition;

/* A kept fixed-interface mode: its frequency, plane (0: x-z, 1: y-z) and column in the plane's
 * eigenvector matrix. */
typedef struct kept_mode {
    double hz;
    int plane, col;
} kept_mode;

/* The working set of one reduction. */
typedef struct reduction {
    partition p;
    gsl_matrix *M, *K; /* physical, dense */
    gsl_matrix *Psi;   /* ni x nb */
    gsl_matrix *V[2];  /* per plane: eigenvectors over that plane's interior DOFs (mass-normalised) */
    int *plane_rows[2];
    int plane_n[2];
    kept_mode *kept;
    int nk;
    gsl_matrix *T; /* nphys x (nb + nk) */
} reduction;

/* 1 for every node that carries a part (the nodes whose DOFs the contact, AMB and forcing laws use). */
static int *boundary_flags(const td_model *m, int nnodes)
{
    int *f = calloc((size_t)nnodes, sizeof *f), k;
    if (!f)
        return NULL;
    for (k = 0; k < m->discs.count; k++)
        f[m->discs.items[k].node] = 1;
    for (k = 0; k < m->ambs.count; k++)
        f[m->ambs.items[k].node] = f[m->ambs.items[k].sensor_node] = 1;
    for (k = 0; k < m->bearings.count; k++)
        f[m->bearings.items[k].node] = 1;
    for (k = 0; k < m->retainers.count; k++)
        f[m->retainers.items[k].node] = 1;
    for (k = 0; k < m->unbalances.count; k++)
        f[m->unbalances.items[k].node] = 1;
    return f;
}

static td_status build_partition(const td_system *s, partition *p, td_error *err)
{
    int *flag = boundary_flags(s->model, s->nnodes), n, d;
    p->nb = p->ni = 0;
    p->b = malloc((size_t)s->nphys * sizeof *p->b);
    p->i = malloc((size_t)s->nphys * sizeof *p->i);
    if (!flag || !p->b || !p->i) {
        free(flag);
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory partitioning the DOFs");
    }
    for (n = 0; n < s->nnodes; n++)
        for (d = 0; d < TD_DOFS_PER_NODE; d++) {
            if (flag[n])
                p->b[p->nb++] = TD_DOF(n, d);
            else
                p->i[p->ni++] = TD_DOF(n, d);
        }
    free(flag);
    if (p->nb == 0)
        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"reduction", 0, "cutoff"}, NULL,
                                 "reduction: the rotor has no boundary node (no part on the shaft) to reduce onto");
    return TD_OK;
}

/* A dense copy of a compressed-column matrix. */
static gsl_matrix *dense_of(const cs_di *A)
{
    gsl_matrix *D = gsl_matrix_calloc((size_t)A->m, (size_t)A->n);
    int j, p;
    if (!D)
        return NULL;
    for (j = 0; j < A->n; j++)
        for (p = A->p[j]; p < A->p[j + 1]; p++)
            *gsl_matrix_ptr(D, (size_t)A->i[p], (size_t)j) += A->x[p];
    return D;
}

/* out = A(rows, cols) */
static gsl_matrix *submatrix(const gsl_matrix *A, const int *rows, int nr, const int *cols, int nc)
{
    gsl_matrix *S = gsl_matrix_alloc((size_t)(nr > 0 ? nr : 1), (size_t)(nc > 0 ? nc : 1));
    int r, c;
    if (!S)
        return NULL;
    for (r = 0; r < nr; r++)
        for (c = 0; c < nc; c++)
            gsl_matrix_set(S, (size_t)r, (size_t)c, gsl_matrix_get(A, (size_t)rows[r], (size_t)cols[c]));
    return S;
}

/* Psi = -K_ii^-1 K_ib by Cholesky: K_ii is positive definite when every interior stretch of shaft
 * ends at a boundary node, which holds it. */
static td_status constraint_modes(reduction *r, td_error *err)
{
    gsl_matrix *Kii = submatrix(r->K, r->p.i, r->p.ni, r->p.i, r->p.ni);
    td_status st = TD_OK;
    r->Psi = submatrix(r->K, r->p.i, r->p.ni, r->p.b, r->p.nb);
    if (!Kii || !r->Psi)
        st = td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the constraint modes");
    else if (gsl_linalg_cholesky_decomp1(Kii) != GSL_SUCCESS || gsl_linalg_cholesky_svx_mat(Kii, r->Psi) != GSL_SUCCESS)
        st = td_error_set(err, TD_ERR_NUMERIC, "reduction: the interior stiffness K_ii is not positive definite");
    else
        gsl_matrix_scale(r->Psi, -1.0);
    gsl_matrix_free(Kii);
    return st;
}

/* Rows (positions in the interior list) of the interior DOFs of one plane: x-z holds x and phi,
 * y-z holds y and theta (touchdown/dofs.h). */
static int plane_rows(const partition *p, int plane, int *rows)
{
    int k, n = 0;
    for (k = 0; k < p->ni; k++) {
        int off = p->i[k] % TD_DOFS_PER_NODE;
        int in_x = off == TD_DOF_X || off == TD_DOF_PHI;
        if (in_x == (plane == 0))
            rows[n++] = k;
    }
    return n;
}

/* Scale the columns of V to unit modal mass v^T M v = 1 (GSL returns unit-norm vectors). */
static void mass_normalise(gsl_matrix *V, const gsl_matrix *M, gsl_vector *work)
{
    size_t j;
    for (j = 0; j < V->size2; j++) {
        gsl_vector_view v = gsl_matrix_column(V, j);
        double mm;
        gsl_blas_dgemv(CblasNoTrans, 1.0, M, &v.vector, 0.0, work);
        gsl_blas_ddot(&v.vector, work, &mm);
        gsl_vector_scale(&v.vector, 1.0 / sqrt(mm));
    }
}

/* Solve K_pp phi = w^2 M_pp phi on one plane's interior DOFs; kept modes appended to r->kept. */
static td_status plane_modes(reduction *r, int plane, double cutoff, td_error *err)
{
    int n = r->plane_n[plane], k, *rows = r->plane_rows[plane], *phys = malloc((size_t)(n > 0 ? n : 1) * sizeof *phys);
    gsl_matrix *Kp = NULL, *Mp = NULL, *Mc = NULL;
    gsl_vector *eval = NULL, *work = NULL;
    gsl_eigen_gensymmv_workspace *w = NULL;
    td_status st = TD_OK;
    if (n == 0) {
        free(phys);
        return TD_OK;
    }
    for (k = 0; phys && k < n; k++)
        phys[k] = r->p.i[rows[k]];
    if (phys) {
        Kp = submatrix(r->K, phys, n, phys, n);
        Mp = submatrix(r->M, phys, n, phys, n);
        Mc = submatrix(r->M, phys, n, phys, n);
    }
    eval = gsl_vector_alloc((size_t)n);
    work = gsl_vector_alloc((size_t)n);
    r->V[plane] = gsl_matrix_alloc((size_t)n, (size_t)n);
    w = gsl_eigen_gensymmv_alloc((size_t)n);
    if (!phys || !Kp || !Mp || !Mc || !eval || !work || !r->V[plane] || !w)
        st = td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the fixed-interface modes");
    else if (gsl_eigen_gensymmv(Kp, Mp, eval, r->V[plane], w) != GSL_SUCCESS)
        st = td_error_set(err, TD_ERR_NUMERIC, "reduction: the fixed-interface eigenproblem failed");
    if (st == TD_OK) {
        mass_normalise(r->V[plane], Mc, work);
        for (k = 0; k < n; k++) {
            double hz = sqrt(fmax(gsl_vector_get(eval, (size_t)k), 0.0)) / (2.0 * TD_PI);
            if (hz < cutoff)
                r->kept[r->nk++] = (kept_mode){hz, plane, k};
        }
    }
    gsl_eigen_gensymmv_free(w);
    gsl_vector_free(work);
    gsl_vector_free(eval);
    gsl_matrix_free(Mc);
    gsl_matrix_free(Mp);
    gsl_matrix_free(Kp);
    free(phys);
    return st;
}

/* Ascending frequency; the x-z plane first in a tie (an isotropic shaft's pairs), then by column. */
static int cmp_kept(const void *a, const void *b)
{
    const kept_mode *x = a, *y = b;
    if (x->hz != y->hz)
        return x->hz < y->hz ? -1 : 1;
    if (x->plane != y->plane)
        return x->plane - y->plane;
    return x->col - y->col;
}

static td_status fixed_interface_modes(reduction *r, double cutoff, td_error *err)
{
    int plane;
    td_status st = TD_OK;
    r->kept = malloc((size_t)(r->p.ni > 0 ? r->p.ni : 1) * sizeof *r->kept);
    if (!r->kept)
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the fixed-interface modes");
    for (plane = 0; plane < 2 && st == TD_OK; plane++) {
        r->plane_rows[plane] = malloc((size_t)(r->p.ni > 0 ? r->p.ni : 1) * sizeof *r->plane_rows[plane]);
        if (!r->plane_rows[plane])
            return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the fixed-interface modes");
        r->plane_n[plane] = plane_rows(&r->p, plane, r->plane_rows[plane]);
        st = plane_modes(r, plane, cutoff, err);
    }
    if (st == TD_OK)
        qsort(r->kept, (size_t)r->nk, sizeof *r->kept, cmp_kept);
    return st;
}

/* T = [I 0; Psi Phi] in the physical row order. */
static td_status build_transform(reduction *r, int nphys, td_error *err)
{
    int nq = r->p.nb + r->nk, k, j;
    r->T = gsl_matrix_calloc((size_t)nphys, (size_t)nq);
    if (!r->T)
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the transformation");
    for (k = 0; k < r->p.nb; k++)
        gsl_matrix_set(r->T, (size_t)r->p.b[k], (size_t)k, 1.0);
    for (k = 0; k < r->p.ni; k++)
        for (j = 0; j < r->p.nb; j++)
            gsl_matrix_set(r->T, (size_t)r->p.i[k], (size_t)j, gsl_matrix_get(r->Psi, (size_t)k, (size_t)j));
    for (j = 0; j < r->nk; j++) {
        const kept_mode *km = &r->kept[j];
        for (k = 0; k < r->plane_n[km->plane]; k++) {
            int row = r->p.i[r->plane_rows[km->plane][k]];
            gsl_matrix_set(r->T, (size_t)row, (size_t)(r->p.nb + j),
                           gsl_matrix_get(r->V[km->plane], (size_t)k, (size_t)km->col));
        }
    }
    return TD_OK;
}

/* T^T A T, made exactly symmetric (sign +1: M, K, C) or skew-symmetric (sign -1: G), as compressed
 * columns without its exact zeros. NULL on out-of-memory. */
static cs_di *project(const gsl_matrix *T, const cs_di *A, double sign)
{
    size_t nq = T->size2, i, j;
    gsl_matrix *D = dense_of(A), *W = gsl_matrix_alloc(T->size1, nq), *R = gsl_matrix_alloc(nq, nq);
    cs_di *out = NULL, *C = NULL;
    if (D && W && R) {
        gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, D, T, 0.0, W);
        gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, T, W, 0.0, R);
        C = cs_di_spalloc((int)nq, (int)nq, (int)(nq * nq), 1, 0);
    }
    if (C) {
        int nz = 0;
        for (j = 0; j < nq; j++) {
            C->p[j] = nz;
            for (i = 0; i < nq; i++) {
                double v = 0.5 * (gsl_matrix_get(R, i, j) + sign * gsl_matrix_get(R, j, i));
                if (v != 0.0) {
                    C->i[nz] = (int)i;
                    C->x[nz++] = v;
                }
            }
        }
        C->p[nq] = nz;
        out = C;
    }
    gsl_matrix_free(R);
    gsl_matrix_free(W);
    gsl_matrix_free(D);
    return out;
}

/* The reduced matrices and gravity load replace the physical ones in s. */
static td_status apply(td_system *s, const reduction *r, td_error *err)
{
    cs_di *M = project(r->T, s->M, 1.0), *K = project(r->T, s->K, 1.0), *C = project(r->T, s->C, 1.0),
          *G = project(r->T, s->G, -1.0);
    size_t nq = r->T->size2;
    double *g = calloc(nq, sizeof *g);
    gsl_vector_const_view gp = gsl_vector_const_view_array(s->gravity_load, (size_t)s->nphys);
    gsl_vector_view gq = gsl_vector_view_array(g ? g : (double[1]){0}, g ? nq : 1);
    if (!M || !K || !C || !G || !g) {
        cs_di_spfree(M), cs_di_spfree(K), cs_di_spfree(C), cs_di_spfree(G), free(g);
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the reduced matrices");
    }
    gsl_blas_dgemv(CblasTrans, 1.0, r->T, &gp.vector, 0.0, &gq.vector); /* f_r = T^T f */
    cs_di_spfree(s->M), cs_di_spfree(s->K), cs_di_spfree(s->C), cs_di_spfree(s->G), free(s->gravity_load);
    s->M = M, s->K = K, s->C = C, s->G = G, s->gravity_load = g;
    s->ndof = (int)nq;
    return TD_OK;
}

/* The maps between q and the nodes, the transformation kept column-major, the modes' data. */
static td_status record(td_system *s, const reduction *r, td_error *err)
{
    int nq = r->p.nb + r->nk, k, j;
    s->phys_to_q = malloc((size_t)s->nphys * sizeof *s->phys_to_q);
    s->q_node = malloc((size_t)nq * sizeof *s->q_node);
    s->T = malloc((size_t)s->nphys * (size_t)nq * sizeof *s->T);
    s->mode_freq = calloc((size_t)(r->nk > 0 ? r->nk : 1), sizeof *s->mode_freq);
    s->mode_amp = calloc((size_t)(r->nk > 0 ? r->nk : 1), sizeof *s->mode_amp);
    if (!s->phys_to_q || !s->q_node || !s->T || !s->mode_freq || !s->mode_amp)
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the coordinate map");
    for (k = 0; k < s->nphys; k++)
        s->phys_to_q[k] = -1;
    for (k = 0; k < nq; k++)
        s->q_node[k] = k < r->p.nb ? r->p.b[k] / TD_DOFS_PER_NODE : -1;
    for (k = 0; k < r->p.nb; k++)
        s->phys_to_q[r->p.b[k]] = k;
    for (j = 0; j < nq; j++)
        for (k = 0; k < s->nphys; k++)
            s->T[k + (size_t)j * (size_t)s->nphys] = gsl_matrix_get(r->T, (size_t)k, (size_t)j);
    s->n_modes = r->nk;
    for (j = 0; j < r->nk; j++) {
        s->mode_freq[j] = r->kept[j].hz;
        for (k = 0; k < s->nphys; k++) {
            int off = k % TD_DOFS_PER_NODE;
            double a = fabs(gsl_matrix_get(r->T, (size_t)k, (size_t)(r->p.nb + j)));
            if ((off == TD_DOF_X || off == TD_DOF_Y) && a > s->mode_amp[j])
                s->mode_amp[j] = a;
        }
    }
    return TD_OK;
}

static void reduction_free(reduction *r)
{
    free(r->p.b);
    free(r->p.i);
    gsl_matrix_free(r->M);
    gsl_matrix_free(r->K);
    gsl_matrix_free(r->Psi);
    gsl_matrix_free(r->V[0]);
    gsl_matrix_free(r->V[1]);
    free(r->plane_rows[0]);
    free(r->plane_rows[1]);
    free(r->kept);
    gsl_matrix_free(r->T);
}

td_status td_system_reduce(td_system *s, td_error *err)
{
    reduction r;
    td_status st;
    memset(&r, 0, sizeof r);
    gsl_set_error_handler_off();
    st = build_partition(s, &r.p, err);
    if (st == TD_OK) {
        r.M = dense_of(s->M);
        r.K = dense_of(s->K);
        if (!r.M || !r.K)
            st = td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the dense matrices");
    }
    if (st == TD_OK)
        st = constraint_modes(&r, err);
    if (st == TD_OK)
        st = fixed_interface_modes(&r, s->model->reduction_cutoff, err);
    if (st == TD_OK)
        st = build_transform(&r, s->nphys, err);
    if (st == TD_OK)
        st = record(s, &r, err);
    if (st == TD_OK)
        st = apply(s, &r, err);
    reduction_free(&r);
    return st;
}

void td_system_reduction_free(td_system *s)
{
    free(s->phys_to_q);
    free(s->q_node);
    free(s->T);
    free(s->mode_freq);
    free(s->mode_amp);
    s->phys_to_q = s->q_node = NULL;
    s->T = s->mode_freq = s->mode_amp = NULL;
    s->n_modes = 0;
}

int td_system_coordinate_node(const td_system *s, int i, int *offset)
{
    if (offset)
        *offset = s->q_node ? (s->q_node[i] >= 0 ? i % TD_DOFS_PER_NODE : -1) : i % TD_DOFS_PER_NODE;
    if (!s->q_node)
        return i / TD_DOFS_PER_NODE;
    return s->q_node[i];
}

double td_system_coordinate_amplitude(const td_system *s, int i)
{
    int k = i - (s->ndof - s->n_modes);
    return s->q_node && k >= 0 && s->mode_amp[k] > 0.0 ? s->mode_amp[k] : 1.0;
}

int td_system_is_reduced(const td_system *sys)
{
    return sys && sys->T ? 1 : 0;
}

int td_system_mode_count(const td_system *sys)
{
    return sys ? sys->n_modes : 0;
}

double td_system_mode_frequency(const td_system *sys, int i)
{
    return sys && i >= 0 && i < sys->n_modes ? sys->mode_freq[i] : NAN;
}

int td_system_physical_dof_count(const td_system *sys)
{
    return sys ? sys->nphys : 0;
}

int td_system_node_dof(const td_system *sys, int node, int offset)
{
    if (!sys || node < 0 || node >= sys->nnodes || offset < 0 || offset >= TD_DOFS_PER_NODE)
        return -1;
    return sys->phys_to_q ? sys->phys_to_q[TD_DOF(node, offset)] : TD_DOF(node, offset);
}

td_status td_system_expand(const td_system *sys, const double *q, double *q_phys, td_error *err)
{
    int i, j;
    if (!sys || !q || !q_phys)
        return td_error_set(err, TD_ERR_INVALID, "td_system_expand: NULL argument");
    if (!sys->T) {
        memcpy(q_phys, q, (size_t)sys->nphys * sizeof *q);
        return TD_OK;
    }
    for (i = 0; i < sys->nphys; i++)
        q_phys[i] = 0.0;
    for (j = 0; j < sys->ndof; j++)
        for (i = 0; q[j] != 0.0 && i < sys->nphys; i++)
            q_phys[i] += sys->T[i + (size_t)j * (size_t)sys->nphys] * q[j];
    return TD_OK;
}

void td_system_project_load(const td_system *s, const double *f_phys, double *f_q)
{
    int i, j;
    if (!s->T) {
        memcpy(f_q, f_phys, (size_t)s->nphys * sizeof *f_q);
        return;
    }
    for (j = 0; j < s->ndof; j++) {
        double sum = 0.0;
        for (i = 0; i < s->nphys; i++)
            sum += s->T[i + (size_t)j * (size_t)s->nphys] * f_phys[i];
        f_q[j] = sum;
    }
}
