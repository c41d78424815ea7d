/*
 * Harmonic (steady-state unbalance) response against closed forms.
 *
 * Model: one node, built by hand so the x and y axes are exactly single-DOF oscillators
 * m x'' + c x' + k x = F_x (rotations held by their own springs, no gyroscopics). With the
 * unbalance F_x = U W^2 cos(W t + p), F_y = U W^2 sin(W t + p):
 *   X = U W^2 e^{ip} / (k - m W^2 + i c W),  Y = -i X  (a forward circular orbit),
 *   |X| = U W^2 / sqrt((k - m W^2)^2 + (c W)^2),  arg X = p - atan2(c W, k - m W^2).
 * The first-order solve is direct (complex LU of a 8-state system), so the error model is
 * round-off times the conditioning (1/(2 zeta) at resonance): 1e-10 relative.
 * Second model: the same mass on an AMB axis with force lag (no mechanical spring):
 *   X = F / (k_dyn - m W^2),  k_dyn = -ks + ki (kp + i W kd) / (1 + i W tau),
 *   Fc = -ki (kp + i W kd) X / (1 + i W tau).
 */
#include "td_test.h"

#include "model/system_internal.h"
#include "touchdown/modal.h"
#include "touchdown/touchdown.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>

#define M_DISC 12.0
#define K_SPRING 3.0e6
#define C_DAMP 1.2e3

/* One node with diagonal M, K, C (x, y, theta, phi) and optional AMB axes on x and y. */
static td_system *one_node(const double m[4], const double k[4], const double c[4], const td_amb_axis *amb, double gx)
{
    td_system *s = calloc(1, sizeof *s);
    cs_di *T[4];
    int i, a;
    assert_non_null(s);
    s->nnodes = 1;
    s->ndof = 4;
    s->nphys = 4; /* full model: q is physical */
    for (a = 0; a < 4; a++)
        T[a] = cs_di_spalloc(4, 4, 8, 1, 1);
    for (i = 0; i < 4; i++) {
        cs_di_entry(T[0], i, i, m[i]);
        cs_di_entry(T[1], i, i, k[i]);
        cs_di_entry(T[2], i, i, c[i]);
        cs_di_entry(T[3], i, i, 0.0);
    }
    s->M = cs_di_compress(T[0]);
    s->K = cs_di_compress(T[1]);
    s->C = cs_di_compress(T[2]);
    s->G = cs_di_compress(T[3]);
    for (a = 0; a < 4; a++)
        cs_di_spfree(T[a]);
    s->gravity_load = calloc(4, sizeof *s->gravity_load);
    assert_non_null(s->gravity_load);
    s->gravity_load[TD_DOF_X] = m[0] * gx;
    if (amb) {
        s->n_amb_axes = 2;
        s->amb_axes = calloc(2, sizeof *s->amb_axes);
        assert_non_null(s->amb_axes);
        for (a = 0; a < 2; a++) {
            s->amb_axes[a] = *amb;
            s->amb_axes[a].axis = a;
            s->amb_axes[a].actuator_dof = s->amb_axes[a].sensor_dof = a;
            s->amb_axes[a].state = amb->tau > 0.0 ? s->n_controller_states++ : -1;
        }
    }
    return s;
}

static td_system *sdof(double gx)
{
    const double m[4] = {M_DISC, M_DISC, 0.5, 0.5};
    const double k[4] = {K_SPRING, K_SPRING, 1.0e7, 1.0e7};
    const double c[4] = {C_DAMP, C_DAMP, 10.0, 10.0};
    return one_node(m, k, c, NULL, gx);
}

static void test_sdof_amplitude_and_phase(void **state)
{
    td_system *s = sdof(0.0);
    double wn = sqrt(K_SPRING / M_DISC);
    const double ratios[5] = {0.3, 0.9, 1.0, 1.1, 3.0};
    td_unbalance u = {0, 2.5e-3, 0.7};
    int i;
    (void)state;
    for (i = 0; i < 5; i++) {
        double W = ratios[i] * wn, d = K_SPRING - M_DISC * W * W;
        double amp = u.magnitude * W * W / sqrt(d * d + C_DAMP * W * C_DAMP * W);
        double phase = u.phase - atan2(C_DAMP * W, d);
        td_harmonic *h = NULL;
        td_orbit o;
        assert_int_equal(td_harmonic_compute(s, W, &u, 1, &h, NULL), TD_OK);
        assert_int_equal(td_harmonic_orbit(h, 0, &o), TD_OK);
        assert_close(o.x_amp, amp, 1e-10, 0.0);
        assert_close(o.y_amp, amp, 1e-10, 0.0);
        assert_close(remainder(o.x_phase - phase, 2.0 * TD_PI), 0.0, 0.0, 1e-10);
        /* Y = -i X: y lags x by a quarter period, a forward circle */
        assert_close(remainder(o.y_phase - (phase - TD_PI / 2.0), 2.0 * TD_PI), 0.0, 0.0, 1e-10);
        assert_close(o.forward, amp, 1e-10, 0.0);
        assert_close(o.backward, 0.0, 0.0, 1e-10 * amp);
        assert_close(o.major, amp, 1e-10, 0.0);
        print_message("W/wn = %.2f: |X| = %.12g m (closed form %.12g), rel err %.2e\n", ratios[i], o.x_amp, amp,
                      td_rel_diff(o.x_amp, amp));
        td_harmonic_free(&h);
        assert_null(h);
    }
    td_system_free(&s);
}

/* Two unbalances superpose; the start state is Re(Z e^{iWt}) plus the static sag. */
static void test_superposition_and_start_state(void **state)
{
    const double g = -9.81;
    td_system *s = sdof(g);
    double W = 0.8 * sqrt(K_SPRING / M_DISC), t = 0.0123, z[8];
    td_unbalance u[2] = {{0, 1e-3, 0.2}, {0, 2e-3, -1.1}};
    double complex X = 0.0;
    int i;
    (void)state;
    for (i = 0; i < 2; i++)
        X += u[i].magnitude * W * W * cexp(I * u[i].phase) / (K_SPRING - M_DISC * W * W + I * C_DAMP * W);
    assert_int_equal(td_modal_state_count(s), 8);
    assert_int_equal(td_modal_start_state(s, W, u, 2, 1, t, z, NULL), TD_OK);
    /* x = Re(X e^{iWt}) + m g / k; v = Re(i W X e^{iWt}); y = Re(-i X e^{iWt}) */
    assert_close(z[TD_DOF_X], creal(X * cexp(I * W * t)) + M_DISC * g / K_SPRING, 1e-10, 0.0);
    assert_close(z[4 + TD_DOF_X], creal(I * W * X * cexp(I * W * t)), 1e-10, 0.0);
    assert_close(z[TD_DOF_Y], creal(-I * X * cexp(I * W * t)), 1e-10, 0.0);
    assert_close(z[4 + TD_DOF_Y], creal(W * X * cexp(I * W * t)), 1e-10, 0.0);
    assert_close(z[TD_DOF_THETA], 0.0, 0.0, 1e-20);
    /* without gravity: the pure orbit */
    assert_int_equal(td_modal_start_state(s, W, u, 2, 0, t, z, NULL), TD_OK);
    assert_close(z[TD_DOF_X], creal(X * cexp(I * W * t)), 1e-10, 0.0);
    /* at rest: only the sag */
    assert_int_equal(td_modal_start_state(s, 0.0, u, 2, 1, 0.0, z, NULL), TD_OK);
    assert_close(z[TD_DOF_X], M_DISC * g / K_SPRING, 1e-12, 0.0);
    assert_close(z[4 + TD_DOF_X], 0.0, 0.0, 1e-20);
    td_system_free(&s);
}

static void test_amb_axis_with_lag(void **state)
{
    const double m[4] = {M_DISC, M_DISC, 0.5, 0.5}, k[4] = {0.0, 0.0, 1.0e7, 1.0e7}, c[4] = {0.0, 0.0, 1.0, 1.0};
    td_amb_axis amb = {0,      0, 0, 0,  1.0e6, 200.0, 1.0e4, 40.0, 1.0 / (2.0 * TD_PI * 100.0),
                       1700.0, 0, 0, -1, 0.0,   0,     -1,    -1,   0.0};
    td_system *s = one_node(m, k, c, &amb, -9.81);
    td_unbalance u = {0, 1e-3, 0.3};
    const double speeds[3] = {50.0, 190.0, 600.0};
    int i;
    (void)state;
    assert_int_equal(td_modal_state_count(s), 10);
    for (i = 0; i < 3; i++) {
        double W = speeds[i], t = 0.37, z[10];
        double complex F = u.magnitude * W * W * cexp(I * u.phase);
        double complex law = amb.ki * (amb.kp + I * W * amb.kd) / (1.0 + I * W * amb.tau);
        double complex X = F / (-amb.ks + law - M_DISC * W * W), Fc = -law * X;
        double xs = M_DISC * -9.81 / (amb.ki * amb.kp - amb.ks); /* static sag on k_eq */
        td_harmonic *h = NULL;
        double re, im;
        assert_int_equal(td_harmonic_compute(s, W, &u, 1, &h, NULL), TD_OK);
        assert_int_equal(td_harmonic_state(h, TD_DOF_X, &re, &im), TD_OK);
        assert_close(re, creal(X), 1e-10, 1e-10 * cabs(X));
        assert_close(im, cimag(X), 1e-10, 1e-10 * cabs(X));
        assert_int_equal(td_harmonic_state(h, 8, &re, &im), TD_OK); /* filter state of the x axis */
        assert_close(re, creal(Fc), 1e-10, 1e-10 * cabs(Fc));
        assert_close(im, cimag(Fc), 1e-10, 1e-10 * cabs(Fc));
        td_harmonic_free(&h);
        /* start state: orbit plus sag, filter state at its steady value -ki kp xs */
        assert_int_equal(td_modal_start_state(s, W, &u, 1, 1, t, z, NULL), TD_OK);
        assert_close(z[TD_DOF_X], creal(X * cexp(I * W * t)) + xs, 1e-10, 1e-10 * cabs(X));
        assert_close(z[8], creal(Fc * cexp(I * W * t)) - amb.ki * amb.kp * xs, 1e-10, 1e-10 * cabs(Fc));
    }
    td_system_free(&s);
}

static void test_undamped_resonance_fails(void **state)
{
    const double m[4] = {1.0, 1.0, 1.0, 1.0}, k[4] = {4.0, 4.0, 9.0, 9.0}, c[4] = {0.0, 0.0, 0.0, 0.0};
    td_system *s = one_node(m, k, c, NULL, 0.0);
    td_unbalance u = {0, 1.0, 0.0};
    td_harmonic *h = (td_harmonic *)1;
    td_error err;
    (void)state;
    /* W = 2 = sqrt(k/m) exactly: i W is an eigenvalue */
    assert_int_equal(td_harmonic_compute(s, 2.0, &u, 1, &h, &err), TD_ERR_NUMERIC);
    assert_null(h);
    /* a node out of range */
    u.node = 1;
    assert_int_equal(td_harmonic_compute(s, 1.0, &u, 1, &h, &err), TD_ERR_INVALID);
    td_system_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sdof_amplitude_and_phase),
        cmocka_unit_test(test_superposition_and_start_state),
        cmocka_unit_test(test_amb_axis_with_lag),
        cmocka_unit_test(test_undamped_resonance_fails),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
