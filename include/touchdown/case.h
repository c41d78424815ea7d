/*
 * touchdown/case.h - read a case file: one file that describes a whole run (machine, speed,
 * schedule, contact law, solver, output, modal analysis).
 *
 * Case files use the libconfig 1.5 syntax; every key, its unit and its default are listed in
 * docs/case-format.md. Units and DOF conventions: touchdown/dofs.h.
 *
 * Errors are one line, "FILE:LINE: KEY: what is wrong" (KEY is the full path of the setting,
 * e.g. "retainers[1].clearance"); a value set by an override reads
 * "FILE: --set 'KEY=VALUE': KEY: what is wrong". Syntax errors found by libconfig read
 * "FILE:LINE: syntax error".
 *
 * libconfig 1.5 converts numbers with the C library, so a program that changes LC_NUMERIC
 * (setlocale) away from "C" may see "1.5" misread; keep LC_NUMERIC at "C" while loading.
 * td_case_load has no other global effect and may run in several threads at once.
 */
#ifndef TOUCHDOWN_CASE_H
#define TOUCHDOWN_CASE_H

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/limits.h"
#include "touchdown/model.h"
#include "touchdown/options.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct td_case td_case;

/** Largest number of shaft elements a case file may ask for. */
#define TD_CASE_MAX_ELEMENTS 10000
/** Largest case file (or included file) read, bytes. */
#define TD_CASE_MAX_FILE_SIZE (16L * 1024L * 1024L)
/** Deepest @include nesting: a file included by the case file is at depth 1 (libconfig's own
 *  limit, 10, is never reached). */
#define TD_CASE_MAX_INCLUDE_DEPTH 8
/** Most @include files expanded for one case, counting each inclusion (a file included twice
 *  counts twice); bounds a file that includes itself several times. */
#define TD_CASE_MAX_INCLUDES 64
/** Most bytes read for one case: the case file and every inclusion together. */
#define TD_CASE_MAX_TOTAL_SIZE (32L * 1024L * 1024L)
/** Largest number of output samples (sample_rate x end_time) a case may ask for; the bounds on
 *  every run are in touchdown/limits.h. */
#define TD_CASE_MAX_SAMPLES TD_MAX_SAMPLES

/**
 * Read and validate a case file.
 *
 * path         the case file; "@include" paths inside it are relative to its directory.
 * overrides    n_overrides strings "KEY=VALUE" (as given to --set on the command line), applied
 *              in order after parsing and before validation, so they are checked like the file.
 *              KEY is a dotted path; list entries are addressed as name[i] (e.g.
 *              "retainers[0].friction=0.2"). VALUE is a libconfig value (190, 1e-8, true,
 *              "text", [2, 10]); a value that does not parse and does not start with one of
 *              " [ ( { is taken as a bare string (contact.model=penalty). May be NULL when
 *              n_overrides is 0. Borrowed for the duration of the call.
 * out          receives the new case (caller frees with td_case_free); set to NULL on failure.
 * err          may be NULL.
 *
 * Returns TD_OK; TD_ERR_IO if the file (or the path) cannot be read as a regular file;
 * TD_ERR_PARSE for a syntax error, an unknown, missing, mistyped or invalid key, a bad
 * override, or a case past the bounds of touchdown/limits.h; TD_ERR_NOMEM; TD_ERR_INVALID for
 * NULL path/out or n_overrides < 0.
 *
 * The optional `sweep` group is read for its shape only (known keys, types, values or a range),
 * its entries kept as written (td_case_sweep_spec); the grid's rules (a range's points and
 * spacing, log ends, zipped counts, limits) are judged by td_sweep_check_case (touchdown/sweep.h),
 * which sits above the case reader: call it after td_case_load where a bad group must be refused,
 * as the tool does for every command.
 */
TD_API td_status td_case_load(const char *path, const char *const *overrides, int n_overrides, td_case **out,
                              td_error *err);

/** Free a case and set *c to NULL. Accepts NULL and *c == NULL. */
TD_API void td_case_free(td_case **c);

/** The machine (borrowed; lives as long as the case). Already checked with td_model_validate. */
TD_API const td_model *td_case_model(const td_case *c);
/** Contact, solver and start options (borrowed). */
TD_API const td_sim_options *td_case_sim_options(const td_case *c);
/** Output options (borrowed). */
TD_API const td_output_options *td_case_output_options(const td_case *c);
/** Modal-analysis options (borrowed). */
TD_API const td_modal_options *td_case_modal_options(const td_case *c);
/** End time of the run, s. */
TD_API double td_case_end_time(const td_case *c);
/**
 * The case text as read (borrowed, NUL-terminated): the file with every @include expanded in
 * place between "# >>> @include" and "# <<< end of" comment lines, followed by the overrides as
 * comment lines: the line TD_CASE_TEXT_OVERRIDES, then one TD_CASE_TEXT_SET line per override (its
 * text as given), so that a reader of stored results can load the case again as it was run. Meant
 * to be stored with the results (e.g. as an HDF5 attribute).
 */
TD_API const char *td_case_text(const td_case *c);
/** The comment line that opens the overrides at the end of a case text (without its newline). */
#define TD_CASE_TEXT_OVERRIDES "# >>> overrides (--set), applied after parsing"
/** The start of each override's comment line in a case text, the override follows it. */
#define TD_CASE_TEXT_SET "# --set "
/** The path given to td_case_load (borrowed copy). */
TD_API const char *td_case_path(const td_case *c);
/** The file's base name without a ".cfg" extension, e.g. "paper-a" (borrowed). */
TD_API const char *td_case_name(const td_case *c);
/**
 * The files read for the case (borrowed): the case file as given first, then every @include file
 * in the order read, as opened (the include directory joined with the name). *count (if not
 * NULL) receives their number. Lets a caller keep its outputs from overwriting its inputs.
 */
TD_API const char *const *td_case_files(const td_case *c, int *count);
/** The housing history's CSV file (`housing.history.file`) as the case opened it (the case file's
 *  directory joined with a relative name), NULL for a case without one (borrowed). */
TD_API const char *td_case_housing_history_file(const td_case *c);
/** The optional "description" string of the case; "" when absent (borrowed). */
TD_API const char *td_case_description(const td_case *c);

/** How the case file wrote one of its controllers (the `controllers` table), beyond what the
 *  model's realisation says (td_model_get_controller with the same index). */
typedef struct td_case_controller_info {
    int rigid;                        /**< 1: rigid-body coordinates (translation and tilt per plane); 0: bearing */
    double reference_z;               /**< m, the rigid-body reference position (rigid only; else 0) */
    int delay;                        /**< whole samples of computation delay (sampled only; else 0) */
    td_discretisation discretisation; /**< how its s-domain blocks were sampled (sampled only) */
    double prewarp;                   /**< Hz, the Tustin prewarp frequency; 0: none */
    int discretised;                  /**< 1: blocks in s were sampled by `discretisation`; 0: none were
                                       *   (continuous, or every block written in z: then discretisation
                                       *   and prewarp did nothing) */
    int plugin;                       /**< 1: a plug-in controller (`plugin`; td_model_get_plugin gives its spec) */
    const char *where;                /**< a plug-in's "FILE:LINE: controllers[i].plugin.library" (or the
                                       *   --set that gave it), for messages about it; else NULL.
                                       *   Borrowed: valid while the case lives */
} td_case_controller_info;

/** Controller i of the case (0 <= i < td_model_controller_count(td_case_model(c))) into *out;
 *  TD_ERR_INVALID for an i out of range or a NULL argument. */
TD_API td_status td_case_controller(const td_case *c, int i, td_case_controller_info *out);

/**
 * The case's optional `sweep` group (docs/case-format.md), read by every td_case_load (its shape:
 * known keys, the types of their values, a key to sweep) as the specs td_sweep_grid_vary and
 * td_sweep_grid_with take, and judged by their rules not here but by td_sweep_check_case
 * (touchdown/sweep.h): one spec per swept key, in the order of the file. td_case_sweep_specs is
 * their number (0 without a group). td_case_sweep_spec returns spec i (borrowed):
 * "KEY=START:STOP:N[:SPACING]" or "KEY=V1,V2,..."; *with (if not NULL) is 1 when it is zipped
 * onto the axis of the spec before (an entry of `with`), 0 when it starts an axis; *where (if not
 * NULL) is its place in the file, "FILE:LINE: sweep.vary[i]" or "FILE:LINE: sweep.vary[i].with[j]".
 * td_sweep_grid_from_case adds them to a grid.
 */
TD_API int td_case_sweep_specs(const td_case *c);
TD_API const char *td_case_sweep_spec(const td_case *c, int i, int *with, const char **where);

/** One key of the case file as the reader's schema describes it (the key tables of
 *  docs/case-format.md are printed from these by `touchdown info --keys`). */
typedef struct td_case_key_info {
    const char *section;     /**< the table of docs/case-format.md that lists it: "top", "shaft", ... */
    char key[128];           /**< the full key, an entry of a list written []: "retainers[].race.inertia" */
    char type[128];          /**< "number", "integer", "boolean", "string", "group", "list", the names... */
    char range[128];         /**< the values it may take beyond its type ("> 0", "1..5"); "" for any */
    const char *unit;        /**< "" for none */
    char default_value[128]; /**< "required", the value an absent key gives, or what it means */
    const char *doc;         /**< what it is, one line */
} td_case_key_info;

/** The number of keys the case reader knows, groups and lists included (not the keys of the
 *  `sweep` group's entries, which touchdown/sweep.h describes). */
TD_API int td_case_key_count(void);
/** Key i (0 <= i < td_case_key_count()) into *out, each group's keys after the group, in the
 *  order of the reader's tables. TD_ERR_INVALID for an i out of range or a NULL out. */
TD_API td_status td_case_key(int i, td_case_key_info *out, td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_CASE_H */
