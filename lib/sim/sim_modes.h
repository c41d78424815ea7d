/*
 * The mode switching's record (sim_modes.c): the work space of the KKT solve that makes a restart
 * consistent and of the impact map, each array with one job (n: DOFs, nr: retainers, ns: stick
 * retainers). Only sim_modes.c touches it (setup.c allocates it).
 */
#ifndef TD_SIM_MODES_H
#define TD_SIM_MODES_H

#include "contact/contact.h"

typedef struct td_sim_kkt {
    double *minv_f;       /* n: M^-1 f (kkt_solve, free_normal_acceleration) */
    double *schur;        /* (nr + ns)^2: kkt_solve's J M^-1 B of the active contacts and rolls */
    double *schur_rhs;    /* nr + ns: its right-hand side, then lambda and F_t */
    double *restitution;  /* nr: impacts, the restitution of each contact in the impact map */
    double *impulse;      /* nr: impacts, the impulse of each contact */
    double *impact_work;  /* nr * (nr + 1): td_contact_impact_map's work space */
    double *minv_cols;    /* n * (nr + ns): M^-1 B_k or M^-1 J_k^T columns of the active contacts */
    td_contact_row *rows; /* nr + ns: contact rows J_k of the active contacts */
    int *active;          /* nr + ns: indices of the retainers in the small system (kkt_solve, impacts) */
    int *active_roll;     /* nr + ns: 1 where that multiplier is a rolling F_t, 0 a normal force */
    int *onset, *entered; /* nr each: onset roots and contacts entered at an instant */
} td_sim_kkt;

#endif
