/*
 * Controllers as linear systems (touchdown/controller.h, docs/theory.md "Controllers" and
 * "Rigid-body coordinates"). Independent references: each block's transfer function evaluated
 * directly as a ratio of complex polynomials, products of responses for laws in series,
 * hand-computed realisations for series/append/transform, and the hand computation of the
 * rigid-body transform with virtual work. scipy.signal checks the rest (tests/validation/control).
 */
#include "td_test.h"

#include "touchdown/controller.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W(f) (2.0 * TD_PI * (f))

/* The polynomial p (descending powers, len terms) at x. */
static double complex poly(const double *p, int len, double complex x)
{
    double complex v = 0.0;
    int i;
    for (i = 0; i < len; i++)
        v = v * x + p[i];
    return v;
}

/* The SISO response of k at f (Hz). */
static double complex response(const td_controller *k, double f)
{
    double re, im;
    td_error err;
    if (td_controller_frequency_response(k, f, &re, &im, &err) != TD_OK)
        fail_msg("frequency_response: %s", err.message);
    return re + I * im;
}

static void assert_complex_close(double complex a, double complex b, double rtol)
{
    double d = cabs(a - b), tol = rtol * cabs(b);
    if (!(d <= tol)) {
        print_error("got %.17g%+.17gi, expected %.17g%+.17gi (|diff| %.3g > %.3g)\n", creal(a), cimag(a), creal(b),
                    cimag(b), d, tol);
        fail();
    }
}

static const double freqs[] = {0.1, 3.0, 17.0, 34.4, 120.0, 999.0, 4321.0};
#define N_FREQS ((int)(sizeof freqs / sizeof freqs[0]))

/* Every block against its transfer function of the header, written out in s. */
static void test_blocks_match_their_transfer_functions(void **state)
{
    td_pid_block pid = {1.0e4, 2.0e5, 40.0, 2000.0}, pd = {1.0e4, 0.0, 40.0, 0.0};
    td_leadlag_block ll = {1.2e4, 15.0, 150.0};
    td_lowpass_block lp1 = {500.0, 1, 0.0}, lp2 = {2000.0, 2, 0.7};
    td_notch_block no = {34.4, 6.0, 0.05};
    td_controller *k[6];
    int i, j;
    (void)state;
    k[0] = td_controller_create_pid(&pid, NULL);
    k[1] = td_controller_create_pid(&pd, NULL);
    k[2] = td_controller_create_leadlag(&ll, NULL);
    k[3] = td_controller_create_lowpass(&lp1, NULL);
    k[4] = td_controller_create_lowpass(&lp2, NULL);
    k[5] = td_controller_create_notch(&no, NULL);
    for (i = 0; i < 6; i++)
        assert_non_null(k[i]);
    assert_int_equal(td_controller_order(k[0]), 2);
    assert_int_equal(td_controller_order(k[1]), 0);
    assert_true(td_controller_has_velocity_feedthrough(k[1]));
    assert_false(td_controller_has_velocity_feedthrough(k[0]));
    for (j = 0; j < N_FREQS; j++) {
        double complex s = I * W(freqs[j]), wd = W(2000.0), wc = W(2000.0), wn = W(34.4);
        double zp = 6.0 / (2.0 * 34.4), zz = 0.05 * zp;
        assert_complex_close(response(k[0], freqs[j]), 1.0e4 + 2.0e5 / s + 40.0 * s / (1.0 + s / wd), 1e-13);
        assert_complex_close(response(k[1], freqs[j]), 1.0e4 + 40.0 * s, 1e-15);
        assert_complex_close(response(k[2], freqs[j]), 1.2e4 * (1.0 + s / W(15.0)) / (1.0 + s / W(150.0)), 1e-13);
        assert_complex_close(response(k[3], freqs[j]), W(500.0) / (s + W(500.0)), 1e-13);
        assert_complex_close(response(k[4], freqs[j]), wc * wc / (s * s + 2.0 * 0.7 * wc * s + wc * wc), 1e-13);
        assert_complex_close(response(k[5], freqs[j]),
                             (s * s + 2.0 * zz * wn * s + wn * wn) / (s * s + 2.0 * zp * wn * s + wn * wn), 1e-12);
    }
    /* the notch's depth is its gain at the centre frequency */
    assert_close(cabs(response(k[5], 34.4)), 0.05, 1e-12, 0.0);
    for (i = 0; i < 6; i++)
        td_controller_free(&k[i]);
    assert_null(k[0]);
}

/* tf in s, proper and improper by one (polynomial division into D1 s + D + rest), and zpk. */
static void test_tf_and_zpk(void **state)
{
    const double num[] = {2.0, 3.0, 7.0, 11.0}, den[] = {4.0, 5.0, 6.0}; /* improper by one */
    const double num2[] = {0.0, 1.0, 30.0}, den2[] = {1.0, 12.0, 3500.0, 1.0e4};
    const double zr[] = {-3.0, -1.0}, zi[] = {0.0, 20.0}, pr[] = {-2.0, -5.0, -40.0}, pi[] = {10.0, 0.0, 0.0};
    td_controller *a = td_controller_create_tf(num, 4, den, 3, 0.0, NULL);
    td_controller *b = td_controller_create_tf(num2, 3, den2, 4, 0.0, NULL);
    td_controller *z = td_controller_create_zpk(zr, zi, 2, pr, pi, 3, 2.5, 0.0, NULL);
    double D, D1;
    int j;
    (void)state;
    assert_non_null(a);
    assert_non_null(b);
    assert_non_null(z);
    assert_int_equal(td_controller_order(a), 2);
    assert_int_equal(td_controller_order(b), 3);
    assert_int_equal(td_controller_order(z), 4);
    td_controller_matrices(a, NULL, NULL, NULL, &D, &D1);
    /* (2 s^3 + 3 s^2 + 7 s + 11) / (4 s^2 + 5 s + 6) = 0.5 s + 0.125 + (...) / (...) */
    assert_close(D1, 0.5, 1e-15, 0.0);
    assert_close(D, 0.125, 1e-15, 0.0);
    for (j = 0; j < N_FREQS; j++) {
        double complex s = I * W(freqs[j]);
        double complex zk = 2.5 * (s + 3.0) * ((s + 1.0) * (s + 1.0) + 400.0);
        double complex pk = ((s + 2.0) * (s + 2.0) + 100.0) * (s + 5.0) * (s + 40.0);
        assert_complex_close(response(a, freqs[j]), poly(num, 4, s) / poly(den, 3, s), 1e-13);
        assert_complex_close(response(b, freqs[j]), poly(num2, 3, s) / poly(den2, 4, s), 1e-12);
        assert_complex_close(response(z, freqs[j]), zk / pk, 1e-12);
    }
    td_controller_free(&a);
    td_controller_free(&b);
    td_controller_free(&z);
}

/* A sampled tf in ascending powers of z^-1 and a sampled zpk (positive powers of z). */
static void test_sampled_tf_and_zpk(void **state)
{
    const double num[] = {0.5, -0.2, 0.1, 0.0}, den[] = {1.0, -1.1, 0.3};
    const double zr[] = {0.5}, zi[] = {0.0}, pr[] = {0.2, 0.6}, pi[] = {0.0, 0.3};
    double rate = 1.0e4;
    td_controller *k = td_controller_create_tf(num, 4, den, 3, rate, NULL);
    td_controller *z = td_controller_create_zpk(zr, zi, 1, pr, pi, 2, 3.0, rate, NULL);
    int j;
    (void)state;
    assert_non_null(k);
    assert_non_null(z);
    assert_int_equal(td_controller_order(k), 2);
    assert_int_equal(td_controller_order(z), 3);
    assert_close(td_controller_sample_rate(k), rate, 0.0, 0.0);
    for (j = 0; j < N_FREQS; j++) {
        double complex q = cexp(-I * W(freqs[j]) / rate), x = 1.0 / q; /* z^-1, z */
        double complex hk = (0.5 - 0.2 * q + 0.1 * q * q) / (1.0 - 1.1 * q + 0.3 * q * q);
        double complex hz = 3.0 * (x - 0.5) / ((x - 0.2) * ((x - 0.6) * (x - 0.6) + 0.09));
        assert_complex_close(response(k, freqs[j]), hk, 1e-12);
        assert_complex_close(response(z, freqs[j]), hz, 1e-12);
    }
    td_controller_free(&k);
    td_controller_free(&z);
}

/* 1st: A1 = -1, B1 = 1, C1 = 2, D1 = 0; 2nd: A2 = -3, B2 = 1, C2 = 1, D2 = 0.5 (by hand). */
static void test_series_append_transform_by_hand(void **state)
{
    const double a1 = -1.0, b1 = 1.0, c1 = 2.0, d1 = 0.0, a2 = -3.0, b2 = 1.0, c2 = 1.0, d2 = 0.5;
    td_controller *k1 = td_controller_create_ss(1, 1, 1, &a1, &b1, &c1, &d1, NULL, 0.0, NULL);
    td_controller *k2 = td_controller_create_ss(1, 1, 1, &a2, &b2, &c2, &d2, NULL, 0.0, NULL);
    td_controller *s = td_controller_series(k1, k2, NULL), *p = td_controller_append(k1, k2, NULL), *t;
    const double Tin[] = {1.0, 2.0, 3.0, 4.0}, Tout[] = {5.0, 6.0, 7.0, 8.0}; /* Tin = [1 3; 2 4] */
    double A[4], B[4], C[4], D[4], D1[4];
    (void)state;
    assert_non_null(s);
    assert_non_null(p);
    td_controller_matrices(s, A, B, C, D, D1);
    /* A = [A1 0; B2 C1 A2], B = [B1; B2 D1], C = [D2 C1  C2], D = D2 D1 */
    assert_true(A[0] == -1.0 && A[1] == 2.0 && A[2] == 0.0 && A[3] == -3.0);
    assert_true(B[0] == 1.0 && B[1] == 0.0 && C[0] == 1.0 && C[1] == 1.0 && D[0] == 0.0 && D1[0] == 0.0);
    td_controller_matrices(p, A, B, C, D, D1);
    assert_int_equal(td_controller_inputs(p), 2);
    assert_int_equal(td_controller_outputs(p), 2);
    assert_true(A[0] == -1.0 && A[1] == 0.0 && A[2] == 0.0 && A[3] == -3.0);
    assert_true(B[0] == 1.0 && B[1] == 0.0 && B[2] == 0.0 && B[3] == 1.0);
    assert_true(C[0] == 2.0 && C[1] == 0.0 && C[2] == 0.0 && C[3] == 1.0);
    assert_true(D[0] == 0.0 && D[1] == 0.0 && D[2] == 0.0 && D[3] == 0.5);
    /* Tout = [5 7; 6 8]: B = diag(1, 1) Tin = [1 3; 2 4], C = Tout diag(2, 1) = [10 7; 12 8],
     * D = Tout diag(0, 0.5) Tin = Tout [0 0; 1 2] = [7 14; 8 16] */
    t = td_controller_transform(p, 2, Tin, 2, Tout, NULL);
    assert_non_null(t);
    td_controller_matrices(t, A, B, C, D, D1);
    assert_true(B[0] == 1.0 && B[1] == 2.0 && B[2] == 3.0 && B[3] == 4.0);
    assert_true(C[0] == 10.0 && C[1] == 12.0 && C[2] == 7.0 && C[3] == 8.0);
    assert_true(D[0] == 7.0 && D[1] == 8.0 && D[2] == 14.0 && D[3] == 16.0);
    td_controller_free(&k1);
    td_controller_free(&k2);
    td_controller_free(&s);
    td_controller_free(&p);
    td_controller_free(&t);
}

/* PD 2 + 3 s (no filter: D = 2, D1 = 3) and 1/(s + 1) in series, either way round, is
 * (3 s + 2)/(s + 1) = 3 - 1/(s + 1), by hand: the velocity feedthrough lands in D, none is left. */
static void test_series_with_velocity_feedthrough_by_hand(void **state)
{
    const double a = -1.0, b = 1.0, c = 1.0, zero = 0.0;
    td_pid_block pd = {2.0, 0.0, 3.0, 0.0};
    td_controller *P = td_controller_create_pid(&pd, NULL);
    td_controller *L = td_controller_create_ss(1, 1, 1, &a, &b, &c, &zero, NULL, 0.0, NULL);
    td_controller *s1 = td_controller_series(P, L, NULL), *s2 = td_controller_series(L, P, NULL);
    double A, B, C, D, D1;
    (void)state;
    assert_non_null(s1);
    assert_non_null(s2);
    /* P then L: B = B2 D1 + A2 B2 E1 = 2 - 3, C = C2, D = C2 B2 E1 = 3 */
    td_controller_matrices(s1, &A, &B, &C, &D, &D1);
    assert_true(A == -1.0 && B == -1.0 && C == 1.0 && D == 3.0 && D1 == 0.0);
    /* L then P: C = D2 C1 + E2 C1 A1 = 2 - 3, D = E2 C1 B1 = 3 */
    td_controller_matrices(s2, &A, &B, &C, &D, &D1);
    assert_true(A == -1.0 && B == 1.0 && C == -1.0 && D == 3.0 && D1 == 0.0);
    td_controller_free(&P);
    td_controller_free(&L);
    td_controller_free(&s1);
    td_controller_free(&s2);
}

/* Laws in series respond as the product of their responses, including the improper-by-one cases
 * (the velocity feedthrough in the first law, in the second, and carried to the result). */
static void test_series_is_the_product(void **state)
{
    td_pid_block pid = {1.0e4, 2.0e5, 40.0, 2000.0}, pd = {1.0e4, 0.0, 40.0, 0.0};
    td_lowpass_block lp1 = {500.0, 1, 0.0}, lp2 = {2000.0, 2, 0.7};
    td_notch_block no = {34.4, 6.0, 0.05};
    td_controller *PID = td_controller_create_pid(&pid, NULL), *PD = td_controller_create_pid(&pd, NULL);
    td_controller *L1 = td_controller_create_lowpass(&lp1, NULL), *L2 = td_controller_create_lowpass(&lp2, NULL);
    td_controller *N = td_controller_create_notch(&no, NULL);
    td_controller *first[] = {PD, L1, N, PID, PD}, *second[] = {L2, PD, PD, N, N}, *s;
    const int improper[] = {0, 0, 1, 0, 1};
    td_error err;
    int c, j;
    (void)state;
    for (c = 0; c < 5; c++) {
        s = td_controller_series(first[c], second[c], &err);
        assert_non_null(s);
        assert_int_equal(td_controller_has_velocity_feedthrough(s), improper[c]);
        assert_int_equal(td_controller_order(s), td_controller_order(first[c]) + td_controller_order(second[c]));
        for (j = 0; j < N_FREQS; j++)
            assert_complex_close(response(s, freqs[j]), response(first[c], freqs[j]) * response(second[c], freqs[j]),
                                 1e-12);
        td_controller_free(&s);
    }
    /* PD then PD: kd^2 s^2 needs the sensor's acceleration */
    assert_null(td_controller_series(PD, PD, &err));
    assert_int_equal(err.code, TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "improper by two"));
    td_controller_free(&PID);
    td_controller_free(&PD);
    td_controller_free(&L1);
    td_controller_free(&L2);
    td_controller_free(&N);
}

/* Bearings at za = 0.2 m and zb = 1.0 m, reference zr = 0.5 m, by hand. */
static void test_rigid_transform_by_hand(void **state)
{
    double T[4], za = 0.2, zb = 1.0, zr = 0.5, theta = 3.0e-4, xa, xb, xr, tilt, Fr = 120.0, M = -35.0, Fa, Fb;
    td_error err;
    (void)state;
    assert_int_equal(td_rigid_transform(za, zb, zr, T, &err), TD_OK);
    /* T = 1/0.8 [0.5 0.3; -1 1] */
    assert_close(T[0], 0.625, 1e-15, 0.0);
    assert_close(T[2], 0.375, 1e-15, 0.0);
    assert_close(T[1], -1.25, 1e-15, 0.0);
    assert_close(T[3], 1.25, 1e-15, 0.0);
    /* a pure translation: both bearings move 1e-4 m; x_r = 1e-4, no tilt */
    xa = xb = 1.0e-4;
    assert_close(T[0] * xa + T[2] * xb, 1.0e-4, 1e-15, 0.0);
    assert_close(T[1] * xa + T[3] * xb, 0.0, 0.0, 1e-20);
    /* a pure tilt about zr: x = theta (z - zr); x_r = 0, tilt = theta */
    xa = theta * (za - zr), xb = theta * (zb - zr);
    xr = T[0] * xa + T[2] * xb, tilt = T[1] * xa + T[3] * xb;
    assert_close(xr, 0.0, 0.0, 1e-19);
    assert_close(tilt, theta, 1e-14, 0.0);
    /* forces: [Fa; Fb] = T^T [Fr; M] sum to Fr and have the moment M about zr */
    Fa = T[0] * Fr + T[1] * M, Fb = T[2] * Fr + T[3] * M;
    assert_close(Fa + Fb, Fr, 1e-15, 0.0);
    assert_close(Fa * (za - zr) + Fb * (zb - zr), M, 1e-14, 0.0);
    /* virtual work for an arbitrary displacement: Fa dxa + Fb dxb = Fr dxr + M dtilt */
    xa = 2.0e-5, xb = -7.0e-5;
    assert_close(Fa * xa + Fb * xb, Fr * (T[0] * xa + T[2] * xb) + M * (T[1] * xa + T[3] * xb), 1e-14, 0.0);
    assert_int_equal(td_rigid_transform(0.4, 0.4, 0.5, T, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "coincide"));
    assert_int_equal(td_rigid_transform(0.1, NAN, 0.5, T, &err), TD_ERR_INVALID);
}

/* Bad laws are refused with TD_ERR_INVALID and a message that says what is wrong. */
static void expect_invalid(td_controller *k, const td_error *err, const char *words)
{
    assert_null(k);
    assert_int_equal(err->code, TD_ERR_INVALID);
    if (!strstr(err->message, words))
        fail_msg("message \"%s\" lacks \"%s\"", err->message, words);
}

static void test_bad_laws_are_refused(void **state)
{
    const double num3[] = {1.0, 0.0, 0.0}, den1[] = {1.0}, den0[] = {0.0, 1.0}, nan1[] = {NAN, 1.0}, one = 1.0;
    double y[1];
    td_pid_block pid = {1.0, -1.0, 0.0, 0.0};
    td_notch_block no = {34.4, 6.0, 1.0};
    td_lowpass_block lp = {100.0, 3, 0.7};
    td_controller *c = td_controller_create_gain(1.0, NULL), *z = td_controller_create_tf(&one, 1, &one, 1, 1e3, NULL);
    td_error err;
    (void)state;
    expect_invalid(td_controller_create_tf(num3, 3, den1, 1, 0.0, &err), &err, "improper by 2");
    expect_invalid(td_controller_create_tf(num3, 2, den0, 2, 0.0, &err), &err, "den[0]");
    expect_invalid(td_controller_create_tf(nan1, 2, den1, 1, 0.0, &err), &err, "not finite");
    /* in z^-1 every tf is proper; in zeros and poles of z, more zeros than poles is not */
    expect_invalid(td_controller_create_zpk(num3, num3 + 1, 2, &one, num3 + 1, 1, 1.0, 1e4, &err), &err,
                   "improper sampled");
    expect_invalid(td_controller_create_tf(num3, 2, den1, 1, NAN, &err), &err, "sample_rate");
    expect_invalid(td_controller_create_gain(INFINITY, &err), &err, "finite");
    expect_invalid(td_controller_create_pid(&pid, &err), &err, "kint");
    assert_string_equal(err.site.field, "kint");
    assert_string_equal(err.message, "pid: kint: must be finite and >= 0 (got -1)");
    expect_invalid(td_controller_create_notch(&no, &err), &err, "depth");
    expect_invalid(td_controller_create_lowpass(&lp, &err), &err, "order");
    expect_invalid(td_controller_series(c, z, &err), &err, "timing");
    expect_invalid(td_controller_append(z, c, &err), &err, "timing");
    expect_invalid(td_controller_create_ss(1, 1, 1, nan1, &one, &one, &one, NULL, 0.0, &err), &err, "not finite");
    expect_invalid(td_controller_create_ss(0, 1, 1, NULL, NULL, NULL, &one, &one, 1e3, &err), &err, "D1");
    /* a sampled law needs a rate; an unfiltered derivative has no sampled form and no step response */
    expect_invalid(td_controller_discretise(c, 0.0, TD_DISCRETISE_TUSTIN, 0.0, &err), &err, "sample_rate");
    expect_invalid(td_controller_discretise(c, 1e3, TD_DISCRETISE_TUSTIN, 600.0, &err), &err, "Nyquist");
    /* the site names the argument, for a case reader to point at the key it read */
    assert_string_equal(err.site.part, "discretise");
    assert_string_equal(err.site.field, "prewarp");
    expect_invalid(td_controller_discretise(z, 1e3, TD_DISCRETISE_ZOH, 0.0, &err), &err, "sampled already");
    td_controller_free(&c);
    pid.kint = 0.0, pid.kd = 40.0;
    c = td_controller_create_pid(&pid, NULL);
    expect_invalid(td_controller_discretise(c, 1e3, TD_DISCRETISE_ZOH, 0.0, &err), &err, "derivative");
    assert_int_equal(td_controller_step_response(c, 0, &one, 1, y, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "impulse"));
    td_controller_free(&c);
    td_controller_free(&z);
}

/* The step response of g (s cos phi + w sin phi)/(s^2 + 2 zeta w s + w^2), by partial fractions:
 * g sin phi/w (1 - e^(-zeta w t) cos wd t) + e^(-zeta w t) sin(wd t) g (cos phi - zeta sin phi)/wd,
 * wd = w sqrt(1 - zeta^2); zeta = 0 gives g (cos phi sin wt + sin phi (1 - cos wt))/w. */
static double resonant_step(double g, double phi, double w, double zeta, double t)
{
    double wd = w * sqrt(1.0 - zeta * zeta), decay = exp(-zeta * w * t);
    return g * sin(phi) / w * (1.0 - decay * cos(wd * t)) + decay * sin(wd * t) * g * (cos(phi) - zeta * sin(phi)) / wd;
}

/* A resonant block is g (s cos phi + w sin phi)/(s^2 + 2 zeta w s + w^2): its response against the
 * ratio written out, and at w against g/(2 zeta w) e^(-j phi) when damped; its poles from its A
 * (trace -2 zeta w, determinant w^2; undamped, A is exactly [0 w; -w 0]); its step response against
 * the closed form (resonant_step). */
static void test_resonant_block(void **state)
{
    static const double phases[] = {0.0, 60.0, 90.0, -135.0}, dampings[] = {0.0, 0.02, 0.3, 0.95};
    const double f0 = 50.93, w = W(f0), t[] = {0.0, 0.0013, 0.0071, 0.019, 0.2};
    double A[4], y[5];
    int i, j, m;
    (void)state;
    for (m = 0; m < 4; m++)
        for (i = 0; i < 4; i++) {
            const double zeta = dampings[m], phi = phases[i] * TD_PI / 180.0;
            td_resonant_block b = {-3.0e3, phases[i], f0, zeta};
            td_controller *k = td_controller_create_resonant(&b, NULL);
            assert_non_null(k);
            assert_int_equal(td_controller_order(k), 2);
            assert_false(td_controller_has_velocity_feedthrough(k));
            for (j = 0; j < N_FREQS; j++) {
                double complex s = I * W(freqs[j]);
                assert_complex_close(response(k, freqs[j]),
                                     -3.0e3 * (s * cos(phi) + w * sin(phi)) / (s * s + 2.0 * zeta * w * s + w * w),
                                     1e-13);
            }
            if (zeta > 0.0)
                assert_complex_close(response(k, f0), -3.0e3 / (2.0 * zeta * w) * cexp(-I * phi), 1e-12);
            td_controller_matrices(k, A, NULL, NULL, NULL, NULL);
            if (zeta == 0.0)
                assert_true(A[0] == 0.0 && A[1] == -w && A[2] == w && A[3] == 0.0);
            assert_close(A[0] + A[3], -2.0 * zeta * w, 1e-15, 0.0);
            assert_close(A[0] * A[3] - A[1] * A[2], w * w, 1e-15, 0.0);
            assert_int_equal(td_controller_step_response(k, 0, t, 5, y, NULL), TD_OK);
            for (j = 0; j < 5; j++)
                assert_close(y[j], resonant_step(-3.0e3, phi, w, zeta, t[j]), 1e-11, 1e-11 * 3.0e3 / w);
            td_controller_free(&k);
        }
}

/* A resonant block's damping is a ratio from 0 (undamped) up to, not including, 1; outside it, or
 * not finite, the block is refused naming the field. */
static void test_resonant_damping_bounded(void **state)
{
    static const double bad[] = {-1.0e-9, -0.5, 1.0, 1.5, INFINITY, NAN};
    td_error err;
    int i;
    (void)state;
    for (i = 0; i < 6; i++) {
        td_resonant_block b = {1.0, 30.0, 50.0, bad[i]};
        expect_invalid(td_controller_create_resonant(&b, &err), &err, "resonant: damping: must be >= 0 and < 1 (got ");
        assert_string_equal(err.site.part, "resonant");
        assert_string_equal(err.site.field, "damping");
    }
}

/* A law whose realisation overflows (an entry inf or NaN) is refused where it is made, naming the
 * block or the operation: every number in range, their arithmetic out of it. */
static void test_overflowing_laws_refused(void **state)
{
    const td_leadlag_block ll = {1.0e300, 1.0e-6, 1.0e6}; /* g (wp/wz)(wz - wp): 1e300 x 1e12 x -6e6 */
    const double num[] = {1.0}, den[] = {1.0e-310, 1.0}, big = 1.0e200, one = 1.0;
    td_controller *a = td_controller_create_gain(1.0e200, NULL), *b = td_controller_create_gain(1.0e200, NULL), *s;
    td_error err;
    (void)state;
    expect_invalid(td_controller_create_leadlag(&ll, &err), &err, "leadlag: the realisation overflows");
    assert_string_equal(err.site.part, "leadlag");
    expect_invalid(td_controller_create_tf(num, 1, den, 2, 0.0, &err), &err, "tf: the realisation overflows");
    expect_invalid(td_controller_series(a, b, &err), &err, "series: the realisation overflows");
    td_controller_free(&b);
    b = td_controller_create_gain(1.7e308, NULL); /* 1.7e308 + 1.7e308 overflows */
    expect_invalid(td_controller_parallel(b, b, &err), &err, "parallel: the realisation overflows");
    /* 1e200 x 1e100 stays in range */
    td_controller_free(&b);
    b = td_controller_create_gain(1.0e100, NULL);
    s = td_controller_series(a, b, &err);
    assert_non_null(s);
    td_controller_free(&s);
    expect_invalid(td_controller_transform(a, 1, &big, 1, &one, &err), &err, "transform: the realisation overflows");
    td_controller_free(&a);
    td_controller_free(&b);
}

/* In parallel the responses add, the velocity feedthroughs too (a PD plus a resonant is still
 * improper by one); laws of other sizes or timing are refused. */
static void test_parallel_is_the_sum(void **state)
{
    td_pid_block pd = {1.0e4, 0.0, 40.0, 0.0};
    td_resonant_block res = {0.6, 45.0, 50.93, 0.0};
    td_notch_block no = {34.4, 6.0, 0.05};
    const double one = 1.0;
    td_controller *a = td_controller_create_pid(&pd, NULL), *b = td_controller_create_resonant(&res, NULL),
                  *n = td_controller_create_notch(&no, NULL), *bn = td_controller_series(b, n, NULL), *k, *two,
                  *z = td_controller_create_tf(&one, 1, &one, 1, 1e3, NULL);
    td_error err;
    int j;
    (void)state;
    k = td_controller_parallel(a, bn, &err);
    assert_non_null(k);
    assert_int_equal(td_controller_order(k), 4);
    assert_true(td_controller_has_velocity_feedthrough(k));
    for (j = 0; j < N_FREQS; j++) {
        double complex s = I * W(freqs[j]), w = W(50.93), wn = W(34.4), phi = TD_PI / 4.0;
        double zp = 6.0 / (2.0 * 34.4), zz = 0.05 * zp;
        double complex notch = (s * s + 2.0 * zz * wn * s + wn * wn) / (s * s + 2.0 * zp * wn * s + wn * wn);
        assert_complex_close(response(k, freqs[j]),
                             1.0e4 + 40.0 * s + 0.6 * (s * cos(phi) + w * sin(phi)) / (s * s + w * w) * notch, 1e-14);
    }
    two = td_controller_append(a, a, NULL);
    expect_invalid(td_controller_parallel(a, two, &err), &err, "size");
    expect_invalid(td_controller_parallel(a, z, &err), &err, "timing");
    td_controller_free(&a);
    td_controller_free(&b);
    td_controller_free(&n);
    td_controller_free(&bn);
    td_controller_free(&k);
    td_controller_free(&two);
    td_controller_free(&z);
}

/* Every block frequency (Hz) is finite, > 0 (a derivative filter may be 0: none) and at most
 * TD_CONTROLLER_FREQUENCY_MAX, and a refusal names the field: a notch at 1e308 Hz made w = inf. */
static void test_block_frequencies_bounded(void **state)
{
    static const double bad[] = {1.0e308, INFINITY, NAN, 1.0000001e6, 1.0e-300, 0.0, -1.0};
    td_error err;
    td_controller *k;
    int i;
    (void)state;
    for (i = 0; i < 7; i++) {
        double f = bad[i];
        td_leadlag_block llz = {1.0, f, 100.0}, llp = {1.0, 10.0, f};
        td_lowpass_block lp = {f, 2, 0.7};
        td_notch_block nf = {f, 6.0, 0.05}, nw = {34.4, f, 0.05};
        td_pid_block pid = {1.0, 0.0, 1.0, f};
        td_resonant_block res = {1.0, 0.0, f, 0.0};
        expect_invalid(td_controller_create_leadlag(&llz, &err), &err, "leadlag: zero: ");
        expect_invalid(td_controller_create_leadlag(&llp, &err), &err, "leadlag: pole: ");
        expect_invalid(td_controller_create_lowpass(&lp, &err), &err, "lowpass: frequency: ");
        expect_invalid(td_controller_create_notch(&nf, &err), &err, "notch: frequency: ");
        assert_string_equal(err.site.field, "frequency");
        expect_invalid(td_controller_create_notch(&nw, &err), &err, "notch: width: ");
        expect_invalid(td_controller_create_resonant(&res, &err), &err, "resonant: frequency: ");
        if (f == 0.0) { /* no derivative filter: the exact derivative */
            k = td_controller_create_pid(&pid, &err);
            assert_non_null(k);
            td_controller_free(&k);
        } else {
            expect_invalid(td_controller_create_pid(&pid, &err), &err, "pid: derivative_filter: ");
        }
    }
    assert_string_equal(err.message, "pid: derivative_filter: must be 0 (none) or 1e-06 to 1e+06 Hz (got -1)");
    {
        td_notch_block top = {TD_CONTROLLER_FREQUENCY_MAX, TD_CONTROLLER_FREQUENCY_MAX, 0.05},
                       bottom = {TD_CONTROLLER_FREQUENCY_MIN, TD_CONTROLLER_FREQUENCY_MAX, 0.05};
        k = td_controller_create_notch(&top, &err);
        assert_non_null(k);
        td_controller_free(&k);
        k = td_controller_create_notch(&bottom, &err);
        assert_non_null(k);
        td_controller_free(&k);
    }
}

/* Tustin (plain and prewarped) is the continuous response at s = beta (z - 1)/(z + 1); the
 * zero-order hold of wc/(s + wc) is (1 - a) z^-1/(1 - a z^-1), a = exp(-wc T); the prewarped law
 * matches the continuous one exactly at the prewarp frequency. */
static void test_discretise_closed_forms(void **state)
{
    td_notch_block no = {34.4, 6.0, 0.05};
    td_lowpass_block lp1 = {500.0, 1, 0.0};
    td_controller *N = td_controller_create_notch(&no, NULL), *L = td_controller_create_lowpass(&lp1, NULL);
    double rate = 2000.0, T = 1.0 / rate, a = exp(-W(500.0) * T), w0 = W(34.4);
    td_controller *Nt = td_controller_discretise(N, rate, TD_DISCRETISE_TUSTIN, 0.0, NULL);
    td_controller *Np = td_controller_discretise(N, rate, TD_DISCRETISE_TUSTIN, 34.4, NULL);
    td_controller *Lz = td_controller_discretise(L, rate, TD_DISCRETISE_ZOH, 0.0, NULL);
    int j;
    (void)state;
    assert_non_null(Nt);
    assert_non_null(Np);
    assert_non_null(Lz);
    assert_close(td_controller_sample_rate(Nt), rate, 0.0, 0.0);
    for (j = 0; j < N_FREQS; j++) {
        double f = freqs[j] < 0.5 * rate ? freqs[j] : 0.37 * rate;
        double complex z = cexp(I * W(f) * T), s2 = 2.0 * rate * (z - 1.0) / (z + 1.0);
        double complex sp = w0 / tan(0.5 * w0 * T) * (z - 1.0) / (z + 1.0);
        double zp = 6.0 / (2.0 * 34.4), zz = 0.05 * zp;
        double complex Ns, Nps;
        Ns = (s2 * s2 + 2.0 * zz * w0 * s2 + w0 * w0) / (s2 * s2 + 2.0 * zp * w0 * s2 + w0 * w0);
        Nps = (sp * sp + 2.0 * zz * w0 * sp + w0 * w0) / (sp * sp + 2.0 * zp * w0 * sp + w0 * w0);
        assert_complex_close(response(Nt, f), Ns, 1e-11);
        assert_complex_close(response(Np, f), Nps, 1e-11);
        assert_complex_close(response(Lz, f), (1.0 - a) / z / (1.0 - a / z), 1e-12);
    }
    /* prewarped: exact at the notch frequency (the depth survives); plain Tustin shifts the notch */
    assert_complex_close(response(Np, 34.4), response(N, 34.4), 1e-9);
    td_controller_free(&N);
    td_controller_free(&L);
    td_controller_free(&Nt);
    td_controller_free(&Np);
    td_controller_free(&Lz);
}

/* A delay of d samples multiplies the response by z^-d and shifts the step sequence by d samples. */
static void test_delay_is_z_to_the_minus_d(void **state)
{
    const double num[] = {0.5, -0.2, 0.1}, den[] = {1.0, -1.1, 0.3};
    double rate = 1.0e4, t[12], y0[12], y3[12];
    td_controller *k = td_controller_create_tf(num, 3, den, 3, rate, NULL), *d3 = td_controller_delay(k, 3, NULL);
    td_controller *d0 = td_controller_delay(k, 0, NULL);
    td_error err;
    int j;
    (void)state;
    assert_non_null(d3);
    assert_int_equal(td_controller_order(d3), td_controller_order(k) + 3);
    assert_int_equal(td_controller_order(d0), td_controller_order(k));
    for (j = 0; j < N_FREQS; j++) {
        double complex z = cexp(I * W(freqs[j]) / rate);
        assert_complex_close(response(d3, freqs[j]), response(k, freqs[j]) / (z * z * z), 1e-13);
    }
    for (j = 0; j < 12; j++)
        t[j] = j / rate;
    assert_int_equal(td_controller_step_response(k, 0, t, 12, y0, &err), TD_OK);
    assert_int_equal(td_controller_step_response(d3, 0, t, 12, y3, &err), TD_OK);
    for (j = 0; j < 12; j++)
        assert_true(y3[j] == (j < 3 ? 0.0 : y0[j - 3]));
    assert_close(y0[0], 0.5, 0.0, 0.0); /* y_0 = D = num[0] / den[0] */
    td_controller_free(&k);
    k = td_controller_create_gain(1.0, NULL); /* continuous: no whole samples to delay by */
    assert_null(td_controller_delay(k, 1, &err));
    assert_non_null(strstr(err.message, "sampled"));
    td_controller_free(&k);
    td_controller_free(&d3);
    td_controller_free(&d0);
}

/* The same law on two outputs fed by one input: append(K, K) with Tin = [1; 1] has twice K's
 * states, half of them a copy; minimal() removes the copy and keeps the response. */
static void test_minimal_removes_duplicate_states(void **state)
{
    td_pid_block pid = {1.0e4, 2.0e5, 40.0, 2000.0};
    td_notch_block no = {34.4, 6.0, 0.05};
    td_controller *P = td_controller_create_pid(&pid, NULL), *N = td_controller_create_notch(&no, NULL);
    td_controller *K = td_controller_series(P, N, NULL), *KK = td_controller_append(K, K, NULL), *T, *M;
    const double Tin[] = {1.0, 1.0}, Tout[] = {1.0, 0.0, 0.0, 1.0};
    double re[2], im[2], rm[2], imm[2];
    int j;
    (void)state;
    T = td_controller_transform(KK, 1, Tin, 2, Tout, NULL);
    assert_non_null(T);
    M = td_controller_minimal(T, NULL);
    assert_non_null(M);
    assert_int_equal(td_controller_order(T), 8);
    assert_int_equal(td_controller_order(M), 4);
    assert_int_equal(td_controller_order(K), 4);
    for (j = 0; j < N_FREQS; j++) {
        assert_int_equal(td_controller_frequency_response(T, freqs[j], re, im, NULL), TD_OK);
        assert_int_equal(td_controller_frequency_response(M, freqs[j], rm, imm, NULL), TD_OK);
        double complex k = response(P, freqs[j]) * response(N, freqs[j]);
        double scale = cabs(response(P, freqs[j])); /* |K| without the notch's dip */
        assert_complex_close(re[0] + I * im[0], k, 1e-12);
        assert_complex_close(re[1] + I * im[1], k, 1e-12);
        /* the orthogonal reduction of this badly scaled law (entries of B up to 1e8) rounds at
         * about 1e-10 of the law's scale, seen relative to |K| in the notch's dip */
        assert_true(cabs(rm[0] + I * imm[0] - k) <= 1e-9 * scale);
        assert_true(cabs(rm[1] + I * imm[1] - k) <= 1e-9 * scale);
    }
    td_controller_free(&P);
    td_controller_free(&N);
    td_controller_free(&K);
    td_controller_free(&KK);
    td_controller_free(&T);
    td_controller_free(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blocks_match_their_transfer_functions),
        cmocka_unit_test(test_tf_and_zpk),
        cmocka_unit_test(test_sampled_tf_and_zpk),
        cmocka_unit_test(test_series_append_transform_by_hand),
        cmocka_unit_test(test_series_with_velocity_feedthrough_by_hand),
        cmocka_unit_test(test_series_is_the_product),
        cmocka_unit_test(test_rigid_transform_by_hand),
        cmocka_unit_test(test_bad_laws_are_refused),
        cmocka_unit_test(test_resonant_block),
        cmocka_unit_test(test_resonant_damping_bounded),
        cmocka_unit_test(test_block_frequencies_bounded),
        cmocka_unit_test(test_parallel_is_the_sum),
        cmocka_unit_test(test_overflowing_laws_refused),
        cmocka_unit_test(test_discretise_closed_forms),
        cmocka_unit_test(test_delay_is_z_to_the_minus_d),
        cmocka_unit_test(test_minimal_removes_duplicate_states),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
