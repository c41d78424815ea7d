/*
 * Model errors located in the case file. The model's checks (td_model_add_*, td_model_validate)
 * name the part, index and field at fault (touchdown/error.h); the reader, which built the model
 * entry by entry, turns them into the setting each value was read from, so a model rule is
 * stated once, in lib/model, and still reported as "FILE:LINE: KEY: what is wrong".
 */
#include "case/case_internal.h"
#include "util/error_internal.h"

#include <stdio.h>
#include <string.h>

/* The keys that make a schedule entry's kind; the model calls the one given "kind" and "index". */
static const char *const change_kinds[] = {"unbalance", "amb_off", "amb_on", NULL};

/* The member of entry g that field `field` of a model part was read from; g when the entry does
 * not set it (a default, or a value derived from other keys). */
static const config_setting_t *field_setting(const config_setting_t *g, const td_error_site *site)
{
    const config_setting_t *s = NULL;
    int k;
    if (!g || !site->field)
        return g;
    if (strcmp(site->part, "change") == 0 && (strcmp(site->field, "index") == 0 || strcmp(site->field, "kind") == 0))
        for (k = 0; !s && change_kinds[k]; k++)
            s = config_setting_get_member(g, change_kinds[k]);
    else if (strcmp(site->part, "amb") == 0 && strcmp(site->field, "tau") == 0 && !td_cr_has(g, "tau"))
        s = config_setting_get_member(g, "bandwidth"); /* tau = 1 / (2 pi bandwidth) */
    else if (strcmp(site->part, "controller") == 0 &&
             (strcmp(site->field, "inputs") == 0 || strcmp(site->field, "outputs") == 0))
        s = config_setting_get_member(g, "ambs"); /* its axes: the AMBs' */
    else if (strcmp(site->part, "disc") == 0 && strcmp(site->field, "outer_radius") == 0)
        s = config_setting_get_member(g, "radius"); /* td_disc_geometry */
    else if (strcmp(site->part, "disc") == 0 && strcmp(site->field, "inner_radius") == 0)
        s = config_setting_get_member(g, "bore_radius");
    else
        s = config_setting_lookup((config_setting_t *)g, site->field); /* "material.E" is a path */
    if (!s && strcmp(site->part, "controller") == 0 && (s = config_setting_get_member(g, "plugin")) != NULL)
        /* a plug-in's fault: the member of its group the field names, else the library it is about */
        s = config_setting_get_member(s, site->field) ? config_setting_get_member(s, site->field)
                                                      : config_setting_get_member(s, "library");
    return s ? s : g;
}

/* Entry i of the list `key` of root, or NULL. */
static const config_setting_t *entry(const config_setting_t *root, const char *key, int i)
{
    const config_setting_t *list = config_setting_get_member(root, key);
    return list && i >= 0 && i < config_setting_length(list) ? config_setting_get_elem(list, (unsigned)i) : NULL;
}

/* The case entry a model part was read from: discs then point masses are the model's discs, each
 * other list is one kind of part in order, index -1 the list itself; the shaft; NULL for the
 * shaft's elements (sections) and unknowns. */
static const config_setting_t *part_entry(const config_setting_t *root, const td_model *model,
                                          const td_error_site *site)
{
    static const char *const parts[][2] = {{"amb", "ambs"},
                                           {"bearing", "bearings"},
                                           {"retainer", "retainers"},
                                           {"unbalance", "unbalances"},
                                           {"speed_ramp", "speed_ramp"},
                                           {"controller", "controllers"}};
    const config_setting_t *discs = config_setting_get_member(root, "discs");
    size_t k;
    if (strcmp(site->part, "disc") == 0) {
        int nd = discs ? config_setting_length(discs) : 0;
        return site->index < nd ? entry(root, "discs", site->index) : entry(root, "point_masses", site->index - nd);
    }
    if (strcmp(site->part, "change") == 0) /* numbered in time order; the entry is its order of addition */
        return entry(root, "schedule", td_model_change_entry(model, site->index));
    if (strcmp(site->part, "spin") == 0 || strcmp(site->part, "recovery") == 0 || strcmp(site->part, "shaft") == 0)
        return config_setting_get_member(root, site->part);
    if (strcmp(site->part, "housing.body") == 0) /* housing body: a group inside `housing`, its mounts' list */
        return config_setting_lookup((config_setting_t *)root, site->part);
    if (strcmp(site->part, "housing.body.mounts") == 0) {
        const config_setting_t *list = config_setting_lookup((config_setting_t *)root, site->part);
        return list && site->index >= 0 && site->index < config_setting_length(list)
                   ? config_setting_get_elem(list, (unsigned)site->index)
                   : list;
    }
    for (k = 0; k < sizeof parts / sizeof parts[0]; k++)
        if (strcmp(site->part, parts[k][0]) == 0)
            return site->index < 0 ? config_setting_get_member(root, parts[k][1])
                                   : entry(root, parts[k][1], site->index);
    return NULL;
}

/* Fail at g's setting for merr's site, with "; see KEY at WHERE" for the part a cross check
 * compared against when the case has it. */
static td_status fail_with_other(td_case_reader *r, const config_setting_t *root, const config_setting_t *g,
                                 const td_error *merr)
{
    const config_setting_t *other = merr->other.part ? part_entry(root, r->c->model, &merr->other) : NULL;
    char key[512], where[1200];
    if (!other)
        return td_cr_fail(r, field_setting(g, &merr->site), NULL, "%s", merr->message + merr->reason);
    other = strcmp(merr->other.part, "shaft") == 0 && merr->other.field && strcmp(merr->other.field, "nodes") == 0
                ? td_cr_shaft_nodes(r)
                : field_setting(other, &merr->other);
    td_cr_key(other, key, sizeof key);
    if (merr->other.index < 0) /* a list the rule counted: where its entries were written */
        td_cr_where_list(r, other, NULL, where, sizeof where);
    else
        td_cr_where(r, other, where, sizeof where);
    return td_cr_fail(r, field_setting(g, &merr->site), NULL, "%s; see %s at %s", merr->message + merr->reason, key,
                      where);
}

td_status td_cr_model_fail(td_case_reader *r, const config_setting_t *g, td_status st, const td_error *merr)
{
    if (st == TD_ERR_NOMEM)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: %s", r->path_shown, merr->message);
    if (!merr->site.part)
        return td_cr_fail(r, g, NULL, "%s", merr->message);
    return fail_with_other(r, config_root_setting(&r->cfg), g, merr);
}

td_status td_cr_validate_fail(td_case_reader *r, const td_error *merr)
{
    const config_setting_t *root = config_root_setting(&r->cfg), *g;
    if (!merr->site.part || !(g = part_entry(root, r->c->model, &merr->site)))
        return td_cr_fail_file(r->err, TD_ERR_PARSE, r->path_shown, 0, "%s", merr->message);
    return fail_with_other(r, root, g, merr);
}
