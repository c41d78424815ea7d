/*
 * Command-line overrides "KEY=VALUE" (--set): VALUE is parsed by libconfig as "v = VALUE;" and
 * grafted into the parsed case at KEY before any key is read, so an override goes through exactly
 * the checks the file does. Every grafted setting carries the override string as its libconfig
 * hook, which is how error messages name the override instead of a file line.
 */
#include "case/case_internal.h"
#include "util/error_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TD_CR_STR_(x) #x
#define TD_CR_STR(x) TD_CR_STR_(x)

/* Longest key accepted in an override. */
#define TD_CR_MAX_KEY 256
/* Most path steps (names and [index]) in a key. */
#define TD_CR_MAX_STEPS 16

typedef struct step {
    char name[TD_CR_MAX_KEY]; /* "" for an [index] step */
    int index;
} step;

/* "CASE: --set 'OV': what" or, for an entry of the case's overrides list, "FILE:LINE: overrides[i]
 * 'OV': what", the echoed override shortened when the whole would not fit. */
static td_status fail_override(td_case_reader *r, td_status code, const char *ov, const char *what)
{
    char shown[2048], where[4096], at[1024], key[512];
    td_cr_printable(ov, shown, sizeof shown);
    if (r->ov_entry) {
        td_cr_where(r, r->ov_entry, at, sizeof at);
        td_cr_key(r->ov_entry, key, sizeof key);
        snprintf(where, sizeof where, "%s: %s: '%s'", at, key, shown);
    } else {
        snprintf(where, sizeof where, "%s: --set '%s'", r->path_shown, shown);
    }
    td_error_set_reason(r->err, code, where, what);
    if (!r->ov_entry)
        td_cr_blame_override(r, ov);
    return code;
}

td_status td_cr_apply_file_overrides(td_case_reader *r)
{
    const config_setting_t *list = config_setting_get_member(config_root_setting(&r->cfg), "overrides");
    td_status st = TD_OK;
    int i, n;
    if (!list)
        return TD_OK;
    if (!config_setting_is_list(list) && !config_setting_is_array(list))
        return td_cr_fail(r, list, NULL, "expected a list of \"KEY=VALUE\" strings");
    r->overrides = list;
    n = config_setting_length(list);
    for (i = 0; st == TD_OK && i < n; i++) {
        const config_setting_t *e = config_setting_get_elem(list, (unsigned)i);
        if (config_setting_type(e) != CONFIG_TYPE_STRING)
            return td_cr_fail(r, e, NULL, "expected a \"KEY=VALUE\" string");
        r->ov_entry = e;
        st = td_cr_apply_override(r, config_setting_get_string(e));
    }
    r->ov_entry = NULL;
    return st;
}

static td_status bad(td_case_reader *r, const char *ov, const char *what)
{
    return fail_override(r, TD_ERR_PARSE, ov, what);
}

static td_status out_of_memory(td_case_reader *r, const char *ov)
{
    return fail_override(r, TD_ERR_NOMEM, ov, "out of memory");
}

/* Split "a.b[2].c" (or libconfig's "a.b.[2].c") into steps; returns the count, -1 if malformed. */
static int split_key(const char *key, step *steps)
{
    const char *p = key;
    int n = 0;
    while (*p) {
        size_t len = strcspn(p, ".[");
        if (len >= TD_CR_MAX_KEY || n == TD_CR_MAX_STEPS)
            return -1;
        if (len > 0) {
            memcpy(steps[n].name, p, len);
            steps[n].name[len] = '\0';
            steps[n++].index = -1;
            p += len;
        } else if (*p != '[') {
            return -1; /* empty name: "a..b" or leading '.' */
        }
        while (*p == '[') {
            char *end;
            long v = strtol(p + 1, &end, 10);
            if (end == p + 1 || *end != ']' || v < 0 || v > 1000000 || n == TD_CR_MAX_STEPS)
                return -1;
            steps[n].name[0] = '\0';
            steps[n++].index = (int)v;
            p = end + 1;
        }
        if (*p == '.') {
            p++;
            if (!*p)
                return -1;
        } else if (*p) {
            return -1;
        }
    }
    return n;
}

/* Deep copy of src appended to parent as `name` (NULL inside lists and arrays). */
static config_setting_t *copy_setting(config_setting_t *parent, const char *name, const config_setting_t *src)
{
    int type = config_setting_type(src), i, ok = 1;
    config_setting_t *dst = config_setting_add(parent, name, type);
    if (!dst)
        return NULL;
    switch (type) {
    case CONFIG_TYPE_INT: ok = config_setting_set_int(dst, config_setting_get_int(src)); break;
    case CONFIG_TYPE_INT64: ok = config_setting_set_int64(dst, config_setting_get_int64(src)); break;
    case CONFIG_TYPE_FLOAT: ok = config_setting_set_float(dst, config_setting_get_float(src)); break;
    case CONFIG_TYPE_BOOL: ok = config_setting_set_bool(dst, config_setting_get_bool(src)); break;
    case CONFIG_TYPE_STRING: ok = config_setting_set_string(dst, config_setting_get_string(src)); break;
    default:
        for (i = 0; ok && i < config_setting_length(src); i++) {
            const config_setting_t *child = config_setting_get_elem(src, (unsigned)i);
            ok = copy_setting(dst, config_setting_is_group(src) ? config_setting_name(child) : NULL, child) != NULL;
        }
    }
    return ok ? dst : NULL;
}

/* Replace element `index` of an array or list in place (libconfig 1.5 cannot insert at an index). */
static td_status replace_element(td_case_reader *r, const char *ov, config_setting_t *agg, int index,
                                 const config_setting_t *val)
{
    config_setting_t *el = config_setting_get_elem(agg, (unsigned)index);
    int et = config_setting_type(el), vt = config_setting_type(val), i, ok = 1;
    if (et == CONFIG_TYPE_FLOAT && (vt == CONFIG_TYPE_INT || vt == CONFIG_TYPE_INT64))
        ok = config_setting_set_float(el, vt == CONFIG_TYPE_INT ? (double)config_setting_get_int(val)
                                                                : (double)config_setting_get_int64(val));
    else if (et != vt)
        return bad(r, ov, "the new value must have the type of the entry it replaces");
    else if (et == CONFIG_TYPE_GROUP) {
        while (config_setting_length(el) > 0)
            config_setting_remove_elem(el, 0);
        for (i = 0; ok && i < config_setting_length(val); i++) {
            const config_setting_t *child = config_setting_get_elem(val, (unsigned)i);
            ok = copy_setting(el, config_setting_name(child), child) != NULL;
        }
    } else if (et == CONFIG_TYPE_INT)
        ok = config_setting_set_int(el, config_setting_get_int(val));
    else if (et == CONFIG_TYPE_INT64)
        ok = config_setting_set_int64(el, config_setting_get_int64(val));
    else if (et == CONFIG_TYPE_FLOAT)
        ok = config_setting_set_float(el, config_setting_get_float(val));
    else if (et == CONFIG_TYPE_BOOL)
        ok = config_setting_set_bool(el, config_setting_get_bool(val));
    else if (et == CONFIG_TYPE_STRING)
        ok = config_setting_set_string(el, config_setting_get_string(val));
    else
        return bad(r, ov, "cannot replace a whole nested list or array entry; set the enclosing key instead");
    if (!ok)
        return out_of_memory(r, ov);
    config_setting_set_hook(el, (void *)ov);
    return TD_OK;
}

/* Walk to the parent of the last step, creating missing groups (marked as coming from `ov`). */
static td_status walk(td_case_reader *r, const char *ov, const step *steps, int n, config_setting_t **out)
{
    config_setting_t *cur = config_root_setting(&r->cfg);
    char msg[TD_ERROR_MESSAGE_SIZE], shown[200];
    int i;
    for (i = 0; i < n; i++) {
        config_setting_t *next;
        if (steps[i].name[0]) {
            if (!config_setting_is_group(cur)) {
                snprintf(msg, sizeof msg, "cannot set '%s': its parent is not a group",
                         td_cr_printable(steps[i].name, shown, sizeof shown));
                return bad(r, ov, msg);
            }
            next = config_setting_get_member(cur, steps[i].name);
            if (!next) {
                if (config_setting_length(cur) >= TD_CASE_MAX_GROUP_KEYS)
                    return bad(r, ov, "the group would hold more than " TD_CR_STR(TD_CASE_MAX_GROUP_KEYS) " keys");
                next = config_setting_add(cur, steps[i].name, CONFIG_TYPE_GROUP);
                if (!next) {
                    snprintf(msg, sizeof msg, "'%s' is not a valid key name",
                             td_cr_printable(steps[i].name, shown, sizeof shown));
                    return bad(r, ov, msg);
                }
                config_setting_set_hook(next, (void *)ov);
            }
        } else {
            if (!config_setting_is_list(cur) && !config_setting_is_array(cur))
                return bad(r, ov, "[index] follows a key that is not a list");
            if (steps[i].index >= config_setting_length(cur)) {
                snprintf(msg, sizeof msg, "index [%d] is out of range (the list has %d entries)", steps[i].index,
                         config_setting_length(cur));
                return bad(r, ov, msg);
            }
            next = config_setting_get_elem(cur, (unsigned)steps[i].index);
        }
        cur = next;
    }
    *out = cur;
    return TD_OK;
}

/* Graft `val` at the steps. */
static td_status graft(td_case_reader *r, const char *ov, const step *steps, int n, const config_setting_t *val)
{
    config_setting_t *parent = NULL, *dst;
    const step *last = &steps[n - 1];
    char msg[TD_ERROR_MESSAGE_SIZE], shown[200];
    td_status st = walk(r, ov, steps, n - 1, &parent);
    if (st != TD_OK)
        return st;
    if (!last->name[0]) {
        if (!config_setting_is_list(parent) && !config_setting_is_array(parent))
            return bad(r, ov, "[index] follows a key that is not a list");
        if (last->index >= config_setting_length(parent)) {
            snprintf(msg, sizeof msg, "index [%d] is out of range (the list has %d entries)", last->index,
                     config_setting_length(parent));
            return bad(r, ov, msg);
        }
        return replace_element(r, ov, parent, last->index, val);
    }
    if (!config_setting_is_group(parent)) {
        snprintf(msg, sizeof msg, "cannot set '%s': its parent is not a group",
                 td_cr_printable(last->name, shown, sizeof shown));
        return bad(r, ov, msg);
    }
    if (config_setting_get_member(parent, last->name))
        config_setting_remove(parent, last->name);
    else if (config_setting_length(parent) >= TD_CASE_MAX_GROUP_KEYS)
        /* libconfig searches a group linearly: a bounded group keeps overrides linear too */
        return bad(r, ov, "the group would hold more than " TD_CR_STR(TD_CASE_MAX_GROUP_KEYS) " keys");
    dst = copy_setting(parent, last->name, val);
    if (!dst) {
        /* copy_setting fails on a bad name, or on memory; a valid name can only mean memory */
        if (!config_setting_get_member(parent, last->name)) {
            snprintf(msg, sizeof msg, "'%s' is not a valid key name", td_cr_printable(last->name, shown, sizeof shown));
            return bad(r, ov, msg);
        }
        return out_of_memory(r, ov);
    }
    config_setting_set_hook(dst, (void *)ov);
    return TD_OK;
}

/* Count the settings of the override's text "v = VALUE;" against the bounds of the case (they
 * add to those of the file) before libconfig parses it; a bound passed is reported as the
 * override's error. */
static td_status count_value(td_case_reader *r, const char *ov, const char *src)
{
    td_text scratch = {NULL, 0, 0, 0, 0};
    td_error scan_err, *saved = r->err;
    int root_keys = r->shape.keys[0];
    td_status st;
    r->err = &scan_err;
    r->shape.depth = 0;
    st = td_cr_expand(r, src, NULL, TD_CASE_MAX_INCLUDE_DEPTH, &scratch);
    r->shape.keys[0] = root_keys; /* "v" is no key of the case; graft bounds the group it goes to */
    r->err = saved;
    free(scratch.data);
    if (st == TD_OK)
        return TD_OK;
    /* the scan names the case file, line 1: keep its reason */
    return bad(r, ov, scan_err.message + scan_err.reason);
}

/* Parse VALUE as a libconfig value into vc (a single setting "v"), or as a bare string. */
static td_status parse_value(td_case_reader *r, const char *ov, const char *value, config_t *vc)
{
    char *src, literal[40], msg[TD_ERROR_MESSAGE_SIZE], shown[200];
    config_setting_t *s;
    size_t n = strlen(value);
    int ok;
    if (td_cr_value_wraps(value, literal, sizeof literal)) {
        snprintf(msg, sizeof msg, "integer %s is out of range (at most 2147483647)", literal);
        return bad(r, ov, msg);
    }
    src = malloc(n + 8);
    if (!src)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
    sprintf(src, "v = %s;", value);
    if (count_value(r, ov, src) != TD_OK) {
        free(src);
        return TD_ERR_PARSE;
    }
    ok = config_read_string(vc, src);
    free(src);
    if (ok && config_setting_length(config_root_setting(vc)) == 1 && config_lookup(vc, "v"))
        return TD_OK;
    if (ok || strchr("\"[({", value[0])) {
        snprintf(msg, sizeof msg, "cannot parse the value '%s' (%s)", td_cr_printable(value, shown, sizeof shown),
                 ok ? "more than one value" : config_error_text(vc));
        return bad(r, ov, msg);
    }
    /* a bare word such as penalty or out/run.h5: take it as a string */
    config_destroy(vc);
    config_init(vc);
    s = config_setting_add(config_root_setting(vc), "v", CONFIG_TYPE_STRING);
    if (!s || !config_setting_set_string(s, value))
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: out of memory", r->path_shown);
    return TD_OK;
}

td_status td_cr_apply_override(td_case_reader *r, const char *ov)
{
    char key[TD_CR_MAX_KEY + 2];
    step steps[TD_CR_MAX_STEPS];
    const char *eq, *value;
    size_t klen;
    int n;
    config_t vc;
    td_status st;

    if (!ov)
        return td_error_set(r->err, TD_ERR_INVALID, "%s: override string is NULL", r->path_shown);
    eq = strchr(ov, '=');
    if (!eq || strchr(ov, '\n'))
        return bad(r, ov, "expected KEY=VALUE on one line (e.g. --set speed=190)");
    /* trim blanks around the key and before the value */
    while (*ov == ' ' || *ov == '\t')
        ov++;
    klen = (size_t)(eq - ov);
    while (klen > 0 && (ov[klen - 1] == ' ' || ov[klen - 1] == '\t'))
        klen--;
    if (klen == 0 || klen > TD_CR_MAX_KEY)
        return bad(r, ov, "expected KEY=VALUE with a non-empty key (e.g. --set speed=190)");
    memcpy(key, ov, klen);
    key[klen] = '\0';
    for (value = eq + 1; *value == ' ' || *value == '\t'; value++)
        ;
    if (!*value)
        return bad(r, ov, "the value after '=' is empty");
    n = split_key(key, steps);
    if (n <= 0)
        return bad(r, ov, "malformed key (use names and [index] joined by dots, e.g. retainers[0].friction)");
    config_init(&vc);
    st = parse_value(r, ov, value, &vc);
    if (st == TD_OK)
        st = graft(r, ov, steps, n, config_lookup(&vc, "v"));
    config_destroy(&vc);
    return st;
}
