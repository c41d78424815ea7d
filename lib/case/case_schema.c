/*
 * The one reader of the case schema's tables (case_schema.h): each row's type says which typed
 * getter of case_value.c reads it, so every key keeps the messages those getters give.
 */
#include "case/case_schema.h"
#include "util/error_internal.h"

#include <string.h>

/* A record read from a group of its own (a part, the gravity), on the stack. */
typedef union cs_record {
    double d;
    long l;
    void *p;
    unsigned char bytes[512];
} cs_record;

/* TD_CS_ENUM stores an int into the enum field its row names: every enum the tables read is
 * int-sized (a row that names another must not compile). */
typedef char cs_enums_are_ints[sizeof(td_contact_model) == sizeof(int) && sizeof(td_contact_damping) == sizeof(int) &&
                                       sizeof(td_linear_solver) == sizeof(int) && sizeof(td_start) == sizeof(int) &&
                                       sizeof(td_beam_theory) == sizeof(int) && sizeof(td_mass_form) == sizeof(int)
                                   ? 1
                                   : -1];

/* The keys of the widest table (the top level) with room to spare. */
#define CS_MAX_KEYS 64

td_status td_cs_check_keys(td_case_reader *r, const config_setting_t *g, const td_cs_table *t)
{
    const char *names[CS_MAX_KEYS + 1];
    int i;
    if (t->count > CS_MAX_KEYS) /* a table grown past the list: never check against a cut list */
        return td_error_set(r->err, TD_ERR_INVALID, "%s: internal: the table of '%s' has over %d keys", r->path_shown,
                            t->name, CS_MAX_KEYS);
    for (i = 0; i < t->count; i++)
        names[i] = t->keys[i].key;
    names[i] = NULL;
    return td_cr_check_keys(r, g, names);
}

/* A path string member into a fixed buffer. */
static td_status read_path(td_case_reader *r, const config_setting_t *g, const char *key, char *buf)
{
    const char *v;
    td_status st = td_cr_string(r, g, key, "", &v);
    if (st != TD_OK)
        return st;
    if (strlen(v) >= TD_OUTPUT_PATH_SIZE)
        return td_cr_fail(r, config_setting_get_member(g, key), NULL, "path too long (%lu characters, at most %d)",
                          (unsigned long)strlen(v), TD_OUTPUT_PATH_SIZE - 1);
    strcpy(buf, v);
    return TD_OK;
}

/* The default of a number key: its `def`, the record's preset value, or the key it copies. */
static double real_default(const td_cs_key *k, const unsigned char *rec)
{
    double v = k->def;
    if (k->need == TD_CS_PRESET)
        memcpy(&v, rec + k->offset, sizeof v);
    else if (k->need == TD_CS_SAME_AS)
        memcpy(&v, rec + k->def_from, sizeof v);
    return v;
}

static int int_default(const td_cs_key *k, const unsigned char *rec)
{
    int v = (int)k->def;
    if (k->need == TD_CS_PRESET)
        memcpy(&v, rec + k->offset, sizeof v);
    else if (k->need == TD_CS_SAME_AS)
        memcpy(&v, rec + k->def_from, sizeof v);
    return v;
}

/* A string member: the record's value (NULL, or its preset) when absent. */
static td_status read_string(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, unsigned char *rec)
{
    const char *v, *def;
    td_status st;
    memcpy(&def, rec + k->offset, sizeof def);
    v = def;
    st = td_cr_string(r, g, k->key, def, &v);
    if (st == TD_OK && !v && k->need == TD_CS_REQUIRED)
        return td_cr_missing(r, g, k->key, k->what);
    memcpy(rec + k->offset, &v, sizeof v);
    return st;
}

/* A group key: in the parent's record at its offset, or a record of its own. */
static td_status read_group(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, unsigned char *rec)
{
    const config_setting_t *sub;
    td_status st = td_cr_group(r, g, k->key, k->need == TD_CS_REQUIRED ? k->what : NULL, &sub);
    if (st != TD_OK || !sub)
        return st;
    return k->sub->finish ? td_cs_read_record(r, sub, k->sub) : td_cs_read(r, sub, k->sub, rec + k->offset);
}

/* A list of groups: each entry a record of its own. */
static td_status read_list(td_case_reader *r, const config_setting_t *g, const td_cs_key *k)
{
    const config_setting_t *list, *e;
    int i;
    td_status st = td_cr_list(r, g, k->key, &list);
    for (i = 0; st == TD_OK && list && i < config_setting_length(list); i++) {
        st = td_cr_entry(r, list, i, &e);
        if (st == TD_OK)
            st = td_cs_read_record(r, e, k->sub);
    }
    return st;
}

td_status td_cs_elsewhere(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    (void)r;
    (void)g;
    (void)k;
    (void)rec;
    return TD_OK;
}

/* One key by its type. */
static td_status read_key(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, unsigned char *rec)
{
    const char *what = k->need == TD_CS_REQUIRED ? k->what : NULL;
    void *at = rec + k->offset;
    int v = 0, n = 0;
    td_status st;
    if (k->read)
        return k->read(r, g, k, rec);
    switch (k->type) {
    case TD_CS_REAL: return td_cr_real(r, g, k->key, what, real_default(k, rec), k->range, (double *)at);
    case TD_CS_INT: return td_cr_int(r, g, k->key, what, int_default(k, rec), k->lo, k->hi, (int *)at);
    case TD_CS_BOOL: return td_cr_bool(r, g, k->key, int_default(k, rec), (int *)at);
    case TD_CS_ENUM:
        st = td_cr_enum(r, g, k->key, k->names, k->name_count, int_default(k, rec), &v);
        memcpy(at, &v, sizeof v);
        return st;
    case TD_CS_PATH: return read_path(r, g, k->key, (char *)at);
    case TD_CS_REALS:
        st = td_cr_reals(r, g, k->key, (int)k->hi, k->range, (double *)at, &n);
        memcpy(rec + k->count_offset, &n, sizeof n);
        return st;
    case TD_CS_GROUP: return read_group(r, g, k, rec);
    case TD_CS_LIST: return read_list(r, g, k);
    case TD_CS_STRING: return read_string(r, g, k, rec);
    case TD_CS_CUSTOM: return TD_OK; /* read with another key of the group */
    }
    return TD_OK;
}

td_status td_cs_read(td_case_reader *r, const config_setting_t *g, const td_cs_table *t, void *rec)
{
    int i, order, last = 0;
    td_status st = td_cs_check_keys(r, g, t);
    for (i = 0; i < t->count; i++)
        last = t->keys[i].order > last ? t->keys[i].order : last;
    for (order = 0; st == TD_OK && order <= last; order++)
        for (i = 0; st == TD_OK && i < t->count; i++) {
            const td_cs_key *k = &t->keys[i];
            if (k->order != order)
                continue;
            st = read_key(r, g, k, rec);
            if (st == TD_OK && k->check)
                st = k->check(r, g, k, rec);
        }
    if (st == TD_OK && t->finish)
        st = t->finish(r, g, rec);
    return st;
}

td_status td_cs_read_record(td_case_reader *r, const config_setting_t *g, const td_cs_table *t)
{
    cs_record rec;
    if (t->size > sizeof rec.bytes)
        return td_error_set(r->err, TD_ERR_INVALID, "%s: internal: the record of '%s' is too large", r->path_shown,
                            t->name);
    memset(&rec, 0, sizeof rec);
    if (t->preset)
        t->preset(rec.bytes);
    return td_cs_read(r, g, t, rec.bytes);
}
