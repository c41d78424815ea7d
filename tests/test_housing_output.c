/*
 * The housing motion's series in the run files (docs/output-format.md): the /housing series and
 * /nodes/absolute_displacement, read back through the result reader (touchdown/result.h) with their
 * shapes and units, against the closed forms of the prescribed motion: a half-sine shock of peak A
 * and duration T leaves the velocity 2 A T / pi and, being symmetric, a displacement growing from its
 * middle, 2 A T / pi (t - start - T / 2); a ramp of the rotation rate to w over d holds w, its angle
 * w d / 2 + w (t - start - d). The absolute displacement of node i is the relative one plus the
 * housing's displacement and its rotation's rigid field at z_i about z_ref: by a about x,
 * y - (z_i - z_ref) a; about y, x + (z_i - z_ref) a. A housing body (no base motion) writes the housing
 * fields too, with its own series /housing/body_displacement and /housing/body_tilt: its state as the
 * simulation gives it (td_sim_housing_body_state), and its rigid field in the absolute displacement.
 */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define A_SHOCK 50.0  /* m/s^2 */
#define T_SHOCK 0.01  /* s */
#define T0_SHOCK 0.02 /* s */
#define W_ROT 0.2     /* rad/s */
#define D_ROT 0.05    /* s */
#define T0_ROT 0.03   /* s */
#define Z_REF 0.25    /* m */
#define T_END 0.1     /* s */
#define BODY 2        /* rotor(): a housing body, no base motion */
#define M_BODY 30.0   /* kg */
#define Z_BODY 0.4    /* m */

static void tmp_name(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/housing_output_%ld_%s", TD_BINARY_DIR, (long)getpid(), name);
}

/* A Jeffcott rotor (nodes at z = 0, 0.5, 1 m) with a retainer at the disc; with `motion` a downward
 * half-sine shock and a rotation ramp about the axis (0.6, 0.8). */
static td_model *rotor(int motion)
{
    td_model *m = NULL;
    td_shaft_element el = {0.5, 0.05, 0.0, {2.11e11, 8.1e10, 1.0}};
    td_bearing b0 = {0, 1.0e6, 2.0e6, 2000.0, 2000.0}, b2 = {2, 1.0e6, 2.0e6, 2000.0, 2000.0};
    td_retainer r = {.node = 1, .clearance = 1e-3, .shaft_radius = 0.025, .bore_radius = 0.026, .friction = 0.1};
    td_housing_pulse shock = {TD_PULSE_HALF_SINE, A_SHOCK, T_SHOCK, T0_SHOCK, {0.0, -1.0}};
    td_housing_pulse turn = {TD_PULSE_RAMP, W_ROT, D_ROT, T0_ROT, {0.6, 0.8}};
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_point_mass(m, 1, 10.0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b2, NULL), TD_OK);
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    assert_int_equal(td_model_set_speed(m, 100.0, NULL), TD_OK);
    if (motion == BODY) { /* the body sags on its mounts under gravity from rest, and rocks */
        td_housing_body body = {.mass = M_BODY, .inertia = 0.4, .centre = Z_BODY, .mount_count = 2};
        body.mounts[0] = (td_housing_mount){0.0, 4.0e6, 400.0};
        body.mounts[1] = (td_housing_mount){1.0, 2.0e6, 200.0};
        assert_int_equal(td_model_set_housing_body(m, &body, NULL), TD_OK);
        assert_int_equal(td_model_set_gravity(m, 0.0, -9.81, NULL), TD_OK);
    } else if (motion) {
        assert_int_equal(td_model_add_housing_shock(m, &shock, NULL), TD_OK);
        assert_int_equal(td_model_add_housing_rotation(m, &turn, NULL), TD_OK);
        assert_int_equal(td_model_set_housing_reference(m, Z_REF, NULL), TD_OK);
    }
    return m;
}

/* Run rotor(motion) to T_END into h5 and csv; body_q (may be NULL) receives the housing body's state
 * at the end (td_sim_housing_body_state). */
static void run_to_files(int motion, const char *h5, const char *csv, double *body_q)
{
    td_model *m = rotor(motion);
    td_sim_options o;
    td_output_options out;
    td_run_summary s;
    td_sim *sim = NULL;
    td_error err;
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    td_output_options_default(&out);
    out.sample_rate = 1000.0;
    snprintf(out.hdf5_path, sizeof out.hdf5_path, "%s", h5);
    snprintf(out.csv_path, sizeof out.csv_path, "%s", csv);
    if (td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    if (td_run(sim, T_END, &out, NULL, NULL, &s, &err) != TD_OK)
        fail_msg("td_run: %s", err.message);
    if (body_q)
        assert_int_equal(td_sim_housing_body_state(sim, body_q, NULL), 1);
    td_sim_free(&sim);
    td_model_free(&m);
}

/* Dataset id as an (n, cols, depth) array with its units. */
static void read_shape(const td_result *r, td_out_id id, size_t n, size_t cols, size_t depth, const char *units,
                       td_result_array *a)
{
    assert_int_equal(td_result_read(r, id, NULL, a, NULL), TD_OK);
    assert_int_equal(a->dims[0], n);
    assert_int_equal(a->dims[1], cols);
    assert_int_equal(a->dims[2], depth);
    assert_string_equal(a->units, units);
}

/* The last sample of the housing's five series against their closed forms, and the samples in the
 * middle of the shock (t = start + T / 2: the peak). */
static void check_motion(const td_result *r, size_t n, const double *t)
{
    static const td_out_id ids[5] = {TD_OUT_HOUSING_ACCELERATION, TD_OUT_HOUSING_VELOCITY, TD_OUT_HOUSING_DISPLACEMENT,
                                     TD_OUT_HOUSING_ROTATION_RATE, TD_OUT_HOUSING_ROTATION_ANGLE};
    static const char *const units[5] = {"m/s^2", "m/s", "m", "rad/s", "rad"};
    double dv = 2.0 * A_SHOCK * T_SHOCK / TD_PI, angle = W_ROT * (0.5 * D_ROT + (T_END - T0_ROT - D_ROT));
    double want[5][2] = {{0.0, 0.0},
                         {0.0, -dv},
                         {0.0, -dv * (T_END - T0_SHOCK - 0.5 * T_SHOCK)},
                         {0.6 * W_ROT, 0.8 * W_ROT},
                         {0.6 * angle, 0.8 * angle}};
    size_t k, c, peak = 0;
    for (k = 0; k < n; k++)
        if (fabs(t[k] - (T0_SHOCK + 0.5 * T_SHOCK)) < 1e-12)
            peak = k;
    assert_true(peak > 0);
    for (k = 0; k < 5; k++) {
        td_result_array a;
        read_shape(r, ids[k], n, 2, 1, units[k], &a);
        for (c = 0; c < 2; c++)
            assert_close(a.v[2 * (n - 1) + c], want[k][c], 1e-12, 1e-15);
        if (k == 0)
            assert_close(a.v[2 * peak + 1], -A_SHOCK, 1e-12, 0.0);
        td_result_array_free(&a);
    }
}

/* /nodes/absolute_displacement - /nodes/displacement at the last sample: the housing's rigid motion. */
static void check_absolute(const td_result *r, size_t n)
{
    double angle = W_ROT * (0.5 * D_ROT + (T_END - T0_ROT - D_ROT));
    double y_h = -2.0 * A_SHOCK * T_SHOCK / TD_PI * (T_END - T0_SHOCK - 0.5 * T_SHOCK);
    td_result_array rel, abs_;
    int i;
    read_shape(r, TD_OUT_NODE_DISPLACEMENT, n, 3, 2, "m", &rel);
    read_shape(r, TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, n, 3, 2, "m", &abs_);
    for (i = 0; i < 3; i++) {
        double z = 0.5 * i, *a = abs_.v + 6 * (n - 1) + 2 * (size_t)i, *q = rel.v + 6 * (n - 1) + 2 * (size_t)i;
        assert_close(a[0] - q[0], (z - Z_REF) * 0.8 * angle, 1e-9, 1e-15);
        assert_close(a[1] - q[1], y_h - (z - Z_REF) * 0.6 * angle, 1e-9, 1e-15);
    }
    td_result_array_free(&rel);
    td_result_array_free(&abs_);
}

static void test_housing_series(void **state)
{
    char h5[512], csv[512], events[600], line[4096];
    td_result *r = NULL;
    td_result_array t;
    FILE *f;
    (void)state;
    tmp_name(h5, sizeof h5, "motion.h5");
    tmp_name(csv, sizeof csv, "motion.csv");
    run_to_files(1, h5, csv, NULL);
    assert_int_equal(td_result_open(h5, &r, NULL), TD_OK);
    assert_int_equal(td_result_read(r, TD_OUT_TIME, NULL, &t, NULL), TD_OK);
    check_motion(r, t.n, t.v);
    check_absolute(r, t.n);
    assert_false(td_result_has(r, TD_OUT_HOUSING_BODY_DISPLACEMENT, NULL)); /* written only with a body */
    assert_false(td_result_has(r, TD_OUT_HOUSING_BODY_TILT, NULL));
    td_result_array_free(&t);
    td_result_free(&r);
    /* the CSV's header: the housing's columns and the nodes' absolute displacement, last */
    assert_non_null(f = fopen(csv, "r"));
    assert_non_null(fgets(line, sizeof line, f));
    fclose(f);
    assert_non_null(strstr(line, ",ax_housing [m/s^2],ay_housing [m/s^2],vx_housing [m/s],"));
    assert_non_null(strstr(line, ",rotx_housing [rad],roty_housing [rad],x_abs_n0 [m],y_abs_n0 [m],"));
    assert_non_null(strstr(line, ",y_abs_n2 [m]\n"));
    td_writer_events_path(csv, events, sizeof events);
    remove(h5), remove(csv), remove(events);
}

/* A case without housing motion writes neither the group nor the absolute displacement. */
static void test_no_motion_no_series(void **state)
{
    char h5[512], csv[512], events[600], line[4096];
    td_result *r = NULL;
    FILE *f;
    (void)state;
    tmp_name(h5, sizeof h5, "still.h5");
    tmp_name(csv, sizeof csv, "still.csv");
    run_to_files(0, h5, csv, NULL);
    assert_int_equal(td_result_open(h5, &r, NULL), TD_OK);
    assert_false(td_result_has(r, TD_OUT_HOUSING, NULL));
    assert_false(td_result_has(r, TD_OUT_HOUSING_ACCELERATION, NULL));
    assert_false(td_result_has(r, TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, NULL));
    assert_true(td_result_has(r, TD_OUT_SUM_MIN_CLEARANCE_MARGIN, NULL)); /* every run has its margin */
    td_result_free(&r);
    assert_non_null(f = fopen(csv, "r"));
    assert_non_null(fgets(line, sizeof line, f));
    fclose(f);
    assert_null(strstr(line, "housing"));
    td_writer_events_path(csv, events, sizeof events);
    remove(h5), remove(csv), remove(events);
}

/* housing body: the last sample of /housing/body_displacement and /housing/body_tilt is the body's state
 * at the end (td_sim_housing_body_state); the prescribed motion's series are zero; at every sample the
 * absolute displacement is the relative one plus the body's rigid field at the node's z about its centre:
 * x + x_b + (z - z_b) phi_b, y + y_b - (z - z_b) theta_b. */
static void check_body(const td_result *r, size_t n, const double *q)
{
    td_result_array d, tilt, acc, rel, abs_;
    size_t k;
    int i;
    read_shape(r, TD_OUT_HOUSING_BODY_DISPLACEMENT, n, 2, 1, "m", &d);
    read_shape(r, TD_OUT_HOUSING_BODY_TILT, n, 2, 1, "rad", &tilt);
    read_shape(r, TD_OUT_HOUSING_ACCELERATION, n, 2, 1, "m/s^2", &acc);
    read_shape(r, TD_OUT_NODE_DISPLACEMENT, n, 3, 2, "m", &rel);
    read_shape(r, TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, n, 3, 2, "m", &abs_);
    assert_true(q[1] < -1e-6 && fabs(q[2]) > 1e-9); /* it sags and rocks: a test that can fail */
    for (i = 0; i < 2; i++) {
        assert_close(d.v[2 * (n - 1) + (size_t)i], q[i], 1e-12, 0.0);
        assert_close(tilt.v[2 * (n - 1) + (size_t)i], q[2 + i], 1e-12, 0.0);
    }
    for (k = 0; k < n; k++)
        for (i = 0; i < 3; i++) {
            double z = 0.5 * i, *a = abs_.v + 6 * k + 2 * (size_t)i, *p = rel.v + 6 * k + 2 * (size_t)i;
            const double *b = d.v + 2 * k, *th = tilt.v + 2 * k;
            assert_true(acc.v[2 * k] == 0.0 && acc.v[2 * k + 1] == 0.0);
            assert_close(a[0], p[0] + b[0] + (z - Z_BODY) * th[1], 1e-12, 1e-18);
            assert_close(a[1], p[1] + b[1] - (z - Z_BODY) * th[0], 1e-12, 1e-18);
        }
    td_result_array_free(&d);
    td_result_array_free(&tilt);
    td_result_array_free(&acc);
    td_result_array_free(&rel);
    td_result_array_free(&abs_);
}

/* A housing body without base motion writes the housing fields, its own series among them. */
static void test_body_series(void **state)
{
    char h5[512], csv[512], events[600], line[4096];
    double q[4];
    td_result *r = NULL;
    td_result_array t;
    FILE *f;
    (void)state;
    tmp_name(h5, sizeof h5, "body.h5");
    tmp_name(csv, sizeof csv, "body.csv");
    run_to_files(BODY, h5, csv, q);
    assert_int_equal(td_result_open(h5, &r, NULL), TD_OK);
    assert_int_equal(td_result_read(r, TD_OUT_TIME, NULL, &t, NULL), TD_OK);
    check_body(r, t.n, q);
    td_result_array_free(&t);
    td_result_free(&r);
    assert_non_null(f = fopen(csv, "r"));
    assert_non_null(fgets(line, sizeof line, f));
    fclose(f);
    assert_non_null(strstr(line, ",rotx_housing [rad],roty_housing [rad],x_housing_body [m],y_housing_body [m],"
                                 "tiltx_housing_body [rad],tilty_housing_body [rad],x_abs_n0 [m],"));
    td_writer_events_path(csv, events, sizeof events);
    remove(h5), remove(csv), remove(events);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_housing_series),
        cmocka_unit_test(test_no_motion_no_series),
        cmocka_unit_test(test_body_series),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
