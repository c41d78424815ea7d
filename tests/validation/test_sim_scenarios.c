/*
 * Whole-run scenarios on the reference rig, each checked against a law that does not come from
 * the simulation: two contacts at once (constraints hold, friction obeys eq. 17), a rotor drop
 * that settles at the static equilibrium of weight, normal force and Coulomb friction, energy
 * conservation of a frictionless undamped contact, and penalty contact bracketing.
 */
#include "td_test.h"

#include "touchdown/case.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The case's sim at rtol, atol (0: the case's), BDF order <= 2, with or without free flight in
 * closed form. */
static td_sim *make_sim_with(const td_case *c, double rtol, double atol, int free_flight)
{
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_error err;
    o.solver.max_order = 2;
    o.solver.free_flight = free_flight;
    if (rtol > 0.0) {
        o.solver.rtol = rtol;
        o.solver.atol = atol;
    }
    if (td_sim_create(td_case_model(c), &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    return s;
}

/* The case's sim, free flight in closed form (the default). */
static td_sim *make_sim(const td_case *c, double rtol, double atol)
{
    return make_sim_with(c, rtol, atol, 1);
}

/* The same with IDA integrating the free flight too. */
static td_sim *make_sim_integrated(const td_case *c, double rtol, double atol)
{
    return make_sim_with(c, rtol, atol, 0);
}

/* Unbalances at both end discs, 1 rad apart, stepped up at 0.1 s: both retainers in contact at
 * once. At every sample with a contact the node is on the circle and the friction force is
 * -sgn(v_s) mu N (eq. 17); the constraints hold to 1e-9 m at every step. Every release carries
 * its interval's peak normal force: at least every force sampled here since the onset, at most
 * the run's peak, and the largest of them is the run's peak. */
/* At an event: the peak a release carries against the normal forces sampled since its onset
 * (sampled_peak, reset here at an onset; the largest release peak is kept in release_peak).
 * Returns 1 for a release. */
static int check_interval_peak(const td_sim *s, double *sampled_peak, double *release_peak)
{
    td_event ev;
    assert_int_equal(td_sim_last_event(s, &ev), TD_OK);
    if (ev.kind == TD_EVENT_CONTACT_ONSET)
        sampled_peak[ev.retainer] = 0.0;
    if (ev.kind != TD_EVENT_RELEASE) {
        assert_true(ev.peak_normal_force == 0.0);
        return 0;
    }
    assert_true(ev.peak_normal_force >= sampled_peak[ev.retainer]);
    assert_true(ev.peak_normal_force > 0.0);
    release_peak[ev.retainer] = fmax(release_peak[ev.retainer], ev.peak_normal_force);
    return 1;
}

/* 1 if a retainer is in contact now (its interval has not ended in a release). */
static int in_contact_at_end(const td_sim *s)
{
    td_retainer_state rs;
    int k;
    for (k = 0; k < 2; k++)
        if (td_sim_retainer_state(s, k, &rs) == TD_OK && rs.in_contact)
            return 1;
    return 0;
}

static void test_two_contacts(void **state)
{
    td_error err;
    const char *ov[2] = {
        "unbalances=({node=1;magnitude=0.02;},{node=11;magnitude=0.02;phase=1.0;})",
        "schedule=({time=0.1;unbalance=0;magnitude=0.1;},{time=0.1;unbalance=1;magnitude=0.1;phase=1.0;})"};
    td_case *c = td_test_load_case("cases/paper-a.cfg", ov, 2);
    td_sim *s = make_sim(c, 0.0, 0.0);
    td_retainer ret[2];
    td_sim_stats st;
    /* Under the sanitizers the run ends at 0.2 s: the step up at 0.1 s, both retainers in contact,
     * onsets, releases and the same checks at every sample (measured: 598 releases and 1155
     * samples with both in contact to 0.3 s, 319 and 391 to 0.2 s); the longer run is the plain
     * pass's. */
    double t = 0.0, t_end = td_test_sanitized() ? 0.2 : 0.3, dt = 1e-4, sampled_peak[2] = {0.0, 0.0},
           release_peak[2] = {0.0, 0.0};
    long both = 0, in_contact = 0, releases = 0;
    int k;
    (void)state;
    for (k = 0; k < 2; k++)
        td_model_get_retainer(td_case_model(c), k, &ret[k]);
    while (t < t_end) {
        double tr;
        td_status r = td_sim_step(s, td_test_next_output(t, dt, t_end), &tr, &err);
        int n_in = 0;
        if (r != TD_OK && r != TD_EVENT)
            fail_msg("%s", err.message);
        if (r == TD_EVENT)
            releases += check_interval_peak(s, sampled_peak, release_peak);
        for (k = 0; k < 2; k++) {
            td_retainer_state rs;
            td_sim_retainer_state(s, k, &rs);
            if (!rs.in_contact) {
                assert_true(rs.radius <= ret[k].clearance * (1 + 2e-6)); /* free: inside (disarmed band atol) */
                continue;
            }
            n_in++;
            in_contact++;
            sampled_peak[k] = fmax(sampled_peak[k], rs.normal_force);
            assert_close(rs.radius, ret[k].clearance, 0.0, 1e-8); /* interpolated states: tolerance level */
            assert_true(rs.normal_force >= 0.0);
            assert_close(rs.friction_force, -(rs.sliding_velocity > 0 ? 1.0 : -1.0) * ret[k].friction * rs.normal_force,
                         1e-12, 1e-9);
        }
        if (n_in == 2)
            both++;
        if (r == TD_OK)
            t = tr;
    }
    td_sim_stats_get(s, &st);
    print_message("%ld releases, largest interval peaks %.3f and %.3f N, run's peak %.3f N\n", releases,
                  release_peak[0], release_peak[1], st.peak_normal_force);
    assert_true(releases >= 20);
    for (k = 0; k < 2; k++)
        assert_true(release_peak[k] <= st.peak_normal_force);
    assert_true(fmax(release_peak[0], release_peak[1]) == st.peak_normal_force || in_contact_at_end(s));
    print_message("two contacts: %ld samples with both retainers in contact, %ld contact samples, %ld onsets, "
                  "worst drift %.3g m, peak %.1f N\n",
                  both, in_contact, st.contact_onsets, st.worst_drift, st.peak_normal_force);
    assert_true(both >= 50);
    assert_true(st.worst_drift < 1e-9);
    td_sim_free(&s);
    td_case_free(&c);
}

/* Rotor drop (both AMBs fail at 0.1 s, gravity on) with structural damping and no unbalance: the
 * rotor must come to rest on both retainers where weight, normal force and sliding friction
 * (v_s = R_s Omega > 0) balance: at the whirl angle -90 deg - atan(mu), with
 * N = m g / (2 sqrt(1 + mu^2)) on each retainer (the rig is symmetric about its middle). */
static void test_rotor_drop_settles(void **state)
{
    td_error err;
    const char *ov[2] = {"unbalances[0].magnitude=0.0", "shaft.rayleigh={alpha=20.0; beta=1e-5;}"};
    td_case *c = td_test_load_case("cases/rotor-drop.cfg", ov, 2);
    td_sim *s = make_sim(c, 0.0, 0.0);
    const td_model *m = td_case_model(c);
    double t = 0.0, t_end = 2.5, dt = 1e-3, gx, gy, g, mass = td_model_total_mass(m);
    td_retainer ret;
    int k;
    (void)state;
    td_model_gravity(m, &gx, &gy);
    g = hypot(gx, gy);
    td_model_get_retainer(m, 0, &ret);
    while (t < t_end) {
        double tr;
        td_status r = td_sim_step(s, td_test_next_output(t, dt, t_end), &tr, &err);
        if (r != TD_OK && r != TD_EVENT)
            fail_msg("%s", err.message);
        if (r == TD_OK)
            t = tr;
    }
    for (k = 0; k < 2; k++) {
        td_retainer_state rs;
        double angle = -0.5 * TD_PI - atan(ret.friction),
               n_exp = mass * g / (2.0 * sqrt(1.0 + ret.friction * ret.friction));
        td_sim_retainer_state(s, k, &rs);
        print_message("retainer %d at rest: angle %.4f deg (expected %.4f), N = %.3f N (expected %.3f)\n", k,
                      rs.whirl_angle * 180 / TD_PI, angle * 180 / TD_PI, rs.normal_force, n_exp);
        assert_true(rs.in_contact);
        assert_close(rs.whirl_angle, angle, 0.0, 1e-3);
        assert_close(rs.normal_force, n_exp, 2e-3, 0.0);
        assert_close(rs.friction_force, -ret.friction * rs.normal_force, 1e-12, 0.0);
        assert_true(fabs(rs.radial_velocity) < 1e-6);
    }
    td_sim_free(&s);
    td_case_free(&c);
}

/* Mechanical energy 1/2 v'Mv + 1/2 q'Kq - f_g'q of the state, from the system matrices. */
typedef struct energy_model {
    int n;
    double *M, *K, *fg;
} energy_model;

static energy_model energy_model_of(const td_model *model)
{
    energy_model e;
    td_system *sys = NULL;
    double gx, gy;
    int i, j;
    assert_int_equal(td_system_create(model, &sys, NULL), TD_OK);
    e.n = td_system_dof_count(sys);
    e.M = malloc(sizeof(double) * e.n * e.n);
    e.K = malloc(sizeof(double) * e.n * e.n);
    e.fg = calloc(e.n, sizeof(double));
    assert_int_equal(td_system_dense(sys, TD_MATRIX_MASS, e.M, NULL), TD_OK);
    assert_int_equal(td_system_dense(sys, TD_MATRIX_STIFFNESS, e.K, NULL), TD_OK);
    td_model_gravity(model, &gx, &gy);
    for (i = 0; i < e.n; i++) /* f_g = M a, a = g on every node's x, y */
        for (j = 0; j < e.n; j++)
            e.fg[i] += e.M[i + j * e.n] * (j % 4 == 0 ? gx : (j % 4 == 1 ? gy : 0.0));
    td_system_free(&sys);
    return e;
}

static double energy(const energy_model *e, td_sim *s)
{
    double *q = malloc(sizeof(double) * e->n), *v = malloc(sizeof(double) * e->n), E = 0.0;
    int i, j;
    td_sim_get_state(s, q, v);
    for (i = 0; i < e->n; i++) {
        for (j = 0; j < e->n; j++)
            E += 0.5 * v[i] * e->M[i + j * e->n] * v[j] + 0.5 * q[i] * e->K[i + j * e->n] * q[j];
        E -= e->fg[i] * q[i];
    }
    free(q), free(v);
    return E;
}

/* Largest relative change of the energy inside any contact phase (between two events, with a
 * retainer in contact), and the largest energy change across an onset (must not be a gain). */
static void energy_run(const td_case *c, double rtol, double atol, double *worst_phase, double *worst_gain,
                       long *onsets)
{
    td_error err;
    energy_model em = energy_model_of(td_case_model(c));
    td_sim *s = make_sim(c, rtol, atol);
    double t = 0.0, t_end = 0.03, dt = 2e-6, e_lo = HUGE_VAL, e_hi = -HUGE_VAL, e_before = 0.0;
    int in_contact = 0, k;
    td_sim_stats st;
    *worst_phase = 0.0;
    *worst_gain = -HUGE_VAL;
    while (t < t_end) {
        double tr, E;
        td_status r = td_sim_step(s, td_test_next_output(t, dt, t_end), &tr, &err);
        if (r != TD_OK && r != TD_EVENT)
            fail_msg("%s", err.message);
        E = energy(&em, s);
        if (r == TD_EVENT) {
            td_event ev;
            td_sim_last_event(s, &ev);
            if (in_contact && e_hi >= e_lo)
                *worst_phase = fmax(*worst_phase, (e_hi - e_lo) / fabs(E));
            if (ev.kind == TD_EVENT_CONTACT_ONSET && e_hi >= e_lo)
                *worst_gain = fmax(*worst_gain, (E - e_before) / fabs(E));
            e_lo = HUGE_VAL;
            e_hi = -HUGE_VAL;
            in_contact = 0;
        } else {
            e_lo = fmin(e_lo, E);
            e_hi = fmax(e_hi, E);
            e_before = E;
            t = tr;
            for (k = 0; k < 2; k++) {
                td_retainer_state rs;
                td_sim_retainer_state(s, k, &rs);
                in_contact = in_contact || rs.in_contact;
            }
        }
    }
    td_sim_stats_get(s, &st);
    *onsets = st.contact_onsets;
    td_sim_free(&s);
    free(em.M), free(em.K), free(em.fg);
}

/* A conservative rig (AMBs replaced by undamped springs, no unbalance, frictionless retainers,
 * gravity on, start at rest): it falls onto both retainers and chatters. Between onset and
 * release the constraint does no work (J v = 0, no friction), so the energy must be constant to
 * the solver tolerance, converging as the tolerance is tightened (BDF2's numerical damping of
 * the undamped high modes the impacts excite is what remains); every plastic impact loses energy.
 * Measured: 4.2e-5 at rtol 1e-8, 8.5e-7 at rtol 1e-10. */
static void test_energy_conservation(void **state)
{
    const char *ov[8] = {"ambs=()",
                         "bearings=({node=3;kxx=1.0e5;},{node=9;kxx=1.0e5;})",
                         "unbalances=()",
                         "schedule=()",
                         "gravity={enabled=true;}",
                         "retainers[0].friction=0.0",
                         "retainers[1].friction=0.0",
                         "start=\"rest\""};
    td_case *c = td_test_load_case("cases/paper-a.cfg", ov, 8);
    /* Under the sanitizers the loose run alone (the tight one's figures print as nan and 0): the same
     * drop, onsets, chatter and releases and the energy bookkeeping; the convergence with the
     * tolerance (the tight run, several times the loose one's cost) is the plain pass's. */
    const int runs = td_test_sanitized() ? 1 : 2;
    const double rtol[2] = {1e-8, 1e-10}, atol[2] = {1e-11, 1e-13};
    double phase[2] = {NAN, NAN}, gain[2] = {NAN, NAN};
    long on[2] = {0, 0};
    int k;
    (void)state;
    for (k = 0; k < runs; k++)
        energy_run(c, rtol[k], atol[k], &phase[k], &gain[k], &on[k]);
    print_message("energy drift inside contact phases: %.3g (rtol 1e-8), %.3g (rtol 1e-10); onsets %ld, %ld; "
                  "largest relative change across an onset %.3g, %.3g\n",
                  phase[0], phase[1], on[0], on[1], gain[0], gain[1]);
    for (k = 0; k < runs; k++) {
        assert_true(on[k] > 2);
        assert_true(gain[k] < 0.0); /* every impact loses energy */
    }
    if (runs == 2) {
        assert_true(phase[1] < 2e-6);
        assert_true(phase[1] < 0.1 * phase[0]);
    }
    td_case_free(&c);
}

/*
 * Rotor drop with partly elastic retainers (restitution e = 0.5, structural damping, no
 * unbalance): like a ball dropped on the floor the rotor must bounce a finite number of times and
 * come to rest in persistent contact (a pressed rotor used to bounce for ever at a rebound speed
 * ~ sqrt(atol), 4e5 onsets in 1 s, never in contact).
 * Bound on the onsets of one bouncing sequence (the onsets at a retainer between two releases):
 * the speeds are v0 e^j, and the simulation ends the sequence with a plastic impact once the
 * rebound e v would rise less than 4 atol against the pressing acceleration a_n, i.e. below
 * v_min = 2 sqrt(2 a_n atol). The weight alone gives a_n >= g, so a sequence has at most
 * 1 + ceil(log(v_min / v0) / log(e)) onsets with v_min = 2 sqrt(2 g atol) (9 for the 0.07 m/s
 * drop here; 4-6 are measured, the shaft's flexure presses harder than g).
 * Energy: AMBs off, the forces are gravity and the shaft's elastic forces (in E), damping and
 * gyroscopic forces (no gain) and friction (only in contact). Across an impact reached in free
 * flight (both retainers free at the sample before) E must not rise: the impact map only removes
 * kinetic energy ((1 - e^2) of the normal part), and the node is caught at the gap, not sunk into
 * the retainer and pushed back against its preload.
 */
static void test_rotor_drop_bouncing_settles(void **state)
{
    td_error err;
    const char *ov[4] = {"unbalances[0].magnitude=0.0", "shaft.rayleigh={alpha=20.0; beta=1e-5;}",
                         "retainers[0].restitution=0.5", "retainers[1].restitution=0.5"};
    td_case *c = td_test_load_case("cases/rotor-drop.cfg", ov, 4);
    td_sim *s = make_sim(c, 0.0, 0.0);
    const td_model *m = td_case_model(c);
    energy_model em = energy_model_of(m);
    /* Under the sanitizers the run ends at 0.4 s: every bouncing sequence (AMBs off at 0.1 s)
     * and its energy check are past by 0.3 s, and the rotor is checked in contact over 0.1 s after
     * that; that it stays so to 0.6 s is the plain pass's. */
    const double e = 0.5, t_end = td_test_sanitized() ? 0.4 : 0.6, t_settled = 0.3, dt = 1e-5;
    double t = 0.0, gx, gy, atol = td_case_sim_options(c)->solver.atol, v0[2] = {0.0, 0.0}, E_prev = 0.0,
           worst_gain = -HUGE_VAL, vmin;
    long seq[2] = {0, 0}, b[2] = {0, 0}, longest = 0, bound = 0, checked = 0, onsets = 0, late = 0;
    int k, free_before = 0;
    (void)state;
    td_model_gravity(m, &gx, &gy);
    vmin = 2.0 * sqrt(2.0 * hypot(gx, gy) * atol);
    while (t < t_end) {
        double tr, E;
        td_status r = td_sim_step(s, td_test_next_output(t, dt, t_end), &tr, &err);
        if (r != TD_OK && r != TD_EVENT)
            fail_msg("%s", err.message);
        E = energy(&em, s);
        if (r == TD_EVENT) {
            td_event ev;
            td_sim_last_event(s, &ev);
            if (ev.retainer < 0)
                continue;
            k = ev.retainer;
            if (ev.kind == TD_EVENT_RELEASE)
                seq[k] = 0;
            if (ev.kind != TD_EVENT_CONTACT_ONSET)
                continue;
            onsets++;
            if (ev.time > t_settled)
                late++;
            if (seq[k]++ == 0) { /* a new sequence: its bound from its first impact speed */
                v0[k] = ev.radial_velocity_before;
                b[k] = 1 + (long)ceil(log(vmin / v0[k]) / log(e));
                bound = b[k] > bound ? b[k] : bound;
            }
            if (seq[k] > b[k])
                fail_msg("retainer %d: %ld onsets in one sequence (bound %ld, first impact %.3g m/s)", k, seq[k], b[k],
                         v0[k]);
            longest = seq[k] > longest ? seq[k] : longest;
            if (free_before) {
                worst_gain = fmax(worst_gain, E - E_prev);
                checked++;
            }
        } else {
            t = tr;
            E_prev = E;
            free_before = 1;
            for (k = 0; k < 2; k++) {
                td_retainer_state rs;
                td_sim_retainer_state(s, k, &rs);
                free_before = free_before && !rs.in_contact;
                if (t > t_settled && !rs.in_contact)
                    fail_msg("retainer %d not in contact at t = %.5f s (after %ld onsets)", k, t, onsets);
            }
        }
    }
    print_message("bouncing drop: %ld onsets, longest sequence %ld (bound %ld), %ld after %.2f s; energy change "
                  "across %ld impacts from free flight: at most %.3g J\n",
                  onsets, longest, bound, late, t_settled, checked, worst_gain);
    assert_true(longest >= 3); /* it did bounce: e = 0.5 was applied */
    assert_int_equal(late, 0);
    assert_true(checked >= onsets / 2);
    assert_true(worst_gain <= 0.0);
    td_sim_free(&s);
    free(em.M), free(em.K), free(em.fg);
    td_case_free(&c);
}

/* The time of the first contact onset of s before t_end, or -1. */
static double first_onset(td_sim *s, double t_end)
{
    td_error err;
    for (;;) {
        td_event ev;
        if (td_sim_step(s, t_end, NULL, &err) != TD_EVENT)
            return -1.0;
        td_sim_last_event(s, &ev);
        if (ev.kind == TD_EVENT_CONTACT_ONSET)
            return ev.time;
    }
}

/* Penalty contact (case C, Kc = 1.25e12 N/m): the free flight is the constraint model's, so the
 * first penalty entry is the first constraint onset (both carried by the closed-form flight up to
 * their first contact, docs/theory.md: they agree to the flight's root tolerance, and with the
 * constraint model integrated by IDA to its accuracy); enter and exit alternate per retainer; the
 * reported normal force is Kc (r - c) inside and never negative. */
static void test_penalty_contact(void **state)
{
    td_error err;
    td_case *cc = td_test_load_case("cases/paper-c.cfg", NULL, 0),
            *ca = td_test_load_case("cases/paper-a.cfg", NULL, 0);
    td_sim *sp = make_sim(cc, 1e-8, 1e-12), *sa = make_sim(ca, 1e-8, 1e-12), *si = make_sim_integrated(ca, 1e-8, 1e-12);
    td_contact_options co = td_case_sim_options(cc)->contact;
    double t = 0.0, t_end = 0.115, dt = 1e-5, t_first_a = -1.0, t_first_i = -1.0, max_pen = 0.0;
    int inside[2] = {0, 0}, k;
    td_retainer ret;
    td_sim_stats st;
    (void)state;
    td_model_get_retainer(td_case_model(cc), 0, &ret);
    while (t < t_end) {
        double tr;
        td_status r = td_sim_step(sp, td_test_next_output(t, dt, t_end), &tr, &err);
        if (r == TD_EVENT) {
            td_event ev;
            td_sim_last_event(sp, &ev);
            if (ev.kind == TD_EVENT_PENALTY_ENTER) {
                assert_int_equal(inside[ev.retainer], 0);
                inside[ev.retainer] = 1;
            } else if (ev.kind == TD_EVENT_PENALTY_EXIT) {
                assert_int_equal(inside[ev.retainer], 1);
                inside[ev.retainer] = 0;
            }
            continue;
        }
        if (r != TD_OK)
            fail_msg("%s", err.message);
        t = tr;
        for (k = 0; k < 2; k++) {
            td_retainer_state rs;
            td_sim_retainer_state(sp, k, &rs);
            assert_true(rs.normal_force >= 0.0);
            if (rs.in_contact) {
                assert_close(rs.normal_force, fmax(0.0, co.stiffness * (rs.radius - ret.clearance)), 1e-9, 1e-6);
                max_pen = fmax(max_pen, rs.radius - ret.clearance);
            }
        }
    }
    t_first_a = first_onset(sa, t_end);
    t_first_i = first_onset(si, t_end);
    td_sim_stats_get(sp, &st);
    print_message("penalty: first entry %.15f s, constraint onset %.15f s (flight), %.15f s (IDA); %ld entries, "
                  "peak %.0f N, largest sampled penetration %.3g m\n",
                  st.first_contact_time, t_first_a, t_first_i, st.contact_onsets, st.peak_normal_force, max_pen);
    assert_true(st.contact_onsets > 0);
    assert_close(st.first_contact_time, t_first_a, 0.0, 1e-12);
    assert_close(st.first_contact_time, t_first_i, 0.0, 1e-8);
    assert_true(st.peak_normal_force > 0.0);
    td_sim_free(&sp), td_sim_free(&sa), td_sim_free(&si);
    td_case_free(&cc), td_case_free(&ca);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_contacts),        cmocka_unit_test(test_rotor_drop_settles),
        cmocka_unit_test(test_energy_conservation), cmocka_unit_test(test_rotor_drop_bouncing_settles),
        cmocka_unit_test(test_penalty_contact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
