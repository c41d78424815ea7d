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
 *
 * Generalized coordinates. A model with a reduction cut-off (td_model_set_reduction) is assembled
 * as a Craig-Bampton reduced rotor (docs/theory.md, "Reduced rotor"): q = [q_b; eta] holds the four
 * physical DOFs of every boundary node (a node carrying a part), node by node, then the
 * fixed-interface modal coordinates eta; the physical displacements are q_phys = T q. Without a
 * reduction q is the physical vector of touchdown/dofs.h and T the identity. A compliant housing's
 * DOFs (touchdown/housing.h td_housing_body) come last: the rotor's coordinates stay relative to the
 * housing, so they move no node (T has zero columns for them). Every matrix, load
 * and state of the system, the modal analysis and the simulation is in q; td_system_node_dof and
 * td_system_expand are the one map between q and the nodes.
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
/** Number of generalized coordinates q: 4 per node for the full model, 4 per boundary node plus
 *  the fixed-interface modes kept for a reduced one; then a housing body's DOFs, last (2 or 4:
 *  touchdown/housing.h td_housing_body), which move no node relative to the housing. */
TD_API int td_system_dof_count(const td_system *sys);
/** Number of physical DOFs, 4 per node, whether reduced or not. */
TD_API int td_system_physical_dof_count(const td_system *sys);
/** 1 if the system is Craig-Bampton reduced, 0 for the full model. */
TD_API int td_system_is_reduced(const td_system *sys);
/** Number of fixed-interface modes kept by the reduction (0 for the full model). */
TD_API int td_system_mode_count(const td_system *sys);
/** Natural frequency (Hz) of fixed-interface mode i (0 <= i < td_system_mode_count), NAN otherwise. */
TD_API double td_system_mode_frequency(const td_system *sys, int i);
/**
 * Static corrections of the gravity load in the reduction basis (docs/theory.md, "Reduced rotor"):
 * one per stretch of interior nodes and plane that gravity loads, unless its kept modes already
 * hold its deflection; they are the last generalized coordinates, after the fixed-interface modes.
 * 0 for the full model or without gravity.
 */
TD_API int td_system_static_correction_count(const td_system *sys);
/** Index in q of DOF `offset` (a td_dof_offset) of `node`: TD_DOF(node, offset) for the full model;
 *  -1 when the node is interior to a reduced rotor (then only td_system_expand gives it), or when
 *  node or offset is out of range. */
TD_API int td_system_node_dof(const td_system *sys, int node, int offset);
/** Physical displacements q_phys = T q (td_system_physical_dof_count long, dofs.h order) from the
 *  generalized q (td_system_dof_count long); both borrowed. A plain copy for the full model. */
TD_API td_status td_system_expand(const td_system *sys, const double *q, double *q_phys, td_error *err);
/** One physical displacement, DOF `offset` of `node`, from the generalized q: q[TD_DOF(node, offset)]
 *  for the full model, row TD_DOF(node, offset) of T times q for a reduced one (td_system_expand of
 *  one DOF, for samplers that need a few nodes); NAN when node or offset is out of range. */
TD_API double td_system_node_displacement(const td_system *sys, const double *q, int node, int offset);
/** The model the system was assembled from (owned by the system). */
TD_API const td_model *td_system_model(const td_system *sys);
/** Copy one matrix (in the generalized coordinates) into a dense column-major ndof x ndof array `out` (entry (i, j) at
 * out[i + j*ndof]). */
TD_API td_status td_system_dense(const td_system *sys, td_matrix_kind which, double *out, td_error *err);
/** Nonzero count of one matrix. */
TD_API int td_system_nnz(const td_system *sys, td_matrix_kind which);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_SYSTEM_H */
