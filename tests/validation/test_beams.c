/*
 * Validation of the shaft element against beam theory: natural frequencies of non-rotating
 * uniform beams in one bending plane (x-z; the y-z plane is its mirror) against closed forms.
 *
 * The consistent mass carries rotary inertia, so the Euler-Bernoulli element converges to the
 * RAYLEIGH beam, omega^2 = EI k^4 / (rho A (1 + r^2 k^2)), r^2 = I / A; the Euler-Bernoulli checks
 * use a beam slender enough (L / d = 1000) that rotary inertia moves the first three frequencies by
 * less than 3e-6 (printed). Timoshenko: shear coefficient of Hutchinson (2001), elements.h.
 * Tables of relative errors per mesh go to stdout.
 */
#include "td_test.h"

#include "model/elements.h"
#include "touchdown/touchdown.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_sort_vector.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define NMESH 6
static const int meshes[NMESH] = {2, 4, 8, 16, 32, 64};
static const td_material steel = {2.11e11, 8.1e10, 7810.0};

typedef enum { PINNED_PINNED, FREE_FREE } supports;

/* The first `nmodes` flexible natural frequencies (rad/s) of a uniform solid beam of n elements. */
static void fe_frequencies(int n, double L, double d, td_beam_theory beam, td_mass_form mass, supports bc, int nmodes,
                           double *omega)
{
    td_model *m = NULL;
    td_system *s = NULL;
    td_shaft_element el;
    td_shaft_options opt = {beam, mass, 0.0, 0.0, TD_SHEAR_HUTCHINSON, 0.0};
    double *K, *M;
    int ndof, i, j, k, nkeep = 0, *keep, skip;
    gsl_matrix *a, *b;
    gsl_vector *ev;
    gsl_eigen_gensymm_workspace *w;
    el.length = L / n;
    el.outer_diameter = d;
    el.inner_diameter = 0.0;
    el.material = steel;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_set_shaft_options(m, &opt, NULL), TD_OK);
    for (i = 0; i < n; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    ndof = td_system_dof_count(s);
    K = malloc(sizeof *K * (size_t)ndof * (size_t)ndof);
    M = malloc(sizeof *M * (size_t)ndof * (size_t)ndof);
    keep = malloc(sizeof *keep * (size_t)ndof);
    assert_non_null(K);
    assert_non_null(M);
    assert_non_null(keep);
    assert_int_equal(td_system_dense(s, TD_MATRIX_STIFFNESS, K, NULL), TD_OK);
    assert_int_equal(td_system_dense(s, TD_MATRIX_MASS, M, NULL), TD_OK);
    /* x-z plane: x and phi of every node, less x at the pinned ends */
    for (k = 0; k <= n; k++) {
        if (!(bc == PINNED_PINNED && (k == 0 || k == n)))
            keep[nkeep++] = TD_DOF(k, TD_DOF_X);
        keep[nkeep++] = TD_DOF(k, TD_DOF_PHI);
    }
    a = gsl_matrix_alloc((size_t)nkeep, (size_t)nkeep);
    b = gsl_matrix_alloc((size_t)nkeep, (size_t)nkeep);
    ev = gsl_vector_alloc((size_t)nkeep);
    w = gsl_eigen_gensymm_alloc((size_t)nkeep);
    assert_non_null(a);
    assert_non_null(b);
    assert_non_null(ev);
    assert_non_null(w);
    for (i = 0; i < nkeep; i++)
        for (j = 0; j < nkeep; j++) {
            gsl_matrix_set(a, (size_t)i, (size_t)j, K[keep[i] + (size_t)keep[j] * ndof]);
            gsl_matrix_set(b, (size_t)i, (size_t)j, M[keep[i] + (size_t)keep[j] * ndof]);
        }
    assert_int_equal(gsl_eigen_gensymm(a, b, ev, w), GSL_SUCCESS);
    gsl_sort_vector(ev);
    skip = bc == FREE_FREE ? 2 : 0; /* free-free: rigid translation and tilt */
    if (bc == FREE_FREE)
        assert_true(fabs(gsl_vector_get(ev, 1)) < 1e-8 * gsl_vector_get(ev, 2));
    for (i = 0; i < nmodes; i++)
        omega[i] = i + skip < nkeep ? sqrt(gsl_vector_get(ev, (size_t)(i + skip))) : NAN;
    gsl_eigen_gensymm_free(w);
    gsl_vector_free(ev);
    gsl_matrix_free(b);
    gsl_matrix_free(a);
    free(keep);
    free(M);
    free(K);
    td_system_free(&s);
    td_model_free(&m);
}

static void section(double d, double *A, double *I)
{
    *A = TD_PI * d * d / 4.0;
    *I = TD_PI * d * d * d * d / 64.0;
}

/* Euler-Bernoulli, simply supported: omega_n = (n pi / L)^2 sqrt(EI / (rho A)). */
static double eb_pinned(int mode, double L, double d)
{
    double A, I, k = mode * TD_PI / L;
    section(d, &A, &I);
    return k * k * sqrt(steel.E * I / (steel.density * A));
}

/* Rayleigh beam (rotary inertia, no shear), simply supported: omega^2 = EI k^4 / (rho A (1 + r^2 k^2)). */
static double rayleigh_pinned(int mode, double L, double d)
{
    double A, I, k = mode * TD_PI / L;
    section(d, &A, &I);
    return sqrt(steel.E * I * pow(k, 4) / (steel.density * A * (1.0 + I / A * k * k)));
}

/* Timoshenko beam (rotary inertia and shear), simply supported, w = W sin kz, psi = Psi cos kz:
 *   rho A rho I w^4 - (rho A EI k^2 + rho A kappa G A + kappa G A rho I k^2) w^2 + kappa G A EI k^4 = 0,
 * the lower root of this quadratic in w^2 is the flexural branch. */
static double timoshenko_pinned(int mode, double L, double d, double kappa)
{
    double A, I, k = mode * TD_PI / L, rho = steel.density, kGA, qa, qb, qc;
    section(d, &A, &I);
    kGA = kappa * steel.G * A;
    qa = rho * A * rho * I;
    qb = rho * A * steel.E * I * k * k + rho * A * kGA + kGA * rho * I * k * k;
    qc = kGA * steel.E * I * pow(k, 4);
    return sqrt(2.0 * qc / (qb + sqrt(qb * qb - 4.0 * qa * qc))); /* smaller root, cancellation-free */
}

/* Euler-Bernoulli free-free: beta_n L roots of cos(bL) cosh(bL) = 1, polished by Newton from the
 * tabulated 4.730040745, 7.853204624, 10.99560784 (so the reference carries 15 digits, not 10). */
static double eb_free(int mode, double L, double d)
{
    static const double tabulated[3] = {4.730040745, 7.853204624, 10.99560784};
    double A, I, x = tabulated[mode - 1], b;
    int it;
    for (it = 0; it < 20; it++) {
        double f = cos(x) * cosh(x) - 1.0, df = cos(x) * sinh(x) - sin(x) * cosh(x);
        x -= f / df;
    }
    assert_close(x, tabulated[mode - 1], 1e-9, 0.0);
    section(d, &A, &I);
    b = x / L;
    return b * b * sqrt(steel.E * I / (steel.density * A));
}

/* Fill err[mesh][mode] with relative errors against ref[mode], print a table with the observed
 * order of convergence log2(err(n/2) / err(n)), and check that every error above `floor` (round-off
 * or a known model difference) falls with refinement. */
static void convergence_table(const char *title, double L, double d, td_beam_theory beam, td_mass_form mass,
                              supports bc, const double ref[3], double floor, double err[NMESH][3])
{
    int i, j;
    printf("\n%s (L = %g m, d = %g m, L/d = %g)\n"
           "  elements   mode 1 rel err (order)   mode 2 rel err (order)   mode 3 rel err (order)\n",
           title, L, d, L / d);
    for (i = 0; i < NMESH; i++) {
        double w[3];
        fe_frequencies(meshes[i], L, d, beam, mass, bc, 3, w);
        printf("  %8d", meshes[i]);
        for (j = 0; j < 3; j++) {
            err[i][j] = isnan(w[j]) ? NAN : (w[j] - ref[j]) / ref[j];
            if (i > 0)
                printf("   %11.3e (%5.2f)", err[i][j], log2(fabs(err[i - 1][j] / err[i][j])));
            else
                printf("   %11.3e        ", err[i][j]);
        }
        printf("\n");
    }
    for (i = 1; i < NMESH; i++)
        for (j = 0; j < 3; j++)
            if (!isnan(err[i - 1][j]) && fabs(err[i - 1][j]) > floor)
                assert_true(fabs(err[i][j]) < fabs(err[i - 1][j]));
    fflush(stdout);
}

/* Index of a mesh in `meshes`. */
static int mesh_index(int elements)
{
    int i;
    for (i = 0; i < NMESH && meshes[i] != elements; i++)
        ;
    assert_true(i < NMESH);
    return i;
}

/* Observed order between `elements` / 2 and `elements` for each mode lies in [lo, hi]. */
static void check_order(double err[NMESH][3], int elements, double lo, double hi)
{
    int i = mesh_index(elements), j;
    for (j = 0; j < 3; j++) {
        double p = log2(fabs(err[i - 1][j] / err[i][j]));
        assert_true(p >= lo && p <= hi);
    }
}

/* All three modes within `tol` at `elements`. */
static void check_within(double err[NMESH][3], int elements, double tol)
{
    int i = mesh_index(elements), j;
    for (j = 0; j < 3; j++)
        assert_true(fabs(err[i][j]) < tol);
}

static void test_euler_bernoulli_pinned_pinned(void **state)
{
    double L = 1.0, d = 1e-3, ref[3], eb[3], err[NMESH][3], w[3];
    int j;
    (void)state;
    for (j = 0; j < 3; j++) {
        ref[j] = rayleigh_pinned(j + 1, L, d);
        eb[j] = eb_pinned(j + 1, L, d);
        assert_true(fabs(eb[j] - ref[j]) / eb[j] < 3e-6); /* rotary inertia negligible here */
    }
    printf("\nEB vs Rayleigh closed form, pinned-pinned, L/d = 1000: (w_EB - w_R) / w_EB = %.2e %.2e %.2e\n",
           (eb[0] - ref[0]) / eb[0], (eb[1] - ref[1]) / eb[1], (eb[2] - ref[2]) / eb[2]);
    convergence_table("Pinned-pinned, EB element, consistent mass, vs Rayleigh closed form", L, d,
                      TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, PINNED_PINNED, ref, 1e-8, err);
    for (j = 0; j < 3; j++)
        assert_true(err[0][j] > 0.0 && err[mesh_index(32)][j] > 0.0); /* consistent mass: from above */
    check_within(err, 16, 1e-3);    /* 16 elements: within 0.1 % (8 elements: mode 3 is 0.13 % off) */
    check_order(err, 16, 3.8, 4.2); /* O(h^4) */
    check_order(err, 32, 3.8, 4.2);
    /* and against the Euler-Bernoulli closed form itself at 16 elements */
    fe_frequencies(16, L, d, TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, PINNED_PINNED, 3, w);
    for (j = 0; j < 3; j++)
        assert_close(w[j], eb[j], 1e-3, 0.0);
}

static void test_euler_bernoulli_free_free(void **state)
{
    double L = 1.0, d = 1e-4, ref[3], err[NMESH][3];
    int j;
    (void)state;
    for (j = 0; j < 3; j++)
        ref[j] = eb_free(j + 1, L, d);
    /* L/d = 1e4: rotary inertia lowers the frequencies by ~1e-8 (the floor of the table) */
    convergence_table("Free-free, EB element, consistent mass, vs Euler-Bernoulli closed form", L, d,
                      TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, FREE_FREE, ref, 1e-7, err);
    check_within(err, 16, 1e-3);
    check_order(err, 32, 3.8, 4.2);
    for (j = 0; j < 3; j++)
        assert_true(fabs(err[NMESH - 1][j]) < 1e-6);
}

/* A stocky beam: the EB element with consistent mass converges to the Rayleigh beam, not to EB. */
static void test_rayleigh_stocky(void **state)
{
    double L = 0.5, d = 0.05, ref[3], err[NMESH][3];
    int j;
    (void)state;
    for (j = 0; j < 3; j++)
        ref[j] = rayleigh_pinned(j + 1, L, d);
    convergence_table("Pinned-pinned, EB element, consistent mass, vs Rayleigh closed form", L, d,
                      TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, PINNED_PINNED, ref, 1e-9, err);
    check_within(err, 16, 1e-3);
    check_order(err, 32, 3.8, 4.2);
    for (j = 0; j < 3; j++) {
        double eb = eb_pinned(j + 1, L, d);
        assert_true(fabs(err[NMESH - 1][j]) < 1e-6);
        assert_true((eb - ref[j]) / eb > 1e-3 * (j + 1) * (j + 1)); /* EB is visibly different here */
    }
}

/* Lumped mass (half mass and half rotary inertia at each end) converges to Rayleigh too, from
 * below, and at least at O(h^2) (the rotary-inertia lumping is a trapezoidal rule). */
static void test_lumped_mass(void **state)
{
    double L = 0.5, d = 0.05, ref[3], err[NMESH][3];
    int i, j;
    (void)state;
    for (j = 0; j < 3; j++)
        ref[j] = rayleigh_pinned(j + 1, L, d);
    convergence_table("Pinned-pinned, EB element, LUMPED mass, vs Rayleigh closed form", L, d, TD_BEAM_EULER_BERNOULLI,
                      TD_MASS_LUMPED, PINNED_PINNED, ref, 1e-9, err);
    for (i = mesh_index(4); i < NMESH; i++)
        for (j = 0; j < 3; j++)
            assert_true(err[i][j] < 0.0);
    check_within(err, 16, 1e-3);
    check_order(err, 64, 1.9, 4.2);
}

/* Timoshenko, simply supported, against the closed form of the Timoshenko beam. The element's
 * interdependent interpolation ties its constant shear strain to EI psi'' by the static relation
 * kappa G A gamma = EI psi'' (up to sign); a vibrating beam breaks that relation by
 * rho I omega^2 psi / (kappa G A), so on a stocky beam the frequencies converge at O(h^2),
 * not at O(h^4) as the EB element does. */
static void test_timoshenko_pinned_pinned(void **state)
{
    static const double slenderness[2] = {10.0, 4.0};
    double d = 0.05, ref[3], err[NMESH][3], kappa;
    td_shaft_element el = {0.1, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    int j, r;
    (void)state;
    kappa = td_shaft_shear_coefficient(&el, TD_SHEAR_HUTCHINSON, 0.0);
    printf("\nTimoshenko: Hutchinson shear coefficient kappa = %.6f (nu = %.6f)\n", kappa, td_shaft_poisson(&el));
    for (r = 0; r < 2; r++) {
        double L = slenderness[r] * d;
        for (j = 0; j < 3; j++) {
            ref[j] = timoshenko_pinned(j + 1, L, d, kappa);
            assert_true(ref[j] < rayleigh_pinned(j + 1, L, d)); /* shear lowers the frequency */
        }
        convergence_table("Pinned-pinned, Timoshenko element, consistent mass, vs Timoshenko closed form", L, d,
                          TD_BEAM_TIMOSHENKO, TD_MASS_CONSISTENT, PINNED_PINNED, ref, 1e-9, err);
        for (j = 0; j < 3; j++)
            assert_true(err[NMESH - 1][j] > 0.0);
        check_within(err, r == 0 ? 32 : 64, 1e-3); /* within 0.1 %: 32 elements at L/d = 10, 64 at L/d = 4 */
        check_order(err, 64, 1.9, 2.2);
    }
}

/* Timoshenko tends to the EB element for slender shafts, the gap shrinking as (d / L)^2; stocky ones are lower. */
static void test_timoshenko_vs_euler_bernoulli(void **state)
{
    static const double ratios[4] = {5.0, 20.0, 100.0, 200.0};
    double d = 0.05, gap[4][3];
    int r, j;
    (void)state;
    printf("\nTimoshenko vs EB element (both 32 elements, consistent mass, pinned-pinned): (w_T - w_EB) / w_EB\n"
           "     L/d           mode 1           mode 2           mode 3\n");
    for (r = 0; r < 4; r++) {
        double wt[3], we[3];
        fe_frequencies(32, ratios[r] * d, d, TD_BEAM_TIMOSHENKO, TD_MASS_CONSISTENT, PINNED_PINNED, 3, wt);
        fe_frequencies(32, ratios[r] * d, d, TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, PINNED_PINNED, 3, we);
        printf("  %6g", ratios[r]);
        for (j = 0; j < 3; j++) {
            gap[r][j] = (wt[j] - we[j]) / we[j];
            printf("   %14.3e", gap[r][j]);
            assert_true(gap[r][j] < 0.0); /* always lower */
        }
        printf("\n");
    }
    assert_true(fabs(gap[3][0]) < 1e-4);                 /* L/d = 200: mode 1 within 1e-4 */
    assert_close(gap[2][0] / gap[3][0], 4.0, 0.01, 0.0); /* O((d/L)^2) */
    assert_true(gap[0][0] < -0.02);                      /* L/d = 5: several per cent lower */
    fflush(stdout);
}

int main(void)
{
    /* clang-format off */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_euler_bernoulli_pinned_pinned),
        cmocka_unit_test(test_euler_bernoulli_free_free),
        cmocka_unit_test(test_rayleigh_stocky),
        cmocka_unit_test(test_lumped_mass),
        cmocka_unit_test(test_timoshenko_pinned_pinned),
        cmocka_unit_test(test_timoshenko_vs_euler_bernoulli),
    };
    /* clang-format on */
    gsl_set_error_handler_off();
    return cmocka_run_group_tests(tests, NULL, NULL);
}
