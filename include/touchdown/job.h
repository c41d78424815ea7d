/*
 * touchdown/job.h - run a case as `touchdown run` does: load it (with KEY=VALUE overrides), create
 * its simulation, run it through its writers and summarise it, or give the failed summary of a
 * run that could not start. The one path of `touchdown run`, of every point of `touchdown sweep`
 * and of `touchdown bench`.
 *
 *   td_job *j;
 *   td_run_summary s;
 *   td_job_create("cases/paper-a.cfg", overrides, n, &j, &err);   (a bad case: no job, err says where)
 *   td_job_run(j, NULL, &s, &err);                                 (files and summary, or the failed summary)
 *   td_job_free(&j);
 *
 * A job runs once. Its settings (simulation options, outputs, end time) start as its case's and
 * may be changed before it starts (td_job_set). The library prints nothing.
 */
#ifndef TOUCHDOWN_JOB_H
#define TOUCHDOWN_JOB_H

#include <signal.h>

#include "touchdown/case.h"
#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/model.h"
#include "touchdown/options.h"
#include "touchdown/run.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct td_job td_job;

/** What a job runs: the simulation's options (start time t0 included), the outputs and sampling
 *  (both paths "": no files, the summary is still made) and the end time. */
typedef struct td_job_settings {
    td_sim_options sim;
    td_output_options out;
    double t_end; /**< s, after sim.t0 */
} td_job_settings;

/**
 * A job of the case file at `path` loaded with `overrides` (td_case_load): its model, its settings
 * (td_case_sim_options, td_case_output_options, td_case_end_time) and its text, which the run
 * stores in its files. On failure *out is NULL and the status and `err` are td_case_load's.
 * Like td_case_load it does not judge the case's `sweep` group, which a single run does not use:
 * td_sweep_check_case(td_job_case(job), &err) refuses a bad one, as the tool does.
 */
TD_API td_status td_job_create(const char *path, const char *const *overrides, int n_overrides, td_job **out,
                               td_error *err);

/**
 * A job of a model built in code (copied; td_model_clone) with `settings` (copied) and
 * `case_text` (copied; NULL: none) to store in its files. TD_ERR_INVALID for NULL model, settings
 * or out; TD_ERR_NOMEM.
 */
TD_API td_status td_job_create_model(const td_model *model, const td_job_settings *settings, const char *case_text,
                                     td_job **out, td_error *err);

/** Free a job (its case, model and simulation) and set *job to NULL. Accepts NULL and *job == NULL. */
TD_API void td_job_free(td_job **job);

/** The job's case (borrowed), NULL for a job of a model (td_job_create_model). */
TD_API const td_case *td_job_case(const td_job *job);

/** The job's model (borrowed): its case's, or its own copy. */
TD_API const td_model *td_job_model(const td_job *job);

/** The job's settings (borrowed; change them with td_job_set). */
TD_API const td_job_settings *td_job_settings_get(const td_job *job);

/** Replace the job's settings (copied) before it starts; TD_ERR_STATE once it has started,
 *  TD_ERR_INVALID for NULL arguments. td_run checks their values when the job runs. */
TD_API td_status td_job_set(td_job *job, const td_job_settings *settings, td_error *err);

/**
 * Refuse, before the run, outputs of the settings that collide with each other or with the files
 * the case was read from, or that cannot be written: td_output_check_paths with td_case_files
 * (none for a job of a model). Its status and `err`.
 */
TD_API td_status td_job_check_outputs(const td_job *job, td_error *err);

/**
 * Start the job: create its simulation (td_sim_create_cancellable: the start state is solved
 * here, at settings.sim.t0), reading `cancel` (may be NULL) between the stages of the set-up:
 * nonzero stops it with TD_ERR_INTERRUPTED. Optional: td_job_run starts a job not yet started;
 * calling it first separates the set-up from the run (a caller timing the run alone). A failed
 * start is kept: td_job_run then returns its status and message with the failed summary.
 * TD_ERR_STATE if the job has started already.
 */
TD_API td_status td_job_start(td_job *job, volatile sig_atomic_t *cancel, td_error *err);

/**
 * Run the job: start it if td_job_start was not called (reading hooks->cancel during the set-up),
 * then td_run to settings.t_end through settings.out with `hooks` (progress, cancel; NULL: none)
 * and the case text. Returns td_run's status (files and summary as td_run leaves them), or the
 * start's status when the simulation could not be created: then no file is written and `summary`
 * (may be NULL) is the failed summary (td_run_summary_failed: the status and message, no answers).
 * A job that has run already returns TD_ERR_STATE (summary: failed, with that status).
 */
TD_API td_status td_job_run(td_job *job, const td_run_hooks *hooks, td_run_summary *summary, td_error *err);

/**
 * Run members 1..n-1 of the spread ensemble of `job` (touchdown/run.h, td_spread_collect): each a
 * job of the job's model (td_job_create_model) with its settings, solver.atol times
 * td_spread_atol_factor(k, n) and no files, into members[k]; members[0] (the run as given, e.g.
 * td_job_run's summary) is not touched. The job is only read: it may have run. `hooks` (may be
 * NULL): hooks->cancel is read before each member and during its run; hooks->progress is called
 * with the member's simulated time and contacts and the fraction of the n - 1 members done. A member
 * that fails is kept in its summary (its status and message) and the next one runs. Returns TD_OK
 * when every member ran (whatever its status); TD_ERR_INTERRUPTED when the cancel flag or the
 * progress callback stopped them (the member stopped and those not run: failed summaries with that
 * status); TD_ERR_INVALID for NULL job or members or an n that is no ensemble.
 */
TD_API td_status td_spread_run(const td_job *job, int n, const td_run_hooks *hooks, td_run_summary *members,
                               td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_JOB_H */
