/*
 * Sampled controllers in the simulation (lib/sim/sampler.c): case A's PD moved into a 10 kHz
 * sampled controller (a 2 kHz derivative filter, Tustin, one sample of delay) on the four AMB axes,
 * over a 0.5 s run with contacts. Sample k falls at t0 + k / rate bit for bit (the state it read
 * was the integrator's at that instant); the samples are 0, 1, 2, ... with none missed or doubled,
 * and their count is the number of k >= 0 with t0 + k / rate <= t_end, floor((t_end - t0) rate) + 1
 * here; the command read at outputs between samples is the last sample's, bit for bit; and the
 * controller's inputs and outputs are those of scipy.signal.dlsim driven by the recorded inputs
 * (tests/validation/control/sampler_dlsim.py, an independent recursion).
 */
#include "td_test.h"

#include "sim/sim_internal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RATE 1.0e4 /* Hz */
#define T_END 0.5  /* s */
#define SUB 3      /* outputs per sample period */
#define AXES 4     /* AMB 0 x, y, AMB 1 x, y */

typedef struct sample {
    long k;
    double t;
    double e[AXES], u[AXES];
} sample;

typedef struct sample_log {
    sample *s;
    long n, cap;
    int bad_size;
} sample_log;

static void log_sample(sample_log *log, long k, double t, const double *e, int nin, const double *u, int nout)
{
    sample *r;
    if (nin != AXES || nout != AXES) {
        log->bad_size = 1;
        return;
    }
    if (log->n == log->cap) {
        log->cap = log->cap ? 2 * log->cap : 1024;
        log->s = realloc(log->s, sizeof *log->s * (size_t)log->cap);
        assert_non_null(log->s);
    }
    r = &log->s[log->n++];
    r->k = k;
    r->t = t;
    memcpy(r->e, e, sizeof r->e);
    memcpy(r->u, u, sizeof r->u);
}

static void on_sample(void *data, int law, long k, double t, const double *e, int nin, const double *u, int nout)
{
    (void)law;
    log_sample((sample_log *)data, k, t, e, nin, u, nout);
}

/* The PD kp + kd s / (1 + s / (2 pi 2 kHz)) of case A's AMBs, Tustin at RATE, one sample of delay,
 * on each of the AXES axes (block-diagonal). */
static td_controller *digital_pd(void)
{
    const td_pid_block pid = {1.0e4, 0.0, 40.0, 2000.0};
    td_error err;
    td_controller *k = td_controller_create_pid(&pid, &err), *kd, *one, *all;
    int i;
    assert_non_null(k);
    kd = td_controller_discretise(k, RATE, TD_DISCRETISE_TUSTIN, 0.0, &err);
    assert_non_null(kd);
    one = td_controller_delay(kd, 1, &err);
    assert_non_null(one);
    all = td_controller_clone(one, &err);
    for (i = 1; i < AXES; i++) {
        td_controller *next = td_controller_append(all, one, &err);
        assert_non_null(next);
        td_controller_free(&all);
        all = next;
    }
    td_controller_free(&k);
    td_controller_free(&kd);
    td_controller_free(&one);
    return all;
}

/* Case A from rest, cut to T_END, its AMBs' PD replaced by the sampled one (a new model). */
static td_model *digital_case_a(td_case **c)
{
    const char *ov[6] = {"end_time=0.5",   "start=\"rest\"", "ambs[0].kp=0.0",
                         "ambs[0].kd=0.0", "ambs[1].kp=0.0", "ambs[1].kd=0.0"};
    const int axes[AXES] = {0, 1, 2, 3};
    td_model *m = NULL;
    td_controller *k = digital_pd();
    td_error err;
    *c = td_test_load_case("cases/paper-a.cfg", ov, 6);
    assert_int_equal(td_model_clone(td_case_model(*c), &m, &err), TD_OK);
    if (td_model_add_controller(m, "digital", k, axes, axes, &err) != TD_OK)
        fail_msg("td_model_add_controller: %s", err.message);
    td_controller_free(&k);
    return m;
}

/* Step s to T_END on outputs SUB per sample period; at each, the held commands must be those of
 * the last sample logged at or before it, bit for bit. Returns the outputs checked between samples. */
static long run_checking_hold(td_sim *s, const sample_log *log)
{
    long j, between = 0, n_out = (long)(T_END * RATE * SUB + 0.5);
    for (j = 1; j <= n_out; j++) {
        double tout = (double)j / (RATE * SUB), tr;
        td_error err;
        td_status st;
        int a;
        const sample *last;
        while ((st = td_sim_step(s, tout, &tr, &err)) == TD_EVENT)
            ;
        if (st != TD_OK)
            fail_msg("td_sim_step to %.17g: %s", tout, err.message);
        assert_true(tr == tout);
        assert_true(log->n > 0);
        last = &log->s[log->n - 1];
        assert_true(last->t <= tout);
        for (a = 0; a < AXES; a++)
            if (s->machine.held_current[a] != last->u[a])
                fail_msg("t = %.17g: axis %d holds %.17g A, the sample at %.17g gave %.17g A", tout, a,
                         s->machine.held_current[a], last->t, last->u[a]);
        between += j % SUB != 0;
    }
    return between;
}

/* The records for sampler_dlsim.py (its header says the layout). */
static void write_records(const char *path, const td_model *m, const sample_log *log)
{
    const td_controller *k = td_model_get_controller(m, 0, NULL, NULL, NULL);
    int n = td_controller_order(k), i, j;
    double *A = calloc((size_t)(n * n + 1), sizeof(double)), *B = calloc((size_t)(n * AXES + 1), sizeof(double));
    double *C = calloc((size_t)(n * AXES + 1), sizeof(double)), *D = calloc(AXES * AXES, sizeof(double));
    FILE *f = fopen(path, "w");
    long r;
    assert_non_null(f);
    assert_true(A && B && C && D);
    td_controller_matrices(k, A, B, C, D, NULL);
    fprintf(f, "%d %d %d %.17g\n", n, AXES, AXES, td_controller_sample_rate(k));
    for (i = 0; i < n; i++, fputc('\n', f)) /* column-major in, rows out */
        for (j = 0; j < n; j++)
            fprintf(f, " %.17g", A[i + n * j]);
    for (i = 0; i < n; i++, fputc('\n', f))
        for (j = 0; j < AXES; j++)
            fprintf(f, " %.17g", B[i + n * j]);
    for (i = 0; i < AXES; i++, fputc('\n', f))
        for (j = 0; j < n; j++)
            fprintf(f, " %.17g", C[i + AXES * j]);
    for (i = 0; i < AXES; i++, fputc('\n', f))
        for (j = 0; j < AXES; j++)
            fprintf(f, " %.17g", D[i + AXES * j]);
    fprintf(f, "%ld\n", log->n);
    for (r = 0; r < log->n; r++, fputc('\n', f)) {
        fprintf(f, "%ld %.17g", log->s[r].k, log->s[r].t);
        for (j = 0; j < AXES; j++)
            fprintf(f, " %.17g", log->s[r].e[j]);
        for (j = 0; j < AXES; j++)
            fprintf(f, " %.17g", log->s[r].u[j]);
    }
    assert_int_equal(fclose(f), 0);
    free(A), free(B), free(C), free(D);
}

/* Sample 0 is taken by td_sim_create, before a hook can be set: the sampler keeps the last sample's
 * inputs and outputs, so it is read from there. */
static void log_first_sample(const td_sim *s, sample_log *log)
{
    const td_sim_sampled *l;
    assert_non_null(s->sampler);
    l = &s->sampler->law[0];
    assert_int_equal(l->k_next, 1);
    log_sample(log, 0, td_sim_time(s), l->e, AXES, l->u, AXES);
}

static void test_sampled_case_a(void **state)
{
    td_case *c = NULL;
    td_model *m = digital_case_a(&c);
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_sim_stats st;
    td_error err;
    sample_log log = {NULL, 0, 0, 0};
    long k, expected = (long)floor((T_END - o.t0) * RATE) + 1, between;
    char cmd[1024];
    (void)state;
    if (td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    assert_non_null(s->sampler);
    log_first_sample(s, &log);
    td_sim_sampler_set_hook(s, on_sample, &log);
    between = run_checking_hold(s, &log);
    assert_true(between > 0);
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    assert_false(log.bad_size);
    assert_true(st.contact_onsets > 0); /* a run with contacts */
    assert_true(st.flight_steps > 0);   /* the closed-form flight carried the free phases, sample to sample */
    assert_int_equal(st.controller_samples, expected);
    assert_int_equal(log.n, expected);
    for (k = 0; k < log.n; k++) {
        assert_int_equal(log.s[k].k, k); /* in order, none missed, none doubled */
        if (log.s[k].t != o.t0 + (double)k / RATE)
            fail_msg("sample %ld read the state at %.17g s, not at t0 + k / rate = %.17g s", k, log.s[k].t,
                     o.t0 + (double)k / RATE);
    }
    write_records("test_sampler_records.txt", m, &log);
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 %s test_sampler_records.txt",
             td_source_path("tests/validation/control/sampler_dlsim.py"));
    assert_int_equal(system(cmd), 0);
    free(log.s);
    td_sim_free(&s);
    td_model_free(&m);
    td_case_free(&c);
}

/* A start time that is not 0: sample 0 is at the start, sample k at t0 + k / rate, and a run of
 * 2.5 periods from there takes samples 0, 1, 2 (the count rule with t0). */
static void test_start_time_offset(void **state)
{
    td_case *c = NULL;
    td_model *m = digital_case_a(&c);
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_sim_stats st;
    td_error err;
    sample_log log = {NULL, 0, 0, 0};
    td_status st_step;
    double tr;
    long k;
    (void)state;
    o.t0 = 0.0123;
    if (td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    log_first_sample(s, &log);
    assert_true(log.s[0].t == o.t0);
    td_sim_sampler_set_hook(s, on_sample, &log);
    while ((st_step = td_sim_step(s, o.t0 + 2.5 / RATE, &tr, &err)) == TD_EVENT)
        ;
    assert_int_equal(st_step, TD_OK);
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    assert_int_equal(st.controller_samples, 3);
    assert_int_equal(log.n, 3);
    for (k = 0; k < log.n; k++) {
        assert_int_equal(log.s[k].k, k);
        assert_true(log.s[k].t == o.t0 + (double)k / RATE);
    }
    free(log.s);
    td_sim_free(&s);
    td_model_free(&m);
    td_case_free(&c);
}

/* Without a sampled controller there is no sampler and no sample. */
static void test_no_sampler_without_sampled_law(void **state)
{
    const char *ov[1] = {"end_time=0.01"};
    td_case *c = td_test_load_case("cases/paper-a.cfg", ov, 1);
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_sim_stats st;
    td_error err;
    double tr;
    (void)state;
    assert_int_equal(td_sim_create(td_case_model(c), &o, &s, &err), TD_OK);
    assert_null(s->sampler);
    assert_int_equal(td_sim_step(s, 0.01, &tr, &err), TD_OK);
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    assert_int_equal(st.controller_samples, 0);
    td_sim_free(&s);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sampled_case_a),
        cmocka_unit_test(test_start_time_offset),
        cmocka_unit_test(test_no_sampler_without_sampled_law),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
