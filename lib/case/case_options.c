/*
 * The tables of the top level and of the run settings: speed, gravity, reduction, end time,
 * start state, and the option groups contact, solver, output and modal, with their custom
 * readers and row checks, and the bounds on the whole run (the `output` row's check). The option
 * groups' defaults are td_*_options_default's (lib/util/options.c, TD_CS_PRESET): the tables
 * never restate them.
 */
#include "case/case_schema.h"
#include "model/gap.h"
#include "touchdown/dofs.h"
#include "touchdown/modal.h"
#include "touchdown/run.h"
#include "util/error_internal.h"
#include "util/limits.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The members of the gravity group, before they become the model's acceleration vector. */
typedef struct gravity_rec {
    int enabled;
    double g;
    double dir[2];
} gravity_rec;

static const char *const start_names[] = {"orbit", "rest", "auto"}; /* td_start order */
static const char *const contact_names[] = {"constraint", "penalty"};
static const char *const linsol_names[] = {"klu", "dense"};

/* Fail at member `key` of g when it is there (its line), else at g naming the key; for a rule
 * that compares it with `other` (a setting, or NULL), where that was written too. */
static td_status fail_at(td_case_reader *r, const config_setting_t *g, const char *key, const config_setting_t *other,
                         const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static td_status fail_at(td_case_reader *r, const config_setting_t *g, const char *key, const config_setting_t *other,
                         const char *fmt, ...)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return s ? td_cr_fail_vs(r, s, other, "%s", msg) : td_cr_fail(r, g, key, "%s", msg);
}

/* gravity.direction [gx, gy]: normalised; absent: the record's [0, -1]. */
static td_status read_direction(td_case_reader *r, const config_setting_t *grav, const td_cs_key *k, void *rec)
{
    const config_setting_t *d = config_setting_get_member(grav, k->key);
    double *dir = ((gravity_rec *)rec)->dir, norm, scale;
    int n = 2;
    td_status st;
    if (!d)
        return TD_OK;
    st = td_cr_reals(r, grav, k->key, 2, TD_CR_FINITE, dir, &n);
    if (st == TD_OK && n != 2)
        return td_cr_fail(r, d, NULL, "expected two components [gx, gy], got %d", n);
    /* scaled by the larger component first: hypot(1.7e308, 1.7e308) overflows, and the
     * direction 0/inf would have turned gravity off */
    scale = fabs(dir[0]) > fabs(dir[1]) ? fabs(dir[0]) : fabs(dir[1]);
    if (st == TD_OK && !(scale > 0.0))
        return td_cr_fail(r, d, NULL, "must not be the zero vector");
    if (st == TD_OK) {
        norm = hypot(dir[0] / scale, dir[1] / scale);
        dir[0] = dir[0] / scale / norm;
        dir[1] = dir[1] / scale / norm;
    }
    return st;
}

static void gravity_preset(void *rec)
{
    ((gravity_rec *)rec)->dir[1] = -1.0;
}

/* gravity { enabled; g; direction [gx, gy]; }: acceleration g along the (normalised) direction. */
static td_status set_gravity(td_case_reader *r, const config_setting_t *grav, void *rec)
{
    const gravity_rec *gr = rec;
    double g = gr->enabled ? gr->g : 0.0;
    td_error merr;
    td_status st = td_model_set_gravity(r->c->model, g * gr->dir[0], g * gr->dir[1], &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, grav, st, &merr);
}

static const td_cs_key gravity_keys[] = {
    {.key = "enabled",
     .type = TD_CS_BOOL,
     .offset = offsetof(gravity_rec, enabled),
     .def = 1,
     .doc = "gravity on (a `gravity` group with `enabled = false` turns it off)"},
    {.key = "g",
     .type = TD_CS_REAL,
     .offset = offsetof(gravity_rec, g),
     .def = 9.81,
     .range = TD_CR_NONNEGATIVE,
     .unit = "m/s^2",
     .doc = "magnitude of the acceleration"},
    {.key = "direction",
     .type = TD_CS_CUSTOM,
     .read = read_direction,
     .doc_type = "array of 2 numbers",
     .doc_range = "not [0, 0]",
     .doc_default = "`[0.0, -1.0]`",
     .doc = "direction [gx, gy] in the x-y plane; normalised to unit length, must not be zero"},
};
const td_cs_table td_cs_gravity = {"gravity",           "gravity",      gravity_keys, TD_CS_COUNT(gravity_keys),
                                   sizeof(gravity_rec), gravity_preset, set_gravity};

/* reduction { cutoff; }: a Craig-Bampton reduced rotor keeping the fixed-interface modes below
 * cutoff Hz (docs/theory.md, "Reduced rotor"); absent: the full model. */
static td_status set_reduction(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    td_status st = td_model_set_reduction(r->c->model, *(const double *)rec, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static const td_cs_key reduction_keys[] = {
    {.key = "cutoff",
     .type = TD_CS_REAL,
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "cut-off frequency of the fixed-interface modes, Hz",
     .unit = "Hz",
     .doc = "keep the fixed-interface modes below this frequency, a few times the highest frequency of interest: a "
            "mode at f is off by at most about (f/f_N)^2 relative, f_N the first mode omitted (on the reference rig at "
            "2000 Hz: 6e-4 below 300 Hz, 1.4 % below 1 kHz; docs/performance.md). A cut-off above every "
            "fixed-interface mode gives the full model's results to rounding"},
};
const td_cs_table td_cs_reduction = {"reduction",    "reduction", reduction_keys, TD_CS_COUNT(reduction_keys),
                                     sizeof(double), NULL,        set_reduction};

/* contact.exponent p < 1 gives an infinite contact stiffness dF/ddelta at first touch */
static td_status check_exponent(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_contact_options *o = rec;
    const config_setting_t *e = config_setting_get_member(g, k->key);
    if (o->exponent < 1.0 && e)
        return td_cr_fail(r, e, NULL, "must be >= 1 (got %g)", o->exponent);
    return TD_OK;
}

static void contact_preset(void *rec)
{
    td_contact_options_default(rec);
}

static const td_cs_key contact_keys[] = {
    {.key = "model",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_contact_options, model),
     .need = TD_CS_PRESET,
     .names = contact_names,
     .name_count = 2,
     .doc = "contact model"},
    {.key = "stiffness",
     .type = TD_CS_REAL,
     .offset = offsetof(td_contact_options, stiffness),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .unit = "N/m^p",
     .doc = "penalty stiffness Kc (N/m when p = 1)"},
    {.key = "exponent",
     .type = TD_CS_REAL,
     .offset = offsetof(td_contact_options, exponent),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .check = check_exponent,
     .doc_range = ">= 1",
     .doc = "penalty exponent p: 1 linear (eq. 4), 1.5 Hertzian"},
    {.key = "damping",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_contact_options, damping),
     .need = TD_CS_PRESET,
     .names = td_cr_damping_names,
     .name_count = TD_CR_DAMPING_NAMES,
     .doc = "penalty damping: Hunt-Crossley F_n = Kc delta^p (1 + d ddelta/dt), Kelvin-Voigt F_n = Kc delta^p + d "
            "ddelta/dt; both clipped at 0 (never pulling)"},
    {.key = "damping_coefficient",
     .type = TD_CS_REAL,
     .offset = offsetof(td_contact_options, damping_coefficient),
     .need = TD_CS_PRESET,
     .range = TD_CR_NONNEGATIVE,
     .unit = "s/m (Hunt-Crossley), N s/m (Kelvin-Voigt)",
     .doc = "d; ignored with `damping = \"none\"`"},
};
const td_cs_table td_cs_contact = {
    "contact", "contact", contact_keys, TD_CS_COUNT(contact_keys), sizeof(td_contact_options), contact_preset, NULL};

/* solver.initial_step within max_step (when max_step bounds the step) */
static td_status check_initial_step(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_solver_options *o = rec;
    if (o->max_step > 0.0 && o->initial_step > o->max_step)
        return fail_at(r, g, k->key, config_setting_get_member(g, "max_step"), "%g s is larger than max_step %g s",
                       o->initial_step, o->max_step);
    return TD_OK;
}

static void solver_preset(void *rec)
{
    td_solver_options_default(rec);
}

static const td_cs_key solver_keys[] = {
    {.key = "rtol",
     .type = TD_CS_REAL,
     .offset = offsetof(td_solver_options, rtol),
     .need = TD_CS_PRESET,
     .range = TD_CR_OPEN_UNIT,
     .doc = "relative tolerance"},
    {.key = "atol",
     .type = TD_CS_REAL,
     .offset = offsetof(td_solver_options, atol),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_range = "> 0, at most 1e-3 of the smallest clearance or air gap ([Limits](#limits))",
     .unit = "m",
     .doc = "absolute tolerance on displacements (other states scaled from it)"},
    {.key = "max_step",
     .type = TD_CS_REAL,
     .offset = offsetof(td_solver_options, max_step),
     .need = TD_CS_PRESET,
     .range = TD_CR_NONNEGATIVE,
     .unit = "s",
     .doc = "largest step; 0: chosen from the whirl period; end_time / max_step at most 1e8 (see Limits)"},
    {.key = "initial_step",
     .type = TD_CS_REAL,
     .offset = offsetof(td_solver_options, initial_step),
     .need = TD_CS_PRESET,
     .range = TD_CR_NONNEGATIVE,
     .check = check_initial_step,
     .doc_range = ">= 0, <= max_step",
     .unit = "s",
     .doc = "first step and restart step after an event; 0: chosen by IDA"},
    {.key = "max_order",
     .type = TD_CS_INT,
     .offset = offsetof(td_solver_options, max_order),
     .need = TD_CS_PRESET,
     .lo = 1,
     .hi = 5,
     .doc = "BDF order limit. 2 (the highest A-stable BDF order) suits damped machines, where it steps over decaying "
            "ringing; on an undamped rotor against rigid or undamped retainers (the paper's cases) orders up to 5 are "
            "both faster and far more accurate at any tolerance, and the paper's cases set 5 with rtol 1e-9 "
            "(`cases/include/paper-solver.cfg`; measurements in "
            "[performance](performance.md#the-papers-cases-settings-that-converge))"},
    {.key = "linear_solver",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_solver_options, linear_solver),
     .need = TD_CS_PRESET,
     .names = linsol_names,
     .name_count = 2,
     .doc = "sparse LU (KLU) or dense LU"},
    {.key = "free_flight",
     .type = TD_CS_BOOL,
     .offset = offsetof(td_solver_options, free_flight),
     .need = TD_CS_PRESET,
     .doc = "carry free flight (every retainer free) in closed form where the machine is linear and time-invariant: "
            "exact contact times and free motion at any tolerance (docs/theory.md, \"Free flight in closed form\"); "
            "false: IDA integrates it too"},
};
const td_cs_table td_cs_solver = {
    "solver", "solver", solver_keys, TD_CS_COUNT(solver_keys), sizeof(td_solver_options), solver_preset, NULL};

/* output.nodes: nodes of the shaft as written, no repeats (read after the other output keys) */
static td_status read_output_nodes(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_output_options *o = rec;
    const config_setting_t *list;
    int i, j;
    td_status st =
        td_cr_ints(r, g, k->key, TD_OUTPUT_MAX_NODES, TD_CR_ANY_INT_LO, TD_CR_ANY_INT_HI, o->nodes, &o->node_count);
    if (st != TD_OK)
        return st;
    list = config_setting_get_member(g, k->key);
    for (i = 0; i < o->node_count; i++) {
        const config_setting_t *s = config_setting_get_elem(list, (unsigned)i);
        if (o->nodes[i] < 0 || o->nodes[i] >= r->nodes)
            return td_cr_fail_vs(r, s, o->nodes[i] < 0 ? NULL : td_cr_shaft_nodes(r),
                                 "node %d is out of range (the shaft has nodes 0..%d)", o->nodes[i], r->nodes - 1);
        for (j = 0; j < i; j++)
            if (o->nodes[j] == o->nodes[i])
                return td_cr_fail(r, s, NULL, "node %d is listed twice", o->nodes[i]);
    }
    return TD_OK;
}

/* long runs: output.window, 0 or a whole number of sample intervals (td_run_window_check) */
static td_status check_window(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_output_options *o = rec;
    char why[320];
    if (td_run_window_check(o->window, o->sample_rate, why, sizeof why))
        return td_cr_fail_vs(r, config_setting_get_member(g, k->key), config_setting_get_member(g, "sample_rate"), "%s",
                             why);
    return TD_OK;
}

/* long runs: output.events (true: the files keep the event table), stored as its opposite so that
 * a td_output_options set to zeros writes the events as before */
static td_status read_output_events(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_output_options *o = rec;
    int keep = !o->omit_events;
    td_status st = td_cr_bool(r, g, k->key, keep, &keep);
    o->omit_events = !keep;
    return st;
}

static void output_preset(void *rec)
{
    td_output_options_default(rec);
}

static const td_cs_key output_keys[] = {
    {.key = "hdf5",
     .type = TD_CS_PATH,
     .offset = offsetof(td_output_options, hdf5_path),
     .doc_default = "`\"\"` (none)",
     .doc = "HDF5 file to write (relative paths: to the working directory)"},
    {.key = "csv",
     .type = TD_CS_PATH,
     .offset = offsetof(td_output_options, csv_path),
     .doc_default = "`\"\"` (none)",
     .doc = "CSV file to write"},
    {.key = "sample_rate",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, sample_rate),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .unit = "Hz",
     .doc =
         "samples per second on a uniform grid (event times added); sample_rate x end_time at most 1e8 (see Limits)"},
    {.key = "nodes",
     .type = TD_CS_CUSTOM,
     .read = read_output_nodes,
     .order = 1,
     .doc_type = "array of integers",
     .doc_range = "nodes of the shaft, at most 64, no repeats",
     .doc_default = "all nodes",
     .doc = "nodes whose displacements are written, at most 64, no repeats"},
    {.key = "compression",
     .type = TD_CS_INT,
     .offset = offsetof(td_output_options, compression),
     .need = TD_CS_PRESET,
     .lo = 0,
     .hi = 9,
     .doc_default = "%s (none)",
     .doc = "HDF5 only: shuffle + deflate at this level on every dataset; lossless (the data read back bit-identical). "
            "`touchdown run --compress N` overrides it. Case A to 2 s: 8.8 MB at 0, 6.6 MB at 4, for about 0.4 s more "
            "writing (docs/output-format.md)"},
    {.key = "section_after",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, section_after),
     .need = TD_CS_PRESET,
     .range = TD_CR_FRACTION,
     .doc = "the once-per-revolution section (docs/output-format.md, \"Once-per-revolution section\") is taken after "
            "this fraction of the run: from t_start + section_after x (end_time - t_start); the part before is the "
            "transient it leaves out"},
    /* long runs */
    {.key = "window",
     .type = TD_CS_REAL,
     .offset = offsetof(td_output_options, window),
     .need = TD_CS_PRESET,
     .range = TD_CR_NONNEGATIVE,
     .check = check_window,
     .doc_range = "0, or a whole number (at least 1) of sample intervals 1 / sample_rate",
     .doc_default = "%s (none)",
     .unit = "s",
     .doc = "summaries over windows of this length, each closed at the grid sample at its end (so a length that is "
            "not a whole number of sample intervals is refused, never lengthened): the speed, and each retainer's "
            "contacts, time in contact, peak normal force (at the integrator's points inside the window), friction "
            "work and race temperature rise, the energy account (docs/output-format.md, \"Window summaries\"); a "
            "long run keeps its story in them at any sample rate"},
    {.key = "events",
     .type = TD_CS_CUSTOM,
     .read = read_output_events,
     .doc_type = "boolean",
     .doc_default = "`true`",
     .doc = "write the event table and a sample at each event; `false`: neither, for a long run that bounces (its "
            "events would outgrow everything else in the files; the window summaries still count every contact)"},
};
const td_cs_table td_cs_output = {
    "output", "output", output_keys, TD_CS_COUNT(output_keys), sizeof(td_output_options), output_preset, NULL};

/* Mechanical DOFs of the refined shaft (case.c applies refine after reading). */
static int modal_dofs(const td_case_reader *r)
{
    return TD_DOFS_PER_NODE * ((r->nodes - 1) * r->refine + 1);
}

static td_status check_speed_max(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_modal_options *o = rec;
    int at_max = td_cr_has(g, "speed_max");
    (void)k;
    if (!(o->speed_max > o->speed_min))
        return fail_at(r, g, at_max ? "speed_max" : "speed_min",
                       config_setting_get_member(g, at_max ? "speed_min" : "speed_max"),
                       "speed_max (%g rad/s) must be larger than speed_min (%g rad/s)", o->speed_max, o->speed_min);
    return TD_OK;
}

static td_status check_speed_steps(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_modal_options *o = rec;
    int dofs = modal_dofs(r);
    if (td_cr_has(g, k->key) && (long)o->speed_steps * dofs > TD_MODAL_MAX_GRID_WORK)
        return fail_at(r, g, k->key, td_cr_shaft_nodes(r),
                       "%d speeds on a model of %d DOFs is too much work: speed_steps x DOFs must "
                       "stay below %ld (here at most %ld speeds; see docs/performance.md)",
                       o->speed_steps, dofs, (long)TD_MODAL_MAX_GRID_WORK, (long)TD_MODAL_MAX_GRID_WORK / dofs);
    return TD_OK;
}

/* modal.modes: at most the model's DOFs, which also bound the default */
static td_status read_modes(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_modal_options *o = rec;
    int dofs = modal_dofs(r);
    td_status st =
        td_cr_int(r, g, k->key, NULL, o->mode_count < dofs ? o->mode_count : dofs, 1, TD_CR_ANY_INT_HI, &o->mode_count);
    if (st == TD_OK && o->mode_count > dofs) /* the bound is the shaft's: say where its nodes were written */
        return fail_at(r, g, k->key, td_cr_shaft_nodes(r), "must lie in [1, %d] (got %d)", dofs, o->mode_count);
    return st;
}

/* modal.operating_speed_min and _max: both or neither, max >= min */
static td_status check_operating_range(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_modal_options *o = rec;
    int has_min = td_cr_has(g, "operating_speed_min"), has_max = td_cr_has(g, k->key);
    if (has_min != has_max)
        return td_cr_fail(r, config_setting_get_member(g, has_min ? "operating_speed_min" : k->key), NULL,
                          "the operating range wants both operating_speed_min and operating_speed_max");
    if (has_max && !(o->operating_speed_max >= o->operating_speed_min))
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL,
                          "operating_speed_max (%g rad/s) must not be below operating_speed_min (%g rad/s)",
                          o->operating_speed_max, o->operating_speed_min);
    return TD_OK;
}

/* modal.response_nodes: nodes of the shaft as written, no repeats */
static td_status read_response_nodes(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_modal_options *o = rec;
    const config_setting_t *list;
    int i, j;
    td_status st =
        td_cr_ints(r, g, k->key, 64, TD_CR_ANY_INT_LO, TD_CR_ANY_INT_HI, o->response_nodes, &o->response_node_count);
    if (st != TD_OK)
        return st;
    list = config_setting_get_member(g, k->key);
    for (i = 0; i < o->response_node_count; i++) {
        const config_setting_t *s = config_setting_get_elem(list, (unsigned)i);
        if (o->response_nodes[i] < 0 || o->response_nodes[i] >= r->nodes)
            return td_cr_fail_vs(r, s, o->response_nodes[i] < 0 ? NULL : td_cr_shaft_nodes(r),
                                 "node %d is out of range (the shaft has nodes 0..%d)", o->response_nodes[i],
                                 r->nodes - 1);
        for (j = 0; j < i; j++)
            if (o->response_nodes[j] == o->response_nodes[i])
                return td_cr_fail(r, s, NULL, "node %d is listed twice", o->response_nodes[i]);
    }
    return TD_OK;
}

static void modal_preset(void *rec)
{
    td_modal_options_default(rec);
}

static const td_cs_key modal_keys[] = {
    {.key = "speed_min",
     .type = TD_CS_REAL,
     .offset = offsetof(td_modal_options, speed_min),
     .need = TD_CS_PRESET,
     .range = TD_CR_NONNEGATIVE,
     .unit = "rad/s",
     .doc = "lowest speed of the Campbell diagram"},
    {.key = "speed_max",
     .type = TD_CS_REAL,
     .offset = offsetof(td_modal_options, speed_max),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .check = check_speed_max,
     .doc_range = "> speed_min",
     .unit = "rad/s",
     .doc = "highest speed of the Campbell diagram"},
    {.key = "speed_steps",
     .type = TD_CS_INT,
     .offset = offsetof(td_modal_options, speed_steps),
     .need = TD_CS_PRESET,
     .lo = 2,
     .hi = 100000,
     .check = check_speed_steps,
     .doc_range = "2..100000, and speed_steps x DOFs <= 200,000",
     .doc = "number of speeds (each costs two eigen-solves; the product limit is checked where the key is written, see "
            "[performance](performance.md#modal-analysis-of-large-models))"},
    {.key = "modes",
     .type = TD_CS_INT,
     .offset = offsetof(td_modal_options, mode_count),
     .need = TD_CS_PRESET,
     .read = read_modes,
     .doc_range = "1..(4 x nodes)",
     .doc_default = "%s (at most 4 x nodes)",
     .doc = "number of modes reported (lowest damped natural frequencies)"},
    {.key = "response_speeds",
     .type = TD_CS_REALS,
     .offset = offsetof(td_modal_options, response_speeds),
     .count_offset = offsetof(td_modal_options, response_speed_count),
     .range = TD_CR_NONNEGATIVE,
     .hi = 64,
     .doc_default = "none",
     .unit = "rad/s",
     .doc = "speeds of the harmonic unbalance response, at most 64"},
    /* the API 617 unbalance response report */
    {.key = "operating_speed_min",
     .type = TD_CS_REAL,
     .offset = offsetof(td_modal_options, operating_speed_min),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "none",
     .unit = "rad/s",
     .doc = "minimum operating speed: the separation margins of the unbalance response's peaks are counted from "
            "it and `operating_speed_max` ([API 617 report](api617.md)); both or neither"},
    {.key = "operating_speed_max",
     .type = TD_CS_REAL,
     .offset = offsetof(td_modal_options, operating_speed_max),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .check = check_operating_range,
     .doc_range = ">= operating_speed_min",
     .doc_default = "none",
     .unit = "rad/s",
     .doc = "maximum continuous speed (MCS) of the operating range"},
    {.key = "response_nodes",
     .type = TD_CS_CUSTOM,
     .read = read_response_nodes,
     .doc_type = "array of integers",
     .doc_range = "nodes of the shaft, at most 64, no repeats",
     .doc_default = "every disc, AMB sensor and retainer node",
     .doc = "nodes of the unbalance response over the speed range (Bode, polar, peaks with their amplification "
            "factors)"},
};
const td_cs_table td_cs_modal = {"modal",      "modal", modal_keys, TD_CS_COUNT(modal_keys), sizeof(td_modal_options),
                                 modal_preset, NULL};

/* Member `key` of the root group `group` (of the root itself when NULL), or NULL. */
static const config_setting_t *member(const config_setting_t *root, const char *group, const char *key)
{
    const config_setting_t *g = group ? config_setting_get_member(root, group) : root;
    return g && config_setting_is_group(g) ? config_setting_get_member(g, key) : NULL;
}

/* The bounds of touchdown/limits.h on the work of the run (checked whether or not the case writes
 * output: the samples are taken anyway). The message names the key that scales the work: end_time
 * when an override set it (--set end_time=1e12), otherwise the rate or the speed it multiplies
 * (`fastest`: `speed`, or the ramp point that reaches `speed` highest up to the end time). */
static td_status check_run_limits(td_case_reader *r, const config_setting_t *root, double speed,
                                  const config_setting_t *fastest)
{
    const td_case *c = r->c;
    const config_setting_t *end = config_setting_get_member(root, "end_time"), *s = NULL;
    char why[256];
    switch (td_run_limit_check(c->end_time, speed, c->output.sample_rate, c->sim.solver.max_step, why, sizeof why)) {
    case TD_LIMIT_NONE: return TD_OK;
    case TD_LIMIT_SAMPLES: s = member(root, "output", "sample_rate"); break;
    case TD_LIMIT_STEPS: s = member(root, "solver", "max_step"); break;
    case TD_LIMIT_REVOLUTIONS: s = fastest; break;
    case TD_LIMIT_ATOL: break; /* check_atol */
    }
    if (!s || config_setting_get_hook(end))
        s = end;
    return td_cr_fail(r, s, NULL, "%s", why);
}

/* solver.atol against the machine's smallest gap (TD_MAX_ATOL_FRACTION), named at solver.atol when
 * the case sets it, else at the clearance or air gap that bounds the default. */
static td_status check_atol(td_case_reader *r, const config_setting_t *root)
{
    const config_setting_t *s = member(root, "solver", "atol"), *part;
    char why[320];
    int k, a;
    if (td_atol_limit_check(r->c->model, r->c->sim.solver.atol, why, sizeof why) == TD_LIMIT_NONE)
        return TD_OK;
    if (!s) {
        td_model_smallest_gap(r->c->model, &k, &a);
        part = config_setting_get_member(root, k >= 0 ? "retainers" : "ambs");
        part = part ? config_setting_get_elem(part, (unsigned)(k >= 0 ? k : a)) : NULL;
        s = part ? config_setting_get_member(part, k >= 0 ? "clearance" : "air_gap") : NULL;
        s = s ? s : part ? part : root;
    }
    return td_cr_fail(r, s, NULL, "%s", why);
}

/* The unbalance force U Omega^2 of every entry of the list `key` with a magnitude, at the case
 * speed, within TD_MAX_UNBALANCE_FORCE (the lists were read and checked by case_parts.c). */
static td_status check_unbalance_forces(td_case_reader *r, const config_setting_t *root, const char *key, double speed,
                                        const config_setting_t *fastest)
{
    const config_setting_t *list = config_setting_get_member(root, key), *s;
    double u, force;
    int i;
    for (i = 0; list && i < config_setting_length(list); i++) {
        s = config_setting_get_member(config_setting_get_elem(list, (unsigned)i), "magnitude");
        if (!s || td_cr_value_real(r, s, TD_CR_NONNEGATIVE, &u) != TD_OK)
            continue;
        force = u * speed * speed;
        if (!(force <= TD_MAX_UNBALANCE_FORCE))
            return td_cr_fail_vs(r, s, fastest,
                                 "the unbalance force U Omega^2 = %g kg m x (%g rad/s)^2 = %.3g N exceeds %.0e N", u,
                                 speed, force, TD_MAX_UNBALANCE_FORCE);
    }
    return TD_OK;
}

/* The highest speed the run reaches up to end_time: `speed`, or on a ramp (piecewise linear) the
 * largest of its value at 0 and at end_time and of its points before end_time; *where: the setting
 * that gives it (`speed`, or the speed of that point or of the point that ends the segment holding
 * end_time). A free spin starts at its top. */
static double highest_speed(const td_case_reader *r, const config_setting_t *root, const config_setting_t **where)
{
    const td_model *m = r->c->model;
    const config_setting_t *ramp = config_setting_get_member(root, "speed_ramp");
    double top = td_model_speed_at(m, 0.0, NULL, NULL), end_time = r->c->end_time;
    int i;
    *where = config_setting_get_member(root, "speed");
    for (i = 0; i < td_model_speed_point_count(m); i++) {
        td_speed_point p;
        double w;
        td_model_get_speed_point(m, i, &p);
        w = p.time <= end_time ? p.speed : td_model_speed_at(m, end_time, NULL, NULL);
        if (w > top) {
            const config_setting_t *e = ramp ? config_setting_get_elem(ramp, (unsigned)i) : NULL;
            top = w;
            *where = e ? config_setting_get_member(e, "speed") : *where;
        }
        if (p.time > end_time)
            break;
    }
    return top;
}

/* The checks of the whole run, once the run settings are read (the `output` key's check). */
static td_status check_run(td_case_reader *r, const config_setting_t *root, const td_cs_key *k, void *rec)
{
    const config_setting_t *fastest = NULL;
    double speed = highest_speed(r, root, &fastest); /* the bounds hold at the highest speed the run reaches */
    td_status st = check_run_limits(r, root, speed, fastest);
    (void)k;
    (void)rec;
    if (st == TD_OK)
        st = check_atol(r, root);
    if (st == TD_OK)
        st = check_unbalance_forces(r, root, "unbalances", speed, fastest);
    if (st == TD_OK)
        st = check_unbalance_forces(r, root, "schedule", speed, fastest);
    return st;
}

/* long runs: end_at_rest only on a run that can come to rest (td_run_rest_refused), named at the key
 * and at the speed it judges */
static td_status check_end_at_rest(td_case_reader *r, const config_setting_t *root, const td_cs_key *k, void *rec)
{
    const td_case *c = rec;
    char why[256];
    if (!c->output.end_at_rest || !td_run_rest_refused(c->model, why, sizeof why))
        return TD_OK;
    return td_cr_fail_vs(r, config_setting_get_member(root, k->key), config_setting_get_member(root, "speed"), "%s",
                         why);
}

static td_status read_description(td_case_reader *r, const config_setting_t *root, const td_cs_key *k, void *rec)
{
    td_case *c = rec;
    const char *desc;
    size_t n;
    td_status st = td_cr_string(r, root, k->key, "", &desc);
    if (st != TD_OK)
        return st;
    n = strlen(desc);
    if (!(c->description = malloc(n + 1)))
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    memcpy(c->description, desc, n + 1);
    return TD_OK;
}

/* speed: the model's (its rules: td_model_set_speed) */
static td_status read_speed(td_case_reader *r, const config_setting_t *root, const td_cs_key *k, void *rec)
{
    td_case *c = rec;
    double speed;
    td_error merr;
    td_status st = td_cr_real(r, root, k->key, k->what, 0.0, k->range, &speed);
    if (st == TD_OK && (st = td_model_set_speed(c->model, speed, &merr)) != TD_OK)
        st = td_cr_model_fail(r, config_setting_get_member(root, k->key), st, &merr);
    return st;
}

static td_status read_shaft(td_case_reader *r, const config_setting_t *root, const td_cs_key *k, void *rec)
{
    (void)k;
    (void)rec;
    return td_cr_read_shaft(r, root);
}

static void root_preset(void *rec)
{
    td_case *c = rec;
    td_sim_options_default(&c->sim);
    td_output_options_default(&c->output);
    td_modal_options_default(&c->modal);
}

/* The top level, in the order of its "unknown key" list; `order` reads it in dependency order:
 * the shaft fixes the nodes, the speed comes before the controllers (a resonant block's frequency
 * defaults to it), AMBs (then the controllers that drive them) before retainers, the run settings
 * before the bounds on the run (the `output` key's check). */
static const td_cs_key root_keys[] = {
    {.key = "description",
     .type = TD_CS_STRING,
     .read = read_description,
     .doc_default = "`\"\"`",
     .doc = "free text, kept with the results"},
    {.key = "speed",
     .type = TD_CS_REAL,
     .need = TD_CS_REQUIRED,
     .range = TD_CR_NONNEGATIVE,
     .read = read_speed,
     .order = 4,
     .what = "rotor speed Omega, rad/s",
     .unit = "rad/s",
     .doc = "rotor speed Omega (spin about +z; a negative speed is refused here, by `--set`, by `touchdown modal "
            "--speed` and by the library: a machine that turns the other way is described from its other end, nodes "
            "numbered from the driven end): constant, or the speed before a `speed_ramp`'s first point, or the start "
            "speed of a free `spin`"},
    {.key = "end_time",
     .type = TD_CS_REAL,
     .offset = offsetof(td_case, end_time),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .order = 14,
     .what = "end time of the run, s",
     .unit = "s",
     .doc = "end of the run (the run starts at t = 0)"},
    {.key = "start",
     .type = TD_CS_ENUM,
     .offset = offsetof(td_case, sim.start),
     .need = TD_CS_PRESET,
     .names = start_names,
     .name_count = 3,
     .order = 15,
     .doc = "state at t = 0. `\"orbit\"`: the steady harmonic orbit of the contact-free linear system for the initial "
            "unbalances (plus static sag under gravity, AMB filter states included), of the machine as it is at the "
            "start, after the `schedule` entries due then (an AMB switched off at t = 0 exerts nothing); refused (exit "
            "2) when that system is unstable at the run speed (it has no steady orbit; a rotor that nothing holds, "
            "e.g. with no bearings and no AMB, is marginally stable and takes its orbit), when under gravity it has no "
            "static position (nothing holds it) or, with constraint contact, when the orbit lies outside a clearance. "
            "`\"rest\"`: centred at rest. `\"auto\"` (the shipped cases): the orbit when the system is stable, has a "
            "steady state and the orbit lies inside every clearance, else rest; the run summary says which start was "
            "used and why. The stability check is a dense eigenvalues-only solve (`td_modal_stability`) done at "
            "start-up for models of up to 800 first-order states (`TD_SIM_STABILITY_MAX_STATES`: the rig up to "
            "`shaft.refine = 8`, 96 elements, 784 states, where it adds about 1.2 s); bigger models are not checked "
            "(`touchdown modal` gives the eigenvalues)"},
    {.key = "shaft",
     .type = TD_CS_GROUP,
     .sub = &td_cs_shaft,
     .need = TD_CS_REQUIRED,
     .read = read_shaft,
     .order = 1,
     .doc = "see [shaft](#shaft)"},
    {.key = "discs",
     .type = TD_CS_LIST,
     .sub = &td_cs_discs,
     .order = 2,
     .doc = "rigid discs, see [discs](#discs-and-point-masses)"},
    {.key = "point_masses",
     .type = TD_CS_LIST,
     .sub = &td_cs_point_masses,
     .order = 3,
     .doc = "point masses without rotary inertia"},
    {.key = "ambs",
     .type = TD_CS_LIST,
     .sub = &td_cs_ambs,
     .order = 4,
     .doc = "active magnetic bearings, see [ambs](#ambs)"},
    {.key = "controllers",
     .type = TD_CS_LIST,
     .sub = &td_cs_controllers,
     .order = 4,
     .doc = "linear controllers of AMBs (transfer functions, blocks in series, rigid-body coordinates, sampled), "
            "see [controllers](#controllers)"},
    {.key = "recovery",
     .type = TD_CS_GROUP,
     .sub = &td_cs_recovery,
     .order = 4,
     .doc_default = "none",
     .doc = "a contact-aware supervisor that switches sampled controllers to recovery laws and back, see "
            "[recovery](#recovery)"},
    {.key = "bearings",
     .type = TD_CS_LIST,
     .sub = &td_cs_bearings,
     .order = 5,
     .doc = "plain linear bearings, see [bearings](#bearings)"},
    {.key = "retainers",
     .type = TD_CS_LIST,
     .sub = &td_cs_retainers,
     .order = 6,
     .doc = "retainer (backup) bearings, see [retainers](#retainers)"},
    {.key = "unbalances",
     .type = TD_CS_LIST,
     .sub = &td_cs_unbalances,
     .order = 7,
     .doc = "see [unbalances and schedule](#unbalances-and-schedule)"},
    {.key = "schedule",
     .type = TD_CS_LIST,
     .sub = &td_cs_schedule,
     .order = 8,
     .doc = "timed changes of unbalances and AMBs"},
    {.key = "gravity",
     .type = TD_CS_GROUP,
     .sub = &td_cs_gravity,
     .order = 12,
     .doc_default = "off",
     .doc = "see [gravity](#gravity)"},
    {.key = "contact",
     .type = TD_CS_GROUP,
     .sub = &td_cs_contact,
     .offset = offsetof(td_case, sim.contact),
     .order = 17,
     .doc_default = "defaults below",
     .doc = "contact law, see [contact](#contact)"},
    {.key = "solver",
     .type = TD_CS_GROUP,
     .sub = &td_cs_solver,
     .offset = offsetof(td_case, sim.solver),
     .order = 18,
     .doc_default = "defaults below",
     .doc = "see [solver](#solver)"},
    {.key = "output",
     .type = TD_CS_GROUP,
     .sub = &td_cs_output,
     .offset = offsetof(td_case, output),
     .order = 19,
     .check = check_run,
     .doc_default = "defaults below",
     .doc = "see [output](#output)"},
    {.key = "modal",
     .type = TD_CS_GROUP,
     .sub = &td_cs_modal,
     .offset = offsetof(td_case, modal),
     .order = 20,
     .doc_default = "defaults below",
     .doc = "see [modal](#modal)"},
    {.key = "overrides",
     .type = TD_CS_CUSTOM,
     .doc_type = "list of strings",
     .doc_default = "none",
     .doc = "`\"KEY=VALUE\"` changes applied to the case after it is read, in order, before any `--set` (same syntax): "
            "a variant of an included machine, e.g. `cases/rub-damped.cfg` gives the rig's retainers a race. An error "
            "in one names the file, the line of the entry and `overrides[i]`: `FILE:LINE: overrides[i]: 'KEY=VALUE': "
            "what`"}, /* applied before the case is read (case_override.c) */
    {.key = "energy",
     .type = TD_CS_BOOL,
     .offset = offsetof(td_case, sim.energy),
     .order = 16,
     .doc = "keep the energy account: the run summary, `--json` and the output files then give the energy held, put in "
            "and lost, and the balance's residual ([theory](theory.md#energy)); costs about 30 % more time on the "
            "undamped rig"},
    {.key = "speed_ramp",
     .type = TD_CS_LIST,
     .sub = &td_cs_speed_ramp,
     .order = 9,
     .doc = "a prescribed speed profile, see [speed transients](#speed-transients)"},
    {.key = "spin",
     .type = TD_CS_GROUP,
     .sub = &td_cs_spin,
     .order = 10,
     .doc_default = "prescribed speed",
     .doc = "the speed as a state (coast-down, drop), see [speed transients](#speed-transients)"},
    {.key = "reduction",
     .type = TD_CS_GROUP,
     .sub = &td_cs_reduction,
     .order = 13,
     .doc_default = "none (full model)",
     .doc = "a Craig-Bampton reduced rotor, see [reduction](#reduction)"},
    {.key = "sweep",
     .type = TD_CS_GROUP,
     .sub = &td_cs_sweep,
     .order = 21,
     .doc = "the keys `touchdown sweep` varies, see [sweep](#sweep); every command checks it, only `touchdown sweep` "
            "runs it"},
    /* the bearing's duty */
    {.key = "limits",
     .type = TD_CS_GROUP,
     .sub = &td_cs_limits,
     .order = 11,
     .doc_default = "the defaults below",
     .doc = "the limits a run is assessed against (vibration zones, temperature rise, drops), see "
            "[limits (assessment)](#limits-assessment)"},
    /* housing motion */
    {.key = "housing",
     .type = TD_CS_GROUP,
     .sub = &td_cs_housing,
     .order = 14,
     .doc_default = "none (a fixed housing)",
     .doc = "the housing's prescribed motion (shocks, a measured acceleration, a rotation), see "
            "[housing](#housing)"},
    /* long runs */
    {.key = "end_at_rest",
     .type = TD_CS_BOOL,
     .offset = offsetof(td_case, output.end_at_rest),
     .need = TD_CS_PRESET,
     .order = 14,
     .check = check_end_at_rest,
     .doc = "end the run, complete, at the first grid sample at which the rotor is at rest: its speed below 1 % of "
            "its start speed or below 1 rad/s (the rule of the ending \"at rest\"), tested only after the last "
            "prescribed change (every `schedule` entry's time, every `speed_ramp` point's, the end of every "
            "`housing` shock and rotation, the `housing.history`'s last time: a drop still to come has not "
            "happened); `end_time` then bounds the run. For a free `spin` (a coast-down, a drop followed "
            "to rest): `t_reached` says when it stopped. Refused when the rotor could not come to rest: a start "
            "`speed` of at most 1 rad/s (already at rest), a speed held constant (neither `spin.free` nor a "
            "`speed_ramp`), or a `speed_ramp` whose last point is not at rest (it holds that speed). It judges the "
            "speed alone: a rotor at rest may still bounce on its retainers"},
    /* projective leap */
    {.key = "leap",
     .type = TD_CS_GROUP,
     .sub = &td_cs_leap,
     .offset = offsetof(td_case, output),
     .order = 20,
     .check = td_cr_check_leap,
     .doc_default = "none (every second integrated)",
     .doc = "step the slow variables of a long coast-down over its stationary bounce, see "
            "[projective leap](#projective-leap)"},
};
const td_cs_table td_cs_root = {"", "top", root_keys, TD_CS_COUNT(root_keys), sizeof(td_case), root_preset, NULL};
