/*
 * Internals of the modal analysis: the dense first-order form of the contact-free system.
 * State layout z = [q; v; w] (touchdown/modal.h).
 */
#ifndef TD_MODAL_INTERNAL_H
#define TD_MODAL_INTERNAL_H

#include "model/system_internal.h"
#include "touchdown/modal.h"

#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

/* The first-order system at one speed, with the Cholesky factor of M kept for load vectors. */
typedef struct td_state_space {
    int ndof;      /* mechanical DOFs */
    int nfilter;   /* AMB filter states */
    int n;         /* 2 ndof + nfilter */
    double omega;  /* speed, rad/s */
    gsl_matrix *A; /* n x n */
    gsl_matrix *L; /* Cholesky factor of M (ndof x ndof) */
} td_state_space;

/* Build the state space of `sys` at speed `omega`; on failure *ss is left empty (freed). */
td_status td_state_space_build(const td_system *sys, double omega, td_state_space *ss, td_error *err);
void td_state_space_free(td_state_space *ss);

/* Load term of a mechanical force f (length ndof): out[ndof .. 2 ndof) = M^-1 f, the rest 0. */
td_status td_state_space_load(const td_state_space *ss, const double *f, double *out, td_error *err);

/* Complex nodal unbalance forces at speed omega: F_x = U omega^2 e^{i p}, F_y = -i U omega^2 e^{i p}
 * (so that Re(F e^{i omega t}) is the force of touchdown/model.h). fre, fim have ndof entries. */
td_status td_unbalance_forces(const td_system *sys, double omega, const td_unbalance *u, int n_u, double *fre,
                              double *fim, td_error *err);

/* Sorted oscillatory modes and mode shapes of a solved analysis (lib/modal/eigen.c). */
struct td_modal {
    double omega;
    int nnodes;
    int n_modes;
    td_mode *modes;
    double *shapes; /* per mode: 4 nnodes doubles, x_re[nnodes], x_im, y_re, y_im */
    int n_real;
    double *real; /* real eigenvalues, descending */
    double max_real;
};

/* Switch GSL's abort-on-error handler off (idempotent; see touchdown/modal.h). */
void td_modal_gsl_quiet(void);

#endif
