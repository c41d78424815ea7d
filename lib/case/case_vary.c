/*
 * The case file's optional `sweep` group, what `touchdown sweep CASE` runs when no --vary
 * replaces it:
 *
 *   sweep = {
 *     vary = ( { key = "speed"; from = 50.0; to = 250.0; points = 41; spacing = "log"; },
 *              { key = "unbalances[0].mass"; values = [ 1e-4, 2e-4 ];
 *                with = ( { key = "unbalances[0].phase"; values = [ 0.0, 1.5 ]; } ); } );
 *   };
 *
 * Each entry becomes the spec --vary (an entry of `with`: --with) would take, kept with the place
 * it was written (td_cr_sweep_spec). The reader checks the group's shape as it checks every group:
 * its keys, the types of the values, a key to sweep, values or a range but not both. What the
 * specs mean (forms, counts, limits) is judged by the sweep's own rules (lib/sweep), so that the
 * command line and the file obey one set of rules.
 */
#include "case/case_internal.h"
#include "util/text.h"

#include <stdlib.h>
#include <string.h>

static const char *const sweep_keys[] = {"vary", NULL};
static const char *const axis_keys[] = {"key", "from", "to", "points", "spacing", "values", "with", NULL};
static const char *const zip_keys[] = {"key", "from", "to", "points", "spacing", "values", NULL};

void td_cr_free_sweep(td_case *c)
{
    while (c->sweep_count > 0) {
        c->sweep_count--;
        free(c->sweep[c->sweep_count].spec);
        free(c->sweep[c->sweep_count].where);
        free(c->sweep[c->sweep_count].at);
        free(c->sweep[c->sweep_count].key);
    }
    free(c->sweep);
    c->sweep = NULL;
}

/* A number setting as the exact text a spec carries. */
static void number_text(const config_setting_t *s, char *buf, size_t n)
{
    if (config_setting_type(s) == CONFIG_TYPE_FLOAT)
        td_text_shortest_number(buf, n, config_setting_get_float(s));
    else
        snprintf(buf, n, "%lld", config_setting_get_int64(s));
}

/* One value of `values` as --set takes it: a number, true/false, or a quoted string. */
static td_status value_text(td_case_reader *r, const config_setting_t *s, td_text *t)
{
    char num[64];
    const char *p;
    int type = config_setting_type(s);
    if (type == CONFIG_TYPE_INT || type == CONFIG_TYPE_INT64 || type == CONFIG_TYPE_FLOAT) {
        number_text(s, num, sizeof num);
        td_text_printf(t, "%s", num);
    } else if (type == CONFIG_TYPE_BOOL)
        td_text_printf(t, "%s", config_setting_get_bool(s) ? "true" : "false");
    else if (type == CONFIG_TYPE_STRING) {
        td_text_append(t, "\"", 1);
        for (p = config_setting_get_string(s); *p; p++) {
            if (*p == '"' || *p == '\\') /* escaped as libconfig reads a --set string */
                td_text_append(t, "\\", 1);
            td_text_append(t, p, 1);
        }
        td_text_append(t, "\"", 1);
    } else
        return td_cr_fail(r, s, NULL, "expected a number, true/false or a \"string\"");
    return TD_OK;
}

/* KEY=V1,V2,... from `values`. */
static td_status list_spec(td_case_reader *r, const config_setting_t *e, td_text *t)
{
    const config_setting_t *v = config_setting_get_member(e, "values");
    int i, n;
    td_status st = TD_OK;
    if (td_cr_has(e, "from") || td_cr_has(e, "to") || td_cr_has(e, "points") || td_cr_has(e, "spacing"))
        return td_cr_fail(r, e, NULL, "give either values or a range (from, to, points, spacing), not both");
    if (!config_setting_is_array(v) && !config_setting_is_list(v))
        return td_cr_fail(r, v, NULL, "expected an array [ ... ] of values");
    if ((n = config_setting_length(v)) == 0)
        return td_cr_fail(r, v, NULL, "no values: give at least one");
    for (i = 0; st == TD_OK && i < n; i++) {
        if (i > 0)
            td_text_append(t, ",", 1);
        st = value_text(r, config_setting_get_elem(v, (unsigned)i), t);
    }
    return st;
}

/* A member of a range that must be a number, as exact text. */
static td_status range_number(td_case_reader *r, const config_setting_t *e, const char *key, const char *what,
                              char *buf, size_t n)
{
    const config_setting_t *s = config_setting_get_member(e, key);
    int type = s ? config_setting_type(s) : CONFIG_TYPE_NONE;
    if (!s)
        return td_cr_missing(r, e, key, what);
    if (type != CONFIG_TYPE_INT && type != CONFIG_TYPE_INT64 && type != CONFIG_TYPE_FLOAT)
        return td_cr_fail(r, s, NULL, "expected a number");
    number_text(s, buf, n);
    return TD_OK;
}

/* KEY=FROM:TO:POINTS[:SPACING] from a range entry. */
static td_status range_spec(td_case_reader *r, const config_setting_t *e, td_text *t)
{
    char from[64], to[64], points[64];
    const char *spacing = NULL;
    td_status st = range_number(r, e, "from", "the range's first value (or give values)", from, sizeof from);
    if (st == TD_OK)
        st = range_number(r, e, "to", "the range's last value", to, sizeof to);
    if (st == TD_OK)
        st = range_number(r, e, "points", "the number of points", points, sizeof points);
    if (st == TD_OK && config_setting_type(config_setting_get_member(e, "points")) == CONFIG_TYPE_FLOAT)
        st = td_cr_fail(r, e, "points", "expected a whole number");
    if (st == TD_OK)
        st = td_cr_string(r, e, "spacing", NULL, &spacing);
    if (st == TD_OK)
        td_text_printf(t, "%s:%s:%s%s%s", from, to, points, spacing ? ":" : "", spacing ? spacing : "");
    return st;
}

static char *dup_string(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    return d ? strcpy(d, s) : NULL;
}

/* The spec joins the case's list of specs, with its place: the entry's "FILE:LINE" and setting
 * (as td_cr_fail would name them) and td_case_sweep_spec's "FILE:LINE: KEY". */
static td_status keep_spec(td_case_reader *r, const config_setting_t *e, int with, td_text *t)
{
    char at[TD_CR_SWEEP_CONTEXT_SIZE], key[TD_CR_SWEEP_KEY_SIZE], where[1024];
    td_cr_sweep_spec *list;
    size_t len;
    if (t->failed)
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    td_cr_where(r, e, at, sizeof at);
    td_cr_key(e, key, sizeof key);
    td_cr_where(r, e, where, sizeof where); /* td_case_sweep_spec's place, as it always was */
    len = strlen(where);
    snprintf(where + len, sizeof where - len, ": %.255s", key);
    if (!(list = realloc(r->c->sweep, (size_t)(r->c->sweep_count + 1) * sizeof *list)))
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    r->c->sweep = list;
    list += r->c->sweep_count;
    memset(list, 0, sizeof *list);
    list->with = with;
    list->values = td_cr_has(e, "values");
    list->spec = t->data;
    t->data = NULL;
    r->c->sweep_count++;
    if (!(list->where = dup_string(where)) || !(list->at = dup_string(at)) || !(list->key = dup_string(key)))
        return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
    return TD_OK;
}

/* One swept key: an entry of `vary` (with = 0) or of its `with` (with = 1). */
static td_status read_key(td_case_reader *r, const config_setting_t *e, int with)
{
    td_text t = {NULL, 0, 0, 0, 0};
    const char *key = NULL;
    td_status st = td_cr_check_keys(r, e, with ? zip_keys : axis_keys);
    if (st == TD_OK)
        st = td_cr_string(r, e, "key", NULL, &key);
    if (st == TD_OK && !key)
        st = td_cr_missing(r, e, "key", "the swept case key, e.g. \"speed\"");
    if (st == TD_OK && (!key[0] || strchr(key, '=')))
        st = td_cr_fail(r, e, "key", "expected a case key such as \"speed\" or \"retainers[0].friction\"");
    if (st == TD_OK) {
        td_text_printf(&t, "%s=", key);
        st = td_cr_has(e, "values") ? list_spec(r, e, &t) : range_spec(r, e, &t);
    }
    if (st == TD_OK)
        st = keep_spec(r, e, with, &t);
    free(t.data);
    return st;
}

/* An entry of `vary`: its key, then the keys zipped with it. */
static td_status read_axis(td_case_reader *r, const config_setting_t *list, int i)
{
    const config_setting_t *e, *with, *z;
    int j;
    td_status st = td_cr_entry(r, list, i, &e);
    if (st == TD_OK)
        st = read_key(r, e, 0);
    if (st == TD_OK)
        st = td_cr_list(r, e, "with", &with);
    for (j = 0; st == TD_OK && with && j < config_setting_length(with); j++) {
        st = td_cr_entry(r, with, j, &z);
        if (st == TD_OK)
            st = read_key(r, z, 1);
    }
    return st;
}

td_status td_cr_read_sweep(td_case_reader *r, const config_setting_t *root)
{
    const config_setting_t *g, *vary = NULL;
    int i;
    td_status st = td_cr_group(r, root, "sweep", NULL, &g);
    if (st != TD_OK || !g)
        return st;
    st = td_cr_check_keys(r, g, sweep_keys);
    if (st == TD_OK)
        st = td_cr_list(r, g, "vary", &vary);
    for (i = 0; st == TD_OK && vary && i < config_setting_length(vary); i++)
        st = read_axis(r, vary, i);
    return st;
}

const td_cr_sweep_spec *td_cr_sweep_entry(const td_case *c, int i)
{
    return &c->sweep[i];
}

void td_cr_sweep_context(const td_cr_sweep_spec *s, const char *setting, char *buf, size_t n)
{
    char key[TD_CR_SWEEP_KEY_SIZE]; /* the key with its setting, cut as td_cr_fail cuts it */
    snprintf(key, sizeof key, "%s%s%s", s->key, setting ? "." : "", setting ? setting : "");
    snprintf(buf, n, "%s: %s", s->at, key);
}
