/*
 * HDF5 back end of td_writer (docs/output-format.md lists the layout).
 *
 * Samples are buffered one chunk at a time and written as whole chunks of extendible datasets,
 * so a long run costs one H5Dwrite per dataset per chunk, not per sample; events likewise (a
 * contact-rich run has thousands, and extending a dataset per event cost about 0.2 ms each).
 * The file uses the HDF5 1.8 format (readable by every HDF5 >= 1.8) so that a long case text
 * fits in a root attribute (the 1.6 format caps attributes at 64 KiB).
 * Shared axes are HDF5 dimension scales (/time, /component, /nodes/node, /retainers/retainer,
 * /ambs/amb, /event) attached to every dataset that has them, so netCDF-4 readers (xarray with
 * h5netcdf or netCDF4) see named dimensions instead of anonymous ones. Strings are variable-length
 * UTF-8, which h5py and netCDF read as text (h5py returns fixed-length strings as bytes).
 * Every HDF5 call runs inside H5E_BEGIN_TRY/H5E_END_TRY: the library never prints, and the
 * automatic error printing of the calling program is restored afterwards.
 */
#include "io/h5_util.h"
#include "io/h5_vfd.h"
#include "io/h5_windows.h"
#include "io/schema.h"
#include "io/writer_internal.h"
#include "util/error_internal.h"

#include <hdf5.h>
#include <hdf5_hl.h> /* H5DS: dimension scales */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Largest number of sample datasets: time, speed, displacement, 13 retainer fields, AMB force (17), with room. */
#define H5_MAX_SERIES 32
/* Chunk of the sample datasets: at most this many rows and about this many bytes. */
#define H5_CHUNK_ROWS 1024
#define H5_CHUNK_BYTES (512 * 1024)
#define H5_EVENT_CHUNK 256 /* events per chunk, and per buffered write */

/* One extendible dataset with rows of `row_len` values (shape [rows, row_dims...]). */
typedef struct h5_series {
    hid_t dset;
    int rank; /* 1 + number of row dimensions */
    hsize_t row_dims[2];
    size_t row_len; /* values per row */
    int is_int8;    /* contact_state: int8, otherwise double */
    void *buf;      /* chunk_rows rows */
} h5_series;

/* One event row in memory (the file type is the packed copy). */
typedef struct h5_event_row {
    double time;
    int kind;
    int retainer;
    int change;
    int64_t sample;
    double radial_velocity_before;
    double radial_velocity_after;
    double tangential_velocity_before;
    double tangential_velocity_after;
    double impulse;
    double normal_force;
    double peak_normal_force;
    int controller; /* these two only with switch_fields (td_output_layout) */
    double sensed_radius;
} h5_event_row;

typedef struct h5_impl {
    hid_t file;
    hid_t event_dset, event_mtype, event_ftype, kind_type;
    hid_t event_index; /* /event: the dimension scale of /events (row numbers) */
    hid_t component;   /* /component (td_schema_components), -1 when no dataset has that axis */
    h5_series series[H5_MAX_SERIES];
    int series_count;
    int idx_time, idx_speed, idx_disp, idx_ret, idx_whirl, idx_amb; /* first series of each part, -1 if absent */
    int idx_thermal; /* heat: the race temperature's series (the housing's next), -1 if absent */
    int idx_housing; /* housing motion: /housing/acceleration, the other four next, -1 if absent */
    int idx_abs;     /* housing motion: /nodes/absolute_displacement, -1 if absent */
    size_t chunk_rows, buffered;
    hsize_t flushed;
    hsize_t event_rows;      /* events in the file */
    h5_event_row *event_buf; /* H5_EVENT_CHUNK buffered events */
    size_t events_buffered;
    hid_t driver;           /* h5_vfd.h registration, -1 if none */
    int io_errno;           /* first I/O error seen by the driver, 0 if none */
    td_h5_windows *windows; /* long runs: /windows, NULL without window_fields */
} h5_impl;

/* Retainer fields in the order of the /retainers datasets. */
static const struct {
    td_out_id id;
    size_t offset;
} ret_fields[] = {{TD_OUT_RET_X, offsetof(td_retainer_state, x)},
                  {TD_OUT_RET_Y, offsetof(td_retainer_state, y)},
                  {TD_OUT_RET_RADIAL_POSITION, offsetof(td_retainer_state, radius)},
                  {TD_OUT_RET_RADIAL_VELOCITY, offsetof(td_retainer_state, radial_velocity)},
                  {TD_OUT_RET_WHIRL_ANGLE, offsetof(td_retainer_state, whirl_angle)},
                  {TD_OUT_RET_NORMAL_FORCE, offsetof(td_retainer_state, normal_force)},
                  {TD_OUT_RET_FRICTION_FORCE, offsetof(td_retainer_state, friction_force)},
                  {TD_OUT_RET_SLIDING_VELOCITY, offsetof(td_retainer_state, sliding_velocity)},
                  /* with race fields (td_output_layout.race_fields) */
                  {TD_OUT_RET_RACE_X, offsetof(td_retainer_state, race_x)},
                  {TD_OUT_RET_RACE_Y, offsetof(td_retainer_state, race_y)},
                  {TD_OUT_RET_RACE_SPEED, offsetof(td_retainer_state, race_speed)}};
#define RET_FIELD_ALL ((int)(sizeof ret_fields / sizeof ret_fields[0]))
/* The double fields written: the first 8, or all with the race fields. */
#define RET_FIELD_COUNT(w) ((w)->race_fields ? RET_FIELD_ALL : RET_FIELD_ALL - 3)

/* ---- errors ------------------------------------------------------------------------------ */

/* Fill err with `what` and the cause: the driver's I/O error, else HDF5's innermost message. */
static td_status h5_fail(td_error *err, const td_writer *w, const char *what)
{
    const h5_impl *h = w->impl;
    return td_h5_fail(err, w->tmp_path, h ? h->io_errno : 0, what);
}

/* The driver hides I/O errors from HDF5 (h5_vfd.h): after each HDF5 operation that succeeded,
 * a write the driver could not do still fails the file. */
static td_status io_checked(td_status st, const td_writer *w, const char *what, td_error *err)
{
    const h5_impl *h = w->impl;
    if (st == TD_OK && h && h->io_errno)
        return h5_fail(err, w, what);
    return st;
}

/* ---- creation ---------------------------------------------------------------------------- */

/* The `units` attribute of the dataset `id` (td_schema). */
static herr_t units_attr(hid_t dset, td_out_id id)
{
    return td_h5_attr_string(dset, td_out_name(TD_OUT_UNITS), td_out_units(id));
}

/* A fixed 1-D dimension scale `id` under `loc` holding `values` (int32 or text). */
static hid_t make_scale(hid_t loc, td_out_id id, hid_t file_type, hid_t mem_type, const void *values, hsize_t n)
{
    const char *name = td_out_name(id);
    hid_t dset = td_h5_fixed_dataset(loc, name, file_type, mem_type, values, 1, &n);
    if (dset >= 0 && (H5DSset_scale(dset, name) < 0 || units_attr(dset, id) < 0)) {
        H5Dclose(dset);
        return -1;
    }
    return dset;
}

/* Scale of the int32 indices 0..n-1 (retainers, AMBs). */
static hid_t make_index_scale(hid_t loc, td_out_id id, int n)
{
    int *v = malloc((size_t)(n > 0 ? n : 1) * sizeof *v);
    hid_t dset;
    int i;
    if (!v)
        return -1;
    for (i = 0; i < n; i++)
        v[i] = i;
    dset = make_scale(loc, id, H5T_STD_I32LE, H5T_NATIVE_INT, v, (hsize_t)n);
    free(v);
    return dset;
}

/* /component = {"x", "y"} (td_schema_components): the last axis of /nodes/displacement and
 * /ambs/force. */
static hid_t make_component_scale(hid_t file)
{
    hid_t type = td_h5_text_type(), dset = -1;
    if (type >= 0)
        dset = make_scale(file, TD_OUT_COMPONENT, type, type, td_schema_components(), 2);
    if (type >= 0)
        H5Tclose(type);
    return dset;
}

/* Create the extendible sample dataset `id` under `loc`. */
static td_status add_series(td_writer *w, h5_impl *h, hid_t loc, td_out_id id, int rank, const hsize_t *row_dims,
                            int is_int8, td_error *err)
{
    h5_series *s = &h->series[h->series_count];
    const char *name = td_out_name(id);
    hid_t dset;
    int i;
    if (h->series_count >= H5_MAX_SERIES) /* a layout this file format was not sized for: a bug */
        return td_error_set(err, TD_ERR_INVALID, "%s: too many sample datasets (%d)", w->tmp_path, H5_MAX_SERIES);
    s->rank = rank;
    s->row_len = 1;
    for (i = 0; i + 1 < rank; i++) {
        s->row_dims[i] = row_dims[i];
        s->row_len *= (size_t)row_dims[i];
    }
    s->is_int8 = is_int8;
    s->dset = -1;
    s->buf = malloc(h->chunk_rows * s->row_len * (is_int8 ? sizeof(int8_t) : sizeof(double)));
    if (!s->buf)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory for the %s buffer", name);
    h->series_count++; /* from here on destroy() frees the buffer */
    dset = td_h5_append_create(loc, name, is_int8 ? H5T_STD_I8LE : H5T_IEEE_F64LE, rank, s->row_dims,
                               (hsize_t)h->chunk_rows, w->compression);
    if (dset < 0)
        return h5_fail(err, w, "cannot create a sample dataset");
    s->dset = dset;
    if (units_attr(dset, id) < 0)
        return h5_fail(err, w, "cannot write a units attribute");
    /* /time is the first series: it names the sample axis of every later one */
    if (h->series_count - 1 == h->idx_time ? H5DSset_scale(dset, td_out_name(TD_OUT_TIME)) < 0
                                           : H5DSattach_scale(dset, h->series[h->idx_time].dset, 0) < 0)
        return h5_fail(err, w, "cannot attach the time axis");
    return TD_OK;
}

/* Attach the scale `scale` to axis `axis` of every series from `first` to the last created. */
static td_status attach_axis(td_writer *w, h5_impl *h, int first, hid_t scale, unsigned axis, td_error *err)
{
    int i;
    if (scale < 0)
        return h5_fail(err, w, "cannot create a dimension scale");
    for (i = first; i < h->series_count; i++)
        if (H5DSattach_scale(h->series[i].dset, scale, axis) < 0)
            return h5_fail(err, w, "cannot attach a dimension scale");
    return TD_OK;
}

/* attach_axis for a scale of this group only, closed afterwards. */
static td_status attach_own_axis(td_writer *w, h5_impl *h, int first, hid_t scale, unsigned axis, td_error *err)
{
    td_status st = attach_axis(w, h, first, scale, axis, err);
    if (scale >= 0)
        H5Dclose(scale);
    return st;
}

static hid_t make_group(hid_t file, td_out_id id, int count)
{
    hid_t g = H5Gcreate2(file, td_out_name(id), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g >= 0 && td_h5_attr_int(g, td_out_name(TD_OUT_COUNT), count) < 0) {
        H5Gclose(g);
        return -1;
    }
    return g;
}

/* housing motion: /nodes/absolute_displacement beside /nodes/displacement, with its axes. */
static td_status create_absolute(td_writer *w, h5_impl *h, hid_t g, const hsize_t *row, td_error *err)
{
    td_status st;
    h->idx_abs = h->series_count;
    st = add_series(w, h, g, TD_OUT_NODE_ABSOLUTE_DISPLACEMENT, 3, row, 0, err);
    if (st == TD_OK && (td_h5_attr_numeric(h->series[h->idx_abs].dset, td_out_name(TD_OUT_NODES_ATTR), H5T_STD_I32LE,
                                           H5T_NATIVE_INT, w->nodes, w->node_count, 1) < 0 ||
                        td_h5_attr_string(h->series[h->idx_abs].dset, td_out_name(TD_OUT_COMPONENTS),
                                          td_schema_components_list()) < 0))
        st = h5_fail(err, w, "cannot write the node attributes");
    if (st == TD_OK) {
        hid_t node = H5Dopen2(g, td_out_name(TD_OUT_NODE), H5P_DEFAULT);
        st = attach_own_axis(w, h, h->idx_abs, node, 1, err);
    }
    return st == TD_OK ? attach_axis(w, h, h->idx_abs, h->component, 2, err) : st;
}

/* housing motion: the group /housing, its five (N, 2) series over /component, then with a housing body
 * its two (in the order of td_writer_housing's values). */
static td_status create_housing(td_writer *w, h5_impl *h, td_error *err)
{
    static const td_out_id ids[] = {TD_OUT_HOUSING_ACCELERATION,   TD_OUT_HOUSING_VELOCITY,
                                    TD_OUT_HOUSING_DISPLACEMENT,   TD_OUT_HOUSING_ROTATION_RATE,
                                    TD_OUT_HOUSING_ROTATION_ANGLE, TD_OUT_HOUSING_BODY_DISPLACEMENT,
                                    TD_OUT_HOUSING_BODY_TILT};
    hid_t g = H5Gcreate2(h->file, td_out_name(TD_OUT_HOUSING), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t row[1] = {2};
    td_status st = TD_OK;
    int i;
    if (g < 0)
        return h5_fail(err, w, "cannot create /housing");
    h->idx_housing = h->series_count;
    for (i = 0; st == TD_OK && i < TD_WRITER_HOUSING_COUNT(w) / 2; i++) {
        st = add_series(w, h, g, ids[i], 2, row, 0, err);
        if (st == TD_OK && td_h5_attr_string(h->series[h->series_count - 1].dset, td_out_name(TD_OUT_COMPONENTS),
                                             td_schema_components_list()) < 0)
            st = h5_fail(err, w, "cannot write the housing attributes");
    }
    if (st == TD_OK)
        st = attach_axis(w, h, h->idx_housing, h->component, 1, err);
    H5Gclose(g);
    return st;
}

/* long runs: /windows (h5_windows.c) */
static td_status create_windows(td_writer *w, h5_impl *h, td_error *err)
{
    int nomem;
    h->windows = td_h5_windows_create(h->file, w->retainer_count, w->compression, &nomem);
    if (!h->windows)
        return nomem ? td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", w->path)
                     : h5_fail(err, w, "cannot create /windows");
    return TD_OK;
}

static td_status create_nodes(td_writer *w, h5_impl *h, td_error *err)
{
    hid_t g = make_group(h->file, TD_OUT_NODES, w->node_count);
    hsize_t row[2];
    td_status st = TD_OK;
    if (g < 0)
        return h5_fail(err, w, "cannot create /nodes");
    if (w->node_count > 0) {
        row[0] = (hsize_t)w->node_count;
        row[1] = 2;
        h->idx_disp = h->series_count;
        st = add_series(w, h, g, TD_OUT_NODE_DISPLACEMENT, 3, row, 0, err);
        if (st == TD_OK && (td_h5_attr_numeric(h->series[h->idx_disp].dset, td_out_name(TD_OUT_NODES_ATTR),
                                               H5T_STD_I32LE, H5T_NATIVE_INT, w->nodes, w->node_count, 1) < 0 ||
                            td_h5_attr_string(h->series[h->idx_disp].dset, td_out_name(TD_OUT_COMPONENTS),
                                              td_schema_components_list()) < 0))
            st = h5_fail(err, w, "cannot write the node attributes");
        if (st == TD_OK)
            st = attach_own_axis(
                w, h, h->idx_disp,
                make_scale(g, TD_OUT_NODE, H5T_STD_I32LE, H5T_NATIVE_INT, w->nodes, (hsize_t)w->node_count), 1, err);
        if (st == TD_OK)
            st = attach_axis(w, h, h->idx_disp, h->component, 2, err);
        if (st == TD_OK && w->housing_fields) /* housing motion */
            st = create_absolute(w, h, g, row, err);
    }
    H5Gclose(g);
    return st;
}

static td_status create_retainers(td_writer *w, h5_impl *h, td_error *err)
{
    hid_t g = make_group(h->file, TD_OUT_RETAINERS, w->retainer_count);
    hsize_t row[1];
    td_status st = TD_OK;
    int i;
    if (g < 0)
        return h5_fail(err, w, "cannot create /retainers");
    if (w->retainer_count > 0) {
        row[0] = (hsize_t)w->retainer_count;
        h->idx_ret = h->series_count;
        for (i = 0; i < RET_FIELD_COUNT(w) && st == TD_OK; i++)
            st = add_series(w, h, g, ret_fields[i].id, 2, row, 0, err);
        if (st == TD_OK)
            st = add_series(w, h, g, TD_OUT_RET_CONTACT_STATE, 2, row, 1, err);
        if (st == TD_OK && w->race_fields)
            st = add_series(w, h, g, TD_OUT_RET_ROLLING, 2, row, 1, err);
        if (st == TD_OK && w->whirl_field) {
            h->idx_whirl = h->series_count;
            st = add_series(w, h, g, TD_OUT_RET_WHIRL_RATE, 2, row, 0, err);
        }
        if (st == TD_OK && w->thermal_fields) { /* heat */
            h->idx_thermal = h->series_count;
            st = add_series(w, h, g, TD_OUT_RET_RACE_TEMPERATURE, 2, row, 0, err);
            if (st == TD_OK)
                st = add_series(w, h, g, TD_OUT_RET_HOUSING_TEMPERATURE, 2, row, 0, err);
        }
        if (st == TD_OK)
            st = attach_own_axis(w, h, h->idx_ret, make_index_scale(g, TD_OUT_RETAINER, w->retainer_count), 1, err);
    }
    H5Gclose(g);
    return st;
}

static td_status create_ambs(td_writer *w, h5_impl *h, td_error *err)
{
    hid_t g = make_group(h->file, TD_OUT_AMBS, w->amb_count);
    hsize_t row[2];
    td_status st = TD_OK;
    if (g < 0)
        return h5_fail(err, w, "cannot create /ambs");
    if (w->amb_count > 0) {
        row[0] = (hsize_t)w->amb_count;
        row[1] = 2;
        h->idx_amb = h->series_count;
        st = add_series(w, h, g, TD_OUT_AMB_FORCE, 3, row, 0, err);
        if (st == TD_OK && td_h5_attr_string(h->series[h->idx_amb].dset, td_out_name(TD_OUT_COMPONENTS),
                                             td_schema_components_list()) < 0)
            st = h5_fail(err, w, "cannot write the AMB attributes");
        if (st == TD_OK)
            st = attach_own_axis(w, h, h->idx_amb, make_index_scale(g, TD_OUT_AMB, w->amb_count), 1, err);
        if (st == TD_OK)
            st = attach_axis(w, h, h->idx_amb, h->component, 2, err);
    }
    H5Gclose(g);
    return st;
}

/* The fields of an event row, in the file's order: what the member is in memory. */
typedef enum ev_mem { EV_DOUBLE, EV_INT, EV_INT64, EV_KIND } ev_mem;
static const struct {
    td_out_id id;
    size_t offset;
    ev_mem mem;
} event_fields[] = {
    {TD_OUT_EV_TIME, offsetof(h5_event_row, time), EV_DOUBLE},
    {TD_OUT_EV_KIND, offsetof(h5_event_row, kind), EV_KIND},
    {TD_OUT_EV_RETAINER, offsetof(h5_event_row, retainer), EV_INT},
    {TD_OUT_EV_CHANGE, offsetof(h5_event_row, change), EV_INT},
    {TD_OUT_EV_SAMPLE, offsetof(h5_event_row, sample), EV_INT64},
    {TD_OUT_EV_RADIAL_VELOCITY_BEFORE, offsetof(h5_event_row, radial_velocity_before), EV_DOUBLE},
    {TD_OUT_EV_RADIAL_VELOCITY_AFTER, offsetof(h5_event_row, radial_velocity_after), EV_DOUBLE},
    {TD_OUT_EV_TANGENTIAL_VELOCITY_BEFORE, offsetof(h5_event_row, tangential_velocity_before), EV_DOUBLE},
    {TD_OUT_EV_TANGENTIAL_VELOCITY_AFTER, offsetof(h5_event_row, tangential_velocity_after), EV_DOUBLE},
    {TD_OUT_EV_IMPULSE, offsetof(h5_event_row, impulse), EV_DOUBLE},
    {TD_OUT_EV_NORMAL_FORCE, offsetof(h5_event_row, normal_force), EV_DOUBLE},
    {TD_OUT_EV_PEAK_NORMAL_FORCE, offsetof(h5_event_row, peak_normal_force), EV_DOUBLE},
    {TD_OUT_EV_CONTROLLER, offsetof(h5_event_row, controller), EV_INT},
    {TD_OUT_EV_SENSED_RADIUS, offsetof(h5_event_row, sensed_radius), EV_DOUBLE}};

/* The event kind enum (its names into `names`, "0=contact_onset,...") and the memory row type;
 * the supervisor's kind and fields only with switch_fields, so that other files keep their layout. */
static int event_types(const td_writer *w, h5_impl *h, char *names, size_t size)
{
    static const td_event_kind kinds[] = {TD_EVENT_CONTACT_ONSET, TD_EVENT_RELEASE,       TD_EVENT_FRICTION_REVERSAL,
                                          TD_EVENT_SCHEDULE,      TD_EVENT_PENALTY_ENTER, TD_EVENT_PENALTY_EXIT,
                                          TD_EVENT_ROLL_START,    TD_EVENT_ROLL_END,      TD_EVENT_CONTROLLER_SWITCH};
    size_t i, n_kinds = sizeof kinds / sizeof kinds[0] - (w->switch_fields ? 0 : 1);
    size_t n_fields = sizeof event_fields / sizeof event_fields[0] - (w->switch_fields ? 0 : 2);
    int ok;
    h->kind_type = H5Tenum_create(H5T_NATIVE_INT);
    ok = h->kind_type >= 0;
    for (i = 0; ok && i < n_kinds; i++) {
        int v = (int)kinds[i];
        size_t len = strlen(names);
        ok = H5Tenum_insert(h->kind_type, td_event_kind_name(kinds[i]), &v) >= 0;
        snprintf(names + len, size - len, "%s%d=%s", i ? "," : "", v, td_event_kind_name(kinds[i]));
    }
    h->event_mtype = ok ? H5Tcreate(H5T_COMPOUND, sizeof(h5_event_row)) : -1;
    ok = h->event_mtype >= 0;
    for (i = 0; ok && i < n_fields; i++) {
        ev_mem m = event_fields[i].mem;
        hid_t type = m == EV_DOUBLE  ? H5T_NATIVE_DOUBLE
                     : m == EV_INT   ? H5T_NATIVE_INT
                     : m == EV_INT64 ? H5T_NATIVE_INT64
                                     : h->kind_type;
        ok = H5Tinsert(h->event_mtype, td_out_name(event_fields[i].id), event_fields[i].offset, type) >= 0;
    }
    return ok;
}

/* The event kind enum, the compound row types and the /events dataset with its scale /event. */
static td_status create_events(td_writer *w, h5_impl *h, td_error *err)
{
    char names[256] = "";
    int ok = event_types(w, h, names, sizeof names);
    if (ok) {
        h->event_ftype = H5Tcopy(h->event_mtype);
        ok = h->event_ftype >= 0 && H5Tpack(h->event_ftype) >= 0;
    }
    if (ok)
        h->event_dset = td_h5_append_create(h->file, td_out_name(TD_OUT_EVENTS), h->event_ftype, 1, NULL,
                                            H5_EVENT_CHUNK, w->compression);
    if (ok && h->event_dset >= 0)
        h->event_index = td_h5_append_create(h->file, td_out_name(TD_OUT_EVENT), H5T_STD_I64LE, 1, NULL, H5_EVENT_CHUNK,
                                             w->compression);
    if (!ok || h->event_dset < 0 || h->event_index < 0 ||
        H5DSset_scale(h->event_index, td_out_name(TD_OUT_EVENT)) < 0 ||
        H5DSattach_scale(h->event_dset, h->event_index, 0) < 0)
        return h5_fail(err, w, "cannot create /events");
    if (units_attr(h->event_index, TD_OUT_EVENT) < 0 ||
        td_h5_attr_string(h->event_dset, td_out_name(TD_OUT_KIND_NAMES), names) < 0 ||
        units_attr(h->event_dset, TD_OUT_EVENTS) < 0)
        return h5_fail(err, w, "cannot write the /events attributes");
    return TD_OK;
}

static size_t choose_chunk_rows(const td_writer *w)
{
    size_t widest = sizeof(double) * 2 * (size_t)(w->node_count > w->amb_count ? w->node_count : w->amb_count);
    size_t rows = H5_CHUNK_ROWS;
    if ((size_t)w->retainer_count * sizeof(double) > widest)
        widest = (size_t)w->retainer_count * sizeof(double);
    if (widest > 0 && H5_CHUNK_BYTES / widest < rows)
        rows = H5_CHUNK_BYTES / widest;
    return rows < 16 ? 16 : rows;
}

static void h5_destroy(td_writer *w);

static td_status open_impl(td_writer *w, h5_impl *h, td_error *err)
{
    td_status st;
    /* The writer created tmp_path exclusively; HDF5 opens it by name, so the descriptor goes. */
    close(w->tmp_fd);
    w->tmp_fd = -1;
    h->file = td_h5_create_file(w->tmp_path, 1, &h->io_errno, &h->driver);
    if (h->file < 0)
        return h5_fail(err, w, h->driver < 0 ? "cannot set up file access" : "cannot create the file");
    h->idx_time = h->series_count;
    if ((st = add_series(w, h, h->file, TD_OUT_TIME, 1, NULL, 0, err)) != TD_OK)
        return st;
    if (w->speed_field) {
        h->idx_speed = h->series_count;
        if ((st = add_series(w, h, h->file, TD_OUT_SPEED, 1, NULL, 0, err)) != TD_OK)
            return st;
    }
    if ((w->node_count > 0 || w->amb_count > 0 || w->housing_fields) &&
        (h->component = make_component_scale(h->file)) < 0)
        return h5_fail(err, w, "cannot create /component");
    if ((st = create_nodes(w, h, err)) != TD_OK || (st = create_retainers(w, h, err)) != TD_OK ||
        (st = create_ambs(w, h, err)) != TD_OK || (!w->omit_events && (st = create_events(w, h, err)) != TD_OK))
        return st;
    if (w->housing_fields && (st = create_housing(w, h, err)) != TD_OK) /* housing motion */
        return st;
    if (w->window_fields && (st = create_windows(w, h, err)) != TD_OK) /* long runs */
        return st;
    if (units_attr(h->file, TD_OUT_ROOT) < 0)
        return h5_fail(err, w, "cannot write the units attribute");
    return TD_OK;
}

static td_status h5_open(td_writer *w, td_error *err)
{
    h5_impl *h = calloc(1, sizeof *h);
    td_status st;
    if (!h)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", w->path);
    h->file = h->event_dset = h->event_mtype = h->event_ftype = h->kind_type = h->event_index = h->component =
        h->driver = -1;
    h->idx_time = h->idx_speed = h->idx_disp = h->idx_ret = h->idx_whirl = h->idx_amb = -1;
    h->idx_thermal = -1;
    h->idx_housing = h->idx_abs = -1; /* housing motion */
    h->chunk_rows = choose_chunk_rows(w);
    w->impl = h;
    h->event_buf = malloc(H5_EVENT_CHUNK * sizeof *h->event_buf);
    if (!h->event_buf) {
        free(h);
        w->impl = NULL;
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", w->path);
    }
    H5E_BEGIN_TRY
    {
        st = io_checked(open_impl(w, h, err), w, "cannot write the file", err);
    }
    H5E_END_TRY;
    if (st != TD_OK)
        h5_destroy(w);
    return st;
}

/* ---- samples ----------------------------------------------------------------------------- */

/* Write the buffered rows to the end of every sample dataset. */
static td_status flush_rows(td_writer *w, h5_impl *h, td_error *err)
{
    int i;
    if (h->buffered == 0)
        return TD_OK;
    for (i = 0; i < h->series_count; i++) {
        const h5_series *s = &h->series[i];
        if (td_h5_append_rows(s->dset, s->is_int8 ? H5T_NATIVE_INT8 : H5T_NATIVE_DOUBLE, s->rank, s->row_dims,
                              h->flushed, h->buffered, s->buf) < 0)
            return h5_fail(err, w, "cannot write samples");
    }
    h->flushed += h->buffered;
    h->buffered = 0;
    return TD_OK;
}

static void buffer_row(const td_writer *w, h5_impl *h, double t, double speed, const double *node_xy,
                       const td_retainer_state *ret, const double *amb_f)
{
    size_t r = h->buffered;
    int i, f;
    ((double *)h->series[h->idx_time].buf)[r] = t;
    if (h->idx_speed >= 0)
        ((double *)h->series[h->idx_speed].buf)[r] = speed;
    if (h->idx_disp >= 0)
        memcpy((double *)h->series[h->idx_disp].buf + r * 2 * (size_t)w->node_count, node_xy,
               2 * (size_t)w->node_count * sizeof(double));
    if (h->idx_ret >= 0) {
        int nf = RET_FIELD_COUNT(w);
        for (f = 0; f < nf; f++) {
            double *row = (double *)h->series[h->idx_ret + f].buf + r * (size_t)w->retainer_count;
            for (i = 0; i < w->retainer_count; i++)
                memcpy(&row[i], (const char *)&ret[i] + ret_fields[f].offset, sizeof(double));
        }
        for (i = 0; i < w->retainer_count; i++) {
            size_t at = r * (size_t)w->retainer_count + (size_t)i;
            ((int8_t *)h->series[h->idx_ret + nf].buf)[at] = (int8_t)(ret[i].in_contact ? 1 : 0);
            if (w->race_fields)
                ((int8_t *)h->series[h->idx_ret + nf + 1].buf)[at] = (int8_t)(ret[i].rolling ? 1 : 0);
            if (h->idx_whirl >= 0)
                ((double *)h->series[h->idx_whirl].buf)[at] = ret[i].whirl_rate;
            if (h->idx_thermal >= 0) { /* heat */
                ((double *)h->series[h->idx_thermal].buf)[at] = ret[i].race_temperature;
                ((double *)h->series[h->idx_thermal + 1].buf)[at] = ret[i].housing_temperature;
            }
        }
    }
    if (h->idx_amb >= 0)
        memcpy((double *)h->series[h->idx_amb].buf + r * 2 * (size_t)w->amb_count, amb_f,
               2 * (size_t)w->amb_count * sizeof(double));
    for (f = 0; h->idx_housing >= 0 && f < TD_WRITER_HOUSING_COUNT(w) / 2; f++) /* housing motion */
        memcpy((double *)h->series[h->idx_housing + f].buf + r * 2, w->housing + 2 * f, 2 * sizeof(double));
    if (h->idx_abs >= 0)
        memcpy((double *)h->series[h->idx_abs].buf + r * 2 * (size_t)w->node_count, w->node_abs_xy,
               2 * (size_t)w->node_count * sizeof(double));
    h->buffered++;
}

static td_status h5_sample(td_writer *w, double t, double speed, const double *node_xy, const td_retainer_state *ret,
                           const double *amb_f, td_error *err)
{
    h5_impl *h = w->impl;
    td_status st = TD_OK;
    buffer_row(w, h, t, speed, node_xy, ret, amb_f);
    if (h->buffered == h->chunk_rows) {
        H5E_BEGIN_TRY
        {
            st = io_checked(flush_rows(w, h, err), w, "cannot write samples", err);
        }
        H5E_END_TRY;
    }
    return st;
}

/* ---- events ------------------------------------------------------------------------------ */

/* Append the buffered events to /events and their row numbers to /event. */
static td_status flush_events(td_writer *w, h5_impl *h, td_error *err)
{
    int64_t rows[H5_EVENT_CHUNK];
    size_t i;
    herr_t rc;
    if (h->events_buffered == 0)
        return TD_OK;
    for (i = 0; i < h->events_buffered; i++)
        rows[i] = (int64_t)(h->event_rows + i);
    rc = td_h5_append_rows(h->event_dset, h->event_mtype, 1, NULL, h->event_rows, h->events_buffered, h->event_buf);
    if (rc >= 0)
        rc = td_h5_append_rows(h->event_index, H5T_NATIVE_INT64, 1, NULL, h->event_rows, h->events_buffered, rows);
    if (rc < 0)
        return h5_fail(err, w, "cannot write events");
    h->event_rows += h->events_buffered;
    h->events_buffered = 0;
    return TD_OK;
}

static td_status h5_event(td_writer *w, const td_event *ev, long sample, td_error *err)
{
    h5_impl *h = w->impl;
    h5_event_row *row = &h->event_buf[h->events_buffered++];
    td_status st = TD_OK;
    memset(row, 0, sizeof *row);
    row->time = ev->time;
    row->kind = (int)ev->kind;
    row->retainer = ev->retainer;
    row->change = ev->change;
    row->sample = (int64_t)sample;
    row->radial_velocity_before = ev->radial_velocity_before;
    row->radial_velocity_after = ev->radial_velocity_after;
    row->tangential_velocity_before = ev->tangential_velocity_before;
    row->tangential_velocity_after = ev->tangential_velocity_after;
    row->impulse = ev->impulse;
    row->normal_force = ev->normal_force;
    row->peak_normal_force = ev->peak_normal_force;
    row->controller = ev->controller;
    row->sensed_radius = ev->sensed_radius;
    if (h->events_buffered == H5_EVENT_CHUNK) {
        H5E_BEGIN_TRY
        {
            st = io_checked(flush_events(w, h, err), w, "cannot write events", err);
        }
        H5E_END_TRY;
    }
    return st;
}

/* ---- finish ------------------------------------------------------------------------------ */

static herr_t write_attr(hid_t file, const td_attr *a)
{
    switch (a->type) {
    case TD_ATTR_STRING: return td_h5_attr_string(file, a->name, a->text);
    case TD_ATTR_DOUBLE:
        return td_h5_attr_numeric(file, a->name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, a->doubles, a->count, a->is_array);
    case TD_ATTR_LONG:
        return td_h5_attr_numeric(file, a->name, H5T_STD_I64LE, H5T_NATIVE_LONG, a->longs, a->count, a->is_array);
    }
    return -1;
}

static td_status finish_impl(td_writer *w, h5_impl *h, int complete, const char *reason, td_error *err)
{
    td_status st = flush_rows(w, h, err);
    int i;
    if (st == TD_OK)
        st = flush_events(w, h, err);
    if (st == TD_OK && h->windows && td_h5_windows_flush(h->windows) < 0) /* long runs */
        st = h5_fail(err, w, "cannot write window summaries");
    if (st != TD_OK)
        return st;
    for (i = 0; i < w->attr_count; i++)
        if (write_attr(h->file, &w->attrs[i]) < 0)
            return h5_fail(err, w, "cannot write a root attribute");
    if (!complete && td_h5_attr_string(h->file, td_out_name(TD_OUT_INCOMPLETE_REASON), reason) < 0)
        return h5_fail(err, w, "cannot write incomplete_reason");
    /* The flag last: a file that stops before this line has no flag at all. */
    if (td_h5_attr_int(h->file, td_out_name(TD_OUT_COMPLETE), complete ? 1 : 0) < 0)
        return h5_fail(err, w, "cannot write the completeness flag");
    if (H5Fflush(h->file, H5F_SCOPE_GLOBAL) < 0)
        return h5_fail(err, w, "cannot flush the file");
    return TD_OK;
}

/* Close every handle; returns -1 if closing the file failed (its data may be lost). */
static herr_t close_handles(h5_impl *h)
{
    herr_t rc = 0;
    int i;
    for (i = 0; i < h->series_count; i++) {
        if (h->series[i].dset >= 0)
            H5Dclose(h->series[i].dset);
        free(h->series[i].buf);
        h->series[i].dset = -1;
        h->series[i].buf = NULL;
    }
    h->series_count = 0;
    td_h5_windows_free(h->windows); /* long runs */
    h->windows = NULL;
    free(h->event_buf);
    h->event_buf = NULL;
    if (h->event_dset >= 0)
        H5Dclose(h->event_dset);
    if (h->event_index >= 0)
        H5Dclose(h->event_index);
    if (h->component >= 0)
        H5Dclose(h->component);
    if (h->event_ftype >= 0)
        H5Tclose(h->event_ftype);
    if (h->event_mtype >= 0)
        H5Tclose(h->event_mtype);
    if (h->kind_type >= 0)
        H5Tclose(h->kind_type);
    h->event_dset = h->event_ftype = h->event_mtype = h->kind_type = h->event_index = h->component = -1;
    if (h->file >= 0)
        rc = H5Fclose(h->file);
    h->file = -1;
    td_h5_vfd_release(h->driver);
    h->driver = -1;
    return rc;
}

static td_status h5_finish(td_writer *w, int complete, const char *reason, td_error *err)
{
    h5_impl *h = w->impl;
    td_status st;
    H5E_BEGIN_TRY
    {
        st = io_checked(finish_impl(w, h, complete, reason, err), w, "cannot finish the file", err);
        if (close_handles(h) < 0 && st == TD_OK)
            st = h5_fail(err, w, "cannot close the file");
        st = io_checked(st, w, "cannot close the file", err);
    }
    H5E_END_TRY;
    free(h);
    w->impl = NULL;
    return st;
}

static void h5_destroy(td_writer *w)
{
    h5_impl *h = w->impl;
    if (!h)
        return;
    H5E_BEGIN_TRY
    {
        close_handles(h);
    }
    H5E_END_TRY;
    free(h);
    w->impl = NULL;
}

/* long runs: one window summary */
static td_status h5_window(td_writer *w, const td_window_summary *win, td_error *err)
{
    h5_impl *h = w->impl;
    td_status st = TD_OK;
    H5E_BEGIN_TRY
    {
        if (td_h5_windows_add(h->windows, win) < 0)
            st = h5_fail(err, w, "cannot write window summaries");
        st = io_checked(st, w, "cannot write window summaries", err);
    }
    H5E_END_TRY;
    return st;
}

const td_writer_ops td_hdf5_writer_ops = {h5_open, h5_sample, h5_event, h5_finish, h5_destroy, h5_window};
