/*
 * combine.c - controllers joined in series, side by side, in parallel (summed), and through static
 * coordinate transforms (touchdown/controller.h). E below is a law's velocity feedthrough D1.
 */
#include "control/control_internal.h"

#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* out (leading dimension ldo) += alpha X Y, X rows x inner (ldx), Y inner x cols (ldy). */
static void mul_add(double *out, int ldo, const double *X, int ldx, const double *Y, int ldy, int rows, int inner,
                    int cols, double alpha)
{
    int i, j, l;
    for (j = 0; j < cols; j++)
        for (l = 0; l < inner; l++) {
            double y = alpha * Y[l + (size_t)j * ldy];
            for (i = 0; i < rows; i++)
                out[i + (size_t)j * ldo] += X[i + (size_t)l * ldx] * y;
        }
}

/* Copies the rows x cols matrix X (ldx) into out (ldo). */
static void put(double *out, int ldo, const double *X, int ldx, int rows, int cols)
{
    int i, j;
    for (j = 0; j < cols; j++)
        for (i = 0; i < rows; i++)
            out[i + (size_t)j * ldo] = X[i + (size_t)j * ldx];
}

static td_status check_timing(const td_controller *a, const td_controller *b, const char *who, td_error *err)
{
    if (!a || !b)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL controller", who);
    if (a->sample_rate != b->sample_rate)
        return td_error_set(err, TD_ERR_INVALID,
                            "%s: the laws differ in timing (sample rates %g and %g Hz; 0: continuous)", who,
                            a->sample_rate, b->sample_rate);
    return TD_OK;
}

/* The terms the velocity feedthrough adds (derivation in docs/theory.md, "Controllers"): with
 * E1 != 0 the second law's state is shifted by B2 E1 e (so that no e' enters a state), with
 * E2 != 0 the derivative of the first law's output is C1 (A1 x1 + B1 e) + D1 e'. */
static td_status series_feedthrough(const td_controller *k1, const td_controller *k2, td_controller *k, td_error *err)
{
    int n1 = k1->n, n2 = k2->n, m = k1->inputs, p1 = k1->outputs, p = k2->outputs, n = k->n;
    double *t1, *t2;
    t1 = calloc((size_t)n2 * m + (size_t)p * n1 + 1, sizeof *t1);
    if (!t1)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a controller");
    t2 = t1 + (size_t)n2 * m;
    mul_add(t1, n2, k2->B, n2, k1->D1, p1, n2, p1, m, 1.0); /* B2 E1 */
    mul_add(t2, p, k2->D1, p, k1->C, p1, p, p1, n1, 1.0);   /* E2 C1 */
    mul_add(k->B + n1, n, k2->A, n2, t1, n2, n2, n2, m, 1.0);
    mul_add(k->D, p, k2->C, p, t1, n2, p, n2, m, 1.0);
    mul_add(k->C, p, t2, p, k1->A, n1, p, n1, n1, 1.0);
    mul_add(k->D, p, t2, p, k1->B, n1, p, n1, m, 1.0);
    mul_add(k->D1, p, k2->D, p, k1->D1, p1, p, p1, m, 1.0);
    mul_add(k->D1, p, k2->D1, p, k1->D, p1, p, p1, m, 1.0);
    free(t1);
    return TD_OK;
}

/* A = [A1 0; B2 C1 A2], B = [B1; B2 D1], C = [D2 C1  C2], D = D2 D1, plus series_feedthrough. */
td_controller *td_controller_series(const td_controller *first, const td_controller *second, td_error *err)
{
    const td_controller *k1 = first, *k2 = second;
    td_controller *k;
    int n1, n2, m, p1, p, n;
    if (check_timing(first, second, "series", err) != TD_OK)
        return NULL;
    if (k2->inputs != k1->outputs) {
        td_error_set(err, TD_ERR_INVALID, "series: the first law has %d outputs, the second %d inputs", k1->outputs,
                     k2->inputs);
        return NULL;
    }
    if (td_controller_has_velocity_feedthrough(k1) && td_controller_has_velocity_feedthrough(k2)) {
        td_error_set(err, TD_ERR_INVALID,
                     "series: both laws are improper by one (velocity feedthrough D1), so their "
                     "series would be improper by two: give one derivative a filter");
        return NULL;
    }
    n1 = k1->n, n2 = k2->n, m = k1->inputs, p1 = k1->outputs, p = k2->outputs, n = n1 + n2;
    k = td_ctl_alloc(n, m, p, k1->sample_rate, err);
    if (!k)
        return NULL;
    put(k->A, n, k1->A, n1, n1, n1);
    put(k->A + n1 + (size_t)n1 * n, n, k2->A, n2, n2, n2);
    mul_add(k->A + n1, n, k2->B, n2, k1->C, p1, n2, p1, n1, 1.0);
    put(k->B, n, k1->B, n1, n1, m);
    mul_add(k->B + n1, n, k2->B, n2, k1->D, p1, n2, p1, m, 1.0);
    mul_add(k->C, p, k2->D, p, k1->C, p1, p, p1, n1, 1.0);
    put(k->C + (size_t)n1 * p, p, k2->C, p, p, n2);
    mul_add(k->D, p, k2->D, p, k1->D, p1, p, p1, m, 1.0);
    if (series_feedthrough(k1, k2, k, err) != TD_OK)
        td_controller_free(&k);
    return td_ctl_finite(k, "series", err);
}

td_controller *td_controller_append(const td_controller *a, const td_controller *b, td_error *err)
{
    td_controller *k;
    int n, m, p;
    if (check_timing(a, b, "append", err) != TD_OK)
        return NULL;
    n = a->n + b->n, m = a->inputs + b->inputs, p = a->outputs + b->outputs;
    k = td_ctl_alloc(n, m, p, a->sample_rate, err);
    if (!k)
        return NULL;
    put(k->A, n, a->A, a->n, a->n, a->n);
    put(k->A + a->n + (size_t)a->n * n, n, b->A, b->n, b->n, b->n);
    put(k->B, n, a->B, a->n, a->n, a->inputs);
    put(k->B + a->n + (size_t)a->inputs * n, n, b->B, b->n, b->n, b->inputs);
    put(k->C, p, a->C, a->outputs, a->outputs, a->n);
    put(k->C + a->outputs + (size_t)a->n * p, p, b->C, b->outputs, b->outputs, b->n);
    put(k->D, p, a->D, a->outputs, a->outputs, a->inputs);
    put(k->D + a->outputs + (size_t)a->inputs * p, p, b->D, b->outputs, b->outputs, b->inputs);
    put(k->D1, p, a->D1, a->outputs, a->outputs, a->inputs);
    put(k->D1 + a->outputs + (size_t)a->inputs * p, p, b->D1, b->outputs, b->outputs, b->inputs);
    return k;
}

/* A = [A1 0; 0 A2], B = [B1; B2], C = [C1  C2], D = D1 + D2, E = E1 + E2. */
td_controller *td_controller_parallel(const td_controller *a, const td_controller *b, td_error *err)
{
    td_controller *k;
    int n, m, p, j;
    if (check_timing(a, b, "parallel", err) != TD_OK)
        return NULL;
    if (a->inputs != b->inputs || a->outputs != b->outputs) {
        td_error_set(err, TD_ERR_INVALID, "parallel: the laws differ in size (%d x %d and %d x %d, outputs x inputs)",
                     a->outputs, a->inputs, b->outputs, b->inputs);
        return NULL;
    }
    n = a->n + b->n, m = a->inputs, p = a->outputs;
    k = td_ctl_alloc(n, m, p, a->sample_rate, err);
    if (!k)
        return NULL;
    put(k->A, n, a->A, a->n, a->n, a->n);
    put(k->A + a->n + (size_t)a->n * n, n, b->A, b->n, b->n, b->n);
    put(k->B, n, a->B, a->n, a->n, m);
    put(k->B + a->n, n, b->B, b->n, b->n, m);
    put(k->C, p, a->C, p, p, a->n);
    put(k->C + (size_t)a->n * p, p, b->C, p, p, b->n);
    for (j = 0; j < p * m; j++) {
        k->D[j] = a->D[j] + b->D[j];
        k->D1[j] = a->D1[j] + b->D1[j];
    }
    return td_ctl_finite(k, "parallel", err);
}

static td_status check_transform(const td_controller *k, int new_inputs, const double *Tin, int new_outputs,
                                 const double *Tout, td_error *err)
{
    if (!k || !Tin || !Tout)
        return td_error_set(err, TD_ERR_INVALID, "transform: NULL argument");
    if (new_inputs < 1 || new_outputs < 1)
        return td_error_set(err, TD_ERR_INVALID, "transform: needs >= 1 new input and output (got %d, %d)", new_inputs,
                            new_outputs);
    if (!td_ctl_all_finite(Tin, k->inputs * new_inputs) || !td_ctl_all_finite(Tout, new_outputs * k->outputs))
        return td_error_set(err, TD_ERR_INVALID, "transform: a matrix entry is not finite");
    return TD_OK;
}

/* B <- B Tin, C <- Tout C, D <- Tout D Tin, D1 <- Tout D1 Tin; A unchanged. */
td_controller *td_controller_transform(const td_controller *k, int new_inputs, const double *Tin, int new_outputs,
                                       const double *Tout, td_error *err)
{
    td_controller *t;
    double *w;
    int n, m, p;
    if (check_transform(k, new_inputs, Tin, new_outputs, Tout, err) != TD_OK)
        return NULL;
    n = k->n, m = k->inputs, p = k->outputs;
    t = td_ctl_alloc(n, new_inputs, new_outputs, k->sample_rate, err);
    w = calloc((size_t)p * new_inputs + 1, sizeof *w);
    if (!t || !w) {
        if (t && !w)
            td_error_set(err, TD_ERR_NOMEM, "out of memory creating a controller");
        td_controller_free(&t);
        free(w);
        return NULL;
    }
    put(t->A, n, k->A, n, n, n);
    mul_add(t->B, n, k->B, n, Tin, m, n, m, new_inputs, 1.0);
    mul_add(t->C, new_outputs, Tout, new_outputs, k->C, p, new_outputs, p, n, 1.0);
    mul_add(w, p, k->D, p, Tin, m, p, m, new_inputs, 1.0);
    mul_add(t->D, new_outputs, Tout, new_outputs, w, p, new_outputs, p, new_inputs, 1.0);
    memset(w, 0, (size_t)p * new_inputs * sizeof *w);
    mul_add(w, p, k->D1, p, Tin, m, p, m, new_inputs, 1.0);
    mul_add(t->D1, new_outputs, Tout, new_outputs, w, p, new_outputs, p, new_inputs, 1.0);
    free(w);
    return td_ctl_finite(t, "transform", err);
}
