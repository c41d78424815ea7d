/* The retainers' thermal networks (lib/sim/thermal.c, docs/theory.md "Thermal retainers"): the
 * closed-form step against the two-exponential solution derived independently (the unsymmetric
 * system's eigenvalues and eigenvectors), the single-node limit, the energy balance, and in a run
 * of the drop: the heat equal to friction_work + drag_work and held by an insulated network to
 * round-off, the same temperatures on two output grids, and across restarts inside a step. */
#include "td_test.h"

#include "sim/sim_internal.h"
#include "sim/thermal.h"
#include "touchdown/case.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const td_retainer_thermal bearing = {40.0, 500.0, 2.0, 1.5, 1.2e-5};

/* T(t) from rest under a constant heat P into the race, derived without the symmetric form: the
 * steady state T_ss = G^-1 e_r P and the modes of A = C^-1 G, s^2 - tr(A) s + det(A) = 0, with the
 * eigenvectors v(s) = (G_rh / C_r, G_rh / C_r - s), in long double. */
static void two_exponentials(const td_retainer_thermal *th, double P, double t, double T[2], double *lost)
{
    long double g = th->race_housing_conductance, ga = th->housing_ambient_conductance;
    long double cr = th->race_capacity, ch = th->housing_capacity;
    long double a = g / cr, tr = g / cr + (g + ga) / ch, det = g * ga / (cr * ch);
    long double s1 = 0.5L * tr + sqrtl(0.25L * tr * tr - det), s2 = det / s1;
    long double ss[2] = {P * (1.0L / ga + 1.0L / g), P / ga};
    long double v1[2] = {a, a - s1}, v2[2] = {a, a - s2};
    long double d = v1[0] * v2[1] - v1[1] * v2[0];
    long double c1 = (-ss[0] * v2[1] + ss[1] * v2[0]) / d, c2 = (-v1[0] * ss[1] + v1[1] * ss[0]) / d;
    int i;
    for (i = 0; i < 2; i++)
        T[i] = (double)(ss[i] + c1 * (i ? v1[1] : v1[0]) * expl(-s1 * t) + c2 * (i ? v2[1] : v2[0]) * expl(-s2 * t));
    /* G_ha times the integral of T_h from 0 to t: the heat the ambient took */
    *lost = (double)(ga * (ss[1] * t - c1 * v1[1] * expm1l(-s1 * t) / s1 - c2 * v2[1] * expm1l(-s2 * t) / s2));
}

/* Carry T from rest to each of the times under P with steps of random lengths (1e-4 s .. 20 s). */
static double worst_against_closed_form(const td_retainer_thermal *th, double P, double scale)
{
    static const double times[] = {0.5, 7.0, 60.0, 600.0, 3600.0, 36000.0};
    td_thermal_network n;
    double T[2] = {0.0, 0.0}, t = 0.0, worst = 0.0, ref[2], lost, balance;
    uint64_t seed = 29;
    int i;
    td_thermal_network_init(&n, th);
    for (i = 0; i < 6; i++) {
        while (t < times[i]) {
            double u = (double)(td_test_splitmix(&seed) >> 11) / 9007199254740992.0;
            double h = fmin(times[i] - t, 1e-4 * pow(2e5, u));
            td_thermal_network_step(&n, T, h, P, P);
            t = t + h == t ? times[i] : t + h;
        }
        two_exponentials(th, P, times[i], ref, &lost);
        worst = fmax(worst, fmax(fabs(T[0] - ref[0]), fabs(T[1] - ref[1])) / scale);
        /* the energy balance: C_r T_r + C_h T_h + G_ha int T_h dt = P t */
        balance = th->race_capacity * T[0] + th->housing_capacity * T[1] + lost;
        assert_close(balance, P * times[i], 1e-12, 0.0);
        print_message("t = %8g s: T_r %.15g (closed form %.15g), T_h %.15g (%.15g) K\n", times[i], T[0], ref[0], T[1],
                      ref[1]);
    }
    return worst;
}

/* A constant heat input: the network's steps reproduce the two-exponential approach to round-off
 * (the steady rise P (1/G_ha + 1/G_rh) is the scale). */
static void test_constant_heat_two_exponentials(void **state)
{
    double P = 100.0, worst = worst_against_closed_form(&bearing, P, P * (1.0 / 1.5 + 1.0 / 2.0));
    (void)state;
    print_message("worst |T - closed form| / T_ss = %.3g\n", worst);
    assert_true(worst < 1e-12);
}

/* A race bonded to its housing (G_rh 1e8 times the rest): one node of capacity C_r + C_h behind
 * G_ha, T = P / G_ha (1 - exp(-G_ha t / (C_r + C_h))), to O(G_ha / G_rh). */
static void test_single_node_limit(void **state)
{
    td_retainer_thermal th = bearing;
    td_thermal_network n;
    double P = 100.0, T[2] = {0.0, 0.0}, t = 0.0, worst = 0.0;
    int i;
    (void)state;
    th.race_housing_conductance = 2e8;
    td_thermal_network_init(&n, &th);
    for (i = 0; i < 400; i++) {
        double h = 0.5 + (i % 7), ref;
        td_thermal_network_step(&n, T, h, P, P);
        t += h;
        ref = P / 1.5 * -expm1(-1.5 * t / 540.0);
        worst = fmax(worst, fmax(fabs(T[0] - ref), fabs(T[1] - ref)) / (P / 1.5));
    }
    print_message("bonded race: worst |T - one node| / (P / G_ha) = %.3g over %g s\n", worst, t);
    assert_true(worst < 1e-7);
    /* and the stiff network still meets the two exponentials */
    assert_true(worst_against_closed_form(&th, P, P / 1.5) < 1e-12);
}

/* An insulated housing (G_ha = 0, one eigenvalue 0): under a heat linear over each segment (random
 * powers at random times) C_r T_r + C_h T_h is the trapezoidal heat to round-off; a step taken back
 * (h < 0) returns to where it started. */
static void test_energy_balance_and_back_step(void **state)
{
    td_retainer_thermal th = bearing;
    td_thermal_network n;
    double T[2] = {0.0, 0.0}, heat = 0.0, p0 = 0.0, worst_back = 0.0, held;
    uint64_t seed = 7;
    int i;
    (void)state;
    th.housing_ambient_conductance = 0.0;
    td_thermal_network_init(&n, &th);
    for (i = 0; i < 5000; i++) {
        double u = (double)(td_test_splitmix(&seed) >> 11) / 9007199254740992.0;
        double h = 1e-5 * pow(1e6, u), p1 = 2000.0 * u * u, before[2] = {T[0], T[1]};
        td_thermal_network_step(&n, T, h, p0, p1);
        heat += 0.5 * h * (p0 + p1);
        if (h < 0.2) { /* back over the segment (far into the fast mode the round-off grows as exp(lambda h)) */
            double back[2] = {T[0], T[1]};
            td_thermal_network_step(&n, back, -h, p1, p0);
            worst_back = fmax(worst_back, fmax(fabs(back[0] - before[0]), fabs(back[1] - before[1])));
        }
        p0 = p1;
    }
    held = th.race_capacity * T[0] + th.housing_capacity * T[1];
    print_message("insulated: heat %.17g J, held %.17g J; worst back step %.3g K at T_r = %.6g K\n", heat, held,
                  worst_back, T[0]);
    assert_close(held, heat, 5e-12, 0.0);
    assert_true(worst_back < 1e-12 * T[0]);
}

/* A heat linear in time: one step over h is 1000 steps over h / 1000 with the heat at their ends on
 * the same line (the exact solution of a linear system composes), from a warm start, for steps
 * short and long against the network's time constants (1 s to 1e4 s here). */
static void test_linear_heat_subdivides(void **state)
{
    static const double lengths[] = {0.01, 3.0, 400.0, 20000.0};
    td_thermal_network n;
    int i, j;
    (void)state;
    td_thermal_network_init(&n, &bearing);
    for (i = 0; i < 4; i++) {
        double h = lengths[i], p0 = 30.0, p1 = 250.0, one[2] = {12.0, 3.0}, many[2] = {12.0, 3.0};
        td_thermal_network_step(&n, one, h, p0, p1);
        for (j = 0; j < 1000; j++)
            td_thermal_network_step(&n, many, h / 1000.0, p0 + (p1 - p0) * j / 1000.0,
                                    p0 + (p1 - p0) * (j + 1) / 1000.0);
        print_message("h = %g s: T_r %.15g in one step, %.15g in 1000\n", h, one[0], many[0]);
        assert_close(many[0], one[0], 1e-12, 0.0);
        assert_close(many[1], one[1], 1e-12, 0.0);
    }
}

/* ---- in a run ------------------------------------------------------------------------------ */

/* The drop with both retainers given a network; G_ha as `ambient`. */
static td_case *drop_with_networks(const char *ambient)
{
    char ov[2][256];
    const char *ovs[2];
    int k;
    for (k = 0; k < 2; k++) {
        snprintf(ov[k], sizeof ov[k],
                 "retainers[%d].thermal = { race_capacity = 0.08; housing_capacity = 2.0; "
                 "race_housing_conductance = 0.5; housing_ambient_conductance = %s; expansion = 1.2e-5; }",
                 k, ambient);
        ovs[k] = ov[k];
    }
    return td_test_load_case("cases/drop.cfg", ovs, 2);
}

/* Step s to t through its events. */
static void step_to(td_sim *s, double t)
{
    td_error err;
    td_status r;
    while ((r = td_sim_step(s, t, NULL, &err)) == TD_EVENT)
        continue;
    if (r != TD_OK)
        fail_msg("td_sim_step to %g s: %s", t, err.message);
}

/* The insulated networks hold the heat: C_r T_r + C_h T_h = heat = friction_work + drag_work at
 * the end (an output inside the integrator's last step), after restarts made at outputs inside
 * steps every 5 ms of the fall (the totals and the networks taken back there). */
static void test_run_heat_held(void **state)
{
    td_case *c = drop_with_networks("0.0");
    td_sim *s = NULL;
    int k, i, restarts = 0;
    double worst_jump = 0.0;
    (void)state;
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, NULL), TD_OK);
    for (i = 1; i <= 150; i++) {
        step_to(s, i * 1e-3);
        if (i > 50 && i % 5 == 0 && s->monitor.totals_t > s->dae.t) { /* a change inside the step */
            td_retainer_state a, b;
            td_unbalance u;
            td_model_get_unbalance(td_case_model(c), 0, &u);
            td_sim_retainer_state(s, 0, &a);
            assert_int_equal(td_sim_set_unbalance(s, 0, u.magnitude, u.phase, NULL), TD_OK);
            td_sim_retainer_state(s, 0, &b);
            worst_jump = fmax(worst_jump, fabs(b.race_temperature - a.race_temperature));
            restarts++;
        }
    }
    for (k = 0; k < 2; k++) {
        td_retainer_totals t;
        td_retainer_state rs;
        assert_int_equal(td_sim_retainer_totals(s, k, &t), TD_OK);
        assert_int_equal(td_sim_retainer_state(s, k, &rs), TD_OK);
        print_message("retainer %d at %g s: friction %.9g J, drag %.9g J, heat %.9g J, held %.9g J; T_r %.6g K, "
                      "T_h %.6g K, peak %.6g K, growth %.3g m\n",
                      k, s->dae.t, t.friction_work, t.drag_work, t.heat,
                      0.08 * rs.race_temperature + 2.0 * rs.housing_temperature, rs.race_temperature,
                      rs.housing_temperature, t.peak_temperature_rise, t.peak_thermal_growth);
        assert_true(t.friction_work > 0.0 && t.drag_work > 0.0);
        assert_true(t.heat == t.friction_work + t.drag_work);
        assert_close(0.08 * rs.race_temperature + 2.0 * rs.housing_temperature, t.heat, 1e-11, 0.0);
        assert_true(t.peak_temperature_rise >= rs.race_temperature);
        assert_close(t.peak_thermal_growth, 1.2e-5 * s->contacts.ret[k].r.bore_radius * t.peak_temperature_rise, 1e-15,
                     0.0);
    }
    print_message("%d restarts inside a step: the race's rise moved by at most %.3g K across them\n", restarts,
                  worst_jump);
    assert_true(restarts >= 10);
    assert_true(worst_jump <= 1e-12);
    td_sim_free(&s);
    td_case_free(&c);
}

/* The outputs do not steer the integrator: on outputs every 1 ms and every 0.25 ms the rises at the
 * common times agree to round-off, though most outputs fall inside a step (taken back there). */
static void test_rises_independent_of_outputs(void **state)
{
    td_case *c = drop_with_networks("0.02");
    td_sim *a = NULL, *b = NULL;
    double worst = 0.0, top = 0.0;
    int i, j, inside = 0;
    (void)state;
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &a, NULL), TD_OK);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &b, NULL), TD_OK);
    for (i = 1; i <= 120; i++) {
        td_retainer_state ra, rb;
        int k;
        step_to(a, i * 1e-3);
        for (j = 1; j <= 4; j++)
            step_to(b, (4 * (i - 1) + j) * 2.5e-4);
        inside += a->monitor.totals_t > a->dae.t;
        for (k = 0; k < 2; k++) {
            td_sim_retainer_state(a, k, &ra);
            td_sim_retainer_state(b, k, &rb);
            worst = fmax(worst, fmax(fabs(ra.race_temperature - rb.race_temperature),
                                     fabs(ra.housing_temperature - rb.housing_temperature)));
            top = fmax(top, ra.race_temperature);
        }
    }
    print_message("two output grids: worst difference %.3g K at rises up to %.6g K, %d of 120 outputs inside a step\n",
                  worst, top, inside);
    assert_true(top > 0.0 && inside > 60);
    assert_true(worst <= 1e-12 * top);
    td_sim_free(&a);
    td_sim_free(&b);
    td_case_free(&c);
}

/* A retainer without a network (rub-damped.cfg's, races with drag, in contact after the unbalance
 * step at 0.1 s): its temperatures and peak are undefined, never 0; its heat still counted. */
static void test_no_network_undefined(void **state)
{
    td_case *c = td_test_load_case("cases/rub-damped.cfg", NULL, 0);
    td_sim *s = NULL;
    td_retainer_state rs;
    td_retainer_totals t;
    (void)state;
    assert_int_equal(td_model_get_retainer_thermal(td_case_model(c), 0, NULL), 0);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, NULL), TD_OK);
    step_to(s, 0.2);
    td_sim_retainer_state(s, 0, &rs);
    td_sim_retainer_totals(s, 0, &t);
    assert_true(td_is_undefined(rs.race_temperature) && td_is_undefined(rs.housing_temperature));
    assert_true(td_is_undefined(t.peak_temperature_rise) && td_is_undefined(t.peak_thermal_growth));
    assert_true(t.drag_work > 0.0 && t.heat == t.friction_work + t.drag_work);
    td_sim_free(&s);
    td_case_free(&c);
}

/* The model's setter checks each value and names the field. */
static void test_model_api(void **state)
{
    td_model *m = NULL;
    td_retainer r = {.node = 0, .clearance = 1e-3, .shaft_radius = 0.02, .bore_radius = 0.021, .friction = 0.1};
    td_retainer_thermal th = bearing, got;
    td_error err;
    (void)state;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_set_retainer_thermal(m, 0, &th, &err), TD_ERR_INVALID); /* no retainer yet */
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    th.housing_capacity = -1.0;
    assert_int_equal(td_model_set_retainer_thermal(m, 0, &th, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "thermal.housing_capacity"));
    th = bearing;
    th.expansion = TD_UNDEFINED;
    assert_int_equal(td_model_set_retainer_thermal(m, 0, &th, &err), TD_OK);
    assert_int_equal(td_model_get_retainer_thermal(m, 0, &got), 1);
    assert_true(got.race_capacity == 40.0 && td_is_undefined(got.expansion));
    assert_int_equal(td_model_get_retainer_thermal(m, 1, &got), 0);
    td_model_free(&m);
}

/* The closed-form step with the 20-term series of phi1, phi2 summed in full (thermal.c's series
 * before its early stop, written out again here): the early stop must give the same bits, at the
 * step lengths of a run (x = lambda h from 1e-12 up) and of the series' whole range (|x| < 0.5), both
 * signs of h (a step taken back). */
static void full_series(double x, double *phi1, double *phi2)
{
    double term1 = 1.0, term2 = 0.5, s1 = 0.0, s2 = 0.0;
    int k;
    for (k = 0; k < 20; k++) {
        s1 += term1;
        s2 += term2;
        term1 *= -x / (double)(k + 2);
        term2 *= -x / (double)(k + 3);
    }
    *phi1 = s1;
    *phi2 = s2;
}

static void step_full_series(const td_thermal_network *n, double T[2], double h, double p0, double p1)
{
    double u[2], z[2], b, phi1, phi2;
    int i;
    u[0] = sqrt(n->capacity[0]) * T[0];
    u[1] = sqrt(n->capacity[1]) * T[1];
    for (i = 0; i < 2; i++) {
        double x = n->lambda[i] * h;
        full_series(x, &phi1, &phi2);
        b = n->q[0][i] / sqrt(n->capacity[0]);
        z[i] = n->q[0][i] * u[0] + n->q[1][i] * u[1];
        z[i] = exp(-x) * z[i] + b * h * (p0 * (phi1 - phi2) + p1 * phi2);
    }
    T[0] = (n->q[0][0] * z[0] + n->q[0][1] * z[1]) / sqrt(n->capacity[0]);
    T[1] = (n->q[1][0] * z[0] + n->q[1][1] * z[1]) / sqrt(n->capacity[1]);
}

static void test_series_stop_same_bits(void **state)
{
    td_thermal_network n;
    double lmax;
    int i, sign;
    (void)state;
    td_thermal_network_init(&n, &bearing);
    lmax = fmax(n.lambda[0], n.lambda[1]);
    for (sign = -1; sign <= 1; sign += 2)
        for (i = 0; i <= 240; i++) {
            /* x = lambda_max h from 1e-12 to just under 0.5, 20 steps a decade */
            double x = fmin(1e-12 * pow(10.0, i / 20.0), 0.4999), h = sign * x / lmax;
            double a[2] = {3.25, 1.5}, b[2] = {3.25, 1.5};
            td_thermal_network_step(&n, a, h, 120.0, 80.0);
            step_full_series(&n, b, h, 120.0, 80.0);
            if (memcmp(a, b, sizeof a) != 0)
                fail_msg("h = %.17g s: T = (%.17g, %.17g), the full series (%.17g, %.17g)", h, a[0], a[1], b[0], b[1]);
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constant_heat_two_exponentials),
        cmocka_unit_test(test_series_stop_same_bits),
        cmocka_unit_test(test_single_node_limit),
        cmocka_unit_test(test_energy_balance_and_back_step),
        cmocka_unit_test(test_linear_heat_subdivides),
        cmocka_unit_test(test_model_api),
        cmocka_unit_test(test_no_network_undefined),
        cmocka_unit_test(test_run_heat_held),
        cmocka_unit_test(test_rises_independent_of_outputs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
