/*
 * The case schema as data: one table per group of the case file, each row a key with its type,
 * the place its value goes (an offset into the group's record), its default, its range, its unit
 * and a one-line doc. td_cs_read reads a group by its table; keys with logic of their own
 * (alternative forms, derived values, lists of numbers checked against the shaft) name a custom
 * reader in their row, so that every key is listed, and documented, in one row
 * (td_case_key_info walks the tables for docs/case-format.md). Cross-part rules are the model's
 * (td_model_add_*, td_model_validate); a table checks only what is about the file.
 */
#ifndef TD_CASE_SCHEMA_H
#define TD_CASE_SCHEMA_H

#include "case/case_internal.h"

#include <stddef.h>

typedef enum td_cs_type {
    TD_CS_REAL,   /* double, checked against `range` */
    TD_CS_INT,    /* int in [lo, hi] */
    TD_CS_BOOL,   /* int, 0 or 1 */
    TD_CS_ENUM,   /* an enum (int-sized): the index of the string among `names` */
    TD_CS_PATH,   /* char[TD_OUTPUT_PATH_SIZE] */
    TD_CS_STRING, /* const char *: the setting's own text, valid while the file is read (a NULL default) */
    TD_CS_REALS,  /* double[hi] with its count (int) at `count_offset` */
    TD_CS_GROUP,  /* a group read by table `sub` (into the record at offset, or its own: sub->finish) */
    TD_CS_LIST,   /* a list of groups, each read by table `sub` into a record of its own */
    TD_CS_CUSTOM  /* read by `read` alone (doc_type says what it takes) */
} td_cs_type;

/* What an absent key gives. */
typedef enum td_cs_need {
    TD_CS_DEFAULT = 0, /* `def` (REAL, INT, BOOL, ENUM index); a group or list: nothing */
    TD_CS_REQUIRED,    /* "missing required key (what)" */
    TD_CS_PRESET,      /* the record's value as the table's preset set it (util/options.c) */
    TD_CS_SAME_AS      /* the value of the key at `def_from`, read before it */
} td_cs_need;

typedef struct td_cs_key td_cs_key;
typedef struct td_cs_table td_cs_table;

/* A custom reader, or a check run after the key is read (present or not): g is the group that
 * holds the key, rec the group's record. */
typedef td_status (*td_cs_read_fn)(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec);
/* After every key of a group with a record of its own: hand the record to the model. */
typedef td_status (*td_cs_finish_fn)(td_case_reader *r, const config_setting_t *g, void *rec);

struct td_cs_key {
    const char *key;
    td_cs_type type;
    size_t offset; /* of the value in the group's record */
    td_cs_need need;
    double def;          /* TD_CS_DEFAULT */
    size_t def_from;     /* TD_CS_SAME_AS: offset of the key it copies */
    td_cr_range range;   /* REAL, REALS */
    td_cr_range rule;    /* the range the model holds the value to (touchdown/model.h), for the docs */
    long lo, hi;         /* INT: the range; REALS: hi = most entries */
    size_t count_offset; /* REALS */
    const char *const *names;
    int name_count;          /* ENUM */
    const td_cs_table *sub;  /* GROUP, LIST */
    td_cs_read_fn read;      /* replaces the generic read; NULL on CUSTOM: read with another key */
    td_cs_read_fn check;     /* a rule tying the key to keys read before it (after the read) */
    int order;               /* keys are read by ascending order, then table order */
    const char *what;        /* TD_CS_REQUIRED: said by "missing required key (what)" */
    const char *unit;        /* NULL: none */
    const char *doc_type;    /* the type as the docs say it, when not the generated one */
    const char *doc_range;   /* the range (a model rule, a form), when not the generated one */
    const char *doc_default; /* the default as the docs say it, when not the generated one ("%s" in
                              * it: where the generated one goes, "%s (none)") */
    const char *doc;         /* one line */
};

struct td_cs_table {
    const char *name;    /* doc prefix of its keys: "solver", "retainers[]", "retainers[].race" */
    const char *section; /* the docs' table it is listed in; NULL: its parent's */
    const td_cs_key *keys;
    int count;
    size_t size;               /* of the record */
    void (*preset)(void *rec); /* sets TD_CS_PRESET defaults (and a record's starting values) */
    td_cs_finish_fn finish;    /* non-NULL: the group has a record of its own, handed over here */
};

#define TD_CS_COUNT(keys) ((int)(sizeof(keys) / sizeof((keys)[0])))

/* The reader of a key read with another key of its group (a form, a pair): reads nothing. */
td_status td_cs_elsewhere(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec);

/* Read group g (already known to be a group) by table t into rec: unknown keys, then each key in
 * order, then t->finish. */
td_status td_cs_read(td_case_reader *r, const config_setting_t *g, const td_cs_table *t, void *rec);
/* Read group g into a record of its own (zeroed, preset), then t->finish. */
td_status td_cs_read_record(td_case_reader *r, const config_setting_t *g, const td_cs_table *t);
/* Reject members of g that t does not list ("unknown key", with the keys in table order). */
td_status td_cs_check_keys(td_case_reader *r, const config_setting_t *g, const td_cs_table *t);

/* The tables (case_options.c, case_parts.c, case_shaft.c). td_cs_root is the case file's top level: its groups and
 * lists name the others. */
extern const td_cs_table td_cs_root;

/* The groups read by case_options.c that the root table names. */
extern const td_cs_table td_cs_contact, td_cs_solver, td_cs_output, td_cs_modal, td_cs_gravity, td_cs_reduction;
/* The lists and groups of case_parts.c. */
extern const td_cs_table td_cs_discs, td_cs_point_masses, td_cs_ambs, td_cs_bearings, td_cs_retainers, td_cs_unbalances,
    td_cs_schedule, td_cs_speed_ramp, td_cs_spin;
/* The shaft (case_shaft.c). */
extern const td_cs_table td_cs_shaft;
/* The sweep (case_vary.c). */
extern const td_cs_table td_cs_sweep;
/* The controllers (case_control.c), and the table of one block of a controller's law (case_blocks.c). */
extern const td_cs_table td_cs_controllers, td_cs_block;
/* A controller's `plugin` group as read (case_plugin.c): the library as written, its `parameters`
 * group (NULL when absent), each member a finite number. */
#define TD_CR_PLUGIN_MAX_PARAMETERS 64
typedef struct td_cr_plugin {
    const char *library;
    const config_setting_t *parameters;
} td_cr_plugin;
extern const td_cs_table td_cs_plugin;
/* Add the plug-in p of controller entry g to the model: `spec` gives its name, rate, delay and
 * axes; the library (under the case file's directory unless absolute) and parameters are p's. A
 * model error is located at the key it is about (`plugin.library` for the library's own). */
td_status td_cr_add_plugin(td_case_reader *r, const config_setting_t *g, const td_cr_plugin *p,
                           const td_plugin_spec *spec);

/* The recovery supervisor (case_recovery.c), read after the controllers it names. */
extern const td_cs_table td_cs_recovery;

/* The assessment (case_assess.c): a retainer's `bearing` group and the top-level `limits`.
 * td_cr_set_retainer_bearing hands the bearing b read from retainer entry g to the model, for
 * the retainer just added, when g has a `bearing` group. */
extern const td_cs_table td_cs_retainer_bearing, td_cs_limits;
td_status td_cr_set_retainer_bearing(td_case_reader *r, const config_setting_t *g, const td_retainer_bearing *b);

/* Block entry e of a law (a group with exactly one member: gain, pid, leadlag, lowpass, notch, tf,
 * zpk or ss) as a new SISO controller (*out, the caller frees it). A block in z (domain = "z")
 * needs sample_rate > 0 (the controller's, Hz) and is sampled at it (*sampled 1); every other
 * block is continuous (*sampled 0). */
td_status td_cr_read_block(td_case_reader *r, const config_setting_t *e, double sample_rate, td_controller **out,
                           int *sampled);

/* housing motion (case_housing.c): the top-level `housing` group */
extern const td_cs_table td_cs_housing;
/* housing body */
/* The compliant housing, `housing.body` (case_housing_body.c). */
extern const td_cs_table td_cs_housing_body;

/* projective leap (case_leap.c): the `leap` group's table, and the root row's check (a free spin, a
 * start after the schedule's last change). */
extern const td_cs_table td_cs_leap;
td_status td_cr_check_leap(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec);

#endif
