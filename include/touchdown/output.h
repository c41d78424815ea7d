/*
 * touchdown/output.h - result files (HDF5 or CSV) written sample by sample.
 *
 * A td_writer never sees the solver: the caller hands it one sample at a time (time, the chosen
 * nodes' x/y displacements, every retainer's contact state, every AMB's force), the events, and
 * named attributes (case text, solver statistics, summary numbers). docs/output-format.md lists
 * every dataset, column, unit and attribute. Units and signs: touchdown/dofs.h.
 *
 * Completeness rule: everything is written to a temporary file PATH.XXXXXX.partial (same
 * directory; XXXXXX six letters or digits, the file created with O_CREAT|O_EXCL so that it is
 * never another writer's) and renamed to PATH only by td_writer_close, after the attributes and,
 * last of all, the completeness flag ("complete" attribute 1/0 in HDF5; final line "# complete"
 * or "# incomplete: REASON" in CSV) have been written and flushed to disk. A file at PATH
 * therefore always carries a flag, and says "complete" only if the writer was closed as complete
 * with every write successful. Two writers on one PATH each rename only their own file: the last
 * to close wins, whole. td_writer_open removes a stale file at PATH once the new temporary file
 * has been created, so an old result is never mistaken for the new one; a failed open leaves
 * nothing behind.
 */
#ifndef TOUCHDOWN_OUTPUT_H
#define TOUCHDOWN_OUTPUT_H

#include <stddef.h>

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/options.h"
#include "touchdown/records.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct td_writer td_writer;

/** File format. */
typedef enum td_writer_kind {
    TD_WRITER_HDF5 = 0, /**< one HDF5 file, extendible chunked datasets */
    TD_WRITER_CSV = 1   /**< PATH (samples) and a sibling events file (td_writer_events_path; omit_events: none) */
} td_writer_kind;

/** What one sample holds, and how the file stores it. Set every field (a struct filled field by
 *  field must set compression too: 0 for the uncompressed files of earlier versions). */
typedef struct td_output_layout {
    int node_count;     /**< nodes whose x, y displacements are written, >= 0 */
    const int *nodes;   /**< node numbers, node_count of them (copied by td_writer_open) */
    int retainer_count; /**< retainers, >= 0 */
    int amb_count;      /**< AMBs, >= 0 */
    int compression;    /**< HDF5 only: deflate level 0 (none) .. 9, with the shuffle filter; CSV ignores it */
    int race_fields;    /**< nonzero: also each retainer's race centre x, y, race speed and rolling flag
                         *   (models with race bodies or stick retainers, touchdown/model.h) */
    int speed_field;    /**< nonzero: also the rotor speed (models whose speed varies: a ramp or a free spin) */
    int whirl_field;    /**< nonzero: also each retainer's whirl rate (models with race fields or a varying
                         *   speed: the paper's cases keep the layout they always had) */
    int switch_fields;  /**< nonzero: the events also carry `controller` and `sensed_radius`, and the event kinds
                         *   include controller_switch (models with a recovery supervisor, touchdown/model.h).
                         *   Last, so that initialisers written before it leave it 0 */
    /* heat */
    int thermal_fields; /**< nonzero: also each retainer's race and housing temperature rise (models where some
                         *   retainer has a thermal network; NaN for the others). Last, as switch_fields */
    /* housing motion */
    int housing_fields; /**< nonzero: also the housing's motion (/housing, (N, 2) each) and the nodes' absolute
                         *   displacement, given by td_writer_housing (models with housing motion or a housing
                         *   body) */
    /* housing body */
    int housing_body_fields; /**< nonzero (only with housing_fields): also the housing body's displacement and tilt
                              *   (/housing/body_displacement, /housing/body_tilt; models with a housing body). Last */
    /* long runs */
    int window_fields; /**< nonzero: the writer also takes window summaries (td_writer_window): /windows in HDF5, a
                        *   third CSV file (td_writer_windows_path); 0: no window CSV file (a stale one at
                        *   td_writer_windows_path is still removed) */
    int omit_events;   /**< nonzero: the file has no event table: no /events and /event in HDF5, no CSV events file
                        *   (a stale one at td_writer_events_path is still removed), and td_writer_event is refused.
                        *   Its summary attributes still count the events (output.events = false). Last */
} td_output_layout;

/**
 * Create a writer on a new PATH.XXXXXX.partial. `layout` is copied. On failure nothing is left on
 * disk and *out is NULL. Errors: TD_ERR_INVALID (NULL/empty path, bad layout, compression outside
 * 0..9, path too long),
 * TD_ERR_IO (the file cannot be created), TD_ERR_NOMEM.
 */
TD_API td_status td_writer_open(td_writer_kind kind, const char *path, const td_output_layout *layout, td_writer **out,
                                td_error *err);

/**
 * Append one sample at time `t` (s) with the rotor speed `speed` (rad/s; written when the layout
 * has speed_field). `node_xy`: 2 node_count values x0, y0, x1, y1, ... (m);
 * `ret`: retainer_count states; `amb_f`: 2 amb_count values Fx0, Fy0, ... (N). Arrays may be
 * NULL only when their count is 0. Samples need not be strictly increasing in time (an event
 * that falls on a grid time gives two samples at that time). After a failed write the writer
 * only accepts td_writer_close (which then marks the file incomplete).
 */
TD_API td_status td_writer_sample(td_writer *w, double t, double speed, const double *node_xy,
                                  const td_retainer_state *ret, const double *amb_f, td_error *err);

/** The number of values of a housing motion sample (td_writer_housing). */
#define TD_WRITER_HOUSING_VALUES 10
/** housing body: the number of values a layout with housing_body_fields adds to it. */
#define TD_WRITER_HOUSING_BODY_VALUES 4

/**
 * housing motion: the housing's part of the next td_writer_sample of a writer whose layout has
 * housing_fields. `motion`: TD_WRITER_HOUSING_VALUES values, the housing's acceleration x, y (m/s^2),
 * velocity x, y (m/s), displacement x, y (m), rotation rate about x, y (rad/s) and rotation angle about
 * x, y (rad), then, when the layout has housing_body_fields, TD_WRITER_HOUSING_BODY_VALUES more: the housing
 * body's centre x, y relative to the base (m) and its tilts theta, phi (rad); `node_abs_xy`: 2 node_count
 * values, the nodes' absolute displacement x0, y0, ... (m; may be NULL when node_count is 0). Copied; a sample
 * without it holds NaN there.
 */
TD_API td_status td_writer_housing(td_writer *w, const double *motion, const double *node_abs_xy, td_error *err);

/**
 * Append one event. `sample` is the row (from 0) of the sample that shows the state right after
 * the event, normally td_writer_sample_count(w) - 1 just after writing it; -1 if there is none.
 * It must be -1 or an existing row (else TD_ERR_INVALID); a writer opened with omit_events takes
 * no event (TD_ERR_INVALID). The run loop takes one sample per event
 * instant, so rows not referenced by any event form the uniform grid.
 */
TD_API td_status td_writer_event(td_writer *w, const td_event *ev, long sample, td_error *err);

/**
 * Named attributes, written at close (root attributes in HDF5, "# name = value" lines at the end
 * of the CSV). Names: 1..63 characters of [A-Za-z0-9_.-]; "complete" and "incomplete_reason" are
 * the writer's own. Setting a name again replaces its value. Values are copied.
 */
TD_API td_status td_writer_set_string(td_writer *w, const char *name, const char *value, td_error *err);
TD_API td_status td_writer_set_double(td_writer *w, const char *name, double value, td_error *err);
TD_API td_status td_writer_set_long(td_writer *w, const char *name, long value, td_error *err);
/** Arrays of n >= 1 values (1-D attributes in HDF5, space separated in CSV). */
TD_API td_status td_writer_set_doubles(td_writer *w, const char *name, const double *values, int n, td_error *err);
TD_API td_status td_writer_set_longs(td_writer *w, const char *name, const long *values, int n, td_error *err);
/** Every field of `stats` as an attribute named after the field (steps, residual_evals, ...,
 *  worst_drift, wall_time), plus library_version = td_version(). */
TD_API td_status td_writer_set_stats(td_writer *w, const td_sim_stats *stats, td_error *err);

/** Number of samples and events written so far. */
TD_API long td_writer_sample_count(const td_writer *w);
TD_API long td_writer_event_count(const td_writer *w);

/**
 * Finish the file and free the writer (*w set to NULL; NULL or *w == NULL accepted: TD_OK).
 * Writes the buffered samples, the attributes, library_version, then the completeness flag:
 * complete = 1 only if `complete` is nonzero and every earlier write succeeded; else complete = 0
 * with `reason` (NULL: "unspecified") as incomplete_reason. Then flushes to disk and renames
 * the temporary file to PATH. Returns TD_OK when the file is at PATH with its flag (even if the flag
 * is 0), TD_ERR_IO when it could not be finished: then the temporary file is removed and no file
 * is at PATH.
 */
TD_API td_status td_writer_close(td_writer **w, int complete, const char *reason, td_error *err);

/** Abandon a writer: remove its temporary file(s), leave nothing at PATH, free. Accepts NULL. */
TD_API void td_writer_discard(td_writer **w);

/**
 * Path of the CSV events file that goes with the samples file `csv_path`: a trailing ".csv" is
 * replaced by ".events.csv", otherwise ".events.csv" is appended. Returns the length it needs
 * (like snprintf); the result is truncated but NUL-terminated when n is too small.
 */
TD_API int td_writer_events_path(const char *csv_path, char *buf, size_t n);

/**
 * Check the output paths of `out` before a run, so that nothing is computed that cannot be
 * written and no input is overwritten. TD_ERR_INVALID, naming the path, when:
 *  - two of the outputs (HDF5, CSV, the CSV events file, the CSV window file) are the same file;
 *    the CSV's companions are checked whether or not the run writes them (td_output_options
 *    omit_events, window), as a stale file at either is removed;
 *  - an output is one of the `n_inputs` paths `inputs` (the case file first, then its @include
 *    files: td_case_files);
 *  - an output's name ends in ".partial" (reserved for temporary files);
 *  - an output exists and is not a regular file, or names a directory;
 *  - an output's directory does not exist or is not writable.
 * Same file: equal device and inode when both exist; when neither exists, the same base name in
 * the same directory (compared by device and inode). Empty paths are skipped. TD_ERR_NOMEM.
 */
TD_API td_status td_output_check_paths(const td_output_options *out, const char *const *inputs, int n_inputs,
                                       td_error *err);

/** The most files one run's output options name (td_output_files). */
#define TD_OUTPUT_FILES 4

/** A file a run writes, or removes when stale, and what it is. */
typedef struct td_output_file {
    char path[TD_OUTPUT_PATH_SIZE + 16]; /**< room for a CSV path and its longest companion's suffix */
    const char *what;                    /**< "HDF5 output", "CSV output", "CSV events output", "CSV window output" */
} td_output_file;

/**
 * The files of a run with the output options `out`, the one list td_output_check_paths checks: the
 * HDF5 file, and with a CSV path the CSV file and its companions, the events file
 * (td_writer_events_path) and the window file (td_writer_windows_path), whether or not the run
 * writes them (a stale one is removed). Empty paths are skipped. For a caller whose own files must
 * not be a run's (a sweep's table and its points' files). Returns their count (at most
 * TD_OUTPUT_FILES), or -1 when `out` is NULL or a path is not NUL-terminated within its array.
 */
TD_API int td_output_files(const td_output_options *out, td_output_file files[TD_OUTPUT_FILES]);

/**
 * 1 if the paths a and b name one file by the rule of td_output_check_paths (equal device and
 * inode when both exist; when neither exists, the same base name in the same directory), else 0
 * (also for NULL or empty paths). For a caller's own outputs beyond one run's, e.g. a sweep's
 * table and its points' files.
 */
TD_API int td_output_same_file(const char *a, const char *b);

/** Lower-case name of an event kind ("contact_onset", "release", ...); "unknown" otherwise. */
TD_API const char *td_event_kind_name(td_event_kind kind);

/* ---- long runs: window summaries (docs/output-format.md, "Window summaries") ---------------- */

/** One window's summary: the run from t_start to t_end condensed. The per-retainer arrays hold
 *  the layout's retainer_count values each. */
typedef struct td_window_summary {
    double t_start, t_end;           /**< s */
    double speed;                    /**< rad/s, the rotor's at t_end */
    double energy_kinetic;           /**< J at t_end (td_energy.kinetic); TD_UNDEFINED without the energy account */
    double energy_residual;          /**< J at t_end (td_energy.residual); TD_UNDEFINED without the energy account */
    const long *contacts;            /**< contact onsets in the window (the events contact_onset and penalty_enter) */
    const double *contact_fraction;  /**< time in contact / (t_end - t_start) */
    const double *peak_normal_force; /**< N, the largest normal force seen in the window: at its samples, its
                                      *   events (their force and the peak of a contact that ended) and the run's
                                      *   peak where that rose in the window; 0 without contact */
    const double *friction_work;     /**< J, the sliding friction's heat in the window */
    const double *race_temperature;  /**< K above the ambient at t_end; TD_UNDEFINED without retainers[].thermal */
} td_window_summary;

/**
 * Append one window summary (a writer whose layout has window_fields; else TD_ERR_INVALID).
 * Written as it comes (HDF5 in chunks), so a long run holds none of them in memory.
 */
TD_API td_status td_writer_window(td_writer *w, const td_window_summary *win, td_error *err);

/** Path of the CSV window file that goes with `csv_path`: as td_writer_events_path with
 *  ".windows.csv". */
TD_API int td_writer_windows_path(const char *csv_path, char *buf, size_t n);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_OUTPUT_H */
