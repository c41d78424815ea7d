/*
 * First contact of case A against the exact solution of the linear contact-free system.
 *
 * Case A (docs/reference-rig.md): the rig at 90 rad/s on the steady orbit for U = 0.02 kg m; at
 * t1 = 0.1 s the unbalance steps to 0.10 kg m and the NDE retainer node (node 2) reaches the
 * clearance circle a few milliseconds later. Until then the system is linear, so
 *
 *   z(t) = z_p2(t) + exp(A (t - t1)) (z_p1(t1) - z_p2(t1)),   z_pk(t) = Re(Z_k e^{i Omega t}),
 *
 * with A the dense first-order matrix built HERE from td_system_dense's M, K, C, G and the AMB
 * law of docs/reference-rig.md (F = ks x + Fc, tau Fc' = -Fc - ki (kp x + kd x')), independently of
 * lib/sim and lib/modal, and (i Omega - A) Z_k = [0; M^-1 F_k; 0] solved by complex LU (GSL). The
 * exponential is GSL's scaling-and-squaring Taylor expm. The contact time is bracketed on a 10 us
 * grid and bisected on r(t) = c to 1e-14 s; the impact velocity is the node's radial velocity
 * there. The exponential is taken of the balanced matrix D^-1 A D (gsl_linalg_balance_matrix):
 * unbalanced, the stiff A (entries ~ omega_max^2 ~ 1e10) cost expm ~1e-9 s in the contact time.
 * The reference is reproducible to 1e-13 s and 4e-11 relative across grids of 2 to 100 us.
 * The simulation's free flight in closed form (lib/sim/flight.c, default tolerances) must agree to
 * 1e-9 s and 1e-8 relative; IDA alone at tight tolerances to 1e-8 s and 1e-6 relative; IDA at the
 * default tolerances is printed only (measured: 7.8e-7 s and 6e-3 relative).
 */
#include "td_test.h"

#include "touchdown/case.h"
#include "touchdown/touchdown.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_complex.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_permutation.h>
#include <gsl/gsl_vector.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct exact {
    int n, N;       /* DOFs, first-order states */
    gsl_matrix *A;  /* N x N */
    gsl_matrix *Ab; /* balanced: Ab = D^-1 A D (GSL's diagonal balancing), so that exp(A t) =
                     * D exp(Ab t) D^-1 is computed on a matrix of norm ~ omega_max, not omega_max^2 */
    gsl_vector *D;
    gsl_vector *Zre1, *Zim1; /* harmonic amplitude per unit unbalance */
    double omega, c, t1;
    int node; /* retainer node */
} exact;

/* Dense copy of one system matrix into a GSL matrix. */
static gsl_matrix *dense(const td_system *sys, td_matrix_kind which, int n)
{
    double *buf = malloc(sizeof(double) * n * n);
    gsl_matrix *m = gsl_matrix_alloc(n, n);
    int i, j;
    assert_int_equal(td_system_dense(sys, which, buf, NULL), TD_OK);
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            gsl_matrix_set(m, i, j, buf[i + j * n]);
    free(buf);
    return m;
}

/* A = [0 I 0; -M^-1 Keff, -M^-1 (C + Omega G), M^-1 B; AMB filter rows]. Returns the filter count. */
static int build_state_matrix(const td_model *model, const td_system *sys, double omega, exact *ex)
{
    int n = td_system_dof_count(sys), na = td_model_amb_count(model), nw = 2 * na, N = 2 * n + nw, i, j, k;
    gsl_matrix *M = dense(sys, TD_MATRIX_MASS, n), *K = dense(sys, TD_MATRIX_STIFFNESS, n);
    gsl_matrix *C = dense(sys, TD_MATRIX_DAMPING, n), *G = dense(sys, TD_MATRIX_GYROSCOPIC, n);
    gsl_matrix *Minv = gsl_matrix_alloc(n, n), *R = gsl_matrix_calloc(n, N);
    gsl_permutation *p = gsl_permutation_alloc(n);
    gsl_matrix *A = gsl_matrix_calloc(N, N);
    gsl_matrix_view blk;
    int sgn;
    /* right-hand side blocks R = [-Keff, -(C + Omega G), B] of M v' = R z */
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            gsl_matrix_set(R, i, j, -gsl_matrix_get(K, i, j));
            gsl_matrix_set(R, i, n + j, -gsl_matrix_get(C, i, j) - omega * gsl_matrix_get(G, i, j));
        }
    for (k = 0; k < na; k++) {
        td_amb a;
        assert_int_equal(td_model_get_amb(model, k, &a), TD_OK);
        assert_true(a.tau > 0.0 && !a.saturation);
        for (j = 0; j < 2; j++) { /* axis x (j = 0) then y */
            int act = 4 * a.node + j, sen = 4 * a.sensor_node + j, w = 2 * n + 2 * k + j;
            *gsl_matrix_ptr(R, act, act) += a.ks; /* F = ks x + Fc */
            *gsl_matrix_ptr(R, act, w) += 1.0;
            gsl_matrix_set(A, w, w, -1.0 / a.tau); /* tau Fc' = -Fc - ki (kp xs + kd vs) */
            gsl_matrix_set(A, w, sen, -a.ki * a.kp / a.tau);
            gsl_matrix_set(A, w, n + sen, -a.ki * a.kd / a.tau);
        }
    }
    gsl_linalg_LU_decomp(M, p, &sgn);
    gsl_linalg_LU_invert(M, p, Minv);
    blk = gsl_matrix_submatrix(A, n, 0, n, N);
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, Minv, R, 0.0, &blk.matrix);
    for (i = 0; i < n; i++)
        gsl_matrix_set(A, i, n + i, 1.0);
    ex->A = A;
    ex->n = n;
    ex->N = N;
    /* harmonic amplitude of the unbalance at U = 1: (i Omega - A) Z = [0; M^-1 F; 0] */
    {
        td_unbalance u;
        gsl_matrix_complex *S = gsl_matrix_complex_alloc(N, N);
        gsl_vector_complex *b = gsl_vector_complex_calloc(N), *z = gsl_vector_complex_alloc(N);
        gsl_permutation *pc = gsl_permutation_alloc(N);
        gsl_complex fx, fy;
        assert_int_equal(td_model_get_unbalance(model, 0, &u), TD_OK);
        /* F_x = Omega^2 cos(Omega t + ph) = Re(Omega^2 e^{i ph} e^{i Omega t}), F_y = Re(-i ...) */
        fx = gsl_complex_polar(omega * omega, u.phase);
        fy = gsl_complex_mul(fx, gsl_complex_rect(0.0, -1.0));
        for (i = 0; i < n; i++) {
            gsl_complex s = gsl_complex_add(gsl_complex_mul_real(fx, gsl_matrix_get(Minv, i, 4 * u.node)),
                                            gsl_complex_mul_real(fy, gsl_matrix_get(Minv, i, 4 * u.node + 1)));
            gsl_vector_complex_set(b, n + i, s);
        }
        for (i = 0; i < N; i++)
            for (j = 0; j < N; j++)
                gsl_matrix_complex_set(S, i, j, gsl_complex_rect(-gsl_matrix_get(A, i, j), i == j ? omega : 0.0));
        gsl_linalg_complex_LU_decomp(S, pc, &sgn);
        gsl_linalg_complex_LU_solve(S, pc, b, z);
        ex->Zre1 = gsl_vector_alloc(N);
        ex->Zim1 = gsl_vector_alloc(N);
        for (i = 0; i < N; i++) {
            ex->Zre1->data[i] = GSL_REAL(gsl_vector_complex_get(z, i));
            ex->Zim1->data[i] = GSL_IMAG(gsl_vector_complex_get(z, i));
        }
        gsl_matrix_complex_free(S);
        gsl_vector_complex_free(b);
        gsl_vector_complex_free(z);
        gsl_permutation_free(pc);
    }
    gsl_matrix_free(M), gsl_matrix_free(K), gsl_matrix_free(C), gsl_matrix_free(G);
    gsl_matrix_free(Minv), gsl_matrix_free(R);
    gsl_permutation_free(p);
    return nw;
}

/* z_p(t) = U Re(Z e^{i Omega t}) for the unit amplitude in Zre1/Zim1. */
static void harmonic(const exact *ex, double U, double t, gsl_vector *z)
{
    double c = cos(ex->omega * t), s = sin(ex->omega * t);
    int i;
    for (i = 0; i < ex->N; i++)
        z->data[i] = U * (ex->Zre1->data[i] * c - ex->Zim1->data[i] * s);
}

/* exp(A tau) x for x in balanced coordinates (x = D^-1 z): result also balanced. */
static void propagate(const exact *ex, double tau, const gsl_vector *x, gsl_vector *out)
{
    gsl_matrix *E = gsl_matrix_alloc(ex->N, ex->N), *At = gsl_matrix_alloc(ex->N, ex->N);
    gsl_matrix_memcpy(At, ex->Ab);
    gsl_matrix_scale(At, tau);
    assert_int_equal(gsl_linalg_exponential_ss(At, E, GSL_PREC_DOUBLE), 0);
    gsl_blas_dgemv(CblasNoTrans, 1.0, E, x, 0.0, out);
    gsl_matrix_free(E), gsl_matrix_free(At);
}

/* z(t) = z_p(U2, t) + D exp(Ab (t - t_h)) x_h, x_h the balanced homogeneous part at t_h. */
static void state_at(const exact *ex, double U2, double t_h, const gsl_vector *x_h, double t, gsl_vector *z)
{
    gsl_vector *zp = gsl_vector_alloc(ex->N);
    propagate(ex, t - t_h, x_h, z);
    gsl_vector_mul(z, ex->D);
    harmonic(ex, U2, t, zp);
    gsl_vector_add(z, zp);
    gsl_vector_free(zp);
}

static double radius(const exact *ex, const gsl_vector *z)
{
    return hypot(z->data[4 * ex->node], z->data[4 * ex->node + 1]);
}

/* Exact first contact after t1: time and radial velocity of the retainer node. */
static void exact_first_contact(exact *ex, double U1, double U2, double *t_contact, double *v_radial)
{
    const double h = 1e-5;
    gsl_matrix *E = gsl_matrix_alloc(ex->N, ex->N), *Ah = gsl_matrix_alloc(ex->N, ex->N);
    gsl_vector *xk = gsl_vector_alloc(ex->N), *tmp = gsl_vector_alloc(ex->N), *z = gsl_vector_alloc(ex->N);
    double tk = ex->t1, lo, hi;
    int k, i;
    /* balance once: Ab = D^-1 A D */
    ex->Ab = gsl_matrix_alloc(ex->N, ex->N);
    ex->D = gsl_vector_alloc(ex->N);
    gsl_matrix_memcpy(ex->Ab, ex->A);
    assert_int_equal(gsl_linalg_balance_matrix(ex->Ab, ex->D), 0);
    /* homogeneous part at t1: z_p1(t1) - z_p2(t1) = (U1 - U2) Re(Z e^{i Omega t1}), balanced */
    harmonic(ex, U1 - U2, ex->t1, xk);
    gsl_vector_div(xk, ex->D);
    gsl_matrix_memcpy(Ah, ex->Ab);
    gsl_matrix_scale(Ah, h);
    assert_int_equal(gsl_linalg_exponential_ss(Ah, E, GSL_PREC_DOUBLE), 0);
    for (k = 0; k < 100000; k++) { /* march on a grid of step h until r >= c */
        gsl_blas_dgemv(CblasNoTrans, 1.0, E, xk, 0.0, tmp);
        gsl_vector_memcpy(z, tmp);
        gsl_vector_mul(z, ex->D);
        {
            gsl_vector *zp = gsl_vector_alloc(ex->N);
            harmonic(ex, U2, tk + h, zp);
            gsl_vector_add(z, zp);
            gsl_vector_free(zp);
        }
        if (radius(ex, z) >= ex->c)
            break;
        gsl_vector_memcpy(xk, tmp);
        tk += h;
    }
    assert_true(k < 100000);
    lo = tk;
    hi = tk + h;
    for (i = 0; i < 200 && hi - lo > 1e-14; i++) {
        double mid = 0.5 * (lo + hi);
        state_at(ex, U2, tk, xk, mid, z);
        if (radius(ex, z) >= ex->c)
            hi = mid;
        else
            lo = mid;
    }
    *t_contact = hi;
    state_at(ex, U2, tk, xk, hi, z);
    {
        double x = z->data[4 * ex->node], y = z->data[4 * ex->node + 1];
        double vx = z->data[ex->n + 4 * ex->node], vy = z->data[ex->n + 4 * ex->node + 1];
        *v_radial = (x * vx + y * vy) / hypot(x, y);
    }
    gsl_matrix_free(E), gsl_matrix_free(Ah);
    gsl_vector_free(xk), gsl_vector_free(tmp), gsl_vector_free(z);
}

/* Run the simulation to its first contact onset (free flight in closed form or integrated);
 * returns the event. */
static td_event sim_first_contact(const td_case *c, double rtol, double atol, int free_flight, td_sim_stats *st)
{
    td_sim_options o = *td_case_sim_options(c);
    td_sim *s = NULL;
    td_error err;
    td_event ev;
    memset(&ev, 0, sizeof ev);
    o.solver.rtol = rtol;
    o.solver.atol = atol;
    o.solver.max_order = 2;
    o.solver.free_flight = free_flight;
    if (td_sim_create(td_case_model(c), &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    for (;;) {
        td_status r = td_sim_step(s, 0.2, NULL, &err);
        if (r == TD_EVENT) {
            td_sim_last_event(s, &ev);
            if (ev.kind == TD_EVENT_CONTACT_ONSET)
                break;
            continue;
        }
        fail_msg("no contact before 0.2 s (%s)", err.message);
    }
    td_sim_stats_get(s, st);
    td_sim_free(&s);
    return ev;
}

static void test_case_a_first_contact(void **state)
{
    td_case *c = NULL;
    td_error err;
    td_system *sys = NULL;
    td_retainer ret;
    td_change ch;
    td_unbalance u;
    exact ex;
    double t_exact, v_exact;
    td_event ev;
    td_sim_stats st;
    (void)state;
    if (td_case_load(td_source_path("cases/paper-a.cfg"), NULL, 0, &c, &err) != TD_OK)
        fail_msg("%s", err.message);
    assert_int_equal(td_system_create(td_case_model(c), &sys, NULL), TD_OK);
    memset(&ex, 0, sizeof ex);
    ex.omega = td_model_speed(td_case_model(c));
    td_model_get_retainer(td_case_model(c), 0, &ret);
    td_model_get_change(td_case_model(c), 0, &ch);
    td_model_get_unbalance(td_case_model(c), 0, &u);
    ex.c = ret.clearance;
    ex.node = ret.node;
    ex.t1 = ch.time;
    build_state_matrix(td_case_model(c), sys, ex.omega, &ex);
    exact_first_contact(&ex, u.magnitude, ch.magnitude, &t_exact, &v_exact);
    print_message("exact first contact t = %.15f s, radial velocity %.12g m/s\n", t_exact, v_exact);

    ev = sim_first_contact(c, 1e-6, 1e-9, 1, &st);
    print_message("free flight in closed form, defaults: t = %.15f s (error %.3g s), v_r = %.12g (rel. error %.3g), "
                  "%ld flight steps, %ld IDA steps\n",
                  ev.time, ev.time - t_exact, ev.radial_velocity_before,
                  td_rel_diff(ev.radial_velocity_before, v_exact), st.flight_steps, st.steps);
    assert_close(ev.time, t_exact, 0.0, 1e-9);
    assert_close(ev.radial_velocity_before, v_exact, 1e-8, 0.0);
    assert_close(st.flight_time, t_exact, 0.0, 1e-9); /* the whole way in closed form */
    ev = sim_first_contact(c, 1e-6, 1e-9, 0, &st);
    print_message(
        "IDA, defaults (rtol 1e-6, atol 1e-9): t = %.15f s (error %.3g s), v_r = %.12g (rel. error %.3g), %ld steps\n",
        ev.time, ev.time - t_exact, ev.radial_velocity_before, td_rel_diff(ev.radial_velocity_before, v_exact),
        st.steps);
    ev = sim_first_contact(c, 1e-12, 1e-16, 0, &st);
    print_message(
        "tight (rtol 1e-12, atol 1e-16): t = %.15f s (error %.3g s), v_r = %.12g (rel. error %.3g), %ld steps\n",
        ev.time, ev.time - t_exact, ev.radial_velocity_before, td_rel_diff(ev.radial_velocity_before, v_exact),
        st.steps);
    assert_close(ev.time, t_exact, 0.0, 1e-8);
    assert_close(ev.radial_velocity_before, v_exact, 1e-6, 0.0);

    gsl_matrix_free(ex.A);
    gsl_matrix_free(ex.Ab);
    gsl_vector_free(ex.D);
    gsl_vector_free(ex.Zre1), gsl_vector_free(ex.Zim1);
    td_system_free(&sys);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_case_a_first_contact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
