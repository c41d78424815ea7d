/*
 * touchdown plot: figures of one sweep table (touchdown sweep):
 *   PREFIXsweep-QUANTITY  a summary quantity (--quantity, default peak_housing_force) against the
 *                         x key (--x), one line per value of the other swept keys
 *   PREFIXregime-map      each point's regime (td_run_summary_regime: free, rub, bounce, backward
 *                         whirl, failed) as a coloured tile over the x key and the y key (--y)
 *   PREFIXbifurcation     the once-per-revolution section radii of every point against the x key,
 *                         the clearance dashed: the classic bifurcation diagram
 * with the data files of the same names (.dat).
 */
#include "plot/plot.h"

#include "touchdown/run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The regimes' colours, by td_regime: failed, free, rub, bounce, backward whirl. */
static const char *const regime_color[TD_REGIME_COUNT] = {"#7f7f7f", "#2ca02c", "#ff7f0e", "#1f77b4", "#d62728"};

/* Points grouped by the values of the keys other than x, each group in x order. */
typedef struct sweep_order {
    size_t *index; /* n: the points, group by group, each by increasing x */
    size_t *start; /* ngroups + 1: group g is index[start[g] .. start[g + 1]) */
    char **label;  /* ngroups: "KEY=VALUE, ..." of the other keys ("" without them) */
    int *group;    /* n: the group of each point */
    size_t ngroups;
} sweep_order;

typedef struct order_item {
    size_t group, point;
    double x;
} order_item;

static int by_group_then_x(const void *a, const void *b)
{
    const order_item *p = a, *q = b;
    if (p->group != q->group)
        return p->group < q->group ? -1 : 1;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    return p->point < q->point ? -1 : p->point > q->point;
}

/* "KEY=VALUE, ..." of point p over every key but x and the keys zipped with it (which move with
 * x along a line), into buf. */
static void group_label(const plot_sweep *s, int x, size_t p, char *buf, size_t n)
{
    size_t len = 0;
    int k;
    buf[0] = '\0';
    for (k = 0; k < s->nkeys && len < n; k++)
        if (s->axis[k] != s->axis[x])
            len += (size_t)snprintf(buf + len, n - len, "%s%s=%s", len ? ", " : "", s->key[k], s->text[k][p]);
}

static void order_free(sweep_order *o)
{
    size_t g;
    for (g = 0; o->label && g < o->ngroups; g++)
        free(o->label[g]);
    free(o->label);
    free(o->index);
    free(o->start);
    free(o->group);
    memset(o, 0, sizeof *o);
}

/* The group of every point: the first point with the same label founds it. */
static int assign_groups(const plot_sweep *s, int x, sweep_order *o)
{
    char buf[1024];
    size_t p, g;
    for (p = 0; p < s->n; p++) {
        group_label(s, x, p, buf, sizeof buf);
        for (g = 0; g < o->ngroups && strcmp(o->label[g], buf); g++)
            ;
        if (g == o->ngroups) {
            if (!(o->label[g] = malloc(strlen(buf) + 1)))
                return -1;
            strcpy(o->label[g], buf);
            o->ngroups++;
        }
        o->group[p] = (int)g;
    }
    return 0;
}

static int order_points(const plot_sweep *s, int x, sweep_order *o)
{
    order_item *it = malloc((s->n + 1) * sizeof *it);
    size_t p, g;
    memset(o, 0, sizeof *o);
    o->index = malloc((s->n + 1) * sizeof *o->index);
    o->start = calloc(s->n + 2, sizeof *o->start);
    o->label = calloc(s->n + 1, sizeof *o->label);
    o->group = malloc((s->n + 1) * sizeof *o->group);
    if (!it || !o->index || !o->start || !o->label || !o->group || assign_groups(s, x, o) != 0) {
        free(it);
        order_free(o);
        return -1;
    }
    for (p = 0; p < s->n; p++) {
        it[p].group = (size_t)o->group[p];
        it[p].point = p;
        it[p].x = s->value[x][p];
    }
    qsort(it, s->n, sizeof *it, by_group_then_x);
    for (p = 0; p < s->n; p++) {
        o->index[p] = it[p].point;
        o->start[it[p].group + 1]++;
    }
    for (g = 0; g < o->ngroups; g++)
        o->start[g + 1] += o->start[g];
    free(it);
    return 0;
}

/* ---- keys and columns ----------------------------------------------------------------------- */

static int key_index(const plot_sweep *s, const char *name)
{
    int k;
    for (k = 0; k < s->nkeys; k++)
        if (!strcmp(s->key[k], name))
            return k;
    return -1;
}

/* The x key: --x, else "speed" when swept, else the first numeric key; -1 with a line printed. */
static int pick_x(const plot_opts *opt, const plot_file *f)
{
    const plot_sweep *s = &f->sweep;
    int k = opt->xkey ? key_index(s, opt->xkey) : key_index(s, "speed");
    if (opt->xkey && (k < 0 || !s->numeric[k])) {
        fprintf(stderr, "touchdown plot: %s: --x '%s' is not a numeric swept key of the table\n", f->path, opt->xkey);
        return -1;
    }
    for (k = k >= 0 && s->numeric[k] ? k : 0; k < s->nkeys && !s->numeric[k]; k++)
        ;
    if (k >= s->nkeys) {
        fprintf(stderr, "touchdown plot: %s: no swept key has numeric values to plot against\n", f->path);
        return -1;
    }
    return k;
}

/* The regime map's y key: --y, else the first other numeric key; -1: none (one row of tiles),
 * -2 with a line printed for a bad --y. */
static int pick_y(const plot_opts *opt, const plot_file *f, int x)
{
    const plot_sweep *s = &f->sweep;
    int k;
    if (opt->ykey) {
        k = key_index(s, opt->ykey);
        if (k < 0 || !s->numeric[k] || s->axis[k] == s->axis[x]) {
            fprintf(stderr, "touchdown plot: %s: --y '%s' is not a numeric swept key of the table off the x axis\n",
                    f->path, opt->ykey);
            return -2;
        }
        return k;
    }
    for (k = 0; k < s->nkeys; k++)
        if (s->axis[k] != s->axis[x] && s->numeric[k])
            return k;
    return -1;
}

/* The axes' scales for the figure's template: logx, and logy where the figure takes --log-y. */
static void axis_scales(FILE *out, const plot_opts *opt, int takes_log_y)
{
    fprintf(out, "logx = %d\nlogy = %d\n", opt->log_x, takes_log_y && opt->log_y);
}

/* The numeric column `name` of the table and its units; -1 with a line printed that lists the
 * columns it could plot. */
static int read_quantity(const plot_file *f, const char *name, td_result_array *q, char *units, size_t n)
{
    td_result *r = NULL;
    char columns[1024] = "";
    int ok;
    memset(q, 0, sizeof *q); /* freed below whether or not it was read */
    ok = td_result_open(f->path, &r, NULL) == TD_OK && plot_sweep_read_column(r, name, f->sweep.n, q) == 0;
    snprintf(units, n, "%s", ok ? q->units : "");
    if (!ok && r)
        plot_sweep_columns(r, f->sweep.n, columns, sizeof columns);
    td_result_free(&r);
    if (!ok) {
        td_result_array_free(q);
        fprintf(stderr, "touchdown plot: %s: --quantity '%s' is not a numeric column of the sweep table (it has: %s)\n",
                f->path, name, columns);
        return -1;
    }
    return 0;
}

/* titles[i] = the groups' labels, as a gnuplot array. */
static void title_array(FILE *out, const sweep_order *o, const size_t *keep, size_t nkeep)
{
    size_t i;
    fprintf(out, "ngroups = %lu\narray titles[%lu]\n", (unsigned long)nkeep, (unsigned long)(nkeep ? nkeep : 1));
    for (i = 0; i < nkeep; i++) {
        fprintf(out, "titles[%lu] = ", (unsigned long)(i + 1));
        plot_gp_string(out, o->label[keep[i]]);
        fputc('\n', out);
    }
}

/* ---- quantity against the x key ------------------------------------------------------------- */

/* 1 if point p has a value of the quantity to draw: it ran to its end and the value is defined. */
static int drawn(const plot_sweep *s, const td_result_array *q, size_t p)
{
    return !s->failed[p] && isfinite(q->v[p]);
}

/* Group g's line: its points in x order, a blank line (a gap in the line) where a point has no
 * value, so that a line never bridges a failed or undefined point. */
static void write_quantity_group(FILE *out, const plot_sweep *s, int x, const sweep_order *o, size_t g,
                                 const td_result_array *q)
{
    size_t i, p;
    int gap = 0;
    for (i = o->start[g]; i < o->start[g + 1]; i++) {
        p = o->index[i];
        if (!drawn(s, q, p)) {
            gap = 1;
            continue;
        }
        fprintf(out, "%s%.12g %.12g %lu\n", gap ? "\n" : "", s->value[x][p], q->v[p], (unsigned long)p);
        gap = 0;
    }
}

/* The last block: the x of every failed or not-run point, marked at the foot of the figure. */
static size_t write_failed_marks(FILE *out, const plot_sweep *s, int x, int first)
{
    size_t p, n = 0;
    for (p = 0; p < s->n; p++)
        if (s->failed[p]) {
            if (n++ == 0)
                fprintf(out, "%s# failed or not run: columns 1 %s, 2 point\n", first ? "" : "\n\n", s->key[x]);
            fprintf(out, "%.12g %lu\n", s->value[x][p], (unsigned long)p);
        }
    return n;
}

static int write_quantity(const plot_job *job, const plot_file *f, const char *name, int x, const sweep_order *o,
                          const td_result_array *q, const char *qname, size_t *keep, size_t *nkeep, size_t *nfailed)
{
    const plot_sweep *s = &f->sweep;
    FILE *out = plot_open(job->opt, name);
    size_t g, i;
    if (!out)
        return PLOT_FAILED;
    fprintf(out, "# %s against %s from %s: one block per value of the other swept keys (gnuplot index)\n", qname,
            s->key[x], f->path);
    fprintf(out, "# columns: 1 %s, 2 %s, 3 point; a blank line where a point has no value\n", s->key[x], qname);
    *nkeep = 0;
    for (g = 0; g < o->ngroups; g++) {
        size_t shown = 0;
        for (i = o->start[g]; i < o->start[g + 1]; i++)
            shown += drawn(s, q, o->index[i]) != 0;
        if (!shown) /* a line without a point would make gnuplot warn */
            continue;
        fprintf(out, "%s# %s\n", *nkeep ? "\n\n" : "", o->label[g]);
        keep[(*nkeep)++] = g;
        write_quantity_group(out, s, x, o, g, q);
    }
    *nfailed = *nkeep ? write_failed_marks(out, s, x, 0) : 0;
    return plot_close(out, job->opt, name);
}

/* One line on stderr for the points of the table that ran without a value of `qname` (e.g. no
 * contact: no first-contact time); the failed ones are told once for every figure. */
static void report_undefined(const plot_file *f, const td_result_array *q, const char *qname)
{
    size_t p, ran = 0, none = 0;
    for (p = 0; p < f->sweep.n; p++)
        if (!f->sweep.failed[p]) {
            ran++;
            none += !isfinite(q->v[p]);
        }
    if (none)
        fprintf(stderr,
                "touchdown plot: %s: %s is undefined at %lu of the %lu points that ran (e.g. no contact): "
                "left out\n",
                f->path, qname, (unsigned long)none, (unsigned long)ran);
}

static int quantity_figure(plot_job *job, const plot_file *f, const char *prefix, int x, const sweep_order *o)
{
    const char *qname = job->opt->quantity ? job->opt->quantity : td_out_name(TD_OUT_SWEEP_PEAK_HOUSING_FORCE);
    char name[300], data[320], units[sizeof((td_result_array *)0)->units], label[256];
    size_t *keep = malloc((o->ngroups + 1) * sizeof *keep), nkeep = 0, nfailed = 0;
    td_result_array q;
    FILE *out;
    int rc = PLOT_FAILED;
    if (!keep)
        return PLOT_FAILED;
    if (read_quantity(f, qname, &q, units, sizeof units) != 0) {
        free(keep);
        return PLOT_BAD_INPUT;
    }
    report_undefined(f, &q, qname);
    snprintf(name, sizeof name, "%ssweep-%s", prefix, qname);
    snprintf(data, sizeof data, "%s.dat", name);
    snprintf(label, sizeof label, units[0] && strcmp(units, "-") ? "%s [%s]" : "%s", qname, units);
    if (write_quantity(job, f, data, x, o, &q, qname, keep, &nkeep, &nfailed) == PLOT_OK && nkeep > 0 &&
        (out = plot_script_begin(job, name, "summary quantity against a swept key", f->path, 1000, 680))) {
        plot_var_string(out, "case_title", f->title);
        plot_var_string(out, "data", data);
        plot_var_string(out, "xlabel", f->sweep.key[x]);
        plot_var_string(out, "ylabel", label);
        axis_scales(out, job->opt, 1);
        title_array(out, o, keep, nkeep);
        fprintf(out, "nfailed = %lu    # failed or not-run points, marked at the foot (the last block)\n",
                (unsigned long)nfailed);
        rc = plot_script_end(out, job, name, NULL, plot_tpl_sweep_quantity);
    } else if (nkeep == 0) { /* every point failed, say: no figure, not an error */
        if (!job->opt->quiet)
            printf("no figure of %s: no point of %s has a value of it\n", qname, f->path);
        rc = PLOT_OK;
    }
    td_result_array_free(&q);
    free(keep);
    return rc;
}

/* ---- regime map ----------------------------------------------------------------------------- */

/* The point halfway between a and b along the axis: the mean, or on a log axis the geometric mean. */
static double halfway(double a, double b, int log_axis)
{
    return log_axis ? sqrt(a * b) : 0.5 * (a + b);
}

/* A tile's edges around `at`: halfway to the next value of v (n of them) on either side, so that
 * tiles of unevenly spaced values meet; the other side's half gap, mirrored, where there is no
 * neighbour. On a log axis the values are > 0 (plot_sweep_figures checks) and halfway is along
 * the log. */
static void tile_edges(const double *v, size_t n, double at, int log_axis, double *lo, double *hi)
{
    double below = -HUGE_VAL, above = HUGE_VAL, w;
    size_t i;
    for (i = 0; i < n; i++) {
        if (isfinite(v[i]) && v[i] < at && v[i] > below)
            below = v[i];
        if (isfinite(v[i]) && v[i] > at && v[i] < above)
            above = v[i];
    }
    w = at != 0.0 ? 0.05 * fabs(at) : 0.5; /* a single value: a narrow tile */
    *lo = isfinite(below) ? halfway(at, below, log_axis) : at - w;
    *hi = isfinite(above) ? halfway(at, above, log_axis) : at + w;
    if (!isfinite(below) && isfinite(above)) /* the first value: as wide below as above */
        *lo = log_axis ? at * at / *hi : 2.0 * at - *hi;
    if (!isfinite(above) && isfinite(below)) /* the last */
        *hi = log_axis ? at * at / *lo : 2.0 * at - *lo;
}

static int write_regimes(const plot_job *job, const plot_file *f, const char *name, int x, int y, int *present)
{
    const plot_sweep *s = &f->sweep;
    FILE *out = plot_open(job->opt, name);
    size_t p;
    if (!out)
        return PLOT_FAILED;
    fprintf(out,
            "# regime of every point of %s (td_run_summary_regime, docs/output-format.md)\n"
            "# columns: 1 %s, 2 %s, 3-4 the tile's left and right edges, 5-6 its bottom and top edges (halfway\n"
            "# to the neighbouring values), 7 regime (0 failed, 1 free, 2 rub, 3 bounce, 4 backward whirl), 8 point\n",
            f->path, s->key[x], y >= 0 ? s->key[y] : "(none: 0)");
    for (p = 0; p < s->n; p++) {
        int r = s->regime[p] >= 0 ? s->regime[p] : TD_REGIME_FAILED;
        double yv = y >= 0 ? s->value[y][p] : 0.0, x0, x1, y0 = -0.5, y1 = 0.5;
        present[r] = 1;
        tile_edges(s->value[x], s->n, s->value[x][p], job->opt->log_x, &x0, &x1);
        if (y >= 0)
            tile_edges(s->value[y], s->n, yv, job->opt->log_y, &y0, &y1);
        fprintf(out, "%.12g %.12g %.12g %.12g %.12g %.12g %d %lu\n", s->value[x][p], yv, x0, x1, y0, y1, r,
                (unsigned long)p);
    }
    return plot_close(out, job->opt, name);
}

/* The regimes present, as gnuplot arrays of their codes, names and colours. */
static void regime_arrays(FILE *out, const int *present)
{
    int r, n = 0, i = 0;
    for (r = 0; r < TD_REGIME_COUNT; r++)
        n += present[r];
    fprintf(out, "nregimes = %d\narray codes[%d]\narray names[%d]\narray colors[%d]\n", n, n, n, n);
    for (r = 0; r < TD_REGIME_COUNT; r++)
        if (present[r]) {
            i++;
            fprintf(out, "codes[%d] = %d; names[%d] = \"%s\"; colors[%d] = \"%s\"\n", i, r, i,
                    td_regime_name((td_regime)r), i, regime_color[r]);
        }
}

static int regime_figure(plot_job *job, const plot_file *f, const char *prefix, int x, int y)
{
    char name[300], data[320];
    int present[TD_REGIME_COUNT] = {0};
    FILE *out;
    snprintf(name, sizeof name, "%sregime-map", prefix);
    snprintf(data, sizeof data, "%s.dat", name);
    if (write_regimes(job, f, data, x, y, present) != PLOT_OK)
        return PLOT_FAILED;
    if (!(out = plot_script_begin(job, name, "regime map", f->path, 1000, 680)))
        return PLOT_FAILED;
    plot_var_string(out, "case_title", f->title);
    plot_var_string(out, "data", data);
    plot_var_string(out, "xlabel", f->sweep.key[x]);
    plot_var_string(out, "ylabel", y >= 0 ? f->sweep.key[y] : "");
    fprintf(out, "has_y = %d    # 0: one swept key, a single row of tiles\n", y >= 0);
    axis_scales(out, job->opt, y >= 0);
    regime_arrays(out, present);
    return plot_script_end(out, job, name, NULL, plot_tpl_regime_map);
}

/* ---- bifurcation diagram -------------------------------------------------------------------- */

/* Group g's section radii (mm) against x, one line per radius; the number written. */
static size_t write_section_group(FILE *out, const plot_sweep *s, int x, const sweep_order *o, size_t g)
{
    size_t i, j, count = 0;
    for (i = o->start[g]; i < o->start[g + 1]; i++) {
        size_t p = o->index[i];
        if (s->failed[p]) /* no answers, its section included */
            continue;
        for (j = 0; j < s->m; j++) {
            double r = s->section[p * s->m + j];
            if (isfinite(r)) {
                fprintf(out, "%.12g %.12g %lu\n", s->value[x][p], 1e3 * r, (unsigned long)p);
                count++;
            }
        }
    }
    return count;
}

/* Section radii of group g that are numbers. */
static size_t section_samples(const plot_sweep *s, const sweep_order *o, size_t g)
{
    size_t i, j, count = 0;
    for (i = o->start[g]; i < o->start[g + 1]; i++)
        for (j = 0; !s->failed[o->index[i]] && j < s->m; j++)
            count += isfinite(s->section[o->index[i] * s->m + j]) != 0;
    return count;
}

static int write_sections(const plot_job *job, const plot_file *f, const char *name, int x, const sweep_order *o,
                          size_t *keep, size_t *nkeep)
{
    const plot_sweep *s = &f->sweep;
    FILE *out = plot_open(job->opt, name);
    size_t g;
    if (!out)
        return PLOT_FAILED;
    fprintf(out,
            "# once-per-revolution section of %s: the retainer node's radius each time the spin angle passes\n"
            "# a multiple of 2 pi, after the transient; one block per value of the other swept keys\n"
            "# columns: 1 %s, 2 radius [mm], 3 point\n",
            f->path, s->key[x]);
    *nkeep = 0;
    for (g = 0; g < o->ngroups; g++) {
        if (section_samples(s, o, g) == 0) /* an empty block would make gnuplot warn */
            continue;
        fprintf(out, "%s# %s\n", *nkeep ? "\n\n" : "", o->label[g]);
        write_section_group(out, s, x, o, g);
        keep[(*nkeep)++] = g;
    }
    return plot_close(out, job->opt, name);
}

/* The clearance (mm) at the points of group g, in x order; the number written. */
static int write_clearance(const plot_job *job, const plot_file *f, const char *name, int x, const sweep_order *o,
                           size_t g, size_t *count)
{
    const plot_sweep *s = &f->sweep;
    FILE *out = plot_open(job->opt, name);
    size_t i;
    if (!out)
        return PLOT_FAILED;
    fprintf(out,
            "# radial clearance of the sampled retainer at the points of '%s'\n# columns: 1 %s, 2 clearance [mm]\n",
            o->label[g], s->key[x]);
    *count = 0;
    for (i = o->start[g]; i < o->start[g + 1]; i++)
        if (isfinite(s->clearance[o->index[i]])) {
            fprintf(out, "%.12g %.12g\n", s->value[x][o->index[i]], 1e3 * s->clearance[o->index[i]]);
            (*count)++;
        }
    return plot_close(out, job->opt, name);
}

/* One line on stderr when points that ran crossed their section fewer than
 * TD_RUN_SECTION_MIN_CROSSINGS times after the transient: their radii cannot tell their orbit. */
static void report_few_crossings(const plot_file *f)
{
    const plot_sweep *s = &f->sweep;
    size_t p, few = 0, ran = 0;
    double fewest = HUGE_VAL;
    for (p = 0; p < s->n; p++) {
        if (s->failed[p] || !(s->section_count[p] > 0.0)) /* no crossing: nothing drawn */
            continue;
        ran++;
        if (td_run_section_too_few(s->section_count[p])) {
            few++;
            fewest = fmin(fewest, s->section_count[p]);
        }
    }
    if (few)
        fprintf(stderr,
                "touchdown plot: %s: bifurcation diagram: %lu of the %lu points that ran crossed the section fewer "
                "than %d times after the transient (fewest %.0f): too few to tell their orbit\n",
                f->path, (unsigned long)few, (unsigned long)ran, TD_RUN_SECTION_MIN_CROSSINGS, fewest);
}

static int bifurcation_figure(plot_job *job, const plot_file *f, const char *prefix, int x, const sweep_order *o)
{
    char name[300], data[320], clear[320];
    size_t *keep = malloc((o->ngroups + 1) * sizeof *keep), nkeep = 0, nclear = 0;
    FILE *out = NULL;
    int rc = keep ? PLOT_OK : PLOT_FAILED;
    snprintf(name, sizeof name, "%sbifurcation", prefix);
    snprintf(data, sizeof data, "%s.dat", name);
    snprintf(clear, sizeof clear, "%sbifurcation-clearance.dat", prefix);
    if (rc == PLOT_OK)
        rc = write_sections(job, f, data, x, o, keep, &nkeep);
    if (rc == PLOT_OK && nkeep == 0) { /* no point reached its section: no figure */
        if (!job->opt->quiet)
            printf("no bifurcation diagram: no point of %s has once-per-revolution section samples\n", f->path);
        free(keep);
        return PLOT_OK;
    }
    if (rc == PLOT_OK)
        report_few_crossings(f);
    if (rc == PLOT_OK)
        rc = write_clearance(job, f, clear, x, o, keep[0], &nclear);
    if (rc == PLOT_OK && !(out = plot_script_begin(job, name, "bifurcation diagram", f->path, 1000, 680)))
        rc = PLOT_FAILED;
    if (out) {
        plot_var_string(out, "case_title", f->title);
        plot_var_string(out, "data", data);
        plot_var_string(out, "clear", clear);
        fprintf(out, "has_clearance = %d\n", nclear > 0);
        plot_var_string(out, "xlabel", f->sweep.key[x]);
        axis_scales(out, job->opt, 0);
        title_array(out, o, keep, nkeep);
        rc = plot_script_end(out, job, name, NULL, plot_tpl_bifurcation);
    }
    free(keep);
    return rc;
}

/* 1 if every value of swept key k is > 0, as a log axis needs; else 0 with a line naming `option`. */
static int all_positive(const plot_file *f, int k, const char *option)
{
    size_t p;
    for (p = 0; p < f->sweep.n; p++)
        if (!(f->sweep.value[k][p] > 0.0)) {
            fprintf(stderr, "touchdown plot: %s: %s has the value %g at point %lu: a log axis needs values > 0\n",
                    option, f->sweep.key[k], f->sweep.value[k][p], (unsigned long)p);
            return 0;
        }
    return 1;
}

/* ---- entry ---------------------------------------------------------------------------------- */

/* One line on stderr when points failed or were not run: how many, by status (the first few). */
static void report_failed(const plot_file *f)
{
    const plot_sweep *s = &f->sweep;
    const char *seen[4];
    size_t count[4], p, nfailed = 0;
    int k, nseen = 0;
    for (p = 0; p < s->n; p++) {
        if (!s->failed[p])
            continue;
        nfailed++;
        for (k = 0; k < nseen && strcmp(seen[k], s->status[p]); k++)
            ;
        if (k < nseen)
            count[k]++;
        else if (nseen < 4) {
            seen[nseen] = s->status[p];
            count[nseen++] = 1;
        }
    }
    if (!nfailed)
        return;
    fprintf(stderr, "touchdown plot: %s: %lu of %lu points failed or not run (", f->path, (unsigned long)nfailed,
            (unsigned long)s->n);
    for (k = 0; k < nseen; k++)
        fprintf(stderr, "%s%s %lu", k ? ", " : "", seen[k], (unsigned long)count[k]);
    fprintf(stderr, "%s): left out of the lines, marked at the foot, 'failed' on the regime map\n",
            nseen == 4 ? ", ..." : "");
}

int plot_sweep_figures(plot_job *job, const plot_file *f, const char *prefix)
{
    sweep_order o;
    int x = pick_x(job->opt, f), y, rc;
    if (x < 0)
        return PLOT_BAD_INPUT;
    if ((y = pick_y(job->opt, f, x)) == -2)
        return PLOT_BAD_INPUT;
    if ((job->opt->log_x && !all_positive(f, x, "--log-x")) ||
        (job->opt->log_y && y >= 0 && !all_positive(f, y, "--log-y")))
        return PLOT_BAD_INPUT;
    if (order_points(&f->sweep, x, &o) != 0) {
        fprintf(stderr, "touchdown plot: out of memory\n");
        return PLOT_FAILED;
    }
    report_failed(f);
    rc = quantity_figure(job, f, prefix, x, &o);
    if (rc == PLOT_OK)
        rc = regime_figure(job, f, prefix, x, y);
    if (rc == PLOT_OK && f->sweep.m > 0)
        rc = bifurcation_figure(job, f, prefix, x, &o);
    order_free(&o);
    return rc;
}
