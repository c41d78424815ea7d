/*
 * td_campbell_critical_speeds (lib/modal/campbell.c) against td_modal_critical_speeds, the search
 * with its own eigen-solves: the same critical speeds bit for bit (the reused grid solves are the
 * very solves the search would make), on the rig with lag filters (paper-a), with a linear
 * controller (rig-notch) and with PID integrators, races and a housing body (all-keys); and the
 * fallback to fresh solves when the diagram is of another grid or another system (a stiffer machine,
 * whose critical speeds differ), or absent.
 */
#include "td_test.h"

#include "touchdown/case.h"
#include "touchdown/modal.h"
#include "touchdown/system.h"

#include <stdlib.h>
#include <string.h>

#define CAP 64

/* The search of td_modal_critical_speeds on sys with options opt into cs (CAP); their count. */
static int search(const td_system *sys, const td_modal_options *opt, td_critical_speed *cs)
{
    td_error err;
    int n = -1;
    memset(cs, 0, CAP * sizeof *cs);
    if (td_modal_critical_speeds(sys, opt, cs, CAP, &n, &err) != TD_OK)
        fail_msg("%s", err.message);
    assert_true(n >= 0 && n <= CAP);
    return n;
}

/* td_campbell_critical_speeds(c, sys, opt) gives the n critical speeds `want`, bit for bit. */
static void same_speeds(const td_campbell *c, const td_system *sys, const td_modal_options *opt,
                        const td_critical_speed *want, int n)
{
    td_critical_speed got[CAP];
    td_error err;
    int count = -1;
    memset(got, 0, sizeof got);
    if (td_campbell_critical_speeds(c, sys, opt, got, CAP, &count, &err) != TD_OK)
        fail_msg("%s", err.message);
    assert_int_equal(count, n);
    assert_memory_equal(got, want, (size_t)n * sizeof *got);
}

/* Another system's (`other`, stiffer AMBs) critical speeds from c: its own, solved afresh, not c's
 * (n of them in `mine`); so c's are not handed to a system they are not of. */
static void other_system(const td_campbell *c, const td_modal_options *opt, const td_critical_speed *mine, int n)
{
    /* rig.cfg's AMBs, stiffer (kp 1.5e4 A/m, not 1e4): other critical speeds */
    const char *stiffer[] = {
        "ambs = ( { node = 3; ks = 1.0e6; ki = 200.0; kp = 1.5e4; kd = 40.0; bandwidth = 100.0; force_capacity = "
        "1700.0; "
        "saturation = false; air_gap = 1.2e-3; }, { node = 9; ks = 1.0e6; ki = 200.0; kp = 1.5e4; kd = 40.0; "
        "bandwidth = 100.0; force_capacity = 1700.0; saturation = false; air_gap = 1.2e-3; } )"};
    td_case *cs = td_test_load_case("cases/paper-a.cfg", stiffer, 1);
    td_system *other = NULL;
    td_critical_speed want[CAP];
    td_error err;
    int m;
    assert_int_equal(td_system_create(td_case_model(cs), &other, &err), TD_OK);
    m = search(other, opt, want);
    assert_true(m > 0);
    assert_true(m != n || memcmp(want, mine, (size_t)n * sizeof *want) != 0);
    same_speeds(c, other, opt, want, m);
    td_system_free(&other);
    td_case_free(&cs);
}

/* The diagram's reuse on the case's system; with `others`, the fallbacks: another system, another grid. */
static void check_case(const char *path, int others)
{
    td_case *cs = td_test_load_case(path, NULL, 0);
    td_system *sys = NULL;
    td_campbell *c = NULL;
    td_modal_options opt = *td_case_modal_options(cs);
    td_critical_speed want[CAP];
    td_error err;
    int n;
    assert_int_equal(td_system_create(td_case_model(cs), &sys, &err), TD_OK);
    opt.speed_steps = 13; /* the case's grid is finer: the test's time */
    if (td_campbell_compute(sys, &opt, &c, &err) != TD_OK)
        fail_msg("%s", err.message);
    n = search(sys, &opt, want);
    assert_true(n > 0);
    same_speeds(c, sys, &opt, want, n);
    if (others) {
        other_system(c, &opt, want, n); /* another system: solved afresh */
        same_speeds(NULL, sys, &opt, want, n);
        opt.speed_steps = 12; /* another grid: solved afresh */
        n = search(sys, &opt, want);
        same_speeds(c, sys, &opt, want, n);
    }
    td_campbell_free(&c);
    td_system_free(&sys);
    td_case_free(&cs);
}

static void test_lag_filters(void **state)
{
    (void)state;
    check_case("cases/paper-a.cfg", 1);
}

static void test_linear_controller(void **state)
{
    (void)state;
    check_case("cases/rig-notch.cfg", 0);
}

static void test_integrators_races_housing_body(void **state)
{
    (void)state;
    check_case("tests/data/case/all-keys.cfg", 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lag_filters),
        cmocka_unit_test(test_linear_controller),
        cmocka_unit_test(test_integrators_races_housing_body),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
