/*
 * A retainer's lumped thermal network (touchdown/model.h td_retainer_thermal; docs/theory.md,
 * "Thermal retainers") in closed form: the race node and the housing node, the ambient at 0,
 *
 *     C dT/dt = -G T + e_r P(t),   C = diag(C_r, C_h),   G = [G_rh, -G_rh; -G_rh, G_rh + G_ha],
 *
 * with T = (T_r, T_h) the rises above the ambient and P the heat into the race. C^(-1/2) G C^(-1/2)
 * is symmetric with eigenvalues lambda_i >= 0 and orthonormal eigenvectors; over a segment of
 * length h with P linear in time each mode z_i follows exactly
 *
 *     z_i(h) = exp(-lambda_i h) z_i(0) + b_i h [P0 (phi1 - phi2) + P1 phi2](lambda_i h),
 *     phi1(x) = (1 - exp(-x)) / x,   phi2(x) = (x - 1 + exp(-x)) / x^2,
 *
 * so a step is exact for any h (also h < 0: the segment taken back) and the energy balance
 * C_r dT_r + C_h dT_h + int G_ha T_h dt = int P dt holds to round-off.
 */
#ifndef TD_SIM_THERMAL_H
#define TD_SIM_THERMAL_H

#include "touchdown/model.h"

typedef struct td_thermal_network {
    double capacity[2]; /* C_r, C_h, J/K */
    double lambda[2];   /* eigenvalues of C^(-1/2) G C^(-1/2), 1/s, >= 0 */
    double q[2][2];     /* its orthonormal eigenvectors, columns: q[row][mode] */
} td_thermal_network;

/* The network of t in modal form. */
void td_thermal_network_init(td_thermal_network *n, const td_retainer_thermal *t);

/* T (race, housing; K above the ambient) after h seconds (h < 0: before) with the heat into the
 * race going linearly from p0 (W, at the start) to p1 (at the end). */
void td_thermal_network_step(const td_thermal_network *n, double T[2], double h, double p0, double p1);

/* The largest lambda_i |h|: how far a step of h reaches into the network's fastest mode. */
double td_thermal_network_reach(const td_thermal_network *n, double h);

#endif
