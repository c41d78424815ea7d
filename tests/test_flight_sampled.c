/*
 * The closed-form free flight carrying a sampled controller (lib/sim/flight.c, flight_modal.c):
 * cases/paper-a-digital.cfg (case A's PD as a 10 kHz sampled law, one sample of delay, the
 * amplifiers' lag continuous) from rest to 0.1 s, before its first contact. Between samples the
 * machine with its held currents is linear, so the flight is exact to rounding from sample to
 * sample; the second method is IDA with the flight off at a thousandth of the case's tolerances.
 * Every sample's inputs (the sensor values it read) and the final displacements agree to 10 times the
 * case's absolute tolerance (the case's own IDA run, at its tolerances, is printed for scale: it is
 * off by more), the samples fall at t0 + k / rate bit for bit in both runs, and their count is the
 * same.
 */
#include "td_test.h"

#include "sim/sim_internal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define T_END 0.1 /* s: the first contact is at 0.105 s */
#define AXES 4

typedef struct sample_log {
    double *t, *e; /* per sample k: its time and AXES inputs */
    long n, cap;
    int bad;
} sample_log;

static void on_sample(void *data, int law, long k, double t, const double *e, int nin, const double *u, int nout)
{
    sample_log *log = data;
    (void)law, (void)u, (void)nout;
    if (nin != AXES || k != log->n + 1) { /* sample 0 was taken by td_sim_create, before the hook */
        log->bad = 1;
        return;
    }
    if (log->n + 1 >= log->cap) {
        log->cap = log->cap ? 2 * log->cap : 2048;
        log->t = realloc(log->t, sizeof(double) * (size_t)log->cap);
        log->e = realloc(log->e, sizeof(double) * AXES * (size_t)log->cap);
        assert_true(log->t && log->e);
    }
    log->n++;
    log->t[k] = t;
    memcpy(log->e + AXES * k, e, sizeof(double) * AXES);
}

/* The case to T_END run with the flight on or off and its tolerances divided by `tighter`, every
 * sample logged; the stats and the final displacements (n) into q. */
static void run_case(const td_case *c, int flight, double tighter, sample_log *log, td_sim_stats *st, double *q)
{
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_error err;
    double t = 0.0;
    o.solver.free_flight = flight;
    o.solver.rtol /= tighter;
    o.solver.atol /= tighter;
    if (td_sim_create(td_case_model(c), &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    assert_non_null(s->sampler);
    assert_int_equal(s->sampler->law[0].k_next, 1);
    td_sim_sampler_set_hook(s, on_sample, log);
    while (t < T_END) {
        td_status r = td_sim_step(s, T_END, &t, &err);
        if (r != TD_OK && r != TD_EVENT)
            fail_msg("td_sim_step: %s", err.message);
    }
    assert_int_equal(td_sim_stats_get(s, st), TD_OK);
    assert_int_equal(td_sim_get_state(s, q, NULL), TD_OK);
    td_sim_free(&s);
}

/* Largest |a - b| over n values. */
static double distance(const double *a, const double *b, long n)
{
    double worst = 0.0;
    long i;
    for (i = 0; i < n; i++)
        worst = fmax(worst, fabs(a[i] - b[i]));
    return worst;
}

/* Largest |a - b| over the translations of n displacements. */
static double translation_distance(const double *a, const double *b, int n)
{
    double worst = 0.0;
    int i;
    for (i = 0; i < n; i++)
        if (i % TD_DOFS_PER_NODE == TD_DOF_X || i % TD_DOFS_PER_NODE == TD_DOF_Y)
            worst = fmax(worst, fabs(a[i] - b[i]));
    return worst;
}

static void test_flight_matches_integrator(void **state)
{
    const char *ov[1] = {"end_time=0.1"};
    td_case *c = td_test_load_case("cases/paper-a-digital.cfg", ov, 1);
    const td_sim_options *o = td_case_sim_options(c);
    sample_log lf = {NULL, NULL, 0, 0, 0}, li = {NULL, NULL, 0, 0, 0}, lc = {NULL, NULL, 0, 0, 0};
    td_sim_stats sf, si, sc;
    int n = td_model_dof_count(td_case_model(c));
    double *q = calloc(3 * (size_t)n, sizeof(double)), de, dq, rate = 1.0e4, bound = 10.0 * o->solver.atol;
    long k;
    (void)state;
    assert_non_null(q);
    run_case(c, 1, 1.0, &lf, &sf, q);
    run_case(c, 0, 1000.0, &li, &si, q + n);
    run_case(c, 0, 1.0, &lc, &sc, q + 2 * n);
    assert_false(lf.bad || li.bad || lc.bad);
    assert_int_equal(sf.contact_onsets, 0);
    assert_true(sf.flight_steps > 0 && sf.flight_time > 0.9 * T_END); /* the flight carried the run */
    assert_int_equal(si.flight_steps, 0);
    assert_int_equal(sf.controller_samples, (long)floor(T_END * rate) + 1);
    assert_int_equal(si.controller_samples, sf.controller_samples);
    assert_int_equal(li.n, lf.n);
    for (k = 1; k <= lf.n; k++)
        if (lf.t[k] != o->t0 + (double)k / rate || li.t[k] != lf.t[k])
            fail_msg("sample %ld at %.17g s (flight) / %.17g s (integrator), not t0 + k / rate", k, lf.t[k], li.t[k]);
    de = distance(lf.e + AXES, li.e + AXES, AXES * lf.n);
    dq = translation_distance(q, q + n, n);
    print_message("sampled PD to %.2g s: %ld samples, %ld flight steps (%.4f s); flight vs integrator at tolerances / "
                  "1000: sensor values %.3g m, final state %.3g m; the integrator at the case's tolerances: %.3g m, "
                  "%.3g m (bound %.3g m)\n",
                  T_END, sf.controller_samples, sf.flight_steps, sf.flight_time, de, dq,
                  distance(lc.e + AXES, li.e + AXES, AXES * lf.n), translation_distance(q + 2 * n, q + n, n), bound);
    assert_true(de <= bound);
    assert_true(dq <= bound);
    free(lf.t), free(lf.e), free(li.t), free(li.e), free(lc.t), free(lc.e);
    free(q);
    td_case_free(&c);
}

/* The amplifiers without a lag (tau = 0): the AMB force is ks x + ki i and steps with the held
 * current at every sample, which the flight's AMB peak load must follow: the peak force over the
 * run as the flight finds it, against IDA's at a thousandth of the tolerances (the peak is found to
 * 1e-6 relative, FLIGHT_PEAK_RTOL). */
static void test_flight_force_steps_with_hold(void **state)
{
    const char *ov[2] = {"end_time=0.1", "ambs = ( { node = 3; ks = 1.0e6; ki = 200.0; tau = 0.0; force_capacity = "
                                         "1700.0; air_gap = 1.2e-3; }, { node = 9; ks = 1.0e6; ki = 200.0; tau = 0.0; "
                                         "force_capacity = 1700.0; air_gap = 1.2e-3; } )"};
    td_case *c = td_test_load_case("cases/paper-a-digital.cfg", ov, 2);
    const td_sim_options *o = td_case_sim_options(c);
    sample_log lf = {NULL, NULL, 0, 0, 0}, li = {NULL, NULL, 0, 0, 0};
    td_sim_stats sf, si;
    int n = td_model_dof_count(td_case_model(c));
    double *q = calloc(2 * (size_t)n, sizeof(double)), de;
    (void)state;
    assert_non_null(q);
    run_case(c, 1, 1.0, &lf, &sf, q);
    run_case(c, 0, 1000.0, &li, &si, q + n);
    assert_false(lf.bad || li.bad);
    assert_int_equal(sf.contact_onsets, 0);
    assert_true(sf.flight_time > 0.9 * T_END);
    assert_int_equal(li.n, lf.n);
    de = distance(lf.e + AXES, li.e + AXES, AXES * lf.n);
    print_message("tau = 0: peak AMB force %.10g N (flight) / %.10g N (integrator), sensor values %.3g m\n",
                  sf.peak_amb_force, si.peak_amb_force, de);
    assert_true(de <= 10.0 * o->solver.atol);
    assert_close(sf.peak_amb_force, si.peak_amb_force, 1e-6, 0.0);
    free(lf.t), free(lf.e), free(li.t), free(li.e);
    free(q);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flight_matches_integrator),
        cmocka_unit_test(test_flight_force_steps_with_hold),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
