/* Contact laws (lib/contact): penalty force, constraint geometry, friction, impact map. */
#include "td_test.h"

#include "contact/contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const td_contact_damping all_laws[3] = {TD_DAMPING_NONE, TD_DAMPING_HUNT_CROSSLEY, TD_DAMPING_KELVIN_VOIGT};

static td_penalty_law law_of(td_contact_damping d, double exponent)
{
    td_penalty_law law;
    law.stiffness = 1.25e10;
    law.exponent = exponent;
    law.damping = d;
    law.coefficient = d == TD_DAMPING_KELVIN_VOIGT ? 2.0e5 : (d == TD_DAMPING_HUNT_CROSSLEY ? 0.5 : 0.0);
    return law;
}

/* No penalty law ever pulls, and none acts outside the circle, whatever the penetration rate. */
static void test_penalty_never_pulls(void **state)
{
    int l, i, j;
    double p;
    (void)state;
    for (p = 1.0; p <= 1.5; p += 0.5)
        for (l = 0; l < 3; l++) {
            td_penalty_law law = law_of(all_laws[l], p);
            for (i = -20; i <= 20; i++)
                for (j = -20; j <= 20; j++) {
                    double delta = i * 1e-6, rate = j * 0.5, dd, dr;
                    double f = td_contact_penalty_force(&law, delta, rate, &dd, &dr);
                    assert_true(f >= 0.0);
                    if (delta <= 0.0) {
                        assert_true(f == 0.0 && dd == 0.0 && dr == 0.0);
                    }
                }
        }
}

/* Linear law is eq. (4) exactly; Hertz exponent gives Kc delta^1.5. */
static void test_penalty_elastic_values(void **state)
{
    td_penalty_law lin = law_of(TD_DAMPING_NONE, 1.0), hertz = law_of(TD_DAMPING_NONE, 1.5);
    (void)state;
    assert_close(td_contact_penalty_force(&lin, 2e-6, 3.0, NULL, NULL), 1.25e10 * 2e-6, 1e-15, 0.0);
    assert_close(td_contact_penalty_force(&hertz, 4e-6, -3.0, NULL, NULL), 1.25e10 * 8e-9, 1e-14, 0.0);
}

/* Hunt-Crossley starts at zero force even at a finite impact speed; Kelvin-Voigt jumps to d*rate. */
static void test_hunt_crossley_starts_at_zero(void **state)
{
    td_penalty_law hc = law_of(TD_DAMPING_HUNT_CROSSLEY, 1.0), kv = law_of(TD_DAMPING_KELVIN_VOIGT, 1.0);
    double rate = 0.05, eps;
    (void)state;
    for (eps = 1e-6; eps > 1e-14; eps /= 10.0) {
        double f = td_contact_penalty_force(&hc, eps, rate, NULL, NULL);
        assert_close(f, 1.25e10 * eps * (1.0 + 0.5 * rate), 1e-14, 0.0);
    }
    assert_true(td_contact_penalty_force(&hc, 1e-15, rate, NULL, NULL) < 1e-4);
    assert_close(td_contact_penalty_force(&kv, 1e-15, rate, NULL, NULL), 2.0e5 * rate, 1e-6, 0.0);
    /* a fast separation clips Hunt-Crossley to zero: (1 + d rate) < 0 */
    assert_true(td_contact_penalty_force(&hc, 1e-6, -3.0, NULL, NULL) == 0.0);
}

/* Analytic partial derivatives agree with central differences away from the clipping kinks. */
static void test_penalty_derivatives(void **state)
{
    int l;
    double p;
    (void)state;
    for (p = 1.0; p <= 1.5; p += 0.5)
        for (l = 0; l < 3; l++) {
            td_penalty_law law = law_of(all_laws[l], p);
            double delta = 3e-6, rate = 0.02, dd, dr, hd = 1e-11, hr = 1e-6;
            double fpd = td_contact_penalty_force(&law, delta + hd, rate, NULL, NULL);
            double fmd = td_contact_penalty_force(&law, delta - hd, rate, NULL, NULL);
            double fpr = td_contact_penalty_force(&law, delta, rate + hr, NULL, NULL);
            double fmr = td_contact_penalty_force(&law, delta, rate - hr, NULL, NULL);
            td_contact_penalty_force(&law, delta, rate, &dd, &dr);
            assert_close(dd, (fpd - fmd) / (2 * hd), 1e-6, 1e-6);
            assert_close(dr, (fpr - fmr) / (2 * hr), 1e-6, 1e-6);
        }
}

/* g vanishes on the circle, J is its gradient, and g'' = J v' + D along a smooth path. */
static void test_constraint_geometry(void **state)
{
    double c = 0.75e-3, J[2], a, h = 1e-7;
    (void)state;
    for (a = 0.0; a < 6.3; a += 0.7) {
        double x = c * cos(a), y = c * sin(a);
        assert_close(td_contact_constraint(x, y, c), 0.0, 0.0, 1e-19);
        td_contact_constraint_jacobian(1.1 * x, 1.1 * y, c, J);
        assert_close(
            J[0],
            (td_contact_constraint(1.1 * x + 1e-10, 1.1 * y, c) - td_contact_constraint(1.1 * x - 1e-10, 1.1 * y, c)) /
                2e-10,
            1e-6, 1e-9);
        assert_close(
            J[1],
            (td_contact_constraint(1.1 * x, 1.1 * y + 1e-10, c) - td_contact_constraint(1.1 * x, 1.1 * y - 1e-10, c)) /
                2e-10,
            1e-6, 1e-9);
    }
    /* path x = rho cos 5t, y = rho sin 5t, rho = c (1 + 0.1 sin 3t): g'' = (rho'^2 + rho rho'')/c */
    {
        double t = 0.37, rho = c * (1 + 0.1 * sin(3 * t)), r1 = 0.3 * c * cos(3 * t), r2 = -0.9 * c * sin(3 * t);
        double cs = cos(5 * t), sn = sin(5 * t);
        double x = rho * cs, y = rho * sn;
        double vx = r1 * cs - 5 * rho * sn, vy = r1 * sn + 5 * rho * cs;
        double ax = r2 * cs - 10 * r1 * sn - 25 * rho * cs, ay = r2 * sn + 10 * r1 * cs - 25 * rho * sn;
        double g2 = (r1 * r1 + rho * r2) / c;
        (void)h;
        td_contact_constraint_jacobian(x, y, c, J);
        assert_close(J[0] * ax + J[1] * ay + td_contact_constraint_dterm(vx, vy, c), g2, 1e-12, 1e-18);
        assert_close(J[0] * vx + J[1] * vy, r1 * rho / c, 1e-12, 1e-18); /* g' = rho rho'/c */
    }
}

/* eq. (16) on a circular whirl at rate w: v = R_s Omega + (R_b - R_s) w - R_b Omega_b; eq. (17) sign. */
static void test_sliding_velocity_and_friction(void **state)
{
    td_retainer ret = {.node = 2,
                       .clearance = 0.75e-3,
                       .shaft_radius = 0.025,
                       .bore_radius = 0.02575,
                       .friction = 0.1,
                       .bore_speed = 3.0,
                       .restitution = 0.0};
    double w = -40.0, c = ret.clearance, a = 0.4;
    double x = c * cos(a), y = c * sin(a), vx = -w * y, vy = w * x;
    (void)state;
    assert_close(td_contact_sliding_velocity(&ret, 90.0, 3.0, x, y, vx, vy), 0.025 * 90.0 + 0.75e-3 * w - 0.02575 * 3.0,
                 1e-14, 1e-15);
    assert_close(td_contact_tangential_velocity(x, y, vx, vy), w * c, 1e-14, 0.0);
    assert_close(td_contact_radial_velocity(x, y, vx, vy), 0.0, 0.0, 1e-16);
    assert_close(td_contact_friction_force(0.1, 1, 700.0), -70.0, 1e-15, 0.0);
    assert_close(td_contact_friction_force(0.1, -1, 700.0), 70.0, 1e-15, 0.0);
}

/* The slip-regularised law: phi = sgn(v_s) outside the band, linear inside, continuous at its
 * edges; and the gradient of eq. (16) against central differences. */
static void test_slip_factor_and_gradient(void **state)
{
    td_retainer ret = {.node = 2,
                       .clearance = 0.75e-3,
                       .shaft_radius = 0.025,
                       .bore_radius = 0.02575,
                       .friction = 0.1,
                       .bore_speed = 3.0,
                       .restitution = 0.0};
    double vreg = TD_CONTACT_SLIP_BAND, d, g[4], z[4] = {3.1e-4, -6.2e-4, 0.021, 0.013};
    int i;
    (void)state;
    assert_close(td_contact_slip_factor(2.0, vreg, &d), 1.0, 0.0, 0.0);
    assert_close(d, 0.0, 0.0, 0.0);
    assert_close(td_contact_slip_factor(-2.0, vreg, &d), -1.0, 0.0, 0.0);
    assert_close(td_contact_slip_factor(0.25 * vreg, vreg, &d), 0.25, 1e-15, 0.0);
    assert_close(d, 1.0 / vreg, 1e-15, 0.0);
    assert_close(td_contact_slip_factor(0.0, vreg, NULL), 0.0, 0.0, 0.0);
    assert_close(td_contact_slip_factor(vreg * (1.0 - 1e-12), vreg, NULL), 1.0, 0.0, 1e-11);
    assert_close(td_contact_slip_factor(-vreg * (1.0 - 1e-12), vreg, NULL), -1.0, 0.0, 1e-11);
    assert_close(td_contact_friction_force(0.1, 0.25, 700.0), -17.5, 1e-15, 0.0);
    td_contact_sliding_velocity_gradient(&ret, z[0], z[1], z[2], z[3], g);
    for (i = 0; i < 4; i++) {
        double zp[4], zm[4], h = 1e-6 * fabs(z[i]), fd;
        memcpy(zp, z, sizeof zp);
        memcpy(zm, z, sizeof zm);
        zp[i] += h;
        zm[i] -= h;
        fd = (td_contact_sliding_velocity(&ret, 90.0, 3.0, zp[0], zp[1], zp[2], zp[3]) -
              td_contact_sliding_velocity(&ret, 90.0, 3.0, zm[0], zm[1], zm[2], zm[3])) /
             (2.0 * h);
        assert_close(g[i], fd, 1e-7, 0.0);
    }
}

/* Impact on a lumped (diagonal) mass: the node's radial velocity becomes -e v_r, the tangential
 * one is kept, nothing else moves. */
static void test_impact_lumped(void **state)
{
    enum { N = 6 };
    double m[N] = {3.0, 3.0, 0.1, 0.1, 7.0, 7.0}, v[N] = {0.02, -0.01, 0.3, -0.2, 0.05, 0.04}, v0[N];
    double minv_jt[N], c = 0.75e-3, a = 2.2, x = c * cos(a), y = c * sin(a), work[2], P, e;
    td_contact_row row;
    int i;
    (void)state;
    for (e = 0.0; e <= 1.0; e += 0.5) {
        double vr0, vt0;
        memcpy(v0, v, sizeof v);
        row.count = 2;
        row.dof[0] = 0;
        row.dof[1] = 1;
        td_contact_constraint_jacobian(x, y, c, row.j);
        for (i = 0; i < N; i++)
            minv_jt[i] = 0.0;
        minv_jt[0] = row.j[0] / m[0];
        minv_jt[1] = row.j[1] / m[1];
        vr0 = td_contact_radial_velocity(x, y, v0[0], v0[1]);
        vt0 = td_contact_tangential_velocity(x, y, v0[0], v0[1]);
        assert_int_equal(td_contact_impact_map(N, 1, &row, minv_jt, &e, v0, &P, work), 0);
        assert_close(td_contact_radial_velocity(x, y, v0[0], v0[1]), -e * vr0, 1e-12, 1e-17);
        assert_close(td_contact_tangential_velocity(x, y, v0[0], v0[1]), vt0, 1e-12, 1e-17);
        for (i = 2; i < N; i++)
            assert_true(v0[i] == v[i]);
        /* impulse = m (1 + e) v_r for a point mass */
        assert_close(P, m[0] * (1 + e) * vr0, 1e-12, 0.0);
    }
}

/* Solve the dense SPD system M x = b by the same small solver (reference for the test below). */
static void solve_dense(int n, const double *M, const double *b, double *x)
{
    double *A = malloc(sizeof(double) * n * n);
    assert_non_null(A);
    memcpy(A, M, sizeof(double) * n * n);
    memcpy(x, b, sizeof(double) * n);
    assert_int_equal(td_contact_dense_solve(n, A, x), 0);
    free(A);
}

/* Consistent (full) mass, two simultaneous constraints with different restitutions: each J_k v
 * is reversed and scaled, and u^T M v is unchanged for every u with J u = 0. */
static void test_impact_consistent_two_constraints(void **state)
{
    enum { N = 8, NM = 2 };
    double M[N * N], B[N * N], v[N], v1[N], minv_jt[N * NM], jt[N], e[NM] = {0.0, 0.6}, P[NM], work[NM * (NM + 1)];
    td_contact_row rows[NM];
    double c = 0.75e-3;
    int i, j, k, trial;
    unsigned seed = 12345u;
    (void)state;
    /* M = B^T B + n I, a random SPD matrix */
    for (i = 0; i < N * N; i++) {
        seed = seed * 1103515245u + 12345u;
        B[i] = ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
    }
    for (i = 0; i < N; i++)
        for (j = 0; j < N; j++) {
            double s = i == j ? N : 0.0;
            for (k = 0; k < N; k++)
                s += B[k + i * N] * B[k + j * N];
            M[i + j * N] = s;
        }
    for (i = 0; i < N; i++) {
        seed = seed * 1103515245u + 12345u;
        v[i] = ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
    }
    rows[0].count = rows[1].count = 2;
    rows[0].dof[0] = 0, rows[0].dof[1] = 1;
    rows[1].dof[0] = 4, rows[1].dof[1] = 5;
    td_contact_constraint_jacobian(c * cos(0.3), c * sin(0.3), c, rows[0].j);
    td_contact_constraint_jacobian(c * cos(2.0), c * sin(2.0), c, rows[1].j);
    for (k = 0; k < NM; k++) {
        for (i = 0; i < N; i++)
            jt[i] = 0.0;
        jt[rows[k].dof[0]] = rows[k].j[0];
        jt[rows[k].dof[1]] = rows[k].j[1];
        solve_dense(N, M, jt, minv_jt + k * N);
    }
    memcpy(v1, v, sizeof v);
    assert_int_equal(td_contact_impact_map(N, NM, rows, minv_jt, e, v1, P, work), 0);
    for (k = 0; k < NM; k++) {
        double before = rows[k].j[0] * v[rows[k].dof[0]] + rows[k].j[1] * v[rows[k].dof[1]];
        double after = rows[k].j[0] * v1[rows[k].dof[0]] + rows[k].j[1] * v1[rows[k].dof[1]];
        assert_close(after, -e[k] * before, 1e-12, 1e-15);
    }
    /* random u with J u = 0: u^T M (v1 - v) = 0 */
    for (trial = 0; trial < 5; trial++) {
        double u[N], dp = 0.0, scale = 0.0;
        for (i = 0; i < N; i++) {
            seed = seed * 1103515245u + 12345u;
            u[i] = ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
        }
        for (k = 0; k < NM; k++) { /* remove the J_k component on the node pair */
            double jj = rows[k].j[0] * rows[k].j[0] + rows[k].j[1] * rows[k].j[1];
            double ju = rows[k].j[0] * u[rows[k].dof[0]] + rows[k].j[1] * u[rows[k].dof[1]];
            u[rows[k].dof[0]] -= ju * rows[k].j[0] / jj;
            u[rows[k].dof[1]] -= ju * rows[k].j[1] / jj;
        }
        for (i = 0; i < N; i++)
            for (j = 0; j < N; j++) {
                dp += u[i] * M[i + j * N] * (v1[j] - v[j]);
                scale += fabs(u[i] * M[i + j * N] * v[j]);
            }
        assert_close(dp, 0.0, 0.0, 1e-13 * scale);
    }
}

static void test_dense_solve_singular(void **state)
{
    double A[4] = {1.0, 2.0, 2.0, 4.0}, b[2] = {1.0, 1.0};
    double A2[9] = {0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 3.0}, b2[3] = {2.0, 1.0, 3.0};
    (void)state;
    assert_int_equal(td_contact_dense_solve(2, A, b), -1);
    /* needs pivoting: [[0 2 0],[1 0 0],[0 0 3]] x = (2, 1, 3) -> x = (1, 1, 1) */
    assert_int_equal(td_contact_dense_solve(3, A2, b2), 0);
    assert_close(b2[0], 1.0, 1e-15, 0.0);
    assert_close(b2[1], 1.0, 1e-15, 0.0);
    assert_close(b2[2], 1.0, 1e-15, 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_penalty_never_pulls),
        cmocka_unit_test(test_penalty_elastic_values),
        cmocka_unit_test(test_hunt_crossley_starts_at_zero),
        cmocka_unit_test(test_penalty_derivatives),
        cmocka_unit_test(test_constraint_geometry),
        cmocka_unit_test(test_sliding_velocity_and_friction),
        cmocka_unit_test(test_slip_factor_and_gradient),
        cmocka_unit_test(test_impact_lumped),
        cmocka_unit_test(test_impact_consistent_two_constraints),
        cmocka_unit_test(test_dense_solve_singular),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
