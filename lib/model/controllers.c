/*
 * The model's controllers: linear laws (td_model_add_controller) and plug-ins
 * (td_model_add_plugin_controller; the spec's copy and library are plugin.c's): owned copies of
 * each law and of its axis lists, their checks, and their part in copying and freeing a model. An
 * AMB axis is numbered 2 amb + axis (0: x, 1: y), as the system numbers them.
 */
#include "model/model_internal.h"
#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

/* Fail naming the part, its index and the field at fault ("PART INDEX: FIELD: ..."). */
#define FAIL_AT(err, part, index, field, ...)                                                                          \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){(part), (index), (field)}, &no_site, __VA_ARGS__)

/* Append c to m's controllers (growing geometrically, as the other parts grow). */
static td_status append_controller(td_model *m, const td_model_controller *c, td_error *err)
{
    if (m->controllers.count == m->controllers.capacity) {
        int cap = m->controllers.capacity ? 2 * m->controllers.capacity : 4;
        td_model_controller *p = realloc(m->controllers.items, (size_t)cap * sizeof *p);
        if (!p)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a controller");
        m->controllers.items = p;
        m->controllers.capacity = cap;
    }
    m->controllers.items[m->controllers.count++] = *c;
    return TD_OK;
}

/* Fill *dst with copies of k, its name and its axis lists (dst is zeroed; on failure it holds what
 * it could copy, for td_model_free_controllers). */
static td_status copy_controller(td_model_controller *dst, const td_controller *k, const char *name, const int *inputs,
                                 const int *outputs, td_error *err)
{
    size_t nin = (size_t)td_controller_inputs(k), nout = (size_t)td_controller_outputs(k);
    td_status st = TD_OK;
    dst->nin = (int)nin;
    dst->nout = (int)nout;
    dst->sample_rate = td_controller_sample_rate(k);
    if (name)
        memcpy(dst->name, name, strlen(name) + 1); /* the caller checked it fits */
    dst->inputs = malloc(nin * sizeof *inputs);
    dst->outputs = malloc(nout * sizeof *outputs);
    if (!dst->inputs || !dst->outputs)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a controller");
    memcpy(dst->inputs, inputs, nin * sizeof *inputs);
    memcpy(dst->outputs, outputs, nout * sizeof *outputs);
    dst->k = td_controller_clone(k, err);
    if (!dst->k)
        st = err && err->code != TD_OK ? err->code : TD_ERR_NOMEM;
    return st;
}

void td_model_free_controllers(td_model *m)
{
    int i;
    for (i = 0; i < m->controllers.count; i++) {
        td_controller_free(&m->controllers.items[i].k);
        td_model_plugin_free(&m->controllers.items[i].plugin);
        free(m->controllers.items[i].inputs);
        free(m->controllers.items[i].outputs);
    }
    free(m->controllers.items);
}

/* Deep copies of src's controllers into m (whose controller array is empty). */
td_status td_model_clone_controllers(td_model *m, const td_model *src, td_error *err)
{
    int i, n = src->controllers.count;
    if (n == 0)
        return TD_OK;
    m->controllers.items = calloc((size_t)n, sizeof *m->controllers.items);
    if (!m->controllers.items)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory cloning a model");
    m->controllers.capacity = n;
    for (i = 0; i < n; i++) {
        const td_model_controller *c = &src->controllers.items[i];
        td_status st;
        m->controllers.count++; /* so that td_model_free releases what this copy holds */
        st = c->plugin ? td_model_plugin_clone(&m->controllers.items[i], c, i, err)
                       : copy_controller(&m->controllers.items[i], c->k, c->name, c->inputs, c->outputs, err);
        if (st != TD_OK)
            return st;
    }
    return TD_OK;
}

/* The axis lists of controller i (added or being added): every axis >= 0 (the upper bound waits
 * for td_model_validate), and no axis commanded by two of its outputs. */
static td_status check_axis_lists(int i, const int *inputs, int nin, const int *outputs, int nout, td_error *err)
{
    int j, l;
    for (j = 0; j < nin; j++)
        if (inputs[j] < 0)
            return FAIL_AT(err, "controller", i, "inputs",
                           "axis %d of input %d must be >= 0 (axis 2 amb + 0 for x, 1 for y)", inputs[j], j);
    for (j = 0; j < nout; j++) {
        if (outputs[j] < 0)
            return FAIL_AT(err, "controller", i, "outputs",
                           "axis %d of output %d must be >= 0 (axis 2 amb + 0 for x, 1 for y)", outputs[j], j);
        for (l = 0; l < j; l++)
            if (outputs[l] == outputs[j])
                return FAIL_AT(err, "controller", i, "outputs", "outputs %d and %d both command axis %d", l, j,
                               outputs[j]);
    }
    return TD_OK;
}

/* What a linear and a plug-in controller share, for controller m->controllers.count being added: its
 * name (fits, not taken), at least one input and output, the rate (0, or sampled within the
 * bounds), and its axis lists. */
static td_status check_new_controller(const td_model *m, const char *name, int nin, int nout, double rate,
                                      const int *inputs, const int *outputs, td_error *err)
{
    int i = m->controllers.count, j;
    if (name && strlen(name) >= sizeof m->controllers.items[0].name)
        return FAIL_AT(err, "controller", i, "name", "is longer than %d characters",
                       (int)sizeof m->controllers.items[0].name - 1);
    for (j = 0; name && name[0] && j < i; j++)
        if (strcmp(m->controllers.items[j].name, name) == 0)
            return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"controller", i, "name"},
                                     &(td_error_site){"controller", j, "name"}, "\"%s\" already names controller %d",
                                     name, j);
    if (nin < 1 || nout < 1)
        return FAIL_AT(err, "controller", i, NULL, "has %d inputs and %d outputs: it needs at least one of each", nin,
                       nout);
    if (rate != 0.0 && !(rate >= TD_CONTROLLER_RATE_MIN && rate <= TD_CONTROLLER_RATE_MAX))
        return FAIL_AT(err, "controller", i, "sample_rate", "must be %g to %g Hz (got %g)", TD_CONTROLLER_RATE_MIN,
                       TD_CONTROLLER_RATE_MAX, rate);
    if (!inputs || !outputs)
        return FAIL_AT(err, "controller", i, inputs ? "outputs" : "inputs", "NULL axis list");
    return check_axis_lists(i, inputs, nin, outputs, nout, err);
}

td_status td_model_add_controller(td_model *m, const char *name, const td_controller *k, const int *inputs,
                                  const int *outputs, td_error *err)
{
    td_model_controller c;
    td_status st;
    double rate;
    if (!m || !k)
        return td_error_set(err, TD_ERR_INVALID, "controller: NULL argument");
    /* a negative or NaN rate is out of bounds too (the law's own check refuses them first) */
    rate = td_controller_sample_rate(k) > 0.0 ? td_controller_sample_rate(k) : 0.0;
    st = check_new_controller(m, name, td_controller_inputs(k), td_controller_outputs(k), rate, inputs, outputs, err);
    if (st != TD_OK)
        return st;
    memset(&c, 0, sizeof c);
    st = copy_controller(&c, k, name, inputs, outputs, err);
    if (st == TD_OK)
        st = append_controller(m, &c, err);
    if (st != TD_OK) {
        td_controller_free(&c.k);
        free(c.inputs);
        free(c.outputs);
    }
    return st;
}

td_status td_model_add_plugin_controller(td_model *m, const td_plugin_spec *spec, td_error *err)
{
    td_model_controller c;
    td_status st;
    int i;
    if (!m || !spec)
        return td_error_set(err, TD_ERR_INVALID, "controller: NULL argument");
    i = m->controllers.count;
    if (!spec->functions && !spec->library)
        return FAIL_AT(err, "controller", i, "library", "a plug-in controller needs a table (functions) or a library");
    st = check_new_controller(m, spec->name, spec->n_inputs, spec->n_outputs, spec->sample_rate, spec->inputs,
                              spec->outputs, err);
    if (st == TD_OK)
        st = td_model_plugin_check(spec, i, err);
    if (st != TD_OK)
        return st;
    memset(&c, 0, sizeof c);
    if (spec->name)
        memcpy(c.name, spec->name, strlen(spec->name) + 1); /* checked: it fits */
    st = td_model_plugin_copy(&c, spec, i, err);
    if (st == TD_OK)
        st = append_controller(m, &c, err);
    if (st != TD_OK) {
        td_model_plugin_free(&c.plugin);
        free(c.inputs);
        free(c.outputs);
    }
    return st;
}

/* Controller i's axis list `field` (n axes) names AMB axes that exist. */
static td_status check_axes_exist(const td_model *m, int i, const char *field, const int *axes, int n, td_error *err)
{
    int j, count = 2 * m->ambs.count;
    for (j = 0; j < n; j++)
        if (axes[j] >= count)
            return FAIL_AT(err, "controller", i, field, "axis %d is out of range (%d AMBs have axes 0..%d)", axes[j],
                           m->ambs.count, count - 1);
    return TD_OK;
}

/* The AMB of an axis controller i drives gives the law to it: its shorthand gains must be 0 (and its
 * ki nonzero for a plug-in that commands forces). */
static td_status check_driven_amb(const td_model *m, int i, int amb, td_error *err)
{
    const td_amb *a = &m->ambs.items[amb];
    const char *key = a->kp != 0.0 ? "kp" : a->kd != 0.0 ? "kd" : a->kint != 0.0 ? "kint" : NULL;
    double v = a->kp != 0.0 ? a->kp : a->kd != 0.0 ? a->kd : a->kint;
    if (m->controllers.items[i].plugin && m->controllers.items[i].plugin->spec.functions->output == TD_PLUGIN_FORCE &&
        a->ki == 0.0) /* the current that makes a force is f / ki */
        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"amb", amb, "ki"},
                                 &(td_error_site){"controller", i, "outputs"},
                                 "must be nonzero: plug-in controller %d (\"%s\") commands this AMB's force", i,
                                 m->controllers.items[i].name);
    if (!key)
        return TD_OK;
    return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"amb", amb, key},
                             &(td_error_site){"controller", i, "outputs"},
                             "must be 0 (got %g): controller %d (\"%s\") drives this AMB and replaces its %s", v, i,
                             m->controllers.items[i].name, key);
}

/* Every controller's axes exist, each axis is driven by one controller at most (but for the two
 * laws of a recovery pair, which the supervisor switches between), and a driven AMB leaves the law
 * to its controller. */
td_status td_model_check_controllers(const td_model *m, td_error *err)
{
    int i, j, l, o;
    for (i = 0; i < m->controllers.count; i++) {
        const td_model_controller *c = &m->controllers.items[i];
        int nout = c->nout;
        if (check_axes_exist(m, i, "inputs", c->inputs, c->nin, err) ||
            check_axes_exist(m, i, "outputs", c->outputs, nout, err))
            return TD_ERR_INVALID;
        for (o = 0; o < nout; o++) {
            for (j = 0; j < i; j++)
                for (l = 0; l < m->controllers.items[j].nout; l++)
                    if (m->controllers.items[j].outputs[l] == c->outputs[o] && !td_model_recovery_paired(m, i, j))
                        return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"controller", i, "outputs"},
                                                 &(td_error_site){"controller", j, "outputs"},
                                                 "axis %d is already driven by controller %d (\"%s\")", c->outputs[o],
                                                 j, m->controllers.items[j].name);
            if (check_driven_amb(m, i, c->outputs[o] / 2, err))
                return TD_ERR_INVALID;
        }
    }
    return TD_OK;
}

int td_model_controller_count(const td_model *m)
{
    return m ? m->controllers.count : 0;
}

const td_controller *td_model_get_controller(const td_model *m, int i, const char **name, const int **inputs,
                                             const int **outputs)
{
    const td_model_controller *c;
    if (!m || i < 0 || i >= m->controllers.count)
        return NULL;
    c = &m->controllers.items[i];
    if (name)
        *name = c->name;
    if (inputs)
        *inputs = c->inputs;
    if (outputs)
        *outputs = c->outputs;
    return c->k;
}
