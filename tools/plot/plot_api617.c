/*
 * touchdown plot: the API 617 report of a modal file (touchdown modal, docs/api617.md):
 *   PREFIXbode   amplitude (the orbit's major semi-axis) and phase of x against speed at every
 *                response node, the peaks with their amplification factors, the operating range
 *   PREFIXpolar  the x response X = |X| e^{i phase} in the complex plane, one curve per node
 * with the data file PREFIXunbalance-response.dat, and the parts' marks on the mode shapes.
 */
#include "plot/plot.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Dataset `id` as a new array (NULL when absent); *n its length, *cols its second dimension (1 for
 * a vector). */
static double *read_any(const td_result *r, td_out_id id, size_t *n, size_t *cols)
{
    td_result_array a;
    if (!td_result_has(r, id, NULL) || td_result_read(r, id, NULL, &a, NULL) != TD_OK)
        return NULL;
    *n = a.rank > 0 ? a.dims[0] : 0;
    *cols = a.rank > 1 ? a.dims[1] : 1;
    return a.v;
}

/* Scalar attribute `id`, NAN when absent. */
static double read_scalar(const td_result *r, td_out_id id)
{
    td_result_array a;
    double v = NAN;
    if (td_result_has(r, id, NULL) && td_result_read(r, id, NULL, &a, NULL) == TD_OK) {
        v = a.n > 0 ? a.v[0] : NAN;
        td_result_array_free(&a);
    }
    return v;
}

static int load_parts(const td_result *r, plot_api617 *a)
{
    static const td_out_id ids[PLOT_PARTS] = {TD_OUT_MODES_DISC_NODES, TD_OUT_MODES_AMB_NODES,
                                              TD_OUT_MODES_SENSOR_NODES, TD_OUT_MODES_RETAINER_NODES};
    int i;
    for (i = 0; i < PLOT_PARTS; i++) {
        size_t n = 0, c;
        a->parts[i] = read_any(r, ids[i], &n, &c);
        a->nparts[i] = a->parts[i] ? (int)n : 0;
    }
    return 0;
}

static int load_peaks(const td_result *r, plot_api617 *a)
{
    size_t n = 0, c = 0;
    a->op_min = read_scalar(r, TD_OUT_PEAK_OPERATING_SPEED_MIN);
    a->op_max = read_scalar(r, TD_OUT_PEAK_OPERATING_SPEED_MAX);
    if (!(a->peak_speed = read_any(r, TD_OUT_PEAK_SPEED, &n, &c)))
        return 0;
    a->np = (int)n;
    a->peak_node = plot_read_vector(r, TD_OUT_PEAK_NODE, NULL, n * c);
    a->peak_amp = plot_read_vector(r, TD_OUT_PEAK_AMPLITUDE, NULL, n * c);
    a->peak_af = plot_read_vector(r, TD_OUT_PEAK_AMPLIFICATION, NULL, n * c);
    return a->peak_node && a->peak_amp && a->peak_af ? 0 : -1;
}

int plot_api617_load(const td_result *r, plot_api617 *a, td_out_id *unreadable)
{
    size_t ns = 0, nn = 0, c = 0;
    memset(a, 0, sizeof *a);
    a->op_min = a->op_max = NAN;
    load_parts(r, a);
    if (!(a->speed = read_any(r, TD_OUT_UR_SPEED, &ns, &c)))
        return 0;
    a->node = read_any(r, TD_OUT_UR_NODE, &nn, &c);
    a->major = plot_read_vector(r, TD_OUT_UR_MAJOR, NULL, ns * nn);
    a->x_amp = plot_read_vector(r, TD_OUT_UR_X_AMP, NULL, ns * nn);
    a->x_phase = plot_read_vector(r, TD_OUT_UR_X_PHASE, NULL, ns * nn);
    a->ns = (int)ns;
    a->nn = (int)nn;
    *unreadable = TD_OUT_UNBALANCE_RESPONSE;
    if (!a->node || !a->major || !a->x_amp || !a->x_phase)
        return -1;
    *unreadable = TD_OUT_RESPONSE_PEAKS;
    return load_peaks(r, a);
}

void plot_api617_free(plot_api617 *a)
{
    int i;
    free(a->speed), free(a->node), free(a->major), free(a->x_amp), free(a->x_phase);
    free(a->peak_node), free(a->peak_speed), free(a->peak_amp), free(a->peak_af);
    for (i = 0; i < PLOT_PARTS; i++)
        free(a->parts[i]);
    memset(a, 0, sizeof *a);
}

void plot_api617_mark_parts(FILE *out, const plot_api617 *a, const double *node_z, int nn)
{
    static const char *const what[PLOT_PARTS] = {"disc", "AMB", "sensor", "retainer"};
    static const char *const color[PLOT_PARTS] = {"#2ca02c", "#1f77b4", "#9467bd", "#d62728"};
    int i, k, tag = 100;
    fprintf(out, "# the parts at their nodes (a dotted line each, its name at the foot of the plot)\n");
    for (i = 0; i < PLOT_PARTS; i++)
        for (k = 0; k < a->nparts[i]; k++) {
            int node = (int)a->parts[i][k];
            double x = node_z && node >= 0 && node < nn ? node_z[node] : (double)node;
            fprintf(out, "set arrow %d from %.9g, graph 0 to %.9g, graph 1 nohead dt 3 lc rgb '%s'\n", tag, x, x,
                    color[i]);
            fprintf(out, "set label %d '%s' at %.9g, graph %.3f center textcolor rgb '%s' font ',8' front\n", tag,
                    what[i], x, 0.03 + 0.035 * i, color[i]);
            tag++;
        }
}

/* One block per response node (gnuplot index j): speed, major semi-axis and |X| in um, phase of x
 * in degrees, Re and Im of X in um. */
static int write_response(const plot_job *job, const plot_file *f, const char *name)
{
    const plot_api617 *a = &f->modal.api;
    FILE *out = plot_open(job->opt, name);
    int j, k;
    if (!out)
        return PLOT_FAILED;
    fprintf(out,
            "# unbalance response from %s: one block (index) per response node\n"
            "# columns: 1 speed [rad/s], 2 major semi-axis [um], 3 |X| [um], 4 phase of x [deg], 5 Re X [um], "
            "6 Im X [um]\n",
            f->path);
    for (j = 0; j < a->nn; j++) {
        fprintf(out, "%s# node %g\n", j ? "\n\n" : "", a->node[j]);
        for (k = 0; k < a->ns; k++) {
            size_t q = (size_t)k * (size_t)a->nn + (size_t)j;
            double amp = 1e6 * a->x_amp[q], ph = a->x_phase[q];
            fprintf(out, "%.12g %.9g %.9g %.9g %.9g %.9g\n", a->speed[k], 1e6 * a->major[q], amp, ph * 180.0 / TD_PI,
                    amp * cos(ph), amp * sin(ph));
        }
    }
    return plot_close(out, job->opt, name);
}

/* The variables both figures read: the data file, one label per node, the title. */
static void common_vars(FILE *out, const plot_file *f, const char *data, const char *what)
{
    const plot_api617 *a = &f->modal.api;
    char title[700];
    int j;
    snprintf(title, sizeof title, "%s\n%s", what, f->title);
    plot_var_string(out, "fig_title", title);
    plot_var_string(out, "data", data);
    fprintf(out, "array label[%d]    # one per response node\n", a->nn);
    for (j = 0; j < a->nn; j++)
        fprintf(out, "label[%d] = 'node %g'\n", j + 1, a->node[j]);
}

static int bode_figure(plot_job *job, const plot_file *f, const char *prefix, const char *data)
{
    const plot_api617 *a = &f->modal.api;
    char name[300];
    FILE *out;
    int i;
    snprintf(name, sizeof name, "%sbode", prefix);
    if (!(out = plot_script_begin(job, name, "Bode plot of the unbalance response", f->path, 1000, 800)))
        return PLOT_FAILED;
    common_vars(out, f, data, "Unbalance response (Bode): the orbit's major semi-axis and the phase of x");
    fprintf(out, "smin = %.12g\nsmax = %.12g\nop_min = %.12g\nop_max = %.12g    # NaN: no operating range\n",
            a->speed[0], a->speed[a->ns - 1] > a->speed[0] ? a->speed[a->ns - 1] : a->speed[0] + 1.0,
            isfinite(a->op_min) ? a->op_min : -1.0, isfinite(a->op_max) ? a->op_max : -1.0);
    for (i = 0; i < a->np; i++)
        if (a->peak_af[i] >= 2.5) /* API 617: the peaks that need a separation margin */
            fprintf(out, "set label %d 'AF %.3g' at %.9g, %.9g center offset 0, 0.8 font ',8' front\n", 200 + i,
                    a->peak_af[i], a->peak_speed[i], 1e6 * a->peak_amp[i]);
    return plot_script_end(out, job, name, plot_tpl_palette, plot_tpl_bode);
}

static int polar_figure(plot_job *job, const plot_file *f, const char *prefix, const char *data)
{
    char name[300];
    FILE *out;
    snprintf(name, sizeof name, "%spolar", prefix);
    if (!(out = plot_script_begin(job, name, "Polar plot of the unbalance response", f->path, 800, 800)))
        return PLOT_FAILED;
    common_vars(out, f, data, "Unbalance response (polar): x = Re(X e^{i W t}) at each response node");
    return plot_script_end(out, job, name, plot_tpl_palette, plot_tpl_polar);
}

int plot_api617_figures(plot_job *job, const plot_file *f, const char *prefix)
{
    char data[300];
    int rc;
    if (f->modal.api.ns < 2 || f->modal.api.nn < 1)
        return PLOT_OK;
    snprintf(data, sizeof data, "%sunbalance-response.dat", prefix);
    if ((rc = write_response(job, f, data)) == PLOT_OK && (rc = bode_figure(job, f, prefix, data)) == PLOT_OK)
        rc = polar_figure(job, f, prefix, data);
    return rc;
}
