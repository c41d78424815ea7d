/*
 * touchdown plot: several simulation files overlaid (e.g. constrained against penalty contact):
 *   compare-rN  radial displacement and normal contact force at retainer N against time, one
 *               colour per file, the legend from the file names
 * It reuses the PREFIXretainerN.dat data files written for each file's own figures.
 */
#include "plot/plot.h"

#include <math.h>
#include <string.h>

static double column_max(const plot_sim *s, const double *m, int r)
{
    double v = 0.0;
    size_t i;
    for (i = 0; i < s->n; i++)
        if (m[i * (size_t)s->nret + (size_t)r] > v)
            v = m[i * (size_t)s->nret + (size_t)r];
    return v;
}

/* data, label and slot: the arrays of the files that have retainer r (slot: palette entry). */
static void file_arrays(FILE *out, const plot_file *const *files, const char *const *prefixes, int count, int r,
                        int have)
{
    int i, k;
    fprintf(out, "array data[%d]\narray label[%d]\narray slot[%d]\n", have, have, have);
    for (i = 0, k = 0; i < count; i++) {
        char data[300];
        if (files[i]->sim.nret <= r)
            continue;
        plot_retainer_data_name(data, sizeof data, prefixes[i], r);
        fprintf(out, "data[%d] = ", ++k);
        plot_gp_string(out, data);
        fprintf(out, "; label[%d] = ", k);
        plot_gp_string(out, files[i]->stem);
        fprintf(out, "; slot[%d] = %d\n", k, i % 8 + 1);
    }
}

static int compare_figure(plot_job *job, const plot_file *const *files, const char *const *prefixes, int count, int r)
{
    char name[64], what[200], title[800];
    double t0 = HUGE_VAL, t1 = -HUGE_VAL, rmax = 0.0, fmax_n = 0.0, c = NAN;
    long node = -1;
    int i, have = 0;
    FILE *out;
    for (i = 0; i < count; i++) {
        const plot_sim *s = &files[i]->sim;
        if (s->nret <= r)
            continue;
        have++;
        t0 = fmin(t0, s->t[0]);
        t1 = fmax(t1, s->t[s->n - 1]);
        rmax = fmax(rmax, 1e3 * column_max(s, s->r, r));
        fmax_n = fmax(fmax_n, column_max(s, s->fn, r));
        if (!isfinite(c) && isfinite(s->clearance[r]))
            c = 1e3 * s->clearance[r];
        if (node < 0)
            node = s->ret_nodes[r];
    }
    if (have < 2)
        return PLOT_OK;
    snprintf(name, sizeof name, "compare-r%d", r);
    if (node >= 0)
        snprintf(what, sizeof what, "Radial displacement and normal contact force at retainer %d (node %ld)", r, node);
    else
        snprintf(what, sizeof what, "Radial displacement and normal contact force at retainer %d", r);
    if (!(out = plot_script_begin(job, name, what, "several files", 1000, 760)))
        return PLOT_FAILED;
    fprintf(out, "# files:\n");
    for (i = 0; i < count; i++)
        fprintf(out, "#   %s: %s\n", files[i]->stem, files[i]->title);
    snprintf(title, sizeof title, "%s\n%s", what, files[0]->title);
    for (i = 1; i < count; i++)
        if (strcmp(files[i]->title, files[0]->title)) {
            snprintf(title, sizeof title, "%s\ncomparison of %d runs", what, have);
            break;
        }
    plot_var_string(out, "fig_title", title);
    file_arrays(out, files, prefixes, count, r, have);
    rmax = 1.1 * fmax(isfinite(c) ? c : 0.0, rmax);
    fmax_n *= 1.1;
    if (isfinite(c))
        fprintf(out, "c = %.9g       # radial clearance, mm\n", c);
    else
        fprintf(out, "c = NaN    # the files give no clearance\n");
    fprintf(out, "RMAX = %.6g    # top of the displacement axis, mm\nFMAX = %.6g    # top of the force axis, N\n",
            rmax > 0.0 ? rmax : 1.0, fmax_n > 0.0 ? fmax_n : 1.0);
    fprintf(out, "t0 = %.12g\nt1 = %.12g    # time axis, s\n", t0, t1 > t0 ? t1 : t0 + 1.0);
    return plot_script_end(out, job, name, plot_tpl_palette, plot_tpl_compare);
}

int plot_compare_figures(plot_job *job, const plot_file *const *files, const char *const *prefixes, int count)
{
    int r, nret = 0, i, rc = PLOT_OK;
    for (i = 0; i < count; i++)
        if (files[i]->sim.nret > nret)
            nret = files[i]->sim.nret;
    for (r = 0; r < nret && rc == PLOT_OK; r++)
        if (job->opt->retainer < 0 || job->opt->retainer == r)
            rc = compare_figure(job, files, prefixes, count, r);
    return rc;
}
