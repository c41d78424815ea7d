/*
 * The reference rig of docs/reference-rig.md built in code, for tests that need the machine
 * without going through the case reader (cases/rig.cfg describes the same machine; the test
 * tests/validation/test_rig_modal.c checks that both give the same eigenvalues).
 *
 * Shaft: 12 equal Euler-Bernoulli steel elements, 2 m, 50 mm diameter, nodes 0 (NDE) to 12 (DE),
 * consistent mass, no structural damping. Solid steel discs (10 kg, radius 0.12 m, so
 * t = m/(rho pi R^2), Ip = m R^2/2 = 0.072 and Id = m (3 R^2 + t^2)/12 = 0.0366676 kg m^2) at nodes
 * 1, 5, 7, 11; 14.6 kg journals at nodes 3 and 9; AMBs at nodes 3 and 9 (collocated, ks 1e6 N/m,
 * ki 200 N/A, kp 1e4 A/m, kd 40 A s/m, capacity 1700 N, no saturation, air gap 1.2 mm);
 * optionally the retainers at nodes 2 and 10 (c 0.75 mm, R_s 25 mm, mu 0.1, Omega_b 0, e 0).
 * No unbalance, no schedule, gravity off: tests add their own.
 */
#ifndef TD_RIG_H
#define TD_RIG_H

#include "touchdown/dofs.h"
#include "touchdown/model.h"

/* The rig's AMB force lag, 1/(2 pi 100 Hz), s. */
#define TD_RIG_TAU (1.0 / (2.0 * TD_PI * 100.0))
/* Retainer clearance, m. */
#define TD_RIG_CLEARANCE 0.75e-3

/* What td_test_build_rig adds besides shaft, discs, journals and AMBs. */
enum { TD_RIG_NO_RETAINERS = 0, TD_RIG_WITH_RETAINERS = 1 };

/* Add the rig's parts to `m` (an empty model from td_model_create) and set its speed (rad/s).
 * amb_tau: the AMB force lag (TD_RIG_TAU for the rig; 0 for the lag-free spring-damper AMB).
 * retainers: TD_RIG_WITH_RETAINERS or TD_RIG_NO_RETAINERS. Fails the calling test on any error. */
void td_test_build_rig(td_model *m, double speed, double amb_tau, int retainers);

/* A new model holding the rig (td_model_create + td_test_build_rig); free with td_model_free. */
td_model *td_test_rig_create(double speed, double amb_tau, int retainers);

#endif
