/*
 * The model's plug-in controllers (td_model_add_plugin_controller, touchdown/plugin.h): the spec's
 * owned copy, the shared library opened with dlopen and its table found with dlsym and checked
 * against this ABI, and their part in copying (the library opened again) and freeing a model. The
 * simulation runs the instances (lib/sim/sampler_plugin.c); the model calls none of a plug-in's
 * functions but its library's entry. td_model_add_plugin_controller is controllers.c's.
 */
#include "model/model_internal.h"
#include "util/error_internal.h"

#include <dlfcn.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

/* Fail naming controller i and the spec's field at fault ("controller I: FIELD: ..."). */
#define FAIL_AT(err, i, field, ...)                                                                                    \
    td_error_set_site((err), TD_ERR_INVALID, &(td_error_site){"controller", (i), (field)}, &no_site, __VA_ARGS__)

/* A copy of s (NULL for NULL; *ok cleared when the allocation fails). */
static char *copy_string(const char *s, int *ok)
{
    char *c;
    if (!s)
        return NULL;
    c = malloc(strlen(s) + 1);
    if (!c)
        *ok = 0;
    else
        memcpy(c, s, strlen(s) + 1);
    return c;
}

/* The table `f` of controller i (from `where`, "functions" or "library") is one this simulation can
 * run: this ABI version, a known output kind, every function set. */
static td_status check_table(const td_plugin_controller *f, int i, const char *where, const char *library,
                             td_error *err)
{
    const char *what = library ? library : "the table";
    if (!f)
        return FAIL_AT(err, i, where, "\"%s\": %s returned NULL (no controller table)", what, TD_PLUGIN_ENTRY_NAME);
    if (f->abi_version != TD_PLUGIN_ABI_VERSION)
        return FAIL_AT(err, i, where,
                       "\"%s\" is built for plug-in ABI version %d; this touchdown runs version %d (rebuild it "
                       "against this touchdown/plugin.h)",
                       what, f->abi_version, TD_PLUGIN_ABI_VERSION);
    if (f->output != TD_PLUGIN_CURRENT && f->output != TD_PLUGIN_FORCE)
        return FAIL_AT(err, i, where, "\"%s\": output %d is neither TD_PLUGIN_CURRENT (0) nor TD_PLUGIN_FORCE (1)",
                       what, (int)f->output);
    if (!f->init || !f->step || !f->reset || !f->free)
        return FAIL_AT(err, i, where, "\"%s\" has no %s function (init, step, reset and free are all needed)", what,
                       !f->init    ? "init"
                       : !f->step  ? "step"
                       : !f->reset ? "reset"
                                   : "free");
    return TD_OK;
}

/* p->spec.library opened (RTLD_NOW: an unresolved symbol fails here, not mid-run) and its table
 * taken from its entry function into p->spec.functions. The library is a file: a name without a
 * slash is the file in the current directory (dlopen would search the system's library path). */
static td_status open_library(td_model_plugin *p, int i, td_error *err)
{
    const char *path = p->spec.library;
    td_plugin_entry entry;
    void *sym;
    char *here = NULL;
    if (!strchr(path, '/')) { /* a path: "pd.so" is the file here, never a search of the library path */
        here = malloc(strlen(path) + 3);
        if (!here)
            return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a controller");
        memcpy(here, "./", 2);
        memcpy(here + 2, path, strlen(path) + 1);
    }
    dlerror(); /* clear an earlier failure's message */
    p->handle = dlopen(here ? here : path, RTLD_NOW | RTLD_LOCAL);
    free(here);
    if (!p->handle) {
        const char *why = dlerror();
        return FAIL_AT(err, i, "library", "cannot load \"%s\": %s", path, why ? why : "dlopen failed");
    }
    sym = dlsym(p->handle, TD_PLUGIN_ENTRY_NAME);
    if (!sym)
        return FAIL_AT(err, i, "library", "\"%s\" does not export %s (the plug-in's entry, touchdown/plugin.h)", path,
                       TD_PLUGIN_ENTRY_NAME);
    /* POSIX: dlsym's object pointer holds the function's address; copied, as ISO C has no cast */
    memcpy(&entry, &sym, sizeof entry);
    p->spec.functions = entry();
    return check_table(p->spec.functions, i, "library", path, err);
}

td_status td_model_plugin_check(const td_plugin_spec *spec, int i, td_error *err)
{
    int j, l;
    if (!(spec->sample_rate >= TD_CONTROLLER_RATE_MIN && spec->sample_rate <= TD_CONTROLLER_RATE_MAX))
        return FAIL_AT(err, i, "sample_rate", "must be %g to %g Hz (got %g): a plug-in controller is sampled",
                       TD_CONTROLLER_RATE_MIN, TD_CONTROLLER_RATE_MAX, spec->sample_rate);
    if (spec->delay < 0)
        return FAIL_AT(err, i, "delay", "must be >= 0 whole samples (got %d)", spec->delay);
    if (spec->n_parameters < 0 || (spec->n_parameters > 0 && (!spec->parameter_names || !spec->parameter_values)))
        return FAIL_AT(err, i, "parameters", "%d parameters need %d names and values", spec->n_parameters,
                       spec->n_parameters);
    for (j = 0; j < spec->n_parameters; j++) {
        const char *name = spec->parameter_names[j];
        if (!name || !name[0])
            return FAIL_AT(err, i, "parameters", "parameter %d has no name", j);
        if (!isfinite(spec->parameter_values[j]))
            return FAIL_AT(err, i, "parameters", "%s = %g is not finite", name, spec->parameter_values[j]);
        for (l = 0; l < j; l++)
            if (strcmp(spec->parameter_names[l], name) == 0)
                return FAIL_AT(err, i, "parameters", "\"%s\" is given twice (parameters %d and %d)", name, l, j);
    }
    return TD_OK;
}

td_status td_model_plugin_copy(td_model_controller *c, const td_plugin_spec *spec, int i, td_error *err)
{
    td_model_plugin *p = calloc(1, sizeof *p);
    size_t np = (size_t)spec->n_parameters, nin = (size_t)spec->n_inputs, nout = (size_t)spec->n_outputs, j;
    char **names;
    int ok = 1;
    c->plugin = p;
    c->nin = spec->n_inputs;
    c->nout = spec->n_outputs;
    c->sample_rate = spec->sample_rate;
    c->inputs = malloc(nin * sizeof *c->inputs);
    c->outputs = malloc(nout * sizeof *c->outputs);
    names = calloc(np + 1, sizeof *names);
    if (!p || !c->inputs || !c->outputs || !names) {
        free(names);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a controller");
    }
    memcpy(c->inputs, spec->inputs, nin * sizeof *c->inputs);
    memcpy(c->outputs, spec->outputs, nout * sizeof *c->outputs);
    p->spec = *spec;
    memcpy(p->name, c->name, sizeof p->name);
    p->spec.name = p->name;
    p->spec.inputs = c->inputs;
    p->spec.outputs = c->outputs;
    p->spec.parameter_names = (const char *const *)names;
    p->spec.library = copy_string(spec->library, &ok);
    p->spec.parameter_values = malloc((np + 1) * sizeof(double));
    for (j = 0; j < np; j++)
        names[j] = copy_string(spec->parameter_names[j], &ok);
    if (!ok || !p->spec.parameter_values)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a controller");
    memcpy((double *)p->spec.parameter_values, spec->parameter_values, np * sizeof(double));
    if (!spec->library)
        return check_table(spec->functions, i, "functions", NULL, err);
    if (open_library(p, i, err))
        return TD_ERR_INVALID;
    /* a table given with the library (a spec read back by td_model_get_plugin) must be the library's */
    if (spec->functions && spec->functions != p->spec.functions)
        return FAIL_AT(err, i, "functions", "differs from the table of \"%s\": give one or the other", spec->library);
    return TD_OK;
}

void td_model_plugin_free(td_model_plugin **pp)
{
    td_model_plugin *p = pp ? *pp : NULL;
    int j;
    if (!p)
        return;
    for (j = 0; p->spec.parameter_names && j < p->spec.n_parameters; j++)
        free((char *)p->spec.parameter_names[j]);
    free((char **)p->spec.parameter_names);
    free((double *)p->spec.parameter_values);
    free((char *)p->spec.library);
    if (p->handle)
        dlclose(p->handle);
    free(p);
    *pp = NULL;
}

td_status td_model_plugin_clone(td_model_controller *dst, const td_model_controller *src, int i, td_error *err)
{
    memcpy(dst->name, src->name, sizeof dst->name);
    return td_model_plugin_copy(dst, &src->plugin->spec, i, err);
}

const td_plugin_spec *td_model_get_plugin(const td_model *m, int i)
{
    if (!m || i < 0 || i >= m->controllers.count || !m->controllers.items[i].plugin)
        return NULL;
    return &m->controllers.items[i].plugin->spec;
}

void td_plugin_spec_setup(const td_plugin_spec *spec, td_plugin_setup *setup)
{
    memset(setup, 0, sizeof *setup);
    setup->abi_version = TD_PLUGIN_ABI_VERSION;
    setup->name = spec->name ? spec->name : "";
    setup->sample_rate = spec->sample_rate;
    setup->n_inputs = spec->n_inputs;
    setup->n_outputs = spec->n_outputs;
    setup->input_axes = spec->inputs;
    setup->output_axes = spec->outputs;
    setup->n_parameters = spec->n_parameters;
    setup->parameter_names = spec->parameter_names;
    setup->parameter_values = spec->parameter_values;
}
