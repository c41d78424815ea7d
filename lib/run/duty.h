/* The run summary's part on the bearing's duty and the vibration zones (lib/run/duty.c). */
#ifndef TD_RUN_DUTY_H
#define TD_RUN_DUTY_H

#include "run/recorder.h"
#include "touchdown/run.h"
#include "util/text.h"

/** The summary's sentinels (td_run_summary_init): nothing graded, nothing settled. */
void td_run_duty_init(td_run_summary *s);
/** A run that did not reach its end: its duty, zones and time to settle TD_UNDEFINED. */
void td_run_duty_undefine(td_run_summary *s);
/** After the run (`sim` the run's, the retainers' totals already in s): the load ratios, the sensors'
 *  peaks and zones, the time to settle. */
void td_run_duty_collect(td_run_summary *s, const td_sim *sim);
/** The text summary's lines. */
void td_run_duty_format(td_text *b, const td_run_summary *s);
/** The JSON summary's members, each followed by a comma. */
void td_run_duty_json(td_text *b, const td_run_summary *s);
/** The files' attributes: retainer_load_ratio and the sensors' (every retainer and AMB of the model),
 *  summary_settle_time; undefined unless reached_end. */
td_status td_run_duty_write(td_recorder *rec, const td_run_summary *s, const td_sim *sim, int reached_end,
                            td_error *err);

#endif
