/*
 * Overhung disc: forward and backward whirl of a disc (m, Ip, Id) at the tip of a massless
 * cantilever against the closed form.
 *
 * Model: one Euler-Bernoulli element (L = 0.3 m, d = 50 mm, E = 2.11e11 Pa, density 1e-3 kg/m^3:
 * shaft mass 5.9e-7 kg against the 10 kg disc) assembled by td_system_create, the disc of the
 * reference rig (m = 10 kg, Ip = 0.072, Id = 0.036668 kg m^2) at the tip node 1. The root node 0
 * is clamped by adding penalty stiffness to its four DOFs in K (the model's bearings have no
 * moment stiffness): 1e9 times the element's own diagonal terms.
 *
 * Closed form, per whirl direction s = +1 (forward) or -1 (backward), the tip stiffness
 * K = EI/L^3 [[12, -6L], [-6L, 4L^2]] on (x, phi):
 *   det([[k11 - m w^2, k12], [k12, k22 - Id w^2 + s Ip Omega w]]) = 0,
 * a quartic in w solved with gsl_poly_complex_solve; its two positive roots are the two whirl
 * frequencies of that direction.
 * Error budget: shaft mass effect ~ m_shaft/m = 6e-8, clamp compliance 1e-9, round-off of the
 * stiff, nearly massless root DOFs (spectrum up to ~1e11 rad/s) ~1e-7: asserted 1e-6.
 */
#include "td_test.h"

#include "model/system_internal.h"
#include "touchdown/modal.h"
#include "touchdown/touchdown.h"

#include <gsl/gsl_poly.h>

#include <math.h>
#include <stdlib.h>

#define L_SHAFT 0.3
#define D_SHAFT 0.05
#define E_SHAFT 2.11e11
#define M_DISC 10.0
#define IP_DISC 0.072
#define ID_DISC 0.036668
#define PENALTY 1e9

static double ei(void)
{
    return E_SHAFT * TD_PI * pow(D_SHAFT, 4) / 64.0;
}

/* Add v to the existing entry (i, i) of a compressed matrix. */
static void add_diagonal(cs_di *A, int i, double v)
{
    int p;
    for (p = A->p[i]; p < A->p[i + 1]; p++)
        if (A->i[p] == i) {
            A->x[p] += v;
            return;
        }
    fail_msg("no diagonal entry %d", i);
}

static td_system *cantilever(void)
{
    td_model *m = NULL;
    td_system *s = NULL;
    td_shaft_element el = {L_SHAFT, D_SHAFT, 0.0, {E_SHAFT, 8.1e10, 1e-3}};
    td_disc d = {1, M_DISC, IP_DISC, ID_DISC};
    double k = ei() / pow(L_SHAFT, 3);
    td_error err;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(m, &d, NULL), TD_OK);
    if (td_system_create(m, &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    td_model_free(&m);
    /* clamp node 0: x, y against 12 EI/L^3, rotations against 4 EI/L */
    add_diagonal(s->K, TD_DOF(0, TD_DOF_X), PENALTY * 12.0 * k);
    add_diagonal(s->K, TD_DOF(0, TD_DOF_Y), PENALTY * 12.0 * k);
    add_diagonal(s->K, TD_DOF(0, TD_DOF_THETA), PENALTY * 4.0 * k * L_SHAFT * L_SHAFT);
    add_diagonal(s->K, TD_DOF(0, TD_DOF_PHI), PENALTY * 4.0 * k * L_SHAFT * L_SHAFT);
    return s;
}

/* The two positive roots (ascending) of the closed-form quartic for whirl sense `sense`. */
static void closed_form(double omega, int sense, double w[2])
{
    double k = ei() / pow(L_SHAFT, 3), L = L_SHAFT;
    double k11 = 12.0 * k, k12 = -6.0 * L * k, k22 = 4.0 * L * L * k;
    double g = sense * IP_DISC * omega, a[5], z[8];
    gsl_poly_complex_workspace *ws = gsl_poly_complex_workspace_alloc(5);
    int i, n = 0;
    /* (k11 - m w^2)(k22 - Id w^2 + g w) - k12^2, ascending powers of w */
    a[0] = k11 * k22 - k12 * k12;
    a[1] = k11 * g;
    a[2] = -(k11 * ID_DISC + M_DISC * k22);
    a[3] = -M_DISC * g;
    a[4] = M_DISC * ID_DISC;
    assert_int_equal(gsl_poly_complex_solve(a, 5, ws, z), 0);
    gsl_poly_complex_workspace_free(ws);
    for (i = 0; i < 4; i++)
        if (fabs(z[2 * i + 1]) <= 1e-9 * fabs(z[2 * i]) && z[2 * i] > 0.0) {
            assert_true(n < 2);
            w[n++] = z[2 * i];
        }
    assert_int_equal(n, 2);
    if (w[0] > w[1]) {
        double t = w[0];
        w[0] = w[1];
        w[1] = t;
    }
}

/* The lowest two modes of whirl `which` among the first 4 modes (the root DOFs' modes lie far above). */
static void fe_whirl(const td_modal *md, td_whirl which, double w[2])
{
    int i, n = 0;
    for (i = 0; i < 4; i++) {
        td_mode mode;
        assert_int_equal(td_modal_get_mode(md, i, &mode), TD_OK);
        if (mode.whirl == which)
            w[n++] = mode.omega_d;
    }
    assert_int_equal(n, 2);
}

static void test_whirl_frequencies(void **state)
{
    td_system *s = cantilever();
    static const double speeds[4] = {0.0, 500.0, 1000.0, 3000.0};
    double prev_forward = 0.0, prev_backward = HUGE_VAL;
    int k, j;
    (void)state;
    for (k = 0; k < 4; k++) {
        td_modal *md = NULL;
        double cf[2], cb[2], wf[2], wb[2];
        assert_int_equal(td_modal_solve(s, speeds[k], &md, NULL), TD_OK);
        closed_form(speeds[k], +1, cf);
        closed_form(speeds[k], -1, cb);
        fe_whirl(md, TD_WHIRL_FORWARD, wf);
        fe_whirl(md, TD_WHIRL_BACKWARD, wb);
        for (j = 0; j < 2; j++) {
            assert_close(wf[j], cf[j], 1e-6, 0.0);
            assert_close(wb[j], cb[j], 1e-6, 0.0);
            print_message(
                "Omega %6.0f: forward %d %.12g (closed %.12g, %.1e), backward %d %.12g (closed %.12g, %.1e)\n",
                speeds[k], j, wf[j], cf[j], td_rel_diff(wf[j], cf[j]), j, wb[j], cb[j], td_rel_diff(wb[j], cb[j]));
        }
        /* the forward (conical) whirl stiffens with speed, the backward one softens */
        if (k > 0) {
            assert_true(wf[1] > prev_forward);
            assert_true(wb[1] < prev_backward);
        }
        prev_forward = wf[1];
        prev_backward = wb[1];
        td_modal_free(&md);
    }
    td_system_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_whirl_frequencies),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
