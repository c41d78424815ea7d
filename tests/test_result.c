/*
 * touchdown/result.h: files written by the library's own writers (td_writer, the modal and sweep
 * writers) read back through the read API. The values must be the bits the writer was given, the
 * units and shapes those of the schema and of docs/output-format.md (a few paths are spelled out
 * here, as the document does, so that a renamed dataset fails), the completeness flag must follow
 * the writer's close (complete, incomplete) and a temporary or cut file never reads as complete.
 * A missing file, a file that is not HDF5 and an HDF5 file of another program are refused with a
 * message naming the file.
 */
#include "td_test.h"

#include "touchdown/modal_output.h"
#include "touchdown/output.h"
#include "touchdown/result.h"
#include "touchdown/sweep.h"
#include "touchdown/version.h"

#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define NODES 2
#define RETS 2
#define AMBS 1
#define ROWS 1500  /* more than one HDF5 chunk of samples */
#define EVENTS 300 /* more than one HDF5 chunk of events */

static const int node_list[NODES] = {3, 8};

/* A double of any size and sign: 53 random bits scaled over +-1e+-9. */
static double any_double(uint64_t *s)
{
    double u = (double)(td_test_splitmix(s) >> 11) / 9007199254740992.0;
    return (u - 0.5) * pow(10.0, (double)(td_test_splitmix(s) % 19) - 9.0);
}

typedef struct run_data {
    double t[ROWS], speed[ROWS];
    double xy[ROWS][2 * NODES];
    td_retainer_state ret[ROWS][RETS];
    double amb[ROWS][2 * AMBS];
    td_event ev[EVENTS];
    long ev_sample[EVENTS];
} run_data;

static void fill_retainer(td_retainer_state *s, uint64_t *seed)
{
    s->x = any_double(seed);
    s->y = any_double(seed);
    s->radius = any_double(seed);
    s->radial_velocity = any_double(seed);
    s->whirl_angle = any_double(seed);
    s->normal_force = any_double(seed);
    s->friction_force = any_double(seed);
    s->sliding_velocity = any_double(seed);
    s->in_contact = (int)(td_test_splitmix(seed) & 1);
    s->race_x = any_double(seed);
    s->race_y = any_double(seed);
    s->race_speed = any_double(seed);
    s->rolling = (int)(td_test_splitmix(seed) & 1);
    s->whirl_rate = any_double(seed);
}

static run_data *make_data(void)
{
    run_data *d = calloc(1, sizeof *d);
    uint64_t seed = 2026;
    int r, i;
    assert_non_null(d);
    for (r = 0; r < ROWS; r++) {
        d->t[r] = r * 1e-4;
        d->speed[r] = any_double(&seed);
        for (i = 0; i < 2 * NODES; i++)
            d->xy[r][i] = any_double(&seed);
        for (i = 0; i < RETS; i++)
            fill_retainer(&d->ret[r][i], &seed);
        for (i = 0; i < 2 * AMBS; i++)
            d->amb[r][i] = any_double(&seed);
    }
    for (i = 0; i < EVENTS; i++) {
        td_event *e = &d->ev[i];
        e->kind = (td_event_kind)(i % 8);
        e->time = d->t[5 * i];
        e->retainer = e->kind == TD_EVENT_SCHEDULE ? -1 : i % RETS;
        e->change = e->kind == TD_EVENT_SCHEDULE ? i : -1;
        e->radial_velocity_before = any_double(&seed);
        e->radial_velocity_after = any_double(&seed);
        e->tangential_velocity_before = any_double(&seed);
        e->tangential_velocity_after = any_double(&seed);
        e->impulse = any_double(&seed);
        e->normal_force = any_double(&seed);
        e->peak_normal_force = any_double(&seed);
        d->ev_sample[i] = i % 7 == 6 ? -1 : 5 * i;
    }
    return d;
}

static void tmp_name(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/result_%ld_%s", TD_BINARY_DIR, (long)getpid(), name);
}

static const char case_text[] = "# a case\nspeed = 90.0;\ndescription = \"r\\u00e9sultat\";\n";
static const double clearance[RETS] = {0.75e-3, 0.7500000000000001e-3};

/* Every sample, event and a few attributes of `d` through td_writer; closed (in)complete. */
static void write_run(const char *path, const run_data *d, int complete)
{
    td_output_layout l;
    td_writer *w = NULL;
    td_error err;
    int r, e = 0;
    memset(&l, 0, sizeof l);
    l.node_count = NODES;
    l.nodes = node_list;
    l.retainer_count = RETS;
    l.amb_count = AMBS;
    l.race_fields = l.speed_field = l.whirl_field = 1;
    assert_int_equal(td_writer_open(TD_WRITER_HDF5, path, &l, &w, &err), TD_OK);
    for (r = 0; r < ROWS; r++) {
        assert_int_equal(td_writer_sample(w, d->t[r], d->speed[r], d->xy[r], d->ret[r], d->amb[r], &err), TD_OK);
        while (e < EVENTS && (d->ev_sample[e] == r || (d->ev_sample[e] < 0 && 5 * e == r)))
            assert_int_equal(td_writer_event(w, &d->ev[e], d->ev_sample[e], &err), TD_OK), e++;
    }
    assert_int_equal(e, EVENTS);
    assert_int_equal(td_writer_set_string(w, td_out_name(TD_OUT_CASE_TEXT), case_text, &err), TD_OK);
    assert_int_equal(td_writer_set_doubles(w, td_out_name(TD_OUT_RETAINER_CLEARANCE), clearance, RETS, &err), TD_OK);
    assert_int_equal(td_writer_set_long(w, td_out_name(TD_OUT_SUM_CONTACTS), 42L, &err), TD_OK);
    assert_int_equal(td_writer_close(&w, complete, complete ? NULL : "stopped at t = 0.1 s", &err), TD_OK);
}

static int bits_equal(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Dataset `id`: its shape (rank, d0, d1, d2) and units as the schema gives them; returned read. */
static td_result_array read_checked(const td_result *r, td_out_id id, int rank, size_t d0, size_t d1, size_t d2)
{
    td_result_array a;
    td_error err;
    assert_int_equal(td_result_read(r, id, NULL, &a, &err), TD_OK);
    assert_int_equal(a.rank, rank);
    assert_int_equal(a.dims[0], d0);
    assert_int_equal(a.dims[1], d1);
    assert_int_equal(a.dims[2], d2);
    assert_int_equal(a.n, d0 * d1 * d2);
    assert_string_equal(a.units, td_out_units(id));
    return a;
}

static void check_samples(const td_result *r, const run_data *d)
{
    td_result_array a;
    size_t k, i;
    a = read_checked(r, TD_OUT_TIME, 1, ROWS, 1, 1);
    for (k = 0; k < ROWS; k++)
        assert_true(bits_equal(a.v[k], d->t[k]));
    td_result_array_free(&a);
    a = read_checked(r, TD_OUT_SPEED, 1, ROWS, 1, 1);
    for (k = 0; k < ROWS; k++)
        assert_true(bits_equal(a.v[k], d->speed[k]));
    td_result_array_free(&a);
    a = read_checked(r, TD_OUT_NODE_DISPLACEMENT, 3, ROWS, NODES, 2);
    for (k = 0; k < ROWS; k++)
        for (i = 0; i < 2 * NODES; i++)
            assert_true(bits_equal(a.v[k * 2 * NODES + i], d->xy[k][i]));
    td_result_array_free(&a);
    a = read_checked(r, TD_OUT_AMB_FORCE, 3, ROWS, AMBS, 2);
    for (k = 0; k < ROWS; k++)
        for (i = 0; i < 2 * AMBS; i++)
            assert_true(bits_equal(a.v[k * 2 * AMBS + i], d->amb[k][i]));
    td_result_array_free(&a);
}

static void check_retainers(const td_result *r, const run_data *d)
{
    static const td_out_id ids[] = {TD_OUT_RET_X,          TD_OUT_RET_RADIAL_POSITION, TD_OUT_RET_NORMAL_FORCE,
                                    TD_OUT_RET_RACE_SPEED, TD_OUT_RET_WHIRL_RATE,      TD_OUT_RET_CONTACT_STATE,
                                    TD_OUT_RET_ROLLING};
    size_t f, k, i;
    for (f = 0; f < sizeof ids / sizeof ids[0]; f++) {
        td_result_array a = read_checked(r, ids[f], 2, ROWS, RETS, 1);
        for (k = 0; k < ROWS; k++)
            for (i = 0; i < RETS; i++) {
                const td_retainer_state *s = &d->ret[k][i];
                double want = f == 0   ? s->x
                              : f == 1 ? s->radius
                              : f == 2 ? s->normal_force
                              : f == 3 ? s->race_speed
                              : f == 4 ? s->whirl_rate
                              : f == 5 ? (double)s->in_contact
                                       : (double)s->rolling;
                assert_true(bits_equal(a.v[k * RETS + i], want));
            }
        td_result_array_free(&a);
    }
}

static void check_events(const td_result *r, const run_data *d)
{
    td_result_event *ev = NULL;
    td_error err;
    size_t n = 0, i;
    assert_int_equal(td_result_events(r, &ev, &n, &err), TD_OK);
    assert_int_equal(n, EVENTS);
    for (i = 0; i < n; i++) {
        const td_event *want = &d->ev[i], *got = &ev[i].event;
        assert_int_equal(got->kind, want->kind);
        assert_string_equal(ev[i].kind_name, td_event_kind_name(want->kind));
        assert_int_equal(got->retainer, want->retainer);
        assert_int_equal(got->change, want->change);
        assert_int_equal(ev[i].sample, d->ev_sample[i]);
        assert_true(bits_equal(got->time, want->time));
        assert_true(bits_equal(got->radial_velocity_before, want->radial_velocity_before));
        assert_true(bits_equal(got->radial_velocity_after, want->radial_velocity_after));
        assert_true(bits_equal(got->tangential_velocity_before, want->tangential_velocity_before));
        assert_true(bits_equal(got->tangential_velocity_after, want->tangential_velocity_after));
        assert_true(bits_equal(got->impulse, want->impulse));
        assert_true(bits_equal(got->normal_force, want->normal_force));
        assert_true(bits_equal(got->peak_normal_force, want->peak_normal_force));
    }
    free(ev);
}

static void check_attributes(const td_result *r)
{
    td_result_array a;
    td_error err;
    char *text = NULL;
    assert_int_equal(td_result_read(r, TD_OUT_RETAINER_CLEARANCE, NULL, &a, &err), TD_OK);
    assert_int_equal(a.rank, 1);
    assert_int_equal(a.n, RETS);
    assert_true(bits_equal(a.v[0], clearance[0]) && bits_equal(a.v[1], clearance[1]));
    assert_string_equal(a.units, "m");
    td_result_array_free(&a);
    assert_int_equal(td_result_read(r, TD_OUT_SUM_CONTACTS, NULL, &a, &err), TD_OK);
    assert_int_equal(a.rank, 0);
    assert_true(a.n == 1 && a.v[0] == 42.0);
    td_result_array_free(&a);
    assert_int_equal(td_result_read_text(r, TD_OUT_CASE_TEXT, NULL, &text, &err), TD_OK);
    assert_string_equal(text, case_text);
    free(text);
    assert_int_equal(td_result_read_text(r, TD_OUT_LIBRARY_VERSION, NULL, &text, &err), TD_OK);
    assert_string_equal(text, td_version());
    free(text);
    /* the units attribute of a dataset, read as an attribute of the object named by `sub` */
    assert_int_equal(td_result_read_text(r, TD_OUT_UNITS, "retainers/normal_force", &text, &err), TD_OK);
    assert_string_equal(text, "N");
    free(text);
    /* absent: a clear refusal naming the file and the attribute */
    assert_int_equal(td_result_read(r, TD_OUT_SUM_ENERGY_KINETIC, NULL, &a, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "summary_energy_kinetic"));
    assert_null(a.v);
}

/* Every dataset of the schema's run file that is in the file carries the schema's units. */
static void check_every_unit(const td_result *r)
{
    int id, seen = 0;
    for (id = 0; id < TD_OUT_ID_COUNT; id++) {
        char *text = NULL;
        char path[128];
        if (td_out_place_of((td_out_id)id) != TD_OUT_DATASET || !(td_out_files((td_out_id)id) & TD_OUT_IN_RUN) ||
            !td_result_has(r, (td_out_id)id, NULL))
            continue;
        assert_true(td_out_path((td_out_id)id, NULL, path, sizeof path) > 0);
        assert_int_equal(td_result_read_text(r, TD_OUT_UNITS, path, &text, NULL), TD_OK);
        assert_string_equal(text, td_out_units((td_out_id)id));
        free(text);
        seen++;
    }
    assert_int_equal(seen, 24); /* every run dataset: this layout has them all */
}

/* Each reading call's refusals on an open run file: the status, a message naming the file and
 * what was asked, and nothing left to free. */
static void check_read_failures(const td_result *r, const char *path)
{
    td_result_array a;
    td_error err;
    char *text = (char *)&text, **list = (char **)&list;
    size_t n = 99;
    memset(&a, 0xff, sizeof a);
    assert_int_equal(td_result_read(r, TD_OUT_ID_COUNT, NULL, &a, &err), TD_ERR_INVALID);
    assert_true(a.v == NULL && a.n == 0 && a.rank == 0 && a.units[0] == '\0');
    /* absent attribute, a dataset asked as text */
    assert_int_equal(td_result_read_text(r, TD_OUT_SUM_ENDING, NULL, &text, &err), TD_ERR_INVALID);
    assert_null(text);
    assert_non_null(strstr(err.message, path));
    assert_non_null(strstr(err.message, "summary_ending"));
    text = (char *)&text;
    assert_int_equal(td_result_read_text(r, TD_OUT_TIME, NULL, &text, &err), TD_ERR_INVALID);
    assert_null(text);
    /* numbers asked as strings, an attribute asked as a dataset */
    assert_int_equal(td_result_read_strings(r, TD_OUT_TIME, NULL, &list, &n, &err), TD_ERR_INVALID);
    assert_true(list == NULL && n == 0);
    assert_non_null(strstr(err.message, path));
    assert_non_null(strstr(err.message, "/time"));
    list = (char **)&list;
    n = 99;
    assert_int_equal(td_result_read_strings(r, TD_OUT_CASE_TEXT, NULL, &list, &n, &err), TD_ERR_INVALID);
    assert_true(list == NULL && n == 0);
    /* columns of a dataset, of a group the file lacks */
    list = (char **)&list;
    n = 99;
    assert_int_equal(td_result_columns(r, TD_OUT_TIME, NULL, 3, &list, &n, &err), TD_ERR_INVALID);
    assert_true(list == NULL && n == 0);
    assert_int_equal(td_result_columns(r, TD_OUT_CAMPBELL, NULL, 3, &list, &n, &err), TD_ERR_INVALID);
    assert_true(list == NULL && n == 0);
    assert_non_null(strstr(err.message, "/campbell"));
    td_result_array_free(&a); /* already empty: harmless */
}

/* A run file: kind, flag, samples, events and attributes as written. */
static void test_run_file(void **state)
{
    run_data *d = make_data();
    td_result *r = NULL;
    td_error err;
    char path[512];
    (void)state;
    tmp_name(path, sizeof path, "run.h5");
    write_run(path, d, 1);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    assert_int_equal(td_result_get_kind(r), TD_RESULT_RUN);
    assert_int_equal(td_result_get_flag(r), TD_RESULT_COMPLETE);
    assert_int_equal(td_result_complete(r), 1);
    check_samples(r, d);
    check_retainers(r, d);
    check_events(r, d);
    check_attributes(r);
    check_every_unit(r);
    check_read_failures(r, path);
    td_result_free(&r);
    assert_null(r);
    remove(path);
    free(d);
}

/* The paths of docs/output-format.md, spelled out: the schema names what the document says. */
static void test_schema_paths(void **state)
{
    static const struct {
        td_out_id id;
        const char *sub, *path, *name;
    } want[] = {{TD_OUT_RET_X, NULL, "retainers/x", "x"},
                {TD_OUT_NODE_DISPLACEMENT, NULL, "nodes/displacement", "displacement"},
                {TD_OUT_AMB_FORCE, NULL, "ambs/force", "force"},
                {TD_OUT_EVENTS, NULL, "events", "events"},
                {TD_OUT_EV_PEAK_NORMAL_FORCE, NULL, "events", "peak_normal_force"},
                {TD_OUT_COMPLETE, NULL, "", "complete"},
                {TD_OUT_CAMPBELL_FREQ_HZ, NULL, "campbell/freq_hz", "freq_hz"},
                {TD_OUT_HARMONIC_X_AMP, "2", "harmonic/2/x_amp", "x_amp"},
                {TD_OUT_HARMONIC_SPEED, "0", "harmonic/0", "speed"},
                {TD_OUT_SWEEP_KEY_AXIS, "speed", "vary/speed", "axis"},
                {TD_OUT_SWEEP_SECTION_RADIUS, NULL, "section_radius", "section_radius"}};
    /* what each is and its type, as docs/output-format.md's tables say */
    static const struct {
        td_out_id id;
        td_out_place place;
        td_out_type type;
    } kinds[] = {
        {TD_OUT_RETAINERS, TD_OUT_GROUP, TD_OUT_NO_TYPE},      {TD_OUT_RET_X, TD_OUT_DATASET, TD_OUT_F64},
        {TD_OUT_RET_CONTACT_STATE, TD_OUT_DATASET, TD_OUT_I8}, {TD_OUT_EVENTS, TD_OUT_DATASET, TD_OUT_COMPOUND},
        {TD_OUT_EV_KIND, TD_OUT_FIELD, TD_OUT_ENUM},           {TD_OUT_COMPLETE, TD_OUT_ATTRIBUTE, TD_OUT_I32},
        {TD_OUT_CASE_TEXT, TD_OUT_ATTRIBUTE, TD_OUT_TEXT},     {TD_OUT_SWEEP_POINTS, TD_OUT_CSV_ONLY, TD_OUT_TEXT}};
    char buf[64];
    size_t i;
    int id;
    (void)state;
    for (i = 0; i < sizeof want / sizeof want[0]; i++) {
        assert_int_equal(td_out_path(want[i].id, want[i].sub, buf, sizeof buf), (int)strlen(want[i].path));
        assert_string_equal(buf, want[i].path);
        assert_string_equal(td_out_name(want[i].id), want[i].name);
    }
    /* every id has a name, a shape and units; out of range is refused */
    for (id = 0; id < TD_OUT_ID_COUNT; id++)
        assert_true(td_out_name((td_out_id)id) && td_out_units((td_out_id)id) && td_out_shape((td_out_id)id));
    assert_null(td_out_name(TD_OUT_ID_COUNT));
    assert_int_equal(td_out_path(TD_OUT_ID_COUNT, NULL, buf, sizeof buf), -1);
    for (i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        assert_int_equal(td_out_place_of(kinds[i].id), kinds[i].place);
        assert_int_equal(td_out_type_of(kinds[i].id), kinds[i].type);
    }
    /* an id out of range is nothing: no place, type, file or parent of a real name */
    for (i = 0; i < 2; i++) {
        td_out_id bad = i ? (td_out_id)-1 : TD_OUT_ID_COUNT;
        assert_int_equal(td_out_place_of(bad), TD_OUT_NO_PLACE);
        assert_int_equal(td_out_type_of(bad), TD_OUT_NO_TYPE);
        assert_int_equal(td_out_files(bad), 0);
        assert_int_equal(td_out_parent(bad), TD_OUT_ID_COUNT);
        assert_null(td_out_units(bad));
        assert_string_equal(td_out_shape(bad), "");
    }
    /* cut short: the length it needs, the text cut and ended */
    assert_int_equal(td_out_path(TD_OUT_RET_RADIAL_VELOCITY, NULL, buf, 8), 25);
    assert_string_equal(buf, "retaine");
}

/* td_out_find: a stored name back to its id. The same name in two places (retainer_nodes: a run
 * file's attribute, a modal file's dataset) is told apart by place and file; every id is found from
 * its own name, place and files (or is one of the same name, place and files declared before it);
 * an unknown name, a NULL one, a wrong place or file is TD_OUT_ID_COUNT. */
static void test_schema_find(void **state)
{
    int id;
    (void)state;
    assert_int_equal(td_out_find("retainer_nodes", TD_OUT_ATTRIBUTE, TD_OUT_IN_RUN), TD_OUT_RETAINER_NODES);
    assert_int_equal(td_out_find("retainer_nodes", TD_OUT_DATASET, TD_OUT_IN_MODAL), TD_OUT_MODES_RETAINER_NODES);
    assert_int_equal(td_out_find("summary_peak_housing_force", TD_OUT_ATTRIBUTE, TD_OUT_IN_RUN),
                     TD_OUT_SUM_PEAK_HOUSING_FORCE);
    assert_int_equal(td_out_find("summary_peak_housing_force", TD_OUT_DATASET, TD_OUT_IN_RUN), TD_OUT_ID_COUNT);
    assert_int_equal(td_out_find("summary_peak_housing_force", TD_OUT_ATTRIBUTE, TD_OUT_IN_SWEEP), TD_OUT_ID_COUNT);
    assert_int_equal(td_out_find("no_such_name", TD_OUT_ATTRIBUTE, TD_OUT_IN_RUN), TD_OUT_ID_COUNT);
    assert_int_equal(td_out_find(NULL, TD_OUT_ATTRIBUTE, TD_OUT_IN_RUN), TD_OUT_ID_COUNT);
    for (id = 0; id < TD_OUT_ID_COUNT; id++) {
        td_out_id found =
            td_out_find(td_out_name((td_out_id)id), td_out_place_of((td_out_id)id), td_out_files((td_out_id)id));
        assert_true(found <= (td_out_id)id);
        assert_string_equal(td_out_name(found), td_out_name((td_out_id)id));
        assert_int_equal(td_out_place_of(found), td_out_place_of((td_out_id)id));
        assert_true(td_out_files(found) & td_out_files((td_out_id)id));
    }
}

/* Copy the first `bytes` of `from` (all when negative) to `to`. */
static void copy_file(const char *from, const char *to, long bytes)
{
    FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
    long k = 0;
    int c;
    assert_non_null(in);
    assert_non_null(out);
    while ((bytes < 0 || k < bytes) && (c = fgetc(in)) != EOF) {
        fputc(c, out);
        k++;
    }
    fclose(in);
    assert_int_equal(fclose(out), 0);
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fclose(f);
    return n;
}

/* Incomplete, temporary and cut files never read as complete. */
static void test_completeness(void **state)
{
    run_data *d = make_data();
    td_result *r = NULL;
    td_error err;
    char path[512], partial[600], cut[600], *reason = NULL;
    (void)state;
    tmp_name(path, sizeof path, "incomplete.h5");
    write_run(path, d, 0);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    assert_int_equal(td_result_get_flag(r), TD_RESULT_INCOMPLETE);
    assert_int_equal(td_result_complete(r), 0);
    assert_int_equal(td_result_read_text(r, TD_OUT_INCOMPLETE_REASON, NULL, &reason, &err), TD_OK);
    assert_string_equal(reason, "stopped at t = 0.1 s");
    free(reason);
    td_result_free(&r);
    /* a complete file under a writer's temporary name is not a result yet */
    write_run(path, d, 1);
    snprintf(partial, sizeof partial, "%s.aB3xY9.partial", path);
    copy_file(path, partial, -1);
    assert_int_equal(td_result_open(partial, &r, &err), TD_OK);
    assert_int_equal(td_result_get_flag(r), TD_RESULT_COMPLETE);
    assert_int_equal(td_result_complete(r), 0);
    td_result_free(&r);
    /* cut in half: refused, naming the file */
    snprintf(cut, sizeof cut, "%s-cut.h5", path);
    copy_file(path, cut, file_size(path) / 2);
    assert_int_equal(td_result_open(cut, &r, &err), TD_ERR_IO);
    assert_null(r);
    assert_non_null(strstr(err.message, cut));
    remove(path);
    remove(partial);
    remove(cut);
    free(d);
}

/* A missing file, a text file and another program's HDF5 file: refused with the file's name. */
/* The reading calls with a NULL handle or output: TD_ERR_INVALID, outputs empty. */
static void refusals_without_file(void)
{
    td_result_array a;
    td_result_event *ev = (td_result_event *)&ev;
    char *text = (char *)&text, **list = (char **)&list;
    size_t n = 99;
    memset(&a, 0xff, sizeof a);
    assert_int_equal(td_result_read(NULL, TD_OUT_TIME, NULL, &a, NULL), TD_ERR_INVALID);
    assert_true(a.v == NULL && a.n == 0);
    assert_int_equal(td_result_read(NULL, TD_OUT_TIME, NULL, NULL, NULL), TD_ERR_INVALID);
    assert_int_equal(td_result_read_text(NULL, TD_OUT_CASE_TEXT, NULL, &text, NULL), TD_ERR_INVALID);
    assert_null(text);
    assert_int_equal(td_result_read_text(NULL, TD_OUT_CASE_TEXT, NULL, NULL, NULL), TD_ERR_INVALID);
    assert_int_equal(td_result_read_strings(NULL, TD_OUT_SWEEP_STATUS, NULL, &list, &n, NULL), TD_ERR_INVALID);
    assert_true(list == NULL && n == 0);
    assert_int_equal(td_result_read_strings(NULL, TD_OUT_SWEEP_STATUS, NULL, &list, NULL, NULL), TD_ERR_INVALID);
    list = (char **)&list;
    n = 99;
    assert_int_equal(td_result_columns(NULL, TD_OUT_ROOT, NULL, 3, &list, &n, NULL), TD_ERR_INVALID);
    assert_true(list == NULL && n == 0);
    n = 99;
    assert_int_equal(td_result_events(NULL, &ev, &n, NULL), TD_ERR_INVALID);
    assert_true(ev == NULL && n == 0);
    td_result_array_free(NULL);
    td_result_strings_free(NULL, 3);
}

static void test_refusals(void **state)
{
    td_result *r = (td_result *)&r;
    td_error err;
    char path[512];
    hsize_t dims[1] = {3};
    double v[3] = {1, 2, 3};
    hid_t f, s, ds;
    FILE *t;
    (void)state;
    tmp_name(path, sizeof path, "missing.h5");
    assert_int_equal(td_result_open(path, &r, &err), TD_ERR_IO);
    assert_null(r);
    assert_non_null(strstr(err.message, path));
    assert_non_null(strstr(err.message, "No such file"));
    tmp_name(path, sizeof path, "text.h5");
    t = fopen(path, "w");
    assert_non_null(t);
    fputs("not hdf5\n", t);
    fclose(t);
    assert_int_equal(td_result_open(path, &r, &err), TD_ERR_IO);
    assert_non_null(strstr(err.message, "not an HDF5 file"));
    remove(path);
    tmp_name(path, sizeof path, "foreign.h5");
    f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    s = H5Screate_simple(1, dims, NULL);
    ds = H5Dcreate2(f, "temperature", H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(ds);
    H5Sclose(s);
    H5Fclose(f);
    assert_int_equal(td_result_open(path, &r, &err), TD_ERR_INVALID);
    assert_null(r);
    assert_non_null(strstr(err.message, "not a touchdown result file"));
    assert_non_null(strstr(err.message, path));
    remove(path);
    assert_int_equal(td_result_open(NULL, &r, &err), TD_ERR_INVALID);
    assert_int_equal(td_result_open(path, NULL, &err), TD_ERR_INVALID);
    td_result_free(NULL);
    /* no handle: no kind, flag or name, and every reading call refuses with nothing to free */
    assert_int_equal(td_result_get_kind(NULL), TD_RESULT_NO_KIND);
    assert_int_equal(td_result_get_flag(NULL), TD_RESULT_NO_FLAG);
    assert_int_equal(td_result_complete(NULL), 0);
    assert_int_equal(td_result_has(NULL, TD_OUT_TIME, NULL), 0);
    refusals_without_file();
}

/* A modal file (critical speeds only: found by its producer attribute) and its units. */
static void test_modal_file(void **state)
{
    td_critical_speed cs[3];
    td_modal_results mr;
    td_result *r = NULL;
    td_result_array a;
    td_error err;
    char path[512];
    int i;
    (void)state;
    memset(&mr, 0, sizeof mr);
    memset(cs, 0, sizeof cs);
    for (i = 0; i < 3; i++) {
        cs[i].speed = 100.0 * (i + 1) + 1.0 / 3.0;
        cs[i].freq_hz = cs[i].speed / (2.0 * TD_PI);
        cs[i].whirl = i == 1 ? TD_WHIRL_BACKWARD : TD_WHIRL_FORWARD;
    }
    mr.critical = cs;
    mr.n_critical = 3;
    mr.case_text = case_text;
    tmp_name(path, sizeof path, "modal.h5");
    assert_int_equal(td_modal_write_hdf5(path, &mr, &err), TD_OK);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    assert_int_equal(td_result_get_kind(r), TD_RESULT_MODAL);
    assert_int_equal(td_result_complete(r), 1);
    assert_false(td_result_has(r, TD_OUT_CAMPBELL, NULL));
    assert_int_equal(td_result_read(r, TD_OUT_CRITICAL_SPEED, NULL, &a, &err), TD_OK);
    assert_int_equal(a.n, 3);
    assert_string_equal(a.units, "rad/s");
    for (i = 0; i < 3; i++)
        assert_true(bits_equal(a.v[i], cs[i].speed));
    td_result_array_free(&a);
    assert_int_equal(td_result_read(r, TD_OUT_CRITICAL_WHIRL, NULL, &a, &err), TD_OK);
    assert_true(a.v[0] == 1.0 && a.v[1] == -1.0 && a.v[2] == 1.0);
    td_result_array_free(&a);
    td_result_free(&r);
    remove(path);
}

/* A sweep table: its keys, text and number columns, the columns listing and its flag. */
static void test_sweep_file(void **state)
{
    td_sweep_grid *g = NULL;
    td_sweep_row rows[3];
    td_sweep_table t = {NULL, NULL, "speed = 1.0;\n", NULL, 0, 0, "interrupted: 3 of 3 points not run"};
    td_result *r = NULL;
    td_result_array a;
    td_error err;
    char path[512], **text = NULL, **cols = NULL;
    size_t n = 0, ncols = 0, i;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, &err), TD_OK);
    assert_int_equal(td_sweep_grid_vary(g, "speed=10:30:3", &err), TD_OK);
    for (i = 0; i < 3; i++)
        td_sweep_row_unknown(&rows[i], TD_SWEEP_NOT_RUN, "not run", NULL);
    t.grid = g;
    t.rows = rows;
    tmp_name(path, sizeof path, "sweep.h5");
    assert_int_equal(td_sweep_write_hdf5(path, &t, &err), TD_OK);
    assert_int_equal(td_result_open(path, &r, &err), TD_OK);
    assert_int_equal(td_result_get_kind(r), TD_RESULT_SWEEP);
    assert_int_equal(td_result_get_flag(r), TD_RESULT_INCOMPLETE);
    assert_int_equal(td_result_read(r, TD_OUT_SWEEP_VARY, "speed", &a, &err), TD_OK);
    assert_true(a.n == 3 && a.v[0] == 10.0 && a.v[1] == 20.0 && a.v[2] == 30.0);
    td_result_array_free(&a);
    assert_int_equal(td_result_read(r, TD_OUT_SWEEP_KEY_AXIS, "speed", &a, &err), TD_OK);
    assert_true(a.n == 1 && a.v[0] == 0.0);
    td_result_array_free(&a);
    assert_int_equal(td_result_read_strings(r, TD_OUT_SWEEP_STATUS, NULL, &text, &n, &err), TD_OK);
    assert_int_equal(n, 3);
    assert_string_equal(text[2], "not run");
    td_result_strings_free(text, n);
    assert_int_equal(td_result_read(r, TD_OUT_SWEEP_PEAK_HOUSING_FORCE, NULL, &a, &err), TD_OK);
    assert_true(a.n == 3 && isnan(a.v[1]));
    assert_string_equal(a.units, "N");
    td_result_array_free(&a);
    /* the numeric columns in name order: not /point, not the text columns, not /section_radius */
    assert_int_equal(td_result_columns(r, TD_OUT_ROOT, NULL, 3, &cols, &ncols, &err), TD_OK);
    assert_int_equal(ncols, 18); /* the eighteen number columns of docs/output-format.md, "Sweep table" */
    assert_string_equal(cols[0], "contact_happened");
    for (i = 1; i < ncols; i++)
        assert_true(strcmp(cols[i - 1], cols[i]) < 0);
    td_result_strings_free(cols, ncols);
    td_result_free(&r);
    td_sweep_grid_free(&g);
    remove(path);
}

/* The ids are public numbers: a program built against 0.14.0's header keeps reading the same outputs,
 * so every id of 0.14.0 keeps its number and new ids go after them. 0.14.0's values (its header):
 * TD_OUT_AMB_NODES 69, TD_OUT_SWEEP_WARNINGS 243, TD_OUT_SWEEP_FROM 250, its last. */
static void test_ids_keep_their_numbers(void **state)
{
    (void)state;
    assert_int_equal(TD_OUT_AMB_NODES, 69);
    assert_int_equal(TD_OUT_SWEEP_WARNINGS, 243);
    assert_int_equal(TD_OUT_SWEEP_FROM, 250);
    assert_true(TD_OUT_RETAINER_DAMAGE > TD_OUT_SWEEP_FROM && TD_OUT_SWEEP_DROPS_TO_FAILURE > TD_OUT_SWEEP_FROM);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_run_file),    cmocka_unit_test(test_schema_paths),
        cmocka_unit_test(test_schema_find), cmocka_unit_test(test_completeness),
        cmocka_unit_test(test_refusals),    cmocka_unit_test(test_modal_file),
        cmocka_unit_test(test_sweep_file),  cmocka_unit_test(test_ids_keep_their_numbers),
    };
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
