/*
 * Long runs: a run that ends at rest (end_at_rest), the window summaries (output.window) and a
 * run's memory that does not grow with its length.
 */
#include "td_test.h"

#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/windows.h"
#include "touchdown/case.h"
#include "touchdown/result.h"
#include "touchdown/run.h"
#include "touchdown/sim.h"

/* rub-damped.cfg's rotor held centred by its AMBs with nothing to push it (no unbalance, no
 * schedule, no gravity), its speed free from 100 rad/s under a constant drag torque T only, on a
 * spin inertia J: the lateral motion stays at rest and the spin obeys J dOmega/dt = -T, so
 * Omega(t) = Omega0 - T t / J and the rotor is at rest (below 1 % of Omega0, 1 rad/s) after
 * t* = 0.99 J Omega0 / T. */
#define SPIN_J 0.01
#define SPIN_T 0.7
#define SPIN_W0 100.0
static const char *spin_down[] = {"unbalances = ()",
                                  "schedule = ()",
                                  "speed = 100.0",
                                  "spin = { free = true; inertia = 0.01; drag_torque = 0.7; drag_viscous = 0.0; }",
                                  "end_at_rest = true",
                                  "end_time = 3.0",
                                  "output.sample_rate = 1000.0"};

/* The run ends, complete, at the first grid sample after t*, with the closed form's speed there. */
static void test_end_at_rest_closed_form(void **state)
{
    td_case *c = td_test_load_case("cases/rub-damped.cfg", spin_down, 7);
    td_output_options out = *td_case_output_options(c);
    td_run_summary sum;
    td_sim *s = NULL;
    td_error err;
    const double t_star = 0.99 * SPIN_J * SPIN_W0 / SPIN_T, dt = 1.0 / out.sample_rate;
    (void)state;
    assert_int_equal(out.end_at_rest, 1);
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, td_case_end_time(c), &out, NULL, NULL, &sum, &err), TD_OK);
    print_message("t* = %.12f s, ended at %.12f s, speed %.12g rad/s, ending %s\n", t_star, sum.t_reached,
                  sum.final_speed, sum.ending);
    assert_int_equal(sum.complete, 1);
    assert_int_equal(sum.ended_at_rest, 1);
    assert_true(sum.t_reached >= t_star && sum.t_reached <= t_star + dt * (1.0 + 1e-9));
    assert_close(sum.final_speed, SPIN_W0 - SPIN_T * sum.t_reached / SPIN_J, 0.0, 1e-6);
    assert_true(td_run_at_rest(SPIN_W0, sum.final_speed));
    assert_string_equal(sum.ending, "free (no contact)");
    td_sim_free(&s);
    td_case_free(&c);
}

/* The value of the CSV file's `#` line "# NAME = VALUE" (the file's attributes), NAN text read as NaN;
 * fails the test if the line is absent. */
static double csv_attribute(const char *csv, const char *name)
{
    char line[1024], head[128];
    double v = 0.0;
    int seen = 0;
    FILE *f = fopen(csv, "r");
    assert_non_null(f);
    snprintf(head, sizeof head, "# %s = ", name);
    while (fgets(line, sizeof line, f))
        if (strncmp(line, head, strlen(head)) == 0) {
            v = strtod(line + strlen(head), NULL);
            seen++;
        }
    fclose(f);
    assert_int_equal(seen, 1);
    return v;
}

/* The run file's summary_ended_at_rest, from the HDF5 file and the CSV file's `#` line alike. */
static double files_rest_flag(const char *h5, const char *csv)
{
    td_result *r = NULL;
    td_result_array a;
    td_error err;
    double v, c = csv_attribute(csv, "summary_ended_at_rest");
    assert_int_equal(td_result_open(h5, &r, &err), TD_OK);
    assert_int_equal(td_result_read(r, TD_OUT_SUM_ENDED_AT_REST, NULL, &a, &err), TD_OK);
    assert_int_equal(a.n, 1);
    v = a.v[0];
    td_result_array_free(&a);
    td_result_free(&r);
    assert_true(isnan(v) ? isnan(c) : c == v); /* the two files say the same */
    return v;
}

/* A progress callback that stops the run at its first call at or after the time *user: there the
 * rest test has just ended the run, so it is the run's last call. */
static int stop_after(double t, double fraction, long contacts, void *user)
{
    (void)fraction;
    (void)contacts;
    return t >= *(const double *)user;
}

/* A run that stopped at rest and then failed (its last progress call asked it to stop): it did not
 * end, complete, at rest: the summary, the JSON and the files say undetermined (false, null, NaN),
 * as for any failed run, never that it ended at rest next to a status that says it failed. */
static void test_end_at_rest_then_interrupted(void **state)
{
    td_case *c = td_test_load_case("cases/rub-damped.cfg", spin_down, 7);
    td_output_options out = *td_case_output_options(c);
    const char *h5 = "test_long_run_stopped.h5", *csv = "test_long_run_stopped.csv";
    double t_star = 0.99 * SPIN_J * SPIN_W0 / SPIN_T;
    td_run_hooks hooks;
    td_run_summary sum;
    td_sim *s = NULL;
    td_error err;
    char json[65536];
    (void)state;
    memset(&hooks, 0, sizeof hooks);
    hooks.progress = stop_after;
    hooks.user = &t_star;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", h5);
    snprintf(out.csv_path, sizeof out.csv_path, "%s", csv);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, td_case_end_time(c), &out, &hooks, NULL, &sum, &err), TD_ERR_INTERRUPTED);
    print_message("%s; t_reached %.12f s (t* %.12f s)\n", err.message, sum.t_reached, t_star);
    assert_true(td_run_at_rest(SPIN_W0, td_sim_speed(s))); /* it had reached rest: the rest sample was taken */
    assert_int_equal(sum.complete, 0);
    assert_int_equal(sum.end_at_rest, 1);
    assert_int_equal(sum.ended_at_rest, 0);
    assert_true(td_run_summary_json(json, sizeof json, &sum) < (int)sizeof json);
    assert_non_null(strstr(json, "\"ended_at_rest\":null"));
    assert_true(isnan(files_rest_flag(h5, csv)));
    td_sim_free(&s);
    td_case_free(&c);
    remove(h5);
    remove(csv);
    remove("test_long_run_stopped.events.csv");
}

/* The same rotor with a drive of 1.0 N m against the 0.7 N m drag: J dOmega/dt = 0.3 N m, so it
 * speeds up (Omega = 100 + 30 t) and never rests. The run reaches end_time, complete, at the closed
 * form's speed, and its summary says it asked to end at rest and did not, in a warning naming the
 * drive. */
static void test_end_at_rest_drive_outruns_drag(void **state)
{
    const char *drive[] = {"unbalances = ()",
                           "schedule = ()",
                           "speed = 100.0",
                           "spin = { free = true; inertia = 0.01; drive_torque = 1.0; drag_torque = 0.7; }",
                           "end_at_rest = true",
                           "end_time = 0.5",
                           "output.sample_rate = 1000.0",
                           "output.section_after = 0.0"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", drive, 8);
    td_output_options out = *td_case_output_options(c);
    td_run_summary sum;
    td_sim *s = NULL;
    td_error err;
    const char *h5 = "test_long_run_drive.h5", *csv = "test_long_run_drive.csv";
    int i, named = 0;
    (void)state;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", h5);
    snprintf(out.csv_path, sizeof out.csv_path, "%s", csv);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, td_case_end_time(c), &out, NULL, NULL, &sum, &err), TD_OK);
    assert_int_equal(sum.complete, 1);
    assert_int_equal(sum.end_at_rest, 1);
    assert_int_equal(sum.ended_at_rest, 0);
    assert_true(files_rest_flag(h5, csv) == 0.0); /* the files say it too: 0, not NaN */
    remove(h5);
    remove(csv);
    remove("test_long_run_drive.events.csv");
    assert_close(sum.t_reached, 0.5, 0.0, 1e-12);
    assert_close(sum.final_speed, SPIN_W0 + (1.0 - SPIN_T) * 0.5 / SPIN_J, 0.0, 1e-6);
    for (i = 0; i < sum.warning_count; i++)
        named += strstr(sum.warnings[i], "end_at_rest: the rotor did not come to rest") != NULL &&
                 strstr(sum.warnings[i], "spin.drive_torque 1 N m exceeds its spin.drag_torque 0.7 N m") != NULL;
    assert_int_equal(named, 1);
    td_sim_free(&s);
    td_case_free(&c);
}

/* td_run applies the case reader's rule: end_at_rest on a speed held constant (rub-damped.cfg: no
 * free spin, no ramp) is refused before anything runs; the rest test of drop.cfg waits for its AMBs'
 * failure at 0.05 s (its schedule's last entry). */
static void test_end_at_rest_refused(void **state)
{
    td_case *c = td_test_load_case("cases/rub-damped.cfg", NULL, 0),
            *drop = td_test_load_case("cases/drop.cfg", NULL, 0);
    td_output_options out = *td_case_output_options(c);
    td_run_summary sum;
    td_sim *s = NULL;
    td_error err;
    char why[256];
    (void)state;
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    out.end_at_rest = 1;
    assert_int_equal(td_run_rest_refused(td_case_model(c), why, sizeof why), 1);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, 0.01, &out, NULL, NULL, &sum, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "end_at_rest: the speed is held at 90 rad/s"));
    assert_true(td_run_rest_after(td_case_model(drop)) == 0.05);
    assert_true(td_run_rest_after(td_case_model(c)) == 1.1); /* its unbalance's last step */
    td_sim_free(&s);
    td_case_free(&c);
    td_case_free(&drop);
}

/* A dataset of the run file as doubles (fails the test if absent). */
static void read_set(const td_result *r, td_out_id id, td_result_array *a)
{
    td_error err;
    assert_int_equal(td_result_read(r, id, NULL, a, &err), TD_OK);
}

/* The row of /time equal to t among the grid rows (an event row at t comes before it). */
static size_t grid_row(const td_result_array *time, double t)
{
    size_t i, at = time->n;
    for (i = 0; i < time->n; i++)
        if (time->v[i] == t)
            at = i; /* the last row at t: the grid sample, taken after the events there */
    assert_true(at < time->n);
    return at;
}

/* 1 if row j is a grid sample: on the grid k / rate, the last row at its time (events come first). */
static int is_grid_row(const td_result_array *time, size_t j, double rate)
{
    double k = time->v[j] * rate;
    return fabs(k - floor(k + 0.5)) < 1e-6 && (j + 1 == time->n || time->v[j + 1] != time->v[j]);
}

typedef struct window_check {
    td_result_array t0, t1, speed, contacts, fraction, peak, friction, temp, residual;
} window_check;

/* The window summaries of drop.cfg to 0.2 s in windows of 0.02 s against the run's own series, events
 * and totals in the same file (a second reading of the same run): the speed and the race temperature
 * at each window's end are the grid sample's there, the contacts are the onsets in the events table
 * between its ends, the time in contact and the friction work add up to the run's totals, the peak
 * is at least that of the samples in the window and of the forces right after its events, and the
 * largest of them is the run's peak (test_window_peak_is_its_own bounds it from above), the contact fraction is within
 * a sample interval's worth of the contact flag of the grid samples, and the last residual is the summary's. */
static void test_windows_against_series(void **state)
{
    static const char *ov[] = {"end_time = 0.2", "output.window = 0.02", "energy = true"};
    td_case *c = td_test_load_case("cases/drop.cfg", ov, 3);
    td_output_options out = *td_case_output_options(c);
    const char *path = "test_long_run_windows.h5";
    td_run_summary sum;
    td_sim *s = NULL;
    td_result *r = NULL;
    td_result_event *ev = NULL;
    td_result_array time, speed, normal, contact, temp;
    window_check w;
    td_error err;
    size_t n_ev, i, j;
    int k, n_ret = 2;
    double contact_sum[2] = {0.0, 0.0}, friction_sum[2] = {0.0, 0.0}, top[2] = {0.0, 0.0};
    (void)state;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", path);
    out.csv_path[0] = '\0';
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, 0.2, &out, NULL, NULL, &sum, &err), TD_OK);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    read_set(r, TD_OUT_TIME, &time);
    read_set(r, TD_OUT_SPEED, &speed);
    read_set(r, TD_OUT_RET_NORMAL_FORCE, &normal);
    read_set(r, TD_OUT_RET_CONTACT_STATE, &contact);
    read_set(r, TD_OUT_RET_RACE_TEMPERATURE, &temp);
    read_set(r, TD_OUT_WIN_TIME_START, &w.t0);
    read_set(r, TD_OUT_WIN_TIME_END, &w.t1);
    read_set(r, TD_OUT_WIN_SPEED, &w.speed);
    read_set(r, TD_OUT_WIN_CONTACTS, &w.contacts);
    read_set(r, TD_OUT_WIN_CONTACT_FRACTION, &w.fraction);
    read_set(r, TD_OUT_WIN_PEAK_NORMAL_FORCE, &w.peak);
    read_set(r, TD_OUT_WIN_FRICTION_WORK, &w.friction);
    read_set(r, TD_OUT_WIN_RACE_TEMPERATURE, &w.temp);
    read_set(r, TD_OUT_WIN_ENERGY_RESIDUAL, &w.residual);
    assert_int_equal(td_result_events(r, &ev, &n_ev, &err), TD_OK);
    assert_int_equal(w.t1.n, 10);
    assert_int_equal(w.contacts.dims[1], n_ret);
    for (i = 0; i < w.t1.n; i++) {
        size_t row = grid_row(&time, w.t1.v[i]);
        assert_close(w.t1.v[i], 0.02 * (double)(i + 1), 1e-12, 0.0);
        assert_true(i == 0 ? w.t0.v[i] == 0.0 : w.t0.v[i] == w.t1.v[i - 1]);
        assert_true(w.speed.v[i] == speed.v[row]);
        for (k = 0; k < n_ret; k++) {
            size_t at = i * (size_t)n_ret + (size_t)k, grid = 0, touching = 0;
            long onsets = 0;
            double peak = 0.0;
            assert_true(w.temp.v[at] == temp.v[row * (size_t)n_ret + (size_t)k]);
            for (j = 0; j < n_ev; j++) {
                const td_event *e = &ev[j].event;
                if (e->retainer == k && e->time > w.t0.v[i] && e->time <= w.t1.v[i]) {
                    onsets += e->kind == TD_EVENT_CONTACT_ONSET || e->kind == TD_EVENT_PENALTY_ENTER;
                    peak = fmax(peak, e->normal_force); /* right after it: a contact's own peak may be earlier */
                }
            }
            for (j = 0; j < time.n; j++)
                if (time.v[j] >= w.t0.v[i] && time.v[j] <= w.t1.v[i]) {
                    if (contact.v[j * (size_t)n_ret + (size_t)k] > 0.0)
                        peak = fmax(peak, normal.v[j * (size_t)n_ret + (size_t)k]);
                    if (time.v[j] > w.t0.v[i] && is_grid_row(&time, j, out.sample_rate)) {
                        grid++;
                        touching += contact.v[j * (size_t)n_ret + (size_t)k] > 0.0;
                    }
                }
            assert_int_equal((long)w.contacts.v[at], onsets);
            assert_true(w.peak.v[at] >= peak);
            assert_close(w.fraction.v[at], (double)touching / (double)grid, 0.0, 0.1);
            contact_sum[k] += w.fraction.v[at] * (w.t1.v[i] - w.t0.v[i]);
            friction_sum[k] += w.friction.v[at];
            top[k] = fmax(top[k], w.peak.v[at]);
        }
    }
    for (k = 0; k < n_ret; k++) {
        assert_close(contact_sum[k], sum.retainers[k].totals.contact_time, 1e-12, 1e-15);
        assert_close(friction_sum[k], sum.retainers[k].totals.friction_work, 1e-12, 1e-15);
        assert_true(top[k] == sum.retainers[k].totals.peak_normal_force);
    }
    assert_true(sum.energy_kept);
    assert_true(w.residual.v[w.residual.n - 1] == sum.energy.residual);
    td_result_array_free(&time);
    td_result_array_free(&speed);
    td_result_array_free(&normal);
    td_result_array_free(&contact);
    td_result_array_free(&temp);
    td_result_array_free(&w.t0);
    td_result_array_free(&w.t1);
    td_result_array_free(&w.speed);
    td_result_array_free(&w.contacts);
    td_result_array_free(&w.fraction);
    td_result_array_free(&w.peak);
    td_result_array_free(&w.friction);
    td_result_array_free(&w.temp);
    td_result_array_free(&w.residual);
    free(ev);
    td_result_free(&r);
    td_sim_free(&s);
    td_case_free(&c);
    remove(path);
}

/* A window's peak is that of the points inside it, never more: drop.cfg to 0.17 s in windows of
 * 0.01 s, sampled at 100 kHz (the samples then miss at most a few tenths of a percent of a contact's
 * peak at the integrator's points, measured 0.22 %). The contact of retainer 0 from 0.157826 s to
 * 0.160238 s peaks at 4452.8 N at 0.15846 s, inside the window (0.15, 0.16]; the window (0.16, 0.17]
 * where it ends holds no more than 2254 N (the force at 0.16 s, falling). Each window's peak is at
 * least the largest force of its samples after its start (the sample at its start closed the window
 * before) and at most 1 % above the largest of its samples with the one at its start (the points
 * between that sample and the next belong to it). */
static void test_window_peak_is_its_own(void **state)
{
    static const char *ov[] = {"end_time = 0.17", "output.window = 0.01", "output.sample_rate = 100000.0"};
    td_case *c = td_test_load_case("cases/drop.cfg", ov, 3);
    td_output_options out = *td_case_output_options(c);
    const char *path = "test_long_run_peak.h5";
    td_run_summary sum;
    td_sim *s = NULL;
    td_result *r = NULL;
    td_result_array time, normal, contact, t0, t1, peak;
    td_error err;
    size_t i, j;
    int k, n_ret = 2;
    (void)state;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", path);
    out.csv_path[0] = '\0';
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, 0.17, &out, NULL, NULL, &sum, &err), TD_OK);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    read_set(r, TD_OUT_TIME, &time);
    read_set(r, TD_OUT_RET_NORMAL_FORCE, &normal);
    read_set(r, TD_OUT_RET_CONTACT_STATE, &contact);
    read_set(r, TD_OUT_WIN_TIME_START, &t0);
    read_set(r, TD_OUT_WIN_TIME_END, &t1);
    read_set(r, TD_OUT_WIN_PEAK_NORMAL_FORCE, &peak);
    assert_int_equal(t1.n, 17);
    for (i = 0; i < t1.n; i++)
        for (k = 0; k < n_ret; k++) {
            double top = 0.0, edge = 0.0, w = peak.v[i * (size_t)n_ret + (size_t)k];
            for (j = 0; j < time.n; j++)
                if (time.v[j] >= t0.v[i] && time.v[j] <= t1.v[i] && contact.v[j * (size_t)n_ret + (size_t)k] > 0.0) {
                    if (time.v[j] > t0.v[i])
                        top = fmax(top, normal.v[j * (size_t)n_ret + (size_t)k]);
                    edge = fmax(edge, normal.v[j * (size_t)n_ret + (size_t)k]);
                }
            if (!(w >= top && w <= 1.01 * fmax(top, edge)))
                print_message("window (%g, %g] retainer %d: peak %.6g N, its samples' %.6g N (%.6g N with its start)\n",
                              t0.v[i], t1.v[i], k, w, top, edge);
            assert_true(w >= top);
            assert_true(w <= 1.01 * edge);
        }
    td_result_array_free(&time);
    td_result_array_free(&normal);
    td_result_array_free(&contact);
    td_result_array_free(&t0);
    td_result_array_free(&t1);
    td_result_array_free(&peak);
    td_result_free(&r);
    td_sim_free(&s);
    td_case_free(&c);
    remove(path);
}

/* The heap in use at the progress calls, its largest (glibc's count of the bytes malloc handed out
 * and not yet freed: it does not depend on time or load; under a sanitizer's allocator it reads 0). */
static int heap_peak(double t, double fraction, long contacts, void *user)
{
    size_t *peak = user, now = mallinfo2().uordblks;
    (void)t;
    (void)fraction;
    (void)contacts;
    if (now > *peak)
        *peak = now;
    return 0;
}

/* The heap a run of rub-damped.cfg to t_end with HDF5 and CSV files at 50 kHz holds at its largest. */
static size_t run_heap(double t_end)
{
    static const char *ov[] = {"output.sample_rate = 50000.0"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", ov, 1);
    td_output_options out = *td_case_output_options(c);
    td_run_hooks hooks;
    td_run_summary sum;
    td_sim *s = NULL;
    td_error err;
    size_t peak = 0;
    memset(&hooks, 0, sizeof hooks);
    hooks.progress = heap_peak;
    hooks.user = &peak;
    hooks.progress_interval = 0.01;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "test_long_run_heap.h5");
    snprintf(out.csv_path, sizeof out.csv_path, "test_long_run_heap.csv");
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    assert_int_equal(td_run(s, t_end, &out, &hooks, NULL, &sum, &err), TD_OK);
    td_sim_free(&s);
    td_case_free(&c);
    remove("test_long_run_heap.h5");
    remove("test_long_run_heap.csv");
    remove("test_long_run_heap.events.csv");
    return peak;
}

/* A run four times as long (20,000 samples of every series more, the contacts of the unbalance step)
 * holds no more heap than the shorter one, give or take 256 KiB: what it writes goes to the files as
 * it comes (HDF5's chunk cache kept up to 1 MiB of each series' written chunks: about 4 MiB more here). */
static void test_memory_bounded(void **state)
{
    size_t short_run = run_heap(0.15), long_run = run_heap(0.55);
    (void)state;
    print_message("heap in use at its largest: %zu bytes to 0.15 s, %zu bytes to 0.55 s\n", short_run, long_run);
    assert_true(long_run <= short_run + 256 * 1024);
}

/* A window closes at the first grid sample at or after its end late in a long run: after a day,
 * 86400 s (an ulp of 1.5e-11 s; 8.64e7 samples at 1 kHz, within TD_MAX_SAMPLES), a window of one
 * sample interval (1 ms) opened at each of 2000 grid times t0 + k / rate is due at the next,
 * t0 + (k + 1) / rate, whichever way the two sums round, and not at the one it opened at (the rule
 * of run/clock.h, the leap's phases' too: a tolerance of 1e-9 of the window's length alone is below
 * an ulp there). */
static void test_window_due_late_clock(void **state)
{
    const double t0 = 86400.0, rate = 1000.0, length = 1.0 / rate;
    td_case *c = td_test_load_case("cases/rub-damped.cfg", spin_down, 7);
    td_sim *s = td_test_new_sim(td_case_model(c), c);
    td_run_windows *w = NULL;
    td_error err;
    long k, late = 0;
    (void)state;
    assert_int_equal(td_run_windows_create(s, length, t0, &w, &err), TD_OK);
    for (k = 0; k < 2000; k++) {
        double t = t0 + (double)k / rate, next = t0 + (double)(k + 1) / rate;
        td_run_windows_reopen(w, s, t);
        assert_false(td_run_windows_due(w, t));
        late += !td_run_windows_due(w, next);
    }
    print_message("%ld of 2000 windows not due at their next grid sample\n", late);
    assert_int_equal(late, 0);
    td_run_windows_free(&w);
    td_sim_free(&s);
    td_case_free(&c);
}

/* A run that starts late (td_run runs from the simulation's clock, here 10 s) at a high sample rate
 * (200 MHz: a sample interval of 5e-9 s, 1e10 times below the clock) closes each window of 10
 * sample intervals on its own grid sample, t0 + 10 (i + 1) / rate, not one or two samples early: the
 * grid clock's tolerance (run/clock.h) is rounding's, of the times' ulps (1.8e-15 s here), not a part
 * of the time (1e-9 of 10 s is two sample intervals). The rotor is held still, so the 10 s before
 * cost little. */
static void test_windows_late_start(void **state)
{
    static const char *still[] = {"unbalances = ()", "schedule = ()"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", still, 2);
    td_output_options out = *td_case_output_options(c);
    const char *path = "test_long_run_late.h5";
    const double t0 = 10.0, rate = 2.0e8;
    td_run_summary sum;
    td_sim *s = NULL;
    td_result *r = NULL;
    td_result_array w0, w1;
    td_error err;
    size_t i, off = 0;
    (void)state;
    out.sample_rate = rate; /* the case reader bounds the samples over end_time: this run is 2000 */
    out.window = 10.0 / rate;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", path);
    out.csv_path[0] = '\0';
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    td_test_step_to(s, t0);
    assert_true(td_sim_time(s) == t0);
    assert_int_equal(td_run(s, t0 + 2000.0 / rate, &out, NULL, NULL, &sum, &err), TD_OK);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    read_set(r, TD_OUT_WIN_TIME_START, &w0);
    read_set(r, TD_OUT_WIN_TIME_END, &w1);
    print_message("%zu windows, the first (%.17g, %.17g]\n", w1.n, w0.v[0], w1.v[0]);
    assert_int_equal(w1.n, 200);
    for (i = 0; i < w1.n; i++) {
        double want = t0 + (double)(10 * (i + 1)) / rate; /* the grid time of its end */
        off += fabs(w1.v[i] - want) > 0.01 / rate;
        assert_true(i == 0 ? w0.v[i] == t0 : w0.v[i] == w1.v[i - 1]);
    }
    print_message("%zu of %zu windows closed off their grid sample\n", off, w1.n);
    assert_int_equal(off, 0);
    td_result_array_free(&w0);
    td_result_array_free(&w1);
    td_result_free(&r);
    td_sim_free(&s);
    td_case_free(&c);
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_end_at_rest_closed_form),
        cmocka_unit_test(test_end_at_rest_refused),
        cmocka_unit_test(test_end_at_rest_drive_outruns_drag),
        cmocka_unit_test(test_window_peak_is_its_own),
        cmocka_unit_test(test_windows_against_series),
        cmocka_unit_test(test_memory_bounded),
        cmocka_unit_test(test_window_due_late_clock),
        cmocka_unit_test(test_end_at_rest_then_interrupted),
        cmocka_unit_test(test_windows_late_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
