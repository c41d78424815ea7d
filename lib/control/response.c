/*
 * response.c - a controller's frequency response (touchdown/controller.h): G = C (sI - A)^-1 B + D
 * (+ s D1), with s = jw (continuous) or z = exp(jw / sample_rate) (sampled), by Gaussian
 * elimination with partial pivoting on the complex (sI - A), which is backward stable and small
 * (a controller has a handful of states).
 */
#include "control/control_internal.h"

#include "touchdown/dofs.h" /* TD_PI */
#include "util/error_internal.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>

/* Solves M X = R in place (M n x n, R n x m, column-major); 0 when M is singular. */
static int complex_solve(double complex *M, double complex *R, int n, int m)
{
    int i, j, c, l;
    for (c = 0; c < n; c++) {
        int piv = c;
        for (i = c + 1; i < n; i++)
            if (cabs(M[i + (size_t)c * n]) > cabs(M[piv + (size_t)c * n]))
                piv = i;
        if (M[piv + (size_t)c * n] == 0.0)
            return 0;
        for (j = 0; j < n && piv != c; j++) {
            double complex t = M[c + (size_t)j * n];
            M[c + (size_t)j * n] = M[piv + (size_t)j * n];
            M[piv + (size_t)j * n] = t;
        }
        for (j = 0; j < m && piv != c; j++) {
            double complex t = R[c + (size_t)j * n];
            R[c + (size_t)j * n] = R[piv + (size_t)j * n];
            R[piv + (size_t)j * n] = t;
        }
        for (i = c + 1; i < n; i++) {
            double complex f = M[i + (size_t)c * n] / M[c + (size_t)c * n];
            for (j = c + 1; j < n; j++)
                M[i + (size_t)j * n] -= f * M[c + (size_t)j * n];
            for (j = 0; j < m; j++)
                R[i + (size_t)j * n] -= f * R[c + (size_t)j * n];
        }
    }
    for (j = 0; j < m; j++)
        for (i = n - 1; i >= 0; i--) {
            double complex s = R[i + (size_t)j * n];
            for (l = i + 1; l < n; l++)
                s -= M[i + (size_t)l * n] * R[l + (size_t)j * n];
            R[i + (size_t)j * n] = s / M[i + (size_t)i * n];
        }
    return 1;
}

/* G = C X + D + s D1 with X = (sI - A)^-1 B already in X. */
static void assemble_response(const td_controller *k, const double complex *X, double complex s, double *re, double *im)
{
    int p = k->outputs, m = k->inputs, n = k->n, i, j, l;
    for (j = 0; j < m; j++)
        for (i = 0; i < p; i++) {
            double complex g = k->D[i + (size_t)j * p];
            if (k->sample_rate == 0.0)
                g += s * k->D1[i + (size_t)j * p];
            for (l = 0; l < n; l++)
                g += k->C[i + (size_t)l * p] * X[l + (size_t)j * n];
            re[i + (size_t)j * p] = creal(g);
            im[i + (size_t)j * p] = cimag(g);
        }
}

td_status td_controller_frequency_response(const td_controller *k, double f, double *re, double *im, td_error *err)
{
    double complex s, *M;
    double w = 2.0 * TD_PI * f;
    int n, i, j, ok;
    if (!k || !re || !im)
        return td_error_set(err, TD_ERR_INVALID, "frequency_response: NULL argument");
    if (!isfinite(f))
        return td_error_set(err, TD_ERR_INVALID, "frequency_response: frequency: must be finite (got %g)", f);
    n = k->n;
    s = k->sample_rate > 0.0 ? cexp(I * (w / k->sample_rate)) : I * w;
    M = malloc(((size_t)n * n + (size_t)n * k->inputs + 1) * sizeof *M);
    if (!M)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in a frequency response");
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            M[i + (size_t)j * n] = (i == j ? s : 0.0) - k->A[i + (size_t)j * n];
    for (i = 0; i < n * k->inputs; i++)
        M[(size_t)n * n + i] = k->B[i];
    ok = complex_solve(M, M + (size_t)n * n, n, k->inputs);
    if (ok)
        assemble_response(k, M + (size_t)n * n, s, re, im);
    free(M);
    if (!ok)
        return td_error_set(err, TD_ERR_NUMERIC, "frequency_response: %g Hz is a pole of the law", f);
    return TD_OK;
}
