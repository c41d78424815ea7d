/*
 * touchdown plot: figures of one simulation file, after the paper's figures 3-8:
 *   PREFIXorbit-rN         orbit at retainer N (x, y in mm, clearance circle, contact samples)
 *   PREFIXradial-force-rN  radial displacement and normal contact force against time, contact shaded
 *   PREFIXamb-forces       AMB forces against time
 * with the data files PREFIXretainerN.dat, PREFIXcontactsN.dat and PREFIXambs.dat.
 */
#include "plot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Largest number of schedule markers drawn on the time axes. */
#define MAX_MARKERS 32
/* An isolated contact interval is drawn at least this fraction of the time axis wide, so that a
 * brief impact (microseconds) still shows at the figure's resolution (see write_contacts). */
#define MIN_SHADE_FRACTION 1.5e-3

/* Colours shared by the figures (from matplotlib's tab10 palette). */
#define COLOR_ORBIT "#1f77b4"
#define COLOR_CONTACT "#d62728"
#define COLOR_SHADE "#f6b7a9"
#define COLOR_CLEARANCE "#333333"
#define COLOR_MARKER "#888888"

void plot_retainer_data_name(char *buf, size_t n, const char *prefix, int r)
{
    snprintf(buf, n, "%sretainer%d.dat", prefix, r);
}

static double at(const double *m, const plot_sim *s, size_t i, int r)
{
    return m[i * (size_t)s->nret + (size_t)r];
}

static double max_of(const double *m, const plot_sim *s, int r)
{
    double v = 0.0;
    size_t i;
    for (i = 0; i < s->n; i++)
        if (at(m, s, i, r) > v)
            v = at(m, s, i, r);
    return v;
}

/* "retainer 0 (node 2)" */
static void retainer_name(char *buf, size_t n, const plot_sim *s, int r)
{
    if (s->ret_nodes[r] >= 0)
        snprintf(buf, n, "retainer %d (node %ld)", r, s->ret_nodes[r]);
    else
        snprintf(buf, n, "retainer %d", r);
}

/* ---- data files ---------------------------------------------------------------------------- */

static int write_retainer_data(const plot_job *job, const plot_file *f, const char *prefix, int r)
{
    const plot_sim *s = &f->sim;
    char name[300];
    FILE *out;
    size_t i;
    plot_retainer_data_name(name, sizeof name, prefix, r);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out, "# retainer %d of %s (node %ld, radial clearance %.6g mm)\n", r, f->path, s->ret_nodes[r],
            1e3 * s->clearance[r]);
    fprintf(out, "# columns: 1 time [s], 2 x [mm], 3 y [mm], 4 radial displacement [mm], "
                 "5 normal force [N], 6 in contact (1/0)\n");
    for (i = 0; i < s->n; i++)
        fprintf(out, "%.12g %.9g %.9g %.9g %.9g %d\n", s->t[i], 1e3 * at(s->x, s, i, r), 1e3 * at(s->y, s, i, r),
                1e3 * at(s->r, s, i, r), at(s->fn, s, i, r), at(s->contact, s, i, r) != 0.0);
    return plot_close(out, job->opt, name);
}

static int is_onset(const plot_event *e, int r)
{
    return e->retainer == r && (!strcmp(e->kind, "contact_onset") || !strcmp(e->kind, "penalty_enter"));
}

static int by_start(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Contact intervals of retainer r. From the contact state: a run of samples in contact starts
 * at its first sample and ends at the next sample out of contact; event samples carry the state
 * after the event (docs/output-format.md), so both ends are event times. Plus every onset event
 * that no interval covers, as a zero-length interval: an impact after which the shaft left the
 * retainer at once (the sample at the event already shows it free). `iv` gets 2 values per
 * interval (room for n + 1 + nev intervals), sorted by start; returns the count. */
static size_t contact_intervals(const plot_sim *s, int r, double *iv)
{
    size_t i, k, count = 0, from_samples;
    int in = 0;
    for (i = 0; i <= s->n; i++) {
        int c = i < s->n && at(s->contact, s, i, r) != 0.0;
        if (c && !in)
            iv[2 * count] = s->t[i];
        if (!c && in) {
            iv[2 * count + 1] = i < s->n ? s->t[i] : s->t[s->n - 1];
            count++;
        }
        in = c;
    }
    from_samples = count;
    for (i = 0, k = 0; i < s->nev; i++) {
        double t = s->ev[i].time;
        if (!is_onset(&s->ev[i], r))
            continue;
        while (k < from_samples && iv[2 * k + 1] < t)
            k++;
        if (k < from_samples && iv[2 * k] <= t)
            continue; /* inside a sampled interval */
        iv[2 * count] = iv[2 * count + 1] = t;
        count++;
    }
    if (count > from_samples)
        qsort(iv, count, 2 * sizeof *iv, by_start);
    return count;
}

/* Write the intervals with the extent to draw: an isolated brief contact (free for more than
 * the minimum width on both sides) is widened to that width so it shows; contacts in a dense
 * train are drawn as they are, so the shading never covers free flight between them.
 * Returns the count, -1 on failure. */
static int write_contacts(const plot_job *job, const plot_sim *s, const char *prefix, int r)
{
    char name[300];
    FILE *out;
    double span = s->t[s->n - 1] - s->t[0], min_w = MIN_SHADE_FRACTION * span;
    double *iv = malloc(2 * (s->n + 1 + s->nev) * sizeof *iv);
    size_t i, count;
    int rc;
    snprintf(name, sizeof name, "%scontacts%d.dat", prefix, r);
    if (!iv || !(out = plot_open(job->opt, name))) {
        if (!iv)
            fprintf(stderr, "touchdown plot: out of memory\n");
        free(iv);
        return -1;
    }
    count = contact_intervals(s, r, iv);
    fprintf(out,
            "# contact intervals of retainer %d\n# columns: 1 start [s], 2 end [s], 3-4 drawn extent (an "
            "isolated contact widened to %.3g %% of the time axis)\n",
            r, 100.0 * MIN_SHADE_FRACTION);
    for (i = 0; i < count; i++) {
        double on = iv[2 * i], off = iv[2 * i + 1], a = on, b = off;
        int isolated = (i == 0 || on - iv[2 * i - 1] > min_w) && (i + 1 == count || iv[2 * i + 2] - off > min_w);
        if (isolated && off - on < min_w) {
            a = 0.5 * (on + off - min_w);
            b = 0.5 * (on + off + min_w);
        }
        fprintf(out, "%.12g %.12g %.12g %.12g\n", on, off, a, b);
    }
    free(iv);
    rc = plot_close(out, job->opt, name);
    return rc == PLOT_OK ? (int)count : -1;
}

static int write_amb_data(const plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_sim *s = &f->sim;
    char name[300];
    FILE *out;
    size_t i;
    int a;
    snprintf(name, sizeof name, "%sambs.dat", prefix);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out, "# AMB forces on the rotor from %s\n# columns: 1 time [s]", f->path);
    for (a = 0; a < s->namb; a++)
        fprintf(out, ", %d Fx AMB %d [N], %d Fy AMB %d [N]", 2 + 2 * a, a, 3 + 2 * a, a);
    fputc('\n', out);
    for (i = 0; i < s->n; i++) {
        fprintf(out, "%.12g", s->t[i]);
        for (a = 0; a < 2 * s->namb; a++)
            fprintf(out, " %.9g", s->amb[i * 2 * (size_t)s->namb + (size_t)a]);
        fputc('\n', out);
    }
    return plot_close(out, job->opt, name);
}

/* ---- script pieces ------------------------------------------------------------------------- */

/* Dashed vertical lines at the scheduled changes (e.g. the unbalance steps); returns how many. */
static int schedule_markers(FILE *out, const plot_sim *s)
{
    double last = NAN;
    size_t i;
    int n = 0;
    for (i = 0; i < s->nev && n < MAX_MARKERS; i++) {
        if (strcmp(s->ev[i].kind, "schedule") || s->ev[i].time == last)
            continue;
        last = s->ev[i].time;
        fprintf(out, "set arrow %d from %.12g, graph 0 to %.12g, graph 1 nohead dt 2 lw 1 lc rgb '%s' front\n", ++n,
                last, last, COLOR_MARKER);
    }
    return n;
}

/* Multiplot figures: one key for every panel, in one row above the top panel (curves of the
 * other panels get key entries through NaN curves in the top one). */
static void key_above(FILE *out, double panels_top)
{
    fprintf(out, "set key at screen 0.535, %.4g center bottom horizontal samplen 3 width 1\n", panels_top + 0.01);
}

/* Key entry for the schedule markers (a curve that draws nothing). */
static void marker_key(FILE *out, int markers)
{
    if (markers > 0)
        fprintf(out, ", \\\n     NaN with lines dt 2 lw 1 lc rgb '%s' title 'scheduled change'", COLOR_MARKER);
}

static void title2(FILE *out, const char *command, const char *line1, const char *line2)
{
    char buf[1100];
    snprintf(buf, sizeof buf, "%s\n%s", line1, line2);
    fprintf(out, "%s ", command);
    plot_gp_string(out, buf);
}

/* The time axis: the samples' span (a single sample gets a small span around it). */
static void time_range(FILE *out, const plot_sim *s)
{
    double t0 = s->t[0], t1 = s->t[s->n - 1];
    if (!(t1 > t0)) {
        t0 -= 1e-3;
        t1 += 1e-3;
    }
    fprintf(out, "set xrange [%.12g:%.12g]\n", t0, t1);
}

/* ---- figures ------------------------------------------------------------------------------- */

static int orbit_figure(plot_job *job, const plot_file *f, const char *prefix, int r)
{
    const plot_sim *s = &f->sim;
    char name[300], data[300], what[200], ret[64];
    double c = 1e3 * s->clearance[r], half;
    FILE *out;
    snprintf(name, sizeof name, "%sorbit-r%d", prefix, r);
    plot_retainer_data_name(data, sizeof data, prefix, r);
    retainer_name(ret, sizeof ret, s, r);
    snprintf(what, sizeof what, "Orbit of the shaft at %s", ret);
    if (!(out = plot_script_begin(job, name, what, f->path, 760, 820)))
        return PLOT_FAILED;
    half = 1.12 * fmax(isfinite(c) ? c : 0.0, 1e3 * max_of(s->r, s, r));
    if (!(half > 0.0))
        half = 1.0;
    title2(out, "set title", what, f->title);
    fprintf(out,
            "\nset size ratio -1              # equal scales on x and y\n"
            "L = %.6g                     # half-width of the axes, mm\n"
            "set xrange [-L:L]\nset yrange [-L:L]\n"
            "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
            "set key outside below center horizontal\n",
            half);
    if (isfinite(c))
        fprintf(out,
                "c = %.9g                     # radial clearance of the retainer, mm\n"
                "set samples 721\n"
                "plot sample [a=0:2*pi] '+' using (c*cos(a)):(c*sin(a)) with lines lw 2 lc rgb '%s' "
                "title sprintf('clearance %%.3g mm', c), \\\n     ",
                c, COLOR_CLEARANCE);
    else
        fprintf(out, "plot ");
    plot_gp_string(out, data);
    fprintf(out, " using 2:3 with lines lw 0.8 lc rgb '%s' title 'orbit'", COLOR_ORBIT);
    if (max_of(s->contact, s, r) > 0.0) {
        fprintf(out, ", \\\n     ");
        plot_gp_string(out, data);
        fprintf(out, " using ($6 > 0 ? $2 : NaN):3 with points pt 7 ps 0.5 lc rgb '%s' title 'in contact'",
                COLOR_CONTACT);
    }
    fputc('\n', out);
    return plot_close(out, job->opt, name);
}

/* The shaded contact intervals as a plot element (boxes from 0 to `top` in y). */
static void shade(FILE *out, const char *contacts, const char *top, int with_title)
{
    plot_gp_string(out, contacts);
    fprintf(out,
            " using (($3+$4)/2):(%s/2):3:4:(0):(%s) with boxxyerror fs solid 0.55 noborder lc rgb '%s' %s, \\\n"
            "     ",
            top, top, COLOR_SHADE, with_title ? "title 'in contact'" : "notitle");
}

static int radial_force_figure(plot_job *job, const plot_file *f, const char *prefix, int r, int intervals)
{
    const plot_sim *s = &f->sim;
    char name[300], data[300], contacts[300], what[200], ret[64];
    double c = 1e3 * s->clearance[r], rmax, fmax_n;
    int markers;
    FILE *out;
    snprintf(name, sizeof name, "%sradial-force-r%d", prefix, r);
    plot_retainer_data_name(data, sizeof data, prefix, r);
    snprintf(contacts, sizeof contacts, "%scontacts%d.dat", prefix, r);
    retainer_name(ret, sizeof ret, s, r);
    snprintf(what, sizeof what, "Radial displacement and normal contact force at %s", ret);
    if (!(out = plot_script_begin(job, name, what, f->path, 1000, 760)))
        return PLOT_FAILED;
    rmax = 1.1 * fmax(isfinite(c) ? c : 0.0, 1e3 * max_of(s->r, s, r));
    fmax_n = 1.1 * max_of(s->fn, s, r);
    fprintf(out,
            "RMAX = %.6g    # top of the displacement axis, mm\n"
            "FMAX = %.6g    # top of the force axis, N\n",
            rmax > 0.0 ? rmax : 1.0, fmax_n > 0.0 ? fmax_n : 1.0);
    if (isfinite(c))
        fprintf(out, "c = %.9g       # radial clearance, mm\n", c);
    time_range(out, s);
    markers = schedule_markers(out, s);
    title2(out, "set multiplot layout 2,1 margins 0.1,0.97,0.08,0.865 spacing 0,0.025 title", what, f->title);
    fprintf(out, "\n\n# top: radial displacement\n"
                 "set format x ''\nunset xlabel\nset ylabel 'radial displacement [mm]'\nset yrange [0:RMAX]\n");
    key_above(out, 0.865);
    fprintf(out, "plot ");
    if (intervals > 0)
        shade(out, contacts, "RMAX", 1);
    plot_gp_string(out, data);
    fprintf(out, " using 1:4 with lines lw 1 lc rgb '%s' title 'radial displacement'", COLOR_ORBIT);
    if (isfinite(c))
        fprintf(out, ", \\\n     c with lines dt 3 lw 2 lc rgb '%s' title 'clearance'", COLOR_CLEARANCE);
    fprintf(out, ", \\\n     NaN with lines lw 1 lc rgb '%s' title 'normal force'", COLOR_CONTACT);
    marker_key(out, markers);
    fprintf(out, "\n\n# bottom: normal contact force\n"
                 "set format x '%%g'\nset xlabel 'time [s]'\nset ylabel 'normal contact force [N]'\n"
                 "set yrange [0:FMAX]\nunset key\nplot ");
    if (intervals > 0)
        shade(out, contacts, "FMAX", 0);
    plot_gp_string(out, data);
    fprintf(out, " using 1:5 with lines lw 1 lc rgb '%s' notitle\n\nunset multiplot\n", COLOR_CONTACT);
    return plot_close(out, job->opt, name);
}

static int amb_figure(plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_sim *s = &f->sim;
    char name[300], data[300];
    int height = 160 + 250 * s->namb;
    double bottom = 60.0 / height, top = 1.0 - 100.0 / height; /* fixed pixel margins */
    int a, markers;
    FILE *out;
    snprintf(name, sizeof name, "%samb-forces", prefix);
    snprintf(data, sizeof data, "%sambs.dat", prefix);
    if (!(out = plot_script_begin(job, name, "AMB forces on the rotor", f->path, 1000, height)))
        return PLOT_FAILED;
    time_range(out, s);
    markers = schedule_markers(out, s);
    fprintf(out, "set multiplot layout %d,1 margins 0.1,0.97,%.3g,%.3g spacing 0,0.04 title ", s->namb, bottom, top);
    {
        char buf[700];
        snprintf(buf, sizeof buf, "AMB forces on the rotor\n%s", f->title);
        plot_gp_string(out, buf);
    }
    fputc('\n', out);
    key_above(out, top);
    for (a = 0; a < s->namb; a++) {
        int last = a == s->namb - 1;
        fprintf(out, "\n# AMB %d\n", a);
        if (s->amb_nodes[a] >= 0)
            fprintf(out, "set ylabel 'AMB %d (node %ld) force [N]'\n", a, s->amb_nodes[a]);
        else
            fprintf(out, "set ylabel 'AMB %d force [N]'\n", a);
        fprintf(out, last ? "set format x '%%g'\nset xlabel 'time [s]'\n" : "set format x ''\nunset xlabel\n");
        fprintf(out, "plot ");
        plot_gp_string(out, data);
        fprintf(out, " using 1:%d with lines lw 1 lc rgb '%s' title 'Fx', \\\n     ", 2 + 2 * a, COLOR_ORBIT);
        plot_gp_string(out, data);
        fprintf(out, " using 1:%d with lines lw 1 lc rgb '%s' title 'Fy'", 3 + 2 * a, "#ff7f0e");
        if (a == 0)
            marker_key(out, markers);
        fprintf(out, a == 0 ? "\nunset key\n" : "\n");
    }
    fprintf(out, "\nunset multiplot\n");
    return plot_close(out, job->opt, name);
}

int plot_sim_figures(plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_sim *s = &f->sim;
    int r, rc = PLOT_OK;
    int first = job->opt->retainer >= 0 ? job->opt->retainer : 0;
    int last = job->opt->retainer >= 0 ? job->opt->retainer : s->nret - 1;
    if (s->nret == 0 && s->namb == 0) {
        fprintf(stderr, "touchdown plot: %s: the run has no retainers and no AMBs, nothing to plot\n", f->path);
        return PLOT_BAD_INPUT;
    }
    for (r = first; r <= last && rc == PLOT_OK; r++) {
        int intervals;
        if ((rc = write_retainer_data(job, f, prefix, r)) != PLOT_OK)
            break;
        if ((intervals = write_contacts(job, s, prefix, r)) < 0)
            return PLOT_FAILED;
        if ((rc = orbit_figure(job, f, prefix, r)) == PLOT_OK)
            rc = radial_force_figure(job, f, prefix, r, intervals);
    }
    if (rc == PLOT_OK && s->namb > 0 && (rc = write_amb_data(job, f, prefix)) == PLOT_OK)
        rc = amb_figure(job, f, prefix);
    return rc;
}
