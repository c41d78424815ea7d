/*
 * The Craig-Bampton reduced rotor (lib/model/reduce.c), always against the full model of the same
 * machine (a second method), never against numbers from an earlier run.
 *
 * Error model used for the tolerances. The reduction basis holds the exact static deflection of
 * the interior under boundary loads (the constraint modes) plus the fixed-interface modes below the
 * cut-off; what is missing is the dynamic part of the omitted fixed-interface modes, whose amplitude
 * in a motion at frequency f relative to their static share is (f/f_N)^2 / (1 - (f/f_N)^2), f_N the
 * lowest omitted one. For an eigenvalue this is a Ritz error of second order: the relative frequency
 * error of a mode at f is at most of order (f/f_N)^2 times the share of the mode in the omitted
 * interior motion (<= 1), so |df|/f <= (f/f_N)^2 for f <= f_N/2; a steady response at the speed
 * f_Omega = Omega/(2 pi) misses at most (f_Omega/f_N)^2/(1 - (f_Omega/f_N)^2) of its interior part.
 * With every fixed-interface mode kept, T is square and invertible: the reduced model is the full
 * one in other coordinates, exact to rounding (1e-9 relative allows for the eigen-solves' own
 * round-off on ill-conditioned 1e8-spread matrices).
 */
#include "td_rig.h"
#include "td_test.h"

#include "model/system_internal.h"
#include "touchdown/case.h"
#include "touchdown/modal.h"
#include "touchdown/run.h"
#include "touchdown/sim.h"
#include "touchdown/system.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The rig with retainers at `speed`, reduced at `cutoff` Hz (0: the full model). */
static td_system *rig_system(double speed, double cutoff)
{
    td_model *m = td_test_rig_create(speed, TD_RIG_TAU, TD_RIG_WITH_RETAINERS);
    td_system *s = NULL;
    td_error err;
    td_unbalance u = {1, 0.02, 0.0};
    assert_int_equal(td_model_add_unbalance(m, &u, &err), TD_OK);
    assert_int_equal(td_model_set_reduction(m, cutoff, &err), TD_OK);
    assert_int_equal(td_system_create(m, &s, &err), TD_OK);
    td_model_free(&m);
    return s;
}

/* Frequencies (Hz) of the vibration modes, ascending; returns their count (at most cap). */
static int vibration_hz(const td_system *sys, double speed, double *hz, int cap)
{
    td_modal *modes = NULL;
    td_error err;
    int i, n = 0;
    assert_int_equal(td_modal_solve(sys, speed, &modes, &err), TD_OK);
    for (i = 0; i < td_modal_mode_count(modes) && n < cap; i++) {
        td_mode md;
        td_modal_get_mode(modes, i, &md);
        if (td_mode_is_vibration(&md))
            hz[n++] = md.freq_hz;
    }
    td_modal_free(&modes);
    return n;
}

/* Lowest fixed-interface frequency at or above `cutoff` (Hz): the first mode the reduction omits. */
static double first_omitted(double cutoff)
{
    td_system *all = rig_system(0.0, 1e12);
    double f = INFINITY;
    int i;
    for (i = 0; i < td_system_mode_count(all); i++)
        if (td_system_mode_frequency(all, i) >= cutoff) {
            f = td_system_mode_frequency(all, i);
            break;
        }
    td_system_free(&all);
    return f;
}

/* Largest relative frequency error of the modes below f_max, reduced at `cutoff` vs full. */
static double worst_error(double speed, double cutoff, double f_max)
{
    double full[128], red[128], worst = 0.0;
    td_system *sf = rig_system(speed, 0.0), *sr = rig_system(speed, cutoff);
    int nf = vibration_hz(sf, speed, full, 128), nr = vibration_hz(sr, speed, red, 128), i;
    for (i = 0; i < nf && full[i] < f_max; i++) {
        assert_true(i < nr);
        worst = fmax(worst, fabs(red[i] - full[i]) / full[i]);
    }
    td_system_free(&sf);
    td_system_free(&sr);
    return worst;
}

/* The coordinate map: boundary nodes physical, interior ones reached through T only; the full
 * model's map is TD_DOF and its expansion a copy. */
static void test_coordinate_map(void **state)
{
    td_system *full = rig_system(100.0, 0.0), *red = rig_system(100.0, 2000.0);
    double q[64], qp[64];
    int i, node = 2; /* retainer 0 */
    (void)state;
    assert_false(td_system_is_reduced(full));
    assert_int_equal(td_system_dof_count(full), 52);
    assert_int_equal(td_system_node_dof(full, 4, TD_DOF_PHI), TD_DOF(4, TD_DOF_PHI));
    assert_true(td_system_is_reduced(red));
    assert_int_equal(td_system_physical_dof_count(red), 52);
    /* boundary: nodes 1, 2, 3, 5, 7, 9, 10, 11 (discs, journals/AMBs, retainers, the unbalance) */
    assert_int_equal(td_system_dof_count(red), 32 + td_system_mode_count(red));
    assert_int_equal(td_system_node_dof(red, 0, TD_DOF_X), -1);
    assert_int_equal(td_system_node_dof(red, 4, TD_DOF_Y), -1);
    assert_int_equal(td_system_node_dof(red, node, TD_DOF_Y), 4 * 1 + TD_DOF_Y);
    for (i = 0; i < td_system_mode_count(red); i++)
        assert_true(td_system_mode_frequency(red, i) < 2000.0);
    /* a unit boundary displacement (node 3) moves its own DOF by 1 and no other boundary DOF; the
     * interior node 4 next to it follows (constraint mode), the interior node 0 beyond the held
     * nodes 1 and 2 does not */
    memset(q, 0, sizeof q);
    q[td_system_node_dof(red, 3, TD_DOF_X)] = 1.0;
    assert_int_equal(td_system_expand(red, q, qp, NULL), TD_OK);
    assert_true(qp[TD_DOF(3, TD_DOF_X)] == 1.0);
    assert_true(qp[TD_DOF(node, TD_DOF_X)] == 0.0);
    assert_true(fabs(qp[TD_DOF(4, TD_DOF_X)]) > 0.1);
    assert_true(qp[TD_DOF(4, TD_DOF_Y)] == 0.0); /* the planes stay apart */
    assert_true(qp[TD_DOF(0, TD_DOF_X)] == 0.0);
    /* one node's displacement is the same row of T q */
    for (i = 0; i < td_system_dof_count(red); i++)
        q[i] = 1e-4 * (i + 1) * (i % 3 - 1);
    assert_int_equal(td_system_expand(red, q, qp, NULL), TD_OK);
    for (i = 0; i < 13; i++) {
        assert_close(td_system_node_displacement(red, q, i, TD_DOF_X), qp[TD_DOF(i, TD_DOF_X)], 1e-14, 1e-20);
        assert_close(td_system_node_displacement(red, q, i, TD_DOF_PHI), qp[TD_DOF(i, TD_DOF_PHI)], 1e-14, 1e-20);
    }
    assert_true(isnan(td_system_node_displacement(red, q, 13, TD_DOF_X)));
    for (i = 0; i < 52; i++)
        q[i] = 1e-3 * (i + 1);
    assert_int_equal(td_system_expand(full, q, qp, NULL), TD_OK);
    assert_memory_equal(q, qp, 52 * sizeof *q);
    assert_true(td_system_node_displacement(full, q, 7, TD_DOF_Y) == q[TD_DOF(7, TD_DOF_Y)]);
    td_system_free(&full);
    td_system_free(&red);
}

/* (a) Every fixed-interface mode kept: the same frequencies as the full model to rounding, at
 * rest and spinning (gyroscopic). */
static void test_all_modes_exact(void **state)
{
    double speeds[2] = {0.0, 300.0};
    int k;
    (void)state;
    for (k = 0; k < 2; k++) {
        double full[128], red[128];
        td_system *sf = rig_system(speeds[k], 0.0), *sr = rig_system(speeds[k], 1e12);
        int nf = vibration_hz(sf, speeds[k], full, 128), nr = vibration_hz(sr, speeds[k], red, 128), i;
        assert_int_equal(td_system_dof_count(sr), td_system_dof_count(sf));
        assert_int_equal(nr, nf);
        for (i = 0; i < nf; i++)
            assert_close(red[i], full[i], 1e-9, 0.0);
        td_system_free(&sf);
        td_system_free(&sr);
    }
}

/* (b) A modest cut-off: the modes below half the first omitted fixed-interface mode within the
 * Ritz bound (f/f_N)^2 of the header; and the error falls as the cut-off rises (checked). */
static void test_error_bound_and_convergence(void **state)
{
    const double speed = 300.0, cutoffs[4] = {1000.0, 2000.0, 5000.0, 1e12};
    double full[128], red[128], prev = INFINITY;
    td_system *sf = rig_system(speed, 0.0), *sr = rig_system(speed, 2000.0);
    double fN = first_omitted(2000.0);
    int nf = vibration_hz(sf, speed, full, 128), nr = vibration_hz(sr, speed, red, 128), i, k, checked = 0;
    (void)state;
    assert_true(isfinite(fN) && fN >= 2000.0);
    for (i = 0; i < nf && full[i] <= 0.5 * fN; i++, checked++) {
        double bound = (full[i] / fN) * (full[i] / fN);
        assert_true(i < nr);
        if (!(fabs(red[i] - full[i]) / full[i] <= bound)) {
            print_error("mode %d: full %.9g Hz, reduced %.9g Hz: error above (f/f_N)^2 = %g\n", i, full[i], red[i],
                        bound);
            fail();
        }
    }
    assert_true(checked >= 12); /* the rig's modes up to ~1 kHz */
    td_system_free(&sf);
    td_system_free(&sr);
    for (k = 0; k < 4; k++) { /* modes below 600 Hz */
        double w = worst_error(speed, cutoffs[k], 600.0);
        assert_true(w < prev);
        prev = w;
    }
    assert_true(prev < 1e-9);
}

/* (c) The steady unbalance response at the sensor (AMB) and retainer nodes: within the dynamic
 * share bound of the header, (f_Omega/f_N)^2 / (1 - (f_Omega/f_N)^2), of the full model's. */
static void test_unbalance_response(void **state)
{
    const double speed = 300.0, cutoff = 2000.0;
    const int nodes[4] = {3, 9, 2, 10};
    td_system *sf = rig_system(speed, 0.0), *sr = rig_system(speed, cutoff);
    td_harmonic *hf = NULL, *hr = NULL;
    td_unbalance u = {1, 0.02, 0.0};
    td_error err;
    double r = speed / (2.0 * TD_PI) / first_omitted(cutoff), bound = r * r / (1.0 - r * r);
    int k;
    (void)state;
    assert_int_equal(td_harmonic_compute(sf, speed, &u, 1, &hf, &err), TD_OK);
    assert_int_equal(td_harmonic_compute(sr, speed, &u, 1, &hr, &err), TD_OK);
    for (k = 0; k < 4; k++) {
        td_orbit of, orr;
        assert_int_equal(td_harmonic_orbit(hf, nodes[k], &of), TD_OK);
        assert_int_equal(td_harmonic_orbit(hr, nodes[k], &orr), TD_OK);
        assert_true(of.major > 0.0);
        assert_close(orr.major, of.major, bound, 0.0);
        assert_close(orr.x_re, of.x_re, bound, bound * of.major);
        assert_close(orr.y_im, of.y_im, bound, bound * of.major);
    }
    /* an interior node (0, the free end) through T */
    assert_int_equal(td_harmonic_orbit(hf, 0, &(td_orbit){0}), TD_OK);
    td_harmonic_free(&hf);
    td_harmonic_free(&hr);
    td_system_free(&sf);
    td_system_free(&sr);
}

/* Peak housing force and time in contact of cases/rub-damped.cfg over its first `t_end` s. */
static void run_rub(double cutoff, double t_end, td_run_summary *s)
{
    char ov_end[64], ov_cut[64];
    const char *ovs[2] = {ov_end, ov_cut};
    td_case *c;
    td_sim *sim = NULL;
    td_output_options out;
    td_error err;
    snprintf(ov_end, sizeof ov_end, "end_time=%.17g", t_end);
    snprintf(ov_cut, sizeof ov_cut, "reduction.cutoff=%.17g", cutoff);
    c = td_test_load_case("cases/rub-damped.cfg", ovs, cutoff > 0.0 ? 2 : 1);
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &sim, &err), TD_OK);
    assert_int_equal(td_system_is_reduced(td_sim_system(sim)), cutoff > 0.0);
    out = *td_case_output_options(c);
    out.hdf5_path[0] = out.csv_path[0] = '\0';
    assert_int_equal(td_run(sim, t_end, &out, NULL, NULL, s, &err), TD_OK);
    td_sim_free(&sim);
    td_case_free(&c);
}

/* (d) Contact: the unbalance step of cases/rub-damped.cfg (ball-bearing retainers, compliant
 * contact) over its first 0.3 s, reduced at 2 kHz (above the rig's modes of interest, 35 Hz whirl
 * and the ~1 kHz contact mode) vs full: peak housing force and time in contact within 2 %. */
static void test_rub_contact_statistics(void **state)
{
    td_run_summary full, red;
    (void)state;
    run_rub(0.0, 0.3, &full);
    run_rub(2000.0, 0.3, &red);
    assert_true(full.contacts > 0 && full.contact_time > 0.05);
    assert_close(red.peak_housing_force, full.peak_housing_force, 0.02, 0.0);
    assert_close(red.contact_time, full.contact_time, 0.02, 0.0);
    assert_int_equal(red.peak_housing_retainer, full.peak_housing_retainer);
}

/* A bare shaft has no node to reduce onto: refused, naming the cut-off. */
static void test_no_boundary(void **state)
{
    td_model *m = NULL;
    td_system *s = NULL;
    td_error err;
    td_shaft_element el = {0.1, 0.05, 0.0, {2.1e11, 8.1e10, 7800.0}};
    int i;
    (void)state;
    assert_int_equal(td_model_create(&m, &err), TD_OK);
    for (i = 0; i < 4; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, &err), TD_OK);
    assert_int_equal(td_model_set_reduction(m, 1000.0, &err), TD_OK);
    assert_int_equal(td_system_create(m, &s, &err), TD_ERR_INVALID);
    assert_null(s);
    assert_non_null(strstr(err.message, "no boundary node"));
    assert_string_equal(err.site.field, "cutoff");
    td_model_free(&m);
}

/* The model's setter checks its value; the cut-off travels with clones and refinements. */
static void test_model_setter(void **state)
{
    td_model *m = td_test_rig_create(0.0, TD_RIG_TAU, TD_RIG_NO_RETAINERS), *fine = NULL;
    td_error err;
    (void)state;
    assert_true(td_model_reduction(m) == 0.0);
    assert_int_equal(td_model_set_reduction(m, -1.0, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.part, "reduction");
    assert_int_equal(td_model_set_reduction(m, NAN, &err), TD_ERR_INVALID);
    assert_int_equal(td_model_set_reduction(m, 1500.0, &err), TD_OK);
    assert_int_equal(td_model_refine(m, 2, &fine, &err), TD_OK);
    assert_true(td_model_reduction(fine) == 1500.0);
    td_model_free(&fine);
    td_model_free(&m);
}

/* A uniform steel shaft, 1 m, 50 mm, 10 elements, on stiff plain bearings at its ends, under
 * gravity along -y, reduced at `cutoff` Hz (0: the full model). Its only boundary nodes are the
 * bearings': every other node is interior. `stepped`: alternate short thin and long thick elements. */
static td_system *sagging_shaft(double cutoff, int stepped)
{
    td_model *m = NULL;
    td_system *s = NULL;
    td_shaft_element el = {0.1, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_bearing b0 = {0, 1e8, 1e8, 0.0, 0.0}, b1 = {10, 1e8, 1e8, 0.0, 0.0};
    td_error err;
    int i;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    for (i = 0; i < 10; i++) {
        if (stepped) { /* short thin necks between long thick pieces: K_gg far from well conditioned */
            el.length = i % 2 ? 0.19 : 0.01;
            el.outer_diameter = i % 2 ? 0.2 : 0.01;
        }
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    }
    assert_int_equal(td_model_add_bearing(m, &b0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b1, NULL), TD_OK);
    assert_int_equal(td_model_set_gravity(m, 0.0, -9.81, NULL), TD_OK);
    assert_int_equal(td_model_set_reduction(m, cutoff, NULL), TD_OK);
    if (td_system_create(m, &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    td_model_free(&m);
    return s;
}

/* The static deflection K q = M g of `s`, expanded to the nodes' y (11 values). */
static void static_sag(const td_system *s, double *y)
{
    int n = td_system_dof_count(s), i, sign;
    double *K = malloc((size_t)n * (size_t)n * sizeof *K), *q = malloc((size_t)n * sizeof *q);
    double *qp = malloc((size_t)td_system_physical_dof_count(s) * sizeof *qp);
    gsl_permutation *p = gsl_permutation_alloc((size_t)n);
    assert_non_null(K), assert_non_null(q), assert_non_null(qp), assert_non_null(p);
    assert_int_equal(td_system_dense(s, TD_MATRIX_STIFFNESS, K, NULL), TD_OK);
    {
        gsl_matrix_view A = gsl_matrix_view_array(K, (size_t)n, (size_t)n); /* symmetric: either order */
        gsl_vector_const_view f = gsl_vector_const_view_array(s->gravity_load, (size_t)n);
        gsl_vector_view x = gsl_vector_view_array(q, (size_t)n);
        assert_int_equal(gsl_linalg_LU_decomp(&A.matrix, p, &sign), 0);
        assert_int_equal(gsl_linalg_LU_solve(&A.matrix, p, &f.vector, &x.vector), 0);
    }
    assert_int_equal(td_system_expand(s, q, qp, NULL), TD_OK);
    for (i = 0; i <= 10; i++)
        y[i] = qp[TD_DOF(i, TD_DOF_Y)];
    gsl_permutation_free(p);
    free(qp), free(q), free(K);
}

/* The reciprocal condition number of the reduced mass matrix of `s` (0 if not positive definite):
 * a basis column that repeats others (to rounding) makes it singular. */
static double mass_rcond(const td_system *s)
{
    int n = td_system_dof_count(s);
    double *M = malloc((size_t)n * (size_t)n * sizeof *M), rcond = 0.0;
    gsl_vector *work = gsl_vector_alloc(3 * (size_t)n);
    gsl_matrix_view A = gsl_matrix_view_array(M, (size_t)n, (size_t)n);
    assert_non_null(M), assert_non_null(work);
    assert_int_equal(td_system_dense(s, TD_MATRIX_MASS, M, NULL), TD_OK);
    gsl_set_error_handler_off();
    if (gsl_linalg_cholesky_decomp1(&A.matrix) != GSL_SUCCESS ||
        gsl_linalg_cholesky_rcond(&A.matrix, &rcond, work) != GSL_SUCCESS)
        rcond = 0.0;
    gsl_vector_free(work);
    free(M);
    return rcond;
}

/* The reduced rotor's statics are the full model's at every node, interior ones included: the
 * shaft's own weight is a load on the interior that the constraint modes (no interior load) leave
 * out, and the kept modes hold only part of. Without the gravity load's static correction the
 * mid-span sag was 20 % short with no mode kept and 7e-4 of the peak at 2 kHz. */
static void test_own_weight_sag(void **state)
{
    /* 1e12 Hz keeps every mode: the basis then spans the whole interior, with nothing to add (a
     * correction from the solve's rounding made the stepped shaft's basis singular) */
    const double cutoffs[5] = {1.0, 300.0, 2000.0, 1e12, 1e12};
    double full[11], red[11], peak = 0.0, rcond = 0.0;
    td_system *s = NULL;
    int c, i;
    (void)state;
    for (c = 0; c < 5; c++) {
        double worst = 0.0;
        if (c == 0 || c == 4) {
            s = sagging_shaft(0.0, c == 4);
            static_sag(s, full);
            rcond = mass_rcond(s);
            td_system_free(&s);
            for (i = 0, peak = 0.0; i <= 10; i++)
                peak = fmax(peak, fabs(full[i]));
        }
        s = sagging_shaft(cutoffs[c], c == 4);
        static_sag(s, red);
        for (i = 0; i <= 10; i++)
            worst = fmax(worst, fabs(red[i] - full[i]));
        print_message("own-weight sag%s reduced at %.0f Hz (%d modes + %d static corrections): off by %.3g of the peak "
                      "%.4g m\n",
                      c == 4 ? " (stepped shaft)" : "", cutoffs[c], td_system_mode_count(s),
                      td_system_static_correction_count(s), worst / peak, peak);
        assert_true(worst <= 1e-9 * peak);
        assert_true(mass_rcond(s) > 1e-3 * rcond);
        if (c >= 3) { /* all modes kept: the deflection is in the basis already, nothing to add */
            assert_int_equal(td_system_static_correction_count(s), 0);
            assert_int_equal(td_system_dof_count(s), td_system_physical_dof_count(s));
        }
        td_system_free(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coordinate_map),
        cmocka_unit_test(test_all_modes_exact),
        cmocka_unit_test(test_error_bound_and_convergence),
        cmocka_unit_test(test_unbalance_response),
        cmocka_unit_test(test_rub_contact_statistics),
        cmocka_unit_test(test_model_setter),
        cmocka_unit_test(test_no_boundary),
        cmocka_unit_test(test_own_weight_sag),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
