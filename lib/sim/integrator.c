/*
 * The integrator: SUNDIALS IDA on the contact DAE (sim_residual.c), its callbacks, its Newton
 * convergence test, the KLU or dense linear solver, and its restarts after every mode switch with
 * the running totals of its counters, which IDAReInit resets.
 */
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ida/ida_ls.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>

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
        for (j = 0; j <= s->dae.neq; j++)
            cp[j] = s->ops.colptr[j];
        for (p = 0; p < s->ops.nnz; p++) {
            ri[p] = s->ops.rowind[p];
            d[p] = s->ops.jdata[p];
        }
    } else {
        SUNMatZero(J);
        for (j = 0; j < s->dae.neq; j++) {
            sunrealtype *col = SUNDenseMatrix_Column(J, j);
            for (p = s->ops.colptr[j]; p < s->ops.colptr[j + 1]; p++)
                col[s->ops.rowind[p]] = s->ops.jdata[p];
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
    for (k = 0; k < s->dae.nr; k++) {
        double mu_floor = MULTIPLIER_FLOOR * DBL_EPSILON * s->contacts.ret[k].r.clearance * cj;
        double lambda_floor = mu_floor * s->machine.stiff_scale / s->machine.freq_scale;
        double fl = 1.0 / (lambda_floor * w[s->dae.ol + k]), fu = 1.0 / (mu_floor * w[s->dae.ou + k]);
        if (fl >= 1.0 && fu >= 1.0)
            continue;
        if (!d) {
            N_VScale(1.0, del, s->solver.newton_del);
            d = N_VGetArrayPointer(s->solver.newton_del);
        }
        d[s->dae.ol + k] *= fmin(fl, 1.0);
        d[s->dae.ou + k] *= fmin(fu, 1.0);
    }
    return d ? s->solver.newton_del : del;
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
    if (IDAGetNonlinearSystemData(s->solver.ida, &tcur, &ypred, &yppred, &yyn, &ypn, &res, &cj, &user) != IDA_SUCCESS)
        return s->solver.ida_ctest(nls, ycor, del, tol, ewt, s->solver.ida_ctest_data);
    flag = s->solver.ida_ctest(nls, ycor, floored_multipliers(s, del, ewt, cj), tol, ewt, s->solver.ida_ctest_data);
    if (flag != SUN_NLS_SUCCESS)
        return flag;
    cor = N_VGetArrayPointer(ycor);
    pred = N_VGetArrayPointer(ypred);
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double x, y;
        if (r->mode != TD_RMODE_CONTACT)
            continue;
        x = pred[s->dae.oq + r->dx] + cor[s->dae.oq + r->dx];
        y = pred[s->dae.oq + r->dy] + cor[s->dae.oq + r->dy];
        if (r->rx >= 0) {
            x -= pred[s->dae.oq + r->rx] + cor[s->dae.oq + r->rx];
            y -= pred[s->dae.oq + r->ry] + cor[s->dae.oq + r->ry];
        }
        if (fabs(td_contact_constraint(x, y, r->r.clearance)) > s->machine.constraint_tol)
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

/* IDA set-up; failures leave their message in s->errmsg. */
td_status td_sim_integrator_create(td_sim *s, td_error *err)
{
    if (td_sun_context_create(&s->solver.ctx) != 0)
        return td_error_set(err, TD_ERR_NOMEM, "SUNContext_Create failed");
    s->dae.y = N_VNew_Serial(s->dae.neq, s->solver.ctx);
    if (!s->dae.y)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the state vectors");
    td_sim_nvector_optimize(s->dae.y); /* before any clone: the clones copy its operations */
    s->dae.yp = N_VClone(s->dae.y);
    s->solver.id = N_VClone(s->dae.y);
    s->solver.atol = N_VClone(s->dae.y);
    s->solver.newton_del = N_VClone(s->dae.y);
    s->solver.ida = IDACreate(s->solver.ctx);
    if (!s->dae.yp || !s->solver.id || !s->solver.atol || !s->solver.newton_del || !s->solver.ida)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the integrator");
    s->solver.sink.fn = message_sink;
    s->solver.sink.data = s;
    if (td_sun_install_message_sink(s->solver.ctx, s->solver.ida, &s->solver.sink) != 0)
        return td_error_set(err, TD_ERR_SOLVER, "cannot install the IDA error handler");
    return TD_OK;
}

td_status td_sim_integrator_attach(td_sim *s, td_error *err)
{
    int flag = IDAInit(s->solver.ida, res_cb, s->dae.t, s->dae.y, s->dae.yp);
    if (flag == IDA_SUCCESS)
        flag = IDASVtolerances(s->solver.ida, s->opt.solver.rtol, s->solver.atol);
    if (flag == IDA_SUCCESS)
        flag = IDASetUserData(s->solver.ida, s);
    if (flag == IDA_SUCCESS)
        flag = IDASetId(s->solver.ida, s->solver.id);
    if (flag == IDA_SUCCESS)
        flag = IDASetSuppressAlg(s->solver.ida, SUNTRUE);
    if (flag == IDA_SUCCESS)
        flag = IDASetMaxOrd(s->solver.ida, s->opt.solver.max_order);
    if (flag == IDA_SUCCESS)
        flag = IDASetMaxNumSteps(s->solver.ida, 100000);
    if (flag != IDA_SUCCESS)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    /* our own Newton solver, so that its convergence test can be wrapped (conv_test_cb) */
    s->solver.NLS = SUNNonlinSol_Newton(s->dae.y, s->solver.ctx);
    if (!s->solver.NLS)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the nonlinear solver");
    if (IDASetNonlinearSolver(s->solver.ida, s->solver.NLS) != IDA_SUCCESS)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    {
        SUNNonlinearSolverContent_Newton c = (SUNNonlinearSolverContent_Newton)s->solver.NLS->content;
        s->solver.ida_ctest = c->CTest;
        s->solver.ida_ctest_data = c->ctest_data;
        if (!s->solver.ida_ctest || SUNNonlinSolSetConvTestFn(s->solver.NLS, conv_test_cb, s) != SUN_NLS_SUCCESS)
            return td_error_set(err, TD_ERR_SOLVER, "cannot install the Newton convergence test");
    }
    if (s->opt.solver.linear_solver == TD_LINSOL_KLU) {
        s->solver.A = SUNSparseMatrix(s->dae.neq, s->dae.neq, s->ops.nnz, CSC_MAT, s->solver.ctx);
        s->solver.LS = s->solver.A ? td_sim_klu_create(s) : NULL;
    } else {
        s->solver.A = SUNDenseMatrix(s->dae.neq, s->dae.neq, s->solver.ctx);
        s->solver.LS = s->solver.A ? SUNLinSol_Dense(s->dae.y, s->solver.A, s->solver.ctx) : NULL;
    }
    if (!s->solver.A || !s->solver.LS)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating the linear solver");
    flag = IDASetLinearSolver(s->solver.ida, s->solver.LS, s->solver.A);
    if (flag == IDA_SUCCESS)
        flag = IDASetJacFn(s->solver.ida, jac_cb);
    if (flag == IDA_SUCCESS && s->dae.nroots > 0) {
        flag = IDARootInit(s->solver.ida, s->dae.nroots, root_cb);
        if (flag == IDA_SUCCESS)
            flag = IDASetNoInactiveRootWarn(s->solver.ida);
    }
    if (flag != IDA_SUCCESS)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    /* directions, first step, step bound and stop time as at every restart */
    if (td_sim_restart(s) != TD_OK)
        return td_error_set(err, TD_ERR_SOLVER, "IDA set-up failed: %s", s->errmsg);
    s->monitor.stats.restarts = 0;
    return TD_OK;
}

/* y, yp at time t inside IDA's last step. */
td_status td_sim_interpolate(td_sim *s, double t)
{
    if (IDAGetDky(s->solver.ida, t, 0, s->dae.y) != IDA_SUCCESS ||
        IDAGetDky(s->solver.ida, t, 1, s->dae.yp) != IDA_SUCCESS) {
        snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: IDA could not interpolate its last step (IDAGetDky)", t);
        return TD_ERR_SOLVER;
    }
    s->dae.t = t;
    td_sim_spin_hold(s, t, N_VGetArrayPointer(s->dae.y), N_VGetArrayPointer(s->dae.yp));
    return TD_OK;
}

/*
 * A run whose steps no longer move time is stalled: fail with a message instead of hanging. A
 * step below STALL_STEP rounding units of max(t, 1 s) (2.2e-13 s up to t = 1 s) advances t by
 * nothing measurable; after an impact IDA starts short but doubles its step, so STALL_COUNT such
 * steps in a row (2.2e-9 s in all) never occur in a run that progresses.
 */
#define STALL_STEP 1e3
#define STALL_COUNT 10000L

int td_sim_stalled(td_sim *s, double t)
{
    double h;
    if (IDAGetLastStep(s->solver.ida, &h) != IDA_SUCCESS || h >= STALL_STEP * DBL_EPSILON * fmax(fabs(t), 1.0)) {
        s->solver.tiny_steps = 0;
        return 0;
    }
    if (++s->solver.tiny_steps < STALL_COUNT)
        return 0;
    snprintf(s->errmsg, sizeof s->errmsg,
             "t = %.9g s: the integrator stalled (%ld steps in a row of %.2g s or less); loosen solver.rtol or "
             "solver.atol",
             t, s->solver.tiny_steps, h);
    return 1;
}

static void save_counters(td_sim *s)
{
    long v;
    if (IDAGetNumSteps(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.steps += v;
    if (IDAGetNumResEvals(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.res += v;
    if (IDAGetNumJacEvals(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.jac += v;
    if (IDAGetNumLinSolvSetups(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.setups += v;
    if (IDAGetNumNonlinSolvIters(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.nli += v;
    if (IDAGetNumErrTestFails(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.etf += v;
    if (IDAGetNumNonlinSolvConvFails(s->solver.ida, &v) == IDA_SUCCESS)
        s->solver.base.ncf += v;
}

/*
 * Restart step: BDF restarts at order 1, whose local error is about h^2/2 |q''| on the
 * displacements; choose h so that this is a quarter of the displacement tolerance at the
 * largest acceleration, within [1e-12 s, hmax] (or the user's initial_step). The displacement
 * tolerance is td_sim_restart_tolerance's (tolerance.c says why it is not IDA's own).
 */
static double restart_step(const td_sim *s)
{
    const double *y = N_VGetArrayPointer(s->dae.y), *yp = N_VGetArrayPointer(s->dae.yp);
    double amax = 0.0, h;
    int i;
    if (s->opt.solver.initial_step > 0.0)
        return s->opt.solver.initial_step;
    for (i = 0; i < s->dae.n; i++) {
        double a = fabs(yp[s->dae.ov + i]) / td_sim_restart_tolerance(s, s->dae.oq + i, y);
        if (a > amax)
            amax = a;
    }
    h = amax > 0.0 ? sqrt(0.5 / amax) : s->solver.hmax;
    if (h > s->solver.hmax)
        h = s->solver.hmax;
    if (h < 1e-12)
        h = 1e-12;
    return h;
}

td_status td_sim_restart(td_sim *s)
{
    double stop = td_sim_next_stop(s);
    int flag;
    save_counters(s);
    td_sim_spin_wrap(s, N_VGetArrayPointer(s->dae.y));
    flag = IDAReInit(s->solver.ida, s->dae.t, s->dae.y, s->dae.yp);
    if (flag == IDA_SUCCESS && td_sim_races_retolerance(s)) /* a race came into or out of contact */
        flag = IDASVtolerances(s->solver.ida, s->opt.solver.rtol, s->solver.atol);
    if (flag == IDA_SUCCESS) {
        td_sim_root_directions(s, s->dae.rootdir);
        if (s->dae.nroots > 0)
            flag = IDASetRootDirection(s->solver.ida, s->dae.rootdir);
    }
    if (flag == IDA_SUCCESS)
        flag = IDASetInitStep(s->solver.ida, restart_step(s));
    if (flag == IDA_SUCCESS)
        flag = IDASetMaxStep(s->solver.ida, s->solver.hmax);
    if (flag == IDA_SUCCESS) /* none: a stop that the flight passed over must not stay set */
        flag = IDASetStopTime(s->solver.ida, isfinite(stop) ? stop : DBL_MAX);
    if (flag != IDA_SUCCESS) {
        if (!s->errmsg[0])
            snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: IDA re-initialisation failed (%d)", s->dae.t, flag);
        return TD_ERR_SOLVER;
    }
    s->solver.t_ida = s->dae.t;
    s->solver.ida_stale = 0;
    td_sim_flight_forget(s);
    s->monitor.stats.restarts++;
    return TD_OK;
}

void td_sim_integrator_counters(const td_sim *s, td_sim_stats *out)
{
    long v;
    out->steps = s->solver.base.steps;
    out->residual_evals = s->solver.base.res;
    out->jacobian_evals = s->solver.base.jac;
    out->linear_setups = s->solver.base.setups;
    out->nonlinear_iters = s->solver.base.nli;
    out->error_test_fails = s->solver.base.etf;
    out->nonlinear_fails = s->solver.base.ncf;
    if (IDAGetNumSteps(s->solver.ida, &v) == IDA_SUCCESS)
        out->steps += v;
    if (IDAGetNumResEvals(s->solver.ida, &v) == IDA_SUCCESS)
        out->residual_evals += v;
    if (IDAGetNumJacEvals(s->solver.ida, &v) == IDA_SUCCESS)
        out->jacobian_evals += v;
    if (IDAGetNumLinSolvSetups(s->solver.ida, &v) == IDA_SUCCESS)
        out->linear_setups += v;
    if (IDAGetNumNonlinSolvIters(s->solver.ida, &v) == IDA_SUCCESS)
        out->nonlinear_iters += v;
    if (IDAGetNumErrTestFails(s->solver.ida, &v) == IDA_SUCCESS)
        out->error_test_fails += v;
    if (IDAGetNumNonlinSolvConvFails(s->solver.ida, &v) == IDA_SUCCESS)
        out->nonlinear_fails += v;
}

void td_sim_integrator_free(td_sim *s)
{
    if (s->solver.ida)
        IDAFree(&s->solver.ida);
    if (s->solver.LS)
        SUNLinSolFree(s->solver.LS);
    if (s->solver.NLS)
        SUNNonlinSolFree(s->solver.NLS);
    if (s->solver.A)
        SUNMatDestroy(s->solver.A);
    if (s->dae.y)
        N_VDestroy(s->dae.y);
    if (s->dae.yp)
        N_VDestroy(s->dae.yp);
    if (s->solver.id)
        N_VDestroy(s->solver.id);
    if (s->solver.atol)
        N_VDestroy(s->solver.atol);
    if (s->solver.newton_del)
        N_VDestroy(s->solver.newton_del);
    if (s->solver.ctx)
        SUNContext_Free(&s->solver.ctx);
}
