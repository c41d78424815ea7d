/*
 * CSV back end of td_writer (docs/output-format.md lists the columns).
 *
 * Two files: the samples (one header line naming each column with its unit, one row per sample)
 * and the events (same style). Comma separated, numbers with 17 significant digits so every
 * double reads back to the same bits; attributes and the completeness line are '#' comments at
 * the end, which gnuplot and pandas (comment='#') skip.
 */
#include "io/schema.h"
#include "io/writer_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct csv_impl {
    FILE *samples;
    FILE *events;
    FILE *windows; /* long runs: the window file, NULL without window_fields */
} csv_impl;

/* The shortest of %.15g, %.16g, %.17g that reads back to the same double: grid times print as
 * 0.0002, not 0.00020000000000000001. Used for times and attributes; the bulk data use %.17g. */
static const char *exact_text(double v, char *buf, size_t n)
{
    int digits;
    if (td_is_undefined(v)) { /* "nan" whatever its sign bit (touchdown/dofs.h, "Undefined values") */
        snprintf(buf, n, "nan");
        return buf;
    }
    for (digits = 15; digits < 17; digits++) {
        snprintf(buf, n, "%.*g", digits, v);
        if (strtod(buf, NULL) == v)
            return buf;
    }
    snprintf(buf, n, "%.17g", v);
    return buf;
}

/* ---- headers ----------------------------------------------------------------------------- */

static int column(FILE *f, int first, td_out_id id, const char *comp, int i);

/* housing motion: the housing's five x-y pairs (with a housing body its two more), then the nodes'
 * absolute displacement, last. */
static int housing_header(FILE *f, const td_writer *w)
{
    static const td_out_id ids[] = {TD_OUT_HOUSING_ACCELERATION,   TD_OUT_HOUSING_VELOCITY,
                                    TD_OUT_HOUSING_DISPLACEMENT,   TD_OUT_HOUSING_ROTATION_RATE,
                                    TD_OUT_HOUSING_ROTATION_ANGLE, TD_OUT_HOUSING_BODY_DISPLACEMENT,
                                    TD_OUT_HOUSING_BODY_TILT};
    const char *const *xy = td_schema_components();
    int i, k, rc = 0;
    for (i = 0; i < TD_WRITER_HOUSING_COUNT(w) / 2; i++)
        for (k = 0; k < 2; k++)
            rc |= column(f, 0, ids[i], xy[k], 0);
    for (i = 0; i < w->node_count; i++)
        for (k = 0; k < 2; k++)
            rc |= column(f, 0, TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, xy[k], w->nodes[i]);
    return rc;
}

/* One column title: ",NAME [UNITS]" (no comma first, no brackets without a unit), NAME the schema's
 * CSV column of `id` filled with the component `comp` and/or the index `i`. */
static int column(FILE *f, int first, td_out_id id, const char *comp, int i)
{
    const char *units = td_schema_csv_units(id);
    int rc = !first && fputc(',', f) == EOF;
    if (comp)
        rc |= fprintf(f, td_schema_csv(id), comp, i) < 0;
    else
        rc |= fprintf(f, td_schema_csv(id), i) < 0;
    if (units[0])
        rc |= fprintf(f, " [%s]", units) < 0;
    return rc;
}

static int write_sample_header(FILE *f, const td_writer *w)
{
    static const td_out_id ret_cols[] = {TD_OUT_RET_X,
                                         TD_OUT_RET_Y,
                                         TD_OUT_RET_RADIAL_POSITION,
                                         TD_OUT_RET_RADIAL_VELOCITY,
                                         TD_OUT_RET_WHIRL_ANGLE,
                                         TD_OUT_RET_NORMAL_FORCE,
                                         TD_OUT_RET_FRICTION_FORCE,
                                         TD_OUT_RET_SLIDING_VELOCITY,
                                         TD_OUT_RET_CONTACT_STATE};
    static const td_out_id race_cols[] = {TD_OUT_RET_RACE_X, TD_OUT_RET_RACE_Y, TD_OUT_RET_RACE_SPEED,
                                          TD_OUT_RET_ROLLING};
    const char *const *xy = td_schema_components();
    int i, k, rc = column(f, 1, TD_OUT_TIME, NULL, 0);
    if (w->speed_field)
        rc |= column(f, 0, TD_OUT_SPEED, NULL, 0);
    for (i = 0; i < w->node_count; i++)
        for (k = 0; k < 2; k++)
            rc |= column(f, 0, TD_OUT_NODE_DISPLACEMENT, xy[k], w->nodes[i]);
    for (i = 0; i < w->retainer_count; i++) {
        for (k = 0; k < 9; k++)
            rc |= column(f, 0, ret_cols[k], NULL, i);
        for (k = 0; k < 4 && w->race_fields; k++)
            rc |= column(f, 0, race_cols[k], NULL, i);
        if (w->whirl_field)
            rc |= column(f, 0, TD_OUT_RET_WHIRL_RATE, NULL, i);
        if (w->thermal_fields) { /* heat */
            rc |= column(f, 0, TD_OUT_RET_RACE_TEMPERATURE, NULL, i);
            rc |= column(f, 0, TD_OUT_RET_HOUSING_TEMPERATURE, NULL, i);
        }
    }
    for (i = 0; i < w->amb_count; i++)
        for (k = 0; k < 2; k++)
            rc |= column(f, 0, TD_OUT_AMB_FORCE, xy[k], i);
    if (w->housing_fields)
        rc |= housing_header(f, w);
    rc |= fputc('\n', f) == EOF;
    return rc;
}

/* The events file's columns: the /events fields in order, the kind's name after the kind. */
static int write_event_header(FILE *f, const td_writer *w)
{
    int id, rc = 0, last = w->switch_fields ? TD_OUT_EV_SENSED_RADIUS : TD_OUT_EV_PEAK_NORMAL_FORCE;
    for (id = TD_OUT_EV_TIME; id <= last; id++)
        rc |= column(f, id == TD_OUT_EV_TIME, (td_out_id)id, NULL, 0);
    rc |= fputc('\n', f) == EOF;
    return rc;
}

/* long runs: the window file's columns (td_window_summary's order; per retainer, retainer by retainer) */
static const td_out_id window_cols[] = {TD_OUT_WIN_CONTACTS, TD_OUT_WIN_CONTACT_FRACTION, TD_OUT_WIN_PEAK_NORMAL_FORCE,
                                        TD_OUT_WIN_FRICTION_WORK, TD_OUT_WIN_RACE_TEMPERATURE};

static int write_window_header(FILE *f, const td_writer *w)
{
    static const td_out_id run_cols[] = {TD_OUT_WIN_TIME_START, TD_OUT_WIN_TIME_END, TD_OUT_WIN_SPEED,
                                         TD_OUT_WIN_ENERGY_KINETIC, TD_OUT_WIN_ENERGY_RESIDUAL};
    int i, k, rc = 0;
    for (k = 0; k < 5; k++)
        rc |= column(f, k == 0, run_cols[k], NULL, 0);
    for (i = 0; i < w->retainer_count; i++)
        for (k = 0; k < 5; k++)
            rc |= column(f, 0, window_cols[k], NULL, i);
    rc |= fputc('\n', f) == EOF;
    return rc;
}

static void csv_destroy(td_writer *w);

/* A stream on the created temporary file; the writer's descriptor is taken over. */
static FILE *adopt(int *fd)
{
    FILE *f = fdopen(*fd, "w");
    if (f)
        *fd = -1;
    return f;
}

static td_status csv_open(td_writer *w, td_error *err)
{
    csv_impl *c = calloc(1, sizeof *c);
    td_status st = TD_OK;
    if (!c)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", w->path);
    w->impl = c;
    errno = 0;
    if (!(c->samples = adopt(&w->tmp_fd)))
        st = td_io_fail(err, w->tmp_path, "cannot open");
    else if (!w->omit_events && !(c->events = adopt(&w->events_fd)))
        st = td_io_fail(err, w->events_tmp, "cannot open");
    else if (w->window_fields && !(c->windows = adopt(&w->windows_fd))) /* long runs */
        st = td_io_fail(err, w->windows_tmp, "cannot open");
    else if (write_sample_header(c->samples, w) || (c->events && write_event_header(c->events, w)) ||
             (c->windows && write_window_header(c->windows, w)))
        st = td_io_fail(err, w->tmp_path, "cannot write the header");
    if (st != TD_OK)
        csv_destroy(w);
    return st;
}

/* ---- rows -------------------------------------------------------------------------------- */

static td_status csv_sample(td_writer *w, double t, double speed, const double *node_xy, const td_retainer_state *ret,
                            const double *amb_f, td_error *err)
{
    FILE *f = ((csv_impl *)w->impl)->samples;
    char tbuf[32];
    int i, rc;
    errno = 0;
    rc = fputs(exact_text(t, tbuf, sizeof tbuf), f) < 0;
    if (w->speed_field)
        rc |= fprintf(f, ",%.17g", speed) < 0;
    for (i = 0; i < 2 * w->node_count; i++)
        rc |= fprintf(f, ",%.17g", node_xy[i]) < 0;
    for (i = 0; i < w->retainer_count; i++) {
        const td_retainer_state *s = &ret[i];
        rc |=
            fprintf(f, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d", s->x, s->y, s->radius, s->radial_velocity,
                    s->whirl_angle, s->normal_force, s->friction_force, s->sliding_velocity, s->in_contact ? 1 : 0) < 0;
        if (w->race_fields)
            rc |= fprintf(f, ",%.17g,%.17g,%.17g,%d", s->race_x, s->race_y, s->race_speed, s->rolling ? 1 : 0) < 0;
        if (w->whirl_field)
            rc |= fprintf(f, ",%.17g", s->whirl_rate) < 0;
        if (w->thermal_fields) /* heat */
            rc |= fprintf(f, ",%.17g,%.17g", s->race_temperature, s->housing_temperature) < 0;
    }
    for (i = 0; i < 2 * w->amb_count; i++)
        rc |= fprintf(f, ",%.17g", amb_f[i]) < 0;
    for (i = 0; w->housing_fields && i < TD_WRITER_HOUSING_COUNT(w); i++) /* housing motion */
        rc |= fprintf(f, ",%.17g", w->housing[i]) < 0;
    for (i = 0; w->housing_fields && i < 2 * w->node_count; i++)
        rc |= fprintf(f, ",%.17g", w->node_abs_xy[i]) < 0;
    rc |= fputc('\n', f) == EOF;
    return rc ? td_io_fail(err, w->tmp_path, "cannot write a sample") : TD_OK;
}

static td_status csv_event(td_writer *w, const td_event *ev, long sample, td_error *err)
{
    FILE *f = ((csv_impl *)w->impl)->events;
    char tbuf[32];
    errno = 0;
    if (fprintf(f, "%s,%d,%s,%d,%d,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g",
                exact_text(ev->time, tbuf, sizeof tbuf), (int)ev->kind, td_event_kind_name(ev->kind), ev->retainer,
                ev->change, sample, ev->radial_velocity_before, ev->radial_velocity_after,
                ev->tangential_velocity_before, ev->tangential_velocity_after, ev->impulse, ev->normal_force,
                ev->peak_normal_force) < 0 ||
        (w->switch_fields && fprintf(f, ",%d,%.17g", ev->controller, ev->sensed_radius) < 0) || fputc('\n', f) == EOF)
        return td_io_fail(err, w->events_tmp, "cannot write an event");
    return TD_OK;
}

/* long runs: one window summary, times as exact_text, the rest %.17g */
static td_status csv_window(td_writer *w, const td_window_summary *win, td_error *err)
{
    FILE *f = ((csv_impl *)w->impl)->windows;
    char a[32], b[32];
    int i, rc;
    errno = 0;
    rc = fprintf(f, "%s,%s,%.17g,%.17g,%.17g", exact_text(win->t_start, a, sizeof a),
                 exact_text(win->t_end, b, sizeof b), win->speed, win->energy_kinetic, win->energy_residual) < 0;
    for (i = 0; i < w->retainer_count; i++)
        rc |= fprintf(f, ",%ld,%.17g,%.17g,%.17g,%.17g", win->contacts[i], win->contact_fraction[i],
                      win->peak_normal_force[i], win->friction_work[i], win->race_temperature[i]) < 0;
    rc |= fputc('\n', f) == EOF;
    return rc ? td_io_fail(err, w->windows_tmp, "cannot write a window summary") : TD_OK;
}

/* ---- finish ------------------------------------------------------------------------------ */

/* A string attribute: one line "# name = value", or for text with newlines "# name:" and one
 * "#| line" per line, so the text can be recovered exactly. */
static int write_string_attr(FILE *f, const char *name, const char *text)
{
    int rc;
    if (!strchr(text, '\n'))
        return fprintf(f, "# %s = %s\n", name, text) < 0;
    rc = fprintf(f, "# %s:\n#| ", name) < 0;
    for (; *text; text++) {
        rc |= fputc(*text, f) == EOF;
        if (*text == '\n' && text[1])
            rc |= fputs("#| ", f) < 0;
    }
    if (text[-1] != '\n')
        rc |= fputc('\n', f) == EOF;
    return rc;
}

static int write_attr(FILE *f, const td_attr *a)
{
    char buf[32];
    int i, rc = 0;
    if (a->type == TD_ATTR_STRING)
        return write_string_attr(f, a->name, a->text);
    rc |= fprintf(f, "# %s =", a->name) < 0;
    for (i = 0; i < a->count; i++) {
        if (a->type == TD_ATTR_DOUBLE)
            rc |= fprintf(f, " %s", exact_text(a->doubles[i], buf, sizeof buf)) < 0;
        else
            rc |= fprintf(f, " %ld", a->longs[i]) < 0;
    }
    rc |= fputc('\n', f) == EOF;
    return rc;
}

static td_status csv_finish(td_writer *w, int complete, const char *reason, td_error *err)
{
    csv_impl *c = w->impl;
    td_status st = TD_OK;
    int i, rc = 0;
    errno = 0;
    for (i = 0; i < w->attr_count; i++)
        rc |= write_attr(c->samples, &w->attrs[i]);
    if (!complete)
        rc |= write_string_attr(c->samples, td_out_name(TD_OUT_INCOMPLETE_REASON), reason);
    /* Events (and window) file first, samples file last: its flag line is the authority. */
    if (c->windows) { /* long runs */
        rc |= td_io_csv_flag(c->windows, complete, reason);
        if (td_io_close_stream(&c->windows))
            st = td_io_fail(err, w->windows_tmp, "cannot finish");
    }
    if (c->events) { /* none without an event table */
        rc |= td_io_csv_flag(c->events, complete, reason);
        if (td_io_close_stream(&c->events))
            st = td_io_fail(err, w->events_tmp, "cannot finish");
    }
    rc |= td_io_csv_flag(c->samples, complete, reason);
    rc |= td_io_close_stream(&c->samples);
    if (rc && st == TD_OK)
        st = td_io_fail(err, w->tmp_path, "cannot finish");
    free(c);
    w->impl = NULL;
    return st;
}

static void csv_destroy(td_writer *w)
{
    csv_impl *c = w->impl;
    if (!c)
        return;
    td_io_close_stream(&c->samples);
    td_io_close_stream(&c->events);
    td_io_close_stream(&c->windows); /* long runs */
    free(c);
    w->impl = NULL;
}

const td_writer_ops td_csv_writer_ops = {csv_open, csv_sample, csv_event, csv_finish, csv_destroy, csv_window};
