/*
 * touchdown/modal_output.h - result files of a modal analysis (touchdown/modal.h): one CSV file
 * with sections, or one HDF5 file with a group per part. docs/output-format.md lists the layout.
 *
 * Completeness rule (the one of touchdown/output.h): each writer writes a temporary file
 * PATH.XXXXXX.partial in the same directory (created with O_CREAT|O_EXCL, so never another
 * writer's file), checks every write, flushes it to disk and renames it to PATH only when every
 * part is written. On failure the temporary file is removed and the error names it and the
 * cause; an earlier file at PATH is left untouched. A file at PATH is therefore always whole,
 * and needs no completeness flag: a modal analysis either finishes or writes nothing.
 */
#ifndef TOUCHDOWN_MODAL_OUTPUT_H
#define TOUCHDOWN_MODAL_OUTPUT_H

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/modal.h"
#include "touchdown/model.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Results to write; any pointer may be NULL (that part is skipped). `modes` is written with all
 * its oscillatory modes, its real eigenvalues and mode shapes; `harmonics` is an array of
 * n_harmonics responses.
 */
typedef struct td_modal_results {
    const td_modal *modes;
    const td_campbell *campbell;
    const td_critical_speed *critical;
    int n_critical;
    const td_harmonic *const *harmonics;
    int n_harmonics;
    const td_model *model; /**< optional: node positions (/modes/node_z) and bearing nodes for plots */
    const char *case_text; /**< optional: the case file text, written as the case_text attribute */
    const td_loop *loop;   /**< optional: the loop analysis (/loop; CSV sections loop, sensitivity_peaks, compliance) */
    /* the API 617 unbalance response report (docs/api617.md) */
    const td_sweep *sweep;        /**< optional: /unbalance_response; CSV sections unbalance_response, response_peaks */
    const double *static_amb;     /**< optional, with model: 2 per AMB (/static_reactions/amb_force) */
    const double *static_bearing; /**< optional, with model: 2 per plain bearing (/static_reactions/bearing_force) */
    const int *sensor_zones;      /**< optional, with sweep and model: td_sweep_sensor_zones (speeds x n_amb) */
    double zone_c_min;            /**< m, their C_min */
    const td_clearance_check *clearance; /**< optional, with sweep and model: td_sweep_clearance_check, one per
                                          *   retainer (/running_clearance; CSV section running_clearance) */
} td_modal_results;

/**
 * CSV: one file with sections, each a '# section: NAME' line, then a header line of column
 * names with units, then rows; numbers as "%.12g". Sections: modes, real_eigenvalues,
 * mode_shapes, campbell, critical_speeds, harmonic, loop, sensitivity_peaks, compliance. Errors: TD_ERR_INVALID (NULL
 * argument, bad counts), TD_ERR_IO (the file cannot be created, written or renamed), TD_ERR_NOMEM.
 */
TD_API td_status td_modal_write_csv(const char *path, const td_modal_results *r, td_error *err);
/**
 * HDF5: groups /modes, /campbell, /critical_speeds, /harmonic/<k>, /loop with one-dimensional (or 2-D for
 * Campbell and mode shapes) double datasets, each with a "units" string attribute. Errors as
 * td_modal_write_csv.
 */
TD_API td_status td_modal_write_hdf5(const char *path, const td_modal_results *r, td_error *err);

/**
 * The loop analysis as one JSON object (what `touchdown modal --json` prints), its keys the names
 * of the /loop outputs: "stable" (true/false), "max_real_part" (1/s), "speed" (rad/s), "axis"
 * (the AMB axes, 2 amb + (0: x, 1: y)), "sensitivity_peak" (linear) and
 * "sensitivity_peak_frequency" (Hz), one per controlled axis, "sensitivity_zones" ("A".."D" per
 * axis) and "sensitivity_zone" (the worst); the sensitivity ones null when the loop is unstable
 * (docs/output-format.md, "Undefined values"). l NULL (no analysis: it was refused or failed):
 * every answer null, "stable" too. Returns the length needed, like snprintf; buf is
 * NUL-terminated when n > 0 (n may be 0 to measure).
 */
TD_API int td_loop_json(char *buf, size_t n, const td_loop *l);

/**
 * Check the output paths of a modal analysis before it runs, with the rules of
 * td_output_check_paths (touchdown/output.h): TD_ERR_INVALID, naming the path, when the CSV and
 * HDF5 outputs are the same file, when an output is one of the `n_inputs` paths `inputs` (the
 * case file and its @include files: td_case_files), ends in ".partial", exists and is not a
 * regular file, or lies in a directory that does not exist or is not writable. Empty or NULL
 * paths are skipped. TD_ERR_NOMEM.
 */
TD_API td_status td_modal_check_paths(const char *csv_path, const char *hdf5_path, const char *const *inputs,
                                      int n_inputs, td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_MODAL_OUTPUT_H */
