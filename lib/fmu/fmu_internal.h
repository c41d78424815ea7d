/*
 * The FMU of a case (touchdown/fmu.h) inside the library: its variables, the settings file of its
 * resources, and what the FMU's binary (fmu/) needs to run one. The one format of resources/ is
 * stated here and written by td_fmu_stage (stage.c) and read by td_fmu_settings_read (settings.c):
 *
 *   resources/case.cfg           the case text as read (td_case_text: every @include expanded in
 *                                place, so the FMU needs none of the case's other files)
 *   resources/touchdown-fmu.cfg  a libconfig file: format (TD_FMU_FORMAT), touchdown (the version
 *                                that staged it), guid, model_identifier, case ("case.cfg"), inputs
 *                                ("none", "current" or "force") and overrides (the td_case_load
 *                                overrides the FMU was staged with, applied again at instantiation,
 *                                then one `controllers[i].plugin.library="plugins/NAME"` per
 *                                plug-in controller: a relative library resolves under the case
 *                                file's directory, resources/; then `housing.history.file=
 *                                "history/NAME"` for a case with a housing history file)
 *   resources/plugins/NAME       each plug-in library the case loads, copied (plugins.c); another
 *                                library of the same file name as plugins/2/NAME, ...
 *   resources/history/NAME       the case's housing history file (CSV), copied (plugins.c)
 *
 * The variables are a pure function of the case's model and the inputs (td_fmu_variables): the
 * stage lists them in modelDescription.xml and the binary rebuilds the same list from the same
 * case, so the two always agree on every value reference.
 */
#ifndef TD_FMU_INTERNAL_H
#define TD_FMU_INTERNAL_H

#include "touchdown/case.h"
#include "touchdown/fmu.h"
#include "util/text.h"

/* The version of the resources' format; the binary refuses any other. */
#define TD_FMU_FORMAT 1
#define TD_FMU_SETTINGS_FILE "touchdown-fmu.cfg"
#define TD_FMU_CASE_FILE "case.cfg"
/* Longest variable name, NUL included. */
#define TD_FMU_NAME_SIZE 64

typedef enum td_fmu_type { TD_FMU_REAL = 0, TD_FMU_INTEGER = 1, TD_FMU_BOOLEAN = 2 } td_fmu_type;

typedef enum td_fmu_causality { TD_FMU_PARAMETER = 0, TD_FMU_INPUT = 1, TD_FMU_OUTPUT = 2 } td_fmu_causality;

/* What a variable is; `index` numbers the AMB, retainer or unbalance, `axis` 0 for x, 1 for y. */
typedef enum td_fmu_quantity {
    TD_FMU_Q_SPEED_PARAM = 0,     /* `speed`, rad/s */
    TD_FMU_Q_UNBALANCE = 1,       /* `unbalances[i].magnitude`, kg m */
    TD_FMU_Q_UNBALANCE_PHASE = 2, /* `unbalances[i].phase`, rad */
    TD_FMU_Q_CLEARANCE = 3,       /* `retainers[i].clearance`, m */
    TD_FMU_Q_FRICTION = 4,        /* `retainers[i].friction` */
    TD_FMU_Q_CURRENT_IN = 5,      /* AMB i's current command on an axis, A (through its amplifier) */
    TD_FMU_Q_FORCE_IN = 6,        /* AMB i's control force on an axis, N (held) */
    TD_FMU_Q_SENSED = 7,          /* AMB i's sensed displacement on an axis, m */
    TD_FMU_Q_AMB_FORCE = 8,       /* AMB i's total force on the rotor on an axis, N */
    TD_FMU_Q_CONTACT_FORCE = 9,   /* retainer i's normal force, N */
    TD_FMU_Q_IN_CONTACT = 10,     /* retainer i in contact */
    TD_FMU_Q_IMPACTS = 11,        /* retainer i's contact onsets so far */
    TD_FMU_Q_ROTOR_SPEED = 12,    /* the rotor speed now, rad/s */
    TD_FMU_Q_EVENTS = 13,         /* events so far (td_sim_stats.events) */
    TD_FMU_Q_HAD_CONTACT = 14,    /* a contact so far: first_contact_time and peak_contact_force hold */
    TD_FMU_Q_FIRST_CONTACT = 15,  /* td_sim_stats.first_contact_time, s (NaN before a contact) */
    TD_FMU_Q_PEAK_FORCE = 16      /* td_sim_stats.peak_normal_force, N */
} td_fmu_quantity;

typedef struct td_fmu_var {
    char name[TD_FMU_NAME_SIZE]; /* a parameter's name is its case key (td_case_load override KEY) */
    unsigned int vr;             /* value reference: the variable's index in the list */
    td_fmu_type type;
    td_fmu_causality causality;
    td_fmu_quantity quantity;
    int index, axis;
    double start; /* parameters (the case's value) and inputs (0) */
    const char *unit;
    const char *description;
} td_fmu_var;

/* The variables of an FMU of `model` with `inputs`, parameters first, then inputs, then outputs,
 * vr = position; *out (free()) and *n. TD_ERR_NOMEM. */
td_status td_fmu_variables(const td_model *model, td_fmu_inputs inputs, td_fmu_var **out, int *n, td_error *err);
/* s as a libconfig string onto t: quoted, with \\, \" and \xNN for control characters (the settings
 * file's strings, resources/touchdown-fmu.cfg). */
void td_fmu_config_string(td_text *t, const char *s);
/* "none", "current", "force"; NULL for another value. */
const char *td_fmu_inputs_name(td_fmu_inputs inputs);
/* The start rule of an FMU with inputs (docs/fmu.md, "The start state with inputs"): it starts at rest,
 * so a case that asks for the orbit (start = "orbit", the default) is TD_ERR_PARSE, naming the case;
 * "auto" becomes rest at instantiation. Checked where the FMU is staged and where it is instantiated. */
td_status td_fmu_check_start(const td_case *c, td_fmu_inputs inputs, td_error *err);

/* The categories of the FMU's log lines (FMI 2.0, 2.2.4 LogCategories; the names those the standard
 * proposes): each line the binary logs is in one of them, and modelDescription.xml lists them all. */
typedef enum td_fmu_log_category {
    TD_FMU_LOG_EVENTS = 0,  /* an event inside a communication step (fmi2OK) */
    TD_FMU_LOG_DISCARD = 1, /* a status the FMU cannot give (fmi2Discard) */
    TD_FMU_LOG_ERROR = 2,   /* a refused call or a failed step (fmi2Error): always logged */
    TD_FMU_LOG_CATEGORIES = 3
} td_fmu_log_category;

typedef struct td_fmu_log_category_def {
    const char *name, *description;
} td_fmu_log_category_def;

extern const td_fmu_log_category_def td_fmu_log_categories[TD_FMU_LOG_CATEGORIES];

/* modelDescription.xml of the FMU of case c into t (util/text.h): FMI 2.0 co-simulation,
 * modelIdentifier id, the guid the settings carry, the variables of td_fmu_variables. */
struct td_text;
td_status td_fmu_model_description(const td_case *c, td_fmu_inputs inputs, const char *id, const char *guid,
                                   struct td_text *t, td_error *err);

/* Longest name of a plug-in library under resources/ ("plugins/[K/]NAME"), NUL included. */
#define TD_FMU_PLUGIN_NAME_SIZE 256

/* The plug-in libraries of a staged case: the overrides that point the FMU at the copies, and the
 * fingerprint of their bytes for the guid ("NAME HASH SIZE" lines). */
typedef struct td_fmu_plugins {
    char **overrides;
    int n;
    td_text fingerprint;
} td_fmu_plugins;

/* Copy each plug-in library case c loads into resources_dir/plugins/, and its housing history file
 * into resources_dir/history/ (plugins.c), and fill *out (freed with td_fmu_plugins_free, also after
 * a failure). TD_ERR_IO naming a file. */
td_status td_fmu_plugins_stage(const td_case *c, const char *resources_dir, td_fmu_plugins *out, td_error *err);
void td_fmu_plugins_free(td_fmu_plugins *p);

/* resources/touchdown-fmu.cfg as read. */
typedef struct td_fmu_settings {
    char guid[64];
    char model_identifier[TD_FMU_NAME_SIZE];
    char *case_path; /* resources/case.cfg joined to the resources directory */
    td_fmu_inputs inputs;
    char **overrides; /* n_overrides strings */
    int n_overrides;
} td_fmu_settings;

/* Read `resources_dir`/touchdown-fmu.cfg into *out (freed with td_fmu_settings_free, also after a
 * failure). TD_ERR_IO for a missing file, TD_ERR_PARSE for a malformed one or another format. */
td_status td_fmu_settings_read(const char *resources_dir, td_fmu_settings *out, td_error *err);
void td_fmu_settings_free(td_fmu_settings *s);

#endif
