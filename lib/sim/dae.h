/*
 * The DAE's record, the lowest of the sim: the unknowns' layout (sizes and block offsets,
 * sim_internal.h), the state they hold now (t, y, y'), the structural matrices of all DOFs and the
 * root functions' buffers. The set-up (setup.c) sizes it, race.c and spin.c lay out the DOFs of the
 * races and the spin and extend the matrices; every layer above reads the layout and moves the
 * state.
 */
#ifndef TD_SIM_DAE_H
#define TD_SIM_DAE_H

#include <nvector/nvector_serial.h>
#include <suitesparse/cs.h>

typedef struct td_sim_dae {
    int n, nw, nr, ns, neq;     /* DOFs (rotor and races), filter states, retainers, stick retainers, equations */
    int oq, ov, ow, ol, ou, of; /* block offsets in y */

    /* the state */
    double t;       /* current time: y, yp hold the state here */
    N_Vector y, yp; /* neq each */

    /* the structural matrices of all n DOFs (race.c): the system's own without races */
    cs_di *M, *K, *C, *G;
    int own_matrices; /* 1: M, K, C, G extended with races, owned */

    /* root functions */
    int nroots;      /* TD_ROOTS_PER_RETAINER per retainer, then n_sat_roots, n_slew_roots */
    int n_sat_roots; /* 2 per AMB axis when any axis saturates (its clip's kinks), else 0 */
    int *rootdir;    /* nroots: their directions for the current modes (td_sim_root_directions) */
    int *rootsfound; /* nroots: the roots found at the last stop (IDAGetRootInfo or the flight) */

    /* 2 per AMB axis when any amplifier has a slew-rate limit (its kinks, after the clips'), else 0 */
    int n_slew_roots;
} td_sim_dae;

#endif
