/*
 * The output schema (schema.h, touchdown/result.h): every name of the files touchdown writes,
 * declared once, with its units, shape and type. docs/output-format.md describes each.
 */
#include "io/schema.h"

#include <stdio.h>
#include <string.h>

#define RUN (TD_OUT_IN_RUN | TD_OUT_IN_RUN_CSV)
#define H5RUN TD_OUT_IN_RUN
#define CSVRUN TD_OUT_IN_RUN_CSV
#define MODAL TD_OUT_IN_MODAL
#define SWEEP TD_OUT_IN_SWEEP
#define SEVERAL TD_OUT_ID_COUNT

/* One entry, by id (designated initialisers: an id cannot land on another's entry). */
#define GROUP(id, name, parent, files) [id] = {name, parent, TD_OUT_GROUP, files, TD_OUT_NO_TYPE, "", "", NULL, NULL}
#define DATA(id, name, parent, files, type, units, shape)                                                              \
    [id] = {name, parent, TD_OUT_DATASET, files, TD_OUT_##type, units, shape, NULL, NULL}
/* A dataset of the modal file whose column in the modal CSV file has a name of its own. */
#define DATA_CSV(id, name, parent, type, units, shape, csv)                                                            \
    [id] = {name, parent, TD_OUT_DATASET, MODAL, TD_OUT_##type, units, shape, csv, NULL}
#define SERIES(id, name, parent, type, units, shape, csv, csv_units)                                                   \
    [id] = {name, parent, TD_OUT_DATASET, RUN, TD_OUT_##type, units, shape, csv, csv_units}
#define ATTR(id, name, parent, files, type, units, shape)                                                              \
    [id] = {name, parent, TD_OUT_ATTRIBUTE, files, TD_OUT_##type, units, shape, NULL, NULL}
#define FIELD(id, name, type, units, csv, csv_units)                                                                   \
    [id] = {name, TD_OUT_EVENTS, TD_OUT_FIELD, RUN, TD_OUT_##type, units, "(E)", csv, csv_units}
#define CSV_LINE(id, name, files) [id] = {name, TD_OUT_ROOT, TD_OUT_CSV_ONLY, files, TD_OUT_TEXT, "", "", NULL, NULL}
/* Root attributes of a run's files (HDF5 and CSV), scalar unless a shape is given. */
#define RUN_ATTR(id, name, type, units) ATTR(id, name, TD_OUT_ROOT, RUN, type, units, "scalar")
#define RET_ATTR(id, name, type, units) ATTR(id, name, TD_OUT_ROOT, RUN, type, units, "(n_ret)")
#define MODE_TABLE(prefix, group, shape)                                                                               \
    DATA_CSV(prefix##SIGMA, "sigma", group, F64, "1/s", shape, "sigma_1_s"),                                           \
        DATA_CSV(prefix##OMEGA_D, "omega_d", group, F64, "rad/s", shape, "omega_d_rad_s"),                             \
        DATA(prefix##FREQ_HZ, "freq_hz", group, MODAL, F64, "Hz", shape),                                              \
        DATA_CSV(prefix##OMEGA_N, "omega_n", group, F64, "rad/s", shape, "omega_n_rad_s"),                             \
        DATA(prefix##ZETA, "zeta", group, MODAL, F64, "1", shape),                                                     \
        DATA(prefix##WHIRL_INDEX, "whirl_index", group, MODAL, F64, "1", shape),                                       \
        DATA(prefix##WHIRL, "whirl", group, MODAL, I32, "1: forward, -1: backward, 0: mixed", shape)
#define COLUMN(id, name, type, units) DATA(id, name, TD_OUT_ROOT, SWEEP, type, units, "(points)")
#define SHAPE_UNITS "1 (normalised: largest |X| or |Y| = 1); rows: modes, columns: nodes"
#define STATE_UNITS "SI per state: m, m/s, N"

static const td_schema_entry entries[TD_OUT_ID_COUNT] = {
    [TD_OUT_ROOT] = {"", TD_OUT_ROOT, TD_OUT_GROUP, RUN | MODAL | SWEEP, TD_OUT_NO_TYPE,
                     "SI (touchdown/dofs.h); each dataset has a units attribute", "", NULL, NULL},
    /* ---- run file: groups, samples, scales ---- */
    GROUP(TD_OUT_NODES, "nodes", TD_OUT_ROOT, H5RUN),
    GROUP(TD_OUT_RETAINERS, "retainers", TD_OUT_ROOT, H5RUN),
    GROUP(TD_OUT_AMBS, "ambs", TD_OUT_ROOT, H5RUN),
    SERIES(TD_OUT_TIME, "time", TD_OUT_ROOT, F64, "s", "(N)", "t", NULL),
    SERIES(TD_OUT_SPEED, "speed", TD_OUT_ROOT, F64, "rad/s", "(N)", NULL, NULL),
    DATA(TD_OUT_COMPONENT, "component", TD_OUT_ROOT, H5RUN, TEXT, "1", "(2)"),
    SERIES(TD_OUT_NODE_DISPLACEMENT, "displacement", TD_OUT_NODES, F64, "m", "(N, n_nodes, 2)", "%s_n%d", NULL),
    DATA(TD_OUT_NODE, "node", TD_OUT_NODES, H5RUN, I32, "node number", "(n_nodes)"),
    SERIES(TD_OUT_RET_X, "x", TD_OUT_RETAINERS, F64, "m", "(N, n_ret)", "x_ret%d", NULL),
    SERIES(TD_OUT_RET_Y, "y", TD_OUT_RETAINERS, F64, "m", "(N, n_ret)", "y_ret%d", NULL),
    SERIES(TD_OUT_RET_RADIAL_POSITION, "radial_position", TD_OUT_RETAINERS, F64, "m", "(N, n_ret)", "r_ret%d", NULL),
    SERIES(TD_OUT_RET_RADIAL_VELOCITY, "radial_velocity", TD_OUT_RETAINERS, F64, "m/s", "(N, n_ret)", "vr_ret%d", NULL),
    SERIES(TD_OUT_RET_WHIRL_ANGLE, "whirl_angle", TD_OUT_RETAINERS, F64, "rad", "(N, n_ret)", "theta_ret%d", NULL),
    SERIES(TD_OUT_RET_NORMAL_FORCE, "normal_force", TD_OUT_RETAINERS, F64, "N", "(N, n_ret)", "N_ret%d", NULL),
    SERIES(TD_OUT_RET_FRICTION_FORCE, "friction_force", TD_OUT_RETAINERS, F64, "N", "(N, n_ret)", "Ff_ret%d", NULL),
    SERIES(TD_OUT_RET_SLIDING_VELOCITY, "sliding_velocity", TD_OUT_RETAINERS, F64, "m/s", "(N, n_ret)", "vs_ret%d",
           NULL),
    SERIES(TD_OUT_RET_CONTACT_STATE, "contact_state", TD_OUT_RETAINERS, I8, "1", "(N, n_ret)", "contact_ret%d", "-"),
    SERIES(TD_OUT_RET_RACE_X, "race_x", TD_OUT_RETAINERS, F64, "m", "(N, n_ret)", "xr_ret%d", NULL),
    SERIES(TD_OUT_RET_RACE_Y, "race_y", TD_OUT_RETAINERS, F64, "m", "(N, n_ret)", "yr_ret%d", NULL),
    SERIES(TD_OUT_RET_RACE_SPEED, "race_speed", TD_OUT_RETAINERS, F64, "rad/s", "(N, n_ret)", "wr_ret%d", NULL),
    SERIES(TD_OUT_RET_ROLLING, "rolling", TD_OUT_RETAINERS, I8, "1", "(N, n_ret)", "rolling_ret%d", "-"),
    SERIES(TD_OUT_RET_WHIRL_RATE, "whirl_rate", TD_OUT_RETAINERS, F64, "rad/s", "(N, n_ret)", "dtheta_ret%d", NULL),
    DATA(TD_OUT_RETAINER, "retainer", TD_OUT_RETAINERS, H5RUN, I32, "retainer index", "(n_ret)"),
    SERIES(TD_OUT_AMB_FORCE, "force", TD_OUT_AMBS, F64, "N", "(N, n_amb, 2)", "F%s_amb%d", NULL),
    DATA(TD_OUT_AMB, "amb", TD_OUT_AMBS, H5RUN, I32, "AMB index", "(n_amb)"),
    DATA(TD_OUT_EVENTS, "events", TD_OUT_ROOT, H5RUN, COMPOUND,
         "time: s; radial_velocity_*, tangential_velocity_*: m/s; impulse: N s; normal_force, peak_normal_force: N",
         "(E)"),
    DATA(TD_OUT_EVENT, "event", TD_OUT_ROOT, H5RUN, I64, "1 (row number of /events)", "(E)"),
    /* ---- run file: the events ---- */
    FIELD(TD_OUT_EV_TIME, "time", F64, "s", "t", NULL),
    FIELD(TD_OUT_EV_KIND, "kind", ENUM, "", NULL, "-"),
    [TD_OUT_EV_KIND_NAME] = {"kind_name", TD_OUT_EVENTS, TD_OUT_CSV_ONLY, CSVRUN, TD_OUT_TEXT, "", "(E)", NULL, NULL},
    FIELD(TD_OUT_EV_RETAINER, "retainer", I32, "", NULL, "-"),
    FIELD(TD_OUT_EV_CHANGE, "change", I32, "", NULL, "-"),
    FIELD(TD_OUT_EV_SAMPLE, "sample", I64, "", NULL, "-"),
    FIELD(TD_OUT_EV_RADIAL_VELOCITY_BEFORE, "radial_velocity_before", F64, "m/s", "vr_before", NULL),
    FIELD(TD_OUT_EV_RADIAL_VELOCITY_AFTER, "radial_velocity_after", F64, "m/s", "vr_after", NULL),
    FIELD(TD_OUT_EV_TANGENTIAL_VELOCITY_BEFORE, "tangential_velocity_before", F64, "m/s", "vt_before", NULL),
    FIELD(TD_OUT_EV_TANGENTIAL_VELOCITY_AFTER, "tangential_velocity_after", F64, "m/s", "vt_after", NULL),
    FIELD(TD_OUT_EV_IMPULSE, "impulse", F64, "N s", NULL, NULL),
    FIELD(TD_OUT_EV_NORMAL_FORCE, "normal_force", F64, "N", "N", NULL),
    FIELD(TD_OUT_EV_PEAK_NORMAL_FORCE, "peak_normal_force", F64, "N", "peak_N", NULL),
    FIELD(TD_OUT_EV_CONTROLLER, "controller", I32, "", NULL, "-"),
    FIELD(TD_OUT_EV_SENSED_RADIUS, "sensed_radius", F64, "m", "r_sensed", NULL),
    /* ---- attributes of datasets and groups ---- */
    ATTR(TD_OUT_UNITS, "units", SEVERAL, H5RUN | MODAL | SWEEP, TEXT, "", "scalar"),
    ATTR(TD_OUT_COUNT, "count", SEVERAL, H5RUN, I32, "", "scalar"),
    ATTR(TD_OUT_NODES_ATTR, "nodes", TD_OUT_NODE_DISPLACEMENT, H5RUN, I32, "", "(n_nodes)"),
    ATTR(TD_OUT_COMPONENTS, "components", SEVERAL, H5RUN, TEXT, "", "scalar"),
    ATTR(TD_OUT_KIND_NAMES, "kind_names", TD_OUT_EVENTS, H5RUN, TEXT, "", "scalar"),
    /* ---- root attributes shared by the files ---- */
    ATTR(TD_OUT_COMPLETE, "complete", TD_OUT_ROOT, RUN | SWEEP, I32, "", "scalar"),
    ATTR(TD_OUT_INCOMPLETE_REASON, "incomplete_reason", TD_OUT_ROOT, RUN | SWEEP, TEXT, "", "scalar"),
    ATTR(TD_OUT_CASE_TEXT, "case_text", TD_OUT_ROOT, RUN | MODAL | SWEEP, TEXT, "", "scalar"),
    ATTR(TD_OUT_LIBRARY_VERSION, "library_version", TD_OUT_ROOT, RUN | SWEEP, TEXT, "", "scalar"),
    /* ---- run file: root attributes ---- */
    RUN_ATTR(TD_OUT_STATUS, "status", TEXT, ""),
    RUN_ATTR(TD_OUT_SAMPLE_RATE, "sample_rate", F64, "Hz"),
    RUN_ATTR(TD_OUT_T_START, "t_start", F64, "s"),
    RUN_ATTR(TD_OUT_T_END, "t_end", F64, "s"),
    RUN_ATTR(TD_OUT_T_REACHED, "t_reached", F64, "s"),
    RUN_ATTR(TD_OUT_MODEL_SPEED, "speed", F64, "rad/s"),
    RET_ATTR(TD_OUT_RETAINER_NODES, "retainer_nodes", I64, ""),
    RET_ATTR(TD_OUT_RETAINER_CLEARANCE, "retainer_clearance", F64, "m"),
    RET_ATTR(TD_OUT_RETAINER_IMPULSE, "retainer_impulse", F64, "N s"),
    RET_ATTR(TD_OUT_RETAINER_IMPACT_IMPULSE, "retainer_impact_impulse", F64, "N s"),
    RET_ATTR(TD_OUT_RETAINER_FRICTION_WORK, "retainer_friction_work", F64, "J"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_HOUSING_FORCE, "retainer_peak_housing_force", F64, "N"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_NORMAL_FORCE, "retainer_peak_normal_force", F64, "N"),
    RET_ATTR(TD_OUT_RETAINER_CONTACT_TIME, "retainer_contact_time", F64, "s"),
    RET_ATTR(TD_OUT_RETAINER_ROLLING_TIME, "retainer_rolling_time", F64, "s"),
    RET_ATTR(TD_OUT_RETAINER_CONTACTS, "retainer_contacts", I64, ""),
    RET_ATTR(TD_OUT_RETAINER_TOUCH_AND_GO, "retainer_touch_and_go", I64, ""),
    /* life */
    RET_ATTR(TD_OUT_RETAINER_DAMAGE, "retainer_damage", F64, "1"),
    RET_ATTR(TD_OUT_RETAINER_DROPS_TO_FAILURE, "retainer_drops_to_failure", F64, "1"),
    RET_ATTR(TD_OUT_RETAINER_LOAD_CYCLES, "retainer_load_cycles", F64, "1"),
    ATTR(TD_OUT_AMB_NODES, "amb_nodes", TD_OUT_ROOT, RUN, I64, "", "(n_amb)"),
    ATTR(TD_OUT_AMB_CAPACITY, "amb_capacity", TD_OUT_ROOT, RUN, F64, "N", "(n_amb)"),
    RUN_ATTR(TD_OUT_STAT_STEPS, "steps", I64, ""),
    RUN_ATTR(TD_OUT_STAT_RESIDUAL_EVALS, "residual_evals", I64, ""),
    RUN_ATTR(TD_OUT_STAT_JACOBIAN_EVALS, "jacobian_evals", I64, ""),
    RUN_ATTR(TD_OUT_STAT_LINEAR_SETUPS, "linear_setups", I64, ""),
    RUN_ATTR(TD_OUT_STAT_NONLINEAR_ITERS, "nonlinear_iters", I64, ""),
    RUN_ATTR(TD_OUT_STAT_ERROR_TEST_FAILS, "error_test_fails", I64, ""),
    RUN_ATTR(TD_OUT_STAT_NONLINEAR_FAILS, "nonlinear_fails", I64, ""),
    RUN_ATTR(TD_OUT_STAT_RESTARTS, "restarts", I64, ""),
    RUN_ATTR(TD_OUT_STAT_EVENTS, "events", I64, ""),
    RUN_ATTR(TD_OUT_STAT_CONTACT_ONSETS, "contact_onsets", I64, ""),
    RUN_ATTR(TD_OUT_STAT_RELEASES, "releases", I64, ""),
    RUN_ATTR(TD_OUT_STAT_PEAK_AMB, "peak_amb", I64, ""),
    RUN_ATTR(TD_OUT_STAT_FLIGHT_STEPS, "flight_steps", I64, ""),
    RUN_ATTR(TD_OUT_STAT_WORST_DRIFT, "worst_drift", F64, "m"),
    RUN_ATTR(TD_OUT_STAT_PEAK_NORMAL_FORCE, "peak_normal_force", F64, "N"),
    RUN_ATTR(TD_OUT_STAT_TIME_IN_CONTACT, "time_in_contact", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_FIRST_CONTACT_TIME, "first_contact_time", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_WALL_TIME, "wall_time", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_PEAK_AMB_FORCE, "peak_amb_force", F64, "N"),
    RUN_ATTR(TD_OUT_STAT_PEAK_AMB_LOAD, "peak_amb_load", F64, "1"),
    RUN_ATTR(TD_OUT_STAT_PEAK_AMB_TIME, "peak_amb_time", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_FLIGHT_TIME, "flight_time", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_CONTROLLER_SAMPLES, "controller_samples", I64, ""),
    RUN_ATTR(TD_OUT_STAT_TIME_SLEWING, "time_slewing", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_CONTROLLER_SWITCHES, "controller_switches", I64, ""),
    RUN_ATTR(TD_OUT_STAT_TIME_ON_RECOVERY, "time_on_recovery", F64, "s"),
    RUN_ATTR(TD_OUT_STAT_LAST_RETURN_TIME, "last_return_time", F64, "s"),
    RUN_ATTR(TD_OUT_WARNINGS, "warnings", TEXT, ""),
    RUN_ATTR(TD_OUT_SUM_FIRST_CONTACT_TIME, "summary_first_contact_time", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_LAST_CONTACT_TIME, "summary_last_contact_time", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_PEAK_NORMAL_FORCE, "summary_peak_normal_force", F64, "N"),
    RUN_ATTR(TD_OUT_SUM_PEAK_HOUSING_FORCE, "summary_peak_housing_force", F64, "N"),
    RUN_ATTR(TD_OUT_SUM_TOTAL_IMPULSE, "summary_total_impulse", F64, "N s"),
    RUN_ATTR(TD_OUT_SUM_FRICTION_WORK, "summary_friction_work", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_FINAL_SPEED, "summary_final_speed", F64, "rad/s"),
    RUN_ATTR(TD_OUT_SUM_ENDING_WHIRL_FREQUENCY, "summary_ending_whirl_frequency", F64, "Hz"),
    RUN_ATTR(TD_OUT_SUM_ENDING_WINDOW, "summary_ending_window", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_CONTACT_TIME, "summary_contact_time", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_CONTACT_FRACTION, "summary_contact_fraction", F64, "1"),
    RUN_ATTR(TD_OUT_SUM_FREE_WINDOW, "summary_free_window", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_REVOLUTIONS, "summary_revolutions", F64, ""),
    RUN_ATTR(TD_OUT_SUM_REVOLUTIONS_AFTER_CONTACT, "summary_revolutions_after_contact", F64, ""),
    RUN_ATTR(TD_OUT_SUM_WALL_TIME, "summary_wall_time", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_SOLVER_WALL_TIME, "summary_solver_wall_time", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_WALL_TIME_PER_REVOLUTION, "summary_wall_time_per_revolution", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_REALTIME_FACTOR, "summary_realtime_factor", F64, "1"),
    RUN_ATTR(TD_OUT_SUM_SAMPLES, "summary_samples", I64, ""),
    RUN_ATTR(TD_OUT_SUM_GRID_SAMPLES, "summary_grid_samples", I64, ""),
    RUN_ATTR(TD_OUT_SUM_EVENTS, "summary_events", I64, ""),
    RUN_ATTR(TD_OUT_SUM_CONTACTS, "summary_contacts", I64, ""),
    RUN_ATTR(TD_OUT_SUM_ENDING, "summary_ending", TEXT, ""),
    RUN_ATTR(TD_OUT_SUM_FREE_AT_END, "summary_free_at_end", F64, ""),
    RUN_ATTR(TD_OUT_SUM_RETURNED_TO_FREE_ORBIT, "summary_returned_to_free_orbit", F64, ""),
    RUN_ATTR(TD_OUT_SUM_PEAK_NORMAL_FORCE_CONVERGES, "summary_peak_normal_force_converges", I64, ""),
    RUN_ATTR(TD_OUT_SUM_ENERGY_KINETIC, "summary_energy_kinetic", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_ELASTIC, "summary_energy_elastic", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_INITIAL, "summary_energy_initial", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_EXTERNAL_WORK, "summary_energy_external_work", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_DRIVE_WORK, "summary_energy_drive_work", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_DAMPING_LOSS, "summary_energy_damping_loss", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_CONTACT_LOSS, "summary_energy_contact_loss", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_DRAG_LOSS, "summary_energy_drag_loss", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_IMPACT_LOSS, "summary_energy_impact_loss", F64, "J"),
    RUN_ATTR(TD_OUT_SUM_ENERGY_RESIDUAL, "summary_energy_residual", F64, "J"),
    RUN_ATTR(TD_OUT_SECTION_START, "section_start", F64, "s"),
    RUN_ATTR(TD_OUT_SECTION_COUNT, "section_count", I64, ""),
    RUN_ATTR(TD_OUT_SECTION_RETAINER, "section_retainer", I64, ""),
    RUN_ATTR(TD_OUT_SECTION_CLEARANCE, "section_clearance", F64, "m"),
    ATTR(TD_OUT_SECTION_TIME, "section_time", TD_OUT_ROOT, RUN, F64, "s", "(kept crossings)"),
    ATTR(TD_OUT_SECTION_RADIUS, "section_radius", TD_OUT_ROOT, RUN, F64, "m", "(kept crossings)"),
    /* ---- modal file ---- */
    ATTR(TD_OUT_PRODUCER, "producer", TD_OUT_ROOT, MODAL, TEXT, "", "scalar"),
    GROUP(TD_OUT_MODES, "modes", TD_OUT_ROOT, MODAL),
    [TD_OUT_MODES_SPEED] = {"speed", TD_OUT_MODES, TD_OUT_ATTRIBUTE, MODAL, TD_OUT_F64, "rad/s", "scalar",
                            "speed_rad_s", NULL},
    ATTR(TD_OUT_MODES_SPEED_UNITS, "speed_units", TD_OUT_MODES, MODAL, TEXT, "", "scalar"),
    MODE_TABLE(TD_OUT_MODES_, TD_OUT_MODES, "(modes)"),
    DATA_CSV(TD_OUT_MODES_REAL_EIGENVALUES, "real_eigenvalues", TD_OUT_MODES, F64, "1/s", "(real roots)", "s_1_s"),
    DATA_CSV(TD_OUT_MODES_SHAPE_X_RE, "shape_x_re", TD_OUT_MODES, F64, SHAPE_UNITS, "(modes, nodes)", "x_re"),
    DATA_CSV(TD_OUT_MODES_SHAPE_X_IM, "shape_x_im", TD_OUT_MODES, F64, SHAPE_UNITS, "(modes, nodes)", "x_im"),
    DATA_CSV(TD_OUT_MODES_SHAPE_Y_RE, "shape_y_re", TD_OUT_MODES, F64, SHAPE_UNITS, "(modes, nodes)", "y_re"),
    DATA_CSV(TD_OUT_MODES_SHAPE_Y_IM, "shape_y_im", TD_OUT_MODES, F64, SHAPE_UNITS, "(modes, nodes)", "y_im"),
    DATA(TD_OUT_MODES_MODE, "mode", TD_OUT_MODES, MODAL, I32, "mode number", "(modes)"),
    DATA(TD_OUT_MODES_NODE_Z, "node_z", TD_OUT_MODES, MODAL, F64, "m", "(nodes)"),
    DATA(TD_OUT_MODES_RETAINER_NODES, "retainer_nodes", TD_OUT_MODES, MODAL, I32, "node", "(n_ret)"),
    DATA(TD_OUT_MODES_AMB_NODES, "amb_nodes", TD_OUT_MODES, MODAL, I32, "node", "(n_amb)"),
    GROUP(TD_OUT_CAMPBELL, "campbell", TD_OUT_ROOT, MODAL),
    MODE_TABLE(TD_OUT_CAMPBELL_, TD_OUT_CAMPBELL, "(speeds, branches)"),
    DATA_CSV(TD_OUT_CAMPBELL_SPEED, "speed", TD_OUT_CAMPBELL, F64, "rad/s", "(speeds)", "speed_rad_s"),
    DATA(TD_OUT_CAMPBELL_BRANCH, "branch", TD_OUT_CAMPBELL, MODAL, I32,
         "branch number (the j-th lowest omega_d at speed_min, tracked by MAC)", "(branches)"),
    DATA_CSV(TD_OUT_CAMPBELL_MAC, "mac", TD_OUT_CAMPBELL, F64, "1 (MAC to the previous speed's point; NaN: none)",
             "(speeds, branches)", "mac"),
    ATTR(TD_OUT_CAMPBELL_LAYOUT, "layout", TD_OUT_CAMPBELL, MODAL, TEXT, "", "scalar"),
    GROUP(TD_OUT_CRITICAL, "critical_speeds", TD_OUT_ROOT, MODAL),
    DATA_CSV(TD_OUT_CRITICAL_SPEED, "speed", TD_OUT_CRITICAL, F64, "rad/s", "(critical speeds)", "speed_rad_s"),
    DATA(TD_OUT_CRITICAL_FREQ_HZ, "freq_hz", TD_OUT_CRITICAL, MODAL, F64, "Hz", "(critical speeds)"),
    DATA(TD_OUT_CRITICAL_ZETA, "zeta", TD_OUT_CRITICAL, MODAL, F64, "1", "(critical speeds)"),
    DATA_CSV(TD_OUT_CRITICAL_SIGMA, "sigma", TD_OUT_CRITICAL, F64, "1/s", "(critical speeds)", "sigma_1_s"),
    DATA(TD_OUT_CRITICAL_WHIRL, "whirl", TD_OUT_CRITICAL, MODAL, I32, "1: forward, -1: backward", "(critical speeds)"),
    DATA(TD_OUT_CRITICAL_BRANCH, "branch", TD_OUT_CRITICAL, MODAL, I32, "index among modes of that whirl",
         "(critical speeds)"),
    GROUP(TD_OUT_HARMONIC, "harmonic", TD_OUT_ROOT, MODAL),
    GROUP(TD_OUT_HARMONIC_I, "", TD_OUT_HARMONIC, MODAL),
    [TD_OUT_HARMONIC_SPEED] = {"speed", TD_OUT_HARMONIC_I, TD_OUT_ATTRIBUTE, MODAL, TD_OUT_F64, "rad/s", "scalar",
                               "speed_rad_s", NULL},
    ATTR(TD_OUT_HARMONIC_SPEED_UNITS, "speed_units", TD_OUT_HARMONIC_I, MODAL, TEXT, "", "scalar"),
    DATA_CSV(TD_OUT_HARMONIC_X_AMP, "x_amp", TD_OUT_HARMONIC_I, F64, "m", "(nodes)", "x_amp_m"),
    DATA_CSV(TD_OUT_HARMONIC_X_PHASE, "x_phase", TD_OUT_HARMONIC_I, F64, "rad", "(nodes)", "x_phase_rad"),
    DATA_CSV(TD_OUT_HARMONIC_Y_AMP, "y_amp", TD_OUT_HARMONIC_I, F64, "m", "(nodes)", "y_amp_m"),
    DATA_CSV(TD_OUT_HARMONIC_Y_PHASE, "y_phase", TD_OUT_HARMONIC_I, F64, "rad", "(nodes)", "y_phase_rad"),
    DATA_CSV(TD_OUT_HARMONIC_FORWARD, "forward", TD_OUT_HARMONIC_I, F64, "m", "(nodes)", "forward_m"),
    DATA_CSV(TD_OUT_HARMONIC_BACKWARD, "backward", TD_OUT_HARMONIC_I, F64, "m", "(nodes)", "backward_m"),
    DATA_CSV(TD_OUT_HARMONIC_MAJOR, "major", TD_OUT_HARMONIC_I, F64, "m", "(nodes)", "major_m"),
    DATA_CSV(TD_OUT_HARMONIC_MINOR, "minor", TD_OUT_HARMONIC_I, F64, "m", "(nodes)", "minor_m"),
    DATA(TD_OUT_HARMONIC_STATE_RE, "state_re", TD_OUT_HARMONIC_I, MODAL, F64, STATE_UNITS, "(states)"),
    DATA(TD_OUT_HARMONIC_STATE_IM, "state_im", TD_OUT_HARMONIC_I, MODAL, F64, STATE_UNITS, "(states)"),
    DATA(TD_OUT_HARMONIC_NODE, "node", TD_OUT_HARMONIC_I, MODAL, I32, "node number", "(nodes)"),
    DATA(TD_OUT_HARMONIC_STATE, "state", TD_OUT_HARMONIC_I, MODAL, I32, "state index", "(states)"),
    CSV_LINE(TD_OUT_MODAL_MODE_SHAPES, "mode_shapes", MODAL),
    CSV_LINE(TD_OUT_MODAL_INDEX, "index", MODAL),
    CSV_LINE(TD_OUT_MODAL_NODE, "node", MODAL),
    /* ---- modal file: the loop analysis (td_loop_compute; docs/theory.md, "Sensitivity") ---- */
    GROUP(TD_OUT_LOOP, "loop", TD_OUT_ROOT, MODAL),
    [TD_OUT_LOOP_SPEED] = {"speed", TD_OUT_LOOP, TD_OUT_ATTRIBUTE, MODAL, TD_OUT_F64, "rad/s", "scalar", "speed_rad_s",
                           NULL},
    ATTR(TD_OUT_LOOP_SPEED_UNITS, "speed_units", TD_OUT_LOOP, MODAL, TEXT, "", "scalar"),
    ATTR(TD_OUT_LOOP_STABLE, "stable", TD_OUT_LOOP, MODAL, I32, "1: stable, 0: not", "scalar"),
    ATTR(TD_OUT_LOOP_MAX_REAL_PART, "max_real_part", TD_OUT_LOOP, MODAL, F64, "1/s", "scalar"),
    ATTR(TD_OUT_LOOP_SAMPLE_RATE, "sample_rate", TD_OUT_LOOP, MODAL, F64, "Hz", "scalar"),
    ATTR(TD_OUT_LOOP_SENSITIVITY_ZONE, "sensitivity_zone", TD_OUT_LOOP, MODAL, TEXT, "", "scalar"),
    DATA_CSV(TD_OUT_LOOP_FREQUENCY, "frequency", TD_OUT_LOOP, F64, "Hz", "(frequencies)", "frequency_hz"),
    DATA(TD_OUT_LOOP_AXIS, "axis", TD_OUT_LOOP, MODAL, I32, "AMB axis 2 amb + (0: x, 1: y)", "(axes)"),
    DATA(TD_OUT_LOOP_AMB_AXIS, "amb_axis", TD_OUT_LOOP, MODAL, I32, "AMB axis 2 amb + (0: x, 1: y)", "(amb axes)"),
    DATA(TD_OUT_LOOP_SENSITIVITY_RE, "sensitivity_re", TD_OUT_LOOP, MODAL, F64, "1", "(frequencies, axes)"),
    DATA(TD_OUT_LOOP_SENSITIVITY_IM, "sensitivity_im", TD_OUT_LOOP, MODAL, F64, "1", "(frequencies, axes)"),
    DATA(TD_OUT_LOOP_OPEN_LOOP_RE, "open_loop_re", TD_OUT_LOOP, MODAL, F64, "1", "(frequencies, axes)"),
    DATA(TD_OUT_LOOP_OPEN_LOOP_IM, "open_loop_im", TD_OUT_LOOP, MODAL, F64, "1", "(frequencies, axes)"),
    DATA_CSV(TD_OUT_LOOP_COMPLIANCE_RE, "compliance_re", TD_OUT_LOOP, F64, "m/N", "(frequencies, amb axes)",
             "compliance_re_m_n"),
    DATA_CSV(TD_OUT_LOOP_COMPLIANCE_IM, "compliance_im", TD_OUT_LOOP, F64, "m/N", "(frequencies, amb axes)",
             "compliance_im_m_n"),
    DATA(TD_OUT_LOOP_SENSITIVITY_PEAK, "sensitivity_peak", TD_OUT_LOOP, MODAL, F64, "1", "(axes)"),
    DATA_CSV(TD_OUT_LOOP_SENSITIVITY_PEAK_FREQUENCY, "sensitivity_peak_frequency", TD_OUT_LOOP, F64, "Hz", "(axes)",
             "sensitivity_peak_frequency_hz"),
    DATA(TD_OUT_LOOP_SENSITIVITY_ZONES, "sensitivity_zones", TD_OUT_LOOP, MODAL, TEXT, "1", "(axes)"),
    CSV_LINE(TD_OUT_LOOP_PEAKS, "sensitivity_peaks", MODAL),
    CSV_LINE(TD_OUT_LOOP_COMPLIANCE, "compliance", MODAL),
    /* ---- sweep table ---- */
    [TD_OUT_SWEEP_POINT] = {"point", TD_OUT_ROOT, TD_OUT_DATASET, SWEEP, TD_OUT_I32, "", "(points)", NULL, "-"},
    GROUP(TD_OUT_SWEEP_VARY, "vary", TD_OUT_ROOT, SWEEP),
    ATTR(TD_OUT_SWEEP_KEY_SPEC, "spec", TD_OUT_SWEEP_VARY, SWEEP, TEXT, "", "scalar"),
    ATTR(TD_OUT_SWEEP_KEY_AXIS, "axis", TD_OUT_SWEEP_VARY, SWEEP, I32, "", "scalar"),
    ATTR(TD_OUT_SWEEP_KEY_ORIGIN, "origin", TD_OUT_SWEEP_VARY, SWEEP, TEXT, "", "scalar"),
    COLUMN(TD_OUT_SWEEP_STATUS, "status", TEXT, ""),
    COLUMN(TD_OUT_SWEEP_MESSAGE, "message", TEXT, ""),
    COLUMN(TD_OUT_SWEEP_PEAK_HOUSING_FORCE, "peak_housing_force", F64, "N"),
    COLUMN(TD_OUT_SWEEP_TOTAL_IMPULSE, "total_impulse", F64, "N s"),
    COLUMN(TD_OUT_SWEEP_FRICTION_WORK, "friction_work", F64, "J"),
    COLUMN(TD_OUT_SWEEP_CONTACT_TIME, "contact_time", F64, "s"),
    COLUMN(TD_OUT_SWEEP_CONTACTS, "contacts", F64, "-"),
    COLUMN(TD_OUT_SWEEP_FIRST_CONTACT_TIME, "first_contact_time", F64, "s"),
    COLUMN(TD_OUT_SWEEP_ENDING, "ending", TEXT, ""),
    COLUMN(TD_OUT_SWEEP_REGIME, "regime", TEXT, ""),
    COLUMN(TD_OUT_SWEEP_ENDING_WHIRL_FREQUENCY, "ending_whirl_frequency", F64, "Hz"),
    COLUMN(TD_OUT_SWEEP_RETURNED_TO_FREE_ORBIT, "returned_to_free_orbit", F64, "-"),
    COLUMN(TD_OUT_SWEEP_SECTION_COUNT, "section_count", F64, "-"),
    COLUMN(TD_OUT_SWEEP_SECTION_RADIUS_MIN, "section_radius_min", F64, "m"),
    COLUMN(TD_OUT_SWEEP_SECTION_RADIUS_MAX, "section_radius_max", F64, "m"),
    COLUMN(TD_OUT_SWEEP_SECTION_CLEARANCE, "section_clearance", F64, "m"),
    COLUMN(TD_OUT_SWEEP_FINAL_SPEED, "final_speed", F64, "rad/s"),
    COLUMN(TD_OUT_SWEEP_PEAK_AMB_LOAD, "peak_amb_load", F64, "1"),
    COLUMN(TD_OUT_SWEEP_T_REACHED, "t_reached", F64, "s"),
    COLUMN(TD_OUT_SWEEP_DROPS_TO_FAILURE, "drops_to_failure", F64, "1"), /* life */
    COLUMN(TD_OUT_SWEEP_WARNINGS, "warnings", TEXT, ""),
    COLUMN(TD_OUT_SWEEP_WALL_TIME, "wall_time", F64, "s"),
    DATA(TD_OUT_SWEEP_SECTION_RADIUS, "section_radius", TD_OUT_ROOT, SWEEP, F64, "m", "(points, 64)"),
    ATTR(TD_OUT_SWEEP_VARY_SPECS, "vary", TD_OUT_ROOT, SWEEP, TEXT, "", "scalar"),
    ATTR(TD_OUT_SWEEP_SET, "set", TD_OUT_ROOT, SWEEP, TEXT, "", "scalar"),
    CSV_LINE(TD_OUT_SWEEP_POINTS, "points", SWEEP),
    CSV_LINE(TD_OUT_SWEEP_WITH, "with", SWEEP),
    CSV_LINE(TD_OUT_SWEEP_FROM, "from", SWEEP),
    /* ---- the bearing's duty ---- */
    RET_ATTR(TD_OUT_RETAINER_PEAK_SLIDING_VELOCITY, "retainer_peak_sliding_velocity", F64, "m/s"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_FRICTION_POWER, "retainer_peak_friction_power", F64, "W"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_PV, "retainer_peak_pv", F64, "Pa m/s"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_CONTACT_STRESS, "retainer_peak_contact_stress", F64, "Pa"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_RACE_SPEED, "retainer_peak_race_speed", F64, "rad/s"),
    RET_ATTR(TD_OUT_RETAINER_LOAD_RATIO, "retainer_load_ratio", F64, "1"),
    RUN_ATTR(TD_OUT_SENSOR_CLEARANCE, "sensor_clearance", F64, "m"),
    ATTR(TD_OUT_SENSOR_PEAK_DISPLACEMENT, "sensor_peak_displacement", TD_OUT_ROOT, RUN, F64, "m", "(n_amb)"),
    ATTR(TD_OUT_SENSOR_ZONE, "sensor_zone", TD_OUT_ROOT, RUN, F64, "0 A, 1 B, 2 C, 3 D", "(n_amb)"),
    RUN_ATTR(TD_OUT_SUM_SETTLE_TIME, "summary_settle_time", F64, "s"),
    RUN_ATTR(TD_OUT_SUM_SETTLED, "summary_settled", F64, ""),
    RUN_ATTR(TD_OUT_SUM_CONTACT_TOTALS_CONVERGE, "summary_contact_totals_converge", I64, ""),
    /* ---- heat: the retainers' thermal networks (series with thermal fields) and the heat totals ---- */
    SERIES(TD_OUT_RET_RACE_TEMPERATURE, "race_temperature", TD_OUT_RETAINERS, F64, "K", "(N, n_ret)", "Tr_ret%d", NULL),
    SERIES(TD_OUT_RET_HOUSING_TEMPERATURE, "housing_temperature", TD_OUT_RETAINERS, F64, "K", "(N, n_ret)", "Th_ret%d",
           NULL),
    RET_ATTR(TD_OUT_RETAINER_DRAG_WORK, "retainer_drag_work", F64, "J"),
    RET_ATTR(TD_OUT_RETAINER_HEAT, "retainer_heat", F64, "J"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_TEMPERATURE_RISE, "retainer_peak_temperature_rise", F64, "K"),
    RET_ATTR(TD_OUT_RETAINER_PEAK_THERMAL_GROWTH, "retainer_peak_thermal_growth", F64, "m"),
    /* ---- modal file: the API 617 unbalance response report (td_unbalance_sweep; docs/api617.md) ---- */
    DATA_CSV(TD_OUT_MODES_LOG_DECREMENT, "log_decrement", TD_OUT_MODES, F64, "1", "(modes)", "log_decrement"),
    DATA(TD_OUT_MODES_DISC_NODES, "disc_nodes", TD_OUT_MODES, MODAL, I32, "node", "(n_disc)"),
    DATA(TD_OUT_MODES_SENSOR_NODES, "sensor_nodes", TD_OUT_MODES, MODAL, I32, "node", "(n_amb)"),
    GROUP(TD_OUT_UNBALANCE_RESPONSE, "unbalance_response", TD_OUT_ROOT, MODAL),
    DATA_CSV(TD_OUT_UR_SPEED, "speed", TD_OUT_UNBALANCE_RESPONSE, F64, "rad/s", "(speeds)", "speed_rad_s"),
    DATA(TD_OUT_UR_NODE, "node", TD_OUT_UNBALANCE_RESPONSE, MODAL, I32, "node number", "(response nodes)"),
    DATA_CSV(TD_OUT_UR_X_AMP, "x_amp", TD_OUT_UNBALANCE_RESPONSE, F64, "m", "(speeds, response nodes)", "x_amp_m"),
    DATA_CSV(TD_OUT_UR_X_PHASE, "x_phase", TD_OUT_UNBALANCE_RESPONSE, F64, "rad", "(speeds, response nodes)",
             "x_phase_rad"),
    DATA_CSV(TD_OUT_UR_Y_AMP, "y_amp", TD_OUT_UNBALANCE_RESPONSE, F64, "m", "(speeds, response nodes)", "y_amp_m"),
    DATA_CSV(TD_OUT_UR_Y_PHASE, "y_phase", TD_OUT_UNBALANCE_RESPONSE, F64, "rad", "(speeds, response nodes)",
             "y_phase_rad"),
    DATA_CSV(TD_OUT_UR_FORWARD, "forward", TD_OUT_UNBALANCE_RESPONSE, F64, "m", "(speeds, response nodes)",
             "forward_m"),
    DATA_CSV(TD_OUT_UR_BACKWARD, "backward", TD_OUT_UNBALANCE_RESPONSE, F64, "m", "(speeds, response nodes)",
             "backward_m"),
    DATA_CSV(TD_OUT_UR_MAJOR, "major", TD_OUT_UNBALANCE_RESPONSE, F64, "m", "(speeds, response nodes)", "major_m"),
    DATA_CSV(TD_OUT_UR_MINOR, "minor", TD_OUT_UNBALANCE_RESPONSE, F64, "m", "(speeds, response nodes)", "minor_m"),
    GROUP(TD_OUT_RESPONSE_PEAKS, "response_peaks", TD_OUT_ROOT, MODAL),
    ATTR(TD_OUT_PEAK_OPERATING_SPEED_MIN, "operating_speed_min", TD_OUT_RESPONSE_PEAKS, MODAL, F64, "rad/s", "scalar"),
    ATTR(TD_OUT_PEAK_OPERATING_SPEED_MAX, "operating_speed_max", TD_OUT_RESPONSE_PEAKS, MODAL, F64, "rad/s", "scalar"),
    DATA(TD_OUT_PEAK_NODE, "node", TD_OUT_RESPONSE_PEAKS, MODAL, I32, "node number", "(peaks)"),
    DATA_CSV(TD_OUT_PEAK_SPEED, "speed", TD_OUT_RESPONSE_PEAKS, F64, "rad/s", "(peaks)", "speed_rad_s"),
    DATA_CSV(TD_OUT_PEAK_AMPLITUDE, "amplitude", TD_OUT_RESPONSE_PEAKS, F64, "m", "(peaks)", "amplitude_m"),
    DATA_CSV(TD_OUT_PEAK_SPEED_LOW, "speed_low", TD_OUT_RESPONSE_PEAKS, F64, "rad/s", "(peaks)", "speed_low_rad_s"),
    DATA_CSV(TD_OUT_PEAK_SPEED_HIGH, "speed_high", TD_OUT_RESPONSE_PEAKS, F64, "rad/s", "(peaks)", "speed_high_rad_s"),
    DATA(TD_OUT_PEAK_AMPLIFICATION, "amplification", TD_OUT_RESPONSE_PEAKS, MODAL, F64, "1", "(peaks)"),
    DATA_CSV(TD_OUT_PEAK_MARGIN, "margin", TD_OUT_RESPONSE_PEAKS, F64, "%", "(peaks)", "margin_percent"),
    DATA_CSV(TD_OUT_PEAK_REQUIRED_MARGIN, "required_margin", TD_OUT_RESPONSE_PEAKS, F64, "%", "(peaks)",
             "required_margin_percent"),
    DATA(TD_OUT_PEAK_VERDICT, "verdict", TD_OUT_RESPONSE_PEAKS, MODAL, I32, "1: pass, 0: fail, -1: undefined",
         "(peaks)"),
    GROUP(TD_OUT_STATIC_REACTIONS, "static_reactions", TD_OUT_ROOT, MODAL),
    /* the CSV columns of both forces: F<component>_N */
    [TD_OUT_STATIC_AMB_FORCE] = {"amb_force", TD_OUT_STATIC_REACTIONS, TD_OUT_DATASET, MODAL, TD_OUT_F64, "N",
                                 "(n_amb, 2)", "F%s_N", NULL},
    DATA(TD_OUT_STATIC_BEARING_FORCE, "bearing_force", TD_OUT_STATIC_REACTIONS, MODAL, F64, "N", "(n_bearing, 2)"),
    CSV_LINE(TD_OUT_STATIC_SUPPORT, "support", MODAL),
    DATA(TD_OUT_UR_SENSOR_ZONE, "sensor_zone", TD_OUT_UNBALANCE_RESPONSE, MODAL, I32,
         "ISO 14839-2 zone: 0 A, 1 B, 2 C, 3 D, -1 undefined", "(speeds, n_amb)"),
    ATTR(TD_OUT_UR_C_MIN, "c_min", TD_OUT_UNBALANCE_RESPONSE, MODAL, F64, "m", "scalar"),
    /* API 617's amplitude at the close clearances (the retainers; td_sweep_clearance_check) */
    GROUP(TD_OUT_RUNNING_CLEARANCE, "running_clearance", TD_OUT_ROOT, MODAL),
    ATTR(TD_OUT_RC_FRACTION, "fraction", TD_OUT_RUNNING_CLEARANCE, MODAL, F64, "1", "scalar"),
    ATTR(TD_OUT_RC_SPEED_MIN, "speed_min", TD_OUT_RUNNING_CLEARANCE, MODAL, F64, "rad/s", "scalar"),
    ATTR(TD_OUT_RC_SPEED_MAX, "speed_max", TD_OUT_RUNNING_CLEARANCE, MODAL, F64, "rad/s", "scalar"),
    DATA(TD_OUT_RC_NODE, "node", TD_OUT_RUNNING_CLEARANCE, MODAL, I32, "node number", "(n_ret)"),
    DATA_CSV(TD_OUT_RC_CLEARANCE, "clearance", TD_OUT_RUNNING_CLEARANCE, F64, "m", "(n_ret)", "clearance_m"),
    DATA_CSV(TD_OUT_RC_AMPLITUDE, "amplitude", TD_OUT_RUNNING_CLEARANCE, F64, "m", "(n_ret)", "amplitude_m"),
    DATA_CSV(TD_OUT_RC_SPEED, "speed", TD_OUT_RUNNING_CLEARANCE, F64, "rad/s", "(n_ret)", "speed_rad_s"),
    DATA(TD_OUT_RC_RATIO, "ratio", TD_OUT_RUNNING_CLEARANCE, MODAL, F64, "1", "(n_ret)"),
    DATA(TD_OUT_RC_VERDICT, "verdict", TD_OUT_RUNNING_CLEARANCE, MODAL, I32, "1: pass, 0: fail, -1: undefined",
         "(n_ret)"),
    /* housing motion */
    RUN_ATTR(TD_OUT_SUM_ENERGY_HOUSING_WORK, "summary_energy_housing_work", F64, "J"),
    /* clearance margin */
    RET_ATTR(TD_OUT_RETAINER_MIN_CLEARANCE_MARGIN, "retainer_min_clearance_margin", F64, "m"),
    RUN_ATTR(TD_OUT_SUM_MIN_CLEARANCE_MARGIN, "summary_min_clearance_margin", F64, "m"),
    RUN_ATTR(TD_OUT_SUM_CONTACT_HAPPENED, "summary_contact_happened", F64, ""),
    RUN_ATTR(TD_OUT_SUM_SHOCK_OUTCOME, "summary_shock_outcome", TEXT, ""),
    COLUMN(TD_OUT_SWEEP_MIN_CLEARANCE_MARGIN, "min_clearance_margin", F64, "m"),
    COLUMN(TD_OUT_SWEEP_CONTACT_HAPPENED, "contact_happened", F64, "-"),
    COLUMN(TD_OUT_SWEEP_SHOCK_OUTCOME, "shock_outcome", TEXT, ""),
    /* housing motion: the series of a model with housing motion (td_model_has_housing_motion) */
    GROUP(TD_OUT_HOUSING, "housing", TD_OUT_ROOT, H5RUN),
    SERIES(TD_OUT_HOUSING_ACCELERATION, "acceleration", TD_OUT_HOUSING, F64, "m/s^2", "(N, 2)", "a%s_housing", NULL),
    SERIES(TD_OUT_HOUSING_VELOCITY, "velocity", TD_OUT_HOUSING, F64, "m/s", "(N, 2)", "v%s_housing", NULL),
    SERIES(TD_OUT_HOUSING_DISPLACEMENT, "displacement", TD_OUT_HOUSING, F64, "m", "(N, 2)", "%s_housing", NULL),
    SERIES(TD_OUT_HOUSING_ROTATION_RATE, "rotation_rate", TD_OUT_HOUSING, F64, "rad/s", "(N, 2)", "w%s_housing", NULL),
    SERIES(TD_OUT_HOUSING_ROTATION_ANGLE, "rotation_angle", TD_OUT_HOUSING, F64, "rad", "(N, 2)", "rot%s_housing",
           NULL),
    SERIES(TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, "absolute_displacement", TD_OUT_NODES, F64, "m", "(N, n_nodes, 2)",
           "%s_abs_n%d", NULL),
    /* housing body: the series of a model with a housing body (td_model_get_housing_body) */
    SERIES(TD_OUT_HOUSING_BODY_DISPLACEMENT, "body_displacement", TD_OUT_HOUSING, F64, "m", "(N, 2)", "%s_housing_body",
           NULL),
    SERIES(TD_OUT_HOUSING_BODY_TILT, "body_tilt", TD_OUT_HOUSING, F64, "rad", "(N, 2)", "tilt%s_housing_body", NULL),
    /* long runs: the window summaries of a run with output.window (td_writer_window) */
    GROUP(TD_OUT_WINDOWS, "windows", TD_OUT_ROOT, H5RUN),
    SERIES(TD_OUT_WIN_TIME_START, "time_start", TD_OUT_WINDOWS, F64, "s", "(W)", "t_start", NULL),
    SERIES(TD_OUT_WIN_TIME_END, "time_end", TD_OUT_WINDOWS, F64, "s", "(W)", "t_end", NULL),
    SERIES(TD_OUT_WIN_SPEED, "speed", TD_OUT_WINDOWS, F64, "rad/s", "(W)", "speed", NULL),
    SERIES(TD_OUT_WIN_ENERGY_KINETIC, "energy_kinetic", TD_OUT_WINDOWS, F64, "J", "(W)", "energy_kinetic", NULL),
    SERIES(TD_OUT_WIN_ENERGY_RESIDUAL, "energy_residual", TD_OUT_WINDOWS, F64, "J", "(W)", "energy_residual", NULL),
    SERIES(TD_OUT_WIN_CONTACTS, "contacts", TD_OUT_WINDOWS, I64, "1", "(W, n_ret)", "contacts_ret%d", "-"),
    SERIES(TD_OUT_WIN_CONTACT_FRACTION, "contact_fraction", TD_OUT_WINDOWS, F64, "1", "(W, n_ret)",
           "contact_fraction_ret%d", "-"),
    SERIES(TD_OUT_WIN_PEAK_NORMAL_FORCE, "peak_normal_force", TD_OUT_WINDOWS, F64, "N", "(W, n_ret)", "N_peak_ret%d",
           NULL),
    SERIES(TD_OUT_WIN_FRICTION_WORK, "friction_work", TD_OUT_WINDOWS, F64, "J", "(W, n_ret)", "friction_work_ret%d",
           NULL),
    SERIES(TD_OUT_WIN_RACE_TEMPERATURE, "race_temperature", TD_OUT_WINDOWS, F64, "K", "(W, n_ret)", "Tr_ret%d", NULL),
    /* projective leap: the leaps made, so that a gap between rows reads as leapt (a run with a leap group) */
    RUN_ATTR(TD_OUT_SUM_LEAPS, "summary_leaps", I64, ""),
    RUN_ATTR(TD_OUT_SUM_LEAPT_TIME, "summary_leapt_time", F64, "s"),
    ATTR(TD_OUT_LEAP_TIME, "leap_time", TD_OUT_ROOT, RUN, F64, "s", "(leaps)"),
    ATTR(TD_OUT_LEAP_LENGTH, "leap_length", TD_OUT_ROOT, RUN, F64, "s", "(leaps)"),
    /* long runs: a run with end_at_rest */
    RUN_ATTR(TD_OUT_SUM_ENDED_AT_REST, "summary_ended_at_rest", F64, ""),
    /* projective leap and long runs: the sweep's columns (a table with a point asked for them) */
    COLUMN(TD_OUT_SWEEP_LEAPS, "leaps", F64, "-"),
    COLUMN(TD_OUT_SWEEP_LEAPT_TIME, "leapt_time", F64, "s"),
    COLUMN(TD_OUT_SWEEP_ENDED_AT_REST, "ended_at_rest", F64, "-"),
};

/* The lateral components, each name written once here (td_schema_components). */
#define COMPONENT_X "x"
#define COMPONENT_Y "y"

const char *const *td_schema_components(void)
{
    static const char *const xy[2] = {COMPONENT_X, COMPONENT_Y};
    return xy;
}

const char *td_schema_components_list(void)
{
    return COMPONENT_X "," COMPONENT_Y;
}

const td_schema_entry *td_schema(td_out_id id)
{
    return (int)id >= 0 && id < TD_OUT_ID_COUNT ? &entries[id] : NULL;
}

const char *td_schema_csv(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return !e ? NULL : e->csv ? e->csv : e->name;
}

const char *td_schema_csv_units(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return !e ? NULL : e->csv_units ? e->csv_units : e->units;
}

const char *td_out_name(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->name : NULL;
}

const char *td_out_units(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->units : NULL;
}

const char *td_out_shape(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->shape : "";
}

td_out_place td_out_place_of(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->place : TD_OUT_NO_PLACE;
}

td_out_type td_out_type_of(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->type : TD_OUT_NO_TYPE;
}

unsigned td_out_files(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->files : 0u;
}

td_out_id td_out_parent(td_out_id id)
{
    const td_schema_entry *e = td_schema(id);
    return e ? e->parent : TD_OUT_ID_COUNT;
}

td_out_id td_out_find(const char *name, td_out_place place, unsigned files)
{
    int i;
    for (i = 0; name && i < TD_OUT_ID_COUNT; i++)
        if (entries[i].name && entries[i].place == place && (entries[i].files & files) &&
            !strcmp(entries[i].name, name))
            return (td_out_id)i;
    return TD_OUT_ID_COUNT;
}

/* Append "/text" (no '/' at the start) to buf, which holds len characters; the new length. */
static size_t append(char *buf, size_t n, size_t len, const char *text)
{
    int k = snprintf(buf + (len < n ? len : n - 1), len < n ? n - len : 1, "%s%s", len > 0 ? "/" : "", text);
    return len + (size_t)(k > 0 ? k : 0);
}

/* The path of a group or dataset: its parents' names joined by '/', the root's "" left out. A
 * group without a name of its own (/harmonic/I) takes `sub` as its name, *used set. */
static size_t object_path(td_out_id id, const char *sub, int *used, char *buf, size_t n)
{
    const td_schema_entry *e = td_schema(id);
    size_t len;
    if (!e || id == TD_OUT_ROOT)
        return 0;
    len = object_path(e->parent, sub, used, buf, n);
    if (e->name[0])
        return append(buf, n, len, e->name);
    *used = 1;
    return append(buf, n, len, sub ? sub : "");
}

int td_out_path(td_out_id id, const char *sub, char *buf, size_t n)
{
    const td_schema_entry *e = td_schema(id);
    char empty[1];
    size_t len = 0;
    int used = 0;
    if (!buf || n == 0) {
        buf = empty;
        n = 1;
    }
    buf[0] = '\0';
    if (!e)
        return -1;
    /* an attribute or field: its object's path (one on several objects: `sub` alone names it) */
    if (e->place == TD_OUT_ATTRIBUTE || e->place == TD_OUT_FIELD || e->place == TD_OUT_CSV_ONLY)
        id = e->parent;
    if (id != TD_OUT_ID_COUNT)
        len = object_path(id, sub, &used, buf, n);
    if (!used && sub && *sub)
        len = append(buf, n, len, sub);
    return (int)len;
}
