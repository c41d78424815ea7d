/*
 * touchdown plot: the loop analysis of a modal file (/loop, docs/output-format.md; docs/theory.md,
 * "Sensitivity"): the sensitivity |S_j| per controlled axis with the ISO 14839-3 zone bands
 * (A < 3 <= B < 4 <= C < 5 <= D), the Bode diagram and the Nyquist curve of L_j (circles of
 * radius 1/3, 1/4, 1/5 around -1: the peak sensitivities 3, 4, 5), and the compliance at each
 * AMB axis. Data files PREFIXloop.dat and PREFIXcompliance.dat. A sampled loop's titles say so
 * (its values are at the sample instants, up to the Nyquist frequency).
 */
#include "plot/plot.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A table `id` (+1: its imaginary part) of nf x cols into *re, *im; 0 or -1. */
static int read_table(const td_result *r, td_out_id id, int nf, int *cols, double **re, double **im)
{
    td_result_array a, b;
    if (td_result_read(r, id, NULL, &a, NULL) != TD_OK)
        return -1;
    if (td_result_read(r, (td_out_id)(id + 1), NULL, &b, NULL) != TD_OK || a.rank != 2 || (int)a.dims[0] != nf ||
        b.n != a.n) {
        td_result_array_free(&a);
        td_result_array_free(&b);
        return -1;
    }
    *cols = (int)a.dims[1];
    *re = a.v;
    *im = b.v;
    return 0;
}

int plot_loop_load(const td_result *r, plot_loop *l)
{
    td_result_array f, st;
    memset(l, 0, sizeof *l);
    if (!td_result_has(r, TD_OUT_LOOP, NULL))
        return 0;
    if (td_result_read(r, TD_OUT_LOOP_FREQUENCY, NULL, &f, NULL) != TD_OK)
        return -1;
    l->freq = f.v;
    l->nf = (int)f.n;
    if (td_result_read(r, TD_OUT_LOOP_STABLE, NULL, &st, NULL) != TD_OK)
        return -1;
    l->stable = st.v[0] != 0.0;
    td_result_array_free(&st);
    if (td_result_has(r, TD_OUT_LOOP_SAMPLE_RATE, NULL)) {
        if (td_result_read(r, TD_OUT_LOOP_SAMPLE_RATE, NULL, &st, NULL) != TD_OK)
            return -1;
        l->rate = st.v[0];
        td_result_array_free(&st);
    }
    if (read_table(r, TD_OUT_LOOP_SENSITIVITY_RE, l->nf, &l->nc, &l->s_re, &l->s_im) ||
        read_table(r, TD_OUT_LOOP_COMPLIANCE_RE, l->nf, &l->na, &l->c_re, &l->c_im))
        return -1;
    /* the sensitivity's shape sets the controlled axes: L and the per-axis vectors are read at
     * that count, so that a file whose tables disagree is refused, never read past its end */
    l->l_re = plot_read_vector(r, TD_OUT_LOOP_OPEN_LOOP_RE, NULL, (size_t)l->nf * (size_t)l->nc);
    l->l_im = plot_read_vector(r, TD_OUT_LOOP_OPEN_LOOP_IM, NULL, (size_t)l->nf * (size_t)l->nc);
    l->axis = plot_read_vector(r, TD_OUT_LOOP_AXIS, NULL, (size_t)l->nc);
    l->peak = plot_read_vector(r, TD_OUT_LOOP_SENSITIVITY_PEAK, NULL, (size_t)l->nc);
    l->fp = plot_read_vector(r, TD_OUT_LOOP_SENSITIVITY_PEAK_FREQUENCY, NULL, (size_t)l->nc);
    return l->l_re && l->l_im && l->axis && l->peak && l->fp && l->nf > 1 ? 0 : -1;
}

void plot_loop_free(plot_loop *l)
{
    free(l->freq), free(l->s_re), free(l->s_im), free(l->l_re), free(l->l_im), free(l->c_re), free(l->c_im);
    free(l->axis), free(l->peak), free(l->fp);
    memset(l, 0, sizeof *l);
}

/* PREFIXloop.dat: per axis j (from 0) columns 2+5j |S|, 3+5j Re L, 4+5j Im L, 5+5j |L| dB, 6+5j
 * arg L deg; PREFIXcompliance.dat: per AMB axis a column 2+a |compliance| m/N. */
static int write_data(const plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_loop *l = &f->modal.loop;
    char name[300];
    FILE *out;
    int k, j, rc;
    snprintf(name, sizeof name, "%sloop.dat", prefix);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out,
            "# loop analysis from %s; columns: 1 f [Hz], then per controlled axis j (from 0): 2+5j |S|, "
            "3+5j Re L, 4+5j Im L, 5+5j |L| [dB], 6+5j arg L [deg]\n",
            f->path);
    for (k = 0; k < l->nf; k++) {
        fprintf(out, "%.9g", l->freq[k]);
        for (j = 0; j < l->nc; j++) {
            size_t q = (size_t)k * (size_t)l->nc + (size_t)j;
            fprintf(out, " %.9g %.9g %.9g %.9g %.9g", hypot(l->s_re[q], l->s_im[q]), l->l_re[q], l->l_im[q],
                    20.0 * log10(hypot(l->l_re[q], l->l_im[q])), atan2(l->l_im[q], l->l_re[q]) * 180.0 / TD_PI);
        }
        fputc('\n', out);
    }
    if ((rc = plot_close(out, job->opt, name)) != PLOT_OK)
        return rc;
    snprintf(name, sizeof name, "%scompliance.dat", prefix);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out, "# compliance from %s; columns: 1 f [Hz], then |x/F| [m/N] per AMB axis (2 amb + x 0, y 1)\n",
            f->path);
    for (k = 0; k < l->nf; k++) {
        fprintf(out, "%.9g", l->freq[k]);
        for (j = 0; j < l->na; j++)
            fprintf(
                out, " %.9g",
                hypot(l->c_re[(size_t)k * (size_t)l->na + (size_t)j], l->c_im[(size_t)k * (size_t)l->na + (size_t)j]));
        fputc('\n', out);
    }
    return plot_close(out, job->opt, name);
}

/* The variables every loop figure reads: data file, axis count and labels, title. */
static void loop_vars(FILE *out, const plot_file *f, const char *data, const char *what, int peaks)
{
    const plot_loop *l = &f->modal.loop;
    char title[700], sampled[96] = "";
    int j, n = strcmp(what, "Compliance") ? l->nc : l->na;
    if (l->rate > 0.0)
        snprintf(sampled, sizeof sampled, ", sampled at %.6g Hz (at the samples)", l->rate);
    snprintf(title, sizeof title, "%s%s\n%s", what, sampled, f->title);
    plot_var_string(out, "fig_title", title);
    plot_var_string(out, "data", data);
    fprintf(out, "fmin = %.9g\nfmax = %.9g\narray label[%d]\n", l->freq[0], l->freq[l->nf - 1], n);
    for (j = 0; j < n; j++) {
        char lab[128];
        int a = strcmp(what, "Compliance") ? (int)l->axis[j] : j;
        if (peaks && l->stable)
            snprintf(lab, sizeof lab, "AMB %d %c: peak %.3g at %.4g Hz", a / 2, a % 2 ? 'y' : 'x', l->peak[j],
                     l->fp[j]);
        else
            snprintf(lab, sizeof lab, "AMB %d %c", a / 2, a % 2 ? 'y' : 'x');
        fprintf(out, "label[%d] = ", j + 1);
        plot_gp_string(out, lab);
        fputc('\n', out);
    }
}

/* One figure NAME from its template. */
static int loop_figure(plot_job *job, const plot_file *f, const char *prefix, const char *name, const char *what,
                       const char *data, const char *tpl)
{
    char fig[300], dat[300];
    FILE *out;
    snprintf(fig, sizeof fig, "%s%s", prefix, name);
    snprintf(dat, sizeof dat, "%s%s", prefix, data);
    if (!(out = plot_script_begin(job, fig, what, f->path, 1000, 680)))
        return PLOT_FAILED;
    loop_vars(out, f, dat, what, tpl == plot_tpl_sensitivity);
    fprintf(out, "stable = %d    # 0: the loop is not stable, S undefined\n", f->modal.loop.stable);
    return plot_script_end(out, job, fig, plot_tpl_palette, tpl);
}

int plot_loop_figures(plot_job *job, const plot_file *f, const char *prefix)
{
    int rc;
    if (f->modal.loop.nf < 2)
        return PLOT_OK;
    if ((rc = write_data(job, f, prefix)) != PLOT_OK)
        return rc;
    if (f->modal.loop.stable && (rc = loop_figure(job, f, prefix, "sensitivity", "Sensitivity (ISO 14839-3)",
                                                  "loop.dat", plot_tpl_sensitivity)) != PLOT_OK)
        return rc;
    if ((rc = loop_figure(job, f, prefix, "open-loop", "Open loop L (Bode)", "loop.dat", plot_tpl_open_loop)) !=
            PLOT_OK ||
        (rc = loop_figure(job, f, prefix, "nyquist", "Open loop L (Nyquist)", "loop.dat", plot_tpl_nyquist)) != PLOT_OK)
        return rc;
    if (f->modal.loop.stable)
        rc = loop_figure(job, f, prefix, "compliance", "Compliance", "compliance.dat", plot_tpl_compliance);
    return rc;
}
