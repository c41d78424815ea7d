/*
 * The monitor's running statistics and event queue: the statistics of the accepted points (contact
 * time, peak normal force, the AMBs' peak load, the constraint drift) and the events waiting to be
 * reported by td_sim_step. Called by the layers above (the flight, the mode switching, the step
 * loop); calls only the retainers' queries and the DAE's forces below it.
 */
#include "sim/sim_internal.h"

#include <math.h>
#include <string.h>

int td_event_is_onset(td_event_kind kind)
{
    return kind == TD_EVENT_CONTACT_ONSET || kind == TD_EVENT_PENALTY_ENTER;
}

/* Queue an event and count it. A contact onset opens the retainer's interval peak; an event that
 * ends a contact interval carries it. */
void td_sim_queue_event(td_sim *s, const td_event *ev)
{
    td_event e = *ev;
    if (td_event_is_onset(e.kind) && e.retainer >= 0)
        s->monitor.totals[e.retainer].interval_peak = 0.0;
    if ((e.kind == TD_EVENT_RELEASE || e.kind == TD_EVENT_PENALTY_EXIT) && e.retainer >= 0)
        e.peak_normal_force = s->monitor.totals[e.retainer].interval_peak;
    if (s->monitor.q_len < s->monitor.q_cap)
        s->monitor.queue[s->monitor.q_len++] = e;
    s->monitor.stats.events++;
    switch (ev->kind) {
    case TD_EVENT_CONTACT_ONSET:
    case TD_EVENT_PENALTY_ENTER:
        s->monitor.stats.contact_onsets++;
        if (td_is_undefined(s->monitor.stats.first_contact_time))
            s->monitor.stats.first_contact_time = ev->time + s->monitor.leapt;
        break;
    case TD_EVENT_RELEASE:
    case TD_EVENT_PENALTY_EXIT: s->monitor.stats.releases++; break;
    default: break;
    }
}

void td_sim_event_velocities(const td_sim *s, int k, const double *y, int after, td_event *ev)
{
    double x, yy, vx, vy, vr, vt;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    vr = td_contact_radial_velocity(x, yy, vx, vy);
    vt = td_contact_tangential_velocity(x, yy, vx, vy);
    if (after) {
        ev->radial_velocity_after = vr;
        ev->tangential_velocity_after = vt;
    } else {
        ev->radial_velocity_before = ev->radial_velocity_after = vr;
        ev->tangential_velocity_before = ev->tangential_velocity_after = vt;
    }
}

/* An event of `kind` at s->dae.t, of retainer k (-1: none), no schedule entry. */
td_event td_sim_event_at(const td_sim *s, td_event_kind kind, int k)
{
    td_event ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = kind;
    ev.time = s->dae.t;
    ev.retainer = k;
    ev.change = -1;
    ev.controller = -1;
    return ev;
}

/* AMB axis k's force at time t against its capacity: a new peak load if it is the largest yet. */
void td_sim_monitor_amb_load(td_sim *s, int k, double force, double t)
{
    const td_amb_axis *a = &s->sys->amb_axes[k];
    double load = fabs(force) / a->capacity;
    if (load > s->monitor.stats.peak_amb_load) {
        s->monitor.stats.peak_amb_load = load;
        s->monitor.stats.peak_amb_force = fabs(force);
        s->monitor.stats.peak_amb_time = t + s->monitor.leapt;
        s->monitor.stats.peak_amb = a->amb;
    }
}

/* The AMBs' peak load at the state y (time t): the axis force against its capacity, while on. */
static void monitor_ambs(td_sim *s, double t, const double *y)
{
    int k;
    for (k = 0; k < s->sys->n_amb_axes; k++)
        if (s->machine.amb_mode[s->sys->amb_axes[k].amb] != TD_AMB_OFF)
            td_sim_monitor_amb_load(s, k, td_sim_amb_axis_force(s, k, y), t);
}

/* The time the amplifiers slew, up to t (the state y). The count of slewing axes holds between
 * two points, a kink of the slew being a stop (a root): it is the count at the interval's start,
 * or at its end after a stop on a kink, where the count is ambiguous (the root function is about
 * 0 there). Signed: an output inside the last step takes back the part of the step beyond it, so
 * that the time is exact at every time reached. */
static void monitor_slew(td_sim *s, double t, const double *y)
{
    int now = td_sim_amb_slewing_axes(s, y);
    int count = s->monitor.slew_kink && t != s->monitor.slew_t ? now : s->monitor.slewing;
    s->monitor.stats.time_slewing += (t - s->monitor.slew_t) * count;
    if (t != s->monitor.slew_t)
        s->monitor.slew_kink = 0;
    s->monitor.slew_t = t;
    s->monitor.slewing = now;
}

/* The peaks at the state y (time t): the retainers' normal forces (the run's peak, the open
 * interval's), the AMBs' load and, at an integrator step's end only (at_step; interpolated states
 * carry the interpolation error), the drift; with the retainers' own peaks (totals.c) when the
 * point was held (td_sim_monitor_step_ahead), which then skipped them. */
static void monitor_peaks(td_sim *s, double t, const double *y, int at_step)
{
    int k;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        double fn;
        if (r->mode == TD_RMODE_FREE)
            continue;
        if (r->mode == TD_RMODE_CONTACT && at_step) {
            double x, yy, vx, vy, drift;
            td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
            drift = fabs(hypot(x, yy) - r->r.clearance);
            if (drift > s->monitor.stats.worst_drift)
                s->monitor.stats.worst_drift = drift;
        }
        fn = td_sim_normal_force(s, k, y);
        s->monitor.totals[k].interval_peak = fmax(s->monitor.totals[k].interval_peak, fn);
        if (fn > s->monitor.stats.peak_normal_force) {
            s->monitor.stats.peak_normal_force = fn;
            s->monitor.stats.peak_time = t + s->monitor.leapt;
            s->monitor.stats.peak_retainer = k;
        }
    }
    monitor_ambs(s, t, y);
}

/* The held point (td_sim_monitor_step_ahead) once the run has reached t: its peaks recorded now,
 * before those of any later point, so that the first instant of a peak stays the first. */
static void monitor_reach(td_sim *s, double t)
{
    if (!s->monitor.ahead || s->monitor.ahead_t > t)
        return;
    s->monitor.ahead = 0;
    monitor_peaks(s, s->monitor.ahead_t, s->monitor.ahead_y, 1);
    td_sim_totals_peaks(s, s->monitor.ahead_y);
}

/* The times summed at the state in s->dae.y (time t): contact and slewing time. They are signed:
 * a retainer's mode holds over a step (it changes at stops only), and an output inside the last
 * step takes back the part of the step beyond it, so that the time is exact at every time
 * reached, the run's end included, and a change made there counts from there. */
static void monitor_sums(td_sim *s, double t)
{
    double dt = t - s->monitor.t_acc;
    int k;
    for (k = 0; k < s->dae.nr; k++)
        if (s->contacts.ret[k].mode != TD_RMODE_FREE)
            s->monitor.stats.time_in_contact += dt;
    if (s->dae.n_slew_roots > 0)
        monitor_slew(s, t, N_VGetArrayPointer(s->dae.y));
    s->monitor.t_acc = t;
}

/* Statistics at the state in s->dae.y (time t), a point the run has reached: the times summed and
 * the peaks, after those of a held point it has reached. */
void td_sim_monitor_at(td_sim *s, double t, int at_step)
{
    monitor_reach(s, t);
    monitor_sums(s, t);
    monitor_peaks(s, t, N_VGetArrayPointer(s->dae.y), at_step);
}

/* An integrator step's end at t beyond the output time the call returns at: the times summed now
 * (the output takes back the part beyond it), the peaks held with a copy of the state. A peak is
 * never a value beyond the time reached, with its time ahead of it: the held point counts once the
 * run reaches it, and not at all if the run goes on from before it (td_sim_monitor_settle). */
void td_sim_monitor_step_ahead(td_sim *s, double t)
{
    monitor_reach(s, t);
    monitor_sums(s, t);
    memcpy(s->monitor.ahead_y, N_VGetArrayPointer(s->dae.y), sizeof(double) * (size_t)s->dae.neq);
    s->monitor.ahead_t = t;
    s->monitor.ahead = 1;
}

void td_sim_monitor_settle(td_sim *s, double t)
{
    monitor_reach(s, t);
    s->monitor.ahead = 0;
}

/* The next queued event into s->monitor.last (td_sim_last_event); 0 when the queue is empty. */
int td_sim_pop_event(td_sim *s)
{
    if (s->monitor.q_pos >= s->monitor.q_len) {
        s->monitor.q_pos = s->monitor.q_len = 0;
        return 0;
    }
    s->monitor.last = s->monitor.queue[s->monitor.q_pos++];
    s->monitor.have_last = 1;
    if (s->monitor.q_pos >= s->monitor.q_len)
        s->monitor.q_pos = s->monitor.q_len = 0;
    return 1;
}
