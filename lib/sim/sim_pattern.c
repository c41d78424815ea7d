/*
 * The Jacobian's sparsity pattern: one fixed compressed-column pattern, the union of every entry
 * any mode can write (system matrices, AMB couplings, linear controllers, every retainer's constraint, friction and
 * penalty blocks, the diagonal of the multiplier rows). A mode switch therefore never changes
 * the structure: KLU's symbolic analysis is done once.
 */
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

/* Entry (row, col) into the triplet matrix T. */
static int put(cs_di *T, int row, int col)
{
    return cs_di_entry(T, row, col, 1.0);
}

/* The 2 x 2 block rows {r0, r1} x cols {c0, c1}. */
static int put_block(cs_di *T, int r0, int r1, int c0, int c1)
{
    return put(T, r0, c0) && put(T, r0, c1) && put(T, r1, c0) && put(T, r1, c1);
}

static int put_matrix(cs_di *T, const cs_di *A, int roff, int coff)
{
    int j, p;
    for (j = 0; j < A->n; j++)
        for (p = A->p[j]; p < A->p[j + 1]; p++)
            if (!put(T, roff + A->i[p], coff + j))
                return 0;
    return 1;
}

/* Retainer k with a race or a rolling state: every coupling among its contact DOFs (node x, y,
 * race x, y, race speed) in q and v, and between them and its multipliers (lambda, eta, F_t). A
 * superset of what a mode writes. */
static int put_race(const td_sim *s, cs_di *T, int k)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    int dofs[6], nd = 0, i, j, ok = 1;
    dofs[nd++] = r->dx;
    dofs[nd++] = r->dy;
    if (r->rx >= 0) {
        dofs[nd++] = r->rx;
        dofs[nd++] = r->ry;
    }
    if (r->rs >= 0)
        dofs[nd++] = r->rs;
    if (s->machine.spin >= 0)
        dofs[nd++] = s->machine.spin;
    for (i = 0; i < nd && ok; i++) {
        int vi = s->dae.ov + dofs[i], qi = s->dae.oq + dofs[i];
        ok = put(T, vi, s->dae.ol + k) && put(T, qi, s->dae.ou + k) && put(T, s->dae.ol + k, qi) &&
             put(T, s->dae.ou + k, qi) && put(T, s->dae.ou + k, vi);
        for (j = 0; j < nd && ok; j++)
            ok = put(T, vi, s->dae.oq + dofs[j]) && put(T, vi, s->dae.ov + dofs[j]) && put(T, qi, s->dae.oq + dofs[j]);
        if (ok && r->fi >= 0) { /* F_t: its column in the v rows, its row v_s over q and v */
            int fk = s->dae.of + r->fi;
            ok = put(T, vi, fk) && put(T, fk, qi) && put(T, fk, vi) && put(T, fk, fk);
        }
    }
    return ok;
}

/* The spin DOF's columns (spin.c): every row G reaches (Omega G v) and the unbalances' rows. */
static int put_spin(const td_sim *s, cs_di *T)
{
    int j, p, i, ok = 1;
    if (s->machine.spin < 0)
        return 1;
    for (j = 0; j < s->dae.G->n && ok; j++)
        for (p = s->dae.G->p[j]; p < s->dae.G->p[j + 1] && ok; p++)
            ok = put(T, s->dae.ov + s->dae.G->i[p], s->dae.ov + s->machine.spin);
    for (i = 0; i < s->machine.nu && ok; i++) {
        int x = s->dae.ov + td_system_node_dof(s->sys, s->machine.unb[i].node, TD_DOF_X),
            y = s->dae.ov + td_system_node_dof(s->sys, s->machine.unb[i].node, TD_DOF_Y);
        ok = put(T, x, s->dae.oq + s->machine.spin) && put(T, y, s->dae.oq + s->machine.spin) &&
             put(T, x, s->dae.ov + s->machine.spin) && put(T, y, s->dae.ov + s->machine.spin) &&
             put(T, s->dae.ov + s->machine.spin, x) && put(T, s->dae.ov + s->machine.spin, y);
    }
    return ok;
}

/* The entries of the linear controllers (sim_lti.c): each continuous law's rows over its states
 * and its inputs' sensors, and the row each driven axis's current enters (its lag state's, or
 * the actuator's v row) over the same columns and the sensors' velocities. */
static int put_lti(const td_sim *s, cs_di *T)
{
    int k, l, r, j, m, ok = 1;
    for (l = 0; l < s->sys->n_laws && ok; l++) {
        const td_lti_law *L = &s->sys->laws[l];
        for (r = 0; L->state >= 0 && r < L->n && ok; r++) {
            int row = s->dae.ow + L->state + r;
            for (j = 0; j < L->n && ok; j++)
                ok = put(T, row, s->dae.ow + L->state + j);
            for (m = 0; m < L->nin && ok; m++)
                ok = put(T, row, s->dae.oq + s->sys->amb_axes[L->in_axis[m]].sensor_dof);
        }
    }
    for (k = 0; k < s->sys->n_amb_axes && ok; k++) {
        const td_amb_axis *a = &s->sys->amb_axes[k];
        const td_lti_law *L;
        int row = a->state >= 0 ? s->dae.ow + a->state : s->dae.ov + a->actuator_dof;
        if (a->law < 0 || (L = &s->sys->laws[a->law])->state < 0)
            continue;
        for (j = 0; j < L->n && ok; j++)
            ok = put(T, row, s->dae.ow + L->state + j);
        for (m = 0; m < L->nin && ok; m++)
            ok = put(T, row, s->dae.oq + s->sys->amb_axes[L->in_axis[m]].sensor_dof) &&
                 put(T, row, s->dae.ov + s->sys->amb_axes[L->in_axis[m]].sensor_dof);
    }
    return ok;
}

static int put_all(const td_sim *s, cs_di *T)
{
    const td_system *sys = s->sys;
    int i, k, ok = 1;
    for (i = 0; i < s->dae.n && ok; i++)
        ok = put(T, s->dae.oq + i, s->dae.oq + i) && put(T, s->dae.oq + i, s->dae.ov + i);
    ok = ok && put_matrix(T, s->dae.M, s->dae.ov, s->dae.ov) && put_matrix(T, s->dae.C, s->dae.ov, s->dae.ov) &&
         put_matrix(T, s->dae.G, s->dae.ov, s->dae.ov) && put_matrix(T, s->dae.K, s->dae.ov, s->dae.oq);
    for (k = 0; k < sys->n_amb_axes && ok; k++) {
        const td_amb_axis *a = &sys->amb_axes[k];
        int act = a->actuator_dof, sen = a->sensor_dof;
        ok = put(T, s->dae.ov + act, s->dae.oq + act) && put(T, s->dae.ov + act, s->dae.oq + sen) &&
             put(T, s->dae.ov + act, s->dae.ov + sen);
        if (ok && a->state >= 0) {
            int w = s->dae.ow + a->state;
            ok = put(T, s->dae.ov + act, w) && put(T, w, w) && put(T, w, s->dae.oq + sen) && put(T, w, s->dae.ov + sen);
        }
        if (ok && a->integral >= 0) {
            int e = s->dae.ow + a->integral, w = a->state >= 0 ? s->dae.ow + a->state : s->dae.ov + act;
            ok = put(T, w, e) && put(T, e, e) && put(T, e, s->dae.oq + sen);
        }
    }
    for (k = 0; k < s->dae.nr && ok; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        int qx = s->dae.oq + r->dx, qy = s->dae.oq + r->dy, vx = s->dae.ov + r->dx, vy = s->dae.ov + r->dy;
        int lk = s->dae.ol + k, uk = s->dae.ou + k;
        ok = put_block(T, vx, vy, qx, qy) && put_block(T, vx, vy, vx, vy) && put(T, vx, lk) && put(T, vy, lk) &&
             put(T, qx, uk) && put(T, qy, uk) && put(T, lk, lk) && put(T, lk, qx) && put(T, lk, qy) && put(T, uk, uk) &&
             put(T, uk, qx) && put(T, uk, qy) && put(T, uk, vx) && put(T, uk, vy);
        if (ok && (r->rx >= 0 || r->rs >= 0 || r->fi >= 0 || s->machine.spin >= 0))
            ok = put_race(s, T, k);
    }
    return ok && put_spin(s, T) && put_lti(s, T);
}

int td_sim_pattern_find(const td_sim *s, int row, int col)
{
    int lo = s->ops.colptr[col], hi = s->ops.colptr[col + 1] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2, r = s->ops.rowind[mid];
        if (r == row)
            return mid;
        if (r < row)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

static int *map_matrix(const td_sim *s, const cs_di *A, int roff, int coff)
{
    int j, p, nz = A->p[A->n];
    int *map = malloc(sizeof(int) * (size_t)(nz > 0 ? nz : 1));
    if (!map)
        return NULL;
    for (j = 0; j < A->n; j++)
        for (p = A->p[j]; p < A->p[j + 1]; p++)
            map[p] = td_sim_pattern_find(s, roff + A->i[p], coff + j);
    return map;
}

/* Where G's entry p times v_j goes in the speed's column (the free spin's d(G v Omega)/dOmega,
 * sim_residual.c jacobian_spin): looked up once here, not at every Jacobian. */
static int *map_spin_column(const td_sim *s)
{
    const cs_di *G = s->dae.G;
    int p, nz = G->p[G->n], *map = malloc(sizeof(int) * (size_t)(nz > 0 ? nz : 1));
    if (!map)
        return NULL;
    for (p = 0; p < nz; p++)
        map[p] = td_sim_pattern_find(s, s->dae.ov + G->i[p], s->dae.ov + s->machine.spin);
    return map;
}

td_status td_sim_pattern_build(td_sim *s, td_error *err)
{
    cs_di *T = cs_di_spalloc(s->dae.neq, s->dae.neq, 16 * s->dae.neq, 1, 1), *C = NULL, *Ct = NULL, *S = NULL;
    int ok = T != NULL && put_all(s, T);
    /* compress, sum duplicates, and sort row indices by transposing twice */
    if (ok)
        ok = (C = cs_di_compress(T)) != NULL && cs_di_dupl(C) && (Ct = cs_di_transpose(C, 1)) != NULL &&
             (S = cs_di_transpose(Ct, 1)) != NULL;
    cs_di_spfree(T);
    cs_di_spfree(C);
    cs_di_spfree(Ct);
    if (!ok) {
        cs_di_spfree(S);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the Jacobian pattern");
    }
    s->ops.nnz = S->p[S->n];
    s->ops.colptr = malloc(sizeof(int) * (size_t)(s->dae.neq + 1));
    s->ops.rowind = malloc(sizeof(int) * (size_t)s->ops.nnz);
    s->ops.jdata = calloc((size_t)s->ops.nnz, sizeof(double));
    if (s->ops.colptr && s->ops.rowind && s->ops.jdata) {
        int i;
        for (i = 0; i <= s->dae.neq; i++)
            s->ops.colptr[i] = S->p[i];
        for (i = 0; i < s->ops.nnz; i++)
            s->ops.rowind[i] = S->i[i];
    }
    cs_di_spfree(S);
    if (!s->ops.colptr || !s->ops.rowind || !s->ops.jdata)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the Jacobian pattern");
    s->ops.map_M = map_matrix(s, s->dae.M, s->dae.ov, s->dae.ov);
    s->ops.map_C = map_matrix(s, s->dae.C, s->dae.ov, s->dae.ov);
    s->ops.map_G = map_matrix(s, s->dae.G, s->dae.ov, s->dae.ov);
    s->ops.map_K = map_matrix(s, s->dae.K, s->dae.ov, s->dae.oq);
    if (!s->ops.map_M || !s->ops.map_C || !s->ops.map_G || !s->ops.map_K)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the Jacobian pattern");
    if (s->machine.spin >= 0 && !(s->ops.map_Gw = map_spin_column(s)))
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the Jacobian pattern");
    return TD_OK;
}

/* ---- the structural operator M v' + (C + Omega G) v + K q, row-compressed ------------------- */

/* Position of column col in row `row` of the structural pattern (always present). */
static int st_find(const td_sim *s, int row, int col)
{
    int lo = s->ops.st_rowptr[row], hi = s->ops.st_rowptr[row + 1] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2, c = s->ops.st_col[mid];
        if (c == col)
            return mid;
        if (c < col)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

/* vals[pos(i, j)] += scale * A(i, j) for every stored entry of A. */
static void st_add(const td_sim *s, const cs_di *A, double scale, double *vals)
{
    int j, p;
    for (j = 0; j < A->n; j++)
        for (p = A->p[j]; p < A->p[j + 1]; p++) {
            int pos = st_find(s, A->i[p], j);
            if (pos >= 0)
                vals[pos] += scale * A->x[p];
        }
}

void td_sim_structural_speed(td_sim *s)
{
    if (!s->ops.st_D)
        return;
    memset(s->ops.st_D, 0, sizeof(double) * (size_t)(s->ops.st_nnz > 0 ? s->ops.st_nnz : 1));
    st_add(s, s->dae.C, 1.0, s->ops.st_D);
    if (s->machine.omega != 0.0)
        st_add(s, s->dae.G, s->machine.omega, s->ops.st_D);
}

td_status td_sim_structural_build(td_sim *s, td_error *err)
{
    cs_di *T = cs_di_spalloc(s->dae.n, s->dae.n, 1, 1, 1), *C = NULL, *R = NULL;
    int ok = T != NULL, i;
    /* the union pattern, transposed: the CSC of U^T is the CSR of U, with sorted columns */
    ok = ok && put_matrix(T, s->dae.M, 0, 0) && put_matrix(T, s->dae.K, 0, 0) && put_matrix(T, s->dae.C, 0, 0) &&
         put_matrix(T, s->dae.G, 0, 0);
    for (i = 0; i < s->dae.n && ok; i++) /* every row present, even an empty one */
        ok = put(T, i, i);
    ok = ok && (C = cs_di_compress(T)) != NULL && cs_di_dupl(C) && (R = cs_di_transpose(C, 0)) != NULL;
    cs_di_spfree(T);
    cs_di_spfree(C);
    if (!ok) {
        cs_di_spfree(R);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the structural operator");
    }
    /* cs_di_transpose sorts the row indices of each column of the result */
    s->ops.st_nnz = R->p[R->n];
    s->ops.st_rowptr = malloc(sizeof(int) * (size_t)(s->dae.n + 1));
    s->ops.st_col = malloc(sizeof(int) * (size_t)(s->ops.st_nnz > 0 ? s->ops.st_nnz : 1));
    s->ops.st_M = calloc((size_t)(s->ops.st_nnz > 0 ? s->ops.st_nnz : 1), sizeof(double));
    s->ops.st_K = calloc((size_t)(s->ops.st_nnz > 0 ? s->ops.st_nnz : 1), sizeof(double));
    s->ops.st_D = calloc((size_t)(s->ops.st_nnz > 0 ? s->ops.st_nnz : 1), sizeof(double));
    if (s->ops.st_rowptr && s->ops.st_col) {
        for (i = 0; i <= s->dae.n; i++)
            s->ops.st_rowptr[i] = R->p[i];
        for (i = 0; i < s->ops.st_nnz; i++)
            s->ops.st_col[i] = R->i[i];
    }
    cs_di_spfree(R);
    if (!s->ops.st_rowptr || !s->ops.st_col || !s->ops.st_M || !s->ops.st_K || !s->ops.st_D)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory building the structural operator");
    st_add(s, s->dae.M, 1.0, s->ops.st_M);
    st_add(s, s->dae.K, 1.0, s->ops.st_K);
    td_sim_structural_speed(s);
    return TD_OK;
}

/* ---- the mass matrix's factorisation (LU, CXSparse) ---------------------------------------- */

td_status td_sim_mass_factor(td_sim *s, td_error *err)
{
    s->ops.Ms = cs_di_sqr(1, s->dae.M, 0);
    if (!s->ops.Ms)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory factorising the mass matrix");
    s->ops.Mn = cs_di_lu(s->dae.M, s->ops.Ms, 1.0);
    if (!s->ops.Mn)
        return td_error_set(err, TD_ERR_NUMERIC, "the mass matrix is singular");
    return TD_OK;
}

void td_sim_mass_solve(const td_sim *s, double *b)
{
    double *x = s->ops.mass_x;
    cs_di_ipvec(s->ops.Mn->pinv, b, x, s->dae.n);
    cs_di_lsolve(s->ops.Mn->L, x);
    cs_di_usolve(s->ops.Mn->U, x);
    cs_di_ipvec(s->ops.Ms->q, x, b, s->dae.n);
}
