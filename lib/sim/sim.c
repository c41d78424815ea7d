/*
 * td_sim: the public functions of touchdown/sim.h. Creation is in setup.c, the step loop in
 * stepping.c, the integrator in integrator.c, the DAE in sim_residual.c, mode switching in
 * sim_modes.c, the per-retainer queries in retainer.c; each public call checks its arguments,
 * starts with no message and reports a failure through its td_error.
 */
#include "sim/sim_internal.h"
#include "sim/supervisor.h"
#include "util/clock.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A public call that can fail begins with no message: whatever it reports is its own, never the
 * leftover of an earlier failure (an interrupt, say, that the caller recovered from). */
static void begin_call(td_sim *s)
{
    s->errmsg[0] = '\0';
}

/* A failure of a public call: the message the sim keeps (s->errmsg, td_sim_errmsg) into *err. */
static td_status failed(const td_sim *s, td_status st, td_error *err)
{
    if (td_sim_plugin_error(s, st, err)) /* a plug-in's failure names its controller (err->site) */
        return st;
    return td_error_set(err, st, "%s", s->errmsg[0] ? s->errmsg : td_strerror(st));
}

/* A public call's outcome: failures reported through *err, TD_OK and TD_EVENT as they are. */
static td_status reported(const td_sim *s, td_status st, td_error *err)
{
    return st < 0 ? failed(s, st, err) : st;
}

td_status td_sim_create(const td_model *model, const td_sim_options *options, td_sim **out, td_error *err)
{
    return td_sim_create_cancellable(model, options, NULL, out, err);
}

td_status td_sim_create_cancellable(const td_model *model, const td_sim_options *options, volatile sig_atomic_t *cancel,
                                    td_sim **out, td_error *err)
{
    if (!model || !out)
        return td_error_set(err, TD_ERR_INVALID, "td_sim_create: NULL argument");
    return td_sim_setup(model, options, cancel, out, err);
}

void td_sim_free(td_sim **sim)
{
    if (!sim || !*sim)
        return;
    td_sim_teardown(*sim);
    *sim = NULL;
}

const char *td_sim_errmsg(const td_sim *sim)
{
    return sim ? sim->errmsg : "";
}

td_status td_sim_step(td_sim *sim, double tout, double *t_reached, td_error *err)
{
    td_status st;
    double w0;
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "td_sim_step: NULL simulation");
    begin_call(sim);
    if (td_sim_pop_event(sim)) {
        if (t_reached)
            *t_reached = sim->dae.t;
        return TD_EVENT;
    }
    if (!isfinite(tout) || tout < sim->dae.t) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_step: tout = %.17g is before the current time %.17g", tout,
                 sim->dae.t);
        return failed(sim, TD_ERR_INVALID, err);
    }
    w0 = td_wall_clock();
    st = tout > sim->dae.t ? td_sim_advance(sim, tout) : TD_OK;
    sim->monitor.stats.wall_time += td_wall_clock() - w0;
    if (t_reached)
        *t_reached = sim->dae.t;
    return reported(sim, st, err);
}

td_status td_sim_start_info_get(const td_sim *sim, td_sim_start_info *out)
{
    if (!sim || !out)
        return TD_ERR_INVALID;
    *out = sim->start;
    return TD_OK;
}

td_status td_sim_set_interrupt(td_sim *sim, volatile sig_atomic_t *flag)
{
    if (!sim)
        return TD_ERR_INVALID;
    sim->interrupt = flag;
    return TD_OK;
}

double td_sim_speed(const td_sim *sim)
{
    return sim ? td_sim_rotor_speed(sim, N_VGetArrayPointer(sim->dae.y)) : 0.0;
}

double td_sim_time(const td_sim *sim)
{
    return sim ? sim->dae.t : NAN;
}

td_status td_sim_last_event(const td_sim *sim, td_event *ev)
{
    if (!sim || !ev)
        return TD_ERR_INVALID;
    if (!sim->monitor.have_last)
        return TD_ERR_STATE;
    *ev = sim->monitor.last;
    return TD_OK;
}

/* ---- accessors --------------------------------------------------------------------------- */

int td_sim_dof_count(const td_sim *sim)
{
    return sim ? sim->sys->ndof : 0;
}

td_status td_sim_get_state(const td_sim *sim, double *q, double *v)
{
    const double *y;
    if (!sim)
        return TD_ERR_INVALID;
    y = N_VGetArrayPointer(sim->dae.y);
    if (q)
        memcpy(q, y + sim->dae.oq, sizeof(double) * (size_t)sim->sys->ndof);
    if (v)
        memcpy(v, y + sim->dae.ov, sizeof(double) * (size_t)sim->sys->ndof);
    return TD_OK;
}

int td_sim_housing_body_state(const td_sim *sim, double q[4], double v[4])
{
    const double *y;
    int nb = sim ? sim->sys->nbody : 0, h = sim ? sim->sys->ndof - nb : 0, k;
    y = sim ? N_VGetArrayPointer(sim->dae.y) : NULL;
    for (k = 0; k < 4; k++) {
        if (q)
            q[k] = k < nb ? y[sim->dae.oq + h + k] : 0.0;
        if (v)
            v[k] = k < nb ? y[sim->dae.ov + h + k] : 0.0;
    }
    return nb > 0;
}

td_status td_sim_retainer_state(const td_sim *sim, int retainer, td_retainer_state *out)
{
    const double *y;
    const td_sim_retainer *r;
    double rx, ry, vx, vy;
    if (!sim || !out || retainer < 0 || retainer >= sim->dae.nr)
        return TD_ERR_INVALID;
    y = N_VGetArrayPointer(sim->dae.y);
    r = &sim->contacts.ret[retainer];
    out->x = y[sim->dae.oq + r->dx];
    out->y = y[sim->dae.oq + r->dy];
    out->race_x = r->rx >= 0 ? y[sim->dae.oq + r->rx] : 0.0;
    out->race_y = r->rx >= 0 ? y[sim->dae.oq + r->ry] : 0.0;
    out->race_speed = td_sim_race_speed(sim, retainer, y);
    td_sim_node_state(sim, retainer, y, &rx, &ry, &vx, &vy);
    out->radius = hypot(rx, ry);
    out->radial_velocity = td_contact_radial_velocity(rx, ry, vx, vy);
    out->whirl_angle = atan2(ry, rx);
    out->whirl_rate = out->radius > 0.0 ? (rx * vy - ry * vx) / (out->radius * out->radius) : 0.0;
    out->normal_force = td_sim_normal_force(sim, retainer, y);
    out->in_contact = r->mode != TD_RMODE_FREE;
    out->rolling = r->rolling;
    out->friction_force =
        out->in_contact
            ? td_contact_friction_force(r->r.friction, td_sim_slip_factor(sim, retainer, y, NULL), out->normal_force)
            : 0.0;
    if (r->rolling) /* F_t acts on the race along t, the opposite on the rotor */
        out->friction_force = -y[sim->dae.of + r->fi];
    out->sliding_velocity = td_sim_sliding_velocity(sim, retainer, y);
    {
        double T[2]; /* heat */
        td_sim_thermal_now(sim, retainer, T);
        out->race_temperature = T[0];
        out->housing_temperature = T[1];
    }
    return TD_OK;
}

td_status td_sim_amb_force(const td_sim *sim, int amb, double f[2])
{
    const double *y;
    int k;
    if (!sim || !f || amb < 0 || amb >= td_model_amb_count(sim->model))
        return TD_ERR_INVALID;
    y = N_VGetArrayPointer(sim->dae.y);
    f[0] = f[1] = 0.0;
    for (k = 0; k < sim->sys->n_amb_axes; k++)
        if (sim->sys->amb_axes[k].amb == amb)
            f[sim->sys->amb_axes[k].axis] = td_sim_amb_axis_force(sim, k, y);
    return TD_OK;
}

td_status td_sim_stats_get(const td_sim *sim, td_sim_stats *out)
{
    if (!sim || !out)
        return TD_ERR_INVALID;
    *out = sim->monitor.stats;
    td_sim_integrator_counters(sim, out);
    td_sim_supervisor_stats(sim, out);
    return TD_OK;
}

td_status td_sim_retainer_totals(const td_sim *sim, int retainer, td_retainer_totals *out)
{
    if (!sim || !out || retainer < 0 || retainer >= sim->dae.nr)
        return TD_ERR_INVALID;
    td_sim_totals_get(sim, retainer, out);
    return TD_OK;
}

td_status td_sim_retainer_peak_since(td_sim *sim, int retainer, double *peak)
{
    if (!sim || !peak || retainer < 0 || retainer >= sim->dae.nr)
        return TD_ERR_INVALID;
    *peak = sim->monitor.totals[retainer].mark_peak;
    sim->monitor.totals[retainer].mark_peak = 0.0;
    return TD_OK;
}

td_status td_sim_energy(const td_sim *sim, td_energy *out)
{
    if (!sim || !out || !sim->opt.energy)
        return TD_ERR_INVALID;
    td_sim_energy_get(sim, out);
    return TD_OK;
}

/* ---- changes between steps --------------------------------------------------------------- */

td_status td_sim_set_unbalance(td_sim *sim, int unbalance, double magnitude, double phase, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (unbalance < 0 || unbalance >= sim->machine.nu || !(magnitude >= 0.0) || !isfinite(magnitude) ||
        !isfinite(phase)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_unbalance: invalid unbalance %d or value", unbalance);
        return failed(sim, TD_ERR_INVALID, err);
    }
    sim->machine.unb[unbalance].magnitude = magnitude;
    sim->machine.unb[unbalance].phase = phase;
    return reported(sim, td_sim_restart_between_steps(sim), err);
}

td_status td_sim_set_speed(td_sim *sim, double omega, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (!TD_SPEED_VALID(omega)) {
        snprintf(sim->errmsg, sizeof sim->errmsg,
                 "td_sim_set_speed: speed must be finite and >= 0 rad/s (got %g; the spin is about +z)", omega);
        return failed(sim, TD_ERR_INVALID, err);
    }
    if (sim->machine.spin >= 0) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_speed: the model's speed is %s, not set by the caller",
                 sim->machine.spin_free ? "free (spin.free)" : "a ramp (speed_ramp)");
        return failed(sim, TD_ERR_INVALID, err);
    }
    /* keep the spin angle continuous: the unbalance force turns on from where it is */
    sim->machine.spin_ref = td_sim_spin_angle(sim, sim->dae.t);
    sim->machine.t_spin_ref = sim->dae.t;
    sim->machine.omega = omega;
    td_sim_structural_speed(sim);
    if (sim->opt.solver.max_step <= 0.0) {
        sim->solver.hmax = td_sim_default_max_step(sim);
    }
    return reported(sim, td_sim_restart_between_steps(sim), err);
}

td_status td_sim_set_amb_mode(td_sim *sim, int amb, td_amb_mode mode, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (amb < 0 || amb >= td_model_amb_count(sim->model) ||
        (mode != TD_AMB_PD && mode != TD_AMB_EXTERNAL && mode != TD_AMB_OFF && mode != TD_AMB_CURRENT)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_amb_mode: invalid AMB %d or mode %d", amb, (int)mode);
        return failed(sim, TD_ERR_INVALID, err);
    }
    td_sim_amb_mode_set(sim, amb, mode);
    if (mode != TD_AMB_OFF)
        sim->machine.amb_drive[amb] = mode;
    return reported(sim, td_sim_restart_between_steps(sim), err);
}

int td_sim_amb_mode(const td_sim *sim, int amb)
{
    return sim && amb >= 0 && amb < td_model_amb_count(sim->model) ? (int)sim->machine.amb_mode[amb] : -1;
}

td_status td_sim_set_amb_control(td_sim *sim, int amb, double fx, double fy, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (amb < 0 || amb >= td_model_amb_count(sim->model) || !isfinite(fx) || !isfinite(fy)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_amb_control: invalid AMB %d or force", amb);
        return failed(sim, TD_ERR_INVALID, err);
    }
    sim->machine.amb_control[2 * amb] = fx;
    sim->machine.amb_control[2 * amb + 1] = fy;
    /* the held force jumps: restart only when it acts now */
    return sim->machine.amb_mode[amb] == TD_AMB_EXTERNAL ? reported(sim, td_sim_restart_between_steps(sim), err)
                                                         : TD_OK;
}

td_status td_sim_set_amb_current(td_sim *sim, int amb, double ix, double iy, td_error *err)
{
    if (!sim)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL simulation", __func__);
    begin_call(sim);
    if (amb < 0 || amb >= td_model_amb_count(sim->model) || !isfinite(ix) || !isfinite(iy)) {
        snprintf(sim->errmsg, sizeof sim->errmsg, "td_sim_set_amb_current: invalid AMB %d or current", amb);
        return failed(sim, TD_ERR_INVALID, err);
    }
    if (sim->machine.amb_current[2 * amb] == ix && sim->machine.amb_current[2 * amb + 1] == iy)
        return TD_OK; /* held as it is: nothing jumps */
    sim->machine.amb_current[2 * amb] = ix;
    sim->machine.amb_current[2 * amb + 1] = iy;
    /* the target ki i jumps (and with it the force where tau = 0, or the lag's rate): restart only when
     * it acts now */
    return sim->machine.amb_mode[amb] == TD_AMB_CURRENT ? reported(sim, td_sim_restart_between_steps(sim), err) : TD_OK;
}

const td_system *td_sim_system(const td_sim *sim)
{
    return sim ? sim->sys : NULL;
}

const td_model *td_sim_model(const td_sim *sim)
{
    return sim ? sim->model : NULL;
}

td_status td_sim_options_get(const td_sim *sim, td_sim_options *out)
{
    if (!sim || !out)
        return TD_ERR_INVALID;
    *out = sim->opt;
    return TD_OK;
}

td_status td_sim_sensor_peak_displacement(const td_sim *sim, int amb, double *out)
{
    if (!sim || !out || amb < 0 || amb >= td_model_amb_count(sim->model))
        return TD_ERR_INVALID;
    td_sim_sensor_peak_get(sim, amb, out);
    return TD_OK;
}
