/*
 * plant_probe: writes the linear plant of a case file, through the public API only, for
 * rig_reference.py, which closes the AMB loops and applies the housing's motion itself.
 *
 *   plant_probe CASE OUT [KEY=VALUE ...]      (the KEY=VALUE are case-file overrides, as --set)
 *
 * OUT is the layout tests/validation/control/closed_loop.py reads:
 *   line 1:  ndof naxes omega
 *   naxes lines:  actuator_dof sensor_dof ks ki tau     (x then y of every AMB)
 *   the law line: "pid KP KINT KD 0" (every AMB's own PD/PID, continuous, no derivative filter)
 *   M, K, C, G: ndof rows of ndof numbers each (G per unit speed)
 * followed by the node positions, for the rigid fields R and T the script builds itself, and the
 * loads of the case that are not the housing's (for a forced response with them):
 *   "nodes N" and N axial positions z_i (m);
 *   "retainers K" and K lines "node clearance" (m);
 *   "unbalances K" and K lines "node magnitude phase" (kg m, rad; the magnitudes at t = 0);
 *   "gravity gx gy" (m/s^2, zero when it is off);
 *   "air_gaps A" and A lines "sensor_node air_gap" (m; 0: not given), one per AMB.
 * The housing motion of the case is not written: the script applies it from its own numbers.
 * Only a full (unreduced) rotor without races is written (every DOF is a node's), and every AMB
 * must have the same gains (one law line); anything else exits 1 with the reason.
 */
#include "touchdown/case.h"
#include "touchdown/dofs.h"
#include "touchdown/model.h"
#include "touchdown/system.h"

#include <stdio.h>
#include <stdlib.h>

static int fail(const char *what, const char *why)
{
    fprintf(stderr, "plant_probe: %s: %s\n", what, why);
    return 1;
}

/* The AMB axes and the common law; 0 if every AMB has the gains of the first. */
static int write_axes(FILE *f, const td_model *m, const td_system *sys)
{
    td_amb first, amb;
    int a, j;
    if (td_model_amb_count(m) < 1 || td_model_get_amb(m, 0, &first) != TD_OK)
        return 1;
    fprintf(f, "%d %d %.17g\n", td_system_dof_count(sys), 2 * td_model_amb_count(m), td_model_speed(m));
    for (a = 0; a < td_model_amb_count(m); a++) {
        if (td_model_get_amb(m, a, &amb) != TD_OK || amb.kp != first.kp || amb.kd != first.kd || amb.kint != first.kint)
            return 1;
        for (j = 0; j < 2; j++) {
            int off = j == 0 ? TD_DOF_X : TD_DOF_Y;
            fprintf(f, "%d %d %.17g %.17g %.17g\n", td_system_node_dof(sys, amb.node, off),
                    td_system_node_dof(sys, amb.sensor_node, off), amb.ks, amb.ki, amb.tau);
        }
    }
    fprintf(f, "pid %.17g %.17g %.17g 0\n", first.kp, first.kint, first.kd);
    return 0;
}

/* The retainers (node, clearance), the unbalances (node, magnitude, phase), gravity and the AMBs'
 * air gaps (at their sensor nodes). */
static int write_loads(FILE *f, const td_model *m)
{
    double gx, gy;
    int i;
    fprintf(f, "retainers %d\n", td_model_retainer_count(m));
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        if (td_model_get_retainer(m, i, &r) != TD_OK)
            return 1;
        fprintf(f, "%d %.17g\n", r.node, r.clearance);
    }
    fprintf(f, "unbalances %d\n", td_model_unbalance_count(m));
    for (i = 0; i < td_model_unbalance_count(m); i++) {
        td_unbalance u;
        if (td_model_get_unbalance(m, i, &u) != TD_OK)
            return 1;
        fprintf(f, "%d %.17g %.17g\n", u.node, u.magnitude, u.phase);
    }
    td_model_gravity(m, &gx, &gy);
    fprintf(f, "gravity %.17g %.17g\n", gx, gy);
    fprintf(f, "air_gaps %d\n", td_model_amb_count(m));
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        if (td_model_get_amb(m, i, &a) != TD_OK)
            return 1;
        fprintf(f, "%d %.17g\n", a.sensor_node, a.air_gap);
    }
    return 0;
}

/* M, K, C, G as dense rows, then the node positions, the retainers, unbalances and gravity. */
static int write_matrices(FILE *f, const td_model *m, const td_system *sys)
{
    const td_matrix_kind kinds[4] = {TD_MATRIX_MASS, TD_MATRIX_STIFFNESS, TD_MATRIX_DAMPING, TD_MATRIX_GYROSCOPIC};
    int n = td_system_dof_count(sys), i, j, k;
    double *A = malloc((size_t)n * (size_t)n * sizeof *A);
    if (!A)
        return 1;
    for (k = 0; k < 4; k++) {
        if (td_system_dense(sys, kinds[k], A, NULL) != TD_OK) {
            free(A);
            return 1;
        }
        for (i = 0; i < n; i++) {
            for (j = 0; j < n; j++)
                fprintf(f, "%.17g ", A[i + (size_t)j * n]);
            fprintf(f, "\n");
        }
    }
    free(A);
    fprintf(f, "nodes %d\n", td_model_node_count(m));
    for (i = 0; i < td_model_node_count(m); i++)
        fprintf(f, "%.17g\n", td_model_node_position(m, i));
    return write_loads(f, m);
}

int main(int argc, char **argv)
{
    td_case *c = NULL;
    td_system *sys = NULL;
    td_error err;
    const td_model *m;
    FILE *f;
    int bad;
    if (argc < 3)
        return fail("usage", "plant_probe CASE OUT [KEY=VALUE ...]");
    if (td_case_load(argv[1], (const char *const *)(argv + 3), argc - 3, &c, &err) != TD_OK)
        return fail(argv[1], err.message);
    m = td_case_model(c);
    if (td_system_create(m, &sys, &err) != TD_OK) {
        td_case_free(&c);
        return fail(argv[1], err.message);
    }
    if (td_system_is_reduced(sys) || td_system_dof_count(sys) != TD_DOFS_PER_NODE * td_model_node_count(m)) {
        td_system_free(&sys);
        td_case_free(&c);
        return fail(argv[1], "a reduced rotor or one with races: not every DOF is a node's");
    }
    f = fopen(argv[2], "w");
    bad = !f || write_axes(f, m, sys) || write_matrices(f, m, sys);
    if (f && fclose(f) != 0)
        bad = 1;
    td_system_free(&sys);
    td_case_free(&c);
    return bad ? fail(argv[2], "not written (AMBs with different gains, or a write failed)") : 0;
}
