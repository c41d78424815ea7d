/*
 * The DAE's record: the unknowns' layout (sizes and block offsets, sim_internal.h), the state they
 * hold now (t, y, y'), the structural matrices of all DOFs (race.c), the mass matrix's
 * factorisation, the Jacobian's fixed pattern and the row-compressed structural operator
 * (sim_pattern.c), and the root functions' buffers (sim_residual.c). The layers above read the
 * layout and change the state; only the set-up (setup.c) sizes it.
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

    /* mass matrix factorisation (LU, CXSparse), for consistent accelerations and the impact map */
    cs_dis *Ms;
    cs_din *Mn;
    double *mass_x;   /* n: td_sim_mass_solve's permuted solution */
    double *power_x;  /* n: highest_frequency's iterate x */
    double *power_kx; /* n: highest_frequency's M^-1 K x */
    double *power_mx; /* n: highest_frequency's M x */

    /* Jacobian: one fixed CSC pattern (superset of every mode), values rebuilt at every call */
    int nnz;
    int *colptr, *rowind;
    double *jdata;
    int *map_M, *map_C, *map_G, *map_K; /* position of each stored entry of the system matrices */

    /* M, K and D = C + Omega G on the union of their patterns, row-compressed (CSR): the residual
     * forms M v' + D v + K q row by row in one pass (sim_residual.c); D follows the speed */
    int st_nnz;
    int *st_rowptr, *st_col;
    double *st_M, *st_K, *st_D;

    /* root functions */
    int nroots;      /* TD_ROOTS_PER_RETAINER per retainer, then n_sat_roots */
    int n_sat_roots; /* 2 per AMB axis when any axis saturates (its clip's kinks), else 0 */
    int *rootdir;    /* nroots: their directions for the current modes (td_sim_root_directions) */
    int *rootsfound; /* nroots: the roots found at the last stop (IDAGetRootInfo or the flight) */
} td_sim_dae;

#endif
