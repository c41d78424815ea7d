/* The run summary's clearance margin, contact and shock outcome (lib/run/outcome.c). */
#ifndef TD_RUN_OUTCOME_H
#define TD_RUN_OUTCOME_H

#include "run/recorder.h"
#include "touchdown/run.h"
#include "util/text.h"

/** The summary's sentinels (td_run_summary_init): no margin yet, no contact, no outcome. */
void td_run_outcome_init(td_run_summary *s);
/** A run that did not reach its end: no margin, no outcome; it touched if it had a contact onset, else
 *  undetermined. */
void td_run_outcome_undefine(td_run_summary *s);
/** After the run (the summary's contacts and free_at_end set; `in_contact` 1 when a retainer is in
 *  contact at the end): the smallest margin over every retainer of `sim`, the contact, the outcome. */
void td_run_outcome_collect(td_run_summary *s, const td_sim *sim, int in_contact);
/** The text summary's line. */
void td_run_outcome_format(td_text *b, const td_run_summary *s);
/** The JSON summary's members, each followed by a comma. */
void td_run_outcome_json(td_text *b, const td_run_summary *s);
/** The files' attributes: retainer_min_clearance_margin (every retainer, undefined unless reached_end),
 *  summary_min_clearance_margin, summary_contact_happened, summary_shock_outcome. */
td_status td_run_outcome_write(td_recorder *rec, const td_run_summary *s, const td_sim *sim, int reached_end,
                               td_error *err);

#endif
