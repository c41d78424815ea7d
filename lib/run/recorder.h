/*
 * The recorder: the one place that reads a td_sim for output. It turns the model and the output
 * options into a td_output_layout, opens the writers (HDF5 and/or CSV), and on each sample reads
 * the simulation's state (nodes, retainers, AMBs) and hands it to every writer, so the writers
 * themselves never see the solver.
 */
#ifndef TD_RUN_RECORDER_H
#define TD_RUN_RECORDER_H

#include "touchdown/model.h"
#include "touchdown/options.h"
#include "touchdown/output.h"
#include "touchdown/result.h"
#include "touchdown/sim.h"

typedef struct td_recorder td_recorder;

/**
 * Check `out` against `model` (sample_rate > 0 and finite, nodes in range; node_count 0: every
 * node), open a writer for each non-empty path and write the model's retainer/AMB metadata as
 * attributes. On failure no file is left behind.
 */
td_status td_recorder_create(const td_model *model, const td_output_options *out, td_recorder **rec, td_error *err);

/** Read the simulation's current state and append it as a sample at time `t` to every writer. */
td_status td_recorder_sample(td_recorder *rec, const td_sim *sim, double t, td_error *err);

/** Retainer states read by the last td_recorder_sample (td_recorder_retainer_count of them). */
const td_retainer_state *td_recorder_retainers(const td_recorder *rec);
int td_recorder_retainer_count(const td_recorder *rec);

/** Append an event to every writer; `sample` is the row showing the state after it (-1: none). */
td_status td_recorder_event(td_recorder *rec, const td_event *ev, long sample, td_error *err);

/** Attributes for every writer (see td_writer_set_*). */
td_status td_recorder_set_string(td_recorder *rec, td_out_id name, const char *value, td_error *err);
td_status td_recorder_set_double(td_recorder *rec, td_out_id name, double value, td_error *err);
td_status td_recorder_set_long(td_recorder *rec, td_out_id name, long value, td_error *err);
td_status td_recorder_set_doubles(td_recorder *rec, td_out_id name, const double *values, int n, td_error *err);
td_status td_recorder_set_longs(td_recorder *rec, td_out_id name, const long *values, int n, td_error *err);
td_status td_recorder_set_stats(td_recorder *rec, const td_sim_stats *stats, td_error *err);

/* long runs */
/** Read the simulation's current state as td_recorder_sample does (td_recorder_retainers then
 *  give it) without writing a sample. */
td_status td_recorder_observe(td_recorder *rec, const td_sim *sim, td_error *err);

/** Append a window summary to every writer (they were opened with window_fields: out->window > 0). */
td_status td_recorder_window(td_recorder *rec, const td_window_summary *win, td_error *err);

/** Close every writer (all are tried even if one fails; the first failure is returned) and free. */
td_status td_recorder_close(td_recorder **rec, int complete, const char *reason, td_error *err);

/** Remove every file and free (for failures before the run starts). Accepts NULL. */
void td_recorder_discard(td_recorder **rec);

#endif
