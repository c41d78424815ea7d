/*
 * Run settings: speed, gravity, end time, start state, and the option groups contact, solver,
 * output and modal. Defaults come from td_*_options_default (lib/util/options.c), so the case
 * reader never restates them.
 */
#include "case/case_internal.h"
#include "model/gap.h"
#include "touchdown/dofs.h"
#include "touchdown/modal.h"
#include "util/error_internal.h"
#include "util/limits.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *const gravity_keys[] = {"enabled", "g", "direction", NULL};
static const char *const contact_keys[] = {"model", "stiffness", "exponent", "damping", "damping_coefficient", NULL};
static const char *const solver_keys[] = {"rtol",      "atol",          "max_step",    "initial_step",
                                          "max_order", "linear_solver", "free_flight", NULL};
static const char *const output_keys[] = {"hdf5", "csv", "sample_rate", "nodes", "compression", "section_after", NULL};
static const char *const modal_keys[] = {"speed_min", "speed_max", "speed_steps", "modes", "response_speeds", NULL};

static const char *const start_names[] = {"orbit", "rest", "auto"}; /* td_start order */
static const char *const contact_names[] = {"constraint", "penalty"};
const char *const td_cr_damping_names[TD_CR_DAMPING_NAMES] = {"none", "hunt-crossley", "kelvin-voigt"};
static const char *const linsol_names[] = {"klu", "dense"};

/* Fail at member `key` of g when it is there (its line), else at g naming the key. */
static td_status fail_at(td_case_reader *r, const config_setting_t *g, const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static td_status fail_at(td_case_reader *r, const config_setting_t *g, const char *key, const char *fmt, ...)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return s ? td_cr_fail(r, s, NULL, "%s", msg) : td_cr_fail(r, g, key, "%s", msg);
}

/* gravity { enabled; g; direction [gx, gy]; }: acceleration g along the (normalised) direction. */
static td_status read_gravity(td_case_reader *r, const config_setting_t *root)
{
    const config_setting_t *grav;
    double g = 9.81, dir[2] = {0.0, -1.0}, norm, scale;
    int enabled = 0, n = 2;
    td_error merr;
    td_status st = td_cr_group(r, root, "gravity", NULL, &grav);
    if (st != TD_OK || !grav)
        return st;
    st = td_cr_check_keys(r, grav, gravity_keys);
    if (st == TD_OK)
        st = td_cr_bool(r, grav, "enabled", 1, &enabled);
    if (st == TD_OK)
        st = td_cr_real(r, grav, "g", NULL, 9.81, TD_CR_NONNEGATIVE, &g);
    if (st == TD_OK && td_cr_has(grav, "direction")) {
        const config_setting_t *d = config_setting_get_member(grav, "direction");
        st = td_cr_reals(r, grav, "direction", 2, TD_CR_FINITE, dir, &n);
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
    }
    if (st != TD_OK)
        return st;
    if (!enabled)
        g = 0.0;
    st = td_model_set_gravity(r->c->model, g * dir[0], g * dir[1], &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, grav, st, &merr);
}

/* reduction { cutoff; }: a Craig-Bampton reduced rotor keeping the fixed-interface modes below
 * cutoff Hz (docs/theory.md, "Reduced rotor"); absent: the full model. */
static td_status read_reduction(td_case_reader *r, const config_setting_t *root)
{
    static const char *const keys[] = {"cutoff", NULL};
    const config_setting_t *g;
    double cutoff = 0.0;
    td_error merr;
    td_status st = td_cr_group(r, root, "reduction", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, keys);
    if (st == TD_OK)
        st = td_cr_real(r, g, "cutoff", "cut-off frequency of the fixed-interface modes, Hz", 0.0, TD_CR_POSITIVE,
                        &cutoff);
    if (st != TD_OK)
        return st;
    st = td_model_set_reduction(r->c->model, cutoff, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static td_status read_contact(td_case_reader *r, const config_setting_t *root, td_contact_options *o)
{
    const config_setting_t *g, *e;
    int model = (int)o->model, damping = (int)o->damping;
    td_status st = td_cr_group(r, root, "contact", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, contact_keys);
    if (st == TD_OK)
        st = td_cr_enum(r, g, "model", contact_names, 2, model, &model);
    if (st == TD_OK)
        st = td_cr_real(r, g, "stiffness", NULL, o->stiffness, TD_CR_POSITIVE, &o->stiffness);
    if (st == TD_OK)
        st = td_cr_real(r, g, "exponent", NULL, o->exponent, TD_CR_POSITIVE, &o->exponent);
    if (st == TD_OK && o->exponent < 1.0 && (e = config_setting_get_member(g, "exponent")) != NULL)
        /* p < 1 gives an infinite contact stiffness dF/ddelta at first touch */
        st = td_cr_fail(r, e, NULL, "must be >= 1 (got %g)", o->exponent);
    if (st == TD_OK)
        st = td_cr_enum(r, g, "damping", td_cr_damping_names, TD_CR_DAMPING_NAMES, damping, &damping);
    if (st == TD_OK)
        st = td_cr_real(r, g, "damping_coefficient", NULL, o->damping_coefficient, TD_CR_NONNEGATIVE,
                        &o->damping_coefficient);
    o->model = (td_contact_model)model;
    o->damping = (td_contact_damping)damping;
    return st;
}

static td_status read_solver(td_case_reader *r, const config_setting_t *root, td_solver_options *o)
{
    const config_setting_t *g;
    int linsol = (int)o->linear_solver;
    td_status st = td_cr_group(r, root, "solver", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, solver_keys);
    if (st == TD_OK)
        st = td_cr_real(r, g, "rtol", NULL, o->rtol, TD_CR_OPEN_UNIT, &o->rtol);
    if (st == TD_OK)
        st = td_cr_real(r, g, "atol", NULL, o->atol, TD_CR_POSITIVE, &o->atol);
    if (st == TD_OK)
        st = td_cr_real(r, g, "max_step", NULL, o->max_step, TD_CR_NONNEGATIVE, &o->max_step);
    if (st == TD_OK)
        st = td_cr_real(r, g, "initial_step", NULL, o->initial_step, TD_CR_NONNEGATIVE, &o->initial_step);
    if (st == TD_OK && o->max_step > 0.0 && o->initial_step > o->max_step)
        st = fail_at(r, g, "initial_step", "%g s is larger than max_step %g s", o->initial_step, o->max_step);
    if (st == TD_OK)
        st = td_cr_int(r, g, "max_order", NULL, o->max_order, 1, 5, &o->max_order);
    if (st == TD_OK)
        st = td_cr_enum(r, g, "linear_solver", linsol_names, 2, linsol, &linsol);
    o->linear_solver = (td_linear_solver)linsol;
    if (st == TD_OK)
        st = td_cr_bool(r, g, "free_flight", o->free_flight, &o->free_flight);
    return st;
}

/* A path string member into a fixed buffer. */
static td_status read_path(td_case_reader *r, const config_setting_t *g, const char *key, char *buf)
{
    const char *v;
    td_status st = td_cr_string(r, g, key, "", &v);
    if (st != TD_OK)
        return st;
    if (strlen(v) >= TD_OUTPUT_PATH_SIZE)
        return td_cr_fail(r, config_setting_get_member(g, key), NULL, "path too long (%lu characters, at most %d)",
                          (unsigned long)strlen(v), TD_OUTPUT_PATH_SIZE - 1);
    strcpy(buf, v);
    return TD_OK;
}

static td_status read_output(td_case_reader *r, const config_setting_t *root, td_output_options *o)
{
    const config_setting_t *g, *list;
    int i, j;
    td_status st = td_cr_group(r, root, "output", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, output_keys);
    if (st == TD_OK)
        st = read_path(r, g, "hdf5", o->hdf5_path);
    if (st == TD_OK)
        st = read_path(r, g, "csv", o->csv_path);
    if (st == TD_OK)
        st = td_cr_real(r, g, "sample_rate", NULL, o->sample_rate, TD_CR_POSITIVE, &o->sample_rate);
    if (st == TD_OK)
        st = td_cr_int(r, g, "compression", NULL, o->compression, 0, 9, &o->compression);
    if (st == TD_OK)
        st = td_cr_real(r, g, "section_after", NULL, o->section_after, TD_CR_FRACTION, &o->section_after);
    if (st == TD_OK)
        st = td_cr_ints(r, g, "nodes", TD_OUTPUT_MAX_NODES, -2147483647L, 2147483647L, o->nodes, &o->node_count);
    if (st != TD_OK)
        return st;
    list = config_setting_get_member(g, "nodes");
    for (i = 0; i < o->node_count; i++) {
        const config_setting_t *s = config_setting_get_elem(list, (unsigned)i);
        if (o->nodes[i] < 0 || o->nodes[i] >= r->nodes)
            return td_cr_fail(r, s, NULL, "node %d is out of range (the shaft has nodes 0..%d)", o->nodes[i],
                              r->nodes - 1);
        for (j = 0; j < i; j++)
            if (o->nodes[j] == o->nodes[i])
                return td_cr_fail(r, s, NULL, "node %d is listed twice", o->nodes[i]);
    }
    return TD_OK;
}

static td_status read_modal(td_case_reader *r, const config_setting_t *root, td_modal_options *o)
{
    const config_setting_t *g;
    int dofs = TD_DOFS_PER_NODE * ((r->nodes - 1) * r->refine + 1); /* of the refined shaft (case.c) */
    td_status st = td_cr_group(r, root, "modal", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, modal_keys);
    if (st == TD_OK)
        st = td_cr_real(r, g, "speed_min", NULL, o->speed_min, TD_CR_NONNEGATIVE, &o->speed_min);
    if (st == TD_OK)
        st = td_cr_real(r, g, "speed_max", NULL, o->speed_max, TD_CR_POSITIVE, &o->speed_max);
    if (st == TD_OK && !(o->speed_max > o->speed_min))
        st = fail_at(r, g, td_cr_has(g, "speed_max") ? "speed_max" : "speed_min",
                     "speed_max (%g rad/s) must be larger than speed_min (%g rad/s)", o->speed_max, o->speed_min);
    if (st == TD_OK)
        st = td_cr_int(r, g, "speed_steps", NULL, o->speed_steps, 2, 100000, &o->speed_steps);
    if (st == TD_OK && td_cr_has(g, "speed_steps") && (long)o->speed_steps * dofs > TD_MODAL_MAX_GRID_WORK)
        st = fail_at(r, g, "speed_steps",
                     "%d speeds on a model of %d DOFs is too much work: speed_steps x DOFs must "
                     "stay below %ld (here at most %ld speeds; see docs/performance.md)",
                     o->speed_steps, dofs, (long)TD_MODAL_MAX_GRID_WORK, (long)TD_MODAL_MAX_GRID_WORK / dofs);
    if (st == TD_OK)
        st = td_cr_int(r, g, "modes", NULL, o->mode_count < dofs ? o->mode_count : dofs, 1, dofs, &o->mode_count);
    if (st == TD_OK)
        st = td_cr_reals(r, g, "response_speeds", (int)(sizeof o->response_speeds / sizeof o->response_speeds[0]),
                         TD_CR_NONNEGATIVE, o->response_speeds, &o->response_speed_count);
    return st;
}

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
static td_status check_unbalance_forces(td_case_reader *r, const config_setting_t *root, const char *key, double speed)
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
            return td_cr_fail(r, s, NULL,
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

td_status td_cr_read_options(td_case_reader *r, const config_setting_t *root)
{
    td_case *c = r->c;
    double speed;
    int start = (int)c->sim.start;
    const config_setting_t *fastest = NULL;
    td_error merr;
    td_status st = td_cr_real(r, root, "speed", "rotor speed Omega, rad/s", 0.0, TD_CR_NONNEGATIVE, &speed);
    if (st == TD_OK && (st = td_model_set_speed(c->model, speed, &merr)) != TD_OK)
        st = td_cr_model_fail(r, config_setting_get_member(root, "speed"), st, &merr);
    if (st == TD_OK)
        st = read_gravity(r, root);
    if (st == TD_OK)
        st = read_reduction(r, root);
    if (st == TD_OK)
        st = td_cr_real(r, root, "end_time", "end time of the run, s", 0.0, TD_CR_POSITIVE, &c->end_time);
    if (st == TD_OK)
        st = td_cr_enum(r, root, "start", start_names, 3, start, &start);
    c->sim.start = (td_start)start;
    if (st == TD_OK)
        st = td_cr_bool(r, root, "energy", 0, &c->sim.energy);
    if (st == TD_OK)
        st = read_contact(r, root, &c->sim.contact);
    if (st == TD_OK)
        st = read_solver(r, root, &c->sim.solver);
    if (st == TD_OK)
        st = read_output(r, root, &c->output);
    if (st == TD_OK) /* the bounds hold at the highest speed the run reaches */
        speed = highest_speed(r, root, &fastest);
    if (st == TD_OK)
        st = check_run_limits(r, root, speed, fastest);
    if (st == TD_OK)
        st = check_atol(r, root);
    if (st == TD_OK)
        st = check_unbalance_forces(r, root, "unbalances", speed);
    if (st == TD_OK)
        st = check_unbalance_forces(r, root, "schedule", speed);
    if (st == TD_OK)
        st = read_modal(r, root, &c->modal);
    return st;
}
