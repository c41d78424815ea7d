/*
 * The clearance margin, the contact flag and the shock outcome of a run (docs/output-format.md,
 * "Clearance margin and shock outcome").
 *
 * A Jeffcott rotor (10 kg disc at the middle node of a massless-ish 1 m shaft on damped, anisotropic
 * plain bearings, no AMB, no gravity) with a retainer at the disc, started on its steady unbalance
 * orbit: an ellipse whose major semi-axis is the harmonic response's (td_harmonic_orbit, a complex
 * linear solve in the frequency domain: the second method). Its smallest margin over the run is
 * clearance - major. The output samples are far apart (20 Hz against two radius peaks per 25 ms
 * revolution), so the largest sampled radius misses the peak: the margin must come from between
 * the points, in the closed-form flight from its own solution, in IDA from the Hermite of r.
 */
#include "td_test.h"

#include "touchdown/modal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <string.h>

#define SPEED 250.0    /* rad/s: below both criticals (about 350 and 420 rad/s) */
#define UNBALANCE 1e-4 /* kg m */
#define PHASE 2.27     /* rad: the half-revolution samples see the orbit's minor axis */
#define WIDE 1.5       /* the clearance over the orbit's major semi-axis: the flight takes long steps */

/* The rotor; clearance c at the disc's retainer; a second unbalance entry (index 1, zero) that the
 * schedule may raise for `pulse` s from t_pulse (0: none). */
/* The rotor with friction coefficient mu at its retainer, no schedule. */
static td_model *jeffcott_mu(double c, double mu)
{
    td_model *m = NULL;
    td_shaft_element el = {0.5, 0.05, 0.0, {2.11e11, 8.1e10, 1.0}};
    td_bearing b0 = {0, 1.0e6, 2.0e6, 2000.0, 2000.0}, b2 = {2, 1.0e6, 2.0e6, 2000.0, 2000.0};
    td_retainer r = {.node = 1, .clearance = c, .shaft_radius = 0.025, .bore_radius = 0.025 + c, .friction = mu};
    td_unbalance u = {1, UNBALANCE, PHASE}, u2 = {1, 0.0, PHASE};
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_point_mass(m, 1, 10.0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b2, NULL), TD_OK);
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, &u2, NULL), TD_OK);
    assert_int_equal(td_model_set_speed(m, SPEED, NULL), TD_OK);
    return m;
}

static td_model *jeffcott(double c, double t_pulse, double pulse, double u_pulse)
{
    td_model *m = jeffcott_mu(c, 0.1);
    if (pulse > 0.0) {
        td_change on = {t_pulse, TD_CHANGE_UNBALANCE, 1, u_pulse, PHASE};
        td_change off = {t_pulse + pulse, TD_CHANGE_UNBALANCE, 1, 0.0, PHASE};
        assert_int_equal(td_model_add_change(m, &on, NULL), TD_OK);
        assert_int_equal(td_model_add_change(m, &off, NULL), TD_OK);
    }
    return m;
}

/* The steady orbit's major semi-axis at the disc, from the harmonic response. */
static double orbit_major(void)
{
    td_model *m = jeffcott(1e-3, 0.0, 0.0, 0.0);
    td_system *sys = NULL;
    td_harmonic *h = NULL;
    td_unbalance u = {1, UNBALANCE, PHASE};
    td_orbit o;
    assert_int_equal(td_system_create(m, &sys, NULL), TD_OK);
    assert_int_equal(td_harmonic_compute(sys, SPEED, &u, 1, &h, NULL), TD_OK);
    assert_int_equal(td_harmonic_orbit(h, 1, &o), TD_OK);
    td_harmonic_free(&h);
    td_system_free(&sys);
    td_model_free(&m);
    return o.major;
}

/* Run the model to t_end from `start` with samples at `rate` (penalty: a compliant contact, else the
 * rigid constraint); the summary into *s. */
static void run(td_model *m, int flight, td_start start, int penalty, double t_end, double rate, td_run_summary *s)
{
    td_sim_options o;
    td_output_options out;
    td_sim *sim = NULL;
    td_error err;
    td_sim_options_default(&o);
    o.start = start;
    o.solver.free_flight = flight;
    if (penalty) {
        o.contact.model = TD_CONTACT_PENALTY;
        o.contact.stiffness = 1e8;
        o.contact.exponent = 1.0;
    }
    td_output_options_default(&out);
    out.sample_rate = rate;
    if (td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    if (td_run(sim, t_end, &out, NULL, NULL, s, &err) != TD_OK)
        fail_msg("td_run: %s", err.message);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* The largest radius of the node over the output grid, sampled again with td_sim_step (the samples
 * a file holds). */
static double sampled_max(double c, int flight, double t_end, double rate)
{
    td_model *m = jeffcott(c, 0.0, 0.0, 0.0);
    td_sim_options o;
    td_sim *sim = NULL;
    double best = 0.0;
    long k;
    td_sim_options_default(&o);
    o.start = TD_START_ORBIT;
    o.solver.free_flight = flight;
    assert_int_equal(td_sim_create(m, &o, &sim, NULL), TD_OK);
    for (k = 1; k <= (long)(t_end * rate + 0.5); k++) {
        td_retainer_state st;
        double t = (double)k / rate;
        td_status r;
        while ((r = td_sim_step(sim, t, NULL, NULL)) == TD_EVENT)
            ;
        assert_int_equal(r, TD_OK);
        assert_int_equal(td_sim_retainer_state(sim, 0, &st), TD_OK);
        best = fmax(best, st.radius);
    }
    td_sim_free(&sim);
    td_model_free(&m);
    return best;
}

/* c - major from the harmonic response, against the margin of the run with samples every half
 * revolution (they see one point of the ellipse: the largest sampled radius misses the peak). With
 * IDA also against its own solution sampled densely (its interpolant, 20 kHz: 80 points a revolution):
 * the Hermite's part of the error apart from the integration's. */
static void near_miss(int flight, double tol, double tol_own)
{
    double major = orbit_major(), c = WIDE * major, t_end = 0.2, rate = SPEED / TD_PI;
    double sampled = sampled_max(c, flight, t_end, rate), dense = flight ? major : sampled_max(c, 0, t_end, 2e4);
    td_run_summary s;
    run(jeffcott(c, 0.0, 0.0, 0.0), flight, TD_START_ORBIT, 0, t_end, rate, &s);
    print_message("%s: major %.9e m, clearance %.9e m: margin %.9e m against c - major %.9e m (error %.2e m), against "
                  "c - the densely sampled radius %.9e m (error %.2e m); largest sampled radius %.9e m; %ld steps\n",
                  flight ? "flight" : "IDA", major, c, s.min_clearance_margin, c - major,
                  s.min_clearance_margin - (c - major), c - dense, s.min_clearance_margin - (c - dense), sampled,
                  s.stats.steps);
    assert_true(sampled < major - 0.5 * (c - major)); /* the samples alone miss the peak */
    assert_close(s.min_clearance_margin, c - major, 0.0, tol);
    assert_close(s.min_clearance_margin, c - dense, 0.0, tol_own);
    assert_close(s.retainers[0].totals.min_clearance_margin, s.min_clearance_margin, 0.0, 0.0);
    assert_int_equal(s.min_clearance_retainer, 0);
    assert_int_equal(s.contact_happened, 0);
    assert_int_equal(s.shock_outcome, TD_SHOCK_NONE);
}

/* The closed-form flight's own search: to TD_MARGIN_RTOL of the clearance (measured 1e-13 m); without
 * the search, the radii at the flight's steps alone miss the peak by more. */
static void test_near_miss_flight(void **state)
{
    double c = WIDE * orbit_major();
    (void)state;
    near_miss(1, TD_MARGIN_RTOL * c, TD_MARGIN_RTOL * c);
}

/* IDA with the Hermite of r between its steps: to its own solution (the Hermite's error, measured
 * 6e-11 m over its ~0.26 ms steps; the largest r at the steps alone misses by 3e-10 m) and to the
 * harmonic response (with the integration's amplitude error at the default tolerances, measured
 * 1.7e-8 m: 0.2 % of the radius). */
static void test_near_miss_ida(void **state)
{
    double c = WIDE * orbit_major();
    (void)state;
    near_miss(0, 5e-3 * c, 2e-5 * c);
}

/* The margin at an output time inside an integrator step counts the step only up to that time: at
 * outputs every 20 us (IDA's steps are ~0.26 ms, so most outputs fall inside one, its end held beyond
 * them), over the first revolution, while the largest radius so far still grows, the margin equals
 * c - the largest radius sampled so far, to the samples' spacing (the radius between two samples
 * 20 us apart exceeds the larger end by r w^2 h^2 / 8 ~ 3e-11 m) and the Hermite's error (6e-11 m).
 * A step counted whole would run ahead of the samples by up to 2e-7 m on the orbit's rising flanks. */
static void test_margin_up_to_output(void **state)
{
    double major = orbit_major(), c = WIDE * major, r_max = 0.0, worst = 0.0;
    td_model *m = jeffcott(c, 0.0, 0.0, 0.0);
    td_sim_options o;
    td_sim *sim = NULL;
    long k;
    (void)state;
    td_sim_options_default(&o);
    o.start = TD_START_ORBIT;
    o.solver.free_flight = 0;
    assert_int_equal(td_sim_create(m, &o, &sim, NULL), TD_OK);
    for (k = 1; k <= 1300; k++) {
        td_retainer_state st;
        td_retainer_totals tot;
        assert_int_equal(td_sim_step(sim, 2e-5 * (double)k, NULL, NULL), TD_OK);
        assert_int_equal(td_sim_retainer_state(sim, 0, &st), TD_OK);
        assert_int_equal(td_sim_retainer_totals(sim, 0, &tot), TD_OK);
        r_max = fmax(r_max, st.radius);
        worst = fmax(worst, fabs(tot.min_clearance_margin - (c - r_max)));
    }
    print_message("margin at the outputs against c - the largest radius sampled so far: worst %.3e m\n", worst);
    assert_true(worst < 2e-10);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* The orbit outside the clearance: it touches at once and bounces on its retainer to the end; the rigid
 * constraint holds the node on the clearance (margin 0 to its drift), a compliant contact lets it in
 * (a negative margin: its penetration, about the orbit's overshoot force over the stiffness). */
static void test_drop(void **state)
{
    double major = orbit_major();
    td_run_summary s;
    (void)state;
    run(jeffcott(0.5 * major, 0.0, 0.0, 0.0), 1, TD_START_REST, 0, 0.2, 1000.0, &s);
    print_message("constraint: margin %.3e m, drift %.3e m, in contact at the end %d, outcome %s\n",
                  s.min_clearance_margin, s.stats.worst_drift, !isnan(s.contact_onset),
                  td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_int_equal(s.contact_happened, 1);
    assert_int_equal(s.free_at_end, 0);
    /* it bounces on the retainer: a drop only when the end finds it in contact in a sustained rub, else
       too soon to tell (no AMB here to fail) */
    assert_int_equal(s.shock_outcome,
                     !isnan(s.contact_onset) && s.regime != TD_REGIME_BOUNCE ? TD_SHOCK_DROP : TD_SHOCK_UNSETTLED);
    assert_true(fabs(s.min_clearance_margin) <= 1e-3 * major);
    run(jeffcott(0.5 * major, 0.0, 0.0, 0.0), 1, TD_START_REST, 1, 0.2, 1000.0, &s);
    print_message("penalty: margin %.3e m, in contact at the end %d, outcome %s\n", s.min_clearance_margin,
                  !isnan(s.contact_onset), td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_int_equal(s.contact_happened, 1);
    assert_int_equal(s.free_at_end, 0);
    /* the compliant contact chatters: a drop when the end finds it in contact, else too soon to tell */
    assert_int_equal(s.shock_outcome, isnan(s.contact_onset) ? TD_SHOCK_UNSETTLED : TD_SHOCK_DROP);
    assert_true(s.min_clearance_margin < -1e-3 * major);
}

/* A pulse of unbalance pushes the orbit out for a while, then the damped rotor returns inside: a
 * pulse much shorter than a revolution touches and leaves (touch), one of several revolutions whirls
 * round the clearance (rub); both end free. */
static void test_touch_and_rub(void **state)
{
    double major = orbit_major(), c = 2.0 * major;
    td_run_summary s;
    (void)state;
    run(jeffcott(c, 0.05, 0.004, 4.0 * UNBALANCE), 1, TD_START_ORBIT, 0, 0.4, 1000.0, &s);
    print_message("short pulse: margin %.3e m, contacts %ld, sustained %ld, touch-and-go %ld, free at end %d: %s\n",
                  s.min_clearance_margin, s.contacts, s.retainers[0].totals.contacts,
                  s.retainers[0].totals.touch_and_go, s.free_at_end,
                  td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_int_equal(s.contact_happened, 1);
    assert_int_equal(s.retainers[0].totals.contacts, 0);
    assert_int_equal(s.shock_outcome, TD_SHOCK_TOUCH);
    run(jeffcott(c, 0.05, 0.1, 4.0 * UNBALANCE), 1, TD_START_ORBIT, 0, 0.4, 1000.0, &s);
    print_message("long pulse: margin %.3e m, contacts %ld, sustained %ld, touch-and-go %ld, free at end %d: %s\n",
                  s.min_clearance_margin, s.contacts, s.retainers[0].totals.contacts,
                  s.retainers[0].totals.touch_and_go, s.free_at_end,
                  td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_int_equal(s.contact_happened, 1);
    assert_true(s.retainers[0].totals.contacts > 0);
    assert_int_equal(s.free_at_end, 1);
    assert_int_equal(s.shock_outcome, TD_SHOCK_RUB);
}

/* A long shock pulse presses the rotor onto its retainer for several revolutions; without friction it
 * hardly whirls there (less than TD_TOUCH_AND_GO_ANGLE), but contact longer than a revolution is
 * sustained: a rub, not a touch. Then it lifts off and ends free. */
static void test_pinned_is_rub(void **state)
{
    double major = orbit_major(), c = 2.0 * major, revolution = 2.0 * TD_PI / SPEED;
    td_model *m = jeffcott_mu(c, 0.0);
    td_housing_pulse push = {TD_PULSE_HALF_SINE, 20.0, 0.1, 0.05, {0.0, -1.0}};
    td_run_summary s;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &push, NULL), TD_OK);
    run(m, 0, TD_START_ORBIT, 0, 0.5, 1000.0, &s);
    print_message("pinned: in contact %.4g s (a revolution %.4g s), sustained %ld, touch-and-go %ld, free at end %d: "
                  "%s\n",
                  s.retainers[0].totals.contact_time, revolution, s.retainers[0].totals.contacts,
                  s.retainers[0].totals.touch_and_go, s.free_at_end,
                  td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_true(s.retainers[0].totals.contact_time > revolution);
    assert_int_equal(s.retainers[0].totals.contacts, 0); /* by the whirl angle alone, a touch-and-go */
    assert_int_equal(s.free_at_end, 1);
    assert_int_equal(s.shock_outcome, TD_SHOCK_RUB);
}

/* The pinned rotor's run ended one revolution after its last contact: free at the end, but too soon to
 * tell (unsettled), not a drop; ended pressed onto its retainer while the pulse still acts, unsettled too
 * (a drop needs an AMB off or a sustained rub held to the end). */
static void test_unsettled(void **state)
{
    double major = orbit_major(), c = 2.0 * major, revolution = 2.0 * TD_PI / SPEED, last;
    td_housing_pulse push = {TD_PULSE_HALF_SINE, 20.0, 0.1, 0.05, {0.0, -1.0}};
    td_model *m = jeffcott_mu(c, 0.0);
    td_run_summary s;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &push, NULL), TD_OK);
    run(m, 0, TD_START_ORBIT, 0, 0.5, 1000.0, &s); /* run() frees the model */
    last = s.last_contact_time;
    assert_true(last > 0.1 && last < 0.5 - 5.0 * revolution); /* settled by 0.5 s (test_pinned_is_rub) */
    m = jeffcott_mu(c, 0.0);
    assert_int_equal(td_model_add_housing_shock(m, &push, NULL), TD_OK);
    run(m, 0, TD_START_ORBIT, 0, last + revolution, 1000.0, &s);
    print_message("ended %.4g s after the last contact (%.4g s; a revolution %.4g s): free at end %d, %s\n",
                  s.t_reached - s.last_contact_time, s.last_contact_time, revolution, s.free_at_end,
                  td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_int_equal(s.free_at_end, 0);
    assert_true(isnan(s.contact_onset)); /* free at the end */
    assert_int_equal(s.shock_outcome, TD_SHOCK_UNSETTLED);
    assert_string_equal(td_shock_outcome_name(TD_SHOCK_UNSETTLED), "unsettled");
    m = jeffcott_mu(c, 0.0);
    assert_int_equal(td_model_add_housing_shock(m, &push, NULL), TD_OK);
    run(m, 0, TD_START_ORBIT, 0, 0.1, 1000.0, &s); /* pressed onto the retainer at the end, the pulse on */
    assert_false(isnan(s.contact_onset));
    assert_int_equal(s.shock_outcome, TD_SHOCK_UNSETTLED); /* it may yet lift off (a drop: tests/cli/test_drop.sh) */
}

/* The revolution that bounds a touch is the one at the contacts: the pinned rotor of test_pinned_is_rub
 * whose model says 60 rad/s (a revolution of 0.105 s, longer than its 0.09 s in contact, as a run-down's
 * slow end would be) but that spins at SPEED from the start (td_sim_set_speed) rubs as the one at SPEED
 * does. It runs 0.7 s: past the model's free_window (0.52 s) after the last contact, free at the end. */
static void test_contact_speed(void **state)
{
    double major = orbit_major(), c = 2.0 * major;
    td_housing_pulse push = {TD_PULSE_HALF_SINE, 20.0, 0.1, 0.05, {0.0, -1.0}};
    td_model *m = jeffcott_mu(c, 0.0);
    td_sim_options o;
    td_output_options out;
    td_sim *sim = NULL;
    td_run_summary s;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &push, NULL), TD_OK);
    assert_int_equal(td_model_set_speed(m, 60.0, NULL), TD_OK);
    td_sim_options_default(&o);
    td_output_options_default(&out);
    out.sample_rate = 1000.0;
    assert_int_equal(td_sim_create(m, &o, &sim, NULL), TD_OK);
    assert_int_equal(td_sim_set_speed(sim, SPEED, NULL), TD_OK);
    assert_int_equal(td_run(sim, 0.7, &out, NULL, NULL, &s, NULL), TD_OK);
    print_message("model speed %g rad/s, at the first contact %g rad/s: in contact %.4g s, %s\n", s.speed,
                  s.contact_speed, s.retainers[0].totals.contact_time,
                  td_shock_outcome_name((td_shock_outcome)s.shock_outcome));
    assert_close(s.contact_speed, SPEED, 0.0, 0.0);
    assert_true(s.retainers[0].totals.contact_time > 2.0 * TD_PI / SPEED);
    assert_int_equal(s.retainers[0].totals.contacts, 0);
    assert_int_equal(s.shock_outcome, TD_SHOCK_RUB);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* A run that does not reach its end has no margin and no outcome: null in JSON; it touched only if it
 * had a contact before it stopped, else that is undetermined. */
static void test_failed_run(void **state)
{
    td_run_summary s;
    char json[65536];
    (void)state;
    td_run_summary_failed(&s, 0.0, 1.0, 100.0, TD_START_REST, TD_ERR_SOLVER, "failed on purpose");
    assert_true(td_is_undefined(s.min_clearance_margin));
    assert_int_equal(s.contact_happened, -1);
    assert_int_equal(s.shock_outcome, TD_SHOCK_UNDEFINED);
    assert_true(td_run_summary_json(json, sizeof json, &s) > 0);
    assert_non_null(strstr(json, "\"min_clearance_margin\":null"));
    assert_non_null(strstr(json, "\"contact_happened\":null"));
    assert_non_null(strstr(json, "\"shock_outcome\":null"));
    assert_null(td_shock_outcome_name(TD_SHOCK_UNDEFINED));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_near_miss_flight),    cmocka_unit_test(test_near_miss_ida),
        cmocka_unit_test(test_margin_up_to_output), cmocka_unit_test(test_drop),
        cmocka_unit_test(test_touch_and_rub),       cmocka_unit_test(test_pinned_is_rub),
        cmocka_unit_test(test_unsettled),           cmocka_unit_test(test_contact_speed),
        cmocka_unit_test(test_failed_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
