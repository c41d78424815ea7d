/*
 * Fixture files for the `touchdown plot` tests (tests/cli/test_plot.sh), written through the
 * public td_writer API, and a check that the HDF5 layout `touchdown plot` reads
 * (docs/output-format.md: /time, /retainers/<field> [samples, retainers], /ambs/force,
 * the /events enum, the root attributes retainer_clearance, retainer_nodes, amb_nodes,
 * case_text, complete) is what the writer produces.
 *
 * The samples are synthetic, not a simulation: a circular whirl at 90 rad/s whose free radius
 * grows past the 0.75 mm clearance after an unbalance step at 0.1 s and decays after a second
 * step at 0.35 s; while the free radius exceeds the clearance the shaft sits on the clearance
 * circle and a normal force proportional to the excess acts. Two variants ("constraint" and
 * "penalty", the second with half the force and a small penetration) and an incomplete file.
 *
 * Files go to $TD_PLOT_FIXTURE_DIR if set, else to the build directory's tests/ folder:
 * plot-fixture-constraint.h5, plot-fixture-penalty.h5, plot-fixture-incomplete.h5,
 * plot-fixture-leap.h5 (two leaps, see write_leaps) and plot-fixture-foreign.h5 (an HDF5 file that
 * is not a touchdown result).
 */
#include "td_test.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "touchdown/output.h"

#define OMEGA 90.0        /* rad/s */
#define CLEARANCE 0.75e-3 /* m */
#define RATE 2000.0       /* Hz */
#define T_END 0.6         /* s */
#define STEP_UP 0.1       /* s */
#define STEP_DOWN 0.35    /* s */
#define K_CONTACT 4.0e6   /* N/m, force per metre of free radius beyond the clearance */
#define K_AMB 1.0e6       /* N/m */

static const char *fixture_path(const char *name)
{
    static char buf[1024];
    const char *dir = getenv("TD_PLOT_FIXTURE_DIR");
    if (!dir || !*dir) {
        mkdir(TD_BINARY_DIR "/tests", 0755);
        dir = TD_BINARY_DIR "/tests";
    }
    snprintf(buf, sizeof buf, "%s/%s", dir, name);
    return buf;
}

/* Free whirl radius (m): 0.3 mm, growing towards 0.9 mm after the step up with a 3x ripple that
 * makes the contact intermittent, relaxing back after the step down. */
static double free_radius(double t)
{
    double a = 0.3e-3;
    if (t >= STEP_UP) {
        double grow = 1.0 - exp(-(t - STEP_UP) / 0.03);
        if (t >= STEP_DOWN)
            grow *= exp(-(t - STEP_DOWN) / 0.02);
        a += grow * (0.6e-3 + 0.12e-3 * sin(3.0 * OMEGA * t));
    }
    return a;
}

typedef struct variant {
    const char *name;
    const char *model;
    double force_scale; /* penalty: smaller forces */
    double penetration; /* m per N beyond the clearance (1 / Kc), 0: rigid */
    double t_stop;      /* last sample time */
    int complete;
} variant;

/* Retainer state of the synthetic orbit at time t for a free radius `a` scaled by `scale`. */
static void retainer_at(double t, double scale, const variant *v, td_retainer_state *s)
{
    double a = scale * free_radius(t), r = a, fn = 0.0;
    memset(s, 0, sizeof *s);
    if (a > CLEARANCE) {
        fn = v->force_scale * K_CONTACT * (a - CLEARANCE);
        r = CLEARANCE + v->penetration * fn;
        s->in_contact = 1;
    }
    s->radius = r;
    s->x = r * cos(OMEGA * t);
    s->y = r * sin(OMEGA * t);
    s->whirl_angle = atan2(s->y, s->x);
    s->normal_force = fn;
    s->friction_force = 0.1 * fn;
}

static void write_event(td_writer *w, td_event_kind kind, double t, int retainer, double fn)
{
    td_event ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = kind;
    ev.time = t;
    ev.retainer = retainer;
    ev.change = kind == TD_EVENT_SCHEDULE ? (t > STEP_UP + 1e-9 ? 1 : 0) : -1;
    ev.normal_force = fn;
    assert_int_equal(td_writer_event(w, &ev, td_writer_sample_count(w) - 1, NULL), TD_OK);
}

static void write_variant(const variant *v)
{
    const long ret_nodes[2] = {2, 10}, amb_nodes[2] = {3, 9};
    const double clearance[2] = {CLEARANCE, CLEARANCE};
    const td_event_kind onset = v->penetration > 0.0 ? TD_EVENT_PENALTY_ENTER : TD_EVENT_CONTACT_ONSET;
    const td_event_kind release = v->penetration > 0.0 ? TD_EVENT_PENALTY_EXIT : TD_EVENT_RELEASE;
    char text[512];
    td_output_layout layout;
    td_writer *w = NULL;
    int was_in = 0, up_done = 0, down_done = 0;
    long k, n = (long)floor(v->t_stop * RATE + 0.5);
    memset(&layout, 0, sizeof layout); /* every field the writer reads, including those set below */
    layout.node_count = 0;
    layout.nodes = NULL;
    layout.retainer_count = 2;
    layout.amb_count = 2;
    layout.compression = 0;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, fixture_path(v->name), &layout, &w, NULL), TD_OK);
    for (k = 0; k <= n; k++) {
        double t = (double)k / RATE, amb[4];
        td_retainer_state ret[2];
        retainer_at(t, 1.0, v, &ret[0]);
        retainer_at(t, 0.4, v, &ret[1]);
        amb[0] = -K_AMB * 1.2 * ret[0].x, amb[1] = -K_AMB * 1.2 * ret[0].y;
        amb[2] = -K_AMB * 0.8 * ret[1].x, amb[3] = -K_AMB * 0.8 * ret[1].y;
        assert_int_equal(td_writer_sample(w, t, 0.0, NULL, ret, amb, NULL), TD_OK);
        if (!up_done && t >= STEP_UP) {
            write_event(w, TD_EVENT_SCHEDULE, STEP_UP, -1, 0.0);
            up_done = 1;
        }
        if (!down_done && t >= STEP_DOWN) {
            write_event(w, TD_EVENT_SCHEDULE, STEP_DOWN, -1, 0.0);
            down_done = 1;
        }
        if (ret[0].in_contact != was_in)
            write_event(w, ret[0].in_contact ? onset : release, t, 0, ret[0].normal_force);
        was_in = ret[0].in_contact;
    }
    snprintf(text, sizeof text,
             "# synthetic fixture for touchdown plot\n"
             "description = \"Plot fixture: synthetic whirl at 90 rad/s, %s contact\";\n"
             "speed = 90.0;\ncontact = { model = \"%s\"; };\nend_time = %.3f;\n",
             v->model, v->model, T_END);
    assert_int_equal(td_writer_set_string(w, "case_text", text, NULL), TD_OK);
    assert_int_equal(td_writer_set_double(w, "sample_rate", RATE, NULL), TD_OK);
    assert_int_equal(td_writer_set_double(w, "speed", OMEGA, NULL), TD_OK);
    assert_int_equal(td_writer_set_longs(w, "retainer_nodes", ret_nodes, 2, NULL), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, "retainer_clearance", clearance, 2, NULL), TD_OK);
    assert_int_equal(td_writer_set_longs(w, "amb_nodes", amb_nodes, 2, NULL), TD_OK);
    assert_int_equal(td_writer_close(&w, v->complete, v->complete ? NULL : "solver failure at t = 0.25 s", NULL),
                     TD_OK);
}

/* ---- the layout touchdown plot reads ------------------------------------------------------- */

static hsize_t dataset_dims(hid_t f, const char *path, hsize_t *dims)
{
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT), s;
    int rank;
    assert_true(d >= 0);
    s = H5Dget_space(d);
    rank = H5Sget_simple_extent_ndims(s);
    H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    H5Dclose(d);
    return (hsize_t)rank;
}

static void check_layout(const char *path, long samples)
{
    static const char *fields[] = {"/retainers/x", "/retainers/y", "/retainers/radial_position",
                                   "/retainers/normal_force", "/retainers/contact_state"};
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT), a, d, t, kt;
    hsize_t dims[3];
    double clr[2];
    int complete = -1, idx, v = (int)TD_EVENT_RELEASE;
    char name[64];
    size_t i;
    assert_true(f >= 0);
    assert_int_equal(dataset_dims(f, "/time", dims), 1);
    assert_int_equal((long)dims[0], samples);
    for (i = 0; i < sizeof fields / sizeof fields[0]; i++) {
        assert_int_equal(dataset_dims(f, fields[i], dims), 2);
        assert_int_equal((long)dims[0], samples);
        assert_int_equal((int)dims[1], 2);
    }
    assert_int_equal(dataset_dims(f, "/ambs/force", dims), 3);
    assert_int_equal((int)dims[1], 2);
    assert_int_equal((int)dims[2], 2);
    a = H5Aopen(f, "retainer_clearance", H5P_DEFAULT);
    assert_true(a >= 0);
    assert_true(H5Aread(a, H5T_NATIVE_DOUBLE, clr) >= 0);
    H5Aclose(a);
    assert_close(clr[0], CLEARANCE, 0.0, 0.0);
    a = H5Aopen(f, "complete", H5P_DEFAULT);
    assert_true(a >= 0 && H5Aread(a, H5T_NATIVE_INT, &complete) >= 0);
    H5Aclose(a);
    assert_int_equal(complete, 1);
    assert_true(H5Aexists(f, "case_text") > 0 && H5Aexists(f, "retainer_nodes") > 0 && H5Aexists(f, "amb_nodes") > 0);
    /* the event kind is an enum whose names the plot tool matches */
    d = H5Dopen2(f, "/events", H5P_DEFAULT);
    assert_true(d >= 0);
    t = H5Dget_type(d);
    idx = H5Tget_member_index(t, "kind");
    assert_true(idx >= 0);
    kt = H5Tget_member_type(t, (unsigned)idx);
    assert_int_equal(H5Tget_class(kt), H5T_ENUM);
    assert_true(H5Tenum_nameof(kt, &v, name, sizeof name) >= 0);
    assert_string_equal(name, "release");
    v = (int)TD_EVENT_SCHEDULE;
    assert_true(H5Tenum_nameof(kt, &v, name, sizeof name) >= 0);
    assert_string_equal(name, "schedule");
    H5Tclose(kt);
    H5Tclose(t);
    H5Dclose(d);
    H5Fclose(f);
}

/* projective leap: the whirl of the constraint variant (free radius 0.3 mm, no contact) with two
 * leaps, as a run that leaps writes them: rows every 1/RATE from 0 to 0.05 s, where an event's
 * row and the grid's row share the time (the event at the grid's instant), the first leap's start;
 * a gap to 0.25 s; rows to 0.3 s, the second leap's start (a grid row alone); a gap to 0.45 s; rows
 * to 0.5 s. The root attributes leap_time and leap_length list the two (docs/output-format.md,
 * "Leaps in the files"). */
static void write_leaps(void)
{
    static const double starts[2] = {0.05, 0.3}, lengths[2] = {0.2, 0.15};
    static const variant v = {"plot-fixture-leap.h5", "constraint", 1.0, 0.0, 0.5, 1};
    const double clearance[2] = {CLEARANCE, CLEARANCE};
    td_output_layout layout;
    td_writer *w = NULL;
    long k, n = (long)floor(v.t_stop * RATE + 0.5);
    memset(&layout, 0, sizeof layout);
    layout.retainer_count = 2;
    layout.amb_count = 2;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, fixture_path(v.name), &layout, &w, NULL), TD_OK);
    for (k = 0; k <= n; k++) {
        double t = (double)k / RATE, amb[4] = {0.0, 0.0, 0.0, 0.0};
        td_retainer_state ret[2];
        if ((t > starts[0] && t < starts[0] + lengths[0]) || (t > starts[1] && t < starts[1] + lengths[1]))
            continue; /* leapt: no row */
        retainer_at(t, 1.0, &v, &ret[0]);
        retainer_at(t, 0.4, &v, &ret[1]);
        if (t == starts[0]) { /* the event's row, then the grid's at the same time */
            assert_int_equal(td_writer_sample(w, t, 0.0, NULL, ret, amb, NULL), TD_OK);
            write_event(w, TD_EVENT_SCHEDULE, t, -1, 0.0);
        }
        assert_int_equal(td_writer_sample(w, t, 0.0, NULL, ret, amb, NULL), TD_OK);
    }
    assert_int_equal(td_writer_set_string(w, "case_text", "description = \"Plot fixture: two leaps\";\n", NULL), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, "retainer_clearance", clearance, 2, NULL), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, "leap_time", starts, 2, NULL), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, "leap_length", lengths, 2, NULL), TD_OK);
    assert_int_equal(td_writer_close(&w, 1, NULL, NULL), TD_OK);
}

/* An HDF5 file that is not a touchdown result (for the "not a touchdown file" error). */
static void write_foreign(void)
{
    hsize_t dims[1] = {3};
    double v[3] = {1.0, 2.0, 3.0};
    hid_t f = H5Fcreate(fixture_path("plot-fixture-foreign.h5"), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t s = H5Screate_simple(1, dims, NULL), d;
    assert_true(f >= 0 && s >= 0);
    d = H5Dcreate2(f, "temperature", H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(d >= 0);
    assert_true(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(d);
    H5Sclose(s);
    assert_true(H5Fclose(f) >= 0);
}

static void test_write_fixtures(void **state)
{
    static const variant variants[3] = {
        {"plot-fixture-constraint.h5", "constraint", 1.0, 0.0, T_END, 1},
        {"plot-fixture-penalty.h5", "penalty", 0.5, 1.0 / 1.25e9, T_END, 1},
        {"plot-fixture-incomplete.h5", "constraint", 1.0, 0.0, 0.25, 0},
    };
    long samples = (long)floor(T_END * RATE + 0.5) + 1;
    int i;
    (void)state;
    for (i = 0; i < 3; i++)
        write_variant(&variants[i]);
    check_layout(fixture_path(variants[0].name), samples);
    write_leaps();
    write_foreign();
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_write_fixtures)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
