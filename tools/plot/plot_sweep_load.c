/*
 * touchdown plot: a sweep table (touchdown sweep, docs/output-format.md "Sweep table") in memory:
 * the swept keys in the order of the table's `vary` attribute with their values from /vary/KEY,
 * each point's regime from /regime, its once-per-revolution section radii from /section_radius
 * (point x 64, NaN-padded) and the sampled retainer's clearance from /section_clearance.
 */
#include "plot.h"

#include "touchdown/run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int bad(const char *path, const char *why)
{
    fprintf(stderr, "touchdown plot: %s: %s\n", path, why);
    return PLOT_BAD_INPUT;
}

int plot_sweep_is_table(hid_t file)
{
    return plot_h5_exists(file, "point") && plot_h5_exists(file, "vary");
}

int plot_sweep_is_column(hid_t file, const char *name, size_t n)
{
    hid_t d, space = -1, type = -1;
    int ok = 0;
    /* a name with a '/' would reach into a group (/vary/KEY are the keys, not results); H5Lexists
     * takes no empty name */
    if (!*name || strchr(name, '/') || !strcmp(name, "point") || H5Lexists(file, name, H5P_DEFAULT) <= 0)
        return 0;
    if (H5Oexists_by_name(file, name, H5P_DEFAULT) <= 0 || (d = H5Dopen2(file, name, H5P_DEFAULT)) < 0)
        return 0; /* a dangling link, a group */
    space = H5Dget_space(d);
    type = H5Dget_type(d);
    if (space >= 0 && type >= 0 && (H5Tget_class(type) == H5T_FLOAT || H5Tget_class(type) == H5T_INTEGER) &&
        H5Sget_simple_extent_ndims(space) == 1 && H5Sget_simple_extent_npoints(space) == (hssize_t)n)
        ok = 1;
    if (type >= 0)
        H5Tclose(type);
    if (space >= 0)
        H5Sclose(space);
    H5Dclose(d);
    return ok;
}

typedef struct column_list {
    size_t n, used, count;
    char *buf, *end;
} column_list;

static herr_t add_column(hid_t file, const char *name, const H5L_info_t *info, void *data)
{
    column_list *l = data;
    size_t len = strlen(name), room = (size_t)(l->end - l->buf) - l->used;
    (void)info;
    if (!plot_sweep_is_column(file, name, l->n))
        return 0;
    if (len + 3 >= room) /* keep room for ", ..." */
        return 1;
    l->used += (size_t)sprintf(l->buf + l->used, "%s%s", l->count++ ? ", " : "", name);
    return 0;
}

void plot_sweep_columns(hid_t file, size_t n, char *buf, size_t size)
{
    column_list l;
    hsize_t at = 0;
    l.n = n;
    l.used = l.count = 0;
    l.buf = buf;
    l.end = buf + size;
    buf[0] = '\0';
    if (H5Literate(file, H5_INDEX_NAME, H5_ITER_INC, &at, add_column, &l) > 0)
        snprintf(buf + l.used, size - l.used, ", ...");
    if (!l.count)
        snprintf(buf, size, "(none)");
}

/* The swept keys, one spec "KEY=..." a line of the `vary` attribute, in the sweep's order. */
static void read_keys(hid_t file, plot_sweep *s)
{
    char *vary = plot_h5_attr_string(file, "vary"), *line = vary;
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
static int read_axis(hid_t file, const char *path, int k)
{
    hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
    double axis = k;
    if (d >= 0) {
        if (plot_h5_attr_double(d, "axis", &axis) != 0)
            axis = k;
        H5Dclose(d);
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
    plot_strings_free(*text, n);
    *text = NULL;
    return -1;
}

/* Key k's values: doubles when the dataset is numeric (and their text), else the text itself. */
static int read_key(hid_t file, plot_sweep *s, int k)
{
    char path[160];
    plot_array a;
    size_t i, n = 0;
    snprintf(path, sizeof path, "vary/%s", s->key[k]);
    s->axis[k] = read_axis(file, path, k);
    if (plot_h5_read_strings(file, path, &s->text[k], &n) == 0)
        return one_per_point(&s->text[k], n, s->n);
    if (plot_h5_read(file, path, &a) != 0 || a.n != s->n) {
        plot_array_free(&a);
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
static int read_regimes(hid_t file, plot_sweep *s)
{
    char **text = NULL;
    size_t i, n = 0;
    int r;
    if (!(s->regime = malloc((s->n + 1) * sizeof *s->regime)))
        return -1;
    for (i = 0; i < s->n; i++)
        s->regime[i] = -1;
    if (!plot_h5_exists(file, "regime"))
        return 0;
    if (plot_h5_read_strings(file, "regime", &text, &n) != 0 || one_per_point(&text, n, s->n) != 0)
        return -1;
    for (i = 0; i < n; i++)
        for (r = 0; r < TD_REGIME_COUNT; r++)
            if (!strcmp(text[i], td_regime_name((td_regime)r)))
                s->regime[i] = r;
    plot_strings_free(text, n);
    return 0;
}

/* A number column the table may lack (tables of older versions): *out gets one value per point,
 * NaN (undefined) where the table has none; a column of another length is refused. */
static int read_optional_column(hid_t file, const char *name, size_t n, double **out)
{
    plot_array a;
    size_t i;
    if (!(*out = malloc((n + 1) * sizeof **out)))
        return -1;
    for (i = 0; i < n; i++)
        (*out)[i] = NAN;
    if (!plot_h5_exists(file, name))
        return 0;
    if (plot_h5_read(file, name, &a) != 0 || a.n != n) {
        plot_array_free(&a);
        return -1;
    }
    memcpy(*out, a.v, n * sizeof *a.v);
    plot_array_free(&a);
    return 0;
}

/* /status: a point is failed (no answers, touchdown/dofs.h "Undefined values") unless it ran to
 * its end, "success"; a table without the column has every point run. And /section_count. */
static int read_status(hid_t file, plot_sweep *s)
{
    size_t i, n = 0;
    if (!(s->failed = calloc(s->n + 1, sizeof *s->failed)) ||
        read_optional_column(file, "section_count", s->n, &s->section_count) != 0)
        return -1;
    if (!plot_h5_exists(file, "status"))
        return 0;
    if (plot_h5_read_strings(file, "status", &s->status, &n) != 0 || one_per_point(&s->status, n, s->n) != 0)
        return -1;
    for (i = 0; i < n; i++)
        s->failed[i] = strcmp(s->status[i], td_strerror(TD_OK)) != 0;
    return 0;
}

/* /section_radius (point x m) and /section_clearance, when the table has them. */
static int read_section(hid_t file, plot_sweep *s)
{
    plot_array a;
    if (read_optional_column(file, "section_clearance", s->n, &s->clearance) != 0)
        return -1;
    if (!plot_h5_exists(file, "section_radius"))
        return 0;
    if (plot_h5_read(file, "section_radius", &a) != 0 || a.rank != 2 || a.dims[0] != s->n) {
        plot_array_free(&a);
        return -1;
    }
    s->section = a.v;
    s->m = a.dims[1];
    return 0;
}

int plot_sweep_load(hid_t file, plot_file *f)
{
    plot_sweep *s = &f->sweep;
    plot_array pt;
    int k;
    if (plot_h5_read(file, "point", &pt) != 0)
        return bad(f->path, "unreadable /point dataset");
    s->n = pt.n;
    plot_array_free(&pt);
    read_keys(file, s);
    if (s->nkeys == 0)
        return bad(f->path, "the sweep table names no swept key (attribute 'vary')");
    for (k = 0; k < s->nkeys; k++)
        if (read_key(file, s, k) != 0) {
            fprintf(stderr, "touchdown plot: %s: unreadable swept key /vary/%s\n", f->path, s->key[k]);
            return PLOT_BAD_INPUT;
        }
    if (read_regimes(file, s) != 0)
        return bad(f->path, "unreadable /regime column");
    if (read_section(file, s) != 0)
        return bad(f->path, "unreadable /section_radius or /section_clearance");
    if (read_status(file, s) != 0)
        return bad(f->path, "unreadable /status or /section_count column");
    return PLOT_OK;
}

void plot_sweep_free(plot_sweep *s)
{
    int k;
    for (k = 0; k < PLOT_SWEEP_MAX_KEYS; k++) {
        free(s->value[k]);
        plot_strings_free(s->text[k], s->text[k] ? s->n : 0);
    }
    free(s->regime);
    free(s->failed);
    free(s->section_count);
    plot_strings_free(s->status, s->status ? s->n : 0);
    free(s->section);
    free(s->clearance);
    memset(s, 0, sizeof *s);
}
