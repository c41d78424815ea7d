/*
 * The loop analysis (touchdown/modal.h, td_loop_compute; docs/theory.md, "Sensitivity"):
 * - S_j, its peak and the compliance against an independent computation at test time
 *   (tests/validation/control/loop_reference.py: numpy + scipy build the loop from the assembled
 *   matrices and the AMB law; the compliance from the existing closed-loop state matrix);
 * - the ISO 14839-3 zone limits at exactly 3, 4 and 5;
 * - the static compliance against the closed form of a rigid rotor on two bearings;
 * - the notch at the first bending mode; the same PD as the shorthand and as a linear controller;
 * - an unstable loop gives no sensitivity (undefined, null in JSON), never a number;
 * - the sampled loop (a sampled controller, AMB 1's shorthand inside the plant) against scipy at
 *   test time (tests/validation/control/sampled_loop_reference.py: cont2discrete zoh and bilinear,
 *   dfreqresp, a hand closed loop over one sample), and its limit as the rate grows: the
 *   continuous loop of the same law, the error falling as T; its grid ends at the Nyquist frequency;
 * - a slowly growing sampled loop (scipy's |mu|) is unstable for td_modal_is_unstable,
 *   td_modal_stability and td_loop_stable alike.
 */
#include "td_test.h"
#include "touchdown/case.h"
#include "touchdown/controller.h"
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
 * kint, tau), the speed, the frequencies to compare at and (acl = 1) the closed-loop state matrix. */
static FILE *dump_machine(const char *path, const td_system *s, const td_model *m, double omega, const double *freq,
                          int nf, int acl)
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
    if (acl) {
        assert_int_equal(td_modal_state_matrix(s, omega, a, &err), TD_OK);
        write_matrix(f, "Acl", a, (size_t)n * (size_t)n);
    }
    free(a);
    return f;
}

/* Run a reference script (python3 with numpy and scipy: their absence fails the test). */
static void run_reference(const char *script, const char *in, const char *out)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 /usr/bin/python3 %s %s %s",
             td_source_path(script), in, out);
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
    } else if (what == 'R') { /* the largest |mu| of a sampled loop over one sample: s = ln(mu) rate */
        assert_close(td_loop_max_real_part(l), log(x) * td_loop_sample_rate(l), 1e-6, 1e-9);
        counts[3]++;
    }
}

static void test_against_scipy(void **state)
{
    td_case *c = NULL;
    td_system *s = load_system(machine, 4, &c);
    td_loop *l = NULL;
    td_error err;
    char dir[] = "/tmp/td_loop_XXXXXX", in[64], out[64], line[512];
    int counts[4] = {0, 0, 0, 0}, k;
    double freq[6];
    FILE *f;
    (void)state;
    assert_int_equal(td_loop_compute(s, 300.0, NULL, &l, &err), TD_OK);
    assert_true(td_loop_stable(l));
    assert_int_equal(td_loop_axis_count(l), 4);
    for (k = 0; k < 6; k++) /* grid points from 1.2 Hz to 2.4 kHz, where the compliance is stored */
        freq[k] = td_loop_frequency(l, 67 + 127 * k);
    assert_non_null(mkdtemp(dir));
    snprintf(in, sizeof in, "%s/in.txt", dir);
    snprintf(out, sizeof out, "%s/out.txt", dir);
    assert_int_equal(fclose(dump_machine(in, s, td_case_model(c), 300.0, freq, 6, 1)), 0);
    run_reference("tests/validation/control/loop_reference.py", in, out);
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

/* The sampled PD of the test below on AMB axes 0 and 1: kp + kd s / (1 + s / (2 pi f_d)), Tustin at
 * `rate`, `delay` samples; AMB 1 keeps the shorthand PID of `machine`. rig_sampled_pd: the system
 * with such a law (its five numbers in that order) on AMB 0. */
static const double sampled_pd[5] = {20000.0, 1.0, 1.0e4, 40.0, 2000.0}; /* rate, delay, kp, kd, f_d */

static td_system *rig_sampled_pd(const double *law, td_case **c)
{
    static const char *ov[] = {"speed=300.0",     "ambs[1].kint=5.0e4", "ambs[1].kp=1.2e4",
                               "ambs[1].kd=35.0", "ambs[0].kp=0",       "ambs[0].kd=0"};
    td_pid_block pid = {law[2], 0.0, law[3], law[4]};
    td_controller *k = td_controller_create_pid(&pid, NULL);
    td_controller *kt = td_controller_discretise(k, law[0], TD_DISCRETISE_TUSTIN, 0.0, NULL);
    td_controller *kd = td_controller_delay(kt, (int)law[1], NULL);
    td_model *m = NULL;
    td_system *s = NULL;
    td_error err;
    int a;
    *c = td_test_load_case("cases/rub-damped.cfg", ov, 6);
    assert_non_null(kd);
    assert_int_equal(td_model_clone(td_case_model(*c), &m, &err), TD_OK);
    for (a = 0; a < 2; a++) {
        char name[32];
        snprintf(name, sizeof name, "digital %d", a);
        assert_int_equal(td_model_add_controller(m, name, kd, &a, &a, &err), TD_OK);
    }
    assert_int_equal(td_system_create(m, &s, &err), TD_OK);
    td_controller_free(&k);
    td_controller_free(&kt);
    td_controller_free(&kd);
    td_model_free(&m);
    return s;
}

/* The sampled loop (20 kHz, one sample of delay) on AMB 0, the shorthand PID on AMB 1 closed inside
 * the plant, against scipy (sampled_loop_reference.py: cont2discrete zoh and bilinear, dfreqresp, a
 * hand closed loop over one sample): S_j at six grid frequencies, its peak, the compliance at the
 * sample instants and the largest |mu|. The peak (3.87) is that of the 304 Hz bending mode, which
 * the hold and the delay leave lightly damped: it comes from the search at the lightly damped
 * closed-loop modes. */
static void test_sampled_against_scipy(void **state)
{
    td_case *c = NULL;
    td_system *s = rig_sampled_pd(sampled_pd, &c);
    td_loop *l = NULL;
    td_error err;
    char dir[] = "/tmp/td_loop_XXXXXX", in[64], out[64], line[512];
    int counts[4] = {0, 0, 0, 0}, k;
    double freq[6];
    FILE *f;
    (void)state;
    assert_int_equal(td_loop_compute(s, 300.0, NULL, &l, &err), TD_OK);
    assert_true(td_loop_stable(l));
    assert_close(td_loop_sample_rate(l), sampled_pd[0], 0.0, 0.0);
    assert_int_equal(td_loop_axis_count(l), 2); /* the sampled axes; AMB 1's loop is in the plant */
    assert_int_equal(td_loop_axis(l, 1), 1);
    assert_close(td_loop_frequency(l, td_loop_frequency_count(l) - 1), fmin(5000.0, 0.5 * sampled_pd[0]), 0.0, 0.0);
    assert_int_equal(td_loop_evaluate(l, 0, 0.5 * sampled_pd[0] * (1.0 + 1e-9), NULL, NULL, NULL, NULL, &err),
                     TD_ERR_INVALID); /* beyond the Nyquist frequency */
    for (k = 0; k < 6; k++)           /* grid points from 1.2 Hz to 2.4 kHz, where the compliance is stored */
        freq[k] = td_loop_frequency(l, 67 + 127 * k);
    assert_non_null(mkdtemp(dir));
    snprintf(in, sizeof in, "%s/in.txt", dir);
    snprintf(out, sizeof out, "%s/out.txt", dir);
    f = dump_machine(in, s, td_case_model(c), 300.0, freq, 6, 0);
    write_matrix(f, "sampled", sampled_pd, 5);
    fprintf(f, "saxes 0 1\n");
    assert_int_equal(fclose(f), 0);
    run_reference("tests/validation/control/sampled_loop_reference.py", in, out);
    f = fopen(out, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f))
        check_line(l, line, counts);
    fclose(f);
    print_message("sampled loop: peaks %.9g at %.6g Hz, %.9g at %.6g Hz, largest real part %.6g 1/s\n",
                  td_loop_sensitivity_peak(l, 0), td_loop_sensitivity_peak_frequency(l, 0),
                  td_loop_sensitivity_peak(l, 1), td_loop_sensitivity_peak_frequency(l, 1), td_loop_max_real_part(l));
    assert_int_equal(counts[0], 12);
    assert_int_equal(counts[1], 24);
    assert_int_equal(counts[2], 2);
    assert_int_equal(counts[3], 1);
    remove(in);
    remove(out);
    rmdir(dir);
    td_loop_free(&l);
    td_system_free(&s);
    td_case_free(&c);
}

/* The largest |mu| of the sampled loop of rig_sampled_pd(law) over one sample, from scipy
 * (sampled_loop_reference.py's hand closed loop: cont2discrete zoh of the plant, the law's own
 * realisation by tf2ss). */
static double reference_max_mu(const td_system *s, const td_case *c, const double *law)
{
    char dir[] = "/tmp/td_loop_XXXXXX", in[64], out[64], line[512];
    double freq = 10.0, mu = NAN, x;
    int j;
    FILE *f;
    assert_non_null(mkdtemp(dir));
    snprintf(in, sizeof in, "%s/in.txt", dir);
    snprintf(out, sizeof out, "%s/out.txt", dir);
    f = dump_machine(in, s, td_case_model(c), 300.0, &freq, 1, 0);
    write_matrix(f, "sampled", law, 5);
    fprintf(f, "saxes 0 1\n");
    assert_int_equal(fclose(f), 0);
    run_reference("tests/validation/control/sampled_loop_reference.py", in, out);
    f = fopen(out, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "R %d %lf", &j, &x) == 2)
            mu = x;
    fclose(f);
    remove(in);
    remove(out);
    rmdir(dir);
    return mu;
}

/* A slowly growing sampled loop is unstable, by one rule for the modal analysis, its stability check
 * and the loop analysis: ln |mu| beyond the rounding of a marginal root (TD_MODAL_MARGINAL_REAL_PART),
 * that is a largest real part above that fraction of the sample rate. The 10 kHz law with one sample
 * of delay and kd = 41.6 leaves the 304 Hz bending mode growing at 0.006 1/s (scipy's |mu|: ln |mu|
 * = 6e-7, four times the margin). Judged against the spectral radius instead (63000 1/s here, set
 * by the delay's root, s = ln(mu) rate with mu = 0.0018: no growth rate of anything), the margin
 * would be 0.0094 1/s and the loop stable. */
static void test_sampled_slow_growth(void **state)
{
    static const double law[5] = {10000.0, 1.0, 1.0e4, 41.6, 2000.0}; /* rate, delay, kp, kd, f_d */
    td_case *c = NULL;
    td_system *s = rig_sampled_pd(law, &c);
    td_modal *m = NULL;
    td_loop *l = NULL;
    td_error err;
    double mu, max_real = NAN;
    int unstable = -1;
    (void)state;
    mu = reference_max_mu(s, c, law);
    print_message("slow growth: scipy max |mu| - 1 = %.6g, ln |mu| rate = %.6g 1/s\n", mu - 1.0, log(mu) * law[0]);
    assert_true(log(mu) > 3.0 * TD_MODAL_MARGINAL_REAL_PART && log(mu) * law[0] < 0.01); /* grows, slowly */
    assert_int_equal(td_modal_solve(s, 300.0, &m, &err), TD_OK);
    assert_close(td_modal_max_real_part(m), log(mu) * law[0], 1e-6, 0.0);
    assert_close(td_modal_sample_rate(m), law[0], 0.0, 0.0);
    assert_close(td_modal_rounding_scale(m), law[0], 0.0, 0.0); /* what the text's stable/marginal word uses */
    assert_true(td_modal_max_real_part(m) < TD_MODAL_MARGINAL_REAL_PART * td_modal_spectral_radius(m));
    assert_int_equal(td_modal_is_unstable(m), 1);
    assert_int_equal(td_modal_stability(s, 300.0, &max_real, &unstable, &err), TD_OK);
    assert_close(max_real, td_modal_max_real_part(m), 1e-6, 0.0);
    assert_int_equal(unstable, 1);
    assert_int_equal(td_loop_compute(s, 300.0, NULL, &l, &err), TD_OK);
    assert_false(td_loop_stable(l));
    td_loop_free(&l);
    td_modal_free(&m);
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
    td_loop_options coarse = {1.0, 1000.0, 100};
    assert_int_equal(td_loop_compute(s, 90.0, &coarse, &l, &err), TD_OK);
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

/* The notch: the rig with its shorthand PD against the same PD (kp 1e4 A/m, kd 40 A s/m, exact
 * derivative) followed by a notch at the first bending mode as one linear controller per axis
 * (td_model_add_controller). The PD loop's first bending pair at 90 rad/s is at 34.12 Hz (backward)
 * and 34.70 Hz (forward); the notch sits on the backward member, 34.1 Hz, width 6 Hz, depth 0.05.
 * On the rub-damped rig (0.2 % shaft damping) that loop is stable; on the undamped paper rig the
 * backward bending mode, which the notch takes out of the AMBs' reach, grows (about +0.13 1/s: the
 * notch's phase lag below its centre), and so it does with the notch at 34.4 Hz on the damped rig
 * (+0.08 1/s). */
static td_system *rig_pd_notch(const char *relative)
{
    static const char *no_gains[] = {"ambs[0].kp=0", "ambs[0].kd=0", "ambs[1].kp=0", "ambs[1].kd=0"};
    td_case *c = td_test_load_case(relative, no_gains, 4);
    td_pid_block pid = {1.0e4, 0.0, 40.0, 0.0};
    td_notch_block nb = {34.1, 6.0, 0.05};
    td_model *m = NULL;
    td_system *s = NULL;
    td_error err;
    td_controller *pd = td_controller_create_pid(&pid, &err), *notch = td_controller_create_notch(&nb, &err);
    td_controller *k = td_controller_series(pd, notch, &err);
    int a;
    assert_non_null(k);
    assert_int_equal(td_model_clone(td_case_model(c), &m, &err), TD_OK);
    for (a = 0; a < 4; a++) {
        char name[32];
        snprintf(name, sizeof name, "pd+notch %d", a); /* names are unique */
        if (td_model_add_controller(m, name, k, &a, &a, &err) != TD_OK)
            fail_msg("%s", err.message);
    }
    assert_int_equal(td_system_create(m, &s, &err), TD_OK);
    td_controller_free(&pd);
    td_controller_free(&notch);
    td_controller_free(&k);
    td_model_free(&m);
    td_case_free(&c);
    return s;
}

/* The largest |S_j| (s = 1) or |L_j| (s = 0) over [lo, hi] Hz, 0.05 Hz apart. */
static double band_max(const td_loop *l, int j, int s, double lo, double hi)
{
    double best = 0.0, sr, si, lr, li;
    int k, n = (int)((hi - lo) / 0.05 + 0.5);
    td_error err;
    for (k = 0; k <= n; k++) {
        assert_int_equal(td_loop_evaluate(l, j, lo + (hi - lo) * k / n, &sr, &si, &lr, &li, &err), TD_OK);
        best = fmax(best, s ? hypot(sr, si) : hypot(lr, li));
    }
    return best;
}

/* What the notch does to the bending mode, per axis: the PD loop's |S| peak of the mode (about 2,
 * at 36 Hz, over 34-38 Hz: above the open-loop mode at 33.8 Hz) flattens to |S| within 0.25 of
 * 1, and the mode's hump of |L| (0.88 at 34.6 Hz, over 34-35 Hz) falls by more than 4 times. */
static void test_notch(void **state)
{
    td_case *c = NULL;
    td_system *pd = load_system(NULL, 0, &c), *notched = rig_pd_notch("cases/rub-damped.cfg");
    td_system *undamped = rig_pd_notch("cases/paper-a.cfg");
    td_loop *l0 = NULL, *l1 = NULL, *lu = NULL;
    td_error err;
    int j;
    td_loop_options coarse = {1.0, 1000.0, 300}; /* the bands below are evaluated apart */
    (void)state;
    assert_int_equal(td_loop_compute(pd, 90.0, &coarse, &l0, &err), TD_OK);
    assert_int_equal(td_loop_compute(notched, 90.0, &coarse, &l1, &err), TD_OK);
    assert_int_equal(td_loop_compute(undamped, 90.0, &coarse, &lu, &err), TD_OK);
    assert_true(td_loop_stable(l0) && td_loop_stable(l1));
    assert_false(td_loop_stable(lu)); /* the undamped rig: the notched bending mode grows */
    assert_true(td_is_undefined(td_loop_sensitivity_peak(lu, 0)));
    assert_int_equal(td_loop_axis_count(l1), 4);
    for (j = 0; j < 4; j++) {
        double s0 = band_max(l0, j, 1, 34.0, 38.0), s1 = band_max(l1, j, 1, 34.0, 38.0);
        double m0 = band_max(l0, j, 0, 34.0, 35.0), m1 = band_max(l1, j, 0, 34.0, 35.0);
        print_message("axis %d: max |S| over 34-38 Hz: PD %.4g, PD + notch %.4g; max |L| over 34-35 Hz: PD %.4g, "
                      "PD + notch %.4g; peak |S| PD %.4g at %.4g Hz, PD + notch %.4g at %.4g Hz\n",
                      j, s0, s1, m0, m1, td_loop_sensitivity_peak(l0, j), td_loop_sensitivity_peak_frequency(l0, j),
                      td_loop_sensitivity_peak(l1, j), td_loop_sensitivity_peak_frequency(l1, j));
        assert_true(s0 > 1.8);
        assert_true(s1 - 1.0 < 0.25 * (s0 - 1.0));
        assert_true(m1 < 0.25 * m0);
    }
    print_message("largest real part: PD %.4g 1/s, PD + notch %.4g 1/s, the same on the undamped rig %.4g 1/s\n",
                  td_loop_max_real_part(l0), td_loop_max_real_part(l1), td_loop_max_real_part(lu));
    td_loop_free(&l0);
    td_loop_free(&l1);
    td_loop_free(&lu);
    td_system_free(&pd);
    td_system_free(&notched);
    td_system_free(&undamped);
    td_case_free(&c);
}

/* The same PD as the shorthand's, given as a linear controller on each axis (exact derivative:
 * velocity feedthrough), gives the same loop: S_j at the grid to rounding. */
static void test_controller_as_shorthand(void **state)
{
    static const char *no_gains[] = {"ambs[0].kp=0", "ambs[0].kd=0", "ambs[1].kp=0", "ambs[1].kd=0"};
    td_case *c = NULL, *c0 = NULL;
    td_system *pd = load_system(NULL, 0, &c0), *s = NULL;
    td_pid_block pid = {1.0e4, 0.0, 40.0, 0.0};
    td_controller *k = td_controller_create_pid(&pid, NULL);
    td_model *m = NULL;
    td_loop_options coarse = {1.0, 1000.0, 200};
    td_loop *l0 = NULL, *l1 = NULL;
    td_error err;
    int a, i, j;
    (void)state;
    c = td_test_load_case("cases/rub-damped.cfg", no_gains, 4);
    assert_int_equal(td_model_clone(td_case_model(c), &m, &err), TD_OK);
    for (a = 0; a < 4; a++) {
        char name[32];
        snprintf(name, sizeof name, "pd %d", a);
        assert_int_equal(td_model_add_controller(m, name, k, &a, &a, &err), TD_OK);
    }
    assert_int_equal(td_system_create(m, &s, &err), TD_OK);
    assert_int_equal(td_loop_compute(pd, 90.0, &coarse, &l0, &err), TD_OK);
    assert_int_equal(td_loop_compute(s, 90.0, &coarse, &l1, &err), TD_OK);
    assert_close(td_loop_sample_rate(l1), 0.0, 0.0, 0.0);
    for (i = 0; i < td_loop_frequency_count(l0); i++)
        for (j = 0; j < 4; j++) {
            double r0, i0, r1, i1;
            td_loop_sensitivity(l0, j, i, &r0, &i0);
            td_loop_sensitivity(l1, j, i, &r1, &i1);
            assert_true(hypot(r1 - r0, i1 - i0) <= 1e-10 * hypot(r0, i0));
        }
    assert_close(td_loop_sensitivity_peak(l1, 0), td_loop_sensitivity_peak(l0, 0), 1e-10, 0.0);
    td_loop_free(&l0);
    td_loop_free(&l1);
    td_system_free(&pd);
    td_system_free(&s);
    td_model_free(&m);
    td_controller_free(&k);
    td_case_free(&c);
    td_case_free(&c0);
}

/* The rig's PD with a 2 kHz derivative filter on each axis, continuous (rate 0) or Tustin-sampled
 * without delay, at `rate` on AMB 0's axes and `rate_de` on AMB 1's: the system. */
static td_system *rig_filtered_pd(double rate, double rate_de)
{
    static const char *no_gains[] = {"ambs[0].kp=0", "ambs[0].kd=0", "ambs[1].kp=0", "ambs[1].kd=0"};
    td_case *c = td_test_load_case("cases/rub-damped.cfg", no_gains, 4);
    td_pid_block filtered = {1.0e4, 0.0, 40.0, 2000.0};
    td_controller *kf = td_controller_create_pid(&filtered, NULL), *k[2];
    td_model *m = NULL;
    td_system *s = NULL;
    td_error err;
    int a;
    k[0] = rate > 0.0 ? td_controller_discretise(kf, rate, TD_DISCRETISE_TUSTIN, 0.0, NULL) : kf;
    k[1] = rate_de > 0.0 ? td_controller_discretise(kf, rate_de, TD_DISCRETISE_TUSTIN, 0.0, NULL) : kf;
    assert_true(k[0] && k[1]);
    assert_int_equal(td_model_clone(td_case_model(c), &m, &err), TD_OK);
    for (a = 0; a < 4; a++) {
        char name[32];
        snprintf(name, sizeof name, "pd %d", a);
        assert_int_equal(td_model_add_controller(m, name, k[a / 2], &a, &a, &err), TD_OK);
    }
    assert_int_equal(td_system_create(m, &s, &err), TD_OK);
    for (a = 0; a < 2; a++)
        if (k[a] != kf)
            td_controller_free(&k[a]);
    td_controller_free(&kf);
    td_model_free(&m);
    td_case_free(&c);
    return s;
}

/* The largest |S_j - S0_j| / |S0_j| over the grid and the axes, and the peaks' relative difference. */
static void loop_difference(const td_loop *l, const td_loop *l0, double *ds, double *dp)
{
    int i, j;
    *ds = *dp = 0.0;
    for (i = 0; i < td_loop_frequency_count(l0); i++)
        for (j = 0; j < td_loop_axis_count(l0); j++) {
            double r0, i0, r1, i1;
            td_loop_sensitivity(l0, j, i, &r0, &i0);
            td_loop_sensitivity(l, j, i, &r1, &i1);
            *ds = fmax(*ds, hypot(r1 - r0, i1 - i0) / hypot(r0, i0));
        }
    for (j = 0; j < td_loop_axis_count(l0); j++)
        *dp = fmax(*dp, fabs(td_loop_sensitivity_peak(l, j) / td_loop_sensitivity_peak(l0, j) - 1.0));
}

/* A second method for the sampled loop: as the rate grows, the sampled loop of a Tustin-sampled
 * law tends to the continuous loop of that law, at first order in T (the hold's half sample): S_j
 * over 1 Hz..1 kHz and its peak at 100 kHz and at 1 MHz, the error at 1 MHz within 5e-3 (S: the
 * hold's phase lag w T / 2 is 3e-3 at 1 kHz) and 1e-3 (the peak), and at most 0.15 of the error at
 * 100 kHz. And the sampled loop's grid ends at the Nyquist frequency; laws at two rates are
 * refused. */
static void test_sampled_tends_to_continuous(void **state)
{
    td_system *s0 = rig_filtered_pd(0.0, 0.0), *s1 = rig_filtered_pd(1.0e5, 1.0e5);
    td_system *s2 = rig_filtered_pd(1.0e6, 1.0e6), *s3 = rig_filtered_pd(4000.0, 4000.0);
    td_system *s4 = rig_filtered_pd(1.0e4, 5.0e3);
    td_loop_options coarse = {1.0, 1000.0, 200}, wide = {1.0, 1.0e6, 20};
    td_loop *l0 = NULL, *l1 = NULL, *l2 = NULL, *l3 = NULL;
    td_error err;
    double d1, p1, d2, p2;
    (void)state;
    assert_int_equal(td_loop_compute(s0, 90.0, &coarse, &l0, &err), TD_OK);
    assert_int_equal(td_loop_compute(s1, 90.0, &coarse, &l1, &err), TD_OK);
    assert_int_equal(td_loop_compute(s2, 90.0, &coarse, &l2, &err), TD_OK);
    assert_true(td_loop_stable(l0) && td_loop_stable(l1) && td_loop_stable(l2));
    loop_difference(l1, l0, &d1, &p1);
    loop_difference(l2, l0, &d2, &p2);
    print_message("sampled vs continuous: S %.3g (100 kHz), %.3g (1 MHz); peak %.3g, %.3g\n", d1, d2, p1, p2);
    assert_true(d2 < 5e-3 && p2 < 1e-3);
    assert_true(d2 < 0.15 * d1 && p2 < 0.15 * p1);
    assert_int_equal(td_loop_compute(s3, 90.0, &wide, &l3, &err), TD_OK);
    assert_close(td_loop_sample_rate(l3), 4000.0, 0.0, 0.0);
    assert_close(td_loop_frequency(l3, td_loop_frequency_count(l3) - 1), 2000.0, 0.0, 0.0);
    wide.f_min = 2000.0;
    td_loop_free(&l3);
    assert_int_equal(td_loop_compute(s3, 90.0, &wide, &l3, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "Nyquist"));
    assert_int_equal(td_loop_compute(s4, 90.0, &coarse, &l3, &err), TD_ERR_INVALID);
    assert_null(l3);
    assert_non_null(strstr(err.message, "needs one sample rate"));
    td_loop_free(&l0);
    td_loop_free(&l1);
    td_loop_free(&l2);
    td_system_free(&s0);
    td_system_free(&s1);
    td_system_free(&s2);
    td_system_free(&s3);
    td_system_free(&s4);
}

/* The static compliance in closed form: a rigid rotor on two bearings carries a force at bearing
 * a on bearing a alone (moments about b), so x_a / F_a = 1 / (ki kp - ks), the PD's stiffness
 * less the magnet's. The rig's shaft is nearly rigid at 0.5 Hz: within 0.2 % (its flexibility
 * and the inertia at 0.5 Hz). */
static void test_static_compliance(void **state)
{
    td_case *c = NULL;
    td_system *s = load_system(NULL, 0, &c);
    td_loop *l = NULL;
    td_error err;
    td_amb b;
    double re, im;
    int a;
    (void)state;
    assert_int_equal(td_loop_compute(s, 90.0, NULL, &l, &err), TD_OK);
    assert_close(td_loop_frequency(l, 0), 0.5, 0.0, 0.0);
    for (a = 0; a < td_loop_amb_axis_count(l); a++) {
        assert_int_equal(td_model_get_amb(td_case_model(c), a / 2, &b), TD_OK);
        assert_int_equal(td_loop_compliance(l, a, 0, &re, &im), TD_OK);
        assert_close(hypot(re, im), 1.0 / (b.ki * b.kp - b.ks), 2e-3, 0.0);
    }
    td_loop_free(&l);
    td_system_free(&s);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_scipy),
        cmocka_unit_test(test_sampled_against_scipy),
        cmocka_unit_test(test_sampled_slow_growth),
        cmocka_unit_test(test_zone_limits),
        cmocka_unit_test(test_static_compliance),
        cmocka_unit_test(test_unstable),
        cmocka_unit_test(test_notch),
        cmocka_unit_test(test_controller_as_shorthand),
        cmocka_unit_test(test_sampled_tends_to_continuous),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
