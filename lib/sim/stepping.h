/*
 * The step loop's record (stepping.c): what stopped the integration beyond the last output time,
 * the progress guard's window and the last good state.
 */
#ifndef TD_SIM_STEPPING_H
#define TD_SIM_STEPPING_H

typedef struct td_sim_loop {
    int pending;            /* what stopped IDA beyond the last output time (TD_PENDING_*), 0: nothing */
    double t_pending;       /* where */
    long passes;            /* integration passes (steps, flights) since t_window (no_progress) */
    double t_window;        /* the time when the current window of passes began */
    double *ysave, *ypsave; /* neq each: the last good state */
} td_sim_loop;

#endif
