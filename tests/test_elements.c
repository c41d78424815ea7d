/* Shaft element matrices (lib/model/elements.c) against textbook closed forms and rigid-body facts. */
#include "td_test.h"

#include "model/elements.h"
#include "touchdown/touchdown.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdlib.h>

/* local element indices, elements.h order */
enum { X1 = 0, Y1 = 1, T1 = 2, P1 = 3, X2 = 4, Y2 = 5, T2 = 6, P2 = 7 };
#define E8(a, i, j) ((a)[8 * (i) + (j)])

static const td_material steel = {2.11e11, 8.1e10, 7810.0};

static td_shaft_element element(double L, double d, double di)
{
    td_shaft_element el;
    el.length = L;
    el.outer_diameter = d;
    el.inner_diameter = di;
    el.material = steel;
    return el;
}

/* u^T A v for an n x n row-major (or symmetric column-major) matrix */
static double quad(const double *A, const double *u, const double *v, int n)
{
    double s = 0.0;
    int i, j;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            s += u[i] * A[n * i + j] * v[j];
    return s;
}

/* Rigid motions of a shaft whose node k sits at z[k]: translations along x and y, tilts in the
 * x-z plane (x = z, phi = +1) and the y-z plane (y = z, theta = -dy/dz = -1), dofs.h. */
static void rigid_modes(const double *z, int nodes, double *u /* 4 x 4 nodes */)
{
    int k, n = 4 * nodes;
    for (k = 0; k < 4 * n; k++)
        u[k] = 0.0;
    for (k = 0; k < nodes; k++) {
        u[0 * n + 4 * k + TD_DOF_X] = 1.0;
        u[1 * n + 4 * k + TD_DOF_Y] = 1.0;
        u[2 * n + 4 * k + TD_DOF_X] = z[k];
        u[2 * n + 4 * k + TD_DOF_PHI] = 1.0;
        u[3 * n + 4 * k + TD_DOF_Y] = z[k];
        u[3 * n + 4 * k + TD_DOF_THETA] = -1.0;
    }
}

/* Number of eigenvalues of the symmetric n x n matrix A below tol * max |eigenvalue|. */
static int count_zero_eigenvalues(const double *A, int n, double tol)
{
    gsl_matrix *a = gsl_matrix_alloc((size_t)n, (size_t)n);
    gsl_vector *ev = gsl_vector_alloc((size_t)n);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc((size_t)n);
    double big = 0.0;
    int i, j, zeros = 0;
    assert_non_null(a);
    assert_non_null(ev);
    assert_non_null(w);
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            gsl_matrix_set(a, (size_t)i, (size_t)j, A[n * i + j]);
    assert_int_equal(gsl_eigen_symm(a, ev, w), GSL_SUCCESS);
    for (i = 0; i < n; i++)
        big = fmax(big, fabs(gsl_vector_get(ev, (size_t)i)));
    for (i = 0; i < n; i++) {
        assert_true(gsl_vector_get(ev, (size_t)i) > -tol * big); /* positive semi-definite */
        if (fabs(gsl_vector_get(ev, (size_t)i)) < tol * big)
            zeros++;
    }
    gsl_eigen_symm_free(w);
    gsl_vector_free(ev);
    gsl_matrix_free(a);
    return zeros;
}

static void check_symmetry(const double *M, const double *K, const double *G)
{
    int i, j;
    double mm = td_test_max_abs(M, 64), mk = td_test_max_abs(K, 64), mg = td_test_max_abs(G, 64);
    for (i = 0; i < 8; i++)
        for (j = 0; j < 8; j++) {
            assert_close(E8(M, i, j), E8(M, j, i), 0.0, 1e-15 * mm);
            assert_close(E8(K, i, j), E8(K, j, i), 0.0, 1e-15 * mk);
            assert_close(E8(G, i, j), -E8(G, j, i), 0.0, 1e-15 * mg);
        }
    for (i = 0; i < 8; i++)
        assert_true(E8(G, i, i) == 0.0);
}

static void test_symmetry_all_forms(void **state)
{
    double M[64], K[64], G[64];
    td_shaft_element els[2];
    int e, b, f;
    (void)state;
    els[0] = element(0.17, 0.05, 0.0);
    els[1] = element(0.05, 0.08, 0.06); /* stocky and hollow: Phi large */
    for (e = 0; e < 2; e++)
        for (b = 0; b < 2; b++)
            for (f = 0; f < 2; f++) {
                td_shaft_element_matrices(&els[e], (td_beam_theory)b, (td_mass_form)f, M, K, G);
                check_symmetry(M, K, G);
            }
}

/* Euler-Bernoulli consistent entries, Przemieniecki (1968) / Friswell et al. (2010) eq. 5.74, 5.119. */
static void test_euler_bernoulli_entries(void **state)
{
    td_shaft_element el = element(0.25, 0.05, 0.02);
    double M[64], K[64], G[64], A, I, L = el.length, rho = steel.density, EI;
    (void)state;
    td_shaft_section(&el, &A, &I);
    assert_close(A, TD_PI / 4.0 * (0.05 * 0.05 - 0.02 * 0.02), 1e-15, 0.0);
    assert_close(I, TD_PI / 64.0 * (pow(0.05, 4) - pow(0.02, 4)), 1e-15, 0.0);
    EI = steel.E * I;
    td_shaft_element_matrices(&el, TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, M, K, G);

    assert_close(E8(K, X1, X1), 12.0 * EI / (L * L * L), 1e-14, 0.0);
    assert_close(E8(K, Y1, Y1), 12.0 * EI / (L * L * L), 1e-14, 0.0);
    assert_close(E8(K, X1, X2), -12.0 * EI / (L * L * L), 1e-14, 0.0);
    /* phi = +dx/dz: a positive end slope of the x-z plane couples as +6EI/L^2 at node 1 */
    assert_close(E8(K, X1, P1), 6.0 * EI / (L * L), 1e-14, 0.0);
    assert_close(E8(K, X1, P2), 6.0 * EI / (L * L), 1e-14, 0.0);
    assert_close(E8(K, X2, P1), -6.0 * EI / (L * L), 1e-14, 0.0);
    /* theta = -dy/dz: the y-z plane couplings change sign */
    assert_close(E8(K, Y1, T1), -6.0 * EI / (L * L), 1e-14, 0.0);
    assert_close(E8(K, Y2, T1), 6.0 * EI / (L * L), 1e-14, 0.0);
    assert_close(E8(K, P1, P1), 4.0 * EI / L, 1e-14, 0.0);
    assert_close(E8(K, T1, T1), 4.0 * EI / L, 1e-14, 0.0);
    assert_close(E8(K, P1, P2), 2.0 * EI / L, 1e-14, 0.0);
    assert_close(E8(K, T1, T2), 2.0 * EI / L, 1e-14, 0.0);
    assert_true(E8(K, X1, Y1) == 0.0 && E8(K, X1, T1) == 0.0 && E8(K, P1, T1) == 0.0);

    /* translational 156/420 = 13/35 plus rotary 36/30 = 6/5 */
    assert_close(E8(M, X1, X1), 13.0 / 35.0 * rho * A * L + 6.0 / 5.0 * rho * I / L, 1e-14, 0.0);
    assert_close(E8(M, X1, X2), 9.0 / 70.0 * rho * A * L - 6.0 / 5.0 * rho * I / L, 1e-14, 0.0);
    assert_close(E8(M, X1, P1), 11.0 / 210.0 * rho * A * L * L + rho * I / 10.0, 1e-14, 0.0);
    assert_close(E8(M, Y1, T1), -(11.0 / 210.0 * rho * A * L * L + rho * I / 10.0), 1e-14, 0.0);
    assert_close(E8(M, X1, P2), -13.0 / 420.0 * rho * A * L * L + rho * I / 10.0, 1e-14, 0.0);
    assert_close(E8(M, P1, P1), rho * A * L * L * L / 105.0 + 2.0 / 15.0 * rho * I * L, 1e-14, 0.0);
    assert_close(E8(M, P1, P2), -rho * A * L * L * L / 140.0 - rho * I * L / 30.0, 1e-14, 0.0);
    assert_close(E8(M, T1, T2), -rho * A * L * L * L / 140.0 - rho * I * L / 30.0, 1e-14, 0.0);

    /* gyroscopic: polar inertia rho J = 2 rho I per length, Nelson & McVaugh (1976) */
    assert_close(E8(G, X1, Y1), 2.0 * rho * I * 36.0 / (30.0 * L), 1e-14, 0.0);
    assert_close(E8(G, T1, P1), 2.0 * rho * I * 4.0 * L / 30.0, 1e-14, 0.0); /* + like a disc's +Ip */
    assert_close(E8(G, P1, T1), -2.0 * rho * I * 4.0 * L / 30.0, 1e-14, 0.0);
    assert_true(E8(G, X1, X2) == 0.0 && E8(G, X1, P1) == 0.0);
}

/* Rigid motions: zero strain energy, mass and inertia from the quadratic forms. */
static void test_rigid_body_single_element(void **state)
{
    double M[64], K[64], G[64], u[32], z[2];
    td_shaft_element el = element(0.3, 0.06, 0.03);
    double A, I, L = el.length, rho = steel.density;
    int b, r;
    (void)state;
    td_shaft_section(&el, &A, &I);
    z[0] = -L / 2.0; /* tilts about the element's centre */
    z[1] = L / 2.0;
    rigid_modes(z, 2, u);
    for (b = 0; b < 2; b++) {
        double Ku[8];
        int i, j;
        td_shaft_element_matrices(&el, (td_beam_theory)b, TD_MASS_CONSISTENT, M, K, G);
        for (r = 0; r < 4; r++) {
            for (i = 0; i < 8; i++) {
                Ku[i] = 0.0;
                for (j = 0; j < 8; j++)
                    Ku[i] += E8(K, i, j) * u[8 * r + j];
            }
            assert_true(td_test_max_abs(Ku, 8) <= 1e-12 * td_test_max_abs(K, 64));
        }
        assert_int_equal(count_zero_eigenvalues(K, 8, 1e-12), 4);
        /* translation: the element mass; tilt about the centre: rho A L^3 / 12 + rho I L */
        assert_close(quad(M, &u[0], &u[0], 8), rho * A * L, 1e-14, 0.0);
        assert_close(quad(M, &u[8], &u[8], 8), rho * A * L, 1e-14, 0.0);
        assert_close(quad(M, &u[16], &u[16], 8), rho * A * L * L * L / 12.0 + rho * I * L, 1e-13, 0.0);
        assert_close(quad(M, &u[24], &u[24], 8), rho * A * L * L * L / 12.0 + rho * I * L, 1e-13, 0.0);
        /* translation and tilt are M-orthogonal about the centre */
        assert_close(quad(M, &u[0], &u[16], 8), 0.0, 0.0, 1e-14 * rho * A * L * L);
        /* gyroscopic: unit theta-tilt against unit phi-tilt gives the polar inertia rho J L = 2 rho I L */
        assert_close(quad(G, &u[24], &u[16], 8), -2.0 * rho * I * L, 1e-13, 0.0); /* theta = -1 */
        assert_close(quad(G, &u[0], &u[8], 8), 0.0, 0.0, 1e-14 * td_test_max_abs(G, 64));
    }
    /* lumped: half the mass at each end, so the tilt inertia about the centre is rho A L (L/2)^2 */
    td_shaft_element_matrices(&el, TD_BEAM_EULER_BERNOULLI, TD_MASS_LUMPED, M, K, G);
    assert_close(quad(M, &u[0], &u[0], 8), rho * A * L, 1e-14, 0.0);
    assert_close(quad(M, &u[16], &u[16], 8), rho * A * L * L * L / 4.0 + rho * I * L, 1e-13, 0.0);
    assert_close(quad(G, &u[24], &u[16], 8), -2.0 * rho * I * L, 1e-13, 0.0);
    for (r = 0; r < 64; r++)
        if (r % 9 != 0)
            assert_true(M[r] == 0.0); /* diagonal */
}

/* A free shaft of unequal, partly hollow elements assembled through td_system. */
static void test_rigid_body_free_shaft(void **state)
{
    static const double lengths[5] = {0.1, 0.25, 0.05, 0.3, 0.2};
    static const double inner[5] = {0.0, 0.02, 0.0, 0.04, 0.0};
    int b;
    (void)state;
    for (b = 0; b < 2; b++) {
        td_model *m = NULL;
        td_system *s = NULL;
        td_shaft_options opt = {(td_beam_theory)b, TD_MASS_CONSISTENT, 0.0, 0.0, TD_SHEAR_HUTCHINSON, 0.0};
        double z[6], *K, *M, *u, total = 0.0;
        int i, j, r, n;
        assert_int_equal(td_model_create(&m, NULL), TD_OK);
        assert_int_equal(td_model_set_shaft_options(m, &opt, NULL), TD_OK);
        z[0] = 0.0;
        for (i = 0; i < 5; i++) {
            td_shaft_element el = element(lengths[i], 0.05, inner[i]);
            double A;
            td_shaft_section(&el, &A, NULL);
            total += steel.density * A * lengths[i];
            assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
            z[i + 1] = z[i] + lengths[i];
        }
        assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
        n = td_system_dof_count(s);
        assert_int_equal(n, 24);
        K = malloc(sizeof *K * (size_t)(n * n));
        M = malloc(sizeof *M * (size_t)(n * n));
        u = malloc(sizeof *u * (size_t)(4 * n));
        assert_non_null(K);
        assert_non_null(M);
        assert_non_null(u);
        assert_int_equal(td_system_dense(s, TD_MATRIX_STIFFNESS, K, NULL), TD_OK);
        assert_int_equal(td_system_dense(s, TD_MATRIX_MASS, M, NULL), TD_OK);
        rigid_modes(z, 6, u);
        for (r = 0; r < 4; r++)
            for (i = 0; i < n; i++) {
                double Ku = 0.0;
                for (j = 0; j < n; j++)
                    Ku += K[i + j * n] * u[r * n + j];
                assert_close(Ku, 0.0, 0.0, 1e-11 * td_test_max_abs(K, n * n));
            }
        assert_int_equal(count_zero_eigenvalues(K, n, 1e-12), 4);
        assert_close(quad(M, &u[0], &u[0], n), total, 1e-14, 0.0);
        assert_close(quad(M, &u[n], &u[n], n), total, 1e-14, 0.0);
        free(u);
        free(M);
        free(K);
        td_system_free(&s);
        td_model_free(&m);
    }
}

/* Timoshenko with a vanishing shear parameter is the Euler-Bernoulli element. Phi scales as
 * (d / L)^2 (G cannot be raised alone: nu = E / 2G - 1 must stay physical), so a hair-thin
 * element (d / L = 1e-6, Phi ~ 2e-12) must agree to O(Phi). */
static void test_timoshenko_limit(void **state)
{
    td_shaft_element el = element(1.0, 1e-6, 0.0);
    double Mt[64], Kt[64], Gt[64], Me[64], Ke[64], Ge[64], phi;
    int i;
    (void)state;
    phi = td_shaft_shear_parameter(&el, TD_BEAM_TIMOSHENKO, td_shaft_shear_coefficient(&el, TD_SHEAR_HUTCHINSON, 0.0));
    assert_true(phi > 0.0 && phi < 1e-11);
    assert_true(td_shaft_shear_parameter(&el, TD_BEAM_EULER_BERNOULLI, 1.0) == 0.0);
    td_shaft_element_matrices(&el, TD_BEAM_TIMOSHENKO, TD_MASS_CONSISTENT, Mt, Kt, Gt);
    td_shaft_element_matrices(&el, TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, Me, Ke, Ge);
    for (i = 0; i < 64; i++) {
        assert_close(Mt[i], Me[i], 20.0 * phi, 1e-15 * td_test_max_abs(Me, 64));
        assert_close(Kt[i], Ke[i], 20.0 * phi, 1e-15 * td_test_max_abs(Ke, 64));
        assert_close(Gt[i], Ge[i], 20.0 * phi, 1e-15 * td_test_max_abs(Ge, 64));
    }
}

/* Timoshenko stiffness against the cantilever flexibility with shear, by the unit-load method:
 * tip deflection under a tip force P L^3 / (3 EI) + P L / (kappa G A), slope P L^2 / (2 EI);
 * under a tip moment: deflection M L^2 / (2 EI), slope M L / EI. */
static void test_timoshenko_cantilever_flexibility(void **state)
{
    td_shaft_element el = element(0.1, 0.08, 0.03);
    double M[64], K[64], A, I, EI, kGA, L = el.length, k11, k12, k22, det;
    double f11, f12, f22;
    (void)state;
    td_shaft_section(&el, &A, &I);
    EI = steel.E * I;
    kGA = td_shaft_shear_coefficient(&el, TD_SHEAR_HUTCHINSON, 0.0) * steel.G * A;
    td_shaft_element_matrices(&el, TD_BEAM_TIMOSHENKO, TD_MASS_CONSISTENT, M, K, NULL);
    assert_true(
        td_shaft_shear_parameter(&el, TD_BEAM_TIMOSHENKO, td_shaft_shear_coefficient(&el, TD_SHEAR_HUTCHINSON, 0.0)) >
        0.3); /* a real shear effect */
    /* node 1 clamped: the x-z block of node 2 inverted is the tip flexibility */
    k11 = E8(K, X2, X2);
    k12 = E8(K, X2, P2);
    k22 = E8(K, P2, P2);
    det = k11 * k22 - k12 * k12;
    f11 = k22 / det;
    f12 = -k12 / det;
    f22 = k11 / det;
    assert_close(f11, L * L * L / (3.0 * EI) + L / kGA, 1e-13, 0.0);
    assert_close(f12, L * L / (2.0 * EI), 1e-13, 0.0); /* a tip force tilts the tip by +dx/dz */
    assert_close(f22, L / EI, 1e-13, 0.0);
    /* y-z plane: same flexibility, slope sign flipped (theta = -dy/dz) */
    assert_close(E8(K, Y2, T2), -k12, 1e-14, 0.0);
}

/* Hutchinson (2001): solid 6 (1 + nu)^2 / (7 + 12 nu + 4 nu^2); thin tube (1 + nu) / (2 + nu). */
static void test_shear_coefficient(void **state)
{
    td_shaft_element solid = element(0.1, 0.05, 0.0), tube = element(0.1, 0.05, 0.05 * (1.0 - 1e-7));
    double nu = steel.E / (2.0 * steel.G) - 1.0;
    (void)state;
    assert_close(td_shaft_poisson(&solid), nu, 1e-15, 0.0);
    assert_close(td_shaft_shear_coefficient(&solid, TD_SHEAR_HUTCHINSON, 0.0),
                 6.0 * (1.0 + nu) * (1.0 + nu) / (7.0 + 12.0 * nu + 4.0 * nu * nu), 1e-15, 0.0);
    assert_close(td_shaft_shear_coefficient(&tube, TD_SHEAR_HUTCHINSON, 0.0), (1.0 + nu) / (2.0 + nu), 1e-6, 0.0);
}

/* Cowper (1966) at nu = 0.3, his table's values: solid circle 6 (1 + nu) / (7 + 6 nu) = 0.8864, thin
 * tube 2 (1 + nu) / (4 + 3 nu) = 0.5306; a given kappa is used as it is; a smaller kappa makes the
 * Timoshenko element softer in shear (its translational stiffness drops). */
static void test_shear_coefficient_choice(void **state)
{
    td_shaft_element solid = element(0.1, 0.05, 0.0), tube = element(0.1, 0.05, 0.05 * (1.0 - 1e-7));
    double Kc[64], Kh[64], kc, kh;
    (void)state;
    solid.material.G = tube.material.G = solid.material.E / 2.6; /* nu = 0.3 */
    assert_close(td_shaft_shear_coefficient(&solid, TD_SHEAR_COWPER, 0.0), 6.0 * 1.3 / (7.0 + 1.8), 1e-15, 0.0);
    assert_close(td_shaft_shear_coefficient(&solid, TD_SHEAR_COWPER, 0.0), 0.8864, 1e-4, 0.0);
    assert_close(td_shaft_shear_coefficient(&tube, TD_SHEAR_COWPER, 0.0), 2.0 * 1.3 / (4.0 + 0.9), 1e-6, 0.0);
    assert_close(td_shaft_shear_coefficient(&tube, TD_SHEAR_COWPER, 0.0), 0.5306, 1e-4, 0.0);
    assert_close(td_shaft_shear_coefficient(&solid, TD_SHEAR_GIVEN, 0.75), 0.75, 0.0, 0.0);
    kc = td_shaft_shear_coefficient(&solid, TD_SHEAR_COWPER, 0.0);
    kh = td_shaft_shear_coefficient(&solid, TD_SHEAR_HUTCHINSON, 0.0);
    assert_true(kc < kh);
    td_shaft_element_matrices_kappa(&solid, TD_BEAM_TIMOSHENKO, kc, TD_MASS_CONSISTENT, NULL, Kc, NULL);
    td_shaft_element_matrices_kappa(&solid, TD_BEAM_TIMOSHENKO, kh, TD_MASS_CONSISTENT, NULL, Kh, NULL);
    assert_true(Kc[0] < Kh[0]);
}

int main(void)
{
    /* clang-format off */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_symmetry_all_forms),
        cmocka_unit_test(test_euler_bernoulli_entries),
        cmocka_unit_test(test_rigid_body_single_element),
        cmocka_unit_test(test_rigid_body_free_shaft),
        cmocka_unit_test(test_timoshenko_limit),
        cmocka_unit_test(test_timoshenko_cantilever_flexibility),
        cmocka_unit_test(test_shear_coefficient),
        cmocka_unit_test(test_shear_coefficient_choice),
    };
    /* clang-format on */
    gsl_set_error_handler_off();
    return cmocka_run_group_tests(tests, NULL, NULL);
}
