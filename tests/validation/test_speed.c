/*
 * Speed transients (docs/theory.md, "Speed transients") against closed forms:
 *  - a free-free rigid rotor spun up from rest by a ramp: its mass centre stays put, so the
 *    journal centre runs round it, x = (U/m)(1 - cos phi), y = -(U/m) sin phi, which holds only
 *    with the unbalance's angular-acceleration term U alpha (sin, -cos)(phi + phase);
 *  - a free spin braked by a constant torque: Omega linear in time with the rotor's polar inertia
 *    rho pi L R^4 / 2; by a viscous drag: Omega exponential;
 *  - the reference rig run up slowly through its critical speeds: away from them the orbit is the
 *    steady unbalance response at the speed of the moment (the modal analysis' harmonic solve).
 */
#include "td_test.h"

#include "td_rig.h"

#include "touchdown/modal.h"
#include "touchdown/system.h"
#include "touchdown/touchdown.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#define LENGTH 0.2     /* m */
#define DIAMETER 0.1   /* m */
#define DENSITY 7810.0 /* kg/m^3 */

/* A one-element steel cylinder, lumped mass, no supports: a rigid body in translation when the
 * nodes are loaded equally. */
static td_model *free_rotor(double speed)
{
    td_model *m = NULL;
    td_shaft_element el = {LENGTH, DIAMETER, 0.0, {2.11e11, 8.1e10, DENSITY}};
    td_shaft_options so = {TD_BEAM_EULER_BERNOULLI, TD_MASS_LUMPED, 0.0, 0.0, TD_SHEAR_HUTCHINSON, 0.0};
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_set_shaft_options(m, &so, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_set_speed(m, speed, NULL), TD_OK);
    return m;
}

/* Tight tolerances: the velocity tolerance scales with the highest natural frequency, which on
 * this stubby free-free element is some 1e6 rad/s (tolerance.c td_sim_set_tolerances) */
static td_sim *start(const td_model *m)
{
    td_sim_options o;
    td_sim *sim = NULL;
    td_error err;
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = 1e-12;
    o.solver.atol = 1e-17;
    if (td_model_validate(m, &err) != TD_OK || td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("%s", err.message);
    return sim;
}

static void step_to(td_sim *sim, double t_end)
{
    double t = td_sim_time(sim);
    td_error err;
    while (t < t_end)
        if (td_sim_step(sim, t_end, &t, &err) != TD_OK)
            fail_msg("step: %s", err.message);
}

static void test_spin_up_keeps_mass_centre(void **state)
{
    const double U = 1e-3, alpha = 800.0; /* kg m, rad/s^2: 0 to 400 rad/s in 0.5 s */
    const double mass = DENSITY * TD_PI / 4.0 * DIAMETER * DIAMETER * LENGTH;
    const double times[4] = {0.1, 0.25, 0.4, 0.5};
    td_model *m = free_rotor(0.0);
    td_unbalance u0 = {0, 0.5 * U, 0.0}, u1 = {1, 0.5 * U, 0.0};
    td_speed_point p0 = {0.0, 0.0}, p1 = {0.5, 0.5 * alpha};
    td_sim *sim;
    double worst = 0.0, q[8], v[8];
    int i, node;
    (void)state;
    assert_int_equal(td_model_add_unbalance(m, &u0, NULL), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, &u1, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p0, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p1, NULL), TD_OK);
    sim = start(m);
    for (i = 0; i < 4; i++) {
        double phi = 0.5 * alpha * times[i] * times[i];
        step_to(sim, times[i]);
        assert_int_equal(td_sim_get_state(sim, q, v), TD_OK);
        assert_close(td_sim_speed(sim), alpha * times[i], 1e-14, 0.0);
        for (node = 0; node < 2; node++) {
            worst = fmax(worst, fabs(q[TD_DOF(node, TD_DOF_X)] - U / mass * (1.0 - cos(phi))));
            worst = fmax(worst, fabs(q[TD_DOF(node, TD_DOF_Y)] + U / mass * sin(phi)));
        }
    }
    print_message("spin-up from rest: journal centre against the closed form within %.3g m (U/m = %.3g m)\n", worst,
                  U / mass);
    /* measured 1.5e-11 m (6.6e-9 m at rtol 1e-9, atol 1e-13: it follows the tolerances); without
     * the alpha term the error is of order U/m */
    assert_true(worst <= 1e-6 * U / mass);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* Worst deviation of the journal centre from the free-free closed form x = (U/m)(1 - cos phi),
 * y = -(U/m) sin phi (the mass centre at rest) and of its velocity, over the samples `times`, of a
 * rotor spun up by the ramp `p` (two points, then held) with the largest step `max_step`. */
static void ramp_drift(double max_step, const td_speed_point p[2], const double *times, int n, double *dq, double *dv)
{
    const double U = 1e-3, mass = DENSITY * TD_PI / 4.0 * DIAMETER * DIAMETER * LENGTH;
    td_model *m = free_rotor(0.0);
    td_unbalance u0 = {0, 0.5 * U, 0.0}, u1 = {1, 0.5 * U, 0.0};
    td_sim_options o;
    td_sim *sim = NULL;
    td_error err;
    double q[8], v[8];
    int i, node;
    assert_int_equal(td_model_add_unbalance(m, &u0, NULL), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, &u1, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p[0], NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p[1], NULL), TD_OK);
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = 1e-6;
    o.solver.atol = 1e-9;
    o.solver.max_step = max_step;
    if (td_model_validate(m, &err) != TD_OK || td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("%s", err.message);
    *dq = *dv = 0.0;
    for (i = 0; i < n; i++) {
        double phi, w = td_model_speed_at(m, times[i], NULL, &phi);
        step_to(sim, times[i]);
        assert_int_equal(td_sim_get_state(sim, q, v), TD_OK);
        for (node = 0; node < 2; node++) {
            *dq = fmax(*dq, hypot(q[TD_DOF(node, TD_DOF_X)] - U / mass * (1.0 - cos(phi)),
                                  q[TD_DOF(node, TD_DOF_Y)] + U / mass * sin(phi)) /
                                (U / mass));
            *dv = fmax(*dv, hypot(v[TD_DOF(node, TD_DOF_X)] - U / mass * w * sin(phi),
                                  v[TD_DOF(node, TD_DOF_Y)] + U / mass * w * cos(phi)) /
                                (U / mass * w));
        }
    }
    td_sim_free(&sim);
    td_model_free(&m);
}

/* The step that ends on a ramp point: its unbalance force must carry the segment's own U alpha.
 * With the next segment's alpha (0 once the speed is held) over that step h, the rotor's momentum
 * is short by U alpha h and the free-free rotor drifts off at U alpha h / m for ever after: the
 * mass centre's closed form (the unbalance force integrated analytically) exposes it, and the error
 * would scale with the step, not the tolerance. */
static void test_ramp_point_keeps_momentum(void **state)
{
    const double T = 0.005; /* 0 to 400 rad/s in T (80000 rad/s^2, alpha/Omega = 200/s at T) */
    const double times[6] = {0.6 * T, 0.9 * T, T, 1.1 * T, 1.2 * T, 1.4 * T};
    const td_speed_point p[2] = {{0.0, 0.0}, {T, 400.0}};
    const double steps[2] = {1e-6, 4e-6}; /* both bind: the tolerance alone would take longer steps */
    double dq[2], dv[2];
    int i;
    (void)state;
    for (i = 0; i < 2; i++) {
        ramp_drift(steps[i], p, times, 6, &dq[i], &dv[i]);
        print_message("held after a ramp, max step %.0e s: mass centre off by %.3g U/m, its velocity by %.3g U w/m\n",
                      steps[i], dq[i], dv[i]);
    }
    /* measured 3e-7 and 4e-6 (position), 3e-7 and 4e-6 (velocity); with the next segment's alpha
     * over the step that ends on the point the velocity was off by up to (alpha/Omega) h: 1e-4 and
     * 4e-4, four times more at four times the step */
    for (i = 0; i < 2; i++) {
        assert_true(dq[i] < 2e-5);
        assert_true(dv[i] < 2e-5);
    }
}

/* The speed a run reports during a ramp (td_sim_speed: the samples' speed column, the final speed)
 * is the prescribed profile's, to rounding, at the default tolerances: the rig held at 50 rad/s,
 * then ramped at 10 rad/s^2 from t = 1 s as in cases/run-up.cfg, sampled every 5 ms. */
static void test_ramp_speed_sampled_exactly(void **state)
{
    td_model *m = td_test_rig_create(50.0, TD_RIG_TAU, TD_RIG_NO_RETAINERS);
    td_unbalance u = {1, 5e-3, 0.0};
    td_speed_point p0 = {1.0, 50.0}, p1 = {21.0, 250.0};
    td_sim_options o;
    td_sim *sim = NULL;
    td_error err;
    double worst = 0.0;
    int i;
    (void)state;
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p0, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p1, NULL), TD_OK);
    td_sim_options_default(&o);
    o.start = TD_START_ORBIT;
    if (td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("%s", err.message);
    for (i = 1; i <= 300; i++) {
        double t = 0.005 * i, w = t < 1.0 ? 50.0 : 50.0 + 10.0 * (t - 1.0);
        step_to(sim, t);
        worst = fmax(worst, fabs(td_sim_speed(sim) - w) / w);
    }
    print_message("ramp: sampled speed against the profile within %.3g of the speed\n", worst);
    assert_true(worst <= 4.0 * DBL_EPSILON); /* the profile's own rounding */
    td_sim_free(&sim);
    td_model_free(&m);
}

/* The energy account is the machine's at the time reached, not at the integrator's last internal
 * step beyond it: a free-free rotor stopped inside a spin-up ramp holds J Omega^2 / 2 in its spin
 * and U^2 Omega^2 / (2 m) in its translation (the journal runs at U Omega / m round the still mass
 * centre), Omega = alpha t, and the balance closes to the tolerance. */
static void test_energy_at_time_reached(void **state)
{
    const double U = 1e-3, alpha = 800.0, t_end = 0.3, w = alpha * t_end;
    const double mass = DENSITY * TD_PI / 4.0 * DIAMETER * DIAMETER * LENGTH;
    td_model *m = free_rotor(0.0);
    td_unbalance u0 = {0, 0.5 * U, 0.0}, u1 = {1, 0.5 * U, 0.0};
    td_speed_point p0 = {0.0, 0.0}, p1 = {0.5, 0.5 * alpha};
    td_sim_options o;
    td_sim *sim = NULL;
    td_error err;
    td_energy e;
    double expect;
    (void)state;
    assert_int_equal(td_model_add_unbalance(m, &u0, NULL), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, &u1, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p0, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p1, NULL), TD_OK);
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = 1e-8;
    o.solver.atol = 1e-12;
    o.energy = 1;
    if (td_model_validate(m, &err) != TD_OK || td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("%s", err.message);
    step_to(sim, t_end);
    assert_int_equal(td_sim_energy(sim, &e), TD_OK);
    expect = 0.5 * td_model_polar_inertia(m) * w * w + 0.5 * U * U * w * w / mass;
    print_message("energy at %.2f s: kinetic %.12g J (closed form %.12g J), residual %.3g J\n", t_end, e.kinetic,
                  expect, e.residual);
    /* measured 2e-10 relative; taken at the step beyond t_end it was off by 2 alpha h / Omega */
    assert_close(e.kinetic, expect, 1e-8, 0.0);
    assert_true(fabs(e.residual) <= 1e-6 * expect);
    td_sim_free(&sim);
    td_model_free(&m);
}

static void test_coast_down(void **state)
{
    const double w0 = 300.0, T0 = 2.0, c = 0.01; /* rad/s, N m, N m s/rad */
    const double R = 0.5 * DIAMETER, J = DENSITY * TD_PI * LENGTH * R * R * R * R / 2.0;
    int viscous;
    (void)state;
    for (viscous = 0; viscous < 2; viscous++) {
        td_model *m = free_rotor(w0);
        td_spin sp = {1, 0.0, 0.0, viscous ? 0.0 : T0, viscous ? c : 0.0};
        td_sim *sim;
        double expect;
        assert_int_equal(td_model_set_spin(m, &sp, NULL), TD_OK);
        assert_close(td_model_polar_inertia(m), J, 1e-14, 0.0);
        sim = start(m);
        step_to(sim, 1.0);
        expect = viscous ? w0 * exp(-c / J) : w0 - T0 / J;
        print_message("coast-down (%s): Omega(1 s) = %.12g rad/s, closed form %.12g rad/s\n",
                      viscous ? "viscous" : "constant torque", td_sim_speed(sim), expect);
        assert_close(td_sim_speed(sim), expect, 1e-8, 0.0);
        td_sim_free(&sim);
        td_model_free(&m);
    }
}

/* The orbit radius at a node against the steady response at the ramp's present speed. */
static double steady_radius(const td_model *m, double speed, const td_unbalance *u, int node)
{
    td_system *sys = NULL;
    td_harmonic *h = NULL;
    td_orbit o;
    assert_int_equal(td_system_create(m, &sys, NULL), TD_OK);
    assert_int_equal(td_harmonic_compute(sys, speed, u, 1, &h, NULL), TD_OK);
    assert_int_equal(td_harmonic_orbit(h, node, &o), TD_OK);
    td_harmonic_free(&h);
    td_system_free(&sys);
    return o.major;
}

static void test_slow_run_up(void **state)
{
    /* 50 to 250 rad/s in 40 s (5 rad/s^2) through the rig's criticals near 118, 134 and 215 rad/s */
    const double speeds[5] = {60.0, 90.0, 160.0, 185.0, 250.0}, alpha = 5.0;
    td_model *m = td_test_rig_create(50.0, TD_RIG_TAU, TD_RIG_NO_RETAINERS);
    td_unbalance u = {5, 1e-3, 0.0};
    td_speed_point p0 = {0.0, 50.0}, p1 = {40.0, 250.0};
    td_sim *sim;
    int i, n = td_model_dof_count(m);
    double *q = calloc(2 * (size_t)n, sizeof *q), worst = 0.0;
    (void)state;
    assert_non_null(q);
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p0, NULL), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p1, NULL), TD_OK);
    {
        td_sim_options o;
        td_error err;
        td_sim_options_default(&o);
        o.start = TD_START_ORBIT; /* the steady orbit at 50 rad/s */
        if (td_sim_create(m, &o, &sim, &err) != TD_OK)
            fail_msg("%s", err.message);
    }
    for (i = 0; i < 5; i++) {
        /* 250 rad/s: 4 s after the ramp's end, for the 215 rad/s mode (zeta 0.015) to settle */
        double t = i < 4 ? (speeds[i] - 50.0) / alpha : 44.0, r, want;
        step_to(sim, t);
        assert_int_equal(td_sim_get_state(sim, q, q + n), TD_OK);
        assert_close(td_sim_speed(sim), speeds[i], 1e-12, 0.0);
        r = hypot(q[TD_DOF(5, TD_DOF_X)], q[TD_DOF(5, TD_DOF_Y)]);
        want = steady_radius(m, speeds[i], &u, 5);
        print_message("run-up at %.0f rad/s: disc orbit %.6g m, steady response %.6g m (%+.3f %%)\n", speeds[i], r,
                      want, 100.0 * (r / want - 1.0));
        worst = fmax(worst, fabs(r / want - 1.0));
    }
    assert_true(worst < 0.01);
    free(q);
    td_sim_free(&sim);
    td_model_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spin_up_keeps_mass_centre),
        cmocka_unit_test(test_ramp_point_keeps_momentum),
        cmocka_unit_test(test_ramp_speed_sampled_exactly),
        cmocka_unit_test(test_energy_at_time_reached),
        cmocka_unit_test(test_coast_down),
        cmocka_unit_test(test_slow_run_up),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
