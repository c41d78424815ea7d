/*
 * The td_sim record and the pieces of the contact DAE, inside the library only.
 *
 * Unknowns, one fixed layout for the whole run (offsets oq, ov, ow, ol, ou):
 *
 *   y = [ q (n) | v (n) | w (nw AMB filter states) | lambda (nr) | eta (nr) | F_t (ns) ]
 *
 * where q and v hold the rotor's DOFs (touchdown/dofs.h) and after them the races' (race.c: per
 * retainer with a race, the x, y of its centre when mounted, then its angle when it can spin; v
 * holds the race speed Omega_b there), and last, when the speed varies, the rotor's spin (spin.c:
 * its angle phi in q, its speed Omega in v). M, K, C, G below are the matrices of all n DOFs.
 *
 * lambda_k is the normal force of retainer k (N) and eta_k the GGL multiplier of its position
 * constraint (the "mu" of the stabilised index-2 form; called eta here so that mu stays the
 * friction coefficient). Residual rows, F(t, y, y') = 0:
 *
 *   q rows   q' - v + sum_k J_k^T eta_k                                   (GGL, eq. 6 stabilised)
 *   v rows   M v' - f(t, q, v, w) + sum_k B_k lambda_k                    (eq. 6)
 *   w rows   w' - (command(xs, vs, e) - w) / tau                          (AMB force lag)
 *            e' - xs                                                      (AMB integrator, PID)
 *   lambda   g_k(q) = (x^2 + y^2 - c^2)/(2c)   in contact, lambda_k = 0 otherwise   (eq. 5 scaled)
 *   eta      J_k v = (x vx + y vy)/c           in contact, eta_k = 0 otherwise      (eq. 13a scaled)
 *   F_t      v_s = 0 (eq. 16)                  rolling, F_t = 0 otherwise   (stick retainers only)
 *
 * with f = f_unbalance + f_gravity + f_amb - (C + Omega G) v - K q - f_penalty, and
 * B_k = J_k^T + phi_k mu_k t_k (the normal direction plus the Coulomb friction of eq. 17 with the
 * slip factor phi_k = phi(v_s) of the slip-regularised law, contact.h td_contact_slip_factor):
 * friction is proportional to the same, implicit, lambda_k.
 */
#ifndef TD_SIM_INTERNAL_H
#define TD_SIM_INTERNAL_H

#include "contact/contact.h"
#include "model/system_internal.h"
#include "sim/dae.h"
#include "sim/integrator.h"
#include "sim/machine.h"
#include "sim/monitor.h"
#include "sim/retainer.h"
#include "sim/sampler.h"
#include "sim/sim_modes.h"
#include "sim/sim_pattern.h"
#include "sim/stepping.h"
#include "sim/sundials_compat.h"
#include "touchdown/sim.h"

#include <math.h>
#include <nvector/nvector_serial.h>
#include <suitesparse/cs.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>

/* The closed-form free flight's decomposition, forcing and anchor (flight_internal.h). */
typedef struct td_sim_flight td_sim_flight;

/* s: a stop (a schedule change, a controller's sample) at most this far after t is due at t: the
 * stop time lands on it exactly, and the rest is rounding. */
#define TD_SIM_DUE_TOLERANCE(t) (1e-14 * (1.0 + fabs(t)))

/*
 * td_sim is the composition of records, each owned by one file or a small group of files behind its
 * own header. They are listed from the bottom up: a file writes the records it owns and those below
 * them and reads those below, never one above (the owners in brackets; setup.c creates and frees
 * them all, sim.c, at the top, serves the public calls):
 *
 *   dae        the unknowns' layout, the state (t, y, y'), the matrices, the root buffers
 *              [setup.c; race.c and spin.c lay out their DOFs]
 *   machine    the machine as it is now: speed, spin, unbalances, AMB modes; the scales
 *              [spin.c; schedule.c and the td_sim_set_* calls change it]
 *   contacts   the retainers and their modes [retainer.c, race.c; sim_modes.c switches them]
 *   ops        the mass factorisation, the Jacobian's pattern, the structural operator
 *              [sim_pattern.c; sim_residual.c writes the Jacobian's values]
 *   monitor    statistics, events, the retainers' totals, the energy account
 *              [monitor.c, totals.c, energy.c]
 *   flight     the closed-form free flight [flight_modal.c, flight_roots.c, flight.c]
 *   sampler    the sampled controllers' states and sample counts [sampler.c]
 *   kkt        the KKT solve's and the impacts' work space [sim_modes.c]
 *   solver     IDA, the tolerances, the restarts and counters [integrator.c, tolerance.c, sim_linsol.c]
 *   section    the once-per-revolution section [section.c]
 *   loop       the step loop's stops, progress window and last good state [stepping.c]
 *   start      how the start state was chosen [start.c]
 *
 * Around them the shared context, which every layer reads: the system, the model, the options, the
 * caller's interrupt flag, and the messages (errmsg, warnmsg), which a failing layer writes.
 */
struct td_sim {
    td_system *sys;        /* owned */
    const td_model *model; /* the system's copy */
    td_sim_options opt;

    td_sim_dae dae;                 /* dae.h */
    td_sim_machine machine;         /* machine.h */
    td_sim_contacts contacts;       /* retainer.h */
    td_sim_operators ops;           /* sim_pattern.h */
    td_sim_monitor monitor;         /* monitor.h */
    td_sim_flight *flight;          /* flight_internal.h; allocated at the first flight, NULL: none yet */
    td_sim_sampler *sampler;        /* sampler.h; NULL: the model has no sampled controller */
    td_sim_kkt kkt;                 /* sim_modes.h */
    td_sim_solver solver;           /* integrator.h */
    struct td_sim_section *section; /* section.c; NULL: no section taken */
    td_sim_loop loop;               /* stepping.h */
    td_sim_start_info start;        /* touchdown/sim.h; start.c */

    volatile sig_atomic_t *interrupt; /* borrowed (td_sim_set_interrupt), NULL: none */
    char errmsg[TD_ERROR_MESSAGE_SIZE];
    char warnmsg[TD_ERROR_MESSAGE_SIZE];
};

/*
 * The files of lib/sim are layers, listed here from the bottom up: a file calls only the files
 * before it in this list, so that no call runs back up and no two files call each other.
 *
 *   sim_nvector, sim_linsol      vector operations, the KLU solver (they call no other file)
 *   spin                         the spin DOF
 *   retainer, race               the retainers' queries and modes, the races' DOFs
 *   sim_pattern                  the Jacobian's pattern, the structural operator, the mass matrix
 *   sim_lti                      the linear controllers' rows, currents and Jacobian entries
 *   sim_residual                 the DAE: forces, residual, Jacobian, roots
 *   monitor, energy, totals      statistics and events, the energy account, the retainers' totals
 *   flight_modal, flight_roots,  the closed-form free flight
 *   flight
 *   sampler                      the sampled controllers' samples
 *   sim_modes, schedule          mode switching (KKT, impacts, roots), the model's timed changes
 *   tolerance, integrator        the tolerances, IDA and its restarts
 *   section                      the once-per-revolution section (section.h)
 *   start, stepping, setup       the start state, the step loop, creation and release
 *   sim                          the public functions of touchdown/sim.h
 */

/* ---- sim_lti.c: linear controllers in the DAE ------------------------------------------------ */

/* The current command (A) of driven AMB axis a (a->law >= 0) at y: C x + D e + D1 e' of its
 * continuous law, or the current its sampled law holds (machine.held_current). */
double td_sim_lti_current(const td_sim *s, const td_amb_axis *a, const double *y);
/* res = x' - A x - B e on every continuous law's rows. */
void td_sim_lti_rows(const td_sim *s, const double *y, const double *yp, double *res);
/* yp = A x + B e on the same rows (the consistent rates at y). */
void td_sim_lti_rates(const td_sim *s, const double *y, double *yp);
/* Jacobian entries of scale * (driven axis a's current) into row `row`: C on the law's states,
 * -D and -D1 on its inputs' sensor displacements and velocities; none for a sampled law. */
void td_sim_lti_jacobian_current(td_sim *s, const td_amb_axis *a, int row, double scale);
/* Jacobian entries of the continuous laws' rows: -A on their states, B on their sensors (e = -xs). */
void td_sim_lti_jacobian_rows(td_sim *s);

/* ---- sim_nvector.c: compiled vector operations ----------------------------------------- */

/* Replace the operations of serial vector v (and of every later clone of it) by the library's
 * compiled loops; see sim_nvector.c for why. */
void td_sim_nvector_optimize(N_Vector v);

/* ---- sim_linsol.c: KLU inside IDA ------------------------------------------------------- */

/* A SUNLinearSolver factorising s->ops.jdata on s->ops.colptr/s->ops.rowind with KLU: one symbolic analysis
 * per run, a pivoting factorisation after every restart, refactorisations in between. */
SUNLinearSolver td_sim_klu_create(const td_sim *s);

/* ---- spin.c: the rotor's spin as a DOF when the speed varies ----------------------------- */

/* rad/s: the free spin's constant drag is regularised over this band around standstill */
#define TD_SIM_SPIN_BAND 1e-2

/* Assign the spin DOF (after the races') when the model's speed varies; s->machine.spin = -1 otherwise. */
void td_sim_spin_layout(td_sim *s);
/* The spin's diagonal entry of matrix `which` ('M': J, 'C': the free spin's viscous drag). */
void td_sim_spin_diagonal(const td_sim *s, char which, double *d);
/* Rotor speed Omega (rad/s) and spin angle phi (rad) at (t, y). */
double td_sim_rotor_speed(const td_sim *s, const double *y);
double td_sim_rotor_angle(const td_sim *s, double t, const double *y);
/* The torque that drives the spin DOF from outside (ramp: J alpha, what the drive must give;
 * free: the drive torque); 0 without a spin DOF. */
double td_sim_spin_torque(const td_sim *s, double t);
/* A free spin's constant drag torque, regularised over TD_SIM_SPIN_BAND at standstill, with its
 * slope in Omega (may be NULL); 0 otherwise. */
double td_sim_spin_drag(const td_sim *s, const double *y, double *dT);
/* The spin's start state into y: angle and speed at s->dae.t. */
void td_sim_spin_start(const td_sim *s, double *y);
/* A ramp's spin angle and speed (and their rates into yp, which may be NULL) in y set to the
 * prescribed profile's at t: what an accepted or interpolated state reports. Nothing otherwise. */
void td_sim_spin_hold(const td_sim *s, double t, double *y, double *yp);
/* The spin angle taken modulo 2 pi (at restarts). */
void td_sim_spin_wrap(const td_sim *s, double *y);

/* ---- retainer.c: the retainers (retainer.h) ---------------------------------------------- */

/* ---- race.c: the races' DOFs and matrices ----------------------------------------------- */

/* Assign the race DOFs after the rotor's and set s->dae.n. */
void td_sim_races_layout(td_sim *s);
/* s->dae.M, s->dae.K, s->dae.C, s->dae.G over all n DOFs. */
td_status td_sim_races_matrices(td_sim *s, td_error *err);
void td_sim_races_free(td_sim *s);
/* f += sign * the races' weight (length n). */
void td_sim_races_gravity(const td_sim *s, double *f, double sign);
/* f += sign * the races' share of the housing motion's inertial loads (their mass times the
 * housing's acceleration at their axial position), for the motion hm. */
void td_sim_races_housing(const td_sim *s, const td_housing_motion *hm, double *f, double sign);
/* The races' start state into y: centres resting on their mounts, speeds at bore_speed. */
void td_sim_races_start(const td_sim *s, double *y);

/* ---- sim_pattern.c: the Jacobian's sparsity pattern, the structural operator, the mass ---- */

/* Build s->ops.colptr, s->ops.rowind, s->ops.jdata and the maps of the system matrices. */
td_status td_sim_pattern_build(td_sim *s, td_error *err);
/* Position of (row, col) in the pattern, -1 if absent. */
int td_sim_pattern_find(const td_sim *s, int row, int col);
/* Build the row-compressed M, K, D of the structural operator (s->st_*), D at s->machine.omega. */
td_status td_sim_structural_build(td_sim *s, td_error *err);
/* Recompute D = C + Omega G after a change of s->machine.omega. */
void td_sim_structural_speed(td_sim *s);
/* Factorise M (s->ops.Ms, s->ops.Mn). */
td_status td_sim_mass_factor(td_sim *s, td_error *err);
/* x = M^-1 b in place (length n). */
void td_sim_mass_solve(const td_sim *s, double *b);

/* ---- sim_residual.c: the DAE ------------------------------------------------------------- */

/* f += sign * the external forces: gravity, unbalance and AMBs (what does work on the machine from
 * outside; applied_forces adds the contacts and the races' drag to them). */
void td_sim_external_forces(const td_sim *s, double t, const double *y, double sign, double *f);
/* f += sign * the housing motion's inertial loads alone (the part of td_sim_external_forces that
 * the energy account books as housing_work); nothing without housing motion. */
void td_sim_housing_forces(const td_sim *s, double t, const double *y, double sign, double *f);
/* Generalised force f(t, q, v, w) of the header comment (everything but inertia and constraints). */
void td_sim_forces(const td_sim *s, double t, const double *y, double *f);
/* F(t, y, y'). */
void td_sim_residual(const td_sim *s, double t, const double *y, const double *yp, double *res);
/* dF/dy + cj dF/dy' into s->ops.jdata (pattern s->ops.colptr, s->ops.rowind). */
void td_sim_jacobian(td_sim *s, double t, double cj, const double *y);
/* Root functions (TD_ROOTS_PER_RETAINER per retainer, then the AMB clips' kinks, then the
 * amplifiers' slew kinks) and their directions for the current modes. */
void td_sim_roots(const td_sim *s, double t, const double *y, double *g);
void td_sim_root_directions(const td_sim *s, int *dir);
/* Force of AMB axis k at state y (N), with the mode of its AMB. */
double td_sim_amb_axis_force(const td_sim *s, int k, const double *y);
/* A free spin's inertial coupling with the unbalances (spin.c): rv -= the forces that the
 * residual's explicit alpha missed and the unbalances' drag on the spin (rv may be NULL); returns
 * their power at y, J/s. 0 unless the spin is free. */
double td_sim_unbalance_spin_coupling(const td_sim *s, double t, const double *y, const double *yp, double *rv);
/* Rate dFc/dt of AMB axis k's lag state at y (tau > 0): towards the shorthand's command, or the
 * target ki i of its linear controller's current (model/amb.c). */
double td_sim_amb_axis_lag_rate(const td_sim *s, int k, const double *y);
/* Rate of AMB axis k's integrator state at y (model/amb.c td_amb_axis_integral_rate); 0 without one. */
double td_sim_amb_axis_integral_rate(const td_sim *s, int k, const double *y);
/* dFc/dt of AMB axis k (tau > 0) at y: the lag's rate through the amplifier's slew limit. */
double td_sim_amb_axis_lag_rate(const td_sim *s, int k, const double *y);
/* How many AMB axes slew at y (their amplifiers held at the slew-rate limit); 0 without a limit. */
int td_sim_amb_slewing_axes(const td_sim *s, const double *y);
/* Spin angle phi(t) at the prescribed speed. */
double td_sim_spin_angle(const td_sim *s, double t);

/* ---- monitor.c: statistics and the event queue ------------------------------------------- */

/* Append an event to the queue (and the statistics). */
void td_sim_queue_event(td_sim *s, const td_event *ev);
/* Fill the velocity fields of an event from the node velocity of retainer k. */
void td_sim_event_velocities(const td_sim *s, int k, const double *y, int after, td_event *ev);
/* An event of `kind` at s->dae.t, of retainer k (-1: none), no schedule entry. */
td_event td_sim_event_at(const td_sim *s, td_event_kind kind, int k);
/* The next queued event into s->monitor.last; 0 when the queue is empty. */
int td_sim_pop_event(td_sim *s);
/* AMB axis k's force `force` at time t: a new peak load if it is the largest yet. */
void td_sim_monitor_amb_load(td_sim *s, int k, double force, double t);
/* Statistics at the state in s->dae.y (time t), a point the run has reached: contact time, peak
 * normal force, AMB load, and at an integrator step's end (at_step) the constraint drift. */
void td_sim_monitor_at(td_sim *s, double t, int at_step);
/* An integrator step's end at t beyond the output time: its times summed, its peaks held until the
 * run reaches t (td_sim_monitor_at, td_sim_monitor_settle). */
void td_sim_monitor_step_ahead(td_sim *s, double t);
/* The run goes on from t (a restart, the flight, a failure's last state): a held point at or before
 * t is recorded, one beyond it dropped (it belongs to an integration that is discarded). */
void td_sim_monitor_settle(td_sim *s, double t);

/* ---- energy.c, totals.c: the energy account and the retainers' running totals ------------- */

/* The energy account's point at time t (energy.c), with the segment length dt since the last one
 * (0 at a restart): called by td_sim_totals_point. */
void td_sim_energy_point(td_sim *s, double t, int restart, double dt);
/* An impact changed the kinetic energy from `before` to `after`, J. */
void td_sim_energy_impact(td_sim *s, double before, double after);
/* The energy account taken back from its last point to s->dae.t (a change or an output inside the
 * integrator's last step), as td_sim_totals_rewind does with the retainers' totals. */
void td_sim_energy_rewind(td_sim *s);
/* projective leap: x^T M y over the velocities (n of them), M the structural mass (energy.c) */
double td_sim_mass_form(const td_sim *s, const double *x, const double *y);
/* Kinetic energy 1/2 v^T M v of the state y, J. */
double td_sim_kinetic_energy(const td_sim *s, const double *y);
/* v^T M v, q^T K q and v^T D v (out[0..2]) of M, K, D stored on one row-compressed pattern of n rows,
 * in one pass; bit for bit the three separate row-by-row sums. */
void td_sim_quadratic_forms(int n, const int *rowptr, const int *col, const double *M, const double *K, const double *D,
                            const double *q, const double *v, double out[3]);
/* The energy account at s->dae.t (td_sim_energy). */
void td_sim_energy_get(const td_sim *s, td_energy *out);
/* A point of the totals at time t with the state in s->dae.y: closes the segment since the last point
 * (restart 0: an accepted step or a stop), or opens one after a restart (restart 1). */
void td_sim_totals_point(td_sim *s, double t, int restart);
/* The retainers' peaks (housing and normal force) at the state y; td_sim_totals_point records them
 * but at a point the monitor holds (td_sim_monitor_step_ahead), whose peaks come when it is reached. */
void td_sim_totals_peaks(td_sim *s, const double *y);
/* Before a restart at s->dae.t inside the integrator's last step (a change between steps): the totals
 * taken back to s->dae.t. */
void td_sim_totals_rewind(td_sim *s);
/* An impact of retainer k with `impulse` (N s); `bounced`: it left at once (touch-and-go). */
void td_sim_totals_impact(td_sim *s, int k, double impulse, int bounced);
/* Retainer k's totals at s->dae.t (td_sim_retainer_totals). */
void td_sim_totals_get(const td_sim *s, int k, td_retainer_totals *out);
/* clearance margin (margin.c): the retainers' smallest clearance - r, from the start (before the first point) */
void td_sim_margin_start(td_sim *s);
/* A point of the totals at t with the state in s->dae.y (td_sim_totals_point): the segment since the last
 * point counted (held when the monitor holds the point, td_sim_monitor_step_ahead), unless the flight
 * covered it (monitor.margin_flown). */
void td_sim_margin_point(td_sim *s, double t);
/* The run goes on from s->dae.t inside a held segment (a change, the flight): it counts up to there. */
void td_sim_margin_rewind(td_sim *s);
/* Retainer k's node reached radius r (m) at a time the run has reached (the flight's own search). */
void td_sim_margin_note(td_sim *s, int k, double r);
/* Retainer k's smallest margin up to s->dae.t, m. */
double td_sim_margin_get(const td_sim *s, int k);
/* The bearing's duty: AMB amb's largest sensed displacement so far (td_sim_sensor_peak_displacement). */
void td_sim_sensor_peak_get(const td_sim *s, int amb, double *out);
/* life (load_cycles.c): the retainers' rainflow counters for those whose bearing has a dynamic
 * rating (td_model_get_retainer_bearing), before the first point; freed by td_sim_life_free. */
td_status td_sim_life_setup(td_sim *s, td_error *err);
void td_sim_life_free(td_sim *s);
/* Retainer k's rolling damage rate at y (1/s, td_life_rolling_rate; 0 without a rating). */
double td_sim_life_rate(const td_sim *s, int k, const double *y);
/* Retainer k's contact load at y, a point the run has reached, into its rainflow counter. */
void td_sim_life_point(td_sim *s, int k, const double *y);
/* Retainer k's damage and load cycles into *out, whose damage holds the rolling damage up to
 * s->dae.t: the cycles closed, those the end closes and the residue added (TD_UNDEFINED: no rating). */
void td_sim_life_get(const td_sim *s, int k, td_retainer_totals *out);

/* ---- thermal.c: heat, the races' drag work and the retainers' thermal networks -------------- */

/* The networks of the model's retainers (td_model_get_retainer_thermal), zero rises. */
void td_sim_thermal_setup(td_sim *s);
/* Retainer k's heat power F_t v_s at y (0 out of contact), W: friction_work's integrand. */
double td_sim_friction_power(const td_sim *s, int k, const double *y);
/* Retainer k's point of the totals with the state in s->dae.y, dt after the last one (0: a restart
 * opens a segment), its friction power there `friction` (W): drag_work and the network carried. */
void td_sim_thermal_point(td_sim *s, int k, double dt, double friction, td_retainer_totals *t);
/* Retainer k's heat taken back from the last point to s->dae.t into t (td_sim_totals_get, rewind)
 * with its temperatures there into T (may be NULL). */
void td_sim_thermal_back(const td_sim *s, int k, td_retainer_totals *t, double T[2]);
/* Before a restart at s->dae.t inside the last step: the networks' states taken back to it. */
void td_sim_thermal_rewind(td_sim *s, int k);
/* The race's rise at the last point into the peak (a point reached: td_sim_totals_peaks). */
void td_sim_thermal_peak(td_sim *s, int k);
/* Retainer k's rises at s->dae.t (race, housing), TD_UNDEFINED without a network. */
void td_sim_thermal_now(const td_sim *s, int k, double T[2]);

/* ---- flight_modal.c, flight_roots.c, flight.c: free flight in closed form ------------------ */

/* Carry the state from s->dae.t in closed form to t_out or the stop t_stop, whichever comes first,
 * or to a root before them (*root = 1, s->dae.rootsfound as IDAGetRootInfo would set it), or less far
 * at an interrupt; y holds the state at the new s->dae.t (y': td_sim_flight_rates). The flight works in
 * the states scaled by `scale` (neq: the integrator's absolute tolerances, each state in its
 * tolerance's units). Returns 0 (nothing moved) when the flight cannot carry the machine: the
 * integrator does. */
int td_sim_flight_advance(td_sim *s, const double *scale, double t_out, double t_stop, int *root);
/* The state was moved by something else (an integrator step, a restart): the next flight starts
 * from s->dae.y afresh. */
void td_sim_flight_forget(td_sim *s);
/* The samples just taken at a stop the flight reached: the flight carries their held currents on
 * from s->dae.t; 0 if it cannot (the caller restarts the integrator). */
int td_sim_flight_hold(td_sim *s);
/* y' at s->dae.t from the flight that carried the state there (its outputs write y only). */
void td_sim_flight_rates(td_sim *s);
void td_sim_flight_free(td_sim *s);
/* The displacements z at t (any time since the anchor) into y[0..nz) without moving anything:
 * outputs between steps (section.c). work: 2 neq doubles. Returns 0 when no flight is anchored. */
int td_sim_flight_peek(const td_sim *s, double t, double *y, double *work);

/* ---- sampler.c: sampled controllers (sampler.h) ------------------------------------------- */

/* s->sampler for the model's sampled laws (td_lti_law with sample_rate > 0), each at rest with its
 * sample 0 at s->dae.t; left NULL when there is none. */
td_status td_sim_sampler_create(td_sim *s, td_error *err);
void td_sim_sampler_free(td_sim *s);
/* The time of the next sample of any law (s->sampler not NULL). */
double td_sim_sampler_next_time(const td_sim *s);
/* Take every sample due at s->dae.t (TD_SIM_DUE_TOLERANCE) from the state in s->dae.y, law by law:
 * the new commands into s->machine.held_current; returns how many (s->sampler not NULL), or -1
 * when a plug-in failed (now or before: s->errmsg says why, td_sim_sampler_failure). The caller
 * restarts the integrator when it took one: the force jumps there. */
int td_sim_sampler_take_due(td_sim *s);
/* TD_ERR_INVALID with the reason in s->errmsg once a plug-in law has failed (the run goes no
 * further), else TD_OK. */
td_status td_sim_sampler_failure(td_sim *s);
/* Tell `hook` of every sample from now on (nothing without a sampled law). */
void td_sim_sampler_set_hook(td_sim *s, td_sim_sample_hook hook, void *data);

/* ---- sampler_plugin.c: a plug-in law's samples ------------------------------------------- */

/* Law l's instance (the plug-in's init) and buffers; TD_ERR_INVALID with the plug-in's reason. */
td_status td_sim_plugin_init(td_sim *s, td_sim_sampled *l, td_error *err);
/* Plug-in law `law`'s direct gain on its output `output`: the largest |D| over its inputs, D its
 * current per unit error at a sample, measured at creation (a linear law's D, touchdown/controller.h). */
double td_sim_plugin_gain(const td_sim *s, int law, int output);
/* A plug-in's failure (s->errmsg still its message, status st) into *err with its site, the failed
 * controller: returns 1; 0 (nothing set) for any other failure. */
int td_sim_plugin_error(const td_sim *s, td_status st, td_error *err);
/* Law l's instance released (its free) and its buffers. */
void td_sim_plugin_free(const td_sim *s, td_sim_sampled *l);
/* Law l's sample k at t_k from its inputs l->e: the held current i_k into l->u. Returns 0, or -1
 * when the plug-in failed (s->errmsg and s->sampler->failure say why). */
int td_sim_plugin_step(td_sim *s, td_sim_sampled *l, long k, double t);

/* ---- sim_modes.c: mode switching, consistent restarts, impacts, roots --------------------- */

/* Make (y, y') consistent with the current modes at time t: eta = 0, lambda of free retainers 0,
 * q' = v, w' = filter rate, and [v'; lambda] from the KKT system. Contacts whose lambda comes out
 * negative (or <= 0 for those flagged in just_entered) are released and the solve repeated; each
 * release is queued as an event unless just entered (then the onset event records it). */
td_status td_sim_make_consistent(td_sim *s, const int *just_entered);
/* 1 if some retainer's mode disagrees with the state y, i.e. IDA missed a crossing of its root:
 * a penalty contact's mode beyond the noise band (retainer.c td_sim_penalty_mode_wanted), or a
 * stick retainer sliding against its slip direction beyond the slip band (stick_out_of_step). */
int td_sim_modes_out_of_step(const td_sim *s, const double *y);
/* Start of a run with the retainers flagged in `touching` on (or a hair outside) their circles:
 * projection and impact as at an onset, then td_sim_make_consistent. */
td_status td_sim_start_contacts(td_sim *s, const int *touching);
/* Handle the roots found at s->dae.t (IDAGetRootInfo in s->dae.rootsfound; all zero: only bring the
 * penalty modes in step with the state). *restart is set when the integrator must be
 * re-initialised. */
td_status td_sim_handle_roots(td_sim *s, int *restart);

/* ---- schedule.c: the model's timed changes ------------------------------------------------ */

/* AMB amb's mode, also in s->sys (td_system_set_amb_off), so that the start state's stability and
 * steady orbit are those of the machine at the start, after the changes due then. */
void td_sim_amb_mode_set(td_sim *s, int amb, td_amb_mode mode);
/* Apply every schedule change due at s->dae.t, queueing TD_EVENT_SCHEDULE events. */
td_status td_sim_apply_due_changes(td_sim *s);
/* Apply silently every change due at or before s->dae.t (before the start of the run). */
void td_sim_apply_past_changes(td_sim *s);
/* Where the integrator must stop next: the next schedule change or speed-ramp point; INFINITY if none. */
double td_sim_next_stop(const td_sim *s);
/* 1 if a schedule change is due at s->dae.t. */
int td_sim_change_due(const td_sim *s);

/* ---- tolerance.c: the integrator's tolerances --------------------------------------------- */

/* The per-component absolute tolerances into s->solver.atol and the differential/algebraic flags into
 * s->solver.id. */
void td_sim_set_tolerances(td_sim *s);
/* Set the race speeds' tolerances in s->solver.atol for the current modes; 1 if one changed. */
int td_sim_races_retolerance(td_sim *s);
/* The tolerance rtol |q_i| + atol that a restart's first step is sized against, at unknown i of the
 * state y (i in the q block): the displacement tolerance on every coordinate. */
double td_sim_restart_tolerance(const td_sim *s, int i, const double *y);

/* ---- integrator.c: IDA ---------------------------------------------------------------------- */

/* The SUNDIALS context, the state vectors and the IDA instance; failures leave their message in
 * s->errmsg. */
td_status td_sim_integrator_create(td_sim *s, td_error *err);
/* IDA initialised on the start state: tolerances, the Newton and linear solvers, the roots. */
td_status td_sim_integrator_attach(td_sim *s, td_error *err);
/* Re-initialise IDA at s->dae.t from s->dae.y, s->dae.yp (counters saved, root directions, restart step,
 * stop time, KLU refactorisation). */
td_status td_sim_restart(td_sim *s);
/* y, yp at time t inside IDA's last step. */
td_status td_sim_interpolate(td_sim *s, double t);
/* 1 (with a message) when IDA's steps have stopped moving t (the step just taken ended at t). */
int td_sim_stalled(td_sim *s, double t);
/* The integrator's counters, over every restart, into the counter fields of out. */
void td_sim_integrator_counters(const td_sim *s, td_sim_stats *out);
void td_sim_integrator_free(td_sim *s);

/* ---- section.c: the once-per-revolution section (section.h) ------------------------------- */

/* The crossings of the spin angle through multiples of 2 pi in (the last covered time, t] from
 * IDA's interpolant (after an accepted step or at a stop inside one) or from the flight. */
void td_sim_section_ida(td_sim *s, double t);
void td_sim_section_flight(td_sim *s, double t);
/* A restart at s->dae.t: samples taken beyond it belonged to a state that has since been changed. */
void td_sim_section_rewind(td_sim *s);
void td_sim_section_free(td_sim *s);

/* ---- start.c: the start state --------------------------------------------------------------- */

/* Stability of the contact-free closed loop at the start speed into s->start. */
void td_sim_start_stability(td_sim *s);
/* The start state into s->dae.y, s->dae.yp (s->start says which); contacts at the start made consistent. */
td_status td_sim_start_state(td_sim *s, td_error *err);

/* ---- stepping.c: the step loop ---------------------------------------------------------------- */

/* Restart after a change made between steps or at a schedule time. */
td_status td_sim_restart_after_change(td_sim *s);
/* The restart after a change between steps (sim.c's td_sim_set_*), with a stop due within rounding of
 * s->dae.t handled at once. */
td_status td_sim_restart_between_steps(td_sim *s);
/* Integrate from s->dae.t to tout (> s->dae.t), stopping early at an event to report or a failure. */
td_status td_sim_advance(td_sim *s, double tout);

/* ---- setup.c: creation and release ---------------------------------------------------------- */

/* A new simulation of `model` into *out (model and out not NULL). */
td_status td_sim_setup(const td_model *model, const td_sim_options *options, volatile sig_atomic_t *cancel,
                       td_sim **out, td_error *err);
void td_sim_teardown(td_sim *s);
/* The step bound when the options set none, at the current speed. */
double td_sim_default_max_step(const td_sim *s);

#endif
