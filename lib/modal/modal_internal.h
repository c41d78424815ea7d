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

/* Where assembled entries go: a dense matrix (dense != NULL) or a CXSparse triplet; entry (i, j)
 * lands in row row0 + i. ok drops to 0 when the triplet could not grow. */
typedef struct td_entry_sink {
    gsl_matrix *dense;
    cs_di *triplet;
    int row0;
    int ok;
} td_entry_sink;

void td_entry_add(td_entry_sink *k, int i, int j, double v);
/* k(i, col0 + j) += scale * S(i, j) */
void td_entry_add_matrix(td_entry_sink *k, const cs_di *S, int col0, double scale);

/* Right-hand blocks R = [-K_eff | -C_eff | B_w] (ndof rows, 2 ndof + nfilter columns) of
 * M v' = R z, as state_space.c describes them. */
void td_state_space_rhs_blocks(const td_system *sys, double omega, td_entry_sink *R);
/* Filter rows w' = rate_x xs + rate_v vs + rate_w w (rows 2 ndof + state of the state vector). */
void td_state_space_filter_rows(const td_system *sys, td_entry_sink *A);
/* L = the Cholesky factor of M (ndof x ndof); TD_ERR_NUMERIC when M is not positive definite (the
 * first-order form needs M^-1, and every steady response refuses such an M alike). */
td_status td_state_space_factor_mass(const td_system *sys, gsl_matrix *L, td_error *err);
/* A zero LU pivot (or a non-finite one) of a complex LU (lib/modal/harmonic.c): i W I - A, or its
 * second-order form, is singular. */
int td_complex_lu_singular(const gsl_matrix_complex *LU);
/* TD_ERR_NUMERIC: i W is an eigenvalue of the system (an undamped resonance), into err. */
td_status td_resonance_error(td_error *err, double W);
/* TD_ERR_INVALID naming the first plug-in controller of sys that drives its axes (touchdown/plugin.h:
 * no linear law to analyse; one standing by for a recovery pair is left out, as a linear one is);
 * TD_OK when there is none. Every analysis of the closed loop asks this first. */
td_status td_system_refuse_plugins(const td_system *sys, td_error *err);
/* TD_OK when the first-order form above can hold sys: no plug-in (td_system_refuse_plugins) and
 * every linear controller continuous (a sampled one has no state here); TD_ERR_INVALID naming the
 * first sampled one otherwise. */
td_status td_state_space_supported(const td_system *sys, td_error *err);

/* Build the state space of `sys` at speed `omega`; on failure *ss is left empty (freed). */
td_status td_state_space_build(const td_system *sys, double omega, td_state_space *ss, td_error *err);
/* The same first-order form with the sampled controllers left out: their axes' held currents are
 * inputs (sampled.c closes that loop at the samples). */
td_status td_state_space_build_plant(const td_system *sys, double omega, td_state_space *ss, td_error *err);
/* 1 if sys has a sampled controller. */
int td_system_has_sampled_law(const td_system *sys);
/* The closed loop of the plant (td_state_space_build_plant) and the sampled controllers over one
 * sample period, z[k+1] = P z[k] with z = [plant state; sampled controllers' states] (N x N, new,
 * *P; *rate the common sample rate, Hz); TD_ERR_INVALID when the rates differ. */
td_status td_sampled_closed_loop(const td_system *sys, double omega, gsl_matrix **P, double *rate, td_error *err);
/* Column of the plant's input matrix (length ss->n, every entry set) for a held current of 1 A on
 * AMB axis a: the rate of its amplifier lag (tau > 0) or its force over M, through the AMB law of
 * model/amb.c (td_amb_axis_current_command). */
td_status td_sampled_current_column(const td_state_space *ss, const td_amb_axis *a, double *col, td_error *err);
/* The zero-order hold of x' = A x + Bu u over one sample, 1/rate s (A n x n, Bu n x nu, column-major):
 * Phi = exp(A T) (n x n) and Gamma = (integral of exp(A s) ds over [0, T]) Bu (n x nu), column-major,
 * by SLICOT MB05ND (td_slicot_expm). */
td_status td_sampled_hold(int n, double rate, const double *A, const double *Bu, int nu, double *Phi, double *Gamma,
                          td_error *err);
void td_state_space_free(td_state_space *ss);

/* Load term of a mechanical force f (length ndof): out[ndof .. 2 ndof) = M^-1 f, the rest 0. */
td_status td_state_space_load(const td_state_space *ss, const double *f, double *out, td_error *err);

/* Complex nodal unbalance forces at speed omega: F_x = U omega^2 e^{i p}, F_y = -i U omega^2 e^{i p}
 * (so that Re(F e^{i omega t}) is the force of touchdown/model.h). fre, fim have ndof entries. */
td_status td_unbalance_forces(const td_system *sys, double omega, const td_unbalance *u, int n_u, double *fre,
                              double *fim, td_error *err);

/* A new td_harmonic (touchdown/modal.h) of the state re + i im (n entries each) at speed omega, the
 * nodes' displacements expanded from its first ndof rows (lib/modal/harmonic.c). */
td_status td_harmonic_from_state(const td_system *sys, double omega, int n, const double *re, const double *im,
                                 td_harmonic **out, td_error *err);

/* The synchronous unbalance response by the second-order (dynamic-stiffness) solve of
 * lib/modal/synchronous.c: td_harmonic_compute's response, for the speeds of the API 617 sweep (its
 * cost and accuracy: docs/api617.md). The solver keeps sys (not owned) and its speed-independent matrices;
 * _create refuses what td_state_space_build refuses (plug-in or sampled controllers). */
typedef struct td_synchronous td_synchronous;
td_status td_synchronous_create(const td_system *sys, td_synchronous **out, td_error *err);
void td_synchronous_free(td_synchronous **s);
/* As td_harmonic_compute(sys, omega, u, n_u, out, err), with the same errors (TD_ERR_NUMERIC: i omega
 * is an eigenvalue of the system, or M is not positive definite). */
td_status td_synchronous_response(td_synchronous *s, double omega, const td_unbalance *u, int n_u, td_harmonic **out,
                                  td_error *err);

/* Sorted oscillatory modes and mode shapes of a solved analysis (lib/modal/eigen.c). */
struct td_modal {
    double omega;
    int nnodes;
    int n_modes;
    td_mode *modes;
    double *shapes; /* per mode: 4 nnodes doubles, x_re[nnodes], x_im, y_re, y_im */
    int n_real;
    double *real;          /* real eigenvalues, descending */
    int n_rounding;        /* zero roots left out, rounding of zero (|s| <= rounding_bound) */
    double rounding_bound; /* 1/s: TD_MODAL_ROUNDOFF_ROOT times the spectral radius */
    double max_real;
    int n_computed;        /* eigenvalues the solver computed (the state count for a full solve) */
    double complete_below; /* every vibration mode with omega_d below this is listed (INFINITY: all) */
    double sample_rate;    /* Hz: a sampled loop's (its roots are s = ln(mu) rate); 0 for a continuous system */
};

/* Sort and store eigenvalues and their eigenvectors (columns of evec, state rows) into a new
 * td_modal (a full one: n_computed = eval->size, complete_below = INFINITY). */
td_status td_modal_collect(const gsl_vector_complex *eval, gsl_matrix_complex *evec, int nnodes, double omega,
                           td_modal **out, td_error *err);

/* td_modal_collect for the eigenvectors of `sys`: a reduced system's are expanded to the nodes
 * first (q_phys = T q), so the shapes cover every node. */
td_status td_modal_collect_system(const gsl_vector_complex *eval, gsl_matrix_complex *evec, const td_system *sys,
                                  double omega, td_modal **out, td_error *err);

/* Systems with at most this many states are always solved in full by the dense solver (the same
 * results as td_modal_solve); larger ones by shift-invert Arnoldi (lib/modal/partial.c). */
#define TD_MODAL_DENSE_MAX_STATES 240

/* The partial analysis of td_modal_solve_lowest with a second demand: every vibration mode with
 * omega_d <= wmax is listed (wmax <= 0: no such demand). force_sparse = 1 takes the Arnoldi path
 * whatever the size (tests compare it with the dense solve). */
td_status td_modal_lowest(const td_system *sys, double omega, int count, double wmax, int force_sparse, td_modal **out,
                          td_error *err);

/* The optimal assignment (lib/modal/assign.c, Hungarian algorithm): row i of the n x m cost matrix
 * (row-major, n <= m, every entry finite) to column row_to_col[i], each column used at most once,
 * with the least sum of costs. Errors: TD_ERR_INVALID, TD_ERR_NOMEM. */
td_status td_assign_min_cost(const double *cost, int n, int m, int *row_to_col, td_error *err);

/* Modal Assurance Criterion of two complex nodal shapes a, b (each 4 nn doubles laid out as
 * td_modal's: x_re, x_im, y_re, y_im): |a^H b|^2 / ((a^H a)(b^H b)) in [0, 1] (lib/modal/campbell.c);
 * 0 when either shape is zero. */
double td_shape_mac(const double *a, const double *b, int nn);

/* Switch GSL's abort-on-error handler off (idempotent; see touchdown/modal.h). */
void td_modal_gsl_quiet(void);

#endif
