/*
 * step.c - a controller's response to a unit step on one input from rest (touchdown/controller.h):
 * exact for a continuous law, y(t) = C H(t) b + d with H(t) the integral of exp(A s) over [0, t]
 * (SLICOT MB05ND at each time), and the held sample sequence of a sampled law.
 */
#include "control/control_internal.h"
#include "control/numerics.h"

#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>

/* A sampled response held on [t_k, t_{k+1}): a time within 1e-9 of a sample period before an
 * instant counts as that instant (a time written as k / rate rounds either way). */
#define TD_STEP_SNAP 1e-9
/* The most samples a sampled step response runs (its y sequence is kept in memory). */
#define TD_STEP_MAX_SAMPLES 10000000L

static td_status check_step(const td_controller *k, int input, const double *t, int n_times, const double *y,
                            td_error *err)
{
    if (!k || (n_times > 0 && (!t || !y)) || n_times < 0)
        return td_error_set(err, TD_ERR_INVALID, "step_response: NULL argument or negative count");
    if (input < 0 || input >= k->inputs)
        return td_error_set(err, TD_ERR_INVALID, "step_response: input %d out of range (the law has %d)", input,
                            k->inputs);
    if (td_controller_has_velocity_feedthrough(k))
        return td_error_set(err, TD_ERR_INVALID,
                            "step_response: the law has an unfiltered derivative (velocity "
                            "feedthrough D1): its step response holds an impulse");
    if (!td_ctl_all_finite(t, n_times))
        return td_error_set(err, TD_ERR_INVALID, "step_response: a time is not finite");
    for (int i = 0; i < n_times; i++)
        if (t[i] < 0.0)
            return td_error_set(err, TD_ERR_INVALID, "step_response: time %d is negative (%g s)", i, t[i]);
    return TD_OK;
}

static td_status continuous_step(const td_controller *k, int input, const double *t, int n_times, double *y,
                                 td_error *err)
{
    int n = k->n, p = k->outputs, i, l;
    const double *b = k->B + (size_t)input * n, *d = k->D + (size_t)input * p;
    double *ex = malloc((2 * (size_t)n * n + (size_t)n + 1) * sizeof *ex), *h, *x;
    td_status st = TD_OK;
    if (!ex)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in a step response");
    h = ex + (size_t)n * n;
    x = h + (size_t)n * n;
    for (i = 0; i < n_times && st == TD_OK; i++) {
        double *yi = y + (size_t)i * p;
        if (n > 0)
            st = td_slicot_expm(n, t[i], k->A, ex, h, err);
        td_ctl_matmul(h, n, n, b, 1, x);
        td_ctl_matmul(k->C, p, n, x, 1, yi);
        for (l = 0; l < p; l++)
            yi[l] += d[l];
    }
    free(ex);
    return st;
}

static td_status sampled_step(const td_controller *k, int input, const double *t, int n_times, double *y, td_error *err)
{
    int n = k->n, p = k->outputs, i, l;
    long kmax = 0, s;
    const double *b = k->B + (size_t)input * n, *d = k->D + (size_t)input * p;
    double *seq, *x, *xn;
    for (i = 0; i < n_times; i++) {
        double ki = floor(t[i] * k->sample_rate + TD_STEP_SNAP);
        if (ki > (double)TD_STEP_MAX_SAMPLES)
            return td_error_set(err, TD_ERR_INVALID, "step_response: %g s is more than %ld samples", t[i],
                                TD_STEP_MAX_SAMPLES);
        kmax = (long)ki > kmax ? (long)ki : kmax;
    }
    seq = malloc(((size_t)(kmax + 1) * p + 2 * (size_t)n + 1) * sizeof *seq);
    if (!seq)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in a step response");
    x = seq + (size_t)(kmax + 1) * p;
    xn = x + n;
    for (l = 0; l < n; l++)
        x[l] = 0.0;
    for (s = 0; s <= kmax; s++) { /* y_k = C x_k + d, x_{k+1} = A x_k + b */
        td_ctl_matmul(k->C, p, n, x, 1, seq + (size_t)s * p);
        for (l = 0; l < p; l++)
            seq[(size_t)s * p + l] += d[l];
        td_ctl_matmul(k->A, n, n, x, 1, xn);
        for (l = 0; l < n; l++)
            x[l] = xn[l] + b[l];
    }
    for (i = 0; i < n_times; i++)
        for (l = 0; l < p; l++)
            y[(size_t)i * p + l] = seq[(size_t)floor(t[i] * k->sample_rate + TD_STEP_SNAP) * p + l];
    free(seq);
    return TD_OK;
}

td_status td_controller_step_response(const td_controller *k, int input, const double *t, int n_times, double *y,
                                      td_error *err)
{
    td_status st = check_step(k, input, t, n_times, y, err);
    if (st != TD_OK)
        return st;
    return k->sample_rate > 0.0 ? sampled_step(k, input, t, n_times, y, err)
                                : continuous_step(k, input, t, n_times, y, err);
}
