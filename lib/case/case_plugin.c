/*
 * A controller's `plugin` group: the user's own controller code (touchdown/plugin.h) in a shared
 * library, named by its path relative to the case file's directory, with the numbers the plug-in's
 * init reads (`parameters`). It is handed to the model as a plug-in controller
 * (td_model_add_plugin_controller), which opens the library and holds the rules about it (a file
 * that cannot be opened, a missing entry symbol, another ABI version): the reader checks what is
 * about the file and locates the model's errors at the key `library`.
 */
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* `parameters`: a group of numbers, each finite (a plug-in's gains; the plug-in judges their values). */
static td_status read_parameters(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_cr_plugin *p = rec;
    const config_setting_t *s;
    double v;
    int i, n;
    td_status st = td_cr_group(r, g, k->key, NULL, &p->parameters);
    if (st != TD_OK || !p->parameters)
        return st;
    n = config_setting_length(p->parameters);
    if (n > TD_CR_PLUGIN_MAX_PARAMETERS)
        return td_cr_fail(r, p->parameters, NULL, "at most %d parameters (got %d)", TD_CR_PLUGIN_MAX_PARAMETERS, n);
    for (i = 0; st == TD_OK && i < n; i++) {
        s = config_setting_get_elem(p->parameters, (unsigned)i);
        st = td_cr_value_real(r, s, TD_CR_FINITE, &v);
    }
    return st;
}

/* `library`: a file name, not empty. */
static td_status check_library(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    const td_cr_plugin *p = rec;
    if (p->library && !p->library[0])
        return td_cr_fail(r, config_setting_get_member(g, k->key), NULL,
                          "names no file: give the plug-in's shared library, e.g. \"pd.so\"");
    return TD_OK;
}

static const td_cs_key plugin_keys[] = {
    {.key = "library",
     .type = TD_CS_STRING,
     .offset = offsetof(td_cr_plugin, library),
     .need = TD_CS_REQUIRED,
     .check = check_library,
     .what = "the plug-in's shared library",
     .doc = "the shared library exporting td_plugin_controller_entry (docs/api.md, \"A plug-in controller\"), its "
            "path relative to the case file's directory (an @include'd file's too) unless absolute"},
    {.key = "parameters",
     .type = TD_CS_CUSTOM,
     .read = read_parameters,
     .doc_type = "group of numbers",
     .doc_default = "none",
     .doc = "the numbers the plug-in's init reads, by name as written, e.g. { kp = 1.0e4; kd = 40.0; } (at most "
            "64); which it needs is the plug-in's to say"},
};
const td_cs_table td_cs_plugin = {"controllers[].plugin", NULL, plugin_keys, TD_CS_COUNT(plugin_keys),
                                  sizeof(td_cr_plugin),   NULL, NULL};

/* The library's path: as written when absolute, else under the case file's directory. */
static char *library_path(const td_case_reader *r, const char *library)
{
    size_t n = strlen(r->dir) + strlen(library) + 2;
    char *path = malloc(n);
    if (path && library[0] == '/')
        snprintf(path, n, "%s", library);
    else if (path)
        snprintf(path, n, "%s/%s", r->dir, library);
    return path;
}

/* A model error about the plug-in of controller entry g: at the key its field names (the AMBs for
 * its axes, a member of `plugin`: case_site.c), else at `library` (the library's own faults). */
static td_status plugin_fail(td_case_reader *r, const config_setting_t *g, td_status st, const td_error *merr)
{
    const config_setting_t *pg = config_setting_get_member(g, "plugin");
    if (st == TD_ERR_NOMEM || (merr->site.part && merr->site.field))
        return td_cr_model_fail(r, g, st, merr);
    return td_cr_fail(r, config_setting_get_member(pg, "library"), NULL, "%s", merr->message + merr->reason);
}

td_status td_cr_add_plugin(td_case_reader *r, const config_setting_t *g, const td_cr_plugin *p,
                           const td_plugin_spec *axes)
{
    const char *names[TD_CR_PLUGIN_MAX_PARAMETERS];
    double values[TD_CR_PLUGIN_MAX_PARAMETERS];
    td_plugin_spec spec = *axes;
    td_error merr;
    td_status st;
    int i, n = p->parameters ? config_setting_length(p->parameters) : 0;
    for (i = 0; i < n; i++) {
        const config_setting_t *s = config_setting_get_elem(p->parameters, (unsigned)i);
        names[i] = config_setting_name(s);
        values[i] = config_setting_type(s) == CONFIG_TYPE_FLOAT ? config_setting_get_float(s)
                                                                : (double)config_setting_get_int64(s);
    }
    spec.functions = NULL;
    spec.n_parameters = n;
    spec.parameter_names = names;
    spec.parameter_values = values;
    if (!(spec.library = library_path(r, p->library)))
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    td_error_clear(&merr);
    st = td_model_add_plugin_controller(r->c->model, &spec, &merr);
    free((char *)spec.library);
    return st == TD_OK ? TD_OK : plugin_fail(r, g, st, &merr);
}
