/*
 * The creation of a simulation and its release: options checked, the system assembled, the
 * retainers, races and spin laid out, the work space, the machine at the start, the scales, the
 * Jacobian pattern, the integrator, the tolerances and the start state, in that order.
 */
#include "model/gap.h"
#include "sim/section.h"
#include "sim/sim_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static td_status check_options(const td_sim_options *o, td_error *err)
{
    const td_solver_options *so = &o->solver;
    const td_contact_options *co = &o->contact;
    if (!(so->rtol > 0.0 && so->rtol < 1.0) || !(so->atol > 0.0) || !isfinite(so->atol))
        return td_error_set(err, TD_ERR_INVALID, "solver tolerances must be positive (rtol < 1)");
    if (!(so->max_step >= 0.0) || !(so->initial_step >= 0.0) || !isfinite(so->max_step) || !isfinite(so->initial_step))
        return td_error_set(err, TD_ERR_INVALID, "solver max_step and initial_step must be >= 0");
    if (so->max_order < 1 || so->max_order > 5)
        return td_error_set(err, TD_ERR_INVALID, "solver max_order must be 1..5, got %d", so->max_order);
    if (so->linear_solver != TD_LINSOL_KLU && so->linear_solver != TD_LINSOL_DENSE)
        return td_error_set(err, TD_ERR_INVALID, "unknown linear solver %d", (int)so->linear_solver);
    if (co->model != TD_CONTACT_CONSTRAINT && co->model != TD_CONTACT_PENALTY)
        return td_error_set(err, TD_ERR_INVALID, "unknown contact model %d", (int)co->model);
    if (co->model == TD_CONTACT_PENALTY) {
        if (!(co->stiffness > 0.0) || !isfinite(co->stiffness))
            return td_error_set(err, TD_ERR_INVALID, "penalty stiffness must be positive");
        if (!(co->exponent >= 1.0) || !isfinite(co->exponent))
            return td_error_set(err, TD_ERR_INVALID, "penalty exponent must be >= 1");
        if (co->damping != TD_DAMPING_NONE && co->damping != TD_DAMPING_HUNT_CROSSLEY &&
            co->damping != TD_DAMPING_KELVIN_VOIGT)
            return td_error_set(err, TD_ERR_INVALID, "unknown contact damping law %d", (int)co->damping);
        if (!(co->damping_coefficient >= 0.0) || !isfinite(co->damping_coefficient))
            return td_error_set(err, TD_ERR_INVALID, "contact damping coefficient must be >= 0");
    }
    if (o->start != TD_START_ORBIT && o->start != TD_START_REST && o->start != TD_START_AUTO)
        return td_error_set(err, TD_ERR_INVALID, "unknown start state %d", (int)o->start);
    if (!isfinite(o->t0))
        return td_error_set(err, TD_ERR_INVALID, "t0 must be finite");
    return TD_OK;
}

/* The work space of sim_internal.h; 0 if out of memory. */
static int alloc_work(td_sim *s, size_t nr)
{
    size_t n = (size_t)s->dae.n, nc = nr + (size_t)s->dae.ns; /* KKT multipliers: lambda and F_t */
    s->ops.mass_x = calloc(n, sizeof(double));
    s->kkt.minv_f = calloc(n, sizeof(double));
    s->ops.power_x = calloc(n, sizeof(double));
    s->ops.power_kx = calloc(n, sizeof(double));
    s->ops.power_mx = calloc(n, sizeof(double));
    s->kkt.schur = calloc(nc * nc, sizeof(double));
    s->kkt.schur_rhs = calloc(nc, sizeof(double));
    s->kkt.restitution = calloc(nr, sizeof(double));
    s->kkt.impulse = calloc(nr, sizeof(double));
    s->kkt.impact_work = calloc(nr * (nr + 1), sizeof(double));
    s->kkt.minv_cols = calloc(n * nc, sizeof(double));
    s->kkt.rows = calloc(nc, sizeof *s->kkt.rows);
    s->kkt.active = calloc(nc, sizeof(int));
    s->kkt.active_roll = calloc(nc, sizeof(int));
    s->kkt.onset = calloc(nr, sizeof(int));
    s->kkt.entered = calloc(nr, sizeof(int));
    s->contacts.roll_tried = calloc(nr, sizeof(int));
    s->contacts.touching = calloc(nr, sizeof(int));
    s->monitor.totals = calloc(nr, sizeof *s->monitor.totals);
    s->monitor.thermal = calloc(nr, sizeof *s->monitor.thermal); /* heat */
    s->monitor.energy_f = calloc(n, sizeof(double));
    return s->ops.mass_x && s->kkt.minv_f && s->ops.power_x && s->ops.power_kx && s->ops.power_mx && s->kkt.schur &&
           s->kkt.schur_rhs && s->kkt.restitution && s->kkt.impulse && s->kkt.impact_work && s->kkt.minv_cols &&
           s->kkt.rows && s->kkt.active && s->kkt.active_roll && s->kkt.onset && s->contacts.roll_tried &&
           s->monitor.totals && s->monitor.energy_f && s->kkt.entered && s->contacts.touching && s->monitor.thermal;
}

static td_status alloc_arrays(td_sim *s, td_error *err)
{
    int na = td_model_amb_count(s->model), ok, i;
    size_t nr = (size_t)(s->dae.nr > 0 ? s->dae.nr : 1);
    s->machine.nu = td_model_unbalance_count(s->model);
    s->machine.unb = calloc((size_t)(s->machine.nu > 0 ? s->machine.nu : 1), sizeof *s->machine.unb);
    s->machine.amb_mode = calloc((size_t)(na > 0 ? na : 1), sizeof *s->machine.amb_mode);
    s->machine.amb_drive = calloc((size_t)(na > 0 ? na : 1), sizeof *s->machine.amb_drive); /* TD_AMB_PD */
    s->machine.amb_control = calloc((size_t)(2 * na + 2), sizeof(double));
    s->machine.held_current = calloc((size_t)(2 * na + 2), sizeof(double));
    s->machine.amb_current = calloc((size_t)(2 * na + 2), sizeof(double));
    s->machine.amb_coef = calloc((size_t)(s->sys->n_amb_axes + 1), sizeof *s->machine.amb_coef);
    s->monitor.q_cap = 4 * s->dae.nr + td_model_change_count(s->model) + 4;
    s->monitor.queue = calloc((size_t)s->monitor.q_cap, sizeof *s->monitor.queue);
    ok = alloc_work(s, nr);
    s->dae.n_sat_roots = s->dae.n_slew_roots = 0;
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        if (s->sys->amb_axes[i].saturation)
            s->dae.n_sat_roots = 2 * s->sys->n_amb_axes;
        if (s->sys->amb_axes[i].slew_rate > 0.0)
            s->dae.n_slew_roots = 2 * s->sys->n_amb_axes;
    }
    s->dae.nroots = TD_ROOTS_PER_RETAINER * s->dae.nr + s->dae.n_sat_roots + s->dae.n_slew_roots;
    s->dae.rootdir =
        calloc(TD_ROOTS_PER_RETAINER * nr + (size_t)(s->dae.n_sat_roots + s->dae.n_slew_roots), sizeof(int));
    s->dae.rootsfound =
        calloc(TD_ROOTS_PER_RETAINER * nr + (size_t)(s->dae.n_sat_roots + s->dae.n_slew_roots), sizeof(int));
    s->loop.ysave = calloc((size_t)s->dae.neq, sizeof(double));
    s->loop.ypsave = calloc((size_t)s->dae.neq, sizeof(double));
    s->monitor.ahead_y = calloc((size_t)s->dae.neq, sizeof(double));
    s->monitor.sensor_peak = calloc((size_t)(na > 0 ? na : 1), sizeof(double)); /* the bearing's duty */
    if (!ok || !s->machine.unb || !s->machine.amb_mode || !s->machine.amb_drive || !s->machine.amb_control ||
        !s->machine.held_current || !s->machine.amb_current || !s->machine.amb_coef || !s->monitor.queue ||
        !s->dae.rootdir || !s->dae.rootsfound || !s->loop.ysave || !s->loop.ypsave || !s->monitor.ahead_y ||
        !s->monitor.sensor_peak)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    return TD_OK;
}

/* The stiffness scale of a linear controller's axis a: the target force per metre of sensor
 * displacement of the law's direct part, |d target/d i| max|D| over the inputs (for a PD written as a
 * transfer function, ki kp, what the shorthand's gives). A strictly proper law (D = 0) has none;
 * its gain at the open-loop magnet's frequency sqrt(|ks| / rotor mass), where the law must act, is
 * taken instead; a plug-in's, measured (td_sim_plugin_gain), or where that is 0 (a non-linear
 * plug-in whose deadband the probe does not leave) the magnet's |ks| (the gain a holding law must
 * exceed). Scales only (tolerances, the step bound), never the dynamics. */
static double law_gain(const td_sim *s, const td_amb_axis *a, double target_i)
{
    const td_lti_law *L = &s->sys->laws[a->law];
    const td_controller *k = td_model_get_controller(s->model, a->law, NULL, NULL, NULL);
    double g = 0.0, mass = td_model_total_mass(s->model), *re;
    int m;
    if (L->plugin) { /* its gain as measured (sampler_plugin.c); it has no frequency response */
        g = td_sim_plugin_gain(s, a->law, a->law_output);
        /* none measured (a deadband wider than the probe, a probe that failed): the least a law that
         * holds the rotor must make, the magnet's own negative stiffness |ks|, as |ks| / |ki| A/m */
        if (g == 0.0 && a->ki != 0.0)
            g = fabs(a->ks / a->ki);
        return isfinite(g) ? fabs(target_i) * g : 0.0;
    }
    for (m = 0; m < L->nin; m++)
        g = fmax(g, fabs(L->D[a->law_output + (size_t)m * L->nout]));
    re = g == 0.0 && mass > 0.0 ? malloc(2 * (size_t)L->nin * (size_t)L->nout * sizeof *re) : NULL;
    if (re && td_controller_frequency_response(k, sqrt(fabs(a->ks) / mass) / (2.0 * TD_PI), re,
                                               re + (size_t)L->nin * (size_t)L->nout, NULL) == TD_OK)
        for (m = 0; m < L->nin; m++) {
            size_t at = (size_t)a->law_output + (size_t)m * (size_t)L->nout;
            g = fmax(g, hypot(re[at], re[(size_t)L->nin * (size_t)L->nout + at]));
        }
    free(re);
    return isfinite(g) ? fabs(target_i) * g : 0.0;
}

/* Machine state at the start: the model's unbalances, AMBs on, retainers free. */
static void init_machine(td_sim *s)
{
    int i, na = td_model_amb_count(s->model);
    s->machine.omega = td_model_speed_at(s->model, s->dae.t, NULL, NULL);
    for (i = 0; i < s->machine.nu; i++)
        td_model_get_unbalance(s->model, i, &s->machine.unb[i]);
    for (i = 0; i < na; i++)
        td_sim_amb_mode_set(s, i, TD_AMB_PD);
    /* the AMB laws are linear (model/amb.c): unit probes give their coefficients exactly */
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        const td_amb_axis *a = &s->sys->amb_axes[i];
        td_sim_amb_coef *c = &s->machine.amb_coef[i];
        c->cmd_x = td_amb_axis_command(a, 1.0, 0.0, 0.0) - td_amb_axis_command(a, 0.0, 0.0, 0.0);
        c->cmd_v = td_amb_axis_command(a, 0.0, 1.0, 0.0) - td_amb_axis_command(a, 0.0, 0.0, 0.0);
        c->cmd_e = td_amb_axis_command(a, 0.0, 0.0, 1.0) - td_amb_axis_command(a, 0.0, 0.0, 0.0);
        if (a->state >= 0) {
            double r0 = td_amb_axis_filter_rate(a, 0.0, 0.0, 0.0, 0.0);
            c->rate_x = td_amb_axis_filter_rate(a, 1.0, 0.0, 0.0, 0.0) - r0;
            c->rate_v = td_amb_axis_filter_rate(a, 0.0, 1.0, 0.0, 0.0) - r0;
            c->rate_e = td_amb_axis_filter_rate(a, 0.0, 0.0, 1.0, 0.0) - r0;
            c->rate_w = td_amb_axis_filter_rate(a, 0.0, 0.0, 0.0, 1.0) - r0;
            c->rate_i = td_amb_axis_lag_rate(a, td_amb_axis_current_command(a, 1.0), 0.0) -
                        td_amb_axis_lag_rate(a, td_amb_axis_current_command(a, 0.0), 0.0);
        }
        c->target_i = td_amb_axis_current_command(a, 1.0) - td_amb_axis_current_command(a, 0.0);
        c->gain_x = a->law >= 0 ? law_gain(s, a, c->target_i) : fabs(c->cmd_x);
    }
}

/* Highest natural frequency sqrt(lambda_max(M^-1 K)) of the shaft, by 60 power iterations with
 * the Rayleigh quotient (an estimate from below, good to a few per cent: it only sets a tolerance). */
static double highest_frequency(const td_sim *s)
{
    double *x = s->ops.power_x, *kx = s->ops.power_kx, *mx = s->ops.power_mx, lam = 0.0;
    int i, it;
    for (i = 0; i < s->dae.n; i++)
        x[i] = (i % 2 ? 1.0 : -1.0) * (1.0 + 0.1 * (i % 7));
    for (it = 0; it < 60; it++) {
        double num = 0.0, den = 0.0, norm = 0.0;
        memset(kx, 0, sizeof(double) * (size_t)s->dae.n);
        cs_di_gaxpy(s->dae.K, x, kx);
        for (i = 0; i < s->dae.n; i++)
            num += x[i] * kx[i];
        td_sim_mass_solve(s, kx); /* kx = M^-1 K x */
        memset(mx, 0, sizeof(double) * (size_t)s->dae.n);
        cs_di_gaxpy(s->dae.M, x, mx);
        for (i = 0; i < s->dae.n; i++)
            den += x[i] * mx[i];
        if (den > 0.0)
            lam = num / den;
        for (i = 0; i < s->dae.n; i++)
            norm = fmax(norm, fabs(kx[i]));
        if (!(norm > 0.0))
            break;
        for (i = 0; i < s->dae.n; i++)
            x[i] = kx[i] / norm;
    }
    return lam > 0.0 ? sqrt(lam) : 0.0;
}

/*
 * Scales for the tolerances and the step bound. Forces scale with a stiffness: the AMB's
 * (|ks| + ki kp, or its controller's gain_x, the largest axis) or, without AMBs, the largest diagonal of K. Velocities
 * scale with a frequency: the larger of the speed and sqrt(stiffness / rotor mass), the rigid-body bearing frequency.
 */
static void set_scales(td_sim *s)
{
    double k = 0.0, mass = td_model_total_mass(s->model), cmin = HUGE_VAL;
    int i;
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        const td_amb_axis *a = &s->sys->amb_axes[i];
        double ka = fabs(a->ks) + s->machine.amb_coef[i].gain_x;
        if (ka > k)
            k = ka;
    }
    if (k == 0.0) {
        const cs_di *K = s->sys->K;
        int j, p;
        for (j = 0; j < K->n; j++)
            for (p = K->p[j]; p < K->p[j + 1]; p++)
                if (K->i[p] == j && fabs(K->x[p]) > k)
                    k = fabs(K->x[p]);
    }
    if (!(k > 0.0))
        k = 1.0;
    s->machine.stiff_scale = k;
    s->machine.freq_scale = mass > 0.0 ? sqrt(k / mass) : 1.0;
    if (fabs(s->machine.omega) > s->machine.freq_scale)
        s->machine.freq_scale = fabs(s->machine.omega);
    if (s->machine.freq_scale < 1.0)
        s->machine.freq_scale = 1.0;
    for (i = 0; i < s->dae.nr; i++)
        if (s->contacts.ret[i].r.clearance < cmin)
            cmin = s->contacts.ret[i].r.clearance;
    if (s->dae.nr == 0)
        cmin = s->opt.solver.atol * 1e3;
    s->machine.freq_max = highest_frequency(s);
    if (s->machine.freq_max < s->machine.freq_scale)
        s->machine.freq_max = s->machine.freq_scale;
    /* contact constraints hold to a tenth of the displacement tolerance at every step */
    s->machine.constraint_tol = 0.1 * s->opt.solver.atol;
    /* hysteresis of the onset root after a release or a bounce: a gap or penetration within the
     * displacement tolerance (ten times the accuracy the constraint is held to) is not a contact; far
     * above rounding (1e-19 m), so a rotor grazing the circle does not chatter */
    s->machine.rearm_eps = s->opt.solver.atol;
    /* impacts slower than 1e-3 of the typical impact speed c * freq_scale become plastic */
    s->machine.rebound_min = 1e-3 * cmin * s->machine.freq_scale;
}

/* Step bound: 1/20 of the shortest period among the spin and the bearing frequency, so that a
 * gap cannot close and open again (two roots) inside one step unnoticed. */
double td_sim_default_max_step(const td_sim *s)
{
    double w = fabs(s->machine.omega) > s->machine.freq_scale ? fabs(s->machine.omega) : s->machine.freq_scale;
    return 2.0 * TD_PI / w / 20.0;
}

static int cancelled(volatile sig_atomic_t *cancel)
{
    return cancel && *cancel;
}

/* TD_OK, or TD_ERR_INTERRUPTED once `cancel` is set: read between the stages of the set-up. */
static td_status setup_stage(td_status st, volatile sig_atomic_t *cancel, td_error *err)
{
    if (st == TD_OK && cancelled(cancel))
        return td_error_set(err, TD_ERR_INTERRUPTED, "interrupted while setting up the simulation");
    return st;
}

/* Block offsets of the unknowns (sim_internal.h), the start time and the statistics' "none yet"
 * markers. */
static void init_layout(td_sim *s)
{
    s->dae.nw = s->sys->n_controller_states;
    s->dae.oq = 0;
    s->dae.ov = s->dae.n;
    s->dae.ow = 2 * s->dae.n;
    s->dae.ol = s->dae.ow + s->dae.nw;
    s->dae.ou = s->dae.ol + s->dae.nr;
    s->dae.of = s->dae.ou + s->dae.nr;
    s->dae.neq = s->dae.of + s->dae.ns;
    s->dae.t = s->solver.t_ida = s->monitor.t_acc = s->opt.t0;
    s->loop.t_window = s->opt.t0;
    s->monitor.stats.first_contact_time = TD_UNDEFINED;
    s->monitor.stats.peak_time = TD_UNDEFINED;
    s->monitor.stats.peak_retainer = -1;
    s->monitor.stats.peak_amb_time = TD_UNDEFINED;
    s->monitor.stats.peak_amb = -1;
}

/* The retainers, free, with their contact laws, and the DOFs of their races after the rotor's
 * (s->dae.n: all DOFs). */
static td_status init_retainers(td_sim *s, td_error *err)
{
    int k;
    s->model = td_system_model(s->sys);
    s->dae.nr = td_model_retainer_count(s->model);
    s->contacts.ret = calloc((size_t)(s->dae.nr > 0 ? s->dae.nr : 1), sizeof *s->contacts.ret);
    if (!s->contacts.ret)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    for (k = 0; k < s->dae.nr; k++) {
        td_sim_retainer_init(&s->contacts.ret[k], s->sys, k, &s->opt.contact);
        if (s->contacts.ret[k].r.stick)
            s->contacts.ret[k].fi = s->dae.ns++;
    }
    td_sim_races_layout(s);
    return td_sim_races_matrices(s, err);
}

/* The sampled controllers' sample 0, at the start time from the start state, and y' made
 * consistent with the commands they hold from then on. */
static td_status first_samples(td_sim *s, td_error *err)
{
    td_status st;
    int taken = td_sim_sampler_take_due(s);
    if (taken < 0) { /* a plug-in failed at sample 0: the failure names its controller */
        st = td_sim_sampler_failure(s);
        td_sim_plugin_error(s, st, err);
        return st;
    }
    if (taken == 0 || (st = td_sim_make_consistent(s, NULL)) == TD_OK)
        return TD_OK;
    return td_error_set(err, st, "%s", s->errmsg);
}

td_status td_sim_setup(const td_model *model, const td_sim_options *options, volatile sig_atomic_t *cancel,
                       td_sim **out, td_error *err)
{
    td_sim *s;
    td_status st;
    char why[320];
    *out = NULL;
    s = calloc(1, sizeof *s);
    if (!s)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory creating a simulation");
    if (options)
        s->opt = *options;
    else
        td_sim_options_default(&s->opt);
    st = check_options(&s->opt, err);
    if (st == TD_OK && td_atol_limit_check(model, s->opt.solver.atol, why, sizeof why) != TD_LIMIT_NONE)
        st = td_error_set(err, TD_ERR_INVALID, "solver.atol: %s", why);
    if (st == TD_OK)
        st = setup_stage(td_system_create(model, &s->sys, err), cancel, err);
    if (st == TD_OK)
        st = init_retainers(s, err);
    if (st == TD_OK) {
        init_layout(s);
        st = alloc_arrays(s, err);
    }
    if (st == TD_OK)
        st = td_sim_sampler_create(s, err);
    if (st == TD_OK) {
        init_machine(s);
        td_sim_apply_past_changes(s);
        s->machine.spin_ref = s->machine.omega * s->dae.t;
        s->machine.t_spin_ref = s->dae.t;
        st = td_sim_mass_factor(s, err);
    }
    if (st == TD_OK) {
        set_scales(s);
        s->solver.hmax = s->opt.solver.max_step > 0.0 ? s->opt.solver.max_step : td_sim_default_max_step(s);
    }
    if (st == TD_OK)
        st = td_sim_pattern_build(s, err);
    if (st == TD_OK)
        st = td_sim_structural_build(s, err);
    if (st == TD_OK)
        st = setup_stage(td_sim_integrator_create(s, err), cancel, err);
    if (st == TD_OK) {
        td_sim_set_tolerances(s);
        td_sim_start_stability(s);
        st = setup_stage(TD_OK, cancel, err);
    }
    if (st == TD_OK)
        st = setup_stage(td_sim_start_state(s, err), cancel, err);
    if (st == TD_OK && s->sampler)
        st = first_samples(s, err);
    if (st == TD_OK)
        st = td_sim_integrator_attach(s, err);
    if (st == TD_OK)
        st = td_sim_life_setup(s, err);
    if (st != TD_OK) {
        td_sim_teardown(s);
        return st;
    }
    td_sim_thermal_setup(s);
    td_sim_margin_start(s); /* clearance margin */
    td_sim_totals_point(s, s->dae.t, 1);
    s->monitor.slewing = td_sim_amb_slewing_axes(s, N_VGetArrayPointer(s->dae.y)); /* from the start */
    s->monitor.slew_t = s->dae.t;
    s->monitor.q_len = s->monitor.q_pos = 0; /* contacts at the start are a state, not events */
    s->monitor.stats.events = s->monitor.stats.releases = s->monitor.stats.contact_onsets = 0;
    *out = s;
    return TD_OK;
}

static void free_work(td_sim *s)
{
    free(s->ops.mass_x);
    free(s->kkt.minv_f);
    free(s->ops.power_x);
    free(s->ops.power_kx);
    free(s->ops.power_mx);
    free(s->kkt.schur);
    free(s->kkt.schur_rhs);
    free(s->kkt.restitution);
    free(s->kkt.impulse);
    free(s->kkt.impact_work);
    free(s->kkt.minv_cols);
    free(s->kkt.rows);
    free(s->kkt.active);
    free(s->kkt.active_roll);
    free(s->kkt.onset);
    free(s->kkt.entered);
    free(s->contacts.roll_tried);
    td_sim_life_free(s);
    free(s->monitor.totals);
    free(s->monitor.thermal);
    free(s->monitor.energy_f);
    free(s->contacts.touching);
}

void td_sim_teardown(td_sim *s)
{
    td_sim_integrator_free(s);
    cs_di_sfree(s->ops.Ms);
    cs_di_nfree(s->ops.Mn);
    free(s->ops.colptr);
    free(s->ops.rowind);
    free(s->ops.jdata);
    free(s->ops.map_M);
    free(s->ops.map_C);
    free(s->ops.map_G);
    free(s->ops.map_K);
    free(s->ops.map_Gw);
    free(s->ops.st_rowptr);
    free(s->ops.st_col);
    free(s->ops.st_M);
    free(s->ops.st_K);
    free(s->ops.st_D);
    free(s->machine.unb);
    free(s->machine.amb_mode);
    free(s->monitor.sensor_peak);
    free(s->machine.amb_drive);
    free(s->machine.amb_control);
    free(s->machine.held_current);
    free(s->machine.amb_current);
    free(s->contacts.ret);
    free(s->machine.amb_coef);
    free(s->monitor.queue);
    free_work(s);
    free(s->dae.rootdir);
    free(s->dae.rootsfound);
    free(s->loop.ysave);
    free(s->monitor.ahead_y);
    free(s->loop.ypsave);
    td_sim_races_free(s);
    td_sim_flight_free(s);
    td_sim_sampler_free(s);
    td_sim_section_free(s);
    td_system_free(&s->sys);
    free(s);
}
