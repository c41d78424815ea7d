/*
 * The linear solver inside IDA's Newton iteration: a SUNLinearSolver on SuiteSparse KLU that
 * factorises the sim's own Jacobian arrays (s->ops.colptr, s->ops.rowind, s->ops.jdata: one fixed pattern,
 * int indices) and keeps KLU's symbolic analysis for the whole run.
 *
 * Why not SUNDIALS's SUNLinSol_KLU: IDAReInit, which the sim calls at every event, makes IDA call
 * the solver's initialize operation, and SUNLinSol_KLU's forces a complete new factorisation
 * there: symbolic analysis (BTF, COLAMD) and a pivoting LU at every event. Here the
 * pattern never changes (sim_pattern.c), so the analysis is done once. What a mode switch can
 * change is which entries are zero (a constraint row of a free retainer is lambda = 0, of a
 * constrained one g(q) = 0), so the first factorisation after a restart pivots afresh
 * (klu_factor); the later ones reuse the pivot order (klu_refactor) and fall back to a pivoting
 * factorisation when KLU's reciprocal pivot growth estimate says that order has gone bad, as
 * SUNLinSol_KLU does.
 */
#include "sim/sim_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <klu.h>

typedef struct td_klu_ls {
    const td_sim *s;
    klu_symbolic *sym;
    klu_numeric *num;
    klu_common common;
    int refresh; /* next setup: factorise with fresh pivoting */
    int last_flag;
} td_klu_ls;

#define KLU_CONTENT(S) ((td_klu_ls *)(S)->content)

static SUNLinearSolver_Type ls_type(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID ls_id(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}

/* Called by IDA after every IDAReInit: the analysis stays, the next factorisation pivots. */
static int ls_initialize(SUNLinearSolver S)
{
    td_klu_ls *c = KLU_CONTENT(S);
    c->refresh = 1;
    c->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
}

/* A pivoting factorisation of the current values; 0 or a SUNLS_* failure. */
static int factor(td_klu_ls *c)
{
    const td_sim *s = c->s;
    if (c->num)
        klu_free_numeric(&c->num, &c->common);
    c->num = klu_factor(s->ops.colptr, s->ops.rowind, s->ops.jdata, c->sym, &c->common);
    if (!c->num)
        return c->common.status == KLU_SINGULAR ? SUNLS_PACKAGE_FAIL_REC : SUNLS_PACKAGE_FAIL_UNREC;
    c->refresh = 0;
    return SUNLS_SUCCESS;
}

/* The matrix argument is IDA's copy of the same values (jac_cb): KLU reads the sim's arrays. */
static int ls_setup(SUNLinearSolver S, SUNMatrix A)
{
    td_klu_ls *c = KLU_CONTENT(S);
    const td_sim *s = c->s;
    (void)A;
    if (!c->sym) {
        c->sym = klu_analyze(s->dae.neq, s->ops.colptr, s->ops.rowind, &c->common);
        if (!c->sym)
            return c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
    }
    if (c->refresh || !c->num)
        return c->last_flag = factor(c);
    /* same pivot order; a cheap estimate of 1/cond (min/max |U_ii|) guards it, as in SUNLinSol_KLU */
    if (!klu_refactor(s->ops.colptr, s->ops.rowind, s->ops.jdata, c->sym, c->num, &c->common) ||
        !klu_rcond(c->sym, c->num, &c->common) || !(c->common.rcond > pow(DBL_EPSILON, 2.0 / 3.0)))
        return c->last_flag = factor(c);
    return c->last_flag = SUNLS_SUCCESS;
}

static int ls_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype tol)
{
    td_klu_ls *c = KLU_CONTENT(S);
    double *xd = N_VGetArrayPointer(x);
    (void)A, (void)tol;
    if (x != b)
        memcpy(xd, N_VGetArrayPointer(b), sizeof(double) * (size_t)c->s->dae.neq);
    if (!c->num || !klu_solve(c->sym, c->num, c->s->dae.neq, 1, xd, &c->common))
        return c->last_flag = SUNLS_PACKAGE_FAIL_REC;
    return c->last_flag = SUNLS_SUCCESS;
}

static sunindextype ls_last_flag(SUNLinearSolver S)
{
    return KLU_CONTENT(S)->last_flag;
}

static int ls_free(SUNLinearSolver S)
{
    td_klu_ls *c;
    if (!S)
        return SUNLS_SUCCESS;
    c = KLU_CONTENT(S);
    if (c) {
        if (c->num)
            klu_free_numeric(&c->num, &c->common);
        if (c->sym)
            klu_free_symbolic(&c->sym, &c->common);
        free(c);
        S->content = NULL;
    }
    SUNLinSolFreeEmpty(S);
    return SUNLS_SUCCESS;
}

SUNLinearSolver td_sim_klu_create(const td_sim *s)
{
    SUNLinearSolver S = SUNLinSolNewEmpty(s->solver.ctx);
    td_klu_ls *c;
    if (!S)
        return NULL;
    c = calloc(1, sizeof *c);
    if (!c) {
        SUNLinSolFreeEmpty(S);
        return NULL;
    }
    c->s = s;
    c->refresh = 1;
    klu_defaults(&c->common);
    S->content = c;
    S->ops->gettype = ls_type;
    S->ops->getid = ls_id;
    S->ops->initialize = ls_initialize;
    S->ops->setup = ls_setup;
    S->ops->solve = ls_solve;
    S->ops->lastflag = ls_last_flag;
    S->ops->free = ls_free;
    return S;
}
