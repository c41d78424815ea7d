/*
 * The step loop behind td_sim_step: IDA's steps and the closed-form flight toward the output time,
 * the stops (roots, schedule times, missed crossings) handled between steps, the restarts after
 * them and after changes between steps, and the guards against a run that stalls.
 */
#include "sim/section.h"
#include "sim/sim_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ida/ida.h>

#define monitor(s, t) td_sim_monitor_at((s), (t), 0)

/* An IDA failure: keep the state of the last successful step. */
static td_status solver_failure(td_sim *s, int flag)
{
    char msg[TD_ERROR_MESSAGE_SIZE];
    double tn = s->dae.t;
    snprintf(msg, sizeof msg, "%s", s->errmsg);
    if (IDAGetCurrentTime(s->solver.ida, &tn) == IDA_SUCCESS && tn >= s->dae.t && td_sim_interpolate(s, tn) == TD_OK) {
        /* state at tn */
    } else {
        memcpy(N_VGetArrayPointer(s->dae.y), s->loop.ysave, sizeof(double) * (size_t)s->dae.neq);
        memcpy(N_VGetArrayPointer(s->dae.yp), s->loop.ypsave, sizeof(double) * (size_t)s->dae.neq);
    }
    td_sim_monitor_settle(s, s->dae.t); /* the run ends here: a step held beyond the output counts if reached */
    snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: IDA failed (flag %d): %.400s", s->dae.t, flag, msg);
    return TD_ERR_SOLVER;
}

/*
 * A run whose work no longer moves time is stuck, whatever the cause (steps, restarts at events,
 * flights cut short by stops), and fails with a message instead of going on for ever. Every
 * PROGRESS_WINDOW passes of integration (an IDA step or a piece of free flight, each with the stops
 * it meets) must advance t by PROGRESS_SPAN at least: a pace of 1e-10 s a pass would need 1e10
 * passes per simulated second, 100 times TD_MAX_STEPS, the most steps any case may force. (An
 * absolute tolerance far above the clearance once made a drop run advance 2e-6 s in 35 s of
 * passes, 6e-8 s a window.) Passes that only interpolate to an output time do not count.
 */
#define PROGRESS_WINDOW 10000L
#define PROGRESS_SPAN 1e-6

static int no_progress(td_sim *s)
{
    if (++s->loop.passes < PROGRESS_WINDOW)
        return 0;
    if (s->dae.t - s->loop.t_window >= PROGRESS_SPAN) {
        s->loop.passes = 0;
        s->loop.t_window = s->dae.t;
        return 0;
    }
    snprintf(s->errmsg, sizeof s->errmsg,
             "t = %.9g s: no progress: %ld integrator steps and stops advanced the time by only %.3g s (a run "
             "this slow would take over %.0e steps per simulated second); loosen solver.rtol or solver.atol, "
             "or check the machine for forces that grow without bound",
             s->dae.t, s->loop.passes, s->dae.t - s->loop.t_window, (double)PROGRESS_WINDOW / PROGRESS_SPAN);
    return 1;
}

/* The integrator restarted at s->dae.t (td_sim_restart): the section's samples taken beyond s->dae.t belonged
 * to a state that has since been changed, and whatever IDA had found beyond s->dae.t belongs to the
 * discarded integration. */
static td_status restart_integrator(td_sim *s)
{
    td_status st;
    td_sim_section_rewind(s);
    td_sim_monitor_settle(s, s->dae.t);
    st = td_sim_restart(s);
    if (st == TD_OK)
        s->loop.pending = 0;
    return st;
}

/* Restart after a change made between steps or at a schedule time; the retainers' totals open
 * their next segment there. */
td_status td_sim_restart_after_change(td_sim *s)
{
    td_status st;
    td_sim_totals_rewind(s); /* a change at an output inside the last step: the totals end here */
    st = td_sim_make_consistent(s, NULL);
    if (st == TD_OK)
        st = restart_integrator(s);
    if (st == TD_OK)
        td_sim_totals_point(s, s->dae.t, 1);
    return st;
}

/* What stopped the integration at s->loop.t_pending (s->loop.pending). */
enum { TD_PENDING_NONE = 0, TD_PENDING_ROOT = 1, TD_PENDING_TSTOP = 2, TD_PENDING_RESYNC = 3 };

/* Handle a root (IDAGetRootInfo in s->dae.rootsfound), a penalty mode out of step with the state
 * (TD_PENDING_RESYNC: no root), or the stop time at s->dae.t. The samples of sampled controllers
 * due then are taken last, from the state after the event or the change. */
static td_status handle_stop(td_sim *s, int kind)
{
    td_status st;
    int taken;
    if (kind == TD_PENDING_RESYNC) {
        memset(s->dae.rootsfound, 0, sizeof(int) * (size_t)s->dae.nroots);
        kind = TD_PENDING_ROOT;
    }
    if (kind == TD_PENDING_ROOT) {
        int restart = 0;
        st = td_sim_handle_roots(s, &restart);
        if (st == TD_OK && restart)
            st = restart_integrator(s);
        if (st == TD_OK && restart) {
            monitor(s, s->dae.t); /* the state after the event: an impact's normal force counts in the peaks */
            td_sim_totals_point(s, s->dae.t, 1);
        }
        taken = st == TD_OK && s->sampler ? td_sim_sampler_take_due(s) : 0;
        if (taken > 0) /* a root on a sample instant */
            st = td_sim_restart_after_change(s);
        return taken < 0 ? td_sim_sampler_failure(s) : st;
    }
    st = td_sim_apply_due_changes(s);
    if (st == TD_OK && s->sampler && td_sim_sampler_take_due(s) < 0)
        return td_sim_sampler_failure(s);
    if (st == TD_OK)
        st = td_sim_restart_after_change(s);
    return st;
}

/* A stop the flight reached (no root): the samples due there are taken and the flight carries the
 * currents they hold on from here, the integrator left stale until it is needed (td_sim_flight_hold);
 * a schedule change, or a flight that cannot go on, takes handle_stop's restart. */
static td_status flight_stop(td_sim *s)
{
    if (!s->sampler || td_sim_change_due(s))
        return handle_stop(s, TD_PENDING_TSTOP);
    if (td_sim_sampler_take_due(s) < 0)
        return td_sim_sampler_failure(s);
    return td_sim_flight_hold(s) ? TD_OK : td_sim_restart_after_change(s);
}

/* The stop pending beyond the last output time (a root, the stop time or a penalty resync): past
 * tout, only interpolate to tout; otherwise handle it. Returns 1 when advance returns *st (tout
 * reached, an event to report or a failure), 0 to go on integrating. */
static int pending_stop(td_sim *s, double tout, td_status *st)
{
    int kind = s->loop.pending;
    if (s->loop.t_pending > tout) {
        *st = td_sim_interpolate(s, tout);
        monitor(s, tout);
        return 1;
    }
    s->loop.pending = 0;
    td_sim_section_ida(s, s->loop.t_pending); /* the crossings before the stop, from the step that found it */
    *st = td_sim_interpolate(s, s->loop.t_pending);
    monitor(s, s->dae.t);
    if (*st == TD_OK)
        td_sim_totals_point(s, s->dae.t, 0); /* the segment up to the stop */
    if (*st == TD_OK)
        *st = handle_stop(s, kind);
    if (*st != TD_OK)
        return 1;
    if (td_sim_pop_event(s)) {
        *st = TD_EVENT;
        return 1;
    }
    return 0;
}

/* The state at tret accepted (an integrator step's end, at_step, or the flight's): statistics,
 * and the state kept as the last good one. A step's end beyond the output time (ahead) has its
 * peaks held until the run reaches it (td_sim_monitor_step_ahead). */
static void accept_point(td_sim *s, double tret, int at_step, int ahead)
{
    s->dae.t = tret;
    td_sim_spin_hold(s, tret, N_VGetArrayPointer(s->dae.y), N_VGetArrayPointer(s->dae.yp));
    if (ahead)
        td_sim_monitor_step_ahead(s, tret);
    else
        td_sim_monitor_at(s, tret, at_step);
    td_sim_totals_point(s, tret, 0);
    memcpy(s->loop.ysave, N_VGetArrayPointer(s->dae.y), sizeof(double) * (size_t)s->dae.neq);
    memcpy(s->loop.ypsave, N_VGetArrayPointer(s->dae.yp), sizeof(double) * (size_t)s->dae.neq);
}

/* Free flight in closed form (flight.c) from s->dae.t toward tout, up to the next stop. Returns 0 if
 * the flight cannot carry the machine now (IDA integrates), 1 when advance returns *st (tout
 * reached, an event to report or a failure), 2 to go on. */
static int fly(td_sim *s, double tout, td_status *st)
{
    double stop = td_sim_next_stop(s), t0 = s->dae.t;
    int root = 0;
    if (!td_sim_flight_advance(s, N_VGetArrayPointer(s->solver.atol), tout, stop, &root))
        return 0;
    s->solver.ida_stale = 1; /* IDA's history is of the state before the flight */
    s->solver.t_ida = s->dae.t;
    td_sim_monitor_settle(s, t0); /* and so is a step of IDA's held beyond t0 */
    td_sim_section_flight(s, s->dae.t);
    accept_point(s, s->dae.t, 0, 0);
    *st = TD_OK;
    if (root || s->dae.t >= stop) {
        *st = root ? handle_stop(s, TD_PENDING_ROOT) : flight_stop(s);
        if (*st != TD_OK)
            return 1;
        if (td_sim_pop_event(s)) {
            *st = TD_EVENT;
            return 1;
        }
        return 2;
    }
    return s->dae.t >= tout ? 1 : 2;
}

td_status td_sim_advance(td_sim *s, double tout)
{
    if (td_sim_sampler_failure(s) != TD_OK) /* a plug-in failed: no result from its sample on */
        return TD_ERR_INVALID;
    for (;;) {
        sunrealtype tret = s->dae.t, tn = s->dae.t;
        int flag;
        td_status st;
        if (s->loop.pending) {
            if (pending_stop(s, tout, &st))
                return st;
            continue;
        }
        if (s->solver.t_ida == s->dae.t &&
            tout == s->dae.t) { /* restarted right here (a stop at tout): nothing to interpolate */
            monitor(s, tout);
            return TD_OK;
        }
        if (s->solver.t_ida >= tout) {
            st = td_sim_interpolate(s, tout);
            monitor(s, tout);
            return st;
        }
        if (tout - s->dae.t <= 1e-14 * (1.0 + fabs(tout))) { /* too close for IDA to start: nothing moves */
            s->dae.t = tout;
            td_sim_monitor_settle(s, tout);
            return TD_OK;
        }
        if (s->interrupt && *s->interrupt) {
            /* y, yp hold the state at s->dae.t here (a step's end, a restart or the flight's end) */
            snprintf(s->errmsg, sizeof s->errmsg, "t = %.9g s: interrupted", s->dae.t);
            return TD_ERR_INTERRUPTED;
        }
        if (no_progress(s))
            return TD_ERR_SOLVER; /* y, yp hold the state at s->dae.t, as for an interrupt */
        switch (fly(s, tout, &st)) {
        case 1: return st;
        case 2: continue;
        default: break;
        }
        if (s->solver.ida_stale) {
            td_sim_flight_rates(s);
            if ((st = restart_integrator(s)) != TD_OK)
                return st;
        }
        flag = IDASolve(s->solver.ida, tout, &tret, s->dae.y, s->dae.yp, IDA_ONE_STEP);
        if (flag < 0)
            return solver_failure(s, flag);
        if (IDAGetCurrentTime(s->solver.ida, &tn) == IDA_SUCCESS && tn > s->solver.t_ida)
            s->solver.t_ida = tn;
        if (td_sim_stalled(s, tret)) {
            accept_point(s, tret, 1, 0); /* the run ends at the stalled step, its state in place */
            return TD_ERR_SOLVER;
        }
        if (flag == IDA_ROOT_RETURN || flag == IDA_TSTOP_RETURN) {
            if (flag == IDA_ROOT_RETURN)
                IDAGetRootInfo(s->solver.ida, s->dae.rootsfound);
            s->loop.pending = flag == IDA_ROOT_RETURN ? TD_PENDING_ROOT : TD_PENDING_TSTOP;
            s->loop.t_pending = tret;
            continue;
        }
        if (td_sim_modes_out_of_step(s, N_VGetArrayPointer(s->dae.y))) {
            /* IDA missed a crossing (retainer.c): switch the mode at this step's end */
            s->loop.pending = TD_PENDING_RESYNC;
            s->loop.t_pending = tret;
            continue;
        }
        accept_point(s, tret, 1, tret > tout);
        td_sim_section_ida(s, tret);
        td_sim_flight_forget(s);
        if (tret > tout) { /* an output inside this step: its sample counts too */
            st = td_sim_interpolate(s, tout);
            monitor(s, tout);
            return st;
        }
        if (tret == tout)
            return TD_OK;
    }
}

/* A change made between steps (the td_sim_set_* calls): the restart, then a stop within rounding ahead
 * of the current time (a sample or schedule time that the last td_sim_step's tout fell short of by an
 * ulp or so) is due now and handled here, as the loop handles a stop it reaches: IDA cannot start
 * towards a stop time within rounding of its own ("tstop is behind current t"), and a stop left an ulp
 * ahead would cut the next step to nothing. */
td_status td_sim_restart_between_steps(td_sim *s)
{
    td_status st = td_sim_restart_after_change(s);
    double stop = td_sim_next_stop(s);
    if (st == TD_OK && stop <= s->dae.t + TD_SIM_DUE_TOLERANCE(s->dae.t)) /* also one passed by rounding */
        st = handle_stop(s, TD_PENDING_TSTOP);
    return st;
}
