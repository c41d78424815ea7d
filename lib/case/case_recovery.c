/*
 * The `recovery` table: the contact-aware recovery supervisor (td_model_set_recovery), its laws
 * named by the `controllers` table's names, read after it. The reader turns names into controller
 * indices and checks what is about the file (a name that no controller has, two name lists of
 * different lengths); the model keeps the rules (sampled pairs at one rate over the same axes,
 * hysteresis), located back at these keys by case_site.c.
 */
#include "case/case_message.h"
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <stdio.h>
#include <string.h>

typedef struct cr_rec {
    td_recovery r;
    int controller_count; /* names in `controller`, to match `nominal`'s (r.pair_count) */
} cr_rec;

/* Controller i's name, a linear law's or a plug-in's ("" when none). */
static const char *controller_name(const td_model *m, int i)
{
    const td_plugin_spec *p = td_model_get_plugin(m, i);
    const char *n = "";
    if (p)
        return p->name ? p->name : "";
    (void)td_model_get_controller(m, i, &n, NULL, NULL);
    return n;
}

/* The index of the controller named `name`, or -1. */
static int controller_index(const td_model *m, const char *name)
{
    int i;
    for (i = 0; i < td_model_controller_count(m); i++)
        if (strcmp(controller_name(m, i), name) == 0)
            return i;
    return -1;
}

/* One name s (a string setting) as a controller index into *out. */
static td_status name_index(td_case_reader *r, const config_setting_t *s, int *out)
{
    const td_model *m = r->c->model;
    const config_setting_t *list = config_setting_get_member(config_root_setting(&r->cfg), "controllers");
    char names[256] = "", shown[64], where[1200];
    size_t len = 0;
    int i;
    if (config_setting_type(s) != CONFIG_TYPE_STRING)
        return td_cr_fail(r, s, NULL, "expected a controller's name \"...\" (or a list of names)");
    *out = controller_index(m, config_setting_get_string(s));
    if (*out >= 0)
        return TD_OK;
    for (i = 0; i < td_model_controller_count(m) && len + 70 < sizeof names; i++) {
        snprintf(names + len, sizeof names - len, "%s\"%.60s\"", i ? ", " : "", controller_name(m, i));
        len = strlen(names);
    }
    if (!list)
        return td_cr_fail(r, s, NULL, "no controller is named \"%s\" (the case has no controllers table)",
                          td_cr_printable(config_setting_get_string(s), shown, sizeof shown));
    td_cr_where_list(r, list, "name", where, sizeof where); /* a --set may have renamed one */
    return td_cr_fail(r, s, NULL,
                      "no controller is named \"%s\" (the controllers table names %s; see controllers at %s)",
                      td_cr_printable(config_setting_get_string(s), shown, sizeof shown), len ? names : "none", where);
}

/* nominal or controller: a name, or a list (or array) of names, one per pair. */
static td_status read_names(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    cr_rec *c = rec;
    const config_setting_t *s = config_setting_get_member(g, k->key);
    int nominal = strcmp(k->key, "nominal") == 0, *out = nominal ? c->r.nominal : c->r.controller, n = 1, i;
    td_status st = TD_OK;
    if (!s)
        return td_cr_missing(r, g, k->key, k->what);
    if (config_setting_is_aggregate(s)) {
        n = config_setting_length(s);
        if (n < 1 || n > TD_RECOVERY_MAX_PAIRS)
            return td_cr_fail(r, s, NULL, "a list of 1 to %d controller names (got %d)", TD_RECOVERY_MAX_PAIRS, n);
        for (i = 0; st == TD_OK && i < n; i++)
            st = name_index(r, config_setting_get_elem(s, (unsigned)i), &out[i]);
    } else {
        st = name_index(r, s, &out[0]);
    }
    if (nominal)
        c->r.pair_count = n;
    else
        c->controller_count = n;
    if (st == TD_OK && !nominal && n != c->r.pair_count)
        return td_cr_fail(r, s, NULL, "gives %d name%s and `nominal` %d: controller[i] replaces nominal[i]", n,
                          n == 1 ? "" : "s", c->r.pair_count);
    return st;
}

static td_status set_recovery(td_case_reader *r, const config_setting_t *g, void *rec)
{
    td_error merr;
    td_status st = td_model_set_recovery(r->c->model, &((cr_rec *)rec)->r, &merr);
    return st == TD_OK ? TD_OK : td_cr_model_fail(r, g, st, &merr);
}

static void preset(void *rec)
{
    ((cr_rec *)rec)->r.enabled = 1;
}

static const td_cs_key rule_keys[] = {
    {.key = "radius_fraction",
     .type = TD_CS_REAL,
     .offset = offsetof(td_recovery_rule, radius_fraction),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .what = "the threshold, a fraction of the smallest retainer clearance",
     .doc = "f: the threshold on the sensed radius is f c, c the smallest retainer clearance; detect: the radius "
            "above it, release: below it (release's f below detect's, hysteresis)"},
    {.key = "dwell",
     .type = TD_CS_REAL,
     .offset = offsetof(td_recovery_rule, dwell),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_NONNEGATIVE,
     .what = "how long the condition must hold, s",
     .unit = "s",
     .doc = "how long the condition must hold at every sample before the switch: ceil(dwell rate) samples after the "
            "first that meets it (0: at that sample)"},
};
static const td_cs_table detect_table = {"recovery.detect", NULL, rule_keys, TD_CS_COUNT(rule_keys), 0, NULL, NULL};
static const td_cs_table release_table = {"recovery.release", NULL, rule_keys, TD_CS_COUNT(rule_keys), 0, NULL, NULL};

static const td_cs_key recovery_keys[] = {
    {.key = "enabled",
     .type = TD_CS_BOOL,
     .offset = offsetof(cr_rec, r.enabled),
     .need = TD_CS_PRESET,
     .doc_default = "true",
     .doc = "`false`: the nominal laws throughout, no switch (the run to compare against)"},
    {.key = "nominal",
     .type = TD_CS_CUSTOM,
     .read = read_names,
     .what = "the name of the nominal controller (or a list of names)",
     .doc_type = "string or list of strings",
     .doc_default = "required",
     .doc = "the controllers (names in `controllers`) that run normally, each sampled"},
    {.key = "controller",
     .type = TD_CS_CUSTOM,
     .read = read_names,
     .order = 1,
     .what = "the name of the recovery controller (or a list of names, one per nominal)",
     .doc_type = "string or list of strings",
     .doc_default = "required",
     .doc = "the recovery controllers, controller[i] replacing nominal[i]: sampled at the same rate, over the same "
            "`ambs` in the same `coordinates`; it stands by (drives nothing, its state at rest) until a switch"},
    {.key = "detect",
     .type = TD_CS_GROUP,
     .sub = &detect_table,
     .offset = offsetof(cr_rec, r.detect),
     .need = TD_CS_REQUIRED,
     .what = "the rule that switches to the recovery controller",
     .doc = "switch to the recovery law when the sensed radius stays above radius_fraction c for dwell s"},
    {.key = "release",
     .type = TD_CS_GROUP,
     .sub = &release_table,
     .offset = offsetof(cr_rec, r.release),
     .need = TD_CS_REQUIRED,
     .what = "the rule that switches back to the nominal controller",
     .doc = "switch back to the nominal law when the sensed radius stays below radius_fraction c for dwell s"},
    {.key = "blend",
     .type = TD_CS_REAL,
     .offset = offsetof(cr_rec, r.blend),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_NONNEGATIVE,
     .what = "the blend time of a switch, s",
     .unit = "s",
     .doc = "the held current moves linearly from the old law's to the new law's over this time after a switch, "
            "both laws running meanwhile (0: a step at the switch sample)"},
};
const td_cs_table td_cs_recovery = {"recovery",     "recovery", recovery_keys, TD_CS_COUNT(recovery_keys),
                                    sizeof(cr_rec), preset,     set_recovery};
