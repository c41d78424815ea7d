/*
 * The machine's schedule: the model's timed changes (unbalance, AMBs off and on) applied when due,
 * and the times at which the integrator must stop (a change, a point of a speed ramp).
 */
#include "sim/sim_internal.h"

#include <math.h>
#include <string.h>

void td_sim_amb_mode_set(td_sim *s, int amb, td_amb_mode mode)
{
    s->machine.amb_mode[amb] = mode;
    td_system_set_amb_off(s->sys, amb, mode == TD_AMB_OFF);
}

/* Apply schedule entry c (the model's TD_CHANGE_*). */
static void apply_change(td_sim *s, const td_change *c)
{
    switch (c->kind) {
    case TD_CHANGE_UNBALANCE:
        if (c->index >= 0 && c->index < s->machine.nu) {
            s->machine.unb[c->index].magnitude = c->magnitude;
            s->machine.unb[c->index].phase = c->phase;
        }
        break;
    case TD_CHANGE_AMB_OFF:
        if (c->index >= 0 && c->index < td_model_amb_count(s->model))
            td_sim_amb_mode_set(s, c->index, TD_AMB_OFF);
        break;
    case TD_CHANGE_AMB_ON:
        if (c->index >= 0 && c->index < td_model_amb_count(s->model))
            td_sim_amb_mode_set(s, c->index, s->machine.amb_drive[c->index]); /* its control as before */
        break;
    }
}

/* Changes at most this close after t count as due at t (the stop time lands on them exactly). */
static double due_tolerance(double t)
{
    return TD_SIM_DUE_TOLERANCE(t);
}

int td_sim_change_due(const td_sim *s)
{
    td_change c;
    if (s->machine.next_change >= td_model_change_count(s->model))
        return 0;
    td_model_get_change(s->model, s->machine.next_change, &c);
    return c.time <= s->dae.t + due_tolerance(s->dae.t);
}

td_status td_sim_apply_due_changes(td_sim *s)
{
    int count = td_model_change_count(s->model);
    while (s->machine.next_change < count) {
        td_change c;
        td_event ev;
        td_model_get_change(s->model, s->machine.next_change, &c);
        if (c.time > s->dae.t + due_tolerance(s->dae.t))
            break;
        apply_change(s, &c);
        ev = td_sim_event_at(s, TD_EVENT_SCHEDULE, -1);
        ev.change = td_model_change_entry(s->model, s->machine.next_change); /* as written, not in time order */
        td_sim_queue_event(s, &ev);
        s->machine.next_change++;
    }
    return TD_OK;
}

void td_sim_apply_past_changes(td_sim *s)
{
    int count = td_model_change_count(s->model);
    while (s->machine.next_change < count) {
        td_change c;
        td_model_get_change(s->model, s->machine.next_change, &c);
        if (c.time > s->dae.t + due_tolerance(s->dae.t))
            break;
        apply_change(s, &c);
        s->machine.next_change++;
    }
}

/* Where the integrator must stop next: the next schedule change, the next point of a speed ramp
 * (the speed's slope jumps there, and with it the unbalance's alpha term), the next sample of a
 * sampled controller (its held command jumps there), or the next kink of the housing's motion;
 * infinity if none. */
double td_sim_next_stop(const td_sim *s)
{
    double stop = INFINITY;
    int i;
    if (s->machine.next_change < td_model_change_count(s->model)) {
        td_change c;
        td_model_get_change(s->model, s->machine.next_change, &c);
        stop = c.time;
    }
    for (i = 0; i < td_model_speed_point_count(s->model); i++) {
        td_speed_point p;
        td_model_get_speed_point(s->model, i, &p);
        if (p.time > s->dae.t + due_tolerance(s->dae.t)) {
            stop = fmin(stop, p.time);
            break;
        }
    }
    if (s->sampler)
        stop = fmin(stop, td_sim_sampler_next_time(s));
    /* housing motion: its pulses' starts and ends and the history's ends (touchdown/housing.h) */
    if (s->sys->base_load[0])
        stop = fmin(stop, td_model_housing_next_kink(s->model, s->dae.t + due_tolerance(s->dae.t)));
    return stop;
}
