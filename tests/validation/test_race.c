/*
 * A retainer race as a body: spin-up under a constant normal load against its closed form.
 *
 * A rotor node of large mass (1000 kg) is pressed onto its retainer by a constant force F (an AMB
 * held at a control force, no gravity). It lands with the shaft at rest and settles; at t_s the
 * shaft is brought to speed W at once (td_sim_set_speed). The race, free to turn with polar
 * inertia J against a constant drag torque T0, is driven by the friction mu N at its bore R_b
 * (eq. 16, 17): while the shaft slides (v_s > 0),
 *
 *     J dOmega_b/dt = mu N R_b - T0,   Omega_b(t) = (mu N R_b - T0) (t - t_s) / J,
 *
 * with N = F. Once the race surface catches up with the shaft's
 * (v_s = 0, Omega_b = W R_s / R_b less the tiny whirl term) it rolls, the friction torque settles
 * at the drag it needs (T0 < mu N R_b), and rolling holds: |v_s| stays inside the slip band.
 * The friction force also pushes the rotor along the circle: N exceeds F by the centripetal force
 * of that motion, M (mu F t / M)^2 / c, a relative 3e-5 by the time the race rolls (1.9 ms).
 *
 * The same with the contact as a constraint (N = lambda) and as a compliant damped contact.
 */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define RACE_F 100.0  /* N, pressing force */
#define RACE_MU 0.2   /* friction */
#define RACE_J 1e-5   /* kg m^2 */
#define RACE_T0 1e-3  /* N m */
#define RACE_W 100.0  /* rad/s */
#define RACE_RS 0.025 /* m */
#define RACE_C 0.5e-3 /* m */
#define RACE_M 1000.0 /* kg */

static td_model *pressed_rotor(double contact_stiffness, int stick)
{
    const double ghost = 1e-12; /* a massless, stiffness-free shaft: node 0 is a point mass */
    td_model *m = NULL;
    td_error err;
    td_shaft_element el = {0.2, 0.05, 0.0, {2.11e11 * ghost, 8.1e10 * ghost, 7810.0 * ghost}};
    td_disc d0 = {0, RACE_M, 0.0, 0.01}, d1 = {1, RACE_M, 0.0, 0.01};
    td_bearing b1 = {1, 1e6, 1e6, 1e3, 1e3};
    td_amb press = {0, 0, 0.0, 1.0, 0.0, 0.0, 0.0, 1e4, 0, 0.0, 0.0, 0.0};
    td_retainer r = {.node = 0,
                     .clearance = RACE_C,
                     .shaft_radius = RACE_RS,
                     .bore_radius = RACE_RS + RACE_C,
                     .friction = RACE_MU,
                     .stick = stick,
                     .race = {.inertia = RACE_J, .drag_torque = RACE_T0}};
    if (contact_stiffness > 0.0) {
        r.contact.stiffness = contact_stiffness;
        r.contact.exponent = 1.0;
        r.contact.damping = TD_DAMPING_KELVIN_VOIGT;
        r.contact.damping_coefficient = 2.0 * sqrt(contact_stiffness * RACE_M); /* critically damped */
    }
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    if (td_model_add_shaft_element(m, &el, &err) || td_model_add_disc(m, &d0, &err) ||
        td_model_add_disc(m, &d1, &err) || td_model_add_bearing(m, &b1, &err) || td_model_add_amb(m, &press, &err) ||
        td_model_add_retainer(m, &r, &err) || td_model_validate(m, &err))
        fail_msg("pressed rotor: %s", err.message);
    return m;
}

static void check_spin_up(double contact_stiffness, int stick)
{
    td_model *m = pressed_rotor(contact_stiffness, stick);
    td_sim_options o;
    td_sim *s = NULL;
    td_error err;
    td_retainer_state rs;
    td_sim_stats st;
    double t = 0.0, t_c = 0.2, rate = (RACE_MU * RACE_F * (RACE_RS + RACE_C) - RACE_T0) / RACE_J;
    long rolls[2] = {0, 0};
    double creep, rolling = RACE_W * RACE_RS / (RACE_RS + RACE_C), worst_slide = 0.0, worst_roll = 0.0, worst_vs = 0.0;
    int i;
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = 1e-8;
    o.solver.atol = 1e-10;
    if (td_sim_create(m, &o, &s, &err) != TD_OK || td_sim_set_amb_mode(s, 0, TD_AMB_EXTERNAL, &err) != TD_OK ||
        td_sim_set_amb_control(s, 0, 0.0, -RACE_F, &err) != TD_OK)
        fail_msg("sim: %s", err.message);
    for (i = 1; i <= 1000; i++) { /* every ms, and every 50 us over the spin-up */
        double tr, tout = i <= 200 ? 1e-3 * i : i <= 600 ? 0.2 + 5e-5 * (i - 200) : 0.22 + 1e-3 * (i - 600);
        td_status r;
        while ((r = td_sim_step(s, tout, &tr, &err)) == TD_EVENT) {
            td_event ev;
            td_sim_last_event(s, &ev);
            rolls[0] += ev.kind == TD_EVENT_ROLL_START;
            rolls[1] += ev.kind == TD_EVENT_ROLL_END;
        }
        if (r != TD_OK)
            fail_msg("spin-up: %s", err.message);
        t = tr;
        td_sim_retainer_state(s, 0, &rs);
        if (t < t_c) {
            continue;
        } else if (i == 200) { /* landed and settled, shaft and race at rest: spin the shaft up */
            assert_true(rs.in_contact && fabs(rs.normal_force - RACE_F) < 1e-3 * RACE_F && fabs(rs.race_speed) < 1e-6);
            rolls[0] = rolls[1] = 0; /* from here on */
            if (td_sim_set_speed(s, RACE_W, &err) != TD_OK)
                fail_msg("set speed: %s", err.message);
            continue;
        }
        if (rs.sliding_velocity > 0.1) { /* sliding */
            double expect = rate * (t - t_c), e = fabs(rs.race_speed - expect) / expect;
            worst_slide = fmax(worst_slide, e);
        } else if (t > t_c + rolling / rate + 0.02) { /* rolling */
            worst_roll = fmax(worst_roll, fabs(rs.race_speed - rolling) / rolling);
            worst_vs = fmax(worst_vs, fabs(rs.sliding_velocity));
        }
    }
    td_sim_stats_get(s, &st);
    printf("contact %s: first contact %.6f s, spin-up worst relative error %.3g, rolling speed error %.3g, "
           "|v_s| <= %.3g m/s while rolling (t = %.3f s)\n",
           contact_stiffness > 0.0 ? "compliant" : "constraint", st.first_contact_time, worst_slide, worst_roll,
           worst_vs, t);
    assert_true(st.first_contact_time > 0.0 && st.first_contact_time < t_c);
    /* the slope is the closed form from the first sample on */
    assert_true(worst_slide > 0.0 && worst_slide < 5e-5);
    assert_true(worst_roll < 1e-4);
    if (stick) {
        /* rolling is a state: v_s = 0 held to the solver's tolerance, the friction force exactly the
         * drag's T0 / R_b, one roll start and no slip */
        double need = RACE_T0 / (RACE_RS + RACE_C);
        printf("rolling: v_s %.3g m/s, friction %.9g N (drag needs %.9g N), roll starts %ld, roll ends %ld\n",
               rs.sliding_velocity, -rs.friction_force, need, rolls[0], rolls[1]);
        assert_true(rs.rolling && worst_vs < 1e-8 && fabs(-rs.friction_force - need) < 1e-3 * need);
        assert_true(rolls[0] == 1 && rolls[1] == 1); /* the speed step ends the landing's roll */
    } else {
        /* rolling held: inside the slip band, creeping at the speed whose friction carries the
         * drag, v_reg T0 / (R_b mu N) */
        creep = 1e-4 * RACE_T0 / ((RACE_RS + RACE_C) * RACE_MU * RACE_F);
        printf("final v_s %.6g m/s, creep closed form %.6g m/s\n", rs.sliding_velocity, creep);
        /* the creep, 2e-7 m/s, is near the velocity tolerance (1e-10 m times the fastest frequency) */
        assert_true(!rs.rolling && worst_vs < 1e-4 && fabs(rs.sliding_velocity - creep) < 0.2 * creep);
    }
    assert_true(t > t_c + rolling / rate + 0.1);
    td_sim_free(&s);
    td_model_free(&m);
}

static void test_spin_up_constraint(void **state)
{
    (void)state;
    check_spin_up(0.0, 0);
}

static void test_spin_up_constraint_stick(void **state)
{
    (void)state;
    check_spin_up(0.0, 1);
}

static void test_spin_up_compliant_stick(void **state)
{
    (void)state;
    check_spin_up(1e8, 1);
}

static void test_spin_up_compliant(void **state)
{
    (void)state;
    check_spin_up(1e8, 0);
}

/*
 * Dry whip: a Jeffcott rotor (point mass m on an isotropic spring k and damper c_d, spinning at W)
 * pressed against a fixed bore (the paper's rigid retainer, no race) with a stick retainer. At
 * contact v_s = R_s W > 0: the friction on the rotor points against the whirl and drives it
 * backwards until the surfaces stop slipping, v_s = R_s W + c dtheta/dt = 0 (eq. 16, R_b - R_s = c):
 *
 *     dtheta/dt = -R_s W / c,  N = m c w^2 - k c (radial balance),  |F_t| = c_d c |w| (tangential),
 *
 * held while |F_t| <= mu N. The rotor is first pushed outwards by a follower force (an AMB held at a
 * control force along the node's radius, renewed every 20 us) until it rolls; then the push is
 * removed and the dry whip must sustain itself.
 */
#define WHIP_M 10.0
#define WHIP_K 1e6
#define WHIP_CD 200.0
#define WHIP_W 10.0
#define WHIP_MU 0.3

static td_model *whip_rotor(double contact_stiffness)
{
    const double ghost = 1e-12;
    td_model *m = NULL;
    td_error err;
    td_shaft_element el = {0.2, 0.05, 0.0, {2.11e11 * ghost, 8.1e10 * ghost, 7810.0 * ghost}};
    td_disc d0 = {0, WHIP_M, 0.0, 0.01}, d1 = {1, WHIP_M, 0.0, 0.01};
    td_bearing b0 = {0, WHIP_K, WHIP_K, WHIP_CD, WHIP_CD}, b1 = {1, WHIP_K, WHIP_K, WHIP_CD, WHIP_CD};
    td_amb push = {0, 0, 0.0, 1.0, 0.0, 0.0, 0.0, 1e5, 0, 0.0, 0.0, 0.0};
    td_retainer r = {.node = 0,
                     .clearance = RACE_C,
                     .shaft_radius = RACE_RS,
                     .bore_radius = RACE_RS + RACE_C,
                     .friction = WHIP_MU,
                     .stick = 1};
    if (contact_stiffness > 0.0) {
        r.contact.stiffness = contact_stiffness;
        r.contact.exponent = 1.0;
        r.contact.damping = TD_DAMPING_KELVIN_VOIGT;
        r.contact.damping_coefficient = 0.3 * 2.0 * sqrt(contact_stiffness * WHIP_M);
    }
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    if (td_model_add_shaft_element(m, &el, &err) || td_model_add_disc(m, &d0, &err) ||
        td_model_add_disc(m, &d1, &err) || td_model_add_bearing(m, &b0, &err) || td_model_add_bearing(m, &b1, &err) ||
        td_model_add_amb(m, &push, &err) || td_model_add_retainer(m, &r, &err) || td_model_set_speed(m, WHIP_W, &err) ||
        td_model_validate(m, &err))
        fail_msg("whip rotor: %s", err.message);
    return m;
}

static void check_dry_whip(double contact_stiffness)
{
    td_model *m = whip_rotor(contact_stiffness);
    td_sim_options o;
    td_sim *s = NULL;
    td_error err;
    td_retainer_state rs;
    double t = 0.0, rolled_at = -1.0, c, w, n_closed, ft_closed, worst_vs = 0.0;
    long roll_ends_after = 0;
    int i;
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = 1e-9;
    o.solver.atol = 1e-12;
    if (td_sim_create(m, &o, &s, &err) != TD_OK || td_sim_set_amb_mode(s, 0, TD_AMB_EXTERNAL, &err) != TD_OK)
        fail_msg("sim: %s", err.message);
    for (i = 1; i <= 30000 && t < 0.3; i++) {
        double tr;
        td_status st;
        td_sim_retainer_state(s, 0, &rs);
        if (rolled_at < 0.0) { /* push outwards along the node's radius */
            double r = rs.radius > 0.0 ? rs.radius : 1.0, fx = rs.radius > 0.0 ? rs.x / r : 0.0;
            double fy = rs.radius > 0.0 ? rs.y / r : -1.0;
            if (td_sim_set_amb_control(s, 0, 1000.0 * fx, 1000.0 * fy, &err) != TD_OK)
                fail_msg("push: %s", err.message);
        }
        while ((st = td_sim_step(s, t + (rolled_at < 0.0 ? 2e-5 : 1e-3), &tr, &err)) == TD_EVENT) {
            td_event ev;
            td_sim_last_event(s, &ev);
            if (ev.kind == TD_EVENT_ROLL_START && rolled_at < 0.0) {
                rolled_at = ev.time;
                if (td_sim_set_amb_control(s, 0, 0.0, 0.0, &err) != TD_OK) /* the push ends */
                    fail_msg("release: %s", err.message);
            } else if (ev.kind == TD_EVENT_ROLL_END && rolled_at >= 0.0) {
                roll_ends_after++;
            }
        }
        if (st != TD_OK)
            fail_msg("dry whip: %s", err.message);
        t = tr;
        if (rolled_at >= 0.0 && t > rolled_at + 0.1) {
            td_sim_retainer_state(s, 0, &rs);
            worst_vs = fmax(worst_vs, fabs(rs.sliding_velocity));
        }
    }
    td_sim_retainer_state(s, 0, &rs);
    c = rs.radius;
    w = -RACE_RS * WHIP_W / RACE_C; /* eq. (16) with v_s = 0 */
    n_closed = WHIP_M * c * w * w - WHIP_K * c;
    ft_closed = WHIP_CD * c * fabs(w);
    printf("dry whip (%s): rolls from %.6f s; at %.3f s N %.6f N (closed form %.6f), |F_t| %.6f N (%.6f), "
           "|v_s| <= %.3g m/s, roll ends after %ld\n",
           contact_stiffness > 0.0 ? "compliant" : "constraint", rolled_at, t, rs.normal_force, n_closed,
           fabs(rs.friction_force), ft_closed, worst_vs, roll_ends_after);
    assert_true(rolled_at > 0.0 && rs.rolling && roll_ends_after == 0);
    assert_true(fabs(rs.normal_force - n_closed) < 1e-4 * n_closed);
    assert_true(fabs(fabs(rs.friction_force) - ft_closed) < 1e-4 * ft_closed);
    assert_true(worst_vs < 1e-6);
    td_sim_free(&s);
    td_model_free(&m);
}

static void test_dry_whip_constraint(void **state)
{
    (void)state;
    check_dry_whip(0.0);
}

static void test_dry_whip_compliant(void **state)
{
    (void)state;
    check_dry_whip(1e10);
}

/*
 * Energy over a rub with the races free to spin (cases/rub-damped.cfg to 0.4 s: the first impacts,
 * spin-up, rolling and the steady rub): the change of the energy held (rotor and races, kinetic and
 * elastic, contact springs) equals the work put in (unbalance, AMBs, the drive holding the speed
 * against friction) less what the shaft's damping, the mounts, the contacts (friction heat,
 * dampers) and the drag took. The residual is the trapezoid rule's error over the steps: it must be
 * small against the largest term and fall as the tolerances tighten.
 */
static double energy_residual(const char *rtol, const char *atol, double *largest)
{
    const char *ovs[4] = {"energy = true", "end_time = 0.4", rtol, atol};
    td_case *c = NULL;
    td_sim *s = NULL;
    td_error err;
    td_energy e;
    double tr;
    td_status st;
    if (td_case_load(td_source_path("cases/rub-damped.cfg"), ovs, 4, &c, &err) != TD_OK ||
        td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err) != TD_OK)
        fail_msg("rub-damped: %s", err.message);
    while ((st = td_sim_step(s, td_case_end_time(c), &tr, &err)) == TD_EVENT)
        ;
    if (st != TD_OK)
        fail_msg("rub-damped: %s", err.message);
    assert_int_equal(td_sim_energy(s, &e), TD_OK);
    *largest = fmax(fmax(e.external_work, e.drive_work), fmax(e.damping_loss, fmax(e.contact_loss, e.drag_loss)));
    printf("%s %s: held %.6g J (start %.6g), external %.6g, drive %.6g; damping %.6g, contact %.6g, drag %.6g, "
           "impacts %.6g; residual %.3g J = %.2e of the largest term\n",
           rtol, atol, e.kinetic + e.elastic, e.initial, e.external_work, e.drive_work, e.damping_loss, e.contact_loss,
           e.drag_loss, e.impact_loss, e.residual, fabs(e.residual) / *largest);
    assert_true(e.contact_loss > 0.0 && e.drag_loss > 0.0 && e.drive_work > 0.0 && e.damping_loss > 0.0);
    td_sim_free(&s);
    td_case_free(&c);
    return fabs(e.residual);
}

static void test_energy_balance(void **state)
{
    double big1, big2, r1 = energy_residual("solver.rtol = 1e-6", "solver.atol = 1e-9", &big1);
    double r2 = energy_residual("solver.rtol = 1e-8", "solver.atol = 1e-11", &big2);
    (void)state;
    assert_true(r1 < 1e-3 * big1);
    assert_true(r2 < 1e-4 * big2 && r2 < 0.2 * r1); /* closes with the tolerance */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spin_up_constraint),       cmocka_unit_test(test_spin_up_compliant),
        cmocka_unit_test(test_spin_up_constraint_stick), cmocka_unit_test(test_spin_up_compliant_stick),
        cmocka_unit_test(test_energy_balance),           cmocka_unit_test(test_dry_whip_constraint),
        cmocka_unit_test(test_dry_whip_compliant),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
