/*
 * td_job (touchdown/job.h) against the lower calls it stands for: case A through its first
 * contact run as a job gives the summary (every field but the wall-clock ones) and the CSV and
 * events files, byte for byte, that td_case_load + td_sim_create + td_run give; a job of the
 * case's model built in code gives the same summary. A start that cannot be made (the steady orbit
 * outside the clearance, a cancel during the set-up) gives the failed summary with td_sim_create's
 * status and message, no answer a number and no file; a case that cannot be loaded gives no job
 * and td_case_load's error; a job runs once and its settings change only before it starts.
 */
#include "td_test.h"

#include "touchdown/dofs.h"
#include "touchdown/touchdown.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CASE_A "cases/paper-a.cfg"

/* A scratch file of this test in the build tree: TD_BINARY_DIR/job_PID_STEM. */
static void scratch(char *dst, const char *stem)
{
    snprintf(dst, TD_OUTPUT_PATH_SIZE, "%s/job_%ld_%s", TD_BINARY_DIR, (long)getpid(), stem);
}

static void assert_same_summary(const td_run_summary *a, const td_run_summary *b)
{
    char *ja = td_test_summary_json(a, b), *jb = td_test_summary_json(b, b);
    assert_string_equal(ja, jb);
    free(ja);
    free(jb);
}

/* The text less its wall-clock lines ("# wall_time = ...", "# summary_realtime_factor = ..."). */
static void drop_wall_lines(char *text)
{
    char *line = text, *out = text;
    while (*line) {
        char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line) + 1 : strlen(line);
        int wall;
        if (end)
            *end = '\0';
        wall = line[0] == '#' && (strstr(line, "wall_time") || strstr(line, "realtime_factor"));
        if (end)
            *end = '\n';
        if (!wall) {
            memmove(out, line, n);
            out += n;
        }
        line += n;
    }
    *out = '\0';
}

/* Two files equal byte for byte but for their wall-clock lines. */
static void assert_same_file(const char *a, const char *b)
{
    char *fa = td_test_read_file(a), *fb = td_test_read_file(b);
    size_t na = strlen(fa);
    drop_wall_lines(fa);
    drop_wall_lines(fb);
    assert_true(strlen(fa) > 0 && strlen(fa) + 400 > na); /* a few short lines dropped, no more */
    assert_string_equal(fa, fb);
    free(fa);
    free(fb);
}

/* CSV output only, at PATH (its events file beside it). */
static void csv_only(td_output_options *out, const char *path)
{
    out->hdf5_path[0] = '\0';
    snprintf(out->csv_path, sizeof out->csv_path, "%s", path);
}

static void events_of(char *dst, const char *csv)
{
    snprintf(dst, TD_OUTPUT_PATH_SIZE, "%.*s.events.csv", (int)(strlen(csv) - 4), csv);
}

/* The run of the case's CSV through td_case_load + td_sim_create + td_run. */
static td_status lower_run(const char *const *ov, int n, const char *csv, td_run_summary *s, td_error *err)
{
    td_case *c = NULL;
    td_sim *sim = NULL;
    td_output_options out;
    td_status st;
    assert_int_equal(td_case_load(td_source_path(CASE_A), ov, n, &c, err), TD_OK);
    out = *td_case_output_options(c);
    csv_only(&out, csv);
    st = td_sim_create(td_case_model(c), td_case_sim_options(c), &sim, err);
    if (st == TD_OK)
        st = td_run(sim, td_case_end_time(c), &out, NULL, td_case_text(c), s, err);
    td_sim_free(&sim);
    td_case_free(&c);
    return st;
}

static void test_job_equals_lower_calls(void **state)
{
    const char *ov[] = {"end_time=0.12"}; /* through the first contact, 0.105 s */
    char csv[TD_OUTPUT_PATH_SIZE], csv_low[TD_OUTPUT_PATH_SIZE], ev[TD_OUTPUT_PATH_SIZE], ev_low[TD_OUTPUT_PATH_SIZE];
    td_job *job = NULL;
    td_job_settings set;
    td_run_summary sj, sl;
    td_error err;
    (void)state;
    /* one path for both (the summary names it): the lower calls' files moved aside first */
    scratch(csv, "run.csv");
    scratch(csv_low, "low.csv");
    events_of(ev, csv);
    events_of(ev_low, csv_low);
    assert_int_equal(lower_run(ov, 1, csv, &sl, &err), TD_OK);
    assert_int_equal(rename(csv, csv_low), 0);
    assert_int_equal(rename(ev, ev_low), 0);
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 1, &job, &err), TD_OK);
    assert_string_equal(td_case_name(td_job_case(job)), "paper-a");
    set = *td_job_settings_get(job);
    assert_true(set.t_end == 0.12);
    csv_only(&set.out, csv);
    assert_int_equal(td_job_set(job, &set, &err), TD_OK);
    assert_int_equal(td_job_check_outputs(job, &err), TD_OK);
    assert_int_equal(td_job_run(job, NULL, &sj, &err), TD_OK);
    td_job_free(&job);
    assert_null(job);
    assert_true(sj.contacts > 0);
    assert_true(sj.t_reached == 0.12);
    assert_same_summary(&sj, &sl);
    assert_same_file(csv, csv_low);
    assert_same_file(ev, ev_low);
    remove(csv);
    remove(csv_low);
    remove(ev);
    remove(ev_low);
}

/* A job of the case's model with settings of its own (a later start, no files) runs as the case's
 * job given the same settings. */
static void test_job_of_a_model(void **state)
{
    const char *ov[] = {"end_time=0.12"};
    td_job *from_case = NULL, *from_model = NULL;
    td_job_settings set;
    td_run_summary sc, sm;
    td_error err;
    (void)state;
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 1, &from_case, &err), TD_OK);
    set = *td_job_settings_get(from_case);
    set.sim.t0 = 0.09;
    set.out.hdf5_path[0] = set.out.csv_path[0] = '\0';
    assert_int_equal(td_job_set(from_case, &set, &err), TD_OK);
    assert_int_equal(td_job_create_model(td_job_model(from_case), &set, "# in code", &from_model, &err), TD_OK);
    assert_null(td_job_case(from_model));
    assert_int_equal(td_job_check_outputs(from_model, &err), TD_OK);
    assert_int_equal(td_job_run(from_case, NULL, &sc, &err), TD_OK);
    assert_int_equal(td_job_run(from_model, NULL, &sm, &err), TD_OK);
    assert_true(sm.t_start == 0.09);
    assert_true(sm.contacts > 0);
    assert_same_summary(&sm, &sc);
    td_job_free(&from_case);
    td_job_free(&from_model);
}

/* Every answer of a failed summary is undefined, never a number; nothing was simulated. */
static void assert_failed_summary(const td_run_summary *s, td_status st, const char *message)
{
    char json[16384];
    assert_int_equal(s->status, st);
    assert_string_equal(s->message, message);
    assert_true(s->t_reached == s->t_start);
    assert_true(td_is_undefined(s->peak_housing_force));
    assert_true(td_is_undefined(s->total_impulse));
    assert_true(td_is_undefined(s->peak_normal_force));
    assert_true(td_is_undefined(s->final_speed));
    assert_int_equal(s->samples, 0);
    assert_true(td_run_summary_json(json, sizeof json, s) < (int)sizeof json);
    assert_non_null(strstr(json, "\"peak_housing_force\":null"));
    assert_non_null(strstr(json, "\"final_speed\":null"));
}

static int exists(const char *path)
{
    return access(path, F_OK) == 0;
}

static void test_failed_start(void **state)
{
    /* at 190 rad/s case A's steady orbit lies outside the retainer clearance (docs/case-format.md,
     * start): "orbit" refuses it in td_sim_create */
    const char *ov[] = {"end_time=0.03", "start=orbit", "speed=190"};
    char csv[TD_OUTPUT_PATH_SIZE];
    td_job *job = NULL;
    td_job_settings set;
    td_run_summary s;
    td_error err, low;
    td_status want;
    (void)state;
    scratch(csv, "failed.csv");
    want = lower_run(ov, 3, csv, &s, &low);
    assert_int_equal(want, TD_ERR_INVALID);
    assert_false(exists(csv));
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 3, &job, &err), TD_OK);
    set = *td_job_settings_get(job);
    csv_only(&set.out, csv);
    assert_int_equal(td_job_set(job, &set, &err), TD_OK);
    memset(&s, 0, sizeof s);
    assert_int_equal(td_job_run(job, NULL, &s, &err), want);
    assert_string_equal(err.message, low.message);
    assert_non_null(strstr(err.message, "clearance"));
    assert_failed_summary(&s, want, low.message);
    assert_true(s.t_start == 0.0 && s.t_end == 0.03 && s.speed == 190.0);
    assert_false(exists(csv));
    /* it ran (and failed): it does not run again, nor take new settings */
    assert_int_equal(td_job_run(job, NULL, &s, &err), TD_ERR_STATE);
    assert_int_equal(s.status, TD_ERR_STATE);
    assert_int_equal(td_job_set(job, &set, &err), TD_ERR_STATE);
    td_job_free(&job);
}

/* A cancel flag already set stops the set-up: TD_ERR_INTERRUPTED, the failed summary; the same
 * from td_job_start, whose failure td_job_run then gives back. */
static void test_cancelled_start(void **state)
{
    const char *ov[] = {"end_time=0.03"};
    volatile sig_atomic_t cancel = 1;
    td_run_hooks hooks;
    td_job *job = NULL;
    td_run_summary s;
    td_error err;
    (void)state;
    memset(&hooks, 0, sizeof hooks);
    hooks.cancel = &cancel;
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 1, &job, &err), TD_OK);
    assert_int_equal(td_job_run(job, &hooks, &s, &err), TD_ERR_INTERRUPTED);
    assert_failed_summary(&s, TD_ERR_INTERRUPTED, err.message);
    td_job_free(&job);

    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 1, &job, &err), TD_OK);
    assert_int_equal(td_job_start(job, &cancel, &err), TD_ERR_INTERRUPTED);
    assert_int_equal(td_job_start(job, &cancel, &err), TD_ERR_STATE);
    cancel = 0; /* the failed start stays failed */
    assert_int_equal(td_job_run(job, &hooks, &s, &err), TD_ERR_INTERRUPTED);
    assert_failed_summary(&s, TD_ERR_INTERRUPTED, err.message);
    td_job_free(&job);
}

/* A case that cannot be loaded: no job, td_case_load's status and message. */
static void test_bad_case(void **state)
{
    const char *ov[] = {"speed=-1"};
    td_case *c = NULL;
    td_job *job = (td_job *)&job; /* set to NULL by the failure */
    td_error err, low;
    (void)state;
    assert_int_equal(td_case_load(td_source_path(CASE_A), ov, 1, &c, &low), TD_ERR_PARSE);
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 1, &job, &err), TD_ERR_PARSE);
    assert_null(job);
    assert_string_equal(err.message, low.message);
    assert_non_null(strstr(err.message, "speed"));
    assert_int_equal(td_job_create_model(NULL, NULL, NULL, &job, &err), TD_ERR_INVALID);
    td_job_free(&job);
    td_job_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_job_equals_lower_calls),
        cmocka_unit_test(test_job_of_a_model),
        cmocka_unit_test(test_failed_start),
        cmocka_unit_test(test_cancelled_start),
        cmocka_unit_test(test_bad_case),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
