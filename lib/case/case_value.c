/*
 * Typed, checked access to libconfig settings: every getter fails with the reader's one error
 * format (case_message.c). libconfig 1.5 tells integers (1) from floats (1.0); every real-valued
 * key accepts both.
 */
#include "case/case_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

td_status td_cr_derived(td_case_reader *r, const config_setting_t *s, double value, const char *what)
{
    if (isfinite(value))
        return TD_OK;
    return td_cr_fail(r, s, NULL, "%s overflows (to %g)", what, value);
}

static const char *type_name(int type)
{
    switch (type) {
    case CONFIG_TYPE_GROUP: return "a group { ... }";
    case CONFIG_TYPE_INT: return "an integer";
    case CONFIG_TYPE_INT64: return "a 64-bit integer";
    case CONFIG_TYPE_FLOAT: return "a number";
    case CONFIG_TYPE_STRING: return "a string";
    case CONFIG_TYPE_BOOL: return "a boolean";
    case CONFIG_TYPE_ARRAY: return "an array [ ... ]";
    case CONFIG_TYPE_LIST: return "a list ( ... )";
    }
    return "nothing";
}

/* Edit distance of two names counting a swap of neighbours as one edit (optimal string
 * alignment), so "strat" is one edit from "start"; names are cut at 63 characters. */
static int edit_distance(const char *a, const char *b)
{
    int d[64][64], i, j, la = (int)strlen(a), lb = (int)strlen(b);
    if (la > 63)
        la = 63;
    if (lb > 63)
        lb = 63;
    for (i = 0; i <= la; i++)
        d[i][0] = i;
    for (j = 0; j <= lb; j++)
        d[0][j] = j;
    for (i = 1; i <= la; i++)
        for (j = 1; j <= lb; j++) {
            int cost = a[i - 1] == b[j - 1] ? 0 : 1, v = d[i - 1][j - 1] + cost;
            if (d[i - 1][j] + 1 < v)
                v = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < v)
                v = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[la][lb];
}

static td_status unknown_key(td_case_reader *r, const config_setting_t *s, const char *const *allowed)
{
    const char *name = config_setting_name(s), *best = NULL;
    int best_d = 1000, i, limit;
    char list[400];
    size_t len = 0;
    for (i = 0; allowed[i]; i++) {
        int d = edit_distance(name, allowed[i]);
        if (d < best_d) {
            best_d = d;
            best = allowed[i];
        }
    }
    limit = strlen(name) >= 6 ? 2 : 1;
    if (best && best_d <= limit)
        return td_cr_fail(r, s, NULL, "unknown key; did you mean '%s'?", best);
    list[0] = '\0';
    for (i = 0; allowed[i] && len + strlen(allowed[i]) + 3 < sizeof list; i++) {
        snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", allowed[i]);
        len = strlen(list);
    }
    return td_cr_fail(r, s, NULL, "unknown key (valid here: %s)", list);
}

td_status td_cr_check_keys(td_case_reader *r, const config_setting_t *g, const char *const *allowed)
{
    int i, j, n = config_setting_length(g);
    for (i = 0; i < n; i++) {
        const config_setting_t *s = config_setting_get_elem(g, (unsigned)i);
        const char *name = config_setting_name(s);
        for (j = 0; allowed[j]; j++)
            if (strcmp(name, allowed[j]) == 0)
                break;
        if (!allowed[j])
            return unknown_key(r, s, allowed);
    }
    return TD_OK;
}

int td_cr_has(const config_setting_t *g, const char *key)
{
    return config_setting_get_member(g, key) != NULL;
}

td_status td_cr_missing(td_case_reader *r, const config_setting_t *g, const char *key, const char *what)
{
    return td_cr_fail(r, g, key, "missing required key (%s)", what);
}

/* Explain a string where a number was expected; NaN and infinities are named because C's
 * strtod would accept them but libconfig cannot write them. */
static td_status not_a_number(td_case_reader *r, const config_setting_t *s, const char *expected)
{
    if (config_setting_type(s) == CONFIG_TYPE_STRING) {
        const char *v = config_setting_get_string(s);
        const char *p = v + (v[0] == '-' || v[0] == '+');
        char shown[64];
        td_cr_printable(v, shown, sizeof shown);
        if (strncmp(p, "nan", 3) == 0 || strncmp(p, "NaN", 3) == 0 || strncmp(p, "NAN", 3) == 0 ||
            strncmp(p, "inf", 3) == 0 || strncmp(p, "Inf", 3) == 0 || strncmp(p, "INF", 3) == 0)
            return td_cr_fail(r, s, NULL, "expected %s, got \"%s\" (NaN and infinities are not accepted)", expected,
                              shown);
        return td_cr_fail(r, s, NULL, "expected %s, got the string \"%s\"", expected, shown);
    }
    return td_cr_fail(r, s, NULL, "expected %s, got %s", expected, type_name(config_setting_type(s)));
}

td_status td_cr_value_real(td_case_reader *r, const config_setting_t *s, td_cr_range range, double *out)
{
    double v;
    switch (config_setting_type(s)) {
    case CONFIG_TYPE_INT: v = (double)config_setting_get_int(s); break;
    case CONFIG_TYPE_INT64: v = (double)config_setting_get_int64(s); break;
    case CONFIG_TYPE_FLOAT: v = config_setting_get_float(s); break;
    default: return not_a_number(r, s, "a number");
    }
    if (!isfinite(v))
        return td_cr_fail(r, s, NULL, "must be finite (got %g; NaN and infinities are not accepted)", v);
    switch (range) {
    case TD_CR_FINITE: break;
    case TD_CR_POSITIVE:
        if (!(v > 0.0))
            return td_cr_fail(r, s, NULL, "must be > 0 (got %g)", v);
        break;
    case TD_CR_NONNEGATIVE:
        if (!(v >= 0.0))
            return td_cr_fail(r, s, NULL, "must be >= 0 (got %g)", v);
        break;
    case TD_CR_FRACTION:
        if (!(v >= 0.0 && v <= 1.0))
            return td_cr_fail(r, s, NULL, "must lie in [0, 1] (got %g)", v);
        break;
    case TD_CR_OPEN_UNIT:
        if (!(v > 0.0 && v < 1.0))
            return td_cr_fail(r, s, NULL, "must lie in (0, 1) (got %g)", v);
        break;
    }
    *out = v;
    return TD_OK;
}

td_status td_cr_value_int(td_case_reader *r, const config_setting_t *s, long lo, long hi, int *out)
{
    long long v;
    switch (config_setting_type(s)) {
    case CONFIG_TYPE_INT: v = config_setting_get_int(s); break;
    case CONFIG_TYPE_INT64: v = config_setting_get_int64(s); break;
    case CONFIG_TYPE_FLOAT:
        return td_cr_fail(r, s, NULL, "expected an integer, got the number %g (write integers without a point)",
                          config_setting_get_float(s));
    default: return not_a_number(r, s, "an integer");
    }
    if (v < lo || v > hi)
        return td_cr_fail(r, s, NULL, "must lie in [%ld, %ld] (got %lld)", lo, hi, v);
    *out = (int)v;
    return TD_OK;
}

td_status td_cr_real(td_case_reader *r, const config_setting_t *g, const char *key, const char *what, double def,
                     td_cr_range range, double *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) {
        if (what)
            return td_cr_missing(r, g, key, what);
        *out = def;
        return TD_OK;
    }
    return td_cr_value_real(r, s, range, out);
}

td_status td_cr_int(td_case_reader *r, const config_setting_t *g, const char *key, const char *what, int def, long lo,
                    long hi, int *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) {
        if (what)
            return td_cr_missing(r, g, key, what);
        *out = def;
        return TD_OK;
    }
    return td_cr_value_int(r, s, lo, hi, out);
}

td_status td_cr_bool(td_case_reader *r, const config_setting_t *g, const char *key, int def, int *out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) {
        *out = def;
        return TD_OK;
    }
    if (config_setting_type(s) != CONFIG_TYPE_BOOL)
        return not_a_number(r, s, "true or false");
    *out = config_setting_get_bool(s) ? 1 : 0;
    return TD_OK;
}

td_status td_cr_string(td_case_reader *r, const config_setting_t *g, const char *key, const char *def, const char **out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    if (!s) {
        *out = def;
        return TD_OK;
    }
    if (config_setting_type(s) != CONFIG_TYPE_STRING)
        return td_cr_fail(r, s, NULL, "expected a string \"...\", got %s", type_name(config_setting_type(s)));
    *out = config_setting_get_string(s);
    return TD_OK;
}

td_status td_cr_enum(td_case_reader *r, const config_setting_t *g, const char *key, const char *const *names, int n,
                     int def, int *out)
{
    const char *v = NULL; /* set by td_cr_string on TD_OK; initialised for gcc -O3's flow analysis */
    char list[256], shown[64];
    size_t len = 0;
    int i;
    td_status st = td_cr_string(r, g, key, NULL, &v);
    if (st != TD_OK)
        return st;
    if (!v) {
        *out = def;
        return TD_OK;
    }
    for (i = 0; i < n; i++)
        if (strcmp(v, names[i]) == 0) {
            *out = i;
            return TD_OK;
        }
    list[0] = '\0';
    for (i = 0; i < n; i++) {
        snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "", names[i]);
        len = strlen(list);
    }
    return td_cr_fail(r, config_setting_get_member(g, key), NULL, "must be one of %s (got \"%s\")", list,
                      td_cr_printable(v, shown, sizeof shown));
}

td_status td_cr_group(td_case_reader *r, const config_setting_t *g, const char *key, const char *what,
                      const config_setting_t **out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    *out = NULL;
    if (!s)
        return what ? td_cr_missing(r, g, key, what) : TD_OK;
    if (!config_setting_is_group(s))
        return td_cr_fail(r, s, NULL, "expected a group { ... }, got %s", type_name(config_setting_type(s)));
    *out = s;
    return TD_OK;
}

td_status td_cr_list(td_case_reader *r, const config_setting_t *g, const char *key, const config_setting_t **out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    *out = NULL;
    if (!s)
        return TD_OK;
    /* "[]" is how an empty list is often written; libconfig types it as an array */
    if (config_setting_is_array(s) && config_setting_length(s) == 0) {
        *out = s;
        return TD_OK;
    }
    if (!config_setting_is_list(s))
        return td_cr_fail(r, s, NULL, "expected a list of groups ( { ... }, { ... } ), got %s",
                          type_name(config_setting_type(s)));
    *out = s;
    return TD_OK;
}

td_status td_cr_entry(td_case_reader *r, const config_setting_t *list, int i, const config_setting_t **out)
{
    const config_setting_t *s = config_setting_get_elem(list, (unsigned)i);
    *out = NULL;
    if (!config_setting_is_group(s))
        return td_cr_fail(r, s, NULL, "expected a group { ... }, got %s", type_name(config_setting_type(s)));
    *out = s;
    return TD_OK;
}

/* The array or list member `key` of scalars, checking its length; *out NULL when absent. */
static td_status vector(td_case_reader *r, const config_setting_t *g, const char *key, int max,
                        const config_setting_t **out)
{
    const config_setting_t *s = config_setting_get_member(g, key);
    *out = NULL;
    if (!s)
        return TD_OK;
    if (!config_setting_is_array(s) && !config_setting_is_list(s))
        return td_cr_fail(r, s, NULL, "expected an array [ ... ], got %s", type_name(config_setting_type(s)));
    if (config_setting_length(s) > max)
        return td_cr_fail(r, s, NULL, "too many entries (%d, at most %d)", config_setting_length(s), max);
    *out = s;
    return TD_OK;
}

td_status td_cr_reals(td_case_reader *r, const config_setting_t *g, const char *key, int max, td_cr_range range,
                      double *out, int *n)
{
    const config_setting_t *s;
    int i;
    td_status st = vector(r, g, key, max, &s);
    *n = 0;
    if (st != TD_OK || !s)
        return st;
    for (i = 0; i < config_setting_length(s); i++) {
        st = td_cr_value_real(r, config_setting_get_elem(s, (unsigned)i), range, &out[i]);
        if (st != TD_OK)
            return st;
    }
    *n = i;
    return TD_OK;
}

td_status td_cr_ints(td_case_reader *r, const config_setting_t *g, const char *key, int max, long lo, long hi, int *out,
                     int *n)
{
    const config_setting_t *s;
    int i;
    td_status st = vector(r, g, key, max, &s);
    *n = 0;
    if (st != TD_OK || !s)
        return st;
    for (i = 0; i < config_setting_length(s); i++) {
        st = td_cr_value_int(r, config_setting_get_elem(s, (unsigned)i), lo, hi, &out[i]);
        if (st != TD_OK)
            return st;
    }
    *n = i;
    return TD_OK;
}
