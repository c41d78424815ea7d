/*
 * Continuous linear controllers (touchdown/controller.h) in the model, the simulation and the
 * closed-loop analysis. Independent references: the shorthand PD law (the same PD written as a
 * transfer function gives the same eigenvalues and the same run), scipy (the closed loop of the rig
 * with a lead-lag + notch controller built from the plant's matrices by
 * tests/validation/control/closed_loop.py, its own realisation and its own loop), central
 * differences of the residual (the Jacobian), the simulation without the closed-form flight (the
 * flight with controller states), and the AMB law's definition (an AMB that is off exerts nothing).
 */
#include "td_jacobian.h"
#include "td_rig.h"
#include "td_test.h"

#include "sim/sim_internal.h"
#include "touchdown/touchdown.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RIG_SPEED 90.0 /* rad/s, the paper's case A */
#define RIG_KP 1.0e4
#define RIG_KD 40.0

/* ---- models -------------------------------------------------------------------------------- */

/* The rig as td_test_build_rig makes it, with its AMBs' shorthand gains set to 0 (a controller
 * then drives them): every part copied through the model's getters. */
static td_model *rig_without_gains(double tau, int retainers)
{
    td_model *src = td_test_rig_create(RIG_SPEED, tau, retainers), *m = NULL;
    td_shaft_options so;
    int i;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    td_model_shaft_options(src, &so);
    assert_int_equal(td_model_set_shaft_options(m, &so, NULL), TD_OK);
    for (i = 0; i < td_model_shaft_element_count(src); i++) {
        td_shaft_element e;
        assert_int_equal(td_model_get_shaft_element(src, i, &e), TD_OK);
        assert_int_equal(td_model_add_shaft_element(m, &e, NULL), TD_OK);
    }
    for (i = 0; i < td_model_disc_count(src); i++) {
        td_disc d;
        assert_int_equal(td_model_get_disc(src, i, &d), TD_OK);
        assert_int_equal(td_model_add_disc(m, &d, NULL), TD_OK);
    }
    for (i = 0; i < td_model_amb_count(src); i++) {
        td_amb a;
        assert_int_equal(td_model_get_amb(src, i, &a), TD_OK);
        a.kp = a.kd = a.kint = 0.0;
        assert_int_equal(td_model_add_amb(m, &a, NULL), TD_OK);
    }
    for (i = 0; i < td_model_retainer_count(src); i++) {
        td_retainer r;
        assert_int_equal(td_model_get_retainer(src, i, &r), TD_OK);
        assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    }
    assert_int_equal(td_model_bearing_count(src) + td_model_unbalance_count(src) + td_model_change_count(src), 0);
    assert_int_equal(td_model_set_speed(m, td_model_speed(src), NULL), TD_OK);
    td_model_free(&src);
    return m;
}

/* Controller k (SISO) on every AMB axis of m, one copy per axis, reading that axis's sensor. */
static void drive_every_axis(td_model *m, const td_controller *k)
{
    int axis;
    for (axis = 0; axis < 2 * td_model_amb_count(m); axis++) {
        char name[16];
        td_error err;
        snprintf(name, sizeof name, "axis%d", axis);
        if (td_model_add_controller(m, name, k, &axis, &axis, &err) != TD_OK)
            fail_msg("add_controller: %s", err.message);
    }
}

/* The shorthand PD kp + kd s as a transfer function: no state, D = kp, velocity feedthrough kd. */
static td_controller *pd_as_tf(void)
{
    const double num[2] = {RIG_KD, RIG_KP}, den[1] = {1.0};
    td_error err;
    td_controller *k = td_controller_create_tf(num, 2, den, 1, 0.0, &err);
    if (!k)
        fail_msg("create_tf: %s", err.message);
    assert_int_equal(td_controller_order(k), 0);
    assert_int_equal(td_controller_has_velocity_feedthrough(k), 1);
    return k;
}

/* The lead-lag + notch of the scipy comparison (closed_loop.py reads these six numbers). */
static const double LAW[6] = {1.0e4, 40.0, 400.0, 34.4, 6.0, 0.05};

static td_controller *leadlag_notch(void)
{
    td_leadlag_block ll = {LAW[0], LAW[1], LAW[2]};
    td_notch_block nb = {LAW[3], LAW[4], LAW[5]};
    td_error err;
    td_controller *a = td_controller_create_leadlag(&ll, &err), *b = a ? td_controller_create_notch(&nb, &err) : NULL;
    td_controller *k = b ? td_controller_series(a, b, &err) : NULL;
    if (!k)
        fail_msg("lead-lag + notch: %s", err.message);
    td_controller_free(&a);
    td_controller_free(&b);
    return k;
}

static td_model *rig_with_law(double tau, int retainers, const td_controller *k)
{
    td_model *m = rig_without_gains(tau, retainers);
    drive_every_axis(m, k);
    return m;
}

/* ---- eigenvalues --------------------------------------------------------------------------- */

/* Every eigenvalue of the closed loop at RIG_SPEED (a pair as both members) into ev (capacity
 * cap), td_modal_state_count + `extra` of them (the states of sampled controllers); returns the count. */
static int closed_loop_eigenvalues(const td_model *m, double complex *ev, int cap, int extra)
{
    td_system *sys = NULL;
    td_modal *md = NULL;
    td_error err;
    int i, n = 0;
    if (td_system_create(m, &sys, &err) != TD_OK || td_modal_solve(sys, RIG_SPEED, &md, &err) != TD_OK)
        fail_msg("modal: %s", err.message);
    assert_int_equal(td_modal_rounding_count(md), 0);
    for (i = 0; i < td_modal_mode_count(md); i++) {
        td_mode mo;
        assert_int_equal(td_modal_get_mode(md, i, &mo), TD_OK);
        assert_true(n + 2 <= cap);
        ev[n++] = mo.sigma + I * mo.omega_d;
        ev[n++] = mo.sigma - I * mo.omega_d;
    }
    for (i = 0; i < td_modal_real_count(md); i++) {
        assert_true(n < cap);
        ev[n++] = td_modal_real_eigenvalue(md, i);
    }
    assert_int_equal(n, td_modal_state_count(sys) + extra);
    td_modal_free(&md);
    td_system_free(&sys);
    return n;
}

/* Each of a's n eigenvalues has one of b's within rtol |a_i| (each of b's used once); returns the
 * largest relative distance. */
static double match_eigenvalues(const double complex *a, const double complex *b, int n, double rtol)
{
    char *used = calloc((size_t)n, 1);
    double worst = 0.0;
    int i, j;
    assert_non_null(used);
    for (i = 0; i < n; i++) {
        int best = -1;
        for (j = 0; j < n; j++)
            if (!used[j] && (best < 0 || cabs(b[j] - a[i]) < cabs(b[best] - a[i])))
                best = j;
        used[best] = 1;
        worst = fmax(worst, cabs(b[best] - a[i]) / cabs(a[i]));
        if (!(cabs(b[best] - a[i]) <= rtol * cabs(a[i])))
            fail_msg("eigenvalue %.12g%+.12gi: nearest %.12g%+.12gi", creal(a[i]), cimag(a[i]), creal(b[best]),
                     cimag(b[best]));
    }
    free(used);
    return worst;
}

/* (a) the shorthand PD and the same PD as a transfer function: the same closed loop */
static void test_pd_eigenvalues_equal_shorthand(void **state)
{
    const double taus[2] = {TD_RIG_TAU, 0.0};
    double complex ea[160], eb[160];
    int t;
    (void)state;
    for (t = 0; t < 2; t++) {
        td_model *shorthand = td_test_rig_create(RIG_SPEED, taus[t], TD_RIG_NO_RETAINERS);
        td_controller *k = pd_as_tf();
        td_model *lti = rig_with_law(taus[t], TD_RIG_NO_RETAINERS, k);
        int na = closed_loop_eigenvalues(shorthand, ea, 160, 0), nb = closed_loop_eigenvalues(lti, eb, 160, 0);
        double worst;
        assert_int_equal(na, nb);
        worst = match_eigenvalues(ea, eb, na, 1e-10);
        print_message("PD as a transfer function, tau %.3g s: %d eigenvalues, largest relative difference %.3g\n",
                      taus[t], na, worst);
        td_controller_free(&k);
        td_model_free(&shorthand);
        td_model_free(&lti);
    }
}

/* ---- runs ---------------------------------------------------------------------------------- */

/* The drop scenario on m: gravity, an unbalance, both AMBs off at 20 ms and back on at 70 ms. */
static void add_drop(td_model *m)
{
    td_unbalance u = {6, 2.0e-4, 0.3};
    td_change c = {0};
    int a;
    assert_int_equal(td_model_set_gravity(m, 0.0, -9.81, NULL), TD_OK);
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    for (a = 0; a < 2; a++) {
        c.index = a;
        c.kind = TD_CHANGE_AMB_OFF;
        c.time = 0.02;
        assert_int_equal(td_model_add_change(m, &c, NULL), TD_OK);
        c.kind = TD_CHANGE_AMB_ON;
        c.time = 0.07;
        assert_int_equal(td_model_add_change(m, &c, NULL), TD_OK);
    }
}

/* A simulation of m with the default options, the closed-form flight on or off, the tolerances
 * divided by `tighter`. */
static td_sim *make_sim_tol(const td_model *m, int free_flight, double tighter)
{
    td_sim_options o;
    td_sim *sim = NULL;
    td_error err;
    td_sim_options_default(&o);
    o.solver.free_flight = free_flight;
    o.solver.rtol /= tighter;
    o.solver.atol /= tighter;
    o.start = TD_START_AUTO; /* the steady orbit, or rest for an unstable loop (the Jacobian's test) */
    if (td_sim_create(m, &o, &sim, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    return sim;
}

static td_sim *make_sim(const td_model *m, int free_flight)
{
    return make_sim_tol(m, free_flight, 1.0);
}

static void run_to(td_sim *sim, double t_end)
{
    double t = td_sim_time(sim);
    td_error err;
    while (t < t_end) {
        td_status st = td_sim_step(sim, t_end, &t, &err);
        if (st != TD_OK && st != TD_EVENT)
            fail_msg("step: %s", err.message);
    }
}

/* Largest |q_a - q_b| over the translations of two runs of the same rotor. */
static double state_distance(const td_sim *a, const td_sim *b)
{
    int n = td_sim_dof_count(a), i;
    double *qa = calloc(4 * (size_t)n, sizeof(double)), *qb = qa + 2 * n, worst = 0.0;
    assert_non_null(qa);
    assert_int_equal(td_sim_dof_count(b), n);
    assert_int_equal(td_sim_get_state(a, qa, qa + n), TD_OK);
    assert_int_equal(td_sim_get_state(b, qb, qb + n), TD_OK);
    for (i = 0; i < n; i++)
        if (i % TD_DOFS_PER_NODE == TD_DOF_X || i % TD_DOFS_PER_NODE == TD_DOF_Y)
            worst = fmax(worst, fabs(qa[i] - qb[i]));
    free(qa);
    return worst;
}

/* (a) a 0.3 s drop onto the retainers and the recovery, shorthand PD against the PD as a
 * transfer function: the same answers to the solver's tolerance */
static void test_pd_run_equals_shorthand(void **state)
{
    td_model *shorthand = td_test_rig_create(RIG_SPEED, TD_RIG_TAU, TD_RIG_WITH_RETAINERS);
    td_controller *k = pd_as_tf();
    td_model *lti = rig_with_law(TD_RIG_TAU, TD_RIG_WITH_RETAINERS, k);
    td_sim *sa, *sb;
    td_sim_stats a, b;
    td_sim_options o;
    double dq;
    (void)state;
    add_drop(shorthand);
    add_drop(lti);
    sa = make_sim(shorthand, 1);
    sb = make_sim(lti, 1);
    run_to(sa, 0.3);
    run_to(sb, 0.3);
    assert_int_equal(td_sim_stats_get(sa, &a), TD_OK);
    assert_int_equal(td_sim_stats_get(sb, &b), TD_OK);
    assert_int_equal(td_sim_options_get(sa, &o), TD_OK);
    dq = state_distance(sa, sb);
    print_message("drop, shorthand / transfer function: first contact %.9g / %.9g s, onsets %ld / %ld, peak normal "
                  "force %.6g / %.6g N, time in contact %.6g / %.6g s, peak AMB force %.6g / %.6g N, final |dq| %.3g m "
                  "(atol %.3g m)\n",
                  a.first_contact_time, b.first_contact_time, a.contact_onsets, b.contact_onsets, a.peak_normal_force,
                  b.peak_normal_force, a.time_in_contact, b.time_in_contact, a.peak_amb_force, b.peak_amb_force, dq,
                  o.solver.atol);
    assert_true(a.contact_onsets > 0);
    assert_int_equal(a.contact_onsets, b.contact_onsets);
    assert_close(b.first_contact_time, a.first_contact_time, 0.0, 1e-6);
    assert_close(b.peak_normal_force, a.peak_normal_force, 1e-3, 0.0);
    assert_close(b.time_in_contact, a.time_in_contact, 1e-3, 1e-5);
    assert_close(b.peak_amb_force, a.peak_amb_force, 1e-4, 0.0);
    assert_true(dq <= 10.0 * o.solver.atol);
    td_sim_free(&sa);
    td_sim_free(&sb);
    td_controller_free(&k);
    td_model_free(&shorthand);
    td_model_free(&lti);
}

/* The AMB forces of every AMB, largest |component|. */
static double amb_force_max(const td_sim *sim)
{
    double worst = 0.0, f[2];
    int a;
    for (a = 0; a < td_model_amb_count(td_sim_model(sim)); a++) {
        assert_int_equal(td_sim_amb_force(sim, a, f), TD_OK);
        worst = fmax(worst, fmax(fabs(f[0]), fabs(f[1])));
    }
    return worst;
}

/* (c) a PID with its integrator (a pole at 0) on every axis, levitating under gravity: the AMB
 * force is exactly 0 while the AMBs are off (the controller runs on and winds up), the run stays
 * finite, the integrators bring the sensors back to 0 after the drop, and a force the caller holds
 * (TD_AMB_EXTERNAL) replaces the controller's. */
static void test_integrator_law_drop(void **state)
{
    td_pid_block pid = {RIG_KP, 2.5e5, RIG_KD, 0.0};
    td_controller *k = td_controller_create_pid(&pid, NULL);
    td_model *m;
    td_sim *sim;
    double t, fmax_on;
    (void)state;
    assert_non_null(k);
    m = rig_with_law(TD_RIG_TAU, TD_RIG_WITH_RETAINERS, k);
    add_drop(m);
    sim = make_sim(m, 1);
    fmax_on = amb_force_max(sim);
    assert_true(fmax_on > 100.0); /* carrying the weight at the start */
    run_to(sim, 0.02);
    for (t = 0.025; t < 0.07; t += 0.01) {
        run_to(sim, t);
        assert_true(amb_force_max(sim) == 0.0);
    }
    run_to(sim, 1.0);
    {
        int n = td_sim_dof_count(sim), i;
        double *q = calloc(2 * (size_t)n, sizeof *q), worst = 0.0;
        const double *y = N_VGetArrayPointer(sim->dae.y);
        assert_non_null(q);
        assert_int_equal(td_sim_get_state(sim, q, q + n), TD_OK);
        for (i = 0; i < sim->dae.neq; i++)
            assert_true(isfinite(y[i]));
        for (i = 0; i < 4; i++)
            worst = fmax(worst, fabs(q[TD_DOF(i < 2 ? 3 : 9, i % 2 ? TD_DOF_Y : TD_DOF_X)]));
        /* PD alone would sag by W/2 / (ki kp - ks), about 0.5 mm */
        print_message("PID controller, 1 s after a 50 ms drop: largest sensor displacement %.3g m\n", worst);
        assert_true(worst < 1e-5);
        /* the caller's held force wins over the controller: ks x + f at AMB 0's actuator (node 3) */
        assert_int_equal(td_sim_set_amb_mode(sim, 0, TD_AMB_EXTERNAL, NULL), TD_OK);
        assert_int_equal(td_sim_set_amb_control(sim, 0, 10.0, -20.0, NULL), TD_OK);
        run_to(sim, 1.01);
        assert_int_equal(td_sim_get_state(sim, q, q + n), TD_OK);
        {
            double f[2];
            td_amb a;
            assert_int_equal(td_model_get_amb(td_sim_model(sim), 0, &a), TD_OK);
            assert_int_equal(td_sim_amb_force(sim, 0, f), TD_OK);
            assert_close(f[0], a.ks * q[TD_DOF(3, TD_DOF_X)] + 10.0, 1e-12, 0.0);
            assert_close(f[1], a.ks * q[TD_DOF(3, TD_DOF_Y)] - 20.0, 1e-12, 0.0);
        }
        free(q);
    }
    td_sim_free(&sim);
    td_controller_free(&k);
    td_model_free(&m);
}

/* The closed-form flight carries a controller's states: the same run with it and without it at a
 * thousandth of the tolerances (an unbalanced rotor in free flight, no contact), under a PID with a
 * slow integrator (a state) and the exact derivative (velocity feedthrough). */
static void test_flight_with_controller_states(void **state)
{
    td_pid_block pid = {RIG_KP, 2.0e3, RIG_KD, 0.0};
    td_controller *k = td_controller_create_pid(&pid, NULL);
    td_model *m = rig_with_law(TD_RIG_TAU, TD_RIG_WITH_RETAINERS, k);
    td_unbalance u = {6, 2.0e-4, 0.3};
    td_sim *with, *without;
    td_sim_stats a, b;
    double dq;
    (void)state;
    assert_int_equal(td_controller_order(k), 1);
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    with = make_sim(m, 1);
    without = make_sim_tol(m, 0, 1000.0);
    run_to(with, 0.2);
    run_to(without, 0.2);
    assert_int_equal(td_sim_stats_get(with, &a), TD_OK);
    assert_int_equal(td_sim_stats_get(without, &b), TD_OK);
    dq = state_distance(with, without);
    print_message("PID: flight steps %ld (integrator steps %ld / %ld), |dq| %.3g m at 0.2 s\n", a.flight_steps, a.steps,
                  b.steps, dq);
    assert_true(a.flight_steps > 0);
    assert_int_equal(b.flight_steps, 0);
    assert_true(dq <= 1e-10);
    td_sim_free(&with);
    td_sim_free(&without);
    td_controller_free(&k);
    td_model_free(&m);
}

/* ---- scipy ----------------------------------------------------------------------------------- */

/* The plant of m (matrices at the rig's speed, AMB axes) and the law's line into `path`, as
 * closed_loop.py reads them. */
static void dump_plant(const td_model *m, const char *law, const char *path)
{
    td_system *sys = NULL;
    const td_matrix_kind kinds[4] = {TD_MATRIX_MASS, TD_MATRIX_STIFFNESS, TD_MATRIX_DAMPING, TD_MATRIX_GYROSCOPIC};
    FILE *f = fopen(path, "w");
    double *A;
    int n, i, j, a;
    assert_non_null(f);
    assert_int_equal(td_system_create(m, &sys, NULL), TD_OK);
    n = td_system_dof_count(sys);
    A = malloc((size_t)n * (size_t)n * sizeof *A);
    assert_non_null(A);
    fprintf(f, "%d %d %.17g\n", n, 2 * td_model_amb_count(m), RIG_SPEED);
    for (a = 0; a < td_model_amb_count(m); a++) {
        td_amb amb;
        assert_int_equal(td_model_get_amb(m, a, &amb), TD_OK);
        for (j = 0; j < 2; j++) {
            int off = j == 0 ? TD_DOF_X : TD_DOF_Y;
            fprintf(f, "%d %d %.17g %.17g %.17g\n", td_system_node_dof(sys, amb.node, off),
                    td_system_node_dof(sys, amb.sensor_node, off), amb.ks, amb.ki, amb.tau);
        }
    }
    fprintf(f, "%s\n", law);
    for (a = 0; a < 4; a++) {
        assert_int_equal(td_system_dense(sys, kinds[a], A, NULL), TD_OK);
        for (i = 0; i < n; i++) {
            for (j = 0; j < n; j++)
                fprintf(f, "%.17g ", A[i + (size_t)j * n]);
            fprintf(f, "\n");
        }
    }
    assert_int_equal(fclose(f), 0);
    free(A);
    td_system_free(&sys);
}

/* closed_loop.py's eigenvalues of the plant in `path` into ev; returns their count. */
static int scipy_eigenvalues(const char *path, double complex *ev, int cap)
{
    char cmd[2048], line[256];
    FILE *p;
    int n = 0;
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 '%s' '%s'", td_source_path("tests/validation/control/closed_loop.py"),
             path);
    p = popen(cmd, "r");
    assert_non_null(p);
    while (fgets(line, sizeof line, p)) {
        double re, im;
        assert_int_equal(sscanf(line, "%lf %lf", &re, &im), 2);
        assert_true(n < cap);
        ev[n++] = re + I * im;
    }
    /* a missing numpy or scipy fails here (the script exits non-zero), it never skips */
    assert_int_equal(pclose(p), 0);
    return n;
}

/* (b) the rig with a lead-lag + notch on every axis: touchdown's closed-loop eigenvalues against
 * numpy's of the loop closed in scipy from the plant's matrices */
static void test_leadlag_notch_eigenvalues_against_scipy(void **state)
{
    const double taus[2] = {TD_RIG_TAU, 0.0};
    double complex ours[200], ref[200];
    int t;
    (void)state;
    for (t = 0; t < 2; t++) {
        td_controller *k = leadlag_notch();
        td_model *m = rig_with_law(taus[t], TD_RIG_NO_RETAINERS, k);
        const char *path = "sim_controller_plant.txt";
        int n, nref, i;
        double worst, re_max = -INFINITY;
        char law[256];
        snprintf(law, sizeof law, "leadlag_notch %.17g %.17g %.17g %.17g %.17g %.17g", LAW[0], LAW[1], LAW[2], LAW[3],
                 LAW[4], LAW[5]);
        dump_plant(m, law, path);
        n = closed_loop_eigenvalues(m, ours, 200, 0);
        nref = scipy_eigenvalues(path, ref, 200);
        assert_int_equal(n, nref);
        worst = match_eigenvalues(ref, ours, n, 1e-8);
        for (i = 0; i < n; i++)
            re_max = fmax(re_max, creal(ours[i]));
        print_message("lead-lag + notch, tau %.3g s: %d eigenvalues (controller order %d per axis), largest relative "
                      "difference to scipy %.3g, largest real part %.6g 1/s\n",
                      taus[t], n, td_controller_order(k), worst, re_max);
        remove(path);
        td_controller_free(&k);
        td_model_free(&m);
    }
}

/* ---- the Jacobian -------------------------------------------------------------------------- */

/* A state with every unknown nonzero and the retainer nodes inside their clearance. */
static void fill_state(const td_sim *s, double *y, double *yp)
{
    int i;
    for (i = 0; i < s->dae.neq; i++) {
        double u = sin(1.7 * i + 0.3), w = cos(2.3 * i + 0.1);
        double sy = i < s->dae.ov ? 1e-4 : i < s->dae.ow ? 1e-2 : i < s->dae.ol ? 300.0 : 0.0;
        double syp = i < s->dae.ov ? 1e-2 : i < s->dae.ow ? 10.0 : i < s->dae.ol ? 1e4 : 0.0;
        y[i] = u * sy;
        yp[i] = w * syp;
    }
}

/* td_sim_jacobian against central differences (steps 1e-3 of each unknown) at fill_state's state. */
static void check_jacobian(td_sim *s, const char *what)
{
    int n = s->dae.neq;
    double *y = calloc((size_t)n, sizeof(double)), *yp = calloc((size_t)n, sizeof(double));
    assert_true(y && yp);
    fill_state(s, y, yp);
    td_test_check_jacobian(s, y, yp, 1e-3, what);
    free(y), free(yp);
}

/* A two-input, two-output law over the x axes of both AMBs: PD + notch and lead-lag + notch side
 * by side, mixed by a full input and output transform (every input reaches every output). */
static td_controller *mimo_law(void)
{
    const double Tin[4] = {1.0, -0.2, 0.3, 1.0}, Tout[4] = {0.9, 0.1, -0.25, 1.1};
    td_notch_block nb = {LAW[3], LAW[4], LAW[5]};
    td_controller *pd = pd_as_tf(), *notch = td_controller_create_notch(&nb, NULL), *ln = leadlag_notch();
    td_controller *pdn = td_controller_series(pd, notch, NULL),
                  *both = pdn ? td_controller_append(pdn, ln, NULL) : NULL;
    td_controller *k = both ? td_controller_transform(both, 2, Tin, 2, Tout, NULL) : NULL;
    assert_non_null(k);
    assert_int_equal(td_controller_has_velocity_feedthrough(k), 1);
    td_controller_free(&pd), td_controller_free(&notch), td_controller_free(&ln), td_controller_free(&pdn),
        td_controller_free(&both);
    return k;
}

static void test_jacobian_with_controllers(void **state)
{
    const double taus[2] = {TD_RIG_TAU, 0.0};
    const int x_axes[2] = {0, 2};
    int t, y_axis;
    (void)state;
    for (t = 0; t < 2; t++) {
        td_model *m = rig_without_gains(taus[t], TD_RIG_WITH_RETAINERS);
        td_controller *k = mimo_law(), *ln = leadlag_notch();
        td_sim *s;
        assert_int_equal(td_model_add_controller(m, "x", k, x_axes, x_axes, NULL), TD_OK);
        for (y_axis = 1; y_axis < 4; y_axis += 2)
            assert_int_equal(td_model_add_controller(m, NULL, ln, &y_axis, &y_axis, NULL), TD_OK);
        s = make_sim(m, 1);
        assert_int_equal(s->dae.nw, (taus[t] > 0.0 ? 4 : 0) + td_controller_order(k) + 2 * td_controller_order(ln));
        check_jacobian(s, taus[t] > 0.0 ? "controllers, lagged AMBs" : "controllers, lag-free AMBs");
        s->machine.amb_mode[0] = TD_AMB_EXTERNAL;
        s->machine.amb_control[0] = 123.0;
        s->machine.amb_control[1] = -45.0;
        s->machine.amb_mode[1] = TD_AMB_OFF;
        check_jacobian(s, "controllers, external/off AMBs");
        td_sim_free(&s);
        td_controller_free(&k);
        td_controller_free(&ln);
        td_model_free(&m);
    }
}

/* ---- the model ----------------------------------------------------------------------------- */

/* A controller's copies survive the caller's, clone and refine keep them; the checks name the
 * part and the key at fault. */
static void test_model_controllers(void **state)
{
    td_controller *k = pd_as_tf();
    td_model *m = rig_without_gains(TD_RIG_TAU, TD_RIG_NO_RETAINERS), *c = NULL, *r = NULL, *bad;
    const int axes[2] = {0, 1}, three = 3, far = 4, neg = -1;
    const char *name;
    const int *in, *out;
    td_error err;
    (void)state;
    assert_int_equal(td_model_add_controller(m, "a", k, &axes[0], &axes[1], &err), TD_OK);
    td_controller_free(&k);
    assert_int_equal(td_model_controller_count(m), 1);
    assert_non_null(td_model_get_controller(m, 0, &name, &in, &out));
    assert_string_equal(name, "a");
    assert_true(in[0] == 0 && out[0] == 1);
    assert_null(td_model_get_controller(m, 1, NULL, NULL, NULL));
    assert_int_equal(td_model_clone(m, &c, NULL), TD_OK);
    assert_int_equal(td_model_refine(m, 2, &r, NULL), TD_OK);
    assert_int_equal(td_model_controller_count(c), 1);
    assert_int_equal(td_model_controller_count(r), 1);
    assert_int_equal(td_controller_order(td_model_get_controller(r, 0, NULL, NULL, NULL)), 0);
    assert_int_equal(td_model_validate(r, &err), TD_OK);
    k = pd_as_tf();
    /* a second controller on axis 1 */
    assert_int_equal(td_model_add_controller(c, "b", k, &three, &axes[1], &err), TD_OK);
    assert_int_equal(td_model_validate(c, &err), TD_ERR_INVALID);
    print_message("%s\n", err.message);
    assert_string_equal(err.site.part, "controller");
    assert_int_equal(err.site.index, 1);
    assert_string_equal(err.site.field, "outputs");
    /* an axis out of range, a negative one, a repeated name */
    assert_int_equal(td_model_add_controller(r, "c", k, &far, &three, &err), TD_OK);
    assert_int_equal(td_model_validate(r, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "inputs");
    assert_int_equal(td_model_add_controller(r, "d", k, &neg, &three, &err), TD_ERR_INVALID);
    assert_int_equal(td_model_add_controller(r, "a", k, &three, &three, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "name");
    /* a driven AMB that keeps a shorthand gain: the error names the AMB and the key */
    bad = td_test_rig_create(RIG_SPEED, TD_RIG_TAU, TD_RIG_NO_RETAINERS);
    assert_int_equal(td_model_add_controller(bad, "e", k, &three, &three, &err), TD_OK);
    assert_int_equal(td_model_validate(bad, &err), TD_ERR_INVALID);
    print_message("%s\n", err.message);
    assert_string_equal(err.site.part, "amb");
    assert_int_equal(err.site.index, 1);
    assert_string_equal(err.site.field, "kp");
    assert_string_equal(err.other.part, "controller");
    td_model_free(&bad);
    td_controller_free(&k);
    td_model_free(&m);
    td_model_free(&c);
    td_model_free(&r);
}

/* The start of a run under a sampled controller: its stability checked on the sampled loop, the
 * orbit (computed for continuous laws) refused when asked for strictly, rest on "auto". */
static void check_sampled_start(const td_model *m)
{
    td_sim *sim = NULL;
    td_sim_options o;
    td_sim_start_info info;
    td_error err;
    td_sim_options_default(&o);
    o.start = TD_START_ORBIT;
    assert_int_equal(td_sim_create(m, &o, &sim, &err), TD_ERR_INVALID);
    print_message("%s\n", err.message);
    o.start = TD_START_AUTO;
    assert_int_equal(td_sim_create(m, &o, &sim, &err), TD_OK);
    assert_int_equal(td_sim_start_info_get(sim, &info), TD_OK);
    assert_int_equal(info.used, TD_START_REST);
    assert_true(info.stability != TD_STABILITY_UNCHECKED && isfinite(info.max_real_part));
    td_sim_free(&sim);
}

/* A sampled controller (a PID with a filtered derivative, Tustin at 10 kHz) on every axis: the
 * eigenvalues of the loop over one sample, exact at the samples, against scipy's (its own Tustin
 * map, zero-order hold and loop), as s = ln(mu) rate; the start's stability check uses them, and the
 * orbit start, computed for continuous laws, is refused when asked for strictly and falls back to
 * rest on "auto". */
static void test_sampled_law_eigenvalues_against_scipy(void **state)
{
    const double taus[2] = {TD_RIG_TAU, 0.0}, rate = 10000.0;
    td_pid_block pid = {RIG_KP, 0.0, RIG_KD, 2000.0};
    double complex ours[200], ref[200];
    int t;
    (void)state;
    for (t = 0; t < 2; t++) {
        td_controller *c = td_controller_create_pid(&pid, NULL);
        td_controller *k = c ? td_controller_discretise(c, rate, TD_DISCRETISE_TUSTIN, 0.0, NULL) : NULL;
        td_model *m;
        const char *path = "sim_controller_sampled.txt";
        char law[256];
        int n, nref, i;
        double worst, re_max = -INFINITY;
        assert_non_null(k);
        m = rig_with_law(taus[t], TD_RIG_NO_RETAINERS, k);
        snprintf(law, sizeof law, "pid_tustin %.17g %.17g %.17g %.17g", pid.kp, pid.kd, pid.derivative_filter, rate);
        dump_plant(m, law, path);
        n = closed_loop_eigenvalues(m, ours, 200, 4 * td_controller_order(k));
        nref = scipy_eigenvalues(path, ref, 200);
        assert_int_equal(n, nref);
        worst = match_eigenvalues(ref, ours, n, 1e-8);
        remove(path);
        if (t == 0)
            check_sampled_start(m);
        for (i = 0; i < n; i++)
            re_max = fmax(re_max, creal(ours[i]));
        print_message("sampled PID, tau %.3g s: %d eigenvalues, largest relative difference to scipy %.3g, largest "
                      "real part %.6g 1/s\n",
                      taus[t], n, worst, re_max);
        td_controller_free(&c);
        td_controller_free(&k);
        td_model_free(&m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_model_controllers),
        cmocka_unit_test(test_pd_eigenvalues_equal_shorthand),
        cmocka_unit_test(test_leadlag_notch_eigenvalues_against_scipy),
        cmocka_unit_test(test_jacobian_with_controllers),
        cmocka_unit_test(test_pd_run_equals_shorthand),
        cmocka_unit_test(test_flight_with_controller_states),
        cmocka_unit_test(test_integrator_law_drop),
        cmocka_unit_test(test_sampled_law_eigenvalues_against_scipy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
