/*
 * The operators' record (sim_pattern.c): the mass matrix's factorisation, the Jacobian's fixed
 * pattern with its values (written by sim_residual.c td_sim_jacobian) and the row-compressed
 * structural operator M v' + (C + Omega G) v + K q. Built once from the DAE's matrices (dae.h) and
 * the retainers' DOFs (retainer.h); read by the residual, the energy account and the integrator.
 */
#ifndef TD_SIM_PATTERN_H
#define TD_SIM_PATTERN_H

#include <suitesparse/cs.h>

typedef struct td_sim_operators {
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
    int *map_Gw;                        /* free spin: position of entry (row of G's entry p, the speed's column) */

    /* M, K and D = C + Omega G on the union of their patterns, row-compressed (CSR): the residual
     * forms M v' + D v + K q row by row in one pass (sim_residual.c); D follows the speed */
    int st_nnz;
    int *st_rowptr, *st_col;
    double *st_M, *st_K, *st_D;
} td_sim_operators;

#endif
