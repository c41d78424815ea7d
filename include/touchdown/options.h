/*
 * touchdown/options.h - how to run a model: contact law, solver, start state, output, modal analysis.
 *
 * Plain structs, filled with defaults by td_*_options_default() and then edited; the case-file
 * reader (touchdown/case.h) fills them from a case file. Units: touchdown/dofs.h.
 */
#ifndef TOUCHDOWN_OPTIONS_H
#define TOUCHDOWN_OPTIONS_H

#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How rotor-retainer contact is modelled. */
typedef enum td_contact_model {
    TD_CONTACT_CONSTRAINT = 0, /**< holonomic constraint with a Lagrange multiplier (paper eqs. 5-15) */
    TD_CONTACT_PENALTY = 1     /**< penalty force F_n = Kc delta^p (+ damping) (paper eq. 4) */
} td_contact_model;

/** Damping law added to a penalty contact; none of them ever pulls (F_n >= 0). */
typedef enum td_contact_damping {
    TD_DAMPING_NONE = 0,          /**< F_n = Kc delta^p */
    TD_DAMPING_HUNT_CROSSLEY = 1, /**< F_n = Kc delta^p (1 + damping * ddelta/dt), clipped at 0; damping in s/m */
    TD_DAMPING_KELVIN_VOIGT = 2   /**< F_n = max(0, Kc delta^p + damping * ddelta/dt); damping in N s/m */
} td_contact_damping;

typedef struct td_contact_options {
    td_contact_model model;
    double stiffness;           /**< penalty Kc, N/m^exponent (N/m when linear) */
    double exponent;            /**< penalty exponent p: 1 linear (eq. 4), 1.5 Hertzian */
    td_contact_damping damping; /**< penalty damping law */
    double damping_coefficient; /**< s/m (Hunt-Crossley) or N s/m (Kelvin-Voigt) */
} td_contact_options;

/** Linear solver inside IDA's Newton iteration. */
typedef enum td_linear_solver {
    TD_LINSOL_KLU = 0,  /**< sparse LU (SuiteSparse KLU), symbolic factorisation once */
    TD_LINSOL_DENSE = 1 /**< dense LU, for comparison */
} td_linear_solver;

typedef struct td_solver_options {
    double rtol;         /**< relative tolerance */
    double atol;         /**< absolute tolerance on displacements, m; other states are scaled from it */
    double max_step;     /**< largest step, s; 0: chosen from the whirl period */
    double initial_step; /**< first step and restart step after an event, s; 0: chosen by IDA */
    int max_order;       /**< BDF order limit, 1..5 */
    td_linear_solver linear_solver;
    int free_flight; /**< nonzero: carry free flight in closed form where the machine is linear and
                          time-invariant (sim.h); 0: integrate it with IDA too */
} td_solver_options;

/** State at t = 0. */
typedef enum td_start {
    TD_START_ORBIT = 0, /**< steady harmonic orbit of the contact-free linear system (plus static sag) */
    TD_START_REST = 1,  /**< centred, at rest, AMB filter states zero */
    TD_START_AUTO = 2   /**< the orbit when the contact-free system is stable (checked) and the orbit lies
                             inside every clearance, else rest (td_sim_start_info says which and why) */
} td_start;

typedef struct td_sim_options {
    td_contact_options contact;
    td_solver_options solver;
    td_start start;
    double t0;  /**< start time, s */
    int energy; /**< nonzero: keep the energy account (td_sim_energy; about 30 % more time on the
                     undamped rig); 0: td_sim_energy reports TD_ERR_INVALID */
} td_sim_options;

/** Largest number of nodes an output can select. */
#define TD_OUTPUT_MAX_NODES 64
/** Longest output path, NUL included. */
#define TD_OUTPUT_PATH_SIZE 1024

typedef struct td_output_options {
    char hdf5_path[TD_OUTPUT_PATH_SIZE]; /**< "" : no HDF5 file */
    char csv_path[TD_OUTPUT_PATH_SIZE];  /**< "" : no CSV file */
    double sample_rate;                  /**< samples per second on a uniform grid (events added), Hz */
    int node_count;                      /**< number of nodes whose displacements are written; 0: all */
    int nodes[TD_OUTPUT_MAX_NODES];
    int compression;      /**< HDF5 deflate level with shuffle, 0 (none) .. 9 */
    double section_after; /**< the once-per-revolution section (td_run_summary) is taken after this
                               fraction of the run, 0 .. 1 (the transient before it is left out);
                               default 0.5: the last half */
    /* long runs */
    int end_at_rest; /**< nonzero: the run ends, complete, at the first grid sample at which the rotor is at
                          rest (td_run_at_rest: below 1 % of its start speed or 1 rad/s), else at t_end */
    double window;   /**< length of the window summaries (td_run_window), s; 0: none */
    int omit_events; /**< nonzero: no event rows and no samples at events in the files (the run's
                          bookkeeping and the window summaries still see every event) */
    /* projective leap (td_run; docs/case-format.md, "Projective leap") */
    double leap_burst;  /**< s: the stretch of full integration the slow rates are read over; 0: no leaps */
    double leap_factor; /**< a leap is this many bursts long (>= 1) */
    double leap_heal;   /**< s: integrated after each leap (and before the first burst), not read */
    double leap_start;  /**< s: no leap before this time (the fall's transient) */
} td_output_options;

/** projective leap: the most retainers a leap's slow state holds (td_run_leap_check refuses more) */
#define TD_LEAP_MAX_RETAINERS 8

typedef struct td_modal_options {
    double speed_min; /**< Campbell diagram speed range, rad/s */
    double speed_max;
    int speed_steps;            /**< number of speeds, >= 2 */
    int mode_count;             /**< modes reported (lowest damped natural frequencies), > 0 */
    int response_speed_count;   /**< harmonic unbalance response speeds */
    double response_speeds[64]; /**< rad/s */
    /* the API 617 unbalance response report (td_unbalance_sweep) */
    double operating_speed_min; /**< minimum operating speed, rad/s; TD_UNDEFINED: no operating range */
    double operating_speed_max; /**< maximum continuous speed, rad/s; TD_UNDEFINED: no operating range */
    int response_node_count;    /**< 0: the default nodes (td_modal_default_response_nodes) */
    int response_nodes[64];     /**< nodes of the swept response (Bode, polar, peaks) */
} td_modal_options;

TD_API void td_contact_options_default(td_contact_options *o);
TD_API void td_solver_options_default(td_solver_options *o);
TD_API void td_sim_options_default(td_sim_options *o);
TD_API void td_output_options_default(td_output_options *o);
TD_API void td_modal_options_default(td_modal_options *o);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_OPTIONS_H */
