/*
 * Writers of modal results (touchdown/modal_output.h): one CSV file with sections, or one HDF5
 * file with a group per part and a "units" attribute on every dataset. Numbers carry 12
 * significant digits in CSV ("%.12g") and full double precision in HDF5. HDF5 axes are dimension
 * scales (the Campbell speeds, branch and mode numbers, node positions) so netCDF readers see
 * named dimensions; strings are variable-length UTF-8, which h5py reads as str. The HDF5
 * conventions and helpers are the simulation writer's (h5_util.h).
 * Like the simulation writers, both write PATH.XXXXXX.partial (td_io_create_temp) and rename it
 * to PATH only once every byte is on disk, so a file at PATH is always whole; the file goes
 * through the writers' HDF5 driver (h5_vfd.h) so that no I/O error is lost.
 */
#include "io/api617_output.h"
#include "io/h5_util.h"
#include "io/h5_vfd.h"
#include "io/loop_output.h"
#include "io/schema.h"
#include "io/writer_internal.h"
#include "touchdown/modal_output.h"
#include "util/error_internal.h"

#include <hdf5.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* ---- CSV --------------------------------------------------------------------------------- */

/* "# section: NAME" of the section `id`. */
static void csv_section(FILE *f, td_out_id id)
{
    fprintf(f, "# section: %s\n", td_out_name(id));
}

/* A section's header line: the CSV names of its columns (td_schema_csv). */
static void csv_columns(FILE *f, const td_out_id *cols, int n)
{
    int i;
    for (i = 0; i < n; i++)
        fprintf(f, "%s%s", i ? "," : "", td_schema_csv(cols[i]));
    fputc('\n', f);
}

static void csv_modes(FILE *f, const td_modal *m)
{
    static const td_out_id modes[] = {TD_OUT_MODES_MODE,        TD_OUT_MODES_SIGMA,   TD_OUT_MODES_OMEGA_D,
                                      TD_OUT_MODES_FREQ_HZ,     TD_OUT_MODES_OMEGA_N, TD_OUT_MODES_ZETA,
                                      TD_OUT_MODES_WHIRL_INDEX, TD_OUT_MODES_WHIRL,   TD_OUT_MODES_LOG_DECREMENT};
    static const td_out_id reals[] = {TD_OUT_MODAL_INDEX, TD_OUT_MODES_REAL_EIGENVALUES};
    static const td_out_id shapes[] = {TD_OUT_MODES_MODE,       TD_OUT_MODAL_NODE,       TD_OUT_MODES_SHAPE_X_RE,
                                       TD_OUT_MODES_SHAPE_X_IM, TD_OUT_MODES_SHAPE_Y_RE, TD_OUT_MODES_SHAPE_Y_IM};
    int i, k, nn = td_modal_node_count(m);
    double *s = malloc(4u * (size_t)(nn > 0 ? nn : 1) * sizeof *s);
    csv_section(f, TD_OUT_MODES);
    fprintf(f, "# %s = %.12g\n", td_schema_csv(TD_OUT_MODES_SPEED), td_modal_speed(m));
    csv_columns(f, modes, 9);
    for (i = 0; i < td_modal_mode_count(m); i++) {
        td_mode md;
        td_modal_get_mode(m, i, &md);
        fprintf(f, "%d,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%s,%.12g\n", i, md.sigma, md.omega_d, md.freq_hz, md.omega_n,
                md.zeta, md.whirl_index, td_whirl_name(md.whirl), td_log_decrement(md.zeta));
    }
    fputc('\n', f);
    csv_section(f, TD_OUT_MODES_REAL_EIGENVALUES);
    csv_columns(f, reals, 2);
    for (i = 0; i < td_modal_real_count(m); i++)
        fprintf(f, "%d,%.12g\n", i, td_modal_real_eigenvalue(m, i));
    fputc('\n', f);
    csv_section(f, TD_OUT_MODAL_MODE_SHAPES);
    csv_columns(f, shapes, 6);
    for (i = 0; s && i < td_modal_mode_count(m); i++) {
        td_modal_mode_shape(m, i, s, s + nn, s + 2 * nn, s + 3 * nn);
        for (k = 0; k < nn; k++)
            fprintf(f, "%d,%d,%.12g,%.12g,%.12g,%.12g\n", i, k, s[k], s[nn + k], s[2 * nn + k], s[3 * nn + k]);
    }
    fprintf(f, "\n");
    free(s);
}

static void csv_campbell(FILE *f, const td_campbell *c)
{
    static const td_out_id cols[] = {TD_OUT_CAMPBELL_SPEED,   TD_OUT_CAMPBELL_BRANCH, TD_OUT_CAMPBELL_OMEGA_D,
                                     TD_OUT_CAMPBELL_FREQ_HZ, TD_OUT_CAMPBELL_SIGMA,  TD_OUT_CAMPBELL_ZETA,
                                     TD_OUT_CAMPBELL_WHIRL,   TD_OUT_CAMPBELL_MAC};
    int k, j;
    csv_section(f, TD_OUT_CAMPBELL);
    csv_columns(f, cols, 8);
    for (k = 0; k < td_campbell_speed_count(c); k++)
        for (j = 0; j < td_campbell_branch_count(c); j++) {
            td_mode md;
            td_campbell_get(c, k, j, &md);
            fprintf(f, "%.12g,%d,%.12g,%.12g,%.12g,%.12g,%s,%.12g\n", td_campbell_speed(c, k), j, md.omega_d,
                    md.freq_hz, md.sigma, md.zeta, td_whirl_name(md.whirl), td_campbell_mac(c, k, j));
        }
    fprintf(f, "\n");
}

static void csv_critical(FILE *f, const td_critical_speed *cs, int n)
{
    static const td_out_id cols[] = {TD_OUT_CRITICAL_SPEED,  TD_OUT_CRITICAL_FREQ_HZ, TD_OUT_CRITICAL_WHIRL,
                                     TD_OUT_CRITICAL_BRANCH, TD_OUT_CRITICAL_ZETA,    TD_OUT_CRITICAL_SIGMA};
    int i;
    csv_section(f, TD_OUT_CRITICAL);
    csv_columns(f, cols, 6);
    for (i = 0; i < n; i++)
        fprintf(f, "%.12g,%.12g,%s,%d,%.12g,%.12g\n", cs[i].speed, cs[i].freq_hz, td_whirl_name(cs[i].whirl),
                cs[i].branch, cs[i].zeta, cs[i].sigma);
    fprintf(f, "\n");
}

static void csv_harmonic(FILE *f, const td_harmonic *const *h, int n)
{
    static const td_out_id cols[] = {TD_OUT_HARMONIC_SPEED,   TD_OUT_MODAL_NODE,        TD_OUT_HARMONIC_X_AMP,
                                     TD_OUT_HARMONIC_X_PHASE, TD_OUT_HARMONIC_Y_AMP,    TD_OUT_HARMONIC_Y_PHASE,
                                     TD_OUT_HARMONIC_FORWARD, TD_OUT_HARMONIC_BACKWARD, TD_OUT_HARMONIC_MAJOR,
                                     TD_OUT_HARMONIC_MINOR};
    int i, k;
    csv_section(f, TD_OUT_HARMONIC);
    csv_columns(f, cols, 10);
    for (i = 0; i < n; i++)
        for (k = 0; h[i] && k < td_harmonic_node_count(h[i]); k++) {
            td_orbit o;
            td_harmonic_orbit(h[i], k, &o);
            fprintf(f, "%.12g,%d,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", td_harmonic_speed(h[i]), k,
                    o.x_amp, o.x_phase, o.y_amp, o.y_phase, o.forward, o.backward, o.major, o.minor);
        }
    fprintf(f, "\n");
}

/* Every section into `f`; a failed write shows in the stream's error flag. */
static void csv_write_all(FILE *f, const td_modal_results *r)
{
    fprintf(f, "# touchdown modal results\n\n");
    if (r->modes)
        csv_modes(f, r->modes);
    if (r->campbell)
        csv_campbell(f, r->campbell);
    if (r->critical)
        csv_critical(f, r->critical, r->n_critical);
    if (r->n_harmonics > 0)
        csv_harmonic(f, r->harmonics, r->n_harmonics);
    if (r->loop)
        td_loop_write_csv_sections(f, r->loop);
    td_api617_write_csv_sections(f, r);
}

static td_status check_results(const td_modal_results *r, const char *what, td_error *err)
{
    if (r->n_critical < 0 || (r->n_critical > 0 && !r->critical) || r->n_harmonics < 0 ||
        (r->n_harmonics > 0 && !r->harmonics))
        return td_error_set(err, TD_ERR_INVALID, "%s: bad result counts", what);
    return TD_OK;
}

static void csv_write_results(FILE *f, const void *r)
{
    csv_write_all(f, r);
}

td_status td_modal_write_csv(const char *path, const td_modal_results *r, td_error *err)
{
    td_status st;
    if (!path || !r)
        return td_error_set(err, TD_ERR_INVALID, "td_modal_write_csv: NULL argument");
    if ((st = check_results(r, "td_modal_write_csv", err)) != TD_OK)
        return st;
    return td_io_write_text_file(path, csv_write_results, r, err);
}

/* ---- HDF5 -------------------------------------------------------------------------------- */

/* The index dataset `id` 0..n-1 with its units (td_h5_index). */
static int h5_index(hid_t group, td_out_id id, int n)
{
    return td_h5_index(group, td_out_name(id), n, td_out_units(id));
}

/* Make `scale` a dimension scale of axis `axis` of the datasets ids[0 .. n) (td_h5_attach). */
static int h5_attach(hid_t group, td_out_id scale, const td_out_id *ids, int n, unsigned axis)
{
    const char *names[16];
    int i;
    for (i = 0; i < n && i < 15; i++)
        names[i] = td_out_name(ids[i]);
    names[i] = NULL;
    return td_h5_attach(group, td_out_name(scale), n > 0 ? names : NULL, axis);
}

/* The mode-shape datasets: rows modes, columns nodes. */
static const td_out_id shape_ids[4] = {TD_OUT_MODES_SHAPE_X_RE, TD_OUT_MODES_SHAPE_X_IM, TD_OUT_MODES_SHAPE_Y_RE,
                                       TD_OUT_MODES_SHAPE_Y_IM};

/* Columns of a td_mode array, gathered one field at a time. */
enum mode_field { F_SIGMA, F_OMEGA_D, F_FREQ, F_OMEGA_N, F_ZETA, F_WHIRL_INDEX };

static double mode_field(const td_mode *m, int field)
{
    switch (field) {
    case F_SIGMA: return m->sigma;
    case F_OMEGA_D: return m->omega_d;
    case F_FREQ: return m->freq_hz;
    case F_OMEGA_N: return m->omega_n;
    case F_ZETA: return m->zeta;
    default: return m->whirl_index;
    }
}

/* The mode table of a group: its first id (sigma; the fields F_SIGMA .. F_WHIRL_INDEX follow in
 * order, then the int whirl). */
#define MODE_TABLE_SIZE 7

/* Attach the scale g/scale to axis `axis` of every dataset h5_mode_table writes. */
static int h5_mode_table_axis(hid_t g, td_out_id first, td_out_id scale, unsigned axis)
{
    td_out_id ids[MODE_TABLE_SIZE];
    int f;
    for (f = 0; f < MODE_TABLE_SIZE; f++)
        ids[f] = (td_out_id)(first + f);
    return h5_attach(g, scale, ids, MODE_TABLE_SIZE, axis);
}

/* Write the td_mode fields of `modes` (count rows x cols, cols 0: 1-D) plus the int whirl dataset
 * as the mode table starting at `first`. */
static int h5_mode_table(hid_t g, td_out_id first, const td_mode *modes, hsize_t rows, hsize_t cols)
{
    size_t n = (size_t)rows * (size_t)(cols ? cols : 1), i;
    double *d = malloc((n ? n : 1) * sizeof *d);
    int *w = malloc((n ? n : 1) * sizeof *w);
    int ok = d && w, f;
    for (f = 0; ok && f < 6; f++) {
        for (i = 0; i < n; i++)
            d[i] = mode_field(&modes[i], f);
        ok = td_h5_table(g, (td_out_id)(first + f), H5T_NATIVE_DOUBLE, d, rows, cols);
    }
    for (i = 0; ok && i < n; i++)
        w[i] = (int)modes[i].whirl;
    ok = ok && td_h5_table(g, (td_out_id)(first + MODE_TABLE_SIZE - 1), H5T_NATIVE_INT, w, rows, cols);
    free(d);
    free(w);
    return ok;
}

static int h5_modes(hid_t file, const td_modal *m)
{
    int nm = td_modal_mode_count(m), nr = td_modal_real_count(m), nn = td_modal_node_count(m), i, ok;
    td_mode *modes = malloc((size_t)(nm ? nm : 1) * sizeof *modes);
    double *real = malloc((size_t)(nr ? nr : 1) * sizeof *real);
    double *sh = malloc(4u * (size_t)(nm ? nm : 1) * (size_t)(nn ? nn : 1) * sizeof *sh);
    double *part = malloc((size_t)(nm ? nm : 1) * (size_t)(nn ? nn : 1) * sizeof *part);
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_MODES), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = modes && real && sh && part && g >= 0;
    for (i = 0; ok && i < nm; i++) {
        td_modal_get_mode(m, i, &modes[i]);
        td_modal_mode_shape(m, i, sh + (size_t)(4 * i) * (size_t)nn, sh + (size_t)(4 * i + 1) * (size_t)nn,
                            sh + (size_t)(4 * i + 2) * (size_t)nn, sh + (size_t)(4 * i + 3) * (size_t)nn);
    }
    for (i = 0; ok && i < nr; i++)
        real[i] = td_modal_real_eigenvalue(m, i);
    ok = ok && td_h5_attr_double(g, td_out_name(TD_OUT_MODES_SPEED), td_modal_speed(m)) >= 0 &&
         td_h5_attr_string(g, td_out_name(TD_OUT_MODES_SPEED_UNITS), td_out_units(TD_OUT_MODES_SPEED)) >= 0;
    ok = ok && h5_mode_table(g, TD_OUT_MODES_SIGMA, modes, (hsize_t)nm, 0);
    ok = ok && td_h5_table(g, TD_OUT_MODES_REAL_EIGENVALUES, H5T_NATIVE_DOUBLE, real, (hsize_t)nr, 0);
    ok = ok && h5_attach(g, TD_OUT_MODES_REAL_EIGENVALUES, NULL, 0, 0); /* its own axis */
    for (i = 0; ok && i < 4; i++) {
        int k, j;
        for (k = 0; k < nm; k++)
            for (j = 0; j < nn; j++)
                part[(size_t)k * (size_t)nn + (size_t)j] = sh[(size_t)(4 * k + i) * (size_t)nn + (size_t)j];
        ok = td_h5_table(g, shape_ids[i], H5T_NATIVE_DOUBLE, part, (hsize_t)nm, (hsize_t)nn);
    }
    ok = ok && h5_index(g, TD_OUT_MODES_MODE, nm) && h5_mode_table_axis(g, TD_OUT_MODES_SIGMA, TD_OUT_MODES_MODE, 0) &&
         h5_attach(g, TD_OUT_MODES_MODE, shape_ids, 4, 0);
    if (g >= 0)
        H5Gclose(g);
    free(modes);
    free(real);
    free(sh);
    free(part);
    return ok;
}

static int h5_campbell(hid_t file, const td_campbell *c)
{
    int ns = td_campbell_speed_count(c), nb = td_campbell_branch_count(c), k, j, ok;
    td_mode *pts = malloc((size_t)(ns ? ns : 1) * (size_t)(nb ? nb : 1) * sizeof *pts);
    double *mac = malloc((size_t)(ns ? ns : 1) * (size_t)(nb ? nb : 1) * sizeof *mac);
    double *sp = malloc((size_t)(ns ? ns : 1) * sizeof *sp);
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_CAMPBELL), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = pts && mac && sp && g >= 0;
    for (k = 0; ok && k < ns; k++) {
        sp[k] = td_campbell_speed(c, k);
        for (j = 0; j < nb; j++) {
            td_campbell_get(c, k, j, &pts[(size_t)k * (size_t)nb + (size_t)j]);
            mac[(size_t)k * (size_t)nb + (size_t)j] = td_campbell_mac(c, k, j);
        }
    }
    ok = ok && td_h5_table(g, TD_OUT_CAMPBELL_SPEED, H5T_NATIVE_DOUBLE, sp, (hsize_t)ns, 0);
    ok = ok && h5_mode_table(g, TD_OUT_CAMPBELL_SIGMA, pts, (hsize_t)ns, (hsize_t)nb);
    ok = ok && td_h5_table(g, TD_OUT_CAMPBELL_MAC, H5T_NATIVE_DOUBLE, mac, (hsize_t)ns, (hsize_t)nb);
    ok = ok && td_h5_attr_string(g, td_out_name(TD_OUT_CAMPBELL_LAYOUT),
                                 "rows: speeds, columns: branches (tracked by MAC from the j-th lowest omega_d at "
                                 "the first speed)") >= 0;
    ok = ok && h5_index(g, TD_OUT_CAMPBELL_BRANCH, nb);
    ok = ok && h5_mode_table_axis(g, TD_OUT_CAMPBELL_SIGMA, TD_OUT_CAMPBELL_SPEED, 0) &&
         h5_mode_table_axis(g, TD_OUT_CAMPBELL_SIGMA, TD_OUT_CAMPBELL_BRANCH, 1);
    ok = ok && h5_attach(g, TD_OUT_CAMPBELL_SPEED, (const td_out_id[]){TD_OUT_CAMPBELL_MAC}, 1, 0) &&
         h5_attach(g, TD_OUT_CAMPBELL_BRANCH, (const td_out_id[]){TD_OUT_CAMPBELL_MAC}, 1, 1);
    if (g >= 0)
        H5Gclose(g);
    free(pts);
    free(mac);
    free(sp);
    return ok;
}

static int h5_critical(hid_t file, const td_critical_speed *cs, int n)
{
    static const td_out_id critical_ids[] = {TD_OUT_CRITICAL_FREQ_HZ, TD_OUT_CRITICAL_ZETA, TD_OUT_CRITICAL_SIGMA,
                                             TD_OUT_CRITICAL_WHIRL, TD_OUT_CRITICAL_BRANCH};
    double *d = malloc((size_t)(n ? n : 1) * 4u * sizeof *d);
    int *w = malloc((size_t)(n ? n : 1) * 2u * sizeof *w), i, ok;
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_CRITICAL), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = d && w && g >= 0;
    for (i = 0; ok && i < n; i++) {
        d[i] = cs[i].speed;
        d[n + i] = cs[i].freq_hz;
        d[2 * n + i] = cs[i].zeta;
        d[3 * n + i] = cs[i].sigma;
        w[i] = (int)cs[i].whirl;
        w[n + i] = cs[i].branch;
    }
    ok = ok && td_h5_table(g, TD_OUT_CRITICAL_SPEED, H5T_NATIVE_DOUBLE, d, (hsize_t)n, 0);
    ok = ok && td_h5_table(g, TD_OUT_CRITICAL_FREQ_HZ, H5T_NATIVE_DOUBLE, d + n, (hsize_t)n, 0);
    ok = ok && td_h5_table(g, TD_OUT_CRITICAL_ZETA, H5T_NATIVE_DOUBLE, d + 2 * n, (hsize_t)n, 0);
    ok = ok && td_h5_table(g, TD_OUT_CRITICAL_SIGMA, H5T_NATIVE_DOUBLE, d + 3 * n, (hsize_t)n, 0);
    ok = ok && td_h5_table(g, TD_OUT_CRITICAL_WHIRL, H5T_NATIVE_INT, w, (hsize_t)n, 0);
    ok = ok && td_h5_table(g, TD_OUT_CRITICAL_BRANCH, H5T_NATIVE_INT, w + n, (hsize_t)n, 0);
    ok = ok && h5_attach(g, TD_OUT_CRITICAL_SPEED, critical_ids, 5, 0);
    if (g >= 0)
        H5Gclose(g);
    free(d);
    free(w);
    return ok;
}

static int h5_harmonic_one(hid_t parent, int index, const td_harmonic *h)
{
    static const td_out_id cols[8] = {TD_OUT_HARMONIC_X_AMP,   TD_OUT_HARMONIC_X_PHASE, TD_OUT_HARMONIC_Y_AMP,
                                      TD_OUT_HARMONIC_Y_PHASE, TD_OUT_HARMONIC_FORWARD, TD_OUT_HARMONIC_BACKWARD,
                                      TD_OUT_HARMONIC_MAJOR,   TD_OUT_HARMONIC_MINOR};
    static const td_out_id states[2] = {TD_OUT_HARMONIC_STATE_RE, TD_OUT_HARMONIC_STATE_IM};
    int nn = td_harmonic_node_count(h), ns = td_harmonic_state_count(h), k, c, ok;
    double *d = malloc((size_t)(nn > ns ? nn : ns) * 2u * sizeof *d);
    char name[32];
    hid_t g;
    snprintf(name, sizeof name, "%d", index);
    g = H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = d && g >= 0 && td_h5_attr_double(g, td_out_name(TD_OUT_HARMONIC_SPEED), td_harmonic_speed(h)) >= 0 &&
         td_h5_attr_string(g, td_out_name(TD_OUT_HARMONIC_SPEED_UNITS), td_out_units(TD_OUT_HARMONIC_SPEED)) >= 0;
    for (c = 0; ok && c < 8; c++) {
        for (k = 0; k < nn; k++) {
            td_orbit o;
            double v[8];
            td_harmonic_orbit(h, k, &o);
            v[0] = o.x_amp, v[1] = o.x_phase, v[2] = o.y_amp, v[3] = o.y_phase;
            v[4] = o.forward, v[5] = o.backward, v[6] = o.major, v[7] = o.minor;
            d[k] = v[c];
        }
        ok = td_h5_table(g, cols[c], H5T_NATIVE_DOUBLE, d, (hsize_t)nn, 0);
    }
    for (k = 0; ok && k < ns; k++)
        td_harmonic_state(h, k, &d[k], &d[ns + k]);
    ok = ok && td_h5_table(g, TD_OUT_HARMONIC_STATE_RE, H5T_NATIVE_DOUBLE, d, (hsize_t)ns, 0);
    ok = ok && td_h5_table(g, TD_OUT_HARMONIC_STATE_IM, H5T_NATIVE_DOUBLE, d + ns, (hsize_t)ns, 0);
    ok = ok && h5_index(g, TD_OUT_HARMONIC_NODE, nn) && h5_attach(g, TD_OUT_HARMONIC_NODE, cols, 8, 0);
    ok = ok && h5_index(g, TD_OUT_HARMONIC_STATE, ns) && h5_attach(g, TD_OUT_HARMONIC_STATE, states, 2, 0);
    if (g >= 0)
        H5Gclose(g);
    free(d);
    return ok;
}

static int h5_harmonics(hid_t file, const td_harmonic *const *h, int n)
{
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_HARMONIC), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int ok = g >= 0, i;
    for (i = 0; ok && i < n; i++)
        ok = !h[i] || h5_harmonic_one(g, i, h[i]);
    if (g >= 0)
        H5Gclose(g);
    return ok;
}

/* Where the nodes and bearings are: node axial positions for mode-shape plots, the retainer and
 * AMB nodes to mark on them. */
static int h5_layout(hid_t file, const td_model *model)
{
    int nn = td_model_node_count(model), nr = td_model_retainer_count(model), na = td_model_amb_count(model);
    int i, ok;
    double *z = malloc((size_t)(nn ? nn : 1) * sizeof *z);
    int *nodes = malloc((size_t)(nr + na ? nr + na : 1) * sizeof *nodes);
    hid_t g = H5Gopen2(file, td_out_name(TD_OUT_MODES), H5P_DEFAULT);
    ok = z && nodes && g >= 0;
    for (i = 0; ok && i < nn; i++)
        z[i] = td_model_node_position(model, i);
    for (i = 0; ok && i < nr; i++) {
        td_retainer r;
        td_model_get_retainer(model, i, &r);
        nodes[i] = r.node;
    }
    for (i = 0; ok && i < na; i++) {
        td_amb a;
        td_model_get_amb(model, i, &a);
        nodes[nr + i] = a.node;
    }
    ok = ok && td_h5_table(g, TD_OUT_MODES_NODE_Z, H5T_NATIVE_DOUBLE, z, (hsize_t)nn, 0);
    ok = ok && (nr == 0 || td_h5_table(g, TD_OUT_MODES_RETAINER_NODES, H5T_NATIVE_INT, nodes, (hsize_t)nr, 0));
    ok = ok && (na == 0 || td_h5_table(g, TD_OUT_MODES_AMB_NODES, H5T_NATIVE_INT, nodes + nr, (hsize_t)na, 0));
    /* node_z is the column axis of the mode shapes; the bearing lists are their own axes */
    ok = ok && h5_attach(g, TD_OUT_MODES_NODE_Z, shape_ids, 4, 1);
    ok = ok && (nr == 0 || h5_attach(g, TD_OUT_MODES_RETAINER_NODES, NULL, 0, 0)) &&
         (na == 0 || h5_attach(g, TD_OUT_MODES_AMB_NODES, NULL, 0, 0));
    if (g >= 0)
        H5Gclose(g);
    free(z);
    free(nodes);
    return ok;
}

/* Every part into the open file; the first part that fails, NULL when every call succeeded. */
static const char *h5_parts(hid_t file, const td_modal_results *r)
{
    if (td_h5_attr_string(file, td_out_name(TD_OUT_PRODUCER), "touchdown modal analysis") < 0)
        return "the producer attribute";
    if (r->modes && !h5_modes(file, r->modes))
        return "/modes";
    if (r->campbell && !h5_campbell(file, r->campbell))
        return "/campbell";
    if (r->critical && !h5_critical(file, r->critical, r->n_critical))
        return "/critical_speeds";
    if (r->n_harmonics > 0 && !h5_harmonics(file, r->harmonics, r->n_harmonics))
        return "/harmonic";
    if (r->loop && !td_loop_write_h5_group(file, r->loop))
        return "/loop";
    if (r->model && r->modes && !h5_layout(file, r->model))
        return "the node layout in /modes";
    if (r->case_text && td_h5_attr_string(file, td_out_name(TD_OUT_CASE_TEXT), r->case_text) < 0)
        return "the case_text attribute";
    return td_api617_write_h5(file, r);
}

/* Create the temporary file `tmp` on the writers' driver (h5_vfd.h: an I/O error goes to
 * io_errno, never into a failed close), write every part and close it; the first failure, with
 * its cause, goes to err. */
static td_status h5_write_all(const char *tmp, const td_modal_results *r, td_error *err)
{
    int io_errno = 0;
    hid_t driver;
    hid_t file = td_h5_create_file(tmp, 0, &io_errno, &driver);
    const char *part = file >= 0 ? h5_parts(file, r) : NULL;
    char what[64];
    td_status st = TD_OK;
    if (file < 0)
        st = td_h5_fail(err, tmp, io_errno, "cannot create the HDF5 file");
    else if (part || io_errno) {
        snprintf(what, sizeof what, "cannot write %s", part ? part : "the HDF5 file");
        st = td_h5_fail(err, tmp, io_errno, what);
    }
    if (file >= 0 && (H5Fclose(file) < 0 || io_errno) && st == TD_OK)
        st = td_h5_fail(err, tmp, io_errno, "cannot close the HDF5 file");
    td_h5_vfd_release(driver);
    return st;
}

static td_status h5_write_results(const char *tmp, const void *r, td_error *err)
{
    td_status st;
    /* HDF5 would print its error stack; the try block silences it only for this call */
    H5E_BEGIN_TRY
    {
        st = h5_write_all(tmp, r, err);
    }
    H5E_END_TRY;
    return st;
}

td_status td_modal_write_hdf5(const char *path, const td_modal_results *r, td_error *err)
{
    td_status st;
    if (!path || !r)
        return td_error_set(err, TD_ERR_INVALID, "td_modal_write_hdf5: NULL argument");
    if ((st = check_results(r, "td_modal_write_hdf5", err)) != TD_OK)
        return st;
    return td_io_write_named_file(path, h5_write_results, r, err);
}
