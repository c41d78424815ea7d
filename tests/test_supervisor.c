/*
 * The recovery supervisor (lib/sim/supervisor.c; touchdown/model.h td_recovery) on a rotor whose
 * orbit its unbalance steps drive past the thresholds whatever the controllers command
 * (tests/data/case/recovery-jeffcott.cfg: the AMB's magnet barely acts). The AMB is driven by a
 * sampled pair at 1 kHz: on each axis the nominal law G1 (1 + A1 z^-1) / (1 - A1 z^-1), the
 * recovery law G2 (1 + A2 z^-1) / (1 - A2 z^-1). Checked against the sensor sequence each sample read (the
 * sampled laws' inputs e = -xs), independently of the supervisor's own arithmetic:
 *  - the switches fall exactly where the rule says: the detection at the sample that ends the first
 *    run of ceil(dwell rate) + 1 consecutive samples with hypot(e) > f_d c, the sample before that
 *    run not meeting it (the dwell exact to one sample), and the release likewise; their events
 *    carry the sample's time t0 + k / rate, the controller switched to and that sample's radius;
 *  - at a switch sample the held current is the outgoing law's output, bit for bit (no jump), and
 *    over the blend it is (1 - b) i_old + b i_new with b = (k - k_s) / (blend rate), i_new the
 *    incoming law's difference equation run from rest at the switch (a second method: the
 *    recursion, not the realisation; the nominal law comes back from rest, not from the state it
 *    left), i_old the outgoing law's run from its own start;
 *  - the summary account: controller_switches, time_on_recovery, last_return_time;
 *  - two pairs over two AMBs each switch by their own sensor's sequence;
 *  - enabled = false takes no switch, and its held currents are bit for bit those of the same
 *    machine with the nominal law alone (no supervisor), as are the enabled run's up to its switch;
 *  - the model rules, each refused with its site.
 */
#include "td_test.h"

#include "sim/sim_internal.h"
#include "sim/supervisor.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RATE 1000.0 /* Hz */
#define G1 1000.0   /* A/m, the nominal gain */
#define A1 0.25     /* its pole and zero */
#define G2 2000.0   /* A/m, the recovery law's gain */
#define A2 0.5
#define CLEARANCE 1.0e-3
#define DETECT 0.5
#define DETECT_DWELL 0.01 /* s: 10 samples */
#define RELEASE 0.3
#define RELEASE_DWELL 0.02 /* s: 20 samples */
#define BLEND 0.005        /* s: 5 samples */
#define MAX_SAMPLES 1024

typedef struct row {
    long k;
    double t, e[2], r, b, held[2], u[2][2];
    int target, ran[2];
} row;

typedef struct log_t {
    row s[MAX_SAMPLES];
    long n;
    struct log_t *other; /* pair 1's samples (its nominal: controller 3), when given */
    td_event ev[8];
    int n_ev;
} log_t;

static void on_pair_sample(void *data, const td_sim_pair_sample *ps)
{
    log_t *log = data;
    row *w;
    int i, j;
    assert_true(log->n < MAX_SAMPLES);
    if (ps->pair != 0) {
        assert_non_null(log->other);
        assert_int_equal(ps->pair, 1);
        on_pair_sample(
            log->other,
            &(td_sim_pair_sample){
                0, ps->k, ps->t, ps->e, ps->nin, ps->r, ps->b, ps->target, {ps->u[0], ps->u[1]}, ps->held, ps->nout});
        return;
    }
    assert_int_equal(ps->nin, 2);
    assert_int_equal(ps->nout, 2);
    w = &log->s[log->n++];
    w->k = ps->k, w->t = ps->t, w->r = ps->r, w->b = ps->b, w->target = ps->target;
    for (i = 0; i < 2; i++) {
        w->e[i] = ps->e[i];
        w->held[i] = ps->held[i];
        w->ran[i] = ps->u[i] != NULL;
        for (j = 0; j < 2; j++)
            w->u[i][j] = ps->u[i] ? ps->u[i][j] : 0.0;
    }
}

/* A sampled law on both axes of AMB 0: g (1 + a z^-1) / (1 - a z^-1), a gain and a first-order
 * section in series. */
static td_controller *law(double g, double a)
{
    const double num[2] = {1.0, a}, den[2] = {1.0, -a};
    td_error err;
    td_controller *k = td_controller_create_tf(num, 2, den, 2, RATE, &err);
    td_controller *gk = td_controller_create_tf((const double[]){g}, 1, (const double[]){1.0}, 1, RATE, &err), *one,
                  *both;
    assert_non_null(k);
    assert_non_null(gk);
    one = td_controller_series(gk, k, &err);
    assert_non_null(one);
    both = td_controller_append(one, one, &err);
    assert_non_null(both);
    td_controller_free(&k);
    td_controller_free(&gk);
    td_controller_free(&one);
    return both;
}

/* The machine with the nominal law, and with the recovery law and the supervisor unless
 * `pairs` is 0 (then the nominal law alone). */
static td_model *machine_at(td_case **c, int pairs, int enabled, const char *override)
{
    const int axes[2] = {0, 1};
    td_model *m = NULL;
    td_controller *n = law(G1, A1), *r = law(G2, A2);
    td_recovery rec;
    td_error err;
    *c = td_test_load_case("tests/data/case/recovery-jeffcott.cfg", &override, override ? 1 : 0);
    assert_int_equal(td_model_clone(td_case_model(*c), &m, &err), TD_OK);
    assert_int_equal(td_model_add_controller(m, "nominal", n, axes, axes, &err), TD_OK);
    if (pairs) {
        assert_int_equal(td_model_add_controller(m, "recovery", r, axes, axes, &err), TD_OK);
        memset(&rec, 0, sizeof rec);
        rec.enabled = enabled;
        rec.pair_count = 1;
        rec.nominal[0] = 0;
        rec.controller[0] = 1;
        rec.detect.radius_fraction = DETECT, rec.detect.dwell = DETECT_DWELL;
        rec.release.radius_fraction = RELEASE, rec.release.dwell = RELEASE_DWELL;
        rec.blend = BLEND;
        if (td_model_set_recovery(m, &rec, &err) != TD_OK)
            fail_msg("td_model_set_recovery: %s", err.message);
    }
    td_controller_free(&n);
    td_controller_free(&r);
    return m;
}

static td_model *machine(td_case **c, int pairs, int enabled)
{
    return machine_at(c, pairs, enabled, NULL);
}

/* Sample 0, taken by td_sim_create from rest before a hook can be set, from the sampler's records:
 * the nominal law's inputs and output, which it held (r = 0 at rest: no switch). */
static void log_first(const td_sim *s, log_t *log, int record)
{
    const td_sim_sampled *l = &s->sampler->law[record];
    row *w = &log->s[log->n++];
    int a;
    assert_int_equal(l->k_next, 1);
    w->t = td_sim_time(s);
    w->ran[0] = 1;
    for (a = 0; a < 2; a++) {
        w->e[a] = l->e[a];
        w->u[0][a] = w->held[a] = l->u[a];
    }
    w->r = hypot(w->e[0], w->e[1]);
    w->b = 1.0;
}

/* Run the machine to its end time, logging every pair sample (sample 0, taken by td_sim_create
 * from rest, from the sampler's record) and every switch event; the held current of the laws
 * alone (no supervisor) into held_alone when given. */
static void run(const td_case *c, const td_model *m, log_t *log, double *held_alone, td_sim_stats *st)
{
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_error err;
    td_status step;
    double tr, t_end = td_case_end_time(c);
    long j, n = (long)floor(t_end * RATE + 0.5);
    log_t *other = log->other;
    memset(log, 0, sizeof *log);
    log->other = other;
    if (td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    log_first(s, log, 0);
    if (other)
        log_first(s, other, 3); /* pair 1's nominal, the model's (and sampler's) fourth law */
    td_sim_supervisor_set_hook(s, on_pair_sample, log);
    for (j = 1; j <= n; j++) { /* outputs at the sample instants: the held current after each */
        while ((step = td_sim_step(s, (double)j / RATE, &tr, &err)) == TD_EVENT) {
            td_event ev;
            assert_int_equal(td_sim_last_event(s, &ev), TD_OK);
            if (ev.kind == TD_EVENT_CONTROLLER_SWITCH && log->n_ev < 8)
                log->ev[log->n_ev++] = ev;
        }
        if (step != TD_OK)
            fail_msg("td_sim_step: %s", err.message);
        if (held_alone && j < MAX_SAMPLES)
            held_alone[j] = s->machine.held_current[0];
    }
    assert_int_equal(td_sim_stats_get(s, st), TD_OK);
    td_sim_free(&s);
}

/* The first k >= from where a run of need + 1 consecutive samples meets `above ? r > f c : r < f c`
 * ends, checking that the run starts where the condition starts to hold; -1 if none. */
static long rule_sample(const log_t *log, long from, int above, double f, long need)
{
    long k, run = 0;
    for (k = from; k < log->n; k++) {
        double r = hypot(log->s[k].e[0], log->s[k].e[1]);
        int met = above ? r > f * CLEARANCE : r < f * CLEARANCE;
        run = met ? run + 1 : 0;
        if (run == need + 1)
            return k;
    }
    return -1;
}

/* The output at sample k (axis a) of the law g (1 + c z^-1) / (1 - c z^-1) run from rest at sample
 * ks: its difference equation y_j = g (e_j + c e_j-1) + c y_j-1. */
static double law_output(const log_t *log, double g, double c, long ks, long k, int a)
{
    double y = 0.0, e_prev = 0.0;
    long j;
    for (j = ks; j <= k; j++) {
        y = g * (log->s[j].e[a] + c * e_prev) + c * y;
        e_prev = log->s[j].e[a];
    }
    return y;
}

/* Over the blend after the switch at ks (to the recovery law when `in` is 1; the old law started at
 * sample k_old): b and the held current. */
static void check_blend(const log_t *log, long k_old, long ks, int in)
{
    long k;
    int a;
    for (k = ks; k < log->n && k <= ks + (long)(BLEND * RATE + 0.5) + 2; k++) {
        const row *w = &log->s[k];
        double b = fmin(1.0, (double)(k - ks) / (BLEND * RATE));
        assert_true(fabs(w->b - b) <= 1e-15);
        for (a = 0; a < 2; a++) {
            double i_new = in ? law_output(log, G2, A2, ks, k, a) : law_output(log, G1, A1, ks, k, a);
            double i_old = in ? law_output(log, G1, A1, k_old, k, a) : law_output(log, G2, A2, k_old, k, a);
            double want = b < 1.0 ? (1.0 - b) * i_old + b * i_new : i_new;
            if (!(fabs(w->held[a] - want) <= 1e-12 * fmax(fabs(want), 1e-9)))
                fail_msg("sample %ld (switch at %ld), axis %d: held %.17g A, the blend gives %.17g A", k, ks, a,
                         w->held[a], want);
        }
        assert_int_equal(w->ran[1 - in], b < 1.0); /* the old law runs while it weighs */
    }
}

static void test_switch_times_and_blend(void **state)
{
    td_case *c = NULL;
    td_model *m = machine(&c, 1, 1);
    log_t *log = calloc(1, sizeof *log);
    td_sim_stats st;
    long kd, kr, k;
    int a;
    (void)state;
    run(c, m, log, NULL, &st);
    assert_true(log->n > 400);
    kd = rule_sample(log, 0, 1, DETECT, 10);
    assert_true(kd > 0);
    kr = rule_sample(log, kd + 1, 0, RELEASE, 20);
    assert_true(kr > kd);
    print_message("detection at sample %ld (%.4f s), release at %ld (%.4f s), %d switch events\n", kd, kd / RATE, kr,
                  kr / RATE, log->n_ev);
    assert_int_equal(log->n_ev, 2);
    assert_true(log->ev[0].time == (double)kd / RATE && log->ev[1].time == (double)kr / RATE);
    assert_int_equal(log->ev[0].controller, 1);
    assert_int_equal(log->ev[1].controller, 0);
    assert_true(log->ev[0].sensed_radius == hypot(log->s[kd].e[0], log->s[kd].e[1]));
    assert_true(log->ev[1].sensed_radius == hypot(log->s[kr].e[0], log->s[kr].e[1]));
    assert_int_equal(log->ev[0].retainer, -1);
    for (a = 0; a < 2; a++) { /* no jump: at the switch sample the held current is the old law's own */
        assert_true(log->s[kd].held[a] == log->s[kd].u[0][a]);
        assert_true(log->s[kr].held[a] == log->s[kr].u[1][a]);
    }
    assert_int_equal(log->s[kd - 1].target, 0);
    assert_int_equal(log->s[kd].target, 1);
    assert_int_equal(log->s[kr].target, 0);
    for (k = 0; k < kd; k++) /* the nominal law from rest at sample 0, alone */
        for (a = 0; a < 2; a++)
            assert_true(fabs(log->s[k].held[a] - law_output(log, G1, A1, 0, k, a)) <=
                        1e-12 * fmax(fabs(log->s[k].held[a]), 1e-9));
    check_blend(log, 0, kd, 1);
    check_blend(log, kd, kr, 0);
    assert_int_equal(st.controller_switches, 2);
    assert_true(fabs(st.time_on_recovery - ((double)kr / RATE - (double)kd / RATE)) <= 1e-15);
    assert_true(st.last_return_time == (double)kr / RATE);
    free(log);
    td_model_free(&m);
    td_case_free(&c);
}

static void test_disabled_takes_no_switch(void **state)
{
    td_case *c = NULL, *c2 = NULL, *c3 = NULL;
    td_model *off = machine(&c, 1, 0), *alone = machine(&c2, 0, 0), *on = machine(&c3, 1, 1);
    log_t *log = calloc(1, sizeof *log), *log_on = calloc(1, sizeof *log_on);
    double *h_off = calloc(MAX_SAMPLES, sizeof(double)), *h_alone = calloc(MAX_SAMPLES, sizeof(double));
    double *h_on = calloc(MAX_SAMPLES, sizeof(double));
    td_sim_stats st;
    long k, kd;
    (void)state;
    run(c, off, log, h_off, &st);
    assert_int_equal(log->n_ev, 0);
    assert_int_equal(st.controller_switches, 0);
    assert_true(st.time_on_recovery == 0.0 && td_is_undefined(st.last_return_time));
    assert_true(rule_sample(log, 0, 1, DETECT, 10) > 0); /* the rule was met: only `enabled` held it back */
    for (k = 0; k < log->n; k++)
        assert_true(log->s[k].target == 0 && !log->s[k].ran[1] && log->s[k].held[0] == log->s[k].u[0][0]);
    run(c2, alone, log_on, h_alone, &st);
    run(c3, on, log_on, h_on, &st);
    kd = rule_sample(log_on, 0, 1, DETECT, 10);
    for (k = 1; k <= 500; k++) {
        assert_true(h_off[k] == h_alone[k]);
        if (k < kd) /* the output at sample k is held from t_k: before the switch, the same run */
            assert_true(h_on[k] == h_alone[k]);
    }
    assert_true(h_on[kd + 1] != h_alone[kd + 1]);
    free(log), free(log_on), free(h_off), free(h_alone), free(h_on);
    td_model_free(&off), td_model_free(&alone), td_model_free(&on);
    td_case_free(&c), td_case_free(&c2), td_case_free(&c3);
}

/* Two pairs, each over its own AMB (pair 1's AMB at the end node, where the unbalance now is, so
 * that the two orbits differ; its recovery law listed before its nominal): each switches where its
 * own sensor's sequence says, and only its own events. */
static void test_two_pairs(void **state)
{
    td_case *c = NULL;
    td_model *m = machine_at(&c, 1, 1, "unbalances[0].node=2");
    td_amb amb;
    td_recovery rec;
    td_controller *n = law(G1, A1), *r = law(G2, A2);
    const int axes[2] = {2, 3};
    log_t *log = calloc(1, sizeof *log), *log1 = calloc(1, sizeof *log1);
    td_sim_stats st;
    td_error err;
    long kd, kr, kd1, kr1;
    int e;
    (void)state;
    assert_int_equal(td_model_get_amb(m, 0, &amb), TD_OK);
    amb.node = amb.sensor_node = 2;
    assert_int_equal(td_model_add_amb(m, &amb, &err), TD_OK);
    assert_int_equal(td_model_add_controller(m, "recovery 1", r, axes, axes, &err), TD_OK);
    assert_int_equal(td_model_add_controller(m, "nominal 1", n, axes, axes, &err), TD_OK);
    td_model_get_recovery(m, &rec);
    rec.pair_count = 2, rec.nominal[1] = 3, rec.controller[1] = 2;
    assert_int_equal(td_model_set_recovery(m, &rec, &err), TD_OK);
    log->other = log1;
    run(c, m, log, NULL, &st);
    kd = rule_sample(log, 0, 1, DETECT, 10);
    kr = rule_sample(log, kd + 1, 0, RELEASE, 20);
    kd1 = rule_sample(log1, 0, 1, DETECT, 10);
    kr1 = rule_sample(log1, kd1 + 1, 0, RELEASE, 20);
    print_message("pair 0 switches at samples %ld, %ld; pair 1 at %ld, %ld\n", kd, kr, kd1, kr1);
    assert_true(kd > 0 && kr > kd && kd1 > 0 && kr1 > kd1);
    assert_int_equal(log->n_ev, 4);
    for (e = 0; e < 4; e++) { /* each in its pair's place, to its pair's controller */
        const td_event *ev = &log->ev[e];
        int to = ev->controller;
        long k = to == 1 ? kd : to == 0 ? kr : to == 2 ? kd1 : kr1;
        const log_t *l = to < 2 ? log : log1;
        assert_true(ev->time == (double)k / RATE);
        assert_true(ev->sensed_radius == hypot(l->s[k].e[0], l->s[k].e[1]));
    }
    assert_int_equal(st.controller_switches, 4);
    assert_int_equal(st.controller_samples, 4 * (long)(0.5 * RATE + 1)); /* four laws, each its instants */
    free(log), free(log1);
    td_controller_free(&n), td_controller_free(&r);
    td_model_free(&m);
    td_case_free(&c);
}

/* Each model rule refuses with its site (the case reader locates it at the key). */
static void test_model_rules(void **state)
{
    td_case *c = NULL;
    td_model *m = machine(&c, 1, 1);
    td_recovery rec, bad;
    td_error err;
    const int x_only[1] = {0};
    td_controller *cont = td_controller_create_gain(5.0, &err), *slow, *half;
    (void)state;
    assert_int_equal(td_model_get_recovery(m, &rec), 1);
    bad = rec, bad.release.radius_fraction = DETECT;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "release.radius_fraction");
    bad = rec, bad.detect.dwell = -1.0;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "detect.dwell");
    bad = rec, bad.blend = NAN;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "blend");
    bad = rec, bad.pair_count = TD_RECOVERY_MAX_PAIRS + 1;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_ERR_INVALID);
    /* the pair rules wait for validation: a continuous law, another rate, other axes, itself */
    slow = td_controller_create_tf((const double[]){1.0}, 1, (const double[]){1.0}, 1, 500.0, &err);
    half = td_controller_create_tf((const double[]){1.0}, 1, (const double[]){1.0}, 1, RATE, &err);
    assert_int_equal(td_model_add_controller(m, "continuous", cont, x_only, x_only, &err), TD_OK);
    assert_int_equal(td_model_add_controller(m, "slow", slow, x_only, x_only, &err), TD_OK);
    assert_int_equal(td_model_add_controller(m, "x only", half, x_only, x_only, &err), TD_OK);
    bad = rec, bad.controller[0] = 2;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.part, "recovery");
    assert_non_null(strstr(err.message, "is continuous"));
    bad.controller[0] = 3;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "a pair runs at one rate"));
    bad.controller[0] = 4;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "the same AMB axes"));
    bad.controller[0] = 0;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "its own recovery law"));
    bad = rec, bad.pair_count = 2, bad.nominal[1] = 1, bad.controller[1] = 0; /* a controller in two pairs */
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "share a controller"));
    bad = rec, bad.nominal[0] = 9; /* no such controller */
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "nominal");
    /* without the pair, the recovery law would drive the nominal's axes a second time */
    bad = rec, bad.pair_count = 0;
    assert_int_equal(td_model_set_recovery(m, &bad, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "already driven"));
    td_controller_free(&cont), td_controller_free(&slow), td_controller_free(&half);
    td_model_free(&m);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_switch_times_and_blend),
        cmocka_unit_test(test_disabled_takes_no_switch),
        cmocka_unit_test(test_two_pairs),
        cmocka_unit_test(test_model_rules),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
