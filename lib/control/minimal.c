/*
 * minimal.c - a minimal, balanced realisation (SLICOT TB01PD, then TB01ID). D and D1 are
 * untouched: removing states and a diagonal similarity change neither.
 */
#include "control/control_internal.h"
#include "control/numerics.h"

#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

td_controller *td_controller_minimal(const td_controller *k, td_error *err)
{
    td_controller *r = NULL;
    double *w;
    int n, m, p, nr = 0;
    if (!k) {
        td_error_set(err, TD_ERR_INVALID, "minimal: NULL controller");
        return NULL;
    }
    n = k->n, m = k->inputs, p = k->outputs;
    if (n == 0)
        return td_controller_clone(k, err);
    w = malloc(((size_t)n * n + (size_t)n * m + (size_t)p * n) * sizeof *w);
    if (!w) {
        td_error_set(err, TD_ERR_NOMEM, "out of memory reducing a controller");
        return NULL;
    }
    td_controller_matrices(k, w, w + (size_t)n * n, w + (size_t)n * n + (size_t)n * m, NULL, NULL);
    if (td_slicot_minimal(n, m, p, w, w + (size_t)n * n, w + (size_t)n * n + (size_t)n * m, &nr, err) == TD_OK &&
        td_slicot_balance(nr, m, p, w, w + (size_t)n * n, w + (size_t)n * n + (size_t)n * m, err) == TD_OK)
        r = td_ctl_alloc(nr, m, p, k->sample_rate, err);
    if (r) {
        memcpy(r->A, w, (size_t)nr * nr * sizeof *w);
        memcpy(r->B, w + (size_t)n * n, (size_t)nr * m * sizeof *w);
        memcpy(r->C, w + (size_t)n * n + (size_t)n * m, (size_t)p * nr * sizeof *w);
        memcpy(r->D, k->D, (size_t)p * m * sizeof *w);
        memcpy(r->D1, k->D1, (size_t)p * m * sizeof *w);
    }
    free(w);
    return td_ctl_finite(r, "minimal", err);
}
