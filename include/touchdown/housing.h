/*
 * touchdown/housing.h - the prescribed motion of the housing (base motion and shock).
 *
 * The rotor's and the races' coordinates stay relative to the housing (touchdown/dofs.h): the AMB
 * sensors, the actuators, the retainers and the bearings move with it. The housing's motion enters
 * the equations of motion only as inertial (d'Alembert) loads in the housing's frame, as gravity
 * does (docs/theory.md, "Base motion"):
 *
 *   M q'' + (C + Omega G) q' + K q = f - M R a(t) - M T alpha(t) - Omega G T w(t)
 *
 * a = (a_x, a_y) the housing's translational acceleration, w = (w_x, w_y) its rotation rate about
 * x and y (pitch and yaw of a rotor whose axis lies fore-aft), alpha = dw/dt; R a unit rigid
 * translation, T a unit rigid rotation about the axial point z_ref (td_model_housing_reference).
 * Units: SI (m/s^2, rad/s); 1 g = 9.80665 m/s^2 (the standard acceleration of gravity).
 */
#ifndef TOUCHDOWN_HOUSING_H
#define TOUCHDOWN_HOUSING_H

#include "touchdown/error.h"
#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* the model (touchdown/model.h, which includes this header) */
struct td_model;

/** The shape of a pulse p(tau), tau = t - start in [0, duration), zero before; after it 0, except
 *  the ramp, which holds its amplitude. A the amplitude, T the duration. */
typedef enum td_pulse_shape {
    TD_PULSE_HALF_SINE = 0, /**< A sin(pi tau / T) */
    TD_PULSE_TRIANGLE = 1,  /**< symmetric: rises to A at T/2, back to 0 at T */
    TD_PULSE_SAWTOOTH = 2,  /**< final peak: A tau / T, then 0 */
    TD_PULSE_VERSINE = 3,   /**< haversine: A (1 - cos(2 pi tau / T)) / 2 */
    TD_PULSE_RAMP = 4       /**< A tau / T, then held at A */
} td_pulse_shape;

/** A shock (the housing's acceleration, amplitude in m/s^2, direction in the x-y plane) or a
 *  rotation (its rotation rate, amplitude in rad/s, direction = the axis: (1, 0) about x, (0, 1)
 *  about y). The direction is normalised when added (it must not be zero). */
typedef struct td_housing_pulse {
    td_pulse_shape shape;
    double amplitude;    /**< > 0 */
    double duration;     /**< s, > 0 */
    double start;        /**< s, >= 0 */
    double direction[2]; /**< finite, not [0, 0] */
} td_housing_pulse;

/** Add a translational acceleration pulse of the housing (the pulses and the history are summed).
 *  A fault names part "shock", its index and the field. */
TD_API td_status td_model_add_housing_shock(struct td_model *m, const td_housing_pulse *p, td_error *err);
/** Add a rotation-rate profile of the housing (summed). A fault names part "rotation". Not a
 *  sawtooth: a rate that drops at once is an angular impulse (its rate change a delta). */
TD_API td_status td_model_add_housing_rotation(struct td_model *m, const td_housing_pulse *p, td_error *err);
/** The housing's acceleration as a piecewise-linear history through the n >= 2 points
 *  (t[i], ax[i], ay[i]) (s, m/s^2), zero before t[0] and after t[n - 1]; t[0] >= 0, t increasing,
 *  all finite. Copies; replaces any history set before. A fault names part "history", the point's
 *  index and the field ("time", "x" or "y"). */
TD_API td_status td_model_set_housing_history(struct td_model *m, int n, const double *t, const double *ax,
                                              const double *ay, td_error *err);
/** The axial point z_ref (m, finite) the housing rotates about; default: the rotor's centre of mass
 *  (td_model_mass_centre, from the shaft and the discs). A fault names part "housing", field "reference". */
TD_API td_status td_model_set_housing_reference(struct td_model *m, double z, td_error *err);
/** 1 if the model has any shock, history or rotation of its housing, else 0. */
TD_API int td_model_has_housing_motion(const struct td_model *m);

/** The prescribed motion at one time, in the housing's frame. */
typedef struct td_housing_motion {
    double acceleration[2]; /**< m/s^2 */
    double velocity[2];     /**< m/s */
    double displacement[2]; /**< m */
    double rate[2];         /**< rad/s, about x and y */
    double rate_change[2];  /**< rad/s^2 (at a kink, the slope after it) */
    double angle[2];        /**< rad */
} td_housing_motion;

/** The prescribed motion at t (s): the closed-form integrals of the pulses and the exact integrals of
 *  the piecewise-linear history, from rest at t = 0. All zero for a model without housing motion. */
TD_API void td_model_housing_motion_at(const struct td_model *m, double t, td_housing_motion *out);
/** z_ref, m: the one set, else the rotor's centre of mass. */
TD_API double td_model_housing_reference(const struct td_model *m);

/** The counts and entries of the housing's motion, for embedders and writers. */
TD_API int td_model_housing_shock_count(const struct td_model *m);
TD_API int td_model_housing_rotation_count(const struct td_model *m);
TD_API td_status td_model_get_housing_shock(const struct td_model *m, int i, td_housing_pulse *out);
TD_API td_status td_model_get_housing_rotation(const struct td_model *m, int i, td_housing_pulse *out);
/** The history's point count (0: none). */
TD_API int td_model_housing_history_count(const struct td_model *m);
/** The first time after t (s) where the motion has a kink the integrator must stop at: a pulse's
 *  start or end (a ramp's: the end of its rise; a triangle's peak too) or the history's first or last time (not its
 * inner points); INFINITY if none. */
TD_API double td_model_housing_next_kink(const struct td_model *m, double t);

/* housing body */
/**
 * A compliant housing (docs/theory.md, "Compliant housing"): the housing as a rigid body on
 * resilient mounts, as machines on shock mounts are. The rotor's and the races' coordinates stay
 * relative to the housing (AMBs, sensors, gaps and controllers are unchanged); the body's own DOFs,
 * relative to the base, are appended after the rotor's generalized coordinates (touchdown/system.h):
 * x, y of its centre of mass, then, with an inertia, its tilts theta (about x) and phi (about y)
 * with touchdown/dofs.h's conventions. Without an inertia the body only translates: its tilt is held
 * by the base (a guided mounting, or mounts far stiffer in tilt than in translation), and the
 * mounts' positions do not matter. `mass` is everything that moves with the housing (the stator,
 * the retainers; a race on a mount is a body of its own, coupled to the body as the rotor is); the
 * rotor's mass adds to it through the coupled mass matrix.
 */
#define TD_HOUSING_MAX_MOUNTS 16 /**< most mounts of a housing body (mounts at one position add up) */

/** One resilient mount, isotropic in x and y. */
typedef struct td_housing_mount {
    double position;  /**< m, axial z of the mount, finite */
    double stiffness; /**< N/m, in each of x and y, >= 0 */
    double damping;   /**< N s/m, in each of x and y, >= 0 */
} td_housing_mount;

/** The housing as a rigid body on its mounts. */
typedef struct td_housing_body {
    double mass;     /**< kg, > 0 */
    double inertia;  /**< kg m^2, transverse, about the centre of mass, >= 0; 0: the body only translates */
    double centre;   /**< m, axial z of the centre of mass, finite */
    int mount_count; /**< 1..TD_HOUSING_MAX_MOUNTS */
    td_housing_mount mounts[TD_HOUSING_MAX_MOUNTS];
} td_housing_body;

/** Give the model a housing body (copied), replacing any it had. The mounts must hold the body:
 *  a total stiffness > 0, and with an inertia mounts at two positions at least. Not with a free
 *  spin (td_spin.free): td_model_validate refuses that. Errors: TD_ERR_INVALID (the field named). */
TD_API td_status td_model_set_housing_body(struct td_model *m, const td_housing_body *b, td_error *err);
/** 1 if the model has a housing body (*out filled, out may be NULL), else 0. */
TD_API int td_model_get_housing_body(const struct td_model *m, td_housing_body *out);
/** The body's DOFs: 0 (none), 2 (translating) or 4 (with an inertia). */
TD_API int td_model_housing_body_dofs(const struct td_model *m);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_HOUSING_H */
