/*
 * touchdown/system.h - the assembled linear rotor: sparse M, K, C, G and the AMB axes.
 *
 * A td_system is a pure function of a td_model (speed enters only as Omega G). The equations
 * it represents, with the DOF ordering of touchdown/dofs.h:
 *
 *   M q'' + (C + Omega G) q' + K q = f_unbalance(t) + f_gravity + f_amb + f_contact
 *
 * K holds the shaft and the plain bearings; AMB forces (negative stiffness, PD current control,
 * force lag, optional saturation) are kept apart because they may saturate or be switched off
 * during a run. C holds Rayleigh damping (alpha M_shaft + beta K_shaft) and plain-bearing damping.
 */
#ifndef TOUCHDOWN_SYSTEM_H
#define TOUCHDOWN_SYSTEM_H

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct td_system td_system;

/** Which assembled matrix. */
typedef enum td_matrix_kind {
    TD_MATRIX_MASS = 0,      /**< M, kg (and kg m^2 on rotations) */
    TD_MATRIX_STIFFNESS = 1, /**< K: shaft and plain bearings, AMBs excluded */
    TD_MATRIX_DAMPING = 2,   /**< C: Rayleigh and plain bearings */
    TD_MATRIX_GYROSCOPIC = 3 /**< G per unit speed (skew-symmetric) */
} td_matrix_kind;

/** Assemble the model (copied: the system does not borrow it). Validates the model first. */
TD_API td_status td_system_create(const td_model *model, td_system **out, td_error *err);
/** Free and set *sys to NULL; accepts NULL. */
TD_API void td_system_free(td_system **sys);
/** Number of mechanical DOFs (4 per node). */
TD_API int td_system_dof_count(const td_system *sys);
/** The model the system was assembled from (owned by the system). */
TD_API const td_model *td_system_model(const td_system *sys);
/** Copy one matrix into a dense column-major ndof x ndof array `out` (entry (i, j) at out[i + j*ndof]). */
TD_API td_status td_system_dense(const td_system *sys, td_matrix_kind which, double *out, td_error *err);
/** Nonzero count of one matrix. */
TD_API int td_system_nnz(const td_system *sys, td_matrix_kind which);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_SYSTEM_H */
