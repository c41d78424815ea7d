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
 * and M_r = T^T M T, likewise K, C, G, and loads f_r = T^T f. With the boundary held, every stretch
 * of interior nodes between boundary nodes is a substructure of its own, and the shaft's x-z and y-z
 * planes are uncoupled in M, K and C: K_ii and M_ii are block-diagonal over (stretch, plane)
 * (checked, not assumed), and Psi and the modes are computed block by block (the cost grows with the
 * longest stretch, not the shaft). Each mode lies in one plane of one stretch, the reduced M, K, C
 * keep the planes uncoupled exactly (their cross entries are exact zeros and are not stored), while
 * G couples them as before.
 *
 * Gravity is a load on the interior too, which the constraint modes (no interior load) and the kept
 * modes reproduce only in part: its static deflection with the boundary held is
 * K_ii^-1 f_i = sum over every fixed-interface mode of phi (phi^T f_i) / w^2. Each stretch and plane
 * with a load gets the part the kept modes miss, u = K_gg^-1 f_g - sum_kept phi (phi^T f_g) / w^2
 * (the static correction, or residual flexibility, of the load: M- and K-orthogonal to the kept
 * modes), as one more column of T, mass-normalised, so that the reduced statics under gravity are
 * the full model's exactly (Galerkin: the exact static solution lies in the basis).
 *
 * The reduced matrices are small and dense; they are stored in the
 * compressed-column form of the full ones so every consumer works on either. The AMBs act at
 * boundary DOFs and stay outside K (system_internal.h).
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

/* One interior substructure: a stretch of consecutive interior nodes in one plane. With the
 * boundary held, stretches are uncoupled (a boundary node between two of them is fixed in all four
 * DOFs) and so are the planes (M, K of the shaft do not couple x-z with y-z): K_ii and M_ii are
 * block-diagonal over the groups, and each is solved on its own. */
typedef struct group {
    int plane;      /* 0: x-z (x, phi), 1: y-z (y, theta) */
    int n;          /* its DOFs */
    int *rows;      /* their positions in the interior list */
    gsl_matrix *V;  /* n x n fixed-interface modes, mass-normalised */
    gsl_vector *S;  /* n: the gravity load's static correction, mass-normalised; NULL if none */
    gsl_vector *w2; /* n: the squared circular frequencies of V's columns */
} group;

/* A kept fixed-interface mode: its frequency, plane, group and column in the group's V; col = -1:
 * the group's static correction S (hz: its Rayleigh quotient, above every kept mode's). */
typedef struct kept_mode {
    double hz;
    int plane, group, col;
} kept_mode;

/* The working set of one reduction. */
typedef struct reduction {
    partition p;
    const cs_di *M, *K; /* physical (the system's) */
    const double *load; /* nphys: the gravity load M g (the system's), for the static corrections */
    int *pos;           /* nphys: position of a physical DOF in the current group, -1 elsewhere */
    int *gid;           /* nphys: group of an interior DOF, -1 for a boundary one */
    gsl_matrix *Psi;    /* ni x nb */
    group *g;
    int ng;
    kept_mode *kept;
    int nk;
    int ns;        /* static corrections among the kept (the last ns) */
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
        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"reduction", 0, "cutoff"},
                                 &(td_error_site){NULL, -1, NULL},
                                 "the rotor has no boundary node (no part on the shaft) to reduce onto");
    return TD_OK;
}

static int in_x_plane(int phys)
{
    int off = phys % TD_DOFS_PER_NODE;
    return off == TD_DOF_X || off == TD_DOF_PHI;
}

/* Split the interior into groups: stretches of consecutive interior nodes (a boundary node ends
 * one), each in two planes. The groups' row lists are filled in interior order. */
static td_status build_groups(reduction *r, td_error *err)
{
    int k, seg = -1, prev = -2;
    r->g = calloc((size_t)(2 * r->p.ni + 1), sizeof *r->g);
    if (!r->g || !r->gid)
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the interior substructures");
    for (k = 0; k < r->p.nb; k++)
        r->gid[r->p.b[k]] = -1;
    for (k = 0; k < r->p.ni; k++) {
        int node = r->p.i[k] / TD_DOFS_PER_NODE;
        group *gr;
        if (node != prev && node != prev + 1)
            seg++;
        prev = node;
        gr = &r->g[2 * seg + !in_x_plane(r->p.i[k])];
        if (!gr->rows && !(gr->rows = malloc((size_t)r->p.ni * sizeof *gr->rows)))
            return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the interior substructures");
        gr->plane = !in_x_plane(r->p.i[k]);
        gr->rows[gr->n++] = k;
        r->gid[r->p.i[k]] = (int)(gr - r->g);
    }
    r->ng = 2 * (seg + 1);
    return TD_OK;
}

/* 1 if A couples two groups (an interior entry between them): the blocks would not be the whole
 * K_ii or M_ii. The shaft elements never do (elements.c: the planes apart, nodes coupled only to
 * their neighbours); this keeps an element that did from being reduced wrongly. */
static int couples_groups(const reduction *r, const cs_di *A)
{
    int j, p;
    for (j = 0; j < A->n; j++)
        for (p = A->p[j]; r->gid[j] >= 0 && p < A->p[j + 1]; p++)
            if (r->gid[A->i[p]] >= 0 && r->gid[A->i[p]] != r->gid[j] && A->x[p] != 0.0)
                return 1;
    return 0;
}

/* Dense A(rows of group gr, cols): cols are physical indices (NULL: the group's own DOFs, nc = n).
 * Reads the sparse columns, mapping rows through r->pos. NULL on out-of-memory. */
static gsl_matrix *group_block(const reduction *r, const group *gr, const cs_di *A, const int *cols, int nc)
{
    gsl_matrix *S = gsl_matrix_calloc((size_t)gr->n, (size_t)(nc > 0 ? nc : 1));
    int c, p;
    if (!S)
        return NULL;
    for (c = 0; c < nc; c++) {
        int j = cols ? cols[c] : r->p.i[gr->rows[c]];
        for (p = A->p[j]; p < A->p[j + 1]; p++)
            if (r->pos[A->i[p]] >= 0)
                *gsl_matrix_ptr(S, (size_t)r->pos[A->i[p]], (size_t)c) += A->x[p];
    }
    return S;
}

/* Psi rows of a group: -K_gg^-1 K_gb by Cholesky. K_gg is positive definite: every stretch of
 * shaft ends at a boundary node, which holds it. Kgg is factored in place. */
static td_status group_constraint_modes(reduction *r, const group *gr, gsl_matrix *Kgg, td_error *err)
{
    gsl_matrix *Kgb = group_block(r, gr, r->K, r->p.b, r->p.nb);
    td_status st = TD_OK;
    int k, j;
    if (!Kgb)
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the constraint modes");
    if (gsl_linalg_cholesky_decomp1(Kgg) != GSL_SUCCESS || gsl_linalg_cholesky_svx_mat(Kgg, Kgb) != GSL_SUCCESS)
        st = td_error_set(err, TD_ERR_NUMERIC, "reduction: the interior stiffness K_ii is not positive definite");
    for (k = 0; st == TD_OK && k < gr->n; k++)
        for (j = 0; j < r->p.nb; j++)
            gsl_matrix_set(r->Psi, (size_t)gr->rows[k], (size_t)j, -gsl_matrix_get(Kgb, (size_t)k, (size_t)j));
    gsl_matrix_free(Kgb);
    return st;
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

/* K_gg phi = w^2 M_gg phi on one group (Kgg, Mgg destroyed); kept modes appended to r->kept. */
static td_status group_modes(reduction *r, int gi, gsl_matrix *Kgg, gsl_matrix *Mgg, double cutoff, td_error *err)
{
    group *gr = &r->g[gi];
    gsl_matrix *Mc = gsl_matrix_alloc((size_t)gr->n, (size_t)gr->n);
    gsl_vector *eval = gsl_vector_alloc((size_t)gr->n), *work = gsl_vector_alloc((size_t)gr->n);
    gsl_eigen_gensymmv_workspace *w = gsl_eigen_gensymmv_alloc((size_t)gr->n);
    td_status st = TD_OK;
    int k;
    gr->V = gsl_matrix_alloc((size_t)gr->n, (size_t)gr->n);
    if (!Mc || !eval || !work || !w || !gr->V)
        st = td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the fixed-interface modes");
    else if (gsl_matrix_memcpy(Mc, Mgg) != GSL_SUCCESS || gsl_eigen_gensymmv(Kgg, Mgg, eval, gr->V, w) != GSL_SUCCESS)
        st = td_error_set(err, TD_ERR_NUMERIC, "reduction: the fixed-interface eigenproblem failed");
    if (st == TD_OK) {
        mass_normalise(gr->V, Mc, work);
        for (k = 0; k < gr->n; k++) {
            double hz = sqrt(fmax(gsl_vector_get(eval, (size_t)k), 0.0)) / (2.0 * TD_PI);
            if (hz < cutoff)
                r->kept[r->nk++] = (kept_mode){hz, gr->plane, gi, k};
        }
    }
    gsl_eigen_gensymmv_free(w);
    gsl_vector_free(work);
    gr->w2 = eval;
    gsl_matrix_free(Mc);
    return st;
}

/* The energy f^T u of the deflection the kept modes leave out, from the modes left out:
 * sum (phi^T f)^2 / w^2 over them (phi mass-normalised). Unlike f^T u it holds no rounding of the
 * solve (eps cond(K_gg) |u|): zero when the group keeps all its modes or f loads none of the others. */
static double left_out_energy(const reduction *r, int gi, const gsl_vector *f, char *kept)
{
    const group *gr = &r->g[gi];
    double sum = 0.0;
    int k;
    memset(kept, 0, (size_t)gr->n);
    for (k = 0; k < r->nk; k++)
        if (r->kept[k].group == gi && r->kept[k].col >= 0)
            kept[r->kept[k].col] = 1;
    for (k = 0; k < gr->n; k++) {
        gsl_vector_const_view phi = gsl_matrix_const_column(gr->V, (size_t)k);
        double pf;
        if (kept[k] || !(gsl_vector_get(gr->w2, (size_t)k) > 0.0))
            continue;
        gsl_blas_ddot(&phi.vector, f, &pf);
        sum += pf * pf / gsl_vector_get(gr->w2, (size_t)k);
    }
    return sum;
}

/* The gravity load's static correction of group gi (docs/theory.md, "Reduced rotor"): with Kchol
 * the Cholesky factor of K_gg and Mg its M_gg, u = K_gg^-1 f_g less the kept modes' share
 * phi (phi^T f_g) / w^2, appended to r->kept unless the modes left out hold none of the deflection
 * (u is then rounding, mostly along kept modes: the basis would be singular). */
static td_status group_static_correction(reduction *r, int gi, const gsl_matrix *Kchol, const gsl_matrix *Mg,
                                         td_error *err)
{
    group *gr = &r->g[gi];
    gsl_vector *f = gsl_vector_calloc((size_t)gr->n), *u = gsl_vector_alloc((size_t)gr->n);
    gsl_vector *w = gsl_vector_alloc((size_t)gr->n);
    char *kept = malloc((size_t)gr->n);
    double full = 0.0, left = 0.0, mass = 0.0, rest = 0.0;
    int k;
    if (!f || !u || !w || !kept) {
        gsl_vector_free(f), gsl_vector_free(u), gsl_vector_free(w), free(kept);
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for a static correction");
    }
    for (k = 0; k < gr->n; k++)
        gsl_vector_set(f, (size_t)k, r->load[r->p.i[gr->rows[k]]]);
    if (gsl_blas_dnrm2(f) > 0.0 && gsl_linalg_cholesky_solve(Kchol, f, u) == GSL_SUCCESS) {
        gsl_blas_ddot(f, u, &full); /* f^T K^-1 f: the static deflection's energy, doubled */
        for (k = 0; k < r->nk; k++) {
            gsl_vector_view phi;
            double pf, w2;
            if (r->kept[k].group != gi || r->kept[k].col < 0)
                continue;
            phi = gsl_matrix_column(gr->V, (size_t)r->kept[k].col);
            w2 = pow(2.0 * TD_PI * r->kept[k].hz, 2);
            gsl_blas_ddot(&phi.vector, f, &pf);
            gsl_blas_daxpy(-pf / w2, &phi.vector, u);
        }
        gsl_blas_ddot(f, u, &left); /* u^T K u = f^T u: u is M-orthogonal to the kept modes */
        gsl_blas_dgemv(CblasNoTrans, 1.0, Mg, u, 0.0, w);
        gsl_blas_ddot(u, w, &mass);
        rest = left_out_energy(r, gi, f, kept);
    }
    if (rest > 1e-12 * full && left > 0.0 && mass > 0.0) {
        gsl_vector_scale(u, 1.0 / sqrt(mass));
        gr->S = u;
        u = NULL;
        r->kept[r->nk++] = (kept_mode){sqrt(left / mass) / (2.0 * TD_PI), gr->plane, gi, -1};
        r->ns++;
    }
    gsl_vector_free(f), gsl_vector_free(u), gsl_vector_free(w), free(kept);
    return TD_OK;
}

/* Constraint-mode rows and fixed-interface modes of group gi. */
static td_status group_substructure(reduction *r, int gi, double cutoff, td_error *err)
{
    group *gr = &r->g[gi];
    gsl_matrix *K1, *K2, *Mg, *M2;
    td_status st;
    int k;
    for (k = 0; k < gr->n; k++)
        r->pos[r->p.i[gr->rows[k]]] = k;
    K1 = group_block(r, gr, r->K, NULL, gr->n);
    K2 = group_block(r, gr, r->K, NULL, gr->n);
    Mg = group_block(r, gr, r->M, NULL, gr->n);
    M2 = group_block(r, gr, r->M, NULL, gr->n);
    if (!K1 || !K2 || !Mg || !M2)
        st = td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for an interior substructure");
    else
        st = group_constraint_modes(r, gr, K1, err);
    if (st == TD_OK)
        st = group_modes(r, gi, K2, Mg, cutoff, err);
    if (st == TD_OK)
        st = group_static_correction(r, gi, K1, M2, err);
    for (k = 0; k < gr->n; k++)
        r->pos[r->p.i[gr->rows[k]]] = -1;
    gsl_matrix_free(K1);
    gsl_matrix_free(K2);
    gsl_matrix_free(Mg);
    gsl_matrix_free(M2);
    return st;
}

/* The fixed-interface modes by ascending frequency, then the static corrections; the x-z plane
 * first in a tie (an isotropic shaft's pairs), then by group and column. */
static int cmp_kept(const void *a, const void *b)
{
    const kept_mode *x = a, *y = b;
    if ((x->col < 0) != (y->col < 0))
        return x->col < 0 ? 1 : -1;
    if (x->hz != y->hz)
        return x->hz < y->hz ? -1 : 1;
    if (x->plane != y->plane)
        return x->plane - y->plane;
    if (x->group != y->group)
        return x->group - y->group;
    return x->col - y->col;
}

/* Psi and the kept fixed-interface modes, group by group. */
static td_status substructures(reduction *r, int nphys, double cutoff, td_error *err)
{
    int k;
    td_status st;
    r->gid = malloc((size_t)nphys * sizeof *r->gid);
    st = build_groups(r, err);
    if (st == TD_OK && (couples_groups(r, r->K) || couples_groups(r, r->M)))
        st = td_error_set(err, TD_ERR_INVALID,
                          "reduction: the shaft couples its x-z and y-z planes or "
                          "non-neighbouring nodes: no Craig-Bampton reduction for it");
    r->pos = malloc((size_t)nphys * sizeof *r->pos);
    /* each group's modes and at most one static correction */
    r->kept = malloc((size_t)(r->p.ni + r->ng + 1) * sizeof *r->kept);
    r->Psi = gsl_matrix_calloc((size_t)(r->p.ni > 0 ? r->p.ni : 1), (size_t)r->p.nb);
    if (st == TD_OK && (!r->pos || !r->kept || !r->Psi))
        st = td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the interior substructures");
    for (k = 0; st == TD_OK && k < nphys; k++)
        r->pos[k] = -1;
    for (k = 0; st == TD_OK && k < r->ng; k++)
        if (r->g[k].n > 0)
            st = group_substructure(r, k, cutoff, err);
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
        const group *gr = &r->g[km->group];
        for (k = 0; k < gr->n; k++)
            gsl_matrix_set(r->T, (size_t)r->p.i[gr->rows[k]], (size_t)(r->p.nb + j),
                           km->col < 0 ? gsl_vector_get(gr->S, (size_t)k)
                                       : gsl_matrix_get(gr->V, (size_t)k, (size_t)km->col));
    }
    return TD_OK;
}

/* W = A T for a sparse A (rows of T contiguous: W row i += A(i, c) T row c). */
static void sparse_times(const cs_di *A, const gsl_matrix *T, gsl_matrix *W)
{
    int c, p;
    gsl_matrix_set_zero(W);
    for (c = 0; c < A->n; c++)
        for (p = A->p[c]; p < A->p[c + 1]; p++) {
            gsl_vector_const_view tc = gsl_matrix_const_row(T, (size_t)c);
            gsl_vector_view wi = gsl_matrix_row(W, (size_t)A->i[p]);
            gsl_blas_daxpy(A->x[p], &tc.vector, &wi.vector);
        }
}

/* The dense R as compressed columns without its exact zeros, made exactly symmetric (sign +1) or
 * skew-symmetric (sign -1) against rounding. NULL on out-of-memory. */
static cs_di *compress_dense(const gsl_matrix *R, double sign)
{
    size_t nq = R->size1, i, j;
    cs_di *C = cs_di_spalloc((int)nq, (int)nq, (int)(nq * nq), 1, 0);
    int nz = 0;
    if (!C)
        return NULL;
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
    return C;
}

/* T^T A T (sign +1: M, K, C; -1: G), compressed. NULL on out-of-memory. */
static cs_di *project(const gsl_matrix *T, const cs_di *A, double sign)
{
    size_t nq = T->size2;
    gsl_matrix *W = gsl_matrix_alloc(T->size1, nq), *R = gsl_matrix_alloc(nq, nq);
    cs_di *out = NULL;
    if (W && R) {
        sparse_times(A, T, W);
        gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, T, W, 0.0, R);
        out = compress_dense(R, sign);
    }
    gsl_matrix_free(R);
    gsl_matrix_free(W);
    return out;
}

/* The housing motion's loads (physical, when the model has them) replaced by their projections
 * T^T f, as the gravity load: the work of a load on the reduced motion is that on the physical one. */
static td_status project_base_loads(td_system *s, const reduction *r)
{
    size_t nq = r->T->size2;
    int k;
    for (k = 0; k < 6; k++) {
        double **f = k < 4 ? &s->base_load[k] : &s->base_gyro[k - 4], *q = *f ? calloc(nq, sizeof *q) : NULL;
        if (!*f)
            continue;
        if (!q)
            return TD_ERR_NOMEM;
        gsl_vector_const_view fp = gsl_vector_const_view_array(*f, (size_t)s->nphys);
        gsl_vector_view fq = gsl_vector_view_array(q, nq);
        gsl_blas_dgemv(CblasTrans, 1.0, r->T, &fp.vector, 0.0, &fq.vector);
        free(*f);
        *f = q;
    }
    return TD_OK;
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
    if (project_base_loads(s, r) != TD_OK) {
        cs_di_spfree(M), cs_di_spfree(K), cs_di_spfree(C), cs_di_spfree(G), free(g);
        return td_error_set(err, TD_ERR_NOMEM, "reduction: out of memory for the housing motion's loads");
    }
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
    s->n_static = r->ns;
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
    int k;
    free(r->p.b);
    free(r->p.i);
    free(r->pos);
    free(r->gid);
    gsl_matrix_free(r->Psi);
    for (k = 0; r->g && k < 2 * r->p.ni + 1; k++) {
        free(r->g[k].rows);
        gsl_matrix_free(r->g[k].V);
        gsl_vector_free(r->g[k].S);
        gsl_vector_free(r->g[k].w2);
    }
    free(r->g);
    free(r->kept);
    gsl_matrix_free(r->T);
}

td_status td_system_reduce(td_system *s, td_error *err)
{
    reduction r;
    td_status st;
    memset(&r, 0, sizeof r);
    gsl_set_error_handler_off();
    r.M = s->M;
    r.K = s->K;
    r.load = s->gravity_load;
    st = build_partition(s, &r.p, err);
    if (st == TD_OK)
        st = substructures(&r, s->nphys, s->model->reduction_cutoff, err);
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
    s->n_static = 0;
}

int td_system_coordinate_node(const td_system *s, int i, int *offset)
{
    if (i >= s->ndof - s->nbody) { /* a housing body's DOF (assemble_body.c) */
        if (offset)
            *offset = -1;
        return -1;
    }
    if (offset)
        *offset = s->q_node ? (s->q_node[i] >= 0 ? i % TD_DOFS_PER_NODE : -1) : i % TD_DOFS_PER_NODE;
    if (!s->q_node)
        return i / TD_DOFS_PER_NODE;
    return s->q_node[i];
}

double td_system_coordinate_amplitude(const td_system *s, int i)
{
    int k = i - (s->ndof - s->nbody - s->n_modes);
    return s->q_node && k >= 0 && k < s->n_modes && s->mode_amp[k] > 0.0 ? s->mode_amp[k] : 1.0;
}

int td_system_is_reduced(const td_system *sys)
{
    return sys && sys->T ? 1 : 0;
}

int td_system_mode_count(const td_system *sys)
{
    return sys ? sys->n_modes - sys->n_static : 0;
}

int td_system_static_correction_count(const td_system *sys)
{
    return sys ? sys->n_static : 0;
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
        for (j = s->nphys; j < s->ndof; j++) /* a housing body's rows: its share below */
            f_q[j] = 0.0;
    } else
        for (j = 0; j < s->ndof; j++) {
            double sum = 0.0;
            for (i = 0; i < s->nphys; i++)
                sum += s->T[i + (size_t)j * (size_t)s->nphys] * f_phys[i];
            f_q[j] = sum;
        }
}

double td_system_node_displacement(const td_system *sys, const double *q, int node, int offset)
{
    int row, j;
    double sum = 0.0;
    if (!sys || !q || node < 0 || node >= sys->nnodes || offset < 0 || offset >= TD_DOFS_PER_NODE)
        return NAN;
    row = TD_DOF(node, offset);
    if (!sys->T)
        return q[row];
    for (j = 0; j < sys->ndof; j++)
        sum += sys->T[row + (size_t)j * (size_t)sys->nphys] * q[j];
    return sum;
}
