/* td_system assembly (lib/model/assemble.c) and the AMB axis law (lib/model/amb.c). */
#include "td_rig.h"
#include "td_test.h"

#include "model/elements.h"
#include "model/system_internal.h"
#include "touchdown/touchdown.h"

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const td_material steel = {2.11e11, 8.1e10, 7810.0};

/* The reference rig of docs/reference-rig.md, built in code (tests/support/td_rig.c): speed 0, lagged
 * AMBs, both retainers. */
static td_model *reference_rig(void)
{
    return td_test_rig_create(0.0, TD_RIG_TAU, TD_RIG_WITH_RETAINERS);
}

static double *dense(const td_system *s, td_matrix_kind which)
{
    int n = td_system_dof_count(s);
    double *a = malloc(sizeof *a * (size_t)n * (size_t)n);
    assert_non_null(a);
    assert_int_equal(td_system_dense(s, which, a, NULL), TD_OK);
    return a;
}

/* u^T A v, A column-major n x n */
static double quad(const double *A, const double *u, const double *v, int n)
{
    double s = 0.0;
    int i, j;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            s += u[i] * A[i + (size_t)j * n] * v[j];
    return s;
}

static void test_rig_mass(void **state)
{
    td_model *m = reference_rig();
    td_system *s = NULL;
    double *M, *ux, *uy, mx, my, shaft = steel.density * TD_PI * 0.025 * 0.025 * 2.0;
    int n, k;
    (void)state;
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    n = td_system_dof_count(s);
    assert_int_equal(n, 52);
    M = dense(s, TD_MATRIX_MASS);
    ux = calloc((size_t)n, sizeof *ux);
    uy = calloc((size_t)n, sizeof *uy);
    assert_non_null(ux);
    assert_non_null(uy);
    for (k = 0; k < 13; k++) {
        ux[TD_DOF(k, TD_DOF_X)] = 1.0;
        uy[TD_DOF(k, TD_DOF_Y)] = 1.0;
    }
    mx = quad(M, ux, ux, n);
    my = quad(M, uy, uy, n);
    print_message("rig mass from u^T M u: x %.15g kg, y %.15g kg (shaft %.15g kg + discs 40 + journals 29.2)\n", mx, my,
                  shaft);
    /* the quadratic form is the sum of the parts to rounding ... */
    assert_close(mx, shaft + 40.0 + 29.2, 1e-14, 0.0);
    assert_close(my, shaft + 40.0 + 29.2, 1e-14, 0.0);
    assert_close(mx, td_model_total_mass(m), 1e-14, 0.0);
    /* ... and docs/reference-rig.md's 99.87 kg is that number rounded to 10 g */
    assert_close(mx, 99.87, 0.0, 0.005);
    free(ux);
    free(uy);
    free(M);
    td_system_free(&s);
    assert_null(s);
    td_system_free(&s);
    td_system_free(NULL);
    td_model_free(&m);
}

static void test_rig_symmetry_and_pattern(void **state)
{
    td_model *m = reference_rig();
    td_system *s = NULL;
    double *M, *K, *C, *G;
    int n, i, j, w, nz;
    (void)state;
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    n = s->ndof;
    M = dense(s, TD_MATRIX_MASS);
    K = dense(s, TD_MATRIX_STIFFNESS);
    C = dense(s, TD_MATRIX_DAMPING);
    G = dense(s, TD_MATRIX_GYROSCOPIC);
    for (i = 0; i < n; i++) {
        assert_true(M[i + i * n] > 0.0);
        assert_true(G[i + i * n] == 0.0);
        for (j = 0; j < n; j++) {
            assert_close(M[i + j * n], M[j + i * n], 0.0, 1e-15 * td_test_max_abs(M, n * n));
            assert_close(K[i + j * n], K[j + i * n], 0.0, 1e-15 * td_test_max_abs(K, n * n));
            assert_close(G[i + j * n], -G[j + i * n], 0.0, 1e-15 * td_test_max_abs(G, n * n));
            assert_true(C[i + j * n] == 0.0); /* no structural damping, no plain bearings on the rig */
        }
    }
    /* pattern: per node its x-z and y-z 2 x 2 blocks (8), per element the two off-diagonal node
     * blocks of both planes (16): 13 * 8 + 12 * 16 = 296 for M, K and G (G couples the planes) */
    assert_int_equal(td_system_nnz(s, TD_MATRIX_MASS), 296);
    assert_int_equal(td_system_nnz(s, TD_MATRIX_STIFFNESS), 296);
    assert_int_equal(td_system_nnz(s, TD_MATRIX_GYROSCOPIC), 296);
    assert_int_equal(td_system_nnz(s, TD_MATRIX_DAMPING), 0);
    /* CSC well formed, rows strictly increasing within a column, no entry outside the dense nonzeros + 0s */
    for (w = 0; w < 4; w++) {
        const cs_di *A = w == 0 ? s->M : w == 1 ? s->K : w == 2 ? s->C : s->G;
        const double *D = w == 0 ? M : w == 1 ? K : w == 2 ? C : G;
        assert_int_equal(A->m, n);
        assert_int_equal(A->n, n);
        assert_int_equal(A->nz, -1);
        nz = 0;
        for (i = 0; i < n * n; i++)
            nz += D[i] != 0.0;
        assert_true(nz <= A->p[n]);
        for (j = 0; j < n; j++)
            for (i = A->p[j]; i < A->p[j + 1]; i++) {
                assert_true(A->i[i] >= 0 && A->i[i] < n);
                if (i > A->p[j])
                    assert_true(A->i[i] > A->i[i - 1]);
                assert_true(A->x[i] == D[A->i[i] + j * n]); /* dense round-trip, entry by entry */
            }
    }
    free(M);
    free(K);
    free(C);
    free(G);
    td_system_free(&s);
    td_model_free(&m);
}

/* Second assembly path: dense loops over element matrices and discs, against the sparse system. */
static void test_rig_dense_against_direct_assembly(void **state)
{
    td_model *m = reference_rig();
    td_system *s = NULL;
    double *M, *K, *G, *Md, *Kd, *Gd, Me[64], Ke[64], Ge[64];
    int n, e, i, j, d;
    (void)state;
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    n = s->ndof;
    M = dense(s, TD_MATRIX_MASS);
    K = dense(s, TD_MATRIX_STIFFNESS);
    G = dense(s, TD_MATRIX_GYROSCOPIC);
    Md = calloc((size_t)(n * n), sizeof *Md);
    Kd = calloc((size_t)(n * n), sizeof *Kd);
    Gd = calloc((size_t)(n * n), sizeof *Gd);
    assert_non_null(Md);
    assert_non_null(Kd);
    assert_non_null(Gd);
    for (e = 0; e < 12; e++) {
        td_shaft_element el;
        assert_int_equal(td_model_get_shaft_element(m, e, &el), TD_OK);
        td_shaft_element_matrices(&el, TD_BEAM_EULER_BERNOULLI, TD_MASS_CONSISTENT, Me, Ke, Ge);
        for (i = 0; i < 8; i++)
            for (j = 0; j < 8; j++) {
                int gi = 4 * e + i, gj = 4 * e + j;
                Md[gi + gj * n] += Me[8 * i + j];
                Kd[gi + gj * n] += Ke[8 * i + j];
                Gd[gi + gj * n] += Ge[8 * i + j];
            }
    }
    for (d = 0; d < td_model_disc_count(m); d++) {
        td_disc disc;
        int b;
        assert_int_equal(td_model_get_disc(m, d, &disc), TD_OK);
        b = 4 * disc.node;
        Md[b + b * n] += disc.mass;
        Md[(b + 1) + (b + 1) * n] += disc.mass;
        Md[(b + 2) + (b + 2) * n] += disc.Id;
        Md[(b + 3) + (b + 3) * n] += disc.Id;
        Gd[(b + 2) + (b + 3) * n] += disc.Ip; /* dofs.h: +Ip at (theta, phi) */
        Gd[(b + 3) + (b + 2) * n] -= disc.Ip;
    }
    for (i = 0; i < n * n; i++) {
        assert_close(M[i], Md[i], 1e-14, 1e-15 * td_test_max_abs(Md, n * n));
        assert_close(K[i], Kd[i], 1e-14, 1e-15 * td_test_max_abs(Kd, n * n));
        assert_close(G[i], Gd[i], 1e-14, 1e-15 * td_test_max_abs(Gd, n * n));
    }
    /* a few spot values straight from the contract */
    /* G(theta5, phi5): the disc's Ip plus rho J 4 L / 30 from each of the two adjacent elements */
    assert_close(G[TD_DOF(5, TD_DOF_THETA) + TD_DOF(5, TD_DOF_PHI) * n],
                 0.072 + 2.0 * 2.0 * steel.density * TD_PI * pow(0.05, 4) / 64.0 * 4.0 * (2.0 / 12.0) / 30.0, 1e-14,
                 0.0);
    free(Md);
    free(Kd);
    free(Gd);
    free(M);
    free(K);
    free(G);
    td_system_free(&s);
    td_model_free(&m);
}

/* gravity_load = M g: its resultant is m g and its moment about z = 0 is g times the first moment of mass. */
static void test_gravity_load(void **state)
{
    td_model *m = reference_rig();
    td_system *s = NULL;
    double gx = 0.3, gy = -9.81, fx = 0.0, fy = 0.0, mxz = 0.0, myz = 0.0, first = 0.0, mass;
    double L = 2.0, shaft = steel.density * TD_PI * 0.025 * 0.025 * L;
    int k, d;
    (void)state;
    assert_int_equal(td_model_set_gravity(m, gx, gy, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    mass = td_model_total_mass(m);
    first = shaft * L / 2.0;
    for (d = 0; d < td_model_disc_count(m); d++) {
        td_disc disc;
        assert_int_equal(td_model_get_disc(m, d, &disc), TD_OK);
        first += disc.mass * td_model_node_position(m, disc.node);
    }
    for (k = 0; k < s->nnodes; k++) {
        double z = td_model_node_position(m, k);
        fx += s->gravity_load[TD_DOF(k, TD_DOF_X)];
        fy += s->gravity_load[TD_DOF(k, TD_DOF_Y)];
        /* virtual work of rigid tilts: x = z, phi = 1 and y = z, theta = -1 (dofs.h) */
        mxz += z * s->gravity_load[TD_DOF(k, TD_DOF_X)] + s->gravity_load[TD_DOF(k, TD_DOF_PHI)];
        myz += z * s->gravity_load[TD_DOF(k, TD_DOF_Y)] - s->gravity_load[TD_DOF(k, TD_DOF_THETA)];
    }
    assert_close(fx, mass * gx, 1e-14, 0.0);
    assert_close(fy, mass * gy, 1e-14, 0.0);
    assert_close(mxz, first * gx, 1e-13, 0.0);
    assert_close(myz, first * gy, 1e-13, 0.0);
    /* off: all zero */
    td_system_free(&s);
    assert_int_equal(td_model_set_gravity(m, 0.0, 0.0, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    for (k = 0; k < s->ndof; k++)
        assert_true(s->gravity_load[k] == 0.0);
    td_system_free(&s);
    td_model_free(&m);
}

static void test_amb_axis_table(void **state)
{
    td_model *m = reference_rig();
    td_system *s = NULL;
    td_amb third = {6, 5, 2.0e5, 100.0, 5.0e3, 20.0, 0.0, 500.0, 1, 0.0, 0.0, 0.0}; /* no lag, non-collocated */
    int k;
    (void)state;
    assert_int_equal(td_model_add_amb(m, &third, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    assert_int_equal(s->n_amb_axes, 6);
    assert_int_equal(s->n_controller_states, 4);
    for (k = 0; k < 6; k++) {
        const td_amb_axis *a = &s->amb_axes[k];
        int node = k < 2 ? 3 : k < 4 ? 9 : 6, sensor = k < 4 ? node : 5;
        int offset = k % 2 == 0 ? TD_DOF_X : TD_DOF_Y;
        assert_int_equal(a->amb, k / 2);
        assert_int_equal(a->axis, k % 2);
        assert_int_equal(a->actuator_dof, TD_DOF(node, offset));
        assert_int_equal(a->sensor_dof, TD_DOF(sensor, offset));
        assert_int_equal(a->state, k < 4 ? k : -1);
        if (k < 4) {
            assert_true(a->ks == 1.0e6 && a->ki == 200.0 && a->kp == 1.0e4 && a->kd == 40.0);
            assert_true(a->tau == 1.0 / (2.0 * TD_PI * 100.0) && a->capacity == 1700.0 && a->saturation == 0);
        } else {
            assert_true(a->ks == 2.0e5 && a->tau == 0.0 && a->capacity == 500.0 && a->saturation == 1);
        }
    }
    td_system_free(&s);
    td_model_free(&m);
}

static void test_amb_law(void **state)
{
    td_amb_axis a;
    double dx = -1.0, dfc = -1.0, f;
    (void)state;
    memset(&a, 0, sizeof a);
    a.ks = 1.0e6;
    a.ki = 200.0;
    a.kp = 1.0e4;
    a.kd = 40.0;
    a.tau = 1.0 / (2.0 * TD_PI * 100.0);
    a.capacity = 1700.0;
    /* command -ki (kp xs + kd vs): 1e-4 m, 0.01 m/s -> -200 (1 + 0.4) = -280 N */
    assert_close(td_amb_axis_command(&a, 1e-4, 0.01, 0.0), -280.0, 1e-14, 0.0);
    /* filter rate (command - fc) / tau */
    assert_close(td_amb_axis_filter_rate(&a, 1e-4, 0.01, 0.0, -80.0), -200.0 * 2.0 * TD_PI * 100.0, 1e-14, 0.0);
    /* unsaturated: ks x + fc, derivatives ks and 1 */
    f = td_amb_axis_force(&a, 1, 1e-4, -280.0, &dx, &dfc);
    assert_close(f, 100.0 - 280.0, 1e-14, 0.0);
    assert_true(dx == 1.0e6 && dfc == 1.0);
    /* saturation off: no clipping even far beyond the capacity */
    f = td_amb_axis_force(&a, 1, 1e-3, 5000.0, &dx, &dfc);
    assert_close(f, 6000.0, 1e-14, 0.0);
    assert_true(dx == 1.0e6 && dfc == 1.0);
    /* saturation on: clipped both ways, derivatives zero; at the limit itself still linear */
    a.saturation = 1;
    f = td_amb_axis_force(&a, 1, 1e-3, 5000.0, &dx, &dfc);
    assert_true(f == 1700.0 && dx == 0.0 && dfc == 0.0);
    f = td_amb_axis_force(&a, 1, -1e-3, -5000.0, &dx, &dfc);
    assert_true(f == -1700.0 && dx == 0.0 && dfc == 0.0);
    f = td_amb_axis_force(&a, 1, 1e-3, 700.0, &dx, &dfc);
    assert_close(f, 1700.0, 1e-15, 0.0);
    assert_true(dx == 1.0e6 && dfc == 1.0);
    f = td_amb_axis_force(&a, 1, 5e-4, 100.0, NULL, NULL); /* NULL derivative pointers accepted */
    assert_close(f, 600.0, 1e-14, 0.0);
    /* disabled (failed AMB): nothing */
    f = td_amb_axis_force(&a, 0, 1e-3, 5000.0, &dx, &dfc);
    assert_true(f == 0.0 && dx == 0.0 && dfc == 0.0);
    /* integral action: -ki kint e joins the command; de/dt = xs while running */
    a.kint = 2.5e5;
    assert_close(td_amb_axis_command(&a, 1e-4, 0.01, -2e-3), -200.0 * (1.0 + 0.4 - 500.0), 1e-14, 0.0);
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, 100.0, 0.0) == -3e-4);
    assert_true(td_amb_axis_integral_rate(&a, 0, -3e-4, 100.0, 0.0) == 0.0); /* off: holds */
    /* clipped at +capacity: xs < 0 would raise the force further, so the integrator stops; xs > 0
     * brings it back and integrates; the same mirrored at -capacity */
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, 1700.0, 0.0) == 0.0);
    assert_true(td_amb_axis_integral_rate(&a, 1, 3e-4, 1700.0, 0.0) == 3e-4);
    assert_true(td_amb_axis_integral_rate(&a, 1, 3e-4, -1700.0, 0.0) == 0.0);
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, -1700.0, 0.0) == -3e-4);
    a.saturation = 0; /* no clip, no clamp */
    assert_true(td_amb_axis_integral_rate(&a, 1, -3e-4, 5000.0, 0.0) == -3e-4);
}

/* Rayleigh damping on the shaft only, plain bearings in K and C, AMBs nowhere in K. */
static void test_damping_and_bearings(void **state)
{
    td_model *m = NULL;
    td_system *s = NULL, *s0 = NULL;
    td_shaft_element el = {0.2, 0.04, 0.01, {2.11e11, 8.1e10, 7810.0}};
    td_shaft_options opt = {TD_BEAM_TIMOSHENKO, TD_MASS_CONSISTENT, 3.0, 2e-5, TD_SHEAR_HUTCHINSON, 0.0};
    td_bearing b = {0, 1e7, 2e7, 300.0, 400.0};
    td_amb amb = {2, 2, 1.0e6, 200.0, 1.0e4, 40.0, 0.0, 1700.0, 0, 0.0, 0.0, 0.0};
    double *M, *K, *C, *K0, Me[64], Ke[64];
    int n, i, e;
    (void)state;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_set_shaft_options(m, &opt, NULL), TD_OK);
    for (i = 0; i < 3; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &(td_disc){1, 5.0, 0.01, 0.006}, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b, NULL), TD_OK);
    assert_int_equal(td_model_add_amb(m, &amb, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    n = s->ndof;
    M = dense(s, TD_MATRIX_MASS);
    K = dense(s, TD_MATRIX_STIFFNESS);
    C = dense(s, TD_MATRIX_DAMPING);
    K0 = dense(s0, TD_MATRIX_STIFFNESS);
    /* expected C from the element matrices: alpha M_shaft + beta K_shaft (the disc's mass excluded) */
    {
        double *Ce = calloc((size_t)(n * n), sizeof *Ce);
        assert_non_null(Ce);
        td_shaft_element_matrices(&el, TD_BEAM_TIMOSHENKO, TD_MASS_CONSISTENT, Me, Ke, NULL);
        for (e = 0; e < 3; e++)
            for (i = 0; i < 64; i++)
                Ce[(4 * e + i / 8) + (size_t)(4 * e + i % 8) * n] +=
                    opt.rayleigh_alpha * Me[i] + opt.rayleigh_beta * Ke[i];
        Ce[0] += 300.0;
        Ce[1 + n] += 400.0;
        for (i = 0; i < n * n; i++)
            assert_close(C[i], Ce[i], 1e-13, 1e-15 * td_test_max_abs(Ce, n * n));
        free(Ce);
    }
    /* K: the shaft plus the bearing only */
    for (i = 0; i < n * n; i++) {
        double extra = i == 0 ? 1e7 : i == 1 + n ? 2e7 : 0.0;
        assert_close(K[i], K0[i] + extra, 1e-15, 1e-15 * td_test_max_abs(K0, n * n));
    }
    assert_true(M[TD_DOF(1, TD_DOF_X) * (n + 1)] > 5.0);
    free(M);
    free(K);
    free(C);
    free(K0);
    td_system_free(&s);
    td_system_free(&s0);
    td_model_free(&m);
}

/* Whirl directions of a first-order eigenvector: forward when Im(X conj(Y)) > 0 (x = cos, y = sin). */
static int is_forward(gsl_complex X, gsl_complex Y)
{
    return GSL_IMAG(X) * GSL_REAL(Y) - GSL_REAL(X) * GSL_IMAG(Y) > 0.0;
}

/*
 * Overhung disc on a massless cantilever: the gyroscopic sign and size against the closed form.
 * Circular whirl at signed frequency w (w > 0 forward) of a disc (m, Id, Ip) on a tip stiffness
 * [k11 k12; k12 k22] (the inverse of the cantilever flexibility, L^3/3EI, L^2/2EI, L/EI):
 *   (k11 - m w^2)(k22 - Id w^2 + Ip Omega w) - k12^2 = 0
 * Forward whirl stiffens with speed, backward softens.
 */
static void test_overhung_disc_whirl(void **state)
{
    static const double speeds[3] = {0.0, 500.0, 3000.0};
    td_model *m = NULL;
    td_system *s = NULL;
    td_shaft_element el = {0.5, 0.05, 0.0, {2.11e11, 8.1e10, 1e-6}}; /* shaft mass ~1e-9 kg */
    td_disc disc = {1, 10.0, 0.072, 0.036668};
    double EI = 2.11e11 * TD_PI * pow(0.05, 4) / 64.0, L = el.length;
    double f11 = L * L * L / (3 * EI), f12 = L * L / (2 * EI), f22 = L / EI, det = f11 * f22 - f12 * f12;
    double k11 = f22 / det, k12 = -f12 / det, k22 = f11 / det;
    double *M, *K, *G, prev_fwd = 0.0, prev_bwd = 1e300;
    int w, i, j;
    (void)state;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &disc, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    M = dense(s, TD_MATRIX_MASS);
    K = dense(s, TD_MATRIX_STIFFNESS);
    G = dense(s, TD_MATRIX_GYROSCOPIC);
    for (w = 0; w < 3; w++) {
        double Om = speeds[w], a[5], z[8], fe[2], be[2], fc[2], bc[2];
        gsl_poly_complex_workspace *pw = gsl_poly_complex_workspace_alloc(5);
        gsl_matrix *A = gsl_matrix_calloc(8, 8);
        gsl_vector_complex *ev = gsl_vector_complex_alloc(8);
        gsl_matrix_complex *V = gsl_matrix_complex_alloc(8, 8);
        gsl_eigen_nonsymmv_workspace *ws = gsl_eigen_nonsymmv_alloc(8);
        int nf = 0, nb = 0;
        assert_non_null(pw);
        assert_non_null(A);
        assert_non_null(ev);
        assert_non_null(V);
        assert_non_null(ws);
        /* node 0 clamped: node 1's four DOFs (global 4..7); M is diagonal there up to ~1e-9 */
        for (i = 0; i < 4; i++) {
            double mii = M[(4 + i) + (4 + i) * 8];
            gsl_matrix_set(A, (size_t)i, (size_t)(4 + i), 1.0);
            for (j = 0; j < 4; j++) {
                assert_true(i == j || fabs(M[(4 + i) + (4 + j) * 8]) < 1e-8 * mii);
                gsl_matrix_set(A, (size_t)(4 + i), (size_t)j, -K[(4 + i) + (4 + j) * 8] / mii);
                gsl_matrix_set(A, (size_t)(4 + i), (size_t)(4 + j), -Om * G[(4 + i) + (4 + j) * 8] / mii);
            }
        }
        assert_int_equal(gsl_eigen_nonsymmv(A, ev, V, ws), GSL_SUCCESS);
        for (i = 0; i < 8; i++) {
            gsl_complex l = gsl_vector_complex_get(ev, (size_t)i);
            assert_close(GSL_REAL(l), 0.0, 0.0, 1e-9 * gsl_complex_abs(l)); /* undamped */
            if (GSL_IMAG(l) <= 0.0)
                continue;
            if (Om == 0.0) { /* degenerate pairs: any planar combination is an eigenvector, so no direction */
                if (nf < 2)
                    fe[nf++] = GSL_IMAG(l);
                else
                    be[nb++] = GSL_IMAG(l);
                continue;
            }
            if (is_forward(gsl_matrix_complex_get(V, 0, (size_t)i), gsl_matrix_complex_get(V, 1, (size_t)i))) {
                assert_true(nf < 2);
                fe[nf++] = GSL_IMAG(l);
            } else {
                assert_true(nb < 2);
                be[nb++] = GSL_IMAG(l);
            }
        }
        assert_int_equal(nf, 2);
        assert_int_equal(nb, 2);
        /* quartic in the signed whirl frequency, ascending coefficients */
        a[0] = k11 * k22 - k12 * k12;
        a[1] = k11 * disc.Ip * Om;
        a[2] = -(k11 * disc.Id + disc.mass * k22);
        a[3] = -disc.mass * disc.Ip * Om;
        a[4] = disc.mass * disc.Id;
        assert_int_equal(gsl_poly_complex_solve(a, 5, pw, z), GSL_SUCCESS);
        nf = nb = 0;
        for (i = 0; i < 4; i++) {
            assert_close(z[2 * i + 1], 0.0, 0.0, 1e-9 * fabs(z[2 * i]));
            if (z[2 * i] > 0.0)
                fc[nf++] = z[2 * i];
            else
                bc[nb++] = -z[2 * i];
        }
        assert_int_equal(nf, 2);
        assert_int_equal(nb, 2);
        if (Om == 0.0) { /* split the four into the lower and upper pair */
            double all[4] = {fe[0], fe[1], be[0], be[1]};
            gsl_sort(all, 1, 4);
            fe[0] = be[0] = all[0];
            fe[1] = be[1] = all[2];
            assert_close(all[1], all[0], 1e-10, 0.0);
            assert_close(all[3], all[2], 1e-10, 0.0);
        }
        gsl_sort(fe, 1, 2);
        gsl_sort(be, 1, 2);
        gsl_sort(fc, 1, 2);
        gsl_sort(bc, 1, 2);
        print_message("Omega %6.0f rad/s: forward %.9g %.9g (closed form %.9g %.9g), backward %.9g %.9g (%.9g %.9g)\n",
                      Om, fe[0], fe[1], fc[0], fc[1], be[0], be[1], bc[0], bc[1]);
        for (i = 0; i < 2; i++) {
            assert_close(fe[i], fc[i], 1e-8, 0.0);
            assert_close(be[i], bc[i], 1e-8, 0.0);
        }
        /* the first forward whirl rises with speed, the first backward one falls */
        assert_true(w == 0 ? fabs(fe[0] - be[0]) < 1e-9 * fe[0] : fe[0] > prev_fwd && be[0] < prev_bwd);
        prev_fwd = fe[0];
        prev_bwd = be[0];
        gsl_eigen_nonsymmv_free(ws);
        gsl_matrix_complex_free(V);
        gsl_vector_complex_free(ev);
        gsl_matrix_free(A);
        gsl_poly_complex_workspace_free(pw);
    }
    free(M);
    free(K);
    free(G);
    td_system_free(&s);
    td_model_free(&m);
}

static void test_invalid_input(void **state)
{
    td_model *m = NULL;
    td_system *s = NULL;
    td_error err;
    double out[4];
    (void)state;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, &err), TD_ERR_INVALID); /* no shaft */
    assert_null(s);
    assert_non_null(strstr(err.message, "no elements"));
    assert_int_equal(td_system_create(NULL, &s, &err), TD_ERR_INVALID);
    assert_int_equal(td_system_create(m, NULL, &err), TD_ERR_INVALID);
    assert_int_equal(td_system_dense(NULL, TD_MATRIX_MASS, out, &err), TD_ERR_INVALID);
    assert_int_equal(td_system_nnz(NULL, TD_MATRIX_MASS), 0);
    assert_int_equal(td_system_dof_count(NULL), 0);
    assert_null(td_system_model(NULL));
    td_model_free(&m);
}

/* The system owns a copy of the model. */
static void test_owns_model_copy(void **state)
{
    td_model *m = reference_rig();
    td_system *s = NULL;
    (void)state;
    assert_int_equal(td_model_set_speed(m, 90.0, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &s, NULL), TD_OK);
    assert_true(td_system_model(s) != m);
    assert_int_equal(td_model_set_speed(m, 190.0, NULL), TD_OK);
    assert_close(td_model_speed(td_system_model(s)), 90.0, 0.0, 0.0);
    td_model_free(&m);
    assert_int_equal(td_model_node_count(td_system_model(s)), 13);
    assert_int_equal(td_model_amb_count(td_system_model(s)), 2);
    td_system_free(&s);
}

int main(void)
{
    /* clang-format off */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rig_mass),
        cmocka_unit_test(test_rig_symmetry_and_pattern),
        cmocka_unit_test(test_rig_dense_against_direct_assembly),
        cmocka_unit_test(test_gravity_load),
        cmocka_unit_test(test_amb_axis_table),
        cmocka_unit_test(test_amb_law),
        cmocka_unit_test(test_damping_and_bearings),
        cmocka_unit_test(test_overhung_disc_whirl),
        cmocka_unit_test(test_invalid_input),
        cmocka_unit_test(test_owns_model_copy),
    };
    /* clang-format on */
    gsl_set_error_handler_off();
    return cmocka_run_group_tests(tests, NULL, NULL);
}
