/*
 * touchdown plot: figures of one modal file (touchdown modal):
 *   PREFIXcampbell     damped natural frequencies against speed, forward/backward whirl, the 1x
 *                      line, the critical speeds
 *   PREFIXmode-shapes  lateral mode shapes of the first modes along the rotor, the discs, AMBs,
 *                      sensors and retainers marked
 *   PREFIXbode, PREFIXpolar  the swept unbalance response (plot_api617.c)
 * with the data files PREFIXcampbell.dat, PREFIXcritical.dat and PREFIXmode-shapes.dat.
 */
#include "plot/plot.h"
#include "touchdown/dofs.h"
#include "touchdown/modal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define COLOR_FORWARD "#1f77b4"
#define COLOR_BACKWARD "#d62728"
#define COLOR_MIXED "#7f7f7f"

/* The name of a whirl as the modal file holds it (1 forward, -1 backward, 0 mixed). */
static const char *whirl_word(double w)
{
    return td_whirl_name(w > 0.5 ? TD_WHIRL_FORWARD : w < -0.5 ? TD_WHIRL_BACKWARD : TD_WHIRL_MIXED);
}

/* ---- Campbell diagram ---------------------------------------------------------------------- */

/* A branch follows one mode by its shape (td_campbell_compute) except where another mode took it
 * over, which its MAC to the previous point says (below TD_CAMPBELL_MAC_REFINE). Files without
 * /campbell/mac (sorted branches, which jump to another curve where modes cross) are cut where the
 * frequency jumps by more than a quarter. Either way the line is cut where the whirl changes. */
static int joins(double f0, double w0, double f1, double w1, const double *mac)
{
    if (!isfinite(f0) || !isfinite(f1) || w0 != w1)
        return 0;
    return mac ? *mac >= TD_CAMPBELL_MAC_REFINE : fabs(f1 - f0) <= 0.25 * fmax(fabs(f0), fabs(f1));
}

static int write_campbell(const plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_modal *m = &f->modal;
    char name[300];
    FILE *out;
    int j, k;
    snprintf(name, sizeof name, "%scampbell.dat", prefix);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out,
            "# Campbell diagram from %s: one block per branch (one mode, tracked by its shape), cut\n"
            "# by blank lines where the whirl changes or another mode takes the branch over\n"
            "# columns: 1 speed [rad/s], 2 damped natural frequency [Hz], 3 whirl (1 forward, -1 backward, "
            "0 mixed)\n",
            f->path);
    for (j = 0; j < m->nb; j++) {
        fprintf(out, "\n# branch %d\n", j);
        for (k = 0; k < m->ns; k++) {
            size_t q = (size_t)k * (size_t)m->nb + (size_t)j, p = q - (size_t)m->nb;
            double fr = m->freq[q];
            if (k > 0 && !joins(m->freq[p], m->whirl[p], fr, m->whirl[q], m->mac ? &m->mac[q] : NULL))
                fputc('\n', out);
            if (isfinite(fr))
                fprintf(out, "%.12g %.12g %g\n", m->speed[k], fr, m->whirl[q]);
        }
    }
    return plot_close(out, job->opt, name);
}

static int write_critical(const plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_modal *m = &f->modal;
    char name[300];
    FILE *out;
    int i;
    snprintf(name, sizeof name, "%scritical.dat", prefix);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out,
            "# critical speeds from %s\n# columns: 1 speed [rad/s], 2 frequency [Hz], 3 whirl (1 forward, "
            "-1 backward)\n",
            f->path);
    for (i = 0; i < m->ncrit; i++)
        fprintf(out, "%.12g %.12g %g\n", m->crit_speed[i], m->crit_freq[i], m->crit_whirl[i]);
    return plot_close(out, job->opt, name);
}

/* critical_text: the critical speeds as a text list (empty when there are none). */
static void critical_list(FILE *out, const plot_modal *m)
{
    char text[2048];
    size_t len;
    int i;
    if (m->ncrit == 0) {
        fprintf(out, "critical_text = \"\"\n");
        return;
    }
    len = (size_t)snprintf(text, sizeof text, "critical speeds:");
    for (i = 0; i < m->ncrit && len < sizeof text - 80; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "\n%8.1f rad/s = %6.0f rpm, %s", m->crit_speed[i],
                                TD_RPM_FROM_RAD_S(m->crit_speed[i]), whirl_word(m->crit_whirl[i]));
    plot_var_string(out, "critical_text", text);
}

static int campbell_figure(plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_modal *m = &f->modal;
    char name[300], data[300], crit[300];
    double smin = m->speed[0], smax = m->speed[m->ns - 1];
    int has_mixed = 0, k;
    FILE *out;
    snprintf(name, sizeof name, "%scampbell", prefix);
    snprintf(data, sizeof data, "%scampbell.dat", prefix);
    snprintf(crit, sizeof crit, "%scritical.dat", prefix);
    for (k = 0; k < m->ns * m->nb; k++)
        has_mixed |= isfinite(m->freq[k]) && fabs(m->whirl[k]) < 0.5;
    if (!(out = plot_script_begin(job, name, "Campbell diagram", f->path, 1000, 720)))
        return PLOT_FAILED;
    plot_var_string(out, "case_title", f->title);
    plot_var_string(out, "data", data);
    plot_var_string(out, "crit", crit);
    critical_list(out, m);
    fprintf(out, "smin = %.12g\nsmax = %.12g    # speed axis, rad/s\n", smin, smax > smin ? smax : smin + 1.0);
    fprintf(out, "has_mixed = %d    # 1: some points neither forward nor backward whirl\n", has_mixed);
    return plot_script_end(out, job, name, NULL, plot_tpl_campbell);
}

/* ---- mode shapes --------------------------------------------------------------------------- */

/* The lateral shape of mode i as real numbers: the x component (or y when x is under half of y:
 * a mode in the y plane), turned in phase so that its largest entry is real positive, scaled
 * to 1 there. Real parts then show the nodes of the shape. Returns 'x' or 'y'. */
static char real_shape(const plot_modal *m, int i, double *out)
{
    const double *re = m->xr + (size_t)i * (size_t)m->nn, *im = m->xi + (size_t)i * (size_t)m->nn;
    double nx = 0.0, ny = 0.0, best = -1.0, cr = 1.0, ci = 0.0;
    char comp = 'x';
    int k;
    for (k = 0; k < m->nn; k++) {
        size_t q = (size_t)i * (size_t)m->nn + (size_t)k;
        nx += m->xr[q] * m->xr[q] + m->xi[q] * m->xi[q];
        ny += m->yr[q] * m->yr[q] + m->yi[q] * m->yi[q];
    }
    if (sqrt(nx) < 0.5 * sqrt(ny)) {
        re = m->yr + (size_t)i * (size_t)m->nn;
        im = m->yi + (size_t)i * (size_t)m->nn;
        comp = 'y';
    }
    for (k = 0; k < m->nn; k++) {
        double a = hypot(re[k], im[k]);
        if (a > best) {
            best = a;
            cr = re[k];
            ci = im[k];
        }
    }
    /* multiply by conj(v_max) / |v_max|^2: v_max becomes 1 */
    for (k = 0; k < m->nn; k++)
        out[k] = best > 0.0 ? (re[k] * cr + im[k] * ci) / (best * best) : 0.0;
    return comp;
}

static int mode_count(const plot_job *job, const plot_modal *m)
{
    int n = job->opt->modes > 0 ? job->opt->modes : 6;
    if (n > PLOT_MAX_MODES)
        n = PLOT_MAX_MODES;
    return n < m->nm ? n : m->nm;
}

static int write_shapes(const plot_job *job, const plot_file *f, const char *prefix, char *comps)
{
    const plot_modal *m = &f->modal;
    int nm = mode_count(job, m), i, k, rc;
    char name[300];
    double *shape = malloc((size_t)nm * (size_t)m->nn * sizeof *shape);
    FILE *out;
    if (!shape) {
        fprintf(stderr, "touchdown plot: out of memory\n");
        return PLOT_FAILED;
    }
    for (i = 0; i < nm; i++)
        comps[i] = real_shape(m, i, shape + (size_t)i * (size_t)m->nn);
    snprintf(name, sizeof name, "%smode-shapes.dat", prefix);
    if (!(out = plot_open(job->opt, name))) {
        free(shape);
        return PLOT_FAILED;
    }
    fprintf(out,
            "# mode shapes from %s, normalised: largest entry 1 (phase turned to make it real)\n"
            "# columns: 1 %s, then one column per mode (mode 1 in column 2)\n",
            f->path, m->node_z ? "axial position z [m]" : "node number");
    for (k = 0; k < m->nn; k++) {
        fprintf(out, "%.9g", m->node_z ? m->node_z[k] : (double)k);
        for (i = 0; i < nm; i++)
            fprintf(out, " %.9g", shape[(size_t)i * (size_t)m->nn + (size_t)k]);
        fputc('\n', out);
    }
    rc = plot_close(out, job->opt, name);
    free(shape);
    return rc;
}

static int shapes_figure(plot_job *job, const plot_file *f, const char *prefix, const char *comps)
{
    const plot_modal *m = &f->modal;
    int nm = mode_count(job, m), i;
    char name[300], data[300], title[700], speed[64];
    FILE *out;
    snprintf(name, sizeof name, "%smode-shapes", prefix);
    snprintf(data, sizeof data, "%smode-shapes.dat", prefix);
    if (!(out = plot_script_begin(job, name, "Mode shapes", f->path, 1000, 650)))
        return PLOT_FAILED;
    if (isfinite(m->mode_speed))
        snprintf(speed, sizeof speed, " at %.6g rad/s", m->mode_speed);
    else
        speed[0] = '\0';
    snprintf(title, sizeof title, "Lateral mode shapes%s (the first %d modes)\n%s", speed, nm, f->title);
    plot_var_string(out, "fig_title", title);
    plot_var_string(out, "data", data);
    plot_var_string(out, "x_label",
                    m->node_z ? "axial position z [m]" : "node number (the file has no node positions)");
    fprintf(out, "array label[%d]    # one per mode\n", nm);
    for (i = 0; i < nm; i++) {
        char label[160];
        if (m->mode_zeta)
            snprintf(label, sizeof label, "%d: %.4g Hz, %s, zeta %.3g%s", i + 1, m->mode_freq[i],
                     whirl_word(m->mode_whirl[i]), m->mode_zeta[i], comps[i] == 'y' ? " (y)" : "");
        else
            snprintf(label, sizeof label, "%d: %.4g Hz, %s%s", i + 1, m->mode_freq[i], whirl_word(m->mode_whirl[i]),
                     comps[i] == 'y' ? " (y)" : "");
        fprintf(out, "label[%d] = ", i + 1);
        plot_gp_string(out, label);
        fputc('\n', out);
    }
    plot_api617_mark_parts(out, &m->api, m->node_z, m->nn);
    return plot_script_end(out, job, name, plot_tpl_palette, plot_tpl_mode_shapes);
}

int plot_modal_figures(plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_modal *m = &f->modal;
    char comps[PLOT_MAX_MODES];
    int rc = PLOT_OK;
    if (m->ns > 0 && m->nb > 0) {
        if ((rc = write_campbell(job, f, prefix)) == PLOT_OK && (rc = write_critical(job, f, prefix)) == PLOT_OK)
            rc = campbell_figure(job, f, prefix);
    }
    if (rc == PLOT_OK && m->nm > 0 && m->nn > 0 && (rc = write_shapes(job, f, prefix, comps)) == PLOT_OK)
        rc = shapes_figure(job, f, prefix, comps);
    if (rc == PLOT_OK)
        rc = plot_loop_figures(job, f, prefix);
    if (rc == PLOT_OK)
        rc = plot_api617_figures(job, f, prefix);
    return rc;
}
