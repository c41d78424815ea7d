/*
 * The second-order synchronous response of the API 617 sweep (lib/modal/synchronous.c) against the
 * first-order solve of td_harmonic_compute (lib/modal/harmonic.c), a second method: the whole state
 * Z = [Q; V; S] at several speeds, below, near and above the machines' rigid-body and bending
 * criticals, on cases with every kind of controller state the bordered [Q; S] system holds: lag
 * filters (paper-a), PID integrators, race bodies, a housing body on mounts and a reduced shaft
 * (all-keys), a linear controller with a lag (rig-notch) and without one, its current then acting
 * directly (rig-notch, tau = 0), an undamped resonant block at its own frequency (its states alone
 * singular there) and AMBs switched off.
 *
 * Tolerance: the two solves round differently, and the dynamic stiffness of a stiff shaft on soft
 * bearings is ill-conditioned (cond ~ (highest mode / speed)^2): the gaps seen are up to 1e-10 of
 * each block's largest entry (rig-notch at 190 rad/s), some 1e6 eps; 1e-9 leaves a factor 10. A wrong
 * term of the elimination is an O(1) error.
 *
 * Which of the two is nearer the truth: test_accuracy solves the same equations, [Q; S] unknown with
 * V = i W Q substituted, from the same double entries (M, the right-hand blocks, the filter rows) by
 * Gaussian elimination in long double (64-bit significand, 2^11 times finer than double). The
 * second-order solve is within 1e-11 of its largest entry (6e-13 seen); the first-order one, through
 * M^-1, is some 60 to 90 times farther (3e-13 to 5e-11): the sweep's differences from
 * td_harmonic_compute are mostly the first-order solve's rounding.
 */
#include "td_test.h"

#include "modal/modal_internal.h"
#include "touchdown/case.h"
#include "touchdown/dofs.h"
#include "touchdown/modal.h"
#include "touchdown/system.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>

#define TOLERANCE 1e-9
#define ACCURACY 1e-11

typedef long double complex lcomplex;

/* Largest |a - b| over rows [lo, hi) of the two responses, relative to the largest |b| there. */
static double block_gap(const td_harmonic *a, const td_harmonic *b, int lo, int hi)
{
    double gap = 0.0, big = 0.0;
    int i;
    for (i = lo; i < hi; i++) {
        double ar, ai, br, bi;
        assert_int_equal(td_harmonic_state(a, i, &ar, &ai), TD_OK);
        assert_int_equal(td_harmonic_state(b, i, &br, &bi), TD_OK);
        gap = fmax(gap, hypot(ar - br, ai - bi));
        big = fmax(big, hypot(br, bi));
    }
    return big > 0.0 ? gap / big : gap;
}

/* Both solves of `path` (with overrides; AMB amb_off switched off unless -1) at the n_speeds speeds;
 * returns the controller state count. */
static int compare_at(const char *path, const char **ov, int n_ov, int node, int want_states, const double *speeds,
                      int n_speeds, int amb_off)
{
    td_case *c = td_test_load_case(path, ov, n_ov);
    td_system *sys = NULL;
    td_synchronous *fast = NULL;
    td_unbalance u[2] = {{0, 1e-3, 0.4}, {0, 2e-3, -1.9}};
    td_error err;
    int nd, nf, k;
    assert_int_equal(td_system_create(td_case_model(c), &sys, &err), TD_OK);
    if (amb_off >= 0)
        td_system_set_amb_off(sys, amb_off, 1);
    if (td_synchronous_create(sys, &fast, &err) != TD_OK)
        fail_msg("%s: %s", path, err.message);
    nd = td_system_dof_count(sys);
    nf = td_modal_state_count(sys) - 2 * nd;
    assert_true(nf >= want_states);
    u[0].node = node;
    u[1].node = node + 2;
    for (k = 0; k < n_speeds; k++) {
        td_harmonic *ref = NULL, *h = NULL;
        double gq, gv, gs;
        assert_int_equal(td_harmonic_compute(sys, speeds[k], u, 2, &ref, &err), TD_OK);
        if (td_synchronous_response(fast, speeds[k], u, 2, &h, &err) != TD_OK)
            fail_msg("%s at %g rad/s: %s", path, speeds[k], err.message);
        assert_int_equal(td_harmonic_state_count(h), td_harmonic_state_count(ref));
        gq = block_gap(h, ref, 0, nd);
        gv = block_gap(h, ref, nd, 2 * nd);
        gs = block_gap(h, ref, 2 * nd, 2 * nd + nf);
        if (!(gq <= TOLERANCE && gv <= TOLERANCE && gs <= TOLERANCE))
            fail_msg("%s at %g rad/s: q %.3g, v %.3g, controller states %.3g of their largest", path, speeds[k], gq, gv,
                     gs);
        td_harmonic_free(&ref);
        td_harmonic_free(&h);
    }
    td_synchronous_free(&fast);
    td_system_free(&sys);
    td_case_free(&c);
    return nf;
}

/* compare_at over speeds below, near and above the machines' rigid-body and bending criticals. */
static int compare_case(const char *path, const char **ov, int n_ov, int node, int want_states)
{
    static const double speeds[] = {0.0, 1.0, 60.0, 117.0, 150.0, 190.0, 400.0, 1200.0};
    return compare_at(path, ov, n_ov, node, want_states, speeds, (int)(sizeof speeds / sizeof speeds[0]), -1);
}

static void test_lag_filters(void **state)
{
    (void)state;
    assert_int_equal(compare_case("cases/paper-a.cfg", NULL, 0, 1, 4), 4);
}

static void test_integrators_races_housing_body(void **state)
{
    (void)state;
    compare_case("tests/data/case/all-keys.cfg", NULL, 0, 1, 4);
}

static void test_linear_controller(void **state)
{
    const char *no_lag[] = {"ambs = ( { node = 3; ks = 1.0e6; ki = 200.0; tau = 0.0; force_capacity = 1700.0; "
                            "saturation = false; air_gap = 1.2e-3; }, { node = 9; ks = 1.0e6; ki = 200.0; tau = 0.0; "
                            "force_capacity = 1700.0; saturation = false; air_gap = 1.2e-3; } )"};
    (void)state;
    compare_case("cases/rig-notch.cfg", NULL, 0, 1, 5);
    compare_case("cases/rig-notch.cfg", no_lag, 1, 1, 1);
}

/* An undamped resonant block (poles +-j w, w = 2 pi 20 Hz) in rig-notch's translation law: at and
 * within 1e-7 of w the controller's own states alone are singular (i w I - P_s), the closed loop
 * is not; the response there is td_harmonic_compute's. */
static void test_undamped_resonant(void **state)
{
    const char *resonant[] = {
        "controllers = ( { name = \"rigid-notch-resonant\"; ambs = [0, 1]; coordinates = \"rigid\"; "
        "translation = ( { parallel = ( { pid = { kp = 2.0e4; kd = 80.0; derivative_filter = 2000.0; }; }, "
        "{ resonant = { gain = 0.5; phase = 60.0; frequency = 20.0; }; } ); }, "
        "{ notch = { frequency = 34.4; width = 6.0; depth = 0.3; }; } ); "
        "tilt = ( { pid = { kp = 5.0e3; kd = 20.0; derivative_filter = 2000.0; }; } ); } )"};
    const double w = 2.0 * TD_PI * 20.0; /* as lib/control/blocks.c forms it */
    const double speeds[] = {w, w * (1.0 - 1e-7), w * (1.0 + 1e-7), 0.0, 60.0, 150.0, 400.0};
    (void)state;
    compare_at("cases/rig-notch.cfg", resonant, 1, 1, 7, speeds, (int)(sizeof speeds / sizeof speeds[0]), -1);
}

/* An AMB that is off (td_system_set_amb_off: no force, its controller runs on, a PID integrator
 * holds): a lag filter's (paper-a), PID integrators (all-keys) and a linear controller (rig-notch). */
static void test_amb_off(void **state)
{
    static const double speeds[] = {0.0, 60.0, 150.0, 400.0};
    const int n = (int)(sizeof speeds / sizeof speeds[0]);
    (void)state;
    compare_at("cases/paper-a.cfg", NULL, 0, 1, 4, speeds, n, 0);
    compare_at("tests/data/case/all-keys.cfg", NULL, 0, 1, 4, speeds, n, 0);
    compare_at("cases/rig-notch.cfg", NULL, 0, 1, 5, speeds, n, 1);
}

/* Row i of the system in [Q; S] (nd + nf unknowns) at speed W into T (row-major, N columns):
 * (-W^2 M - R_q - i W R_v) Q - R_s S = F for i < nd, -(P_q + i W P_v) Q + (i W I - P_s) S = 0 below. */
static void reference_rows(const td_system *sys, double W, const gsl_matrix *Md, const gsl_matrix *R,
                           const gsl_matrix *A, lcomplex *T)
{
    int nd = sys->ndof, n = td_modal_state_count(sys), nf = n - 2 * nd, N = nd + nf, i, j;
    long double w = W;
    for (i = 0; i < nd; i++) {
        for (j = 0; j < nd; j++)
            T[i * N + j] = -w * w * gsl_matrix_get(Md, i, j) - (long double)gsl_matrix_get(R, i, j) -
                           I * w * gsl_matrix_get(R, i, nd + j);
        for (j = 0; j < nf; j++)
            T[i * N + nd + j] = -(long double)gsl_matrix_get(R, i, 2 * nd + j);
    }
    for (i = 0; i < nf; i++) {
        for (j = 0; j < nd; j++)
            T[(nd + i) * N + j] =
                -(long double)gsl_matrix_get(A, 2 * nd + i, j) - I * w * gsl_matrix_get(A, 2 * nd + i, nd + j);
        for (j = 0; j < nf; j++)
            T[(nd + i) * N + nd + j] = (i == j ? I * w : 0.0L) - (long double)gsl_matrix_get(A, 2 * nd + i, 2 * nd + j);
    }
}

/* x = T^-1 x (N x N, row-major; T overwritten) by Gaussian elimination with partial pivoting. */
static void solve_long_double(lcomplex *T, lcomplex *x, int N)
{
    int i, j, k;
    for (k = 0; k < N; k++) {
        int p = k;
        lcomplex t;
        for (i = k + 1; i < N; i++)
            if (cabsl(T[i * N + k]) > cabsl(T[p * N + k]))
                p = i;
        for (j = 0; j < N; j++) {
            t = T[k * N + j];
            T[k * N + j] = T[p * N + j];
            T[p * N + j] = t;
        }
        t = x[k];
        x[k] = x[p];
        x[p] = t;
        for (i = k + 1; i < N; i++) {
            lcomplex f = T[i * N + k] / T[k * N + k];
            for (j = k; j < N; j++)
                T[i * N + j] -= f * T[k * N + j];
            x[i] -= f * x[k];
        }
    }
    for (k = N - 1; k >= 0; k--) {
        lcomplex s = x[k];
        for (j = k + 1; j < N; j++)
            s -= T[k * N + j] * x[j];
        x[k] = s / T[k * N + k];
    }
}

/* The largest |Q - q_ref| of h over the largest |q_ref| (nd entries). */
static double q_error(const td_harmonic *h, const lcomplex *ref, int nd)
{
    long double gap = 0.0L, big = 0.0L;
    int i;
    for (i = 0; i < nd; i++) {
        double re, im;
        assert_int_equal(td_harmonic_state(h, i, &re, &im), TD_OK);
        gap = fmaxl(gap, cabsl(re + I * (long double)im - ref[i]));
        big = fmaxl(big, cabsl(ref[i]));
    }
    return (double)(gap / big);
}

/* Q of the unbalances u at speed W by the long-double solve into q (nd + nf entries). */
static void reference_response(const td_system *sys, double W, const td_unbalance *u, int n_u, lcomplex *q)
{
    int nd = sys->ndof, n = td_modal_state_count(sys), N = n - nd, i;
    gsl_matrix *R = gsl_matrix_calloc((size_t)nd, (size_t)n), *A = gsl_matrix_calloc((size_t)n, (size_t)n);
    gsl_matrix *Md = gsl_matrix_calloc((size_t)nd, (size_t)nd);
    td_entry_sink rk = {NULL, NULL, 0, 1}, ak = {NULL, NULL, 0, 1}, mk = {NULL, NULL, 0, 1};
    double *f = calloc(2u * (size_t)nd, sizeof *f);
    lcomplex *T = malloc((size_t)N * (size_t)N * sizeof *T);
    assert_true(R && A && Md && f && T);
    rk.dense = R, ak.dense = A, mk.dense = Md;
    td_state_space_rhs_blocks(sys, W, &rk);
    td_state_space_filter_rows(sys, &ak);
    td_entry_add_matrix(&mk, sys->M, 0, 1.0);
    assert_int_equal(td_unbalance_forces(sys, W, u, n_u, f, f + nd, NULL), TD_OK);
    reference_rows(sys, W, Md, R, A, T);
    for (i = 0; i < N; i++)
        q[i] = i < nd ? f[i] + I * (long double)f[nd + i] : 0.0L;
    solve_long_double(T, q, N);
    free(T);
    free(f);
    gsl_matrix_free(Md);
    gsl_matrix_free(A);
    gsl_matrix_free(R);
}

static void accuracy_of(const char *path, double W)
{
    td_case *c = td_test_load_case(path, NULL, 0);
    td_system *sys = NULL;
    td_synchronous *fast = NULL;
    td_harmonic *first = NULL, *second = NULL;
    td_unbalance u = {1, 1e-3, 0.4};
    lcomplex *ref;
    double e1, e2;
    assert_int_equal(td_system_create(td_case_model(c), &sys, NULL), TD_OK);
    assert_int_equal(td_synchronous_create(sys, &fast, NULL), TD_OK);
    ref = malloc((size_t)td_modal_state_count(sys) * sizeof *ref);
    assert_non_null(ref);
    reference_response(sys, W, &u, 1, ref);
    assert_int_equal(td_harmonic_compute(sys, W, &u, 1, &first, NULL), TD_OK);
    assert_int_equal(td_synchronous_response(fast, W, &u, 1, &second, NULL), TD_OK);
    e1 = q_error(first, ref, sys->ndof);
    e2 = q_error(second, ref, sys->ndof);
    if (!(e2 <= ACCURACY))
        fail_msg("%s at %g rad/s: second-order %.3g, first-order %.3g off the long-double solve", path, W, e2, e1);
    td_harmonic_free(&first);
    td_harmonic_free(&second);
    free(ref);
    td_synchronous_free(&fast);
    td_system_free(&sys);
    td_case_free(&c);
}

/* Near the rigid-body peaks, between them and the bending mode, and at the top of the range. */
static void test_accuracy(void **state)
{
    (void)state;
    accuracy_of("cases/paper-a.cfg", 138.2383);
    accuracy_of("cases/paper-a.cfg", 190.0);
    accuracy_of("cases/rig-notch.cfg", 146.237);
    accuracy_of("tests/data/case/all-keys.cfg", 150.0);
    accuracy_of("cases/rub-damped.cfg", 400.0);
}

/* A speed that is no speed is refused, with no response made; freeing twice is harmless. */
static void test_refusals(void **state)
{
    td_case *c = td_test_load_case("cases/paper-a.cfg", NULL, 0);
    td_system *sys = NULL;
    td_synchronous *fast = NULL;
    td_unbalance u = {1, 1e-3, 0.0};
    td_harmonic *h = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_system_create(td_case_model(c), &sys, &err), TD_OK);
    assert_int_equal(td_synchronous_create(sys, &fast, &err), TD_OK);
    assert_int_equal(td_synchronous_response(fast, -1.0, &u, 1, &h, &err), TD_ERR_INVALID);
    assert_int_equal(td_synchronous_response(fast, NAN, &u, 1, &h, &err), TD_ERR_INVALID);
    assert_null(h);
    td_synchronous_free(&fast);
    td_synchronous_free(&fast);
    td_system_free(&sys);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lag_filters),       cmocka_unit_test(test_integrators_races_housing_body),
        cmocka_unit_test(test_linear_controller), cmocka_unit_test(test_accuracy),
        cmocka_unit_test(test_refusals),          cmocka_unit_test(test_undamped_resonant),
        cmocka_unit_test(test_amb_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
