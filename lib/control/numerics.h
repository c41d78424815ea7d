/*
 * numerics.h - the matrix functions of control theory that lib/ uses, implemented in slicot.c with
 * SLICOT (the routine named in each comment). lib/control uses them, and so may the analyses.
 */
#ifndef TD_CONTROL_NUMERICS_H
#define TD_CONTROL_NUMERICS_H

#include "touchdown/error.h"

/* Matrices are column-major with leading dimension = their row count (n for A and
 * B, p for C and D). Each returns TD_OK, TD_ERR_NOMEM or TD_ERR_NUMERIC with a message naming
 * the routine. */

/* AB04MD, TYPE = 'C': the continuous (A, B, C, D) becomes, in place, the discrete system of the
 * bilinear map s = beta (z - 1)/(z + 1) (alpha = 1). */
td_status td_slicot_bilinear(int n, int m, int p, double beta, double *A, double *B, double *C, double *D,
                             td_error *err);

/* MB05ND: EX = exp(A delta) and EXINT = the integral of exp(A s) ds over [0, delta] (n x n each),
 * computed on A balanced by a diagonal similarity (TB01ID) and transformed back, so that they are
 * those of A itself; with B, the zero-order hold over delta: Ad = EX, Bd = EXINT B. */
td_status td_slicot_expm(int n, double delta, const double *A, double *EX, double *EXINT, td_error *err);

/* TB01PD (JOB = 'M', EQUIL = 'S', rank tolerance 1e-10, slicot.c): removes the uncontrollable and unobservable states
 * of (A, B, C) in place; *nr is the remaining order, the leading nr x nr, nr x m and p x nr parts (re-packed with
 * leading dimensions nr, nr and p) hold the minimal realisation. */
td_status td_slicot_minimal(int n, int m, int p, double *A, double *B, double *C, int *nr, td_error *err);

/* TB01ID (JOB = 'A'): balances (A, B, C) in place by a diagonal similarity. */
td_status td_slicot_balance(int n, int m, int p, double *A, double *B, double *C, td_error *err);

#endif
