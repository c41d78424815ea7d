/*
 * Plug-in controllers (touchdown/plugin.h; lib/model/plugin.c, lib/sim/sampler_plugin.c). The
 * independent reference is the built-in sampled law: the PD plug-in (tests/plugins/pd.c, its
 * difference equation i = -(b0 xs_k + b1 xs_{k-1})) and the transfer function b0 + b1 z^-1 in z^-1
 * (td_controller_create_tf, run by the sampler's state-space update) on case A's four AMB axes,
 * over a run with contacts: the same state to the last bit at every output, the same statistics.
 */
#include "td_rig.h"
#include "td_test.h"

#include "sim/sim_internal.h"
#include "touchdown/touchdown.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RATE 1.0e4 /* Hz */
#define KP 1.0e4   /* A/m, case A's AMBs */
#define KD 40.0    /* A s/m */
#define AXES 4     /* AMB 0 x, y, AMB 1 x, y */
#define T_END 0.13 /* s: case A touches its retainers from 0.105 s on (the unbalance steps up at 0.1 s) */
#define DT 2.5e-4  /* s between the outputs compared */

/* td_plugin_controller_entry (touchdown/plugin.h) is the PD plug-in's (tests/plugins/pd.c, linked
 * into this test: a program's own table); the test plug-ins' libraries are in PLUGINS. */
#define PLUGINS TD_BINARY_DIR "/tests/plugins/"

/* Case A from rest, cut to T_END, its AMBs' shorthand PD set to 0 (a controller drives them). */
static td_model *case_a(td_case **c)
{
    const char *ov[6] = {"end_time=0.13",  "start=\"rest\"", "ambs[0].kp=0.0",
                         "ambs[0].kd=0.0", "ambs[1].kp=0.0", "ambs[1].kd=0.0"};
    td_model *m = NULL;
    td_error err;
    *c = td_test_load_case("cases/paper-a.cfg", ov, 6);
    assert_int_equal(td_model_clone(td_case_model(*c), &m, &err), TD_OK);
    return m;
}

/* The built-in PD of the plug-in: b0 + b1 z^-1 at RATE (b0, b1 computed as pd.c computes them),
 * `delay` samples later, one SISO law per axis. */
static void add_builtin_pd(td_model *m, int delay)
{
    const double num[2] = {KP + KD * RATE, -KD * RATE}, den[1] = {1.0};
    td_error err;
    td_controller *k = td_controller_create_tf(num, 2, den, 1, RATE, &err), *kd;
    int axis;
    assert_non_null(k);
    kd = td_controller_delay(k, delay, &err);
    assert_non_null(kd);
    for (axis = 0; axis < AXES; axis++) {
        char name[16];
        snprintf(name, sizeof name, "axis%d", axis);
        if (td_model_add_controller(m, name, kd, &axis, &axis, &err) != TD_OK)
            fail_msg("td_model_add_controller: %s", err.message);
    }
    td_controller_free(&k);
    td_controller_free(&kd);
}

/* A spec for one axis of the PD plug-in: the program's table, or `library` when not NULL. */
static td_plugin_spec pd_spec(const char *name, const int *axis, const char *library, int delay)
{
    static const char *const names[2] = {"kp", "kd"};
    static const double values[2] = {KP, KD};
    td_plugin_spec p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.functions = library ? NULL : td_plugin_controller_entry();
    p.library = library;
    p.sample_rate = RATE;
    p.delay = delay;
    p.n_inputs = p.n_outputs = 1;
    p.inputs = p.outputs = axis;
    p.n_parameters = 2;
    p.parameter_names = names;
    p.parameter_values = values;
    return p;
}

/* The PD plug-in's table on the axes from `first` on, one controller per axis. */
static void add_pd_axes(td_model *m, int first)
{
    int axis;
    for (axis = first; axis < AXES; axis++) {
        char name[16];
        td_plugin_spec p;
        td_error err;
        snprintf(name, sizeof name, "axis%d", axis);
        p = pd_spec(name, &axis, NULL, 0);
        if (td_model_add_plugin_controller(m, &p, &err) != TD_OK)
            fail_msg("td_model_add_plugin_controller: %s", err.message);
    }
}

/* The PD plug-in on each axis, one controller per axis as add_builtin_pd adds them. */
static void add_plugin_pd(td_model *m, const char *library, int delay)
{
    int axis;
    for (axis = 0; axis < AXES; axis++) {
        char name[16];
        td_plugin_spec p;
        td_error err;
        snprintf(name, sizeof name, "axis%d", axis);
        p = pd_spec(name, &axis, library, delay);
        if (td_model_add_plugin_controller(m, &p, &err) != TD_OK)
            fail_msg("td_model_add_plugin_controller: %s", err.message);
    }
}

/* Largest |a - b| over the rotor's displacements (m; rad for the rotations) of two simulations of
 * one machine. */
static double state_difference(const td_sim *a, const td_sim *b)
{
    const double *ya = N_VGetArrayPointer(a->dae.y) + a->dae.oq, *yb = N_VGetArrayPointer(b->dae.y) + b->dae.oq;
    double d = 0.0;
    int i;
    for (i = 0; i < a->sys->ndof; i++)
        d = fmax(d, fabs(ya[i] - yb[i]));
    return d;
}

/* Whether s has touched a retainer yet. */
static int touched(const td_sim *s)
{
    td_sim_stats st;
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    return !isnan(st.first_contact_time);
}

/* Runs a and b side by side to T_END; the largest displacement difference at the outputs, over
 * the whole run, and in *free over the outputs before either touched a retainer (may be NULL).
 * `exact` also asks for the whole state and the held currents to be the same bits at every output. */
static double run_side_by_side(td_sim *a, td_sim *b, int exact, double *free)
{
    double t = 0.0, worst = 0.0, d;
    assert_int_equal(a->dae.neq, b->dae.neq);
    if (free)
        *free = 0.0;
    while (t < T_END) {
        t = td_test_next_output(t, DT, T_END);
        td_test_step_to(a, t);
        td_test_step_to(b, t);
        d = state_difference(a, b);
        worst = fmax(worst, d);
        if (free && !touched(a) && !touched(b))
            *free = fmax(*free, d);
        if (exact && (memcmp(N_VGetArrayPointer(a->dae.y), N_VGetArrayPointer(b->dae.y),
                             (size_t)a->dae.neq * sizeof(double)) != 0 ||
                      memcmp(a->machine.held_current, b->machine.held_current, AXES * sizeof(double)) != 0))
            fail_msg("t = %.17g: the plug-in's run differs from the built-in one (largest displacement difference "
                     "%.3g m)",
                     t, d);
    }
    return worst;
}

/* The statistics of two runs that must be the same run. */
static void assert_same_stats(const td_sim *a, const td_sim *b)
{
    td_sim_stats sa, sb;
    assert_int_equal(td_sim_stats_get(a, &sa), TD_OK);
    assert_int_equal(td_sim_stats_get(b, &sb), TD_OK);
    assert_true(sa.contact_onsets > 0); /* a run with contacts */
    printf("contact onsets %ld, first contact at %.6g s, samples %ld, steps %ld\n", sa.contact_onsets,
           sa.first_contact_time, sa.controller_samples, sa.steps);
    assert_int_equal(sa.contact_onsets, sb.contact_onsets);
    assert_int_equal(sa.controller_samples, sb.controller_samples);
    assert_int_equal(sa.steps, sb.steps);
    assert_true(sa.first_contact_time == sb.first_contact_time);
}

/* Models a and b of case c run side by side are the same run: the whole state and the held currents
 * the same bits at every output, and the same statistics. Frees the models and the case. */
static void assert_same_run(td_model **a, td_model **b, td_case **c)
{
    td_sim *sa = td_test_new_sim(*a, *c), *sb = td_test_new_sim(*b, *c);
    assert_true(run_side_by_side(sa, sb, 1, NULL) == 0.0);
    assert_same_stats(sa, sb);
    td_sim_free(&sa);
    td_sim_free(&sb);
    td_model_free(a);
    td_model_free(b);
    td_case_free(c);
}

/* The PD plug-in registered as a program's table equals the built-in sampled PD bit for bit. */
static void test_registered_pd_is_builtin_pd(void **state)
{
    td_case *c = NULL;
    td_model *mb = case_a(&c), *mp = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_model_clone(mb, &mp, &err), TD_OK);
    add_builtin_pd(mb, 0);
    add_plugin_pd(mp, NULL, 0);
    assert_null(td_model_get_plugin(mb, 0));
    assert_non_null(td_model_get_plugin(mp, 3));
    assert_null(td_model_get_controller(mp, 3, NULL, NULL, NULL));
    assert_same_run(&mb, &mp, &c);
}

/* The PD plug-in loaded from its shared library (tests/plugins/pd.c built as pd.so) is the same run
 * as the one registered as a table: the library's table is the same code. */
static void test_library_pd_is_registered_pd(void **state)
{
    td_case *c = NULL;
    td_model *mt = case_a(&c), *ml = NULL, *mc = NULL;
    const td_plugin_spec *p;
    td_error err;
    (void)state;
    assert_int_equal(td_model_clone(mt, &ml, &err), TD_OK);
    add_plugin_pd(mt, NULL, 0);
    add_plugin_pd(ml, PLUGINS "pd.so", 0);
    p = td_model_get_plugin(ml, 1);
    assert_non_null(p);
    assert_non_null(p->functions); /* the library's table */
    assert_true(p->functions != td_plugin_controller_entry());
    assert_string_equal(p->library, PLUGINS "pd.so");
    assert_string_equal(p->name, "axis1");
    assert_int_equal(p->n_parameters, 2);
    assert_string_equal(p->parameter_names[1], "kd");
    assert_true(p->parameter_values[1] == KD);
    assert_int_equal(p->inputs[0], 1);
    /* a clone opens the library again; the copy runs as the original */
    assert_int_equal(td_model_clone(ml, &mc, &err), TD_OK);
    assert_true(td_model_get_plugin(mc, 1)->functions == p->functions);
    td_model_free(&ml);
    assert_same_run(&mt, &mc, &c);
}

/* Adding a plug-in controller fails with `expected` in the message, naming controller 0 and the
 * field at fault; the model is left without it. */
static void expect_add_fails(const td_plugin_spec *p, const char *field, const char *expected)
{
    td_model *m = td_test_rig_create(0.0, 0.0, 0);
    td_error err;
    assert_int_equal(td_model_add_plugin_controller(m, p, &err), TD_ERR_INVALID);
    if (!strstr(err.message, expected))
        fail_msg("\"%s\" does not say \"%s\"", err.message, expected);
    assert_string_equal(err.site.part, "controller");
    assert_int_equal(err.site.index, 0);
    assert_string_equal(err.site.field, field);
    assert_int_equal(td_model_controller_count(m), 0);
    td_model_free(&m);
}

/* A library that cannot be loaded, has no entry or another ABI, and the spec's own faults: each a
 * one-line error naming the controller and the field; a plug-in that crashes in its init loads (its
 * init is not called until a simulation is created). */
static void test_bad_libraries_and_specs(void **state)
{
    const int axis = 0;
    td_plugin_spec p = pd_spec("bad", &axis, PLUGINS "no_entry.so", 0);
    td_model *m = td_test_rig_create(0.0, 0.0, 0);
    td_error err;
    (void)state;
    expect_add_fails(&p, "library", "does not export td_plugin_controller_entry");
    p.library = PLUGINS "wrong_abi.so";
    expect_add_fails(&p, "library", "built for plug-in ABI version 2; this touchdown runs version 1");
    p.library = PLUGINS "missing.so";
    expect_add_fails(&p, "library", "cannot load \"" PLUGINS "missing.so\"");
    p.library = "libm.so.6"; /* the system has it, but a plug-in's library is a file, never searched for */
    expect_add_fails(&p, "library", "cannot load \"libm.so.6\": ./libm.so.6: cannot open shared object file");
    p.library = PLUGINS "pd.so";
    p.functions = td_plugin_controller_entry();
    expect_add_fails(&p, "functions", "differs from the table of");
    p = pd_spec("bad", &axis, NULL, 0);
    p.sample_rate = 0.0;
    expect_add_fails(&p, "sample_rate", "a plug-in controller is sampled");
    p = pd_spec("bad", &axis, NULL, -1);
    expect_add_fails(&p, "delay", "must be >= 0");
    p = pd_spec("bad", &axis, NULL, 0);
    p.functions = NULL;
    expect_add_fails(&p, "library", "needs a table (functions) or a library");
    p = pd_spec("bad", &axis, PLUGINS "crash.so", 0);
    assert_int_equal(td_model_add_plugin_controller(m, &p, &err), TD_OK);
    td_model_free(&m);
}

/* Case A with the plug-in of `library` on its four axes. */
static td_model *case_a_with(const char *library, td_case **c)
{
    td_model *m = case_a(c);
    add_plugin_pd(m, library, 0);
    return m;
}

/* A plug-in whose init refuses: td_sim_create fails with its reason, naming the controller. */
static void test_init_refusing(void **state)
{
    td_case *c = NULL;
    td_model *m = case_a_with(PLUGINS "refuse.so", &c);
    td_sim *s = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_sim_create(m, td_case_sim_options(c), &s, &err), TD_ERR_INVALID);
    assert_null(s);
    assert_string_equal(err.message,
                        "controller 0: plug-in \"axis0\" init failed: refuse: gain schedule \"axis0\" needs parameter "
                        "\"table\"");
    assert_string_equal(err.site.part, "controller");
    assert_int_equal(err.site.index, 0);
    assert_null(err.site.field);
    td_model_free(&m);
    td_case_free(&c);
}

/* A plug-in that commands NaN from sample 3 on: td_sim_step fails there with the sample and the
 * reason, having integrated nothing past sample 3's instant, and so does every later call. */
static void test_nan_output(void **state)
{
    td_case *c = NULL;
    td_model *m = case_a_with(PLUGINS "nan.so", &c);
    td_sim *s = td_test_new_sim(m, c);
    td_error err;
    double t = -1.0;
    int a;
    (void)state;
    assert_int_equal(td_sim_step(s, 1.0e-3, &t, &err), TD_ERR_INVALID);
    assert_string_equal(err.message,
                        "controller 0: plug-in \"axis0\" failed at sample 3 (t = 0.0003 s): command 0 (AMB 0 x) is "
                        "nan, not a finite current");
    assert_string_equal(err.site.part, "controller"); /* the sampler's own record, site and reason kept */
    assert_int_equal(err.site.index, 0);
    assert_true(strncmp(err.message + err.reason, "plug-in \"axis0\" failed at sample 3", 34) == 0);
    assert_true(t == 3.0 / RATE); /* stopped at the sample */
    for (a = 0; a < AXES; a++)
        assert_true(s->machine.held_current[a] == 0.0); /* the NaN was never held */
    assert_int_equal(td_sim_step(s, 2.0e-3, &t, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "failed at sample 3"));
    assert_true(t == 3.0 / RATE);
    td_sim_free(&s);
    td_model_free(&m);
    td_case_free(&c);
}

/* Two runs of case A, the built-in PD and the plug-in's `table`, each `delay` samples late, side by
 * side: the largest displacement difference at the outputs, into *free before the first contact. */
static double compare_pd(int delay, const td_plugin_controller *table, double *free)
{
    static const char *const names[3] = {"kp", "kd", "force_gain"};
    td_case *c = NULL;
    td_model *mb = case_a(&c), *mp = NULL;
    td_sim *sb, *sp;
    td_error err;
    double d;
    int axis;
    assert_int_equal(td_model_clone(mb, &mp, &err), TD_OK);
    add_builtin_pd(mb, delay);
    for (axis = 0; axis < AXES; axis++) {
        char name[16];
        double values[3] = {KP, KD, 0.0};
        td_plugin_spec p;
        td_amb amb;
        snprintf(name, sizeof name, "axis%d", axis);
        assert_int_equal(td_model_get_amb(mp, axis / 2, &amb), TD_OK);
        values[2] = amb.ki; /* a force table: the PD's current times ki */
        p = pd_spec(name, &axis, NULL, delay);
        p.functions = table;
        p.n_parameters = table->output == TD_PLUGIN_FORCE ? 3 : 2;
        p.parameter_names = names;
        p.parameter_values = values;
        if (td_model_add_plugin_controller(mp, &p, &err) != TD_OK)
            fail_msg("td_model_add_plugin_controller: %s", err.message);
    }
    sb = td_test_new_sim(mb, c);
    sp = td_test_new_sim(mp, c);
    d = run_side_by_side(sb, sp, 0, free);
    td_sim_free(&sb);
    td_sim_free(&sp);
    td_model_free(&mb);
    td_model_free(&mp);
    td_case_free(&c);
    return d;
}

/* A plug-in's delay is the built-in z^-delay. One sample late, the runs agree to rounding while the
 * rotor flies free (the closed-form flight, which no tolerance steers), but not to the bit once it
 * touches: the built-in delayed law's direct gain D is 0, so the simulation scales its integrator
 * tolerances by the law's frequency response, which a plug-in does not have (its scale is its
 * measured direct gain, lib/sim/sampler_plugin.c); the contacts then carry the tolerance-sized
 * difference on. */
static void test_delay(void **state)
{
    double free, d = compare_pd(1, td_plugin_controller_entry(), &free);
    (void)state;
    printf("plug-in PD one sample late against the built-in z^-1 PD: largest displacement difference %.3g m "
           "before the first contact, %.3g m over the run (clearance %.3g m)\n",
           free, d, TD_RIG_CLEARANCE);
    assert_true(free < 1.0e-12 * TD_RIG_CLEARANCE);
    assert_true(d < 1.0e-4 * TD_RIG_CLEARANCE);
}

/* The direct gain the simulation measures of a force table (its tolerance scale, in A per unit
 * error) is the current table's: the force per metre over ki. */
static void check_force_gain(const td_plugin_controller *force)
{
    static const char *const names[3] = {"kp", "kd", "force_gain"};
    const double values[3] = {KP, KD, 200.0}; /* the rig's ki */
    td_case *c = NULL;
    td_model *mc = case_a(&c), *mf = NULL;
    td_sim *sc, *sf;
    td_plugin_spec p;
    td_error err;
    const int axis = 0;
    assert_int_equal(td_model_clone(mc, &mf, &err), TD_OK);
    add_plugin_pd(mc, NULL, 0);
    p = pd_spec("force", &axis, NULL, 0);
    p.functions = force;
    p.n_parameters = 3;
    p.parameter_names = names;
    p.parameter_values = values;
    assert_int_equal(td_model_add_plugin_controller(mf, &p, &err), TD_OK);
    add_pd_axes(mf, 1);
    sc = td_test_new_sim(mc, c);
    sf = td_test_new_sim(mf, c);
    assert_true(td_sim_plugin_gain(sc, 0, 0) == KP + KD * RATE);
    assert_close(td_sim_plugin_gain(sf, 0, 0), KP + KD * RATE, 1e-15, 0.0);
    td_sim_free(&sc);
    td_sim_free(&sf);
    td_model_free(&mc);
    td_model_free(&mf);
    td_case_free(&c);
}

/* A force table on an AMB whose ki is 0 has no current to command: the model refuses it, naming the
 * AMB's ki and the controller. */
static void test_force_needs_ki(void **state)
{
    const td_shaft_element el = {0.5, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    const td_amb amb = {1, 1, 0.0, 0.0, 0.0, 0.0, 0.0, 1700.0, 0, 1.2e-3, 0.0, 0.0}; /* ki = 0 */
    td_plugin_controller force = *td_plugin_controller_entry();
    td_model *m = NULL;
    td_plugin_spec p;
    td_error err;
    const int axis = 0;
    (void)state;
    force.output = TD_PLUGIN_FORCE;
    assert_int_equal(td_model_create(&m, &err), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, &err), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, &err), TD_OK);
    assert_int_equal(td_model_add_amb(m, &amb, &err), TD_OK);
    p = pd_spec("force", &axis, NULL, 0);
    p.functions = &force;
    assert_int_equal(td_model_add_plugin_controller(m, &p, &err), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.part, "amb");
    assert_int_equal(err.site.index, 0);
    assert_string_equal(err.site.field, "ki");
    assert_string_equal(err.other.part, "controller");
    assert_non_null(strstr(err.message, "plug-in controller 0 (\"force\") commands this AMB's force"));
    td_model_free(&m);
}

/* A table whose output is TD_PLUGIN_FORCE: the PD's current times ki, which the simulation divides
 * by ki. (ki i) / ki is i only to rounding (ki = 200 N/A is no power of two), so the runs agree to
 * that rounding, carried by the dynamics, while the rotor flies free, and the contacts carry it on. */
static void test_force_output(void **state)
{
    td_plugin_controller force = *td_plugin_controller_entry();
    double free, d;
    (void)state;
    force.output = TD_PLUGIN_FORCE;
    check_force_gain(&force);
    d = compare_pd(0, &force, &free);
    printf("plug-in PD commanding forces against the built-in PD: largest displacement difference %.3g m before "
           "the first contact, %.3g m over the run (clearance %.3g m)\n",
           free, d, TD_RIG_CLEARANCE);
    assert_true(free > 0.0); /* the rounding is there */
    assert_true(free < 1.0e-9 * TD_RIG_CLEARANCE);
    assert_true(d < 1.0e-4 * TD_RIG_CLEARANCE);
}

/* The analyses that need a linear law refuse a model with a plug-in, naming it; an "auto" start
 * falls back to rest with that reason, an "orbit" start is refused; the start's stability stays
 * unchecked with the analysis' refusal as its reason, whatever the start. */
static void test_analyses_refuse(void **state)
{
    td_case *c = NULL;
    td_model *m = case_a_with(PLUGINS "pd.so", &c);
    td_sim_options o = *td_case_sim_options(c);
    td_system *sys = NULL;
    td_modal *md = NULL;
    td_loop *lp = NULL;
    td_campbell *cb = NULL;
    td_harmonic *hr = NULL;
    td_modal_options mo;
    td_unbalance u = {1, 0.02, 0.0};
    td_sim *s = NULL;
    td_sim_start_info info;
    td_error err;
    double mr;
    int unstable;
    const char *why = "modal: controller 0 (\"axis0\") is a plug-in, the user's own code with no linear law";
    (void)state;
    assert_int_equal(td_system_create(m, &sys, &err), TD_OK);
    assert_int_equal(td_modal_solve(sys, 90.0, &md, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, why));
    assert_int_equal(td_modal_stability(sys, 90.0, &mr, &unstable, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, why));
    assert_int_equal(td_loop_compute(sys, 90.0, NULL, &lp, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, why));
    td_modal_options_default(&mo);
    assert_int_equal(td_campbell_compute(sys, &mo, &cb, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, why));
    assert_int_equal(td_harmonic_compute(sys, 90.0, &u, 1, &hr, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, why));
    o.start = TD_START_AUTO;
    if (td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    assert_int_equal(td_sim_start_info_get(s, &info), TD_OK);
    assert_int_equal(info.used, TD_START_REST);
    assert_int_equal(info.stability, TD_STABILITY_UNCHECKED);
    assert_string_equal(info.reason, "controller 0 (\"axis0\") is a plug-in: no steady orbit computed");
    assert_non_null(strstr(info.unchecked, why)); /* the stability's own reason, also at start = "rest" */
    td_sim_free(&s);
    o.start = TD_START_REST;
    if (td_sim_create(m, &o, &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    assert_int_equal(td_sim_start_info_get(s, &info), TD_OK);
    assert_int_equal(info.stability, TD_STABILITY_UNCHECKED);
    assert_string_equal(info.reason, "");
    assert_non_null(strstr(info.unchecked, why));
    td_sim_free(&s);
    o.start = TD_START_ORBIT;
    assert_int_equal(td_sim_create(m, &o, &s, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "start = \"orbit\": controller 0 (\"axis0\") is a plug-in"));
    td_system_free(&sys);
    td_model_free(&m);
    td_case_free(&c);
}

/* The PD plug-in of docs/api.md ("A plug-in controller"), compiled from the page's text against the
 * header alone, equals the built-in PD bit for bit: the page is enough to write a working plug-in. */
static void test_documented_plugin(void **state)
{
    char *doc = td_test_read_file(td_source_path("docs/api.md")), *code, *end, cmd[2048];
    td_case *c = NULL;
    td_model *mb = case_a(&c), *mp = NULL;
    td_error err;
    FILE *f;
    (void)state;
    code = strstr(doc, "## A plug-in controller");
    assert_non_null(code);
    code = strstr(code, "```c\n");
    assert_non_null(code);
    code += 5;
    end = strstr(code, "```");
    assert_non_null(end);
    f = fopen("doc_pd.c", "w");
    assert_non_null(f);
    assert_int_equal(fwrite(code, 1, (size_t)(end - code), f), (size_t)(end - code));
    assert_int_equal(fclose(f), 0);
    snprintf(cmd, sizeof cmd,
             "%s -std=c99 -Wall -Wextra -pedantic -Werror -O2 -shared -fPIC -I%s -o doc_pd.so doc_pd.c", TD_C_COMPILER,
             td_source_path("include"));
    assert_int_equal(system(cmd), 0);
    assert_int_equal(td_model_clone(mb, &mp, &err), TD_OK);
    add_builtin_pd(mb, 0);
    add_plugin_pd(mp, "./doc_pd.so", 0);
    assert_same_run(&mb, &mp, &c);
    free(doc);
}

/* ---- a non-linear plug-in: a PD with a deadband ------------------------------------------------ */

#define DEADBAND 4.0e-6 /* m: wider than the probe's 2^-20 m, far inside case A's clearance */

/* -(KP + KD RATE) d(xs) + KD RATE d(xs_{k-1}), d the deadband: 0 for |xs| <= DEADBAND. */
static void *dead_init(const td_plugin_setup *s, char *message, int message_size)
{
    (void)s, (void)message, (void)message_size;
    return calloc(1, sizeof(double));
}

static int dead_step(void *instance, long k, double t, const double *sensed, double *command, char *message,
                     int message_size)
{
    double *last = instance, x = sensed[0], d = fabs(x) <= DEADBAND ? 0.0 : x - copysign(DEADBAND, x);
    (void)k, (void)t, (void)message, (void)message_size;
    command[0] = -(KP + KD * RATE) * d + KD * RATE * *last;
    *last = d;
    return 0;
}

static int dead_reset(void *instance, char *message, int message_size)
{
    (void)message, (void)message_size;
    *(double *)instance = 0.0;
    return 0;
}

static const td_plugin_controller deadband = {
    TD_PLUGIN_ABI_VERSION, TD_PLUGIN_CURRENT, dead_init, dead_step, dead_reset, free};

/* A plug-in the probe measures no gain of (its deadband is wider than the probe) still gives the
 * tolerances a scale: the magnet's |ks| (setup.c law_gain), where a gain of 0 was taken as it was
 * (the stiffness scale then lacked the controller's part, and an AMB's filter state would be
 * weighed at atol N); the run goes through its first contacts. */
static void test_deadband_scale(void **state)
{
    td_case *c = NULL;
    td_model *m = case_a(&c);
    td_sim *s;
    td_sim_stats st;
    int axis;
    (void)state;
    for (axis = 0; axis < AXES; axis++) {
        char name[16];
        td_plugin_spec p;
        td_error err;
        snprintf(name, sizeof name, "axis%d", axis);
        p = pd_spec(name, &axis, NULL, 0);
        p.functions = &deadband;
        p.n_parameters = 0;
        if (td_model_add_plugin_controller(m, &p, &err) != TD_OK)
            fail_msg("td_model_add_plugin_controller: %s", err.message);
    }
    s = td_test_new_sim(m, c);
    for (axis = 0; axis < AXES; axis++) {
        const td_amb_axis *a = &s->sys->amb_axes[axis];
        printf("axis %d: measured gain %g A/m, scale %g N/m (|ks| %g N/m)\n", axis,
               td_sim_plugin_gain(s, a->law, a->law_output), s->machine.amb_coef[axis].gain_x, fabs(a->ks));
        assert_true(td_sim_plugin_gain(s, a->law, a->law_output) == 0.0);
        assert_true(fabs(a->ks) > 0.0);
        assert_close(s->machine.amb_coef[axis].gain_x, fabs(a->ks), 1e-15, 0.0);
    }
    td_test_step_to(s, T_END);
    assert_int_equal(td_sim_stats_get(s, &st), TD_OK);
    printf("deadband PD to %g s: %ld steps, first contact at %.6g s\n", T_END, st.steps, st.first_contact_time);
    assert_true(st.contact_onsets > 0);
    td_sim_free(&s);
    td_model_free(&m);
    td_case_free(&c);
}

/* The table's layout, as the ABI, holds whatever enum size a plug-in's compiler picks: a plug-in
 * built with -fshort-enums (1-byte enums) sees every member of td_plugin_controller at the offset
 * and with the size this build does. (An enum member, `output`, was 1 byte there and 4 here.) */
static void test_table_layout(void **state)
{
    static const char *const program =
        "#include <stddef.h>\n#include <stdio.h>\n#include \"touchdown/plugin.h\"\n"
        "#define M(f) offsetof(td_plugin_controller, f), sizeof(((td_plugin_controller *)0)->f)\n"
        "int main(void) { printf(\"%zu %zu %zu %zu %zu %zu %zu %zu %zu %zu %zu %zu %zu\", M(abi_version), "
        "M(output), M(init), M(step), M(reset), M(free), sizeof(td_plugin_controller)); return 0; }\n";
    char cmd[2048], got[256] = "", want[256];
    FILE *f;
    (void)state;
#define M(f) offsetof(td_plugin_controller, f), sizeof(((td_plugin_controller *)0)->f)
    snprintf(want, sizeof want, "%zu %zu %zu %zu %zu %zu %zu %zu %zu %zu %zu %zu %zu", M(abi_version), M(output),
             M(init), M(step), M(reset), M(free), sizeof(td_plugin_controller));
#undef M
    f = fopen("layout.c", "w");
    assert_non_null(f);
    assert_true(fputs(program, f) >= 0);
    assert_int_equal(fclose(f), 0);
    snprintf(cmd, sizeof cmd, "%s -std=c99 -fshort-enums -I%s -o layout layout.c && ./layout > layout.txt",
             TD_C_COMPILER, td_source_path("include"));
    assert_int_equal(system(cmd), 0);
    f = fopen("layout.txt", "r");
    assert_non_null(f);
    assert_non_null(fgets(got, sizeof got, f));
    fclose(f);
    printf("td_plugin_controller (offset size of each member, then its size): %s here, %s with -fshort-enums\n", want,
           got);
    assert_string_equal(got, want);
}

/* ---- a recovery pair (td_recovery) ------------------------------------------------------------ */

#define PAIR_RATE 1000.0 /* Hz */

/* The PD of a pair's law on both axes of AMB 0 at PAIR_RATE: the built-in b0 + b1 z^-1 (appended
 * for the two axes) when `plugin` is 0, else the PD plug-in's table. */
static void add_pair_law(td_model *m, const char *name, double kp, double kd, int plugin)
{
    const int axes[2] = {0, 1};
    const double num[2] = {kp + kd * PAIR_RATE, -kd * PAIR_RATE}, den[1] = {1.0}, values[2] = {kp, kd};
    td_error err;
    td_plugin_spec p;
    td_controller *k, *both;
    if (plugin) {
        p = pd_spec(name, axes, NULL, 0); /* on both axes, at the pair's rate, with this law's gains */
        p.sample_rate = PAIR_RATE;
        p.n_inputs = p.n_outputs = 2;
        p.parameter_values = values;
        if (td_model_add_plugin_controller(m, &p, &err) != TD_OK)
            fail_msg("td_model_add_plugin_controller: %s", err.message);
        return;
    }
    k = td_controller_create_tf(num, 2, den, 1, PAIR_RATE, &err);
    assert_non_null(k);
    both = td_controller_append(k, k, &err);
    assert_non_null(both);
    assert_int_equal(td_model_add_controller(m, name, both, axes, axes, &err), TD_OK);
    td_controller_free(&k);
    td_controller_free(&both);
}

/* tests/data/case/recovery-jeffcott.cfg (its orbit crosses the thresholds whatever the laws do)
 * under a supervisor switching a nominal PD and a stiffer recovery PD, each a plug-in or not. */
static td_model *pair_machine(const td_case *c, int nominal_plugin, int recovery_plugin)
{
    td_model *m = NULL;
    td_recovery rec;
    td_error err;
    assert_int_equal(td_model_clone(td_case_model(c), &m, &err), TD_OK);
    add_pair_law(m, "nominal", 1000.0, 0.5, nominal_plugin);
    add_pair_law(m, "recovery", 2000.0, 1.0, recovery_plugin);
    memset(&rec, 0, sizeof rec);
    rec.enabled = 1;
    rec.pair_count = 1;
    rec.nominal[0] = 0;
    rec.controller[0] = 1;
    rec.detect.radius_fraction = 0.5, rec.detect.dwell = 0.01;
    rec.release.radius_fraction = 0.3, rec.release.dwell = 0.02;
    rec.blend = 0.0; /* a step: the incoming law's first output counts (a blend weighs it 0) */
    if (td_model_set_recovery(m, &rec, &err) != TD_OK)
        fail_msg("td_model_set_recovery: %s", err.message);
    return m;
}

/* Step s to each sample instant to t_end, the held currents of AMB 0 after each into held (n x 2). */
static void pair_run(td_sim *s, double t_end, double *held, long n)
{
    long j;
    for (j = 0; j < n && (double)(j + 1) / PAIR_RATE <= t_end; j++) {
        td_test_step_to(s, (double)(j + 1) / PAIR_RATE);
        held[2 * j] = s->machine.held_current[0];
        held[2 * j + 1] = s->machine.held_current[1];
    }
}

/* A plug-in in a recovery pair: the supervisor switches to it and back, resetting it (the
 * incoming law starts from rest: the nominal PD plug-in comes back with xs(k - 1) = 0, not with the
 * sensor it last read); as the recovery law, and as both laws, the run is bit for bit the
 * built-in pair's, switches and returns included. */
static void test_recovery_pair(void **state)
{
    enum { N = 500 };
    static double held[3][2 * N];
    td_case *c = td_test_load_case("tests/data/case/recovery-jeffcott.cfg", NULL, 0);
    td_sim_stats st[3];
    int v;
    (void)state;
    for (v = 0; v < 3; v++) {
        td_model *m = pair_machine(c, v == 2, v >= 1);
        td_sim *s = td_test_new_sim(m, c);
        pair_run(s, td_case_end_time(c), held[v], N);
        assert_int_equal(td_sim_stats_get(s, &st[v]), TD_OK);
        td_sim_free(&s);
        td_model_free(&m);
    }
    assert_true(st[0].controller_switches >= 2); /* there and back */
    for (v = 1; v < 3; v++) {
        assert_int_equal(st[v].controller_switches, st[0].controller_switches);
        assert_int_equal(st[v].controller_samples, st[0].controller_samples);
        assert_true(st[v].last_return_time == st[0].last_return_time);
        assert_memory_equal(held[v], held[0], sizeof held[0]);
    }
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_registered_pd_is_builtin_pd),
        cmocka_unit_test(test_library_pd_is_registered_pd),
        cmocka_unit_test(test_bad_libraries_and_specs),
        cmocka_unit_test(test_init_refusing),
        cmocka_unit_test(test_nan_output),
        cmocka_unit_test(test_delay),
        cmocka_unit_test(test_force_output),
        cmocka_unit_test(test_force_needs_ki),
        cmocka_unit_test(test_analyses_refuse),
        cmocka_unit_test(test_documented_plugin),
        cmocka_unit_test(test_table_layout),
        cmocka_unit_test(test_deadband_scale),
        cmocka_unit_test(test_recovery_pair),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
