/*
 * The touchdown bearing's duty and the sensors' peaks (lib/sim/totals.c), taken at the
 * integrator's accepted points, against the states the run shows at its outputs and events: a peak
 * at an output takes no value of the step beyond it (held until the run reaches it: a race that
 * spins up would show a speed above its speed at the output), also when a change restarts the
 * integrator at outputs (the held point dropped), and at the end each peak is the largest
 * value shown, to what lies between the samples. On the drop (cases/drop.cfg) through its fall to
 * 0.12 s.
 */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <string.h>

/* The largest values the run showed so far, at its outputs and events. */
typedef struct shown {
    double sliding[2], power[2], pv[2], race[2], sensor[2], normal[2];
} shown;

/* The states at the time reached: retainers in contact, sensors while their AMB works. */
static void show(const td_sim *s, double t, shown *m)
{
    const td_system *sys = td_sim_system(s);
    double q[2048];
    int k;
    assert_true(td_sim_dof_count(s) <= 2048);
    for (k = 0; k < 2; k++) {
        td_retainer_state rs;
        td_amb a;
        assert_int_equal(td_sim_retainer_state(s, k, &rs), TD_OK);
        m->race[k] = fmax(m->race[k], fabs(rs.race_speed));
        if (rs.in_contact) {
            m->sliding[k] = fmax(m->sliding[k], fabs(rs.sliding_velocity));
            m->power[k] = fmax(m->power[k], -rs.friction_force * rs.sliding_velocity); /* F_t opposes v_s */
            m->pv[k] = fmax(m->pv[k], rs.normal_force / (2.0 * 0.025 * 0.018) * fabs(rs.sliding_velocity));
            m->normal[k] = fmax(m->normal[k], rs.normal_force);
        }
        assert_int_equal(td_model_get_amb(td_sim_model(s), k, &a), TD_OK);
        assert_int_equal(td_sim_get_state(s, q, NULL), TD_OK);
        if (t < 0.05) /* both AMBs fail at 0.05 s */
            m->sensor[k] = fmax(m->sensor[k], hypot(td_system_node_displacement(sys, q, a.sensor_node, TD_DOF_X),
                                                    td_system_node_displacement(sys, q, a.sensor_node, TD_DOF_Y)));
    }
}

/* What the previous output showed of a retainer: whether it slid in contact, and its race's speed. */
typedef struct previous {
    int sliding[2];
    double race[2];
    int event; /* an event came since */
} previous;

/* A race spinning up under sliding friction from one output to the next, with no event between, rises
 * all along: the largest speed of the accepted points up to t is its speed at t. A peak that took
 * the step beyond t (held until the run reaches it) exceeds it. Returns the checks made. */
static int check_not_ahead(const td_sim *s, const shown *before, previous *p, double t)
{
    int k, checks = 0;
    for (k = 0; k < 2; k++) {
        td_retainer_totals tt;
        td_retainer_state rs;
        assert_int_equal(td_sim_retainer_totals(s, k, &tt), TD_OK);
        assert_int_equal(td_sim_retainer_state(s, k, &rs), TD_OK);
        if (!p->event && p->sliding[k] && rs.in_contact && !rs.rolling && rs.race_speed > p->race[k] &&
            rs.race_speed > before->race[k] * (1.0 + 1e-3)) {
            if (!(tt.peak_race_speed <= rs.race_speed * (1.0 + 1e-9)))
                fail_msg("t = %.9f s, retainer %d: peak race speed %.12g rad/s above the race's speed then, %.12g", t,
                         k, tt.peak_race_speed, rs.race_speed);
            checks++;
        }
        p->sliding[k] = rs.in_contact && !rs.rolling;
        p->race[k] = rs.race_speed;
    }
    p->event = 0;
    return checks;
}

/* Run the drop to 0.12 s with outputs every 0.01 ms; `restart`: a change (the unbalance set to its own
 * value) at every 50th output, which restarts the integrator there and drops the point held beyond it. */
static void run_drop(int restart, shown *m, td_retainer_totals tot[2], double sensor[2])
{
    static const char *ov[] = {"retainers[0].bearing = { static_rating = 18000.0; balls = 10; ball_diameter = 0.0111; "
                               "pitch_diameter = 0.0775; width = 0.018; }",
                               "retainers[1].bearing = { width = 0.018; }"};
    td_case *c = td_test_load_case("cases/drop.cfg", ov, 2);
    td_sim *s = NULL;
    td_error err;
    previous p;
    int k, checks = 0;
    memset(m, 0, sizeof *m);
    memset(&p, 0, sizeof p);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    show(s, 0.0, m);
    for (k = 1; k * 1.0e-5 <= 0.12; k++) {
        double t = k * 1.0e-5, tr = 0.0;
        shown before = *m;
        td_status r;
        while ((r = td_sim_step(s, t, &tr, &err)) == TD_EVENT) {
            show(s, tr, m);
            p.event = 1;
        }
        assert_int_equal(r, TD_OK);
        checks += check_not_ahead(s, &before, &p, tr);
        show(s, tr, m);
        if (restart && k % 50 == 0)
            assert_int_equal(td_sim_set_unbalance(s, 0, 0.005, 0.0, &err), TD_OK);
    }
    print_message("drop to 0.12 s%s: %d outputs with a race spinning up checked\n",
                  restart ? ", restarted at every 50th output" : "", checks);
    assert_true(checks >= 5);
    for (k = 0; k < 2; k++) {
        assert_int_equal(td_sim_retainer_totals(s, k, &tot[k]), TD_OK);
        assert_int_equal(td_sim_sensor_peak_displacement(s, k, &sensor[k]), TD_OK);
    }
    td_sim_free(&s);
    td_case_free(&c);
}

/* A peak at the accepted points against the largest value shown: not below it (to the output's
 * interpolation, `below`), above it by at most what lies between the samples (`above`). */
static void close_to_shown(const char *what, int k, double peak, double shown_max, double below, double above)
{
    print_message("  retainer/AMB %d %-22s %.9g (shown: %.9g)\n", k, what, peak, shown_max);
    if (!(peak >= shown_max * (1.0 - below) && peak <= shown_max * (1.0 + above)))
        fail_msg("%s %d: %.12g against the largest shown %.12g", what, k, peak, shown_max);
}

static void test_duty_peaks(void **state)
{
    shown m;
    td_retainer_totals t[2];
    double sensor[2];
    int k, restart;
    (void)state;
    for (restart = 0; restart < 2; restart++) {
        run_drop(restart, &m, t, sensor);
        for (k = 0; k < 2; k++) {
            assert_true(m.normal[k] > 1000.0 && m.sliding[k] > 1.0); /* both retainers were hit */
            close_to_shown("peak sliding velocity", k, t[k].peak_sliding_velocity, m.sliding[k], 1e-6, 0.01);
            close_to_shown("peak friction power", k, t[k].peak_friction_power, m.power[k], 1e-6, 0.01);
            close_to_shown("peak PV", k, t[k].peak_pv, m.pv[k], 1e-6, 0.01);
            close_to_shown("peak race speed", k, t[k].peak_race_speed, m.race[k], 1e-6, 1e-5);
            close_to_shown("sensor peak", k, sensor[k], m.sensor[k], 1e-6, 1e-6);
        }
        /* the Hertz stress of retainer 0's bearing at its peak load; retainer 1 gives no ball geometry */
        assert_true(t[0].peak_contact_stress ==
                    td_ball_inner_contact_stress(t[0].peak_normal_force, 10, 0.0111, 0.0775, 0.52));
        assert_true(t[0].peak_contact_stress > 1e9 && td_is_undefined(t[1].peak_contact_stress));
    }
}

/* The contact of some retainer, from the events of a run stepped by hand: when it first began, when
 * the one open at the end began (or -1), when the last one ended (or -1). */
static void contact_history(const char *file, const char **ov, int n, double t_end, double *first, double *onset,
                            double *ended)
{
    td_case *c = td_test_load_case(file, ov, n);
    td_sim *s = NULL;
    td_error err;
    td_status r;
    double tr = 0.0;
    int in = 0, k;
    *first = *onset = *ended = -1.0;
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    while ((r = td_sim_step(s, t_end, &tr, &err)) == TD_EVENT) {
        int now = 0;
        for (k = 0; k < td_model_retainer_count(td_case_model(c)); k++) {
            td_retainer_state rs;
            assert_int_equal(td_sim_retainer_state(s, k, &rs), TD_OK);
            now |= rs.in_contact;
        }
        if (now && !in)
            *onset = tr, *first = *first < 0.0 ? tr : *first;
        if (!now && in)
            *ended = tr, *onset = -1.0;
        in = now;
    }
    assert_int_equal(r, TD_OK);
    td_sim_free(&s);
    td_case_free(&c);
}

/* The time to settle (docs/theory.md, "Time to settle") of td_run against the contact history: the
 * steady rub of rub-damped.cfg held to 0.8 s (settled in its contact), the same run to its end at 2 s
 * (the rub ends at the unbalance step at 1.1 s: settled free), the drop to 0.3 s (bouncing: not
 * settled). */
static void test_time_to_settle(void **state)
{
    static const char *to_08[] = {"end_time = 0.8"}, *to_03[] = {"end_time = 0.3"};
    const struct {
        const char *file;
        const char **ov;
        double t_end;
        int settled;
    } runs[] = {{"cases/rub-damped.cfg", to_08, 0.8, 1},
                {"cases/rub-damped.cfg", NULL, 2.0, 1},
                {"cases/drop.cfg", to_03, 0.3, 0}};
    size_t i;
    (void)state;
    for (i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        td_case *c = td_test_load_case(runs[i].file, runs[i].ov, runs[i].ov ? 1 : 0);
        td_output_options out = *td_case_output_options(c);
        td_run_summary sum;
        td_sim *s = NULL;
        td_error err;
        double first, onset, ended, since;
        out.hdf5_path[0] = out.csv_path[0] = '\0';
        assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
        assert_int_equal(td_run(s, runs[i].t_end, &out, NULL, NULL, &sum, &err), TD_OK);
        contact_history(runs[i].file, runs[i].ov, runs[i].ov ? 1 : 0, runs[i].t_end, &first, &onset, &ended);
        since = onset >= 0.0 ? onset : ended;
        print_message("%s to %g s: first contact %.9f s, the last %s %.9f s, last stretch %.4g s: settled %d, settle "
                      "time %.9g s\n",
                      runs[i].file, runs[i].t_end, first, onset >= 0.0 ? "began" : "ended", since, sum.ending_window,
                      sum.settled, sum.settle_time);
        assert_int_equal(sum.settled, runs[i].settled);
        assert_int_equal(runs[i].t_end - since >= sum.ending_window, runs[i].settled);
        assert_true(first > 0.0 && sum.first_contact_time == first);
        if (runs[i].settled)
            assert_true(sum.settle_time == since - first);
        else
            assert_true(td_is_undefined(sum.settle_time));
        assert_int_equal(sum.contact_totals_converge, td_run_summary_regime(&sum) != TD_REGIME_BOUNCE);
        td_sim_free(&s);
        td_case_free(&c);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_duty_peaks),
        cmocka_unit_test(test_time_to_settle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
