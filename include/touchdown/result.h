/*
 * touchdown/result.h - the output schema and reading result files.
 *
 * The schema: every dataset, group, attribute and event field of the files touchdown writes (a
 * run's HDF5 and CSV files, a modal file, a sweep table) has one td_out_id here, and its name,
 * units, shape and type are declared once, as a table, in lib/io/schema.c. The writers take every
 * name from that table, so a reader that uses the ids reads what the writers wrote.
 * docs/output-format.md describes each name.
 *
 * The reader: td_result_open opens a run, modal or sweep HDF5 file, says which it is and whether
 * it is complete (docs/output-format.md, "Completeness rule"), and reads its datasets (as doubles
 * or text, with their units and shape), its events and its attributes. No call prints; every
 * failure is a status with a one-line message naming the file. The HDF5 library's own error
 * printing is silenced inside every call.
 */
#ifndef TOUCHDOWN_RESULT_H
#define TOUCHDOWN_RESULT_H

#include <stddef.h>

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/records.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the schema ----------------------------------------------------------------------------- */

/**
 * Every name of the output files (td_out_name gives the text). The ids' numbers are not stable
 * across versions (a new name may be added anywhere in the list); the names are: store or
 * exchange names, never numbers.
 */
typedef enum td_out_id {
    TD_OUT_ROOT = 0, /**< the file's root group ("") */
    /* run file: groups, sample datasets and dimension scales */
    TD_OUT_NODES,
    TD_OUT_RETAINERS,
    TD_OUT_AMBS,
    TD_OUT_TIME,
    TD_OUT_SPEED,
    TD_OUT_COMPONENT,
    TD_OUT_NODE_DISPLACEMENT,
    TD_OUT_NODE,
    TD_OUT_RET_X,
    TD_OUT_RET_Y,
    TD_OUT_RET_RADIAL_POSITION,
    TD_OUT_RET_RADIAL_VELOCITY,
    TD_OUT_RET_WHIRL_ANGLE,
    TD_OUT_RET_NORMAL_FORCE,
    TD_OUT_RET_FRICTION_FORCE,
    TD_OUT_RET_SLIDING_VELOCITY,
    TD_OUT_RET_CONTACT_STATE,
    TD_OUT_RET_RACE_X,
    TD_OUT_RET_RACE_Y,
    TD_OUT_RET_RACE_SPEED,
    TD_OUT_RET_ROLLING,
    TD_OUT_RET_WHIRL_RATE,
    TD_OUT_RETAINER,
    TD_OUT_AMB_FORCE,
    TD_OUT_AMB,
    TD_OUT_EVENTS,
    TD_OUT_EVENT,
    /* run file: the fields of /events (and the columns of the CSV events file) */
    TD_OUT_EV_TIME,
    TD_OUT_EV_KIND,
    TD_OUT_EV_KIND_NAME,
    TD_OUT_EV_RETAINER,
    TD_OUT_EV_CHANGE,
    TD_OUT_EV_SAMPLE,
    TD_OUT_EV_RADIAL_VELOCITY_BEFORE,
    TD_OUT_EV_RADIAL_VELOCITY_AFTER,
    TD_OUT_EV_TANGENTIAL_VELOCITY_BEFORE,
    TD_OUT_EV_TANGENTIAL_VELOCITY_AFTER,
    TD_OUT_EV_IMPULSE,
    TD_OUT_EV_NORMAL_FORCE,
    TD_OUT_EV_PEAK_NORMAL_FORCE,
    TD_OUT_EV_CONTROLLER, /* only in the files of a model with a recovery supervisor */
    TD_OUT_EV_SENSED_RADIUS,
    /* attributes of datasets and groups */
    TD_OUT_UNITS,
    TD_OUT_COUNT,
    TD_OUT_NODES_ATTR,
    TD_OUT_COMPONENTS,
    TD_OUT_KIND_NAMES,
    /* root attributes shared by the files */
    TD_OUT_COMPLETE,
    TD_OUT_INCOMPLETE_REASON,
    TD_OUT_CASE_TEXT,
    TD_OUT_LIBRARY_VERSION,
    /* run file: root attributes */
    TD_OUT_STATUS,
    TD_OUT_SAMPLE_RATE,
    TD_OUT_T_START,
    TD_OUT_T_END,
    TD_OUT_T_REACHED,
    TD_OUT_MODEL_SPEED,
    TD_OUT_RETAINER_NODES,
    TD_OUT_RETAINER_CLEARANCE,
    TD_OUT_RETAINER_IMPULSE,
    TD_OUT_RETAINER_IMPACT_IMPULSE,
    TD_OUT_RETAINER_FRICTION_WORK,
    TD_OUT_RETAINER_PEAK_HOUSING_FORCE,
    TD_OUT_RETAINER_PEAK_NORMAL_FORCE,
    TD_OUT_RETAINER_CONTACT_TIME,
    TD_OUT_RETAINER_ROLLING_TIME,
    TD_OUT_RETAINER_CONTACTS,
    TD_OUT_RETAINER_TOUCH_AND_GO,
    TD_OUT_AMB_NODES,
    TD_OUT_AMB_CAPACITY,
    TD_OUT_STAT_STEPS,
    TD_OUT_STAT_RESIDUAL_EVALS,
    TD_OUT_STAT_JACOBIAN_EVALS,
    TD_OUT_STAT_LINEAR_SETUPS,
    TD_OUT_STAT_NONLINEAR_ITERS,
    TD_OUT_STAT_ERROR_TEST_FAILS,
    TD_OUT_STAT_NONLINEAR_FAILS,
    TD_OUT_STAT_RESTARTS,
    TD_OUT_STAT_EVENTS,
    TD_OUT_STAT_CONTACT_ONSETS,
    TD_OUT_STAT_RELEASES,
    TD_OUT_STAT_PEAK_AMB,
    TD_OUT_STAT_FLIGHT_STEPS,
    TD_OUT_STAT_WORST_DRIFT,
    TD_OUT_STAT_PEAK_NORMAL_FORCE,
    TD_OUT_STAT_TIME_IN_CONTACT,
    TD_OUT_STAT_FIRST_CONTACT_TIME,
    TD_OUT_STAT_WALL_TIME,
    TD_OUT_STAT_PEAK_AMB_FORCE,
    TD_OUT_STAT_PEAK_AMB_LOAD,
    TD_OUT_STAT_PEAK_AMB_TIME,
    TD_OUT_STAT_FLIGHT_TIME,
    TD_OUT_STAT_CONTROLLER_SAMPLES,
    TD_OUT_STAT_TIME_SLEWING,
    TD_OUT_STAT_CONTROLLER_SWITCHES, /* these three only in the files of a model with a recovery supervisor */
    TD_OUT_STAT_TIME_ON_RECOVERY,
    TD_OUT_STAT_LAST_RETURN_TIME,
    TD_OUT_WARNINGS,
    TD_OUT_SUM_FIRST_CONTACT_TIME,
    TD_OUT_SUM_LAST_CONTACT_TIME,
    TD_OUT_SUM_PEAK_NORMAL_FORCE,
    TD_OUT_SUM_PEAK_HOUSING_FORCE,
    TD_OUT_SUM_TOTAL_IMPULSE,
    TD_OUT_SUM_FRICTION_WORK,
    TD_OUT_SUM_FINAL_SPEED,
    TD_OUT_SUM_ENDING_WHIRL_FREQUENCY,
    TD_OUT_SUM_ENDING_WINDOW,
    TD_OUT_SUM_CONTACT_TIME,
    TD_OUT_SUM_CONTACT_FRACTION,
    TD_OUT_SUM_FREE_WINDOW,
    TD_OUT_SUM_REVOLUTIONS,
    TD_OUT_SUM_REVOLUTIONS_AFTER_CONTACT,
    TD_OUT_SUM_WALL_TIME,
    TD_OUT_SUM_SOLVER_WALL_TIME,
    TD_OUT_SUM_WALL_TIME_PER_REVOLUTION,
    TD_OUT_SUM_REALTIME_FACTOR,
    TD_OUT_SUM_SAMPLES,
    TD_OUT_SUM_GRID_SAMPLES,
    TD_OUT_SUM_EVENTS,
    TD_OUT_SUM_CONTACTS,
    TD_OUT_SUM_ENDING,
    TD_OUT_SUM_FREE_AT_END,
    TD_OUT_SUM_RETURNED_TO_FREE_ORBIT,
    TD_OUT_SUM_PEAK_NORMAL_FORCE_CONVERGES,
    TD_OUT_SUM_ENERGY_KINETIC,
    TD_OUT_SUM_ENERGY_ELASTIC,
    TD_OUT_SUM_ENERGY_INITIAL,
    TD_OUT_SUM_ENERGY_EXTERNAL_WORK,
    TD_OUT_SUM_ENERGY_DRIVE_WORK,
    TD_OUT_SUM_ENERGY_DAMPING_LOSS,
    TD_OUT_SUM_ENERGY_CONTACT_LOSS,
    TD_OUT_SUM_ENERGY_DRAG_LOSS,
    TD_OUT_SUM_ENERGY_IMPACT_LOSS,
    TD_OUT_SUM_ENERGY_RESIDUAL,
    TD_OUT_SECTION_START,
    TD_OUT_SECTION_COUNT,
    TD_OUT_SECTION_RETAINER,
    TD_OUT_SECTION_CLEARANCE,
    TD_OUT_SECTION_TIME,
    TD_OUT_SECTION_RADIUS,
    /* modal file */
    TD_OUT_PRODUCER,
    TD_OUT_MODES,
    TD_OUT_MODES_SPEED,
    TD_OUT_MODES_SPEED_UNITS,
    TD_OUT_MODES_SIGMA, /* the mode table: sigma .. whirl in this order, as for /campbell */
    TD_OUT_MODES_OMEGA_D,
    TD_OUT_MODES_FREQ_HZ,
    TD_OUT_MODES_OMEGA_N,
    TD_OUT_MODES_ZETA,
    TD_OUT_MODES_WHIRL_INDEX,
    TD_OUT_MODES_WHIRL,
    TD_OUT_MODES_REAL_EIGENVALUES,
    TD_OUT_MODES_SHAPE_X_RE,
    TD_OUT_MODES_SHAPE_X_IM,
    TD_OUT_MODES_SHAPE_Y_RE,
    TD_OUT_MODES_SHAPE_Y_IM,
    TD_OUT_MODES_MODE,
    TD_OUT_MODES_NODE_Z,
    TD_OUT_MODES_RETAINER_NODES,
    TD_OUT_MODES_AMB_NODES,
    TD_OUT_CAMPBELL,
    TD_OUT_CAMPBELL_SIGMA,
    TD_OUT_CAMPBELL_OMEGA_D,
    TD_OUT_CAMPBELL_FREQ_HZ,
    TD_OUT_CAMPBELL_OMEGA_N,
    TD_OUT_CAMPBELL_ZETA,
    TD_OUT_CAMPBELL_WHIRL_INDEX,
    TD_OUT_CAMPBELL_WHIRL,
    TD_OUT_CAMPBELL_SPEED,
    TD_OUT_CAMPBELL_BRANCH,
    TD_OUT_CAMPBELL_LAYOUT,
    TD_OUT_CRITICAL,
    TD_OUT_CRITICAL_SPEED,
    TD_OUT_CRITICAL_FREQ_HZ,
    TD_OUT_CRITICAL_ZETA,
    TD_OUT_CRITICAL_SIGMA,
    TD_OUT_CRITICAL_WHIRL,
    TD_OUT_CRITICAL_BRANCH,
    TD_OUT_HARMONIC,
    TD_OUT_HARMONIC_I, /**< /harmonic/I, I = 0, 1, ...: the `sub` of the reading calls names I */
    TD_OUT_HARMONIC_SPEED,
    TD_OUT_HARMONIC_SPEED_UNITS,
    TD_OUT_HARMONIC_X_AMP, /* the orbit columns: x_amp .. minor in this order */
    TD_OUT_HARMONIC_X_PHASE,
    TD_OUT_HARMONIC_Y_AMP,
    TD_OUT_HARMONIC_Y_PHASE,
    TD_OUT_HARMONIC_FORWARD,
    TD_OUT_HARMONIC_BACKWARD,
    TD_OUT_HARMONIC_MAJOR,
    TD_OUT_HARMONIC_MINOR,
    TD_OUT_HARMONIC_STATE_RE,
    TD_OUT_HARMONIC_STATE_IM,
    TD_OUT_HARMONIC_NODE,
    TD_OUT_HARMONIC_STATE,
    TD_OUT_MODAL_MODE_SHAPES, /**< the modal CSV file's section of the mode shapes */
    TD_OUT_MODAL_INDEX,       /**< the modal CSV file's column of the real eigenvalues' index */
    TD_OUT_MODAL_NODE,        /**< the modal CSV file's node column (mode shapes, harmonic) */
    TD_OUT_LOOP,              /**< /loop: the loop analysis (td_loop_compute) */
    TD_OUT_LOOP_SPEED,
    TD_OUT_LOOP_SPEED_UNITS,
    TD_OUT_LOOP_STABLE,
    TD_OUT_LOOP_MAX_REAL_PART,
    TD_OUT_LOOP_SAMPLE_RATE, /**< a sampled loop's only (td_loop_sample_rate) */
    TD_OUT_LOOP_SENSITIVITY_ZONE,
    TD_OUT_LOOP_FREQUENCY,
    TD_OUT_LOOP_AXIS,
    TD_OUT_LOOP_AMB_AXIS,
    TD_OUT_LOOP_SENSITIVITY_RE,
    TD_OUT_LOOP_SENSITIVITY_IM,
    TD_OUT_LOOP_OPEN_LOOP_RE,
    TD_OUT_LOOP_OPEN_LOOP_IM,
    TD_OUT_LOOP_COMPLIANCE_RE,
    TD_OUT_LOOP_COMPLIANCE_IM,
    TD_OUT_LOOP_SENSITIVITY_PEAK,
    TD_OUT_LOOP_SENSITIVITY_PEAK_FREQUENCY,
    TD_OUT_LOOP_SENSITIVITY_ZONES,
    TD_OUT_LOOP_PEAKS,      /**< the modal CSV file's section of the sensitivity peaks */
    TD_OUT_LOOP_COMPLIANCE, /**< the modal CSV file's section of the compliance */
    /* sweep table */
    TD_OUT_SWEEP_POINT,
    TD_OUT_SWEEP_VARY, /**< the group /vary: the `sub` of the reading calls names the key */
    TD_OUT_SWEEP_KEY_SPEC,
    TD_OUT_SWEEP_KEY_AXIS,
    TD_OUT_SWEEP_KEY_ORIGIN,
    TD_OUT_SWEEP_STATUS, /* the columns after the swept keys, in the table's order */
    TD_OUT_SWEEP_MESSAGE,
    TD_OUT_SWEEP_PEAK_HOUSING_FORCE,
    TD_OUT_SWEEP_TOTAL_IMPULSE,
    TD_OUT_SWEEP_FRICTION_WORK,
    TD_OUT_SWEEP_CONTACT_TIME,
    TD_OUT_SWEEP_CONTACTS,
    TD_OUT_SWEEP_FIRST_CONTACT_TIME,
    TD_OUT_SWEEP_ENDING,
    TD_OUT_SWEEP_REGIME,
    TD_OUT_SWEEP_ENDING_WHIRL_FREQUENCY,
    TD_OUT_SWEEP_RETURNED_TO_FREE_ORBIT,
    TD_OUT_SWEEP_SECTION_COUNT,
    TD_OUT_SWEEP_SECTION_RADIUS_MIN,
    TD_OUT_SWEEP_SECTION_RADIUS_MAX,
    TD_OUT_SWEEP_SECTION_CLEARANCE,
    TD_OUT_SWEEP_FINAL_SPEED,
    TD_OUT_SWEEP_PEAK_AMB_LOAD,
    TD_OUT_SWEEP_T_REACHED,
    TD_OUT_SWEEP_WARNINGS,
    TD_OUT_SWEEP_WALL_TIME,
    TD_OUT_SWEEP_SECTION_RADIUS,
    TD_OUT_SWEEP_VARY_SPECS,
    TD_OUT_SWEEP_SET,
    TD_OUT_SWEEP_POINTS,
    TD_OUT_SWEEP_WITH,
    TD_OUT_SWEEP_FROM,
    /* the bearing's duty */
    TD_OUT_RETAINER_PEAK_SLIDING_VELOCITY,
    TD_OUT_RETAINER_PEAK_FRICTION_POWER,
    TD_OUT_RETAINER_PEAK_PV,
    TD_OUT_RETAINER_PEAK_CONTACT_STRESS,
    TD_OUT_RETAINER_PEAK_RACE_SPEED,
    TD_OUT_RETAINER_LOAD_RATIO,
    TD_OUT_SENSOR_CLEARANCE,
    TD_OUT_SENSOR_PEAK_DISPLACEMENT,
    TD_OUT_SENSOR_ZONE,
    TD_OUT_SUM_SETTLE_TIME,
    TD_OUT_SUM_SETTLED,
    TD_OUT_SUM_CONTACT_TOTALS_CONVERGE,
    /* heat */
    TD_OUT_RET_RACE_TEMPERATURE,
    TD_OUT_RET_HOUSING_TEMPERATURE,
    TD_OUT_RETAINER_DRAG_WORK,
    TD_OUT_RETAINER_HEAT,
    TD_OUT_RETAINER_PEAK_TEMPERATURE_RISE,
    TD_OUT_RETAINER_PEAK_THERMAL_GROWTH,
    /* the API 617 unbalance response report (modal file; docs/api617.md) */
    TD_OUT_MODES_LOG_DECREMENT, /**< /modes/log_decrement */
    TD_OUT_MODES_DISC_NODES,    /**< /modes/disc_nodes, for the mode-shape plots */
    TD_OUT_MODES_SENSOR_NODES,  /**< /modes/sensor_nodes (AMB sensors) */
    TD_OUT_UNBALANCE_RESPONSE,  /**< /unbalance_response: the swept response (td_unbalance_sweep) */
    TD_OUT_UR_SPEED,
    TD_OUT_UR_NODE,
    TD_OUT_UR_X_AMP, /* the swept orbit columns: x_amp .. minor in this order */
    TD_OUT_UR_X_PHASE,
    TD_OUT_UR_Y_AMP,
    TD_OUT_UR_Y_PHASE,
    TD_OUT_UR_FORWARD,
    TD_OUT_UR_BACKWARD,
    TD_OUT_UR_MAJOR,
    TD_OUT_UR_MINOR,
    TD_OUT_RESPONSE_PEAKS, /**< /response_peaks: the peaks with their API 617 assessment */
    TD_OUT_PEAK_OPERATING_SPEED_MIN,
    TD_OUT_PEAK_OPERATING_SPEED_MAX,
    TD_OUT_PEAK_NODE,
    TD_OUT_PEAK_SPEED,
    TD_OUT_PEAK_AMPLITUDE,
    TD_OUT_PEAK_SPEED_LOW,
    TD_OUT_PEAK_SPEED_HIGH,
    TD_OUT_PEAK_AMPLIFICATION,
    TD_OUT_PEAK_MARGIN,
    TD_OUT_PEAK_REQUIRED_MARGIN,
    TD_OUT_PEAK_VERDICT,
    TD_OUT_STATIC_REACTIONS, /**< /static_reactions: the supports' forces under gravity */
    TD_OUT_STATIC_AMB_FORCE,
    TD_OUT_STATIC_BEARING_FORCE,
    TD_OUT_STATIC_SUPPORT, /**< the modal CSV file's column of the support's kind */
    TD_OUT_UR_SENSOR_ZONE, /**< /unbalance_response/sensor_zone: ISO 14839-2 zone per speed and AMB sensor */
    TD_OUT_UR_C_MIN,       /**< /unbalance_response attribute: C_min of the zones */
    TD_OUT_CAMPBELL_MAC,   /**< /campbell/mac: each point's MAC to its branch's point at the previous speed */
    /* life: written only when a retainer's bearing has a dynamic rating (appended here, after every id
       of 0.14.0 and this release's other blocks, so that no earlier id changes its number) */
    TD_OUT_RETAINER_DAMAGE,
    TD_OUT_RETAINER_DROPS_TO_FAILURE,
    TD_OUT_RETAINER_LOAD_CYCLES,
    TD_OUT_SWEEP_DROPS_TO_FAILURE, /**< only in a table with a row whose bearings have a dynamic rating */
    /* API 617's amplitude at the close clearances (the retainers; td_sweep_clearance_check) */
    TD_OUT_RUNNING_CLEARANCE, /**< /running_clearance, one row per retainer */
    TD_OUT_RC_FRACTION,       /**< attribute: the limit, a fraction of the clearance */
    TD_OUT_RC_SPEED_MIN,      /**< attribute: the range checked, rad/s (the sweep's when no operating range) */
    TD_OUT_RC_SPEED_MAX,
    TD_OUT_RC_NODE,
    TD_OUT_RC_CLEARANCE,
    TD_OUT_RC_AMPLITUDE,
    TD_OUT_RC_SPEED,
    TD_OUT_RC_RATIO,
    TD_OUT_RC_VERDICT,
    /* housing motion */
    TD_OUT_SUM_ENERGY_HOUSING_WORK, /**< only with the energy account of a model with housing motion */
    /* clearance margin (docs/output-format.md, "Clearance margin and shock outcome") */
    TD_OUT_RETAINER_MIN_CLEARANCE_MARGIN, /**< root attribute (n_ret), m */
    TD_OUT_SUM_MIN_CLEARANCE_MARGIN,      /**< root attribute, m: the smallest over the retainers */
    TD_OUT_SUM_CONTACT_HAPPENED,          /**< root attribute: 1, 0, NaN (undetermined) */
    TD_OUT_SUM_SHOCK_OUTCOME,             /**< root attribute: none, touch, rub, drop ("" for a failed run) */
    TD_OUT_SWEEP_MIN_CLEARANCE_MARGIN,    /**< sweep column, m */
    TD_OUT_SWEEP_CONTACT_HAPPENED,        /**< sweep column: 1, 0, NaN */
    TD_OUT_SWEEP_SHOCK_OUTCOME,           /**< sweep column: text */
    /* housing motion (the series of a model with housing motion) */
    TD_OUT_HOUSING,                    /**< group /housing */
    TD_OUT_HOUSING_ACCELERATION,       /**< (N, 2) m/s^2 */
    TD_OUT_HOUSING_VELOCITY,           /**< (N, 2) m/s */
    TD_OUT_HOUSING_DISPLACEMENT,       /**< (N, 2) m */
    TD_OUT_HOUSING_ROTATION_RATE,      /**< (N, 2) rad/s, about x and y */
    TD_OUT_HOUSING_ROTATION_ANGLE,     /**< (N, 2) rad */
    TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, /**< /nodes/absolute_displacement (N, n_nodes, 2) m */
    /* housing body (the series of a model with a housing body) */
    TD_OUT_HOUSING_BODY_DISPLACEMENT, /**< (N, 2) m, the body's centre relative to the base */
    TD_OUT_HOUSING_BODY_TILT,         /**< (N, 2) rad, the body's theta, phi */
    /* long runs: the window summaries (a run with output.window; docs/output-format.md, "Window summaries") */
    TD_OUT_WINDOWS,               /**< group /windows; in CSV the window file */
    TD_OUT_WIN_TIME_START,        /**< (W) s */
    TD_OUT_WIN_TIME_END,          /**< (W) s */
    TD_OUT_WIN_SPEED,             /**< (W) rad/s at the window's end */
    TD_OUT_WIN_ENERGY_KINETIC,    /**< (W) J at the window's end, NaN without the energy account */
    TD_OUT_WIN_ENERGY_RESIDUAL,   /**< (W) J at the window's end, NaN without the energy account */
    TD_OUT_WIN_CONTACTS,          /**< (W, n_ret) contact onsets */
    TD_OUT_WIN_CONTACT_FRACTION,  /**< (W, n_ret) 1 */
    TD_OUT_WIN_PEAK_NORMAL_FORCE, /**< (W, n_ret) N */
    TD_OUT_WIN_FRICTION_WORK,     /**< (W, n_ret) J */
    TD_OUT_WIN_RACE_TEMPERATURE,  /**< (W, n_ret) K above the ambient at the window's end */
    /* projective leap: the leaps made (a run with a leap group; docs/output-format.md, "Leaps in the files") */
    TD_OUT_SUM_LEAPS,      /**< leaps made */
    TD_OUT_SUM_LEAPT_TIME, /**< s of the run leapt, not integrated */
    TD_OUT_LEAP_TIME,      /**< (leaps) s: each leap's start, the run's time of the row before its gap */
    TD_OUT_LEAP_LENGTH,    /**< (leaps) s: each leap's length, its gap */
    /* long runs */
    TD_OUT_SUM_ENDED_AT_REST, /**< 1, 0, NaN (failed): a run with end_at_rest ended at rest */
    /* projective leap and long runs: the sweep's columns of them */
    TD_OUT_SWEEP_LEAPS,         /**< sweep column: leaps made (a table with a point that leaps) */
    TD_OUT_SWEEP_LEAPT_TIME,    /**< sweep column: s leapt */
    TD_OUT_SWEEP_ENDED_AT_REST, /**< sweep column: 1, 0, NaN (a table with a point asked to end at rest) */
    TD_OUT_ID_COUNT             /**< number of ids; also "several objects" as the parent of an attribute */
} td_out_id;

/** What a name is in the file. */
typedef enum td_out_place {
    TD_OUT_NO_PLACE = -1, /**< no name: an id out of range */
    TD_OUT_GROUP = 0,
    TD_OUT_DATASET = 1,   /**< a dataset (also a dimension scale, which is one) */
    TD_OUT_ATTRIBUTE = 2, /**< an attribute of its parent (td_out_parent) */
    TD_OUT_FIELD = 3,     /**< a field of the /events compound (and a column of the CSV events file) */
    TD_OUT_CSV_ONLY = 4   /**< a line or column only the CSV file has */
} td_out_place;

/** Type in the file (HDF5). */
typedef enum td_out_type {
    TD_OUT_NO_TYPE = 0, /**< a group */
    TD_OUT_F64 = 1,
    TD_OUT_I64 = 2,
    TD_OUT_I32 = 3,
    TD_OUT_I8 = 4,
    TD_OUT_TEXT = 5,    /**< variable-length UTF-8 */
    TD_OUT_ENUM = 6,    /**< the event kind (int32 enum) */
    TD_OUT_COMPOUND = 7 /**< /events */
} td_out_type;

/** Which files hold a name (a bit set). */
enum { TD_OUT_IN_RUN = 1, TD_OUT_IN_RUN_CSV = 2, TD_OUT_IN_MODAL = 4, TD_OUT_IN_SWEEP = 8 };

/** The name itself: the link or attribute name, never a path ("x" of /retainers/x); "" for the
 *  root; NULL for an id out of range. */
TD_API const char *td_out_name(td_out_id id);
/** The units: what the dataset's `units` attribute says, for an attribute or field its unit in
 *  docs/output-format.md; "" when it has none. NULL for an id out of range. */
TD_API const char *td_out_units(td_out_id id);
/** The shape, in the words of docs/output-format.md ("(N, n_ret)", "scalar"); never NULL. */
TD_API const char *td_out_shape(td_out_id id);
/** What `id` is in the file (group, dataset, attribute, event field, CSV line or column);
 *  TD_OUT_NO_PLACE for an id out of range. */
TD_API td_out_place td_out_place_of(td_out_id id);
/** Its type in the HDF5 file (a CSV-only name: TD_OUT_TEXT); TD_OUT_NO_TYPE for a group and for an
 *  id out of range. */
TD_API td_out_type td_out_type_of(td_out_id id);
/** The files that hold it, TD_OUT_IN_* bits; 0 for an id out of range. */
TD_API unsigned td_out_files(td_out_id id);
/** The group a dataset or group is in, the object an attribute is on (TD_OUT_ID_COUNT: several,
 *  e.g. `units`), /events for a field; TD_OUT_ID_COUNT for an id out of range. */
TD_API td_out_id td_out_parent(td_out_id id);
/**
 * The path from the root ("retainers/x"; an attribute: its object's path) into buf; `sub`, when
 * not NULL, is appended after a '/' (a swept key under TD_OUT_SWEEP_VARY, the index I under
 * TD_OUT_HARMONIC_I). Returns the length snprintf would, -1 for an id out of range.
 */
TD_API int td_out_path(td_out_id id, const char *sub, char *buf, size_t n);
/**
 * The id of the name `name` that is a `place` (group, dataset, attribute, ...) in one of the files
 * `files` (TD_OUT_IN_* bits): the lookup of a name stored or exchanged, e.g. a quantity a report
 * lists, which an older or newer schema may lack. TD_OUT_ID_COUNT when this schema declares no such
 * name (also for a NULL name).
 */
TD_API td_out_id td_out_find(const char *name, td_out_place place, unsigned files);

/* ---- reading -------------------------------------------------------------------------------- */

/** An open result file (opaque): td_result_open, td_result_free. One handle is not to be used
 *  from two threads at once. */
typedef struct td_result td_result;

typedef enum td_result_kind {
    TD_RESULT_NO_KIND = -1, /**< no file: td_result_get_kind(NULL) */
    TD_RESULT_RUN = 0,      /**< td_run / touchdown run */
    TD_RESULT_MODAL = 1,    /**< td_modal_write_hdf5 / touchdown modal */
    TD_RESULT_SWEEP = 2     /**< td_sweep_write_hdf5 / touchdown sweep */
} td_result_kind;

/** The completeness flag as the file holds it. */
typedef enum td_result_flag {
    TD_RESULT_NO_FLAG = -1,   /**< no `complete` attribute: a file still written or killed (.partial) */
    TD_RESULT_INCOMPLETE = 0, /**< complete = 0: see the attribute incomplete_reason */
    TD_RESULT_COMPLETE = 1
} td_result_flag;

/**
 * Open the HDF5 file `path` for reading and say what it is.
 *
 * path   the file (borrowed for the call; the handle keeps its own copy).
 * out    receives the new handle, which keeps the file open until td_result_free; set to NULL on
 *        failure.
 * err    may be NULL.
 *
 * Returns TD_OK; TD_ERR_IO for a file that cannot be read (missing, not HDF5, damaged or cut
 * short); TD_ERR_INVALID for an HDF5 file that is none of touchdown's (a run file has /time and
 * /retainers, a sweep table /point and /vary, a modal file the producer attribute or /campbell or
 * /modes), and for a NULL out or a NULL or empty path; TD_ERR_NOMEM.
 */
TD_API td_status td_result_open(const char *path, td_result **out, td_error *err);
/** Close; *r set to NULL. Accepts NULL and *r == NULL. */
TD_API void td_result_free(td_result **r);

/** Which file it is; TD_RESULT_NO_KIND for a NULL handle. */
TD_API td_result_kind td_result_get_kind(const td_result *r);
/** The flag (TD_RESULT_COMPLETE for a modal file: one is written whole or not at all);
 *  TD_RESULT_NO_FLAG for a NULL handle. */
TD_API td_result_flag td_result_get_flag(const td_result *r);
/**
 * 1 only for a whole result: flag 1 (a modal file: readable), and a name that is not a writer's
 * temporary PATH.XXXXXX.partial; else 0 (also for a NULL handle).
 */
TD_API int td_result_complete(const td_result *r);

/** 1 if `id` (with `sub`, see td_out_path) exists in the file: a group, a dataset, an attribute;
 *  0 otherwise, and for a NULL handle or an id out of range. */
TD_API int td_result_has(const td_result *r, td_out_id id, const char *sub);

/** A dataset or numeric attribute read as doubles, row-major (missing dims are 1). */
typedef struct td_result_array {
    double *v;       /**< n values, malloc'd (td_result_array_free) */
    size_t n;        /**< product of the dims */
    int rank;        /**< 0 (a scalar attribute) to 3 */
    size_t dims[3];  /**< unused dims are 1 */
    char units[128]; /**< the dataset's units attribute, else the schema's (td_out_units) */
} td_result_array;

/**
 * Read a numeric dataset (TD_OUT_DATASET: rank 1..3, any integer or float type) or a numeric
 * attribute (TD_OUT_ATTRIBUTE, on the object td_out_path names) as doubles into *a, which then
 * owns its values (td_result_array_free). `sub` as for td_out_path (TD_OUT_ROOT with `sub` reads
 * any dataset by its path, e.g. a sweep column named by the user).
 *
 * Returns TD_OK; TD_ERR_INVALID for a NULL a or r, an id out of range, a path too long, and a
 * name that is absent, not numeric or unreadable (the message names the file and the object). On
 * failure *a is all zero (nothing to free).
 */
TD_API td_status td_result_read(const td_result *r, td_out_id id, const char *sub, td_result_array *a, td_error *err);
/** Free the values of *a and set every field of it to zero (so a second call is harmless).
 *  Accepts NULL. */
TD_API void td_result_array_free(td_result_array *a);

/**
 * A text attribute (any string type; `id` a TD_OUT_ATTRIBUTE, on the object td_out_path names
 * with `sub`), malloc'd into *text (the caller frees it with free()).
 *
 * Returns TD_OK; TD_ERR_INVALID for a NULL text or r, an id that is no attribute, a path too
 * long, and an attribute that is absent or not text (the message names the file, the attribute
 * and its object). On failure *text is NULL.
 */
TD_API td_status td_result_read_text(const td_result *r, td_out_id id, const char *sub, char **text, td_error *err);

/**
 * A dataset of variable-length strings (`id` with `sub` as for td_out_path; the text columns of a
 * sweep table are 1-D), its values in row-major order: *n malloc'd strings in *text, a NULL
 * string read as "" (td_result_strings_free frees them).
 *
 * Returns TD_OK; TD_ERR_INVALID for a NULL text, n or r, an id that is an attribute or out of
 * range, a path too long, and a dataset that is absent, not of variable-length strings or
 * unreadable (the message names the file and the dataset). On failure *text is NULL and *n 0.
 */
TD_API td_status td_result_read_strings(const td_result *r, td_out_id id, const char *sub, char ***text, size_t *n,
                                        td_error *err);
/** Free the n strings of `text` and the array itself (td_result_read_strings,
 *  td_result_columns). Accepts NULL. */
TD_API void td_result_strings_free(char **text, size_t n);

/**
 * The numeric 1-D datasets of n values directly in the group `id` (+ `sub`), other than its
 * dimension scales' index TD_OUT_SWEEP_POINT, in name order: *n_names malloc'd names
 * (td_result_strings_free). The columns of a sweep table: TD_OUT_ROOT with n = the points.
 *
 * Returns TD_OK (no such dataset: *n_names 0); TD_ERR_INVALID for a NULL names, n_names or r, an
 * id that is no group, a path too long, and a group that is absent (the message names the file
 * and the group); TD_ERR_NOMEM. On failure *names is NULL and *n_names 0.
 */
TD_API td_status td_result_columns(const td_result *r, td_out_id id, const char *sub, size_t n, char ***names,
                                   size_t *n_names, td_error *err);

/** One row of /events. */
typedef struct td_result_event {
    td_event event;
    long sample;        /**< the sample row taken at the event, -1 if none */
    char kind_name[32]; /**< the kind's name as the file's enum has it ("contact_onset", ...) */
} td_result_event;

/**
 * Every row of a run file's /events, malloc'd into *events (the caller frees it with free()), their
 * number in *n: 0 rows (and *events NULL) when the file has no /events. A run that had no event and
 * one that omitted them (output.events = false: no /events, its summary attributes still count
 * them) both give 0 rows here; td_result_has(r, TD_OUT_EVENTS, NULL) tells the two apart.
 *
 * Returns TD_OK; TD_ERR_INVALID for a NULL events, n or r, and an /events table that cannot be
 * read (the message names the file). On failure *events is NULL and *n 0.
 */
TD_API td_status td_result_events(const td_result *r, td_result_event **events, size_t *n, td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_RESULT_H */
