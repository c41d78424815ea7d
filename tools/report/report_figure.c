/* touchdown report: the report's figure, by gnuplot through the plot tool's script helpers and its
 * template tools/plot/gp/report.gp: normal forces, the rotor's and the races' speeds, the races'
 * temperatures and the orbits at the retainers. */
#include "plot/plot.h"
#include "report/report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The series of the figure; a dataset the file lacks is NULL (its columns NaN). leaps: the
 * leaps' starts (projective leap; empty without a leap made). */
typedef struct figure_data {
    size_t n;
    int nret;
    td_result_array t, speed, fn, race, x, y, temp, leaps;
} figure_data;

/* Read the dataset `id` when it has the shape (n) or (n, nret); else leave *a empty. */
static void series(const td_result *r, td_out_id id, size_t n, int nret, td_result_array *a)
{
    memset(a, 0, sizeof *a);
    if (id == TD_OUT_ID_COUNT || !td_result_has(r, id, NULL) || td_result_read(r, id, NULL, a, NULL) != TD_OK)
        return;
    if (a->dims[0] != n || (nret > 0 && a->dims[1] != (size_t)nret) || a->dims[2] != 1)
        td_result_array_free(a);
}

static double at(const td_result_array *a, size_t i, int k)
{
    return a->v ? a->v[i * (a->rank > 1 ? a->dims[1] : 1) + (size_t)k] : NAN;
}

static void data_free(figure_data *d)
{
    td_result_array_free(&d->t);
    td_result_array_free(&d->speed);
    td_result_array_free(&d->fn);
    td_result_array_free(&d->race);
    td_result_array_free(&d->x);
    td_result_array_free(&d->y);
    td_result_array_free(&d->temp);
    td_result_array_free(&d->leaps);
}

static int data_load(const td_result *r, int nret, figure_data *d)
{
    memset(d, 0, sizeof *d);
    if (td_result_read(r, TD_OUT_TIME, NULL, &d->t, NULL) != TD_OK || d->t.rank != 1)
        return -1;
    d->n = d->t.n;
    d->nret = nret;
    series(r, TD_OUT_SPEED, d->n, 0, &d->speed);
    series(r, TD_OUT_RET_NORMAL_FORCE, d->n, nret, &d->fn);
    series(r, TD_OUT_RET_RACE_SPEED, d->n, nret, &d->race);
    series(r, TD_OUT_RET_X, d->n, nret, &d->x);
    series(r, TD_OUT_RET_Y, d->n, nret, &d->y);
    series(r, td_out_find("race_temperature", TD_OUT_DATASET, TD_OUT_IN_RUN), d->n, nret, &d->temp);
    /* projective leap: where the gaps are, so that no line is drawn across one (as touchdown plot) */
    if (td_result_has(r, TD_OUT_LEAP_TIME, NULL) && td_result_read(r, TD_OUT_LEAP_TIME, NULL, &d->leaps, NULL) != TD_OK)
        return -1;
    return 0;
}

static int write_data(const plot_opts *opt, const figure_data *d, const char *path)
{
    FILE *out = plot_open(opt, "report.dat");
    plot_leaps leaps;
    size_t i;
    int k;
    if (!out)
        return PLOT_FAILED;
    plot_leaps_begin(&leaps, d->leaps.v, d->leaps.n);
    fprintf(out,
            "# the drop report's figure of %s\n# columns: 1 time [s], 2 rotor speed [rad/s], then per retainer "
            "k from 3 + 5k: normal force [N], race speed [rad/s], x [mm], y [mm], race temperature rise [K]\n",
            path);
    for (i = 0; i < d->n; i++) {
        plot_leap_break(out, &leaps, d->t.v, i);
        fprintf(out, "%.12g %.9g", d->t.v[i], at(&d->speed, i, 0));
        for (k = 0; k < d->nret; k++)
            fprintf(out, " %.9g %.9g %.9g %.9g %.9g", at(&d->fn, i, k), at(&d->race, i, k), 1e3 * at(&d->x, i, k),
                    1e3 * at(&d->y, i, k), at(&d->temp, i, k));
        fputc('\n', out);
    }
    return plot_close(out, opt, "report.dat");
}

/* The clearances (mm) into the script as a gnuplot array, and the orbit axes' half width L. */
static void write_clearances(FILE *f, const td_result *r, int nret)
{
    td_result_array c;
    double big = 0.0;
    int k;
    memset(&c, 0, sizeof c);
    if (td_result_read(r, TD_OUT_RETAINER_CLEARANCE, NULL, &c, NULL) != TD_OK || c.n != (size_t)nret)
        td_result_array_free(&c);
    fprintf(f, "array clearance[%d]\n", nret > 0 ? nret : 1);
    for (k = 0; k < nret; k++) {
        double mm = c.v ? 1e3 * c.v[k] : NAN;
        fprintf(f, "clearance[%d] = %.9g\n", k + 1, mm);
        if (mm > big)
            big = mm;
    }
    fprintf(f, "L = %.9g    # mm, half the orbit axes\n", big > 0.0 ? 1.3 * big : 1.0);
    td_result_array_free(&c);
}

int report_figure(const td_result *r, const report *rep, const char *dir, const char *name)
{
    plot_opts opt;
    plot_job job;
    figure_data d;
    FILE *f;
    char title[512];
    int st;
    memset(&opt, 0, sizeof opt);
    opt.dir = dir;
    opt.run = opt.quiet = 1;
    memset(&job, 0, sizeof job);
    job.opt = &opt;
    if (data_load(r, rep->nret, &d)) { /* a run file has /time (td_result_open) */
        fprintf(stderr, "touchdown report: %s: its time series cannot be read\n", rep->path);
        data_free(&d);
        return PLOT_FAILED;
    }
    st = write_data(&opt, &d, rep->path);
    if (st == PLOT_OK && (f = plot_script_begin(&job, name, "the drop report's figure", rep->path, 1400, 1000))) {
        snprintf(title, sizeof title, "%s%s", rep->description[0] ? rep->description : rep->path,
                 rep->complete ? "" : "  [INCOMPLETE: not answers]");
        plot_var_string(f, "case_title", title);
        plot_var_string(f, "data", "report.dat");
        fprintf(f, "nret = %d\nhas_speed = %d\nhas_races = %d\nhas_temperature = %d\n", rep->nret, d.speed.v != NULL,
                rep->nret > 0 && d.race.v != NULL, rep->nret > 0 && d.temp.v != NULL);
        write_clearances(f, r, rep->nret);
        st = plot_script_end(f, &job, name, NULL, plot_tpl_report);
    } else if (st == PLOT_OK) {
        st = PLOT_FAILED;
    }
    data_free(&d);
    return st == PLOT_OK ? plot_run_all(&job) : st;
}
