/*
 * control_internal.h - the realisation behind a td_controller (touchdown/controller.h) and the
 * helpers the files of lib/control share.
 */
#ifndef TD_CONTROL_INTERNAL_H
#define TD_CONTROL_INTERNAL_H

#include "touchdown/controller.h"
#include "util/error_internal.h" /* TD_PRINTF */

/* One state-space realisation (A, B, C, D, D1), every matrix column-major, all in one allocation
 * that follows the struct. Sign convention and meaning: touchdown/controller.h. */
struct td_controller {
    int n;              /* states */
    int inputs;         /* error signals e (m) */
    int outputs;        /* current commands i (A) */
    double *A;          /* n x n */
    double *B;          /* n x inputs */
    double *C;          /* outputs x n */
    double *D;          /* outputs x inputs */
    double *D1;         /* outputs x inputs, velocity feedthrough; all zero for a sampled law */
    double sample_rate; /* Hz; 0: continuous */
};

/* A zeroed controller of the given sizes and timing; NULL with err set when out of memory. */
td_controller *td_ctl_alloc(int n, int inputs, int outputs, double sample_rate, td_error *err);

/* 1 if any of the count values is nonzero. */
int td_ctl_any_nonzero(const double *v, int count);

/* 1 if all count values are finite (a NULL v with count 0 is fine). */
int td_ctl_all_finite(const double *v, int count);

/* TD_ERR_INVALID with the message "PART: FIELD: REASON" (printf-style REASON) and err->site naming
 * the part (a block, "tf", "discretise", ...; index -1: in no model) and the field (its member or
 * argument, as the header names it), so that a case reader can point at the key it read. */
td_status td_ctl_invalid(td_error *err, const char *part, const char *field, const char *fmt, ...) TD_PRINTF(4, 5);

/* td_ctl_invalid with "must be finite and > 0 (got V)" unless v is; returns the status. */
td_status td_ctl_check_positive(double v, const char *part, const char *field, td_error *err);

/* td_ctl_invalid unless v is a block's frequency, TD_CONTROLLER_FREQUENCY_MIN to _MAX Hz (or 0,
 * none, when zero_ok); returns the status. */
td_status td_ctl_check_frequency(double v, int zero_ok, const char *part, const char *field, td_error *err);

/* k itself when every entry of its realisation is finite; else NULL (k freed) with TD_ERR_INVALID
 * naming `part`: numbers at the ends of the double range overflowed in the arithmetic that built
 * it, and a law of inf or NaN must not reach the analyses (their eigen-solver did not return on
 * one). A NULL k (a failure already set) passes through. */
td_controller *td_ctl_finite(td_controller *k, const char *part, td_error *err);

/* The proper or improper-by-one SISO law num/den, both in descending powers of s (or of z for a
 * sampled law: then deg num <= deg den), realised in controllable canonical form. Leading zeros
 * of num are ignored; den[0] != 0. `who` names the caller in messages. */
td_controller *td_ctl_from_polynomials(const double *num, int num_len, const double *den, int den_len,
                                       double sample_rate, const char *who, td_error *err);

/* Z = X Y for column-major X (rows x inner) and Y (inner x cols); Z (rows x cols) is overwritten. */
void td_ctl_matmul(const double *X, int rows, int inner, const double *Y, int cols, double *Z);

#endif
