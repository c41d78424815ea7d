/*
 * discretise.c - sampled laws: a continuous law sampled by Tustin's bilinear map (optionally
 * prewarped) or by the zero-order hold, and a computation delay of whole samples as a shift
 * register on the outputs (touchdown/controller.h; docs/theory.md, "Controllers").
 */
#include "control/control_internal.h"
#include "control/numerics.h"

#include "touchdown/dofs.h" /* TD_PI */
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static td_status check_discretise(const td_controller *k, double rate, td_discretisation method, double prewarp,
                                  td_error *err)
{
    if (!k)
        return td_error_set(err, TD_ERR_INVALID, "discretise: NULL controller");
    if (k->sample_rate > 0.0)
        return td_error_set(err, TD_ERR_INVALID, "discretise: the law is sampled already (at %g Hz)", k->sample_rate);
    if (td_ctl_check_positive(rate, "discretise", "sample_rate", err) != TD_OK)
        return err ? err->code : TD_ERR_INVALID;
    if (method != TD_DISCRETISE_TUSTIN && method != TD_DISCRETISE_ZOH)
        return td_ctl_invalid(err, "discretise", "method", "unknown method %d", (int)method);
    if (!(isfinite(prewarp) && prewarp >= 0.0 && prewarp < 0.5 * rate))
        return td_ctl_invalid(err, "discretise", "prewarp",
                              "must be >= 0 and below the Nyquist frequency %g Hz (got %g)", 0.5 * rate, prewarp);
    if (method == TD_DISCRETISE_ZOH && prewarp != 0.0)
        return td_ctl_invalid(err, "discretise", "prewarp", "applies to Tustin only (got %g Hz with zoh)", prewarp);
    if (td_controller_has_velocity_feedthrough(k))
        return td_error_set(err, TD_ERR_INVALID,
                            "discretise: the law has an unfiltered derivative (velocity "
                            "feedthrough D1), which has no sampled form: give it a filter");
    return TD_OK;
}

/* Zero-order hold: Ad = exp(A T), Bd = (integral of exp(A s) ds over [0, T]) B, C and D kept. */
static td_status zoh(td_controller *d, const td_controller *k, td_error *err)
{
    int n = k->n;
    double *ex = malloc(2 * (size_t)n * n * sizeof *ex), *h;
    td_status st;
    if (!ex)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory discretising a controller");
    h = ex + (size_t)n * n;
    st = td_slicot_expm(n, 1.0 / d->sample_rate, k->A, ex, h, err);
    if (st == TD_OK) {
        memcpy(d->A, ex, (size_t)n * n * sizeof *ex);
        td_ctl_matmul(h, n, n, k->B, k->inputs, d->B);
    }
    free(ex);
    return st;
}

/* Tustin: s = beta (z - 1)/(z + 1), beta = 2 rate, or w0 / tan(w0 T / 2) so that the sampled
 * response equals the continuous one at w0 (the prewarp frequency). */
td_controller *td_controller_discretise(const td_controller *k, double sample_rate, td_discretisation method,
                                        double prewarp, td_error *err)
{
    td_controller *d;
    td_status st = TD_OK;
    if (check_discretise(k, sample_rate, method, prewarp, err) != TD_OK)
        return NULL;
    d = td_controller_clone(k, err);
    if (!d)
        return NULL;
    d->sample_rate = sample_rate;
    if (k->n > 0 && method == TD_DISCRETISE_ZOH) {
        st = zoh(d, k, err);
    } else if (k->n > 0) {
        double w0 = 2.0 * TD_PI * prewarp;
        double beta = prewarp > 0.0 ? w0 / tan(0.5 * w0 / sample_rate) : 2.0 * sample_rate;
        st = td_slicot_balance(k->n, k->inputs, k->outputs, d->A, d->B, d->C, err);
        if (st == TD_OK)
            st = td_slicot_bilinear(k->n, k->inputs, k->outputs, beta, d->A, d->B, d->C, d->D, err);
    }
    if (st != TD_OK)
        td_controller_free(&d);
    return td_ctl_finite(d, "discretise", err);
}

/* States [x; s1; ...; s_d], s_j (outputs each) the output j samples ago:
 * x+ = A x + B e, s1+ = C x + D e, s_{j+1}+ = s_j, output s_d. */
td_controller *td_controller_delay(const td_controller *k, int samples, td_error *err)
{
    td_controller *d;
    int n, p, N, i, j, l;
    if (!k) {
        td_error_set(err, TD_ERR_INVALID, "delay: NULL controller");
        return NULL;
    }
    if (samples < 0) {
        td_ctl_invalid(err, "delay", "samples", "must be >= 0 (got %d)", samples);
        return NULL;
    }
    if (!(k->sample_rate > 0.0)) {
        td_error_set(err, TD_ERR_INVALID,
                     "delay: a delay of whole samples needs a sampled law (this one is continuous)");
        return NULL;
    }
    if (samples == 0)
        return td_controller_clone(k, err);
    n = k->n, p = k->outputs, N = n + samples * p;
    d = td_ctl_alloc(N, k->inputs, p, k->sample_rate, err);
    if (!d)
        return NULL;
    for (j = 0; j < n; j++) {
        for (i = 0; i < n; i++)
            d->A[i + (size_t)j * N] = k->A[i + (size_t)j * n];
        for (i = 0; i < p; i++)
            d->A[n + i + (size_t)j * N] = k->C[i + (size_t)j * p];
    }
    for (l = 1; l < samples; l++)
        for (i = 0; i < p; i++)
            d->A[n + l * p + i + (size_t)(n + (l - 1) * p + i) * N] = 1.0;
    for (j = 0; j < k->inputs; j++) {
        for (i = 0; i < n; i++)
            d->B[i + (size_t)j * N] = k->B[i + (size_t)j * n];
        for (i = 0; i < p; i++)
            d->B[n + i + (size_t)j * N] = k->D[i + (size_t)j * p];
    }
    for (i = 0; i < p; i++)
        d->C[i + (size_t)(n + (samples - 1) * p + i) * p] = 1.0;
    return d;
}
