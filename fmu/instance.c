/*
 * An instance of touchdown's FMU (instance.h): made from its resources (lib/fmu/fmu_internal.h), the
 * simulation created at initialisation from the case with the parameters the importer set (each a
 * td_case_load override KEY=VALUE), and stepped from one communication point exactly onto the next
 * (FMI 2.0, 4.2.2 fmi2DoStep), through every event inside the step.
 */
#include "fmu/instance.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The category of a line of `status`. */
static td_fmu_log_category category_of(fmi2Status status)
{
    return status >= fmi2Error ? TD_FMU_LOG_ERROR : status == fmi2OK ? TD_FMU_LOG_EVENTS : TD_FMU_LOG_DISCARD;
}

fmi2Status td_fmu_log(const td_fmu_instance *in, fmi2Status status, const char *fmt, ...)
{
    char msg[TD_ERROR_MESSAGE_SIZE + 128];
    td_fmu_log_category cat = category_of(status);
    va_list ap;
    /* an error's line is the reason of the fmi2Error it comes with, not debug output: always sent */
    if (!in->logger || (cat != TD_FMU_LOG_ERROR && !(in->logging && (in->log_mask & (1u << cat)))))
        return status;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* the message is data, never the logger's format */
    in->logger(in->env, in->name, status, td_fmu_log_categories[cat].name, "%s", msg);
    return status;
}

fmi2Status td_fmu_instance_set_logging(td_fmu_instance *in, int on, size_t n, const fmi2String categories[])
{
    unsigned mask = n ? 0u : (1u << TD_FMU_LOG_CATEGORIES) - 1u;
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        for (k = 0; k < TD_FMU_LOG_CATEGORIES && categories && categories[i]; k++)
            if (strcmp(categories[i], td_fmu_log_categories[k].name) == 0)
                break;
        if (!categories || !categories[i] || k == TD_FMU_LOG_CATEGORIES)
            return td_fmu_log(in, fmi2Error,
                              "fmi2SetDebugLogging: '%s' is no log category of this FMU (see its "
                              "modelDescription.xml)",
                              categories && categories[i] ? categories[i] : "(null)");
        mask |= 1u << k;
    }
    in->logging = on;
    in->log_mask = mask;
    return fmi2OK;
}

static int hex(int c)
{
    return c >= '0' && c <= '9'   ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                  : -1;
}

/* The local path of a file URI (RFC 8089: file:///p, file://localhost/p, file:/p), percent-decoded,
 * without a trailing slash; NULL for anything else. */
static char *uri_path(const char *uri)
{
    const char *p;
    char *out, *o;
    if (!uri || strncmp(uri, "file:", 5) != 0)
        return NULL;
    p = uri + 5;
    if (strncmp(p, "//localhost/", 12) == 0)
        p += 11;
    else if (strncmp(p, "///", 3) == 0)
        p += 2;
    else if (p[0] != '/' || p[1] == '/')
        return NULL; /* a remote host */
    if (!(out = malloc(strlen(p) + 1)))
        return NULL;
    for (o = out; *p; p++) {
        if (*p == '%' && hex(p[1]) >= 0 && hex(p[2]) >= 0) {
            *o++ = (char)(16 * hex(p[1]) + hex(p[2]));
            p += 2;
        } else {
            *o++ = *p;
        }
    }
    *o = '\0';
    while (o > out + 1 && o[-1] == '/')
        *--o = '\0';
    return out;
}

/* The variables and their start values from the case of the resources. */
static int load_variables(td_fmu_instance *in)
{
    td_case *c = NULL;
    td_error err;
    int i;
    if (td_case_load(in->settings.case_path, (const char *const *)in->settings.overrides, in->settings.n_overrides, &c,
                     &err) != TD_OK) {
        td_fmu_log(in, fmi2Error, "%s", err.message);
        return 0;
    }
    if (td_fmu_check_start(c, in->settings.inputs, &err) != TD_OK) {
        td_fmu_log(in, fmi2Error, "fmi2Instantiate: %s", err.message);
        td_case_free(&c);
        return 0;
    }
    i = td_fmu_variables(td_case_model(c), in->settings.inputs, &in->var, &in->n_var, &err) == TD_OK;
    td_case_free(&c);
    if (!i || !(in->value = calloc((size_t)in->n_var + 1, sizeof *in->value))) {
        td_fmu_log(in, fmi2Error, "out of memory instantiating the FMU");
        return 0;
    }
    td_fmu_instance_reset(in);
    return 1;
}

td_fmu_instance *td_fmu_instance_create(const char *name, const char *guid, const char *resources,
                                        fmi2CallbackLogger logger, fmi2ComponentEnvironment env, int logging)
{
    td_fmu_instance *in = calloc(1, sizeof *in);
    char *dir;
    td_error err;
    if (!in)
        return NULL;
    in->logger = logger, in->env = env, in->logging = logging;
    in->log_mask = (1u << TD_FMU_LOG_CATEGORIES) - 1u;
    if (!(in->name = malloc(strlen(name ? name : "") + 1))) {
        free(in);
        return NULL;
    }
    strcpy(in->name, name ? name : "");
    if (!(dir = uri_path(resources))) {
        td_fmu_log(in, fmi2Error, "fmi2Instantiate: the resource location '%s' is not a local file URI",
                   resources ? resources : "(null)");
    } else if (td_fmu_settings_read(dir, &in->settings, &err) != TD_OK) {
        td_fmu_log(in, fmi2Error, "fmi2Instantiate: %s", err.message);
    } else if (!guid || strcmp(guid, in->settings.guid) != 0) {
        td_fmu_log(in, fmi2Error, "fmi2Instantiate: guid %s is not the FMU's %s", guid ? guid : "(null)",
                   in->settings.guid);
    } else if (load_variables(in)) {
        free(dir);
        return in;
    }
    free(dir);
    td_fmu_instance_free(in);
    return NULL;
}

void td_fmu_instance_free(td_fmu_instance *in)
{
    if (!in)
        return;
    td_sim_free(&in->sim);
    td_fmu_settings_free(&in->settings);
    free(in->var);
    free(in->value);
    free(in->q);
    free(in->name);
    free(in);
}

void td_fmu_instance_reset(td_fmu_instance *in)
{
    int i;
    td_sim_free(&in->sim);
    for (i = 0; i < in->n_var; i++)
        in->value[i] = in->var[i].start;
    in->state = TD_FMU_INSTANTIATED;
    in->t_start = in->t_comm = 0.0;
    in->has_stop = 0;
    in->inputs_held = 0;
}

/* The overrides of the simulation: the staged ones, then KEY=VALUE for each parameter the importer
 * changed (a parameter left at its start value is the case's own, untouched). *list (free() it and
 * its strings), *n; 0 when out of memory. */
static int parameter_overrides(const td_fmu_instance *in, char ***list, int *n)
{
    int i, k = in->settings.n_overrides;
    char **l = calloc((size_t)(k + in->n_var + 1), sizeof *l);
    *list = l;
    *n = 0;
    if (!l)
        return 0;
    for (i = 0; i < k; i++)
        l[(*n)++] = in->settings.overrides[i];
    for (i = 0; i < in->n_var; i++) {
        const td_fmu_var *v = &in->var[i];
        if (v->causality != TD_FMU_PARAMETER || memcmp(&in->value[i], &v->start, sizeof(double)) == 0)
            continue;
        if (!(l[*n] = malloc(TD_FMU_NAME_SIZE + 32)))
            return 0;
        snprintf(l[(*n)++], TD_FMU_NAME_SIZE + 32, "%s=%.17g", v->name, in->value[i]);
    }
    return 1;
}

static void free_overrides(const td_fmu_instance *in, char **list, int n)
{
    int i;
    for (i = in->settings.n_overrides; list && i < n; i++)
        free(list[i]);
    free(list);
}

/* The held inputs into the simulation: per AMB its current (TD_AMB_CURRENT) or control force. */
static fmi2Status apply_inputs(td_fmu_instance *in)
{
    td_error err;
    int i;
    for (i = 0; i < in->n_var && !in->inputs_held; i++) {
        const td_fmu_var *v = &in->var[i];
        td_status st = TD_OK;
        if (v->causality != TD_FMU_INPUT || v->axis != 0)
            continue; /* x and y together, at the x input (y follows it: td_fmu_variables) */
        if (v->quantity == TD_FMU_Q_CURRENT_IN)
            st = td_sim_set_amb_current(in->sim, v->index, in->value[i], in->value[i + 1], &err);
        else
            st = td_sim_set_amb_control(in->sim, v->index, in->value[i], in->value[i + 1], &err);
        if (st != TD_OK)
            return td_fmu_log(in, fmi2Error, "%s", err.message);
    }
    in->inputs_held = 1;
    return fmi2OK;
}

/* Every AMB driven by the inputs (none: the case's own laws drive them); one the case's schedule has
 * failed at the start stays failed, and its restore (if the schedule has one) gives it to the inputs. */
static fmi2Status input_modes(td_fmu_instance *in)
{
    td_amb_mode mode = in->settings.inputs == TD_FMU_INPUTS_CURRENT ? TD_AMB_CURRENT : TD_AMB_EXTERNAL;
    td_error err;
    int a;
    for (a = 0; in->settings.inputs != TD_FMU_INPUTS_NONE && a < td_model_amb_count(td_sim_model(in->sim)); a++) {
        int failed = td_sim_amb_mode(in->sim, a) == TD_AMB_OFF;
        if (td_sim_set_amb_mode(in->sim, a, mode, &err) != TD_OK ||
            (failed && td_sim_set_amb_mode(in->sim, a, TD_AMB_OFF, &err) != TD_OK))
            return td_fmu_log(in, fmi2Error, "%s", err.message);
    }
    in->inputs_held = 0;
    return apply_inputs(in);
}

/* The line of a case that fails to load: when the override at fault is one of the importer's
 * parameters (the case reader names it in err->site, touchdown/error.h), the parameter and the
 * reader's reason, since the importer set neither a --set nor the resources' path. */
static fmi2Status load_failed(const td_fmu_instance *in, const char *what, char **ov, int n, const td_error *err)
{
    int i = err->site.part && strcmp(err->site.part, "override") == 0 ? err->site.index : -1;
    const char *eq = i >= in->settings.n_overrides && i < n ? strchr(ov[i], '=') : NULL; /* KEY=VALUE */
    if (eq)
        return td_fmu_log(in, fmi2Error, "%s: parameter %.*s = %s: %s", what, (int)(eq - ov[i]), ov[i], eq + 1,
                          err->message + err->reason);
    return td_fmu_log(in, fmi2Error, "%s: %s", what, err->message);
}

/* The simulation of case c from t_start. An FMU with inputs starts at rest when the case asks for
 * "auto": the orbit would be the case's own controllers', which the inputs replace (load_variables
 * refuses "orbit"). */
static fmi2Status create_sim(td_fmu_instance *in, const char *what, const td_case *c)
{
    td_sim_options opt = *td_case_sim_options(c);
    td_error err;
    opt.t0 = in->t_start;
    if (in->settings.inputs != TD_FMU_INPUTS_NONE && opt.start == TD_START_AUTO)
        opt.start = TD_START_REST;
    if (td_sim_create(td_case_model(c), &opt, &in->sim, &err) != TD_OK)
        return td_fmu_log(in, fmi2Error, "%s: %s", what, err.message);
    free(in->q); /* the displacements' buffer for the sensed outputs, made once here */
    if (!(in->q = malloc(sizeof(double) * (size_t)(td_sim_dof_count(in->sim) + 1)))) {
        td_sim_free(&in->sim);
        return td_fmu_log(in, fmi2Error, "%s: out of memory initialising the FMU", what);
    }
    return input_modes(in);
}

fmi2Status td_fmu_instance_start(td_fmu_instance *in, const char *what)
{
    td_case *c = NULL;
    td_error err;
    char **ov;
    int n;
    fmi2Status fs;
    td_sim_free(&in->sim);
    if (!parameter_overrides(in, &ov, &n)) {
        free_overrides(in, ov, n);
        return td_fmu_log(in, fmi2Error, "%s: out of memory initialising the FMU", what);
    }
    if (td_case_load(in->settings.case_path, (const char *const *)ov, n, &c, &err) != TD_OK)
        fs = load_failed(in, what, ov, n, &err);
    else
        fs = create_sim(in, what, c);
    td_case_free(&c);
    free_overrides(in, ov, n);
    in->t_comm = in->t_start;
    return fs;
}

/* An event inside a step, into the log (category logEvents). */
static void log_event(td_fmu_instance *in)
{
    td_event ev;
    if (td_sim_last_event(in->sim, &ev) == TD_OK)
        td_fmu_log(in, fmi2OK, "event %s at t = %.17g s (retainer %d)", td_event_kind_name(ev.kind), ev.time,
                   ev.retainer);
}

fmi2Status td_fmu_instance_step(td_fmu_instance *in, double t, double h)
{
    double tout = t + h, tol = 1e-12 * fmax(1.0, fabs(in->t_comm));
    td_status st;
    td_error err;
    if (!isfinite(t) || !isfinite(h) || !(h > 0.0))
        return td_fmu_log(in, fmi2Error, "fmi2DoStep: the step must be finite and > 0 (t = %.17g, h = %.17g)", t, h);
    if (fabs(t - in->t_comm) > tol)
        return td_fmu_log(in, fmi2Error, "fmi2DoStep: the communication point %.17g is not the FMU's time %.17g", t,
                          in->t_comm);
    if (in->has_stop && tout > in->t_stop + 1e-12 * fmax(1.0, fabs(in->t_stop)))
        return td_fmu_log(in, fmi2Error, "fmi2DoStep: t + h = %.17g is past the stop time %.17g", tout, in->t_stop);
    if (!(tout > td_sim_time(in->sim)))
        return td_fmu_log(in, fmi2Error, "fmi2DoStep: t + h = %.17g does not move on from %.17g", tout,
                          td_sim_time(in->sim));
    if (apply_inputs(in) != fmi2OK)
        return fmi2Error;
    while ((st = td_sim_step(in->sim, tout, NULL, &err)) == TD_EVENT)
        log_event(in);
    if (st != TD_OK)
        return td_fmu_log(in, fmi2Error, "fmi2DoStep at t = %.17g: %s", td_sim_time(in->sim), err.message);
    in->t_comm = tout;
    return fmi2OK;
}

fmi2Status td_fmu_instance_set_real(td_fmu_instance *in, const fmi2ValueReference vr[], size_t n, const fmi2Real v[])
{
    size_t i;
    for (i = 0; i < n; i++) { /* all checked before any is set: a refused call changes nothing */
        const td_fmu_var *var = vr[i] < (fmi2ValueReference)in->n_var ? &in->var[vr[i]] : NULL;
        if (!var)
            return td_fmu_log(in, fmi2Error, "fmi2SetReal: value reference %u is no variable of this FMU", vr[i]);
        if (var->type != TD_FMU_REAL || var->causality == TD_FMU_OUTPUT)
            return td_fmu_log(in, fmi2Error,
                              "fmi2SetReal: %s (value reference %u) is an output, not an input or parameter", var->name,
                              vr[i]);
        if (var->causality == TD_FMU_PARAMETER && in->state >= TD_FMU_STEPPING)
            return td_fmu_log(in, fmi2Error, "fmi2SetReal: %s is a fixed parameter: set it before initialisation ends",
                              var->name);
        if (!isfinite(v[i]))
            return td_fmu_log(in, fmi2Error, "fmi2SetReal: %s = %g: not a finite number", var->name, v[i]);
    }
    for (i = 0; i < n; i++) {
        const td_fmu_var *var = &in->var[vr[i]];
        if (var->causality == TD_FMU_PARAMETER && in->sim) /* made in initialisation mode: made again */
            td_sim_free(&in->sim);
        if (var->causality == TD_FMU_INPUT && in->value[vr[i]] != v[i])
            in->inputs_held = 0;
        in->value[vr[i]] = v[i];
    }
    return fmi2OK;
}

/* Output `v` of the simulation now: *x; fmi2Error (logged by the caller) when the simulation cannot
 * give it. */
static int output(const td_fmu_instance *in, const td_fmu_var *v, double *x)
{
    td_retainer_state rs;
    td_retainer_totals rt;
    td_sim_stats stats;
    double f[2];
    td_amb amb;
    td_sim_stats_get(in->sim, &stats);
    switch (v->quantity) {
    case TD_FMU_Q_SENSED:
        if (td_model_get_amb(td_sim_model(in->sim), v->index, &amb) != TD_OK ||
            td_sim_get_state(in->sim, in->q, NULL) != TD_OK)
            return 0;
        *x = td_system_node_displacement(td_sim_system(in->sim), in->q, amb.sensor_node, v->axis ? TD_DOF_Y : TD_DOF_X);
        return 1;
    case TD_FMU_Q_AMB_FORCE: return td_sim_amb_force(in->sim, v->index, f) == TD_OK ? (*x = f[v->axis], 1) : 0;
    case TD_FMU_Q_CONTACT_FORCE:
    case TD_FMU_Q_IN_CONTACT:
        if (td_sim_retainer_state(in->sim, v->index, &rs) != TD_OK)
            return 0;
        *x = v->quantity == TD_FMU_Q_IN_CONTACT ? (double)(rs.in_contact != 0) : rs.normal_force;
        return 1;
    case TD_FMU_Q_IMPACTS: /* every contact onset: a contact interval or a touch-and-go impact (records.h) */
        if (td_sim_retainer_totals(in->sim, v->index, &rt) != TD_OK)
            return 0;
        *x = (double)(rt.contacts + rt.touch_and_go);
        return 1;
    case TD_FMU_Q_ROTOR_SPEED: *x = td_sim_speed(in->sim); return 1;
    case TD_FMU_Q_EVENTS: *x = (double)stats.events; return 1;
    case TD_FMU_Q_HAD_CONTACT: *x = (double)!td_is_undefined(stats.first_contact_time); return 1;
    case TD_FMU_Q_FIRST_CONTACT: *x = stats.first_contact_time; return 1;
    case TD_FMU_Q_PEAK_FORCE: *x = stats.peak_normal_force; return 1; /* 0 before a contact: no force yet */
    default: return 0;
    }
}

fmi2Status td_fmu_instance_get(td_fmu_instance *in, fmi2ValueReference vr, td_fmu_type type, double *out)
{
    const td_fmu_var *v = vr < (fmi2ValueReference)in->n_var ? &in->var[vr] : NULL;
    static const char *const names[] = {"Real", "Integer", "Boolean"};
    if (!v)
        return td_fmu_log(in, fmi2Error, "fmi2Get%s: value reference %u is no variable of this FMU", names[type], vr);
    if (v->type != type)
        return td_fmu_log(in, fmi2Error, "fmi2Get%s: %s (value reference %u) is a %s variable", names[type], v->name,
                          vr, names[v->type]);
    if (v->causality != TD_FMU_OUTPUT) {
        *out = in->value[vr];
        return fmi2OK;
    }
    if (!in->sim && in->state != TD_FMU_INITIALISING)
        return td_fmu_log(in, fmi2Error, "fmi2Get%s: %s has no value before initialisation", names[type], v->name);
    if (!in->sim) {
        char what[32];
        snprintf(what, sizeof what, "fmi2Get%s", names[type]);
        if (td_fmu_instance_start(in, what) != fmi2OK)
            return fmi2Error;
    }
    if (!output(in, v, out))
        return td_fmu_log(in, fmi2Error, "fmi2Get%s: %s: the simulation cannot give it at t = %.17g", names[type],
                          v->name, td_sim_time(in->sim));
    return fmi2OK;
}
