/*
 * The loop analysis (touchdown/modal.h, td_loop_compute; docs/theory.md, "Sensitivity"):
 * - S_j, its peak and the compliance against an independent computation at test time
 *   (tests/validation/control/loop_reference.py: numpy + scipy build the loop from the assembled
 *   matrices and the AMB law; the compliance from the existing closed-loop state matrix);
 * - the ISO 14839-3 zone limits at exactly 3, 4 and 5;
 * - an unstable loop gives no sensitivity (undefined, null in JSON), never a number.
 */
#include "td_test.h"
#include "touchdown/case.h"
#include "touchdown/modal.h"
#include "touchdown/modal_output.h"
#include "touchdown/system.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The rub-damped rig (shaft damping, so every mode is damped) at 300 rad/s (gyroscopic coupling
 * between x and y), with a PID on the DE AMB and a different kp: the axes' loops differ. */
static const char *machine[] = {"speed=300.0", "ambs[1].kint=5.0e4", "ambs[1].kp=1.2e4", "ambs[1].kd=35.0"};

static td_system *load_system(const char **overrides, int n, td_case **c)
{
    td_system *s = NULL;
    td_error err;
    *c = td_test_load_case("cases/rub-damped.cfg", overrides, n);
    assert_int_equal(td_system_create(td_case_model(*c), &s, &err), TD_OK);
    return s;
}

static void write_matrix(FILE *f, const char *name, const double *a, size_t n)
{
    size_t i;
    fprintf(f, "%s", name);
    for (i = 0; i < n; i++)
        fprintf(f, " %.17g", a[i]);
    fputc('\n', f);
}

/* What the reference needs: the matrices, each AMB axis (actuator dof, sensor dof, ks, ki, kp, kd,
 * kint, tau), the speed, the frequencies to compare at and the closed-loop state matrix. */
static void dump_machine(const char *path, const td_system *s, const td_model *m, double omega, const double *freq,
                         int nf)
{
    int nd = td_system_dof_count(s), n = td_modal_state_count(s), i, k;
    double *a = malloc((size_t)n * (size_t)n * sizeof *a);
    FILE *f = fopen(path, "w");
    td_error err;
    assert_non_null(a);
    assert_non_null(f);
    fprintf(f, "ndof %d\nomega %.17g\n", nd, omega);
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb b;
        assert_int_equal(td_model_get_amb(m, i, &b), TD_OK);
        for (k = 0; k < 2; k++)
            fprintf(f, "amb %d %d %.17g %.17g %.17g %.17g %.17g %.17g\n", td_system_node_dof(s, b.node, k),
                    td_system_node_dof(s, b.sensor_node, k), b.ks, b.ki, b.kp, b.kd, b.kint, b.tau);
    }
    for (k = 0; k < 4; k++) {
        static const char *names[4] = {"M", "K", "C", "G"};
        assert_int_equal(td_system_dense(s, (td_matrix_kind)k, a, &err), TD_OK);
        write_matrix(f, names[k], a, (size_t)nd * (size_t)nd);
    }
    write_matrix(f, "freq", freq, (size_t)nf);
    assert_int_equal(td_modal_state_matrix(s, omega, a, &err), TD_OK);
    write_matrix(f, "Acl", a, (size_t)n * (size_t)n);
    assert_int_equal(fclose(f), 0);
    free(a);
}

/* Run the reference (python3 with numpy and scipy: their absence fails the test). */
static void run_reference(const char *in, const char *out)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 %s %s %s", td_source_path("tests/validation/control/loop_reference.py"),
             in, out);
    assert_int_equal(system(cmd), 0);
}

/* Compare one reference line with the library. */
static void check_line(const td_loop *l, const char *line, int *counts)
{
    char what;
    int j;
    double x, y, z;
    td_error err;
    if (sscanf(line, "%c %d %lf %lf %lf", &what, &j, &x, &y, &z) < 4)
        fail_msg("bad reference line: %s", line);
    if (what == 'S') { /* S_j(x Hz) = y + i z */
        double re, im;
        assert_int_equal(td_loop_evaluate(l, j, x, &re, &im, NULL, NULL, &err), TD_OK);
        assert_true(hypot(re - y, im - z) <= 1e-8 * hypot(y, z));
        counts[0]++;
    } else if (what == 'X') { /* compliance of AMB axis j at a grid frequency */
        double re = 0.0, im = 0.0;
        int k;
        for (k = 0; k < td_loop_frequency_count(l); k++)
            if (fabs(td_loop_frequency(l, k) - x) <= 1e-12 * x)
                assert_int_equal(td_loop_compliance(l, j, k, &re, &im), TD_OK);
        assert_true(hypot(re - y, im - z) <= 1e-7 * hypot(y, z));
        counts[1]++;
    } else if (what == 'P') { /* peak x at y Hz */
        assert_close(td_loop_sensitivity_peak(l, j), x, 1e-9, 0.0);
        assert_close(td_loop_sensitivity_peak_frequency(l, j), y, 1e-5, 0.0);
        counts[2]++;
    }
}

static void test_against_scipy(void **state)
{
    td_case *c = NULL;
    td_system *s = load_system(machine, 4, &c);
    td_loop *l = NULL;
    td_error err;
    char dir[] = "/tmp/td_loop_XXXXXX", in[64], out[64], line[512];
    int counts[3] = {0, 0, 0}, k;
    double freq[6];
    FILE *f;
    (void)state;
    assert_int_equal(td_loop_compute(s, 300.0, NULL, &l, &err), TD_OK);
    assert_true(td_loop_stable(l));
    assert_int_equal(td_loop_axis_count(l), 4);
    for (k = 0; k < 6; k++) /* grid points from 1.2 Hz to 2.4 kHz, where the compliance is stored */
        freq[k] = td_loop_frequency(l, 100 + 190 * k);
    assert_non_null(mkdtemp(dir));
    snprintf(in, sizeof in, "%s/in.txt", dir);
    snprintf(out, sizeof out, "%s/out.txt", dir);
    dump_machine(in, s, td_case_model(c), 300.0, freq, 6);
    run_reference(in, out);
    f = fopen(out, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f))
        check_line(l, line, counts);
    fclose(f);
    assert_int_equal(counts[0], 24);
    assert_int_equal(counts[1], 24);
    assert_int_equal(counts[2], 4);
    remove(in);
    remove(out);
    rmdir(dir);
    td_loop_free(&l);
    td_system_free(&s);
    td_case_free(&c);
}

/* ISO 14839-3:2006 zone limits, exactly at 3, 4 and 5 and just below. */
static void test_zone_limits(void **state)
{
    (void)state;
    assert_int_equal(td_loop_zone(1.0), 'A');
    assert_int_equal(td_loop_zone(nextafter(3.0, 0.0)), 'A');
    assert_int_equal(td_loop_zone(3.0), 'B');
    assert_int_equal(td_loop_zone(nextafter(4.0, 0.0)), 'B');
    assert_int_equal(td_loop_zone(4.0), 'C');
    assert_int_equal(td_loop_zone(nextafter(5.0, 0.0)), 'C');
    assert_int_equal(td_loop_zone(5.0), 'D');
    assert_int_equal(td_loop_zone(1e300), 'D');
    assert_int_equal(td_loop_zone(TD_UNDEFINED), 0);
}

/* kp ki below ks: the magnet's negative stiffness wins, the loop is unstable: no sensitivity. */
static void test_unstable(void **state)
{
    static const char *weak[] = {"ambs[0].kp=1.0e3", "ambs[1].kp=1.0e3"};
    td_case *c = NULL;
    td_system *s = load_system(weak, 2, &c);
    td_loop *l = NULL;
    td_error err;
    double re, im;
    char json[2048];
    (void)state;
    assert_int_equal(td_loop_compute(s, 90.0, NULL, &l, &err), TD_OK);
    assert_false(td_loop_stable(l));
    assert_true(td_loop_max_real_part(l) > 1.0);
    assert_true(td_is_undefined(td_loop_sensitivity_peak(l, 0)));
    assert_int_equal(td_loop_sensitivity_zone(l, 0), 0);
    assert_int_equal(td_loop_worst_zone(l), 0);
    assert_int_equal(td_loop_sensitivity(l, 0, 10, &re, &im), TD_OK);
    assert_true(td_is_undefined(re) && td_is_undefined(im));
    assert_int_equal(td_loop_open_loop(l, 0, 10, &re, &im), TD_OK);
    assert_true(isfinite(re) && isfinite(im));
    assert_true(td_loop_json(json, sizeof json, l) < (int)sizeof json);
    assert_non_null(strstr(json, "\"stable\":false"));
    assert_non_null(strstr(json, "\"sensitivity_peak\":null"));
    assert_non_null(strstr(json, "\"sensitivity_zone\":null"));
    td_loop_free(&l);
    td_system_free(&s);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_scipy),
        cmocka_unit_test(test_zone_limits),
        cmocka_unit_test(test_unstable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
