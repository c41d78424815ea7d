/*
 * The first-order form of the contact-free system (touchdown/modal.h):
 *
 *   q' = v
 *   M v' = -K_eff q - C_eff v + B_w w
 *   w'   = (command(xs, vs, e) - w) / tau       (one per AMB axis with tau > 0)
 *   e'   = xs                                   (one per AMB axis with kint > 0: PID)
 *   x'   = A x + B e,  e = -xs                   (the states of each continuous linear controller)
 *
 * An axis a linear controller drives takes ki i in place of the command, i = C x + D e + D1 e'
 * (touchdown/controller.h), lagged or not as the AMB says.
 * K_eff = K - ks at (actuator, actuator) for every AMB axis; C_eff = C + Omega G. An axis with
 * tau == 0 has no filter state: its force ks x + command(xs, vs, e) is exactly a spring-damper,
 * -ki kp at (actuator, sensor) moved to K_eff and -ki kd to C_eff, plus -ki kint on e. The
 * integrator runs unclamped here: the analysis is of the linear, unsaturated loop. An AMB that is off
 * (td_system_set_amb_off) exerts nothing and its integrator holds, as in the simulation. The AMB coefficients come from
 * the axis law in model/amb.c (evaluated at unit inputs, which is exact for a linear law), so the
 * AMB physics lives in one place.
 */
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <math.h>
#include <stdlib.h>

void td_modal_gsl_quiet(void)
{
    gsl_set_error_handler_off();
}

int td_modal_state_count(const td_system *sys)
{
    return sys ? 2 * sys->ndof + sys->n_controller_states : 0;
}

void td_entry_add(td_entry_sink *k, int i, int j, double v)
{
    if (k->dense)
        *gsl_matrix_ptr(k->dense, (size_t)(k->row0 + i), (size_t)j) += v;
    else if (v != 0.0 && !cs_di_entry(k->triplet, k->row0 + i, j, v))
        k->ok = 0;
}

/* sink(i, col0 + j) += scale * S(i, j) */
void td_entry_add_matrix(td_entry_sink *k, const cs_di *S, int col0, double scale)
{
    int j, p;
    for (j = 0; j < S->n; j++)
        for (p = S->p[j]; p < S->p[j + 1]; p++)
            td_entry_add(k, S->i[p], col0 + j, scale * S->x[p]);
}

/* Linear coefficients of one AMB axis, from the law functions of system_internal.h. */
typedef struct amb_coeffs {
    double dfdx;                           /* d(force)/dx at the actuator: ks (unsaturated, enabled) */
    double dfdfc;                          /* d(force)/d(Fc): 1 */
    double cmd_x;                          /* d(command)/d(xs) = -ki kp */
    double cmd_v;                          /* d(command)/d(vs) = -ki kd */
    double cmd_e;                          /* d(command)/d(e) = -ki kint */
    double rate_x, rate_v, rate_e, rate_w; /* d(dFc/dt)/d(xs, vs, e, Fc), tau > 0 only */
    double target_i;                       /* d(target force)/d(current) = ki, a driven axis */
    double rate_i;                         /* d(dFc/dt)/d(current) = ki / tau, tau > 0 only */
} amb_coeffs;

static amb_coeffs amb_axis_coeffs(const td_amb_axis *a)
{
    amb_coeffs c = {0};
    (void)td_amb_axis_force(a, !a->off, 0.0, 0.0, &c.dfdx, &c.dfdfc); /* an AMB off: 0, 0 */
    c.cmd_x = td_amb_axis_command(a, 1.0, 0.0, 0.0);
    c.cmd_v = td_amb_axis_command(a, 0.0, 1.0, 0.0);
    c.cmd_e = td_amb_axis_command(a, 0.0, 0.0, 1.0);
    if (a->state >= 0) {
        c.rate_x = td_amb_axis_filter_rate(a, 1.0, 0.0, 0.0, 0.0);
        c.rate_v = td_amb_axis_filter_rate(a, 0.0, 1.0, 0.0, 0.0);
        c.rate_e = td_amb_axis_filter_rate(a, 0.0, 0.0, 1.0, 0.0);
        c.rate_w = td_amb_axis_filter_rate(a, 0.0, 0.0, 0.0, 1.0);
        c.rate_i = td_amb_axis_lag_rate(a, td_amb_axis_current_command(a, 1.0), 0.0);
    }
    c.target_i = td_amb_axis_current_command(a, 1.0);
    return c;
}

/* Row `row` += scale * (the current command of axis a's output, a continuous law): C on the law's
 * states, D on its inputs' sensor displacements and D1 on their velocities, both times de/dxs = -1. */
static void add_current(const td_system *sys, const td_amb_axis *a, int row, double scale, td_entry_sink *R)
{
    const td_lti_law *L = &sys->laws[a->law];
    int nd = sys->ndof, o = a->law_output, j, m;
    if (L->state < 0)
        return; /* a sampled law's held current is an input of the plant (sampled.c) */
    for (j = 0; j < L->n; j++)
        td_entry_add(R, row, 2 * nd + L->state + j, scale * L->C[o + (size_t)j * L->nout]);
    for (m = 0; m < L->nin; m++) {
        int sen = sys->amb_axes[L->in_axis[m]].sensor_dof;
        td_entry_add(R, row, sen, -scale * L->D[o + (size_t)m * L->nout]);
        if (L->D1)
            td_entry_add(R, row, nd + sen, -scale * L->D1[o + (size_t)m * L->nout]);
    }
}

/* The continuous laws' rows x' = A x + B e, e = -xs. */
static void law_rows(const td_system *sys, td_entry_sink *A)
{
    int nd = sys->ndof, l, r, j, m;
    for (l = 0; l < sys->n_laws; l++) {
        const td_lti_law *L = &sys->laws[l];
        for (r = 0; L->state >= 0 && r < L->n; r++) {
            int row = 2 * nd + L->state + r;
            for (j = 0; j < L->n; j++)
                td_entry_add(A, row, 2 * nd + L->state + j, L->A[r + (size_t)j * L->n]);
            for (m = 0; m < L->nin; m++)
                td_entry_add(A, row, sys->amb_axes[L->in_axis[m]].sensor_dof, -L->B[r + (size_t)m * L->n]);
        }
    }
}

td_status td_system_refuse_plugins(const td_system *sys, td_error *err)
{
    int l;
    for (l = 0; sys && l < sys->n_laws; l++)
        if (sys->laws[l].plugin && !sys->laws[l].standby)
            return td_error_set(err, TD_ERR_INVALID,
                                "modal: controller %d (\"%s\") is a plug-in, the user's own code with no linear "
                                "law: the analyses of the closed loop need linear controllers",
                                l, sys->laws[l].plugin->name);
    return TD_OK;
}

td_status td_state_space_supported(const td_system *sys, td_error *err)
{
    int l;
    if (td_system_refuse_plugins(sys, err) != TD_OK)
        return TD_ERR_INVALID;
    for (l = 0; sys && l < sys->n_laws; l++)
        if (sys->laws[l].state < 0)
            return td_error_set(err, TD_ERR_INVALID,
                                "modal: controller %d is sampled (%g Hz): the closed-loop analysis here is of "
                                "continuous controllers",
                                l, sys->laws[l].sample_rate);
    return TD_OK;
}

void td_state_space_rhs_blocks(const td_system *sys, double omega, td_entry_sink *R)
{
    int nd = sys->ndof, k;
    td_entry_add_matrix(R, sys->K, 0, -1.0);
    td_entry_add_matrix(R, sys->C, nd, -1.0);
    td_entry_add_matrix(R, sys->G, nd, -omega);
    for (k = 0; k < sys->n_amb_axes; k++) {
        const td_amb_axis *a = &sys->amb_axes[k];
        amb_coeffs c = amb_axis_coeffs(a);
        int act = a->actuator_dof, sen = a->sensor_dof;
        /* F = ks x + Fc on the right-hand side: +ks x */
        td_entry_add(R, act, act, c.dfdx);
        if (a->state < 0) {
            /* lag-free: Fc = command(xs, vs, e) exactly */
            td_entry_add(R, act, sen, c.dfdfc * c.cmd_x);
            td_entry_add(R, act, nd + sen, c.dfdfc * c.cmd_v);
            if (a->integral >= 0)
                td_entry_add(R, act, 2 * nd + a->integral, c.dfdfc * c.cmd_e);
            if (a->law >= 0) /* Fc = ki i, i = C x + D e + D1 e' */
                add_current(sys, a, act, c.dfdfc * c.target_i, R);
        } else {
            td_entry_add(R, act, 2 * nd + a->state, c.dfdfc);
        }
    }
}

void td_state_space_filter_rows(const td_system *sys, td_entry_sink *A)
{
    int nd = sys->ndof, k;
    for (k = 0; k < sys->n_amb_axes; k++) {
        const td_amb_axis *a = &sys->amb_axes[k];
        amb_coeffs c = amb_axis_coeffs(a);
        if (a->state >= 0) {
            int row = 2 * nd + a->state;
            td_entry_add(A, row, a->sensor_dof, c.rate_x);
            td_entry_add(A, row, nd + a->sensor_dof, c.rate_v);
            td_entry_add(A, row, row, c.rate_w);
            if (a->integral >= 0)
                td_entry_add(A, row, 2 * nd + a->integral, c.rate_e);
            if (a->law >= 0)
                add_current(sys, a, row, c.rate_i, A);
        }
        if (a->integral >= 0 && !a->off) /* e' = xs; an AMB off holds it (e' = 0) */
            td_entry_add(A, 2 * nd + a->integral, a->sensor_dof, 1.0);
    }
    law_rows(sys, A); /* a controller runs on its sensors while its AMB is off */
}

void td_state_space_free(td_state_space *ss)
{
    if (!ss)
        return;
    gsl_matrix_free(ss->A);
    gsl_matrix_free(ss->L);
    ss->A = ss->L = NULL;
}

/* L = Cholesky factor of the dense M (modal_internal.h). */
td_status td_state_space_factor_mass(const td_system *sys, gsl_matrix *L, td_error *err)
{
    td_entry_sink k = {NULL, NULL, 0, 1};
    k.dense = L;
    gsl_matrix_set_zero(L);
    td_entry_add_matrix(&k, sys->M, 0, 1.0);
    if (gsl_linalg_cholesky_decomp1(L) != GSL_SUCCESS)
        return td_error_set(err, TD_ERR_NUMERIC,
                            "modal: the mass matrix is not positive definite (a DOF without mass or inertia?)");
    return TD_OK;
}

td_status td_state_space_build(const td_system *sys, double omega, td_state_space *ss, td_error *err)
{
    if (!sys || !ss)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL system");
    if (td_state_space_supported(sys, err) != TD_OK)
        return TD_ERR_INVALID;
    return td_state_space_build_plant(sys, omega, ss, err);
}

td_status td_state_space_build_plant(const td_system *sys, double omega, td_state_space *ss, td_error *err)
{
    gsl_matrix *R = NULL;
    size_t nd, n;
    td_status st;
    if (!sys || !ss)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL system");
    if (!TD_SPEED_VALID(omega))
        return td_error_set(err, TD_ERR_INVALID, "modal: speed must be finite and >= 0 rad/s (got %g)", omega);
    td_modal_gsl_quiet();
    ss->ndof = sys->ndof;
    ss->nfilter = sys->n_controller_states;
    ss->n = td_modal_state_count(sys);
    ss->omega = omega;
    nd = (size_t)ss->ndof;
    n = (size_t)ss->n;
    ss->A = gsl_matrix_calloc(n, n);
    ss->L = gsl_matrix_alloc(nd, nd);
    R = gsl_matrix_alloc(nd, n);
    if (!ss->A || !ss->L || !R) {
        gsl_matrix_free(R);
        td_state_space_free(ss);
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for a %d-state system", ss->n);
    }
    st = td_state_space_factor_mass(sys, ss->L, err);
    if (st == TD_OK) {
        size_t i;
        td_entry_sink rk = {NULL, NULL, 0, 1}, ak = {NULL, NULL, 0, 1};
        rk.dense = R;
        ak.dense = ss->A;
        /* v rows: M^-1 [-K_eff | -C_eff | B_w] */
        gsl_matrix_set_zero(R);
        td_state_space_rhs_blocks(sys, omega, &rk);
        if (gsl_linalg_cholesky_svx_mat(ss->L, R) != GSL_SUCCESS)
            st = td_error_set(err, TD_ERR_NUMERIC, "modal: solving with the mass matrix failed");
        else {
            gsl_matrix_view vrows = gsl_matrix_submatrix(ss->A, nd, 0, nd, n);
            gsl_matrix_memcpy(&vrows.matrix, R);
            for (i = 0; i < nd; i++) /* q' = v */
                gsl_matrix_set(ss->A, i, nd + i, 1.0);
            td_state_space_filter_rows(sys, &ak);
        }
    }
    gsl_matrix_free(R);
    if (st != TD_OK)
        td_state_space_free(ss);
    return st;
}

td_status td_state_space_load(const td_state_space *ss, const double *f, double *out, td_error *err)
{
    int i;
    gsl_vector_view x;
    for (i = 0; i < ss->n; i++)
        out[i] = 0.0;
    for (i = 0; i < ss->ndof; i++)
        out[ss->ndof + i] = f[i];
    x = gsl_vector_view_array(out + ss->ndof, (size_t)ss->ndof);
    if (gsl_linalg_cholesky_svx(ss->L, &x.vector) != GSL_SUCCESS)
        return td_error_set(err, TD_ERR_NUMERIC, "modal: solving with the mass matrix failed");
    return TD_OK;
}

static td_status physical_unbalance_forces(const td_system *sys, double omega, const td_unbalance *u, int n_u,
                                           double *fre, double *fim, td_error *err)
{
    int i;
    if (n_u < 0 || (n_u > 0 && !u))
        return td_error_set(err, TD_ERR_INVALID, "modal: bad unbalance list");
    for (i = 0; i < n_u; i++) {
        double a = u[i].magnitude * omega * omega, c = cos(u[i].phase), s = sin(u[i].phase);
        int x, y;
        if (u[i].node < 0 || u[i].node >= sys->nnodes)
            return td_error_set(err, TD_ERR_INVALID, "modal: unbalance %d: node %d out of range (0..%d)", i, u[i].node,
                                sys->nnodes - 1);
        if (!isfinite(a) || !isfinite(u[i].phase))
            return td_error_set(err, TD_ERR_INVALID, "modal: unbalance %d: magnitude and phase must be finite", i);
        x = TD_DOF(u[i].node, TD_DOF_X);
        y = TD_DOF(u[i].node, TD_DOF_Y);
        /* F_x = Re(U w^2 e^{ip} e^{iwt}) = U w^2 cos(wt + p); F_y = Re(-i U w^2 e^{ip} e^{iwt}) = U w^2 sin(wt + p) */
        fre[x] += a * c;
        fim[x] += a * s;
        fre[y] += a * s;
        fim[y] -= a * c;
    }
    return TD_OK;
}

/* The forces on the physical DOFs (nphys each), then projected on q (T^T f, reduce.c). */
td_status td_unbalance_forces(const td_system *sys, double omega, const td_unbalance *u, int n_u, double *fre,
                              double *fim, td_error *err)
{
    double *phys = calloc(2u * (size_t)sys->nphys, sizeof *phys);
    td_status st;
    if (!phys)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the unbalance forces");
    st = physical_unbalance_forces(sys, omega, u, n_u, phys, phys + sys->nphys, err);
    td_system_project_load(sys, phys, fre);
    td_system_project_load(sys, phys + sys->nphys, fim);
    if (sys->nbody > 0) { /* housing body: the unbalance, from outside the machine, shakes it too */
        td_system_body_share(sys, fre);
        td_system_body_share(sys, fim);
    }
    free(phys);
    return st;
}

td_status td_modal_state_matrix(const td_system *sys, double omega, double *A, td_error *err)
{
    td_state_space ss;
    td_status st;
    int i, j;
    if (!A)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL output matrix");
    st = td_state_space_build(sys, omega, &ss, err);
    if (st != TD_OK)
        return st;
    for (j = 0; j < ss.n; j++)
        for (i = 0; i < ss.n; i++)
            A[i + (size_t)j * (size_t)ss.n] = gsl_matrix_get(ss.A, (size_t)i, (size_t)j);
    td_state_space_free(&ss);
    return TD_OK;
}
