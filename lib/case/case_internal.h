/*
 * Case-file reader internals: the td_case record, the reader state shared by the section
 * readers, and the typed getters that turn libconfig settings into checked values with
 * "FILE:LINE: KEY: what is wrong" errors.
 *
 * The files of lib/case in layers, each calling only the layers below it (no call cycle between
 * files; tests/style/call_cycles.py):
 *   1. case_message.c   where a setting is, its key, user text made printable, the error format
 *   2. case_value.c     typed getters of libconfig settings
 *   3. case_text.c      reading files, @include expanded, wrapped literals, the files read
 *   4. case_override.c  "KEY=VALUE" grafted into the parsed case (the value bounded by 3's scan)
 *   5. case_site.c      model errors turned back into the settings they came from
 *   6. case_schema.c    the generic reader of a group by its table (case_schema.h)
 *   7. the tables: case_vary.c, case_shaft.c, case_parts.c, case_blocks.c (a controller's blocks),
 *      case_plugin.c (a controller's plug-in), case_control.c (the controllers, built of those
 *      blocks or a plug-in), then case_options.c (the root table, which names the others)
 *   8. case_keys.c      every key of the tables, for the docs
 *   9. case.c           td_case_load and the rest of touchdown/case.h
 * A function two layers need lives in the lower one.
 */
#ifndef TD_CASE_INTERNAL_H
#define TD_CASE_INTERNAL_H

#include <libconfig.h>
#include <stddef.h>

#include "case/case_message.h"     /* layer 1's helpers that need no reader, also lib/sweep's */
#include "case/case_sweep_specs.h" /* the `sweep` group as read, as lib/sweep sees it */
#include "touchdown/case.h"
#include "util/text.h"

struct td_case {
    td_model *model;
    td_sim_options sim;
    td_output_options output;
    td_modal_options modal;
    double end_time;
    char *text;        /* expanded case text + overrides as comments */
    char *path;        /* as given */
    char *name;        /* base name without .cfg */
    char *description; /* "" when absent */
    char **files;      /* the case file and every @include file read, as opened (td_case_files) */
    int file_count;
    struct td_cr_sweep_spec *sweep; /* the `sweep` group as specs, as read (td_cr_sweep_spec) */
    int sweep_count;
    td_case_controller_info *controllers; /* per controller of the model, as the file wrote it */
    int controller_count;
    /* housing motion */
    char *history_file; /* the housing history's CSV file as read (td_case_housing_history_file); NULL: none */
};

/* A decimal or hex integer literal that libconfig 1.5 silently wraps to 32 bits (it has no
 * overflow check); found by td_cr_scan_text, reported against the setting on that line. */
typedef struct td_cr_wrap_site {
    char *file; /* file name as libconfig records it (the @include string); NULL: main file */
    int line;
    int ordinal; /* numbers before it on its line: picks its setting among several on one line */
    char literal[40];
} td_cr_wrap_site;

/* The shape of the case text, counted by td_cr_expand before libconfig sees it: libconfig 1.5
 * compares every new key with each earlier key of its group (quadratic in the keys of a group) and
 * does not check its allocations (a crash when memory runs out), so what it is handed is bounded
 * up front by TD_CASE_MAX_GROUP_KEYS, TD_CASE_MAX_SETTINGS and TD_CASE_MAX_NESTING. */
typedef struct td_cr_shape {
    int depth;                         /* brackets open */
    char open[TD_CASE_MAX_NESTING];    /* '{', '(' or '[' of each open bracket */
    int keys[TD_CASE_MAX_NESTING + 1]; /* keys so far of the group at each depth (0: the root) */
    long settings;                     /* settings libconfig will create: keys and list/array entries */
    unsigned long long name_compares;  /* key comparisons libconfig 1.5 will make finding duplicates */
} td_cr_shape;

typedef struct td_case_reader {
    config_t cfg;
    const char *path; /* the case file as given */
    char *path_shown; /* the path as quoted in messages (td_cr_printable) */
    char *dir;        /* include directory: the case file's directory, "." when none */
    char *dir_shown;  /* the include directory as quoted in messages */
    int has_dir;      /* path names a directory: included files are shown as dir/name */
    td_error *err;
    td_case *c;
    int nodes;  /* shaft node count as written in the case, once the shaft is read */
    int refine; /* shaft.refine: every element split this many times after reading */
    td_cr_wrap_site *wraps;
    int wrap_count, wrap_cap;
    int includes; /* @include files expanded so far (limit TD_CASE_MAX_INCLUDES) */
    size_t bytes; /* bytes read so far, main file and includes (limit TD_CASE_MAX_TOTAL_SIZE) */
    td_cr_shape shape;
    const config_setting_t *overrides; /* the case's own "overrides" list, or NULL: its strings are the
                                        * hooks of what they graft (td_cr_where names the entry) */
    const config_setting_t *ov_entry;  /* the entry being applied, NULL for a --set */
    const char *const *sets;           /* td_case_load's overrides (n_sets): an error on a value one of */
    int n_sets;                        /* them wrote names it (td_cr_blame_override) */
} td_case_reader;

/* Range a real value must lie in. */
typedef enum td_cr_range {
    TD_CR_FINITE = 0,      /* any finite value */
    TD_CR_POSITIVE = 1,    /* > 0 */
    TD_CR_NONNEGATIVE = 2, /* >= 0 */
    TD_CR_FRACTION = 3,    /* [0, 1] */
    TD_CR_OPEN_UNIT = 4    /* (0, 1) */
} td_cr_range;

/* ---- 1. locations and messages (case_message.c; the rest: case_message.h) -------------- */
/* How a file libconfig recorded (NULL: main) is shown in messages. */
void td_cr_file_shown(const td_case_reader *r, const char *file, char *buf, size_t n);
/* Full key of a setting, e.g. "retainers[1].clearance"; "" for the root. */
void td_cr_key(const config_setting_t *s, char *buf, size_t n);
/* "FILE:LINE" or "FILE: --set 'K=V'" of a setting. */
void td_cr_where(const td_case_reader *r, const config_setting_t *s, char *buf, size_t n);
/* The setting the shaft's node count was read from: shaft.nodes, else shaft.elements (else the
 * shaft, or NULL): a node index is checked against it. */
const config_setting_t *td_cr_shaft_nodes(const td_case_reader *r);
/* td_cr_where of a list whose entries (or each entry's `member`, when not NULL) a rule counts or
 * looks up, or of the first of them an override wrote: where the user wrote what the rule saw. */
void td_cr_where_list(const td_case_reader *r, const config_setting_t *list, const char *member, char *buf, size_t n);
/* When `ov` is one of td_case_load's overrides, r->err's site names it: {"override", its index,
 * NULL} (touchdown/error.h); otherwise (NULL, an entry of the case's own list) nothing changes. */
void td_cr_blame_override(const td_case_reader *r, const char *ov);
/* Fail with "WHERE: KEY[.sub]: message", the message at r->err->reason and the override that wrote
 * s, if any, in r->err->site (td_cr_blame_override); returns TD_ERR_PARSE. `sub` may be NULL. */
td_status td_cr_fail(td_case_reader *r, const config_setting_t *s, const char *sub, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* td_cr_fail at s for a rule that compares s with the setting `other` (NULL: a default), adding
 * "; see OTHER at WHERE": where the user wrote the other value, a line or a --set. */
td_status td_cr_fail_vs(td_case_reader *r, const config_setting_t *s, const config_setting_t *other, const char *fmt,
                        ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* ---- 2. typed getters (case_value.c) ---------------------------------------------------- */
/* A quantity derived from setting s (`what`, e.g. "the time constant tau = 1 / (2 pi bandwidth)"):
 * fail naming s when it overflowed to infinity or is NaN. */
td_status td_cr_derived(td_case_reader *r, const config_setting_t *s, double value, const char *what);
/* Reject members of group g whose names are not in the NULL-terminated `allowed`. */
td_status td_cr_check_keys(td_case_reader *r, const config_setting_t *g, const char *const *allowed);
/* 1 if group g has member `key`. */
int td_cr_has(const config_setting_t *g, const char *key);
td_status td_cr_missing(td_case_reader *r, const config_setting_t *g, const char *key, const char *what);

td_status td_cr_value_real(td_case_reader *r, const config_setting_t *s, td_cr_range range, double *out);
td_status td_cr_value_int(td_case_reader *r, const config_setting_t *s, long lo, long hi, int *out);
/* Optional/required members. `what` describes the key for "missing" messages (NULL: optional,
 * then `def` is stored when absent). */
td_status td_cr_real(td_case_reader *r, const config_setting_t *g, const char *key, const char *what, double def,
                     td_cr_range range, double *out);
td_status td_cr_int(td_case_reader *r, const config_setting_t *g, const char *key, const char *what, int def, long lo,
                    long hi, int *out);
/* The range of a node number the reader takes: any int; whether the shaft has that node is the
 * model's rule (td_model_add_*, td_model_validate), stated once there. */
#define TD_CR_ANY_INT_LO (-2147483647L)
#define TD_CR_ANY_INT_HI 2147483647L
td_status td_cr_bool(td_case_reader *r, const config_setting_t *g, const char *key, int def, int *out);
td_status td_cr_string(td_case_reader *r, const config_setting_t *g, const char *key, const char *def,
                       const char **out);
/* A string member that must be one of `names` (n of them); *out is its index. */
td_status td_cr_enum(td_case_reader *r, const config_setting_t *g, const char *key, const char *const *names, int n,
                     int def, int *out);
/* An optional group member: *out is NULL when absent. */
td_status td_cr_group(td_case_reader *r, const config_setting_t *g, const char *key, const char *what,
                      const config_setting_t **out);
/* An optional list of groups "( {...}, ... )": *out is NULL when absent, entries checked by td_cr_entry. */
td_status td_cr_list(td_case_reader *r, const config_setting_t *g, const char *key, const config_setting_t **out);
td_status td_cr_entry(td_case_reader *r, const config_setting_t *list, int i, const config_setting_t **out);
/* An optional array or list of at most `max` numbers (or integers) into out[]; *n = count (0 when absent). */
td_status td_cr_reals(td_case_reader *r, const config_setting_t *g, const char *key, int max, td_cr_range range,
                      double *out, int *n);
td_status td_cr_ints(td_case_reader *r, const config_setting_t *g, const char *key, int max, long lo, long hi, int *out,
                     int *n);

/* ---- 3. text (case_text.c) ------------------------------------------------------------- */
/* Read a regular file of at most TD_CASE_MAX_FILE_SIZE bytes, rejecting binary data and CR-only line
 * endings. `what` says what it is ("case file", "history file"), `shown` names it in messages.
 * TD_ERR_IO if unreadable, TD_ERR_PARSE if binary. */
td_status td_cr_read_file(const char *what, const char *shown, const char *path, char **text, td_error *err);
/* Add `path` to the case's list of files read (td_case_files); TD_ERR_NOMEM on failure. */
td_status td_cr_record_file(td_case *c, const char *path);
/* Append `text` (the file libconfig calls `file`, NULL for the main file) to `out` with every
 * @include expanded in place, and record integer literals libconfig would wrap. */
td_status td_cr_expand(td_case_reader *r, const char *text, const char *file, int depth, td_text *out);
/* Scan one value string (an override) for literals libconfig would wrap; returns 1 if found. */
int td_cr_value_wraps(const char *text, char *literal, size_t n);

/* ---- 4. overrides (case_override.c) ------------------------------------------------------ */
/* Apply one "KEY=VALUE" string to the parsed configuration. */
td_status td_cr_apply_override(td_case_reader *r, const char *ov);
/* The case's own list `overrides = ( "KEY=VALUE", ... )`, applied in order before the --set ones. */
td_status td_cr_apply_file_overrides(td_case_reader *r);

/* ---- 5. model errors located (case_site.c) ----------------------------------------------- */
/* Re-word an error of a td_model_* call made for entry (or group) g with the location of the
 * setting it came from: the member of g named by the error's field (touchdown/error.h), else g. */
td_status td_cr_model_fail(td_case_reader *r, const config_setting_t *g, td_status st, const td_error *merr);
/* Re-word an error of td_model_validate on the model read from the case: the part, index and
 * field it names become the setting they were read from, a part it compared against is named
 * with its location; "FILE: message" when it names no part of the case. */
td_status td_cr_validate_fail(td_case_reader *r, const td_error *merr);

/* ---- 7. group tables: what other files use (the rest: case_schema.h) -------------------- */
/* The names of td_contact_damping, in its order (case_parts.c: the run's and the retainers'
 * contact groups). */
#define TD_CR_DAMPING_NAMES 3
extern const char *const td_cr_damping_names[TD_CR_DAMPING_NAMES];

/* The required `shaft` group by its table (case_shaft.c), with the element arrays it needs. */
td_status td_cr_read_shaft(td_case_reader *r, const config_setting_t *root);
/* Free the case's sweep specs. (What lib/sweep reads of them: case_sweep_specs.h.) */
void td_cr_free_sweep(td_case *c);

#endif
