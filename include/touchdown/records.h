/*
 * touchdown/records.h - the records a simulation produces and the writers store: events, the
 * contact state of a retainer, the solver statistics. Their own header, so that the writers
 * (touchdown/output.h) do not depend on the simulation (touchdown/sim.h).
 * Units and sign conventions: touchdown/dofs.h.
 */
#ifndef TOUCHDOWN_RECORDS_H
#define TOUCHDOWN_RECORDS_H

#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What stopped a step early. */
typedef enum td_event_kind {
    TD_EVENT_CONTACT_ONSET = 0,     /**< rotor reached the clearance circle moving outward (impact) */
    TD_EVENT_RELEASE = 1,           /**< normal force reached zero: the rotor leaves the retainer */
    TD_EVENT_FRICTION_REVERSAL = 2, /**< sliding velocity (eq. 16) changed sign: it crossed the whole
                                         slip band |v_s| < 1e-4 m/s of the friction law (docs/theory.md) */
    TD_EVENT_SCHEDULE = 3,          /**< a timed change of the model (unbalance step, AMB failure) */
    TD_EVENT_PENALTY_ENTER = 4,     /**< penalty model: penetration delta became positive */
    TD_EVENT_PENALTY_EXIT = 5,      /**< penalty model: penetration delta returned to zero */
    TD_EVENT_ROLL_START = 6,        /**< stick retainer: v_s reached 0 and the friction force that rolling
                                         without slip needs is within mu N: it rolls */
    TD_EVENT_ROLL_END = 7,          /**< stick retainer: rolling needs more than mu N (or an impact): it slips */
    TD_EVENT_CONTROLLER_SWITCH = 8  /**< the recovery supervisor switched a pair of sampled controllers
                                         (touchdown/model.h td_recovery): td_event.controller is the law
                                         switched to, td_event.sensed_radius the radius it judged */
} td_event_kind;

/** 1 if an event of `kind` opens a contact (an onset: TD_EVENT_CONTACT_ONSET or
 *  TD_EVENT_PENALTY_ENTER, which the contacts count), else 0. */
TD_API int td_event_is_onset(td_event_kind kind);

/** One event, as recorded in the event table. Velocities are of the retainer node. */
typedef struct td_event {
    td_event_kind kind;
    double time;                   /**< s */
    int retainer;                  /**< retainer index, -1 for schedule events */
    int change;                    /**< TD_EVENT_SCHEDULE: the schedule entry as written (its order of
                                        addition, td_model_change_entry), else -1 */
    double radial_velocity_before; /**< m/s, positive outward */
    double radial_velocity_after;
    double tangential_velocity_before; /**< m/s, positive along the whirl direction */
    double tangential_velocity_after;
    double impulse;           /**< N s, normal impulse of the impact map (onset only) */
    double normal_force;      /**< N, right after the event */
    double peak_normal_force; /**< N, the largest normal force of the contact interval this event ends
                                   (release, penalty exit; 0 for other events), taken at the integrator's
                                   steps, the output samples and right after the impact. Under the rigid constraint it
                                 is the instantaneous peak, which does not converge with the mesh (docs/theory.md) */
    int controller;           /**< TD_EVENT_CONTROLLER_SWITCH: the controller switched to (td_model_get_controller's
                                   index), else -1. Last, as sensed_radius: the output files carry both only for
                                   a model with a recovery supervisor */
    double sensed_radius;     /**< TD_EVENT_CONTROLLER_SWITCH: m, the sensed radius at the switch sample (the largest
                                   over the pair's AMBs of hypot(xs_x, xs_y) at the sensor), else 0 */
} td_event;

/** Contact state of one retainer at the current time. */
typedef struct td_retainer_state {
    double x, y;             /**< node displacement, m */
    double radius;           /**< radial position r of the node relative to the race centre, m (the gap is c - r) */
    double radial_velocity;  /**< dr/dt, m/s */
    double whirl_angle;      /**< angle of the node around the race centre, atan2, rad */
    double normal_force;     /**< N >= 0 while in contact */
    double friction_force;   /**< N, tangential, positive along the whirl direction */
    double sliding_velocity; /**< eq. 16, m/s */
    int in_contact;          /**< 1 while the contact is active */
    double race_x, race_y;   /**< race centre displacement on its mount, m (0 without a mount) */
    double race_speed;       /**< race speed Omega_b, rad/s (bore_speed when it is fixed) */
    int rolling;             /**< 1 while rolling without slip (stick retainers, model.h) */
    double whirl_rate;       /**< d(whirl_angle)/dt, rad/s: > 0 forward (with the spin), < 0 backward */
    /* heat */
    double race_temperature;    /**< K above the ambient, the race node (TD_UNDEFINED without retainers[].thermal) */
    double housing_temperature; /**< K above the ambient, the housing node (TD_UNDEFINED without it) */
} td_retainer_state;

/**
 * What one retainer has received so far: the quantities that converge as the mesh and the
 * tolerances are refined (docs/validation.md), unlike the instantaneous peak of a rigid contact.
 * Time integrals are trapezoidal over the integrator's steps (not the output samples); the
 * impacts of the constraint model add their impulses.
 */
typedef struct td_retainer_totals {
    double impulse;            /**< N s: integral of the normal force plus the impacts' impulses */
    double impact_impulse;     /**< N s: the impacts' share (constraint model impact map) */
    double contact_time;       /**< s in contact */
    double rolling_time;       /**< s rolling without slip (stick retainers) */
    double normal_force_sq;    /**< N^2 s: integral of N^2 (rms normal force = sqrt(this / contact_time)) */
    double friction_work;      /**< J: integral of F_t v_s, the heat of sliding into the retainer (>= 0) */
    double whirl_angle;        /**< rad: whirl angle swept while in contact (mean whirl rate = this / contact_time) */
    double peak_housing_force; /**< N: largest force into the housing (the mount force k_m r + c_m r' on a
                                    mount, the contact force |N n + F_t t| on a fixed bore) */
    double peak_normal_force;  /**< N */
    long contacts;             /**< contact intervals that swept at least TD_TOUCH_AND_GO_ANGLE of whirl
                                    (the one still open counts) */
    long touch_and_go;         /**< impacts that left again within less: bounces, rebounds, grazes */
    /* the bearing's duty (docs/theory.md, "The bearing's duty"): peaks at the accepted points, like
     * peak_normal_force; 0 before the first contact (peak_race_speed: from the start) */
    double peak_sliding_velocity; /**< m/s, largest |v_s| in contact */
    double peak_friction_power;   /**< W, largest F_t v_s */
    double peak_pv;             /**< Pa m/s, largest N / (2 R_s b) |v_s| (TD_UNDEFINED without the bearing's width b) */
    double peak_contact_stress; /**< Pa, Hertz, the most loaded ball on the inner raceway at peak_normal_force
                                     (TD_UNDEFINED without the bearing's ball geometry) */
    double peak_race_speed;     /**< rad/s, largest |race speed| */
    /* heat */
    double drag_work; /**< J: work of the race's drag torques (the bearing's own losses; 0 on a fixed race) */
    double heat;      /**< J into the thermal network: friction_work + drag_work (the same trapezoids) */
    double peak_temperature_rise; /**< K: the race's largest rise above the ambient (TD_UNDEFINED without
                                       retainers[].thermal) */
    double peak_thermal_growth;   /**< m: the race bore's radial growth alpha R_b peak_temperature_rise (an output
                                       only: the clearance does not change; TD_UNDEFINED without the expansion) */
    /* life (touchdown/assess.h td_life_law; docs/theory.md, "Touchdown bearing life") */
    double damage;      /**< Miner sum of the ISO 281 rating life used: the contact load's rainflow cycles (those
                             the history's end closes and its residue included) and the race's revolutions
                             under load; TD_UNDEFINED without the bearing's dynamic rating */
    double load_cycles; /**< the contact load's rainflow cycles counted (a half cycle 0.5), those of the end
                             included; TD_UNDEFINED without the bearing's dynamic rating (the gate's scale) */
    /* clearance margin (docs/output-format.md, "Clearance margin") */
    double min_clearance_margin; /**< m: the smallest clearance - r over the run, r the node's radius from the race
                                      centre (the housing's bore, or the race's moving centre on a mount); < 0: a
                                      compliant contact's penetration. Between the integrator's points the largest
                                      r of the cubic Hermite through r and dr/dt at both ends; in closed-form free
                                      flight the flight's own solution, searched to TD_MARGIN_RTOL of the clearance */
} td_retainer_totals;

/**
 * The machine's energy account so far (docs/theory.md, "Energy"): what it holds now, what came in
 * and what was lost. residual is 0 up to the integration error (trapezoidal over the steps).
 */
typedef struct td_energy {
    double kinetic;       /**< J now: 1/2 v^T M v, rotor and races */
    double elastic;       /**< J now: 1/2 q^T K q (shaft, AMB negative stiffness excluded, mounts) + contact springs */
    double initial;       /**< J: kinetic + elastic at the start */
    double external_work; /**< J: work of gravity, the unbalances and the AMBs */
    double drive_work;    /**< J: the drive holding the rotor's speed against friction, F_t R_s Omega */
    double damping_loss;  /**< J: dissipated by C (shaft material damping, mounts, the races' viscous drag) */
    double contact_loss;  /**< J: dissipated in the contacts (friction heat, contact dampers) */
    double drag_loss;     /**< J: the races' constant drag */
    double impact_loss;   /**< J: kinetic energy the impacts took (restitution < 1) */
    double residual;      /**< J: kinetic + elastic - initial - external - drive - housing + the losses */
    /* housing motion */
    double housing_work; /**< J: work of the housing motion's inertial loads on the relative motion
                              (touchdown/housing.h; 0 without housing motion) */
} td_energy;

/** A contact that sweeps less whirl angle than this (rad) before it ends is a touch-and-go impact. */
#define TD_TOUCH_AND_GO_ANGLE 1.0

/** clearance margin: the closed-form flight finds a retainer's smallest margin to this fraction of its
 *  clearance (td_retainer_totals.min_clearance_margin) */
#define TD_MARGIN_RTOL 1e-4

/** Running totals across every restart of the integrator. */
typedef struct td_sim_stats {
    long steps;
    long residual_evals;
    long jacobian_evals;
    long linear_setups;
    long nonlinear_iters;
    long error_test_fails;
    long nonlinear_fails;
    long restarts; /**< re-initialisations after events */
    long events;   /**< events of any kind */
    long contact_onsets;
    long releases;
    double worst_drift;        /**< max |r - c| while in constrained contact, m */
    double peak_normal_force;  /**< N */
    double peak_time;          /**< s, time of peak_normal_force (TD_UNDEFINED if no contact) */
    int peak_retainer;         /**< retainer of peak_normal_force (-1 if no contact) */
    double time_in_contact;    /**< s, summed over retainers */
    double first_contact_time; /**< s, TD_UNDEFINED if none */
    double wall_time;          /**< s spent inside td_sim_step */
    double peak_amb_force;     /**< N: largest |force| of one AMB axis while the AMB works (steps and outputs) */
    double peak_amb_load;      /**< largest |force| / force_capacity of one AMB axis (1: at its capacity) */
    double peak_amb_time;      /**< s, time of peak_amb_load, at most the time reached (TD_UNDEFINED: none) */
    int peak_amb;              /**< AMB of peak_amb_load (-1 if no AMB force) */
    long flight_steps;         /**< steps of the closed-form free flight (root bounds evaluated) */
    double flight_time;        /**< s simulated in closed-form free flight */
    long controller_samples;   /**< samples taken by sampled controllers (each law's count, summed) */
    double time_slewing;       /**< s, summed over AMB axes, with the amplifier at its slew-rate limit */
    long controller_switches;  /**< switches of the recovery supervisor (touchdown/model.h td_recovery), both ways */
    double time_on_recovery;   /**< s, summed over the supervisor's pairs, on the recovery law (up to now) */
    double last_return_time;   /**< s, the last switch back to a nominal law (TD_UNDEFINED if none) */
} td_sim_stats;

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_RECORDS_H */
