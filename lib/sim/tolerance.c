/*
 * The integrator's tolerances: the per-component absolute tolerances of every unknown
 * (IDASVtolerances), which the integrator, the restart step and the flight's scaling all read.
 */
#include "sim/sim_internal.h"
#include "touchdown/dofs.h"

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_linalg.h>

#include <math.h>

/*
 * The race speed's absolute tolerance, rad/s. In contact the race is coupled to the node: v_s ties
 * its surface speed R_b Omega_b to the node's tangential velocity, which is controlled to
 * atol freq_max, so the race speed gets that, divided by R_b (a tighter one made the error test fail
 * on the node's noise carried into it). Free, the race has no fast modes and nothing else: the slow
 * scale atol freq_scale / R_b resolves its coast-down to rest under the drag (at freq_max it
 * wandered by 0.05 rad/s about rest).
 */
static double race_speed_atol(const td_sim *s, int k)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    return s->opt.solver.atol * (r->mode != TD_RMODE_FREE ? s->machine.freq_max : s->machine.freq_scale) /
           r->r.bore_radius;
}

int td_sim_races_retolerance(td_sim *s)
{
    double *at = N_VGetArrayPointer(s->solver.atol);
    int k, changed = 0;
    for (k = 0; k < s->dae.nr; k++) {
        int i = s->dae.ov + s->contacts.ret[k].rs;
        double want;
        if (s->contacts.ret[k].rs < 0)
            continue;
        want = race_speed_atol(s, k);
        changed = changed || at[i] != want;
        at[i] = want;
    }
    return changed;
}

/*
 * Per-component absolute tolerances (IDASVtolerances):
 *   q       atol on displacements (m); atol / L_e on the slopes (rad), L_e the mean length of the
 *           shaft elements at the node: a slope error e moves the beam's deflection by ~ e L_e.
 *           Not the loosest scale that argument allows, atol 27 / (4 L_e) (the Hermite shape
 *           functions move the deflection between two nodes by at most (4/27) e L_e), although the
 *           slopes bind most steps of the damped rig cases: the slope error is the bending ringing
 *           an impact excites, and it reaches the contact force. Measured on 0.16.0: with the looser
 *           scale the first impact of cases/rub-damped.cfg misses a converged reference by 0.82 % instead of
 *           0.35 % (tests/validation/test_tolerance.c), where atol x 2 on every component saves as
 *           many steps over the run (27 %) for 0.43 %, and case B's peak force leaves its
 *           spread. (cases/drop.cfg saves a quarter of its steps and its answers stay inside the
 *           scatter of its bounce sequence, which hides the error the first impact above shows.);
 *   v       atol * freq_max, the velocity of a displacement atol in the fastest mode of the shaft.
 *           The shaft has no structural damping, so every impact or force step sets its highest
 *           modes ringing (amplitude ~ impulse / (m omega), undamped for ever). A velocity
 *           tolerance at the slow scale (atol * the bearing frequency) would make IDA resolve that
 *           ringing in v long after it is below atol in q (measured on case A: 6x more steps); at
 *           freq_max the velocity test is no stricter than the displacement test for any mode,
 *           and the displacements, what the run reports, stay controlled to atol + rtol |q|;
 *   w       atol times the axis's control stiffness ki kp (the force error of a position error atol),
 *           or its linear controller's (gain_x); a linear controller's states as lti_tolerances says;
 *   lambda  atol * stiff_scale (N); eta (a velocity correction, m/s): atol * freq_scale. lambda and
 *           eta are algebraic and excluded from the error test, but the Newton convergence test
 *           still weighs them.
 */
/* The races' DOFs: the centre as a displacement, its velocity at the mount's own frequency
 * sqrt(k_m / m_r) (the race rings on its mount, not in the shaft's modes); the angle as the arc
 * atol / R_b at the race surface, and the speed as race_speed_atol says. The shaft's freq_max
 * would be looser (the race's velocities bind a quarter of cases/drop.cfg's steps), but the race's
 * velocity drives its contact's damper: at freq_max (measured on 0.16.0) the first impact of cases/rub-damped.cfg moves
 * away from its converged value (0.35 -> 0.48 %) with no fewer steps, and the drop saves 13 % of its
 * steps (means of five runs), inside the scatter of its bounce sequence. */
static void race_tolerances(td_sim *s, double *at, double *id)
{
    double atol = s->opt.solver.atol;
    int k, i;
    for (k = 0; k < s->dae.nr; k++) {
        const td_sim_retainer *r = &s->contacts.ret[k];
        int dofs[3] = {r->rx, r->ry, r->rs};
        for (i = 0; i < 3; i++) {
            double scale = i == 2 ? 1.0 / r->r.bore_radius : 1.0;
            if (dofs[i] < 0)
                continue;
            at[s->dae.oq + dofs[i]] = atol * scale;
            at[s->dae.ov + dofs[i]] =
                i == 2 ? race_speed_atol(s, k)
                       : atol * fmax(s->machine.freq_scale, sqrt(r->r.race.mount_stiffness / r->r.race.mass));
            id[s->dae.oq + dofs[i]] = id[s->dae.ov + dofs[i]] = 1.0;
        }
    }
}

/* The spin DOF (spin.c): an angle error turns the unbalance force and the orbit with it, so it
 * gets the displacement tolerance over the tightest clearance (the scale of the orbits that
 * matter); the speed that over the bearing period. */
static void spin_tolerances(const td_sim *s, double *at, double *id)
{
    double c = 1e-3;
    int k;
    if (s->machine.spin < 0)
        return;
    for (k = 0; k < s->dae.nr; k++)
        c = fmin(c, s->contacts.ret[k].r.clearance);
    at[s->dae.oq + s->machine.spin] = s->opt.solver.atol / c;
    at[s->dae.ov + s->machine.spin] = s->opt.solver.atol / c * s->machine.freq_scale;
    id[s->dae.oq + s->machine.spin] = id[s->dae.ov + s->machine.spin] =
        s->machine.spin_free ? 1.0 : 0.0; /* a ramp's are algebraic */
}

/*
 * A linear controller's states (x' = A x + B e) have no units of their own: a realisation may
 * scale each one freely. Each gets the excursion that a sensor error of atol at the bearing
 * frequency w = freq_scale drives in it, max over the inputs of |((j w I - A)^-1 B)_i| atol: an
 * error of that size in the state is worth the displacement tolerance at its input, the scale the
 * shorthand's lag state gets in force (atol ki kp). A state no input reaches at w (or a singular
 * j w I - A, a pole exactly at j w) falls back to atol.
 */
static void law_tolerances(const td_sim *s, const td_lti_law *L, double *at, double *id)
{
    size_t n = (size_t)L->n, i, j;
    gsl_matrix_complex *M = gsl_matrix_complex_alloc(n, n);
    gsl_vector_complex *b = gsl_vector_complex_alloc(n), *z = gsl_vector_complex_alloc(n);
    gsl_permutation *p = gsl_permutation_alloc(n);
    double atol = s->opt.solver.atol, w = s->machine.freq_scale, *scale = at + s->dae.ow + L->state;
    int sign, m, ok = M && b && z && p;
    for (i = 0; i < n; i++)
        scale[i] = 0.0;
    for (i = 0; ok && i < n; i++)
        for (j = 0; j < n; j++)
            gsl_matrix_complex_set(M, i, j, gsl_complex_rect(-L->A[i + j * n], i == j ? w : 0.0));
    ok = ok && gsl_linalg_complex_LU_decomp(M, p, &sign) == GSL_SUCCESS;
    for (m = 0; ok && m < L->nin; m++) {
        for (i = 0; i < n; i++)
            gsl_vector_complex_set(b, i, gsl_complex_rect(L->B[i + (size_t)m * n], 0.0));
        ok = gsl_linalg_complex_LU_solve(M, p, b, z) == GSL_SUCCESS;
        for (i = 0; ok && i < n; i++)
            scale[i] = fmax(scale[i], gsl_complex_abs(gsl_vector_complex_get(z, i)));
    }
    for (i = 0; i < n; i++) {
        scale[i] = ok && isfinite(scale[i]) && scale[i] > 0.0 ? atol * scale[i] : atol;
        id[s->dae.ow + L->state + (int)i] = 1.0;
    }
    gsl_matrix_complex_free(M);
    gsl_vector_complex_free(b);
    gsl_vector_complex_free(z);
    gsl_permutation_free(p);
}

static void lti_tolerances(const td_sim *s, double *at, double *id)
{
    int l;
    for (l = 0; l < s->sys->n_laws; l++)
        if (s->sys->laws[l].state >= 0 && s->sys->laws[l].n > 0)
            law_tolerances(s, &s->sys->laws[l], at, id);
}

void td_sim_set_tolerances(td_sim *s)
{
    double *at = N_VGetArrayPointer(s->solver.atol), *id = N_VGetArrayPointer(s->solver.id), atol = s->opt.solver.atol;
    int i;
    int ne = td_model_shaft_element_count(s->model);
    for (i = 0; i < s->sys->ndof; i++) {
        int off, node = td_system_coordinate_node(s->sys, i, &off);
        /* a fixed-interface modal coordinate of a reduced rotor moves the nodes by up to its mode's
         * largest amplitude per unit: its tolerance is the displacement tolerance over that */
        double scale = node < 0 ? 1.0 / td_system_coordinate_amplitude(s->sys, i) : 1.0;
        if (off == TD_DOF_THETA || off == TD_DOF_PHI) {
            /* a slope error e moves the interpolated deflection by about e L_e */
            double len = 0.0;
            int cnt = 0;
            td_shaft_element el;
            if (node > 0 && node - 1 < ne && td_model_get_shaft_element(s->model, node - 1, &el) == TD_OK)
                len += el.length, cnt++;
            if (node < ne && td_model_get_shaft_element(s->model, node, &el) == TD_OK)
                len += el.length, cnt++;
            if (cnt > 0 && len > 0.0)
                scale = cnt / len;
        }
        at[s->dae.oq + i] = atol * scale;
        at[s->dae.ov + i] = atol * scale * s->machine.freq_max;
        id[s->dae.oq + i] = id[s->dae.ov + i] = 1.0;
    }
    for (i = 0; i < s->sys->n_amb_axes; i++) {
        const td_amb_axis *a = &s->sys->amb_axes[i];
        double kc = s->machine.amb_coef[i].gain_x;
        if (a->state >= 0) {
            at[s->dae.ow + a->state] = atol * (kc > 1.0 ? kc : 1.0);
            id[s->dae.ow + a->state] = 1.0;
        }
        if (a->integral >= 0) {
            /* e (m s) moves the force by ki kint e as xs does by ki kp xs: an error of e worth the
             * displacement tolerance in force, or the displacement tolerance over a bearing period */
            double ke = fabs(s->machine.amb_coef[i].cmd_e);
            at[s->dae.ow + a->integral] = kc > 0.0 ? atol * kc / ke : atol / s->machine.freq_scale;
            id[s->dae.ow + a->integral] = 1.0;
        }
    }
    lti_tolerances(s, at, id);
    race_tolerances(s, at, id);
    spin_tolerances(s, at, id);
    for (i = 0; i < s->dae.ns; i++) { /* F_t: a force, algebraic like lambda */
        at[s->dae.of + i] = atol * s->machine.stiff_scale;
        id[s->dae.of + i] = 0.0;
    }
    for (i = 0; i < s->dae.nr; i++) {
        at[s->dae.ol + i] = atol * s->machine.stiff_scale;
        at[s->dae.ou + i] = atol * s->machine.freq_scale;
        id[s->dae.ol + i] = id[s->dae.ou + i] = 0.0;
    }
}

/*
 * The tolerance a restart's first step is sized against (integrator.c restart_step): rtol |q_i| +
 * atol, the displacement tolerance, on every coordinate of q, where IDA's error test weighs the
 * slopes, the race and spin angles and a reduced rotor's modal coordinates with their own absolute
 * tolerances (td_sim_set_tolerances: the slopes' atol / L_e is 6 atol on the paper's rotor). The
 * restart step estimates only the displacements' order-1 error and none of the velocities'; the
 * tighter measure on the angles is its margin. Measured with IDA's own measure in its place (rtol
 * |q_i| + atol_i): every shipped run changes, the first steps after a restart grow by up to
 * sqrt(6), error-test failures go from 90 to 537 (case A) and 65 to 541 (case B), and the peak
 * normal forces of the penalty cases C and D move by 18-32 %, so this measure stays the restart
 * step's.
 */
double td_sim_restart_tolerance(const td_sim *s, int i, const double *y)
{
    return s->opt.solver.rtol * fabs(y[i]) + s->opt.solver.atol;
}
