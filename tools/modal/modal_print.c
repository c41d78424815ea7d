/* Printing of modal results shared by `touchdown modal` and `touchdown info`. */
#include "modal/modal_print.h"

#include <math.h>

int td_print_modes(FILE *f, const td_modal *modes, int count, int digits)
{
    int i, shown = 0, n = td_modal_mode_count(modes), overdamped = 0;
    fprintf(f, "  %-4s %*s %*s %12s  %-8s  %s\n", "#", digits + 6, "omega_d [rad/s]", digits + 6, "f [Hz]", "zeta",
            "whirl", "log dec");
    for (i = 0; i < n && shown < count; i++) {
        td_mode m;
        td_modal_get_mode(modes, i, &m);
        if (!td_mode_is_vibration(&m)) {
            overdamped++;
            continue;
        }
        shown++;
        fprintf(f, "  %-4d %*.*g %*.*g %12.6g  %-8s  %.6g\n", shown, digits + 6, digits, m.omega_d, digits + 6, digits,
                m.freq_hz, m.zeta, td_whirl_name(m.whirl), td_log_decrement(m.zeta));
    }
    return overdamped;
}

/* What can give the model overdamped roots, for their line's label: its AMBs' force lags and
 * integrators, else (or also) its damping. */
static void overdamped_sources(const td_model *model, char *out, size_t size)
{
    int i, lag = 0, integ = 0;
    for (i = 0; i < td_model_amb_count(model); i++) {
        td_amb a;
        if (td_model_get_amb(model, i, &a) != TD_OK)
            continue;
        lag = lag || a.tau > 0.0;
        integ = integ || a.kint > 0.0;
    }
    snprintf(out, size, "%s%s%s%s", lag ? "AMB force lags, " : "", integ ? "AMB integrators, " : "",
             lag || integ ? "" : "no AMB lag or integrator: ", "damping");
}

void td_print_overdamped(FILE *f, const td_modal *modes, const td_model *model)
{
    int i, n = td_modal_mode_count(modes), any = 0;
    char label[96];
    overdamped_sources(model, label, sizeof label);
    for (i = 0; i < n; i++) {
        td_mode m;
        td_modal_get_mode(modes, i, &m);
        if (td_mode_is_vibration(&m))
            continue;
        if (!any++)
            fprintf(f, "overdamped roots (%s) [1/s]:", label);
        fprintf(f, " %.12g%+.6gi", m.sigma, m.omega_d);
    }
    for (i = 0; i < td_modal_real_count(modes); i++) {
        if (!any++)
            fprintf(f, "overdamped roots (%s) [1/s]:", label);
        fprintf(f, " %.12g", td_modal_real_eigenvalue(modes, i));
    }
    if (any)
        fputc('\n', f);
    if (td_modal_rounding_count(modes) > 0)
        fprintf(f, "zero roots: %d at rounding level (|s| < %.3g 1/s; rigid-body motion no bearing holds), not modes\n",
                td_modal_rounding_count(modes), td_modal_rounding_bound(modes));
}

const char *td_stability_word(const td_modal *modes)
{
    double worst = td_modal_max_real_part(modes), scale = td_modal_rounding_scale(modes);
    if (td_modal_is_unstable(modes))
        return "UNSTABLE";
    if (worst < -TD_MODAL_ROUNDOFF_REAL_PART * scale)
        return "stable";
    return "marginally stable (undamped modes)";
}
