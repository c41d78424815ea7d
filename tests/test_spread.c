/*
 * The spread of a run's answers (touchdown/run.h, td_spread_run in touchdown/job.h):
 *   - the members' atol factors are the doubles nearest 1 +- w k / m (read from their decimals);
 *   - td_spread_collect against hand-made summaries: least, median (odd and even counts), greatest,
 *     spread and the settle rule worked out here; a failed member counted, left out of every
 *     statistic (its planted numbers nowhere) and null in the JSON; a value a member does not have;
 *     a median of 0; the endings that count as the run's; an n that is no ensemble refused;
 *   - td_run_summary_json_spread is td_run_summary_json's object with "spread" added, td_spread_json's;
 *   - td_spread_run's members equal jobs loaded from the case with solver.atol set to the scaled
 *     value (the case reader's path, not the settings'), its progress runs from 0 to 1 over the
 *     members, and a cancel or a progress stop ends it with the rest counted as failed.
 */
#include "td_test.h"

#include "run/summary.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CASE_A "cases/paper-a.cfg"

/* A completed member with the given leading answers (the rest as a run leaves them). */
static void completed(td_run_summary *s, double housing, double impulse, long contacts)
{
    td_run_summary_init(s, 0.0, 1.0, 90.0);
    s->complete = 1;
    s->t_reached = 1.0;
    s->peak_housing_force = housing;
    s->total_impulse = impulse;
    s->friction_work = impulse / 4.0;
    s->final_speed = 90.0;
    s->contacts = contacts;
    s->contact_time = 0.5;
    s->first_contact_time = 0.1;
    s->peak_normal_force = housing - 40.0;
    s->stats.peak_amb = 1;
    s->stats.peak_amb_force = 700.0;
    snprintf(s->ending, sizeof s->ending, "sliding on the retainers, bouncing");
    s->regime = TD_REGIME_BOUNCE;
}

/* A member that failed, its fields holding numbers that must appear nowhere. */
static void failed(td_run_summary *s)
{
    completed(s, 1.234e12, 1.234e12, 987654);
    s->status = TD_ERR_SOLVER;
    s->complete = 0;
}

static void test_factors(void **state)
{
    static const int ms[] = {1, 2, 4, 5, 8, 10}; /* 1 / (100 m) has at most 5 decimals */
    char text[32];
    size_t i;
    int n, k;
    (void)state;
    for (n = -1; n <= 25; n++)
        assert_int_equal(td_spread_members_valid(n), n >= 3 && n <= 21 && n % 2 == 1);
    assert_true(td_spread_atol_factor(0, 5) == 1.0);
    assert_true(td_spread_atol_factor(1, 5) == 1.005 && td_spread_atol_factor(2, 5) == 0.995);
    assert_true(td_spread_atol_factor(3, 5) == 1.01 && td_spread_atol_factor(4, 5) == 0.99);
    assert_true(td_is_undefined(td_spread_atol_factor(5, 5)) && td_is_undefined(td_spread_atol_factor(-1, 5)));
    assert_true(td_is_undefined(td_spread_atol_factor(0, 4)) && td_is_undefined(td_spread_atol_factor(1, 23)));
    for (i = 0; i < sizeof ms / sizeof ms[0]; i++) {
        int m = ms[i];
        for (k = 1; k <= m; k++) {
            int units = 1000 * k / m; /* 1e5 k / (100 m) */
            snprintf(text, sizeof text, "1.%05d", units);
            assert_true(td_spread_atol_factor(2 * k - 1, 2 * m + 1) == strtod(text, NULL));
            snprintf(text, sizeof text, "0.%05d", 100000 - units);
            assert_true(td_spread_atol_factor(2 * k, 2 * m + 1) == strtod(text, NULL));
        }
    }
    for (n = 3; n <= 21; n += 2) /* every ensemble: within +-1 %, the outermost at it, all distinct */
        for (k = 1; k < n; k++) {
            double f = td_spread_atol_factor(k, n);
            assert_true(f >= 0.99 && f <= 1.01 && f != 1.0);
            assert_true(k < n - 2 || fabs(fabs(f - 1.0) - 0.01) < 1e-15);
            assert_true(k < 3 || fabs(f - 1.0) > fabs(td_spread_atol_factor(k - 2, n) - 1.0));
        }
}

static void test_collect_odd(void **state)
{
    td_run_summary m[5];
    td_spread sp;
    const td_spread_stat *h, *imp, *c;
    (void)state;
    completed(&m[0], 8494.0, 720.6, 1579);
    completed(&m[1], 7978.0, 719.4, 1505);
    completed(&m[2], 9300.0, 720.9, 1571);
    completed(&m[3], 8100.0, 720.0, 1540);
    completed(&m[4], 8900.0, 720.3, 1600);
    assert_int_equal(td_spread_collect(m, 5, &sp, NULL), TD_OK);
    assert_int_equal(sp.members, 5);
    assert_int_equal(sp.completed, 5);
    assert_int_equal(sp.failed, 0);
    assert_int_equal(sp.same_ending, 5);
    assert_string_equal(sp.ending, "sliding on the retainers, bouncing");
    h = &sp.answers[TD_SPREAD_PEAK_HOUSING_FORCE];
    assert_true(h->run == 8494.0 && h->count == 5);
    assert_true(h->least == 7978.0 && h->median == 8494.0 && h->greatest == 9300.0);
    assert_true(h->spread == (9300.0 - 7978.0) / 8494.0);
    assert_int_equal(h->settles, 0); /* 15.6 % > 2 % */
    assert_true(h->values[1] == 7978.0 && h->values[4] == 8900.0 && td_is_undefined(h->values[5]));
    imp = &sp.answers[TD_SPREAD_TOTAL_IMPULSE];
    assert_true(imp->median == 720.3 && imp->spread == (720.9 - 719.4) / 720.3);
    assert_int_equal(imp->settles, 1); /* 0.21 % */
    c = &sp.answers[TD_SPREAD_CONTACTS];
    assert_true(c->median == 1571.0 && c->spread == (1600.0 - 1505.0) / 1571.0);
    assert_int_equal(c->settles, 0); /* 6.0 % */
    assert_true(sp.answers[TD_SPREAD_FINAL_SPEED].spread == 0.0);
    assert_int_equal(sp.answers[TD_SPREAD_FINAL_SPEED].settles, 1);
    assert_true(sp.answers[TD_SPREAD_PEAK_AMB_FORCE].median == 700.0);
    assert_true(sp.atol_factor[0] == 1.0 && sp.atol_factor[3] == 1.01);
    assert_string_equal(td_spread_answer_name(TD_SPREAD_PEAK_HOUSING_FORCE), "peak_housing_force");
    assert_string_equal(td_spread_answer_name(TD_SPREAD_PEAK_AMB_FORCE), "peak_amb_force");
    assert_null(td_spread_answer_name(TD_SPREAD_ANSWERS));
}

/* A failed member: counted, in no statistic, null in the JSON; four completed give an even median. */
static void test_collect_failed_member(void **state)
{
    td_run_summary m[5];
    td_spread sp;
    const td_spread_stat *h;
    char json[16384], want[256];
    (void)state;
    completed(&m[0], 8494.0, 720.6, 1579);
    completed(&m[1], 7978.0, 719.4, 1505);
    failed(&m[2]);
    completed(&m[3], 8100.0, 720.0, 1540);
    completed(&m[4], 8900.0, 720.3, 1600);
    assert_int_equal(td_spread_collect(m, 5, &sp, NULL), TD_OK);
    assert_int_equal(sp.completed, 4);
    assert_int_equal(sp.failed, 1);
    assert_int_equal(sp.status[2], TD_ERR_SOLVER);
    assert_int_equal(sp.same_ending, 4);
    h = &sp.answers[TD_SPREAD_PEAK_HOUSING_FORCE];
    assert_int_equal(h->count, 4);
    assert_true(h->least == 7978.0 && h->greatest == 8900.0);
    assert_true(h->median == 0.5 * (8100.0 + 8494.0));
    assert_true(td_is_undefined(h->values[2]));
    assert_true(sp.answers[TD_SPREAD_CONTACTS].median == 0.5 * (1540.0 + 1579.0));
    assert_true(td_spread_json(json, sizeof json, &sp) < (int)sizeof json);
    assert_null(strstr(json, "1234"));
    assert_null(strstr(json, "987654"));
    assert_non_null(strstr(json, "\"values\":[8494,7978,null,8100,8900]"));
    snprintf(want, sizeof want, "\"status\":[\"%s\",\"%s\",\"%s\",\"%s\",\"%s\"]", td_strerror(TD_OK),
             td_strerror(TD_OK), td_strerror(TD_ERR_SOLVER), td_strerror(TD_OK), td_strerror(TD_OK));
    assert_non_null(strstr(json, want));
    assert_non_null(strstr(json, "\"members\":5,\"completed\":4,\"failed\":1,"));
    /* member 0 failed: no run value, no ending to match */
    failed(&m[0]);
    assert_int_equal(td_spread_collect(m, 5, &sp, NULL), TD_OK);
    assert_int_equal(sp.completed, 3);
    assert_int_equal(sp.same_ending, 0);
    assert_true(td_is_undefined(sp.answers[TD_SPREAD_TOTAL_IMPULSE].run));
    assert_true(sp.answers[TD_SPREAD_TOTAL_IMPULSE].median == 720.0);
    assert_true(td_spread_json(json, sizeof json, &sp) < (int)sizeof json);
    assert_non_null(strstr(json, "\"total_impulse\":{\"run\":null,\"count\":3,"));
    assert_non_null(strstr(json, "\"ending\":null,"));
}

/* Values a member does not have, one value, a median of 0. */
static void test_collect_undefined(void **state)
{
    td_run_summary m[3];
    td_spread sp;
    char text[8192];
    int k;
    (void)state;
    completed(&m[0], 10.0, 2.0, 3);
    completed(&m[1], 10.0, 2.0, 3);
    completed(&m[2], 10.0, 2.0, 3);
    m[1].first_contact_time = m[2].first_contact_time = TD_UNDEFINED;
    m[0].stats.peak_amb = m[1].stats.peak_amb = m[2].stats.peak_amb = -1; /* no working AMB */
    m[0].final_speed = -1.0, m[1].final_speed = 0.0, m[2].final_speed = 1.0;
    assert_int_equal(td_spread_collect(m, 3, &sp, NULL), TD_OK);
    assert_int_equal(sp.answers[TD_SPREAD_FIRST_CONTACT_TIME].count, 1);
    assert_true(sp.answers[TD_SPREAD_FIRST_CONTACT_TIME].median == 0.1);
    assert_true(td_is_undefined(sp.answers[TD_SPREAD_FIRST_CONTACT_TIME].spread));
    assert_int_equal(sp.answers[TD_SPREAD_FIRST_CONTACT_TIME].settles, -1);
    assert_int_equal(sp.answers[TD_SPREAD_PEAK_AMB_FORCE].count, 0);
    assert_true(td_is_undefined(sp.answers[TD_SPREAD_PEAK_AMB_FORCE].median));
    assert_true(sp.answers[TD_SPREAD_FINAL_SPEED].median == 0.0);
    assert_true(td_is_undefined(sp.answers[TD_SPREAD_FINAL_SPEED].spread));
    assert_int_equal(sp.answers[TD_SPREAD_FINAL_SPEED].settles, -1);
    assert_true(sp.answers[TD_SPREAD_PEAK_HOUSING_FORCE].spread == 0.0);
    assert_true(td_spread_format(text, sizeof text, &sp) < (int)sizeof text);
    assert_non_null(strstr(text, "  peak AMB force            none in every run\n"));
    assert_non_null(strstr(text, "  first contact             0.1 s; 1 run: 0.1 .. 0.1 s, median 0.1 s, spread n/a"));
    assert_non_null(
        strstr(text, "  peak housing force        10 N; 3 runs: 10 .. 10 N, median 10 N, spread 0 %: settles\n"));
    k = td_spread_format(text, sizeof text, NULL);
    assert_int_equal(k, (int)strlen(text));
    assert_non_null(strstr(text, "not measured"));
}

/* Which members ended as the run did: its regime and its ending but for the whirl frequency. */
static void test_endings(void **state)
{
    td_run_summary m[5];
    td_spread sp;
    int k;
    (void)state;
    for (k = 0; k < 5; k++) {
        completed(&m[k], 1.0, 1.0, 1);
        m[k].regime = TD_REGIME_BACKWARD_WHIRL;
        snprintf(m[k].ending, sizeof m[k].ending, "backward whirl at %.4g Hz, rolling", 12.3 + 0.1 * k);
    }
    snprintf(m[2].ending, sizeof m[2].ending, "backward whirl at 12.3 Hz, sliding"); /* another kind */
    m[3].regime = TD_REGIME_RUB;                                                     /* another regime */
    m[4].status = TD_ERR_SOLVER;                                                     /* failed */
    assert_int_equal(td_spread_collect(m, 5, &sp, NULL), TD_OK);
    assert_int_equal(sp.same_ending, 2);
    assert_string_equal(sp.ending, "backward whirl at 12.3 Hz, rolling");
}

static void test_collect_refuses(void **state)
{
    td_run_summary m[4];
    td_spread sp;
    td_error err;
    int k;
    (void)state;
    for (k = 0; k < 4; k++)
        completed(&m[k], 1.0, 1.0, 1);
    assert_int_equal(td_spread_collect(m, 4, &sp, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "4 members"));
    assert_int_equal(td_spread_collect(m, 1, &sp, &err), TD_ERR_INVALID);
    assert_int_equal(td_spread_collect(NULL, 3, &sp, &err), TD_ERR_INVALID);
    assert_int_equal(td_spread_collect(m, 3, NULL, &err), TD_ERR_INVALID);
}

/* The summary's JSON with the spread: the summary's own object, one member more. */
static void test_summary_json_spread(void **state)
{
    td_run_summary m[3];
    td_spread sp;
    char *plain, *with, *alone, *want;
    int np, nw, na;
    (void)state;
    completed(&m[0], 8.0, 2.0, 3);
    completed(&m[1], 9.0, 2.0, 3);
    failed(&m[2]);
    assert_int_equal(td_spread_collect(m, 3, &sp, NULL), TD_OK);
    np = td_run_summary_json(NULL, 0, &m[0]);
    nw = td_run_summary_json_spread(NULL, 0, &m[0], &sp);
    na = td_spread_json(NULL, 0, &sp);
    plain = malloc((size_t)np + 1), with = malloc((size_t)nw + 1), alone = malloc((size_t)na + 1);
    want = malloc((size_t)(np + na) + 16);
    assert_true(plain && with && alone && want);
    td_run_summary_json(plain, (size_t)np + 1, &m[0]);
    td_run_summary_json_spread(with, (size_t)nw + 1, &m[0], &sp);
    td_spread_json(alone, (size_t)na + 1, &sp);
    assert_true(np > 0 && plain[np - 1] == '}');
    sprintf(want, "%.*s,\"spread\":%s}", np - 1, plain, alone);
    assert_string_equal(with, want);
    td_run_summary_json_spread(with, (size_t)nw + 1, &m[0], NULL);
    sprintf(want, "%.*s,\"spread\":null}", np - 1, plain);
    assert_string_equal(with, want);
    free(plain), free(with), free(alone), free(want);
}

/* The run of case A to 0.12 s (through its first contact) with solver.atol = atol, no files. */
static void case_run(double atol, td_run_summary *s)
{
    char set_atol[64];
    const char *ov[] = {"end_time=0.12", set_atol};
    td_job *job = NULL;
    td_job_settings set;
    snprintf(set_atol, sizeof set_atol, "solver.atol=%.17g", atol);
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 2, &job, NULL), TD_OK);
    set = *td_job_settings_get(job);
    set.out.hdf5_path[0] = set.out.csv_path[0] = '\0';
    assert_int_equal(td_job_set(job, &set, NULL), TD_OK);
    assert_int_equal(td_job_run(job, NULL, s, NULL), TD_OK);
    td_job_free(&job);
}

/* The job of case A to 0.12 s without files. */
static td_job *job_a(void)
{
    const char *ov[] = {"end_time=0.12"};
    td_job *job = NULL;
    td_job_settings set;
    assert_int_equal(td_job_create(td_source_path(CASE_A), ov, 1, &job, NULL), TD_OK);
    set = *td_job_settings_get(job);
    set.out.hdf5_path[0] = set.out.csv_path[0] = '\0';
    assert_int_equal(td_job_set(job, &set, NULL), TD_OK);
    return job;
}

typedef struct seen {
    double last, stop_after;
    int calls, backwards;
} seen;

static int watch(double t, double fraction, long contacts, void *user)
{
    seen *p = user;
    (void)t, (void)contacts;
    p->backwards += fraction < p->last;
    p->last = fraction;
    p->calls++;
    return fraction > p->stop_after;
}

static void test_spread_run(void **state)
{
    td_job *job = job_a();
    td_run_summary m[3], direct;
    td_run_hooks hooks;
    seen p = {0.0, 2.0, 0, 0};
    td_spread sp;
    double atol = td_job_settings_get(job)->sim.solver.atol;
    int k;
    (void)state;
    assert_int_equal(td_job_run(job, NULL, &m[0], NULL), TD_OK); /* member 0: the run as given */
    memset(&hooks, 0, sizeof hooks);
    hooks.progress = watch;
    hooks.user = &p;
    assert_int_equal(td_spread_run(job, 3, &hooks, m, NULL), TD_OK);
    assert_true(p.calls >= 2 && p.backwards == 0 && p.last == 1.0);
    for (k = 1; k < 3; k++) {
        char *a, *b;
        case_run(atol * td_spread_atol_factor(k, 3), &direct);
        a = td_test_summary_json(&m[k], &direct), b = td_test_summary_json(&direct, &direct);
        assert_string_equal(a, b);
        free(a), free(b);
        assert_true(m[k].hdf5_path[0] == '\0' && m[k].csv_path[0] == '\0');
    }
    assert_int_equal(td_spread_collect(m, 3, &sp, NULL), TD_OK);
    assert_int_equal(sp.completed, 3);
    assert_true(sp.answers[TD_SPREAD_TOTAL_IMPULSE].run == m[0].total_impulse);
    assert_true(sp.answers[TD_SPREAD_TOTAL_IMPULSE].values[2] == m[2].total_impulse);
    td_job_free(&job);
}

/* A cancel before the members, and a progress stop in the third of four: the rest not run, failed. */
static void test_spread_run_stopped(void **state)
{
    td_job *job = job_a();
    td_run_summary m[5];
    td_run_hooks hooks;
    volatile sig_atomic_t cancel = 1;
    seen p = {0.0, 0.5, 0, 0};
    td_spread sp;
    td_error err;
    int k;
    (void)state;
    assert_int_equal(td_job_run(job, NULL, &m[0], NULL), TD_OK);
    memset(&hooks, 0, sizeof hooks);
    hooks.cancel = &cancel;
    assert_int_equal(td_spread_run(job, 3, &hooks, m, &err), TD_ERR_INTERRUPTED);
    assert_non_null(strstr(err.message, "after 0 of its 2"));
    assert_int_equal(m[1].status, TD_ERR_INTERRUPTED);
    assert_int_equal(m[2].status, TD_ERR_INTERRUPTED);
    assert_true(td_is_undefined(m[2].peak_housing_force));
    assert_int_equal(td_spread_collect(m, 3, &sp, NULL), TD_OK);
    assert_int_equal(sp.completed, 1);
    assert_int_equal(sp.failed, 2);
    cancel = 0;
    hooks.progress = watch;
    hooks.user = &p; /* stops once past half of the four members: in the third */
    assert_int_equal(td_spread_run(job, 5, &hooks, m, &err), TD_ERR_INTERRUPTED);
    assert_non_null(strstr(err.message, "after 2 of its 4"));
    for (k = 1; k <= 2; k++)
        assert_int_equal(m[k].status, TD_OK);
    for (k = 3; k <= 4; k++)
        assert_int_equal(m[k].status, TD_ERR_INTERRUPTED);
    assert_int_equal(td_spread_run(job, 4, NULL, m, &err), TD_ERR_INVALID);
    assert_int_equal(td_spread_run(NULL, 3, NULL, m, &err), TD_ERR_INVALID);
    td_job_free(&job);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_factors),
        cmocka_unit_test(test_collect_odd),
        cmocka_unit_test(test_collect_failed_member),
        cmocka_unit_test(test_collect_undefined),
        cmocka_unit_test(test_endings),
        cmocka_unit_test(test_collect_refuses),
        cmocka_unit_test(test_summary_json_spread),
        cmocka_unit_test(test_spread_run),
        cmocka_unit_test(test_spread_run_stopped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
