/*
 * The housing's prescribed motion in the simulation (touchdown/housing.h, docs/theory.md "Base
 * motion"), against references outside the code:
 *   - a rigid rotor on two PD AMBs, spinning at Omega, whose housing turns at a constant rate w
 *     (after a ramp): the bearings must turn its angular momentum Ip Omega with the housing, a couple
 *     of moment Ip Omega w (dH/dt = w x H), so in the steady state the AMB forces are +-Ip Omega w / L
 *     (statics of the rigid body: L the bearings' span), whatever the gains;
 *   - a shock that drives the rig into its retainers with the energy account on: the balance closes
 *     to the integrator's tolerance once the work of the housing's loads is booked, and it would miss
 *     by that work if it were not.
 */
#include "td_rig.h"
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <string.h>

#define SPAN 0.2 /* m, between the AMBs */

/* A short stiff shaft (4 elements, 100 mm diameter) with a disc of large Ip at mid-span on two
 * collocated lag-free PD AMBs at its ends, at speed omega. */
static td_model *rigid_rotor(double omega)
{
    td_model *m = NULL;
    td_shaft_element el = {SPAN / 4.0, 0.1, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_disc d = {2, 20.0, 0.6, 0.35};
    td_amb a = {0, 0, 1.0e5, 100.0, 1.2e4, 20.0, 0.0, 1.0e4, 0, 0.0, 0.0, 0.0};
    int i;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    for (i = 0; i < 4; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &d, NULL), TD_OK);
    assert_int_equal(td_model_add_amb(m, &a, NULL), TD_OK);
    a.node = a.sensor_node = 4;
    assert_int_equal(td_model_add_amb(m, &a, NULL), TD_OK);
    assert_int_equal(td_model_set_speed(m, omega, NULL), TD_OK);
    return m;
}

static td_sim *new_sim(const td_model *m, double rtol, double atol, int energy)
{
    td_sim_options o;
    td_sim *s = NULL;
    td_error err;
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = rtol;
    o.solver.atol = atol;
    o.energy = energy;
    if (td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    return s;
}

/* Pitch and yaw rates (about x and y) ramped up over 50 ms and held: the steady AMB forces. */
static void test_constant_rotation_rate(void **state)
{
    const double omega = 150.0, wx = 0.4, wy = 0.25;
    td_model *m = rigid_rotor(omega);
    td_housing_pulse p = {TD_PULSE_RAMP, wx, 0.05, 0.01, {1.0, 0.0}};
    double f0[2], f1[2], couple_x, couple_y, ip = td_model_polar_inertia(m);
    td_sim *s;
    (void)state;
    assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
    p.amplitude = wy, p.direction[0] = 0.0, p.direction[1] = 1.0;
    assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
    s = new_sim(m, 1e-10, 1e-14, 0);
    td_test_step_to(s, 0.8); /* the closed loop's slowest mode decays within ~0.1 s */
    assert_int_equal(td_sim_amb_force(s, 0, f0), TD_OK);
    assert_int_equal(td_sim_amb_force(s, 1, f1), TD_OK);
    /* about x: dH/dt = w_x e_x x Ip Omega e_z = -Ip Omega w_x e_y, the moment the bearings give:
     * z F_x summed = -Ip Omega w_x with F_x0 + F_x1 = 0, so F_x1 = -Ip Omega w_x / L at z = L; about y
     * likewise +Ip Omega w_y e_x = -z F_y summed, F_y1 = -Ip Omega w_y / L */
    couple_x = -ip * omega * wx / SPAN;
    couple_y = -ip * omega * wy / SPAN;
    print_message("AMB forces at 0.8 s: (%.12g, %.12g) N and (%.12g, %.12g) N; closed form +-(%.12g, %.12g) N\n", f0[0],
                  f0[1], f1[0], f1[1], couple_x, couple_y);
    assert_close(f1[0], couple_x, 1e-6, 0.0);
    assert_close(f1[1], couple_y, 1e-6, 0.0);
    assert_close(f0[0], -couple_x, 1e-6, 0.0);
    assert_close(f0[1], -couple_y, 1e-6, 0.0);
    td_sim_free(&s);
    td_model_free(&m);
}

/* The gyroscopic load follows the speed when it varies: a speed ramp from 100 to 200 rad/s (held
 * after 0.2 s) and a free spin at 150 rad/s (no torque on it: its speed stays), each under a steady
 * pitch rate: the couple is Ip Omega w / L at the speed of the end. */
static void test_varying_speed(void **state)
{
    const double w = 0.4;
    int k;
    (void)state;
    for (k = 0; k < 2; k++) {
        td_model *m = rigid_rotor(k == 0 ? 100.0 : 150.0);
        td_housing_pulse p = {TD_PULSE_RAMP, w, 0.05, 0.01, {1.0, 0.0}};
        td_speed_point a = {0.0, 100.0}, b = {0.2, 200.0};
        td_spin sp;
        double f1[2], omega = k == 0 ? 200.0 : 150.0;
        td_sim *s;
        memset(&sp, 0, sizeof sp);
        sp.free = 1;
        assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
        if (k == 0) {
            assert_int_equal(td_model_add_speed_point(m, &a, NULL), TD_OK);
            assert_int_equal(td_model_add_speed_point(m, &b, NULL), TD_OK);
        } else {
            assert_int_equal(td_model_set_spin(m, &sp, NULL), TD_OK);
        }
        s = new_sim(m, 1e-10, 1e-14, 0);
        td_test_step_to(s, 0.8);
        assert_int_equal(td_sim_amb_force(s, 1, f1), TD_OK);
        print_message("%s: speed %.12g rad/s, AMB 1 force %.12g N; closed form %.12g N\n",
                      k == 0 ? "speed ramp" : "free spin", td_sim_speed(s), f1[0],
                      -td_model_polar_inertia(m) * omega * w / SPAN);
        assert_close(td_sim_speed(s), omega, 1e-9, 0.0);
        assert_close(f1[0], -td_model_polar_inertia(m) * omega * w / SPAN, 1e-6, 0.0);
        td_sim_free(&s);
        td_model_free(&m);
    }
}

/* A steady acceleration a along +x (a ramp held): the rotor lags behind, to -x relative to the
 * housing, and its bearings push it along with the housing, their forces summing to m a (m the
 * rotor's mass) with no moment about the centre of mass. */
static void test_constant_acceleration(void **state)
{
    const double acc = 10.0;
    td_model *m = rigid_rotor(150.0);
    td_housing_pulse p = {TD_PULSE_RAMP, acc, 0.05, 0.0, {1.0, 0.0}};
    double f0[2], f1[2], q[20], zc = td_model_mass_centre(m);
    td_sim *s;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &p, NULL), TD_OK);
    s = new_sim(m, 1e-10, 1e-14, 0);
    td_test_step_to(s, 0.8);
    assert_int_equal(td_sim_amb_force(s, 0, f0), TD_OK);
    assert_int_equal(td_sim_amb_force(s, 1, f1), TD_OK);
    assert_int_equal(td_sim_dof_count(s), 20);
    assert_int_equal(td_sim_get_state(s, q, NULL), TD_OK);
    print_message("AMB forces at 0.8 s: %.12g N, %.12g N; m a = %.12g N; disc x %.6g m\n", f0[0], f1[0],
                  td_model_total_mass(m) * acc, q[TD_DOF(2, TD_DOF_X)]);
    assert_true(q[TD_DOF(2, TD_DOF_X)] < 0.0);
    assert_close(f0[0] + f1[0], td_model_total_mass(m) * acc, 1e-6, 0.0);
    assert_close((0.0 - zc) * f0[0] + (SPAN - zc) * f1[0], 0.0, 0.0, 1e-6 * td_model_total_mass(m) * acc * SPAN);
    assert_close(f0[1] + f1[1], 0.0, 0.0, 1e-9);
    td_sim_free(&s);
    td_model_free(&m);
}

/* A race on its mount (a retainer at node 1, clear of the rotor) under a steady acceleration along +x
 * and a steady angular acceleration about x (a slow rate ramp): at rest on its mount it is
 * deflected by its own d'Alembert load, -m_b (a_x, a_y - (z - z_ref) alpha_x) / k_mount. */
static void test_race_share(void **state)
{
    const double acc = 10.0, alpha = 0.1, mb = 2.0, km = 1.0e7;
    td_model *m = rigid_rotor(150.0);
    td_retainer r;
    td_housing_pulse p = {TD_PULSE_RAMP, acc, 0.05, 0.0, {1.0, 0.0}};
    td_retainer_state rs;
    double dz;
    td_sim *s;
    (void)state;
    memset(&r, 0, sizeof r);
    r.node = 1, r.clearance = 1e-3, r.shaft_radius = 0.05, r.bore_radius = 0.051, r.friction = 0.1;
    r.race.mass = mb, r.race.mount_stiffness = km, r.race.mount_damping = 2.0e3;
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    assert_int_equal(td_model_add_housing_shock(m, &p, NULL), TD_OK);
    p.amplitude = alpha * 10.0, p.duration = 10.0; /* rate rising at alpha over 10 s */
    assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
    dz = td_model_node_position(m, 1) - td_model_housing_reference(m);
    s = new_sim(m, 1e-10, 1e-14, 0);
    td_test_step_to(s, 0.5);
    assert_int_equal(td_sim_retainer_state(s, 0, &rs), TD_OK);
    print_message("race at 0.5 s: (%.9g, %.9g) m; expected (%.9g, %.9g) m\n", rs.race_x, rs.race_y, -mb * acc / km,
                  mb * dz * alpha / km);
    assert_int_equal(rs.in_contact, 0);
    assert_close(rs.race_x, -mb * acc / km, 1e-6, 0.0);
    assert_close(rs.race_y, mb * dz * alpha / km, 1e-6, 0.0);
    td_sim_free(&s);
    td_model_free(&m);
}

/* The run's statistics to t_end of the rigid rotor with an unbalance, free flight on, with the shocks
 * given (n of them). */
static td_sim_stats kinks_run(const td_housing_pulse *p, int n, double t_end)
{
    td_model *m = rigid_rotor(150.0);
    td_unbalance u = {2, 1e-4, 0.0};
    td_sim_stats st;
    td_sim *s;
    int i;
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    for (i = 0; i < n; i++)
        assert_int_equal(td_model_add_housing_shock(m, &p[i], NULL), TD_OK);
    s = new_sim(m, 1e-6, 1e-9, 0);
    td_test_step_to(s, t_end);
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    td_sim_free(&s);
    td_model_free(&m);
    return st;
}

/* The integrator stops at each pulse's start and end (and a triangle's peak): a restart each, on top
 * of the run without them; and the closed-form free flight, which carries the run without housing
 * motion, is off with it (its forcing is time-invariant). */
static void test_kinks_and_flight(void **state)
{
    const td_housing_pulse p[2] = {{TD_PULSE_SAWTOOTH, 5.0, 0.01, 0.02, {1.0, 0.0}},
                                   {TD_PULSE_TRIANGLE, 5.0, 0.01, 0.05, {0.0, 1.0}}};
    td_sim_stats none = kinks_run(p, 0, 0.1), with = kinks_run(p, 2, 0.1);
    (void)state;
    print_message("restarts %ld without the shocks, %ld with; flight %.3g s and %.3g s of 0.1 s\n", none.restarts,
                  with.restarts, none.flight_time, with.flight_time);
    assert_int_equal(with.restarts, none.restarts + 5); /* 0.02, 0.03; 0.05, 0.055, 0.06 */
    assert_true(none.flight_time > 0.05);
    assert_true(with.flight_time == 0.0);
}

/* The rig at 190 rad/s (with or without its retainers) under a half-sine of `g` times 1 g over 10 ms
 * upward, energy kept, to t_end. */
static void shock_energy(double g, int retainers, double rtol, double t_end, td_energy *e, td_sim_stats *stats)
{
    td_model *m = td_test_rig_create(190.0, TD_RIG_TAU, retainers);
    td_housing_pulse p = {TD_PULSE_HALF_SINE, g * 9.80665, 0.01, 0.005, {0.0, 1.0}};
    td_sim *s;
    assert_int_equal(td_model_add_housing_shock(m, &p, NULL), TD_OK);
    s = new_sim(m, rtol, 1e-9 * rtol / 1e-6, 1);
    td_test_step_to(s, t_end);
    assert_int_equal(td_sim_energy(s, e), TD_OK);
    assert_int_equal(td_sim_stats_get(s, stats), TD_OK);
    td_sim_free(&s);
    td_model_free(&m);
}

static void report(const char *what, double rtol, const td_energy *e, const td_sim_stats *st)
{
    print_message("%s, rtol %g: housing work %.6g J, residual %.3g J (%.2e of it; %.3g J unbooked), held %.3g J, "
                  "impacts %.3g J, contact %.3g J, drive %.3g J, %ld contact onsets\n",
                  what, rtol, e->housing_work, e->residual, fabs(e->residual / e->housing_work),
                  e->residual + e->housing_work, e->kinetic + e->elastic, e->impact_loss, e->contact_loss,
                  e->drive_work, st->contact_onsets);
}

/* A 5 g shock on the rig without retainers (on the rig it would reach them: its static deflection
 * under 1 g is about 0.5 mm of the 0.75 mm clearance): the base's work is what the rotor holds and
 * its AMBs take; the balance closes to the integrator's tolerance. */
static void test_shock_energy_free(void **state)
{
    td_energy coarse, fine;
    td_sim_stats st;
    (void)state;
    shock_energy(5.0, TD_RIG_NO_RETAINERS, 1e-6, 0.04, &coarse, &st);
    report("5 g", 1e-6, &coarse, &st);
    assert_true(fabs(coarse.housing_work) > 10.0 * (coarse.kinetic + coarse.elastic)); /* the AMBs took most */
    assert_true(fabs(coarse.residual) < 1e-3 * fabs(coarse.housing_work));
    shock_energy(5.0, TD_RIG_NO_RETAINERS, 1e-8, 0.04, &fine, &st);
    report("5 g", 1e-8, &fine, &st);
    assert_close(fine.housing_work, coarse.housing_work, 1e-3, 0.0);
    assert_true(fabs(fine.residual) < 1e-5 * fabs(fine.housing_work));
}

/* A 20 g shock into the retainers (impacts, rubs, the drive's work against friction): the residual
 * is an integration error, which shrinks with the tolerance, the base's work the same at both. */
static void test_shock_energy_contact(void **state)
{
    td_energy coarse, fine;
    td_sim_stats st;
    (void)state;
    shock_energy(20.0, TD_RIG_WITH_RETAINERS, 1e-6, 0.05, &coarse, &st);
    report("20 g", 1e-6, &coarse, &st);
    assert_true(st.contact_onsets > 0);
    assert_true(fabs(coarse.residual) < 1e-2 * fabs(coarse.housing_work));
    shock_energy(20.0, TD_RIG_WITH_RETAINERS, 1e-8, 0.05, &fine, &st);
    report("20 g", 1e-8, &fine, &st);
    assert_close(fine.housing_work, coarse.housing_work, 1e-2, 0.0);
    assert_true(fabs(fine.residual) < 1e-4 * fabs(fine.housing_work));
    assert_true(fabs(fine.residual) < 0.1 * fabs(coarse.residual));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constant_rotation_rate),
        cmocka_unit_test(test_varying_speed),
        cmocka_unit_test(test_constant_acceleration),
        cmocka_unit_test(test_kinks_and_flight),
        cmocka_unit_test(test_race_share),
        cmocka_unit_test(test_shock_energy_free),
        cmocka_unit_test(test_shock_energy_contact),
    };
    return cmocka_run_group_tests_name("base_motion", tests, NULL, NULL);
}
