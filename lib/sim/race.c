/*
 * The retainers' races as bodies (model.h td_race): their DOFs, appended after the rotor's, and
 * their share of the structural matrices, gravity and start state.
 *
 * A race on a mount has two DOFs, the x and y of its centre, with its mass, the mount's stiffness
 * and damping to the housing; a race with inertia has one more, its angle (q) and speed Omega_b
 * (v), with the polar inertia J and the viscous drag as a damper. None of them couples to the rotor
 * except through the contact forces (sim_residual.c), so they are blocks on the diagonal:
 *
 *     M = diag(M_rotor, m_r, m_r, J, ...),  K = diag(K_rotor, k_m, k_m, 0, ...),
 *     C = diag(C_rotor, c_m, c_m, c_drag, ...),  G = diag(G_rotor, 0, ...).
 *
 * The rotor's spin DOF, when the speed varies (spin.c), is one more block on that diagonal (its
 * polar inertia in M, a free spin's viscous drag in C). Without either the rotor's matrices are used
 * as they are (the paper's cases).
 */
#include "model/rigid_motion.h"
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

void td_sim_races_layout(td_sim *s)
{
    int k, n = s->sys->ndof;
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_retainer *r = &s->contacts.ret[k];
        if (r->r.race.mount_stiffness > 0.0) {
            r->rx = n++;
            r->ry = n++;
        }
        if (r->r.race.inertia > 0.0)
            r->rs = n++;
    }
    s->dae.n = n;
    td_sim_spin_layout(s);
}

/* Diagonal values of the race DOFs for matrix `which` (M, K, C): 0 where none. */
static void race_diagonal(const td_sim *s, char which, double *d)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        const td_race *b = &r->r.race;
        if (r->rx >= 0) {
            double v = which == 'M'   ? b->mass
                       : which == 'K' ? b->mount_stiffness
                       : which == 'C' ? b->mount_damping
                                      : 0.0;
            d[r->rx] = d[r->ry] = v;
        }
        if (r->rs >= 0)
            d[r->rs] = which == 'M' ? b->inertia : which == 'C' ? b->drag_viscous : 0.0;
    }
    td_sim_spin_diagonal(s, which, d);
}

/* A, n_rotor x n_rotor, extended to s->dae.n x s->dae.n with the race diagonal of `which`. NULL: no memory. */
static cs_di *extend(const td_sim *s, const cs_di *A, char which, double *diag)
{
    int n0 = A->n, nz0 = A->p[n0], j, nz;
    cs_di *E;
    memset(diag, 0, sizeof(double) * (size_t)s->dae.n);
    race_diagonal(s, which, diag);
    E = cs_di_spalloc(s->dae.n, s->dae.n, nz0 + (s->dae.n - n0), 1, 0);
    if (!E)
        return NULL;
    memcpy(E->p, A->p, sizeof(int) * (size_t)(n0 + 1));
    memcpy(E->i, A->i, sizeof(int) * (size_t)nz0);
    memcpy(E->x, A->x, sizeof(double) * (size_t)nz0);
    nz = nz0;
    for (j = n0; j < s->dae.n; j++) {
        if (diag[j] != 0.0) {
            E->i[nz] = j;
            E->x[nz++] = diag[j];
        }
        E->p[j + 1] = nz;
    }
    return E;
}

/* housing body */
/* The races' mass coupled to a housing body (assemble_body.c): a race's absolute displacement is its
 * own (relative to the housing) plus the body's rigid field at its axial position, r_x h and r_y h,
 * so M gains m (r_x, r_y) between the race's x, y and the body's DOFs and m (r_x r_x^T + r_y r_y^T)
 * on the body's. *M is replaced; nothing without a body or a mounted race. */
static td_status couple_races(const td_sim *s, cs_di **M, td_error *err)
{
    int h = s->sys->ndof - s->sys->nbody, nb = s->sys->nbody, k, i, j, ok = 1, c, p;
    cs_di *T, *C;
    if (nb == 0)
        return TD_OK;
    T = cs_di_spalloc(s->dae.n, s->dae.n, (*M)->p[(*M)->n] + 4 * nb * s->dae.nr + nb * nb * s->dae.nr + 1, 1, 1);
    for (c = 0; T && ok && c < (*M)->n; c++)
        for (p = (*M)->p[c]; ok && p < (*M)->p[c + 1]; p++)
            ok = cs_di_entry(T, (*M)->i[p], c, (*M)->x[p]);
    for (k = 0; T && ok && k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double rx[4], ry[4], m = r->r.race.mass;
        if (r->rx < 0)
            continue;
        td_system_body_point_field(s->sys, r->r.node, rx, ry);
        for (j = 0; ok && j < nb; j++) {
            ok = cs_di_entry(T, r->rx, h + j, m * rx[j]) && cs_di_entry(T, h + j, r->rx, m * rx[j]) &&
                 cs_di_entry(T, r->ry, h + j, m * ry[j]) && cs_di_entry(T, h + j, r->ry, m * ry[j]);
            for (i = 0; ok && i < nb; i++)
                ok = cs_di_entry(T, h + i, h + j, m * (rx[i] * rx[j] + ry[i] * ry[j]));
        }
    }
    C = T && ok ? td_system_compress(T) : NULL;
    cs_di_spfree(T);
    if (!C)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory coupling the races to the housing body");
    cs_di_spfree(*M);
    *M = C;
    return TD_OK;
}

td_status td_sim_races_matrices(td_sim *s, td_error *err)
{
    const td_system *sys = s->sys;
    double *diag;
    if (s->dae.n == sys->ndof) { /* no races: the rotor's own matrices */
        s->dae.M = sys->M, s->dae.K = sys->K, s->dae.C = sys->C, s->dae.G = sys->G;
        return TD_OK;
    }
    diag = malloc(sizeof(double) * (size_t)s->dae.n);
    s->dae.own_matrices = 1;
    if (diag) {
        s->dae.M = extend(s, sys->M, 'M', diag);
        s->dae.K = extend(s, sys->K, 'K', diag);
        s->dae.C = extend(s, sys->C, 'C', diag);
        s->dae.G = extend(s, sys->G, 'G', diag);
    }
    free(diag);
    if (!s->dae.M || !s->dae.K || !s->dae.C || !s->dae.G)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory assembling the retainer races");
    return couple_races(s, &s->dae.M, err);
}

void td_sim_races_free(td_sim *s)
{
    if (s->dae.own_matrices) {
        cs_di_spfree(s->dae.M);
        cs_di_spfree(s->dae.K);
        cs_di_spfree(s->dae.C);
        cs_di_spfree(s->dae.G);
    }
    s->dae.M = s->dae.K = s->dae.C = s->dae.G = NULL;
    s->dae.own_matrices = 0;
}

void td_sim_races_gravity(const td_sim *s, double *f, double sign)
{
    double gx, gy;
    int k;
    td_model_gravity(s->model, &gx, &gy);
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        if (r->rx < 0)
            continue;
        f[r->rx] += sign * r->r.race.mass * gx;
        f[r->ry] += sign * r->r.race.mass * gy;
        /* housing body: its share of the race's weight (nothing without a body) */
        td_system_body_point_force(s->sys, r->r.node, sign * r->r.race.mass * gx, sign * r->r.race.mass * gy, f);
    }
}

void td_sim_races_housing(const td_sim *s, const td_housing_motion *hm, double *f, double sign)
{
    double zref = 0.0;
    int k, have_ref = 0;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double m = r->r.race.mass, base[TD_DOFS_PER_NODE], a[TD_DOFS_PER_NODE];
        if (r->rx < 0)
            continue;
        if (!have_ref)
            zref = td_model_housing_reference(s->model), have_ref = 1;
        /* the housing's acceleration at the race's axial position: a + alpha x (z - z_ref) e_z */
        base[TD_DOF_X] = hm->acceleration[0], base[TD_DOF_Y] = hm->acceleration[1];
        base[TD_DOF_THETA] = hm->rate_change[0], base[TD_DOF_PHI] = hm->rate_change[1];
        td_rigid_motion_at(base, td_model_node_position(s->model, r->r.node) - zref, a);
        f[r->rx] -= sign * m * a[TD_DOF_X];
        f[r->ry] -= sign * m * a[TD_DOF_Y];
        /* housing body: its share of the race's inertial load (nothing without a body) */
        td_system_body_point_force(s->sys, r->r.node, -sign * m * a[TD_DOF_X], -sign * m * a[TD_DOF_Y], f);
    }
}

/* housing body: the races' weight carried by its mounts, added to the body's static position of
 * an orbit start (the system's, without the races). Nothing without a body or from rest. */
static void races_body_sag(const td_sim *s, double *y)
{
    double load[4] = {0.0, 0.0, 0.0, 0.0}, dh[4], gx, gy;
    int h = s->sys->ndof - s->sys->nbody, j, k;
    if (s->sys->nbody == 0 || s->start.used != TD_START_ORBIT)
        return;
    td_model_gravity(s->model, &gx, &gy);
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double rx[4], ry[4];
        if (r->rx < 0)
            continue;
        td_system_body_point_field(s->sys, r->r.node, rx, ry);
        for (j = 0; j < s->sys->nbody; j++)
            load[j] += r->r.race.mass * (rx[j] * gx + ry[j] * gy);
    }
    td_system_body_static(s->sys, load, dh);
    for (j = 0; j < s->sys->nbody; j++)
        y[s->dae.oq + h + j] += dh[j];
}

void td_sim_races_start(const td_sim *s, double *y)
{
    double gx, gy;
    int k;
    td_model_gravity(s->model, &gx, &gy);
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        const td_race *b = &r->r.race;
        if (r->rx >= 0) { /* resting on its mount under its weight */
            y[s->dae.oq + r->rx] = b->mass * gx / b->mount_stiffness;
            y[s->dae.oq + r->ry] = b->mass * gy / b->mount_stiffness;
        }
        if (r->rs >= 0)
            y[s->dae.ov + r->rs] = r->r.bore_speed;
    }
    races_body_sag(s, y);
    td_sim_spin_start(s, y);
}
