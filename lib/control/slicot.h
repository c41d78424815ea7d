/*
 * slicot.h - the SLICOT routines touchdown calls (SLICOT 5.0, Debian libslicot-dev, GPL-2+; a
 * Fortran 77 library that ships no C header), declared here once and included only by slicot.c,
 * whose wrappers (numerics.h) own the workspaces and turn INFO into a td_status with a message.
 *
 * Fortran calling convention (gfortran >= 8): every argument by pointer, INTEGER a 4-byte int,
 * arrays column-major, and each CHARACTER argument adds a hidden size_t length at the end of the
 * argument list, in the order of the CHARACTER arguments.
 */
#ifndef TD_CONTROL_SLICOT_H
#define TD_CONTROL_SLICOT_H

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

#endif
