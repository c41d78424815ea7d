/*
 * The closed-form free flight with races as bodies (lib/sim/flight.c, flight_modal.c, flight_race.c)
 * on cases/rub-damped.cfg: ball-bearing retainers, each race on a damped mount (its x, y among the
 * modal states) and spinning under its drag torque and viscous drag (its speed and angle carried
 * piecewise in closed form), a compliant contact, the rotor on its AMBs.
 *
 * 1. The same free interval by two methods: the races are set ringing on their mounts and spinning
 *    (one from 10 rad/s, so that it reaches the drag's regularisation band and decays inside it,
 *    one from -300 rad/s, outside the band all along), and the machine runs 0.09 s free, once in
 *    the flight, and by IDA with the flight off at 1e-3 and 1e-5 of the case's tolerances. At nine
 *    points, dense while the races ring, the races' centres, velocities, speeds and angles and the
 *    retainer nodes of IDA converge on the flight's (closer at the tighter tolerances) and agree
 *    with them there (centres and nodes to the case's atol).
 * 2. The first contact (after the unbalance step at 0.1 s): the flight's time against IDA's at a
 *    thousandth of the tolerances, the case's own IDA run printed for scale.
 */
#include "td_test.h"

#include "sim/sim_internal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define T_FREE 0.09 /* s: the interval of test 1 (the unbalance step comes at 0.1 s) */
#define POINTS 9
/* s: the points of test 1, dense while the races ring on their mounts (2.5 kHz, decaying at 2.5e3 1/s) */
static const double point[POINTS] = {1e-4, 2e-4, 4e-4, 8e-4, 1.6e-3, 3.2e-3, 1e-2, 5e-2, T_FREE};

/* What test 1 compares at each point: per retainer the race's x, y, vx, vy, speed, angle and the
 * node's x, y relative to the race. */
#define VALUES 8

static td_sim *create(const td_case *c, int flight, double tighter)
{
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_error err;
    o.solver.free_flight = flight;
    o.solver.rtol /= tighter;
    o.solver.atol /= tighter;
    if (td_sim_create(td_case_model(c), &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    return s;
}

/* The races set ringing and spinning (test 1's start), the integrator restarted there. */
static void kick_races(td_sim *s)
{
    double *y = N_VGetArrayPointer(s->dae.y);
    const double speed[2] = {10.0, -300.0};
    int k;
    for (k = 0; k < 2; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        assert_true(r->rx >= 0 && r->rs >= 0);
        y[s->dae.oq + r->rx] += 2e-5 * (k ? -1.0 : 1.0);
        y[s->dae.ov + r->ry] += 0.01;
        y[s->dae.ov + r->rs] = speed[k];
    }
    assert_int_equal(td_sim_restart_between_steps(s), TD_OK);
}

static void values(const td_sim *s, double *out)
{
    const double *y = N_VGetArrayPointer(s->dae.y);
    int k;
    for (k = 0; k < 2; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double *o = out + VALUES * k, vx, vy;
        o[0] = y[s->dae.oq + r->rx];
        o[1] = y[s->dae.oq + r->ry];
        o[2] = y[s->dae.ov + r->rx];
        o[3] = y[s->dae.ov + r->ry];
        o[4] = y[s->dae.ov + r->rs];
        o[5] = y[s->dae.oq + r->rs];
        td_sim_node_state(s, k, y, &o[6], &o[7], &vx, &vy);
    }
}

/* Run s to each point, the values at each into out (POINTS x 2 VALUES). */
static void run_free(td_sim *s, double *out, td_sim_stats *st)
{
    td_error err;
    double t = 0.0;
    int i;
    for (i = 0; i < POINTS; i++) {
        double tout = point[i];
        while (t < tout) {
            td_status r = td_sim_step(s, tout, &t, &err);
            if (r != TD_OK && r != TD_EVENT)
                fail_msg("td_sim_step: %s", err.message);
        }
        values(s, out + 2 * VALUES * i);
    }
    assert_int_equal(td_sim_stats_get(s, st), TD_OK);
}

/* Largest |a - b| of value v over every point and retainer. */
static double worst(const double *a, const double *b, int v)
{
    double w = 0.0;
    int i;
    for (i = 0; i < 2 * POINTS; i++)
        w = fmax(w, fabs(a[VALUES * i + v] - b[VALUES * i + v]));
    return w;
}

/* The largest differences of each kind (centres, velocities, speeds, angles, nodes) into d[5]. */
static void differences(const double *a, const double *b, double d[5])
{
    d[0] = fmax(worst(a, b, 0), worst(a, b, 1));
    d[1] = fmax(worst(a, b, 2), worst(a, b, 3));
    d[2] = worst(a, b, 4);
    d[3] = worst(a, b, 5);
    d[4] = fmax(worst(a, b, 6), worst(a, b, 7));
}

static void test_races_fly_as_integrated(void **state)
{
    const char *ov[1] = {"end_time=0.1"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ov, 1);
    double atol = td_case_sim_options(c)->solver.atol, f[2 * VALUES * POINTS], i[2 * VALUES * POINTS];
    double d3[5], d5[5], *last = f + 2 * VALUES * (POINTS - 1);
    const double tighter[2] = {1e3, 1e5};
    td_sim_stats sf, si;
    td_sim *s;
    int k;
    (void)state;
    s = create(c, 1, 1.0);
    kick_races(s);
    run_free(s, f, &sf);
    td_sim_free(&s);
    for (k = 0; k < 2; k++) {
        s = create(c, 0, tighter[k]);
        kick_races(s);
        run_free(s, i, &si);
        td_sim_free(&s);
        differences(f, i, k ? d5 : d3);
        assert_int_equal(si.contact_onsets, 0);
        assert_int_equal(si.flight_steps, 0);
    }
    print_message(
        "races free to %.2g s: flight %ld steps (%.4f s), race speeds at the end %.3g and %.6g rad/s; flight vs "
        "integrator at tolerances / 1e3 and / 1e5: centres %.3g, %.3g m, velocities %.3g, %.3g m/s, speeds "
        "%.3g, %.3g rad/s, angles %.3g, %.3g rad, nodes %.3g, %.3g m\n",
        T_FREE, sf.flight_steps, sf.flight_time, last[4], last[VALUES + 4], d3[0], d5[0], d3[1], d5[1], d3[2], d5[2],
        d3[3], d5[3], d3[4], d5[4]);
    assert_int_equal(sf.contact_onsets, 0);
    assert_true(sf.flight_time > 0.99 * T_FREE); /* the flight carried it all */
    /* race 0 reached the band (w_b = v_reg / R_b ~ 4e-3 rad/s) and decayed inside it; race 1 did not */
    assert_true(fabs(last[4]) < 1e-3);
    assert_true(last[VALUES + 4] < -280.0);
    for (k = 0; k < 5; k++) /* IDA converges on the flight's values */
        assert_true(d5[k] < 0.5 * d3[k]);
    assert_true(d5[0] <= atol && d5[4] <= atol);
    assert_true(d5[1] <= 1e-5); /* the races ring at 0.3 m/s */
    assert_true(d5[2] <= 1e-9 && d5[3] <= 1e-10);
    td_case_free(&c);
}

/* The first contact's time of the case run to 0.11 s. */
static double first_contact(const td_case *c, int flight, double tighter, td_sim_stats *st)
{
    td_sim *s = create(c, flight, tighter);
    td_error err;
    double t = 0.0;
    while (t < 0.11) {
        td_status r = td_sim_step(s, 0.11, &t, &err);
        if (r != TD_OK && r != TD_EVENT)
            fail_msg("td_sim_step: %s", err.message);
        if (td_sim_stats_get(s, st) == TD_OK && st->contact_onsets > 0)
            break;
    }
    assert_int_equal(td_sim_stats_get(s, st), TD_OK);
    td_sim_free(&s);
    return st->first_contact_time;
}

static void test_first_contact_with_races(void **state)
{
    const char *ov[1] = {"end_time=0.11"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ov, 1);
    td_sim_stats sf, si, sc;
    double tf, ti, tc;
    (void)state;
    tf = first_contact(c, 1, 1.0, &sf);
    ti = first_contact(c, 0, 1000.0, &si);
    tc = first_contact(c, 0, 1.0, &sc);
    print_message("first contact with races: %.15g s (flight, %ld steps, %.6f s flown), %.15g s (integrator at "
                  "tolerances / 1000), %.15g s (integrator at the case's tolerances)\n",
                  tf, sf.flight_steps, sf.flight_time, ti, tc);
    assert_true(sf.contact_onsets > 0 && si.contact_onsets > 0);
    assert_true(sf.flight_time > 0.1);
    assert_true(fabs(tf - ti) <= 1e-9);
    td_case_free(&c);
}

/* A saturating AMB that has failed exerts nothing and integrates nothing (model/amb.c): its clip is
 * no kink, and the flight carries the machine (here rub-damped with AMB 1 saturating, failed from
 * the start, a plain bearing at its node instead): the state at 0.09 s against IDA's at 1e-5 of the
 * tolerances. */
static void test_failed_saturating_amb_flies(void **state)
{
    const char *ov[4] = {"end_time=0.1", "ambs[1].saturation = true",
                         "bearings = ( { node = 9; kxx = 1.0e6; cxx = 200.0; } )",
                         "schedule = ( { time = 0.0; amb_off = 1; } )"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ov, 4);
    double atol = td_case_sim_options(c)->solver.atol, f[2 * VALUES * POINTS], i[2 * VALUES * POINTS], d[5];
    td_sim_stats sf, si;
    td_sim *s;
    (void)state;
    s = create(c, 1, 1.0);
    assert_int_equal(td_sim_amb_mode(s, 1), TD_AMB_OFF);
    run_free(s, f, &sf);
    td_sim_free(&s);
    s = create(c, 0, 1e5);
    run_free(s, i, &si);
    td_sim_free(&s);
    differences(f, i, d);
    print_message(
        "AMB 1 saturating and failed: flight %ld steps (%.4f s); nodes %.3g m from IDA's at tolerances / 1e5\n",
        sf.flight_steps, sf.flight_time, d[4]);
    assert_int_equal(sf.contact_onsets, 0);
    assert_true(sf.flight_time > 0.99 * T_FREE);
    assert_true(d[4] <= atol);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_races_fly_as_integrated),
        cmocka_unit_test(test_first_contact_with_races),
        cmocka_unit_test(test_failed_saturating_amb_flies),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
