/*
 * touchdown plot: a sweep table (touchdown sweep, docs/output-format.md "Sweep table") in memory:
 * the swept keys in the order of the table's `vary` attribute with their values from /vary/KEY,
 * each point's regime from /regime, its once-per-revolution section radii from /section_radius
 * (point x 64, NaN-padded) and the sampled retainer's clearance from /section_clearance.
 */
#include "plot/plot.h"

#include "touchdown/run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int plot_sweep_read_column(const td_result *r, const char *name, size_t n, td_result_array *a)
{
    memset(a, 0, sizeof *a);
    /* a name with a '/' would reach into a group (/vary/KEY are the keys, not results) */
    if (!*name || strchr(name, '/') || !strcmp(name, td_out_name(TD_OUT_SWEEP_POINT)))
        return -1;
    if (td_result_read(r, TD_OUT_ROOT, name, a, NULL) != TD_OK)
        return -1;
    if (a->rank != 1 || a->n != n) {
        td_result_array_free(a);
        return -1;
    }
    return 0;
}

void plot_sweep_columns(const td_result *r, size_t n, char *buf, size_t size)
{
    char **names = NULL;
    size_t count = 0, used = 0, listed = 0, i;
    buf[0] = '\0';
    if (td_result_columns(r, TD_OUT_ROOT, NULL, n, &names, &count, NULL) != TD_OK)
        count = 0;
    for (i = 0; i < count; i++) {
        if (strlen(names[i]) + 3 >= size - used) { /* keep room for ", ..." */
            snprintf(buf + used, size - used, ", ...");
            break;
        }
        used += (size_t)sprintf(buf + used, "%s%s", listed++ ? ", " : "", names[i]);
    }
    td_result_strings_free(names, count);
    if (!listed)
        snprintf(buf, size, "(none)");
}

/* The swept keys, one spec "KEY=..." a line of the `vary` attribute, in the sweep's order. */
static void read_keys(const td_result *r, plot_sweep *s)
{
    char *vary = NULL, *line;
    td_result_read_text(r, TD_OUT_SWEEP_VARY_SPECS, NULL, &vary, NULL);
    line = vary;
    while (line && *line && s->nkeys < PLOT_SWEEP_MAX_KEYS) {
        char *next = strchr(line, '\n'), *eq;
        if (next)
            *next++ = '\0';
        eq = strchr(line, '=');
        if (eq && eq > line && (size_t)(eq - line) < sizeof s->key[0]) {
            memcpy(s->key[s->nkeys], line, (size_t)(eq - line));
            s->key[s->nkeys++][eq - line] = '\0';
        }
        line = next;
    }
    free(vary);
}

/* The `axis` attribute of /vary/KEY (keys zipped onto one axis share it); k, an axis of its own,
 * for a table without it. */
static int read_axis(const td_result *r, const char *key, int k)
{
    td_result_array a;
    double axis = k;
    if (td_result_read(r, TD_OUT_SWEEP_KEY_AXIS, key, &a, NULL) == TD_OK) {
        axis = a.v[0];
        td_result_array_free(&a);
    }
    return (int)axis;
}

/* 0 if the strings *text just read (n of them) are one per point (want); else -1, with them freed
 * by their own count and *text NULL, so that nothing of the wrong length is kept for
 * plot_sweep_free (which frees s->n of each). */
static int one_per_point(char ***text, size_t n, size_t want)
{
    if (n == want)
        return 0;
    td_result_strings_free(*text, n);
    *text = NULL;
    return -1;
}

/* Key k's values: doubles when the dataset is numeric (and their text), else the text itself. */
static int read_key(const td_result *r, plot_sweep *s, int k)
{
    td_result_array a;
    size_t i, n = 0;
    s->axis[k] = read_axis(r, s->key[k], k);
    if (td_result_read_strings(r, TD_OUT_SWEEP_VARY, s->key[k], &s->text[k], &n, NULL) == TD_OK)
        return one_per_point(&s->text[k], n, s->n);
    if (td_result_read(r, TD_OUT_SWEEP_VARY, s->key[k], &a, NULL) != TD_OK || a.n != s->n) {
        td_result_array_free(&a);
        return -1;
    }
    s->numeric[k] = 1;
    s->value[k] = a.v;
    if (!(s->text[k] = calloc(s->n + 1, sizeof *s->text[k])))
        return -1;
    for (i = 0; i < s->n; i++) {
        char buf[64];
        snprintf(buf, sizeof buf, "%.12g", a.v[i]);
        if (!(s->text[k][i] = malloc(strlen(buf) + 1)))
            return -1;
        strcpy(s->text[k][i], buf);
    }
    return 0;
}

/* /regime as td_regime codes (-1: not a regime name, or no column). */
static int read_regimes(const td_result *r, plot_sweep *s)
{
    char **text = NULL;
    size_t i, n = 0;
    int k;
    if (!(s->regime = malloc((s->n + 1) * sizeof *s->regime)))
        return -1;
    for (i = 0; i < s->n; i++)
        s->regime[i] = -1;
    if (!td_result_has(r, TD_OUT_SWEEP_REGIME, NULL))
        return 0;
    if (td_result_read_strings(r, TD_OUT_SWEEP_REGIME, NULL, &text, &n, NULL) != TD_OK ||
        one_per_point(&text, n, s->n) != 0)
        return -1;
    for (i = 0; i < n; i++)
        for (k = 0; k < TD_REGIME_COUNT; k++)
            if (!strcmp(text[i], td_regime_name((td_regime)k)))
                s->regime[i] = k;
    td_result_strings_free(text, n);
    return 0;
}

/* A number column the table may lack (tables of older versions): *out gets one value per point,
 * NaN (undefined) where the table has none; a column of another length is refused. */
static int read_optional_column(const td_result *r, td_out_id id, size_t n, double **out)
{
    td_result_array a;
    size_t i;
    if (!(*out = malloc((n + 1) * sizeof **out)))
        return -1;
    for (i = 0; i < n; i++)
        (*out)[i] = NAN;
    if (!td_result_has(r, id, NULL))
        return 0;
    if (td_result_read(r, id, NULL, &a, NULL) != TD_OK || a.n != n) {
        td_result_array_free(&a);
        return -1;
    }
    memcpy(*out, a.v, n * sizeof *a.v);
    td_result_array_free(&a);
    return 0;
}

/* /status: a point is failed (no answers, touchdown/dofs.h "Undefined values") unless it ran to
 * its end, "success"; a table without the column has every point run. And /section_count. */
static int read_status(const td_result *r, plot_sweep *s)
{
    size_t i, n = 0;
    if (!(s->failed = calloc(s->n + 1, sizeof *s->failed)) ||
        read_optional_column(r, TD_OUT_SWEEP_SECTION_COUNT, s->n, &s->section_count) != 0)
        return -1;
    if (!td_result_has(r, TD_OUT_SWEEP_STATUS, NULL))
        return 0;
    if (td_result_read_strings(r, TD_OUT_SWEEP_STATUS, NULL, &s->status, &n, NULL) != TD_OK ||
        one_per_point(&s->status, n, s->n) != 0)
        return -1;
    for (i = 0; i < n; i++)
        s->failed[i] = strcmp(s->status[i], td_strerror(TD_OK)) != 0;
    return 0;
}

/* /section_radius (point x m) and /section_clearance, when the table has them. */
static int read_section(const td_result *r, plot_sweep *s)
{
    td_result_array a;
    if (read_optional_column(r, TD_OUT_SWEEP_SECTION_CLEARANCE, s->n, &s->clearance) != 0)
        return -1;
    if (!td_result_has(r, TD_OUT_SWEEP_SECTION_RADIUS, NULL))
        return 0;
    if (td_result_read(r, TD_OUT_SWEEP_SECTION_RADIUS, NULL, &a, NULL) != TD_OK || a.rank != 2 || a.dims[0] != s->n) {
        td_result_array_free(&a);
        return -1;
    }
    s->section = a.v;
    s->m = a.dims[1];
    return 0;
}

int plot_sweep_load(const td_result *r, plot_file *f)
{
    plot_sweep *s = &f->sweep;
    td_result_array pt;
    int k;
    if (td_result_read(r, TD_OUT_SWEEP_POINT, NULL, &pt, NULL) != TD_OK)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_SWEEP_POINT, " dataset");
    s->n = pt.n;
    td_result_array_free(&pt);
    read_keys(r, s);
    if (s->nkeys == 0)
        return plot_bad_part(f->path, "the sweep table names no swept key (attribute '", TD_OUT_SWEEP_VARY_SPECS, "')");
    for (k = 0; k < s->nkeys; k++)
        if (read_key(r, s, k) != 0) {
            char where[256];
            td_out_path(TD_OUT_SWEEP_VARY, s->key[k], where, sizeof where);
            fprintf(stderr, "touchdown plot: %s: unreadable swept key /%s\n", f->path, where);
            return PLOT_BAD_INPUT;
        }
    if (read_regimes(r, s) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_SWEEP_REGIME, " column");
    if (read_section(r, s) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_SWEEP_SECTION_RADIUS, " or its clearance column");
    if (read_status(r, s) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_SWEEP_STATUS, " or section count column");
    return PLOT_OK;
}

void plot_sweep_free(plot_sweep *s)
{
    int k;
    for (k = 0; k < PLOT_SWEEP_MAX_KEYS; k++) {
        free(s->value[k]);
        td_result_strings_free(s->text[k], s->text[k] ? s->n : 0);
    }
    free(s->regime);
    free(s->failed);
    free(s->section_count);
    td_result_strings_free(s->status, s->status ? s->n : 0);
    free(s->section);
    free(s->clearance);
    memset(s, 0, sizeof *s);
}
