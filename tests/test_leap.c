/*
 * The projective leap (lib/sim/leap.h): the rates read over a burst and the leap of the slow state,
 * against the closed form of a free rotor spinning down under drag with no contact.
 */
#include "td_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/leap.h"
#include "sim/leap.h"
#include "sim/sim_internal.h"
#include "touchdown/case.h"
#include "touchdown/result.h"
#include "touchdown/run.h"
#include "touchdown/sim.h"

/* rub-damped.cfg's rotor centred by its AMBs with nothing to push it (no unbalance, schedule or
 * gravity), its speed free from W0 under a constant drag torque T and a viscous drag c on a spin
 * inertia J, the energy account kept: J dOmega/dt = -T - c Omega, so
 *   Omega(t) = (W0 + T/c) exp(-c t / J) - T/c   (c > 0),   Omega(t) = W0 - T t / J   (c = 0),
 * and the constant drag's loss is T times the integral of Omega. */
#define SPIN_J 0.01
#define SPIN_T 0.7
#define SPIN_W0 100.0

static td_case *spin_case(double viscous)
{
    static char spin[200];
    static const char *ov[] = {"unbalances = ()", "schedule = ()", "speed = 100.0", spin,
                               "energy = true",   "end_time = 3.0"};
    snprintf(spin, sizeof spin, "spin = { free = true; inertia = %.17g; drag_torque = %.17g; drag_viscous = %.17g; }",
             SPIN_J, SPIN_T, viscous);
    return td_test_load_case("cases/rub-damped.cfg", ov, 6);
}

static double omega_at(double c, double t)
{
    return c > 0.0 ? (SPIN_W0 + SPIN_T / c) * exp(-c * t / SPIN_J) - SPIN_T / c : SPIN_W0 - SPIN_T * t / SPIN_J;
}

/* integral of Omega from 0 to t */
static double angle_at(double c, double t)
{
    return c > 0.0 ? (SPIN_W0 + SPIN_T / c) * SPIN_J / c * -expm1(-c * t / SPIN_J) - SPIN_T / c * t
                   : SPIN_W0 * t - 0.5 * SPIN_T * t * t / SPIN_J;
}

/* The rates over a burst are the closed form's mean rates: the speed's and the constant drag's loss. */
/* A burst of `s` from t1 to t2 (t1 at or after its time now): the slow state at its ends into *a and
 * *b, their mean rates into *r. */
static void burst(td_sim *s, double t1, double t2, td_sim_leap_state *a, td_sim_leap_state *b, td_sim_leap_state *r)
{
    td_error err;
    td_test_step_to(s, t1);
    assert_int_equal(td_sim_leap_read(s, a, &err), TD_OK);
    td_test_step_to(s, t2);
    assert_int_equal(td_sim_leap_read(s, b, &err), TD_OK);
    assert_int_equal(td_sim_leap_rates(a, b, r, &err), TD_OK);
}

static void test_rates_closed_form(void **state)
{
    const double c = 2.0e-3, t1 = 0.2, t2 = 0.5;
    td_case *cs = spin_case(c);
    td_sim *s = td_test_new_sim(td_case_model(cs), cs);
    td_sim_leap_state a, b, r;
    td_error err;
    (void)state;
    burst(s, t1, t2, &a, &b, &r);
    print_message("rate %.12g rad/s^2 (closed form %.12g), drag loss %.12g W (%.12g)\n", r.speed,
                  (omega_at(c, t2) - omega_at(c, t1)) / (t2 - t1), r.energy.drag_loss,
                  SPIN_T * (angle_at(c, t2) - angle_at(c, t1)) / (t2 - t1));
    assert_close(r.t, t2 - t1, 1e-14, 0.0);
    assert_close(r.speed, (omega_at(c, t2) - omega_at(c, t1)) / (t2 - t1), 1e-6, 0.0);
    assert_close(r.mean_speed, 0.5 * (omega_at(c, t1) + omega_at(c, t2)), 1e-8, 0.0);
    assert_close(r.energy.drag_loss, SPIN_T * (angle_at(c, t2) - angle_at(c, t1)) / (t2 - t1), 1e-6, 0.0);
    assert_true(r.contacts[0] == 0.0 && r.totals[0].contact_time == 0.0);
    /* the ends must be of one run, in order */
    assert_int_equal(td_sim_leap_rates(&b, &a, &r, &err), TD_ERR_INVALID);
    td_sim_free(&s);
    td_case_free(&cs);
}

/* Under a constant torque the speed falls linearly: a leap of L after a burst lands on the closed
 * form, the integration after it goes on from there (the speed at simulation time t is that of
 * t + L), and the energy account, the drag's loss included, still closes. */
static void test_leap_closed_form(void **state)
{
    const double t1 = 0.1, t2 = 0.3, L = 0.6, t3 = 0.5;
    td_case *cs = spin_case(0.0);
    td_sim *s = td_test_new_sim(td_case_model(cs), cs);
    td_sim_leap_state a, b, r;
    td_energy e;
    td_error err;
    (void)state;
    burst(s, t1, t2, &a, &b, &r);
    assert_close(r.speed, -SPIN_T / SPIN_J, 1e-9, 0.0);
    assert_int_equal(td_sim_leap(s, L, &r, &err), TD_OK);
    assert_close(td_sim_time(s), t2, 0.0, 0.0); /* the clock is the caller's */
    assert_close(td_sim_speed(s), omega_at(0.0, t2 + L), 1e-10, 0.0);
    td_test_step_to(s, t3);
    assert_close(td_sim_speed(s), omega_at(0.0, t3 + L), 1e-10, 0.0);
    assert_int_equal(td_sim_energy(s, &e), TD_OK);
    print_message("after the leap: %.12g rad/s (closed form %.12g), drag loss %.12g J (%.12g), residual %.3g J\n",
                  td_sim_speed(s), omega_at(0.0, t3 + L), e.drag_loss, SPIN_T * angle_at(0.0, t3 + L), e.residual);
    assert_close(e.drag_loss, SPIN_T * angle_at(0.0, t3 + L), 1e-9, 0.0);
    assert_close(e.kinetic - e.initial, 0.5 * SPIN_J * (pow(omega_at(0.0, t3 + L), 2) - SPIN_W0 * SPIN_W0), 1e-8, 0.0);
    assert_true(fabs(e.residual) < 1e-9 * e.initial);
    td_sim_free(&s);
    td_case_free(&cs);
}

/* The energy account closes across a leap to rounding when the lateral motion's energy changes over
 * the burst: rub-damped.cfg's rotor with its unbalance, spinning down freely under a constant torque
 * (its unbalance response grows from rest and follows the falling speed), a burst over that
 * change. The leap books every term at the burst's powers (scaled by the speed) and moves the spin
 * so that the kinetic energy pays for exactly their sum: the residual after the leap is the one
 * before it (the burst's dOmega/dt would have put the lateral energy's change times L / B into it).
 * The speed so moved differs from the burst's own dOmega/dt by that share. (The closed form of a
 * spin-down with no lateral motion: test_leap_closed_form.) */
static void test_leap_energy_closes(void **state)
{
    static char spin[200];
    static const char *ov[] = {"speed = 100.0", spin, "energy = true", "end_time = 3.0"};
    const double t1 = 0.05, t2 = 0.25, L = 0.6, t3 = 0.3;
    td_case *cs;
    td_sim *s;
    td_sim_leap_state a, b, r;
    td_energy e0, e1, e2;
    td_error err;
    double w0, w1, dlat;
    (void)state;
    snprintf(spin, sizeof spin, "spin = { free = true; inertia = %.17g; drag_torque = %.17g; drag_viscous = 0.0; }",
             SPIN_J, SPIN_T);
    cs = td_test_load_case("cases/rub-damped.cfg", ov, 4);
    s = td_test_new_sim(td_case_model(cs), cs);
    burst(s, t1, t2, &a, &b, &r);
    /* a restart's own projection (the constrained contact's drift, taken back at every restart, at the
     * integrator's tolerance) first, so that what the residual measures is the leap's */
    assert_int_equal(td_sim_restart_between_steps(s), TD_OK);
    assert_int_equal(td_sim_energy(s, &e0), TD_OK);
    w0 = td_sim_speed(s);
    assert_int_equal(td_sim_leap(s, L, &r, &err), TD_OK);
    assert_int_equal(td_sim_energy(s, &e1), TD_OK);
    w1 = td_sim_speed(s);
    dlat = (b.energy.kinetic + b.energy.elastic - 0.5 * SPIN_J * b.speed * b.speed) -
           (a.energy.kinetic + a.energy.elastic - 0.5 * SPIN_J * a.speed * a.speed);
    print_message("lateral energy over the burst %.6g J; residual %.6g J before the leap, %.6g J after (of %.6g J); "
                  "speed change %.12g rad/s, the burst's rate gives %.12g\n",
                  dlat, e0.residual, e1.residual, e0.initial, w1 - w0, L * r.speed);
    assert_true(fabs(e1.residual - e0.residual) < 1e-12 * e0.initial);
    /* the speed: the burst's dOmega/dt carries the lateral motion's energy change dE over the burst,
     * the energy's speed does not; they differ by at most its share L / B dE over J Omega, Omega the
     * least speed on the way (the races that move with the rotor only add inertia) */
    assert_true(fabs((w1 - w0) - L * r.speed) <= L / (t2 - t1) * fabs(dlat) / (SPIN_J * w1));
    assert_true(fabs((w1 - w0) - L * r.speed) > 0.1 * L / (t2 - t1) * fabs(dlat) / (SPIN_J * w0));
    td_test_step_to(s, t3); /* and the integration after it keeps closing */
    assert_int_equal(td_sim_energy(s, &e2), TD_OK);
    print_message("residual %.6g J at %g s\n", e2.residual, t3);
    assert_true(fabs(e2.residual - e0.residual) < 1e-4 * e0.initial); /* the integrator's own, as before */
    td_sim_free(&s);
    td_case_free(&cs);
}

/* Leaps refused: no length, one that would stop the rotor, one on a speed that is not free. */
static void test_leap_refused(void **state)
{
    td_case *cs = spin_case(0.0), *fixed = td_test_load_case("cases/rub-damped.cfg", NULL, 0);
    td_sim *s = td_test_new_sim(td_case_model(cs), cs), *f = td_test_new_sim(td_case_model(fixed), fixed);
    td_sim_leap_state a, b, r, fa, fb, fr;
    td_error err;
    (void)state;
    assert_int_equal(td_sim_leap_read(s, &a, &err), TD_OK);
    td_test_step_to(s, 0.1);
    assert_int_equal(td_sim_leap_read(s, &b, &err), TD_OK);
    assert_int_equal(td_sim_leap_rates(&a, &b, &r, &err), TD_OK);
    assert_int_equal(td_sim_leap(s, 0.0, &r, &err), TD_ERR_INVALID);
    assert_int_equal(td_sim_leap(s, 2.0, &r, &err), TD_ERR_INVALID); /* 100 - 70 x 2 < 0 */
    print_message("%s\n", err.message);
    assert_non_null(strstr(err.message, "would stop the rotor"));
    assert_close(td_sim_speed(s), omega_at(0.0, 0.1), 1e-9, 0.0); /* nothing changed */
    assert_int_equal(td_sim_leap_read(f, &fa, &err), TD_OK);
    td_test_step_to(f, 0.01);
    assert_int_equal(td_sim_leap_read(f, &fb, &err), TD_OK);
    assert_int_equal(td_sim_leap_rates(&fa, &fb, &fr, &err), TD_OK);
    assert_int_equal(td_sim_leap(f, 0.1, &fr, &err), TD_ERR_INVALID);
    td_sim_free(&s);
    td_sim_free(&f);
    td_case_free(&cs);
    td_case_free(&fixed);
}

/* The progress calls of a run (progress_interval 0: after every grid sample), their times kept. */
typedef struct progress_log {
    long n;
    double t[4096];
} progress_log;

static int log_progress(double t, double fraction, long contacts, void *user)
{
    progress_log *p = user;
    (void)fraction;
    (void)contacts;
    if (p->n < (long)(sizeof p->t / sizeof p->t[0]))
        p->t[p->n] = t;
    p->n++;
    return 0;
}

/* The CSV file's `#` lines list the leaps as the HDF5 file does (at, len: its leap_time, leap_length):
 * "# summary_leaps = N", "# leap_time = t1 t2 ...", "# leap_length = L1 L2 ...". */
static void csv_leaps(const char *csv, const td_result_array *at, const td_result_array *len, long leaps)
{
    char line[8192];
    int seen = 0;
    FILE *f = fopen(csv, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        const td_result_array *want = strncmp(line, "# leap_time = ", 14) == 0     ? at
                                      : strncmp(line, "# leap_length = ", 16) == 0 ? len
                                                                                   : NULL;
        char *p = strchr(line, '=') + 1, *end;
        size_t k;
        if (strncmp(line, "# summary_leaps = ", 18) == 0) {
            assert_int_equal(strtol(line + 18, NULL, 10), leaps);
            seen++;
        }
        for (k = 0; want && k < want->n; k++, p = end) {
            double v = strtod(p, &end);
            assert_true(end != p);
            assert_close(v, want->v[k], 0.0, 0.0); /* the same bits */
        }
        seen += want != NULL;
    }
    fclose(f);
    assert_int_equal(seen, 3);
}

/* Through td_run and the case key: the spin-down with constant torque leapt (bursts of 0.1 s, leaps
 * of 0.8 s after 0.05 s of healing, from 0.1 s; the second would overshoot rest, and is shortened to
 * end at twice the at-rest speed) ends at rest at the first grid sample after the
 * closed form's t* = 0.99 J W0 / T, with the closed form's speed there; the file's series have no
 * row inside a leap (every gap between rows is a sample interval, or a leap), and the summary says
 * how much was leapt; the files list the leaps (each one's start and length, a gap between rows in
 * order; HDF5 attributes and the CSV's `#` lines alike) and that the run ended at rest. The progress
 * calls report the run's clock: each the time of a row of the file, in order, after a leap the row it
 * lands on (the simulation's clock is behind by the time leapt). */
static void test_run_leap_closed_form(void **state)
{
    static const char *ov[] = {"unbalances = ()",
                               "schedule = ()",
                               "speed = 100.0",
                               "spin = { free = true; inertia = 0.01; drag_torque = 0.7; drag_viscous = 0.0; }",
                               "end_at_rest = true",
                               "end_time = 2.0",
                               "output.sample_rate = 1000.0",
                               "leap = { burst = 0.1; factor = 8.0; heal = 0.05; start = 0.1; }"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ov, 8);
    td_output_options out = *td_case_output_options(c);
    const char *path = "test_leap_run.h5", *csv = "test_leap_run.csv";
    const double t_star = 0.99 * SPIN_J * SPIN_W0 / SPIN_T, dt = 1.0e-3;
    static progress_log calls;
    td_run_hooks hooks;
    td_run_summary sum;
    td_sim *s = NULL;
    td_result *r = NULL;
    td_result_array time, speed, at, len, total;
    td_error err;
    double gaps = 0.0;
    size_t i, j = 0, k;
    (void)state;
    memset(&hooks, 0, sizeof hooks);
    hooks.progress = log_progress;
    hooks.user = &calls;
    calls.n = 0;
    assert_close(out.leap_burst, 0.1, 0.0, 0.0);
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", path);
    snprintf(out.csv_path, sizeof out.csv_path, "%s", csv);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, td_case_end_time(c), &out, &hooks, NULL, &sum, &err), TD_OK);
    print_message("t* = %.12f s, ended at %.12f s (%ld leaps, %.6g s leapt), speed %.12g rad/s\n", t_star,
                  sum.t_reached, sum.leaps, sum.leapt_time, sum.final_speed);
    assert_int_equal(sum.ended_at_rest, 1);
    assert_true(sum.leaps >= 2 && sum.leapt_time > 0.5);
    assert_true(sum.t_reached >= t_star && sum.t_reached <= t_star + dt * (1.0 + 1e-9));
    assert_close(sum.final_speed, SPIN_W0 - SPIN_T * sum.t_reached / SPIN_J, 0.0, 1e-6);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    assert_int_equal(td_result_read(r, TD_OUT_TIME, NULL, &time, &err), TD_OK);
    assert_int_equal(td_result_read(r, TD_OUT_SPEED, NULL, &speed, &err), TD_OK);
    /* the files list the leaps: each gap between rows that is not a sample interval, in order */
    assert_int_equal(td_result_read(r, TD_OUT_LEAP_TIME, NULL, &at, &err), TD_OK);
    assert_int_equal(td_result_read(r, TD_OUT_LEAP_LENGTH, NULL, &len, &err), TD_OK);
    assert_int_equal(at.n, (size_t)sum.leaps);
    assert_int_equal(len.n, (size_t)sum.leaps);
    for (i = 1; i < time.n; i++) {
        double gap = time.v[i] - time.v[i - 1];
        assert_close(speed.v[i], SPIN_W0 - SPIN_T * time.v[i] / SPIN_J, 0.0, 1e-6); /* before and after leaps */
        if (gap > 1.5 * dt) {
            gaps += gap; /* a leap, from the row before it to the row it lands on: no rows inside */
            assert_true(j < at.n);
            assert_close(at.v[j], time.v[i - 1], 0.0, 0.0);
            assert_close(len.v[j], gap, 1e-12, 0.0);
            j++;
        } else {
            assert_close(gap, dt, 1e-6, 0.0);
        }
    }
    assert_int_equal(j, at.n);
    assert_close(gaps, sum.leapt_time, 1e-9, 0.0);
    assert_int_equal(td_result_read(r, TD_OUT_SUM_LEAPS, NULL, &total, &err), TD_OK);
    assert_close(total.v[0], (double)sum.leaps, 0.0, 0.0);
    td_result_array_free(&total);
    assert_int_equal(td_result_read(r, TD_OUT_SUM_LEAPT_TIME, NULL, &total, &err), TD_OK);
    assert_close(total.v[0], sum.leapt_time, 0.0, 0.0);
    td_result_array_free(&total);
    /* the run asked to end at rest and did: the files say so, as the JSON's ended_at_rest */
    assert_int_equal(td_result_read(r, TD_OUT_SUM_ENDED_AT_REST, NULL, &total, &err), TD_OK);
    assert_close(total.v[0], 1.0, 0.0, 0.0);
    td_result_array_free(&total);
    csv_leaps(csv, &at, &len, sum.leaps);
    /* one progress call after each grid sample the loop takes (no events: every row a grid sample),
     * but for a leap's start: the leap is made there and the call reports the row it lands on */
    print_message("%ld progress calls, %zu rows, %ld leaps\n", calls.n, time.n, sum.leaps);
    assert_int_equal(calls.n, (long)time.n - sum.leaps);
    for (i = 0, j = 0, k = 0; i < time.n && k < sizeof calls.t / sizeof calls.t[0]; i++) {
        if (j < at.n && time.v[i] == at.v[j]) {
            j++;
            continue;
        }
        assert_close(calls.t[k], time.v[i], 0.0, 0.0);
        k++;
    }
    assert_int_equal(k, (size_t)calls.n);
    /* the once-per-revolution section is the run's: it starts at half of end_time = 2 s, 1 s of run
     * time, which the simulation's own clock (behind by the time leapt) never reaches, and its
     * crossings are where the closed form's angle, integrated and leapt alike, passes 2 pi k */
    print_message("section from %.6g s: %ld crossings, the last at %.12g s\n", sum.section_start, sum.section_count,
                  sum.section_kept > 0 ? sum.section_time[sum.section_kept - 1] : NAN);
    assert_true(sum.t_reached - sum.leapt_time < sum.section_start);
    assert_true(sum.section_count > 0 && sum.section_kept > 0);
    for (i = 0; i < (size_t)sum.section_kept; i++) {
        double phi = angle_at(0.0, sum.section_time[i]) / (2.0 * TD_PI);
        assert_true(sum.section_time[i] >= sum.section_start && sum.section_time[i] <= sum.t_reached);
        assert_close(phi, round(phi), 0.0, 1e-6);
    }
    td_result_array_free(&time);
    td_result_array_free(&speed);
    td_result_array_free(&at);
    td_result_array_free(&len);
    td_result_free(&r);
    td_sim_free(&s);
    td_case_free(&c);
    remove(path);
    remove(csv);
    remove("test_leap_run.events.csv");
}

/* A leap's length is the one the leap will make: with the energy account on, the speed moves by the
 * energy balance's change (td_sim_leap_speed_change), not by the burst's own dOmega/dt, which a
 * fluctuation of the lateral motion's energy can bias. Here the burst's start is read with the
 * speed of its end (a dOmega/dt of 0), while its net power is the drag's: a leap of factor 20
 * bursts at the energy balance's -T / J would turn the rotor backwards. The run's side shortens it
 * to the longest whole number of sample intervals that keeps twice the at-rest speed (2 rad/s of
 * W0 = 100 rad/s), and the leap is made, at the closed form's rate: the drag's power T Omega_mean over
 * the burst, booked at the speed's scale against the mean speed the burst's ends give (here the end's),
 * pays J Omega dOmega, so dOmega/dt = -T / J Omega_mean / Omega_end. */
static void test_run_leap_shortened_by_energy(void **state)
{
    td_case *cs = spin_case(0.0);
    td_sim *s = td_test_new_sim(td_case_model(cs), cs);
    td_output_options o;
    td_run_leap l;
    td_run_leap_counts now = {0, 0, 0.0};
    td_sim_leap_state a, b, r;
    td_error err;
    const double t1 = 0.05, t2 = 0.15, sample_rate = 1000.0;
    double L, w0, w1, g;
    (void)state;
    memset(&o, 0, sizeof o);
    o.leap_burst = t2 - t1;
    o.leap_factor = 20.0;
    o.leap_heal = 0.05;
    o.leap_start = 0.0;
    assert_int_equal(td_run_leap_init(&l, &o, SPIN_W0), 1);
    burst(s, t1, t2, &a, &b, &r);
    l.phase = 2; /* in the burst begun at t1, which ends now */
    l.until = t2;
    l.from = a;
    l.from.speed = b.speed; /* its dOmega/dt reads 0 */
    w0 = td_sim_speed(s);
    g = SPIN_T / SPIN_J * 0.5 * (a.speed + b.speed) / b.speed; /* the drag's power over the mean speed read */
    L = td_run_leap_due(&l, s, t2, sample_rate, 3.0, &now, &r, &err);
    print_message("leap of %.6g s from %.12g rad/s (the burst's dOmega/dt %g rad/s^2)\n", L, w0, r.speed);
    assert_true(L > 0.0 && L < 20.0 * o.leap_burst);
    assert_int_equal(td_run_leap_make(&l, s, t2, L, &r, &now, &err), TD_OK);
    w1 = td_sim_speed(s);
    print_message("after it: %.12g rad/s (closed form %.12g)\n", w1, w0 - g * L);
    assert_close(w1, w0 - g * L, 1e-6, 0.0);
    assert_true(w1 >= 2.0 && w1 < 2.0 + g / sample_rate + 1e-6); /* the longest, to a sample */
    td_sim_free(&s);
    td_case_free(&cs);
}

/* Bad leap groups: one line naming the file, the override and the key, and why. */
static void test_leap_bad_input(void **state)
{
    static const struct {
        const char *base, *set, *want;
    } bad[] = {
        {"cases/drop-to-rest.cfg", "leap = { burst = 1.0; factor = 0.5; heal = 0.5; start = 3.0; }",
         "leap.factor: must be >= 1 (got 0.5)"},
        {"cases/drop-to-rest.cfg", "leap = { burst = 0.001; factor = 4.0; heal = 0.5; start = 3.0; }",
         "leap.burst: 0.001 s is shorter than the sample interval"},
        {"cases/drop-to-rest.cfg", "leap = { burst = 1.0; factor = 4.0; start = 3.0; }", "leap.heal: missing"},
        {"cases/drop-to-rest.cfg", "leap = { burst = 1.0; factor = 4.0; heal = -1.0; start = 3.0; }", "leap.heal"},
        {"cases/rub-damped.cfg", "leap = { burst = 0.1; factor = 4.0; heal = 0.0; start = 0.0; }",
         "leap: a leap needs the speed as a free state (spin.free = true)"},
        {"cases/drop-to-rest.cfg", "leap = { burst = 1.0; factor = 4.0; heal = 0.5; start = 0.01; }",
         "leap.start: 0.01 s is before the last prescribed change, at 0.05 s"},
        /* a start at or after end_time, which bounds a run that ends at rest too: no leap could happen */
        {"cases/drop-to-rest.cfg", "leap = { burst = 1.0; factor = 4.0; heal = 0.5; start = 400.0; }",
         "leap.start: 400 s is not before end_time = 400 s: the run ends before a leap may begin (leap.burst = 0 runs "
         "without leaps)"},
        {"cases/drop.cfg", "leap = { burst = 0.1; factor = 4.0; heal = 0.1; start = 2.5; }",
         "leap.start: 2.5 s is not before end_time ="},
        /* the housing's motion runs on the simulation's clock as the schedule does: a shock ending
         * at 50.011 s, the last point of a history, are prescribed changes; a ramp never ends */
        {"cases/drop-to-rest.cfg",
         "housing = { shocks = ({ shape = \"half-sine\"; amplitude = 490.0; duration = 0.011; start = 50.0; "
         "direction = [0.0, 1.0]; }); }",
         "leap.start: 3 s is before the last prescribed change, at 50.011 s"},
        {"cases/drop-to-rest.cfg", "housing = { history = { time = [0.0, 4.0]; x = [0.0, 1.0]; y = [0.0, 0.0]; }; }",
         "leap.start: 3 s is before the last prescribed change, at 4 s"},
        {"cases/drop-to-rest.cfg",
         "housing = { rotation = ({ shape = \"ramp\"; rate = 0.1; duration = 0.01; start = 0.0; "
         "axis = [1.0, 0.0]; }); }",
         "leap: housing.rotation[0] (a ramp) turns the housing for ever: the housing's motion never ends"},
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *ov[1];
        td_case *c = NULL;
        td_error err;
        ov[0] = bad[i].set;
        assert_int_equal(td_case_load(td_source_path(bad[i].base), ov, 1, &c, &err), TD_ERR_PARSE);
        print_message("%s\n", err.message);
        assert_non_null(strstr(err.message, bad[i].want));
        assert_non_null(strstr(err.message, bad[i].base));
        assert_null(strchr(err.message, '\n'));
    }
}

/* td_run checks the leap's options against the model as the case reader does (td_run_leap_check):
 * each bad one is TD_ERR_INVALID, named, before any file is written. */
static void test_run_leap_checked(void **state)
{
    td_case *cs = spin_case(0.0), *held = td_test_load_case("cases/rub-damped.cfg", NULL, 0);
    const td_output_options *good = td_case_output_options(cs);
    const char *path = "test_leap_checked.h5";
    const td_housing_pulse shock = {TD_PULSE_HALF_SINE, 10.0, 0.1, 1.0, {0.0, 1.0}}; /* ends at 1.1 s */
    td_model *nine = NULL, *shocked = NULL;
    td_retainer ret, other;
    td_error err;
    int i;
    (void)state;
    remove(path);
    assert_int_equal(td_model_clone(td_case_model(cs), &nine, &err), TD_OK);
    assert_int_equal(td_model_get_retainer(nine, 0, &ret), TD_OK);
    assert_int_equal(td_model_clone(td_case_model(cs), &shocked, &err), TD_OK);
    assert_int_equal(td_model_add_housing_shock(shocked, &shock, &err), TD_OK);
    assert_int_equal(td_model_get_retainer(nine, 1, &other), TD_OK);
    /* one more than a leap holds (TD_SIM_LEAP_RETAINERS), one a node: at the nodes without one */
    for (i = 0; i < td_model_node_count(nine) && td_model_retainer_count(nine) < 9; i++) {
        td_retainer at = ret;
        at.node = i;
        if (i != ret.node && i != other.node)
            assert_int_equal(td_model_add_retainer(nine, &at, &err), TD_OK);
    }
    assert_int_equal(td_model_retainer_count(nine), 9);
    for (i = 0; i < 9; i++) {
        td_output_options out = *good;
        const td_model *m = i == 5 ? td_case_model(held) : i == 6 ? shocked : i == 7 ? nine : td_case_model(cs);
        const char *want[] = {
            "leap: must be >= 1 (got 0.5)",
            "leap: must be >= 1 (got nan)",
            "leap: must be a finite time >= 0 s (got -1)",
            "s is shorter than the sample interval 1 / output.sample_rate",
            "leap: must be a finite time >= 0 s (got nan)",
            "leap: a leap needs the speed as a free state",
            "leap: 0.1 s is before the last prescribed change, at 1.1 s",
            "leap: a leap handles at most 8 retainers (the model has 9)",
            "leap: 1 s is not before end_time = 1 s: the run ends before a leap may begin (leap.burst = 0 "
            "runs without leaps)"};
        td_sim *s = NULL;
        td_run_summary sum;
        out.leap_burst = i == 3 ? 0.5 / out.sample_rate : 0.1, out.leap_factor = i == 0 ? 0.5 : i == 1 ? NAN : 4.0;
        out.leap_heal = i == 2 ? -1.0 : 0.05, out.leap_start = i == 4 ? NAN : i == 8 ? 1.0 : 0.1;
        snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", path);
        out.csv_path[0] = '\0';
        assert_int_equal(td_sim_create(m, td_case_sim_options(cs), &s, &err), TD_OK);
        assert_int_equal(td_run(s, 1.0, &out, NULL, NULL, &sum, &err), TD_ERR_INVALID);
        print_message("%s\n", err.message);
        assert_non_null(strstr(err.message, want[i]));
        assert_int_equal(sum.status, TD_ERR_INVALID);
        assert_null(fopen(path, "rb")); /* refused before any file */
        td_sim_free(&s);
    }
    td_model_free(&nine);
    td_model_free(&shocked);
    td_case_free(&cs);
    td_case_free(&held);
}

/* The number of the summary's warnings that contain `text`. */
static int warned(const td_run_summary *sum, const char *text)
{
    int i, n = 0;
    for (i = 0; i < sum->warning_count; i++)
        n += strstr(sum->warnings[i], text) != NULL;
    return n;
}

/* A leap group that makes no leap, on the free spin-down from 100 rad/s (70 rad/s^2: 30 rad/s at 1 s,
 * far from rest), healings of 0.05 s and bursts of 0.1 s: a leap is made at the end of a burst that
 * follows a healing from leap.start, with a healing and a burst left after it before end_time
 * (run/leap.c). From 0.9 s to end_time 1 s the first burst would end at 1.05 s; from 0.8 s it ends at
 * 0.95 s but a leap needs end_time past 0.8 + 2 (0.05 + 0.1) = 1.1 s; to 1.1005 s it has room for
 * half a sample interval, and is refused (a leap is whole sample intervals). Each run completes,
 * integrated throughout (no time leapt, the closed form's speed at the end), and says why in a
 * warning, in the summary and its JSON's `warnings` (the tool prints them on stderr); the same group
 * from 0.1 s leaps, without that warning. */
static void test_run_leap_none_warned(void **state)
{
    static const char *ov[] = {"unbalances = ()",
                               "schedule = ()",
                               "speed = 100.0",
                               "spin = { free = true; inertia = 0.01; drag_torque = 0.7; drag_viscous = 0.0; }",
                               "end_time = 1.0",
                               "output.sample_rate = 1000.0",
                               "leap = { burst = 0.1; factor = 8.0; heal = 0.05; start = 0.9; }"};
    static const struct {
        double start, end;
        const char *why; /* NULL: it leaps */
    } runs[] = {
        {0.9, 1.0, "the run ended at t = 1 s, before its first burst ended at 1.05 s"},
        {0.8, 1.0,
         "end_time 1 s leaves no room after the first burst (ending at 0.95 s) for the healing and the "
         "burst a leap must end before it: it would need to be past 1.1 s"},
        {0.8, 1.1005, "each leap due was refused"},
        {0.1, 1.0, NULL},
    };
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ov, 7);
    td_output_options out = *td_case_output_options(c);
    td_run_summary sum;
    td_sim *s = NULL;
    td_error err;
    char json[65536];
    size_t i;
    (void)state;
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    for (i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        int none = runs[i].why != NULL;
        out.leap_start = runs[i].start;
        assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
        assert_int_equal(td_run(s, runs[i].end, &out, NULL, NULL, &sum, &err), TD_OK);
        print_message("from %g s to %g s: %ld leaps, %d warnings\n", out.leap_start, runs[i].end, sum.leaps,
                      sum.warning_count);
        assert_int_equal(sum.leap, 1);
        assert_true(none ? sum.leaps == 0 && sum.leapt_time == 0.0 : sum.leaps > 0);
        if (none)
            assert_close(sum.final_speed, SPIN_W0 - SPIN_T * runs[i].end / SPIN_J, 0.0, 1e-6);
        assert_int_equal(warned(&sum, "the leap group made no leap"), none);
        if (none) {
            assert_int_equal(warned(&sum, runs[i].why), 1);
            assert_int_equal(warned(&sum, "(leap.start 0.8 s, leap.heal 0.05 s, leap.burst 0.1 s)") +
                                 warned(&sum, "(leap.start 0.9 s, leap.heal 0.05 s, leap.burst 0.1 s)"),
                             1);
        }
        assert_true(td_run_summary_json(json, sizeof json, &sum) < (int)sizeof json);
        assert_non_null(strstr(json, "\"warnings\":["));
        assert_true((strstr(strstr(json, "\"warnings\":["), "the leap group made no leap") != NULL) == none);
        td_sim_free(&s);
    }
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rates_closed_form),    cmocka_unit_test(test_leap_closed_form),
        cmocka_unit_test(test_leap_refused),         cmocka_unit_test(test_run_leap_closed_form),
        cmocka_unit_test(test_leap_bad_input),       cmocka_unit_test(test_leap_energy_closes),
        cmocka_unit_test(test_run_leap_checked),     cmocka_unit_test(test_run_leap_shortened_by_energy),
        cmocka_unit_test(test_run_leap_none_warned),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
