/*
 * touchdown/sim.h - time-domain simulation through retainer contact on SUNDIALS IDA.
 *
 * A td_sim integrates the rotor of a td_model from t0, steps to output times or to the next
 * event, and lets the caller read state and contact forces and change the machine between
 * steps (unbalance, speed, AMB forces: the AMBs may be driven by the caller's own sampled
 * controller instead of the built-in PD law). Two simulations never share state.
 * Units, DOF ordering and sign conventions: touchdown/dofs.h.
 */
#ifndef TOUCHDOWN_SIM_H
#define TOUCHDOWN_SIM_H

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/model.h"
#include "touchdown/options.h"
#include "touchdown/records.h"
#include "touchdown/system.h"

#include <signal.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct td_sim td_sim;

/** How an AMB is driven. */
typedef enum td_amb_mode {
    TD_AMB_PD = 0,       /**< built-in PD current control with force lag (the default) */
    TD_AMB_EXTERNAL = 1, /**< control force held at the value set by td_sim_set_amb_control (zero-order hold) */
    TD_AMB_OFF = 2,      /**< failed: no force at all */
    TD_AMB_CURRENT = 3   /**< current command held at the value set by td_sim_set_amb_current, through the
                              amplifier (its lag, slew limit and clip) exactly as a sampled controller's */
} td_amb_mode;

/** Create a simulation of `model` (copied) with `options` (copied; NULL: defaults).
 *  Sets the start state (steady orbit or rest, touchdown/options.h td_start) at options->t0.
 *  An orbit start (TD_START_ORBIT) of a contact-free system found unstable (checked up to
 *  TD_SIM_STABILITY_MAX_STATES states), or one outside a clearance with constraint contact, fails
 *  with TD_ERR_INVALID; TD_START_AUTO starts those at rest instead (td_sim_start_info_get). */
TD_API td_status td_sim_create(const td_model *model, const td_sim_options *options, td_sim **out, td_error *err);
/** td_sim_create that also reads `cancel` (may be NULL) between the stages of its set-up (system
 *  build, stability check, start-state solve): nonzero stops it with TD_ERR_INTERRUPTED. */
TD_API td_status td_sim_create_cancellable(const td_model *model, const td_sim_options *options,
                                           volatile sig_atomic_t *cancel, td_sim **out, td_error *err);

/** Largest first-order state count (touchdown/modal.h) whose stability td_sim_create checks; a
 *  bigger model is not checked (its dense eigen-solve costs ~ seconds to minutes). */
#define TD_SIM_STABILITY_MAX_STATES 800

/** Stability of the contact-free closed loop (AMB filter states included) at the start speed. */
typedef enum td_stability {
    TD_STABILITY_UNCHECKED = -1, /**< not checked: more than TD_SIM_STABILITY_MAX_STATES states, a
                                  *   plug-in controller (no linear law), or no eigen-solution; the
                                  *   start info's `unchecked` says which */
    TD_STABILITY_STABLE = 0,     /**< every eigenvalue decays or is undamped (marginal) */
    TD_STABILITY_UNSTABLE = 1    /**< some eigenvalue grows (real part above round-off) */
} td_stability;

/** How the start state was chosen. */
typedef struct td_sim_start_info {
    td_start requested;     /**< the option */
    td_start used;          /**< TD_START_ORBIT or TD_START_REST */
    td_stability stability; /**< of the contact-free system at the start speed */
    double max_real_part;   /**< rightmost eigenvalue's real part, 1/s (NAN when unchecked) */
    char reason[256];       /**< why TD_START_AUTO fell back to rest ("" otherwise) */
    char unchecked[256];    /**< why the stability is TD_STABILITY_UNCHECKED ("" otherwise) */
} td_sim_start_info;

/** Copy the start-state choice into *out. TD_ERR_INVALID on NULL arguments. */
TD_API td_status td_sim_start_info_get(const td_sim *sim, td_sim_start_info *out);
/** Free and set *sim to NULL; accepts NULL. */
TD_API void td_sim_free(td_sim **sim);
/** Message of the last failure of this simulation, the one the failing call also put in its
 *  td_error. td_sim_step and the td_sim_set_* calls clear it when they begin, so it is "" after
 *  one of them succeeds and never a leftover of an earlier failure. Owned by the sim. */
TD_API const char *td_sim_errmsg(const td_sim *sim);

/** Advance towards `tout` (> current time). Returns TD_OK having reached tout, TD_EVENT having
 *  stopped at an event (read it with td_sim_last_event; call again to go on), or a negative
 *  status on failure, described in *err (the state stays at the last good time). *t_reached may
 *  be NULL. */
TD_API td_status td_sim_step(td_sim *sim, double tout, double *t_reached, td_error *err);
/** Borrow `flag` (NULL: clear) as an interrupt request: td_sim_step reads it before every
 *  internal integrator step and, when it is nonzero, returns TD_ERR_INTERRUPTED at once with the
 *  state at the last good step (td_sim_time, td_sim_get_state etc. read it; stepping may go on
 *  once the flag is cleared). The flag must outlive the sim or be cleared first. */
TD_API td_status td_sim_set_interrupt(td_sim *sim, volatile sig_atomic_t *flag);
/** Current time, s. */
TD_API double td_sim_time(const td_sim *sim);
/** The event that stopped the last td_sim_step with TD_EVENT. */
TD_API td_status td_sim_last_event(const td_sim *sim, td_event *ev);

/** Number of the rotor's generalized coordinates (touchdown/system.h: 4 per node for the full
 *  model, then a housing body's DOFs; the races' states are read with td_sim_retainer_state). */
TD_API int td_sim_dof_count(const td_sim *sim);
/** Copy displacements q and velocities v (each td_sim_dof_count long; either may be NULL), in the
 *  generalized coordinates of td_sim_system (td_system_expand gives the nodes' displacements). */
TD_API td_status td_sim_get_state(const td_sim *sim, double *q, double *v);
/** The assembled system the simulation integrates (borrowed, valid until td_sim_free); NULL for a
 *  NULL sim. */
TD_API const td_system *td_sim_system(const td_sim *sim);
TD_API td_status td_sim_retainer_state(const td_sim *sim, int retainer, td_retainer_state *out);
/** Total force of AMB `amb` on the rotor, f[0] along x, f[1] along y, N. */
TD_API td_status td_sim_amb_force(const td_sim *sim, int amb, double f[2]);
TD_API td_status td_sim_stats_get(const td_sim *sim, td_sim_stats *out);
/** Totals of retainer `retainer` up to the current time (touchdown/records.h td_retainer_totals). */
TD_API td_status td_sim_retainer_totals(const td_sim *sim, int retainer, td_retainer_totals *out);
/** long runs: the largest normal force of retainer `retainer` at the points reached (those of its
 *  totals' peak_normal_force) since the last call for it, or since the start, N (0 without contact),
 *  into *peak; the next call counts from now. The peak of a window of a run (td_output_options.window). */
TD_API td_status td_sim_retainer_peak_since(td_sim *sim, int retainer, double *peak);
/** The energy account so far (touchdown/records.h td_energy). */
TD_API td_status td_sim_energy(const td_sim *sim, td_energy *out);
/** The rotor speed now, rad/s: the model's or the last td_sim_set_speed, the ramp's, or the free spin's state. */
TD_API double td_sim_speed(const td_sim *sim);

/* Changes between steps; each takes effect from the current time (the integrator restarts).
 * Invalid arguments give TD_ERR_INVALID, a failed restart its status; *err says which. */
TD_API td_status td_sim_set_unbalance(td_sim *sim, int unbalance, double magnitude, double phase, td_error *err);
TD_API td_status td_sim_set_speed(td_sim *sim, double omega, td_error *err);
/** AMB `amb`'s mode from now on. A mode other than TD_AMB_OFF is also the one a schedule's restore
 *  (TD_CHANGE_AMB_ON) returns the AMB to after a failure (TD_AMB_PD until the caller chooses one). */
TD_API td_status td_sim_set_amb_mode(td_sim *sim, int amb, td_amb_mode mode, td_error *err);
/** AMB `amb`'s mode now (TD_AMB_OFF while a schedule's failure holds); -1 for a NULL sim or an AMB it
 *  does not have. */
TD_API int td_sim_amb_mode(const td_sim *sim, int amb);
/** Control force (ki times current) of AMB `amb` for TD_AMB_EXTERNAL, held until the next call:
 *  the total force is ks x + f (clipped when the AMB saturates), N. */
TD_API td_status td_sim_set_amb_control(td_sim *sim, int amb, double fx, double fy, td_error *err);
/** Current command of AMB `amb` for TD_AMB_CURRENT (A along x and y), held until the next call (zero-order
 *  hold, 0 until the first): it drives the AMB's amplifier as a sampled controller's held current does,
 *  the target force ki i reached through the force lag tau and the slew limit, the total ks x + Fc
 *  clipped when the AMB saturates (docs/theory.md, "Controllers"). Invalid AMB or non-finite current:
 *  TD_ERR_INVALID. */
TD_API td_status td_sim_set_amb_current(td_sim *sim, int amb, double ix, double iy, td_error *err);

/** The simulation's own copy of the model it was created from (borrowed, valid until td_sim_free;
 *  later td_sim_set_* changes are not in it); NULL for a NULL sim. */
TD_API const td_model *td_sim_model(const td_sim *sim);
/** Copy the options the simulation was created with (defaults filled in for NULL) into *out.
 *  TD_ERR_INVALID on NULL arguments. */
TD_API td_status td_sim_options_get(const td_sim *sim, td_sim_options *out);

/* the bearing's duty */
/** The largest 0-peak displacement hypot(x_s, y_s) at AMB `amb`'s sensor so far, over the accepted
 *  points while the AMB works (ISO 14839-2's D: touchdown/assess.h), m; 0 before any. TD_ERR_INVALID
 *  for an AMB out of range or a NULL argument. */
TD_API td_status td_sim_sensor_peak_displacement(const td_sim *sim, int amb, double *out);

/* housing body */
/** The housing body's state (touchdown/housing.h td_housing_body) relative to the base: q and v (each
 *  4 long, either may be NULL) receive x, y of its centre of mass (m, m/s) and its tilts theta, phi
 *  (rad, rad/s; touchdown/dofs.h), the tilts 0 for a body that only translates. Returns 1 with a body,
 *  0 without one (q, v zeroed) or for a NULL sim. */
TD_API int td_sim_housing_body_state(const td_sim *sim, double q[4], double v[4]);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_SIM_H */
