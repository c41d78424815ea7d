/*
 * The integrator's record: SUNDIALS IDA on the contact DAE, its Newton and linear solvers, the
 * per-component tolerances, the restarts and the running totals of the counters. integrator.c owns
 * it, with tolerance.c (the tolerances) and sim_linsol.c (KLU). The layers above read it (the
 * section IDA's interpolant, the public calls the counters); the step loop also keeps IDA's time in
 * it and marks its history stale after a flight, the set-up and td_sim_set_speed its step bound.
 */
#ifndef TD_SIM_INTEGRATOR_H
#define TD_SIM_INTEGRATOR_H

#include "sim/sundials_compat.h"

#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>

/* Running totals of the IDA counters, which IDAReInit resets. */
typedef struct td_sim_counters {
    long steps, res, jac, setups, nli, etf, ncf;
} td_sim_counters;

typedef struct td_sim_solver {
    SUNContext ctx;
    void *ida;
    N_Vector id;         /* 1: differential, 0: algebraic (tolerance.c) */
    N_Vector atol;       /* the per-component absolute tolerances (tolerance.c) */
    N_Vector newton_del; /* the Newton correction, its multipliers weighed against their rounding floor */
    SUNMatrix A;
    SUNLinearSolver LS;
    SUNNonlinearSolver NLS;
    SUNNonlinSolConvTestFn ida_ctest; /* IDA's own Newton convergence test, wrapped by the sim's */
    void *ida_ctest_data;
    td_sun_message_sink sink;
    double hmax;          /* s: the step bound */
    double t_ida;         /* IDA's internal time (>= t after an interpolated output) */
    int ida_stale;        /* the flight moved the state: IDA restarts before its next step */
    long tiny_steps;      /* consecutive IDA steps too short to move t (td_sim_stalled) */
    td_sim_counters base; /* IDA counters of finished integrator runs */
} td_sim_solver;

#endif
