/*
 * The second-order synchronous response of the API 617 sweep (lib/modal/synchronous.c) against the
 * first-order solve of td_harmonic_compute (lib/modal/harmonic.c), a second method: the whole state
 * Z = [Q; V; S] at several speeds, below, near and above the machines' rigid-body and bending
 * criticals, on cases with every kind of controller state the elimination handles: lag filters
 * (paper-a), PID integrators, race bodies, a housing body on mounts and a reduced shaft (all-keys),
 * a linear controller with a lag (rig-notch) and without one, its current then acting directly
 * (rig-notch, tau = 0).
 *
 * Tolerance: the two solves round differently, and the dynamic stiffness of a stiff shaft on soft
 * bearings is ill-conditioned (cond ~ (highest mode / speed)^2): the gaps seen are up to 1e-10 of
 * each block's largest entry (rig-notch at 190 rad/s), some 1e6 eps; 1e-9 leaves a factor 10. A wrong
 * term of the elimination is an O(1) error.
 */
#include "td_test.h"

#include "modal/modal_internal.h"
#include "touchdown/case.h"
#include "touchdown/modal.h"
#include "touchdown/system.h"

#include <math.h>
#include <stdlib.h>

#define TOLERANCE 1e-9

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

/* Both solves of `path` (with overrides) at each speed; returns the controller state count. */
static int compare_case(const char *path, const char **ov, int n_ov, int node, int want_states)
{
    static const double speeds[] = {0.0, 1.0, 60.0, 117.0, 150.0, 190.0, 400.0, 1200.0};
    td_case *c = td_test_load_case(path, ov, n_ov);
    td_system *sys = NULL;
    td_synchronous *fast = NULL;
    td_unbalance u[2] = {{0, 1e-3, 0.4}, {0, 2e-3, -1.9}};
    td_error err;
    size_t k;
    int nd, nf;
    assert_int_equal(td_system_create(td_case_model(c), &sys, &err), TD_OK);
    if (td_synchronous_create(sys, &fast, &err) != TD_OK)
        fail_msg("%s: %s", path, err.message);
    nd = td_system_dof_count(sys);
    nf = td_modal_state_count(sys) - 2 * nd;
    assert_true(nf >= want_states);
    u[0].node = node;
    u[1].node = node + 2;
    for (k = 0; k < sizeof speeds / sizeof speeds[0]; k++) {
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
        cmocka_unit_test(test_lag_filters),
        cmocka_unit_test(test_integrators_races_housing_body),
        cmocka_unit_test(test_linear_controller),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
