/*
 * projective leap: the run loop's side (leap.h). The burst's counters (events, contact onsets, time
 * in contact) are the run's own, kept by the loop from the events; the simulation's totals and
 * energy account are moved on by td_sim_leap.
 */
#include "run/leap.h"

#include "run/clock.h"
#include "touchdown/dofs.h"
#include "touchdown/run.h"
#include "util/error_internal.h"

#include <math.h>
#include <string.h>

int td_run_leap_init(td_run_leap *l, const td_output_options *o, double speed0)
{
    if (!(o->leap_burst > 0.0))
        return 0;
    memset(l, 0, sizeof *l);
    l->burst = o->leap_burst;
    l->factor = o->leap_factor;
    l->heal = o->leap_heal;
    l->start = o->leap_start;
    l->speed0 = speed0;
    return 1;
}

/* 1 if a leap ending at `speed` would end too close to rest: half of it is at rest (td_run_at_rest),
 * or past it (the rule takes |speed|: a leap that would turn the rotor backwards), so that the last
 * approach to rest is integrated. */
static int near_rest(const td_run_leap *l, double speed)
{
    return !(speed > 0.0) || td_run_at_rest(l->speed0, 0.5 * speed);
}

int td_run_leap_feasible(const td_run_leap *l, const td_sim *sim, double length, const td_sim_leap_state *rate)
{
    double x;
    td_error err;
    return length > 0.0 && td_sim_leap_speed_change(sim, length, rate, &x, &err) == TD_OK &&
           !near_rest(l, td_sim_speed(sim) + x);
}

/* The leap's length: factor bursts in whole sample intervals, ending before t_end less a healing
 * and a burst, and one that can be made (td_run_leap_feasible: the speed change the leap will make
 * keeps off rest); the longest such, by bisection when the full one cannot, then in whole sample
 * intervals (rounded down, and one down again if that lands on the limit). */
static double leap_length(const td_run_leap *l, const td_sim *sim, const td_sim_leap_state *rate, double t,
                          double sample_rate, double t_end)
{
    double L = fmin(l->factor * rate->t, t_end - t - l->heal - rate->t), lo = 0.0, hi = L;
    int i;
    if (!(L > 0.0))
        return 0.0;
    if (!td_run_leap_feasible(l, sim, L, rate)) {
        for (i = 0; i < 60; i++) {
            double mid = 0.5 * (lo + hi);
            if (td_run_leap_feasible(l, sim, mid, rate))
                lo = mid;
            else
                hi = mid;
        }
        L = lo;
    }
    L = floor(L * sample_rate + 1e-9) / sample_rate;
    while (L > 0.0 && !td_run_leap_feasible(l, sim, L, rate)) /* a whole interval up may cross the limit */
        L -= 1.0 / sample_rate;
    return L > 0.0 ? L : 0.0;
}

double td_run_leap_due(td_run_leap *l, const td_sim *sim, double t, double rate, double t_end,
                       const td_run_leap_counts *now, td_sim_leap_state *rate_out, td_error *err)
{
    td_sim_leap_state to;
    if (l->phase == 0 && t >= l->start) {
        l->phase = 1;
        l->until = t + l->heal;
    }
    if (l->phase == 1 && td_run_reached(t, l->until)) {
        if (td_sim_leap_read(sim, &l->from, err) != TD_OK)
            return -1.0;
        l->counts = *now;
        l->phase = 2;
        l->until = t + l->burst;
        return 0.0;
    }
    if (l->phase != 2 || !td_run_reached(t, l->until))
        return 0.0;
    if (td_sim_leap_read(sim, &to, err) != TD_OK || td_sim_leap_rates(&l->from, &to, rate_out, err) != TD_OK)
        return -1.0;
    l->phase = 1; /* a leap refused (too close to the end or to rest) goes on with the next healing */
    l->until = t + l->heal;
    return leap_length(l, sim, rate_out, t, rate, t_end);
}

td_status td_run_leap_make(td_run_leap *l, td_sim *sim, double t, double length, const td_sim_leap_state *rate,
                           td_run_leap_counts *now, td_error *err)
{
    double B = rate->t, dw, delta;
    td_status st = td_sim_leap_speed_change(sim, length, rate, &dw, err);
    if (st != TD_OK || (st = td_sim_leap(sim, length, rate, err)) != TD_OK)
        return st;
    l->dw_power += dw; /* what the leap made, and what the burst's own dOmega/dt would have */
    l->dw_rate += length * rate->speed;
    delta = rate->speed - l->rate_mean;
    l->rate_mean += length / (l->offset + length) * delta;
    l->rate_m2 += length * delta * (rate->speed - l->rate_mean);
    now->events += lround(length * (double)(now->events - l->counts.events) / B);
    now->contacts += lround(length * (double)(now->contacts - l->counts.contacts) / B);
    now->contact_time += length * (now->contact_time - l->counts.contact_time) / B;
    l->offset += length;
    l->leaps++;
    l->phase = 1;
    l->until = t + length + l->heal;
    return TD_OK;
}

double td_run_leap_decel_sd(const td_run_leap *l)
{
    return l->leaps > 1 && l->offset > 0.0 ? sqrt(l->rate_m2 / l->offset) : TD_UNDEFINED;
}
