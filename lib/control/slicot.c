/*
 * slicot.c - the one file that calls SLICOT (its declarations and conventions: slicot.h) and the
 * wrappers of numerics.h.
 */
#include "control/slicot.h"
#include "control/numerics.h"

#include "util/error_internal.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

static int imax(int a, int b)
{
    return a > b ? a : b;
}

static td_status info_error(td_error *err, const char *routine, const char *what, int info)
{
    if (info < 0)
        return td_error_set(err, TD_ERR_NUMERIC, "SLICOT %s: argument %d had an illegal value", routine, -info);
    return td_error_set(err, TD_ERR_NUMERIC, "SLICOT %s: %s (INFO = %d)", routine, what, info);
}

td_status td_slicot_bilinear(int n, int m, int p, double beta, double *A, double *B, double *C, double *D,
                             td_error *err)
{
    const double alpha = 1.0;
    int lda = imax(1, n), ldc = imax(1, p), ldwork = imax(1, 64 * n), info = 0;
    int *iwork = malloc((size_t)imax(1, n) * sizeof *iwork);
    double *dwork = malloc((size_t)ldwork * sizeof *dwork);
    if (!iwork || !dwork) {
        free(iwork);
        free(dwork);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in SLICOT AB04MD's workspace");
    }
    ab04md_("C", &n, &m, &p, &alpha, &beta, A, &lda, B, &lda, C, &ldc, D, &ldc, iwork, dwork, &ldwork, &info, 1);
    free(iwork);
    free(dwork);
    if (info != 0)
        return info_error(err, "AB04MD", "beta I - A is singular: the law has a pole at s = 2 rate", info);
    return TD_OK;
}

/* A balanced copy of A (TB01ID, JOB = 'N': A alone, by a diagonal similarity inv(S) A S); scale
 * receives S. */
static td_status balance_matrix(int n, const double *A, double *Ab, double *scale, td_error *err)
{
    double maxred = 0.0, dummy = 0.0;
    int lda = n > 0 ? n : 1, zero = 0, one = 1, info = 0;
    memcpy(Ab, A, (size_t)n * n * sizeof *A);
    tb01id_("N", &n, &zero, &zero, &maxred, Ab, &lda, &dummy, &one, &dummy, &one, scale, &info, 1);
    return info == 0 ? TD_OK : info_error(err, "TB01ID", "failed", info);
}

/* MB05ND on the balanced A, then back: exp(A d) = S exp(inv(S) A S d) inv(S), and so for the
 * integral. Without the balancing MB05ND lost up to 1e-10 (relative) on the realisations of
 * chained blocks (entries from 1 to 1e8) against scipy's expm (tests/validation/control). TOL is
 * MB05ND's requested relative error of its Pade approximant: machine precision. */
td_status td_slicot_expm(int n, double delta, const double *A, double *EX, double *EXINT, td_error *err)
{
    const double tol = DBL_EPSILON;
    int ld = imax(1, n), ldwork = imax(1, 2 * n * n + n), info = 0, i, j;
    int *iwork = malloc((size_t)ld * sizeof *iwork);
    double *dwork = malloc(((size_t)ldwork + (size_t)n * n + (size_t)n + 1) * sizeof *dwork), *Ab, *scale;
    td_status st;
    if (!iwork || !dwork) {
        free(iwork);
        free(dwork);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in SLICOT MB05ND's workspace");
    }
    Ab = dwork + ldwork;
    scale = Ab + (size_t)n * n;
    st = balance_matrix(n, A, Ab, scale, err);
    if (st == TD_OK)
        mb05nd_(&n, &delta, Ab, &ld, EX, &ld, EXINT, &ld, &tol, iwork, dwork, &ldwork, &info);
    for (j = 0; j < n && st == TD_OK && info == 0; j++)
        for (i = 0; i < n; i++) {
            EX[i + (size_t)j * n] *= scale[i] / scale[j];
            EXINT[i + (size_t)j * n] *= scale[i] / scale[j];
        }
    free(iwork);
    free(dwork);
    if (st == TD_OK && info != 0)
        return info_error(err, "MB05ND",
                          info == n + 1 ? "delta times the norm of A is too large" : "the Pade denominator is singular",
                          info);
    return st;
}

/* Copies the rows x cols matrix X (ldx) into Y (ldy). */
static void copy_block(const double *X, int ldx, double *Y, int ldy, int rows, int cols)
{
    int i, j;
    for (j = 0; j < cols; j++)
        for (i = 0; i < rows; i++)
            Y[i + (size_t)j * ldy] = X[i + (size_t)j * ldx];
}

/* TB01PD's rank decisions: a block whose estimated reciprocal condition number is below this is
 * rank deficient. The default (N^2 eps) is too tight for laws built in series from blocks of very
 * different gains: the duplicated series of a PID (kp 1e4, kint 2e5, kd 40, 2 kHz filter) and a
 * notch, one input feeding both copies, kept all 8 states at the default and 4 (the right
 * number) from 1e-12 to 1e-8 with EQUIL = 'S' (tests/test_controller.c). */
#define TD_SLICOT_RANK_TOL 1e-10

/* TB01PD uses B as n x max(m, p) and C as max(m, p) x n workspace: both go through padded copies. */
td_status td_slicot_minimal(int n, int m, int p, double *A, double *B, double *C, int *nr, td_error *err)
{
    const double tol = TD_SLICOT_RANK_TOL;
    int mp = imax(m, p), lda = imax(1, n), ldc = imax(1, mp), info = 0, k = 0;
    int ldwork = imax(1, n + imax(n, 3 * mp)) + 64 * imax(1, n);
    double *b = calloc((size_t)lda * mp + (size_t)ldc * lda + (size_t)ldwork, sizeof *b), *c, *dwork;
    int *iwork = malloc((size_t)(n + mp + 1) * sizeof *iwork);
    if (!b || !iwork) {
        free(b);
        free(iwork);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in SLICOT TB01PD's workspace");
    }
    c = b + (size_t)lda * mp;
    dwork = c + (size_t)ldc * lda;
    copy_block(B, n, b, lda, n, m);
    copy_block(C, p, c, ldc, p, n);
    tb01pd_("M", "S", &n, &m, &p, A, &lda, b, &lda, c, &ldc, &k, &tol, iwork, dwork, &ldwork, &info, 1, 1);
    if (info == 0) {
        copy_block(A, lda, A, imax(1, k), k, k); /* re-pack in place: each entry moves to a lower index */
        copy_block(b, lda, B, imax(1, k), k, m);
        copy_block(c, ldc, C, p, p, k);
        *nr = k;
    }
    free(b);
    free(iwork);
    return info == 0 ? TD_OK : info_error(err, "TB01PD", "failed", info);
}

td_status td_slicot_balance(int n, int m, int p, double *A, double *B, double *C, td_error *err)
{
    double maxred = 0.0, *scale = malloc((size_t)imax(1, n) * sizeof *scale);
    int lda = imax(1, n), ldc = imax(1, p), info = 0;
    if (!scale)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory in SLICOT TB01ID's workspace");
    tb01id_("A", &n, &m, &p, &maxred, A, &lda, B, &lda, C, &ldc, scale, &info, 1);
    free(scale);
    return info == 0 ? TD_OK : info_error(err, "TB01ID", "failed", info);
}
