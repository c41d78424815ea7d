/*
 * AMB control that levitates (docs/theory.md): PID AMBs hold the reference rig centred under
 * gravity. Independent references: the static force balance (the AMBs carry the whole weight) and
 * integral action's defining property (a steady state has every sensor at zero).
 */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>

/* The sensor displacements (x, y at both AMB nodes) and the AMBs' summed force along y. */
static void amb_state(const td_sim *sim, double *worst_xs, double *fy)
{
    const td_model *m = td_sim_model(sim);
    int n = td_sim_dof_count(sim), i;
    double *q = calloc(2 * (size_t)n, sizeof *q), *v = q + n;
    assert_non_null(q);
    assert_int_equal(td_sim_get_state(sim, q, v), TD_OK);
    *worst_xs = 0.0;
    *fy = 0.0;
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        double f[2];
        assert_int_equal(td_model_get_amb(m, i, &a), TD_OK);
        *worst_xs =
            fmax(*worst_xs, fmax(fabs(q[TD_DOF(a.sensor_node, TD_DOF_X)]), fabs(q[TD_DOF(a.sensor_node, TD_DOF_Y)])));
        assert_int_equal(td_sim_amb_force(sim, i, f), TD_OK);
        *fy += f[1];
    }
    free(q);
}

static void step_to(td_sim *sim, double t_end)
{
    double t = td_sim_time(sim);
    td_error err;
    while (t < t_end) {
        td_status st = td_sim_step(sim, t_end, &t, &err);
        if (st != TD_OK && st != TD_EVENT)
            fail_msg("step: %s", err.message);
    }
}

/* Levitated start, a failure of 8 ms (the rotor falls 0.34 mm, clear of its retainers), restored:
 * centred before the failure and again once the transient has died away, with the weight carried. */
static void test_pid_levitates_and_recentres(void **state)
{
    td_case *c = td_test_load_case("tests/data/case/pid-short-fail.cfg", NULL, 0);
    const td_model *m = td_case_model(c);
    double weight = 9.81 * td_model_total_mass(m), xs, fy, pd_sag;
    td_amb a;
    td_sim *sim = NULL;
    (void)state;
    assert_int_equal(td_sim_create(m, td_case_sim_options(c), &sim, NULL), TD_OK);
    /* the static start: the integrators hold the bias, the sensors read zero to rounding, where PD
     * alone would leave the rotor about W/2 / (ki kp - ks) low */
    assert_int_equal(td_model_get_amb(m, 0, &a), TD_OK);
    pd_sag = 0.5 * weight / (a.ki * a.kp - a.ks);
    amb_state(sim, &xs, &fy);
    print_message("levitated start: |xs| <= %.3g m (PD sag about %.3g m), AMB force %.10g N, weight %.10g N\n", xs,
                  pd_sag, fy, weight);
    assert_true(xs <= 1e-15 && pd_sag > 4e-4);
    assert_close(fy, weight, 1e-11, 0.0);
    step_to(sim, 0.049);
    amb_state(sim, &xs, &fy);
    assert_true(xs <= 1e-12);
    assert_close(fy, weight, 1e-9, 0.0);
    /* after the failure: levitated and centred again (slowest excited mode about -3 1/s) */
    step_to(sim, 4.0);
    amb_state(sim, &xs, &fy);
    print_message("4 s after a failure of 8 ms: |xs| <= %.3g m, AMB force %.10g N\n", xs, fy);
    assert_true(xs <= 1e-12);
    assert_close(fy, weight, 1e-9, 0.0);
    td_sim_free(&sim);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pid_levitates_and_recentres),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
