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
 * it was written (td_cr_sweep_spec). The group is read by its tables (case_schema.h, below) as
 * every group is: its keys, the types of the values, a key to sweep, values or a range but not
 * both; the range's numbers are kept as the text they were written in. What the specs mean
 * (forms, counts, limits) is judged by the sweep's own rules (lib/sweep/case_group.c), so that
 * the command line and the file obey one set of rules.
 */
#include "case/case_schema.h"
#include "touchdown/sweep.h" /* TD_SWEEP_MAX_POINTS, for the docs */
#include "util/text.h"

#include <stdlib.h>
#include <string.h>

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

/* The text of a range's number: a double's shortest, or an integer's digits. */
#define SWEEP_NUMBER_SIZE 64

/* An entry of `vary` or of its `with`, as read: the parts its spec is made of. */
typedef struct sweep_entry {
    const char *key;
    const config_setting_t *values; /* NULL: a range */
    char from[SWEEP_NUMBER_SIZE], to[SWEEP_NUMBER_SIZE], points[SWEEP_NUMBER_SIZE];
    const char *spacing; /* NULL: the sweep's default */
} sweep_entry;

/* key: a case key as --set takes it (whether the case has it is checked when a point loads). */
static td_status check_key(td_case_reader *r, const config_setting_t *e, const td_cs_key *k, void *rec)
{
    const sweep_entry *s = rec;
    if (!s->key[0] || strchr(s->key, '='))
        return td_cr_fail(r, e, k->key, "expected a case key such as \"speed\" or \"retainers[0].friction\"");
    return TD_OK;
}

/* values: one form or the other, an array of at least one value (each value's type: keep_entry). */
static td_status read_values(td_case_reader *r, const config_setting_t *e, const td_cs_key *k, void *rec)
{
    const config_setting_t *v = config_setting_get_member(e, k->key);
    if (!v)
        return TD_OK;
    if (td_cr_has(e, "from") || td_cr_has(e, "to") || td_cr_has(e, "points") || td_cr_has(e, "spacing"))
        return td_cr_fail(r, e, NULL, "give either values or a range (from, to, points, spacing), not both");
    if (!config_setting_is_array(v) && !config_setting_is_list(v))
        return td_cr_fail(r, v, NULL, "expected an array [ ... ] of values");
    if (config_setting_length(v) == 0)
        return td_cr_fail(r, v, NULL, "no values: give at least one");
    ((sweep_entry *)rec)->values = v;
    return TD_OK;
}

/* from, to, points: a number each when there are no values, kept as the exact text the spec carries
 * (the sweep judges them: lib/sweep). */
static td_status read_bound(td_case_reader *r, const config_setting_t *e, const td_cs_key *k, void *rec)
{
    const config_setting_t *s = config_setting_get_member(e, k->key);
    int type = s ? config_setting_type(s) : CONFIG_TYPE_NONE;
    if (td_cr_has(e, "values")) /* read_values refused a range beside them */
        return TD_OK;
    if (!s)
        return td_cr_missing(r, e, k->key, k->what);
    if (type != CONFIG_TYPE_INT && type != CONFIG_TYPE_INT64 && type != CONFIG_TYPE_FLOAT)
        return td_cr_fail(r, s, NULL, "expected a number");
    number_text(s, (char *)rec + k->offset, SWEEP_NUMBER_SIZE);
    return TD_OK;
}

static td_status check_points(td_case_reader *r, const config_setting_t *e, const td_cs_key *k, void *rec)
{
    const config_setting_t *s = config_setting_get_member(e, k->key);
    (void)rec;
    if (s && !td_cr_has(e, "values") && config_setting_type(s) == CONFIG_TYPE_FLOAT)
        return td_cr_fail(r, e, k->key, "expected a whole number");
    return TD_OK;
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

/* Entry e as its spec, KEY=V1,V2,... or KEY=FROM:TO:POINTS[:SPACING], into the case's list
 * (with = 1: zipped onto the axis before it). */
static td_status keep_entry(td_case_reader *r, const config_setting_t *e, const sweep_entry *s, int with)
{
    td_text t = {NULL, 0, 0, 0, 0};
    int i, n = s->values ? config_setting_length(s->values) : 0;
    td_status st = TD_OK;
    td_text_printf(&t, "%s=", s->key);
    for (i = 0; st == TD_OK && i < n; i++) {
        if (i > 0)
            td_text_append(&t, ",", 1);
        st = value_text(r, config_setting_get_elem(s->values, (unsigned)i), &t);
    }
    if (!s->values)
        td_text_printf(&t, "%s:%s:%s%s%s", s->from, s->to, s->points, s->spacing ? ":" : "",
                       s->spacing ? s->spacing : "");
    if (st == TD_OK)
        st = keep_spec(r, e, with, &t);
    free(t.data);
    return st;
}

/* with: the axis's own spec is kept first, then the keys zipped onto it, each after its axis in
 * the case's list (the order the sweep adds them in: lib/sweep/case_group.c). */
static td_status read_with(td_case_reader *r, const config_setting_t *e, const td_cs_key *k, void *rec)
{
    const config_setting_t *with, *z;
    int j;
    td_status st = keep_entry(r, e, rec, 0);
    if (st == TD_OK)
        st = td_cr_list(r, e, k->key, &with);
    for (j = 0; st == TD_OK && with && j < config_setting_length(with); j++) {
        st = td_cr_entry(r, with, j, &z);
        if (st == TD_OK)
            st = td_cs_read_record(r, z, k->sub);
    }
    return st;
}

static td_status keep_with(td_case_reader *r, const config_setting_t *z, void *rec)
{
    return keep_entry(r, z, rec, 1);
}

static const td_cs_table sweep_with;

/* The members of an entry of `vary`, in the order of its "unknown key" list; an entry of `with`
 * has the same but `with` (the last). `order` reads the key, then the values (which refuse a
 * range beside them), then the range, then `with`. */
static const td_cs_key entry_keys[] = {
    {.key = "key",
     .type = TD_CS_STRING,
     .offset = offsetof(sweep_entry, key),
     .need = TD_CS_REQUIRED,
     .check = check_key,
     .what = "the swept case key, e.g. \"speed\"",
     .doc = "the swept case key, as `--set` takes it: `\"speed\"`, `\"retainers[0].friction\"`, `\"contact.model\"`"},
    {.key = "from",
     .type = TD_CS_REAL,
     .offset = offsetof(sweep_entry, from),
     .need = TD_CS_REQUIRED,
     .read = read_bound,
     .order = 2,
     .what = "the range's first value (or give values)",
     .unit = "the key's",
     .doc_default = "required for a range",
     .doc = "the range's first value"},
    {.key = "to",
     .type = TD_CS_REAL,
     .offset = offsetof(sweep_entry, to),
     .need = TD_CS_REQUIRED,
     .read = read_bound,
     .order = 2,
     .what = "the range's last value",
     .unit = "the key's",
     .doc_default = "required for a range",
     .doc = "the range's last value (may be below `from`)"},
    {.key = "points",
     .type = TD_CS_INT,
     .offset = offsetof(sweep_entry, points),
     .need = TD_CS_REQUIRED,
     .lo = 1,
     .hi = TD_SWEEP_MAX_POINTS, /* for the docs: the sweep judges the count (lib/sweep) */
     .read = read_bound,
     .check = check_points,
     .order = 2,
     .what = "the number of points",
     .doc_default = "required for a range",
     .doc = "number of values, both ends included (1: `from` alone)"},
    {.key = "spacing",
     .type = TD_CS_STRING,
     .offset = offsetof(sweep_entry, spacing),
     .order = 2,
     .doc_type = "`\"linear\"` or `\"log\"`",
     .doc_default = "`\"linear\"`",
     .doc = "`\"log\"`: geometric progression (a constant ratio), `from` and `to` > 0"},
    {.key = "values",
     .type = TD_CS_CUSTOM,
     .read = read_values,
     .order = 1,
     .unit = "the key's",
     .doc_type = "array or list of numbers, `true`/`false`, strings",
     .doc_default = "required without a range",
     .doc = "the values, instead of a range"},
    {.key = "with",
     .type = TD_CS_LIST,
     .sub = &sweep_with,
     .read = read_with,
     .order = 3,
     .doc = "keys zipped onto this axis, each with as many values as the axis"},
};
static const td_cs_table sweep_vary = {"sweep.vary[]",      NULL, entry_keys, TD_CS_COUNT(entry_keys),
                                       sizeof(sweep_entry), NULL, NULL};
static const td_cs_table sweep_with = {"sweep.vary[].with[]", NULL, entry_keys, TD_CS_COUNT(entry_keys) - 1,
                                       sizeof(sweep_entry),   NULL, keep_with};

static const td_cs_key sweep_keys[] = {
    {.key = "vary", .type = TD_CS_LIST, .sub = &sweep_vary, .doc = "the axes, slowest first"},
};
const td_cs_table td_cs_sweep = {"sweep", "sweep", sweep_keys, TD_CS_COUNT(sweep_keys), 0, NULL, NULL};

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
