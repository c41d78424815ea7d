/*
 * Modal analysis of the reference rig (docs/reference-rig.md) against ross-rotordynamics,
 * and the AMB force lag against the closed-form characteristic cubic of one axis.
 *
 * Lag-free rig: Euler-Bernoulli shaft (shear off), consistent mass with rotary inertia, gyroscopics;
 * each AMB with tau = 0 is exactly the spring-damper k_eq = ki kp - ks = 1e6 N/m,
 * c_eq = ki kd = 8000 N s/m. The reference numbers in tests/data/rig_ross_reference.csv come from
 * tests/validation/ross/rig_reference.py (ross 2.x, same model; lateral modes only).
 * Both codes form A = [0 I; -M^-1 K, -M^-1 (C + Omega G)] and solve a dense eigenproblem, so the
 * only differences are element matrices (same Euler-Bernoulli formulas) and round-off: 1e-6 relative.
 */
#include "td_rig.h"
#include "td_test.h"

#include "model/system_internal.h"
#include "touchdown/modal.h"
#include "touchdown/touchdown.h"

#include "touchdown/case.h"

#include <gsl/gsl_poly.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RIG_TAU TD_RIG_TAU

/* The reference rig (tests/support/td_rig.c) without retainers; tau = AMB force lag (0: lag-free). */
static td_system *rig_system(double tau)
{
    td_model *m = td_test_rig_create(0.0, tau, TD_RIG_NO_RETAINERS);
    td_system *s = NULL;
    td_error err;
    if (td_system_create(m, &s, &err) != TD_OK)
        fail_msg("rig: %s", err.message);
    td_model_free(&m);
    return s;
}

typedef struct ref_row {
    double speed, sigma, omega_d, zeta;
    int mode;
    char whirl[16];
} ref_row;

/* Read the ross reference CSV; returns the number of rows (at most cap). */
static int read_reference(ref_row *rows, int cap)
{
    FILE *f = fopen(td_source_path("tests/data/rig_ross_reference.csv"), "r");
    char line[512];
    int n = 0, header = 0;
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        if (!header) {
            header = 1;
            assert_non_null(strstr(line, "omega_d_rad_s"));
            continue;
        }
        assert_true(n < cap);
        assert_int_equal(sscanf(line, "%lf,%d,%lf,%lf,%lf,%15s", &rows[n].speed, &rows[n].mode, &rows[n].sigma,
                                &rows[n].omega_d, &rows[n].zeta, rows[n].whirl),
                         6);
        n++;
    }
    fclose(f);
    return n;
}

static void test_lag_free_rig_matches_ross(void **state)
{
    ref_row rows[256];
    int n = read_reference(rows, 256), i, checked = 0;
    td_system *s = rig_system(0.0);
    static const double speeds[3] = {0.0, 90.0, 190.0};
    int k;
    (void)state;
    assert_int_equal(td_modal_state_count(s), 2 * 52);
    for (k = 0; k < 3; k++) {
        td_modal *md = NULL;
        double worst_w = 0.0, worst_z = 0.0;
        int count = 0;
        assert_int_equal(td_modal_solve(s, speeds[k], &md, NULL), TD_OK);
        assert_int_equal(td_modal_real_count(md), 0);
        for (i = 0; i < n; i++) {
            td_mode mode;
            if (rows[i].speed != speeds[k])
                continue;
            assert_int_equal(td_modal_get_mode(md, rows[i].mode, &mode), TD_OK);
            assert_close(mode.omega_d, rows[i].omega_d, 1e-6, 0.0);
            assert_close(mode.zeta, rows[i].zeta, 1e-6, 1e-12);
            assert_close(mode.sigma, rows[i].sigma, 1e-6, 0.0);
            if (td_rel_diff(mode.omega_d, rows[i].omega_d) > worst_w)
                worst_w = td_rel_diff(mode.omega_d, rows[i].omega_d);
            if (td_rel_diff(mode.zeta, rows[i].zeta) > worst_z)
                worst_z = td_rel_diff(mode.zeta, rows[i].zeta);
            /* whirl: compare where ross finds a pure sense at speed (degenerate at rest) */
            if (speeds[k] > 0.0 && strcmp(rows[i].whirl, "forward") == 0)
                assert_int_equal(mode.whirl, TD_WHIRL_FORWARD);
            if (speeds[k] > 0.0 && strcmp(rows[i].whirl, "backward") == 0)
                assert_int_equal(mode.whirl, TD_WHIRL_BACKWARD);
            count++;
        }
        print_message("ross, %g rad/s: %d modes, max rel diff omega_d %.3e, zeta %.3e\n", speeds[k], count, worst_w,
                      worst_z);
        assert_true(count >= 8);
        checked += count;
        td_modal_free(&md);
    }
    assert_int_equal(checked, n);
    td_system_free(&s);
}

/* Roots of (m s^2 - ks)(tau s + 1) + ki (kp + kd s) = 0, the characteristic equation of one AMB
 * axis (F = ks x + Fc, tau Fc' = -Fc - ki (kp x + kd x')) on a rigid mass m. */
static void axis_cubic_roots(double m, double ks, double ki, double kp, double kd, double tau, double z[6])
{
    double a[4];
    gsl_poly_complex_workspace *w = gsl_poly_complex_workspace_alloc(4);
    a[0] = -ks + ki * kp;
    a[1] = -ks * tau + ki * kd;
    a[2] = m;
    a[3] = m * tau;
    assert_int_equal(gsl_poly_complex_solve(a, 4, w, z), 0);
    gsl_poly_complex_workspace_free(w);
}

/* One node: a rigid mass m (x, y) with an AMB on both axes; rotations held by springs far away
 * in frequency. Built by hand so the system is exactly the single-axis problem. */
static td_system *rigid_mass_amb(double m, const td_amb_axis *proto)
{
    td_system *s = calloc(1, sizeof *s);
    cs_di *T[4];
    int i, k;
    assert_non_null(s);
    s->nnodes = 1;
    s->ndof = 4;
    s->nphys = 4; /* full model: q is physical */
    for (k = 0; k < 4; k++)
        T[k] = cs_di_spalloc(4, 4, 8, 1, 1);
    for (i = 0; i < 4; i++) {
        cs_di_entry(T[0], i, i, i < 2 ? m : 1.0);      /* M: m on x, y; 1 kg m^2 on rotations */
        cs_di_entry(T[1], i, i, i < 2 ? 0.0 : 1.0e12); /* K: rotations only, 1e6 rad/s */
        cs_di_entry(T[2], i, i, 0.0);                  /* C */
        cs_di_entry(T[3], i, i, 0.0);                  /* G */
    }
    s->M = cs_di_compress(T[0]);
    s->K = cs_di_compress(T[1]);
    s->C = cs_di_compress(T[2]);
    s->G = cs_di_compress(T[3]);
    for (k = 0; k < 4; k++)
        cs_di_spfree(T[k]);
    s->n_amb_axes = 2;
    s->amb_axes = calloc(2, sizeof *s->amb_axes);
    s->gravity_load = calloc(4, sizeof *s->gravity_load);
    assert_non_null(s->amb_axes);
    for (k = 0; k < 2; k++) {
        s->amb_axes[k] = *proto;
        s->amb_axes[k].axis = k;
        s->amb_axes[k].actuator_dof = s->amb_axes[k].sensor_dof = k;
        s->amb_axes[k].state = proto->tau > 0.0 ? s->n_controller_states++ : -1;
    }
    return s;
}

static void test_single_axis_lag_cubic(void **state)
{
    /* the rig's AMB on a 50 kg rigid mass (about half the rotor) */
    td_amb_axis proto = {0, 0, 0, 0, 1.0e6, 200.0, 1.0e4, 40.0, RIG_TAU, 1700.0, 0, 0, -1, 0.0, 0, -1, -1, 0.0};
    double m = 50.0, z[6];
    td_system *s = rigid_mass_amb(m, &proto);
    td_modal *md = NULL;
    int r, found_complex = 0;
    (void)state;
    axis_cubic_roots(m, proto.ks, proto.ki, proto.kp, proto.kd, proto.tau, z);
    assert_int_equal(td_modal_state_count(s), 10);
    assert_int_equal(td_modal_solve(s, 0.0, &md, NULL), TD_OK);
    for (r = 0; r < 3; r++) {
        double re = z[2 * r], im = z[2 * r + 1];
        if (im > 0.0) {
            /* each axis contributes the pair: two modes at this frequency */
            int i, hits = 0;
            for (i = 0; i < td_modal_mode_count(md); i++) {
                td_mode mode;
                td_modal_get_mode(md, i, &mode);
                if (fabs(mode.omega_d - im) <= 1e-9 * hypot(re, im) && fabs(mode.sigma - re) <= 1e-9 * hypot(re, im))
                    hits++;
            }
            assert_int_equal(hits, 2);
            found_complex = 1;
            print_message("AMB axis cubic: s = %.12g +- %.12g i\n", re, im);
        } else if (im == 0.0) {
            int i, hits = 0;
            for (i = 0; i < td_modal_real_count(md); i++)
                if (fabs(td_modal_real_eigenvalue(md, i) - re) <= 1e-9 * fabs(re))
                    hits++;
            assert_int_equal(hits, 2);
            print_message("AMB axis cubic: s = %.12g (real)\n", re);
        }
    }
    assert_true(found_complex);
    td_modal_free(&md);
    td_system_free(&s);
}

static void test_rig_with_lag(void **state)
{
    td_system *s = rig_system(RIG_TAU), *s0 = rig_system(0.0);
    td_modal_options opt;
    td_critical_speed cs[16];
    static const double speeds[2] = {90.0, 190.0};
    int k, i, ncs = 0;
    (void)state;
    assert_int_equal(td_modal_state_count(s), 2 * 52 + 4);
    for (k = 0; k < 2; k++) {
        td_modal *md = NULL, *md0 = NULL;
        assert_int_equal(td_modal_solve(s, speeds[k], &md, NULL), TD_OK);
        assert_int_equal(td_modal_solve(s0, speeds[k], &md0, NULL), TD_OK);
        /* the rig runs contact-free at its case speeds: the linear system is stable */
        /* the rig runs contact-free at its case speeds: no growing mode. The highest modes have
         * nodes at the AMBs and the shaft has no structural damping, so their real parts are
         * round-off (|sigma| ~ 1e-16 |s|): check zeta, not the sign of sigma. */
        for (i = 0; i < td_modal_mode_count(md); i++) {
            td_mode a;
            td_modal_get_mode(md, i, &a);
            assert_true(a.zeta > -1e-12);
        }
        for (i = 0; i < td_modal_real_count(md); i++)
            assert_true(td_modal_real_eigenvalue(md, i) < 0.0);
        /* 4 filter states: 2 more eigenvalues in pairs or 4 more real ones */
        assert_int_equal(2 * td_modal_mode_count(md) + td_modal_real_count(md), 2 * 52 + 4);
        for (i = 0; i < 6; i++) {
            td_mode a, b;
            td_modal_get_mode(md, i, &a);
            td_modal_get_mode(md0, i, &b);
            print_message("%g rad/s mode %d: lag %.9g rad/s zeta %.6f whirl %+d | lag-free %.9g rad/s zeta %.6f\n",
                          speeds[k], i, a.omega_d, a.zeta, (int)a.whirl, b.omega_d, b.zeta);
        }
        for (i = 0; i < td_modal_real_count(md); i++)
            print_message("%g rad/s real eigenvalue %.9g\n", speeds[k], td_modal_real_eigenvalue(md, i));
        td_modal_free(&md);
        td_modal_free(&md0);
    }
    td_modal_options_default(&opt);
    opt.speed_min = 0.0;
    opt.speed_max = 400.0;
    opt.speed_steps = 41;
    assert_int_equal(td_modal_critical_speeds(s, &opt, cs, 16, &ncs, NULL), TD_OK);
    for (i = 0; i < ncs && i < 16; i++)
        print_message("critical speed (lag): %.12g rad/s %s branch %d zeta %.6f\n", cs[i].speed,
                      cs[i].whirl == TD_WHIRL_FORWARD ? "forward" : "backward", cs[i].branch, cs[i].zeta);
    assert_int_equal(td_modal_critical_speeds(s0, &opt, cs, 16, &ncs, NULL), TD_OK);
    for (i = 0; i < ncs && i < 16; i++)
        print_message("critical speed (lag-free): %.12g rad/s %s branch %d zeta %.6f\n", cs[i].speed,
                      cs[i].whirl == TD_WHIRL_FORWARD ? "forward" : "backward", cs[i].branch, cs[i].zeta);
    td_system_free(&s);
    td_system_free(&s0);
}

/* The rig of cases/paper-a.cfg (through the case reader) is the rig built here, lag included:
 * same eigenvalues to round-off. This ties the ross comparison to the machine the runs use. */
static void test_case_file_rig_is_this_rig(void **state)
{
    td_case *c = NULL;
    td_system *sc = NULL, *s = rig_system(RIG_TAU);
    td_modal *a = NULL, *b = NULL;
    td_error err;
    int i;
    (void)state;
    if (td_case_load(td_source_path("cases/paper-a.cfg"), NULL, 0, &c, &err) != TD_OK)
        fail_msg("%s", err.message);
    assert_int_equal(td_system_create(td_case_model(c), &sc, &err), TD_OK);
    assert_close(td_model_speed(td_case_model(c)), 90.0, 0.0, 0.0);
    assert_int_equal(td_modal_state_count(sc), td_modal_state_count(s));
    assert_int_equal(td_modal_solve(sc, 90.0, &a, NULL), TD_OK);
    assert_int_equal(td_modal_solve(s, 90.0, &b, NULL), TD_OK);
    assert_int_equal(td_modal_mode_count(a), td_modal_mode_count(b));
    for (i = 0; i < 16; i++) {
        td_mode x, y;
        td_modal_get_mode(a, i, &x);
        td_modal_get_mode(b, i, &y);
        assert_close(x.omega_d, y.omega_d, 1e-10, 0.0);
        assert_close(x.sigma, y.sigma, 1e-9, 1e-9);
    }
    td_modal_free(&a);
    td_modal_free(&b);
    td_system_free(&sc);
    td_system_free(&s);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lag_free_rig_matches_ross),
        cmocka_unit_test(test_single_axis_lag_cubic),
        cmocka_unit_test(test_rig_with_lag),
        cmocka_unit_test(test_case_file_rig_is_this_rig),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
