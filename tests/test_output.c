/*
 * td_writer: synthetic samples and events written to HDF5 and CSV are read back independently
 * (HDF5 C API, a CSV parser with strtod) and compared bit for bit; the completeness protocol
 * (PATH.XXXXXX.partial, flag last, rename) is checked for complete, incomplete and failed files,
 * and with the file size limit (RLIMIT_FSIZE) standing in for a full disk.
 */
#include "td_test.h"

#include "io/writer_internal.h"
#include "touchdown/case.h"
#include "touchdown/modal.h"
#include "touchdown/modal_output.h"
#include "touchdown/output.h"
#include "touchdown/result.h"
#include "touchdown/version.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define NODES 3
#define RETS 2
#define AMBS 2
#define ROWS 2500  /* more than two HDF5 chunks of 1024 rows, the last one partial */
#define EVENTS 300 /* more than one HDF5 event chunk of 256 */

static const int node_list[NODES] = {2, 7, 11};

/* ---- synthetic data ---------------------------------------------------------------------- */

/* Any finite double, by bit pattern (subnormals, -0 and huge values included), with a few
 * special values mixed in. */
static double any_double(uint64_t *s)
{
    static const double specials[] = {
        0.0, -0.0, 0.1, 1.0 / 3.0, DBL_MAX, -DBL_MAX, DBL_MIN, 4.9406564584124654e-324, 1e-10, 2.0000000001};
    for (;;) {
        uint64_t bits = td_test_splitmix(s);
        double d;
        if ((bits & 0xff) < 10)
            return specials[bits & 0xff];
        memcpy(&d, &bits, sizeof d);
        if (isfinite(d))
            return d;
    }
}

typedef struct sample_set {
    double t[ROWS];
    double xy[ROWS][2 * NODES];
    td_retainer_state ret[ROWS][RETS];
    double amb[ROWS][2 * AMBS];
    td_event ev[EVENTS];
} sample_set;

static sample_set *make_samples(void)
{
    sample_set *d = calloc(1, sizeof *d);
    uint64_t seed = 12345;
    int r, i;
    assert_non_null(d);
    for (r = 0; r < ROWS; r++) {
        d->t[r] = r < 10 ? (double)r / 10000.0 : any_double(&seed);
        for (i = 0; i < 2 * NODES; i++)
            d->xy[r][i] = any_double(&seed);
        for (i = 0; i < RETS; i++) {
            td_retainer_state *s = &d->ret[r][i];
            s->x = any_double(&seed);
            s->y = any_double(&seed);
            s->radius = any_double(&seed);
            s->radial_velocity = any_double(&seed);
            s->whirl_angle = any_double(&seed);
            s->normal_force = any_double(&seed);
            s->friction_force = any_double(&seed);
            s->sliding_velocity = any_double(&seed);
            s->in_contact = (int)(td_test_splitmix(&seed) & 1);
        }
        for (i = 0; i < 2 * AMBS; i++)
            d->amb[r][i] = any_double(&seed);
    }
    for (i = 0; i < EVENTS; i++) {
        td_event *e = &d->ev[i];
        e->kind = (td_event_kind)(i % 6);
        e->time = any_double(&seed);
        e->retainer = e->kind == TD_EVENT_SCHEDULE ? -1 : i % RETS;
        e->change = e->kind == TD_EVENT_SCHEDULE ? i : -1;
        e->radial_velocity_before = any_double(&seed);
        e->radial_velocity_after = any_double(&seed);
        e->tangential_velocity_before = any_double(&seed);
        e->tangential_velocity_after = any_double(&seed);
        e->impulse = any_double(&seed);
        e->normal_force = any_double(&seed);
        e->peak_normal_force = any_double(&seed);
    }
    return d;
}

static const char case_text[] = "# a case\nspeed = 90.0;\nname = \"A \\\"quoted\\\" = name\";\n";

static td_output_layout full_layout(void)
{
    td_output_layout l = {0};
    l.node_count = NODES;
    l.nodes = node_list;
    l.retainer_count = RETS;
    l.amb_count = AMBS;
    l.compression = 0;
    return l;
}

static td_sim_stats some_stats(void)
{
    td_sim_stats s;
    memset(&s, 0, sizeof s);
    s.steps = 123456789L;
    s.residual_evals = 234567890L;
    s.jacobian_evals = 3456L;
    s.linear_setups = 4567L;
    s.nonlinear_iters = 5678L;
    s.error_test_fails = 67L;
    s.nonlinear_fails = 7L;
    s.restarts = 89L;
    s.events = 90L;
    s.contact_onsets = 12L;
    s.releases = 11L;
    s.worst_drift = 1.2345678901234567e-13;
    s.peak_normal_force = 1834.5678901234567;
    s.time_in_contact = 0.12345678901234567;
    s.first_contact_time = 0.10000000012345678;
    s.wall_time = 3.1415926535897931;
    return s;
}

/* Writes the whole sample set (events after samples 5*i), attributes, and closes; HDF5 datasets
 * deflated at `level`. */
static void write_all_level(td_writer_kind kind, const char *path, const sample_set *d, int complete, int level)
{
    td_output_layout l = full_layout();
    td_writer *w = NULL;
    td_error err;
    td_sim_stats stats = some_stats();
    const double clearance[2] = {0.75e-3, 0.7500000000000001e-3};
    const long ret_nodes[2] = {2, 10};
    int r, e = 0;
    struct stat sb;
    l.compression = level;
    assert_int_equal(td_writer_open(kind, path, &l, &w, &err), TD_OK);
    for (r = 0; r < ROWS; r++) {
        assert_int_equal(td_writer_sample(w, d->t[r], 0.0, d->xy[r], d->ret[r], d->amb[r], &err), TD_OK);
        if (e < EVENTS && r == 5 * e + 3)
            assert_int_equal(td_writer_event(w, &d->ev[e++], td_writer_sample_count(w) - 1, &err), TD_OK);
        /* While writing, nothing is at the final path. */
        if (r == ROWS / 2)
            assert_int_not_equal(stat(path, &sb), 0);
    }
    assert_int_equal(td_writer_sample_count(w), ROWS);
    assert_int_equal(td_writer_event_count(w), EVENTS);
    /* an event must point at a written row (or -1) */
    assert_int_equal(td_writer_event(w, &d->ev[0], ROWS, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_event(w, &d->ev[0], -2, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_event_count(w), EVENTS);
    assert_int_equal(td_writer_set_string(w, "case_text", case_text, &err), TD_OK);
    assert_int_equal(td_writer_set_string(w, "note", "first", &err), TD_OK);
    assert_int_equal(td_writer_set_string(w, "note", "replaced value", &err), TD_OK);
    assert_int_equal(td_writer_set_double(w, "speed", 90.000000000000014, &err), TD_OK);
    assert_int_equal(td_writer_set_long(w, "summary_contacts", -42L, &err), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, "retainer_clearance", clearance, 2, &err), TD_OK);
    assert_int_equal(td_writer_set_longs(w, "retainer_nodes", ret_nodes, 2, &err), TD_OK);
    assert_int_equal(td_writer_set_stats(w, &stats, &err), TD_OK);
    assert_int_equal(td_writer_close(&w, complete, complete ? NULL : "solver failed at t = 0.5 s\nsecond line", &err),
                     TD_OK);
    assert_null(w);
}

static void write_all(td_writer_kind kind, const char *path, const sample_set *d, int complete)
{
    write_all_level(kind, path, d, complete, 0);
}

static void tmp_name(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/output_%ld_%s", TD_BINARY_DIR, (long)getpid(), name);
}

/* Temporary files of the output `path`: entries named BASENAME.*.partial in its directory. */
static int partials_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    char dir[1024];
    size_t blen = strlen(base);
    struct dirent *e;
    DIR *d;
    int count = 0;
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    d = opendir(dir);
    if (!d)
        return 0;
    while ((e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name);
        if (n >= blen + 8 && strncmp(e->d_name, base, blen) == 0 && e->d_name[blen] == '.' &&
            strcmp(e->d_name + n - 8, ".partial") == 0)
            count++;
    }
    closedir(d);
    return count;
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

static int bits_equal(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

#define assert_bits(actual, expected)                                                                                  \
    do {                                                                                                               \
        double a_ = (actual), e_ = (expected);                                                                         \
        if (!bits_equal(a_, e_)) {                                                                                     \
            print_error("%s = %.17g, expected %.17g (bitwise)\n", #actual, a_, e_);                                    \
            fail();                                                                                                    \
        }                                                                                                              \
    } while (0)

/* ---- HDF5 reading helpers ---------------------------------------------------------------- */

/* A text attribute: variable-length UTF-8 (what h5py reads as str), returned as a malloc'd copy. */
static char *h5_attr_string(hid_t obj, const char *name)
{
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t;
    char *v = NULL, *s;
    assert_true(a >= 0);
    t = H5Aget_type(a);
    assert_int_equal(H5Tget_class(t), H5T_STRING);
    assert_true(H5Tis_variable_str(t) > 0);
    assert_int_equal(H5Tget_cset(t), H5T_CSET_UTF8);
    assert_true(H5Aread(a, t, &v) >= 0);
    assert_non_null(v);
    s = strdup(v);
    assert_non_null(s);
    H5free_memory(v);
    H5Tclose(t);
    H5Aclose(a);
    return s;
}

static int h5_attr_count(hid_t obj, const char *name)
{
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT), sp;
    int n;
    assert_true(a >= 0);
    sp = H5Aget_space(a);
    n = (int)H5Sget_simple_extent_npoints(sp);
    H5Sclose(sp);
    H5Aclose(a);
    return n;
}

static void h5_attr_read(hid_t obj, const char *name, hid_t mem_type, void *out)
{
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    assert_true(a >= 0);
    assert_true(H5Aread(a, mem_type, out) >= 0);
    H5Aclose(a);
}

static double h5_attr_double(hid_t obj, const char *name)
{
    double v;
    assert_int_equal(h5_attr_count(obj, name), 1);
    h5_attr_read(obj, name, H5T_NATIVE_DOUBLE, &v);
    return v;
}

static long long h5_attr_ll(hid_t obj, const char *name)
{
    long long v;
    assert_int_equal(h5_attr_count(obj, name), 1);
    h5_attr_read(obj, name, H5T_NATIVE_LLONG, &v);
    return v;
}

/* Read a whole dataset; checks its shape against dims (rank entries). */
static void *h5_read(hid_t file, const char *name, hid_t mem_type, size_t elem, int rank, const hsize_t *dims)
{
    hid_t d = H5Dopen2(file, name, H5P_DEFAULT), sp;
    hsize_t got[4];
    size_t total = 1;
    void *buf;
    int i;
    assert_true(d >= 0);
    sp = H5Dget_space(d);
    assert_int_equal(H5Sget_simple_extent_ndims(sp), rank);
    H5Sget_simple_extent_dims(sp, got, NULL);
    for (i = 0; i < rank; i++) {
        assert_int_equal(got[i], dims[i]);
        total *= (size_t)dims[i];
    }
    buf = malloc(total * elem + 1);
    assert_non_null(buf);
    assert_true(H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
    H5Sclose(sp);
    H5Dclose(d);
    return buf;
}

static void h5_check_units(hid_t file, const char *dataset, const char *units)
{
    hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    char *u;
    assert_true(d >= 0);
    u = h5_attr_string(d, "units");
    assert_string_equal(u, units);
    free(u);
    H5Dclose(d);
}

typedef struct ev_row {
    double time;
    int kind;
    int retainer;
    int change;
    long long sample;
    double vr_b, vr_a, vt_b, vt_a, impulse, normal_force, peak_normal_force;
} ev_row;

static hid_t event_mem_type(void)
{
    hid_t kind = H5Tenum_create(H5T_NATIVE_INT), m = H5Tcreate(H5T_COMPOUND, sizeof(ev_row));
    int v;
    for (v = 0; v <= (int)TD_EVENT_ROLL_END; v++)
        H5Tenum_insert(kind, td_event_kind_name((td_event_kind)v), &v);
    H5Tinsert(m, "time", HOFFSET(ev_row, time), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "kind", HOFFSET(ev_row, kind), kind);
    H5Tinsert(m, "retainer", HOFFSET(ev_row, retainer), H5T_NATIVE_INT);
    H5Tinsert(m, "change", HOFFSET(ev_row, change), H5T_NATIVE_INT);
    H5Tinsert(m, "sample", HOFFSET(ev_row, sample), H5T_NATIVE_LLONG);
    H5Tinsert(m, "radial_velocity_before", HOFFSET(ev_row, vr_b), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "radial_velocity_after", HOFFSET(ev_row, vr_a), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "tangential_velocity_before", HOFFSET(ev_row, vt_b), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "tangential_velocity_after", HOFFSET(ev_row, vt_a), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "impulse", HOFFSET(ev_row, impulse), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "normal_force", HOFFSET(ev_row, normal_force), H5T_NATIVE_DOUBLE);
    H5Tinsert(m, "peak_normal_force", HOFFSET(ev_row, peak_normal_force), H5T_NATIVE_DOUBLE);
    H5Tclose(kind);
    return m;
}

/* ---- HDF5 -------------------------------------------------------------------------------- */

static void test_hdf5_round_trip(void **state)
{
    sample_set *d = make_samples();
    char path[512];
    hid_t f, g, mt;
    hsize_t dims[3];
    double *t, *xy, *amb;
    int8_t *contact;
    int *nodes, r, i, e;
    ev_row *ev;
    char *s;
    double clearance[2];
    long long ret_nodes[2];
    td_sim_stats stats = some_stats();
    static const char *fields[] = {"x",
                                   "y",
                                   "radial_position",
                                   "radial_velocity",
                                   "whirl_angle",
                                   "normal_force",
                                   "friction_force",
                                   "sliding_velocity"};
    (void)state;
    tmp_name(path, sizeof path, "rt.h5");
    write_all(TD_WRITER_HDF5, path, d, 1);
    assert_int_equal(partials_of(path), 0);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);

    dims[0] = ROWS;
    t = h5_read(f, "/time", H5T_NATIVE_DOUBLE, sizeof(double), 1, dims);
    for (r = 0; r < ROWS; r++)
        assert_bits(t[r], d->t[r]);
    dims[1] = NODES;
    dims[2] = 2;
    xy = h5_read(f, "/nodes/displacement", H5T_NATIVE_DOUBLE, sizeof(double), 3, dims);
    for (r = 0; r < ROWS; r++)
        for (i = 0; i < 2 * NODES; i++)
            assert_bits(xy[r * 2 * NODES + i], d->xy[r][i]);
    dims[1] = AMBS;
    amb = h5_read(f, "/ambs/force", H5T_NATIVE_DOUBLE, sizeof(double), 3, dims);
    for (r = 0; r < ROWS; r++)
        for (i = 0; i < 2 * AMBS; i++)
            assert_bits(amb[r * 2 * AMBS + i], d->amb[r][i]);
    dims[1] = RETS;
    for (e = 0; e < 8; e++) {
        char name[64];
        double *v;
        snprintf(name, sizeof name, "/retainers/%s", fields[e]);
        v = h5_read(f, name, H5T_NATIVE_DOUBLE, sizeof(double), 2, dims);
        for (r = 0; r < ROWS; r++)
            for (i = 0; i < RETS; i++) {
                const td_retainer_state *st = &d->ret[r][i];
                const double want[8] = {st->x,
                                        st->y,
                                        st->radius,
                                        st->radial_velocity,
                                        st->whirl_angle,
                                        st->normal_force,
                                        st->friction_force,
                                        st->sliding_velocity};
                assert_bits(v[r * RETS + i], want[e]);
            }
        free(v);
    }
    contact = h5_read(f, "/retainers/contact_state", H5T_NATIVE_INT8, 1, 2, dims);
    for (r = 0; r < ROWS; r++)
        for (i = 0; i < RETS; i++)
            assert_int_equal(contact[r * RETS + i], d->ret[r][i].in_contact);

    /* node numbers, units */
    g = H5Dopen2(f, "/nodes/displacement", H5P_DEFAULT);
    assert_int_equal(h5_attr_count(g, "nodes"), NODES);
    nodes = calloc(NODES, sizeof *nodes);
    h5_attr_read(g, "nodes", H5T_NATIVE_INT, nodes);
    for (i = 0; i < NODES; i++)
        assert_int_equal(nodes[i], node_list[i]);
    H5Dclose(g);
    h5_check_units(f, "/time", "s");
    h5_check_units(f, "/nodes/displacement", "m");
    h5_check_units(f, "/retainers/normal_force", "N");
    h5_check_units(f, "/retainers/radial_velocity", "m/s");
    h5_check_units(f, "/retainers/whirl_angle", "rad");
    h5_check_units(f, "/ambs/force", "N");

    /* events: the compound table, kind as an enum; sample = row written just before */
    mt = event_mem_type();
    dims[0] = EVENTS;
    ev = h5_read(f, "/events", mt, sizeof(ev_row), 1, dims);
    for (e = 0; e < EVENTS; e++) {
        assert_bits(ev[e].time, d->ev[e].time);
        assert_int_equal(ev[e].kind, (int)d->ev[e].kind);
        assert_int_equal(ev[e].retainer, d->ev[e].retainer);
        assert_int_equal(ev[e].change, d->ev[e].change);
        assert_int_equal(ev[e].sample, 5 * e + 3);
        assert_bits(ev[e].vr_b, d->ev[e].radial_velocity_before);
        assert_bits(ev[e].vr_a, d->ev[e].radial_velocity_after);
        assert_bits(ev[e].vt_b, d->ev[e].tangential_velocity_before);
        assert_bits(ev[e].vt_a, d->ev[e].tangential_velocity_after);
        assert_bits(ev[e].impulse, d->ev[e].impulse);
        assert_bits(ev[e].normal_force, d->ev[e].normal_force);
        assert_bits(ev[e].peak_normal_force, d->ev[e].peak_normal_force);
    }
    H5Tclose(mt);
    g = H5Dopen2(f, "/events", H5P_DEFAULT);
    s = h5_attr_string(g, "kind_names");
    assert_non_null(strstr(s, "0=contact_onset"));
    assert_non_null(strstr(s, "5=penalty_exit"));
    free(s);
    H5Dclose(g);

    /* root attributes */
    s = h5_attr_string(f, "case_text");
    assert_string_equal(s, case_text);
    free(s);
    s = h5_attr_string(f, "note");
    assert_string_equal(s, "replaced value");
    free(s);
    s = h5_attr_string(f, "library_version");
    assert_string_equal(s, td_version());
    free(s);
    assert_bits(h5_attr_double(f, "speed"), 90.000000000000014);
    assert_int_equal(h5_attr_ll(f, "summary_contacts"), -42);
    assert_int_equal(h5_attr_count(f, "retainer_clearance"), 2);
    h5_attr_read(f, "retainer_clearance", H5T_NATIVE_DOUBLE, clearance);
    assert_bits(clearance[0], 0.75e-3);
    assert_bits(clearance[1], 0.7500000000000001e-3);
    h5_attr_read(f, "retainer_nodes", H5T_NATIVE_LLONG, ret_nodes);
    assert_int_equal(ret_nodes[0], 2);
    assert_int_equal(ret_nodes[1], 10);
    assert_int_equal(h5_attr_ll(f, "steps"), stats.steps);
    assert_int_equal(h5_attr_ll(f, "residual_evals"), stats.residual_evals);
    assert_int_equal(h5_attr_ll(f, "jacobian_evals"), stats.jacobian_evals);
    assert_int_equal(h5_attr_ll(f, "events"), stats.events);
    assert_int_equal(h5_attr_ll(f, "restarts"), stats.restarts);
    assert_bits(h5_attr_double(f, "worst_drift"), stats.worst_drift);
    assert_bits(h5_attr_double(f, "wall_time"), stats.wall_time);
    assert_bits(h5_attr_double(f, "first_contact_time"), stats.first_contact_time);
    assert_int_equal(h5_attr_ll(f, "complete"), 1);
    assert_int_equal(H5Aexists(f, "incomplete_reason"), 0);
    assert_int_equal(H5Fclose(f), 0);

    free(t);
    free(xy);
    free(amb);
    free(contact);
    free(nodes);
    free(ev);
    free(d);
    remove(path);
}

static void test_hdf5_incomplete(void **state)
{
    sample_set *d = make_samples();
    char path[512];
    hid_t f;
    hsize_t dims[1] = {ROWS};
    double *t;
    char *s;
    (void)state;
    tmp_name(path, sizeof path, "inc.h5");
    write_all(TD_WRITER_HDF5, path, d, 0);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_int_equal(h5_attr_ll(f, "complete"), 0);
    s = h5_attr_string(f, "incomplete_reason");
    assert_string_equal(s, "solver failed at t = 0.5 s\nsecond line");
    free(s);
    /* everything written so far is kept */
    t = h5_read(f, "/time", H5T_NATIVE_DOUBLE, sizeof(double), 1, dims);
    assert_bits(t[ROWS - 1], d->t[ROWS - 1]);
    free(t);
    H5Fclose(f);
    free(d);
    remove(path);
}

/* No nodes, retainers or AMBs: just the time, the groups exist with count 0. */
static void test_hdf5_empty_layout(void **state)
{
    char path[512];
    td_output_layout l = {0};
    td_writer *w = NULL;
    hid_t f, g, mt;
    hsize_t dims[1] = {3};
    double *t;
    int i;
    (void)state;
    tmp_name(path, sizeof path, "empty.h5");
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, NULL), TD_OK);
    for (i = 0; i < 3; i++)
        assert_int_equal(td_writer_sample(w, 0.5 * i, 0.0, NULL, NULL, NULL, NULL), TD_OK);
    assert_int_equal(td_writer_close(&w, 1, NULL, NULL), TD_OK);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    t = h5_read(f, "/time", H5T_NATIVE_DOUBLE, sizeof(double), 1, dims);
    assert_bits(t[2], 1.0);
    free(t);
    g = H5Gopen2(f, "/retainers", H5P_DEFAULT);
    assert_true(g >= 0);
    assert_int_equal(h5_attr_ll(g, "count"), 0);
    H5Gclose(g);
    dims[0] = 0;
    mt = event_mem_type();
    t = h5_read(f, "/events", mt, sizeof(ev_row), 1, dims);
    free(t);
    H5Tclose(mt);
    assert_int_equal(h5_attr_ll(f, "complete"), 1);
    H5Fclose(f);
    remove(path);
}

/* ---- CSV --------------------------------------------------------------------------------- */

/* Next line of *p (without the newline, written into place); NULL at the end. */
static char *next_line(char **p)
{
    char *line = *p, *nl;
    if (!*line)
        return NULL;
    nl = strchr(line, '\n');
    if (nl) {
        *nl = '\0';
        *p = nl + 1;
    } else {
        *p = line + strlen(line);
    }
    return line;
}

/* Split a CSV data line into doubles; returns the count. */
static int parse_row(char *line, double *out, int max)
{
    int n = 0;
    char *p = line, *end;
    while (n < max) {
        errno = 0;
        out[n++] = strtod(p, &end);
        assert_true(end != p);
        assert_int_equal(errno == ERANGE && fabs(out[n - 1]) > 1.0, 0);
        if (*end != ',')
            break;
        p = end + 1;
    }
    assert_int_equal(*end, '\0');
    return n;
}

static void expected_header(char *buf, size_t n)
{
    static const char *cols[] = {"x", "y", "r", "vr", "theta", "N", "Ff", "vs", "contact"};
    static const char *units[] = {"m", "m", "m", "m/s", "rad", "N", "N", "m/s", "-"};
    size_t len = 0;
    int i, k;
    len += (size_t)snprintf(buf + len, n - len, "t [s]");
    for (i = 0; i < NODES; i++)
        len += (size_t)snprintf(buf + len, n - len, ",x_n%d [m],y_n%d [m]", node_list[i], node_list[i]);
    for (i = 0; i < RETS; i++)
        for (k = 0; k < 9; k++)
            len += (size_t)snprintf(buf + len, n - len, ",%s_ret%d [%s]", cols[k], i, units[k]);
    for (i = 0; i < AMBS; i++)
        len += (size_t)snprintf(buf + len, n - len, ",Fx_amb%d [N],Fy_amb%d [N]", i, i);
}

/* Value `index` of the numeric attribute line "# NAME = v0 v1 ..." in a CSV text. */
static double csv_attr_value(const char *text, const char *name, int index)
{
    char key[128];
    const char *p;
    char *end;
    double v = 0.0;
    int i;
    snprintf(key, sizeof key, "\n# %s =", name);
    p = strstr(text, key);
    assert_non_null(p);
    p += strlen(key);
    for (i = 0; i <= index; i++) {
        v = strtod(p, &end);
        assert_true(end != p);
        p = end;
    }
    return v;
}

#define CSV_COLS (1 + 2 * NODES + 9 * RETS + 2 * AMBS)

static void check_csv_samples(const char *path, const sample_set *d, int complete)
{
    char *text = td_test_read_file(path), *p = text, *line, header[2048];
    double v[CSV_COLS + 1];
    int r = 0, i, flag_seen = 0, case_lines = 0;
    expected_header(header, sizeof header);
    line = next_line(&p);
    assert_string_equal(line, header);
    while ((line = next_line(&p)) != NULL && line[0] != '#') {
        assert_true(r < ROWS);
        assert_int_equal(parse_row(line, v, CSV_COLS + 1), CSV_COLS);
        assert_bits(v[0], d->t[r]);
        for (i = 0; i < 2 * NODES; i++)
            assert_bits(v[1 + i], d->xy[r][i]);
        for (i = 0; i < RETS; i++) {
            const td_retainer_state *s = &d->ret[r][i];
            const double *c = v + 1 + 2 * NODES + 9 * i;
            assert_bits(c[0], s->x);
            assert_bits(c[1], s->y);
            assert_bits(c[2], s->radius);
            assert_bits(c[3], s->radial_velocity);
            assert_bits(c[4], s->whirl_angle);
            assert_bits(c[5], s->normal_force);
            assert_bits(c[6], s->friction_force);
            assert_bits(c[7], s->sliding_velocity);
            assert_bits(c[8], (double)s->in_contact);
        }
        for (i = 0; i < 2 * AMBS; i++)
            assert_bits(v[1 + 2 * NODES + 9 * RETS + i], d->amb[r][i]);
        r++;
    }
    assert_int_equal(r, ROWS);
    /* trailer: only comments, the flag on the very last line */
    for (; line; line = next_line(&p)) {
        assert_int_equal(line[0], '#');
        assert_false(flag_seen);
        if (strncmp(line, "#| ", 3) == 0)
            case_lines++;
        if (strcmp(line, "# complete") == 0 || strncmp(line, "# incomplete: ", 14) == 0) {
            flag_seen = 1;
            if (complete)
                assert_string_equal(line, "# complete");
            else
                assert_string_equal(line, "# incomplete: solver failed at t = 0.5 s second line");
        }
    }
    assert_true(flag_seen);
    assert_int_equal(case_lines, complete ? 3 : 5); /* case text, and the two-line reason */
    free(text); /* next_line cut it into lines: read it again for whole-text searches */
    text = td_test_read_file(path);
    assert_non_null(strstr(text, "\n# case_text:\n#| # a case\n#| speed = 90.0;\n"));
    assert_non_null(strstr(text, "\n# note = replaced value\n"));
    assert_bits(csv_attr_value(text, "speed", 0), 90.000000000000014);
    assert_non_null(strstr(text, "\n# summary_contacts = -42\n"));
    assert_bits(csv_attr_value(text, "retainer_clearance", 0), 0.75e-3);
    assert_bits(csv_attr_value(text, "retainer_clearance", 1), 0.7500000000000001e-3);
    assert_non_null(strstr(text, "\n# steps = 123456789\n"));
    assert_non_null(strstr(text, "\n# library_version = " TD_VERSION "\n"));
    free(text);
}

static void check_csv_events(const char *path, const sample_set *d, int complete)
{
    char *text = td_test_read_file(path), *p = text, *line;
    int e = 0;
    line = next_line(&p);
    assert_string_equal(line, "t [s],kind [-],kind_name,retainer [-],change [-],sample [-],vr_before [m/s],"
                              "vr_after [m/s],vt_before [m/s],vt_after [m/s],impulse [N s],N [N],peak_N [N]");
    while ((line = next_line(&p)) != NULL && line[0] != '#') {
        const td_event *ev = &d->ev[e];
        char *f[13], *q = line;
        int k;
        for (k = 0; k < 13; k++) {
            f[k] = q;
            q = strchr(q, ',');
            if (k < 12) {
                assert_non_null(q);
                *q++ = '\0';
            }
        }
        assert_null(q);
        assert_bits(strtod(f[0], NULL), ev->time);
        assert_int_equal(atoi(f[1]), (int)ev->kind);
        assert_string_equal(f[2], td_event_kind_name(ev->kind));
        assert_int_equal(atoi(f[3]), ev->retainer);
        assert_int_equal(atoi(f[4]), ev->change);
        assert_int_equal(atol(f[5]), 5 * e + 3);
        assert_bits(strtod(f[6], NULL), ev->radial_velocity_before);
        assert_bits(strtod(f[7], NULL), ev->radial_velocity_after);
        assert_bits(strtod(f[8], NULL), ev->tangential_velocity_before);
        assert_bits(strtod(f[9], NULL), ev->tangential_velocity_after);
        assert_bits(strtod(f[10], NULL), ev->impulse);
        assert_bits(strtod(f[11], NULL), ev->normal_force);
        assert_bits(strtod(f[12], NULL), ev->peak_normal_force);
        e++;
    }
    assert_int_equal(e, EVENTS);
    assert_non_null(line);
    assert_string_equal(line, complete ? "# complete" : "# incomplete: solver failed at t = 0.5 s second line");
    assert_null(next_line(&p));
    free(text);
}

static void test_csv_round_trip(void **state)
{
    sample_set *d = make_samples();
    char path[512], events[1100];
    int complete;
    (void)state;
    for (complete = 1; complete >= 0; complete--) {
        tmp_name(path, sizeof path, complete ? "rt.csv" : "inc.csv");
        td_writer_events_path(path, events, sizeof events);
        write_all(TD_WRITER_CSV, path, d, complete);
        assert_int_equal(partials_of(path), 0);
        assert_int_equal(partials_of(events), 0);
        check_csv_samples(path, d, complete);
        check_csv_events(events, d, complete);
        remove(path);
        remove(events);
    }
    free(d);
}

/* gnuplot (the intended reader) sees every row and the right values, columns named by header. */
static void test_csv_gnuplot(void **state)
{
    char path[512], events[1100], cmd[4096], out[256];
    td_output_layout l = full_layout();
    td_writer *w = NULL;
    td_retainer_state ret[RETS];
    double xy[2 * NODES] = {0}, amb[2 * AMBS] = {0};
    FILE *p;
    long records = -1;
    double max_n = 0.0;
    int r;
    (void)state;
    if (system("gnuplot --version > /dev/null 2>&1") != 0)
        skip();
    tmp_name(path, sizeof path, "gp.csv");
    memset(ret, 0, sizeof ret);
    assert_int_equal(td_writer_open(TD_WRITER_CSV, path, &l, &w, NULL), TD_OK);
    for (r = 0; r < 1000; r++) {
        ret[0].normal_force = 1000.0 * sin(0.01 * r) * sin(0.01 * r) + 0.123456789012345;
        assert_int_equal(td_writer_sample(w, r * 1e-4, 0.0, xy, ret, amb, NULL), TD_OK);
    }
    assert_int_equal(td_writer_set_string(w, "case_text", case_text, NULL), TD_OK);
    assert_int_equal(td_writer_close(&w, 1, NULL, NULL), TD_OK);
    snprintf(cmd, sizeof cmd,
             "gnuplot -e 'set datafile separator \",\"; stats \"%s\" using 1:\"N_ret0 [N]\" nooutput; "
             "print sprintf(\"%%d %%.17g\", STATS_records, STATS_max_y)' 2>&1",
             path);
    p = popen(cmd, "r");
    assert_non_null(p);
    assert_non_null(fgets(out, sizeof out, p));
    pclose(p);
    assert_int_equal(sscanf(out, "%ld %lf", &records, &max_n), 2);
    assert_int_equal(records, 1000);
    {
        double want = 0.0;
        for (r = 0; r < 1000; r++) {
            double v = 1000.0 * sin(0.01 * r) * sin(0.01 * r) + 0.123456789012345;
            want = v > want ? v : want;
        }
        assert_bits(max_n, want);
    }
    td_writer_events_path(path, events, sizeof events);
    remove(path);
    remove(events);
}

/* ---- the completeness protocol ----------------------------------------------------------- */

static void test_open_failure_leaves_nothing(void **state)
{
    td_output_layout l = full_layout();
    td_writer *w = (td_writer *)&l; /* must be reset to NULL */
    td_error err;
    char path[512], dir[256];
    int kind;
    (void)state;
    for (kind = 0; kind < 2; kind++) {
        tmp_name(dir, sizeof dir, "no_such_dir");
        snprintf(path, sizeof path, "%s/out.%s", dir, kind ? "csv" : "h5");
        w = (td_writer *)&l;
        assert_int_equal(td_writer_open((td_writer_kind)kind, path, &l, &w, &err), TD_ERR_IO);
        assert_null(w);
        assert_non_null(strstr(err.message, "out."));
        assert_false(exists(path));
        assert_false(exists(dir));
    }
    /* invalid arguments */
    tmp_name(path, sizeof path, "bad.h5");
    l.node_count = -1;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, &err), TD_ERR_INVALID);
    l = full_layout();
    l.nodes = NULL;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, &err), TD_ERR_INVALID);
    l = full_layout();
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, "", &l, &w, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_open((td_writer_kind)7, path, &l, &w, &err), TD_ERR_INVALID);
    assert_false(exists(path));
}

/* A stale complete file at PATH disappears as soon as a new writer opens on PATH. */
static void test_stale_file_removed(void **state)
{
    td_output_layout l = full_layout();
    td_writer *w = NULL;
    char path[512];
    FILE *f;
    int kind;
    (void)state;
    for (kind = 0; kind < 2; kind++) {
        tmp_name(path, sizeof path, kind ? "stale.csv" : "stale.h5");
        f = fopen(path, "w");
        assert_non_null(f);
        fputs("old result\n# complete\n", f);
        fclose(f);
        assert_int_equal(td_writer_open((td_writer_kind)kind, path, &l, &w, NULL), TD_OK);
        assert_false(exists(path));
        assert_int_equal(partials_of(path), 1);
        td_writer_discard(&w);
        assert_null(w);
        assert_false(exists(path));
        assert_int_equal(partials_of(path), 0);
    }
}

static void put_file(const char *path, const char *text);

/* What a reader of a run file learns of its events through the public API: 1 if the file has its
 * event table, 0 if the run omitted it; in both cases td_result_events must give 0 rows here (no
 * event was written). */
static int events_recorded(const char *path)
{
    td_result *r = NULL;
    td_result_event *rows = NULL;
    size_t n = 1;
    int has;
    assert_int_equal(td_result_open(path, &r, NULL), TD_OK);
    has = td_result_has(r, TD_OUT_EVENTS, NULL);
    assert_int_equal(td_result_events(r, &rows, &n, NULL), TD_OK);
    assert_int_equal(n, 0);
    if (!has)
        assert_null(rows); /* as documented: no table, no rows */
    free(rows);
    td_result_free(&r);
    return has;
}

/* output.events = false: no event table at all (an empty one would say "no events, complete" of a run
 * that had them): no CSV events file (a stale one removed, no temporary one left), no /events or
 * /event in HDF5, events refused; a run that fails still marks its samples file incomplete. */
static void test_omitted_events(void **state)
{
    td_output_layout l = full_layout();
    td_retainer_state ret[RETS];
    td_event ev;
    td_writer *w = NULL;
    double xy[2 * NODES] = {0.0}, amb[2 * AMBS] = {0.0};
    char path[512], events[600], last[256] = "", line[256];
    FILE *f;
    hid_t h;
    int kind;
    (void)state;
    memset(ret, 0, sizeof ret);
    memset(&ev, 0, sizeof ev);
    l.omit_events = 1;
    for (kind = 0; kind < 2; kind++) {
        tmp_name(path, sizeof path, kind ? "noev.csv" : "noev.h5");
        td_writer_events_path(path, events, sizeof events);
        if (kind)
            put_file(events, "old events\n# complete\n");
        assert_int_equal(td_writer_open((td_writer_kind)kind, path, &l, &w, NULL), TD_OK);
        assert_false(exists(events));
        assert_int_equal(partials_of(events), 0);
        assert_int_equal(td_writer_sample(w, 0.0, 0.0, xy, ret, amb, NULL), TD_OK);
        assert_int_equal(td_writer_event(w, &ev, 0, NULL), TD_ERR_INVALID);
        assert_int_equal(td_writer_close(&w, 0, "solver failed", NULL), TD_OK);
        assert_false(exists(events));
        assert_int_equal(partials_of(path) + partials_of(events), 0);
        if (kind) {
            f = fopen(path, "r");
            assert_non_null(f);
            while (fgets(line, sizeof line, f))
                snprintf(last, sizeof last, "%s", line);
            fclose(f);
            assert_string_equal(last, "# incomplete: solver failed\n");
        } else {
            h = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
            assert_true(h >= 0);
            assert_int_equal(H5Lexists(h, "events", H5P_DEFAULT), 0);
            assert_int_equal(H5Lexists(h, "event", H5P_DEFAULT), 0);
            assert_int_equal(h5_attr_ll(h, "complete"), 0);
            H5Fclose(h);
            assert_int_equal(events_recorded(path), 0);
        }
        remove(path);
        remove(events);
    }
    /* the same file with its events kept and none happening has an event table, empty */
    l.omit_events = 0;
    tmp_name(path, sizeof path, "noev-kept.h5");
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, NULL), TD_OK);
    assert_int_equal(td_writer_sample(w, 0.0, 0.0, xy, ret, amb, NULL), TD_OK);
    assert_int_equal(td_writer_close(&w, 1, NULL, NULL), TD_OK);
    assert_int_equal(events_recorded(path), 1);
    remove(path);
}

/* The CSV file's companions (the events file, the window file) follow one rule: a stale one from an
 * earlier run is removed when a writer opens on PATH, whether or not this run writes it. Here
 * neither is written (output.events = false, no window summaries), so neither may be left. */
static void test_stale_companions_removed(void **state)
{
    td_output_layout l = full_layout();
    td_retainer_state ret[RETS];
    td_writer *w = NULL;
    double xy[2 * NODES] = {0.0}, amb[2 * AMBS] = {0.0};
    char path[512], events[600], windows[600];
    (void)state;
    memset(ret, 0, sizeof ret);
    l.omit_events = 1;
    l.window_fields = 0;
    tmp_name(path, sizeof path, "companions.csv");
    td_writer_events_path(path, events, sizeof events);
    td_writer_windows_path(path, windows, sizeof windows);
    put_file(events, "old events\n# complete\n");
    put_file(windows, "old windows\n# complete\n");
    assert_int_equal(td_writer_open(TD_WRITER_CSV, path, &l, &w, NULL), TD_OK);
    assert_false(exists(events));
    assert_false(exists(windows));
    assert_int_equal(td_writer_sample(w, 0.0, 0.0, xy, ret, amb, NULL), TD_OK);
    assert_int_equal(td_writer_close(&w, 1, NULL, NULL), TD_OK);
    assert_true(exists(path));
    assert_false(exists(events));
    assert_false(exists(windows));
    assert_int_equal(partials_of(path) + partials_of(events) + partials_of(windows), 0);
    remove(path);
}

/* One writer of `path` from start to end: its temporary file created (the leftover scan first),
 * written and renamed to `path` if `commit`, else removed; 0 on success, else 1 with the message
 * in *err. */
static int whole_write(const char *path, int commit, td_error *err)
{
    char *tmp = NULL;
    int fd = -1, lock = -1, bad;
    if (td_io_create_temp(path, &tmp, &fd, &lock, err) != TD_OK)
        return 1;
    bad = write(fd, "x\n", 2) != 2;
    close(fd);
    if (commit)
        bad = bad || td_io_commit_temp(tmp, path, err) != TD_OK;
    else
        bad = bad || remove(tmp) != 0;
    free(tmp);
    close(lock);
    return bad;
}

/* Writes of one path by each of two processes at once (the race they once lost took a few
 * thousand to show). */
#define CONCURRENT_WRITES 20000

/* Two writers of one path at once both succeed: a child writes the path in a tight loop (each of
 * its writes scans for leftovers and locks the unlocked temporary files it finds) while this
 * process does the same. A file created and not yet locked is one such; its writer used to fail
 * ("cannot lock its temporary file") when the scan held it for that moment, or lose it to the scan
 * (then fail at the rename). */
static void test_concurrent_writers(void **state)
{
    char path[512], msg[TD_ERROR_MESSAGE_SIZE] = "";
    td_error err;
    int i, status = -1, failed = 0;
    pid_t pid;
    (void)state;
    tmp_name(path, sizeof path, "both.txt");
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        for (i = 0; i < CONCURRENT_WRITES; i++)
            failed += whole_write(path, i == 0, &err);
        _exit(failed ? 1 : 0);
    }
    for (i = 0; i < CONCURRENT_WRITES; i++)
        if (whole_write(path, i == 0, &err) != 0 && failed++ == 0)
            snprintf(msg, sizeof msg, "%s", err.message);
    waitpid(pid, &status, 0);
    if (failed)
        fail_msg("%d of %d writes failed, the first: %s", failed, CONCURRENT_WRITES, msg);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    assert_true(exists(path));
    assert_int_equal(partials_of(path), 0);
    remove(path);
}

/* The leftover scan removes a temporary file nobody holds the lock of (empty and new: a writer
 * that created it and had not locked it yet creates another, test_concurrent_writers) and keeps
 * a locked one. */
static void test_leftovers(void **state)
{
    char path[512], orphan[600], live[600];
    td_error err;
    int fd;
    (void)state;
    tmp_name(path, sizeof path, "left.txt");
    snprintf(orphan, sizeof orphan, "%s.aaaaaa.partial", path);
    snprintf(live, sizeof live, "%s.bbbbbb.partial", path);
    assert_true((fd = open(orphan, O_WRONLY | O_CREAT | O_EXCL, 0666)) >= 0);
    close(fd);
    assert_true((fd = open(live, O_WRONLY | O_CREAT | O_EXCL, 0666)) >= 0);
    assert_int_equal(flock(fd, LOCK_EX), 0);
    assert_int_equal(whole_write(path, 1, &err), 0);
    assert_false(exists(orphan));
    assert_true(exists(live));
    close(fd); /* its writer is gone now */
    assert_int_equal(whole_write(path, 1, &err), 0);
    assert_false(exists(live));
    assert_int_equal(partials_of(path), 0);
    remove(path);
}

/* Run job(arg) in a child process with a file size limit of `limit` bytes (SIGXFSZ ignored:
 * writes fail with EFBIG, as on a full disk); the child exits through exit() with job's return
 * value, so the HDF5 library's exit handler runs too. Returns the child's wait status. */
static int run_limited(int (*job)(const void *), const void *arg, long limit)
{
    pid_t pid = fork();
    int status = -1;
    if (pid == 0) {
        struct rlimit rl;
        rl.rlim_cur = rl.rlim_max = (rlim_t)limit;
        signal(SIGXFSZ, SIG_IGN);
        signal(SIGSEGV, SIG_DFL); /* not cmocka's handler: the parent must see a crash */
        signal(SIGABRT, SIG_DFL);
        signal(SIGBUS, SIG_DFL);
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0)
            exit(10);
        exit(job(arg));
    }
    if (pid > 0)
        waitpid(pid, &status, 0);
    return status;
}

/* Fails the test unless the child exited normally with code 0. */
static void assert_child_ok(int status, int which)
{
    if (!WIFEXITED(status))
        fail_msg("case %d: the child died with signal %d", which, WIFSIGNALED(status) ? WTERMSIG(status) : -1);
    assert_int_equal(WEXITSTATUS(status), 0);
}

typedef struct limited_write {
    td_writer_kind kind;
    const char *path;
    int rows, events;
} limited_write;

/* Write the samples and events, close as complete; 0 only if every failure was TD_ERR_IO. */
static int write_job(const void *arg)
{
    const limited_write *job = arg;
    td_output_layout l = full_layout();
    td_writer *w = NULL;
    td_retainer_state ret[RETS];
    double xy[2 * NODES] = {0}, amb[2 * AMBS] = {0};
    td_event ev;
    td_status st;
    int r, failed = 0;
    memset(ret, 0, sizeof ret);
    memset(&ev, 0, sizeof ev);
    if (td_writer_open(job->kind, job->path, &l, &w, NULL) != TD_OK)
        return 11;
    for (r = 0; r < job->rows; r++)
        if ((st = td_writer_sample(w, r * 1e-4, 0.0, xy, ret, amb, NULL)) != TD_OK)
            failed |= st != TD_ERR_IO && st != TD_ERR_STATE;
    for (r = 0; r < job->events; r++)
        if ((st = td_writer_event(w, &ev, -1, NULL)) != TD_OK)
            failed |= st != TD_ERR_IO && st != TD_ERR_STATE;
    if (td_writer_close(&w, 1, NULL, NULL) != TD_ERR_IO || w != NULL)
        return 12;
    return failed ? 13 : 0;
}

/* A full disk (the file size limit) while writing: TD_ERR_IO, no crash (also not in HDF5's exit
 * handler after a failed close), nothing at PATH and no temporary file left. */
static void test_failed_writes_leave_nothing(void **state)
{
    limited_write cases[] = {{TD_WRITER_CSV, NULL, 20000, 0},     /* the samples file fills up */
                             {TD_WRITER_CSV, NULL, 10, 20000},    /* the events file fills up */
                             {TD_WRITER_HDF5, NULL, 200000, 0},   /* the samples datasets fill up */
                             {TD_WRITER_HDF5, NULL, 10, 100000}}; /* the events dataset fills up */
    char path[512], events[1100];
    size_t i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        tmp_name(path, sizeof path, cases[i].kind == TD_WRITER_CSV ? "full.csv" : "full.h5");
        td_writer_events_path(path, events, sizeof events);
        cases[i].path = path;
        assert_child_ok(run_limited(write_job, &cases[i], 64 * 1024), (int)i);
        assert_false(exists(path));
        assert_false(exists(events));
        assert_int_equal(partials_of(path), 0);
        assert_int_equal(partials_of(events), 0);
    }
}

/* Write `text` to `path`; fails the test on error. */
static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* Modal results big enough to pass a 16 KiB limit in CSV (rows) and HDF5 (case text). */
typedef struct modal_job {
    const char *path;
    int hdf5;
} modal_job;

/* 0 when the write fails with TD_ERR_IO and a message naming the path and the cause (the file
 * size limit: EFBIG), 20 + status otherwise (20: it succeeded), 30 for a vaguer message. */
static int modal_job_run(const void *arg)
{
    const modal_job *job = arg;
    enum { N = 2000 };
    static td_critical_speed cs[N];
    static char text[32 * 1024]; /* under the 64 KiB attribute limit of the default HDF5 format */
    td_modal_results r;
    td_error err;
    td_status st;
    int i;
    for (i = 0; i < N; i++) {
        cs[i].speed = 100.0 + i;
        cs[i].freq_hz = cs[i].speed / (2.0 * TD_PI);
        cs[i].zeta = 0.01;
    }
    memset(text, 'x', sizeof text - 1);
    memset(&r, 0, sizeof r);
    r.critical = cs;
    r.n_critical = N;
    r.case_text = text;
    td_error_clear(&err);
    st = job->hdf5 ? td_modal_write_hdf5(job->path, &r, &err) : td_modal_write_csv(job->path, &r, &err);
    if (st != TD_ERR_IO)
        return 20 + (int)st;
    return strstr(err.message, job->path) && strstr(err.message, strerror(EFBIG)) ? 0 : 30;
}

/* The modal writers write a temporary file and rename it: a write that fails on a full disk
 * (the file size limit) reports the path and the cause, leaves no temporary file, and leaves
 * at PATH what was there before: nothing, or the earlier file untouched. Without the limit the
 * new file replaces the old one. */
static void test_modal_writers_rename(void **state)
{
    modal_job job;
    char path[512];
    char *text;
    int old;
    (void)state;
    for (job.hdf5 = 0; job.hdf5 < 2; job.hdf5++)
        for (old = 0; old < 2; old++) {
            tmp_name(path, sizeof path, job.hdf5 ? "modal.h5" : "modal.csv");
            job.path = path;
            if (old)
                put_file(path, "old\n");
            assert_child_ok(run_limited(modal_job_run, &job, 16 * 1024), 2 * job.hdf5 + old);
            if (old) {
                text = td_test_read_file(path);
                assert_string_equal(text, "old\n");
                free(text);
            } else {
                assert_false(exists(path));
            }
            assert_int_equal(partials_of(path), 0);
            assert_int_equal(modal_job_run(&job), 20 + TD_OK); /* no limit in this process */
            assert_true(exists(path));
            assert_int_equal(partials_of(path), 0);
            remove(path);
        }
}

/* td_output_files: the HDF5 file, the CSV file and its two companions, named as the writer names
 * them (td_writer_events_path, td_writer_windows_path), whole even for the longest CSV path. */
static void test_output_files(void **state)
{
    td_output_file f[TD_OUTPUT_FILES];
    td_output_options o;
    size_t len;
    (void)state;
    td_output_options_default(&o);
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "d/r.h5");
    snprintf(o.csv_path, sizeof o.csv_path, "d/r.csv");
    assert_int_equal(td_output_files(&o, f), 4);
    assert_string_equal(f[0].path, "d/r.h5");
    assert_string_equal(f[1].path, "d/r.csv");
    assert_string_equal(f[2].path, "d/r.events.csv");
    assert_string_equal(f[3].path, "d/r.windows.csv");
    assert_string_equal(f[3].what, "CSV window output");
    o.hdf5_path[0] = '\0';
    memset(o.csv_path, 'a', sizeof o.csv_path - 1); /* the longest path, without ".csv" */
    o.csv_path[sizeof o.csv_path - 1] = '\0';
    assert_int_equal(td_output_files(&o, f), 3);
    len = strlen(o.csv_path);
    assert_true(strlen(f[0].path) == len && !strncmp(f[1].path, o.csv_path, len) &&
                !strncmp(f[2].path, o.csv_path, len));
    assert_string_equal(f[1].path + len, ".events.csv");
    assert_string_equal(f[2].path + len, ".windows.csv");
    o.csv_path[0] = '\0';
    assert_int_equal(td_output_files(&o, f), 0);
    assert_int_equal(td_output_files(NULL, f), -1);
    memset(o.hdf5_path, 'a', sizeof o.hdf5_path); /* not NUL-terminated */
    assert_int_equal(td_output_files(&o, f), -1);
}

/* td_output_check_paths against independently built collisions: the same file by name, by hard
 * link, through the events file; an input recorded by td_case_load (td_case_files: the case
 * and its @include file); reserved names; non-regular outputs; missing directories. */
static void test_output_path_checks(void **state)
{
    char dir[512], main_cfg[600], part[600], link_path[600], csv[600];
    const char *inputs[2];
    const char *const *files;
    td_output_options o;
    td_case *c = NULL;
    td_error err;
    char *jeffcott;
    int n = 0;
    (void)state;
    tmp_name(dir, sizeof dir, "paths");
    assert_int_equal(mkdir(dir, 0755), 0);
    snprintf(main_cfg, sizeof main_cfg, "%s/main.cfg", dir);
    snprintf(part, sizeof part, "%s/part.cfg", dir);
    jeffcott = td_test_read_file(td_source_path("cases/jeffcott.cfg"));
    put_file(part, jeffcott);
    free(jeffcott);
    put_file(main_cfg, "@include \"part.cfg\"\n");
    assert_int_equal(td_case_load(main_cfg, NULL, 0, &c, &err), TD_OK);
    files = td_case_files(c, &n);
    assert_int_equal(n, 2);
    assert_string_equal(files[0], main_cfg);
    assert_non_null(strstr(files[1], "part.cfg"));

    td_output_options_default(&o);
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "%s/r.h5", dir);
    snprintf(o.csv_path, sizeof o.csv_path, "%s/r.csv", dir);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_OK);
    /* the same name, the events file, a reserved name */
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "%s/./r.csv", dir);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "%s/r.events.csv", dir);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "%s/r.csv.ab12CD.partial", dir);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    /* the @include file, also through a hard link; the case file through "dir/../dir" */
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "%s", part);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "@include"));
    snprintf(link_path, sizeof link_path, "%s/link.h5", dir);
    assert_int_equal(link(part, link_path), 0);
    snprintf(o.hdf5_path, sizeof o.hdf5_path, "%s", link_path);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    snprintf(csv, sizeof csv, "%s/../%s/main.cfg", dir, strrchr(dir, '/') + 1);
    o.hdf5_path[0] = '\0';
    snprintf(o.csv_path, sizeof o.csv_path, "%s", csv);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    inputs[0] = main_cfg;
    assert_int_equal(td_output_check_paths(&o, inputs, 0, &err), TD_OK); /* no inputs given */
    /* not a regular file, no such directory */
    snprintf(o.csv_path, sizeof o.csv_path, "/dev/null");
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    snprintf(o.csv_path, sizeof o.csv_path, "%s", dir);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    snprintf(o.csv_path, sizeof o.csv_path, "%s/missing/r.csv", dir);
    assert_int_equal(td_output_check_paths(&o, files, n, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "does not exist"));
    td_case_free(&c);
    remove(link_path);
    remove(part);
    remove(main_cfg);
    assert_int_equal(rmdir(dir), 0);
}

/* td_modal_check_paths: the rules of td_output_check_paths for the two modal outputs, which
 * have no events file (r.events.csv is a free name next to r.csv). */
static void test_modal_path_checks(void **state)
{
    char dir[512], cfg[600], csv[600], h5[600], other[600];
    const char *inputs[1];
    td_error err;
    (void)state;
    tmp_name(dir, sizeof dir, "modal_paths");
    assert_int_equal(mkdir(dir, 0755), 0);
    snprintf(cfg, sizeof cfg, "%s/case.cfg", dir);
    snprintf(csv, sizeof csv, "%s/r.csv", dir);
    snprintf(h5, sizeof h5, "%s/r.h5", dir);
    put_file(cfg, "speed = 1.0;\n");
    inputs[0] = cfg;
    assert_int_equal(td_modal_check_paths(csv, h5, inputs, 1, &err), TD_OK);
    assert_int_equal(td_modal_check_paths("", NULL, inputs, 1, &err), TD_OK); /* no outputs */
    snprintf(other, sizeof other, "%s/r.events.csv", dir);
    assert_int_equal(td_modal_check_paths(csv, other, inputs, 1, &err), TD_OK);
    /* the same file twice, the case file, a reserved name */
    snprintf(other, sizeof other, "%s/./r.csv", dir);
    assert_int_equal(td_modal_check_paths(csv, other, inputs, 1, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "same file"));
    assert_int_equal(td_modal_check_paths(cfg, h5, inputs, 1, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "case file"));
    assert_int_equal(td_modal_check_paths(csv, "r.h5.ab12CD.partial", inputs, 1, &err), TD_ERR_INVALID);
    /* not a regular file, no such directory */
    assert_int_equal(td_modal_check_paths("/dev/null", h5, inputs, 1, &err), TD_ERR_INVALID);
    assert_int_equal(td_modal_check_paths(csv, dir, inputs, 1, &err), TD_ERR_INVALID);
    snprintf(other, sizeof other, "%s/missing/r.h5", dir);
    assert_int_equal(td_modal_check_paths(csv, other, inputs, 1, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "does not exist"));
    assert_int_equal(td_modal_check_paths(csv, h5, NULL, 1, &err), TD_ERR_INVALID);
    remove(cfg);
    assert_int_equal(rmdir(dir), 0);
}

static void test_attribute_names(void **state)
{
    td_output_layout l = {0};
    td_writer *w = NULL;
    td_error err;
    char path[512], events[1100], long_name[100];
    (void)state;
    tmp_name(path, sizeof path, "names.csv");
    assert_int_equal(td_writer_open(TD_WRITER_CSV, path, &l, &w, NULL), TD_OK);
    assert_int_equal(td_writer_set_double(w, "complete", 1.0, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_set_string(w, "incomplete_reason", "x", &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_set_double(w, "a b", 1.0, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_set_double(w, "a=b", 1.0, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_set_double(w, "", 1.0, &err), TD_ERR_INVALID);
    memset(long_name, 'a', 64);
    long_name[64] = '\0';
    assert_int_equal(td_writer_set_double(w, long_name, 1.0, &err), TD_ERR_INVALID);
    long_name[63] = '\0';
    assert_int_equal(td_writer_set_double(w, long_name, 1.0, &err), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, "x", NULL, 1, &err), TD_ERR_INVALID);
    assert_int_equal(td_writer_set_string(w, "ok.name-1", NULL, &err), TD_OK); /* NULL: "" */
    assert_int_equal(td_writer_close(&w, 1, NULL, &err), TD_OK);
    assert_int_equal(td_writer_close(&w, 1, NULL, &err), TD_OK); /* NULL handle: no-op */
    td_writer_discard(&w);
    td_writer_events_path(path, events, sizeof events);
    remove(path);
    remove(events);
}

static void test_events_path(void **state)
{
    char buf[64];
    (void)state;
    assert_int_equal(td_writer_events_path("dir/out.csv", buf, sizeof buf), 18);
    assert_string_equal(buf, "dir/out.events.csv");
    td_writer_events_path("out.dat", buf, sizeof buf);
    assert_string_equal(buf, "out.dat.events.csv");
    td_writer_events_path(".csv", buf, sizeof buf);
    assert_string_equal(buf, ".events.csv");
    assert_int_equal(td_writer_events_path("abc.csv", buf, 5), 14);
    assert_string_equal(buf, "abc.");
    assert_string_equal(td_event_kind_name(TD_EVENT_FRICTION_REVERSAL), "friction_reversal");
    assert_string_equal(td_event_kind_name((td_event_kind)99), "unknown");
}

/* ---- dimension scales, compression --------------------------------------------------------- */

/* The sample datasets, in the order of the writer. */
static const char *const sample_sets[] = {"/time",
                                          "/nodes/displacement",
                                          "/retainers/x",
                                          "/retainers/y",
                                          "/retainers/radial_position",
                                          "/retainers/radial_velocity",
                                          "/retainers/whirl_angle",
                                          "/retainers/normal_force",
                                          "/retainers/friction_force",
                                          "/retainers/sliding_velocity",
                                          "/retainers/contact_state",
                                          "/ambs/force"};
#define SAMPLE_SETS ((int)(sizeof sample_sets / sizeof sample_sets[0]))

/* Is `scale_path` attached to axis `axis` of `dset_path`, and is it a scale named after itself? */
static int scale_attached(hid_t f, const char *dset_path, const char *scale_path, unsigned axis)
{
    hid_t d = H5Dopen2(f, dset_path, H5P_DEFAULT), sc = H5Dopen2(f, scale_path, H5P_DEFAULT);
    char name[64] = "";
    const char *base = strrchr(scale_path, '/') + 1;
    int ok;
    assert_true(d >= 0 && sc >= 0);
    ok = H5DSis_scale(sc) > 0 && H5DSget_scale_name(sc, name, sizeof name) > 0 && strcmp(name, base) == 0 &&
         H5DSis_attached(d, sc, axis) > 0;
    H5Dclose(sc);
    H5Dclose(d);
    return ok;
}

static void test_hdf5_dimension_scales(void **state)
{
    sample_set *d = make_samples();
    char path[512];
    hsize_t dims[1];
    int *nodes, *rets, i;
    long long *rows;
    hid_t f;
    (void)state;
    tmp_name(path, sizeof path, "scales.h5");
    write_all(TD_WRITER_HDF5, path, d, 1);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    /* one time axis on every sample dataset */
    for (i = 1; i < SAMPLE_SETS; i++)
        if (!scale_attached(f, sample_sets[i], "/time", 0))
            fail_msg("%s: /time is not the scale of its first axis", sample_sets[i]);
    assert_true(scale_attached(f, "/nodes/displacement", "/nodes/node", 1));
    assert_true(scale_attached(f, "/nodes/displacement", "/component", 2));
    assert_true(scale_attached(f, "/ambs/force", "/ambs/amb", 1));
    assert_true(scale_attached(f, "/ambs/force", "/component", 2));
    for (i = 2; i + 1 < SAMPLE_SETS; i++)
        assert_true(scale_attached(f, sample_sets[i], "/retainers/retainer", 1));
    assert_true(scale_attached(f, "/events", "/event", 0));
    /* the scales hold the coordinates: node numbers, retainer and event indices */
    dims[0] = NODES;
    nodes = h5_read(f, "/nodes/node", H5T_NATIVE_INT, sizeof(int), 1, dims);
    assert_memory_equal(nodes, node_list, sizeof node_list);
    dims[0] = RETS;
    rets = h5_read(f, "/retainers/retainer", H5T_NATIVE_INT, sizeof(int), 1, dims);
    for (i = 0; i < RETS; i++)
        assert_int_equal(rets[i], i);
    dims[0] = EVENTS;
    rows = h5_read(f, "/event", H5T_NATIVE_LLONG, sizeof(long long), 1, dims);
    for (i = 0; i < EVENTS; i++)
        assert_int_equal(rows[i], i);
    h5_check_units(f, "/component", "1");
    H5Fclose(f);
    free(nodes);
    free(rets);
    free(rows);
    free(d);
    remove(path);
}

/* The raw bytes of a whole dataset in its file type (compound, int8 or double alike). */
static unsigned char *h5_raw(hid_t f, const char *name, size_t *size)
{
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT), t, sp;
    unsigned char *buf;
    assert_true(d >= 0);
    t = H5Dget_type(d);
    sp = H5Dget_space(d);
    *size = H5Tget_size(t) * (size_t)H5Sget_simple_extent_npoints(sp);
    buf = malloc(*size + 1);
    assert_non_null(buf);
    assert_true(*size == 0 || H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
    return buf;
}

/* Shuffle then deflate at `level` on dataset `name`. */
static void check_filters(hid_t f, const char *name, int level)
{
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT), dcpl = H5Dget_create_plist(d);
    unsigned flags, cd[4];
    size_t ncd = 4;
    assert_int_equal(H5Pget_nfilters(dcpl), 2);
    assert_int_equal(H5Pget_filter2(dcpl, 0, &flags, &ncd, cd, 0, NULL, NULL), H5Z_FILTER_SHUFFLE);
    ncd = 4;
    assert_int_equal(H5Pget_filter2(dcpl, 1, &flags, &ncd, cd, 0, NULL, NULL), H5Z_FILTER_DEFLATE);
    assert_true(ncd >= 1);
    assert_int_equal(cd[0], level);
    H5Pclose(dcpl);
    H5Dclose(d);
}

static void test_hdf5_compression_lossless(void **state)
{
    static const char *const others[] = {"/events", "/event", "/nodes/node", "/retainers/retainer"};
    sample_set *d = make_samples();
    char plain[512], packed[512];
    hid_t a, b;
    int i;
    (void)state;
    tmp_name(plain, sizeof plain, "plain.h5");
    tmp_name(packed, sizeof packed, "packed.h5");
    write_all_level(TD_WRITER_HDF5, plain, d, 1, 0);
    write_all_level(TD_WRITER_HDF5, packed, d, 1, 9);
    a = H5Fopen(plain, H5F_ACC_RDONLY, H5P_DEFAULT);
    b = H5Fopen(packed, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(a >= 0 && b >= 0);
    for (i = 0; i < SAMPLE_SETS + 4; i++) {
        const char *name = i < SAMPLE_SETS ? sample_sets[i] : others[i - SAMPLE_SETS];
        size_t na, nb;
        unsigned char *ra = h5_raw(a, name, &na), *rb = h5_raw(b, name, &nb);
        assert_true(na > 0);
        assert_int_equal(na, nb);
        if (memcmp(ra, rb, na) != 0)
            fail_msg("%s differs between deflate 0 and 9", name);
        if (i < SAMPLE_SETS || i == SAMPLE_SETS)
            check_filters(b, name, 9);
        free(ra);
        free(rb);
    }
    H5Fclose(a);
    H5Fclose(b);
    free(d);
    remove(plain);
    remove(packed);
}

static void test_bad_compression_rejected(void **state)
{
    td_output_layout l = full_layout();
    td_writer *w = NULL;
    td_error err;
    char path[512], partial[600];
    (void)state;
    tmp_name(path, sizeof path, "badlevel.h5");
    snprintf(partial, sizeof partial, "%s.partial", path);
    l.compression = 10;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "compression 10"));
    assert_null(w);
    assert_false(exists(path) || exists(partial));
    l.compression = -1;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, &err), TD_ERR_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hdf5_round_trip),
        cmocka_unit_test(test_hdf5_incomplete),
        cmocka_unit_test(test_hdf5_empty_layout),
        cmocka_unit_test(test_csv_round_trip),
        cmocka_unit_test(test_csv_gnuplot),
        cmocka_unit_test(test_open_failure_leaves_nothing),
        cmocka_unit_test(test_stale_file_removed),
        cmocka_unit_test(test_stale_companions_removed),
        cmocka_unit_test(test_omitted_events),
        cmocka_unit_test(test_concurrent_writers),
        cmocka_unit_test(test_leftovers),
        cmocka_unit_test(test_failed_writes_leave_nothing),
        cmocka_unit_test(test_modal_writers_rename),
        cmocka_unit_test(test_modal_path_checks),
        cmocka_unit_test(test_output_path_checks),
        cmocka_unit_test(test_output_files),
        cmocka_unit_test(test_attribute_names),
        cmocka_unit_test(test_events_path),
        cmocka_unit_test(test_hdf5_dimension_scales),
        cmocka_unit_test(test_hdf5_compression_lossless),
        cmocka_unit_test(test_bad_compression_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
