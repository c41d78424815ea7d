/*
 * The housing's prescribed motion (touchdown/housing.h): each pulse's exact integrals against their
 * closed forms written out here and against numerical quadrature of the pulse itself; the
 * history's exact integrals against hand values and quadrature; the kinks; each rule's error (part,
 * index, field); a CSV history's fault located in the CSV file; and the system's base loads against
 * the rotor's mass and polar inertia (full and reduced).
 */
#include "td_test.h"

#include "model/system_internal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static td_model *shaft_model(void)
{
    td_model *m = NULL;
    td_shaft_element el = {0.1, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_disc d = {3, 12.0, 0.09, 0.05};
    int i;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    for (i = 0; i < 8; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &d, NULL), TD_OK);
    return m;
}

static td_housing_pulse pulse(td_pulse_shape shape, double amplitude, double duration, double start, double dx,
                              double dy)
{
    td_housing_pulse p;
    memset(&p, 0, sizeof p);
    p.shape = shape, p.amplitude = amplitude, p.duration = duration, p.start = start;
    p.direction[0] = dx, p.direction[1] = dy;
    return p;
}

/* The pulses' closed forms as the shock standards write them (unit amplitude), and their
 * integrals from the start, written out independently of lib/model/housing.c: at tau in [0, T]. */
static void closed_form(td_pulse_shape shape, double T, double tau, double out[3])
{
    double w = TD_PI / T, h = 0.5 * T;
    switch (shape) {
    case TD_PULSE_HALF_SINE:
        out[0] = sin(w * tau), out[1] = (1.0 - cos(w * tau)) / w, out[2] = tau / w - sin(w * tau) / (w * w);
        return;
    case TD_PULSE_TRIANGLE:
        if (tau <= h) {
            out[0] = tau / h, out[1] = tau * tau / (2.0 * h), out[2] = tau * tau * tau / (6.0 * h);
        } else { /* by symmetry: the rise's integrals at h plus the fall's */
            double s = tau - h;
            out[0] = 1.0 - s / h, out[1] = h / 2.0 + s - s * s / (2.0 * h);
            out[2] = h * h / 6.0 + h / 2.0 * s + s * s / 2.0 - s * s * s / (6.0 * h);
        }
        return;
    case TD_PULSE_VERSINE:
        w = 2.0 * TD_PI / T;
        out[0] = 0.5 * (1.0 - cos(w * tau)), out[1] = 0.5 * (tau - sin(w * tau) / w);
        out[2] = 0.5 * (tau * tau / 2.0 - (1.0 - cos(w * tau)) / (w * w));
        return;
    case TD_PULSE_SAWTOOTH:
    case TD_PULSE_RAMP: out[0] = tau / T, out[1] = tau * tau / (2.0 * T), out[2] = tau * tau * tau / (6.0 * T); return;
    }
}

/* The pulse's value at t (amplitude A), its velocity and displacement from its own closed forms:
 * after the end the velocity is held (for the ramp the acceleration too) and the displacement grows
 * linearly (quadratically for the ramp). */
static void expected(td_pulse_shape shape, double A, double T, double t0, double t, double out[3])
{
    double tau = t - t0, end[3];
    int k;
    if (tau < 0.0) {
        out[0] = out[1] = out[2] = 0.0;
        return;
    }
    if (t < t0 + T) { /* the pulse's end as the model compares it: at the end, the value after it */
        closed_form(shape, T, tau, out);
    } else {
        double s = tau - T;
        closed_form(shape, T, T, end);
        out[0] = shape == TD_PULSE_RAMP ? 1.0 : 0.0;
        out[1] = end[1] + out[0] * s;
        out[2] = end[2] + end[1] * s + 0.5 * out[0] * s * s;
    }
    for (k = 0; k < 3; k++)
        out[k] *= A;
}

static void test_pulse_closed_forms(void **state)
{
    static const double fractions[] = {-0.5, 0.0, 1e-6, 0.013, 0.25, 0.5, 0.61, 0.999, 1.0, 1.7, 40.0};
    int shape;
    size_t k;
    (void)state;
    for (shape = TD_PULSE_HALF_SINE; shape <= TD_PULSE_RAMP; shape++) {
        td_model *m = shaft_model();
        td_housing_pulse p = pulse((td_pulse_shape)shape, 490.0, 0.011, 0.05, 0.0, -2.0);
        assert_int_equal(td_model_add_housing_shock(m, &p, NULL), TD_OK);
        for (k = 0; k < sizeof fractions / sizeof fractions[0]; k++) {
            double t = 0.05 + fractions[k] * 0.011, e[3];
            td_housing_motion hm;
            td_model_housing_motion_at(m, t, &hm);
            expected((td_pulse_shape)shape, 490.0, 0.011, 0.05, t, e);
            /* along the normalised direction [0, -1] */
            assert_close(hm.acceleration[1], -e[0], 1e-12, 1e-12 * 490.0);
            assert_close(hm.velocity[1], -e[1], 1e-12, 1e-15);
            /* the displacement near the start to its relative precision (the closed forms above
             * cancel there; lib/model/housing.c uses series) */
            assert_close(hm.displacement[1], -e[2], fractions[k] < 0.01 ? 1e-6 : 1e-12, 1e-18);
            assert_close(hm.acceleration[0], 0.0, 0.0, 0.0);
            assert_close(hm.rate[0] + hm.rate[1] + hm.angle[0] + hm.angle[1], 0.0, 0.0, 0.0);
        }
        td_model_free(&m);
    }
}

/* Near the start the displacement is A T^2/pi^2 (x - sin x) with x = pi tau/T: its leading term
 * A pi tau^3 / (6 T) to the series' precision, where x - sin x computed directly cancels. */
static void test_pulse_start_precision(void **state)
{
    td_model *m = shaft_model();
    td_housing_pulse p = pulse(TD_PULSE_HALF_SINE, 1.0, 1.0, 0.0, 1.0, 0.0);
    td_housing_motion hm;
    double tau = 1e-5, x = TD_PI * tau;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &p, NULL), TD_OK);
    td_model_housing_motion_at(m, tau, &hm);
    assert_close(hm.displacement[0], (x * x * x / 6.0 - x * x * x * x * x / 120.0) / (TD_PI * TD_PI), 1e-14, 0.0);
    td_model_free(&m);
}

/* Composite 3-point Gauss-Legendre quadrature over [a, b] in n pieces of the motion's acceleration
 * (which 0), velocity (1) or rate about y (2): its nodes lie inside the pieces, so a jump at a or b
 * (a sawtooth's end) is seen from the inside. */
static double quadrature(const td_model *m, int which, double a, double b, int n)
{
    static const double x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double h = (b - a) / n, sum = 0.0;
    int i, k;
    for (i = 0; i < n; i++)
        for (k = 0; k < 3; k++) {
            td_housing_motion hm;
            td_model_housing_motion_at(m, a + h * (i + 0.5 + 0.5 * x[k]), &hm);
            sum += w[k] * 0.5 * h * (which == 0 ? hm.acceleration[0] : which == 1 ? hm.velocity[0] : hm.rate[1]);
        }
    return sum;
}

/* The integrals against quadrature of the evaluated acceleration (velocity) and velocity
 * (displacement), piece by piece between the kinks, for two pulses and a rotation summed. */
static void test_pulse_quadrature(void **state)
{
    td_model *m = shaft_model();
    td_housing_pulse a = pulse(TD_PULSE_TRIANGLE, 100.0, 0.02, 0.01, 1.0, 0.0);
    td_housing_pulse b = pulse(TD_PULSE_VERSINE, 50.0, 0.006, 0.015, 1.0, 0.0);
    td_housing_pulse c = pulse(TD_PULSE_SAWTOOTH, 30.0, 0.05, 0.02, 1.0, 0.0);
    td_housing_pulse r = pulse(TD_PULSE_RAMP, 0.3, 0.05, 0.02, 0.0, 1.0);
    double kinks[16], v = 0.0, d = 0.0, ang = 0.0, t = 0.0;
    int n = 0, i;
    td_housing_motion hm;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &a, NULL), TD_OK);
    assert_int_equal(td_model_add_housing_shock(m, &b, NULL), TD_OK);
    assert_int_equal(td_model_add_housing_shock(m, &c, NULL), TD_OK);
    assert_int_equal(td_model_add_housing_rotation(m, &r, NULL), TD_OK);
    while (n < 16 && isfinite(kinks[n] = td_model_housing_next_kink(m, n ? kinks[n - 1] : 0.0)))
        n++;
    /* starts, the triangle's peak, ends: 0.01, 0.015, 0.02 (all), 0.021, 0.03, 0.07 */
    assert_int_equal(n, 6);
    assert_close(kinks[0], 0.01, 0.0, 0.0);
    assert_close(kinks[2], 0.02, 0.0, 0.0);
    assert_close(kinks[5], 0.07, 0.0, 0.0);
    kinks[n++] = 0.1;
    /* v, d and the angle as quadratures of the evaluated a, v and rate */
    for (i = 0; i < n; i++) {
        v += quadrature(m, 0, t, kinks[i], 4000);
        d += quadrature(m, 1, t, kinks[i], 4000);
        ang += quadrature(m, 2, t, kinks[i], 4000);
        t = kinks[i];
    }
    td_model_housing_motion_at(m, 0.1, &hm);
    assert_close(hm.velocity[0], v, 1e-11, 0.0);
    assert_close(hm.displacement[0], d, 1e-11, 0.0);
    assert_close(hm.angle[1], ang, 1e-11, 0.0);
    assert_close(hm.acceleration[0], 0.0, 0.0, 0.0); /* the sawtooth has dropped */
    assert_close(hm.rate[1], 0.3, 0.0, 0.0);         /* the ramp holds */
    td_model_free(&m);
}

/* The rate change is the rate's slope (the slope after a kink, at the kink). */
static void test_rate_change(void **state)
{
    int shape;
    (void)state;
    for (shape = TD_PULSE_HALF_SINE; shape <= TD_PULSE_RAMP; shape++) {
        td_model *m = shaft_model();
        td_housing_pulse p = pulse((td_pulse_shape)shape, 0.2, 0.4, 0.1, 1.0, 1.0);
        double t, h = 1e-6;
        if (shape == TD_PULSE_SAWTOOTH) { /* refused as a rotation: test_rules */
            td_model_free(&m);
            continue;
        }
        assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
        for (t = 0.11; t < 0.5; t += 0.037) {
            td_housing_motion a, b, c;
            td_model_housing_motion_at(m, t - h, &a);
            td_model_housing_motion_at(m, t, &b);
            td_model_housing_motion_at(m, t + h, &c);
            assert_close(b.rate_change[0], (c.rate[0] - a.rate[0]) / (2.0 * h), 1e-6, 1e-9);
            assert_close(b.rate[0], b.rate[1], 0.0, 0.0); /* axis [1, 1] normalised */
        }
        td_model_free(&m);
    }
}

/* A piecewise-linear record: zero before its first time and after its last, its integrals exact per
 * segment (hand values of a trapezoid: 0 -> 10 m/s^2 over 0.01 s, held 0.01 s, back to 0 over 0.01 s),
 * shifted by its start. */
static void test_history(void **state)
{
    td_model *m = shaft_model();
    const double t[] = {0.02, 0.03, 0.04, 0.05}, ax[] = {0.0, 10.0, 10.0, 0.0}, ay[] = {0.0, -4.0, 0.0, 0.0};
    td_housing_motion hm;
    (void)state;
    assert_int_equal(td_model_set_housing_history(m, 4, t, ax, ay, NULL), TD_OK);
    assert_true(td_model_has_housing_motion(m));
    assert_int_equal(td_model_housing_history_count(m), 4);
    td_model_housing_motion_at(m, 0.01, &hm);
    assert_close(hm.acceleration[0] + hm.velocity[0] + hm.displacement[0], 0.0, 0.0, 0.0);
    td_model_housing_motion_at(m, 0.025, &hm); /* a = 1000 s', v = 500 s'^2, d = 500/3 s'^3, s' = 5 ms */
    assert_close(hm.acceleration[0], 5.0, 1e-14, 0.0);
    assert_close(hm.velocity[0], 500.0 * 25e-6, 1e-14, 0.0);
    assert_close(hm.displacement[0], 500.0 / 3.0 * 125e-9, 1e-13, 0.0);
    td_model_housing_motion_at(m, 0.035, &hm); /* held at 10 m/s^2 from v = 0.05 m/s, d = 500/3 (0.01)^3 m */
    assert_close(hm.velocity[0], 0.05 + 10.0 * 0.005, 1e-14, 0.0);
    assert_close(hm.displacement[0], 500.0 / 3.0 * 1e-6 + 0.05 * 0.005 + 5.0 * 0.005 * 0.005, 1e-13, 0.0);
    td_model_housing_motion_at(m, 0.1, &hm); /* after: v held at the area 0.2 m/s, d grows linearly */
    assert_close(hm.acceleration[0], 0.0, 0.0, 0.0);
    assert_close(hm.velocity[0], 0.2, 1e-14, 0.0);
    /* d at the end: the area 0.2 m/s times the distance from its centroid (0.035 s), then 0.2 m/s on */
    assert_close(hm.displacement[0], 0.2 * (0.05 - 0.035) + 0.2 * 0.05, 1e-13, 0.0);
    /* y: a triangle of area -0.04 m/s over [0.02, 0.04] */
    assert_close(hm.velocity[1], -0.04, 1e-14, 0.0);
    assert_close(hm.displacement[1], -0.04 * (0.1 - 0.03), 1e-13, 0.0);
    /* the ends are the kinks, the inner points are not */
    assert_close(td_model_housing_next_kink(m, 0.0), 0.02, 0.0, 0.0);
    assert_close(td_model_housing_next_kink(m, 0.02), 0.05, 0.0, 0.0);
    assert_true(isinf(td_model_housing_next_kink(m, 0.05)));
    td_model_free(&m);
}

/* Each rule once, naming the part, the index and the field. */
static void expect_fault(td_status st, const td_error *err, const char *part, int index, const char *field)
{
    assert_int_equal(st, TD_ERR_INVALID);
    assert_non_null(err->site.part);
    assert_string_equal(err->site.part, part);
    assert_int_equal(err->site.index, index);
    assert_string_equal(err->site.field, field);
}

static void test_rules(void **state)
{
    td_model *m = shaft_model();
    td_housing_pulse ok = pulse(TD_PULSE_VERSINE, 1.0, 0.01, 0.0, 3.0, 4.0), p;
    const double t[] = {0.0, 0.01, 0.01}, bad_t[] = {-0.01, 0.0, 0.01}, a[] = {0.0, 1.0, 0.0},
                 nan_a[] = {0.0, NAN, 0.0};
    td_error err;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &ok, &err), TD_OK);
    assert_int_equal(td_model_get_housing_shock(m, 0, &p), TD_OK);
    assert_close(p.direction[0], 0.6, 1e-15, 0.0); /* normalised */
    assert_close(p.direction[1], 0.8, 1e-15, 0.0);
    p = ok, p.amplitude = 0.0;
    expect_fault(td_model_add_housing_shock(m, &p, &err), &err, "shock", 1, "amplitude");
    p = ok, p.duration = INFINITY;
    expect_fault(td_model_add_housing_shock(m, &p, &err), &err, "shock", 1, "duration");
    p = ok, p.start = -1e-3;
    expect_fault(td_model_add_housing_rotation(m, &p, &err), &err, "rotation", 0, "start");
    p = ok, p.direction[0] = p.direction[1] = 0.0;
    expect_fault(td_model_add_housing_rotation(m, &p, &err), &err, "rotation", 0, "direction");
    p = ok, p.direction[1] = NAN;
    expect_fault(td_model_add_housing_rotation(m, &p, &err), &err, "rotation", 0, "direction");
    p = ok, p.shape = (td_pulse_shape)7;
    expect_fault(td_model_add_housing_shock(m, &p, &err), &err, "shock", 1, "shape");
    /* a rate that drops at once is an angular impulse the loads cannot apply; an acceleration's drop is a step */
    p = ok, p.shape = TD_PULSE_SAWTOOTH;
    expect_fault(td_model_add_housing_rotation(m, &p, &err), &err, "rotation", 0, "shape");
    assert_non_null(strstr(err.message, "angular impulse: use triangle or versine"));
    assert_int_equal(td_model_add_housing_shock(m, &p, &err), TD_OK);
    p = ok, p.direction[0] = 1e308, p.direction[1] = 1e308; /* no overflow in the norm */
    assert_int_equal(td_model_add_housing_rotation(m, &p, &err), TD_OK);
    expect_fault(td_model_set_housing_history(m, 3, t, a, a, &err), &err, "history", 2, "time");
    expect_fault(td_model_set_housing_history(m, 3, bad_t, a, a, &err), &err, "history", 0, "time");
    expect_fault(td_model_set_housing_history(m, 2, t, nan_a, a, &err), &err, "history", 1, "x");
    expect_fault(td_model_set_housing_history(m, 2, t, a, nan_a, &err), &err, "history", 1, "y");
    expect_fault(td_model_set_housing_history(m, 1, t, a, a, &err), &err, "history", -1, "time");
    expect_fault(td_model_set_housing_reference(m, NAN, &err), &err, "housing", 0, "reference");
    assert_int_equal(td_model_housing_history_count(m), 0); /* nothing set by a refused call */
    assert_int_equal(td_model_housing_shock_count(m), 2);
    assert_int_equal(td_model_housing_rotation_count(m), 1);
    td_model_free(&m);
}

/* A copy and a refined copy keep the motion and the reference point (the default: the centre of
 * mass, which refining keeps). */
static void test_clone_and_refine(void **state)
{
    td_model *m = shaft_model(), *c = NULL, *r = NULL;
    td_housing_pulse p = pulse(TD_PULSE_HALF_SINE, 20.0, 0.01, 0.0, 1.0, 0.0);
    const double t[] = {0.0, 0.01}, a[] = {0.0, 1.0};
    td_housing_motion hm, hc;
    (void)state;
    assert_int_equal(td_model_add_housing_shock(m, &p, NULL), TD_OK);
    assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
    assert_int_equal(td_model_set_housing_history(m, 2, t, a, a, NULL), TD_OK);
    assert_int_equal(td_model_clone(m, &c, NULL), TD_OK);
    assert_int_equal(td_model_refine(m, 3, &r, NULL), TD_OK);
    td_model_housing_motion_at(m, 0.007, &hm);
    td_model_housing_motion_at(c, 0.007, &hc);
    assert_memory_equal(&hm, &hc, sizeof hm);
    td_model_housing_motion_at(r, 0.007, &hc);
    assert_memory_equal(&hm, &hc, sizeof hm);
    assert_close(td_model_housing_reference(m), td_model_mass_centre(m), 0.0, 0.0);
    assert_close(td_model_housing_reference(r), td_model_housing_reference(m), 1e-14, 0.0);
    assert_int_equal(td_model_set_housing_reference(m, 0.1, NULL), TD_OK);
    assert_close(td_model_housing_reference(m), 0.1, 0.0, 0.0);
    td_model_free(&c);
    td_model_free(&r);
    td_model_free(&m);
}

/* A CSV history's fault names the case's line and key and the CSV file's line and column. */
static void test_csv_fault_located(void **state)
{
    td_case *c = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/housing-csv-number.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "housing-csv-number.cfg:5: housing.history.file: "));
    assert_non_null(strstr(err.message, "housing-csv-number.csv:4: column 3 'ay [g]': 'two'"));
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/housing-csv-unit.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_non_null(
        strstr(err.message, "housing-csv-unit.csv:1: column 3 'ay [furlong/fortnight^2]': an unknown unit"));
    /* the header's names are required: a name that is no quantity, a quantity named twice */
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/housing-csv-name.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "housing-csv-name.csv:2: column 2 'accel [g]': name it t or time"));
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/housing-csv-twice.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_non_null(
        strstr(err.message, "housing-csv-twice.csv:1: column 3 'Y [m/s^2]': the same quantity as column 2 'ay [g]'"));
    /* read as the case file is (td_cr_read_file): CR-only line endings are refused, not run together */
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/housing-csv-cr.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "housing-csv-cr.csv:1: carriage return without a line feed"));
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/housing-csv-missing.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_non_null(strstr(err.message, ": cannot read the history file: "));
}

/* The CSV columns are mapped by their names, in any order and case: housing-reordered.csv is
 * tests/data/case/housing-record.csv (0.5 g along x, -1 g along y at 5 ms) as `Time [ms], AY [g], x [m/s^2]`. */
static void test_csv_columns_by_name(void **state)
{
    td_case *c = NULL;
    td_housing_motion hm;
    (void)state;
    assert_int_equal(td_case_load(td_source_path("tests/data/case/housing-reordered.cfg"), NULL, 0, &c, NULL), TD_OK);
    assert_int_equal(td_model_housing_history_count(td_case_model(c)), 3);
    td_model_housing_motion_at(td_case_model(c), 0.005, &hm);
    assert_close(hm.acceleration[0], 0.5 * 9.80665, 1e-15, 0.0);
    assert_close(hm.acceleration[1], -9.80665, 1e-15, 0.0);
    td_model_housing_motion_at(td_case_model(c), 0.0075, &hm); /* halfway down the second segment */
    assert_close(hm.acceleration[0], 0.25 * 9.80665, 1e-15, 0.0);
    td_case_free(&c);
}

/* sum of x . f over the rotor's x (y) DOFs of a load f: with R_x, the load of a unit translation
 * M R_x gives the total mass; with the rigid tilt T_y, G T_x gives -Ip (dofs.h: G_(phi,theta) = -Ip). */
static double rigid_work(const td_system *s, const double *f, int kind, double zref)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < s->ndof; i++) {
        int off, node = td_system_coordinate_node(s, i, &off);
        double dz = node >= 0 ? td_model_node_position(s->model, node) - zref : 0.0;
        if (node < 0)
            continue; /* a fixed-interface mode: 0 in a rigid motion */
        if (kind == 0 && off == TD_DOF_X)
            sum += f[i];
        else if (kind == 1 && (off == TD_DOF_X || off == TD_DOF_PHI))
            sum += f[i] * (off == TD_DOF_X ? dz : 1.0);
    }
    return sum;
}

static void check_base_loads(td_model *m)
{
    td_system *s = NULL;
    double zref = td_model_housing_reference(m);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    assert_non_null(s->base_load[0]);
    assert_close(rigid_work(s, s->base_load[0], 0, zref), td_model_total_mass(m), 1e-12, 0.0);
    /* R_x . M T_y: the mass's first moment about z_ref, 0 about the centre of mass */
    assert_close(rigid_work(s, s->base_load[3], 0, zref), 0.0, 0.0, 1e-12 * td_model_total_mass(m));
    assert_close(rigid_work(s, s->base_gyro[0], 1, zref), -td_model_polar_inertia(m), 1e-12, 0.0);
    assert_close(rigid_work(s, s->base_gyro[1], 1, zref), 0.0, 0.0, 1e-15);
    td_system_free(&s);
}

static void test_base_loads(void **state)
{
    td_model *m = shaft_model();
    td_housing_pulse p = pulse(TD_PULSE_RAMP, 0.1, 0.1, 0.0, 1.0, 0.0);
    td_system *s = NULL;
    td_amb amb = {1, 1, 1.0e5, 100.0, 1.0e4, 20.0, 0.0, 1000.0, 0, 0.0, 0.0, 0.0};
    (void)state;
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK); /* none without housing motion */
    assert_null(s->base_load[0]);
    assert_null(s->base_gyro[1]);
    td_system_free(&s);
    assert_int_equal(td_model_add_housing_rotation(m, &p, NULL), TD_OK);
    check_base_loads(m);
    /* the reduced rotor (parts at nodes 1, 3, 7 keep their DOFs): the projected loads do the same
     * work on the rigid motions, which the constraint modes hold exactly */
    assert_int_equal(td_model_add_amb(m, &amb, NULL), TD_OK);
    amb.node = amb.sensor_node = 7;
    assert_int_equal(td_model_add_amb(m, &amb, NULL), TD_OK);
    assert_int_equal(td_model_set_reduction(m, 3000.0, NULL), TD_OK);
    check_base_loads(m);
    td_model_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pulse_closed_forms),
        cmocka_unit_test(test_pulse_start_precision),
        cmocka_unit_test(test_pulse_quadrature),
        cmocka_unit_test(test_rate_change),
        cmocka_unit_test(test_history),
        cmocka_unit_test(test_rules),
        cmocka_unit_test(test_clone_and_refine),
        cmocka_unit_test(test_csv_fault_located),
        cmocka_unit_test(test_csv_columns_by_name),
        cmocka_unit_test(test_base_loads),
    };
    return cmocka_run_group_tests_name("housing", tests, NULL, NULL);
}
