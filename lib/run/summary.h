/* The run summary's initial state, shared by td_run and td_run_summary_failed (lib/run/summary.c). */
#ifndef TD_RUN_SUMMARY_H
#define TD_RUN_SUMMARY_H

#include "touchdown/run.h"
#include "util/text.h"

/** `s` before a run from t0 towards t_end at `speed`: nothing simulated, every "none" sentinel set,
 *  status TD_OK, the start requested and used TD_START_REST. */
void td_run_summary_init(td_run_summary *s, double t0, double t_end, double speed);

/** The whirl of a retainer over its contact time, from its totals at the end (`speed` the rotor's,
 *  `span` the time from the run's first contact to the end of its last): into out->whirl,
 *  out->whirl_frequency, out->mean_normal and out->rms_normal. */
void td_run_retainer_classify(td_run_retainer *out, double speed, double span);

/** A run that did not reach its end has no answers: every quantity that sums up or picks the
 *  largest over the whole run, or describes its end, set TD_UNDEFINED (touchdown/run.h). */
void td_run_summary_undefine_answers(td_run_summary *s);

/** long runs: whether a run asked to end at rest did: 1 (it stopped at rest), 0 (it reached t_end at
 *  speed), -1 (undetermined: it failed), TD_RUN_NOT_APPLICABLE (not asked: no end_at_rest). The one
 *  reading of the JSON's `ended_at_rest` and the files' `summary_ended_at_rest`. */
int td_run_summary_rest_flag(const td_run_summary *s);

/** td_run_summary_json's object less its closing brace, into `b`: a writer that adds members to it
 *  (td_run_summary_json_spread) closes it. */
void td_run_summary_json_members(td_text *b, const td_run_summary *s);

#endif
