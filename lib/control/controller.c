/*
 * controller.c - the td_controller object: allocation, copies, the state-space constructor and
 * the readers (touchdown/controller.h).
 */
#include "control/control_internal.h"

#include "util/error_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

td_controller *td_ctl_alloc(int n, int inputs, int outputs, double sample_rate, td_error *err)
{
    size_t count = (size_t)n * (size_t)n + (size_t)n * (size_t)inputs + (size_t)outputs * (size_t)n +
                   2 * (size_t)outputs * (size_t)inputs;
    td_controller *k = calloc(1, sizeof *k + (count ? count : 1) * sizeof(double));
    if (!k) {
        td_error_set(err, TD_ERR_NOMEM, "out of memory creating a controller");
        return NULL;
    }
    k->n = n;
    k->inputs = inputs;
    k->outputs = outputs;
    k->sample_rate = sample_rate;
    k->A = (double *)(k + 1);
    k->B = k->A + (size_t)n * (size_t)n;
    k->C = k->B + (size_t)n * (size_t)inputs;
    k->D = k->C + (size_t)outputs * (size_t)n;
    k->D1 = k->D + (size_t)outputs * (size_t)inputs;
    return k;
}

int td_ctl_any_nonzero(const double *v, int count)
{
    int i;
    for (i = 0; i < count; i++)
        if (v[i] != 0.0)
            return 1;
    return 0;
}

int td_ctl_all_finite(const double *v, int count)
{
    int i;
    for (i = 0; i < count; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

td_status td_ctl_invalid(td_error *err, const char *part, const char *field, const char *fmt, ...)
{
    td_error_site site = {part, -1, field}, none = {NULL, -1, NULL};
    char reason[TD_ERROR_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    return td_error_set_site(err, TD_ERR_INVALID, &site, &none, "%s", reason);
}

td_status td_ctl_check_positive(double v, const char *part, const char *field, td_error *err)
{
    if (!(isfinite(v) && v > 0.0))
        return td_ctl_invalid(err, part, field, "must be finite and > 0 (got %g)", v);
    return TD_OK;
}

td_status td_ctl_check_frequency(double v, int zero_ok, const char *part, const char *field, td_error *err)
{
    if (!((v >= TD_CONTROLLER_FREQUENCY_MIN && v <= TD_CONTROLLER_FREQUENCY_MAX) || (zero_ok && v == 0.0)))
        return td_ctl_invalid(err, part, field, "must be %s%g to %g Hz (got %g)", zero_ok ? "0 (none) or " : "",
                              TD_CONTROLLER_FREQUENCY_MIN, TD_CONTROLLER_FREQUENCY_MAX, v);
    return TD_OK;
}

td_controller *td_ctl_finite(td_controller *k, const char *part, td_error *err)
{
    size_t n;
    if (!k)
        return NULL;
    n = (size_t)k->n * (size_t)k->n + (size_t)k->n * (size_t)k->inputs + (size_t)k->outputs * (size_t)k->n +
        2 * (size_t)k->outputs * (size_t)k->inputs; /* A, B, C, D and D1, one allocation */
    if (td_ctl_all_finite(k->A, (int)n))
        return k;
    td_controller_free(&k);
    td_ctl_invalid(err, part, NULL,
                   "the realisation overflows (an entry is inf or NaN): its numbers are too far apart "
                   "for double precision");
    return NULL;
}

void td_ctl_matmul(const double *X, int rows, int inner, const double *Y, int cols, double *Z)
{
    int i, j, l;
    for (j = 0; j < cols; j++)
        for (i = 0; i < rows; i++) {
            double z = 0.0;
            for (l = 0; l < inner; l++)
                z += X[i + (size_t)l * rows] * Y[l + (size_t)j * inner];
            Z[i + (size_t)j * rows] = z;
        }
}

/* Checks the sizes and values of create_ss's arguments. */
static td_status check_ss(int n, int inputs, int outputs, const double *A, const double *B, const double *C,
                          const double *D, const double *D1, double sample_rate, td_error *err)
{
    if (n < 0 || inputs < 1 || outputs < 1)
        return td_error_set(err, TD_ERR_INVALID, "ss: needs n >= 0 states, >= 1 input and >= 1 output (got %d, %d, %d)",
                            n, inputs, outputs);
    if ((n > 0 && (!A || !B || !C)) || !D)
        return td_error_set(err, TD_ERR_INVALID, "ss: a matrix is missing (NULL)");
    if (!(isfinite(sample_rate) && sample_rate >= 0.0))
        return td_ctl_invalid(err, "ss", "sample_rate", "must be finite and >= 0 (got %g)", sample_rate);
    if (!td_ctl_all_finite(A, n * n) || !td_ctl_all_finite(B, n * inputs) || !td_ctl_all_finite(C, outputs * n) ||
        !td_ctl_all_finite(D, outputs * inputs) || (D1 && !td_ctl_all_finite(D1, outputs * inputs)))
        return td_error_set(err, TD_ERR_INVALID, "ss: a matrix entry is not finite");
    if (sample_rate > 0.0 && D1 && td_ctl_any_nonzero(D1, outputs * inputs))
        return td_ctl_invalid(err, "ss", "D1", "a sampled law has no velocity feedthrough (D1 must be NULL or zero)");
    return TD_OK;
}

td_controller *td_controller_create_ss(int n, int inputs, int outputs, const double *A, const double *B,
                                       const double *C, const double *D, const double *D1, double sample_rate,
                                       td_error *err)
{
    td_controller *k;
    if (check_ss(n, inputs, outputs, A, B, C, D, D1, sample_rate, err) != TD_OK)
        return NULL;
    k = td_ctl_alloc(n, inputs, outputs, sample_rate, err);
    if (!k)
        return NULL;
    if (n > 0) {
        memcpy(k->A, A, (size_t)n * (size_t)n * sizeof *A);
        memcpy(k->B, B, (size_t)n * (size_t)inputs * sizeof *B);
        memcpy(k->C, C, (size_t)outputs * (size_t)n * sizeof *C);
    }
    memcpy(k->D, D, (size_t)outputs * (size_t)inputs * sizeof *D);
    if (D1)
        memcpy(k->D1, D1, (size_t)outputs * (size_t)inputs * sizeof *D1);
    return k;
}

td_controller *td_controller_clone(const td_controller *k, td_error *err)
{
    td_controller *c;
    if (!k) {
        td_error_set(err, TD_ERR_INVALID, "td_controller_clone: NULL controller");
        return NULL;
    }
    c = td_ctl_alloc(k->n, k->inputs, k->outputs, k->sample_rate, err);
    if (c)
        td_controller_matrices(k, c->A, c->B, c->C, c->D, c->D1);
    return c;
}

void td_controller_free(td_controller **k)
{
    if (k) {
        free(*k);
        *k = NULL;
    }
}

int td_controller_order(const td_controller *k)
{
    return k ? k->n : 0;
}
int td_controller_inputs(const td_controller *k)
{
    return k ? k->inputs : 0;
}
int td_controller_outputs(const td_controller *k)
{
    return k ? k->outputs : 0;
}
double td_controller_sample_rate(const td_controller *k)
{
    return k ? k->sample_rate : 0.0;
}

int td_controller_has_velocity_feedthrough(const td_controller *k)
{
    return k ? td_ctl_any_nonzero(k->D1, k->outputs * k->inputs) : 0;
}

void td_controller_matrices(const td_controller *k, double *A, double *B, double *C, double *D, double *D1)
{
    size_t nn, ni, on, oi;
    if (!k)
        return;
    nn = (size_t)k->n * (size_t)k->n;
    ni = (size_t)k->n * (size_t)k->inputs;
    on = (size_t)k->outputs * (size_t)k->n;
    oi = (size_t)k->outputs * (size_t)k->inputs;
    if (A && nn)
        memcpy(A, k->A, nn * sizeof *A);
    if (B && ni)
        memcpy(B, k->B, ni * sizeof *B);
    if (C && on)
        memcpy(C, k->C, on * sizeof *C);
    if (D)
        memcpy(D, k->D, oi * sizeof *D);
    if (D1)
        memcpy(D1, k->D1, oi * sizeof *D1);
}
