/*
 * Reading result files (touchdown/result.h): the names come from the schema (schema.c), the same
 * table the writers take theirs from. Every HDF5 call runs inside H5E_BEGIN_TRY/H5E_END_TRY: the
 * library never prints. A file is opened once and read lazily, dataset by dataset, so that a
 * damaged file costs no more HDF5 calls than the reads asked for (HDF5 1.10 can hang on some
 * damaged files: fuzz/findings/P1).
 */
#include "io/schema.h"
#include "io/writer_internal.h"
#include "util/error_internal.h"

#include <errno.h>
#include <hdf5.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct td_result {
    hid_t file;
    char *path;
    td_result_kind kind;
    td_result_flag flag;
};

/* Longest object path the reader builds. */
#define RESULT_PATH_SIZE 1024

/* ---- paths and links ------------------------------------------------------------------------ */

/* The object path of `id` + `sub` into buf ("." for the root, as HDF5 names it); 0 if too long. */
static int object_path(td_out_id id, const char *sub, char *buf, size_t n)
{
    int len = td_out_path(id, sub, buf, n);
    if (len < 0 || (size_t)len >= n)
        return 0;
    if (len == 0)
        snprintf(buf, n, ".");
    return 1;
}

/* 1 if every link of `path` ("a", "a/b", ...) exists under `loc` (H5Lexists needs each step). */
static int link_exists(hid_t loc, const char *path)
{
    char part[RESULT_PATH_SIZE];
    const char *p = path;
    if (!strcmp(path, "."))
        return 1;
    for (;;) {
        const char *slash = strchr(p, '/');
        size_t len = slash ? (size_t)(slash - path) : strlen(path);
        if (len == 0 || len >= sizeof part)
            return 0;
        memcpy(part, path, len);
        part[len] = '\0';
        if (H5Lexists(loc, part, H5P_DEFAULT) <= 0)
            return 0;
        if (!slash)
            return 1;
        p = slash + 1;
    }
}

static int is_attribute(td_out_id id)
{
    return td_out_place_of(id) == TD_OUT_ATTRIBUTE;
}

/* 1 if the attribute `name` of the object `obj` (a path) exists. */
static int attribute_exists(hid_t file, const char *obj, const char *name)
{
    return link_exists(file, obj) && H5Aexists_by_name(file, obj, name, H5P_DEFAULT) > 0;
}

static td_status missing(td_error *err, const td_result *r, td_out_id id, const char *obj)
{
    if (is_attribute(id))
        return td_error_set(err, TD_ERR_INVALID, "%s: no attribute '%s' on /%s", r->path, td_out_name(id),
                            strcmp(obj, ".") ? obj : "");
    return td_error_set(err, TD_ERR_INVALID, "%s: no readable /%s", r->path, obj);
}

/* ---- open ----------------------------------------------------------------------------------- */

/* The flag attribute of a run file or a sweep table: 1 when nonzero, 0, or none. */
static td_result_flag read_flag(hid_t file)
{
    const char *name = td_out_name(TD_OUT_COMPLETE);
    double v = 0.0;
    hid_t a, type;
    int ok = 0;
    if (H5Aexists(file, name) <= 0 || (a = H5Aopen(file, name, H5P_DEFAULT)) < 0)
        return TD_RESULT_NO_FLAG;
    type = H5Aget_type(a);
    if (type >= 0 && (H5Tget_class(type) == H5T_INTEGER || H5Tget_class(type) == H5T_FLOAT)) {
        hid_t space = H5Aget_space(a);
        ok = space >= 0 && H5Sget_simple_extent_npoints(space) == 1 && H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0;
        if (space >= 0)
            H5Sclose(space);
    }
    if (type >= 0)
        H5Tclose(type);
    H5Aclose(a);
    return !ok ? TD_RESULT_NO_FLAG : v != 0.0 ? TD_RESULT_COMPLETE : TD_RESULT_INCOMPLETE;
}

static int has(hid_t file, td_out_id id)
{
    char path[RESULT_PATH_SIZE];
    return object_path(id, NULL, path, sizeof path) && link_exists(file, path);
}

/* Which file it is, from the names only the writer of each kind writes; -1: none. */
static int detect_kind(hid_t file)
{
    if (has(file, TD_OUT_SWEEP_POINT) && has(file, TD_OUT_SWEEP_VARY))
        return TD_RESULT_SWEEP;
    if (has(file, TD_OUT_TIME) && has(file, TD_OUT_RETAINERS))
        return TD_RESULT_RUN;
    if (H5Aexists(file, td_out_name(TD_OUT_PRODUCER)) > 0 || has(file, TD_OUT_CAMPBELL) || has(file, TD_OUT_MODES))
        return TD_RESULT_MODAL;
    return -1;
}

static td_status open_file(td_result *r, td_error *err)
{
    FILE *probe = fopen(r->path, "rb");
    int kind;
    if (!probe)
        return td_error_set(err, TD_ERR_IO, "%s: %s", r->path, strerror(errno));
    fclose(probe);
    if (H5Fis_hdf5(r->path) <= 0)
        return td_error_set(err, TD_ERR_IO,
                            "%s: not an HDF5 file (a touchdown result is the .h5 file of 'touchdown run', 'modal' or "
                            "'sweep')",
                            r->path);
    if ((r->file = H5Fopen(r->path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0)
        return td_error_set(err, TD_ERR_IO, "%s: cannot open the HDF5 file (damaged or cut short?)", r->path);
    if ((kind = detect_kind(r->file)) < 0)
        return td_error_set(err, TD_ERR_INVALID,
                            "%s: not a touchdown result file (neither /time and /retainers, /campbell or /modes, nor "
                            "/point and /vary)",
                            r->path);
    r->kind = (td_result_kind)kind;
    r->flag = kind == TD_RESULT_MODAL ? TD_RESULT_COMPLETE : read_flag(r->file);
    return TD_OK;
}

td_status td_result_open(const char *path, td_result **out, td_error *err)
{
    td_result *r;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_result_open: NULL output pointer");
    *out = NULL;
    if (!path || !path[0])
        return td_error_set(err, TD_ERR_INVALID, "td_result_open: empty path");
    if (!(r = calloc(1, sizeof *r)) || !(r->path = malloc(strlen(path) + 1))) {
        free(r);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", path);
    }
    strcpy(r->path, path);
    r->file = -1;
    H5E_BEGIN_TRY
    {
        st = open_file(r, err);
    }
    H5E_END_TRY;
    if (st != TD_OK) {
        td_result_free(&r);
        return st;
    }
    *out = r;
    return TD_OK;
}

void td_result_free(td_result **r)
{
    if (!r || !*r)
        return;
    if ((*r)->file >= 0) {
        H5E_BEGIN_TRY
        {
            H5Fclose((*r)->file);
        }
        H5E_END_TRY;
    }
    free((*r)->path);
    free(*r);
    *r = NULL;
}

td_result_kind td_result_get_kind(const td_result *r)
{
    return r ? r->kind : TD_RESULT_NO_KIND;
}

td_result_flag td_result_get_flag(const td_result *r)
{
    return r ? r->flag : TD_RESULT_NO_FLAG;
}

int td_result_complete(const td_result *r)
{
    size_t len = r ? strlen(r->path) : 0, suffix = strlen(TD_IO_TEMP_SUFFIX);
    if (!r || r->flag != TD_RESULT_COMPLETE)
        return 0;
    return !(len >= suffix && !strcmp(r->path + len - suffix, TD_IO_TEMP_SUFFIX));
}

int td_result_has(const td_result *r, td_out_id id, const char *sub)
{
    char obj[RESULT_PATH_SIZE];
    int yes = 0;
    if (!r || !td_schema(id) || !object_path(id, sub, obj, sizeof obj))
        return 0;
    H5E_BEGIN_TRY
    {
        yes = is_attribute(id) ? attribute_exists(r->file, obj, td_out_name(id)) : link_exists(r->file, obj);
    }
    H5E_END_TRY;
    return yes;
}

/* ---- numbers -------------------------------------------------------------------------------- */

void td_result_array_free(td_result_array *a)
{
    if (!a)
        return;
    free(a->v);
    memset(a, 0, sizeof *a);
}

static int is_numeric(hid_t type)
{
    return type >= 0 && (H5Tget_class(type) == H5T_FLOAT || H5Tget_class(type) == H5T_INTEGER);
}

/* Shape of `space` (rank 0..3) into a; 0 if it has more axes. */
static int take_shape(hid_t space, td_result_array *a)
{
    hsize_t dims[3] = {1, 1, 1};
    int rank = space >= 0 ? H5Sget_simple_extent_ndims(space) : -1, i;
    if (rank < 0 || rank > 3 || H5Sget_simple_extent_dims(space, dims, NULL) < 0)
        return 0;
    a->rank = rank;
    a->n = 1;
    for (i = 0; i < 3; i++) {
        a->dims[i] = i < rank ? (size_t)dims[i] : 1;
        a->n *= a->dims[i];
    }
    return 1;
}

/* A text attribute of `obj` read with its own type (HDF5 will not convert UTF-8 to ASCII). */
static char *attr_text(hid_t obj, const char *name)
{
    hid_t a, type = -1, space = -1;
    char *s = NULL;
    if (H5Aexists(obj, name) <= 0 || (a = H5Aopen(obj, name, H5P_DEFAULT)) < 0)
        return NULL;
    type = H5Aget_type(a);
    space = H5Aget_space(a);
    if (type >= 0 && space >= 0 && H5Tget_class(type) == H5T_STRING && H5Sget_simple_extent_npoints(space) == 1) {
        if (H5Tis_variable_str(type) > 0) {
            char *vs = NULL;
            if (H5Aread(a, type, &vs) >= 0 && vs) {
                if ((s = malloc(strlen(vs) + 1)) != NULL)
                    strcpy(s, vs);
                H5free_memory(vs);
            }
        } else if ((s = calloc(H5Tget_size(type) + 1, 1)) != NULL && H5Aread(a, type, s) < 0) {
            free(s);
            s = NULL;
        }
    }
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    H5Aclose(a);
    return s;
}

/* The numeric dataset at `path` into a, its units from its attribute (else the schema's). */
static int read_dataset(hid_t file, const char *path, td_out_id id, td_result_array *a)
{
    hid_t d, space, type;
    char *units;
    int ok = 0;
    if (!link_exists(file, path) || (d = H5Dopen2(file, path, H5P_DEFAULT)) < 0)
        return 0;
    space = H5Dget_space(d);
    type = H5Dget_type(d);
    if (is_numeric(type) && take_shape(space, a) && a->rank >= 1 &&
        (a->v = malloc((a->n ? a->n : 1) * sizeof *a->v)) != NULL)
        ok = a->n == 0 || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a->v) >= 0;
    units = ok ? attr_text(d, td_out_name(TD_OUT_UNITS)) : NULL;
    snprintf(a->units, sizeof a->units, "%s", units ? units : td_out_units(id));
    free(units);
    if (type >= 0)
        H5Tclose(type);
    if (space >= 0)
        H5Sclose(space);
    H5Dclose(d);
    return ok;
}

/* The numeric attribute `name` of the object `obj` into a (units: the schema's). */
static int read_attribute(hid_t file, const char *obj, td_out_id id, td_result_array *a)
{
    hid_t at, space, type;
    int ok = 0;
    if (!attribute_exists(file, obj, td_out_name(id)) ||
        (at = H5Aopen_by_name(file, obj, td_out_name(id), H5P_DEFAULT, H5P_DEFAULT)) < 0)
        return 0;
    space = H5Aget_space(at);
    type = H5Aget_type(at);
    if (is_numeric(type) && take_shape(space, a) && a->n > 0 && (a->v = malloc(a->n * sizeof *a->v)) != NULL)
        ok = H5Aread(at, H5T_NATIVE_DOUBLE, a->v) >= 0;
    snprintf(a->units, sizeof a->units, "%s", td_out_units(id));
    if (type >= 0)
        H5Tclose(type);
    if (space >= 0)
        H5Sclose(space);
    H5Aclose(at);
    return ok;
}

td_status td_result_read(const td_result *r, td_out_id id, const char *sub, td_result_array *a, td_error *err)
{
    char obj[RESULT_PATH_SIZE];
    int ok = 0;
    if (!a)
        return td_error_set(err, TD_ERR_INVALID, "td_result_read: NULL array");
    memset(a, 0, sizeof *a);
    if (!r || !td_schema(id))
        return td_error_set(err, TD_ERR_INVALID, "td_result_read: NULL result or unknown id %d", (int)id);
    if (!object_path(id, sub, obj, sizeof obj))
        return td_error_set(err, TD_ERR_INVALID, "%s: a path longer than %d characters", r->path, RESULT_PATH_SIZE - 1);
    H5E_BEGIN_TRY
    {
        ok = is_attribute(id) ? read_attribute(r->file, obj, id, a) : read_dataset(r->file, obj, id, a);
    }
    H5E_END_TRY;
    if (!ok) {
        td_result_array_free(a);
        return missing(err, r, id, obj);
    }
    return TD_OK;
}

/* ---- text ----------------------------------------------------------------------------------- */

td_status td_result_read_text(const td_result *r, td_out_id id, const char *sub, char **text, td_error *err)
{
    char obj[RESULT_PATH_SIZE];
    if (!text)
        return td_error_set(err, TD_ERR_INVALID, "td_result_read_text: NULL output");
    *text = NULL;
    if (!r || !is_attribute(id) || !object_path(id, sub, obj, sizeof obj))
        return td_error_set(err, TD_ERR_INVALID, "td_result_read_text: not an attribute");
    H5E_BEGIN_TRY
    {
        hid_t o = link_exists(r->file, obj) ? H5Oopen(r->file, obj, H5P_DEFAULT) : -1;
        if (o >= 0) {
            *text = attr_text(o, td_out_name(id));
            H5Oclose(o);
        }
    }
    H5E_END_TRY;
    return *text ? TD_OK : missing(err, r, id, obj);
}

void td_result_strings_free(char **text, size_t n)
{
    size_t i;
    for (i = 0; text && i < n; i++)
        free(text[i]);
    free(text);
}

/* Copies of the n strings raw[] (NULL: "") into *out; 0 when out of memory. */
static int copy_strings(char **raw, size_t n, char ***out)
{
    char **copy = calloc(n + 1, sizeof *copy);
    size_t i;
    for (i = 0; copy && i < n; i++) {
        const char *s = raw[i] ? raw[i] : "";
        if (!(copy[i] = malloc(strlen(s) + 1))) {
            td_result_strings_free(copy, i);
            return 0;
        }
        strcpy(copy[i], s);
    }
    *out = copy;
    return copy != NULL;
}

/* A rank-1 dataset of variable-length strings, read with its own type (UTF-8 stays UTF-8). */
static int read_strings(hid_t file, const char *path, char ***out, size_t *n)
{
    hid_t d, type, space;
    char **raw = NULL;
    hssize_t count = -1;
    int ok = 0;
    if (!link_exists(file, path) || (d = H5Dopen2(file, path, H5P_DEFAULT)) < 0)
        return 0;
    type = H5Dget_type(d);
    space = H5Dget_space(d);
    if (type >= 0 && space >= 0 && H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0)
        count = H5Sget_simple_extent_npoints(space);
    if (count >= 0 && (raw = calloc((size_t)count + 1, sizeof *raw)) != NULL &&
        H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw) >= 0) {
        ok = copy_strings(raw, (size_t)count, out);
        H5Dvlen_reclaim(type, space, H5P_DEFAULT, raw);
    }
    free(raw);
    *n = ok ? (size_t)count : 0;
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    H5Dclose(d);
    return ok;
}

td_status td_result_read_strings(const td_result *r, td_out_id id, const char *sub, char ***text, size_t *n,
                                 td_error *err)
{
    char obj[RESULT_PATH_SIZE];
    int ok = 0;
    if (!text || !n)
        return td_error_set(err, TD_ERR_INVALID, "td_result_read_strings: NULL output");
    *text = NULL;
    *n = 0;
    if (!r || is_attribute(id) || !object_path(id, sub, obj, sizeof obj))
        return td_error_set(err, TD_ERR_INVALID, "td_result_read_strings: not a dataset");
    H5E_BEGIN_TRY
    {
        ok = read_strings(r->file, obj, text, n);
    }
    H5E_END_TRY;
    return ok ? TD_OK : missing(err, r, id, obj);
}

/* ---- columns -------------------------------------------------------------------------------- */

typedef struct column_list {
    size_t n; /* values per column */
    const char *skip;
    char **names;
    size_t count, cap;
    int failed;
} column_list;

/* 1 if loc/name is a numeric 1-D dataset of l->n values (a dangling link or a group: 0). */
static int is_column(hid_t loc, const char *name, const column_list *l)
{
    hid_t d, space, type;
    int ok;
    if (!*name || !strcmp(name, l->skip) || H5Oexists_by_name(loc, name, H5P_DEFAULT) <= 0 ||
        (d = H5Dopen2(loc, name, H5P_DEFAULT)) < 0)
        return 0;
    space = H5Dget_space(d);
    type = H5Dget_type(d);
    ok = is_numeric(type) && space >= 0 && H5Sget_simple_extent_ndims(space) == 1 &&
         H5Sget_simple_extent_npoints(space) == (hssize_t)l->n;
    if (type >= 0)
        H5Tclose(type);
    if (space >= 0)
        H5Sclose(space);
    H5Dclose(d);
    return ok;
}

static herr_t add_column(hid_t loc, const char *name, const H5L_info_t *info, void *data)
{
    column_list *l = data;
    (void)info;
    if (!is_column(loc, name, l))
        return 0;
    if (l->count == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 16;
        char **p = realloc(l->names, cap * sizeof *p);
        if (!p) {
            l->failed = 1;
            return -1;
        }
        l->names = p;
        l->cap = cap;
    }
    if (!(l->names[l->count] = malloc(strlen(name) + 1))) {
        l->failed = 1;
        return -1;
    }
    strcpy(l->names[l->count++], name);
    return 0;
}

td_status td_result_columns(const td_result *r, td_out_id id, const char *sub, size_t n, char ***names, size_t *n_names,
                            td_error *err)
{
    char obj[RESULT_PATH_SIZE];
    column_list l;
    hsize_t at = 0;
    hid_t g = -1;
    if (!names || !n_names)
        return td_error_set(err, TD_ERR_INVALID, "td_result_columns: NULL output");
    *names = NULL;
    *n_names = 0;
    if (!r || td_out_place_of(id) != TD_OUT_GROUP || !object_path(id, sub, obj, sizeof obj))
        return td_error_set(err, TD_ERR_INVALID, "td_result_columns: not a group");
    memset(&l, 0, sizeof l);
    l.n = n;
    l.skip = td_out_name(TD_OUT_SWEEP_POINT);
    H5E_BEGIN_TRY
    {
        if (link_exists(r->file, obj) && (g = H5Gopen2(r->file, obj, H5P_DEFAULT)) >= 0) {
            H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, &at, add_column, &l);
            H5Gclose(g);
        }
    }
    H5E_END_TRY;
    if (g < 0 || l.failed) {
        td_result_strings_free(l.names, l.count);
        return l.failed ? td_error_set(err, TD_ERR_NOMEM, "out of memory listing %s", r->path)
                        : missing(err, r, id, obj);
    }
    *names = l.names;
    *n_names = l.count;
    return TD_OK;
}

/* ---- events --------------------------------------------------------------------------------- */

/* One row in memory; the fields the file lacks stay 0. */
typedef struct event_row {
    double time;
    int kind;
    int retainer;
    int change;
    int64_t sample;
    double v[7];    /* radial_velocity_before .. peak_normal_force, in the order of the schema */
    int controller; /* a recovery supervisor's files only; -1 when the file lacks it */
    double sensed_radius;
} event_row;

/* The memory row type: every field of the file's compound that the schema names, the kind as
 * the file's own enum (HDF5 converts enums by name) in native size. -1 on failure. */
static hid_t event_memory_type(hid_t ftype, hid_t *kind_type)
{
    hid_t m = H5Tcreate(H5T_COMPOUND, sizeof(event_row)), kf;
    int idx = H5Tget_member_index(ftype, td_out_name(TD_OUT_EV_KIND)), k, ok = m >= 0 && idx >= 0;
    *kind_type = -1;
    if (ok && (kf = H5Tget_member_type(ftype, (unsigned)idx)) >= 0) {
        if (H5Tget_class(kf) == H5T_ENUM)
            *kind_type = H5Tget_native_type(kf, H5T_DIR_DEFAULT);
        H5Tclose(kf);
    }
    ok = ok && *kind_type >= 0 && H5Tget_size(*kind_type) == sizeof(int) &&
         H5Tinsert(m, td_out_name(TD_OUT_EV_TIME), offsetof(event_row, time), H5T_NATIVE_DOUBLE) >= 0 &&
         H5Tinsert(m, td_out_name(TD_OUT_EV_KIND), offsetof(event_row, kind), *kind_type) >= 0;
    if (ok && H5Tget_member_index(ftype, td_out_name(TD_OUT_EV_RETAINER)) >= 0)
        ok = H5Tinsert(m, td_out_name(TD_OUT_EV_RETAINER), offsetof(event_row, retainer), H5T_NATIVE_INT) >= 0;
    if (ok && H5Tget_member_index(ftype, td_out_name(TD_OUT_EV_CHANGE)) >= 0)
        ok = H5Tinsert(m, td_out_name(TD_OUT_EV_CHANGE), offsetof(event_row, change), H5T_NATIVE_INT) >= 0;
    if (ok && H5Tget_member_index(ftype, td_out_name(TD_OUT_EV_SAMPLE)) >= 0)
        ok = H5Tinsert(m, td_out_name(TD_OUT_EV_SAMPLE), offsetof(event_row, sample), H5T_NATIVE_INT64) >= 0;
    if (ok && H5Tget_member_index(ftype, td_out_name(TD_OUT_EV_CONTROLLER)) >= 0)
        ok = H5Tinsert(m, td_out_name(TD_OUT_EV_CONTROLLER), offsetof(event_row, controller), H5T_NATIVE_INT) >= 0;
    if (ok && H5Tget_member_index(ftype, td_out_name(TD_OUT_EV_SENSED_RADIUS)) >= 0)
        ok = H5Tinsert(m, td_out_name(TD_OUT_EV_SENSED_RADIUS), offsetof(event_row, sensed_radius),
                       H5T_NATIVE_DOUBLE) >= 0;
    for (k = 0; ok && k < 7; k++) {
        const char *name = td_out_name((td_out_id)(TD_OUT_EV_RADIAL_VELOCITY_BEFORE + k));
        if (H5Tget_member_index(ftype, name) >= 0)
            ok = H5Tinsert(m, name, offsetof(event_row, v) + (size_t)k * sizeof(double), H5T_NATIVE_DOUBLE) >= 0;
    }
    if (!ok && m >= 0) {
        H5Tclose(m);
        m = -1;
    }
    return m;
}

static void take_event(const event_row *row, hid_t kind_type, td_result_event *e)
{
    int kind = row->kind;
    memset(e, 0, sizeof *e);
    e->event.time = row->time;
    e->event.kind = (td_event_kind)row->kind;
    e->event.retainer = row->retainer;
    e->event.change = row->change;
    e->sample = (long)row->sample;
    e->event.radial_velocity_before = row->v[0];
    e->event.radial_velocity_after = row->v[1];
    e->event.tangential_velocity_before = row->v[2];
    e->event.tangential_velocity_after = row->v[3];
    e->event.impulse = row->v[4];
    e->event.normal_force = row->v[5];
    e->event.peak_normal_force = row->v[6];
    e->event.controller = row->controller;
    e->event.sensed_radius = row->sensed_radius;
    if (H5Tenum_nameof(kind_type, &kind, e->kind_name, sizeof e->kind_name) < 0)
        snprintf(e->kind_name, sizeof e->kind_name, "unknown");
}

/* Every row of /events into *out (*n); 0 on failure. */
static int read_events(hid_t file, td_result_event **out, size_t *n)
{
    hid_t d = H5Dopen2(file, td_out_name(TD_OUT_EVENTS), H5P_DEFAULT), ftype, space, mtype = -1, kind_type = -1;
    hssize_t count;
    event_row *rows = NULL;
    size_t i;
    int ok = 0;
    if (d < 0)
        return 0;
    ftype = H5Dget_type(d);
    space = H5Dget_space(d);
    count = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
    if (ftype >= 0 && count >= 0 && H5Tget_class(ftype) == H5T_COMPOUND)
        mtype = event_memory_type(ftype, &kind_type);
    if (mtype >= 0 && (rows = calloc((size_t)count + 1, sizeof *rows)) != NULL &&
        (*out = calloc((size_t)count + 1, sizeof **out)) != NULL) {
        for (i = 0; i < (size_t)count; i++)
            rows[i].controller = -1; /* what a file without the field means (records.h) */
        ok = count == 0 || H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0;
    }
    for (i = 0; ok && i < (size_t)count; i++)
        take_event(&rows[i], kind_type, &(*out)[i]);
    *n = ok ? (size_t)count : 0;
    free(rows);
    if (mtype >= 0)
        H5Tclose(mtype);
    if (kind_type >= 0)
        H5Tclose(kind_type);
    if (ftype >= 0)
        H5Tclose(ftype);
    if (space >= 0)
        H5Sclose(space);
    H5Dclose(d);
    return ok;
}

td_status td_result_events(const td_result *r, td_result_event **events, size_t *n, td_error *err)
{
    int ok = 0, present = 0;
    if (!events || !n)
        return td_error_set(err, TD_ERR_INVALID, "td_result_events: NULL output");
    *events = NULL;
    *n = 0;
    if (!r)
        return td_error_set(err, TD_ERR_INVALID, "td_result_events: NULL result");
    H5E_BEGIN_TRY
    {
        present = link_exists(r->file, td_out_name(TD_OUT_EVENTS));
        ok = present && read_events(r->file, events, n);
    }
    H5E_END_TRY;
    if (!present)
        return TD_OK; /* a file without events: none */
    if (!ok) {
        free(*events);
        *events = NULL;
        return td_error_set(err, TD_ERR_INVALID, "%s: unreadable /%s table", r->path, td_out_name(TD_OUT_EVENTS));
    }
    return TD_OK;
}
