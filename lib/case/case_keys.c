/*
 * The case schema's tables (case_schema.h) as a list of keys with their type, range, unit,
 * default and doc, for the documentation: every key once, each group's keys after it.
 */
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A number as the docs write it: %g without the exponent's plus sign and leading zeros (1e-6). */
static void number_text(double v, char *buf, size_t n)
{
    char raw[64], *e;
    snprintf(raw, sizeof raw, "%g", v);
    e = strchr(raw, 'e');
    if (e) {
        const char *digits = e + 1 + (e[1] == '+' || e[1] == '-');
        int negative = e[1] == '-';
        while (digits[0] == '0' && digits[1])
            digits++;
        e[0] = '\0';
        snprintf(buf, n, "%se%s%s", raw, negative ? "-" : "", digits);
        return;
    }
    snprintf(buf, n, "%s", raw);
}

static const char *range_text(td_cr_range range)
{
    switch (range) {
    case TD_CR_FINITE: return "";
    case TD_CR_POSITIVE: return "> 0";
    case TD_CR_NONNEGATIVE: return ">= 0";
    case TD_CR_FRACTION: return "in [0, 1]";
    case TD_CR_OPEN_UNIT: return "in (0, 1)";
    }
    return "";
}

/* "`\"a\"` or `\"b\"`", "`\"a\"`, `\"b\"` or `\"c\"`" */
static void names_text(const td_cs_key *k, char *buf, size_t n)
{
    size_t len = 0;
    int i;
    buf[0] = '\0';
    for (i = 0; i < k->name_count && len < n; i++) {
        const char *sep = i == 0 ? "" : i == k->name_count - 1 ? " or " : ", ";
        snprintf(buf + len, n - len, "%s`\"%s\"`", sep, k->names[i]);
        len = strlen(buf);
    }
}

static void type_text(const td_cs_key *k, char *buf, size_t n)
{
    const char *t = "";
    switch (k->type) {
    case TD_CS_REAL: t = "number"; break;
    case TD_CS_INT: t = "integer"; break;
    case TD_CS_BOOL: t = "boolean"; break;
    case TD_CS_ENUM: names_text(k, buf, n); return;
    case TD_CS_PATH:
    case TD_CS_STRING: t = "string"; break;
    case TD_CS_REALS: t = "array of numbers"; break;
    case TD_CS_GROUP: t = "group"; break;
    case TD_CS_LIST: t = "list"; break;
    case TD_CS_CUSTOM: t = ""; break;
    }
    snprintf(buf, n, "%s", k->doc_type ? k->doc_type : t);
}

static void key_range(const td_cs_key *k, char *buf, size_t n)
{
    const char *r = range_text(k->range != TD_CR_FINITE ? k->range : k->rule);
    if (k->doc_range)
        snprintf(buf, n, "%s", k->doc_range);
    else if (k->type == TD_CS_INT && k->lo > TD_CR_ANY_INT_LO && k->hi < TD_CR_ANY_INT_HI)
        snprintf(buf, n, "%ld..%ld", k->lo, k->hi);
    else if (k->type == TD_CS_REALS)
        snprintf(buf, n, "%s%sat most %ld", r, r[0] ? ", " : "", k->hi);
    else if (k->type == TD_CS_REAL)
        snprintf(buf, n, "%s", r);
    else
        buf[0] = '\0';
}

/* The value an absent key gives: `def`, or the record's as the table's preset sets it. */
static void value_text(const td_cs_key *k, const td_cs_table *t, char *buf, size_t n)
{
    unsigned char *rec = calloc(1, t->size ? t->size : 1);
    double d = k->def;
    int v = (int)k->def;
    if (rec && k->need == TD_CS_PRESET && t->preset) {
        t->preset(rec);
        memcpy(&d, rec + k->offset, sizeof d);
        memcpy(&v, rec + k->offset, sizeof v);
    }
    free(rec);
    switch (k->type) {
    case TD_CS_REAL: number_text(d, buf, n); return;
    case TD_CS_INT: snprintf(buf, n, "%d", v); return;
    case TD_CS_BOOL: snprintf(buf, n, "%s", v ? "true" : "false"); return;
    case TD_CS_ENUM: snprintf(buf, n, "`\"%s\"`", v >= 0 && v < k->name_count ? k->names[v] : "?"); return;
    case TD_CS_PATH:
    case TD_CS_STRING: snprintf(buf, n, "`\"\"`"); return;
    default: snprintf(buf, n, "none"); return;
    }
}

static void default_text(const td_cs_key *k, const td_cs_table *t, char *buf, size_t n)
{
    char value[128];
    if (k->doc_default && !strstr(k->doc_default, "%s")) {
        snprintf(buf, n, "%s", k->doc_default);
        return;
    }
    if (k->need == TD_CS_REQUIRED)
        snprintf(value, sizeof value, "required");
    else
        value_text(k, t, value, sizeof value);
    if (k->doc_default) /* "%s (none)": the value with what it means */
        snprintf(buf, n, k->doc_default, value);
    else
        snprintf(buf, n, "%s", value);
}

static void describe(const td_cs_key *k, const td_cs_table *t, const char *section, td_case_key_info *out)
{
    memset(out, 0, sizeof *out);
    out->section = section;
    snprintf(out->key, sizeof out->key, "%s%s%s", t->name, t->name[0] ? "." : "", k->key);
    type_text(k, out->type, sizeof out->type);
    key_range(k, out->range, sizeof out->range);
    out->unit = k->unit ? k->unit : "";
    default_text(k, t, out->default_value, sizeof out->default_value);
    out->doc = k->doc ? k->doc : "";
}

/* Walk table t (in `section`) to the *i-th key; 1 when found (described into out). */
static int walk(const td_cs_table *t, const char *section, int *i, td_case_key_info *out)
{
    int j;
    section = t->section ? t->section : section;
    for (j = 0; j < t->count; j++) {
        const td_cs_key *k = &t->keys[j];
        if ((*i)-- == 0) {
            if (out)
                describe(k, t, section, out);
            return 1;
        }
        if ((k->type == TD_CS_GROUP || k->type == TD_CS_LIST) && k->sub && walk(k->sub, section, i, out))
            return 1;
    }
    return 0;
}

int td_case_key_count(void)
{
    int i = -1;
    walk(&td_cs_root, "top", &i, NULL);
    return -1 - i;
}

td_status td_case_key(int i, td_case_key_info *out, td_error *err)
{
    int left = i;
    if (!out || i < 0)
        return td_error_set(err, TD_ERR_INVALID, "td_case_key: NULL output or key %d out of range", i);
    if (!walk(&td_cs_root, "top", &left, out))
        return td_error_set(err, TD_ERR_INVALID, "td_case_key: key %d out of range (there are %d)", i,
                            td_case_key_count());
    td_error_clear(err);
    return TD_OK;
}
