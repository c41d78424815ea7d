/*
 * The variables of a case's FMU (fmu_internal.h): parameters (the common case keys the case sets,
 * named by their keys so that a value set by the importer is a td_case_load override), the inputs
 * the FMU was staged with, and the outputs: per AMB axis the sensed displacement and the force, per
 * retainer the normal force, whether it touches and its impacts, the rotor speed, the events and
 * the run's first contact and peak contact force (touchdown/records.h td_sim_stats).
 */
#include "fmu/fmu_internal.h"
#include "util/error_internal.h"

#include <stdio.h>
#include <stdlib.h>

typedef struct var_list {
    td_fmu_var *v;
    int n, cap;
} var_list;

static td_fmu_var *add(var_list *l, td_fmu_type type, td_fmu_causality causality, td_fmu_quantity q, int index,
                       int axis)
{
    td_fmu_var *v;
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 32;
        td_fmu_var *p = realloc(l->v, (size_t)cap * sizeof *p);
        if (!p)
            return NULL;
        l->v = p;
        l->cap = cap;
    }
    v = &l->v[l->n];
    v->vr = (unsigned int)l->n;
    l->n++;
    v->type = type;
    v->causality = causality;
    v->quantity = q;
    v->index = index;
    v->axis = axis;
    v->start = 0.0;
    v->name[0] = '\0';
    v->unit = "";
    v->description = "";
    return v;
}

/* A parameter named `key` with the case's value. */
static int add_param(var_list *l, td_fmu_quantity q, int index, const char *key, double value, const char *unit,
                     const char *description)
{
    td_fmu_var *v = add(l, TD_FMU_REAL, TD_FMU_PARAMETER, q, index, 0);
    if (!v)
        return 0;
    snprintf(v->name, sizeof v->name, "%s", key);
    v->start = value;
    v->unit = unit;
    v->description = description;
    return 1;
}

static int add_parameters(var_list *l, const td_model *m)
{
    char key[TD_FMU_NAME_SIZE];
    int i, ok = 1;
    if (!td_model_speed_varies(m)) /* a ramp or a free spin: the speed is not one number */
        ok = add_param(l, TD_FMU_Q_SPEED_PARAM, 0, "speed", td_model_speed(m), "rad/s", "rotor speed Omega");
    for (i = 0; ok && i < td_model_unbalance_count(m); i++) {
        td_unbalance u;
        td_model_get_unbalance(m, i, &u);
        snprintf(key, sizeof key, "unbalances[%d].magnitude", i);
        ok = add_param(l, TD_FMU_Q_UNBALANCE, i, key, u.magnitude, "kg.m", "unbalance U at t = 0");
        snprintf(key, sizeof key, "unbalances[%d].phase", i);
        ok = ok && add_param(l, TD_FMU_Q_UNBALANCE_PHASE, i, key, u.phase, "rad", "unbalance phase");
    }
    for (i = 0; ok && i < td_model_retainer_count(m); i++) {
        td_retainer r;
        td_model_get_retainer(m, i, &r);
        snprintf(key, sizeof key, "retainers[%d].clearance", i);
        ok = add_param(l, TD_FMU_Q_CLEARANCE, i, key, r.clearance, "m", "radial clearance c");
        snprintf(key, sizeof key, "retainers[%d].friction", i);
        ok = ok && add_param(l, TD_FMU_Q_FRICTION, i, key, r.friction, "1", "Coulomb friction coefficient mu");
    }
    return ok;
}

/* A variable of AMB or retainer `index` named "PART[index].SUFFIX" (axis >= 0: "_x" or "_y" after it). */
static int add_part(var_list *l, td_fmu_type type, td_fmu_causality c, td_fmu_quantity q, int index, int axis,
                    const char *part, const char *suffix, const char *unit, const char *description)
{
    td_fmu_var *v = add(l, type, c, q, index, axis < 0 ? 0 : axis);
    if (!v)
        return 0;
    if (axis < 0)
        snprintf(v->name, sizeof v->name, "%s[%d].%s", part, index, suffix);
    else
        snprintf(v->name, sizeof v->name, "%s[%d].%s_%c", part, index, suffix, axis == 0 ? 'x' : 'y');
    v->unit = unit;
    v->description = description;
    return 1;
}

static int add_inputs(var_list *l, const td_model *m, td_fmu_inputs inputs)
{
    int a, k, ok = 1;
    for (a = 0; ok && inputs != TD_FMU_INPUTS_NONE && a < td_model_amb_count(m); a++)
        for (k = 0; ok && k < 2; k++)
            ok = inputs == TD_FMU_INPUTS_CURRENT
                     ? add_part(l, TD_FMU_REAL, TD_FMU_INPUT, TD_FMU_Q_CURRENT_IN, a, k, "ambs", "current", "A",
                                "current command, through the amplifier's lag, slew limit and clip")
                     : add_part(l, TD_FMU_REAL, TD_FMU_INPUT, TD_FMU_Q_FORCE_IN, a, k, "ambs", "control_force", "N",
                                "control force ki i, held (the total force is ks x + it)");
    return ok;
}

/* An output of the whole machine. */
static int add_named(var_list *l, td_fmu_type type, td_fmu_quantity q, const char *name, const char *unit,
                     const char *description)
{
    td_fmu_var *v = add(l, type, TD_FMU_OUTPUT, q, 0, 0);
    if (!v)
        return 0;
    snprintf(v->name, sizeof v->name, "%s", name);
    v->unit = unit;
    v->description = description;
    return 1;
}

static int add_outputs(var_list *l, const td_model *m)
{
    int a, k, ok = 1;
    for (a = 0; ok && a < td_model_amb_count(m); a++)
        for (k = 0; ok && k < 2; k++)
            ok = add_part(l, TD_FMU_REAL, TD_FMU_OUTPUT, TD_FMU_Q_SENSED, a, k, "ambs", "sensed", "m",
                          "displacement at the sensor") &&
                 add_part(l, TD_FMU_REAL, TD_FMU_OUTPUT, TD_FMU_Q_AMB_FORCE, a, k, "ambs", "force", "N",
                          "total force of the AMB on the rotor");
    for (a = 0; ok && a < td_model_retainer_count(m); a++)
        ok = add_part(l, TD_FMU_REAL, TD_FMU_OUTPUT, TD_FMU_Q_CONTACT_FORCE, a, -1, "retainers", "contact_force", "N",
                      "normal contact force") &&
             add_part(l, TD_FMU_BOOLEAN, TD_FMU_OUTPUT, TD_FMU_Q_IN_CONTACT, a, -1, "retainers", "in_contact", "",
                      "the rotor touches the retainer") &&
             add_part(l, TD_FMU_INTEGER, TD_FMU_OUTPUT, TD_FMU_Q_IMPACTS, a, -1, "retainers", "impacts", "",
                      "contact onsets so far");
    return ok && add_named(l, TD_FMU_REAL, TD_FMU_Q_ROTOR_SPEED, "rotor_speed", "rad/s", "rotor speed now") &&
           add_named(l, TD_FMU_INTEGER, TD_FMU_Q_EVENTS, "events", "", "events of any kind so far") &&
           add_named(l, TD_FMU_BOOLEAN, TD_FMU_Q_HAD_CONTACT, "contact_occurred", "",
                     "a contact so far: first_contact_time and peak_contact_force hold values") &&
           add_named(l, TD_FMU_REAL, TD_FMU_Q_FIRST_CONTACT, "first_contact_time", "s",
                     "time of the first contact (NaN before one)") &&
           add_named(l, TD_FMU_REAL, TD_FMU_Q_PEAK_FORCE, "peak_contact_force", "N", "largest normal force so far");
}

td_status td_fmu_variables(const td_model *model, td_fmu_inputs inputs, td_fmu_var **out, int *n, td_error *err)
{
    var_list l = {NULL, 0, 0};
    *out = NULL;
    *n = 0;
    if (!add_parameters(&l, model) || !add_inputs(&l, model, inputs) || !add_outputs(&l, model)) {
        free(l.v);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory listing the FMU's variables");
    }
    *out = l.v;
    *n = l.n;
    return TD_OK;
}

const char *td_fmu_inputs_name(td_fmu_inputs inputs)
{
    switch (inputs) {
    case TD_FMU_INPUTS_NONE: return "none";
    case TD_FMU_INPUTS_CURRENT: return "current";
    case TD_FMU_INPUTS_FORCE: return "force";
    }
    return NULL;
}

td_status td_fmu_check_start(const td_case *c, td_fmu_inputs inputs, td_error *err)
{
    if (inputs == TD_FMU_INPUTS_NONE || td_case_sim_options(c)->start != TD_START_ORBIT)
        return TD_OK;
    /* the orbit is that of the case's own controllers, which the inputs replace from the start */
    return td_error_set(err, TD_ERR_PARSE,
                        "%s: start = \"orbit\" (also the default of a case that sets no start) is the steady orbit "
                        "under the case's own controllers, which the FMU's %s inputs replace: an FMU with inputs "
                        "starts at rest (set start = \"rest\" or \"auto\")",
                        td_case_path(c), td_fmu_inputs_name(inputs));
}
