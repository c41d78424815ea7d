/*
 * The amplifier's slew-rate limit (docs/theory.md, "AMB control") against its closed form. On an
 * AMB axis with the force lag tau and the limit S (A/s), dFc/dt = clip(r, +-ki S) with
 * r = (command - Fc)/tau. A rigid rotor (one lumped-mass element) carries one AMB with ks = 0 and
 * kp = 0, so that Fc follows the command alone:
 *
 *   release: the command steps from Fc0 to 0 at t = 0 (kd = 0: the command is 0 whatever the rotor
 *            does). r = -Fc/tau: while Fc > ki S tau the amplifier slews, Fc = Fc0 - ki S t, up to
 *            t1 = (Fc0 - ki S tau)/(ki S); then Fc = ki S tau e^{-(t - t1)/tau}.
 *   onset:   the AMB is off (no force), so the rotor falls freely, the sensor velocity is -g t and
 *            the command ki kd g t; Fc = ki kd g (t - tau + tau e^{-t/tau}) and r = ki kd g
 *            (1 - e^{-t/tau}) reaches ki S (S < kd g) at t* = -tau ln(1 - S/(kd g)); after it
 *            Fc = Fc(t*) + ki S (t - t*) (the command outruns the amplifier for good).
 *
 * The slew's kinks are root functions, so each instant is found as a root: the run's time_slewing
 * statistic is t1 in the first, end - t* in the second. Also: the law's pieces (the clip, the
 * integrator's anti-windup while slewing), and a limit never reached leaves a run with contacts
 * bit for bit as it is without one.
 */
#include "td_test.h"

#include "model/system_internal.h"
#include "sim/sim_internal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LENGTH 0.2   /* m */
#define DIAMETER 0.1 /* m */
#define KI 200.0     /* N/A */
#define TAU (1.0 / (2.0 * TD_PI * 100.0))
#define G 9.81          /* m/s^2 */
#define DROP_SAMPLES 80 /* ms of the drop run */

/* A rigid rotor at rest, speed 0, its AMB at node 0 (ks = kp = 0, derivative gain kd, limit slew). */
static td_model *rigid_rotor(double kd, double slew, double gravity)
{
    td_model *m = NULL;
    td_shaft_element el = {LENGTH, DIAMETER, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_shaft_options so = {TD_BEAM_EULER_BERNOULLI, TD_MASS_LUMPED, 0.0, 0.0, TD_SHEAR_HUTCHINSON, 0.0};
    td_amb a;
    memset(&a, 0, sizeof a);
    a.ki = KI;
    a.kd = kd;
    a.tau = TAU;
    a.force_capacity = 1e6;
    a.slew_rate = slew;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_set_shaft_options(m, &so, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_set_speed(m, 0.0, NULL), TD_OK);
    assert_int_equal(td_model_set_gravity(m, 0.0, -gravity, NULL), TD_OK);
    assert_int_equal(td_model_add_amb(m, &a, NULL), TD_OK);
    return m;
}

/* A simulation from rest with tight tolerances (the closed forms are followed to the rounding). */
static td_sim *start(const td_model *m)
{
    td_sim_options o;
    td_sim *s = NULL;
    td_error err;
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    o.solver.rtol = 1e-10;
    o.solver.atol = 1e-13;
    if (td_model_validate(m, &err) != TD_OK || td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    return s;
}

/* The lag state Fc of AMB 0's y axis now. */
static double fc_y(const td_sim *s)
{
    return N_VGetArrayPointer(s->dae.y)[s->dae.ow + s->sys->amb_axes[1].state];
}

static double time_slewing(const td_sim *s)
{
    td_sim_stats st;
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    return st.time_slewing;
}

/* The clip, the side it holds on, and the integrator stopped only while slewing deeper. */
static void test_law(void **state)
{
    td_amb_axis a;
    (void)state;
    memset(&a, 0, sizeof a);
    a.ki = -KI; /* the limit is |ki| S whatever the sign convention of ki */
    a.kint = 1e5;
    a.capacity = 1e4;
    assert_true(td_amb_axis_slew(&a, 1e9) == 1e9 && td_amb_axis_slewing(&a, 1e9) == 0); /* no limit */
    a.slew_rate = 50.0;                                                                 /* ki S = 1e4 N/s */
    assert_true(td_amb_axis_slew(&a, 3e4) == 1e4 && td_amb_axis_slewing(&a, 3e4) == 1);
    assert_true(td_amb_axis_slew(&a, -3e4) == -1e4 && td_amb_axis_slewing(&a, -3e4) == -1);
    assert_true(td_amb_axis_slew(&a, 0.5e4) == 0.5e4 && td_amb_axis_slewing(&a, 0.5e4) == 0);
    assert_true(td_amb_axis_slew(&a, 1e4) == 1e4 && td_amb_axis_slewing(&a, 1e4) == 0); /* at the kink */
    /* integrating xs moves r by -ki kint xs / tau (ki > 0): slewing up, xs < 0 drives r deeper and
     * the integrator stops; xs > 0 brings r back and integrates; mirrored when slewing down */
    a.ki = KI;
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, 0.0, 3e4) == 0.0);
    assert_true(td_amb_axis_integral_rate(&a, 1, 3e-4, 0.0, 3e4) == 3e-4);
    assert_true(td_amb_axis_integral_rate(&a, 1, 3e-4, 0.0, -3e4) == 0.0);
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, 0.0, -3e4) == -3e-4);
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, 0.0, 0.5e4) == -3e-4); /* inside the limit */
    assert_true(td_amb_axis_integral_rate(&a, 0, 3e-4, 0.0, 0.5e4) == 0.0);    /* off: holds */
}

/* The release (header): the ramp, the root instant t1 and the exponential after it. */
static void test_release(void **state)
{
    const double fc0 = 600.0, slew = 500.0, L = KI * slew, t1 = (fc0 - L * TAU) / L, dt = 2.5e-4;
    td_model *m = rigid_rotor(0.0, slew, 0.0);
    td_sim *s = start(m);
    double worst = 0.0, worst_ramp = 0.0, t;
    (void)state;
    /* the command steps to 0 from Fc0 at t = 0 */
    N_VGetArrayPointer(s->dae.y)[s->dae.ow + s->sys->amb_axes[1].state] = fc0;
    assert_int_equal(td_sim_restart_after_change(s), TD_OK);
    s->monitor.slewing = td_sim_amb_slewing_axes(s, N_VGetArrayPointer(s->dae.y));
    assert_int_equal(s->monitor.slewing, 1);
    for (t = dt; t < 12 * TAU; t += dt) {
        double exact = t < t1 ? fc0 - L * t : L * TAU * exp(-(t - t1) / TAU);
        assert_int_equal(td_sim_step(s, t, NULL, NULL), TD_OK);
        if (t < t1)
            worst_ramp = fmax(worst_ramp, fabs(fc_y(s) - exact));
        else
            worst = fmax(worst, fabs(fc_y(s) - exact));
    }
    print_message("release: Fc within %.3g N of the ramp, %.3g N of the exponential (Fc0 %g N); slewing %.15g s, t1 "
                  "%.15g s\n",
                  worst_ramp, worst, fc0, time_slewing(s), t1);
    /* measured 1.4e-10 N on the ramp (linear: the integrator follows it to the rounding), 1.2e-6 N
     * on the exponential, the root instant to 3e-13 s */
    assert_true(worst_ramp < 1e-8 && worst < 1e-4);
    assert_close(time_slewing(s), t1, 0.0, 1e-11);
    td_sim_free(&s);
    td_model_free(&m);
}

/* Without the limit the same step decays as Fc0 e^{-t/tau} from the start: the clip above acts. */
static void test_release_unlimited(void **state)
{
    const double fc0 = 600.0, t = 3e-3;
    td_model *m = rigid_rotor(0.0, 0.0, 0.0);
    td_sim *s = start(m);
    (void)state;
    N_VGetArrayPointer(s->dae.y)[s->dae.ow + s->sys->amb_axes[1].state] = fc0;
    assert_int_equal(td_sim_restart_after_change(s), TD_OK);
    assert_int_equal(td_sim_step(s, t, NULL, NULL), TD_OK);
    assert_close(fc_y(s), fc0 * exp(-t / TAU), 1e-5, 0.0);
    assert_true(time_slewing(s) == 0.0);
    td_sim_free(&s);
    td_model_free(&m);
}

/* The onset in a free fall with the AMB off (header): the lag, the root instant t* and the ramp. */
static void test_onset(void **state)
{
    const double kd = 40.0, slew = 200.0, a = KI * kd * G, L = KI * slew, end = 0.01, dt = 2.5e-4;
    const double ts = -TAU * log(1.0 - slew / (kd * G)), fs = a * (ts - TAU + TAU * exp(-ts / TAU));
    td_model *m = rigid_rotor(kd, slew, G);
    td_change off = {0.0, TD_CHANGE_AMB_OFF, 0, 0.0, 0.0};
    td_sim *s;
    double worst = 0.0, t;
    (void)state;
    assert_int_equal(td_model_add_change(m, &off, NULL), TD_OK);
    s = start(m);
    for (t = dt; t < end + 0.5 * dt; t += dt) {
        double exact = t < ts ? a * (t - TAU + TAU * exp(-t / TAU)) : fs + L * (t - ts);
        assert_int_equal(td_sim_step(s, fmin(t, end), NULL, NULL), TD_OK);
        worst = fmax(worst, fabs(fc_y(s) - exact) / exact);
    }
    print_message("onset: Fc within %.3g relative of the closed form; slewing %.15g s, end - t* %.15g s\n", worst,
                  time_slewing(s), end - ts);
    /* measured 5.6e-8 relative, the root instant to 3.5e-11 s */
    assert_true(worst < 1e-6);
    assert_close(time_slewing(s), end - ts, 0.0, 1e-9);
    td_sim_free(&s);
    td_model_free(&m);
}

/* Case A's rig (cases/paper-a.cfg) dropped onto its retainers under gravity (both AMBs off until
 * 40 ms) and caught again, without free flight, with the amplifiers' limit `slew` (A/s; "0": none):
 * q and v at every ms into qv, the solver's counts into *st. */
static void run_drop(const char *slew, double *qv, td_sim_stats *st)
{
    char s0[64], s1[64];
    const char *ov[] = {"solver.free_flight=false",
                        "solver.rtol=1e-6",
                        "start=\"rest\"",
                        "gravity={enabled=true;}",
                        "schedule=({time=0.0; amb_off=0;}, {time=0.0; amb_off=1;}, {time=0.04; amb_on=0;}, "
                        "{time=0.04; amb_on=1;})",
                        s0,
                        s1};
    td_case *c;
    td_sim *s = NULL;
    td_error err;
    int i, n;
    snprintf(s0, sizeof s0, "ambs[0].slew_rate=%s", slew);
    snprintf(s1, sizeof s1, "ambs[1].slew_rate=%s", slew);
    c = td_test_load_case("cases/paper-a.cfg", ov, 7);
    if (td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    n = td_sim_dof_count(s);
    for (i = 1; i <= DROP_SAMPLES; i++) {
        td_status r;
        while ((r = td_sim_step(s, 1e-3 * i, NULL, &err)) == TD_EVENT) {
        }
        assert_int_equal(r, TD_OK);
        assert_int_equal(td_sim_get_state(s, qv + 2 * n * (i - 1), qv + 2 * n * (i - 1) + n), TD_OK);
    }
    assert_int_equal(td_sim_stats_get(s, st), TD_OK);
    td_sim_free(&s);
    td_case_free(&c);
}

/* A limit never reached: the same run, bit for bit (the clip is inactive, and its root functions
 * never change sign); a limit reached (the impacts and the catch need ~3e3 A/s): another run. */
static void test_unreached_limit(void **state)
{
    const int n = 2 * 13 * 4 * DROP_SAMPLES; /* q and v of the rig's 13 nodes */
    double *a = calloc((size_t)n, sizeof(double)), *b = calloc((size_t)n, sizeof(double));
    td_sim_stats sa, sb;
    (void)state;
    assert_true(a && b);
    run_drop("0.0", a, &sa);
    run_drop("1.0e7", b, &sb);
    print_message("drop: %ld steps, %ld restarts, %ld contact onsets; slewing %g s with 1e7 A/s\n", sa.steps,
                  sa.restarts, sa.contact_onsets, sb.time_slewing);
    assert_true(sa.contact_onsets >= 2 && sb.time_slewing == 0.0);
    assert_true(memcmp(a, b, sizeof(double) * (size_t)n) == 0);
    assert_true(sa.steps == sb.steps && sa.restarts == sb.restarts && sa.residual_evals == sb.residual_evals &&
                sa.events == sb.events && sa.peak_normal_force == sb.peak_normal_force);
    run_drop("500.0", b, &sb);
    print_message("drop: slewing %g s with 500 A/s\n", sb.time_slewing);
    assert_true(sb.time_slewing > 0.0 && memcmp(a, b, sizeof(double) * (size_t)n) != 0);
    free(a);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_law),   cmocka_unit_test(test_release),         cmocka_unit_test(test_release_unlimited),
        cmocka_unit_test(test_onset), cmocka_unit_test(test_unreached_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
