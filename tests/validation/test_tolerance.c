/*
 * The per-component absolute tolerances (lib/sim/tolerance.c) against a converged reference.
 *
 * cases/rub-damped.cfg to 0.11 s: a damped shaft lands on its compliant ball-bearing retainers
 * (races on mounts, Kelvin-Voigt contact); the run's peak normal force is that of the first impact
 * (0.106 s), a single deterministic event, not a draw of a bouncing sequence. Its error is the
 * integrator's, so it converges with the tolerances: at the library's defaults (rtol 1e-6,
 * atol 1e-9 m) it lies within 0.5 % of a reference at 100 times tighter tolerances, and at 10 times
 * tighter its error is below a fifth of the defaults' (the local error control holds the global
 * error about in proportion to the tolerance).
 *
 * What it guards: the slopes' and velocities' tolerances are scaled from the displacement one, and
 * the scale decides this error. The slopes' atol / L_e is not the loosest scale a deflection
 * argument allows (atol 27 / (4 L_e), the Hermite bound of the deflection between two nodes); with
 * that looser scale the defaults' error here more than doubles and this test fails
 * (lib/sim/tolerance.c has the numbers and says why the scale stays).
 */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>

static double first_impact_peak(const char *rtol, const char *atol)
{
    const char *ovs[3] = {"end_time = 0.11", rtol, atol};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ovs, 3);
    td_sim *s = td_test_new_sim(td_case_model(c), c);
    td_sim_stats st;
    td_test_step_to(s, td_case_end_time(c));
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    printf("%s, %s: peak normal force %.6f N at %.9f s, retainer %d, %ld steps\n", rtol, atol, st.peak_normal_force,
           st.peak_time, st.peak_retainer, st.steps);
    /* the first impact: retainer 0 (next to the unbalance), just after the step of 0.1 s */
    assert_int_equal(st.peak_retainer, 0);
    assert_true(st.peak_time > 0.1 && st.peak_time < 0.108);
    td_sim_free(&s);
    td_case_free(&c);
    return st.peak_normal_force;
}

static void test_first_impact_converges(void **state)
{
    double ref = first_impact_peak("solver.rtol = 1e-8", "solver.atol = 1e-11");
    double f6 = first_impact_peak("solver.rtol = 1e-6", "solver.atol = 1e-9");
    double f7 = first_impact_peak("solver.rtol = 1e-7", "solver.atol = 1e-10");
    double e6 = td_rel_diff(f6, ref), e7 = td_rel_diff(f7, ref);
    (void)state;
    printf("relative error against the reference: %.3g (defaults), %.3g (10 times tighter)\n", e6, e7);
    assert_true(e6 < 5e-3);
    assert_true(e7 < 0.2 * e6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_impact_converges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
