/* A case run as `touchdown run` runs it: load, set-up, run, summary (touchdown/job.h). Built on the
 * public calls: the case reader, td_sim_create and td_run do the work, this file their order. */
#include "touchdown/job.h"
#include "touchdown/output.h"

#include "util/error_internal.h"

#include <stdlib.h>
#include <string.h>

/* Where a job is: made, started (a simulation), failed to start (no simulation), run. */
typedef enum job_state { JOB_MADE, JOB_STARTED, JOB_START_FAILED, JOB_RAN } job_state;

struct td_job {
    td_case *c;      /* NULL for a job of a model */
    td_model *model; /* a job of a model: its copy; NULL for a case */
    char *case_text; /* a job of a model: its copy or NULL; a case's is td_case_text */
    td_job_settings settings;
    td_sim *sim;
    job_state state;
    td_status start_status; /* a failed start, given back by td_job_run */
    td_error start_err;
};

td_status td_job_create(const char *path, const char *const *overrides, int n_overrides, td_job **out, td_error *err)
{
    td_job *j;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_job_create: NULL argument");
    *out = NULL;
    j = calloc(1, sizeof *j);
    if (!j)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a job");
    st = td_case_load(path, overrides, n_overrides, &j->c, err);
    if (st != TD_OK) {
        free(j);
        return st;
    }
    j->settings.sim = *td_case_sim_options(j->c);
    j->settings.out = *td_case_output_options(j->c);
    j->settings.t_end = td_case_end_time(j->c);
    *out = j;
    return TD_OK;
}

td_status td_job_create_model(const td_model *model, const td_job_settings *settings, const char *case_text,
                              td_job **out, td_error *err)
{
    td_job *j;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_job_create_model: NULL argument");
    *out = NULL;
    if (!model || !settings)
        return td_error_set(err, TD_ERR_INVALID, "td_job_create_model: NULL argument");
    j = calloc(1, sizeof *j);
    if (!j)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a job");
    if ((st = td_model_clone(model, &j->model, err)) != TD_OK) {
        free(j);
        return st;
    }
    if (case_text && !(j->case_text = malloc(strlen(case_text) + 1))) {
        td_job_free(&j);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a job");
    }
    if (case_text)
        memcpy(j->case_text, case_text, strlen(case_text) + 1);
    j->settings = *settings;
    *out = j;
    return TD_OK;
}

void td_job_free(td_job **job)
{
    if (!job || !*job)
        return;
    td_sim_free(&(*job)->sim);
    td_case_free(&(*job)->c);
    td_model_free(&(*job)->model);
    free((*job)->case_text);
    free(*job);
    *job = NULL;
}

const td_case *td_job_case(const td_job *job)
{
    return job ? job->c : NULL;
}

const td_model *td_job_model(const td_job *job)
{
    if (!job)
        return NULL;
    return job->c ? td_case_model(job->c) : job->model;
}

const td_job_settings *td_job_settings_get(const td_job *job)
{
    return job ? &job->settings : NULL;
}

td_status td_job_set(td_job *job, const td_job_settings *settings, td_error *err)
{
    if (!job || !settings)
        return td_error_set(err, TD_ERR_INVALID, "td_job_set: NULL argument");
    if (job->state != JOB_MADE)
        return td_error_set(err, TD_ERR_STATE, "td_job_set: the job has started");
    job->settings = *settings;
    return TD_OK;
}

td_status td_job_check_outputs(const td_job *job, td_error *err)
{
    int n = 0;
    const char *const *inputs;
    if (!job)
        return td_error_set(err, TD_ERR_INVALID, "td_job_check_outputs: NULL job");
    inputs = job->c ? td_case_files(job->c, &n) : NULL;
    return td_output_check_paths(&job->settings.out, inputs, n, err);
}

td_status td_job_start(td_job *job, volatile sig_atomic_t *cancel, td_error *err)
{
    td_status st;
    if (!job)
        return td_error_set(err, TD_ERR_INVALID, "td_job_start: NULL job");
    if (job->state != JOB_MADE)
        return td_error_set(err, TD_ERR_STATE, "td_job_start: the job has started");
    td_error_clear(&job->start_err);
    st = td_sim_create_cancellable(td_job_model(job), &job->settings.sim, cancel, &job->sim, &job->start_err);
    job->state = st == TD_OK ? JOB_STARTED : JOB_START_FAILED;
    job->start_status = st;
    if (err)
        *err = job->start_err;
    return st;
}

/* The summary of a job that ran no simulation: the status and message, nothing simulated. */
static void failed_summary(const td_job *job, td_status st, const char *message, td_run_summary *summary)
{
    td_run_summary_failed(summary, job->settings.sim.t0, job->settings.t_end, td_model_speed(td_job_model(job)),
                          job->settings.sim.start, st, message);
}

td_status td_job_run(td_job *job, const td_run_hooks *hooks, td_run_summary *summary, td_error *err)
{
    const char *text;
    if (!job)
        return td_error_set(err, TD_ERR_INVALID, "td_job_run: NULL job");
    if (job->state == JOB_RAN) {
        td_status st = td_error_set(err, TD_ERR_STATE, "td_job_run: the job has run already");
        failed_summary(job, st, "td_job_run: the job has run already", summary);
        return st;
    }
    if (job->state == JOB_MADE)
        td_job_start(job, hooks ? hooks->cancel : NULL, NULL);
    if (job->state == JOB_START_FAILED) {
        failed_summary(job, job->start_status, job->start_err.message, summary);
        if (err)
            *err = job->start_err;
        job->state = JOB_RAN;
        return job->start_status;
    }
    job->state = JOB_RAN;
    text = job->c ? td_case_text(job->c) : job->case_text;
    return td_run(job->sim, job->settings.t_end, &job->settings.out, hooks, text, summary, err);
}
