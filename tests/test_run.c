/*
 * td_run on a small rotor that touches its retainer: the samples lie exactly on the uniform grid
 * plus the event instants; the event table and the sampled states equal what a hand-written step
 * loop on an identical simulation sees through td_sim_last_event / td_sim_retainer_state (bit
 * for bit: the simulation is deterministic); the summary agrees with the event table; a
 * cancelled run leaves an incomplete file; bad arguments leave no file.
 */
#include "td_test.h"

#include "run/summary.h"
#include "run/warnings.h"

#include "touchdown/dofs.h"
#include "touchdown/output.h"
#include "touchdown/run.h"
#include "touchdown/touchdown.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define RATE 2000.0 /* Hz */
#define T_END 0.3   /* s */
#define OMEGA 200.0 /* rad/s */
#define CLEARANCE 2.0e-5

/*
 * Jeffcott-like rotor (cases/jeffcott.cfg): 0.6 m steel shaft, d = 20 mm, six elements, a 4.91 kg
 * disc at mid-span (node 3), stiff plain bearings at the ends, first critical speed about
 * 250 rad/s; a soft PD AMB (no negative stiffness) at node 1 and a retainer with 20 um clearance
 * at the disc. At 200 rad/s the unbalance orbit is 3.6 um with U = 1e-5 kg m; U steps to 2e-4 kg m
 * (orbit ~70 um) at 0.02 s (small_rotor), so the disc hits the retainer, and back to 1e-5 at 0.1 s.
 * Here with retainer `ret`, unbalance `u` and n scheduled changes.
 */
static td_model *jeffcott_rotor(const td_retainer *ret, const td_unbalance *u, const td_change *changes, int n)
{
    td_model *m = NULL;
    td_shaft_element el = {0.1, 0.02, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_disc disc = {3, 4.91, 0.0245, 0.0124};
    td_bearing b0 = {0, 1e8, 1e8, 200.0, 200.0}, b6 = {6, 1e8, 1e8, 200.0, 200.0};
    td_amb amb = {1, 1, 0.0, 1.0, 1e5, 20.0, 1e-4, 1e4, 0, 0.0, 0.0, 0.0};
    td_error err;
    int i;
    assert_int_equal(td_model_create(&m, &err), TD_OK);
    for (i = 0; i < 6; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, &err), TD_OK);
    assert_int_equal(td_model_add_disc(m, &disc, &err), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b0, &err), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b6, &err), TD_OK);
    assert_int_equal(td_model_add_amb(m, &amb, &err), TD_OK);
    assert_int_equal(td_model_add_retainer(m, ret, &err), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, u, &err), TD_OK);
    for (i = 0; i < n; i++)
        assert_int_equal(td_model_add_change(m, &changes[i], &err), TD_OK);
    assert_int_equal(td_model_set_speed(m, OMEGA, &err), TD_OK);
    if (td_model_validate(m, &err) != TD_OK)
        fail_msg("model: %s", err.message);
    return m;
}

static td_model *small_rotor(void)
{
    td_retainer ret = {.node = 3,
                       .clearance = CLEARANCE,
                       .shaft_radius = 0.01,
                       .bore_radius = 0.01 + CLEARANCE,
                       .friction = 0.1,
                       .bore_speed = 0.0,
                       .restitution = 0.0};
    td_unbalance u = {3, 1e-5, 0.0};
    td_change steps[2] = {{0.02, TD_CHANGE_UNBALANCE, 0, 2e-4, 0.0}, {0.1, TD_CHANGE_UNBALANCE, 0, 1e-5, 0.0}};
    return jeffcott_rotor(&ret, &u, steps, 2);
}

/* small_rotor without the unbalance steps: a free linear rotor in its steady unbalance orbit. */
static td_model *steady_rotor(void)
{
    td_retainer ret = {.node = 3, .clearance = CLEARANCE, .shaft_radius = 0.01, .bore_radius = 0.01 + CLEARANCE};
    td_unbalance u = {3, 1e-5, 0.7};
    return jeffcott_rotor(&ret, &u, NULL, 0);
}

static td_sim *make_sim(const td_model *m)
{
    td_sim *sim = NULL;
    td_error err;
    td_sim_options opt;
    td_sim_options_default(&opt);
    if (td_sim_create(m, &opt, &sim, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    return sim;
}

static void out_paths(td_output_options *out, const char *stem)
{
    td_output_options_default(out);
    snprintf(out->hdf5_path, sizeof out->hdf5_path, "%s/run_%ld_%s.h5", TD_BINARY_DIR, (long)getpid(), stem);
    snprintf(out->csv_path, sizeof out->csv_path, "%s/run_%ld_%s.csv", TD_BINARY_DIR, (long)getpid(), stem);
    out->sample_rate = RATE;
    out->node_count = 2;
    out->nodes[0] = 1;
    out->nodes[1] = 3;
}

static void remove_outputs(const td_output_options *out)
{
    char ev[TD_OUTPUT_PATH_SIZE + 32];
    td_writer_events_path(out->csv_path, ev, sizeof ev);
    remove(out->hdf5_path);
    remove(out->csv_path);
    remove(ev);
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* ---- what a hand-written loop sees ------------------------------------------------------- */

typedef struct reference {
    int rows;
    double t[4096];
    double r[4096]; /* retainer radial position */
    double n[4096]; /* normal force */
    int contact[4096];
    double x3[4096]; /* node 3 x */
    int on_grid[4096];
    int events;
    td_event ev[512];
    int ev_row[512];
} reference;

static void ref_sample(reference *ref, const td_sim *sim, double t, int on_grid)
{
    td_retainer_state rs;
    double q[28];
    assert_true(ref->rows < 4096);
    assert_int_equal(td_sim_dof_count(sim), 28);
    assert_int_equal(td_sim_get_state(sim, q, NULL), TD_OK);
    assert_int_equal(td_sim_retainer_state(sim, 0, &rs), TD_OK);
    ref->t[ref->rows] = t;
    ref->r[ref->rows] = rs.radius;
    ref->n[ref->rows] = rs.normal_force;
    ref->contact[ref->rows] = rs.in_contact;
    ref->x3[ref->rows] = q[TD_DOF(3, TD_DOF_X)];
    ref->on_grid[ref->rows] = on_grid;
    ref->rows++;
}

/* The sampling rule of docs/output-format.md, written out independently of lib/run/run.c. */
static void reference_run(const td_model *m, reference *ref)
{
    td_sim *sim = make_sim(m);
    long k;
    double last_event_t = -1.0;
    int last_event_row = -1;
    memset(ref, 0, sizeof *ref);
    ref_sample(ref, sim, 0.0, 1);
    for (k = 1;; k++) {
        double target = (double)k / RATE;
        int last = target >= T_END - 1e-6 / RATE;
        if (last)
            target = T_END;
        while (target - td_sim_time(sim) > 4.0 * DBL_EPSILON * (target > 1.0 ? target : 1.0)) {
            td_status st = td_sim_step(sim, target, NULL, NULL);
            if (st == TD_OK)
                break;
            assert_int_equal(st, TD_EVENT);
            assert_true(ref->events < 512);
            assert_int_equal(td_sim_last_event(sim, &ref->ev[ref->events]), TD_OK);
            /* one sample per event instant, shared by every event at that instant */
            if (td_sim_time(sim) != last_event_t) {
                ref_sample(ref, sim, td_sim_time(sim), 0);
                last_event_t = td_sim_time(sim);
                last_event_row = ref->rows - 1;
            }
            ref->ev_row[ref->events++] = last_event_row;
        }
        ref_sample(ref, sim, target, 1);
        if (last)
            break;
    }
    td_sim_free(&sim);
}

/* ---- reading the HDF5 result (touchdown/result.h) ------------------------------------------ */

static td_result *open_result(const char *path)
{
    td_result *r = NULL;
    td_error err;
    if (td_result_open(path, &r, &err) != TD_OK)
        fail_msg("td_result_open: %s", err.message);
    assert_int_equal(td_result_get_kind(r), TD_RESULT_RUN);
    return r;
}

/* The dataset `id` (rows x cols_expected values), malloc'd; *rows its first dimension. */
static double *read_doubles(const td_result *f, td_out_id id, size_t *rows, int cols_expected)
{
    td_result_array a;
    td_error err;
    if (td_result_read(f, id, NULL, &a, &err) != TD_OK)
        fail_msg("td_result_read: %s", err.message);
    assert_int_equal(a.n, a.dims[0] * (size_t)cols_expected);
    assert_string_equal(a.units, td_out_units(id));
    *rows = a.dims[0];
    return a.v;
}

static double root_double(const td_result *f, td_out_id id)
{
    td_result_array a;
    double v;
    td_error err;
    if (td_result_read(f, id, NULL, &a, &err) != TD_OK)
        fail_msg("td_result_read: %s", err.message);
    assert_int_equal(a.n, 1);
    v = a.v[0];
    td_result_array_free(&a);
    return v;
}

static long long root_ll(const td_result *f, td_out_id id)
{
    return (long long)root_double(f, id);
}

static td_result_event *read_events(const td_result *f, size_t *n)
{
    td_result_event *ev = NULL;
    td_error err;
    if (td_result_events(f, &ev, n, &err) != TD_OK)
        fail_msg("td_result_events: %s", err.message);
    return ev;
}

/* ---- tests ------------------------------------------------------------------------------- */

static void test_run_matches_hand_loop(void **state)
{
    td_model *m = small_rotor();
    td_sim *sim = make_sim(m);
    td_output_options out;
    td_run_summary s;
    td_error err;
    reference *ref = calloc(1, sizeof *ref);
    td_result *f;
    size_t rows, n_ev, i;
    double *t, *r, *x, *nf;
    td_result_event *ev;
    long grid = 0, onsets = 0;
    double contact_time = 0.0, onset_t = -1.0, first_onset = -1.0, last_release = -1.0, window;
    double sampled_peak = 0.0, sampled_peak_t = -1.0;
    int peak_in_contact = 0;
    (void)state;
    assert_non_null(ref);
    out_paths(&out, "hand");
    remove_outputs(&out);
    if (td_run(sim, T_END, &out, NULL, "case text", &s, &err) != TD_OK)
        fail_msg("td_run: %s", err.message);
    assert_int_equal(s.status, TD_OK);
    assert_int_equal(s.complete, 1);
    td_sim_free(&sim);

    reference_run(m, ref);
    print_message("rows %d, events %d, contacts %ld, first contact %.10f s, peak %.6g N, "
                  "contact fraction %.4f, wall %.3f s\n",
                  ref->rows, ref->events, s.contacts, s.first_contact_time, s.peak_normal_force, s.contact_fraction,
                  s.wall_time);
    assert_true(ref->events >= 3); /* two schedule events and at least one contact onset */

    f = open_result(out.hdf5_path);
    assert_int_equal(td_result_complete(f), 1);
    assert_int_equal(root_ll(f, TD_OUT_COMPLETE), 1);
    t = read_doubles(f, TD_OUT_TIME, &rows, 1);
    assert_int_equal(rows, (size_t)ref->rows);
    r = read_doubles(f, TD_OUT_RET_RADIAL_POSITION, &rows, 1);
    nf = read_doubles(f, TD_OUT_RET_NORMAL_FORCE, &rows, 1);
    x = read_doubles(f, TD_OUT_NODE_DISPLACEMENT, &rows, 4);
    for (i = 0; i < rows; i++) {
        if (!same_bits(t[i], ref->t[i]) || !same_bits(r[i], ref->r[i]) || !same_bits(nf[i], ref->n[i]) ||
            !same_bits(x[4 * i + 2], ref->x3[i]))
            fail_msg("row %lu: t %.17g/%.17g r %.17g/%.17g N %.17g/%.17g", (unsigned long)i, t[i], ref->t[i], r[i],
                     ref->r[i], nf[i], ref->n[i]);
        if (i > 0)
            assert_true(t[i] >= t[i - 1]);
        if (ref->on_grid[i]) {
            /* exactly on the grid: t = k / rate for the next k, or t_end */
            assert_true(same_bits(t[i], (double)grid / RATE) || (grid == (long)(T_END * RATE) && t[i] == T_END));
            grid++;
        }
    }
    assert_int_equal(grid, (long)(T_END * RATE + 0.5) + 1);
    assert_int_equal(s.grid_samples, grid);
    assert_int_equal(s.samples, (long)rows);

    ev = read_events(f, &n_ev);
    assert_int_equal(n_ev, (size_t)ref->events);
    assert_int_equal(s.events, ref->events);
    for (i = 0; i < n_ev; i++) {
        const td_event *e = &ref->ev[i];
        assert_true(same_bits(ev[i].event.time, e->time));
        assert_int_equal(ev[i].event.kind, (int)e->kind);
        assert_int_equal(ev[i].event.retainer, e->retainer);
        assert_int_equal(ev[i].event.change, e->change);
        assert_true(same_bits(ev[i].event.radial_velocity_before, e->radial_velocity_before));
        assert_true(same_bits(ev[i].event.radial_velocity_after, e->radial_velocity_after));
        assert_true(same_bits(ev[i].event.tangential_velocity_before, e->tangential_velocity_before));
        assert_true(same_bits(ev[i].event.tangential_velocity_after, e->tangential_velocity_after));
        assert_true(same_bits(ev[i].event.impulse, e->impulse));
        assert_true(same_bits(ev[i].event.normal_force, e->normal_force));
        /* the sample taken at the event: same time, not a grid row */
        assert_int_equal(ev[i].sample, ref->ev_row[i]);
        assert_true(same_bits(t[ev[i].sample], ev[i].event.time));
        assert_false(ref->on_grid[ev[i].sample]);
        /* contact bookkeeping from the table alone (one retainer, plastic impacts) */
        if (ev[i].event.kind == TD_EVENT_CONTACT_ONSET) {
            onsets++;
            if (first_onset < 0.0)
                first_onset = ev[i].event.time;
            if (ref->contact[ev[i].sample] && onset_t < 0.0)
                onset_t = ev[i].event.time;
        } else if (ev[i].event.kind == TD_EVENT_RELEASE && onset_t >= 0.0) {
            peak_in_contact |= s.peak_time >= onset_t && s.peak_time <= ev[i].event.time;
            contact_time += ev[i].event.time - onset_t;
            onset_t = -1.0;
            last_release = ev[i].event.time;
        }
    }
    if (onset_t >= 0.0)
        contact_time += T_END - onset_t;
    assert_true(onsets >= 1);
    assert_int_equal(s.contacts, onsets);
    assert_true(same_bits(s.first_contact_time, first_onset));
    assert_close(s.contact_time, contact_time, 1e-12, 1e-15);
    assert_close(s.contact_fraction, contact_time / T_END, 1e-12, 1e-15);
    assert_close(s.revolutions, OMEGA * T_END / (2.0 * TD_PI), 1e-14, 0.0);
    assert_close(s.revolutions_after_contact, OMEGA * (T_END - first_onset) / (2.0 * TD_PI), 1e-14, 0.0);
    assert_true(s.wall_time_per_revolution > 0.0);
    /* free orbit: no contact in the last 5 revolutions (the unbalance drops at 0.1 s) */
    window = TD_RUN_FREE_REVOLUTIONS * 2.0 * TD_PI / OMEGA;
    assert_close(s.free_window, window, 1e-15, 0.0);
    assert_true(onset_t < 0.0);
    assert_true(same_bits(s.last_contact_time, last_release));
    assert_int_equal(s.free_at_end, T_END - last_release >= window);
    assert_int_equal(s.returned_to_free_orbit, T_END - last_release >= window);
    print_message("last contact ended %.10f s, returned to free orbit %d\n", last_release, s.returned_to_free_orbit);
    assert_true(s.peak_normal_force > 0.0);
    /* the peak: at least the largest sampled force, at its first sample if it is that one, and
     * anyway inside a contact interval of the event table, at the one retainer */
    for (i = 0; i < rows; i++)
        if (nf[i] > sampled_peak) {
            sampled_peak = nf[i];
            sampled_peak_t = t[i];
        }
    assert_true(s.peak_normal_force >= sampled_peak);
    if (s.peak_normal_force == sampled_peak)
        assert_true(same_bits(s.peak_time, sampled_peak_t));
    assert_true(peak_in_contact);
    assert_int_equal(s.peak_retainer, 0);
    print_message("peak %.6g N at %.10f s (largest sample %.6g N at %.10f s)\n", s.peak_normal_force, s.peak_time,
                  sampled_peak, sampled_peak_t);
    /* every file written is named */
    assert_string_equal(s.hdf5_path, out.hdf5_path);
    assert_string_equal(s.csv_path, out.csv_path);
    assert_non_null(strstr(s.events_path, ".events.csv"));
    assert_true(exists(s.events_path));
    assert_int_equal(root_ll(f, TD_OUT_SUM_CONTACTS), onsets);
    assert_int_equal(root_ll(f, TD_OUT_STAT_STEPS), s.stats.steps);
    td_result_free(&f);

    free(t);
    free(r);
    free(nf);
    free(x);
    free(ev);
    free(ref);
    remove_outputs(&out);
    td_model_free(&m);
}

/* Cancel (as a signal handler would) once t passes 0.05 s: incomplete files, what was computed kept. */
typedef struct cancel_ctx {
    volatile sig_atomic_t *flag;
    double at;
    int calls;
} cancel_ctx;

static int cancel_later(double t, double fraction, long contacts, void *user)
{
    cancel_ctx *c = user;
    (void)contacts;
    assert_true(fraction >= 0.0 && fraction <= 1.0);
    c->calls++;
    if (t >= c->at)
        *c->flag = 1;
    return 0;
}

static void test_run_cancel(void **state)
{
    td_model *m = small_rotor();
    td_sim *sim = make_sim(m);
    td_output_options out;
    td_run_summary s;
    td_error err;
    volatile sig_atomic_t flag = 0;
    cancel_ctx ctx;
    td_run_hooks hooks;
    td_result *f;
    size_t rows;
    double *t;
    char reason[512] = "", *tail, *text = NULL;
    FILE *csv;
    char line[512], last[512] = "";
    (void)state;
    out_paths(&out, "cancel");
    ctx.flag = &flag;
    ctx.at = 0.05;
    ctx.calls = 0;
    memset(&hooks, 0, sizeof hooks);
    hooks.progress = cancel_later;
    hooks.user = &ctx;
    hooks.progress_interval = 0.01;
    hooks.cancel = &flag;
    assert_int_equal(td_run(sim, T_END, &out, &hooks, NULL, &s, &err), TD_ERR_INTERRUPTED);
    assert_non_null(strstr(err.message, "interrupted"));
    assert_int_equal(s.complete, 0);
    assert_true(ctx.calls >= 5 && ctx.calls <= 8); /* every 0.01 s of simulated time up to 0.05 s */
    assert_true(s.t_reached >= 0.05 && s.t_reached < 0.05 + 2.0 / RATE);
    /* a run that did not reach its end has no answers (touchdown/dofs.h, "Undefined values"),
     * though it counted its samples */
    assert_true(td_is_undefined(s.peak_housing_force) && td_is_undefined(s.total_impulse));
    assert_true(td_is_undefined(s.final_speed) && td_is_undefined(s.contact_time));
    assert_true(td_is_undefined(s.retainers[0].totals.impulse));
    assert_true(s.samples > 0);
    f = open_result(out.hdf5_path);
    assert_int_equal(td_result_get_flag(f), TD_RESULT_INCOMPLETE);
    assert_int_equal(td_result_complete(f), 0);
    assert_true(td_is_undefined(root_double(f, TD_OUT_SUM_PEAK_HOUSING_FORCE)));
    assert_true(td_is_undefined(root_double(f, TD_OUT_SUM_FINAL_SPEED)));
    assert_true(root_double(f, TD_OUT_T_REACHED) == s.t_reached);
    assert_int_equal(td_result_read_text(f, TD_OUT_INCOMPLETE_REASON, NULL, &text, &err), TD_OK);
    snprintf(reason, sizeof reason, "%s", text);
    free(text);
    assert_non_null(strstr(reason, "interrupted at t = 0.05"));
    t = read_doubles(f, TD_OUT_TIME, &rows, 1);
    assert_int_equal(rows, (size_t)s.samples);
    assert_true(same_bits(t[rows - 1], s.t_reached));
    free(t);
    td_result_free(&f);
    csv = fopen(out.csv_path, "r");
    assert_non_null(csv);
    while (fgets(line, sizeof line, csv))
        memcpy(last, line, sizeof line);
    fclose(csv);
    tail = strstr(last, "# incomplete: interrupted at t = ");
    assert_non_null(tail);
    td_sim_free(&sim);
    remove_outputs(&out);
    td_model_free(&m);
}

static void test_run_bad_arguments(void **state)
{
    td_model *m = small_rotor();
    td_sim *sim = make_sim(m);
    td_output_options out;
    td_run_summary s;
    td_error err;
    (void)state;
    out_paths(&out, "bad");
    remove_outputs(&out);
    assert_int_equal(td_run(sim, 0.0, &out, NULL, NULL, &s, &err), TD_ERR_INVALID);
    out.nodes[1] = 7; /* the shaft has nodes 0..6 */
    assert_int_equal(td_run(sim, 0.1, &out, NULL, NULL, &s, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "node 7"));
    out.nodes[1] = 3;
    out.sample_rate = 0.0;
    assert_int_equal(td_run(sim, 0.1, &out, NULL, NULL, &s, &err), TD_ERR_INVALID);
    assert_false(exists(out.hdf5_path));
    assert_false(exists(out.csv_path));
    assert_int_equal(td_sim_time(sim), 0.0); /* nothing was stepped */
    /* no files at all: still a complete run with its summary (15 ms before the unbalance step:
     * the grid 0..30, no event) */
    out.sample_rate = RATE;
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    assert_int_equal(td_run(sim, 0.015, &out, NULL, NULL, &s, &err), TD_OK);
    assert_int_equal(s.complete, 1);
    assert_int_equal(s.grid_samples, 31);
    assert_int_equal(s.events, 0);
    assert_int_equal(s.samples, 31);
    assert_int_equal(s.contacts, 0);
    assert_true(td_is_undefined(s.first_contact_time));                /* no contact: no first-contact time */
    assert_true(td_is_undefined(s.revolutions_after_contact));         /* and no revolutions after it */
    assert_int_equal(s.free_at_end, -1);                               /* 0.015 s is shorter than 5 revolutions */
    assert_int_equal(s.returned_to_free_orbit, TD_RUN_NOT_APPLICABLE); /* no contact to return from */
    assert_true(s.t_reached == 0.015);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* ---- summary text ------------------------------------------------------------------------ */

static td_run_summary made_up_summary(void)
{
    td_run_summary s;
    memset(&s, 0, sizeof s);
    s.status = TD_OK;
    s.complete = 1;
    s.t_end = s.t_reached = 2.0;
    s.speed = 90.0;
    s.samples = 20013;
    s.grid_samples = 20001;
    s.events = 12;
    s.contacts = 5;
    s.first_contact_time = 0.12345678912345678;
    s.last_contact_time = 1.1000000001;
    s.peak_normal_force = 1834.25;
    s.contact_time = 0.5;
    s.contact_fraction = 0.25;
    s.free_window = 5 * 2.0 * TD_PI / 90.0;
    s.free_at_end = 1;
    s.returned_to_free_orbit = 1;
    s.revolutions = 90.0 * 2.0 / (2.0 * TD_PI);
    s.wall_time_per_revolution = TD_UNDEFINED;
    s.realtime_factor = 0.5;
    s.stats.steps = 4242;
    s.stats.first_contact_time = TD_UNDEFINED;
    return s;
}

static void test_summary_text(void **state)
{
    td_run_summary s = made_up_summary();
    char buf[4096], small[16];
    int n;
    (void)state;
    n = td_run_summary_format(buf, sizeof buf, &s);
    assert_int_equal(n, (int)strlen(buf));
    assert_non_null(strstr(buf, "0.1234567891 s")); /* 1e-10 s resolution */
    assert_non_null(strstr(buf, "returned to free orbit      yes"));
    assert_non_null(strstr(buf, "wall time per revolution    n/a"));
    assert_int_equal(td_run_summary_format(small, sizeof small, &s), n);
    assert_int_equal(strlen(small), sizeof small - 1);
    assert_int_equal(td_run_summary_format(NULL, 0, &s), n);

    n = td_run_summary_json(buf, sizeof buf, &s);
    assert_int_equal(n, (int)strlen(buf));
    assert_int_equal(buf[0], '{');
    assert_int_equal(buf[n - 1], '}');
    assert_non_null(strstr(buf, "\"first_contact_time\":0.12345678912345678,"));
    assert_non_null(strstr(buf, "\"wall_time_per_revolution\":null,"));
    assert_non_null(strstr(buf, "\"returned_to_free_orbit\":true,"));
    assert_non_null(strstr(buf, "\"complete\":true,"));
    assert_non_null(strstr(buf, "\"steps\":4242,"));
    /* a retainer whose race speed has no value: null in JSON, n/a in the text, never 0 */
    s.retainer_count = 2;
    snprintf(s.retainers[0].whirl, sizeof s.retainers[0].whirl, "none");
    snprintf(s.retainers[1].whirl, sizeof s.retainers[1].whirl, "none");
    s.retainers[0].race_speed = 12.5;
    s.retainers[1].race_speed = TD_UNDEFINED;
    s.retainers[0].whirl_frequency = s.retainers[1].whirl_frequency = TD_UNDEFINED;
    td_run_summary_json(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "\"retainer_race_speed\":[12.5,null]"));
    td_run_summary_format(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "; race 12.5 rad/s\n"));
    assert_non_null(strstr(buf, "; race n/a\n"));
    s.complete = 0;
    s.status = TD_ERR_SOLVER;
    snprintf(s.message, sizeof s.message, "bad \"step\"\n at t = 1");
    td_run_summary_json(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "\"message\":\"bad \\\"step\\\"\\u000a at t = 1\""));
    td_run_summary_format(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "INCOMPLETE (solver failure)"));
}

/* The AMB Jeffcott rotor past its Routh-Hurwitz limit kp = kd / tau (tests/data/case/amb-jeffcott.cfg),
 * started at rest: the summary says unstable in text and JSON; nothing touched, so "returned to
 * free orbit" and the peak do not apply (null). */
static void test_summary_unstable_run(void **state)
{
    const char *ov[3] = {"ambs[0].kp=1.01e4", "ambs[1].kp=1.01e4", "start=\"rest\""};
    td_case *c = td_test_load_case("tests/data/case/amb-jeffcott.cfg", ov, 3);
    td_output_options out = *td_case_output_options(c);
    td_sim *sim = NULL;
    td_run_summary s;
    td_error err;
    char buf[8192];
    (void)state;
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &sim, &err), TD_OK);
    assert_int_equal(td_run(sim, 0.005, &out, NULL, NULL, &s, &err), TD_OK);
    assert_int_equal(s.start.stability, TD_STABILITY_UNSTABLE);
    assert_true(s.start.max_real_part > 0.0);
    td_run_summary_format(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "contact-free system         unstable"));
    assert_non_null(strstr(buf, "start                       rest\n"));
    assert_non_null(strstr(buf, "returned to free orbit      n/a"));
    assert_non_null(strstr(buf, "files                       none"));
    td_run_summary_json(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "\"stability\":\"unstable\","));
    assert_non_null(strstr(buf, "\"start\":\"rest\","));
    assert_non_null(strstr(buf, "\"returned_to_free_orbit\":null,"));
    assert_non_null(strstr(buf, "\"peak_time\":null,\"peak_retainer\":null,"));
    assert_non_null(strstr(buf, "\"hdf5_path\":null,\"csv_path\":null,\"events_path\":null,"));
    td_sim_free(&sim);
    td_case_free(&c);
}

/* A run that fails before it starts still has a summary: status, message, time reached. */
static void test_summary_failed_before_start(void **state)
{
    td_run_summary s;
    char buf[8192];
    (void)state;
    td_run_summary_failed(&s, 0.0, 2.0, 90.0, TD_START_ORBIT, TD_ERR_INVALID, "the orbit is \"outside\"");
    assert_int_equal(s.complete, 0);
    td_run_summary_json(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "\"complete\":false,\"status\":\"invalid argument\","));
    assert_non_null(strstr(buf, "\"message\":\"the orbit is \\\"outside\\\"\","));
    assert_non_null(strstr(buf, "\"t_reached\":0,"));
    assert_non_null(strstr(buf, "\"start_requested\":\"orbit\",\"start\":null,"));
    td_run_summary_format(buf, sizeof buf, &s);
    assert_non_null(strstr(buf, "INCOMPLETE (invalid argument): the orbit is \"outside\""));
    assert_non_null(strstr(buf, "start                       n/a"));
}

/* What td_run reads from the sim: its own copy of the model and the options it was created with. */
static void test_sim_accessors(void **state)
{
    td_model *m = small_rotor();
    td_sim *sim = NULL;
    td_sim_options opt, got;
    td_error err;
    (void)state;
    td_sim_options_default(&opt);
    opt.solver.max_step = 1.25e-4;
    if (td_sim_create(m, &opt, &sim, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    assert_non_null(td_sim_model(sim));
    assert_true(td_sim_model(sim) != m); /* a copy: m may be freed */
    assert_int_equal(td_model_dof_count(td_sim_model(sim)), td_model_dof_count(m));
    assert_true(td_model_speed(td_sim_model(sim)) == td_model_speed(m));
    assert_int_equal(td_sim_options_get(sim, &got), TD_OK);
    assert_true(got.solver.max_step == 1.25e-4);
    assert_true(got.solver.rtol == opt.solver.rtol);
    assert_null(td_sim_model(NULL));
    assert_int_equal(td_sim_options_get(NULL, &got), TD_ERR_INVALID);
    assert_int_equal(td_sim_options_get(sim, NULL), TD_ERR_INVALID);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* The JSON string escape of touchdown/json.h: RFC 8259's mandatory escapes, snprintf's contract. */
static void test_json_string(void **state)
{
    char buf[64];
    (void)state;
    assert_int_equal(td_json_string(buf, sizeof buf, "a\"b\\c\n\001d/\xc3\xa9"), 25);
    assert_string_equal(buf, "\"a\\\"b\\\\c\\u000a\\u0001d/\xc3\xa9\"");
    assert_int_equal(td_json_string(NULL, 0, "a\"b"), 6);
    assert_int_equal(td_json_string(buf, 4, "a\"b"), 6);
    assert_string_equal(buf, "\"a\\");
    assert_int_equal(td_json_string(buf, sizeof buf, NULL), 2);
    assert_string_equal(buf, "\"\"");
}

/* td_run_summary_ending on hand-made totals over a stretch of 1 s at 100 rad/s (15.9 Hz spin):
 * the whirl rate is the whirl angle swept over the contact time, signed like the spin. */
/* The steady orbit of steady_rotor, started on it, to t_end with the section from a third of T_END
 * on; free_flight: the closed-form flight carries it, else IDA. */
static void steady_section_to(int free_flight, double t_end, td_run_summary *s)
{
    td_model *m = steady_rotor();
    td_sim *sim = NULL;
    td_sim_options opt;
    td_output_options out;
    td_error err;
    td_sim_options_default(&opt);
    opt.start = TD_START_ORBIT;
    opt.solver.free_flight = free_flight;
    if (!free_flight) { /* tight enough that IDA's own error stays far below the check's 1e-5 */
        opt.solver.rtol = 1e-10;
        opt.solver.atol = 1e-15;
    }
    if (td_sim_create(m, &opt, &sim, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    td_output_options_default(&out);
    out.sample_rate = RATE;
    out.section_after = T_END / 3.0 / t_end;
    if (td_run(sim, t_end, &out, NULL, NULL, s, &err) != TD_OK)
        fail_msg("td_run: %s", err.message);
    td_sim_free(&sim);
    td_model_free(&m);
}

static void steady_section(int free_flight, td_run_summary *s)
{
    steady_section_to(free_flight, T_END, s);
}

/* The harmonic response's position of node 3 where the spin angle is a multiple of 2 pi: the
 * unbalance force turns with e^{i omega t}, so there the orbit is at (Re X, Re Y). */
static double harmonic_section_radius(void)
{
    td_model *m = steady_rotor();
    td_system *sys = NULL;
    td_harmonic *h = NULL;
    td_unbalance u;
    td_orbit o;
    td_error err;
    double r;
    assert_int_equal(td_system_create(m, &sys, &err), TD_OK);
    td_model_get_unbalance(m, 0, &u);
    assert_int_equal(td_harmonic_compute(sys, OMEGA, &u, 1, &h, &err), TD_OK);
    assert_int_equal(td_harmonic_orbit(h, 3, &o), TD_OK);
    r = hypot(o.x_re, o.y_re);
    td_harmonic_free(&h);
    td_system_free(&sys);
    td_model_free(&m);
    return r;
}

/* A free linear rotor in its steady unbalance orbit: every once-per-revolution sample is the
 * harmonic response's radius at phase 0 (closed form, touchdown/modal.h), from the flight's
 * closed form and from IDA's interpolant alike; one crossing a revolution after the transient. */
static void test_section_steady_orbit(void **state)
{
    td_run_summary *s = calloc(2, sizeof *s);
    double expect = harmonic_section_radius(), period = 2.0 * TD_PI / OMEGA;
    int pass, i;
    (void)state;
    assert_non_null(s);
    steady_section(1, &s[0]);
    steady_section(0, &s[1]);
    assert_true(s[0].stats.flight_time > 0.5 * T_END); /* the flight carried it */
    assert_true(s[1].stats.flight_time == 0.0);
    for (pass = 0; pass < 2; pass++) {
        const td_run_summary *p = &s[pass];
        /* crossings at t = 2 pi k / omega in [T_END / 3, T_END] */
        long expect_count = (long)floor(T_END / period) - (long)ceil(T_END / 3.0 / period) + 1;
        assert_int_equal(p->section_count, expect_count);
        assert_int_equal(p->section_kept,
                         expect_count < TD_RUN_SECTION_SAMPLES ? expect_count : TD_RUN_SECTION_SAMPLES);
        assert_int_equal(p->section_retainer, 0);
        assert_close(p->section_start, T_END / 3.0, 1e-15, 0.0);
        for (i = 0; i < p->section_kept; i++) {
            double k = p->section_time[i] / period;
            assert_close(k, floor(k + 0.5), 1e-9, 0.0);
            /* flight: the closed form; IDA: its interpolant at tight tolerances */
            assert_close(p->section_radius[i], expect, pass == 0 ? 1e-9 : 1e-5, 0.0);
        }
    }
    free(s);
}

/* A run that ends 1e-9 s before a crossing, inside IDA's last step, which runs on past the end: the
 * section holds the crossings up to the end only (it used to count the one beyond end_time, with its
 * time past it). Crossings at t = 2 pi k / omega: the 9th is 0.2827 s. */
static void test_section_ends_at_end_time(void **state)
{
    td_run_summary *s = calloc(1, sizeof *s);
    double period = 2.0 * TD_PI / OMEGA, t_end = 9.0 * period - 1e-9;
    long expect = 8 - (long)ceil(T_END / 3.0 / period) + 1; /* k = ceil(T_END / 3 / period) .. 8 */
    (void)state;
    assert_non_null(s);
    steady_section_to(0, t_end, s);
    print_message("to %.12f s: %ld crossings (expected %ld), the last at %.12f s; IDA %ld steps\n", t_end,
                  s->section_count, expect, s->section_kept ? s->section_time[s->section_kept - 1] : NAN,
                  s->stats.steps);
    assert_true(s->section_kept > 0 && s->stats.flight_time == 0.0);
    assert_true(s->section_time[s->section_kept - 1] <= t_end);
    assert_int_equal(s->section_count, expect);
    free(s);
}

/* A speed ramp down from 200 to 100 rad/s (a run-down): the spin angle is a state, and every
 * crossing found on IDA's interpolant of it is where the prescribed angle, the closed-form integral
 * of the ramp (td_model_speed_at), is the next multiple of 2 pi. */
static void test_section_speed_ramp(void **state)
{
    td_model *m = steady_rotor();
    td_speed_point p0 = {0.0, OMEGA}, p1 = {T_END, 0.5 * OMEGA};
    td_sim *sim;
    td_output_options out;
    td_run_summary *s = calloc(1, sizeof *s);
    td_error err;
    double total;
    int i;
    (void)state;
    assert_non_null(s);
    assert_int_equal(td_model_add_speed_point(m, &p0, &err), TD_OK);
    assert_int_equal(td_model_add_speed_point(m, &p1, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_OK);
    sim = make_sim(m);
    td_output_options_default(&out);
    out.sample_rate = RATE;
    out.section_after = 0.0;
    if (td_run(sim, T_END, &out, NULL, NULL, s, &err) != TD_OK)
        fail_msg("td_run: %s", err.message);
    td_model_speed_at(m, T_END, NULL, &total);
    /* crossings 2 pi k, k = 1 .. floor(total / 2 pi), all kept */
    assert_int_equal(s->section_count, (long)floor(total / (2.0 * TD_PI)));
    assert_int_equal(s->section_kept, s->section_count);
    for (i = 0; i < s->section_kept; i++) {
        double angle;
        td_model_speed_at(m, s->section_time[i], NULL, &angle);
        assert_close(angle, 2.0 * TD_PI * (i + 1), 1e-9, 0.0);
        assert_true(s->section_radius[i] > 0.0 && s->section_radius[i] < CLEARANCE);
    }
    td_sim_free(&sim);
    td_model_free(&m);
    free(s);
}

/* The state td_sim_step gives at time t (events on the way passed), node 3's radius there. */
static double radius_stepped_to(td_sim *sim, double t, double *q)
{
    td_status st;
    while ((st = td_sim_step(sim, t, NULL, NULL)) == TD_EVENT)
        ;
    assert_int_equal(st, TD_OK);
    assert_int_equal(td_sim_get_state(sim, q, NULL), TD_OK);
    return hypot(q[TD_DOF(3, TD_DOF_X)], q[TD_DOF(3, TD_DOF_Y)]);
}

/* Through contact and the free flights between (small_rotor, from rest): each section sample is
 * the state at its crossing time as a second simulation, stepped to exactly that time through the
 * public API, has it (to rounding): the crossing's own instant, not an output sample near it. */
static void test_section_matches_stepping(void **state)
{
    td_model *m = small_rotor();
    td_sim *sim = make_sim(m), *again = make_sim(m);
    td_output_options out;
    td_run_summary *s = calloc(1, sizeof *s);
    double *q = calloc((size_t)td_sim_dof_count(again), sizeof *q), period = 2.0 * TD_PI / OMEGA;
    td_error err;
    int i;
    (void)state;
    assert_true(s && q);
    td_output_options_default(&out);
    out.sample_rate = RATE;
    out.section_after = 0.0;
    if (td_run(sim, T_END, &out, NULL, NULL, s, &err) != TD_OK)
        fail_msg("td_run: %s", err.message);
    assert_true(s->contacts > 0);
    assert_int_equal(s->section_count, (long)floor(T_END / period));
    assert_int_equal(s->section_kept, s->section_count);
    for (i = 0; i < s->section_kept; i++) {
        /* the crossings themselves: t = 2 pi k / omega, off the 2 kHz output grid */
        assert_close(s->section_time[i], period * (i + 1), 1e-14, 0.0);
        assert_close(s->section_radius[i], radius_stepped_to(again, s->section_time[i], q), 1e-12, 0.0);
    }
    td_sim_free(&again);
    td_sim_free(&sim);
    td_model_free(&m);
    free(q);
    free(s);
}

/* Taking the section moves nothing: the contact run of small_rotor gives the same answers, bit for
 * bit, with the section over the whole run and without one. */
static void test_section_changes_nothing(void **state)
{
    td_run_summary *s = calloc(2, sizeof *s);
    int pass, k;
    (void)state;
    assert_non_null(s);
    for (pass = 0; pass < 2; pass++) {
        td_model *m = small_rotor();
        td_sim *sim = make_sim(m);
        td_output_options out;
        td_error err;
        td_output_options_default(&out);
        out.sample_rate = RATE;
        out.section_after = pass == 0 ? 0.0 : 1.0;
        if (td_run(sim, T_END, &out, NULL, NULL, &s[pass], &err) != TD_OK)
            fail_msg("td_run: %s", err.message);
        td_sim_free(&sim);
        td_model_free(&m);
    }
    assert_true(s[0].contacts > 0 && s[0].section_count > 0 && s[1].section_count == 0);
    assert_true(same_bits(s[0].peak_housing_force, s[1].peak_housing_force));
    assert_true(same_bits(s[0].total_impulse, s[1].total_impulse));
    assert_true(same_bits(s[0].friction_work, s[1].friction_work));
    assert_true(same_bits(s[0].peak_normal_force, s[1].peak_normal_force));
    assert_true(same_bits(s[0].stats.time_in_contact, s[1].stats.time_in_contact));
    assert_int_equal(s[0].stats.steps, s[1].stats.steps);
    assert_int_equal(s[0].events, s[1].events);
    for (k = 0; k < s[0].retainer_count; k++)
        assert_memory_equal(&s[0].retainers[k].totals, &s[1].retainers[k].totals, sizeof s[0].retainers[k].totals);
    free(s);
}

static void test_summary_ending(void **state)
{
    static const struct {
        double contact, rolling, angle, speed; /* over the stretch: s, s, rad; final speed rad/s */
        long contacts;
        const char *want;
        double f;
        td_regime regime; /* td_run_summary_regime: the same stretch, the same thresholds */
    } cases[] = {
        {0.0, 0.0, 0.0, 100.0, 0, "free (no contact)", TD_UNDEFINED, TD_REGIME_FREE}, /* no whirl */
        {0.0, 0.0, 0.0, 100.0, 3, "recovered", TD_UNDEFINED, TD_REGIME_FREE},
        {1.0, 0.9, 0.2, 100.0, 3, "rolling on the retainers", 0.2 / (2.0 * TD_PI), TD_REGIME_RUB},
        {1.0, 0.1, -0.2, 100.0, 3, "sliding on the retainers", -0.2 / (2.0 * TD_PI), TD_REGIME_RUB},
        {1.0, 0.9, -60.0, 100.0, 3, "backward whirl at -9.549 Hz, rolling", -60.0 / (2.0 * TD_PI),
         TD_REGIME_BACKWARD_WHIRL},
        {0.4, 0.0, 24.0, 100.0, 3, "forward rub at 9.549 Hz, sliding, bouncing", 60.0 / (2.0 * TD_PI),
         TD_REGIME_BOUNCE},
        {1.0, 0.9, -60.0, 0.5, 3, "at rest", TD_UNDEFINED, TD_REGIME_RUB},
        /* bouncing and creeping back 80 degrees while in contact: a bounce, not a whirl */
        {0.1, 0.0, -1.4, 100.0, 3, "sliding on the retainers, bouncing", -14.0 / (2.0 * TD_PI), TD_REGIME_BOUNCE},
        /* bouncing, but round the clearance one and a half times backward: a bouncing whirl */
        {0.4, 0.0, -3.0 * TD_PI, 100.0, 3, "backward whirl at -3.75 Hz, sliding, bouncing", -3.75,
         TD_REGIME_BACKWARD_WHIRL},
        /* in contact all along, a slow backward whirl of under a turn is still a whirl */
        {1.0, 0.9, -6.0, 100.0, 3, "backward whirl at -0.9549 Hz, rolling", -6.0 / (2.0 * TD_PI),
         TD_REGIME_BACKWARD_WHIRL},
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        td_run_summary s;
        td_retainer_totals before[2], after[2];
        memset(before, 0, sizeof before);
        memset(after, 0, sizeof after);
        memset(&s, 0, sizeof s);
        s.contacts = cases[i].contacts;
        s.ending_window = 1.0;
        before[1].contact_time = 5.0; /* retainer 1 carries the stretch */
        before[1].whirl_angle = 7.0;
        before[1].rolling_time = 2.0;
        after[1] = before[1];
        after[1].contact_time += cases[i].contact;
        after[1].rolling_time += cases[i].rolling;
        after[1].whirl_angle += cases[i].angle;
        after[0].contact_time = 0.1 * cases[i].contact; /* retainer 0 less */
        td_run_summary_ending(&s, before, after, 2, 100.0, cases[i].speed);
        assert_string_equal(s.ending, cases[i].want);
        if (td_is_undefined(cases[i].f))
            assert_true(td_is_undefined(s.ending_whirl_frequency));
        else
            assert_close(s.ending_whirl_frequency, cases[i].f, 1e-12, 0.0);
        s.status = TD_OK;
        assert_int_equal(td_run_summary_regime(&s), cases[i].regime);
        s.status = TD_ERR_SOLVER;
        assert_int_equal(td_run_summary_regime(&s), TD_REGIME_FAILED);
    }
    assert_string_equal(td_regime_name(TD_REGIME_BACKWARD_WHIRL), "backward whirl");
    assert_string_equal(td_regime_name(TD_REGIME_FAILED), "failed");
}

/* More warnings than a summary keeps: the first TD_RUN_MAX_WARNINGS - 1 as found, then a notice
 * counting the rest (ten schedule entries after the end: seven kept, three left out). With exactly
 * TD_RUN_MAX_WARNINGS all are kept. */
static void test_warnings_overflow(void **state)
{
    td_model *m = NULL;
    td_run_summary s;
    td_change c = {0};
    td_output_options out;
    char want[TD_RUN_WARNING_SIZE];
    int i, n;
    (void)state;
    td_output_options_default(&out);
    for (n = TD_RUN_MAX_WARNINGS; n <= TD_RUN_MAX_WARNINGS + 2; n += 2) {
        assert_int_equal(td_model_create(&m, NULL), TD_OK);
        for (i = 0; i < n; i++) {
            c.time = 2.0 + i;
            assert_int_equal(td_model_add_change(m, &c, NULL), TD_OK);
        }
        td_run_summary_init(&s, 0.0, 1.0, 0.0);
        td_run_check_warnings(&s, m, &out);
        assert_int_equal(s.warning_count, TD_RUN_MAX_WARNINGS);
        assert_int_equal(s.warnings_left_out, n > TD_RUN_MAX_WARNINGS ? n - (TD_RUN_MAX_WARNINGS - 1) : 0);
        for (i = 0; i < TD_RUN_MAX_WARNINGS - (s.warnings_left_out > 0); i++) {
            snprintf(want, sizeof want, "schedule[%d] at t = %d s", i, 2 + i);
            assert_non_null(strstr(s.warnings[i], want));
        }
        if (s.warnings_left_out > 0) {
            snprintf(want, sizeof want, "%d more warnings left out", n - (TD_RUN_MAX_WARNINGS - 1));
            assert_non_null(strstr(s.warnings[TD_RUN_MAX_WARNINGS - 1], want));
        }
        td_model_free(&m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_summary_text),
        cmocka_unit_test(test_warnings_overflow),
        cmocka_unit_test(test_run_bad_arguments),
        cmocka_unit_test(test_run_matches_hand_loop),
        cmocka_unit_test(test_run_cancel),
        cmocka_unit_test(test_summary_unstable_run),
        cmocka_unit_test(test_summary_failed_before_start),
        cmocka_unit_test(test_sim_accessors),
        cmocka_unit_test(test_json_string),
        cmocka_unit_test(test_summary_ending),
        cmocka_unit_test(test_section_steady_orbit),
        cmocka_unit_test(test_section_ends_at_end_time),
        cmocka_unit_test(test_section_changes_nothing),
        cmocka_unit_test(test_section_speed_ramp),
        cmocka_unit_test(test_section_matches_stepping),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
