/*
 * The error of a reduced rotor against the full model, printed by `touchdown modal` and
 * `touchdown info` for a case with a `reduction` group: the vibration modes below the cut-off and
 * the steady unbalance response at the retainer and AMB nodes, each full vs reduced.
 */
#include "modal/modal_print.h"

#include "touchdown/sim.h"

#include <math.h>
#include <stdlib.h>

/* The full model's dense eigen-solve and harmonic LU are O(states^3): the size the simulation
 * still checks for stability at start-up (about a second; the rig refined 8 times), no more. */
#define TD_REDUCTION_COMPARE_MAX_STATES TD_SIM_STABILITY_MAX_STATES

/* Relative difference of b from a (0 when both are 0). */
static double rel_error(double a, double b)
{
    return a != 0.0 ? fabs(b - a) / fabs(a) : fabs(b);
}

/* Every mode of `sys` at `speed` (a dense solve: the comparison is made only for models of at
 * most TD_REDUCTION_COMPARE_MAX_STATES first-order states). */
static td_modal *all_modes(const td_system *sys, double speed, td_error *err)
{
    td_modal *modes = NULL;
    if (td_modal_solve(sys, speed, &modes, err) != TD_OK)
        return NULL;
    return modes;
}

/* Frequency of the i-th vibration mode (NAN past the last). */
static double vibration_hz(const td_modal *modes, int i)
{
    int k, n = td_modal_mode_count(modes), seen = 0;
    for (k = 0; k < n; k++) {
        td_mode m;
        td_modal_get_mode(modes, k, &m);
        if (td_mode_is_vibration(&m) && seen++ == i)
            return m.freq_hz;
    }
    return NAN;
}

/* Full vs reduced frequencies below the cut-off; returns the largest relative error. */
static double print_frequencies(FILE *f, const td_modal *full, const td_modal *red, double cutoff)
{
    double worst = 0.0, a, b;
    int i;
    fprintf(f, "  %-4s %20s %20s %12s\n", "#", "f full [Hz]", "f reduced [Hz]", "rel. error");
    for (i = 0; (a = vibration_hz(full, i)) < cutoff; i++) {
        b = vibration_hz(red, i);
        if (rel_error(a, b) > worst || isnan(b))
            worst = isnan(b) ? INFINITY : rel_error(a, b);
        fprintf(f, "  %-4d %20.12g %20.12g %12.3e\n", i + 1, a, b, rel_error(a, b));
    }
    return worst;
}

/* One node's major semi-axis, full vs reduced; returns the relative error (0 if not computed). */
static double print_orbit(FILE *f, const td_harmonic *hf, const td_harmonic *hr, const char *what, int node)
{
    td_orbit of, orr;
    if (td_harmonic_orbit(hf, node, &of) != TD_OK || td_harmonic_orbit(hr, node, &orr) != TD_OK)
        return 0.0;
    fprintf(f, "  %-12s node %-4d %20.12g %20.12g %12.3e\n", what, node, of.major, orr.major,
            rel_error(of.major, orr.major));
    return rel_error(of.major, orr.major);
}

/* The unbalance response at one speed at the retainer and AMB nodes; returns the largest error. */
static double print_response(FILE *f, const td_model *m, const td_system *full, const td_system *red, double speed,
                             td_error *err)
{
    td_harmonic *hf = NULL, *hr = NULL;
    td_unbalance *u = calloc((size_t)td_model_unbalance_count(m) + 1, sizeof *u);
    double worst = 0.0;
    char what[32];
    int i, n_u = td_model_unbalance_count(m);
    for (i = 0; u && i < n_u; i++)
        td_model_get_unbalance(m, i, &u[i]);
    if (u && td_harmonic_compute(full, speed, u, n_u, &hf, err) == TD_OK &&
        td_harmonic_compute(red, speed, u, n_u, &hr, err) == TD_OK) {
        fprintf(f, "  unbalance response at %.9g rad/s, major semi-axis [m]:\n", speed);
        for (i = 0; i < td_model_retainer_count(m); i++) {
            td_retainer r;
            td_model_get_retainer(m, i, &r);
            snprintf(what, sizeof what, "retainer %d", i);
            worst = fmax(worst, print_orbit(f, hf, hr, what, r.node));
        }
        for (i = 0; i < td_model_amb_count(m); i++) {
            td_amb a;
            td_model_get_amb(m, i, &a);
            snprintf(what, sizeof what, "amb %d", i);
            worst = fmax(worst, print_orbit(f, hf, hr, what, a.sensor_node));
        }
    } else
        fprintf(f, "  unbalance response at %.9g rad/s: %s\n", speed, err->message);
    td_harmonic_free(&hf);
    td_harmonic_free(&hr);
    free(u);
    return worst;
}

/* The full model's system: the case's model without its reduction. */
static td_system *full_system(const td_model *m, td_error *err)
{
    td_model *copy = NULL;
    td_system *sys = NULL;
    if (td_model_clone(m, &copy, err) == TD_OK && td_model_set_reduction(copy, 0.0, err) == TD_OK)
        td_system_create(copy, &sys, err);
    td_model_free(&copy);
    return sys;
}

int td_print_reduction_error(FILE *f, const td_system *red, double speed, const double *response_speeds, int n_speeds)
{
    const td_model *m = td_system_model(red);
    double cutoff = td_model_reduction(m), wf = 0.0, wr = 0.0;
    td_error err;
    td_system *full = full_system(m, &err);
    td_modal *mf = NULL, *mr = NULL;
    int i;
    if (full && td_modal_state_count(full) > TD_REDUCTION_COMPARE_MAX_STATES) {
        fprintf(f,
                "reduction error against the full model: not computed, the full model has %d first-order states "
                "(at most %d are compared; `touchdown modal` of the full case gives its modes)\n",
                td_modal_state_count(full), TD_REDUCTION_COMPARE_MAX_STATES);
        td_system_free(&full);
        return 0;
    }
    if (full) {
        mf = all_modes(full, speed, &err);
        mr = mf ? all_modes(red, speed, &err) : NULL;
    }
    if (!mr) {
        fprintf(stderr, "touchdown: comparing with the full model: %s\n", err.message);
        td_modal_free(&mf);
        td_system_free(&full);
        return 1;
    }
    fprintf(f, "reduction error against the full model (%d DOFs) at %.9g rad/s, modes below %.9g Hz:\n",
            td_system_dof_count(full), speed, cutoff);
    wf = print_frequencies(f, mf, mr, cutoff);
    for (i = 0; i < n_speeds; i++)
        wr = fmax(wr, print_response(f, m, full, red, response_speeds[i], &err));
    if (n_speeds == 0) /* no modal.response_speeds: the case speed */
        wr = print_response(f, m, full, red, speed, &err);
    fprintf(f, "  largest relative error: frequencies %.3e, unbalance response %.3e\n", wf, wr);
    td_modal_free(&mr);
    td_modal_free(&mf);
    td_system_free(&full);
    return 0;
}

void td_print_reduction(FILE *f, const td_system *sys)
{
    int nq = td_system_dof_count(sys), nm = td_system_mode_count(sys), ns = td_system_static_correction_count(sys);
    if (!td_system_is_reduced(sys))
        return;
    fprintf(f, "reduction    Craig-Bampton below %.9g Hz: %d boundary DOFs + %d fixed-interface modes",
            td_model_reduction(td_system_model(sys)), nq - nm - ns - td_model_housing_body_dofs(td_system_model(sys)),
            nm);
    if (nm > 0)
        fprintf(f, " (%.6g..%.6g Hz)", td_system_mode_frequency(sys, 0), td_system_mode_frequency(sys, nm - 1));
    if (ns > 0)
        fprintf(f, " + %d static correction%s of the weight", ns, ns > 1 ? "s" : "");
    fprintf(f, " = %d of %d DOFs\n", nq, td_system_physical_dof_count(sys));
}
