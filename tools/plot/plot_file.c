/* touchdown plot: a simulation or modal result file (docs/output-format.md, lib/io/modal_writer.c)
 * loaded into memory, simulation samples cut to the time window. */
#include "plot/plot.h"
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

static void make_title(plot_file *f, const td_result *r)
{
    char *text = NULL, *reason = NULL;
    char desc[300];
    td_result_read_text(r, TD_OUT_CASE_TEXT, NULL, &text, NULL);
    if (!(text && case_description(text, desc, sizeof desc)))
        snprintf(desc, sizeof desc, "%s", f->stem);
    free(text);
    if (f->kind != PLOT_KIND_MODAL && f->complete == 0) {
        td_result_read_text(r, TD_OUT_INCOMPLETE_REASON, NULL, &reason, NULL);
        snprintf(f->title, sizeof f->title, "%s  [INCOMPLETE: %.150s]", desc, reason ? reason : "no reason given");
        free(reason);
    } else if (f->kind != PLOT_KIND_MODAL && f->complete < 0) {
        snprintf(f->title, sizeof f->title, "%s  [no completeness flag]", desc);
    } else {
        snprintf(f->title, sizeof f->title, "%s", desc);
    }
}

/* ---- simulation files ---------------------------------------------------------------------- */

/* Read the dataset `id` (n x cols x depth) or fail. */
static int read_matrix(const td_result *r, td_out_id id, size_t n, size_t cols, size_t depth, td_result_array *a)
{
    if (td_result_read(r, id, NULL, a, NULL) != TD_OK)
        return -1;
    if (a->dims[0] != n || a->dims[1] != cols || a->dims[2] != depth) {
        td_result_array_free(a);
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
static int read_events(const td_result *r, plot_sim *s, const plot_window *win)
{
    td_result_event *ev = NULL;
    size_t n = 0, i;
    if (td_result_events(r, &ev, &n, NULL) != TD_OK)
        return -1;
    s->ev = malloc((n > 0 ? n : 1) * sizeof *s->ev);
    if (!s->ev) {
        free(ev);
        return -1;
    }
    for (i = 0; i < n; i++) {
        plot_event *e = &s->ev[s->nev];
        if (ev[i].event.time < win->from || ev[i].event.time > win->to)
            continue;
        e->time = ev[i].event.time;
        e->retainer = ev[i].event.retainer;
        snprintf(e->kind, sizeof e->kind, "%s", ev[i].kind_name);
        s->nev++;
    }
    free(ev);
    return 0;
}

/* The attribute `id` into to[0 .. count) when it has that many values (else to is left alone). */
static void read_table(const td_result *r, td_out_id id, int count, double *to, long *to_long)
{
    td_result_array a;
    int i;
    if (td_result_read(r, id, NULL, &a, NULL) != TD_OK)
        return;
    for (i = 0; a.n == (size_t)count && i < count; i++)
        if (to)
            to[i] = a.v[i];
        else
            to_long[i] = (long)a.v[i];
    td_result_array_free(&a);
}

/* Node numbers and clearances from the root attributes (absent: -1 and NAN). */
static int read_tables(const td_result *r, plot_sim *s)
{
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
    read_table(r, TD_OUT_RETAINER_CLEARANCE, s->nret, s->clearance, NULL);
    read_table(r, TD_OUT_RETAINER_NODES, s->nret, NULL, s->ret_nodes);
    read_table(r, TD_OUT_AMB_NODES, s->namb, NULL, s->amb_nodes);
    return 0;
}

/* Retainer and AMB counts from the dataset shapes (the groups may be empty). */
static int count_columns(const td_result *r, td_out_id id, size_t n, int *count)
{
    td_result_array a;
    *count = 0;
    if (!td_result_has(r, id, NULL))
        return 0;
    if (td_result_read(r, id, NULL, &a, NULL) != TD_OK)
        return -1;
    if (a.dims[0] != n) {
        td_result_array_free(&a);
        return -1;
    }
    *count = (int)a.dims[1];
    td_result_array_free(&a);
    return 0;
}

/* housing motion: the housing's acceleration and displacement, and a housing body's displacement, (n, 2)
 * each, into s->housing (n x 6) with the rows kept; nothing without them (a file without housing fields),
 * -1 when they do not fit the samples. */
static int keep_housing(const td_result *r, plot_sim *s, const unsigned char *keep, size_t n)
{
    td_result_array a, d, b;
    size_t i, k = 0;
    int rc = 0;
    if (!td_result_has(r, TD_OUT_HOUSING_ACCELERATION, NULL) || !td_result_has(r, TD_OUT_HOUSING_DISPLACEMENT, NULL))
        return 0;
    memset(&d, 0, sizeof d);
    memset(&b, 0, sizeof b);
    s->housing_body = td_result_has(r, TD_OUT_HOUSING_BODY_DISPLACEMENT, NULL);
    if (read_matrix(r, TD_OUT_HOUSING_ACCELERATION, n, 2, 1, &a) != 0)
        return -1;
    if (read_matrix(r, TD_OUT_HOUSING_DISPLACEMENT, n, 2, 1, &d) != 0 ||
        (s->housing_body && read_matrix(r, TD_OUT_HOUSING_BODY_DISPLACEMENT, n, 2, 1, &b) != 0) ||
        !(s->housing = calloc(6 * s->n + 1, sizeof(double))))
        rc = -1;
    for (i = 0; rc == 0 && i < n; i++)
        if (keep[i]) {
            memcpy(s->housing + 6 * k, a.v + 2 * i, 2 * sizeof(double));
            memcpy(s->housing + 6 * k + 2, d.v + 2 * i, 2 * sizeof(double));
            if (s->housing_body)
                memcpy(s->housing + 6 * k + 4, b.v + 2 * i, 2 * sizeof(double));
            k++;
        }
    td_result_array_free(&a);
    td_result_array_free(&d);
    td_result_array_free(&b);
    return rc;
}

/* The samples of /retainers and /ambs (kept where keep is set), the tables and the events. */
static int keep_samples(const td_result *r, plot_file *f, const plot_window *win, td_result_array *t,
                        td_result_array *a, td_result_array *amb)
{
    plot_sim *s = &f->sim;
    double **dst[5];
    unsigned char *keep;
    size_t n = t->n, i, kept = 0;
    int k;
    dst[0] = &s->x, dst[1] = &s->y, dst[2] = &s->r, dst[3] = &s->fn, dst[4] = &s->contact;
    if (!(keep = malloc(n ? n : 1)))
        return bad(f->path, "out of memory", PLOT_FAILED);
    for (i = 0; i < n; i++) {
        keep[i] = t->v[i] >= win->from && t->v[i] <= win->to;
        kept += keep[i];
    }
    if (kept == 0) {
        free(keep);
        return bad(f->path, n ? "no samples inside the time window (--from/--to)" : "the file holds no samples",
                   PLOT_BAD_INPUT);
    }
    s->n = kept;
    s->t = compact(t->v, keep, n, 1);
    t->v = NULL;
    for (k = 0; k < 5; k++) {
        *dst[k] = compact(a[k].v, keep, n, (size_t)s->nret);
        a[k].v = NULL;
    }
    s->amb = compact(amb->v, keep, n, 2 * (size_t)s->namb);
    amb->v = NULL;
    if (keep_housing(r, s, keep, n) != 0) { /* housing motion */
        free(keep);
        return plot_bad_part(f->path, "", TD_OUT_HOUSING_ACCELERATION, " or its displacement has the wrong shape");
    }
    free(keep);
    if (read_tables(r, s) != 0)
        return bad(f->path, "out of memory", PLOT_FAILED);
    if (read_events(r, s, win) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_EVENTS, " table");
    return PLOT_OK;
}

static int load_sim(const td_result *r, plot_file *f, const plot_window *win)
{
    static const td_out_id fields[5] = {TD_OUT_RET_X, TD_OUT_RET_Y, TD_OUT_RET_RADIAL_POSITION, TD_OUT_RET_NORMAL_FORCE,
                                        TD_OUT_RET_CONTACT_STATE};
    plot_sim *s = &f->sim;
    td_result_array t, a[5], amb;
    size_t n;
    int k, rc = PLOT_OK;
    memset(a, 0, sizeof a);
    memset(&amb, 0, sizeof amb);
    if (td_result_read(r, TD_OUT_TIME, NULL, &t, NULL) != TD_OK || t.rank != 1) {
        td_result_array_free(&t);
        return plot_bad_part(f->path, "unreadable ", TD_OUT_TIME, " dataset (not a touchdown simulation file?)");
    }
    n = t.n;
    if (count_columns(r, TD_OUT_RET_X, n, &s->nret) != 0 || count_columns(r, TD_OUT_AMB_FORCE, n, &s->namb) != 0) {
        td_result_array_free(&t);
        return plot_bad_part(f->path, "the sample datasets do not match ", TD_OUT_TIME, "");
    }
    for (k = 0; k < 5 && s->nret > 0 && rc == PLOT_OK; k++)
        if (read_matrix(r, fields[k], n, (size_t)s->nret, 1, &a[k]) != 0)
            rc = plot_bad_part(f->path, "a dataset of ", TD_OUT_RETAINERS, " is missing or has the wrong shape");
    if (rc == PLOT_OK && s->namb > 0 && read_matrix(r, TD_OUT_AMB_FORCE, n, (size_t)s->namb, 2, &amb) != 0)
        rc = plot_bad_part(f->path, "", TD_OUT_AMB_FORCE, " has the wrong shape");
    if (rc == PLOT_OK)
        rc = keep_samples(r, f, win, &t, a, &amb);
    if (rc == PLOT_OK && td_result_has(r, TD_OUT_LEAP_TIME, NULL)) { /* projective leap: where the gaps are */
        td_result_array leaps;
        if (td_result_read(r, TD_OUT_LEAP_TIME, NULL, &leaps, NULL) != TD_OK)
            rc = plot_bad_part(f->path, "unreadable ", TD_OUT_LEAP_TIME, " attribute");
        s->leap_time = leaps.v;
        s->nleap = leaps.n;
    }
    td_result_array_free(&t);
    td_result_array_free(&amb);
    for (k = 0; k < 5; k++)
        td_result_array_free(&a[k]);
    return rc;
}

/* ---- modal files --------------------------------------------------------------------------- */

static int load_campbell(const td_result *r, plot_modal *m)
{
    td_result_array f;
    if (!td_result_has(r, TD_OUT_CAMPBELL_FREQ_HZ, NULL))
        return 0;
    if (td_result_read(r, TD_OUT_CAMPBELL_FREQ_HZ, NULL, &f, NULL) != TD_OK || f.rank != 2) {
        td_result_array_free(&f);
        return -1;
    }
    m->ns = (int)f.dims[0];
    m->nb = (int)f.dims[1];
    m->freq = f.v;
    m->speed = plot_read_vector(r, TD_OUT_CAMPBELL_SPEED, NULL, (size_t)m->ns);
    m->whirl = plot_read_vector(r, TD_OUT_CAMPBELL_WHIRL, NULL, (size_t)m->ns * (size_t)m->nb);
    if (plot_read_optional(r, TD_OUT_CAMPBELL_MAC, NULL, (size_t)m->ns * (size_t)m->nb, &m->mac))
        return -1;
    return m->speed && m->whirl ? 0 : -1;
}

static int load_critical(const td_result *r, plot_modal *m)
{
    td_result_array s;
    if (!td_result_has(r, TD_OUT_CRITICAL_SPEED, NULL))
        return 0;
    if (td_result_read(r, TD_OUT_CRITICAL_SPEED, NULL, &s, NULL) != TD_OK || s.rank != 1) {
        td_result_array_free(&s);
        return -1;
    }
    m->ncrit = (int)s.n;
    m->crit_speed = s.v;
    m->crit_freq = plot_read_vector(r, TD_OUT_CRITICAL_FREQ_HZ, NULL, s.n);
    m->crit_whirl = plot_read_vector(r, TD_OUT_CRITICAL_WHIRL, NULL, s.n);
    return m->crit_freq && m->crit_whirl ? 0 : -1;
}

/* Axial node positions into *z, if the file has them (/modes/node_z, or at the root in older
 * files, m); -1 when they are there with another count than the shapes' nodes. */
static int node_positions(const td_result *r, size_t nn, double **z)
{
    if (plot_read_optional(r, TD_OUT_MODES_NODE_Z, NULL, nn, z))
        return -1;
    return *z ? 0 : plot_read_optional(r, TD_OUT_ROOT, td_out_name(TD_OUT_MODES_NODE_Z), nn, z);
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

static int load_shapes(const td_result *r, plot_modal *m)
{
    td_result_array xr, speed;
    size_t total;
    if (!td_result_has(r, TD_OUT_MODES_SHAPE_X_RE, NULL))
        return 0;
    if (td_result_read(r, TD_OUT_MODES_SHAPE_X_RE, NULL, &xr, NULL) != TD_OK || xr.rank != 2) {
        td_result_array_free(&xr);
        return -1;
    }
    m->nm = (int)xr.dims[0];
    m->nn = (int)xr.dims[1];
    m->xr = xr.v;
    total = (size_t)m->nm * (size_t)m->nn;
    m->xi = plot_read_vector(r, TD_OUT_MODES_SHAPE_X_IM, NULL, total);
    m->yr = plot_read_vector(r, TD_OUT_MODES_SHAPE_Y_RE, NULL, total);
    m->yi = plot_read_vector(r, TD_OUT_MODES_SHAPE_Y_IM, NULL, total);
    m->mode_freq = plot_read_vector(r, TD_OUT_MODES_FREQ_HZ, NULL, (size_t)m->nm);
    m->mode_whirl = plot_read_vector(r, TD_OUT_MODES_WHIRL, NULL, (size_t)m->nm);
    if (plot_read_optional(r, TD_OUT_MODES_ZETA, NULL, (size_t)m->nm, &m->mode_zeta) ||
        node_positions(r, (size_t)m->nn, &m->node_z))
        return -1;
    m->mode_speed = NAN;
    if (td_result_read(r, TD_OUT_MODES_SPEED, NULL, &speed, NULL) == TD_OK) {
        m->mode_speed = speed.v[0];
        td_result_array_free(&speed);
    }
    if (!(m->xi && m->yr && m->yi && m->mode_freq && m->mode_whirl))
        return -1;
    drop_overdamped(m);
    return 0;
}

static int load_modal(const td_result *r, plot_file *f)
{
    plot_modal *m = &f->modal;
    td_out_id unreadable;
    if (load_campbell(r, m) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_CAMPBELL, " group");
    if (load_critical(r, m) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_CRITICAL, " group");
    if (load_shapes(r, m) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_MODES, " group");
    if (plot_loop_load(r, &m->loop) != 0)
        return plot_bad_part(f->path, "unreadable ", TD_OUT_LOOP, " group");
    if (plot_api617_load(r, &m->api, &unreadable) != 0)
        return plot_bad_part(f->path, "unreadable ", unreadable, " group");
    if (m->ns == 0 && m->nm == 0)
        return bad(f->path, "the modal file holds neither a Campbell diagram nor mode shapes", PLOT_BAD_INPUT);
    return PLOT_OK;
}

/* ---- entry --------------------------------------------------------------------------------- */

int plot_file_load(const char *path, const plot_window *win, plot_file *f)
{
    td_result *r = NULL;
    td_error err;
    int rc;
    memset(f, 0, sizeof *f);
    f->path = path;
    make_stem(path, f->stem, sizeof f->stem);
    if (td_result_open(path, &r, &err) != TD_OK) {
        fprintf(stderr, "touchdown plot: %s\n", err.message);
        return err.code == TD_ERR_NOMEM ? PLOT_FAILED : PLOT_BAD_INPUT;
    }
    f->complete = (int)td_result_get_flag(r);
    switch (td_result_get_kind(r)) {
    case TD_RESULT_SWEEP:
        f->kind = PLOT_KIND_SWEEP;
        rc = plot_sweep_load(r, f);
        break;
    case TD_RESULT_RUN:
        f->kind = PLOT_KIND_SIM;
        rc = load_sim(r, f, win);
        break;
    default: f->kind = PLOT_KIND_MODAL; rc = load_modal(r, f);
    }
    if (rc == PLOT_OK)
        make_title(f, r);
    td_result_free(&r);
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
    free(s->housing);   /* housing motion */
    free(s->leap_time); /* projective leap */
    free(m->speed), free(m->freq), free(m->whirl), free(m->mac), free(m->crit_speed), free(m->crit_freq),
        free(m->crit_whirl);
    free(m->mode_freq), free(m->mode_whirl), free(m->mode_zeta), free(m->xr), free(m->xi), free(m->yr), free(m->yi);
    free(m->node_z);
    plot_loop_free(&m->loop);
    plot_api617_free(&m->api);
    plot_sweep_free(&f->sweep);
    memset(s, 0, sizeof *s);
    memset(m, 0, sizeof *m);
}
