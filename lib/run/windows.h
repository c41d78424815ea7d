/*
 * long runs: the window summaries of a run (td_output_options.window; docs/output-format.md, "Window
 * summaries"). The run loop feeds every sample it reads and every event; a window closes at the first
 * grid sample at or after its end, and its summary goes to the files at once: the accumulator holds
 * one window, whatever the run's length.
 */
#ifndef TD_RUN_WINDOWS_H
#define TD_RUN_WINDOWS_H

#include "run/recorder.h"
#include "touchdown/sim.h"

typedef struct td_run_windows td_run_windows;

/** Windows of `length` s from t0 over the retainers of `sim`; *out NULL when length is 0 (none). */
td_status td_run_windows_create(td_sim *sim, double length, double t0, td_run_windows **out, td_error *err);

/** A state read at a sample (td_recorder_retainers): its normal forces count towards the peaks. */
void td_run_windows_sample(td_run_windows *w, const td_retainer_state *ret, int n);

/** An event: an onset counts as a contact; its force (right after it) counts towards the peak. */
void td_run_windows_event(td_run_windows *w, const td_event *ev);

/** 1 if the window open now ends at or before t (a grid time). */
int td_run_windows_due(const td_run_windows *w, double t);

/** Close the window open now at t (the state of `sim` and `ret` being that at t, its sample already
 *  noted by td_run_windows_sample) and write its summary; the next window begins at t. Nothing when the window has no
 * length. */
td_status td_run_windows_close(td_run_windows *w, td_sim *sim, const td_retainer_state *ret, double t, td_recorder *rec,
                               td_error *err);

/** projective leap: open the next window at t without closing one (the stretch before t was leapt: no
 *  window covers it). Nothing for a NULL w. */
void td_run_windows_reopen(td_run_windows *w, td_sim *sim, double t);

/** Windows written so far. */
long td_run_windows_count(const td_run_windows *w);

void td_run_windows_free(td_run_windows **w);

#endif
