/*
 * The API 617 report (touchdown/modal.h, lib/modal/api617.c) against closed forms: a Jeffcott
 * rotor's unbalance response peak, half-power speeds and amplification factor, the log decrement
 * of its mode, API 617's required margins, and the static reactions of a two-support beam (lever
 * rule) on plain bearings and on PID AMBs with a force lag (closed-loop static equilibrium).
 * ROSS checks the rig itself (tests/modal/ross_rig.py).
 */
#include "td_test.h"

#include "touchdown/assess.h"
#include "touchdown/modal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define G 9.81

/* A Jeffcott rotor that is a rigid body in translation: a short, very stiff and light shaft of two
 * elements (its first bending mode some 1e3 times above the translation mode), a point mass in the
 * middle and two equal bearings (k/2, c/2 each) at the ends, so that the unbalance at the middle
 * excites the translation mode m x'' + c x' + k x = U w^2 e^{iwt} of m = disc + shaft alone. */
#define J_DISC 20.0
#define J_K 2.0e6
#define J_RHO 10.0
#define J_L 0.2
#define J_D 0.1
static td_model *jeffcott_model(double zeta, double *mass)
{
    td_model *m = NULL;
    td_shaft_element el = {J_L / 2, J_D, 0.0, {2.11e15, 8.1e14, J_RHO}};
    td_disc d = {1, J_DISC, 0.0, 0.0};
    double total = J_DISC + J_RHO * TD_PI * J_D * J_D / 4 * J_L, c = 2.0 * zeta * sqrt(J_K * total);
    td_bearing b0 = {0, J_K / 2, J_K / 2, c / 2, c / 2}, b2 = {2, J_K / 2, J_K / 2, c / 2, c / 2};
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &d, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b2, NULL), TD_OK);
    *mass = total;
    return m;
}

static td_system *jeffcott(double zeta, double *mass)
{
    td_model *m = jeffcott_model(zeta, mass);
    td_system *s = NULL;
    td_error err;
    if (td_system_create(m, &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    td_model_free(&m);
    return s;
}

/* The closed form of |X(w)| = U w^2 / |k - m w^2 + i c w|: its peak at w_p = w_n / sqrt(1 - 2 zeta^2)
 * and the half-power speeds, the roots u = w^2 of 2 U^2 u^2 = a_p^2 ((k - m u)^2 + c^2 u). */
static void jeffcott_closed_form(double m, double zeta, double U, double *wp, double *ap, double *w1, double *w2)
{
    double wn = sqrt(J_K / m), c = 2.0 * zeta * sqrt(J_K * m), a, b, q, disc;
    *wp = wn / sqrt(1.0 - 2.0 * zeta * zeta);
    *ap = U * *wp * *wp / hypot(J_K - m * *wp * *wp, c * *wp);
    a = *ap * *ap * m * m - 2.0 * U * U;
    b = *ap * *ap * (c * c - 2.0 * J_K * m);
    q = *ap * *ap * J_K * J_K;
    disc = sqrt(b * b - 4.0 * a * q);
    *w1 = sqrt((-b - disc) / (2.0 * a));
    *w2 = sqrt((-b + disc) / (2.0 * a));
    if (*w1 > *w2) {
        double t = *w1;
        *w1 = *w2;
        *w2 = t;
    }
}

/* The sweep's peak at the disc: its speed, amplitude, half-power speeds and AF against the closed
 * form (the shaft's flexibility, 1e-6 of the bearings' compliance, is the difference), and AF
 * against the textbook 1 / (2 zeta), which is approximate: within 1 % at zeta = 0.02. */
static void test_jeffcott_amplification(void **state)
{
    const double zeta = 0.02, U = 1e-4;
    double mass, wp, ap, w1, w2, af;
    td_system *s = jeffcott(zeta, &mass);
    td_unbalance u = {1, U, 0.0};
    int node = 1, i, found = 0;
    td_sweep_options opt = {0.0, 600.0, 200.0, 250.0, &node, 1};
    td_sweep *sw = NULL;
    td_response_peak p;
    td_error err;
    (void)state;
    jeffcott_closed_form(mass, zeta, U, &wp, &ap, &w1, &w2);
    af = wp / (w2 - w1);
    if (td_unbalance_sweep(s, &u, 1, &opt, &sw, &err) != TD_OK)
        fail_msg("%s", err.message);
    for (i = 0; i < td_sweep_peak_count(sw); i++) {
        assert_int_equal(td_sweep_get_peak(sw, i, &p), TD_OK);
        if (p.amplitude < 0.5 * ap)
            continue;
        found++;
        print_message("peak %.10g rad/s (closed form %.10g), N1 %.10g (%.10g), N2 %.10g (%.10g), AF %.8g (%.8g; "
                      "1/(2 zeta) %.8g)\n",
                      p.speed, wp, p.speed_low, w1, p.speed_high, w2, p.amplification, af, 0.5 / zeta);
        assert_true(td_rel_diff(p.speed, wp) < 1e-5);
        assert_true(td_rel_diff(p.amplitude, ap) < 1e-5);
        assert_true(td_rel_diff(p.speed_low, w1) < 1e-5);
        assert_true(td_rel_diff(p.speed_high, w2) < 1e-5);
        assert_true(td_rel_diff(p.amplification, af) < 1e-4);
        assert_true(td_rel_diff(p.amplification, 0.5 / zeta) < 0.01);
        /* above the MCS of 250 rad/s (w_n = 312 rad/s): margin and requirement of that side */
        assert_true(td_rel_diff(p.margin, 100.0 * (p.speed - 250.0) / 250.0) < 1e-12);
        assert_true(td_rel_diff(p.required_margin, fmin(26.0, 10.0 + 17.0 * (1.0 - 1.0 / (af - 1.5)))) < 1e-4);
        assert_int_equal(p.verdict, p.margin >= p.required_margin);
    }
    assert_int_equal(found, 1);
    /* the grid is finer than 5 % change of the amplitude between neighbours near the peak */
    assert_true(td_sweep_speed_count(sw) > 101);
    td_sweep_free(&sw);
    td_system_free(&s);
}

/* The log decrement: ln of the ratio of successive peaks of e^{sigma t} cos(omega_d t), one damped
 * period 2 pi / omega_d apart, = -2 pi sigma / omega_d, against td_log_decrement(zeta) of the mode. */
static void test_log_decrement(void **state)
{
    double mass;
    td_system *s = jeffcott(0.05, &mass);
    td_modal *md = NULL;
    td_mode mode;
    int i;
    (void)state;
    assert_int_equal(td_modal_solve(s, 0.0, &md, NULL), TD_OK);
    for (i = 0; i < td_modal_mode_count(md); i++) {
        assert_int_equal(td_modal_get_mode(md, i, &mode), TD_OK);
        assert_true(td_rel_diff(td_log_decrement(mode.zeta), -2.0 * TD_PI * mode.sigma / mode.omega_d) < 1e-9);
    }
    assert_true(td_rel_diff(td_log_decrement(0.05), 2.0 * TD_PI * 0.05 / sqrt(1.0 - 0.0025)) < 1e-15);
    assert_true(isnan(td_log_decrement(1.0)));
    assert_true(isnan(td_log_decrement(NAN)));
    td_modal_free(&md);
    td_system_free(&s);
}

/* API 617 7th ed. 2.6.2.10 (docs/api617.md): none below AF 2.5; 17 (1 - 1/(AF - 1.5)) capped at 16 below the
 * operating range, 10 + that capped at 26 above. */
static void test_required_margin(void **state)
{
    (void)state;
    assert_true(td_api617_required_margin(2.4, 0) == 0.0);
    assert_true(td_api617_required_margin(2.4, 1) == 0.0);
    assert_true(fabs(td_api617_required_margin(3.5, 0) - 8.5) < 1e-12);
    assert_true(fabs(td_api617_required_margin(3.5, 1) - 18.5) < 1e-12);
    assert_true(td_api617_required_margin(100.0, 0) == 16.0);
    assert_true(td_api617_required_margin(100.0, 1) == 26.0);
    assert_true(isnan(td_api617_required_margin(NAN, 0)));
    assert_true(isnan(td_api617_required_margin(-1.0, 1)));
}

/* A steel shaft of 1 m on 4 elements, a 10 kg disc at its tip (node 4), supports at nodes 0 and 3
 * (z = 0, 0.75 m): plain bearings, or PID AMBs with a force lag (amb != 0). */
static td_model *overhung_model(int amb, double *shaft_mass)
{
    td_model *m = NULL;
    td_shaft_element el = {0.25, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_disc d = {4, 10.0, 0.05, 0.03};
    td_bearing b = {0, 5e7, 3e7, 100.0, 100.0};
    td_amb a = {0, 0, 1e6, 200.0, 1e4, 40.0, 1.0 / (2.0 * TD_PI * 500.0), 5000.0, 0, 1e-3, 2e5, 0.0};
    int i, nodes[2] = {0, 3};
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    for (i = 0; i < 4; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &d, NULL), TD_OK);
    for (i = 0; i < 2; i++) {
        b.node = a.node = a.sensor_node = nodes[i];
        assert_int_equal(amb ? td_model_add_amb(m, &a, NULL) : td_model_add_bearing(m, &b, NULL), TD_OK);
    }
    assert_int_equal(td_model_set_gravity(m, 0.0, -G, NULL), TD_OK);
    *shaft_mass = 7810.0 * TD_PI * 0.05 * 0.05 / 4;
    return m;
}

static td_system *system_of(td_model *m)
{
    td_system *s = NULL;
    td_error err;
    if (td_system_create(m, &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    return s;
}

static td_system *overhung_beam(int amb, double *shaft_mass)
{
    td_model *m = overhung_model(amb, shaft_mass);
    td_system *s = system_of(m);
    td_model_free(&m);
    return s;
}

/* Statics of a beam on two supports (the lever rule: the reactions balance the weight and its
 * moment about either support, whatever the supports' stiffness): R3 0.75 = g (m_s 0.5 + m_d 1.0),
 * R0 = g (m_s + m_d) - R3; nothing in x. */
static void test_static_reactions_lever_rule(void **state)
{
    int amb;
    (void)state;
    for (amb = 0; amb < 2; amb++) {
        double ms, f[4], r3, r0;
        td_system *s = overhung_beam(amb, &ms);
        td_error err;
        memset(f, 0, sizeof f);
        if (td_static_reactions(s, amb ? f : NULL, amb ? NULL : f, &err) != TD_OK)
            fail_msg("%s", err.message);
        r3 = G * (ms * 0.5 + 10.0 * 1.0) / 0.75;
        r0 = G * (ms + 10.0) - r3;
        print_message("%s: R0 %.12g N (lever rule %.12g), R3 %.12g N (%.12g)\n", amb ? "AMBs" : "bearings", f[1], r0,
                      f[3], r3);
        assert_true(td_rel_diff(f[1], r0) < 1e-9);
        assert_true(td_rel_diff(f[3], r3) < 1e-9);
        assert_true(fabs(f[0]) < 1e-9 && fabs(f[2]) < 1e-9);
        td_system_free(&s);
    }
}

/* The zone of each AMB sensor along the sweep is td_vibration_zone_of of the orbit's major semi-axis
 * at its sensor node (from a harmonic solve of its own at that speed) against the smallest
 * retainer clearance; a sweep without a sensor node gives none. */
static void test_sensor_zones(void **state)
{
    double ms, c_min;
    td_model *m = overhung_model(1, &ms);
    td_system *s;
    td_retainer r;
    td_unbalance u = {4, 1e-3, 0.0};
    int nodes[3] = {0, 3, 4}, zones[2 * TD_SWEEP_MAX_SPEEDS], k, i, changes = 0;
    td_sweep_options opt = {0.0, 1500.0, NAN, NAN, nodes, 3};
    td_sweep *sw = NULL;
    td_zone_limits lim;
    td_error err;
    (void)state;
    td_zone_limits_default(&lim);
    /* two retainers, the tighter one at the tip: C_min is its clearance */
    memset(&r, 0, sizeof r);
    r.node = 4, r.clearance = 2e-4, r.shaft_radius = 0.025, r.bore_radius = 0.0252;
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    r.node = 0, r.clearance = 3e-4, r.bore_radius = 0.0253;
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    s = system_of(m);
    if (td_unbalance_sweep(s, &u, 1, &opt, &sw, &err) != TD_OK)
        fail_msg("%s", err.message);
    assert_int_equal(td_sweep_sensor_zones(sw, m, zones, &c_min, &err), TD_OK);
    assert_true(c_min == 2e-4);
    for (k = 0; k < td_sweep_speed_count(sw); k += 7)
        for (i = 0; i < 2; i++) {
            td_harmonic *h = NULL;
            td_orbit o;
            assert_int_equal(td_harmonic_compute(s, td_sweep_speed(sw, k), &u, 1, &h, NULL), TD_OK);
            assert_int_equal(td_harmonic_orbit(h, nodes[i], &o), TD_OK);
            assert_int_equal(zones[2 * k + i], td_vibration_zone_of(o.major, 2e-4, &lim));
            changes += k > 0 && zones[2 * k + i] != zones[2 * (k - 7) + i];
            td_harmonic_free(&h);
        }
    assert_true(changes > 0); /* the response crosses at least one boundary over the sweep */
    td_sweep_free(&sw);
    opt.node_count = 1; /* node 0 only: AMB 1's sensor (node 3) is no response node */
    assert_int_equal(td_unbalance_sweep(s, &u, 1, &opt, &sw, &err), TD_OK);
    assert_int_equal(td_sweep_sensor_zones(sw, m, zones, &c_min, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "sensor node 3"));
    td_sweep_free(&sw);
    td_model_free(&m);
    td_system_free(&s);
}

/* Bad arguments are refused, naming what is wrong; no sweep is made. */
static void test_sweep_arguments(void **state)
{
    double mass;
    td_system *s = jeffcott(0.05, &mass);
    td_unbalance u = {1, 1e-4, 0.0};
    int node = 7, good = 1;
    td_sweep_options opt = {0.0, 600.0, NAN, NAN, &node, 1};
    td_sweep *sw = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_unbalance_sweep(s, &u, 1, &opt, &sw, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "node 7"));
    assert_null(sw);
    opt.nodes = &good;
    opt.speed_max = 0.0;
    assert_int_equal(td_unbalance_sweep(s, &u, 1, &opt, &sw, &err), TD_ERR_INVALID);
    opt.speed_max = 600.0;
    opt.node_count = 0;
    assert_int_equal(td_unbalance_sweep(s, &u, 1, &opt, &sw, &err), TD_ERR_INVALID);
    /* no operating range: margins undefined, verdict -1 */
    opt.node_count = 1;
    assert_int_equal(td_unbalance_sweep(s, &u, 1, &opt, &sw, &err), TD_OK);
    assert_true(td_sweep_peak_count(sw) >= 1);
    {
        td_response_peak p;
        assert_int_equal(td_sweep_get_peak(sw, 0, &p), TD_OK);
        assert_true(isnan(p.margin) && isnan(p.required_margin));
        assert_int_equal(p.verdict, -1);
        assert_int_equal(td_sweep_get_peak(sw, td_sweep_peak_count(sw), &p), TD_ERR_INVALID);
    }
    td_sweep_free(&sw);
    td_sweep_free(&sw);
    td_system_free(&s);
}

/* |X(w)| of the Jeffcott rotor, U w^2 / |k - m w^2 + i c w| (its orbit is a circle: major = |X|). */
static double jeffcott_amplitude(double m, double zeta, double U, double w)
{
    double c = 2.0 * zeta * sqrt(J_K * m);
    return U * w * w / hypot(J_K - m * w * w, c * w);
}

/* A plain retainer at `node` of radial clearance c. */
static td_retainer retainer_at(int node, double c)
{
    td_retainer r;
    memset(&r, 0, sizeof r);
    r.node = node;
    r.clearance = c;
    r.shaft_radius = 0.05;
    r.bore_radius = 0.05 + c;
    r.friction = 0.1;
    return r;
}

/* The Jeffcott rotor with retainers at the disc (clearance c) and at a bearing node that is no
 * response node; its sweep's amplitude check against the closed form: over the operating range
 * 200..250 rad/s (below the peak: largest at 250 rad/s, the range's end), over the whole sweep
 * without one (the peak's amplitude), pass at amplitude / c = 0.7, fail at 0.8, undefined at a node
 * the sweep did not compute. */
static void test_clearance_check(void **state)
{
    const double zeta = 0.02, U = 1e-4;
    double mass, wp, ap, w1, w2, a250, ratio[2] = {0.7, 0.8};
    int node = 1, r, with_range;
    td_unbalance u = {1, U, 0.0};
    td_error err;
    (void)state;
    for (with_range = 0; with_range < 2; with_range++) {
        td_sweep_options opt = {0.0,   600.0, with_range ? 200.0 : TD_UNDEFINED, with_range ? 250.0 : TD_UNDEFINED,
                                &node, 1};
        td_model *m0 = jeffcott_model(zeta, &mass);
        td_system *s = NULL;
        td_sweep *sw = NULL;
        double lo, hi, want, at;
        assert_int_equal(td_system_create(m0, &s, &err), TD_OK);
        if (td_unbalance_sweep(s, &u, 1, &opt, &sw, &err) != TD_OK)
            fail_msg("%s", err.message);
        jeffcott_closed_form(mass, zeta, U, &wp, &ap, &w1, &w2);
        a250 = jeffcott_amplitude(mass, zeta, U, 250.0);
        want = with_range ? a250 : ap;
        at = with_range ? 250.0 : wp;
        td_sweep_clearance_range(sw, &lo, &hi);
        assert_true(lo == (with_range ? 200.0 : 0.0) && hi == (with_range ? 250.0 : 600.0));
        for (r = 0; r < 2; r++) {
            td_model *m = jeffcott_model(zeta, &mass);
            td_retainer ret = retainer_at(1, want / ratio[r]), other = retainer_at(0, 1e-3);
            td_clearance_check c[2];
            assert_int_equal(td_model_add_retainer(m, &ret, NULL), TD_OK);
            assert_int_equal(td_model_add_retainer(m, &other, NULL), TD_OK);
            assert_int_equal(td_sweep_clearance_check(sw, m, c, &err), TD_OK);
            print_message("range %d: amplitude %.10g at %.8g rad/s (closed form %.10g at %.8g), ratio %.6g\n",
                          with_range, c[0].amplitude, c[0].speed, want, at, c[0].ratio);
            assert_true(td_rel_diff(c[0].amplitude, want) < 1e-6);
            assert_true(td_rel_diff(c[0].speed, at) < 1e-5);
            assert_true(td_rel_diff(c[0].ratio, ratio[r]) < 1e-6);
            assert_int_equal(c[0].verdict, r == 0);
            assert_int_equal(c[1].node, 0);
            assert_true(td_is_undefined(c[1].amplitude) && td_is_undefined(c[1].ratio));
            assert_int_equal(c[1].verdict, -1);
            td_model_free(&m);
        }
        assert_int_equal(td_sweep_clearance_check(NULL, m0, NULL, &err), TD_ERR_INVALID);
        td_sweep_free(&sw);
        td_system_free(&s);
        td_model_free(&m0);
    }
}

/* The peaks admitted (docs/api617.md): of each response node, exactly the local maxima of the
 * swept curve of at least 1 % of the node's largest amplitude over the sweep. On the rig of
 * cases/drop.cfg node 14 has a ripple of 0.11 % of its largest (68.8 rad/s), which the rule leaves out. */
static void test_peak_admission(void **state)
{
    td_case *c = NULL;
    td_system *s = NULL;
    td_sweep *sw = NULL;
    td_error err;
    td_unbalance u[8];
    const td_modal_options *mo;
    int nodes[TD_SWEEP_MAX_NODES], nn, n_u, i, j, k, below = 0;
    (void)state;
    if (td_case_load(td_source_path("cases/drop.cfg"), NULL, 0, &c, &err) != TD_OK)
        fail_msg("%s", err.message);
    mo = td_case_modal_options(c);
    assert_int_equal(td_system_create(td_case_model(c), &s, &err), TD_OK);
    n_u = td_model_unbalance_count(td_case_model(c));
    assert_true(n_u > 0 && n_u <= 8);
    for (i = 0; i < n_u; i++)
        td_model_get_unbalance(td_case_model(c), i, &u[i]);
    nn = td_modal_default_response_nodes(td_case_model(c), nodes, TD_SWEEP_MAX_NODES);
    {
        td_sweep_options opt = {mo->speed_min, mo->speed_max, TD_UNDEFINED, TD_UNDEFINED, nodes, nn};
        if (td_unbalance_sweep(s, u, n_u, &opt, &sw, &err) != TD_OK)
            fail_msg("%s", err.message);
    }
    for (j = 0; j < nn; j++) {
        double top = 0.0;
        int grid_peaks = 0, reported = 0;
        td_orbit o0, o, o1;
        for (k = 0; k < td_sweep_speed_count(sw); k++) {
            td_sweep_orbit(sw, k, j, &o);
            top = fmax(top, o.major);
        }
        for (k = 1; k + 1 < td_sweep_speed_count(sw); k++) {
            td_sweep_orbit(sw, k - 1, j, &o0);
            td_sweep_orbit(sw, k, j, &o);
            td_sweep_orbit(sw, k + 1, j, &o1);
            if (o.major > o0.major && o.major >= o1.major) {
                grid_peaks += o.major >= 0.01 * top;
                below += o.major < 0.01 * top;
            }
        }
        for (i = 0; i < td_sweep_peak_count(sw); i++) {
            td_response_peak p;
            td_sweep_get_peak(sw, i, &p);
            if (p.node != nodes[j])
                continue;
            reported++;
            assert_true(p.amplitude >= 0.01 * top);
        }
        print_message("node %d: largest %.4g m, %d peaks reported, %d grid maxima >= 1 %%\n", nodes[j], top, reported,
                      grid_peaks);
        assert_int_equal(reported, grid_peaks);
    }
    assert_true(below > 0); /* the rule is exercised: some maximum is left out */
    td_sweep_free(&sw);
    td_system_free(&s);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_jeffcott_amplification), cmocka_unit_test(test_log_decrement),
        cmocka_unit_test(test_required_margin),        cmocka_unit_test(test_static_reactions_lever_rule),
        cmocka_unit_test(test_sweep_arguments),        cmocka_unit_test(test_sensor_zones),
        cmocka_unit_test(test_clearance_check),        cmocka_unit_test(test_peak_admission),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
