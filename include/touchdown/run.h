/*
 * touchdown/run.h - the run loop: step a td_sim to t_end, write samples and events, summarise.
 *
 * td_run samples the simulation on a uniform grid t0 + k / sample_rate (IDA's interpolant: the
 * simulation steps to each output time, no extra steps), adds one sample at every event instant,
 * writes the event table, the solver statistics and the summary into the result files
 * (touchdown/output.h, docs/output-format.md), and closes them complete or incomplete.
 * The library prints nothing: the tool prints td_run_summary_format / td_run_summary_json.
 */
#ifndef TOUCHDOWN_RUN_H
#define TOUCHDOWN_RUN_H

#include <signal.h>
#include <stddef.h>

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/model.h"
#include "touchdown/options.h"
#include "touchdown/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/** "Returned to a free orbit" means: no retainer in contact during the last this many revolutions. */
#define TD_RUN_FREE_REVOLUTIONS 5

/** returned_to_free_orbit of a run without contact: the statement does not apply (JSON null, "n/a"). */
#define TD_RUN_NOT_APPLICABLE (-2)

/** Crossings of the once-per-revolution section a summary keeps: the last this many. */
#define TD_RUN_SECTION_SAMPLES 64

/** Fewest crossings of the section that tell its orbit: a period-4 orbit (the longest a rub's
 *  period doubling usually shows before chaos) repeats twice in 8. A section or a bifurcation
 *  diagram from fewer is said to be suspect (a warning). */
#define TD_RUN_SECTION_MIN_CROSSINGS 8

/** Progress callback: the run's time t (s) at the grid sample just taken (with projective leaps the
 *  run's clock, the simulation's plus the time leapt: after a leap, the sample it lands on), fraction
 *  of the run done (0..1), contact onsets so far, the user pointer. Return 0 to go on, nonzero to stop the run
 * (incomplete, TD_ERR_INTERRUPTED). */
typedef int (*td_progress_fn)(double t, double fraction, long contacts, void *user);

/** Optional hooks; a NULL td_run_hooks pointer means none. */
typedef struct td_run_hooks {
    td_progress_fn progress;       /**< NULL: no progress calls */
    void *user;                    /**< passed to progress */
    double progress_interval;      /**< simulated s between progress calls (0: after every sample);
                                        a last call is made at the end of a complete run */
    volatile sig_atomic_t *cancel; /**< NULL, or a flag (e.g. set by a signal handler) checked before
                                        every integrator step (td_run hands it to td_sim_set_interrupt
                                        for the run, replacing any flag set there, and clears it
                                        after); nonzero stops the run (TD_ERR_INTERRUPTED) */
} td_run_hooks;

/**
 * The regime a run settled in, over the stretch its ending is judged on (td_run_summary_ending),
 * one rule for the sweep table's `regime` column and the regime map: FREE no retainer in contact
 * over the stretch (never touched, or recovered); BACKWARD_WHIRL in contact there with a whirl
 * rate at least 5 % of the spin, backward, and either in contact at least half the stretch or
 * carried round the clearance at least once while in contact (a bounce that creeps back a
 * fraction of a turn at each touch is no whirl); BOUNCE in contact less than half the stretch, not
 * whirling backward; RUB in contact at least half the stretch (a forward rub, rolling or sliding
 * on the retainers, or at rest on them); FAILED the run did not reach its end.
 */
typedef enum td_regime {
    TD_REGIME_FAILED = 0,
    TD_REGIME_FREE = 1,
    TD_REGIME_RUB = 2,
    TD_REGIME_BOUNCE = 3,
    TD_REGIME_BACKWARD_WHIRL = 4
} td_regime;
/** Most warnings one summary keeps (td_run_summary.warnings); a last one says how many more. */
#define TD_RUN_MAX_WARNINGS 8
/** Longest warning, NUL included. */
#define TD_RUN_WARNING_SIZE 320

/** Number of td_regime values. */
#define TD_REGIME_COUNT 5

/**
 * What a run's contacts came to (docs/output-format.md, "Clearance margin and shock outcome"): NONE no
 * contact; TOUCH contact, brief: every contact left within TD_TOUCH_AND_GO_ANGLE of whirl, and each
 * retainer was in contact for less than a revolution (2 pi / |speed|) in all; and free at the end; RUB
 * sustained contact (a contact that whirled TD_TOUCH_AND_GO_ANGLE or more, or a retainer in contact
 * longer than a revolution in all), and free at the end; DROP on the retainers at the end (in contact,
 * or within the last TD_RUN_FREE_REVOLUTIONS revolutions of a contact: td_run_summary.free_at_end 0)
 * with nothing to lift it off: an AMB off, or in contact at the end after contact over at least half
 * the ending's stretch (the regime a rub or a backward whirl, not a bounce); UNSETTLED on the retainers
 * at the end otherwise (bouncing, or just lifted off, with every AMB working): too soon to tell (end_time must cover
 * the settling); UNDEFINED the run did not reach its end. The revolution is 2 pi over the speed at the first contact
 * (td_run_summary.contact_speed).
 */
typedef enum td_shock_outcome {
    TD_SHOCK_UNDEFINED = -1,
    TD_SHOCK_NONE = 0,
    TD_SHOCK_TOUCH = 1,
    TD_SHOCK_RUB = 2,
    TD_SHOCK_DROP = 3,
    TD_SHOCK_UNSETTLED = 4
} td_shock_outcome;

/** Retainers whose totals td_run_summary carries itself (the output files carry every retainer's). */
#define TD_RUN_SUMMARY_RETAINERS 8
/** AMBs whose sensors the summary grades (ISO 14839-2 zones): the first this many. */
#define TD_RUN_SUMMARY_AMBS 8

/** One retainer at the end of a run: its totals and what its whirl was (td_run_whirl_classify). */
typedef struct td_run_retainer {
    td_retainer_totals totals;
    double race_speed;      /**< rad/s at the end (TD_UNDEFINED when its state cannot be read) */
    double mean_normal;     /**< N: impulse / contact time while in contact (TD_UNDEFINED without contact) */
    double rms_normal;      /**< N: sqrt(integral of N^2 / contact time) (TD_UNDEFINED without contact) */
    double whirl_frequency; /**< Hz: mean whirl rate while in contact / 2 pi, signed like the spin (< 0 backward);
                                 TD_UNDEFINED without a sustained contact (no whirl) */
    char whirl[40];         /**< "none", "touch-and-go", or "forward|backward rolling|sliding[, bouncing]" */
    /* the bearing's duty */
    double load_ratio; /**< peak normal force / the bearing's static rating C0 (TD_UNDEFINED without C0) */
    /* life (touchdown/assess.h; docs/theory.md, "Touchdown bearing life") */
    double drops_to_failure; /**< 1 / totals.damage: runs like this one the bearing survives (ISO 281 L10, 90 %
                                  reliability); TD_UNDEFINED without a dynamic rating or without damage */
} td_run_retainer;

/** What a run did. Times in s, forces in N. A quantity without a value is TD_UNDEFINED (NaN,
 *  touchdown/dofs.h): one of something that did not happen (no contact: no first-contact time),
 *  and every answer of a run that did not reach its end (status != TD_OK: the forces, impulse,
 *  work, times in contact, final speed, energy and retainer totals, which sum up or pick the
 *  largest over the whole run or describe its end). What it did reach is kept: t_reached, the
 *  counts of samples, events and contacts, the first and last contact times, the solver's
 *  counts (its peaks, time in contact and AMB peak are answers: undefined). */
typedef struct td_run_summary {
    td_status status;                    /**< what td_run returned */
    int complete;                        /**< 1 if the run reached t_end and every file was finished complete */
    char message[TD_ERROR_MESSAGE_SIZE]; /**< why the run is incomplete ("" if complete) */
    double t_start;                      /**< simulation time when td_run began */
    double t_end;                        /**< requested end */
    double t_reached;                    /**< last time reached */
    double speed;                        /**< rotor speed used to count revolutions (the model's), rad/s */
    long samples;                        /**< samples taken (grid + event samples) */
    long grid_samples;                   /**< of which on the uniform grid */
    long events;                         /**< events seen (td_sim_step returned TD_EVENT) */
    long contacts;                       /**< contact onsets: TD_EVENT_CONTACT_ONSET + TD_EVENT_PENALTY_ENTER */
    double first_contact_time;           /**< TD_UNDEFINED if no contact */
    double last_contact_time; /**< time the last contact ended (t_reached if still in contact), TD_UNDEFINED if none */
    /* the answers that converge with the mesh and the tolerances (docs/validation.md) */
    double peak_housing_force; /**< N: largest force into the housing, over retainers and time */
    int peak_housing_retainer; /**< its retainer (-1 if none) */
    double total_impulse;      /**< N s: the normal force's impulse, summed over retainers */
    double friction_work;      /**< J: heat of sliding, summed over retainers */
    double final_speed;        /**< rad/s: rotor speed at the end */
    int retainer_count;        /**< retainers in the model; the first TD_RUN_SUMMARY_RETAINERS in `retainers` */
    td_run_retainer retainers[TD_RUN_SUMMARY_RETAINERS];
    char ending[96];                     /**< how the run ended, over its last stretch (td_run_summary_ending):
                                              "free (no contact)", "recovered", "at rest", "rolling on the
                                              retainers", "sliding on the retainers", "backward whirl at F Hz",
                                              "forward rub at F Hz" (", rolling|sliding", ", bouncing"), or
                                              "undetermined" */
    double ending_whirl_frequency;       /**< Hz: mean whirl rate over that stretch of the retainer most in
                                              contact, signed like the spin (< 0 backward); TD_UNDEFINED
                                              without whirl (no contact over it, or at rest) */
    double ending_window;                /**< s: that stretch, the last max(5 revolutions, 10 % of the run) */
    int regime;                          /**< td_regime of that stretch, set with `ending` (read it with
                                              td_run_summary_regime, which also says FAILED for a failed run) */
    int energy_kept;                     /**< 1: the case kept the energy account (td_sim_options.energy) */
    td_energy energy;                    /**< it, at the end (all 0 when not kept) */
    int peak_converges;                  /**< 0: some retainer is a rigid constraint, whose instantaneous peak normal
                                              force does not converge with the mesh (only its impulse does) */
    double peak_normal_force;            /**< largest normal force: solver statistics, samples and events */
    double peak_time;                    /**< when peak_normal_force occurred, s (TD_UNDEFINED if no contact force) */
    int peak_retainer;                   /**< retainer of peak_normal_force (-1 if no contact force) */
    double contact_time;                 /**< time with at least one retainer in contact */
    double contact_fraction;             /**< contact_time / (t_reached - t_start) */
    double free_window;                  /**< TD_RUN_FREE_REVOLUTIONS revolutions, s (TD_UNDEFINED if speed <= 0) */
    int free_at_end;                     /**< 1: no contact during the last free_window of the run; 0: contact
                                              in it; -1: undetermined (speed <= 0 or run shorter than the window) */
    int returned_to_free_orbit;          /**< 1: contacts > 0 and free_at_end == 1; 0: contacts > 0 and
                                              free_at_end == 0; TD_RUN_NOT_APPLICABLE: no contact;
                                              -1: undetermined */
    double revolutions;                  /**< speed (t_reached - t_start) / (2 pi) */
    double revolutions_after_contact;    /**< speed (t_reached - first_contact_time) / (2 pi); TD_UNDEFINED
                                              without a contact */
    double wall_time;                    /**< wall-clock time of the whole td_run (solver + output), s */
    double solver_wall_time;             /**< wall-clock time inside td_sim_step, s */
    double wall_time_per_revolution;     /**< the paper's figure of merit: solver wall time after the first
                                              contact / revolutions after it; TD_UNDEFINED without one */
    double realtime_factor;              /**< simulated seconds per wall-clock second of the whole run (> 1:
                                              faster than real time); TD_UNDEFINED if not measured */
    td_sim_stats stats;                  /**< the simulation's statistics at the end (steps, events, worst_drift...) */
    td_sim_start_info start;             /**< start state used and the stability of the contact-free system */
    int start_known;                     /**< 0: failed before a simulation existed, `start` is n/a but for
                                              start.requested */
    char hdf5_path[TD_OUTPUT_PATH_SIZE]; /**< files written (complete or marked incomplete), "" for none */
    char csv_path[TD_OUTPUT_PATH_SIZE];  /**< samples CSV */
    char events_path[TD_OUTPUT_PATH_SIZE]; /**< events CSV next to csv_path */
    /* the once-per-revolution (stroboscopic, Poincare) section: the radial displacement of one
       retainer's node each time the spin angle passes a multiple of 2 pi, at the exact crossing
       time (IDA's interpolant or the closed-form flight, as the output samples), after the
       transient (td_output_options.section_after). The retainer: the one with the largest peak
       housing force (peak_housing_retainer), retainer 0 without contact. */
    double section_start;                          /**< s: crossings from this time on are taken
                                                        (TD_UNDEFINED: the run failed before it began) */
    long section_count;                            /**< crossings taken (also those no longer kept) */
    int section_kept;                              /**< the last this many are kept, <= TD_RUN_SECTION_SAMPLES */
    int section_retainer;                          /**< retainer sampled, -1: the model has none */
    double section_clearance;                      /**< m, its radial clearance (NaN without one) */
    double section_time[TD_RUN_SECTION_SAMPLES];   /**< s, oldest first */
    double section_radius[TD_RUN_SECTION_SAMPLES]; /**< m, sqrt(x^2 + y^2) of the node relative to its retainer */
    /* Why the result may be suspect, each a sentence without a prefix, in the order found
       (docs/output-format.md, "Warnings"): an AMB past its force capacity with saturation off; a
       schedule entry at or after the end time (it never happens); a retainer clearance larger
       than the shaft radius there that no AMB air gap bounds; a section from fewer than
       TD_RUN_SECTION_MIN_CROSSINGS crossings. td_run checks them once, at the end of the run. */
    int warning_count;     /**< warnings kept, <= TD_RUN_MAX_WARNINGS */
    int warnings_left_out; /**< warnings found past the first TD_RUN_MAX_WARNINGS - 1 and not kept (0 if
                                none were): the last kept is then a notice saying how many */
    char warnings[TD_RUN_MAX_WARNINGS][TD_RUN_WARNING_SIZE]; /**< each NUL-terminated */
    int supervised; /**< 1: the model has a recovery supervisor (touchdown/model.h td_recovery): stats'
                         controller_switches, time_on_recovery and last_return_time are its account, and the
                         text, JSON and files carry them. The fields below were appended after it (the record only grows
                       at its end) */
    /* the bearing's duty (docs/theory.md, "Assessment") */
    int sensor_count;        /**< AMBs; the first TD_RUN_SUMMARY_AMBS below */
    double sensor_clearance; /**< C_min, m: the smallest retainer clearance
                                  (TD_UNDEFINED without a retainer) */
    double
        sensor_peak_displacement[TD_RUN_SUMMARY_AMBS]; /**< m, the largest 0-peak displacement at the AMB's
                                                             sensor while it worked (td_sim_sensor_peak_displacement) */
    int sensor_zone[TD_RUN_SUMMARY_AMBS];              /**< its ISO 14839-2 zone against the model's limits
                                                            (td_vibration_zone, -1: undefined) */
    double contact_onset; /**< s, when the contact still open at the end began (TD_UNDEFINED: free at the end) */
    double settle_time;   /**< s from the first contact until the rotor settled (docs/theory.md, "Time to settle"):
                               to contact_onset when that contact has held through the last stretch
                               (ending_window), to last_contact_time when the rotor has been free through it;
                               TD_UNDEFINED otherwise (settled says why) */
    int settled;          /**< 1: settled (settle_time); 0: not settled, it still touches and leaves its
                               retainers in the last stretch; TD_RUN_NOT_APPLICABLE: no contact; -1: undetermined
                               (the run did not reach its end) */
    int contact_totals_converge; /**< 0: the run bounces at its end (regime bounce), a chaotic sequence of impacts:
                                      its impulse, time in contact, contact counts, mean and rms normal force,
                                      whirl frequency, the energy lost in damping and in the contacts, and the
                                      life's load cycles, damage and drops to failure (rainflow cycles of those
                                      impacts) move with the mesh and the tolerances (docs/validation.md) */
    /* life */
    int life_kept; /**< 1: some retainer's bearing has a dynamic rating (td_model_get_retainer_bearing): the
                        retainers' damage, drops to failure and load cycles are in the text, JSON and files */
    /* housing motion */
    int housing_motion; /**< 1: the model has a prescribed housing motion (touchdown/housing.h): with the energy
                             account, its housing_work is in the text, JSON and files */
    /* clearance margin (docs/output-format.md, "Clearance margin and shock outcome") */
    double min_clearance_margin; /**< m: the smallest td_retainer_totals.min_clearance_margin over the retainers
                                      (TD_UNDEFINED without a retainer, and for a run that did not reach its end) */
    int min_clearance_retainer;  /**< its retainer (-1: none) */
    int contact_happened;        /**< 1: the rotor touched a retainer (a contact onset, or in contact from the
                                      start); 0: it did not; -1: undetermined (the run failed before any contact) */
    int shock_outcome;           /**< td_shock_outcome */
    double contact_speed;        /**< rad/s: the rotor speed at the first contact, whose revolution bounds a touch
                                      (TD_UNDEFINED without a contact) */
    /* long runs */
    int ended_at_rest; /**< 1: the run ended, complete, at the first grid sample at rest (end_at_rest,
                            td_run_at_rest) at t_reached, at or before t_end; 0 otherwise */
    int end_at_rest;   /**< 1: the run was asked to end at rest (td_output_options.end_at_rest); one that
                            reached t_end instead then carries a warning saying so */
    /* projective leap (td_output_options.leap_burst) */
    int leap;                /**< 1: the run was asked to leap */
    long leaps;              /**< leaps made: stretches not integrated, their slow state moved on at a burst's rates */
    double leapt_time;       /**< s of the run leapt (the rest, t_reached - t_start - leapt_time, integrated) */
    double leap_decel_power; /**< rad/s^2 over the leaps: the speed's rate the leaps made (the kinetic energy
                                  paying the bursts' net power), time-weighted; undefined without a leap */
    double leap_decel_speed; /**< rad/s^2: the bursts' own dOmega/dt over the same leaps (the check) */
    double leap_decel_sd;    /**< rad/s^2: the time-weighted spread (sd) of the bursts' dOmega/dt */
} td_run_summary;

/**
 * Run `sim` from its current time t0 to `t_end` (> t0).
 *
 * The model is the simulation's own (td_sim_model): its node, retainer and AMB counts give the
 * output layout, its node numbers and clearances are written as attributes, and its speed counts
 * the revolutions.
 *
 * out:       files and sampling (sample_rate > 0; nodes in range; node_count 0: every node);
 *            both paths empty: no files, the summary is still filled.
 * hooks:     progress callback and cancel flag, or NULL.
 * case_text: written as the case_text attribute (NULL: "").
 * summary:   filled in every case, also when td_run fails before its first step (may be NULL).
 *
 * Returns TD_OK when t_end was reached and every file closed complete. On a solver failure
 * (TD_ERR_SOLVER or the sim's status), a cancel or a progress stop (TD_ERR_INTERRUPTED) or a
 * write failure (TD_ERR_IO) the files are kept at their paths with everything written so far,
 * marked incomplete, and the status is returned with `err` saying what happened and when.
 * Invalid arguments (TD_ERR_INVALID) or a file that cannot be created (TD_ERR_IO) return before
 * any step, leaving no file behind; a run past the bounds of touchdown/limits.h (samples, steps
 * forced by max_step, revolutions) is an invalid argument.
 */
TD_API td_status td_run(td_sim *sim, double t_end, const td_output_options *out, const td_run_hooks *hooks,
                        const char *case_text, td_run_summary *summary, td_error *err);

/** Fill `s` for a run that failed before td_run could start it (no simulation: e.g. td_sim_create
 *  failed): status `st`, `message`, the start option `requested`, nothing simulated, no files. */
TD_API void td_run_summary_failed(td_run_summary *s, double t_start, double t_end, double speed, td_start requested,
                                  td_status st, const char *message);

/**
 * How a run ended, from the retainers' totals at the start of its last stretch (`before`, taken at
 * t_end - window) and at the end (`after`), n retainers, and the final rotor speed `speed`
 * against the start speed `speed0`: fills s->ending and s->ending_whirl_frequency. A rotor whose
 * whirl rate stays below 5 % of its spin sits on its retainers (rolling or sliding there); faster,
 * it whirls backward or rubs forward; in contact less than half the stretch, it also bounces, and
 * then whirls only if carried round the clearance at least once while in contact (else it sits on
 * its retainers, bouncing). Also sets s->regime (td_regime).
 */
TD_API void td_run_summary_ending(td_run_summary *s, const td_retainer_totals *before, const td_retainer_totals *after,
                                  int n, double speed0, double speed);

/** The run's td_regime: TD_REGIME_FAILED unless it reached its end (status TD_OK), else the
 *  regime td_run_summary_ending found. */
TD_API td_regime td_run_summary_regime(const td_run_summary *s);
/** "free", "rub", "bounce", "backward whirl", "failed" (anything else). */
TD_API const char *td_regime_name(td_regime r);
/** "none", "touch", "rub", "drop", "unsettled"; NULL for TD_SHOCK_UNDEFINED (anything else): no value. */
TD_API const char *td_shock_outcome_name(td_shock_outcome o);
/** Whether a rotor that started at speed0 and turns at speed (rad/s) is at rest: below 1 % of
 *  speed0 or below 1 rad/s. The summary's ending "at rest" uses it; a report judges the totals of a
 *  run (damage, heat) as those of a whole drop only when the run ended at rest. */
TD_API int td_run_at_rest(double speed0, double speed);
/** The time of the last change the model prescribes: its schedule's last entry, its speed ramp's last
 *  point, the end of its last housing shock or rotation (a ramp's: the end of its rise), its housing
 *  history's last time; -HUGE_VAL when none. end_at_rest (td_output_options) tests the speed only
 *  after it (before it a drop is still to come); a leap may start only after it (td_run_leap_check). */
TD_API double td_run_rest_after(const td_model *m);
/** end_at_rest: 0 if a run of `m` can end at rest, else 1 with the reason into `why` (size bytes):
 *  its start speed already at rest (at most 1 rad/s: the run would stop at its first sample) or a
 *  speed held constant (neither a free spin nor a speed ramp: it never slows down), or a speed ramp
 *  whose last point is not at rest (td_run_at_rest: the ramp holds that speed after it). The one rule the
 *  case reader (naming the key) and td_run apply. */
TD_API int td_run_rest_refused(const td_model *m, char *why, size_t size);
/** projective leap: the option td_run_leap_check finds at fault. */
typedef enum td_leap_fault {
    TD_LEAP_FINE = 0,   /**< none (or no leaps asked for: leap_burst = 0) */
    TD_LEAP_BURST = 1,  /**< leap_burst: not finite, negative, or shorter than a sample interval */
    TD_LEAP_FACTOR = 2, /**< leap_factor: not finite, or below 1 */
    TD_LEAP_HEAL = 3,   /**< leap_heal: not finite, or negative */
    TD_LEAP_START = 4,  /**< leap_start: not finite, negative, not before the run's end, or before a prescribed
                             change (td_run_rest_after) */
    TD_LEAP_MODEL = 5   /**< the model: a speed that is not a free state, more retainers than a leap handles
                             (TD_LEAP_MAX_RETAINERS), housing motion held for ever (a ramp shock or rotation) */
} td_leap_fault;
/** projective leap (td_output_options.leap_*): TD_LEAP_FINE if a run of `m` to t_end (s; the case's
 *  end_time, also when it ends at rest: then its cap) may leap as `o` asks, else the option at fault
 *  with the reason into `why` (size bytes); a leap_start at or after t_end is refused (no leap could
 *  happen). The one rule the case reader (naming the key) and td_run (TD_ERR_INVALID) apply. */
TD_API td_leap_fault td_run_leap_check(const td_model *m, const td_output_options *o, double t_end, char *why,
                                       size_t size);
/** 1 if a section of `crossings` (> 0) samples is too short to tell an orbit (fewer than
 *  TD_RUN_SECTION_MIN_CROSSINGS), 0 otherwise (none at all: nothing to tell). The one rule behind
 *  the run's warning and the bifurcation diagram's. */
TD_API int td_run_section_too_few(double crossings);

/** Human-readable multi-line summary (times with 10 decimals). Returns the length needed, like
 *  snprintf; buf is always NUL-terminated when n > 0. */
TD_API int td_run_summary_format(char *buf, size_t n, const td_run_summary *s);
/** The summary as one JSON object (doubles with 17 significant digits, TD_UNDEFINED as null).
 *  Returns the length needed, like snprintf. */
TD_API int td_run_summary_json(char *buf, size_t n, const td_run_summary *s);

/*
 * The spread of a run's answers: does THIS run's answer settle, or is it one draw of a chaotic
 * sequence of impacts? An ensemble of n runs (n odd, TD_SPREAD_MIN_MEMBERS..TD_SPREAD_MAX_MEMBERS):
 * member 0 is the run as given; members 1..n-1 the same case with solver.atol scaled by
 * td_spread_atol_factor (1 +- TD_SPREAD_ATOL_WIDTH k / m, m = (n - 1) / 2, k = 1..m) and no files
 * (td_spread_run, touchdown/job.h). The members are equally accurate: an answer that converges
 * with the tolerances moves by a fraction of its error between them, a chaotic one by as much as
 * the bounce sequence moves it. td_spread_collect gathers each leading answer over the members
 * that reached their end; td_spread_format and td_spread_json write it (docs/validation.md).
 */

/** Fewest and most members of an ensemble (odd counts only). */
#define TD_SPREAD_MIN_MEMBERS 3
#define TD_SPREAD_MAX_MEMBERS 21
/** Members' solver.atol lies within 1 +- this of the run's (+-1 %). */
#define TD_SPREAD_ATOL_WIDTH 0.01
/**
 * An answer settles when its spread is at most the relative range of solver.atol over the members,
 * 2 TD_SPREAD_ATOL_WIDTH (2 %). Why that bound: an answer A that converges with the tolerance, A =
 * A* + C atol^p, moves by dA / A = p e datol / atol, e = |A - A*| / |A| the part of its error that
 * atol sets; over the members (datol / atol spanning 2 TD_SPREAD_ATOL_WIDTH) its spread is about
 * p e 2 TD_SPREAD_ATOL_WIDTH. An integrator that controls its local error has a global error at most
 * proportional to its tolerance (p <= 1), so a spread larger than the range of atol needs e > 1, an
 * error larger than the answer: it follows no converging value but the sequence of impacts. A
 * spread within the range proves no convergence either: the answer is reproducible to its spread.
 */
#define TD_SPREAD_SETTLE_LIMIT (2.0 * TD_SPREAD_ATOL_WIDTH)

/** The leading answers of td_run_summary whose spread is measured, in the order they are written. */
typedef enum td_spread_answer {
    TD_SPREAD_PEAK_HOUSING_FORCE = 0, /**< peak_housing_force, N */
    TD_SPREAD_TOTAL_IMPULSE,          /**< total_impulse, N s */
    TD_SPREAD_FRICTION_WORK,          /**< friction_work, J */
    TD_SPREAD_FINAL_SPEED,            /**< final_speed, rad/s */
    TD_SPREAD_CONTACTS,               /**< contacts (onsets) */
    TD_SPREAD_CONTACT_TIME,           /**< contact_time, s */
    TD_SPREAD_FIRST_CONTACT_TIME,     /**< first_contact_time, s (none without contact) */
    TD_SPREAD_PEAK_NORMAL_FORCE,      /**< peak_normal_force, N */
    TD_SPREAD_PEAK_AMB_FORCE,         /**< stats.peak_amb_force, N (none without a working AMB) */
    TD_SPREAD_ANSWERS                 /**< how many */
} td_spread_answer;

/** One answer over the members. A member that did not reach its end (status != TD_OK) gives no
 *  value; nor does one of a quantity it does not have (no contact: no first-contact time). */
typedef struct td_spread_stat {
    double run;                           /**< member 0's value (TD_UNDEFINED: none, or member 0 failed) */
    int count;                            /**< members with a value */
    double least;                         /**< smallest of those values (TD_UNDEFINED when count is 0) */
    double median;                        /**< their median (the mean of the middle two when count is even) */
    double greatest;                      /**< largest */
    double spread;                        /**< (greatest - least) / |median|; 0 when all are equal; TD_UNDEFINED when
                                               count < 2, or the median is 0 and the values differ */
    int settles;                          /**< 1: spread <= TD_SPREAD_SETTLE_LIMIT, 0: larger, -1: spread undefined */
    double values[TD_SPREAD_MAX_MEMBERS]; /**< each member's value, TD_UNDEFINED where it has none */
} td_spread_stat;

/** The answers of an ensemble (td_spread_collect). */
typedef struct td_spread {
    int members;                               /**< n */
    int completed;                             /**< members that reached their end (status TD_OK) */
    int failed;                                /**< members - completed: counted, never in a statistic */
    int same_ending;                           /**< completed members that ended as member 0 did: its regime
                                                    and its `ending` but for the whirl frequency (0 when
                                                    member 0 failed) */
    char ending[96];                           /**< member 0's ending */
    double atol_factor[TD_SPREAD_MAX_MEMBERS]; /**< td_spread_atol_factor of each member */
    td_status status[TD_SPREAD_MAX_MEMBERS];   /**< each member's status */
    td_spread_stat answers[TD_SPREAD_ANSWERS];
} td_spread;

/** 1 if n members make an ensemble: odd, TD_SPREAD_MIN_MEMBERS..TD_SPREAD_MAX_MEMBERS. */
TD_API int td_spread_members_valid(int n);

/**
 * The factor on solver.atol of `member` (0..n-1) of an ensemble of n (td_spread_members_valid):
 * 1 for member 0; for k = 1..m (m = (n - 1) / 2) member 2k - 1 has 1 + TD_SPREAD_ATOL_WIDTH k / m
 * and member 2k has 1 - TD_SPREAD_ATOL_WIDTH k / m, each the double nearest that rational
 * (n = 5: 1, 1.005, 0.995, 1.01, 0.99). TD_UNDEFINED for a member or n out of range.
 */
TD_API double td_spread_atol_factor(int member, int n);

/** The name of an answer as in the summary's JSON ("peak_housing_force", ...), NULL out of range. */
TD_API const char *td_spread_answer_name(td_spread_answer a);

/**
 * Gather the n members' summaries (members[0] the run as given, members[k] the run at
 * td_spread_atol_factor(k, n)) into `out`: each answer's values, least, median, greatest, spread
 * and whether it settles, over the members that reached their end; the failed ones counted
 * (out->failed, out->status) and left out. TD_ERR_INVALID for NULL arguments or an n that is no
 * ensemble (td_spread_members_valid).
 */
TD_API td_status td_spread_collect(const td_run_summary *members, int n, td_spread *out, td_error *err);

/** The spread as text, one line per answer (member 0's value, the range, the median, the spread
 *  and whether it settles) after a line on the members, and the rule; for a NULL spread one line
 *  saying it was not measured (the run did not reach its end). Returns the length needed, like
 *  snprintf; buf is always NUL-terminated when n > 0. */
TD_API int td_spread_format(char *buf, size_t n, const td_spread *spread);
/** The spread as one JSON object (docs/output-format.md, "spread"): doubles with 17 significant
 *  digits, a value a member does not have as null. Returns the length needed, like snprintf. */
TD_API int td_spread_json(char *buf, size_t n, const td_spread *spread);
/** td_run_summary_json's object with one more member, "spread": td_spread_json's object, or null
 *  for a NULL spread (asked for but not measured: the run did not reach its end). */
TD_API int td_run_summary_json_spread(char *buf, size_t n, const td_run_summary *s, const td_spread *spread);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_RUN_H */
