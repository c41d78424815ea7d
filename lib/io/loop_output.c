/*
 * The loop analysis in the modal files and as JSON (loop_output.h, touchdown/modal_output.h):
 * every name from the schema (schema.c), the same names as the JSON keys of `touchdown modal
 * --json`. An undefined value (an unstable loop's sensitivity) is "nan" in CSV, NaN in HDF5,
 * null in JSON, an empty zone "" in the files (docs/output-format.md, "Undefined values"). A sampled
 * loop's sample rate is written for it alone (null in JSON for a continuous loop).
 */
#include "io/loop_output.h"
#include "io/h5_util.h"
#include "io/schema.h"
#include "touchdown/modal_output.h"
#include "util/text.h"

#include <math.h>
#include <stdlib.h>

/* ---- CSV --------------------------------------------------------------------------------- */

/* The section line, then `notes` ("# NAME = VALUE" lines, may be ""), then the column names. */
static void csv_header(FILE *f, td_out_id section, const char *notes, const td_out_id *cols, int n)
{
    int i;
    fprintf(f, "# section: %s\n%s", td_out_name(section), notes);
    for (i = 0; i < n; i++)
        fprintf(f, "%s%s", i ? "," : "", td_schema_csv(cols[i]));
    fputc('\n', f);
}

/* One line "a,b" of a zone: the letter, or "" when undefined. */
static const char *zone_text(char z, char *buf)
{
    buf[0] = z;
    buf[1] = '\0';
    return buf;
}

void td_loop_write_csv_sections(FILE *f, const td_loop *l)
{
    static const td_out_id loop[] = {TD_OUT_LOOP_FREQUENCY,      TD_OUT_LOOP_AXIS,         TD_OUT_LOOP_SENSITIVITY_RE,
                                     TD_OUT_LOOP_SENSITIVITY_IM, TD_OUT_LOOP_OPEN_LOOP_RE, TD_OUT_LOOP_OPEN_LOOP_IM};
    static const td_out_id peaks[] = {TD_OUT_LOOP_AXIS, TD_OUT_LOOP_SENSITIVITY_PEAK,
                                      TD_OUT_LOOP_SENSITIVITY_PEAK_FREQUENCY, TD_OUT_LOOP_SENSITIVITY_ZONES};
    static const td_out_id comp[] = {TD_OUT_LOOP_FREQUENCY, TD_OUT_LOOP_AMB_AXIS, TD_OUT_LOOP_COMPLIANCE_RE,
                                     TD_OUT_LOOP_COMPLIANCE_IM};
    int k, j, nc = td_loop_axis_count(l), na = td_loop_amb_axis_count(l);
    char z[2];
    double v[4];
    char notes[320];
    int at = snprintf(notes, sizeof notes, "# %s = %.12g\n# %s = %d\n# %s = %.12g\n", td_schema_csv(TD_OUT_LOOP_SPEED),
                      td_loop_speed(l), td_out_name(TD_OUT_LOOP_STABLE), td_loop_stable(l),
                      td_out_name(TD_OUT_LOOP_MAX_REAL_PART), td_loop_max_real_part(l));
    if (td_loop_sample_rate(l) > 0.0 && at > 0 && (size_t)at < sizeof notes)
        snprintf(notes + at, sizeof notes - (size_t)at, "# %s = %.12g\n", td_out_name(TD_OUT_LOOP_SAMPLE_RATE),
                 td_loop_sample_rate(l));
    csv_header(f, TD_OUT_LOOP, notes, loop, 6);
    for (k = 0; k < td_loop_frequency_count(l); k++)
        for (j = 0; j < nc; j++) {
            td_loop_sensitivity(l, j, k, &v[0], &v[1]);
            td_loop_open_loop(l, j, k, &v[2], &v[3]);
            fprintf(f, "%.12g,%d,%.12g,%.12g,%.12g,%.12g\n", td_loop_frequency(l, k), td_loop_axis(l, j), v[0], v[1],
                    v[2], v[3]);
        }
    fputc('\n', f);
    snprintf(notes, sizeof notes, "# %s = %s\n", td_out_name(TD_OUT_LOOP_SENSITIVITY_ZONE),
             zone_text(td_loop_worst_zone(l), z));
    csv_header(f, TD_OUT_LOOP_PEAKS, notes, peaks, 4);
    for (j = 0; j < nc; j++)
        fprintf(f, "%d,%.12g,%.12g,%s\n", td_loop_axis(l, j), td_loop_sensitivity_peak(l, j),
                td_loop_sensitivity_peak_frequency(l, j), zone_text(td_loop_sensitivity_zone(l, j), z));
    fputc('\n', f);
    csv_header(f, TD_OUT_LOOP_COMPLIANCE, "", comp, 4);
    for (k = 0; k < td_loop_frequency_count(l); k++)
        for (j = 0; j < na; j++) {
            td_loop_compliance(l, j, k, &v[0], &v[1]);
            fprintf(f, "%.12g,%d,%.12g,%.12g\n", td_loop_frequency(l, k), j, v[0], v[1]);
        }
    fputc('\n', f);
}

/* ---- HDF5 -------------------------------------------------------------------------------- */

/* Table `id` (re) and id + 1 (im): (frequencies, cols) from get(l, j, k). */
static int h5_table(hid_t g, const td_loop *l, td_out_id id, int cols,
                    td_status (*get)(const td_loop *, int, int, double *, double *))
{
    int nf = td_loop_frequency_count(l), k, j, ok;
    double *re = malloc((size_t)(nf * cols + 1) * sizeof *re), *im = malloc((size_t)(nf * cols + 1) * sizeof *im);
    ok = re && im;
    for (k = 0; ok && k < nf; k++)
        for (j = 0; j < cols; j++)
            get(l, j, k, &re[k * cols + j], &im[k * cols + j]);
    ok = ok && td_h5_table(g, id, H5T_NATIVE_DOUBLE, re, (hsize_t)nf, (hsize_t)cols) &&
         td_h5_table(g, (td_out_id)(id + 1), H5T_NATIVE_DOUBLE, im, (hsize_t)nf, (hsize_t)cols);
    free(re);
    free(im);
    return ok;
}

/* The per-axis lists: axis, amb_axis, sensitivity_peak, its frequency, the zones. */
static int h5_axes(hid_t g, const td_loop *l)
{
    int nc = td_loop_axis_count(l), na = td_loop_amb_axis_count(l), j, ok;
    int *ax = malloc((size_t)(nc + na + 1) * sizeof *ax);
    double *pk = malloc((size_t)(2 * nc + 1) * sizeof *pk);
    char(*zones)[2] = malloc((size_t)(nc + 1) * sizeof *zones);
    const char **zp = malloc((size_t)(nc + 1) * sizeof *zp);
    hid_t text = td_h5_text_type();
    hsize_t dims[1];
    ok = ax && pk && zones && zp && text >= 0;
    for (j = 0; ok && j < nc; j++) {
        ax[j] = td_loop_axis(l, j);
        pk[j] = td_loop_sensitivity_peak(l, j);
        pk[nc + j] = td_loop_sensitivity_peak_frequency(l, j);
        zp[j] = zone_text(td_loop_sensitivity_zone(l, j), zones[j]);
    }
    for (j = 0; ok && j < na; j++)
        ax[nc + j] = j;
    dims[0] = (hsize_t)nc;
    ok = ok && td_h5_table(g, TD_OUT_LOOP_AXIS, H5T_NATIVE_INT, ax, (hsize_t)nc, 0) &&
         td_h5_table(g, TD_OUT_LOOP_AMB_AXIS, H5T_NATIVE_INT, ax + nc, (hsize_t)na, 0) &&
         td_h5_table(g, TD_OUT_LOOP_SENSITIVITY_PEAK, H5T_NATIVE_DOUBLE, pk, (hsize_t)nc, 0) &&
         td_h5_table(g, TD_OUT_LOOP_SENSITIVITY_PEAK_FREQUENCY, H5T_NATIVE_DOUBLE, pk + nc, (hsize_t)nc, 0) &&
         td_h5_dataset(g, td_out_name(TD_OUT_LOOP_SENSITIVITY_ZONES), text, text, zp, 1, dims,
                       td_out_units(TD_OUT_LOOP_SENSITIVITY_ZONES));
    if (text >= 0)
        H5Tclose(text);
    free(ax);
    free(pk);
    free(zones);
    free(zp);
    return ok;
}

int td_loop_write_h5_group(hid_t file, const td_loop *l)
{
    const char *by_freq[7] = {td_out_name(TD_OUT_LOOP_SENSITIVITY_RE),
                              td_out_name(TD_OUT_LOOP_SENSITIVITY_IM),
                              td_out_name(TD_OUT_LOOP_OPEN_LOOP_RE),
                              td_out_name(TD_OUT_LOOP_OPEN_LOOP_IM),
                              td_out_name(TD_OUT_LOOP_COMPLIANCE_RE),
                              td_out_name(TD_OUT_LOOP_COMPLIANCE_IM),
                              NULL};
    const char *by_axis[5] = {by_freq[0], by_freq[1], by_freq[2], by_freq[3], NULL};
    const char *by_amb[3] = {by_freq[4], by_freq[5], NULL};
    char z[2];
    int nf = td_loop_frequency_count(l), k, ok;
    double *f = malloc((size_t)(nf + 1) * sizeof *f);
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_LOOP), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = f && g >= 0;
    for (k = 0; ok && k < nf; k++)
        f[k] = td_loop_frequency(l, k);
    ok = ok && td_h5_attr_double(g, td_out_name(TD_OUT_LOOP_SPEED), td_loop_speed(l)) >= 0 &&
         td_h5_attr_string(g, td_out_name(TD_OUT_LOOP_SPEED_UNITS), td_out_units(TD_OUT_LOOP_SPEED)) >= 0 &&
         td_h5_attr_int(g, td_out_name(TD_OUT_LOOP_STABLE), td_loop_stable(l)) >= 0 &&
         td_h5_attr_double(g, td_out_name(TD_OUT_LOOP_MAX_REAL_PART), td_loop_max_real_part(l)) >= 0 &&
         td_h5_attr_string(g, td_out_name(TD_OUT_LOOP_SENSITIVITY_ZONE), zone_text(td_loop_worst_zone(l), z)) >= 0;
    if (ok && td_loop_sample_rate(l) > 0.0)
        ok = td_h5_attr_double(g, td_out_name(TD_OUT_LOOP_SAMPLE_RATE), td_loop_sample_rate(l)) >= 0;
    ok = ok && td_h5_table(g, TD_OUT_LOOP_FREQUENCY, H5T_NATIVE_DOUBLE, f, (hsize_t)nf, 0);
    ok = ok && h5_table(g, l, TD_OUT_LOOP_SENSITIVITY_RE, td_loop_axis_count(l), td_loop_sensitivity) &&
         h5_table(g, l, TD_OUT_LOOP_OPEN_LOOP_RE, td_loop_axis_count(l), td_loop_open_loop) &&
         h5_table(g, l, TD_OUT_LOOP_COMPLIANCE_RE, td_loop_amb_axis_count(l), td_loop_compliance) && h5_axes(g, l);
    ok = ok && td_h5_attach(g, td_out_name(TD_OUT_LOOP_FREQUENCY), by_freq, 0) &&
         td_h5_attach(g, td_out_name(TD_OUT_LOOP_AXIS), by_axis, 1) &&
         td_h5_attach(g, td_out_name(TD_OUT_LOOP_AMB_AXIS), by_amb, 1);
    if (g >= 0)
        H5Gclose(g);
    free(f);
    return ok;
}

/* ---- JSON -------------------------------------------------------------------------------- */

static void json_number(td_text *b, double v)
{
    if (isfinite(v))
        td_text_printf(b, "%.17g", v);
    else
        td_text_printf(b, "null");
}

/* "key":[...] of the per-axis values get(l, j) (zone: the letters), null when none is defined. */
static void json_axis_list(td_text *b, td_out_id key, const td_loop *l, double (*get)(const td_loop *, int), int zone)
{
    int j, nc = td_loop_axis_count(l);
    td_text_printf(b, ",\"%s\":", td_out_name(key));
    if (!l || !td_loop_stable(l)) {
        td_text_printf(b, "null");
        return;
    }
    td_text_printf(b, "[");
    for (j = 0; j < nc; j++) {
        if (j)
            td_text_printf(b, ",");
        if (zone)
            td_text_printf(b, "\"%c\"", td_loop_sensitivity_zone(l, j));
        else
            json_number(b, get(l, j));
    }
    td_text_printf(b, "]");
}

int td_loop_json(char *buf, size_t n, const td_loop *l)
{
    td_text b;
    int j;
    char z = td_loop_worst_zone(l);
    td_text_fixed(&b, buf, n);
    td_text_printf(&b, "{\"%s\":%s,\"%s\":", td_out_name(TD_OUT_LOOP_STABLE),
                   !l                  ? "null"
                   : td_loop_stable(l) ? "true"
                                       : "false",
                   td_out_name(TD_OUT_LOOP_MAX_REAL_PART));
    json_number(&b, l ? td_loop_max_real_part(l) : NAN);
    td_text_printf(&b, ",\"%s\":", td_out_name(TD_OUT_LOOP_SPEED));
    json_number(&b, l ? td_loop_speed(l) : NAN);
    td_text_printf(&b, ",\"%s\":", td_out_name(TD_OUT_LOOP_SAMPLE_RATE));
    json_number(&b, l && td_loop_sample_rate(l) > 0.0 ? td_loop_sample_rate(l) : NAN);
    td_text_printf(&b, ",\"%s\":[", td_out_name(TD_OUT_LOOP_AXIS));
    for (j = 0; l && j < td_loop_axis_count(l); j++)
        td_text_printf(&b, "%s%d", j ? "," : "", td_loop_axis(l, j));
    td_text_printf(&b, "]");
    json_axis_list(&b, TD_OUT_LOOP_SENSITIVITY_PEAK, l, td_loop_sensitivity_peak, 0);
    json_axis_list(&b, TD_OUT_LOOP_SENSITIVITY_PEAK_FREQUENCY, l, td_loop_sensitivity_peak_frequency, 0);
    json_axis_list(&b, TD_OUT_LOOP_SENSITIVITY_ZONES, l, NULL, 1);
    if (z)
        td_text_printf(&b, ",\"%s\":\"%c\"", td_out_name(TD_OUT_LOOP_SENSITIVITY_ZONE), z);
    else
        td_text_printf(&b, ",\"%s\":null", td_out_name(TD_OUT_LOOP_SENSITIVITY_ZONE));
    td_text_printf(&b, "}");
    return (int)b.len;
}
