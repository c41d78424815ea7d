/*
 * touchdown plot: figures of one simulation file, after the paper's figures 3-8:
 *   PREFIXorbit-rN         orbit at retainer N (x, y in mm, clearance circle, contact samples)
 *   PREFIXradial-force-rN  radial displacement and normal contact force against time, contact shaded
 *   PREFIXamb-forces       AMB forces against time
 *   PREFIXhousing          the housing's acceleration and displacement against time (a run with housing motion)
 * with the data files PREFIXretainerN.dat, PREFIXcontactsN.dat, PREFIXambs.dat and PREFIXhousing.dat.
 */
#include "plot/plot.h"
#include "touchdown/dofs.h"   /* TD_STANDARD_GRAVITY */
#include "touchdown/output.h" /* td_event_kind_name */

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Largest number of schedule markers drawn on the time axes. */
#define MAX_MARKERS 32
/* An isolated contact interval is drawn at least this fraction of the time axis wide, so that a
 * brief impact (microseconds) still shows at the figure's resolution (see write_contacts). */
#define MIN_SHADE_FRACTION 1.5e-3

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
    plot_leaps leaps;
    plot_retainer_data_name(name, sizeof name, prefix, r);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out, "# retainer %d of %s (node %ld, radial clearance %.6g mm)\n", r, f->path, s->ret_nodes[r],
            1e3 * s->clearance[r]);
    fprintf(out, "# columns: 1 time [s], 2 x [mm], 3 y [mm], 4 radial displacement [mm], "
                 "5 normal force [N], 6 in contact (1/0)\n");
    plot_leaps_begin(&leaps, s->leap_time, s->nleap); /* projective leap */
    for (i = 0; i < s->n; i++) {
        plot_leap_break(out, &leaps, s->t, i);
        fprintf(out, "%.12g %.9g %.9g %.9g %.9g %d\n", s->t[i], 1e3 * at(s->x, s, i, r), 1e3 * at(s->y, s, i, r),
                1e3 * at(s->r, s, i, r), at(s->fn, s, i, r), at(s->contact, s, i, r) != 0.0);
    }
    return plot_close(out, job->opt, name);
}

static int is_onset(const plot_event *e, int r)
{
    return e->retainer == r && (!strcmp(e->kind, td_event_kind_name(TD_EVENT_CONTACT_ONSET)) ||
                                !strcmp(e->kind, td_event_kind_name(TD_EVENT_PENALTY_ENTER)));
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
    plot_leaps leaps;
    int a;
    snprintf(name, sizeof name, "%sambs.dat", prefix);
    if (!(out = plot_open(job->opt, name)))
        return PLOT_FAILED;
    fprintf(out, "# AMB forces on the rotor from %s\n# columns: 1 time [s]", f->path);
    for (a = 0; a < s->namb; a++)
        fprintf(out, ", %d Fx AMB %d [N], %d Fy AMB %d [N]", 2 + 2 * a, a, 3 + 2 * a, a);
    fputc('\n', out);
    plot_leaps_begin(&leaps, s->leap_time, s->nleap); /* projective leap */
    for (i = 0; i < s->n; i++) {
        plot_leap_break(out, &leaps, s->t, i);
        fprintf(out, "%.12g", s->t[i]);
        for (a = 0; a < 2 * s->namb; a++)
            fprintf(out, " %.9g", s->amb[i * 2 * (size_t)s->namb + (size_t)a]);
        fputc('\n', out);
    }
    return plot_close(out, job->opt, name);
}

/* ---- figures: variables for the templates tools/plot/gp/NAME.gp -------------------------- */

/* markers = "T1 T2 ...": the scheduled changes (e.g. the unbalance steps), drawn dashed. */
static void schedule_markers(FILE *out, const plot_sim *s)
{
    double last = NAN;
    size_t i;
    int n = 0;
    fprintf(out, "markers = \"");
    for (i = 0; i < s->nev && n < MAX_MARKERS; i++) {
        if (strcmp(s->ev[i].kind, td_event_kind_name(TD_EVENT_SCHEDULE)) || s->ev[i].time == last)
            continue;
        last = s->ev[i].time;
        fprintf(out, n++ ? " %.12g" : "%.12g", last);
    }
    fprintf(out, "\"    # times of the scheduled changes, s\n");
}

/* t0, t1: the samples' span (a single sample gets a small span around it). */
static void time_range(FILE *out, const plot_sim *s)
{
    double t0 = s->t[0], t1 = s->t[s->n - 1];
    if (!(t1 > t0)) {
        t0 -= 1e-3;
        t1 += 1e-3;
    }
    fprintf(out, "t0 = %.12g\nt1 = %.12g    # time axis, s\n", t0, t1);
}

/* what, case_title, data and the clearance c (NaN when the file has none) of retainer r. */
static void retainer_vars(FILE *out, const plot_file *f, const char *what, const char *data, double c)
{
    plot_var_string(out, "what", what);
    plot_var_string(out, "case_title", f->title);
    plot_var_string(out, "data", data);
    if (isfinite(c))
        fprintf(out, "c = %.9g       # radial clearance of the retainer, mm\n", c);
    else
        fprintf(out, "c = NaN    # the file gives no clearance\n");
}

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
    retainer_vars(out, f, what, data, c);
    fprintf(out, "L = %.6g                     # half-width of the axes, mm\n", half > 0.0 ? half : 1.0);
    fprintf(out, "in_contact = %d    # 1: some samples in contact (drawn red)\n", max_of(s->contact, s, r) > 0.0);
    return plot_script_end(out, job, name, NULL, plot_tpl_orbit);
}

static int radial_force_figure(plot_job *job, const plot_file *f, const char *prefix, int r, int intervals)
{
    const plot_sim *s = &f->sim;
    char name[300], data[300], contacts[300], what[200], ret[64];
    double c = 1e3 * s->clearance[r], rmax, fmax_n;
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
    retainer_vars(out, f, what, data, c);
    plot_var_string(out, "contacts", contacts);
    fprintf(out, "intervals = %d    # contact intervals in it\n", intervals);
    fprintf(out,
            "RMAX = %.6g    # top of the displacement axis, mm\n"
            "FMAX = %.6g    # top of the force axis, N\n",
            rmax > 0.0 ? rmax : 1.0, fmax_n > 0.0 ? fmax_n : 1.0);
    time_range(out, s);
    schedule_markers(out, s);
    return plot_script_end(out, job, name, plot_tpl_markers, plot_tpl_radial_force);
}

static int amb_figure(plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_sim *s = &f->sim;
    char name[300], data[300];
    int a;
    FILE *out;
    snprintf(name, sizeof name, "%samb-forces", prefix);
    snprintf(data, sizeof data, "%sambs.dat", prefix);
    if (!(out = plot_script_begin(job, name, "AMB forces on the rotor", f->path, 1000, 160 + 250 * s->namb)))
        return PLOT_FAILED;
    plot_var_string(out, "case_title", f->title);
    plot_var_string(out, "data", data);
    fprintf(out, "amb_names = \"");
    for (a = 0; a < s->namb; a++)
        if (s->amb_nodes[a] >= 0)
            fprintf(out, "%s'AMB %d (node %ld)'", a ? " " : "", a, s->amb_nodes[a]);
        else
            fprintf(out, "%s'AMB %d'", a ? " " : "", a);
    fprintf(out, "\"    # one panel each\n");
    time_range(out, s);
    schedule_markers(out, s);
    return plot_script_end(out, job, name, plot_tpl_markers, plot_tpl_amb_forces);
}

/* housing motion: the housing's acceleration (in g, TD_STANDARD_GRAVITY, the shock standards' unit) and
 * displacement against time, x and y, with a housing body's displacement, from PREFIXhousing.dat. */
static int housing_figure(plot_job *job, const plot_file *f, const char *prefix)
{
    const plot_sim *s = &f->sim;
    char name[300], data[300];
    FILE *out;
    size_t i;
    plot_leaps leaps;
    int still = 1;
    snprintf(name, sizeof name, "%shousing", prefix);
    snprintf(data, sizeof data, "%shousing.dat", prefix);
    if (!(out = plot_open(job->opt, data)))
        return PLOT_FAILED;
    fprintf(out,
            "# the housing's prescribed motion from %s\n# columns: 1 time [s], 2 ax [g], 3 ay [g], 4 x [mm], "
            "5 y [mm] (1 g = %g m/s^2)%s\n",
            f->path, TD_STANDARD_GRAVITY,
            s->housing_body ? ", 6 body x [mm], 7 body y [mm] (relative to the base)" : "");
    plot_leaps_begin(&leaps, s->leap_time, s->nleap); /* projective leap */
    for (i = 0; i < s->n; i++) {
        const double *h = s->housing + 6 * i;
        plot_leap_break(out, &leaps, s->t, i);
        still = still && h[0] == 0.0 && h[1] == 0.0;
        fprintf(out, "%.12g %.9g %.9g %.9g %.9g", s->t[i], h[0] / TD_STANDARD_GRAVITY, h[1] / TD_STANDARD_GRAVITY,
                1e3 * h[2], 1e3 * h[3]);
        if (s->housing_body)
            fprintf(out, " %.9g %.9g", 1e3 * h[4], 1e3 * h[5]);
        fputc('\n', out);
    }
    if (plot_close(out, job->opt, data) != PLOT_OK)
        return PLOT_FAILED;
    if (!(out = plot_script_begin(job, name, "Housing motion", f->path, 1000, 700)))
        return PLOT_FAILED;
    plot_var_string(out, "case_title", f->title);
    plot_var_string(out, "data", data);
    fprintf(out, "body = %d    # 1: the data has a housing body's displacement\n", s->housing_body);
    fprintf(out, "still = %d   # 1: the housing's acceleration is 0 throughout (a body without base motion)\n", still);
    time_range(out, s);
    schedule_markers(out, s);
    return plot_script_end(out, job, name, plot_tpl_markers, plot_tpl_housing);
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
    if (rc == PLOT_OK && s->housing) /* housing motion */
        rc = housing_figure(job, f, prefix);
    return rc;
}
