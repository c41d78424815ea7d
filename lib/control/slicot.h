/*
 * slicot.h - the SLICOT routines touchdown calls (SLICOT 5.0, Debian libslicot-dev, GPL-2+; a
 * Fortran 77 library that ships no C header), declared here once and called only from slicot.c,
 * whose wrappers own the workspaces and turn INFO into a td_status with a message.
 *
 * Fortran calling convention (gfortran >= 8): every argument by pointer, INTEGER a 4-byte int,
 * arrays column-major, and each CHARACTER argument adds a hidden size_t length at the end of the
 * argument list, in the order of the CHARACTER arguments.
 */
#ifndef TD_CONTROL_SLICOT_H
#define TD_CONTROL_SLICOT_H

#include "touchdown/error.h"

#include <stddef.h>

/* The Fortran routines (argument names as in the SLICOT documentation). */
void ab04md_(const char *type, const int *n, const int *m, const int *p, const double *alpha, const double *beta,
             double *a, const int *lda, double *b, const int *ldb, double *c, const int *ldc, double *d, const int *ldd,
             int *iwork, double *dwork, const int *ldwork, int *info, size_t type_len);
void mb05nd_(const int *n, const double *delta, const double *a, const int *lda, double *ex, const int *ldex,
             double *exint, const int *ldexin, const double *tol, int *iwork, double *dwork, const int *ldwork,
             int *info);
void tb01pd_(const char *job, const char *equil, const int *n, const int *m, const int *p, double *a, const int *lda,
             double *b, const int *ldb, double *c, const int *ldc, int *nr, const double *tol, int *iwork,
             double *dwork, const int *ldwork, int *info, size_t job_len, size_t equil_len);
void tb01id_(const char *job, const int *n, const int *m, const int *p, double *maxred, double *a, const int *lda,
             double *b, const int *ldb, double *c, const int *ldc, double *scale, int *info, size_t job_len);

/* The wrappers. Matrices are column-major with leading dimension = their row count (n for A and
 * B, p for C and D). Each returns TD_OK, TD_ERR_NOMEM or TD_ERR_NUMERIC with a message naming
 * the routine. */

/* AB04MD, TYPE = 'C': the continuous (A, B, C, D) becomes, in place, the discrete system of the
 * bilinear map s = beta (z - 1)/(z + 1) (alpha = 1). */
td_status td_slicot_bilinear(int n, int m, int p, double beta, double *A, double *B, double *C, double *D,
                             td_error *err);

/* MB05ND: EX = exp(A delta) and EXINT = the integral of exp(A s) ds over [0, delta] (n x n each). */
td_status td_slicot_expm(int n, double delta, const double *A, double *EX, double *EXINT, td_error *err);

/* TB01PD (JOB = 'M', EQUIL = 'S'): removes the uncontrollable and unobservable states of
 * (A, B, C) in place; *nr is the remaining order, the leading nr x nr, nr x m and p x nr parts
 * (re-packed with leading dimensions nr, nr and p) hold the minimal realisation. */
td_status td_slicot_minimal(int n, int m, int p, double *A, double *B, double *C, int *nr, td_error *err);

/* TB01ID (JOB = 'A'): balances (A, B, C) in place by a diagonal similarity. */
td_status td_slicot_balance(int n, int m, int p, double *A, double *B, double *C, td_error *err);

#endif
