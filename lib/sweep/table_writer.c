/*
 * Writers of a sweep's table (touchdown/sweep.h): one CSV file, or one HDF5 file with a dataset
 * per column over the dimension `point`. Like the simulation and modal writers, both write
 * PATH.XXXXXX.partial (td_io_create_temp) and rename it to PATH once it is on disk, and the
 * completeness flag is the last thing written, so a table never looks finished when it is not.
 * Numbers are printed with 17 significant digits in CSV (they read back to the same double).
 */
#include "io/h5_util.h"
#include "io/h5_vfd.h"
#include "io/schema.h"
#include "io/writer_internal.h"
#include "touchdown/dofs.h"
#include "touchdown/sweep.h"
#include "touchdown/version.h"
#include "util/error_internal.h"

#include <hdf5.h>

#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The quantity columns after the swept values, in order; wall time stays last so that tables of
 * the same sweep compare equal once it is cut. */
typedef enum col_kind { COL_TEXT, COL_DOUBLE, COL_LONG, COL_INT } col_kind;

typedef struct sweep_column {
    td_out_id id; /* name and units: td_schema */
    col_kind kind;
    size_t offset;
} sweep_column;

static const sweep_column columns[] = {
    {TD_OUT_SWEEP_STATUS, COL_TEXT, offsetof(td_sweep_row, status)},
    {TD_OUT_SWEEP_MESSAGE, COL_TEXT, offsetof(td_sweep_row, message)},
    {TD_OUT_SWEEP_PEAK_HOUSING_FORCE, COL_DOUBLE, offsetof(td_sweep_row, peak_housing_force)},
    {TD_OUT_SWEEP_TOTAL_IMPULSE, COL_DOUBLE, offsetof(td_sweep_row, total_impulse)},
    {TD_OUT_SWEEP_FRICTION_WORK, COL_DOUBLE, offsetof(td_sweep_row, friction_work)},
    {TD_OUT_SWEEP_CONTACT_TIME, COL_DOUBLE, offsetof(td_sweep_row, contact_time)},
    {TD_OUT_SWEEP_CONTACTS, COL_LONG, offsetof(td_sweep_row, contacts)},
    {TD_OUT_SWEEP_FIRST_CONTACT_TIME, COL_DOUBLE, offsetof(td_sweep_row, first_contact_time)},
    {TD_OUT_SWEEP_ENDING, COL_TEXT, offsetof(td_sweep_row, ending)},
    {TD_OUT_SWEEP_REGIME, COL_TEXT, offsetof(td_sweep_row, regime)},
    {TD_OUT_SWEEP_ENDING_WHIRL_FREQUENCY, COL_DOUBLE, offsetof(td_sweep_row, ending_whirl_frequency)},
    {TD_OUT_SWEEP_RETURNED_TO_FREE_ORBIT, COL_INT, offsetof(td_sweep_row, returned_to_free_orbit)},
    {TD_OUT_SWEEP_SECTION_COUNT, COL_LONG, offsetof(td_sweep_row, section_count)},
    {TD_OUT_SWEEP_SECTION_RADIUS_MIN, COL_DOUBLE, offsetof(td_sweep_row, section_radius_min)},
    {TD_OUT_SWEEP_SECTION_RADIUS_MAX, COL_DOUBLE, offsetof(td_sweep_row, section_radius_max)},
    {TD_OUT_SWEEP_SECTION_CLEARANCE, COL_DOUBLE, offsetof(td_sweep_row, section_clearance)},
    {TD_OUT_SWEEP_FINAL_SPEED, COL_DOUBLE, offsetof(td_sweep_row, final_speed)},
    {TD_OUT_SWEEP_PEAK_AMB_LOAD, COL_DOUBLE, offsetof(td_sweep_row, peak_amb_load)},
    {TD_OUT_SWEEP_T_REACHED, COL_DOUBLE, offsetof(td_sweep_row, t_reached)},
    {TD_OUT_SWEEP_DROPS_TO_FAILURE, COL_DOUBLE, offsetof(td_sweep_row, drops_to_failure)}, /* life: optional */
    /* clearance margin */
    {TD_OUT_SWEEP_MIN_CLEARANCE_MARGIN, COL_DOUBLE, offsetof(td_sweep_row, min_clearance_margin)},
    {TD_OUT_SWEEP_CONTACT_HAPPENED, COL_INT, offsetof(td_sweep_row, contact_happened)},
    {TD_OUT_SWEEP_SHOCK_OUTCOME, COL_TEXT, offsetof(td_sweep_row, shock_outcome)},
    /* projective leap and long runs: optional (shown_columns) */
    {TD_OUT_SWEEP_LEAPS, COL_LONG, offsetof(td_sweep_row, leaps)},
    {TD_OUT_SWEEP_LEAPT_TIME, COL_DOUBLE, offsetof(td_sweep_row, leapt_time)},
    {TD_OUT_SWEEP_ENDED_AT_REST, COL_INT, offsetof(td_sweep_row, ended_at_rest)},
    {TD_OUT_SWEEP_WARNINGS, COL_TEXT, offsetof(td_sweep_row, warnings)},
    {TD_OUT_SWEEP_WALL_TIME, COL_DOUBLE, offsetof(td_sweep_row, wall_time)},
};
#define N_COLUMNS ((int)(sizeof columns / sizeof columns[0]))

/* The columns shown only when some row asks for them (asks; shown_columns). */
static int optional(td_out_id id)
{
    return id == TD_OUT_SWEEP_DROPS_TO_FAILURE || id == TD_OUT_SWEEP_LEAPS || id == TD_OUT_SWEEP_LEAPT_TIME ||
           id == TD_OUT_SWEEP_ENDED_AT_REST;
}

/* Whether row r asks for the optional column `id`. */
static int asks(const td_sweep_row *r, td_out_id id)
{
    switch (id) {
    case TD_OUT_SWEEP_DROPS_TO_FAILURE: return r->life_kept;
    case TD_OUT_SWEEP_ENDED_AT_REST: return r->end_at_rest;
    default: return r->leap; /* leaps, leapt_time */
    }
}

/* Which columns are in the table (shown[c]): every column but the optional ones, the life's only
 * when some row's bearings have a dynamic rating (td_sweep_row.life_kept), the leaps' when some
 * point leaps and ended_at_rest when some point was asked to end at rest (td_sweep_row.leap,
 * end_at_rest: as the run's JSON has them), so that a sweep without them has the table it always
 * had. Found once per table and handed to the writers: a scan of the rows per optional column,
 * O(points), where asking it per cell cost O(points^2) for a table of 100,000 points. */
static void shown_columns(const td_sweep_table *t, int shown[N_COLUMNS])
{
    long p, n = td_sweep_grid_points(t->grid);
    int c;
    for (c = 0; c < N_COLUMNS; c++) {
        shown[c] = !optional(columns[c].id);
        for (p = 0; !shown[c] && p < n; p++)
            shown[c] = asks(&t->rows[p], columns[c].id);
    }
}

static const char *col_text(const td_sweep_row *r, int c)
{
    return (const char *)r + columns[c].offset;
}

/* A column's value as the table holds it: a count that is unknown (-1) and a flag that is not 1
 * or 0 (returned_to_free_orbit n/a or undetermined) are undefined, NaN like every other number
 * without a value (touchdown/dofs.h, "Undefined values"). */
static double col_double(const td_sweep_row *r, int c)
{
    const char *p = (const char *)r + columns[c].offset;
    if (columns[c].kind == COL_LONG) {
        long v = *(const long *)(const void *)p;
        return v >= 0 ? (double)v : TD_UNDEFINED;
    }
    if (columns[c].kind == COL_INT) {
        int v = *(const int *)(const void *)p;
        return v == 0 || v == 1 ? (double)v : TD_UNDEFINED;
    }
    return *(const double *)(const void *)p;
}

static td_status check_table(const td_sweep_table *t, const char *path, const char *fn, td_error *err)
{
    if (!path || !t || !t->grid || !t->rows || (t->n_sets > 0 && !t->sets))
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL argument", fn);
    return TD_OK;
}

/* ---- CSV --------------------------------------------------------------------------------- */

/* A text field, quoted (quotes doubled) when it holds a comma, a quote or a line break. */
static void csv_text(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\n\r")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s == '\n' || *s == '\r' ? ' ' : *s, f);
    }
    fputc('"', f);
}

static void csv_header(FILE *f, const td_sweep_table *t, const int *shown)
{
    const td_sweep_grid *g = t->grid;
    int a, c;
    fprintf(f, "%s [%s]", td_out_name(TD_OUT_SWEEP_POINT), td_schema_csv_units(TD_OUT_SWEEP_POINT));
    for (a = 0; a < td_sweep_grid_keys(g); a++) {
        fputc(',', f);
        csv_text(f, td_sweep_grid_key(g, a));
    }
    for (c = 0; c < N_COLUMNS; c++)
        if (shown[c])
            fprintf(f, td_out_units(columns[c].id)[0] ? ",%s [%s]" : ",%s", td_out_name(columns[c].id),
                    td_out_units(columns[c].id));
    fputc('\n', f);
}

static void csv_row(FILE *f, const td_sweep_table *t, const int *shown, long point, const td_sweep_row *r)
{
    const td_sweep_grid *g = t->grid;
    int a, c;
    fprintf(f, "%ld", point);
    for (a = 0; a < td_sweep_grid_keys(g); a++) {
        fputc(',', f);
        csv_text(f, td_sweep_grid_value(g, point, a));
    }
    for (c = 0; c < N_COLUMNS; c++) {
        if (!shown[c])
            continue;
        fputc(',', f);
        if (columns[c].kind == COL_TEXT)
            csv_text(f, col_text(r, c));
        else if (td_is_undefined(col_double(r, c)))
            fputs("nan", f); /* gnuplot, numpy and pandas read it as a missing value */
        else if (columns[c].kind == COL_DOUBLE)
            fprintf(f, "%.17g", col_double(r, c));
        else
            fprintf(f, "%.0f", col_double(r, c));
    }
    fputc('\n', f);
}

/* Multi-line text as "# name:" and one "#| line" per line, like the simulation CSV. */
static void csv_comment_text(FILE *f, const char *name, const char *text)
{
    size_t len = strlen(text);
    fprintf(f, "# %s:\n#| ", name);
    for (; *text; text++) {
        fputc(*text, f);
        if (*text == '\n' && text[1])
            fputs("#| ", f);
    }
    if (len == 0 || text[-1] != '\n')
        fputc('\n', f);
}

/* Per axis: "# vary = SPEC" of its first key, "# with = SPEC" of each key zipped with it, then
 * "# from = ORIGIN" (command line, or the case file's FILE:LINE: sweep.vary[i]). */
/* Why the table is incomplete: its reason, else the rule's own. */
static const char *incomplete_reason(const td_sweep_table *t)
{
    return t->reason && t->reason[0] ? t->reason : "not every point was run";
}

static void csv_axes(FILE *f, const td_sweep_grid *g)
{
    int k, n = td_sweep_grid_keys(g);
    for (k = 0; k < n; k++) {
        int first = k == 0 || td_sweep_grid_axis(g, k - 1) != td_sweep_grid_axis(g, k);
        fprintf(f, "# %s = %s\n", td_out_name(first ? TD_OUT_SWEEP_VARY_SPECS : TD_OUT_SWEEP_WITH),
                td_sweep_grid_spec(g, k));
        if (k == n - 1 || td_sweep_grid_axis(g, k + 1) != td_sweep_grid_axis(g, k))
            fprintf(f, "# %s = %s\n", td_out_name(TD_OUT_SWEEP_FROM), td_sweep_grid_origin(g, k));
    }
}

static void csv_attributes(FILE *f, const td_sweep_table *t)
{
    int i;
    fprintf(f, "# %s = %s\n# %s = %ld\n", td_out_name(TD_OUT_LIBRARY_VERSION), td_version(),
            td_out_name(TD_OUT_SWEEP_POINTS), td_sweep_grid_points(t->grid));
    csv_axes(f, t->grid);
    for (i = 0; i < t->n_sets; i++)
        fprintf(f, "# %s = %s\n", td_out_name(TD_OUT_SWEEP_SET), t->sets[i]);
    if (t->case_text && t->case_text[0])
        csv_comment_text(f, td_out_name(TD_OUT_CASE_TEXT), t->case_text);
    td_io_csv_flag(f, t->complete, incomplete_reason(t)); /* a failed write shows at the close */
}

static void csv_write_all(FILE *f, const td_sweep_table *t)
{
    long p, n = td_sweep_grid_points(t->grid);
    int shown[N_COLUMNS];
    shown_columns(t, shown);
    csv_header(f, t, shown);
    for (p = 0; p < n; p++)
        csv_row(f, t, shown, p, &t->rows[p]);
    csv_attributes(f, t);
}

static void csv_write_table(FILE *f, const void *t)
{
    csv_write_all(f, t);
}

td_status td_sweep_write_csv(const char *path, const td_sweep_table *t, td_error *err)
{
    td_status st = check_table(t, path, "td_sweep_write_csv", err);
    return st != TD_OK ? st : td_io_write_text_file(path, csv_write_table, t, err);
}

/* ---- HDF5 -------------------------------------------------------------------------------- */

/* One text column: a variable-length UTF-8 dataset `name` of the n strings in `text`. */
static int h5_text_column(hid_t loc, const char *name, const char **text, hsize_t n)
{
    hid_t type = td_h5_text_type();
    int ok = type >= 0 && td_h5_dataset(loc, name, type, type, text, 1, &n, "");
    if (type >= 0)
        H5Tclose(type);
    return ok;
}

static int h5_quantity(hid_t file, const td_sweep_table *t, int c, hsize_t n, const char **text, double *num)
{
    hsize_t p;
    for (p = 0; p < n; p++) {
        if (columns[c].kind == COL_TEXT)
            text[p] = col_text(&t->rows[p], c);
        else
            num[p] = col_double(&t->rows[p], c);
    }
    if (columns[c].kind == COL_TEXT)
        return h5_text_column(file, td_out_name(columns[c].id), text, n);
    /* counts and flags are small whole numbers: a double holds them exactly and keeps one type */
    return td_h5_dataset(file, td_out_name(columns[c].id), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, num, 1, &n,
                         td_out_units(columns[c].id));
}

/* The attributes of /vary/KEY: its spec, its axis (keys of one axis are zipped) and where the
 * axis came from. */
static int h5_key_attributes(hid_t group, const td_sweep_grid *g, int k)
{
    hid_t d = H5Dopen2(group, td_sweep_grid_key(g, k), H5P_DEFAULT);
    int ok = d >= 0 && td_h5_attr_string(d, td_out_name(TD_OUT_SWEEP_KEY_SPEC), td_sweep_grid_spec(g, k)) >= 0 &&
             td_h5_attr_int(d, td_out_name(TD_OUT_SWEEP_KEY_AXIS), td_sweep_grid_axis(g, k)) >= 0 &&
             td_h5_attr_string(d, td_out_name(TD_OUT_SWEEP_KEY_ORIGIN), td_sweep_grid_origin(g, k)) >= 0;
    if (d >= 0)
        H5Dclose(d);
    return ok;
}

/* /vary/KEY: a swept key's values, doubles when all are numbers, else their text. */
static int h5_axis(hid_t group, const td_sweep_grid *g, int k, hsize_t n, const char **text, double *num)
{
    hsize_t p;
    int ok;
    for (p = 0; p < n; p++) {
        text[p] = td_sweep_grid_value(g, (long)p, k);
        num[p] = strtod(text[p], NULL);
    }
    if (td_sweep_grid_numeric(g, k))
        ok = td_h5_dataset(group, td_sweep_grid_key(g, k), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, num, 1, &n, "");
    else
        ok = h5_text_column(group, td_sweep_grid_key(g, k), text, n);
    return ok && h5_key_attributes(group, g, k);
}

static int h5_axes(hid_t file, const td_sweep_table *t, hsize_t n, const char **text, double *num)
{
    hid_t group = H5Gcreate2(file, td_out_name(TD_OUT_SWEEP_VARY), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int a, ok = group >= 0;
    for (a = 0; ok && a < td_sweep_grid_keys(t->grid); a++)
        ok = h5_axis(group, t->grid, a, n, text, num);
    if (group >= 0)
        H5Gclose(group);
    return ok;
}

/* section_radius: point x TD_RUN_SECTION_SAMPLES, each row's last section radii, NaN-padded. */
static int h5_section(hid_t file, const td_sweep_table *t, hsize_t n)
{
    hsize_t dims[2], p;
    double *v = malloc((size_t)(n > 0 ? n : 1) * TD_RUN_SECTION_SAMPLES * sizeof *v);
    int ok;
    dims[0] = n;
    dims[1] = TD_RUN_SECTION_SAMPLES;
    for (p = 0; v && p < n; p++)
        memcpy(v + p * TD_RUN_SECTION_SAMPLES, t->rows[p].section_radius, sizeof t->rows[p].section_radius);
    ok = v && td_h5_dataset(file, td_out_name(TD_OUT_SWEEP_SECTION_RADIUS), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v, 2,
                            dims, td_out_units(TD_OUT_SWEEP_SECTION_RADIUS));
    free(v);
    return ok;
}

/* Every column's dataset along the scale /point. */
static int h5_columns(hid_t file, const td_sweep_table *t)
{
    hsize_t n = (hsize_t)td_sweep_grid_points(t->grid);
    const char **text = malloc((size_t)n * sizeof *text);
    double *num = malloc((size_t)n * sizeof *num);
    const char *names[N_COLUMNS + TD_SWEEP_MAX_KEYS + 2];
    char vary_names[TD_SWEEP_MAX_KEYS][TD_SWEEP_KEY_SIZE + 8];
    int shown[N_COLUMNS];
    int c, a, m = 0,
              ok = text && num &&
                   td_h5_index(file, td_out_name(TD_OUT_SWEEP_POINT), (int)n, td_out_units(TD_OUT_SWEEP_POINT)) &&
                   h5_axes(file, t, n, text, num);
    shown_columns(t, shown);
    for (c = 0; ok && c < N_COLUMNS; c++)
        if (shown[c]) {
            ok = h5_quantity(file, t, c, n, text, num);
            names[m++] = td_out_name(columns[c].id);
        }
    for (a = 0; a < td_sweep_grid_keys(t->grid); a++) {
        td_out_path(TD_OUT_SWEEP_VARY, td_sweep_grid_key(t->grid, a), vary_names[a], sizeof vary_names[a]);
        names[m + a] = vary_names[a];
    }
    names[m + td_sweep_grid_keys(t->grid)] = td_out_name(TD_OUT_SWEEP_SECTION_RADIUS);
    names[m + td_sweep_grid_keys(t->grid) + 1] = NULL;
    ok = ok && h5_section(file, t, n) && td_h5_attach(file, td_out_name(TD_OUT_SWEEP_POINT), names, 0);
    free(text);
    free(num);
    return ok;
}

/* The sweep's description; then, last, the completeness flag. */
static int h5_attributes(hid_t file, const td_sweep_table *t)
{
    char *vary = NULL, *sets = NULL;
    size_t nv = 1, ns = 1;
    int a, i, ok;
    for (a = 0; a < td_sweep_grid_keys(t->grid); a++)
        nv += strlen(td_sweep_grid_spec(t->grid, a)) + 1;
    for (i = 0; i < t->n_sets; i++)
        ns += strlen(t->sets[i]) + 1;
    ok = (vary = calloc(nv, 1)) != NULL && (sets = calloc(ns, 1)) != NULL;
    for (a = 0; ok && a < td_sweep_grid_keys(t->grid); a++) /* one spec a line, zipped keys too */
        strcat(strcat(vary, td_sweep_grid_spec(t->grid, a)), "\n");
    for (i = 0; ok && i < t->n_sets; i++)
        strcat(strcat(sets, t->sets[i]), "\n");
    ok = ok && td_h5_attr_string(file, td_out_name(TD_OUT_SWEEP_VARY_SPECS), vary) >= 0 &&
         td_h5_attr_string(file, td_out_name(TD_OUT_SWEEP_SET), sets) >= 0 &&
         td_h5_attr_string(file, td_out_name(TD_OUT_CASE_TEXT), t->case_text ? t->case_text : "") >= 0 &&
         td_h5_attr_string(file, td_out_name(TD_OUT_LIBRARY_VERSION), td_version()) >= 0;
    if (ok && !t->complete)
        ok = td_h5_attr_string(file, td_out_name(TD_OUT_INCOMPLETE_REASON), incomplete_reason(t)) >= 0;
    ok = ok && td_h5_attr_int(file, td_out_name(TD_OUT_COMPLETE), t->complete ? 1 : 0) >= 0;
    free(vary);
    free(sets);
    return ok;
}

static td_status h5_write_all(const char *tmp, const td_sweep_table *t, td_error *err)
{
    int io_errno = 0;
    hid_t driver;
    hid_t file = td_h5_create_file(tmp, 1, &io_errno, &driver);
    td_status st = TD_OK;
    if (file < 0)
        st = td_h5_fail(err, tmp, io_errno, "cannot create the HDF5 file");
    else if (!h5_columns(file, t) || !h5_attributes(file, t) || io_errno)
        st = td_h5_fail(err, tmp, io_errno, "cannot write the sweep table");
    if (file >= 0 && (H5Fclose(file) < 0 || io_errno) && st == TD_OK)
        st = td_h5_fail(err, tmp, io_errno, "cannot close the HDF5 file");
    td_h5_vfd_release(driver);
    return st;
}

static td_status h5_write_table(const char *tmp, const void *t, td_error *err)
{
    td_status st;
    H5E_BEGIN_TRY /* HDF5 would print its error stack; silenced for this call only */
    {
        st = h5_write_all(tmp, t, err);
    }
    H5E_END_TRY;
    return st;
}

td_status td_sweep_write_hdf5(const char *path, const td_sweep_table *t, td_error *err)
{
    td_status st = check_table(t, path, "td_sweep_write_hdf5", err);
    return st != TD_OK ? st : td_io_write_named_file(path, h5_write_table, t, err);
}
