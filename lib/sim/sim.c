/*
 * td_sim: creation, the IDA set-up, the step loop and the public accessors (touchdown/sim.h).
 * The DAE itself is in sim_residual.c, mode switching in sim_modes.c, the per-retainer queries and
 * mode bookkeeping in retainer.c.
 */
#include "model/gap.h"
#include "sim/sim_internal.h"
#include "touchdown/dofs.h"
#include "touchdown/modal.h"
#include "util/clock.h"
#include "util/error_internal.h"
#include "util/limits.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ida/ida_ls.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>

/* ---- IDA callbacks ----------------------------------------------------------------------- */

static int res_cb(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void *data)
{
    td_sim_residual((const td_sim *)data, t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), N_VGetArrayPointer(r));
    return 0;
}

static int jac_cb(sunrealtype t, sunrealtype cj, N_Vector y, N_Vector yp, N_Vector r, SUNMatrix J, void *data,
                  N_Vector t1, N_Vector t2, N_Vector t3)
{
    td_sim *s = (td_sim *)data;
    int j, p;
    (void)yp, (void)r, (void)t1, (void)t2, (void)t3;
    td_sim_jacobian(s, t, cj, N_VGetArrayPointer(y));
    if (SUNMatGetID(J) == SUNMATRIX_SPARSE) {
        /* IDA's SUNMatZero cleared the index arrays too: write the whole pattern every time */
        sunindextype *cp = SUNSparseMatrix_IndexPointers(J), *ri = SUNSparseMatrix_IndexValues(J);
        sunrealtype *d = SUNSparseMatrix_Data(J);
        for (j = 0; j <= s->neq; j++)
            cp[j] = s->colptr[j];
        for (p = 0; p < s->nnz; p++) {
            ri[p] = s->rowind[p];
            d[p] = s->jdata[p];
        }
    } else {
        SUNMatZero(J);
        for (j = 0; j < s->neq; j++) {
            sunrealtype *col = SUNDenseMatrix_Column(J, j);
            for (p = s->colptr[j]; p < s->colptr[j + 1]; p++)
                col[s->rowind[p]] = s->jdata[p];
        }
    }
    return 0;
}

static int root_cb(sunrealtype t, N_Vector y, N_Vector yp, sunrealtype *g, void *data)
{
    (void)yp;
    td_sim_roots((const td_sim *)data, t, N_VGetArrayPointer(y), g);
    return 0;
}

/*
 * The contact multipliers lambda and mu are index-2 unknowns: a step's Newton iteration can fix
 * them only to cj times the rounding of the constraint rows. mu moves q by mu / cj, so the rounding
 * of g (eps c, the clearance) leaves mu uncertain by ~ cj eps c; lambda moves the node's velocity
 * by lambda / (m cj), so the rounding of J v (eps c freq_scale) leaves it uncertain by
 * ~ cj eps c stiff_scale / freq_scale (m = stiff_scale / freq_scale^2). Below that floor a Newton
 * correction is noise: weighed against a tighter tolerance, a short step never converges, IDA
 * shortens it, cj grows and the floor with it (at rtol 1e-12, atol 1e-15 case B's steps fell to
 * 1e-18 s and stayed there). Each multiplier's correction is therefore weighed against its
 * tolerance or MULTIPLIER_FLOOR times that floor, whichever is larger; at the default tolerances
 * the floor is orders of magnitude below the tolerance and the test is IDA's own.
 */
#define MULTIPLIER_FLOOR 64.0

static N_Vector floored_multipliers(td_sim *s, N_Vector del, N_Vector ewt, double cj)
{
    const double *w = N_VGetArrayPointer(ewt);
    double *d = NULL;
    int k;
    for (k = 0; k < s->nr; k++) {
        double mu_floor = MULTIPLIER_FLOOR * DBL_EPSILON * s->ret[k].r.clearance * cj;
        double lambda_floor = mu_floor * s->stiff_scale / s->freq_scale;
        double fl = 1.0 / (lambda_floor * w[s->ol + k]), fu = 1.0 / (mu_floor * w[s->ou + k]);
        if (fl >= 1.0 && fu >= 1.0)
            continue;
        if (!d) {
            N_VScale(1.0, del, s->newton_del);
            d = N_VGetArrayPointer(s->newton_del);
        }
        d[s->ol + k] *= fmin(fl, 1.0);
        d[s->ou + k] *= fmin(fu, 1.0);
    }
    return d ? s->newton_del : del;
}

/*
 * Newton convergence test: IDA's own test (a weighted RMS norm of the last correction over all
 * unknowns, with the convergence rate of earlier steps; the multipliers floored as above), and then
 * every active contact constraint |g| <= constraint_tol at the iterate. Why the second test: the
 * RMS over ~100 unknowns lets a single component sit at a few times its weight, and IDA accepts a
 * single modified-Newton iteration when earlier steps converged fast. On case A that let the
 * constraint residual and the GGL multiplier eta grow in a two-step oscillation (eta ~ g/h
 * alternating in sign, |r - c| up to 5e-9 m) until a convergence failure reset it. Demanding the
 * constraint itself at acceptance costs an extra iteration now and then and keeps |r - c| below the
 * tolerance at every step.
 */
static int conv_test_cb(SUNNonlinearSolver nls, N_Vector ycor, N_Vector del, sunrealtype tol, N_Vector ewt, void *data)
{
    td_sim *s = (td_sim *)data;
    sunrealtype tcur, cj;
    N_Vector ypred, yppred, yyn, ypn, res;
    void *user;
    const double *cor, *pred;
    int k, flag;
    if (IDAGetNonlinearSystemData(s->ida, &tcur, &ypred, &yppred, &yyn, &ypn, &res, &cj, &user) != IDA_SUCCESS)
        return s->ida_ctest(nls, ycor, del, tol, ewt, s->ida_ctest_data);
    flag = s->ida_ctest(nls, ycor, floored_multipliers(s, del, ewt, cj), tol, ewt, s->ida_ctest_data);
    if (flag != SUN_NLS_SUCCESS)
        return flag;
    cor = N_VGetArrayPointer(ycor);
    pred = N_VGetArrayPointer(ypred);
    for (k = 0; k < s->nr; k++) {
        const td_sim_retainer *r = &s->ret[k];
        double x, y;
        if (r->mode != TD_RMODE_CONTACT)
            continue;
        x = pred[s->oq + r->dx] + cor[s->oq + r->dx];
        y = pred[s->oq + r->dy] + cor[s->oq + r->dy];
        if (r->rx >= 0) {
            x -= pred[s->oq + r->rx] + cor[s->oq + r->rx];
            y -= pred[s->oq + r->ry] + cor[s->oq + r->ry];
        }
        if (fabs(td_contact_constraint(x, y, r->r.clearance)) > s->constraint_tol)
            return SUN_NLS_CONTINUE;
    }
    return flag;
}

/* IDA's messages go into the sim's buffers: errors into errmsg, warnings into warnmsg. */
static void message_sink(int code, const char *function, const char *msg, void *data)
{
    td_sim *s = (td_sim *)data;
    if (code < 0)
        snprintf(s->errmsg, sizeof s->errmsg, "IDA %s: %s", function ? function : "", msg ? msg : "");
    else
        snprintf(s->warnmsg, sizeof s->warnmsg, "IDA %s: %s", function ? function : "", msg ? msg : "");
}

/* ---- creation ---------------------------------------------------------------------------- */

static td_status check_options(const td_sim_options *o, td_error *err)
{
    const td_solver_options *so = &o->solver;
    const td_contact_options *co = &o->contact;
    if (!(so->rtol > 0.0 && so->rtol < 1.0) || !(so->atol > 0.0) || !isfinite(so->atol))
        return td_error_set(err, TD_ERR_INVALID, "solver tolerances must be positive (rtol < 1)");
    if (!(so->max_step >= 0.0) || !(so->initial_step >= 0.0) || !isfinite(so->max_step) || !isfinite(so->initial_step))
        return td_error_set(err, TD_ERR_INVALID, "solver max_step and initial_step must be >= 0");
    if (so->max_order < 1 || so->max_order > 5)
        return td_error_set(err, TD_ERR_INVALID, "solver max_order must be 1..5, got %d", so->max_order);
    if (so->linear_solver != TD_LINSOL_KLU && so->linear_solver != TD_LINSOL_DENSE)
        return td_error_set(err, TD_ERR_INVALID, "unknown linear solver %d", (int)so->linear_solver);
    if (co->model != TD_CONTACT_CONSTRAINT && co->model != TD_CONTACT_PENALTY)
        return td_error_set(err, TD_ERR_INVALID, "unknown contact model %d", (int)co->model);
    if (co->model == TD_CONTACT_PENALTY) {
        if (!(co->stiffness > 0.0) || !isfinite(co->stiffness))
            return td_error_set(err, TD_ERR_INVALID, "penalty stiffness must be positive");
        if (!(co->exponent >= 1.0) || !isfinite(co->exponent))
            return td_error_set(err, TD_ERR_INVALID, "penalty exponent must be >= 1");
        if (co->damping != TD_DAMPING_NONE && co->damping != TD_DAMPING_HUNT_CROSSLEY &&
            co->damping != TD_DAMPING_KELVIN_VOIGT)
            return td_error_set(err, TD_ERR_INVALID, "unknown contact damping law %d", (int)co->damping);
        if (!(co->damping_coefficient >= 0.0) || !isfinite(co->damping_coefficient))
            return td_error_set(err, TD_ERR_INVALID, "contact damping coefficient must be >= 0");
    }
    if (o->start != TD_START_ORBIT && o->start != TD_START_REST && o->start != TD_START_AUTO)
        return td_error_set(err, TD_ERR_INVALID, "unknown start state %d", (int)o->start);
    if (!isfinite(o->t0))
        return td_error_set(err, TD_ERR_INVALID, "t0 must be finite");
    return TD_OK;
}

/* The work space of sim_internal.h; 0 if out of memory. */
static int alloc_work(td_sim *s, size_t nr)
{
    size_t n = (size_t)s->n, nc = nr + (size_t)s->ns; /* KKT multipliers: lambda and F_t */
    s->mass_x = calloc(n, sizeof(double));
    s->minv_f = calloc(n, sizeof(double));
    s->power_x = calloc(n, sizeof(double));
    s->power_kx = calloc(n, sizeof(double));
    s->power_mx = calloc(n, sizeof(double));
    s->schur = calloc(nc * nc, sizeof(double));
    s->schur_rhs = calloc(nc, sizeof(double));
    s->restitution = calloc(nr, sizeof(double));
    s->impulse = calloc(nr, sizeof(double));
    s->impact_work = calloc(nr * (nr + 1), sizeof(double));
    s->minv_cols = calloc(n * nc, sizeof(double));
    s->rows = calloc(nc, sizeof *s->rows);
    s->active = calloc(nc, sizeof(int));
    s->active_roll = calloc(nc, sizeof(int));
    s->onset = calloc(nr, sizeof(int));
    s->entered = calloc(nr, sizeof(int));
    s->roll_tried = calloc(nr, sizeof(int));
    s->touching = calloc(nr, sizeof(int));
    s->totals = calloc(nr, sizeof *s->totals);
    s->energy_f = calloc(n, sizeof(double));
    return s->mass_x && s->minv_f && s->power_x && s->power_kx && s->power_mx && s->schur && s->schur_rhs &&
           s->restitution && s->impulse && s->impact_work && s->minv_cols && s->rows && s->active && s->active_roll &&
           s->onset && s->roll_tried && s->totals && s->energy_f && s->entered && s->touching;
}

static td_status alloc_arrays(td_sim *s, td_error *err)
{
    int na = td_model_amb_count(s->model), ok, i;
    size_t nr = (size_t)(s->nr > 0 ? s->nr : 1);
    s->nu = td_model_unbalance_count(s->model);
    s->unb = calloc((size_t)(s->nu > 0 ? s->nu : 1), sizeof *s->unb);
    s->amb_mode = calloc((size_t)(na > 0 ? na : 1), sizeof *s->amb_mode);
    s->amb_control = calloc((size_t)(2 * na + 2), sizeof(double));
    s->amb_coef = calloc((size_t)(s->sys->n_amb_axes + 1), sizeof *s->amb_coef);
    s->q_cap = 4 * s->nr + td_model_change_count(s->model) + 4;
    s->queue = calloc((size_t)s->q_cap, sizeof *s->queue);
    ok = alloc_work(s, nr);
    s->n_sat_roots = 0;
    for (i = 0; i < s->sys->n_amb_axes; i++)
        if (s->sys->amb_axes[i].saturation)
            s->n_sat_roots = 2 * s->sys->n_amb_axes;
    s->nroots = TD_ROOTS_PER_RETAINER * s->nr + s->n_sat_roots;
    s->rootdir = calloc(TD_ROOTS_PER_RETAINER * nr + (size_t)s->n_sat_roots, sizeof(int));
    s->rootsfound = calloc(TD_ROOTS_PER_RETAINER * nr + (size_t)s->n_sat_roots, sizeof(int));
    s->ysave = calloc((size_t)s->neq, sizeof(double));
    s->ypsave = calloc((size_t)s->neq, sizeof(double));
    if (!ok || !s->unb || !s->amb_mode || !s->amb_control || !s->amb_coef || !s->queue || !s->rootdir ||
        !s->rootsfound || !s->ysave || !s->ypsave)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    return TD_OK;
}

/* Machine state at the start: the model's unbalances, AMBs on, retainers free. */
static void init_machine(td_sim *s)
{
    int i, na = td_model_amb_count(s->model);
    s->omega = td_model_speed_at(s->model, s->t, NULL, NULL);
    for (i = 0; i < s->nu; i++)
        td_model_get_unbalance(s->model, i, &s->unb[i]);
    for (i = 0; i < na; i++)
        td_sim_amb_mode_set(s, i, TD_AMB_PD);
    /* the AMB laws are linear (model/amb.c): unit probes give their coefficients exactly */
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        const td_amb_axis *a = &s->sys->amb_axes[i];
        td_sim_amb_coef *c = &s->amb_coef[i];
        c->cmd_x = td_amb_axis_command(a, 1.0, 0.0, 0.0) - td_amb_axis_command(a, 0.0, 0.0, 0.0);
        c->cmd_v = td_amb_axis_command(a, 0.0, 1.0, 0.0) - td_amb_axis_command(a, 0.0, 0.0, 0.0);
        c->cmd_e = td_amb_axis_command(a, 0.0, 0.0, 1.0) - td_amb_axis_command(a, 0.0, 0.0, 0.0);
        if (a->state >= 0) {
            double r0 = td_amb_axis_filter_rate(a, 0.0, 0.0, 0.0, 0.0);
            c->rate_x = td_amb_axis_filter_rate(a, 1.0, 0.0, 0.0, 0.0) - r0;
            c->rate_v = td_amb_axis_filter_rate(a, 0.0, 1.0, 0.0, 0.0) - r0;
            c->rate_e = td_amb_axis_filter_rate(a, 0.0, 0.0, 1.0, 0.0) - r0;
            c->rate_w = td_amb_axis_filter_rate(a, 0.0, 0.0, 0.0, 1.0) - r0;
        }
    }
}

/* Highest natural frequency sqrt(lambda_max(M^-1 K)) of the shaft, by 60 power iterations with
 * the Rayleigh quotient (an estimate from below, good to a few per cent: it only sets a tolerance). */
static double highest_frequency(const td_sim *s)
{
    double *x = s->power_x, *kx = s->power_kx, *mx = s->power_mx, lam = 0.0;
    int i, it;
    for (i = 0; i < s->n; i++)
        x[i] = (i % 2 ? 1.0 : -1.0) * (1.0 + 0.1 * (i % 7));
    for (it = 0; it < 60; it++) {
        double num = 0.0, den = 0.0, norm = 0.0;
        memset(kx, 0, sizeof(double) * (size_t)s->n);
        cs_di_gaxpy(s->K, x, kx);
        for (i = 0; i < s->n; i++)
            num += x[i] * kx[i];
        td_sim_mass_solve(s, kx); /* kx = M^-1 K x */
        memset(mx, 0, sizeof(double) * (size_t)s->n);
        cs_di_gaxpy(s->M, x, mx);
        for (i = 0; i < s->n; i++)
            den += x[i] * mx[i];
        if (den > 0.0)
            lam = num / den;
        for (i = 0; i < s->n; i++)
            norm = fmax(norm, fabs(kx[i]));
        if (!(norm > 0.0))
            break;
        for (i = 0; i < s->n; i++)
            x[i] = kx[i] / norm;
    }
    return lam > 0.0 ? sqrt(lam) : 0.0;
}

/*
 * Scales for the tolerances and the step bound. Forces scale with a stiffness: the AMB's
 * (|ks| + ki kp, the largest axis) or, without AMBs, the largest diagonal of K. Velocities scale
 * with a frequency: the larger of the speed and sqrt(stiffness / rotor mass), the rigid-body
 * bearing frequency.
 */
static void set_scales(td_sim *s)
{
    double k = 0.0, mass = td_model_total_mass(s->model), cmin = HUGE_VAL;
    int i;
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        const td_amb_axis *a = &s->sys->amb_axes[i];
        double ka = fabs(a->ks) + fabs(s->amb_coef[i].cmd_x);
        if (ka > k)
            k = ka;
    }
    if (k == 0.0) {
        const cs_di *K = s->sys->K;
        int j, p;
        for (j = 0; j < K->n; j++)
            for (p = K->p[j]; p < K->p[j + 1]; p++)
                if (K->i[p] == j && fabs(K->x[p]) > k)
                    k = fabs(K->x[p]);
    }
    if (!(k > 0.0))
        k = 1.0;
    s->stiff_scale = k;
    s->freq_scale = mass > 0.0 ? sqrt(k / mass) : 1.0;
    if (fabs(s->omega) > s->freq_scale)
        s->freq_scale = fabs(s->omega);
    if (s->freq_scale < 1.0)
        s->freq_scale = 1.0;
    for (i = 0; i < s->nr; i++)
        if (s->ret[i].r.clearance < cmin)
            cmin = s->ret[i].r.clearance;
    if (s->nr == 0)
        cmin = s->opt.solver.atol * 1e3;
    s->freq_max = highest_frequency(s);
    if (s->freq_max < s->freq_scale)
        s->freq_max = s->freq_scale;
    /* contact constraints hold to a tenth of the displacement tolerance at every step */
    s->constraint_tol = 0.1 * s->opt.solver.atol;
    /* hysteresis of the onset root after a release or a bounce: a gap or penetration of a tenth of
     * the displacement tolerance (the accuracy the constraint is held to) is not a new contact; far
     * above rounding (1e-19 m), so a rotor grazing the circle does not chatter */
    s->rearm_eps = s->opt.solver.atol;
    /* impacts slower than 1e-3 of the typical impact speed c * freq_scale become plastic */
    s->rebound_min = 1e-3 * cmin * s->freq_scale;
}

/* Step bound: 1/20 of the shortest period among the spin and the bearing frequency, so that a
 * gap cannot close and open again (two roots) inside one step unnoticed. */
static double default_max_step(const td_sim *s)
{
    double w = fabs(s->omega) > s->freq_scale ? fabs(s->omega) : s->freq_scale;
    return 2.0 * TD_PI / w / 20.0;
}

/*
 * Per-component absolute tolerances (IDASVtolerances):
 *   q       atol on displacements (m); atol / L_e on the slopes (rad), L_e the mean length of the
 *           shaft elements at the node: a slope error e moves the beam's deflection by ~ e L_e;
 *   v       atol * freq_max, the velocity of a displacement atol in the fastest mode of the shaft.
 *           The shaft has no structural damping, so every impact or force step sets its highest
 *           modes ringing (amplitude ~ impulse / (m omega), undamped for ever). A velocity
 *           tolerance at the slow scale (atol * the bearing frequency) would make IDA resolve that
 *           ringing in v long after it is below atol in q (measured on case A: 6x more steps); at
 *           freq_max the velocity test is no stricter than the displacement test for any mode,
 *           and the displacements, what the run reports, stay controlled to atol + rtol |q|;
 *   w       atol times the axis's control stiffness ki kp (the force error of a position error atol);
 *   lambda  atol * stiff_scale (N); eta (a velocity correction, m/s): atol * freq_scale. lambda and
 *           eta are algebraic and excluded from the error test, but the Newton convergence test
 *           still weighs them.
 */
/* The races' DOFs: the centre as a displacement, its velocity at the mount's own frequency
 * sqrt(k_m / m_r) (the race rings on its mount, not in the shaft's modes); the angle as the arc
 * atol / R_b at the race surface, and the speed as race.c td_sim_race_speed_atol says. */
static void race_tolerances(td_sim *s, double *at, double *id)
{
    double atol = s->opt.solver.atol;
    int k, i;
    for (k = 0; k < s->nr; k++) {
        const td_sim_retainer *r = &s->ret[k];
        int dofs[3] = {r->rx, r->ry, r->rs};
        for (i = 0; i < 3; i++) {
            double scale = i == 2 ? 1.0 / r->r.bore_radius : 1.0;
            if (dofs[i] < 0)
                continue;
            at[s->oq + dofs[i]] = atol * scale;
            at[s->ov + dofs[i]] = i == 2 ? td_sim_race_speed_atol(s, k)
                                         : atol * fmax(s->freq_scale, sqrt(r->r.race.mount_stiffness / r->r.race.mass));
            id[s->oq + dofs[i]] = id[s->ov + dofs[i]] = 1.0;
        }
    }
}

/* The spin DOF (spin.c): an angle error turns the unbalance force and the orbit with it, so it
 * gets the displacement tolerance over the tightest clearance (the scale of the orbits that
 * matter); the speed that over the bearing period. */
static void spin_tolerances(const td_sim *s, double *at, double *id)
{
    double c = 1e-3;
    int k;
    if (s->spin < 0)
        return;
    for (k = 0; k < s->nr; k++)
        c = fmin(c, s->ret[k].r.clearance);
    at[s->oq + s->spin] = s->opt.solver.atol / c;
    at[s->ov + s->spin] = s->opt.solver.atol / c * s->freq_scale;
    id[s->oq + s->spin] = id[s->ov + s->spin] = s->spin_free ? 1.0 : 0.0; /* a ramp's are algebraic */
}

static void set_tolerances(td_sim *s)
{
    double *at = N_VGetArrayPointer(s->atol), *id = N_VGetArrayPointer(s->id), atol = s->opt.solver.atol;
    int i;
    int ne = td_model_shaft_element_count(s->model);
    for (i = 0; i < s->sys->ndof; i++) {
        int off, node = td_system_coordinate_node(s->sys, i, &off);
        /* a fixed-interface modal coordinate of a reduced rotor moves the nodes by up to its mode's
         * largest amplitude per unit: its tolerance is the displacement tolerance over that */
        double scale = node < 0 ? 1.0 / td_system_coordinate_amplitude(s->sys, i) : 1.0;
        if (off == TD_DOF_THETA || off == TD_DOF_PHI) {
            /* a slope error e moves the interpolated deflection by about e L_e */
            double len = 0.0;
            int cnt = 0;
            td_shaft_element el;
            if (node > 0 && node - 1 < ne && td_model_get_shaft_element(s->model, node - 1, &el) == TD_OK)
                len += el.length, cnt++;
            if (node < ne && td_model_get_shaft_element(s->model, node, &el) == TD_OK)
                len += el.length, cnt++;
            if (cnt > 0 && len > 0.0)
                scale = cnt / len;
        }
        at[s->oq + i] = atol * scale;
        at[s->ov + i] = atol * scale * s->freq_max;
        id[s->oq + i] = id[s->ov + i] = 1.0;
    }
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        const td_amb_axis *a = &s->sys->amb_axes[i];
        double kc = fabs(s->amb_coef[i].cmd_x);
        if (a->state >= 0) {
            at[s->ow + a->state] = atol * (kc > 1.0 ? kc : 1.0);
            id[s->ow + a->state] = 1.0;
        }
        if (a->integral >= 0) {
            /* e (m s) moves the force by ki kint e as xs does by ki kp xs: an error of e worth the
             * displacement tolerance in force, or the displacement tolerance over a bearing period */
            double ke = fabs(s->amb_coef[i].cmd_e);
            at[s->ow + a->integral] = kc > 0.0 ? atol * kc / ke : atol / s->freq_scale;
            id[s->ow + a->integral] = 1.0;
        }
    }
    race_tolerances(s, at, id);
    spin_tolerances(s, at, id);
    for (i = 0; i < s->ns; i++) { /* F_t: a force, algebraic like lambda */
        at[s->of + i] = atol * s->stiff_scale;
        id[s->of + i] = 0.0;
    }
    for (i = 0; i < s->nr; i++) {
        at[s->ol + i] = atol * s->stiff_scale;
        at[s->ou + i] = atol * s->freq_scale;
        id[s->ol + i] = id[s->ou + i] = 0.0;
    }
}

static td_status factor_mass(td_sim *s, td_error *err)
{
    s->Ms = cs_di_sqr(1, s->M, 0);
    if (!s->Ms)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory factorising the mass matrix");
    s->Mn = cs_di_lu(s->M, s->Ms, 1.0);
    if (!s->Mn)
        return td_error_set(err, TD_ERR_NUMERIC, "the mass matrix is singular");
    return TD_OK;
}

/* A start orbit at most this far outside a clearance circle (relative) counts as touching it. */
#define TD_START_TOUCH_TOLERANCE 1e-6

/* Stability of the contact-free closed loop at the start speed, from the eigenvalues of its
 * first-order form (lib/modal, AMB filter states included). A model too big for a quick dense
 * eigen-solve, or one the solver fails on, stays unchecked: the check informs, it never blocks. */
static void check_stability(td_sim *s)
{
    int unstable = 0;
    s->start.stability = TD_STABILITY_UNCHECKED;
    s->start.max_real_part = NAN;
    if (td_modal_state_count(s->sys) > TD_SIM_STABILITY_MAX_STATES ||
        td_modal_stability(s->sys, s->omega, &s->start.max_real_part, &unstable, NULL) != TD_OK)
        return;
    s->start.stability = unstable ? TD_STABILITY_UNSTABLE : TD_STABILITY_STABLE;
}

/* First retainer whose start radius exceeds its clearance by more than the grazing tolerance
 * (its radius in *rad), -1 if none. */
static int first_outside(const td_sim *s, const double *y, double *rad)
{
    int k;
    for (k = 0; k < s->nr; k++) {
        const td_sim_retainer *r = &s->ret[k];
        double x, yy, vx, vy;
        td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
        *rad = hypot(x, yy);
        if (*rad - r->r.clearance > TD_START_TOUCH_TOLERANCE * r->r.clearance)
            return k;
    }
    return -1;
}

/* The rotor's state [q (ndof) | v (ndof) | w] at the start of y, as the modal analysis writes it,
 * moved to its places when races add DOFs after the rotor's (y = [q (n) | v (n) | w ...]). */
static void spread_rotor_state(const td_sim *s, double *y)
{
    int nd = s->sys->ndof, i;
    if (s->n == nd)
        return;
    for (i = s->nw - 1; i >= 0; i--) /* back to front: the blocks only move up */
        y[s->ow + i] = y[2 * nd + i];
    for (i = nd - 1; i >= 0; i--)
        y[s->ov + i] = y[nd + i];
    for (i = nd; i < s->ov; i++) /* the races' q, and the gap the rotor's v left */
        y[s->oq + i] = 0.0;
    for (i = s->ov + nd; i < s->ow; i++)
        y[i] = 0.0;
}

/* The time whose phase omega t the steady orbit takes: the start time, or with a ramp the time at
 * which a constant speed would have turned the spin angle the ramp has turned. */
static double orbit_phase_time(const td_sim *s)
{
    double angle;
    if (s->spin < 0 || !(s->omega > 0.0))
        return s->t;
    td_model_speed_at(s->model, s->t, NULL, &angle);
    return angle / s->omega;
}

/* The steady orbit into y. An unstable system has none that the motion would stay on: "orbit"
 * refuses it, "auto" stays at rest; "auto" also stays at rest when the orbit is not contact-free.
 * s->start.used says which start y holds. */
static td_status orbit_start(td_sim *s, double *y, td_error *err)
{
    int strict = s->opt.start == TD_START_ORBIT, k;
    double gx, gy, rad = 0.0;
    td_error merr;
    td_status st;
    if (s->start.stability == TD_STABILITY_UNSTABLE) {
        if (strict)
            return td_error_set(err, TD_ERR_INVALID,
                                "start = \"orbit\": the contact-free system is unstable at %.6g rad/s (rightmost "
                                "eigenvalue real part %.6g 1/s), so it has no steady orbit; use start = \"rest\"",
                                s->omega, s->start.max_real_part);
        snprintf(s->start.reason, sizeof s->start.reason,
                 "the contact-free system is unstable (rightmost eigenvalue real part %.6g 1/s)",
                 s->start.max_real_part);
        return TD_OK;
    }
    td_model_gravity(s->model, &gx, &gy);
    st = td_modal_start_state(s->sys, s->omega, s->unb, s->nu, gx != 0.0 || gy != 0.0, orbit_phase_time(s), y + s->oq,
                              &merr);
    if (st == TD_ERR_NUMERIC) { /* no steady state: nothing holds the rotor against gravity, a resonance */
        N_VConst(0.0, s->y);
        if (strict)
            return td_error_set(err, TD_ERR_INVALID,
                                "start = \"orbit\": %s, so there is no steady orbit; use "
                                "start = \"rest\"",
                                merr.message);
        snprintf(s->start.reason, sizeof s->start.reason, "no steady orbit: %.200s", merr.message);
        return TD_OK;
    }
    if (st != TD_OK)
        return td_error_set(err, st, "%s", merr.message);
    spread_rotor_state(s, y);
    s->start.used = TD_START_ORBIT;
    if (strict || (k = first_outside(s, y, &rad)) < 0)
        return TD_OK;
    snprintf(s->start.reason, sizeof s->start.reason,
             "the steady orbit lies outside the clearance of retainer %d (r = %.6g m > c = %.6g m)", k, rad,
             s->ret[k].r.clearance);
    N_VConst(0.0, s->y);
    s->start.used = TD_START_REST;
    return TD_OK;
}

static td_status start_state(td_sim *s, td_error *err)
{
    double *y = N_VGetArrayPointer(s->y);
    int *touching = s->touching;
    int k;
    td_status st;
    N_VConst(0.0, s->y);
    N_VConst(0.0, s->yp);
    s->start.requested = s->opt.start;
    s->start.used = TD_START_REST;
    s->start.reason[0] = '\0';
    if (s->opt.start != TD_START_REST && (st = orbit_start(s, y, err)) != TD_OK)
        return st;
    td_sim_races_start(s, y);
    for (k = 0; k < s->nr; k++) {
        td_sim_retainer *r = &s->ret[k];
        double x, yy, vx, vy, rad, c = r->r.clearance;
        td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
        rad = hypot(x, yy);
        touching[k] = 0;
        if (rad <= c)
            continue;
        if (td_sim_penalty_model(s, k)) {
            r->mode = TD_RMODE_PENETRATING;
            td_sim_init_slip(s, k, y);
        } else if (rad - c <= TD_START_TOUCH_TOLERANCE * c) {
            touching[k] = 1; /* grazing start: into contact as at an onset, if it presses */
        } else {
            return td_error_set(err, TD_ERR_INVALID,
                                "the start state is outside the clearance of retainer %d (r = %.9g m > c = %.9g m): "
                                "the free orbit is not contact-free; use start = \"auto\" or \"rest\", or reduce "
                                "the unbalance",
                                k, rad, c);
        }
    }
    st = td_sim_start_contacts(s, touching);
    return st == TD_OK ? TD_OK : td_error_set(err, st, "inconsistent start state: %s", s->errmsg);
}

/* IDA set-up; failures leave their message in s->errmsg. */
static td_status setup_ida(td_sim *s, td_error *err)
{
    if (td_sun_context_create(&s->ctx) != 0)
        return td_error_set(err, TD_ERR_NOMEM, "SUNContext_Create failed");
    s->y = N_VNew_Serial(s->neq, s->ctx);
    if (!s->y)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the state vectors");
    td_sim_nvector_optimize(s->y); /* before any clone: the clones copy its operations */
    s->yp = N_VClone(s->y);
    s->id = N_VClone(s->y);
    s->atol = N_VClone(s->y);
    s->newton_del = N_VClone(s->y);
    s->ida = IDACreate(s->ctx);
    if (!s->yp || !s->id || !s->atol || !s->newton_del || !s->ida)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the integrator");
    s->sink.fn = message_sink;
    s->sink.data = s;
    if (td_sun_install_message_sink(s->ctx, s->ida, &s->sink) != 0)
        return td_error_set(err, TD_ERR_SOLVER, "cannot install the IDA error handler");
    return TD_OK;
}

static td_status attach_ida(td_sim *s, td_error *err)
{
    int flag = IDAInit(s->ida, res_cb, s->t, s->y, s->yp);
    if (flag == IDA_SUCCESS)
        flag = IDASVtolerances(s->ida, s->opt.solver.rtol, s->atol);
    if (flag == IDA_SUCCESS)
        flag = IDASetUserData(s->ida, s);
    if (flag == IDA_SUCCESS)
        flag = IDASetId(s->ida, s->id);
    if (flag == IDA_SUCCESS)
        flag = IDASetSuppressAlg(s->ida, SUNTRUE);
    if (flag == IDA_SUCCESS)
        flag = IDASetMaxOrd(s->ida, s->opt.solver.max_order);
    if (flag == IDA_SUCCESS)
        flag = IDASetMaxNumSteps(s->ida, 100000);
    if (flag != IDA_SUCCESS)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    /* our own Newton solver, so that its convergence test can be wrapped (conv_test_cb) */
    s->NLS = SUNNonlinSol_Newton(s->y, s->ctx);
    if (!s->NLS)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the nonlinear solver");
    if (IDASetNonlinearSolver(s->ida, s->NLS) != IDA_SUCCESS)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    {
        SUNNonlinearSolverContent_Newton c = (SUNNonlinearSolverContent_Newton)s->NLS->content;
        s->ida_ctest = c->CTest;
        s->ida_ctest_data = c->ctest_data;
        if (!s->ida_ctest || SUNNonlinSolSetConvTestFn(s->NLS, conv_test_cb, s) != SUN_NLS_SUCCESS)
            return td_error_set(err, TD_ERR_SOLVER, "cannot install the Newton convergence test");
    }
    if (s->opt.solver.linear_solver == TD_LINSOL_KLU) {
        s->A = SUNSparseMatrix(s->neq, s->neq, s->nnz, CSC_MAT, s->ctx);
        s->LS = s->A ? td_sim_klu_create(s) : NULL;
    } else {
        s->A = SUNDenseMatrix(s->neq, s->neq, s->ctx);
        s->LS = s->A ? SUNLinSol_Dense(s->y, s->A, s->ctx) : NULL;
    }
    if (!s->A || !s->LS)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the linear solver");
    flag = IDASetLinearSolver(s->ida, s->LS, s->A);
    if (flag == IDA_SUCCESS)
        flag = IDASetJacFn(s->ida, jac_cb);
    if (flag == IDA_SUCCESS && s->nroots > 0) {
        flag = IDARootInit(s->ida, s->nroots, root_cb);
        if (flag == IDA_SUCCESS)
            flag = IDASetNoInactiveRootWarn(s->ida);
    }
    if (flag != IDA_SUCCESS)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    /* directions, first step, step bound and stop time as at every restart */
    if (td_sim_restart(s) != TD_OK)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    s->stats.restarts = 0;
    return TD_OK;
}

static int cancelled(volatile sig_atomic_t *cancel)
{
    return cancel && *cancel;
}

/* TD_OK, or TD_ERR_INTERRUPTED once `cancel` is set: read between the stages of the set-up. */
static td_status setup_stage(td_status st, volatile sig_atomic_t *cancel, td_error *err)
{
    if (st == TD_OK && cancelled(cancel))
        return td_error_set(err, TD_ERR_INTERRUPTED, "interrupted while setting up the simulation");
    return st;
}

/* Block offsets of the unknowns (sim_internal.h), the start time and the statistics' "none yet"
 * markers. */
static void init_layout(td_sim *s)
{
    s->nw = s->sys->n_controller_states;
    s->oq = 0;
    s->ov = s->n;
    s->ow = 2 * s->n;
    s->ol = s->ow + s->nw;
    s->ou = s->ol + s->nr;
    s->of = s->ou + s->nr;
    s->neq = s->of + s->ns;
    s->t = s->t_ida = s->t_acc = s->opt.t0;
    s->t_window = s->opt.t0;
    s->stats.first_contact_time = TD_UNDEFINED;
    s->stats.peak_time = TD_UNDEFINED;
    s->stats.peak_retainer = -1;
    s->stats.peak_amb_time = TD_UNDEFINED;
    s->stats.peak_amb = -1;
}

/* The retainers, free, with their contact laws, and the DOFs of their races after the rotor's
 * (s->n: all DOFs). */
static td_status init_retainers(td_sim *s, td_error *err)
{
    int k;
    s->model = td_system_model(s->sys);
    s->nr = td_model_retainer_count(s->model);
    s->ret = calloc((size_t)(s->nr > 0 ? s->nr : 1), sizeof *s->ret);
    if (!s->ret)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    for (k = 0; k < s->nr; k++) {
        td_sim_retainer_init(&s->ret[k], s->sys, k, &s->opt.contact);
        if (s->ret[k].r.stick)
            s->ret[k].fi = s->ns++;
    }
    td_sim_races_layout(s);
    return td_sim_races_matrices(s, err);
}

td_status td_sim_create(const td_model *model, const td_sim_options *options, td_sim **out, td_error *err)
{
    return td_sim_create_cancellable(model, options, NULL, out, err);
}

td_status td_sim_create_cancellable(const td_model *model, const td_sim_options *options, volatile sig_atomic_t *cancel,
                                    td_sim **out, td_error *err)
{
    td_sim *s;
    td_status st;
    char why[320];
    if (!model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_sim_create: NULL argument");
    *out = NULL;
    s = calloc(1, sizeof *s);
    if (!s)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    if (options)
        s->opt = *options;
    else
        td_sim_options_default(&s->opt);
    st = check_options(&s->opt, err);
    if (st == TD_OK && td_atol_limit_check(model, s->opt.solver.atol, why, sizeof why) != TD_LIMIT_NONE)
        st = td_error_set(err, TD_ERR_INVALID, "solver.atol: %s", why);
    if (st == TD_OK)
        st = setup_stage(td_system_create(model, &s->sys, err), cancel, err);
    if (st == TD_OK)
        st = init_retainers(s, err);
    if (st == TD_OK) {
        init_layout(s);
        st = alloc_arrays(s, err);
    }
    if (st == TD_OK) {
        init_machine(s);
        td_sim_apply_past_changes(s);
        s->spin_ref = s->omega * s->t;
        s->t_spin_ref = s->t;
        st = factor_mass(s, err);
    }
    if (st == TD_OK) {
        set_scales(s);
        s->hmax = s->opt.solver.max_step > 0.0 ? s->opt.solver.max_step : default_max_step(s);
    }
    if (st == TD_OK)
        st = td_sim_pattern_build(s, err);
    if (st == TD_OK)
        st = td_sim_structural_build(s, err);
    if (st == TD_OK)
        st = setup_stage(setup_ida(s, err), cancel, err);
    if (st == TD_OK) {
        set_tolerances(s);
        check_stability(s);
        st = setup_stage(TD_OK, cancel, err);
    }
    if (st == TD_OK)
        st = setup_stage(start_state(s, err), cancel, err);
    if (st == TD_OK)
        st = attach_ida(s, err);
    if (st != TD_OK) {
        td_sim_free(&s);
        return st;
    }
    td_sim_totals_point(s, s->t, 1);
    s->q_len = s->q_pos = 0; /* contacts at the start are a state, not events */
    s->stats.events = s->stats.releases = s->stats.contact_onsets = 0;
    *out = s;
    return TD_OK;
}

static void free_work(td_sim *s)
{
    free(s->mass_x);
    free(s->minv_f);
    free(s->power_x);
    free(s->power_kx);
    free(s->power_mx);
    free(s->schur);
    free(s->schur_rhs);
    free(s->restitution);
    free(s->impulse);
    free(s->impact_work);
    free(s->minv_cols);
    free(s->rows);
    free(s->active);
    free(s->active_roll);
    free(s->onset);
    free(s->entered);
    free(s->roll_tried);
    free(s->totals);
    free(s->energy_f);
    free(s->touching);
}

void td_sim_free(td_sim **sim)
{
    td_sim *s;
    if (!sim || !*sim)
        return;
    s = *sim;
    if (s->ida)
        IDAFree(&s->ida);
    if (s->LS)
        SUNLinSolFree(s->LS);
    if (s->NLS)
        SUNNonlinSolFree(s->NLS);
    if (s->A)
        SUNMatDestroy(s->A);
    if (s->y)
        N_VDestroy(s->y);
    if (s->yp)
        N_VDestroy(s->yp);
    if (s->id)
        N_VDestroy(s->id);
    if (s->atol)
        N_VDestroy(s->atol);
    if (s->newton_del)
        N_VDestroy(s->newton_del);
    if (s->ctx)
        SUNContext_Free(&s->ctx);
    cs_di_sfree(s->Ms);
    cs_di_nfree(s->Mn);
    free(s->colptr);
    free(s->rowind);
    free(s->jdata);
    free(s->map_M);
    free(s->map_C);
    free(s->map_G);
    free(s->map_K);
    free(s->st_rowptr);
    free(s->st_col);
    free(s->st_M);
    free(s->st_K);
    free(s->st_D);
    free(s->unb);
    free(s->amb_mode);
    free(s->amb_control);
    free(s->ret);
    free(s->amb_coef);
    free(s->queue);
    free_work(s);
    free(s->rootdir);
    free(s->rootsfound);
    free(s->ysave);
    free(s->ypsave);
    td_sim_races_free(s);
    td_sim_flight_free(s);
    td_sim_section_free(s);
    td_system_free(&s->sys);
    free(s);
    *sim = NULL;
}

const char *td_sim_errmsg(const td_sim *sim)
{
    return sim ? sim->errmsg : "";
}

/* ---- stepping ---------------------------------------------------------------------------- */

/* The AMBs' peak load at the state y (time t): the axis force against its capacity. */
static void monitor_ambs(td_sim *s, double t, const double *y)
{
    int k;
    for (k = 0; k < s->sys->n_amb_axes; k++) {
        const td_amb_axis *a = &s->sys->amb_axes[k];
        double f = fabs(td_sim_amb_axis_force(s, k, y));
        if (s->amb_mode[a->amb] != TD_AMB_OFF && f / a->capacity > s->stats.peak_amb_load) {
            s->stats.peak_amb_load = f / a->capacity;
            s->stats.peak_amb_force = f;
            s->stats.peak_amb_time = t;
            s->stats.peak_amb = a->amb;
        }
    }
}

/* Statistics at the state in s->y (time t): contact time, peak normal force, AMB load, and, at
 * integrator steps only (at_step; interpolated states carry the interpolation error), the drift. */
static void monitor_at(td_sim *s, double t, int at_step)
{
    const double *y = N_VGetArrayPointer(s->y);
    double dt = t - s->t_acc;
    int k;
    for (k = 0; k < s->nr; k++) {
        const td_sim_retainer *r = &s->ret[k];
        double fn;
        if (r->mode == TD_RMODE_FREE)
            continue;
        if (dt > 0.0)
            s->stats.time_in_contact += dt;
        if (r->mode == TD_RMODE_CONTACT && at_step) {
            double x, yy, vx, vy, drift;
            td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
            drift = fabs(hypot(x, yy) - r->r.clearance);
            if (drift > s->stats.worst_drift)
                s->stats.worst_drift = drift;
        }
        fn = td_sim_normal_force(s, k, y);
        s->totals[k].interval_peak = fmax(s->totals[k].interval_peak, fn);
        if (fn > s->stats.peak_normal_force) {
            s->stats.peak_normal_force = fn;
            s->stats.peak_time = t;
            s->stats.peak_retainer = k;
        }
    }
    monitor_ambs(s, t, y);
    if (t > s->t_acc)
        s->t_acc = t;
}

#define monitor(s, t) monitor_at((s), (t), 0)

static int pop_event(td_sim *s)
{
    if (s->q_pos >= s->q_len) {
        s->q_pos = s->q_len = 0;
        return 0;
    }
    s->last = s->queue[s->q_pos++];
    s->have_last = 1;
    if (s->q_pos >= s->q_len)
        s->q_pos = s->q_len = 0;
    return 1;
}

/* y, yp at time t inside IDA's last step. */
static td_status interpolate(td_sim *s, double t)
{
    if (IDAGetDky(s->ida, t, 0, s->y) != IDA_SUCCESS || IDAGetDky(s->ida, t, 1, s->yp) != IDA_SUCCESS) {
        snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: IDA could not interpolate its last step (IDAGetDky)", t);
        return TD_ERR_SOLVER;
    }
    s->t = t;
    td_sim_spin_hold(s, t, N_VGetArrayPointer(s->y), N_VGetArrayPointer(s->yp));
    return TD_OK;
}

/* An IDA failure: keep the state of the last successful step. */
static td_status solver_failure(td_sim *s, int flag)
{
    char msg[TD_ERROR_MESSAGE_SIZE];
    double tn = s->t;
    snprintf(msg, sizeof msg, "%s", s->errmsg);
    if (IDAGetCurrentTime(s->ida, &tn) == IDA_SUCCESS && tn >= s->t && interpolate(s, tn) == TD_OK) {
        /* state at tn */
    } else {
        memcpy(N_VGetArrayPointer(s->y), s->ysave, sizeof(double) * (size_t)s->neq);
        memcpy(N_VGetArrayPointer(s->yp), s->ypsave, sizeof(double) * (size_t)s->neq);
    }
    snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: IDA failed (flag %d): %.400s", s->t, flag, msg);
    return TD_ERR_SOLVER;
}

/*
 * A run whose steps no longer move time is stalled: fail with a message instead of hanging. A
 * step below STALL_STEP rounding units of max(t, 1 s) (2.2e-13 s up to t = 1 s) advances t by
 * nothing measurable; after an impact IDA starts short but doubles its step, so STALL_COUNT such
 * steps in a row (2.2e-9 s in all) never occur in a run that progresses.
 */
#define STALL_STEP 1e3
#define STALL_COUNT 10000L

static int stalled(td_sim *s, double t)
{
    double h;
    if (IDAGetLastStep(s->ida, &h) != IDA_SUCCESS || h >= STALL_STEP * DBL_EPSILON * fmax(fabs(t), 1.0)) {
        s->tiny_steps = 0;
        return 0;
    }
    if (++s->tiny_steps < STALL_COUNT)
        return 0;
    snprintf(s->errmsg, sizeof s->errmsg,
             "t = %.9g s: the integrator stalled (%ld steps in a row of %.2g s or less); loosen solver.rtol or "
             "solver.atol",
             t, s->tiny_steps, h);
    return 1;
}

/*
 * A run whose work no longer moves time is stuck, whatever the cause (steps, restarts at events,
 * flights cut short by stops), and fails with a message instead of going on for ever. Every
 * PROGRESS_WINDOW passes of integration (an IDA step or a piece of free flight, each with the stops
 * it meets) must advance t by PROGRESS_SPAN at least: a pace of 1e-10 s a pass would need 1e10
 * passes per simulated second, 100 times TD_MAX_STEPS, the most steps any case may force. (An
 * absolute tolerance far above the clearance once made a drop run advance 2e-6 s in 35 s of
 * passes, 6e-8 s a window.) Passes that only interpolate to an output time do not count.
 */
#define PROGRESS_WINDOW 10000L
#define PROGRESS_SPAN 1e-6

static int no_progress(td_sim *s)
{
    if (++s->passes < PROGRESS_WINDOW)
        return 0;
    if (s->t - s->t_window >= PROGRESS_SPAN) {
        s->passes = 0;
        s->t_window = s->t;
        return 0;
    }
    snprintf(s->errmsg, sizeof s->errmsg,
             "t = %.9g s: no progress: %ld integrator steps and stops advanced the time by only %.3g s (a run "
             "this slow would take over %.0e steps per simulated second); loosen solver.rtol or solver.atol, "
             "or check the machine for forces that grow without bound",
             s->t, s->passes, s->t - s->t_window, (double)PROGRESS_WINDOW / PROGRESS_SPAN);
    return 1;
}

/* Restart after a change made between steps or at a schedule time; the retainers' totals open
 * their next segment there. */
static td_status restart_after_change(td_sim *s)
{
    td_status st;
    td_sim_totals_rewind(s); /* a change at an output inside the last step: the totals end here */
    st = td_sim_make_consistent(s, NULL);
    if (st == TD_OK)
        st = td_sim_restart(s);
    if (st == TD_OK)
        td_sim_totals_point(s, s->t, 1);
    return st;
}

/* What stopped the integration at s->t_pending (s->pending). */
enum { TD_PENDING_NONE = 0, TD_PENDING_ROOT = 1, TD_PENDING_TSTOP = 2, TD_PENDING_RESYNC = 3 };

/* Handle a root (IDAGetRootInfo in s->rootsfound), a penalty mode out of step with the state
 * (TD_PENDING_RESYNC: no root), or the stop time at s->t. */
static td_status handle_stop(td_sim *s, int kind)
{
    td_status st;
    if (kind == TD_PENDING_RESYNC) {
        memset(s->rootsfound, 0, sizeof(int) * (size_t)s->nroots);
        kind = TD_PENDING_ROOT;
    }
    if (kind == TD_PENDING_ROOT) {
        int restart = 0;
        st = td_sim_handle_roots(s, &restart);
        if (st == TD_OK && restart)
            st = td_sim_restart(s);
        if (st == TD_OK && restart) {
            monitor(s, s->t); /* the state after the event: an impact's normal force counts in the peaks */
            td_sim_totals_point(s, s->t, 1);
        }
        return st;
    }
    st = td_sim_apply_due_changes(s);
    if (st == TD_OK)
        st = restart_after_change(s);
    return st;
}

/* The stop pending beyond the last output time (a root, the stop time or a penalty resync): past
 * tout, only interpolate to tout; otherwise handle it. Returns 1 when advance returns *st (tout
 * reached, an event to report or a failure), 0 to go on integrating. */
static int pending_stop(td_sim *s, double tout, td_status *st)
{
    int kind = s->pending;
    if (s->t_pending > tout) {
        *st = interpolate(s, tout);
        monitor(s, tout);
        return 1;
    }
    s->pending = 0;
    td_sim_section_ida(s, s->t_pending); /* the crossings before the stop, from the step that found it */
    *st = interpolate(s, s->t_pending);
    monitor(s, s->t);
    if (*st == TD_OK)
        td_sim_totals_point(s, s->t, 0); /* the segment up to the stop */
    if (*st == TD_OK)
        *st = handle_stop(s, kind);
    if (*st != TD_OK)
        return 1;
    if (pop_event(s)) {
        *st = TD_EVENT;
        return 1;
    }
    return 0;
}

/* The state at tret accepted (an integrator step's end, at_step, or the flight's): statistics,
 * and the state kept as the last good one. */
static void accept_point(td_sim *s, double tret, int at_step)
{
    s->t = tret;
    td_sim_spin_hold(s, tret, N_VGetArrayPointer(s->y), N_VGetArrayPointer(s->yp));
    monitor_at(s, tret, at_step);
    td_sim_totals_point(s, tret, 0);
    memcpy(s->ysave, N_VGetArrayPointer(s->y), sizeof(double) * (size_t)s->neq);
    memcpy(s->ypsave, N_VGetArrayPointer(s->yp), sizeof(double) * (size_t)s->neq);
}

/* Free flight in closed form (flight.c) from s->t toward tout, up to the next stop. Returns 0 if
 * the flight cannot carry the machine now (IDA integrates), 1 when advance returns *st (tout
 * reached, an event to report or a failure), 2 to go on. */
static int fly(td_sim *s, double tout, td_status *st)
{
    double stop = td_sim_next_stop(s);
    int root = 0;
    if (!td_sim_flight_advance(s, tout, stop, &root))
        return 0;
    s->ida_stale = 1; /* IDA's history is of the state before the flight */
    s->t_ida = s->t;
    td_sim_section_flight(s, s->t);
    accept_point(s, s->t, 0);
    *st = TD_OK;
    if (root || s->t >= stop) {
        *st = handle_stop(s, root ? TD_PENDING_ROOT : TD_PENDING_TSTOP);
        if (*st != TD_OK)
            return 1;
        if (pop_event(s)) {
            *st = TD_EVENT;
            return 1;
        }
        return 2;
    }
    return s->t >= tout ? 1 : 2;
}

static td_status advance(td_sim *s, double tout)
{
    for (;;) {
        sunrealtype tret = s->t, tn = s->t;
        int flag;
        td_status st;
        if (s->pending) {
            if (pending_stop(s, tout, &st))
                return st;
            continue;
        }
        if (s->t_ida == s->t && tout == s->t) { /* restarted right here (a stop at tout): nothing to interpolate */
            monitor(s, tout);
            return TD_OK;
        }
        if (s->t_ida >= tout) {
            st = interpolate(s, tout);
            monitor(s, tout);
            return st;
        }
        if (tout - s->t <= 1e-14 * (1.0 + fabs(tout))) { /* too close for IDA to start: nothing moves */
            s->t = tout;
            return TD_OK;
        }
        if (s->interrupt && *s->interrupt) {
            /* y, yp hold the state at s->t here (a step's end, a restart or the flight's end) */
            snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: interrupted", s->t);
            return TD_ERR_INTERRUPTED;
        }
        if (no_progress(s))
            return TD_ERR_SOLVER; /* y, yp hold the state at s->t, as for an interrupt */
        switch (fly(s, tout, &st)) {
        case 1: return st;
        case 2: continue;
        default: break;
        }
        if (s->ida_stale) {
            td_sim_flight_rates(s);
            if ((st = td_sim_restart(s)) != TD_OK)
                return st;
        }
        flag = IDASolve(s->ida, tout, &tret, s->y, s->yp, IDA_ONE_STEP);
        if (flag < 0)
            return solver_failure(s, flag);
        if (IDAGetCurrentTime(s->ida, &tn) == IDA_SUCCESS && tn > s->t_ida)
            s->t_ida = tn;
        if (stalled(s, tret)) {
            accept_point(s, tret, 1); /* the run ends at the stalled step, its state in place */
            return TD_ERR_SOLVER;
        }
        if (flag == IDA_ROOT_RETURN || flag == IDA_TSTOP_RETURN) {
            if (flag == IDA_ROOT_RETURN)
                IDAGetRootInfo(s->ida, s->rootsfound);
            s->pending = flag == IDA_ROOT_RETURN ? TD_PENDING_ROOT : TD_PENDING_TSTOP;
            s->t_pending = tret;
            continue;
        }
        if (td_sim_modes_out_of_step(s, N_VGetArrayPointer(s->y))) {
            /* IDA missed a crossing (retainer.c): switch the mode at this step's end */
            s->pending = TD_PENDING_RESYNC;
            s->t_pending = tret;
            continue;
        }
        accept_point(s, tret, 1);
        td_sim_section_ida(s, tret);
        td_sim_flight_forget(s);
        if (tret > tout) { /* an output inside this step: its sample counts too */
            st = interpolate(s, tout);
            monitor(s, tout);
            return st;
        }
        if (tret == tout)
            return TD_OK;
    }
}

/* A public call that can fail begins with no message: whatever it reports is its own, never the
 * leftover of an earlier failure (an interrupt, say, that the caller recovered from). */
static void begin_call(td_sim *s)
{
    s->errmsg[0] = '\0';
}

/* A failure of a public call: the message the sim keeps (s->errmsg, td_sim_errmsg) into *err. */
static td_status failed(const td_sim *s, td_status st, td_error *err)
{
    return td_error_set(err, st, "%s", s->errmsg[0] ? s->errmsg : td_strerror(st));
}

/* A public call's outcome: failures reported through *err, TD_OK and TD_EVENT as they are. */
static td_status reported(const td_sim *s, td_status st, td_error *err)
{
    return st < 0 ? failed(s, st, err) : st;
}

td_status td_sim_step(td_sim *sim, double tout, double *t_reached, td_error *err)
{
    td_status st;
    double w0;
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "td_sim_step: NULL simulation");
    begin_call(sim);
    if (pop_event(sim)) {
        if (t_reached)
            *t_reached = sim->t;
        return TD_EVENT;
    }
    if (!isfinite(tout) || tout < sim->t) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_step: tout = %.17g is before the current time %.17g", tout,
                 sim->t);
        return failed(sim, TD_ERR_INVALID, err);
    }
    w0 = td_wall_clock();
    st = tout > sim->t ? advance(sim, tout) : TD_OK;
    sim->stats.wall_time += td_wall_clock() - w0;
    if (t_reached)
        *t_reached = sim->t;
    return reported(sim, st, err);
}

td_status td_sim_start_info_get(const td_sim *sim, td_sim_start_info *out)
{
    if (!sim || !out)
        return TD_ERR_INVALID;
    *out = sim->start;
    return TD_OK;
}

td_status td_sim_set_interrupt(td_sim *sim, volatile sig_atomic_t *flag)
{
    if (!sim)
        return TD_ERR_INVALID;
    sim->interrupt = flag;
    return TD_OK;
}

double td_sim_speed(const td_sim *sim)
{
    return sim ? td_sim_rotor_speed(sim, N_VGetArrayPointer(sim->y)) : 0.0;
}

double td_sim_time(const td_sim *sim)
{
    return sim ? sim->t : NAN;
}

td_status td_sim_last_event(const td_sim *sim, td_event *ev)
{
    if (!sim || !ev)
        return TD_ERR_INVALID;
    if (!sim->have_last)
        return TD_ERR_STATE;
    *ev = sim->last;
    return TD_OK;
}

/* ---- accessors --------------------------------------------------------------------------- */

int td_sim_dof_count(const td_sim *sim)
{
    return sim ? sim->sys->ndof : 0;
}

td_status td_sim_get_state(const td_sim *sim, double *q, double *v)
{
    const double *y;
    if (!sim)
        return TD_ERR_INVALID;
    y = N_VGetArrayPointer(sim->y);
    if (q)
        memcpy(q, y + sim->oq, sizeof(double) * (size_t)sim->sys->ndof);
    if (v)
        memcpy(v, y + sim->ov, sizeof(double) * (size_t)sim->sys->ndof);
    return TD_OK;
}

td_status td_sim_retainer_state(const td_sim *sim, int retainer, td_retainer_state *out)
{
    const double *y;
    const td_sim_retainer *r;
    double rx, ry, vx, vy;
    if (!sim || !out || retainer < 0 || retainer >= sim->nr)
        return TD_ERR_INVALID;
    y = N_VGetArrayPointer(sim->y);
    r = &sim->ret[retainer];
    out->x = y[sim->oq + r->dx];
    out->y = y[sim->oq + r->dy];
    out->race_x = r->rx >= 0 ? y[sim->oq + r->rx] : 0.0;
    out->race_y = r->rx >= 0 ? y[sim->oq + r->ry] : 0.0;
    out->race_speed = td_sim_race_speed(sim, retainer, y);
    td_sim_node_state(sim, retainer, y, &rx, &ry, &vx, &vy);
    out->radius = hypot(rx, ry);
    out->radial_velocity = td_contact_radial_velocity(rx, ry, vx, vy);
    out->whirl_angle = atan2(ry, rx);
    out->whirl_rate = out->radius > 0.0 ? (rx * vy - ry * vx) / (out->radius * out->radius) : 0.0;
    out->normal_force = td_sim_normal_force(sim, retainer, y);
    out->in_contact = r->mode != TD_RMODE_FREE;
    out->rolling = r->rolling;
    out->friction_force =
        out->in_contact
            ? td_contact_friction_force(r->r.friction, td_sim_slip_factor(sim, retainer, y, NULL), out->normal_force)
            : 0.0;
    if (r->rolling) /* F_t acts on the race along t, the opposite on the rotor */
        out->friction_force = -y[sim->of + r->fi];
    out->sliding_velocity = td_sim_sliding_velocity(sim, retainer, y);
    return TD_OK;
}

td_status td_sim_amb_force(const td_sim *sim, int amb, double f[2])
{
    const double *y;
    int k;
    if (!sim || !f || amb < 0 || amb >= td_model_amb_count(sim->model))
        return TD_ERR_INVALID;
    y = N_VGetArrayPointer(sim->y);
    f[0] = f[1] = 0.0;
    for (k = 0; k < sim->sys->n_amb_axes; k++)
        if (sim->sys->amb_axes[k].amb == amb)
            f[sim->sys->amb_axes[k].axis] = td_sim_amb_axis_force(sim, k, y);
    return TD_OK;
}

td_status td_sim_stats_get(const td_sim *sim, td_sim_stats *out)
{
    long v;
    if (!sim || !out)
        return TD_ERR_INVALID;
    *out = sim->stats;
    out->steps = sim->base.steps;
    out->residual_evals = sim->base.res;
    out->jacobian_evals = sim->base.jac;
    out->linear_setups = sim->base.setups;
    out->nonlinear_iters = sim->base.nli;
    out->error_test_fails = sim->base.etf;
    out->nonlinear_fails = sim->base.ncf;
    if (IDAGetNumSteps(sim->ida, &v) == IDA_SUCCESS)
        out->steps += v;
    if (IDAGetNumResEvals(sim->ida, &v) == IDA_SUCCESS)
        out->residual_evals += v;
    if (IDAGetNumJacEvals(sim->ida, &v) == IDA_SUCCESS)
        out->jacobian_evals += v;
    if (IDAGetNumLinSolvSetups(sim->ida, &v) == IDA_SUCCESS)
        out->linear_setups += v;
    if (IDAGetNumNonlinSolvIters(sim->ida, &v) == IDA_SUCCESS)
        out->nonlinear_iters += v;
    if (IDAGetNumErrTestFails(sim->ida, &v) == IDA_SUCCESS)
        out->error_test_fails += v;
    if (IDAGetNumNonlinSolvConvFails(sim->ida, &v) == IDA_SUCCESS)
        out->nonlinear_fails += v;
    return TD_OK;
}

/* ---- changes between steps --------------------------------------------------------------- */

td_status td_sim_set_unbalance(td_sim *sim, int unbalance, double magnitude, double phase, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (unbalance < 0 || unbalance >= sim->nu || !(magnitude >= 0.0) || !isfinite(magnitude) || !isfinite(phase)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_unbalance: invalid unbalance %d or value", unbalance);
        return failed(sim, TD_ERR_INVALID, err);
    }
    sim->unb[unbalance].magnitude = magnitude;
    sim->unb[unbalance].phase = phase;
    return reported(sim, restart_after_change(sim), err);
}

td_status td_sim_set_speed(td_sim *sim, double omega, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (!TD_SPEED_VALID(omega)) {
        snprintf(sim->errmsg, sizeof sim->errmsg,
                 "td_sim_set_speed: speed must be finite and >= 0 rad/s (got %g; the spin is about +z)", omega);
        return failed(sim, TD_ERR_INVALID, err);
    }
    if (sim->spin >= 0) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_speed: the model's speed is %s, not set by the caller",
                 sim->spin_free ? "free (spin.free)" : "a ramp (speed_ramp)");
        return failed(sim, TD_ERR_INVALID, err);
    }
    /* keep the spin angle continuous: the unbalance force turns on from where it is */
    sim->spin_ref = td_sim_spin_angle(sim, sim->t);
    sim->t_spin_ref = sim->t;
    sim->omega = omega;
    td_sim_structural_speed(sim);
    if (sim->opt.solver.max_step <= 0.0) {
        sim->hmax = default_max_step(sim);
    }
    return reported(sim, restart_after_change(sim), err);
}

td_status td_sim_set_amb_mode(td_sim *sim, int amb, td_amb_mode mode, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (amb < 0 || amb >= td_model_amb_count(sim->model) ||
        (mode != TD_AMB_PD && mode != TD_AMB_EXTERNAL && mode != TD_AMB_OFF)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_amb_mode: invalid AMB %d or mode %d", amb, (int)mode);
        return failed(sim, TD_ERR_INVALID, err);
    }
    td_sim_amb_mode_set(sim, amb, mode);
    return reported(sim, restart_after_change(sim), err);
}

td_status td_sim_set_amb_control(td_sim *sim, int amb, double fx, double fy, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (amb < 0 || amb >= td_model_amb_count(sim->model) || !isfinite(fx) || !isfinite(fy)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_amb_control: invalid AMB %d or force", amb);
        return failed(sim, TD_ERR_INVALID, err);
    }
    sim->amb_control[2 * amb] = fx;
    sim->amb_control[2 * amb + 1] = fy;
    /* the held force jumps: restart only when it acts now */
    return sim->amb_mode[amb] == TD_AMB_EXTERNAL ? reported(sim, restart_after_change(sim), err) : TD_OK;
}

const td_system *td_sim_system(const td_sim *sim)
{
    return sim ? sim->sys : NULL;
}

const td_model *td_sim_model(const td_sim *sim)
{
    return sim ? sim->model : NULL;
}

td_status td_sim_options_get(const td_sim *sim, td_sim_options *out)
{
    if (!sim || !out)
        return TD_ERR_INVALID;
    *out = sim->opt;
    return TD_OK;
}
