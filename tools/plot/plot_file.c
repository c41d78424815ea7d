/* touchdown plot: a simulation or modal result file (docs/output-format.md, lib/io/modal_writer.c)
 * loaded into memory, simulation samples cut to the time window. */
#include "plot.h"
#include "touchdown/modal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* One line "touchdown plot: PATH: message". */
static int bad(const char *path, const char *msg, int code)
{
    fprintf(stderr, "touchdown plot: %s: %s\n", path, msg);
    return code;
}

/* ---- names and titles ---------------------------------------------------------------------- */

static void make_stem(const char *path, char *stem, size_t n)
{
    const char *base = strrchr(path, '/');
    size_t len;
    base = base ? base + 1 : path;
    snprintf(stem, n, "%s", base);
    len = strlen(stem);
    if (len > 3 && !strcmp(stem + len - 3, ".h5"))
        stem[len - 3] = '\0';
    else if (len > 5 && !strcmp(stem + len - 5, ".hdf5"))
        stem[len - 5] = '\0';
    if (!stem[0])
        snprintf(stem, n, "result");
}

/* The value of the last top-level `description = "..."` line of the case text (an override is
 * appended at the end, so the last one wins); 0 if there is none. */
static int case_description(const char *text, char *out, size_t n)
{
    const char *line = text;
    int found = 0;
    while (line && *line) {
        const char *p = line, *next = strchr(line, '\n');
        while (*p == ' ' || *p == '\t')
            p++;
        if (!strncmp(p, "description", 11)) {
            p += 11;
            while (*p == ' ' || *p == '\t')
                p++;
            if (*p == '=' || *p == ':') {
                p++;
                while (*p == ' ' || *p == '\t')
                    p++;
                if (*p == '"') {
                    size_t k = 0;
                    for (p++; *p && *p != '"' && *p != '\n'; p++) {
                        if (*p == '\\' && p[1] && p[1] != '\n')
                            p++;
                        if (k + 1 < n)
                            out[k++] = *p;
                    }
                    out[k] = '\0';
                    found = k > 0;
                }
            }
        }
        line = next ? next + 1 : NULL;
    }
    return found;
}

static void make_title(plot_file *f, hid_t file)
{
    char *text = plot_h5_attr_string(file, "case_text"), *reason;
    char desc[300];
    if (!(text && case_description(text, desc, sizeof desc)))
        snprintf(desc, sizeof desc, "%s", f->stem);
    free(text);
    if (f->kind != PLOT_KIND_MODAL && f->complete == 0) {
        reason = plot_h5_attr_string(file, "incomplete_reason");
        snprintf(f->title, sizeof f->title, "%s  [INCOMPLETE: %.150s]", desc, reason ? reason : "no reason given");
        free(reason);
    } else if (f->kind != PLOT_KIND_MODAL && f->complete < 0) {
        snprintf(f->title, sizeof f->title, "%s  [no completeness flag]", desc);
    } else {
        snprintf(f->title, sizeof f->title, "%s", desc);
    }
}

/* ---- simulation files ---------------------------------------------------------------------- */

/* Read /retainers/NAME (n x nret) or fail. */
static int read_matrix(hid_t file, const char *name, size_t n, size_t cols, size_t depth, plot_array *a)
{
    if (plot_h5_read(file, name, a) != 0)
        return -1;
    if (a->dims[0] != n || a->dims[1] != cols || a->dims[2] != depth) {
        plot_array_free(a);
        return -1;
    }
    return 0;
}

/* Keep the rows of `a` (row length `len`) whose flag is set; returns the compacted array. */
static double *compact(double *v, const unsigned char *keep, size_t n, size_t len)
{
    size_t i, k = 0;
    if (!v)
        return NULL;
    for (i = 0; i < n; i++)
        if (keep[i]) {
            memmove(v + k * len, v + i * len, len * sizeof *v);
            k++;
        }
    return v;
}

/* Events inside the window: time, retainer and the kind's name from the file's enum. */
static int read_events(hid_t file, plot_sim *s, const plot_window *win)
{
    typedef struct row {
        double time;
        int retainer;
        int kind;
    } row;
    hid_t d, ftype = -1, kind_ftype = -1, kind_mtype = -1, mtype = -1, space = -1;
    hssize_t n;
    row *rows = NULL;
    int idx, rc = -1;
    size_t i;
    if (!plot_h5_exists(file, "events"))
        return 0; /* a file without events plots fine */
    if ((d = H5Dopen2(file, "events", H5P_DEFAULT)) < 0)
        return -1;
    ftype = H5Dget_type(d);
    space = H5Dget_space(d);
    n = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
    idx = ftype >= 0 ? H5Tget_member_index(ftype, "kind") : -1;
    if (idx >= 0)
        kind_ftype = H5Tget_member_type(ftype, (unsigned)idx);
    if (kind_ftype >= 0 && H5Tget_class(kind_ftype) == H5T_ENUM)
        kind_mtype = H5Tget_native_type(kind_ftype, H5T_DIR_DEFAULT);
    if (n < 0 || kind_mtype < 0 || H5Tget_size(kind_mtype) != sizeof(int))
        goto done;
    mtype = H5Tcreate(H5T_COMPOUND, sizeof(row));
    if (mtype < 0 || H5Tinsert(mtype, "time", HOFFSET(row, time), H5T_NATIVE_DOUBLE) < 0 ||
        H5Tinsert(mtype, "retainer", HOFFSET(row, retainer), H5T_NATIVE_INT) < 0 ||
        H5Tinsert(mtype, "kind", HOFFSET(row, kind), kind_mtype) < 0)
        goto done;
    rows = malloc((size_t)(n > 0 ? n : 1) * sizeof *rows);
    s->ev = malloc((size_t)(n > 0 ? n : 1) * sizeof *s->ev);
    if (!rows || !s->ev || (n > 0 && H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) < 0))
        goto done;
    for (i = 0; i < (size_t)n; i++) {
        plot_event *e = &s->ev[s->nev];
        if (rows[i].time < win->from || rows[i].time > win->to)
            continue;
        e->time = rows[i].time;
        e->retainer = rows[i].retainer;
        if (H5Tenum_nameof(kind_mtype, &rows[i].kind, e->kind, sizeof e->kind) < 0)
            snprintf(e->kind, sizeof e->kind, "unknown");
        s->nev++;
    }
    rc = 0;
done:
    free(rows);
    if (mtype >= 0)
        H5Tclose(mtype);
    if (kind_mtype >= 0)
        H5Tclose(kind_mtype);
    if (kind_ftype >= 0)
        H5Tclose(kind_ftype);
    if (ftype >= 0)
        H5Tclose(ftype);
    if (space >= 0)
        H5Sclose(space);
    H5Dclose(d);
    return rc;
}

/* Node numbers and clearances from the root attributes (absent: -1 and NAN). */
static int read_tables(hid_t file, plot_sim *s)
{
    double *v = NULL;
    size_t n = 0;
    int i;
    s->clearance = malloc((size_t)(s->nret + 1) * sizeof *s->clearance);
    s->ret_nodes = malloc((size_t)(s->nret + 1) * sizeof *s->ret_nodes);
    s->amb_nodes = malloc((size_t)(s->namb + 1) * sizeof *s->amb_nodes);
    if (!s->clearance || !s->ret_nodes || !s->amb_nodes)
        return -1;
    for (i = 0; i < s->nret; i++) {
        s->clearance[i] = NAN;
        s->ret_nodes[i] = -1;
    }
    for (i = 0; i < s->namb; i++)
        s->amb_nodes[i] = -1;
    if (plot_h5_attr_doubles(file, "retainer_clearance", &v, &n) == 0 && n == (size_t)s->nret)
        for (i = 0; i < s->nret; i++)
            s->clearance[i] = v[i];
    free(v);
    if (plot_h5_attr_doubles(file, "retainer_nodes", &v, &n) == 0 && n == (size_t)s->nret)
        for (i = 0; i < s->nret; i++)
            s->ret_nodes[i] = (long)v[i];
    free(v);
    if (plot_h5_attr_doubles(file, "amb_nodes", &v, &n) == 0 && n == (size_t)s->namb)
        for (i = 0; i < s->namb; i++)
            s->amb_nodes[i] = (long)v[i];
    free(v);
    return 0;
}

/* Retainer and AMB counts from the dataset shapes (the groups may be empty). */
static int count_columns(hid_t file, const char *path, size_t n, int *count)
{
    plot_array a;
    *count = 0;
    if (!plot_h5_exists(file, path))
        return 0;
    if (plot_h5_read(file, path, &a) != 0)
        return -1;
    if (a.dims[0] != n) {
        plot_array_free(&a);
        return -1;
    }
    *count = (int)a.dims[1];
    plot_array_free(&a);
    return 0;
}

static int load_sim(hid_t file, plot_file *f, const plot_window *win)
{
    static const char *fields[5] = {"retainers/x", "retainers/y", "retainers/radial_position", "retainers/normal_force",
                                    "retainers/contact_state"};
    plot_sim *s = &f->sim;
    plot_array t, a[5], amb;
    double **dst[5];
    unsigned char *keep = NULL;
    size_t n, i, kept = 0;
    int k, rc = PLOT_FAILED;
    memset(a, 0, sizeof a);
    memset(&amb, 0, sizeof amb);
    dst[0] = &s->x, dst[1] = &s->y, dst[2] = &s->r, dst[3] = &s->fn, dst[4] = &s->contact;
    if (plot_h5_read(file, "time", &t) != 0 || t.rank != 1)
        return bad(f->path, "unreadable /time dataset (not a touchdown simulation file?)", PLOT_BAD_INPUT);
    n = t.n;
    if (count_columns(file, "retainers/x", n, &s->nret) != 0 || count_columns(file, "ambs/force", n, &s->namb) != 0) {
        plot_array_free(&t);
        return bad(f->path, "/retainers or /ambs datasets do not match /time", PLOT_BAD_INPUT);
    }
    for (k = 0; k < 5 && s->nret > 0; k++)
        if (read_matrix(file, fields[k], n, (size_t)s->nret, 1, &a[k]) != 0) {
            rc = bad(f->path, "a /retainers dataset is missing or has the wrong shape", PLOT_BAD_INPUT);
            goto done;
        }
    if (s->namb > 0 && read_matrix(file, "ambs/force", n, (size_t)s->namb, 2, &amb) != 0) {
        rc = bad(f->path, "/ambs/force has the wrong shape", PLOT_BAD_INPUT);
        goto done;
    }
    if (!(keep = malloc(n ? n : 1)))
        goto nomem;
    for (i = 0; i < n; i++) {
        keep[i] = t.v[i] >= win->from && t.v[i] <= win->to;
        kept += keep[i];
    }
    if (kept == 0) {
        rc = bad(f->path, n ? "no samples inside the time window (--from/--to)" : "the file holds no samples",
                 PLOT_BAD_INPUT);
        goto done;
    }
    s->n = kept;
    s->t = compact(t.v, keep, n, 1);
    t.v = NULL;
    for (k = 0; k < 5; k++) {
        *dst[k] = compact(a[k].v, keep, n, (size_t)s->nret);
        a[k].v = NULL;
    }
    s->amb = compact(amb.v, keep, n, 2 * (size_t)s->namb);
    amb.v = NULL;
    if (read_tables(file, s) != 0)
        goto nomem;
    if (read_events(file, s, win) != 0) {
        rc = bad(f->path, "unreadable /events table", PLOT_BAD_INPUT);
        goto done;
    }
    rc = PLOT_OK;
    goto done;
nomem:
    rc = bad(f->path, "out of memory", PLOT_FAILED);
done:
    free(keep);
    plot_array_free(&t);
    plot_array_free(&amb);
    for (k = 0; k < 5; k++)
        plot_array_free(&a[k]);
    return rc;
}

/* ---- modal files --------------------------------------------------------------------------- */

/* Dataset `path` as a new array of `n` doubles (NULL when absent or of another size). */
static double *read_vector(hid_t file, const char *path, size_t n)
{
    plot_array a;
    if (plot_h5_read(file, path, &a) != 0)
        return NULL;
    if (a.n != n) {
        plot_array_free(&a);
        return NULL;
    }
    return a.v;
}

static int load_campbell(hid_t file, plot_modal *m)
{
    plot_array f;
    if (!plot_h5_exists(file, "campbell/freq_hz"))
        return 0;
    if (plot_h5_read(file, "campbell/freq_hz", &f) != 0 || f.rank != 2)
        return -1;
    m->ns = (int)f.dims[0];
    m->nb = (int)f.dims[1];
    m->freq = f.v;
    m->speed = read_vector(file, "campbell/speed", (size_t)m->ns);
    m->whirl = read_vector(file, "campbell/whirl", (size_t)m->ns * (size_t)m->nb);
    return m->speed && m->whirl ? 0 : -1;
}

static int load_critical(hid_t file, plot_modal *m)
{
    plot_array s;
    if (!plot_h5_exists(file, "critical_speeds/speed"))
        return 0;
    if (plot_h5_read(file, "critical_speeds/speed", &s) != 0 || s.rank != 1)
        return -1;
    m->ncrit = (int)s.n;
    m->crit_speed = s.v;
    m->crit_freq = read_vector(file, "critical_speeds/freq_hz", s.n);
    m->crit_whirl = read_vector(file, "critical_speeds/whirl", s.n);
    return m->crit_freq && m->crit_whirl ? 0 : -1;
}

/* Axial node positions, if the file has them (dataset /modes/node_z or /node_z, m). */
static double *node_positions(hid_t file, size_t nn)
{
    double *z = read_vector(file, "modes/node_z", nn);
    return z ? z : read_vector(file, "node_z", nn);
}

/* Keep only vibration modes: the overdamped AMB-lag pairs (see touchdown/modal.h) have no
 * meaningful shape along the rotor. */
static void drop_overdamped(plot_modal *m)
{
    int i, k, kept = 0;
    for (i = 0; i < m->nm; i++) {
        td_mode md;
        md.zeta = m->mode_zeta ? m->mode_zeta[i] : 0.0;
        if (!td_mode_is_vibration(&md))
            continue;
        for (k = 0; k < m->nn; k++) {
            size_t to = (size_t)kept * (size_t)m->nn + (size_t)k, from = (size_t)i * (size_t)m->nn + (size_t)k;
            m->xr[to] = m->xr[from], m->xi[to] = m->xi[from], m->yr[to] = m->yr[from], m->yi[to] = m->yi[from];
        }
        m->mode_freq[kept] = m->mode_freq[i];
        m->mode_whirl[kept] = m->mode_whirl[i];
        if (m->mode_zeta)
            m->mode_zeta[kept] = m->mode_zeta[i];
        kept++;
    }
    m->nm = kept;
}

static int load_shapes(hid_t file, plot_modal *m)
{
    plot_array xr;
    hid_t g;
    size_t total;
    if (!plot_h5_exists(file, "modes/shape_x_re"))
        return 0;
    if (plot_h5_read(file, "modes/shape_x_re", &xr) != 0 || xr.rank != 2)
        return -1;
    m->nm = (int)xr.dims[0];
    m->nn = (int)xr.dims[1];
    m->xr = xr.v;
    total = (size_t)m->nm * (size_t)m->nn;
    m->xi = read_vector(file, "modes/shape_x_im", total);
    m->yr = read_vector(file, "modes/shape_y_re", total);
    m->yi = read_vector(file, "modes/shape_y_im", total);
    m->mode_freq = read_vector(file, "modes/freq_hz", (size_t)m->nm);
    m->mode_whirl = read_vector(file, "modes/whirl", (size_t)m->nm);
    m->mode_zeta = read_vector(file, "modes/zeta", (size_t)m->nm);
    m->node_z = node_positions(file, (size_t)m->nn);
    m->mode_speed = NAN;
    if ((g = H5Gopen2(file, "modes", H5P_DEFAULT)) >= 0) {
        plot_h5_attr_double(g, "speed", &m->mode_speed);
        H5Gclose(g);
    }
    if (!(m->xi && m->yr && m->yi && m->mode_freq && m->mode_whirl))
        return -1;
    drop_overdamped(m);
    return 0;
}

static int load_modal(hid_t file, plot_file *f)
{
    plot_modal *m = &f->modal;
    if (load_campbell(file, m) != 0)
        return bad(f->path, "unreadable /campbell group", PLOT_BAD_INPUT);
    if (load_critical(file, m) != 0)
        return bad(f->path, "unreadable /critical_speeds group", PLOT_BAD_INPUT);
    if (load_shapes(file, m) != 0)
        return bad(f->path, "unreadable /modes group", PLOT_BAD_INPUT);
    if (m->ns == 0 && m->nm == 0)
        return bad(f->path, "the modal file holds neither a Campbell diagram nor mode shapes", PLOT_BAD_INPUT);
    return PLOT_OK;
}

/* ---- entry --------------------------------------------------------------------------------- */

static int is_modal(hid_t file)
{
    char *producer = plot_h5_attr_string(file, "producer");
    int yes = producer && strstr(producer, "modal") != NULL;
    free(producer);
    return yes || plot_h5_exists(file, "campbell") || plot_h5_exists(file, "modes");
}

int plot_file_load(const char *path, const plot_window *win, plot_file *f)
{
    FILE *probe;
    hid_t file;
    htri_t is_h5;
    double flag;
    int rc;
    memset(f, 0, sizeof *f);
    f->path = path;
    make_stem(path, f->stem, sizeof f->stem);
    if (!(probe = fopen(path, "rb")))
        return bad(path, strerror(errno), PLOT_BAD_INPUT);
    fclose(probe);
    is_h5 = H5Fis_hdf5(path);
    if (is_h5 <= 0)
        return bad(path,
                   "not an HDF5 file (touchdown plot reads the .h5 files of 'touchdown run' and 'touchdown modal')",
                   PLOT_BAD_INPUT);
    if ((file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0)
        return bad(path, "cannot open the HDF5 file", PLOT_BAD_INPUT);
    if (plot_sweep_is_table(file)) {
        f->kind = PLOT_KIND_SWEEP;
        f->complete = plot_h5_attr_double(file, "complete", &flag) == 0 ? flag != 0.0 : -1;
        rc = plot_sweep_load(file, f);
    } else if (plot_h5_exists(file, "time") && plot_h5_exists(file, "retainers")) {
        f->kind = PLOT_KIND_SIM;
        f->complete = plot_h5_attr_double(file, "complete", &flag) == 0 ? flag != 0.0 : -1;
        rc = load_sim(file, f, win);
    } else if (is_modal(file)) {
        f->kind = PLOT_KIND_MODAL;
        f->complete = 1;
        rc = load_modal(file, f);
    } else {
        rc =
            bad(path,
                "not a touchdown result file (neither /time and /retainers, /campbell or /modes, nor /point and /vary)",
                PLOT_BAD_INPUT);
    }
    if (rc == PLOT_OK)
        make_title(f, file);
    H5Fclose(file);
    if (rc != PLOT_OK)
        plot_file_free(f);
    return rc;
}

void plot_file_free(plot_file *f)
{
    plot_sim *s = &f->sim;
    plot_modal *m = &f->modal;
    free(s->t), free(s->x), free(s->y), free(s->r), free(s->fn), free(s->contact), free(s->amb);
    free(s->clearance), free(s->ret_nodes), free(s->amb_nodes), free(s->ev);
    free(m->speed), free(m->freq), free(m->whirl), free(m->crit_speed), free(m->crit_freq), free(m->crit_whirl);
    free(m->mode_freq), free(m->mode_whirl), free(m->mode_zeta), free(m->xr), free(m->xi), free(m->yr), free(m->yi);
    free(m->node_z);
    plot_sweep_free(&f->sweep);
    memset(s, 0, sizeof *s);
    memset(m, 0, sizeof *m);
}
